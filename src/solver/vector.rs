//! The few vector operations the solvers share, on plain slices (the
//! iterates live in the body's or the layer's coordinates, never in a
//! matrix type).

pub(crate) fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Signed displacement component of largest magnitude.
pub(crate) fn max_displacement(full: &[f64]) -> f64 {
    full.iter()
        .copied()
        .fold(0.0, |m: f64, v| if v.abs() > m.abs() { v } else { m })
}
