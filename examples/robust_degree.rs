//! Probe: high degree / many points: time and soundness per strategy.
use nurbs_box::enclose::all_strategies;
use nurbs_box::robust::check_enclosure;
use nurbs_box::validate::dense_params;
use nurbs_box::NurbsCurve;
use std::time::Instant;

fn wiggly(p: usize, n: usize, dim: usize, rational: bool) -> NurbsCurve {
    let npts = n;
    let m = npts + p;
    let ni = npts - p - 1;
    let knots: Vec<f64> = (0..=m)
        .map(|i| (i.saturating_sub(p).min(ni + 1)) as f64 / (ni + 1) as f64)
        .collect();
    let pts: Vec<Vec<f64>> = (0..npts)
        .map(|i| {
            (0..dim)
                .map(|j| ((i * 7 + j * 3) % 11) as f64 - 5.0 + (i as f64 * 0.37).sin())
                .collect()
        })
        .collect();
    let w = rational.then(|| (0..npts).map(|i| 1.0 + (i % 3) as f64).collect());
    NurbsCurve::new(p, knots, pts, w).unwrap()
}

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .map(|s| s.parse().unwrap())
        .collect();
    let (p, n, dim, rat) = (args[0], args[1], args[2], args[3] == 1);
    let c = wiggly(p, n, dim, rat);
    let params = dense_params(&c, 2);
    let only = std::env::var("STRAT").ok();
    for s in all_strategies(None)
        .into_iter()
        .filter(|s| only.as_deref().is_none_or(|o| o == s.name()))
    {
        let t = Instant::now();
        let e = s.enclose(&c);
        let dt = t.elapsed().as_secs_f64();
        let r = check_enclosure(&c, &e, s.guarantee(), &params);
        println!(
            "p={p} n={n} {} t={dt:.3} term={:?} ok={:?} lo0={:e} hi0={:e} gap={:e}",
            s.name(),
            e.termination(),
            r.err(),
            e.coords[0].lo,
            e.coords[0].hi,
            e.coords[0].gap()
        );
        println!("  stats {:?}", e.stats());
    }
}
