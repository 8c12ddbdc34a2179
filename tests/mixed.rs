//! The mixed formulations for nearly incompressible plane-strain bodies —
//! `mixed` (B̄ with the dilatation projected onto the continuous splines of
//! degree p − 1, lumped) and `local_mixed` (projected per element onto
//! Q_{p−1}): their algebra, a uniform-stress patch test, agreement with the
//! displacement formulation where nothing locks, what they do near
//! incompressibility, the warning and the scene key.

mod common;
use companion::hertz as setup;
use companion::lame;

use iga_contact::assembly::{self, ElementStress};
use iga_contact::contact::{PenaltyKind, Theta};
use iga_contact::dofs::{Body, DofMap};
use iga_contact::geometry::rectangle;
use iga_contact::linsolve::{Factoriser, Method, Pattern};
use iga_contact::material::{Formulation, Material, Plane};
use iga_contact::nurbs::Side;
use iga_contact::post::{relative, PressureProfile};
use iga_contact::scene::Scene;
use iga_contact::solver::{solve, SolverKind, SolverOptions};
use iga_contact::space::Space;
use iga_contact::Error;

fn lame_rows(f: Formulation, nu: f64, p: usize, ns: &[usize]) -> Vec<lame::Row> {
    let problem = lame::Lame {
        poisson: nu,
        formulation: f,
        ..lame::Lame::default()
    };
    ns.iter().map(|&n| problem.solve(p, n).unwrap()).collect()
}

/// With the exact dilatation θ̄ = tr ε, the split σ = 2μ dev ε + κ θ̄ I
/// (3D deviator, ε_zz = 0) is Hooke's law of plane strain, σ_zz included.
#[test]
fn the_split_stress_with_the_exact_dilatation_is_hookes_law() {
    for nu in [0.0, 0.3, 0.49999, -0.5] {
        let m = Material::new(3.0e5, nu, Plane::Strain).unwrap();
        let eps = [1.3e-3, -0.4e-3, 0.7e-3];
        let want = m.stress(eps);
        let (got, szz) = m.mixed_stress(eps, eps[0] + eps[1]);
        let scale = want.iter().map(|s| s.abs()).fold(0.0, f64::max);
        for i in 0..3 {
            assert!((got[i] - want[i]).abs() <= 1e-9 * scale, "ν = {nu}, {i}");
        }
        assert!(
            (szz - m.stress_zz(want)).abs() <= 1e-9 * scale,
            "ν = {nu}: σ_zz"
        );
        // D = D_dev + κ m mᵀ
        let (d, dd, k) = (m.d_matrix(), m.d_deviatoric(), m.bulk_modulus());
        for i in 0..3 {
            for j in 0..3 {
                let vol = if i < 2 && j < 2 { k } else { 0.0 };
                assert!(
                    (d[i][j] - dd[i][j] - vol).abs() <= 1e-9 * d[0][0],
                    "ν = {nu}"
                );
            }
        }
    }
}

