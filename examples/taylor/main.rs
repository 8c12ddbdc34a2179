//! The Taylor contact patch test: the program behind the chapter "The
//! Taylor contact patch test" (the paper's Table 1 and Figs. 1–3).
//!
//! Two stacked plane-stress blocks on non-matching meshes are pressed
//! together by a uniform pressure. The exact solution is a homogeneous
//! stress state that every NURBS space here represents exactly, so a
//! contact discretisation passes the test when it reproduces that state up
//! to round-off. The program solves the scene `data/scenes/taylor.toml`
//! with both contact integration rules, measures the errors and writes
//! `book/src/generated/taylor/`.
//!
//! Run it with `cargo run --release --example taylor`.

use companion::chapter::Chapter;
use companion::taylor::{
    blocks_problem, consistency, lower_elements, patch_errors, Exact, LowerBlock, PatchErrors,
    SIDE_SAMPLES,
};
use companion::Facts;
use iga_contact::contact::{Integration, Master};
use iga_contact::error::Result;
use iga_contact::problem::Problem;
use iga_contact::report::drawing::{
    control_net, element_lines, field_cells, labelled, FieldPoint, Placement,
};
use iga_contact::report::history::history_table;
use iga_contact::report::plot::{field_figure, geometry_figure, LineKind, Polyline, BLACK_INDEX};
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};
use iga_contact::report::vtu::sample_bodies;
use iga_contact::solver::{solve, Solution};

// ANCHOR: paper
/// What the paper reports for its solve of the test: BFGS iterations and
/// the largest relative σ_yy error (0.13 %).
const PAPER_ITERATIONS: usize = 6;
const PAPER_SYY_ERROR: f64 = 0.0013;
/// The rows of the paper's Table 1 that survived: iteration, residual
/// norm, update norm, max displacement (m). Row 5 was lost, and the paper
/// does not say how its norms were scaled.
const PAPER_TABLE_1: [(usize, f64, f64, f64); 5] = [
    (1, 0.0676575, 0.560272, -0.100001),
    (2, 0.0370776, 1.72072e-05, -0.100001),
    (3, 0.025447, 7.99243e-05, -0.0999878),
    (4, 0.0300309, 7.24258e-05, -0.1),
    (6, 0.00438419, 2.72107e-05, -0.1),
];
// ANCHOR_END: paper

/// A solved variant of the test.
struct Case {
    rule: Integration,
    exact: Exact,
    /// ‖R(u_exact)‖ / ‖R(0)‖.
    consistency: f64,
    problem: Problem,
    solution: Solution,
    errors: PatchErrors,
}

/// The relative σ_yy error at a map point, the quantity Fig. T3 colours.
fn syy_error_at(q: &FieldPoint, pressure: f64) -> f64 {
    (q.stress[1] + pressure).abs() / pressure
}

/// The largest relative σ_yy error over the cells of the Fig. T3 map.
fn syy_map_max(case: &Case) -> f64 {
    let p = case.exact.pressure;
    field_cells(
        &case.problem,
        &case.solution.full,
        MAP_SUBCELLS,
        Placement::Reference,
        |q| syy_error_at(q, p),
    )
    .map_or(f64::NAN, |cells| {
        cells
            .iter()
            .map(|c| c.value)
            .fold(f64::NEG_INFINITY, f64::max)
    })
}

/// The largest value of the σ_yy error map of `case` in each body's
/// element row along the contact interface and in its other elements:
/// `(body name, [near, far])`, what Fig. T3b shows of where the Gauss
/// error sits.
fn syy_map_rows(case: &Case) -> Result<Vec<(String, [f64; 2])>> {
    let p = case.exact.pressure;
    let problem = &case.problem;
    let cells = field_cells(
        problem,
        &case.solution.full,
        MAP_SUBCELLS,
        Placement::Reference,
        |q| syy_error_at(q, p),
    )?;
    // field_cells walks bodies, then elements, MAP_SUBCELLS² cells each
    let mut cells = cells.chunks(MAP_SUBCELLS * MAP_SUBCELLS);
    let mut rows = Vec::new();
    for (b, body) in problem.bodies.iter().enumerate() {
        let side = problem.pairs.iter().find_map(|pair| match pair.master {
            _ if pair.slave == b => Some(pair.slave_side),
            Master::Body { body, side } if body == b => Some(side),
            _ => None,
        });
        let near: Vec<usize> = side.map_or_else(Vec::new, |side| {
            body.space
                .boundary(side)
                .iter()
                .map(|e| e.element)
                .collect()
        });
        let mut max = [f64::NEG_INFINITY; 2];
        for e in 0..body.space.elements.len() {
            let row = usize::from(!near.contains(&e));
            let worst = cells
                .next()
                .into_iter()
                .flatten()
                .map(|c| c.value)
                .fold(f64::NEG_INFINITY, f64::max);
            max[row] = max[row].max(worst);
        }
        rows.push((body.name.clone(), max));
    }
    Ok(rows)
}

