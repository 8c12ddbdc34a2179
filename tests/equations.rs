//! Direct tests of the paper's equations that no other test checks on its
//! own — (2), (4)–(5) on a curved master, (7), (8), (11) and (19) — and the
//! check that the book's equation index (book/src/equations.md) names only
//! tests, items and sections that exist.

mod common;

use common::{hertz, perturbed_solution, rough, taylor};
use iga_contact::assembly::displacement_at;
use iga_contact::contact::nitsche::{heaviside, local_matrix, negative_part};
use iga_contact::contact::projection::closest_point;
use iga_contact::contact::{contact_points, ContactPair, Integration, Master, Theta};
use iga_contact::dofs::{Body, DofMap};
use iga_contact::geometry;
use iga_contact::linsolve::mul;
use iga_contact::nurbs::{KnotVector, NurbsCurve, Side};
use iga_contact::problem::{Kernel, Problem};
use iga_contact::space::Space;
use std::path::Path;

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// The Hertz disk's radius and the Taylor test's pressure, from the scenes.
const HERTZ_RADIUS: f64 = 0.2;
const TAYLOR_PRESSURE: f64 = 1e8;

/// The Taylor patch test's exact field (plane stress, uniform σ_yy = −q):
/// u = (ν q x / E, −q y / E), affine, so the NURBS space holds it exactly.
fn taylor_exact(p: &Problem) -> Vec<f64> {
    let mut full = vec![0.0; p.map.n_total()];
    for (b, body) in p.bodies.iter().enumerate() {
        let m = &body.material;
        for (a, x) in body.space.patch.points.iter().enumerate() {
            full[p.map.global(b, a, 0)] = m.poisson * TAYLOR_PRESSURE * x[0] / m.young;
            full[p.map.global(b, a, 1)] = -TAYLOR_PRESSURE * x[1] / m.young;
        }
    }
    full
}

// ---------------------------------------------------------------- Eq. (2)

#[test]
fn eq2_the_displacement_field_reproduces_affine_fields_and_the_quadrature_values() {
    let p = hertz(3, 3, Theta::Incomplete);
    let space = &p.bodies[0].space;
    // d_A = a + G P_A  ⇒  u(ξ, η) = a + G x(ξ, η) on the curved, rational disk.
    let (a, g) = ([1e-3, -2e-3], [[4e-3, -1e-3], [2e-3, 5e-4]]);
    let affine = |x: [f64; 2]| {
        [
            a[0] + g[0][0] * x[0] + g[0][1] * x[1],
            a[1] + g[1][0] * x[0] + g[1][1] * x[1],
        ]
    };
    let mut full = vec![0.0; p.map.n_total()];
    for (cp, &x) in space.patch.points.iter().enumerate() {
        let u = affine(x);
        full[p.map.global(0, cp, 0)] = u[0];
        full[p.map.global(0, cp, 1)] = u[1];
    }
    let d = |cp: usize| p.map.cp_displacement(&full, 0, cp);
    let params = rough(200, 3);
    for w in params.chunks(2) {
        let (xi, eta) = (w[0] + 0.5, w[1] + 0.5);
        let u = space.displacement(xi, eta, d).unwrap();
        let exact = affine(space.patch.point(xi, eta));
        assert!(
            (u[0] - exact[0]).abs() < 1e-15 && (u[1] - exact[1]).abs() < 1e-15,
            "({xi}, {eta}): {u:?} against {exact:?}"
        );
    }
    // Open knot vectors interpolate at the corners: u(0, 0) = d_0.
    assert_eq!(space.displacement(0.0, 0.0, d).unwrap(), d(0));

    // A rough field: equal to the quadrature path's value at every Gauss point
    // (tensor-product tables there, the rational basis here).
    let full: Vec<f64> = rough(p.map.n_total(), 11);
    let d = |cp: usize| p.map.cp_displacement(&full, 0, cp);
    let mut checked = 0;
    for e in &space.elements {
        for qp in space.quadrature(e).unwrap() {
            let u = space.displacement(qp.param[0], qp.param[1], d).unwrap();
            let v = displacement_at(&p.map, &full, 0, &e.cps, &qp.shape);
            assert!(
                (u[0] - v[0]).abs() < 1e-14 && (u[1] - v[1]).abs() < 1e-14,
                "{u:?} vs {v:?}"
            );
            checked += 1;
        }
    }
    assert_eq!(checked, 9 * 16);

    for (xi, eta, field) in [(1.5, 0.5, "ξ"), (0.5, -0.1, "η"), (f64::NAN, 0.5, "ξ")] {
        let err = space.displacement(xi, eta, d).unwrap_err().to_string();
        assert!(err.contains(field), "{err}");
    }
}

