//! The Nitsche parameters of a contact pair as typed values: a scene's
//! `nitsche` table is validated into them once
//! ([`crate::scene::NitscheSpec`]), and contact pairs and the chapter
//! programs use them as they are.

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

/// The rule that sets γ, as a scene's key `penalty` names it: a
/// [`Penalty`] without its factor.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PenaltyKind {
    /// The paper's empirical formula, Eq. (11).
    #[default]
    Empirical,
    /// The stability bound of each slave element.
    Sharp,
}

/// The range of a [`PenaltyFactor`]. γ is the factor times E/h, and the
/// stiffness it is added to is of order E/h too: twelve decades apart, with
/// the system's own conditioning on top, one of the two is lost in the
/// other's 1e-16 round-off. The penalty studies' range (1e-12 to 1e6) lies
/// inside.
pub const MIN_PENALTY_FACTOR: f64 = 1e-12;
pub const MAX_PENALTY_FACTOR: f64 = 1e12;

/// A factor that scales a penalty: a number in
/// [`MIN_PENALTY_FACTOR`]`..=`[`MAX_PENALTY_FACTOR`], as only
/// [`PenaltyFactor::new`] makes one, so that what holds one needs no check.
#[derive(Clone, Copy, Debug, PartialEq, PartialOrd)]
pub struct PenaltyFactor(f64);

impl PenaltyFactor {
    /// The factor 1: the paper's penalty, or the bound itself.
    pub const ONE: PenaltyFactor = PenaltyFactor(1.0);

    /// `value` as a factor, if it lies in the range.
    pub fn new(value: f64) -> std::result::Result<Self, PenaltyFactorError> {
        if !(value.is_finite() && value > 0.0) {
            Err(PenaltyFactorError::NotPositive(value))
        } else if !(MIN_PENALTY_FACTOR..=MAX_PENALTY_FACTOR).contains(&value) {
            Err(PenaltyFactorError::OutOfRange(value))
        } else {
            Ok(PenaltyFactor(value))
        }
    }

    /// The number.
    pub fn get(self) -> f64 {
        self.0
    }
}

/// Why a number is no [`PenaltyFactor`]: data, rendered once by `Display`
/// into the reason of the input error that names the key
/// ([`PenaltyFactorError::at`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PenaltyFactorError {
    /// Zero, negative, infinite or NaN.
    NotPositive(f64),
    /// Positive and finite, but outside the range.
    OutOfRange(f64),
}

impl PenaltyFactorError {
    /// The input error of key `field` (`contact[0].nitsche.penalty_factor`).
    pub fn at(self, field: impl Into<String>) -> Error {
        let shown = match self {
            PenaltyFactorError::NotPositive(v) => v.to_string(),
            // as written in a scene: 1e300, not three hundred digits
            PenaltyFactorError::OutOfRange(v) => format!("{v:e}"),
        };
        Error::invalid(field, shown, self.to_string())
    }
}

impl fmt::Display for PenaltyFactorError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PenaltyFactorError::NotPositive(_) => f.write_str("must be positive and finite"),
            PenaltyFactorError::OutOfRange(_) => write!(
                f,
                "must lie in {MIN_PENALTY_FACTOR:e}..={MAX_PENALTY_FACTOR:e}: beyond, the \
                 penalty against the stiffness falls below or rises above the round-off of \
                 double precision, so the contact terms vanish in the stiffness or swamp it \
                 (and γ itself can overflow)"
            ),
        }
    }
}

/// How the penalty γ of a pair is chosen, with the factor that scales it.
/// A scene writes it as two keys, `penalty` (the [`PenaltyKind`]) and
/// `penalty_factor` (the factor, whose meaning the kind sets).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Penalty {
    /// The paper's empirical formula, Eq. (11), times `factor`
    /// ([`super::penalty::empirical_penalty`]); 1 reproduces the paper.
    Empirical { factor: PenaltyFactor },
    /// The stability bound of the θ-family from each slave element's
    /// trace-inverse constant, times the safety factor `safety`
    /// ([`super::penalty::sharp_penalty`]).
    Sharp { safety: PenaltyFactor },
}

