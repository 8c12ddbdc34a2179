//! The paper's benchmark set-ups as plain constructors (the scene files in
//! `data/scenes/` describe the same problems declaratively).

use crate::assembly::Load;
use crate::contact::{ContactPair, Integration, Master};
use crate::dofs::{Body, DofMap};
use crate::error::Result;
use crate::geometry;
use crate::material::{Material, Plane};
use crate::nurbs::{NurbsPatch, Side};
use crate::problem::Problem;
use crate::space::Space;

/// Taylor contact patch test: plane stress, two stacked blocks on
/// non-matching meshes (lower 4×2, upper 3×2), E = 1e9, ν = 0.3, 1e8 Pa
/// on top. The upper block's bottom is the slave.
pub struct Taylor {
    pub degree: usize,
    pub lower: [usize; 2],
    pub upper: [usize; 2],
    pub integration: Integration,
    pub theta: f64,
    pub penalty_factor: f64,
}

impl Default for Taylor {
    fn default() -> Self {
        Self {
            degree: 2,
            lower: [4, 2],
            upper: [3, 2],
            integration: Integration::Segment,
            theta: 0.0,
            penalty_factor: 1.0,
        }
    }
}

pub const TAYLOR_PRESSURE: f64 = 1e8;
pub const TAYLOR_YOUNG: f64 = 1e9;

impl Taylor {
    pub fn material() -> Material {
        Material {
            young: TAYLOR_YOUNG,
            poisson: 0.3,
            plane: Plane::Stress,
        }
    }

    pub fn build(&self) -> Result<Problem> {
        self.build_with(Self::material(), Self::material(), 1.0)
    }

    /// As [`Taylor::build`] with given materials and a load multiplier.
    pub fn build_with(&self, lower: Material, upper: Material, load_scale: f64) -> Result<Problem> {
        self.build_with_gap(lower, upper, load_scale, 0.0)
    }

    /// As [`Taylor::build_with`] with the upper block lifted by `gap`
    /// (negative: an initial penetration).
    pub fn build_with_gap(
        &self,
        lower: Material,
        upper: Material,
        load_scale: f64,
        gap: f64,
    ) -> Result<Problem> {
        let lo = geometry::rectangle(0.0, 0.0, 1.0, 0.5)?.k_refined(self.degree, self.lower)?;
        let up = geometry::rectangle(0.0, 0.5 + gap, 1.0, 1.0 + gap)?
            .k_refined(self.degree, self.upper)?;
        let bodies = vec![
            Body {
                name: "lower".into(),
                space: Space::new(lo, None)?,
                material: lower,
            },
            Body {
                name: "upper".into(),
                space: Space::new(up, None)?,
                material: upper,
            },
        ];
        let mut b = DofMap::builder(&bodies);
        b.fix_side(0, Side::EtaMin, 1, 0.0)?
            .fix_side(0, Side::XiMin, 0, 0.0)?
            .fix_side(1, Side::XiMin, 0, 0.0)?;
        let map = b.build();
        let loads = [Load::Pressure {
            body: 1,
            side: Side::EtaMax,
            pressure: TAYLOR_PRESSURE * load_scale,
        }];
        let pair = ContactPair {
            integration: self.integration,
            theta: self.theta,
            penalty_factor: self.penalty_factor,
            ..ContactPair::new(
                1,
                Side::EtaMin,
                Master::Body {
                    body: 0,
                    side: Side::EtaMax,
                },
            )
        };
        Problem::new(bodies, map, &loads, vec![pair])
    }
}

/// Hertz contact of a disk on a rigid plane: plane strain, R = 0.2,
/// E = 2e7, ν = 0.1, body force (0, −1.3e6); the half disk x ≥ 0 with
/// u_x = 0 on the symmetry line.
pub struct Hertz {
    pub degree: usize,
    pub elements: usize,
    pub theta: f64,
    pub penalty_factor: f64,
    pub integration: Integration,
    /// Replace the exact NURBS disk by an isoparametric Lagrange mesh of this
    /// degree (FEM Q1/Q2) with nodes on the exact circle.
    pub lagrange: Option<usize>,
}

