use iga_contact::geometry;
use iga_contact::space::Space;
#[test]
fn probe() {
    let disk = geometry::half_disk([0.0, 0.2], 0.2)
        .unwrap()
        .k_refined(2, [3, 3])
        .unwrap();
    let sp = Space::new(disk, None).unwrap();
    for e in &sp.elements {
        let [[xa, xb], [ya, yb]] = e.range;
        let c = sp.shape(e, 0.5 * (xa + xb), 0.5 * (ya + yb)).unwrap().det_j;
        for (x, y) in [(xa, ya), (xb, ya), (xa, yb), (xb, yb)] {
            match sp.shape(e, x, y) {
                Ok(s) if s.det_j < 1e-6 * c => println!(
                    "{:?} corner ({x},{y}) det {:e} ratio {:e}",
                    e.spans,
                    s.det_j,
                    s.det_j / c
                ),
                Err(err) => {
                    println!("{:?} corner ({x},{y}) err {err}", e.spans);
                    for d in [1e-10, 1e-8, 1e-6, 1e-4] {
                        let xx = 0.5 * (xa + xb) + (1.0 - 2.0 * d) * (x - 0.5 * (xa + xb));
                        let yy = 0.5 * (ya + yb) + (1.0 - 2.0 * d) * (y - 0.5 * (ya + yb));
                        let s = sp.shape(e, xx, yy).unwrap();
                        println!("   d {d:e}: det ratio {:e}", s.det_j / c);
                    }
                }
                _ => {}
            }
        }
    }
}
