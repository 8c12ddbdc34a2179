//! Factorise once, condense onto the contact layer.
//!
//! Every contact term of every kernel (17)–(18), for every θ and every
//! active set, lives on the DOFs L that some contact point's functionals
//! reach (the slave boundary elements, plus the master trace). So with
//!
//!   A₀ = K + Σ_q w γ jn jnᵀ   (over every potential contact point),
//!
//! symmetric positive definite whenever contact over the whole boundary
//! holds the bodies, every kernel is A₀ plus a matrix on L × L.
//! [`Condensation`] factorises A₀ once by sparse Cholesky, with L ordered
//! last and the interior I by AMD on the graph of A₀ with L made a clique
//! (`layer_last_order`). Then the trailing ℓ × ℓ block of the factor
//! gives the Schur complement
//!
//!   S₀ = A_LL − A_LI A_II⁻¹ A_IL = L_LL L_LLᵀ
//!
//! (dense: L couples through the whole body), a forward pass over the
//! interior columns gives the condensed right-hand side
//! b̂_L = b_L − A_LI A_II⁻¹ b_I, and a backward pass over them recovers the
//! interior from u_L. A kernel A₀ + C (C on L × L) is then solved exactly
//! by b ↦ (b̂_L ↦ (S₀ + C)⁻¹ b̂_L ↦ interior), with one dense factorisation
//! of S₀ + C per kernel.
//!
//! Cost: one sparse Cholesky (the layer-last order adds a few per cent of
//! fill to the unconstrained AMD order), ℓ³/3
//! flops for S₀, ℓ² doubles for it; per vector, one sparse triangular pass
//! each way.

use crate::error::{Error, Result, SingularError};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::matmul::triangular::BlockStructure;
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::sparse::linalg::cholesky::supernodal::{SupernodalLltRef, SymbolicSupernodalCholesky};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholesky, SymbolicCholeskyRaw,
    SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::SymbolicSparseColMatRef;
use faer::sparse::{FaerError, SparseColMatRef, SymbolicSparseColMat};
use faer::{Accum, Mat, MatMut, Par};

/// A₀ factorised with the layer L last, and its Schur complement on L.
pub struct Condensation {
    n: usize,
    /// The layer's DOFs (indices of A₀), increasing: layer position k is
    /// DOF `layer[k]`.
    layer: Vec<usize>,
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    /// S₀ = L_LL L_LLᵀ, ℓ × ℓ, both triangles stored.
    s0: Mat<f64>,
    /// Non-zeros of the sparse factor (for the record).
    factor_nnz: usize,
}

fn singular(what: &'static str, error: FaerError) -> Error {
    SingularError::Condensation { what, error }.into()
}

