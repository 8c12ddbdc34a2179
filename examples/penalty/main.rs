//! The penalty, measured: the program behind the chapter "The penalty,
//! measured". It compares the paper's empirical penalty (11) with the sharp
//! bound below which the θ-family loses coercivity, element by element, for
//! degrees 1 to 5 on four set-ups; solves with the sharp penalty as an
//! option; and maps the small-penalty regime where the solvers part ways.
//! The disk on an elastic block of rising stiffness is the heavy program
//! `penalty_contrast`. Output: `book/src/generated/penalty/`.
//!
//! Run it with `cargo run --release --example penalty`.

use companion::chapter::Chapter;
use companion::penalty::{hertz, measure};
use companion::Facts;
use iga_contact::contact::penalty::stability_bound;
use iga_contact::contact::{ContactPoint, PenaltyKind, Theta};
use iga_contact::error::Result;
use iga_contact::post::{penalty_stability, relative};
use iga_contact::problem::Problem;
use iga_contact::report::plot::{line_chart, Axes, Series};
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};
use iga_contact::scene::RefineSpec;
use iga_contact::solver::{SolverKind, SolverOptions};

// ANCHOR: setups
/// The degrees compared; p = 1 is the Lagrange Q1 mesh (a NURBS circle
/// needs p ≥ 2).
const DEGREES: [usize; 5] = [1, 2, 3, 4, 5];
/// Elements per direction of the slave bodies' meshes.
const MESHES: [usize; 2] = [4, 16];
/// The set-ups, in the order of the tables.
const SETUPS: [&str; 4] = [
    "Hertz disk",
    "Taylor blocks",
    "two cylinders",
    "block on floor",
];

fn refine(p: usize, elements: [usize; 2]) -> RefineSpec {
    match p {
        1 => RefineSpec::lagrange(1, elements),
        p => RefineSpec::iga(p, elements),
    }
}

/// The four set-ups, each with degree `p` and `n` elements per direction
/// on its slave body (the Taylor blocks keep their 4×2 and 3×2 pattern,
/// scaled by n/4; the block on the floor, 1 m × 0.5 m, has square
/// elements).
fn setups(p: usize, n: usize) -> Result<[Problem; 4]> {
    let m = (n / 4).max(1);
    let hertz = companion::shipped("hertz.toml")?.refined("disk", refine(p, [n, n]))?;
    let taylor = companion::shipped("taylor.toml")?
        .refined("lower", refine(p, [4 * m, 2 * m]))?
        .refined("upper", refine(p, [3 * m, 2 * m]))?;
    let cylinders = companion::shipped("two_cylinders.toml")?
        .refined("upper", refine(p, [n, n]))?
        .refined("lower", refine(p, [2 * n, 2 * n]))?;
    let block = companion::shipped("minimal.toml")?.refined("block", refine(p, [n, n / 2]))?;
    Ok([
        hertz.build()?,
        taylor.build()?,
        cylinders.build()?,
        block.build()?,
    ])
}
// ANCHOR_END: setups

// ANCHOR: ratios
/// γ₍₁₁₎ over the trace constant C_T of a contact point: the paper's
/// penalty in units of the bound of θ = 1 (θ = 0 needs a quarter of it).
fn ratio(cp: &ContactPoint) -> f64 {
    cp.gamma / stability_bound(cp.trace_constant, 1.0)
}

/// The point where the bodies first touch: the least initial gap.
fn first_touch(problem: &Problem) -> &ContactPoint {
    problem
        .points
        .iter()
        .min_by(|a, b| a.g0.total_cmp(&b.g0))
        .expect("every set-up has contact points")
}

/// The point of smallest ratio over the regular points of the contact side
/// (the map is regular there; see `ContactPoint::regular`).
fn smallest_regular(problem: &Problem) -> &ContactPoint {
    problem
        .points
        .iter()
        .filter(|cp| cp.regular)
        .min_by(|a, b| ratio(a).total_cmp(&ratio(b)))
        .expect("every set-up has regular contact points")
}

