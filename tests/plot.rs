//! Figure output: files are valid SVG carrying their text, deterministic,
//! and bad input is refused before anything is written.

use iga_contact::report::plot::{
    annotated_figure, chart, field_figure, geometry_figure, line_chart, Axes, Bounds, Chart,
    ChartLine, Color, FieldCell, Label, LabelSide, LegendEntry, LineKind, Polyline, Series, Stroke,
    BLACK_INDEX, WHITE_INDEX,
};
use std::f64::consts::PI;
use std::path::PathBuf;

fn out(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("target")
        .join("plot-check")
        .join(name)
}

fn read(path: &PathBuf) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The contents of the `<text>` elements.
fn svg_texts(svg: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| {
            let body = &t[t.find('>')? + 1..];
            Some(body[..body.find("</text>")?].trim().to_string())
        })
        .collect()
}

fn assert_svg_with_text(path: &PathBuf, texts: &[&str]) -> String {
    let svg = read(path);
    let found = svg_texts(&svg);
    assert!(
        svg.starts_with("<svg"),
        "{} does not start with <svg",
        path.display()
    );
    assert!(svg.trim_end().ends_with("</svg>"));
    for t in texts {
        assert!(
            found.iter().any(|f| f == t),
            "{} lacks the text {t:?} (has {found:?})",
            path.display()
        );
    }
    svg
}

/// Renders with `draw` into two files and checks the bytes agree.
fn assert_deterministic(name: &str, draw: impl Fn(&PathBuf)) {
    let a = out(&format!("{name}-a.svg"));
    let b = out(&format!("{name}-b.svg"));
    draw(&a);
    draw(&b);
    let first = std::fs::read(&a).unwrap();
    draw(&a);
    assert_eq!(first, std::fs::read(&a).unwrap(), "{name}: rerun differs");
    assert_eq!(first, std::fs::read(&b).unwrap(), "{name}: copies differ");
}

fn convergence_axes() -> Axes {
    Axes {
        title: "Convergence of the contact iteration".into(),
        x_label: "iteration".into(),
        y_label: "relative residual".into(),
        log_x: false,
        log_y: true,
    }
}

fn convergence_series() -> Vec<Series> {
    let newton: Vec<(f64, f64)> = [1.0, 3e-2, 4e-4, 2e-7, 5e-13]
        .iter()
        .enumerate()
        .map(|(k, &r)| (k as f64, r))
        .collect();
    let bfgs: Vec<(f64, f64)> = (0..18)
        .map(|k| (k as f64, 0.55_f64.powi(k * k / 6 + k)))
        .collect();
    // A residual of exactly zero must be skipped on the log axis.
    let mut corrected = bfgs.iter().map(|&(k, r)| (k, r * 0.3)).collect::<Vec<_>>();
    corrected[9].1 = 0.0;
    vec![
        Series::line("Newton", newton).with_markers(),
        Series::line("BFGS", bfgs).with_markers(),
        Series::line("corrected BFGS", corrected).dashed(),
        Series::line("", vec![(0.0, 1e-10), (17.0, 1e-10)]).dashed(),
    ]
}

#[test]
fn line_chart_writes_svg_with_title_and_legend() {
    let path = out("line.svg");
    line_chart(&path, &convergence_axes(), &convergence_series()).unwrap();
    assert_svg_with_text(
        &path,
        &[
            "Convergence of the contact iteration",
            "Newton",
            "BFGS",
            "corrected BFGS",
            "iteration",
            "relative residual",
        ],
    );
    assert_deterministic("line-det", |p| {
        line_chart(p, &convergence_axes(), &convergence_series()).unwrap()
    });
}

#[test]
fn line_chart_on_linear_axes() {
    let path = out("line-linear.svg");
    let pressure: Vec<(f64, f64)> = (0..=80)
        .map(|i| {
            let x = -1.0 + 2.0 * i as f64 / 80.0;
            (x, 4.0 / PI * (1.0 - x * x).max(0.0).sqrt() * 1.5e4)
        })
        .collect();
    let axes = Axes {
        title: "Contact pressure".into(),
        x_label: "x / a".into(),
        y_label: "p [Pa]".into(),
        ..Axes::default()
    };
    let exact = Series::line("Hertz", pressure.clone());
    let computed = Series {
        label: "Nitsche, p = 2".into(),
        points: pressure
            .iter()
            .step_by(4)
            .map(|&(x, p)| (x, p * 0.98))
            .collect(),
        markers: true,
        ..Series::default()
    };
    line_chart(&path, &axes, &[exact, computed]).unwrap();
    assert_svg_with_text(&path, &["Contact pressure", "Hertz", "Nitsche, p = 2"]);
}

