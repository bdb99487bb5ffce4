//! Cubic B-spline interpolation through points p_0 .. p_m in any dimension (lab course
//! "B-Spline-Kurven", sec. 2.3-2.4): data parameters by the uniform, chordal, centripetal or Foley
//! rule, knots t_{i+3} = t̂_i with clamped ends, natural end conditions (C'' = 0) or prescribed end
//! tangents, and the tridiagonal system solved by the Thomas algorithm.
//!
//! The construction runs in f64 and is not exact: the result is *a* curve (a valid
//! [`NurbsCurve`]) that passes through the data up to rounding in the solve. Every guarantee
//! of the crate is about that curve as given; [`interpolation_residual`] bounds, verified,
//! how far it actually misses the data.

use crate::build::knot_vectors::interpolation_knots;
use crate::build::tridiagonal::{solve_tridiagonal, TridiagonalError};
use crate::error::{CurveError, EvalError};
use crate::num::iv;
use crate::spline::curve::NurbsCurve;
use crate::spline::eval::CurveEval;
use inari::Interval;
use std::fmt;
use std::str::FromStr;
use thiserror::Error;

/// How the data parameters t̂_0 < ... < t̂_m are chosen (lab course "B-Spline-Kurven", sec. 2.3).
/// t̂_0 = 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Parametrization {
    /// t̂_i = i ("äquidistant"). Allows repeated consecutive points.
    Uniform,
    /// t̂_{i+1} - t̂_i = |p_{i+1} - p_i| (eq. 5), approximating arc length.
    #[default]
    Chordal,
    /// t̂_{i+1} - t̂_i = sqrt|p_{i+1} - p_i| (eq. 6).
    Centripetal,
    /// Foley's rule (eq. 7) with the chordal metric d_i = |p_{i+1} - p_i| in place of Nielson's
    /// (the simplification the source allows): the chord lengths are enlarged by the turning
    /// angles at both ends. Plane curves only.
    Foley,
}

impl Parametrization {
    /// All rules, in the order of the source.
    pub const ALL: [Parametrization; 4] = [
        Parametrization::Uniform,
        Parametrization::Chordal,
        Parametrization::Centripetal,
        Parametrization::Foley,
    ];

    /// The command-line name (`uniform`, `chordal`, `centripetal`, `foley`).
    pub fn name(self) -> &'static str {
        match self {
            Parametrization::Uniform => "uniform",
            Parametrization::Chordal => "chordal",
            Parametrization::Centripetal => "centripetal",
            Parametrization::Foley => "foley",
        }
    }
}

impl fmt::Display for Parametrization {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Parametrization {
    type Err = InterpolateError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Parametrization::ALL
            .into_iter()
            .find(|p| p.name() == s)
            .ok_or_else(|| InterpolateError::UnknownParametrization(s.to_string()))
    }
}

/// The condition imposed at one end of the interpolant (lab course "B-Spline-Kurven", sec. 2.3: the
/// two missing equations).
#[derive(Debug, Clone, PartialEq, Default)]
pub enum EndCondition {
    /// C'' = 0 at this end (natural spline, eq. 13).
    #[default]
    Natural,
    /// C' equals this vector at this end (with respect to the data parameters t̂).
    Tangent(Vec<f64>),
}

/// Options of [`interpolate_cubic_with`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct InterpolationOptions {
    /// parameter rule
    pub param: Parametrization,
    /// condition at t̂_0
    pub start: EndCondition,
    /// condition at t̂_m
    pub end: EndCondition,
}

