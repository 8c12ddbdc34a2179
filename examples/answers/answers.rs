//! Answers off the benchmark path: scenes a user might write (bodies held
//! by supports only, prescribed displacements, unit scales, the stiffer
//! body as slave, near-incompressible bodies, penalties over eighteen
//! decades, large loads), each given to `check` and `run` as a child
//! process, and each answer judged against a reference: p₀ within
//! [`WRONG`] of it and the contact force balancing the load to
//! [`BALANCE`]. An answer outside that is wrong; a wrong answer on exit 0
//! must carry a warning.

use crate::harness::{launch, Launch, Outcome};

/// The address-space limit of every launch, as in the reliability campaign.
pub const LIMIT: u64 = 8 << 30;
/// Seconds a launch may take before it is stopped.
pub const TIMEOUT: f64 = 30.0;
use companion::chapter::Chapter;
use iga_contact::material::{Material, Plane};
use iga_contact::post::hertz::{Cylinder, Hertz};
use iga_contact::post::PressureProfile;
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};
use iga_contact::scene::Scene;
use iga_contact::solver::{solve, SolverOptions};
use iga_contact::Result;
use std::collections::BTreeMap;
use std::f64::consts::PI;
use std::path::Path;

/// p₀ more than this fraction off its reference is a wrong answer.
pub const WRONG: f64 = 0.05;
/// The contact force balancing the load worse than this (relative) is a
/// wrong answer.
pub const BALANCE: f64 = 1e-8;

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

/// What a launch of `run` came to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Verdict {
    /// Exit 0, p₀ and the balance right.
    Right,
    /// Exit 0, wrong, with a warning on the report line.
    WarnedWrong,
    /// Exit 0, right, with a warning (a cautious warning).
    WarnedRight,
    /// Exit 0, wrong, and nothing said: the defect this campaign hunts.
    SilentWrong,
    /// Exit 1 with one error line (a failed solve, reported).
    Failed,
    /// Exit 2 with one error line (refused).
    Refused,
    /// Anything else: a signal, a backtrace, another exit code.
    Unclean,
}

impl Verdict {
    pub const ALL: [Verdict; 7] = [
        Verdict::Right,
        Verdict::WarnedRight,
        Verdict::WarnedWrong,
        Verdict::SilentWrong,
        Verdict::Failed,
        Verdict::Refused,
        Verdict::Unclean,
    ];

