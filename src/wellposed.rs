//! Is the problem posed well enough to be solved? Checks made before any
//! solve, each refusing with a diagnosis instead of letting a solver return
//! an arbitrary answer or fail with a misleading message:
//!
//! 1. **Rigid modes contact cannot hold** ([`check_rigid_modes`]).
//!    Frictionless contact acts only through the normal jumps
//!    ⟦u_n⟧ = jnᵀu of its quadrature points. A rigid motion r of the bodies
//!    that the supports leave free and that no contact point sees
//!    (jnᵀr = 0 at every point) is in the kernel of every matrix of the
//!    method — stiffness and contact terms alike, since σ(r) = 0 — so the
//!    problem is singular whether loaded or not: a block that can slide
//!    along a flat contact surface, a disk that can spin about its centre
//!    on a curved one, a body with no support and no contact.
//! 2. **Enough quadrature** ([`min_quadrature`], [`min_contact_gauss_points`]).
//! 3. **An input scale double precision can carry** ([`representable`]).

use crate::contact::ContactPoint;
use crate::dofs::{Body, DofMap};
use crate::error::{Error, Result};
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};

/// Gauss points per direction a body of degree p needs: p + 1, the rule
/// that integrates the stiffness exactly on affine elements (the integrand
/// ∇R_a·D∇R_b has degree 2p per direction there). Fewer points may leave
/// zero-energy (hourglass) modes: `quadrature = 1` on the minimal block
/// gives σ_yy between −1.3e5 and +8.7e4 where −1e4 is exact. That is the
/// only case measured; on smooth splines of many elements a reduced rule
/// can still be rank-sufficient, so the rule is a safe bound, not a
/// necessary one.
pub fn min_quadrature(degree: usize) -> usize {
    degree + 1
}

/// Gauss points per contact element or segment for degree p: p + 1, exact
/// for the products of two traces (degree 2p) on a straight side, which is
/// what the contact matrices jn jnᵀ and sn jnᵀ integrate. Fewer points
/// sample the contact constraint too coarsely for the displacement field it
/// must hold, and spurious stresses follow.
pub fn min_contact_gauss_points(degree: usize) -> usize {
    degree + 1
}

/// Magnitudes of input, and of what they imply, must lie in
/// [`MIN_SCALE`] ..= [`MAX_SCALE`]: the solvers square residual entries (norms)
/// and multiply stiffness by displacement, so a scale beyond about 1e±154
/// overflows or underflows, and the margin keeps the geometric factors
/// (derivatives over small elements, the penalty p²E/h) in range too.
pub const MIN_SCALE: f64 = 1e-150;
/// See [`MIN_SCALE`].
pub const MAX_SCALE: f64 = 1e150;

/// Checks that a non-zero magnitude is one double precision can carry
/// through the solve; `what` says what the value is (for the message).
pub fn representable(field: &str, value: f64, what: &str) -> Result<()> {
    let a = value.abs();
    if a == 0.0 || !a.is_finite() || (MIN_SCALE..=MAX_SCALE).contains(&a) {
        return Ok(());
    }
    let (kind, bound) = if a > MAX_SCALE {
        ("overflows", MAX_SCALE)
    } else {
        ("underflows", MIN_SCALE)
    };
    Err(Error::invalid(
        field,
        format!("{value:e}"),
        format!(
            "the input scale {kind} double precision: {what} would be of order {a:.0e}, beyond \
             the {bound:.0e} that squared residuals and stiffness products can carry; rescale the \
             units (e.g. MPa and mm)"
        ),
    ))
}

/// Below this share of its size, a rigid motion counts as unseen by the
/// contact normals (the weighted mean of (jnᵀr)² over the points, for r
/// of unit size, is compared with its square).
pub const UNHELD: f64 = 1e-6;

/// A body's rigid motions: translation x, translation y, and rotation
/// about `centre`, scaled by `size` so that all three move the body by
/// about one unit. Being dimensionless, the basis judges a mode free or
/// held the same way in any unit of length (a rotation in metres of a
/// body one nanometre wide would otherwise look 1e-18 times weaker than a
/// translation, and one a thousand kilometres wide 1e12 times stronger).
pub(crate) struct RigidBasis {
    centre: [f64; 2],
    size: f64,
}

