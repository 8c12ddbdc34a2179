//! Bodies, global degree-of-freedom numbering and Dirichlet conditions by
//! elimination.
//!
//! Global DOF `offset[b] + 2·A + c` is component c of control point A of
//! body b. Dirichlet conditions act on control-point values (the paper's
//! convention); they are eliminated, so the solved system holds only the
//! free DOFs and no large numbers ever enter the matrix.
//!
//! An elastic body of several patches is several [`Body`] entries, one
//! per patch, joined by [`DofMapBuilder::join`]: the control points that
//! two patches share on a matching interface keep one global DOF per
//! patch (so every per-patch loop reads its own numbering), and those
//! copies map to one free DOF, which makes the displacement C⁰ across.
//! Non-matching interfaces keep their DOFs apart and are recorded as
//! [`Tie`]s, which the assembly ties weakly, by Nitsche's method.

use crate::error::{Error, Result};
use crate::interface::{Interface, Tie};
use crate::material::{Formulation, Material};
use crate::nurbs::Side;
use crate::space::Space;

/// One elastic body: a discretised patch, its material and how its stress
/// is discretised.
#[derive(Clone, Debug)]
pub struct Body {
    pub name: String,
    pub space: Space,
    pub material: Material,
    pub formulation: Formulation,
}

const FIXED: usize = usize::MAX;

/// The map between global DOFs and the free (unknown) ones.
#[derive(Clone, Debug)]
pub struct DofMap {
    offsets: Vec<usize>,
    free_of: Vec<usize>,
    prescribed: Vec<f64>,
    n_free: usize,
    /// The elastic body (group of patches) of every patch.
    group_of: Vec<usize>,
    /// The class representative of every global DOF (itself unless a
    /// matching interface shares it).
    rep: Vec<usize>,
    /// The non-matching interfaces, tied weakly.
    ties: Vec<Tie>,
    tie_factor: f64,
}

/// The factor β of the tie's penalty γ = 0.1 β E (p + 1)(p + d)(1/h₁ + 1/h₂)
/// ([`crate::assembly::tie_stiffness`]): Eq. (11) with penalty factor β,
/// here ten times the paper's 1. The symmetric tie is stable only above a multiple of the trace
/// constant of the two sides' elements: on the Taylor lower block (p = 2,
/// 3 against 4 elements up the interface) the tied body stops being
/// positive definite below β ≈ 0.83, on the five-patch disk with its core
/// refined apart from its arcs between 1 and 10 (`tests/taylor_patches.rs`),
/// so 10 keeps a margin of about twelve on the first.
pub const TIE_FACTOR: f64 = 10.0;

/// Below this β a tie is refused: above the loss of definiteness measured
/// on the Taylor block, so that a factor chosen by hand far below the
/// default is told, not solved. It is a floor, not a guarantee: on the
/// curved interfaces of the disk the loss lies higher, between 1 and 10.
pub const MIN_TIE_FACTOR: f64 = 2.0;

/// Collects Dirichlet conditions before numbering the free DOFs.
pub struct DofMapBuilder<'a> {
    bodies: &'a [Body],
    offsets: Vec<usize>,
    fixed: Vec<Option<f64>>,
    group_of: Vec<usize>,
    /// Union–find parent of every global DOF, and the next member of its
    /// class (a circular list, to fix every copy of a shared DOF at once).
    parent: Vec<usize>,
    next: Vec<usize>,
    ties: Vec<Tie>,
    tie_factor: f64,
}

