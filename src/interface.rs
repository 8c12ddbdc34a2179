//! Matching interfaces between the patches of one body: which sides meet,
//! which control points they share, and the fold of a per-patch matrix
//! into the joined unknowns.
//!
//! Two sides match when they run between the same two end points (either
//! way round) with the same degree, the same knots along the side (after
//! refinement) and coincident control points with proportional weights:
//! then the two traces are one and the same NURBS curve with one and the
//! same basis, so identifying the control points gives a displacement that
//! is C⁰ across and a geometry that stays exact. Sides that meet end to
//! end without matching are refused; tying them weakly (Nitsche on the
//! interface) is not built.

use crate::error::{Error, Result};
use crate::nurbs::{NurbsPatch, Side};
use faer::sparse::{SparseColMat, Triplet};

/// Relative tolerance (of the body's extent) for coincident points.
const COINCIDE: f64 = 1e-9;

/// How two patch sides meet.
#[derive(Clone, Debug, PartialEq)]
pub enum Interface {
    /// They do not run between the same two points.
    Apart,
    /// They do, but not as one curve with one basis: why.
    NotMatching(String),
    /// They match: the pairs (control point of the first, of the second).
    Matching(Vec<(usize, usize)>),
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
        return Interface::Apart;
    };
    let (da, db) = (a.degree()[sa.along()], b.degree()[sb.along()]);
    if da != db {
        return Interface::NotMatching(format!("degree {da} against {db} along the side"));
    }
    let (ka, kb) = (unit_knots(a, sa, false), unit_knots(b, sb, reversed));
    if ka.len() != kb.len() || ka.iter().zip(&kb).any(|(x, y)| (x - y).abs() > 1e-12) {
        return Interface::NotMatching(format!(
            "{} against {} knots along the side",
            ka.len(),
            kb.len()
        ));
    }
    let order: Vec<usize> = if reversed {
        ib.iter().rev().copied().collect()
    } else {
        ib.clone()
    };
    let ratio = b.weights[order[0]] / a.weights[ia[0]];
    for (&ca, &cb) in ia.iter().zip(&order) {
        if !near(a.points[ca], b.points[cb], tol) {
            return Interface::NotMatching(format!(
                "control point {:?} against {:?}",
                a.points[ca], b.points[cb]
            ));
        }
        if (b.weights[cb] / a.weights[ca] - ratio).abs() > 1e-12 * ratio {
            return Interface::NotMatching("weights not proportional along the side".into());
        }
    }
    Interface::Matching(ia.into_iter().zip(order).collect())
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
