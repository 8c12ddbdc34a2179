//! The transcripts of the chapter "Scene files and the command line": the
//! `iga-contact` binary of this build, run on the shipped scenes and on
//! copies of `hertz.toml` with one edit each, its output recorded as a
//! reader sees it, and the tables the chapter shows about the scenes.
//!
//! Everything written is a function of the code: wall times in the output
//! are masked (`…`), paths are relative to a scratch folder laid out like
//! the repository. Output: `book/src/generated/scenes/`.
//!
//! `cargo build --release && cargo run --release --example scenes` (the
//! binary must be built first: `cargo run --example` builds only examples).

use companion::chapter::{cli_binary, Chapter, Cost, PROGRAMS};
use companion::Facts;
use iga_contact::report::table::{Column, Format, Table};
use iga_contact::resources::{ADDRESS_SPACE_SHARE, PHYSICAL_SHARE};
use iga_contact::scene::{self, OutputSpec};
use iga_contact::{Error, Result};
use std::path::{Path, PathBuf};
use std::process::Command;

/// A scratch folder with `data/scenes/` copied in, where the binary runs.
struct Shell {
    bin: PathBuf,
    dir: PathBuf,
}

impl Shell {
    fn new() -> Result<Self> {
        let dir = std::env::temp_dir().join(format!("scenes-chapter-{}", std::process::id()));
        let scenes = dir.join("data/scenes");
        let io = |path: &Path| {
            let path = path.display().to_string();
            move |source| Error::Io { path, source }
        };
        std::fs::create_dir_all(&scenes).map_err(io(&scenes))?;
        for file in shipped()? {
            let to = scenes.join(&file);
            std::fs::copy(companion::shipped_path(&file), &to).map_err(io(&to))?;
        }
        Ok(Self {
            bin: cli_binary()?,
            dir,
        })
    }

    /// Writes `name` in the scratch folder: `hertz.toml` with `from`
    /// replaced by `to` (which must occur).
    fn edited(&self, name: &str, from: &str, to: &str) -> Result<()> {
        let text =
            std::fs::read_to_string(companion::shipped_path("hertz.toml")).map_err(|source| {
                Error::Io {
                    path: "hertz.toml".into(),
                    source,
                }
            })?;
        if !text.contains(from) {
            return Err(Error::invalid("edit", from, "not found in hertz.toml"));
        }
        let path = self.dir.join(name);
        std::fs::write(&path, text.replacen(from, to, 1)).map_err(|source| Error::Io {
            path: path.display().to_string(),
            source,
        })
    }

    /// Runs `iga-contact ARGS` and appends the exchange to `log`: the
    /// command, what it printed (times masked), and a non-zero exit code.
    fn run(&self, log: &mut String, comment: &str, args: &[&str]) -> Result<i32> {
        let out = Command::new(&self.bin)
            .args(args)
            .current_dir(&self.dir)
            .output()
            .map_err(|source| Error::Io {
                path: self.bin.display().to_string(),
                source,
            })?;
        if !comment.is_empty() {
            log.push_str(&format!("# {comment}\n"));
        }
        log.push_str(&format!("$ iga-contact {}\n", args.join(" ")));
        for stream in [&out.stdout, &out.stderr] {
            for line in String::from_utf8_lossy(stream).lines() {
                log.push_str(&mask_seconds(line));
                log.push('\n');
            }
        }
        let code = out.status.code().unwrap_or(-1);
        if code != 0 {
            log.push_str(&format!("# exit code {code}\n"));
        }
        log.push('\n');
        Ok(code)
    }
}

impl Drop for Shell {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// `0.02 s` → `… s`: the wall times the CLI prints vary from run to run.
fn mask_seconds(line: &str) -> String {
    let words: Vec<&str> = line.split(' ').collect();
    let mut out = Vec::with_capacity(words.len());
    for (k, w) in words.iter().enumerate() {
        let seconds_follow = words
            .get(k + 1)
            .is_some_and(|n| n.trim_end_matches([';', ',', ')']) == "s");
        if seconds_follow && w.contains('.') && w.parse::<f64>().is_ok() {
            out.push("…");
        } else {
            out.push(w);
        }
    }
    out.join(" ")
}

/// The shipped scene files, sorted.
fn shipped() -> Result<Vec<String>> {
    let dir = companion::shipped_path("");
    let mut files: Vec<String> = std::fs::read_dir(&dir)
        .map_err(|source| Error::Io {
            path: dir.display().to_string(),
            source,
        })?
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".toml"))
        .collect();
    files.sort();
    Ok(files)
}

