//! NURBS evaluation: points and derivatives, f64 / interval / MPFR, point or interval
//! parameters.

use crate::error::EvalError;
use crate::num::{iv, Scalar};
use crate::spline::bspline::{basis_funs, HSpline};
use crate::spline::curve::NurbsCurve;
use inari::Interval;

use crate::num::binom;

/// Precomputed homogeneous derivative splines A^(l), w^(l), l = 0..=order (thesis eq. 2.7,
/// applied to the homogeneous curve), for repeated evaluation of C, C', C'', ...
///
/// Rational derivatives follow thesis eq. 3.10 (NURBS Book eq. 4.8):
/// C^(k) = (A^(k) - sum_{i=1}^{k} binom(k, i) w^(i) C^(k-i)) / w.
#[derive(Debug, Clone)]
pub struct CurveEval<S> {
    levels: Vec<HSpline<S>>,
    domain: (f64, f64),
}

impl<S: Scalar> CurveEval<S> {
    /// Precompute derivative control points up to `order`.
    pub fn new(c: &NurbsCurve, order: usize) -> Self {
        let mut levels = vec![HSpline::<S>::from_curve(c)];
        for _ in 0..order {
            let d = levels.last().unwrap().derivative();
            levels.push(d);
        }
        CurveEval {
            levels,
            domain: c.domain(),
        }
    }

    /// Highest derivative order available.
    pub fn order(&self) -> usize {
        self.levels.len() - 1
    }

    /// The homogeneous spline of order l.
    pub fn level(&self, l: usize) -> &HSpline<S> {
        &self.levels[l]
    }

    /// Cartesian dimension.
    pub fn dim(&self) -> usize {
        self.levels[0].dim
    }

    /// Span index (of the curve itself) of an f64 parameter.
    pub fn span(&self, u: f64) -> usize {
        self.levels[0].span(u)
    }

    /// C, C', ..., C^(k) at parameter `u` lying in span `span` (of the curve), k <= order.
    /// For an interval `u` inside the closed span this encloses the values over all of `u`.
    pub fn derivs_in_span(&self, span: usize, u: &S, k: usize) -> Vec<Vec<S>> {
        let rows: Vec<usize> = (0..self.levels[0].hdim()).collect();
        self.rows_derivs_in_span(span, u, k, &rows)
    }

    /// C_j, C_j', ..., C_j^(k) of coordinate j alone at `u` in span `span` (k <= order): the
    /// evaluation of [`CurveEval::derivs_in_span`] on the rows of coordinate j and the weight
    /// only (1/d of the work; the values are those of the full evaluation, row by row).
    pub fn coord_derivs_in_span(&self, span: usize, u: &S, k: usize, j: usize) -> Vec<S> {
        let all = [j, self.dim()];
        let rows = &all[..1 + self.levels[0].rational as usize];
        let v = self.rows_derivs_in_span(span, u, k, rows);
        v.into_iter().map(|mut v| v.swap_remove(0)).collect()
    }

    /// The shared body: de Boor corner cutting of the given homogeneous rows (the weight row,
    /// if rational, last) on every derivative level, then the rational quotient rule (thesis
    /// eq. 3.10) on the Cartesian rows.
    fn rows_derivs_in_span(&self, span: usize, u: &S, k: usize, rows: &[usize]) -> Vec<Vec<S>> {
        assert!(k <= self.order(), "derivative order {k} not precomputed");
        let mut hom: Vec<Vec<S>> = Vec::with_capacity(k + 1);
        let mut buf = Vec::new();
        for l in 0..=k {
            if l > self.levels[0].degree {
                hom.push(vec![S::zero(); rows.len()]);
            } else {
                let v = self.levels[l].eval_span_rows(span - l, u, rows, &mut buf);
                hom.push(v.to_vec());
            }
        }
        if !self.levels[0].rational {
            return hom;
        }
        quotient_rule(&hom, rows.len() - 1)
    }

    /// C^(l)(u) for l = 0..=k at an f64 parameter in the domain.
    pub fn derivs(&self, u: f64, k: usize) -> Result<Vec<Vec<S>>, EvalError> {
        check_domain(self.domain, u)?;
        Ok(self.derivs_in_span(self.span(u), &S::from_f64(u), k))
    }
}

