//! The Taylor contact patch test (the paper's section 5.1, Table 1 and
//! Figs. 1–3).
//!
//! Two stacked plane-stress blocks on non-matching meshes are pressed
//! together by a uniform pressure. The exact solution is a homogeneous
//! stress state, σ_yy = −p everywhere, with the linear displacement
//! u = (ν p x / E, −p y / E), which every NURBS space here represents
//! exactly. A contact discretisation *passes* the patch test when the
//! discrete solution is that field up to round-off.
//!
//! [`run`] solves the test twice with the default BFGS solver, once with
//! segment integration of the contact integral and once with plain Gauss
//! points per slave element, measures the error at every bulk Gauss point of
//! both bodies, and writes the chapter's tables and figures.

use crate::assembly::{displacement_at, strain_at};
use crate::benchmarks::{Taylor, TAYLOR_PRESSURE};
use crate::contact::Integration;
use crate::dofs::DofMap;
use crate::error::{Error, Result};
use crate::nurbs::Side;
use crate::problem::Problem;
use crate::report::atomic::write_text;
use crate::report::plot::{
    field_figure, geometry_figure, FieldCell, LineKind, Polyline, BLACK_INDEX,
};
use crate::report::vtu::sample_bodies;
use crate::solver::history::History;
use crate::solver::{solve, Solution, SolverOptions};
use std::fmt;
use std::path::Path;

/// Index of the lower (master) block in the problem [`Taylor::build`] returns.
pub const LOWER: usize = 0;
/// Index of the upper (slave, loaded) block.
pub const UPPER: usize = 1;
/// Height of the top face, where the pressure acts.
pub const TOP: f64 = 1.0;
/// Abscissa of the right faces.
pub const RIGHT: f64 = 1.0;
/// Width of the loaded face: the applied load is `TAYLOR_PRESSURE * WIDTH`.
pub const WIDTH: f64 = 1.0;

/// Iterations the paper reports for its (BFGS) solve of the test.
pub const PAPER_ITERATIONS: usize = 6;
/// Largest relative σ_yy error the paper reports (0.13 %).
pub const PAPER_MAX_REL_ERROR_SYY: f64 = 0.0013;

/// Table 1 of the paper as far as it survived, as printed: (iteration,
/// residual norm, update norm, max displacement in m). Row 5 was lost, and
/// the paper does not say how its norms were scaled.
pub const PAPER_TABLE_1: [(usize, &str, &str, &str); 5] = [
    (1, "0.0676575", "0.560272", "-0.100001"),
    (2, "0.0370776", "1.72072e-05", "-0.100001"),
    (3, "0.025447", "7.99243e-05", "-0.0999878"),
    (4, "0.0300309", "7.24258e-05", "-0.1"),
    (6, "0.00438419", "2.72107e-05", "-0.1"),
];

/// Subcells per element direction of the sampled figures.
const FIGURE_SUBDIVISIONS: usize = 8;
/// Points per boundary element where u_y(top) and u_x(x = 1) are sampled
/// (besides the control points of those sides).
pub const SIDE_SAMPLES: usize = 9;
/// Lower clamp of the plotted log10 error: round-off is ~1e-16.
const ERROR_FLOOR: f64 = 1e-16;

/// The exact displacement of the patch test at `x`, for the default
/// materials and load: u = (ν p x / E, −p y / E).
pub fn exact_displacement(x: [f64; 2]) -> [f64; 2] {
    let m = Taylor::material();
    let strain_y = -TAYLOR_PRESSURE / m.young;
    let strain_x = -m.poisson * strain_y;
    [strain_x * x[0], strain_y * x[1]]
}

