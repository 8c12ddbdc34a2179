//! Tensor-product NURBS patches: Eq. (1), x(ξ,η) = Σ_A R_A(ξ,η) P_A.

use super::curve::{check_net, NurbsCurve};
use super::knots::KnotVector;
use crate::error::Result;
use serde::{Deserialize, Serialize};

/// A side of the parameter square.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Side {
    /// ξ = 0, parameterised by η.
    XiMin,
    /// ξ = 1, parameterised by η.
    XiMax,
    /// η = 0, parameterised by ξ.
    EtaMin,
    /// η = 1, parameterised by ξ.
    EtaMax,
}

impl Side {
    pub const ALL: [Side; 4] = [Side::XiMin, Side::XiMax, Side::EtaMin, Side::EtaMax];

    /// The parametric direction that runs along the side (0 = ξ, 1 = η).
    pub fn along(self) -> usize {
        match self {
            Side::XiMin | Side::XiMax => 1,
            Side::EtaMin | Side::EtaMax => 0,
        }
    }

    /// True for the sides at the upper end of their fixed parameter.
    pub fn is_max(self) -> bool {
        matches!(self, Side::XiMax | Side::EtaMax)
    }

    pub fn name(self) -> &'static str {
        match self {
            Side::XiMin => "xi_min",
            Side::XiMax => "xi_max",
            Side::EtaMin => "eta_min",
            Side::EtaMax => "eta_max",
        }
    }
}

/// A 2D NURBS patch. Control point (i, j) is stored at `i + j * n_xi`.
#[derive(Clone, Debug)]
pub struct NurbsPatch {
    pub knots: [KnotVector; 2],
    pub points: Vec<[f64; 2]>,
    pub weights: Vec<f64>,
}

/// The non-zero rational basis functions at one parametric point, with
/// their parametric derivatives; `indices[k]` is the control point of `r[k]`.
#[derive(Clone, Debug)]
pub struct PatchBasis {
    pub indices: Vec<usize>,
    pub r: Vec<f64>,
    pub dr: Vec<[f64; 2]>,
}

impl NurbsPatch {
    pub fn new(knots: [KnotVector; 2], points: Vec<[f64; 2]>, weights: Vec<f64>) -> Result<Self> {
        check_net(
            knots[0].n_basis() * knots[1].n_basis(),
            &points,
            &weights,
            "patch",
        )?;
        Ok(Self {
            knots,
            points,
            weights,
        })
    }

    pub fn n(&self) -> [usize; 2] {
        [self.knots[0].n_basis(), self.knots[1].n_basis()]
    }

    pub fn degree(&self) -> [usize; 2] {
        [self.knots[0].degree(), self.knots[1].degree()]
    }

    pub fn index(&self, i: usize, j: usize) -> usize {
        i + j * self.knots[0].n_basis()
    }

    /// Basis at (ξ, η), in the spans that hold the point.
    pub fn basis(&self, xi: f64, eta: f64) -> PatchBasis {
        let spans = [self.knots[0].find_span(xi), self.knots[1].find_span(eta)];
        self.basis_in_spans(spans, xi, eta)
    }

    /// Basis at (ξ, η) computed in the given knot spans.
    pub fn basis_in_spans(&self, spans: [usize; 2], xi: f64, eta: f64) -> PatchBasis {
        let nx = self.knots[0].basis_ders(spans[0], xi, 1);
        let ny = self.knots[1].basis_ders(spans[1], eta, 1);
        self.tensor_basis(spans, &nx, &ny)
    }

    /// Combines 1D B-spline values and derivatives (`[value, d/du]` per
    /// direction) into the rational 2D basis. Split out so that a space can
    /// reuse cached 1D tables.
    pub fn tensor_basis(&self, spans: [usize; 2], nx: &[Vec<f64>], ny: &[Vec<f64>]) -> PatchBasis {
        let [p, q] = self.degree();
        let n0 = self.knots[0].n_basis();
        let m = (p + 1) * (q + 1);
        let mut indices = Vec::with_capacity(m);
        for b in 0..=q {
            for a in 0..=p {
                indices.push(spans[0] - p + a + (spans[1] - q + b) * n0);
            }
        }
        let mut r = vec![0.0; m];
        let mut dr = vec![[0.0; 2]; m];
        self.tensor_basis_into(spans, [&nx[0], &nx[1]], [&ny[0], &ny[1]], &mut r, &mut dr);
        PatchBasis { indices, r, dr }
    }

    /// [`Self::tensor_basis`] into caller-owned buffers of at least
    /// (p + 1)(q + 1) entries, ξ index fastest, so that element loops
    /// allocate nothing per point.
    pub fn tensor_basis_into(
        &self,
        spans: [usize; 2],
        nx: [&[f64]; 2],
        ny: [&[f64]; 2],
        r: &mut [f64],
        dr: &mut [[f64; 2]],
    ) {
        let [p, q] = self.degree();
        let n0 = self.knots[0].n_basis();
        let m = (p + 1) * (q + 1);
        let (mut w, mut wx, mut wy) = (0.0, 0.0, 0.0);
        let mut k = 0;
        for b in 0..=q {
            let j = spans[1] - q + b;
            for a in 0..=p {
                let i = spans[0] - p + a;
                let wi = self.weights[i + j * n0];
                let v = nx[0][a] * ny[0][b] * wi;
                let vx = nx[1][a] * ny[0][b] * wi;
                let vy = nx[0][a] * ny[1][b] * wi;
                w += v;
                wx += vx;
                wy += vy;
                r[k] = v;
                dr[k] = [vx, vy];
                k += 1;
            }
        }
        for k in 0..m {
            let v = r[k];
            dr[k] = [
                (dr[k][0] * w - v * wx) / (w * w),
                (dr[k][1] * w - v * wy) / (w * w),
            ];
            r[k] = v / w;
        }
    }

