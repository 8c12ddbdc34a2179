//! Contacts that repeat one another: two `[[contact]]` entries on one
//! stretch of a slave side against one master model the same contact
//! twice. The Nitsche terms then add up, each entry carries half of the
//! pressure, and the summary reports two half answers, so the scene is
//! refused before anything is built.

use super::{MasterSpec, Scene};
use crate::error::{Error, Result};
use crate::nurbs::Side;
use std::collections::HashMap;

impl Scene {
    /// Refuses contact `j` when an earlier contact `i` has the same slave
    /// body, shares a slave piece (patch, side) with it, and has the same
    /// master: the same side of the same body, or a rigid segment on the
    /// same line as `i`'s, with the same direction, that overlaps it.
    pub(super) fn refuse_repeated_contacts(&self, names: &HashMap<&str, usize>) -> Result<()> {
        let pieces: Vec<Vec<(usize, Side)>> = self
            .contacts
            .iter()
            .enumerate()
            .map(|(i, c)| match (c.slave_side, &c.slave_boundary) {
                (Some(side), _) => Ok(vec![(0, side)]),
                (None, Some(name)) => {
                    let b = names[c.slave.as_str()];
                    self.boundary_of(b, &format!("contact[{i}].slave_boundary"), name)
                }
                (None, None) => Ok(Vec::new()),
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
                if shared && same_obstacle(&a.master, &b.master) {
                    return Err(Error::invalid(
                        format!("contact[{j}]"),
                        format!("slave {:?} against the master of contact[{i}]", b.slave),
                        format!(
                            "contact[{i}] already joins this stretch of the slave to this \
                             master, and two contacts on it add their Nitsche terms, so each \
                             would carry half of the pressure: keep one of them (or give \
                             contact[{j}] a master that does not overlap)"
                        ),
                    ));
                }
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
                && a.slave_side == Some(*b_side)
                && b.slave_side == Some(*a_side)
        }
        _ => false,
    }
}

/// Whether two masters are one obstacle where they could both touch a
/// slave: the same side of one body, or rigid segments on one line, in one
/// direction, overlapping over a positive length.
fn same_obstacle(a: &MasterSpec, b: &MasterSpec) -> bool {
    match (a, b) {
        (MasterSpec::Body { body: x, side: s }, MasterSpec::Body { body: y, side: t }) => {
            x == y && s == t
        }
        (
            MasterSpec::RigidSegment { from: a0, to: a1 },
            MasterSpec::RigidSegment { from: b0, to: b1 },
        ) => {
            let d = [a1[0] - a0[0], a1[1] - a0[1]];
            let len2 = d[0] * d[0] + d[1] * d[1];
            // off the line by more than round-off of the segment's length
            let off =
                |p: &[f64; 2]| ((p[0] - a0[0]) * d[1] - (p[1] - a0[1]) * d[0]).abs() > 1e-9 * len2;
            if off(b0) || off(b1) {
                return false;
            }
            // positions along a's direction, a from 0 to 1
            let at = |p: &[f64; 2]| ((p[0] - a0[0]) * d[0] + (p[1] - a0[1]) * d[1]) / len2;
            let (s, t) = (at(b0), at(b1));
            // the opposite direction is a ceiling, refused on its own
            s < t && t.min(1.0) - s.max(0.0) > 1e-9
        }
        _ => false,
    }
}
