//! Tick positions and their labels: round values on linear axes, decades
//! and their multiples on logarithmic ones, as dense as the labels allow.

use super::bounds::Bounds;
use super::font::{text_size, TICK_SIZE};

/// Tick positions in plot coordinates (log10 of the value on a log axis),
/// with their labels.
#[derive(Clone, Debug, Default)]
pub(super) struct Ticks {
    pub(super) major: Vec<(f64, String)>,
    pub(super) minor: Vec<f64>,
}

impl Ticks {
    pub(super) fn label_of(&self, v: f64) -> String {
        let tol = 1e-9
            * self
                .major
                .iter()
                .fold(1e-300_f64, |m, (p, _)| m.max(p.abs()));
        self.major
            .iter()
            .min_by(|a, b| (a.0 - v).abs().total_cmp(&(b.0 - v).abs()))
            .filter(|(p, _)| (p - v).abs() <= tol.max(1e-12))
            .map(|(_, s)| s.clone())
            .unwrap_or_default()
    }

    pub(super) fn max_label_width(&self) -> i32 {
        self.major
            .iter()
            .map(|(_, s)| text_size(s, TICK_SIZE).0)
            .max()
            .unwrap_or(0)
    }

    /// The densest ticks (at most 10) whose labels do not crowd each other:
    /// neighbours at least a label's width apart plus a gap along x, two
    /// label heights along y. Spacing is checked pixel by pixel, because on
    /// a log axis 8, 9 and 10 sit much closer than 10, 20 and 50.
    pub(super) fn fitting(b: Bounds, log: bool, length: i32, horizontal: bool) -> Ticks {
        let mut max_n = 10;
        loop {
            let t = Ticks::new(b, log, max_n);
            if max_n <= 2 || t.labels_fit(b, length, horizontal) {
                return t;
            }
            max_n -= 1;
        }
    }

    fn labels_fit(&self, b: Bounds, length: i32, horizontal: bool) -> bool {
        let px = |p: f64| (p - b.lo) / b.span() * f64::from(length);
        let height = text_size("0", TICK_SIZE).1;
        self.major.windows(2).all(|w| {
            let need = if horizontal {
                (text_size(&w[0].1, TICK_SIZE).0 + text_size(&w[1].1, TICK_SIZE).0) / 2 + 24
            } else {
                2 * height + 8
            };
            (px(w[1].0) - px(w[0].0)).abs() >= f64::from(need)
        })
    }

    pub(super) fn new(b: Bounds, log: bool, max_n: usize) -> Ticks {
        if log {
            log_ticks(b, max_n)
        } else {
            let values = linear_tick_values(b.lo, b.hi, max_n);
            let labels = format_linear(&values.0, values.1);
            Ticks {
                major: values.0.into_iter().zip(labels).collect(),
                minor: Vec::new(),
            }
        }
    }
}

/// The smallest of 1, 2, 5 × 10^k that is at least `raw`.
fn nice_step(raw: f64) -> f64 {
    let e = raw.log10().floor();
    let base = 10f64.powf(e);
    [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .map(|m| m * base)
        .find(|&s| s >= raw * (1.0 - 1e-12))
        .unwrap_or(10.0 * base)
}

/// At most about `max_n` round values in `[lo, hi]`, and their spacing.
fn linear_tick_values(lo: f64, hi: f64, max_n: usize) -> (Vec<f64>, f64) {
    let span = hi - lo;
    if span.is_nan() || span <= 0.0 || !span.is_finite() {
        return (vec![lo], 1.0);
    }
    let step = nice_step(span / max_n.max(1) as f64);
    let first = (lo / step - 1e-9).ceil() as i64;
    let last = (hi / step + 1e-9).floor() as i64;
    // Bounds are padded and finite, so the count is small; the cap guards
    // against float pathologies producing a runaway loop.
    let values = (first..=last).take(100).map(|k| k as f64 * step).collect();
    (values, step)
}

fn superscript(n: i32) -> String {
    n.to_string()
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            '0' => '⁰',
            '1' => '¹',
            '2' => '²',
            '3' => '³',
            '4' => '⁴',
            '5' => '⁵',
            '6' => '⁶',
            '7' => '⁷',
            '8' => '⁸',
            '9' => '⁹',
            other => other,
        })
        .collect()
}

