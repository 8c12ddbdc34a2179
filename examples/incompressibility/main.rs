//! Near incompressibility: the program behind the chapter "Near
//! incompressibility". Poisson's ratio from 0.3 to 0.49999 on the Hertz
//! disk for the three formulations (`formulation = "displacement" |
//! "local_mixed" | "mixed"`)
//! and p = 2, 3, 4, with the sharp penalty held at twice its bound so that
//! locking is measured alone; Lamé's cylinder at ν = 0.3 and 0.49999 for
//! both; the mean stress along the contact side. Output:
//! `book/src/generated/incompressibility/`.
//!
//! Run it with `cargo run --release --example incompressibility`.

use companion::{hertz, lame};

use companion::chapter::Chapter;
use companion::Facts;
use iga_contact::assembly::ElementStress;
use iga_contact::contact::PenaltyKind;
use iga_contact::error::Result;
use iga_contact::material::Formulation;
use iga_contact::nurbs::Side;
use iga_contact::post::{relative, PressureProfile};
use iga_contact::problem::Problem;
use iga_contact::report::plot::{line_chart, Axes, Series};
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};
use iga_contact::scene::Scene;
use iga_contact::solver::{solve, Solution, SolverKind, SolverOptions};

// ANCHOR: setup
/// The ν axis: from a compressible solid to within 10⁻⁵ of one half.
const POISSON: [f64; 6] = [0.3, 0.45, 0.49, 0.499, 0.4999, 0.49999];
const DEGREES: [usize; 3] = [2, 3, 4];
/// Elements per direction of the Hertz disk.
const MESH: usize = 32;
/// The sharp penalty at this multiple of its stability bound: locking is
/// then the only thing that changes along the ν axis.
const SAFETY: f64 = 2.0;

/// The Hertz scene with degree `p`, Poisson's ratio `nu` and formulation `f`.
fn scene(p: usize, nu: f64, f: Formulation) -> Result<Scene> {
    let mut s = hertz::scene(hertz::iga(p, MESH))?;
    let disk = s.body_mut("disk")?;
    disk.material.poisson = nu;
    disk.formulation = f;
    for n in s.nitsche_mut() {
        n.penalty = PenaltyKind::Sharp;
        n.penalty_factor = SAFETY;
    }
    Ok(s)
}
// ANCHOR_END: setup

const FORMULATIONS: [(Formulation, &str); 3] = [
    (Formulation::Displacement, "displacement"),
    (Formulation::LocalMixed, "local_mixed"),
    (Formulation::Mixed, "mixed"),
];

struct Run {
    nu: f64,
    p: usize,
    name: &'static str,
    /// (p₀ error, a error, iterations), or None where Newton failed.
    errors: Option<(f64, f64, usize)>,
}

