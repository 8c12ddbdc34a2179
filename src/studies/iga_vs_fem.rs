//! IGA against FEM on the paper's coarse Hertz mesh (8×8): the exact NURBS
//! half disk with p = 2 against isoparametric Lagrange Q1 and Q2 meshes of
//! the same element count (nodes on the exact circle), same Nitsche contact,
//! same BFGS solver.
//!
//! This module also holds the measuring helpers shared by the
//! `error_vs_time` and `solvers` studies: a dense pressure profile, its peak
//! and half-width, the relative L2 distance of two profiles, and a timed
//! solve.

use crate::benchmarks::{Hertz, HertzAnalytic};
use crate::contact::{contact_points, ContactPair, Integration};
use crate::error::Result;
use crate::linsolve::mul;
use crate::problem::Problem;
use crate::report::atomic::write_text;
use crate::report::plot::{line_chart, Axes, Series};
use crate::solver::{solve, Solution, SolverKind, SolverOptions};
use std::path::Path;
use std::time::Instant;

/// Gauss points per contact element used to sample the pressure profile.
pub const PROFILE_GAUSS_POINTS: usize = 20;

/// A discretisation of the Hertz disk.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Exact NURBS half disk, k-refined to this degree.
    Iga(usize),
    /// Isoparametric Lagrange mesh of this degree (Q1, Q2).
    Fem(usize),
}

impl Method {
    /// `iga` or `fem`.
    pub fn kind(&self) -> &'static str {
        match self {
            Method::Iga(_) => "iga",
            Method::Fem(_) => "fem",
        }
    }

    pub fn degree(&self) -> usize {
        match *self {
            Method::Iga(p) | Method::Fem(p) => p,
        }
    }

    /// `IGA p=2`, `FEM Q1`, ...
    pub fn label(&self) -> String {
        match self {
            Method::Iga(p) => format!("IGA p={p}"),
            Method::Fem(p) => format!("FEM Q{p}"),
        }
    }

    /// The Hertz set-up with `elements` × `elements` elements.
    pub fn hertz(&self, elements: usize) -> Hertz {
        match *self {
            Method::Iga(p) => Hertz {
                degree: p,
                elements,
                ..Hertz::default()
            },
            Method::Fem(p) => Hertz {
                degree: p,
                elements,
                lagrange: Some(p),
                ..Hertz::default()
            },
        }
    }
}

/// One pressure sample: (x, pressure, quadrature weight).
pub type Sample = (f64, f64, f64);

/// Contact pressure −\[P\]₋ sampled at `gauss` Gauss points per contact
/// element: `(x, pressure, quadrature weight)`, sorted by x.
pub fn pressure_samples(problem: &Problem, full: &[f64], gauss: usize) -> Result<Vec<Sample>> {
    let pairs: Vec<ContactPair> = problem
        .pairs
        .iter()
        .map(|p| ContactPair {
            integration: Integration::Gauss,
            gauss_points: Some(gauss),
            ..p.clone()
        })
        .collect();
    let points = contact_points(&problem.bodies, &problem.map, &pairs)?;
    let mut out: Vec<Sample> = points
        .iter()
        .map(|cp| (cp.x[0], -cp.p(full).min(0.0), cp.weight))
        .collect();
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    Ok(out)
}

/// [`pressure_samples`] at [`PROFILE_GAUSS_POINTS`] points per element, or,
/// where a contact element's map is not invertible at some of those points
/// (the Lagrange Q2 interpolant folds slightly at the far corner of the
/// contact side, away from the contact zone), at the largest of 16, 12, 10,
/// 8, 6, 4 that works. Returns the samples and the count used.
pub fn profile(problem: &Problem, full: &[f64]) -> Result<(Vec<Sample>, usize)> {
    let mut last = None;
    for g in [PROFILE_GAUSS_POINTS, 16, 12, 10, 8, 6, 4] {
        match pressure_samples(problem, full, g) {
            Ok(s) => return Ok((s, g)),
            Err(e) => last = Some(e),
        }
    }
    Err(last.expect("tried at least once"))
}

