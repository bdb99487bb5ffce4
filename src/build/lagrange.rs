//! Lagrange interpolation curves (the lecture 'Modellierung mit Kurven', "Interpolierende
//! Kurven: Lagrange Interpolation"), beside the cubic spline interpolation of
//! [`crate::build::interpolate`].
//!
//! Given points q_0 .. q_g and parameters u_0 < ... < u_g (the lecture's "Stützstellenvektor"),
//! the Lagrange basis L_i^g(t) = prod_{k != i} (t - u_k) / (u_i - u_k) has L_i^g(u_j) =
//! delta_ij, and c(t) = sum_i q_i L_i^g(t) is the polynomial curve of degree g through the
//! points: c(u_i) = q_i. The basis sums to one (affine invariance), but it is not
//! non-negative, so there is no convex-hull property, and with many points the curve
//! overshoots (the lecture's warning; Runge's example f(x) = 1/(1 + 25 x^2) on [-1, 1], see
//! `examples/runge.rs`).
//!
//! * [`LagrangeCurve`] is the curve itself, defined exactly by the f64 points and parameters.
//! * [`LagrangeCurve::eval`] evaluates it generically over [`Scalar`] in the first barycentric
//!   form (Berrut & Trefethen 2004, the "modified Lagrange formula"), falling back to the
//!   lecture's product form when t may coincide with a node.
//! * [`LagrangeCurve::to_bezier`] converts it to the crate's curve form, one Bézier segment of
//!   degree g on the clamped knots {u_0^(g+1), u_g^(g+1)}, computed in rigorous double-double
//!   arithmetic, and carries the rounding of the conversion as a per-coordinate radius (see [`LagrangeBezier`] for the guarantee).

use crate::build::bezier_tools::binom_s;
use crate::build::interpolate::{
    parameters, validate as validate_points, InterpolateError, Parametrization,
};
use crate::enclose::{BoxEncloser, Enclosure};
use crate::error::CurveError;
use crate::num::ddi::Ddi;
use crate::num::{iv, Scalar};
use crate::spline::bspline::BezierSeg;
use crate::spline::curve::NurbsCurve;
use inari::Interval;
use thiserror::Error;

/// The largest degree g (g + 1 points) [`LagrangeCurve`] accepts. The conversion to Bernstein
/// form costs O(g^3) interval operations, and far below this degree the coefficients of
/// equidistant interpolation are already astronomically large (the overshoot the lecture
/// warns about): more points are a misuse, reported as an error.
pub const MAX_LAGRANGE_DEGREE: usize = 400;

/// Why a Lagrange curve could not be built or converted.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum LagrangeError {
    /// The points are not a valid point set (too few, mixed dimensions, non-finite, or their
    /// parameters could not be computed).
    #[error(transparent)]
    Points(#[from] InterpolateError),
    /// More than [`MAX_LAGRANGE_DEGREE`] + 1 points.
    #[error("points: Lagrange interpolation takes at most {max} points (degree {}), got {got}", max - 1)]
    TooManyPoints {
        /// the limit, MAX_LAGRANGE_DEGREE + 1
        max: usize,
        /// number of points given
        got: usize,
    },
    /// Not one parameter per point.
    #[error("params: expected one parameter per point ({expected}), got {got}")]
    ParamCount {
        /// number of points
        expected: usize,
        /// number of parameters
        got: usize,
    },
    /// A parameter is NaN or infinite.
    #[error("params[{index}]: expected a finite number, got {value}")]
    NonFiniteParam {
        /// its position
        index: usize,
        /// the value
        value: f64,
    },
    /// The parameters are not strictly increasing (a repeated parameter makes the basis
    /// undefined: the lecture's u_0 < ... < u_g).
    #[error("params[{index}]: parameters must be strictly increasing, but {value} <= params[{}] = {previous}", index - 1)]
    NotIncreasing {
        /// position of the offending parameter
        index: usize,
        /// its value
        value: f64,
        /// the parameter before it
        previous: f64,
    },
    /// A Bernstein coefficient overflowed f64 (the curve is too wild to be represented).
    #[error("lagrange: Bernstein coefficient {index} of coordinate {coord} overflows f64")]
    Overflow {
        /// coefficient index
        index: usize,
        /// coordinate
        coord: usize,
    },
    /// The converted curve is not a valid curve.
    #[error("lagrange curve: {0}")]
    Curve(#[from] CurveError),
}

impl LagrangeError {
    /// A short machine-readable kind, used in JSON error records.
    pub fn kind(&self) -> &'static str {
        match self {
            LagrangeError::Points(e) => e.kind(),
            LagrangeError::TooManyPoints { .. } => "too_many_points",
            LagrangeError::ParamCount { .. } => "param_count",
            LagrangeError::NonFiniteParam { .. } => "non_finite_param",
            LagrangeError::NotIncreasing { .. } => "params_not_increasing",
            LagrangeError::Overflow { .. } => "overflow",
            LagrangeError::Curve(e) => e.kind(),
        }
    }
}

