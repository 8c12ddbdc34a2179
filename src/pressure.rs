//! The pressure space of the mixed formulation: the continuous splines of
//! degree p − 1 and continuity one less than the displacement's, on the
//! same knots (the derivative space: each knot vector loses its first and
//! last knot). A maximally smooth displacement space of degree p has about
//! two DOFs per element and this space about one function per element, so
//! the incompressibility constraints do not outnumber the displacements —
//! a discontinuous pressure of degree p − 1 per element imposes p² per
//! element and locks (chapter "Near incompressibility").
//!
//! The dilatation is projected with the pressure mass lumped by rows,
//! θ̄ = Σ_i N̂_i (ĝ_i · u) / m̂_i with ĝ_i = ∫ N̂_i div and m̂_i = ∫ N̂_i, so
//! the condensed volumetric stiffness κ Σ_i ĝ_i ĝ_iᵀ / m̂_i stays sparse,
//! symmetric and positive semi-definite. In the incompressible limit it
//! imposes the constraints ĝ_i · u = 0 of the consistent projection; the
//! lumping only changes the compressible part, by O(h²) in the pressure.

use crate::dofs::Body;
use crate::error::Result;
use crate::nurbs::KnotVector;
use crate::space::{Element, ElementValues, Space};
use rayon::prelude::*;

/// One pressure function's integrals over one element: its index, ∫_e N̂_i,
/// and ∫_e N̂_i ∂/∂x_c per element DOF (2·a + c).
type Local = (usize, f64, Vec<f64>);

/// The pressure space of one body and its divergence functionals.
#[derive(Clone, Debug)]
pub struct SplinePressure {
    knots: [KnotVector; 2],
    n0: usize,
    mass: Vec<f64>,
    /// ĝ_i as (2·cp + component, value), sorted by the first entry.
    div: Vec<Vec<(usize, f64)>>,
    /// Per element: the pressure functions not zero on it, with ∫_e N̂_i.
    element_mass: Vec<Vec<(usize, f64)>>,
}

impl SplinePressure {
    /// Integrates m̂_i, ĝ_i and ∫_e N̂_i with the body's own quadrature.
    pub fn new(body: &Body) -> Result<Self> {
        let space = &body.space;
        let knots = [0, 1].map(|d| {
            let k = space.patch.knots[d].knots();
            let p = space.patch.knots[d].degree();
            KnotVector::new(k[1..k.len() - 1].to_vec(), p.saturating_sub(1))
        });
        let [k0, k1] = knots;
        let knots = [k0?, k1?];
        let n0 = knots[0].n_basis();
        let n = n0 * knots[1].n_basis();
        let mut this = Self {
            knots,
            n0,
            mass: vec![0.0; n],
            div: vec![Vec::new(); n],
            element_mass: Vec::with_capacity(space.elements.len()),
        };
        // the elements' integrals in parallel, merged in element order:
        // deterministic, and the merge is linear in the entries
        let locals: Vec<Result<Vec<Local>>> = space
            .elements
            .par_iter()
            .map_init(
                || ElementValues::new(space),
                |values, el| this.element_integrals(values, space, el),
            )
            .collect();
        for (el, local) in space.elements.iter().zip(locals) {
            let local = local?;
            let mut em = Vec::with_capacity(local.len());
            for (i, m, g) in local {
                this.mass[i] += m;
                em.push((i, m));
                for (a, &cp) in el.cps.iter().enumerate() {
                    this.div[i].push((2 * cp, g[2 * a]));
                    this.div[i].push((2 * cp + 1, g[2 * a + 1]));
                }
            }
            this.element_mass.push(em);
        }
        this.div.par_iter_mut().for_each(merge_sorted);
        Ok(this)
    }

