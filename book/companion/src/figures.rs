//! Figures of the formulation chapters: the NURBS basis functions of a knot
//! vector, a control net with its weights (of one patch, or of the patches
//! of one body), and a sketch of the contact geometry (slave point,
//! closest-point projection, normals and gap) drawn from the contact code
//! itself.
//!
//! They are described with the public API of [`iga_contact::report::plot`]
//! and the control nets of [`iga_contact::report::drawing`] only (annotated
//! geometry figures and charts of their own), so that this module does not
//! depend on how plots are laid out or drawn.

use iga_contact::contact::ContactPoint;
use iga_contact::nurbs::{KnotVector, NurbsCurve, NurbsPatch};
use iga_contact::report::drawing::{control_net, labelled};
use iga_contact::report::plot::{
    annotated_figure, chart, typographic_minus, Bounds, Chart, ChartLine, Color, Label, LabelSide,
    LegendEntry, LineKind, Polyline, Stroke, BLACK_INDEX,
};
use iga_contact::{Error, Result};
use std::path::Path;

// ---------------------------------------------------------------------------
// Basis functions
// ---------------------------------------------------------------------------

/// Subscript digits, for labels such as N₃,₂.
fn subscript(n: usize) -> String {
    n.to_string()
        .chars()
        .map(|c| char::from_u32('₀' as u32 + c.to_digit(10).unwrap_or(0)).unwrap_or(c))
        .collect()
}

/// The B-spline basis N_{i,p} (`weights = None`) or the rational basis
/// R_i = w_i N_{i,p} / Σ_j w_j N_{j,p} of `knots`, sampled at `n` points
/// per knot span (knots included, so kinks at repeated knots are drawn
/// sharp): one vector of (ξ, value) per function.
pub fn sample_basis(
    knots: &KnotVector,
    weights: Option<&[f64]>,
    n: usize,
) -> Result<Vec<Vec<(f64, f64)>>> {
    let nb = knots.n_basis();
    if let Some(w) = weights {
        if w.len() != nb {
            return Err(Error::invalid(
                "weights",
                format!("{} weights", w.len()),
                format!("the knot vector has {nb} basis functions"),
            ));
        }
        for (i, &wi) in w.iter().enumerate() {
            if !(wi.is_finite() && wi > 0.0) {
                return Err(Error::invalid(
                    format!("weights[{i}]"),
                    wi,
                    "must be positive and finite",
                ));
            }
        }
    }
    if n == 0 {
        return Err(Error::invalid("samples per span", n, "must be at least 1"));
    }
    let p = knots.degree();
    let mut out = vec![Vec::new(); nb];
    for (span, a, b) in knots.spans() {
        for k in 0..=n {
            let xi = a + (b - a) * k as f64 / n as f64;
            // Evaluated in this span, so both one-sided values at a knot appear.
            let values = &knots.basis_ders(span, xi, 0)[0];
            let first = span - p;
            let wsum: f64 = match weights {
                Some(w) => (0..=p).map(|j| w[first + j] * values[j]).sum(),
                None => 1.0,
            };
            for (j, &v) in values.iter().enumerate() {
                let w = weights.map_or(1.0, |w| w[first + j]);
                out[first + j].push((xi, w * v / wsum));
            }
        }
    }
    // Outside its support a function is zero: close each curve to the ends
    // of the parameter range so that it reads as a function on all of it.
    let (lo, hi) = (knots.first(), knots.last());
    for f in &mut out {
        if f.first().is_some_and(|q| q.0 > lo) {
            f.insert(0, (lo, 0.0));
        }
        if f.last().is_some_and(|q| q.0 < hi) {
            f.push((hi, 0.0));
        }
    }
    Ok(out)
}