/// Why points could not be interpolated. Every variant names the offending position.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum InterpolateError {
    /// Fewer than two points.
    #[error("points: at least 2 points are needed, got {got}")]
    TooFewPoints {
        /// number of points given
        got: usize,
    },
    /// A point without coordinates.
    #[error("points[{index}]: a point needs at least one coordinate")]
    EmptyPoint {
        /// its position
        index: usize,
    },
    /// Points of different dimensions.
    #[error("points[{index}]: has {got} coordinates, but points[0] has {expected}")]
    DimensionMismatch {
        /// position of the offending point
        index: usize,
        /// dimension of point 0
        expected: usize,
        /// dimension of this point
        got: usize,
    },
    /// NaN or infinite coordinate.
    #[error("points[{index}][{coord}]: expected a finite number, got {value}")]
    NonFinite {
        /// point index
        index: usize,
        /// coordinate index
        coord: usize,
        /// the value
        value: f64,
    },
    /// Two consecutive points coincide, which gives an empty parameter interval.
    #[error("points[{index}] and points[{}] coincide: the {param} parametrisation needs distinct consecutive points (use uniform, or drop the duplicate)", index + 1)]
    CoincidentPoints {
        /// the first of the two
        index: usize,
        /// the rule in use
        param: Parametrization,
    },
    /// The data parameters are not strictly increasing and finite (points too close for their
    /// distance to register, or distances overflowing f64).
    #[error("points[{index}]: its parameter {value} does not exceed the previous one or is not finite (distances too small or too large for f64)")]
    DegenerateParameters {
        /// the point whose parameter failed
        index: usize,
        /// the parameter computed for it
        value: f64,
    },
    /// Foley's rule is defined for plane curves only (lab course "B-Spline-Kurven", sec. 2.3).
    #[error("param: the foley parametrisation needs 2-D points, got {dim}-D (use chordal or centripetal)")]
    FoleyNeeds2D {
        /// dimension of the points
        dim: usize,
    },
    /// An end tangent of the wrong dimension or with non-finite values.
    #[error("{end} tangent: expected {expected} finite coordinates, got {got:?}")]
    InvalidTangent {
        /// "start" or "end"
        end: &'static str,
        /// dimension of the points
        expected: usize,
        /// the tangent given
        got: Vec<f64>,
    },
    /// Unknown parametrisation name.
    #[error("param: unknown parametrisation {0:?}, expected one of uniform, chordal, centripetal, foley")]
    UnknownParametrization(String),
    /// The linear system broke down.
    #[error(transparent)]
    Solve(#[from] TridiagonalError),
    /// The computed control points do not form a valid curve (e.g. they overflow f64).
    #[error("interpolant: {0}")]
    Curve(#[from] CurveError),
}

impl InterpolateError {
    /// A short machine-readable kind, used in JSON error records.
    pub fn kind(&self) -> &'static str {
        match self {
            InterpolateError::TooFewPoints { .. } => "too_few_points",
            InterpolateError::EmptyPoint { .. } => "zero_dimension",
            InterpolateError::DimensionMismatch { .. } => "dimension_mismatch",
            InterpolateError::NonFinite { .. } => "non_finite_coordinate",
            InterpolateError::CoincidentPoints { .. } => "coincident_points",
            InterpolateError::DegenerateParameters { .. } => "degenerate_parameters",
            InterpolateError::FoleyNeeds2D { .. } => "foley_needs_2d",
            InterpolateError::InvalidTangent { .. } => "invalid_tangent",
            InterpolateError::UnknownParametrization(_) => "unknown_parametrization",
            InterpolateError::Solve(_) => "singular_system",
            InterpolateError::Curve(e) => e.kind(),
        }
    }
}

/// The result of an interpolation: the curve and the data parameters t̂_j with C(t̂_j) ≈ p_j.
#[derive(Debug, Clone, PartialEq)]
pub struct Interpolant {
    /// the cubic B-spline, clamped, m + 3 control points
    pub curve: NurbsCurve,
    /// the data parameters t̂_0 = 0 < ... < t̂_m (also its knots)
    pub params: Vec<f64>,
}

/// Check the point set: at least 2 points, one dimension >= 1, finite values. Returns d.
pub(crate) fn validate(points: &[Vec<f64>]) -> Result<usize, InterpolateError> {
    if points.len() < 2 {
        return Err(InterpolateError::TooFewPoints { got: points.len() });
    }
    let dim = points[0].len();
    for (i, p) in points.iter().enumerate() {
        if p.is_empty() {
            return Err(InterpolateError::EmptyPoint { index: i });
        }
        if p.len() != dim {
            return Err(InterpolateError::DimensionMismatch {
                index: i,
                expected: dim,
                got: p.len(),
            });
        }
        if let Some(j) = p.iter().position(|x| !x.is_finite()) {
            return Err(InterpolateError::NonFinite {
                index: i,
                coord: j,
                value: p[j],
            });
        }
    }
    Ok(dim)
}

/// Euclidean length of p - q without intermediate overflow (hypot folds; |p - q| itself may
/// still overflow to infinity, which the caller reports).
fn dist(p: &[f64], q: &[f64]) -> f64 {
    p.iter()
        .zip(q)
        .fold(0.0, |acc: f64, (a, b)| acc.hypot(a - b))
}

