//! Pixel layout: where title, legend, plot, label areas and colour bar go,
//! sized from the measured text so that nothing overlaps.

use super::bounds::Bounds;
use super::font::{text_size, DESC_SIZE, TICK_SIZE, TITLE_SIZE};
use super::legend::{legend_rows, LEGEND_ROW};
use super::ticks::Ticks;
use super::LegendEntry;

pub(super) const WIDTH: u32 = 800;
pub(super) const LINE_CHART_HEIGHT: u32 = 600;
pub(super) const PAD: i32 = 12;
/// Room right of the plot for half of the last x tick label.
const RIGHT_PAD: i32 = 30;
pub(super) const TICK_MARK: i32 = 5;

/// Bounds of the plot height of equal-aspect figures: a slender body should
/// not produce a ribbon nor a tower.
const MIN_PLOT_HEIGHT: i32 = 240;
const MAX_PLOT_HEIGHT: i32 = 620;

/// Pixel layout of a figure: title, legend strip, one plot with its label
/// areas, and optionally a colour bar to the right.
#[derive(Clone, Debug)]
pub(super) struct Frame {
    pub(super) size: (u32, u32),
    pub(super) title: String,
    pub(super) legend: Vec<LegendEntry>,
    pub(super) rows: Vec<Vec<usize>>,
    pub(super) legend_top: i32,
    /// Plot area: left, top, width, height.
    pub(super) plot: (i32, i32, i32, i32),
    pub(super) y_area: i32,
    pub(super) x_area: i32,
    pub(super) x_desc: String,
    pub(super) y_desc: String,
    pub(super) x_ticks: Ticks,
    pub(super) y_ticks: Ticks,
    pub(super) x_range: Bounds,
    pub(super) y_range: Bounds,
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
    pub(super) fn fixed(
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
    pub(super) fn equal_aspect(
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
