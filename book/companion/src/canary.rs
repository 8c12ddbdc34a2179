//! The solver's fingerprint, which ties a heavy chapter's committed data to
//! the code that computed them.
//!
//! The heavy chapter programs (minutes to hours) are not rerun by the tests,
//! so their committed data can silently fall behind the solver: once, a
//! change of the default solver cut the iterations of a heavy table from
//! 5–83 to 3–7 while the chapter's prose still described the old counts.
//! Each heavy program therefore records [`fingerprint`] in its facts under
//! [`KEY`], and a quick test recomputes it: when the solver's behaviour has
//! changed since the data were made, the test names the chapter to rerun.
//!
//! The fingerprint is what a change of behaviour moves and a change of
//! machine does not: the iterations and factorisations of a few small solves
//! (Hertz p = 2 on 8 × 8 with each solver family, and the disk on an elastic
//! block), and p₀ to six significant digits, well above the round-off that
//! a different summation order of the threaded assembly leaves.

use crate::hertz as setup;
use iga_contact::error::Result;
use iga_contact::post::PressureProfile;
use iga_contact::scene::OutputSpec;
use iga_contact::solver::{solve, SolverKind, SolverOptions};

/// The fact key under which a heavy chapter records the fingerprint.
pub const KEY: &str = "solver_canary";

/// One line per canary solve, joined by `; `: `name: iterations it,
/// factorisations f, p0 …` (or the failure's kind).
pub fn fingerprint() -> Result<String> {
    let hertz = setup::scene(setup::iga(2, 8))?;
    let mut block = crate::shipped("disk_on_block.toml")?;
    block.output = OutputSpec::default();
    let solvers = [
        ("default", SolverOptions::default()),
        ("newton", SolverOptions::with_kind(SolverKind::Newton)),
        ("paper", SolverOptions::paper()),
    ];
    let mut lines = Vec::new();
    for (scene_name, scene) in [("hertz8", &hertz), ("disk_on_block", &block)] {
        let problem = scene.build()?;
        for (solver_name, opts) in &solvers {
            let line = match solve(&problem, opts) {
                Ok(s) => {
                    let p0 = PressureProfile::dense(&problem, &s.full)?.measures(0).p0;
                    format!(
                        "{scene_name} {solver_name}: {} it, {} fact, p0 {p0:.5e}",
                        s.history.len(),
                        s.factorisations
                    )
                }
                Err(e) => format!("{scene_name} {solver_name}: {}", e.kind()),
            };
            lines.push(line);
        }
    }
    Ok(lines.join("; "))
}

/// Records the fingerprint of the code running now in a heavy chapter's
/// facts.
pub fn record(facts: &mut crate::Facts) -> Result<()> {
    facts.text(KEY, fingerprint()?)
}
