//! What a run reports: [`RunReport`] to the caller, `summary.toml` and the
//! pressure-profile table to the output directory.

use crate::contact::Contacts;
use crate::error::Result;
use crate::history::History;
use crate::post::PressureProfile;
use crate::report::table::{Column, Format, Table, Unit};
use crate::solver::{self, SolverOptions};
use crate::timing::PhaseTimes;
use serde::Serialize;
use std::fmt;
use std::path::PathBuf;

/// What a [`Scene::run`](super::Scene::run) did.
#[derive(Clone, Debug, PartialEq)]
pub struct RunReport {
    /// Free degrees of freedom.
    pub dofs: usize,
    pub iterations: usize,
    pub corrections: usize,
    /// Contact points with P ≤ 0 at the solution, and in all.
    pub active_points: usize,
    pub contact_points: usize,
    /// Resultant force the masters exert on the slaves.
    pub contact_force: [f64; 2],
    /// Resultant of the external loads (computed only for the summary).
    pub applied_force: Option<[f64; 2]>,
    /// Files written (committed together), sorted by name.
    pub files: Vec<PathBuf>,
    /// Wall-clock time of build, solve and output.
    pub seconds: f64,
    /// The same, split by phase ([`PhaseTimes`]).
    pub timing: PhaseTimes,
    /// What the solution may not be ([`solver::Warning`]), one per cause,
    /// each with one remedy: a converged run is reported with them, never
    /// silently.
    pub warnings: Vec<solver::Warning>,
}

impl fmt::Display for RunReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "converged in {} iteration{} ({} correction{}), {} DOFs, {}/{} contact points active, \
             contact force ({:.6e}, {:.6e}), {:.2} s",
            self.iterations,
            if self.iterations == 1 { "" } else { "s" },
            self.corrections,
            if self.corrections == 1 { "" } else { "s" },
            self.dofs,
            self.active_points,
            self.contact_points,
            self.contact_force[0],
            self.contact_force[1],
            self.seconds
        )?;
        // The warnings are lines of their own (the tool prints them on
        // stderr), so that the place written to follows the files.
        match self.files.len() {
            0 => write!(f, "; no outputs requested"),
            1 => write!(f, "; wrote 1 file"),
            n => write!(f, "; wrote {n} files"),
        }
    }
}

/// The summary file, `summary.toml`.
#[derive(Serialize)]
pub(super) struct Summary<'a> {
    pub(super) title: &'a str,
    pub(super) dofs: usize,
    pub(super) iterations: usize,
    pub(super) corrections: usize,
    pub(super) relative_residual: f64,
    pub(super) contact_points: usize,
    pub(super) active_points: usize,
    pub(super) contact_force: [f64; 2],
    pub(super) applied_force: [f64; 2],
    /// One entry per contact pair: p0, half_width, contact force.
    pub(super) contact: Vec<PairSummary>,
    /// The run's warnings ([`solver::Warning`]), one line per cause; absent
    /// when there is none.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub(super) warnings: Vec<String>,
    /// The solver options as TOML (a `usize::MAX` limit, which TOML cannot
    /// hold, is written as the largest TOML integer).
    pub(super) solver: toml::Value,
    /// Seconds per phase of the run up to this file, and the wall time;
    /// the file's own writing and the commit of the outputs come after.
    pub(super) timing: PhaseTimes,
}

/// What `summary.toml` reports of one contact pair, measured by
/// [`crate::post`] on the dense pressure profile.
#[derive(Serialize)]
pub(super) struct PairSummary {
    /// Peak contact pressure of the main zone; absent when the profile
    /// finds no zone (`zones = 0`), as are the two below.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) p0: Option<f64>,
    /// Contact half-width, along the contact tangent at the peak.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) half_width: Option<f64>,
    /// Separate contact zones (1: one connected zone).
    pub(super) zones: usize,
    /// The largest pressure over every zone (p0 describes the main one).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) p_max: Option<f64>,
    /// Force of the master on the slave.
    pub(super) contact_force: [f64; 2],
    /// Active contact points whose penalty γ lies below the stability bound
    /// of the pair's θ ([`post::penalty_stability`]); 0 is the safe answer.
    pub(super) penalty_below_bound_points: usize,
    /// The smallest γ / bound over the active points (below 1: unstable);
    /// absent when no active point has a positive bound (θ = −1).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) min_penalty_ratio: Option<f64>,
}

/// `opts` as a TOML table, saturating integers beyond TOML's i64 range.
pub(super) fn solver_table(opts: &SolverOptions) -> toml::Value {
    if let Ok(v) = toml::Value::try_from(opts) {
        return v;
    }
    let mut clamped = *opts;
    for v in [
        &mut clamped.max_iter,
        &mut clamped.correction_after,
        &mut clamped.line_search_after,
    ] {
        *v = (*v).min(i64::MAX as usize);
    }
    toml::Value::try_from(clamped).unwrap_or_else(|_| toml::Value::String(format!("{opts:?}")))
}

/// The relative residual a converged run ends with; a run that needed no
/// iteration (nothing to balance: zero load) ends with 0, not 1.
pub(super) fn final_relative_residual(h: &History) -> f64 {
    match h.rows.last() {
        Some(r) => r.relative_residual,
        None if h.initial_residual == 0.0 => 0.0,
        None => 1.0,
    }
}

/// `v` with a negative zero turned into +0 (IEEE: −0 + 0 = +0), so that no
/// output shows `-0`.
pub(super) fn no_negative_zero(v: f64) -> f64 {
    v + 0.0
}

/// The dense pressure profile as a table: contact (its index among the
/// scene's `[[contact]]` entries, as in `summary.toml`, whatever the number
/// of patch sides its slave boundary crosses), position, bracket, pressure,
/// and whether the map is regular there (1) or singular (0: the bracket is
/// 1/det J of the stress, and the measures of `summary.toml` skip it).
pub(super) fn profile_table(profile: &PressureProfile, contacts: &Contacts) -> Result<Table> {
    let mut t = Table::new(vec![
        Column::plain("contact", "contact"),
        Column::new("x", "x", Unit::None, Format::Sci(6)),
        Column::new("y", "y", Unit::None, Format::Sci(6)),
        Column::new("bracket", "P", Unit::None, Format::Sci(6)),
        Column::new("pressure", "pressure", Unit::None, Format::Sci(6)),
        Column::plain("regular", "regular map"),
    ]);
    for s in profile.samples() {
        t.push(vec![
            contacts.of(s.pair).into(),
            s.x[0].into(),
            s.x[1].into(),
            s.bracket.into(),
            s.pressure().into(),
            usize::from(s.regular).into(),
        ])?;
    }
    Ok(t)
}
