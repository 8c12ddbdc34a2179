//! Contact pairs and their quadrature points: everything about a point of
//! Γc that does not depend on the displacement (small deformation).

use super::penalty::{empirical_penalty, PenaltyInputs};
use super::projection::{closest_point, Projection};
use crate::dofs::{Body, DofMap};
use crate::error::{Error, Result};
use crate::nurbs::{NurbsCurve, Side};
use crate::quadrature;
use serde::{Deserialize, Serialize};

/// What the slave side is pressed against.
#[derive(Clone, Debug)]
pub enum Master {
    /// A rigid obstacle bounded by `curve`. The obstacle lies on the right
    /// of the curve's direction, so its outward normal is the tangent turned
    /// by +90° (a segment from left to right is a floor).
    Rigid(NurbsCurve),
    /// A side of another (elastic) body.
    Body { body: usize, side: Side },
}

/// How the contact integral over Γc is evaluated.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Integration {
    /// Gauss points per slave element: simple, but the integrand has kinks
    /// where master knots project, so it is not integrated exactly.
    Gauss,
    /// Each slave element is cut where master knots project; the integrand
    /// is smooth on every segment and the contact patch test is passed exactly.
    Segment,
}

/// A slave side, a master, and the Nitsche parameters of Eq. (9)–(11).
#[derive(Clone, Debug)]
pub struct ContactPair {
    pub slave: usize,
    pub slave_side: Side,
    pub master: Master,
    /// θ ∈ {1, 0, −1}; the paper uses 0.
    pub theta: f64,
    /// Multiplies the empirical penalty (11); 1 reproduces the paper.
    pub penalty_factor: f64,
    pub integration: Integration,
    /// Gauss points per element or segment; default p + 2.
    pub gauss_points: Option<usize>,
}

impl ContactPair {
    /// The paper's choices: θ = 0, penalty factor 1, segment integration.
    pub fn new(slave: usize, slave_side: Side, master: Master) -> Self {
        Self {
            slave,
            slave_side,
            master,
            theta: 0.0,
            penalty_factor: 1.0,
            integration: Integration::Segment,
            gauss_points: None,
        }
    }
}

/// A contact quadrature point with its linear functionals over the DOFs in
/// `dofs` (global numbering): σ_n(u) = Σ sn_k u_k and ⟦u_n⟧ = Σ jn_k u_k.
#[derive(Clone, Debug)]
pub struct ContactPoint {
    pub pair: usize,
    /// Reference position x¹ on the slave.
    pub x: [f64; 2],
    /// Slave side parameter.
    pub t: f64,
    /// n¹ = −n²(x̄²).
    pub normal: [f64; 2],
    /// Initial gap g₀ = (X̄² − X¹)·n¹.
    pub g0: f64,
    pub gamma: f64,
    pub theta: f64,
    /// Quadrature weight including the arc length.
    pub weight: f64,
    pub dofs: Vec<usize>,
    pub sn: Vec<f64>,
    pub jn: Vec<f64>,
}

impl ContactPoint {
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
}

/// The master side as a curve with everything needed to evaluate it.
enum MasterGeometry<'a> {
    Rigid(&'a NurbsCurve),
    Body {
        body: usize,
        side: Side,
        curve: NurbsCurve,
        bodies: &'a [Body],
    },
}

impl MasterGeometry<'_> {
    fn curve(&self) -> &NurbsCurve {
        match self {
            MasterGeometry::Rigid(c) => c,
            MasterGeometry::Body { curve, .. } => curve,
        }
    }
}

