//! Bézier tools (lecture "Modellierung mit Kurven"): Bézier segments as curves, the monomial
//! form with Horner evaluation and the basis change both ways, the Hermite form of a cubic
//! segment, and degree elevation.
//!
//! Bernstein evaluation is de Casteljau's scheme, [`BezierSeg::eval_local`]; this module adds
//! no second copy of it. Everything is generic over [`Scalar`] and works on homogeneous rows,
//! so rational segments are handled by the same code (the conversions are linear maps of the
//! rows). With `S = Interval` every result encloses the exact converted coefficients.

use crate::error::CurveError;
use crate::num::Scalar;
use crate::spline::bspline::{BezierSeg, HSpline};
use crate::spline::curve::NurbsCurve;
use crate::spline::eval::binom;
use thiserror::Error;

/// Why a Bézier conversion is not possible.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum BezierToolError {
    /// The Hermite form is for cubic segments.
    #[error("hermite: needs a cubic segment, got degree {degree}")]
    NotCubic {
        /// the degree given
        degree: usize,
    },
    /// The Hermite form is for polynomial (non-rational) segments.
    #[error("hermite: needs a non-rational segment (all weights 1)")]
    Rational,
    /// The segment's parameter interval is empty or not finite.
    #[error("segment: parameter interval [{a}, {b}] must satisfy a < b, both finite")]
    BadInterval {
        /// start
        a: f64,
        /// end
        b: f64,
    },
}

/// Binomial coefficient in S, built by the multiplicative recurrence in S itself, so that for
/// intervals it encloses the exact integer whatever its size.
pub(crate) fn binom_s<S: Scalar>(n: usize, k: usize) -> S {
    if n <= 50 {
        // exact in f64 (C(50, 25) < 2^53): eval's `binom` rounds its product to the integer
        return S::from_f64(binom(n, k));
    }
    (0..k).fold(S::one(), |acc, i| {
        acc * S::from_usize(n - i) / S::from_usize(i + 1)
    })
}

impl<S: Scalar> BezierSeg<S> {
    /// A polynomial segment over [a, b] from Cartesian control points (`dim` values each,
    /// row-major; degree = points - 1).
    pub fn from_points(a: f64, b: f64, dim: usize, pts: Vec<S>) -> Self {
        let degree = pts.len() / dim.max(1) - 1;
        BezierSeg {
            a,
            b,
            degree,
            dim,
            rational: false,
            pts,
        }
    }

    /// Degree elevation p -> p + 1 (Farin, Curves and Surfaces for CAGD, sec. 5.1; NURBS Book
    /// eq. 5.36 for one segment): Q_0 = P_0, Q_{p+1} = P_p and
    /// Q_i = (i P_{i-1} + (p + 1 - i) P_i) / (p + 1). Applied to the homogeneous rows it
    /// elevates rational segments as well; the curve is the same.
    ///
    /// Written with integer weights and one division (not as a (P_{i-1} - P_i) + P_i with a
    /// rounded a = i/(p+1)): each P occurs once, so intervals suffer no dependency, the
    /// products by small integers and the sum are exact for data of moderate precision (e.g.
    /// font coordinates), and then the result is the correctly rounded value — a singleton
    /// interval exactly when the elevated point is representable. For intervals the new
    /// points always enclose the exact ones.
    pub fn elevate(&self) -> BezierSeg<S> {
        let h = self.hdim();
        let p = self.degree;
        let mut q = Vec::with_capacity((p + 2) * h);
        q.extend_from_slice(&self.pts[..h]);
        let den = S::from_usize(p + 1);
        for i in 1..=p {
            let (wl, wr) = (S::from_usize(i), S::from_usize(p + 1 - i));
            for c in 0..h {
                let prev = self.pts[(i - 1) * h + c].clone();
                let cur = self.pts[i * h + c].clone();
                q.push((wl.clone() * prev + wr.clone() * cur) / den.clone());
            }
        }
        q.extend_from_slice(&self.pts[p * h..]);
        BezierSeg {
            degree: p + 1,
            pts: q,
            ..self.clone()
        }
    }

    /// Elevate `times` times.
    pub fn elevate_by(&self, times: usize) -> BezierSeg<S> {
        (0..times).fold(self.clone(), |s, _| s.elevate())
    }
}

