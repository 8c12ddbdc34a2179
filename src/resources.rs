//! Resources known before work starts: degrees of freedom, matrix
//! non-zeros and peak memory of a run, estimated from the scene alone, and
//! the memory budget they are checked against.
//!
//! The estimate uses only the knot vectors of the exact geometry and the
//! refinement asked for (O(number of knots) work, nothing of the size of
//! the discretisation is allocated), so a scene that would need hundreds
//! of gigabytes is refused in microseconds, naming the key that makes it
//! large, instead of dying in an allocation.
//!
//! # The memory model
//!
//! Per body with n₀ × n₁ control points of degrees p, q on E elements:
//!
//! - element matrix entries T = E · 4 (p+1)²(q+1)² (the assembly stores one
//!   coordinate triplet of 24 bytes per entry, and holds all element
//!   matrices of a body, 8 bytes per entry, until they are scattered);
//! - non-zeros nnz = 4 · n₀(2p+1) · n₁(2q+1) (basis functions overlap p+1
//!   spans per direction: an upper bound, exact away from the ends for
//!   maximal continuity);
//! - contact triplets T_c = Σ points · (2 · element control points of the
//!   slave and master)², since every contact point couples whole elements;
//! - the factor of the kernel, [`FILL`] · nnz · log₂(DOFs) entries of 8
//!   bytes (nested dissection on a 2D mesh), twice that for LU; the
//!   Cholesky-plus-low-rank factorisation also keeps the dense block
//!   Z = S⁻¹U of DOFs × rank entries, and two kernels (tied and secant)
//!   are alive at once;
//! - the VTU, [`VTU_BYTES_PER_POINT`] per sampled point (samples, cells
//!   and the XML text).
//!
//! The peak is the largest of the assembly phase, the sparsity-pattern
//! phase, and the solve (factor plus the matrices kept alive), plus a
//! fixed [`BASE_BYTES`]. The constants were calibrated against the peak
//! resident memory of `iga-contact run` on scenes from degree 1 to 10 (see
//! `examples/memory_calibration.rs` and `RELIABILITY_NOTES.md`): the
//! estimate is above every measured peak.

use crate::error::{Error, Result};

/// Bytes of a run that does not depend on its size (code, allocator arenas,
/// thread stacks, fonts).
pub const BASE_BYTES: f64 = 64.0 * MIB;
/// Factor entries per matrix non-zero and per level of nested dissection.
pub const FILL: f64 = 1.0;
/// Safety factor on the modelled bytes (allocator slack, transient copies).
pub const MARGIN: f64 = 1.25;
/// VTU bytes per sampled point: 88 B of samples, about 50 B of cells, and
/// the XML text (≈ 250 B) with room for its growth.
pub const VTU_BYTES_PER_POINT: f64 = 640.0;

const MIB: f64 = 1024.0 * 1024.0;

/// The discretisation of one body, as the scene asks for it.
#[derive(Clone, Debug, PartialEq)]
pub struct BodySize {
    /// Key path of the body's refinement (or geometry) in the scene.
    pub field: String,
    /// The value shown when this body is named as too large.
    pub value: String,
    /// Control points per direction.
    pub n: [usize; 2],
    pub degree: [usize; 2],
    /// Elements per direction.
    pub elements: [usize; 2],
    /// Elements along each side: [xi_min/xi_max, eta_min/eta_max].
    pub side_elements: [usize; 2],
}

impl BodySize {
    pub fn control_points(&self) -> f64 {
        self.n[0] as f64 * self.n[1] as f64
    }

    pub fn n_elements(&self) -> f64 {
        self.elements[0] as f64 * self.elements[1] as f64
    }

    /// Control points of one element.
    pub fn element_points(&self) -> f64 {
        (self.degree[0] + 1) as f64 * (self.degree[1] + 1) as f64
    }

    /// Entries of all element stiffness matrices.
    pub fn element_entries(&self) -> f64 {
        let m = 2.0 * self.element_points();
        self.n_elements() * m * m
    }

    /// Upper bound on the stiffness non-zeros.
    pub fn nonzeros(&self) -> f64 {
        let dir = |d: usize| {
            let n = self.n[d] as f64;
            (n * (2 * self.degree[d] + 1) as f64).min(n * n)
        };
        4.0 * dir(0) * dir(1)
    }
}

/// A contact pair's share of the estimate.
#[derive(Clone, Debug, PartialEq)]
pub struct PairSize {
    /// Upper bound on the contact quadrature points.
    pub points: f64,
    /// DOFs coupled at one point (slave element plus master element).
    pub dofs_per_point: f64,
    /// Rank of the low-rank part of the kernel: the DOFs of the contact
    /// trace (both sides), twice that for θ ≠ 0.
    pub rank: f64,
}

