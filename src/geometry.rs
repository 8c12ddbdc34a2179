//! Geometry builders. Circles are quadratic rational arcs, so every circular
//! boundary is exact, before and after refinement.

use crate::error::{Error, Result};
use crate::nurbs::interpolate::Collocation;
use crate::nurbs::{KnotVector, NurbsCurve, NurbsPatch};

const S: f64 = std::f64::consts::FRAC_1_SQRT_2;

fn check_positive(field: &str, v: f64) -> Result<()> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(field, v, "must be positive and finite"))
    }
}

fn bilinear() -> [KnotVector; 2] {
    let k = KnotVector::new(vec![0.0, 0.0, 1.0, 1.0], 1).expect("static knots");
    [k.clone(), k]
}

fn quadratic_single_span() -> KnotVector {
    KnotVector::new(vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], 2).expect("static knots")
}

/// The rectangle [x0, x1] × [y0, y1] as a bilinear patch (ξ along x, η along y).
pub fn rectangle(x0: f64, y0: f64, x1: f64, y1: f64) -> Result<NurbsPatch> {
    for (f, v) in [("x0", x0), ("y0", y0), ("x1", x1), ("y1", y1)] {
        crate::error::finite(f, v)?;
    }
    check_positive("width", x1 - x0)?;
    check_positive("height", y1 - y0)?;
    NurbsPatch::new(
        bilinear(),
        vec![[x0, y0], [x1, y0], [x0, y1], [x1, y1]],
        vec![1.0; 4],
    )
}

/// A general bilinear quadrilateral with corners in counter-clockwise order
/// (used for distorted patch tests).
pub fn quadrilateral(c: [[f64; 2]; 4]) -> Result<NurbsPatch> {
    NurbsPatch::new(bilinear(), vec![c[0], c[1], c[3], c[2]], vec![1.0; 4])
}

/// The full disk of radius `r` about `center`: the classical nine-point
/// quadratic patch whose four sides are 90° arcs, with corners at 225°,
/// 315°, 45° and 135°.
///
/// The Jacobian vanishes at the four corners (the boundary is smooth there),
/// which Gauss quadrature never samples.
pub fn full_disk(center: [f64; 2], r: f64) -> Result<NurbsPatch> {
    check_positive("radius", r)?;
    let q = std::f64::consts::SQRT_2;
    let unit = [
        ([-S, -S], 1.0),
        ([0.0, -q], S),
        ([S, -S], 1.0),
        ([-q, 0.0], S),
        ([0.0, 0.0], 1.0),
        ([q, 0.0], S),
        ([-S, S], 1.0),
        ([0.0, q], S),
        ([S, S], 1.0),
    ];
    let points = unit
        .iter()
        .map(|(p, _)| [center[0] + r * p[0], center[1] + r * p[1]])
        .collect();
    let weights = unit.iter().map(|(_, w)| *w).collect();
    NurbsPatch::new(
        [quadratic_single_span(), quadratic_single_span()],
        points,
        weights,
    )
}

/// The half disk {x ≥ cx} of the disk of radius `r` about `center`: the
/// right half of [`full_disk`], cut exactly along ξ = 1/2 by knot insertion.
///
/// Sides: `xi_min` is the straight diameter (symmetry line), `eta_min` the
/// 45° arc from the lowest point (cx, cy − r) to the 315° point, `xi_max` the
/// 90° arc on the right and `eta_max` the 45° arc ending at the top.
pub fn half_disk(center: [f64; 2], r: f64) -> Result<NurbsPatch> {
    full_disk(center, r)?.upper_part_xi(0.5)
}

/// The quarter annulus r_in ≤ |x| ≤ r_out in the first quadrant. ξ runs
/// along the arcs (quadratic, from the x axis to the y axis), η radially
/// (linear). Sides: `eta_min` inner arc, `eta_max` outer arc, `xi_min` on
/// the x axis, `xi_max` on the y axis.
pub fn quarter_annulus(r_in: f64, r_out: f64) -> Result<NurbsPatch> {
    check_positive("inner_radius", r_in)?;
    check_positive("outer_radius - inner_radius", r_out - r_in)?;
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for r in [r_in, r_out] {
        points.extend([[r, 0.0], [r, r], [0.0, r]]);
        weights.extend([1.0, S, 1.0]);
    }
    let lin = KnotVector::new(vec![0.0, 0.0, 1.0, 1.0], 1).expect("static knots");
    NurbsPatch::new([quadratic_single_span(), lin], points, weights)
}

