//! Wall-clock timing of whole computations, for the chapters that report
//! time. Times vary from run to run on a shared machine; the book quotes
//! only ratios of times measured in one run.

use crate::error::Result;
use serde::Serialize;
use std::time::Instant;

/// A value and how long it took to compute.
#[derive(Clone, Debug)]
pub struct Timed<T> {
    /// The value of the last repeat.
    pub value: T,
    /// The median wall time of the repeats, in seconds.
    pub seconds: f64,
    pub repeats: usize,
}

/// Runs `f` `repeats` times (at least once) and keeps the median time; the
/// first error stops the repeats and is returned.
pub fn median_time<T>(repeats: usize, mut f: impl FnMut() -> Result<T>) -> Result<Timed<T>> {
    let mut times = Vec::with_capacity(repeats.max(1));
    let mut value = None;
    for _ in 0..repeats.max(1) {
        let t = Instant::now();
        value = Some(f()?);
        times.push(t.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    Ok(Timed {
        value: value.expect("at least one repeat"),
        seconds: times[times.len() / 2],
        repeats: times.len(),
    })
}

/// The phases of a run of a scene, in the order they happen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Phase {
    /// Reading and validating the scene, the memory estimate, the output
    /// folder check, the refinement of every body and the DOF numbering.
    ParseAndBuild,
    /// The contact points (projection, gap, penalty, and the trace-inverse
    /// constant of every slave element) and the rigid-mode check on them.
    ContactSetup,
    /// The bulk stiffness and the loads.
    Assembly,
    /// The factorisation of the bulk before the iterations and its
    /// condensation on the contact layer (0 when the solver factorises a
    /// kernel per iteration instead: that time is in the iterations).
    Factorisation,
    /// The rest of the solve: the iterations, the recovery of the body from
    /// the layer, and the solver's checks before and after.
    Iterations,
    /// What the outputs are computed from: resultants, active set,
    /// penalty stability, the dense pressure profile and its measures.
    PostProcessing,
    /// Drawing, formatting and staging the output files.
    Output,
}

/// Wall time of each [`Phase`] of one run and of the whole run, in
/// seconds: the `[timing]` table of `summary.toml`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct PhaseTimes {
    pub parse_and_build: f64,
    pub contact_setup: f64,
    pub assembly: f64,
    pub factorisation: f64,
    pub iterations: f64,
    pub post_processing: f64,
    pub output: f64,
    /// From the start of the [`Stopwatch`] to the moment the times were
    /// read, measured on its own clock (not summed from the phases).
    pub wall: f64,
}

impl PhaseTimes {
    /// The sum of the phases, to compare with [`PhaseTimes::wall`].
    pub fn sum(&self) -> f64 {
        self.parts().iter().map(|(_, s)| s).sum()
    }

    /// The phases in the order they happen, each with its key in the
    /// `[timing]` table of `summary.toml`.
    pub fn parts(&self) -> [(&'static str, f64); 7] {
        [
            ("parse_and_build", self.parse_and_build),
            ("contact_setup", self.contact_setup),
            ("assembly", self.assembly),
            ("factorisation", self.factorisation),
            ("iterations", self.iterations),
            ("post_processing", self.post_processing),
            ("output", self.output),
        ]
    }

    /// The times of a `[timing]` table read back (e.g. from a
    /// `summary.toml`): `get` gives the value of a key, `None` when it is
    /// missing, and the first missing key is returned as the error.
    pub fn from_keys(
        mut get: impl FnMut(&str) -> Option<f64>,
    ) -> std::result::Result<Self, &'static str> {
        let mut t = Self::default();
        for (key, _) in Self::default().parts() {
            let v = get(key).ok_or(key)?;
            *t.slot_of(key).expect("a key of parts") = v;
        }
        t.wall = get("wall").ok_or("wall")?;
        Ok(t)
    }

    fn slot_of(&mut self, key: &str) -> Option<&mut f64> {
        Some(match key {
            "parse_and_build" => &mut self.parse_and_build,
            "contact_setup" => &mut self.contact_setup,
            "assembly" => &mut self.assembly,
            "factorisation" => &mut self.factorisation,
            "iterations" => &mut self.iterations,
            "post_processing" => &mut self.post_processing,
            "output" => &mut self.output,
            "wall" => &mut self.wall,
            _ => return None,
        })
    }

