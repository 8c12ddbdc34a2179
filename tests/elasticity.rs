//! Linear elasticity, Eq. (3): patch tests on a distorted rational patch,
//! element stiffness properties, load vectors, material validation, and a
//! reduced Lamé convergence study.

mod common;

use iga_contact::assembly::{self, Load};
use iga_contact::dofs::{Body, DofMap};
use iga_contact::geometry::{half_disk, quadrilateral, rectangle};
use iga_contact::linsolve::{Factoriser, Method, Pattern};
use iga_contact::material::{Material, Plane};
use iga_contact::nurbs::{NurbsPatch, Side};
use iga_contact::space::Space;
use nalgebra::SymmetricEigen;

use companion::lame;

/// A quadrilateral with no two sides parallel, k-refined to degree `p`,
/// whose interior control points and weights are then moved by a fixed
/// pseudo-random amount: a genuinely rational, distorted patch with
/// straight sides.
fn distorted_patch(p: usize) -> NurbsPatch {
    distorted(p, true)
}

/// As [`distorted_patch`]; `rational = false` leaves all weights at 1 (a
/// distorted polynomial B-spline map).
fn distorted(p: usize, rational: bool) -> NurbsPatch {
    let base = quadrilateral([[0.0, 0.0], [2.0, 0.3], [2.4, 1.9], [-0.2, 1.5]]).unwrap();
    let mut patch = base.k_refined(p, [3, 4]).unwrap();
    let [n0, n1] = patch.n();
    for j in 1..n1 - 1 {
        for i in 1..n0 - 1 {
            let k = patch.index(i, j);
            let s = (k as f64 * 1.7 + 0.3).sin();
            let c = (k as f64 * 2.3 + 1.1).cos();
            patch.points[k][0] += 0.06 * s;
            patch.points[k][1] += 0.06 * c;
            if rational {
                patch.weights[k] *= 1.0 + 0.35 * (k as f64 * 0.9).sin();
            }
        }
    }
    patch
}

fn solve(bodies: &[Body], map: &DofMap, loads: &[Load]) -> Vec<f64> {
    let (trip, lift) = assembly::stiffness(bodies, map).unwrap();
    let f = assembly::load_vector(bodies, map, loads).unwrap();
    let rhs: Vec<f64> = f.iter().zip(&lift).map(|(a, b)| a - b).collect();
    let pattern = Pattern::new(map.n_free(), &[&trip]).unwrap();
    let k = pattern.matrix(&[&trip.vals]).unwrap();
    let factor = Factoriser::default().factor(&k, Method::Cholesky).unwrap();
    map.expand(&factor.solve(&rhs).unwrap())
}

fn patch_test(p: usize, plane: Plane, quad_order: Option<usize>) -> (f64, f64) {
    patch_test_on(distorted_patch(p), plane, quad_order)
}

/// Solves the affine-field patch test on `patch` and returns the largest
/// relative displacement and stress errors over a grid of interior points.
fn patch_test_on(patch: NurbsPatch, plane: Plane, quad_order: Option<usize>) -> (f64, f64) {
    let a = [[1.0e-3, -2.5e-3], [0.7e-3, 1.8e-3]];
    let b = [0.4e-3, -0.9e-3];
    let field = move |x: [f64; 2]| {
        [
            a[0][0] * x[0] + a[0][1] * x[1] + b[0],
            a[1][0] * x[0] + a[1][1] * x[1] + b[1],
        ]
    };
    let material = Material::new(2.0e5, 0.3, plane).unwrap();
    let space = Space::new(patch, quad_order).unwrap();
    let bodies = vec![Body {
        name: "patch".into(),
        space,
        material,
        formulation: iga_contact::material::Formulation::Displacement,
    }];
    let mut builder = DofMap::builder(&bodies);
    for side in Side::ALL {
        builder.fix_side_field(0, side, field).unwrap();
    }
    let map = builder.build();
    assert!(map.n_free() > 0, "the patch must have interior unknowns");
    let u = solve(&bodies, &map, &[]);

    let eps = [a[0][0], a[1][1], a[0][1] + a[1][0]];
    let sigma = material.stress(eps);
    let (u_scale, s_scale) = (
        2.5e-3 * 3.0,
        sigma.iter().fold(0.0_f64, |m, s| m.max(s.abs())),
    );
    let space = &bodies[0].space;
    let (mut u_err, mut s_err) = (0.0_f64, 0.0_f64);
    let m = 23;
    for j in 0..m {
        for i in 0..m {
            let xi = 0.013 + 0.974 * i as f64 / (m - 1) as f64;
            let eta = 0.021 + 0.958 * j as f64 / (m - 1) as f64;
            let e = &space.elements[space.locate(xi, eta)];
            let shape = space.shape(e, xi, eta).expect("det J > 0 everywhere");
            let uh = assembly::displacement_at(&map, &u, 0, &e.cps, &shape);
            let ue = field(shape.x);
            u_err = u_err.max((uh[0] - ue[0]).hypot(uh[1] - ue[1]) / u_scale);
            let (_, s) = assembly::strain_stress(&bodies, &map, &u, 0, xi, eta).unwrap();
            for c in 0..3 {
                s_err = s_err.max((s[c] - sigma[c]).abs() / s_scale);
            }
        }
    }
    (u_err, s_err)
}

