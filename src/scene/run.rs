//! [`Scene::run`]: build, solve, and stage the requested outputs as one
//! transaction.

use super::summary::{
    final_relative_residual, no_negative_zero, profile_table, solver_table, PairSummary, Summary,
};
use super::{files, RunReport, Scene};
use crate::error::{Error, Result};
use crate::post::{self, PenaltyStability, PressureProfile};
use crate::problem::Problem;
use crate::report::atomic::OutputSet;
use crate::report::history::history_table_noted;
use crate::report::table::Unit;
use crate::report::{plot, vtu};
use crate::resources::Budget;
use crate::solver;
use crate::timing::{Phase, Stopwatch};
use std::path::Path;

impl Scene {
    /// Builds, solves, and writes the outputs requested in `[output]` into
    /// `out_dir`, within the default memory budget
    /// ([`Budget::from_machine`]). See [`Scene::run_within`].
    pub fn run(&self, out_dir: impl AsRef<Path>) -> Result<RunReport> {
        self.run_within(out_dir, &Budget::from_machine())
    }

    /// Builds, solves, and writes the outputs requested in `[output]` into
    /// `out_dir` — nothing else: a scene without outputs writes no file and
    /// does not even create the directory.
    ///
    /// Before any work: the scene is validated, its estimated peak memory
    /// is checked against `budget`, and the output directory is checked
    /// (it must be creatable and replaceable). The outputs are one
    /// transaction ([`OutputSet`]): staged beside `out_dir` and swapped in
    /// as a whole, so a failed or interrupted run leaves the earlier
    /// results exactly as they were.
    pub fn run_within(&self, out_dir: impl AsRef<Path>, budget: &Budget) -> Result<RunReport> {
        self.run_timed(out_dir, budget, Stopwatch::start())
    }

    /// As [`Scene::run_within`], charging the time of every phase to
    /// `clock` (started by the caller, e.g. before it read the scene):
    /// the phases are reported in [`RunReport::timing`] and in the
    /// `[timing]` table of `summary.toml`.
    pub fn run_timed(
        &self,
        out_dir: impl AsRef<Path>,
        budget: &Budget,
        mut clock: Stopwatch,
    ) -> Result<RunReport> {
        let valid = self.valid()?;
        valid.estimate()?.check(budget, "output.vtu_subdivisions")?;
        let o = &self.output;
        let set = if o.is_empty() {
            None
        } else {
            Some(OutputSet::begin_expecting(out_dir, &o.file_names())?)
        };
        let problem = valid.assemble(&mut clock)?;
        super::check::vtu_samplable(o, &problem.bodies)?;
        clock.lap(Phase::ParseAndBuild);
        let mut solution = solver::solve(&problem, &self.solver)?;
        let solve = clock.take();
        let factorisation = solution.phases.condensation.min(solve);
        clock.charge(Phase::Factorisation, factorisation);
        clock.charge(Phase::Iterations, solve - factorisation);
        // the zones are measured on the dense profile, which the solver
        // does not sample, and which is sampled only for the outputs that
        // show it (a run without them stays as cheap as its solve); one
        // that cannot be sampled (a folded map) fails those outputs below
        let profile = (o.pressure_profile || o.figures || o.summary)
            .then(|| PressureProfile::dense(&problem, &solution.full).ok())
            .flatten();
        if let Some(profile) = &profile {
            let zones = post::zone_warnings(&problem, profile, &solution.warnings);
            solution.warnings.extend(zones);
        }
        let full = &solution.full;
        let contact_force = post::contact_resultant(&problem, full).map(no_negative_zero);
        let active_points = problem.active_points(&solution.u);
        let stability = post::penalty_stability(&problem, full);
        let history = &solution.history;
        let title = self.title.as_deref().unwrap_or("scene");
        let applied_force = if o.summary {
            Some(post::applied_resultant(&problem)?.map(no_negative_zero))
        } else {
            None
        };
        let files = match set {
            None => {
                clock.lap(Phase::PostProcessing);
                Vec::new()
            }
            Some(mut set) => {
                let outputs = Outputs {
                    title,
                    contact_force,
                    applied_force,
                    active_points,
                    stability: &stability,
                    profile: profile.as_ref(),
                };
                let target = set.target().to_path_buf();
                let unwritten =
                    self.stage_outputs(&mut set, &problem, &solution, &outputs, &mut clock)?;
                let files = set.commit()?;
                clock.lap(Phase::Output);
                if let Some(e) = unwritten {
                    return Err(vtu_not_written(&target, e));
                }
                files
            }
        };
        let timing = clock.times();
        Ok(RunReport {
            dofs: problem.n(),
            iterations: history.len(),
            corrections: history.corrections(),
            active_points,
            contact_points: problem.points.len(),
            contact_force,
            applied_force,
            files,
            seconds: timing.wall,
            timing,
            warnings: solution.warnings.clone(),
        })
    }

