//! The parent's side of a case: it runs the case in a child process of its
//! own (`case.rs`) and reads back what it printed.

use crate::cli::{CliRun, FALLBACK_MAX_MEMORY};
use crate::{PARTS_CHECKED_FROM, PARTS_WITHIN};
use iga_contact::timing::PhaseTimes;
use std::process::{Command, Stdio};

/// The in-process measurements of a case.
pub struct InProcess {
    pub condensation: f64,
    pub iterations: usize,
    pub iterations_s: f64,
    pub recovery: f64,
    pub total: f64,
    /// The mean processor time of a build and a solve.
    pub total_cpu: f64,
    pub force_error: f64,
    pub peak: f64,
}

/// Everything measured of one case, in one process run.
pub struct Row {
    pub p: usize,
    pub n: usize,
    pub dofs: usize,
    pub layer: usize,
    pub assembly: f64,
    /// The fastest of the reference factorisations.
    pub cholesky: f64,
    /// The first reference factorisation of the process.
    pub cholesky_first: f64,
    /// Processor times of the first and of the least of the factorisations.
    pub cholesky_first_cpu: f64,
    pub cholesky_cpu: f64,
    pub route_b: f64,
    /// `None` above [`IN_PROCESS_UP_TO`].
    pub solve: Option<InProcess>,
    pub cli: CliRun,
}

/// Runs the case in a child process of its own ([`crate::case`]) and reads back
/// what it printed.
pub fn measure(p: usize, n: usize) -> Result<Row, String> {
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let out = Command::new(exe)
        .args(["--case", &p.to_string(), &n.to_string()])
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| e.to_string())?;
    let text = String::from_utf8_lossy(&out.stdout);
    if let Some(why) = text.lines().find_map(|l| l.strip_prefix("failed ")) {
        return Err(why.to_string());
    }
    if !out.status.success() {
        return Err(format!(
            "p = {p}, {n}²: the process of the case ended with {}",
            out.status
        ));
    }
    let mut values = std::collections::HashMap::new();
    for line in text.lines() {
        let (k, v) = line
            .split_once(' ')
            .ok_or(format!("p = {p}, {n}²: `{line}` is not `key value`"))?;
        let v: f64 = v.parse().map_err(|e| format!("{k}: {e}"))?;
        values.insert(k.to_string(), v);
    }
    let get = |k: &str| -> Result<f64, String> {
        values
            .get(k)
            .copied()
            .ok_or(format!("p = {p}, {n}²: the case printed no {k}"))
    };
    let solve = if values.contains_key("total") {
        Some(InProcess {
            condensation: get("condensation")?,
            iterations: get("iterations")? as usize,
            iterations_s: get("iterations_s")?,
            recovery: get("recovery")?,
            total: get("total")?,
            total_cpu: get("total_cpu")?,
            force_error: get("force_error")?,
            peak: get("peak")?,
        })
    } else {
        None
    };
    let timing = PhaseTimes::from_keys(|k| {
        values
            .get(&format!(
                "cli_{}",
                if k == "wall" { "timing_wall" } else { k }
            ))
            .copied()
    })
    .map_err(|k| format!("p = {p}, {n}²: no cli_{k}"))?;
    let cli = CliRun {
        max_memory: (get("cli_fallback")? != 0.0).then_some(FALLBACK_MAX_MEMORY),
        wall: get("cli_wall")?,
        cpu: get("cli_cpu")?,
        peak: get("cli_peak")?,
        timing,
        iterations: get("cli_iteration_count")? as usize,
    };
    let within = (cli.timing.sum() - cli.wall).abs() / cli.wall;
    if n >= PARTS_CHECKED_FROM && within > PARTS_WITHIN {
        return Err(format!(
            "p = {p}, {n}²: the [timing] parts add up to {:.3} s, the run took {:.3} s",
            cli.timing.sum(),
            cli.wall
        ));
    }
    Ok(Row {
        p,
        n,
        dofs: get("dofs")? as usize,
        layer: get("layer")? as usize,
        assembly: get("assembly")?,
        cholesky: get("cholesky")?,
        cholesky_first: get("cholesky_first")?,
        cholesky_first_cpu: get("cholesky_first_cpu")?,
        cholesky_cpu: get("cholesky_cpu")?,
        route_b: get("route_b")?,
        solve,
        cli,
    })
}

/// A case above [`crate::IN_PROCESS_UP_TO`] that could not run.
pub struct NotRun {
    pub p: usize,
    pub n: usize,
    pub reason: String,
}