    pub fn label(self) -> &'static str {
        match self {
            Verdict::Right => "right",
            Verdict::WarnedRight => "right, warned",
            Verdict::WarnedWrong => "wrong, warned",
            Verdict::SilentWrong => "wrong, silent",
            Verdict::Failed => "failed (exit 1)",
            Verdict::Refused => "refused (exit 2)",
            Verdict::Unclean => "unclean",
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

/// The Hertz scene of `data/scenes/hertz.toml` with its lengths scaled by
/// `length`, E and the load by `stiffness`, the load by `load`, degree
/// `p` on `n`², the given ν, θ, penalty factor and solver kind, writing
/// only its summary.
#[allow(clippy::too_many_arguments)]
fn hertz(
    length: f64,
    stiffness: f64,
    load: f64,
    poisson: f64,
    p: usize,
    n: usize,
    theta: i32,
    factor: f64,
    newton: bool,
) -> String {
    let r = 0.2 * length;
    let young = 2.0e7 * stiffness;
    let force = -1.3e6 * load * stiffness / length;
    let solver = if newton {
        "[solver]\nkind = \"newton\"\n"
    } else {
        ""
    };
    format!(
        r#"title = "answers"
[[body]]
name = "disk"
geometry = {{ half_disk = {{ center = [0.0, {r:e}], radius = {r:e} }} }}
refine = {{ degree = {p}, elements = [{n}, {n}] }}
material = {{ young = {young:e}, poisson = {poisson}, plane = "strain" }}
[[support]]
body = "disk"
side = "xi_min"
component = "x"
[[load]]
body_force = {{ body = "disk", force = [0.0, {force:e}] }}
[[contact]]
slave = "disk"
slave_side = "eta_min"
master = {{ rigid_segment = {{ from = [{x0:e}, 0.0], to = [{x1:e}, 0.0] }} }}
nitsche = {{ theta = {theta}, penalty_factor = {factor:e} }}
{solver}[output]
summary = true
"#,
        x0 = -r,
        x1 = 2.0 * r,
    )
}

/// Hertz's p₀ for the disk of [`hertz`] (the half model carries half of
/// the weight P of the whole disk).
fn hertz_p0(length: f64, stiffness: f64, load: f64, poisson: f64) -> f64 {
    let r = 0.2 * length;
    let material = Material {
        young: 2.0e7 * stiffness,
        poisson,
        plane: Plane::Strain,
    };
    let weight = 1.3e6 * load * stiffness / length * PI * r * r;
    Hertz::new(
        Cylinder::Elastic {
            radius: r,
            material,
        },
        Cylinder::RigidPlane,
        weight,
    )
    .p0
}

/// A block [0, 1] × [0, H] on the floor y = 0, its top pushed down by δ,
/// symmetric about x = 0, free on the right: σ_yy = −E/(1 − ν²)·δ/H
/// everywhere, so p₀ is that pressure.
fn block(poisson: f64, p: usize, n: usize, theta: i32) -> (String, f64) {
    let (young, height, delta) = (2.0e7, 0.5, 1e-3);
    let scene = format!(
        r#"title = "answers: a block pressed down"
[[body]]
name = "block"
geometry = {{ rectangle = {{ x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = {height} }} }}
refine = {{ degree = {p}, elements = [{n}, {n}] }}
material = {{ young = {young:e}, poisson = {poisson}, plane = "strain" }}
[[support]]
body = "block"
side = "xi_min"
component = "x"
[[support]]
body = "block"
side = "eta_max"
component = "y"
value = {v:e}
[[contact]]
slave = "block"
slave_side = "eta_min"
master = {{ rigid_segment = {{ from = [-1.0, 0.0], to = [2.0, 0.0] }} }}
nitsche = {{ theta = {theta} }}
[output]
summary = true
"#,
        v = -delta
    );
    (scene, young / (1.0 - poisson * poisson) * delta / height)
}

/// Which body of the disk on the block is the slave.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Slave {
    /// The disk, the softer body: the references.
    Disk,
    /// The block.
    Block,
    /// Each, of one half of the unbiased form (the disk named slave).
    Both,
}

/// `data/scenes/disk_on_block.toml` with the block `ratio` times stiffer
/// than the disk, the disk on `n`² and the block on 2n × n, and the slave
/// as `slave` says.
fn disk_on_block(ratio: f64, n: usize, slave: Slave, newton: bool) -> Result<String> {
    let text =
        std::fs::read_to_string(companion::shipped_path("disk_on_block.toml")).map_err(|e| {
            iga_contact::Error::Io {
                path: "disk_on_block.toml".into(),
                source: e,
            }
        })?;
    let mut text = text
        .replace(
            "refine = { degree = 2, elements = [16, 16] }",
            &format!("refine = {{ degree = 2, elements = [{n}, {n}] }}"),
        )
        .replace(
            "refine = { degree = 2, elements = [32, 16] }",
            &format!("refine = {{ degree = 2, elements = [{}, {n}] }}", 2 * n),
        );
    // the block's material is the second `young = 2.0e7`
    if let Some(k) = text.rfind("young = 2.0e7") {
        text.replace_range(
            k..k + "young = 2.0e7".len(),
            &format!("young = {:e}", 2.0e7 * ratio),
        );
    }
    if slave == Slave::Both {
        text = text.replace("sides = \"biased\"", "sides = \"unbiased\"");
        assert!(
            text.contains("unbiased"),
            "disk_on_block.toml names no `sides`"
        );
    }
    if slave == Slave::Block {
        text = text.replace(
            "slave = \"disk\"\nslave_side = \"eta_min\"\nmaster = { body = \"block\", side = \"eta_max\" }",
            "slave = \"block\"\nslave_side = \"eta_max\"\nmaster = { body = \"disk\", side = \"eta_min\" }",
        );
    }
    let cut = text.find("[output]").unwrap_or(text.len());
    text.truncate(cut);
    if newton {
        text.push_str("[solver]\nkind = \"newton\"\n");
    }
    text.push_str("[output]\nsummary = true\n");
    Ok(text)
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
        let scene = Scene::from_toml_str(&disk_on_block(ratio, 2 * finest, Slave::Disk, false)?)?;
        out.insert(ratio.to_bits(), solved_p0(&scene)?);
    }
    Ok(out)
}

