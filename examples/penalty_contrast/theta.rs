//! Table PS4: θ = 1 and θ = −1 on the default variant of the pair, and
//! θ = 1 on the rigid plane.

use crate::{disk_on_block, rigid, rigid_plane_p0, Both, Variant, CONTRAST_MESHES, RATIOS};
use companion::penalty::measure;
use companion::{Facts, Solver};
use iga_contact::contact::Theta;
use iga_contact::error::Result;
use iga_contact::post::{penalty_stability, relative};
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};

// ANCHOR: contrast_theta
/// θ = 1 and θ = −1, in the column order of Table PS4.
const OTHER_THETAS: [Theta; 2] = [Theta::Symmetric, Theta::Skew];

/// One row of Table PS4: the default variant on one mesh at one ratio.
pub struct ThetaRow {
    elements: usize,
    ratio: f64,
    /// In the order of `OTHER_THETAS`.
    runs: Vec<ThetaRun>,
}

struct ThetaRun {
    /// p₀ of BFGS against the rigid plane with θ = 0; `None` if BFGS
    /// failed.
    deviation: Option<f64>,
    /// Newton failed (counted with BFGS's failures, as in Table PS3).
    newton_failed: bool,
    iterations: Cell,
}

/// The disk on the rigid plane with θ = 1 (16²).
pub struct RigidTheta1 {
    active: usize,
    active_below: usize,
    /// p₀ against θ = 0 on the same mesh.
    vs_theta0: f64,
}

/// Every mesh and ratio of Table PS4, with both θ.
pub fn solve_thetas() -> Result<Vec<ThetaRow>> {
    let mut rows = Vec::new();
    for n in CONTRAST_MESHES {
        let rigid0 = rigid_plane_p0(n, Theta::Incomplete, 1.0)?;
        for ratio in RATIOS {
            let mut runs = Vec::new();
            for theta in OTHER_THETAS {
                let problem = disk_on_block(n, ratio, Variant::Slave, theta)?;
                let r = Both::solve(&problem)?;
                runs.push(ThetaRun {
                    deviation: r.bfgs.as_ref().ok().map(|o| relative(o.p0, rigid0)),
                    newton_failed: r.newton.is_err(),
                    iterations: r.iterations(),
                });
            }
            rows.push(ThetaRow {
                elements: n,
                ratio,
                runs,
            });
        }
    }
    Ok(rows)
}

/// Table PS4.
pub fn theta_table(rows: &[ThetaRow]) -> Result<Table> {
    let mut table = Table::new(vec![
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        Column::new("ratio", "E_b/E_d", Unit::None, Format::Sci(0)),
        Column::new("p0_theta1", "θ = 1", Unit::None, Format::SignedPercent(2)),
        Column::plain("its_theta1", "its"),
        Column::new(
            "p0_theta_minus1",
            "θ = −1",
            Unit::None,
            Format::SignedPercent(2),
        ),
        Column::plain("its_theta_minus1", "its"),
    ]);
    for r in rows {
        let mut row: Vec<Cell> = vec![r.elements.into(), r.ratio.into()];
        for run in &r.runs {
            row.push(run.deviation.map_or(Cell::Empty, Cell::from));
            row.push(run.iterations.clone());
        }
        table.push(row)?;
    }
    Ok(table)
}

/// The rigid plane with θ = 1 and (11): below its bound at every active
/// point.
pub fn solve_rigid_theta1() -> Result<RigidTheta1> {
    let problem = rigid(16, Theta::Symmetric, 1.0)?;
    let o = measure(&problem, &Solver::Bfgs.options())?.expect("θ = 1 converges");
    let st = penalty_stability(&problem, &o.solution.full)[0];
    Ok(RigidTheta1 {
        active: st.active,
        active_below: st.active_below,
        vs_theta0: relative(o.p0, rigid_plane_p0(16, Theta::Incomplete, 1.0)?),
    })
}

/// The summary of Table PS4, the failures over both tables, and θ = 1 on
/// the rigid plane.
pub fn record_theta_facts(
    f: &mut Facts,
    rows: &[ThetaRow],
    rigid: &RigidTheta1,
    contrast_failures: usize,
) -> Result<()> {
    // ratio ≥ 10²: a stiff block
    let worst = |k: usize| {
        rows.iter()
            .filter(|r| r.ratio >= 1e2)
            .filter_map(|r| r.runs[k].deviation)
            .fold(0.0f64, |a, d| a.max(d.abs()))
    };
    f.number("theta1_worst_stiff", worst(0), Format::Percent(1))?;
    f.number("theta_minus1_worst_stiff", worst(1), Format::Percent(1))?;
    let failures = rows
        .iter()
        .flat_map(|r| &r.runs)
        .filter(|run| run.deviation.is_none() || run.newton_failed)
        .count();
    f.count("contrast_all_failures", contrast_failures + failures)?;
    f.count("rigid_theta1_active", rigid.active)?;
    f.count("rigid_theta1_below", rigid.active_below)?;
    f.number(
        "rigid_theta1_vs_theta0_16",
        rigid.vs_theta0,
        Format::SignedPercent(1),
    )
}
// ANCHOR_END: contrast_theta
