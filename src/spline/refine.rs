//! Refinement on the f64 curve model: knot insertion, subdivision, Bézier decomposition.
//! The kernels are the generic ones in [`crate::HSpline`]; here they run in f64 and the result
//! is converted back to a [`NurbsCurve`] (so these are *not* exact: use `HSpline<Interval>` for
//! verified refinement).

use crate::error::EvalError;
use crate::spline::bspline::HSpline;
use crate::spline::curve::NurbsCurve;

fn from_hspline(h: &HSpline<f64>) -> NurbsCurve {
    // Knot insertion keeps weights positive (convex combinations) and the knot vector valid,
    // so this cannot fail for a curve built from a valid one.
    to_curve(h).expect("refinement of a valid curve is valid")
}

/// The curve of an f64 spline, or `None` when its data are not a valid curve (e.g. knot
/// removal beyond tolerance can make a weight non-positive).
pub(crate) fn to_curve(h: &HSpline<f64>) -> Option<NurbsCurve> {
    let hd = h.hdim();
    let d = h.dim;
    let mut pts = Vec::with_capacity(h.npts() * d);
    let mut w = Vec::with_capacity(h.npts());
    for c in h.pts.chunks(hd) {
        let wi = if h.rational { c[d] } else { 1.0 };
        pts.extend(c[..d].iter().map(|x| if h.rational { x / wi } else { *x }));
        w.push(wi);
    }
    NurbsCurve::from_flat(h.degree, d, h.knots.clone(), pts, h.rational.then_some(w)).ok()
}

impl NurbsCurve {
    fn check(&self, u: f64) -> Result<(), EvalError> {
        crate::spline::eval::check_domain(self.domain(), u)
    }

    /// Insert the knot u r times (NURBS Book A5.1; thesis eq. 4.12, 4.15/4.16). Insertions
    /// beyond multiplicity p are ignored. The curve is unchanged up to f64 rounding.
    pub fn insert_knot(&self, u: f64, r: usize) -> Result<NurbsCurve, EvalError> {
        self.check(u)?;
        Ok(from_hspline(
            &HSpline::<f64>::from_curve(self).insert_knot(u, r),
        ))
    }

    /// Split at an interior parameter u (thesis sec. 4.2, "Unterteilen der Kurve": subdivision by
    /// inserting u p times): the curves over [a, u] and [u, b].
    pub fn split_at(&self, u: f64) -> Result<(NurbsCurve, NurbsCurve), EvalError> {
        self.check(u)?;
        let (a, b) = self.domain();
        if u == a || u == b {
            return Err(EvalError::ParamOutOfDomain {
                param: u,
                start: a,
                end: b,
            });
        }
        let p = self.degree();
        let h = HSpline::<f64>::from_curve(self).insert_knot(u, p);
        let hd = h.hdim();
        // after insertion u has multiplicity >= p; the point at u is P_j, j = last(u) - p
        let last = h.knots.partition_point(|&x| x <= u) - 1;
        let j = last - p;
        // Multiplicity p + 1 (the curve jumps at u): the left piece ends with P_{j-1} (its
        // limit at u) and already has u p + 1 times; with multiplicity p, P_j is shared and
        // the left knots get one more u.
        let jump = crate::spline::knots::multiplicity(&h.knots, u) > p;
        let (lk, lpts) = if jump {
            (h.knots[..=last].to_vec(), h.pts[..j * hd].to_vec())
        } else {
            let mut lk = h.knots[..=j + p].to_vec();
            lk.push(u);
            (lk, h.pts[..(j + 1) * hd].to_vec())
        };
        let mut rk = vec![u];
        rk.extend_from_slice(&h.knots[j + 1..]);
        let left = HSpline {
            knots: lk,
            pts: lpts,
            ..h.clone()
        };
        let right = HSpline {
            knots: rk,
            pts: h.pts[j * hd..].to_vec(),
            ..h
        };
        Ok((from_hspline(&left), from_hspline(&right)))
    }