/// The Lagrange curve c(t) = sum_{i=0}^{g} q_i L_i^g(t) through q_i at t = u_i, exactly as the
/// f64 points and parameters define it (every guarantee below refers to this exact curve).
#[derive(Debug, Clone, PartialEq)]
pub struct LagrangeCurve {
    params: Vec<f64>,
    dim: usize,
    /// q_i, row-major, `dim` values each
    points: Vec<f64>,
}

impl LagrangeCurve {
    /// The curve through `points` at the given parameters (strictly increasing, finite, one
    /// per point; at least 2 points, so g >= 1).
    pub fn new(params: Vec<f64>, points: &[Vec<f64>]) -> Result<Self, LagrangeError> {
        let dim = validate_points(points)?;
        if points.len() > MAX_LAGRANGE_DEGREE + 1 {
            return Err(LagrangeError::TooManyPoints {
                max: MAX_LAGRANGE_DEGREE + 1,
                got: points.len(),
            });
        }
        if params.len() != points.len() {
            return Err(LagrangeError::ParamCount {
                expected: points.len(),
                got: params.len(),
            });
        }
        if let Some(i) = params.iter().position(|x| !x.is_finite()) {
            return Err(LagrangeError::NonFiniteParam {
                index: i,
                value: params[i],
            });
        }
        if let Some(i) = (1..params.len()).find(|&i| params[i] <= params[i - 1]) {
            return Err(LagrangeError::NotIncreasing {
                index: i,
                value: params[i],
                previous: params[i - 1],
            });
        }
        Ok(LagrangeCurve {
            params,
            dim,
            points: points.concat(),
        })
    }

    /// The curve through `points` with data parameters by the rule `param` (uniform, chordal,
    /// centripetal or Foley, exactly as for the cubic spline: [`parameters`]).
    pub fn interpolate(points: &[Vec<f64>], param: Parametrization) -> Result<Self, LagrangeError> {
        if points.len() > MAX_LAGRANGE_DEGREE + 1 {
            return Err(LagrangeError::TooManyPoints {
                max: MAX_LAGRANGE_DEGREE + 1,
                got: points.len(),
            });
        }
        let t = parameters(points, param)?;
        Self::new(t, points)
    }

    /// The degree g (number of points - 1).
    pub fn degree(&self) -> usize {
        self.params.len() - 1
    }

    /// The number of coordinates.
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// The parameters u_0 < ... < u_g.
    pub fn params(&self) -> &[f64] {
        &self.params
    }

    /// The point q_i.
    pub fn point(&self, i: usize) -> &[f64] {
        &self.points[i * self.dim..(i + 1) * self.dim]
    }

    /// The parameter interval [u_0, u_g] (the domain of [`LagrangeCurve::to_bezier`]'s curve;
    /// [`LagrangeCurve::eval`] works for any t).
    pub fn domain(&self) -> (f64, f64) {
        (self.params[0], self.params[self.degree()])
    }