impl BezierSeg<f64> {
    /// The segment as a clamped NURBS curve over [a, b] (knots a^(p+1) b^(p+1)); weights from
    /// the last row if rational. Fails (typed) if the data are not a valid curve.
    pub fn to_curve(&self) -> Result<NurbsCurve, CurveError> {
        let p = self.degree;
        let h = self.hdim();
        let mut knots = vec![self.a; p + 1];
        knots.extend(vec![self.b; p + 1]);
        let mut pts = Vec::with_capacity((p + 1) * self.dim);
        let mut w = Vec::with_capacity(p + 1);
        for c in self.pts.chunks(h) {
            let wi = if self.rational { c[self.dim] } else { 1.0 };
            pts.extend(c[..self.dim].iter().map(|x| x / wi));
            w.push(wi);
        }
        NurbsCurve::from_flat(p, self.dim, knots, pts, self.rational.then_some(w))
    }
}

/// The Bézier curve with the given control points (and weights) on [0, 1], as a
/// [`NurbsCurve`] (degree = number of points - 1).
pub fn bezier_curve(
    points: Vec<Vec<f64>>,
    weights: Option<Vec<f64>>,
) -> Result<NurbsCurve, CurveError> {
    let p = points.len().saturating_sub(1);
    let mut knots = vec![0.0; p + 1];
    knots.extend(vec![1.0; p + 1]);
    NurbsCurve::new(p, knots, points, weights)
}

/// The Bézier segments of a curve (one per non-empty span, NURBS Book A5.6), in S.
pub fn bezier_segments<S: Scalar>(c: &NurbsCurve) -> Vec<BezierSeg<S>> {
    HSpline::<S>::from_curve(c).decompose()
}

/// A segment in the monomial basis of the local parameter t in [0, 1]:
/// c(t) = sum_k a_k t^k (lecture "Modellierung mit Kurven", "Monombasis"), homogeneous rows
/// like [`BezierSeg`].
#[derive(Debug, Clone, PartialEq)]
pub struct MonomialSeg<S> {
    /// parameter interval start in the original curve
    pub a: f64,
    /// parameter interval end
    pub b: f64,
    /// degree
    pub degree: usize,
    /// Cartesian dimension
    pub dim: usize,
    /// whether the last row is the weight row
    pub rational: bool,
    /// coefficients a_0 .. a_p, row-major, `hdim` values each
    pub coeffs: Vec<S>,
}

impl<S: Scalar> MonomialSeg<S> {
    fn hdim(&self) -> usize {
        self.dim + self.rational as usize
    }

    /// Basis change Bernstein -> monomial (lecture "Modellierung mit Kurven",
    /// "Basistransformation", T_{M<-B}): a_k = C(p, k) Δ^k b_0, the k-th forward difference of
    /// the control points, which is the matrix of the source (for p = 3: rows
    /// 1 -3 3 -1 / 3 -6 3 / 3 -3 / 1) applied row-wise.
    pub fn from_bezier(s: &BezierSeg<S>) -> Self {
        let h = s.hdim();
        let p = s.degree;
        let mut diff = s.pts.clone();
        let mut coeffs = Vec::with_capacity(diff.len());
        for k in 0..=p {
            let f = binom_s::<S>(p, k);
            coeffs.extend((0..h).map(|c| f.clone() * diff[c].clone()));
            // next forward differences Δ^{k+1} b_i = Δ^k b_{i+1} - Δ^k b_i, i = 0..p-k-1
            for i in 0..p - k {
                for c in 0..h {
                    diff[i * h + c] = diff[(i + 1) * h + c].clone() - diff[i * h + c].clone();
                }
            }
        }
        MonomialSeg {
            a: s.a,
            b: s.b,
            degree: p,
            dim: s.dim,
            rational: s.rational,
            coeffs,
        }
    }

    /// Basis change monomial -> Bernstein (T_{B<-M} of the lecture "Modellierung mit Kurven",
    /// for p = 3 the matrix 1 0 0 0 / 1 1/3 0 0 / 1 2/3 1/3 0 / 1 1 1 1):
    /// b_i = sum_{k<=i} C(i, k) / C(p, k) a_k.
    pub fn to_bezier(&self) -> BezierSeg<S> {
        let h = self.hdim();
        let p = self.degree;
        let mut pts = vec![S::zero(); (p + 1) * h];
        for i in 0..=p {
            for k in 0..=i {
                let f = binom_s::<S>(i, k) / binom_s::<S>(p, k);
                for c in 0..h {
                    pts[i * h + c] =
                        pts[i * h + c].clone() + f.clone() * self.coeffs[k * h + c].clone();
                }
            }
        }
        BezierSeg {
            a: self.a,
            b: self.b,
            degree: p,
            dim: self.dim,
            rational: self.rational,
            pts,
        }
    }

    /// Horner evaluation at local t, all rows (lecture "Modellierung mit Kurven",
    /// "Hornerschema": f = a_g; for i = g-1..0: f = a_i + t f). O(p) per row.
    pub fn eval_horner(&self, t: &S) -> Vec<S> {
        let h = self.hdim();
        let p = self.degree;
        let mut f: Vec<S> = self.coeffs[p * h..].to_vec();
        for i in (0..p).rev() {
            for (c, fc) in f.iter_mut().enumerate() {
                *fc = self.coeffs[i * h + c].clone() + t.clone() * fc.clone();
            }
        }
        f
    }
}