#[test]
fn log_axes_with_zero_and_negative_values_do_not_panic() {
    let axes = Axes {
        title: "Error against mesh size".into(),
        x_label: "h".into(),
        y_label: "error".into(),
        log_x: true,
        log_y: true,
    };
    let series = [
        Series::line(
            "L2",
            vec![(0.0, 1.0), (0.5, 0.1), (0.25, 0.02), (0.125, 0.0)],
        ),
        Series::line("H1", vec![(0.5, -1.0), (0.25, 0.3), (0.125, 0.15)]).with_markers(),
    ];
    let path = out("log-zero.svg");
    line_chart(&path, &axes, &series).unwrap();
    assert_svg_with_text(&path, &["Error against mesh size", "L2", "H1"]);

    // Nothing positive at all: an error, not a panic and not a file.
    let path = out("log-nothing.svg");
    let _ = std::fs::remove_file(&path);
    let only_zero = [Series::line("zero", vec![(1.0, 0.0), (2.0, 0.0)])];
    assert!(line_chart(&path, &axes, &only_zero).is_err());
    assert!(!path.exists());

    // A range inside one decade still gets labelled ticks.
    let path = out("log-narrow.svg");
    let narrow = [Series::line(
        "narrow",
        vec![(1.0, 2.1), (2.0, 2.3), (3.0, 2.2)],
    )];
    line_chart(&path, &convergence_axes(), &narrow).unwrap();
    assert_svg_with_text(&path, &["narrow"]);
}

#[test]
fn line_chart_rejects_bad_input_without_writing() {
    let path = out("nan.svg");
    let _ = std::fs::remove_file(&path);
    let bad = [Series::line("bad", vec![(0.0, 1.0), (1.0, f64::NAN)])];
    let err = line_chart(&path, &convergence_axes(), &bad).unwrap_err();
    assert!(err.to_string().contains("points[1].y"), "{err}");
    assert!(!path.exists());

    let inf = [Series::line("inf", vec![(f64::INFINITY, 1.0)])];
    assert!(line_chart(&path, &convergence_axes(), &inf).is_err());
    assert!(line_chart(&path, &convergence_axes(), &[]).is_err());
    assert!(line_chart(&path, &convergence_axes(), &[Series::line("empty", vec![])]).is_err());
    assert!(!path.exists());
}

/// A half disc resting on a block: element boundaries and control nets.
fn contact_geometry() -> Vec<Polyline> {
    let mut lines = Vec::new();
    let (r, cy) = (1.0, 1.0);
    for k in 0..=4 {
        let a = PI + PI * k as f64 / 4.0;
        let ray = vec![[0.0, cy], [r * a.cos(), cy + r * a.sin()]];
        lines.push(Polyline::new(ray, LineKind::Solid, 0).labelled("disc elements"));
    }
    let arc: Vec<[f64; 2]> = (0..=64)
        .map(|i| {
            let a = PI + PI * i as f64 / 64.0;
            [r * a.cos(), cy + r * a.sin()]
        })
        .collect();
    lines.push(Polyline::new(arc, LineKind::Solid, 0).labelled("disc elements"));
    let net = vec![[-1.0, 1.0], [-1.0, 0.0], [0.0, 0.0], [1.0, 0.0], [1.0, 1.0]];
    lines.push(Polyline::new(net, LineKind::ControlNet, 3).labelled("control net"));
    for i in 0..=8 {
        let x = -2.0 + 0.5 * i as f64;
        let line = vec![[x, -1.0], [x, 0.0]];
        lines.push(Polyline::new(line, LineKind::Thin, BLACK_INDEX).labelled("block elements"));
    }
    for j in 0..=2 {
        let y = -1.0 + 0.5 * j as f64;
        let line = vec![[-2.0, y], [2.0, y]];
        lines.push(Polyline::new(line, LineKind::Thin, BLACK_INDEX).labelled("block elements"));
    }
    lines.push(
        Polyline::new(vec![[-2.0, 0.02], [2.0, 0.02]], LineKind::Dashed, 2).labelled("rigid plane"),
    );
    lines
}

#[test]
fn geometry_figure_writes_svg_with_legend() {
    let path = out("geometry.svg");
    geometry_figure(&path, "Half disc on a block", &contact_geometry()).unwrap();
    let svg = assert_svg_with_text(
        &path,
        &[
            "Half disc on a block",
            "disc elements",
            "control net",
            "block elements",
            "rigid plane",
        ],
    );
    // Shared labels make one legend entry.
    let texts = svg_texts(&svg);
    assert_eq!(texts.iter().filter(|t| *t == "disc elements").count(), 1);
    assert_deterministic("geometry-det", |p| {
        geometry_figure(p, "Half disc on a block", &contact_geometry()).unwrap()
    });

    // A degenerate geometry (a single point, a straight line) still draws.
    geometry_figure(
        out("point.svg"),
        "point",
        &[Polyline::new(vec![[1.0, 1.0]], LineKind::ControlNet, 0)],
    )
    .unwrap();
    geometry_figure(
        out("segment.svg"),
        "segment",
        &[Polyline::new(
            vec![[0.0, 0.0], [5.0, 0.0]],
            LineKind::Solid,
            0,
        )],
    )
    .unwrap();
}

