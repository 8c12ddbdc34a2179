//! The discrete space of one patch: elements (non-empty knot-span
//! products), quadrature, boundary elements, and shape functions mapped to
//! physical coordinates — Eq. (2), u(ξ,η) = Σ_A R_A(ξ,η) d_A.

mod tables;
mod values;

pub use values::ElementValues;

use crate::error::{Error, GeometryError, Result};
use crate::nurbs::{NurbsPatch, PatchBasis, Side};
use crate::quadrature;
use tables::SpanTables;

/// One element: the product of a non-empty ξ span and a non-empty η span.
#[derive(Clone, Debug)]
pub struct Element {
    /// Knot-span indices (as [`crate::nurbs::KnotVector::find_span`] returns).
    pub spans: [usize; 2],
    /// Parametric extent [ξ_a, ξ_b] and [η_a, η_b].
    pub range: [[f64; 2]; 2],
    /// Control points supported on the element, ξ index fastest.
    pub cps: Vec<usize>,
}

/// Shape functions at one point, in the element's local order.
#[derive(Clone, Debug)]
pub struct Shape {
    pub x: [f64; 2],
    pub r: Vec<f64>,
    /// ∂R/∂x and ∂R/∂y.
    pub grad: Vec<[f64; 2]>,
    /// |det J|: the area factor of the map (see [`Space::orientation`]).
    pub det_j: f64,
}

/// A quadrature point of an element, with its shape functions and the
/// weight already multiplied by det J. Element loops use
/// [`ElementValues`], which allocates nothing per point.
#[derive(Clone, Debug)]
pub struct QuadPoint {
    pub param: [f64; 2],
    pub weight: f64,
    pub shape: Shape,
}

/// An element side lying on a patch side.
#[derive(Clone, Debug)]
pub struct BoundaryElement {
    pub side: Side,
    /// Index into [`Space::elements`].
    pub element: usize,
    /// Extent of the side parameter on this element.
    pub range: [f64; 2],
    /// Physical length of the element side (the h of Eq. 11).
    pub length: f64,
}

/// The space spanned by the NURBS basis of one patch.
#[derive(Clone, Debug)]
pub struct Space {
    pub patch: NurbsPatch,
    pub elements: Vec<Element>,
    /// Gauss points per direction.
    pub quad_order: usize,
    /// Sign of det J over the patch (+1 or −1). A patch may be parameterised
    /// either way round (the quarter annulus, with ξ counter-clockwise along
    /// the arcs and η outward, has det J < 0); a fold shows as a sign change.
    orientation: f64,
    /// The 1D tables of the ξ and η spans at the Gauss points.
    tables: [SpanTables; 2],
}

impl Space {
    /// Builds the elements; `quad_order` defaults to p + 1 Gauss points per
    /// direction (exact for the polynomial part of the stiffness integrand
    /// on affine maps, and the usual choice for NURBS).
    pub fn new(patch: NurbsPatch, quad_order: Option<usize>) -> Result<Self> {
        let pmax = patch.degree()[0].max(patch.degree()[1]);
        let quad_order = quad_order.unwrap_or(pmax + 1);
        if quad_order == 0 || quad_order > 30 {
            return Err(Error::invalid(
                "quadrature_order",
                quad_order,
                "must lie in 1..=30",
            ));
        }
        let [p, q] = patch.degree();
        let n0 = patch.n()[0];
        let mut elements = Vec::new();
        for (sy, y0, y1) in patch.knots[1].spans() {
            for (sx, x0, x1) in patch.knots[0].spans() {
                let mut cps = Vec::with_capacity((p + 1) * (q + 1));
                for j in sy - q..=sy {
                    for i in sx - p..=sx {
                        cps.push(i + j * n0);
                    }
                }
                elements.push(Element {
                    spans: [sx, sy],
                    range: [[x0, x1], [y0, y1]],
                    cps,
                });
            }
        }
        let tables = [0, 1].map(|d| SpanTables::new(&patch.knots[d], quad_order));
        let mut space = Self {
            patch,
            elements,
            quad_order,
            orientation: 1.0,
            tables,
        };
        // The orientation is the sign of det J at the centre of the first element.
        let e = &space.elements[0];
        let c = [
            0.5 * (e.range[0][0] + e.range[0][1]),
            0.5 * (e.range[1][0] + e.range[1][1]),
        ];
        let j = space
            .patch
            .jacobian_of(&space.patch.basis_in_spans(e.spans, c[0], c[1]));
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        if !(det.is_finite() && det != 0.0) {
            return Err(GeometryError::DegenerateMap {
                xi: c[0],
                eta: c[1],
                det_j: det,
            }
            .into());
        }
        space.orientation = det.signum();
        Ok(space)
    }