    fn slot(&mut self, phase: Phase) -> &mut f64 {
        match phase {
            Phase::ParseAndBuild => &mut self.parse_and_build,
            Phase::ContactSetup => &mut self.contact_setup,
            Phase::Assembly => &mut self.assembly,
            Phase::Factorisation => &mut self.factorisation,
            Phase::Iterations => &mut self.iterations,
            Phase::PostProcessing => &mut self.post_processing,
            Phase::Output => &mut self.output,
        }
    }
}

/// Charges wall time to the phases of a run: every interval between two
/// laps goes to exactly one phase, so the phases cover the run without gap
/// or overlap.
#[derive(Clone, Debug)]
pub struct Stopwatch {
    start: Instant,
    last: Instant,
    times: PhaseTimes,
}

impl Stopwatch {
    /// Starts the run's clock now (the command line starts it before it
    /// reads the scene).
    pub fn start() -> Self {
        let now = Instant::now();
        Self {
            start: now,
            last: now,
            times: PhaseTimes::default(),
        }
    }

    /// The seconds since the last lap, which then starts anew; the caller
    /// charges them (possibly split) with [`Stopwatch::charge`].
    pub fn take(&mut self) -> f64 {
        let now = Instant::now();
        let s = now.duration_since(self.last).as_secs_f64();
        self.last = now;
        s
    }

    /// Adds `seconds` to `phase`.
    pub fn charge(&mut self, phase: Phase, seconds: f64) {
        *self.times.slot(phase) += seconds;
    }

    /// Charges the time since the last lap to `phase`.
    pub fn lap(&mut self, phase: Phase) {
        let s = self.take();
        self.charge(phase, s);
    }

    /// The times so far, with the wall time up to now.
    pub fn times(&self) -> PhaseTimes {
        PhaseTimes {
            wall: self.start.elapsed().as_secs_f64(),
            ..self.times
        }
    }
}

/// When and on what a measurement ran: what a chapter states about results
/// that the tests do not regenerate (the heavy programs), and what any
/// timing needs beside it.
#[derive(Clone, Debug, PartialEq)]
pub struct Machine {
    /// The UTC date, `YYYY-MM-DD`.
    pub date: String,
    /// The processor's model name (`/proc/cpuinfo`), or "unknown".
    pub cpu: String,
    /// Threads this process may run on.
    pub cores: usize,
    /// Physical memory in bytes (`/proc/meminfo`), if known.
    pub memory: Option<u64>,
    /// The 1-minute load average (`/proc/loadavg`): other processes
    /// competing for the cores while the figures were taken.
    pub load: Option<f64>,
}

impl Machine {
    /// This machine, now.
    pub fn here() -> Self {
        let cpu = std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|t| {
                t.lines()
                    .find(|l| l.starts_with("model name"))
                    .and_then(|l| l.split_once(':'))
                    .map(|(_, v)| v.split_whitespace().collect::<Vec<_>>().join(" "))
            })
            .unwrap_or_else(|| "unknown".into());
        let load = std::fs::read_to_string("/proc/loadavg")
            .ok()
            .and_then(|t| t.split_whitespace().next()?.parse().ok());
        Self {
            date: utc_date(std::time::SystemTime::now()),
            cpu,
            cores: std::thread::available_parallelism().map_or(1, |n| n.get()),
            memory: crate::resources::meminfo_total(),
            load,
        }
    }

    /// Records the machine as facts `<prefix>date`, `<prefix>cpu`,
    /// `<prefix>cores`, `<prefix>memory` and `<prefix>load`, all marked as
    /// varying from run to run.
    pub fn record(&self, facts: &mut crate::report::facts::Facts, prefix: &str) -> Result<()> {
        let memory = self.memory.map_or("unknown".into(), |b| {
            crate::resources::human_bytes(b as f64)
        });
        let load = self.load.map_or("unknown".into(), |l| format!("{l:.1}"));
        facts.timed_text(&format!("{prefix}date"), &self.date)?;
        facts.timed_text(&format!("{prefix}cpu"), &self.cpu)?;
        facts.timed_text(&format!("{prefix}cores"), self.cores.to_string())?;
        facts.timed_text(&format!("{prefix}memory"), memory)?;
        facts.timed_text(&format!("{prefix}load"), load)
    }
}

