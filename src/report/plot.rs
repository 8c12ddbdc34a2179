//! The paper's figures: line charts (convergence histories, contact
//! pressures), geometry drawings (meshes, control nets) and filled scalar
//! fields (stresses on the deformed body).
//!
//! Every figure is an SVG file by default and a PNG file when the path ends in
//! `.png`. Output is deterministic: identical input gives identical bytes, so
//! figures can be committed and diffed. Files are written atomically, and all
//! input is validated before anything is drawn, so an error never leaves a
//! half-written or misleading figure behind.
//!
//! Layout is computed here rather than left to plotters' defaults: the label
//! areas are sized from the measured tick labels, the legend sits in its own
//! strip between title and plot (so it can never hide data), and geometry is
//! drawn with an equal aspect ratio by sizing the figure to the body.
//!
//! ```no_run
//! use iga_contact::report::plot::{line_chart, Axes, Series};
//! let axes = Axes {
//!     title: "Convergence".into(),
//!     x_label: "iteration".into(),
//!     y_label: "relative residual".into(),
//!     log_x: false,
//!     log_y: true,
//! };
//! let history = Series::line("BFGS", vec![(0.0, 1.0), (1.0, 1e-3), (2.0, 1e-8)]).with_markers();
//! line_chart("convergence.svg", &axes, &[history])?;
//! # Ok::<(), iga_contact::error::Error>(())
//! ```

use crate::error::{Error, Result};
use crate::report::atomic::write_atomic;
use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;
use std::sync::Once;

// ---------------------------------------------------------------------------
// Public API
// ---------------------------------------------------------------------------

/// One curve of a [`line_chart`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Series {
    /// Legend text; an empty label keeps the series out of the legend.
    pub label: String,
    pub points: Vec<(f64, f64)>,
    /// Draw a marker at every point (the shape cycles with the series index,
    /// so curves stay distinguishable in greyscale print).
    pub markers: bool,
    pub stroke: Stroke,
    /// Index into the palette; `None`: the series index, so that each curve
    /// has its own colour. Curves that belong together (one degree's two
    /// errors and its reference slopes) share one.
    pub color: Option<usize>,
    /// Marker shape; `None`: the series index.
    pub shape: Option<usize>,
}

/// How a [`Series`] is stroked: data solid, guides dashed or dotted, so
/// that measured curves and reference lines cannot be mistaken for each
/// other.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Stroke {
    #[default]
    Solid,
    Dashed,
    Dotted,
}

impl Stroke {
    /// Dash and gap lengths in pixels, for the dashed kinds.
    fn pattern(self) -> Option<(u32, u32)> {
        match self {
            Stroke::Solid => None,
            Stroke::Dashed => Some((8, 5)),
            Stroke::Dotted => Some((2, 4)),
        }
    }
}

impl Series {
    /// A solid line without markers.
    pub fn line(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            label: label.into(),
            points,
            markers: false,
            stroke: Stroke::Solid,
            color: None,
            shape: None,
        }
    }

    pub fn with_markers(mut self) -> Self {
        self.markers = true;
        self
    }

    pub fn dashed(mut self) -> Self {
        self.stroke = Stroke::Dashed;
        self
    }

    pub fn dotted(mut self) -> Self {
        self.stroke = Stroke::Dotted;
        self
    }

    pub fn colored(mut self, palette_index: usize) -> Self {
        self.color = Some(palette_index);
        self
    }

    /// Markers of the given shape.
    pub fn with_shape(mut self, shape: usize) -> Self {
        self.markers = true;
        self.shape = Some(shape);
        self
    }
}

/// Titles and scales of a [`line_chart`].
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Axes {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub log_x: bool,
    pub log_y: bool,
}

/// How a [`Polyline`] is stroked.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum LineKind {
    /// 2 px solid: body outlines, element boundaries of coarse meshes.
    #[default]
    Solid,
    /// 2 px dashed: reference or undeformed configurations.
    Dashed,
    /// 1 px dashed with a marker at every point: NURBS control polygons.
    ControlNet,
    /// 1 px solid: dense meshes and overlays on a field, where 2 px lines
    /// would hide what they sit on.
    Thin,
}

/// A polyline of a [`geometry_figure`] or an overlay of a [`field_figure`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Polyline {
    pub points: Vec<[f64; 2]>,
    pub style: LineKind,
    /// Index into [`PALETTE`] (taken modulo its length).
    pub color: usize,
    /// Legend text. Polylines sharing a label share one legend entry (the
    /// first one's style), so every element boundary can carry "elements".
    pub label: Option<String>,
}

impl Polyline {
    pub fn new(points: Vec<[f64; 2]>, style: LineKind, color: usize) -> Self {
        Polyline {
            points,
            style,
            color,
            label: None,
        }
    }

    pub fn labelled(mut self, label: impl Into<String>) -> Self {
        self.label = Some(label.into());
        self
    }
}

/// One quadrilateral of a [`field_figure`]: corners in cyclic order (either
/// orientation) and the value it is filled with.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FieldCell {
    pub corners: [[f64; 2]; 4],
    pub value: f64,
}

impl FieldCell {
    /// A cell whose colour is the mean of its four corner values.
    pub fn from_corner_values(corners: [[f64; 2]; 4], values: [f64; 4]) -> Self {
        FieldCell {
            corners,
            value: values.iter().sum::<f64>() / 4.0,
        }
    }
}

/// Colours addressed by [`Polyline::color`]: the ten "tab10" colours (series
/// of a line chart use them in order), then black (index 10) and white (11).
pub const PALETTE: [(u8, u8, u8); 12] = [
    (0x1f, 0x77, 0xb4),
    (0xff, 0x7f, 0x0e),
    (0x2c, 0xa0, 0x2c),
    (0xd6, 0x27, 0x28),
    (0x94, 0x67, 0xbd),
    (0x8c, 0x56, 0x4b),
    (0xe3, 0x77, 0xc2),
    (0x7f, 0x7f, 0x7f),
    (0xbc, 0xbd, 0x22),
    (0x17, 0xbe, 0xcf),
    (0x00, 0x00, 0x00),
    (0xff, 0xff, 0xff),
];