    /// The Lagrange basis L_0^g(t) .. L_g^g(t) in the lecture's product form
    /// prod_{k != i} (t - u_k) / (u_i - u_k). O(g^2); no division by a quantity depending on
    /// t, so it is sound for any interval t (also one containing nodes).
    pub fn basis<S: Scalar>(&self, t: &S) -> Vec<S> {
        self.products(|ui: &S, uk: &S| (t.clone() - uk.clone()) / (ui.clone() - uk.clone()))
    }

    /// For each i: prod_{k != i} f(u_i, u_k), in S.
    fn products<S: Scalar>(&self, f: impl Fn(&S, &S) -> S) -> Vec<S> {
        let u: Vec<S> = self.params.iter().map(|&x| S::from_f64(x)).collect();
        (0..u.len())
            .map(|i| {
                (0..u.len())
                    .filter(|&k| k != i)
                    .fold(S::one(), |acc, k| acc * f(&u[i], &u[k]))
            })
            .collect()
    }

    /// The barycentric weights in S (see [`Barycentric`]); O(g^2) once, then O(g d) per point.
    pub fn barycentric<S: Scalar>(&self) -> Barycentric<'_, S> {
        let (a, b) = self.domain();
        // Any positive f64 works as the scale C (it cancels exactly); (b - a) / 4, the
        // "capacity" of the interval, keeps the products near 1 (the rescaling Berrut &
        // Trefethen suggest).
        let c = (b - a) / 4.0;
        let c = if c.is_normal() { c } else { 1.0 };
        let cs = S::from_f64(c);
        let weights = self.products(|ui: &S, uk: &S| cs.clone() / (ui.clone() - uk.clone()));
        Barycentric {
            curve: self,
            scale: cs,
            weights,
        }
    }

    /// c(t) in S (all coordinates); shorthand for `self.barycentric::<S>().eval(t)`.
    pub fn eval<S: Scalar>(&self, t: &S) -> Vec<S> {
        self.barycentric::<S>().eval(t)
    }

    /// Convert to one Bézier segment of degree g over [u_0, u_g] (a [`NurbsCurve`] on clamped
    /// knots) with the rounding carried; see [`LagrangeBezier`]. The coefficients are
    /// computed in rigorous double-double arithmetic ([`Ddi`], about 2^-100 relative), so the
    /// radius is essentially the rounding of the coefficients to f64 (half an ulp), even
    /// where the conversion is ill-conditioned (clustered parameters, many points);
    /// [`LagrangeCurve::to_bezier_with`] runs it in another verified type.
    pub fn to_bezier(&self) -> Result<LagrangeBezier, LagrangeError> {
        self.to_bezier_with::<Ddi>()
    }

    /// [`LagrangeCurve::to_bezier`] with the coefficients computed in S (a verified type:
    /// `Interval` or `Ddi`; with `f64` the radius is meaningless).
    ///
    /// Method. With t = u_0 + s (u_g - u_0), each factor of L_i is linear in s with Bernstein
    /// coefficients
    ///
    /// ```text
    /// (t - u_k) / (u_i - u_k) = (1 - s) (u_0 - u_k) / (u_i - u_k) + s (u_g - u_k) / (u_i - u_k),
    /// ```
    ///
    /// formed from differences of the f64 data only (no rounded s_k = (u_k - u_0) / (u_g - u_0)
    /// enters). The product of the g factors is accumulated in the scaled Bernstein basis
    /// s^l (1 - s)^(m - l), where multiplying by a0 (1 - s) + a1 s is the convolution
    /// c'_l = a0 c_l + a1 c_{l-1} (no binomials on the way); at the end the Bernstein
    /// coefficients are b_l = sum_i q_i c^(i)_l / C(g, l) (binomials in S, exact, from
    /// [`crate::build::bezier_tools`]). Each step is an operation of the verified type on
    /// enclosures, so every b_l encloses the exact Bernstein coefficient of the exact Lagrange
    /// curve (inclusion isotonicity). Dividing each factor by u_i - u_k on the way (rather
    /// than the product at the end) keeps the running products near the size of L_i and away
    /// from overflow. The f64 coefficient is m_l = the representative of b_l, and the radius
    /// takes max_l |b_l - m_l| from the verified difference b_l - m_l. O(g^3 + g^2 d).
    pub fn to_bezier_with<S: Scalar>(&self) -> Result<LagrangeBezier, LagrangeError> {
        let g = self.degree();
        let d = self.dim;
        let u = &self.params;
        let p = S::from_f64;
        let (u0, ug) = (p(u[0]), p(u[g]));
        let mut coeffs = vec![S::zero(); (g + 1) * d];
        let mut c: Vec<S> = Vec::with_capacity(g + 1);
        for i in 0..=g {
            c.clear();
            c.push(S::one());
            let ui = p(u[i]);
            for (k, &uk) in u.iter().enumerate() {
                if k == i {
                    continue;
                }
                let uk = p(uk);
                let den = ui.clone() - uk.clone();
                let a0 = (u0.clone() - uk.clone()) / den.clone();
                let a1 = (ug.clone() - uk) / den;
                // c' = a0 c + a1 (c shifted by one); in place from the top
                let top = a1.clone() * c[c.len() - 1].clone();
                for l in (1..c.len()).rev() {
                    c[l] = a0.clone() * c[l].clone() + a1.clone() * c[l - 1].clone();
                }
                c[0] = a0 * c[0].clone();
                c.push(top);
            }
            for (l, cl) in c.iter().enumerate() {
                for j in 0..d {
                    let q = p(self.points[i * d + j]);
                    coeffs[l * d + j] = coeffs[l * d + j].clone() + cl.clone() * q;
                }
            }
        }
        let mut mids = Vec::with_capacity(coeffs.len());
        let mut encl = Vec::with_capacity(coeffs.len());
        let mut radius = vec![0.0f64; d];
        for l in 0..=g {
            let binom: S = binom_s(g, l);
            for j in 0..d {
                let b = coeffs[l * d + j].clone() / binom.clone();
                let bi = b.to_interval();
                if !(bi.inf().is_finite() && bi.sup().is_finite()) {
                    return Err(LagrangeError::Overflow { index: l, coord: j });
                }
                let m = b.to_f64();
                let m = if bi.contains(m) { m } else { bi.mid() };
                // |b_exact - m| <= mag(b - m): the difference is formed in the verified type
                // and rounded outward by to_interval.
                radius[j] = radius[j].max((b - p(m)).to_interval().mag());
                mids.push(m);
                encl.push(bi);
            }
        }
        let mut knots = vec![u[0]; g + 1];
        knots.extend(std::iter::repeat_n(u[g], g + 1));
        let curve = NurbsCurve::from_flat(g, d, knots, mids, None)?;
        Ok(LagrangeBezier {
            curve,
            radius,
            coefficients: BezierSeg::from_points(u[0], u[g], d, encl),
        })
    }
}

