//! Gauss–Legendre quadrature on [a, b].

/// Nodes and weights of the n-point Gauss–Legendre rule on [-1, 1], by
/// Newton iteration on the Legendre polynomial from Chebyshev guesses.
pub fn gauss_legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
    assert!(n >= 1, "a Gauss rule needs at least one point");
    let mut x = vec![0.0; n];
    let mut w = vec![0.0; n];
    for i in 0..n.div_ceil(2) {
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 0.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, z);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * z * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            let pn = if n == 1 { z } else { p1 };
            let pn1 = if n == 1 { 1.0 } else { p0 };
            dp = n as f64 * (z * pn - pn1) / (z * z - 1.0);
            let dz = pn / dp;
            z -= dz;
            if dz.abs() < 1e-16 {
                break;
            }
        }
        if n == 1 {
            dp = 1.0;
            z = 0.0;
        }
        x[i] = -z;
        x[n - 1 - i] = z;
        let wi = if n == 1 {
            2.0
        } else {
            2.0 / ((1.0 - z * z) * dp * dp)
        };
        w[i] = wi;
        w[n - 1 - i] = wi;
    }
    (x, w)
}

/// The rules the spaces use (up to 30 points per direction), each computed
/// once: assembly asks for the same rule on every element, and the Newton
/// iteration behind it was a few per cent of assembling a small mesh.
const CACHED: usize = 32;

fn cached_rule(n: usize) -> Option<&'static (Vec<f64>, Vec<f64>)> {
    static RULES: std::sync::OnceLock<Vec<(Vec<f64>, Vec<f64>)>> = std::sync::OnceLock::new();
    let rules = RULES.get_or_init(|| (1..=CACHED).map(gauss_legendre).collect());
    (1..=CACHED).contains(&n).then(|| &rules[n - 1])
}

/// A rule mapped to [a, b].
pub fn on_interval(n: usize, a: f64, b: f64) -> Vec<(f64, f64)> {
    let computed;
    let (x, w) = match cached_rule(n) {
        Some(rule) => rule,
        None => {
            computed = gauss_legendre(n);
            &computed
        }
    };
    let h = 0.5 * (b - a);
    x.iter()
        .zip(w.iter())
        .map(|(xi, wi)| (a + h * (xi + 1.0), h * wi))
        .collect()
}
