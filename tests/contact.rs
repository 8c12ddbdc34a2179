//! The contact Jacobians against finite differences of the residual, for
//! θ = 0, 1, −1, on a rigid master (Hertz) and a deformable one (Taylor).

mod common;

use common::{hertz, hertz_scene, perturbed_solution, taylor};
use iga_contact::assembly::Load;
use iga_contact::contact::{Integration, Theta};
use iga_contact::problem::{Kernel, Problem};
use iga_contact::solver::{solve, SolverKind, SolverOptions};

fn dense(p: &Problem, kind: Kernel) -> Vec<Vec<f64>> {
    let a = p.kernel(kind).unwrap();
    let n = p.n();
    let mut d = vec![vec![0.0; n]; n];
    let s = a.symbolic();
    for j in 0..n {
        for k in s.col_ptr()[j]..s.col_ptr()[j + 1] {
            d[s.row_idx()[k]][j] += a.val()[k];
        }
    }
    d
}

/// Checks −∂R/∂u_j against column j of the secant kernel (18) at `u`,
/// for every column whose perturbation keeps every P(u) on one side of 0.
fn check_jacobian(p: &Problem, u: &[f64]) -> usize {
    let k = dense(p, Kernel::Secant(u));
    let scale = u.iter().fold(0.0f64, |m, v| m.max(v.abs())).max(1e-12);
    let h = 1e-6 * scale;
    let sign = |v: &[f64]| -> Vec<bool> {
        let full = p.map.expand(v);
        p.points.iter().map(|cp| cp.p(&full) <= 0.0).collect()
    };
    let s0 = sign(u);
    let mut checked = 0;
    for j in 0..p.n() {
        let mut up = u.to_vec();
        let mut dn = u.to_vec();
        up[j] += h;
        dn[j] -= h;
        if sign(&up) != s0 || sign(&dn) != s0 {
            continue; // at the kink the Jacobian is only a generalised one
        }
        let (rp, _) = p.residual(&up);
        let (rm, _) = p.residual(&dn);
        let col: Vec<f64> = (0..p.n()).map(|i| k[i][j]).collect();
        let norm = col.iter().map(|v| v * v).sum::<f64>().sqrt();
        let err = (0..p.n())
            .map(|i| (-(rp[i] - rm[i]) / (2.0 * h) - col[i]).powi(2))
            .sum::<f64>()
            .sqrt();
        assert!(
            err <= 1e-6 * norm,
            "column {j}: |FD − K| = {err:.3e}, |K| = {norm:.3e}"
        );
        checked += 1;
    }
    checked
}

#[test]
fn secant_matrix_is_the_jacobian_on_a_rigid_master() {
    for theta in Theta::ALL {
        let p = hertz(2, 4, theta);
        let u = perturbed_solution(&p, 1e-3, 7);
        let active = p.active_points(&u);
        assert!(
            active > 0 && active < p.points.len(),
            "θ = {theta}: want a mixed active set, got {active}"
        );
        let checked = check_jacobian(&p, &u);
        assert!(
            checked >= p.n() * 9 / 10,
            "θ = {theta}: only {checked} of {} columns away from the kink",
            p.n()
        );
    }
}

#[test]
fn secant_matrix_is_the_jacobian_between_two_bodies() {
    for theta in Theta::ALL {
        let p = taylor(Integration::Gauss, theta);
        let u = perturbed_solution(&p, 1e-2, 7);
        assert_eq!(p.active_points(&u), p.points.len());
        assert_eq!(check_jacobian(&p, &u), p.n(), "θ = {theta}");
    }
}

#[test]
fn tied_kernel_is_symmetric_only_for_theta_one() {
    for theta in Theta::ALL {
        let symmetric = theta == Theta::Symmetric;
        let p = hertz(2, 4, theta);
        let k = dense(&p, Kernel::Tied);
        let scale = k.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        let asym = (0..p.n())
            .flat_map(|i| (0..p.n()).map(move |j| (i, j)))
            .map(|(i, j)| (k[i][j] - k[j][i]).abs())
            .fold(0.0, f64::max);
        assert_eq!(
            asym <= 1e-12 * scale,
            symmetric,
            "θ = {theta}: asymmetry {asym:.3e} of {scale:.3e}"
        );
    }
}

#[test]
fn a_body_pulled_away_from_the_floor_is_reported_as_floating() {
    let mut scene = hertz_scene(2, 4, Theta::Incomplete);
    for l in &mut scene.loads {
        if let Load::BodyForce { force, .. } = l {
            force[1] = -force[1];
        }
    }
    let p = scene.build().unwrap();
    for kind in [SolverKind::Bfgs, SolverKind::Newton] {
        let opts = SolverOptions {
            max_iter: 40,
            ..SolverOptions::with_kind(kind)
        };
        let err = solve(&p, &opts).expect_err("no equilibrium without contact");
        let msg = err.to_string();
        assert!(msg.contains("floats"), "{kind:?}: {msg}");
        assert_eq!(err.kind(), iga_contact::ErrorKind::FloatingBody);
    }
}

#[test]
fn the_disk_has_exactly_one_floating_mode_and_the_blocks_one_each() {
    let h = hertz(2, 2, Theta::Incomplete);
    assert_eq!(
        h.floating_modes().len(),
        1,
        "vertical translation of the disk"
    );
    let t = taylor(Integration::Segment, Theta::Incomplete);
    assert_eq!(
        t.floating_modes().len(),
        1,
        "vertical translation of the upper block"
    );
    h.check_support().unwrap();
    t.check_support().unwrap();
}
