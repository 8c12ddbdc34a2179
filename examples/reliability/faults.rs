//! Faults injected into the output transaction: after each, the output
//! folder is compared byte for byte with the earlier set and the new one.

use crate::harness::{body_scene, launch, refine, Launch, Outcome, ALL_OUTPUTS, SHAPES};
use iga_contact::report::atomic;
use iga_contact::report::table::{Column, Table};
use iga_contact::resources::human_bytes;
use iga_contact::Result;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

type Set = BTreeMap<String, Vec<u8>>;

/// The kills are spaced by this many times a clean run over [`KILLS`]
/// moments, and go on past that span until a run ends before its kill, so
/// that they cover every phase up to the commit and beyond whatever the
/// machine's load.
pub const KILL_SPAN: f64 = 1.25;
/// The planned number of kill moments (more if the runs are slow).
pub const KILLS: usize = 40;
/// SIGINT and SIGTERM are each sent at this many moments of a run.
pub const SIGNAL_MOMENTS: usize = 10;
/// Rounds of two runs started together into one folder.
pub const CONCURRENT_ROUNDS: usize = 30;
/// The fixture: elements per direction and VTU subdivisions.
pub const FIXTURE: (usize, usize) = (24, 12);

/// Two scenes ("old" and "new", different titles) writing every output into
/// one folder, and the two complete sets of files they write.
pub struct Fixture {
    dir: PathBuf,
    out: PathBuf,
    old: Set,
    new: Set,
    /// Wall time of one clean run (median of five).
    pub seconds: f64,
}

/// What a fault left behind.
struct Trial {
    outcome: Outcome,
    /// "old", "new" or "MIXED".
    state: &'static str,
    staging: usize,
}

impl Fixture {
    pub fn new(work: &Path, name: &str, elements: usize, subdivisions: usize) -> Self {
        let dir = work.join(name);
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("the work folder takes the fixture");
        let output = format!("{ALL_OUTPUTS}vtu_subdivisions = {subdivisions}\n");
        for t in ["old", "new"] {
            let text = body_scene(t, SHAPES[0].1, &refine(2, [elements; 2]), "", &output);
            std::fs::write(dir.join(format!("{t}.toml")), text).expect("writable");
        }
        let o = launch(
            &dir,
            &["run", "new.toml", "--out", "reference"],
            Launch::default(),
        );
        assert!(o.code == Some(0), "{}", o.stderr);
        let new = companion::timing::untimed_snapshot(&dir.join("reference")).expect("readable");
        let mut f = Self {
            out: dir.join("out"),
            dir,
            old: Set::new(),
            new,
            seconds: o.seconds,
        };
        f.reset();
        f.old = companion::timing::untimed_snapshot(&f.out).expect("readable");
        // the time of a run as the faults meet it: the median of five
        // (the first run of a fresh scene is the slowest)
        let mut times: Vec<f64> = (0..5)
            .map(|_| {
                let t = f.run_new(Launch::default()).outcome.seconds;
                f.reset();
                t
            })
            .collect();
        times.sort_by(f64::total_cmp);
        f.seconds = times[2];
        f
    }

    /// The files of a complete set, with their sizes.
    pub fn files(&self) -> Vec<(String, usize)> {
        self.new.iter().map(|(n, b)| (n.clone(), b.len())).collect()
    }

    fn reset(&self) {
        let o = launch(
            &self.dir,
            &["run", "old.toml", "--out", "out"],
            Launch::default(),
        );
        assert!(o.code == Some(0), "{}", o.stderr);
    }

    fn run_new(&self, how: Launch) -> Trial {
        let outcome = launch(&self.dir, &["run", "new.toml", "--out", "out"], how);
        self.trial(outcome)
    }

    fn trial(&self, outcome: Outcome) -> Trial {
        let now = companion::timing::untimed_snapshot(&self.out).unwrap_or_default();
        let state = if now == self.old {
            "old"
        } else if now == self.new {
            "new"
        } else {
            "MIXED"
        };
        Trial {
            outcome,
            state,
            staging: atomic::staging_entries(&self.out).len(),
        }
    }
}

