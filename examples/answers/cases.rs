//! The cases of the campaign, class by class, each with the p₀ its answer
//! must reach: a closed form (the pressed block, Hertz), or a converged run
//! solved here (the disk on a block, the large loads, the coarse meshes).

use crate::scenes::{block, disk_on_block, ClosedForm, HertzScene, SceneSolver, Slave};
use iga_contact::post::PressureProfile;
use iga_contact::scene::Scene;
use iga_contact::solver::{solve, SolverOptions};
use iga_contact::Result;
use std::collections::BTreeMap;

/// The classes of scene, in the order the chapter lists them.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Class {
    /// A block pressed onto the floor by a prescribed top displacement: no
    /// rigid mode left to contact.
    Prescribed,
    /// Hertz with every length scaled by L (the pressure kept).
    LengthScale,
    /// Hertz with E and the load scaled by s.
    StiffnessScale,
    /// A disk on an elastic block, either body the slave.
    SlaveMaster,
    /// The unbiased form (each body the slave of one half), on the same
    /// disk on block.
    Unbiased,
    /// Hertz at ν up to 0.49999, every θ and degree.
    Poisson,
    /// Hertz with the penalty factor from 1e-12 to 1e6, every θ.
    Penalty,
    /// Hertz with the load up to 16 times the benchmark's.
    Load,
    /// Hertz from one element to 64² at degrees 2 to 5, every θ.
    Mesh,
}

impl Class {
    pub const ALL: [Class; 9] = [
        Class::Prescribed,
        Class::LengthScale,
        Class::StiffnessScale,
        Class::SlaveMaster,
        Class::Unbiased,
        Class::Poisson,
        Class::Penalty,
        Class::Load,
        Class::Mesh,
    ];

    pub fn label(self) -> &'static str {
        match self {
            Class::Prescribed => "pressed block, no rigid mode",
            Class::LengthScale => "length scale L = 1e-9 … 1e9",
            Class::StiffnessScale => "stiffness scale s = 1e-6 … 1e12",
            Class::SlaveMaster => "slave/master swapped",
            Class::Unbiased => "unbiased form, block ×1 … ×1e4",
            Class::Poisson => "ν = 0.3 … 0.49999",
            Class::Penalty => "penalty factor 1e-12 … 1e6",
            Class::Load => "load × 1 … 16",
            Class::Mesh => "1 … 64² elements, p = 2 … 5",
        }
    }
}

/// One scene of the campaign and the p₀ its answer must reach.
pub struct Case {
    pub class: Class,
    pub label: String,
    pub scene: String,
    pub p0: f64,
    /// What the contact force must balance.
    pub balance: Balance,
}

/// The equilibrium a right answer meets, in y: every case holds x by
/// symmetry supports, whose reactions take the x part of the contact force
/// (with a curved master its normals tilt), so only y is the contact's
/// alone. `summary.toml`'s `contact_force` is the force on the slaves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Balance {
    /// A prescribed displacement loads the body: its reaction is no
    /// applied load, so there is nothing to balance.
    None,
    /// The load acts on the slave: contact + applied = 0.
    LoadOnSlave,
    /// The load acts on the master: the slave's contact force equals it.
    LoadOnMaster,
}

/// A Hertz case of `class`, judged against `p0`.
fn hertz_case(class: Class, label: String, scene: HertzScene, p0: f64) -> Case {
    Case {
        class,
        label,
        scene: scene.toml(),
        p0,
        balance: Balance::LoadOnSlave,
    }
}

/// p₀ of `scene` solved in-process with the default solver.
fn solved_p0(scene: &Scene) -> Result<f64> {
    let problem = scene.build()?;
    let solution = solve(&problem, &SolverOptions::default())?;
    let profile = PressureProfile::dense(&problem, &solution.full)?;
    Ok(profile.measures(0).p0)
}

/// The references the disk-on-block cases are judged by: the disk (the
/// softer body) as slave on a mesh twice as fine as the finest case.
fn block_references(ratios: &[f64], finest: usize) -> Result<BTreeMap<u64, f64>> {
    let mut out = BTreeMap::new();
    for &ratio in ratios {
        let text = disk_on_block(ratio, 2 * finest, Slave::Disk, SceneSolver::Default)?;
        let scene = Scene::from_toml_str(&text)?;
        out.insert(ratio.to_bits(), solved_p0(&scene)?);
    }
    Ok(out)
}

/// The references of the large loads: the same disk at p = 3 on 64².
fn load_reference(load: f64) -> Result<f64> {
    let reference = HertzScene {
        load,
        degree: 3,
        elements: 64,
        theta: -1,
        ..HertzScene::default()
    };
    solved_p0(&Scene::from_toml_str(&reference.toml())?)
}

/// The powers of ten from 10^lo to 10^hi.
fn decades(lo: i32, hi: i32) -> Vec<f64> {
    (lo..=hi).map(|k| 10f64.powi(k)).collect()
}

/// Every case of the campaign, class by class.
pub fn cases() -> Result<Vec<Case>> {
    let mut out = Vec::new();
    prescribed(&mut out);
    scales(&mut out);
    slave_master(&mut out)?;
    poisson(&mut out);
    penalty(&mut out);
    mesh(&mut out)?;
    load(&mut out)?;
    Ok(out)
}

