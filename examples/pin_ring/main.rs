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

use companion::chapter::Chapter;
use companion::Facts;
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

/// Fig. PR1: the compound cylinder's interface pressure along the angle,
/// on the three coarsest rungs, against Lamé's q.
fn draw_compound(chapter: &Chapter, ladder: &[Run], q: f64) -> Result<()> {
    let mut series: Vec<Series> = ladder[..3]
        .iter()
        .map(|r| {
            let mut pts: Vec<(f64, f64)> = r
                .samples
                .iter()
                .map(|s| (s.x[1].atan2(s.x[0]).to_degrees(), s.pressure() * 1e-6))
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            Series::line(format!("k = {}", r.rung), pts)
        })
        .collect();
    series.push(Series::line("Lamé", vec![(0.0, q * 1e-6), (90.0, q * 1e-6)]).dashed());
    line_chart(
        chapter.path("compound_pressure.svg"),
        &Axes {
            title: "Compound cylinder, p = 2: interface pressure".into(),
            x_label: "angle from the x axis (°)".into(),
            y_label: "contact pressure (MPa)".into(),
            log_x: false,
            log_y: false,
        },
        &series,
    )
}

/// Fig. PR2: the pin's contact pressure against the angle from the lowest
/// point, on three rungs and the reference.
fn draw_pin(chapter: &Chapter, pins: &[Run], reference: &Run, center: [f64; 2]) -> Result<()> {
    let curve = |r: &Run| {
        let mut pts: Vec<(f64, f64)> = r
            .samples
            .iter()
            .map(|s| (angle_from_bottom(s.x, center), s.pressure() * 1e-6))
            .collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        pts
    };
    let mut series: Vec<Series> = pins[..3]
        .iter()
        .map(|r| Series::line(format!("n = {}", r.rung), curve(r)))
        .collect();
    series.push(
        Series::line(
            format!("reference, n = {}", reference.rung),
            curve(reference),
        )
        .dashed(),
    );
    line_chart(
        chapter.path("pin_pressure.svg"),
        &Axes {
            title: "Pin in a ring, p = 2: contact pressure".into(),
            x_label: "angle from the lowest point (°)".into(),
            y_label: "contact pressure (MPa)".into(),
            log_x: false,
            log_y: false,
        },
        &series,
    )
}

/// Fig. PR3: the errors of both benchmarks against the elements along the
/// interface (the slave's).
fn draw_errors(
    chapter: &Chapter,
    ladder: &[Run],
    q: f64,
    pins: &[Run],
    reference: &Run,
    center: [f64; 2],
) -> Result<()> {
    let reference_angle = half_angle(reference, center);
    // slave elements along the interface: the outer ring's 2k; the pin's
    // three arc patches carry n each
    let compound = |f: fn((f64, f64)) -> f64| -> Vec<(f64, f64)> {
        ladder
            .iter()
            .map(|r| ((2 * r.rung) as f64, f(lame_errors(r, q))))
            .collect()
    };
    let pin_p0 = pins
        .iter()
        .map(|r| ((3 * r.rung) as f64, relative(r.p0, reference.p0).abs()))
        .collect();
    let pin_angle = pins
        .iter()
        .map(|r| {
            let e = (half_angle(r, center) - reference_angle).abs() / reference_angle;
            ((3 * r.rung) as f64, e)
        })
        .collect();
    line_chart(
        chapter.path("errors.svg"),
        &Axes {
            title: "Conformal contact, p = 2: errors under refinement".into(),
            x_label: "slave elements along the interface".into(),
            y_label: "relative error".into(),
            log_x: true,
            log_y: true,
        },
        &[
            Series::line("compound: max |p − q|/q", compound(|e| e.0)).with_markers(),
            Series::line("compound: L² error / q", compound(|e| e.1)).with_markers(),
            Series::line("pin: p₀ vs reference", pin_p0)
                .with_markers()
                .dashed(),
            Series::line("pin: half-angle vs reference", pin_angle)
                .with_markers()
                .dashed(),
        ],
    )
}

// ANCHOR: facts
/// The set-up of the compound cylinder, Lamé's q, and what its ladder shows.
fn record_compound_facts(f: &mut Facts, c: &Compound, ladder: &[Run]) -> Result<()> {
    let q = c.q();
    f.number("compound_a_mm", c.a * 1e3, Format::Fixed(0))?;
    f.number("compound_b_mm", c.b * 1e3, Format::Fixed(0))?;
    f.number("compound_c_mm", c.c * 1e3, Format::Fixed(0))?;
    f.number("compound_inner_gpa", c.inner.young * 1e-9, Format::Fixed(0))?;
    f.number("compound_inner_nu", c.inner.poisson, Format::Fixed(2))?;
    f.number("compound_outer_gpa", c.outer.young * 1e-9, Format::Fixed(0))?;
    f.number("compound_outer_nu", c.outer.poisson, Format::Fixed(2))?;
    f.number("compound_p_mpa", c.p * 1e-6, Format::Fixed(0))?;
    f.number("lame_q_mpa", q * 1e-6, Format::Fixed(4))?;
    f.number("lame_q_ratio", q / c.p, Format::Fixed(4))?;
    let errors: Vec<(f64, f64)> = ladder.iter().map(|r| lame_errors(r, q)).collect();
    let (coarse, fine) = (errors[0], errors[errors.len() - 1]);
    f.number("compound_coarsest_max_error", coarse.0, Format::Pow10(1))?;
    f.number("compound_finest_max_error", fine.0, Format::Pow10(1))?;
    f.number("compound_finest_l2_error", fine.1, Format::Pow10(1))?;
    let n = errors.len();
    let rate = |a: f64, b: f64| (a / b).log2();
    f.number(
        "compound_last_rate_max",
        rate(errors[n - 2].0, errors[n - 1].0),
        Format::Fixed(2),
    )?;
    f.number(
        "compound_last_rate_l2",
        rate(errors[n - 2].1, errors[n - 1].1),
        Format::Fixed(2),
    )?;
    f.number(
        "compound_mean_rate_l2",
        rate(errors[0].1, errors[n - 1].1) / (n - 1) as f64,
        Format::Fixed(2),
    )?;
    f.count(
        "compound_max_iterations",
        ladder
            .iter()
            .map(|r| r.solution.history.len())
            .max()
            .unwrap_or(0),
    )?;
    f.count("compound_finest_dofs", ladder[n - 1].problem.n())?;
    let first = compound_base()?;
    f.number(
        "compound_penalty_factor",
        first.contacts[0].nitsche.penalty_factor,
        Format::Fixed(1),
    )?;
    f.count("compound_finest_k", ladder[n - 1].rung)
}

