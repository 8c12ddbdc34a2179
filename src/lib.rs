//! Isogeometric frictionless contact with Nitsche's method, solved by a
//! corrected BFGS iteration: a literate companion to Hu (2021).
//!
//! Data flows one way: [`nurbs`]/[`geometry`] → [`space`] → [`assembly`] →
//! [`contact`] → [`solver`] → [`post`] → [`report`].
//!
//! The library holds no machinery of the book that documents it: it picks
//! no global allocator (the `iga-contact` binary does), reads no file of the
//! book, and the chapter programs' registry, outputs and facts live in the
//! book's own crate, `book/companion`.

pub mod assembly;
pub mod condense;
pub mod contact;
pub mod dofs;
pub mod error;
pub mod geometry;
pub mod history;
pub mod interface;
pub mod linsolve;
pub mod material;
pub mod nurbs;
pub mod post;
pub mod pressure;
pub mod problem;
pub mod quadrature;
pub mod report;
pub mod resources;
pub mod scene;
pub mod solver;
pub mod space;
pub mod sparse;
pub mod timing;
pub mod wellposed;

pub use error::{Error, ErrorKind, Result};
