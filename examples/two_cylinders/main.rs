//! Two elastic cylinders: the program behind the chapter "Two elastic
//! cylinders". The line contact of two elastic cylinders, a limiting case of
//! Hertz's curved bodies, beside the paper's disk on a rigid plane: two
//! disks of different radii and moduli pressed together,
//! solved on a mesh ladder with two solvers and measured against the plane
//! Hertz solution for two bodies and against a converged fine-mesh
//! reference. Output: `book/src/generated/two_cylinders/`.
//!
//! Run it with `cargo run --release --example two_cylinders`.

use companion::chapter::Chapter;
use companion::{Facts, Solver};
use iga_contact::assembly::Load;
use iga_contact::error::{Error, Result};
use iga_contact::post::hertz::{Cylinder, Hertz};
use iga_contact::post::{self, relative, PressureProfile};
use iga_contact::problem::Problem;
use iga_contact::report::drawing::{field_cells, Placement};
use iga_contact::report::plot::{
    field_figure, line_chart, Axes, LineKind, Polyline, Series, BLACK_INDEX,
};
use iga_contact::report::table::{Column, Format, Table, Unit, CONTACT_ERRORS};
use iga_contact::scene::{GeometrySpec, RefineSpec, Scene};
use iga_contact::solver::{solve, Solution};
use std::f64::consts::PI;

// ANCHOR: setup
/// Elements per direction of the upper disk; the lower one has twice as
/// many, so that elements along the contact are of similar size.
const LADDER: [usize; 5] = [4, 8, 16, 32, 64];
/// The reference: p = 3 on the finest rung.
const REFERENCE: (usize, usize) = (3, 64);

/// The scene with degree `p` and `n`² (upper) and (2n)² (lower) elements.
fn scene(p: usize, n: usize) -> Result<Scene> {
    let mut s = companion::shipped("two_cylinders.toml")?
        .refined("upper", RefineSpec::iga(p, [n, n]))?
        .refined("lower", RefineSpec::iga(p, [2 * n, 2 * n]))?;
    s.output = Default::default();
    Ok(s)
}

/// Hertz's solution for the scene's two disks under the upper disk's
/// weight: 1/R = 1/R₁ + 1/R₂, 1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂.
fn analytic(scene: &Scene) -> Result<Hertz> {
    let cylinder = |k: usize| match scene.bodies[k].geometry {
        GeometrySpec::HalfDisk { radius, .. } => Ok(Cylinder::Elastic {
            radius,
            material: scene.bodies[k].material,
        }),
        ref g => Err(Error::invalid(
            format!("body[{k}].geometry"),
            g.kind(),
            "not a half disk",
        )),
    };
    let (upper, lower) = (cylinder(0)?, cylinder(1)?);
    let Cylinder::Elastic { radius, .. } = upper else {
        unreachable!()
    };
    let density = scene
        .loads
        .iter()
        .find_map(|l| match l {
            Load::BodyForce { force, .. } => Some(force[0].hypot(force[1])),
            _ => None,
        })
        .ok_or_else(|| Error::invalid("load", "none", "the upper disk is loaded by its weight"))?;
    Ok(Hertz::new(upper, lower, density * PI * radius * radius))
}
// ANCHOR_END: setup

/// One solve, measured on the dense profile of the upper disk's arc.
struct Run {
    degree: usize,
    elements: usize,
    solver: Solver,
    problem: Problem,
    solution: Solution,
    p0: f64,
    half_width: f64,
    zones: usize,
}

fn run(p: usize, n: usize, solver: Solver) -> Result<Run> {
    let problem = scene(p, n)?.build()?;
    let solution = solve(&problem, &solver.options())?;
    let m = PressureProfile::dense(&problem, &solution.full)?.measures(0);
    Ok(Run {
        degree: p,
        elements: n,
        solver,
        p0: m.p0,
        half_width: m.half_width,
        zones: m.zones,
        problem,
        solution,
    })
}

/// The chapter "Two elastic cylinders", section by section.
fn main() -> Result<()> {
    let mut chapter = Chapter::from_args("two_cylinders")?;

    // The model: Hertz's solution for the pair (its facts below).
    let exact = analytic(&scene(2, 8)?)?;

    // The mesh ladder: Table C1, Figs. C3 and C2.
    let ladder = solve_ladder()?;
    chapter.table("ladder", &ladder_table(&ladder, &exact)?)?;
    draw_errors(&chapter, &ladder)?;
    draw_pressure(&chapter, &ladder, &exact)?;

    // Fig. C1 of "The model", drawn on the ladder's 8² rung.
    draw_deformed(&chapter, &ladder)?;

    // The facts of "The model" and of "The mesh ladder".
    record_model_facts(chapter.facts(), &exact)?;
    record_ladder_facts(chapter.facts(), &ladder, &exact)?;
    chapter.finish()
}

// ANCHOR: ladder
/// The solves of "The mesh ladder": p = 2 on every rung with both solvers,
/// the reference, and the reference's check.
struct Ladder {
    /// p = 2, rung by rung, BFGS then Newton.
    runs: Vec<Run>,
    reference: Run,
    /// The reference's degree on half its elements.
    coarse_reference: Run,
}