    /// The geometry map of Eq. (1): the physical point
    /// x(ξ, η) = Σ_A R_A(ξ, η) P_A of the parameters (ξ, η), with the
    /// rational basis R_A of [`Self::basis`] and the control points P_A.
    /// (ξ, η) must lie in the knot vectors' ranges.
    pub fn point(&self, xi: f64, eta: f64) -> [f64; 2] {
        let b = self.basis(xi, eta);
        self.map(&b)
    }

    /// x = Σ R_A P_A for a precomputed basis.
    pub fn map(&self, b: &PatchBasis) -> [f64; 2] {
        let mut x = [0.0; 2];
        for (k, &a) in b.indices.iter().enumerate() {
            x[0] += b.r[k] * self.points[a][0];
            x[1] += b.r[k] * self.points[a][1];
        }
        x
    }

    /// Jacobian `J[r][c]` = ∂x_r/∂ξ_c for a precomputed basis.
    pub fn jacobian_of(&self, b: &PatchBasis) -> [[f64; 2]; 2] {
        let mut j = [[0.0; 2]; 2];
        for (k, &a) in b.indices.iter().enumerate() {
            for r in 0..2 {
                for c in 0..2 {
                    j[r][c] += self.points[a][r] * b.dr[k][c];
                }
            }
        }
        j
    }

    pub fn jacobian(&self, xi: f64, eta: f64) -> [[f64; 2]; 2] {
        self.jacobian_of(&self.basis(xi, eta))
    }

    /// Parametric point on `side` at side parameter `t`.
    pub fn side_point(&self, side: Side, t: f64) -> [f64; 2] {
        let lo = |d: usize| self.knots[d].first();
        let hi = |d: usize| self.knots[d].last();
        match side {
            Side::XiMin => [lo(0), t],
            Side::XiMax => [hi(0), t],
            Side::EtaMin => [t, lo(1)],
            Side::EtaMax => [t, hi(1)],
        }
    }

    /// Unit outward normal and the tangent length |∂x/∂t| on `side` for a
    /// basis evaluated at a side point. The normal is the tangent turned by
    /// 90°, with the sign fixed by the inward parametric direction so that
    /// it does not depend on the patch orientation.
    pub fn side_frame(&self, side: Side, b: &PatchBasis) -> ([f64; 2], f64) {
        let j = self.jacobian_of(b);
        let along = side.along();
        let across = 1 - along;
        let t = [j[0][along], j[1][along]];
        let len = t[0].hypot(t[1]);
        let mut n = [t[1] / len, -t[0] / len];
        // inward direction: +∂x/∂(across) on a min side, − on a max side
        let s = if side.is_max() { -1.0 } else { 1.0 };
        let inward = [s * j[0][across], s * j[1][across]];
        if n[0] * inward[0] + n[1] * inward[1] > 0.0 {
            n = [-n[0], -n[1]];
        }
        (n, len)
    }

    /// Indices of the control points on `side`, in the order of the side parameter.
    pub fn side_indices(&self, side: Side) -> Vec<usize> {
        let [n0, n1] = self.n();
        match side {
            Side::XiMin => (0..n1).map(|j| self.index(0, j)).collect(),
            Side::XiMax => (0..n1).map(|j| self.index(n0 - 1, j)).collect(),
            Side::EtaMin => (0..n0).map(|i| self.index(i, 0)).collect(),
            Side::EtaMax => (0..n0).map(|i| self.index(i, n1 - 1)).collect(),
        }
    }

    /// The boundary curve of `side` (exact: an open knot vector interpolates
    /// its end row of control points).
    pub fn side_curve(&self, side: Side) -> NurbsCurve {
        let idx = self.side_indices(side);
        NurbsCurve {
            knots: self.knots[side.along()].clone(),
            points: idx.iter().map(|&a| self.points[a]).collect(),
            weights: idx.iter().map(|&a| self.weights[a]).collect(),
        }
    }

    /// `n + 1` points of the physical curve ξ = `c` (dir = 0) or η = `c`
    /// (dir = 1), for drawing knot lines and outlines.
    pub fn iso_curve(&self, dir: usize, c: f64, n: usize) -> Vec<[f64; 2]> {
        let k = &self.knots[1 - dir];
        let (a, b) = (k.first(), k.last());
        (0..=n)
            .map(|i| {
                let t = a + (b - a) * i as f64 / n as f64;
                if dir == 0 {
                    self.point(c, t)
                } else {
                    self.point(t, c)
                }
            })
            .collect()
    }

    /// The closed boundary of the patch, counter-clockwise in parameter
    /// space, with `n` segments per side.
    pub fn outline(&self, n: usize) -> Vec<[f64; 2]> {
        let (k0, k1) = (&self.knots[0], &self.knots[1]);
        let mut o = self.iso_curve(1, k1.first(), n);
        o.extend(self.iso_curve(0, k0.last(), n));
        let mut top = self.iso_curve(1, k1.last(), n);
        top.reverse();
        o.extend(top);
        let mut left = self.iso_curve(0, k0.first(), n);
        left.reverse();
        o.extend(left);
        o
    }

    /// Affine map of the control net (rigid motions, scaling).
    pub fn transformed(&self, f: impl Fn([f64; 2]) -> [f64; 2]) -> Self {
        let mut out = self.clone();
        for p in out.points.iter_mut() {
            *p = f(*p);
        }
        out
    }
}
