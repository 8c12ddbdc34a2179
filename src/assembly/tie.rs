//! The weak tie of a non-matching interface between two patches of one
//! body, by Nitsche's method (symmetric, θ = 1):
//!
//!   a_Γ(u, v) = −∫_Γ ⟦v⟧·{σ(u) n} − ∫_Γ {σ(v) n}·⟦u⟧ + γ ∫_Γ ⟦u⟧·⟦v⟧,
//!
//! with n the outward normal of the first patch, ⟦u⟧ = u₁ − u₂ and
//! {σ n} = ½ (σ₁ + σ₂) n. The first term is what integrating the bulk by
//! parts on each patch leaves on Γ, so the exact solution satisfies the
//! tied equations (consistency); the second makes the form symmetric, so
//! the tied stiffness stays symmetric and, with γ large enough, positive
//! definite; the third holds the two sides together.
//!
//! γ = 0.1 β E (p + 1)(p + d)(1/h₁ + 1/h₂) at each point: Eq. (11) with
//! penalty factor β = [`crate::dofs::TIE_FACTOR`] (ten times the paper's), E the
//! larger modulus of the two patches, p the larger degree along the side
//! and h_k the height of patch k's element across the interface (its area
//! over its side's length), which is what the trace inequality that γ must
//! beat scales with.
//!
//! Integrated on the union of the two sides' knot partitions
//! ([`crate::interface::Tie::segments`]), p + 2 Gauss points a segment: on
//! each segment both traces are single polynomial pieces, so on affine
//! patches every integrand is a polynomial integrated exactly, and the
//! patch test is passed to round-off. The tie is linear: it adds to the
//! stiffness, and the solvers see only the sum.

use super::Triplets;
use crate::dofs::{Body, DofMap};
use crate::error::{Error, Result};
use crate::quadrature;
use crate::space::BoundaryElement;
use nalgebra::DMatrix;

/// The spatial dimension d in γ.
const DIM: f64 = 2.0;

/// The boundary element of `side` holding parameter `t`.
fn element_at(elements: &[BoundaryElement], t: f64) -> Option<&BoundaryElement> {
    elements
        .iter()
        .find(|be| be.range[0] <= t && t <= be.range[1])
}

/// Area of element `e` of `body`, from its own quadrature.
fn area(body: &Body, e: usize) -> Result<f64> {
    let el = &body.space.elements[e];
    Ok(body.space.quadrature(el)?.iter().map(|q| q.weight).sum())
}

/// The traction (σ n) of the basis function `k`, component `c`, for the
/// elasticity matrix `d`: σ = D ε with ε of u = R_k e_c.
fn traction(grad: [f64; 2], c: usize, d: &[[f64; 3]; 3], n: [f64; 2]) -> [f64; 2] {
    let eps = if c == 0 {
        [grad[0], 0.0, grad[1]]
    } else {
        [0.0, grad[1], grad[0]]
    };
    let s: Vec<f64> = (0..3)
        .map(|i| (0..3).map(|j| d[i][j] * eps[j]).sum())
        .collect();
    [s[0] * n[0] + s[2] * n[1], s[2] * n[0] + s[1] * n[1]]
}

/// The tie matrices of every non-matching interface of `map`
/// ([`DofMap::ties`]) with the penalty factor `factor`, as triplets over
/// the free DOFs of `map`, and their lift (the prescribed columns times
/// their values; subtract it from the load). [`crate::problem::Problem`]
/// adds them with the map's own, checked, factor
/// ([`DofMap::tie_factor`]); another factor here is for studying the
/// penalty.
pub fn tie_stiffness(bodies: &[Body], map: &DofMap, factor: f64) -> Result<(Triplets, Vec<f64>)> {
    let mut trip = Triplets::default();
    let mut lift = vec![0.0; map.n_free()];
    for tie in map.ties() {
        let [pa, pb] = tie.patches;
        let (a, b) = (&bodies[pa], &bodies[pb]);
        let young = a.material.young.max(b.material.young);
        let degree = a.space.patch.degree()[tie.sides[0].along()]
            .max(b.space.patch.degree()[tie.sides[1].along()]);
        let p = degree as f64;
        let sides = [
            a.space.boundary(tie.sides[0]),
            b.space.boundary(tie.sides[1]),
        ];
        let d = [a.material.d_matrix(), b.material.d_matrix()];
        for seg in tie.segments(&a.space.patch, &b.space.patch) {
            let mid = 0.5 * (seg[0] + seg[1]);
            let (ta0, ta1) = (
                tie.param(0, &a.space.patch, seg[0]),
                tie.param(0, &a.space.patch, seg[1]),
            );
            let elements = [
                element_at(&sides[0], tie.param(0, &a.space.patch, mid)),
                element_at(&sides[1], tie.param(1, &b.space.patch, mid)),
            ];
            let [Some(ea), Some(eb)] = elements else {
                return Err(Error::invalid(
                    "tie",
                    format!("patches {pa} and {pb}"),
                    "a segment of the interface lies on no element of one side",
                ));
            };
            let heights = [
                area(a, ea.element)? / ea.length,
                area(b, eb.element)? / eb.length,
            ];
            let gamma = factor
                * 0.1
                * young
                * (p + 1.0)
                * (p + DIM)
                * (1.0 / heights[0] + 1.0 / heights[1]);
            let rule = quadrature::on_interval(degree + 2, ta0, ta1);
            let na = a.space.elements[ea.element].cps.len();
            let nb = b.space.elements[eb.element].cps.len();
            let mut ke = DMatrix::zeros(2 * (na + nb), 2 * (na + nb));
            for (t, w) in rule {
                let s = seg[0] + (seg[1] - seg[0]) * (t - ta0) / (ta1 - ta0);
                let (sha, n, len) = a.space.side_shape(ea, t)?;
                let (shb, _, _) = b.space.side_shape(eb, tie.param(1, &b.space.patch, s))?;
                // J (jump) and F (average traction) as 2 × N rows over
                // the DOFs of both elements, first patch's first
                let cols = 2 * (na + nb);
                let (mut jump, mut flux) = (DMatrix::zeros(2, cols), DMatrix::zeros(2, cols));
                let mut at = 0;
                for (k, shape) in [&sha, &shb].into_iter().enumerate() {
                    let sign = if k == 0 { 1.0 } else { -1.0 };
                    for (i, (&r, &g)) in shape.r.iter().zip(&shape.grad).enumerate() {
                        for c in 0..2 {
                            jump[(c, at + 2 * i + c)] = sign * r;
                            let f = traction(g, c, &d[k], n);
                            flux[(0, at + 2 * i + c)] = 0.5 * f[0];
                            flux[(1, at + 2 * i + c)] = 0.5 * f[1];
                        }
                    }
                    at += 2 * shape.r.len();
                }
                let wl = w * len;
                let jt = jump.transpose();
                ke += wl * (gamma * &jt * &jump - &jt * &flux - flux.transpose() * &jump);
            }
            let dofs: Vec<usize> = map
                .element_dofs(pa, &a.space.elements[ea.element].cps)
                .into_iter()
                .chain(map.element_dofs(pb, &b.space.elements[eb.element].cps))
                .collect();
            trip.add(map, &dofs, &ke, &mut lift);
        }
    }
    Ok((trip, lift))
}