/// Sub-cells per element direction of the field maps.
const MAP_SUBCELLS: usize = 8;

fn rule_name(rule: Integration) -> &'static str {
    match rule {
        Integration::Segment => "segment",
        Integration::Gauss => "gauss",
    }
}

// ANCHOR: solve
/// Solves the scene with contact integration `rule` and measures it.
fn solve_case(rule: Integration) -> Result<Case> {
    let mut scene = companion::shipped("taylor.toml")?;
    for nitsche in scene.nitsche_mut() {
        nitsche.integration = rule;
    }
    let problem = scene.build()?;
    let solution = solve(&problem, &scene.solver)?;
    let exact = Exact::of_problem(&problem)?;
    let errors = patch_errors(&problem, &solution.full, &exact)?;
    Ok(Case {
        rule,
        consistency: consistency(&problem, &exact),
        exact,
        problem,
        solution,
        errors,
    })
}

// ANCHOR_END: solve

/// The chapter "The Taylor contact patch test", section by section.
fn main() -> Result<()> {
    let mut chapter = Chapter::from_args("taylor")?;
    let cases = [
        solve_case(Integration::Segment)?,
        solve_case(Integration::Gauss)?,
    ];
    let segment = &cases[0];
    // The paper's 0.13 % is the largest value of its error map, so ours is
    // the largest value of our map (sub-cell centres), not the Gauss-point
    // maximum of Table T1, which samples the field at other points.
    let map_max = cases.each_ref().map(syy_map_max);

    // Results: Tables T1 and T2.
    write_results(&mut chapter, &cases)?;

    // Comparison with the paper: Tables T3 to T6.
    write_comparison(&mut chapter, &cases, map_max)?;

    // The numbers the prose quotes.
    let f = chapter.facts();
    record_paper_facts(f, &cases, map_max)?;
    record_case_facts(f, &cases)?;

    // "A lower block of two patches": Table T7 and its facts.
    write_patches(&mut chapter)?;

    // Figs. T1 to T3 and the VTU.
    mesh_figure(&chapter, segment)?;
    displacement_figure(&chapter, segment)?;
    error_figures(&chapter, &cases)?;
    write_vtu(&chapter, segment)?;
    chapter.finish()
}

/// The largest displacement of a case's last iteration: the quantity of
/// the last row of the paper's Table 1.
fn max_u(c: &Case) -> f64 {
    c.solution
        .history
        .rows
        .last()
        .map_or(f64::NAN, |r| r.max_displacement)
}

// ANCHOR: tables
/// An error column: every error of Tables T1, T2 and T7 is printed with
/// two significant digits.
fn sci(key: &'static str, label: &'static str, unit: Unit) -> Column {
    Column::new(key, label, unit, Format::Sci(2))
}

