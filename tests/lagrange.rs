//! Lagrange interpolation curves (the lecture 'Modellierung mit Kurven'): interpolation,
//! affine invariance, closed-form Bernstein coefficients, and the guarantee of the conversion
//! to a Bézier curve: |c_j(t) - curve_j(t)| <= radius[j], so a widened verified box of the
//! f64 curve encloses the exact Lagrange curve (checked against MPFR). Runge's example and the
//! `interpolate --basis lagrange` command.

use inari::Interval;
use nurbs_box::build::interpolate::{interpolate_cubic, Parametrization};
use nurbs_box::build::lagrange::{widen_enclosure, LagrangeCurve};
use nurbs_box::enclose::strategy_by_name;
use nurbs_box::num::iv;
use proptest::prelude::*;

mod common;
use common::config;

/// 2..=13 points in 1..=3 dimensions, consecutive points apart (first coordinate increasing).
fn point_sets() -> impl Strategy<Value = Vec<Vec<f64>>> {
    (1usize..=3, 2usize..=13).prop_flat_map(|(d, n)| {
        prop::collection::vec(prop::collection::vec(-10.0f64..10.0, d), n).prop_map(|mut v| {
            let mut acc = 0.0;
            for p in v.iter_mut() {
                acc += 0.1 + p[0].abs();
                p[0] = acc;
            }
            v
        })
    })
}

const RULES: [Parametrization; 3] = [
    Parametrization::Uniform,
    Parametrization::Chordal,
    Parametrization::Centripetal,
];

fn runge(n: usize) -> Vec<Vec<f64>> {
    (0..n)
        .map(|i| {
            let x = -1.0 + 2.0 * i as f64 / (n - 1) as f64;
            vec![x, 1.0 / (1.0 + 25.0 * x * x)]
        })
        .collect()
}

