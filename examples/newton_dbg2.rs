use nurbs_box::enclose::{BoxEncloser, Newton};
use nurbs_box::NurbsCurve;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
include!("/tmp/gen.rs");
fn main() {
    let seed: u64 = std::env::args().nth(1).unwrap().parse().unwrap();
    let thesis = std::env::args().nth(2).is_some();
    let c = random_curve(seed);
    println!(
        "knots {:?}\npts {:?}\nw {:?}",
        c.knots(),
        c.control_points(),
        c.weights()
    );
    let n = if thesis {
        Newton::thesis()
    } else {
        Newton::default()
    };
    let e = n.enclose(&c);
    for cb in &e.coords {
        println!(
            "[{:e},{:e}] inner [{:e},{:e}] {:?} {:?} argmin {} argmax {}",
            cb.lo,
            cb.hi,
            cb.inner_lo,
            cb.inner_hi,
            cb.stats,
            cb.termination,
            cb.argmin.len(),
            cb.argmax.len()
        );
        for x in cb.argmin.iter().take(3) {
            println!("  {:?}", x);
        }
    }
}