/// Every `[output]` key, with the file it makes.
fn output_files() -> Result<Vec<(&'static str, &'static str)>> {
    let keys = [
        "iterations",
        "pressure_profile",
        "summary",
        "vtu",
        "figures",
    ];
    keys.iter()
        .map(|&key| {
            let spec: OutputSpec = toml::from_str(&format!("{key} = true"))
                .map_err(|e| Error::invalid("output", key, e.to_string()))?;
            match spec.file_names()[..] {
                [file] => Ok((key, file)),
                _ => Err(Error::invalid("output", key, "not exactly one file")),
            }
        })
        .collect()
}

/// The chapter "Scene files and the command line", section by section.
fn main() -> Result<()> {
    let mut chapter = Chapter::from_args("scenes")?;
    let shell = Shell::new()?;

    // The shipped scenes: their table.
    chapter.table("shipped", &shipped_table()?)?;

    // The command line: its help, and the shipped scenes checked and run.
    chapter.text("help.txt", &help(&shell)?)?;
    chapter.text("runs.txt", &runs(&shell)?)?;

    // Outputs: lean scenes: what the Hertz run wrote, and its summary. The
    // summary holds the run's seconds per phase (`[timing]`), and so its
    // size and text vary from run to run.
    chapter.table("outputs", &outputs_table(&shell)?)?;
    for f in ["outputs.csv", "outputs.md", "hertz_summary.toml"] {
        chapter.timed(f);
    }
    chapter.text("hertz_summary.toml", &hertz_summary(&shell)?)?;

    // Validation and error messages: the transcript of the edited scenes.
    chapter.text("errors.txt", &errors(&shell)?)?;

    // The command line: the programs `reproduce` runs, the memory budget.
    chapter.table("programs", &programs_table()?)?;
    record_memory_facts(chapter.facts())?;
    chapter.finish()
}

// ANCHOR: shipped
/// "The shipped scenes": what each describes and asks for.
fn shipped_table() -> Result<Table> {
    let mut table = Table::new(vec![
        Column::plain("file", "file"),
        Column::plain("title", "title"),
        Column::plain("bodies", "bodies"),
        Column::plain("dofs", "DOFs"),
        Column::plain("outputs", "outputs"),
    ]);
    for file in shipped()? {
        let scene = companion::shipped(&file)?;
        let outputs = scene.output.file_names();
        table.push(vec![
            format!("`{file}`").into(),
            scene
                .title
                .clone()
                .unwrap_or_else(|| "(none)".into())
                .into(),
            scene.bodies.len().into(),
            scene.build()?.n().into(),
            if outputs.is_empty() {
                "none".into()
            } else {
                outputs.len().to_string().into()
            },
        ])?;
    }
    Ok(table)
}
// ANCHOR_END: shipped

/// "The command line": the command line's own help.
fn help(shell: &Shell) -> Result<String> {
    let mut log = String::new();
    for args in [&["--help"][..], &["run", "--help"], &["check", "--help"]] {
        shell.run(&mut log, "", args)?;
    }
    Ok(log)
}

// ANCHOR: runs
/// "The command line": checking and running the shipped scenes (the Hertz
/// run writes the folder `outputs_table` measures).
fn runs(shell: &Shell) -> Result<String> {
    let mut log = String::new();
    shell.run(&mut log, "", &["check", "data/scenes/hertz.toml"])?;
    shell.run(&mut log, "", &["run", "data/scenes/hertz.toml"])?;
    shell.run(
        &mut log,
        "no [output] table: nothing is written",
        &["run", "data/scenes/minimal.toml"],
    )?;
    shell.run(
        &mut log,
        "",
        &["run", "data/scenes/taylor.toml", "--out", "results/taylor"],
    )?;
    Ok(log)
}
// ANCHOR_END: runs