/// A uniform strain prescribed through its affine displacement on the
/// whole boundary of a patch is reproduced exactly by both mixed
/// formulations at ν = 0.49999: the displacement, and the stress at every
/// sampled point (the projection reproduces the constant dilatation).
#[test]
fn the_mixed_element_passes_the_uniform_stress_patch_test() {
    let grad = [[2.0e-4, 0.5e-4], [-1.0e-4, -1.5e-4]];
    let field = |x: [f64; 2]| {
        [
            grad[0][0] * x[0] + grad[0][1] * x[1],
            grad[1][0] * x[0] + grad[1][1] * x[1],
        ]
    };
    let eps = [grad[0][0], grad[1][1], grad[0][1] + grad[1][0]];
    for (p, f) in [2, 3]
        .into_iter()
        .flat_map(|p| [(p, Formulation::Mixed), (p, Formulation::LocalMixed)])
    {
        // an affine map, so that Gauss quadrature integrates the constant
        // stress against every basis gradient exactly
        let patch = rectangle(0.5, 1.0, 2.0, 1.8)
            .unwrap()
            .k_refined(p, [3, 4])
            .unwrap();
        let material = Material::new(1.0e5, 0.49999, Plane::Strain).unwrap();
        let bodies = vec![Body {
            name: "patch".into(),
            space: Space::new(patch, None).unwrap(),
            material,
            formulation: f,
        }];
        let mut b = DofMap::builder(&bodies);
        for side in [Side::XiMin, Side::XiMax, Side::EtaMin, Side::EtaMax] {
            b.fix_side_field(0, side, field).unwrap();
        }
        let map = b.build();
        let (trip, lift) = assembly::stiffness(&bodies, &map).unwrap();
        let rhs: Vec<f64> = lift.iter().map(|l| -l).collect();
        let k = Pattern::new(map.n_free(), &[&trip])
            .unwrap()
            .matrix(&[&trip.vals])
            .unwrap();
        let u = Factoriser::default()
            .factor(&k, Method::Cholesky)
            .unwrap()
            .solve(&rhs)
            .unwrap();
        let full = map.expand(&u);
        let want = material.stress(eps);
        let want_zz = material.stress_zz(want);
        let space = &bodies[0].space;
        for (ei, el) in space.elements.iter().enumerate() {
            let stress = ElementStress::new(&bodies[0], ei).unwrap();
            // inside, and on the element's edges and corners, where the
            // knot span to the right belongs to the next element (output
            // samples such as the VTU subdivisions lie there)
            for (s, t) in [
                (0.2, 0.7),
                (0.5, 0.5),
                (0.9, 0.1),
                (0.0, 0.0),
                (1.0, 0.3),
                (1.0, 1.0),
            ] {
                let xi = el.range[0][0] + s * (el.range[0][1] - el.range[0][0]);
                let eta = el.range[1][0] + t * (el.range[1][1] - el.range[1][0]);
                let shape = space.shape(el, xi, eta).unwrap();
                let ue = assembly::displacement_at(&map, &full, 0, &el.cps, &shape);
                let ux = field(shape.x);
                // the scale of u is 4·10⁻⁴; κ/μ ≈ 5·10⁴ amplifies round-off
                let du = (ue[0] - ux[0]).abs() + (ue[1] - ux[1]).abs();
                assert!(du <= 1e-9 * 4e-4, "p = {p}: u off by {du:e}");
                let (sig, szz) = stress.stress(&map, &full, 0, &shape, xi, eta);
                // κ amplifies round-off in θ̄ by κ/μ ≈ 5·10⁴
                let tol = 1e-6 * want.iter().map(|s| s.abs()).fold(0.0, f64::max);
                for i in 0..3 {
                    assert!(
                        (sig[i] - want[i]).abs() <= tol,
                        "p = {p}: σ[{i}] {sig:?} vs {want:?}"
                    );
                }
                assert!((szz - want_zz).abs() <= tol, "p = {p}: σ_zz");
            }
        }
    }
}

/// Where nothing locks (ν = 0.3) the two formulations converge alike on
/// Lamé's cylinder: optimal rates (within 0.2 of p + 1 in L², of p in
/// energy) for p = 2, 3, and L² errors within 1 % of each other.
#[test]
fn at_nu_0_3_mixed_and_displacement_converge_alike() {
    for p in [2, 3] {
        let ns = [8, 16, 32];
        let d = lame_rows(Formulation::Displacement, 0.3, p, &ns);
        let m = lame_rows(Formulation::Mixed, 0.3, p, &ns);
        let l = lame_rows(Formulation::LocalMixed, 0.3, p, &ns);
        for rows in [&d, &m, &l] {
            let (l2, en) = lame::rates(rows).last().unwrap().unwrap();
            assert!(
                (l2 - (p as f64 + 1.0)).abs() <= 0.2,
                "p = {p}: L² rate {l2}"
            );
            assert!((en - p as f64).abs() <= 0.2, "p = {p}: energy rate {en}");
        }
        for (a, b) in d.iter().zip(&m).chain(d.iter().zip(&l)) {
            assert!(
                relative(b.l2_error, a.l2_error).abs() <= 0.01,
                "p = {p}, {}²: {} vs {}",
                a.n,
                b.l2_error,
                a.l2_error
            );
        }
    }
}

