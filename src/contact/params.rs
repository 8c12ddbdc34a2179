//! The Nitsche parameters of a contact pair, in one typed group with one
//! default and one validation, used by scene files, contact pairs and the
//! chapter programs alike.

use crate::error::{Error, Result};
use serde::de::{self, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::fmt;

/// The member of the θ-family of Nitsche formulations (Eq. 9).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Theta {
    /// θ = 1: derives from an energy; symmetric tangent.
    Symmetric,
    /// θ = 0: the paper's variant; the simplest residual, non-symmetric tangent.
    #[default]
    Incomplete,
    /// θ = −1: skew-symmetric; stable for any penalty γ > 0.
    Skew,
}

impl Theta {
    /// Every variant, in the order θ = 1, 0, −1.
    pub const ALL: [Theta; 3] = [Theta::Symmetric, Theta::Incomplete, Theta::Skew];

    /// The number θ.
    pub fn value(self) -> f64 {
        match self {
            Theta::Symmetric => 1.0,
            Theta::Incomplete => 0.0,
            Theta::Skew => -1.0,
        }
    }

    /// The variant of the number θ ∈ {1, 0, −1}.
    pub fn from_value(theta: f64) -> Option<Self> {
        Self::ALL.into_iter().find(|t| t.value() == theta)
    }
}

impl fmt::Display for Theta {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // a typographic minus, as everywhere in the book's tables
        f.write_str(match self {
            Theta::Symmetric => "1",
            Theta::Incomplete => "0",
            Theta::Skew => "−1",
        })
    }
}

/// In scene files θ is the number 1, 0 or −1.
impl Serialize for Theta {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.serialize_i64(self.value() as i64)
    }
}

impl<'de> Deserialize<'de> for Theta {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct V;
        impl Visitor<'_> for V {
            type Value = Theta;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("θ = 1, 0 or -1")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> std::result::Result<Theta, E> {
                Theta::from_value(v)
                    .ok_or_else(|| E::invalid_value(de::Unexpected::Float(v), &self))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> std::result::Result<Theta, E> {
                Theta::from_value(v as f64)
                    .ok_or_else(|| E::invalid_value(de::Unexpected::Signed(v), &self))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> std::result::Result<Theta, E> {
                Theta::from_value(v as f64)
                    .ok_or_else(|| E::invalid_value(de::Unexpected::Unsigned(v), &self))
            }
        }
        d.deserialize_any(V)
    }
}

/// How the contact integral over Γc is evaluated.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Integration {
    /// Gauss points per slave element, the paper's rule: simple, but the integrand has kinks
    /// where master knots project, so it is not integrated exactly.
    Gauss,
    /// Each slave element is cut where master knots project; the integrand
    /// is smooth on every segment and the contact patch test is passed exactly.
    #[default]
    Segment,
}

/// How the penalty γ of a pair is chosen.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Penalty {
    /// The paper's empirical formula, Eq. (11).
    #[default]
    Empirical,
    /// The stability bound of the θ-family from each slave element's
    /// trace-inverse constant ([`super::penalty::sharp_penalty`]); the
    /// penalty factor is then the safety factor over the bound.
    Sharp,
}

/// Which sides of a pair between two elastic bodies carry the contact terms.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Sides {
    /// The paper's biased form: the integrals run over the slave side, with
    /// the slave's normal stress.
    #[default]
    Biased,
    /// Each body is the slave once, with half the weight (Chouly, Mlika &
    /// Renard 2018): symmetric in the two bodies. The mirrored half pairs
    /// its points along their own normal
    /// ([`super::projection::along_normal`]), so that both halves measure
    /// one gap. A rigid master has only one side, so there this is the
    /// biased form.
    Unbiased,
}

/// Whose Young's modulus E enters the penalty (11) of a point.
///
/// The slave should be the softer body: its modulus then sets γ at the
/// scale of the body the contact terms act on. A slave stiffer than its
/// master, or `Max` with a stiffer master, makes γ far exceed the
/// stability bound of the softer body, and p₀ grows with it; both are
/// warned ([`crate::solver::Warning::StifferSlave`],
/// [`crate::solver::Warning::PenaltyFarAboveBound`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Modulus {
    /// The body whose normal stress the point uses (its slave): the penalty
    /// and the consistency term then share one stress scale.
    #[default]
    Slave,
    /// max(E¹, E²), the stiffer of the two bodies: over-penalises a softer
    /// slave (warned when γ leaves the stable range; the remedy is
    /// `Slave`).
    Max,
}

