//! Probe: every strategy on extreme curves; containment, finiteness, time.
use nurbs_box::enclose::{all_strategies, Guarantee};
use nurbs_box::gen::{self, Family, GenParams, KnotStyle};
use nurbs_box::validate::{check_containment, dense_params};
use nurbs_box::NurbsCurve;
use std::time::Instant;

fn run(name: &str, c: &NurbsCurve) {
    for s in all_strategies(None) {
        let t = Instant::now();
        let e = s.enclose(c);
        let dt = t.elapsed().as_secs_f64();
        let cc = check_containment(c, &e, &dense_params(c, 20));
        let fin = e
            .coords
            .iter()
            .all(|b| b.lo.is_finite() && b.hi.is_finite());
        if s.guarantee() == Guarantee::Verified && (!cc.misses.is_empty() || !fin || dt > 0.5) {
            println!(
                "{name} {} misses={} finite={fin} t={dt:.3} lo={:?} hi={:?} term={:?}",
                s.name(),
                cc.misses.len(),
                e.lo(),
                e.hi(),
                e.termination()
            );
        }
    }
}

fn main() {
    let n: u64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(200);
    for seed in 0..n {
        let mut r = gen::rng(seed);
        let (f, c) = gen::nasty_curve(&mut r);
        run(&format!("seed{seed}:{}", f.name()), &c);
    }
    // combos
    for seed in 0..n {
        let mut r = gen::rng(seed);
        let p = GenParams {
            coord_log10: (-300.0, 300.0),
            rational: 1.0,
            weight_log10: (-6.0, 6.0),
            degree: 1..=12,
            dim: 1..=10,
            knot_styles: vec![
                KnotStyle::Clustered,
                KnotStyle::Unclamped,
                KnotStyle::Multiple,
            ],
            flat: 0.3,
            symmetric: 0.2,
            ..GenParams::default()
        };
        let c = gen::random_curve(&mut r, &p);
        run(&format!("combo{seed}"), &c);
    }
    let _ = Family::ALL;
}