/// Turning angle at p_i (the angle between p_i - p_{i-1} and p_{i+1} - p_i, in [0, pi]) of a 2-D
/// polyline: pi - Theta_i in the notation of the lab course "B-Spline-Kurven", eq. 7. Directions
/// are normalised first so the cross and dot products cannot overflow.
fn turning_angle(prev: &[f64], p: &[f64], next: &[f64], d_in: f64, d_out: f64) -> f64 {
    let (ax, ay) = ((p[0] - prev[0]) / d_in, (p[1] - prev[1]) / d_in);
    let (bx, by) = ((next[0] - p[0]) / d_out, (next[1] - p[1]) / d_out);
    (ax * by - ay * bx).abs().atan2(ax * bx + ay * by)
}

/// The data parameters t̂_0 = 0 < t̂_1 < ... < t̂_m for `points` under `param`
/// (lab course "B-Spline-Kurven", sec. 2.3, eqs. 5-7). Validates the points first.
pub fn parameters(
    points: &[Vec<f64>],
    param: Parametrization,
) -> Result<Vec<f64>, InterpolateError> {
    let dim = validate(points)?;
    let m = points.len() - 1;
    if param == Parametrization::Uniform {
        // Integers are exact in f64 (up to 2^53 points).
        return Ok((0..=m).map(|i| i as f64).collect());
    }
    if param == Parametrization::Foley && dim != 2 {
        return Err(InterpolateError::FoleyNeeds2D { dim });
    }
    let d: Vec<f64> = points.windows(2).map(|w| dist(&w[0], &w[1])).collect();
    if let Some(i) = d.iter().position(|&x| x == 0.0) {
        return Err(InterpolateError::CoincidentPoints { index: i, param });
    }
    let steps: Vec<f64> = match param {
        Parametrization::Uniform | Parametrization::Chordal => d.clone(),
        Parametrization::Centripetal => d.iter().map(|x| x.sqrt()).collect(),
        Parametrization::Foley => {
            // eq. 7: theta_hat_i = min(pi - Theta_i, pi/2) at the interior points; the terms
            // with d_{-1} = d_m = 0 vanish, so the end angles are never needed.
            let th: Vec<f64> = (0..=m)
                .map(|i| {
                    if i == 0 || i == m {
                        0.0
                    } else {
                        turning_angle(&points[i - 1], &points[i], &points[i + 1], d[i - 1], d[i])
                            .min(std::f64::consts::FRAC_PI_2)
                    }
                })
                .collect();
            (0..m)
                .map(|i| {
                    let left = if i == 0 {
                        0.0
                    } else {
                        1.5 * th[i] * d[i - 1] / (d[i - 1] + d[i])
                    };
                    let right = if i + 1 == m {
                        0.0
                    } else {
                        1.5 * th[i + 1] * d[i + 1] / (d[i + 1] + d[i])
                    };
                    d[i] * (1.0 + left + right)
                })
                .collect()
        }
    };
    let mut t = Vec::with_capacity(m + 1);
    t.push(0.0);
    for (i, s) in steps.iter().enumerate() {
        let next = t[i] + s;
        if !(next.is_finite() && next > t[i]) {
            return Err(InterpolateError::DegenerateParameters {
                index: i + 1,
                value: next,
            });
        }
        t.push(next);
    }
    Ok(t)
}

fn check_tangent(e: &EndCondition, end: &'static str, dim: usize) -> Result<(), InterpolateError> {
    if let EndCondition::Tangent(v) = e {
        if v.len() != dim || v.iter().any(|x| !x.is_finite()) {
            return Err(InterpolateError::InvalidTangent {
                end,
                expected: dim,
                got: v.clone(),
            });
        }
    }
    Ok(())
}

/// The natural cubic spline interpolant through `points` with the given parametrisation (lab course
/// "B-Spline-Kurven", sec. 2.3). Shorthand for [`interpolate_cubic_with`] with natural ends.
pub fn interpolate_cubic(
    points: &[Vec<f64>],
    param: Parametrization,
) -> Result<NurbsCurve, InterpolateError> {
    let opts = InterpolationOptions {
        param,
        ..Default::default()
    };
    Ok(interpolate_cubic_with(points, &opts)?.curve)
}

