//! The one font every figure is measured and drawn with, and the text sizes.

use plotters::prelude::*;
use std::sync::Once;

/// Layout is measured with the bundled DejaVu Sans; naming it first in the
/// SVG makes viewers that have it reproduce that layout exactly, while the
/// generic fallback keeps the text sans-serif elsewhere.
pub(super) const FAMILY: &str = "DejaVu Sans, sans-serif";

pub(super) const TITLE_SIZE: f64 = 24.0;
pub(super) const DESC_SIZE: f64 = 20.0;
pub(super) const TICK_SIZE: f64 = 17.0;
pub(super) const LEGEND_SIZE: f64 = 17.0;

pub(super) static FONTS: Once = Once::new();

pub(super) fn ensure_fonts() {
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
pub(super) fn font(size: f64) -> FontDesc<'static> {
    ensure_fonts();
    FontDesc::new(FontFamily::Name(FAMILY), size, FontStyle::Normal)
}

pub(super) fn text_size(text: &str, size: f64) -> (i32, i32) {
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
