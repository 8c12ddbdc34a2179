//! Factorising the kernels (17)–(18) of one solve.
//!
//! Both kernels are non-symmetric for θ ≠ 1, which calls for LU. But for
//! θ ≤ 0 their non-symmetric part, −Σ w (jn snᵀ + θ sn jnᵀ), lives in the
//! rows and columns of the contact trace, so the kernel is a symmetric
//! positive definite matrix plus a correction of rank r or 2r, r ~ √n
//! ([`Problem::kernel_split`]). A Cholesky factorisation with the
//! Sherman–Morrison–Woodbury identity ([`crate::linsolve::LowRankCorrected`])
//! solves it exactly and, with faer, several times faster than LU. For
//! θ = 1 the kernel is symmetric but indefinite, so it stays with LU.

use super::history::Event;
use crate::error::{Error, Result};
use crate::linsolve::{Factor, Factoriser, Method};
use crate::problem::{Kernel, Problem};
use serde::{Deserialize, Serialize};
use std::rc::Rc;

/// How the solvers factorise their kernels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Factorisation {
    /// Cholesky with the low-rank trace correction where it applies (every
    /// point θ ≤ 0, the symmetric part positive definite, the set-up check
    /// passed), sparse LU otherwise.
    #[default]
    Auto,
    /// Sparse LU of the assembled kernel, always.
    Lu,
}

/// Factorises the kernel `kind` of `problem` as `how` asks, reusing the
/// symbolic analyses kept in `fac`. A low-rank factorisation that needed
/// refinement, or was refused in favour of LU, is logged in `events`
/// ([`Event::KernelRefined`], [`Event::KernelLuFallback`]); LU chosen
/// because some θ > 0 is the design, not an event.
pub fn factor_kernel(
    problem: &Problem,
    fac: &mut Factoriser,
    kind: Kernel,
    how: Factorisation,
    events: &mut Vec<Event>,
) -> Result<Factor> {
    if how == Factorisation::Auto {
        if let Some(split) = problem.kernel_split(kind)? {
            match fac.factor_low_rank(&split.spd, &split.u, &split.v) {
                Ok(f) => {
                    if matches!(&f, Factor::LowRank(l) if l.refines()) {
                        events.push(Event::KernelRefined);
                    }
                    return Ok(f);
                }
                // not positive definite, or ill-conditioned: LU decides
                Err(Error::Singular(_)) => events.push(Event::KernelLuFallback),
                Err(e) => return Err(e),
            }
        }
    }
    fac.factor(&problem.kernel(kind)?, Method::Lu)
}

/// The kernels of one solve. The tied kernel (17) is factorised once and
/// kept: it starts the iteration and stands in for the secant kernel (18)
/// whenever no contact point is active — then (18) is the bare stiffness,
/// singular for a body that only contact holds, which is what
/// [`Event::FloatingGuard`] records.
pub(crate) struct Kernels<'a> {
    problem: &'a Problem,
    how: Factorisation,
    fac: Factoriser,
    tied: Rc<Factor>,
    /// Events of the tied factorisation, for the first iteration's record.
    startup: Vec<Event>,
    pub factorisations: usize,
}

impl<'a> Kernels<'a> {
    pub fn new(problem: &'a Problem, how: Factorisation) -> Result<Self> {
        let mut fac = Factoriser::default();
        let mut startup = Vec::new();
        let tied = Rc::new(factor_kernel(
            problem,
            &mut fac,
            Kernel::Tied,
            how,
            &mut startup,
        )?);
        Ok(Self {
            problem,
            how,
            fac,
            tied,
            startup,
            factorisations: 1,
        })
    }

    /// The events of the tied factorisation, once.
    pub fn take_startup_events(&mut self) -> Vec<Event> {
        std::mem::take(&mut self.startup)
    }

    pub fn tied(&self) -> Rc<Factor> {
        Rc::clone(&self.tied)
    }

    /// The secant kernel (18) at `u`, or the kept tied kernel if the active set is empty.
    pub fn secant(&mut self, u: &[f64], events: &mut Vec<Event>) -> Result<Rc<Factor>> {
        if self.problem.active_points(u) == 0 && !self.problem.points.is_empty() {
            events.push(Event::FloatingGuard);
            return Ok(self.tied());
        }
        self.factorisations += 1;
        Ok(Rc::new(factor_kernel(
            self.problem,
            &mut self.fac,
            Kernel::Secant(u),
            self.how,
            events,
        )?))
    }
}
