//! The disk on an elastic block: the heavy program behind the section
//! "Stiffness contrast" of the chapter "The penalty, measured". The Hertz
//! disk rests on a block whose modulus is 1 to 10⁶ times the disk's, on
//! three meshes, with both solvers and three variants of the pair (whose
//! modulus enters (11), which sides carry the contact terms), against the
//! disk on the rigid plane. Output: `book/src/generated/penalty_contrast/`.
//!
//! Run it with `cargo run --release --example penalty_contrast` (a few
//! minutes of one core).

use companion::chapter::Chapter;
use companion::penalty::{hertz, measure, Run};
use iga_contact::contact::{Modulus, Role, Sides, Theta};
use iga_contact::error::Result;
use iga_contact::post::{self, penalty_stability, relative};
use iga_contact::problem::Problem;
use iga_contact::report::plot::{line_chart, Axes, Series};
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};
use iga_contact::scene::RefineSpec;
use iga_contact::solver::{SolverKind, SolverOptions};

// ANCHOR: contrast_setup
/// Block stiffness over disk stiffness, E_block / E_disk.
const RATIOS: [f64; 4] = [1.0, 1e2, 1e4, 1e6];
/// Elements per direction of the disk (the block has 2n × n).
const CONTRAST_MESHES: [usize; 3] = [16, 32, 64];

/// The variants compared: whose modulus enters (11), and which sides
/// carry the contact terms.
const VARIANTS: [(Modulus, Sides); 3] = [
    (Modulus::Slave, Sides::Biased),
    (Modulus::Max, Sides::Biased),
    (Modulus::Slave, Sides::Unbiased),
];

/// `data/scenes/disk_on_block.toml` with the disk on n² elements, the
/// block 2n × n, the block's modulus `ratio` times the disk's, and the
/// pair's `modulus`, `sides` and `theta`.
fn disk_on_block(
    n: usize,
    ratio: f64,
    modulus: Modulus,
    sides: Sides,
    theta: Theta,
) -> Result<Problem> {
    let mut s = companion::shipped("disk_on_block.toml")?
        .refined("disk", RefineSpec::iga(2, [n, n]))?
        .refined("block", RefineSpec::iga(2, [2 * n, n]))?
        .with_nitsche(|x| {
            x.modulus = modulus;
            x.sides = sides;
            x.theta = theta;
        });
    s.body_mut("block")?.material.young *= ratio;
    s.build()
}

/// The same disk on the rigid plane (the Hertz scene on the same mesh,
/// with the same θ and the same segment integration).
fn rigid(n: usize, theta: Theta, factor: f64) -> Result<Problem> {
    hertz(n, |x| {
        x.theta = theta;
        x.penalty_factor = factor;
        x.integration = iga_contact::contact::Integration::Segment;
    })
}
// ANCHOR_END: contrast_setup

/// Both solvers on one problem: the default BFGS and Newton.
fn both(problem: &Problem) -> Result<[Run; 2]> {
    Ok([
        measure(problem, &SolverOptions::default())?,
        measure(problem, &SolverOptions::with_kind(SolverKind::Newton))?,
    ])
}

/// Iterations of both solvers as "BFGS / Newton", or the failure.
fn iterations(r: &[Run; 2]) -> Cell {
    let one = |o: &Run| match o {
        Ok(o) => o.solution.history.len().to_string(),
        Err(kind) => kind.to_string(),
    };
    Cell::Text(format!("{} / {}", one(&r[0]), one(&r[1])))
}

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

