//! Properties of cubic spline interpolation (lab course "B-Spline-Kurven") and of the Thomas
//! solver.

use inari::Interval;
use nurbs_box::build::interpolate::{
    interpolate_cubic_with, interpolation_residual, EndCondition, InterpolationOptions,
    Parametrization,
};
use nurbs_box::build::tridiagonal::solve_tridiagonal;
use nurbs_box::num::iv;
use nurbs_box::NurbsCurve;
use proptest::prelude::*;

/// Point sets: 2..12 points in 1..4 dimensions, consecutive points at least 1e-3 apart in the
/// first coordinate (so every parametrisation is defined), coordinates of mixed magnitude.
fn point_sets() -> impl Strategy<Value = Vec<Vec<f64>>> {
    (1usize..4, 2usize..12).prop_flat_map(|(d, n)| {
        prop::collection::vec(
            prop::collection::vec(-100.0f64..100.0, d).prop_map(|mut p| {
                if p[0].abs() < 1e-3 {
                    p[0] = 1e-3;
                }
                p
            }),
            n,
        )
        .prop_map(|mut v| {
            // make consecutive points distinct: accumulate |x| in the first coordinate
            let mut acc = 0.0;
            for p in v.iter_mut() {
                acc += p[0].abs();
                p[0] = acc;
            }
            v
        })
    })
}

fn params_for(dim: usize) -> Vec<Parametrization> {
    Parametrization::ALL
        .into_iter()
        .filter(|p| dim == 2 || *p != Parametrization::Foley)
        .collect()
}

fn scale(points: &[Vec<f64>]) -> f64 {
    points.iter().flatten().fold(1.0f64, |m, x| m.max(x.abs()))
}

/// max over sampled u of |C''(u)| (f64), a scale for "C'' = 0 at the ends".
fn second_derivative_scale(c: &NurbsCurve) -> f64 {
    let (a, b) = c.domain();
    (0..=200)
        .map(|i| {
            let u = (a + (b - a) * i as f64 / 200.0).min(b);
            let d: Vec<f64> = c.derivative(u, 2).unwrap();
            d.iter().fold(0.0f64, |m, x| m.max(x.abs()))
        })
        .fold(f64::MIN_POSITIVE, f64::max)
}

