//! The stiffness assembled straight into compressed columns: the pattern from
//! control-point connectivity, then the elements integrated in parallel bands
//! of columns, each band written by one task.

use super::element::element_integrals;
use crate::dofs::{Body, DofMap};
use crate::error::Result;
use crate::material::Formulation;
use crate::pressure::SplinePressure;
use crate::space::ElementValues;
use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use rayon::prelude::*;

/// For every basis function of a knot vector, the first and last basis
/// function it shares a span with — or, with `reach` = r > 0, a span
/// within r spans of one of its own (the mixed formulation couples two
/// functions when both meet the support of one pressure function, whose
/// support is p spans wide: r = p − 1).
fn coupled_range(knots: &crate::nurbs::KnotVector, reach: usize) -> Vec<(usize, usize)> {
    let p = knots.degree();
    let spans: Vec<usize> = knots.spans().iter().map(|s| s.0).collect();
    let mut own = vec![(usize::MAX, 0usize); knots.n_basis()];
    for (k, &s) in spans.iter().enumerate() {
        for r in &mut own[s - p..=s] {
            r.0 = r.0.min(k);
            r.1 = r.1.max(k);
        }
    }
    own.iter()
        .map(|&(lo, hi)| {
            let (lo, hi) = (lo.saturating_sub(reach), (hi + reach).min(spans.len() - 1));
            (spans[lo] - p, spans[hi])
        })
        .collect()
}

/// The number of free DOFs with a global index below g, for every g.
fn free_before(map: &DofMap) -> Vec<usize> {
    let mut out = Vec::with_capacity(map.n_total() + 1);
    let mut k = 0;
    for g in 0..map.n_total() {
        out.push(k);
        if map.free(g).is_some() {
            k += 1;
        }
    }
    out.push(k);
    out
}

/// Splits `v` at the increasing positions `at` (first 0, last `v.len()`).
fn split_at_all<'a, T>(mut v: &'a mut [T], at: &[usize]) -> Vec<&'a mut [T]> {
    let mut out = Vec::with_capacity(at.len().saturating_sub(1));
    for w in at.windows(2) {
        let (head, tail) = v.split_at_mut(w[1] - w[0]);
        out.push(head);
        v = tail;
    }
    out
}

/// Column chunks per body for the parallel passes: rows of control points
/// (η index) [k0, k1), with the free columns they own.
struct Chunk {
    body: usize,
    rows: [usize; 2],
    cols: [usize; 2],
}

fn chunks(bodies: &[Body], map: &DofMap, before: &[usize]) -> Vec<Chunk> {
    let threads = rayon::current_num_threads().max(1);
    let mut out = Vec::new();
    for (b, body) in bodies.iter().enumerate() {
        let [n0, n1] = body.space.patch.n();
        let q = body.space.patch.degree()[1];
        // a few bands per thread balance the load; an element is integrated
        // by every band it touches, so bands much taller than the q + 1
        // rows of an element keep that repetition small
        let height = n1.div_ceil(4 * threads).max(4 * (q + 1));
        let mut k0 = 0;
        while k0 < n1 {
            let k1 = (k0 + height).min(n1);
            let col = |k: usize| {
                if k == n1 {
                    before[map.global(b, 0, 0) + 2 * n0 * n1]
                } else {
                    before[map.global(b, k * n0, 0)]
                }
            };
            out.push(Chunk {
                body: b,
                rows: [k0, k1],
                cols: [col(k0), col(k1)],
            });
            k0 = k1;
        }
    }
    out
}

/// The bulk operator of all bodies over the free DOFs: see
/// [`stiffness_matrix`].
pub struct Bulk {
    /// The stiffness, compressed by columns.
    pub k: SparseColMat<usize, f64>,
    /// K_fc ū, the columns of the prescribed DOFs times their values.
    pub lift: Vec<f64>,
    /// The load of the body forces.
    pub body_load: Vec<f64>,
}

