//! Criterion benches: one group per sweep (strategy x size), and a side-by-side group against
//! kurbo's unverified `CubicBez::bounding_box` on the same random 2-D cubic Béziers.
//!
//! `cargo bench --bench enclose` ; after the criterion groups a ratio summary is printed
//! (verified strategy time / kurbo time, measured in the same run).

use criterion::{black_box, criterion_group, BenchmarkId, Criterion, Throughput};
use kurbo::{CubicBez, ParamCurveExtrema, Point};
use nurbs_box::enclose::{all_strategies, strategy_by_name};
use nurbs_box::NurbsCurve;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::time::{Duration, Instant};

fn clamped_uniform(npts: usize, p: usize) -> Vec<f64> {
    let spans = npts - p;
    let mut k = vec![0.0; p + 1];
    k.extend((1..spans).map(|i| i as f64 / spans as f64));
    k.extend(std::iter::repeat_n(1.0, p + 1));
    k
}

fn curve_1d(npts: usize, p: usize, seed: u64) -> NurbsCurve {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    let v: Vec<f64> = (0..npts).map(|_| r.random_range(-1.0..1.0)).collect();
    NurbsCurve::from_flat(p, 1, clamped_uniform(npts, p), v, None).unwrap()
}

fn curve_2d_nurbs(npts: usize, p: usize, seed: u64) -> NurbsCurve {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    let v: Vec<f64> = (0..2 * npts).map(|_| r.random_range(-1.0..1.0)).collect();
    let w: Vec<f64> = (0..npts).map(|_| r.random_range(0.5..2.0)).collect();
    NurbsCurve::from_flat(p, 2, clamped_uniform(npts, p), v, Some(w)).unwrap()
}

/// Random 2-D cubic Béziers, as kurbo curves and as NURBS curves (same f64 data).
fn cubics(count: usize) -> (Vec<CubicBez>, Vec<NurbsCurve>) {
    let mut r = ChaCha8Rng::seed_from_u64(7);
    let mut k = Vec::new();
    let mut n = Vec::new();
    for _ in 0..count {
        let p: Vec<(f64, f64)> = (0..4)
            .map(|_| (r.random_range(-100.0..100.0), r.random_range(-100.0..100.0)))
            .collect();
        k.push(CubicBez::new(
            Point::new(p[0].0, p[0].1),
            Point::new(p[1].0, p[1].1),
            Point::new(p[2].0, p[2].1),
            Point::new(p[3].0, p[3].1),
        ));
        n.push(
            NurbsCurve::new(
                3,
                clamped_uniform(4, 3),
                p.iter().map(|q| vec![q.0, q.1]).collect(),
                None,
            )
            .unwrap(),
        );
    }
    (k, n)
}

fn knot_sweep(c: &mut Criterion) {
    let mut g = c.benchmark_group("knot_sweep");
    g.sample_size(20)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1));
    for npts in [5, 11, 101, 1001, 10_001, 100_001] {
        let curve = curve_1d(npts, 3, npts as u64);
        g.throughput(Throughput::Elements(npts as u64));
        for s in all_strategies(None) {
            g.bench_with_input(BenchmarkId::new(s.name(), npts), &curve, |b, cu| {
                b.iter(|| s.enclose(black_box(cu)))
            });
        }
    }
    g.finish();
}

fn degree_sweep(c: &mut Criterion) {
    let mut g = c.benchmark_group("degree_sweep");
    g.sample_size(20)
        .warm_up_time(Duration::from_millis(300))
        .measurement_time(Duration::from_secs(1));
    for p in [2, 3, 5, 7, 10, 15, 20] {
        let curve = curve_2d_nurbs(if p <= 10 { 11 } else { 21 }, p, 100 + p as u64);
        for s in all_strategies(None) {
            g.bench_with_input(BenchmarkId::new(s.name(), p), &curve, |b, cu| {
                b.iter(|| s.enclose(black_box(cu)))
            });
        }
    }
    g.finish();
}