/// Palette index of black.
pub const BLACK_INDEX: usize = 10;
/// Palette index of white.
pub const WHITE_INDEX: usize = 11;

/// Line chart of several series, with a legend and an automatic range with a
/// small margin. On a logarithmic axis non-positive values are left out and
/// the curve is broken there rather than joined across the gap.
pub fn line_chart(path: impl AsRef<Path>, axes: &Axes, series: &[Series]) -> Result<()> {
    let fig = LineChart::new(axes, series)?;
    render(path.as_ref(), &fig)
}

/// A drawing of geometry with equal aspect ratio; the figure's height follows
/// the body's proportions (within limits).
pub fn geometry_figure(path: impl AsRef<Path>, title: &str, lines: &[Polyline]) -> Result<()> {
    let fig = GeometryFigure::new(title, lines)?;
    render(path.as_ref(), &fig)
}

/// A scalar field filled on quadrilateral cells (equal aspect ratio) with a
/// viridis colour bar labelled `colorbar_label`, and polylines drawn on top.
pub fn field_figure(
    path: impl AsRef<Path>,
    title: &str,
    colorbar_label: &str,
    cells: &[FieldCell],
    overlay: &[Polyline],
) -> Result<()> {
    let fig = FieldFigure::new(title, colorbar_label, cells, overlay)?;
    render(path.as_ref(), &fig)
}

/// The viridis colour of `t` in `[0, 1]` (clamped; NaN maps to the low end).
pub fn viridis(t: f64) -> (u8, u8, u8) {
    // Matplotlib's viridis sampled at tenths: close enough to the original
    // for a colour bar, and small enough to keep by hand.
    const STOPS: [(u8, u8, u8); 11] = [
        (0x44, 0x01, 0x54),
        (0x48, 0x24, 0x75),
        (0x41, 0x44, 0x87),
        (0x35, 0x5f, 0x8d),
        (0x2a, 0x78, 0x8e),
        (0x21, 0x91, 0x8c),
        (0x22, 0xa8, 0x84),
        (0x44, 0xbf, 0x70),
        (0x7a, 0xd1, 0x51),
        (0xbd, 0xdf, 0x26),
        (0xfd, 0xe7, 0x25),
    ];
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let s = t * 10.0;
    let i = (s.floor() as usize).min(9);
    let f = s - i as f64;
    let lerp = |a: u8, b: u8| (a as f64 + (b as f64 - a as f64) * f).round() as u8;
    let (a, b) = (STOPS[i], STOPS[i + 1]);
    (lerp(a.0, b.0), lerp(a.1, b.1), lerp(a.2, b.2))
}

// ---------------------------------------------------------------------------
// Fonts, colours, sizes
// ---------------------------------------------------------------------------

/// Layout is measured with the bundled DejaVu Sans; naming it first in the
/// SVG makes viewers that have it reproduce that layout exactly, while the
/// generic fallback keeps the text sans-serif elsewhere.
const FAMILY: &str = "DejaVu Sans, sans-serif";

const TITLE_SIZE: f64 = 24.0;
const DESC_SIZE: f64 = 20.0;
const TICK_SIZE: f64 = 17.0;
const LEGEND_SIZE: f64 = 17.0;

const WIDTH: u32 = 800;
const LINE_CHART_HEIGHT: u32 = 600;
const PAD: i32 = 12;
/// Room right of the plot for half of the last x tick label.
const RIGHT_PAD: i32 = 30;
const TICK_MARK: i32 = 5;

const LEGEND_SAMPLE: i32 = 36;
const LEGEND_GAP: i32 = 8;
const LEGEND_SPACING: i32 = 26;
const LEGEND_ROW: i32 = 24;

/// Bounds of the plot height of equal-aspect figures: a slender body should
/// not produce a ribbon nor a tower.
const MIN_PLOT_HEIGHT: i32 = 240;
const MAX_PLOT_HEIGHT: i32 = 620;

const GRID_MAJOR: RGBColor = RGBColor(0xdd, 0xdd, 0xdd);
const GRID_MINOR: RGBColor = RGBColor(0xf0, 0xf0, 0xf0);

static FONTS: Once = Once::new();

fn ensure_fonts() {
    FONTS.call_once(|| {
        // The bundled font is known to parse; were it to fail, the first text
        // would report FontUnavailable, which surfaces as an ordinary Err.
        for family in [FAMILY, "sans-serif"] {
            let _ =
                plotters::style::register_font(family, FontStyle::Normal, dejavu::sans::regular());
            let _ = plotters::style::register_font(family, FontStyle::Bold, dejavu::sans::bold());
        }
    });
}

/// Every measurement and every text goes through here, so the fonts are
/// registered before the first layout, not just before the first drawing.
fn font(size: f64) -> FontDesc<'static> {
    ensure_fonts();
    FontDesc::new(FontFamily::Name(FAMILY), size, FontStyle::Normal)
}

fn text_size(text: &str, size: f64) -> (i32, i32) {
    // Layout is measured before `render` runs, so the fonts must be
    // registered here too: otherwise the first figure of a process is laid
    // out with zero-width text. A zero estimate for an unmeasurable string
    // would merely make a label area tight, so it is no reason to fail.
    ensure_fonts();
    font(size)
        .box_size(text)
        .map(|(w, h)| (w as i32, h as i32))
        .unwrap_or((0, size as i32))
}

