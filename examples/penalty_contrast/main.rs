//! The disk on an elastic block: the heavy program behind the section
//! "Stiffness contrast" of the chapter "The penalty, measured". The Hertz
//! disk rests on a block whose modulus is 1 to 10⁶ times the disk's, on
//! three meshes, with both solvers and three variants of the pair (whose
//! modulus enters (11), which sides carry the contact terms), against the
//! disk on the rigid plane. Output: `book/src/generated/penalty_contrast/`.
//!
//! Run it with `cargo run --release --example penalty_contrast` (a few
//! minutes of one core).
//!
//! The parts: the three variants against the rigid plane (`contrast.rs`:
//! Table PS3, Fig. PS2) and the other two θ (`theta.rs`: Table PS4).

mod contrast;
mod theta;

use companion::chapter::Chapter;
use companion::penalty::{hertz, measure, Run};
use companion::Solver;
use iga_contact::contact::{Modulus, Sides, Theta};
use iga_contact::error::Result;
use iga_contact::problem::Problem;
use iga_contact::report::table::{Cell, Format};
use iga_contact::scene::RefineSpec;

// ANCHOR: contrast_setup
/// Block stiffness over disk stiffness, E_block / E_disk.
const RATIOS: [f64; 4] = [1.0, 1e2, 1e4, 1e6];
/// Elements per direction of the disk (the block has 2n × n).
const CONTRAST_MESHES: [usize; 3] = [16, 32, 64];

/// The variants compared: whose modulus enters (11), and which sides
/// carry the contact terms.
#[derive(Clone, Copy, PartialEq)]
enum Variant {
    /// The slave's modulus, the biased form (the crate's default).
    Slave,
    /// The larger modulus, the biased form.
    Max,
    /// The slave's modulus, the unbiased form.
    Unbiased,
}

impl Variant {
    /// In the column order of Table PS3.
    const ALL: [Variant; 3] = [Variant::Slave, Variant::Max, Variant::Unbiased];

    fn modulus(self) -> Modulus {
        match self {
            Variant::Slave | Variant::Unbiased => Modulus::Slave,
            Variant::Max => Modulus::Max,
        }
    }

    fn sides(self) -> Sides {
        match self {
            Variant::Slave | Variant::Max => Sides::Biased,
            Variant::Unbiased => Sides::Unbiased,
        }
    }

    /// The name its facts and curves go by.
    fn name(self) -> &'static str {
        match self {
            Variant::Slave => "slave",
            Variant::Max => "max",
            Variant::Unbiased => "unbiased",
        }
    }
}

/// `data/scenes/disk_on_block.toml` with the disk on n² elements, the
/// block 2n × n, the block's modulus `ratio` times the disk's, and the
/// pair's `variant` and `theta`.
fn disk_on_block(n: usize, ratio: f64, variant: Variant, theta: Theta) -> Result<Problem> {
    let mut s = companion::shipped("disk_on_block.toml")?
        .refined("disk", RefineSpec::iga(2, [n, n]))?
        .refined("block", RefineSpec::iga(2, [2 * n, n]))?
        .with_nitsche(|x| {
            x.modulus = variant.modulus();
            x.sides = variant.sides();
            x.theta = theta;
        });
    s.body_mut("block")?.material.young *= ratio;
    s.build()
}

/// The same disk on the rigid plane (the Hertz scene on the same mesh,
/// with the same θ and the same segment integration).
fn rigid(n: usize, theta: Theta, factor: f64) -> Result<Problem> {
    hertz(n, |x| {
        x.theta = theta;
        x.penalty_factor = factor;
        x.integration = iga_contact::contact::Integration::Segment;
    })
}
// ANCHOR_END: contrast_setup

/// p₀ of the disk on the rigid plane with the default BFGS.
fn rigid_plane_p0(n: usize, theta: Theta, factor: f64) -> Result<f64> {
    Ok(measure(&rigid(n, theta, factor)?, &Solver::Bfgs.options())?
        .expect("the rigid case converges")
        .p0)
}

/// Both solvers on one problem: the default BFGS and Newton.
struct Both {
    bfgs: Run,
    newton: Run,
}

impl Both {
    fn solve(problem: &Problem) -> Result<Both> {
        Ok(Both {
            bfgs: measure(problem, &Solver::Bfgs.options())?,
            newton: measure(problem, &Solver::Newton.options())?,
        })
    }

    /// Iterations of both solvers as "BFGS / Newton", or the failure.
    fn iterations(&self) -> Cell {
        let one = |o: &Run| match o {
            Ok(o) => o.solution.history.len().to_string(),
            Err(kind) => kind.to_string(),
        };
        Cell::Text(format!("{} / {}", one(&self.bfgs), one(&self.newton)))
    }
}

/// The section "Stiffness contrast" of "The penalty, measured", table by
/// table.
fn main() -> Result<()> {
    let mut chapter = Chapter::from_args("penalty_contrast")?;
    let started = std::time::Instant::now();

    // Table PS3 and Fig. PS2: the three variants against the rigid plane.
    let contrast = contrast::solve_contrast()?;
    chapter.table("contrast", &contrast::contrast_table(&contrast)?)?;
    contrast::draw_contrast(&chapter, &contrast)?;
    contrast::record_contrast_facts(chapter.facts(), &contrast)?;

    // Table PS4: the other two θ on the default variant, and θ = 1 on the
    // rigid plane.
    let thetas = theta::solve_thetas()?;
    chapter.table("contrast_theta", &theta::theta_table(&thetas)?)?;
    let rigid_theta1 = theta::solve_rigid_theta1()?;
    let contrast_failures = contrast::failures(&contrast);
    theta::record_theta_facts(chapter.facts(), &thetas, &rigid_theta1, contrast_failures)?;

    let minutes = started.elapsed().as_secs_f64() / 60.0;
    chapter
        .facts()
        .timed_number("run_minutes", minutes, Format::Fixed(1))?;
    chapter.finish()
}