/// `s` with a leading hyphen-minus replaced by the typographic minus, as in
/// printed figures.
pub fn typographic_minus(s: String) -> String {
    match s.strip_prefix('-') {
        Some(rest) => format!("\u{2212}{rest}"),
        None => s,
    }
}

/// Labels for equally spaced ticks: plain decimals with as many digits as
/// the spacing needs, or `m×10ⁿ` when the numbers are very large or small.
fn format_linear(values: &[f64], step: f64) -> Vec<String> {
    let max_abs = values.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let step_exp = (step.log10() + 1e-9).floor() as i32;
    let zero = |v: f64| v.abs() < 1e-6 * step;
    if max_abs >= 1e5 || (max_abs > 0.0 && max_abs < 1e-3) {
        values
            .iter()
            .map(|&v| {
                if zero(v) {
                    return "0".to_string();
                }
                let mut e = v.abs().log10().floor() as i32;
                let digits = (e - step_exp).max(0) as usize;
                let mut m = v / 10f64.powi(e);
                let rounded: f64 = format!("{m:.digits$}").parse().unwrap_or(m);
                if rounded.abs() >= 10.0 {
                    e += 1;
                    m /= 10.0;
                }
                let digits = (e - step_exp).max(0) as usize;
                typographic_minus(format!("{m:.digits$}×10{}", superscript(e)))
            })
            .collect()
    } else {
        let digits = (-step_exp).max(0) as usize;
        values
            .iter()
            .map(|&v| {
                if zero(v) {
                    "0".to_string()
                } else {
                    typographic_minus(format!("{v:.digits$}"))
                }
            })
            .collect()
    }
}

/// Labels of log-axis ticks m·10^k: plain decimals ("0.02", "50") when every
/// value lies in [10⁻³, 10⁵), otherwise "10ᵏ" and "m×10ᵏ".
fn log_labels(ticks: &[(u32, i32)]) -> Vec<String> {
    let plain = ticks.iter().all(|&(_, k)| (-3..5).contains(&k));
    ticks
        .iter()
        .map(|&(m, k)| match (plain, m) {
            (true, _) => format!("{}", f64::from(m) * 10f64.powi(k)),
            (false, 1) => format!("10{}", superscript(k)),
            (false, _) => format!("{m}×10{}", superscript(k)),
        })
        .collect()
}