fn palette(index: usize) -> RGBColor {
    let (r, g, b) = PALETTE[index % PALETTE.len()];
    RGBColor(r, g, b)
}

// ---------------------------------------------------------------------------
// Validation and ranges
// ---------------------------------------------------------------------------

fn check_finite(field: impl FnOnce() -> String, value: f64) -> Result<()> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(Error::invalid(field(), value, "must be a finite number"))
    }
}

fn check_polylines(what: &str, lines: &[Polyline]) -> Result<()> {
    for (i, line) in lines.iter().enumerate() {
        for (j, p) in line.points.iter().enumerate() {
            for (k, &v) in p.iter().enumerate() {
                check_finite(|| format!("{what}[{i}].points[{j}][{k}]"), v)?;
            }
        }
    }
    Ok(())
}

#[derive(Clone, Copy, Debug)]
struct Bounds {
    lo: f64,
    hi: f64,
}

impl Bounds {
    fn of(values: impl IntoIterator<Item = f64>) -> Option<Bounds> {
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
    /// gets a width of its own so that it still maps onto the plot.
    fn padded(self, fraction: f64, what: &str) -> Result<Bounds> {
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

    fn span(self) -> f64 {
        self.hi - self.lo
    }

    fn mid(self) -> f64 {
        0.5 * (self.lo + self.hi)
    }
}

// ---------------------------------------------------------------------------
// Ticks and their labels
// ---------------------------------------------------------------------------

/// Tick positions in plot coordinates (log10 of the value on a log axis),
/// with their labels.
#[derive(Clone, Debug, Default)]
struct Ticks {
    major: Vec<(f64, String)>,
    minor: Vec<f64>,
}

impl Ticks {
    fn label_of(&self, v: f64) -> String {
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

    fn max_label_width(&self) -> i32 {
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
    fn fitting(b: Bounds, log: bool, length: i32, horizontal: bool) -> Ticks {
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

    fn new(b: Bounds, log: bool, max_n: usize) -> Ticks {
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

/// Typographic minus, as in printed figures.
fn minus(s: String) -> String {
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
                minus(format!("{m:.digits$}×10{}", superscript(e)))
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
                    minus(format!("{v:.digits$}"))
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

// ---------------------------------------------------------------------------
// Legend
// ---------------------------------------------------------------------------

#[derive(Clone, Debug)]
struct LegendEntry {
    label: String,
    color: RGBColor,
    width: u32,
    stroke: Stroke,
    marker: Option<usize>,
}

impl LegendEntry {
    fn extent(&self) -> i32 {
        LEGEND_SAMPLE + LEGEND_GAP + text_size(&self.label, LEGEND_SIZE).0
    }
}

/// Entries broken into rows no wider than `width`.
fn legend_rows(entries: &[LegendEntry], width: i32) -> Vec<Vec<usize>> {
    let mut rows: Vec<Vec<usize>> = Vec::new();
    let mut used = 0;
    for (i, e) in entries.iter().enumerate() {
        let w = e.extent();
        match rows.last_mut() {
            Some(row) if used + LEGEND_SPACING + w <= width => {
                row.push(i);
                used += LEGEND_SPACING + w;
            }
            _ => {
                rows.push(vec![i]);
                used = w;
            }
        }
    }
    rows
}

fn polyline_legend(lines: &[Polyline]) -> Vec<LegendEntry> {
    let mut entries: Vec<LegendEntry> = Vec::new();
    for line in lines {
        let Some(label) = line.label.as_ref().filter(|l| !l.is_empty()) else {
            continue;
        };
        if entries.iter().any(|e| &e.label == label) {
            continue;
        }
        let (width, dashed, marker) = stroke_of(line.style);
        entries.push(LegendEntry {
            label: label.clone(),
            color: palette(line.color),
            width,
            stroke: if dashed {
                Stroke::Dashed
            } else {
                Stroke::Solid
            },
            marker: marker.then_some(0),
        });
    }
    entries
}

/// Stroke width, dashing and markers of a line kind.
fn stroke_of(kind: LineKind) -> (u32, bool, bool) {
    match kind {
        LineKind::Solid => (2, false, false),
        LineKind::Dashed => (2, true, false),
        LineKind::ControlNet => (1, true, true),
        LineKind::Thin => (1, false, false),
    }
}

// ---------------------------------------------------------------------------
// Layout
// ---------------------------------------------------------------------------

/// Pixel layout of a figure: title, legend strip, one plot with its label
/// areas, and optionally a colour bar to the right.
#[derive(Clone, Debug)]
struct Frame {
    size: (u32, u32),
    title: String,
    legend: Vec<LegendEntry>,
    rows: Vec<Vec<usize>>,
    legend_top: i32,
    /// Plot area: left, top, width, height.
    plot: (i32, i32, i32, i32),
    y_area: i32,
    x_area: i32,
    x_desc: String,
    y_desc: String,
    x_ticks: Ticks,
    y_ticks: Ticks,
    x_range: Bounds,
    y_range: Bounds,
}

/// Height of everything above the plot for a given legend.
fn header_height(title: &str, rows: usize) -> (i32, i32) {
    let title_h = text_size(title, TITLE_SIZE).1.max(TITLE_SIZE as i32);
    let legend_top = PAD + title_h + 10;
    let legend_h = if rows > 0 {
        rows as i32 * LEGEND_ROW + 6
    } else {
        0
    };
    // The top y tick label is centred on the plot's upper edge.
    (legend_top, legend_top + legend_h + TICK_SIZE as i32 / 2 + 4)
}

fn y_area_width(ticks: &Ticks, desc: &str) -> i32 {
    let desc_h = if desc.is_empty() {
        0
    } else {
        text_size(desc, DESC_SIZE).1 + 10
    };
    PAD / 2 + desc_h + ticks.max_label_width() + 2 * TICK_MARK + 4
}

fn x_area_height(desc: &str) -> i32 {
    let desc_h = if desc.is_empty() {
        0
    } else {
        text_size(desc, DESC_SIZE).1 + 8
    };
    2 * TICK_MARK + text_size("0", TICK_SIZE).1 + 6 + desc_h
}

impl Frame {
    /// A plot filling a fixed-size figure.
    #[allow(clippy::too_many_arguments)]
    fn fixed(
        size: (u32, u32),
        title: &str,
        legend: Vec<LegendEntry>,
        x_desc: &str,
        y_desc: &str,
        x_range: Bounds,
        y_range: Bounds,
        log: (bool, bool),
    ) -> Frame {
        let x_area = x_area_height(x_desc);
        // The y ticks depend on the plot height, which depends on the legend
        // rows, which depend on the plot width, which depends on the y ticks:
        // a guess of the height converges in one more pass.
        let mut plot_h = size.1 as i32 * 3 / 4;
        let mut frame = None;
        for _ in 0..3 {
            let y_ticks = Ticks::fitting(y_range, log.1, plot_h, false);
            let y_area = y_area_width(&y_ticks, y_desc);
            let left = PAD + y_area;
            let plot_w = size.0 as i32 - left - RIGHT_PAD;
            let rows = legend_rows(&legend, plot_w);
            let (legend_top, top) = header_height(title, rows.len());
            let new_h = size.1 as i32 - top - x_area - PAD;
            let x_ticks = Ticks::fitting(x_range, log.0, plot_w, true);
            let converged = new_h == plot_h;
            plot_h = new_h;
            frame = Some(Frame {
                size,
                title: title.to_string(),
                legend: legend.clone(),
                rows,
                legend_top,
                plot: (left, top, plot_w, new_h),
                y_area,
                x_area,
                x_desc: x_desc.to_string(),
                y_desc: y_desc.to_string(),
                x_ticks,
                y_ticks,
                x_range,
                y_range,
            });
            if converged {
                break;
            }
        }
        frame.expect("the layout loop runs at least once")
    }

    /// A plot whose data ranges are widened so that one unit has the same
    /// length along x and y; the figure height adapts to the data's aspect.
    fn equal_aspect(
        width: u32,
        right_reserve: i32,
        title: &str,
        legend: Vec<LegendEntry>,
        data_x: Bounds,
        data_y: Bounds,
    ) -> Frame {
        // every geometry and field figure is drawn in the crate's SI units
        let (x_desc, y_desc) = ("x (m)", "y (m)");
        let x_area = x_area_height(x_desc);
        let mut y_range = data_y;
        let mut frame: Option<Frame> = None;
        // Tick labels set the label-area width, which sets the plot width,
        // which sets the ranges, which set the tick labels: iterate to a fixed
        // point (two passes almost always suffice).
        for _ in 0..4 {
            let y_guess = Ticks::new(y_range, false, 8);
            let y_area = y_area_width(&y_guess, y_desc);
            let left = PAD + y_area;
            let plot_w = width as i32 - left - RIGHT_PAD - right_reserve;
            let rows = legend_rows(&legend, plot_w);
            let (legend_top, top) = header_height(title, rows.len());
            let ideal_h = plot_w as f64 * data_y.span() / data_x.span();
            let plot_h = (ideal_h.round() as i32).clamp(MIN_PLOT_HEIGHT, MAX_PLOT_HEIGHT);
            let scale = (plot_w as f64 / data_x.span()).min(plot_h as f64 / data_y.span());
            let half_x = 0.5 * plot_w as f64 / scale;
            let half_y = 0.5 * plot_h as f64 / scale;
            let x_range = Bounds {
                lo: data_x.mid() - half_x,
                hi: data_x.mid() + half_x,
            };
            let new_y = Bounds {
                lo: data_y.mid() - half_y,
                hi: data_y.mid() + half_y,
            };
            let x_ticks = Ticks::fitting(x_range, false, plot_w, true);
            let y_ticks = Ticks::fitting(new_y, false, plot_h, false);
            let stable = y_area_width(&y_ticks, y_desc) == y_area;
            let height = top + plot_h + x_area + PAD;
            y_range = new_y;
            frame = Some(Frame {
                size: (width, height as u32),
                title: title.to_string(),
                legend: legend.clone(),
                rows,
                legend_top,
                plot: (left, top, plot_w, plot_h),
                y_area,
                x_area,
                x_desc: x_desc.to_string(),
                y_desc: y_desc.to_string(),
                x_ticks,
                y_ticks,
                x_range,
                y_range,
            });
            if stable {
                break;
            }
        }
        frame.expect("the layout loop runs at least once")
    }
}

// ---------------------------------------------------------------------------
// Rendering
// ---------------------------------------------------------------------------

type DrawResult<T, DB> =
    std::result::Result<T, DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;
type Coords = Cartesian2d<TickAxis, TickAxis>;

/// A linear axis whose grid lines are exactly the precomputed ticks.
///
/// plotters' own key-point wrapper drops the value formatter of `f64` axes,
/// and its log axis finds no ticks inside a single decade; owning the axis
/// sidesteps both (log axes are linear axes over log10 of the data).
struct TickAxis {
    linear: RangedCoordf64,
    range: Bounds,
    major: Vec<f64>,
    minor: Vec<f64>,
}

impl TickAxis {
    fn new(range: Bounds, ticks: &Ticks) -> TickAxis {
        TickAxis {
            linear: (range.lo..range.hi).into(),
            range,
            major: ticks.major.iter().map(|(p, _)| *p).collect(),
            minor: ticks.minor.clone(),
        }
    }
}

impl Ranged for TickAxis {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        self.linear.map(value, limit)
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            self.minor.clone()
        } else {
            self.major.clone()
        }
    }

    fn range(&self) -> std::ops::Range<f64> {
        self.range.lo..self.range.hi
    }
}

/// A validated figure, ready to be drawn on any backend.
trait Figure {
    fn frame(&self) -> &Frame;
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<(), DB>;
}

fn render(path: &Path, fig: &impl Figure) -> Result<()> {
    ensure_fonts();
    let size = fig.frame().size;
    let failed = |e: String| Error::Io {
        path: path.display().to_string(),
        source: std::io::Error::other(format!("drawing the figure failed: {e}")),
    };
    let png = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !png {
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
            fig.draw(&root).map_err(|e| failed(e.to_string()))?;
            root.present().map_err(|e| failed(e.to_string()))?;
        }
        // plotters escapes markup but passes control characters through,
        // which no XML reader accepts.
        return write_atomic(path, crate::report::xml_safe(&svg).as_bytes());
    }
    // The bitmap backend can only encode to a file; render next to the target
    // and move the bytes through write_atomic like every other output.
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    // Threads of one process may render the same target concurrently.
    static RENDERS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = RENDERS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let tmp = path.with_file_name(format!(".{name}.{}.{n}.render.png", std::process::id()));
    if let Some(dir) = tmp.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|source| Error::Io {
            path: dir.display().to_string(),
            source,
        })?;
    }
    let drawn = (|| {
        let root = BitMapBackend::new(&tmp, size).into_drawing_area();
        fig.draw(&root).map_err(|e| failed(e.to_string()))?;
        root.present().map_err(|e| failed(e.to_string()))
    })();
    let bytes = drawn.and_then(|()| {
        std::fs::read(&tmp).map_err(|source| Error::Io {
            path: tmp.display().to_string(),
            source,
        })
    });
    let _ = std::fs::remove_file(&tmp);
    write_atomic(path, &bytes?)
}

fn draw_header<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    frame: &Frame,
) -> DrawResult<(), DB> {
    root.fill(&WHITE)?;
    let (left, _, plot_w, _) = frame.plot;
    let centre = left + plot_w / 2;
    let style = font(TITLE_SIZE)
        .color(&BLACK)
        .pos(Pos::new(HPos::Center, VPos::Top));
    root.draw(&Text::new(frame.title.clone(), (centre, PAD), style))?;
    for (r, row) in frame.rows.iter().enumerate() {
        let extent: i32 = row.iter().map(|&i| frame.legend[i].extent()).sum::<i32>()
            + LEGEND_SPACING * (row.len() as i32 - 1);
        let y = frame.legend_top + r as i32 * LEGEND_ROW + LEGEND_ROW / 2;
        let mut x = centre - extent / 2;
        for &i in row {
            let e = &frame.legend[i];
            let style = ShapeStyle::from(&e.color).stroke_width(e.width);
            let RGBColor(r, g, b) = e.color;
            if 0.2126 * r as f64 + 0.7152 * g as f64 + 0.0722 * b as f64 > 200.0 {
                // A white overlay line would vanish against the page; show
                // it on a grey swatch, as it appears on the field.
                root.draw(&Rectangle::new(
                    [(x - 3, y - 7), (x + LEGEND_SAMPLE + 3, y + 7)],
                    RGBColor(0x90, 0x90, 0x90).filled(),
                ))?;
            }
            let ends = vec![(x, y), (x + LEGEND_SAMPLE, y)];
            // the legend's samples are short, so their dashes are too
            let pattern = match e.stroke {
                Stroke::Solid => None,
                Stroke::Dashed => Some((6, 4)),
                Stroke::Dotted => Some((2, 3)),
            };
            if let Some((dash, gap)) = pattern {
                root.draw(&DashedPathElement::new(ends, dash, gap, style))?;
            } else {
                root.draw(&PathElement::new(ends, style))?;
            }
            if let Some(m) = e.marker {
                root.draw(&Polygon::new(
                    marker_outline(m)
                        .into_iter()
                        .map(|(dx, dy)| (x + LEGEND_SAMPLE / 2 + dx, y + dy))
                        .collect::<Vec<_>>(),
                    e.color.filled(),
                ))?;
            }
            let text = font(LEGEND_SIZE)
                .color(&BLACK)
                .pos(Pos::new(HPos::Left, VPos::Center));
            root.draw(&Text::new(
                e.label.clone(),
                (x + LEGEND_SAMPLE + LEGEND_GAP, y),
                text,
            ))?;
            x += e.extent() + LEGEND_SPACING;
        }
    }
    Ok(())
}

/// The plot area together with its label areas.
fn chart_region<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    frame: &Frame,
) -> DrawingArea<DB, Shift> {
    let (left, top, w, h) = frame.plot;
    root.clone().shrink(
        (left - frame.y_area, top),
        ((w + frame.y_area) as u32, (h + frame.x_area) as u32),
    )
}

/// The axes and grid of the plot; returns the chart to draw into.
fn draw_axes<'a, DB: DrawingBackend>(
    region: &'a DrawingArea<DB, Shift>,
    frame: &Frame,
    grid: bool,
) -> DrawResult<ChartContext<'a, DB, Coords>, DB> {
    let mut chart = ChartBuilder::on(region)
        .x_label_area_size(frame.x_area)
        .y_label_area_size(frame.y_area)
        .build_cartesian_2d(
            TickAxis::new(frame.x_range, &frame.x_ticks),
            TickAxis::new(frame.y_range, &frame.y_ticks),
        )?;
    let x_fmt = |v: &f64| frame.x_ticks.label_of(*v);
    let y_fmt = |v: &f64| frame.y_ticks.label_of(*v);
    let mut mesh = chart.configure_mesh();
    mesh.x_label_formatter(&x_fmt)
        .y_label_formatter(&y_fmt)
        .label_style(font(TICK_SIZE).color(&BLACK))
        .axis_desc_style(font(DESC_SIZE).color(&BLACK))
        .bold_line_style(GRID_MAJOR)
        .light_line_style(GRID_MINOR)
        .axis_style(BLACK)
        .set_all_tick_mark_size(TICK_MARK);
    if !frame.x_desc.is_empty() {
        mesh.x_desc(frame.x_desc.clone());
    }
    if !frame.y_desc.is_empty() {
        mesh.y_desc(frame.y_desc.clone());
    }
    if !grid {
        // A field covers the grid anyway, and it would show through gaps
        // between cells as stray lines.
        mesh.disable_mesh();
    }
    mesh.draw()?;
    Ok(chart)
}

