//! What the nonlinear solvers iterate on: the whole body
//! ([`BodySystem`], the paper's iteration) or the contact layer
//! ([`TraceSystem`], the condensed problem). Both give the residual, P at
//! every contact point, kernels for a given activity, and the floor of
//! what floating point can resolve.

use super::factorise::{factor_kernel, Factorisation};
use super::history::Event;
use super::stopping::Floor;
use super::trace::{DenseLu, TraceProblem};
use super::vector::max_displacement;
use crate::error::Result;
use crate::linsolve::{Factor, Factoriser};
use crate::problem::{ContactState, Kernel, Problem};
use std::rc::Rc;

/// A factorised kernel.
pub(crate) trait LinearSolve {
    fn solve(&self, b: &[f64]) -> Result<Vec<f64>>;
}

impl LinearSolve for Factor {
    fn solve(&self, b: &[f64]) -> Result<Vec<f64>> {
        Factor::solve(self, b)
    }
}

impl LinearSolve for DenseLu {
    fn solve(&self, b: &[f64]) -> Result<Vec<f64>> {
        DenseLu::solve(self, b)
    }
}

/// A full-space kernel A₀ + C solved through the condensation.
struct CondensedKernel<'p> {
    trace: Rc<TraceProblem<'p>>,
    lu: DenseLu,
}

impl LinearSolve for CondensedKernel<'_> {
    fn solve(&self, b: &[f64]) -> Result<Vec<f64>> {
        self.trace.solve_full(&self.lu, b)
    }
}

/// The space a solver iterates in.
pub(crate) trait System<'p> {
    fn dim(&self) -> usize;
    fn p_values(&self, u: &[f64]) -> Vec<f64>;
    /// The residual with the points marked in `forced` under the tied law,
    /// the contact state, and the round-off floors of ‖R‖ at `u`.
    fn residual_forced(&self, u: &[f64], forced: &[bool]) -> (Vec<f64>, ContactState, Floor);
    /// What the residual gains when the points `dropped` (each with
    /// P ≤ 0 at `u`) are taken out of the active set: R of the active set
    /// without them is R(u) plus this.
    fn released(&self, u: &[f64], dropped: &[usize]) -> Vec<f64>;
    /// The kernel of the activity `h` (one H per contact point).
    fn factor(&mut self, h: &[f64], events: &mut Vec<Event>) -> Result<Rc<dyn LinearSolve + 'p>>;

    /// A full DOF vector in this space's coordinates.
    fn coords(&self, full: &[f64]) -> Vec<f64>;
    /// The signed largest component of the displacement this space holds.
    fn max_displacement(&self, u: &[f64]) -> f64;
    /// The free displacement of the bodies.
    fn body(&self, u: Vec<f64>) -> Vec<f64>;
}

/// The whole body: the iteration of the paper, over every free DOF.
pub(crate) struct BodySystem<'p> {
    problem: &'p Problem,
    how: Factorisation,
    fac: Factoriser,
    /// The condensation that solves the kernels ([`Factorisation::Auto`]).
    trace: Option<Rc<TraceProblem<'p>>>,
}

impl<'p> BodySystem<'p> {
    pub fn new(problem: &'p Problem, how: Factorisation) -> Result<Self> {
        let trace = match how {
            Factorisation::Auto => Some(Rc::new(TraceProblem::new(problem)?)),
            Factorisation::LowRank | Factorisation::Lu => None,
        };
        Ok(Self {
            problem,
            how,
            fac: Factoriser::default(),
            trace,
        })
    }
}

impl<'p> System<'p> for BodySystem<'p> {
    fn dim(&self) -> usize {
        self.problem.n()
    }

    fn p_values(&self, u: &[f64]) -> Vec<f64> {
        self.problem.p_values(u)
    }

    fn residual_forced(&self, u: &[f64], forced: &[bool]) -> (Vec<f64>, ContactState, Floor) {
        let (r, state, (typical, cancelling)) = self.problem.residual_with_floor(u, forced);
        (
            r,
            state,
            Floor {
                typical,
                cancelling,
            },
        )
    }

    fn released(&self, u: &[f64], dropped: &[usize]) -> Vec<f64> {
        let full = self.problem.map.expand(u);
        let mut out = vec![0.0; u.len()];
        for &q in dropped {
            let cp = &self.problem.points[q];
            let (sigma, jump) = cp.normal_stress_and_jump(&full);
            let p = sigma + cp.gamma * (cp.g0 - jump);
            for (k, &d) in cp.dofs.iter().enumerate() {
                if let Some(i) = self.problem.map.free(d) {
                    out[i] +=
                        cp.weight / cp.gamma * p * (cp.theta * cp.sn[k] - cp.gamma * cp.jn[k]);
                }
            }
        }
        out
    }

    fn factor(&mut self, h: &[f64], events: &mut Vec<Event>) -> Result<Rc<dyn LinearSolve + 'p>> {
        if let Some(trace) = &self.trace {
            let lu = DenseLu::new(&trace.kernel(h))?;
            return Ok(Rc::new(CondensedKernel {
                trace: Rc::clone(trace),
                lu,
            }));
        }
        Ok(Rc::new(factor_kernel(
            self.problem,
            &mut self.fac,
            Kernel::Activity(h),
            self.how,
            events,
        )?))
    }

    fn max_displacement(&self, u: &[f64]) -> f64 {
        max_displacement(&self.problem.map.expand(u))
    }

    fn body(&self, u: Vec<f64>) -> Vec<f64> {
        u
    }

    fn coords(&self, full: &[f64]) -> Vec<f64> {
        self.problem.map.restrict(full)
    }
}

/// The contact layer: the condensed problem of [`TraceProblem`].
pub(crate) struct TraceSystem<'p> {
    trace: Rc<TraceProblem<'p>>,
}

impl<'p> TraceSystem<'p> {
    pub fn new(problem: &'p Problem) -> Result<Self> {
        Ok(Self {
            trace: Rc::new(TraceProblem::new(problem)?),
        })
    }
}

impl<'p> System<'p> for TraceSystem<'p> {
    fn dim(&self) -> usize {
        self.trace.dim()
    }

    fn p_values(&self, u: &[f64]) -> Vec<f64> {
        self.trace.p_values(u)
    }

    fn residual_forced(&self, u: &[f64], forced: &[bool]) -> (Vec<f64>, ContactState, Floor) {
        self.trace.residual_forced(u, forced)
    }

    fn released(&self, u: &[f64], dropped: &[usize]) -> Vec<f64> {
        self.trace.released(u, dropped)
    }

    fn factor(&mut self, h: &[f64], _: &mut Vec<Event>) -> Result<Rc<dyn LinearSolve + 'p>> {
        Ok(Rc::new(DenseLu::new(&self.trace.kernel(h))?))
    }

    fn max_displacement(&self, u: &[f64]) -> f64 {
        max_displacement(u)
    }

    fn body(&self, u: Vec<f64>) -> Vec<f64> {
        self.trace.recover(&u)
    }

    fn coords(&self, full: &[f64]) -> Vec<f64> {
        self.trace.coords(full)
    }
}