impl CurveEval<Interval> {
    /// Enclosure of C^(l)(u) for l = 0..=k over all u in [a, b] (clipped to the domain), split at
    /// the knots it straddles and hulled (each piece is one polynomial).
    pub fn enclose_over(&self, c: &NurbsCurve, a: f64, b: f64, k: usize) -> Vec<Vec<Interval>> {
        let mut acc: Option<Vec<Vec<Interval>>> = None;
        let mut pieces = c.spans_straddled(a, b);
        // The value at an interior knot b belongs to the span that starts at b (find_span:
        // u_k <= u < u_{k+1}), which the straddled spans (ending at b) do not include. It
        // differs from the left piece's limit where some C^(l), l <= k, may jump: at a knot
        // of multiplicity m with m + k > p (C is C^{p-m} there). Add the point piece [b, b].
        if let Some(&(last, _, hi)) = pieces.last() {
            let kb = c.find_span(hi);
            if kb != last && crate::spline::knots::multiplicity(c.knots(), hi) + k > c.degree() {
                pieces.push((kb, hi, hi));
            }
        }
        for (span, lo, hi) in pieces {
            let v = self.derivs_in_span(span, &iv::span(lo, hi), k);
            acc = Some(match acc {
                None => v,
                Some(a) => a
                    .into_iter()
                    .zip(v)
                    .map(|(x, y)| {
                        x.into_iter()
                            .zip(y)
                            .map(|(s, t)| s.convex_hull(t))
                            .collect()
                    })
                    .collect(),
            });
        }
        acc.unwrap_or_else(|| vec![vec![Interval::EMPTY; c.dim()]; k + 1])
    }
}

pub(crate) fn check_domain((a, b): (f64, f64), u: f64) -> Result<(), EvalError> {
    if u >= a && u <= b {
        Ok(())
    } else {
        Err(EvalError::ParamOutOfDomain {
            param: u,
            start: a,
            end: b,
        })
    }
}

impl NurbsCurve {
    /// C(u) by de Boor corner cutting in homogeneous coordinates (thesis CurvePntByCornerCut and
    /// CurvePntByCornerCut_int), in any [`Scalar`]. With `S = Interval` the result is a verified
    /// enclosure of the exact point.
    pub fn point<S: Scalar>(&self, u: f64) -> Result<Vec<S>, EvalError> {
        check_domain(self.domain(), u)?;
        let h = HSpline::<S>::from_curve(self);
        let v = h.eval(u);
        Ok(project(v, self.dim(), self.is_rational()))
    }

    /// C(u) as the basis-function sum (thesis CurvePoint2 / NURBS Book A4.1 with A2.2).
    pub fn point_by_basis<S: Scalar>(&self, u: f64) -> Result<Vec<S>, EvalError> {
        check_domain(self.domain(), u)?;
        let p = self.degree();
        let k = self.find_span(u);
        let n = basis_funs(self.knots(), k, &S::from_f64(u), p);
        let d = self.dim();
        let mut acc = vec![S::zero(); d + 1];
        for (i, ni) in n.into_iter().enumerate() {
            let idx = k - p + i;
            let w = S::from_f64(self.weight(idx));
            let nw = ni * w;
            for (j, x) in self.control_point(idx).iter().enumerate() {
                acc[j] = acc[j].clone() + nw.clone() * S::from_f64(*x);
            }
            acc[d] = acc[d].clone() + nw;
        }
        let w = acc.pop().unwrap();
        Ok(acc.into_iter().map(|x| x / w.clone()).collect())
    }

    /// The k-th derivative C^(k)(u) (k = 0 is the point) in any [`Scalar`] (thesis Diff /
    /// Diff_intKNR: derivative control points eq. 2.7 and rational derivatives eq. 3.10).
    pub fn derivative<S: Scalar>(&self, u: f64, k: usize) -> Result<Vec<S>, EvalError> {
        let e = CurveEval::<S>::new(self, k);
        Ok(e.derivs(u, k)?.pop().unwrap())
    }

    /// Verified enclosure of C^(k)(u) for all u in the interval `u` (which must lie in the
    /// domain). Parameter intervals that straddle knots are split at them and the pieces hulled.
    pub fn enclose_derivative(&self, u: Interval, k: usize) -> Result<Vec<Interval>, EvalError> {
        let (a, b) = self.domain();
        if u.is_empty() || u.inf() < a || u.sup() > b {
            return Err(EvalError::ParamOutOfDomain {
                param: if u.is_empty() {
                    f64::NAN
                } else if u.inf() < a {
                    u.inf()
                } else {
                    u.sup()
                },
                start: a,
                end: b,
            });
        }
        let e = CurveEval::<Interval>::new(self, k);
        Ok(e.enclose_over(self, u.inf(), u.sup(), k).pop().unwrap())
    }

