//! Taylor's patch test with a lower block of two patches: sharing the
//! control points of a matching interface, and tied by Nitsche's method
//! across a non-matching one (3 against 4 elements up the shared side).
//! Both reproduce the exact homogeneous state to 1e-10, as the one-patch
//! block does; the tied body is positive definite with the penalty chosen,
//! a tiny penalty is refused (and would make it indefinite), and the tie
//! converges under refinement on the five-patch disk with a core refined
//! apart from its arcs.

use companion::taylor::{blocks_problem, patch_errors, Exact, LowerBlock, PatchErrors};
use iga_contact::assembly::{stiffness, tie_stiffness};
use iga_contact::dofs::{Body, DofMap, MIN_TIE_FACTOR, TIE_FACTOR};
use iga_contact::geometry::{disk_5, rectangle};
use iga_contact::linsolve::{Factoriser, Method};
use iga_contact::material::{Formulation, Material, Plane};
use iga_contact::nurbs::Side;
use iga_contact::problem::Problem;
use iga_contact::scene::Scene;
use iga_contact::solver::{solve, Solution};
use iga_contact::space::Space;

const TOL: f64 = 1e-10;

fn scene() -> Scene {
    companion::shipped("taylor.toml").unwrap()
}

fn solved(lower: LowerBlock) -> (Problem, Solution, PatchErrors) {
    let scene = scene();
    let p = blocks_problem(&scene, lower).unwrap();
    let s = solve(&p, &scene.solver).unwrap_or_else(|e| panic!("{lower:?}: {e}"));
    let e = patch_errors(&p, &s.full, &Exact::of_problem(&p).unwrap()).unwrap();
    (p, s, e)
}

fn assert_exact(e: &PatchErrors, what: &str) {
    for (name, v) in [
        ("σ_yy", e.syy),
        ("σ_xx", e.sxx),
        ("σ_xy", e.sxy),
        ("force", e.force),
    ] {
        assert!(v < TOL, "{what}: {name} error {v:e}");
    }
    let scale = 0.1;
    assert!(
        e.displacement < TOL * scale,
        "{what}: u error {:e}",
        e.displacement
    );
    assert!(
        (e.uy_top + 0.1).abs() < TOL * scale,
        "{what}: u_y top {}",
        e.uy_top
    );
    assert!(
        (e.ux_right - 0.03).abs() < TOL * scale,
        "{what}: u_x right {}",
        e.ux_right
    );
}

/// The upper block is the same patch in every case: its control-point
/// displacements are compared directly.
fn upper_displacements(p: &Problem, s: &Solution) -> Vec<[f64; 2]> {
    let b = p.bodies.len() - 1;
    (0..p.bodies[b].space.n_cp())
        .map(|a| p.map.cp_displacement(&s.full, b, a))
        .collect()
}

#[test]
fn two_matching_patches_pass_the_patch_test_like_one() {
    let (p1, s1, e1) = solved(LowerBlock::One);
    assert_exact(&e1, "one patch");
    let (p2, s2, e2) = solved(LowerBlock::Matching);
    assert!(p2.map.is_linked() && p2.map.ties().is_empty());
    assert_exact(&e2, "two matching patches");
    for (a, b) in upper_displacements(&p1, &s1)
        .iter()
        .zip(upper_displacements(&p2, &s2))
    {
        assert!((a[0] - b[0]).hypot(a[1] - b[1]) < TOL * 0.1, "{a:?} {b:?}");
    }
}

#[test]
fn two_non_matching_patches_tied_by_nitsche_pass_the_patch_test() {
    let (p, s, e) = solved(LowerBlock::NonMatching);
    assert_eq!(p.map.ties().len(), 1);
    assert!(!p.map.is_linked());
    assert_exact(&e, "two non-matching patches");
    let (p1, s1, _) = solved(LowerBlock::One);
    for (a, b) in upper_displacements(&p1, &s1)
        .iter()
        .zip(upper_displacements(&p, &s))
    {
        assert!((a[0] - b[0]).hypot(a[1] - b[1]) < TOL * 0.1, "{a:?} {b:?}");
    }
}

