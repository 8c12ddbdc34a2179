//! Conformal contact: the program behind the chapter "Conformal contact: a
//! pin in a ring". Two benchmarks where the contact surfaces fit each other
//! before any load:
//!
//! 1. a compound cylinder under internal pressure (two concentric rings in
//!    contact all around), whose interface pressure Lamé's thick cylinders
//!    give in closed form, solved on a ladder of non-matching meshes;
//! 2. a pin pushed down in a ring with no clearance (a multi-patch slave in
//!    a one-patch half annulus), which has no closed form: its peak
//!    pressure and contact half-angle are measured on a ladder against a
//!    finer reference.
//!
//! Output: `book/src/generated/pin_ring/`. Run it with
//! `cargo run --release --example pin_ring`.

mod facts;
mod figures;

use companion::chapter::Chapter;
use companion::Facts;
use facts::{record_compound_facts, record_pin_facts};
use figures::{draw_compound, draw_errors, draw_pin};
use iga_contact::assembly::Load;
use iga_contact::error::{Error, Result};
use iga_contact::material::Material;
use iga_contact::post::{self, relative, PressureProfile, ProfileSample};
use iga_contact::problem::Problem;
use iga_contact::report::plot::{line_chart, Axes, Series};
use iga_contact::report::table::{Column, Format, Table, Unit};
use iga_contact::scene::{GeometrySpec, RefineSpec, Scene};
use iga_contact::solver::{solve, Solution};

// ANCHOR: lame
/// The compound cylinder of `examples/pin_ring/compound_cylinder.toml`: radii a < b < c,
/// the inner ring's and the outer ring's materials, the bore pressure.
struct Compound {
    a: f64,
    b: f64,
    c: f64,
    inner: Material,
    outer: Material,
    p: f64,
}

impl Compound {
    /// Reads the radii, materials and bore pressure of the scene.
    fn of(scene: &Scene) -> Result<Self> {
        let radii = |k: usize| match scene.bodies[k].geometry {
            GeometrySpec::QuarterAnnulus {
                inner_radius,
                outer_radius,
            } => Ok((inner_radius, outer_radius)),
            ref g => Err(Error::invalid(
                format!("body[{k}].geometry"),
                g.kind(),
                "not a quarter annulus",
            )),
        };
        let ((a, b), (b2, c)) = (radii(0)?, radii(1)?);
        if b != b2 {
            return Err(Error::invalid(
                "body[1].geometry.quarter_annulus.inner_radius",
                b2,
                "must equal the inner ring's outer radius",
            ));
        }
        let p = scene
            .loads
            .iter()
            .find_map(|l| match l {
                Load::Pressure { pressure, .. } => Some(*pressure),
                _ => None,
            })
            .ok_or_else(|| Error::invalid("load", "none", "the bore carries a pressure"))?;
        Ok(Compound {
            a,
            b,
            c,
            inner: scene.bodies[0].material,
            outer: scene.bodies[1].material,
            p,
        })
    }

    /// Lamé's interface pressure q, plane strain. A thick cylinder
    /// r₁ ≤ r ≤ r₂ under pressures P₁ inside and P₂ outside moves
    /// radially by u(r) = (1 + ν)/E · [(1 − 2ν) A r + B / r], with
    /// A = (P₁r₁² − P₂r₂²)/(r₂² − r₁²) and B = (P₁ − P₂) r₁²r₂²/(r₂² − r₁²).
    /// Equal radial displacements of both rings at r = b (inner: P₁ = p,
    /// P₂ = q; outer: P₁ = q, P₂ = 0) is one linear equation for q.
    fn q(&self) -> f64 {
        let (a, b, c, p) = (self.a, self.b, self.c, self.p);
        let (e1, n1) = (self.inner.young, self.inner.poisson);
        let (e2, n2) = (self.outer.young, self.outer.poisson);
        let load = 2.0 * (1.0 - n1 * n1) * p * a * a / (e1 * (b * b - a * a));
        let inner = (1.0 + n1) * ((1.0 - 2.0 * n1) * b * b + a * a) / (e1 * (b * b - a * a));
        let outer = (1.0 + n2) * ((1.0 - 2.0 * n2) * b * b + c * c) / (e2 * (c * c - b * b));
        load / (inner + outer)
    }
}
// ANCHOR_END: lame

// ANCHOR: setup
/// The compound cylinder's ladder: k, with 3k × k elements on the inner
/// ring and 2k × k on the outer one: not matching along the interface,
/// though both share the knots at ξ = m/k (the quarter annuli map the
/// parameter to the angle alike).
const COMPOUND_LADDER: [usize; 6] = [1, 2, 4, 8, 16, 32];

/// The pin's ladder: n, with the pin refined [n, n/2] (n elements along
/// each arc patch) and the ring [3n/2, 3n/4] (3n/2 along each 90°).
const PIN_LADDER: [usize; 4] = [4, 8, 16, 32];
/// The pin's reference: the same degree on a mesh twice as fine as the
/// finest rung.
const PIN_REFERENCE: usize = 64;
/// The degree of every solve.
const DEGREE: usize = 2;

