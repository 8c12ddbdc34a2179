//! Table PS3 and Fig. PS2: the disk on the block, each variant of the pair
//! solved by both solvers at every stiffness ratio and mesh, against the
//! disk on the rigid plane; and the facts of their summary.

use crate::{disk_on_block, rigid_plane_p0, Both, Variant, CONTRAST_MESHES, RATIOS};
use companion::chapter::Chapter;
use companion::Facts;
use iga_contact::contact::{Role, Theta};
use iga_contact::error::Result;
use iga_contact::post::{self, relative};
use iga_contact::problem::Problem;
use iga_contact::report::plot::{line_chart, Axes, Series};
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};

/// The share of the contact force carried by the disk's half of the
/// unbiased form, Σ w [P]₋ over its points against both halves.
fn disk_share(problem: &Problem, full: &[f64]) -> f64 {
    let half = |role: Role| -> f64 {
        problem
            .points
            .iter()
            .filter(|cp| cp.role == role)
            .map(|cp| cp.weight * cp.p(full).min(0.0))
            .sum()
    };
    let (disk, block) = (half(Role::Slave), half(Role::Master));
    disk / (disk + block)
}

/// How far apart the two halves of the unbiased form see the bodies: the
/// mean gap g_n over the active points of the block's half minus that of
/// the disk's half. Near zero when both halves measure one gap function;
/// two different linearised gaps would make the halves' penalties pull
/// against each other.
fn gap_mismatch(problem: &Problem, full: &[f64]) -> f64 {
    let mean = |role: Role| -> f64 {
        let active: Vec<f64> = problem
            .points
            .iter()
            .filter(|cp| cp.role == role && cp.p(full) < 0.0)
            .map(|cp| cp.g0 - cp.normal_stress_and_jump(full).1)
            .collect();
        active.iter().sum::<f64>() / active.len().max(1) as f64
    };
    mean(Role::Master) - mean(Role::Slave)
}

/// |F_c + F_applied| / |F_applied| in y: the contact carries the load.
fn imbalance(problem: &Problem, full: &[f64]) -> Result<f64> {
    let [_, fy] = post::contact_resultant(problem, full);
    let [_, ly] = post::applied_resultant(problem)?;
    Ok(((fy + ly) / ly).abs())
}

// ANCHOR: contrast
/// Table PS3 on one mesh.
pub struct ContrastMesh {
    elements: usize,
    /// p₀ of the disk on the rigid plane, θ = 0.
    rigid_p0: f64,
    /// Ratio by ratio, in the order of `RATIOS`.
    rows: Vec<ContrastRow>,
    /// How far the stiffest converged slave-modulus run is from the rigid
    /// plane with twice the penalty.
    limit_vs_doubled: f64,
    /// The unbiased form at ratio 1, if both solvers converged there.
    halves: Option<Halves>,
}

/// One ratio on one mesh: each variant solved by both solvers.
struct ContrastRow {
    ratio: f64,
    /// In the order of `Variant::ALL`.
    variants: Vec<VariantRun>,
}

/// One variant at one ratio on one mesh.
struct VariantRun {
    variant: Variant,
    iterations: Cell,
    /// `None` unless both solvers converged.
    converged: Option<Converged>,
}

/// What Table PS3 and its facts quote of a run both solvers converged on.
struct Converged {
    /// p₀ of BFGS.
    p0: f64,
    /// p₀ of BFGS / p₀,rigid − 1.
    deviation: f64,
    /// |p₀ of Newton / p₀ of BFGS − 1|.
    solver_gap: f64,
    /// Of BFGS.
    imbalance: f64,
}

/// The unbiased form's two halves at ratio 1.
struct Halves {
    disk_share: f64,
    gap_mismatch: f64,
}

/// Every mesh, ratio and variant, and the rigid runs they are measured
/// against.
pub fn solve_contrast() -> Result<Vec<ContrastMesh>> {
    CONTRAST_MESHES
        .into_iter()
        .map(solve_contrast_mesh)
        .collect()
}

