//! The reliability campaign: the program behind the chapter "Reliability".
//!
//! It probes the `iga-contact` binary of this build as a user would, as a
//! child process, hundreds of times, and the library directly where the
//! question is about the numerics:
//!
//! 1. `check` at the documented maxima (times, answers);
//! 2. refinement time against the number of control points (library);
//! 3. the memory estimate against measured peaks (`wait4` → `ru_maxrss`);
//! 4. valid but hard scenes under an 8 GiB address-space limit, every
//!    outcome counted (no signal, no backtrace);
//! 5. ill-posed input: the refusal and its message;
//! 6. large initial gaps, with both solvers and the paper's (library);
//! 7. faults injected into the output transaction: a full disk at every
//!    file, unwritable locations, SIGKILL spread over a run, SIGINT and
//!    SIGTERM, concurrent runs into one folder.
//!
//! Output: `book/src/generated/reliability/`. A heavy program (about 15
//! minutes and up to 6 GB on two cores): `reproduce --all`, or
//! `cargo build --release && cargo run --release --example reliability`.

mod campaign;
mod faults;
use companion::harness;

use companion::chapter::Chapter;
use companion::timing::{median_time, Machine};
use companion::Solver;
use harness::{body_scene, commit, launch, mesh, refine, Launch, MULTIPATCH_SHAPES, SHAPES};
use iga_contact::post::contact_resultant;
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};
use iga_contact::scene::{Scene, MAX_DEGREE, MAX_ELEMENTS};
use iga_contact::solver::solve;
use iga_contact::{geometry, Result};
use std::path::Path;
use std::time::Instant;

// ---------------------------------------------------------------------------
// 1. check at the documented maxima
// ---------------------------------------------------------------------------

/// `about 1.6 GiB` from a `check` answer or refusal.
fn about(text: &str) -> String {
    let Some(at) = text.find("about ") else {
        return String::new();
    };
    text[at..]
        .split_whitespace()
        .take(3)
        .collect::<Vec<_>>()
        .join(" ")
}

// ANCHOR: maxima
fn maxima(work: &Path, chapter: &mut Chapter) -> Result<f64> {
    let cases = [
        (MAX_DEGREE, [64, 64]),
        (MAX_DEGREE, [MAX_ELEMENTS, 1]),
        (2, [MAX_ELEMENTS, 1]),
        (MAX_DEGREE, [MAX_ELEMENTS, MAX_ELEMENTS]),
        (1, [MAX_ELEMENTS, MAX_ELEMENTS]),
    ];
    let mut table = Table::new(vec![
        Column::plain("degree", "p"),
        Column::plain("mesh", "mesh"),
        Column::new("seconds", "`check`", Unit::Second, Format::Fixed(2)),
        Column::plain("exit", "exit"),
        Column::plain("answer", "answer"),
    ]);
    let mut slowest: f64 = 0.0;
    for (p, e) in cases {
        let text = body_scene("maxima", SHAPES[0].1, &refine(p, e), "", "");
        std::fs::write(work.join("maxima.toml"), text).expect("writable work folder");
        let o = launch(work, &["check", "maxima.toml"], Launch::default());
        slowest = slowest.max(o.seconds);
        let answer = match o.code {
            Some(0) => format!("valid; a run needs {}", about(&o.stdout)),
            Some(2) => format!("refused: a run would need {}", about(&o.stderr)),
            _ => format!("unexpected: {}", o.stderr.trim()),
        };
        table.push(vec![
            p.into(),
            mesh(e).into(),
            o.seconds.into(),
            o.status().into(),
            answer.into(),
        ])?;
    }
    chapter.table("maxima", &table)?;
    chapter.timed("maxima.csv");
    chapter.timed("maxima.md");
    Ok(slowest)
}
// ANCHOR_END: maxima

// ---------------------------------------------------------------------------
// 2. refinement time against size
// ---------------------------------------------------------------------------

