//! The chapter's figures: the model (H1), the residuals of the 8×8
//! histories (H2), u_y on the deformed disk (H3) and its VTU file, the
//! pressure profiles (H4, with their CSV), and the convergence study (H5,
//! H6).

use crate::convergence::{Convergence, Profile};
use crate::ladder::Run;
use crate::{CONVERGENCE_ELEMENTS, LADDER_DEGREES, REFERENCE};
use companion::chapter::Chapter;
use iga_contact::error::Result;
use iga_contact::nurbs::Side;
use iga_contact::post::hertz::Hertz;
use iga_contact::post::relative;
use iga_contact::problem::Problem;
use iga_contact::report::drawing::{control_net, element_lines, field_cells, labelled, Placement};
use iga_contact::report::plot::{
    field_figure, geometry_figure, line_chart, Axes, LineKind, Polyline, Series, BLACK_INDEX,
};
use iga_contact::report::table::{Column, Format, Table, Unit};
use iga_contact::report::vtu::sample_bodies;

/// The solution on the paper's mesh for a viewer (Fig. H3 is drawn from
/// the same run).
pub fn write_vtu(chapter: &Chapter, default: &Run) -> Result<()> {
    sample_bodies(
        &default.problem.bodies,
        &default.problem.map,
        &default.solution.full,
        4,
    )?
    .write(chapter.path("hertz.vtu"))
}

// ANCHOR: figures
/// Fig. 4: elements, control net, slave arc, symmetry line and floor.
pub fn model_figure(chapter: &Chapter, problem: &Problem) -> Result<()> {
    let patch = &problem.bodies[0].space.patch;
    let mut lines = labelled(element_lines(patch, LineKind::Thin, 0), "elements");
    lines.extend(labelled(control_net(patch, 1), "control net"));
    let slave = patch.side_curve(Side::EtaMin);
    let (a, b) = (slave.knots.first(), slave.knots.last());
    let arc = (0..=64)
        .map(|i| slave.point(a + (b - a) * i as f64 / 64.0))
        .collect();
    lines.push(Polyline::new(arc, LineKind::Solid, 3).labelled("slave side Γc (eta_min)"));
    let top = patch.point(patch.knots[0].first(), patch.knots[1].last());
    lines.push(
        Polyline::new(vec![[0.0, 0.0], top], LineKind::Dashed, 2)
            .labelled("symmetry line, u_x = 0"),
    );
    lines.push(floor(patch.points.iter().map(|p| p[0]).fold(0.0, f64::max)));
    let [e0, e1] = problem.bodies[0].space.n_elements();
    geometry_figure(
        chapter.path("model.svg"),
        &format!("Half disk, p = 2, {e0}×{e1} elements, on a rigid floor"),
        &lines,
    )
}

fn floor(width: f64) -> Polyline {
    Polyline::new(
        vec![[-0.1 * width, 0.0], [1.1 * width, 0.0]],
        LineKind::Solid,
        BLACK_INDEX,
    )
    .labelled("rigid floor y = 0")
}

/// Fig. 5: u_y on the deformed half disk (true scale).
pub fn uy_figure(chapter: &Chapter, r: &Run) -> Result<()> {
    let cells = field_cells(&r.problem, &r.solution.full, 6, Placement::Deformed, |q| {
        q.displacement[1] * 1e3
    })?;
    let patch = &r.problem.bodies[0].space.patch;
    let overlay = vec![
        Polyline::new(patch.outline(64), LineKind::Dashed, BLACK_INDEX).labelled("undeformed"),
        floor(patch.points.iter().map(|p| p[0]).fold(0.0, f64::max)),
    ];
    let [e0, e1] = r.problem.bodies[0].space.n_elements();
    field_figure(
        chapter.path("uy.svg"),
        &format!("Vertical displacement on the deformed half disk (true scale), p = 2, {e0}×{e1}"),
        "u_y (mm)",
        &cells,
        &overlay,
    )
}

/// Table 2 as a picture: the relative residual of both 8×8 histories.
pub fn residual_figure(chapter: &Chapter, paper: &Run, default: &Run) -> Result<()> {
    let series = |name: &str, r: &Run| {
        let pts = r
            .solution
            .history
            .rows
            .iter()
            .map(|row| (row.iteration as f64, row.relative_residual))
            .collect();
        Series::line(name, pts).with_markers()
    };
    line_chart(
        chapter.path("iterations_8x8.svg"),
        &Axes {
            title: "BFGS on 8×8, p = 2: each residual relative to its own first".into(),
            x_label: "iteration".into(),
            y_label: "‖R‖ / ‖R₀‖ (dimensionless)".into(),
            log_x: false,
            log_y: true,
        },
        &[
            series("paper's iteration: full steps, whole body", paper),
            series("default: full steps, contact layer", default),
        ],
    )
}

