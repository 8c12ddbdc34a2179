//! The stability atlas: the method on stiff and extreme cases, each ending
//! either converged or in a typed, diagnosed error.
//!
//! Axes: the penalty factor over ten decades for θ = 1, 0, −1 (Hertz and
//! Taylor), the stiffness contrast between the Taylor blocks, near
//! incompressibility, the load level, open and penetrating initial gaps,
//! and meshes from 1×1 to 256×256 with degrees 1 to 5.

use crate::assembly::strain_stress;
use crate::benchmarks::{
    Hertz, HertzAnalytic, Taylor, HERTZ_BODY_FORCE, HERTZ_RADIUS, TAYLOR_PRESSURE,
};
use crate::contact::Integration;
use crate::error::{Error, Result};
use crate::material::Material;
use crate::problem::Problem;
use crate::report::atomic::write_text;
use crate::solver::history::{Event, History};
use crate::solver::{solve, Solution, SolverOptions};
use std::path::Path;

/// What a case is measured against.
#[derive(Clone, Copy)]
enum Metric {
    /// Peak contact pressure at the Gauss points, relative to this value.
    PeakPressure(f64),
    /// Largest relative deviation of σ_yy from this uniform value.
    UniformStress(f64),
    /// The bodies must not touch: no active point.
    NoContact,
}

/// Builds one case's problem.
type Builder = Box<dyn Fn() -> Result<Problem>>;

struct Case {
    name: String,
    theta: f64,
    penalty_factor: f64,
    build: Builder,
    metric: Metric,
}

/// One row of the atlas.
#[derive(Clone, Debug)]
pub struct Row {
    pub case: String,
    pub theta: f64,
    pub penalty_factor: f64,
    pub status: String,
    pub iterations: usize,
    pub corrections: usize,
    pub skipped_updates: usize,
    /// Kernel factorisations whose low-rank solves needed refinement.
    pub kernel_refined: usize,
    /// Kernel factorisations where the low-rank path was refused for LU.
    pub kernel_lu_fallbacks: usize,
    pub error_vs_reference: Option<f64>,
    pub error_kind: String,
    pub diagnosis: String,
}

impl Row {
    fn record(&mut self, h: &History) {
        self.iterations = h.len();
        self.corrections = h.corrections();
        self.skipped_updates = h.skipped_updates();
        self.kernel_refined = h.count(|e| *e == Event::KernelRefined);
        self.kernel_lu_fallbacks = h.count(|e| *e == Event::KernelLuFallback);
    }
}

fn peak_pressure(p: &Problem, s: &Solution) -> f64 {
    p.pressures(&s.full)
        .iter()
        .map(|(_, v)| *v)
        .fold(0.0, f64::max)
}

fn max_syy_error(p: &Problem, s: &Solution, exact: f64) -> Result<f64> {
    let mut worst: f64 = 0.0;
    for (b, body) in p.bodies.iter().enumerate() {
        for el in &body.space.elements {
            for qp in body.space.quadrature(el)? {
                let (_, sig) =
                    strain_stress(&p.bodies, &p.map, &s.full, b, qp.param[0], qp.param[1])?;
                worst = worst.max(((sig[1] - exact) / exact).abs());
            }
        }
    }
    Ok(worst)
}

fn hertz_p0_for(material: Material, load_scale: f64) -> f64 {
    let e_star = material.young / (1.0 - material.poisson * material.poisson);
    let load = HERTZ_BODY_FORCE * load_scale * std::f64::consts::PI * HERTZ_RADIUS * HERTZ_RADIUS;
    let a = 2.0 * (load * HERTZ_RADIUS / (std::f64::consts::PI * e_star)).sqrt();
    2.0 * load / (std::f64::consts::PI * a)
}

