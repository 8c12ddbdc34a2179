//! Measuring a Taylor patch-test solution against the exact homogeneous
//! state, for the Taylor chapter's program; `tests/taylor.rs` checks that
//! the measures notice a wrong field.

use iga_contact::assembly::{displacement_at, strain_at, Load};
use iga_contact::contact::{ContactPair, Contacts, Master};
use iga_contact::dofs::{Body, DofMap};
use iga_contact::error::{Error, Result};
use iga_contact::geometry::rectangle;
use iga_contact::material::Material;
use iga_contact::nurbs::Side;
use iga_contact::post;
use iga_contact::problem::Problem;
use iga_contact::scene::Scene;
use iga_contact::space::Space;

/// Points per boundary element where u_y(top) and u_x(x = 1) are sampled,
/// besides the control points of those sides.
pub const SIDE_SAMPLES: usize = 9;

/// The exact patch-test state: uniform σ_yy = −p and the displacement
/// u = (ν p x / E, −p y / E) of the blocks' common material.
#[derive(Clone, Copy, Debug)]
pub struct Exact {
    pub pressure: f64,
    pub material: Material,
}

impl Exact {
    /// The exact state of a built Taylor scene (`data/scenes/taylor.toml`
    /// or a variant of it): its pressure load and the blocks' common
    /// material, read here once for the chapter program and the tests.
    pub fn of_problem(problem: &Problem) -> Result<Exact> {
        let material = problem
            .bodies
            .first()
            .ok_or_else(|| Error::invalid("taylor problem", "bodies", "expected a body"))?
            .material;
        Ok(Exact {
            pressure: pressure(&problem.loads)?,
            material,
        })
    }

    pub fn displacement(&self, x: [f64; 2]) -> [f64; 2] {
        let strain_y = -self.pressure / self.material.young;
        let strain_x = -self.material.poisson * strain_y;
        [strain_x * x[0], strain_y * x[1]]
    }
}

/// The exact field at the control points of every body of `problem`: the
/// discrete exact solution, since the blocks are affine images of the
/// parameter square and NURBS reproduce linear fields.
pub fn exact_full(problem: &Problem, exact: &Exact) -> Vec<f64> {
    let mut full = vec![0.0; problem.map.n_total()];
    for (b, body) in problem.bodies.iter().enumerate() {
        for (a, &x) in body.space.patch.points.iter().enumerate() {
            let u = exact.displacement(x);
            full[problem.map.global(b, a, 0)] = u[0];
            full[problem.map.global(b, a, 1)] = u[1];
        }
    }
    full
}

/// Nitsche's consistency, measured: ‖R(u_exact)‖ / ‖R(0)‖, the residual
/// (13) of the discrete exact solution relative to the load.
pub fn consistency(problem: &Problem, exact: &Exact) -> f64 {
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let u = problem.map.restrict(&exact_full(problem, exact));
    norm(&problem.residual(&u).0) / norm(&problem.residual(&vec![0.0; problem.n()]).0)
}

/// The errors of a discrete solution against [`Exact`]. Stress errors are
/// relative to p, at every bulk Gauss point of both blocks; displacements
/// are sampled on the loaded top face and the right faces.
#[derive(Clone, Debug, PartialEq)]
pub struct PatchErrors {
    /// Bulk Gauss points examined (both blocks).
    pub gauss_points: usize,
    /// max |σ_yy + p| / p.
    pub syy: f64,
    /// max |σ_xx| / p.
    pub sxx: f64,
    /// max |σ_xy| / p.
    pub sxy: f64,
    /// max ‖u − u_exact‖ at the Gauss points.
    pub displacement: f64,
    /// The sampled u_y on the top face farthest from the exact value.
    pub uy_top: f64,
    /// The sampled u_x on the right faces farthest from the exact value.
    pub ux_right: f64,
    /// ‖contact force − load‖ / load.
    pub force: f64,
}

/// The pressure of the Taylor scene's one pressure load.
fn pressure<B>(loads: &[Load<B>]) -> Result<f64> {
    loads
        .iter()
        .find_map(|l| match l {
            Load::Pressure { pressure, .. } => Some(*pressure),
            _ => None,
        })
        .ok_or_else(|| Error::invalid("taylor scene", "loads", "expected a pressure"))
}

