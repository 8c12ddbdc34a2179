//! An affine displacement u(X) = a + B X: NURBS and isoparametric spaces
//! reproduce it exactly wherever the map is invertible, so a sampled
//! displacement must equal the field at the sampled point and the stress
//! must be D B everywhere in a body.

use iga_contact::dofs::{Body, DofMap};

pub const A: [f64; 2] = [1e-3, -2e-3];
pub const B: [[f64; 2]; 2] = [[1e-3, 2e-4], [-3e-4, 5e-4]];

pub fn affine(x: [f64; 2]) -> [f64; 2] {
    [
        A[0] + B[0][0] * x[0] + B[0][1] * x[1],
        A[1] + B[1][0] * x[0] + B[1][1] * x[1],
    ]
}

/// The displacement vector of [`affine`] at every control point.
pub fn affine_at_control_points(bodies: &[Body], map: &DofMap) -> Vec<f64> {
    let mut u = vec![0.0; map.n_total()];
    for (bi, b) in bodies.iter().enumerate() {
        for (cp, &x) in b.space.patch.points.iter().enumerate() {
            let v = affine(x);
            u[map.global(bi, cp, 0)] = v[0];
            u[map.global(bi, cp, 1)] = v[1];
        }
    }
    u
}
