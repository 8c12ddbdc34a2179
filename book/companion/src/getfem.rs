//! The peer: GetFEM's runs of the same Hertz problem, made by
//! `scripts/getfem_hertz.py` as a child process and read back from the CSV
//! it writes, and GetFEM's estimators applied to our solutions, so that
//! both codes are measured against the same reference solution with the
//! same estimator.

use iga_contact::contact::{ContactPoint, Role};
use iga_contact::error::{Error, Result};
use iga_contact::post;
use iga_contact::problem::Problem;
use std::process::Command;

/// The script, and where it writes its CSV, from the source tree's root.
pub const SCRIPT: &str = "scripts/getfem_hertz.py";
pub const CSV: &str = "data/getfem/hertz_getfem.csv";
/// The interpreter Debian's `python3-getfem` installs for.
pub const PYTHON: &str = "/usr/bin/python3";

// ANCHOR: peer_run
/// One GetFEM run (one line of the CSV).
#[derive(Clone, Debug)]
pub struct PeerRun {
    /// Lagrange degree of the Q_k element.
    pub degree: usize,
    /// Elements per direction.
    pub elements: usize,
    pub dofs: usize,
    /// The factor F of Eq. (11) the script gave GetFEM's brick.
    pub factor: f64,
    /// The largest relative difference of the brick's γ from Eq. (11) at
    /// the contact sample points.
    pub gamma_deviation: f64,
    /// max(−σ_yy) on 20 points per contact face (Pa).
    pub p0: f64,
    /// The first zero of the deformed gap y + u_y along the arc (m).
    pub half_width: f64,
    pub newton_iterations: usize,
    pub converged: bool,
    /// The model set-up (spaces, integration, bricks), mesh excluded (s).
    pub setup_seconds: f64,
    /// GetFEM's Newton with MUMPS (s).
    pub solve_seconds: f64,
}
// ANCHOR_END: peer_run

/// The CSV: its comment line (how the runs were made), the GetFEM version
/// and date of the runs, and every run.
#[derive(Clone, Debug)]
pub struct Peer {
    pub comment: String,
    pub version: String,
    pub date: String,
    pub runs: Vec<PeerRun>,
}

/// Whether GetFEM can be imported by [`PYTHON`].
pub fn available() -> bool {
    Command::new(PYTHON)
        .args(["-c", "import getfem"])
        .output()
        .is_ok_and(|o| o.status.success())
}

/// Runs the script on `ladder` (elements per direction, for Q1 and Q2) at
/// the penalty factors `factors`, and reads what it wrote.
pub fn run(ladder: &[usize], factors: &[f64]) -> Result<Peer> {
    let root = crate::source_root();
    let meshes: Vec<String> = ladder.iter().map(|n| n.to_string()).collect();
    let meshes = meshes.join(",");
    let factors: Vec<String> = factors.iter().map(|f| f.to_string()).collect();
    let out = Command::new(PYTHON)
        .current_dir(root)
        .arg(SCRIPT)
        .args(["--out", CSV, "--ladder"])
        .arg(format!("q1:{meshes}"))
        .arg(format!("q2:{meshes}"))
        .arg("--factor")
        .args(&factors)
        .output()
        .map_err(|source| Error::Io {
            path: PYTHON.into(),
            source,
        })?;
    if !out.status.success() {
        return Err(Error::invalid(
            SCRIPT,
            format!("exit status {}", out.status),
            String::from_utf8_lossy(&out.stderr).trim().to_string(),
        ));
    }
    load()
}

/// Reads [`CSV`].
pub fn load() -> Result<Peer> {
    let path = crate::source_root().join(CSV);
    let text = std::fs::read_to_string(&path).map_err(|source| Error::Io {
        path: path.display().to_string(),
        source,
    })?;
    parse(&text)
}

const COLUMNS: [&str; 18] = [
    "code",
    "element",
    "degree",
    "elements",
    "dofs",
    "factor",
    "gamma",
    "gamma_deviation",
    "r_min",
    "r_max",
    "p0",
    "half_width",
    "newton_iterations",
    "converged",
    "setup_seconds",
    "solve_seconds",
    "getfem_version",
    "date",
];