/// The references of the large loads: the same disk at p = 3 on 64².
fn load_reference(load: f64) -> Result<f64> {
    let scene = Scene::from_toml_str(&hertz(1.0, 1.0, load, 0.1, 3, 64, -1, 1.0, false))?;
    solved_p0(&scene)
}

/// Every case of the campaign.
pub fn cases() -> Result<Vec<Case>> {
    let mut out = Vec::new();
    let push = |out: &mut Vec<Case>, class, label: String, scene, p0, balance| {
        out.push(Case {
            class,
            label,
            scene,
            p0,
            balance,
        })
    };
    let solvers = [(false, "default"), (true, "newton")];
    for poisson in [0.0, 0.3, 0.49] {
        for p in [1, 2, 3] {
            for n in [4, 16] {
                for theta in [-1, 0, 1] {
                    let (scene, p0) = block(poisson, p, n, theta);
                    push(
                        &mut out,
                        Class::Prescribed,
                        format!("block ν = {poisson}, p = {p}, {n}², θ = {theta}"),
                        scene,
                        p0,
                        Balance::None,
                    );
                }
            }
        }
    }
    let decades = |lo: i32, hi: i32| (lo..=hi).map(|k| 10f64.powi(k)).collect::<Vec<_>>();
    for (newton, solver) in solvers {
        for length in decades(-9, 9) {
            push(
                &mut out,
                Class::LengthScale,
                format!("Hertz 16², L = {length:e}, {solver}"),
                hertz(length, 1.0, 1.0, 0.1, 2, 16, 0, 1.0, newton),
                hertz_p0(length, 1.0, 1.0, 0.1),
                Balance::LoadOnSlave,
            );
        }
        for stiffness in decades(-6, 12) {
            push(
                &mut out,
                Class::StiffnessScale,
                format!("Hertz 16², s = {stiffness:e}, {solver}"),
                hertz(1.0, stiffness, 1.0, 0.1, 2, 16, 0, 1.0, newton),
                hertz_p0(1.0, stiffness, 1.0, 0.1),
                Balance::LoadOnSlave,
            );
        }
    }
    let ratios = [1.0, 1e2, 1e4];
    let refs = block_references(&ratios, 32)?;
    for (newton, solver) in solvers {
        for ratio in ratios {
            for n in [8, 16, 32] {
                for (slave, class, name) in [
                    (Slave::Disk, Class::SlaveMaster, "slave disk"),
                    (Slave::Block, Class::SlaveMaster, "slave block"),
                    (Slave::Both, Class::Unbiased, "unbiased"),
                ] {
                    push(
                        &mut out,
                        class,
                        format!("disk on block ×{ratio:e}, {n}², {name}, {solver}"),
                        disk_on_block(ratio, n, slave, newton)?,
                        refs[&ratio.to_bits()],
                        if slave == Slave::Block {
                            Balance::LoadOnMaster
                        } else {
                            Balance::LoadOnSlave
                        },
                    );
                }
            }
        }
    }
    for (newton, solver) in solvers {
        for poisson in [0.3, 0.45, 0.49, 0.499, 0.4999, 0.49999] {
            for p in [2, 3, 4] {
                for n in [16, 32] {
                    for theta in [-1, 0, 1] {
                        push(
                            &mut out,
                            Class::Poisson,
                            format!("Hertz ν = {poisson}, p = {p}, {n}², θ = {theta}, {solver}"),
                            hertz(1.0, 1.0, 1.0, poisson, p, n, theta, 1.0, newton),
                            hertz_p0(1.0, 1.0, 1.0, poisson),
                            Balance::LoadOnSlave,
                        );
                    }
                }
            }
        }
    }
    for (newton, solver) in solvers {
        for factor in decades(-12, 6) {
            for (p, meshes) in [(2, &[8, 16, 32][..]), (3, &[8, 16][..])] {
                for &n in meshes {
                    for theta in [-1, 0, 1] {
                        push(
                            &mut out,
                            Class::Penalty,
                            format!(
                                "Hertz p = {p}, {n}², factor {factor:e}, θ = {theta}, {solver}"
                            ),
                            hertz(1.0, 1.0, 1.0, 0.1, p, n, theta, factor, newton),
                            hertz_p0(1.0, 1.0, 1.0, 0.1),
                            Balance::LoadOnSlave,
                        );
                    }
                }
            }
        }
    }
    // from one element up: judged against the converged disk, not Hertz's
    // infinite half-plane (the finite disk's own offset is not an error)
    let converged = load_reference(1.0)?;
    for (newton, solver) in solvers {
        for p in 2..=5 {
            for n in [1, 2, 4, 8, 16, 32, 64] {
                for theta in [-1, 0, 1] {
                    push(
                        &mut out,
                        Class::Mesh,
                        format!("Hertz p = {p}, {n}², θ = {theta}, {solver}"),
                        hertz(1.0, 1.0, 1.0, 0.1, p, n, theta, 1.0, newton),
                        converged,
                        Balance::LoadOnSlave,
                    );
                }
            }
        }
    }
    for load in [1.0, 2.0, 4.0, 8.0, 16.0] {
        let p0 = load_reference(load)?;
        for (newton, solver) in solvers {
            for n in [8, 16, 32] {
                push(
                    &mut out,
                    Class::Load,
                    format!("Hertz {n}², load × {load}, {solver}"),
                    hertz(1.0, 1.0, load, 0.1, 2, n, 0, 1.0, newton),
                    p0,
                    Balance::LoadOnSlave,
                );
            }
        }
    }
    Ok(out)
}