proptest! {
    #![proptest_config(config(64))]

    /// Interpolation and affine invariance of the evaluation (product and barycentric forms),
    /// and the conversion: the verified enclosure of the f64 Bézier curve at u_i, widened by
    /// the radius, contains q_i; at random t it meets the interval evaluation of the Lagrange
    /// curve (both enclose the exact value, unless the conversion is wrong).
    #[test]
    fn conversion_interpolates_and_agrees(points in point_sets(), ts in prop::collection::vec(0.0f64..1.0, 8)) {
        let d = points[0].len();
        for rule in RULES {
            let lc = LagrangeCurve::interpolate(&points, rule).unwrap();
            let lb = lc.to_bezier().unwrap();
            let (a, b) = lc.domain();
            prop_assert_eq!(lb.curve.domain(), (a, b));
            prop_assert_eq!(lb.curve.degree(), points.len() - 1);
            let widen = |e: Vec<Interval>| -> Vec<Interval> {
                e.iter().zip(&lb.radius).map(|(x, &r)| *x + iv::span(-r, r)).collect()
            };
            for (u, q) in lc.params().iter().zip(&points) {
                let e = widen(lb.curve.enclose_point(iv::point(*u)).unwrap());
                for j in 0..d {
                    prop_assert!(e[j].contains(q[j]), "{rule}: c({u}) = {:?} misses {}", e[j], q[j]);
                }
                // exact at the nodes
                prop_assert_eq!(&lc.eval::<f64>(u), q);
            }
            for &s in &ts {
                let t = a + (b - a) * s;
                let basis = lc.basis(&iv::point(t));
                let sum = basis.iter().fold(iv::point(0.0), |acc, x| acc + *x);
                prop_assert!(sum.contains(1.0), "sum of the basis {:?}", sum);
                let exact = lc.eval(&iv::point(t));
                let conv = widen(lb.curve.enclose_point(iv::point(t)).unwrap());
                for j in 0..d {
                    prop_assert!(!exact[j].intersection(conv[j]).is_empty(),
                        "{rule}: t={t}: Lagrange {:?} vs converted {:?}", exact[j], conv[j]);
                    let f: Vec<f64> = lc.eval(&t);
                    prop_assert!(exact[j].inf() - 1e-9 <= f[j] && f[j] <= exact[j].sup() + 1e-9);
                }
            }
            // the same conversion in f64 interval arithmetic encloses the same coefficients
            let li = lc.to_bezier_with::<Interval>().unwrap();
            for (x, y) in li.coefficients.pts.iter().zip(&lb.coefficients.pts) {
                prop_assert!(!x.intersection(*y).is_empty(), "{rule}: {:?} vs {:?}", x, y);
            }
            // the radius is rounding, not slack: tiny against the coefficients
            let cmax = lb.curve.points_flat().iter().fold(1.0f64, |m, x| m.max(x.abs()));
            for &r in &lb.radius {
                prop_assert!(r <= 1e-11 * cmax, "{rule}: radius {r} vs coefficients {cmax}");
            }
        }
    }

    /// Affine invariance (the lecture: the basis sums to one): the curve through A q_i + v is
    /// A c(t) + v, here with a 2-D rotation-shear and a shift.
    #[test]
    fn affine_invariance(points in point_sets(), t in 0.0f64..1.0) {
        let pts2: Vec<Vec<f64>> = points.iter().map(|p| vec![p[0], p.get(1).copied().unwrap_or(0.5)]).collect();
        let m = [[0.6, -0.8], [0.3, 1.7]];
        let v = [3.0, -2.0];
        let f = |p: &[f64]| vec![m[0][0] * p[0] + m[0][1] * p[1] + v[0], m[1][0] * p[0] + m[1][1] * p[1] + v[1]];
        let moved: Vec<Vec<f64>> = pts2.iter().map(|p| f(p)).collect();
        let params: Vec<f64> = (0..pts2.len()).map(|i| i as f64).collect();
        let lc = LagrangeCurve::new(params.clone(), &pts2).unwrap();
        let lm = LagrangeCurve::new(params, &moved).unwrap();
        let tt = t * (pts2.len() - 1) as f64;
        let a = f(&lc.eval::<f64>(&tt));
        let b = lm.eval::<f64>(&tt);
        let sc = moved.iter().flatten().fold(1.0f64, |s, x| s.max(x.abs()));
        let growth = 2f64.powi(pts2.len() as i32);
        for j in 0..2 {
            prop_assert!((a[j] - b[j]).abs() <= 1e-12 * sc * growth, "{} vs {}", a[j], b[j]);
        }
    }
}

/// Data from the polynomial (t, t^2 - 3t) at t = 0, 1, ..., g are reproduced: the Bernstein
/// coefficients over [0, g] are closed-form, x_l = g l / g = l and, with t^2 = g^2 s^2 and
/// s^2 = sum l (l - 1) / (g (g - 1)) B_l, y_l = g l (l - 1) / (g - 1) - 3 l. The enclosures
/// must contain them and the f64 curve must be within the radius.
#[test]
fn polynomial_data_give_closed_form_coefficients() {
    for g in 2..=16usize {
        let pts: Vec<Vec<f64>> = (0..=g)
            .map(|i| {
                let t = i as f64;
                vec![t, t * t - 3.0 * t]
            })
            .collect();
        let lc = LagrangeCurve::interpolate(&pts, Parametrization::Uniform).unwrap();
        let lb = lc.to_bezier().unwrap();
        for l in 0..=g {
            let (gf, lf) = (g as f64, l as f64);
            let want = [lf, gf * lf * (lf - 1.0) / (gf - 1.0) - 3.0 * lf];
            for (j, &w) in want.iter().enumerate() {
                let enc = lb.coefficients.pts[l * 2 + j];
                let got = lb.curve.control_point(l)[j];
                assert!(
                    enc.inf() - 1e-9 <= w && w <= enc.sup() + 1e-9,
                    "g={g} l={l} j={j}: {enc:?} vs {w}"
                );
                assert!((got - w).abs() <= lb.radius[j] + 1e-12 * (1.0 + w.abs()));
            }
        }
    }
    // small exact case: every coefficient exact, radius 0
    let lc = LagrangeCurve::new(vec![0., 1., 2.], &[vec![0.], vec![1.], vec![0.]]).unwrap();
    let lb = lc.to_bezier().unwrap();
    assert_eq!(lb.curve.points_flat(), &[0., 2., 0.]);
    assert_eq!(lb.radius, vec![0.0]);
}

