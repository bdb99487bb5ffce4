//! [`TightEval`]: verified point and small-box evaluation of single coordinates, about one ulp
//! (of the coordinate scale) wide — the precision layer under the verified box strategies.
//!
//! * [`TightEval::coord_at`] runs the generic de Boor kernel ([`HSpline::eval_span`]) on
//!   [`Ddi`] (rigorous double-double) and rounds the resulting ~2^-100-wide enclosure outward to
//!   f64 once: one ulp wide, or a single float when the exact value is one.
//! * [`TightEval::coord_over`] encloses C_j over a (small) parameter box X = [a, b] per polynomial
//!   piece with the mean-value form (Moore 1966; Neumaier, *Interval Methods for Systems of
//!   Equations*, 1990, sec. 2.3)
//!   `C(X) ⊆ C(m) + C'(X)(X - m)`
//!   and the second-order Taylor form `C(m) + C'(m)(X - m) + C''(X)(X - m)^2 / 2`, whose
//!   extremal side is sharpened by completing the square (below). `C(m)` and `C'(m)` come from
//!   `Ddi`, `C'(X)`, `C''(X)` from interval de Boor over X ([`CurveEval::derivs_in_span`]). The
//!   results are intersected with the naive interval enclosure `C(X)`. Near a critical point
//!   `C'(X)` and `C'(m)` are tiny, the correction term is far below an ulp, and the bound is
//!   `C(m)` rounded outward: one ulp.
//!
//! Each coordinate is handled as its own 1-D curve (same knots and weights), so a coordinate
//! costs a 1-D (non-rational) or 2-row (rational) de Boor run, not a d-dimensional one.

use crate::bspline::HSpline;
use crate::curve::NurbsCurve;
use crate::ddi::Ddi;
use crate::eval::CurveEval;
use crate::scalar::{iv, Scalar};
use inari::Interval;
use std::cell::RefCell;

/// Per-coordinate evaluators (coordinate j as a 1-D NURBS curve with the same weights).
#[derive(Debug, Clone)]
struct CoordEval {
    /// C_j and C_j' at points, in `Ddi`.
    ddi: CurveEval<Ddi>,
    /// C_j, C_j', C_j'' over parameter intervals.
    ival: CurveEval<Interval>,
}

/// Verified, ~1-ulp-tight evaluation of the coordinates of one curve (built once per curve).
#[derive(Debug, Clone)]
pub struct TightEval {
    curve: NurbsCurve,
    coords: Vec<CoordEval>,
}

thread_local! {
    /// Scratch space for de Boor on `Ddi` (no allocation on the hot path after the first call).
    static DDI_BUF: RefCell<Vec<Ddi>> = const { RefCell::new(Vec::new()) };
}

impl TightEval {
    /// Precompute, per coordinate, the homogeneous control points in `Ddi` (with the first
    /// derivative) and in intervals (with the first two derivatives).
    pub fn new(curve: &NurbsCurve) -> Self {
        let coords = (0..curve.dim())
            .map(|j| {
                let c1 = curve.coordinate_curve(j);
                CoordEval {
                    ddi: CurveEval::new(&c1, 1),
                    ival: CurveEval::new(&c1, 2),
                }
            })
            .collect();
        TightEval {
            curve: curve.clone(),
            coords,
        }
    }

    /// The curve this evaluator was built for.
    pub fn curve(&self) -> &NurbsCurve {
        &self.curve
    }

    /// `C_j(u)` of piece `span` at the exact f64 parameter `u`, as a `Ddi` (rational: A_j / w).
    fn ddi_at(&self, j: usize, span: usize, u: f64) -> Ddi {
        let h: &HSpline<Ddi> = self.coords[j].ddi.level(0);
        DDI_BUF.with(|b| {
            let mut buf = b.borrow_mut();
            h.eval_span(span, &Ddi::exact(u), &mut buf);
            if h.rational {
                buf[0] / buf[1]
            } else {
                buf[0]
            }
        })
    }