impl RigidBasis {
    /// The basis of one body of several patches (the control points of
    /// all of them).
    pub(crate) fn of_patches(bodies: &[Body], patches: &[usize]) -> Self {
        let pts: Vec<[f64; 2]> = patches
            .iter()
            .flat_map(|&b| bodies[b].space.patch.points.iter().copied())
            .collect();
        let n = pts.len().max(1) as f64;
        let c = pts
            .iter()
            .fold([0.0, 0.0], |a, p| [a[0] + p[0] / n, a[1] + p[1] / n]);
        let size = pts
            .iter()
            .map(|p| (p[0] - c[0]).hypot(p[1] - c[1]))
            .fold(0.0, f64::max);
        Self {
            centre: c,
            size: if size > 0.0 { size } else { 1.0 },
        }
    }

    /// Component `comp` of mode `k` at `p`.
    pub(crate) fn value(&self, k: usize, p: [f64; 2], comp: usize) -> f64 {
        match (k, comp) {
            (0, 0) | (1, 1) => 1.0,
            (2, 0) => -(p[1] - self.centre[1]) / self.size,
            (2, 1) => (p[0] - self.centre[0]) / self.size,
            _ => 0.0,
        }
    }

    /// Words for the motion with coefficients `c`.
    fn describe(&self, c: &[f64]) -> String {
        let t = [c[0], c[1]];
        let omega = c[2] / self.size;
        let tn = t[0].hypot(t[1]);
        let around = if omega.abs() > 1e-9 * tn / self.size {
            let p = [self.centre[0] - t[1] / omega, self.centre[1] + t[0] / omega];
            let far = (p[0] - self.centre[0]).hypot(p[1] - self.centre[1]) > 1e6 * self.size;
            (!far).then_some(p)
        } else {
            None
        };
        match around {
            Some(p) => format!("rotate about ({}, {})", short(p[0]), short(p[1])),
            None => format!("slide along ({}, {})", short(t[0] / tn), short(t[1] / tn)),
        }
    }
}

/// A coordinate for a message: four significant digits, no `-0`.
fn short(v: f64) -> String {
    let v = if v.abs() < 1e-12 { 0.0 } else { v };
    let s = format!("{:.4}", v);
    let s = s.trim_end_matches('0').trim_end_matches('.').to_string();
    if s == "-0" {
        "0".into()
    } else {
        s
    }
}

/// Free rigid modes of one body (its patches `patches`): coefficient
/// vectors (over [`RigidBasis`]) that move no prescribed DOF.
pub(crate) fn free_modes(
    bodies: &[Body],
    patches: &[usize],
    map: &DofMap,
    basis: &RigidBasis,
) -> Vec<Vector3<f64>> {
    let mut mtm = Matrix3::<f64>::zeros();
    for &b in patches {
        for (a, p) in bodies[b].space.patch.points.iter().enumerate() {
            for comp in 0..2 {
                if map.free(map.global(b, a, comp)).is_none() {
                    let row = Vector3::from_fn(|k, _| basis.value(k, *p, comp));
                    mtm += row * row.transpose();
                }
            }
        }
    }
    let eig = mtm.symmetric_eigen();
    let tol = 1e-10 * (1.0 + mtm.trace());
    (0..3)
        .filter(|&k| eig.eigenvalues[k] <= tol)
        .map(|k| eig.eigenvectors.column(k).into_owned())
        .collect()
}

