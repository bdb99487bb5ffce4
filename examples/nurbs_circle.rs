//! The unit circle as a rational quadratic NURBS curve (nine control points, the Piegl &
//! Tiller construction), enclosed by every registered strategy: each verified box is
//! [-1, 1]^2 up to its certified gap.
//!
//! Run: `cargo run --example nurbs_circle`

use nurbs_box::{all_strategies, NurbsCurve};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // Four quarter arcs; the corner points have weight sqrt(2)/2.
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let circle = NurbsCurve::new(
        2,
        vec![0., 0., 0., 1., 1., 2., 2., 3., 3., 4., 4., 4.],
        vec![
            vec![1., 0.],
            vec![1., 1.],
            vec![0., 1.],
            vec![-1., 1.],
            vec![-1., 0.],
            vec![-1., -1.],
            vec![0., -1.],
            vec![1., -1.],
            vec![1., 0.],
        ],
        Some(vec![1., w, 1., w, 1., w, 1., w, 1.]),
    )?;

    for s in all_strategies(None) {
        let e = s.enclose(&circle);
        // How far the outer box lies outside [-1, 1]^2, and the certified gap (an upper bound
        // on the overestimation, from the inner bounds the curve provably reaches).
        let excess = e
            .coords
            .iter()
            .map(|c| (-1.0 - c.lo).abs().max((c.hi - 1.0).abs()))
            .fold(0.0, f64::max);
        let gap = e.coords.iter().map(|c| c.gap()).fold(0.0, f64::max);
        println!(
            "{:>22} ({:?}): box [{}, {}] x [{}, {}], off [-1,1]^2 by {excess:.1e}, gap {gap:.1e}",
            e.strategy,
            s.guarantee(),
            e.coords[0].lo,
            e.coords[0].hi,
            e.coords[1].lo,
            e.coords[1].hi,
        );
        if e.verified {
            // The exact box [-1, 1]^2 lies inside the outer box, and the outer box is within
            // the gap of it.
            for c in &e.coords {
                assert!(c.lo <= -1.0 && c.hi >= 1.0);
                assert!(-1.0 - c.lo <= c.gap() && c.hi - 1.0 <= c.gap());
            }
        }
    }
    Ok(())
}
