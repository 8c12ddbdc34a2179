//! The checks of single values shared by the scene's validation, and the
//! check of the magnitudes the input implies.

use super::{load_kind, Scene};
use crate::assembly::Load;
use crate::error::{Error, Result};
use crate::wellposed;

/// A number as shown in error messages: plain, or in exponent form when
/// the plain form would be long (`1e308`, not 309 digits).
pub(super) fn show(v: f64) -> String {
    let plain = v.to_string();
    if plain.len() > 16 {
        format!("{v:e}")
    } else {
        plain
    }
}

pub(super) fn finite(field: impl Into<String>, v: f64) -> Result<()> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(Error::invalid(field, v, "must be a finite number"))
    }
}

pub(super) fn finite_point(field: &str, p: [f64; 2]) -> Result<()> {
    for (c, &v) in p.iter().enumerate() {
        finite(format!("{field}[{c}]"), v)?;
    }
    Ok(())
}

pub(super) fn positive(field: impl Into<String>, v: f64) -> Result<()> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(
            field,
            show(v),
            "must be positive and finite",
        ))
    }
}

pub(super) fn in_range(field: impl Into<String>, v: usize, lo: usize, hi: usize) -> Result<()> {
    if (lo..=hi).contains(&v) {
        Ok(())
    } else {
        Err(Error::invalid(field, v, format!("must lie in {lo}..={hi}")))
    }
}

/// [`wellposed::representable`] for a magnitude implied by the input
/// value at `field`, showing that value.
pub(super) fn check_scale(field: &str, value: f64, implied: f64, what: &str) -> Result<()> {
    wellposed::representable(field, implied, what).map_err(|e| match e {
        Error::InvalidInput { field, reason, .. } => Error::invalid(field, show(value), reason),
        other => other,
    })
}

impl Scene {
    /// Checks that the magnitudes of the input, and the displacements they
    /// imply, are ones double precision can carry ([`wellposed::representable`]).
    pub(super) fn validate_scales(&self) -> Result<()> {
        let names = self.body_index();
        let mut size = Vec::with_capacity(self.bodies.len());
        for (i, b) in self.bodies.iter().enumerate() {
            let f = format!("body[{i}]");
            let young = b.material.young;
            wellposed::representable(&format!("{f}.material.young"), young, "the stiffness")?;
            let l = b.geometry.size();
            let (key, value) = b.geometry.size_key();
            let g = format!("{f}.geometry.{}.{key}", b.geometry.kind());
            check_scale(&g, value.unwrap_or(l), l, "the body size")?;
            size.push(l);
        }
        for (i, l) in self.loads.iter().enumerate() {
            let b = names[l.body().as_str()];
            let (key, value, force) = match l {
                Load::BodyForce { force, .. } => {
                    let m = force[0].hypot(force[1]);
                    ("force", m, m * size[b] * size[b])
                }
                Load::Traction { traction, .. } => {
                    let m = traction[0].hypot(traction[1]);
                    ("traction", m, m * size[b])
                }
                Load::Pressure { pressure, .. } => ("pressure", *pressure, pressure * size[b]),
            };
            let field = format!("load[{i}].{}.{key}", load_kind(l));
            check_scale(&field, value, force, "the load resultant")?;
            let young = self.bodies[b].material.young;
            check_scale(&field, value, force / young, "the displacements")?;
        }
        for (i, s) in self.supports.iter().enumerate() {
            let b = names[s.body.as_str()];
            let young = self.bodies[b].material.young;
            let field = format!("support[{i}].value");
            check_scale(&field, s.value, s.value, "the prescribed displacement")?;
            check_scale(&field, s.value, s.value * young, "the support reactions")?;
        }
        Ok(())
    }
}