/// The stiffness of all bodies, assembled straight into compressed
/// columns over the free DOFs, the lift K_fc ū, and the load of the
/// constant body forces `forces` (one per body; the integrals share the
/// stiffness's quadrature).
///
/// The pattern comes from control-point connectivity: in a tensor-product
/// patch, control points (i, k) and (i', k') share an element exactly when
/// i, i' share a span of ξ and k, k' one of η, so a column's rows are a
/// product of two index ranges, known before any element is integrated.
/// `couplings` adds (row, column) pairs of free DOFs that no element
/// joins (contact between bodies), with zero values. Elements are then
/// integrated in parallel and their values added in place: the columns are
/// split into bands of control-point rows, each owned by one task, which
/// integrates every element touching its band (elements on a band's edge
/// are integrated by both neighbours) and writes only its own columns.
pub fn stiffness_matrix(
    bodies: &[Body],
    map: &DofMap,
    couplings: &[(usize, usize)],
    forces: &[[f64; 2]],
) -> Result<Bulk> {
    let n = map.n_free();
    let before = free_before(map);
    // extra couplings by column, sorted, without duplicates
    let mut extra: Vec<(usize, usize)> = couplings.iter().map(|&(i, j)| (j, i)).collect();
    extra.sort_unstable();
    extra.dedup();
    let mut extra_ptr = vec![0usize; n + 1];
    for &(j, _) in &extra {
        extra_ptr[j + 1] += 1;
    }
    for j in 0..n {
        extra_ptr[j + 1] += extra_ptr[j];
    }
    // the global DOF of every free column
    let mut global_of = vec![0usize; n];
    for g in 0..map.n_total() {
        if let Some(i) = map.free(g) {
            global_of[i] = g;
        }
    }
    let ranges: Vec<[Vec<(usize, usize)>; 2]> = bodies
        .iter()
        .map(|b| {
            let reach = |d: usize| match b.formulation {
                Formulation::Mixed => b.space.patch.knots[d].degree().saturating_sub(1),
                _ => 0,
            };
            [
                coupled_range(&b.space.patch.knots[0], reach(0)),
                coupled_range(&b.space.patch.knots[1], reach(1)),
            ]
        })
        .collect();
    let chunks = chunks(bodies, map, &before);
    // rows of column j: the free DOFs of the coupled control points,
    // merged with the extra couplings (both sorted)
    let column = |b: usize, j: usize, emit: &mut dyn FnMut(usize)| {
        let g = global_of[j];
        let n0 = bodies[b].space.patch.n()[0];
        let cp = (g - map.global(b, 0, 0)) / 2;
        let (ri, rk) = (ranges[b][0][cp % n0], ranges[b][1][cp / n0]);
        let mut ex = extra[extra_ptr[j]..extra_ptr[j + 1]]
            .iter()
            .map(|e| e.1)
            .peekable();
        let mut push = |i: usize, emit: &mut dyn FnMut(usize)| {
            while let Some(&e) = ex.peek() {
                if e < i {
                    emit(e);
                    ex.next();
                } else {
                    if e == i {
                        ex.next();
                    }
                    break;
                }
            }
            emit(i);
        };
        for k in rk.0..=rk.1 {
            for i in ri.0..=ri.1 {
                for c in 0..2 {
                    if let Some(f) = map.free(map.global(b, i + k * n0, c)) {
                        push(f, &mut *emit);
                    }
                }
            }
        }
        for e in ex {
            emit(e);
        }
    };
    let mut counts = vec![0usize; n];
    chunks
        .par_iter()
        .zip(split_at_all(&mut counts, &chunk_bounds(&chunks, n)).into_par_iter())
        .for_each(|(ch, cnt)| {
            for (j, c) in (ch.cols[0]..ch.cols[1]).zip(cnt.iter_mut()) {
                column(ch.body, j, &mut |_| *c += 1);
            }
        });
    let mut col_ptr = vec![0usize; n + 1];
    for j in 0..n {
        col_ptr[j + 1] = col_ptr[j] + counts[j];
    }
    drop(counts);
    let nnz = col_ptr[n];
    let mut row_idx = vec![0usize; nnz];
    let bounds: Vec<usize> = chunk_bounds(&chunks, n)
        .iter()
        .map(|&j| col_ptr[j])
        .collect();
    chunks
        .par_iter()
        .zip(split_at_all(&mut row_idx, &bounds).into_par_iter())
        .for_each(|(ch, rows)| {
            let mut at = 0;
            for j in ch.cols[0]..ch.cols[1] {
                column(ch.body, j, &mut |i| {
                    rows[at] = i;
                    at += 1;
                });
            }
        });
    // values, in place
    let mut val = vec![0.0; nnz];
    let mut lift = vec![0.0; n];
    let mut body_load = vec![0.0; n];
    let lifts = split_at_all(&mut lift, &chunk_bounds(&chunks, n));
    let body_loads = split_at_all(&mut body_load, &chunk_bounds(&chunks, n));
    let vals = split_at_all(&mut val, &bounds);
    let (col_ptr_ref, row_idx_ref) = (&col_ptr, &row_idx);
    // the pressure space of each mixed body, built once; its volumetric
    // terms κ ĝ_i ĝ_iᵀ / m̂_i are rank one and formed where they are added
    let pressures: Vec<Option<SplinePressure>> = bodies
        .iter()
        .map(|b| match b.formulation {
            Formulation::Mixed => SplinePressure::new(b).map(Some),
            _ => Ok(None),
        })
        .collect::<Result<_>>()?;
    let pressures = &pressures;
    chunks
        .par_iter()
        .zip(
            vals.into_par_iter()
                .zip(lifts.into_par_iter().zip(body_loads)),
        )
        .map(|(ch, (vals, (lift, body_load)))| -> Result<()> {
            let body = &bodies[ch.body];
            let force = forces.get(ch.body).copied().filter(|f| *f != [0.0, 0.0]);
            let q = body.space.patch.degree()[1];
            let owned = OwnedColumns {
                cols: ch.cols,
                col_ptr: col_ptr_ref,
                row_idx: row_idx_ref,
            };
            let mut values = ElementValues::new(&body.space);
            for (e, el) in body.space.elements.iter().enumerate() {
                let sy = el.spans[1];
                if sy < ch.rows[0] || sy - q >= ch.rows[1] {
                    continue;
                }
                let (ke, fe) = element_integrals(&mut values, body, e, force)?;
                let dofs = map.element_dofs(ch.body, &el.cps);
                let free: Vec<Option<usize>> = dofs.iter().map(|&g| map.free(g)).collect();
                owned.add(map, &dofs, &free, |a, b| ke[(a, b)], vals, lift);
                if force.is_some() {
                    for (a, fa) in free.iter().enumerate() {
                        if let Some(i) = owned.column(fa) {
                            body_load[i - ch.cols[0]] += fe[a];
                        }
                    }
                }
            }
            // the mixed formulation's volumetric terms, one per pressure
            // function, into the columns this task owns
            if let Some(sp) = &pressures[ch.body] {
                let kappa = body.material.bulk_modulus();
                for i in 0..sp.len() {
                    let (g, m) = (sp.div(i), sp.mass(i));
                    let dofs: Vec<usize> = g
                        .iter()
                        .map(|e| map.global(ch.body, e.0 / 2, e.0 % 2))
                        .collect();
                    let free: Vec<Option<usize>> = dofs.iter().map(|&d| map.free(d)).collect();
                    if free.iter().any(|f| owned.column(f).is_some()) {
                        let k = |a: usize, b: usize| kappa * g[a].1 * g[b].1 / m;
                        owned.add(map, &dofs, &free, k, vals, lift);
                    }
                }
            }
            Ok(())
        })
        .collect::<Result<Vec<()>>>()?;
    let symbolic = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
    Ok(Bulk {
        k: SparseColMat::new(symbolic, val),
        lift,
        body_load,
    })
}