    /// Whether each domain end is clamped: C(u_p) = P_0 exactly when u_1 = u_p, and
    /// C(u_{n+1}) = P_n exactly when u_{n+1} = u_{n+p} (the de Boor triangle collapses to the
    /// end control point; for rational curves too, the weights cancel).
    pub fn clamped_ends(&self) -> [bool; 2] {
        let (p, n, k) = (self.degree(), self.num_points() - 1, self.knots());
        // (and the end span must be the one of P_0 / P_n: u_p < u_{p+1}, u_n < u_{n+1})
        [
            k[1] == k[p] && k[p] < k[p + 1],
            k[n + 1] == k[n + p] && k[n] < k[n + 1],
        ]
    }

    /// Verified enclosures of C at the two domain ends: exact point intervals of P_0 / P_n at a
    /// clamped end (see [`NurbsCurve::clamped_ends`]), de Boor in verified midpoint-radius
    /// arithmetic otherwise (a few ulps wide at low degree, a few hundred at degree 40).
    pub fn end_values(&self) -> [Vec<Interval>; 2] {
        let (a, b) = self.domain();
        let cl = self.clamped_ends();
        let n = self.num_points() - 1;
        // (the homogeneous spline built once, and only for an unclamped end; de Boor in
        // midpoint-radius arithmetic, `Mr`: verified like inari's intervals, a few hundred
        // ulps wide at degree 40 instead of one, at a twentieth of the cost)
        let h = (!(cl[0] && cl[1])).then(|| HSpline::<crate::num::Mr>::from_curve(self));
        let at = |i: usize, u: f64, clamped: bool| -> Vec<Interval> {
            match (&h, clamped) {
                (Some(h), false) => {
                    let v: Vec<Interval> = h.eval(u).iter().map(|x| x.to_interval()).collect();
                    project(v, self.dim(), self.is_rational())
                }
                _ => self
                    .control_point(i)
                    .iter()
                    .map(|&x| iv::point(x))
                    .collect(),
            }
        };
        [at(0, a, cl[0]), at(n, b, cl[1])]
    }

    /// Verified enclosure of C(u) for all u in the interval `u` (see
    /// [`NurbsCurve::enclose_derivative`]).
    pub fn enclose_point(&self, u: Interval) -> Result<Vec<Interval>, EvalError> {
        self.enclose_derivative(u, 0)
    }
}

/// The rational quotient rule (thesis eq. 3.10, NURBS Book eq. 4.8), the one generic copy:
/// from the homogeneous derivatives `hom[l]` = (A^(l), w^(l)) (`dim + 1` values each,
/// l = 0..=k) the Cartesian C^(l) = (A^(l) - sum_{i=1}^{l} binom(l, i) w^(i) C^(l-i)) / w,
/// l = 0..=k. Each step is a field operation, so for verified types every C^(l) encloses the
/// exact derivative (binomials exact in f64).
pub fn quotient_rule<S: Scalar>(hom: &[Vec<S>], d: usize) -> Vec<Vec<S>> {
    let w0 = hom[0][d].clone();
    let mut out: Vec<Vec<S>> = Vec::with_capacity(hom.len());
    for l in 0..hom.len() {
        let mut v: Vec<S> = hom[l][..d].to_vec();
        for i in 1..=l {
            let f = S::from_f64(binom(l, i)) * hom[i][d].clone();
            for (j, vj) in v.iter_mut().enumerate() {
                *vj = vj.clone() - f.clone() * out[l - i][j].clone();
            }
        }
        for vj in v.iter_mut() {
            *vj = vj.clone() / w0.clone();
        }
        out.push(v);
    }
    out
}

