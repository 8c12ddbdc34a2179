//! Each case given to `check` and `run` as a child process, and each answer
//! judged against its reference: p₀ within [`WRONG`] of it and the contact
//! force balancing the load to [`BALANCE`]. An answer outside that is
//! wrong; a wrong answer on exit 0 must carry a warning.

use crate::cases::{cases, Balance, Case, Class};
use crate::harness::{launch, Launch, Outcome};
use iga_contact::Result;
use std::path::Path;

/// The address-space limit of every launch, as in the reliability campaign.
pub const LIMIT: u64 = 8 << 30;
/// Seconds a launch may take before it is stopped.
pub const TIMEOUT: f64 = 30.0;
/// p₀ more than this fraction off its reference is a wrong answer.
pub const WRONG: f64 = 0.05;
/// The contact force balancing the load worse than this (relative) is a
/// wrong answer.
pub const BALANCE: f64 = 1e-8;

/// What a launch of `run` came to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Verdict {
    /// Exit 0, p₀ and the balance right.
    Right,
    /// Exit 0, wrong, with a warning on the report line.
    WarnedWrong,
    /// Exit 0, right, with a warning (a cautious warning).
    WarnedRight,
    /// Exit 0, wrong, and nothing said: the defect this campaign hunts.
    SilentWrong,
    /// Exit 1 with one error line (a failed solve, reported).
    Failed,
    /// Exit 2 with one error line (refused).
    Refused,
    /// Anything else: a signal, a backtrace, another exit code.
    Unclean,
}

impl Verdict {
    pub const ALL: [Verdict; 7] = [
        Verdict::Right,
        Verdict::WarnedRight,
        Verdict::WarnedWrong,
        Verdict::SilentWrong,
        Verdict::Failed,
        Verdict::Refused,
        Verdict::Unclean,
    ];

    pub fn label(self) -> &'static str {
        match self {
            Verdict::Right => "right",
            Verdict::WarnedRight => "right, warned",
            Verdict::WarnedWrong => "wrong, warned",
            Verdict::SilentWrong => "wrong, silent",
            Verdict::Failed => "failed (exit 1)",
            Verdict::Refused => "refused (exit 2)",
            Verdict::Unclean => "unclean",
        }
    }
}

/// What a `summary.toml` says of the first pair.
struct PairSummary {
    p0: f64,
    /// The relative imbalance in y of the contact force against the
    /// applied load on the slave and on the master.
    imbalance: [f64; 2],
}

/// p₀ of the first pair and the relative imbalance in y of the contact
/// force against the applied load on the slave and on the master, from a
/// `summary.toml`.
fn read_summary(path: &Path) -> Option<PairSummary> {
    let text = std::fs::read_to_string(path).ok()?;
    let v: toml::Value = toml::from_str(&text).ok()?;
    let pair = v.get("contact")?.as_array()?.first()?;
    // absent where the profile finds no zone: no peak was measured, which
    // is as far from the reference as a peak of zero
    let p0 = pair.get("p0").map_or(Some(0.0), toml::Value::as_float)?;
    let vec2 = |key: &str| -> Option<[f64; 2]> {
        let a = v.get(key)?.as_array()?;
        Some([a.first()?.as_float()?, a.get(1)?.as_float()?])
    };
    let (c, a) = (vec2("contact_force")?, vec2("applied_force")?);
    let size = a[1].abs().max(f64::MIN_POSITIVE);
    Some(PairSummary {
        p0,
        imbalance: [(c[1] + a[1]).abs() / size, (c[1] - a[1]).abs() / size],
    })
}

/// A verdict, and p₀ / reference − 1 (NaN without an answer).
struct Judged {
    verdict: Verdict,
    error: f64,
}

impl Judged {
    fn without_answer(verdict: Verdict) -> Self {
        Judged {
            verdict,
            error: f64::NAN,
        }
    }
}

/// The verdict on a `run` of `case` that wrote into `out`.
fn judge(case: &Case, o: &Outcome, out: &Path) -> Judged {
    if o.timed_out || !o.clean() {
        return Judged::without_answer(Verdict::Unclean);
    }
    match o.code {
        Some(0) => {}
        Some(1) => return Judged::without_answer(Verdict::Failed),
        _ => return Judged::without_answer(Verdict::Refused),
    }
    let warned = o.stdout.contains("warning") || o.stderr.contains("warning: ");
    let Some(summary) = read_summary(&out.join("summary.toml")) else {
        return Judged::without_answer(Verdict::Unclean);
    };
    let error = summary.p0 / case.p0 - 1.0;
    let imbalance = match case.balance {
        Balance::None => 0.0,
        Balance::LoadOnSlave => summary.imbalance[0],
        Balance::LoadOnMaster => summary.imbalance[1],
    };
    let right = error.abs() <= WRONG && imbalance <= BALANCE;
    let verdict = match (right, warned) {
        (true, false) => Verdict::Right,
        (true, true) => Verdict::WarnedRight,
        (false, true) => Verdict::WarnedWrong,
        (false, false) => Verdict::SilentWrong,
    };
    Judged { verdict, error }
}

/// One case's result.
pub struct Answer {
    pub class: Class,
    pub label: String,
    pub verdict: Verdict,
    /// p₀ / reference − 1 (NaN without an answer).
    pub error: f64,
    pub iterations: Option<i64>,
    /// The report line (exit 0) or the error line.
    pub message: String,
    /// Peak resident memory of the `run`, bytes.
    pub peak_bytes: f64,
}

/// Every answer of the campaign, and the number of launches it took.
pub struct Answers {
    pub answers: Vec<Answer>,
    pub launches: usize,
}

/// Runs every case through `check` and `run` in `work`.
pub fn run(work: &Path) -> Result<Answers> {
    let how = Launch {
        address_space: Some(LIMIT),
        timeout: TIMEOUT,
        ..Launch::default()
    };
    let mut answers = Vec::new();
    let mut launches = 0;
    for (k, case) in cases()?.into_iter().enumerate() {
        let name = format!("a{k}.toml");
        std::fs::write(work.join(&name), &case.scene).expect("the work folder takes a scene");
        let c = launch(work, &["check", &name], how);
        launches += 1;
        let out = work.join(format!("a{k}-out"));
        let r = launch(
            work,
            &["run", &name, "--out", &out.display().to_string()],
            how,
        );
        launches += 1;
        let Judged { mut verdict, error } = judge(&case, &r, &out);
        if !c.clean() || c.timed_out {
            verdict = Verdict::Unclean;
        }
        let iterations = std::fs::read_to_string(out.join("summary.toml"))
            .ok()
            .and_then(|t| toml::from_str::<toml::Value>(&t).ok())
            .and_then(|v| v.get("iterations").and_then(|i| i.as_integer()));
        let message = if r.code == Some(0) {
            r.stdout.trim().to_string()
        } else {
            r.message()
        };
        answers.push(Answer {
            class: case.class,
            label: case.label,
            verdict,
            error,
            iterations,
            message,
            peak_bytes: r.peak_bytes,
        });
        let _ = std::fs::remove_dir_all(&out);
        let _ = std::fs::remove_file(work.join(&name));
    }
    Ok(Answers { answers, launches })
}
