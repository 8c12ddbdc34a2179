use iga_contact::assembly::{load_vector, stiffness, Load};
use iga_contact::benchmarks::Hertz;
use iga_contact::contact::contact_points;
use iga_contact::linsolve::{Factoriser, Method, Pattern};
use iga_contact::problem::{Kernel, Problem};
use iga_contact::solver::{solve, SolverKind, SolverOptions};
use std::time::Instant;
fn main() {
    for n in std::env::args()
        .skip(1)
        .map(|a| a.parse::<usize>().unwrap())
    {
        let h = Hertz {
            elements: n,
            ..Hertz::default()
        };
        let t = Instant::now();
        let pr = h.build().unwrap();
        let t_build = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let (trip, _) = stiffness(&pr.bodies, &pr.map).unwrap();
        let t_stiff = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let _f = load_vector(
            &pr.bodies,
            &pr.map,
            &[Load::BodyForce {
                body: 0,
                force: [0.0, -1.0],
            }],
        )
        .unwrap();
        let t_load = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let _pts = contact_points(&pr.bodies, &pr.map, &pr.pairs).unwrap();
        let t_cp = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let pat = Pattern::new(pr.n(), &trip).unwrap();
        let t_pat = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let _m = pat.matrix(&trip.vals).unwrap();
        let t_fill = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let k = pr.kernel(Kernel::Tied).unwrap();
        let t_kernel = t.elapsed().as_secs_f64();
        let mut fac = Factoriser::default();
        let t = Instant::now();
        let f = fac.factor(&k, Method::Lu).unwrap();
        let t_lu1 = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let _f2 = fac.factor(&k, Method::Lu).unwrap();
        let t_lu2 = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let _x = f.solve(&pr.rhs).unwrap();
        let t_sol = t.elapsed().as_secs_f64();
        let u = vec![0.0; pr.n()];
        let t = Instant::now();
        let _r = pr.residual(&u);
        let t_res = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let s = solve(&pr, &SolverOptions::with_kind(SolverKind::Bfgs)).unwrap();
        let t_solve = t.elapsed().as_secs_f64();
        println!("n{n} dofs {} trip {} build {t_build:.3} [stiff {t_stiff:.3} load {t_load:.3} cp {t_cp:.3} pattern {t_pat:.3} fill {t_fill:.3}] kernel {t_kernel:.3} lu_sym+num {t_lu1:.3} lu_num {t_lu2:.3} trisolve {t_sol:.4} residual {t_res:.4} solve {t_solve:.3} it {} fac {}",
            pr.n(), trip.len(), s.history.len(), s.factorisations);
    }
}
