//! Wall-clock timing of a run of a scene: the phases its `summary.toml`
//! reports under `[timing]`. (The chapters' repeated measurements and the
//! machine they ran on are the book's, in `companion::timing`.)

use serde::Serialize;
use std::time::Instant;

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

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

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
}