/// The pressed blocks, against their closed form.
fn prescribed(out: &mut Vec<Case>) {
    for poisson in [0.0, 0.3, 0.49] {
        for p in [1, 2, 3] {
            for n in [4, 16] {
                for theta in [-1, 0, 1] {
                    let ClosedForm { scene, p0 } = block(poisson, p, n, theta);
                    out.push(Case {
                        class: Class::Prescribed,
                        label: format!("block ν = {poisson}, p = {p}, {n}², θ = {theta}"),
                        scene,
                        p0,
                        balance: Balance::None,
                    });
                }
            }
        }
    }
}

/// Hertz in other units: every length scaled, then E and the load.
fn scales(out: &mut Vec<Case>) {
    for solver in SceneSolver::ALL {
        let name = solver.label();
        for length in decades(-9, 9) {
            let scene = HertzScene {
                length,
                solver,
                ..HertzScene::default()
            };
            let label = format!("Hertz 16², L = {length:e}, {name}");
            out.push(hertz_case(
                Class::LengthScale,
                label,
                scene,
                scene.hertz_p0(),
            ));
        }
        for stiffness in decades(-6, 12) {
            let scene = HertzScene {
                stiffness,
                solver,
                ..HertzScene::default()
            };
            let label = format!("Hertz 16², s = {stiffness:e}, {name}");
            out.push(hertz_case(
                Class::StiffnessScale,
                label,
                scene,
                scene.hertz_p0(),
            ));
        }
    }
}

/// The disk on a block, either body the slave or both, against the disk
/// as slave on a finer mesh.
fn slave_master(out: &mut Vec<Case>) -> Result<()> {
    let ratios = [1.0, 1e2, 1e4];
    let refs = block_references(&ratios, 32)?;
    for solver in SceneSolver::ALL {
        for ratio in ratios {
            for n in [8, 16, 32] {
                for (slave, class, name) in [
                    (Slave::Disk, Class::SlaveMaster, "slave disk"),
                    (Slave::Block, Class::SlaveMaster, "slave block"),
                    (Slave::Both, Class::Unbiased, "unbiased"),
                ] {
                    out.push(Case {
                        class,
                        label: format!(
                            "disk on block ×{ratio:e}, {n}², {name}, {}",
                            solver.label()
                        ),
                        scene: disk_on_block(ratio, n, slave, solver)?,
                        p0: refs[&ratio.to_bits()],
                        balance: if slave == Slave::Block {
                            Balance::LoadOnMaster
                        } else {
                            Balance::LoadOnSlave
                        },
                    });
                }
            }
        }
    }
    Ok(())
}

/// Hertz at ν up to 0.49999, against Hertz's p₀ for that ν.
fn poisson(out: &mut Vec<Case>) {
    for solver in SceneSolver::ALL {
        for poisson in [0.3, 0.45, 0.49, 0.499, 0.4999, 0.49999] {
            for p in [2, 3, 4] {
                for n in [16, 32] {
                    for theta in [-1, 0, 1] {
                        let scene = HertzScene {
                            poisson,
                            degree: p,
                            elements: n,
                            theta,
                            solver,
                            ..HertzScene::default()
                        };
                        let label = format!(
                            "Hertz ν = {poisson}, p = {p}, {n}², θ = {theta}, {}",
                            solver.label()
                        );
                        out.push(hertz_case(Class::Poisson, label, scene, scene.hertz_p0()));
                    }
                }
            }
        }
    }
}

/// Hertz with the penalty factor over eighteen decades.
fn penalty(out: &mut Vec<Case>) {
    for solver in SceneSolver::ALL {
        for factor in decades(-12, 6) {
            for (p, meshes) in [(2, &[8, 16, 32][..]), (3, &[8, 16][..])] {
                for &n in meshes {
                    for theta in [-1, 0, 1] {
                        let scene = HertzScene {
                            degree: p,
                            elements: n,
                            theta,
                            factor,
                            solver,
                            ..HertzScene::default()
                        };
                        let label = format!(
                            "Hertz p = {p}, {n}², factor {factor:e}, θ = {theta}, {}",
                            solver.label()
                        );
                        out.push(hertz_case(Class::Penalty, label, scene, scene.hertz_p0()));
                    }
                }
            }
        }
    }
}

/// From one element up: judged against the converged disk, not Hertz's
/// infinite half-plane (the finite disk's own offset is not an error).
fn mesh(out: &mut Vec<Case>) -> Result<()> {
    let converged = load_reference(1.0)?;
    for solver in SceneSolver::ALL {
        for p in 2..=5 {
            for n in [1, 2, 4, 8, 16, 32, 64] {
                for theta in [-1, 0, 1] {
                    let scene = HertzScene {
                        degree: p,
                        elements: n,
                        theta,
                        solver,
                        ..HertzScene::default()
                    };
                    let label = format!("Hertz p = {p}, {n}², θ = {theta}, {}", solver.label());
                    out.push(hertz_case(Class::Mesh, label, scene, converged));
                }
            }
        }
    }
    Ok(())
}

/// Hertz with the load up to 16 times the benchmark's, against the same
/// disk converged.
fn load(out: &mut Vec<Case>) -> Result<()> {
    for load in [1.0, 2.0, 4.0, 8.0, 16.0] {
        let p0 = load_reference(load)?;
        for solver in SceneSolver::ALL {
            for n in [8, 16, 32] {
                let scene = HertzScene {
                    load,
                    elements: n,
                    solver,
                    ..HertzScene::default()
                };
                let label = format!("Hertz {n}², load × {load}, {}", solver.label());
                out.push(hertz_case(Class::Load, label, scene, p0));
            }
        }
    }
    Ok(())
}