    /// +1 if the parameterisation preserves orientation (det J > 0), −1 if
    /// it reverses it. Integrals use |det J| either way.
    pub fn orientation(&self) -> f64 {
        self.orientation
    }

    pub fn n_cp(&self) -> usize {
        self.patch.points.len()
    }

    /// Number of elements per direction.
    pub fn n_elements(&self) -> [usize; 2] {
        [
            self.patch.knots[0].spans().len(),
            self.patch.knots[1].spans().len(),
        ]
    }

    /// Shape functions of element `e` at (ξ, η); fails where the map folds
    /// (det J vanishes or has the sign opposite to the patch orientation).
    /// `det_j` is |det J|, the area factor.
    pub fn shape(&self, e: &Element, xi: f64, eta: f64) -> Result<Shape> {
        self.shape_of(self.patch.basis_in_spans(e.spans, xi, eta), xi, eta)
    }

    /// Maps a parametric basis at (ξ, η) to physical shape functions.
    fn shape_of(&self, b: PatchBasis, xi: f64, eta: f64) -> Result<Shape> {
        let PatchBasis { indices, r, dr } = b;
        // the parametric derivatives become the physical gradients in place:
        // one allocation less per point
        let mut grad = dr;
        let (x, det_j) = self.physical(&indices, &r, &mut grad, xi, eta)?;
        Ok(Shape { x, r, grad, det_j })
    }

    /// The physical point and |det J| of the basis `r`, `grad` (R_a and
    /// ∂R_a/∂(ξ, η) of control points `indices`), turning `grad` into
    /// ∂R_a/∂(x, y) in place; fails where the map folds.
    fn physical(
        &self,
        indices: &[usize],
        r: &[f64],
        grad: &mut [[f64; 2]],
        xi: f64,
        eta: f64,
    ) -> Result<([f64; 2], f64)> {
        let points = &self.patch.points;
        // J and x in the operation order of `NurbsPatch::jacobian_of` and `map`
        let mut j = [[0.0; 2]; 2];
        for (k, &a) in indices.iter().enumerate() {
            for r in 0..2 {
                for c in 0..2 {
                    j[r][c] += points[a][r] * grad[k][c];
                }
            }
        }
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        if (det * self.orientation).is_nan() || det * self.orientation <= 0.0 || !det.is_finite() {
            return Err(GeometryError::NotInvertible {
                xi,
                eta,
                det_j: det,
                orientation: self.orientation,
            }
            .into());
        }
        let mut x = [0.0; 2];
        for (k, &a) in indices.iter().enumerate() {
            x[0] += r[k] * points[a][0];
            x[1] += r[k] * points[a][1];
        }
        for d in grad.iter_mut() {
            *d = [
                (j[1][1] * d[0] - j[1][0] * d[1]) / det,
                (-j[0][1] * d[0] + j[0][0] * d[1]) / det,
            ];
        }
        Ok((x, det.abs()))
    }

