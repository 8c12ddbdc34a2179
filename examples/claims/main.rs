//! The paper's claims with verdicts: the program behind the chapter "What
//! the paper claims, and what we measured".
//!
//! It solves nothing. It reads the facts the other chapter programs wrote
//! (`book/src/generated/<chapter>/facts.txt`), applies to each claim of the
//! paper a rule that turns the evidence into a verdict — holds, holds with
//! limits, does not hold — and writes the verdict table and its facts to
//! `book/src/generated/claims/`. It must run after the chapters it reads
//! (`companion::PROGRAMS` lists it after them).
//!
//! Run it with `cargo run --release --example claims`.

use companion::chapter::Chapter;
use companion::facts;
use companion::facts::Facts;
use companion::Solver;
use iga_contact::error::{Error, Result};
use iga_contact::report::table::{Column, Format, Table};

// ANCHOR: verdict
/// What the evidence says about a claim.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Verdict {
    Holds,
    HoldsWithLimits,
    DoesNotHold,
    /// No case measures the claim: the book states what it would need.
    NotTested,
}

impl Verdict {
    fn as_str(self) -> &'static str {
        match self {
            Verdict::Holds => "holds",
            Verdict::HoldsWithLimits => "holds with limits",
            Verdict::DoesNotHold => "does not hold",
            Verdict::NotTested => "not tested",
        }
    }

    /// All of the cases support the claim: it holds; some: it holds with
    /// limits; none: it does not hold.
    fn of(supporting: usize, cases: usize) -> Self {
        if cases > 0 && supporting == cases {
            Verdict::Holds
        } else if supporting > 0 {
            Verdict::HoldsWithLimits
        } else {
            Verdict::DoesNotHold
        }
    }
}
// ANCHOR_END: verdict

/// One claim, judged.
struct Claim {
    key: &'static str,
    claim: &'static str,
    verdict: Verdict,
    evidence: String,
    conditions: &'static str,
    chapter: &'static str,
}

/// A number of a chapter's facts, or an error naming it.
fn value(f: &Facts, chapter: &str, key: &str) -> Result<f64> {
    f.value(key)
        .ok_or_else(|| Error::invalid(format!("{chapter} facts"), key, "missing or not a number"))
}

fn text<'a>(f: &'a Facts, chapter: &str, key: &str) -> Result<&'a str> {
    f.get(key)
        .ok_or_else(|| Error::invalid(format!("{chapter} facts"), key, "missing"))
}

const SETUPS: [(&str, &str); 4] = [
    ("hertz", "Hertz disk"),
    ("taylor", "Taylor blocks"),
    ("cylinders", "two cylinders"),
    ("block", "block on floor"),
];

/// The meshes and degrees of the Hertz chapter's solver ladder.
const LADDER: [(usize, usize); 8] = [
    (2, 8),
    (2, 16),
    (2, 32),
    (2, 64),
    (3, 8),
    (3, 16),
    (3, 32),
    (3, 64),
];

// ANCHOR: claims
/// Claim 1, its cost half: (11) spares an eigenvalue problem per iteration.
/// No program here times the crate's one eigenproblem per slave element
/// against the paper's per-iteration one, so the verdict says so.
fn penalty_cost_claim() -> Claim {
    Claim {
        key: "penalty_cost",
        claim: "the empirical penalty (11) spares the per-iteration eigenvalue problem (the cost)",
        verdict: Verdict::NotTested,
        evidence: "neither the paper's per-iteration eigenproblem nor the crate's one eigenproblem per slave element (taken over all its contact points, so independent of the active set) is timed".into(),
        conditions: "none: no case is run",
        chapter: "[Nitsche's method](nitsche.md), [The penalty, measured](penalty_study.md#the-sharp-bound)",
    }
}

