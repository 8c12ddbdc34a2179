//! Input validation and data ranges: every figure checks its numbers here
//! before anything is laid out, and pads its ranges here.

use super::Polyline;
use crate::error::{Error, Result};

pub(super) fn check_finite(field: impl FnOnce() -> String, value: f64) -> Result<()> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(Error::invalid(field(), value, "must be a finite number"))
    }
}

pub(super) fn check_polylines(what: &str, lines: &[Polyline]) -> Result<()> {
    for (i, line) in lines.iter().enumerate() {
        for (j, p) in line.points.iter().enumerate() {
            for (k, &v) in p.iter().enumerate() {
                check_finite(|| format!("{what}[{i}].points[{j}][{k}]"), v)?;
            }
        }
    }
    Ok(())
}

/// A closed range of data coordinates, from `lo` to `hi`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    pub lo: f64,
    pub hi: f64,
}

impl Bounds {
    /// The smallest range holding every value; `None` for no values.
    pub fn of(values: impl IntoIterator<Item = f64>) -> Option<Bounds> {
        values.into_iter().fold(None, |b, v| {
            Some(match b {
                None => Bounds { lo: v, hi: v },
                Some(Bounds { lo, hi }) => Bounds {
                    lo: lo.min(v),
                    hi: hi.max(v),
                },
            })
        })
    }

    /// Widens by `fraction` of the span on each side; a (nearly) empty span
    /// gets a width of its own so that it still maps onto the plot. `what`
    /// names the range in the error when the result is not finite.
    pub fn padded(self, fraction: f64, what: &str) -> Result<Bounds> {
        let span = self.hi - self.lo;
        let mid = 0.5 * (self.lo + self.hi);
        let scale = self.lo.abs().max(self.hi.abs());
        let b = if span <= 1e-9 * scale || span == 0.0 {
            let half = if scale > 0.0 { 0.05 * scale } else { 1.0 };
            Bounds {
                lo: mid - half,
                hi: mid + half,
            }
        } else {
            Bounds {
                lo: self.lo - fraction * span,
                hi: self.hi + fraction * span,
            }
        };
        if b.lo.is_finite() && b.hi.is_finite() && (b.hi - b.lo).is_finite() {
            Ok(b)
        } else {
            Err(Error::invalid(
                what,
                format!("[{:e}, {:e}]", self.lo, self.hi),
                "range too large to plot",
            ))
        }
    }

    pub fn span(self) -> f64 {
        self.hi - self.lo
    }

    pub fn mid(self) -> f64 {
        0.5 * (self.lo + self.hi)
    }
}

pub(super) fn polyline_bounds(lines: &[Polyline]) -> Option<(Bounds, Bounds)> {
    let pts = || lines.iter().flat_map(|l| l.points.iter());
    Some((
        Bounds::of(pts().map(|p| p[0]))?,
        Bounds::of(pts().map(|p| p[1]))?,
    ))
}

/// Pads both ranges by the same length, so that a body touching the frame
/// on one side does not on the other, and a degenerate direction (a
/// straight line) gets the other's extent.
pub(super) fn square_pad(bx: Bounds, by: Bounds) -> Result<(Bounds, Bounds)> {
    let span = bx.span().max(by.span());
    let (bx, by) = if span > 0.0 {
        let widen = |b: Bounds| {
            if b.span() < 1e-6 * span {
                Bounds {
                    lo: b.mid() - 0.05 * span,
                    hi: b.mid() + 0.05 * span,
                }
            } else {
                b
            }
        };
        (widen(bx), widen(by))
    } else {
        (bx.padded(0.0, "x range")?, by.padded(0.0, "y range")?)
    };
    let pad = 0.04 * bx.span().max(by.span());
    let grow = |b: Bounds, what: &str| {
        let g = Bounds {
            lo: b.lo - pad,
            hi: b.hi + pad,
        };
        g.padded(0.0, what)
    };
    Ok((grow(bx, "x range")?, grow(by, "y range")?))
}
