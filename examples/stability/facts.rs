//! The numbers the prose quotes: the counts of the outcomes, and each
//! case's measures.

use crate::atlas::{Row, Status};
use crate::cases::SHARP_SAFETY;
use crate::tables::PENALTY_TOLERANCE;
use companion::Facts;
use iga_contact::contact::Theta;
use iga_contact::error::{ErrorKind, Result};
use iga_contact::post::relative;
use iga_contact::report::table::Format;

// ANCHOR: facts
/// The prose counts the cases by outcome, and quotes the tolerance and the
/// sharp penalty's safety factor.
pub fn record_count_facts(f: &mut Facts, rows: &[Row]) -> Result<()> {
    f.count("cases", rows.len())?;
    let count = |pred: &dyn Fn(&Row) -> bool| rows.iter().filter(|r| pred(r)).count();
    f.count("converged", count(&|r| r.status == Status::Converged))?;
    f.count("failed", count(&|r| r.status == Status::Failed))?;
    f.count("no_contact", count(&|r| r.status == Status::NoContact))?;
    f.count("restarted", count(&|r| r.restarted()))?;
    f.count("warned_below_bound", count(&|r| r.below > 0))?;
    f.count(
        "singular",
        count(&|r| r.error_kind == ErrorKind::SingularKernel.tag()),
    )?;
    f.number("tolerance", PENALTY_TOLERANCE, Format::Percent(0))?;
    f.number("sharp_safety", SHARP_SAFETY, Format::Plain)
}

/// The facts' key of a case: its name with `_` for `.` and `-`, then the
/// θ (t1, t0, tm1).
fn fact_key(r: &Row) -> String {
    let theta = match r.theta {
        Theta::Symmetric => "t1",
        Theta::Incomplete => "t0",
        Theta::Skew => "tm1",
    };
    format!("{}_{theta}", r.case.replace(['.', '-'], "_"))
}

/// Every section quotes single cases: per case and θ, its error, p₀ and
/// reference, its points, its displacement, warnings, status and
/// iterations.
pub fn record_case_facts(f: &mut Facts, rows: &[Row]) -> Result<()> {
    for r in rows {
        let key = fact_key(r);
        if let Some(e) = r.error {
            f.number(&format!("{key}_error"), e, Format::Pow10(1))?;
            f.number(&format!("{key}_percent"), e, Format::Percent(1))?;
        }
        if let Some(p0) = r.p0 {
            f.number(&format!("{key}_p0"), p0 * 1e-6, Format::Pow10(2))?;
        }
        if let Some(p0) = r.reference {
            f.number(&format!("{key}_reference"), p0 * 1e-6, Format::Pow10(2))?;
        }
        if let Some(b) = r.single_point_bracket {
            f.number(&format!("{key}_bracket"), b * 1e-6, Format::Pow10(2))?;
        }
        if let Some(a) = r.active {
            f.count(&format!("{key}_active"), a)?;
        }
        f.count(&format!("{key}_below"), r.below)?;
        f.count(&format!("{key}_below_inactive"), r.below_inactive)?;
        f.count(&format!("{key}_singular_active"), r.singular_active)?;
        if let Some(u) = r.max_displacement {
            f.number(&format!("{key}_umax_mm"), u * 1e3, Format::Fixed(2))?;
        }
        f.count(&format!("{key}_warnings"), r.warnings.len())?;
        f.text(&format!("{key}_status"), r.status.key())?;
        f.count(&format!("{key}_iterations"), r.history.len())?;
    }
    Ok(())
}
/// "The penalty range of each θ" measures the penalty axis against the
/// paper's 8×8 setting, itself a coarse solution: each of its p₀ is also
/// set against the converged disk (the fine reference), signed.
pub fn record_fine_facts(f: &mut Facts, rows: &[Row], fine: f64) -> Result<()> {
    for r in rows
        .iter()
        .filter(|r| r.case.starts_with("hertz_8x8_penalty"))
    {
        if let Some(p0) = r.p0 {
            let key = format!("{}_vs_fine", fact_key(r));
            f.number(&key, relative(p0, fine), Format::SignedPercent(1))?;
        }
    }
    Ok(())
}
// ANCHOR_END: facts