/// Ticks of a log axis whose bounds are given in decades (log10 units).
///
/// Labels the densest of these that gives at least two and at most `max_n`
/// labels: every multiple m·10ᵏ (m = 1…9), the 1-2-5 multiples, the
/// decades, every second (third, …) decade. The multiples not labelled
/// become grid lines while there are not too many of them. A range inside a
/// single step falls back to linear round values.
fn log_ticks(b: Bounds, max_n: usize) -> Ticks {
    let max_n = max_n.max(2);
    let inside = |p: f64| p >= b.lo - 1e-9 && p <= b.hi + 1e-9;
    let pos = |(m, k): (u32, i32)| k as f64 + f64::from(m).log10();
    let all: Vec<(u32, i32)> = ((b.lo.floor() as i32)..=(b.hi.ceil() as i32))
        .flat_map(|k| (1..10).map(move |m| (m, k)))
        .filter(|&t| inside(pos(t)))
        .collect();
    // Level 0: every multiple; 1: the 1-2-5 multiples; s + 1: every s-th decade.
    let labelled = |level: i32, (m, k): (u32, i32)| match level {
        0 => true,
        1 => matches!(m, 1 | 2 | 5),
        s => m == 1 && k.rem_euclid(s - 1) == 0,
    };
    let decades = all.iter().filter(|t| t.0 == 1).count() as i32;
    let level = (0..=decades.max(1) + 1).find(|&level| {
        let n = all.iter().filter(|&&t| labelled(level, t)).count();
        (2..=max_n).contains(&n)
    });
    if let Some(level) = level {
        let (major, rest): (Vec<_>, Vec<_>) =
            all.iter().copied().partition(|&t| labelled(level, t));
        // A few dozen grid lines at most: beyond that they grey the plot.
        let minor = if all.len() <= 120 {
            rest.into_iter().map(pos).collect()
        } else {
            rest.into_iter().filter(|t| t.0 == 1).map(pos).collect()
        };
        let labels = log_labels(&major);
        return Ticks {
            major: major.into_iter().map(pos).zip(labels).collect(),
            minor,
        };
    }
    let (values, step) = linear_tick_values(10f64.powf(b.lo), 10f64.powf(b.hi), max_n);
    let values: Vec<f64> = values.into_iter().filter(|&v| v > 0.0).collect();
    let labels = format_linear(&values, step);
    Ticks {
        major: values.iter().map(|v| v.log10()).zip(labels).collect(),
        minor: Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_steps() {
        assert_eq!(nice_step(0.3), 0.5);
        assert_eq!(nice_step(1.0), 1.0);
        assert_eq!(nice_step(1.1), 2.0);
        assert_eq!(nice_step(7.0), 10.0);
    }

    #[test]
    fn linear_labels_use_the_digits_of_the_step() {
        let (v, s) = linear_tick_values(-0.05, 1.05, 6);
        assert_eq!(
            format_linear(&v, s),
            ["0", "0.2", "0.4", "0.6", "0.8", "1.0"]
        );
        let (v, s) = linear_tick_values(0.0, 3e-5, 3);
        assert_eq!(format_linear(&v, s), ["0", "1×10⁻⁵", "2×10⁻⁵", "3×10⁻⁵"]);
        let (v, s) = linear_tick_values(-250.0, 250.0, 5);
        assert_eq!(
            format_linear(&v, s),
            ["\u{2212}200", "\u{2212}100", "0", "100", "200"]
        );
    }

    fn labels(t: &Ticks) -> Vec<&str> {
        t.major.iter().map(|(_, s)| s.as_str()).collect()
    }

    #[test]
    fn log_labels_are_powers_of_ten() {
        let t = log_ticks(Bounds { lo: -12.3, hi: 0.2 }, 8);
        assert_eq!(
            labels(&t),
            ["10⁻¹²", "10⁻¹⁰", "10⁻⁸", "10⁻⁶", "10⁻⁴", "10⁻²", "10⁰"]
        );
        let narrow = log_ticks(Bounds { lo: 0.1, hi: 0.9 }, 8);
        assert!(narrow.major.len() >= 2);
        let tiny = log_ticks(
            Bounds {
                lo: 0.301,
                hi: 0.32,
            },
            8,
        );
        assert!(tiny.major.len() >= 2, "{tiny:?}");
    }

    /// An axis over 2…128 elements (log10 0.2…2.2 with padding) is labelled
    /// 1-2-5, not just at 10 and 100; over 8…64 the labels do not run into
    /// each other (they once read "8×10⁰9×10⁰10¹").
    #[test]
    fn short_log_ranges_label_sub_decades_that_fit() {
        let b = Bounds { lo: 0.2, hi: 2.2 };
        let t = Ticks::fitting(b, true, 640, true);
        assert_eq!(labels(&t), ["2", "5", "10", "20", "50", "100"]);
        let b = Bounds {
            lo: 8f64.log10() - 0.05,
            hi: 64f64.log10() + 0.05,
        };
        let t = Ticks::fitting(b, true, 640, true);
        assert!(t.labels_fit(b, 640, true), "{t:?}");
        assert_eq!(labels(&t), ["10", "20", "50"]);
        // Vertical axes need more room per label, so fewer labels.
        let t = Ticks::fitting(Bounds { lo: -3.1, hi: 0.1 }, true, 300, false);
        assert_eq!(labels(&t), ["0.001", "0.01", "0.1", "1"]);
        let t = Ticks::fitting(Bounds { lo: -6.1, hi: -4.9 }, true, 600, false);
        assert_eq!(labels(&t), ["10⁻⁶", "2×10⁻⁶", "5×10⁻⁶", "10⁻⁵"]);
    }
}