/// The errors of a discrete solution against the exact patch-test state.
///
/// Stress errors are relative to the pressure p = 1e8 Pa and taken at every
/// bulk Gauss point of both bodies (the points the stiffness is integrated
/// with). Displacement checks sample the loaded top face and the right faces
/// at their control points and at [`SIDE_SAMPLES`] points per element.
#[derive(Clone, Debug, PartialEq)]
pub struct PatchErrors {
    /// Number of bulk Gauss points examined (both bodies).
    pub gauss_points: usize,
    /// max |σ_yy + p| / p over the Gauss points.
    pub max_rel_error_syy: f64,
    /// max |σ_xx| / p.
    pub max_rel_error_sxx: f64,
    /// max |σ_xy| / p.
    pub max_rel_error_sxy: f64,
    /// max ‖u − u_exact‖ at the Gauss points (m).
    pub max_displacement_error: f64,
    /// The sampled u_y on the top face farthest from −0.1 (m).
    pub uy_top: f64,
    /// max |u_y(top) + 0.1| (m).
    pub uy_top_deviation: f64,
    /// The sampled u_x on the right faces (both bodies) farthest from 0.03 (m).
    pub ux_right: f64,
    /// max |u_x(x = 1) − 0.03| (m).
    pub ux_right_deviation: f64,
    /// Resultant force the lower block exerts on the upper one (N per unit
    /// thickness).
    pub contact_force: [f64; 2],
    /// ‖contact force − (0, p·width)‖ / (p·width).
    pub contact_force_rel_error: f64,
}

/// Compares the full displacement vector `full` of a Taylor problem (as
/// [`Taylor::build`] lays it out) with the exact solution.
pub fn patch_errors(problem: &Problem, full: &[f64]) -> Result<PatchErrors> {
    check_layout(problem, full)?;
    let p = TAYLOR_PRESSURE;
    let map = &problem.map;
    let mut out = PatchErrors {
        gauss_points: 0,
        max_rel_error_syy: 0.0,
        max_rel_error_sxx: 0.0,
        max_rel_error_sxy: 0.0,
        max_displacement_error: 0.0,
        uy_top: 0.0,
        uy_top_deviation: 0.0,
        ux_right: 0.0,
        ux_right_deviation: 0.0,
        contact_force: [0.0; 2],
        contact_force_rel_error: 0.0,
    };
    for (bi, body) in problem.bodies.iter().enumerate() {
        for e in &body.space.elements {
            for qp in body.space.quadrature(e)? {
                let s = body
                    .material
                    .stress(strain_at(map, full, bi, &e.cps, &qp.shape));
                let u = displacement_at(map, full, bi, &e.cps, &qp.shape);
                let ue = exact_displacement(qp.shape.x);
                out.gauss_points += 1;
                out.max_rel_error_syy = nan_max(out.max_rel_error_syy, (s[1] + p).abs() / p);
                out.max_rel_error_sxx = nan_max(out.max_rel_error_sxx, s[0].abs() / p);
                out.max_rel_error_sxy = nan_max(out.max_rel_error_sxy, s[2].abs() / p);
                out.max_displacement_error = nan_max(
                    out.max_displacement_error,
                    (u[0] - ue[0]).hypot(u[1] - ue[1]),
                );
            }
        }
    }

    let uy_exact = exact_displacement([0.0, TOP])[1];
    let top = side_displacements(problem, full, UPPER, Side::EtaMax)?;
    (out.uy_top, out.uy_top_deviation) = worst(top.iter().map(|u| u[1]), uy_exact);
    let ux_exact = exact_displacement([RIGHT, 0.0])[0];
    let mut right = side_displacements(problem, full, LOWER, Side::XiMax)?;
    right.extend(side_displacements(problem, full, UPPER, Side::XiMax)?);
    (out.ux_right, out.ux_right_deviation) = worst(right.iter().map(|u| u[0]), ux_exact);

    let f = problem.contact_force(full);
    let load = p * WIDTH;
    out.contact_force = f;
    out.contact_force_rel_error = f[0].hypot(f[1] - load) / load;
    Ok(out)
}

fn check_layout(problem: &Problem, full: &[f64]) -> Result<()> {
    let names: Vec<&str> = problem.bodies.iter().map(|b| b.name.as_str()).collect();
    if names != ["lower", "upper"] {
        return Err(Error::invalid(
            "taylor.bodies",
            names.join(", "),
            "expected the two blocks `lower, upper` of benchmarks::Taylor",
        ));
    }
    if full.len() != problem.map.n_total() {
        return Err(Error::invalid(
            "taylor.displacement",
            format!("{} values", full.len()),
            format!("the DOF map has {} DOFs", problem.map.n_total()),
        ));
    }
    Ok(())
}

/// The value farthest from `exact` and its distance; a NaN value wins (and
/// stays), so that a broken solution cannot look exact.
fn worst(values: impl Iterator<Item = f64>, exact: f64) -> (f64, f64) {
    let (mut value, mut dev) = (exact, 0.0_f64);
    for v in values {
        let d = (v - exact).abs();
        if dev.is_nan() {
            break;
        }
        if d.is_nan() || d > dev {
            (value, dev) = (v, d);
        }
    }
    (value, dev)
}

