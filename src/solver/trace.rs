//! The contact problem condensed exactly onto the layer L
//! ([`crate::condense`]).
//!
//! With A₀ = K + G, G = Σ_q w γ jn jnᵀ, factorised once and its interior
//! eliminated, the residual (13) on L at an interior-relaxed displacement
//! (R_I = 0) is
//!
//!   R̂(u_L) = f̂_L − S₀ u_L + G u_L − g_c(u_L),
//!
//! where g_c is the contact internal force, and the kernel of an active
//! set H is
//!
//!   T(H) = S₀ − G + Σ_q (point matrix of q at H_q),
//!
//! the exact Schur complement of the full kernel. Both are dense ℓ × ℓ
//! operations, so an iteration costs O(ℓ²) and a kernel O(ℓ³) — against
//! a sparse triangular pass over the whole body before.

use super::stopping::Floor;
use super::vector::norm;
use crate::condense::Condensation;
use crate::contact::nitsche::{add_force_at, add_force_size_at, local_matrix, Law};
use crate::contact::ContactPoint;
use crate::error::{Result, SingularError};
use crate::problem::{ContactState, Problem};
use faer::linalg::solvers::Solve;
use faer::Mat;

/// A contact point in layer numbering: its free DOFs as layer positions,
/// the functionals on them, and the parts of σ_n and ⟦u_n⟧ that come
/// from prescribed displacements.
struct LayerPoint {
    at: Vec<usize>,
    /// Index of each entry of `at` in the point's own DOF list.
    local: Vec<usize>,
    sigma_fixed: f64,
    jump_fixed: f64,
}

/// The condensed problem: S₀, f̂_L and the contact points on L.
pub struct TraceProblem<'a> {
    problem: &'a Problem,
    cond: Condensation,
    points: Vec<LayerPoint>,
    /// f̂_L, the condensed load.
    fhat: Vec<f64>,
    /// The forward state of the load (for the recovery of the body).
    load: Mat<f64>,
}

/// Layers larger than this are not condensed: the dense ℓ × ℓ kernels
/// would need more than about 2 GB (three copies of 8ℓ² bytes).
pub const MAX_LAYER: usize = 9000;

impl<'a> TraceProblem<'a> {
    /// Factorises A₀ and condenses the load. Fails with a
    /// [`SingularError`] if A₀ is not positive definite.
    pub fn new(problem: &'a Problem) -> Result<Self> {
        let layer = problem.layer();
        if layer.len() > MAX_LAYER {
            return Err(SingularError::LayerTooLarge {
                dofs: layer.len(),
                max: MAX_LAYER,
            }
            .into());
        }
        let a0 = problem.bulk_plus_penalty_values()?;
        let cond = Condensation::new(
            faer::sparse::SparseColMatRef::new(problem.k.symbolic(), &a0),
            layer,
        )?;
        drop(a0);
        let mut at_layer = vec![usize::MAX; problem.n()];
        for (k, &i) in cond.layer().iter().enumerate() {
            at_layer[i] = k;
        }
        let points = problem
            .points
            .iter()
            .map(|cp| {
                let mut p = LayerPoint {
                    at: Vec::new(),
                    local: Vec::new(),
                    sigma_fixed: 0.0,
                    jump_fixed: 0.0,
                };
                for (k, &d) in cp.dofs.iter().enumerate() {
                    match problem.map.free(d) {
                        Some(i) if at_layer[i] != usize::MAX => {
                            p.at.push(at_layer[i]);
                            p.local.push(k);
                        }
                        Some(_) => {} // σ_n and ⟦u_n⟧ do not see it
                        None => {
                            let v = problem.map.prescribed(d);
                            p.sigma_fixed += cp.sn[k] * v;
                            p.jump_fixed += cp.jn[k] * v;
                        }
                    }
                }
                p
            })
            .collect();
        let (load, fhat) = cond.condense_vec(&problem.rhs);
        Ok(Self {
            problem,
            cond,
            points,
            fhat,
            load,
        })
    }

    /// ℓ, the number of layer DOFs.
    pub fn dim(&self) -> usize {
        self.fhat.len()
    }