/// Peak pressure and contact half-width of a sorted profile. The
/// half-width extrapolates p² linearly in x² (exact for Hertz's ellipse)
/// from the last two loaded samples, clamped between the last loaded and
/// the first unloaded sample.
pub fn peak_and_half_width(samples: &[Sample]) -> (f64, f64) {
    let p0 = samples.iter().map(|s| s.1).fold(0.0, f64::max);
    let tol = 1e-9 * p0;
    let Some(last) = samples.iter().rposition(|s| s.1 > tol) else {
        return (0.0, 0.0);
    };
    let x1 = samples[last].0;
    let x2 = samples.get(last + 1).map_or(x1, |s| s.0);
    let mut a = x1;
    if last > 0 {
        let (xa, pa) = (samples[last - 1].0, samples[last - 1].1);
        let (xb, pb) = (x1, samples[last].1);
        let (qa, qb) = (pa * pa, pb * pb);
        if qa > qb && xb > xa {
            // q(s) = qa + (qb − qa)(s − xa²)/(xb² − xa²) = 0
            let s = xa * xa + qa * (xb * xb - xa * xa) / (qa - qb);
            if s.is_finite() && s > 0.0 {
                a = s.sqrt();
            }
        }
    }
    (p0, a.clamp(x1, x2.max(x1)))
}

/// Linear interpolation of a sorted profile at x (constant beyond its ends).
pub fn interpolate(samples: &[Sample], x: f64) -> f64 {
    let i = samples.partition_point(|s| s.0 < x);
    if i == 0 {
        return samples.first().map_or(0.0, |s| s.1);
    }
    if i == samples.len() {
        return samples.last().map_or(0.0, |s| s.1);
    }
    let (x0, p0, _) = samples[i - 1];
    let (x1, p1, _) = samples[i];
    if x1 > x0 {
        p0 + (p1 - p0) * (x - x0) / (x1 - x0)
    } else {
        p1
    }
}

/// Relative L2 distance of `samples` to `reference` over x ∈ [0, x_max],
/// with the samples' own quadrature weights:
/// √(Σ w (p − p_ref)²) / √(Σ w p_ref²).
pub fn relative_l2(samples: &[Sample], reference: &[Sample], x_max: f64) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for &(x, p, w) in samples.iter().filter(|s| s.0 <= x_max) {
        let r = interpolate(reference, x);
        num += w * (p - r) * (p - r);
        den += w * r * r;
    }
    (num / den).sqrt()
}

/// Strain energy ½ uᵀKu over the free DOFs.
pub fn strain_energy(problem: &Problem, u: &[f64]) -> f64 {
    0.5 * mul(&problem.k, u)
        .iter()
        .zip(u)
        .map(|(a, b)| a * b)
        .sum::<f64>()
}

/// One measured run: assembly + solve, timed together.
pub struct Run {
    pub method: Method,
    pub elements: usize,
    pub dofs: usize,
    /// Which solver produced the solution.
    pub solver: SolverKind,
    pub solution: Solution,
    pub problem: Problem,
    /// Median wall time of (Problem::new + solve) over `repeats` runs.
    pub seconds: f64,
    pub repeats: usize,
}

/// Builds and solves `method` on an `elements`² mesh `repeats` times and
/// keeps the median time (assembly + solve). Errors (e.g. non-convergence)
/// are returned as such.
pub fn timed_run(method: Method, elements: usize, kind: SolverKind, repeats: usize) -> Result<Run> {
    let opts = SolverOptions::with_kind(kind);
    let mut times = Vec::new();
    let mut last = None;
    for _ in 0..repeats.max(1) {
        let t = Instant::now();
        let problem = method.hertz(elements).build()?;
        let solution = solve(&problem, &opts)?;
        times.push(t.elapsed().as_secs_f64());
        last = Some((problem, solution));
    }
    times.sort_by(f64::total_cmp);
    let (problem, solution) = last.expect("at least one repeat");
    Ok(Run {
        method,
        elements,
        dofs: problem.n(),
        solver: kind,
        solution,
        problem,
        seconds: times[times.len() / 2],
        repeats: times.len(),
    })
}

