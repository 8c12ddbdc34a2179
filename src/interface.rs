//! Interfaces between the patches of one body: which sides meet, which
//! control points they share, how two non-matching sides are laid on each
//! other, and the fold of a per-patch matrix into the joined unknowns.
//!
//! Two sides match when they run between the same two end points (either
//! way round) with the same degree, the same knots along the side (after
//! refinement) and coincident control points with proportional weights:
//! then the two traces are one and the same NURBS curve with one and the
//! same basis, so identifying the control points gives a displacement that
//! is C⁰ across and a geometry that stays exact. Sides that are one curve
//! with different bases (other knots or degrees along the side, as two
//! refinements of one side give) do not match; they are tied weakly, by
//! Nitsche's method ([`crate::assembly::tie_stiffness`]), on the union of
//! their knot partitions ([`Tie::segments`]). For that the two parameters
//! must be one linear function of the other (refinement by knot insertion
//! or degree elevation keeps it so); sides that run between the same end
//! points as two other curves, or meet over only part of their length, are
//! refused.

use crate::error::{Error, Result};
use crate::nurbs::{NurbsCurve, NurbsPatch, Side};
use faer::sparse::{SparseColMat, Triplet};

/// Relative tolerance (of the body's extent) for coincident points.
const COINCIDE: f64 = 1e-9;

/// How two patch sides meet.
#[derive(Clone, Debug, PartialEq)]
pub enum Interface {
    /// They do not run between the same two points.
    Apart,
    /// They touch in a way that neither matching nor a tie can join: why.
    NotMatching(String),
    /// They match: the pairs (control point of the first, of the second).
    Matching(Vec<(usize, usize)>),
    /// They are one curve with two bases: tied by Nitsche's method; true
    /// when the second runs the other way.
    NonMatching { reversed: bool },
}

/// A non-matching interface of one body: side `sides[0]` of patch
/// `patches[0]` laid on side `sides[1]` of patch `patches[1]` (indices
/// into the bodies), the second run the other way when `reversed`. The
/// unit parameter s ∈ [0, 1] of the first side is the common parameter.
#[derive(Clone, Debug, PartialEq)]
pub struct Tie {
    pub patches: [usize; 2],
    pub sides: [Side; 2],
    pub reversed: bool,
}

impl Tie {
    /// The side parameter of patch k (0 or 1) at the common parameter s.
    pub fn param(&self, k: usize, patch: &NurbsPatch, s: f64) -> f64 {
        let kv = &patch.knots[self.sides[k].along()];
        let s = if k == 1 && self.reversed { 1.0 - s } else { s };
        kv.first() + (kv.last() - kv.first()) * s
    }

    /// The union of the two sides' knot partitions, in the common
    /// parameter: the segments [s₀, s₁] on each of which both traces are
    /// one polynomial (or rational) piece, so a Gauss rule per segment
    /// integrates products of the two exactly where they are polynomial.
    pub fn segments(&self, a: &NurbsPatch, b: &NurbsPatch) -> Vec<[f64; 2]> {
        let mut s = unit_knots(a, self.sides[0], false);
        s.extend(unit_knots(b, self.sides[1], self.reversed));
        s.sort_by(f64::total_cmp);
        s.dedup_by(|x, y| (*x - *y).abs() <= 1e-12);
        s.windows(2).map(|w| [w[0], w[1]]).collect()
    }
}