/// The point of smallest ratio on the whole contact side.
fn smallest(problem: &Problem) -> &ContactPoint {
    problem
        .points
        .iter()
        .min_by(|a, b| ratio(a).total_cmp(&ratio(b)))
        .expect("every set-up has contact points")
}
// ANCHOR_END: ratios

/// The chapter "The penalty, measured", section by section.
fn main() -> Result<()> {
    let mut chapter = Chapter::from_args("penalty")?;

    // (11) against the bound: Table PS1, Fig. PS1 and their facts.
    let survey = survey_ratios()?;
    chapter.csv("ratios", &survey.long)?;
    chapter.table("first_touch", &first_touch_table(&survey.first)?)?;
    draw_ratios(&chapter, &survey.first)?;
    record_ratio_facts(chapter.facts(), &survey.first)?;

    // Where the map is singular.
    record_corner_facts(chapter.facts(), &survey)?;

    // The sharp penalty as an option: Table PS2.
    let sharp = compare_sharp_penalty()?;
    chapter.table("sharp", &sharp.table)?;
    record_sharp_facts(chapter.facts(), &sharp)?;

    // Small penalties, where the answer stops being unique: Table PS5.
    let small = sweep_small_penalties()?;
    chapter.table("small_penalty", &small.table)?;
    record_small_facts(chapter.facts(), &small)?;

    chapter.finish()
}

// ANCHOR: table
/// [set-up][mesh][degree] → the ratio at first touch.
type FirstTouch = [[[f64; 5]; 2]; 4];

/// What the survey of the four set-ups gives Table PS1, Fig. PS1 and the
/// facts on the singular corner.
struct Survey {
    /// Every set-up, degree and mesh: the ratio at first touch and the
    /// smallest (the long form of Table PS1, `ratios.csv`).
    long: Table,
    first: FirstTouch,
    /// Hertz 16²: (first-touch point, smallest point) per degree.
    corner: Vec<(ContactPoint, ContactPoint)>,
    /// Hertz 16², NURBS degrees (p ≥ 2): the smallest ratio over the regular points.
    regular_min: f64,
    /// Hertz 16², p = 2: the points where the map is singular.
    singular_points: usize,
}

/// Table PS1 and the corner's facts come from one pass over every set-up,
/// degree and mesh.
fn survey_ratios() -> Result<Survey> {
    let mut long = Table::new(vec![
        Column::plain("setup", "set-up"),
        Column::plain("degree", "p"),
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        Column::new(
            "first_touch",
            "at first touch",
            Unit::None,
            Format::Fixed(3),
        ),
        Column::new("smallest", "smallest", Unit::None, Format::Sci(1)),
    ]);
    let mut first = [[[0.0; 5]; 2]; 4];
    let mut corner = Vec::new();
    let mut regular_min = f64::INFINITY;
    let mut singular_points = 0;
    for (ip, p) in DEGREES.into_iter().enumerate() {
        for (im, n) in MESHES.into_iter().enumerate() {
            for (is, problem) in setups(p, n)?.iter().enumerate() {
                let (f, s) = (first_touch(problem), smallest(problem));
                first[is][im][ip] = ratio(f);
                long.push(vec![
                    SETUPS[is].into(),
                    p.into(),
                    n.into(),
                    ratio(f).into(),
                    ratio(s).into(),
                ])?;
                if is == 0 && n == 16 {
                    corner.push((f.clone(), s.clone()));
                    // p = 1 is the Lagrange Q1 mesh, whose corner elements have the
                    // smallest ratio of all; the statement is about the NURBS degrees
                    if p >= 2 {
                        regular_min = regular_min.min(ratio(smallest_regular(problem)));
                    }
                    if p == 2 {
                        singular_points = problem.points.iter().filter(|cp| !cp.regular).count();
                    }
                }
            }
        }
    }
    Ok(Survey {
        long,
        first,
        corner,
        regular_min,
        singular_points,
    })
}