/// [`timed_run`] with BFGS; if BFGS does not converge, the failure is kept
/// in the returned label (`bfgs`, or `newton (bfgs failed: …)`) and the run
/// is repeated with Newton so the discretisation can still be measured.
pub fn bfgs_or_newton(method: Method, elements: usize, repeats: usize) -> Result<(Run, String)> {
    match timed_run(method, elements, SolverKind::Bfgs, repeats) {
        Ok(r) => Ok((r, "bfgs".to_string())),
        Err(e @ crate::error::Error::NotConverged { .. }) => Ok((
            timed_run(method, elements, SolverKind::Newton, repeats)?,
            format!("newton (bfgs failed: {e})"),
        )),
        Err(e) => Err(e),
    }
}

/// Relative error in percent.
pub fn percent(value: f64, exact: f64) -> f64 {
    100.0 * (value - exact).abs() / exact.abs()
}

/// The paper's 8×8 single-thread figures.
pub const PAPER_IGA_SECONDS: f64 = 323.0;
pub const PAPER_FEM_SECONDS: f64 = 213.0;
pub const PAPER_IGA_ERROR: f64 = 9.91;
pub const PAPER_FEM_ERROR: f64 = 28.7;

/// The mesh of the comparison (the paper's).
pub const ELEMENTS: usize = 8;
/// Timing repeats per method (median kept).
pub const REPEATS: usize = 11;

/// The three discretisations compared.
pub fn methods() -> [Method; 3] {
    [Method::Iga(2), Method::Fem(1), Method::Fem(2)]
}

/// One row of the comparison table.
pub struct Row {
    pub method: Method,
    pub dofs: usize,
    pub iterations: usize,
    pub corrections: usize,
    pub p0: f64,
    pub p0_error: f64,
    pub half_width: f64,
    pub half_width_error: f64,
    pub seconds: f64,
    pub samples: Vec<Sample>,
    /// `bfgs`, or `newton (bfgs failed: …)`.
    pub solver: String,
    /// Gauss points per contact element of the sampled profile.
    pub gauss: usize,
}

/// Runs the three discretisations on the 8×8 mesh.
pub fn compare(repeats: usize) -> Result<Vec<Row>> {
    let exact = HertzAnalytic::new();
    let mut rows = Vec::new();
    for m in methods() {
        let (run, solver) = bfgs_or_newton(m, ELEMENTS, repeats)?;
        let (samples, gauss) = profile(&run.problem, &run.solution.full)?;
        let (p0, a) = peak_and_half_width(&samples);
        rows.push(Row {
            method: m,
            dofs: run.dofs,
            iterations: run.solution.history.len(),
            corrections: run.solution.history.corrections(),
            p0,
            p0_error: percent(p0, exact.p0),
            half_width: a,
            half_width_error: percent(a, exact.half_width),
            seconds: run.seconds,
            samples,
            solver,
            gauss,
        });
    }
    Ok(rows)
}

