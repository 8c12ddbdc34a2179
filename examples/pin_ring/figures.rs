//! The chapter's figures: Figs. PR1–PR3.

// the chapter's runs, measures and imports
use super::*;

/// Fig. PR1: the compound cylinder's interface pressure along the angle,
/// on the three coarsest rungs, against Lamé's q.
pub fn draw_compound(chapter: &Chapter, ladder: &[Run], q: f64) -> Result<()> {
    let mut series: Vec<Series> = ladder[..3]
        .iter()
        .map(|r| {
            let mut pts: Vec<(f64, f64)> = r
                .samples
                .iter()
                .map(|s| (s.x[1].atan2(s.x[0]).to_degrees(), s.pressure() * 1e-6))
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            Series::line(format!("k = {}", r.rung), pts)
        })
        .collect();
    series.push(Series::line("Lamé", vec![(0.0, q * 1e-6), (90.0, q * 1e-6)]).dashed());
    line_chart(
        chapter.path("compound_pressure.svg"),
        &Axes {
            title: "Compound cylinder, p = 2: interface pressure".into(),
            x_label: "angle from the x axis (°)".into(),
            y_label: "contact pressure (MPa)".into(),
            log_x: false,
            log_y: false,
        },
        &series,
    )
}

/// Fig. PR2: the pin's contact pressure against the angle from the lowest
/// point, on three rungs and the reference.
pub fn draw_pin(chapter: &Chapter, pins: &[Run], reference: &Run, center: [f64; 2]) -> Result<()> {
    let curve = |r: &Run| {
        let mut pts: Vec<(f64, f64)> = r
            .samples
            .iter()
            .map(|s| (angle_from_bottom(s.x, center), s.pressure() * 1e-6))
            .collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        pts
    };
    let mut series: Vec<Series> = pins[..3]
        .iter()
        .map(|r| Series::line(format!("n = {}", r.rung), curve(r)))
        .collect();
    series.push(
        Series::line(
            format!("reference, n = {}", reference.rung),
            curve(reference),
        )
        .dashed(),
    );
    line_chart(
        chapter.path("pin_pressure.svg"),
        &Axes {
            title: "Pin in a ring, p = 2: contact pressure".into(),
            x_label: "angle from the lowest point (°)".into(),
            y_label: "contact pressure (MPa)".into(),
            log_x: false,
            log_y: false,
        },
        &series,
    )
}

/// Fig. PR3: the errors of both benchmarks against the elements along the
/// interface (the slave's).
pub fn draw_errors(
    chapter: &Chapter,
    ladder: &[Run],
    q: f64,
    pins: &[Run],
    reference: &Run,
    center: [f64; 2],
) -> Result<()> {
    let reference_angle = half_angle(reference, center);
    // slave elements along the interface: the outer ring's 2k; the pin's
    // three arc patches carry n each
    let compound = |f: fn((f64, f64)) -> f64| -> Vec<(f64, f64)> {
        ladder
            .iter()
            .map(|r| ((2 * r.rung) as f64, f(lame_errors(r, q))))
            .collect()
    };
    let pin_p0 = pins
        .iter()
        .map(|r| ((3 * r.rung) as f64, relative(r.p0, reference.p0).abs()))
        .collect();
    let pin_angle = pins
        .iter()
        .map(|r| {
            let e = (half_angle(r, center) - reference_angle).abs() / reference_angle;
            ((3 * r.rung) as f64, e)
        })
        .collect();
    line_chart(
        chapter.path("errors.svg"),
        &Axes {
            title: "Conformal contact, p = 2: errors under refinement".into(),
            x_label: "slave elements along the interface".into(),
            y_label: "relative error".into(),
            log_x: true,
            log_y: true,
        },
        &[
            Series::line("compound: max |p − q|/q", compound(|e| e.0)).with_markers(),
            Series::line("compound: L² error / q", compound(|e| e.1)).with_markers(),
            Series::line("pin: p₀ vs reference", pin_p0)
                .with_markers()
                .dashed(),
            Series::line("pin: half-angle vs reference", pin_angle)
                .with_markers()
                .dashed(),
        ],
    )
}
