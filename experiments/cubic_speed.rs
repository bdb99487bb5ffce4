//! Quick per-curve timing of the verified strategies on random 2-D cubic Béziers (the bench
//! `cargo bench --bench enclose` has the full comparison with kurbo).
use nurbs_box::enclose::strategy_by_name;
use nurbs_box::NurbsCurve;
use rand::{Rng, SeedableRng};
use std::time::Instant;
fn main() {
    let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    let cs: Vec<NurbsCurve> = (0..1000)
        .map(|_| {
            let p: Vec<Vec<f64>> = (0..4)
                .map(|_| vec![r.random_range(-100.0..100.0), r.random_range(-100.0..100.0)])
                .collect();
            NurbsCurve::new(3, vec![0., 0., 0., 0., 1., 1., 1., 1.], p, None).unwrap()
        })
        .collect();
    // optional arguments: strategy names (default: hull bezier newton), e.g. for a profiler
    let args: Vec<String> = std::env::args().skip(1).collect();
    let names: Vec<&str> = if args.is_empty() {
        vec!["hull", "bezier", "newton"]
    } else {
        args.iter().map(|s| s.as_str()).collect()
    };
    // (REPS=N repeats more, for a profiler)
    let reps = std::env::var("REPS")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(if args.is_empty() { 5 } else { 1 });
    for name in names {
        let s = strategy_by_name(name, None).unwrap();
        let cs = if std::env::var_os("BIG_ONLY").is_some() {
            &cs[..1]
        } else {
            &cs[..]
        };
        let mut best = f64::INFINITY;
        for _ in 0..reps {
            let t = Instant::now();
            let x: f64 = cs.iter().map(|c| s.enclose(c).coords[0].hi).sum();
            std::hint::black_box(x);
            best = best.min(t.elapsed().as_secs_f64() / cs.len() as f64);
        }
        println!("{name}: {:.0} ns per cubic", best * 1e9);
        if std::env::var_os("CUBICS_ONLY").is_some() {
            continue;
        }
        // the thesis's largest case: p = 3, 101 control points, 1-D
        // (BIG_P=p: one 2-D rational span of degree p instead, as in the speed report)
        let big = match std::env::var("BIG_P")
            .ok()
            .and_then(|p| p.parse::<usize>().ok())
        {
            Some(p) => {
                nurbs_box::testkit::gen::thesis_curve_2d_nurbs_with(p + 1, p, 100 + p as u64)
                    .unwrap()
            }
            None => nurbs_box::testkit::gen::thesis_curve_1d(101, 3, 101).unwrap(),
        };
        let mut best = f64::INFINITY;
        for _ in 0..reps * 20 {
            let t = Instant::now();
            std::hint::black_box(s.enclose(std::hint::black_box(&big)));
            best = best.min(t.elapsed().as_secs_f64());
        }
        println!("{name}: {:.1} µs on p = 3, 101 points", best * 1e6);
        if std::env::var_os("STATS").is_some() {
            println!("{:?}", s.enclose(&big).stats());
        }
    }
}
