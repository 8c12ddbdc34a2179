//! Factorising the kernels (17)–(18) of one solve.
//!
//! The default ([`Factorisation::Auto`]) factorises once per problem: the
//! bulk stiffness plus the penalty term of the whole potential contact
//! boundary, A₀, by sparse Cholesky with the contact layer ordered last
//! ([`crate::condense`]). Every kernel, of every θ (θ = 1 included) and
//! every active set, is A₀ plus a matrix on the layer, so it costs one
//! dense factorisation of the layer's Schur complement plus that matrix
//! ([`super::trace`]).
//!
//! The two earlier ways factorise each assembled kernel on its own:
//! sparse LU, or — for θ ≤ 0 — Cholesky of its symmetric positive
//! definite part with a Sherman–Morrison–Woodbury correction of the trace
//! rows ([`Problem::kernel_split`], [`crate::linsolve::LowRankCorrected`]).

use super::guard::Guard;
use super::history::Event;
use super::system::{LinearSolve, System};
use super::Start;
use crate::contact::nitsche::heaviside;
use crate::error::Result;
use crate::linsolve::{Factor, Factoriser, Method};
use crate::problem::{Kernel, Problem};
use serde::{Deserialize, Serialize};
use std::rc::Rc;

/// How the solvers factorise their kernels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Factorisation {
    /// Factorise once: Cholesky of A₀ with the contact layer last, then a
    /// dense factorisation of the layer's Schur complement per kernel.
    /// Falls back to [`Factorisation::LowRank`] when the layer is too
    /// large for dense kernels ([`super::trace::MAX_LAYER`]).
    #[default]
    Auto,
    /// Per kernel: Cholesky plus the low-rank trace correction where it
    /// applies (every point θ ≤ 0, the symmetric part positive definite,
    /// the set-up check passed), sparse LU otherwise.
    LowRank,
    /// Sparse LU of the assembled kernel, always.
    Lu,
}

/// Factorises the assembled full-space kernel `kind` of `problem` on its
/// own, reusing the symbolic analyses kept in `fac`: by LU for
/// [`Factorisation::Lu`], by the low-rank path otherwise (`Auto` has no
/// single-kernel form: it factorises A₀ once for a whole solve). A
/// low-rank factorisation that needed refinement, or was refused in
/// favour of LU, is logged in `events` ([`Event::KernelRefined`],
/// [`Event::KernelLuFallback`]); LU chosen because some θ > 0 is the
/// design, not an event.
pub fn factor_kernel(
    problem: &Problem,
    fac: &mut Factoriser,
    kind: Kernel,
    how: Factorisation,
    events: &mut Vec<Event>,
) -> Result<Factor> {
    if how != Factorisation::Lu {
        if let Some(split) = problem.kernel_split(kind)? {
            match fac.factor_low_rank(&split.spd, &split.u, &split.v) {
                Ok(f) => {
                    if matches!(&f, Factor::LowRank(l) if l.refines()) {
                        events.push(Event::KernelRefined);
                    }
                    return Ok(f);
                }
                // not positive definite, or ill-conditioned: LU decides;
                // out of memory or a singular kernel LU cannot help
                Err(e) if e.lu_may_help() => events.push(Event::KernelLuFallback),
                Err(e) => return Err(e.into()),
            }
        }
    }
    Ok(fac.factor(&problem.kernel(kind)?, Method::Lu)?)
}

/// A kernel ready for solves, with the activity it was built for and the
/// points the floating guard forced active.
pub(crate) struct Built<'p> {
    pub factor: Rc<dyn LinearSolve + 'p>,
    pub activity: Vec<f64>,
    /// Per point: forced active by the guard (empty: none).
    pub forced: Vec<bool>,
}

impl Built<'_> {
    pub fn guarded(&self) -> bool {
        self.forced.iter().any(|&f| f)
    }
}