/// NaN-propagating maximum: a NaN error must not hide behind `f64::max`.
fn nan_max(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

/// Displacements on `side` of body `body`: at the side's control points
/// (for these affine blocks, control-point values are nodal values of the
/// linear exact field), then at sampled points of every boundary element.
fn side_displacements(
    problem: &Problem,
    full: &[f64],
    body: usize,
    side: Side,
) -> Result<Vec<[f64; 2]>> {
    let map = &problem.map;
    let space = &problem.bodies[body].space;
    let mut out: Vec<[f64; 2]> = space
        .patch
        .side_indices(side)
        .into_iter()
        .map(|cp| map.cp_displacement(full, body, cp))
        .collect();
    for be in space.boundary(side) {
        let e = &space.elements[be.element];
        for k in 0..SIDE_SAMPLES {
            let t =
                be.range[0] + (be.range[1] - be.range[0]) * k as f64 / (SIDE_SAMPLES - 1) as f64;
            let (shape, _, _) = space.side_shape(&be, t)?;
            out.push(displacement_at(map, full, body, &e.cps, &shape));
        }
    }
    Ok(out)
}

/// A solved Taylor problem with its errors.
pub struct CaseRun {
    pub problem: Problem,
    pub solution: Solution,
    pub errors: PatchErrors,
}

/// Builds `setup`, solves it with `opts` and measures the errors.
pub fn solve_case(setup: &Taylor, opts: &SolverOptions) -> Result<CaseRun> {
    let problem = setup.build()?;
    let solution = solve(&problem, opts)?;
    let errors = patch_errors(&problem, &solution.full)?;
    Ok(CaseRun {
        problem,
        solution,
        errors,
    })
}

/// One integration rule's outcome.
#[derive(Clone, Debug, PartialEq)]
pub struct CaseSummary {
    pub integration: Integration,
    /// BFGS iterations to convergence.
    pub iterations: usize,
    /// Contact quadrature points on the slave side.
    pub contact_points: usize,
    pub errors: PatchErrors,
    pub history: History,
}

/// What [`run`] measured.
#[derive(Clone, Debug, PartialEq)]
pub struct TaylorSummary {
    pub segment: CaseSummary,
    pub gauss: CaseSummary,
}

impl TaylorSummary {
    pub fn cases(&self) -> [&CaseSummary; 2] {
        [&self.segment, &self.gauss]
    }
}

/// `segment` or `gauss`, as in the file names and the CSV.
pub fn integration_name(i: Integration) -> &'static str {
    match i {
        Integration::Segment => "segment",
        Integration::Gauss => "gauss",
    }
}

/// Solves the default Taylor problem with segment and with Gauss
/// integration and writes into `out`:
///
/// - `summary.csv`, `summary.md`: iterations and errors of both rules
///   beside the paper's;
/// - `iterations_segment.csv`, `iterations_gauss.csv`, `iterations.md`:
///   the iteration histories (Table 1);
/// - `mesh.svg` (Fig. 1), `displacement.svg` (Fig. 2),
///   `error_syy_segment.svg`, `error_syy_gauss.svg` (Fig. 3);
/// - `taylor.vtu`: the segment-integration solution, sampled.
///
/// No file holds a time or a timing, so two runs write identical bytes.
pub fn run(out: &Path) -> Result<TaylorSummary> {
    let opts = SolverOptions::default();
    let segment = solve_case(
        &Taylor {
            integration: Integration::Segment,
            ..Taylor::default()
        },
        &opts,
    )?;
    let gauss = solve_case(
        &Taylor {
            integration: Integration::Gauss,
            ..Taylor::default()
        },
        &opts,
    )?;
    let summarise = |integration, c: &CaseRun| CaseSummary {
        integration,
        iterations: c.solution.history.len(),
        contact_points: c.problem.points.len(),
        errors: c.errors.clone(),
        history: c.solution.history.clone(),
    };
    let summary = TaylorSummary {
        segment: summarise(Integration::Segment, &segment),
        gauss: summarise(Integration::Gauss, &gauss),
    };

    write_text(out.join("summary.csv"), &summary_csv(&summary))?;
    write_text(out.join("summary.md"), &summary_md(&summary))?;
    for c in summary.cases() {
        write_text(
            out.join(format!(
                "iterations_{}.csv",
                integration_name(c.integration)
            )),
            &c.history.to_csv(),
        )?;
    }
    write_text(out.join("iterations.md"), &iterations_md(&summary))?;

    mesh_figure(&segment.problem, &out.join("mesh.svg"))?;
    displacement_figure(&segment, &out.join("displacement.svg"))?;
    for (c, name) in [(&segment, "segment"), (&gauss, "gauss")] {
        error_figure(c, name, &out.join(format!("error_syy_{name}.svg")))?;
    }
    sample_bodies(
        &segment.problem.bodies,
        &segment.problem.map,
        &segment.solution.full,
        4,
    )?
    .write(out.join("taylor.vtu"))?;
    Ok(summary)
}

