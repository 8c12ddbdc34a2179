//! Scene files: parsing, validation (one table of refused scenes, each row
//! checking that the error names the key path and the value), the shipped
//! scenes, and lean, atomic output. One module per concern:
//!
//! - [`text`]: the scene texts the tests edit (a small valid scene of two
//!   blocks, one body, a block on a rigid floor);
//! - [`shipped`]: the shipped scenes parse, build, round-trip and agree
//!   with what they stand for;
//! - [`syntax`]: TOML syntax errors and unreadable files;
//! - [`accepted`]: scenes beside the rejected ones that must build, and the
//!   defaults;
//! - [`rejected`]: the one table of refused scenes;
//! - [`build_errors`]: errors found by building or checking, beside the
//!   table;
//! - [`quadrature`]: under-integration, allowed and at the minimum;
//! - [`outputs`]: what a run writes and reports.

#[path = "../common/mod.rs"]
mod common;

mod accepted;
mod build_errors;
mod outputs;
mod quadrature;
mod rejected;
mod shipped;
mod syntax;
mod text;
