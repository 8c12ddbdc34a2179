//! The clocks and the memory of this process: peak resident memory, its
//! restart between phases, processor time; and how often a phase is timed.

/// Peak resident memory of this process (GB), from /proc/self/status:
/// the largest resident set since the start or since the last
/// [`reset_peak`].
pub fn peak_gb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        })
        .map_or(f64::NAN, |kb| kb / 1024.0 / 1024.0)
}

extern "C" {
    /// mimalloc's own: frees the pages it keeps for reuse back to the
    /// system (the chapter programs' allocator is mimalloc, linked statically).
    fn mi_collect(force: bool);
}

/// Returns the memory freed so far to the system and restarts the peak
/// (VmHWM) at the present resident set, so that the next phase's peak is
/// its own: the Cholesky's factor, freed but kept by the allocator, would
/// otherwise count in the solve's peak. Writing 5 to
/// `/proc/self/clear_refs` resets VmHWM (Linux ≥ 4.0).
pub fn reset_peak() {
    // SAFETY: mi_collect takes no pointer and only releases free pages.
    unsafe { mi_collect(true) };
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

/// How often a phase is timed (the median is kept): on a shared machine one
/// sample of a phase varies by tens of per cent, and a phase of a few
/// hundredths of a second on the small mesh is mostly timer and scheduler
/// noise.
pub fn repeats(n: usize) -> usize {
    match n {
        0..=64 => 7,
        65..=256 => 3,
        _ => 1,
    }
}

/// Cholesky factorisations timed per case: the first (on memory the
/// process has never touched, as every factorisation of a command-line run)
/// and at least one more (on memory the allocator kept).
pub fn cholesky_repeats(n: usize) -> usize {
    repeats(n).max(2)
}

/// Processor time (user and system, all threads) of a `getrusage` result.
pub fn cpu_of(u: &libc::rusage) -> f64 {
    let t = |v: libc::timeval| v.tv_sec as f64 + v.tv_usec as f64 * 1e-6;
    t(u.ru_utime) + t(u.ru_stime)
}

/// Processor time this process has used so far (all threads), in seconds:
/// beside the wall time, a measure that other jobs on the machine disturb
/// far less.
pub fn cpu_seconds() -> f64 {
    // SAFETY: an all-zero rusage is a valid value of the plain C struct.
    let mut u: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: `u` is valid for writes for the duration of the call.
    unsafe { libc::getrusage(libc::RUSAGE_SELF, &mut u) };
    cpu_of(&u)
}