#[test]
fn geometry_figure_rejects_bad_input_without_writing() {
    let path = out("geometry-nan.svg");
    let _ = std::fs::remove_file(&path);
    let mut lines = contact_geometry();
    lines[2].points[1][0] = f64::NAN;
    let err = geometry_figure(&path, "bad", &lines).unwrap_err();
    assert!(err.to_string().contains("lines[2].points[1][0]"), "{err}");
    assert!(geometry_figure(&path, "empty", &[]).is_err());
    assert!(!path.exists());
}

/// `n × m` cells on a quarter annulus with a smooth field.
fn annulus_cells(n: usize, m: usize) -> Vec<FieldCell> {
    let point = |i: usize, j: usize| {
        let r = 1.0 + j as f64 / m as f64;
        let a = 0.5 * PI * i as f64 / n as f64;
        [r * a.cos(), r * a.sin()]
    };
    let mut cells = Vec::with_capacity(n * m);
    for i in 0..n {
        for j in 0..m {
            let corners = [
                point(i, j),
                point(i + 1, j),
                point(i + 1, j + 1),
                point(i, j + 1),
            ];
            let values = corners.map(|[x, y]| 1e6 * (x * x - y * y) / (x * x + y * y).powi(2));
            cells.push(FieldCell::from_corner_values(corners, values));
        }
    }
    cells
}

fn annulus_overlay() -> Vec<Polyline> {
    let arc = |r: f64| -> Vec<[f64; 2]> {
        (0..=64)
            .map(|i| {
                let a = 0.5 * PI * i as f64 / 64.0;
                [r * a.cos(), r * a.sin()]
            })
            .collect()
    };
    vec![
        Polyline::new(arc(1.0), LineKind::Thin, WHITE_INDEX).labelled("element boundaries"),
        Polyline::new(arc(1.5), LineKind::Thin, WHITE_INDEX).labelled("element boundaries"),
        Polyline::new(arc(2.0), LineKind::Thin, WHITE_INDEX).labelled("element boundaries"),
        Polyline::new(arc(2.1), LineKind::Dashed, 3).labelled("obstacle"),
    ]
}

#[test]
fn field_figure_writes_compact_svg_and_png() {
    let cells = annulus_cells(200, 100);
    assert_eq!(cells.len(), 20_000);
    let path = out("field.svg");
    field_figure(
        &path,
        "Radial stress",
        "σ_rr [Pa]",
        &cells,
        &annulus_overlay(),
    )
    .unwrap();
    let svg = assert_svg_with_text(
        &path,
        &[
            "Radial stress",
            "σ_rr [Pa]",
            "element boundaries",
            "obstacle",
        ],
    );
    assert!(svg.len() < 2_500_000, "field SVG is {} bytes", svg.len());
    assert!(!svg.contains("NaN"));

    let small = annulus_cells(12, 6);
    assert_deterministic("field-det", |p| {
        field_figure(p, "Radial stress", "σ_rr [Pa]", &small, &annulus_overlay()).unwrap()
    });

    let png = out("field.png");
    field_figure(
        &png,
        "Radial stress",
        "σ_rr [Pa]",
        &small,
        &annulus_overlay(),
    )
    .unwrap();
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");

    // A constant field has a colour bar of its own width, not a panic.
    let constant: Vec<FieldCell> = small
        .iter()
        .map(|c| FieldCell { value: 2.0, ..*c })
        .collect();
    field_figure(out("field-constant.svg"), "constant", "u", &constant, &[]).unwrap();
}

#[test]
fn field_figure_rejects_bad_input_without_writing() {
    let path = out("field-nan.svg");
    let _ = std::fs::remove_file(&path);
    let mut cells = annulus_cells(4, 2);
    cells[5].value = f64::NAN;
    let err = field_figure(&path, "bad", "v", &cells, &[]).unwrap_err();
    assert!(err.to_string().contains("cells[5].value"), "{err}");
    let mut cells = annulus_cells(4, 2);
    cells[1].corners[2][1] = f64::NEG_INFINITY;
    assert!(field_figure(&path, "bad", "v", &cells, &[]).is_err());
    let mut overlay = annulus_overlay();
    overlay[0].points[3][1] = f64::NAN;
    assert!(field_figure(&path, "bad", "v", &annulus_cells(4, 2), &overlay).is_err());
    assert!(field_figure(&path, "empty", "v", &[], &[]).is_err());
    assert!(!path.exists());
}