    /// Bézier decomposition (NURBS Book A5.6): one Bézier curve (clamped, knots {a^(p+1),
    /// b^(p+1)}) per non-empty span of the domain.
    pub fn bezier_segments(&self) -> Vec<NurbsCurve> {
        HSpline::<f64>::from_curve(self)
            .decompose()
            .into_iter()
            .map(|s| {
                let p = s.degree;
                let mut knots = vec![s.a; p + 1];
                knots.extend(std::iter::repeat_n(s.b, p + 1));
                from_hspline(&HSpline {
                    degree: p,
                    knots,
                    dim: s.dim,
                    rational: s.rational,
                    pts: s.pts,
                })
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use inari::Interval;

    fn curve() -> NurbsCurve {
        NurbsCurve::new(
            3,
            vec![-1., -0.5, 0., 0.3, 0.7, 0.7, 1.2, 2., 2.5, 3.],
            vec![
                vec![0., 1.],
                vec![1., 3.],
                vec![2., -1.],
                vec![4., 0.5],
                vec![3., 3.],
                vec![5., 2.],
            ],
            Some(vec![1., 2., 0.5, 1., 3., 1.]),
        )
        .unwrap()
    }

    fn close(a: &[f64], b: &[f64]) -> bool {
        a.iter()
            .zip(b)
            .all(|(x, y)| (x - y).abs() <= 1e-12 * (1. + x.abs()))
    }

    #[test]
    fn insertion_split_and_decomposition_keep_the_curve() {
        let c = curve();
        let (a, b) = c.domain();
        let ins = c.insert_knot(0.5, 2).unwrap();
        let (l, r) = c.split_at(0.9).unwrap();
        let segs = c.bezier_segments();
        assert_eq!(segs.len(), 2);
        for i in 0..=200 {
            let u = a + (b - a) * i as f64 / 200.0;
            let p: Vec<f64> = c.point(u).unwrap();
            let enc: Vec<Interval> = c.point(u).unwrap();
            assert!(close(&p, &ins.point::<f64>(u).unwrap()));
            let side = if u <= 0.9 { &l } else { &r };
            assert!(close(&p, &side.point::<f64>(u).unwrap()));
            let seg = segs
                .iter()
                .find(|s| s.domain().0 <= u && u <= s.domain().1)
                .unwrap();
            let q: Vec<f64> = seg.point(u).unwrap();
            assert!(close(&p, &q));
            // verified Bézier extraction encloses the f64 evaluation too
            let hs = HSpline::<Interval>::from_curve(&c).bezier_segment(c.find_span(u));
            let t = (u - hs.a) / (hs.b - hs.a);
            let v = crate::spline::eval::project(
                hs.eval_local(&Interval::try_from((t, t)).unwrap()),
                2,
                true,
            );
            for j in 0..2 {
                assert!(v[j].inf() - 1e-12 <= p[j] && p[j] <= v[j].sup() + 1e-12);
                assert!(enc[j].contains(p[j]));
            }
        }
    }

    #[test]
    fn split_at_a_jump_knot_is_valid_and_keeps_the_curve() {
        // regression: multiplicity p + 1 at u gave a left knot vector with u p + 2 times
        let c = NurbsCurve::new(
            1,
            vec![0., 0., 0.5, 0.5, 1., 1.],
            vec![vec![0.], vec![1.], vec![5.], vec![6.]],
            None,
        )
        .unwrap();
        let (l, r) = c.split_at(0.5).unwrap();
        assert_eq!(l.knots(), &[0., 0., 0.5, 0.5]);
        assert_eq!(l.control_points(), vec![vec![0.], vec![1.]]);
        assert_eq!(r.knots(), &[0.5, 0.5, 1., 1.]);
        assert_eq!(r.point::<f64>(0.5).unwrap(), c.point::<f64>(0.5).unwrap());
        assert_eq!(l.point::<f64>(0.25).unwrap(), c.point::<f64>(0.25).unwrap());
    }

    #[test]
    fn insertion_at_an_unclamped_domain_end_keeps_the_curve() {
        // regression: A5.1 was given the total multiplicity of u = u_{n+1} as s
        let c = NurbsCurve::new(
            2,
            vec![0., 1., 2., 3., 4., 5., 6.],
            vec![vec![0.], vec![1.], vec![3.], vec![-2.]],
            None,
        )
        .unwrap();
        let (a, b) = c.domain();
        for r in 1..=2 {
            for u0 in [a, b] {
                let ins = c.insert_knot(u0, r).unwrap();
                assert_eq!(ins.domain(), (a, b));
                for i in 0..=20 {
                    let u = a + (b - a) * i as f64 / 20.0;
                    assert!(close(
                        &c.point::<f64>(u).unwrap(),
                        &ins.point::<f64>(u).unwrap()
                    ));
                }
            }
        }
    }
}
