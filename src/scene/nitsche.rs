//! The `nitsche` table of a contact as a scene writes it, and its reading
//! into the library's typed [`Nitsche`] parameters: the two keys `penalty`
//! and `penalty_factor` are one [`Penalty`] there, read here once.

use crate::contact::{
    GaussCount, GaussPoints, Integration, Modulus, Nitsche, Penalty, PenaltyFactor, PenaltyKind,
    Sides, Theta,
};
use crate::error::Result;
use serde::{Deserialize, Serialize};

/// The `nitsche` table of a `[[contact]]`, key for key; every key has the
/// default of [`Nitsche`]. [`Scene::validate`](super::Scene::validate)
/// reads it into a [`Nitsche`] ([`NitscheSpec::validate`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct NitscheSpec {
    /// θ of Eq. (9); the paper uses 0.
    pub theta: Theta,
    /// How γ is chosen: the empirical Eq. (11) (the paper) or the sharp bound.
    pub penalty: PenaltyKind,
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

impl Default for NitscheSpec {
    /// The keys of [`Nitsche::default`].
    fn default() -> Self {
        let Nitsche {
            theta,
            penalty: _,
            modulus,
            sides,
            integration,
            gauss_points,
        } = Nitsche::default();
        let gauss_points = gauss_points.fixed();
        Self {
            theta,
            penalty: PenaltyKind::default(),
            modulus,
            sides,
            penalty_factor: PenaltyFactor::ONE.get(),
            integration,
            gauss_points,
        }
    }
}

impl NitscheSpec {
    /// The typed parameters of the table at key path `field` (e.g.
    /// `contact[0].nitsche`), or the error naming the key and value that
    /// are out of range.
    pub fn validate(&self, field: &str) -> Result<Nitsche> {
        let factor = PenaltyFactor::new(self.penalty_factor)
            .map_err(|e| e.at(format!("{field}.penalty_factor")))?;
        let gauss_points = match self.gauss_points {
            None => GaussPoints::DegreePlusTwo,
            Some(n) => GaussPoints::Fixed(GaussCount::new(n, format!("{field}.gauss_points"))?),
        };
        Ok(Nitsche {
            theta: self.theta,
            penalty: Penalty::new(self.penalty, factor),
            modulus: self.modulus,
            sides: self.sides,
            integration: self.integration,
            gauss_points,
        })
    }

    /// Gauss points per element or segment for the pair's degree `degree`
    /// ([`Nitsche::points`]).
    pub fn points(&self, degree: usize) -> usize {
        self.gauss_points
            .unwrap_or(GaussPoints::DegreePlusTwo.count(degree))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::{MAX_PENALTY_FACTOR, MIN_PENALTY_FACTOR};

    #[derive(Deserialize, Serialize)]
    struct Wrap {
        nitsche: NitscheSpec,
    }

    fn read(keys: &str) -> NitscheSpec {
        toml::from_str::<Wrap>(&format!("nitsche = {{ {keys} }}"))
            .unwrap()
            .nitsche
    }

    fn factor(f: f64) -> PenaltyFactor {
        PenaltyFactor::new(f).unwrap()
    }

    /// Each combination of the two keys, either absent, gives the penalty
    /// whose meaning the kind sets; the other keys come through as they are.
    #[test]
    fn penalty_and_factor_become_one_penalty() {
        let cases = [
            (
                "",
                Penalty::Empirical {
                    factor: factor(1.0),
                },
            ),
            (
                "penalty_factor = 0.5",
                Penalty::Empirical {
                    factor: factor(0.5),
                },
            ),
            (
                "penalty = \"empirical\"",
                Penalty::Empirical {
                    factor: factor(1.0),
                },
            ),
            (
                "penalty = \"empirical\", penalty_factor = 3",
                Penalty::Empirical {
                    factor: factor(3.0),
                },
            ),
            (
                "penalty = \"sharp\"",
                Penalty::Sharp {
                    safety: factor(1.0),
                },
            ),
            (
                "penalty = \"sharp\", penalty_factor = 2.0",
                Penalty::Sharp {
                    safety: factor(2.0),
                },
            ),
            (
                "penalty_factor = 1e-12, penalty = \"sharp\"",
                Penalty::Sharp {
                    safety: factor(MIN_PENALTY_FACTOR),
                },
            ),
            (
                "penalty_factor = 1e12",
                Penalty::Empirical {
                    factor: factor(MAX_PENALTY_FACTOR),
                },
            ),
        ];
        for (keys, penalty) in cases {
            let n = read(keys).validate("contact[0].nitsche").unwrap();
            assert_eq!(n.penalty, penalty, "{keys}");
            assert_eq!(
                Nitsche { penalty, ..n },
                Nitsche {
                    penalty,
                    ..Nitsche::default()
                },
                "{keys}"
            );
        }
        let all = read(
            "theta = -1, penalty = \"sharp\", penalty_factor = 4, modulus = \"max\", \
             sides = \"unbiased\", integration = \"gauss\", gauss_points = 5",
        );
        assert_eq!(
            all.validate("c").unwrap(),
            Nitsche {
                theta: Theta::Skew,
                penalty: Penalty::Sharp {
                    safety: factor(4.0)
                },
                modulus: Modulus::Max,
                sides: Sides::Unbiased,
                integration: Integration::Gauss,
                gauss_points: GaussPoints::Fixed(GaussCount::new(5, "n").unwrap()),
            }
        );
        assert_eq!(read(""), NitscheSpec::default());
        let back: Wrap = toml::from_str(&toml::to_string(&Wrap { nitsche: all }).unwrap()).unwrap();
        assert_eq!(back.nitsche, all);
    }

    /// A factor out of range is refused whichever kind it scales, by one
    /// error line naming the key under the table's path.
    #[test]
    fn a_factor_out_of_range_names_the_key() {
        for kind in ["empirical", "sharp"] {
            for (value, shown) in [
                ("0", "0"),
                ("-2.5", "-2.5"),
                ("nan", "NaN"),
                ("inf", "inf"),
                ("1e300", "1e300"),
                ("1e-13", "1e-13"),
                ("1.0000000000001e12", "1.0000000000001e12"),
            ] {
                let spec = read(&format!("penalty = \"{kind}\", penalty_factor = {value}"));
                let e = spec.validate("contact[3].nitsche").unwrap_err().to_string();
                let line =
                    format!("invalid input: `contact[3].nitsche.penalty_factor` = {shown}: ");
                assert!(e.starts_with(&line), "{kind} {value}: {e}");
                assert_eq!(e.lines().count(), 1, "{e}");
            }
        }
        let e = read("gauss_points = 0")
            .validate("contact[1].nitsche")
            .unwrap_err();
        assert!(
            e.to_string()
                .contains("`contact[1].nitsche.gauss_points` = 0"),
            "{e}"
        );
    }
}
