//! Kept only for `tests/scene.rs`, which still includes this file by path;
//! the Hertz set-up itself is `companion::hertz`. Remove this file once
//! that test uses `companion::hertz` directly.

#![allow(unused_imports)]

pub use companion::hertz::*;