fn main() -> Result<()> {
    let mut chapter = Chapter::from_args("penalty_contrast")?;
    let started = std::time::Instant::now();
    // ANCHOR: contrast
    let mut contrast = Table::new(vec![
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
    // [variant][mesh] → (ratio, p₀ / p₀,rigid − 1) of the default BFGS
    let mut curves: Vec<Vec<Vec<(f64, f64)>>> =
        vec![vec![Vec::new(); CONTRAST_MESHES.len()]; VARIANTS.len()];
    let mut solver_gap = 0.0f64;
    let mut worst_imbalance = 0.0f64;
    let mut failures = 0usize;
    let mut limit_vs_doubled = Vec::new();
    let mut share = Vec::new(); // unbiased, ratio 1: the disk half's share per mesh
    let mut mismatch = Vec::new(); // unbiased, ratio 1: the halves' gap mismatch per mesh
    for (im, n) in CONTRAST_MESHES.into_iter().enumerate() {
        let rigid_p0 = measure(
            &rigid(n, Theta::Incomplete, 1.0)?,
            &SolverOptions::default(),
        )?
        .expect("the rigid case converges")
        .p0;
        let mut last_p0 = 0.0;
        for ratio in RATIOS {
            let mut row: Vec<Cell> = vec![n.into(), ratio.into()];
            let mut gap = 0.0f64;
            let mut imb = 0.0f64;
            for (iv, &(modulus, sides)) in VARIANTS.iter().enumerate() {
                let problem = disk_on_block(n, ratio, modulus, sides, Theta::Incomplete)?;
                let r = both(&problem)?;
                match (&r[0], &r[1]) {
                    (Ok(b), Ok(nw)) => {
                        gap = gap.max(relative(nw.p0, b.p0).abs());
                        imb = imb.max(imbalance(&problem, &b.solution.full)?);
                        let dev = relative(b.p0, rigid_p0);
                        curves[iv][im].push((ratio, 100.0 * dev));
                        row.push(dev.into());
                        if iv == 0 {
                            last_p0 = b.p0;
                        }
                        if sides == Sides::Unbiased && ratio == 1.0 {
                            share.push(disk_share(&problem, &b.solution.full));
                            mismatch.push(gap_mismatch(&problem, &b.solution.full));
                        }
                    }
                    _ => {
                        failures += 1;
                        row.push(Cell::Empty);
                    }
                }
                row.push(iterations(&r));
            }
            solver_gap = solver_gap.max(gap);
            worst_imbalance = worst_imbalance.max(imb);
            row.extend([rigid_p0.into(), gap.into(), imb.into()]);
            contrast.push(row)?;
        }
        // the stiff-block limit against the rigid plane with about the γ
        // of an elastic master: (1/h₁ + 1/h₂) ≈ 2/h₁
        let doubled = measure(
            &rigid(n, Theta::Incomplete, 2.0)?,
            &SolverOptions::default(),
        )?
        .expect("the rigid case converges")
        .p0;
        limit_vs_doubled.push(relative(last_p0, doubled).abs());
    }
    chapter.table("contrast", &contrast)?;
    // ANCHOR_END: contrast

    // The deviation from the rigid plane against the stiffness ratio.
    let names = ["slave", "max", "unbiased"];
    let mut series = Vec::new();
    for (iv, name) in names.iter().enumerate().take(2) {
        for (im, n) in CONTRAST_MESHES.iter().enumerate() {
            let s = Series::line(format!("{name}, {n}²"), curves[iv][im].clone()).with_markers();
            series.push(if iv == 1 { s.dashed() } else { s });
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
    )?;

    // ANCHOR: contrast_facts
    let f = chapter.facts();
    let column =
        |iv: usize, im: usize| -> Vec<f64> { curves[iv][im].iter().map(|c| c.1 / 100.0).collect() };
    let monotone =
        |v: &[f64]| v.windows(2).all(|w| w[1] >= w[0]) || v.windows(2).all(|w| w[1] <= w[0]);
    for (iv, name) in names.iter().enumerate() {
        let meshes = CONTRAST_MESHES.len();
        let mono = (0..meshes).all(|im| monotone(&column(iv, im)));
        f.text(&format!("{name}_monotone"), if mono { "yes" } else { "no" })?;
        let worst = (0..meshes)
            .flat_map(|im| column(iv, im).into_iter().skip(1))
            .fold(0.0f64, |a, d| a.max(d.abs()));
        f.number(&format!("{name}_worst_stiff"), worst, Format::Percent(1))?;
        let all_within =
            (0..meshes).all(|im| column(iv, im).iter().skip(1).all(|d| d.abs() <= 0.02));
        f.text(
            &format!("{name}_within_2_percent"),
            if all_within { "yes" } else { "no" },
        )?;
    }
    // the figures per mesh index every ratio: they exist when every run converged
    if failures == 0 {
        for (im, n) in CONTRAST_MESHES.iter().enumerate() {
            f.number(
                &format!("slave_1e6_{n}"),
                column(0, im)[3],
                Format::SignedPercent(2),
            )?;
            f.number(
                &format!("max_1e2_{n}"),
                column(1, im)[1],
                Format::SignedPercent(1),
            )?;
            f.number(
                &format!("max_1e4_{n}"),
                column(1, im)[2],
                Format::SignedPercent(1),
            )?;
            f.number(
                &format!("limit_vs_doubled_{n}"),
                limit_vs_doubled[im],
                Format::Percent(2),
            )?;
        }
        for (im, n) in CONTRAST_MESHES.iter().enumerate() {
            f.number(
                &format!("unbiased_1e2_{n}"),
                column(2, im)[1],
                Format::SignedPercent(2),
            )?;
            f.number(
                &format!("unbiased_1_{n}"),
                column(2, im)[0],
                Format::SignedPercent(1),
            )?;
            f.number(
                &format!("unbiased_share_{n}"),
                share[im],
                Format::Percent(0),
            )?;
            f.number(
                &format!("unbiased_gap_mismatch_um_{n}"),
                mismatch[im] * 1e6,
                Format::Fixed(1),
            )?;
        }
    }
    f.number("contrast_solver_gap", solver_gap, Format::Pow10(0))?;
    f.number("contrast_imbalance", worst_imbalance, Format::Pow10(0))?;
    f.count("contrast_failures", failures)?;
    // ANCHOR_END: contrast_facts

    // The other two θ on the default variant.
    // ANCHOR: contrast_theta
    let mut thetas = Table::new(vec![
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
    let mut theta_worst = [0.0f64; 2];
    for n in CONTRAST_MESHES {
        let rigid0 = measure(
            &rigid(n, Theta::Incomplete, 1.0)?,
            &SolverOptions::default(),
        )?
        .expect("the rigid case converges")
        .p0;
        for ratio in RATIOS {
            let mut row: Vec<Cell> = vec![n.into(), ratio.into()];
            for (k, theta) in [Theta::Symmetric, Theta::Skew].into_iter().enumerate() {
                let problem = disk_on_block(n, ratio, Modulus::Slave, Sides::Biased, theta)?;
                let r = both(&problem)?;
                match &r[0] {
                    Ok(o) => {
                        let dev = relative(o.p0, rigid0);
                        if ratio >= 1e2 {
                            theta_worst[k] = theta_worst[k].max(dev.abs());
                        }
                        row.push(dev.into());
                    }
                    Err(_) => {
                        failures += 1;
                        row.push(Cell::Empty);
                    }
                }
                row.push(iterations(&r));
            }
            thetas.push(row)?;
        }
    }
    chapter.table("contrast_theta", &thetas)?;
    let f = chapter.facts();
    f.number("theta1_worst_stiff", theta_worst[0], Format::Percent(1))?;
    f.number(
        "theta_minus1_worst_stiff",
        theta_worst[1],
        Format::Percent(1),
    )?;
    f.count("contrast_all_failures", failures)?;
    // the rigid plane with θ = 1 and (11): below its bound at every active point
    let problem = rigid(16, Theta::Symmetric, 1.0)?;
    let o = measure(&problem, &SolverOptions::default())?.expect("θ = 1 converges");
    let st = penalty_stability(&problem, &o.solution.full)[0];
    f.count("rigid_theta1_active", st.active)?;
    f.count("rigid_theta1_below", st.active_below)?;
    let rigid0 = measure(
        &rigid(16, Theta::Incomplete, 1.0)?,
        &SolverOptions::default(),
    )?
    .expect("the rigid case converges")
    .p0;
    f.number(
        "rigid_theta1_vs_theta0_16",
        relative(o.p0, rigid0),
        Format::SignedPercent(1),
    )?;
    // ANCHOR_END: contrast_theta

    let minutes = started.elapsed().as_secs_f64() / 60.0;
    chapter
        .facts()
        .timed_number("run_minutes", minutes, Format::Fixed(1))?;
    chapter.finish()
}