const NCUBIC: usize = 1000;

fn kurbo_side_by_side(c: &mut Criterion) {
    let (kc, nc) = cubics(NCUBIC);
    let mut g = c.benchmark_group("cubic_bezier_2d");
    g.throughput(Throughput::Elements(NCUBIC as u64));
    g.bench_function("kurbo_bounding_box", |b| {
        b.iter(|| {
            kc.iter()
                .map(|c| black_box(c).bounding_box().x1)
                .sum::<f64>()
        })
    });
    for s in all_strategies(None) {
        g.bench_function(s.name(), |b| {
            b.iter(|| {
                nc.iter()
                    .map(|c| s.enclose(black_box(c)).coords[0].hi)
                    .sum::<f64>()
            })
        });
    }
    g.finish();
}

/// Ratio summary measured in the same run: min over repetitions of the time for all cubics.
fn ratio_summary() {
    let (kc, nc) = cubics(NCUBIC);
    let best = |f: &mut dyn FnMut() -> f64| {
        let mut best = f64::INFINITY;
        for _ in 0..30 {
            let t = Instant::now();
            black_box(f());
            best = best.min(t.elapsed().as_secs_f64());
        }
        best / NCUBIC as f64
    };
    let tk = best(&mut || {
        kc.iter()
            .map(|c| black_box(c).bounding_box().x1)
            .sum::<f64>()
    });
    println!("\nratio summary (2-D cubic Béziers, per curve, same run):");
    println!("  kurbo bounding_box (unverified): {:8.1} ns", tk * 1e9);
    for name in ["newton", "bezier", "hull"] {
        if let Some(s) = strategy_by_name(name, None) {
            let ts = best(&mut || {
                nc.iter()
                    .map(|c| s.enclose(black_box(c)).coords[0].hi)
                    .sum::<f64>()
            });
            println!(
                "  {name:>8} (verified):            {:8.1} ns  = {:.2}x kurbo",
                ts * 1e9,
                ts / tk
            );
        }
    }
    // thesis's largest case: degree 3, 101 control points, 1-D
    let big = curve_1d(101, 3, 101);
    for name in ["newton", "bezier"] {
        if let Some(s) = strategy_by_name(name, None) {
            let mut best_t = f64::INFINITY;
            for _ in 0..200 {
                let t = Instant::now();
                black_box(s.enclose(black_box(&big)));
                best_t = best_t.min(t.elapsed().as_secs_f64());
            }
            println!("  {name:>8} on the thesis's largest case (p = 3, 101 points): {:.1} µs (target <= 100 µs)", best_t * 1e6);
        }
    }
}

/// Surfaces: every surface strategy on a bicubic 4 x 4 Bézier patch (random net in [-1, 1]^3)
/// and on a rational biquadratic patch; `hull` is the control-net box, the baseline of the
/// time ratio in `results/surfaces.md`.
fn surfaces(c: &mut Criterion) {
    use nurbs_box::surface::enclose::all_surface_strategies;
    use nurbs_box::surface::gen::random_surface;
    let mut g = c.benchmark_group("surface");
    g.sample_size(10);
    let cases = [
        ("bicubic_4x4", random_surface(77, 3, 3, 0, false)),
        (
            "rational_biquadratic_5x5",
            random_surface(78, 2, 2, 2, true),
        ),
    ];
    for (label, s) in &cases {
        for st in all_surface_strategies(&nurbs_box::enclose::Settings::default()) {
            g.bench_with_input(BenchmarkId::new(st.name(), label), s, |b, s| {
                b.iter(|| st.enclose(black_box(s)))
            });
        }
    }
    g.finish();
}

criterion_group!(
    benches,
    kurbo_side_by_side,
    knot_sweep,
    degree_sweep,
    surfaces
);

fn main() {
    benches();
    ratio_summary();
    Criterion::default().configure_from_args().final_summary();
}
