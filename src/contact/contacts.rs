//! The contacts as the user wrote them. A contact whose slave boundary runs
//! over several patches is several [`super::ContactPair`]s, one per patch
//! side, consecutive and joined end to end; what is reported about the
//! contact (a warning, its count of points, its remedy, where its zone
//! ends) is about the whole boundary, not about one piece of it, and names
//! the contact by the user's index.

use crate::error::{Error, Result};
use std::ops::Range;

/// Which consecutive pairs make up each contact.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Contacts {
    /// The pairs of contact `c`: `ranges[c]`; together they cover
    /// `0..pairs`, in order, none empty.
    ranges: Vec<Range<usize>>,
}

impl Contacts {
    /// Each of `pairs` pairs a contact of its own (a problem built pair by
    /// pair, or a scene whose slave boundaries are each one patch side).
    pub fn each_pair(pairs: usize) -> Self {
        Self {
            ranges: (0..pairs).map(|k| k..k + 1).collect(),
        }
    }

    /// Contacts of `sizes[c]` consecutive pairs each, in order.
    pub fn of_sizes(sizes: &[usize]) -> Result<Self> {
        let mut at = 0;
        let mut ranges = Vec::with_capacity(sizes.len());
        for (c, &n) in sizes.iter().enumerate() {
            if n == 0 {
                return Err(Error::invalid(
                    format!("contact[{c}]"),
                    "0 pairs",
                    "a contact has at least one slave side",
                ));
            }
            ranges.push(at..at + n);
            at += n;
        }
        Ok(Self { ranges })
    }

    /// The number of contacts.
    pub fn len(&self) -> usize {
        self.ranges.len()
    }

    pub fn is_empty(&self) -> bool {
        self.ranges.is_empty()
    }

    /// The number of pairs over all contacts.
    pub fn pairs(&self) -> usize {
        self.ranges.last().map_or(0, |r| r.end)
    }

    /// The pairs of contact `c`, in order along its slave boundary.
    pub fn pieces(&self, c: usize) -> Range<usize> {
        self.ranges[c].clone()
    }

    /// The contact that pair `pair` is a piece of.
    pub fn of(&self, pair: usize) -> usize {
        self.ranges.partition_point(|r| r.end <= pair)
    }

    /// Every contact with its pairs.
    pub fn iter(&self) -> impl Iterator<Item = (usize, Range<usize>)> + '_ {
        self.ranges.iter().cloned().enumerate()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pairs_map_to_the_contact_they_are_a_piece_of() {
        let c = Contacts::of_sizes(&[1, 3, 2]).unwrap();
        assert_eq!(c.len(), 3);
        assert_eq!(c.pairs(), 6);
        let owners: Vec<usize> = (0..6).map(|k| c.of(k)).collect();
        assert_eq!(owners, [0, 1, 1, 1, 2, 2]);
        assert_eq!(c.pieces(1), 1..4);
        let each = Contacts::each_pair(3);
        assert_eq!((0..3).map(|k| each.of(k)).collect::<Vec<_>>(), [0, 1, 2]);
        assert!(Contacts::of_sizes(&[2, 0]).is_err());
        assert!(Contacts::of_sizes(&[]).unwrap().is_empty());
    }
}