/// p₀ of the first pair and the relative imbalance in y of the contact
/// force against the applied load on the slave and on the master, from a
/// `summary.toml`.
fn read_summary(path: &Path) -> Option<(f64, [f64; 2])> {
    let text = std::fs::read_to_string(path).ok()?;
    let v: toml::Value = toml::from_str(&text).ok()?;
    let pair = v.get("contact")?.as_array()?.first()?;
    // absent where the profile finds no zone: no peak was measured, which
    // is as far from the reference as a peak of zero
    let p0 = pair.get("p0").map_or(Some(0.0), toml::Value::as_float)?;
    let vec2 = |key: &str| -> Option<[f64; 2]> {
        let a = v.get(key)?.as_array()?;
        Some([a.first()?.as_float()?, a.get(1)?.as_float()?])
    };
    let (c, a) = (vec2("contact_force")?, vec2("applied_force")?);
    let size = a[1].abs().max(f64::MIN_POSITIVE);
    Some((p0, [(c[1] + a[1]).abs() / size, (c[1] - a[1]).abs() / size]))
}

/// The verdict on a `run` of `case` that wrote into `out`.
fn judge(case: &Case, o: &Outcome, out: &Path) -> (Verdict, f64) {
    if o.timed_out || !o.clean() {
        return (Verdict::Unclean, f64::NAN);
    }
    match o.code {
        Some(0) => {}
        Some(1) => return (Verdict::Failed, f64::NAN),
        _ => return (Verdict::Refused, f64::NAN),
    }
    let warned = o.stdout.contains("warning") || o.stderr.contains("warning: ");
    let Some((p0, imbalance)) = read_summary(&out.join("summary.toml")) else {
        return (Verdict::Unclean, f64::NAN);
    };
    let error = p0 / case.p0 - 1.0;
    let imbalance = match case.balance {
        Balance::None => 0.0,
        Balance::LoadOnSlave => imbalance[0],
        Balance::LoadOnMaster => imbalance[1],
    };
    let right = error.abs() <= WRONG && imbalance <= BALANCE;
    let verdict = match (right, warned) {
        (true, false) => Verdict::Right,
        (true, true) => Verdict::WarnedRight,
        (false, true) => Verdict::WarnedWrong,
        (false, false) => Verdict::SilentWrong,
    };
    (verdict, error)
}

