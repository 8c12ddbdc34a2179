//! The trace-inverse constant C_T of a slave element, from the solver's
//! own contact points: the largest ratio of the element's weighted normal
//! stress to its energy (the premise of the stability bound of Eq. 11's
//! penalty), for the displacement and the mixed formulations, and the
//! sharp penalty set from it.

use super::params::{Nitsche, Penalty};
use super::penalty::{rigid_modes, sharp_penalty, trace_constant};
use super::point::ContactPoint;
use crate::dofs::Body;
use crate::error::{Error, Result};
use crate::pressure::SplinePressure;

/// Computes the trace-inverse constant of the slave element under `be` from
/// its contact points `points` (the solver's own quadrature), stores it in
/// every point, and with the sharp penalty sets γ from it.
pub(super) fn set_trace_constant(
    slave: &Body,
    be: &crate::space::BoundaryElement,
    nitsche: &Nitsche,
    pressure: Option<&SplinePressure>,
    points: &mut [ContactPoint],
) -> Result<()> {
    if points.is_empty() {
        return Ok(());
    }
    let el = &slave.space.elements[be.element];
    let cps: Vec<[f64; 2]> = el
        .cps
        .iter()
        .map(|&a| slave.space.patch.points[a])
        .collect();
    let c = match pressure {
        None => {
            let stiffness = crate::assembly::element_stiffness(slave, be.element)?;
            trace_constant(
                &stiffness,
                &rigid_modes(&cps),
                points.iter().map(|cp| (cp.weight, cp.sn.as_slice())),
            )?
        }
        Some(sp) => mixed_trace_constant(slave, be, sp, &cps, points)?,
    };
    let safety = match nitsche.penalty {
        Penalty::Sharp { .. } if !c.is_finite() => return Err(Error::invalid(
            "nitsche.penalty",
            "sharp",
            format!(
                "element {} has modes of no energy that carry normal stress (an under-integrated element, or, at degree 8 and above, round-off in the element's constant), so no sharp bound is computed: use penalty = \"empirical\" with a penalty_factor",
                be.element
            ),
        )),
        Penalty::Sharp { safety } => Some(safety.get()),
        Penalty::Empirical { .. } => None,
    };
    for cp in points {
        cp.trace_constant = c;
        if let Some(safety) = safety {
            cp.gamma = sharp_penalty(c, cp.theta, safety);
        }
    }
    Ok(())
}

/// The trace constant of a slave element of the mixed formulation. Its
/// energy a(v, v) = Σ_e [∫_e dev + κ Σ_i (∫_e N̂_i) t_i²] with t_i = ĝ_i·v/m̂_i
/// splits exactly into element parts, and σ_n on the element depends on the
/// element's own DOFs v_e and on the t_i of its pressure functions, which
/// the DOFs of the neighbouring elements set independently of v_e. So the
/// constant is that of an energy diag(K_dev,e, w diag(∫_e N̂_i)) over
/// (v_e, t), with σ_n(v) = s_dev·v_e + κ Σ_i N̂_i(x) t_i.
///
/// The weight w is not κ alone. In terms of the pressure p = κ t the
/// volumetric energy is ‖p‖²/κ, which vanishes as ν → ½: the constant then
/// grows like κ/h and the sharp penalty with it, to thousands of times Eq. (11)
/// at ν = 0.49999, a stiff penalty that spoils p₀ at the edge of the
/// contact. But the pressure of this space is also held by the inf-sup
/// condition, which bounds ‖p‖ by the deviatoric energy, ‖p‖²/(2μ) up to a
/// constant of order one; as for Nitsche's method in Stokes flow (Freund &
/// Stenberg 1995), the penalty then scales with the shear modulus. The
/// energy takes the stronger of the two controls,
/// w = κ · max(1, κ/(2μ)): κ itself while κ ≤ 2μ (ν ≤ 2/7).
fn mixed_trace_constant(
    slave: &Body,
    be: &crate::space::BoundaryElement,
    sp: &SplinePressure,
    cps: &[[f64; 2]],
    points: &[ContactPoint],
) -> Result<f64> {
    let space = &slave.space;
    let el = &space.elements[be.element];
    let n = 2 * el.cps.len();
    let active = sp.on_element(be.element);
    let kappa = slave.material.bulk_modulus();
    let mu = slave.material.shear_modulus();
    let dev = crate::assembly::element_stiffness(slave, be.element)?;
    let k = n + active.len();
    let mut energy = nalgebra::DMatrix::zeros(k, k);
    energy.view_mut((0, 0), (n, n)).copy_from(&dev);
    let weight = kappa * (kappa / (2.0 * mu)).max(1.0);
    for (j, &(_, me)) in active.iter().enumerate() {
        energy[(n + j, n + j)] = weight * me;
    }
    let mut rigid = nalgebra::DMatrix::zeros(k, 3);
    rigid.view_mut((0, 0), (n, 3)).copy_from(&rigid_modes(cps));
    let mut rows = Vec::with_capacity(points.len());
    for cp in points {
        let (shape, _, _) = space.side_shape(be, cp.t)?;
        let q = space.patch.side_point(be.side, cp.t);
        let nn = cp.normal;
        let m = [nn[0] * nn[0], nn[1] * nn[1], 2.0 * nn[0] * nn[1]];
        let mut s = vec![0.0; k];
        for (a, g) in shape.grad.iter().enumerate() {
            for c in 0..2 {
                // −(2μ/3) tr ε enters σ_xx and σ_yy, so σ_n with m₀ + m₁ = 1
                s[2 * a + c] -= 2.0 * mu / 3.0 * g[c];
            }
            s[2 * a] += m[0] * 2.0 * mu * g[0] + m[2] * mu * g[1];
            s[2 * a + 1] += m[1] * 2.0 * mu * g[1] + m[2] * mu * g[0];
        }
        for (i, v) in sp.basis(q[0], q[1]) {
            if let Some(j) = active.iter().position(|e| e.0 == i) {
                s[n + j] += kappa * v;
            }
        }
        rows.push((cp.weight, s));
    }
    trace_constant(
        &energy,
        &rigid,
        rows.iter().map(|(w, s)| (*w, s.as_slice())),
    )
}
