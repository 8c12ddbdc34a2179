//! The facts the chapter's prose quotes.

// the chapter's runs, measures and imports
use super::*;

// ANCHOR: facts
/// The set-up of the compound cylinder, Lamé's q, and what its ladder shows.
pub fn record_compound_facts(f: &mut Facts, c: &Compound, ladder: &[Run]) -> Result<()> {
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
pub fn record_pin_facts(
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