/// Barycentric evaluation of a [`LagrangeCurve`] in S (Berrut & Trefethen 2004, "Barycentric
/// Lagrange Interpolation", SIAM Review 46(3), the first or "modified Lagrange" form):
///
/// ```text
/// c(t) = l(t) sum_i (w_i C / (t - u_i)) q_i,  l(t) = prod_k (t - u_k) / C,
/// w_i = prod_{k != i} C / (u_i - u_k)
/// ```
///
/// with a scale C > 0 (an f64, exact) that cancels. The first form is used rather than the
/// second (the quotient of two sums) because t occurs in it only through the differences
/// t - u_i, which keeps interval enclosures tight; it is backward stable in floating point
/// (Higham 2004).
#[derive(Debug, Clone)]
pub struct Barycentric<'a, S> {
    curve: &'a LagrangeCurve,
    scale: S,
    weights: Vec<S>,
}

impl<S: Scalar> Barycentric<'_, S> {
    /// The weights w_i (scaled by C^g, see the type's documentation).
    pub fn weights(&self) -> &[S] {
        &self.weights
    }

    /// c(t), all coordinates. At a node (t - u_i exactly zero) the result is q_i itself. When
    /// some t - u_i may be zero without being exactly zero (an interval t around a node) the
    /// barycentric quotient is undefined there, and the product form
    /// [`LagrangeCurve::basis`] is used instead: both are the same polynomial, so for
    /// intervals either result encloses c(t) for every real t enclosed by `t`.
    pub fn eval(&self, t: &S) -> Vec<S> {
        let c = self.curve;
        let d = c.dim;
        let diffs: Vec<S> = c
            .params
            .iter()
            .map(|&u| t.clone() - S::from_f64(u))
            .collect();
        if let Some(i) = diffs.iter().position(Scalar::is_exact_zero) {
            return c.point(i).iter().map(|&x| S::from_f64(x)).collect();
        }
        if diffs.iter().any(|x| x.to_interval().contains(0.0)) {
            let basis = c.basis(t);
            return (0..d)
                .map(|j| {
                    basis.iter().enumerate().fold(S::zero(), |acc, (i, l)| {
                        acc + l.clone() * S::from_f64(c.points[i * d + j])
                    })
                })
                .collect();
        }
        let l = diffs
            .iter()
            .fold(S::one(), |acc, x| acc * x.clone() / self.scale.clone());
        let mut sum = vec![S::zero(); d];
        for (i, x) in diffs.iter().enumerate() {
            let f = self.weights[i].clone() * self.scale.clone() / x.clone();
            for (j, s) in sum.iter_mut().enumerate() {
                *s = s.clone() + f.clone() * S::from_f64(c.points[i * d + j]);
            }
        }
        sum.into_iter().map(|s| l.clone() * s).collect()
    }
}