// ANCHOR: refinement
/// Times k-refinement of the unit rectangle (library, median of 5) on
/// three ladders, and fits the exponent of time against control points.
fn refinement(chapter: &mut Chapter) -> Result<()> {
    let ladders: [(&str, usize, [[usize; 2]; 4]); 3] = [
        (
            "p2",
            2,
            [[256, 256], [512, 512], [1024, 1024], [2048, 2048]],
        ),
        (
            "p10",
            10,
            [[128, 128], [256, 256], [512, 512], [1024, 1024]],
        ),
        ("p10_strip", 10, [[512, 1], [1024, 1], [2048, 1], [4096, 1]]),
    ];
    let exact = geometry::rectangle(0.0, 0.0, 1.0, 0.5)?;
    let mut table = Table::new(vec![
        Column::plain("degree", "p"),
        Column::plain("mesh", "mesh"),
        Column::plain("control_points", "control points"),
        Column::new("seconds", "time", Unit::Millisecond, Format::Fixed(1)),
        Column::new("per_point", "per point", Unit::Second, Format::Sci(2)).csv_only(),
        Column::new("ns_per_point", "ns / point", Unit::None, Format::Fixed(0)).markdown_only(),
    ]);
    for (key, p, meshes) in ladders {
        let mut fit = Vec::new();
        for e in meshes {
            let timed = median_time(5, || exact.k_refined(p, e))?;
            let n = timed.value.points.len();
            let per_point = timed.seconds / n as f64;
            table.push(vec![
                p.into(),
                mesh(e).into(),
                n.into(),
                timed.seconds.into(),
                per_point.into(),
                (per_point * 1e9).into(),
            ])?;
            fit.push(((n as f64).ln(), timed.seconds.ln()));
        }
        // least-squares slope of ln t against ln n
        let m = fit.len() as f64;
        let (sx, sy) = fit.iter().fold((0.0, 0.0), |(a, b), (x, y)| (a + x, b + y));
        let (mx, my) = (sx / m, sy / m);
        let num: f64 = fit.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
        let den: f64 = fit.iter().map(|(x, _)| (x - mx).powi(2)).sum();
        let facts = chapter.facts();
        facts.timed_number(
            &format!("refine_exponent_{key}"),
            num / den,
            Format::Fixed(2),
        )?;
    }
    chapter.table("refinement", &table)?;
    chapter.timed("refinement.csv");
    chapter.timed("refinement.md");
    Ok(())
}
// ANCHOR_END: refinement

// ---------------------------------------------------------------------------
// 4. ill-posed input
// ---------------------------------------------------------------------------

// ANCHOR: illposed
/// Scenes that cannot be solved as posed, and what `check` answers.
fn ill_posed(work: &Path, chapter: &mut Chapter) -> Result<usize> {
    let minimal = std::fs::read_to_string(companion::shipped_path("minimal.toml"))
        .expect("the shipped minimal scene");
    let taylor = std::fs::read_to_string(companion::shipped_path("taylor.toml"))
        .expect("the shipped Taylor scene");
    let rollers = "[[support]]\nbody = \"block\"\nside = \"xi_min\"\ncomponent = \"x\"\n";
    let upper = "[[support]]\nbody = \"upper\"\nside = \"xi_min\"\ncomponent = \"x\"\n";
    // every edit below must find its target, or the row would test the
    // unedited scene
    let edit = |text: &str, from: &str, to: &str| {
        assert!(text.contains(from), "the shipped scene has no {from:?}");
        text.replace(from, to)
    };
    let quadrature = "elements = [4, 1] }\nquadrature = 1";
    // a quarter annulus bearing on a concentric one: the contact normals are
    // radial, so nothing resists a rotation about the common centre
    let annuli = include_str!("../../tests/fixtures/rotating_annuli.toml");
    let cases: [(&str, String); 8] = [
        (
            "a quarter annulus in a concentric one, the outer held",
            annuli.to_string(),
        ),
        (
            "`minimal.toml` without its support",
            edit(&minimal, rollers, ""),
        ),
        (
            "`taylor.toml` without the upper block's support",
            edit(&taylor, upper, ""),
        ),
        (
            "`minimal.toml` with `quadrature = 1`",
            edit(&minimal, "elements = [4, 1] }", quadrature),
        ),
        (
            "the same with `allow_underintegration = true`",
            format!(
                "allow_underintegration = true\n{}",
                edit(&minimal, "elements = [4, 1] }", quadrature)
            ),
        ),
        (
            "`minimal.toml` with `nitsche = { gauss_points = 1 }`",
            format!("{minimal}nitsche = {{ gauss_points = 1 }}\n"),
        ),
        (
            "`minimal.toml` with `young = 1e-300`",
            edit(&minimal, "young = 1.0e6", "young = 1e-300"),
        ),
        (
            "`minimal.toml` with `pressure = 1e200`",
            edit(&minimal, "pressure = 1.0e4", "pressure = 1e200"),
        ),
    ];
    let mut table = Table::new(vec![
        Column::plain("input", "input"),
        Column::plain("exit", "exit"),
        Column::plain("answer", "answer of `check`"),
    ]);
    let mut refused = 0;
    for (label, text) in cases {
        std::fs::write(work.join("scene.toml"), text).expect("writable work folder");
        let o = launch(work, &["check", "scene.toml"], Launch::default());
        refused += usize::from(o.code == Some(2));
        let answer = match o.code {
            Some(0) => "valid".to_string(),
            _ => o.message(),
        };
        table.push(vec![label.into(), o.status().into(), answer.into()])?;
    }
    chapter.table("ill_posed", &table)?;
    Ok(refused)
}
// ANCHOR_END: illposed