/// The UTC calendar date of `t` (proleptic Gregorian; days from civil,
/// H. Hinnant's algorithm), so that no date crate is needed for one line.
pub fn utc_date(t: std::time::SystemTime) -> String {
    let secs = t
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs()) as i64;
    let z = secs.div_euclid(86_400) + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!("{year:04}-{month:02}-{day:02}")
}

/// The files of a finished run's output folder ([`crate::report::atomic::snapshot`])
/// with what differs between two runs of one scene taken out: the
/// `[timing]` table of `summary.toml`, and the byte counts of the manifest
/// (which follow that file's length). What is left is the answer, which two
/// runs must write byte for byte alike.
pub fn untimed_snapshot(
    dir: &std::path::Path,
) -> std::io::Result<std::collections::BTreeMap<String, Vec<u8>>> {
    use crate::report::atomic;
    let mut files = atomic::snapshot(dir)?;
    for (name, bytes) in files.iter_mut() {
        let text = String::from_utf8_lossy(bytes).into_owned();
        let kept: Vec<&str> = match name.as_str() {
            "summary.toml" => {
                let mut in_timing = false;
                text.lines()
                    .filter(|l| {
                        if l.starts_with('[') {
                            in_timing = l.trim() == "[timing]";
                        }
                        !in_timing
                    })
                    .collect()
            }
            atomic::MANIFEST => text
                .lines()
                .filter(|l| !l.starts_with("bytes = "))
                .collect(),
            _ => continue,
        };
        *bytes = kept.join("\n").into_bytes();
    }
    Ok(files)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::{Duration, UNIX_EPOCH};

    #[test]
    fn the_phases_cover_the_wall_time() {
        let mut clock = Stopwatch::start();
        let busy = |ms: u64| std::thread::sleep(Duration::from_millis(ms));
        busy(20);
        clock.lap(Phase::ParseAndBuild);
        busy(10);
        let solve = clock.take();
        clock.charge(Phase::Factorisation, 0.25 * solve);
        clock.charge(Phase::Iterations, 0.75 * solve);
        busy(5);
        clock.lap(Phase::Output);
        let t = clock.times();
        assert!(t.parse_and_build >= 0.020 && t.output >= 0.005, "{t:?}");
        assert_eq!(t.factorisation * 3.0, t.iterations);
        assert_eq!(t.contact_setup + t.assembly + t.post_processing, 0.0);
        // every interval is charged once: the sum misses only the time
        // between the last lap and the reading of the wall clock (two
        // statements; the margin is for a descheduled thread)
        assert!(t.sum() <= t.wall && t.wall - t.sum() < 0.1, "{t:?}");
        assert!(t.sum() >= 0.035, "{t:?}");
    }

    /// The keys of `parts` are the fields serialised into `[timing]`,
    /// and reading them back gives the same times.
    #[test]
    fn timing_keys_round_trip() {
        let t = PhaseTimes {
            parse_and_build: 1.0,
            contact_setup: 2.0,
            assembly: 3.0,
            factorisation: 4.0,
            iterations: 5.0,
            post_processing: 6.0,
            output: 7.0,
            wall: 28.5,
        };
        let table: toml::Table = toml::from_str(&toml::to_string(&t).unwrap()).unwrap();
        let back = PhaseTimes::from_keys(|k| table.get(k)?.as_float()).unwrap();
        assert_eq!(back, t);
        assert_eq!(t.sum(), 28.0);
        assert_eq!(table.len(), t.parts().len() + 1);
        let missing = PhaseTimes::from_keys(|k| (k != "output").then_some(1.0));
        assert_eq!(missing, Err("output"));
    }

    #[test]
    fn dates_of_known_instants() {
        let at = |s: u64| utc_date(UNIX_EPOCH + Duration::from_secs(s));
        assert_eq!(at(0), "1970-01-01");
        assert_eq!(at(951_782_400), "2000-02-29"); // a leap day of a 400-year
        assert_eq!(at(1_709_164_800), "2024-02-29");
        assert_eq!(at(1_735_689_599), "2024-12-31"); // the last second of 2024
        assert_eq!(at(4_107_542_400), "2100-03-01"); // 2100 is no leap year
    }
}
