//! The solvers the chapter programs compare, by name: the library's default
//! BFGS, the paper's iteration, each with and without the secant
//! correction, the paper's iteration from the balanced start, and Newton.
//! A chapter names a solver by a [`Solver`], never by a string; the string
//! its tables and facts write is [`Solver::key`] (or [`Solver::name`]).

use iga_contact::solver::{Growth, SolverKind, SolverOptions, Start};

// ANCHOR: solvers
/// A solver the chapters compare, in the order of the Hertz ladder.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Solver {
    /// The library's default BFGS (`SolverOptions::default()`).
    Bfgs,
    /// The paper's iteration (`SolverOptions::paper()`, or a scene's own
    /// `[solver]` table: full steps).
    Paper,
    /// The paper's iteration from the balanced secant start instead of the
    /// tied kernel: the like-for-like test of the start.
    PaperSecantStart,
    /// The paper's iteration never corrected: the like-for-like test of the
    /// correction.
    PaperNoCorrection,
    /// The default BFGS never corrected.
    BfgsNoCorrection,
    /// Semismooth Newton, with the default's other options.
    Newton,
}

impl Solver {
    /// The options of the solver, the paper's iteration being `paper`
    /// (`SolverOptions::paper()`, or a scene's own `[solver]` table).
    pub fn options_from(self, paper: SolverOptions) -> SolverOptions {
        match self {
            Solver::Bfgs => SolverOptions::default(),
            Solver::Paper => paper,
            // the start alone: `growth = "auto"` would also cut the growth
            // after a secant start, which the tied start does not
            Solver::PaperSecantStart => SolverOptions {
                start: Start::Secant,
                growth: Growth::Full,
                ..paper
            },
            Solver::PaperNoCorrection => SolverOptions {
                kind: SolverKind::BfgsNoCorrection,
                ..paper
            },
            Solver::BfgsNoCorrection => SolverOptions::with_kind(SolverKind::BfgsNoCorrection),
            Solver::Newton => SolverOptions::with_kind(SolverKind::Newton),
        }
    }
}
// ANCHOR_END: solvers

impl Solver {
    /// Every solver, in the order of the Hertz ladder.
    pub const ALL: [Solver; 6] = [
        Solver::Bfgs,
        Solver::Paper,
        Solver::PaperSecantStart,
        Solver::PaperNoCorrection,
        Solver::BfgsNoCorrection,
        Solver::Newton,
    ];

    /// The options of the solver, the paper's iteration being
    /// `SolverOptions::paper()`.
    pub fn options(self) -> SolverOptions {
        self.options_from(SolverOptions::paper())
    }

    /// The key the tables (CSV and Markdown) and the facts use: `bfgs`,
    /// `bfgs_paper`, …, `newton`.
    pub fn key(self) -> &'static str {
        match self {
            Solver::Bfgs => "bfgs",
            Solver::Paper => "bfgs_paper",
            Solver::PaperSecantStart => "bfgs_paper_secant_start",
            Solver::PaperNoCorrection => "bfgs_paper_no_correction",
            Solver::BfgsNoCorrection => "bfgs_no_correction",
            Solver::Newton => "newton",
        }
    }

    /// The name a reader sees in a table or a legend.
    pub fn name(self) -> &'static str {
        match self {
            Solver::Bfgs => "default BFGS",
            Solver::Paper => "the paper's BFGS",
            Solver::PaperSecantStart => "the paper's BFGS from the secant start",
            Solver::PaperNoCorrection => "the paper's BFGS without correction",
            Solver::BfgsNoCorrection => "default BFGS without correction",
            Solver::Newton => "Newton",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_solver_has_its_own_key_and_name() {
        for (i, a) in Solver::ALL.iter().enumerate() {
            for b in &Solver::ALL[i + 1..] {
                assert_ne!(a.key(), b.key());
                assert_ne!(a.name(), b.name());
            }
        }
    }

    #[test]
    fn only_the_paper_variants_read_the_paper_options() {
        let paper = SolverOptions::paper();
        for s in [Solver::Bfgs, Solver::BfgsNoCorrection, Solver::Newton] {
            assert_eq!(
                s.options_from(paper),
                s.options_from(SolverOptions::default())
            );
        }
        assert_eq!(Solver::Paper.options(), paper);
    }
}