/// The mesh ladder, with both solvers, and the reference.
fn solve_ladder() -> Result<Ladder> {
    let mut runs = Vec::new();
    for n in LADDER {
        for solver in [Solver::Bfgs, Solver::Newton] {
            runs.push(run(2, n, solver)?);
        }
    }
    let reference = run(REFERENCE.0, REFERENCE.1, Solver::Newton)?;
    // The reference's own error, estimated by its distance from the same
    // degree on half the elements (an upper estimate for a converging pair).
    let coarse_reference = run(REFERENCE.0, REFERENCE.1 / 2, Solver::Newton)?;
    Ok(Ladder {
        runs,
        reference,
        coarse_reference,
    })
}
// ANCHOR_END: ladder

impl Ladder {
    /// The p = 2 rungs solved by BFGS, coarsest first.
    fn bfgs(&self) -> Vec<&Run> {
        self.runs
            .iter()
            .filter(|r| r.solver == Solver::Bfgs)
            .collect()
    }
}

// ANCHOR: table
/// Table C1: every rung and the reference, against Hertz and (CSV only)
/// against the reference.
fn ladder_table(ladder: &Ladder, exact: &Hertz) -> Result<Table> {
    let reference = &ladder.reference;
    let [p0_hertz, a_hertz, p0_reference, a_reference] = CONTACT_ERRORS;
    let mut table = Table::new(vec![
        // The degree tells the p = 3 reference row from the p = 2 rungs;
        // Markdown only, so that the CSV keeps its columns.
        Column::plain("degree", "p").markdown_only(),
        Column::new("elements", "mesh (upper)", Unit::None, Format::Mesh),
        Column::plain("dofs", "DOFs"),
        Column::plain("solver", "solver"),
        Column::plain("iterations", "its"),
        Column::new("p0", "p₀", Unit::Megapascal, Format::Fixed(4)),
        Column::new("half_width", "a", Unit::Millimetre, Format::Fixed(2)),
        p0_hertz,
        a_hertz,
        p0_reference.csv_only(),
        a_reference.csv_only(),
        Column::plain("zones", "zones").csv_only(),
    ]);
    for r in ladder.runs.iter().chain(std::iter::once(reference)) {
        table.push(vec![
            r.degree.into(),
            r.elements.into(),
            r.problem.n().into(),
            r.solver.key().into(),
            r.solution.history.len().into(),
            r.p0.into(),
            r.half_width.into(),
            relative(r.p0, exact.p0).into(),
            relative(r.half_width, exact.half_width).into(),
            relative(r.p0, reference.p0).into(),
            relative(r.half_width, reference.half_width).into(),
            r.zones.into(),
        ])?;
    }
    Ok(table)
}
// ANCHOR_END: table

/// Fig. C3: the errors against the reference, p = 2 and BFGS, against the
/// mesh.
fn draw_errors(chapter: &Chapter, ladder: &Ladder) -> Result<()> {
    let reference = &ladder.reference;
    let bfgs = ladder.bfgs();
    let error = |f: fn(&Run) -> f64, reference: f64| -> Vec<(f64, f64)> {
        bfgs.iter()
            .map(|r| (r.elements as f64, relative(f(r), reference).abs()))
            .collect()
    };
    line_chart(
        chapter.path("errors.svg"),
        &Axes {
            title: "Two cylinders, p = 2: error against the reference".into(),
            x_label: "elements per direction (upper disk)".into(),
            y_label: "relative error".into(),
            log_x: true,
            log_y: true,
        },
        &[
            Series::line("p₀", error(|r| r.p0, reference.p0)).with_markers(),
            Series::line("a", error(|r| r.half_width, reference.half_width))
                .with_markers()
                .dashed(),
        ],
    )
}

/// Fig. C2: the pressure of the finest p = 2 rung against Hertz's ellipse.
fn draw_pressure(chapter: &Chapter, ladder: &Ladder, exact: &Hertz) -> Result<()> {
    let bfgs = ladder.bfgs();
    let fine = bfgs.last().expect("a ladder");
    let profile = PressureProfile::dense(&fine.problem, &fine.solution.full)?;
    let x_max = 1.5 * exact.half_width;
    let pts = profile
        .pair(0)
        .iter()
        .filter(|s| s.x[0] <= x_max)
        .map(|s| (s.x[0] * 1e3, s.pressure() * 1e-6))
        .collect();
    let ellipse = (0..=300)
        .map(|i| {
            let x = x_max * i as f64 / 300.0;
            (x * 1e3, exact.pressure(x) * 1e-6)
        })
        .collect();
    line_chart(
        chapter.path("pressure_profile.svg"),
        &Axes {
            title: format!(
                "Contact pressure, p = 2, {0}² on {1}²",
                fine.elements,
                2 * fine.elements
            ),
            x_label: "x (mm)".into(),
            y_label: "pressure (MPa)".into(),
            log_x: false,
            log_y: false,
        },
        &[
            Series::line("IGA", pts),
            Series::line("Hertz, two cylinders", ellipse).dashed(),
        ],
    )
}