/// Claim 1, its stability half: what the saving would give up. Evidence:
/// (11) over the θ = 0 bound at first touch, smallest over p = 1…5, for each
/// set-up of the penalty chapter.
fn penalty_claim() -> Result<Claim> {
    let f = facts("penalty")?;
    let mut above = Vec::new();
    let mut below = Vec::new();
    for (key, name) in SETUPS {
        let margin = value(&f, "penalty", &format!("{key}_first_min_theta0"))?;
        let entry = format!("{name} {}", Format::Fixed(2).render(margin));
        if margin > 1.0 {
            above.push(entry);
        } else {
            below.push(entry);
        }
    }
    let verdict = Verdict::of(above.len(), SETUPS.len());
    let mut evidence = format!(
        "(11) over the θ = 0 bound, smallest over p = 1…5: above 1 on {}",
        above.join(", ")
    );
    if !below.is_empty() {
        evidence += &format!("; below 1 on {}", below.join(", "));
    }
    // not judged: the rule samples first touch only, and along the side (11) falls further
    let side = value(&f, "penalty", "hertz_regular_min_theta0")?;
    evidence += &format!(
        "; not judged: over the regular points of the whole Hertz side (p = 2…5) {}",
        Format::Fixed(2).render(side)
    );
    Ok(Claim {
        key: "penalty",
        claim: "with (11) instead of the eigenvalue problem, the penalty stays stable (above the θ = 0 bound)",
        verdict,
        evidence,
        conditions: "θ = 0, penalty factor 1, p = 1 (Q1 on the disk and the cylinders) to 5, 16², where the bodies first touch",
        chapter: "[The penalty, measured](penalty_study.md)",
    })
}

/// The Hertz chapter's fact of one run of its solver ladder: the
/// iterations of `solver` on p, `n`², or `failed`.
fn ladder_key(solver: Solver, p: usize, n: usize) -> String {
    format!("its_{}_p{p}_{n}", solver.key())
}

/// Claim 2: K̃₀ (17) is a good enough start for BFGS. Like for like: the
/// paper's iteration (its correction rule, full steps, body space) from K̃₀
/// and from the balanced secant start, nothing else changed, on every run of
/// the Hertz ladder, and on Taylor. A run supports the start when the
/// iteration converges from K̃₀, or fails from both starts (then the start
/// is not what fails); it does not when only the secant start converges.
fn start_claim() -> Result<Claim> {
    let f = facts("hertz")?;
    let converges = |solver: Solver, p: usize, n: usize| -> Result<bool> {
        Ok(text(&f, "hertz", &ladder_key(solver, p, n))? != "failed")
    };
    let mut tied = 0;
    let mut secant = 0;
    let mut limits = Vec::new();
    for (p, n) in LADDER {
        let t = converges(Solver::Paper, p, n)?;
        let s = converges(Solver::PaperSecantStart, p, n)?;
        tied += usize::from(t);
        secant += usize::from(s);
        if !t && s {
            limits.push(format!("p = {p} on {n}²"));
        }
    }
    let taylor = value(&facts("taylor")?, "taylor", "segment_iterations")?;
    let supported = LADDER.len() - limits.len();
    let mut evidence = format!(
        "the paper's iteration converges on {tied} of {} Hertz runs from K̃₀ and on {secant} from the \
         secant start",
        LADDER.len()
    );
    if !limits.is_empty() {
        evidence += &format!("; only the secant start converges on {}", limits.join(", "));
    }
    evidence += &format!(
        "; on the Taylor test K̃₀ converges in {}",
        iterations(taylor)
    );
    Ok(Claim {
        key: "start",
        claim: "K̃₀ (17) is a good enough start for BFGS",
        verdict: Verdict::of(supported, LADDER.len()),
        evidence,
        conditions: "Hertz p = 2, 3 on 8² to 64², θ = 0, (11), the paper's correction rule, full steps, body space",
        chapter: "[Hertz](hertz.md#the-solver-ladder)",
    })
}