/// One case's result.
pub struct Answer {
    pub class: Class,
    pub label: String,
    pub verdict: Verdict,
    /// p₀ / reference − 1 (NaN without an answer).
    pub error: f64,
    pub iterations: Option<i64>,
    /// The report line (exit 0) or the error line.
    pub message: String,
    /// Peak resident memory of the `run`, bytes.
    pub peak_bytes: f64,
}

/// Runs every case through `check` and `run` in `work`; returns the
/// answers and the number of launches.
pub fn run(work: &Path) -> Result<(Vec<Answer>, usize)> {
    let how = Launch {
        address_space: Some(LIMIT),
        timeout: TIMEOUT,
        ..Launch::default()
    };
    let mut answers = Vec::new();
    let mut launches = 0;
    for (k, case) in cases()?.into_iter().enumerate() {
        let name = format!("a{k}.toml");
        std::fs::write(work.join(&name), &case.scene).expect("the work folder takes a scene");
        let c = launch(work, &["check", &name], how);
        launches += 1;
        let out = work.join(format!("a{k}-out"));
        let r = launch(
            work,
            &["run", &name, "--out", &out.display().to_string()],
            how,
        );
        launches += 1;
        let (mut verdict, error) = judge(&case, &r, &out);
        if !c.clean() || c.timed_out {
            verdict = Verdict::Unclean;
        }
        let iterations = std::fs::read_to_string(out.join("summary.toml"))
            .ok()
            .and_then(|t| toml::from_str::<toml::Value>(&t).ok())
            .and_then(|v| v.get("iterations").and_then(|i| i.as_integer()));
        let message = if r.code == Some(0) {
            r.stdout.trim().to_string()
        } else {
            r.message()
        };
        answers.push(Answer {
            class: case.class,
            label: case.label,
            verdict,
            error,
            iterations,
            message,
            peak_bytes: r.peak_bytes,
        });
        let _ = std::fs::remove_dir_all(&out);
        let _ = std::fs::remove_file(work.join(&name));
    }
    Ok((answers, launches))
}

/// What the chapter quotes of the answers.
pub struct Summary {
    pub cases: usize,
    pub launches: usize,
    pub silent_wrong: usize,
    pub unclean: usize,
    /// The largest |p₀/p₀(L = 1) − 1| over the length and stiffness
    /// sweeps that answered, and whether every answer took the iterations
    /// of the unscaled one.
    pub scale_spread: f64,
    pub scale_same_iterations: bool,
    /// The largest |p₀/p₀(closed form) − 1| of the pressed blocks.
    pub prescribed_error: f64,
    /// The largest peak resident memory of a `run`, bytes.
    pub peak_bytes: f64,
}