/// A cubic segment in Hermite form over [a, b] (lecture "Modellierung mit Kurven",
/// "Hermite Interpolation"):
/// c(u) = H0(s) q0 + Δ H1(s) m0 + Δ H2(s) m1 + H3(s) q1, s = (u - a)/Δ, Δ = b - a, with
/// H0 = (1-s)^2 (1+2s), H1 = s (1-s)^2, H2 = -s^2 (1-s), H3 = (3-2s) s^2. So c(a) = q0,
/// c(b) = q1, c'(a) = m0, c'(b) = m1 (derivatives with respect to u).
#[derive(Debug, Clone, PartialEq)]
pub struct HermiteCubic<S> {
    /// start of the parameter interval
    pub a: f64,
    /// end of the parameter interval
    pub b: f64,
    /// start point
    pub q0: Vec<S>,
    /// start tangent dc/du
    pub m0: Vec<S>,
    /// end point
    pub q1: Vec<S>,
    /// end tangent dc/du
    pub m1: Vec<S>,
}

impl<S: Scalar> HermiteCubic<S> {
    /// The Bézier form: b0 = q0, b1 = q0 + Δ m0 / 3, b2 = q1 - Δ m1 / 3, b3 = q1 (end
    /// derivative of a Bézier cubic is 3 (b1 - b0) / Δ; lecture "Modellierung mit Kurven",
    /// "Endtangenteninterpolation").
    pub fn to_bezier(&self) -> Result<BezierSeg<S>, BezierToolError> {
        let dt = self.delta()?;
        let f = dt / S::from_usize(3);
        let d = self.q0.len();
        let mut pts = Vec::with_capacity(4 * d);
        pts.extend(self.q0.iter().cloned());
        pts.extend((0..d).map(|j| self.q0[j].clone() + f.clone() * self.m0[j].clone()));
        pts.extend((0..d).map(|j| self.q1[j].clone() - f.clone() * self.m1[j].clone()));
        pts.extend(self.q1.iter().cloned());
        Ok(BezierSeg::from_points(self.a, self.b, d, pts))
    }

    /// The Hermite form of a polynomial cubic Bézier segment: m0 = 3 (b1 - b0) / Δ,
    /// m1 = 3 (b3 - b2) / Δ.
    pub fn from_bezier(s: &BezierSeg<S>) -> Result<Self, BezierToolError> {
        if s.degree != 3 {
            return Err(BezierToolError::NotCubic { degree: s.degree });
        }
        if s.rational {
            return Err(BezierToolError::Rational);
        }
        let d = s.dim;
        let pt = |i: usize| &s.pts[i * d..(i + 1) * d];
        let mut h = HermiteCubic {
            a: s.a,
            b: s.b,
            q0: pt(0).to_vec(),
            m0: Vec::new(),
            q1: pt(3).to_vec(),
            m1: Vec::new(),
        };
        let f = S::from_usize(3) / h.delta()?;
        h.m0 = (0..d)
            .map(|j| f.clone() * (pt(1)[j].clone() - pt(0)[j].clone()))
            .collect();
        h.m1 = (0..d)
            .map(|j| f.clone() * (pt(3)[j].clone() - pt(2)[j].clone()))
            .collect();
        Ok(h)
    }

    /// Evaluate with the Hermite basis at local s in [0, 1] (u = a + s Δ).
    pub fn eval_local(&self, s: &S) -> Result<Vec<S>, BezierToolError> {
        let dt = self.delta()?;
        let one = S::one();
        let two = S::from_usize(2);
        let r = one.clone() - s.clone();
        let h0 = r.clone() * r.clone() * (one + two.clone() * s.clone());
        let h1 = s.clone() * r.clone() * r.clone();
        let h2 = -(s.clone() * s.clone() * r);
        let h3 = (S::from_usize(3) - two * s.clone()) * s.clone() * s.clone();
        Ok((0..self.q0.len())
            .map(|j| {
                h0.clone() * self.q0[j].clone()
                    + dt.clone()
                        * (h1.clone() * self.m0[j].clone() + h2.clone() * self.m1[j].clone())
                    + h3.clone() * self.q1[j].clone()
            })
            .collect())
    }

