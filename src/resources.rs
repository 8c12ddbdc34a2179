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
//! It follows the data structures of the default solver, which factorises
//! the bulk once by sparse Cholesky and iterates on the dense contact
//! layer ([`crate::condense`]). Per body with n₀ × n₁ control points of
//! degrees p, q and N = 2 n₀ n₁ DOFs:
//!
//! - stiffness non-zeros nnz = 4 · n₀(2p+1) · n₁(2q+1) (basis functions
//!   overlap p+1 spans per direction: exact away from the ends for maximal
//!   continuity), stored as values and row indices (16 bytes each);
//! - the Cholesky factor's entries F(N, p) = exp(c₀ + c₁ℓ + c₂ℓ² + c₃r +
//!   c₄rℓ + c₅r²), ℓ = ln N, r = ln(p+1): a fit ([`FILL_FIT`]) to the
//!   exact counts of faer's symbolic analysis (AMD order) on rectangles of
//!   degree 1 to 10 and 8² to 512² elements, within a factor 1.35 of every
//!   one of them; stored in about [`FACTOR_BYTES`] per entry (values,
//!   supernodal row indices, workspace), twice that for LU;
//! - the contact couplings: every contact point couples all DOFs of its
//!   slave and master elements, d = 2 (p+1)(q+1) + master, and the
//!   pattern is built from the list of (row, column) pairs, d² per point,
//!   held twice (as listed and sorted by column, 16 bytes a pair);
//! - the layer: ℓ_c = 4 × the control points along the slave side (the two
//!   rows of control points the normal stress reaches) plus 2 × those of a
//!   deformable master side; its dense matrices (the Schur complement,
//!   the kernel being factorised, its factor and a copy) are 4 · 8 ℓ_c²
//!   bytes;
//! - the VTU, [`VTU_BYTES_PER_POINT`] per sampled point.
//!
//! The peak is the largest of three phases plus a fixed [`BASE_BYTES`]
//! and the [`WORKING_BYTES`] of vectors and allocator caches:
//! the pattern (couplings and the stiffness being built), the
//! factorisation (stiffness, the bulk-plus-penalty values and the AMD
//! pattern, 40 bytes per non-zero, with the factor and the layer's dense
//! matrices), and the output (stiffness and the VTU). The chapter
//! "Reliability" tabulates it against the peak resident memory (`VmHWM`)
//! of `iga-contact run` (`examples/memory_table.rs`).

use crate::error::{Error, Result};
use crate::material::Formulation;

/// Bytes of a run that does not depend on its size (code, allocator
/// arenas, thread stacks): the peak of the smallest scenes.
pub const BASE_BYTES: f64 = 16.0 * MIB;
/// Bytes the solver's vectors and the allocator's per-thread caches add
/// once a scene has more than [`WORKING_DOFS`] DOFs (measured: the peaks
/// of scenes of 10³ to 10⁴ DOFs lie this far above the data structures).
pub const WORKING_BYTES: f64 = 20.0 * MIB;
/// DOFs from which [`WORKING_BYTES`] count in full (in proportion below).
pub const WORKING_DOFS: f64 = 1000.0;
/// Coefficients of the fit of ln F, the Cholesky factor's entries, in
/// (1, ℓ, ℓ², r, rℓ, r²) with ℓ = ln(DOFs), r = ln(p+1).
pub const FILL_FIT: [f64; 6] = [-0.16039, 1.42787, -0.017929, 1.76683, 0.152347, -0.434232];
/// Bytes per factor entry: the value, the supernodal row indices and the
/// numeric workspace (the measured `Condensation::bytes` is 9.7 per entry).
pub const FACTOR_BYTES: f64 = 10.0;
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
    /// The bulk formulation: the mixed one widens the stencil.
    pub formulation: Formulation,
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

    /// How many spans beyond its own a basis function couples with in
    /// direction `d`: p − 1 for the mixed formulation, whose volumetric
    /// terms join the functions under one pressure function (p spans wide),
    /// 0 otherwise.
    pub fn reach(&self, d: usize) -> usize {
        match self.formulation {
            Formulation::Mixed => self.degree[d].saturating_sub(1),
            Formulation::Displacement | Formulation::LocalMixed => 0,
        }
    }

    /// Upper bound on the stiffness non-zeros: 2p + 1 coupled functions
    /// per direction, 2(p + reach) + 1 with the mixed stencil.
    pub fn nonzeros(&self) -> f64 {
        let dir = |d: usize| {
            let n = self.n[d] as f64;
            (n * (2 * (self.degree[d] + self.reach(d)) + 1) as f64).min(n * n)
        };
        4.0 * dir(0) * dir(1)
    }

    /// The degree whose stencil is as wide as this body's: the factor's
    /// fill ([`factor_entries`]) follows the stencil, so the mixed body of
    /// degree p fills like a displacement body of degree 2p − 1.
    pub fn stencil_degree(&self) -> usize {
        (0..2)
            .map(|d| self.degree[d] + self.reach(d))
            .max()
            .unwrap_or(0)
    }

    /// Bytes of the mixed formulation's pressure space while the stiffness
    /// is built: per pressure function (about one per control point) its
    /// divergence functional over the 2p × 2q control points of its
    /// support, two DOFs each, 16 bytes an entry.
    pub fn pressure_bytes(&self) -> f64 {
        match self.formulation {
            Formulation::Mixed => {
                let support = (2 * self.degree[0] * 2 * self.degree[1]) as f64;
                self.control_points() * 2.0 * support * 16.0
            }
            Formulation::Displacement | Formulation::LocalMixed => 0.0,
        }
    }
}