fn validate(pair: &ContactPair, ip: usize, bodies: &[Body]) -> Result<()> {
    let f = |k: &str| format!("contact[{ip}].{k}");
    if pair.slave >= bodies.len() {
        return Err(Error::invalid(
            f("slave"),
            pair.slave,
            format!("there are {} bodies", bodies.len()),
        ));
    }
    if let Master::Body { body, .. } = pair.master {
        if body >= bodies.len() {
            return Err(Error::invalid(
                f("master"),
                body,
                format!("there are {} bodies", bodies.len()),
            ));
        }
        if body == pair.slave {
            return Err(Error::invalid(
                f("master"),
                body,
                "self-contact is not supported",
            ));
        }
    }
    if !pair.theta.is_finite() || ![-1.0, 0.0, 1.0].contains(&pair.theta) {
        return Err(Error::invalid(f("theta"), pair.theta, "must be 1, 0 or -1"));
    }
    if !(pair.penalty_factor.is_finite() && pair.penalty_factor > 0.0) {
        return Err(Error::invalid(
            f("penalty_factor"),
            pair.penalty_factor,
            "must be positive and finite",
        ));
    }
    if let Some(n) = pair.gauss_points {
        if n == 0 || n > 30 {
            return Err(Error::invalid(f("gauss_points"), n, "must lie in 1..=30"));
        }
    }
    Ok(())
}

/// Builds every contact quadrature point of every pair.
///
/// Points whose projection falls beyond the end of the master are left
/// out: no master surface faces them.
pub fn contact_points(
    bodies: &[Body],
    map: &DofMap,
    pairs: &[ContactPair],
) -> Result<Vec<ContactPoint>> {
    let mut out = Vec::new();
    for (ip, pair) in pairs.iter().enumerate() {
        validate(pair, ip, bodies)?;
        let slave = &bodies[pair.slave];
        let master = match &pair.master {
            Master::Rigid(c) => MasterGeometry::Rigid(c),
            Master::Body { body, side } => MasterGeometry::Body {
                body: *body,
                side: *side,
                curve: bodies[*body].space.patch.side_curve(*side),
                bodies,
            },
        };
        let (young, degree) = match &master {
            MasterGeometry::Rigid(_) => (slave.material.young, max_degree(slave)),
            MasterGeometry::Body { body, .. } => {
                let m = &bodies[*body];
                (
                    slave.material.young.max(m.material.young),
                    max_degree(slave).max(max_degree(m)),
                )
            }
        };
        let n_gauss = pair.gauss_points.unwrap_or(degree + 2);
        let slave_curve = slave.space.patch.side_curve(pair.slave_side);
        let cuts = match pair.integration {
            Integration::Gauss => Vec::new(),
            Integration::Segment => projected_master_knots(master.curve(), &slave_curve)
                .map_err(|e| within(e, ip, &slave_side(pair, bodies)))?,
        };
        for be in slave.space.boundary(pair.slave_side) {
            let mut breaks = vec![be.range[0]];
            let eps = 1e-10 * (be.range[1] - be.range[0]);
            breaks.extend(
                cuts.iter()
                    .copied()
                    .filter(|&t| t > be.range[0] + eps && t < be.range[1] - eps),
            );
            breaks.push(be.range[1]);
            for seg in breaks.windows(2) {
                for (t, w) in quadrature::on_interval(n_gauss, seg[0], seg[1]) {
                    if let Some(cp) =
                        make_point(ip, pair, bodies, map, &master, &be, t, w, young, degree)?
                    {
                        out.push(cp);
                    }
                }
            }
        }
    }
    Ok(out)
}

/// Words for the slave side of a pair, for messages.
fn slave_side(pair: &ContactPair, bodies: &[Body]) -> String {
    format!(
        "the slave side {} of body {:?}",
        pair.slave_side.name(),
        bodies[pair.slave].name
    )
}

/// A geometry error of contact pair `ip`, told as happening on `what`.
fn within(e: Error, ip: usize, what: &str) -> Error {
    match e {
        Error::Geometry(m) => Error::Geometry(format!("contact[{ip}]: {what}: {m}")),
        other => other,
    }
}

fn max_degree(b: &Body) -> usize {
    let d = b.space.patch.degree();
    d[0].max(d[1])
}

/// Slave-side parameters of the master's knots (segment integration).
fn projected_master_knots(master: &NurbsCurve, slave: &NurbsCurve) -> Result<Vec<f64>> {
    let mut out = Vec::new();
    for b in master.knots.breaks() {
        let pr = closest_point(slave, master.point(b))?;
        if pr.orthogonal {
            out.push(pr.t);
        }
    }
    out.sort_by(f64::total_cmp);
    Ok(out)
}

