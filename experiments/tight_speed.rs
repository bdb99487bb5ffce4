//! Timing of the precision layer: `cargo run --release --bin tight_speed`.
//!
//! Measures `TightEval::new`, `coord_at`, `coord_over` (a 1e-12 box around a critical point) on
//! a 2-D cubic Bézier, and kurbo's (unverified, f64) `CubicBez::bounding_box` as the baseline.
use kurbo::{CubicBez, ParamCurveExtrema, Point};
use nurbs_box::{NurbsCurve, TightEval};
use std::hint::black_box;
use std::time::Instant;

fn time<F: FnMut() -> f64>(name: &str, n: usize, mut f: F) -> f64 {
    // TIGHT_SPEED=<prefix> runs only the matching cases (for profiling).
    if let Ok(sel) = std::env::var("TIGHT_SPEED") {
        if !name.starts_with(sel.as_str()) {
            return 0.0;
        }
    }
    // Minimum over many short batches (~1000 calls): the machine is shared, and a short batch
    // often runs undisturbed, so the minimum estimates the undisturbed cost.
    let mut acc = 0.0;
    let mut ns = f64::INFINITY;
    let batch = 1000;
    for _ in 0..(n / batch).max(20) {
        let t = Instant::now();
        for _ in 0..batch {
            acc += f();
        }
        ns = ns.min(t.elapsed().as_nanos() as f64 / batch as f64);
    }
    println!("{name:40} {ns:10.1} ns   (checksum {:.3e})", black_box(acc));
    ns
}

fn main() {
    let p = [(0.0, 0.0), (1.0, 2.0), (2.0, 1.7), (3.0, -0.5)];
    let c = NurbsCurve::new(
        3,
        vec![0., 0., 0., 0., 1., 1., 1., 1.],
        p.iter().map(|&(x, y)| vec![x, y]).collect(),
        None,
    )
    .unwrap();
    let cb = CubicBez::new(
        Point::new(p[0].0, p[0].1),
        Point::new(p[1].0, p[1].1),
        Point::new(p[2].0, p[2].1),
        Point::new(p[3].0, p[3].1),
    );
    // The maximum of y by f64 Newton on y'.
    let f = nurbs_box::CurveEval::<f64>::new(&c, 2);
    let mut ustar = 0.5;
    for _ in 0..50 {
        let d = f.derivs(ustar, 2).unwrap();
        ustar -= d[1][1] / d[2][1];
    }
    let n = 200_000;
    time("kurbo CubicBez::bounding_box", n, || {
        let b = black_box(&cb).bounding_box();
        b.x1 + b.y1
    });
    for name in ["bezier", "newton"] {
        let st = nurbs_box::enclose::strategy_by_name(name, None).unwrap();
        time(&format!("strategy {name}: verified box"), n / 20, || {
            st.enclose(black_box(&c)).hi()[1]
        });
    }
    time("TightEval::new (2-D cubic)", n / 10, || {
        let t = TightEval::new(black_box(&c));
        t.curve().degree() as f64
    });
    time(
        "new + coord_over (cold: builds the span data)",
        n / 10,
        || {
            let t = TightEval::new(black_box(&c));
            t.coord_over(1, ustar - 1e-12, ustar + 1e-12).sup()
        },
    );
    let t = TightEval::new(&c);
    time("coord_at", n, || t.coord_at(1, black_box(0.3)).sup());
    time("coord_over (1e-12 box at a max)", n, || {
        t.coord_over(1, black_box(ustar - 1e-12), ustar + 1e-12)
            .sup()
    });
    time("point (2 coords)", n, || t.point(black_box(0.3))[0].sup());
    let (x, y) = (
        nurbs_box::Ddi::exact(0.3) / nurbs_box::Ddi::exact(7.0),
        nurbs_box::Ddi::exact(0.7) / nurbs_box::Ddi::exact(3.0),
    );
    use nurbs_box::Scalar;
    time("op: Ddi mul", n, || (black_box(x) * black_box(y)).hi());
    time("op: Ddi add", n, || (black_box(x) + black_box(y)).hi());
    time("op: Ddi div", n, || (black_box(x) / black_box(y)).hi());
    time("op: Ddi to_interval", n, || {
        black_box(x).to_interval().sup()
    });
    let (ix, iy) = (x.to_interval(), y.to_interval());
    time("op: inari mul", n, || (black_box(ix) * black_box(iy)).sup());
    time("op: inari add", n, || (black_box(ix) + black_box(iy)).sup());
    let w = [1.0, 0.7, 1.3, 1.0];
    let cr = NurbsCurve::new(
        3,
        vec![0., 0., 0., 0., 1., 1., 1., 1.],
        p.iter().map(|&(x, y)| vec![x, y]).collect(),
        Some(w.to_vec()),
    )
    .unwrap();
    let tr = TightEval::new(&cr);
    time("rational coord_at", n, || {
        tr.coord_at(1, black_box(0.3)).sup()
    });
    let fr = nurbs_box::CurveEval::<f64>::new(&cr, 2);
    let mut ur = 0.5;
    for _ in 0..50 {
        let d = fr.derivs(ur, 2).unwrap();
        ur -= d[1][1] / d[2][1];
    }
    time("rational coord_over (1e-12 box at a max)", n, || {
        tr.coord_over(1, black_box(ur - 1e-12), ur + 1e-12).sup()
    });
    time("coord_over (monotone 1e-12 box)", n, || {
        t.coord_over(1, black_box(0.2 - 1e-12), 0.2 + 1e-12).sup()
    });
    time("coord_over (1e-3 box at a max)", n / 10, || {
        t.coord_over(1, black_box(ustar - 1e-3), ustar + 1e-3).sup()
    });
}