proptest! {
    /// The interpolant passes through every data point: the verified enclosure of C(t̂_j) lies
    /// within a few thousand ulps of the data scale of p_j. (Exact containment cannot hold: the
    /// control points are the rounded solution of the linear system, so the exact curve misses
    /// p_j by about the rounding error of the solve.)
    #[test]
    fn passes_through_data(points in point_sets()) {
        let d = points[0].len();
        for param in params_for(d) {
            let opts = InterpolationOptions { param, ..Default::default() };
            let it = interpolate_cubic_with(&points, &opts).unwrap();
            let r = interpolation_residual(&it.curve, &it.params, &points).unwrap();
            let tol = 1e-12 * scale(&points) * points.len() as f64;
            prop_assert!(r <= tol, "{param}: residual {r} > {tol}");
            for (t, p) in it.params.iter().zip(&points) {
                let enc = it.curve.enclose_point(iv::point(*t)).unwrap();
                for (e, x) in enc.iter().zip(p) {
                    let widened = Interval::try_from((e.inf() - tol, e.sup() + tol)).unwrap();
                    prop_assert!(widened.contains(*x));
                }
            }
        }
    }

    /// Natural end conditions: the enclosure of C'' at both ends contains 0 up to the rounding
    /// of the solve (relative to the size of C'' along the curve).
    #[test]
    fn natural_ends(points in point_sets()) {
        let d = points[0].len();
        for param in params_for(d) {
            let opts = InterpolationOptions { param, ..Default::default() };
            let it = interpolate_cubic_with(&points, &opts).unwrap();
            let c = &it.curve;
            // C'' is of size |p| / dt^2; rounding in the solve perturbs it by eps times that
            let dt = it.params.windows(2).map(|w| w[1] - w[0]).fold(f64::INFINITY, f64::min);
            let s = second_derivative_scale(c) + scale(&points) / (dt * dt);
            let (a, b) = c.domain();
            for u in [a, b] {
                for e in c.enclose_derivative(iv::point(u), 2).unwrap() {
                    prop_assert!(e.mag() <= 1e-10 * s, "{param} C''({u}) = {e:?}, scale {s}");
                }
            }
        }
    }

    /// Prescribed end tangents are met (the enclosure of C' at the ends is within rounding of
    /// the prescribed vector).
    #[test]
    fn end_tangents(points in point_sets(), t0 in -10.0f64..10.0, t1 in -10.0f64..10.0) {
        let d = points[0].len();
        let opts = InterpolationOptions {
            param: Parametrization::Centripetal,
            start: EndCondition::Tangent(vec![t0; d]),
            end: EndCondition::Tangent(vec![t1; d]),
        };
        let it = interpolate_cubic_with(&points, &opts).unwrap();
        let (a, b) = it.curve.domain();
        let tol = 1e-9 * (scale(&points) / (it.params[1] - it.params[0]).min(b - it.params[it.params.len() - 2]) + 10.0);
        for (u, t) in [(a, t0), (b, t1)] {
            for e in it.curve.enclose_derivative(iv::point(u), 1).unwrap() {
                prop_assert!((e.mid() - t).abs() <= tol, "C'({u}) = {e:?}, want {t}");
            }
        }
        prop_assert!(interpolation_residual(&it.curve, &it.params, &points).unwrap()
            <= 1e-12 * scale(&points) * points.len() as f64);
    }

    /// Collinear, equally spaced points give a straight line traversed at constant speed: the
    /// natural spline of linear data is the linear function (uniqueness of the interpolant).
    #[test]
    fn collinear_points_give_a_line(
        origin in prop::collection::vec(-10.0f64..10.0, 2..4),
        step in prop::collection::vec(0.1f64..3.0, 3),
        n in 2usize..15,
    ) {
        let d = origin.len();
        let points: Vec<Vec<f64>> = (0..n)
            .map(|i| (0..d).map(|j| origin[j] + i as f64 * step[j]).collect())
            .collect();
        for param in params_for(d) {
            let opts = InterpolationOptions { param, ..Default::default() };
            let c = interpolate_cubic_with(&points, &opts).unwrap().curve;
            // every control point lies on the line origin + s * step
            for q in c.control_points() {
                let s = (q[0] - origin[0]) / step[0];
                for j in 0..d {
                    prop_assert!((q[j] - origin[j] - s * step[j]).abs() < 1e-11 * (1.0 + n as f64));
                }
            }
            // C'' vanishes along the whole curve (enclosure over the full domain)
            let (a, b) = c.domain();
            let dd = c.enclose_derivative(iv::span(a, b), 2).unwrap();
            let speed: Vec<f64> = c.derivative(a, 1).unwrap();
            let snorm = speed.iter().map(|x| x * x).sum::<f64>().sqrt();
            for e in dd {
                prop_assert!(e.mag() < 1e-9 * snorm * snorm.max(1.0) * n as f64, "{param}: {e:?}");
            }
        }
    }

    /// The Thomas solver agrees with dense Gaussian elimination on random strictly diagonally
    /// dominant tridiagonal systems.
    #[test]
    fn thomas_agrees_with_dense(
        rows in prop::collection::vec((-1.0f64..1.0, -1.0f64..1.0, 0.1f64..2.0, -50.0f64..50.0, -5.0f64..5.0), 1..40),
        sign in prop::bool::ANY,
    ) {
        let n = rows.len();
        let a: Vec<f64> = rows.iter().enumerate().map(|(i, r)| if i == 0 { 0.0 } else { r.0 }).collect();
        let c: Vec<f64> = rows.iter().enumerate().map(|(i, r)| if i + 1 == n { 0.0 } else { r.1 }).collect();
        let s = if sign { 1.0 } else { -1.0 };
        let b: Vec<f64> = (0..n).map(|i| s * (a[i].abs() + c[i].abs() + rows[i].2)).collect();
        let mut rhs: Vec<f64> = rows.iter().flat_map(|r| [r.3, r.4]).collect();
        let dense = dense_solve(&a, &b, &c, &rhs, 2);
        solve_tridiagonal(&a, &b, &c, &mut rhs, 2).unwrap();
        let xs = dense.iter().fold(1.0f64, |m, x| m.max(x.abs()));
        for (x, y) in rhs.iter().zip(&dense) {
            prop_assert!((x - y).abs() <= 1e-12 * xs, "{x} vs {y}");
        }
    }
}

/// Gaussian elimination with partial pivoting on the dense matrix (test reference only).
fn dense_solve(a: &[f64], b: &[f64], c: &[f64], rhs: &[f64], ncols: usize) -> Vec<f64> {
    let n = b.len();
    let w = n + ncols;
    let mut m = vec![0.0; n * w];
    for i in 0..n {
        m[i * w + i] = b[i];
        if i > 0 {
            m[i * w + i - 1] = a[i];
        }
        if i + 1 < n {
            m[i * w + i + 1] = c[i];
        }
        for j in 0..ncols {
            m[i * w + n + j] = rhs[i * ncols + j];
        }
    }
    for k in 0..n {
        let piv = (k..n)
            .max_by(|&x, &y| m[x * w + k].abs().total_cmp(&m[y * w + k].abs()))
            .unwrap();
        for j in 0..w {
            m.swap(k * w + j, piv * w + j);
        }
        for i in k + 1..n {
            let f = m[i * w + k] / m[k * w + k];
            for j in k..w {
                m[i * w + j] -= f * m[k * w + j];
            }
        }
    }
    let mut x = vec![0.0; n * ncols];
    for col in 0..ncols {
        for i in (0..n).rev() {
            let mut s = m[i * w + n + col];
            for j in i + 1..n {
                s -= m[i * w + j] * x[j * ncols + col];
            }
            x[i * ncols + col] = s / m[i * w + i];
        }
    }
    x
}