impl Default for Penalty {
    /// The paper's: Eq. (11) with factor 1.
    fn default() -> Self {
        Penalty::Empirical {
            factor: PenaltyFactor::ONE,
        }
    }
}

impl Penalty {
    /// The penalty of kind `kind` scaled by `factor`.
    pub fn new(kind: PenaltyKind, factor: PenaltyFactor) -> Self {
        match kind {
            PenaltyKind::Empirical => Penalty::Empirical { factor },
            PenaltyKind::Sharp => Penalty::Sharp { safety: factor },
        }
    }
}

/// Largest number of Gauss points per contact element or segment.
pub const MAX_GAUSS_POINTS: usize = 30;

/// A number of Gauss points per contact element or segment, in
/// `1..=`[`MAX_GAUSS_POINTS`], as only [`GaussCount::new`] makes one, so
/// that what holds one needs no check.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct GaussCount(usize);

impl GaussCount {
    /// `n` as a count, if it lies in `1..=`[`MAX_GAUSS_POINTS`]; else the
    /// error naming `field`, the key it was read from
    /// (`contact[0].nitsche.gauss_points`).
    pub fn new(n: usize, field: impl Into<String>) -> Result<Self> {
        if (1..=MAX_GAUSS_POINTS).contains(&n) {
            Ok(GaussCount(n))
        } else {
            Err(Error::invalid(
                field,
                n,
                format!("must lie in 1..={MAX_GAUSS_POINTS}"),
            ))
        }
    }

    /// The number.
    pub fn get(self) -> usize {
        self.0
    }
}

/// How many Gauss points each contact element or segment gets.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum GaussPoints {
    /// p + 2, with p the highest degree of the pair's bodies (the
    /// library's default): one more than the p + 1 that integrates the
    /// product of two traces on a straight side exactly.
    #[default]
    DegreePlusTwo,
    /// A count of the user's, as a scene's `gauss_points` key gives it.
    Fixed(GaussCount),
}

impl GaussPoints {
    /// The count for the pair's degree `degree` (the highest of its bodies').
    pub fn count(self, degree: usize) -> usize {
        match self {
            GaussPoints::DegreePlusTwo => degree + 2,
            GaussPoints::Fixed(n) => n.get(),
        }
    }

    /// The user's count, if one was given.
    pub fn fixed(self) -> Option<usize> {
        match self {
            GaussPoints::DegreePlusTwo => None,
            GaussPoints::Fixed(n) => Some(n.get()),
        }
    }
}

/// The Nitsche parameters of one contact pair, as a scene's `nitsche`
/// table is validated into ([`crate::scene::NitscheSpec`]) and chapter
/// programs build them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Nitsche {
    /// θ of Eq. (9); the paper uses 0.
    pub theta: Theta,
    /// How γ is chosen, and its factor: the empirical Eq. (11) (the
    /// paper) or the sharp bound.
    pub penalty: Penalty,
    /// Whose modulus enters (11) between two elastic bodies.
    pub modulus: Modulus,
    /// One side (the paper's) or both, between two elastic bodies.
    pub sides: Sides,
    pub integration: Integration,
    /// Gauss points per element or segment.
    pub gauss_points: GaussPoints,
}

impl Default for Nitsche {
    /// θ = 0 and the empirical penalty with factor 1 (the paper's); the
    /// slave's modulus in (11), the biased form, and segment integration
    /// (the library's: the paper integrates contact at Gauss points,
    /// `integration = "gauss"`).
    fn default() -> Self {
        Self {
            theta: Theta::Incomplete,
            penalty: Penalty::default(),
            modulus: Modulus::Slave,
            sides: Sides::Biased,
            integration: Integration::Segment,
            gauss_points: GaussPoints::DegreePlusTwo,
        }
    }
}