    /// Eq. (2): the displacement u(ξ, η) = Σ_A R_A(ξ, η) d_A at a point of
    /// the parameter domain, where `d(A)` is the displacement of control
    /// point A. For body `b` of a solved problem with full displacement
    /// vector `full`, that is `|a| map.cp_displacement(&full, b, a)`.
    ///
    /// ```
    /// # use iga_contact::{geometry, space::Space};
    /// let space = Space::new(geometry::rectangle(0.0, 0.0, 2.0, 1.0)?, None)?;
    /// // d_A = (0.01 x_A, 0): a uniform stretch, reproduced exactly.
    /// let d = |a: usize| [0.01 * space.patch.points[a][0], 0.0];
    /// let u = space.displacement(0.25, 0.5, d)?;
    /// assert!((u[0] - 0.005).abs() < 1e-15 && u[1] == 0.0);
    /// # Ok::<(), iga_contact::Error>(())
    /// ```
    pub fn displacement(
        &self,
        xi: f64,
        eta: f64,
        d: impl Fn(usize) -> [f64; 2],
    ) -> Result<[f64; 2]> {
        for (field, v, k) in [
            ("ξ", xi, &self.patch.knots[0]),
            ("η", eta, &self.patch.knots[1]),
        ] {
            if !(v >= k.first() && v <= k.last()) {
                return Err(Error::invalid(
                    field,
                    v,
                    format!(
                        "must lie in the parameter range [{}, {}]",
                        k.first(),
                        k.last()
                    ),
                ));
            }
        }
        let b = self.patch.basis(xi, eta);
        Ok(b.indices.iter().zip(&b.r).fold([0.0; 2], |u, (&a, &r)| {
            let da = d(a);
            [u[0] + r * da[0], u[1] + r * da[1]]
        }))
    }

    /// Gauss points of element `e`, each owning its shape functions. For
    /// loops over elements, [`ElementValues`] gives the same values without
    /// an allocation per point.
    pub fn quadrature(&self, e: &Element) -> Result<Vec<QuadPoint>> {
        let mut values = ElementValues::new(self);
        values.reinit(self, e)?;
        Ok((0..values.n_points())
            .map(|q| values.quad_point(q))
            .collect())
    }

    /// The element that holds (ξ, η).
    pub fn locate(&self, xi: f64, eta: f64) -> usize {
        let sx = self.patch.knots[0].find_span(xi);
        let sy = self.patch.knots[1].find_span(eta);
        let nx = self.n_elements()[0];
        let ix = self.patch.knots[0]
            .spans()
            .iter()
            .position(|s| s.0 == sx)
            .unwrap_or(0);
        let iy = self.patch.knots[1]
            .spans()
            .iter()
            .position(|s| s.0 == sy)
            .unwrap_or(0);
        ix + iy * nx
    }

    /// The element sides along `side`, in the order of the side parameter.
    pub fn boundary(&self, side: Side) -> Vec<BoundaryElement> {
        let along = side.along();
        let knots = &self.patch.knots;
        let fixed = if side.is_max() {
            knots[1 - along].last()
        } else {
            knots[1 - along].first()
        };
        let mut out = Vec::new();
        for (_, a, b) in knots[along].spans() {
            let mid = 0.5 * (a + b);
            let p = self.patch.side_point(side, mid);
            let element = self.locate(p[0], p[1]);
            let r = self.elements[element].range[1 - along];
            debug_assert!(r[0] <= fixed && fixed <= r[1]);
            let length = quadrature::on_interval(self.quad_order.max(4), a, b)
                .iter()
                .map(|&(t, w)| {
                    let q = self.patch.side_point(side, t);
                    let j = self.patch.jacobian(q[0], q[1]);
                    w * j[0][along].hypot(j[1][along])
                })
                .sum();
            out.push(BoundaryElement {
                side,
                element,
                range: [a, b],
                length,
            });
        }
        out
    }

    /// Shape functions and side frame (outward normal, |∂x/∂t|) at side
    /// parameter `t` of a boundary element.
    pub fn side_shape(&self, be: &BoundaryElement, t: f64) -> Result<(Shape, [f64; 2], f64)> {
        let e = &self.elements[be.element];
        let q = self.patch.side_point(be.side, t);
        let b = self.patch.basis_in_spans(e.spans, q[0], q[1]);
        let (n, len) = self.patch.side_frame(be.side, &b);
        let shape = self.shape(e, q[0], q[1])?;
        Ok((shape, n, len))
    }
}
