//! The assembled contact problem: bulk stiffness, loads, contact points,
//! and the residual (13) and kernels (17)–(18) the solvers need, all over
//! the free DOFs.

use crate::assembly::{
    load_vector, split_body_forces, stiffness_matrix, tie_stiffness, Bulk, Load, Triplets,
};
use crate::contact::nitsche::{add_force, add_force_size_at, heaviside, local_matrix, Law};
use crate::contact::{contact_points, ContactPair, ContactPoint, Contacts, Master};
use crate::dofs::{Body, DofMap};
use crate::error::{Error, FloatingBody, Result, SingularError};
use crate::wellposed::{free_modes, RigidBasis};
use faer::sparse::{SparseColMat, Triplet};
use nalgebra::DMatrix;

/// Which approximate tangent to build.
#[derive(Clone, Copy, Debug)]
pub enum Kernel<'a> {
    /// Eq. (17): every contact point active (normal "tied" coupling).
    Tied,
    /// Eq. (18)–(19): active set of P at the given free displacement.
    Secant(&'a [f64]),
    /// H given per contact point (1 active, 0 inactive): the secant
    /// kernel of an active set chosen by the caller (see the floating
    /// guard of [`crate::solver`]).
    Activity(&'a [f64]),
}

/// Everything needed to evaluate R(u) and the kernels.
pub struct Problem {
    pub bodies: Vec<Body>,
    pub map: DofMap,
    pub pairs: Vec<ContactPair>,
    /// The contacts the pairs make up: each pair its own, unless
    /// [`Problem::with_contacts`] joins the pieces of a slave boundary that
    /// runs over several patches.
    pub contacts: Contacts,
    /// The applied loads (body indices into `bodies`).
    pub loads: Vec<Load>,
    pub points: Vec<ContactPoint>,
    /// F − K_fc ū over the free DOFs.
    pub rhs: Vec<f64>,
    /// Bulk stiffness over the free DOFs, in the kernels' pattern (the
    /// contact couplings between bodies stored as zeros).
    pub k: SparseColMat<usize, f64>,
}

/// A kernel written as S + U Vᵀ: see [`Problem::kernel_split`].
pub struct KernelSplit {
    /// S: the bulk stiffness plus the symmetric positive semidefinite
    /// contact terms.
    pub spd: SparseColMat<usize, f64>,
    /// U, n × k.
    pub u: SparseColMat<usize, f64>,
    /// V, n × k.
    pub v: SparseColMat<usize, f64>,
}

impl KernelSplit {
    /// k, the rank of the correction U Vᵀ.
    pub fn rank(&self) -> usize {
        self.u.ncols()
    }
}

/// `k` plus the triplets `t`, added in place where `k`'s pattern holds
/// them (the couplings put them there); otherwise rebuilt with them.
fn add_in_pattern(k: SparseColMat<usize, f64>, t: &Triplets) -> Result<SparseColMat<usize, f64>> {
    if t.is_empty() {
        return Ok(k);
    }
    let (symbolic, mut val) = k.into_parts();
    let (ptr, idx) = (symbolic.col_ptr(), symbolic.row_idx());
    let mut all_in = true;
    for ((&i, &j), &v) in t.rows.iter().zip(&t.cols).zip(&t.vals) {
        match idx[ptr[j]..ptr[j + 1]].binary_search(&i) {
            Ok(at) => val[ptr[j] + at] += v,
            Err(_) => all_in = false,
        }
    }
    if all_in {
        return Ok(SparseColMat::new(symbolic, val));
    }
    // not expected: the entries of `k` as they were, and `t` beside them
    let mut entries = Vec::with_capacity(val.len() + t.len());
    for j in 0..symbolic.ncols() {
        for at in ptr[j]..ptr[j + 1] {
            entries.push(Triplet::new(idx[at], j, val[at]));
        }
    }
    for ((&i, &j), &v) in t.rows.iter().zip(&t.cols).zip(&t.vals) {
        if idx[ptr[j]..ptr[j + 1]].binary_search(&i).is_ok() {
            continue;
        }
        entries.push(Triplet::new(i, j, v));
    }
    SparseColMat::try_new_from_triplets(symbolic.nrows(), symbolic.ncols(), &entries)
        .map_err(|e| Error::out_of_memory("the tied stiffness", e))
}

/// Summary of the contact state at one displacement.
#[derive(Clone, Copy, Debug, Default)]
pub struct ContactState {
    pub active: usize,
}

impl Problem {
    pub fn new(
        bodies: Vec<Body>,
        map: DofMap,
        loads: &[Load],
        pairs: Vec<ContactPair>,
    ) -> Result<Self> {
        Self::require_free_dofs(&map)?;
        let points = contact_points(&bodies, &map, &pairs)?;
        Self::with_points(bodies, map, loads, pairs, points)
    }

    /// As [`Problem::new`], with the contact points of `pairs` already
    /// built ([`contact_points`] of the same bodies, map and pairs): a
    /// caller that needed them first (the rigid-mode check of a scene)
    /// does not build them, with an element stiffness and an eigenvalue
    /// problem per slave element, twice.
    pub fn with_points(
        bodies: Vec<Body>,
        map: DofMap,
        loads: &[Load],
        pairs: Vec<ContactPair>,
        points: Vec<ContactPoint>,
    ) -> Result<Self> {
        Self::require_free_dofs(&map)?;
        // One pattern for everything: the bulk stiffness is stored in the
        // kernels' pattern, with zeros where only contact couples two DOFs
        // (two bodies), so every kernel has the same symbolic structure.
        let mut couplings = Vec::new();
        for cp in &points {
            let free: Vec<usize> = cp.dofs.iter().filter_map(|&d| map.free(d)).collect();
            for &i in &free {
                couplings.extend(free.iter().map(|&j| (i, j)));
            }
        }
        // the ties of non-matching interfaces couple DOFs no element joins:
        // their entries join the pattern, and their values are added after
        let (tie, tie_lift) = tie_stiffness(&bodies, &map, map.tie_factor())?;
        couplings.extend(tie.rows.iter().copied().zip(tie.cols.iter().copied()));
        // body forces share the stiffness's quadrature
        let (forces, others) = split_body_forces(&bodies, loads)?;
        let Bulk { k, lift, body_load } = if map.is_linked() {
            // patches sharing control points: assembled per patch on the
            // split numbering, then summed into the shared unknowns
            let (split, into) = map.unlinked();
            let bulk = stiffness_matrix(&bodies, &split, &[], &forces)?;
            let n = map.n_free();
            Bulk {
                k: crate::interface::fold(&bulk.k, &into, n, &couplings)?,
                lift: crate::interface::fold_vec(&bulk.lift, &into, n),
                body_load: crate::interface::fold_vec(&bulk.body_load, &into, n),
            }
        } else {
            stiffness_matrix(&bodies, &map, &couplings, &forces)?
        };
        let k = add_in_pattern(k, &tie)?;
        let mut rhs = load_vector(&bodies, &map, &others)?;
        for (((r, l), b), t) in rhs.iter_mut().zip(&lift).zip(&body_load).zip(&tie_lift) {
            *r += b - l - t;
        }
        Ok(Self {
            bodies,
            map,
            contacts: Contacts::each_pair(pairs.len()),
            pairs,
            loads: loads.to_vec(),
            points,
            rhs,
            k,
        })
    }

    /// The problem with its pairs grouped into `contacts`, which must
    /// cover them; the pieces of one contact must share its slave body,
    /// its master and its parameters, since what is reported of a
    /// contact is taken from its first piece.
    pub fn with_contacts(mut self, contacts: Contacts) -> Result<Self> {
        if contacts.pairs() != self.pairs.len() {
            return Err(Error::invalid(
                "contacts",
                format!("{} pairs", contacts.pairs()),
                format!("the problem has {} contact pairs", self.pairs.len()),
            ));
        }
        for (c, pieces) in contacts.iter() {
            let first = &self.pairs[pieces.start];
            let group = self.map.group(first.slave);
            for k in pieces {
                let pair = &self.pairs[k];
                // (a rigid master is one curve given once per contact)
                let same_master = match (&pair.master, &first.master) {
                    (Master::Rigid(_), Master::Rigid(_)) => true,
                    (Master::Body { body: a, side: s }, Master::Body { body: b, side: t }) => {
                        a == b && s == t
                    }
                    _ => false,
                };
                if self.map.group(pair.slave) != group
                    || !same_master
                    || pair.nitsche != first.nitsche
                {
                    return Err(Error::invalid(
                        format!("contact[{c}]"),
                        format!("pair {k}"),
                        "the pieces of a contact share its slave body, master and parameters",
                    ));
                }
            }
        }
        self.contacts = contacts;
        Ok(self)
    }

    fn require_free_dofs(map: &DofMap) -> Result<()> {
        if map.n_free() == 0 {
            return Err(Error::invalid(
                "supports",
                "all DOFs",
                "every degree of freedom is prescribed",
            ));
        }
        Ok(())
    }

    pub fn n(&self) -> usize {
        self.map.n_free()
    }

    /// H per contact point: 1 everywhere for the tied kernel (17), H(P(u))
    /// for the secant kernel (18)–(19).
    fn activity(&self, kind: Kernel) -> Vec<f64> {
        match kind {
            Kernel::Tied => vec![1.0; self.points.len()],
            Kernel::Secant(u) => self.p_values(u).into_iter().map(heaviside).collect(),
            Kernel::Activity(h) => h.to_vec(),
        }
    }

    /// P(u) = σ_n + γ g_n at every contact point, for the free displacement `u`.
    pub fn p_values(&self, u: &[f64]) -> Vec<f64> {
        let full = self.map.expand(u);
        self.points.iter().map(|cp| cp.p(&full)).collect()
    }

    /// The free DOFs that some contact functional (σ_n or ⟦u_n⟧) reaches,
    /// increasing: the layer L on which every contact term lives.
    pub fn layer(&self) -> Vec<usize> {
        let mut on = vec![false; self.n()];
        for cp in &self.points {
            for (k, &d) in cp.dofs.iter().enumerate() {
                if let Some(i) = self
                    .map
                    .free(d)
                    .filter(|_| cp.sn[k] != 0.0 || cp.jn[k] != 0.0)
                {
                    on[i] = true;
                }
            }
        }
        (0..self.n()).filter(|&i| on[i]).collect()
    }

    /// A₀ = K + Σ_q w γ jn jnᵀ over every contact point (free DOFs): the
    /// bulk stiffness plus the penalty term of the whole potential contact
    /// boundary, symmetric positive definite whenever contact everywhere
    /// holds the bodies. Every kernel (17)–(18), of every θ and active
    /// set, is A₀ plus a matrix on the [`Problem::layer`].
    pub fn bulk_plus_penalty(&self) -> Result<SparseColMat<usize, f64>> {
        self.matrix_of(self.bulk_plus_penalty_values()?)
    }

    /// The values of [`Problem::bulk_plus_penalty`], in the pattern of
    /// [`Problem::k`].
    pub fn bulk_plus_penalty_values(&self) -> Result<Vec<f64>> {
        self.values_with(|_, cp| {
            let w = cp.weight * cp.gamma;
            DMatrix::from_fn(cp.dofs.len(), cp.dofs.len(), |a, b| w * cp.jn[a] * cp.jn[b])
        })
    }

    /// The values of the bulk stiffness plus every point's `local` matrix
    /// (rows and columns of prescribed DOFs dropped), in the pattern of
    /// [`Problem::k`].
    fn values_with(
        &self,
        local: impl Fn(usize, &ContactPoint) -> DMatrix<f64>,
    ) -> Result<Vec<f64>> {
        let mut val = self.k.val().to_vec();
        let s = self.k.symbolic();
        let (ptr, idx) = (s.col_ptr(), s.row_idx());
        for (q, cp) in self.points.iter().enumerate() {
            let m = local(q, cp);
            let free: Vec<(usize, usize)> = cp
                .dofs
                .iter()
                .enumerate()
                .filter_map(|(a, &d)| self.map.free(d).map(|i| (a, i)))
                .collect();
            for &(b, j) in &free {
                let col = &idx[ptr[j]..ptr[j + 1]];
                for &(a, i) in &free {
                    let at = col
                        .binary_search(&i)
                        .map_err(|_| SingularError::OutsidePattern { row: i, col: j })?;
                    val[ptr[j] + at] += m[(a, b)];
                }
            }
        }
        Ok(val)
    }

    /// A matrix of the kernels' pattern: the bulk stiffness plus every
    /// point's `local` matrix.
    fn with_bulk(
        &self,
        local: impl Fn(usize, &ContactPoint) -> DMatrix<f64>,
    ) -> Result<SparseColMat<usize, f64>> {
        self.matrix_of(self.values_with(local)?)
    }

    /// The matrix of the pattern of [`Problem::k`] with the values `val`.
    fn matrix_of(&self, val: Vec<f64>) -> Result<SparseColMat<usize, f64>> {
        let symbolic = self
            .k
            .symbolic()
            .to_owned()
            .map_err(|e| Error::out_of_memory("a kernel's pattern", e))?;
        Ok(SparseColMat::new(symbolic, val))
    }

    /// The kernel matrix: bulk stiffness plus the contact matrix of `kind`.
    /// Same sparsity pattern for every kind, so one symbolic factorisation
    /// serves them all.
    pub fn kernel(&self, kind: Kernel) -> Result<SparseColMat<usize, f64>> {
        let h = self.activity(kind);
        self.with_bulk(|q, cp| local_matrix(cp, h[q]))
    }

    /// The kernel of `kind` split as S + U Vᵀ for
    /// [`crate::linsolve::Factoriser::factor_low_rank`], when every point
    /// has θ ≤ 0 (otherwise `None`).
    ///
    /// The point matrix is H w (γ jn jnᵀ − jn snᵀ − θ sn jnᵀ) − (1 − H)
    /// (θ/γ) w sn snᵀ. Its symmetric positive semidefinite terms (the
    /// first, and the last for θ ≤ 0) go into S. The rest is
    /// E_R M + Nᵀ E_Rᵀ, with R the trace DOFs (jn ≠ 0) of the active
    /// points, M = −Σ H w `jn[R]` snᵀ and N = −Σ H θ w `jn[R]` snᵀ: rows of
    /// the trace, and for θ ≠ 0 also columns. So U = [E_R | Nᵀ] and
    /// V = [Mᵀ | E_R], of rank r = |R| for θ = 0 and 2r otherwise.
    pub fn kernel_split(&self, kind: Kernel) -> Result<Option<KernelSplit>> {
        if self.points.iter().any(|cp| cp.theta > 0.0) {
            return Ok(None);
        }
        let h = self.activity(kind);
        let spd = self.with_bulk(|q, cp| {
            let (w, g, th) = (cp.weight, cp.gamma, cp.theta);
            DMatrix::from_fn(cp.dofs.len(), cp.dofs.len(), |a, b| {
                h[q] * w * g * cp.jn[a] * cp.jn[b]
                    - (1.0 - h[q]) * (th / g) * w * cp.sn[a] * cp.sn[b]
            })
        })?;
        let n = self.n();
        let mut row_of = vec![usize::MAX; n];
        let mut rows = Vec::new();
        // (free DOF b, trace index of a, −H w jn[a] sn[b]) and its θ multiple
        let mut mt = Vec::new();
        let mut nt = Vec::new();
        for (q, cp) in self.points.iter().enumerate() {
            if h[q] == 0.0 {
                continue;
            }
            for (a, &da) in cp.dofs.iter().enumerate() {
                let Some(i) = self.map.free(da).filter(|_| cp.jn[a] != 0.0) else {
                    continue;
                };
                if row_of[i] == usize::MAX {
                    row_of[i] = rows.len();
                    rows.push(i);
                }
                for (b, &db) in cp.dofs.iter().enumerate() {
                    if let Some(j) = self.map.free(db) {
                        let v = -h[q] * cp.weight * cp.jn[a] * cp.sn[b];
                        mt.push((j, row_of[i], v));
                        if cp.theta != 0.0 {
                            nt.push((j, row_of[i], cp.theta * v));
                        }
                    }
                }
            }
        }
        let r = rows.len();
        let identity: Vec<_> = rows.iter().enumerate().map(|(c, &i)| (i, c, 1.0)).collect();
        let shifted = |t: &[(usize, usize, f64)]| -> Vec<(usize, usize, f64)> {
            t.iter().map(|&(i, c, v)| (i, c + r, v)).collect()
        };
        let (u, v, k) = if nt.is_empty() {
            (identity, mt, r)
        } else {
            let u = [identity.clone(), shifted(&nt)].concat();
            let v = [mt, shifted(&identity)].concat();
            (u, v, 2 * r)
        };
        let build = |t: Vec<(usize, usize, f64)>| {
            let t: Vec<_> = t
                .into_iter()
                .map(|(i, j, v)| Triplet::new(i, j, v))
                .collect();
            SparseColMat::try_new_from_triplets(n, k, &t)
                .map_err(|e| Error::Singular(SingularError::LowRankFactors(e)))
        };
        Ok(Some(KernelSplit {
            spd,
            u: build(u)?,
            v: build(v)?,
        }))
    }

    /// Number of contact points with P(u) ≤ 0 at the free displacement `u`.
    pub fn active_points(&self, u: &[f64]) -> usize {
        let full = self.map.expand(u);
        self.points.iter().filter(|cp| cp.p(&full) <= 0.0).count()
    }

    /// The residual (13), R(u) = L(v) − a(u, v) + contact work, over the
    /// free DOFs, and the contact state.
    pub fn residual(&self, u: &[f64]) -> (Vec<f64>, ContactState) {
        self.residual_forced(u, &[])
    }

    /// As [`Problem::residual`], with the points marked in `forced` (empty:
    /// none) treated as active whatever the sign of P: their contact force
    /// is that of the tied law, \[P\]₋ replaced by P. This is the residual
    /// whose linearisation is the secant kernel with those points active,
    /// so a step with it closes their gap (the floating guard).
    pub fn residual_forced(&self, u: &[f64], forced: &[bool]) -> (Vec<f64>, ContactState) {
        let (r, state, _) = self.residual_with_floor(u, forced);
        (r, state)
    }

    /// As [`Problem::residual_forced`], with the round-off of evaluating R
    /// at `u`, from the same pass over K and the contact points: two norms
    /// of the component-wise sums of the magnitudes of the terms of R,
    /// times ε, `(typical, cancelling)`. Both count |f| and |K||u|;
    /// `typical` counts each contact force as computed, |g_c|, and
    /// `cancelling` its terms before they cancel
    /// ([`crate::contact::nitsche::add_force_size_at`]), a bound that small
    /// penalties or large stresses make far larger.
    pub fn residual_with_floor(
        &self,
        u: &[f64],
        forced: &[bool],
    ) -> (Vec<f64>, ContactState, (f64, f64)) {
        let full = self.map.expand(u);
        let mut ku = vec![0.0; self.n()];
        let mut size: Vec<f64> = self.rhs.iter().map(|v| v.abs()).collect();
        let s = self.k.symbolic();
        let (ptr, idx, val) = (s.col_ptr(), s.row_idx(), self.k.val());
        for j in 0..self.n() {
            for k in ptr[j]..ptr[j + 1] {
                let a = val[k] * u[j];
                ku[idx[k]] += a;
                size[idx[k]] += a.abs();
            }
        }
        let mut r: Vec<f64> = self.rhs.iter().zip(&ku).map(|(f, k)| f - k).collect();
        let mut wide = size.clone();
        let mut active = 0;
        let (mut g, mut g_size) = (Vec::new(), Vec::new());
        for (q, cp) in self.points.iter().enumerate() {
            g.clear();
            g.resize(cp.dofs.len(), 0.0);
            g_size.clear();
            g_size.resize(cp.dofs.len(), 0.0);
            let law = match forced.get(q) {
                Some(true) => Law::Tied,
                _ => Law::Contact,
            };
            let p = add_force(cp, &full, &mut g, law);
            if p <= 0.0 {
                active += 1;
            }
            let (mut sigma_size, mut jump_size) = (0.0, 0.0);
            for (k, &dof) in cp.dofs.iter().enumerate() {
                sigma_size += (cp.sn[k] * full[dof]).abs();
                jump_size += (cp.jn[k] * full[dof]).abs();
            }
            add_force_size_at(cp, sigma_size, jump_size, p, law, &mut g_size);
            for (k, &dof) in cp.dofs.iter().enumerate() {
                if let Some(i) = self.map.free(dof) {
                    r[i] -= g[k];
                    size[i] += g[k].abs();
                    wide[i] += g_size[k];
                }
            }
        }
        let norm = |v: &[f64]| f64::EPSILON * v.iter().map(|x| x * x).sum::<f64>().sqrt();
        (r, ContactState { active }, (norm(&size), norm(&wide)))
    }

    /// Rigid-body modes (full-length vectors, one per mode) that the
    /// supports leave free: only contact can hold these. A body of several
    /// patches moves as one.
    pub fn floating_modes(&self) -> Vec<Vec<f64>> {
        let mut modes = Vec::new();
        for group in self.map.groups() {
            let basis = RigidBasis::of_patches(&self.bodies, &group);
            for coef in free_modes(&self.bodies, &group, &self.map, &basis) {
                let mut v = vec![0.0; self.map.n_total()];
                for &b in &group {
                    for (a, p) in self.bodies[b].space.patch.points.iter().enumerate() {
                        for comp in 0..2 {
                            v[self.map.global(b, a, comp)] =
                                (0..3).map(|m| coef[m] * basis.value(m, *p, comp)).sum();
                        }
                    }
                }
                modes.push(v);
            }
        }
        modes
    }

    /// Fails when no compressive contact force can balance the load along a
    /// free rigid mode r: equilibrium needs r·F = Σ w |P| (⟦r_n⟧) with
    /// |P| ≥ 0, impossible if every ⟦r_n⟧ has the wrong sign (or there is
    /// no contact point at all).
    pub fn check_support(&self) -> Result<()> {
        for (mode, r) in self.floating_modes().into_iter().enumerate() {
            let rf: f64 = self
                .map
                .restrict(&r)
                .iter()
                .zip(&self.rhs)
                .map(|(a, b)| a * b)
                .sum();
            let scale: f64 = self
                .rhs
                .iter()
                .map(|v| v.abs())
                .sum::<f64>()
                .max(f64::MIN_POSITIVE);
            if rf.abs() <= 1e-12 * scale {
                continue;
            }
            let can_balance = self.points.iter().any(|cp| {
                let (_, jump) = cp.normal_stress_and_jump(&r);
                jump * rf > 0.0
            });
            if !can_balance {
                return Err(FloatingBody {
                    mode,
                    load_work: rf,
                    contact_points: self.points.len(),
                }
                .into());
            }
        }
        Ok(())
    }
}