fn chattr(flag: &str, path: &Path) -> bool {
    Command::new("chattr")
        .arg(flag)
        .arg(path)
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

/// The fault table, and how many trials left a mixed folder.
pub struct Faults {
    pub table: Table,
    pub mixed: usize,
    pub trials: usize,
    pub fixture_seconds: f64,
    pub fixture_files: Vec<(String, usize)>,
    pub kills: usize,
    /// Kills after which a staging folder was left, and of those the ones
    /// the next run removed.
    pub kills_left: usize,
    pub kills_cleaned: usize,
    /// The last kill moment, in clean runs.
    pub kill_span: f64,
}

impl Faults {
    fn row(&mut self, fault: &str, trials: &[Trial], next: &str) -> Result<()> {
        let mut codes: BTreeMap<String, usize> = BTreeMap::new();
        let mut states: BTreeMap<&str, usize> = BTreeMap::new();
        let mut left = 0;
        for t in trials {
            *codes.entry(t.outcome.status()).or_default() += 1;
            *states.entry(t.state).or_default() += 1;
            left += usize::from(t.staging > 0);
            self.mixed += usize::from(t.state == "MIXED");
        }
        self.trials += trials.len();
        let list = |m: Vec<(String, usize)>| {
            m.iter()
                .map(|(k, v)| format!("{k} × {v}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        self.table.push(vec![
            fault.into(),
            trials.len().into(),
            list(codes.into_iter().collect()).into(),
            list(
                states
                    .into_iter()
                    .map(|(k, v)| (k.to_string(), v))
                    .collect(),
            )
            .into(),
            left.into(),
            next.into(),
        ])
    }
}

/// Injects every fault into runs of the fixture.
pub fn run(work: &Path) -> Result<Faults> {
    let f = Fixture::new(work, "faults", FIXTURE.0, FIXTURE.1);
    let mut out = Faults {
        table: Table::new(vec![
            Column::plain("fault", "fault"),
            Column::plain("trials", "trials"),
            Column::plain("exit", "exit codes"),
            Column::plain("folder", "folder after"),
            Column::plain("staging_left", "staging left"),
            Column::plain("next_run", "next run"),
        ]),
        mixed: 0,
        trials: 0,
        fixture_seconds: f.seconds,
        fixture_files: f.files(),
        kills: 0,
        kills_left: 0,
        kills_cleaned: 0,
        kill_span: 0.0,
    };

    // A full disk at every file: a file-size limit one byte below each size.
    let mut limits: Vec<u64> = out
        .fixture_files
        .iter()
        .map(|(_, b)| *b as u64 - 1)
        .collect();
    limits.sort();
    limits.dedup();
    let trials: Vec<Trial> = limits
        .into_iter()
        .map(|limit| {
            f.run_new(Launch {
                file_size: Some(limit),
                ..Launch::default()
            })
        })
        .collect();
    out.row("full disk, below each output's size", &trials, "—")?;

    // Unwritable locations (the immutable attribute: needs root and ext4).
    if chattr("+i", &f.out) {
        let t = f.run_new(Launch::default());
        chattr("-i", &f.out);
        out.row("output folder immutable", &[t], "—")?;
        let _ = chattr("+i", &f.dir);
        let t = f.run_new(Launch::default());
        chattr("-i", &f.dir);
        out.row("parent folder immutable", &[t], "—")?;
        let file = f.out.join("summary.toml");
        chattr("+i", &file);
        let t = f.run_new(Launch::default());
        // The immutable file left with the earlier set, into the staging
        // folder beside the target: release it there.
        for entry in atomic::staging_entries(&f.out) {
            chattr("-i", &entry.join("summary.toml"));
        }
        chattr("-i", &file);
        let next = f.run_new(Launch::default());
        let next = format!(
            "exit {}, staging left {}",
            next.outcome.status(),
            next.staging
        );
        out.row("one earlier file immutable", &[t], &next)?;
        f.reset();
    } else {
        out.table.push(vec![
            "unwritable locations (chattr unavailable: not root on ext4)".into(),
            0.into(),
            "".into(),
            "".into(),
            0.into(),
            "".into(),
        ])?;
    }

    // SIGKILL at evenly spaced moments, on past the planned span until a
    // run ends before its kill (at most three times as many moments).
    let step = f.seconds * KILL_SPAN / (KILLS - 1) as f64;
    let mut trials = Vec::new();
    for k in 0..3 * KILLS {
        let t = f.run_new(Launch {
            signal: Some((libc::SIGKILL, step * k as f64)),
            ..Launch::default()
        });
        let (ended, left) = (t.outcome.code == Some(0), t.staging > 0);
        trials.push(t);
        f.reset();
        if left {
            out.kills_left += 1;
            out.kills_cleaned += usize::from(atomic::staging_entries(&f.out).is_empty());
        }
        out.kill_span = step * k as f64 / f.seconds;
        if k + 1 >= KILLS && ended {
            break;
        }
    }
    out.kills = trials.len();
    let next = format!(
        "staging removed {} of {}",
        out.kills_cleaned, out.kills_left
    );
    out.row(
        &format!("SIGKILL at {} moments, parse to past the end", out.kills),
        &trials,
        &next,
    )?;

    // SIGINT and SIGTERM.
    for (sig, name) in [(libc::SIGINT, "SIGINT"), (libc::SIGTERM, "SIGTERM")] {
        let mut trials = Vec::new();
        for k in 1..=SIGNAL_MOMENTS {
            trials.push(f.run_new(Launch {
                signal: Some((sig, f.seconds * k as f64 / SIGNAL_MOMENTS as f64)),
                ..Launch::default()
            }));
            f.reset();
        }
        out.row(&format!("{name} at {SIGNAL_MOMENTS} moments"), &trials, "—")?;
    }

    // Two different scenes into one folder at once.
    let small = Fixture::new(work, "concurrent", 8, 2);
    let mut trials = Vec::new();
    for _ in 0..CONCURRENT_ROUNDS {
        let a = std::thread::spawn({
            let dir = small.dir.clone();
            move || {
                launch(
                    &dir,
                    &["run", "old.toml", "--out", "out"],
                    Launch::default(),
                )
            }
        });
        let b = launch(
            &small.dir,
            &["run", "new.toml", "--out", "out"],
            Launch::default(),
        );
        let a = a.join().expect("the first run returns");
        trials.push(small.trial(if a.code == Some(0) { b } else { a }));
    }
    out.row("two scenes at once into one folder", &trials, "—")?;
    Ok(out)
}

/// `name` size, … for the fixture's files.
pub fn describe(files: &[(String, usize)]) -> String {
    files
        .iter()
        .map(|(n, b)| format!("`{n}` {}", human_bytes(*b as f64)))
        .collect::<Vec<_>>()
        .join(", ")
}