/// Exactly `integration,iterations,max_rel_error_syy,uy_top`; `uy_top` is
/// the sampled top displacement farthest from −0.1 (see [`PatchErrors`]).
pub fn summary_csv(s: &TaylorSummary) -> String {
    let mut t = String::from("integration,iterations,max_rel_error_syy,uy_top\n");
    for c in s.cases() {
        t.push_str(&format!(
            "{},{},{:.3e},{:.12e}\n",
            integration_name(c.integration),
            c.iterations,
            c.errors.max_rel_error_syy,
            c.errors.uy_top
        ));
    }
    t
}

/// The chapter's results table: exact value, the paper's and both rules'.
pub fn summary_md(s: &TaylorSummary) -> String {
    let (g, sg) = (&s.gauss, &s.segment);
    let e = |f: fn(&PatchErrors) -> f64| (sci(f(&sg.errors)), sci(f(&g.errors)));
    let v = |f: fn(&PatchErrors) -> f64| (fixed(f(&sg.errors)), fixed(f(&g.errors)));
    let mut rows: Vec<[String; 5]> = vec![
        [
            "BFGS iterations".into(),
            "–".into(),
            PAPER_ITERATIONS.to_string(),
            sg.iterations.to_string(),
            g.iterations.to_string(),
        ],
        [
            "contact quadrature points".into(),
            "–".into(),
            "not stated".into(),
            sg.contact_points.to_string(),
            g.contact_points.to_string(),
        ],
        [
            "bulk Gauss points checked".into(),
            "–".into(),
            "–".into(),
            sg.errors.gauss_points.to_string(),
            g.errors.gauss_points.to_string(),
        ],
    ];
    let mut push = |name: &str, exact: &str, paper: &str, (a, b): (String, String)| {
        rows.push([name.into(), exact.into(), paper.into(), a, b]);
    };
    push(
        "max \\|σ_yy + p\\| / p",
        "0",
        "1.3e-3 (0.13 %)",
        e(|x| x.max_rel_error_syy),
    );
    push("max \\|σ_xx\\| / p", "0", "–", e(|x| x.max_rel_error_sxx));
    push("max \\|σ_xy\\| / p", "0", "–", e(|x| x.max_rel_error_sxy));
    push(
        "max ‖u − u_exact‖ at Gauss points (m)",
        "0",
        "–",
        e(|x| x.max_displacement_error),
    );
    push(
        "u_y on top, worst sample (m)",
        "−0.1",
        "−0.1",
        v(|x| x.uy_top),
    );
    push(
        "max \\|u_y(top) + 0.1\\| (m)",
        "0",
        "–",
        e(|x| x.uy_top_deviation),
    );
    push(
        "u_x at x = 1, worst sample (m)",
        "0.03",
        "–",
        v(|x| x.ux_right),
    );
    push(
        "max \\|u_x(x = 1) − 0.03\\| (m)",
        "0",
        "–",
        e(|x| x.ux_right_deviation),
    );
    push(
        "contact force (N/m)",
        "1e8",
        "–",
        (
            sci6(sg.errors.contact_force[1]),
            sci6(g.errors.contact_force[1]),
        ),
    );
    push(
        "\\|force − load\\| / load",
        "0",
        "–",
        e(|x| x.contact_force_rel_error),
    );
    let mut t = String::from(
        "| quantity | exact | paper | segment integration | Gauss integration |\n\
         |---|---|---|---|---|\n",
    );
    for r in rows {
        t.push_str(&format!("| {} |\n", r.join(" | ")));
    }
    t
}