/// "Results": Tables T1 (`summary`) and T2 (`errors`), one row per
/// integration rule. summary.csv keeps exactly the columns other tools
/// read.
fn write_results(chapter: &mut Chapter, cases: &[Case; 2]) -> Result<()> {
    let mut summary = Table::new(vec![
        Column::plain("integration", "integration"),
        Column::plain("iterations", "BFGS iterations"),
        sci("max_rel_error_syy", "max |σ_yy + p|/p", Unit::None),
        Column::new(
            "uy_top",
            "u_y on top, worst sample",
            Unit::Metre,
            Format::Fixed(9),
        ),
    ]);
    let mut errors = Table::new(vec![
        Column::plain("integration", "integration"),
        Column::plain("contact_points", "points"),
        sci("max_rel_error_sxx", "max |σ_xx|/p", Unit::None),
        sci("max_rel_error_sxy", "max |σ_xy|/p", Unit::None),
        sci("max_displacement_error", "max ‖u − u*‖", Unit::Metre),
        Column::new(
            "ux_right",
            "u_x at x = 1, worst",
            Unit::Metre,
            Format::Fixed(9),
        )
        .csv_only(),
        Column::new("force_error", "force error", Unit::None, Format::Sci(2)),
    ]);
    for c in cases {
        let e = &c.errors;
        let name = rule_name(c.rule);
        summary.push(vec![
            name.into(),
            c.solution.history.len().into(),
            e.syy.into(),
            e.uy_top.into(),
        ])?;
        errors.push(vec![
            name.into(),
            c.problem.points.len().into(),
            e.sxx.into(),
            e.sxy.into(),
            e.displacement.into(),
            e.ux_right.into(),
            e.force.into(),
        ])?;
    }
    chapter.table("summary", &summary)?;
    chapter.table("errors", &errors)
}

/// "Comparison with the paper": Table T3 (the paper's numbers beside
/// ours), T4 (the paper's history) and T5, T6 (ours).
fn write_comparison(chapter: &mut Chapter, cases: &[Case; 2], map_max: [f64; 2]) -> Result<()> {
    chapter.table("paper_beside_ours", &paper_beside_ours(cases, map_max)?)?;
    chapter.table("iterations_paper", &paper_history()?)?;
    for c in cases {
        let t = history_table(&c.solution.history, Unit::NewtonPerMetre, Unit::Metre)?;
        chapter.table(&format!("iterations_{}", rule_name(c.rule)), &t)?;
    }
    Ok(())
}

/// Table T3: the paper's numbers beside ours, each labelled with where
/// the paper gives it.
fn paper_beside_ours(cases: &[Case; 2], map_max: [f64; 2]) -> Result<Table> {
    let mut beside = Table::new(vec![
        Column::plain("quantity", "quantity"),
        Column::plain("paper", "the paper"),
        Column::plain("segment", "ours, segment"),
        Column::plain("gauss", "ours, Gauss points"),
    ]);
    let percent = |v: f64| Cell::from(Format::Percent(2).render(v));
    let fixed = |v: f64| Cell::from(Format::Fixed(5).render(v));
    // One row per quantity: its label, the paper's value, and ours for
    // each case (segment, Gauss). The error row is the largest value of
    // the map, as the paper's; the displacement row the largest
    // displacement of the last iteration, as the paper's Table 1 column.
    let rows: [(&str, Cell, [Cell; 2]); 3] = [
        (
            "quasi-Newton iterations (the paper's Table 1)",
            PAPER_ITERATIONS.into(),
            cases.each_ref().map(|c| c.solution.history.len().into()),
        ),
        (
            "largest value of the σ_yy error map, |σ_yy + p|/p (the paper's Fig. 3)",
            percent(PAPER_SYY_ERROR),
            map_max.map(percent),
        ),
        (
            "max u, m (the paper's Table 1, last row)",
            PAPER_TABLE_1[PAPER_TABLE_1.len() - 1].3.into(),
            cases.each_ref().map(|c| fixed(max_u(c))),
        ),
    ];
    for (quantity, paper, [segment, gauss]) in rows {
        beside.push(vec![quantity.into(), paper, segment, gauss])?;
    }
    Ok(beside)
}

/// Table T4: the rows of the paper's Table 1 that survived, as printed.
fn paper_history() -> Result<Table> {
    let mut paper = Table::new(vec![
        Column::plain("iteration", "it."),
        Column::new("residual", "‖R‖", Unit::None, Format::Plain),
        Column::new("update", "‖Δu‖", Unit::None, Format::Plain),
        Column::new("max_displacement", "max u", Unit::Metre, Format::Plain),
    ]);
    for (k, r, du, u) in PAPER_TABLE_1 {
        paper.push(vec![k.into(), r.into(), du.into(), u.into()])?;
    }
    Ok(paper)
}

// ANCHOR_END: tables