#[test]
fn extreme_layouts_render() {
    // Slender bodies: the figure height is clamped and the range widened.
    let rect = |w: f64, h: f64| vec![[0.0, 0.0], [w, 0.0], [w, h], [0.0, h], [0.0, 0.0]];
    let wide = [Polyline::new(rect(10.0, 0.2), LineKind::Solid, 0).labelled("strip")];
    geometry_figure(out("wide.svg"), "Wide strip", &wide).unwrap();
    let tall = [Polyline::new(rect(0.1, 3.0), LineKind::Solid, 1).labelled("column")];
    geometry_figure(out("tall.svg"), "Tall column", &tall).unwrap();

    // Many long legend labels wrap into rows; log x with tiny values.
    let axes = Axes {
        title: "Penalty sweep".into(),
        x_label: "γ".into(),
        y_label: "gap".into(),
        log_x: true,
        log_y: false,
    };
    let series: Vec<Series> = (0..7)
        .map(|k| {
            let pts = (0..20)
                .map(|i| {
                    let g = 10f64.powf(-8.0 + 0.5 * i as f64);
                    (g, -3e-5 * (k + 1) as f64 / (1.0 + g))
                })
                .collect();
            Series::line(format!("quadratic NURBS, {} elements", 4 << k), pts).with_markers()
        })
        .collect();
    let path = out("wrap.svg");
    line_chart(&path, &axes, &series).unwrap();
    assert_svg_with_text(&path, &["quadratic NURBS, 256 elements", "γ"]);
}

/// A chart a chapter composes itself: a hat function over a grey guide.
fn hat_chart(lines: Vec<ChartLine>, x_range: Bounds) -> Chart {
    Chart {
        title: "A hat function".into(),
        x_label: "ξ".into(),
        y_label: "value".into(),
        x_range,
        y_range: Bounds {
            lo: -0.05,
            hi: 1.05,
        },
        legend: vec![LegendEntry {
            label: "N₀".into(),
            color: Color::Palette(0),
            width: 2,
            stroke: Stroke::Solid,
            marker: None,
        }],
        lines,
    }
}

fn hat_lines() -> Vec<ChartLine> {
    vec![
        ChartLine {
            points: vec![(0.5, -0.05), (0.5, 1.05)],
            color: Color::Rgb(0x99, 0x99, 0x99),
            width: 1,
            dash: Some((4, 4)),
        },
        ChartLine {
            points: vec![(0.0, 0.0), (0.5, 1.0), (1.0, 0.0)],
            color: Color::Palette(0),
            width: 2,
            dash: None,
        },
    ]
}

#[test]
fn composed_chart_and_annotated_figure_write_svg_and_refuse_bad_input() {
    let unit = Bounds { lo: 0.0, hi: 1.0 };
    let path = out("chart.svg");
    chart(&path, &hat_chart(hat_lines(), unit)).unwrap();
    assert_svg_with_text(&path, &["A hat function", "N₀", "ξ", "value"]);
    assert_deterministic("chart-det", |p| {
        chart(p, &hat_chart(hat_lines(), unit)).unwrap()
    });

    let bad = out("chart-bad.svg");
    let _ = std::fs::remove_file(&bad);
    let mut nan = hat_lines();
    nan[1].points[1].1 = f64::NAN;
    let err = chart(&bad, &hat_chart(nan, unit)).unwrap_err();
    assert!(err.to_string().contains("lines[1].points[1].y"), "{err}");
    let empty = Bounds { lo: 1.0, hi: 1.0 };
    assert!(chart(&bad, &hat_chart(hat_lines(), empty)).is_err());
    assert!(!bad.exists());

    let path = out("annotated.svg");
    let lines = [Polyline::new(
        vec![[0.0, 0.0], [1.0, 0.5]],
        LineKind::Solid,
        0,
    )];
    let labels = [Label::new([0.0, 0.0], "x¹", LabelSide::Left).colored(3)];
    annotated_figure(&path, "A labelled segment", &lines, &labels).unwrap();
    assert_svg_with_text(&path, &["A labelled segment", "x¹"]);
    let far = [Label::new([f64::INFINITY, 0.0], "far", LabelSide::Right)];
    let bad = out("annotated-bad.svg");
    let _ = std::fs::remove_file(&bad);
    let err = annotated_figure(&bad, "bad", &lines, &far).unwrap_err();
    assert!(err.to_string().contains("labels[0].at[0]"), "{err}");
    assert!(!bad.exists());
}