/// Table 1: the paper's surviving rows beside both histories.
pub fn iterations_md(s: &TaylorSummary) -> String {
    let n = s
        .cases()
        .iter()
        .map(|c| c.history.len())
        .chain([PAPER_ITERATIONS])
        .max()
        .unwrap_or(0);
    let mut t = String::from(
        "| it. | paper ‖R‖ | paper ‖Δu‖ | paper max u | segment ‖R‖/‖R₀‖ | segment ‖Δu‖ | segment max u | Gauss ‖R‖/‖R₀‖ | Gauss ‖Δu‖ | Gauss max u |\n\
         |---|---|---|---|---|---|---|---|---|---|\n",
    );
    for k in 1..=n {
        let paper = match PAPER_TABLE_1.iter().find(|r| r.0 == k) {
            Some(&(_, r, du, m)) => [minus(r), minus(du), minus(m)],
            None if k <= PAPER_ITERATIONS => ["lost".into(), "lost".into(), "lost".into()],
            None => ["".into(), "".into(), "".into()],
        };
        let ours = |c: &CaseSummary| match c.history.rows.get(k - 1) {
            Some(r) => [
                sci(r.relative_residual),
                sci(r.update),
                fixed(r.max_displacement),
            ],
            None => ["".into(), "".into(), "".into()],
        };
        let cells: Vec<String> = std::iter::once(k.to_string())
            .chain(paper)
            .chain(ours(&s.segment))
            .chain(ours(&s.gauss))
            .collect();
        t.push_str(&format!("| {} |\n", cells.join(" | ")));
    }
    t.push_str(&format!(
        "\n‖R₀‖ = {} N (segment) and {} N (Gauss): the residual of the start u = 0. \
         Full histories, with absolute norms, active contact points and solver events, \
         are in `iterations_segment.csv` and `iterations_gauss.csv`.\n",
        sci(s.segment.history.initial_residual),
        sci(s.gauss.history.initial_residual)
    ));
    t
}

/// Three significant digits, scientific, with a typographic minus.
fn sci(x: f64) -> String {
    minus(&format!("{x:.2e}"))
}

fn sci6(x: f64) -> String {
    minus(&format!("{x:.6e}"))
}

/// Ten decimals (displacements of order 0.1 m).
fn fixed(x: f64) -> String {
    minus(&format!("{x:.10}"))
}

fn minus(s: &str) -> String {
    s.replace('-', "−")
}

// ---------------------------------------------------------------- figures

/// Element boundaries (knot lines) of every body, in the colour of the body.
fn element_lines(problem: &Problem, style: LineKind, mono: bool) -> Vec<Polyline> {
    let mut lines = Vec::new();
    for (bi, body) in problem.bodies.iter().enumerate() {
        let patch = &body.space.patch;
        let color = if mono { BLACK_INDEX } else { bi };
        for dir in 0..2 {
            for b in patch.knots[dir].breaks() {
                let mut l = Polyline::new(patch.iso_curve(dir, b, 16), style, color);
                if !mono {
                    l = l.labelled(format!("{}: elements", body.name));
                }
                lines.push(l);
            }
        }
    }
    lines
}

/// Fig. 1: knot lines and control nets of both blocks.
fn mesh_figure(problem: &Problem, path: &Path) -> Result<()> {
    let mut lines = element_lines(problem, LineKind::Solid, false);
    for (bi, body) in problem.bodies.iter().enumerate() {
        let patch = &body.space.patch;
        let [n0, n1] = patch.n();
        let label = format!("{}: control net", body.name);
        for j in 0..n1 {
            let pts = (0..n0).map(|i| patch.points[patch.index(i, j)]).collect();
            lines.push(Polyline::new(pts, LineKind::ControlNet, bi + 2).labelled(label.clone()));
        }
        for i in 0..n0 {
            let pts = (0..n1).map(|j| patch.points[patch.index(i, j)]).collect();
            lines.push(Polyline::new(pts, LineKind::ControlNet, bi + 2).labelled(label.clone()));
        }
    }
    geometry_figure(
        path,
        "Taylor patch test: 4×2 and 3×2 elements, p = 2",
        &lines,
    )
}