/// The compound cylinder's scene, beside this program: the chapter's own
/// set-up rather than a shipped scene (see the chapter on why its
/// iteration count is not the same in any units).
fn compound_base() -> Result<Scene> {
    Scene::load(companion::chapter::source_root().join("examples/pin_ring/compound_cylinder.toml"))
}

fn compound_scene(k: usize) -> Result<Scene> {
    let mut s = compound_base()?
        .refined("inner", RefineSpec::iga(DEGREE, [3 * k, k]))?
        .refined("outer", RefineSpec::iga(DEGREE, [2 * k, k]))?;
    s.output = Default::default();
    Ok(s)
}

fn pin_scene(n: usize) -> Result<Scene> {
    let mut s = companion::shipped("pin_ring.toml")?
        .refined("pin", RefineSpec::iga(DEGREE, [n, n / 2]))?
        .refined("ring", RefineSpec::iga(DEGREE, [3 * n / 2, 3 * n / 4]))?;
    s.output = Default::default();
    Ok(s)
}
// ANCHOR_END: setup

/// One solve and its dense pressure profile, the samples of every pair
/// (the pieces of the slave boundary) in one list.
struct Run {
    /// k (compound cylinder) or n (pin).
    rung: usize,
    problem: Problem,
    solution: Solution,
    samples: Vec<ProfileSample>,
    /// p₀ and zones of the joined slave boundary.
    p0: f64,
    zones: usize,
}

fn run(scene: &Scene, rung: usize) -> Result<Run> {
    let problem = scene.build()?;
    let solution = solve(&problem, &scene.solver)?;
    let profile = PressureProfile::dense(&problem, &solution.full)?;
    let m = profile.measures_joined(0..problem.pairs.len());
    let samples = profile
        .samples()
        .iter()
        .filter(|s| s.regular)
        .copied()
        .collect();
    Ok(Run {
        rung,
        p0: m.p0,
        zones: m.zones,
        problem,
        solution,
        samples,
    })
}

// ANCHOR: measures
/// The errors of the interface pressure against Lamé's q over the dense
/// samples: the largest relative one and the relative L² one,
/// (∫(p − q)² ds / ∫ds)^½ / q.
fn lame_errors(r: &Run, q: f64) -> (f64, f64) {
    let max = r
        .samples
        .iter()
        .map(|s| relative(s.pressure(), q).abs())
        .fold(0.0, f64::max);
    let (mut sq, mut len) = (0.0, 0.0);
    for s in &r.samples {
        sq += s.weight * (s.pressure() - q).powi(2);
        len += s.weight;
    }
    (max, (sq / len).sqrt() / q)
}

/// The angle φ of a point on the pin's circle from its lowest point,
/// in degrees (0 at the bottom, 90 at the side).
fn angle_from_bottom(x: [f64; 2], center: [f64; 2]) -> f64 {
    (x[0] - center[0]).atan2(center[1] - x[1]).to_degrees()
}

/// The contact half-angle: where, going up from the lowest point, the
/// Nitsche bracket P of the dense profile first turns non-negative (linear
/// interpolation of the signed bracket between the two samples); 90° if it
/// never does on the lower half.
fn half_angle(r: &Run, center: [f64; 2]) -> f64 {
    let mut pts: Vec<(f64, f64)> = r
        .samples
        .iter()
        .map(|s| (angle_from_bottom(s.x, center), s.bracket))
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    for w in pts.windows(2) {
        let ((f0, b0), (f1, b1)) = (w[0], w[1]);
        if b0 < 0.0 && b1 >= 0.0 {
            return f0 + (f1 - f0) * b0 / (b0 - b1);
        }
    }
    90.0
}

/// The relative imbalance of the vertical contact resultant against the
/// assembled load.
fn force_balance(r: &Run) -> Result<f64> {
    let [_, fy] = post::contact_resultant(&r.problem, &r.solution.full);
    let [_, ly] = post::applied_resultant(&r.problem)?;
    Ok(((fy + ly) / ly).abs())
}
// ANCHOR_END: measures