/// Table PS1 as the book shows it: one row per set-up and mesh, one column
/// per degree.
fn first_touch_table(first: &FirstTouch) -> Result<Table> {
    let mut wide = Table::new(
        [
            Column::plain("setup", "set-up"),
            Column::new("elements", "mesh", Unit::None, Format::Mesh),
        ]
        .into_iter()
        .chain(
            ["p1", "p2", "p3", "p4", "p5"]
                .iter()
                .zip(["p = 1", "p = 2", "p = 3", "p = 4", "p = 5"])
                .map(|(&key, header)| Column::new(key, header, Unit::None, Format::Fixed(2))),
        )
        .collect(),
    );
    for (is, name) in SETUPS.iter().enumerate() {
        for (im, n) in MESHES.into_iter().enumerate() {
            let mut row: Vec<Cell> = vec![(*name).into(), n.into()];
            row.extend(first[is][im].iter().map(|&r| Cell::from(r)));
            wide.push(row)?;
        }
    }
    Ok(wide)
}
// ANCHOR_END: table

/// Fig. PS1: the ratio where contact begins, against the degree, with the
/// bounds of θ = 1 (ratio 1) and θ = 0 (ratio ¼).
fn draw_ratios(chapter: &Chapter, first: &FirstTouch) -> Result<()> {
    let mut series: Vec<Series> = SETUPS
        .iter()
        .enumerate()
        .map(|(is, &name)| {
            let pts = DEGREES
                .iter()
                .zip(first[is][1])
                .map(|(&p, r)| (p as f64, r))
                .collect();
            Series::line(name, pts).with_markers()
        })
        .collect();
    let ends = [DEGREES[0] as f64, DEGREES[DEGREES.len() - 1] as f64];
    for (label, y) in [("bound of θ = 1", 1.0), ("bound of θ = 0", 0.25)] {
        series.push(Series::line(label, ends.iter().map(|&x| (x, y)).collect()).dashed());
    }
    line_chart(
        chapter.path("ratios.svg"),
        &Axes {
            title: "The empirical penalty over the sharp bound, where contact begins (16²)".into(),
            x_label: "degree p".into(),
            y_label: "γ₍₁₁₎ / C_T".into(),
            log_x: false,
            log_y: true,
        },
        &series,
    )
}

// ANCHOR: facts
/// The prose of "(11) against the bound" quotes, per set-up, the range of
/// Table PS1 on 16² and the order of C_T in p; and how much the Hertz
/// ratios move with the mesh.
fn record_ratio_facts(f: &mut Facts, first: &FirstTouch) -> Result<()> {
    for (is, key) in ["hertz", "taylor", "cylinders", "block"].iter().enumerate() {
        record_setup_facts(f, key, first[is][1])?;
    }
    let spread = |is: usize| {
        DEGREES
            .iter()
            .enumerate()
            .map(|(ip, _)| relative(first[is][0][ip], first[is][1][ip]).abs())
            .fold(0.0, f64::max)
    };
    f.number("hertz_mesh_spread", spread(0), Format::Percent(0))
}

/// One set-up's facts, from its ratios at first touch on 16² (`mine`, one
/// per degree).
fn record_setup_facts(f: &mut Facts, key: &str, mine: [f64; 5]) -> Result<()> {
    let lo = mine.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = mine.iter().copied().fold(0.0, f64::max);
    f.number(&format!("{key}_first_min"), lo, Format::Fixed(2))?;
    f.number(&format!("{key}_first_max"), hi, Format::Fixed(2))?;
    // the bound of θ = 0 in the same units: 4 γ / C_T
    f.number(
        &format!("{key}_first_min_theta0"),
        4.0 * lo,
        Format::Fixed(2),
    )?;
    for (p, r) in DEGREES.iter().zip(mine) {
        f.number(&format!("{key}_first_p{p}"), r, Format::Fixed(2))?;
    }
    // The growth of C_T with p, in units of E(1/h₁ + 1/h₂), which do not
    // change with p on these meshes: c(p) = 0.1 (p+1)(p+d) / ratio. Its
    // spread once divided by p², against its growth once divided by
    // (p+1)², tells which of the two is the order of C_T; the limit of
    // the ratio for large p is then 0.1 / (c/p²) at the top degree.
    let c: Vec<f64> = DEGREES
        .iter()
        .zip(mine)
        .map(|(&p, r)| 0.1 * ((p + 1) * (p + 2)) as f64 / r)
        .collect();
    let per = |k: fn(f64) -> f64| -> Vec<f64> {
        DEGREES
            .iter()
            .zip(&c)
            .map(|(&p, c)| c / k(p as f64))
            .collect()
    };
    let by_p2 = per(|p| p * p);
    let by_pp1 = per(|p| (p + 1.0) * (p + 1.0));
    let (lo2, hi2) = by_p2
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(l, h), &v| (l.min(v), h.max(v)));
    f.number(
        &format!("{key}_ct_p2_spread"),
        (hi2 - lo2) / lo2,
        Format::Percent(1),
    )?;
    f.number(
        &format!("{key}_ct_pp1_growth"),
        by_pp1[by_pp1.len() - 1] / by_pp1[0],
        Format::Fixed(1),
    )?;
    f.number(
        &format!("{key}_first_limit"),
        0.1 / by_p2[by_p2.len() - 1],
        Format::Fixed(2),
    )
}
// ANCHOR_END: facts

