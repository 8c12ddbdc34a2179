//! Measures three exact ways to solve with the BFGS kernel (17) on Hertz,
//! p = 2.
//!
//! The tied kernel is K̃₀ = P − Σ w jn snᵀ with P = K + Σ w γ jn jnᵀ
//! symmetric positive definite (the penalty part alone supports the disk).
//!
//! - LU of K̃₀ (faer, COLAMD ordering);
//! - Cholesky of P and, for every kernel solve, a right-preconditioned
//!   GMRES on K̃₀ P⁻¹ to 1e-12;
//! - Cholesky of P and the Sherman–Morrison–Woodbury correction of the r
//!   trace rows where Σ w jn snᵀ lives (the solvers' default,
//!   `Factorisation::Auto`).
//!
//! Writes `book/src/generated/kernel/factorisation.md` (and prints it),
//! per mesh: set-up times, the cost of one kernel solve each way, the GMRES
//! iteration count and the rank r of the correction.

#[path = "common/hertz.rs"]
mod setup;

use iga_contact::linsolve::{mul, Factor, Factoriser, Method};
use iga_contact::problem::Kernel;
use iga_contact::report::chapter::Chapter;
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};
use iga_contact::solver::kernel::{factor_kernel, Factorisation};
use std::time::Instant;

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Right-preconditioned GMRES (no restart) for A x = b with M⁻¹ = `prec`.
fn gmres(
    a: &faer::sparse::SparseColMat<usize, f64>,
    prec: &Factor,
    b: &[f64],
    tol: f64,
    max: usize,
) -> (Vec<f64>, usize) {
    let n = b.len();
    let beta = norm(b);
    let mut v: Vec<Vec<f64>> = vec![b.iter().map(|x| x / beta).collect()];
    let mut h = vec![vec![0.0; max]; max + 1];
    let (mut cs, mut sn) = (vec![0.0; max], vec![0.0; max]);
    let mut g = vec![0.0; max + 1];
    g[0] = beta;
    let mut k = 0;
    while k < max {
        let z = prec.solve(&v[k]).unwrap();
        let mut w = mul(a, &z);
        for i in 0..=k {
            h[i][k] = w.iter().zip(&v[i]).map(|(x, y)| x * y).sum();
            for (wj, vj) in w.iter_mut().zip(&v[i]) {
                *wj -= h[i][k] * vj;
            }
        }
        h[k + 1][k] = norm(&w);
        v.push(w.iter().map(|x| x / h[k + 1][k]).collect());
        for i in 0..k {
            let t = cs[i] * h[i][k] + sn[i] * h[i + 1][k];
            h[i + 1][k] = -sn[i] * h[i][k] + cs[i] * h[i + 1][k];
            h[i][k] = t;
        }
        let r = h[k][k].hypot(h[k + 1][k]);
        cs[k] = h[k][k] / r;
        sn[k] = h[k + 1][k] / r;
        h[k][k] = r;
        h[k + 1][k] = 0.0;
        g[k + 1] = -sn[k] * g[k];
        g[k] *= cs[k];
        k += 1;
        if g[k].abs() <= tol * beta {
            break;
        }
    }
    let mut y = vec![0.0; k];
    for i in (0..k).rev() {
        y[i] = (g[i] - (i + 1..k).map(|j| h[i][j] * y[j]).sum::<f64>()) / h[i][i];
    }
    let mut u = vec![0.0; n];
    for (i, yi) in y.iter().enumerate() {
        for (uj, vj) in u.iter_mut().zip(&v[i]) {
            *uj += yi * vj;
        }
    }
    (prec.solve(&u).unwrap(), k)
}

/// Mean seconds of `f` over `reps` calls, and its last result.
fn timed<T>(reps: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let t = Instant::now();
    let mut last = f();
    for _ in 1..reps {
        last = f();
    }
    (t.elapsed().as_secs_f64() / reps as f64, last)
}

fn main() -> iga_contact::Result<()> {
    let mut chapter = Chapter::from_args("kernel")?;
    let mut table = Table::new(vec![
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        Column::plain("dofs", "DOFs"),
        Column::new("lu_setup", "LU", Unit::Second, Format::Fixed(3)),
        Column::new(
            "cholesky_setup",
            "Cholesky of S",
            Unit::Second,
            Format::Fixed(3),
        ),
        Column::new(
            "low_rank_setup",
            "low-rank set-up",
            Unit::Second,
            Format::Fixed(3),
        ),
        Column::plain("rank", "rank r"),
        Column::new("lu_solve", "LU solve", Unit::Millisecond, Format::Fixed(2)),
        Column::new(
            "low_rank_solve",
            "low-rank solve",
            Unit::Millisecond,
            Format::Fixed(2),
        ),
        Column::plain("gmres_iterations", "GMRES its"),
        Column::new(
            "gmres_solve",
            "GMRES solve",
            Unit::Millisecond,
            Format::Fixed(2),
        ),
    ]);
    let mut ratios = Vec::new();
    for n in [16, 64, 128] {
        let p = setup::scene(setup::iga(2, n))?.build()?;
        let kt = p.kernel(Kernel::Tied)?;
        let factor = |how| {
            timed(1, || {
                factor_kernel(
                    &p,
                    &mut Factoriser::default(),
                    Kernel::Tied,
                    how,
                    &mut Vec::new(),
                )
            })
        };
        let (t_lu, lu) = factor(Factorisation::Lu);
        let lu = lu?;
        let (t_low, low) = factor(Factorisation::Auto);
        let low = low?;
        let Factor::LowRank(lr) = &low else {
            panic!("the θ = 0 Hertz kernel should take the low-rank path");
        };
        let rank = lr.rank();
        let split = p.kernel_split(Kernel::Tied)?.expect("θ = 0");
        let (t_ch, ch) = timed(1, || {
            Factoriser::default().factor(&split.spd, Method::Cholesky)
        });
        let ch = ch?;
        let b = p.rhs.clone();
        let reps = 5;
        let (s_lu, x_lu) = timed(reps, || lu.solve(&b));
        let x_lu = x_lu?;
        let (s_low, x_low) = timed(reps, || low.solve(&b));
        let x_low = x_low?;
        let (s_gm, (x_gm, its)) = timed(reps, || gmres(&kt, &ch, &b, 1e-12, 200));
        for (name, x) in [("low-rank", &x_low), ("GMRES", &x_gm)] {
            let d: Vec<f64> = x_lu.iter().zip(x).map(|(a, c)| a - c).collect();
            let diff = norm(&d) / norm(&x_lu);
            assert!(diff < 1e-8, "{name} and LU disagree: {diff:.2e}");
        }
        let its: Cell = if its >= 200 {
            "200 (cap)".into()
        } else {
            its.into()
        };
        ratios.push((n, s_lu / s_low, t_lu / t_low));
        table.push(vec![
            n.into(),
            p.n().into(),
            t_lu.into(),
            t_ch.into(),
            t_low.into(),
            rank.into(),
            s_lu.into(),
            s_low.into(),
            its,
            s_gm.into(),
        ])?;
    }
    print!("{}", table.to_markdown());
    chapter.table("factorisation", &table)?;
    chapter.timed("factorisation.csv");
    chapter.timed("factorisation.md");
    let f = chapter.facts();
    for (n, solve, set_up) in ratios {
        f.timed_number(&format!("solve_speedup_{n}"), solve, Format::Times(2))?;
        f.timed_number(&format!("setup_speedup_{n}"), set_up, Format::Times(1))?;
    }
    chapter.finish()
}
