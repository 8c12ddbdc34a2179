//! The penalty against its stability bound: a run or check whose penalty
//! lies below the bound at the points that carry the contact warns (CLI:
//! one `warning:` line naming the pair; `summary.toml`: per-pair fields;
//! `iterations.csv`: an event), and one above it does not.

use iga_contact::contact::penalty::stability_bound;
use iga_contact::contact::{PenaltyKind, Theta};
use iga_contact::post::penalty_stability;
use iga_contact::scene::RefineSpec;
use iga_contact::solver::{solve, Warning};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_iga-contact");

/// The shipped Hertz scene (8², p = 2) with θ = `theta`, the library's
/// default solver (the paper's full-step BFGS diverges for θ = 1), and
/// every output but the VTU file.
fn hertz_text(theta: i32) -> String {
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("data/scenes/hertz.toml"),
    )
    .unwrap();
    let (head, tail) = text.split_at(text.find("[solver]").unwrap());
    let outputs = &tail[tail.find("[output]").unwrap()..];
    format!("{head}{outputs}")
        .replace(
            "nitsche = { theta = 0,",
            &format!("nitsche = {{ theta = {theta},"),
        )
        .replace("vtu = true", "vtu = false")
}

fn workdir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("penalty-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn cli(dir: &Path, args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs")
}

fn warnings(o: &Output) -> Vec<String> {
    String::from_utf8_lossy(&o.stderr)
        .lines()
        .filter(|l| l.starts_with("warning: "))
        .map(str::to_string)
        .collect()
}

fn summary_pair(dir: &Path) -> toml::Table {
    let text = std::fs::read_to_string(dir.join("out/hertz/summary.toml")).unwrap();
    let t: toml::Table = toml::from_str(&text).unwrap();
    t["contact"].as_array().unwrap()[0]
        .as_table()
        .unwrap()
        .clone()
}

