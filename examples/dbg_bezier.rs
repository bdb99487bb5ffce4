use nurbs_box::enclose::{BezierSubdivision, BoxEncloser};
use std::time::Instant;
fn main() {
    let p: usize = std::env::args().nth(1).map_or(11, |s| s.parse().unwrap());
    let c = nurbs_box::gen::thesis_curve_2d_nurbs_with(21, p, 5).unwrap();
    let s = BezierSubdivision::default();
    let t = Instant::now();
    let e = s.enclose(&c);
    println!("{} {:?}", s.name(), t.elapsed());
    for cb in &e.coords {
        println!(
            "  [{:e}, {:e}] inner [{:e}, {:e}] {:?} {:?}",
            cb.lo, cb.hi, cb.inner_lo, cb.inner_hi, cb.stats, cb.termination
        );
        for x in cb.argmin.iter().chain(&cb.argmax) {
            println!("     {:?}", x);
        }
    }
}