/// A scalar sampled on `FIGURE_SUBDIVISIONS`² cells per element of every
/// body: `value(body, x, u, σ)` at each cell centre. With `deformed` the
/// cell corners are moved by the displacement.
fn sampled_cells(
    problem: &Problem,
    full: &[f64],
    deformed: bool,
    value: impl Fn(usize, [f64; 2], [f64; 2], [f64; 3]) -> f64,
) -> Result<Vec<FieldCell>> {
    let n = FIGURE_SUBDIVISIONS;
    let map: &DofMap = &problem.map;
    let mut cells = Vec::new();
    for (bi, body) in problem.bodies.iter().enumerate() {
        let space = &body.space;
        for e in &space.elements {
            let [[xa, xb], [ya, yb]] = e.range;
            let at = |s: f64, t: f64| -> Result<([f64; 2], [f64; 2], [f64; 3])> {
                let (xi, eta) = (xa + (xb - xa) * s, ya + (yb - ya) * t);
                let shape = space.shape(e, xi, eta)?;
                let u = displacement_at(map, full, bi, &e.cps, &shape);
                let sigma = body
                    .material
                    .stress(strain_at(map, full, bi, &e.cps, &shape));
                Ok((shape.x, u, sigma))
            };
            let corner = |s: f64, t: f64| -> Result<[f64; 2]> {
                let (x, u, _) = at(s, t)?;
                Ok(if deformed {
                    [x[0] + u[0], x[1] + u[1]]
                } else {
                    x
                })
            };
            for j in 0..n {
                for i in 0..n {
                    let (s0, s1) = (i as f64 / n as f64, (i + 1) as f64 / n as f64);
                    let (t0, t1) = (j as f64 / n as f64, (j + 1) as f64 / n as f64);
                    let (x, u, sigma) = at(0.5 * (s0 + s1), 0.5 * (t0 + t1))?;
                    cells.push(FieldCell {
                        corners: [
                            corner(s0, t0)?,
                            corner(s1, t0)?,
                            corner(s1, t1)?,
                            corner(s0, t1)?,
                        ],
                        value: value(bi, x, u, sigma),
                    });
                }
            }
        }
    }
    Ok(cells)
}

/// Fig. 2: u_y on the deformed blocks (true scale), with the undeformed
/// outlines dashed.
fn displacement_figure(c: &CaseRun, path: &Path) -> Result<()> {
    let cells = sampled_cells(&c.problem, &c.solution.full, true, |_, _, u, _| u[1])?;
    let mut overlay = Vec::new();
    for body in &c.problem.bodies {
        let p = &body.space.patch;
        overlay.push(
            Polyline::new(p.outline(16), LineKind::Dashed, BLACK_INDEX).labelled("undeformed"),
        );
    }
    field_figure(
        path,
        "u_y on the deformed blocks (true scale)",
        "u_y (m)",
        &cells,
        &overlay,
    )
}

/// Fig. 3: log10 of the relative σ_yy error, clamped below at 1e-16.
fn error_figure(c: &CaseRun, name: &str, path: &Path) -> Result<()> {
    let rule = if name == "gauss" { "Gauss" } else { name };
    let p = TAYLOR_PRESSURE;
    let cells = sampled_cells(&c.problem, &c.solution.full, false, |_, _, _, s| {
        ((s[1] + p).abs() / p).max(ERROR_FLOOR).log10()
    })?;
    let overlay = element_lines(&c.problem, LineKind::Thin, true);
    field_figure(
        path,
        &format!("Relative σ_yy error, {rule} integration"),
        "log10 |σ_yy + p| / p",
        &cells,
        &overlay,
    )
}

impl fmt::Display for TaylorSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "Taylor contact patch test (paper: {PAPER_ITERATIONS} iterations, max σ_yy error 0.13 %)"
        )?;
        for c in self.cases() {
            let e = &c.errors;
            writeln!(
                f,
                "  {:<8} {:>3} iterations, {:>3} contact points: max |σ_yy+p|/p = {:.3e}, \
                 |σ_xx|/p = {:.3e}, |σ_xy|/p = {:.3e}, u_y(top) = {:.12} (dev {:.3e}), \
                 u_x(x=1) = {:.12} (dev {:.3e}), force error {:.3e}",
                integration_name(c.integration),
                c.iterations,
                c.contact_points,
                e.max_rel_error_syy,
                e.max_rel_error_sxx,
                e.max_rel_error_sxy,
                e.uy_top,
                e.uy_top_deviation,
                e.ux_right,
                e.ux_right_deviation,
                e.contact_force_rel_error
            )?;
        }
        Ok(())
    }
}
