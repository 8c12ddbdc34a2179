//! A block on a rigid floor, as scene text: the rectangle [0, 1] × [0, 0.5]
//! (E = 10⁶, ν = 0.3, plane strain), p = 2, under a pressure of 10⁴ on its
//! top, its bottom the slave against the segment from (−0.5, 0) to (1.5, 0).
//! Tests edit the text (`young = 1.0e6`, `pressure = 1.0e4`,
//! `y0 = 0.0, x1 = 1.0, y1 = 0.5`) to make their cases.

/// The support that holds the block's sliding: u_x = 0 on its left side.
pub const HELD: &str = "[[support]]\nbody = \"block\"\nside = \"xi_min\"\ncomponent = \"x\"\n";

/// The block on `elements`, with the given supports (TOML tables).
pub fn block_on_floor(elements: [usize; 2], supports: &str) -> String {
    let [nx, ny] = elements;
    format!(
        r#"
[[body]]
name = "block"
geometry = {{ rectangle = {{ x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 0.5 }} }}
refine = {{ degree = 2, elements = [{nx}, {ny}] }}
material = {{ young = 1.0e6, poisson = 0.3, plane = "strain" }}
{supports}
[[load]]
pressure = {{ body = "block", side = "eta_max", pressure = 1.0e4 }}

[[contact]]
slave = "block"
slave_side = "eta_min"
master = {{ rigid_segment = {{ from = [-0.5, 0.0], to = [1.5, 0.0] }} }}
"#
    )
}