/// Cubic B-spline interpolation (lab course "B-Spline-Kurven", sec. 2.3, eqs. 8-14).
///
/// Knots: t_{i+3} = t̂_i with fourfold end knots (eqs. 8-9; the source's 1-based t_1..t_{m+5}
/// are our u_1..u_{m+5}, plus u_0 = t̂_0 and u_{m+6} = t̂_m which do not influence the curve).
/// Unknowns d_0 .. d_{m+2}; equations, one per row of the tridiagonal system (14):
/// * row 0: d_0 = p_0 and row m+2: d_{m+2} = p_m (eq. 10),
/// * rows i = 2..m: (1-β_i)((1-α_i) d_{i-1} + α_i d_i) + β_i((1-γ_i) d_i + γ_i d_{i+1}) =
///   p_{i-1} (eqs. 11-12, the de Boor scheme at t_{i+2} = t̂_{i-1}),
/// * row 1 and row m+1: natural ends -d_0 + (1+α_2) d_1 - α_2 d_2 = 0 and
///   (γ_m - 1) d_m + (2 - γ_m) d_{m+1} - d_{m+2} = 0 (eq. 13, signs as in (14); for m = 1 the
///   values α_2 = 1, γ_1 = 0 follow from the same formulas), or a prescribed tangent
///   C'(t̂_0) = 3 (d_1 - d_0) / (t̂_1 - t̂_0), C'(t̂_m) = 3 (d_{m+2} - d_{m+1}) / (t̂_m - t̂_{m-1})
///   (end derivative of a clamped cubic, thesis eq. 2.7).
///
/// The system is solved by [`solve_tridiagonal`] for all coordinates at once.
pub fn interpolate_cubic_with(
    points: &[Vec<f64>],
    opts: &InterpolationOptions,
) -> Result<Interpolant, InterpolateError> {
    let params = parameters(points, opts.param)?;
    let dim = points[0].len();
    check_tangent(&opts.start, "start", dim)?;
    check_tangent(&opts.end, "end", dim)?;
    let m = points.len() - 1;
    let knots = interpolation_knots(&params);
    let t = |j: usize| knots[j];
    // alpha_i, beta_i, gamma_i of eq. 11 (all denominators are > 0: they span at least one
    // non-empty data interval because the parameters are strictly increasing).
    let alpha = |i: usize| (t(i + 2) - t(i)) / (t(i + 3) - t(i));
    let beta = |i: usize| (t(i + 2) - t(i + 1)) / (t(i + 3) - t(i + 1));
    let gamma = |i: usize| (t(i + 2) - t(i + 1)) / (t(i + 4) - t(i + 1));
    let n = m + 3;
    let (mut a, mut b, mut c) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let mut rhs = vec![0.0; n * dim];
    b[0] = 1.0;
    rhs[..dim].copy_from_slice(&points[0]);
    b[n - 1] = 1.0;
    rhs[(n - 1) * dim..].copy_from_slice(&points[m]);
    for i in 2..=m {
        let (al, be, ga) = (alpha(i), beta(i), gamma(i));
        a[i] = (1.0 - be) * (1.0 - al);
        b[i] = (1.0 - be) * al + be * (1.0 - ga);
        c[i] = be * ga;
        rhs[i * dim..(i + 1) * dim].copy_from_slice(&points[i - 1]);
    }
    match &opts.start {
        EndCondition::Natural => {
            let al = alpha(2);
            (a[1], b[1], c[1]) = (-1.0, 1.0 + al, -al);
        }
        EndCondition::Tangent(v) => {
            // d_1 - d_0 = (t̂_1 - t̂_0)/3 * T_0
            let h = (params[1] - params[0]) / 3.0;
            (a[1], b[1], c[1]) = (-1.0, 1.0, 0.0);
            for (j, x) in v.iter().enumerate() {
                rhs[dim + j] = h * x;
            }
        }
    }
    match &opts.end {
        EndCondition::Natural => {
            let ga = gamma(m);
            (a[m + 1], b[m + 1], c[m + 1]) = (ga - 1.0, 2.0 - ga, -1.0);
        }
        EndCondition::Tangent(v) => {
            // d_{m+1} - d_{m+2} = -(t̂_m - t̂_{m-1})/3 * T_m (positive diagonal)
            let h = (params[m] - params[m - 1]) / 3.0;
            (a[m + 1], b[m + 1], c[m + 1]) = (0.0, 1.0, -1.0);
            for (j, x) in v.iter().enumerate() {
                rhs[(m + 1) * dim + j] = -h * x;
            }
        }
    }
    solve_tridiagonal(&a, &b, &c, &mut rhs, dim)?;
    let curve = NurbsCurve::from_flat(3, dim, knots, rhs, None)?;
    Ok(Interpolant { curve, params })
}

