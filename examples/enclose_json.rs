//! Parse a curve from JSON text, enclose it with the interval Newton strategy, and print the
//! verified bounds per coordinate.
//!
//! Run: `cargo run --example enclose_json`

use nurbs_box::{parse_curve, strategy_by_name};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // A rational cubic in the plane (the curve format of docs/formats.md).
    let json = r#"{"degree": 3,
        "knots": [0, 0, 0, 0, 0.5, 1, 1, 1, 1],
        "control_points": [[0, 0], [1, 2], [2, -1], [3, 3], [4, 0]],
        "weights": [1, 1, 2, 1, 1]}"#;
    let curve = parse_curve(json.as_bytes())?;

    // `None`: the strategy's own tolerance. The names are in `nurbs_box::enclose::STRATEGY_NAMES`.
    let newton = strategy_by_name("newton", None).ok_or("the newton strategy is not built in")?;
    let e = newton.enclose(&curve);

    println!("strategy {}, verified: {}", e.strategy, e.verified);
    for (j, c) in e.coords.iter().enumerate() {
        // The exact minimum of coordinate j lies in [lo, inner_lo], the maximum in
        // [inner_hi, hi]: the curve stays within [lo, hi] and provably reaches inner_lo and
        // inner_hi. gap() bounds how much the outer box can overestimate.
        println!(
            "x{j}: outer [{}, {}], inner [{}, {}], certified gap {:e}, termination {:?}",
            c.lo,
            c.hi,
            c.inner_lo,
            c.inner_hi,
            c.gap(),
            c.termination
        );
    }
    println!("overall termination: {:?}", e.termination());
    Ok(())
}