impl Nitsche {
    /// Gauss points per element or segment for the pair's degree `degree`
    /// (the highest of its bodies').
    pub fn points(&self, degree: usize) -> usize {
        self.gauss_points.count(degree)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Deserialize, Serialize)]
    struct Wrap {
        theta: Theta,
    }

    #[test]
    fn theta_reads_numbers_and_rejects_others() {
        for (text, theta) in [
            ("1", Theta::Symmetric),
            ("0", Theta::Incomplete),
            ("-1", Theta::Skew),
            ("-1.0", Theta::Skew),
        ] {
            let w: Wrap = toml::from_str(&format!("theta = {text}")).unwrap();
            assert_eq!(w.theta, theta);
            let back: Wrap = toml::from_str(&toml::to_string(&w).unwrap()).unwrap();
            assert_eq!(back.theta, w.theta);
        }
        for bad in ["0.5", "2", "\"zero\""] {
            assert!(toml::from_str::<Wrap>(&format!("theta = {bad}")).is_err());
        }
    }

    /// The limits themselves are factors, the numbers just beyond them
    /// and every non-positive or non-finite number are not, each with its
    /// own reason.
    #[test]
    fn a_penalty_factor_lies_in_its_range() {
        for ok in [MIN_PENALTY_FACTOR, 1e-3, 1.0, 2.0, MAX_PENALTY_FACTOR] {
            assert_eq!(PenaltyFactor::new(ok).map(PenaltyFactor::get), Ok(ok));
        }
        let below = MIN_PENALTY_FACTOR * (1.0 - f64::EPSILON);
        let above = MAX_PENALTY_FACTOR * (1.0 + f64::EPSILON);
        for out in [below, above, 1e-300, 1e300] {
            assert_eq!(
                PenaltyFactor::new(out),
                Err(PenaltyFactorError::OutOfRange(out))
            );
        }
        for bad in [0.0, -0.0, -2.5, f64::INFINITY, f64::NEG_INFINITY] {
            assert_eq!(
                PenaltyFactor::new(bad),
                Err(PenaltyFactorError::NotPositive(bad))
            );
        }
        assert!(matches!(
            PenaltyFactor::new(f64::NAN),
            Err(PenaltyFactorError::NotPositive(v)) if v.is_nan()
        ));
    }

    /// The error line of a refused factor: the key, the value as a scene
    /// writes it, and the reason.
    #[test]
    fn a_refused_factor_names_its_key() {
        let field = "contact[0].nitsche.penalty_factor";
        let e = |v: f64| PenaltyFactor::new(v).unwrap_err().at(field).to_string();
        assert_eq!(
            e(-2.5),
            "invalid input: `contact[0].nitsche.penalty_factor` = -2.5: must be positive and \
             finite"
        );
        assert_eq!(
            e(f64::NAN),
            "invalid input: `contact[0].nitsche.penalty_factor` = NaN: must be positive and \
             finite"
        );
        assert_eq!(
            e(1e300),
            "invalid input: `contact[0].nitsche.penalty_factor` = 1e300: must lie in \
             1e-12..=1e12: beyond, the penalty against the stiffness falls below or rises \
             above the round-off of double precision, so the contact terms vanish in the \
             stiffness or swamp it (and γ itself can overflow)"
        );
        assert!(e(1e-13).starts_with(
            "invalid input: `contact[0].nitsche.penalty_factor` = 1e-13: must lie in"
        ));
    }

    #[test]
    fn the_kind_chooses_what_the_factor_means() {
        let f = PenaltyFactor::new(2.0).unwrap();
        assert_eq!(
            Penalty::new(PenaltyKind::Empirical, f),
            Penalty::Empirical { factor: f }
        );
        assert_eq!(
            Penalty::new(PenaltyKind::Sharp, f),
            Penalty::Sharp { safety: f }
        );
        assert_eq!(
            Penalty::default(),
            Penalty::new(PenaltyKind::default(), PenaltyFactor::ONE)
        );
    }

    #[test]
    fn gauss_counts_name_the_key() {
        for (n, ok) in [(1, true), (30, true), (0, false), (31, false)] {
            let r = GaussCount::new(n, "contact[2].nitsche.gauss_points");
            assert_eq!(r.is_ok(), ok, "{n}");
            match r {
                Ok(c) => assert_eq!(GaussPoints::Fixed(c).count(7), n),
                Err(e) => assert!(
                    e.to_string()
                        .contains("`contact[2].nitsche.gauss_points` = "),
                    "{e}"
                ),
            }
        }
        assert_eq!(GaussPoints::DegreePlusTwo.count(3), 5);
    }
}