/// A [`LagrangeCurve`] converted to the crate's curve form, with the conversion's rounding.
///
/// `curve` is an f64 Bézier curve of degree g on the knots {u_0^(g+1), u_g^(g+1)}: over
/// [u_0, u_g] it is sum_l m_l B_l^g(s), s = (t - u_0) / (u_g - u_0), where m_l is the midpoint
/// of an interval that encloses the exact Bernstein coefficient b_l of the Lagrange curve
/// (`coefficients`). `radius[j]` is a verified upper bound on max_l |b_lj - m_lj|.
///
/// **Guarantee.** For every t in [u_0, u_g] and every coordinate j,
/// |c_j(t) - curve_j(t)| <= `radius[j]`, where c is the exact Lagrange curve: the difference is
/// sum_l (b_lj - m_lj) B_l^g(s), and the Bernstein polynomials are non-negative and sum to one
/// on [0, 1] (a partition of unity), so it is a convex combination of numbers of magnitude
/// <= `radius[j]`. Hence a verified box [lo, hi] of `curve` widened to
/// [lo - radius, hi + radius] (rounded outward) is a verified box of the Lagrange curve over
/// [u_0, u_g]: [`LagrangeBezier::widen`] does that, [`LagrangeBezier::enclose`] encloses and
/// widens in one call. `radius` is 0 exactly when every coefficient was computed exactly; then
/// `curve` *is* the Lagrange curve.
///
/// The command line (`nurbs-box interpolate --basis lagrange`) writes `curve`; the `enclose` of
/// that output is a verified box of this f64 curve, and it becomes one of the Lagrange curve
/// after widening by `radius` (written by `interpolate --report FILE`).
#[derive(Debug, Clone)]
pub struct LagrangeBezier {
    /// the f64 Bézier curve (midpoints of the coefficient enclosures)
    pub curve: NurbsCurve,
    /// per coordinate: a verified bound on the coefficient error, hence on |c_j - curve_j|
    pub radius: Vec<f64>,
    /// the enclosures of the exact Bernstein coefficients, over [u_0, u_g]
    pub coefficients: BezierSeg<Interval>,
}

