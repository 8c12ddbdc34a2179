//! The scene files of the campaign, as a user would write them: the Hertz
//! disk in other units, materials, meshes, penalties and loads; a block
//! pressed down by a prescribed displacement; the disk on an elastic block
//! with either body as the slave.

use iga_contact::material::{Material, Plane};
use iga_contact::post::hertz::{Cylinder, Hertz};
use iga_contact::Result;
use std::f64::consts::PI;

/// The solver a scene names in its `[solver]` table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SceneSolver {
    /// No `[solver]` table: the default BFGS.
    Default,
    /// `kind = "newton"`.
    Newton,
}

impl SceneSolver {
    pub const ALL: [SceneSolver; 2] = [SceneSolver::Default, SceneSolver::Newton];

    /// The name that ends each case's label, and the scale table's column.
    pub fn label(self) -> &'static str {
        match self {
            SceneSolver::Default => "default",
            SceneSolver::Newton => "newton",
        }
    }

    /// The scene's `[solver]` table (none for the default).
    fn table(self) -> &'static str {
        match self {
            SceneSolver::Default => "",
            SceneSolver::Newton => "[solver]\nkind = \"newton\"\n",
        }
    }
}

/// The Hertz scene of `data/scenes/hertz.toml` with its lengths scaled by
/// `length`, E and the load by `stiffness`, the load by `load`, degree
/// `degree` on `elements`², the given ν, θ, penalty factor and solver,
/// writing only its summary. The default is the benchmark's disk on 16²
/// with p = 2, ν = 0.1, θ = 0 and the factor 1, solved by the default
/// solver.
#[derive(Clone, Copy, Debug)]
pub struct HertzScene {
    pub length: f64,
    pub stiffness: f64,
    pub load: f64,
    pub poisson: f64,
    pub degree: usize,
    pub elements: usize,
    pub theta: i32,
    pub factor: f64,
    pub solver: SceneSolver,
}

impl Default for HertzScene {
    fn default() -> Self {
        HertzScene {
            length: 1.0,
            stiffness: 1.0,
            load: 1.0,
            poisson: 0.1,
            degree: 2,
            elements: 16,
            theta: 0,
            factor: 1.0,
            solver: SceneSolver::Default,
        }
    }
}

impl HertzScene {
    /// The scene file.
    pub fn toml(&self) -> String {
        let HertzScene {
            length,
            stiffness,
            load,
            poisson,
            degree: p,
            elements: n,
            theta,
            factor,
            solver,
        } = *self;
        let r = 0.2 * length;
        let young = 2.0e7 * stiffness;
        let force = -1.3e6 * load * stiffness / length;
        let solver = solver.table();
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

    /// Hertz's p₀ for the disk (the half model carries half of the weight
    /// P of the whole disk).
    pub fn hertz_p0(&self) -> f64 {
        let r = 0.2 * self.length;
        let material = Material {
            young: 2.0e7 * self.stiffness,
            poisson: self.poisson,
            plane: Plane::Strain,
        };
        let weight = 1.3e6 * self.load * self.stiffness / self.length * PI * r * r;
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
}

/// A scene and the p₀ its closed form gives.
pub struct ClosedForm {
    pub scene: String,
    pub p0: f64,
}

/// A block [0, 1] × [0, H] on the floor y = 0, its top pushed down by δ,
/// symmetric about x = 0, free on the right: σ_yy = −E/(1 − ν²)·δ/H
/// everywhere, so p₀ is that pressure.
pub fn block(poisson: f64, p: usize, n: usize, theta: i32) -> ClosedForm {
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
    ClosedForm {
        scene,
        p0: young / (1.0 - poisson * poisson) * delta / height,
    }
}

/// Which body of the disk on the block is the slave.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Slave {
    /// The disk, the softer body: the references.
    Disk,
    /// The block.
    Block,
    /// Each, of one half of the unbiased form (the disk named slave).
    Both,
}

/// `data/scenes/disk_on_block.toml` with the block `ratio` times stiffer
/// than the disk, the disk on `n`² and the block on 2n × n, the slave as
/// `slave` says, and the solver `solver`.
pub fn disk_on_block(ratio: f64, n: usize, slave: Slave, solver: SceneSolver) -> Result<String> {
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
    text.push_str(solver.table());
    text.push_str("[output]\nsummary = true\n");
    Ok(text)
}
