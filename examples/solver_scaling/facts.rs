//! What the program writes: the three tables (timed, printed too) and the
//! facts the chapter quotes, case by case.

use crate::measure::{NotRun, Row};
use crate::tables::tables;
use crate::{PARTS_CHECKED_FROM, PARTS_WITHIN};
use companion::chapter::Chapter;
use companion::Facts;
use iga_contact::report::table::Format;

/// Writes `book/src/generated/solver_scaling/`: the tables and the facts.
pub fn write_chapter(rows: &[Row], not_run: &[NotRun]) -> iga_contact::Result<()> {
    let mut chapter = Chapter::at(companion::chapter::generated_root().join("solver_scaling"))?;
    write_tables(&mut chapter, rows)?;
    let facts = chapter.facts();
    // the chapter states when and on what the times were taken
    companion::timing::Machine::here().record(facts, "machine_")?;
    facts.number("parts_within", PARTS_WITHIN, Format::Percent(0))?;
    facts.count("parts_checked_from", PARTS_CHECKED_FROM)?;
    for NotRun { p, n, reason } in not_run {
        facts.text(&format!("p{p}_{n}_status"), format!("not run: {reason}"))?;
    }
    for r in rows {
        record_case_facts(facts, r)?;
    }
    chapter.finish()
}

/// The three tables, printed and written; every one of their files holds
/// times.
fn write_tables(chapter: &mut Chapter, rows: &[Row]) -> iga_contact::Result<()> {
    let [scaling, phases, cli] = tables(rows)?;
    print!(
        "{}\n{}\n{}",
        scaling.to_markdown(),
        phases.to_markdown(),
        cli.to_markdown()
    );
    chapter.table("scaling", &scaling)?;
    chapter.table("phases", &phases)?;
    chapter.table("cli", &cli)?;
    for stem in ["scaling", "phases", "cli"] {
        chapter.timed(&format!("{stem}.csv"));
        chapter.timed(&format!("{stem}.md"));
    }
    Ok(())
}

/// The facts of one case: its status, its ratios and times, its command
/// line's budget, and in-process (up to `IN_PROCESS_UP_TO`) its own.
fn record_case_facts(facts: &mut Facts, r: &Row) -> iga_contact::Result<()> {
    let key = format!("p{}_{}", r.p, r.n);
    facts.text(&format!("{key}_status"), "run")?;
    facts.timed_number(
        &format!("{key}_cli_ratio_first"),
        r.cli.wall / r.cholesky_first,
        Format::Times(1),
    )?;
    facts.timed_number(
        &format!("{key}_cli_cpu_ratio"),
        r.cli.cpu / r.cholesky_cpu,
        Format::Times(1),
    )?;
    facts.timed_number(
        &format!("{key}_cholesky_first_cpu_ratio"),
        r.cholesky_first_cpu / r.cholesky_cpu,
        Format::Times(1),
    )?;
    facts.timed_number(
        &format!("{key}_cholesky_first"),
        r.cholesky_first,
        Format::Fixed(1),
    )?;
    facts.timed_number(
        &format!("{key}_parts_gap"),
        (r.cli.timing.sum() - r.cli.wall).abs() / r.cli.wall,
        Format::Percent(1),
    )?;
    facts.timed_number(
        &format!("{key}_cli_post"),
        r.cli.timing.post_processing / r.cli.wall,
        Format::Percent(0),
    )?;
    facts.count(&format!("{key}_dofs"), r.dofs)?;
    let cli = &r.cli;
    facts.timed_number(
        &format!("{key}_cli_ratio"),
        cli.wall / r.cholesky,
        Format::Times(1),
    )?;
    facts.timed_number(&format!("{key}_cli_wall"), cli.wall, Format::Fixed(1))?;
    facts.timed_number(
        &format!("{key}_cli_peak_gb"),
        cli.peak / 1e9,
        Format::Fixed(1),
    )?;
    facts.timed_number(
        &format!("{key}_cli_outside_solve"),
        (cli.wall - cli.timing.factorisation - cli.timing.iterations) / cli.wall,
        Format::Percent(0),
    )?;
    facts.timed_number(&format!("{key}_cholesky"), r.cholesky, Format::Fixed(1))?;
    facts.count(&format!("{key}_iterations"), cli.iterations)?;
    facts.text(
        &format!("{key}_cli_budget"),
        cli.max_memory
            .map_or("the default memory budget".into(), |m| {
                format!("`--max-memory {m}` (the default budget refuses it)")
            }),
    )?;
    let Some(s) = &r.solve else { return Ok(()) };
    facts.timed_number(
        &format!("{key}_ratio"),
        s.total / r.cholesky,
        Format::Times(1),
    )?;
    facts.timed_number(&format!("{key}_total"), s.total, Format::Fixed(1))?;
    facts.timed_number(
        &format!("{key}_cpu_ratio"),
        s.total_cpu / r.cholesky_cpu,
        Format::Times(1),
    )?;
    facts.timed_number(&format!("{key}_peak_gb"), s.peak, Format::Fixed(1))?;
    facts.number(
        &format!("{key}_force_error"),
        s.force_error.max(1e-16),
        Format::Pow10(0),
    )?;
    Ok(())
}