    /// Verified enclosure of `C_j(u)` at the exact f64 parameter `u` (which should lie in the
    /// domain; outside it the end pieces are extended). The span is found exactly; the value is
    /// computed in [`Ddi`] and rounded outward once, so the interval is a single float or one
    /// ulp wide, except after overflow (then it is whatever interval de Boor gives, possibly
    /// ENTIRE — never wrong).
    pub fn coord_at(&self, j: usize, u: f64) -> Interval {
        let span = self.curve.find_span(u);
        let v = self.ddi_at(j, span, u);
        if v.is_entire() {
            // Overflow in double-double: the plain interval evaluation may still be finite.
            return self.coords[j]
                .ival
                .derivs_in_span(span, &iv::point(u), 0)
                .swap_remove(0)
                .swap_remove(0);
        }
        v.to_interval()
    }

    /// All coordinates of C(u) (see [`TightEval::coord_at`]).
    pub fn point(&self, u: f64) -> Vec<Interval> {
        (0..self.curve.dim()).map(|j| self.coord_at(j, u)).collect()
    }

    /// Verified enclosure of `{C_j(u) : u in [a, b]}` (clipped to the domain; EMPTY if [a, b] is
    /// empty or misses the domain). Made for small boxes around critical points (about one ulp
    /// wide then), valid for any box. Boxes straddling knots are split there and the pieces'
    /// enclosures hulled, so discontinuities of C' (or C) are handled.
    pub fn coord_over(&self, j: usize, a: f64, b: f64) -> Interval {
        if a.is_nan() || b.is_nan() || a > b {
            return Interval::EMPTY;
        }
        let mut acc = Interval::EMPTY;
        for (span, lo, hi) in self.curve.spans_straddled(a, b) {
            acc = acc.convex_hull(self.piece_over(j, span, lo, hi));
        }
        acc
    }

    /// Enclosure of piece `span` of C_j over [lo, hi] (inside the closed span).
    fn piece_over(&self, j: usize, span: usize, lo: f64, hi: f64) -> Interval {
        if lo == hi {
            let v = self.ddi_at(j, span, lo);
            if !v.is_entire() {
                return v.to_interval();
            }
        }
        let ce = &self.coords[j];
        // Interval C, C', C'' over X = [lo, hi] (the piece is one rational function there).
        let e = ce.ival.derivs_in_span(span, &iv::span(lo, hi), 2);
        let (c0x, c1x, c2x) = (e[0][0], e[1][0], e[2][0]);
        // Expansion point m in [lo, hi] (clamped in case of rounding), C(m), C'(m) in Ddi.
        let m = (lo + 0.5 * (hi - lo)).clamp(lo, hi);
        let d = ce.ddi.derivs_in_span(span, &Ddi::exact(m), 1);
        let (cm, c1m) = (d[0][0], d[1][0].to_interval());
        if cm.is_entire() {
            return c0x;
        }
        // H = X - m, outward rounded; contains 0.
        let h = iv::span(
            (iv::point(lo) - iv::point(m)).inf(),
            (iv::point(hi) - iv::point(m)).sup(),
        );
        // Mean-value form: C(u) - C(m) = C'(xi)(u - m), xi in X.
        let t1 = c1x * h;
        // Taylor form: C(u) - C(m) = C'(m)(u - m) + C''(xi)(u - m)^2 / 2.
        let t2 = c1m * h + c2x * h.sqr() * iv::point(0.5);
        let mut t = t1.intersection(t2);
        // Completing the square on the extremal side: for fixed h, the Taylor term is at most
        // max(c1 h) + sup(C'') h^2 / 2; if sup(C'') = -k < 0 this is at most g^2 / (2k) with
        // g = max(sup C'(m), -inf C'(m), 0) (maximise over h; h >= 0 and h <= 0 separately).
        // Symmetrically below if inf(C'') > 0. All in inari (outward rounded).
        let g = iv::point(c1m.sup().max(-c1m.inf()).max(0.0));
        if c2x.sup() < 0.0 {
            let bound = (g.sqr() / (iv::point(-c2x.sup()) * iv::point(2.0))).sup();
            t = t.intersection(iv::span(t.inf(), bound.max(t.inf())));
        }
        if c2x.inf() > 0.0 {
            let bound = (g.sqr() / (iv::point(c2x.inf()) * iv::point(2.0))).sup();
            t = t.intersection(iv::span((-bound).min(t.sup()), t.sup()));
        }
        if t.is_empty() {
            // Cannot happen in exact arithmetic (both forms contain the true range, which
            // contains 0 at u = m); fall back to the naive enclosure rather than guess.
            return c0x;
        }
        let r = (cm + Ddi::from_interval(t)).to_interval();
        let out = r.intersection(c0x);
        if out.is_empty() {
            c0x
        } else {
            out
        }
    }
}