/// The lower block alone (rollers below, held in x on the left): two
/// patches of 2 × 3 and 2 × 4 elements, tied.
fn lower_block() -> (Vec<Body>, Supports) {
    let material = Material::new(1e9, 0.3, Plane::Stress).unwrap();
    let bodies: Vec<Body> = [([0.0, 0.5], [2, 3]), ([0.5, 1.0], [2, 4])]
        .into_iter()
        .map(|(x, el)| Body {
            name: "lower".into(),
            space: Space::new(
                rectangle(x[0], 0.0, x[1], 0.5)
                    .unwrap()
                    .k_refined(2, el)
                    .unwrap(),
                None,
            )
            .unwrap(),
            material,
            formulation: Formulation::Displacement,
        })
        .collect();
    (bodies, Supports)
}

/// The lower block's supports and tie.
struct Supports;

impl Supports {
    fn map(&self, bodies: &[Body], factor: Option<f64>) -> iga_contact::Result<DofMap> {
        let mut b = DofMap::builder(bodies);
        if let Some(f) = factor {
            b.tie_factor(f)?;
        }
        b.join("lower", &[0, 1])?;
        b.fix_side(0, Side::EtaMin, 1, 0.0)?;
        b.fix_side(1, Side::EtaMin, 1, 0.0)?;
        b.fix_side(0, Side::XiMin, 0, 0.0)?;
        Ok(b.build())
    }
}

/// Does the tied stiffness of the lower block with penalty factor
/// `factor` admit a Cholesky factorisation?
fn cholesky_succeeds(bodies: &[Body], map: &DofMap, factor: f64) -> bool {
    let (mut t, _) = stiffness(bodies, map).unwrap();
    let (tie, _) = tie_stiffness(bodies, map, factor).unwrap();
    t.rows.extend(tie.rows);
    t.cols.extend(tie.cols);
    t.vals.extend(tie.vals);
    let n = map.n_free();
    let entries: Vec<_> = (0..t.len())
        .map(|k| faer::sparse::Triplet::new(t.rows[k], t.cols[k], t.vals[k]))
        .collect();
    let k = faer::sparse::SparseColMat::try_new_from_triplets(n, n, &entries).unwrap();
    Factoriser::default().factor(&k, Method::Cholesky).is_ok()
}

#[test]
fn the_tied_body_is_positive_definite_and_a_tiny_penalty_is_refused() {
    let (bodies, parts) = lower_block();
    let map = parts.map(&bodies, None).unwrap();
    assert_eq!(map.tie_factor(), TIE_FACTOR);
    // the problem's own stiffness (the tie added in its pattern)
    let p = Problem::new(bodies.clone(), map.clone(), &[], vec![]).unwrap();
    assert!(Factoriser::default().factor(&p.k, Method::Cholesky).is_ok());
    assert!(cholesky_succeeds(&bodies, &map, TIE_FACTOR));
    assert!(cholesky_succeeds(&bodies, &map, MIN_TIE_FACTOR));
    // a tiny penalty makes the symmetric tie indefinite...
    assert!(!cholesky_succeeds(&bodies, &map, 0.1));
    // ... and is refused, in one line naming the key
    let e = parts.map(&bodies, Some(0.1)).expect_err("refused");
    let msg = e.to_string();
    assert!(
        msg.contains("tie.penalty_factor") && !msg.contains('\n'),
        "{msg}"
    );
}