/// Rejects rigid motions that neither the supports nor the contact points
/// hold, naming the body (or bodies) and the motion.
pub fn check_rigid_modes(bodies: &[Body], map: &DofMap, points: &[ContactPoint]) -> Result<()> {
    // Free modes of every elastic body (a group of patches moving as one),
    // as (body, coefficients); `group_at[patch]` is the body.
    let groups = map.groups();
    let mut group_at = vec![0; bodies.len()];
    for (gi, g) in groups.iter().enumerate() {
        for &b in g {
            group_at[b] = gi;
        }
    }
    let bases: Vec<RigidBasis> = groups
        .iter()
        .map(|g| RigidBasis::of_patches(bodies, g))
        .collect();
    let name = |gi: usize| &bodies[groups[gi][0]].name;
    let mut modes: Vec<(usize, Vector3<f64>)> = Vec::new();
    for (gi, g) in groups.iter().enumerate() {
        for c in free_modes(bodies, g, map, &bases[gi]) {
            modes.push((gi, c));
        }
    }
    if modes.is_empty() {
        return Ok(());
    }
    // Body, patch and control point of every global DOF a contact point
    // touches.
    let owner = |g: usize| -> (usize, usize, usize, usize) {
        let b = (0..bodies.len())
            .rev()
            .find(|&b| map.global(b, 0, 0) <= g)
            .unwrap_or(0);
        let local = g - map.global(b, 0, 0);
        (group_at[b], b, local / 2, local % 2)
    };
    // G[q][m] = jn_qᵀ r_m, weighted: M = Σ w_q g_q g_qᵀ / Σ w_q.
    let m = modes.len();
    let mut gram = DMatrix::<f64>::zeros(m, m);
    let mut total_weight = 0.0;
    let mut g = vec![0.0; m];
    for cp in points {
        g.fill(0.0);
        for (k, &dof) in cp.dofs.iter().enumerate() {
            if cp.jn[k] == 0.0 {
                continue;
            }
            let (gi, b, a, comp) = owner(dof);
            let x = bodies[b].space.patch.points[a];
            for (j, (mb, c)) in modes.iter().enumerate() {
                if *mb == gi {
                    let r: f64 = (0..3).map(|i| c[i] * bases[gi].value(i, x, comp)).sum();
                    g[j] += cp.jn[k] * r;
                }
            }
        }
        let w = cp.weight.abs();
        total_weight += w;
        for i in 0..m {
            for j in 0..m {
                gram[(i, j)] += w * g[i] * g[j];
            }
        }
    }
    if total_weight > 0.0 {
        gram /= total_weight;
    }
    let unheld = |idx: &[usize]| -> Option<DVector<f64>> {
        let sub = DMatrix::from_fn(idx.len(), idx.len(), |i, j| gram[(idx[i], idx[j])]);
        let eig = sub.clone().symmetric_eigen();
        let k = (0..idx.len()).find(|&k| eig.eigenvalues[k] <= UNHELD * UNHELD)?;
        Some(eig.eigenvectors.column(k).into_owned())
    };
    let touched = |b: usize| {
        points
            .iter()
            .any(|cp| cp.dofs.iter().any(|&d| owner(d).0 == b))
    };
    // One body at a time (the others held), then all together.
    for b in 0..groups.len() {
        let idx: Vec<usize> = (0..m).filter(|&j| modes[j].0 == b).collect();
        if idx.is_empty() {
            continue;
        }
        if let Some(v) = unheld(&idx) {
            let mut c = Vector3::zeros();
            for (i, &j) in idx.iter().enumerate() {
                c += v[i] * modes[j].1;
            }
            let why = if touched(b) {
                "no support holds it and frictionless contact acts only along the contact \
                 normals, which this motion never changes"
            } else {
                "no support holds it and no contact point touches the body"
            };
            return Err(Error::invalid(
                format!("body[{b}]"),
                format!("{:?}", name(b)),
                format!(
                    "can {} freely: {why}, so the problem is singular; add a [[support]] \
                     that holds this motion",
                    bases[b].describe(c.as_slice())
                ),
            ));
        }
    }
    let all: Vec<usize> = (0..m).collect();
    if let Some(v) = unheld(&all) {
        let mut parts = Vec::new();
        for b in 0..groups.len() {
            let mut c = Vector3::zeros();
            for (j, (mb, cj)) in modes.iter().enumerate() {
                if *mb == b {
                    c += v[j] * cj;
                }
            }
            if c.norm() > 1e-6 {
                parts.push(format!(
                    "{:?} can {}",
                    name(b),
                    bases[b].describe(c.as_slice())
                ));
            }
        }
        let first = modes[(0..m)
            .max_by(|&i, &j| v[i].abs().total_cmp(&v[j].abs()))
            .unwrap_or(0)]
        .0;
        return Err(Error::invalid(
            format!("body[{first}]"),
            format!("{:?}", name(first)),
            format!(
                "together, {}: no support holds this joint motion and the contact normals never \
                 see it, so the problem is singular; add a [[support]] that holds it",
                parts.join(" while ")
            ),
        ));
    }
    Ok(())
}