impl NurbsCurve {
    /// Coordinate j as a 1-D NURBS curve (same degree, knots and weights).
    pub fn coordinate_curve(&self, j: usize) -> NurbsCurve {
        let pts: Vec<f64> = (0..self.num_points())
            .map(|i| self.control_point(i)[j])
            .collect();
        NurbsCurve::from_flat(
            self.degree(),
            1,
            self.knots().to_vec(),
            pts,
            self.weights().map(|w| w.to_vec()),
        )
        .expect("a coordinate of a valid curve is a valid 1-D curve")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Width of an interval in ulps of `scale` (ulp(scale) = spacing of floats at scale).
    fn ulps(x: Interval, scale: f64) -> f64 {
        let ulp = f64::from_bits(scale.to_bits() + 1) - scale;
        (x.sup() - x.inf()) / ulp
    }

    #[test]
    fn circle_is_unit_within_rounded_weight() {
        let c = crate::eval::tests::circle();
        let t = TightEval::new(&c);
        for i in 0..=1000 {
            let u = i as f64 / 1000.0;
            let p = t.point(u);
            for x in &p {
                assert!(ulps(*x, 1.0) <= 1.0, "u={u}: {x:?}");
            }
            let r2 = p[0] * p[0] + p[1] * p[1];
            // The weight sqrt(2)/2 is rounded: |C|^2 = 1 only up to ~1e-16.
            assert!(
                r2.inf() <= 1.0 + 1e-16 && r2.sup() >= 1.0 - 1e-16,
                "u={u}: {r2:?}"
            );
            let naive: Vec<Interval> = c.point(u).unwrap();
            for (x, y) in p.iter().zip(&naive) {
                assert!(!x.intersection(*y).is_empty());
            }
        }
        // Exact values stay exact: the knots of multiplicity p give control points.
        for (u, x, y) in [
            (0.0, 1.0, 0.0),
            (0.25, 0.0, 1.0),
            (0.5, -1.0, 0.0),
            (1.0, 1.0, 0.0),
        ] {
            assert_eq!(t.point(u), vec![iv::point(x), iv::point(y)], "u={u}");
        }
    }

    #[test]
    fn dyadic_cubic_bezier_is_exact() {
        // Small integer control points and t = k/64: every Bernstein term is exact in f64, so
        // the exact value is a float and the enclosure must be that single float.
        let pts = [3.0, -7.0, 11.0, 2.0];
        let c = NurbsCurve::new(
            3,
            vec![0., 0., 0., 0., 1., 1., 1., 1.],
            pts.iter().map(|&x| vec![x]).collect(),
            None,
        )
        .unwrap();
        let t = TightEval::new(&c);
        for k in 0..=64 {
            let u = k as f64 / 64.0;
            // Bernstein form sum_i binom(3, i) (1-u)^(3-i) u^i P_i, exact for these data.
            let b: f64 = (0..4)
                .map(|i| {
                    [1.0, 3.0, 3.0, 1.0][i]
                        * (1.0 - u).powi(3 - i as i32)
                        * u.powi(i as i32)
                        * pts[i]
                })
                .sum();
            let v = t.coord_at(0, u);
            assert!(v.contains(b), "u={u}: {b} not in {v:?}");
            assert!(ulps(v, 11.0) <= 1.0, "u={u}: {v:?}");
        }
    }

    /// A random curve: degree 1..=10, clamped or not, rational or not, knots with repeats.
    pub(crate) fn random_curve(rng: &mut ChaCha8Rng, dim: usize) -> NurbsCurve {
        let p = rng.random_range(1..=10usize);
        let n = p + 1 + rng.random_range(0..6usize);
        let clamped = rng.random_bool(0.5);
        let mut knots: Vec<f64> = Vec::new();
        while knots.len() < n + p + 1 {
            let x: f64 = rng.random_range(0.0..1.0);
            let reps = if rng.random_bool(0.2) { 2 } else { 1 };
            for _ in 0..reps {
                knots.push(x);
            }
        }
        knots.truncate(n + p + 1);
        knots.sort_by(f64::total_cmp);
        if clamped {
            for i in 0..=p {
                knots[i] = 0.0;
                let m = knots.len();
                knots[m - 1 - i] = 1.0;
            }
        }
        let pts: Vec<Vec<f64>> = (0..n)
            .map(|_| (0..dim).map(|_| rng.random_range(-10.0..10.0)).collect())
            .collect();
        let w = if rng.random_bool(0.5) {
            Some(
                (0..n)
                    .map(|_| 10f64.powf(rng.random_range(-2.0..2.0)))
                    .collect(),
            )
        } else {
            None
        };
        NurbsCurve::new(p, knots, pts, w).unwrap_or_else(|_| random_curve(rng, dim))
    }

    #[test]
    fn coord_at_encloses_naive_samples_and_is_tight() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        for _ in 0..200 {
            let c = random_curve(&mut rng, 2);
            let t = TightEval::new(&c);
            let (a, b) = c.domain();
            for i in 0..=20 {
                let u = (a + (b - a) * i as f64 / 20.0).min(b);
                let naive: Vec<Interval> = c.point(u).unwrap();
                for (j, nj) in naive.iter().enumerate() {
                    let v = t.coord_at(j, u);
                    assert!(!v.intersection(*nj).is_empty(), "{c:?} u={u}");
                    assert!(ulps(v, c.coord_scale(j)) <= 2.0, "{v:?} vs scale");
                }
            }
        }
    }

