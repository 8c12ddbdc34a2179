//! "The sharp penalty as an option": the Hertz disk with (11) and with the
//! sharp penalty, for the three θ (Table PS2).

use crate::ratios::first_touch;
use companion::penalty::{hertz, measure};
use companion::{Facts, Solver};
use iga_contact::contact::penalty::stability_bound;
use iga_contact::contact::{PenaltyKind, Theta};
use iga_contact::error::Result;
use iga_contact::post::{penalty_stability, relative};
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};

// ANCHOR: sharp
/// What the runs with (11) and with the sharp penalty give Table PS2 and
/// its facts.
pub struct SharpRuns {
    pub table: Table,
    /// [mesh][choice]: the spread of p₀ over θ, over the paper's p₀.
    theta_spread: [[f64; 3]; 2],
    /// θ = 1 with (11), per mesh.
    theta1_empirical: [BelowBound; 2],
}

/// The points of a solution with a penalty below the stability bound.
#[derive(Clone, Copy, Default)]
struct BelowBound {
    /// Active points below C_T.
    active: usize,
    /// Regular inactive points below θ·C_T.
    inactive: usize,
}

/// "The sharp penalty as an option": the Hertz disk with (11) and with the
/// sharp penalty at safety factors 1 and 2, for the three θ.
pub fn compare_sharp_penalty() -> Result<SharpRuns> {
    let mut table = Table::new(vec![
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        Column::plain("theta", "θ"),
        Column::plain("penalty", "penalty"),
        Column::new("gamma_over_bound", "γ/bound", Unit::None, Format::Fixed(2)),
        Column::plain("iterations", "its"),
        Column::new(
            "p0_vs_paper",
            "p₀ vs (11), θ = 0",
            Unit::None,
            Format::SignedPercent(2),
        ),
        Column::plain("below", "below"),
        Column::plain("inactive_below", "inactive below"),
    ]);
    let choices = [
        ("(11)", PenaltyKind::Empirical, 1.0),
        ("sharp ×1", PenaltyKind::Sharp, 1.0),
        ("sharp ×2", PenaltyKind::Sharp, 2.0),
    ];
    let mut theta_spread = [[0.0f64; 3]; 2];
    let mut theta1_empirical = [BelowBound::default(); 2];
    for (im, n) in [16usize, 32].into_iter().enumerate() {
        let paper = measure(&hertz(n, |_| ())?, &Solver::Bfgs.options())?
            .expect("the paper's setting converges")
            .p0;
        for (ic, &(label, penalty, factor)) in choices.iter().enumerate() {
            let mut p0s = Vec::new();
            for theta in Theta::ALL {
                let problem = hertz(n, |x| {
                    x.theta = theta;
                    x.penalty = penalty;
                    x.penalty_factor = factor;
                })?;
                let cp = first_touch(&problem);
                // θ = −1 has no bound: the column shows γ over the bound of θ = 0
                let bound = stability_bound(cp.trace_constant, theta.value().max(0.0));
                let o = measure(&problem, &Solver::Bfgs.options())?;
                let (its, p0, below, inactive): (Cell, Cell, Cell, Cell) = match &o {
                    Ok(o) => {
                        p0s.push(o.p0);
                        let st = penalty_stability(&problem, &o.solution.full)[0];
                        if theta == Theta::Symmetric && ic == 0 {
                            theta1_empirical[im] = BelowBound {
                                active: st.active_below,
                                inactive: st.inactive_below,
                            };
                        }
                        (
                            o.solution.history.len().into(),
                            relative(o.p0, paper).into(),
                            st.active_below.into(),
                            st.inactive_below.into(),
                        )
                    }
                    Err(kind) => ((*kind).into(), Cell::Empty, Cell::Empty, Cell::Empty),
                };
                table.push(vec![
                    n.into(),
                    theta.to_string().into(),
                    label.into(),
                    (cp.gamma / bound).into(),
                    its,
                    p0,
                    below,
                    inactive,
                ])?;
            }
            let lo = p0s.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = p0s.iter().copied().fold(0.0, f64::max);
            theta_spread[im][ic] = (hi - lo) / paper;
        }
    }
    Ok(SharpRuns {
        table,
        theta_spread,
        theta1_empirical,
    })
}

/// The prose under Table PS2 quotes how far the three θ spread p₀, and
/// how many points θ = 1 with (11) leaves below its bound.
pub fn record_sharp_facts(f: &mut Facts, sharp: &SharpRuns) -> Result<()> {
    // per mesh, per choice of Table PS2: (11), sharp ×1, sharp ×2
    for (im, n) in [16usize, 32].into_iter().enumerate() {
        for (ic, choice) in ["empirical", "sharp1", "sharp2"].into_iter().enumerate() {
            f.number(
                &format!("theta_spread_{choice}_{n}"),
                sharp.theta_spread[im][ic],
                Format::Percent(1),
            )?;
        }
    }
    for (im, n) in [16usize, 32].into_iter().enumerate() {
        let below = sharp.theta1_empirical[im];
        f.number(
            &format!("theta1_active_below_{n}"),
            below.active as f64,
            Format::Fixed(0),
        )?;
        f.number(
            &format!("theta1_inactive_below_{n}"),
            below.inactive as f64,
            Format::Fixed(0),
        )?;
    }
    Ok(())
}
// ANCHOR_END: sharp
