//! Isotropic linear elasticity in 2D: plane strain and plane stress.

use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// The 2D reduction of the 3D law.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Plane {
    /// ε_zz = 0 (thick bodies: the Hertz cylinder).
    Strain,
    /// σ_zz = 0 (thin plates: the Taylor patch test).
    Stress,
}

/// Young's modulus, Poisson's ratio and the plane assumption.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    pub young: f64,
    pub poisson: f64,
    pub plane: Plane,
}

impl Material {
    /// Validated constructor; `field` prefixes the names in errors.
    pub fn new(young: f64, poisson: f64, plane: Plane) -> Result<Self> {
        let m = Self {
            young,
            poisson,
            plane,
        };
        m.validate("material")?;
        Ok(m)
    }

    /// E > 0 and finite, −1 < ν < 0.5.
    pub fn validate(&self, field: &str) -> Result<()> {
        if !(self.young.is_finite() && self.young > 0.0) {
            return Err(Error::invalid(
                format!("{field}.young"),
                self.young,
                "Young's modulus must be positive and finite",
            ));
        }
        if !(self.poisson.is_finite() && self.poisson > -1.0 && self.poisson < 0.5) {
            return Err(Error::invalid(
                format!("{field}.poisson"),
                self.poisson,
                "Poisson's ratio must lie in (-1, 0.5)",
            ));
        }
        Ok(())
    }

    /// The constitutive matrix D in Voigt order (xx, yy, xy) with
    /// engineering shear strain γ_xy = 2 ε_xy.
    pub fn d_matrix(&self) -> [[f64; 3]; 3] {
        let (e, nu) = (self.young, self.poisson);
        let (a, b) = match self.plane {
            Plane::Strain => {
                let c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
                (c * (1.0 - nu), c * nu)
            }
            Plane::Stress => {
                let c = e / (1.0 - nu * nu);
                (c, c * nu)
            }
        };
        let g = e / (2.0 * (1.0 + nu));
        [[a, b, 0.0], [b, a, 0.0], [0.0, 0.0, g]]
    }

    /// σ = D ε for a Voigt strain.
    pub fn stress(&self, strain: [f64; 3]) -> [f64; 3] {
        let d = self.d_matrix();
        let mut s = [0.0; 3];
        for i in 0..3 {
            for j in 0..3 {
                s[i] += d[i][j] * strain[j];
            }
        }
        s
    }

    /// The out-of-plane stress σ_zz implied by the plane assumption.
    pub fn stress_zz(&self, s: [f64; 3]) -> f64 {
        match self.plane {
            Plane::Strain => self.poisson * (s[0] + s[1]),
            Plane::Stress => 0.0,
        }
    }
}