/// At ν = 0.49999 the local projection lowers Lamé's errors below the
/// displacement formulation's on every mesh — but it does not remove locking: on the meshes up to
/// 32² the mixed errors still fall faster than the optimal rate, towards
/// the compressible ones from above (the local pressure of degree p − 1
/// has p² modes per element against about two displacement DOFs per
/// element of a maximally smooth spline space). The test pins both facts.
#[test]
fn near_incompressibility_the_local_projection_helps_but_still_locks() {
    let ns = [8, 16, 32];
    for p in [2, 3] {
        let d = lame_rows(Formulation::Displacement, 0.49999, p, &ns);
        let m = lame_rows(Formulation::LocalMixed, 0.49999, p, &ns);
        let c = lame_rows(Formulation::Displacement, 0.3, p, &ns);
        for ((a, b), r) in d.iter().zip(&m).zip(&c) {
            assert!(b.l2_error < a.l2_error, "p = {p}, {}²", a.n);
            // still above the compressible error: locked
            assert!(b.l2_error > 1.5 * r.l2_error, "p = {p}, {}²", a.n);
        }
        let (l2, _) = lame::rates(&m).last().unwrap().unwrap();
        assert!(
            l2 > p as f64 + 1.5,
            "p = {p}: L² rate {l2} (pre-asymptotic)"
        );
    }
}

fn hertz_run(
    f: Formulation,
    nu: f64,
    p: usize,
    n: usize,
    theta: Theta,
    kind: SolverKind,
) -> (f64, f64, usize) {
    let mut s = common::hertz_scene(p, n, theta);
    s.bodies[0].material.poisson = nu;
    s.bodies[0].formulation = f;
    for ni in s.nitsche_mut() {
        ni.penalty = PenaltyKind::Sharp;
        ni.penalty_factor = 2.0;
    }
    let exact = setup::analytic(&s).unwrap();
    let prob = s.build().unwrap();
    let sol = solve(&prob, &SolverOptions::with_kind(kind)).unwrap();
    let m = PressureProfile::dense(&prob, &sol.full)
        .unwrap()
        .measures(0);
    (
        relative(m.p0, exact.p0),
        relative(m.half_width, exact.half_width),
        sol.history.len(),
    )
}

/// Hertz at ν = 0.3 (32², sharp penalty): the mixed contact stress gives
/// p₀ and a within 2.5 % of Hertz for θ = −1, 0, 1, with BFGS and Newton,
/// like the displacement formulation.
#[test]
fn hertz_at_nu_0_3_is_right_with_the_mixed_contact_stress() {
    for theta in [Theta::Skew, Theta::Incomplete, Theta::Symmetric] {
        for kind in [SolverKind::Bfgs, SolverKind::Newton] {
            let (ep, ea, _) = hertz_run(Formulation::Mixed, 0.3, 2, 32, theta, kind);
            assert!(
                ep.abs() <= 0.025 && ea.abs() <= 0.025,
                "{theta:?} {kind:?}: {ep} {ea}"
            );
        }
    }
}

/// Hertz at ν = 0.499, 32², p = 2 and 3: the mixed formulation is within
/// 2 % of Hertz in p₀ and 6 % in a, with BFGS and Newton.
#[test]
fn hertz_at_nu_0_499_is_right_with_the_mixed_formulation() {
    for p in [2, 3] {
        for kind in [SolverKind::Bfgs, SolverKind::Newton] {
            let (ep, ea, _) = hertz_run(Formulation::Mixed, 0.499, p, 32, Theta::Incomplete, kind);
            assert!(
                ep.abs() <= 0.02 && ea.abs() <= 0.06,
                "p = {p} {kind:?}: {ep} {ea}"
            );
        }
    }
}

/// The most iterations a near-incompressible mixed Hertz run may take: the
/// default solver's target on the Hertz ladder.
const MAX_ITERATIONS: usize = 10;

/// Issue 20's tolerance: an error within 2 % of Hertz beyond the offset
/// `offset` of the displacement formulation at ν = 0.3 on the same mesh.
fn within_offset(error: f64, offset: f64) -> bool {
    error.abs() <= 0.02 + offset.abs()
}