/// Formats a weight or knot compactly: 0.7071, 1, 0.5.
fn short(v: f64) -> String {
    let s = format!("{v:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    typographic_minus(s.to_string())
}

/// The basis functions of `knots` on one chart, one colour per function,
/// with grey dashed lines at the knots. With `weights`, the rational basis
/// R_i is drawn solid and the B-splines N_{i,p} it is built from dashed in
/// the same colour, so the pull of each weight is visible.
pub fn basis_figure(
    path: impl AsRef<Path>,
    title: &str,
    knots: &KnotVector,
    weights: Option<&[f64]>,
) -> Result<()> {
    const SAMPLES_PER_SPAN: usize = 60;
    let p = knots.degree();
    let mut curves = Vec::new();
    let mut legend = Vec::new();
    let rational = sample_basis(knots, weights, SAMPLES_PER_SPAN)?;
    for (i, f) in rational.into_iter().enumerate() {
        let color = Color::Palette(i % 10);
        let label = match weights {
            Some(_) => format!("R{}", subscript(i)),
            None => format!("N{},{}", subscript(i), subscript(p)),
        };
        legend.push(LegendEntry {
            label,
            color,
            width: 2,
            stroke: Stroke::Solid,
            marker: None,
        });
        curves.push(ChartLine {
            points: f,
            color,
            width: 2,
            dash: None,
        });
    }
    if weights.is_some() {
        for (i, f) in sample_basis(knots, None, SAMPLES_PER_SPAN)?
            .into_iter()
            .enumerate()
        {
            // The B-spline drawn under a rational function: thin and dashed.
            curves.push(ChartLine {
                points: f,
                color: Color::Palette(i % 10),
                width: 1,
                dash: Some((5, 4)),
            });
        }
        legend.push(LegendEntry {
            label: "B-splines N (all weights 1)".into(),
            color: Color::Palette(7),
            width: 1,
            stroke: Stroke::Dashed,
            marker: None,
        });
    }
    let x = Bounds {
        lo: knots.first(),
        hi: knots.last(),
    }
    .padded(0.03, "knot range")?;
    let y = Bounds::of(curves.iter().flat_map(|c| c.points.iter().map(|q| q.1)))
        .unwrap_or(Bounds { lo: 0.0, hi: 1.0 });
    let y = Bounds {
        lo: y.lo.min(0.0),
        hi: y.hi.max(1.0),
    }
    .padded(0.05, "basis values")?;
    // Grey dashed lines at the knots, under the curves.
    let breaks = knots.breaks().into_iter().map(|k| ChartLine {
        points: vec![(k, y.lo), (k, y.hi)],
        color: Color::Rgb(0x99, 0x99, 0x99),
        width: 1,
        dash: Some((4, 4)),
    });
    let lines = breaks.chain(curves).collect();
    chart(
        path,
        &Chart {
            title: title.to_string(),
            x_label: "ξ".into(),
            y_label: "value".into(),
            x_range: x,
            y_range: y,
            legend,
            lines,
        },
    )
}

// ---------------------------------------------------------------------------
// Control net
// ---------------------------------------------------------------------------

/// The control polygon of `patch`, its rows and columns, dashed with a
/// marker at each control point, in palette colour `color`.
fn net_lines(patch: &NurbsPatch, color: usize, label: &str) -> Vec<Polyline> {
    labelled(control_net(patch, color), label)
}

/// The weight of each control point written beside it, away from
/// `centre` so that the text sits outside the net's lines where possible.
/// A point that several patches share (with one weight) is labelled once.
fn weight_labels<'a>(
    points: impl IntoIterator<Item = (&'a [f64; 2], &'a f64)>,
    centre: [f64; 2],
    color: usize,
) -> Vec<Label> {
    let mut seen: Vec<([f64; 2], f64)> = Vec::new();
    let mut labels = Vec::new();
    for (&p, &w) in points {
        // shared points coincide to round-off (matching interfaces copy them)
        let same = |(q, v): &([f64; 2], f64)| {
            (p[0] - q[0]).hypot(p[1] - q[1]) <= 1e-12 * (1.0 + p[0].hypot(p[1]))
                && (w - v).abs() <= 1e-12
        };
        if seen.iter().any(same) {
            continue;
        }
        seen.push((p, w));
        let side = side_toward([p[0] - centre[0], p[1] - centre[1]]);
        labels.push(Label::new(p, short(w), side).colored(color));
    }
    labels
}

/// The side of a point a label goes to so that it lies in direction `d`
/// from the point (the nearer axis decides).
fn side_toward(d: [f64; 2]) -> LabelSide {
    if d[0].abs() >= d[1].abs() {
        if d[0] >= 0.0 {
            LabelSide::Right
        } else {
            LabelSide::Left
        }
    } else if d[1] >= 0.0 {
        LabelSide::Above
    } else {
        LabelSide::Below
    }
}

/// The mean of `points`.
fn centroid<'a>(points: impl IntoIterator<Item = &'a [f64; 2]>) -> [f64; 2] {
    let (mut c, mut n) = ([0.0, 0.0], 0.0);
    for p in points {
        c = [c[0] + p[0], c[1] + p[1]];
        n += 1.0;
    }
    [c[0] / n, c[1] / n]
}