/// The columns [cols₀, cols₁) of the compressed matrix that one task owns,
/// with the pattern of the whole matrix.
struct OwnedColumns<'a> {
    cols: [usize; 2],
    col_ptr: &'a [usize],
    row_idx: &'a [usize],
}

impl OwnedColumns<'_> {
    /// The free index `f` if this task owns it.
    fn column(&self, f: &Option<usize>) -> Option<usize> {
        f.filter(|&j| j >= self.cols[0] && j < self.cols[1])
    }

    /// Adds the local matrix `k(a, b)` over the global DOFs `dofs` (free indices
    /// `free`): its owned columns into `vals` (the values of the owned
    /// columns), and for its owned rows the prescribed columns times their
    /// values into `lift` (indexed from cols₀). The free rows of `dofs`
    /// must be increasing, like a column's rows, so one pass finds them.
    fn add(
        &self,
        map: &DofMap,
        dofs: &[usize],
        free: &[Option<usize>],
        k: impl Fn(usize, usize) -> f64,
        vals: &mut [f64],
        lift: &mut [f64],
    ) {
        let base = self.col_ptr[self.cols[0]];
        for (bl, fb) in free.iter().enumerate() {
            let Some(j) = self.column(fb) else { continue };
            let rows = &self.row_idx[self.col_ptr[j]..self.col_ptr[j + 1]];
            let mut at = 0;
            for (a, fa) in free.iter().enumerate() {
                let Some(i) = *fa else { continue };
                while rows[at] < i {
                    at += 1;
                }
                vals[self.col_ptr[j] - base + at] += k(a, bl);
            }
        }
        for (a, fa) in free.iter().enumerate() {
            let Some(i) = self.column(fa) else { continue };
            for (bl, fb) in free.iter().enumerate() {
                if fb.is_none() {
                    lift[i - self.cols[0]] += k(a, bl) * map.prescribed(dofs[bl]);
                }
            }
        }
    }
}

/// The free-column boundaries of the chunks: 0, …, n.
fn chunk_bounds(chunks: &[Chunk], n: usize) -> Vec<usize> {
    let mut b: Vec<usize> = chunks.iter().map(|c| c.cols[0]).collect();
    b.push(n);
    b
}