/// How the lower block of [`blocks_problem`] is made.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LowerBlock {
    /// One patch of 4 × 2 elements.
    One,
    /// Two patches side by side (split at x = 0.5), 2 × 2 elements each:
    /// a matching interface, its control points shared.
    Matching,
    /// Two patches of 2 × 3 and 2 × 4 elements: 3 against 4 elements up
    /// the shared side, tied by Nitsche's method.
    NonMatching,
}

/// The elements of the lower block's patches, left to right.
pub fn lower_elements(lower: LowerBlock) -> Vec<[usize; 2]> {
    match lower {
        LowerBlock::One => vec![[4, 2]],
        LowerBlock::Matching => vec![[2, 2], [2, 2]],
        LowerBlock::NonMatching => vec![[2, 3], [2, 4]],
    }
}

/// The Taylor test of `scene` (`data/scenes/taylor.toml`: its materials,
/// pressure, upper block and Nitsche parameters) with the lower block made
/// as `lower` says. The lower block's top is the slave boundary (one
/// contact of one piece per patch) and the upper block's bottom its
/// master, since a master is one patch side: the contact side of the
/// lower block spans its patches. Bodies `lower` (one or two patches),
/// then `upper`.
pub fn blocks_problem(scene: &Scene, lower: LowerBlock) -> Result<Problem> {
    let spec = |name: &str| scene.bodies.iter().find(|b| b.name == name);
    let (Some(lo), Some(up)) = (spec("lower"), spec("upper")) else {
        return Err(Error::invalid(
            "taylor scene",
            "bodies",
            "expected the bodies `lower, upper` of data/scenes/taylor.toml",
        ));
    };
    let pressure = pressure(&scene.loads)?;
    let nitsche = scene
        .contacts
        .first()
        .ok_or_else(|| Error::invalid("taylor scene", "contacts", "expected one contact"))?
        .nitsche
        .validate("contact[0].nitsche")?;
    let body = |name: &str, x: [f64; 2], y: [f64; 2], el: [usize; 2], m: Material| {
        Ok(Body {
            name: name.into(),
            space: Space::new(rectangle(x[0], y[0], x[1], y[1])?.k_refined(2, el)?, None)?,
            material: m,
            formulation: lo.formulation,
        })
    };
    let elements = lower_elements(lower);
    let width = 1.0 / elements.len() as f64;
    let mut bodies = elements
        .iter()
        .enumerate()
        .map(|(k, &el)| {
            let x = [k as f64 * width, (k + 1) as f64 * width];
            body("lower", x, [0.0, 0.5], el, lo.material)
        })
        .collect::<Result<Vec<Body>>>()?;
    let n_lower = bodies.len();
    bodies.push(body("upper", [0.0, 1.0], [0.5, 1.0], [3, 2], up.material)?);
    let upper = n_lower;
    let mut dofs = DofMap::builder(&bodies);
    if n_lower > 1 {
        dofs.join("lower", &(0..n_lower).collect::<Vec<_>>())?;
    }
    for p in 0..n_lower {
        dofs.fix_side(p, Side::EtaMin, 1, 0.0)?;
    }
    dofs.fix_side(0, Side::XiMin, 0, 0.0)?;
    dofs.fix_side(upper, Side::XiMin, 0, 0.0)?;
    let map = dofs.build();
    let loads = [Load::Pressure {
        body: upper,
        side: Side::EtaMax,
        pressure,
    }];
    let pairs = (0..n_lower)
        .map(|p| ContactPair {
            slave: p,
            slave_side: Side::EtaMax,
            master: Master::Body {
                body: upper,
                side: Side::EtaMin,
            },
            nitsche,
        })
        .collect();
    Problem::new(bodies, map, &loads, pairs)?.with_contacts(Contacts::of_sizes(&[n_lower])?)
}