/// `n` iterations, in words that agree with `n`.
fn iterations(n: f64) -> String {
    if n == 1.0 {
        "1 iteration".to_string()
    } else {
        format!("{n} iterations")
    }
}

/// Claim 3: the secant correction (18) rescues BFGS when the contact zone
/// changes. Like for like: the paper's iteration with and without (18).
fn correction_claim() -> Result<Claim> {
    let f = facts("hertz")?;
    let mut helped = 0;
    let mut cases = 0;
    let mut pairs = Vec::new();
    for (p, n) in LADDER {
        let with = f.value(&ladder_key(Solver::Paper, p, n));
        let without = f.value(&ladder_key(Solver::PaperNoCorrection, p, n));
        let show = |v: Option<f64>| v.map_or("failed".to_string(), |v| format!("{v}"));
        pairs.push(format!("p = {p}, {n}²: {} / {}", show(with), show(without)));
        cases += 1;
        // helped: the corrected run converges, in fewer iterations or
        // where the uncorrected one fails
        if let Some(w) = with {
            if without.is_none_or(|o| w < o) {
                helped += 1;
            }
        }
    }
    Ok(Claim {
        key: "correction",
        claim: "the secant correction (18) rescues BFGS when the contact zone changes",
        verdict: Verdict::of(helped, cases),
        evidence: format!(
            "iterations of the paper's BFGS with / without (18): {}; it helps in {helped} of {cases}",
            pairs.join("; ")
        ),
        conditions: "Hertz p = 2, 3 on 8² to 64², θ = 0, (11), tied start, full steps, body space",
        chapter: "[Hertz](hertz.md#the-solver-ladder), [Solvers](solvers.md)",
    })
}

/// Claim 4: IGA is more accurate than FEM on the same coarse mesh. Evidence:
/// p₀ and a of IGA p = 2, FEM Q1 and FEM Q2 on 8×8 against the converged
/// reference of the Hertz chapter.
fn accuracy_claim() -> Result<Claim> {
    let g = facts("iga_vs_fem")?;
    let h = facts("hertz")?;
    let rp0 = value(&h, "hertz", "reference_p0_mpa")?;
    let ra = value(&h, "hertz", "reference_a_mm")?;
    let error = |m: &str| -> Result<[f64; 2]> {
        let p0 = value(&g, "iga_vs_fem", &format!("{m}_p0_mpa"))?;
        let a = value(&g, "iga_vs_fem", &format!("{m}_a_mm"))?;
        Ok([(p0 / rp0 - 1.0).abs(), (a / ra - 1.0).abs()])
    };
    let iga = error("iga")?;
    let mut better = 0;
    let mut cases = 0;
    let mut parts = Vec::new();
    for (m, name) in [("q1", "Q1"), ("q2", "Q2")] {
        let e = error(m)?;
        for (k, q) in ["p₀", "a"].iter().enumerate() {
            cases += 1;
            if iga[k] < e[k] {
                better += 1;
            }
            parts.push(format!(
                "{q}: IGA {} against {name} {}",
                Format::Percent(1).render(iga[k]),
                Format::Percent(1).render(e[k])
            ));
        }
    }
    Ok(Claim {
        key: "accuracy",
        claim: "IGA is more accurate than FEM on the same coarse mesh (the paper: because its boundary is exact)",
        verdict: Verdict::of(better, cases),
        evidence: format!(
            "errors against the converged reference: {}; IGA wins {better} of {cases}",
            parts.join("; ")
        ),
        conditions: "Hertz 8×8, IGA p = 2 against isoparametric Q1 and Q2 (nodes on the circle), θ = 0, (11)",
        chapter: "[IGA against FEM](iga_vs_fem.md)",
    })
}

/// How much slower IGA must be for a timing to support claim 5: the solves
/// take milliseconds on a shared machine, so a ratio near 1 is a tie, and
/// a verdict must not turn on a ratio of 0.9 becoming 1.0.
const CLEARLY_SLOWER: f64 = 1.25;

