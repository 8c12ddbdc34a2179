//! Valid but hard scenes under an 8 GiB address-space limit: every shape
//! at every extreme of the documented limits, given to `check` and `run`,
//! every outcome counted.

use crate::harness::{
    body_scene, launch, mesh, multipatch_scene, refine, Launch, Outcome, ALL_OUTPUTS,
    MULTIPATCH_SHAPES, SHAPES,
};
use std::collections::BTreeMap;
use std::path::Path;

/// The address-space limit of every launch.
pub const LIMIT: u64 = 8 << 30;
/// Seconds after which the harness stops a launch.
pub const TIMEOUT: f64 = 30.0;

// ANCHOR: grid
/// The refinements of the grid: none, k-refinement at degrees 2, 5, 10 on
/// the extreme meshes, degree 1 on the largest, and Lagrange Q1, Q4.
pub fn refinements() -> Vec<(String, String)> {
    let mut out = vec![("as given".to_string(), String::new())];
    for p in [2, 5, 10] {
        for e in [[1, 1], [64, 64], [4096, 1], [1, 4096], [4096, 4096]] {
            out.push((format!("p = {p}, {}", mesh(e)), refine(p, e)));
        }
    }
    for e in [[1024, 1024], [4096, 4096]] {
        out.push((format!("p = 1, {}", mesh(e)), refine(1, e)));
    }
    for q in [1, 4] {
        for e in [[64, 64], [4096, 4096]] {
            let r = format!(
                "refine = {{ lagrange = {q}, elements = [{}, {}] }}",
                e[0], e[1]
            );
            out.push((format!("Q{q}, {}", mesh(e)), r));
        }
    }
    out
}

/// The refinements of the multi-patch bodies, whose patches each take the
/// mesh (five of them for the full disk): degrees 2 and 5 on the extreme
/// square meshes, and a Lagrange mesh, which they refuse.
pub fn multipatch_refinements() -> Vec<(String, String)> {
    let mut out = vec![("as given".to_string(), String::new())];
    for p in [2, 5] {
        for e in [[1, 1], [64, 64], [4096, 4096]] {
            out.push((format!("p = {p}, {}", mesh(e)), refine(p, e)));
        }
    }
    out.push((
        "Q2, 64²".to_string(),
        "refine = { lagrange = 2, elements = [64, 64] }".to_string(),
    ));
    out
}