/// A fill-reducing order of `pattern` (n × n, symmetric, both triangles)
/// with the DOFs `layer` (increasing, distinct) last: the interior by
/// approximate minimum degree, then the layer in its own order.
///
/// The interior is ordered on the whole graph with the layer made a
/// clique — the block it becomes in the factor anyway, since S₀ is dense.
/// A layer node then has degree ℓ or more from the start, so minimum degree
/// leaves the layer to the end, as the factorisation will, and every
/// interior degree counts the layer neighbours whose rows its column will
/// fill. Ordering the interior on its own graph instead (blind to those
/// rows) costs about half as many flops again in the factorisation
/// (Hertz p = 2, 256²: 3.9·10¹⁰ against 2.7·10¹⁰, 2.5·10¹⁰ for the
/// unconstrained order).
fn layer_last_order(
    pattern: SymbolicSparseColMatRef<'_, usize>,
    layer: &[usize],
) -> Result<Vec<usize>> {
    let n = pattern.nrows();
    let mut in_layer = vec![false; n];
    for &i in layer {
        in_layer[i] = true;
    }
    // the upper triangle (AMD reads the pattern of A + Aᵀ) with the layer
    // block replaced by a full one
    let mut col_ptr = Vec::with_capacity(n + 1);
    let mut row_idx = Vec::new();
    col_ptr.push(0);
    let mut next_layer = 0;
    for j in 0..n {
        let rows = pattern.row_idx_of_col(j).take_while(|&i| i <= j);
        if in_layer[j] {
            next_layer += 1;
            let clique = &layer[..next_layer];
            merge_sorted(rows.filter(|&i| !in_layer[i]), clique, &mut row_idx);
        } else {
            row_idx.extend(rows);
        }
        col_ptr.push(row_idx.len());
    }
    let nnz = row_idx.len();
    let graph = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
    let (mut fwd, mut inv) = (vec![0usize; n], vec![0usize; n]);
    let mut mem = MemBuffer::try_new(faer::sparse::linalg::amd::order_scratch::<usize>(n, nnz))
        .map_err(|e| Error::out_of_memory("the AMD workspace", e))?;
    // AMD sets rows of degree above dense·√n aside, unordered, as dense; the
    // layer's (ℓ and more) must stay in the graph for their degrees to count
    let control = faer::sparse::linalg::amd::Control {
        dense: (2.0 * layer.len() as f64 / (n as f64).sqrt()).max(10.0),
        ..Default::default()
    };
    faer::sparse::linalg::amd::order(
        &mut fwd,
        &mut inv,
        graph.as_ref(),
        control,
        MemStack::new(&mut mem),
    )
    .map_err(|e| singular("AMD ordering", e))?;
    drop(mem);
    Ok(fwd
        .into_iter()
        .filter(|&i| !in_layer[i])
        .chain(layer.iter().copied())
        .collect())
}

/// Appends the union of two increasing sequences to `out`, increasing.
fn merge_sorted(a: impl Iterator<Item = usize>, b: &[usize], out: &mut Vec<usize>) {
    let mut a = a.peekable();
    let mut b = b.iter().copied().peekable();
    loop {
        let next = match (a.peek(), b.peek()) {
            (Some(&x), Some(&y)) if x < y => a.next(),
            (Some(&x), Some(&y)) if x == y => {
                b.next();
                a.next()
            }
            (_, Some(_)) => b.next(),
            (Some(_), None) => a.next(),
            (None, None) => break,
        };
        out.extend(next);
    }
}

