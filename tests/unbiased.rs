//! The two halves of the unbiased form on curved contact (the disk on the
//! block): each half's jump ⟦u_n⟧ is exact for the displacement it sees,
//! and both halves measure one gap function, so that their penalties do
//! not pull against each other (chapter "The penalty, measured").

use iga_contact::contact::projection::closest_point;
use iga_contact::contact::{Role, Sides};
use iga_contact::nurbs::Side;
use iga_contact::problem::Problem;
use iga_contact::scene::RefineSpec;

fn disk_on_block(n: usize) -> Problem {
    companion::shipped("disk_on_block.toml")
        .unwrap()
        .refined("disk", RefineSpec::iga(2, [n, n]))
        .unwrap()
        .refined("block", RefineSpec::iga(2, [2 * n, n]))
        .unwrap()
        .with_nitsche(|n| n.sides = Sides::Unbiased)
        .build()
        .unwrap()
}

/// A displacement field linear in the coordinates is reproduced exactly by
/// NURBS (Σ R_a x_a = x), so the jump of every contact point, in both
/// halves, must equal the field evaluated at the point and at its partner
/// on the other body, dotted with the point's normal.
#[test]
fn both_halves_measure_the_jump_of_a_linear_field_exactly() {
    let problem = disk_on_block(8);
    // the disk moves by u(x) = (0.3 y, 0.7 x + 0.2 y), the block stays
    let field = |x: [f64; 2]| [0.3 * x[1], 0.7 * x[0] + 0.2 * x[1]];
    let mut u = vec![0.0; problem.map.n_total()];
    for (a, &p) in problem.bodies[0].space.patch.points.iter().enumerate() {
        let v = field(p);
        u[problem.map.global(0, a, 0)] = v[0];
        u[problem.map.global(0, a, 1)] = v[1];
    }
    let mut halves = [0usize; 2];
    for cp in &problem.points {
        let (_, jump) = cp.normal_stress_and_jump(&u);
        // the disk's point: the point itself in the disk's half, its
        // partner (at distance g₀ along the normal) in the block's half
        let (disk_point, sign, k) = match cp.role {
            Role::Slave => (cp.x, 1.0, 0),
            Role::Master => (
                [
                    cp.x[0] + cp.g0 * cp.normal[0],
                    cp.x[1] + cp.g0 * cp.normal[1],
                ],
                -1.0,
                1,
            ),
        };
        halves[k] += 1;
        let v = field(disk_point);
        let want = sign * (v[0] * cp.normal[0] + v[1] * cp.normal[1]);
        assert!(
            (jump - want).abs() <= 1e-9 * (1.0 + want.abs()),
            "{:?} at {:?}: {jump} vs {want}",
            cp.role,
            cp.x
        );
    }
    assert!(halves[0] > 0 && halves[1] > 0, "{halves:?}");
}

/// The block's half pairs each block point with the disk point on its
/// normal line, which is the disk point whose closest point on the block
/// it is: the pairing of the disk's half, inverted. Both halves then see
/// the same initial gap along the same normal.
#[test]
fn the_block_half_inverts_the_pairing_of_the_disk_half() {
    let problem = disk_on_block(8);
    let block_top = problem.bodies[1].space.patch.side_curve(Side::EtaMax);
    let mut checked = 0;
    for cp in problem.points.iter().filter(|cp| cp.role == Role::Master) {
        let partner = [
            cp.x[0] + cp.g0 * cp.normal[0],
            cp.x[1] + cp.g0 * cp.normal[1],
        ];
        let back = closest_point(&block_top, partner).unwrap();
        let miss = (back.point[0] - cp.x[0]).hypot(back.point[1] - cp.x[1]);
        assert!(
            miss < 1e-10,
            "block point {:?}: back at {:?}",
            cp.x,
            back.point
        );
        // the disk's half would measure the same gap from the partner
        assert!((back.distance - cp.g0.abs()).abs() < 1e-10);
        checked += 1;
    }
    assert!(checked > 0);
}
