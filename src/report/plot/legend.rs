//! The legend strip between title and plot: its entries' extents and how
//! they break into rows.

use super::figure::stroke_of;
use super::font::{text_size, LEGEND_SIZE};
use super::{Color, LegendEntry, Polyline, Stroke};

pub(super) const LEGEND_SAMPLE: i32 = 36;
pub(super) const LEGEND_GAP: i32 = 8;
pub(super) const LEGEND_SPACING: i32 = 26;
pub(super) const LEGEND_ROW: i32 = 24;

impl LegendEntry {
    pub(super) fn extent(&self) -> i32 {
        LEGEND_SAMPLE + LEGEND_GAP + text_size(&self.label, LEGEND_SIZE).0
    }
}

/// Entries broken into rows no wider than `width`.
pub(super) fn legend_rows(entries: &[LegendEntry], width: i32) -> Vec<Vec<usize>> {
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

pub(super) fn polyline_legend(lines: &[Polyline]) -> Vec<LegendEntry> {
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
            color: Color::Palette(line.color),
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