/// Runge's example: the Lagrange curve through 11 equidistant samples of 1 / (1 + 25 x^2)
/// overshoots to about 1.9 near x = ±0.96 (the lecture's warning), while the natural cubic
/// spline stays near [1/26, 1]. Boxes: verified (newton), Lagrange widened by its radius.
#[test]
fn runge_overshoots_and_the_spline_does_not() {
    let newton = strategy_by_name("newton", None).unwrap();
    let pts = runge(11);
    let lb = LagrangeCurve::interpolate(&pts, Parametrization::Uniform)
        .unwrap()
        .to_bezier()
        .unwrap();
    let e = lb.enclose(newton.as_ref());
    assert!(e.verified);
    let y = &e.coords[1];
    assert!(y.hi > 1.9 && y.hi < 2.0, "Lagrange max {}", y.hi);
    assert!(y.lo < -0.2, "Lagrange min {}", y.lo);
    // x(t) is linear in t (Lagrange reproduces linear data): the x box is [-1, 1]
    assert!((e.coords[0].lo + 1.0).abs() < 1e-12 && (e.coords[0].hi - 1.0).abs() < 1e-12);
    let sp = interpolate_cubic(&pts, Parametrization::Uniform).unwrap();
    let es = newton.enclose(&sp);
    assert!(
        es.coords[1].hi < 1.01 && es.coords[1].lo > 0.0,
        "{:?}",
        es.coords[1]
    );
    // widening by zero changes nothing; by r moves every bound by at least r
    assert_eq!(widen_enclosure(&es, &[0.0, 0.0]), es);
    let w = widen_enclosure(&es, &[0.5, 0.25]);
    assert!(w.coords[1].hi >= es.coords[1].hi + 0.25 && w.coords[1].lo <= es.coords[1].lo - 0.25);
    assert!(w.coords[1].inner_hi <= es.coords[1].inner_hi - 0.25);
}

#[cfg(feature = "mpfr")]
mod mpfr {
    use super::*;
    use rug::Float;

    /// At MPFR samples, the exact Lagrange curve (barycentric form at 256 bits) and the f64
    /// Bézier curve (de Boor at 256 bits) differ by at most the radius, and the widened
    /// verified box of the f64 curve contains the exact Lagrange curve; also for Runge's
    /// example with 21 points, whose coefficients are large.
    fn check(lc: &LagrangeCurve) {
        let lb = lc.to_bezier().unwrap();
        let newton = strategy_by_name("newton", None).unwrap();
        let e = lb.enclose(newton.as_ref());
        let (a, b) = lc.domain();
        let d = lc.dim();
        let mut worst = vec![0.0f64; d];
        for i in 0..=400 {
            let t = (a + (b - a) * i as f64 / 400.0).min(b);
            let exact = lc.eval(&Float::with_val(256, t));
            let conv: Vec<Float> = lb.curve.point(t).unwrap();
            for j in 0..d {
                let diff = Float::with_val(256, &exact[j] - &conv[j]).abs().to_f64();
                worst[j] = worst[j].max(diff);
                assert!(
                    diff <= lb.radius[j] + 1e-60,
                    "t={t} j={j}: |c - curve| = {diff} > radius {}",
                    lb.radius[j]
                );
                let lo = Float::with_val(256, e.coords[j].lo);
                let hi = Float::with_val(256, e.coords[j].hi);
                assert!(
                    lo <= exact[j] && exact[j] <= hi,
                    "t={t} j={j}: outside the box"
                );
            }
        }
        // the exact curve reaches the widened inner bounds up to the sampling resolution
        let _ = worst;
    }