/// Issue 20's Hertz criterion for one case: the mixed formulation at `nu`
/// on `n`², degree `p`, lies within 2 % of Hertz in p₀ and a beyond the
/// offset the displacement formulation shows at ν = 0.3 on the same mesh,
/// degree, θ and solver (the disk is finite), and takes at most
/// [`MAX_ITERATIONS`] iterations. Under the default growth rule the
/// displacement run at ν = 0.3 takes 4–5 iterations and the mixed one up to
/// two more; what is required here is the solver's cap.
fn meets_the_hertz_criterion(nu: f64, p: usize, n: usize, theta: Theta, kind: SolverKind) {
    let (dp, da, di) = hertz_run(Formulation::Displacement, 0.3, p, n, theta, kind);
    let (ep, ea, it) = hertz_run(Formulation::Mixed, nu, p, n, theta, kind);
    let case =
        format!("ν = {nu}, p = {p}, {n}², {theta:?} {kind:?}: p₀ {ep} ({dp}), a {ea} ({da})");
    assert!(within_offset(ep, dp) && within_offset(ea, da), "{case}");
    assert!(
        it <= MAX_ITERATIONS,
        "{case}: {it} iterations ({di} at ν = 0.3)"
    );
}

/// The criterion at ν = 0.49999 on 32², p = 2 and 3, θ = −1, 0, 1, BFGS
/// and Newton.
#[test]
fn hertz_at_nu_0_49999_meets_issue_20_with_the_mixed_formulation() {
    for p in [2, 3] {
        for theta in [Theta::Skew, Theta::Incomplete, Theta::Symmetric] {
            for kind in [SolverKind::Bfgs, SolverKind::Newton] {
                meets_the_hertz_criterion(0.49999, p, 32, theta, kind);
            }
        }
    }
}

/// The same criterion at ν = 0.4999 and on 64² (p = 2, θ = 0 and 1).
#[test]
fn hertz_at_nu_0_4999_and_on_64_meets_issue_20() {
    for (nu, n, theta) in [
        (0.4999, 32, Theta::Incomplete),
        (0.4999, 32, Theta::Symmetric),
        (0.49999, 64, Theta::Incomplete),
        (0.49999, 64, Theta::Symmetric),
    ] {
        for kind in [SolverKind::Bfgs, SolverKind::Newton] {
            meets_the_hertz_criterion(nu, 2, n, theta, kind);
        }
    }
}

/// The sharp penalty of the mixed formulation does not grow with κ: from
/// ν = 0.3 to 0.49999 (κ/μ from 2.2 to 10⁵) its smallest value over the
/// contact side changes by less than a factor 1.5, and it stays within a
/// factor 10 of the empirical Eq. (11). (Weighting the pressure energy by κ
/// alone made it grow like κ.)
#[test]
fn the_mixed_sharp_penalty_does_not_grow_with_kappa() {
    let smallest = |nu: f64, penalty: PenaltyKind| {
        let mut s = common::hertz_scene(2, 32, Theta::Incomplete);
        s.bodies[0].material.poisson = nu;
        s.bodies[0].formulation = Formulation::Mixed;
        for ni in s.nitsche_mut() {
            ni.penalty = penalty;
            ni.penalty_factor = if penalty == PenaltyKind::Sharp {
                2.0
            } else {
                1.0
            };
        }
        let prob = s.build().unwrap();
        prob.points
            .iter()
            .filter(|c| c.regular)
            .map(|c| c.gamma)
            .fold(f64::MAX, f64::min)
    };
    let (g3, g5) = (
        smallest(0.3, PenaltyKind::Sharp),
        smallest(0.49999, PenaltyKind::Sharp),
    );
    assert!(g5 / g3 < 1.5 && g3 / g5 < 1.5, "{g3:e} → {g5:e}");
    let empirical = smallest(0.49999, PenaltyKind::Empirical);
    assert!(
        g5 / empirical < 10.0 && empirical / g5 < 10.0,
        "{g5:e} vs {empirical:e}"
    );
}

const SCENE: &str = r#"
[[body]]
name = "block"
geometry = { rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 0.5 } }
refine = { degree = 2, elements = [4, 2] }
material = { young = 1.0e6, poisson = 0.3, plane = "strain" }
formulation = "mixed"

[[support]]
body = "block"
side = "xi_min"
component = "x"