impl Condensation {
    /// Factorises `a0` (symmetric positive definite, both triangles
    /// stored) with the DOFs `layer` (increasing, distinct) ordered last.
    /// Fails with [`SingularError::BulkNotPositiveDefinite`] if `a0` is not
    /// positive definite — the bodies are not held even with contact
    /// everywhere.
    pub fn new(a0: SparseColMatRef<'_, usize, f64>, layer: Vec<usize>) -> Result<Self> {
        let n = a0.nrows();
        let ell = layer.len();
        let fwd = layer_last_order(a0.symbolic(), &layer)?;
        let mut inv = vec![0usize; n];
        for (new, &old) in fwd.iter().enumerate() {
            inv[old] = new;
        }
        let perm = faer::perm::PermRef::new_checked(&fwd, &inv, n);
        let symbolic = factorize_symbolic_cholesky(
            a0.symbolic(),
            faer::Side::Lower,
            SymmetricOrdering::Custom(perm),
            CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                ..Default::default()
            },
        )
        .map_err(|e| singular("symbolic Cholesky of the bulk-plus-boundary matrix", e))?;
        let par = faer::get_global_parallelism();
        let mut values = Vec::new();
        values
            .try_reserve_exact(symbolic.len_val())
            .map_err(|e| Error::out_of_memory("the Cholesky factor", e))?;
        values.resize(symbolic.len_val(), 0.0);
        let scratch = symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default());
        let mut mem = MemBuffer::try_new(scratch)
            .map_err(|e| Error::out_of_memory("the Cholesky workspace", e))?;
        symbolic
            .factorize_numeric_llt(
                &mut values,
                a0,
                faer::Side::Lower,
                Default::default(),
                par,
                MemStack::new(&mut mem),
                Default::default(),
            )
            .map_err(SingularError::BulkNotPositiveDefinite)?;
        drop(mem);
        let mut this = Self {
            n,
            layer,
            symbolic,
            values,
            s0: Mat::zeros(0, 0),
            factor_nnz: 0,
        };
        this.factor_nnz = this.count_nnz();
        let l_ll = this.trailing_block();
        let mut s0 = Mat::<f64>::zeros(ell, ell);
        faer::linalg::matmul::triangular::matmul(
            s0.as_mut(),
            BlockStructure::TriangularLower,
            Accum::Replace,
            l_ll.as_ref(),
            BlockStructure::TriangularLower,
            l_ll.transpose(),
            BlockStructure::TriangularUpper,
            1.0,
            par,
        );
        for j in 0..ell {
            for i in 0..j {
                s0[(i, j)] = s0[(j, i)];
            }
        }
        this.s0 = s0;
        Ok(this)
    }

    fn supernodal(&self) -> &SymbolicSupernodalCholesky<usize> {
        match self.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(s) => s,
            SymbolicCholeskyRaw::Simplicial(_) => unreachable!("supernodal forced"),
        }
    }

    fn factor(&self) -> SupernodalLltRef<'_, usize, f64> {
        SupernodalLltRef::new(self.supernodal(), &self.values)
    }

    fn count_nnz(&self) -> usize {
        let sym = self.supernodal();
        (0..sym.n_supernodes())
            .map(|s| {
                let w = sym.supernode_end()[s] - sym.supernode_begin()[s];
                let p = sym.supernode(s).pattern().len();
                w * (w + 1) / 2 + w * p
            })
            .sum()
    }

    /// First permuted index of the layer.
    fn offset(&self) -> usize {
        self.n - self.layer.len()
    }

    /// L_LL, the trailing ℓ × ℓ block of the factor (lower triangular).
    fn trailing_block(&self) -> Mat<f64> {
        let off = self.offset();
        let ell = self.layer.len();
        let mut l = Mat::<f64>::zeros(ell, ell);
        let f = self.factor();
        let sym = self.supernodal();
        for s in 0..sym.n_supernodes() {
            let (start, end) = (sym.supernode_begin()[s], sym.supernode_end()[s]);
            if end <= off {
                continue;
            }
            let node = f.supernode(s);
            let m = node.val();
            let w = end - start;
            for c in start.max(off)..end {
                let jc = c - start;
                for i in jc..w {
                    l[(start + i - off, c - off)] = m[(i, jc)];
                }
                for (p, &row) in node.pattern().iter().enumerate() {
                    l[(row - off, c - off)] = m[(w + p, jc)];
                }
            }
        }
        l
    }

    /// n, the order of A₀.
    pub fn n(&self) -> usize {
        self.n
    }

    /// The layer L (DOFs of A₀, increasing).
    pub fn layer(&self) -> &[usize] {
        &self.layer
    }

    /// S₀, the Schur complement of A₀ on the layer (ℓ × ℓ, dense).
    pub fn schur(&self) -> &Mat<f64> {
        &self.s0
    }

    /// Stored entries of the sparse Cholesky factor (lower triangle).
    pub fn factor_nnz(&self) -> usize {
        self.factor_nnz
    }

    /// Bytes held: the factor, S₀ and the symbolic structure.
    pub fn bytes(&self) -> usize {
        let sym = self.supernodal();
        8 * (self.values.len() + self.s0.nrows() * self.s0.ncols())
            + 8 * (sym.row_idx().len() + 4 * self.n)
    }

    /// Permutes the columns of `b` (n × k) into factor order.
    fn permute(&self, b: faer::MatRef<'_, f64>) -> Mat<f64> {
        let (fwd, _) = self.symbolic.perm().expect("custom order").arrays();
        Mat::from_fn(self.n, b.ncols(), |i, j| b[(fwd[i], j)])
    }

    /// Forward substitution over the interior columns of the permuted
    /// `x` (n × k, factor order): afterwards its interior rows hold
    /// y_I = L_II⁻¹ b_I and its layer rows b̂_L = b_L − L_LI y_I.
    fn forward_interior(&self, mut x: MatMut<'_, f64>) {
        let off = self.offset();
        let f = self.factor();
        let sym = self.supernodal();
        let par = Par::Seq;
        for s in 0..sym.n_supernodes() {
            let start = sym.supernode_begin()[s];
            if start >= off {
                break;
            }
            let end = sym.supernode_end()[s];
            let node = f.supernode(s);
            let m = node.val();
            let w = end - start;
            let k = end.min(off) - start;
            let (top, _) = m.split_at_row(w);
            faer::linalg::triangular_solve::solve_lower_triangular_in_place(
                top.submatrix(0, 0, k, k),
                x.rb_mut().subrows_mut(start, k),
                par,
            );
            let below = m.submatrix(k, 0, m.nrows() - k, k);
            let mut tmp = Mat::<f64>::zeros(below.nrows(), x.ncols());
            faer::linalg::matmul::matmul(
                tmp.as_mut(),
                Accum::Replace,
                below,
                x.rb().subrows(start, k),
                1.0,
                par,
            );
            let rows = (start + k..end).chain(node.pattern().iter().copied());
            for (t, i) in rows.enumerate() {
                for j in 0..x.ncols() {
                    x[(i, j)] -= tmp[(t, j)];
                }
            }
        }
    }

    /// Backward substitution over the interior columns of `x` (factor
    /// order) whose layer rows hold u_L: afterwards its interior rows hold
    /// u_I = L_IIᵀ⁻¹ (y_I − L_LIᵀ u_L).
    fn backward_interior(&self, mut x: MatMut<'_, f64>) {
        let off = self.offset();
        let f = self.factor();
        let sym = self.supernodal();
        let par = Par::Seq;
        for s in (0..sym.n_supernodes()).rev() {
            let start = sym.supernode_begin()[s];
            if start >= off {
                continue;
            }
            let end = sym.supernode_end()[s];
            let node = f.supernode(s);
            let m = node.val();
            let w = end - start;
            let k = end.min(off) - start;
            let below = m.submatrix(k, 0, m.nrows() - k, k);
            let rows: Vec<usize> = (start + k..end)
                .chain(node.pattern().iter().copied())
                .collect();
            let gathered = Mat::from_fn(rows.len(), x.ncols(), |t, j| x[(rows[t], j)]);
            faer::linalg::matmul::matmul(
                x.rb_mut().subrows_mut(start, k),
                Accum::Add,
                below.transpose(),
                gathered.as_ref(),
                -1.0,
                par,
            );
            let (top, _) = m.split_at_row(w);
            faer::linalg::triangular_solve::solve_upper_triangular_in_place(
                top.submatrix(0, 0, k, k).transpose(),
                x.rb_mut().subrows_mut(start, k),
                par,
            );
        }
    }

    /// Condenses the right-hand sides `b` (n × k): returns the forward
    /// state (factor order, needed by [`Condensation::extend`]) and b̂_L
    /// (ℓ × k, layer order).
    pub fn condense(&self, b: faer::MatRef<'_, f64>) -> (Mat<f64>, Mat<f64>) {
        let mut x = self.permute(b);
        self.forward_interior(x.as_mut());
        let off = self.offset();
        let bl = x.as_ref().subrows(off, self.layer.len()).to_owned();
        (x, bl)
    }

    /// The solution of A x = b for A = A₀ + C (C on L × L) from the
    /// forward state of b and x_L = (S₀ + C)⁻¹ b̂_L (ℓ × k): one backward
    /// pass. Returns x in the original order, n × k.
    pub fn extend(&self, mut state: Mat<f64>, x_l: faer::MatRef<'_, f64>) -> Mat<f64> {
        let off = self.offset();
        state
            .as_mut()
            .subrows_mut(off, self.layer.len())
            .copy_from(x_l);
        self.backward_interior(state.as_mut());
        let (_, inv) = self.symbolic.perm().expect("custom order").arrays();
        Mat::from_fn(self.n, x_l.ncols(), |i, j| state[(inv[i], j)])
    }

    /// [`Condensation::condense`] for one vector.
    pub fn condense_vec(&self, b: &[f64]) -> (Mat<f64>, Vec<f64>) {
        let (state, bl) = self.condense(faer::MatRef::from_column_major_slice(b, b.len(), 1));
        (state, bl.col(0).iter().copied().collect())
    }

    /// [`Condensation::extend`] for one vector.
    pub fn extend_vec(&self, state: Mat<f64>, x_l: &[f64]) -> Vec<f64> {
        let x = self.extend(
            state,
            faer::MatRef::from_column_major_slice(x_l, x_l.len(), 1),
        );
        x.col(0).iter().copied().collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::linalg::solvers::Solve;
    use faer::sparse::{SparseColMat, Triplet};

    /// A 2D 5-point Laplacian on an m × m grid plus a diagonal shift: SPD.
    fn laplacian(m: usize) -> SparseColMat<usize, f64> {
        grid_laplacian(m, m)
    }

    /// The same on an m × r grid (r rows of m nodes, node i + m j).
    fn grid_laplacian(m: usize, r: usize) -> SparseColMat<usize, f64> {
        let id = |i: usize, j: usize| i + m * j;
        let mut t = Vec::new();
        for j in 0..r {
            for i in 0..m {
                t.push(Triplet::new(id(i, j), id(i, j), 4.2));
                if i + 1 < m {
                    t.push(Triplet::new(id(i, j), id(i + 1, j), -1.0));
                    t.push(Triplet::new(id(i + 1, j), id(i, j), -1.0));
                }
                if j + 1 < r {
                    t.push(Triplet::new(id(i, j), id(i, j + 1), -1.0));
                    t.push(Triplet::new(id(i, j + 1), id(i, j), -1.0));
                }
            }
        }
        SparseColMat::try_new_from_triplets(m * r, m * r, &t).unwrap()
    }

    #[test]
    fn the_schur_complement_and_the_block_solve_match_dense_algebra() {
        let m = 12;
        let a = laplacian(m);
        let n = m * m;
        // the bottom two grid rows and a scattered column: like a contact layer
        let mut layer: Vec<usize> = (0..2 * m).chain([5 * m + 7, 9 * m + 3]).collect();
        layer.sort_unstable();
        let c = Condensation::new(a.as_ref(), layer.clone()).unwrap();
        let ell = layer.len();
        let dense = a.to_dense();
        let interior: Vec<usize> = (0..n).filter(|i| !layer.contains(i)).collect();
        let sub =
            |r: &[usize], s: &[usize]| Mat::from_fn(r.len(), s.len(), |i, j| dense[(r[i], s[j])]);
        let aii = sub(&interior, &interior);
        let ail = sub(&interior, &layer);
        let x = aii.partial_piv_lu().solve(&ail);
        let want = sub(&layer, &layer) - ail.transpose() * &x;
        let err = (c.schur() - &want).norm_max() / want.norm_max();
        assert!(err <= 1e-13, "S₀: {err:.2e}");
        // A = A₀ + C with C on the layer: the block solve is exact
        let cmat = Mat::from_fn(ell, ell, |i, j| ((3 * i + 7 * j) % 5) as f64 * 0.3 - 0.5);
        let mut full = dense.clone();
        for i in 0..ell {
            for j in 0..ell {
                full[(layer[i], layer[j])] += cmat[(i, j)];
            }
        }
        let b = Mat::from_fn(n, 2, |i, j| ((i * 13 + j * 5) % 11) as f64 - 5.0);
        let (state, bl) = c.condense(b.as_ref());
        let xl = (c.schur() + &cmat).partial_piv_lu().solve(&bl);
        let got = c.extend(state, xl.as_ref());
        let want = full.partial_piv_lu().solve(&b);
        let err = (&got - &want).norm_max() / want.norm_max();
        assert!(err <= 1e-12, "block solve: {err:.2e}");
    }

    /// Stored entries of the supernodal factor of `a` in the order `fwd`.
    fn factor_entries(a: &SparseColMat<usize, f64>, fwd: &[usize]) -> usize {
        let n = fwd.len();
        let mut inv = vec![0; n];
        for (k, &i) in fwd.iter().enumerate() {
            inv[i] = k;
        }
        let sym = factorize_symbolic_cholesky(
            a.symbolic(),
            faer::Side::Lower,
            SymmetricOrdering::Custom(faer::perm::PermRef::new_checked(fwd, &inv, n)),
            CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                ..Default::default()
            },
        )
        .unwrap();
        sym.len_val()
    }

    /// The unconstrained AMD order of `a`.
    fn amd(a: &SparseColMat<usize, f64>) -> Vec<usize> {
        let n = a.nrows();
        let (mut f, mut i) = (vec![0; n], vec![0; n]);
        let req = faer::sparse::linalg::amd::order_scratch::<usize>(n, a.val().len());
        let mut mem = MemBuffer::new(req);
        faer::sparse::linalg::amd::order(
            &mut f,
            &mut i,
            a.symbolic(),
            Default::default(),
            MemStack::new(&mut mem),
        )
        .unwrap();
        f
    }

    /// The layer-last order fills the factor little more than AMD free to
    /// place the layer anywhere, and less than AMD of the interior alone
    /// with the layer appended.
    #[test]
    fn the_layer_last_order_adds_little_fill() {
        let m = 60;
        let a = laplacian(m);
        let n = m * m;
        // the bottom two grid rows: a contact layer
        let layer: Vec<usize> = (0..2 * m).collect();
        let fwd = layer_last_order(a.symbolic(), &layer).unwrap();
        assert_eq!(&fwd[n - layer.len()..], &layer[..]);
        let mut seen = vec![false; n];
        fwd.iter().for_each(|&i| seen[i] = true);
        assert!(seen.iter().all(|&s| s), "a permutation");
        let constrained = factor_entries(&a, &fwd);
        let free = factor_entries(&a, &amd(&a));
        // AMD of the interior's own graph (the grid of the other m − 2
        // rows), the layer appended
        let interior: Vec<usize> = (2 * m..n).collect();
        let blind: Vec<usize> = amd(&grid_laplacian(m, m - 2))
            .iter()
            .map(|&k| interior[k])
            .chain(layer.clone())
            .collect();
        let blind = factor_entries(&a, &blind);
        let c = constrained as f64;
        assert!(
            c <= 1.1 * free as f64,
            "{constrained} against {free} unconstrained"
        );
        assert!(
            c < blind as f64,
            "{constrained} against {blind} blind to the layer"
        );
    }

    #[test]
    fn a_matrix_that_is_not_positive_definite_is_refused() {
        let m = 6;
        let mut a = laplacian(m);
        let (sym, vals) = a.parts_mut();
        let ptr = sym.col_ptr();
        // make the last diagonal entry negative
        let last = sym.ncols() - 1;
        for k in ptr[last]..ptr[last + 1] {
            if sym.row_idx()[k] == last {
                vals[k] = -1.0;
            }
        }
        let err = Condensation::new(a.as_ref(), vec![0, 1, last])
            .err()
            .expect("indefinite");
        assert_eq!(err.kind(), crate::error::ErrorKind::SingularKernel, "{err}");
    }
}
