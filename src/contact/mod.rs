//! Nitsche contact: pairs and their quadrature points (gap, normal, Eq. 4–5),
//! the closest-point projection, the empirical penalty (11), and the
//! residual and matrices of Eq. (9), (13), (17)–(19).

pub mod contacts;
pub mod nitsche;
pub mod pair;
pub mod params;
pub mod penalty;
pub mod point;
pub mod projection;
pub mod stability;
mod trace;

pub use contacts::Contacts;
pub use pair::{contact_points, ContactPair, ContactPoint, Master, Role};
pub use params::{
    GaussCount, GaussPoints, Integration, Modulus, Nitsche, Penalty, PenaltyFactor,
    PenaltyFactorError, PenaltyKind, Sides, Theta, MAX_PENALTY_FACTOR, MIN_PENALTY_FACTOR,
};