/// Fig. C1: the deformed pair, coloured by u_y (true scale), on the 8²
/// rung.
fn draw_deformed(chapter: &Chapter, ladder: &Ladder) -> Result<()> {
    let bfgs = ladder.bfgs();
    let coarse = bfgs.iter().find(|r| r.elements == 8).expect("an 8² rung");
    let cells = field_cells(
        &coarse.problem,
        &coarse.solution.full,
        4,
        Placement::Deformed,
        |q| q.displacement[1] * 1e3,
    )?;
    let outlines: Vec<Polyline> = coarse
        .problem
        .bodies
        .iter()
        .map(|b| {
            Polyline::new(b.space.patch.outline(64), LineKind::Dashed, BLACK_INDEX)
                .labelled("undeformed")
        })
        .collect();
    field_figure(
        chapter.path("deformed.svg"),
        "Two cylinders: u_y on the deformed bodies (true scale), p = 2",
        "u_y (mm)",
        &cells,
        &outlines,
    )
}

// ANCHOR: facts
/// "The model" quotes Hertz's solution and the radius and modulus it uses.
fn record_model_facts(f: &mut Facts, exact: &Hertz) -> Result<()> {
    f.number("hertz_p0_mpa", exact.p0 * 1e-6, Format::Fixed(4))?;
    f.number("hertz_a_mm", exact.half_width * 1e3, Format::Fixed(3))?;
    f.number("radius_mm", exact.radius * 1e3, Format::Fixed(1))?;
    f.number("modulus_mpa", exact.modulus * 1e-6, Format::Fixed(2))
}

/// "The mesh ladder" quotes the errors of the reference and of the finest
/// rung, the force balance, the load's quadrature error, the reference's
/// own error, how far the two solvers part and the number of zones.
fn record_ladder_facts(f: &mut Facts, ladder: &Ladder, exact: &Hertz) -> Result<()> {
    let (runs, reference) = (&ladder.runs, &ladder.reference);
    let hertz = [exact.p0, exact.half_width];
    let reference_pa = [reference.p0, reference.half_width];
    f.contact_errors(
        "reference",
        reference_pa,
        "hertz",
        hertz,
        Format::SignedPercent(1),
    )?;
    f.count("reference_dofs", reference.problem.n())?;
    let bfgs = ladder.bfgs();
    let finest = bfgs.last().expect("a ladder");
    let finest_pa = [finest.p0, finest.half_width];
    f.contact_errors(
        "finest",
        finest_pa,
        "reference",
        reference_pa,
        Format::SignedPercent(2),
    )?;
    f.contact_errors(
        "finest",
        finest_pa,
        "hertz",
        hertz,
        Format::SignedPercent(2),
    )?;
    f.number("force_balance", force_balance(runs), Format::Pow10(0))?;
    f.number(
        "load_quadrature",
        load_quadrature(runs, exact),
        Format::Pow10(0),
    )?;
    let coarse_reference = &ladder.coarse_reference;
    f.contact_errors(
        "reference_check",
        [coarse_reference.p0, coarse_reference.half_width],
        "reference",
        reference_pa,
        Format::SignedPercent(2),
    )?;
    f.number("solver_spread", solver_spread(runs), Format::Pow10(0))?;
    f.count("max_zones", runs.iter().map(|r| r.zones).max().unwrap_or(0))
}

/// The largest relative imbalance of the vertical contact resultant and
/// the assembled load over the rungs.
fn force_balance(runs: &[Run]) -> f64 {
    runs.iter()
        .map(|r| {
            let [fx, fy] = post::contact_resultant(&r.problem, &r.solution.full);
            let [lx, ly] = post::applied_resultant(&r.problem).unwrap_or([f64::NAN; 2]);
            // the horizontal force of the curved interface goes into the symmetry support
            let _ = (fx, lx);
            ((fy + ly) / ly).abs()
        })
        .fold(0.0, f64::max)
}

/// The assembled load is the weight of the half disk up to the quadrature
/// error of the disk's area: the largest over the rungs.
fn load_quadrature(runs: &[Run], exact: &Hertz) -> f64 {
    runs.iter()
        .map(|r| {
            let [_, ly] = post::applied_resultant(&r.problem).unwrap_or([f64::NAN; 2]);
            relative(-ly, exact.load / 2.0).abs()
        })
        .fold(0.0, f64::max)
}

/// The largest relative difference in p₀ or a between BFGS and Newton on
/// the same rung.
fn solver_spread(runs: &[Run]) -> f64 {
    LADDER
        .iter()
        .map(|&n| {
            let pair: Vec<&Run> = runs.iter().filter(|r| r.elements == n).collect();
            relative(pair[0].p0, pair[1].p0)
                .abs()
                .max(relative(pair[0].half_width, pair[1].half_width).abs())
        })
        .fold(0.0, f64::max)
}
// ANCHOR_END: facts