// ---------------------------------------------------------- Eqs. (4)–(5)

/// A half disk lifted above a rigid master that bulges upwards, with the
/// contact points the contact code builds for it.
fn disk_over_a_curved_master() -> (NurbsCurve, Vec<iga_contact::contact::ContactPoint>) {
    let r = HERTZ_RADIUS;
    let (centre, radius) = ([0.0, -2.0 * r], 2.0 * r);
    let (from, to) = (100f64.to_radians(), 60f64.to_radians());
    let half = 0.5 * (to - from);
    let at = |t: f64, s: f64| [centre[0] + s * t.cos(), centre[1] + s * t.sin()];
    let master = NurbsCurve::new(
        KnotVector::new(vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], 2).unwrap(),
        vec![
            at(from, radius),
            at(0.5 * (from + to), radius / half.cos()),
            at(to, radius),
        ],
        vec![1.0, half.cos(), 1.0],
    )
    .unwrap();
    let patch = geometry::half_disk([0.0, 1.1 * r], r)
        .unwrap()
        .k_refined(2, [4, 4])
        .unwrap();
    let bodies = vec![Body {
        name: "disk".into(),
        space: Space::new(patch, None).unwrap(),
        material: common::scene("hertz.toml").bodies[0].material,
        formulation: iga_contact::material::Formulation::Displacement,
    }];
    let map = DofMap::builder(&bodies).build();
    let mut pair = ContactPair::new(0, Side::EtaMin, Master::Rigid(master.clone()));
    pair.nitsche.integration = Integration::Gauss;
    let points = contact_points(&bodies, &map, &[pair]).unwrap();
    (master, points)
}

#[test]
fn eq4_eq5_normals_and_gaps_on_a_curved_master_follow_the_projection() {
    let (master, points) = disk_over_a_curved_master();
    assert_eq!(points.len(), 4 * 4, "every slave point faces the master");
    for cp in &points {
        let pr = closest_point(&master, cp.x).unwrap();
        // (4): n¹ = −n² where the master's outward normal n² is its tangent
        // turned by +90°; for an open gap it is (x̄² − x¹)/‖x̄² − x¹‖.
        let n2 = [-pr.tangent[1], pr.tangent[0]];
        assert!((cp.normal[0] + n2[0]).abs() < 1e-15 && (cp.normal[1] + n2[1]).abs() < 1e-15);
        let d = [pr.point[0] - cp.x[0], pr.point[1] - cp.x[1]];
        // (5) at u = 0: g₀ = (x̄² − x¹)·n¹ equals the distance, since the
        // projection is orthogonal and the gap is open.
        assert!(cp.g0 > 0.0);
        assert!((cp.g0 - pr.distance).abs() < 1e-12 * HERTZ_RADIUS);
        assert!(
            (d[0] - cp.g0 * cp.normal[0]).abs() < 1e-10 * HERTZ_RADIUS
                && (d[1] - cp.g0 * cp.normal[1]).abs() < 1e-10 * HERTZ_RADIUS,
            "x̄² − x¹ = {d:?} is not g₀ n¹ = {} · {:?}",
            cp.g0,
            cp.normal
        );
        // The master is the circle of radius 2R about (0, −2R): the normal
        // is radial there, and the gap is the distance to the circle.
        let r = HERTZ_RADIUS;
        let dist_centre = cp.x[0].hypot(cp.x[1] + 2.0 * r);
        assert!((cp.g0 - (dist_centre - 2.0 * r)).abs() < 1e-12 * r);
    }
    // Not a flat floor: the normals differ from point to point.
    let tilt = points
        .iter()
        .map(|cp| cp.normal[0].abs())
        .fold(0.0, f64::max);
    assert!(tilt > 0.1, "largest horizontal normal component {tilt}");
}