/// A frame around the plot area, drawn last so that cells do not cover it.
fn draw_box<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    frame: &Frame,
) -> DrawResult<(), DB> {
    let (left, top, w, h) = frame.plot;
    root.draw(&Rectangle::new(
        [(left, top), (left + w - 1, top + h - 1)],
        BLACK.stroke_width(1),
    ))
}

/// Pixel outline of a marker; `shape` cycles through circle, square,
/// triangle, diamond and inverted triangle. All are polygons so that one
/// element type serves every shape (a 12-gon is a circle to the eye).
fn marker_outline(shape: usize) -> Vec<(i32, i32)> {
    let s = 4;
    match shape % 5 {
        0 => (0..12)
            .map(|k| {
                let a = k as f64 * std::f64::consts::PI / 6.0;
                (
                    (4.5 * a.cos()).round() as i32,
                    (4.5 * a.sin()).round() as i32,
                )
            })
            .collect(),
        1 => vec![(-s, -s), (s, -s), (s, s), (-s, s)],
        2 => vec![(0, -s - 1), (s + 1, s), (-s - 1, s)],
        3 => vec![(0, -s - 2), (s + 1, 0), (0, s + 2), (-s - 1, 0)],
        _ => vec![(0, s + 1), (s + 1, -s), (-s - 1, -s)],
    }
}