[[load]]
pressure = { body = "block", side = "eta_max", pressure = 1.0e4 }

[[contact]]
slave = "block"
slave_side = "eta_min"
master = { rigid_segment = { from = [-0.5, 0.0], to = [1.5, 0.0] } }
"#;

fn one_line_error(text: &str) -> Error {
    let err = match Scene::from_toml_str(text) {
        Ok(s) => s.build().err().expect("the scene should be refused"),
        Err(e) => e,
    };
    let msg = format!("error: {err}");
    assert_eq!(msg.lines().count(), 1, "{msg}");
    assert!(msg.contains("body[0].formulation"), "{msg}");
    err
}

/// The key: "mixed" builds and solves; a misspelt value and the mixed
/// formulation in plane stress are refused in one line naming the key.
#[test]
fn the_formulation_key_is_validated() {
    let s = Scene::from_toml_str(SCENE).unwrap();
    assert_eq!(s.bodies[0].formulation, Formulation::Mixed);
    let p = s.build().unwrap();
    assert_eq!(p.bodies[0].formulation, Formulation::Mixed);
    solve(&p, &SolverOptions::default()).unwrap();
    let default = SCENE.replace("formulation = \"mixed\"\n", "");
    let d = Scene::from_toml_str(&default).unwrap();
    assert_eq!(d.bodies[0].formulation, Formulation::Displacement);
    one_line_error(&SCENE.replace("\"mixed\"", "\"mixd\""));
    let err = one_line_error(&SCENE.replace("plane = \"strain\"", "plane = \"stress\""));
    assert!(matches!(err, Error::InvalidInput { .. }), "{err}");
    assert!(err.to_string().contains("plane stress"), "{err}");
}

/// The near-incompressibility warning: a displacement body at ν = 0.499 on
/// 32² is warned and told to use the mixed formulation; following the
/// advice silences the warning and brings p₀ within 2 % of Hertz. The
/// local mixed formulation is still judged (it locks), the mixed one not.
#[test]
fn following_the_locking_warning_makes_hertz_right() {
    use iga_contact::solver::warning::{locking, Warning};
    let body = |f: Formulation| {
        let mut s = common::hertz_scene(2, 32, Theta::Incomplete);
        s.bodies[0].material.poisson = 0.499;
        s.bodies[0].formulation = f;
        s.build().unwrap().bodies.remove(0)
    };
    let w = locking(&body(Formulation::Displacement)).expect("a warning");
    assert!(matches!(w, Warning::NearlyIncompressible { .. }));
    let text = w.to_string();
    assert!(text.contains("set formulation = \"mixed\""), "{text}");
    assert!(locking(&body(Formulation::LocalMixed)).is_some());
    assert!(locking(&body(Formulation::Mixed)).is_none());
    let (before, _, _) = hertz_run(
        Formulation::Displacement,
        0.499,
        2,
        32,
        Theta::Incomplete,
        SolverKind::Newton,
    );
    let (after, _, _) = hertz_run(
        Formulation::Mixed,
        0.499,
        2,
        32,
        Theta::Incomplete,
        SolverKind::Newton,
    );
    assert!(
        before.abs() > 0.02 && after.abs() <= 0.02,
        "{before} → {after}"
    );
}

/// The mixed formulation meets issue 20's Lamé criterion at ν = 0.49999:
/// rates within 0.2 of p + 1 (L²) and p (energy) for p = 2, 3, and errors
/// within 25 % of the compressible ones — the continuous pressure does not
/// lock where the local one does.
#[test]
fn the_mixed_formulation_does_not_lock_on_lame() {
    for p in [2, 3] {
        let m = lame_rows(Formulation::Mixed, 0.49999, p, &[8, 16, 32]);
        let c = lame_rows(Formulation::Displacement, 0.3, p, &[32]);
        for (l2, en) in lame::rates(&m).into_iter().flatten() {
            assert!(
                (l2 - (p as f64 + 1.0)).abs() <= 0.2,
                "p = {p}: L² rate {l2}"
            );
            assert!((en - p as f64).abs() <= 0.2, "p = {p}: energy rate {en}");
        }
        assert!(m[2].l2_error <= 1.25 * c[0].l2_error, "p = {p}");
    }
}
