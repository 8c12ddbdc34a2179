//! "Convergence under refinement" and "The pressure profile": Newton on
//! every degree and mesh of the study, the fine reference, and the dense
//! profiles of two meshes.

use crate::ladder::{not_converged, run, Ladder, Run};
use crate::{CONVERGENCE_ELEMENTS, LADDER_DEGREES, PROFILE_ELEMENTS, REFERENCE};
use companion::Solver;
use iga_contact::error::Result;
use iga_contact::post::PressureProfile;
use std::collections::BTreeMap;

/// p₀, a and the DOFs of one Newton solve.
#[derive(Clone, Copy)]
pub struct Measured {
    pub p0: f64,
    pub half_width: f64,
    pub dofs: usize,
}

impl Measured {
    pub fn of(r: &Run) -> Self {
        Measured {
            p0: r.p0,
            half_width: r.half_width,
            dofs: r.problem.n(),
        }
    }
}

/// One degree and mesh of the study.
pub struct Rung {
    pub degree: usize,
    pub elements: usize,
    pub measured: Measured,
}

/// What "Convergence under refinement" reports: the reference, every
/// degree and mesh of the study, and the reference's check one mesh
/// coarser.
pub struct Convergence {
    pub reference: Measured,
    pub rows: Vec<Rung>,
    /// The reference's degree on half its elements per direction.
    pub check: Measured,
}

// ANCHOR: convergence
/// Fig. 6: Newton solutions (the discrete solution does not depend on
/// the solver, see the ladder), reused from the ladder where it has them.
pub fn convergence_study(ladder: &Ladder) -> Result<Convergence> {
    let mut newton: BTreeMap<(usize, usize), Measured> = ladder
        .runs
        .iter()
        .filter(|r| r.solver == Solver::Newton)
        .map(|r| ((r.degree, r.elements), Measured::of(r)))
        .collect();
    let newton_opts = Solver::Newton.options();
    let mut measured = |p: usize, n: usize| -> Result<Measured> {
        if let Some(&m) = newton.get(&(p, n)) {
            return Ok(m);
        }
        let r = run(p, n, Solver::Newton, &newton_opts)?.map_err(|f| not_converged(&f))?;
        let m = Measured::of(&r);
        newton.insert((p, n), m);
        Ok(m)
    };
    let reference = measured(REFERENCE.0, REFERENCE.1)?;
    let mut rows = Vec::new();
    for p in LADDER_DEGREES {
        for n in CONVERGENCE_ELEMENTS {
            rows.push(Rung {
                degree: p,
                elements: n,
                measured: measured(p, n)?,
            });
        }
    }
    let check = measured(REFERENCE.0, REFERENCE.1 / 2)?;
    Ok(Convergence {
        reference,
        rows,
        check,
    })
}
// ANCHOR_END: convergence

/// The dense pressure profile of one mesh.
pub struct Profile {
    pub elements: usize,
    pub profile: PressureProfile,
}

/// "The pressure profile": the dense profiles of two meshes, against
/// Hertz's ellipse.
pub fn pressure_profiles() -> Result<Vec<Profile>> {
    let newton_opts = Solver::Newton.options();
    let mut profiles = Vec::new();
    for n in PROFILE_ELEMENTS {
        let r = run(2, n, Solver::Newton, &newton_opts)?.map_err(|f| not_converged(&f))?;
        profiles.push(Profile {
            elements: n,
            profile: PressureProfile::dense(&r.problem, &r.solution.full)?,
        });
    }
    Ok(profiles)
}