/// The chapter "Conformal contact: a pin in a ring", section by section.
fn main() -> Result<()> {
    let mut chapter = Chapter::from_args("pin_ring")?;

    // Benchmark 1: the compound cylinder, Table PR1 and Figs. PR1, PR3.
    let compound = Compound::of(&compound_scene(1)?)?;
    let q = compound.q();
    let ladder = COMPOUND_LADDER
        .iter()
        .map(|&k| run(&compound_scene(k)?, k))
        .collect::<Result<Vec<_>>>()?;
    chapter.table("compound", &compound_table(&ladder, q)?)?;
    draw_compound(&chapter, &ladder, q)?;

    // Benchmark 2: the pin, Table PR2 and Figs. PR2, PR3.
    let pin = companion::shipped("pin_ring.toml")?;
    let center = pin_center(&pin)?;
    let pins = PIN_LADDER
        .iter()
        .map(|&n| run(&pin_scene(n)?, n))
        .collect::<Result<Vec<_>>>()?;
    let reference = run(&pin_scene(PIN_REFERENCE)?, PIN_REFERENCE)?;
    chapter.table("pin", &pin_table(&pins, &reference, center)?)?;
    draw_pin(&chapter, &pins, &reference, center)?;
    draw_errors(&chapter, &ladder, q, &pins, &reference, center)?;

    record_compound_facts(chapter.facts(), &compound, &ladder)?;
    record_pin_facts(chapter.facts(), &pin, &pins, &reference, center)?;
    chapter.finish()
}

/// The centre of the pin's half disk.
fn pin_center(scene: &Scene) -> Result<[f64; 2]> {
    match scene.bodies[0].geometry {
        GeometrySpec::HalfDisk4 { center, .. } => Ok(center),
        ref g => Err(Error::invalid(
            "body[0].geometry",
            g.kind(),
            "not a half_disk_4",
        )),
    }
}

// ANCHOR: tables
/// Table PR1: the compound cylinder's ladder against Lamé.
fn compound_table(ladder: &[Run], q: f64) -> Result<Table> {
    let mut table = Table::new(vec![
        Column::plain("k", "k"),
        Column::plain("inner_along", "inner, along").csv_only(),
        Column::plain("outer_along", "outer, along").csv_only(),
        Column::plain("dofs", "DOFs"),
        Column::plain("iterations", "its"),
        Column::new("p_min", "min p", Unit::Megapascal, Format::Fixed(4)),
        Column::new("p_max", "max p", Unit::Megapascal, Format::Fixed(4)),
        Column::new("error_max", "max error", Unit::None, Format::Sci(2)),
        Column::new("error_l2", "L² error", Unit::None, Format::Sci(2)),
        Column::new("rate_max", "rate (max)", Unit::None, Format::Fixed(2)),
        Column::new("rate_l2", "rate (L²)", Unit::None, Format::Fixed(2)),
        Column::plain("warnings", "warnings").csv_only(),
    ]);
    let errors: Vec<(f64, f64)> = ladder.iter().map(|r| lame_errors(r, q)).collect();
    for (i, r) in ladder.iter().enumerate() {
        let pressures = r.samples.iter().map(|s| s.pressure());
        let p_min = pressures.clone().fold(f64::INFINITY, f64::min);
        let p_max = pressures.fold(0.0, f64::max);
        // the rate over a halving of the element size: log₂ of the fall
        let rate = |f: fn(&(f64, f64)) -> f64| match i {
            0 => iga_contact::report::table::Cell::Empty,
            _ => (f(&errors[i - 1]) / f(&errors[i])).log2().into(),
        };
        table.push(vec![
            r.rung.into(),
            (3 * r.rung).into(),
            (2 * r.rung).into(),
            r.problem.n().into(),
            r.solution.history.len().into(),
            p_min.into(),
            p_max.into(),
            errors[i].0.into(),
            errors[i].1.into(),
            rate(|e| e.0),
            rate(|e| e.1),
            r.solution.warnings.len().into(),
        ])?;
    }
    Ok(table)
}

/// Table PR2: the pin's ladder and its reference (last row).
fn pin_table(pins: &[Run], reference: &Run, center: [f64; 2]) -> Result<Table> {
    let mut table = Table::new(vec![
        Column::plain("n", "n"),
        Column::plain("dofs", "DOFs"),
        Column::plain("iterations", "its"),
        Column::new("p0", "p₀", Unit::Megapascal, Format::Fixed(2)),
        Column::new("half_angle", "half-angle (°)", Unit::None, Format::Fixed(2)),
        Column::new(
            "p0_error_reference",
            "p₀ vs ref.",
            Unit::None,
            Format::SignedPercent(3),
        ),
        Column::new(
            "half_angle_error_reference",
            "angle vs ref. (°)",
            Unit::None,
            Format::Fixed(3),
        ),
        Column::new("force_balance", "force balance", Unit::None, Format::Sci(1)),
        Column::plain("zones", "zones").csv_only(),
        Column::plain("warnings", "warnings").csv_only(),
    ]);
    let reference_angle = half_angle(reference, center);
    for r in pins.iter().chain(std::iter::once(reference)) {
        let angle = half_angle(r, center);
        table.push(vec![
            r.rung.into(),
            r.problem.n().into(),
            r.solution.history.len().into(),
            r.p0.into(),
            angle.into(),
            relative(r.p0, reference.p0).into(),
            (angle - reference_angle).into(),
            force_balance(r)?.into(),
            r.zones.into(),
            r.solution.warnings.len().into(),
        ])?;
    }
    Ok(table)
}
// ANCHOR_END: tables
