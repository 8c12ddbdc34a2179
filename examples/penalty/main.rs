//! The penalty, measured: the program behind the chapter "The penalty,
//! measured". It compares the paper's empirical penalty (11) with the sharp
//! bound below which the θ-family loses coercivity, element by element, for
//! degrees 1 to 5 on four set-ups; solves with the sharp penalty as an
//! option; and maps the small-penalty regime where the solvers part ways.
//! The disk on an elastic block of rising stiffness is the heavy program
//! `penalty_contrast`. Output: `book/src/generated/penalty/`.
//!
//! Run it with `cargo run --release --example penalty`.
//!
//! The parts: the ratio of (11) to the bound and Table PS1 (`ratios.rs`),
//! the singular corner of the disk (`corner.rs`), the sharp penalty
//! (`sharp.rs`) and the small penalties (`small.rs`).

mod corner;
mod ratios;
mod sharp;
mod small;

use companion::chapter::Chapter;
use iga_contact::error::Result;
use iga_contact::problem::Problem;
use iga_contact::scene::RefineSpec;

// ANCHOR: setups
/// The degrees compared; p = 1 is the Lagrange Q1 mesh (a NURBS circle
/// needs p ≥ 2).
const DEGREES: [usize; 5] = [1, 2, 3, 4, 5];
/// Elements per direction of the slave bodies' meshes.
const MESHES: [usize; 2] = [4, 16];
/// The set-ups, in the order of the tables.
const SETUPS: [&str; 4] = [
    "Hertz disk",
    "Taylor blocks",
    "two cylinders",
    "block on floor",
];

fn refine(p: usize, elements: [usize; 2]) -> RefineSpec {
    match p {
        1 => RefineSpec::lagrange(1, elements),
        p => RefineSpec::iga(p, elements),
    }
}

/// The four set-ups, each with degree `p` and `n` elements per direction
/// on its slave body (the Taylor blocks keep their 4×2 and 3×2 pattern,
/// scaled by n/4; the block on the floor, 1 m × 0.5 m, has square
/// elements).
fn setups(p: usize, n: usize) -> Result<[Problem; 4]> {
    let m = (n / 4).max(1);
    let hertz = companion::shipped("hertz.toml")?.refined("disk", refine(p, [n, n]))?;
    let taylor = companion::shipped("taylor.toml")?
        .refined("lower", refine(p, [4 * m, 2 * m]))?
        .refined("upper", refine(p, [3 * m, 2 * m]))?;
    let cylinders = companion::shipped("two_cylinders.toml")?
        .refined("upper", refine(p, [n, n]))?
        .refined("lower", refine(p, [2 * n, 2 * n]))?;
    let block = companion::shipped("minimal.toml")?.refined("block", refine(p, [n, n / 2]))?;
    Ok([
        hertz.build()?,
        taylor.build()?,
        cylinders.build()?,
        block.build()?,
    ])
}
// ANCHOR_END: setups

/// The chapter "The penalty, measured", section by section.
fn main() -> Result<()> {
    let mut chapter = Chapter::from_args("penalty")?;

    // (11) against the bound: Table PS1, Fig. PS1 and their facts.
    let survey = ratios::survey_ratios()?;
    ratios::write_survey(&mut chapter, &survey)?;
    ratios::record_ratio_facts(chapter.facts(), &survey.first)?;

    // Where the map is singular.
    corner::record_corner_facts(chapter.facts(), &survey)?;

    // The sharp penalty as an option: Table PS2.
    let sharp = sharp::compare_sharp_penalty()?;
    chapter.table("sharp", &sharp.table)?;
    sharp::record_sharp_facts(chapter.facts(), &sharp)?;

    // Small penalties, where the answer stops being unique: Table PS5.
    let small = small::sweep_small_penalties()?;
    chapter.table("small_penalty", &small.table)?;
    small::record_small_facts(chapter.facts(), &small)?;

    chapter.finish()
}
