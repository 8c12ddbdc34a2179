//! "Where the map is singular": the degenerate corner of the Hertz disk.

use crate::ratios::{ratio, Survey};
use companion::Facts;
use iga_contact::error::Result;
use iga_contact::report::table::Format;

// ANCHOR: corner
/// "Where the map is singular": the degenerate corner of the nine-point
/// disk. The Jacobian of the disk's map vanishes at the end of the slave
/// arc, so the normal stress of the last element's shape functions grows
/// without bound there.
pub fn record_corner_facts(f: &mut Facts, survey: &Survey) -> Result<()> {
    let corner = &survey.corner;
    let (f2, s2) = (&corner[1].first_touch, &corner[1].smallest); // p = 2, 16²
    f.number("corner_ratio_p2", ratio(s2), Format::Pow10(0))?;
    f.number(
        "corner_ct_growth_p2",
        s2.trace_constant / f2.trace_constant,
        Format::Pow10(0),
    )?;
    f.number("corner_gap_mm", s2.g0 * 1e3, Format::Fixed(0))?;
    f.number(
        "corner_angle_deg",
        (s2.x[0] / 0.2).asin().to_degrees(),
        Format::Fixed(0),
    )?;
    let worst = corner
        .iter()
        .map(|c| ratio(&c.smallest))
        .fold(f64::INFINITY, f64::min);
    f.number("corner_ratio_min", worst, Format::Pow10(0))?;
    // away from the singular corner: the smallest ratio over the regular
    // points of the Hertz side (16², every degree), in units of the bound of
    // θ = 1 and of θ = 0
    f.number("hertz_regular_min", survey.regular_min, Format::Fixed(2))?;
    f.number(
        "hertz_regular_min_theta0",
        4.0 * survey.regular_min,
        Format::Fixed(2),
    )?;
    f.number(
        "hertz_singular_points",
        survey.singular_points as f64,
        Format::Fixed(0),
    )
}
// ANCHOR_END: corner
