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

/// How the bulk part of the stress is discretised.
///
/// The displacement formulation takes σ = D ε(u) at every point. Near
/// incompressibility (ν → ½ in plane strain) its volumetric term κ (div u)²
/// asks div u to vanish at every quadrature point, more constraints than a
/// spline space can meet, and the body locks. The mixed formulations are
/// the B̄ method (Hughes 2000, §4.5; Elguedj, Bazilevs, Calo & Hughes,
/// CMAME 197, 2008): σ = 2μ dev ε(u) + κ θ̄ I with θ̄ a projection of div u
/// onto a pressure space, the pressure eliminated so that the stiffness
/// stays symmetric positive definite and sparse (one factorisation per
/// solve). `Mixed` projects onto the continuous splines of degree p − 1
/// ([`crate::pressure`]) and does not lock; `LocalMixed` projects per element
/// onto Q_{p−1}, keeps the element-local structure, and still locks.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Formulation {
    /// σ = D ε(u) (the paper's).
    #[default]
    Displacement,
    /// σ = 2μ dev ε(u) + κ θ̄ I with θ̄ the projection of div u onto the
    /// continuous splines of degree p − 1 ([`crate::pressure`]).
    Mixed,
    /// As `Mixed` with θ̄ the projection onto polynomials of degree p − 1
    /// per element, discontinuous between elements: element-local, but it
    /// still locks on maximally smooth splines (kept as the comparison of
    /// the chapter "Near incompressibility").
    LocalMixed,
}

impl Formulation {
    /// The name used in scene files.
    pub fn name(self) -> &'static str {
        match self {
            Formulation::Displacement => "displacement",
            Formulation::Mixed => "mixed",
            Formulation::LocalMixed => "local_mixed",
        }
    }
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

    /// The shear modulus μ = E / (2(1 + ν)).
    pub fn shear_modulus(&self) -> f64 {
        self.young / (2.0 * (1.0 + self.poisson))
    }

    /// The 3D bulk modulus κ = λ + 2μ/3 = E / (3(1 − 2ν)).
    pub fn bulk_modulus(&self) -> f64 {
        self.young / (3.0 * (1.0 - 2.0 * self.poisson))
    }

    /// The deviatoric part of the plane-strain D: σ_dev = 2μ dev ε with the
    /// 3D deviator (ε_zz = 0 enters the trace), so that D = D_dev + κ m mᵀ,
    /// m = (1, 1, 0). In Voigt order with engineering shear.
    pub fn d_deviatoric(&self) -> [[f64; 3]; 3] {
        let mu = self.shear_modulus();
        let (a, b) = (4.0 * mu / 3.0, -2.0 * mu / 3.0);
        [[a, b, 0.0], [b, a, 0.0], [0.0, 0.0, mu]]
    }

    /// The plane-strain stress of the mixed formulation from the strain and
    /// the projected dilatation θ̄: (σ_xx, σ_yy, σ_xy) and σ_zz. With
    /// θ̄ = tr ε it equals [`Material::stress`] and [`Material::stress_zz`].
    pub fn mixed_stress(&self, strain: [f64; 3], theta: f64) -> ([f64; 3], f64) {
        let mu = self.shear_modulus();
        let kappa = self.bulk_modulus();
        let tr = strain[0] + strain[1];
        let p = kappa * theta - 2.0 * mu * tr / 3.0;
        (
            [
                2.0 * mu * strain[0] + p,
                2.0 * mu * strain[1] + p,
                mu * strain[2],
            ],
            p,
        )
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
