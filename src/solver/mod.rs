//! Nonlinear solvers for the contact problem: BFGS (16) with the tied start
//! (17) and the secant correction (18)–(19), and a globalised semismooth Newton.

pub mod history;