/// The half annulus r_in ≤ |x − c| ≤ r_out, x ≥ cx, about `center`: one
/// patch whose arcs are exact. ξ runs counter-clockwise along the arcs
/// from the lowest points (270°) through 0° to the highest (90°):
/// quadratic, two 90° rational arcs joined by a double knot at ξ = 1/2
/// (no single quadratic span reaches 180°: its middle weight would be 0).
/// The two arcs have equal parametric speed at the junction, so the map is
/// C¹ there although the basis is only C⁰. η runs outward (linear).
/// Sides: `eta_min` the inner arc, `eta_max` the outer arc, `xi_min` the
/// lower cut on x = cx, `xi_max` the upper one. det J < 0 everywhere (ξ
/// counter-clockwise, η outward), as for [`quarter_annulus`].
///
/// Refined with `elements = [n, m]`, each 90° arc gets n elements (so 2n
/// along the half) and the radial direction m.
pub fn half_annulus(center: [f64; 2], r_in: f64, r_out: f64) -> Result<NurbsPatch> {
    crate::error::finite("center", center[0])?;
    crate::error::finite("center", center[1])?;
    check_positive("inner_radius", r_in)?;
    check_positive("outer_radius - inner_radius", r_out - r_in)?;
    let unit = [
        ([0.0, -1.0], 1.0),
        ([1.0, -1.0], S),
        ([1.0, 0.0], 1.0),
        ([1.0, 1.0], S),
        ([0.0, 1.0], 1.0),
    ];
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for r in [r_in, r_out] {
        for (u, w) in unit {
            points.push([center[0] + r * u[0], center[1] + r * u[1]]);
            weights.push(w);
        }
    }
    let arcs = KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0], 2)?;
    let lin = KnotVector::new(vec![0.0, 0.0, 1.0, 1.0], 1)?;
    NurbsPatch::new([arcs, lin], points, weights)
}

/// A straight segment as a linear NURBS curve (a rigid flat obstacle).
pub fn segment(a: [f64; 2], b: [f64; 2]) -> Result<NurbsCurve> {
    let k = KnotVector::new(vec![0.0, 0.0, 1.0, 1.0], 1)?;
    NurbsCurve::new(k, vec![a, b], vec![1.0, 1.0])
}

