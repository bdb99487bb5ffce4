//! Timing of the interval Newton strategies (release build):
//! `cargo run --release --bin newton_speed`.
//! Cases: the thesis's largest table case (degree 3, 101 control points, 1-D), the thesis's
//! degree table (11 points, p = 2..10), random 2-D cubic Béziers; default vs thesis settings.
use nurbs_box::enclose::{BoxEncloser, Newton, SearchRegion};
use nurbs_box::NurbsCurve;
use rand::{Rng, SeedableRng};
use std::time::{Duration, Instant};

fn uniform_clamped(p: usize, npts: usize) -> Vec<f64> {
    let inner = npts - p - 1;
    let mut k = vec![0.0; p + 1];
    k.extend((1..=inner).map(|i| i as f64 / (inner + 1) as f64));
    k.extend(vec![1.0; p + 1]);
    k
}

/// Median time per call over `reps` calls (after one warm-up), and the last result.
fn time(s: &dyn BoxEncloser, c: &NurbsCurve, reps: usize) -> (Duration, nurbs_box::Enclosure) {
    let mut e = s.enclose(c);
    let mut t: Vec<Duration> = (0..reps)
        .map(|_| {
            let t0 = Instant::now();
            e = s.enclose(std::hint::black_box(c));
            t0.elapsed()
        })
        .collect();
    t.sort();
    (t[reps / 2], e)
}

fn main() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(2009);
    let strategies: Vec<Box<dyn BoxEncloser>> = vec![
        Box::new(Newton::default()),
        Box::new(Newton::thesis()),
        Box::new(SearchRegion::thesis(Newton::default())),
        Box::new(SearchRegion::verified(Newton::default())),
    ];
    println!("thesis table 1 (1-D, p = 3, n + 1 control points); median over random curves");
    println!("n\tstrategy\tmedian_time\tnewton_it\tderiv_evals\ttime_deriv");
    for n in [4usize, 5, 6, 10, 20, 50, 70, 100] {
        let curves: Vec<NurbsCurve> = (0..20)
            .map(|_| {
                let pts = (0..=n).map(|_| vec![rng.random_range(-1.0..1.0)]).collect();
                NurbsCurve::new(3, uniform_clamped(3, n + 1), pts, None).unwrap()
            })
            .collect();
        for s in &strategies {
            let mut ts: Vec<Duration> = Vec::new();
            let (mut it, mut ev, mut td) = (0u64, 0u64, Duration::ZERO);
            for c in &curves {
                let (t, e) = time(s.as_ref(), c, 51);
                ts.push(t);
                let st = e.stats();
                it += st.newton_iterations;
                ev += st.derivative_evaluations;
                td += st.time_derivatives;
            }
            ts.sort();
            println!(
                "{n}\t{}\t{:?}\t{:.1}\t{:.1}\t{:?}",
                s.name(),
                ts[ts.len() / 2],
                it as f64 / 20.0,
                ev as f64 / 20.0,
                td / 20
            );
        }
    }
    println!("\nthesis table 2 (2-D, 11 control points, random weights 0.5..2), degree p");
    for p in 2..=10usize {
        let curves: Vec<NurbsCurve> = (0..20)
            .map(|_| {
                let pts = (0..11)
                    .map(|_| vec![rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)])
                    .collect();
                let w = (0..11).map(|_| rng.random_range(0.5..2.0)).collect();
                NurbsCurve::new(p, uniform_clamped(p, 11), pts, Some(w)).unwrap()
            })
            .collect();
        for s in &strategies[..2] {
            let mut ts: Vec<Duration> = Vec::new();
            let mut it = 0u64;
            for c in &curves {
                let (t, e) = time(s.as_ref(), c, 21);
                ts.push(t);
                it += e.stats().newton_iterations;
            }
            ts.sort();
            println!(
                "p={p}\t{}\t{:?}\t{:.1} it",
                s.name(),
                ts[ts.len() / 2],
                it as f64 / 20.0
            );
        }
    }
    println!("\n2-D cubic Bézier (random points), median over 200 curves");
    let curves: Vec<NurbsCurve> = (0..200)
        .map(|_| {
            let pts = (0..4)
                .map(|_| vec![rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)])
                .collect();
            NurbsCurve::new(3, uniform_clamped(3, 4), pts, None).unwrap()
        })
        .collect();
    for s in &strategies {
        let mut ts: Vec<Duration> = curves.iter().map(|c| time(s.as_ref(), c, 101).0).collect();
        ts.sort();
        println!("{}\tmedian {:?}\tp90 {:?}", s.name(), ts[100], ts[180]);
    }
}
