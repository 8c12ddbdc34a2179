//! The generated folder of one book chapter, `book/src/generated/<name>/`:
//! what a chapter program writes — tables (CSV + Markdown), texts, figures
//! and the facts its prose quotes.

use crate::facts::{self, Facts};
use iga_contact::report::atomic::{install_signal_cleanup, OutputSet};
use iga_contact::report::table::Table;
use iga_contact::{Error, Result};
use std::path::{Path, PathBuf};

/// The root of the source tree this crate was built from (the workspace:
/// `book/companion/` is two levels down), where the chapter programs read
/// the shipped scenes and write the book's generated folders.
pub fn source_root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .ancestors()
        .nth(2)
        .expect("book/companion sits two levels below the workspace root")
}

/// The book's generated folders, `book/src/generated/` of the source tree.
pub fn generated_root() -> PathBuf {
    source_root().join("book/src/generated")
}

/// The `iga-contact` binary of this build, for chapter programs that show
/// or probe the command line: `target/<profile>/iga-contact`, beside the
/// folder of the running example. Refused when it is missing, or older than
/// a source file of the library or the binary — it would then not be the
/// code the chapter describes (`cargo run --example` builds the examples,
/// not the binary).
pub fn cli_binary() -> Result<PathBuf> {
    let io = |path: &Path| {
        let path = path.display().to_string();
        move |source| Error::Io { path, source }
    };
    let exe = std::env::current_exe().map_err(io(Path::new("the running program")))?;
    let bin = exe
        .parent()
        .and_then(Path::parent)
        .map(|d| d.join("iga-contact"))
        .ok_or_else(|| Error::invalid("iga-contact binary", exe.display(), "no target folder"))?;
    let built = std::fs::metadata(&bin)
        .and_then(|m| m.modified())
        .map_err(io(&bin))?;
    let root = source_root();
    let mut stack = vec![root.join("src"), root.join("Cargo.toml")];
    while let Some(path) = stack.pop() {
        let meta = std::fs::metadata(&path).map_err(io(&path))?;
        if meta.is_dir() {
            for entry in std::fs::read_dir(&path).map_err(io(&path))? {
                stack.push(entry.map_err(io(&path))?.path());
            }
        } else if meta.modified().map_err(io(&path))? > built {
            return Err(Error::invalid(
                "iga-contact binary",
                bin.display(),
                format!(
                    "older than {}: run `cargo build --release` first",
                    path.strip_prefix(root).unwrap_or(&path).display()
                ),
            ));
        }
    }
    Ok(bin)
}

/// How long a chapter program runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cost {
    /// Seconds to a minute: run by the main job, and run again by the tests,
    /// which compare its output with the committed files.
    Quick,
    /// Minutes and gigabytes (a scaling benchmark, a fault-injection
    /// campaign): run by `reproduce --all`; the book states when
    /// its committed results were measured.
    Heavy,
}

/// A chapter program: the Cargo example that regenerates the generated
/// folder `chapter` of the book.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Program {
    pub example: &'static str,
    pub chapter: &'static str,
    pub cost: Cost,
}

const fn program(example: &'static str, chapter: &'static str, cost: Cost) -> Program {
    Program {
        example,
        chapter,
        cost,
    }
}

/// Every chapter program, in the order `reproduce` runs them (a program
/// after those whose facts it reads).
pub const PROGRAMS: &[Program] = &[
    program("formulation", "formulation", Cost::Quick),
    program("lame", "lame", Cost::Quick),
    program("taylor", "taylor", Cost::Quick),
    program("hertz", "hertz", Cost::Quick),
    program("two_cylinders", "two_cylinders", Cost::Quick),
    program("pin_ring", "pin_ring", Cost::Quick),
    program("iga_vs_fem", "iga_vs_fem", Cost::Quick),
    program("error_vs_time", "error_vs_time", Cost::Quick),
    program("getfem_peer", "getfem_peer", Cost::Heavy),
    program("solvers", "solvers", Cost::Quick),
    program("solver_scaling", "solver_scaling", Cost::Heavy),
    program("penalty", "penalty", Cost::Quick),
    program("penalty_contrast", "penalty_contrast", Cost::Heavy),
    program("stability", "stability", Cost::Quick),
    program("incompressibility", "incompressibility", Cost::Quick),
    // reads the facts of taylor, hertz, iga_vs_fem and penalty
    program("claims", "claims", Cost::Quick),
    program("scenes", "scenes", Cost::Quick),
    program("reliability", "reliability", Cost::Heavy),
    program("answers", "answers", Cost::Heavy),
    program("memory_table", "memory_table", Cost::Heavy),
];

