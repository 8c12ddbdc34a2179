//! A prototype, not the shipped formulation: B̄ with the dilatation
//! projected onto the *continuous* splines of degree p − 1 and continuity
//! C^{p−2} on the displacement knots (the derivative space, about one
//! function per element), with the pressure mass lumped by rows so that
//! the condensed stiffness stays sparse:
//!
//!   K = ∫ Bᵀ D_dev B + κ Σ_i ĝ_i ĝ_iᵀ / m̂_i,  ĝ_i = ∫ N̂_i div,  m̂_i = ∫ N̂_i.
//!
//! Bulk only, on Lamé's cylinder: it shows which pressure space removes the
//! locking. Its stencil is 2p − 1 control points per direction, and σ_n at
//! a point reaches the neighbouring elements, which is why it is not yet
//! the `mixed` formulation (see the chapter).

use iga_contact::assembly::{self, btdb, Triplets};
use iga_contact::dofs::{Body, DofMap};
use iga_contact::error::Result;
use iga_contact::linsolve::{Factoriser, Method, Pattern};
use iga_contact::material::Formulation;
use iga_contact::nurbs::{KnotVector, Side};
use iga_contact::space::Space;
use nalgebra::DMatrix;

/// Relative L² and energy errors of the prototype on Lamé's cylinder with
/// degree `p`, `n` × `n` elements and Poisson's ratio `nu`.
pub fn lame_errors(p: usize, n: usize, nu: f64) -> Result<(f64, f64)> {
    let lame = crate::lame::Lame {
        poisson: nu,
        ..crate::lame::Lame::default()
    };
    let patch = iga_contact::geometry::quarter_annulus(1.0, 2.0)?.k_refined(p, [n, n])?;
    let material = lame.material()?;
    let bodies = vec![Body {
        name: "c".into(),
        space: Space::new(patch, None)?,
        material,
        formulation: Formulation::Displacement,
    }];
    let mut b = DofMap::builder(&bodies);
    b.fix_side(0, Side::XiMin, 1, 0.0)?
        .fix_side(0, Side::XiMax, 0, 0.0)?;
    let map = b.build();
    let space = &bodies[0].space;
    let pk: Vec<KnotVector> = (0..2)
        .map(|d| {
            let k = space.patch.knots[d].knots();
            // the derivative space: one knot fewer at each end, degree p − 1
            KnotVector::new(k[1..k.len() - 1].to_vec(), p - 1)
        })
        .collect::<Result<_>>()?;
    let npx = pk[0].n_basis();
    let np = npx * pk[1].n_basis();
    let pbasis = |xi: f64, eta: f64| -> Vec<(usize, f64)> {
        let (sx, sy) = (pk[0].find_span(xi), pk[1].find_span(eta));
        let (bx, by) = (pk[0].basis_ders(sx, xi, 0), pk[1].basis_ders(sy, eta, 0));
        let mut out = Vec::new();
        for (jy, vy) in by[0].iter().enumerate() {
            for (jx, vx) in bx[0].iter().enumerate() {
                out.push((sx + 1 - p + jx + (sy + 1 - p + jy) * npx, vx * vy));
            }
        }
        out
    };
    let dd = material.d_deviatoric();
    let (mu, kappa) = (material.shear_modulus(), material.bulk_modulus());
    let mut g: Vec<std::collections::BTreeMap<usize, f64>> = vec![Default::default(); np];
    let mut m = vec![0.0; np];
    let mut trip = Triplets::default();
    let mut lift = vec![0.0; map.n_free()];
    for el in &space.elements {
        let nc = el.cps.len();
        let dofs = map.element_dofs(0, &el.cps);
        let mut ke = DMatrix::zeros(2 * nc, 2 * nc);
        for qp in space.quadrature(el)? {
            for a in 0..nc {
                for bb in 0..nc {
                    let k = btdb(qp.shape.grad[a], qp.shape.grad[bb], &dd);
                    for i in 0..2 {
                        for j in 0..2 {
                            ke[(2 * a + i, 2 * bb + j)] += qp.weight * k[i][j];
                        }
                    }
                }
            }
            for (i, v) in pbasis(qp.param[0], qp.param[1]) {
                m[i] += qp.weight * v;
                for (a, gr) in qp.shape.grad.iter().enumerate() {
                    for c in 0..2 {
                        *g[i].entry(dofs[2 * a + c]).or_default() += qp.weight * v * gr[c];
                    }
                }
            }
        }
        trip.add(&map, &dofs, &ke, &mut lift);
    }
    for i in 0..np {
        let dofs: Vec<usize> = g[i].keys().copied().collect();
        let v: Vec<f64> = g[i].values().copied().collect();
        let k = DMatrix::from_fn(v.len(), v.len(), |r, c| kappa * v[r] * v[c] / m[i]);
        trip.add(&map, &dofs, &k, &mut lift);
    }
    let load = iga_contact::assembly::Load::Pressure {
        body: 0,
        side: Side::EtaMin,
        pressure: lame.pressure,
    };
    let f = assembly::load_vector(&bodies, &map, &[load])?;
    let rhs: Vec<f64> = f.iter().zip(&lift).map(|(f, l)| f - l).collect();
    let k = Pattern::new(map.n_free(), &[&trip])?.matrix(&[&trip.vals])?;
    let u = Factoriser::default()
        .factor(&k, Method::Cholesky)?
        .solve(&rhs)?;
    let u = map.expand(&u);
    let theta_i: Vec<f64> = (0..np)
        .map(|i| g[i].iter().map(|(d, v)| v * u[*d]).sum::<f64>() / m[i])
        .collect();
    let split = |e: [f64; 3], vol: f64| {
        let tr = (e[0] + e[1]) / 3.0;
        let dev = [e[0] - tr, e[1] - tr, -tr];
        2.0 * mu * (dev[0] * dev[0] + dev[1] * dev[1] + dev[2] * dev[2] + 0.5 * e[2] * e[2])
            + kappa * vol * vol
    };
    let (mut l2n, mut l2d, mut enn, mut end) = (0.0, 0.0, 0.0, 0.0);
    for el in &space.elements {
        let gx = iga_contact::quadrature::on_interval(p + 3, el.range[0][0], el.range[0][1]);
        let gy = iga_contact::quadrature::on_interval(p + 3, el.range[1][0], el.range[1][1]);
        for &(eta, wy) in &gy {
            for &(xi, wx) in &gx {
                let shape = space.shape(el, xi, eta)?;
                let w = wx * wy * shape.det_j;
                let uh = assembly::displacement_at(&map, &u, 0, &el.cps, &shape);
                let eh = assembly::strain_at(&map, &u, 0, &el.cps, &shape);
                let th: f64 = pbasis(xi, eta).iter().map(|(i, v)| v * theta_i[*i]).sum();
                let ue = lame.displacement(shape.x);
                let ee = lame.strain(shape.x);
                let de = [eh[0] - ee[0], eh[1] - ee[1], eh[2] - ee[2]];
                l2n += w * ((uh[0] - ue[0]).powi(2) + (uh[1] - ue[1]).powi(2));
                l2d += w * (ue[0] * ue[0] + ue[1] * ue[1]);
                enn += w * split(de, th - ee[0] - ee[1]);
                end += w * split(ee, ee[0] + ee[1]);
            }
        }
    }
    Ok(((l2n / l2d).sqrt(), (enn / end).sqrt()))
}
