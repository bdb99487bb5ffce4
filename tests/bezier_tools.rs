//! Properties of the Bézier tools (lecture "Modellierung mit Kurven"): basis changes round-trip,
//! Horner and de Casteljau agree, Hermite form round-trips, degree elevation keeps the curve
//! (verified: the interval enclosures of the original and the elevated segment at the same t always
//! overlap).

use inari::Interval;
use nurbs_box::build::bezier_tools::{HermiteCubic, MonomialSeg};
use nurbs_box::num::iv;
use nurbs_box::BezierSeg;
use proptest::prelude::*;

fn segments() -> impl Strategy<Value = (usize, Vec<f64>, Option<Vec<f64>>)> {
    (1usize..4, 1usize..9, prop::bool::ANY).prop_flat_map(|(d, p, rat)| {
        (
            Just(d),
            prop::collection::vec(-100.0f64..100.0, (p + 1) * d),
            if rat {
                prop::collection::vec(0.05f64..20.0, p + 1)
                    .prop_map(Some)
                    .boxed()
            } else {
                Just(None).boxed()
            },
        )
    })
}

fn hom<S: nurbs_box::Scalar>(d: usize, pts: &[f64], w: &Option<Vec<f64>>) -> BezierSeg<S> {
    let mut h = Vec::new();
    for (i, c) in pts.chunks(d).enumerate() {
        match w {
            Some(w) => {
                h.extend(c.iter().map(|x| S::from_f64(w[i]) * S::from_f64(*x)));
                h.push(S::from_f64(w[i]));
            }
            None => h.extend(c.iter().map(|x| S::from_f64(*x))),
        }
    }
    BezierSeg {
        a: 0.0,
        b: 1.0,
        degree: pts.len() / d - 1,
        dim: d,
        rational: w.is_some(),
        pts: h,
    }
}

fn close(x: &[f64], y: &[f64], tol: f64) -> bool {
    x.iter().zip(y).all(|(a, b)| (a - b).abs() <= tol)
}

proptest! {
    #[test]
    fn monomial_round_trip_and_horner((d, pts, w) in segments(), t in 0.0f64..=1.0) {
        let s: BezierSeg<f64> = hom(d, &pts, &w);
        let m = MonomialSeg::from_bezier(&s);
        let back = m.to_bezier();
        let scale = s.pts.iter().fold(1.0f64, |a, x| a.max(x.abs()));
        // the monomial coefficients grow like 2^p |b|; the round trip loses that factor
        prop_assert!(close(&back.pts, &s.pts, 1e-13 * scale * (1 << s.degree) as f64));
        prop_assert!(close(&m.eval_horner(&t), &s.eval_local(&t), 1e-12 * scale * (1 << s.degree) as f64));
        // verified: the interval versions at the same t overlap (both enclose the exact value)
        let si: BezierSeg<Interval> = hom(d, &pts, &w);
        let mi = MonomialSeg::from_bezier(&si);
        let ti = iv::point(t);
        for (x, y) in mi.eval_horner(&ti).iter().zip(si.eval_local(&ti)) {
            prop_assert!(!x.intersection(y).is_empty(), "{x:?} vs {y:?}");
        }
        for (x, y) in mi.to_bezier().pts.iter().zip(&si.pts) {
            prop_assert!(!x.intersection(*y).is_empty());
        }
    }

    #[test]
    fn hermite_round_trip(pts in prop::collection::vec(-100.0f64..100.0, 8), a in -5.0f64..5.0, len in 0.01f64..10.0, t in 0.0f64..=1.0) {
        let s = BezierSeg::<f64>::from_points(a, a + len, 2, pts);
        let h = HermiteCubic::from_bezier(&s).unwrap();
        let back = h.to_bezier().unwrap();
        prop_assert!(close(&back.pts, &s.pts, 1e-12 * 100.0));
        prop_assert!(close(&h.eval_local(&t).unwrap(), &s.eval_local(&t), 1e-11 * 100.0));
        // the Hermite tangents are the derivative of the segment as a curve
        let c = s.to_curve().unwrap();
        let d0: Vec<f64> = c.derivative(s.a, 1).unwrap();
        let d1: Vec<f64> = c.derivative(s.b, 1).unwrap();
        let tol = 1e-12 * 600.0 / len;
        prop_assert!(close(&d0, &h.m0, tol) && close(&d1, &h.m1, tol));
    }

    #[test]
    fn elevation_keeps_the_curve((d, pts, w) in segments(), times in 1usize..4, t in 0.0f64..=1.0) {
        let si: BezierSeg<Interval> = hom(d, &pts, &w);
        let ei = si.elevate_by(times);
        prop_assert_eq!(ei.degree, si.degree + times);
        let ti = iv::point(t);
        for (x, y) in ei.eval_local(&ti).iter().zip(si.eval_local(&ti)) {
            prop_assert!(!x.intersection(y).is_empty(), "{x:?} vs {y:?}");
        }
        // and in f64, as curves (rational segments included)
        let s: BezierSeg<f64> = hom(d, &pts, &w);
        let (c, ce) = (s.to_curve().unwrap(), s.elevate_by(times).to_curve().unwrap());
        let (p, q): (Vec<f64>, Vec<f64>) = (c.point(t).unwrap(), ce.point(t).unwrap());
        // relative rounding of the homogeneous rows, amplified by the weight ratio at worst
        let wr = w.as_ref().map_or(1.0, |w| {
            w.iter().cloned().fold(0.0, f64::max) / w.iter().cloned().fold(f64::INFINITY, f64::min)
        });
        prop_assert!(close(&p, &q, 1e-13 * 100.0 * wr), "{p:?} vs {q:?}");
    }
}