fn draw_polylines<DB: DrawingBackend>(
    chart: &mut ChartContext<'_, DB, Coords>,
    lines: &[Polyline],
) -> DrawResult<(), DB> {
    for line in lines {
        let (width, dashed, markers) = stroke_of(line.style);
        let color = palette(line.color);
        let style = ShapeStyle::from(&color).stroke_width(width);
        let pts: Vec<(f64, f64)> = line.points.iter().map(|p| (p[0], p[1])).collect();
        if dashed {
            chart.draw_series(DashedLineSeries::new(pts.clone(), 6, 4, style))?;
        } else {
            chart.draw_series(LineSeries::new(pts.clone(), style))?;
        }
        if markers {
            let outline = marker_outline(0);
            chart
                .draw_series(pts.into_iter().map(|p| {
                    EmptyElement::at(p) + Polygon::new(outline.clone(), color.filled())
                }))?;
        }
    }
    Ok(())
}

// ---------------------------------------------------------------------------
// Line chart
// ---------------------------------------------------------------------------

struct LineChart {
    frame: Frame,
    /// Per series: its connected runs, in plot coordinates.
    runs: Vec<Vec<Vec<(f64, f64)>>>,
    series: Vec<Series>,
}

impl LineChart {
    fn new(axes: &Axes, series: &[Series]) -> Result<LineChart> {
        if series.is_empty() {
            return Err(Error::invalid(
                "series",
                "[]",
                "a line chart needs at least one series",
            ));
        }
        for s in series {
            for (j, &(x, y)) in s.points.iter().enumerate() {
                check_finite(|| format!("series[{:?}].points[{j}].x", s.label), x)?;
                check_finite(|| format!("series[{:?}].points[{j}].y", s.label), y)?;
            }
        }
        let to_plot = |v: f64, log: bool| match (log, v > 0.0) {
            (false, _) => Some(v),
            (true, true) => Some(v.log10()),
            (true, false) => None,
        };
        let runs: Vec<Vec<Vec<(f64, f64)>>> = series
            .iter()
            .map(|s| {
                let mut runs = vec![Vec::new()];
                for &(x, y) in &s.points {
                    match (to_plot(x, axes.log_x), to_plot(y, axes.log_y)) {
                        (Some(px), Some(py)) => runs.last_mut().unwrap().push((px, py)),
                        _ if runs.last().is_some_and(|r| !r.is_empty()) => runs.push(Vec::new()),
                        _ => {}
                    }
                }
                runs.retain(|r| !r.is_empty());
                runs
            })
            .collect();
        let all = || runs.iter().flatten().flatten();
        let (Some(bx), Some(by)) = (
            Bounds::of(all().map(|p| p.0)),
            Bounds::of(all().map(|p| p.1)),
        ) else {
            return Err(Error::invalid(
                "series",
                format!("{} series", series.len()),
                if axes.log_x || axes.log_y {
                    "no point with positive coordinates on the logarithmic axes"
                } else {
                    "every series is empty"
                },
            ));
        };
        let x_range = bx.padded(0.03, "x range")?;
        let y_range = by.padded(0.05, "y range")?;
        let legend = series
            .iter()
            .enumerate()
            .filter(|(_, s)| !s.label.is_empty())
            .map(|(i, s)| LegendEntry {
                label: s.label.clone(),
                color: palette(s.color.unwrap_or(i % 10)),
                width: 2,
                stroke: s.stroke,
                marker: s.markers.then_some(s.shape.unwrap_or(i)),
            })
            .collect();
        let frame = Frame::fixed(
            (WIDTH, LINE_CHART_HEIGHT),
            &axes.title,
            legend,
            &axes.x_label,
            &axes.y_label,
            x_range,
            y_range,
            (axes.log_x, axes.log_y),
        );
        Ok(LineChart {
            frame,
            runs,
            series: series.to_vec(),
        })
    }
}

