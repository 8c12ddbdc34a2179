//! Accuracy per second: IGA p = 2, 3, 4 and FEM Q1, Q2 over a mesh ladder,
//! errors against a converged fine-mesh reference (IGA p = 3, 128×128)
//! and against Hertz, plotted against wall time (assembly + solve).
//!
//! BFGS (the paper's solver) is tried first; where it does not converge the
//! failure is recorded in the `solver` column and the run is repeated with
//! Newton, so the accuracy of the discretisation can still be measured.

use super::iga_vs_fem::{
    bfgs_or_newton, peak_and_half_width, percent, profile, relative_l2, strain_energy, timed_run,
    Method, Run,
};
use crate::benchmarks::HertzAnalytic;
use crate::error::Result;
use crate::report::atomic::write_text;
use crate::report::plot::{line_chart, Axes, Series};
use crate::solver::SolverKind;
use std::path::Path;

/// Elements per direction of the ladder.
pub const LADDER: [usize; 5] = [4, 8, 16, 32, 64];
/// The reference discretisation.
pub const REFERENCE: (Method, usize) = (Method::Iga(3), 128);
/// Accuracy targets (relative, not percent).
pub const TARGETS: [f64; 3] = [0.05, 0.01, 0.001];

/// Every discretisation of the study.
pub fn methods() -> [Method; 5] {
    [
        Method::Iga(2),
        Method::Iga(3),
        Method::Iga(4),
        Method::Fem(1),
        Method::Fem(2),
    ]
}

/// The converged reference: profile, p₀, half-width, strain energy.
pub struct Reference {
    pub samples: Vec<super::iga_vs_fem::Sample>,
    pub p0: f64,
    pub half_width: f64,
    pub energy: f64,
}

impl Reference {
    /// Solves `method` on `elements`² with Newton (fastest to converge).
    pub fn compute(method: Method, elements: usize) -> Result<Self> {
        let run = timed_run(method, elements, SolverKind::Newton, 1)?;
        Self::from_run(&run)
    }

    pub fn from_run(run: &Run) -> Result<Self> {
        let (samples, _) = profile(&run.problem, &run.solution.full)?;
        let (p0, half_width) = peak_and_half_width(&samples);
        Ok(Self {
            energy: strain_energy(&run.problem, &run.solution.u),
            samples,
            p0,
            half_width,
        })
    }
}

/// One rung of the ladder.
pub struct Point {
    pub method: Method,
    pub elements: usize,
    pub dofs: usize,
    /// `bfgs`, or `newton (bfgs failed: …)`.
    pub solver: String,
    pub iterations: usize,
    pub seconds: f64,
    pub p0_error: f64,
    pub half_width_error: f64,
    pub pressure_l2_error: f64,
    pub energy_error: f64,
    pub p0_error_hertz: f64,
    pub half_width_error_hertz: f64,
}

/// Measures one discretisation against `reference`.
pub fn measure(method: Method, elements: usize, reference: &Reference) -> Result<Point> {
    let exact = HertzAnalytic::new();
    // Repeat cheap runs so that their median time means something.
    let repeats = if elements <= 16 { 5 } else { 1 };
    let (run, solver) = bfgs_or_newton(method, elements, repeats)?;
    let (samples, _) = profile(&run.problem, &run.solution.full)?;
    let (p0, a) = peak_and_half_width(&samples);
    let energy = strain_energy(&run.problem, &run.solution.u);
    Ok(Point {
        method,
        elements,
        dofs: run.dofs,
        solver,
        iterations: run.solution.history.len(),
        seconds: run.seconds,
        p0_error: (p0 - reference.p0).abs() / reference.p0,
        half_width_error: (a - reference.half_width).abs() / reference.half_width,
        pressure_l2_error: relative_l2(&samples, &reference.samples, 1.2 * reference.half_width),
        energy_error: ((energy - reference.energy).abs() / reference.energy).sqrt(),
        p0_error_hertz: percent(p0, exact.p0) / 100.0,
        half_width_error_hertz: percent(a, exact.half_width) / 100.0,
    })
}

/// The first (cheapest) run of `method` from which on every finer run meets
/// `target` in the quantity `err`: (seconds, elements).
pub fn first_reaching(
    points: &[Point],
    method: Method,
    target: f64,
    err: impl Fn(&Point) -> f64,
) -> Option<(f64, usize)> {
    let mine: Vec<&Point> = points.iter().filter(|p| p.method == method).collect();
    (0..mine.len())
        .find(|&i| mine[i..].iter().all(|p| err(p) <= target))
        .map(|i| (mine[i].seconds, mine[i].elements))
}