/// How the kernels are factorised, for the fill estimate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Factoring {
    /// Cholesky (with a low-rank correction): one factor.
    Cholesky,
    /// LU may be needed: room for both factors.
    Lu,
}

/// The estimated size of a run.
#[derive(Clone, Debug, PartialEq)]
pub struct Estimate {
    pub bodies: Vec<BodySize>,
    pub pairs: Vec<PairSize>,
    /// Degrees of freedom before supports are applied.
    pub dofs: f64,
    /// Stiffness non-zeros (upper bound).
    pub nonzeros: f64,
    /// Points sampled for the VTU (0 if none is written).
    pub vtu_points: f64,
    pub factoring: Factoring,
    /// The bytes of each phase: assembly, pattern, solve, output.
    pub phases: [f64; 4],
}

/// Names of the phases, aligned with [`Estimate::phases`].
pub const PHASES: [&str; 4] = ["assembly", "sparsity pattern", "solve", "output"];

impl Estimate {
    /// Computes the phases from the sizes.
    pub fn new(
        bodies: Vec<BodySize>,
        pairs: Vec<PairSize>,
        vtu_subdivisions: Option<usize>,
        factoring: Factoring,
    ) -> Self {
        let t: f64 = bodies.iter().map(BodySize::element_entries).sum();
        let t_max = bodies
            .iter()
            .map(BodySize::element_entries)
            .fold(0.0, f64::max);
        let tc: f64 = pairs
            .iter()
            .map(|p| p.points * p.dofs_per_point * p.dofs_per_point)
            .sum();
        let nnz: f64 = bodies.iter().map(BodySize::nonzeros).sum();
        let dofs: f64 = bodies.iter().map(|b| 2.0 * b.control_points()).sum();
        let vtu_points = vtu_subdivisions.map_or(0.0, |s| {
            let per = ((s + 1) * (s + 1)) as f64;
            bodies.iter().map(|b| b.n_elements() * per).sum()
        });
        // Assembly: the triplets (reserved in full) and one body's element matrices.
        let assembly = 24.0 * t + 8.0 * t_max;
        // Pattern: the triplets, three index arrays over them, the pattern.
        let pattern = 48.0 * (t + tc) + 8.0 * nnz + 40.0 * dofs;
        // Kept for the solve: triplet values and slots, K and its pattern.
        let kept = 16.0 * t + 8.0 * tc + 24.0 * nnz;
        let levels = dofs.max(2.0).log2();
        let fill = 8.0 * FILL * nnz * levels;
        let rank: f64 = pairs.iter().map(|p| p.rank).sum();
        let factor = 2.0
            * match factoring {
                Factoring::Cholesky => fill + 8.0 * dofs * rank,
                Factoring::Lu => 2.0 * fill,
            };
        // A kernel build: contact triplets and two matrices of the pattern.
        let solve = kept + 24.0 * tc + 32.0 * nnz + factor;
        let output = kept + VTU_BYTES_PER_POINT * vtu_points;
        Self {
            bodies,
            pairs,
            dofs,
            nonzeros: nnz,
            vtu_points,
            factoring,
            phases: [assembly, pattern, solve, output].map(|b| MARGIN * b + BASE_BYTES),
        }
    }

    /// The estimated peak memory in bytes.
    pub fn peak_bytes(&self) -> f64 {
        self.phases.iter().copied().fold(0.0, f64::max)
    }

    /// The phase that sets the peak.
    pub fn peak_phase(&self) -> &'static str {
        let k = (0..4)
            .max_by(|&a, &b| self.phases[a].total_cmp(&self.phases[b]))
            .unwrap_or(0);
        PHASES[k]
    }

    /// Refuses the run if the peak exceeds `budget`, naming the body whose
    /// discretisation weighs most (or the VTU sampling when the output
    /// phase sets the peak).
    pub fn check(&self, budget: &Budget, vtu_field: &str) -> Result<()> {
        let peak = self.peak_bytes();
        if peak <= budget.bytes as f64 {
            return Ok(());
        }
        let summary = format!(
            "the run would need about {} ({} phase: {} DOFs, {} matrix non-zeros), over the \
             memory budget of {} ({})",
            human_bytes(peak),
            self.peak_phase(),
            human_count(self.dofs),
            human_count(self.nonzeros),
            human_bytes(budget.bytes as f64),
            budget.source
        );
        if self.peak_phase() == "output" && self.vtu_points > 0.0 {
            return Err(Error::invalid(
                vtu_field,
                format!("{} sample points", human_count(self.vtu_points)),
                format!("{summary}; lower the subdivisions or turn the VTU off"),
            ));
        }
        let heaviest = self
            .bodies
            .iter()
            .max_by(|a, b| a.element_entries().total_cmp(&b.element_entries()));
        let (field, value) = heaviest.map_or(("body".to_string(), String::new()), |b| {
            (b.field.clone(), b.value.clone())
        });
        Err(Error::invalid(
            field,
            value,
            format!("{summary}; use fewer elements or a lower degree"),
        ))
    }
}