impl<'a> DofMapBuilder<'a> {
    /// Prescribes `value` on component `comp` of control point `cp` of body `body`.
    pub fn fix(&mut self, body: usize, cp: usize, comp: usize, value: f64) -> Result<&mut Self> {
        let nb = self.bodies.len();
        let b = self.bodies.get(body).ok_or_else(|| {
            Error::invalid("support.body", body, format!("there are {nb} bodies"))
        })?;
        if cp >= b.space.n_cp() {
            return Err(Error::invalid(
                "support.control_point",
                cp,
                format!("body `{}` has {} control points", b.name, b.space.n_cp()),
            ));
        }
        if comp > 1 {
            return Err(Error::invalid(
                "support.component",
                comp,
                "must be 0 (x) or 1 (y)",
            ));
        }
        crate::error::finite("support.value", value)?;
        let g0 = self.offsets[body] + 2 * cp + comp;
        let mut g = g0;
        loop {
            self.fixed[g] = Some(value);
            g = self.next[g];
            if g == g0 {
                break;
            }
        }
        Ok(self)
    }

    fn find(&mut self, mut g: usize) -> usize {
        while self.parent[g] != g {
            self.parent[g] = self.parent[self.parent[g]];
            g = self.parent[g];
        }
        g
    }

    /// Makes global DOFs `a` and `b` one unknown.
    fn unite(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra == rb {
            return;
        }
        let (lo, hi) = (ra.min(rb), ra.max(rb));
        self.parent[hi] = lo;
        self.next.swap(a, b);
    }

    /// Sets the factor β of the penalty of every tie
    /// ([`TIE_FACTOR`] unless set); refuses one below [`MIN_TIE_FACTOR`],
    /// where the symmetric tie can make the body's stiffness indefinite.
    pub fn tie_factor(&mut self, factor: f64) -> Result<&mut Self> {
        if !(factor.is_finite() && (MIN_TIE_FACTOR..=1e12).contains(&factor)) {
            return Err(Error::invalid(
                "tie.penalty_factor",
                format!("{factor:e}"),
                format!(
                    "must lie in {MIN_TIE_FACTOR}..=1e12: below, the symmetric Nitsche tie of a \
                     non-matching interface can make the body's stiffness indefinite"
                ),
            ));
        }
        self.tie_factor = factor;
        Ok(self)
    }

    /// Makes the patches `patches` (indices into the bodies) one elastic
    /// body: every pair of sides that match (the same knots along the
    /// side, coincident control points and weights, either way round)
    /// shares its control points; every pair that is one curve with two
    /// bases is recorded as a [`Tie`]. Call it before any `fix`. Fails,
    /// naming the body and the patches, when two sides meet but are not
    /// one curve (or meet over only part of their length), when a tied
    /// patch is not of the displacement formulation, or when a patch
    /// shares no side with the others.
    pub fn join(&mut self, name: &str, patches: &[usize]) -> Result<&mut Self> {
        let group = self.group_of[patches[0]];
        for &p in patches {
            self.group_of[p] = group;
        }
        let size = patches
            .iter()
            .map(|&p| crate::interface::extent(&self.bodies[p].space.patch))
            .fold(0.0, f64::max);
        let mut joined = vec![patches.len() == 1; patches.len()];
        for (ia, &a) in patches.iter().enumerate() {
            for (ib, &b) in patches.iter().enumerate().skip(ia + 1) {
                let (pa, pb) = (&self.bodies[a].space.patch, &self.bodies[b].space.patch);
                for sa in Side::ALL {
                    for sb in Side::ALL {
                        let at =
                            || format!("patches {ia} ({}) and {ib} ({})", sa.name(), sb.name());
                        let shared = match crate::interface::matching(pa, sa, pb, sb, size) {
                            Interface::Apart => continue,
                            Interface::NotMatching(why) => {
                                return Err(Error::invalid(
                                    format!("body {name:?}"),
                                    at(),
                                    format!("the interface can be neither shared nor tied: {why}"),
                                ));
                            }
                            Interface::NonMatching { reversed } => {
                                let displacement = |p: usize| {
                                    self.bodies[p].formulation == Formulation::Displacement
                                };
                                if !(displacement(a) && displacement(b)) {
                                    return Err(Error::invalid(
                                        format!("body {name:?}"),
                                        at(),
                                        "a non-matching interface is tied for the displacement \
                                         formulation only (the tie's traction is D ε)",
                                    ));
                                }
                                self.ties.push(Tie {
                                    patches: [a, b],
                                    sides: [sa, sb],
                                    reversed,
                                });
                                joined[ia] = true;
                                joined[ib] = true;
                                continue;
                            }
                            Interface::Matching(pairs) => pairs,
                        };
                        joined[ia] = true;
                        joined[ib] = true;
                        for (ca, cb) in shared {
                            for c in 0..2 {
                                let (ga, gb) =
                                    (self.offsets[a] + 2 * ca + c, self.offsets[b] + 2 * cb + c);
                                self.unite(ga, gb);
                            }
                        }
                    }
                }
            }
        }
        if let Some(i) = joined.iter().position(|j| !j) {
            return Err(Error::invalid(
                format!("body {name:?}"),
                format!("patch {i}"),
                "shares no side with the other patches of the body",
            ));
        }
        Ok(self)
    }

