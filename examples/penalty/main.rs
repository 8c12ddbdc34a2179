//! The penalty, measured: the program behind the chapter "The penalty,
//! measured". It compares the paper's empirical penalty (11) with the sharp
//! bound below which the θ-family loses coercivity, element by element, for
//! degrees 1 to 5 on the Hertz disk, the Taylor blocks and two elastic
//! cylinders. Output: `book/src/generated/penalty/`.
//!
//! Run it with `cargo run --release --example penalty`.

use iga_contact::contact::penalty::stability_bound;
use iga_contact::error::Result;
use iga_contact::problem::Problem;
use iga_contact::report::chapter::Chapter;
use iga_contact::report::plot::{line_chart, Axes, Series};
use iga_contact::report::table::{Column, Format, Table, Unit};
use iga_contact::scene::{RefineSpec, Scene};

// ANCHOR: setups
/// The degrees compared; p = 1 is the Lagrange Q1 mesh (a NURBS circle
/// needs p ≥ 2).
const DEGREES: [usize; 5] = [1, 2, 3, 4, 5];
/// Elements per direction of the disks' meshes.
const MESHES: [usize; 2] = [4, 16];

fn refine(p: usize, elements: [usize; 2]) -> RefineSpec {
    match p {
        1 => RefineSpec::lagrange(1, elements),
        p => RefineSpec::iga(p, elements),
    }
}

/// The three set-ups, each with degree `p` and `n` elements per direction
/// on its slave body (the Taylor blocks keep their 4×2 and 3×2 pattern,
/// scaled by n/4).
fn setups(p: usize, n: usize) -> Result<[(&'static str, Problem); 3]> {
    let m = (n / 4).max(1);
    let hertz = Scene::shipped("hertz.toml")?.refined("disk", refine(p, [n, n]))?;
    let taylor = Scene::shipped("taylor.toml")?
        .refined("lower", refine(p, [4 * m, 2 * m]))?
        .refined("upper", refine(p, [3 * m, 2 * m]))?;
    let cylinders = Scene::shipped("two_cylinders.toml")?
        .refined("upper", refine(p, [n, n]))?
        .refined("lower", refine(p, [2 * n, 2 * n]))?;
    Ok([
        ("Hertz disk", hertz.build()?),
        ("Taylor blocks", taylor.build()?),
        ("two cylinders", cylinders.build()?),
    ])
}
// ANCHOR_END: setups

// ANCHOR: ratios
/// γ₍₁₁₎ over the trace constant C_T of every contact point: the paper's
/// penalty in units of the bound of θ = 1 (θ = 0 needs a quarter of it).
/// Returns the ratio where the bodies first touch (least initial gap), and
/// the smallest and largest over the whole contact side.
fn ratios(problem: &Problem) -> (f64, f64, f64) {
    let ratio = |cp: &iga_contact::contact::ContactPoint| {
        cp.gamma / stability_bound(cp.trace_constant, 1.0)
    };
    let first = problem
        .points
        .iter()
        .min_by(|a, b| a.g0.total_cmp(&b.g0))
        .map_or(f64::NAN, ratio);
    let (lo, hi) = problem
        .points
        .iter()
        .map(ratio)
        .fold((f64::INFINITY, 0.0f64), |(l, h), r| (l.min(r), h.max(r)));
    (first, lo, hi)
}
// ANCHOR_END: ratios

fn main() -> Result<()> {
    let mut chapter = Chapter::from_args("penalty")?;

    // ANCHOR: table
    let mut table = Table::new(vec![
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
        Column::new("largest", "largest", Unit::None, Format::Fixed(3)),
    ]);
    let mut at_first: Vec<(&str, usize, f64)> = Vec::new();
    for p in DEGREES {
        for n in MESHES {
            for (name, problem) in setups(p, n)? {
                let (first, lo, hi) = ratios(&problem);
                table.push(vec![
                    name.into(),
                    p.into(),
                    n.into(),
                    first.into(),
                    lo.into(),
                    hi.into(),
                ])?;
                if n == 16 {
                    at_first.push((name, p, first));
                }
            }
        }
    }
    chapter.table("ratios", &table)?;
    // ANCHOR_END: table

    // The ratio where contact begins, against the degree, with the bounds
    // of θ = 1 (ratio 1) and θ = 0 (ratio ¼).
    let mut series: Vec<Series> = ["Hertz disk", "Taylor blocks", "two cylinders"]
        .iter()
        .map(|&name| {
            let pts = at_first
                .iter()
                .filter(|r| r.0 == name)
                .map(|r| (r.1 as f64, r.2))
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
    )?;

    // ANCHOR: facts
    let f = chapter.facts();
    for (name, key) in [
        ("Hertz disk", "hertz"),
        ("Taylor blocks", "taylor"),
        ("two cylinders", "cylinders"),
    ] {
        let mine: Vec<f64> = at_first
            .iter()
            .filter(|r| r.0 == name)
            .map(|r| r.2)
            .collect();
        let (lo, hi) = mine
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(l, h), &r| (l.min(r), h.max(r)));
        f.number(&format!("{key}_first_min"), lo, Format::Fixed(2))?;
        f.number(&format!("{key}_first_max"), hi, Format::Fixed(2))?;
        for (p, r) in DEGREES.iter().zip(&mine) {
            f.number(&format!("{key}_first_p{p}"), *r, Format::Fixed(2))?;
        }
    }
    // ANCHOR_END: facts
    chapter.finish()
}
