//! Measures whether an exact symmetric path beats faer's LU for the BFGS
//! kernel (17) on Hertz, p = 2.
//!
//! The tied kernel is K̃₀ = P − Σ w jn snᵀ with P = K + Σ w γ jn jnᵀ
//! symmetric positive definite (the penalty part alone supports the disk).
//! The alternative to one LU of K̃₀ is one Cholesky of P and, for every
//! kernel solve, a right-preconditioned GMRES on K̃₀ P⁻¹ to 1e-12: the
//! difference is a boundary term of low rank, so few iterations are needed.
//!
//! Prints, per mesh: factorisation times, the cost of one kernel solve both
//! ways, the GMRES iteration count, and the break-even number of solves.

use iga_contact::assembly::Triplets;
use iga_contact::benchmarks::Hertz;
use iga_contact::linsolve::{mul, Factor, Factoriser, Method, Pattern};
use iga_contact::problem::{Kernel, Problem};
use nalgebra::DMatrix;
use std::time::Instant;

fn penalty_part(p: &Problem) -> iga_contact::Result<faer::sparse::SparseColMat<usize, f64>> {
    let mut t = Triplets::default();
    let s = p.k.symbolic();
    for j in 0..p.n() {
        for k in s.col_ptr()[j]..s.col_ptr()[j + 1] {
            t.rows.push(s.row_idx()[k]);
            t.cols.push(j);
            t.vals.push(p.k.val()[k]);
        }
    }
    let mut scratch = vec![0.0; p.n()];
    for cp in &p.points {
        let n = cp.dofs.len();
        let m = DMatrix::from_fn(n, n, |a, b| cp.weight * cp.gamma * cp.jn[a] * cp.jn[b]);
        t.add_block(&p.map, &cp.dofs, &cp.dofs, &m, &mut scratch);
    }
    Pattern::new(p.n(), &t)?.matrix(&t.vals)
}

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

fn main() -> iga_contact::Result<()> {
    println!("| elements | dofs | LU (s) | Cholesky of P (s) | LU solve (ms) | GMRES iterations | GMRES solve (ms) | solves to break even |");
    println!("|---|---|---|---|---|---|---|---|");
    for n in [16, 64, 128] {
        let p = Hertz {
            elements: n,
            ..Hertz::default()
        }
        .build()?;
        let kt = p.kernel(Kernel::Tied)?;
        let t = Instant::now();
        let lu = Factoriser::default().factor(&kt, Method::Lu)?;
        let t_lu = t.elapsed().as_secs_f64();
        let pm = penalty_part(&p)?;
        let t = Instant::now();
        let ch = Factoriser::default().factor(&pm, Method::Cholesky)?;
        let t_ch = t.elapsed().as_secs_f64();
        let b = p.rhs.clone();
        let reps = 5;
        let t = Instant::now();
        let mut x_lu = Vec::new();
        for _ in 0..reps {
            x_lu = lu.solve(&b)?;
        }
        let s_lu = t.elapsed().as_secs_f64() / reps as f64;
        let t = Instant::now();
        let mut res = (Vec::new(), 0);
        for _ in 0..reps {
            res = gmres(&kt, &ch, &b, 1e-12, 200);
        }
        let s_gm = t.elapsed().as_secs_f64() / reps as f64;
        let diff = norm(
            &x_lu
                .iter()
                .zip(&res.0)
                .map(|(a, c)| a - c)
                .collect::<Vec<_>>(),
        ) / norm(&x_lu);
        assert!(diff < 1e-8, "GMRES and LU disagree: {diff:.2e}");
        let gain = t_lu - t_ch;
        let loss = s_gm - s_lu;
        let even = if gain <= 0.0 {
            "never".to_string()
        } else {
            format!("{:.0}", gain / loss.max(1e-12))
        };
        println!(
            "| {n}×{n} | {} | {t_lu:.3} | {t_ch:.3} | {:.2} | {} | {:.2} | {even} |",
            p.n(),
            1e3 * s_lu,
            res.1,
            1e3 * s_gm
        );
    }
    Ok(())
}