/// The body of `patch` with its element boundaries (knot lines), its control
/// net, and the weight of every control point written beside it.
pub fn control_net_figure(path: impl AsRef<Path>, title: &str, patch: &NurbsPatch) -> Result<()> {
    const SEGMENTS: usize = 64;
    let mut lines = Vec::new();
    for dir in 0..2 {
        for &c in &patch.knots[dir].breaks() {
            lines.push(
                Polyline::new(patch.iso_curve(dir, c, SEGMENTS), LineKind::Solid, 0)
                    .labelled("element boundaries"),
            );
        }
    }
    lines.extend(net_lines(patch, 3, "control net"));
    let centre = centroid(&patch.points);
    let labels = weight_labels(patch.points.iter().zip(&patch.weights), centre, 3);
    annotated_figure(path, title, &lines, &labels)
}

/// The patches of one body, each in its own colour: its boundary (the
/// exact curves, sampled), its control net, and arrows along ξ and η
/// near its corner (ξ, η) = (0, 0), labelled with the patch's index; the
/// weight of every control point beside it, in black, once where patches
/// share the point. A side two patches share is one curve: it shows the
/// colour of the lower index, so that the first patch (a core, which
/// touches only other patches) keeps its outline.
pub fn multipatch_figure(
    path: impl AsRef<Path>,
    title: &str,
    patches: &[NurbsPatch],
) -> Result<()> {
    const SEGMENTS: usize = 96;
    // Where the arrows start, as a share of each parameter range: off the
    // corner, so that the arrows of patches meeting there stay apart, and
    // short of the middle of the side, where the weights are written.
    const INSET: [f64; 2] = [0.12, 0.25];
    let all = || patches.iter().flat_map(|p| p.points.iter());
    let (Some(bx), Some(by)) = (
        Bounds::of(all().map(|p| p[0])),
        Bounds::of(all().map(|p| p[1])),
    ) else {
        return Err(Error::invalid("patches", "none", "nothing to draw"));
    };
    let len = 0.05 * bx.span().max(by.span());
    let mut lines = Vec::new();
    let mut labels = Vec::new();
    // The arrows first: they carry the legend's entry of their patch.
    for (k, patch) in patches.iter().enumerate() {
        let color = k % 10;
        let name = format!("patch {k}");
        let at = |dir: usize| {
            let kv = &patch.knots[dir];
            kv.first() + INSET[dir] * (kv.last() - kv.first())
        };
        let (xi, eta) = (at(0), at(1));
        let tail = patch.point(xi, eta);
        let j = patch.jacobian(xi, eta);
        for (dir, symbol) in [(0, "ξ"), (1, "η")] {
            let t = [j[0][dir], j[1][dir]];
            let norm = t[0].hypot(t[1]);
            if !(norm.is_finite() && norm > 0.0) {
                return Err(Error::invalid(
                    format!("patches[{k}]"),
                    format!("∂x/∂{symbol} = {t:?} at ({xi}, {eta})"),
                    "the map degenerates next to the corner (0, 0)",
                ));
            }
            let d = [t[0] / norm, t[1] / norm];
            lines.extend(arrow(tail, d, len, color, Some(&name)));
            let tip = [tail[0] + len * d[0], tail[1] + len * d[1]];
            let text = format!("{symbol}{}", subscript(k));
            labels.push(Label::new(tip, text, side_toward(d)).colored(color));
        }
    }
    for (k, patch) in patches.iter().enumerate().rev() {
        for dir in 0..2 {
            let kv = &patch.knots[dir];
            for c in [kv.first(), kv.last()] {
                let side = patch.iso_curve(dir, c, SEGMENTS);
                lines.push(Polyline::new(side, LineKind::Solid, k % 10));
            }
        }
    }
    for (k, patch) in patches.iter().enumerate() {
        lines.extend(net_lines(patch, k % 10, "control nets"));
    }
    let centre = centroid(all());
    let weights = patches.iter().flat_map(|p| p.points.iter().zip(&p.weights));
    for mut label in weight_labels(weights, centre, BLACK_INDEX) {
        // Beside a point at the left or right end of the net the text
        // would run into the frame (labels do not widen the plot): above.
        let end = |v: f64, b: Bounds| (v - b.lo).min(b.hi - v) <= 1e-9 * b.span();
        if matches!(label.side, LabelSide::Left | LabelSide::Right) && end(label.at[0], bx) {
            label.side = LabelSide::Above;
        }
        labels.push(label);
    }
    annotated_figure(path, title, &lines, &labels)
}

// ---------------------------------------------------------------------------
// Contact sketch
// ---------------------------------------------------------------------------