#[allow(clippy::too_many_arguments)]
fn make_point(
    ip: usize,
    pair: &ContactPair,
    bodies: &[Body],
    map: &DofMap,
    master: &MasterGeometry,
    be: &crate::space::BoundaryElement,
    t: f64,
    w: f64,
    young: f64,
    degree: usize,
) -> Result<Option<ContactPoint>> {
    let slave = &bodies[pair.slave];
    let space = &slave.space;
    let (shape, _, len) = space
        .side_shape(be, t)
        .map_err(|e| within(e, ip, &slave_side(pair, bodies)))?;
    let x = shape.x;
    let pr: Projection = closest_point(master.curve(), x).map_err(|e| {
        let what = match master {
            MasterGeometry::Rigid(_) => "the rigid master curve".to_string(),
            MasterGeometry::Body { body, side, .. } => format!(
                "the master side {} of body {:?}",
                side.name(),
                bodies[*body].name
            ),
        };
        within(e, ip, &what)
    })?;
    if !pr.orthogonal {
        return Ok(None);
    }
    // Master outward normal n², then n¹ = −n².
    let (n2, h_master, master_part) = match master {
        MasterGeometry::Rigid(_) => ([-pr.tangent[1], pr.tangent[0]], None, None),
        MasterGeometry::Body {
            body, side, bodies, ..
        } => {
            let mspace = &bodies[*body].space;
            let mb = mspace.boundary(*side);
            let k = mb
                .iter()
                .position(|e| pr.t >= e.range[0] && pr.t <= e.range[1])
                .unwrap_or(mb.len() - 1);
            let mbe = &mb[k];
            let el = &mspace.elements[mbe.element];
            let q = mspace.patch.side_point(*side, pr.t);
            let basis = mspace.patch.basis_in_spans(el.spans, q[0], q[1]);
            let (n, _) = mspace.patch.side_frame(*side, &basis);
            (n, Some(mbe.length), Some((*body, el.cps.clone(), basis.r)))
        }
    };
    let normal = [-n2[0], -n2[1]];
    let g0 = (pr.point[0] - x[0]) * normal[0] + (pr.point[1] - x[1]) * normal[1];
    let gamma = empirical_penalty(
        PenaltyInputs {
            young,
            degree,
            h_slave: be.length,
            h_master,
        },
        pair.penalty_factor,
    );

    // σ_n = mᵀ D B u with m = (n_x², n_y², 2 n_x n_y) in Voigt notation.
    let d = slave.material.d_matrix();
    let m = [
        normal[0] * normal[0],
        normal[1] * normal[1],
        2.0 * normal[0] * normal[1],
    ];
    let q: Vec<f64> = (0..3)
        .map(|j| (0..3).map(|i| m[i] * d[i][j]).sum())
        .collect();
    let el = &space.elements[be.element];
    let mut dofs = map.element_dofs(pair.slave, &el.cps);
    let mut sn = Vec::with_capacity(dofs.len());
    let mut jn = Vec::with_capacity(dofs.len());
    for (a, g) in shape.grad.iter().enumerate() {
        sn.push(q[0] * g[0] + q[2] * g[1]);
        sn.push(q[1] * g[1] + q[2] * g[0]);
        jn.push(shape.r[a] * normal[0]);
        jn.push(shape.r[a] * normal[1]);
    }
    if let Some((mbody, cps, r)) = master_part {
        for (b, &cp) in cps.iter().enumerate() {
            if r[b] == 0.0 {
                continue;
            }
            for c in 0..2 {
                dofs.push(map.global(mbody, cp, c));
                sn.push(0.0);
                jn.push(-r[b] * normal[c]);
            }
        }
    }
    Ok(Some(ContactPoint {
        pair: ip,
        x,
        t,
        normal,
        g0,
        gamma,
        theta: pair.theta,
        weight: w * len,
        dofs,
        sn,
        jn,
    }))
}