    #[test]
    fn coord_over_near_a_maximum_is_one_ulp() {
        // y(t) of a cubic Bézier with a maximum inside; locate it by f64 Newton, then a small
        // box around it must be enclosed within ~1 ulp and contain every sampled point value.
        let c = NurbsCurve::new(
            3,
            vec![0., 0., 0., 0., 1., 1., 1., 1.],
            vec![
                vec![0.0, 0.0],
                vec![1.0, 2.0],
                vec![2.0, 1.7],
                vec![3.0, -0.5],
            ],
            None,
        )
        .unwrap();
        let t = TightEval::new(&c);
        let f = CurveEval::<f64>::new(&c, 2);
        let mut u = 0.5;
        for _ in 0..50 {
            let d = f.derivs(u, 2).unwrap();
            u -= d[1][1] / d[2][1];
        }
        for w in [0.0, 1e-15, 1e-12, 1e-9, 1e-6, 1e-4] {
            let (a, b) = (u - w, u + w);
            let box_ = t.coord_over(1, a, b);
            assert!(
                ulps(box_, c.coord_scale(1)) <= 2.0 || w >= 1e-6,
                "w={w}: {box_:?}"
            );
            // the upper end is the maximum: within one ulp of the point value at u
            let at = t.coord_at(1, u);
            assert!(
                box_.sup() <= f64::from_bits(at.sup().to_bits() + 1),
                "w={w}"
            );
            for i in 0..=100 {
                let s = a + (b - a) * i as f64 / 100.0;
                // coord_at(s) = [RD, RU] of the exact C(s): inside the box iff the box holds C(s)
                assert!(t.coord_at(1, s.clamp(a, b)).subset(box_), "w={w} s={s}");
            }
        }
    }