// ---------------------------------------------------------------------------
// 5. large initial gaps
// ---------------------------------------------------------------------------

// ANCHOR: gaps
/// A body above the floor, held only sideways, loaded downwards: only a
/// rigid motion closes the gap.
struct Lifted {
    label: &'static str,
    /// Its size, the unit of the gap.
    size: f64,
    /// Its scene, lifted by a gap.
    scene: fn(f64) -> String,
    /// The load the contact must carry.
    load: f64,
}

fn block(gap: f64) -> String {
    format!(
        r#"[[body]]
name = "block"
geometry = {{ rectangle = {{ x0 = 0.0, y0 = {gap}, x1 = 1.0, y1 = {top} }} }}
refine = {{ degree = 2, elements = [6, 3] }}
material = {{ young = 1.0e9, poisson = 0.3, plane = "strain" }}
[[support]]
body = "block"
side = "xi_min"
component = "x"
[[load]]
pressure = {{ body = "block", side = "eta_max", pressure = 1.0e7 }}
[[contact]]
slave = "block"
slave_side = "eta_min"
master = {{ rigid_segment = {{ from = [-1.0, 0.0], to = [2.0, 0.0] }} }}
"#,
        top = gap + 0.5
    )
}

fn disk(gap: f64) -> String {
    let hertz = std::fs::read_to_string(companion::shipped_path("hertz.toml"))
        .expect("the shipped Hertz scene");
    let solver = hertz.find("[solver]").unwrap_or(hertz.len());
    hertz[..solver].replace(
        "center = [0.0, 0.2]",
        &format!("center = [0.0, {}]", 0.2 + gap),
    )
}

/// Initial gaps, in units of the body's size.
const GAP_RATIOS: [f64; 6] = [0.0, 0.002, 0.02, 0.2, 1.0, 2.0];

/// What the gaps' facts quote.
struct Gaps {
    /// The largest iteration count of the default BFGS and Newton.
    most_iterations: usize,
    /// The largest relative force error of any converged run.
    worst_force_error: f64,
}

