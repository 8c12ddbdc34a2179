//! Hertz contact of an elastic disk on a rigid plane: the program behind
//! the chapter "Hertz contact of a disk on a rigid plane" (the paper's
//! Fig. 4, Table 2, Figs. 5 and 6).
//!
//! The scene `data/scenes/hertz.toml` models the right half of the disk,
//! loaded by its own weight and resting on a rigid floor; symmetry holds
//! u_x = 0 on the diameter. The program solves it on a ladder of meshes
//! with six solvers (`ladder.rs`), records the 8×8 iteration history,
//! measures the peak pressure and the contact half-width on every mesh
//! against Hertz and a fine reference (`convergence.rs`), and writes the
//! tables (`tables.rs`), the figures (`figures.rs`) and the facts the
//! prose quotes (`facts.rs`) into `book/src/generated/hertz/`.
//!
//! Run it with `cargo run --release --example hertz`.

mod convergence;
mod facts;
mod figures;
mod ladder;
mod tables;

use companion::chapter::Chapter;
use companion::hertz as setup;
use companion::Solver;
use iga_contact::error::Result;

// ANCHOR: constants
/// The iteration at which the paper's correction fired on the 8×8 mesh.
const PAPER_CORRECTION_ITERATION: usize = 13;
/// Degrees and meshes (elements per direction) of the solver ladder.
const LADDER_DEGREES: [usize; 2] = [2, 3];
const LADDER_ELEMENTS: [usize; 4] = [8, 16, 32, 64];
/// Meshes of the convergence study (Fig. 6).
const CONVERGENCE_ELEMENTS: [usize; 6] = [4, 8, 16, 32, 64, 128];
/// The converged reference: (degree, elements per direction).
const REFERENCE: (usize, usize) = (3, 128);
/// Meshes of the pressure-profile figure (p = 2).
const PROFILE_ELEMENTS: [usize; 2] = [8, 64];
// ANCHOR_END: constants

/// The chapter "Hertz contact of a disk on a rigid plane", section by
/// section.
fn main() -> Result<()> {
    let mut chapter = Chapter::from_args("hertz")?;
    let base = setup::scene(setup::iga(2, 8))?;
    let exact = setup::analytic(&base)?;

    // The solver ladder: Tables H5 and H6.
    let ladder = ladder::solve_ladder(&base)?;
    tables::write_ladder(&mut chapter, &ladder)?;

    // The iteration history on 8×8 (the paper's Table 2): Tables H1, H2, Fig. H2.
    let paper = ladder.run(Solver::Paper, 2, 8)?;
    let default = ladder.run(Solver::Bfgs, 2, 8)?;
    tables::write_histories(&mut chapter, paper, default)?;
    figures::residual_figure(&chapter, paper, default)?;

    // The model and the vertical displacement on 8×8: Figs. H1, H3, the VTU.
    figures::model_figure(&chapter, &default.problem)?;
    figures::uy_figure(&chapter, default)?;
    figures::write_vtu(&chapter, default)?;

    // Convergence under refinement: Tables H3 and H4, Figs. H5 and H6.
    let study = convergence::convergence_study(&ladder)?;
    tables::write_convergence(&mut chapter, &study, &exact)?;
    figures::convergence_figures(&chapter, &study, &exact)?;

    // The pressure profile: Fig. H4.
    let profiles = convergence::pressure_profiles()?;
    figures::profile_outputs(&mut chapter, &profiles, &exact)?;

    // The numbers the prose quotes.
    let f = chapter.facts();
    facts::record_model_facts(f, &exact)?;
    facts::record_convergence_facts(f, &study, &exact)?;
    facts::record_8x8_facts(f, paper, default, &study, &exact)?;
    facts::record_ladder_facts(f, &ladder, &exact)?;
    chapter.finish()
}