// ---------------------------------------------------------------- Eq. (7)

/// R₇(u) = L(v) − a(u, v) + ∫ σ_n(u) ⟦v_n⟧ dΓ over the free DOFs: the
/// residual of the weak form (7), with the bulk's own normal stress as the
/// contact traction.
fn residual_eq7(p: &Problem, full: &[f64], with_boundary_work: bool) -> Vec<f64> {
    let u = p.map.restrict(full);
    let ku = mul(&p.k, &u);
    let mut r: Vec<f64> = p.rhs.iter().zip(&ku).map(|(f, k)| f - k).collect();
    if with_boundary_work {
        for cp in &p.points {
            let (sigma_n, _) = cp.normal_stress_and_jump(full);
            for (k, &dof) in cp.dofs.iter().enumerate() {
                if let Some(i) = p.map.free(dof) {
                    r[i] += cp.weight * sigma_n * cp.jn[k];
                }
            }
        }
    }
    r
}

#[test]
fn eq7_the_exact_contact_state_satisfies_the_boundary_work_form() {
    let p = taylor(Integration::Segment, Theta::Incomplete);
    let full = taylor_exact(&p);
    let scale = norm(&p.rhs);
    let with = norm(&residual_eq7(&p, &full, true)) / scale;
    let without = norm(&residual_eq7(&p, &full, false)) / scale;
    assert!(with < 1e-12, "‖R₇(u_exact)‖/‖L‖ = {with:.3e}");
    // The boundary work is what balances the load across the interface.
    assert!(without > 0.1, "without it: {without:.3e}");
}

// ---------------------------------------------------------------- Eq. (8)

/// (8) σ_n = [σ_n + γ g_n]₋ holds exactly when the Signorini conditions (6)
/// hold: g_n ≥ 0, σ_n ≤ 0, σ_n g_n = 0.
#[test]
fn eq8_the_bracket_identity_is_equivalent_to_the_contact_conditions() {
    let values = [-2.0, -1.0, -0.5, -1e-3, 0.0, 1e-3, 0.5, 1.0, 2.0];
    let mut both = [0; 2];
    for gamma in [1e-2, 1.0, 1e3] {
        for &sigma in &values {
            for &gap in &values {
                let identity = (sigma - negative_part(sigma + gamma * gap)).abs() <= 1e-12;
                let signorini = gap >= 0.0 && sigma <= 0.0 && sigma * gap == 0.0;
                assert_eq!(identity, signorini, "σ = {sigma}, g = {gap}, γ = {gamma}");
                both[usize::from(identity)] += 1;
            }
        }
    }
    assert!(both[0] > 0 && both[1] > 0, "{both:?}");
}

#[test]
fn eq8_holds_at_the_exact_patch_state_and_fails_once_the_blocks_overlap() {
    let p = taylor(Integration::Segment, Theta::Incomplete);
    let mut full = taylor_exact(&p);
    for cp in &p.points {
        let (sigma_n, jump) = cp.normal_stress_and_jump(&full);
        assert!(
            (sigma_n + TAYLOR_PRESSURE).abs() < 1e-6 * TAYLOR_PRESSURE,
            "{sigma_n}"
        );
        assert!((cp.g0 - jump).abs() < 1e-15, "closed gap");
        let bracket = negative_part(cp.p(&full));
        assert!((bracket - sigma_n).abs() < 1e-9 * TAYLOR_PRESSURE);
    }
    // Push the upper (slave) block down by δ: the stress is unchanged, the
    // gap is −δ, and the bracket exceeds the traction by γ δ.
    let delta = 1e-6;
    let upper = 1;
    for a in 0..p.bodies[upper].space.n_cp() {
        full[p.map.global(upper, a, 1)] -= delta;
    }
    for cp in &p.points {
        let (sigma_n, _) = cp.normal_stress_and_jump(&full);
        let bracket = negative_part(cp.p(&full));
        let excess = sigma_n - bracket;
        assert!(
            (excess - cp.gamma * delta).abs() < 1e-6 * cp.gamma * delta,
            "σ_n − [P]₋ = {excess:.6e}, γδ = {:.6e}",
            cp.gamma * delta
        );
    }
}