// ANCHOR: corner
/// "Where the map is singular": the degenerate corner of the nine-point
/// disk. The Jacobian of the disk's map vanishes at the end of the slave
/// arc, so the normal stress of the last element's shape functions grows
/// without bound there.
fn record_corner_facts(f: &mut Facts, survey: &Survey) -> Result<()> {
    let corner = &survey.corner;
    let (f2, s2) = &corner[1]; // p = 2, 16²
    f.number("corner_ratio_p2", ratio(s2), Format::Pow10(0))?;
    f.number(
        "corner_ct_growth_p2",
        s2.trace_constant / f2.trace_constant,
        Format::Pow10(0),
    )?;
    f.number("corner_gap_mm", s2.g0 * 1e3, Format::Fixed(0))?;
    f.number(
        "corner_angle_deg",
        (s2.x[0] / 0.2).asin().to_degrees(),
        Format::Fixed(0),
    )?;
    let worst = corner
        .iter()
        .map(|(_, s)| ratio(s))
        .fold(f64::INFINITY, f64::min);
    f.number("corner_ratio_min", worst, Format::Pow10(0))?;
    // away from the singular corner: the smallest ratio over the regular
    // points of the Hertz side (16², every degree), in units of the bound of
    // θ = 1 and of θ = 0
    f.number("hertz_regular_min", survey.regular_min, Format::Fixed(2))?;
    f.number(
        "hertz_regular_min_theta0",
        4.0 * survey.regular_min,
        Format::Fixed(2),
    )?;
    f.number(
        "hertz_singular_points",
        survey.singular_points as f64,
        Format::Fixed(0),
    )
}
// ANCHOR_END: corner

// ANCHOR: sharp
/// What the runs with (11) and with the sharp penalty give Table PS2 and
/// its facts.
struct SharpRuns {
    table: Table,
    /// [mesh][choice]: the spread of p₀ over θ, over the paper's p₀.
    theta_spread: [[f64; 3]; 2],
    /// θ = 1 with (11), per mesh: (active points below C_T, regular
    /// inactive points below θ·C_T).
    theta1_empirical: [(usize, usize); 2],
}

