//! Colours: the palette lines and series are drawn from, the viridis map of
//! scalar fields, and the greys of the grid.

use plotters::style::RGBColor;

/// Colours addressed by [`Polyline::color`](super::Polyline::color): the
/// ten "tab10" colours (series of a line chart use them in order), then
/// black (index 10) and white (11).
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

pub(super) const GRID_MAJOR: RGBColor = RGBColor(0xdd, 0xdd, 0xdd);
pub(super) const GRID_MINOR: RGBColor = RGBColor(0xf0, 0xf0, 0xf0);

pub(super) fn palette(index: usize) -> RGBColor {
    let (r, g, b) = PALETTE[index % PALETTE.len()];
    RGBColor(r, g, b)
}

/// A colour of a figure: an entry of [`PALETTE`] (taken modulo its length)
/// or one of its own, such as the grey of guide lines.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Color {
    Palette(usize),
    Rgb(u8, u8, u8),
}

impl Color {
    pub(super) fn rgb(self) -> RGBColor {
        match self {
            Color::Palette(index) => palette(index),
            Color::Rgb(r, g, b) => RGBColor(r, g, b),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn viridis_ends() {
        assert_eq!(viridis(0.0), (0x44, 0x01, 0x54));
        assert_eq!(viridis(1.0), (0xfd, 0xe7, 0x25));
        assert_eq!(viridis(f64::NAN), viridis(0.0));
    }
}