// --------------------------------------------------------------- Eq. (11)

#[test]
fn eq11_every_contact_point_carries_the_empirical_penalty_of_its_element() {
    for (degree, elements) in [(2, 4), (3, 2)] {
        let p = hertz(degree, elements, Theta::Incomplete);
        let space = &p.bodies[0].space;
        let young = p.bodies[0].material.young;
        let deg = degree as f64;
        for cp in &p.points {
            // The slave boundary element that holds the point, and its length.
            let be = space
                .boundary(Side::EtaMin)
                .into_iter()
                .find(|be| cp.t >= be.range[0] && cp.t <= be.range[1])
                .unwrap();
            // Its length, measured independently: the arc of the exact circle
            // between the element's end points.
            let ends = [be.range[0], be.range[1]].map(|t| space.patch.side_point(Side::EtaMin, t));
            let ends = ends.map(|q| space.patch.point(q[0], q[1]));
            let chord = (ends[1][0] - ends[0][0]).hypot(ends[1][1] - ends[0][1]);
            let arc = 2.0 * HERTZ_RADIUS * (chord / (2.0 * HERTZ_RADIUS)).asin();
            let gamma = 0.1 * young * (deg + 1.0) * (deg + 2.0) / arc; // rigid: 1/h₂ = 0
            assert!(
                (cp.gamma - gamma).abs() < 1e-10 * gamma,
                "p = {degree}: γ = {} against {gamma}",
                cp.gamma
            );
        }
    }
}

// --------------------------------------------------------------- Eq. (19)

#[test]
fn eq19_the_heaviside_function_is_the_derivative_of_the_bracket() {
    let h = 1e-7;
    for x in [-3.0, -1e-3, -2e-7, 2e-7, 1e-3, 3.0] {
        let fd = (negative_part(x + h) - negative_part(x - h)) / (2.0 * h);
        assert!(
            (fd - heaviside(x)).abs() < 1e-8,
            "x = {x}: {fd} vs {}",
            heaviside(x)
        );
    }
    // At the kink itself the point counts as active, like [x]₋'s left slope.
    assert_eq!(heaviside(0.0), 1.0);
    assert_eq!(heaviside(-0.0), 1.0);
}

/// Column `j` of the kernel of `kind`, densely.
fn kernel_column(p: &Problem, kind: Kernel, j: usize) -> Vec<f64> {
    let mut e = vec![0.0; p.n()];
    e[j] = 1.0;
    mul(&p.kernel(kind).unwrap(), &e)
}

/// −∂R/∂u_j by central differences.
fn fd_column(p: &Problem, u: &[f64], j: usize, h: f64) -> Vec<f64> {
    let (mut up, mut dn) = (u.to_vec(), u.to_vec());
    up[j] += h;
    dn[j] -= h;
    let (rp, rm) = (p.residual(&up).0, p.residual(&dn).0);
    rp.iter()
        .zip(&rm)
        .map(|(a, b)| -(a - b) / (2.0 * h))
        .collect()
}