    #[test]
    fn coord_over_is_sound_on_random_boxes() {
        let mut rng = ChaCha8Rng::seed_from_u64(2);
        for _ in 0..100 {
            let c = random_curve(&mut rng, 1);
            let t = TightEval::new(&c);
            let (a, b) = c.domain();
            for _ in 0..10 {
                let x: f64 = rng.random_range(a..b);
                let w = (b - a) * 10f64.powf(rng.random_range(-16.0..0.0));
                let (lo, hi) = (x, (x + w).min(b));
                let e = t.coord_over(0, lo, hi);
                let naive = c.enclose_point(iv::span(lo, hi)).unwrap()[0];
                assert!(e.subset(naive), "{e:?} not in naive {naive:?}");
                for i in 0..=50 {
                    let s = (lo + (hi - lo) * i as f64 / 50.0).min(hi);
                    // The exact C(s) lies in coord_at(s); it must lie in e too.
                    assert!(!t.coord_at(0, s).intersection(e).is_empty(), "s={s}");
                    #[cfg(feature = "mpfr")]
                    {
                        let x: Vec<rug::Float> = c.point(s).unwrap();
                        assert!(
                            e.inf() <= x[0] && x[0] <= e.sup(),
                            "s={s}: {e:?} misses {}",
                            x[0]
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn huge_coordinates_and_extreme_weights_stay_sound() {
        let c = NurbsCurve::new(
            3,
            vec![0., 0., 0., 0., 0.5, 1., 1., 1., 1.],
            vec![
                vec![1e300, -1e-300],
                vec![-1.5e300, 3e-300],
                vec![1.7e308, 0.0],
                vec![-1e300, 1e-300],
                vec![1e299, 2e-300],
            ],
            Some(vec![1e-6, 1e6, 1.0, 1e6, 1e-6]),
        )
        .unwrap();
        let t = TightEval::new(&c);
        for i in 0..=64 {
            let u = i as f64 / 64.0;
            let p = t.point(u);
            let naive: Vec<Interval> = c.point(u).unwrap();
            for j in 0..2 {
                assert!(!p[j].is_empty());
                assert!(!p[j].intersection(naive[j]).is_empty() || naive[j].is_empty());
            }
            let o = t.coord_over(0, u, (u + 1e-3).min(1.0));
            assert!(p[0].subset(o) || !p[0].intersection(o).is_empty());
        }
    }

    /// Against 256-bit MPFR on random curves: containment always, width <= 2 ulps of the
    /// coordinate scale; prints the width distribution (run with --nocapture).
    #[cfg(feature = "mpfr")]
    #[test]
    fn coord_at_contains_mpfr_and_width_stats() {
        let mut rng = ChaCha8Rng::seed_from_u64(9);
        let mut widths: Vec<f64> = Vec::new();
        for _ in 0..300 {
            let c = random_curve(&mut rng, 2);
            let t = TightEval::new(&c);
            let (a, b) = c.domain();
            for _ in 0..20 {
                let u = rng.random_range(a..=b);
                let exact: Vec<rug::Float> = c.point(u).unwrap();
                for (j, x) in exact.iter().enumerate() {
                    let v = t.coord_at(j, u);
                    assert!(
                        v.inf() <= *x && *x <= v.sup(),
                        "{c:?} u={u} j={j}: {v:?} misses {x}"
                    );
                    let w = ulps(v, c.coord_scale(j));
                    assert!(w <= 2.0, "width {w} ulps at u={u}");
                    widths.push(w);
                }
            }
        }
        widths.sort_by(f64::total_cmp);
        println!(
            "coord_at width in ulps of coord scale: median {:.3}, p90 {:.3}, max {:.3} (n = {})",
            widths[widths.len() / 2],
            widths[widths.len() * 9 / 10],
            widths[widths.len() - 1],
            widths.len()
        );
    }
}
