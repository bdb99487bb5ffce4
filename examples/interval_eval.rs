//! Verified evaluation: enclosures of a point C(u) and of derivatives C^(k)(u), for an exact
//! parameter and for a whole parameter interval.
//!
//! Run: `cargo run --example interval_eval`

use inari::Interval;
use nurbs_box::num::iv;
use nurbs_box::NurbsCurve;

/// `[inf, sup]` per coordinate.
fn show(v: &[Interval]) -> String {
    let parts: Vec<String> = v
        .iter()
        .map(|x| format!("[{}, {}]", x.inf(), x.sup()))
        .collect();
    parts.join(" x ")
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // A cubic B-spline in the plane, domain [0, 1].
    let c = NurbsCurve::new(
        3,
        vec![0., 0., 0., 0., 0.5, 1., 1., 1., 1.],
        vec![
            vec![0., 0.],
            vec![1., 2.],
            vec![2., -1.],
            vec![3., 3.],
            vec![4., 0.],
        ],
        None,
    )?;

    // u = 0.3 is not exactly representable; iv::point takes the f64 nearest to it, and the
    // result is a verified enclosure of C at that f64 (interval de Boor, outward rounding).
    let p = c.enclose_point(iv::point(0.3))?;
    println!("C(0.3) in {}", show(&p));

    // The first and second derivative at the same parameter.
    for k in 1..=2 {
        let d = c.enclose_derivative(iv::point(0.3), k)?;
        println!("C^({k})(0.3) in {}", show(&d));
    }

    // A parameter interval: the result contains C(u) for every u in [0.25, 0.35]
    // (intervals straddling a knot are split there and the pieces hulled).
    let u = iv::span(0.25, 0.35);
    let range = c.enclose_point(u)?;
    println!("C([0.25, 0.35]) in {}", show(&range));

    // Outside the domain is an error, not a guess.
    assert!(c.enclose_point(iv::point(1.5)).is_err());
    Ok(())
}