#[test]
fn run_warns_below_the_bound_and_not_above() {
    // θ = 1 needs γ above the trace constant C_T, which (11) is not on the
    // Hertz disk for p = 2; θ = 0 needs only C_T/4.
    let below = workdir("run-below");
    std::fs::write(below.join("hertz.toml"), hertz_text(1)).unwrap();
    let o = cli(&below, &["run", "hertz.toml"]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let w = warnings(&o);
    assert_eq!(w.len(), 1, "{w:?}");
    for part in [
        "hertz.toml",
        "contact[0]",
        "active points",
        "smallest γ/bound 0.",
        "which θ > 0 needs at every point",
        "set contact[0].nitsche.",
    ] {
        assert!(w[0].contains(part), "{part:?} missing in {}", w[0]);
    }
    let pair = summary_pair(&below);
    let n = pair["penalty_below_bound_points"].as_integer().unwrap();
    assert!(n > 0);
    assert!(pair["min_penalty_ratio"].as_float().unwrap() < 1.0);
    assert!(w[0].contains(&format!(": {n} of the ")), "{}", w[0]);
    assert!(!w[0].contains(" or "), "one remedy: {}", w[0]);
    let history = std::fs::read_to_string(below.join("out/hertz/iterations.csv")).unwrap();
    let last = history.lines().last().unwrap();
    assert!(
        last.contains(&format!("penalty below bound: contact[0], {n} points")),
        "{last}"
    );

    let above = workdir("run-above");
    std::fs::write(above.join("hertz.toml"), hertz_text(0)).unwrap();
    let o = cli(&above, &["run", "hertz.toml"]);
    assert_eq!(o.status.code(), Some(0));
    assert!(
        o.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let pair = summary_pair(&above);
    assert_eq!(pair["penalty_below_bound_points"].as_integer(), Some(0));
    assert!(pair["min_penalty_ratio"].as_float().unwrap() > 1.0);
    let history = std::fs::read_to_string(above.join("out/hertz/iterations.csv")).unwrap();
    assert!(!history.contains("penalty below bound"));
}

#[test]
fn check_warns_where_the_bodies_first_touch() {
    let dir = workdir("check");
    for (theta, warns) in [(1, true), (0, false), (-1, false)] {
        std::fs::write(dir.join("hertz.toml"), hertz_text(theta)).unwrap();
        let o = cli(&dir, &["check", "hertz.toml"]);
        assert_eq!(o.status.code(), Some(0));
        let w = warnings(&o);
        assert_eq!(w.len(), usize::from(warns), "θ = {theta}: {w:?}");
        if warns {
            assert!(w[0].contains("where the bodies first touch"), "{}", w[0]);
            assert!(!w[0].contains(" or "), "one remedy: {}", w[0]);
        }
    }
    // the shipped scenes are all silent, at check and at run
    for name in [
        "hertz.toml",
        "taylor.toml",
        "two_cylinders.toml",
        "disk_on_block.toml",
    ] {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("data/scenes")
            .join(name);
        let path = path.to_str().unwrap();
        for args in [vec!["check", path], vec!["run", path, "--out", "out"]] {
            let cmd = args[0];
            let o = cli(&dir, &args);
            assert_eq!(o.status.code(), Some(0), "{cmd} {name}");
            assert!(warnings(&o).is_empty(), "{cmd} {name}: {:?}", warnings(&o));
        }
    }
}

/// The warning follows the bound, not the scene: scaling the penalty to a
/// little below or above the factor it names turns it on or off, and its
/// counts agree with the points' own γ and C_T.
#[test]
fn the_warning_follows_the_bound() {
    let scene = |theta: Theta, penalty: PenaltyKind, factor: f64| {
        let mut s = companion::shipped("hertz.toml")
            .unwrap()
            .refined("disk", RefineSpec::iga(2, [8, 8]))
            .unwrap()
            .with_nitsche(|n| {
                n.theta = theta;
                n.penalty = penalty;
                n.penalty_factor = factor;
            });
        s.solver = Default::default();
        s.output = Default::default();
        s
    };
    let out = workdir("library");
    let report = scene(Theta::Symmetric, PenaltyKind::Empirical, 1.0)
        .run(&out)
        .unwrap();
    let s = scene(Theta::Symmetric, PenaltyKind::Empirical, 1.0);
    let problem = s.build().unwrap();
    let full = solve(&problem, &s.solver).unwrap().full;
    let stability = penalty_stability(&problem, &full)[0];
    assert!(matches!(
        report.warnings.as_slice(),
        [Warning::PenaltyBelowBound { below, active, min_ratio, .. }]
            if *below == stability.active_below && *active == stability.active
                && *min_ratio == stability.min_ratio()
    ));
    let needed = stability.factor_needed(1.0).unwrap();
    assert!(needed > 1.0);

    // the counts, recomputed from the points
    let active: Vec<_> = problem
        .points
        .iter()
        .filter(|cp| cp.p(&full) <= 0.0)
        .collect();
    let below = active
        .iter()
        .filter(|cp| cp.gamma < stability_bound(cp.trace_constant, 1.0))
        .count();
    let ratio = active
        .iter()
        .map(|cp| cp.gamma / stability_bound(cp.trace_constant, 1.0))
        .fold(f64::INFINITY, f64::min);
    assert_eq!(stability.active, active.len());
    assert_eq!(stability.active_below, below);
    assert_eq!(stability.min_active_ratio, Some(ratio));
    // θ = 1 keeps −(1/γ) w σ_n σ_nᵀ at the inactive points: they need
    // γ > C_T too (points at the singular corner are never judged)
    let inactive: Vec<_> = problem
        .points
        .iter()
        .filter(|cp| cp.p(&full) > 0.0 && cp.regular)
        .collect();
    let inactive_below = inactive
        .iter()
        .filter(|cp| cp.gamma < cp.trace_constant)
        .count();
    assert_eq!(stability.inactive_below, inactive_below);
    assert!(
        inactive_below > 0,
        "the Hertz disk's points near its corner"
    );

    // a little above the factor named: silent; a little below: warned
    for (factor, warns) in [(1.2 * needed, false), (0.8 * needed, true)] {
        let r = scene(Theta::Symmetric, PenaltyKind::Empirical, factor)
            .run(&out)
            .unwrap();
        assert_eq!(below_bound(&r.warnings), warns, "factor {factor}");
    }
    // the sharp penalty sits on the bound with safety 1, below it with less
    for (safety, warns) in [(1.0, false), (2.0, false), (0.5, true)] {
        let r = scene(Theta::Symmetric, PenaltyKind::Sharp, safety)
            .run(&out)
            .unwrap();
        assert_eq!(below_bound(&r.warnings), warns, "safety {safety}");
    }
    // θ = −1 has no bound: never warned, however small the penalty
    let r = scene(Theta::Skew, PenaltyKind::Empirical, 0.05)
        .run(&out)
        .unwrap();
    assert!(!below_bound(&r.warnings));
}

fn below_bound(w: &[Warning]) -> bool {
    w.iter()
        .any(|w| matches!(w, Warning::PenaltyBelowBound { .. }))
}

/// The θ = 1 tied kernel (17) of a real mesh, densely, with the sharp
/// penalty γ = `safety` · C_T at every point, and whether nalgebra's
/// dense Cholesky accepts it (it is symmetric for θ = 1).
fn tied_kernel_is_positive_definite(mesh: [usize; 2], block: bool, safety: f64) -> bool {
    let base = if block {
        companion::shipped("block_compression.toml")
            .unwrap()
            .refined("block", RefineSpec::iga(2, mesh))
            .unwrap()
    } else {
        companion::shipped("hertz.toml")
            .unwrap()
            .refined("disk", RefineSpec::iga(2, mesh))
            .unwrap()
    };
    let s = base.with_nitsche(|n| {
        n.theta = Theta::Symmetric;
        n.penalty = PenaltyKind::Sharp;
        n.penalty_factor = safety;
    });
    let p = s.build().unwrap();
    let k = p
        .kernel(iga_contact::problem::Kernel::Tied)
        .unwrap()
        .to_dense();
    let n = k.nrows();
    let a = nalgebra::DMatrix::from_fn(n, n, |i, j| k[(i, j)]);
    // θ = 1 kernels are symmetric up to the round-off of their assembly
    let sym = 0.5 * (&a + a.transpose());
    assert!((&a - &sym).amax() <= 1e-8 * a.amax());
    sym.cholesky().is_some()
}

/// The largest safety factor at which the tied kernel is not positive
/// definite, by bisection on [0, 2].
fn definiteness_threshold(mesh: [usize; 2], block: bool) -> f64 {
    let (mut lo, mut hi) = (0.0, 2.0);
    assert!(!tied_kernel_is_positive_definite(mesh, block, 1e-6));
    assert!(tied_kernel_is_positive_definite(mesh, block, hi));
    for _ in 0..30 {
        let mid = 0.5 * (lo + hi);
        if tied_kernel_is_positive_definite(mesh, block, mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

/// The stability bound on real elements. The bound γ > C_T of θ = 1 is
/// elementwise (Young's inequality on each slave element's own energy), so
/// it is sufficient: a little above it, the tied kernel of every mesh is
/// positive definite, where a C_T too small (a wrong trace constant) would
/// show an indefinite kernel. It is not necessary: the maximiser of
/// ∫σ_n² / a_e on one element does not carry v_n = σ_n/γ, and a global v
/// pays energy in the neighbouring elements its spline basis reaches, so
/// the kernel loses definiteness at a smaller γ, s·C_T with s < 1. What
/// also holds, and is checked, is that s lies within a factor 2 of the
/// bound (the bound is not loose) and that it stays so as the
/// mesh is refined (the bound scales like the kernel's own threshold).
#[test]
fn the_stability_bound_holds_on_real_elements() {
    for (mesh, block) in [
        ([4, 4], false),
        ([8, 8], false),
        ([4, 1], true),
        ([8, 2], true),
    ] {
        for safety in [1.0 + 1e-6, 1.01, 1.1] {
            assert!(
                tied_kernel_is_positive_definite(mesh, block, safety),
                "{mesh:?}, block {block}: not positive definite at {safety} × the bound"
            );
        }
        let s = definiteness_threshold(mesh, block);
        assert!(s <= 1.0, "{mesh:?}: {s}");
        assert!(s >= 0.5, "{mesh:?}: {s}");
    }
}

/// At degree 6 and 7 the element's B-splines that barely reach into it
/// make its stiffness badly scaled; the trace constant is computed after
/// a Jacobi scaling, so it stays finite and close to the C_T ∝ p² trend of
/// lower degrees, the empirical penalty on Hertz 8² is judged above its
/// bound (no warning), and the sharp penalty is accepted. (Without the
/// scaling, every point had C_T = ∞: a warning "γ/bound 0.000" whose
/// advice, the sharp penalty, was refused.)
#[test]
fn the_trace_constant_is_finite_at_degrees_six_and_seven() {
    let per_p2 = |p: usize| {
        let problem = companion::shipped("hertz.toml")
            .unwrap()
            .refined("disk", RefineSpec::iga(p, [8, 8]))
            .unwrap()
            .build()
            .unwrap();
        let c = problem.points[0].trace_constant;
        assert!(c.is_finite() && c > 0.0, "p = {p}: C_T = {c}");
        assert!(
            problem
                .points
                .iter()
                .filter(|cp| cp.regular)
                .all(|cp| cp.trace_constant.is_finite()),
            "p = {p}"
        );
        (c / (p * p) as f64, problem)
    };
    let (base, _) = per_p2(5);
    for p in [6, 7] {
        let (c, problem) = per_p2(p);
        // the p² trend of the penalty chapter, within a factor 2
        assert!(
            (0.5..2.0).contains(&(c / base)),
            "p = {p}: C_T/p² {c:e} against {base:e} at p = 5"
        );
        let s = solve(&problem, &Default::default()).unwrap();
        assert!(!below_bound(&s.warnings), "p = {p}: {:?}", s.warnings);
        let sharp = companion::shipped("hertz.toml")
            .unwrap()
            .refined("disk", RefineSpec::iga(p, [8, 8]))
            .unwrap()
            .with_nitsche(|n| {
                n.penalty = PenaltyKind::Sharp;
                n.penalty_factor = 2.0;
            })
            .build();
        assert!(sharp.is_ok(), "p = {p}: {:?}", sharp.err());
    }
}