fn cases(reference_8x8: f64) -> Vec<Case> {
    let mut out = Vec::new();
    let factors: Vec<f64> = (-4..=6).map(|k| 10f64.powi(k)).collect();
    for theta in [1.0, 0.0, -1.0] {
        for &f in &factors {
            out.push(Case {
                name: format!("hertz_8x8_penalty_{f:.0e}"),
                theta,
                penalty_factor: f,
                build: Box::new(move || {
                    Hertz {
                        theta,
                        penalty_factor: f,
                        ..Hertz::default()
                    }
                    .build()
                }),
                metric: Metric::PeakPressure(reference_8x8),
            });
            out.push(Case {
                name: format!("taylor_penalty_{f:.0e}"),
                theta,
                penalty_factor: f,
                build: Box::new(move || {
                    Taylor {
                        theta,
                        penalty_factor: f,
                        ..Taylor::default()
                    }
                    .build()
                }),
                metric: Metric::UniformStress(-TAYLOR_PRESSURE),
            });
        }
    }
    for k in [-6, -4, -2, 0, 2, 4, 6] {
        let c = 10f64.powi(k);
        out.push(Case {
            name: format!("taylor_contrast_{c:.0e}"),
            theta: 0.0,
            penalty_factor: 1.0,
            build: Box::new(move || {
                let upper = Material {
                    young: Taylor::material().young * c,
                    ..Taylor::material()
                };
                Taylor::default().build_with(Taylor::material(), upper, 1.0)
            }),
            metric: Metric::UniformStress(-TAYLOR_PRESSURE),
        });
    }
    for nu in [0.3, 0.45, 0.49, 0.499, 0.4999] {
        let m = Material {
            poisson: nu,
            ..Hertz::material()
        };
        out.push(Case {
            name: format!("hertz_16x16_nu_{nu}"),
            theta: 0.0,
            penalty_factor: 1.0,
            build: Box::new(move || {
                Hertz {
                    elements: 16,
                    ..Hertz::default()
                }
                .build_with(m, 1.0)
            }),
            metric: Metric::PeakPressure(hertz_p0_for(m, 1.0)),
        });
    }
    for k in [-8, -6, -4, -2, 0, 1, 2, 3] {
        let s = 10f64.powi(k);
        out.push(Case {
            name: format!("hertz_16x16_load_{s:.0e}"),
            theta: 0.0,
            penalty_factor: 1.0,
            build: Box::new(move || {
                Hertz {
                    elements: 16,
                    ..Hertz::default()
                }
                .build_with(Hertz::material(), s)
            }),
            metric: Metric::PeakPressure(hertz_p0_for(Hertz::material(), s)),
        });
    }
    let t = Taylor::material();
    let gap_cases: Vec<(&str, Builder, Metric)> = vec![
        (
            "taylor_open_gap_unloaded",
            Box::new(move || Taylor::default().build_with_gap(t, t, 0.0, 1e-2)),
            Metric::NoContact,
        ),
        (
            "taylor_gap_closed_by_load",
            Box::new(move || Taylor::default().build_with_gap(t, t, 1.0, 1e-3)),
            Metric::UniformStress(-TAYLOR_PRESSURE),
        ),
        (
            "taylor_initial_penetration",
            Box::new(move || Taylor::default().build_with_gap(t, t, 1.0, -1e-3)),
            Metric::UniformStress(-TAYLOR_PRESSURE),
        ),
        (
            "hertz_lifted_and_pulled_up",
            Box::new(|| Hertz::default().build_lifted(Hertz::material(), -1.0, 1e-2)),
            Metric::NoContact,
        ),
        (
            "hertz_lifted_then_falls",
            Box::new(|| Hertz::default().build_lifted(Hertz::material(), 1.0, 1e-4)),
            Metric::PeakPressure(reference_8x8),
        ),
        (
            "hertz_initial_penetration",
            Box::new(|| Hertz::default().build_lifted(Hertz::material(), 1.0, -1e-4)),
            Metric::PeakPressure(reference_8x8),
        ),
    ];
    for (name, build, metric) in gap_cases {
        out.push(Case {
            name: name.into(),
            theta: 0.0,
            penalty_factor: 1.0,
            build,
            metric,
        });
    }
    let analytic = HertzAnalytic::new().p0;
    for degree in 1..=5 {
        for n in [1, 4, 16] {
            let lagrange = (degree == 1).then_some(1);
            out.push(Case {
                name: format!("hertz_p{degree}_{n}x{n}"),
                theta: 0.0,
                penalty_factor: 1.0,
                build: Box::new(move || {
                    Hertz {
                        degree: degree.max(2),
                        elements: n,
                        lagrange,
                        ..Hertz::default()
                    }
                    .build()
                }),
                metric: Metric::PeakPressure(analytic),
            });
        }
    }
    for n in [128, 256] {
        out.push(Case {
            name: format!("hertz_p2_{n}x{n}"),
            theta: 0.0,
            penalty_factor: 1.0,
            build: Box::new(move || {
                Hertz {
                    elements: n,
                    ..Hertz::default()
                }
                .build()
            }),
            metric: Metric::PeakPressure(analytic),
        });
    }
    out.push(Case {
        name: "taylor_segment_vs_gauss_gauss".into(),
        theta: 0.0,
        penalty_factor: 1.0,
        build: Box::new(|| {
            Taylor {
                integration: Integration::Gauss,
                ..Taylor::default()
            }
            .build()
        }),
        metric: Metric::UniformStress(-TAYLOR_PRESSURE),
    });
    out
}