impl Figure for LineChart {
    fn frame(&self) -> &Frame {
        &self.frame
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<(), DB> {
        draw_header(root, &self.frame)?;
        let region = chart_region(root, &self.frame);
        let mut chart = draw_axes(&region, &self.frame, true)?;
        for (i, (s, runs)) in self.series.iter().zip(&self.runs).enumerate() {
            let color = palette(s.color.unwrap_or(i % 10));
            let style = ShapeStyle::from(&color).stroke_width(2);
            for run in runs {
                if let Some((dash, gap)) = s.stroke.pattern() {
                    chart.draw_series(DashedLineSeries::new(run.clone(), dash, gap, style))?;
                } else {
                    chart.draw_series(LineSeries::new(run.clone(), style))?;
                }
                if s.markers {
                    let outline = marker_outline(s.shape.unwrap_or(i));
                    chart.draw_series(run.iter().map(|&p| {
                        EmptyElement::at(p) + Polygon::new(outline.clone(), color.filled())
                    }))?;
                }
            }
        }
        draw_box(root, &self.frame)
    }
}

// ---------------------------------------------------------------------------
// Geometry figure
// ---------------------------------------------------------------------------

struct GeometryFigure {
    frame: Frame,
    lines: Vec<Polyline>,
}

fn polyline_bounds(lines: &[Polyline]) -> Option<(Bounds, Bounds)> {
    let pts = || lines.iter().flat_map(|l| l.points.iter());
    Some((
        Bounds::of(pts().map(|p| p[0]))?,
        Bounds::of(pts().map(|p| p[1]))?,
    ))
}

impl GeometryFigure {
    fn new(title: &str, lines: &[Polyline]) -> Result<GeometryFigure> {
        check_polylines("lines", lines)?;
        let Some((bx, by)) = polyline_bounds(lines) else {
            return Err(Error::invalid(
                "lines",
                format!("{} polylines", lines.len()),
                "a geometry figure needs at least one point",
            ));
        };
        let (bx, by) = square_pad(bx, by)?;
        let frame = Frame::equal_aspect(WIDTH, 0, title, polyline_legend(lines), bx, by);
        Ok(GeometryFigure {
            frame,
            lines: lines.to_vec(),
        })
    }
}

/// Pads both ranges by the same length, so that a body touching the frame
/// on one side does not on the other, and a degenerate direction (a
/// straight line) gets the other's extent.
fn square_pad(bx: Bounds, by: Bounds) -> Result<(Bounds, Bounds)> {
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

impl Figure for GeometryFigure {
    fn frame(&self) -> &Frame {
        &self.frame
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<(), DB> {
        draw_header(root, &self.frame)?;
        let region = chart_region(root, &self.frame);
        let mut chart = draw_axes(&region, &self.frame, true)?;
        draw_polylines(&mut chart, &self.lines)?;
        draw_box(root, &self.frame)
    }
}

// ---------------------------------------------------------------------------
// Field figure
// ---------------------------------------------------------------------------

const BAR_GAP: i32 = 24;
const BAR_WIDTH: i32 = 22;

struct FieldFigure {
    frame: Frame,
    label: String,
    cells: Vec<FieldCell>,
    overlay: Vec<Polyline>,
    values: Bounds,
    bar_ticks: Ticks,
}

impl FieldFigure {
    fn new(
        title: &str,
        label: &str,
        cells: &[FieldCell],
        overlay: &[Polyline],
    ) -> Result<FieldFigure> {
        for (i, c) in cells.iter().enumerate() {
            check_finite(|| format!("cells[{i}].value"), c.value)?;
            for (j, p) in c.corners.iter().enumerate() {
                for (k, &v) in p.iter().enumerate() {
                    check_finite(|| format!("cells[{i}].corners[{j}][{k}]"), v)?;
                }
            }
        }
        check_polylines("overlay", overlay)?;
        let Some(values) = Bounds::of(cells.iter().map(|c| c.value)) else {
            return Err(Error::invalid(
                "cells",
                "[]",
                "a field figure needs at least one cell",
            ));
        };
        let values = if values.span() > 1e-12 * values.lo.abs().max(values.hi.abs()) {
            values
        } else {
            values.padded(0.0, "field values")?
        };
        let corners = || cells.iter().flat_map(|c| c.corners.iter());
        let pts = || corners().chain(overlay.iter().flat_map(|l| l.points.iter()));
        let bx = Bounds::of(pts().map(|p| p[0])).expect("cells are not empty");
        let by = Bounds::of(pts().map(|p| p[1])).expect("cells are not empty");
        let (bx, by) = square_pad(bx, by)?;
        // The bar's height, hence its ticks, is only known after the layout,
        // which needs the labels' width: reserve room for the widest labels
        // any tick density could produce.
        let widest = (2..=10)
            .map(|n| Ticks::new(values, false, n).max_label_width())
            .max()
            .unwrap_or(0);
        let label_h = if label.is_empty() {
            0
        } else {
            text_size(label, DESC_SIZE).1 + 10
        };
        let reserve = BAR_GAP + BAR_WIDTH + 2 * TICK_MARK + widest + label_h + 4;
        let frame = Frame::equal_aspect(WIDTH, reserve, title, polyline_legend(overlay), bx, by);
        let bar_ticks = Ticks::fitting(values, false, frame.plot.3, false);
        Ok(FieldFigure {
            frame,
            label: label.to_string(),
            cells: cells.to_vec(),
            overlay: overlay.to_vec(),
            values,
            bar_ticks,
        })
    }

    fn color(&self, v: f64) -> RGBColor {
        let (r, g, b) = viridis((v - self.values.lo) / self.values.span());
        RGBColor(r, g, b)
    }

    fn draw_colorbar<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> DrawResult<(), DB> {
        let (left, top, w, h) = self.frame.plot;
        let x0 = left + w + BAR_GAP;
        let x1 = x0 + BAR_WIDTH;
        let bottom = top + h - 1;
        let to_y = |v: f64| {
            bottom - ((v - self.values.lo) / self.values.span() * (h - 1) as f64).round() as i32
        };
        // One band per pixel row (capped) looks continuous at any size.
        let bands = (h - 1).clamp(1, 256);
        for i in 0..bands {
            let ya = bottom - (i * (h - 1)) / bands;
            let yb = bottom - ((i + 1) * (h - 1)) / bands;
            let t = (i as f64 + 0.5) / bands as f64;
            let (r, g, b) = viridis(t);
            root.draw(&Rectangle::new(
                [(x0, yb), (x1, ya)],
                RGBColor(r, g, b).filled(),
            ))?;
        }
        root.draw(&Rectangle::new(
            [(x0, top), (x1, bottom)],
            BLACK.stroke_width(1),
        ))?;
        let text = font(TICK_SIZE)
            .color(&BLACK)
            .pos(Pos::new(HPos::Left, VPos::Center));
        let mut label_right = x1 + 2 * TICK_MARK;
        for (v, s) in &self.bar_ticks.major {
            let y = to_y(*v);
            if y < top - 1 || y > bottom + 1 {
                continue;
            }
            root.draw(&PathElement::new(vec![(x1, y), (x1 + TICK_MARK, y)], BLACK))?;
            root.draw(&Text::new(s.clone(), (x1 + 2 * TICK_MARK, y), text.clone()))?;
            label_right = label_right.max(x1 + 2 * TICK_MARK + text_size(s, TICK_SIZE).0);
        }
        if !self.label.is_empty() {
            let style = font(DESC_SIZE)
                .transform(FontTransform::Rotate270)
                .color(&BLACK)
                .pos(Pos::new(HPos::Center, VPos::Top));
            root.draw(&Text::new(
                self.label.clone(),
                (label_right + 10, top + h / 2),
                style,
            ))?;
        }
        Ok(())
    }
}

/// The quadrilateral `q` (pixels) pushed about a pixel outwards.
///
/// Anti-aliased renderers leave hairline gaps between abutting polygons;
/// growing every cell makes neighbours overlap instead, at no cost in file
/// size. Each corner moves along its miter so that both adjacent edges move
/// out by one pixel, whatever the cell's shape and orientation.
fn grow(q: [(i32, i32); 4]) -> Vec<(i32, i32)> {
    let p = q.map(|(x, y)| (x as f64, y as f64));
    let area2: f64 = (0..4)
        .map(|i| {
            let (a, b) = (p[i], p[(i + 1) % 4]);
            a.0 * b.1 - b.0 * a.1
        })
        .sum();
    let sign = area2.signum();
    let normals: Vec<(f64, f64)> = (0..4)
        .map(|i| {
            let (a, b) = (p[i], p[(i + 1) % 4]);
            let (dx, dy) = (b.0 - a.0, b.1 - a.1);
            let len = dx.hypot(dy);
            if len == 0.0 || sign == 0.0 {
                (0.0, 0.0)
            } else {
                (sign * dy / len, -sign * dx / len)
            }
        })
        .collect();
    (0..4)
        .map(|i| {
            let (n0, n1) = (normals[(i + 3) % 4], normals[i]);
            let (mx, my) = (n0.0 + n1.0, n0.1 + n1.1);
            let denom = 1.0 + n0.0 * n1.0 + n0.1 * n1.1;
            // Sharp corners would shoot a long miter spike; cap it.
            let (mut ox, mut oy) = if denom > 1e-9 {
                (mx / denom, my / denom)
            } else {
                (0.0, 0.0)
            };
            let len = ox.hypot(oy);
            if len > 2.0 {
                ox *= 2.0 / len;
                oy *= 2.0 / len;
            }
            (q[i].0 + ox.round() as i32, q[i].1 + oy.round() as i32)
        })
        .collect()
}

impl Figure for FieldFigure {
    fn frame(&self) -> &Frame {
        &self.frame
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<(), DB> {
        draw_header(root, &self.frame)?;
        let region = chart_region(root, &self.frame);
        let mut chart = draw_axes(&region, &self.frame, false)?;
        for c in &self.cells {
            let px = c.corners.map(|p| chart.backend_coord(&(p[0], p[1])));
            root.draw(&Polygon::new(grow(px), self.color(c.value).filled()))?;
        }
        draw_polylines(&mut chart, &self.overlay)?;
        self.draw_colorbar(root)?;
        draw_box(root, &self.frame)
    }
}

// The formulation chapters' figures live in their own file but are a child
// of this module, so that they share its layout and rendering.
#[path = "figures.rs"]
pub mod figures;

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

    #[test]
    fn grown_cells_cover_their_edges() {
        // Either orientation grows outwards.
        let ccw = grow([(0, 0), (10, 0), (10, 10), (0, 10)]);
        assert_eq!(ccw, [(-1, -1), (11, -1), (11, 11), (-1, 11)]);
        let cw = grow([(0, 0), (0, 10), (10, 10), (10, 0)]);
        assert_eq!(cw, [(-1, -1), (-1, 11), (11, 11), (11, -1)]);
        // A cell collapsed to a point stays put rather than exploding.
        assert_eq!(grow([(3, 3); 4]), [(3, 3); 4]);
    }

    #[test]
    fn viridis_ends() {
        assert_eq!(viridis(0.0), (0x44, 0x01, 0x54));
        assert_eq!(viridis(1.0), (0xfd, 0xe7, 0x25));
        assert_eq!(viridis(f64::NAN), viridis(0.0));
    }
}
