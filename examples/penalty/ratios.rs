//! "(11) against the bound": the paper's penalty over the sharp bound at
//! the contact points of the four set-ups, for every degree and mesh
//! (Table PS1, Fig. PS1 and their facts).

use crate::{setups, DEGREES, MESHES, SETUPS};
use companion::chapter::Chapter;
use companion::Facts;
use iga_contact::contact::penalty::stability_bound;
use iga_contact::contact::ContactPoint;
use iga_contact::error::Result;
use iga_contact::post::relative;
use iga_contact::problem::Problem;
use iga_contact::report::plot::{line_chart, Axes, Series};
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};

// ANCHOR: ratios
/// γ₍₁₁₎ over the trace constant C_T of a contact point: the paper's
/// penalty in units of the bound of θ = 1 (θ = 0 needs a quarter of it).
pub fn ratio(cp: &ContactPoint) -> f64 {
    cp.gamma / stability_bound(cp.trace_constant, 1.0)
}

/// The point where the bodies first touch: the least initial gap.
pub fn first_touch(problem: &Problem) -> &ContactPoint {
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

// ANCHOR: table
/// [set-up][mesh][degree] → the ratio at first touch.
pub type FirstTouch = [[[f64; 5]; 2]; 4];

/// What the survey of the four set-ups gives Table PS1, Fig. PS1 and the
/// facts on the singular corner.
pub struct Survey {
    /// Every set-up, degree and mesh: the ratio at first touch and the
    /// smallest (the long form of Table PS1, `ratios.csv`).
    pub long: Table,
    pub first: FirstTouch,
    /// Hertz 16², per degree.
    pub corner: Vec<Corner>,
    /// Hertz 16², NURBS degrees (p ≥ 2): the smallest ratio over the regular points.
    pub regular_min: f64,
    /// Hertz 16², p = 2: the points where the map is singular.
    pub singular_points: usize,
}

/// Two points of the Hertz side on one degree.
pub struct Corner {
    /// Where the bodies first touch.
    pub first_touch: ContactPoint,
    /// The point of smallest ratio.
    pub smallest: ContactPoint,
}

/// Table PS1 and the corner's facts come from one pass over every set-up,
/// degree and mesh.
pub fn survey_ratios() -> Result<Survey> {
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
                    corner.push(Corner {
                        first_touch: f.clone(),
                        smallest: s.clone(),
                    });
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

/// Table PS1 (the long form in `ratios.csv`, the wide one in
/// `first_touch`) and Fig. PS1.
pub fn write_survey(chapter: &mut Chapter, survey: &Survey) -> Result<()> {
    chapter.csv("ratios", &survey.long)?;
    chapter.table("first_touch", &first_touch_table(&survey.first)?)?;
    draw_ratios(chapter, &survey.first)
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
pub fn record_ratio_facts(f: &mut Facts, first: &FirstTouch) -> Result<()> {
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