/// The largest β at which the lower block's tied stiffness is not
/// positive definite, by bisection: the margin [`MIN_TIE_FACTOR`] and
/// [`TIE_FACTOR`] keep over it.
#[test]
fn the_penalty_keeps_a_margin_over_the_loss_of_definiteness() {
    let (bodies, parts) = lower_block();
    let map = parts.map(&bodies, None).unwrap();
    let (mut lo, mut hi) = (1e-4_f64, 100.0_f64);
    for _ in 0..30 {
        let mid = (lo * hi).sqrt();
        if cholesky_succeeds(&bodies, &map, mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    eprintln!("definite above β = {hi:.4}");
    assert!(hi < 0.5 * MIN_TIE_FACTOR, "{hi}");
    assert!(hi > 0.1 * MIN_TIE_FACTOR, "{hi}");
    assert!(hi < 0.1 * TIE_FACTOR, "{hi}");
}

/// The five-patch disk with its core refined apart from its arcs (n + 1
/// against n elements along the curved interfaces), tied, the boundary
/// held to a quadratic field the space does not hold exactly: the tied
/// stiffness is positive definite on every mesh and the jump across the
/// ties falls under refinement (a weak tie that did not converge would
/// leave it, or let it grow with the penalty's 1/h).
#[test]
fn the_tie_converges_under_refinement_on_the_five_patch_disk() {
    let mp = disk_5([0.0, 0.0], 1.0).unwrap();
    let material = Material::new(1.0, 0.3, Plane::Strain).unwrap();
    let field = |x: [f64; 2]| [0.1 * x[0] * x[0], 0.05 * x[0] * x[1]];
    let mut errors = Vec::new();
    for n in [4, 8, 16] {
        let arcs = mp.refined(2, [n, n]).unwrap();
        let core = mp.refined(2, [n + 1, n]).unwrap();
        let mut patches = arcs.clone();
        patches[0] = core[0].clone();
        let bodies: Vec<Body> = patches
            .into_iter()
            .map(|patch| Body {
                name: "disk".into(),
                space: Space::new(patch, None).unwrap(),
                material,
                formulation: Formulation::Displacement,
            })
            .collect();
        let all: Vec<usize> = (0..bodies.len()).collect();
        let mut b = DofMap::builder(&bodies);
        b.join("disk", &all).unwrap();
        let outer: Vec<(usize, Side)> = mp.boundary("arc").unwrap().to_vec();
        for &(p, side) in &outer {
            b.fix_side_field(p, side, field).unwrap();
        }
        let map = b.build();
        assert_eq!(map.ties().len(), 4, "the core against each arc");
        let p = Problem::new(bodies, map, &[], vec![]).unwrap();
        let f = Factoriser::default()
            .factor(&p.k, Method::Cholesky)
            .expect("tied disk positive definite");
        let u = p.map.expand(&f.solve(&p.rhs).unwrap());
        errors.push(jump_norm(&p, &u));
    }
    eprintln!("tie jump: {errors:?}");
    assert!(
        errors[1] < 0.5 * errors[0] && errors[2] < 0.5 * errors[1],
        "{errors:?}"
    );
}

/// √∫ ⟦u⟧² ds over the ties, in the common unit parameter s, by a
/// midpoint rule of eight points on each segment.
fn jump_norm(p: &Problem, u: &[f64]) -> f64 {
    let mut sum = 0.0;
    for tie in p.map.ties() {
        let [a, b] = tie.patches;
        let (pa, pb) = (&p.bodies[a].space, &p.bodies[b].space);
        for seg in tie.segments(&pa.patch, &pb.patch) {
            for k in 0..8 {
                let s = seg[0] + (seg[1] - seg[0]) * (k as f64 + 0.5) / 8.0;
                let qa = pa
                    .patch
                    .side_point(tie.sides[0], tie.param(0, &pa.patch, s));
                let qb = pb
                    .patch
                    .side_point(tie.sides[1], tie.param(1, &pb.patch, s));
                let ua = pa
                    .displacement(qa[0], qa[1], |c| p.map.cp_displacement(u, a, c))
                    .unwrap();
                let ub = pb
                    .displacement(qb[0], qb[1], |c| p.map.cp_displacement(u, b, c))
                    .unwrap();
                let xa = pa.patch.point(qa[0], qa[1]);
                let xb = pb.patch.point(qb[0], qb[1]);
                assert!(
                    (xa[0] - xb[0]).hypot(xa[1] - xb[1]) < 1e-12,
                    "{xa:?} {xb:?}"
                );
                sum +=
                    ((ua[0] - ub[0]).powi(2) + (ua[1] - ub[1]).powi(2)) * (seg[1] - seg[0]) / 8.0;
            }
        }
    }
    sum.sqrt()
}