// ANCHOR: facts
/// "Comparison with the paper" quotes the paper's numbers, on the scales
/// of ours, and what its own history says.
fn record_paper_facts(f: &mut Facts, cases: &[Case; 2], map_max: [f64; 2]) -> Result<()> {
    let [segment, gauss] = cases;
    f.count("paper_iterations", PAPER_ITERATIONS)?;
    f.number("paper_syy_error", PAPER_SYY_ERROR, Format::Percent(2))?;
    f.number("paper_syy_log10", PAPER_SYY_ERROR.log10(), Format::Fixed(2))?;
    f.number(
        "gauss_syy_log10",
        gauss.errors.syy.log10(),
        Format::Fixed(2),
    )?;
    f.number("gauss_map_log10", map_max[1].log10(), Format::Fixed(2))?;
    f.number("gauss_map_percent", map_max[1], Format::Percent(2))?;
    for (body, [near, far]) in syy_map_rows(gauss)? {
        f.number(
            &format!("gauss_map_{body}_interface_log10"),
            near.log10(),
            Format::Fixed(2),
        )?;
        f.number(
            &format!("gauss_map_{body}_away_log10"),
            far.log10(),
            Format::Fixed(2),
        )?;
    }
    f.number("gauss_max_u", max_u(gauss), Format::Fixed(5))?;
    f.number("segment_max_u", max_u(segment), Format::Fixed(5))?;
    // The paper's own history: how far its first iterate is from the exact
    // top displacement, and how large its later updates are against the
    // first (in its own, unstated, norm scaling).
    let (_, _, first_update, first_u) = PAPER_TABLE_1[0];
    f.number(
        "paper_first_max_u_offset",
        (first_u + 0.1).abs(),
        Format::Pow10(0),
    )?;
    let later = PAPER_TABLE_1[1..]
        .iter()
        .map(|r| r.2)
        .fold(0.0f64, f64::max);
    f.number(
        "paper_later_update_ratio",
        later / first_update,
        Format::Pow10(1),
    )
}

/// "The program" and "Results" quote each rule's errors and iterations,
/// and what the measures sample.
fn record_case_facts(f: &mut Facts, cases: &[Case; 2]) -> Result<()> {
    for c in cases {
        let name = rule_name(c.rule);
        let e = &c.errors;
        f.count(&format!("{name}_iterations"), c.solution.history.len())?;
        f.count(&format!("{name}_contact_points"), c.problem.points.len())?;
        f.number(&format!("{name}_syy_error"), e.syy, Format::Pow10(1))?;
        f.number(&format!("{name}_syy_percent"), e.syy, Format::Percent(2))?;
        f.number(&format!("{name}_uy_top"), e.uy_top, Format::Fixed(5))?;
        f.number(&format!("{name}_force_error"), e.force, Format::Pow10(0))?;
        f.number(
            &format!("{name}_consistency"),
            c.consistency,
            Format::Pow10(0),
        )?;
        let first = c.solution.history.rows[0].relative_residual;
        f.number(&format!("{name}_first_residual"), first, Format::Pow10(0))?;
    }
    let segment = &cases[0];
    f.count("gauss_points_checked", segment.errors.gauss_points)?;
    f.count("side_samples", SIDE_SAMPLES)?;
    // the exact state widens the blocks by ε_xx = ν p / E
    let widening = segment.exact.displacement([1.0, 0.0])[0];
    f.number("relative_widening", widening, Format::Percent(0))
}
// ANCHOR_END: facts

// ANCHOR: patches
/// "A lower block of two patches": the segment rule's test with the lower
/// block as one patch, as two matching patches and as two non-matching
/// ones tied by Nitsche's method (Table T7, `patches`), the lower block
/// the slave in all three.
fn write_patches(chapter: &mut Chapter) -> Result<()> {
    let scene = companion::shipped("taylor.toml")?;
    let mut table = Table::new(vec![
        Column::plain("lower_block", "lower block"),
        Column::plain("elements", "elements (left, right)"),
        Column::plain("ties", "tied interfaces"),
        Column::plain("iterations", "BFGS iterations"),
        sci("max_rel_error_syy", "max |σ_yy + p|/p", Unit::None),
        sci("max_displacement_error", "max ‖u − u*‖", Unit::Metre),
    ]);
    for (lower, name) in [
        (LowerBlock::One, "one_patch"),
        (LowerBlock::Matching, "matching"),
        (LowerBlock::NonMatching, "non_matching"),
    ] {
        let problem = blocks_problem(&scene, lower)?;
        let solution = solve(&problem, &scene.solver)?;
        let e = patch_errors(&problem, &solution.full, &Exact::of_problem(&problem)?)?;
        let elements: Vec<String> = lower_elements(lower)
            .iter()
            .map(|[x, y]| format!("{x}×{y}"))
            .collect();
        table.push(vec![
            name.replace('_', " ").into(),
            elements.join(", ").into(),
            problem.map.ties().len().into(),
            solution.history.len().into(),
            e.syy.into(),
            e.displacement.into(),
        ])?;
        let f = chapter.facts();
        f.number(&format!("{name}_syy_error"), e.syy, Format::Pow10(1))?;
        f.number(
            &format!("{name}_displacement_error"),
            e.displacement,
            Format::Pow10(1),
        )?;
    }
    chapter.facts().number(
        "tie_factor",
        iga_contact::dofs::TIE_FACTOR,
        Format::Fixed(0),
    )?;
    chapter.table("patches", &table)
}
// ANCHOR_END: patches