/// A contact pair's share of the estimate.
#[derive(Clone, Debug, PartialEq)]
pub struct PairSize {
    /// Upper bound on the contact quadrature points.
    pub points: f64,
    /// DOFs coupled at one point (slave element plus master element).
    pub dofs_per_point: f64,
    /// DOFs of the contact layer the pair contributes: those the normal
    /// stress and the jump reach.
    pub layer: f64,
}

/// How the bulk is factorised, for the size of its factor.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Factoring {
    /// Cholesky: one triangle.
    Cholesky,
    /// LU: room for both triangles.
    Lu,
}

/// Entries of the sparse Cholesky factor of a body with `dofs` DOFs and
/// degree `degree` ([`FILL_FIT`]).
pub fn factor_entries(dofs: f64, degree: usize) -> f64 {
    let l = dofs.max(2.0).ln();
    let r = ((degree + 1) as f64).ln();
    let c = FILL_FIT;
    let fit = (c[0] + c[1] * l + c[2] * l * l + c[3] * r + c[4] * r * l + c[5] * r * r).exp();
    // A factor holds at most its full lower triangle.
    fit.min(dofs * (dofs + 1.0) / 2.0)
}

/// The estimated size of a run.
#[derive(Clone, Debug, PartialEq)]
pub struct Estimate {
    pub bodies: Vec<BodySize>,
    pub pairs: Vec<PairSize>,
    /// Free degrees of freedom: those the solve numbers (shared interface
    /// points once, supported components left out).
    pub dofs: f64,
    /// Stiffness non-zeros (upper bound).
    pub nonzeros: f64,
    /// The VTU's subdivisions per element side (none if no VTU is written).
    pub vtu_subdivisions: Option<usize>,
    /// Points sampled for the VTU (0 if none is written).
    pub vtu_points: f64,
    pub factoring: Factoring,
    /// Entries of the sparse factor (every body).
    pub factor_entries: f64,
    /// DOFs of the contact layer.
    pub layer: f64,
    /// The bytes of each phase ([`PHASES`]), [`BASE_BYTES`] included.
    pub phases: [f64; 3],
}

/// Names of the phases, aligned with [`Estimate::phases`].
pub const PHASES: [&str; 3] = ["sparsity pattern", "factorisation", "output"];

