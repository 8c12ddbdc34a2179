//! Lamé's thick-walled cylinder under internal pressure, plane strain: the
//! convergence study of the elasticity discretisation (Eq. 3) against the
//! exact solution that `examples/lame.rs` runs, and the incompressibility
//! chapter and the tests reuse.
//!
//! One quarter of the cross-section, r_in ≤ r ≤ r_out in the first
//! quadrant, is modelled with the exact quarter-annulus NURBS patch. The
//! inner arc carries the pressure; symmetry gives u_y = 0 on the x axis and
//! u_x = 0 on the y axis.

use iga_contact::assembly::{self, Load};
use iga_contact::dofs::{Body, DofMap};
use iga_contact::geometry::quarter_annulus;
use iga_contact::linsolve::{Factoriser, Method, Pattern};
use iga_contact::material::{Formulation, Material, Plane};
use iga_contact::nurbs::Side;
use iga_contact::quadrature;
use iga_contact::report::table::{Column, Format, Table, Unit};
use iga_contact::space::Space;
use iga_contact::Result;

/// The cylinder: radii, material (plane strain) and internal pressure.
#[derive(Clone, Copy, Debug)]
pub struct Lame {
    pub r_in: f64,
    pub r_out: f64,
    pub young: f64,
    pub poisson: f64,
    pub pressure: f64,
    /// The body's formulation (the paper's displacement one by default).
    pub formulation: Formulation,
}

impl Default for Lame {
    fn default() -> Self {
        Self {
            r_in: 1.0,
            r_out: 2.0,
            young: 1.0e5,
            poisson: 0.3,
            pressure: 100.0,
            formulation: Formulation::Displacement,
        }
    }
}

/// One refinement level of one degree.
#[derive(Clone, Copy, Debug)]
pub struct Row {
    pub degree: usize,
    /// Elements per direction.
    pub n: usize,
    /// Total number of elements, n².
    pub elements: usize,
    /// Unknowns of the solved system (free DOFs).
    pub dofs: usize,
    pub l2_error: f64,
    pub energy_error: f64,
}

impl Lame {
    pub fn material(&self) -> Result<Material> {
        Material::new(self.young, self.poisson, Plane::Strain)
    }

    /// The constants of u_r(r) = A r + B / r.
    ///
    /// σ_rr = 2(λ+μ) A − 2μ B / r²; σ_rr(r_in) = −p and σ_rr(r_out) = 0 give
    /// B = p a² b² / (2μ (b² − a²)) and A = p a² / (2(λ+μ)(b² − a²)).
    pub fn constants(&self) -> (f64, f64) {
        let (e, nu, p) = (self.young, self.poisson, self.pressure);
        let (a2, b2) = (self.r_in * self.r_in, self.r_out * self.r_out);
        let mu = e / (2.0 * (1.0 + nu));
        let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let a = p * a2 / (2.0 * (lambda + mu) * (b2 - a2));
        let b = p * a2 * b2 / (2.0 * mu * (b2 - a2));
        (a, b)
    }

    /// Exact displacement u = (A + B/r²) x.
    pub fn displacement(&self, x: [f64; 2]) -> [f64; 2] {
        let (a, b) = self.constants();
        let r2 = x[0] * x[0] + x[1] * x[1];
        let f = a + b / r2;
        [f * x[0], f * x[1]]
    }

    /// Exact strain in Voigt order (ε_xx, ε_yy, γ_xy).
    pub fn strain(&self, x: [f64; 2]) -> [f64; 3] {
        let (a, b) = self.constants();
        let r2 = x[0] * x[0] + x[1] * x[1];
        let r4 = r2 * r2;
        let d = x[1] * x[1] - x[0] * x[0];
        [a + b * d / r4, a - b * d / r4, -4.0 * b * x[0] * x[1] / r4]
    }

    /// Exact radial and hoop stresses at radius r.
    pub fn polar_stress(&self, r: f64) -> (f64, f64) {
        let (a2, b2) = (self.r_in * self.r_in, self.r_out * self.r_out);
        let c = self.pressure * a2 / (b2 - a2);
        (c * (1.0 - b2 / (r * r)), c * (1.0 + b2 / (r * r)))
    }