/// The memory a run may use, and where that figure comes from.
#[derive(Clone, Debug, PartialEq)]
pub struct Budget {
    pub bytes: u64,
    pub source: String,
}

/// Share of the physical memory a run may use by default.
pub const PHYSICAL_SHARE: f64 = 0.75;
/// Share of an address-space limit (`ulimit -v`) a run may use: virtual
/// memory also holds code, thread stacks and allocator arenas.
pub const ADDRESS_SPACE_SHARE: f64 = 0.8;

impl Budget {
    /// An explicit budget (the `--max-memory` option).
    pub fn explicit(bytes: u64) -> Self {
        Self {
            bytes,
            source: "set by --max-memory".into(),
        }
    }

    /// The default: [`PHYSICAL_SHARE`] of the physical memory
    /// (`/proc/meminfo`), or less under an address-space limit.
    pub fn from_machine() -> Self {
        let mut budget = match meminfo_total() {
            Some(total) => Self {
                bytes: (total as f64 * PHYSICAL_SHARE) as u64,
                source: format!(
                    "{:.0}% of the physical memory of {}; --max-memory overrides",
                    100.0 * PHYSICAL_SHARE,
                    human_bytes(total as f64)
                ),
            },
            None => Self {
                bytes: u64::MAX,
                source: "physical memory unknown".into(),
            },
        };
        if let Some(limit) = address_space_limit() {
            let usable = (limit as f64 * ADDRESS_SPACE_SHARE) as u64;
            if usable < budget.bytes {
                budget = Self {
                    bytes: usable,
                    source: format!(
                        "{:.0}% of the address-space limit (ulimit -v) of {}",
                        100.0 * ADDRESS_SPACE_SHARE,
                        human_bytes(limit as f64)
                    ),
                };
            }
        }
        budget
    }
}

/// `MemTotal` from `/proc/meminfo`, in bytes.
pub(crate) fn meminfo_total() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

/// The soft address-space limit of this process, if any (`/proc/self/limits`).
fn address_space_limit() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/self/limits").ok()?;
    let line = text.lines().find(|l| l.starts_with("Max address space"))?;
    line.split_whitespace().nth(3)?.parse().ok()
}

/// Parses a size such as `8G`, `512M`, `1.5GiB` or `1000000` (bytes).
pub fn parse_size(text: &str) -> Result<u64> {
    let t = text.trim();
    let split = t
        .find(|c: char| !(c.is_ascii_digit() || c == '.'))
        .unwrap_or(t.len());
    let (num, unit) = t.split_at(split);
    let scale = match unit.trim().to_ascii_lowercase().as_str() {
        "" | "b" => 1.0,
        "k" | "kb" | "kib" => 1024.0,
        "m" | "mb" | "mib" => MIB,
        "g" | "gb" | "gib" => 1024.0 * MIB,
        "t" | "tb" | "tib" => 1024.0 * 1024.0 * MIB,
        _ => f64::NAN,
    };
    let value: f64 = num.parse().unwrap_or(f64::NAN) * scale;
    if (1.0..1.8e19).contains(&value) {
        Ok(value as u64)
    } else {
        Err(Error::invalid(
            "--max-memory",
            text,
            "must be a size such as 8G, 512M or a number of bytes",
        ))
    }
}

/// `1.5 GiB`-style text.
pub fn human_bytes(b: f64) -> String {
    let units = ["B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"];
    let mut v = b;
    let mut k = 0;
    while v >= 1024.0 && k + 1 < units.len() {
        v /= 1024.0;
        k += 1;
    }
    if k == 0 {
        format!("{v:.0} B")
    } else {
        format!("{v:.1} {}", units[k])
    }
}

/// `3.2e9`-style text for large counts, plain below a million.
pub fn human_count(n: f64) -> String {
    if n < 1e6 {
        format!("{n:.0}")
    } else {
        format!("{n:.2e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_with_units() {
        assert_eq!(parse_size("1000").unwrap(), 1000);
        assert_eq!(parse_size("8G").unwrap(), 8 << 30);
        assert_eq!(parse_size("512 MiB").unwrap(), 512 << 20);
        assert_eq!(parse_size("1.5g").unwrap(), 3 << 29);
        for bad in ["", "G", "-1G", "8X", "nan", "0"] {
            let e = parse_size(bad).unwrap_err().to_string();
            assert!(e.contains("--max-memory"), "{bad}: {e}");
        }
    }

    #[test]
    fn the_budget_is_below_the_physical_memory() {
        let b = Budget::from_machine();
        if let Some(total) = meminfo_total() {
            assert!(b.bytes < total, "{b:?}");
        }
    }
}
