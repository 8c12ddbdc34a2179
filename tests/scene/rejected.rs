//! Rejected scenes: one table, one row per refused case. Each row checks
//! that the error names the key path and the value, and what its message
//! says (and does not).

use crate::text::{
    base_with, block_on_floor, lower_body, master, nitsche, nurbs_body, one_body, plain_body,
    refine, BASE, HELD, SQUARE, TRIANGLE,
};
use iga_contact::scene::Scene;
use iga_contact::Error;

/// Asserts that `text` fails, parsing or building, with an invalid-input
/// error naming `path` and showing `value` (a row of [`rejected`]).
#[track_caller]
pub fn rejects(text: &str, path: &'static str, value: &'static str) {
    if let Some(why) = reject(text, path, value).failure() {
        panic!("`{path}`: {why}");
    }
}

/// A scene that must be refused, by parsing or by building: the key path
/// and the value the error names, and what its message says (and does
/// not).
struct Reject {
    text: String,
    path: &'static str,
    value: &'static str,
    says: &'static [&'static str],
    lacks: &'static [&'static str],
}

/// A row of [`rejected`].
fn reject(text: impl Into<String>, path: &'static str, value: &'static str) -> Reject {
    Reject {
        text: text.into(),
        path,
        value,
        says: &[],
        lacks: &[],
    }
}

impl Reject {
    /// Fragments the message must contain.
    fn says(self, says: &'static [&'static str]) -> Self {
        Self { says, ..self }
    }

    /// Fragments the message must not contain.
    fn lacks(self, lacks: &'static [&'static str]) -> Self {
        Self { lacks, ..self }
    }

    /// Why this row fails, if it does.
    fn failure(&self) -> Option<String> {
        let (path, value) = (self.path, self.value);
        let err = match Scene::from_toml_str(&self.text).and_then(|s| s.build()) {
            Ok(_) => return Some("accepted".into()),
            Err(e) => e,
        };
        let msg = err.to_string();
        let Error::InvalidInput {
            field, value: v, ..
        } = &err
        else {
            return Some(format!("not invalid input: {msg}"));
        };
        if field != path || v != value {
            return Some(format!("names `{field}` = {v}: {msg}"));
        }
        if !msg.contains(&format!("`{path}` = {value}")) {
            return Some(format!("does not show `{path}` = {value}: {msg}"));
        }
        let missing: Vec<_> = self.says.iter().filter(|s| !msg.contains(*s)).collect();
        let present: Vec<_> = self.lacks.iter().filter(|s| msg.contains(*s)).collect();
        (!missing.is_empty() || !present.is_empty())
            .then(|| format!("lacks {missing:?}, has {present:?}: {msg}"))
    }
}