/// "The sharp penalty as an option": the Hertz disk with (11) and with the
/// sharp penalty at safety factors 1 and 2, for the three θ.
fn compare_sharp_penalty() -> Result<SharpRuns> {
    let mut table = Table::new(vec![
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        Column::plain("theta", "θ"),
        Column::plain("penalty", "penalty"),
        Column::new("gamma_over_bound", "γ/bound", Unit::None, Format::Fixed(2)),
        Column::plain("iterations", "its"),
        Column::new(
            "p0_vs_paper",
            "p₀ vs (11), θ = 0",
            Unit::None,
            Format::SignedPercent(2),
        ),
        Column::plain("below", "below"),
        Column::plain("inactive_below", "inactive below"),
    ]);
    let choices = [
        ("(11)", PenaltyKind::Empirical, 1.0),
        ("sharp ×1", PenaltyKind::Sharp, 1.0),
        ("sharp ×2", PenaltyKind::Sharp, 2.0),
    ];
    let mut theta_spread = [[0.0f64; 3]; 2];
    let mut theta1_empirical = [(0usize, 0usize); 2];
    for (im, n) in [16usize, 32].into_iter().enumerate() {
        let paper = measure(&hertz(n, |_| ())?, &SolverOptions::default())?
            .expect("the paper's setting converges")
            .p0;
        for (ic, &(label, penalty, factor)) in choices.iter().enumerate() {
            let mut p0s = Vec::new();
            for theta in Theta::ALL {
                let problem = hertz(n, |x| {
                    x.theta = theta;
                    x.penalty = penalty;
                    x.penalty_factor = factor;
                })?;
                let cp = first_touch(&problem);
                // θ = −1 has no bound: the column shows γ over the bound of θ = 0
                let bound = stability_bound(cp.trace_constant, theta.value().max(0.0));
                let o = measure(&problem, &SolverOptions::default())?;
                let (its, p0, below, inactive): (Cell, Cell, Cell, Cell) = match &o {
                    Ok(o) => {
                        p0s.push(o.p0);
                        let st = penalty_stability(&problem, &o.solution.full)[0];
                        if theta == Theta::Symmetric && ic == 0 {
                            theta1_empirical[im] = (st.active_below, st.inactive_below);
                        }
                        (
                            o.solution.history.len().into(),
                            relative(o.p0, paper).into(),
                            st.active_below.into(),
                            st.inactive_below.into(),
                        )
                    }
                    Err(kind) => ((*kind).into(), Cell::Empty, Cell::Empty, Cell::Empty),
                };
                table.push(vec![
                    n.into(),
                    theta.to_string().into(),
                    label.into(),
                    (cp.gamma / bound).into(),
                    its,
                    p0,
                    below,
                    inactive,
                ])?;
            }
            let lo = p0s.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = p0s.iter().copied().fold(0.0, f64::max);
            theta_spread[im][ic] = (hi - lo) / paper;
        }
    }
    Ok(SharpRuns {
        table,
        theta_spread,
        theta1_empirical,
    })
}

/// The prose under Table PS2 quotes how far the three θ spread p₀, and
/// how many points θ = 1 with (11) leaves below its bound.
fn record_sharp_facts(f: &mut Facts, sharp: &SharpRuns) -> Result<()> {
    // per mesh, per choice of Table PS2: (11), sharp ×1, sharp ×2
    for (im, n) in [16usize, 32].into_iter().enumerate() {
        for (ic, choice) in ["empirical", "sharp1", "sharp2"].into_iter().enumerate() {
            f.number(
                &format!("theta_spread_{choice}_{n}"),
                sharp.theta_spread[im][ic],
                Format::Percent(1),
            )?;
        }
    }
    for (im, n) in [16usize, 32].into_iter().enumerate() {
        let (active, inactive) = sharp.theta1_empirical[im];
        f.number(
            &format!("theta1_active_below_{n}"),
            active as f64,
            Format::Fixed(0),
        )?;
        f.number(
            &format!("theta1_inactive_below_{n}"),
            inactive as f64,
            Format::Fixed(0),
        )?;
    }
    Ok(())
}
// ANCHOR_END: sharp

// ANCHOR: small
/// What the sweep of small penalties gives Table PS5 and its facts.
struct SmallSweep {
    table: Table,
    /// θ = 1: the fewest regular inactive points below θ·C_T over the
    /// converged rows (a fact, not a column: the table is at the page's
    /// width).
    theta1_inactive: usize,
    /// Per θ: the smallest factor from which on the solvers agree.
    unique_from: [f64; 3],
}