fn run_case(case: &Case) -> Row {
    let mut row = Row {
        case: case.name.clone(),
        theta: case.theta,
        penalty_factor: case.penalty_factor,
        status: "failed".into(),
        iterations: 0,
        corrections: 0,
        skipped_updates: 0,
        kernel_refined: 0,
        kernel_lu_fallbacks: 0,
        error_vs_reference: None,
        error_kind: String::new(),
        diagnosis: String::new(),
    };
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(
        || -> Result<(Problem, Solution)> {
            let p = (case.build)()?;
            let s = solve(&p, &SolverOptions::default())?;
            Ok((p, s))
        },
    ));
    match outcome {
        Err(_) => {
            row.error_kind = "panic".into();
            row.diagnosis = "the solver panicked (a defect)".into();
        }
        Ok(Err(e)) => {
            if let Error::NotConverged { history, .. } = &e {
                row.record(history);
            }
            row.error_kind = e.kind().into();
            row.diagnosis = e.to_string();
        }
        Ok(Ok((p, s))) => {
            row.record(&s.history);
            let active = p.active_points(&s.u);
            let err = match case.metric {
                Metric::PeakPressure(reference) => {
                    Ok(Some((peak_pressure(&p, &s) - reference).abs() / reference))
                }
                Metric::UniformStress(exact) => max_syy_error(&p, &s, exact).map(Some),
                Metric::NoContact => Ok(None),
            };
            match err {
                _ if s.full.iter().any(|v| !v.is_finite()) => {
                    row.error_kind = "nan".into();
                    row.diagnosis = "non-finite displacement".into();
                }
                Err(e) => {
                    row.error_kind = e.kind().into();
                    row.diagnosis = e.to_string();
                }
                Ok(e) => {
                    row.error_vs_reference = e;
                    row.status = if active == 0 {
                        "no_contact".into()
                    } else {
                        "converged".into()
                    };
                    if matches!(case.metric, Metric::NoContact) && active > 0 {
                        row.status = "failed".into();
                        row.error_kind = "unexpected_contact".into();
                    }
                }
            }
        }
    }
    row
}

fn csv_field(s: &str) -> String {
    format!("\"{}\"", s.replace('"', "'"))
}

fn fmt_err(e: Option<f64>) -> String {
    e.map_or(String::new(), |v| format!("{v:.3e}"))
}

/// Runs every case; `progress` is told each case as it finishes.
pub fn atlas(progress: impl FnMut(usize, usize, &Row)) -> Result<Vec<Row>> {
    atlas_where(|_| true, progress)
}

/// Runs the cases whose name passes `keep`.
pub fn atlas_where(
    keep: impl Fn(&str) -> bool,
    mut progress: impl FnMut(usize, usize, &Row),
) -> Result<Vec<Row>> {
    let reference = {
        let p = Hertz::default().build()?;
        let s = solve(&p, &SolverOptions::default())?;
        peak_pressure(&p, &s)
    };
    let all: Vec<Case> = cases(reference)
        .into_iter()
        .filter(|c| keep(&c.name))
        .collect();
    let mut rows = Vec::with_capacity(all.len());
    for (k, case) in all.iter().enumerate() {
        let row = run_case(case);
        progress(k + 1, all.len(), &row);
        rows.push(row);
    }
    Ok(rows)
}