/// Moving one DOF carries one contact point across its kink P = 0: on each
/// side the secant matrix (18) with H of (19) is the exact Jacobian, and the
/// two differ by that point's matrix alone.
#[test]
fn eq19_the_secant_matrix_is_the_jacobian_on_each_side_of_a_kink() {
    for theta in Theta::ALL {
        let p = hertz(2, 4, theta);
        let u0 = perturbed_solution(&p, 1e-3, 5);
        let full0 = p.map.expand(&u0);
        // P(u) is affine in u: dP/du_j = sn_k − γ jn_k for the point's DOF k.
        let slope = |q: usize, j: usize| -> f64 {
            let cp = &p.points[q];
            cp.dofs
                .iter()
                .enumerate()
                .filter(|&(_, &g)| p.map.free(g) == Some(j))
                .map(|(k, _)| cp.sn[k] - cp.gamma * cp.jn[k])
                .sum()
        };
        let mut found = None;
        'search: for (q, cp) in p.points.iter().enumerate() {
            for &g in &cp.dofs {
                let Some(j) = p.map.free(g) else { continue };
                let s = slope(q, j);
                if s.abs() < 1e-6 * cp.gamma {
                    continue;
                }
                let t_kink = -cp.p(&full0) / s;
                let delta = 1e-3 * t_kink.abs().max(1e-9);
                let at = |t: f64| {
                    let mut u = u0.clone();
                    u[j] += t;
                    u
                };
                let (um, up) = (at(t_kink - delta), at(t_kink + delta));
                let (fm, fp) = (p.map.expand(&um), p.map.expand(&up));
                // Every other point keeps its side, with room for the FD step.
                let h = 1e-3 * delta;
                let clear = p.points.iter().enumerate().all(|(r, o)| {
                    r == q || {
                        let margin = 4.0 * h * slope(r, j).abs();
                        o.p(&fm).signum() == o.p(&fp).signum() && o.p(&fm).abs() > margin
                    }
                });
                if clear {
                    found = Some((q, j, um, up, h));
                    break 'search;
                }
            }
        }
        let (q, j, um, up, h) = found.expect("a point whose kink one DOF crosses alone");
        let mut columns = Vec::new();
        for u in [&um, &up] {
            let k = kernel_column(&p, Kernel::Secant(u), j);
            let fd = fd_column(&p, u, j, h);
            let err = norm(&k.iter().zip(&fd).map(|(a, b)| a - b).collect::<Vec<_>>());
            assert!(
                err <= 1e-7 * norm(&k),
                "θ = {theta}: |K − FD| = {err:.3e}, |K| = {:.3e}",
                norm(&k)
            );
            columns.push(k);
        }
        // The jump of the Jacobian is the point's matrix times the jump of H.
        let cp = &p.points[q];
        let (hm, hp) = (
            heaviside(cp.p(&p.map.expand(&um))),
            heaviside(cp.p(&p.map.expand(&up))),
        );
        assert_ne!(hm, hp, "the point changes side");
        let m = local_matrix(cp, hp - hm);
        let b = cp
            .dofs
            .iter()
            .position(|&g| p.map.free(g) == Some(j))
            .unwrap();
        let mut expected = vec![0.0; p.n()];
        for (a, &g) in cp.dofs.iter().enumerate() {
            if let Some(i) = p.map.free(g) {
                expected[i] += m[(a, b)];
            }
        }
        // local_matrix(cp, ΔH) also carries the H-independent θ term; remove it.
        let base = local_matrix(cp, 0.0);
        for (a, &g) in cp.dofs.iter().enumerate() {
            if let Some(i) = p.map.free(g) {
                expected[i] -= base[(a, b)];
            }
        }
        let jump: Vec<f64> = columns[1]
            .iter()
            .zip(&columns[0])
            .map(|(a, b)| a - b)
            .collect();
        let err = norm(
            &jump
                .iter()
                .zip(&expected)
                .map(|(a, b)| a - b)
                .collect::<Vec<_>>(),
        );
        assert!(
            norm(&jump) > 1e-3 * norm(&columns[0]),
            "θ = {theta}: no kink"
        );
        assert!(
            err <= 1e-10 * norm(&expected),
            "θ = {theta}: jump off by {err:.3e}"
        );
    }
}

// ------------------------------------------------------ the equation index