#[test]
fn distorted_patch_is_rational_and_valid() {
    for p in [2, 3] {
        let patch = distorted_patch(p);
        let w = &patch.weights;
        let (lo, hi) = w
            .iter()
            .fold((f64::MAX, f64::MIN), |(l, h), &v| (l.min(v), h.max(v)));
        assert!(hi / lo > 1.5, "weights should vary: {lo}..{hi}");
        // Space::quadrature fails if det J ≤ 0 at any Gauss point.
        let space = Space::new(patch, Some(8)).unwrap();
        for e in &space.elements {
            space.quadrature(e).expect("det J > 0");
        }
    }
}

#[test]
fn patch_test_reproduces_affine_fields() {
    for p in [2, 3] {
        for plane in [Plane::Strain, Plane::Stress] {
            let (u_err, s_err) = patch_test(p, plane, Some(p + 12));
            assert!(
                u_err < 1e-10 && s_err < 1e-10,
                "p = {p}, {plane:?}: displacement error {u_err:e}, stress error {s_err:e}"
            );
        }
    }
}

#[test]
fn element_stiffness_has_three_rigid_modes() {
    for (p, plane) in [(2, Plane::Strain), (3, Plane::Stress)] {
        let material = Material::new(1.0e3, 0.25, plane).unwrap();
        let space = Space::new(distorted_patch(p), None).unwrap();
        let body = Body {
            name: "free".into(),
            space,
            material,
            formulation: iga_contact::material::Formulation::Displacement,
        };
        for e in [0, 5] {
            let ke = assembly::element_stiffness(&body, e).unwrap();
            let n = ke.nrows();
            assert_eq!(n, 2 * (p + 1) * (p + 1));
            let scale = ke.amax();
            let asym = (&ke - ke.transpose()).amax();
            assert!(asym <= 1e-13 * scale, "asymmetry {asym:e} of {scale:e}");
            let mut ev: Vec<f64> = SymmetricEigen::new(ke)
                .eigenvalues
                .iter()
                .copied()
                .collect();
            ev.sort_by(f64::total_cmp);
            let max = ev[n - 1];
            assert!(ev[0] > -1e-10 * max, "negative eigenvalue {:e}", ev[0]);
            for (k, &l) in ev.iter().enumerate().take(3) {
                assert!(l.abs() < 1e-10 * max, "rigid mode {k}: {l:e} of {max:e}");
            }
            assert!(
                ev[3] > 1e-6 * max,
                "a fourth zero-energy mode: {:e} of {max:e}",
                ev[3]
            );
        }
    }
}

#[test]
fn body_force_integrates_to_force_times_area() {
    let r = 0.2;
    let force = [0.3, -1.3e6];
    for (n, quad, tol) in [(8, None, 1e-8), (4, Some(12), 1e-12), (16, Some(8), 1e-12)] {
        let patch = half_disk([0.0, 0.2], r)
            .unwrap()
            .k_refined(2, [n, n])
            .unwrap();
        let bodies = vec![Body {
            name: "disk".into(),
            space: Space::new(patch, quad).unwrap(),
            material: Material::new(2e7, 0.1, Plane::Strain).unwrap(),
            formulation: iga_contact::material::Formulation::Displacement,
        }];
        let map = DofMap::builder(&bodies).build();
        let f =
            assembly::load_vector(&bodies, &map, &[Load::BodyForce { body: 0, force }]).unwrap();
        let area = std::f64::consts::PI * r * r / 2.0;
        for c in 0..2 {
            let total: f64 = f.iter().skip(c).step_by(2).sum();
            let expect = force[c] * area;
            let rel = (total - expect).abs() / expect.abs();
            eprintln!("n = {n}, quad = {quad:?}, component {c}: rel {rel:e}");
            assert!(
                rel < tol,
                "n = {n}, quad = {quad:?}, component {c}: {total} vs {expect} (rel {rel:e})"
            );
        }
    }
}

