//! Wall-clock timing of whole computations, for the chapters that report
//! time. Times vary from run to run on a shared machine; the book quotes
//! only ratios of times measured in one run.

use crate::error::Result;
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
