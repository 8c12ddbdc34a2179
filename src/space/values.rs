//! The quadrature values of one element in reusable flat buffers, in the
//! manner of deal.II's `FEValues` and Ferrite.jl's `CellValues`: one
//! object per thread (or per parallel chunk), sized once, `reinit`ed per
//! element. Assembly used to collect a `Vec` of points per element, each
//! owning its own basis and gradient vectors; here an element allocates
//! nothing.

use super::tables::SpanTables;
use super::{Element, QuadPoint, Shape, Space};
use crate::error::Result;

/// Shape functions, physical points and weights at the Gauss points of one
/// element: point q = gx + gy · n (ξ fastest, as the element's control
/// points), basis function a of point q at `q · n_basis + a`.
#[derive(Clone, Debug, Default)]
pub struct ElementValues {
    n_basis: usize,
    n_points: usize,
    param: Vec<[f64; 2]>,
    x: Vec<[f64; 2]>,
    det_j: Vec<f64>,
    /// Gauss weight times |det J|.
    weight: Vec<f64>,
    r: Vec<f64>,
    /// ∂R/∂x and ∂R/∂y.
    grad: Vec<[f64; 2]>,
}

impl ElementValues {
    /// Buffers sized for the elements of `space`; [`Self::reinit`] grows
    /// them if it meets a larger element (another body's space).
    pub fn new(space: &Space) -> Self {
        let mut this = Self::default();
        this.reserve(space);
        this
    }

    fn reserve(&mut self, space: &Space) {
        let [p, q] = space.patch.degree();
        let nb = (p + 1) * (q + 1);
        let nq = space.quad_order * space.quad_order;
        if self.param.len() < nq {
            self.param.resize(nq, [0.0; 2]);
            self.x.resize(nq, [0.0; 2]);
            self.det_j.resize(nq, 0.0);
            self.weight.resize(nq, 0.0);
        }
        if self.r.len() < nq * nb {
            self.r.resize(nq * nb, 0.0);
            self.grad.resize(nq * nb, [0.0; 2]);
        }
        self.n_basis = nb;
        self.n_points = nq;
    }

    /// Evaluates element `e` of `space`; fails where the map folds, at the
    /// first such Gauss point (η outer, ξ inner), as [`Space::shape`] does.
    pub fn reinit(&mut self, space: &Space, e: &Element) -> Result<()> {
        self.reserve(space);
        let n = space.quad_order;
        let nb = self.n_basis;
        let (own_x, own_y);
        let tx = match space.tables[0].lookup(e.spans[0], e.range[0], n) {
            Some(t) => t,
            None => {
                own_x = SpanTables::single(&space.patch.knots[0], n, e.spans[0], e.range[0]);
                own_x.lookup(e.spans[0], e.range[0], n).expect("just built")
            }
        };
        let ty = match space.tables[1].lookup(e.spans[1], e.range[1], n) {
            Some(t) => t,
            None => {
                own_y = SpanTables::single(&space.patch.knots[1], n, e.spans[1], e.range[1]);
                own_y.lookup(e.spans[1], e.range[1], n).expect("just built")
            }
        };
        for (gy, &(eta, wy)) in ty.rule.iter().enumerate() {
            let ny = ty.rows(gy);
            for (gx, &(xi, wx)) in tx.rule.iter().enumerate() {
                let k = gx + gy * n;
                let r = &mut self.r[k * nb..(k + 1) * nb];
                let grad = &mut self.grad[k * nb..(k + 1) * nb];
                space
                    .patch
                    .tensor_basis_into(e.spans, tx.rows(gx), ny, r, grad);
                let (x, det_j) = space.physical(&e.cps, r, grad, xi, eta)?;
                self.param[k] = [xi, eta];
                self.x[k] = x;
                self.det_j[k] = det_j;
                self.weight[k] = wx * wy * det_j;
            }
        }
        Ok(())
    }

    /// Gauss points of the element.
    pub fn n_points(&self) -> usize {
        self.n_points
    }

    /// Basis functions not zero on the element.
    pub fn n_basis(&self) -> usize {
        self.n_basis
    }

    /// (ξ, η) of point `q`.
    pub fn param(&self, q: usize) -> [f64; 2] {
        self.param[q]
    }

    /// The physical point x(ξ, η) of point `q`.
    pub fn point(&self, q: usize) -> [f64; 2] {
        self.x[q]
    }

    /// |det J| at point `q`.
    pub fn det_j(&self, q: usize) -> f64 {
        self.det_j[q]
    }

    /// The Gauss weight of point `q` times |det J|.
    pub fn weight(&self, q: usize) -> f64 {
        self.weight[q]
    }

    /// R_a at point `q`, in the element's local order.
    pub fn values(&self, q: usize) -> &[f64] {
        &self.r[q * self.n_basis..(q + 1) * self.n_basis]
    }

    /// (∂R_a/∂x, ∂R_a/∂y) at point `q`, in the element's local order.
    pub fn grads(&self, q: usize) -> &[[f64; 2]] {
        &self.grad[q * self.n_basis..(q + 1) * self.n_basis]
    }

    /// Point `q` as an owned [`QuadPoint`].
    pub fn quad_point(&self, q: usize) -> QuadPoint {
        QuadPoint {
            param: self.param[q],
            weight: self.weight[q],
            shape: Shape {
                x: self.x[q],
                r: self.values(q).to_vec(),
                grad: self.grads(q).to_vec(),
                det_j: self.det_j[q],
            },
        }
    }
}
