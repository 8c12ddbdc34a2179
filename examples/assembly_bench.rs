//! Assembly and factorisation timings for the Hertz half disk (p = 2).
//!
//! The half disk of radius 0.2 (plane strain, E = 2e7, ν = 0.1) with
//! u_x = 0 on the symmetry line (`xi_min`) and u_y = 0 on the lower arc
//! (`eta_min`), so that the stiffness is symmetric positive definite. For
//! each mesh it times: stiffness assembly (triplets over the free DOFs),
//! the sparsity pattern and CSC fill, Cholesky (symbolic + numeric, then
//! numeric alone with the symbolic analysis reused) and LU for comparison.
//!
//! `cargo run --release --example assembly_bench [-- n1 n2 ...]` (default
//! 64 256 elements per direction). Diagnostics: `BENCH_SPLIT=1` also times
//! the element matrices and the quadrature alone; `BENCH_ASSEMBLY_ONLY=1`
//! stops after the assembly (for profiling it).
//!
//! `cargo run --release --example assembly_bench -- buffers [reps] n1 n2 ...`
//! times, in one run and on the same meshes, the element matrices of every
//! element with quadrature buffers ([`ElementValues`]) made afresh for each
//! element, as the assembly did before it reused them, and with one set per
//! thread reused across its elements, as it does now; then the whole CSC
//! assembly (which reuses them). Medians of `reps` runs (default 5),
//! interleaved so that a change in the machine's load falls on both.
//!
//! `cargo run --release --example assembly_bench -- assembly [reps] n1 n2 ...`
//! times the stiffness assembly alone, `reps` times per mesh (default 7),
//! and prints the median with the fastest and slowest run: the figures of
//! the allocators' doc comments (book/companion/src/allocator.rs, and
//! `allocator` in src/main.rs). Build it with `--no-default-features` for
//! the system allocator. On a shared machine the spread between runs is wide; compare
//! medians taken in the same session.

use iga_contact::assembly;
use iga_contact::dofs::{Body, DofMap};
use iga_contact::geometry::half_disk;
use iga_contact::linsolve::{Factoriser, Method, Pattern};
use iga_contact::material::{Material, Plane};
use iga_contact::nurbs::Side;
use iga_contact::space::{ElementValues, Space};
use std::time::Instant;

struct Timing {
    n: usize,
    dofs: usize,
    nnz: usize,
    assembly: f64,
    pattern: f64,
    cholesky: f64,
    cholesky_numeric: f64,
    lu: f64,
    residual: f64,
}

/// The Hertz half disk at n × n elements, with its DOF map.
fn problem(n: usize) -> iga_contact::Result<(Vec<Body>, DofMap)> {
    let patch = half_disk([0.0, 0.2], 0.2)?.k_refined(2, [n, n])?;
    let bodies = vec![Body {
        name: "half disk".into(),
        space: Space::new(patch, None)?,
        material: Material::new(2.0e7, 0.1, Plane::Strain)?,
        formulation: iga_contact::material::Formulation::Displacement,
    }];
    let mut builder = DofMap::builder(&bodies);
    builder
        .fix_side(0, Side::XiMin, 0, 0.0)?
        .fix_side(0, Side::EtaMin, 1, 0.0)?;
    let map = builder.build();
    Ok((bodies, map))
}