/// Fig. 6a, 6b and the errors against the reference.
pub fn convergence_figures(chapter: &Chapter, study: &Convergence, exact: &Hertz) -> Result<()> {
    let rows = &study.rows;
    let (rp0, ra) = (study.reference.p0, study.reference.half_width);
    let xs = [CONVERGENCE_ELEMENTS[0] as f64, REFERENCE.1 as f64];
    let reference = format!("reference (p = {}, {}²)", REFERENCE.0, REFERENCE.1);
    let horizontal =
        |name: String, y: f64| Series::line(name, xs.iter().map(|&x| (x, y)).collect()).dashed();
    for (file, title, label, value, hertz, refv) in [
        (
            "half_width.svg",
            "Contact half-width against the mesh",
            "a (mm)",
            1,
            exact.half_width * 1e3,
            ra * 1e3,
        ),
        (
            "peak_pressure.svg",
            "Peak contact pressure against the mesh",
            "p₀ (MPa)",
            0,
            exact.p0 * 1e-6,
            rp0 * 1e-6,
        ),
    ] {
        let mut series: Vec<Series> = LADDER_DEGREES
            .iter()
            .map(|&p| {
                let pts = rows
                    .iter()
                    .filter(|r| r.degree == p)
                    .map(|r| {
                        let m = r.measured;
                        let y = if value == 0 {
                            m.p0 * 1e-6
                        } else {
                            m.half_width * 1e3
                        };
                        (r.elements as f64, y)
                    })
                    .collect();
                Series::line(format!("IGA p = {p}"), pts).with_markers()
            })
            .collect();
        series.push(horizontal("Hertz".into(), hertz));
        series.push(horizontal(reference.clone(), refv));
        line_chart(
            chapter.path(file),
            &Axes {
                title: title.into(),
                x_label: "elements per direction".into(),
                y_label: label.into(),
                log_x: true,
                log_y: false,
            },
            &series,
        )?;
    }
    let mut series = Vec::new();
    for p in LADDER_DEGREES {
        let mine: Vec<_> = rows
            .iter()
            .filter(|r| r.degree == p && (p, r.elements) != REFERENCE)
            .collect();
        let p0 = mine
            .iter()
            .map(|r| (r.elements as f64, relative(r.measured.p0, rp0).abs()))
            .collect();
        let a = mine
            .iter()
            .map(|r| (r.elements as f64, relative(r.measured.half_width, ra).abs()))
            .collect();
        series.push(Series::line(format!("p₀, p = {p}"), p0).with_markers());
        series.push(
            Series::line(format!("a, p = {p}"), a)
                .with_markers()
                .dashed(),
        );
    }
    line_chart(
        chapter.path("errors.svg"),
        &Axes {
            title: format!("Error against the {reference}"),
            x_label: "elements per direction".into(),
            y_label: "relative error".into(),
            log_x: true,
            log_y: true,
        },
        &series,
    )
}
// ANCHOR_END: figures

/// The dense profiles as a table and a figure, up to 1.5 a.
pub fn profile_outputs(chapter: &mut Chapter, profiles: &[Profile], exact: &Hertz) -> Result<()> {
    let x_max = 1.5 * exact.half_width;
    let mut t = Table::new(vec![
        Column::plain("elements", "elements"),
        Column::new("x", "x", Unit::Millimetre, Format::Fixed(3)),
        Column::new("pressure", "pressure", Unit::Megapascal, Format::Fixed(4)),
        Column::new("hertz", "Hertz", Unit::Megapascal, Format::Fixed(4)),
    ]);
    let mut series = Vec::new();
    for Profile { elements, profile } in profiles {
        let n = *elements;
        let samples: Vec<_> = profile.pair(0).iter().filter(|s| s.x[0] <= x_max).collect();
        for s in &samples {
            t.push(vec![
                n.into(),
                s.x[0].into(),
                s.pressure().into(),
                exact.pressure(s.x[0]).into(),
            ])?;
        }
        let pts = samples
            .iter()
            .map(|s| (s.x[0] * 1e3, s.pressure() * 1e-6))
            .collect();
        series.push(Series::line(format!("IGA p = 2, {n}×{n}"), pts));
    }
    let ellipse = (0..=300)
        .map(|i| {
            let x = x_max * i as f64 / 300.0;
            (x * 1e3, exact.pressure(x) * 1e-6)
        })
        .collect();
    series.push(Series::line("Hertz p₀√(1 − x²/a²)", ellipse).dashed());
    // CSV only: the Markdown would be thousands of rows
    chapter.csv("pressure_profile", &t)?;
    line_chart(
        chapter.path("pressure_profile.svg"),
        &Axes {
            title: "Contact pressure along the floor".into(),
            x_label: "x (mm)".into(),
            y_label: "pressure (MPa)".into(),
            log_x: false,
            log_y: false,
        },
        &series,
    )
}