/// "Small penalties: where the answer stops being unique": (11) scaled
/// down on the Hertz disk (8², p = 2), solved by three solvers.
fn sweep_small_penalties() -> Result<SmallSweep> {
    const FACTORS: [f64; 6] = [1e-4, 1e-3, 1e-2, 1e-1, 0.3, 1.0];
    let solvers = [
        ("bfgs", SolverOptions::default()),
        ("newton", SolverOptions::with_kind(SolverKind::Newton)),
        ("paper", SolverOptions::paper()),
    ];
    let paper_setting = measure(&hertz(8, |_| ())?, &SolverOptions::default())?
        .expect("the paper's setting converges")
        .p0;
    let mut small = Table::new(vec![
        Column::plain("theta", "θ"),
        Column::new("factor", "factor", Unit::None, Format::Sci(0)),
        Column::new("ratio", "γ/bound", Unit::None, Format::Sci(1)),
        Column::new("p0_bfgs", "BFGS", Unit::None, Format::SignedPercent(1)),
        Column::new("p0_newton", "Newton", Unit::None, Format::SignedPercent(1)),
        Column::new("p0_paper", "paper's", Unit::None, Format::SignedPercent(1)),
        Column::plain("zones", "zones"),
        Column::new("overlap", "overlap", Unit::Millimetre, Format::Fixed(3)),
    ]);
    let mut theta1_inactive = usize::MAX;
    let mut unique_from = [f64::INFINITY; 3];
    for (it, theta) in Theta::ALL.into_iter().enumerate() {
        for factor in FACTORS {
            let problem = hertz(8, |x| {
                x.theta = theta;
                x.penalty_factor = factor;
            })?;
            let mut row: Vec<Cell> = vec![theta.to_string().into(), factor.into()];
            let outcomes: Vec<_> = solvers
                .iter()
                .map(|(_, o)| measure(&problem, o))
                .collect::<Result<_>>()?;
            // the smallest γ/bound over the active points and the largest
            // overlap −g_n, of the first solver that converged
            let first_ok = outcomes.iter().find_map(|o| o.as_ref().ok());
            let (r, overlap) = match first_ok {
                Some(o) => {
                    let st = penalty_stability(&problem, &o.solution.full)[0];
                    let overlap = problem
                        .points
                        .iter()
                        .map(|cp| cp.normal_stress_and_jump(&o.solution.full).1 - cp.g0)
                        .fold(f64::NEG_INFINITY, f64::max);
                    if theta == Theta::Symmetric {
                        theta1_inactive = theta1_inactive.min(st.inactive_below);
                    }
                    (
                        st.min_active_ratio
                            .map(Cell::from)
                            .unwrap_or_else(|| "none".into()),
                        Cell::from(overlap),
                    )
                }
                None => (Cell::Empty, Cell::Empty),
            };
            row.push(r);
            for o in &outcomes {
                row.push(match o {
                    Ok(o) => relative(o.p0, paper_setting).into(),
                    Err(_) => "failed".into(),
                });
            }
            let zones: Vec<String> = outcomes
                .iter()
                .map(|o| o.as_ref().map_or("–".to_string(), |o| o.zones.to_string()))
                .collect();
            row.push(zones.join(" / ").into());
            row.push(overlap);
            small.push(row)?;
            // the solvers that converge agree (at least two, the same p₀ to
            // 10⁻⁶); a solver that fails is shown in the table
            let p0s: Vec<f64> = outcomes
                .iter()
                .filter_map(|o| o.as_ref().ok().map(|o| o.p0))
                .collect();
            let agree = p0s.len() >= 2 && p0s.iter().all(|&p| relative(p, p0s[0]).abs() < 1e-6);
            if agree {
                unique_from[it] = unique_from[it].min(factor);
            } else {
                unique_from[it] = f64::INFINITY;
            }
        }
    }
    Ok(SmallSweep {
        table: small,
        theta1_inactive,
        unique_from,
    })
}

/// The bullets under Table PS5 quote, per θ, the factor from which on the
/// solvers agree.
fn record_small_facts(f: &mut Facts, small: &SmallSweep) -> Result<()> {
    f.number(
        "theta1_small_inactive_below_min",
        small.theta1_inactive as f64,
        Format::Fixed(0),
    )?;
    for (it, key) in ["theta1", "theta0", "theta_minus1"].iter().enumerate() {
        match small.unique_from[it] {
            v if v.is_finite() => f.number(&format!("{key}_agree_from"), v, Format::Pow10(0))?,
            _ => f.text(&format!("{key}_agree_from"), "never")?,
        }
    }
    Ok(())
}
// ANCHOR_END: small