/// The largest distance between two control points' coordinates (the
/// scale of the tolerance).
pub fn extent(patch: &NurbsPatch) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in &patch.points {
        for c in 0..2 {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    (hi[0] - lo[0]).hypot(hi[1] - lo[1])
}

fn near(a: [f64; 2], b: [f64; 2], tol: f64) -> bool {
    (a[0] - b[0]).hypot(a[1] - b[1]) <= tol
}

/// The knots along `side`, mapped to [0, 1] (reversed: t ↦ 1 − t, in
/// increasing order).
fn unit_knots(patch: &NurbsPatch, side: Side, reversed: bool) -> Vec<f64> {
    let k = &patch.knots[side.along()];
    let (a, b) = (k.first(), k.last());
    let mut t: Vec<f64> = k.knots().iter().map(|v| (v - a) / (b - a)).collect();
    if reversed {
        t = t.iter().rev().map(|v| 1.0 - v).collect();
    }
    t
}

/// How side `sa` of `a` meets side `sb` of `b`; `size` scales the
/// tolerance of coincidence.
pub fn matching(a: &NurbsPatch, sa: Side, b: &NurbsPatch, sb: Side, size: f64) -> Interface {
    let tol = COINCIDE * size;
    let (ia, ib) = (a.side_indices(sa), b.side_indices(sb));
    let (a0, a1) = (a.points[ia[0]], a.points[ia[ia.len() - 1]]);
    let (b0, b1) = (b.points[ib[0]], b.points[ib[ib.len() - 1]]);
    if near(a0, a1, tol) || near(b0, b1, tol) {
        // a side collapsed to a point meets nothing
        return Interface::Apart;
    }
    let reversed = if near(a0, b0, tol) && near(a1, b1, tol) {
        false
    } else if near(a0, b1, tol) && near(a1, b0, tol) {
        true
    } else {
        return match partial_overlap(a, sa, b, sb, tol) {
            true => Interface::NotMatching(
                "the sides meet over only part of their length; split the longer one where \
                 the shorter ends"
                    .into(),
            ),
            false => Interface::Apart,
        };
    };
    if let Some(at) = off_curve(a, sa, b, sb, reversed, tol) {
        return Interface::NotMatching(format!(
            "the sides run between the same points but part at {at:?}: not one curve under a \
             linear map of their parameters"
        ));
    }
    let (da, db) = (a.degree()[sa.along()], b.degree()[sb.along()]);
    let (ka, kb) = (unit_knots(a, sa, false), unit_knots(b, sb, reversed));
    if da != db || ka.len() != kb.len() || ka.iter().zip(&kb).any(|(x, y)| (x - y).abs() > 1e-12) {
        return Interface::NonMatching { reversed };
    }
    let order: Vec<usize> = if reversed {
        ib.iter().rev().copied().collect()
    } else {
        ib.clone()
    };
    let ratio = b.weights[order[0]] / a.weights[ia[0]];
    for (&ca, &cb) in ia.iter().zip(&order) {
        // one curve with one knot vector: a differing control point or
        // weight is another rational basis of it, which a tie joins
        if !near(a.points[ca], b.points[cb], tol)
            || (b.weights[cb] / a.weights[ca] - ratio).abs() > 1e-12 * ratio
        {
            return Interface::NonMatching { reversed };
        }
    }
    Interface::Matching(ia.into_iter().zip(order).collect())
}

/// The first point of side `sa` (at the knots of both sides and between
/// them) that side `sb`, under the linear map of the unit parameters,
/// does not reproduce within `tol`; `None` when the two are one curve.
fn off_curve(
    a: &NurbsPatch,
    sa: Side,
    b: &NurbsPatch,
    sb: Side,
    reversed: bool,
    tol: f64,
) -> Option<[f64; 2]> {
    let tie = Tie {
        patches: [0, 1],
        sides: [sa, sb],
        reversed,
    };
    let (ca, cb) = (a.side_curve(sa), b.side_curve(sb));
    let mut s: Vec<f64> = Vec::new();
    for seg in tie.segments(a, b) {
        // three points a segment: a curve of degree ≤ 2 agreeing there
        // and at the ends is the same on the segment
        s.extend((0..4).map(|k| seg[0] + (seg[1] - seg[0]) * k as f64 / 4.0));
    }
    s.push(1.0);
    s.into_iter().find_map(|s| {
        let (x, y) = (ca.point(tie.param(0, a, s)), cb.point(tie.param(1, b, s)));
        (!near(x, y, tol)).then_some(x)
    })
}

/// The distance from `x` to `curve`: the nearest of a sampling refined by
/// a few projection steps (enough to tell on the curve from off it).
fn distance(curve: &NurbsCurve, x: [f64; 2]) -> f64 {
    let (lo, hi) = (curve.knots.first(), curve.knots.last());
    let n = 4 * curve.knots.spans().len();
    let d = |t: f64| {
        let p = curve.point(t);
        (p[0] - x[0]).hypot(p[1] - x[1])
    };
    let mut t = (0..=n)
        .map(|k| lo + (hi - lo) * k as f64 / n as f64)
        .min_by(|&s, &t| d(s).total_cmp(&d(t)))
        .unwrap_or(lo);
    for _ in 0..8 {
        let (p, dp) = curve.point_and_tangent(t);
        let len2 = dp[0] * dp[0] + dp[1] * dp[1];
        if len2 == 0.0 {
            break;
        }
        let step = ((x[0] - p[0]) * dp[0] + (x[1] - p[1]) * dp[1]) / len2;
        t = (t + step).clamp(lo, hi);
    }
    d(t)
}

/// True when an inner point of one side (the middle of one of its knot
/// spans) lies on the other: sides that do not share both ends but overlap
/// over a length, which neither sharing nor a tie joins (the rest of the
/// longer side would be a crack).
fn partial_overlap(a: &NurbsPatch, sa: Side, b: &NurbsPatch, sb: Side, tol: f64) -> bool {
    // a curve lies in the hull of its control points: sides whose boxes
    // are apart cannot overlap, and most pairs of a body end here
    let boxed = |p: &NurbsPatch, s: Side| {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for i in p.side_indices(s) {
            for c in 0..2 {
                lo[c] = lo[c].min(p.points[i][c]);
                hi[c] = hi[c].max(p.points[i][c]);
            }
        }
        (lo, hi)
    };
    let ((la, ha), (lb, hb)) = (boxed(a, sa), boxed(b, sb));
    if (0..2).any(|c| la[c] > hb[c] + tol || lb[c] > ha[c] + tol) {
        return false;
    }
    let on = |p: &NurbsPatch, sp: Side, q: &NurbsPatch, sq: Side| {
        let (cp, cq) = (p.side_curve(sp), q.side_curve(sq));
        cp.knots
            .spans()
            .iter()
            .any(|&(_, u0, u1)| distance(&cq, cp.point(0.5 * (u0 + u1))) <= tol)
    };
    on(a, sa, b, sb) || on(b, sb, a, sa)
}

/// Sums the matrix `k` over the split free DOFs of
/// [`crate::dofs::DofMap::unlinked`] into the joined ones (`into[i]` is the
/// joined DOF of split DOF i, `n` their number), with explicit zeros at
/// `couplings`, pairs of joined DOFs that only contact couples. O(nnz).
pub fn fold(
    k: &SparseColMat<usize, f64>,
    into: &[usize],
    n: usize,
    couplings: &[(usize, usize)],
) -> Result<SparseColMat<usize, f64>> {
    let s = k.symbolic();
    let (ptr, idx, val) = (s.col_ptr(), s.row_idx(), k.val());
    let mut t = Vec::with_capacity(val.len() + couplings.len());
    for j in 0..k.ncols() {
        for at in ptr[j]..ptr[j + 1] {
            t.push(Triplet::new(into[idx[at]], into[j], val[at]));
        }
    }
    t.extend(couplings.iter().map(|&(i, j)| Triplet::new(i, j, 0.0)));
    SparseColMat::try_new_from_triplets(n, n, &t)
        .map_err(|e| Error::out_of_memory("the joined stiffness", e))
}

/// Sums a vector over the split free DOFs into the joined ones.
pub fn fold_vec(v: &[f64], into: &[usize], n: usize) -> Vec<f64> {
    let mut out = vec![0.0; n];
    for (x, &i) in v.iter().zip(into) {
        out[i] += x;
    }
    out
}