    /// Prescribes `value` on component `comp` of every control point of a side.
    /// On a side only that side's control points carry non-zero basis
    /// functions, so this fixes the whole boundary trace.
    pub fn fix_side(
        &mut self,
        body: usize,
        side: Side,
        comp: usize,
        value: f64,
    ) -> Result<&mut Self> {
        let nb = self.bodies.len();
        let b = self.bodies.get(body).ok_or_else(|| {
            Error::invalid("support.body", body, format!("there are {nb} bodies"))
        })?;
        for cp in b.space.patch.side_indices(side) {
            self.fix(body, cp, comp, value)?;
        }
        Ok(self)
    }

    /// Prescribes a displacement field u(X) at every control point of a side:
    /// exact for fields the NURBS space reproduces (affine ones).
    pub fn fix_side_field(
        &mut self,
        body: usize,
        side: Side,
        field: impl Fn([f64; 2]) -> [f64; 2],
    ) -> Result<&mut Self> {
        let idx = self.bodies[body].space.patch.side_indices(side);
        for cp in idx {
            let u = field(self.bodies[body].space.patch.points[cp]);
            self.fix(body, cp, 0, u[0])?;
            self.fix(body, cp, 1, u[1])?;
        }
        Ok(self)
    }

    pub fn build(&self) -> DofMap {
        let root = |mut g: usize| {
            while self.parent[g] != g {
                g = self.parent[g];
            }
            g
        };
        let rep: Vec<usize> = (0..self.fixed.len()).map(root).collect();
        let mut map = number(
            self.offsets.clone(),
            &self.fixed,
            rep,
            self.group_of.clone(),
        );
        map.ties = self.ties.clone();
        map.tie_factor = self.tie_factor;
        map
    }
}

/// Numbers the free DOFs in the order of their class representatives
/// (which precede every other member): without shared DOFs, in global order.
fn number(
    offsets: Vec<usize>,
    fixed: &[Option<f64>],
    rep: Vec<usize>,
    group_of: Vec<usize>,
) -> DofMap {
    let mut free_of = vec![FIXED; fixed.len()];
    let mut prescribed = vec![0.0; fixed.len()];
    let mut n_free = 0;
    for (g, f) in fixed.iter().enumerate() {
        match f {
            Some(v) => prescribed[g] = *v,
            None if rep[g] == g => {
                free_of[g] = n_free;
                n_free += 1;
            }
            None => free_of[g] = free_of[rep[g]],
        }
    }
    DofMap {
        offsets,
        free_of,
        prescribed,
        n_free,
        group_of,
        rep,
        ties: Vec::new(),
        tie_factor: TIE_FACTOR,
    }
}