/// The set-up of the pin, its reference and what its ladder shows.
fn record_pin_facts(
    f: &mut Facts,
    scene: &Scene,
    pins: &[Run],
    reference: &Run,
    center: [f64; 2],
) -> Result<()> {
    let (radius, outer) = match (&scene.bodies[0].geometry, &scene.bodies[1].geometry) {
        (
            GeometrySpec::HalfDisk4 { radius, .. },
            GeometrySpec::HalfAnnulus { outer_radius, .. },
        ) => (*radius, *outer_radius),
        _ => {
            return Err(Error::invalid(
                "pin_ring.toml",
                "bodies",
                "a half_disk_4 pin and a half_annulus ring",
            ))
        }
    };
    let force = scene
        .loads
        .iter()
        .find_map(|l| match l {
            Load::BodyForce { force, .. } => Some(force[1].abs()),
            _ => None,
        })
        .ok_or_else(|| Error::invalid("load", "none", "the pin carries a body force"))?;
    let m = scene.bodies[0].material;
    f.number("pin_radius_mm", radius * 1e3, Format::Fixed(0))?;
    f.number("ring_outer_mm", outer * 1e3, Format::Fixed(0))?;
    f.number("pin_gpa", m.young * 1e-9, Format::Fixed(0))?;
    f.number("pin_nu", m.poisson, Format::Fixed(2))?;
    f.number("pin_body_force", force * 1e-9, Format::Fixed(1))?;
    // the load on the whole pin per unit length: the body force times the disk
    let load = force * std::f64::consts::PI * radius * radius;
    f.number("pin_load_mn", load * 1e-6, Format::Fixed(3))?;
    f.number(
        "pin_mean_pressure_mpa",
        load / (2.0 * radius) * 1e-6,
        Format::Fixed(1),
    )?;
    f.count("pin_reference_n", reference.rung)?;
    f.count("pin_reference_dofs", reference.problem.n())?;
    f.number(
        "pin_reference_p0_mpa",
        reference.p0 * 1e-6,
        Format::Fixed(1),
    )?;
    let reference_angle = half_angle(reference, center);
    f.number("pin_reference_angle", reference_angle, Format::Fixed(2))?;
    f.number(
        "pin_reference_p0_ratio",
        reference.p0 / (load / (2.0 * radius)),
        Format::Fixed(3),
    )?;
    // the cosine law p = p₀ cos φ over the lower half, the classical
    // approximation of a pin in a hole with no clearance: p₀ = 4/π · P/(2R)
    let cosine = 4.0 / std::f64::consts::PI * load / (2.0 * radius);
    f.number(
        "cosine_p0_ratio",
        4.0 / std::f64::consts::PI,
        Format::Fixed(3),
    )?;
    f.number(
        "pin_reference_p0_vs_cosine",
        relative(reference.p0, cosine),
        Format::SignedPercent(1),
    )?;
    let finest = pins.last().expect("a ladder");
    f.number(
        "pin_finest_p0_vs_reference",
        relative(finest.p0, reference.p0),
        Format::SignedPercent(3),
    )?;
    f.number(
        "pin_finest_angle_vs_reference",
        half_angle(finest, center) - reference_angle,
        Format::Fixed(3),
    )?;
    f.number(
        "pin_coarsest_p0_vs_reference",
        relative(pins[0].p0, reference.p0),
        Format::SignedPercent(2),
    )?;
    let balance = pins
        .iter()
        .chain(std::iter::once(reference))
        .map(force_balance)
        .collect::<Result<Vec<_>>>()?
        .into_iter()
        .fold(0.0, f64::max);
    f.number("pin_force_balance", balance, Format::Pow10(0))?;
    f.count(
        "pin_max_iterations",
        pins.iter()
            .chain(std::iter::once(reference))
            .map(|r| r.solution.history.len())
            .max()
            .unwrap_or(0),
    )?;
    f.number(
        "pin_penalty_factor",
        scene.contacts[0].nitsche.penalty_factor,
        Format::Fixed(1),
    )
}
// ANCHOR_END: facts
