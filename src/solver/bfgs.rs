//! BFGS in product form, Eq. (16), over a sparse factorisation of its kernel.
//!
//! The inverse update
//!   H_{k+1} = (I − ρ s yᵀ) H_k (I − ρ y sᵀ) + ρ s sᵀ,  ρ = 1/(yᵀs),
//! is never formed: H_k r is evaluated by the two-loop recursion over the
//! stored pairs, with H_0 r a triangular solve with the kernel factors.
//! Cost per iteration: O(n k) for k pairs plus one solve.

use super::attempt::{end_iteration, Attempt, Iterate};
use super::history::{Event, History};
use super::kernel::Kernels;
use super::line_search::{line_search, Fallback};
use super::options::{CorrectOn, Damping, SolverOptions, Start};
use super::stopping::Tracker;
use super::system::System;
use super::vector::{dot, norm};
use crate::error::Result;
use crate::problem::Problem;

/// The stored (s, y) pairs of the inverse update.
#[derive(Clone, Debug, Default)]
pub struct InverseUpdate {
    pairs: Vec<(Vec<f64>, Vec<f64>, f64)>,
}

impl InverseUpdate {
    /// Stores (s, y) if the curvature yᵀs is safely positive; otherwise
    /// returns the rejected curvature.
    pub fn push(&mut self, s: Vec<f64>, y: Vec<f64>, tol: f64) -> std::result::Result<(), f64> {
        let ys = dot(&y, &s);
        if ys > tol * norm(&y) * norm(&s) && ys.is_finite() {
            self.pairs.push((s, y, 1.0 / ys));
            Ok(())
        } else {
            Err(ys)
        }
    }

    pub fn clear(&mut self) {
        self.pairs.clear();
    }

    pub fn len(&self) -> usize {
        self.pairs.len()
    }

    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }

    /// H_k r by the two-loop recursion, with H_0 applied by `h0`.
    pub fn apply(
        &self,
        r: &[f64],
        h0: impl FnOnce(&[f64]) -> Result<Vec<f64>>,
    ) -> Result<Vec<f64>> {
        let mut q = r.to_vec();
        let mut alpha = vec![0.0; self.pairs.len()];
        for (i, (s, y, rho)) in self.pairs.iter().enumerate().rev() {
            alpha[i] = rho * dot(s, &q);
            for (qk, yk) in q.iter_mut().zip(y) {
                *qk -= alpha[i] * yk;
            }
        }
        let mut z = h0(&q)?;
        for (i, (s, y, rho)) in self.pairs.iter().enumerate() {
            let beta = rho * dot(y, &z);
            for (zk, sk) in z.iter_mut().zip(s) {
                *zk += (alpha[i] - beta) * sk;
            }
        }
        Ok(z)
    }
}

