//! Iteration counts of the contact solvers, and the full-step semismooth
//! Newton (primal-dual active set) map of the contact layer, measured.
//!
//! `cargo run --release --example iterations -- ladder [MAX]` prints, for
//! Hertz p = 2 and 3 on 16²…MAX² (default 256) and the disk on an elastic
//! block (`data/scenes/disk_on_block.toml`, stiffness ratio 1) on
//! 16²…min(MAX, 128)² at penalty factors 1 to 30, the iterations and
//! kernel factorisations of the default solver and of `kind = "newton"`.
//!
//! The last two columns are the solvers with `growth = "full"`: the
//! iteration before the cut growth ([`iga_contact::solver::Growth`]).
//!
//! `cargo run --release --example iterations -- history N FACTOR` prints
//! the active points and relative residual of every iteration of both
//! solvers on the disk on the block (N², penalty factor FACTOR).
//!
//! `cargo run --release --example iterations -- map N FACTOR` runs the
//! undamped active-set map A ↦ {P(u(A)) ≤ 0} on the disk on the block
//! (N², penalty factor FACTOR), where u(A) is the root of the linear piece
//! of A (what a full Newton step lands on from any iterate), from sets
//! that differ from a root's by m points at the edge of its contact zone,
//! and prints how many maps each start takes and which root it reaches.
//!
//! `cargo run --release --example iterations -- emulate N FACTOR K KEPT`
//! runs that map from the first K points of the contact line with the
//! growth of every map cut to the fraction KEPT (`cut_growth`; 1 is the
//! plain map) and prints how many maps reach the root.
//!
//! Not a chapter program: its output is not in the book.

use iga_contact::contact::nitsche::heaviside;
use iga_contact::error::{Error, Result};
use iga_contact::problem::Problem;
use iga_contact::scene::RefineSpec;
use iga_contact::solver::trace::{DenseLu, TraceProblem};
use iga_contact::solver::{solve, Growth, SolverKind, SolverOptions};

fn disk_on_block(n: usize, factor: f64) -> Result<Problem> {
    companion::shipped("disk_on_block.toml")?
        .refined("disk", RefineSpec::iga(2, [n, n]))?
        .refined("block", RefineSpec::iga(2, [2 * n, n]))?
        .with_nitsche(|x| x.penalty_factor = factor)
        .build()
}

fn hertz(p: usize, n: usize) -> Result<Problem> {
    companion::shipped("hertz.toml")?
        .refined("disk", RefineSpec::iga(p, [n, n]))?
        .build()
}

/// "iterations/factorisations (active points, warnings)" of one solve.
fn count(problem: &Problem, opts: &SolverOptions) -> String {
    match solve(problem, opts) {
        Ok(s) => format!(
            "{:>3}/{:<3} ({} active{})",
            s.history.len(),
            s.factorisations,
            s.history.rows.last().map_or(0, |r| r.active_points),
            if s.warnings.is_empty() {
                String::new()
            } else {
                format!(", {} warnings", s.warnings.len())
            }
        ),
        Err(e) => e.kind().to_string(),
    }
}

fn ladder(max: usize) -> Result<()> {
    println!("case | layer DOFs | contact points | default | newton | default, growth = full | newton, growth = full");
    let full = |kind| SolverOptions {
        growth: Growth::Full,
        ..SolverOptions::with_kind(kind)
    };
    let row = |label: String, problem: &Problem| {
        println!(
            "{label} | {} | {} | {} | {} | {} | {}",
            problem.layer().len(),
            problem.points.len(),
            count(problem, &SolverOptions::with_kind(SolverKind::Bfgs)),
            count(problem, &SolverOptions::with_kind(SolverKind::Newton)),
            count(problem, &full(SolverKind::Bfgs)),
            count(problem, &full(SolverKind::Newton)),
        );
    };
    let mut n = 16;
    while n <= max {
        for p in [2, 3] {
            row(format!("hertz p = {p}, {n}²"), &hertz(p, n)?);
        }
        n *= 2;
    }
    let mut n = 16;
    while n <= max.min(128) {
        for factor in [1.0, 2.0, 5.0, 10.0, 20.0, 30.0] {
            row(
                format!("disk on block {n}², factor {factor}"),
                &disk_on_block(n, factor)?,
            );
        }
        n *= 2;
    }
    Ok(())
}

/// The undamped active-set map on the layer of one problem.
struct Map<'a> {
    trace: TraceProblem<'a>,
}

impl Map<'_> {
    /// u(A) for the activity `h`: the root of the linear piece of A, one
    /// Newton step from u = 0 with the points of A under the tied law
    /// (exact when no point penetrates at u = 0, checked by the caller).
    fn root_of_piece(&self, h: &[bool]) -> Result<Vec<f64>> {
        let activity: Vec<f64> = h.iter().map(|&a| f64::from(u8::from(a))).collect();
        let zero = vec![0.0; self.trace.dim()];
        let r = self.trace.residual_forced(&zero, h).0;
        DenseLu::new(&self.trace.kernel(&activity))?.solve(&r)
    }

    fn next(&self, h: &[bool]) -> Result<Vec<bool>> {
        let u = self.root_of_piece(h)?;
        Ok(self
            .trace
            .p_values(&u)
            .into_iter()
            .map(|p| heaviside(p) > 0.5)
            .collect())
    }

    /// Maps from `h` until a fixed point (a root: its active set is its
    /// own), at most `limit` maps; the number of maps and the set.
    fn run(&self, mut h: Vec<bool>, limit: usize) -> Result<(usize, Vec<bool>)> {
        for k in 1..=limit {
            let next = self.next(&h)?;
            if next == h {
                return Ok((k, h));
            }
            h = next;
        }
        Err(Error::invalid(
            "map",
            limit,
            "no fixed point within the limit",
        ))
    }
}