    pub fn condensation(&self) -> &Condensation {
        &self.cond
    }

    fn pairs(&self) -> impl Iterator<Item = (&ContactPoint, &LayerPoint)> {
        self.problem.points.iter().zip(&self.points)
    }

    /// (σ_n, ⟦u_n⟧) of a point at the layer displacement `u`.
    fn stress_and_jump(cp: &ContactPoint, lp: &LayerPoint, u: &[f64]) -> (f64, f64) {
        let (mut s, mut j) = (lp.sigma_fixed, lp.jump_fixed);
        for (&i, &k) in lp.at.iter().zip(&lp.local) {
            s += cp.sn[k] * u[i];
            j += cp.jn[k] * u[i];
        }
        (s, j)
    }

    /// Σ|s_k u_k| and Σ|j_k u_k| of a point (the sizes of the sums that
    /// give σ_n and ⟦u_n⟧), for the round-off floor.
    fn stress_and_jump_sizes(cp: &ContactPoint, lp: &LayerPoint, u: &[f64]) -> (f64, f64) {
        let (mut s, mut j) = (lp.sigma_fixed.abs(), lp.jump_fixed.abs());
        for (&i, &k) in lp.at.iter().zip(&lp.local) {
            s += (cp.sn[k] * u[i]).abs();
            j += (cp.jn[k] * u[i]).abs();
        }
        (s, j)
    }

    /// P at every contact point for the layer displacement `u`.
    pub fn p_values(&self, u: &[f64]) -> Vec<f64> {
        self.pairs()
            .map(|(cp, lp)| {
                let (s, j) = Self::stress_and_jump(cp, lp, u);
                s + cp.gamma * (cp.g0 - j)
            })
            .collect()
    }

    /// R̂(u) over the layer, with the points marked in `forced` under the
    /// tied law (see [`Problem::residual_forced`]); also the round-off
    /// floor of its evaluation, ε ‖ |f̂| + |S₀||u| + |G||u| + |g_c| ‖, with
    /// g_c counted as computed and before its terms cancel ([`Floor`]).
    pub fn residual_forced(&self, u: &[f64], forced: &[bool]) -> (Vec<f64>, ContactState, Floor) {
        let ell = self.dim();
        let s0 = self.cond.schur();
        let mut r = self.fhat.clone();
        let mut size: Vec<f64> = self.fhat.iter().map(|v| v.abs()).collect();
        // the same, with the contact forces counted before they cancel
        let mut wide = Vec::new();
        for j in 0..ell {
            let uj = u[j];
            if uj == 0.0 {
                continue;
            }
            for (i, (ri, si)) in r.iter_mut().zip(size.iter_mut()).enumerate() {
                let a = s0[(i, j)] * uj;
                *ri -= a;
                *si += a.abs();
            }
        }
        wide.extend_from_slice(&size);
        let mut active = 0;
        for (q, (cp, lp)) in self.pairs().enumerate() {
            // + G u on the free layer DOFs (the penalty added to A₀)
            let ju: f64 = lp
                .at
                .iter()
                .zip(&lp.local)
                .map(|(&i, &k)| cp.jn[k] * u[i])
                .sum();
            let wg = cp.weight * cp.gamma;
            let (sigma, jump) = Self::stress_and_jump(cp, lp, u);
            let mut g = vec![0.0; cp.dofs.len()];
            let law = match forced.get(q) {
                Some(true) => Law::Tied,
                _ => Law::Contact,
            };
            let p = add_force_at(cp, sigma, jump, &mut g, law);
            if p <= 0.0 {
                active += 1;
            }
            let (sigma_size, jump_size) = Self::stress_and_jump_sizes(cp, lp, u);
            let mut g_size = vec![0.0; cp.dofs.len()];
            add_force_size_at(cp, sigma_size, jump_size, p, law, &mut g_size);
            for (&i, &k) in lp.at.iter().zip(&lp.local) {
                let a = wg * cp.jn[k] * ju;
                r[i] += a - g[k];
                size[i] += a.abs() + g[k].abs();
                wide[i] += a.abs() + g_size[k];
            }
        }
        let floor = Floor {
            typical: f64::EPSILON * norm(&size),
            cancelling: f64::EPSILON * norm(&wide),
        };
        (r, ContactState { active }, floor)
    }