/// Parses the CSV text (see [`load`]): every problem is an error naming
/// the file, the line, the column and the value. The file has no quoted
/// fields, so a split at commas reads it exactly.
pub fn parse(text: &str) -> Result<Peer> {
    let bad = |line: usize, column: &str, value: &str, why: &str| {
        Error::invalid(
            format!("{CSV}: line {line}, column `{column}`"),
            value,
            why.to_string(),
        )
    };
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
    let mut comment = String::new();
    let (header_line, header) = loop {
        match lines.next() {
            Some((_, l)) if l.starts_with('#') => {
                comment = l.trim_start_matches('#').trim().to_string();
            }
            Some((_, l)) if l.trim().is_empty() => {}
            Some(found) => break found,
            None => return Err(bad(1, "header", "", "no header line")),
        }
    };
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    let mut index = [0; COLUMNS.len()];
    for (k, c) in COLUMNS.iter().enumerate() {
        index[k] = names
            .iter()
            .position(|n| n == c)
            .ok_or_else(|| bad(header_line, c, header, "the header lacks this column"))?;
    }
    let (mut version, mut date) = (String::new(), String::new());
    let mut runs = Vec::new();
    for (n, line) in lines {
        if line.trim().is_empty() || line.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        if fields.len() != names.len() {
            return Err(bad(
                n,
                "(all)",
                line,
                &format!("{} fields, the header has {}", fields.len(), names.len()),
            ));
        }
        let field = |c: usize| fields[index[c]];
        let number = |c: usize| -> Result<f64> {
            let v = field(c);
            match v.parse::<f64>() {
                Ok(x) if x.is_finite() => Ok(x),
                _ => Err(bad(n, COLUMNS[c], v, "not a finite number")),
            }
        };
        let count = |c: usize| -> Result<usize> {
            let v = field(c);
            v.parse::<usize>()
                .map_err(|_| bad(n, COLUMNS[c], v, "not a whole number"))
        };
        if field(0) != "getfem" {
            return Err(bad(n, "code", field(0), "expected `getfem`"));
        }
        let converged = match field(13) {
            "true" => true,
            "false" => false,
            v => return Err(bad(n, "converged", v, "expected true or false")),
        };
        let run = PeerRun {
            degree: count(2)?,
            elements: count(3)?,
            dofs: count(4)?,
            factor: number(5)?,
            gamma_deviation: number(7)?,
            p0: number(10)?,
            half_width: number(11)?,
            newton_iterations: count(12)?,
            converged,
            setup_seconds: number(14)?,
            solve_seconds: number(15)?,
        };
        if field(1) != format!("Q{}", run.degree) {
            return Err(bad(n, "element", field(1), "does not match the degree"));
        }
        (version, date) = (field(16).to_string(), field(17).to_string());
        runs.push(run);
    }
    if runs.is_empty() {
        return Err(bad(header_line, "(all)", "", "no runs"));
    }
    Ok(Peer {
        comment,
        version,
        date,
        runs,
    })
}

// ANCHOR: peer_estimators
/// The slave points of pair 0 on 20 Gauss points per contact element,
/// ordered by x: where the GetFEM script samples its solutions. Where a
/// coarse Lagrange interpolant of the disk folds near the end of the arc
/// (Q2 on 4²), fewer points per element, as the dense profile does.
fn samples(problem: &Problem) -> Result<Vec<ContactPoint>> {
    let mut found = post::dense_contact_points(problem, 20);
    for per_element in [16, 12, 10, 8, 6, 4] {
        if !matches!(found, Err(Error::Geometry(_))) {
            break;
        }
        found = post::dense_contact_points(problem, per_element);
    }
    let mut points: Vec<ContactPoint> = found?
        .into_iter()
        .filter(|c| c.role == Role::Slave && c.pair == 0)
        .collect();
    points.sort_by(|a, b| a.x[0].total_cmp(&b.x[0]));
    Ok(points)
}

/// The GetFEM script's estimator of p₀ applied to our solution `full` of
/// `problem`: max(−σ_n) on its sample points (the floor's normal is −y, so
/// σ_n = σ_yy there).
pub fn peak_pressure(problem: &Problem, full: &[f64]) -> Result<f64> {
    Ok(samples(problem)?
        .iter()
        .map(|c| -c.normal_stress_and_jump(full).0)
        .fold(f64::NEG_INFINITY, f64::max))
}

/// The GetFEM script's estimator of a applied to our solution: the first
/// x, going outwards from x = 0, where the deformed gap g₀ − ⟦u_n⟧ turns
/// from ≤ 0 to > 0 (linear between the two samples), and the number of
/// samples before it whose gap is negative (overlap).
pub fn first_gap_zero(problem: &Problem, full: &[f64]) -> Result<(f64, usize)> {
    let points = samples(problem)?;
    let gap: Vec<f64> = points
        .iter()
        .map(|c| c.g0 - c.normal_stress_and_jump(full).1)
        .collect();
    for k in 1..points.len() {
        if gap[k - 1] <= 0.0 && gap[k] > 0.0 {
            let (x0, x1) = (points[k - 1].x[0], points[k].x[0]);
            let x = x0 + (x1 - x0) * (-gap[k - 1]) / (gap[k] - gap[k - 1]);
            return Ok((x, gap[..k].iter().filter(|&&g| g < 0.0).count()));
        }
    }
    let last = points.last().map_or(0.0, |c| c.x[0]);
    Ok((last, gap.iter().filter(|&&g| g < 0.0).count()))
}
// ANCHOR_END: peer_estimators
