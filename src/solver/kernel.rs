//! The kernels (17)–(18) of one solve: the tied kernel, the secant
//! kernels with the floating guard, and which active set a secant kernel
//! is built for: the set of its iterate, with the growth since the last
//! kernel cut after a full step ([`cut_growth`], [`super::Growth`]; why, in
//! [`super::newton`]). How each is factorised: [`factor_kernel`].

pub use super::factorise::{factor_kernel, Factorisation};
use super::guard::Guard;
use super::history::Event;
use super::options::{Growth, Start};
use super::system::{LinearSolve, System};
use super::vector::dot;
use crate::contact::nitsche::heaviside;
use crate::error::Result;
use crate::problem::Problem;
use std::rc::Rc;

/// A kernel ready for solves, with the activity it was built for and the
/// points the floating guard forced active.
pub(crate) struct Built<'p> {
    pub factor: Rc<dyn LinearSolve + 'p>,
    pub activity: Vec<f64>,
    /// Per point: forced active by the guard (empty: none).
    pub forced: Vec<bool>,
    /// The points with P ≤ 0 left out by [`cut_growth`].
    pub dropped: Vec<usize>,
}

impl Built<'_> {
    pub fn guarded(&self) -> bool {
        self.forced.iter().any(|&f| f)
    }

    /// The residual a step with this kernel follows from `u` (residual
    /// `r`): that of the kernel's own active set, the guard's points under
    /// the tied law and the dropped points open, so that a full step lands
    /// on the root of the kernel's linear piece.
    pub fn drive(&self, sys: &dyn System<'_>, u: &[f64], r: &[f64]) -> Vec<f64> {
        let mut drive = if self.guarded() {
            sys.residual_forced(u, &self.forced).0
        } else {
            r.to_vec()
        };
        if !self.dropped.is_empty() {
            for (d, e) in drive.iter_mut().zip(sys.released(u, &self.dropped)) {
                *d += e;
            }
        }
        drive
    }
}

/// The contact points of each side of each pair, in the order of the
/// slave parameter t: the lines along which a contact zone is a run of
/// consecutive active points.
pub fn lines(problem: &Problem) -> Vec<Vec<usize>> {
    let mut keys: Vec<(usize, bool)> = Vec::new();
    let mut out: Vec<Vec<usize>> = Vec::new();
    for (q, cp) in problem.points.iter().enumerate() {
        let key = (cp.pair, cp.role == crate::contact::Role::Slave);
        match keys.iter().position(|k| *k == key) {
            Some(i) => out[i].push(q),
            None => {
                keys.push(key);
                out.push(vec![q]);
            }
        }
    }
    for line in &mut out {
        line.sort_by(|&a, &b| problem.points[a].t.total_cmp(&problem.points[b].t));
    }
    out
}

/// The active set `next` with every run of points it adds along a line
/// next to exactly one zone (active run) of `kernel` cut to the fraction
/// `kept` (rounded up, so at least one point) nearest that zone. Added runs
/// that start a new zone or fill a hole between two zones are kept whole,
/// and releases are kept.
///
/// Why: a full semismooth Newton step from the kernel's active set A lands
/// on the root of A's linear piece, so the undamped iteration is the map
/// A ↦ {P(u(A)) ≤ 0}, and on the disk on the block (`examples/iterations.rs`,
/// modes `map` and `emulate`) it is lopsided. From a zone too short, the
/// root penetrates beyond its edge over about as far again as the zone is
/// short (from 5 points short, 5 too many at factor 20; further at small
/// penalties and from far below), so the edge the root wants lies a little
/// less than halfway. From a zone too long, the root pulls only at its last
/// point or two, often leaving islands of active points outside the zone,
/// so a zone entered from above shrinks a point or two per step: the 20–40
/// iterations of the disk on the block, whose balanced start lies below the
/// root and whose first step overshoots to about twice it. Keeping 40 % of
/// the growth keeps the iterates below each edge and closes on it
/// geometrically; 50 % lands above it from the far-too-small starts of a
/// stiff penalty (measured on 128², factor 20: 23 maps against 6), 33 %
/// slows the approach from below (8–9 maps). A set equal to its own next
/// set, a root's, is left alone, so the roots are those of the plain
/// iteration.
pub fn cut_growth(kernel: &[bool], next: &[bool], lines: &[Vec<usize>], kept: f64) -> Vec<bool> {
    let mut out = next.to_vec();
    for line in lines {
        let n = line.len();
        let added = |i: usize| next[line[i]] && !kernel[line[i]];
        let mut i = 0;
        while i < n {
            if !added(i) {
                i += 1;
                continue;
            }
            let start = i;
            while i < n && added(i) {
                i += 1;
            }
            let end = i;
            let keep = ((end - start) as f64 * kept).ceil() as usize;
            let before = start > 0 && kernel[line[start - 1]];
            let after = end < n && kernel[line[end]];
            let dropped = match (before, after) {
                (true, false) => start + keep..end,
                (false, true) => start..end - keep,
                _ => 0..0,
            };
            for k in dropped {
                out[line[k]] = false;
            }
        }
    }
    out
}