/// The isoparametric Lagrange (FEM) counterpart of `exact`: a C⁰ spline of
/// degree `degree` on `elements` equal parameter spans per direction that
/// interpolates `exact` at the equispaced Lagrange nodes of every element.
///
/// Per element, the C⁰ spline space *is* Q_p, and interpolation at the
/// nodes is exactly the Lagrange interpolant, so this reproduces an
/// isoparametric Q1/Q2 mesh whose nodes lie on the exact geometry (on the
/// circle, for a disk) while the edges between nodes are polynomial chords.
/// Being a spline patch, it runs through the same assembly, contact and
/// solvers as the NURBS model — only the basis differs.
pub fn lagrange_interpolant(
    exact: &NurbsPatch,
    degree: usize,
    elements: [usize; 2],
) -> Result<NurbsPatch> {
    if !(1..=4).contains(&degree) {
        return Err(Error::invalid(
            "lagrange_degree",
            degree,
            "must lie in 1..=4",
        ));
    }
    let mut knots = Vec::new();
    let mut nodes = Vec::new();
    for (dir, &n) in elements.iter().enumerate() {
        let (a, b) = (exact.knots[dir].first(), exact.knots[dir].last());
        let kv = KnotVector::uniform(degree, n, 0)?;
        let tau: Vec<f64> = (0..=n * degree)
            .map(|k| a + (b - a) * k as f64 / (n * degree) as f64)
            .collect();
        let scaled: Vec<f64> = kv.knots().iter().map(|t| a + (b - a) * t).collect();
        knots.push(KnotVector::new(scaled, degree)?);
        nodes.push(tau);
    }
    let c0 = Collocation::new(&knots[0], &nodes[0])?;
    let c1 = Collocation::new(&knots[1], &nodes[1])?;
    let (n0, n1) = (nodes[0].len(), nodes[1].len());
    // Tensor-product interpolation: the values at the nodes, solved along
    // ξ for every η row, then along η for every ξ column.
    let mut values = Vec::with_capacity(n0 * n1);
    for &eta in &nodes[1] {
        for &xi in &nodes[0] {
            values.push(exact.point(xi, eta));
        }
    }
    let mut line = Vec::with_capacity(n0.max(n1));
    for c in 0..2 {
        for j in 0..n1 {
            line.clear();
            line.extend((0..n0).map(|i| values[i + j * n0][c]));
            c0.solve_in_place(&mut line);
            for (i, v) in line.iter().enumerate() {
                values[i + j * n0][c] = *v;
            }
        }
        for i in 0..n0 {
            line.clear();
            line.extend((0..n1).map(|j| values[i + j * n0][c]));
            c1.solve_in_place(&mut line);
            for (j, v) in line.iter().enumerate() {
                values[i + j * n0][c] = *v;
            }
        }
    }
    let points = values;
    let [k0, k1]: [KnotVector; 2] = knots.try_into().expect("two directions");
    NurbsPatch::new([k0, k1], points, vec![1.0; n0 * n1])
}

/// A body of several patches with matching interfaces, and its named
/// boundaries: each a list of (patch, side) joined end to end, in order
/// along the boundary.
#[derive(Clone, Debug)]
pub struct MultiPatch {
    pub patches: Vec<NurbsPatch>,
    pub boundaries: Vec<(&'static str, Vec<(usize, crate::nurbs::Side)>)>,
    /// Per patch and parametric direction, which count of a refinement
    /// `elements = [along, across]` it takes (see [`MultiPatch::refined`]).
    pub counts: Vec<[Count; 2]>,
}

/// Which of the two element counts of a multi-patch refinement a patch
/// direction takes: the count along the circle (and along the core's
/// sides, which face arcs) or the count across the arc patches.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Count {
    Along,
    Across,
}

impl MultiPatch {
    /// Every patch k-refined to `degree` with `elements = [along, across]`
    /// distributed by [`MultiPatch::counts`], so that every interface
    /// keeps matching.
    pub fn refined(&self, degree: usize, elements: [usize; 2]) -> Result<Vec<NurbsPatch>> {
        self.patches
            .iter()
            .zip(&self.counts)
            .map(|(p, c)| p.k_refined(degree, self.divisions(c, elements)))
            .collect()
    }

    /// The element counts per direction of a patch of counts `c`.
    pub fn divisions(&self, c: &[Count; 2], elements: [usize; 2]) -> [usize; 2] {
        c.map(|d| match d {
            Count::Along => elements[0],
            Count::Across => elements[1],
        })
    }

    /// The pieces of the boundary called `name`, if the builder defines it.
    pub fn boundary(&self, name: &str) -> Option<&[(usize, crate::nurbs::Side)]> {
        self.boundaries
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, b)| b.as_slice())
    }

    /// The names of the boundaries, for messages.
    pub fn boundary_names(&self) -> Vec<&'static str> {
        self.boundaries.iter().map(|(n, _)| *n).collect()
    }
}

/// Half the side of the square core of [`disk_5`], as a share of the radius:
/// the core's corners sit at 0.4·√2 ≈ 0.57 of the radius, so the four arc
/// patches are of about the core's size and no element is squeezed.
const CORE: f64 = 0.4;

/// A patch between a straight inner segment and a circular arc of at
/// most 90° about the origin of the unit disk: ξ along both (quadratic,
/// with the arc's weights on both rows, so the segment is straight), η
/// from the segment (η = 0) to the arc (η = 1), linear. Rows: `inner`
/// then `outer`, each three control points.
fn arc_patch(inner: [[f64; 2]; 3], outer: [[f64; 2]; 3], w: f64) -> Result<NurbsPatch> {
    let lin = KnotVector::new(vec![0.0, 0.0, 1.0, 1.0], 1).expect("static knots");
    let points = inner.iter().chain(&outer).copied().collect();
    NurbsPatch::new(
        [quadratic_single_span(), lin],
        points,
        vec![1.0, w, 1.0, 1.0, w, 1.0],
    )
}

