//! Answers off the benchmark path: the program behind the section of that
//! name in the chapter "Reliability".
//!
//! It writes scenes a user might write once off the shipped benchmarks —
//! bodies held only by supports and pressed by a prescribed displacement,
//! Hertz in other units, either body of a pair as the slave, ν up to
//! 0.49999, penalties over eighteen decades, large loads, one element to
//! 64² — gives each to `check` and `run` of this build's `iga-contact` as a
//! child process, and judges every answer against a closed form or a
//! converged run: the scene files (`scenes.rs`), the cases and their
//! references (`cases.rs`), the launches and their verdicts (`judge.rs`),
//! and the tables (`report.rs`).
//!
//! Output: `book/src/generated/answers/`. A heavy program (about 2 minutes
//! on an idle two-core machine): `reproduce --only answers`.

use companion::harness;

mod cases;
mod judge;
mod report;
mod scenes;

use companion::chapter::Chapter;
use companion::timing::Machine;
use companion::Facts;
use iga_contact::report::table::Format;
use iga_contact::Result;
use std::time::Instant;

/// The section "Answers off the benchmark path" of "Reliability".
fn main() -> Result<()> {
    // fail fast: the chapter folder must take the report before the work
    let mut chapter = Chapter::from_args("answers")?;
    harness::binary();
    let work = std::env::temp_dir().join(format!("answers-{}", std::process::id()));
    std::fs::create_dir_all(&work).expect("a temporary work folder");
    let t0 = Instant::now();
    let start = Machine::here();
    let answered = report::report(&work, &mut chapter)?;
    let _ = std::fs::remove_dir_all(&work);
    record_run_facts(chapter.facts(), &start, t0)?;
    record_facts(chapter.facts(), &answered)?;
    let dir = chapter.dir().display().to_string();
    chapter.finish()?;
    println!("wrote {dir}/ in {:.0} s", t0.elapsed().as_secs_f64());
    Ok(())
}

/// When, where and on what the campaign ran (`start`: the machine when it
/// began at `t0`).
fn record_run_facts(f: &mut Facts, start: &Machine, t0: Instant) -> Result<()> {
    let end = Machine::here();
    start.record(f, "")?;
    f.timed_text(
        "load_end",
        end.load.map_or("unknown".into(), |l| format!("{l:.1}")),
    )?;
    f.timed_text("commit", harness::commit())?;
    f.timed_number(
        "minutes",
        t0.elapsed().as_secs_f64() / 60.0,
        Format::Fixed(1),
    )
}

/// What the section quotes of the answers.
fn record_facts(f: &mut Facts, answered: &report::Summary) -> Result<()> {
    f.count("answers_cases", answered.cases)?;
    f.count("answers_classes", cases::Class::ALL.len())?;
    f.count("answers_launches", answered.launches)?;
    f.count("answers_silent_wrong", answered.silent_wrong)?;
    f.count("answers_unclean", answered.unclean)?;
    f.timed_number(
        "answers_peak_mb",
        answered.peak_bytes / 1e6,
        Format::Fixed(0),
    )?;
    f.number("answers_wrong", judge::WRONG, Format::Percent(0))?;
    f.number("answers_balance", judge::BALANCE, Format::Pow10(0))?;
    f.number(
        "scale_spread",
        answered.scale_spread.max(1e-16),
        Format::Pow10(0),
    )?;
    f.text(
        "scale_same_iterations",
        if answered.scale_same_iterations {
            "yes"
        } else {
            "no"
        },
    )?;
    f.number(
        "prescribed_error",
        answered.prescribed_error.max(1e-16),
        Format::Pow10(0),
    )
}
