use iga_contact::benchmarks::{Hertz, HertzAnalytic, Taylor};
use iga_contact::solver::{solve, SolverKind, SolverOptions};
fn main() {
    let p = Taylor::default().build().unwrap();
    let s = solve(&p, &SolverOptions::default());
    match s {
        Ok(s) => {
            println!("taylor iters {}", s.history.len());
            print!("{}", s.history.to_csv());
            println!("force {:?}", p.contact_force(&s.full));
        }
        Err(e) => println!("taylor err {e}"),
    }
    for kind in [
        SolverKind::Bfgs,
        SolverKind::Newton,
        SolverKind::BfgsNoCorrection,
    ] {
        let t = std::time::Instant::now();
        let p = Hertz::default().build().unwrap();
        match solve(&p, &SolverOptions::with_kind(kind)) {
            Ok(s) => {
                println!(
                    "hertz {kind:?} iters {} corr {} t {:?}",
                    s.history.len(),
                    s.history.corrections(),
                    t.elapsed()
                );
                println!(
                    "force {:?} load {}",
                    p.contact_force(&s.full),
                    HertzAnalytic::new().load / 2.0
                );
                if kind == SolverKind::Bfgs {
                    print!("{}", s.history.to_csv());
                }
            }
            Err(e) => println!("hertz {kind:?} err {e}"),
        }
    }
}
