//! Lamé's thick-walled cylinder under internal pressure, plane strain: a
//! convergence study of the elasticity discretisation (Eq. 3) against the
//! exact solution.
//!
//! One quarter of the cross-section, r_in ≤ r ≤ r_out in the first
//! quadrant, is modelled with the exact quarter-annulus NURBS patch. The
//! inner arc carries the pressure; symmetry gives u_y = 0 on the x axis and
//! u_x = 0 on the y axis. For degrees p = 2, 3, 4 and n × n elements, the
//! relative L² and energy errors are written to
//! `book/src/generated/lame/convergence.{csv,md,svg}`. The set-up, the
//! solve and the measures are `companion::lame`.
//!
//! Run with `cargo run --release --example lame`. The run fails (non-zero
//! exit) if the observed rates on the finest levels fall below p + 0.8 (L²)
//! or p − 0.2 (energy).

use companion::chapter::Chapter;
use companion::lame::{check_rates, plot, rates, table, Lame, Row};
use iga_contact::report::table::Format;

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    let problem = Lame::default();
    let mut chapter = Chapter::from_args("lame")?;
    let levels = [2, 4, 8, 16, 32, 64];
    let mut rows = Vec::new();
    let mut failures = Vec::new();
    for p in [2, 3, 4] {
        let start = rows.len();
        for &n in &levels {
            let t = std::time::Instant::now();
            let row = problem.solve(p, n)?;
            eprintln!(
                "p = {p}, {n:>2}×{n:<2}: {:>6} DOFs, L² {:.3e}, energy {:.3e} ({:.2} s)",
                row.dofs,
                row.l2_error,
                row.energy_error,
                t.elapsed().as_secs_f64()
            );
            rows.push(row);
        }
        if let Err(e) = check_rates(&rows[start..], p) {
            failures.push(e);
        }
    }
    let table = table(&rows)?;
    chapter.table("convergence", &table)?;
    plot(&rows, &chapter.path("convergence.svg"))?;
    println!("{}", table.to_markdown());
    let f = chapter.facts();
    for p in [2, 3, 4] {
        let group: Vec<Row> = rows.iter().filter(|r| r.degree == p).cloned().collect();
        if let Some(Some((l2, en))) = rates(&group).last() {
            f.number(&format!("l2_rate_p{p}"), *l2, Format::Fixed(2))?;
            f.number(&format!("energy_rate_p{p}"), *en, Format::Fixed(2))?;
        }
        if let Some(finest) = group.last() {
            f.count(&format!("dofs_finest_p{p}"), finest.dofs)?;
            f.number(
                &format!("energy_error_finest_p{p}"),
                finest.energy_error,
                Format::Pow10(1),
            )?;
        }
    }
    chapter.finish()?;
    if !failures.is_empty() {
        return Err(format!("rates below the expected ones:\n{}", failures.join("\n")).into());
    }
    Ok(())
}