impl DofMap {
    /// Starts numbering the DOFs of `bodies`.
    pub fn builder(bodies: &[Body]) -> DofMapBuilder<'_> {
        let mut offsets = Vec::with_capacity(bodies.len() + 1);
        let mut n = 0;
        for b in bodies {
            offsets.push(n);
            n += 2 * b.space.n_cp();
        }
        offsets.push(n);
        DofMapBuilder {
            bodies,
            offsets,
            fixed: vec![None; n],
            group_of: (0..bodies.len()).collect(),
            parent: (0..n).collect(),
            next: (0..n).collect(),
            ties: Vec::new(),
            tie_factor: TIE_FACTOR,
        }
    }

    /// True when some patches share DOFs (a body of several patches).
    pub fn is_linked(&self) -> bool {
        self.rep.iter().enumerate().any(|(g, &r)| r != g)
    }

    /// The non-matching interfaces of the bodies, tied weakly.
    pub fn ties(&self) -> &[Tie] {
        &self.ties
    }

    /// The factor β of the ties' penalty ([`DofMapBuilder::tie_factor`]).
    pub fn tie_factor(&self) -> f64 {
        self.tie_factor
    }

    /// The elastic body that patch `b` belongs to (`b` itself unless
    /// [`DofMapBuilder::join`] joined it to others; then the first patch).
    pub fn group(&self, b: usize) -> usize {
        self.group_of[b]
    }

    /// The patches of every elastic body, in patch order.
    pub fn groups(&self) -> Vec<Vec<usize>> {
        let mut out: Vec<Vec<usize>> = Vec::new();
        let mut at = vec![usize::MAX; self.group_of.len()];
        for (b, &g) in self.group_of.iter().enumerate() {
            if at[g] == usize::MAX {
                at[g] = out.len();
                out.push(Vec::new());
            }
            out[at[g]].push(b);
        }
        out
    }

    /// The same map with every shared DOF split into one free DOF per
    /// patch, and for each of its free DOFs the free DOF of `self` it
    /// folds into: the per-patch assembly runs on the split map, and
    /// [`crate::interface::fold`] sums its matrix into this one.
    pub fn unlinked(&self) -> (DofMap, Vec<usize>) {
        let fixed: Vec<Option<f64>> = self
            .free_of
            .iter()
            .zip(&self.prescribed)
            .map(|(&f, &v)| (f == FIXED).then_some(v))
            .collect();
        let split = number(
            self.offsets.clone(),
            &fixed,
            (0..fixed.len()).collect(),
            self.group_of.clone(),
        );
        let mut into = vec![0; split.n_free];
        for (g, &f) in split.free_of.iter().enumerate() {
            if f != FIXED {
                into[f] = self.free_of[g];
            }
        }
        (split, into)
    }

    pub fn n_total(&self) -> usize {
        self.free_of.len()
    }

    pub fn n_free(&self) -> usize {
        self.n_free
    }

    /// Global DOF of component `comp` of control point `cp` of body `body`.
    pub fn global(&self, body: usize, cp: usize, comp: usize) -> usize {
        self.offsets[body] + 2 * cp + comp
    }

    /// The free index of global DOF `g`, or `None` if it is prescribed.
    pub fn free(&self, g: usize) -> Option<usize> {
        let f = self.free_of[g];
        (f != FIXED).then_some(f)
    }

    pub fn prescribed(&self, g: usize) -> f64 {
        self.prescribed[g]
    }

    /// Global DOFs of the control points `cps` of body `body`, in local order
    /// (control point major, component minor).
    pub fn element_dofs(&self, body: usize, cps: &[usize]) -> Vec<usize> {
        cps.iter()
            .flat_map(|&a| [self.global(body, a, 0), self.global(body, a, 1)])
            .collect()
    }

    /// The full displacement vector from the free unknowns.
    pub fn expand(&self, free: &[f64]) -> Vec<f64> {
        self.free_of
            .iter()
            .zip(&self.prescribed)
            .map(|(&f, &v)| if f == FIXED { v } else { free[f] })
            .collect()
    }

    /// The free part of a full vector.
    pub fn restrict(&self, full: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.n_free];
        for (g, &f) in self.free_of.iter().enumerate() {
            if f != FIXED {
                out[f] = full[g];
            }
        }
        out
    }

    /// Displacement of control point `cp` of body `body` in a full vector.
    pub fn cp_displacement(&self, full: &[f64], body: usize, cp: usize) -> [f64; 2] {
        let g = self.global(body, cp, 0);
        [full[g], full[g + 1]]
    }
}