    proptest! {
        #![proptest_config(config(32))]
        #[test]
        fn widened_box_encloses_the_exact_lagrange_curve(points in point_sets(), rule in 0usize..3) {
            check(&LagrangeCurve::interpolate(&points, RULES[rule]).unwrap());
        }
    }

    #[test]
    fn runge_21_points_against_mpfr() {
        for n in [11, 15, 21] {
            let lc = LagrangeCurve::interpolate(&runge(n), Parametrization::Uniform).unwrap();
            check(&lc);
            // chordal parameters: the radius is non-zero there (inexact differences)
            let lc = LagrangeCurve::interpolate(&runge(n), Parametrization::Chordal).unwrap();
            assert!(lc.to_bezier().unwrap().radius.iter().any(|&r| r > 0.0));
            check(&lc);
        }
    }
}

// ---- `nurbs-box interpolate --basis lagrange` ----

fn run(args: &[&str], stdin: &str) -> (i32, String, String) {
    common::run_bin(args, stdin.as_bytes())
}

#[test]
fn cli_lagrange_pipes_into_enclose_with_a_radius_report() {
    let sets = format!(
        "{}\n[[0,0]]\n{}\n",
        serde_json::to_string(&runge(11)).unwrap(),
        serde_json::to_string(&runge(5)).unwrap()
    );
    let dir = std::env::temp_dir().join(format!("nurbs-box-lag-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let rep = dir.join("report.jsonl");
    let (code, curves, err) = run(
        &[
            "interpolate",
            "--basis",
            "lagrange",
            "--param",
            "uniform",
            "--report",
            rep.to_str().unwrap(),
        ],
        &sets,
    );
    // a single point (degree 0) is no curve: error record for set 1, exit 1
    assert_eq!(code, 1, "{err}");
    let e: serde_json::Value = serde_json::from_str(err.trim()).unwrap();
    assert_eq!(e["index"], 1);
    assert_eq!(e["error"]["kind"], "too_few_points");
    let lines: Vec<&str> = curves.lines().collect();
    assert_eq!(lines.len(), 2);
    let c0 = nurbs_box::parse_curve(lines[0].as_bytes()).unwrap();
    assert_eq!(c0.degree(), 10);
    // the written curve is the library's conversion, bit for bit
    let lb = LagrangeCurve::interpolate(&runge(11), Parametrization::Uniform)
        .unwrap()
        .to_bezier()
        .unwrap();
    assert_eq!(c0, lb.curve);
    let reports: Vec<serde_json::Value> = std::fs::read_to_string(&rep)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(reports.len(), 2);
    assert_eq!(reports[0]["index"], 0);
    assert_eq!(reports[1]["index"], 2);
    assert_eq!(reports[0]["basis"], "lagrange");
    assert_eq!(reports[0]["degree"], 10);
    let radius: Vec<f64> = reports[0]["coefficient_radius"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert_eq!(radius, lb.radius);
    // enclose accepts the stream; Runge's overshoot shows in the y box
    let (code, boxes, _) = run(&["enclose"], &curves);
    assert_eq!(code, 0);
    let b0: serde_json::Value = serde_json::from_str(boxes.lines().next().unwrap()).unwrap();
    assert_eq!(b0["verified"], true);
    assert!(b0["hi"][1].as_f64().unwrap() > 1.5);
    // the cubic spline of the same data (default basis) does not overshoot
    let (code, cubic, _) = run(
        &["interpolate", "--param", "uniform"],
        &sets[..sets.find('\n').unwrap()],
    );
    assert_eq!(code, 0);
    let (_, boxes, _) = run(&["enclose"], &cubic);
    let bc: serde_json::Value = serde_json::from_str(boxes.trim()).unwrap();
    assert!(bc["hi"][1].as_f64().unwrap() < 1.01);
    // bad basis: usage error
    assert_eq!(run(&["interpolate", "--basis", "hermite"], "").0, 2);
    let _ = std::fs::remove_dir_all(&dir);
}