/// The fraction of an added run that [`cut_growth`] keeps.
pub const KEPT: f64 = 0.4;

/// The kernels of one solve: the tied kernel (17) and secant kernels (18)
/// with the floating guard, counted, and the active sets they were built
/// for (to detect a cycle).
pub(crate) struct Kernels<'s, 'p> {
    pub sys: &'s mut dyn System<'p>,
    guard: Guard,
    pub factorisations: usize,
    built: Vec<Vec<bool>>,
    /// The contact lines ([`lines`]).
    lines: Vec<Vec<usize>>,
    /// Whether the secant kernels cut the growth ([`cut_growth`]).
    cut: bool,
}

impl<'s, 'p> Kernels<'s, 'p> {
    /// The kernels of one start: `growth` resolved for `start`.
    pub fn new(
        sys: &'s mut dyn System<'p>,
        problem: &Problem,
        growth: Growth,
        start: Start,
    ) -> Self {
        Self {
            sys,
            guard: Guard::new(problem),
            factorisations: 0,
            built: Vec::new(),
            lines: lines(problem),
            cut: growth.cuts(start),
        }
    }

    /// Whether the last kernel built revisits the active set of an
    /// earlier one (not the one just before it).
    pub fn cycled(&self) -> bool {
        match self.built.split_last() {
            Some((last, earlier)) if earlier.len() >= 2 => {
                earlier[..earlier.len() - 1].contains(last)
            }
            _ => false,
        }
    }

