//! The peer: GetFEM's runs of the same Hertz problem, read from the CSV
//! that `scripts/getfem_hertz.py` wrote, and GetFEM's estimator of p₀
//! applied to one of our solutions, so that both codes' p₀ are measured
//! against the same reference solution with their own estimator.

use iga_contact::contact::Role;
use iga_contact::error::{Error, Result};
use iga_contact::post;
use iga_contact::problem::Problem;
use std::path::Path;

/// Where the committed GetFEM runs are, from the crate's root.
pub const CSV: &str = "data/getfem/hertz_getfem.csv";

// ANCHOR: peer_run
/// One GetFEM run (one line of the CSV).
#[derive(Clone, Debug)]
pub struct PeerRun {
    /// Lagrange degree of the Q_k element.
    pub degree: usize,
    /// Elements per direction.
    pub elements: usize,
    pub dofs: usize,
    /// max(−σ_yy) on 20 points per contact face (Pa).
    pub p0: f64,
    /// The first zero of the deformed gap y + u_y along the arc (m).
    pub half_width: f64,
    pub newton_iterations: usize,
    /// Model set-up and solve, mesh generation excluded (s).
    pub seconds: f64,
}
// ANCHOR_END: peer_run

/// The CSV: its comment line (how the runs were made), the GetFEM version
/// and date of the runs, and the converged runs.
#[derive(Clone, Debug)]
pub struct Peer {
    pub comment: String,
    pub version: String,
    pub date: String,
    pub runs: Vec<PeerRun>,
}

/// Reads [`CSV`]. Every problem is an error naming the file, the line, the
/// column and the value; a run GetFEM did not converge is an error too,
/// since its p₀ and a are not results.
pub fn load() -> Result<Peer> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(CSV);
    let text = std::fs::read_to_string(&path).map_err(|source| Error::Io {
        path: path.display().to_string(),
        source,
    })?;
    parse(&text)
}

const COLUMNS: [&str; 12] = [
    "code",
    "element",
    "degree",
    "elements",
    "dofs",
    "p0",
    "half_width",
    "newton_iterations",
    "converged",
    "seconds",
    "getfem_version",
    "date",
];

/// Parses the CSV text (see [`load`]). The file has no quoted fields, so a
/// split at commas reads it exactly; a CSV crate would add a dependency for
/// one file of twelve plain columns.
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
                Ok(x) if x.is_finite() && x >= 0.0 => Ok(x),
                _ => Err(bad(n, COLUMNS[c], v, "not a finite non-negative number")),
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
        match field(8) {
            "true" => {}
            "false" => return Err(bad(n, "converged", "false", "a run that did not converge")),
            v => return Err(bad(n, "converged", v, "expected true or false")),
        }
        let run = PeerRun {
            degree: count(2)?,
            elements: count(3)?,
            dofs: count(4)?,
            p0: number(5)?,
            half_width: number(6)?,
            newton_iterations: count(7)?,
            seconds: number(9)?,
        };
        if field(1) != format!("Q{}", run.degree) {
            return Err(bad(n, "element", field(1), "does not match the degree"));
        }
        if run.p0 == 0.0 || run.half_width == 0.0 {
            return Err(bad(n, "p0", field(5), "p0 and half_width must be positive"));
        }
        (version, date) = (field(10).to_string(), field(11).to_string());
        runs.push(run);
    }
    if runs.is_empty() {
        return Err(bad(header_line, "(all)", "", "no runs"));
    }
    runs.sort_by_key(|r| (r.degree, r.elements));
    Ok(Peer {
        comment,
        version,
        date,
        runs,
    })
}

// ANCHOR: peer_estimators
/// The GetFEM script's estimator of p₀ applied to our solution `full` of
/// `problem`: max(−σ_n) on 20 Gauss points per contact element (the
/// floor's normal is −y, so σ_n = σ_yy there).
///
/// Its estimator of a, the first zero of the deformed gap, is not applied
/// to our solutions: Nitsche's method keeps the gap inside the contact
/// zone only as small as the discretisation error over γ, not of one sign,
/// and on our solutions it is positive from the first points on, so that
/// "first zero" lands next to x = 0. GetFEM's a is therefore compared with
/// our estimator's.
pub fn peak_pressure(problem: &Problem, full: &[f64]) -> Result<f64> {
    let points = post::dense_contact_points(problem, 20)?;
    Ok(points
        .iter()
        .filter(|c| c.role == Role::Slave && c.pair == 0)
        .map(|c| -c.normal_stress_and_jump(full).0)
        .fold(f64::NEG_INFINITY, f64::max))
}
// ANCHOR_END: peer_estimators