/// "Outputs: lean scenes": what the Hertz run wrote, every output key, its
/// file and its size.
fn outputs_table(shell: &Shell) -> Result<Table> {
    let out = shell.dir.join("out/hertz");
    let mut table = Table::new(vec![
        Column::plain("key", "key"),
        Column::plain("file", "file"),
        Column::plain("bytes", "bytes (hertz.toml)"),
    ]);
    for (key, file) in output_files()? {
        let size = std::fs::metadata(out.join(file)).map_err(|source| Error::Io {
            path: format!("out/hertz/{file}"),
            source,
        })?;
        table.push(vec![
            format!("`{key}`").into(),
            format!("`{file}`").into(),
            (size.len() as usize).into(),
        ])?;
    }
    Ok(table)
}

/// "Outputs: lean scenes": the summary the Hertz run wrote.
fn hertz_summary(shell: &Shell) -> Result<String> {
    let out = shell.dir.join("out/hertz");
    std::fs::read_to_string(out.join(scene::files::SUMMARY)).map_err(|source| Error::Io {
        path: "out/hertz/summary.toml".into(),
        source,
    })
}

// ANCHOR: errors
/// "Validation and error messages": copies of hertz.toml with one edit
/// each, and what the binary says.
fn errors(shell: &Shell) -> Result<String> {
    let edits: [(&str, &str, &str, &str); 9] = [
        (
            "young.toml",
            "young = -2.0e7",
            "young = 2.0e7",
            "young = -2.0e7",
        ),
        (
            "typo.toml",
            "a misspelt key: nu for poisson",
            "poisson = 0.1",
            "nu = 0.1",
        ),
        (
            "elements.toml",
            "elements = [8, 0]",
            "elements = [8, 8]",
            "elements = [8, 0]",
        ),
        (
            "brace.toml",
            "a missing closing brace",
            "elements = [8, 8] }",
            "elements = [8, 8]",
        ),
        ("theta.toml", "theta = 0.5", "theta = 0,", "theta = 0.5,"),
        (
            "body.toml",
            "a support of a body that does not exist",
            "body = \"disk\"\nside",
            "body = \"disc\"\nside",
        ),
        (
            "slide.toml",
            "the support holding y instead of x: the disk can slide",
            "component = \"x\"\nvalue = 0.0\n",
            "component = \"y\"\nvalue = 0.0\n",
        ),
        (
            "quadrature.toml",
            "quadrature = 1",
            "plane = \"strain\" }",
            "plane = \"strain\" }\nquadrature = 1",
        ),
        (
            "max_iter.toml",
            "max_iter = 5: valid, but the solver stops",
            "max_iter = 300",
            "max_iter = 5",
        ),
    ];
    let mut log = String::new();
    for (file, what, from, to) in edits {
        shell.edited(file, from, to)?;
        let command = if file == "max_iter.toml" {
            "run"
        } else {
            "check"
        };
        shell.run(
            &mut log,
            &format!("hertz.toml with {what}"),
            &[command, file],
        )?;
    }
    shell.run(
        &mut log,
        "a memory budget the run does not fit",
        &["check", "data/scenes/hertz.toml", "--max-memory", "10M"],
    )?;
    shell.run(
        &mut log,
        "an output folder that is a file: refused before the solve",
        &[
            "run",
            "data/scenes/hertz.toml",
            "--out",
            "data/scenes/minimal.toml",
        ],
    )?;
    shell.run(&mut log, "", &["check", "no_such_scene.toml"])?;
    Ok(log)
}
// ANCHOR_END: errors

/// "The command line": the chapter programs `reproduce` runs.
fn programs_table() -> Result<Table> {
    let mut table = Table::new(vec![
        Column::plain("example", "program"),
        Column::plain("chapter", "writes"),
        Column::plain("cost", "run by"),
    ]);
    for p in PROGRAMS {
        table.push(vec![
            format!("`{}`", p.example).into(),
            format!("`generated/{}/`", p.chapter).into(),
            match p.cost {
                Cost::Quick => "`reproduce`, the tests",
                Cost::Heavy => "`reproduce --all`",
            }
            .into(),
        ])?;
    }
    Ok(table)
}

/// "The command line" quotes the default memory budget, which
/// `--max-memory` overrides.
fn record_memory_facts(f: &mut Facts) -> Result<()> {
    f.number("physical_share", PHYSICAL_SHARE, Format::Percent(0))?;
    f.number(
        "address_space_share",
        ADDRESS_SPACE_SHARE,
        Format::Percent(0),
    )
}
