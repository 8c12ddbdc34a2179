//! Hertz's plane-strain solution for two long cylinders pressed together
//! by a load P per unit length: the reference of the Hertz chapters.
//!
//! With the effective radius 1/R = 1/R₁ + 1/R₂ (a plane has 1/R₂ = 0) and
//! the contact modulus 1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂ (a rigid body has
//! 1/E₂ = 0),
//!
//!   a = 2 √(P R / (π E*)),   p₀ = 2P / (π a),   p(x) = p₀ √(1 − x²/a²).

use crate::material::Material;
use std::f64::consts::PI;

/// One of the two bodies in contact.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Cylinder {
    /// An elastic cylinder of this radius.
    Elastic { radius: f64, material: Material },
    /// An elastic half-space (radius ∞).
    HalfSpace(Material),
    /// A rigid plane.
    RigidPlane,
}

impl Cylinder {
    fn curvature(&self) -> f64 {
        match self {
            Cylinder::Elastic { radius, .. } => 1.0 / radius,
            _ => 0.0,
        }
    }

    /// (1 − ν²)/E; 0 for a rigid body.
    fn compliance(&self) -> f64 {
        match self {
            Cylinder::Elastic { material, .. } | Cylinder::HalfSpace(material) => {
                (1.0 - material.poisson * material.poisson) / material.young
            }
            Cylinder::RigidPlane => 0.0,
        }
    }
}

/// The analytic contact of two bodies under a load per unit length.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hertz {
    /// P, the load per unit length pressing the bodies together.
    pub load: f64,
    /// R, the effective radius.
    pub radius: f64,
    /// E*, the contact modulus.
    pub modulus: f64,
    /// a, the contact half-width.
    pub half_width: f64,
    /// p₀, the peak pressure.
    pub p0: f64,
}

impl Hertz {
    /// The contact of `a` and `b` under `load` per unit length.
    pub fn new(a: Cylinder, b: Cylinder, load: f64) -> Self {
        let radius = 1.0 / (a.curvature() + b.curvature());
        let modulus = 1.0 / (a.compliance() + b.compliance());
        let half_width = 2.0 * (load * radius / (PI * modulus)).sqrt();
        Self {
            load,
            radius,
            modulus,
            half_width,
            p0: 2.0 * load / (PI * half_width),
        }
    }

    /// p(x) = p₀ √(1 − x²/a²) inside the contact zone, 0 outside.
    pub fn pressure(&self, x: f64) -> f64 {
        let s = 1.0 - (x / self.half_width).powi(2);
        if s > 0.0 {
            self.p0 * s.sqrt()
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Plane;

    fn steel() -> Material {
        Material {
            young: 2e11,
            poisson: 0.3,
            plane: Plane::Strain,
        }
    }

    /// The pressure integrates to the load, p₀ and a are consistent, and a
    /// cylinder on a rigid plane is the limit of one on a stiff cylinder.
    #[test]
    fn hertz_is_consistent() {
        let c = Cylinder::Elastic {
            radius: 0.2,
            material: steel(),
        };
        let h = Hertz::new(c, Cylinder::RigidPlane, 1e5);
        let n = 100_000;
        let dx = 2.0 * h.half_width / n as f64;
        let total: f64 = (0..n)
            .map(|i| h.pressure(-h.half_width + (i as f64 + 0.5) * dx) * dx)
            .sum();
        assert!((total - h.load).abs() <= 1e-6 * h.load);
        let stiff = Cylinder::Elastic {
            radius: 1e9,
            material: Material {
                young: 1e20,
                ..steel()
            },
        };
        let limit = Hertz::new(c, stiff, 1e5);
        assert!((limit.half_width - h.half_width).abs() <= 1e-6 * h.half_width);
        // two equal cylinders: R halves, E* halves, so a is the same as one on a rigid plane
        let pair = Hertz::new(c, c, 1e5);
        assert!((pair.half_width - h.half_width).abs() <= 1e-12 * h.half_width);
    }
}