    /// Solves on `n × n` elements of degree `p` and measures the errors
    /// with p + 3 Gauss points per direction.
    pub fn solve(&self, p: usize, n: usize) -> Result<Row> {
        let patch = quarter_annulus(self.r_in, self.r_out)?.k_refined(p, [n, n])?;
        let bodies = vec![Body {
            name: "cylinder".into(),
            space: Space::new(patch, None)?,
            material: self.material()?,
            formulation: self.formulation,
        }];
        let mut builder = DofMap::builder(&bodies);
        builder
            .fix_side(0, Side::XiMin, 1, 0.0)?
            .fix_side(0, Side::XiMax, 0, 0.0)?;
        let map = builder.build();
        let (trip, lift) = assembly::stiffness(&bodies, &map)?;
        let load = Load::Pressure {
            body: 0,
            side: Side::EtaMin,
            pressure: self.pressure,
        };
        let f = assembly::load_vector(&bodies, &map, &[load])?;
        let rhs: Vec<f64> = f.iter().zip(&lift).map(|(f, l)| f - l).collect();
        let k = Pattern::new(map.n_free(), &[&trip])?.matrix(&[&trip.vals])?;
        let u_free = Factoriser::default()
            .factor(&k, Method::Cholesky)?
            .solve(&rhs)?;
        let u = map.expand(&u_free);

        let d = bodies[0].material.d_matrix();
        let energy = |e: [f64; 3]| -> f64 {
            (0..3)
                .map(|i| (0..3).map(|j| e[i] * d[i][j] * e[j]).sum::<f64>())
                .sum()
        };
        // the mixed formulation's energy: 2μ |dev e|² + κ (θ̄_h − tr ε)², the
        // displacement one's eᵀ D e written the same way
        let (mu, kappa) = (
            bodies[0].material.shear_modulus(),
            bodies[0].material.bulk_modulus(),
        );
        let split_energy = |e: [f64; 3], vol: f64| -> f64 {
            let tr = (e[0] + e[1]) / 3.0;
            let dev = [e[0] - tr, e[1] - tr, -tr];
            2.0 * mu * (dev[0] * dev[0] + dev[1] * dev[1] + dev[2] * dev[2] + 0.5 * e[2] * e[2])
                + kappa * vol * vol
        };
        let space = &bodies[0].space;
        let (mut l2_num, mut l2_den, mut en_num, mut en_den) = (0.0, 0.0, 0.0, 0.0);
        let pressure = match self.formulation {
            Formulation::Mixed => Some(std::sync::Arc::new(
                iga_contact::pressure::SplinePressure::new(&bodies[0])?,
            )),
            _ => None,
        };
        for (ei, el) in space.elements.iter().enumerate() {
            let stress_of =
                assembly::ElementStress::with_pressure(&bodies[0], ei, pressure.as_ref())?;
            let gx = quadrature::on_interval(p + 3, el.range[0][0], el.range[0][1]);
            let gy = quadrature::on_interval(p + 3, el.range[1][0], el.range[1][1]);
            for &(eta, wy) in &gy {
                for &(xi, wx) in &gx {
                    let shape = space.shape(el, xi, eta)?;
                    let w = wx * wy * shape.det_j;
                    let uh = assembly::displacement_at(&map, &u, 0, &el.cps, &shape);
                    let eh = assembly::strain_at(&map, &u, 0, &el.cps, &shape);
                    let ue = self.displacement(shape.x);
                    let ee = self.strain(shape.x);
                    let du = [uh[0] - ue[0], uh[1] - ue[1]];
                    let de = [eh[0] - ee[0], eh[1] - ee[1], eh[2] - ee[2]];
                    l2_num += w * (du[0] * du[0] + du[1] * du[1]);
                    l2_den += w * (ue[0] * ue[0] + ue[1] * ue[1]);
                    match self.formulation {
                        Formulation::Displacement => {
                            en_num += w * energy(de);
                            en_den += w * energy(ee);
                        }
                        Formulation::Mixed | Formulation::LocalMixed => {
                            let th = stress_of.dilatation(&map, &u, 0, &shape, xi, eta);
                            en_num += w * split_energy(de, th - ee[0] - ee[1]);
                            en_den += w * split_energy(ee, ee[0] + ee[1]);
                        }
                    }
                }
            }
        }
        Ok(Row {
            degree: p,
            n,
            elements: space.elements.len(),
            dofs: map.n_free(),
            l2_error: (l2_num / l2_den).sqrt(),
            energy_error: (en_num / en_den).sqrt(),
        })
    }
}

/// Observed rates with respect to the element size h ∝ 1/n between each
/// level and the previous one: `(l2, energy)`; `None` on the first level.
pub fn rates(rows: &[Row]) -> Vec<Option<(f64, f64)>> {
    rows.iter()
        .enumerate()
        .map(|(k, r)| {
            let prev = rows[..k].last()?;
            let dh = (r.n as f64 / prev.n as f64).ln();
            Some((
                (prev.l2_error / r.l2_error).ln() / dh,
                (prev.energy_error / r.energy_error).ln() / dh,
            ))
        })
        .collect()
}

/// Checks the rate between the last two levels of one degree: at least
/// p + 0.8 in L² (optimal p + 1) and p − 0.2 in energy (optimal p).
pub fn check_rates(rows: &[Row], p: usize) -> std::result::Result<(), String> {
    let rs = rates(rows);
    if rs.len() < 2 {
        return Err(format!("p = {p}: need at least two levels"));
    }
    if let (Some(row), Some(Some((l2, en)))) = (rows.last(), rs.last()) {
        let (l2, en) = (*l2, *en);
        if l2 < p as f64 + 0.8 || en < p as f64 - 0.2 {
            return Err(format!(
                "p = {p}, {n}×{n} elements: L² rate {l2:.2} (need ≥ {:.1}), energy rate {en:.2} (need ≥ {:.1})",
                p as f64 + 0.8,
                p as f64 - 0.2,
                n = row.n,
            ));
        }
    }
    Ok(())
}