fn accuracy_table(points: &[Point]) -> String {
    type Quantity = (&'static str, fn(&Point) -> f64);
    let quantities: [Quantity; 2] = [
        ("p₀", |p| p.p0_error),
        ("pressure L2", |p| p.pressure_l2_error),
    ];
    let mut md = String::from(
        "Seconds (assembly + solve) of the cheapest mesh from which on every finer mesh of the ladder \
         meets the target; errors against the reference; — = not reached on the ladder.\n\n| quantity | target |",
    );
    for m in methods() {
        md.push_str(&format!(" {} |", m.label()));
    }
    md.push_str(" first |\n|---|---|");
    for _ in methods() {
        md.push_str("---|");
    }
    md.push_str("---|\n");
    for (name, err) in quantities {
        for t in TARGETS {
            md.push_str(&format!("| {name} | {}% |", 100.0 * t));
            let mut best: Option<(f64, Method)> = None;
            for m in methods() {
                match first_reaching(points, m, t, err) {
                    Some((s, n)) => {
                        md.push_str(&format!(" {s:.3} s ({n}²) |"));
                        if best.is_none_or(|(b, _)| s < b) {
                            best = Some((s, m));
                        }
                    }
                    None => md.push_str(" — |"),
                }
            }
            match best {
                Some((_, m)) => md.push_str(&format!(" {} |\n", m.label())),
                None => md.push_str(" none |\n"),
            }
        }
    }
    md
}

fn plot(
    out: &Path,
    file: &str,
    what: &str,
    points: &[Point],
    err: fn(&Point) -> f64,
) -> Result<()> {
    let series: Vec<Series> = methods()
        .iter()
        .map(|&m| {
            Series::line(
                m.label(),
                points
                    .iter()
                    .filter(|p| p.method == m && err(p) > 0.0)
                    .map(|p| (p.seconds, err(p)))
                    .collect(),
            )
            .with_markers()
        })
        .collect();
    line_chart(
        out.join(file),
        &Axes {
            title: format!("{what} error against wall time"),
            x_label: "assembly + solve (s)".into(),
            y_label: format!("relative {what} error"),
            log_x: true,
            log_y: true,
        },
        &series,
    )
}

/// Writes `runs.{csv,md}`, `reference.md`, `accuracy_per_second.md` and the
/// three error-against-time plots.
pub fn run(out: &Path) -> Result<()> {
    let (rm, rn) = REFERENCE;
    let reference = Reference::compute(rm, rn)?;
    let exact = HertzAnalytic::new();
    write_text(
        out.join("reference.md"),
        &format!(
            "| | p₀ (Pa) | a (m) | strain energy (J/m) |\n|---|---|---|---|\n\
             | reference: {} {rn}×{rn} | {:.5e} | {:.6} | {:.6e} |\n\
             | Hertz | {:.5e} | {:.6} | |\n\
             | reference against Hertz | {:.2}% | {:.2}% | |\n",
            rm.label(),
            reference.p0,
            reference.half_width,
            reference.energy,
            exact.p0,
            exact.half_width,
            percent(reference.p0, exact.p0),
            percent(reference.half_width, exact.half_width),
        ),
    )?;

    let mut points = Vec::new();
    for m in methods() {
        for n in LADDER {
            points.push(measure(m, n, &reference)?);
        }
    }

    let mut csv = String::from(
        "method,degree,elements,dofs,seconds,p0_error,half_width_error,pressure_l2_error,energy_error,p0_error_hertz,half_width_error_hertz,iterations,solver\n",
    );
    let mut md = String::from(
        "Relative errors against the reference (IGA p=3, 128×128) and against Hertz. \
         Energy error: √(|E(u_h) − E(u_ref)| / E(u_ref)) with E = ½uᵀKu.\n\n\
         | method | elements | dofs | iterations | p₀ | a | pressure L2 | energy | p₀ vs Hertz | a vs Hertz | solver |\n\
         |---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for p in &points {
        csv.push_str(&format!(
            "{},{},{},{},{:.6},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{},\"{}\"\n",
            p.method.kind(),
            p.method.degree(),
            p.elements,
            p.dofs,
            p.seconds,
            p.p0_error,
            p.half_width_error,
            p.pressure_l2_error,
            p.energy_error,
            p.p0_error_hertz,
            p.half_width_error_hertz,
            p.iterations,
            p.solver.replace('"', "'"),
        ));
        md.push_str(&format!(
            "| {} | {}² | {} | {} | {:.2e} | {:.2e} | {:.2e} | {:.2e} | {:.2e} | {:.2e} | {} |\n",
            p.method.label(),
            p.elements,
            p.dofs,
            p.iterations,
            p.p0_error,
            p.half_width_error,
            p.pressure_l2_error,
            p.energy_error,
            p.p0_error_hertz,
            p.half_width_error_hertz,
            p.solver,
        ));
    }
    write_text(out.join("runs.csv"), &csv)?;
    write_text(out.join("runs.md"), &md)?;
    write_text(out.join("accuracy_per_second.md"), &accuracy_table(&points))?;
    plot(out, "p0_vs_time.svg", "p₀", &points, |p| p.p0_error)?;
    plot(out, "half_width_vs_time.svg", "half-width", &points, |p| {
        p.half_width_error
    })?;
    plot(
        out,
        "pressure_l2_vs_time.svg",
        "pressure L2",
        &points,
        |p| p.pressure_l2_error,
    )?;
    Ok(())
}