/// Compares `full` (all DOFs of the Taylor scene: bodies `lower`, `upper`)
/// with the exact state. A NaN anywhere makes the errors NaN, so that a
/// broken solution cannot look exact.
pub fn patch_errors(problem: &Problem, full: &[f64], exact: &Exact) -> Result<PatchErrors> {
    let mut names: Vec<&str> = problem.bodies.iter().map(|b| b.name.as_str()).collect();
    // the lower block may be several patches, left to right: its right
    // face is the last one's
    names.dedup();
    let upper = problem.bodies.len().saturating_sub(1);
    let lower = upper.saturating_sub(1);
    if names != ["lower", "upper"] || full.len() != problem.map.n_total() {
        return Err(Error::invalid(
            "taylor problem",
            names.join(", "),
            "expected the bodies `lower, upper` of data/scenes/taylor.toml and their displacement",
        ));
    }
    let p = exact.pressure;
    let map = &problem.map;
    let mut e = PatchErrors {
        gauss_points: 0,
        syy: 0.0,
        sxx: 0.0,
        sxy: 0.0,
        displacement: 0.0,
        uy_top: 0.0,
        ux_right: 0.0,
        force: 0.0,
    };
    for (bi, body) in problem.bodies.iter().enumerate() {
        for el in &body.space.elements {
            for qp in body.space.quadrature(el)? {
                let s = body
                    .material
                    .stress(strain_at(map, full, bi, &el.cps, &qp.shape));
                let u = displacement_at(map, full, bi, &el.cps, &qp.shape);
                let ue = exact.displacement(qp.shape.x);
                e.gauss_points += 1;
                e.syy = nan_max(e.syy, (s[1] + p).abs() / p);
                e.sxx = nan_max(e.sxx, s[0].abs() / p);
                e.sxy = nan_max(e.sxy, s[2].abs() / p);
                e.displacement = nan_max(e.displacement, (u[0] - ue[0]).hypot(u[1] - ue[1]));
            }
        }
    }
    let top = problem.bodies[upper].space.patch.side_curve(Side::EtaMax);
    let uy_exact = exact.displacement(top.point(top.knots.first()))[1];
    e.uy_top = worst(
        side_displacements(problem, full, upper, Side::EtaMax)?.map(|u| u[1]),
        uy_exact,
    );
    let right = problem.bodies[lower].space.patch.side_curve(Side::XiMax);
    let ux_exact = exact.displacement(right.point(right.knots.first()))[0];
    e.ux_right = worst(
        side_displacements(problem, full, lower, Side::XiMax)?
            .chain(side_displacements(problem, full, upper, Side::XiMax)?)
            .map(|u| u[0]),
        ux_exact,
    );
    // the contact force on the slave: it balances the load on the upper
    // block, and equals it on the lower one
    let f = post::contact_resultant(problem, full);
    let load = post::applied_resultant(problem)?;
    let sign = if problem.pairs.first().map(|p| p.slave) == Some(upper) {
        1.0
    } else {
        -1.0
    };
    e.force = (f[0] + sign * load[0]).hypot(f[1] + sign * load[1]) / load[0].hypot(load[1]);
    Ok(e)
}

/// The value farthest from `exact`; a NaN wins.
fn worst(values: impl Iterator<Item = f64>, exact: f64) -> f64 {
    values.fold(exact, |w, v| {
        if w.is_nan() || v.is_nan() {
            f64::NAN
        } else if (v - exact).abs() > (w - exact).abs() {
            v
        } else {
            w
        }
    })
}

/// NaN-propagating maximum.
fn nan_max(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

/// Displacements on `side` of `body`: at the side's control points (for
/// the affine blocks these are nodal values of the linear exact field),
/// then at [`SIDE_SAMPLES`] points of every boundary element.
fn side_displacements(
    problem: &Problem,
    full: &[f64],
    body: usize,
    side: Side,
) -> Result<impl Iterator<Item = [f64; 2]>> {
    let map = &problem.map;
    let space = &problem.bodies[body].space;
    let mut out: Vec<[f64; 2]> = space
        .patch
        .side_indices(side)
        .into_iter()
        .map(|cp| map.cp_displacement(full, body, cp))
        .collect();
    for be in space.boundary(side) {
        let el = &space.elements[be.element];
        for k in 0..SIDE_SAMPLES {
            let t =
                be.range[0] + (be.range[1] - be.range[0]) * k as f64 / (SIDE_SAMPLES - 1) as f64;
            let (shape, _, _) = space.side_shape(&be, t)?;
            out.push(displacement_at(map, full, body, &el.cps, &shape));
        }
    }
    Ok(out.into_iter())
}