/// Scales the unit-disk patches to radius `r` about `center`.
fn placed(patches: Vec<NurbsPatch>, center: [f64; 2], r: f64) -> Vec<NurbsPatch> {
    patches
        .into_iter()
        .map(|p| p.transformed(|x| [center[0] + r * x[0], center[1] + r * x[1]]))
        .collect()
}

/// The five patches of the unit disk: the core square [−a, a]² (ξ along x,
/// η along y, quadratic with the arcs' weights so its sides match theirs)
/// and the arc patches below, right, above and left of it, each between a
/// side of the core and a 90° arc (ξ counter-clockwise along the arc, η
/// outward). `top_clockwise` runs the upper arc patch's ξ the other way
/// (for [`half_disk_4`], which keeps its right half).
fn unit_disk_5(top_clockwise: bool) -> Result<Vec<NurbsPatch>> {
    let a = CORE;
    let q = std::f64::consts::SQRT_2;
    let mut core_pts = Vec::new();
    let mut core_w = Vec::new();
    let u = [1.0, S, 1.0];
    for (j, y) in [-a, 0.0, a].iter().enumerate() {
        for (i, x) in [-a, 0.0, a].iter().enumerate() {
            core_pts.push([*x, *y]);
            core_w.push(u[i] * u[j]);
        }
    }
    let core = NurbsPatch::new(
        [quadratic_single_span(), quadratic_single_span()],
        core_pts,
        core_w,
    )?;
    let bottom = arc_patch(
        [[-a, -a], [0.0, -a], [a, -a]],
        [[-S, -S], [0.0, -q], [S, -S]],
        S,
    )?;
    let right = arc_patch([[a, -a], [a, 0.0], [a, a]], [[S, -S], [q, 0.0], [S, S]], S)?;
    let top = if top_clockwise {
        arc_patch([[-a, a], [0.0, a], [a, a]], [[-S, S], [0.0, q], [S, S]], S)?
    } else {
        arc_patch([[a, a], [0.0, a], [-a, a]], [[S, S], [0.0, q], [-S, S]], S)?
    };
    let left = arc_patch(
        [[-a, a], [-a, 0.0], [-a, -a]],
        [[-S, S], [-q, 0.0], [-S, -S]],
        S,
    )?;
    Ok(vec![core, bottom, right, top, left])
}

/// The disk of radius `r` about `center` as five patches without a
/// singular point: a square core (patch 0) and four arc patches, below
/// (1), right (2), above (3) and left (4) of it, each spanning 90° of the
/// circle between the directions 225°, 315°, 45° and 135°; every circle is
/// exact. Boundaries: `arc` (the whole circle, counter-clockwise from
/// 225°), `arc_bottom`, `arc_right`, `arc_top`, `arc_left` (one arc patch
/// each) and `arc_lower` (135° through 270° to 45°: left, bottom, right).
///
/// Refined with `elements = [n, m]`, every arc patch gets n elements along
/// its arc and m across, and the core n × n, so that every interface
/// matches.
pub fn disk_5(center: [f64; 2], r: f64) -> Result<MultiPatch> {
    check_positive("radius", r)?;
    use crate::nurbs::Side::EtaMax;
    Ok(MultiPatch {
        patches: placed(unit_disk_5(false)?, center, r),
        boundaries: vec![
            (
                "arc",
                vec![(1, EtaMax), (2, EtaMax), (3, EtaMax), (4, EtaMax)],
            ),
            ("arc_bottom", vec![(1, EtaMax)]),
            ("arc_right", vec![(2, EtaMax)]),
            ("arc_top", vec![(3, EtaMax)]),
            ("arc_left", vec![(4, EtaMax)]),
            ("arc_lower", vec![(4, EtaMax), (1, EtaMax), (2, EtaMax)]),
        ],
        counts: arc_counts(5),
    })
}