impl Estimate {
    /// Computes the phases from the sizes; `dofs` are the free DOFs.
    pub fn new(
        bodies: Vec<BodySize>,
        pairs: Vec<PairSize>,
        dofs: f64,
        vtu_subdivisions: Option<usize>,
        factoring: Factoring,
    ) -> Self {
        let couplings: f64 = pairs
            .iter()
            .map(|p| p.points * p.dofs_per_point * p.dofs_per_point)
            .sum();
        let nnz: f64 = bodies.iter().map(BodySize::nonzeros).sum();
        let vtu_points = vtu_subdivisions.map_or(0.0, |s| {
            let per = ((s + 1) * (s + 1)) as f64;
            bodies.iter().map(|b| b.n_elements() * per).sum()
        });
        let per_entry = match factoring {
            Factoring::Cholesky => FACTOR_BYTES,
            Factoring::Lu => 2.0 * FACTOR_BYTES,
        };
        let factor: f64 = bodies
            .iter()
            .map(|b| factor_entries(2.0 * b.control_points(), b.stencil_degree()))
            .sum();
        let layer: f64 = pairs.iter().map(|p| p.layer).sum::<f64>().min(dofs);
        // The stiffness: values and row indices.
        let k = 16.0 * nnz;
        // The pattern: the coupling pairs, listed and sorted, while the
        // stiffness is built.
        let pressure: f64 = bodies.iter().map(BodySize::pressure_bytes).sum();
        let pattern = 32.0 * couplings + k + pressure;
        // The factorisation: the stiffness, the bulk-plus-penalty values
        // and the AMD pattern of the interior, the factor, and the dense
        // matrices of the layer.
        let factorisation = k + 24.0 * nnz + per_entry * factor + 32.0 * layer * layer;
        let output = k + VTU_BYTES_PER_POINT * vtu_points;
        Self {
            bodies,
            pairs,
            dofs,
            nonzeros: nnz,
            vtu_subdivisions,
            vtu_points,
            factoring,
            factor_entries: factor,
            layer,
            phases: [pattern, factorisation, output]
                .map(|b| b + BASE_BYTES + WORKING_BYTES * (dofs / WORKING_DOFS).min(1.0)),
        }
    }

    /// The estimated peak memory in bytes.
    pub fn peak_bytes(&self) -> f64 {
        self.phases.iter().copied().fold(0.0, f64::max)
    }

    /// The phase that sets the peak.
    pub fn peak_phase(&self) -> &'static str {
        let k = (0..PHASES.len())
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
        // The VTU is named only when its samples are most of the peak.
        let vtu_bytes = VTU_BYTES_PER_POINT * self.vtu_points;
        if let (true, Some(s)) = (
            self.peak_phase() == "output" && vtu_bytes > 0.5 * peak,
            self.vtu_subdivisions,
        ) {
            return Err(Error::invalid(
                vtu_field,
                s,
                format!(
                    "{summary}, most of it the VTU's {} sample points; lower the subdivisions \
                     or turn the VTU off",
                    human_count(self.vtu_points)
                ),
            ));
        }
        let heaviest = self
            .bodies
            .iter()
            .max_by(|a, b| a.nonzeros().total_cmp(&b.nonzeros()));
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

/// Share of the available memory (`MemAvailable`: free memory plus what
/// the kernel can reclaim at once) a run's estimate may take by default.
/// The estimate can fall below the measured peak (the memory table of the
/// chapter "Reliability" gives its smallest ratio, and its check holds this
/// share below that ratio), so a run admitted at this share still peaks
/// inside the available memory.
pub const PHYSICAL_SHARE: f64 = 0.8;
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

    /// The default: [`PHYSICAL_SHARE`] of the available memory
    /// (`MemAvailable` of `/proc/meminfo`, else `MemTotal`), or less under
    /// an address-space limit.
    pub fn from_machine() -> Self {
        let available = meminfo("MemAvailable:").map(|b| (b, "available memory (MemAvailable)"));
        let mut budget =
            match available.or_else(|| meminfo("MemTotal:").map(|b| (b, "physical memory"))) {
                Some((bytes, what)) => Self {
                    bytes: (bytes as f64 * PHYSICAL_SHARE) as u64,
                    source: format!(
                        "{:.0}% of the {what} of {}, a margin for the estimate's error; \
                         --max-memory overrides",
                        100.0 * PHYSICAL_SHARE,
                        human_bytes(bytes as f64)
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
pub fn meminfo_total() -> Option<u64> {
    meminfo("MemTotal:")
}

/// A line of `/proc/meminfo` (`key` with its colon), in bytes.
fn meminfo(key: &str) -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with(key))?;
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
            "must be a positive size such as 8G, 512M or a number of bytes (at least 1)",
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
    fn the_budget_is_the_available_memory_at_most() {
        let b = Budget::from_machine();
        if let Some(total) = meminfo_total() {
            assert!(b.bytes <= total, "{b:?}");
        }
    }

    /// The fit stays within the full triangle, and grows with the mesh
    /// and the degree over the range it was fitted on.
    #[test]
    fn the_factor_fit_grows_with_size_and_degree() {
        assert_eq!(factor_entries(4.0, 1), 10.0);
        for p in 1..=10 {
            let mut last = 0.0;
            for m in [8usize, 16, 64, 256, 1024] {
                let dofs = 2.0 * ((m + p) * (m + p)) as f64;
                let f = factor_entries(dofs, p);
                assert!(f > last && f > dofs, "p = {p}, {m}²: {f}");
                last = f;
            }
        }
    }
}