fn root_size(h: &[bool]) -> usize {
    h.iter().filter(|&&a| a).count()
}

fn map(n: usize, factor: f64) -> Result<()> {
    let problem = disk_on_block(n, factor)?;
    let trace = TraceProblem::new(&problem)?;
    if trace
        .p_values(&vec![0.0; trace.dim()])
        .iter()
        .any(|&p| p < 0.0)
    {
        return Err(Error::invalid("map", "u = 0", "a contact point penetrates"));
    }
    let m = Map { trace };
    let points = problem.points.len();
    // the contact points along the slave side, from the disk's lowest point
    let mut order: Vec<usize> = (0..points).collect();
    order.sort_by(|&a, &b| problem.points[a].x[0].total_cmp(&problem.points[b].x[0]));
    let prefix = |k: usize| {
        let mut h = vec![false; points];
        for &q in order.iter().take(k) {
            h[q] = true;
        }
        h
    };
    let limit = 200;
    let (maps, root) = m.run(prefix(points / 4), limit)?;
    let size = root_size;
    let contiguous = |h: &[bool]| h == prefix(size(h)).as_slice();
    println!(
        "disk on block {n}², factor {factor}: {points} contact points; from the first quarter active: {maps} maps to a root with {} active points (contiguous: {})",
        size(&root),
        contiguous(&root)
    );
    // other roots among the contiguous sets near the edge
    let mut roots = Vec::new();
    for k in root_size(&root).saturating_sub(12)..=(root_size(&root) + 12).min(points) {
        if m.next(&prefix(k))? == prefix(k) {
            roots.push(k.to_string());
        }
    }
    println!(
        "contiguous active sets within 12 points of it that are roots: {}",
        roots.join(", ")
    );
    println!("start (root ± m edge points) | maps | active points of the root reached");
    let base = size(&root);
    for shift in [-40i64, -20, -10, -5, -2, 2, 5, 10, 20, 40, 80] {
        let k = base as i64 + shift;
        if k <= 0 || k as usize > points {
            continue;
        }
        let (maps, reached) = m.run(prefix(k as usize), limit)?;
        println!("{shift:+} | {maps} | {}", size(&reached));
    }
    Ok(())
}

fn hist(n: usize, factor: f64) -> Result<()> {
    let problem = disk_on_block(n, factor)?;
    for kind in [SolverKind::Bfgs, SolverKind::Newton] {
        match solve(&problem, &SolverOptions::with_kind(kind)) {
            Ok(s) => println!(
                "{kind:?}: {}",
                s.history
                    .rows
                    .iter()
                    .map(|r| format!("{}({:.1e})", r.active_points, r.relative_residual))
                    .collect::<Vec<_>>()
                    .join(" ")
            ),
            Err(e) => println!("{kind:?}: {e}"),
        }
    }
    Ok(())
}

/// The map with the growth cut to `kept` ([`iga_contact::solver::kernel::cut_growth`])
/// from the first `k0` points along the line: how many maps to the root,
/// and the root's zones (start..end along t).
fn emulate(n: usize, factor: f64, k0: usize, kept: f64) -> Result<()> {
    let problem = disk_on_block(n, factor)?;
    let trace = TraceProblem::new(&problem)?;
    let m = Map { trace };
    let lines = iga_contact::solver::kernel::lines(&problem);
    let line = &lines[0];
    let mut h = vec![false; problem.points.len()];
    for &q in line.iter().take(k0) {
        h[q] = true;
    }
    let runs = |h: &[bool]| -> String {
        let mut out = Vec::new();
        let mut i = 0;
        while i < line.len() {
            if h[line[i]] {
                let s = i;
                while i < line.len() && h[line[i]] {
                    i += 1;
                }
                out.push(format!("{s}..{i}"));
            } else {
                i += 1;
            }
        }
        out.join(",")
    };
    for k in 1..=40 {
        let b = m.next(&h)?;
        if b == h {
            println!(
                "{n}² factor {factor} from {k0}, kept {kept}: {k} maps to {}",
                runs(&b)
            );
            break;
        }
        h = iga_contact::solver::kernel::cut_growth(&h, &b, &lines, kept);
    }
    Ok(())
}

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let number = |k: usize, default: f64| -> Result<f64> {
        args.get(k).map_or(Ok(default), |s| {
            s.parse()
                .map_err(|_| Error::invalid("argument", s, "not a number"))
        })
    };
    match args.first().map(String::as_str) {
        Some("map") => map(number(1, 32.0)? as usize, number(2, 20.0)?),
        Some("emulate") => emulate(
            number(1, 32.0)? as usize,
            number(2, 20.0)?,
            number(3, 10.0)? as usize,
            number(4, iga_contact::solver::kernel::KEPT)?,
        ),
        Some("history") => hist(number(1, 32.0)? as usize, number(2, 20.0)?),
        Some("ladder") | None => ladder(number(1, 256.0)? as usize),
        Some(other) => Err(Error::invalid(
            "mode",
            other,
            "use `ladder`, `map`, `history` or `emulate`",
        )),
    }
}