/// One row per (degree, level), with the observed rates in h between
/// levels (Markdown only; `convergence.csv` keeps exactly the columns
/// `degree,elements,dofs,l2_error,energy_error`, `elements` the total count).
pub fn table(rows: &[Row]) -> Result<Table> {
    let mut t = Table::new(vec![
        Column::plain("degree", "p"),
        Column::new("mesh", "mesh", Unit::None, Format::Mesh).markdown_only(),
        Column::plain("elements", "elements").csv_only(),
        Column::plain("dofs", "DOFs"),
        Column::new("l2_error", "rel. L² error", Unit::None, Format::Sci(3)),
        Column::new("l2_rate", "L² rate", Unit::None, Format::Fixed(2)).markdown_only(),
        Column::new(
            "energy_error",
            "rel. energy error",
            Unit::None,
            Format::Sci(3),
        ),
        Column::new("energy_rate", "energy rate", Unit::None, Format::Fixed(2)).markdown_only(),
    ]);
    let mut start = 0;
    while start < rows.len() {
        let p = rows[start].degree;
        let end = start + rows[start..].iter().take_while(|r| r.degree == p).count();
        let group = &rows[start..end];
        for (r, rate) in group.iter().zip(rates(group)) {
            t.push(vec![
                r.degree.into(),
                r.n.into(),
                r.elements.into(),
                r.dofs.into(),
                r.l2_error.into(),
                rate.map(|(a, _)| a).into(),
                r.energy_error.into(),
                rate.map(|(_, b)| b).into(),
            ])?;
        }
        start = end;
    }
    Ok(t)
}

/// Both errors against the number of unknowns, log–log: one colour per
/// degree, the data solid (L² with circles, energy with squares), the
/// reference slopes of the optimal rates dotted. The legend names the
/// degrees and the two markers once, not every curve.
pub fn plot(rows: &[Row], path: &std::path::Path) -> Result<()> {
    use iga_contact::report::plot::{line_chart, Axes, Series, BLACK_INDEX};
    const CIRCLE: usize = 0;
    const SQUARE: usize = 1;
    let mut degrees: Vec<usize> = rows.iter().map(|r| r.degree).collect();
    degrees.dedup();
    let mut series = Vec::new();
    for (k, &p) in degrees.iter().enumerate() {
        let pts = |f: fn(&Row) -> f64| -> Vec<(f64, f64)> {
            rows.iter()
                .filter(|r| r.degree == p)
                .map(|r| (r.dofs as f64, f(r)))
                .collect()
        };
        series.push(
            Series::line("", pts(|r| r.l2_error))
                .with_shape(CIRCLE)
                .colored(k),
        );
        series.push(
            Series::line("", pts(|r| r.energy_error))
                .with_shape(SQUARE)
                .colored(k),
        );
    }
    // Reference slopes in N (unknowns ~ h⁻²): the optimal L² rate p + 1 in
    // h is a slope −(p + 1)/2 in N, the energy rate p a slope −p/2. Each is
    // drawn through the finest point of its curve, over the last two decades.
    for (k, &p) in degrees.iter().enumerate() {
        let last = rows.iter().rfind(|r| r.degree == p).expect("rows of p");
        let n1 = last.dofs as f64;
        for (err, rate) in [(last.l2_error, p + 1), (last.energy_error, p)] {
            let slope = -(rate as f64) / 2.0;
            let n0 = n1 / 100.0;
            let line = vec![(n0, err * (n0 / n1).powf(slope)), (n1, err)];
            series.push(Series::line("", line).dotted().colored(k));
        }
    }
    // The legend: one entry per degree, per marker and for the guides
    // (point-less series draw nothing but their legend entry).
    for (k, &p) in degrees.iter().enumerate() {
        series.push(Series::line(format!("p = {p}"), vec![]).colored(k));
    }
    series.push(
        Series::line("L²", vec![])
            .with_shape(CIRCLE)
            .colored(BLACK_INDEX),
    );
    series.push(
        Series::line("energy", vec![])
            .with_shape(SQUARE)
            .colored(BLACK_INDEX),
    );
    series.push(
        Series::line("optimal slope in N (L²: −(p+1)/2, energy: −p/2)", vec![])
            .dotted()
            .colored(BLACK_INDEX),
    );
    let axes = Axes {
        title: "Lamé cylinder: relative errors".into(),
        x_label: "unknowns (free DOFs)".into(),
        y_label: "relative error".into(),
        log_x: true,
        log_y: true,
    };
    line_chart(path, &axes, &series)
}
