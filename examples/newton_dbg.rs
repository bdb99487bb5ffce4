use nurbs_box::enclose::{BezierSubdivision, BoxEncloser, Newton, SearchRegion};
use nurbs_box::NurbsCurve;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::time::Instant;
include!("/tmp/gen.rs");
fn main() {
    let strats: Vec<Box<dyn BoxEncloser>> = vec![
        Box::new(Newton::default()),
        Box::new(Newton::thesis()),
        Box::new(SearchRegion::verified(Newton::default())),
    ];
    let mut tot = [std::time::Duration::ZERO; 3];
    for seed in 0..60u64 {
        let c = random_curve(seed ^ 0x5eed);
        let mut line = format!(
            "seed {seed} p={} n={} d={} rat={}",
            c.degree(),
            c.num_points(),
            c.dim(),
            c.is_rational()
        );
        for (si, s) in strats.iter().enumerate() {
            let t = Instant::now();
            let e = s.enclose(&c);
            let el = t.elapsed();
            tot[si] += el;
            line += &format!(" | {} {:?} {:?}", s.name(), el, e.termination());
        }
        if line.contains("ms ") || line.contains("s |") {
            println!("{line}");
        }
    }
    println!("totals {tot:?}");
}