#[test]
fn pressure_on_a_straight_side_integrates_to_pressure_times_length() {
    // A trapezoid whose top side is inclined: length and normal are not trivial.
    let corners = [[0.0, 0.0], [3.0, 0.0], [2.5, 2.0], [0.5, 1.0]];
    let patch = quadrilateral(corners)
        .unwrap()
        .k_refined(3, [5, 3])
        .unwrap();
    let bodies = vec![Body {
        name: "trapezoid".into(),
        space: Space::new(patch, None).unwrap(),
        material: Material::new(1.0, 0.2, Plane::Stress).unwrap(),
        formulation: iga_contact::material::Formulation::Displacement,
    }];
    let map = DofMap::builder(&bodies).build();
    let p = 7.5;
    let f = assembly::load_vector(
        &bodies,
        &map,
        &[Load::Pressure {
            body: 0,
            side: Side::EtaMax,
            pressure: p,
        }],
    )
    .unwrap();
    let (a, b) = (corners[3], corners[2]);
    let t = [b[0] - a[0], b[1] - a[1]];
    let len = t[0].hypot(t[1]);
    // outward normal of the top side (the body lies below it)
    let n = [-t[1] / len, t[0] / len];
    for c in 0..2 {
        let total: f64 = f.iter().skip(c).step_by(2).sum();
        let expect = -p * len * n[c];
        assert!(
            (total - expect).abs() <= 1e-12 * p * len,
            "component {c}: {total} vs {expect}"
        );
    }

    // the bottom of an axis-aligned rectangle: total force = p × width, upward
    let patch = rectangle(0.0, 0.0, 1.5, 0.5)
        .unwrap()
        .k_refined(2, [4, 2])
        .unwrap();
    let bodies = vec![Body {
        name: "block".into(),
        space: Space::new(patch, None).unwrap(),
        material: Material::new(1.0, 0.2, Plane::Stress).unwrap(),
        formulation: iga_contact::material::Formulation::Displacement,
    }];
    let map = DofMap::builder(&bodies).build();
    let f = assembly::load_vector(
        &bodies,
        &map,
        &[Load::Pressure {
            body: 0,
            side: Side::EtaMin,
            pressure: 2.0,
        }],
    )
    .unwrap();
    let fx: f64 = f.iter().step_by(2).sum();
    let fy: f64 = f.iter().skip(1).step_by(2).sum();
    assert!(fx.abs() < 1e-14, "{fx}");
    assert!((fy - 3.0).abs() < 1e-13, "{fy}");
}

#[test]
fn material_validation_names_the_field() {
    let bad: [(f64, f64, &str); 8] = [
        (0.0, 0.3, "young"),
        (-1.0, 0.3, "young"),
        (f64::NAN, 0.3, "young"),
        (f64::INFINITY, 0.3, "young"),
        (1.0, 0.5, "poisson"),
        (1.0, 0.7, "poisson"),
        (1.0, -1.0, "poisson"),
        (1.0, f64::NAN, "poisson"),
    ];
    for (e, nu, field) in bad {
        for plane in [Plane::Strain, Plane::Stress] {
            let err = Material::new(e, nu, plane).expect_err("must be rejected");
            let msg = err.to_string();
            assert!(
                msg.contains(&format!("material.{field}")),
                "E = {e}, ν = {nu}: `{msg}` does not name {field}"
            );
            assert_eq!(err.kind(), iga_contact::ErrorKind::InvalidInput);
        }
    }
    // a custom prefix is carried through
    let m = Material {
        young: 1.0,
        poisson: 0.5,
        plane: Plane::Strain,
    };
    let msg = m.validate("bodies[1].material").unwrap_err().to_string();
    assert!(msg.contains("bodies[1].material.poisson"), "{msg}");
    // the admissible extremes just inside the bounds pass
    assert!(Material::new(1e-9, -0.999, Plane::Stress).is_ok());
    assert!(Material::new(1e12, 0.499, Plane::Strain).is_ok());
}

#[test]
fn lame_rates_reduced() {
    let problem = lame::Lame::default();
    for p in [2, 3] {
        let rows: Vec<lame::Row> = [2, 4, 8, 16]
            .iter()
            .map(|&n| problem.solve(p, n).unwrap())
            .collect();
        lame::check_rates(&rows, p).unwrap();
    }
}

