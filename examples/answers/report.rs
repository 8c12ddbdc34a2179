//! The answers as the chapter shows them: the verdicts per class, the
//! silent wrong and unclean answers, the two scale sweeps, the pressed
//! blocks; and what the facts quote of them.

use crate::cases::Class;
use crate::judge::{run, Answer, Answers, Verdict};
use crate::scenes::SceneSolver;
use companion::chapter::Chapter;
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};
use iga_contact::Result;
use std::path::Path;

/// What the chapter quotes of the answers.
pub struct Summary {
    pub cases: usize,
    pub launches: usize,
    pub silent_wrong: usize,
    pub unclean: usize,
    /// The largest |p₀/p₀(L = 1) − 1| over the length and stiffness
    /// sweeps that answered, and whether every answer took the iterations
    /// of the unscaled one.
    pub scale_spread: f64,
    pub scale_same_iterations: bool,
    /// The largest |p₀/p₀(closed form) − 1| of the pressed blocks.
    pub prescribed_error: f64,
    /// The largest peak resident memory of a `run`, bytes.
    pub peak_bytes: f64,
}

/// Runs the answers in `work` and writes their tables into `chapter`:
/// `answers` (verdicts per class), `answers_silent.md` (every silent wrong
/// answer), `answers_unclean.md`, `scale` (the two sweeps), `prescribed`
/// (the pressed blocks).
pub fn report(work: &Path, chapter: &mut Chapter) -> Result<Summary> {
    let Answers { answers, launches } = run(work)?;
    chapter.table("answers", &verdict_table(&answers)?)?;
    chapter.text("answers_silent.md", &silent_list(&answers))?;
    chapter.text("answers_unclean.md", &unclean_list(&answers))?;
    let scale = scale_sweeps(&answers)?;
    chapter.table("scale", &scale.table)?;
    let prescribed = prescribed_blocks(&answers)?;
    chapter.table("prescribed", &prescribed.table)?;
    let count = |v: Verdict| answers.iter().filter(|a| a.verdict == v).count();
    Ok(Summary {
        cases: answers.len(),
        launches,
        silent_wrong: count(Verdict::SilentWrong),
        unclean: count(Verdict::Unclean),
        scale_spread: scale.spread,
        scale_same_iterations: scale.same_iterations,
        prescribed_error: prescribed.worst,
        peak_bytes: answers.iter().map(|a| a.peak_bytes).fold(0.0, f64::max),
    })
}

/// The verdicts, class by class.
fn verdict_table(answers: &[Answer]) -> Result<Table> {
    let mut columns = vec![Column::plain("class", "class")];
    for v in Verdict::ALL {
        columns.push(Column::plain(v.label(), v.label()));
    }
    let mut counts = Table::new(columns);
    for class in Class::ALL {
        let mut row: Vec<Cell> = vec![class.label().into()];
        for v in Verdict::ALL {
            row.push(
                answers
                    .iter()
                    .filter(|a| a.class == class && a.verdict == v)
                    .count()
                    .into(),
            );
        }
        counts.push(row)?;
    }
    Ok(counts)
}

/// Every silent wrong answer and how far off it is.
fn silent_list(answers: &[Answer]) -> String {
    answers
        .iter()
        .filter(|a| a.verdict == Verdict::SilentWrong)
        .map(|a| {
            format!(
                "- {}: p₀ {} off its reference\n",
                a.label,
                Format::SignedPercent(1).render(a.error)
            )
        })
        .collect()
}

/// Every launch that did not end cleanly, and what it said.
fn unclean_list(answers: &[Answer]) -> String {
    answers
        .iter()
        .filter(|a| a.verdict == Verdict::Unclean)
        .map(|a| format!("- {}: {}\n", a.label, a.message))
        .collect()
}

/// The scale sweeps: iterations and p₀ against the unscaled run.
struct ScaleSweeps {
    table: Table,
    /// The largest |p₀/p₀(1) − 1| of an answer.
    spread: f64,
    /// Whether every run answered, in the iterations of the unscaled one.
    same_iterations: bool,
}

fn scale_sweeps(answers: &[Answer]) -> Result<ScaleSweeps> {
    let mut scale = Table::new(vec![
        Column::plain("sweep", "sweep"),
        Column::plain("solver", "solver"),
        Column::plain("factor", "factor"),
        Column::plain("iterations", "iterations"),
        Column::new("p0_deviation", "p₀ / p₀(1) − 1", Unit::None, Format::Sci(1)),
    ]);
    let mut spread: f64 = 0.0;
    let mut same = true;
    for (class, sweep) in [(Class::LengthScale, "L"), (Class::StiffnessScale, "s")] {
        for solver in SceneSolver::ALL {
            let runs: Vec<&Answer> = answers
                .iter()
                .filter(|a| a.class == class && a.label.ends_with(solver.label()))
                .collect();
            let unit = runs
                .iter()
                .find(|a| a.label.contains("= 1e0,"))
                .map(|a| (a.error, a.iterations));
            for a in &runs {
                let factor = a
                    .label
                    .split(" = ")
                    .nth(1)
                    .and_then(|s| s.split(',').next())
                    .unwrap_or("?")
                    .to_string();
                let deviation = match (unit, a.verdict) {
                    (Some((e1, _)), Verdict::Right | Verdict::WarnedRight) => {
                        (1.0 + a.error) / (1.0 + e1) - 1.0
                    }
                    _ => f64::NAN,
                };
                if deviation.is_finite() {
                    spread = spread.max(deviation.abs());
                } else {
                    same = false;
                }
                if unit.map(|u| u.1) != Some(a.iterations) {
                    same = false;
                }
                let its: Cell = match a.iterations {
                    Some(i) => (i as usize).into(),
                    None => a.verdict.label().into(),
                };
                let dev: Cell = if deviation.is_finite() {
                    deviation.into()
                } else {
                    "–".into()
                };
                scale.push(vec![
                    sweep.into(),
                    solver.label().into(),
                    factor.into(),
                    its,
                    dev,
                ])?;
            }
        }
    }
    Ok(ScaleSweeps {
        table: scale,
        spread,
        same_iterations: same,
    })
}

/// The pressed blocks against their closed form.
struct PrescribedBlocks {
    table: Table,
    /// The largest |p₀/p₀(closed form) − 1| (infinite if one did not
    /// answer).
    worst: f64,
}

fn prescribed_blocks(answers: &[Answer]) -> Result<PrescribedBlocks> {
    let mut prescribed = Table::new(vec![
        Column::plain("case", "case"),
        Column::plain("verdict", "verdict"),
        Column::new("error", "p₀ / closed form − 1", Unit::None, Format::Sci(1)),
    ]);
    let mut worst: f64 = 0.0;
    for a in answers.iter().filter(|a| a.class == Class::Prescribed) {
        if a.error.is_finite() {
            worst = worst.max(a.error.abs());
        } else {
            worst = f64::INFINITY;
        }
        let e: Cell = if a.error.is_finite() {
            a.error.into()
        } else {
            "–".into()
        };
        prescribed.push(vec![a.label.clone().into(), a.verdict.label().into(), e])?;
    }
    Ok(PrescribedBlocks {
        table: prescribed,
        worst,
    })
}