/// For each θ, the penalty factors (Hertz 8×8) that converge within 5 % of
/// the reference.
pub fn penalty_ranges(rows: &[Row]) -> Vec<(f64, Vec<f64>)> {
    [1.0, 0.0, -1.0]
        .iter()
        .map(|&theta| {
            let ok = rows
                .iter()
                .filter(|r| r.case.starts_with("hertz_8x8_penalty") && r.theta == theta)
                .filter(|r| {
                    r.status == "converged" && r.error_vs_reference.is_some_and(|e| e <= 0.05)
                })
                .map(|r| r.penalty_factor)
                .collect();
            (theta, ok)
        })
        .collect()
}

/// The cases whose kernels needed refinement or fell back to LU
/// (see [`crate::solver::kernel::factor_kernel`]), with totals.
fn kernel_paths_md(rows: &[Row]) -> String {
    let mut md =
        String::from("| case | θ | refined factorisations | LU fallbacks |\n|---|---|---|---|\n");
    for r in rows
        .iter()
        .filter(|r| r.kernel_refined + r.kernel_lu_fallbacks > 0)
    {
        md.push_str(&format!(
            "| {} | {} | {} | {} |\n",
            r.case, r.theta, r.kernel_refined, r.kernel_lu_fallbacks
        ));
    }
    let sum = |f: fn(&Row) -> usize| rows.iter().map(f).sum::<usize>();
    md.push_str(&format!(
        "| all {} cases | | {} | {} |\n",
        rows.len(),
        sum(|r| r.kernel_refined),
        sum(|r| r.kernel_lu_fallbacks)
    ));
    md
}

/// Writes `atlas.csv`, `atlas.md`, `penalty_ranges.md` and
/// `kernel_paths.md` into `out`.
pub fn run(out: &Path) -> Result<()> {
    let rows = atlas(|k, n, r| {
        eprintln!(
            "  [{k}/{n}] {} θ={} → {} {}",
            r.case, r.theta, r.status, r.error_kind
        )
    })?;
    let mut csv = String::from("case,theta,penalty_factor,status,iterations,corrections,skipped_updates,error_vs_reference,error_kind,diagnosis\n");
    let mut md = String::from("| case | θ | penalty factor | status | iterations | corrections | skipped | error vs reference | error kind |\n|---|---|---|---|---|---|---|---|---|\n");
    for r in &rows {
        csv.push_str(&format!(
            "{},{},{:e},{},{},{},{},{},{},{}\n",
            r.case,
            r.theta,
            r.penalty_factor,
            r.status,
            r.iterations,
            r.corrections,
            r.skipped_updates,
            fmt_err(r.error_vs_reference),
            r.error_kind,
            csv_field(&r.diagnosis)
        ));
        md.push_str(&format!(
            "| {} | {} | {:.0e} | {} | {} | {} | {} | {} | {} |\n",
            r.case,
            r.theta,
            r.penalty_factor,
            r.status,
            r.iterations,
            r.corrections,
            r.skipped_updates,
            fmt_err(r.error_vs_reference),
            r.error_kind
        ));
    }
    let mut ranges = String::from(
        "| θ | converged within 5 % of the reference for penalty factors |\n|---|---|\n",
    );
    for (theta, ok) in penalty_ranges(&rows) {
        let list = if ok.is_empty() {
            "none".to_string()
        } else {
            format!(
                "{:.0e} … {:.0e} ({} of 11 values)",
                ok.iter().cloned().fold(f64::INFINITY, f64::min),
                ok.iter().cloned().fold(0.0, f64::max),
                ok.len()
            )
        };
        ranges.push_str(&format!("| {theta} | {list} |\n"));
    }
    write_text(out.join("atlas.csv"), &csv)?;
    write_text(out.join("atlas.md"), &md)?;
    write_text(out.join("penalty_ranges.md"), &ranges)?;
    write_text(out.join("kernel_paths.md"), &kernel_paths_md(&rows))?;
    Ok(())
}