// ANCHOR: figures
/// Fig. T1 (the paper's Fig. 1): element boundaries and control nets of
/// both blocks.
fn mesh_figure(chapter: &Chapter, segment: &Case) -> Result<()> {
    let mut lines = Vec::new();
    for (b, body) in segment.problem.bodies.iter().enumerate() {
        let patch = &body.space.patch;
        let name = &body.name;
        lines.extend(labelled(
            element_lines(patch, LineKind::Solid, b),
            &format!("{name}: elements"),
        ));
        lines.extend(labelled(
            control_net(patch, b + 2),
            &format!("{name}: control net"),
        ));
    }
    let [lo, up] = [0, 1].map(|b| segment.problem.bodies[b].space.n_elements());
    geometry_figure(
        chapter.path("mesh.svg"),
        &format!(
            "Taylor patch test: {}×{} and {}×{} elements, p = 2",
            lo[0], lo[1], up[0], up[1]
        ),
        &lines,
    )
}

/// Fig. T2 (the paper's Fig. 2): u_y on the deformed blocks, the
/// undeformed outlines dashed.
fn displacement_figure(chapter: &Chapter, segment: &Case) -> Result<()> {
    let cells = field_cells(
        &segment.problem,
        &segment.solution.full,
        MAP_SUBCELLS,
        Placement::Deformed,
        |p| p.displacement[1],
    )?;
    let outlines: Vec<Polyline> = segment
        .problem
        .bodies
        .iter()
        .map(|b| {
            Polyline::new(b.space.patch.outline(16), LineKind::Dashed, BLACK_INDEX)
                .labelled("undeformed")
        })
        .collect();
    field_figure(
        chapter.path("displacement.svg"),
        "u_y on the deformed blocks (true scale)",
        "u_y (m)",
        &cells,
        &outlines,
    )
}

/// Fig. T3 (the paper's Fig. 3): log10 of the relative σ_yy error, clamped
/// at round-off, one map per rule.
fn error_figures(chapter: &Chapter, cases: &[Case; 2]) -> Result<()> {
    for c in cases {
        let p = c.exact.pressure;
        let cells = field_cells(
            &c.problem,
            &c.solution.full,
            MAP_SUBCELLS,
            Placement::Reference,
            |q| syy_error_at(q, p).max(1e-16).log10(),
        )?;
        let grid: Vec<Polyline> = c
            .problem
            .bodies
            .iter()
            .flat_map(|b| element_lines(&b.space.patch, LineKind::Thin, BLACK_INDEX))
            .collect();
        let name = rule_name(c.rule);
        field_figure(
            chapter.path(&format!("error_syy_{name}.svg")),
            &format!("Relative σ_yy error, {name} integration"),
            &format!(
                "log₁₀ |σ_yy + p|/p (the paper's max: {})",
                Format::Fixed(2).render(PAPER_SYY_ERROR.log10())
            ),
            &cells,
            &grid,
        )?;
    }
    Ok(())
}

/// The segment solution for a viewer (Figs. T1 and T2 are drawn from the
/// same case).
fn write_vtu(chapter: &Chapter, segment: &Case) -> Result<()> {
    sample_bodies(
        &segment.problem.bodies,
        &segment.problem.map,
        &segment.solution.full,
        4,
    )?
    .write(chapter.path("taylor.vtu"))
}
// ANCHOR_END: figures