    /// What R̂(u) gains when the points `dropped` (all with P ≤ 0) leave
    /// the active set: their contact force beyond the θ term, w/γ · P ·
    /// (θ sn − γ jn), added back.
    pub fn released(&self, u: &[f64], dropped: &[usize]) -> Vec<f64> {
        let mut out = vec![0.0; self.dim()];
        for &q in dropped {
            let (cp, lp) = (&self.problem.points[q], &self.points[q]);
            let (sigma, jump) = Self::stress_and_jump(cp, lp, u);
            let p = sigma + cp.gamma * (cp.g0 - jump);
            for (&i, &k) in lp.at.iter().zip(&lp.local) {
                out[i] += cp.weight / cp.gamma * p * (cp.theta * cp.sn[k] - cp.gamma * cp.jn[k]);
            }
        }
        out
    }

    /// T(H) = S₀ − G + Σ_q (point matrix at H_q), dense.
    pub fn kernel(&self, h: &[f64]) -> Mat<f64> {
        let mut t = self.cond.schur().clone();
        for (q, (cp, lp)) in self.pairs().enumerate() {
            let m = local_matrix(cp, h[q]);
            let wg = cp.weight * cp.gamma;
            for (&i, &a) in lp.at.iter().zip(&lp.local) {
                for (&j, &b) in lp.at.iter().zip(&lp.local) {
                    t[(i, j)] += m[(a, b)] - wg * cp.jn[a] * cp.jn[b];
                }
            }
        }
        t
    }

    /// The layer part of a full DOF vector.
    pub fn coords(&self, full: &[f64]) -> Vec<f64> {
        let free = self.problem.map.restrict(full);
        self.cond.layer().iter().map(|&i| free[i]).collect()
    }

    /// The free displacement of the bodies whose layer part is `u`, the
    /// interior relaxed (R_I = 0): one backward pass.
    pub fn recover(&self, u: &[f64]) -> Vec<f64> {
        self.cond.extend_vec(self.load.clone(), u)
    }

    /// The free displacement solving A x = b for A = A₀ + C, from the
    /// dense factorisation of S₀ + C (the full-space kernel solve).
    pub fn solve_full(&self, kernel: &DenseLu, b: &[f64]) -> Result<Vec<f64>> {
        let (state, bl) = self.cond.condense_vec(b);
        let xl = kernel.solve(&bl)?;
        Ok(self.cond.extend_vec(state, &xl))
    }
}

/// A dense LU factorisation (partial pivoting) of a trace kernel.
pub struct DenseLu(faer::linalg::solvers::PartialPivLu<f64>);

impl DenseLu {
    /// Fails with [`SingularError::TraceKernel`] when a pivot vanishes
    /// relative to the largest (below 10⁻¹⁴ of it): the kernel does not
    /// hold the bodies.
    pub fn new(a: &Mat<f64>) -> Result<Self> {
        let lu = a.partial_piv_lu();
        let d = lu.U().diagonal().column_vector();
        let (mut lo, mut hi) = (f64::INFINITY, 0.0f64);
        for v in d.iter() {
            lo = lo.min(v.abs());
            hi = hi.max(v.abs());
        }
        let held = lo > 1e-14 * hi && hi.is_finite();
        if !held {
            return Err(SingularError::TraceKernel {
                smallest: lo,
                largest: hi,
            }
            .into());
        }
        Ok(Self(lu))
    }

    pub fn solve(&self, b: &[f64]) -> Result<Vec<f64>> {
        let x = self.0.solve(faer::ColRef::from_slice(b));
        let x: Vec<f64> = x.iter().copied().collect();
        if x.iter().all(|v| v.is_finite()) {
            Ok(x)
        } else {
            Err(SingularError::NonFiniteSolution.into())
        }
    }
}