/// The kernels of one solve: the tied kernel (17) and secant kernels (18)
/// with the floating guard, counted, and the active sets they were built
/// for (to detect a cycle).
pub(crate) struct Kernels<'s, 'p> {
    pub sys: &'s mut dyn System<'p>,
    guard: Guard,
    pub factorisations: usize,
    built: Vec<Vec<bool>>,
}

impl<'s, 'p> Kernels<'s, 'p> {
    pub fn new(sys: &'s mut dyn System<'p>, problem: &Problem) -> Self {
        Self {
            sys,
            guard: Guard::new(problem),
            factorisations: 0,
            built: Vec::new(),
        }
    }

    /// Whether the last kernel built revisits the active set of an
    /// earlier one (not the one just before it).
    pub fn cycled(&self) -> bool {
        match self.built.split_last() {
            Some((last, earlier)) if earlier.len() >= 2 => {
                earlier[..earlier.len() - 1].contains(last)
            }
            _ => false,
        }
    }

    fn build(
        &mut self,
        h: Vec<f64>,
        forced: Vec<bool>,
        events: &mut Vec<Event>,
    ) -> Result<Built<'p>> {
        self.factorisations += 1;
        self.built.push(h.iter().map(|&v| v > 0.5).collect());
        Ok(Built {
            factor: self.sys.factor(&h, events)?,
            activity: h,
            forced,
        })
    }

    /// The tied kernel (17): every point active.
    pub fn tied(&mut self, events: &mut Vec<Event>) -> Result<Built<'p>> {
        self.build(vec![1.0; self.guard.points()], Vec::new(), events)
    }

    /// The secant kernel (18) at `u`. If its active set does not hold a
    /// floating body, the guard adds the nearest points
    /// ([`Event::FloatingGuard`]).
    pub fn secant(&mut self, u: &[f64], events: &mut Vec<Event>) -> Result<Built<'p>> {
        let p = self.sys.p_values(u);
        let mut h: Vec<f64> = p.iter().map(|&v| heaviside(v)).collect();
        let chosen = self.guard.select(&p);
        let mut forced = Vec::new();
        if !chosen.is_empty() {
            events.push(Event::FloatingGuard);
            forced = vec![false; p.len()];
            for q in chosen {
                h[q] = 1.0;
                forced[q] = true;
            }
        }
        self.build(h, forced, events)
    }

    /// The first kernel of `start` at `u` (residual `r`). For
    /// [`Start::Secant`], `u` and `r` are first shifted rigidly by
    /// [`Kernels::balance`].
    pub fn start(
        &mut self,
        start: Start,
        u: &mut [f64],
        r: &mut Vec<f64>,
        events: &mut Vec<Event>,
    ) -> Result<Built<'p>> {
        match start {
            Start::Tied => self.tied(events),
            Start::Secant => {
                if self.balance(u, r) {
                    *r = self.sys.residual_forced(u, &[]).0;
                }
                self.secant(u, events)
            }
        }
    }

    /// Shifts `u` rigidly along the floating modes so that the load along
    /// each is balanced by the contact forces; returns whether it moved.
    pub fn balance(&self, u: &mut [f64], r: &[f64]) -> bool {
        if self.guard.modes.is_empty() {
            return false;
        }
        let modes: Vec<Vec<f64>> = self
            .guard
            .modes
            .iter()
            .map(|m| self.sys.coords(m))
            .collect();
        let f0: Vec<f64> = modes.iter().map(|m| super::dot(m, r)).collect();
        let t = self.guard.balance(&self.sys.p_values(u), &f0);
        let mut moved = false;
        for (m, tk) in modes.iter().zip(&t) {
            if *tk != 0.0 {
                moved = true;
                for (ui, mi) in u.iter_mut().zip(m) {
                    *ui += tk * mi;
                }
            }
        }
        moved
    }

    /// The activity H(P(u)) at `u`.
    pub fn activity(&self, u: &[f64]) -> Vec<f64> {
        self.sys.p_values(u).into_iter().map(heaviside).collect()
    }
}