/// mdBook's heading ids: lower case, whitespace to '-', only alphanumerics,
/// '-' and '_' kept.
fn heading_id(title: &str) -> String {
    title
        .trim()
        .chars()
        .filter_map(|c| match c {
            c if c.is_whitespace() => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .flat_map(char::to_lowercase)
        .collect()
}

/// The headings of a chapter (outside code blocks): (level, id, line).
fn headings(text: &str) -> Vec<(usize, String, usize)> {
    let mut out = Vec::new();
    let mut fence = false;
    for (n, line) in text.lines().enumerate() {
        if line.trim_start().starts_with("```") {
            fence = !fence;
            continue;
        }
        if fence {
            continue;
        }
        let level = line.chars().take_while(|&c| c == '#').count();
        if (1..=6).contains(&level) && line[level..].starts_with(' ') {
            out.push((level, heading_id(&line[level..]), n));
        }
    }
    out
}

/// Every `(…)` target in `text` that starts with `prefix`.
fn link_targets<'a>(text: &'a str, prefix: &str) -> Vec<&'a str> {
    text.match_indices(&format!("]({prefix}"))
        .map(|(i, _)| {
            let rest = &text[i + 2..];
            &rest[..rest.find(')').unwrap_or(rest.len())]
        })
        .collect()
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The index lists Eqs. (1)–(19) in order; every section, doc-test, test
/// and library item it names exists, and every equation with code names at
/// least one item and one test.
#[test]
fn the_equation_index_names_only_things_that_exist() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let index = read(&root.join("book/src/equations.md"));
    let mut sections: Vec<(usize, &str)> = Vec::new();
    for (pos, _) in index.match_indices("\n## Eq. (") {
        let n: usize = index[pos + 9..]
            .split(')')
            .next()
            .and_then(|s| s.parse().ok())
            .expect("`## Eq. (n)`");
        sections.push((n, &index[pos + 1..]));
    }
    let numbers: Vec<usize> = sections.iter().map(|s| s.0).collect();
    assert_eq!(numbers, (1..=19).collect::<Vec<_>>());
    // every source file of the library, at any depth (modules are folders)
    let mut sources = String::new();
    let mut stack = vec![root.join("src")];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let p = entry.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|e| e == "rs") {
                sources.push_str(&read(&p));
            }
        }
    }
    for (n, text) in sections {
        let body = &text[..text[1..].find("\n## ").map_or(text.len(), |i| i + 1)];
        let line = |key: &str| {
            body.lines()
                .find(|l| l.starts_with(&format!("- **{key}**")))
                .unwrap_or_else(|| panic!("Eq. ({n}): no `- **{key}**` line"))
        };
        // Sections and doc-tests: the chapter and its heading exist; a
        // doc-test section holds a Rust block that `cargo test` runs.
        for key in ["Section", "Doc-test"] {
            for target in link_targets(line(key), "") {
                let (file, id) = target.split_once('#').unwrap_or((target, ""));
                if !file.ends_with(".md") {
                    continue;
                }
                let chapter = read(&root.join("book/src").join(file));
                let hs = headings(&chapter);
                let k = hs
                    .iter()
                    .position(|h| h.1 == id)
                    .unwrap_or_else(|| panic!("Eq. ({n}): no heading #{id} in {file}"));
                if key == "Doc-test" {
                    let end = hs[k + 1..]
                        .iter()
                        .find(|h| h.0 <= hs[k].0)
                        .map_or(usize::MAX, |h| h.2);
                    let has_test = chapter
                        .lines()
                        .skip(hs[k].2)
                        .take(end - hs[k].2)
                        .any(|l| l.trim_start() == "```rust");
                    assert!(has_test, "Eq. ({n}): no ```rust block under {file}#{id}");
                }
            }
        }
        // Library items: an api: link whose item is defined in src/.
        let items = link_targets(line("Code"), "api:");
        for item in &items {
            let name = item.trim_end_matches("()").rsplit("::").next().unwrap();
            let defined = [
                "fn", "struct", "enum", "trait", "const", "type", "mod", "pub",
            ]
            .iter()
            .any(|kw| sources.contains(&format!("{kw} {name}")))
                || sources.contains(&format!("    {name},"))
                || sources.contains(&format!("    {name}("));
            assert!(defined, "Eq. ({n}): `{item}` is not defined in src/");
        }
        // Tests: `path/file.rs::name` with a `fn name(` in that file.
        let tests: Vec<&str> = line("Tests")
            .split('`')
            .skip(1)
            .step_by(2)
            .filter(|s| s.contains(".rs::"))
            .collect();
        for t in &tests {
            let (file, name) = t.split_once("::").unwrap();
            let src = read(&root.join(file));
            assert!(
                src.contains(&format!("fn {name}(")),
                "Eq. ({n}): no test `{name}` in {file}"
            );
        }
        let no_code = line("Code").contains("none");
        if !no_code {
            assert!(!items.is_empty(), "Eq. ({n}): no library item");
            assert!(!tests.is_empty(), "Eq. ({n}): no test");
        }
    }
}
