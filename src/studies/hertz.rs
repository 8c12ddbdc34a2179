//! Hertz study (being written).