#[test]
fn lame_exact_solution_satisfies_the_equations() {
    let problem = lame::Lame::default();
    let d = problem.material().unwrap().d_matrix();
    let stress = |x: [f64; 2]| {
        let e = problem.strain(x);
        let mut s = [0.0; 3];
        for i in 0..3 {
            for j in 0..3 {
                s[i] += d[i][j] * e[j];
            }
        }
        s
    };
    for r in [problem.r_in, 1.3, problem.r_out] {
        for t in [0.0, 0.4, 1.1, std::f64::consts::FRAC_PI_2] {
            let (c, s) = (f64::cos(t), f64::sin(t));
            let x = [r * c, r * s];
            let sig = stress(x);
            let srr = sig[0] * c * c + sig[1] * s * s + 2.0 * sig[2] * s * c;
            let stt = sig[0] * s * s + sig[1] * c * c - 2.0 * sig[2] * s * c;
            let (srr_e, stt_e) = problem.polar_stress(r);
            let tol = 1e-12 * problem.pressure;
            assert!((srr - srr_e).abs() < tol && (stt - stt_e).abs() < tol);
            // the strain is the symmetric gradient of the displacement
            let h = 1e-6;
            let u = |dx: f64, dy: f64| problem.displacement([x[0] + dx, x[1] + dy]);
            let dudx = [
                (u(h, 0.0)[0] - u(-h, 0.0)[0]) / (2.0 * h),
                (u(h, 0.0)[1] - u(-h, 0.0)[1]) / (2.0 * h),
            ];
            let dudy = [
                (u(0.0, h)[0] - u(0.0, -h)[0]) / (2.0 * h),
                (u(0.0, h)[1] - u(0.0, -h)[1]) / (2.0 * h),
            ];
            let e = problem.strain(x);
            let fd = [dudx[0], dudy[1], dudy[0] + dudx[1]];
            for k in 0..3 {
                assert!(
                    (e[k] - fd[k]).abs() < 1e-8 * e[0].abs().max(1e-12),
                    "{e:?} vs {fd:?}"
                );
            }
        }
        // equilibrium in the radial direction: dσ_rr/dr + (σ_rr − σ_θθ)/r = 0
        let h = 1e-5;
        let (s0, t0) = problem.polar_stress(r);
        let ds = (problem.polar_stress(r + h).0 - problem.polar_stress(r - h).0) / (2.0 * h);
        assert!((ds + (s0 - t0) / r).abs() < 1e-6 * problem.pressure);
    }
    assert!(
        (problem.polar_stress(problem.r_in).0 + problem.pressure).abs() < 1e-12 * problem.pressure
    );
    assert!(problem.polar_stress(problem.r_out).0.abs() < 1e-12 * problem.pressure);
}

/// The patch test is exact only if the quadrature is. On a distorted
/// *polynomial* map, ∇R_A det J is a polynomial of degree ≤ 2p − 1 per
/// direction, so the default p + 1 Gauss points integrate the residual of
/// an affine field exactly; on a *rational* map it is a rational function,
/// and the default rule leaves a small error that disappears as the rule
/// is refined.
#[test]
fn patch_test_and_quadrature() {
    for p in [2, 3] {
        for plane in [Plane::Strain, Plane::Stress] {
            let (u, s) = patch_test_on(distorted(p, false), plane, None);
            assert!(
                u < 1e-10 && s < 1e-10,
                "polynomial map, p = {p}: {u:e}, {s:e}"
            );

            let errs: Vec<f64> = [p + 1, p + 3, p + 5, p + 9]
                .iter()
                .map(|&q| patch_test(p, plane, Some(q)).1)
                .collect();
            assert!(errs[0] > 1e-7, "rational map, default rule: {errs:?}");
            assert!(
                errs.windows(2).all(|w| w[1] < 0.1 * w[0]),
                "the error must fall with the quadrature order: {errs:?}"
            );
        }
    }
}

/// The quarter annulus runs ξ counter-clockwise along the arcs and η
/// outward, so det J < 0 everywhere: a valid, orientation-reversing map.
/// Integrals use |det J|; a map whose det J changes sign (a fold) is refused.
#[test]
fn orientation_reversing_maps_are_accepted_and_folds_rejected() {
    let (a, b) = (1.0, 2.0);
    let patch = iga_contact::geometry::quarter_annulus(a, b)
        .unwrap()
        .k_refined(2, [3, 3])
        .unwrap();
    let space = Space::new(patch, Some(8)).unwrap();
    assert_eq!(space.orientation(), -1.0);
    let area = common::area(&space);
    let exact = std::f64::consts::PI * (b * b - a * a) / 4.0;
    assert!((area - exact).abs() < 1e-12 * exact, "{area} vs {exact}");

    let square = rectangle(0.0, 0.0, 1.0, 1.0).unwrap();
    assert_eq!(Space::new(square.clone(), None).unwrap().orientation(), 1.0);
    let mut folded = square.k_refined(2, [2, 2]).unwrap();
    let k = folded.index(1, 1);
    folded.points[k] = [3.0, 3.0];
    let space = Space::new(folded, None).unwrap();
    let err = space
        .elements
        .iter()
        .find_map(|e| space.quadrature(e).err())
        .expect("a folded map must be refused");
    assert_eq!(err.kind(), iga_contact::ErrorKind::Geometry, "{err}");
}