/// Runs the answers in `work` and writes their tables into `chapter`:
/// `answers` (verdicts per class), `answers_silent.md` (every silent wrong
/// answer), `scale` (the two sweeps), `prescribed` (the pressed blocks).
pub fn report(work: &Path, chapter: &mut Chapter) -> Result<Summary> {
    let (answers, launches) = run(work)?;
    let mut columns = vec![Column::plain("class", "class")];
    for v in Verdict::ALL {
        columns.push(Column::plain(v.label(), v.label()));
    }
    let mut counts = Table::new(columns);
    for class in Class::ALL {
        let mut row: Vec<Cell> = vec![class.label().into()];
        for v in Verdict::ALL {
            row.push(
                answers
                    .iter()
                    .filter(|a| a.class == class && a.verdict == v)
                    .count()
                    .into(),
            );
        }
        counts.push(row)?;
    }
    chapter.table("answers", &counts)?;
    let silent: String = answers
        .iter()
        .filter(|a| a.verdict == Verdict::SilentWrong)
        .map(|a| {
            format!(
                "- {}: p₀ {} off its reference\n",
                a.label,
                Format::SignedPercent(1).render(a.error)
            )
        })
        .collect();
    chapter.text("answers_silent.md", &silent)?;
    let unclean: String = answers
        .iter()
        .filter(|a| a.verdict == Verdict::Unclean)
        .map(|a| format!("- {}: {}\n", a.label, a.message))
        .collect();
    chapter.text("answers_unclean.md", &unclean)?;

    // the scale sweeps: iterations and p₀ against the unscaled run
    let mut scale = Table::new(vec![
        Column::plain("sweep", "sweep"),
        Column::plain("solver", "solver"),
        Column::plain("factor", "factor"),
        Column::plain("iterations", "iterations"),
        Column::new("p0_deviation", "p₀ / p₀(1) − 1", Unit::None, Format::Sci(1)),
    ]);
    let mut spread: f64 = 0.0;
    let mut same = true;
    for (class, sweep) in [(Class::LengthScale, "L"), (Class::StiffnessScale, "s")] {
        for solver in ["default", "newton"] {
            let runs: Vec<&Answer> = answers
                .iter()
                .filter(|a| a.class == class && a.label.ends_with(solver))
                .collect();
            let unit = runs
                .iter()
                .find(|a| a.label.contains("= 1e0,"))
                .map(|a| (a.error, a.iterations));
            for a in &runs {
                let factor = a
                    .label
                    .split(" = ")
                    .nth(1)
                    .and_then(|s| s.split(',').next())
                    .unwrap_or("?")
                    .to_string();
                let deviation = match (unit, a.verdict) {
                    (Some((e1, _)), Verdict::Right | Verdict::WarnedRight) => {
                        (1.0 + a.error) / (1.0 + e1) - 1.0
                    }
                    _ => f64::NAN,
                };
                if deviation.is_finite() {
                    spread = spread.max(deviation.abs());
                } else {
                    same = false;
                }
                if unit.map(|u| u.1) != Some(a.iterations) {
                    same = false;
                }
                let its: Cell = match a.iterations {
                    Some(i) => (i as usize).into(),
                    None => a.verdict.label().into(),
                };
                let dev: Cell = if deviation.is_finite() {
                    deviation.into()
                } else {
                    "–".into()
                };
                scale.push(vec![sweep.into(), solver.into(), factor.into(), its, dev])?;
            }
        }
    }
    chapter.table("scale", &scale)?;

    let mut prescribed = Table::new(vec![
        Column::plain("case", "case"),
        Column::plain("verdict", "verdict"),
        Column::new("error", "p₀ / closed form − 1", Unit::None, Format::Sci(1)),
    ]);
    let mut worst: f64 = 0.0;
    for a in answers.iter().filter(|a| a.class == Class::Prescribed) {
        if a.error.is_finite() {
            worst = worst.max(a.error.abs());
        } else {
            worst = f64::INFINITY;
        }
        let e: Cell = if a.error.is_finite() {
            a.error.into()
        } else {
            "–".into()
        };
        prescribed.push(vec![a.label.clone().into(), a.verdict.label().into(), e])?;
    }
    chapter.table("prescribed", &prescribed)?;
    Ok(Summary {
        cases: answers.len(),
        launches,
        silent_wrong: answers
            .iter()
            .filter(|a| a.verdict == Verdict::SilentWrong)
            .count(),
        unclean: answers
            .iter()
            .filter(|a| a.verdict == Verdict::Unclean)
            .count(),
        scale_spread: spread,
        scale_same_iterations: same,
        prescribed_error: worst,
        peak_bytes: answers.iter().map(|a| a.peak_bytes).fold(0.0, f64::max),
    })
}
