//! One case of the atlas solved with the default solver, its outcome
//! classified and measured; and the whole atlas, case by case.

use crate::{Case, Metric};
use iga_contact::assembly::strain_stress;
use iga_contact::contact::Theta;
use iga_contact::error::{Error, Result};
use iga_contact::post::{relative, PressureProfile};
use iga_contact::problem::Problem;
use iga_contact::solver::history::{Event, History};
use iga_contact::solver::warning::OVER_PENALTY;
use iga_contact::solver::{solve, Solution, SolverOptions, Warning};

/// How a case ended.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// Converged, with contact.
    Converged,
    /// Converged with no active contact point.
    NoContact,
    /// A typed error.
    Failed,
}

impl Status {
    /// The name the atlas and the facts use.
    pub fn key(self) -> &'static str {
        match self {
            Status::Converged => "converged",
            Status::NoContact => "no_contact",
            Status::Failed => "failed",
        }
    }
}

/// One row of the atlas.
pub struct Row {
    pub case: String,
    pub theta: Theta,
    pub penalty_factor: f64,
    pub status: Status,
    pub history: History,
    pub error: Option<f64>,
    /// The measured p₀ (peak-pressure cases that converged) and its reference.
    pub p0: Option<f64>,
    pub reference: Option<f64>,
    /// Active points at the solution, and how many of them have a penalty
    /// below the stability bound.
    pub active: Option<usize>,
    pub below: usize,
    /// Inactive points below the bound. For θ = 1 they matter too: every
    /// point, active or not, adds −(θ/γ) w sₙsₙᵀ to the tangent, negative
    /// semidefinite for θ > 0, so coercivity needs γ above the bound there
    /// as well. The solver's warning counts them too, against θ·C_T.
    pub below_inactive: usize,
    /// Active points on a singular element (at the degenerate (det J = 0)
    /// corner of the disk), which the library counts but never judges.
    pub singular_active: usize,
    /// The largest displacement component at the solution (m).
    pub max_displacement: Option<f64>,
    /// γ g₀ of the only active point, when one point carries the contact:
    /// the penalty bracket at the axis once the disk has sunk to it.
    pub single_point_bracket: Option<f64>,
    pub warnings: Vec<Warning>,
    pub error_kind: String,
    pub diagnosis: String,
}

impl Row {
    pub fn restarted(&self) -> bool {
        self.history.count(|e| *e == Event::Restart) > 0
    }

    /// The short note of the Markdown tables: a restart, and the warnings.
    pub fn note(&self) -> String {
        let mut parts = Vec::new();
        if self
            .active
            .is_some_and(|a| a > 0 && a == self.singular_active)
        {
            parts.push("p₀ not measured: every active point on det J = 0".to_string());
        }
        if self.restarted() {
            parts.push("restarted".to_string());
        }
        for w in &self.warnings {
            parts.push(match w {
                Warning::PenaltyBelowBound { below, active, .. } => {
                    format!("γ < bound at {below}/{active}")
                }
                Warning::UnresolvedContact { active, .. } => {
                    format!(
                        "{active} active point{}",
                        if *active == 1 { "" } else { "s" }
                    )
                }
                Warning::PenaltyFarAboveBound { over, active, .. } => {
                    format!("γ > {OVER_PENALTY} × bound at {over}/{active}")
                }
                Warning::PenaltyLoose { .. } => "loose penalty (θ = −1)".to_string(),
                Warning::StifferSlave { .. } => "stiffer slave".to_string(),
                Warning::NearlyIncompressible { .. } => "locking".to_string(),
                Warning::ZoneAtSideEnd { .. } => "zone at side end".to_string(),
                Warning::ClosedFacingAway { .. } => "closed facing away".to_string(),
                Warning::SeveralZones { zones, .. } => format!("{} zones", zones.len()),
                Warning::CoarseZone { .. } => "coarse zone".to_string(),
            });
        }
        parts.join("; ")
    }
}

