//! Runge's example, f(x) = 1 / (1 + 25 x^2) on [-1, 1]: verified boxes of the Lagrange curve
//! (the lecture 'Modellierung mit Kurven': "Vorsicht: bei vielen Knoten kommt es bei der
//! Lagrange-Interpolation zu Überschwingen") next to those of the natural cubic spline through
//! the same points, for a growing number of equidistant samples; Chebyshev samples
//! x_i = -cos(i pi / g) as the classical remedy.
//!
//! Points (x_i, f(x_i)) as a 2-D curve with uniform parameters, exactly what
//! `nurbs-box interpolate --param uniform [--basis lagrange]` builds (for equidistant x_i the
//! Lagrange curve is then the graph of the interpolating polynomial; the Chebyshev rows use
//! the parameters t_i = x_i, i.e. the polynomial interpolant itself). Boxes by the `newton`
//! strategy; the Lagrange boxes are widened by the conversion radius, so they are verified
//! boxes of the exact Lagrange curves.
//!
//! Run: `cargo run --release --bin runge` (writes `results/runge.md`; `--out PATH` to
//! write elsewhere, `-` for stdout).

use nurbs_box::build::interpolate::{interpolate_cubic, Parametrization};
use nurbs_box::build::lagrange::LagrangeCurve;
use nurbs_box::enclose::{strategy_by_name, CoordBox};
use nurbs_box::testkit::report::Provenance;
use std::fmt::Write as _;

fn f(x: f64) -> f64 {
    1.0 / (1.0 + 25.0 * x * x)
}

fn fmt_box(c: &CoordBox) -> String {
    format!("[{:.6}, {:.6}]", c.lo, c.hi)
}

/// (above, below): how far the outer box leaves the data range [1/26, 1] of f.
fn overshoot(c: &CoordBox, lo: f64, hi: f64) -> (f64, f64) {
    ((c.hi - hi).max(0.0), (lo - c.lo).max(0.0))
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let out = args
        .iter()
        .position(|a| a == "--out")
        .and_then(|i| args.get(i + 1))
        .cloned()
        .unwrap_or_else(|| "results/runge.md".into());
    let prov = Provenance::collect();
    let newton = strategy_by_name("newton", None).expect("newton strategy");
    let (fmin, fmax) = (f(1.0), f(0.0));
    let mut md = String::new();
    writeln!(md, "# Runge's example: Lagrange curve vs cubic spline\n").unwrap();
    writeln!(md, "{}\n", prov.line()).unwrap();
    writeln!(
        md,
        "f(x) = 1/(1 + 25 x^2) sampled at n points of [-1, 1]; the curve through (x_i, f(x_i)) \
         with uniform parameters. y-boxes are verified outer boxes (`newton`; Lagrange widened \
         by the conversion radius r_y). The data range is [1/26, 1] = [{fmin:.6}, {fmax:.6}]; \
         'overshoot' is how far the box leaves it (above / below).\n"
    )
    .unwrap();
    writeln!(
        md,
        "| n | Lagrange y-box | Lagrange overshoot | r_y | cubic spline y-box | spline overshoot | Lagrange, Chebyshev x_i: y-box |"
    )
    .unwrap();
    writeln!(md, "|--:|---|---|--:|---|---|---|").unwrap();
    for n in [5usize, 7, 9, 11, 13, 15, 17, 19, 21] {
        let pts: Vec<Vec<f64>> = (0..n)
            .map(|i| {
                let x = -1.0 + 2.0 * i as f64 / (n - 1) as f64;
                vec![x, f(x)]
            })
            .collect();
        let lb = LagrangeCurve::interpolate(&pts, Parametrization::Uniform)
            .and_then(|l| l.to_bezier())
            .expect("Lagrange curve");
        let el = lb.enclose(newton.as_ref());
        assert!(el.verified);
        let sp = interpolate_cubic(&pts, Parametrization::Uniform).expect("cubic spline");
        let es = newton.enclose(&sp);
        let g = (n - 1) as f64;
        let cheb: Vec<Vec<f64>> = (0..n)
            .map(|i| {
                let x = -(std::f64::consts::PI * i as f64 / g).cos();
                vec![x, f(x)]
            })
            .collect();
        let params: Vec<f64> = cheb.iter().map(|p| p[0]).collect();
        let ec = LagrangeCurve::new(params, &cheb)
            .and_then(|l| l.to_bezier())
            .expect("Chebyshev Lagrange curve")
            .enclose(newton.as_ref());
        let (la, lbw) = overshoot(&el.coords[1], fmin, fmax);
        let (sa, sb) = overshoot(&es.coords[1], fmin, fmax);
        writeln!(
            md,
            "| {n} | {} | {la:.4} / {lbw:.4} | {:.1e} | {} | {sa:.4} / {sb:.4} | {} |",
            fmt_box(&el.coords[1]),
            lb.radius[1],
            fmt_box(&es.coords[1]),
            fmt_box(&ec.coords[1]),
        )
        .unwrap();
    }
    if out == "-" {
        print!("{md}");
    } else {
        std::fs::write(&out, &md).unwrap_or_else(|e| panic!("cannot write {out}: {e}"));
        print!("{md}");
        eprintln!("wrote {out}");
    }
}