fn run(p: usize, nu: f64, (f, name): (Formulation, &'static str)) -> Result<Run> {
    let s = scene(p, nu, f)?;
    let exact = hertz::analytic(&s)?;
    let problem = s.build()?;
    let errors = match solve(&problem, &SolverOptions::with_kind(SolverKind::Newton)) {
        Ok(sol) => {
            let m = PressureProfile::dense(&problem, &sol.full)?.measures(0);
            Some((
                relative(m.p0, exact.p0),
                relative(m.half_width, exact.half_width),
                sol.history.len(),
            ))
        }
        Err(_) => None,
    };
    Ok(Run {
        nu,
        p,
        name,
        errors,
    })
}

/// −(σ_xx + σ_yy + σ_zz)/3 along the contact side (x, MPa), eight points
/// per boundary element, for x ≤ `x_max`.
fn mean_pressure(problem: &Problem, sol: &Solution, x_max: f64) -> Result<Vec<(f64, f64)>> {
    let body = &problem.bodies[0];
    let space = &body.space;
    let mut out = Vec::new();
    for be in space.boundary(Side::EtaMin) {
        let stress = ElementStress::new(body, be.element)?;
        for k in 0..8 {
            let t = be.range[0] + (k as f64 + 0.5) / 8.0 * (be.range[1] - be.range[0]);
            let (shape, _, _) = space.side_shape(&be, t)?;
            if shape.x[0] > x_max {
                continue;
            }
            let q = space.patch.side_point(Side::EtaMin, t);
            let (s, szz) = stress.stress(&problem.map, &sol.full, 0, &shape, q[0], q[1]);
            out.push((shape.x[0] * 1e3, -(s[0] + s[1] + szz) / 3.0 * 1e-6));
        }
    }
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    Ok(out)
}

/// The chapter "Near incompressibility", section by section.
fn main() -> Result<()> {
    let mut chapter = Chapter::from_args("incompressibility")?;

    // Hertz along the ν axis: Table IN1, Fig. IN1.
    let runs = solve_axis()?;
    chapter.table("hertz_axis", &axis_table(&runs)?)?;
    draw_p0_error(&chapter, &runs)?;

    // Lamé's cylinder: Table IN2.
    let lame = solve_lame()?;
    chapter.table("lame", &lame.table)?;

    // The pressure along the contact: Fig. IN2.
    let mean = solve_mean_stress()?;
    draw_mean_stress(&chapter, &mean.curves)?;

    // The facts of the three sections.
    record_setup_facts(chapter.facts(), mean.half_width)?;
    record_mean_facts(chapter.facts(), &mean.measures)?;
    record_axis_facts(chapter.facts(), &runs)?;
    record_lame_facts(chapter.facts(), &lame.finest_rates)?;
    chapter.finish()
}

// ANCHOR: axis
/// "Hertz along the ν axis": every degree, Poisson's ratio and
/// formulation, solved by Newton.
fn solve_axis() -> Result<Vec<Run>> {
    let mut runs = Vec::new();
    for &p in &DEGREES {
        for &nu in &POISSON {
            for f in FORMULATIONS {
                runs.push(run(p, nu, f)?);
            }
        }
    }
    Ok(runs)
}
// ANCHOR_END: axis

/// Table IN1: iterations and the errors of p₀ and a against Hertz, run by
/// run.
fn axis_table(runs: &[Run]) -> Result<Table> {
    let mut table = Table::new(vec![
        Column::new("poisson", "ν", Unit::None, Format::Plain),
        Column::plain("degree", "p"),
        Column::plain("formulation", "formulation"),
        Column::plain("iterations", "its"),
        Column::new(
            "p0_vs_hertz",
            "p₀ vs Hertz",
            Unit::None,
            Format::SignedPercent(1),
        ),
        Column::new(
            "a_vs_hertz",
            "a vs Hertz",
            Unit::None,
            Format::SignedPercent(1),
        ),
    ]);
    for r in runs {
        let (ep, ea, it): (Cell, Cell, Cell) = match r.errors {
            Some((ep, ea, it)) => (ep.into(), ea.into(), it.into()),
            None => (Cell::Empty, Cell::Empty, "failed".into()),
        };
        table.push(vec![r.nu.into(), r.p.into(), r.name.into(), it, ep, ea])?;
    }
    Ok(table)
}

/// Fig. IN1: the p₀ error against ½ − ν, one curve per degree and
/// formulation.
fn draw_p0_error(chapter: &Chapter, runs: &[Run]) -> Result<()> {
    let mut series = Vec::new();
    for (k, &p) in DEGREES.iter().enumerate() {
        for (j, (_, name)) in FORMULATIONS.iter().enumerate() {
            let pts: Vec<(f64, f64)> = runs
                .iter()
                .filter(|r| r.p == p && r.name == *name)
                .filter_map(|r| r.errors.map(|e| (0.5 - r.nu, e.0.abs().max(1e-4))))
                .collect();
            let s = Series::line(format!("{name}, p = {p}"), pts)
                .with_markers()
                .colored(k);
            series.push(if j == 0 { s.dashed() } else { s });
        }
    }
    line_chart(
        chapter.path("p0_error.svg"),
        &Axes {
            title: format!("Hertz, {MESH}²: p₀ error against ½ − ν"),
            x_label: "½ − ν".into(),
            y_label: "|p₀ error| (relative)".into(),
            log_x: true,
            log_y: true,
        },
        &series,
    )
}

// ANCHOR: lame
/// What Lamé's cylinder gives Table IN2 and its facts.
struct LameStudy {
    table: Table,
    /// The rates between the two finest meshes: (ν, formulation, p, L²,
    /// energy).
    finest_rates: Vec<(f64, &'static str, usize, f64, f64)>,
}

/// "Lamé's cylinder": the three formulations at ν = 0.3 and 0.49999, p = 2
/// and 3, on 4² … 32², with the observed rates.
fn solve_lame() -> Result<LameStudy> {
    let mut lame_table = Table::new(vec![
        Column::new("poisson", "ν", Unit::None, Format::Plain),
        Column::plain("formulation", "formulation"),
        Column::plain("degree", "p"),
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        Column::new("l2_error", "L² error", Unit::None, Format::Sci(2)),
        Column::new("energy_error", "energy error", Unit::None, Format::Sci(2)),
        Column::new("l2_rate", "L² rate", Unit::None, Format::Fixed(2)),
        Column::new("energy_rate", "energy rate", Unit::None, Format::Fixed(2)),
    ]);
    let mut finest_rates = Vec::new();
    for nu in [0.3, 0.49999] {
        for (formulation, name) in FORMULATIONS {
            for p in [2, 3] {
                let rows: Vec<(usize, f64, f64)> = [4, 8, 16, 32]
                    .iter()
                    .map(|&n| {
                        lame::Lame {
                            poisson: nu,
                            formulation,
                            ..lame::Lame::default()
                        }
                        .solve(p, n)
                        .map(|r| (n, r.l2_error, r.energy_error))
                    })
                    .collect::<Result<_>>()?;
                for (k, &(n, l2, en)) in rows.iter().enumerate() {
                    let (l2r, enr): (Cell, Cell) = match k.checked_sub(1).map(|j| rows[j]) {
                        Some((n0, l20, en0)) => {
                            let dh = (n as f64 / n0 as f64).ln();
                            let (a, b) = ((l20 / l2).ln() / dh, (en0 / en).ln() / dh);
                            if k + 1 == rows.len() {
                                finest_rates.push((nu, name, p, a, b));
                            }
                            (a.into(), b.into())
                        }
                        None => (Cell::Empty, Cell::Empty),
                    };
                    lame_table.push(vec![
                        nu.into(),
                        name.into(),
                        p.into(),
                        n.into(),
                        l2.into(),
                        en.into(),
                        l2r,
                        enr,
                    ])?;
                }
            }
        }
    }
    Ok(LameStudy {
        table: lame_table,
        finest_rates,
    })
}
// ANCHOR_END: lame

/// Poisson's ratio of "The pressure along the contact".
const NEAR_HALF: f64 = 0.49999;

/// The curves of Fig. IN2 and the Hertz half-width they are drawn to.
struct MeanStress {
    curves: Vec<Series>,
    /// Hertz's a at ν = `NEAR_HALF`.
    half_width: f64,
    /// Per formulation: the largest distance of its mean stress from
    /// Hertz's along the side, over Hertz's mean stress at x = 0, and its
    /// smallest mean pressure (MPa; below zero is tension).
    measures: Vec<MeanMeasures>,
}

/// How far one formulation's mean stress lies from Hertz's (Fig. IN2).
struct MeanMeasures {
    name: &'static str,
    largest_deviation: f64,
    least_mpa: f64,
}

/// "The pressure along the contact": the mean stress along the contact
/// side, p = 2, ν = `NEAR_HALF`, for the three formulations and Hertz.
fn solve_mean_stress() -> Result<MeanStress> {
    let nu = NEAR_HALF;
    let mut curves = Vec::new();
    let mut exact_a = 0.0;
    let mut measures = Vec::new();
    for (k, f) in FORMULATIONS.iter().enumerate() {
        let s = scene(2, nu, f.0)?;
        let exact = hertz::analytic(&s)?;
        exact_a = exact.half_width;
        let problem = s.build()?;
        let sol = solve(&problem, &SolverOptions::with_kind(SolverKind::Newton))?;
        let pts = mean_pressure(&problem, &sol, 2.0 * exact.half_width)?;
        // Hertz at the surface: σ_xx = σ_yy = −p(x), σ_zz = 2ν·(−p(x))
        let hertz_mpa = |x_mm: f64| 2.0 * (1.0 + nu) / 3.0 * exact.pressure(x_mm * 1e-3) * 1e-6;
        measures.push(MeanMeasures {
            name: f.1,
            largest_deviation: pts
                .iter()
                .map(|&(x, m)| (m - hertz_mpa(x)).abs())
                .fold(0.0, f64::max)
                / hertz_mpa(0.0),
            least_mpa: pts.iter().map(|p| p.1).fold(f64::INFINITY, f64::min),
        });
        curves.push(Series::line(f.1, pts).colored(k));
        if k == 0 {
            let hertz_mean = (0..=200)
                .map(|i| {
                    let x_mm = 2.0 * exact.half_width * i as f64 / 200.0 * 1e3;
                    (x_mm, hertz_mpa(x_mm))
                })
                .collect();
            curves.push(
                Series::line("Hertz", hertz_mean)
                    .dashed()
                    .colored(FORMULATIONS.len()),
            );
        }
    }
    Ok(MeanStress {
        curves,
        half_width: exact_a,
        measures,
    })
}

/// Fig. IN2: the mean stress along the contact side.
fn draw_mean_stress(chapter: &Chapter, curves: &[Series]) -> Result<()> {
    line_chart(
        chapter.path("mean_stress.svg"),
        &Axes {
            title: format!("Mean stress along the contact side, p = 2, {MESH}², ν = {NEAR_HALF}"),
            x_label: "x (mm)".into(),
            y_label: "−(σ_xx + σ_yy + σ_zz)/3 (MPa)".into(),
            log_x: false,
            log_y: false,
        },
        curves,
    )
}

// ANCHOR: facts
/// The set-up the prose quotes: the mesh, the penalty's safety factor and
/// Hertz's a at ν = `NEAR_HALF` (Fig. IN2's caption).
fn record_setup_facts(f: &mut Facts, exact_a: f64) -> Result<()> {
    f.count("mesh", MESH)?;
    f.number("safety", SAFETY, Format::Plain)?;
    f.number("hertz_a_mm_incompressible", exact_a * 1e3, Format::Fixed(2))
}

/// "Hertz along the ν axis" quotes the errors of p₀ and a at ν = 0.3,
/// 0.499 and 0.49999, per degree and formulation.
fn record_axis_facts(f: &mut Facts, runs: &[Run]) -> Result<()> {
    let find = |p: usize, nu: f64, name: &str| {
        runs.iter()
            .find(|r| r.p == p && r.nu == nu && r.name == name)
            .and_then(|r| r.errors)
    };
    for p in DEGREES {
        for (_, name) in FORMULATIONS {
            for (nu, key) in [(0.3, "03"), (0.499, "499"), (0.49999, "49999")] {
                match find(p, nu, name) {
                    Some((ep, ea, _)) => {
                        f.number(
                            &format!("p0_{name}_p{p}_{key}"),
                            ep,
                            Format::SignedPercent(1),
                        )?;
                        f.number(
                            &format!("a_{name}_p{p}_{key}"),
                            ea,
                            Format::SignedPercent(1),
                        )?;
                    }
                    None => {
                        f.text(&format!("p0_{name}_p{p}_{key}"), "no convergence")?;
                        f.text(&format!("a_{name}_p{p}_{key}"), "no convergence")?;
                    }
                }
            }
        }
    }
    Ok(())
}

/// "The pressure along the contact" quotes how far each formulation's
/// mean stress lies from Hertz's, and its least mean pressure.
fn record_mean_facts(f: &mut Facts, measures: &[MeanMeasures]) -> Result<()> {
    for m in measures {
        f.number(
            &format!("mean_deviation_{}", m.name),
            m.largest_deviation,
            Format::Fixed(2),
        )?;
        f.number(
            &format!("mean_least_{}", m.name),
            m.least_mpa,
            Format::Fixed(2),
        )?;
    }
    Ok(())
}

/// "Lamé's cylinder" quotes the rates between the two finest meshes at
/// ν = 0.49999.
fn record_lame_facts(f: &mut Facts, finest_rates: &[(f64, &str, usize, f64, f64)]) -> Result<()> {
    for &(nu, name, p, l2, en) in finest_rates {
        if nu == 0.49999 {
            f.number(&format!("l2_rate_{name}_p{p}"), l2, Format::Fixed(2))?;
            f.number(&format!("energy_rate_{name}_p{p}"), en, Format::Fixed(2))?;
        }
    }
    Ok(())
}
// ANCHOR_END: facts
