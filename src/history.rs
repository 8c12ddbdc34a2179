//! The iteration record kept by every nonlinear solver: plain data, below
//! every module, so that an error can carry the history of the solve it ends
//! ([`crate::Error::NotConverged`]) without the error type depending on the
//! solver.

use std::fmt;

/// Something notable that happened during one iteration.
#[derive(Clone, Debug, PartialEq)]
pub enum Event {
    /// The BFGS kernel was replaced by the secant matrix (18) and refactorised.
    Correction,
    /// A BFGS pair was dropped because yᵀs was not safely positive.
    SkippedUpdate { curvature: f64 },
    /// The line search halved the step this many times.
    LineSearchCuts(usize),
    /// The active set did not hold a floating body, so the nearest contact
    /// points were made active (and pulled onto the obstacle).
    FloatingGuard,
    /// A kernel factorised by Cholesky plus the low-rank correction failed
    /// the plain accuracy check, so its solves refine iteratively.
    KernelRefined,
    /// The low-rank kernel factorisation was refused (S not positive
    /// definite, or inaccurate even with refinement); LU took over.
    KernelLuFallback,
    /// The damped iteration from the first start stalled, so the solve
    /// started again from u = 0 with the tied kernel (17)
    /// ([`crate::solver::OnStall::RestartTied`]).
    Restart,
}

impl fmt::Display for Event {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Event::Correction => write!(f, "correction"),
            Event::SkippedUpdate { curvature } => {
                write!(f, "skipped update (yᵀs = {curvature:.2e})")
            }
            Event::LineSearchCuts(n) => write!(f, "line search ×{n}"),
            Event::FloatingGuard => write!(f, "floating guard"),
            Event::KernelRefined => write!(f, "kernel refined"),
            Event::KernelLuFallback => write!(f, "kernel by LU"),
            Event::Restart => write!(f, "restart from the tied kernel"),
        }
    }
}

/// One row of the iteration table.
#[derive(Clone, Debug, PartialEq)]
pub struct Iteration {
    /// 1-based iteration number.
    pub iteration: usize,
    /// ‖R(u_k)‖₂ after the update (on the contact layer, the residual of
    /// the condensed problem, which is the whole residual: the interior
    /// is relaxed).
    pub residual: f64,
    /// ‖R(u_k)‖ / ‖R(u_0)‖.
    pub relative_residual: f64,
    /// ‖Δu‖₂ of the update (on the contact layer: of its DOFs).
    pub update: f64,
    /// The displacement component of largest magnitude (signed; on the
    /// contact layer: of its DOFs, the body being recovered only at the end).
    pub max_displacement: f64,
    /// Number of contact quadrature points with P ≤ 0.
    pub active_points: usize,
    pub events: Vec<Event>,
}

/// The whole record of a solve.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct History {
    /// ‖R(u_0)‖, the reference for relative residuals.
    pub initial_residual: f64,
    pub rows: Vec<Iteration>,
}

impl History {
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// The relative residual of the last iteration; with no iteration, 0
    /// if the start was already converged (R₀ = 0, e.g. no load) and 1
    /// otherwise.
    pub fn last_relative_residual(&self) -> f64 {
        match self.rows.last() {
            Some(r) => r.relative_residual,
            None if self.initial_residual == 0.0 => 0.0,
            None => 1.0,
        }
    }

    /// Number of iterations that carry `pred`.
    pub fn count(&self, pred: impl Fn(&Event) -> bool) -> usize {
        self.rows
            .iter()
            .flat_map(|r| r.events.iter())
            .filter(|e| pred(e))
            .count()
    }

    pub fn corrections(&self) -> usize {
        self.count(|e| *e == Event::Correction)
    }

    pub fn skipped_updates(&self) -> usize {
        self.count(|e| matches!(e, Event::SkippedUpdate { .. }))
    }

    /// The period of an exact cycle at the end of the history: the
    /// smallest p in 2..=30 such that the last three periods repeat, active
    /// counts equal and relative residuals within 10⁻⁶ of each other.
    pub fn cycle_period(&self) -> Option<usize> {
        let rows = &self.rows;
        (2..=30).find(|&p| {
            rows.len() >= 3 * p
                && (rows.len() - 2 * p..rows.len()).all(|i| {
                    let (a, b) = (&rows[i], &rows[i - p]);
                    a.active_points == b.active_points
                        && (a.relative_residual - b.relative_residual).abs()
                            <= 1e-6 * a.relative_residual.abs()
                })
        })
    }
}