/// The range of `penalty_factor`. γ is the factor times E/h, and the
/// stiffness it is added to is of order E/h too: twelve decades apart, with
/// the system's own conditioning on top, one of the two is lost in the
/// other's 1e-16 round-off. The penalty studies' range (1e-12 to 1e6) lies
/// inside.
pub const MIN_PENALTY_FACTOR: f64 = 1e-12;
pub const MAX_PENALTY_FACTOR: f64 = 1e12;

/// Largest number of Gauss points per contact element or segment.
pub const MAX_GAUSS_POINTS: usize = 30;

/// The Nitsche parameters of one contact pair (scene key `nitsche`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Nitsche {
    /// θ of Eq. (9); the paper uses 0.
    pub theta: Theta,
    /// How γ is chosen: the empirical Eq. (11) (the paper) or the sharp bound.
    pub penalty: Penalty,
    /// Whose modulus enters (11) between two elastic bodies.
    pub modulus: Modulus,
    /// One side (the paper's) or both, between two elastic bodies.
    pub sides: Sides,
    /// Multiplies the penalty; 1 reproduces the paper. For the sharp
    /// penalty it is the safety factor over the stability bound.
    pub penalty_factor: f64,
    pub integration: Integration,
    /// Gauss points per element or segment; `None`: p + 2.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gauss_points: Option<usize>,
}

impl Default for Nitsche {
    /// θ = 0 and penalty factor 1 (the paper's); the slave's modulus in
    /// (11), the biased form, and segment integration (the library's: the
    /// paper integrates contact at Gauss points, `integration = "gauss"`).
    fn default() -> Self {
        Self {
            theta: Theta::Incomplete,
            penalty: Penalty::Empirical,
            modulus: Modulus::Slave,
            sides: Sides::Biased,
            penalty_factor: 1.0,
            integration: Integration::Segment,
            gauss_points: None,
        }
    }
}

impl Nitsche {
    /// Checks the parameters; `field` is the key path of the group
    /// (e.g. `contact[0].nitsche`).
    pub fn validate(&self, field: &str) -> Result<()> {
        if !(self.penalty_factor.is_finite() && self.penalty_factor > 0.0) {
            return Err(Error::invalid(
                format!("{field}.penalty_factor"),
                self.penalty_factor,
                "must be positive and finite",
            ));
        }
        if !(MIN_PENALTY_FACTOR..=MAX_PENALTY_FACTOR).contains(&self.penalty_factor) {
            return Err(Error::invalid(
                format!("{field}.penalty_factor"),
                // as written in a scene: 1e300, not three hundred digits
                format!("{:e}", self.penalty_factor),
                format!(
                    "must lie in {MIN_PENALTY_FACTOR:e}..={MAX_PENALTY_FACTOR:e}: beyond, the \
                     penalty against the stiffness falls below or rises above the round-off \
                     of double precision, so the contact terms vanish in the stiffness or \
                     swamp it (and γ itself can overflow)"
                ),
            ));
        }
        if let Some(n) = self.gauss_points {
            if n == 0 || n > MAX_GAUSS_POINTS {
                return Err(Error::invalid(
                    format!("{field}.gauss_points"),
                    n,
                    format!("must lie in 1..={MAX_GAUSS_POINTS}"),
                ));
            }
        }
        Ok(())
    }

    /// Gauss points per element or segment for slave degree `degree`.
    pub fn points(&self, degree: usize) -> usize {
        self.gauss_points.unwrap_or(degree + 2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Deserialize, Serialize)]
    struct Wrap {
        nitsche: Nitsche,
    }

    #[test]
    fn theta_reads_numbers_and_rejects_others() {
        for (text, theta) in [
            ("1", Theta::Symmetric),
            ("0", Theta::Incomplete),
            ("-1", Theta::Skew),
            ("-1.0", Theta::Skew),
        ] {
            let w: Wrap = toml::from_str(&format!("nitsche = {{ theta = {text} }}")).unwrap();
            assert_eq!(w.nitsche.theta, theta);
            assert_eq!(w.nitsche.penalty_factor, 1.0);
            let back: Wrap = toml::from_str(&toml::to_string(&w).unwrap()).unwrap();
            assert_eq!(back.nitsche, w.nitsche);
        }
        for bad in ["0.5", "2", "\"zero\""] {
            assert!(toml::from_str::<Wrap>(&format!("nitsche = {{ theta = {bad} }}")).is_err());
        }
    }

    #[test]
    fn validation_names_the_key() {
        let n = Nitsche {
            penalty_factor: -1.0,
            ..Nitsche::default()
        };
        let e = n.validate("contact[0].nitsche").unwrap_err().to_string();
        assert!(e.contains("contact[0].nitsche.penalty_factor"), "{e}");
        let n = Nitsche {
            gauss_points: Some(0),
            ..Nitsche::default()
        };
        assert!(n.validate("x").is_err());
    }
}