impl LagrangeBezier {
    /// Widen a verified box of [`LagrangeBezier::curve`] by `radius` into one of the exact
    /// Lagrange curve (see [`widen_enclosure`]).
    pub fn widen(&self, e: &Enclosure) -> Enclosure {
        widen_enclosure(e, &self.radius)
    }

    /// Enclose [`LagrangeBezier::curve`] with `strategy` and widen: for a verified strategy, a
    /// verified box of the exact Lagrange curve over [u_0, u_g].
    pub fn enclose(&self, strategy: &dyn BoxEncloser) -> Enclosure {
        self.widen(&strategy.enclose(&self.curve))
    }
}

/// A box of a curve c̃ turned into a box of any curve c with |c_j - c̃_j| <= `radius[j]` on the
/// same domain: outer bounds move out by the radius, inner bounds (values the curve provably
/// reaches) move in, all rounded outward in interval arithmetic so the statements stay exact:
/// lo' = RD(lo - r), hi' = RU(hi + r), inner_lo' = RU(inner_lo + r), inner_hi' =
/// RD(inner_hi - r). A radius of 0 leaves the bounds as they are.
pub fn widen_enclosure(e: &Enclosure, radius: &[f64]) -> Enclosure {
    let mut out = e.clone();
    for (c, &r) in out.coords.iter_mut().zip(radius) {
        if r == 0.0 {
            continue;
        }
        let r = iv::point(r);
        c.lo = (iv::point(c.lo) - r).inf();
        c.hi = (iv::point(c.hi) + r).sup();
        c.inner_lo = (iv::point(c.inner_lo) + r).sup();
        c.inner_hi = (iv::point(c.inner_hi) - r).inf();
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pts(v: &[[f64; 2]]) -> Vec<Vec<f64>> {
        v.iter().map(|p| p.to_vec()).collect()
    }

    #[test]
    fn a_parabola_has_exact_bernstein_coefficients() {
        // q = (0, 1, 0) at u = 0, 1, 2: c(t) = t (2 - t) = 4 s (1 - s), s = t / 2: b = 0, 2, 0.
        let lc = LagrangeCurve::new(vec![0., 1., 2.], &[vec![0.], vec![1.], vec![0.]]).unwrap();
        let lb = lc.to_bezier().unwrap();
        assert_eq!(lb.curve.points_flat().to_vec(), vec![0., 2., 0.]);
        assert_eq!(lb.radius, vec![0.0]);
        assert_eq!(lb.curve.knots(), &[0., 0., 0., 2., 2., 2.]);
        assert_eq!(lc.eval::<f64>(&0.5), vec![0.75]);
        assert_eq!(lc.eval::<f64>(&1.0), vec![1.0]);
    }

    #[test]
    fn errors_are_typed() {
        let e = |r: Result<LagrangeCurve, LagrangeError>| r.unwrap_err().kind();
        let p = pts(&[[0., 0.], [1., 1.], [2., 0.]]);
        assert_eq!(
            e(LagrangeCurve::new(vec![0., 1., 1.], &p)),
            "params_not_increasing"
        );
        assert_eq!(e(LagrangeCurve::new(vec![0., 1.], &p)), "param_count");
        assert_eq!(
            e(LagrangeCurve::new(vec![0., f64::NAN, 1.], &p)),
            "non_finite_param"
        );
        assert_eq!(e(LagrangeCurve::new(vec![0.], &p[..1])), "too_few_points");
        assert_eq!(e(LagrangeCurve::new(vec![], &[])), "too_few_points");
        assert_eq!(
            e(LagrangeCurve::interpolate(
                &pts(&[[0., 0.], [0., 0.]]),
                Parametrization::Chordal
            )),
            "coincident_points"
        );
        let many: Vec<Vec<f64>> = (0..=MAX_LAGRANGE_DEGREE + 1)
            .map(|i| vec![i as f64])
            .collect();
        assert_eq!(
            e(LagrangeCurve::interpolate(&many, Parametrization::Uniform)),
            "too_many_points"
        );
    }
}