/// A verified upper bound on max_j max_coord |C(t̂_j) - p_j| for the exact curve `curve` (the
/// f64 data as given): C(t̂_j) is enclosed by de Boor corner cutting in interval arithmetic
/// ([`CurveEval`] with `Interval`, the kernel behind [`NurbsCurve::enclose_point`], set up once
/// so the whole check is O(m)), the difference to p_j is formed in interval arithmetic
/// (outward rounded) and its magnitude taken.
pub fn interpolation_residual(
    curve: &NurbsCurve,
    params: &[f64],
    points: &[Vec<f64>],
) -> Result<f64, EvalError> {
    let ev = CurveEval::<Interval>::new(curve, 0);
    let mut worst: f64 = 0.0;
    for (t, p) in params.iter().zip(points) {
        let enc = ev.derivs(*t, 0)?.swap_remove(0);
        for (e, x) in enc.iter().zip(p) {
            worst = worst.max((*e - iv::point(*x)).mag());
        }
    }
    Ok(worst)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::bspline::basis_funs;

    fn pts(v: &[[f64; 2]]) -> Vec<Vec<f64>> {
        v.iter().map(|p| p.to_vec()).collect()
    }

    #[test]
    fn rows_of_eq_12_are_the_basis_function_values() {
        // The coefficients of eq. 12 are N_{i-1,3}, N_{i,3}, N_{i+1,3} at t̂_{i-1}.
        let params = [0.0, 0.7, 1.1, 2.9, 3.0, 4.5];
        let knots = interpolation_knots(&params);
        let t = |j: usize| knots[j];
        for i in 2..params.len() - 1 {
            let (al, be, ga) = (
                (t(i + 2) - t(i)) / (t(i + 3) - t(i)),
                (t(i + 2) - t(i + 1)) / (t(i + 3) - t(i + 1)),
                (t(i + 2) - t(i + 1)) / (t(i + 4) - t(i + 1)),
            );
            let row = [
                (1.0 - be) * (1.0 - al),
                (1.0 - be) * al + be * (1.0 - ga),
                be * ga,
            ];
            // span of t_{i+2} is i+2; basis_funs gives N_{i-1..i+2}; the last one is 0 there
            let n = basis_funs::<f64>(&knots, i + 2, &t(i + 2), 3);
            for k in 0..3 {
                assert!((n[k] - row[k]).abs() < 1e-15, "i={i} k={k}");
            }
            assert_eq!(n[3], 0.0);
        }
    }

    #[test]
    fn passes_through_points_with_natural_ends() {
        let p = pts(&[[0., 0.], [1., 2.], [3., 1.], [4., 4.], [6., 0.], [7., 1.]]);
        for param in Parametrization::ALL {
            let it = interpolate_cubic_with(
                &p,
                &InterpolationOptions {
                    param,
                    ..Default::default()
                },
            )
            .unwrap();
            let r = interpolation_residual(&it.curve, &it.params, &p).unwrap();
            assert!(r < 1e-13, "{param}: residual {r}");
            let (a, b) = it.curve.domain();
            for u in [a, b] {
                for e in it.curve.enclose_derivative(iv::point(u), 2).unwrap() {
                    // C'' at the ends is 0 up to the rounding of the solve
                    assert!(e.mag() < 1e-12, "{param}: C''({u}) = {e:?}");
                }
            }
        }
    }

    #[test]
    fn two_points_give_the_segment_and_tangents_are_honoured() {
        let p = pts(&[[1., 1.], [4., 5.]]);
        let c = interpolate_cubic(&p, Parametrization::Chordal).unwrap();
        assert_eq!(c.knots(), &[0., 0., 0., 0., 5., 5., 5., 5.]);
        let q: Vec<f64> = c.point(2.5).unwrap();
        assert!((q[0] - 2.5).abs() < 1e-15 && (q[1] - 3.0).abs() < 1e-15);
        let opts = InterpolationOptions {
            param: Parametrization::Uniform,
            start: EndCondition::Tangent(vec![0., 3.]),
            end: EndCondition::Tangent(vec![-1., 0.]),
        };
        let p = pts(&[[0., 0.], [1., 1.], [2., 0.]]);
        let it = interpolate_cubic_with(&p, &opts).unwrap();
        let d0: Vec<Interval> = it.curve.enclose_derivative(iv::point(0.0), 1).unwrap();
        let d1: Vec<Interval> = it.curve.enclose_derivative(iv::point(2.0), 1).unwrap();
        assert!((d0[0].mid() - 0.).abs() < 1e-14 && (d0[1].mid() - 3.).abs() < 1e-14);
        assert!((d1[0].mid() + 1.).abs() < 1e-14 && (d1[1].mid() - 0.).abs() < 1e-14);
        assert!(interpolation_residual(&it.curve, &it.params, &p).unwrap() < 1e-14);
    }

    #[test]
    fn parameters_follow_the_rules() {
        let p = pts(&[[0., 0.], [3., 4.], [3., 13.]]);
        assert_eq!(
            parameters(&p, Parametrization::Uniform).unwrap(),
            vec![0., 1., 2.]
        );
        assert_eq!(
            parameters(&p, Parametrization::Chordal).unwrap(),
            vec![0., 5., 14.]
        );
        let c = parameters(&p, Parametrization::Centripetal).unwrap();
        assert!((c[1] - 5f64.sqrt()).abs() < 1e-15 && (c[2] - c[1] - 3.0).abs() < 1e-15);
        // Foley: the turning angle at p_1 is the angle between (3,4) and (0,9): acos(4/5)
        let f = parameters(&p, Parametrization::Foley).unwrap();
        let th = (0.8f64).acos();
        let want1 = 5.0 * (1.0 + 1.5 * th * 9.0 / 14.0);
        let want2 = 9.0 * (1.0 + 1.5 * th * 5.0 / 14.0);
        assert!((f[1] - want1).abs() < 1e-13 && (f[2] - f[1] - want2).abs() < 1e-13);
        // collinear points: Foley is chordal
        let q = pts(&[[0., 0.], [1., 1.], [3., 3.]]);
        let (fo, ch) = (
            parameters(&q, Parametrization::Foley).unwrap(),
            parameters(&q, Parametrization::Chordal).unwrap(),
        );
        assert!(fo.iter().zip(&ch).all(|(a, b)| (a - b).abs() < 1e-14));
    }

    #[test]
    fn degenerate_input_is_a_typed_error() {
        let k = |p: &[Vec<f64>], param| interpolate_cubic(p, param).unwrap_err().kind();
        use Parametrization::*;
        assert_eq!(k(&pts(&[[0., 0.]]), Chordal), "too_few_points");
        assert_eq!(k(&[], Uniform), "too_few_points");
        assert_eq!(k(&[vec![0.], vec![1., 2.]], Uniform), "dimension_mismatch");
        assert_eq!(k(&[vec![], vec![]], Uniform), "zero_dimension");
        assert_eq!(
            k(&pts(&[[0., 0.], [f64::NAN, 1.]]), Uniform),
            "non_finite_coordinate"
        );
        assert_eq!(
            k(&pts(&[[0., 0.], [1., 1.], [1., 1.]]), Centripetal),
            "coincident_points"
        );
        // uniform allows repeated values (plateaus of sampled functions)
        assert!(interpolate_cubic(&pts(&[[0., 0.], [1., 1.], [1., 1.]]), Uniform).is_ok());
        assert_eq!(
            k(&[vec![0., 0., 0.], vec![1., 0., 0.]], Foley),
            "foley_needs_2d"
        );
        // a step too small to change the accumulated parameter
        assert_eq!(
            k(&pts(&[[0., 0.], [1e20, 0.], [1e20, 1.]]), Chordal),
            "degenerate_parameters"
        );
        assert_eq!(
            k(&pts(&[[-1e308, 0.], [1e308, 0.], [0., 0.]]), Chordal),
            "degenerate_parameters"
        );
        let bad = InterpolationOptions {
            start: EndCondition::Tangent(vec![1.]),
            ..Default::default()
        };
        let e = interpolate_cubic_with(&pts(&[[0., 0.], [1., 1.]]), &bad).unwrap_err();
        assert_eq!(e.kind(), "invalid_tangent");
        assert!(e.to_string().contains("start"));
        assert_eq!(
            "spline".parse::<Parametrization>().unwrap_err().kind(),
            "unknown_parametrization"
        );
        assert_eq!("foley".parse::<Parametrization>().unwrap(), Foley);
        let m = k(&pts(&[[0., 0.], [1., 1.], [1., 1.]]), Chordal);
        assert_eq!(m, "coincident_points");
        let msg = interpolate_cubic(&pts(&[[0., 0.], [1., 1.], [1., 1.]]), Chordal)
            .unwrap_err()
            .to_string();
        assert!(
            msg.contains("points[1]") && msg.contains("points[2]"),
            "{msg}"
        );
    }
}