/// BFGS from the kernel `opts.start`; with `correct`, the correction:
/// after `correction_after` iterations, whenever the rule `opts.correct_on`
/// fires, refactorise the kernel as the secant matrix (18) at the current
/// iterate and drop the pairs. The paper's rule is [`CorrectOn::Growth`]
/// after 8 iterations.
///
/// The paper takes full steps. A full BFGS or secant step can overshoot
/// into a far-off active set (the secant step is a Newton step, which can
/// cycle), so steps may be damped by a backtracking line search on ‖R‖ —
/// our addition, logged as [`Event::LineSearchCuts`] — as `opts.damping`
/// says: once `opts.line_search_after` corrections have fired
/// (`usize::MAX`: the paper's undamped iteration), or once a correction
/// revisits an active set (the default). A step whose kernel the floating
/// guard completed is taken in full: it is the rigid motion that closes
/// the gap.
///
/// With the default options — the balanced secant start, a correction at
/// every change of the active set from the first iteration on — the
/// kernel is the exact tangent of the current linear piece whenever the
/// active set moves, and the BFGS pairs carry the iteration only while it
/// stays: on Hertz the iteration and factorisation counts are those of
/// semismooth Newton.
///
/// One start of the iteration, from u = 0 with the kernel of `start`,
/// continuing `history` (the rows of an earlier start, or none).
pub(crate) fn solve(
    sys: &mut dyn System<'_>,
    problem: &Problem,
    opts: &SolverOptions,
    start: Start,
    history: History,
    correct: bool,
) -> Result<Attempt> {
    let n = sys.dim();
    let mut u = vec![0.0; n];
    let (mut r, mut state, floor) = sys.residual_forced(&u, &[]);
    let mut events = Vec::new();
    if !history.is_empty() {
        events.push(Event::Restart);
    }
    let mut tracker = Tracker::new(opts, norm(&r), history);
    if Tracker::at_floor(&r, floor) {
        return Ok(Attempt {
            u,
            history: tracker.history,
            factorisations: 0,
            stalled: false,
        });
    }
    let mut kernels = Kernels::new(sys, problem, opts.growth, start);
    let mut kernel = kernels.start(start, &mut u, &mut r, &mut events)?;
    let mut update = InverseUpdate::default();
    let mut corrections = 0;
    let mut cycled = false;
    let first_row = tracker.history.len();
    loop {
        // right after a guarded (re)factorisation, the step follows the
        // residual of the guard's force law
        let drive = if update.is_empty() {
            kernel.drive(&*kernels.sys, &u, &r)
        } else {
            r.clone()
        };
        let guarded = kernel.guarded() && update.is_empty();
        let dir = update.apply(&drive, |q| kernel.factor.solve(q))?;
        let damped = tracker.history.len() > first_row
            && !guarded
            && match opts.damping {
                Damping::AfterCorrections => corrections >= opts.line_search_after,
                Damping::OnCycle => cycled,
            };
        // from a floating iterate, backtracking cannot help (see `Fallback::Full`)
        let fallback = if state.active == 0 {
            Fallback::Full
        } else {
            Fallback::Best
        };
        let step = line_search(&*kernels.sys, &u, &dir, &r, damped, fallback);
        let du: Vec<f64> = dir.iter().map(|d| step.alpha * d).collect();
        u = step.u;
        let r_new = step.r;
        state = step.state;
        if step.cuts > 0 {
            events.push(Event::LineSearchCuts(step.cuts));
        }
        let y: Vec<f64> = r.iter().zip(&r_new).map(|(a, b)| a - b).collect();
        if let Err(curvature) = update.push(du.clone(), y, opts.curvature_tol) {
            events.push(Event::SkippedUpdate { curvature });
        }
        let k = tracker.history.len() + 1 - first_row;
        let grew = norm(&r_new) > norm(&r);
        let done = tracker.converged(&u, &du, &r_new, step.floor);
        let trigger = match opts.correct_on {
            CorrectOn::Growth => grew,
            CorrectOn::ActiveSet => grew || kernels.activity(&u) != kernel.activity,
        };
        if correct && !done && k > opts.correction_after && trigger && norm(&r_new).is_finite() {
            events.push(Event::Correction);
            corrections += 1;
            kernel = kernels.secant(&u, step.alpha == 1.0, &mut events)?;
            cycled |= kernels.cycled();
            update.clear();
        }
        r = r_new;
        let it = Iterate {
            du: &du,
            r: &r,
            floor: step.floor,
            active: state.active,
            events: std::mem::take(&mut events),
            damped,
        };
        if let Some(end) = end_iteration(&mut tracker, &kernels, problem, &mut u, it) {
            return end;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};

    /// The two-loop product equals the explicit dense recursion (16).
    #[test]
    fn product_form_matches_dense_update() {
        let n = 7;
        let mut seed = 12345u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        };
        // a non-symmetric H0, like the inverse of the tied kernel for θ = 0
        let a = DMatrix::from_fn(n, n, |i, j| if i == j { 4.0 } else { rnd() });
        let h0 = a.clone().try_inverse().unwrap();
        let mut dense = h0.clone();
        let mut upd = InverseUpdate::default();
        for _ in 0..5 {
            let s = DVector::from_fn(n, |_, _| rnd());
            let y = &a * &s + DVector::from_fn(n, |_, _| 0.1 * rnd());
            let rho = 1.0 / y.dot(&s);
            let i = DMatrix::<f64>::identity(n, n);
            dense = (&i - rho * &s * y.transpose()) * &dense * (&i - rho * &y * s.transpose())
                + rho * &s * s.transpose();
            upd.push(s.as_slice().to_vec(), y.as_slice().to_vec(), 1e-12)
                .expect("positive curvature");
        }
        let r = DVector::from_fn(n, |_, _| rnd());
        let expect = &dense * &r;
        let got = upd
            .apply(r.as_slice(), |q| {
                Ok(a.clone()
                    .lu()
                    .solve(&DVector::from_column_slice(q))
                    .unwrap()
                    .as_slice()
                    .to_vec())
            })
            .unwrap();
        for k in 0..n {
            assert!(
                (got[k] - expect[k]).abs() <= 1e-12 * expect.amax(),
                "{k}: {} vs {}",
                got[k],
                expect[k]
            );
        }
    }

    #[test]
    fn negative_curvature_is_rejected() {
        let mut upd = InverseUpdate::default();
        assert!(upd.push(vec![1.0, 0.0], vec![-1.0, 0.0], 1e-12).is_err());
        assert!(upd.is_empty());
    }
}
