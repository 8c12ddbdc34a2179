//! The stability atlas: the program behind the chapter "Stability atlas".
//! The method on stiff and extreme cases — penalties over ten decades for
//! the three θ, stiffness contrast, near incompressibility, load levels,
//! open and penetrating gaps, very coarse and fine meshes — each ending
//! either converged or in a typed, diagnosed error.
//! Output: `book/src/generated/stability/`.
//!
//! Run it with `cargo run --release --example stability`.
//!
//! The parts: the cases of the atlas, axis by axis (`cases.rs`); one case
//! solved and classified (`atlas.rs`); the tables (`tables.rs`) and the
//! facts (`facts.rs`).

mod atlas;
mod cases;
mod facts;
mod tables;

use companion::chapter::Chapter;
use companion::hertz as setup;
use iga_contact::contact::Theta;
use iga_contact::error::{Error, Result};
use iga_contact::post::PressureProfile;
use iga_contact::report::table::Format;
use iga_contact::scene::Scene;
use iga_contact::solver::{solve, SolverOptions};

// ANCHOR: metric
/// What a case is measured against.
#[derive(Clone, Copy)]
enum Metric {
    /// The peak contact pressure p₀, relative to this value.
    PeakPressure(f64),
    /// The largest relative deviation of σ_yy from this uniform value.
    UniformStress(f64),
    /// The bodies must not touch: no active point.
    NoContact,
}
// ANCHOR_END: metric

/// One case: its name, θ and penalty factor (for the table), its scene, and
/// its metric.
struct Case {
    name: String,
    theta: Theta,
    penalty_factor: f64,
    scene: Scene,
    metric: Metric,
}

/// The chapter "Stability atlas", section by section.
fn main() -> Result<()> {
    let mut chapter = Chapter::from_args("stability")?;

    // Axes and references: every case of the atlas, solved.
    let fine = reference_fine()?;
    let all = cases::cases(reference_8x8()?, fine)?;
    let rows = atlas::run_atlas(&all);

    // The full atlas: every case and its diagnosis (atlas.csv).
    chapter.csv("atlas", &tables::atlas_table(&rows)?)?;

    // The penalty range of each θ: the penalty × θ views of the two problems.
    let hertz_view = tables::penalty_view(&rows, "hertz_8x8_penalty", Format::Percent(1))?;
    chapter.text("penalty_hertz.md", &hertz_view.to_markdown())?;
    let taylor_view = tables::penalty_view(&rows, "taylor_penalty", Format::Sci(0))?;
    chapter.text("penalty_taylor.md", &taylor_view.to_markdown())?;

    // The full atlas: the other axes, case by case.
    chapter.text("cases.md", &tables::others_table(&rows)?.to_markdown())?;

    // The penalty range of each θ: the factors within the tolerance.
    chapter.table("penalty_ranges", &tables::ranges_table(&rows)?)?;

    // The facts of every section: the counts, and each case's measures.
    facts::record_count_facts(chapter.facts(), &rows)?;
    facts::record_case_facts(chapter.facts(), &rows)?;
    facts::record_fine_facts(chapter.facts(), &rows, fine)?;
    chapter.finish()
}

/// "Axes and references": p₀ of the Hertz disk on 8², the reference of the
/// Hertz 8² cases on the penalty and gap axes.
fn reference_8x8() -> Result<f64> {
    let s = cases::hertz(2, 8)?;
    let p = s.build()?;
    let sol = solve(&p, &SolverOptions::default())?;
    Ok(PressureProfile::dense(&p, &sol.full)?.measures(0).p0)
}

/// "Axes and references": the Hertz chapter's converged reference (p = 3,
/// 128²), from its facts; the reference of the mesh and degree axis.
fn reference_fine() -> Result<f64> {
    Ok(companion::facts("hertz")?
        .value("reference_p0_mpa")
        .ok_or_else(|| Error::invalid("hertz facts", "reference_p0_mpa", "missing"))?
        * 1e6)
}
