//! The heavy chapters' committed data were computed by a solver that
//! behaves as today's does: each records the solver's fingerprint
//! (`companion::canary`), and a change of the solver's behaviour since
//! fails here, naming the chapter to rerun.

use companion::{canary, facts, Cost, PROGRAMS};

#[test]
fn every_heavy_chapter_was_computed_by_todays_solver() {
    let now = canary::fingerprint().expect("the canary solves run");
    let mut stale = Vec::new();
    for p in PROGRAMS.iter().filter(|p| p.cost == Cost::Heavy) {
        let facts = facts(p.chapter).expect("a heavy chapter has committed facts");
        match facts.get(canary::KEY) {
            Some(then) if then == now => {}
            then => stale.push(format!(
                "{}: recorded {:?}; rerun `cargo run --release --bin reproduce -- --only {}`",
                p.chapter,
                then.unwrap_or("nothing"),
                p.example
            )),
        }
    }
    assert!(
        stale.is_empty(),
        "today's solver: {now}\nstale heavy data:\n{}",
        stale.join("\n")
    );
}

/// The fingerprint moves when the solver's behaviour does: the paper's
/// BFGS and Newton take different numbers of iterations on the canary
/// scenes, so a change of solver shows in the text.
#[test]
fn the_fingerprint_tells_solvers_apart() {
    let now = canary::fingerprint().expect("the canary solves run");
    let iterations = |solver: &str| {
        let head = format!("hertz8 {solver}: ");
        now.split("; ")
            .find_map(|l| l.strip_prefix(&head))
            .expect("each solver has a line")
            .to_string()
    };
    assert_ne!(iterations("newton"), iterations("paper"), "{now}");
    assert_eq!(now.matches("; ").count(), 5, "six canary solves: {now}");
}