/// Median, fastest and slowest of `reps` runs of `f`, in seconds.
fn spread(
    reps: usize,
    mut f: impl FnMut() -> iga_contact::Result<()>,
) -> iga_contact::Result<[f64; 3]> {
    let mut times = Vec::with_capacity(reps);
    for _ in 0..reps {
        let t = Instant::now();
        f()?;
        times.push(t.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    Ok([times[reps / 2], times[0], times[reps - 1]])
}

/// `reps` assemblies at n × n, as triplets ([`assembly::stiffness`]) and
/// into the CSC matrix the solver uses ([`assembly::stiffness_matrix`]).
fn assembly_times(n: usize, reps: usize) -> iga_contact::Result<[[f64; 3]; 2]> {
    let (bodies, map) = problem(n)?;
    let triplets = spread(reps, || assembly::stiffness(&bodies, &map).map(drop))?;
    let csc = spread(reps, || {
        assembly::stiffness_matrix(&bodies, &map, &[], &[]).map(drop)
    })?;
    Ok([triplets, csc])
}

/// The element matrices of every element of `body`, in parallel, with
/// buffers made afresh per element (`reuse` false) or once per thread;
/// returns a sum of entries so that the work cannot be skipped.
fn element_matrices(body: &Body, reuse: bool) -> iga_contact::Result<f64> {
    use rayon::prelude::*;
    let ne = body.space.elements.len();
    if reuse {
        (0..ne)
            .into_par_iter()
            .map_init(
                || ElementValues::new(&body.space),
                |values, e| assembly::element_stiffness_with(values, body, e).map(|k| k[(0, 0)]),
            )
            .sum()
    } else {
        (0..ne)
            .into_par_iter()
            .map(|e| assembly::element_stiffness(body, e).map(|k| k[(0, 0)]))
            .sum()
    }
}

/// Medians over `reps` interleaved runs at n × n: element matrices with
/// fresh buffers, with reused ones, and the whole CSC assembly.
fn buffer_times(n: usize, reps: usize) -> iga_contact::Result<[f64; 3]> {
    let (bodies, map) = problem(n)?;
    let mut times = [vec![], vec![], vec![]];
    for _ in 0..reps {
        for (k, t) in times.iter_mut().enumerate() {
            let start = Instant::now();
            match k {
                0 => drop(element_matrices(&bodies[0], false)?),
                1 => drop(element_matrices(&bodies[0], true)?),
                _ => drop(assembly::stiffness_matrix(&bodies, &map, &[], &[])?),
            }
            t.push(start.elapsed().as_secs_f64());
        }
    }
    Ok(times.map(|mut t| {
        t.sort_by(f64::total_cmp);
        t[t.len() / 2]
    }))
}

fn run(n: usize) -> iga_contact::Result<Timing> {
    let (bodies, map) = problem(n)?;

    let t = Instant::now();
    let (trip, _lift) = assembly::stiffness(&bodies, &map)?;
    let assembly = t.elapsed().as_secs_f64();
    if std::env::var_os("BENCH_ASSEMBLY_ONLY").is_some() {
        eprintln!("assembly {assembly:.3} s, {} triplets", trip.len());
        std::process::exit(0);
    }
    if std::env::var_os("BENCH_SPLIT").is_some() {
        use rayon::prelude::*;
        let t = Instant::now();
        let ne = bodies[0].space.elements.len();
        let s: f64 = (0..ne)
            .into_par_iter()
            .map(|e| assembly::element_stiffness(&bodies[0], e).map(|k| k[(0, 0)]))
            .sum::<iga_contact::Result<f64>>()?;
        eprintln!(
            "  element matrices alone: {:.3} s ({s:.1e})",
            t.elapsed().as_secs_f64()
        );
        let t = Instant::now();
        let q: usize = (0..ne)
            .into_par_iter()
            .map_init(
                || ElementValues::new(&bodies[0].space),
                |values, e| {
                    let space = &bodies[0].space;
                    values
                        .reinit(space, &space.elements[e])
                        .map(|()| values.n_points())
                },
            )
            .sum::<iga_contact::Result<usize>>()?;
        eprintln!(
            "  quadrature alone: {:.3} s ({q} points)",
            t.elapsed().as_secs_f64()
        );
    }

    let t = Instant::now();
    let pattern = Pattern::new(map.n_free(), &[&trip])?;
    let k = pattern.matrix(&[&trip.vals])?;
    let pattern_time = t.elapsed().as_secs_f64();
    let nnz = k.symbolic().col_ptr()[k.ncols()];

    let mut fact = Factoriser::default();
    let t = Instant::now();
    let llt = fact.factor(&k, Method::Cholesky)?;
    let cholesky = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let llt2 = fact.factor(&k, Method::Cholesky)?;
    let cholesky_numeric = t.elapsed().as_secs_f64();
    drop(llt2);

    // a check that the factor is usable: solve K x = K·1 and compare with 1
    let ones = vec![1.0; map.n_free()];
    let b = iga_contact::linsolve::mul(&k, &ones);
    let x = llt.solve(&b)?;
    let residual = x.iter().map(|v| (v - 1.0).abs()).fold(0.0, f64::max);
    drop(llt);

    let t = Instant::now();
    let lu = Factoriser::default().factor(&k, Method::Lu)?;
    let lu_time = t.elapsed().as_secs_f64();
    drop(lu);

    Ok(Timing {
        n,
        dofs: map.n_free(),
        nnz,
        assembly,
        pattern: pattern_time,
        cholesky,
        cholesky_numeric,
        lu: lu_time,
        residual,
    })
}

/// `[reps] n1 n2 ...` of a timing mode: the run count (`default` when
/// only sizes are given; at least 1) and the meshes.
fn reps_and_sizes(
    args: &[String],
    default: usize,
) -> Result<(usize, Vec<usize>), std::num::ParseIntError> {
    let (reps, sizes) = match args {
        [reps, sizes @ ..] if !sizes.is_empty() => (reps.parse()?, sizes),
        _ => (default, args),
    };
    let sizes = sizes.iter().map(|a| a.parse()).collect::<Result<_, _>>()?;
    Ok((reps.max(1), sizes))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("buffers") {
        let (reps, sizes) = reps_and_sizes(&args[1..], 5)?;
        println!("| elements | runs | element matrices, fresh buffers s | reused buffers s | fresh ÷ reused | CSC assembly s |");
        println!("|---|---:|---:|---:|---:|---:|");
        for n in sizes {
            let [fresh, reused, csc] = buffer_times(n, reps)?;
            println!(
                "| {n}×{n} | {reps} | {fresh:.3} | {reused:.3} | {:.2}× | {csc:.3} |",
                fresh / reused
            );
        }
        return Ok(());
    }
    if args.first().map(String::as_str) == Some("assembly") {
        let (reps, sizes) = reps_and_sizes(&args[1..], 7)?;
        println!("| elements | runs | triplets: median (fastest–slowest) s | CSC: median (fastest–slowest) s |");
        println!("|---|---:|---:|---:|");
        for n in sizes {
            let [t, c] = assembly_times(n, reps)?;
            println!(
                "| {n}×{n} | {reps} | {:.3} ({:.3}–{:.3}) | {:.3} ({:.3}–{:.3}) |",
                t[0], t[1], t[2], c[0], c[1], c[2]
            );
        }
        return Ok(());
    }
    let sizes: Vec<usize> = if args.is_empty() {
        vec![64, 256]
    } else {
        args.iter().map(|a| a.parse()).collect::<Result<_, _>>()?
    };
    println!(
        "| elements | DOFs | nnz | assembly s | pattern+fill s | Cholesky (sym+num) s | Cholesky (num) s | LU s | max |x−1| |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|");
    for n in sizes {
        let t = run(n)?;
        println!(
            "| {n}×{n} | {} | {} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.1e} |",
            t.dofs,
            t.nnz,
            t.assembly,
            t.pattern,
            t.cholesky,
            t.cholesky_numeric,
            t.lu,
            t.residual,
            n = t.n
        );
    }
    Ok(())
}
