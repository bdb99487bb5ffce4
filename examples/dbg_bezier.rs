use nurbs_box::enclose::{BezierSubdivision, BoxEncloser, ControlHull};
use nurbs_box::NurbsCurve;
use std::time::Instant;
fn main() {
    let c = NurbsCurve::new(
        3,
        vec![0., 0., 0., 0., 1., 1., 1., 1.],
        vec![
            vec![10., -50.],
            vec![90., 30.],
            vec![-70., 40.],
            vec![20., -10.],
        ],
        None,
    )
    .unwrap();
    for s in [
        &BezierSubdivision::default() as &dyn BoxEncloser,
        &ControlHull,
    ] {
        let t = Instant::now();
        let e = s.enclose(&c);
        println!("{} {:?}", s.name(), t.elapsed());
        for cb in &e.coords {
            println!(
                "  [{:e}, {:e}] inner [{:e}, {:e}] {:?} {:?}",
                cb.lo, cb.hi, cb.inner_lo, cb.inner_hi, cb.stats, cb.termination
            );
        }
    }
}
