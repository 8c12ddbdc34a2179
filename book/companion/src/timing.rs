//! Timing for the chapters that report time: the median of repeated runs,
//! the machine they ran on, and a run's outputs with their times taken out.
//! Times vary from run to run on a shared machine; the book quotes only
//! ratios of times measured in one run.

use crate::facts::Facts;
use iga_contact::Result;
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
            memory: iga_contact::resources::meminfo_total(),
            load,
        }
    }

    /// Records the machine as facts `<prefix>date`, `<prefix>cpu`,
    /// `<prefix>cores`, `<prefix>memory` and `<prefix>load`, all marked as
    /// varying from run to run.
    pub fn record(&self, facts: &mut Facts, prefix: &str) -> Result<()> {
        let memory = self.memory.map_or("unknown".into(), |b| {
            iga_contact::resources::human_bytes(b as f64)
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

/// The files of a finished run's output folder ([`iga_contact::report::atomic::snapshot`])
/// with what differs between two runs of one scene taken out: the
/// `[timing]` table of `summary.toml`, and the byte counts of the manifest
/// (which follow that file's length). What is left is the answer, which two
/// runs must write byte for byte alike.
pub fn untimed_snapshot(
    dir: &std::path::Path,
) -> std::io::Result<std::collections::BTreeMap<String, Vec<u8>>> {
    use iga_contact::report::atomic;
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
    fn dates_of_known_instants() {
        let at = |s: u64| utc_date(UNIX_EPOCH + Duration::from_secs(s));
        assert_eq!(at(0), "1970-01-01");
        assert_eq!(at(951_782_400), "2000-02-29"); // a leap day of a 400-year
        assert_eq!(at(1_709_164_800), "2024-02-29");
        assert_eq!(at(1_735_689_599), "2024-12-31"); // the last second of 2024
        assert_eq!(at(4_107_542_400), "2100-03-01"); // 2100 is no leap year
    }
}