/// Every refused scene: the rules of the shape (unknown keys, types,
/// either-or tables), of the values, of well-posedness and of the scales
/// double precision carries. Adding a rule's case is adding a row.
// One row a line where it fits, so that the table reads as one.
#[rustfmt::skip]
fn rejected() -> Vec<Reject> {
    let nurbs_square = |degree: &str| {
        nurbs_body("[0.0, 0.0, 1.0, 1.0]", SQUARE, "").replacen("degree = [1, 1]", degree, 1)
    };
    let held = block_on_floor(HELD);
    vec![
        // unknown keys
        reject(format!("{BASE}\n[outputs]\nvtu = true\n"), "outputs", "{ vtu = true }")
            .says(&["unknown field `outputs`"]),
        reject(base_with("poisson = 0.3,", "poisson = 0.3, nu = 0.3,"), "body[0].material.nu", "0.3")
            .says(&["unknown field `nu`"]),
        reject(base_with("x1 = 1.0, y1 = 0.5", "x1 = 1.0, y1 = 0.5, z1 = 2"), "body[0].geometry.rectangle.z1", "2"),
        reject(base_with("side = \"eta_max\" }", "side = \"eta_max\", rigid = true }"), "contact[0].master.rigid", "true"),
        reject(base_with("rtol = 1e-10", "rtol = 1e-10\ntolerance = 1"), "solver.tolerance", "1"),
        reject(format!("{BASE}\n[output]\nvtk = true\n"), "output.vtk", "true"),
        // types
        reject(base_with("young = 1.0e9, poisson = 0.3", "young = \"big\", poisson = 0.3"), "body[0].material.young", "\"big\"")
            .says(&["expected a number"])
            .lacks(&["f64"]),
        // serde's type names do not reach the user
        reject(base_with("geometry = { rectangle = { x0 = 0.0", "geometry = { full_disk = { center = [0.0, 0.0], radius = 1.0 }, rectangle = { x0 = 0.0"), "body[0].geometry", "{ full_disk = { center = [0.0, 0.0], radius = 1.0 }, rectangle = { x0 = 0.0, x1 …")
            .says(&["name exactly one kind"]).lacks(&["element"]),
        reject(base_with("refine = { degree = 2, elements = [2, 1] }", "refine = 3"), "body[0].refine", "3").says(&["expected a table"]).lacks(&["struct", "RefineSpec"]),
        reject(refine("degree = 1.5, elements = [2, 1]"), "body[0].refine.degree", "1.5").says(&["non-negative integer"]).lacks(&["usize"]),
        reject(refine("degree = 2, elements = [2, -1]"), "body[0].refine.elements[1]", "-1"),
        reject(refine("degree = 2, elements = [2]"), "body[0].refine.elements", "[2]"),
        reject(base_with("kind = \"bfgs\"", "kind = \"lbfgs\""), "solver.kind", "\"lbfgs\""),
        reject(base_with("kind = \"bfgs\"", "kind = \"bfgs\"\nfactorisation = \"cholesky\""), "solver.factorisation", "\"cholesky\""),
        reject(base_with("plane = \"stress\"", "plane = \"strainn\""), "body[0].material.plane", "\"strainn\""),
        reject(base_with("slave_side = \"eta_min\"", "slave_side = \"bottom\""), "contact[0].slave_side", "\"bottom\"")
            .says(&["eta_min"]),
        reject(base_with("side = \"eta_min\"", "side = \"south\""), "support[0].side", "\"south\""),
        // where a support or a slave acts: exactly one of its keys
        reject(base_with("side = \"eta_min\"\ncomponent = \"y\"", "side = \"eta_min\"\npoint = [0.0, 0.0]\ncomponent = \"y\""), "support[0]", "body \"lower\"")
            .says(&["needs exactly one of `side`, `boundary` or `point`"]),
        reject(base_with("slave_side = \"eta_min\"", "slave_side = \"eta_min\"\nslave_boundary = \"arc\""), "contact[0].slave_side", "slave \"upper\"")
            .says(&["needs exactly one of `slave_side`"]),
        // materials and finite numbers
        reject(base_with("young = 1.0e9", "young = -1.0"), "body[0].material.young", "-1"),
        reject(base_with("young = 1.0e9", "young = 0.0"), "body[0].material.young", "0"),
        reject(base_with("poisson = 0.3", "poisson = 0.5"), "body[0].material.poisson", "0.5"),
        reject(base_with("poisson = 0.3", "poisson = -1.0"), "body[0].material.poisson", "-1"),
        reject(base_with("young = 1.0e9", "young = inf"), "body[0].material.young", "inf"),
        reject(base_with("x0 = 0.0, y0 = 0.0", "x0 = nan, y0 = 0.0"), "body[0].geometry.rectangle.x0", "NaN"),
        reject(base_with("value = 0.0", "value = -inf"), "support[0].value", "-inf"),
        // refinement
        reject(refine("degree = 0, elements = [2, 1]"), "body[0].refine.degree", "0"),
        reject(refine("degree = 11, elements = [2, 1]"), "body[0].refine.degree", "11"),
        reject(
            one_body("{ half_disk = { center = [0.0, 0.2], radius = 0.2 } }", "refine = { degree = 1, elements = [2, 2] }"),
            "body[0].refine.degree",
            "1",
        )
        .says(&["lagrange"]),
        reject(refine("degree = 2, elements = [2, 0]"), "body[0].refine.elements[1]", "0"),
        reject(refine("degree = 2, elements = [5000, 1]"), "body[0].refine.elements[0]", "5000"),
        reject(refine("lagrange = 5, elements = [2, 1]"), "body[0].refine.lagrange", "5"),
        reject(refine("lagrange = 0, elements = [2, 1]"), "body[0].refine.lagrange", "0"),
        reject(refine("degree = 2, lagrange = 2, elements = [2, 1]"), "body[0].refine.degree", "2"),
        reject(refine("elements = [2, 1]"), "body[0].refine", "elements = [2, 1]"),
        reject(lower_body("quadrature = 0"), "body[0].quadrature", "0"),
        // geometry
        reject(
            one_body("{ half_disk = { center = [0.0, 0.2], radius = -0.2 } }", "refine = { degree = 2, elements = [2, 2] }"),
            "body[0].geometry.half_disk.radius",
            "-0.2",
        ),
        reject(plain_body("{ full_disk = { center = [0.0, 0.0], radius = 0.0 } }"), "body[0].geometry.full_disk.radius", "0"),
        reject(plain_body("{ full_disk = { center = [0.0, 0.0], radius = 1e308 } }"), "body[0].geometry.full_disk.radius", "1e308"),
        reject(
            plain_body("{ quarter_annulus = { inner_radius = -1.0, outer_radius = 2.0 } }"),
            "body[0].geometry.quarter_annulus.inner_radius",
            "-1",
        ),
        reject(
            plain_body("{ quarter_annulus = { inner_radius = 2.0, outer_radius = 1.0 } }"),
            "body[0].geometry.quarter_annulus.outer_radius",
            "1",
        ),
        reject(plain_body("{ full_disk = { center = [inf, 0.0], radius = 1.0 } }"), "body[0].geometry.full_disk.center[0]", "inf"),
        reject(base_with("x1 = 1.0, y1 = 0.5", "x1 = -1.0, y1 = 0.5"), "body[0].geometry.rectangle.x1", "-1"),
        reject(base_with("x1 = 1.0, y1 = 0.5", "x1 = 1.0, y1 = 0.0"), "body[0].geometry.rectangle.y1", "0"),
        reject(
            plain_body("{ quadrilateral = { corners = [[0.0, 0.0], [0.2, 1.2], [1.5, 1.0], [2.0, 0.0]] } }"),
            "body[0].geometry.quadrilateral.corners[0]",
            "[0.0, 0.0]",
        ),
        reject(
            plain_body("{ quadrilateral = { corners = [[0.0, 0.0], [2.0, 0.0], [0.5, 0.5], [0.0, 2.0]] } }"),
            "body[0].geometry.quadrilateral.corners[2]",
            "[0.5, 0.5]",
        ),
        // NURBS patches
        reject(nurbs_body("[0.0, 0.0, 1.0, 1.0]", SQUARE, ", weights = [1.0, 1.0, 0.0, 1.0]"), "body[0].geometry.nurbs.weights[2]", "0"),
        reject(nurbs_body("[0.0, 0.0, 1.0, 1.0]", SQUARE, ", weights = [1.0, 1.0, 1.0]"), "body[0].geometry.nurbs.weights", "3 weights"),
        reject(nurbs_body("[0.0, 0.5, 1.0, 1.0]", SQUARE, ""), "body[0].geometry.nurbs.knots_xi[0]", "0").says(&["open"]),
        reject(
            nurbs_body(
                "[0.0, 0.0, 0.7, 0.3, 1.0, 1.0]",
                "[[0.0, 0.0], [0.3, 0.0], [0.7, 0.0], [1.0, 0.0], [0.0, 1.0], [0.3, 1.0], [0.7, 1.0], [1.0, 1.0]]",
                "",
            ),
            "body[0].geometry.nurbs.knots_xi[3]",
            "0.3",
        )
        .says(&["non-decreasing"]),
        reject(nurbs_body("[0.0, 0.0, nan, 1.0, 1.0]", SQUARE, ""), "body[0].geometry.nurbs.knots_xi[2]", "NaN"),
        reject(nurbs_square("degree = [0, 1]"), "body[0].geometry.nurbs.degree[0]", "0"),
        reject(nurbs_square("degree = [1, 12]"), "body[0].geometry.nurbs.degree[1]", "12"),
        reject(
            nurbs_body("[0.0, 0.0, 1.0, 1.0]", "[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]", ""),
            "body[0].geometry.nurbs.control_points",
            "3 points",
        ),
        reject(
            nurbs_body("[0.0, 0.0, 1.0, 1.0]", "[[0.0, 0.0], [1.0, 0.0], [0.0, inf], [1.0, 1.0]]", ""),
            "body[0].geometry.nurbs.control_points[2][1]",
            "inf",
        ),
        // bodies and the names that refer to them
        reject("title = \"empty\"\n", "body", "[]"),
        reject(base_with("name = \"upper\"", "name = \"lower\""), "body[1].name", "\"lower\"").says(&["body[0]"]),
        reject(base_with("name = \"upper\"", "name = \"  \""), "body[1].name", "\"  \""),
        reject(
            base_with("body = \"lower\"\nside = \"eta_min\"", "body = \"floor\"\nside = \"eta_min\""),
            "support[0].body",
            "\"floor\"",
        )
        .says(&["lower, upper"]),
        reject(base_with("pressure = { body = \"upper\"", "pressure = { body = \"top\""), "load[0].pressure.body", "\"top\""),
        reject(base_with("body_force = { body = \"upper\"", "body_force = { body = \"x\""), "load[1].body_force.body", "\"x\""),
        reject(base_with("traction = { body = \"upper\"", "traction = { body = \"y\""), "load[2].traction.body", "\"y\""),
        reject(base_with("pressure = 1.0e8", "pressure = nan"), "load[0].pressure.pressure", "NaN"),
        reject(base_with("force = [0.0, -1.0]", "force = [0.0, -inf]"), "load[1].body_force.force[1]", "-inf"),
        reject(base_with("traction = [0.0, 0.0]", "traction = [inf, 0.0]"), "load[2].traction.traction[0]", "inf"),
        // contact pairs
        reject(base_with("slave = \"upper\"", "slave = \"top\""), "contact[0].slave", "\"top\""),
        reject(master("{ body = \"floor\", side = \"eta_max\" }"), "contact[0].master.body", "\"floor\""),
        reject(master("{ body = \"upper\", side = \"eta_max\" }"), "contact[0].master.body", "\"upper\"").says(&["self-contact"]),
        reject(master("{ body = \"lower\" }"), "contact[0].master.side", "(absent)"),
        reject(master("{}"), "contact[0].master", "{}"),
        reject(
            master("{ body = \"lower\", side = \"eta_max\", rigid_segment = { from = [0.0, 0.0], to = [1.0, 0.0] } }"),
            "contact[0].master",
            "rigid_segment and body",
        ),
        reject(
            master("{ rigid_segment = { from = [0.0, nan], to = [1.0, 0.5] } }"),
            "contact[0].master.rigid_segment.from[1]",
            "NaN",
        ),
        reject(
            master("{ rigid_segment = { from = [0.5, 0.5], to = [0.5, 0.5] } }"),
            "contact[0].master.rigid_segment.to",
            "[0.5, 0.5]",
        ),
        // a floor from right to left is a ceiling: the slave lies inside it
        reject(
            master("{ rigid_segment = { from = [2.0, 0.5], to = [-1.0, 0.5] } }"),
            "contact[0].master",
            "the rigid curve from [2.0, 0.5] to [-1.0, 0.5]",
        )
        .says(&["points away from the master", "swap `from` and `to`"]),
        // the same contact twice: each would carry half of the pressure
        reject(
            base_with(
                "[solver]",
                "[[contact]]\nslave = \"upper\"\nslave_side = \"eta_min\"\nmaster = { body = \"lower\", side = \"eta_max\" }\n\n[solver]",
            ),
            "contact[1]",
            "slave \"upper\" against the master of contact[0]",
        )
        .says(&["the pressure is shared between them"]),
        // the same interface again with the roles swapped
        reject(
            base_with(
                "[solver]",
                "[[contact]]\nslave = \"lower\"\nslave_side = \"eta_max\"\nmaster = { body = \"upper\", side = \"eta_min\" }\n\n[solver]",
            ),
            "contact[1]",
            "slave \"lower\" against the slave of contact[0]",
        )
        .says(&["sides = \"unbiased\""]),
        // two floors on one line that overlap: the same obstacle twice
        reject(
            master("{ rigid_segment = { from = [-1.0, 0.5], to = [2.0, 0.5] } }").replacen(
                "[solver]",
                "[[contact]]\nslave = \"upper\"\nslave_side = \"eta_min\"\nmaster = { rigid_segment = { from = [0.5, 0.5], to = [3.0, 0.5] } }\n\n[solver]",
                1,
            ),
            "contact[1]",
            "slave \"upper\" against the master of contact[0]",
        ),
        // a parallel floor just below the first: the first hides it
        reject(
            master("{ rigid_segment = { from = [-1.0, 0.5], to = [2.0, 0.5] } }").replacen(
                "[solver]",
                "[[contact]]\nslave = \"upper\"\nslave_side = \"eta_min\"\nmaster = { rigid_segment = { from = [-1.0, 0.4999], to = [2.0, 0.4999] } }\n\n[solver]",
                1,
            ),
            "contact[1]",
            "slave \"upper\" against the master of contact[0]",
        )
        .says(&["one hides the other"]),
        // the lower block's bottom faces away from the upper block
        reject(
            master("{ body = \"lower\", side = \"eta_min\" }"),
            "contact[0]",
            "body \"upper\" against side eta_min of body \"lower\"",
        )
        .says(&["face each other"]),
        reject(
            format!(
                "{}\n[[contact]]\nslave = \"b\"\nslave_side = \"eta_max\"\n\
                 master = {{ rigid_segment = {{ from = [0.0, 2.0], to = [1.0, 2.0] }} }}\n",
                one_body(TRIANGLE, "refine = { degree = 2, elements = [2, 2] }")
            ),
            "contact[0].slave_side",
            "eta_max",
        )
        .says(&["collapsed"]),
        reject(nitsche("theta = 0.5"), "contact[0].nitsche.theta", "0.5"),
        reject(nitsche("theta = nan"), "contact[0].nitsche.theta", "nan"),
        reject(nitsche("penalty_factor = 0"), "contact[0].nitsche.penalty_factor", "0"),
        reject(nitsche("penalty_factor = -2.5"), "contact[0].nitsche.penalty_factor", "-2.5"),
        reject(nitsche("penalty_factor = 1e300"), "contact[0].nitsche.penalty_factor", "1e300").says(&["round-off"]),
        reject(nitsche("penalty_factor = 1e-13"), "contact[0].nitsche.penalty_factor", "1e-13"),
        reject(nitsche("gauss_points = 0"), "contact[0].nitsche.gauss_points", "0"),
        // solver and outputs
        reject(base_with("rtol = 1e-10", "rtol = 0.0"), "solver.rtol", "0"),
        reject(base_with("rtol = 1e-10", "rtol = 1e-10\nutol = 1.0"), "solver.utol", "1"),
        reject(base_with("rtol = 1e-10", "rtol = 1e-10\ncurvature_tol = nan"), "solver.curvature_tol", "NaN"),
        reject(base_with("rtol = 1e-10", "rtol = 1e-10\nmax_iter = 0"), "solver.max_iter", "0"),
        reject(format!("{BASE}\n[output]\nvtu = true\nvtu_subdivisions = 0\n"), "output.vtu_subdivisions", "0"),
        reject(
            plain_body("{ rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 1.0 } }") + "\n[output]\npressure_profile = true\n",
            "output.pressure_profile",
            "true",
        ),
        reject(
            plain_body("{ rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 1.0 } }") + "\n[output]\nfigures = true\n",
            "output.figures",
            "true",
        ),
        // rigid modes nothing holds
        reject(block_on_floor(""), "body[0]", "\"block\"")
            .says(&["slide along (1, 0)", "contact normals", "[[support]]"]),
        reject(block_on_floor("").replace("pressure = 1.0e4", "pressure = 0.0"), "body[0]", "\"block\""),
        reject(
            base_with("[[support]]\nbody = \"upper\"\nside = \"xi_min\"\ncomponent = \"x\"\n", ""),
            "body[1]",
            "\"upper\"",
        )
        .says(&["slide along (1, 0)"]),
        reject(include_str!("../fixtures/rotating_annuli.toml"), "body[1]", "\"inner\"").says(&["rotate about (0, 0)"]),
        reject(
            plain_body("{ rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 1.0 } }")
                .replace("[[support]]\nbody = \"b\"\nside = \"eta_min\"\ncomponent = \"x\"\n", ""),
            "body[0]",
            "\"b\"",
        )
        .says(&["slide along (1, 0)", "no contact"]),
        // under-integration
        reject(lower_body("quadrature = 2"), "body[0].quadrature", "2")
            .says(&["3 Gauss points", "allow_underintegration = true"]),
        reject(nitsche("gauss_points = 2"), "contact[0].nitsche.gauss_points", "2").says(&["allow_underintegration"]),
        // scales beyond double precision
        reject(held.replace("young = 1.0e6", "young = 1e-300"), "body[0].material.young", "1e-300")
            .says(&["underflows"])
            .lacks(&["diverged"]),
        reject(held.replace("pressure = 1.0e4", "pressure = 1e200"), "load[0].pressure.pressure", "1e200").says(&["overflows"]),
        reject(
            held.replace("young = 1.0e6", "young = 1e-100").replace("pressure = 1.0e4", "pressure = 1e100"),
            "load[0].pressure.pressure",
            "1e100",
        )
        .says(&["displacements would be of order"]),
        reject(plain_body("{ full_disk = { center = [0.0, 0.0], radius = 1e200 } }"), "body[0].geometry.full_disk.radius", "1e200")
            .says(&["overflows"]),
    ]
}

#[test]
fn every_rejected_scene_names_its_key_value_and_reason() {
    let rows = rejected();
    let failures: Vec<String> = rows
        .iter()
        .enumerate()
        .filter_map(|(i, r)| {
            r.failure()
                .map(|why| format!("row {i}, `{}`: {why}", r.path))
        })
        .collect();
    assert!(
        failures.is_empty(),
        "{} of {} rows failed:\n{}",
        failures.len(),
        rows.len(),
        failures.join("\n")
    );
}