    /// ∫_e N̂_i and ∫_e N̂_i ∂/∂x_c over the element's shape functions (2·a
    /// + c), for the pressure functions i not zero on element `el`.
    fn element_integrals(
        &self,
        values: &mut ElementValues,
        space: &Space,
        el: &Element,
    ) -> Result<Vec<Local>> {
        let mut local: Vec<Local> = Vec::new();
        values.reinit(space, el)?;
        for q in 0..values.n_points() {
            let [xi, eta] = values.param(q);
            for (i, v) in self.basis(xi, eta) {
                let k = match local.iter().position(|l| l.0 == i) {
                    Some(k) => k,
                    None => {
                        local.push((i, 0.0, vec![0.0; 2 * el.cps.len()]));
                        local.len() - 1
                    }
                };
                let wv = values.weight(q) * v;
                local[k].1 += wv;
                for (a, g) in values.grads(q).iter().enumerate() {
                    local[k].2[2 * a] += wv * g[0];
                    local[k].2[2 * a + 1] += wv * g[1];
                }
            }
        }
        Ok(local)
    }

    /// The number of pressure functions.
    pub fn len(&self) -> usize {
        self.mass.len()
    }

    pub fn is_empty(&self) -> bool {
        self.mass.is_empty()
    }

    /// m̂_i = ∫ N̂_i.
    pub fn mass(&self, i: usize) -> f64 {
        self.mass[i]
    }

    /// ĝ_i = ∫ N̂_i div as (2·cp + component, value), sorted.
    pub fn div(&self, i: usize) -> &[(usize, f64)] {
        &self.div[i]
    }

    /// The pressure functions not zero on element `e`, with ∫_e N̂_i.
    pub fn on_element(&self, e: usize) -> &[(usize, f64)] {
        &self.element_mass[e]
    }

    /// The non-zero pressure functions at (ξ, η), as (index, value).
    pub fn basis(&self, xi: f64, eta: f64) -> Vec<(usize, f64)> {
        self.basis_in_spans(
            [self.knots[0].find_span(xi), self.knots[1].find_span(eta)],
            xi,
            eta,
        )
    }

    /// The pressure functions of the displacement element whose knot spans
    /// are `spans` ([`crate::space::Element::spans`]), at (ξ, η). On the
    /// element's edges this stays with the element's own functions, where
    /// [`SplinePressure::basis`] takes the span to the right of a knot,
    /// whose functions the element's stress does not reach.
    pub fn basis_on_element(&self, spans: [usize; 2], xi: f64, eta: f64) -> Vec<(usize, f64)> {
        // the pressure knots drop the first knot: span s becomes s − 1
        self.basis_in_spans(spans.map(|s| s - 1), xi, eta)
    }

    fn basis_in_spans(&self, span: [usize; 2], xi: f64, eta: f64) -> Vec<(usize, f64)> {
        let bx = self.knots[0].basis_ders(span[0], xi, 0);
        let by = self.knots[1].basis_ders(span[1], eta, 0);
        let first = [0, 1].map(|d| span[d] - self.knots[d].degree());
        let mut out = Vec::with_capacity(bx[0].len() * by[0].len());
        for (jy, vy) in by[0].iter().enumerate() {
            for (jx, vx) in bx[0].iter().enumerate() {
                out.push((first[0] + jx + (first[1] + jy) * self.n0, vx * vy));
            }
        }
        out
    }

    /// θ̄(ξ, η) in the element of knot spans `spans` as a functional over
    /// the body's DOFs (2·cp + component), sorted: Σ_i N̂_i(ξ, η) ĝ_i / m̂_i
    /// over the element's own functions ([`SplinePressure::basis_on_element`]),
    /// so that on its edges it reaches only the DOFs its stress does.
    pub fn theta_row_on_element(&self, spans: [usize; 2], xi: f64, eta: f64) -> Vec<(usize, f64)> {
        self.theta_of(self.basis_on_element(spans, xi, eta))
    }

    fn theta_of(&self, basis: Vec<(usize, f64)>) -> Vec<(usize, f64)> {
        let mut row: Vec<(usize, f64)> = Vec::new();
        for (i, v) in basis {
            let c = v / self.mass[i];
            row.extend(self.div[i].iter().map(|&(d, g)| (d, c * g)));
        }
        merge_sorted(&mut row);
        row
    }
}

/// Sorts (index, value) pairs by index and sums the values of equal indices.
fn merge_sorted(v: &mut Vec<(usize, f64)>) {
    v.sort_by_key(|e| e.0);
    v.dedup_by(|later, kept| {
        if later.0 == kept.0 {
            kept.1 += later.1;
            true
        } else {
            false
        }
    });
}