/// The largest relative deviation of σ_yy from `exact` over the bulk
/// quadrature points.
fn max_syy_error(p: &Problem, s: &Solution, exact: f64) -> Result<f64> {
    let mut worst: f64 = 0.0;
    for (b, body) in p.bodies.iter().enumerate() {
        for el in &body.space.elements {
            for qp in body.space.quadrature(el)? {
                let (_, sig) =
                    strain_stress(&p.bodies, &p.map, &s.full, b, qp.param[0], qp.param[1])?;
                worst = worst.max(relative(sig[1], exact).abs());
            }
        }
    }
    Ok(worst)
}

// ANCHOR: run
/// Solves one case with the default solver and classifies the outcome.
pub fn run_case(case: &Case) -> Row {
    let mut row = Row {
        case: case.name.clone(),
        theta: case.theta,
        penalty_factor: case.penalty_factor,
        status: Status::Failed,
        history: History::default(),
        error: None,
        p0: None,
        reference: match case.metric {
            Metric::PeakPressure(r) => Some(r),
            _ => None,
        },
        active: None,
        below: 0,
        below_inactive: 0,
        singular_active: 0,
        max_displacement: None,
        single_point_bracket: None,
        warnings: Vec::new(),
        error_kind: String::new(),
        diagnosis: String::new(),
    };
    let solved = case.scene.build().and_then(|p| {
        let s = solve(&p, &SolverOptions::default())?;
        Ok((p, s))
    });
    let (p, s) = match solved {
        Ok(ps) => ps,
        Err(e) => {
            if let Error::NotConverged { history, .. } = &e {
                row.history = history.clone();
            }
            row.error_kind = e.kind().tag().into();
            row.diagnosis = e.to_string();
            return row;
        }
    };
    row.history = s.history.clone();
    row.warnings = s.warnings.clone();
    let active: Vec<_> = p.points.iter().filter(|cp| cp.p(&s.full) <= 0.0).collect();
    row.active = Some(active.len());
    row.below = active
        .iter()
        .filter(|cp| cp.below_stability_bound())
        .count();
    row.below_inactive = p
        .points
        .iter()
        .filter(|cp| cp.p(&s.full) > 0.0 && cp.below_stability_bound())
        .count();
    row.singular_active = active.iter().filter(|cp| !cp.regular).count();
    row.max_displacement = Some(s.full.iter().fold(0.0, |m: f64, u| m.max(u.abs())));
    if let [only] = active.as_slice() {
        row.single_point_bracket = Some(only.gamma * only.g0);
    }
    let error = match case.metric {
        // The profile is sampled where the map is regular: with every active
        // point on the degenerate corner it has no pressure to measure, and a
        // deviation of 1 would only say so.
        Metric::PeakPressure(_) if !active.is_empty() && row.singular_active == active.len() => {
            Ok(None)
        }
        Metric::PeakPressure(reference) => PressureProfile::dense(&p, &s.full).map(|prof| {
            let p0 = prof.measures(0).p0;
            row.p0 = Some(p0);
            Some(relative(p0, reference).abs())
        }),
        Metric::UniformStress(exact) => max_syy_error(&p, &s, exact).map(Some),
        Metric::NoContact => Ok(None),
    };
    match error {
        Err(e) => {
            row.error_kind = e.kind().tag().into();
            row.diagnosis = e.to_string();
        }
        Ok(_) if matches!(case.metric, Metric::NoContact) && !active.is_empty() => {
            row.error_kind = "unexpected_contact".into();
        }
        Ok(e) => {
            row.error = e;
            row.status = if active.is_empty() {
                Status::NoContact
            } else {
                Status::Converged
            };
        }
    }
    row
}
// ANCHOR_END: run

/// Every case solved in turn, with its outcome and warnings reported on
/// standard error as it goes.
pub fn run_atlas(all: &[Case]) -> Vec<Row> {
    let mut rows = Vec::with_capacity(all.len());
    for (k, case) in all.iter().enumerate() {
        let row = run_case(case);
        eprintln!(
            "  [{}/{}] {} θ = {} → {} {}",
            k + 1,
            all.len(),
            row.case,
            row.theta,
            row.status.key(),
            row.error_kind
        );
        for w in &row.warnings {
            eprintln!("      warning: {w}");
        }
        rows.push(row);
    }
    rows
}
