//! The memory estimate against the measured peak: the program behind the
//! memory table of the chapter "Reliability".
//!
//! Each case is a rectangle of degree p on an m × m mesh resting on a rigid
//! floor under its weight, run by the `iga-contact` binary of this build as
//! a child process (with `--max-memory 1T`, so that none is refused); its
//! peak resident memory (`VmHWM`, from `wait4`'s `ru_maxrss`) is compared
//! with [`Scene::estimate`] (the largest of three runs for the small
//! cases, whose peaks vary from launch to launch). Meshes grow per degree until the estimate
//! would pass [`LIMIT`], one run at a time.
//!
//! Output: `book/src/generated/memory_table/`. A heavy program (minutes,
//! up to about 15 GB): `reproduce --only memory_table`.

use companion::harness;

use companion::chapter::Chapter;
use harness::{body_scene, launch, mesh, refine, Launch, SHAPES};
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};
use iga_contact::resources::human_bytes;
use iga_contact::scene::Scene;
use iga_contact::Result;

/// No case whose estimate is above this is run: room for the largest
/// case (p = 2 on 1024², about 13 GB measured) on a 24 GB machine, with
/// the rest left to the system.
const LIMIT: f64 = 20.0e9;

/// (degree, meshes per direction): every degree the chapter names, the
/// meshes as far as [`LIMIT`] and the run time allow; p = 2, whose ladder
/// reaches 1024², last.
const CASES: [(usize, &[usize]); 6] = [
    (1, &[8, 32, 128, 512]),
    (3, &[8, 32, 128, 256]),
    (4, &[8, 32, 128]),
    (6, &[8, 32, 64]),
    (10, &[8, 16, 32]),
    (2, &[8, 32, 128, 256, 512, 1024]),
];

/// Cases estimated below this run [`REPEATS`] times and keep the largest
/// peak: a run of tens of megabytes peaks differently from one launch to
/// the next (measured here: 25 and 34 MB for the same case), by as much
/// as the estimate's own error, while a run of gigabytes does not.
const SMALL: f64 = 1.0e9;
const REPEATS: usize = 3;

fn main() -> Result<()> {
    let mut chapter = Chapter::from_args("memory_table")?;
    let work = std::env::temp_dir().join(format!("memory-table-{}", std::process::id()));
    std::fs::create_dir_all(&work).expect("a work folder");
    let mut table = Table::new(vec![
        Column::plain("degree", "p"),
        Column::plain("mesh", "mesh"),
        Column::plain("dofs", "DOFs"),
        Column::new("factor", "factor entries", Unit::None, Format::Sci(2)).csv_only(),
        Column::plain("phase", "peak phase"),
        Column::new("estimate", "estimate", Unit::Megabyte, Format::Fixed(0)),
        Column::new("peak", "VmHWM", Unit::Megabyte, Format::Fixed(0)),
        Column::new("ratio", "estimate / peak", Unit::None, Format::Fixed(2)),
        Column::new("seconds", "run", Unit::Second, Format::Fixed(1)).csv_only(),
    ]);
    let (mut lo, mut hi, mut largest, mut runs) = (f64::INFINITY, 0.0f64, 0.0f64, 0usize);
    for (p, meshes) in CASES {
        for &m in meshes {
            let e = [m, m];
            let text = body_scene(
                "memory",
                SHAPES[0].1,
                &refine(p, e),
                "",
                "[output]\nsummary = true\n",
            );
            let estimate = Scene::from_toml_str(&text)?.estimate()?;
            if estimate.peak_bytes() > LIMIT {
                eprintln!("memory_table: p = {p}, {m}²: estimate over the limit, not run");
                break;
            }
            std::fs::write(work.join("memory.toml"), &text).expect("writable work folder");
            let args = ["run", "memory.toml", "--out", "out", "--max-memory", "1T"];
            let repeats = if estimate.peak_bytes() < SMALL {
                REPEATS
            } else {
                1
            };
            let outcomes: Vec<_> = (0..repeats)
                .map(|_| launch(&work, &args, Launch::default()))
                .collect();
            if let Some(bad) = outcomes.iter().find(|o| o.code != Some(0)) {
                eprintln!("memory_table: p = {p}, {m}²: {}", bad.stderr.trim());
                continue;
            }
            let o = outcomes
                .into_iter()
                .max_by(|a, b| a.peak_bytes.total_cmp(&b.peak_bytes))
                .expect("at least one run");
            let ratio = estimate.peak_bytes() / o.peak_bytes;
            eprintln!(
                "memory_table: p = {p}, {m}²: estimate {}, peak {}, ratio {ratio:.2}",
                human_bytes(estimate.peak_bytes()),
                human_bytes(o.peak_bytes)
            );
            (lo, hi) = (lo.min(ratio), hi.max(ratio));
            largest = largest.max(o.peak_bytes);
            runs += 1;
            table.push(vec![
                p.into(),
                mesh(e).into(),
                estimate.dofs.into(),
                estimate.factor_entries.into(),
                Cell::from(estimate.peak_phase()),
                estimate.peak_bytes().into(),
                o.peak_bytes.into(),
                ratio.into(),
                o.seconds.into(),
            ])?;
        }
    }
    let _ = std::fs::remove_dir_all(&work);
    chapter.table("memory", &table)?;
    chapter.timed("memory.csv");
    chapter.timed("memory.md");
    let f = chapter.facts();
    f.timed_number("runs", runs as f64, Format::Fixed(0))?;
    f.timed_number("ratio_min", lo, Format::Fixed(2))?;
    f.timed_number("ratio_max", hi, Format::Fixed(2))?;
    f.timed_number("largest_peak_gb", largest / 1e9, Format::Fixed(1))?;
    chapter.finish()
}