/// The output sets: none, all, all with the finest VTU.
pub fn output_sets() -> [(&'static str, String); 3] {
    [
        ("no outputs", String::new()),
        ("all outputs", ALL_OUTPUTS.to_string()),
        (
            "all outputs, VTU ×64",
            format!("{ALL_OUTPUTS}vtu_subdivisions = 64\n"),
        ),
    ]
}
// ANCHOR_END: grid

/// Extremes of other keys: (label, scene).
pub fn extremes() -> Vec<(String, String)> {
    let rect = SHAPES[0].1;
    let mut out = vec![
        (
            "quadrature 30 at degree 10, 64²".into(),
            body_scene("q30", rect, &refine(10, [64, 64]), "quadrature = 30", ""),
        ),
        (
            "quadrature 30 at degree 10, 4², all outputs".into(),
            body_scene(
                "q30",
                rect,
                &refine(10, [4, 4]),
                "quadrature = 30",
                ALL_OUTPUTS,
            ),
        ),
    ];
    let many: String = (0..40)
        .map(|i| {
            format!(
                "[[body]]\nname = \"b{i}\"\ngeometry = {{ rectangle = {{ x0 = {i}.0, y0 = 0.0, x1 = {i}.5, y1 = 0.5 }} }}\n\
                 {}\nmaterial = {{ young = 1.0e6, poisson = 0.3, plane = \"strain\" }}\n\
                 [[support]]\nbody = \"b{i}\"\nside = \"eta_min\"\ncomponent = \"x\"\n\
                 [[support]]\nbody = \"b{i}\"\nside = \"eta_min\"\ncomponent = \"y\"\n",
                refine(4, [64, 64])
            )
        })
        .collect();
    out.push(("40 bodies of degree 4 on 64²".into(), many));
    let knots: Vec<String> = (1..2000)
        .map(|i| format!("{}", i as f64 / 2000.0))
        .collect();
    let points: Vec<String> = (0..2)
        .flat_map(|j| {
            (0..2001).map(move |i| format!("[{}, {}]", i as f64 / 2000.0, j as f64 * 0.5))
        })
        .collect();
    let nurbs_long = format!(
        "{{ nurbs = {{ degree = [1, 1], knots_xi = [0.0, 0.0, {}, 1.0, 1.0], knots_eta = [0.0, 0.0, 1.0, 1.0], control_points = [{}] }} }}",
        knots.join(", "),
        points.join(", ")
    );
    out.push((
        "a NURBS of 2000 spans refined to degree 10 on 4096²".into(),
        body_scene("long NURBS", &nurbs_long, &refine(10, [4096, 4096]), "", ""),
    ));
    let plain = |title: &str, output: &str| body_scene(title, rect, "", "", output);
    out.push((
        "a title with control characters and markup".into(),
        plain("nul \\u0000 <&>", ALL_OUTPUTS),
    ));
    out.push((
        "E = 1e-300".into(),
        plain("tiny E", "").replace("young = 2.0e7", "young = 1e-300"),
    ));
    out.push((
        "a load of 1e200".into(),
        plain("huge load", "").replace("force = [0.0, -1.3e6]", "force = [0.0, -1e200]"),
    ));
    out.push((
        "zero load, all outputs".into(),
        plain("zero load", ALL_OUTPUTS).replace("-1.3e6", "0.0"),
    ));
    out.push((
        "a body with no support".into(),
        body_scene("unsupported", rect, &refine(2, [4, 4]), "", "").replace(
            "[[support]]\nbody = \"b\"\nside = \"xi_min\"\ncomponent = \"x\"\n",
            "",
        ),
    ));
    out
}

/// Every outcome of the campaign.
#[derive(Default)]
pub struct Tally {
    pub scenes: usize,
    pub extremes: usize,
    pub launches: usize,
    /// Launches per outcome.
    pub by_outcome: BTreeMap<&'static str, usize>,
    /// Launches that were not clean: a signal, a backtrace, or other than
    /// one `error:` line.
    pub unclean: Vec<String>,
    pub slowest_check: f64,
    /// Exit-1 messages (the first words), with the scenes that gave them.
    pub failures: BTreeMap<String, Vec<String>>,
    /// Launches the harness stopped.
    pub stopped: Vec<String>,
}

/// The outcomes, in the order the chapter's table lists them.
pub const OUTCOMES: [&str; 5] = [
    "exit 0: answered",
    "exit 1: failed cleanly (one error line)",
    "exit 2: refused cleanly (one error line)",
    "stopped by the harness after the time limit",
    "anything else (signal, backtrace, other exit)",
];

impl Tally {
    fn record(&mut self, what: &str, o: &Outcome) {
        self.launches += 1;
        let outcome = if o.timed_out {
            self.stopped.push(what.to_string());
            OUTCOMES[3]
        } else if !o.clean() {
            self.unclean
                .push(format!("{what}: {} {}", o.status(), o.stderr.trim()));
            OUTCOMES[4]
        } else {
            match o.code {
                Some(0) => OUTCOMES[0],
                Some(1) => OUTCOMES[1],
                _ => OUTCOMES[2],
            }
        };
        *self.by_outcome.entry(outcome).or_default() += 1;
        if o.code == Some(1) {
            let m: String = o.message().split(';').next().unwrap_or("").to_string();
            self.failures.entry(m).or_default().push(what.to_string());
        }
    }
}

/// Runs the campaign in `work`.
pub fn run(work: &Path) -> Tally {
    let limited = Launch {
        address_space: Some(LIMIT),
        timeout: TIMEOUT,
        ..Launch::default()
    };
    let mut scenes: Vec<(String, String)> = Vec::new();
    for (shape, g) in SHAPES {
        for (rl, r) in refinements() {
            for (ol, o) in output_sets() {
                scenes.push((
                    format!("{shape}, {rl}, {ol}"),
                    body_scene("campaign", g, &r, "", &o),
                ));
            }
        }
    }
    for shape in &MULTIPATCH_SHAPES {
        for (rl, r) in multipatch_refinements() {
            for (ol, o) in output_sets() {
                scenes.push((
                    format!("{}, {rl}, {ol}", shape.name),
                    multipatch_scene("campaign", shape, &r, &o),
                ));
            }
        }
    }
    let extremes = extremes();
    let mut tally = Tally {
        extremes: extremes.len(),
        ..Tally::default()
    };
    scenes.extend(extremes);
    for (k, (label, text)) in scenes.iter().enumerate() {
        let name = format!("c{k}.toml");
        std::fs::write(work.join(&name), text).expect("the work folder takes a scene");
        tally.scenes += 1;
        let c = launch(work, &["check", &name], limited);
        tally.slowest_check = tally.slowest_check.max(c.seconds);
        tally.record(&format!("check: {label}"), &c);
        let r = launch(work, &["run", &name, "--out", "campaign-out"], limited);
        tally.record(&format!("run: {label}"), &r);
    }
    tally
}