    /// Computes and stages every requested output: first what they are
    /// computed from (charged to post-processing), then the files (charged
    /// to output, up to the summary, which reports the times so far).
    /// Returns why the VTU could not be sampled, if it could not, with the
    /// other files staged: a solve is not thrown away for one output.
    fn stage_outputs(
        &self,
        set: &mut OutputSet,
        problem: &Problem,
        solution: &solver::Solution,
        out: &Outputs,
        clock: &mut Stopwatch,
    ) -> Result<Option<Error>> {
        let Outputs {
            title,
            contact_force,
            applied_force,
            active_points,
            stability,
            profile,
        } = *out;
        let o = &self.output;
        let full = &solution.full;
        let history = &solution.history;
        let sampled;
        let profile = match (o.pressure_profile || o.figures || o.summary, profile) {
            (false, _) => None,
            (true, Some(p)) => Some(p),
            (true, None) => {
                // sampled again for its error
                sampled = PressureProfile::dense(problem, full)?;
                Some(&sampled)
            }
        };
        let contact = match (applied_force, &profile) {
            (Some(_), Some(profile)) => {
                let forces = post::contact_resultants(problem, full);
                // one entry per [[contact]], over the pairs of its pieces
                problem
                    .contacts
                    .iter()
                    .map(|(_, r)| {
                        let m = profile.measures_joined(r.clone());
                        let f = forces[r.clone()]
                            .iter()
                            .fold([0.0, 0.0], |a, f| [a[0] + f[0], a[1] + f[1]]);
                        let st = &stability[r];
                        // no zone on the profile: nothing was measured, and a
                        // 0 would read as a measured peak of zero
                        let measured = |x: f64| (m.zones > 0).then(|| no_negative_zero(x));
                        PairSummary {
                            p0: measured(m.p0),
                            half_width: measured(m.half_width),
                            zones: m.zones,
                            p_max: measured(m.p_max),
                            contact_force: f.map(no_negative_zero),
                            penalty_below_bound_points: st.iter().map(|s| s.active_below).sum(),
                            min_penalty_ratio: st
                                .iter()
                                .filter_map(|s| s.min_active_ratio)
                                .reduce(f64::min),
                        }
                    })
                    .collect()
            }
            _ => Vec::new(),
        };
        clock.lap(Phase::PostProcessing);
        if let (true, Some(profile)) = (o.figures, &profile) {
            let pairs = problem.contacts.len();
            let series: Vec<plot::Series> = (0..pairs)
                .map(|k| {
                    let samples = || problem.contacts.pieces(k).flat_map(|r| profile.pair(r));
                    // where the map is singular the bracket is not a
                    // pressure, and is left out; a slave side of elements
                    // that all touch a singular corner (one element on
                    // the nine-point disk) has nothing else, so its
                    // brackets are drawn and the legend says what they are
                    let regular = samples().any(|p| p.regular);
                    let points = samples()
                        .filter(|p| p.regular || !regular)
                        .map(|p| (p.x[0], p.pressure()))
                        .collect();
                    let name = if pairs > 1 {
                        format!("contact[{k}]")
                    } else {
                        String::new()
                    };
                    let label = match (regular, name.is_empty()) {
                        (true, _) => name,
                        (false, true) => "singular map: brackets, not pressures".to_string(),
                        (false, false) => {
                            format!("{name} (singular map: brackets, not pressures)")
                        }
                    };
                    plot::Series::line(label, points)
                })
                .collect();
            let axes = plot::Axes {
                title: format!("{title}: contact pressure"),
                x_label: "x".into(),
                y_label: "contact pressure".into(),
                log_x: false,
                log_y: false,
            };
            // staged, not written into `set.dir()`: a stage holds the
            // set's lock, so a signal cannot race the file's creation
            let svg = plot::line_chart_svg(Path::new(files::FIGURE), &axes, &series)?;
            set.stage(files::FIGURE, svg.as_bytes())?;
        }
        if o.iterations {
            let notes: Vec<String> = solution
                .warnings
                .iter()
                .filter_map(solver::Warning::note)
                .collect();
            let table = history_table_noted(history, Unit::None, Unit::None, &notes)?;
            set.stage(files::ITERATIONS, table.to_csv().as_bytes())?;
        }
        if let (true, Some(profile)) = (o.pressure_profile, &profile) {
            set.stage(
                files::PRESSURE_PROFILE,
                profile_table(profile, &problem.contacts)?
                    .to_csv()
                    .as_bytes(),
            )?;
        }
        // what the solution decides (a non-finite field): where samples
        // are taken was checked before the solve
        let mut unwritten = None;
        if o.vtu {
            match vtu::sample_bodies(&problem.bodies, &problem.map, full, o.vtu_subdivisions) {
                Ok(mesh) => {
                    let xml = mesh.to_xml();
                    drop(mesh);
                    set.stage(files::VTU, xml.as_bytes())?;
                }
                Err(e) => unwritten = Some(e),
            }
        }
        if let Some(applied_force) = applied_force {
            clock.lap(Phase::Output);
            let summary = Summary {
                title,
                dofs: problem.n(),
                iterations: history.len(),
                corrections: history.corrections(),
                relative_residual: no_negative_zero(final_relative_residual(history)),
                contact_points: problem.points.len(),
                active_points,
                contact_force,
                applied_force,
                contact,
                warnings: solution.warnings.iter().map(|w| w.to_string()).collect(),
                solver: solver_table(&self.solver),
                timing: clock.times(),
            };
            let text = toml::to_string(&summary)
                .map_err(|e| Error::invalid("output.summary", title, e.to_string()))?;
            set.stage(files::SUMMARY, text.as_bytes())?;
        }
        Ok(unwritten)
    }
}

/// The error of a run whose VTU could not be sampled after the solve: it
/// names the file, the cause, and says where the other outputs went.
fn vtu_not_written(target: &Path, cause: Error) -> Error {
    Error::Io {
        path: target.join(files::VTU).display().to_string(),
        source: std::io::Error::other(format!(
            "not written: {cause}; the other outputs are in `{}`",
            target.display()
        )),
    }
}

/// The figures of a run that go into its outputs.
struct Outputs<'a> {
    title: &'a str,
    contact_force: [f64; 2],
    applied_force: Option<[f64; 2]>,
    active_points: usize,
    stability: &'a [PenaltyStability],
    /// The dense profile, if it could be sampled.
    profile: Option<&'a PressureProfile>,
}
