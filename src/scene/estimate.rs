//! The resources a run needs, from the scene alone: sizes from the knot
//! vectors, nothing of the size of the discretisation allocated.

mod free_dofs;

use super::patches::in_body;
use super::validate::Valid;
use super::{MasterSpec, RefineSpec, Scene, SlaveAt};
use crate::error::Result;
use crate::nurbs::{KnotVector, NurbsPatch};
use crate::resources::{BodySize, Estimate, Factoring, PairSize};
use crate::solver::Factorisation;

impl Scene {
    /// Validates the scene and estimates DOFs, non-zeros and peak memory of
    /// a run from it alone, allocating nothing of the size of the
    /// discretisation.
    pub fn estimate(&self) -> Result<Estimate> {
        self.valid()?.estimate()
    }
}

impl Valid<'_> {
    /// [`Scene::estimate`] of the validated scene.
    pub(super) fn estimate(&self) -> Result<Estimate> {
        let per_body = (0..self.bodies.len())
            .map(|i| self.body_sizes(i))
            .collect::<Result<Vec<_>>>()?;
        let exact: Vec<Vec<NurbsPatch>> = (0..self.bodies.len())
            .map(|i| self.exact_patches(i))
            .collect::<Result<_>>()?;
        // the first patch of every body among all patches' sizes
        let first: Vec<usize> = per_body
            .iter()
            .scan(0, |n, v| {
                let at = *n;
                *n += v.len();
                Some(at)
            })
            .collect();
        let sizes: Vec<BodySize> = per_body.into_iter().flatten().collect();
        let names = self.body_index();
        let dofs = self.free_dofs(&exact, &sizes, &first)?;
        // one pair per piece of a slave boundary
        let mut pieces = Vec::new();
        for c in &self.contacts {
            let b = names[c.slave.as_str()];
            match &c.slave_at {
                &SlaveAt::Side(side) => pieces.push((c, first[b], side)),
                SlaveAt::Boundary(name) => {
                    for (p, side) in self.boundary_of(b, "slave_boundary", name)? {
                        pieces.push((c, first[b] + p, side));
                    }
                }
            }
        }
        let pairs = pieces
            .into_iter()
            .map(|(c, slave, slave_side)| {
                let s = &sizes[slave];
                let along = slave_side.along();
                let mut degree = s.degree[0].max(s.degree[1]);
                let mut coupled = s.element_points();
                let mut master_breaks = 2.0;
                // Two rows of slave control points reach the normal stress.
                let mut layer = 4.0 * s.n[along] as f64;
                if let MasterSpec::Body { body, side } = &c.master {
                    let m = &sizes[first[names[body.as_str()]]];
                    degree = degree.max(m.degree[0].max(m.degree[1]));
                    coupled += m.element_points();
                    master_breaks = m.elements[side.along()] as f64 + 1.0;
                    layer += 2.0 * m.n[side.along()] as f64;
                }
                let g = c.nitsche.points(degree) as f64;
                PairSize {
                    points: g * (s.elements[along] as f64 + master_breaks),
                    dofs_per_point: 2.0 * coupled,
                    layer,
                }
            })
            .collect();
        // The bulk is factorised by Cholesky whatever θ (the layer's dense
        // kernels take the non-symmetric part), by LU only if asked.
        let lu = self.solver.factorisation == Factorisation::Lu;
        let vtu = self.output.vtu.then_some(self.output.vtu_subdivisions);
        let factoring = if lu {
            Factoring::Lu
        } else {
            Factoring::Cholesky
        };
        Ok(Estimate::new(sizes, pairs, dofs, vtu, factoring))
    }
}

impl Scene {
    /// The exact patches of body `i`, before refinement.
    fn exact_patches(&self, i: usize) -> Result<Vec<NurbsPatch>> {
        let b = &self.bodies[i];
        match b.geometry.multipatch() {
            None => Ok(vec![self.exact_patch(i)?]),
            Some(mp) => Ok(mp.map_err(|e| in_body(e, i, &b.name, ""))?.patches),
        }
    }

    /// The sizes of body `i`'s discretisation (one per patch), from its
    /// knot vectors alone.
    fn body_sizes(&self, i: usize) -> Result<Vec<BodySize>> {
        let b = &self.bodies[i];
        match b.geometry.multipatch() {
            None => Ok(vec![self.patch_size(i, &self.exact_patch(i)?, None)?]),
            Some(mp) => {
                let mp = mp.map_err(|e| in_body(e, i, &b.name, ""))?;
                mp.patches
                    .iter()
                    .zip(&mp.counts)
                    .map(|(patch, c)| {
                        let elements = b.refine.as_ref().map(|r| mp.divisions(c, r.elements()));
                        self.patch_size(i, patch, elements)
                    })
                    .collect()
            }
        }
    }

    /// The size of one exact patch of body `i` once refined, with the
    /// element counts `elements` instead of the body's (a multi-patch
    /// body's per patch).
    fn patch_size(
        &self,
        i: usize,
        exact: &NurbsPatch,
        elements: Option<[usize; 2]>,
    ) -> Result<BodySize> {
        let b = &self.bodies[i];
        // Per direction: basis functions and elements after refinement.
        let count = |kv: &KnotVector, d: usize| -> (usize, usize, usize) {
            let spans = kv.spans().len();
            let elements = elements.or(b.refine.as_ref().map(RefineSpec::elements));
            let elements = &elements.unwrap_or([1, 1]);
            match b.refine {
                None => (kv.n_basis(), spans, kv.degree()),
                Some(RefineSpec::KRefine { degree, .. }) => {
                    let p = degree.max(kv.degree());
                    let mult = kv.multiplicities();
                    let raise = p - kv.degree();
                    let interior: usize = mult[1..mult.len() - 1].iter().map(|m| m + raise).sum();
                    (
                        p + 1 + interior + spans * (elements[d] - 1),
                        spans * elements[d],
                        p,
                    )
                }
                Some(RefineSpec::Lagrange { degree: q, .. }) => {
                    (elements[d] * q + 1, elements[d], q)
                }
            }
        };
        let (n0, e0, p0) = count(&exact.knots[0], 0);
        let (n1, e1, p1) = count(&exact.knots[1], 1);
        let (field, value) = match &b.refine {
            Some(r) => (
                format!("body[{i}].refine.elements"),
                format!("{:?}", r.elements()),
            ),
            None => (
                format!("body[{i}].geometry"),
                format!("{n0} × {n1} control points"),
            ),
        };
        Ok(BodySize {
            field,
            value,
            n: [n0, n1],
            degree: [p0, p1],
            elements: [e0, e1],
            side_elements: [e1, e0],
            formulation: b.formulation,
        })
    }
}
