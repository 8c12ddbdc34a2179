//! The cost of the mixed formulation against the displacement one: Hertz
//! (p = 2, θ = 0, the default solver) on n × n elements at ν = 0.3, where
//! both formulations give the same answer, built and solved alternately
//! `reps` times in one run; prints the median build and solve times, the
//! stiffness's stored entries and the iterations of each, and their ratios.
//!
//! `cargo run --release --example mixed_bench [-- reps n1 n2 ...]`
//! (default 3 runs of 256²). The mixed formulation's volumetric term
//! couples every displacement function with those under the pressure
//! functions of its support, 4p − 1 control points per direction instead
//! of 2p + 1 (chapter "Near incompressibility"), so its matrix and its
//! factor are larger: this benchmark says by how much the run pays for it.

use companion::shipped;
use iga_contact::material::Formulation;
use iga_contact::scene::RefineSpec;
use iga_contact::solver::{solve, SolverOptions};
use std::time::Instant;

/// Median build and solve seconds, stored entries of the bulk stiffness
/// and iterations of one formulation.
#[derive(Default)]
struct Timing {
    build: Vec<f64>,
    solve: Vec<f64>,
    nnz: usize,
    iterations: usize,
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse())
        .collect::<Result<_, _>>()?;
    let (reps, sizes) = match args.split_first() {
        Some((&reps, sizes)) if !sizes.is_empty() => (reps.max(1), sizes.to_vec()),
        _ => (3, vec![256]),
    };
    println!(
        "| elements | formulation | build s | solve s | total s | stiffness entries | iterations |"
    );
    println!("|---|---|---:|---:|---:|---:|---:|");
    for n in sizes {
        let mut t = [Timing::default(), Timing::default()];
        for _ in 0..reps {
            for (k, f) in [Formulation::Displacement, Formulation::Mixed]
                .into_iter()
                .enumerate()
            {
                let mut s = shipped("hertz.toml")?;
                s.bodies[0].refine = Some(RefineSpec::iga(2, [n, n]));
                s.bodies[0].material.poisson = 0.3;
                s.bodies[0].formulation = f;
                s.solver = SolverOptions::default();
                let start = Instant::now();
                let problem = s.build()?;
                t[k].build.push(start.elapsed().as_secs_f64());
                let start = Instant::now();
                let solution = solve(&problem, &SolverOptions::default())?;
                t[k].solve.push(start.elapsed().as_secs_f64());
                t[k].nnz = problem.k.compute_nnz();
                t[k].iterations = solution.history.len();
            }
        }
        let mut total = [0.0; 2];
        for (k, name) in ["displacement", "mixed"].into_iter().enumerate() {
            let (b, s) = (median(&mut t[k].build), median(&mut t[k].solve));
            total[k] = b + s;
            println!(
                "| {n}² | {name} | {b:.2} | {s:.2} | {:.2} | {} | {} |",
                b + s,
                t[k].nnz,
                t[k].iterations
            );
        }
        println!(
            "| {n}² | mixed ÷ displacement | | | {:.2}× | {:.2}× | |",
            total[1] / total[0],
            t[1].nnz as f64 / t[0].nnz as f64
        );
    }
    Ok(())
}