/// Solves every lifted body with the default BFGS, Newton and the paper's
/// BFGS (the columns of the table, in this order).
fn gaps(chapter: &mut Chapter) -> Result<Gaps> {
    let bodies = [
        Lifted {
            label: "block",
            size: 0.5,
            scene: block,
            load: 1.0e7,
        },
        Lifted {
            label: "half disk",
            size: 0.4,
            scene: disk,
            load: 1.3e6 * std::f64::consts::PI * 0.04 / 2.0,
        },
    ];
    let solvers = [Solver::Bfgs, Solver::Newton, Solver::Paper];
    let mut table = Table::new(vec![
        Column::plain("body", "body"),
        Column::new("gap_ratio", "gap / size", Unit::None, Format::Fixed(3)),
        Column::plain("bfgs", "BFGS"),
        Column::plain("newton", "Newton"),
        Column::plain("paper", "paper's BFGS"),
        Column::new("force_error", "force error", Unit::None, Format::Sci(0)),
    ]);
    let (mut most, mut worst) = (0, 0.0f64);
    for Lifted {
        label,
        size,
        scene,
        load,
    } in bodies
    {
        for ratio in GAP_RATIOS {
            let problem = Scene::from_toml_str(&scene(ratio * size))?.build()?;
            let mut row: Vec<Cell> = vec![label.into(), ratio.into()];
            let mut error = 0.0f64;
            for solver in solvers {
                match solve(&problem, &solver.options()) {
                    Ok(s) => {
                        let f = contact_resultant(&problem, &s.full)[1];
                        error = error.max((f - load).abs() / load);
                        if solver != Solver::Paper {
                            most = most.max(s.history.len());
                        }
                        row.push(s.history.len().into());
                    }
                    Err(iga_contact::Error::NotConverged { history, .. }) => {
                        row.push(format!("failed ({})", history.len()).into());
                    }
                    Err(e) => row.push(format!("error: {e}").into()),
                }
            }
            worst = worst.max(error);
            row.push(error.max(1e-16).into());
            table.push(row)?;
        }
    }
    chapter.table("gaps", &table)?;
    Ok(Gaps {
        most_iterations: most,
        worst_force_error: worst,
    })
}
// ANCHOR_END: gaps

// ---------------------------------------------------------------------------

/// The number of generated inputs of `tests/fuzz.rs` and its families, read
/// from its proptest configurations.
fn fuzz_counts() -> (u32, usize) {
    let src = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz.rs"))
        .unwrap_or_default();
    let mut total = 0;
    let mut groups = 0;
    for part in src.split("proptest_config(config(").skip(1) {
        let n: String = part
            .chars()
            .take_while(|c| c.is_ascii_digit() || *c == '_')
            .collect();
        total += n.replace('_', "").parse::<u32>().unwrap_or(0);
        groups += 1;
    }
    (total, groups)
}