pub const HERTZ_RADIUS: f64 = 0.2;
pub const HERTZ_YOUNG: f64 = 2e7;
pub const HERTZ_POISSON: f64 = 0.1;
pub const HERTZ_BODY_FORCE: f64 = 1.3e6;

impl Default for Hertz {
    fn default() -> Self {
        Self {
            degree: 2,
            elements: 8,
            theta: 0.0,
            penalty_factor: 1.0,
            integration: Integration::Gauss,
            lagrange: None,
        }
    }
}

/// Analytic Hertz quantities for a cylinder on a rigid plane (plane strain).
pub struct HertzAnalytic {
    pub load: f64,
    pub half_width: f64,
    pub p0: f64,
}

impl HertzAnalytic {
    pub fn new() -> Self {
        let r = HERTZ_RADIUS;
        let e_star = HERTZ_YOUNG / (1.0 - HERTZ_POISSON * HERTZ_POISSON);
        let load = HERTZ_BODY_FORCE * std::f64::consts::PI * r * r;
        let a = 2.0 * (load * r / (std::f64::consts::PI * e_star)).sqrt();
        Self {
            load,
            half_width: a,
            p0: 2.0 * load / (std::f64::consts::PI * a),
        }
    }

    /// p(x) = p₀ √(1 − x²/a²).
    pub fn pressure(&self, x: f64) -> f64 {
        let s = 1.0 - (x / self.half_width).powi(2);
        if s > 0.0 {
            self.p0 * s.sqrt()
        } else {
            0.0
        }
    }
}

impl Default for HertzAnalytic {
    fn default() -> Self {
        Self::new()
    }
}

impl Hertz {
    pub fn material() -> Material {
        Material {
            young: HERTZ_YOUNG,
            poisson: HERTZ_POISSON,
            plane: Plane::Strain,
        }
    }

    pub fn patch(&self) -> Result<NurbsPatch> {
        self.patch_at(0.0)
    }

    /// The disk with its lowest point at height `lift` above the floor.
    pub fn patch_at(&self, lift: f64) -> Result<NurbsPatch> {
        let exact = geometry::half_disk([0.0, HERTZ_RADIUS + lift], HERTZ_RADIUS)?;
        match self.lagrange {
            None => exact.k_refined(self.degree, [self.elements, self.elements]),
            Some(p) => geometry::lagrange_interpolant(&exact, p, [self.elements, self.elements]),
        }
    }

    pub fn build(&self) -> Result<Problem> {
        self.build_with(Self::material(), 1.0)
    }

    pub fn build_with(&self, material: Material, load_scale: f64) -> Result<Problem> {
        self.build_lifted(material, load_scale, 0.0)
    }

    /// As [`Hertz::build_with`] with the disk lifted by `lift` (negative:
    /// an initial penetration).
    pub fn build_lifted(&self, material: Material, load_scale: f64, lift: f64) -> Result<Problem> {
        let bodies = vec![Body {
            name: "disk".into(),
            space: Space::new(self.patch_at(lift)?, None)?,
            material,
        }];
        let mut b = DofMap::builder(&bodies);
        b.fix_side(0, Side::XiMin, 0, 0.0)?;
        let map = b.build();
        let loads = [Load::BodyForce {
            body: 0,
            force: [0.0, -HERTZ_BODY_FORCE * load_scale],
        }];
        let r = HERTZ_RADIUS;
        let floor = geometry::segment([-r, 0.0], [2.0 * r, 0.0])?;
        let pair = ContactPair {
            integration: self.integration,
            theta: self.theta,
            penalty_factor: self.penalty_factor,
            ..ContactPair::new(0, Side::EtaMin, Master::Rigid(floor))
        };
        Problem::new(bodies, map, &loads, vec![pair])
    }
}