/// Claim 5: IGA takes longer than FEM. Evidence: the 8×8 timings of the
/// IGA-against-FEM chapter, the paper's iteration on one thread (timed); a
/// case supports the claim when IGA is clearly slower.
fn time_claim() -> Result<Claim> {
    let g = facts("iga_vs_fem")?;
    let mut slower = 0;
    let mut cases = 0;
    let mut parts = Vec::new();
    let mut default = Vec::new();
    let iga_its = value(&g, "iga_vs_fem", "iga_paper_iterations")?;
    for (m, name) in [("q1", "Q1"), ("q2", "Q2")] {
        let ratio = value(&g, "iga_vs_fem", &format!("{m}_paper_ratio"))?;
        let its = value(&g, "iga_vs_fem", &format!("{m}_paper_iterations"))?;
        cases += 1;
        if ratio > CLEARLY_SLOWER {
            slower += 1;
        }
        parts.push(format!(
            "IGA time / {name} time {} (IGA {}, {name} {})",
            Format::Times(2).render(ratio),
            iterations(iga_its),
            iterations(its)
        ));
        let ratio = value(&g, "iga_vs_fem", &format!("{m}_ratio"))?;
        default.push(format!("{name} {}", Format::Times(2).render(ratio)));
    }
    Ok(Claim {
        key: "time",
        claim: "IGA takes longer than FEM",
        verdict: Verdict::of(slower, cases),
        evidence: format!(
            "{} (the paper: {}); a case counts when IGA is slower by more than {}; milliseconds, against the paper's minutes; with the default solver on {} threads, not judged: {}",
            parts.join(", "),
            text(&g, "iga_vs_fem", "paper_ratio")?,
            Format::Times(2).render(CLEARLY_SLOWER),
            text(&g, "iga_vs_fem", "threads")?,
            default.join(", ")
        ),
        conditions: "Hertz 8×8, the paper's iteration, one thread, median of repeated runs on a shared machine",
        chapter: "[IGA against FEM](iga_vs_fem.md), [Accuracy per second](error_vs_time.md)",
    })
}
// ANCHOR_END: claims

fn main() -> Result<()> {
    let mut chapter = Chapter::from_args("claims")?;
    let claims = [
        penalty_cost_claim(),
        penalty_claim()?,
        start_claim()?,
        correction_claim()?,
        accuracy_claim()?,
        time_claim()?,
    ];
    // ANCHOR: table
    let mut table = Table::new(vec![
        Column::plain("claim", "the paper's claim"),
        Column::plain("verdict", "verdict"),
        Column::plain("evidence", "what we measured"),
        Column::plain("conditions", "conditions"),
        Column::plain("chapter", "measured in"),
    ]);
    for c in &claims {
        table.push(vec![
            c.claim.into(),
            format!("**{}**", c.verdict.as_str()).into(),
            c.evidence.clone().into(),
            c.conditions.into(),
            c.chapter.into(),
        ])?;
    }
    // the timing claim rests on wall-clock times
    let timed: Vec<&Claim> = claims.iter().filter(|c| c.key == "time").collect();
    let untimed: Vec<&Claim> = claims.iter().filter(|c| c.key != "time").collect();
    chapter.table("verdicts", &table)?;
    chapter.timed("verdicts.csv");
    chapter.timed("verdicts.md");
    let f = chapter.facts();
    for c in untimed {
        f.text(&format!("{}_verdict", c.key), c.verdict.as_str())?;
    }
    for c in timed {
        f.timed_text(&format!("{}_verdict", c.key), c.verdict.as_str())?;
    }
    // the penalty claim is judged in two rows (cost, stability)
    f.count("claims", claims.len() - 1)?;
    f.number("clearly_slower", CLEARLY_SLOWER, Format::Times(2))?;
    // ANCHOR_END: table
    chapter.finish()
}
