//! The scene texts the tests edit: a small valid scene ([`BASE`]) and the
//! edits of it the tests make, one body with a given geometry, and a block
//! on a rigid floor.

pub use crate::common::block::HELD;
pub use crate::common::shipped_text;

/// A small valid scene with two bodies, every kind of load and both kinds
/// of master, on which the validation tests make one change each.
pub const BASE: &str = r#"
title = "base"

[[body]]
name = "lower"
geometry = { rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 0.5 } }
refine = { degree = 2, elements = [2, 1] }
material = { young = 1.0e9, poisson = 0.3, plane = "stress" }

[[body]]
name = "upper"
geometry = { rectangle = { x0 = 0.0, y0 = 0.5, x1 = 1.0, y1 = 1.0 } }
refine = { degree = 2, elements = [1, 1] }
material = { young = 1.0e9, poisson = 0.3, plane = "stress" }

[[support]]
body = "lower"
side = "eta_min"
component = "y"
value = 0.0

[[support]]
body = "lower"
side = "xi_min"
component = "x"

[[support]]
body = "upper"
side = "xi_min"
component = "x"

[[load]]
pressure = { body = "upper", side = "eta_max", pressure = 1.0e8 }

[[load]]
body_force = { body = "upper", force = [0.0, -1.0] }

[[load]]
traction = { body = "upper", side = "xi_max", traction = [0.0, 0.0] }

[[contact]]
slave = "upper"
slave_side = "eta_min"
master = { body = "lower", side = "eta_max" }

[solver]
kind = "bfgs"
rtol = 1e-10
"#;

/// A single body with a geometry given as a TOML inline table.
pub fn one_body(geometry: &str, refine: &str) -> String {
    format!(
        r#"
[[body]]
name = "b"
geometry = {geometry}
{refine}
material = {{ young = 1.0, poisson = 0.3, plane = "strain" }}

[[support]]
body = "b"
side = "eta_min"
component = "y"

[[support]]
body = "b"
side = "eta_min"
component = "x"
"#
    )
}

pub fn base_with(from: &str, to: &str) -> String {
    assert!(BASE.contains(from), "the base scene lacks {from:?}");
    BASE.replacen(from, to, 1)
}

/// A block on a rigid floor (p = 2 on 2 × 2) with the given supports (TOML
/// tables).
pub fn block_on_floor(supports: &str) -> String {
    crate::common::block::block_on_floor([2, 2], supports)
}

pub fn nurbs_body(knots_xi: &str, control_points: &str, weights: &str) -> String {
    one_body(
        &format!(
            "{{ nurbs = {{ degree = [1, 1], knots_xi = {knots_xi}, knots_eta = [0.0, 0.0, 1.0, 1.0], \
             control_points = {control_points}{weights} }} }}"
        ),
        "refine = { degree = 2, elements = [2, 2] }",
    )
}

pub const SQUARE: &str = "[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]]";

/// `BASE` with the contact pair's Nitsche table set to `{ set }`.
pub fn nitsche(set: &str) -> String {
    base_with(
        "side = \"eta_max\" }\n",
        &format!("side = \"eta_max\" }}\nnitsche = {{ {set} }}\n"),
    )
}

/// `BASE` with the contact pair's master set to `master`.
pub fn master(master: &str) -> String {
    base_with(
        "master = { body = \"lower\", side = \"eta_max\" }",
        &format!("master = {master}"),
    )
}

/// `BASE` with `degree = 2, elements = [2, 1]` of the lower body's refine
/// table replaced.
pub fn refine(to: &str) -> String {
    base_with("degree = 2, elements = [2, 1]", to)
}

/// `BASE` with a line added to the lower body's table.
pub fn lower_body(line: &str) -> String {
    base_with(
        "plane = \"stress\" }\n\n[[body]]",
        &format!("plane = \"stress\" }}\n{line}\n\n[[body]]"),
    )
}

/// A single body with no refinement and geometry `geometry`.
pub fn plain_body(geometry: &str) -> String {
    one_body(geometry, "")
}

/// A triangle: the η = 1 side of this bilinear patch is a single point.
pub const TRIANGLE: &str = "{ nurbs = { degree = [1, 1], knots_xi = [0.0, 0.0, 1.0, 1.0], \
                        knots_eta = [0.0, 0.0, 1.0, 1.0], \
                        control_points = [[0.0, 0.0], [1.0, 0.0], [0.5, 1.0], [0.5, 1.0]] } }";
