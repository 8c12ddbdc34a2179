//! Contacts that repeat one another: two `[[contact]]` entries on one
//! slave side against one master (or against rigid segments where one
//! hides the other) model one contact twice. The Nitsche terms then add
//! up wherever both are active, which with a penalty is within |σ_n|/γ of
//! either obstacle, the pressure is shared between the entries, and the
//! summary reports parts of one answer (measured by a new user: a second
//! floor 1e-4 below the first carried 37.5 % of the load), so the scene is
//! refused before anything is built.

use super::{MasterSpec, Scene, SlaveAt};
use crate::error::{Error, Result};
use crate::nurbs::Side;
use std::collections::HashMap;

impl Scene {
    /// Refuses contact `j` when an earlier contact `i` has the same slave
    /// body, shares a slave piece (patch, side) with it, and has the same
    /// master (the same side of the same body, or a rigid segment in the
    /// same direction on the same or a parallel line, overlapping `i`'s),
    /// or when `j` is `i` with slave and master swapped.
    pub(super) fn refuse_repeated_contacts(&self, names: &HashMap<&str, usize>) -> Result<()> {
        let pieces: Vec<Vec<(usize, Side)>> = self
            .contacts
            .iter()
            .enumerate()
            .map(|(i, c)| match &c.slave_at {
                &SlaveAt::Side(side) => Ok(vec![(0, side)]),
                SlaveAt::Boundary(name) => {
                    let b = names[c.slave.as_str()];
                    self.boundary_of(b, &format!("contact[{i}].slave_boundary"), name)
                }
            })
            .collect::<Result<_>>()?;
        for j in 1..self.contacts.len() {
            for i in 0..j {
                let (a, b) = (&self.contacts[i], &self.contacts[j]);
                let shared = a.slave == b.slave && pieces[i].iter().any(|p| pieces[j].contains(p));
                if swapped(a, b) {
                    return Err(Error::invalid(
                        format!("contact[{j}]"),
                        format!("slave {:?} against the slave of contact[{i}]", b.slave),
                        format!(
                            "contact[{i}] already joins these two sides with the roles \
                             swapped, and the two contacts add their Nitsche terms on one \
                             interface, each with its full weight: keep one of them, and set \
                             `nitsche.sides = \"unbiased\"` on it for the form that treats \
                             both bodies alike"
                        ),
                    ));
                }
                if !shared {
                    continue;
                }
                let why = match same_obstacle(&a.master, &b.master) {
                    Some(Overlap::Same) => "already joins this slave side to this master",
                    Some(Overlap::Parallel) => {
                        "joins this slave side to a rigid segment that overlaps this one in \
                         the same direction, on a line within a thousandth of its direction, \
                         so one hides the other (the slave reaches the farther only through \
                         the nearer)"
                    }
                    None => continue,
                };
                return Err(Error::invalid(
                    format!("contact[{j}]"),
                    format!("slave {:?} against the master of contact[{i}]", b.slave),
                    format!(
                        "contact[{i}] {why}; the two contacts add their Nitsche terms where \
                         both are active, and the pressure is shared between them: keep one \
                         of them (or give contact[{j}] a master that does not overlap)"
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// Whether `b` is `a` with slave and master swapped: `b`'s slave is `a`'s
/// master body, on the side `a` names, and `b`'s master is `a`'s slave
/// side. (A master is one patch, so both sides are sides of one-patch
/// bodies.)
fn swapped(a: &super::ContactSpec, b: &super::ContactSpec) -> bool {
    match (&a.master, &b.master) {
        (
            MasterSpec::Body {
                body: am,
                side: a_side,
            },
            MasterSpec::Body {
                body: bm,
                side: b_side,
            },
        ) => {
            *bm == a.slave
                && *am == b.slave
                && a.slave_at == SlaveAt::Side(*b_side)
                && b.slave_at == SlaveAt::Side(*a_side)
        }
        _ => false,
    }
}

/// How two masters of one slave stretch coincide.
enum Overlap {
    /// The same side of the same body, or one rigid line.
    Same,
    /// Rigid segments on parallel lines (or one line, at an angle within
    /// round-off of a drawn coordinate), one direction, overlapping.
    Parallel,
}

/// The sine of the angle below which two rigid segments count as parallel:
/// a segment whose end is off by 1e-6 over a metre (a coordinate typed to
/// six digits) is the same line's direction, and a V-groove's sides are
/// degrees apart.
const PARALLEL: f64 = 1e-3;

/// Whether two masters are one obstacle where they could both touch a
/// slave, or one hides the other: the same side of one body, or rigid
/// segments in one direction on parallel lines, overlapping over a positive
/// length (the nearer hides the farther over the overlap).
fn same_obstacle(a: &MasterSpec, b: &MasterSpec) -> Option<Overlap> {
    match (a, b) {
        (MasterSpec::Body { body: x, side: s }, MasterSpec::Body { body: y, side: t }) => {
            (x == y && s == t).then_some(Overlap::Same)
        }
        (
            MasterSpec::RigidSegment { from: a0, to: a1 },
            MasterSpec::RigidSegment { from: b0, to: b1 },
        ) => {
            let d = [a1[0] - a0[0], a1[1] - a0[1]];
            let e = [b1[0] - b0[0], b1[1] - b0[1]];
            let (la, lb) = (d[0].hypot(d[1]), e[0].hypot(e[1]));
            let cross = d[0] * e[1] - d[1] * e[0];
            let dot = d[0] * e[0] + d[1] * e[1];
            // the opposite direction is a ceiling, refused on its own
            if dot <= 0.0 || cross.abs() > PARALLEL * la * lb {
                return None;
            }
            // positions along a's direction, a from 0 to 1
            let len2 = la * la;
            let at = |p: &[f64; 2]| ((p[0] - a0[0]) * d[0] + (p[1] - a0[1]) * d[1]) / len2;
            let (s, t) = (at(b0), at(b1));
            if t.min(1.0) - s.max(0.0) <= 1e-9 {
                return None;
            }
            // off a's line by more than round-off of its length
            let off =
                |p: &[f64; 2]| ((p[0] - a0[0]) * d[1] - (p[1] - a0[1]) * d[0]).abs() > 1e-9 * len2;
            Some(if off(b0) || off(b1) {
                Overlap::Parallel
            } else {
                Overlap::Same
            })
        }
        _ => None,
    }
}
