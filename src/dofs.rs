//! Bodies, global degree-of-freedom numbering and Dirichlet conditions by
//! elimination.
//!
//! Global DOF `offset[b] + 2·A + c` is component c of control point A of
//! body b. Dirichlet conditions act on control-point values (the paper's
//! convention); they are eliminated, so the solved system holds only the
//! free DOFs and no large numbers ever enter the matrix.

use crate::error::{Error, Result};
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
}

/// Collects Dirichlet conditions before numbering the free DOFs.
pub struct DofMapBuilder<'a> {
    bodies: &'a [Body],
    offsets: Vec<usize>,
    fixed: Vec<Option<f64>>,
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
        self.fixed[self.offsets[body] + 2 * cp + comp] = Some(value);
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
        let mut free_of = vec![FIXED; self.fixed.len()];
        let mut prescribed = vec![0.0; self.fixed.len()];
        let mut n_free = 0;
        for (g, f) in self.fixed.iter().enumerate() {
            match f {
                Some(v) => prescribed[g] = *v,
                None => {
                    free_of[g] = n_free;
                    n_free += 1;
                }
            }
        }
        DofMap {
            offsets: self.offsets.clone(),
            free_of,
            prescribed,
            n_free,
        }
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
        }
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