/// [`disk_5`] turned by −45° about its centre: the core's corners lie on
/// the axes through the centre and the arc patches are the four quadrants,
/// lower left (patch 1, 180° to 270°), lower right (2), upper right (3)
/// and upper left (4), so the vertical centre line runs through patch
/// corners (the core's top and bottom corners, the lowest and highest
/// points), where a point support can hold the disk in x as a symmetry
/// line would. Boundaries: `arc` (counter-clockwise from 180°),
/// `arc_lower` (180° to 360°: patches 1 and 2), `arc_upper` (0° to 180°),
/// `arc_right` (270° to 90°) and `arc_left` (90° to 270°). Refined as
/// [`disk_5`].
pub fn disk_5_diagonal(center: [f64; 2], r: f64) -> Result<MultiPatch> {
    check_positive("radius", r)?;
    use crate::nurbs::Side::EtaMax;
    let (c, s) = (
        std::f64::consts::FRAC_1_SQRT_2,
        -std::f64::consts::FRAC_1_SQRT_2,
    );
    let turned = unit_disk_5(false)?
        .into_iter()
        .map(|p| p.transformed(|x| [c * x[0] - s * x[1], s * x[0] + c * x[1]]))
        .collect();
    Ok(MultiPatch {
        patches: placed(turned, center, r),
        boundaries: vec![
            (
                "arc",
                vec![(1, EtaMax), (2, EtaMax), (3, EtaMax), (4, EtaMax)],
            ),
            ("arc_lower", vec![(1, EtaMax), (2, EtaMax)]),
            ("arc_upper", vec![(3, EtaMax), (4, EtaMax)]),
            ("arc_right", vec![(2, EtaMax), (3, EtaMax)]),
            ("arc_left", vec![(4, EtaMax), (1, EtaMax)]),
        ],
        counts: arc_counts(5),
    })
}

/// The half disk {x ≥ cx} of radius `r` about `center` as four patches
/// without a singular point: the right halves of [`disk_5`]'s core
/// (patch 0), lower arc patch (1, from 270° to 315°) and upper arc patch
/// (3, from 90° to 45°), and its right arc patch (2, from 315° to 45°).
/// Boundaries: `straight` (the diameter on x = cx: the sides ξ = 0 of
/// patches 1, 0 and 3), `arc` (270° to 90°), `arc_lower` (270° to 45°:
/// patches 1 and 2) and `arc_bottom` (patch 1 alone).
///
/// Four is the fewest: quadrilaterals that meet side to side with no
/// corner of 180° (where det J would vanish) cannot tile a half disk in
/// three, since its two 90° corners leave an odd number of ends for the
/// interior edges. Refined with `elements = [n, m]`, every patch gets n
/// elements along the circle (and along each side of the core) and m
/// across the arc patches.
pub fn half_disk_4(center: [f64; 2], r: f64) -> Result<MultiPatch> {
    check_positive("radius", r)?;
    use crate::nurbs::Side::{EtaMax, XiMin};
    let full = unit_disk_5(true)?;
    let patches = vec![
        full[0].upper_part_xi(0.5)?,
        full[1].upper_part_xi(0.5)?,
        full[2].clone(),
        full[3].upper_part_xi(0.5)?,
    ];
    Ok(MultiPatch {
        patches: placed(patches, center, r),
        boundaries: vec![
            ("straight", vec![(1, XiMin), (0, XiMin), (3, XiMin)]),
            ("arc", vec![(1, EtaMax), (2, EtaMax), (3, EtaMax)]),
            ("arc_lower", vec![(1, EtaMax), (2, EtaMax)]),
            ("arc_bottom", vec![(1, EtaMax)]),
        ],
        counts: arc_counts(4),
    })
}

/// The core (patch 0) takes the count along the circle both ways, the arc
/// patches along their arc and across.
fn arc_counts(n: usize) -> Vec<[Count; 2]> {
    let mut c = vec![[Count::Along, Count::Across]; n];
    c[0] = [Count::Along, Count::Along];
    c
}