/// Writes `comparison.{csv,md}`, `timings.{csv,md}` and
/// `pressure_profiles.svg`.
pub fn run(out: &Path) -> Result<()> {
    let exact = HertzAnalytic::new();
    let rows = compare(REPEATS)?;

    let mut csv = String::from(
        "method,degree,elements,dofs,iterations,corrections,samples_per_element,p0,p0_error_pct,half_width,half_width_error_pct,solver\n",
    );
    let mut md = format!(
        "Hertz {ELEMENTS}×{ELEMENTS}, BFGS; errors against Hertz (p₀ = {:.4e} Pa, a = {:.5} m); \
         pressure sampled at the Gauss points (column \"samples\" per contact element) of a dense contact quadrature.\n\n\
         | method | dofs | iterations | corrections | samples | p₀ (Pa) | p₀ error (%) | a (m) | a error (%) | solver |\n\
         |---|---|---|---|---|---|---|---|---|---|\n",
        exact.p0, exact.half_width
    );
    for r in &rows {
        csv.push_str(&format!(
            "{},{},{},{},{},{},{},{:.6e},{:.4},{:.6e},{:.4},\"{}\"\n",
            r.method.kind(),
            r.method.degree(),
            ELEMENTS,
            r.dofs,
            r.iterations,
            r.corrections,
            r.gauss,
            r.p0,
            r.p0_error,
            r.half_width,
            r.half_width_error,
            r.solver.replace('"', "'")
        ));
        md.push_str(&format!(
            "| {} | {} | {} | {} | {} | {:.4e} | {:.2} | {:.5} | {:.2} | {} |\n",
            r.method.label(),
            r.dofs,
            r.iterations,
            r.corrections,
            r.gauss,
            r.p0,
            r.p0_error,
            r.half_width,
            r.half_width_error,
            r.solver
        ));
    }
    md.push_str(&format!(
        "| paper: IGA p=2 | | | 1 (at iteration 13) | | | {PAPER_IGA_ERROR} | | | BFGS |\n\
         | paper: FEM | | | | | | {PAPER_FEM_ERROR} | | | BFGS |\n"
    ));
    write_text(out.join("comparison.csv"), &csv)?;
    write_text(out.join("comparison.md"), &md)?;

    let iga = rows[0].seconds;
    let mut tcsv = String::from("method,degree,seconds,repeats,ratio_iga_over_method,solver\n");
    let mut tmd = format!(
        "Median of {REPEATS} runs of assembly + BFGS solve, single process, measured in one run.\n\n\
         | method | seconds | IGA / method | solver |\n|---|---|---|---|\n"
    );
    for r in &rows {
        tcsv.push_str(&format!(
            "{},{},{:.6},{},{:.4},{}\n",
            r.method.kind(),
            r.method.degree(),
            r.seconds,
            REPEATS,
            iga / r.seconds,
            if r.solver == "bfgs" { "bfgs" } else { "newton" }
        ));
        tmd.push_str(&format!(
            "| {} | {:.4} | {:.2} | {} |\n",
            r.method.label(),
            r.seconds,
            iga / r.seconds,
            if r.solver == "bfgs" {
                "BFGS"
            } else {
                "Newton (BFGS failed)"
            }
        ));
    }
    tmd.push_str(&format!(
        "| paper: IGA | {PAPER_IGA_SECONDS} | 1.00 | BFGS |\n| paper: FEM | {PAPER_FEM_SECONDS} | {:.2} | BFGS |\n",
        PAPER_IGA_SECONDS / PAPER_FEM_SECONDS
    ));
    write_text(out.join("timings.csv"), &tcsv)?;
    write_text(out.join("timings.md"), &tmd)?;

    let x_max = 1.5 * exact.half_width;
    let mut series: Vec<Series> = rows
        .iter()
        .map(|r| {
            Series::line(
                r.method.label(),
                r.samples
                    .iter()
                    .filter(|s| s.0 <= x_max)
                    .map(|s| (s.0, s.1))
                    .collect(),
            )
        })
        .collect();
    let hertz: Vec<(f64, f64)> = (0..=300)
        .map(|k| {
            let x = x_max * k as f64 / 300.0;
            (x, exact.pressure(x))
        })
        .collect();
    series.push(Series::line("Hertz", hertz).dashed());
    line_chart(
        out.join("pressure_profiles.svg"),
        &Axes {
            title: format!("Contact pressure, Hertz {ELEMENTS}×{ELEMENTS}"),
            x_label: "x (m)".into(),
            y_label: "pressure (Pa)".into(),
            log_x: false,
            log_y: false,
        },
        &series,
    )?;
    Ok(())
}