fn solve_contrast_mesh(n: usize) -> Result<ContrastMesh> {
    let rigid_p0 = rigid_plane_p0(n, Theta::Incomplete, 1.0)?;
    let mut rows = Vec::new();
    let mut halves = None;
    for ratio in RATIOS {
        let mut variants = Vec::new();
        for variant in Variant::ALL {
            let problem = disk_on_block(n, ratio, variant, Theta::Incomplete)?;
            let runs = Both::solve(&problem)?;
            let converged = match (&runs.bfgs, &runs.newton) {
                (Ok(b), Ok(nw)) => {
                    let full = &b.solution.full;
                    // at ratio 1 the bodies are alike, so a symmetric method
                    // should split the force evenly
                    if variant == Variant::Unbiased && ratio == 1.0 {
                        halves = Some(Halves {
                            disk_share: disk_share(&problem, full),
                            gap_mismatch: gap_mismatch(&problem, full),
                        });
                    }
                    Some(Converged {
                        p0: b.p0,
                        deviation: relative(b.p0, rigid_p0),
                        solver_gap: relative(nw.p0, b.p0).abs(),
                        imbalance: imbalance(&problem, full)?,
                    })
                }
                _ => None,
            };
            variants.push(VariantRun {
                variant,
                iterations: runs.iterations(),
                converged,
            });
        }
        rows.push(ContrastRow { ratio, variants });
    }
    // the stiff-block limit against the rigid plane with about the γ
    // of an elastic master: (1/h₁ + 1/h₂) ≈ 2/h₁
    let stiffest = rows
        .iter()
        .rev()
        .find_map(|r| r.run(Variant::Slave).converged.as_ref())
        .map_or(0.0, |c| c.p0);
    let doubled = rigid_plane_p0(n, Theta::Incomplete, 2.0)?;
    Ok(ContrastMesh {
        elements: n,
        rigid_p0,
        rows,
        limit_vs_doubled: relative(stiffest, doubled).abs(),
        halves,
    })
}

impl ContrastRow {
    fn run(&self, variant: Variant) -> &VariantRun {
        self.variants
            .iter()
            .find(|v| v.variant == variant)
            .expect("every variant")
    }

    fn converged(&self) -> impl Iterator<Item = &Converged> {
        self.variants.iter().filter_map(|v| v.converged.as_ref())
    }

    fn solver_gap(&self) -> f64 {
        self.converged().fold(0.0, |a, c| a.max(c.solver_gap))
    }

    fn imbalance(&self) -> f64 {
        self.converged().fold(0.0, |a, c| a.max(c.imbalance))
    }
}

/// Table PS3, and in the CSV the rigid p₀, the solvers' difference and the
/// force balance.
pub fn contrast_table(contrast: &[ContrastMesh]) -> Result<Table> {
    let mut table = Table::new(vec![
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        Column::new("ratio", "E_b/E_d", Unit::None, Format::Sci(0)),
        Column::new("p0_slave", "slave", Unit::None, Format::SignedPercent(2)),
        Column::plain("its_slave", "its"),
        Column::new("p0_max", "max", Unit::None, Format::SignedPercent(2)),
        Column::plain("its_max", "its"),
        Column::new(
            "p0_unbiased",
            "unbiased",
            Unit::None,
            Format::SignedPercent(2),
        ),
        Column::plain("its_unbiased", "its"),
        Column::new("p0_rigid", "rigid p₀", Unit::Megapascal, Format::Fixed(4)).csv_only(),
        Column::new(
            "p0_newton_vs_bfgs",
            "Newton vs BFGS",
            Unit::None,
            Format::Sci(1),
        )
        .csv_only(),
        Column::new("imbalance", "imbalance", Unit::None, Format::Sci(1)).csv_only(),
    ]);
    for mesh in contrast {
        for r in &mesh.rows {
            let mut row: Vec<Cell> = vec![mesh.elements.into(), r.ratio.into()];
            for v in &r.variants {
                row.push(
                    v.converged
                        .as_ref()
                        .map_or(Cell::Empty, |c| c.deviation.into()),
                );
                row.push(v.iterations.clone());
            }
            row.extend([
                mesh.rigid_p0.into(),
                r.solver_gap().into(),
                r.imbalance().into(),
            ]);
            table.push(row)?;
        }
    }
    Ok(table)
}
// ANCHOR_END: contrast

/// Fig. PS2: the deviation from the rigid plane against the stiffness
/// ratio, for the slave's and the larger modulus (Table PS3 gives the
/// unbiased form).
pub fn draw_contrast(chapter: &Chapter, contrast: &[ContrastMesh]) -> Result<()> {
    let mut series = Vec::new();
    for variant in [Variant::Slave, Variant::Max] {
        for mesh in contrast {
            let points = mesh
                .rows
                .iter()
                .filter_map(|r| {
                    let c = r.run(variant).converged.as_ref()?;
                    Some((r.ratio, 100.0 * c.deviation))
                })
                .collect();
            let name = variant.name();
            let s = Series::line(format!("{name}, {}²", mesh.elements), points).with_markers();
            series.push(if variant == Variant::Max {
                s.dashed()
            } else {
                s
            });
        }
    }
    line_chart(
        chapter.path("contrast.svg"),
        &Axes {
            title: "Disk on a block: p₀ against the rigid plane, θ = 0".into(),
            x_label: "E_block / E_disk".into(),
            y_label: "p₀ / p₀,rigid − 1 (%)".into(),
            log_x: true,
            log_y: false,
        },
        &series,
    )
}