/// Homogeneous -> Cartesian (thesis helper `Hinv`): divide by the weight row if rational.
pub fn project<S: Scalar>(v: Vec<S>, dim: usize, rational: bool) -> Vec<S> {
    crate::spline::bezier::cartesian(v, dim, rational)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The 9-point rational quadratic unit circle (NURBS Book ex. 7.2).
    pub(crate) fn circle() -> NurbsCurve {
        crate::testkit::gen::nurbs_circle()
    }

    #[test]
    fn circle_points_have_unit_norm_within_enclosure() {
        // The weight 1/sqrt(2) is rounded, so the curve is a circle only up to ~1e-16:
        // the enclosure of |C|^2 must contain 1 up to that.
        let c = circle();
        for i in 0..=1000 {
            let u = i as f64 / 1000.0;
            let p: Vec<Interval> = c.point(u).unwrap();
            let r2 = p[0] * p[0] + p[1] * p[1];
            assert!(r2.inf() <= 1.0 + 1e-15 && r2.sup() >= 1.0 - 1e-15, "u={u}");
            assert!(r2.wid() < 1e-14);
            let f: Vec<f64> = c.point(u).unwrap();
            // f64 evaluation has its own rounding errors: it lies within a few ulps of the
            // (exact-containing) enclosure, not necessarily inside it.
            for j in 0..2 {
                assert!(
                    p[j].inf() - 4e-16 <= f[j] && f[j] <= p[j].sup() + 4e-16,
                    "u={u}"
                );
            }
            let g: Vec<f64> = c.point_by_basis(u).unwrap();
            assert!((g[0] - f[0]).abs() < 1e-15 && (g[1] - f[1]).abs() < 1e-15);
        }
    }

    #[test]
    fn derivative_of_cubic_bezier_matches_closed_form() {
        // B(t) = (1-t)^3 P0 + 3(1-t)^2 t P1 + 3(1-t) t^2 P2 + t^3 P3
        let pts = [0.0, 1.0, -2.0, 5.0];
        let c = NurbsCurve::new(
            3,
            vec![0., 0., 0., 0., 1., 1., 1., 1.],
            pts.iter().map(|&x| vec![x]).collect(),
            None,
        )
        .unwrap();
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            let s = 1.0 - t;
            let b = s * s * s * pts[0]
                + 3. * s * s * t * pts[1]
                + 3. * s * t * t * pts[2]
                + t * t * t * pts[3];
            let d1 = 3.
                * (s * s * (pts[1] - pts[0])
                    + 2. * s * t * (pts[2] - pts[1])
                    + t * t * (pts[3] - pts[2]));
            let d2 =
                6. * (s * (pts[2] - 2. * pts[1] + pts[0]) + t * (pts[3] - 2. * pts[2] + pts[1]));
            let e: Vec<Vec<Interval>> = CurveEval::<Interval>::new(&c, 3).derivs(t, 3).unwrap();
            for (v, ex) in [
                (0, b),
                (1, d1),
                (2, d2),
                (3, 6. * (pts[3] - 3. * pts[2] + 3. * pts[1] - pts[0])),
            ] {
                let x = e[v][0];
                assert!(
                    x.inf() - 1e-12 <= ex && ex <= x.sup() + 1e-12,
                    "t={t} order {v}: {ex} vs [{}, {}]",
                    x.inf(),
                    x.sup()
                );
            }
        }
    }

    #[test]
    fn rational_derivative_of_circle_is_tangent() {
        let c = circle();
        for i in 0..100 {
            let u = i as f64 / 100.0;
            let e = CurveEval::<f64>::new(&c, 2).derivs(u, 2).unwrap();
            let dot = e[0][0] * e[1][0] + e[0][1] * e[1][1];
            assert!(dot.abs() < 1e-12, "C.C' = {dot} at {u}");
            let ei = CurveEval::<Interval>::new(&c, 2).derivs(u, 2).unwrap();
            for l in 0..3 {
                for j in 0..2 {
                    assert!(ei[l][j].contains(e[l][j]) || (ei[l][j].inf() - e[l][j]).abs() < 1e-12);
                }
            }
        }
    }

    #[test]
    fn interval_param_straddling_knots_encloses_samples() {
        let c = circle();
        let enc = c.enclose_point(iv::span(0.2, 0.6)).unwrap();
        for i in 0..=400 {
            let u = 0.2 + 0.4 * i as f64 / 400.0;
            let f: Vec<f64> = c.point(u.min(0.6)).unwrap();
            assert!(enc[0].contains(f[0]) && enc[1].contains(f[1]));
        }
        assert!(c.enclose_point(iv::span(0.2, 1.5)).is_err());
        assert!(c.point::<f64>(-0.1).is_err());
    }

    #[test]
    fn enclosure_ending_at_a_jump_knot_contains_the_value_there() {
        // regression: C(b) of a knot b of multiplicity p + 1 comes from the span starting at
        // b, which the straddled spans of [a, b] did not include
        let c = NurbsCurve::new(
            1,
            vec![0., 0., 0.5, 0.5, 1., 1.],
            vec![vec![0.], vec![1.], vec![5.], vec![6.]],
            None,
        )
        .unwrap();
        let e = c.enclose_point(iv::span(0.25, 0.5)).unwrap();
        assert!(e[0].contains(5.0) && e[0].contains(0.5), "{e:?}");
        // C' of a quadratic with a double knot (C^0) at 0.5: right derivative at 0.5
        let q = NurbsCurve::new(
            2,
            vec![0., 0., 0., 0.5, 0.5, 1., 1., 1.],
            vec![vec![0.], vec![1.], vec![0.], vec![3.], vec![0.]],
            None,
        )
        .unwrap();
        let d: Vec<f64> = q.derivative(0.5, 1).unwrap();
        let e = q.enclose_derivative(iv::span(0.1, 0.5), 1).unwrap();
        assert!(e[0].contains(d[0]), "{d:?} {e:?}");
    }
}