    fn build(
        &mut self,
        h: Vec<f64>,
        forced: Vec<bool>,
        dropped: Vec<usize>,
        events: &mut Vec<Event>,
    ) -> Result<Built<'p>> {
        self.factorisations += 1;
        self.built.push(h.iter().map(|&v| v > 0.5).collect());
        Ok(Built {
            factor: self.sys.factor(&h, events)?,
            activity: h,
            forced,
            dropped,
        })
    }

    /// The tied kernel (17): every point active.
    pub fn tied(&mut self, events: &mut Vec<Event>) -> Result<Built<'p>> {
        self.build(
            vec![1.0; self.guard.points()],
            Vec::new(),
            Vec::new(),
            events,
        )
    }

    /// The secant kernel (18) at `u`. If its active set does not hold a
    /// floating body, the guard adds the nearest points
    /// ([`Event::FloatingGuard`]). With the growth cut and `full` (u is a
    /// full step from the last kernel), the points the active set adds are
    /// cut as [`cut_growth`] says.
    pub fn secant(&mut self, u: &[f64], full: bool, events: &mut Vec<Event>) -> Result<Built<'p>> {
        let mut p = self.sys.p_values(u);
        let mut h: Vec<f64> = p.iter().map(|&v| heaviside(v)).collect();
        let mut dropped = Vec::new();
        if let (true, true, Some(last)) = (self.cut, full, self.built.last()) {
            let next: Vec<bool> = h.iter().map(|&v| v > 0.5).collect();
            let cut = cut_growth(last, &next, &self.lines, KEPT);
            for (q, (&c, &n)) in cut.iter().zip(&next).enumerate() {
                if n && !c {
                    h[q] = 0.0;
                    dropped.push(q);
                    // for the guard, an open point nearest the obstacle
                    p[q] = p[q].abs().max(f64::MIN_POSITIVE);
                }
            }
        }
        let chosen = self.guard.select(&p);
        let mut forced = Vec::new();
        if !chosen.is_empty() {
            events.push(Event::FloatingGuard);
            forced = vec![false; p.len()];
            for q in chosen {
                h[q] = 1.0;
                forced[q] = true;
            }
        }
        dropped.retain(|&q| h[q] < 0.5);
        self.build(h, forced, dropped, events)
    }

    /// The first kernel of `start` at `u` (residual `r`). For
    /// [`Start::Secant`], `u` and `r` are first shifted rigidly by
    /// [`Kernels::balance`].
    pub fn start(
        &mut self,
        start: Start,
        u: &mut [f64],
        r: &mut Vec<f64>,
        events: &mut Vec<Event>,
    ) -> Result<Built<'p>> {
        match start {
            Start::Tied => self.tied(events),
            Start::Secant => {
                if self.balance(u, r) {
                    *r = self.sys.residual_forced(u, &[]).0;
                }
                self.secant(u, false, events)
            }
        }
    }

    /// Shifts `u` rigidly along the floating modes so that the load along
    /// each is balanced by the contact forces; returns whether it moved.
    pub fn balance(&self, u: &mut [f64], r: &[f64]) -> bool {
        if self.guard.modes.is_empty() {
            return false;
        }
        let modes: Vec<Vec<f64>> = self
            .guard
            .modes
            .iter()
            .map(|m| self.sys.coords(m))
            .collect();
        let f0: Vec<f64> = modes.iter().map(|m| dot(m, r)).collect();
        let t = self.guard.balance(&self.sys.p_values(u), &f0);
        let mut moved = false;
        for (m, tk) in modes.iter().zip(&t) {
            if *tk != 0.0 {
                moved = true;
                for (ui, mi) in u.iter_mut().zip(m) {
                    *ui += tk * mi;
                }
            }
        }
        moved
    }

    /// The activity H(P(u)) at `u`.
    pub fn activity(&self, u: &[f64]) -> Vec<f64> {
        self.sys.p_values(u).into_iter().map(heaviside).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn set(s: &str) -> Vec<bool> {
        s.chars().map(|c| c == '#').collect()
    }

    /// On one line: growth next to one zone keeps its 40 % (rounded up)
    /// nearest the zone, on either side; a new zone, a filled hole and the
    /// releases are kept; a set equal to the kernel's is left alone.
    #[test]
    fn growth_is_cut_next_to_a_zone_only() {
        let line = vec![(0..20).collect::<Vec<usize>>()];
        let cut = |a: &str, b: &str| {
            let out = cut_growth(&set(a), &set(b), &line, KEPT);
            out.iter()
                .map(|&x| if x { '#' } else { '.' })
                .collect::<String>()
        };
        // three added on the left: two kept; one on the right: kept; five
        // on the right: two kept
        assert_eq!(
            cut("...#####............", "#########..........."),
            ".########..........."
        );
        assert_eq!(
            cut("..####..............", "..#########........."),
            "..######............"
        );
        // a hole filled between two zones, a new zone, a release
        assert_eq!(
            cut("##..##..........#...", "######.....###......"),
            "######.....###......"
        );
        // one point added: kept (the edge moves by at least one point)
        assert_eq!(
            cut("####................", "#####..............."),
            "#####..............."
        );
        let root = "..######............";
        assert_eq!(cut(root, root), root);
    }

    /// The points of a line are taken in the order of t, whatever their
    /// order in the problem.
    #[test]
    fn lines_follow_the_slave_parameter() {
        let line = vec![vec![3, 0, 2, 1]];
        // along t: 3 0 2 1; the kernel holds 3, the map adds 0 2 1
        let a = [false, false, false, true];
        let b = [true, true, true, true];
        let out = cut_growth(&a, &b, &line, KEPT);
        // 40 % of 3 rounded up: 2 points nearest the zone (0 and 2)
        assert_eq!(out, vec![true, false, true, true]);
    }
}
