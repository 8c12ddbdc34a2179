//! The free DOFs of a run counted from the scene alone, as the DOF map of
//! the solve numbers them: the control points of the refined patches, the
//! points a matching interface shares counted once, less the components
//! the supports prescribe. The estimate counted every patch's control
//! points in full, supports and shared points too (Hertz: 200 for the
//! solve's 190).
//!
//! Work and memory are O(patches + supports): each patch's control points
//! fall into its interior, which nothing shares or holds, the interiors of
//! its four sides and its four corners; an interface shares a side and
//! its two corners, a support holds sides and corners, so only those
//! pieces are tracked.

use super::super::validate::Valid;
use super::super::SupportAt;
use crate::error::Result;
use crate::nurbs::{NurbsPatch, Side};
use crate::resources::BodySize;

/// The pieces of every patch: 4 corners then 4 side interiors.
const PIECES: usize = 8;

/// Corner (ξ end, η end) of a patch, as a piece index.
fn corner(ci: usize, cj: usize) -> usize {
    ci + 2 * cj
}

fn side_index(s: Side) -> usize {
    4 + Side::ALL.iter().position(|&t| t == s).expect("a side")
}

/// The corners at the start and the end of `side`, in its parameter's order.
fn side_corners(side: Side) -> [usize; 2] {
    match side {
        Side::XiMin => [corner(0, 0), corner(0, 1)],
        Side::XiMax => [corner(1, 0), corner(1, 1)],
        Side::EtaMin => [corner(0, 0), corner(1, 0)],
        Side::EtaMax => [corner(0, 1), corner(1, 1)],
    }
}

/// The patches' pieces, joined where interfaces share them.
struct Pieces {
    parent: Vec<usize>,
    /// Control points of each piece.
    count: Vec<usize>,
    /// The components held, per piece (read at the root).
    held: Vec<[bool; 2]>,
}

impl Pieces {
    fn root(&mut self, mut a: usize) -> usize {
        while self.parent[a] != a {
            self.parent[a] = self.parent[self.parent[a]];
            a = self.parent[a];
        }
        a
    }

    fn unite(&mut self, a: usize, b: usize) {
        let (a, b) = (self.root(a), self.root(b));
        if a != b {
            self.parent[b.max(a)] = a.min(b);
        }
    }

    fn hold(&mut self, a: usize, comp: usize) {
        let r = self.root(a);
        self.held[r][comp] = true;
    }
}

impl Valid<'_> {
    /// The free DOFs of a run: `exact[i]` are scene body i's exact
    /// patches, `sizes` every patch's refined size (body by body), and
    /// `first[i]` the index in `sizes` of body i's first patch.
    pub(super) fn free_dofs(
        &self,
        exact: &[Vec<NurbsPatch>],
        sizes: &[BodySize],
        first: &[usize],
    ) -> Result<f64> {
        let n = sizes.len();
        let mut pieces = Pieces {
            parent: (0..PIECES * n).collect(),
            count: sizes
                .iter()
                .flat_map(|s| {
                    let inner = |d: usize| s.n[d].saturating_sub(2);
                    // XiMin and XiMax run along η, EtaMin and EtaMax along ξ
                    [1, 1, 1, 1, inner(1), inner(1), inner(0), inner(0)]
                })
                .collect(),
            held: vec![[false; 2]; PIECES * n],
        };
        // matching interfaces: sides of one body running between the same
        // two points (the build checks that they match)
        for (i, patches) in exact.iter().enumerate() {
            let size = patches
                .iter()
                .map(crate::interface::extent)
                .fold(0.0, f64::max);
            let tol = 1e-9 * size;
            let near = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]) <= tol;
            let ends = |p: &NurbsPatch, s: Side| {
                let idx = p.side_indices(s);
                [p.points[idx[0]], p.points[idx[idx.len() - 1]]]
            };
            for (a, pa) in patches.iter().enumerate() {
                for (b, pb) in patches.iter().enumerate().skip(a + 1) {
                    for sa in Side::ALL {
                        for sb in Side::ALL {
                            let ([a0, a1], [b0, b1]) = (ends(pa, sa), ends(pb, sb));
                            if near(a0, a1) || near(b0, b1) {
                                continue; // a collapsed side meets nothing
                            }
                            let reversed = if near(a0, b0) && near(a1, b1) {
                                false
                            } else if near(a0, b1) && near(a1, b0) {
                                true
                            } else {
                                continue;
                            };
                            let (ga, gb) = (PIECES * (first[i] + a), PIECES * (first[i] + b));
                            pieces.unite(ga + side_index(sa), gb + side_index(sb));
                            let (ca, mut cb) = (side_corners(sa), side_corners(sb));
                            if reversed {
                                cb.reverse();
                            }
                            for k in 0..2 {
                                pieces.unite(ga + ca[k], gb + cb[k]);
                            }
                        }
                    }
                }
            }
        }
        let names = self.body_index();
        for (k, s) in self.supports.iter().enumerate() {
            let b = names[s.body.as_str()];
            let comp = s.component.index();
            let sides: Vec<(usize, Side)> = match &s.at {
                &SupportAt::Side(side) => vec![(0, side)],
                SupportAt::Boundary(name) => {
                    self.boundary_of(b, &format!("support[{k}].boundary"), name)?
                }
                &SupportAt::Point(x) => {
                    if let Some((p, c)) = nearest_corner(&exact[b], x) {
                        pieces.hold(PIECES * (first[b] + p) + c, comp);
                    }
                    Vec::new()
                }
            };
            for (p, side) in sides {
                let g = PIECES * (first[b] + p);
                pieces.hold(g + side_index(side), comp);
                for c in side_corners(side) {
                    pieces.hold(g + c, comp);
                }
            }
        }
        let mut free = 0usize;
        for a in 0..PIECES * n {
            if pieces.root(a) == a {
                let held = pieces.held[a].iter().filter(|&&h| h).count();
                free += pieces.count[a] * (2 - held);
            }
        }
        let interiors: usize = sizes
            .iter()
            .map(|s| 2 * s.n[0].saturating_sub(2) * s.n[1].saturating_sub(2))
            .sum();
        Ok((free + interiors) as f64)
    }
}

/// The patch corner of `patches` nearest `x` (a point support holds the
/// corner control point there; the build refuses any other point).
fn nearest_corner(patches: &[NurbsPatch], x: [f64; 2]) -> Option<(usize, usize)> {
    let mut best: Option<(f64, usize, usize)> = None;
    for (p, patch) in patches.iter().enumerate() {
        let [n0, n1] = patch.n();
        for (ci, cj) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            let y = patch.points[patch.index(ci * (n0 - 1), cj * (n1 - 1))];
            let d = (y[0] - x[0]).hypot(y[1] - x[1]);
            if best.is_none_or(|b| d < b.0) {
                best = Some((d, p, corner(ci, cj)));
            }
        }
    }
    best.map(|(_, p, c)| (p, c))
}
