//! What the programs of "The penalty, measured" share (`penalty`, quick,
//! and `penalty_contrast`, heavy): one solve measured on the dense pressure
//! profile, and the Hertz disk with chosen Nitsche parameters.

use iga_contact::error::Result;
use iga_contact::post::PressureProfile;
use iga_contact::problem::Problem;
use iga_contact::scene::NitscheSpec;
use iga_contact::scene::RefineSpec;
use iga_contact::solver::{solve, Solution, SolverOptions};

/// One converged solve, measured on the dense profile.
pub struct Outcome {
    pub solution: Solution,
    pub p0: f64,
    pub zones: usize,
}

/// A solve that converged, or the kind of the error it stopped with.
pub type Run = std::result::Result<Outcome, &'static str>;

/// Solves `problem`; a failed solve is a result here (the tables show it),
/// not an error of the program.
pub fn measure(problem: &Problem, options: &SolverOptions) -> Result<Run> {
    match solve(problem, options) {
        Ok(solution) => {
            let m = PressureProfile::dense(problem, &solution.full)?.measures(0);
            Ok(Ok(Outcome {
                p0: m.p0,
                zones: m.zones,
                solution,
            }))
        }
        Err(e) => Ok(Err(e.kind().tag())),
    }
}

/// The Hertz disk on `n`² elements, p = 2, with the Nitsche parameters
/// `set` (the scene's own solver table is not used: every run names its
/// solver).
pub fn hertz(n: usize, set: impl FnMut(&mut NitscheSpec)) -> Result<Problem> {
    crate::shipped("hertz.toml")?
        .refined("disk", RefineSpec::iga(2, [n, n]))?
        .with_nitsche(set)
        .build()
}