/// Where a chapter program writes, and the facts it collects on the way.
///
/// A chapter's outputs form one set ([`OutputSet`]): every file is staged
/// beside the target, and [`Chapter::finish`] swaps the whole set in. Until
/// then the earlier results stay as they were; a program that fails, or is
/// interrupted, leaves them untouched, and files that a program no longer
/// writes do not linger.
pub struct Chapter {
    set: OutputSet,
    facts: Facts,
    /// Files that hold wall-clock times (see [`Chapter::timed`]).
    timed: Vec<String>,
    /// A heavy chapter records the solver's fingerprint with its facts
    /// ([`crate::canary`]), so that a quick test can tell when its data fall
    /// behind the code.
    cost: Cost,
}

/// The name of the file that lists a chapter's timed outputs.
pub const TIMED: &str = "timed.toml";

/// What [`Chapter::finish`] records about the outputs: which files and
/// facts hold wall-clock times, and so differ from run to run. Everything
/// else a chapter program writes is a function of the code alone, and the
/// crate's tests compare it byte for byte with a fresh run.
#[derive(Clone, Debug, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Manifest {
    pub timed_files: Vec<String>,
    pub timed_facts: Vec<String>,
}

impl Manifest {
    /// Reads `<dir>/timed.toml`.
    pub fn load(dir: &Path) -> Result<Self> {
        let path = dir.join(TIMED);
        let text = std::fs::read_to_string(&path).map_err(|source| Error::Io {
            path: path.display().to_string(),
            source,
        })?;
        toml::from_str(&text)
            .map_err(|e| Error::invalid(path.display().to_string(), "timed outputs", e.to_string()))
    }
}

impl Chapter {
    /// The chapter `name`, written to `book/src/generated/<name>`, or to the
    /// directory given on the command line as `--out DIR`. Checks now that
    /// the folder can take the outputs (fail fast), and removes the staging
    /// of an interrupted run on SIGINT or SIGTERM.
    pub fn from_args(name: &str) -> Result<Self> {
        let mut args = std::env::args().skip(1);
        let mut dir = generated_root().join(name);
        while let Some(a) = args.next() {
            match a.as_str() {
                "--out" => {
                    dir = args
                        .next()
                        .map(PathBuf::from)
                        .ok_or_else(|| Error::invalid("--out", "", "needs a directory"))?;
                }
                other => {
                    return Err(Error::invalid(
                        "argument",
                        other,
                        "the only option is `--out DIR`",
                    ))
                }
            }
        }
        install_signal_cleanup()?;
        Self::at(dir)
    }

    /// A chapter written to `dir`.
    pub fn at(dir: impl Into<PathBuf>) -> Result<Self> {
        let dir = dir.into();
        // the book's folder of a heavy program, whoever writes it
        let cost = PROGRAMS
            .iter()
            .find(|p| generated_root().join(p.chapter) == dir)
            .map_or(Cost::Quick, |p| p.cost);
        Ok(Self {
            set: OutputSet::begin(dir)?,
            facts: Facts::new(),
            timed: Vec::new(),
            cost,
        })
    }

    /// The folder the chapter's files end up in.
    pub fn dir(&self) -> &Path {
        self.set.target()
    }

    /// The path an output file is written to now (in the staging folder),
    /// for figures drawn straight to disk.
    pub fn path(&self, file: &str) -> PathBuf {
        self.set.dir().join(file)
    }

    /// Writes `<stem>.csv` and `<stem>.md`.
    pub fn table(&mut self, stem: &str, table: &Table) -> Result<()> {
        self.csv(stem, table)?;
        self.text(&format!("{stem}.md"), &table.to_markdown())
    }

    /// Writes only `<stem>.csv` (for tables too long to read in the book).
    pub fn csv(&mut self, stem: &str, table: &Table) -> Result<()> {
        self.text(&format!("{stem}.csv"), &table.to_csv())
    }

    /// Writes a text file.
    pub fn text(&mut self, file: &str, text: &str) -> Result<()> {
        self.set.stage(file, text.as_bytes()).map(|_| ())
    }

    /// Marks `file` as holding wall-clock times: it changes from run to run.
    pub fn timed(&mut self, file: &str) {
        self.timed.push(file.to_string());
    }

    /// The facts the chapter's prose quotes.
    pub fn facts(&mut self) -> &mut Facts {
        &mut self.facts
    }

    /// Writes the facts and the list of timed outputs, and swaps the
    /// complete set of files in; a heavy chapter's facts gain the solver's
    /// fingerprint first.
    pub fn finish(mut self) -> Result<()> {
        if self.cost == Cost::Heavy {
            crate::canary::record(&mut self.facts)?;
        }
        let facts = self.facts.to_text();
        self.text(facts::FILE, &facts)?;
        let manifest = Manifest {
            timed_files: self.timed.clone(),
            timed_facts: self.facts.timed_keys().map(String::from).collect(),
        };
        let text = toml::to_string(&manifest)
            .map_err(|e| Error::invalid(TIMED, "timed outputs", e.to_string()))?;
        self.text(TIMED, &text)?;
        self.set.commit().map(|_| ())
    }
}
