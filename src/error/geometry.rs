//! Why a geometric query failed, as data.

/// Why a geometric query failed: the parameters and values where it did,
/// and, in the wrapping variants, where in the model (a body, an element,
/// a contact pair) the query was made.
///
/// The layers from [`crate::nurbs`] to [`crate::report`] raise it; it
/// lives with the crate error, which carries it, because that error sits
/// below every layer that fails.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum GeometryError {
    /// Knot refinement from the space of `old` to that of `new` would
    /// change the parameter range or lower the degree.
    #[error("refinement must keep the parameter range and not lower the degree")]
    RefinementNotNested {
        old_degree: usize,
        new_degree: usize,
        old_range: [f64; 2],
        new_range: [f64; 2],
    },
    /// The coefficients handed to a refinement are not `dim` per basis
    /// function.
    #[error("{coefficients} coefficients of dimension {dim} do not match {basis} basis functions")]
    CoefficientCount {
        coefficients: usize,
        dim: usize,
        basis: usize,
    },
    /// `knot` appears in the refined space with too low a multiplicity for
    /// that space to contain the old one.
    #[error("knot {knot} needs a higher multiplicity in the refined space to keep the continuity (the refined space must contain the old one)")]
    KnotMultiplicity { knot: f64 },
    /// Interpolation needs one point per basis function.
    #[error("interpolation needs {basis} points for {basis} basis functions, got {points}")]
    InterpolationPointCount { basis: usize, points: usize },
    /// Interpolation point `point` lies in the support of a basis function
    /// more than the degree away from `function` (Schoenberg–Whitney).
    #[error("interpolation point {point} is too far from the support of basis function {function} (Schoenberg–Whitney condition violated)")]
    FarFromSupport { point: f64, function: usize },
    /// Interpolation point `point` lies outside the support of basis
    /// function `function`, its own (Schoenberg–Whitney).
    #[error("interpolation point {point} does not lie in the support of basis function {function} (Schoenberg–Whitney condition violated)")]
    OutsideSupport { point: f64, function: usize },
    /// det J is zero or not finite at the centre of the first element, so
    /// the patch has no orientation.
    #[error("the geometric map is degenerate at (ξ, η) = ({xi}, {eta}): det J = {det_j:.3e}")]
    DegenerateMap { xi: f64, eta: f64, det_j: f64 },
    /// det J vanishes at (ξ, η) or has the sign opposite to the patch
    /// `orientation` (±1): the map folds.
    #[error("the geometric map is not invertible at (ξ, η) = ({xi}, {eta}): det J = {det_j:.3e} (patch orientation {orientation:+})")]
    NotInvertible {
        xi: f64,
        eta: f64,
        det_j: f64,
        orientation: f64,
    },
    /// det J at (ξ, η) and at the points nudged towards the element centre
    /// is negligible against its value `centre` there.
    #[error("the geometric map is nearly singular at (ξ, η) = ({xi}, {eta}) and around it: det J = {det_j:.3e} against {centre:.3e} at the element centre")]
    NearlySingular {
        xi: f64,
        eta: f64,
        det_j: f64,
        centre: f64,
    },
    /// The pressure mass matrix of element `element` of the mixed body
    /// `body` (its name) has no Cholesky factor.
    #[error("body `{body}`, element {element}: the pressure mass matrix is not positive definite")]
    PressureMass { body: String, element: usize },
    /// A closest-point projection was asked for a point that is not finite.
    #[error("cannot project the non-finite point {point:?}")]
    NonFinitePoint { point: [f64; 2] },
    /// The closest point of `point` lies where the curve has no tangent.
    #[error("cannot project {point:?}: the curve is degenerate at t = {t} (zero tangent)")]
    ZeroTangent { point: [f64; 2], t: f64 },
    /// The normal line through `point` meets the curve where it has no
    /// tangent.
    #[error("cannot intersect the normal line at {point:?}: the curve is degenerate at t = {t}")]
    NormalLineDegenerate { point: [f64; 2], t: f64 },
    /// `cause` at the element of knot spans `spans` of body `body` (its
    /// name).
    #[error("body `{body}`, element spans {spans:?}: {cause}")]
    Element {
        body: String,
        spans: [usize; 2],
        cause: Box<GeometryError>,
    },
    /// `cause` at a point of body `body` (its name) sampled for output.
    #[error("body `{body}`: {cause}")]
    Sample {
        body: String,
        cause: Box<GeometryError>,
    },
    /// `cause` while building body `index` of a scene, named `name`.
    #[error("body[{index}] ({name:?}): {cause}")]
    Body {
        index: usize,
        name: String,
        cause: Box<GeometryError>,
    },
    /// `cause` on the part `part` of the contact pair of scene entry
    /// `contact[contact]`.
    #[error("contact[{contact}]: {part}: {cause}")]
    Contact {
        contact: usize,
        part: ContactPart,
        cause: Box<GeometryError>,
    },
}

impl GeometryError {
    /// Whether the geometric map itself is at fault (zero, folded or nearly
    /// singular det J), under any context: an error of the input geometry,
    /// not of a query on it.
    pub fn is_map_fault(&self) -> bool {
        match self {
            GeometryError::DegenerateMap { .. }
            | GeometryError::NotInvertible { .. }
            | GeometryError::NearlySingular { .. } => true,
            GeometryError::Element { cause, .. } | GeometryError::Body { cause, .. } => {
                cause.is_map_fault()
            }
            _ => false,
        }
    }
}

/// The curve of a contact pair a geometric query ran on.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ContactPart {
    /// The slave side named `side` (`eta_min`, ...) of body `body`.
    SlaveSide { side: &'static str, body: String },
    /// The master side named `side` of body `body`.
    MasterSide { side: &'static str, body: String },
    /// The rigid master curve.
    RigidMaster,
}

impl std::fmt::Display for ContactPart {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ContactPart::SlaveSide { side, body } => {
                write!(f, "the slave side {side} of body {body:?}")
            }
            ContactPart::MasterSide { side, body } => {
                write!(f, "the master side {side} of body {body:?}")
            }
            ContactPart::RigidMaster => f.write_str("the rigid master curve"),
        }
    }
}