    fn delta(&self) -> Result<S, BezierToolError> {
        if !(self.a.is_finite() && self.b.is_finite() && self.a < self.b) {
            return Err(BezierToolError::BadInterval {
                a: self.a,
                b: self.b,
            });
        }
        Ok(S::from_f64(self.b) - S::from_f64(self.a))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::iv;
    use inari::Interval;

    #[test]
    fn basis_change_example_of_seed_004() {
        // f = 2 B0 - 2 B1 + 5 B2 + 1 B3 (lecture "Modellierung mit Kurven", slide "Polynombasen
        // Vergleich"). The slide gives 2 - 12 t + 33 t^2 - 23 t^3, but its own expansion sums the
        // t^3 terms to -2 - 6 - 15 + 1 = -22 (= b3 - 3 b2 + 3 b1 - b0): the slide has a typo.
        let s = BezierSeg::<f64>::from_points(0.0, 1.0, 1, vec![2., -2., 5., 1.]);
        let m = MonomialSeg::from_bezier(&s);
        assert_eq!(m.coeffs, vec![2., -12., 33., -22.]);
        let back = m.to_bezier();
        for (x, y) in back.pts.iter().zip(&s.pts) {
            assert!((x - y).abs() < 1e-14);
        }
        // intervals enclose the exact coefficients (here integers)
        let si = BezierSeg::<Interval>::from_points(
            0.0,
            1.0,
            1,
            [2., -2., 5., 1.].iter().map(|&x| iv::point(x)).collect(),
        );
        let bi = MonomialSeg::from_bezier(&si).to_bezier();
        for (x, y) in bi.pts.iter().zip(&s.pts) {
            assert!(x.contains(*y));
        }
    }

    #[test]
    fn horner_de_casteljau_and_hermite_agree() {
        let pts = vec![0., 0., 1., 3., 4., -1., 5., 2.];
        let s = BezierSeg::<f64>::from_points(1.0, 3.0, 2, pts);
        let m = MonomialSeg::from_bezier(&s);
        let h = HermiteCubic::from_bezier(&s).unwrap();
        assert_eq!(h.m0, vec![1.5, 4.5]);
        for i in 0..=20 {
            let t = i as f64 / 20.0;
            let a = s.eval_local(&t);
            let b = m.eval_horner(&t);
            let c = h.eval_local(&t).unwrap();
            for j in 0..2 {
                assert!((a[j] - b[j]).abs() < 1e-13 && (a[j] - c[j]).abs() < 1e-13);
            }
        }
        let back = h.to_bezier().unwrap();
        for (x, y) in back.pts.iter().zip(&s.pts) {
            assert!((x - y).abs() < 1e-14);
        }
        // end tangents of the curve are the Hermite tangents
        let c = s.to_curve().unwrap();
        let d: Vec<f64> = c.derivative(1.0, 1).unwrap();
        assert!((d[0] - 1.5).abs() < 1e-14 && (d[1] - 4.5).abs() < 1e-14);
    }

    #[test]
    fn hermite_errors() {
        let s = BezierSeg::<f64>::from_points(0.0, 1.0, 1, vec![0., 1., 2.]);
        assert_eq!(
            HermiteCubic::from_bezier(&s).unwrap_err(),
            BezierToolError::NotCubic { degree: 2 }
        );
        let c = bezier_curve(
            vec![vec![0.], vec![1.], vec![2.], vec![3.]],
            Some(vec![1., 2., 1., 1.]),
        )
        .unwrap();
        let r = &bezier_segments::<f64>(&c)[0];
        assert_eq!(
            HermiteCubic::from_bezier(r).unwrap_err(),
            BezierToolError::Rational
        );
        let s = BezierSeg::<f64>::from_points(1.0, 1.0, 1, vec![0., 1., 2., 3.]);
        assert!(matches!(
            HermiteCubic::from_bezier(&s),
            Err(BezierToolError::BadInterval { .. })
        ));
    }

    #[test]
    fn elevation_of_a_rational_segment_keeps_the_curve() {
        let c = bezier_curve(
            vec![vec![1., 0.], vec![1., 1.], vec![0., 1.]],
            Some(vec![1., std::f64::consts::FRAC_1_SQRT_2, 1.]),
        )
        .unwrap();
        let s = &bezier_segments::<f64>(&c)[0];
        let e = s.elevate_by(3);
        assert_eq!(e.degree, 5);
        let ce = e.to_curve().unwrap();
        for i in 0..=10 {
            let u = i as f64 / 10.0;
            let a: Vec<f64> = c.point(u).unwrap();
            let b: Vec<f64> = ce.point(u).unwrap();
            assert!((a[0] - b[0]).abs() < 1e-15 && (a[1] - b[1]).abs() < 1e-15);
        }
    }

    #[test]
    fn large_degree_binomials_enclose() {
        let b: Interval = binom_s(60, 30);
        assert!(b.contains(118264581564861424.0));
        assert_eq!(binom(10, 3), 120.0);
    }
}
