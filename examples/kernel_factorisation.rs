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

use iga_contact::benchmarks::Hertz;
use iga_contact::linsolve::{mul, Factor, Factoriser, Method};
use iga_contact::problem::Kernel;
use iga_contact::report::atomic::write_text;
use iga_contact::solver::kernel::{factor_kernel, Factorisation};
use iga_contact::studies::default_dir;
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
    let mut table = String::from("| elements | DOFs | LU (s) | Cholesky of S (s) | low-rank set-up (s) | rank r | LU solve (ms) | low-rank solve (ms) | GMRES iterations | GMRES solve (ms) |\n|---|---|---|---|---|---|---|---|---|---|\n");
    for n in [16, 64, 128] {
        let p = Hertz {
            elements: n,
            ..Hertz::default()
        }
        .build()?;
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
        let its = if its >= 200 {
            "200 (cap)".to_string()
        } else {
            its.to_string()
        };
        table.push_str(&format!(
            "| {n}×{n} | {} | {t_lu:.3} | {t_ch:.3} | {t_low:.3} | {rank} | {:.2} | {:.2} | {its} | {:.2} |\n",
            p.n(),
            1e3 * s_lu,
            1e3 * s_low,
            1e3 * s_gm
        ));
    }
    let out = default_dir("kernel").join("factorisation.md");
    write_text(&out, &table)?;
    print!("{table}");
    println!("written to {}", out.display());
    Ok(())
}