fn main() -> Result<()> {
    // fail fast: the chapter folder must take the report before the work
    let mut chapter = Chapter::from_args("reliability")?;
    harness::binary();
    let work = std::env::temp_dir().join(format!("reliability-{}", std::process::id()));
    std::fs::create_dir_all(&work).expect("a temporary work folder");
    let t0 = Instant::now();
    let start = Machine::here();

    eprintln!("1/6 check at the maxima");
    let slowest_maximum = maxima(&work, &mut chapter)?;
    eprintln!("2/6 refinement");
    refinement(&mut chapter)?;
    eprintln!("3/6 campaign");
    let tally = campaign::run(&work);
    eprintln!("4/6 ill-posed input");
    let refused = ill_posed(&work, &mut chapter)?;
    eprintln!("5/6 gaps");
    let gaps = gaps(&mut chapter)?;
    eprintln!("6/6 faults");
    let faults = faults::run(&work)?;
    let _ = std::fs::remove_dir_all(&work);

    // the campaign's outcomes and the lists behind them
    let mut outcomes = Table::new(vec![
        Column::plain("outcome", "outcome"),
        Column::plain("launches", "launches"),
    ]);
    for o in campaign::OUTCOMES {
        outcomes.push(vec![
            o.into(),
            tally.by_outcome.get(o).copied().unwrap_or(0).into(),
        ])?;
    }
    chapter.table("campaign", &outcomes)?;
    let mut details = String::new();
    for (message, scenes) in &tally.failures {
        details.push_str(&format!(
            "- `{message}` ({}): {}\n",
            scenes.len(),
            scenes.join("; ")
        ));
    }
    chapter.text("campaign_failures.md", &details)?;
    let stopped: String = tally.stopped.iter().map(|s| format!("- {s}\n")).collect();
    chapter.text("campaign_stopped.md", &stopped)?;
    let unclean: String = tally.unclean.iter().map(|s| format!("- {s}\n")).collect();
    chapter.text("campaign_unclean.md", &unclean)?;
    chapter.table("faults", &faults.table)?;
    for f in [
        "campaign.csv",
        "campaign.md",
        "campaign_failures.md",
        "campaign_stopped.md",
        "campaign_unclean.md",
        "faults.csv",
        "faults.md",
    ] {
        chapter.timed(f);
    }

    let (fuzz, families) = fuzz_counts();
    let total = t0.elapsed().as_secs_f64();
    let end = Machine::here();
    let f = chapter.facts();
    start.record(f, "")?;
    f.timed_text(
        "load_end",
        end.load.map_or("unknown".into(), |l| format!("{l:.1}")),
    )?;
    f.timed_text("commit", commit())?;
    f.timed_number("minutes", total / 60.0, Format::Fixed(0))?;
    f.count("max_degree", MAX_DEGREE)?;
    f.count("max_elements", MAX_ELEMENTS)?;
    f.timed_number("slowest_check_at_maxima", slowest_maximum, Format::Fixed(2))?;
    f.count("campaign_limit_gib", (campaign::LIMIT >> 30) as usize)?;
    f.timed_number("campaign_timeout", campaign::TIMEOUT, Format::Fixed(0))?;
    f.count("campaign_shapes", SHAPES.len())?;
    f.count("campaign_refinements", campaign::refinements().len())?;
    f.count("campaign_multipatch_shapes", MULTIPATCH_SHAPES.len())?;
    f.count(
        "campaign_multipatch_refinements",
        campaign::multipatch_refinements().len(),
    )?;
    f.count("campaign_output_sets", campaign::output_sets().len())?;
    f.count("campaign_extremes", tally.extremes)?;
    let extremes: Vec<String> = campaign::extremes().into_iter().map(|(l, _)| l).collect();
    f.text("campaign_extreme_list", extremes.join("; "))?;
    f.count("campaign_scenes", tally.scenes)?;
    f.count("campaign_launches", tally.launches)?;
    f.count("campaign_unclean", tally.unclean.len())?;
    f.count("campaign_stopped", tally.stopped.len())?;
    f.timed_number(
        "campaign_slowest_check",
        tally.slowest_check,
        Format::Fixed(2),
    )?;
    f.count("ill_posed_refused", refused)?;
    f.count("gap_max_iterations", gaps.most_iterations)?;
    f.number(
        "gap_ratio_max",
        GAP_RATIOS[GAP_RATIOS.len() - 1],
        Format::Plain,
    )?;
    f.number(
        "gap_force_error",
        gaps.worst_force_error.max(1e-16),
        Format::Pow10(0),
    )?;
    f.count("fuzz_inputs", fuzz as usize)?;
    f.count("fuzz_families", families)?;
    f.count("fault_trials", faults.trials)?;
    f.count("mixed_outputs", faults.mixed)?;
    f.timed_number("kills", faults.kills as f64, Format::Fixed(0))?;
    f.count("kills_left", faults.kills_left)?;
    f.count("kills_cleaned", faults.kills_cleaned)?;
    f.timed_number("kill_span", faults.kill_span, Format::Fixed(2))?;
    f.count("signal_moments", faults::SIGNAL_MOMENTS)?;
    f.count("concurrent_rounds", faults::CONCURRENT_ROUNDS)?;
    f.text("fixture_mesh", mesh([faults::FIXTURE.0; 2]))?;
    f.timed_number("fixture_seconds", faults.fixture_seconds, Format::Fixed(2))?;
    f.count("fixture_files", faults.fixture_files.len())?;
    f.text("fixture_listing", faults::describe(&faults.fixture_files))?;
    let dir = chapter.dir().display().to_string();
    chapter.finish()?;
    println!("wrote {dir}/ in {total:.0} s");
    Ok(())
}
