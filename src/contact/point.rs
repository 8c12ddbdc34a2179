//! A contact quadrature point: its functionals σ_n(u) and ⟦u_n⟧ over the
//! DOFs it reaches. Built by [`super::pair`], read by the penalty checks
//! and the Nitsche terms; a file of its own so that neither depends on
//! the other through it.

use super::stability::stability_bound;

/// Which body of its pair a contact point lies on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Role {
    /// On the pair's slave side (every point of the biased form).
    Slave,
    /// On the master side, the slave of the mirrored half of the unbiased form.
    Master,
}

/// A contact quadrature point with its linear functionals over the DOFs in
/// `dofs` (global numbering): σ_n(u) = Σ sn_k u_k and ⟦u_n⟧ = Σ jn_k u_k.
#[derive(Clone, Debug)]
pub struct ContactPoint {
    pub pair: usize,
    /// The body of the pair whose side the point lies on.
    pub role: Role,
    /// Reference position x¹ on the slave.
    pub x: [f64; 2],
    /// Slave side parameter.
    pub t: f64,
    /// n¹ = −n²(x̄²).
    pub normal: [f64; 2],
    /// Initial gap g₀ = (x̄² − x¹)·n¹, between positions in the undeformed bodies.
    pub g0: f64,
    pub gamma: f64,
    /// The trace-inverse constant C_T of the slave element that holds the
    /// point ([`super::penalty::trace_constant`]); γ below
    /// [`super::penalty::stability_bound`] of it loses coercivity.
    pub trace_constant: f64,
    pub theta: f64,
    /// Quadrature weight including the arc length, and the share below.
    pub weight: f64,
    /// The share of the contact's weight the point's form carries: 1 in the
    /// biased form, ½ in each half of the unbiased one. `trace_constant`,
    /// from the shared weights, is the half's; the penalty's scale against
    /// the body (over- or under-penalisation) is that of the whole weight,
    /// `trace_constant / share`, as the two halves add to one penalty γ on
    /// one gap.
    pub share: f64,
    /// The degrees of freedom the point's functionals reach, in the global
    /// numbering of the full displacement vector: the two DOFs of each
    /// control point of the slave element holding x¹, then (for an elastic
    /// master) those of the master control points whose basis functions are
    /// non-zero at x̄². `sn` and `jn` are indexed like this list.
    pub dofs: Vec<usize>,
    /// The normal stress σ_n(u) = n¹·σ(u¹)n¹ at x¹ in the contact direction n¹
    /// (the slave's own normal only on mirrored points or where the surfaces
    /// are parallel), as a linear functional:
    /// σ_n(u) = Σ_k `sn[k] u[dofs[k]]`. It uses the slave's basis gradients and
    /// material only, so its entries on master DOFs are zero.
    pub sn: Vec<f64>,
    /// The jump of the normal displacement ⟦u_n⟧ = (u¹(x¹) − u²(x̄²))·n¹ as
    /// a linear functional, ⟦u_n⟧ = Σ_k `jn[k] u[dofs[k]]`: R¹_A n¹ on the slave
    /// DOFs, −R²_B n¹ on the master's. The gap is g_n = g₀ − ⟦u_n⟧, Eq. (5).
    pub jn: Vec<f64>,
    /// False on a slave element whose geometric map is singular at an end
    /// ([`super::pair::regular_map`]): σ_n there divides by det J ≈ 0, so neither the
    /// bracket nor the trace constant of the element measures the contact.
    pub regular: bool,
    /// The cosine between the outward normal of the side the point lies on
    /// and n¹: positive where that side faces its master. Where it is
    /// negative the master lies behind the surface, inside the body, and a
    /// closed gap there is measured through the body
    /// ([`ContactPoint::faces_away`]).
    pub facing: f64,
}

/// The cosine between two unit normals below which (in magnitude) they
/// count as perpendicular: round-off of a normal computed from a NURBS
/// map, not a direction.
pub const PERPENDICULAR: f64 = 1e-8;

/// The cosine between the slave's normal and n¹ below which an active point
/// meets its master at a grazing angle (more than 60° off): no contact
/// surface does that where it carries load (Hertz under 16 times the load
/// reaches 45° at the edge of its zone); a side drawn nearly edge-on to
/// the master (a block's side tilted 6° from upright against a floor) does.
pub const GRAZING: f64 = 0.5;

impl ContactPoint {
    /// Whether the point meets its master at a grazing angle, edge-on, or
    /// faces away from it ([`GRAZING`]).
    pub fn grazes(&self) -> bool {
        self.facing < GRAZING
    }

    /// Whether the side of the point faces away from its master (beyond
    /// round-off of perpendicular normals).
    pub fn faces_away(&self) -> bool {
        self.facing < -PERPENDICULAR
    }

    /// Whether the side of the point faces its master (beyond round-off of
    /// perpendicular normals).
    pub fn faces_master(&self) -> bool {
        self.facing > PERPENDICULAR
    }

    /// (σ_n(u), ⟦u_n⟧) for a full displacement vector.
    pub fn normal_stress_and_jump(&self, u: &[f64]) -> (f64, f64) {
        let mut s = 0.0;
        let mut j = 0.0;
        for (k, &g) in self.dofs.iter().enumerate() {
            s += self.sn[k] * u[g];
            j += self.jn[k] * u[g];
        }
        (s, j)
    }

    /// P(u) = σ_n(u) + γ g_n(u) with g_n = g₀ − ⟦u_n⟧.
    pub fn p(&self, u: &[f64]) -> f64 {
        let (s, j) = self.normal_stress_and_jump(u);
        s + self.gamma * (self.g0 - j)
    }

    /// The smallest stable γ at this point: the stability bound of its
    /// slave element for its θ ([`stability_bound`]).
    pub fn stability_bound(&self) -> f64 {
        stability_bound(self.trace_constant, self.theta)
    }

    /// Whether γ lies below [`Self::stability_bound`]: where such a point is
    /// active, the tangent need not be coercive. A point where the map is
    /// singular ([`Self::regular`]) is never judged: its C_T measures the
    /// 1/det J of σ_n, not the penalty.
    pub fn below_stability_bound(&self) -> bool {
        self.regular && self.gamma < self.stability_bound()
    }
}