/// An arrow from `tail` along `dir` (unit) of length `len`, as a shaft and
/// a two-stroke head.
fn arrow(
    tail: [f64; 2],
    dir: [f64; 2],
    len: f64,
    color: usize,
    label: Option<&str>,
) -> Vec<Polyline> {
    let head = [tail[0] + len * dir[0], tail[1] + len * dir[1]];
    let back = 0.22 * len;
    let barb = |s: f64| {
        let (c, sn) = (0.93969, s * 0.34202); // ±20°
        let d = [-(c * dir[0] - sn * dir[1]), -(sn * dir[0] + c * dir[1])];
        [head[0] + back * d[0], head[1] + back * d[1]]
    };
    let shaft = Polyline::new(vec![tail, head], LineKind::Solid, color);
    vec![
        match label {
            Some(label) => shaft.labelled(label),
            None => shaft,
        },
        Polyline::new(vec![barb(1.0), head, barb(-1.0)], LineKind::Solid, color),
    ]
}

/// A sketch of the contact geometry of Eqs. (4)–(5) from contact points
/// built by the contact code ([`iga_contact::contact::contact_points`], which
/// projects each slave point with [`iga_contact::contact::projection::closest_point`]):
/// the slave and master curves, every point's projection ray (x¹ to
/// x̄² = x¹ + g₀ n¹, thin), and for the point `highlight` the slave point
/// x¹, its projection x̄², the master's outward normal n² there, the slave
/// normal n¹ = −n², and the gap g₀.
pub fn contact_sketch(
    path: impl AsRef<Path>,
    title: &str,
    slave: &NurbsCurve,
    master: &NurbsCurve,
    points: &[ContactPoint],
    highlight: usize,
) -> Result<()> {
    const SEGMENTS: usize = 96;
    let Some(cp) = points.get(highlight) else {
        return Err(Error::invalid(
            "highlight",
            highlight,
            format!("there are {} contact points", points.len()),
        ));
    };
    let curve = |c: &NurbsCurve| -> Vec<[f64; 2]> {
        let (a, b) = (c.knots.first(), c.knots.last());
        (0..=SEGMENTS)
            .map(|k| c.point(a + (b - a) * k as f64 / SEGMENTS as f64))
            .collect()
    };
    let foot = |cp: &ContactPoint| {
        [
            cp.x[0] + cp.g0 * cp.normal[0],
            cp.x[1] + cp.g0 * cp.normal[1],
        ]
    };
    let (slave_line, master_line) = (curve(slave), curve(master));
    let both = || slave_line.iter().chain(&master_line);
    let (Some(bx), Some(by)) = (
        Bounds::of(both().map(|p| p[0])),
        Bounds::of(both().map(|p| p[1])),
    ) else {
        return Err(Error::invalid("curves", "empty", "nothing to draw"));
    };
    let (x1, x2, n1) = (cp.x, foot(cp), cp.normal);
    let n2 = [-n1[0], -n1[1]];
    // The normals lie on the projection ray (the projection is orthogonal):
    // each covers a third of the gap from its own end, so they never meet.
    let len = (cp.g0.abs() / 3.0).min(0.15 * bx.span().max(by.span()));
    let mut lines = vec![
        Polyline::new(slave_line, LineKind::Solid, 0).labelled("slave Γc¹"),
        Polyline::new(master_line, LineKind::Solid, 1).labelled("master Γc²"),
    ];
    for p in points {
        lines.push(Polyline::new(vec![p.x, foot(p)], LineKind::Thin, 7).labelled("projections"));
    }
    lines.push(Polyline::new(vec![x1, x2], LineKind::Dashed, BLACK_INDEX).labelled("gap g₀"));
    lines.extend(arrow(x1, n1, len, 3, Some("n¹ = −n²")));
    lines.extend(arrow(x2, n2, len, 2, Some("n² (master, outward)")));
    lines.push(Polyline::new(vec![x1], LineKind::ControlNet, BLACK_INDEX));
    lines.push(Polyline::new(vec![x2], LineKind::ControlNet, BLACK_INDEX));
    let mid = [0.5 * (x1[0] + x2[0]), 0.5 * (x1[1] + x2[1])];
    let tip = |x: [f64; 2], d: [f64; 2]| [x[0] + len * d[0], x[1] + len * d[1]];
    let labels = [
        Label::new(x1, "x¹", LabelSide::Left),
        Label::new(x2, "x̄²", LabelSide::Left),
        Label::new(mid, format!("g₀ = {} m", short(cp.g0)), LabelSide::Right),
        Label::new(tip(x1, n1), "n¹", LabelSide::Left).colored(3),
        Label::new(tip(x2, n2), "n²", LabelSide::Left).colored(2),
    ];
    annotated_figure(path, title, &lines, &labels)
}