// ANCHOR: contrast_facts
/// Runs on which a solver failed, over Table PS3.
pub fn failures(contrast: &[ContrastMesh]) -> usize {
    contrast
        .iter()
        .flat_map(|m| &m.rows)
        .flat_map(|r| &r.variants)
        .filter(|v| v.converged.is_none())
        .count()
}

impl ContrastMesh {
    /// The deviations of `variant` from the rigid plane, ratio by ratio,
    /// over the runs both solvers converged on.
    fn deviations(&self, variant: Variant) -> Vec<f64> {
        self.rows
            .iter()
            .filter_map(|r| r.run(variant).converged.as_ref())
            .map(|c| c.deviation)
            .collect()
    }

    /// The deviation of `variant` at `ratio`; the facts that quote it
    /// exist only when every run converged.
    fn deviation(&self, variant: Variant, ratio: f64) -> f64 {
        self.rows
            .iter()
            .find(|r| r.ratio == ratio)
            .and_then(|r| r.run(variant).converged.as_ref())
            .expect("every run converged")
            .deviation
    }
}

/// The summary of Table PS3: per variant, whether it is monotone and how
/// close it comes at ratio ≥ 10²; per mesh, the cells the prose quotes;
/// over the table, the solvers' difference, the force balance and the
/// failures.
pub fn record_contrast_facts(f: &mut Facts, contrast: &[ContrastMesh]) -> Result<()> {
    let monotone =
        |v: &[f64]| v.windows(2).all(|w| w[1] >= w[0]) || v.windows(2).all(|w| w[1] <= w[0]);
    let yes_no = |b: bool| if b { "yes" } else { "no" };
    for variant in Variant::ALL {
        let name = variant.name();
        let mono = contrast.iter().all(|m| monotone(&m.deviations(variant)));
        f.text(&format!("{name}_monotone"), yes_no(mono))?;
        // skip(1): the first ratio, 1, is not a stiff block
        let worst = contrast
            .iter()
            .flat_map(|m| m.deviations(variant).into_iter().skip(1))
            .fold(0.0f64, |a, d| a.max(d.abs()));
        f.number(&format!("{name}_worst_stiff"), worst, Format::Percent(1))?;
        let all_within = contrast.iter().all(|m| {
            m.deviations(variant)
                .iter()
                .skip(1)
                .all(|d| d.abs() <= 0.02)
        });
        f.text(&format!("{name}_within_2_percent"), yes_no(all_within))?;
    }
    let failures = failures(contrast);
    // the figures per mesh index every ratio: they exist when every run converged
    if failures == 0 {
        for m in contrast {
            let n = m.elements;
            let at = |variant, ratio| m.deviation(variant, ratio);
            let halves = m.halves.as_ref().expect("every run converged");
            f.number(
                &format!("slave_1e6_{n}"),
                at(Variant::Slave, 1e6),
                Format::SignedPercent(2),
            )?;
            f.number(
                &format!("max_1e2_{n}"),
                at(Variant::Max, 1e2),
                Format::SignedPercent(1),
            )?;
            f.number(
                &format!("max_1e4_{n}"),
                at(Variant::Max, 1e4),
                Format::SignedPercent(1),
            )?;
            f.number(
                &format!("limit_vs_doubled_{n}"),
                m.limit_vs_doubled,
                Format::Percent(2),
            )?;
            f.number(
                &format!("unbiased_1e2_{n}"),
                at(Variant::Unbiased, 1e2),
                Format::SignedPercent(2),
            )?;
            f.number(
                &format!("unbiased_1_{n}"),
                at(Variant::Unbiased, 1.0),
                Format::SignedPercent(1),
            )?;
            f.number(
                &format!("unbiased_share_{n}"),
                halves.disk_share,
                Format::Percent(0),
            )?;
            f.number(
                &format!("unbiased_gap_mismatch_um_{n}"),
                halves.gap_mismatch * 1e6,
                Format::Fixed(1),
            )?;
        }
    }
    let rows = || contrast.iter().flat_map(|m| &m.rows);
    let solver_gap = rows().fold(0.0f64, |a, r| a.max(r.solver_gap()));
    let worst_imbalance = rows().fold(0.0f64, |a, r| a.max(r.imbalance()));
    f.number("contrast_solver_gap", solver_gap, Format::Pow10(0))?;
    f.number("contrast_imbalance", worst_imbalance, Format::Pow10(0))?;
    f.count("contrast_failures", failures)
}
// ANCHOR_END: contrast_facts
