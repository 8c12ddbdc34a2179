//! "Small penalties: where the answer stops being unique": (11) scaled
//! down on the Hertz disk, solved by three solvers (Table PS5).

use companion::penalty::{hertz, measure};
use companion::{Facts, Solver};
use iga_contact::contact::Theta;
use iga_contact::error::Result;
use iga_contact::post::{penalty_stability, relative};
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};

// ANCHOR: small
/// What the sweep of small penalties gives Table PS5 and its facts.
pub struct SmallSweep {
    pub table: Table,
    /// θ = 1: the fewest regular inactive points below θ·C_T over the
    /// converged rows (a fact, not a column: the table is at the page's
    /// width).
    theta1_inactive: usize,
    /// Per θ: the smallest factor from which on the solvers agree.
    unique_from: [f64; 3],
}

/// "Small penalties: where the answer stops being unique": (11) scaled
/// down on the Hertz disk (8², p = 2), solved by three solvers.
pub fn sweep_small_penalties() -> Result<SmallSweep> {
    const FACTORS: [f64; 6] = [1e-4, 1e-3, 1e-2, 1e-1, 0.3, 1.0];
    // in the column order of the table
    let solvers = [Solver::Bfgs, Solver::Newton, Solver::Paper];
    let paper_setting = measure(&hertz(8, |_| ())?, &Solver::Bfgs.options())?
        .expect("the paper's setting converges")
        .p0;
    let mut small = Table::new(vec![
        Column::plain("theta", "θ"),
        Column::new("factor", "factor", Unit::None, Format::Sci(0)),
        Column::new("ratio", "γ/bound", Unit::None, Format::Sci(1)),
        Column::new("p0_bfgs", "BFGS", Unit::None, Format::SignedPercent(1)),
        Column::new("p0_newton", "Newton", Unit::None, Format::SignedPercent(1)),
        Column::new("p0_paper", "paper's", Unit::None, Format::SignedPercent(1)),
        Column::plain("zones", "zones"),
        Column::new("overlap", "overlap", Unit::Millimetre, Format::Fixed(3)),
    ]);
    let mut theta1_inactive = usize::MAX;
    let mut unique_from = [f64::INFINITY; 3];
    for (it, theta) in Theta::ALL.into_iter().enumerate() {
        for factor in FACTORS {
            let problem = hertz(8, |x| {
                x.theta = theta;
                x.penalty_factor = factor;
            })?;
            let mut row: Vec<Cell> = vec![theta.to_string().into(), factor.into()];
            let outcomes: Vec<_> = solvers
                .iter()
                .map(|s| measure(&problem, &s.options()))
                .collect::<Result<_>>()?;
            // the smallest γ/bound over the active points and the largest
            // overlap −g_n, of the first solver that converged
            let first_ok = outcomes.iter().find_map(|o| o.as_ref().ok());
            let (r, overlap) = match first_ok {
                Some(o) => {
                    let st = penalty_stability(&problem, &o.solution.full)[0];
                    let overlap = problem
                        .points
                        .iter()
                        .map(|cp| cp.normal_stress_and_jump(&o.solution.full).1 - cp.g0)
                        .fold(f64::NEG_INFINITY, f64::max);
                    if theta == Theta::Symmetric {
                        theta1_inactive = theta1_inactive.min(st.inactive_below);
                    }
                    (
                        st.min_active_ratio
                            .map(Cell::from)
                            .unwrap_or_else(|| "none".into()),
                        Cell::from(overlap),
                    )
                }
                None => (Cell::Empty, Cell::Empty),
            };
            row.push(r);
            for o in &outcomes {
                row.push(match o {
                    Ok(o) => relative(o.p0, paper_setting).into(),
                    Err(_) => "failed".into(),
                });
            }
            let zones: Vec<String> = outcomes
                .iter()
                .map(|o| o.as_ref().map_or("–".to_string(), |o| o.zones.to_string()))
                .collect();
            row.push(zones.join(" / ").into());
            row.push(overlap);
            small.push(row)?;
            // the solvers that converge agree (at least two, the same p₀ to
            // 10⁻⁶); a solver that fails is shown in the table
            let p0s: Vec<f64> = outcomes
                .iter()
                .filter_map(|o| o.as_ref().ok().map(|o| o.p0))
                .collect();
            let agree = p0s.len() >= 2 && p0s.iter().all(|&p| relative(p, p0s[0]).abs() < 1e-6);
            if agree {
                unique_from[it] = unique_from[it].min(factor);
            } else {
                unique_from[it] = f64::INFINITY;
            }
        }
    }
    Ok(SmallSweep {
        table: small,
        theta1_inactive,
        unique_from,
    })
}

/// The bullets under Table PS5 quote, per θ, the factor from which on the
/// solvers agree.
pub fn record_small_facts(f: &mut Facts, small: &SmallSweep) -> Result<()> {
    f.number(
        "theta1_small_inactive_below_min",
        small.theta1_inactive as f64,
        Format::Fixed(0),
    )?;
    for (it, key) in ["theta1", "theta0", "theta_minus1"].iter().enumerate() {
        match small.unique_from[it] {
            v if v.is_finite() => f.number(&format!("{key}_agree_from"), v, Format::Pow10(0))?,
            _ => f.text(&format!("{key}_agree_from"), "never")?,
        }
    }
    Ok(())
}
// ANCHOR_END: small
