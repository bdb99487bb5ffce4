//! The per-span Bernstein back-end ([`super::Newton::bernstein`],
//! [`super::Newton::bezier_pretest`]; not in the thesis): the Bézier points of the shifted piece C_j - c of one knot span, the
//! Bernstein coefficients of the derivative numerator F and of F', evaluated over boxes of
//! the span's local parameter t ([`T`]) by de Casteljau, and the one map from t back to the
//! curve parameter u ([`SpanPoly::to_u`]).

use super::param::{midpoint, T, U};
use crate::num::ddi::{dist_up, eta_multiple, up, Ddi, ETA16, U1};
use crate::num::mr::Mr;
use crate::num::{iv, pool, Scalar};
use crate::spline::bezier::{bernstein_value_s, de_casteljau_levels};
use crate::spline::bspline::BezierSeg;
use crate::spline::curve::NurbsCurve;
use inari::Interval;
use smallvec::SmallVec;

/// The Bernstein form of coordinate j on one knot span k = [a, b] = [u_k, u_{k+1}], in [`Mr`]
/// ([`Newton::bernstein`]; not in the thesis). With t = (u - a) / (b - a):
/// * `seg`: the homogeneous Bézier points ((x_i - c) w_i, w_i) (rational) or x_i - c of the
///   shifted piece C_j - c, by Boehm knot insertion on the p + 1 local control points (NURBS
///   Book A5.1 via [`HSpline::bezier_segment`]; thesis eq. 4.12). c is a local control point
///   value (the most frequent one): the points of a flat run become exact zeros, so nearly flat
///   coordinates keep their relative accuracy (the shift changes neither C_j' nor its zeros);
/// * `f`: F(t) = A_t W - A W_t (rational; A, W the shifted numerator and the weight in t), or
///   A_t / p (polynomial), in Bernstein form of degree n = 2p - 2 (p - 1). The rational
///   coefficients: with B_i' B_l - B_i B_l' = (i - l) B_i B_l / (t (1 - t)) for degree-p
///   Bernstein polynomials and B_i^p B_l^p / (t (1 - t)) = C(p,i) C(p,l) / C(2p-2,i+l-1)
///   B_{i+l-1}^{2p-2},
///   F = sum_{i<l} (l - i) C(p,i) C(p,l) / C(2p-2,i+l-1) (a_l w_i - a_i w_l) B_{i+l-1}^{2p-2}
///   (Farin, "Curves and Surfaces for CAGD", sec. 13 on rational Bézier derivatives; the same
///   sum as in `Engine::monotone`). C_j' = F / (W^2 (b - a)) (or p F / (b - a)): F has the
///   sign and the zeros of C_j' on the closed span;
/// * `df`: F' = n sum (F_{i+1} - F_i) B_i^{n-1} (the hodograph).
///
/// Ranges over a box come from the hull of the coefficients restricted to it by de Casteljau
/// (convex hull property: Bernstein polynomials are >= 0 and sum to 1; for the rational values
/// the positive weights make the point a convex combination of the Cartesian Bézier points).
/// Every Mr operation encloses its exact result, so every coefficient encloses the exact one.
pub(crate) struct SpanPoly {
    /// span index k
    pub(super) k: usize,
    /// the shift c (a control point coordinate, exact)
    c: f64,
    /// homogeneous Bézier segment of C_j - c over [a, b]
    seg: BezierSeg<Mr>,
    /// F, degree n
    f: BezierSeg<Mr>,
    /// F', degree n - 1 (one zero coefficient for n = 0)
    df: BezierSeg<Mr>,
    /// an enclosure of F'' over the span (hull of its Bernstein coefficients)
    d2: Interval,
    /// the segment of `seg` in double-double: the shifted rows of the span's shared `Ddi`
    /// points ([`shifted_from_points`]), of which `seg` is the `Mr` rounding
    dseg: BezierSeg<Ddi>,
    /// bounds over the closed span (convex hull property, from the coefficient enclosures):
    /// |F| <= `fmax`, |F'| <= `dfmax`, and (rational) W >= `wmin` (not positive, or NaN: no
    /// bound; 1 for a polynomial piece). Infinite where a coefficient is unbounded.
    fmax: f64,
    dfmax: f64,
    wmin: f64,
}

/// The form's vectors go back to this thread's pool (`num::pool`) for the next span's form:
/// a batch allocates them once per thread instead of once per span and coordinate.
impl Drop for SpanPoly {
    fn drop(&mut self) {
        pool::give(std::mem::take(&mut self.seg.pts));
        pool::give(std::mem::take(&mut self.f.pts));
        pool::give(std::mem::take(&mut self.df.pts));
        pool::give(std::mem::take(&mut self.dseg.pts));
    }
}

/// Push the parts of the closed interval [lo, hi] that the closed intervals `free`
/// (increasing; F proven zero-free there: [`Numerator::zero_estimates`]) do not cover, each as a
/// closed interval with depth 0, to `gaps`: the parts still to be excluded. (A part's ends may
/// lie in `free`, which only makes it larger than needed.)
fn push_unproven(gaps: &mut Vec<(f64, f64, u32)>, lo: f64, hi: f64, free: &[(f64, f64)]) {
    let mut left = lo;
    for &(f0, f1) in free {
        if f1 < left {
            continue;
        }
        if f0 >= hi {
            break;
        }
        if f0 > left {
            gaps.push((left, f0, 0));
        }
        left = left.max(f1);
        if left >= hi {
            return;
        }
    }
    if left < hi {
        gaps.push((left, hi, 0));
    }
}

impl SpanPoly {
    /// The form of coordinate j of `c` on span k; `pair` from [`pair_coefficients`] (rational;
    /// empty: F is left unknown, ENTIRE). `pts`: the span's double-double Bézier points, every
    /// row (`TightEval::bezier_points`), shared by the coordinates and the candidates'
    /// evaluations ([`shifted_from_points`]; before, each coordinate ran its own knot
    /// insertion of its shifted rows in `Mr`).
    pub(crate) fn new(c: &NurbsCurve, j: usize, k: usize, pair: &[Mr], pts: &[Ddi]) -> Self {
        let h = c.dim() + c.is_rational() as usize;
        Self::from_rows(c, j, k, pair, |i| (pts[i * h + j], pts[i * h + h - 1]))
    }

    /// The form of coordinate j of a non-rational `c` on span k from that coordinate's
    /// double-double Bézier points alone, `q` (p + 1 enclosures of the exact ones; the driver's
    /// lane computes them per span, without the curve-wide [`TightEval`] sweep).
    ///
    /// [`TightEval`]: crate::spline::tight::TightEval
    pub(crate) fn from_coefficients(c: &NurbsCurve, j: usize, k: usize, q: &[Ddi]) -> Self {
        debug_assert!(!c.is_rational() && q.len() == c.degree() + 1);
        Self::from_rows(c, j, k, &[], |i| (q[i], Ddi::exact(1.0)))
    }

    /// The form of coordinate j of a rational `c` on span k from that coordinate's
    /// double-double homogeneous Bézier points alone: `x` (the row w x_j) and `w` (the
    /// weights' row), p + 1 enclosures of the exact ones each (the driver's lane computes them
    /// per span, without the curve-wide sweep), with the degree's `pair` coefficients
    /// ([`pair_coefficients`]).
    pub(crate) fn from_homogeneous(
        c: &NurbsCurve,
        j: usize,
        k: usize,
        pair: &[Mr],
        x: &[Ddi],
        w: &[Ddi],
    ) -> Self {
        debug_assert!(c.is_rational() && x.len() == c.degree() + 1 && w.len() == x.len());
        Self::from_rows(c, j, k, pair, |i| (x[i], w[i]))
    }

    /// [`SpanPoly::new`] with point i's coordinate j and weight given by `row(i)` (the weight
    /// is read for a rational curve only).
    fn from_rows(
        c: &NurbsCurve,
        j: usize,
        k: usize,
        pair: &[Mr],
        row: impl Fn(usize) -> (Ddi, Ddi),
    ) -> Self {
        let p = c.degree();
        let rational = c.is_rational();
        let shift = span_shift(&mut (k - p..=k).map(|i| c.control_point(i)[j]).collect::<SmallVec<[f64; 32]>>());
        let dseg = shifted_from_points(c, k, shift, row);
        let seg = BezierSeg {
            a: dseg.a,
            b: dseg.b,
            degree: p,
            dim: 1,
            rational,
            pts: {
                let mut v = pool::take(dseg.pts.len());
                v.extend(dseg.pts.iter().map(|&x| Mr::from_ddi(x)));
                v
            },
        };
        let q = &seg.pts;
        let mut fco: Vec<Mr> = pool::take(2 * p);
        if rational && pair.is_empty() {
            // degree above BERNSTEIN_MAX_DEGREE: F unknown
            fco.push(Mr::ENTIRE);
        } else if rational {
            pair_sum_f64(q, pair, p, &mut fco);
        } else {
            fco.extend(q.windows(2).map(|w| w[1] - w[0]));
        }
        Self::with_f(k, shift, seg, dseg, fco, rational && pair.is_empty())
    }

    /// The form with F's coefficients recomputed from the span's double-double points
    /// (`dseg`) in [`Ddi`] and rounded to `Mr` ([`f_from_ddi`]), where the `Mr` sums of
    /// [`SpanPoly::new`] left them wide: radii above 2^-44 of their own coefficients, from
    /// products of extreme weights that cancel (terms ~1e6 for an F ~1e-6), or from Cartesian
    /// differences of nearly equal points. About 2^-100 of the terms instead of 2^-53, so that
    /// the signs of F show close to its zeros again. `None` where nothing is to be gained (every
    /// radius already small against its own coefficient, F unknown, degree above
    /// [`F_DDI_MAX_DEGREE`]).
    pub(crate) fn refined(&self) -> Option<SpanPoly> {
        // (nothing to gain where every radius is already below 2^-44 of its own coefficient;
        // a radius small against the largest coefficient may still swamp the small ones next
        // to a zero of F, 1e5 .. 1e9 times smaller at the other end of the span)
        let small = |x: &Mr| x.rad() <= x.mid().abs() * (1.0 / 17_592_186_044_416.0);
        if self.f.pts.iter().all(small) || !self.f.pts.iter().all(|x| x.rad().is_finite()) {
            return None;
        }
        let fco = f_from_ddi(&self.dseg)?;
        Some(Self::with_f(self.k, self.c, self.seg.clone(), self.dseg.clone(), fco, false))
    }

    /// The form from its parts: the span index, the shift, the `Mr` and double-double
    /// segments and F's coefficients (F', F'''s hull and the bounds follow from them;
    /// `unknown`: F is not known, its one coefficient ENTIRE, and neither is F').
    fn with_f(
        k: usize,
        shift: f64,
        seg: BezierSeg<Mr>,
        dseg: BezierSeg<Ddi>,
        fco: Vec<Mr>,
        unknown: bool,
    ) -> Self {
        let rational = seg.rational;
        let n = fco.len() - 1;
        let mut dco: Vec<Mr> = pool::take(n.max(1));
        if unknown {
            dco.push(Mr::ENTIRE);
        } else if n == 0 {
            dco.push(Mr::from_f64(0.0));
        } else {
            let nm = Mr::from_usize(n);
            dco.extend(fco.windows(2).map(|w| nm * (w[1] - w[0])));
        }
        let poly = |pts: Vec<Mr>| BezierSeg {
            a: seg.a,
            b: seg.b,
            degree: pts.len() - 1,
            dim: 1,
            rational: false,
            pts,
        };
        let d2 = second_hull(&dco);
        let (fmax, dfmax) = (mag_bound(fco.iter().copied()), mag_bound(dco.iter().copied()));
        let wmin = if rational { weight_floor(&seg.pts) } else { 1.0 };
        SpanPoly {
            k,
            c: shift,
            f: poly(fco),
            df: poly(dco),
            d2,
            seg,
            dseg,
            fmax,
            dfmax,
            wmin,
        }
    }

    /// The Bézier points of `s` over [t0, t1] inside [0, 1]: de Casteljau at t1 (left part,
    /// over [0, t1]), then at an enclosure of t0 / t1 (right part of that). For every exact
    /// parameter in the enclosure the split encloses the exact sub-segment
    /// ([`BezierSeg::sub_points`]), so the result encloses the points over [t0, t1].
    fn restrict<S: Scalar>(s: &BezierSeg<S>, t0: f64, t1: f64) -> Vec<S> {
        let t1s = (t1 < 1.0).then(|| S::from_f64(t1));
        let t0s = (t0 > 0.0).then(|| S::from_f64(t0) / S::from_f64(t1));
        s.sub_points(t1s.as_ref(), t0s.as_ref())
    }

    /// F over the box t = [t0, t1] (at t0 for a point): [`Numerator::over`].
    pub(super) fn f(&self, t: T) -> Interval {
        self.numerator().over(t)
    }

    /// F alone, for the steps that read nothing else ([`Numerator`]).
    pub(crate) fn numerator(&self) -> Numerator<'_> {
        Numerator { f: &self.f }
    }

    /// F at the f64 point t in plain f64 with an a-priori error bound ([`value_f64`]):
    /// (enclosure, bound E), or `None` (degree above [`F64_RESTRICT_MAX`]). Wider than the `Mr`
    /// value of [`SpanPoly::f`] (E ~ 2^-49 n max |F_i| or less instead of the coefficients' own
    /// errors); the Newton search uses it where that width does not matter
    /// (`Engine::f_newton`).
    pub(super) fn f_value_f64(&self, t: f64) -> Option<(Interval, f64)> {
        value_f64(&self.f.pts, t)
    }

    /// F' at the point t: in f64 with the a-priori bound where that excludes 0 with the bound
    /// far below |F'(t)| (as for the restriction in [`SpanPoly::df`]), else in `Mr`.
    fn df_at(&self, t: f64) -> Interval {
        match value_f64(&self.df.pts, t) {
            Some((v, e)) if !v.contains(0.0) && e <= v.mig() * (1.0 / 1_073_741_824.0) => v,
            _ => bernstein_value_s(&self.df.pts, t).to_interval(),
        }
    }

    /// F' over the box t = [t0, t1] (at t0 for a point). A small box (width at most 2^-20: the
    /// Newton boxes around the zero estimates, converged or not; F'(m) is the O(n) value with
    /// its a-priori bound, about as wide as the restriction's hull) first tries the mean value
    /// form F'(m) + F''([0, 1])
    /// ([t0, t1] - m), m the midpoint: F'(t) = F'(m) + F''(ξ)(t - m) with ξ between t and m,
    /// F''(ξ) in the hull of F'''s hodograph coefficients (`d2`, convex hull property), all in
    /// outward-rounded interval arithmetic; one evaluation instead of the two splits of the
    /// restriction. It is used when it excludes 0 (else the restriction's hull,
    /// which is sharper where F'' varies much).
    pub(super) fn df(&self, t: T) -> Interval {
        let (t0, t1) = (t.lo, t.hi);
        if t0 == t1 {
            return self.df_at(t0);
        }
        let w = t1 - t0;
        if w <= 1.0 / 1_048_576.0 && !self.d2.is_entire() {
            let m = midpoint(t0, t1);
            let dm = self.df_at(m);
            let mv = dm + self.d2 * (iv::span(t0, t1) - iv::point(m));
            if !mv.is_empty() && !mv.contains(0.0) {
                return mv;
            }
        }
        // (as in `f`; and only where its error bound is far below |F'| over the box, so that
        // the Newton step's contraction is that of the exact range)
        match restrict_hull_f64(&self.df.pts, t0, t1) {
            Some((v, e, _)) if !v.contains(0.0) && e <= v.mig() * (1.0 / 1_073_741_824.0) => v,
            _ => hull(&Self::restrict(&self.df, t0, t1)),
        }
    }

    /// The values of the piece C_j over the box t = [t0, t1]: hull of the Cartesian Bézier
    /// points of the restricted segment, shifted back by c. The rows of the homogeneous segment
    /// are restricted in f64 with the a-priori bound of [`restrict_hull_f64`] where that applies
    /// (each restricted homogeneous coefficient within E_row of the exact one; the Cartesian
    /// points are the outward-rounded quotients of those enclosures, their hull contains the
    /// piece's values by the convex hull property with positive weights), else in `Mr`.
    pub(super) fn values(&self, t: T) -> Interval {
        if let Some(v) = self.values_small(t) {
            return v;
        }
        if t.lo < t.hi {
            if let Some(v) = segment_values_f64(&self.seg, t.lo, t.hi) {
                return iv::add(v, iv::point(self.c));
            }
        }
        let q = Self::restrict(&self.seg, t.lo, t.hi);
        iv::add(hull(&cartesian(q, self.seg.rational)), iv::point(self.c))
    }

    /// [`SpanPoly::values`] over a small box (width at most 2^-20 of the span: the converged
    /// boxes of the Newton search) in O(p) instead of the restriction's O(p^2): the piece at the
    /// midpoint t_m (each row by [`vs_row`], with its a-priori bound; the quotient of the
    /// enclosures for a rational piece, whose weight enclosure must be positive) widened by
    /// r L, where r >= |t - t_m| for t in the box ([`dist_up`]) and L bounds |dC_j/dt| on the
    /// closed span: dC_j/dt = F / W^2 (rational) or p F (polynomial; see [`SpanPoly`]), with
    /// |F| <= `fmax` and W >= `wmin` > 0 there (convex hull property). By the mean value
    /// theorem every value of the piece over the box lies within r L of C_j(t_m). All rounded
    /// outward (sums by [`iv::add`], quotients by [`iv::div_positive`], the magnitudes by the
    /// upper bounds [`iv::mul_up`] and [`iv::div_up`]). `None` where that does not apply (wider boxes,
    /// degree above [`VS_MAX`], no positive weight bound, something not finite).
    fn values_small(&self, t: T) -> Option<Interval> {
        let (t0, t1) = (t.lo, t.hi);
        if !(t0 < t1 && t1 - t0 <= 1.0 / 1_048_576.0) {
            return None;
        }
        let tm = midpoint(t0, t1);
        let r = dist_up(tm, t0).max(dist_up(t1, tm));
        let (v, l) = if self.seg.rational {
            if self.wmin.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
                return None;
            }
            let (a, _) = vs_row(&self.seg.pts, 2, 0, tm)?;
            let (w, _) = vs_row(&self.seg.pts, 2, 1, tm)?;
            if w.inf().partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
                return None;
            }
            let wm = self.wmin;
            (iv::div_positive(a, w), iv::div_up(iv::div_up(self.fmax, wm), wm))
        } else {
            let (a, _) = vs_row(&self.seg.pts, 1, 0, tm)?;
            (a, iv::mul_up(self.fmax, self.seg.degree as f64))
        };
        // (upper bounds by round to nearest stepped up, and sums rounded as inari's, without
        // its switches of the rounding mode)
        let rl = iv::mul_up(r, l);
        let out = iv::add(iv::add(v, iv::span(-rl, rl)), iv::point(self.c));
        (rl.is_finite() && out.is_common_interval()).then_some(out)
    }

    /// As [`SpanPoly::values`], and C_j at the parameter u(t_mid) (a real in the closed span:
    /// a value of the piece there), in double-double intervals ([`Ddi`]): for the candidate
    /// boxes, where the few hundred ulps of the Mr points would show in the bounds.
    pub(super) fn values_tight(&self, t: T) -> (Interval, Interval) {
        let (t0, t1) = (t.lo, t.hi);
        let seg = &self.dseg;
        let r = self.seg.rational;
        let over = hull(&cartesian(Self::restrict(seg, t0, t1), r));
        let at = hull(&cartesian(
            seg.eval_local(&Ddi::from_f64(midpoint(t0, t1))),
            r,
        ));
        let sh = iv::point(self.c);
        (over + sh, at + sh)
    }

    /// The piece C_j over the box t = [t0, t1] of the local parameter (t0 < t1), about one ulp
    /// wide near a critical point, from the span's double-double points alone (no Taylor
    /// expansion of the span, which costs O(p^2) double-double operations per row): `(enc, v,
    /// v0)` with
    ///
    /// * v: the piece at the midpoint t_m of the box (an f64 strictly inside it, so u(t_m) is
    ///   a parameter inside the span: a value the curve attains; for a box without a double
    ///   strictly inside, its lower end t0, which lies in [0, 1) since t0 < t1 <= 1: u(t0) is
    ///   in [u_k, u_{k+1}), where the curve is the piece, right-continuous at u_k), in `Ddi`: c + A(t_m) / W(t_m)
    ///   (rational) or c + A(t_m) from the shifted rows by the VS algorithm
    ///   ([`bernstein_value_s`], every step an enclosure);
    /// * enc ⊇ C_j(t) for every t in [t0, t1]: by the mean value theorem
    ///   C_j(t) = C_j(t_m) + C_j'(ξ)(t - t_m) with ξ in the box and |t - t_m| <= r (r an upper
    ///   bound of both distances, [`dist_up`]), and dC_j/dt = F / W^2 (rational; F the
    ///   derivative numerator of the form) or p F (polynomial): |C_j'(ξ)| <= |F([t0, t1])| /
    ///   wmin^2 (or p |F|), with F([t0, t1]) from [`restrict_hull_f64`] and wmin > 0 a lower
    ///   bound of the weights on the span (their Bézier points' lower ends: convex hull
    ///   property), or where that is not far below an ulp of v the larger of wmin and
    ///   W(t_m) - r max |W'| (mean value theorem on W over the box, |W'| <= [`weight_slope`]),
    ///   a lower bound of W over the box alone. So enc = v + [-e, e] with e an upper bound of
    ///   r |F| / wb^2 (wb that lower bound; or r p |F|)
    ///   (outward interval arithmetic; the widening in `Ddi`, then one outward rounding). Near
    ///   a zero of F, |F| over a box of width w is about |F'| w, so e ~ |F'| w^2: far below an
    ///   ulp for the converged boxes;
    /// * v0: the piece at t = 0 (the first Bézier point, exact where `TightEval` snapped it):
    ///   the curve's value at the span's start u_k (right-continuous).
    ///
    /// `None` where a weight bound is not positive or something overflowed.
    pub(super) fn tight_over(&self, t: T) -> Option<(Interval, Ddi, Ddi)> {
        let (enc, v) = self.box_form().tight_over(t, || weight_slope(&self.seg.pts))?;
        // (v0: the first Bézier point, the piece at t = 0)
        let shift = Ddi::exact(self.c);
        let pts = &self.dseg.pts;
        let v0 = if self.dseg.rational { pts[0] / pts[1] } else { pts[0] } + shift;
        Some((enc, v, v0))
    }

    /// What [`SpanPoly::tight_over`] reads of the form.
    fn box_form(&self) -> BoxForm<'_> {
        BoxForm {
            dseg: &self.dseg,
            shift: self.c,
            f: &self.f,
            dfmax: self.dfmax,
            wmin: self.wmin,
        }
    }

    /// The box of the curve parameter u that contains u(t) for every t in the box t = [t0, t1]
    /// of this span [a, b] = [u_k, u_{k+1}], rounded outward and clamped to the closed span
    /// ([`super::param::local_to_u`]).
    pub(super) fn to_u(&self, t: T) -> U {
        let (lo, hi) = super::param::local_to_u(self.seg.a, self.seg.b, t.lo, t.hi);
        U::new(lo, hi)
    }

    /// [`Numerator::swamped`].
    pub(crate) fn f_swamped(&self) -> bool {
        self.numerator().swamped()
    }

    /// [`Numerator::zero_estimates`].
    #[cfg(test)]
    pub(super) fn zero_estimates(&self, out: &mut Vec<Estimate>, max: usize, h: f64, free: &mut Vec<(f64, f64)>) -> bool {
        self.numerator().zero_estimates(out, max, h, free)
    }

    /// [`Numerator::zero_boxes`].
    pub(super) fn zero_boxes(
        &self,
        h: f64,
        max: usize,
        scratch: (&mut Vec<Estimate>, &mut Vec<(f64, f64)>),
        boxes: &mut Vec<(f64, f64)>,
        gaps: &mut Vec<(f64, f64, u32)>,
    ) -> bool {
        self.numerator().zero_boxes(h, max, scratch, boxes, gaps)
    }

    /// [`Numerator::critical_boxes`].
    pub(crate) fn critical_boxes(&self, h: f64) -> Option<Vec<(f64, f64)>> {
        self.numerator().critical_boxes(h)
    }

    /// [`Numerator::exclude_gaps`].
    pub(crate) fn exclude_gaps(&self, gaps: &mut Vec<(f64, f64, u32)>, evals: &mut u64) -> bool {
        self.numerator().exclude_gaps(gaps, evals)
    }

    /// The values of the piece over the box [x0, x1] of the local parameter (x0 < x1), cheap
    /// ([`SpanPoly::values`]).
    pub(crate) fn box_values(&self, x0: f64, x1: f64) -> Interval {
        self.values(T::new(x0, x1))
    }

    /// The values of the piece over the box [x0, x1] of the local parameter, about one ulp
    /// wide near a critical point, and the value at a parameter inside the box, in `Ddi`
    /// ([`SpanPoly::tight_over`]).
    pub(crate) fn box_tight(&self, x0: f64, x1: f64) -> Option<(Interval, Ddi)> {
        self.box_form().tight_over(T::new(x0, x1), || weight_slope(&self.seg.pts))
    }

    /// Whether F >= 0 / F <= 0 on the whole span (all coefficients of one sign), i.e. C_j
    /// non-decreasing / non-increasing on the closed span.
    pub(super) fn f_signs(&self) -> (bool, bool) {
        // (the ends of the coefficients' enclosures, `Mr::bounds`: the hull's, without an
        // inari call per coefficient)
        let (lo, hi) = self.f.pts.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
            let (l, h) = x.bounds();
            (lo.min(l), hi.max(h))
        });
        (lo >= 0.0, hi <= 0.0)
    }
}

/// The derivative numerator F of one span and coordinate alone (its Bernstein coefficients,
/// enclosed in [`Mr`]; see [`SpanPoly`]): the root isolation of the float-first proof reads
/// nothing else, so it runs on the F of a [`SpanPoly`] or on one computed without the rest of
/// the form (the lean proof of `bezier::Critical`).
#[derive(Clone, Copy)]
pub(crate) struct Numerator<'a> {
    f: &'a BezierSeg<Mr>,
}

impl Numerator<'_> {
    /// F over the box t = [t0, t1] (at t0 for a point): de Casteljau value, or the
    /// coefficient hull (restricted in f64 with an a-priori bound, [`restrict_hull_f64`], else
    /// in `Mr`).
    pub(super) fn over(&self, t: T) -> Interval {
        let (t0, t1) = (t.lo, t.hi);
        if t0 == t1 {
            // (O(n) instead of de Casteljau's O(n^2): F has degree 2p - 2)
            return bernstein_value_s(&self.f.pts, t0).to_interval();
        }
        // (the f64 restriction's error bound is relative to the largest coefficient: where it
        // cannot exclude 0, e.g. coefficients of very different magnitudes from extreme
        // weights, the `Mr` restriction, which tracks each coefficient's own error, decides)
        // (and where the f64 coefficients straddle 0 by more than their bound, the `Mr` ones
        // would too: the f64 hull is then as good an answer, since only whether 0 can be
        // excluded matters for a box)
        match restrict_hull_f64(&self.f.pts, t0, t1) {
            Some((v, _, straddles)) if !v.contains(0.0) || straddles => v,
            _ => hull(&SpanPoly::restrict(self.f, t0, t1)),
        }
    }

    /// Whether every coefficient enclosure of F contains 0 or lies within four of its radii of
    /// it (and F is not exactly 0): the rounding of the Bernstein form swamps F, so no box of the
    /// span can be excluded with it
    /// (e.g. a span of 1e-14 where the Bézier points agree to a few ulps and F, their
    /// differences, is below their rounding errors).
    pub(crate) fn swamped(&self) -> bool {
        let zero = self.f.pts.iter().all(|x| x.mid() == 0.0 && x.rad() == 0.0);
        // (within a few radii of 0 rather than containing it: a coefficient whose enclosure
        // just misses 0 is as much noise, and then the subdivision cannot exclude boxes either;
        // an ENTIRE coefficient has an infinite radius)
        !zero && self.f.pts.iter().all(|x| x.mid().abs() <= 4.0 * x.rad())
    }

    /// Float first: f64 estimates of the zeros of F in (0, 1), from the midpoints of its
    /// coefficients, sorted, pushed to `out`; `false` if there seem to be more than `max`
    /// (or the coefficients are not finite). The estimates only place the tiny boxes
    /// [r - h, r + h] of the Newton search (`Engine::seed_float_first`), which proves or
    /// excludes everything itself; what this proves on the way goes to `free` (below).
    ///
    /// Bernstein subdivision with sign-change counts (variation diminishing property: a
    /// polynomial has no more zeros in (0, 1) than its Bernstein coefficients have sign
    /// changes; Farin, "Curves and Surfaces for CAGD"): a piece with no change is dropped, a
    /// piece with one change holds one simple zero of the f64 polynomial, located by Newton's
    /// method safeguarded by bisection; pieces with more changes are halved (to width 2^-20,
    /// then located like one-change pieces: a near-double zero), at most 8 (max + 1) pieces;
    /// so is a piece with one change whose coefficient at an end of the span is rounding noise
    /// (a zero of F at the knot besides the one the change shows, left to the end rule).
    ///
    /// `free` receives closed intervals of [0, 1], in increasing order, on which F provably has
    /// no zero. The pieces' f64 coefficients are within E_d of the exact coefficients of F over
    /// the piece ([`halving_bound`], d its depth), so a coefficient c with |c| > E_d has the
    /// exact one's sign. A piece is proven
    ///
    /// * **zero-free** when every coefficient has a proven sign and they all agree: F has that
    ///   sign on the closed piece (convex hull property);
    /// * **free but for the box** [x0, x1] = [r - h, r + h] around its estimate r (or, where
    ///   the signs at its ends are not proven, [r - h', r + h'] with h' = [`FLOAT_FIRST_H`] > h: the
    ///   box pushed with the estimate is then the wider one), when
    ///   t0 < x0 < x1 < t1, every coefficient has a proven sign with exactly one change, and F
    ///   at x0 (at x1) provably has the sign of the first (last) coefficient (f64 de Casteljau
    ///   with the a-priori bound of [`value_f64`]). Then F has at most one zero in (t0, t1)
    ///   (Descartes' rule of signs for the Bernstein basis, counted with multiplicity), one lies
    ///   in (x0, x1) (intermediate values: the signs at x0 and x1 differ), and F(t0), F(t1)
    ///   (the end coefficients) are not 0: [t0, x0] and [x1, t1] hold none.
    ///
    /// * **free but for a box at an end of the piece** ([`Numerator::end_rule`]), for a piece
    ///   whose coefficient there is rounding noise (a zero of F at a knot, t = 0 or 1, or at
    ///   the halving point t = 1/2 of a symmetric span); that end is then added to the
    ///   estimates, its box reaching into the neighbouring piece.
    ///
    /// Nothing else is claimed; the caller excludes the rest of the gaps between the boxes as
    /// before.
    pub(super) fn zero_estimates(
        &self,
        out: &mut Vec<Estimate>,
        max: usize,
        h: f64,
        free: &mut Vec<(f64, f64)>,
    ) -> bool {
        // (the buffers filled in place: inline buffers returned by value, as `collect` and
        // `from_slice` give them, are moved whole, up to 4 kB per call)
        let mut c: SmallVec<[f64; 64]> = SmallVec::new();
        c.extend(self.f.pts.iter().map(|x| x.mid()));
        let len = c.len();
        if len < 2 || !c.iter().all(|x| x.is_finite()) {
            return false;
        }
        // the bound's inputs: the largest |midpoint| and radius (an infinite radius gives an
        // infinite bound, which proves nothing)
        let m = c.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        let rad = self.f.pts.iter().fold(0.0f64, |a, x| a.max(x.rad()));
        let mut dc: SmallVec<[f64; 64]> = SmallVec::new();
        dc.extend(crate::spline::bezier::hodograph_iter(&c));
        let changes = |v: &[f64]| {
            // (without a zero coefficient, the usual case, by comparisons summed without
            // branches: the signs of the coefficients are unpredictable)
            if v.iter().fold(true, |a, &x| a & (x != 0.0)) {
                return v
                    .windows(2)
                    .map(|w| ((w[0] > 0.0) != (w[1] > 0.0)) as usize)
                    .sum();
            }
            let mut n = 0;
            let mut last = 0.0f64;
            for &x in v {
                if x != 0.0 {
                    if last != 0.0 && (x > 0.0) != (last > 0.0) {
                        n += 1;
                    }
                    last = x;
                }
            }
            n
        };
        // Pieces (t0, t1, where their coefficients start in `arena`, depth), last in first out:
        // the piece popped is always the one stored last, so its storage is freed by
        // truncating (no allocation per piece for the usual degrees). The left half is popped
        // first, so the pieces come in increasing order of t.
        // (the whole span, the first piece, from `c` itself: most spans need no halving, and
        // then no arena)
        let mut stack: SmallVec<[(f64, f64, usize, u32); 16]> = SmallVec::new();
        let mut arena: SmallVec<[f64; 512]> = SmallVec::new();
        let mut v: SmallVec<[f64; 64]> = SmallVec::new();
        v.extend_from_slice(&c);
        let mut first = Some((0.0, 1.0, 0));
        // (at most 8 (max + 1) pieces examined: noise-level coefficients of a nearly flat F
        // would otherwise split without end; then no estimates, the search runs as before)
        let mut pieces = 0;
        loop {
            let (t0, t1, depth) = match first.take() {
                Some(piece) => piece,
                None => match stack.pop() {
                    Some((t0, t1, start, depth)) => {
                        debug_assert_eq!(start + len, arena.len());
                        v.clear();
                        v.extend_from_slice(&arena[start..]);
                        arena.truncate(start);
                        (t0, t1, depth)
                    }
                    None => break,
                },
            };
            pieces += 1;
            if pieces > 8 * (max + 1) {
                return false;
            }
            let n = changes(&v);
            let e = halving_bound(len - 1, depth, m, rad);
            // (one sign change and an end coefficient of the piece that is rounding noise: a
            // zero of F at the span's end, a knot, or at the halving point of a symmetric
            // span, besides the one the change shows; halved like a piece of several changes,
            // so that the end's piece is left to the end rule and the other zero to one of its
            // own)
            let noisy_end = v[0].abs() <= e || v[len - 1].abs() <= e;
            let n = if n == 1 && noisy_end && t1 - t0 > 1.0 / 1_048_576.0 { 2 } else { n };
            let proved = if n == 0 {
                let free_piece = proven_changes(&v, e) == Some(0);
                if free_piece {
                    push_free(free, t0, t1);
                }
                free_piece
            } else if n == 1 || t1 - t0 <= 1.0 / 1_048_576.0 {
                if out.len() >= max {
                    return false;
                }
                let r = locate(&c, &dc, t0, t1, polygon_crossing(&v, t0, t1));
                let one_change = n == 1 && proven_changes(&v, e) == Some(1);
                let one_at = |hr: f64| {
                    let (x0, x1) = (r - hr, r + hr);
                    t0 < x0
                        && x1 < t1
                        && self.has_sign(x0, v[0] > 0.0)
                        && self.has_sign(x1, v[len - 1] > 0.0)
                };
                // (where F's values at r -+ h are below their error bound, a small slope next
                // to wide coefficients (tiny spans), the box widened once to FLOAT_FIRST_H:
                // still far below the widths where the tight enclosures over a box lose
                // accuracy)
                let hr = if !one_change {
                    None
                } else if one_at(h) {
                    Some(h)
                } else {
                    (h < FLOAT_FIRST_H && one_at(FLOAT_FIRST_H)).then_some(FLOAT_FIRST_H)
                };
                out.push((r, hr.unwrap_or(h)));
                if let Some(hr) = hr {
                    push_free(free, t0, r - hr);
                    push_free(free, r + hr, t1);
                }
                hr.is_some()
            } else {
                // the halves at 1/2 (right stored first, so the left one is popped first)
                let mid = 0.5 * (t0 + t1);
                let r0 = arena.len();
                arena.resize(r0 + 2 * len, 0.0);
                let (right, left) = arena[r0..].split_at_mut(len);
                halve(&mut v, left, right);
                stack.push((mid, t1, r0, depth + 1));
                stack.push((t0, mid, r0 + len, depth + 1));
                continue;
            };
            // (a piece with at most one sign change that the rules above leave open: a zero at
            // an end of the piece, the span's or the halving point)
            if !proved && n <= 1 {
                if let Some((end, f0, f1, hr)) = self.end_rule(&v, e, t0, t1, h) {
                    if out.len() >= max {
                        return false;
                    }
                    out.push((end, hr));
                    push_free(free, f0, f1);
                }
            }
        }
        out.sort_by(|a, b| a.0.total_cmp(&b.0));
        true
    }

    /// The boxes of the float-first search and what is left to exclude between them: the
    /// estimates of [`Numerator::zero_estimates`] (at most `max`; `est` and `free` are its
    /// scratch) as boxes [r - h, r + h] (each with its own half-width, `h` or the wider one of
    /// the estimation) clamped to [0, 1] and merged where they overlap
    /// (`boxes`, increasing), and the parts of [0, 1] outside the boxes that its zero-free
    /// intervals do not cover (`gaps`, closed, depth 0). `false` where the estimation gave
    /// nothing (then `boxes` and `gaps` are empty). Every zero of F in [0, 1] lies in a box or
    /// in a gap.
    pub(super) fn zero_boxes(
        &self,
        h: f64,
        max: usize,
        (est, free): (&mut Vec<Estimate>, &mut Vec<(f64, f64)>),
        boxes: &mut Vec<(f64, f64)>,
        gaps: &mut Vec<(f64, f64, u32)>,
    ) -> bool {
        est.clear();
        free.clear();
        boxes.clear();
        gaps.clear();
        if !self.zero_estimates(est, max, h, free) {
            return false;
        }
        for &(r, hr) in est.iter() {
            push_free(boxes, (r - hr).max(0.0), (r + hr).min(1.0));
        }
        let mut left = 0.0;
        for &(lo, hi) in boxes.iter() {
            if lo > left {
                push_unproven(gaps, left, lo, free);
            }
            left = hi;
        }
        if left < 1.0 {
            push_unproven(gaps, left, 1.0, free);
        }
        true
    }

    /// The critical points of the piece, proven located (the `bezier` strategy's fast path
    /// on spans of any degree): the boxes of [`SpanPoly::zero_boxes`] (half-width `h`), whose
    /// union holds every zero of F in [0, 1]; `None` unless the estimation's zero-free
    /// intervals and [`Numerator::exclude_gaps`] cover everything outside the boxes. Sound: a
    /// zero of F outside every box would lie in a proven zero-free interval or an excluded
    /// gap. Since F has the sign and the zeros of C_j' on the closed span, every interior
    /// extremum of the piece lies in a box.
    pub(crate) fn critical_boxes(&self, h: f64) -> Option<Vec<(f64, f64)>> {
        // (the scratch vectors from this thread's pool, `num::pool`, and handed back; the
        // boxes' vector too, which a caller may give back to the pool when done)
        let (mut est, mut free, mut gaps) = (pool::take(0), pool::take(0), pool::take(0));
        let mut boxes = pool::take(0);
        let max = self.f.pts.len() + 1;
        let found = self.zero_boxes(h, max, (&mut est, &mut free), &mut boxes, &mut gaps)
            && self.exclude_gaps(&mut gaps, &mut 0);
        pool::give(est);
        pool::give(free);
        pool::give(gaps);
        found.then_some(boxes)
    }

    /// Whether F provably has no zero in any of the `gaps` ([t0, t1, depth] in [0, 1], used
    /// up): each is excluded where the enclosure of F over it ([`SpanPoly::f`], the hull of
    /// its Bernstein coefficients restricted to the gap, every one enclosing the exact one)
    /// excludes 0, after at most two halvings (depth < 2); `false` at the first gap that is not
    /// excluded (a gap whose end is next to a zero just outside it would need many halvings).
    /// `evals` counts the enclosures of F.
    pub(crate) fn exclude_gaps(&self, gaps: &mut Vec<(f64, f64, u32)>, evals: &mut u64) -> bool {
        while let Some((g0, g1, depth)) = gaps.pop() {
            *evals += 1;
            let fg = self.over(T::new(g0, g1));
            if !fg.is_empty() && !fg.contains(0.0) {
                continue; // no zero of F in [g0, g1]
            }
            let m = midpoint(g0, g1);
            if depth < 2 && g0 < m && m < g1 {
                gaps.push((g0, m, depth + 1));
                gaps.push((m, g1, depth + 1));
            } else {
                return false;
            }
        }
        true
    }

    /// The end rule of [`Numerator::zero_estimates`], for a zero of F at (or next to) an end of
    /// a piece, where the piece's end coefficient there is rounding noise: at an end of the
    /// span (a symmetric curve's extremum at a knot), or at the midpoint where the pieces were
    /// halved (a symmetric span's zero of F at t = 1/2). For a piece [t0, t1] whose f64
    /// coefficients `v` (within `e` of the exact ones) other than the last all have one proven
    /// sign s, with t0 < x0 = t1 - h and F(x0) of proven sign s, it returns the estimate t1
    /// (whose box [t1 - h, t1 + h], clamped to [0, 1], the caller makes) and the zero-free
    /// [t0, x0] (and symmetrically at t0: the estimate t0 and [t0 + h, t1]). Proof: the
    /// exact coefficients have at most one sign change (between the last two), so F has at most
    /// one zero in (t0, t1) (Descartes' rule of signs for the Bernstein basis); if the last one
    /// has sign -s there is one in (x0, t1) (intermediate values), and that is the only one;
    /// otherwise there is none. F(t0), the first coefficient, is not 0. So [t0, x0] holds no
    /// zero, and the box holds every zero of the piece beyond it (and whatever zeros of the
    /// next piece it covers: a box may hold any number).
    ///
    /// Where F(t1 - h) lies below its error bound (F's slope at the end small against its
    /// largest coefficients, which set the bound of [`value_f64`]: a symmetric curve's
    /// extremum at a knot, the span steep at its far end) the box is widened once to
    /// [`FLOAT_FIRST_H`], as for the estimates of [`Numerator::zero_estimates`] (the same proof
    /// with h' in place of h). Returned: the end, the zero-free interval and the box's
    /// half-width.
    fn end_rule(
        &self,
        v: &[f64],
        e: f64,
        t0: f64,
        t1: f64,
        h: f64,
    ) -> Option<(f64, f64, f64, f64)> {
        let len = v.len();
        if len < 2 {
            return None;
        }
        let widths = [h, FLOAT_FIRST_H];
        let widths = &widths[..if h < FLOAT_FIRST_H { 2 } else { 1 }];
        if proven_changes(&v[..len - 1], e) == Some(0) {
            for &hr in widths {
                let x0 = t1 - hr;
                if t0 < x0 && self.has_sign(x0, v[0] > 0.0) {
                    return Some((t1, t0, x0, hr));
                }
            }
        }
        if proven_changes(&v[1..], e) == Some(0) {
            for &hr in widths {
                let x1 = t0 + hr;
                if x1 < t1 && self.has_sign(x1, v[len - 1] > 0.0) {
                    return Some((t0, x1, t1, hr));
                }
            }
        }
        None
    }

    /// Whether F(t) provably is > 0 (`positive`) or < 0 at the point t in [0, 1]: the f64 value
    /// with its a-priori bound ([`value_f64`], else [`value_vs_f64_weighted`]) excludes 0 on
    /// that side.
    fn has_sign(&self, t: f64, positive: bool) -> bool {
        let proves = |v: Option<(Interval, f64)>| match v {
            Some((v, _)) if positive => v.inf() > 0.0,
            Some((v, _)) => v.sup() < 0.0,
            None => false,
        };
        // (the plain bound first; where it swamps the value, the one weighted by the basis at
        // t, which sees only the coefficients near t)
        proves(value_f64(&self.f.pts, t)) || proves(value_vs_f64_weighted(&self.f.pts, t))
    }
}

/// The hull of F'' over [0, 1] from the Bernstein coefficients D'_i of F' (m of them, each
/// within its radius r_i of its centre c_i): the coefficients of F'' are X_i = (m - 1)
/// (D'_{i+1} - D'_i) (NURBS Book eq. 1.10, the hodograph), whose hull contains F'' (convex
/// hull property), taken in plain f64 with one a-priori bound. With nm = m - 1 (an exact small
/// integer), s_i = fl(c_{i+1} - c_i) and v_i = fl(nm s_i), |X_i - v_i| is at most
/// nm (r_{i+1} + r_i) plus nm |s_i - (c_{i+1} - c_i)| plus |nm s_i - v_i|, so at most
/// 2 nm R + nm U1 |s_i| + U1 |v_i| + eta; with nm |s_i| <= (1 + U1) |v_i| + eta,
/// |X_i - v_i| <= E = 2 nm R + 4 U1 V + 16 eta (R, V
/// the largest r_i and |v_i|), three terms of Lemma B (`up`). The hull [min v_i - E,
/// max v_i + E] rounded outward one step holds every X_i for every choice of the D'_i in
/// their enclosures; the whole line where something is not finite, the point 0 for fewer
/// than two coefficients (F' constant; an unknown F' is one ENTIRE coefficient, and every use
/// of this hull adds it to an F'(m) that is then ENTIRE too).
fn second_hull(dco: &[Mr]) -> Interval {
    if dco.len() < 2 {
        return iv::point(0.0);
    }
    let nm = (dco.len() - 1) as f64;
    // (the v_i by the shared hodograph kernel on the centres)
    // (filled in place: a collected inline buffer is moved whole)
    let mut mids: SmallVec<[f64; 128]> = SmallVec::new();
    mids.extend(dco.iter().map(|x| x.mid()));
    let rmax = dco.iter().fold(0.0f64, |m, x| m.max(x.rad()));
    let (mut lo, mut hi, mut finite) = (f64::INFINITY, f64::NEG_INFINITY, true);
    for v in crate::spline::bezier::hodograph_iter(&mids) {
        finite &= v.is_finite();
        lo = lo.min(v);
        hi = hi.max(v);
    }
    let e = up(nm * (rmax + rmax) + 4.0 * U1 * (-lo).max(hi) + ETA16);
    if !(finite && e.is_finite()) {
        return Interval::ENTIRE;
    }
    Interval::try_from(((lo - e).next_down(), (hi + e).next_up())).unwrap_or(Interval::ENTIRE)
}

/// The lean form of one span and coordinate for `bezier`'s proof (`bezier::Critical`): of
/// [`SpanPoly`] only what that proof reads (the shifted double-double segment, F, and the
/// bounds of its tight box enclosures), built by the same operations (the same shift, the
/// same F, the same `dfmax` and `wmin`: the same boxes and enclosures), without the form's
/// `Mr` segment, F' and the hull of F'', which the Newton search and the cheap box values
/// need.
pub(crate) struct SpanProof {
    dseg: BezierSeg<Ddi>,
    shift: f64,
    f: BezierSeg<Mr>,
    dfmax: f64,
    wmin: f64,
}

impl Drop for SpanProof {
    fn drop(&mut self) {
        pool::give(std::mem::take(&mut self.dseg.pts));
        pool::give(std::mem::take(&mut self.f.pts));
    }
}

impl SpanProof {
    /// The form of coordinate j of `c` on span k with point i's coordinate j and weight given
    /// by `row(i)` (as [`SpanPoly::new`], [`SpanPoly::from_coefficients`] and
    /// [`SpanPoly::from_homogeneous`]; `pair` from [`pair_coefficients`] for a rational curve);
    /// `None` where F would be unknown (a rational curve without `pair`).
    pub(crate) fn new(
        c: &NurbsCurve,
        j: usize,
        k: usize,
        pair: &[Mr],
        row: impl Fn(usize) -> (Ddi, Ddi),
    ) -> Option<SpanProof> {
        let p = c.degree();
        let rational = c.is_rational();
        if rational && pair.is_empty() {
            return None;
        }
        // (the local control values and the `Mr` rounding of the points, as the form's `seg`,
        // in arrays on the stack up to degree 11, filled by plain loops)
        let (mut xs, mut xh) = ([0.0f64; 12], Vec::new());
        let xs = filled(&mut xs, &mut xh, p + 1, |i| c.control_point(k - p + i)[j]);
        let shift = span_shift(xs);
        let dseg = shifted_from_points(c, k, shift, row);
        let (mut qs, mut qh) = ([Mr::ENTIRE; 24], Vec::new());
        let q = filled(&mut qs, &mut qh, dseg.pts.len(), |i| Mr::from_ddi(dseg.pts[i]));
        let mut fco: Vec<Mr> = pool::take(2 * p);
        if rational {
            pair_sum_f64(q, pair, p, &mut fco);
        } else {
            fco.extend(q.windows(2).map(|w| w[1] - w[0]));
        }
        let (dfmax, wmin) = derivative_bounds(&fco, rational.then_some(q));
        let f = BezierSeg {
            a: dseg.a,
            b: dseg.b,
            degree: fco.len() - 1,
            dim: 1,
            rational: false,
            pts: fco,
        };
        Some(SpanProof { dseg, shift, f, dfmax, wmin })
    }

    /// F alone ([`Numerator`]).
    pub(crate) fn numerator(&self) -> Numerator<'_> {
        Numerator { f: &self.f }
    }

    /// [`SpanPoly::box_tight`] on this form.
    pub(crate) fn box_tight(&self, x0: f64, x1: f64) -> Option<(Interval, Ddi)> {
        let form = BoxForm {
            dseg: &self.dseg,
            shift: self.shift,
            f: &self.f,
            dfmax: self.dfmax,
            wmin: self.wmin,
        };
        // (|W'| from the `Mr` rounding of the weights, as the form's)
        let slope = || {
            let (mut qs, mut qh) = ([Mr::ENTIRE; 24], Vec::new());
            weight_slope(filled(&mut qs, &mut qh, self.dseg.pts.len(), |i| Mr::from_ddi(self.dseg.pts[i])))
        };
        form.tight_over(T::new(x0, x1), slope)
    }
}

/// The bounds `dfmax` >= |F'| and `wmin` <= W on the span of [`SpanPoly`] from F's
/// coefficients `fco` and, for a rational piece, its `Mr` points `q` (rows ((x - c) w, w)):
/// the hull bound of F' = n sum (F_{i+1} - F_i) B_i^{n-1} and the smallest lower end of the
/// weights' Bézier points (convex hull property; 1 for a polynomial piece).
fn derivative_bounds(fco: &[Mr], q: Option<&[Mr]>) -> (f64, f64) {
    let n = fco.len() - 1;
    let dfmax = if n == 0 {
        0.0
    } else {
        let nm = Mr::from_usize(n);
        mag_bound(fco.windows(2).map(|w| nm * (w[1] - w[0])))
    };
    (dfmax, q.map_or(1.0, weight_floor))
}

/// The smallest lower end of the weights' Bézier points among the rows ((x - c) w, w) `q`: a
/// lower bound of W on the span (convex hull property).
fn weight_floor(q: &[Mr]) -> f64 {
    q.iter().skip(1).step_by(2).fold(f64::INFINITY, |m, w| m.min(w.bounds().0))
}

/// What the tight enclosure over a box of [`SpanPoly::tight_over`] reads: the span's shifted
/// double-double segment and its shift, F and the bounds |F'| <= `dfmax`, W >= `wmin` on the
/// span. Shared by [`SpanPoly`] and the lean [`SpanProof`].
struct BoxForm<'a> {
    dseg: &'a BezierSeg<Ddi>,
    shift: f64,
    f: &'a BezierSeg<Mr>,
    dfmax: f64,
    wmin: f64,
}

impl BoxForm<'_> {
    /// [`SpanPoly::tight_over`] without v0, with `slope` the bound of |W'| on the span
    /// ([`weight_slope`], computed only where the weights' lower bound is needed over the box
    /// alone).
    fn tight_over(&self, t: T, slope: impl FnOnce() -> f64) -> Option<(Interval, Ddi)> {
        let seg = self.dseg;
        let p = seg.degree;
        let (t0, t1) = (t.lo, t.hi);
        if !(0.0 <= t0 && t0 < t1 && t1 <= 1.0) {
            return None;
        }
        // (a box of two neighbouring doubles, as the search leaves at machine precision, has no
        // double strictly inside: then its lower end)
        let mid = midpoint(t0, t1);
        let tm = if t0 < mid && mid < t1 { mid } else { t0 };
        let r = dist_up(tm, t0).max(dist_up(t1, tm));
        let h = if seg.rational { 2 } else { 1 };
        let row = |i: usize| -> SmallVec<[Ddi; 32]> {
            seg.pts.iter().skip(i).step_by(h).copied().collect()
        };
        let shift = Ddi::exact(self.shift);
        // |F| over the box: |F(t_m)| + r max |F'| (mean value theorem; F(t_m) by the f64 value
        // with its a-priori bound, |F'| <= `dfmax` on the span by the convex hull property), in
        // O(n); where that is not finite, the f64 restriction's hull with its a-priori bound (a
        // magnitude is all that is needed here, so no sharper form where that hull holds 0),
        // else `Mr`'s
        let by_value = value_f64(&self.f.pts, tm)
            .map(|(v, _)| iv::add_up(v.mag(), iv::mul_up(r, self.dfmax)))
            .filter(|m| m.is_finite());
        let fm = match by_value {
            Some(m) => m,
            None => match restrict_hull_f64(&self.f.pts, t0, t1) {
                Some((v, _, _)) => v.mag(),
                None => hull(&SpanPoly::restrict(self.f, t0, t1)).mag(),
            },
        };
        // (the rows' values at t_m: in double words with one a-priori bound up to degree
        // VS_DW_MAX, else by the scheme in `Ddi`)
        let (v, e) = if seg.rational {
            let wmin = self.wmin;
            if wmin.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
                return None;
            }
            let [x, w] = value_vs_dw::<2>(&seg.pts, h, tm).unwrap_or_else(|| {
                [bernstein_value_s(&row(0), tm), bernstein_value_s(&row(1), tm)]
            });
            let v = x / w + shift;
            let rf = iv::mul_up(r, fm);
            let e = iv::div_up(iv::div_up(rf, wmin), wmin);
            // (where that is not far below an ulp of the value: W over the box is at least
            // W(t_m) - r max |W'| by the mean value theorem, often far above the span's smallest
            // weight wmin when the weights vary over the span (|W'| bounded by
            // [`weight_slope`], computed only here); either bound holds, the larger is taken; a
            // NaN or infinite term fails the comparison and leaves wmin)
            let e = if e <= 0.125 * crate::num::ulp(v.hi()) {
                e
            } else {
                let local = (w.lower_end() - iv::mul_up(r, slope())).next_down();
                let wb = if local > wmin { local } else { wmin };
                iv::div_up(iv::div_up(rf, wb), wb)
            };
            (v, e)
        } else {
            let [x] = value_vs_dw::<1>(&seg.pts, h, tm)
                .unwrap_or_else(|| [bernstein_value_s(&row(0), tm)]);
            let v = x + shift;
            let e = iv::mul_up(iv::mul_up(r, fm), p as f64);
            (v, e)
        };
        if v.is_entire() || !e.is_finite() {
            return None;
        }
        // (widened in double-double, then rounded outward once: a tiny e does not cost the
        // extra ulp on each side that adding it in f64 intervals would)
        let enc = v.widen(e).to_interval();
        Some((enc, v))
    }
}

/// An upper bound of |W'(t)| for t in [0, 1], W the weight of a rational Bézier segment whose
/// homogeneous points `pts` are (x w, w) pairs of degree p (`Mr` enclosures): W' = p sum_i
/// (w_{i+1} - w_i) B_i^{p-1} (the hodograph, NURBS Book eq. 1.10) with nonnegative Bernstein
/// polynomials summing to 1, so |W'| <= p max_i |w_{i+1} - w_i|, and for every choice of the weights
/// in their enclosures [l_i, h_i] (`Mr::bounds`, outward) |w_{i+1} - w_i| <= max(h_{i+1} - l_i,
/// h_i - l_{i+1}); each difference in round to nearest stepped one ulp up, the product by
/// `iv::mul_up`. +inf where something is not finite (then the bound is of no use and the
/// caller keeps its other one).
fn weight_slope(pts: &[Mr]) -> f64 {
    // (the weights w_i = pts[2 i + 1])
    let p = (pts.len() / 2).saturating_sub(1);
    let mut m = 0.0f64;
    for i in 0..p {
        let ((l0, h0), (l1, h1)) = (pts[2 * i + 1].bounds(), pts[2 * i + 3].bounds());
        let d = (h1 - l0).max(h0 - l1);
        if !d.is_finite() {
            return f64::INFINITY;
        }
        m = m.max(d.next_up());
    }
    iv::mul_up(p as f64, m)
}

/// The largest [`Mr::mag`] of `v` (at least 0): Mr::mag is max(-lo, hi) of [`Mr::bounds`],
/// (next_down(fl(c - r)), next_up(fl(c + r))) for r > 0, which is next_up(fl(|c| + r)) since
/// round to nearest is odd and monotone, and |c| for r = 0; next_up is monotone, so the
/// largest of those is next_up of the largest |c| + r, with the exact ones beside: the same
/// value, without two steps per coefficient.
fn mag_bound(v: impl IntoIterator<Item = Mr>) -> f64 {
    let (mut exact, mut wide) = (0.0f64, f64::NEG_INFINITY);
    for x in v {
        if x.rad() == 0.0 {
            exact = exact.max(x.mid().abs());
        } else {
            wide = wide.max(x.mid().abs() + x.rad());
        }
    }
    exact.max(wide.next_up())
}

/// de Casteljau's split at 1/2 (NURBS Book A1.5) of the f64 Bernstein coefficients `b`
/// (overwritten) into `left` (over [0, 1/2]) and `right` (over [1/2, 1]): the shared kernel's
/// levels written to caller buffers (`bezier::de_casteljau_split` without its allocations), for
/// the estimates of [`Numerator::zero_estimates`].
/// (Generic so that the test of [`halving_bound`] runs the same splits in exact arithmetic.)
fn halve<S: Scalar>(b: &mut [S], left: &mut [S], right: &mut [S]) {
    let n = b.len() - 1;
    left[0] = b[0].clone();
    right[n] = b[n].clone();
    de_casteljau_levels(b, 1, &S::from_f64(0.5), |r, b| {
        left[r] = b[0].clone();
        right[n - r] = b[n - r].clone();
    });
}

/// A bound E_d of the distance of every f64 coefficient of a piece of depth d of
/// [`Numerator::zero_estimates`] (d halvings by [`halve`] of the midpoints of degree-n
/// coefficients, largest |midpoint| `m`, largest radius `rad`) from the exact coefficient of
/// F over the piece (whose ends are dyadic, so exact): each halving is n de Casteljau levels at
/// t = 1/2 in the f64 kernel, every level an error of at most 5.01 u M̄ + 1.01 η against the
/// exact cut of its computed operands, with the operands' errors passing through the convex
/// combination without growing (the argument of [`restrict_hull_f64`], there for 2n levels);
/// so L = n d levels give at most 5.01 L u M̄ + 1.01 L η, with M̄ <= M (1 + 5.01 L u) + 2 L η
/// <= 1.001 M + 2 L η for L <= 2^30 (u = 2^-53, η = 2^-1075). The midpoints are within `rad`
/// of the exact coefficients and the restriction is linear with nonnegative weights summing
/// to 1, which adds `rad`. E_d = up(2^-50 L m + L 2^-1073 + rad) >= 8 L u m + 4 L η + rad
/// (Lemma B of [`crate::num::ddi`]; 2^-50 L and L 2^-1073 are exact). Infinite for L above
/// 2^30 or non-finite inputs (then nothing is proven). Tested against exact rational
/// subdivision (`halving_bound_holds_exactly`).
fn halving_bound(n: usize, depth: u32, m: f64, rad: f64) -> f64 {
    let l = (n as u64).saturating_mul(depth as u64);
    if l > 1 << 30 {
        return f64::INFINITY;
    }
    let lf = l as f64;
    // (L 2^-1073 as the subnormal 2L 2^-1074 built from its bits, exact for L <= 2^30: a product
    // with a subnormal result takes a slow path in the hardware)
    up(lf * (1.0 / 1_125_899_906_842_624.0) * m + f64::from_bits(2 * l) + rad)
}

/// The number of sign changes of the exact coefficients within `e` of the f64 coefficients
/// `v` when every |v_i| > e (each exact coefficient then has the sign of v_i), else `None`
/// (a coefficient of unknown sign, or non-finite data). Every coefficient must be finite: the
/// bound's proof assumes that no computed value overflowed, and an overflow anywhere in the
/// halvings reaches every later piece (each halving's apex is in both halves), so a finite
/// piece had only finite ancestors. (An infinite coefficient would otherwise pass as a proven
/// sign: values near f64::MAX, whose differences overflow.)
fn proven_changes(v: &[f64], e: f64) -> Option<usize> {
    if !e.is_finite() {
        return None;
    }
    // (every |v_i| > e and finite (false for a NaN), and the sign changes, summed without
    // branches: the signs are unpredictable)
    let ok = v.iter().fold(true, |a, &x| a & x.is_finite() & (x.abs() > e));
    let n = v
        .windows(2)
        .map(|w| ((w[0] > 0.0) != (w[1] > 0.0)) as usize)
        .sum();
    ok.then_some(n)
}

/// Append the closed interval [lo, hi] to the list `free` of intervals increasing in their
/// lower ends, merged with the last one where they touch or overlap.
fn push_free(free: &mut Vec<(f64, f64)>, lo: f64, hi: f64) {
    match free.last_mut() {
        Some(last) if lo <= last.1 => last.1 = last.1.max(hi),
        _ => free.push((lo, hi)),
    }
}

/// A zero estimate of [`Numerator::zero_estimates`] and the half-width of its box.
pub(super) type Estimate = (f64, f64);

/// The half-width 2^-30 of `newton`'s float-first boxes in the local parameter
/// (`Engine::seed_float_first`), and of an estimate's box where the caller's own is too
/// narrow for the signs of F at its ends to be proven ([`Numerator::zero_estimates`]).
pub(super) const FLOAT_FIRST_H: f64 = 1.0 / 1_073_741_824.0;

/// How close (in t in [0, 1]) an estimate of [`locate`] needs to be: far below the half-width
/// 2^-30 of the boxes the Newton search puts around it (`Engine::seed_float_first`). Asking for
/// more made Newton's f64 steps bounce at the rounding level of the evaluation until the
/// iteration limit (most of the estimation cost at degree 10).
const LOCATE_TOL: f64 = 1.0 / 17_592_186_044_416.0; // 2^-44

/// Where the control polygon of the piece `v` over [t0, t1] (Bernstein coefficients, abscissae
/// i / n) first crosses 0, mapped to [t0, t1]: the start of [`locate`] (it converges to a simple
/// zero quadratically under subdivision; Farin, "Curves and Surfaces for CAGD"). The midpoint
/// when there is no crossing.
fn polygon_crossing(v: &[f64], t0: f64, t1: f64) -> f64 {
    let n = v.len().saturating_sub(1).max(1) as f64;
    let mut last: Option<(usize, f64)> = None;
    for (i, &x) in v.iter().enumerate() {
        if x == 0.0 {
            continue;
        }
        if let Some((l, y)) = last {
            if (x > 0.0) != (y > 0.0) {
                let s = (l as f64 + (i - l) as f64 * (y / (y - x))) / n;
                return t0 + s * (t1 - t0);
            }
        }
        last = Some((i, x));
    }
    0.5 * (t0 + t1)
}

/// A zero of the f64 Bernstein polynomial `c` (derivative coefficients `dc`) in [t0, t1],
/// where the sign changes once: [`locate_by`] on its values (an estimate only; see
/// [`Numerator::zero_estimates`]).
fn locate(c: &[f64], dc: &[f64], t0: f64, t1: f64, start: f64) -> f64 {
    let f0 = crate::spline::bezier::bernstein_value(c, t0);
    locate_by(
        |t| crate::spline::bezier::bernstein_value_pair(c, dc, t),
        f0 > 0.0,
        t0,
        t1,
        start,
    )
}

/// A zero of an f64 function in [t0, t1] where its sign changes once (`pos_t0`: its sign at
/// t0), from `f(t)` = (value, derivative): Newton's method from `start` (the midpoint if
/// `start` is not inside), a bisection step whenever it leaves the bracket, until a step or
/// the bracket is below [`LOCATE_TOL`]. An estimate only: the callers choose test points or
/// boxes from it and prove everything there.
pub(crate) fn locate_by(
    f: impl Fn(f64) -> (f64, f64),
    pos_t0: bool,
    mut t0: f64,
    mut t1: f64,
    start: f64,
) -> f64 {
    let mut t = if start > t0 && start < t1 {
        start
    } else {
        0.5 * (t0 + t1)
    };
    for _ in 0..60 {
        let (ft, d) = f(t);
        if ft == 0.0 {
            return t;
        }
        // keep the bracket: the zero is between the ends of opposite sign
        if (ft > 0.0) == pos_t0 {
            t0 = t;
        } else {
            t1 = t;
        }
        let mut nt = t - ft / d;
        // (a converged step first: at the rounding level a step can land just outside the
        // updated bracket, and a bisection from there crawled back in dozens of steps)
        if (nt - t).abs() <= LOCATE_TOL || t1 - t0 <= LOCATE_TOL {
            return t;
        }
        if !(nt > t0 && nt < t1) {
            nt = 0.5 * (t0 + t1);
        }
        t = nt;
    }
    t
}

/// The homogeneous Bézier segment of the shifted piece C_j - c on span k of `c`, rows
/// ((x - c) w, w) (rational) or x - c, from the span's double-double Bézier points, point i's
/// coordinate j and weight given by `row(i)` (from every row of the homogeneous curve,
/// [`crate::spline::tight::TightEval::bezier_points`], or the lane's own points): knot
/// insertion is linear in the control points, so the shifted piece's Bézier points are
/// A_i - c W_i (A_i, W_i the points of the rows w x_j and w; x_i - c without weights), each
/// enclosed by one `Ddi` operation (a fused multiply-add: about 2^-100 relative to |A_i|, so a
/// flat run's points come out within that of 0, where the former insertion of the shifted
/// points in `Mr` gave exact zeros and a few hundred ulps elsewhere).
fn shifted_from_points(
    c: &NurbsCurve,
    k: usize,
    shift: f64,
    row: impl Fn(usize) -> (Ddi, Ddi),
) -> BezierSeg<Ddi> {
    let p = c.degree();
    let rational = c.is_rational();
    let neg = Ddi::exact(-shift);
    let mut out = pool::take((p + 1) * (1 + rational as usize));
    for i in 0..=p {
        let (a, w) = row(i);
        if rational {
            out.push(w.mul_add(neg, a));
            out.push(w);
        } else {
            out.push(a + neg);
        }
    }
    let kn = c.knots();
    BezierSeg {
        a: kn[k],
        b: kn[k + 1],
        degree: p,
        dim: 1,
        rational,
        pts: out,
    }
}

/// The values over the local box [t0, t1] (0 <= t0 < t1 <= 1) of the one-coordinate segment
/// `seg` (rows x w, w or x): its rows restricted in f64 with the a-priori bound of
/// [`restrict_hull_f64`] (each restricted homogeneous coefficient within E_row of the exact
/// one, over a box containing [t0, t1]), the hull of the outward-rounded quotients of those
/// enclosures (convex hull property of the rational piece, weights > 0). `None` where that does
/// not apply (degree above [`F64_RESTRICT_MAX`]) or gives nothing finite.
pub(crate) fn segment_values_f64(seg: &BezierSeg<Mr>, t0: f64, t1: f64) -> Option<Interval> {
    if !(0.0 <= t0 && t0 < t1 && t1 <= 1.0) {
        return None;
    }
    // (both rows in one interleaved restriction: the same splits per row, each row with its
    // own bound)
    let v = if seg.rational {
        restricted_f64::<2, _>(&seg.pts, t0, t1, |b, e| {
            b.chunks_exact(2).fold(Interval::EMPTY, |a, q| {
                a.convex_hull(widened(q[0], q[0], e[0]) / widened(q[1], q[1], e[1]))
            })
        })
    } else {
        restricted_f64::<1, _>(&seg.pts, t0, t1, |b, e| {
            b.iter()
                .fold(Interval::EMPTY, |a, &x| a.convex_hull(widened(x, x, e[0])))
        })
    }?;
    (!v.is_empty() && v.is_common_interval()).then_some(v)
}

/// The Bernstein coefficients of the rational derivative numerator (see [`SpanPoly`]),
/// D_k = sum over i < l with i + l - 1 = k of P_il (A_l W_i - A_i W_l), for homogeneous points
/// `q` = (A_0, W_0, A_1, W_1, ...) and pair coefficients P_il = `pair[i (p + 1) + l]`, all
/// enclosed in [`Mr`]: the sums in plain f64 on the centres, each enclosed with one a-priori
/// bound, instead of an `Mr` operation per product with its own radius and exactness test
/// (O(p^2) per span and coordinate; -8% of `newton`'s instructions on the `high_degree`
/// family).
///
/// The bound (u = 2^-53, U1 = u (1 + 2^-50), η = 2^-1075 the underflow error of a product). Per
/// term, with centres a, w, P and radii r: x1 = fl(a_l w_i), x2 = fl(a_i w_l), t = fl(x1 - x2),
/// v = fl(P t), S = |x1| + |x2|, ρ1 = |a_l| r_wi + |w_i| r_al + r_al r_wi (so |A_l W_i - a_l w_i|
/// <= ρ1; ρ2 alike). Each rounding errs by at most U1 |result| (+ η for a product), so with
/// the exact D = A_l W_i - A_i W_l: |D - t| <= ρ1 + ρ2 + U1 (S + |t|) + 2η, |t| <= 1.001 S,
/// |D| <= 1.01 S + ρ1 + ρ2 + 2η, and for every P in the pair's enclosure
/// |P D - v| <= r_P |D| + |P| |D - t| + U1 |v| + η
///          <= r_P (1.01 S + ρ1 + ρ2) + |P| (ρ1 + ρ2) + 3.03 u |P| S + η (2 r_P + 2 |P| + 1).
/// The m terms of D_k are summed in order from 0: at most (m - 1) roundings of partial sums
/// of |v| <= 1.01 |P| S each, error <= 1.03 (m - 1) u sum |P| S (m <= 256). So
/// the sum over the terms of r_P (1.01 S + ρ1 + ρ2) + |P| (ρ1 + ρ2), plus
/// (3.03 + 1.03 (m - 1)) u sum |P| S, plus η sum (2 r_P + 2 |P| + 1), is a bound of
/// |D_k - d_k|. The products computed for this bound can underflow too, each by at most η:
/// three in each of ρ1, ρ2 (which the bound multiplies by |P| + r_P, so 6 (|P| + r_P) η), and
/// a few more per term; so the η share per term taken is 10 (r_P + |P|) + 17 multiples of
/// 2^-1074 = 2η, at least twice what is needed. E_k is computed in f64 from nonnegative terms
/// only: each of its at most 2^12 roundings to nearest loses at most a factor 1 - u, so the
/// computed sum times 1 + 2^-40, rounded, is at least E_k. A term whose products each have a
/// factor that is an exact 0 (centre and radius 0) is exactly 0 and adds nothing (flat runs,
/// shifted to zero, stay exact zeros); any other term adds its η share, also where its
/// computed radius terms underflowed to 0 (a zero centre with a subnormal radius times a
/// weight near 1e-214). A non-finite centre or bound gives ENTIRE. Tested against exact rational
/// sums over the corners of the input enclosures (`pair_sum_bound_holds_exactly`).
fn pair_sum_f64(q: &[Mr], pair: &[Mr], p: usize, out: &mut Vec<Mr>) {
    // (the scratch rows on the stack, zeroed by a few wide stores: sized for degree 7 where
    // that is enough, the usual degrees, else for degree 31; the heap above)
    if p <= 7 {
        pair_sum_f64_in::<48, 65>(q, pair, p, out)
    } else {
        pair_sum_f64_in::<192, 160>(q, pair, p, out)
    }
}

/// [`pair_sum_f64`] with scratch arrays of `R` and `A` values on the stack.
fn pair_sum_f64_in<const R: usize, const A: usize>(q: &[Mr], pair: &[Mr], p: usize, out: &mut Vec<Mr>) {
    const C: f64 = f64::EPSILON / 2.0; // u
    let n = 2 * p - 1;
    let m1 = p + 1;
    // The points as rows (centres and radii of the a_i and the w_i, and whether each is an
    // exact zero), so that the terms of the consecutive sums k = 2i + x (l = i + 1 + x) for
    // one i come from contiguous values, four at a time where AVX2 is enabled
    // ([`pair_terms4`]); the same IEEE operations in the same order for every term and sum as
    // [`pair_term`], so the same result bit for bit either way.
    // (exactly zero: centre and radius; a test on the computed ρ would let a radius product
    // that underflowed to 0 pass)
    let nil = |x: Mr| x.mid() == 0.0 && x.rad() == 0.0;
    let (mut rows_s, mut rows_h) = ([0.0f64; R], Vec::new());
    let rows = zeroed(&mut rows_s, &mut rows_h, 6 * m1);
    for (i, x) in q.chunks_exact(2).take(m1).enumerate() {
        rows[i] = x[0].mid();
        rows[m1 + i] = x[1].mid();
        rows[2 * m1 + i] = x[0].rad();
        rows[3 * m1 + i] = x[1].rad();
        // (as all-ones / all-zero bit masks)
        rows[4 * m1 + i] = f64::from_bits(if nil(x[0]) { u64::MAX } else { 0 });
        rows[5 * m1 + i] = f64::from_bits(if nil(x[1]) { u64::MAX } else { 0 });
    }
    let row = |r: usize| &rows[r * m1..(r + 1) * m1];
    let pts = PairRows {
        a: row(0),
        w: row(1),
        ra: row(2),
        rw: row(3),
        an: row(4),
        wn: row(5),
    };
    // per k: the centre d, the radius terms, sum |P| S, the η count, the number of terms m
    let (mut acc_s, mut acc_h) = ([0.0f64; A], Vec::new());
    let acc = zeroed(&mut acc_s, &mut acc_h, 5 * n);
    for i in 0..p {
        let len = p - i;
        let pcs = &pair[i * m1 + i + 1..i * m1 + i + 1 + len];
        let mut x = 0;
        #[cfg(all(target_arch = "x86_64", target_feature = "avx2"))]
        while x + 4 <= len {
            // SAFETY: AVX2 is enabled at compile time (the cfg above); the indices of the four
            // terms, l = i + 1 + x..+4 <= p and k = 2i + x..+4 <= i + p - 1 < n, are inside
            // `pts`, `pcs` and every row of `acc` (checked by the slices inside).
            unsafe { pair_terms4(&pts, i, x, &pcs[x..x + 4], acc, n) };
            x += 4;
        }
        while x < len {
            let t = pair_term(&pts, i, i + 1 + x, pcs[x]);
            let k = 2 * i + x;
            for (r, v) in t.into_iter().enumerate() {
                acc[r * n + k] += v;
            }
            x += 1;
        }
    }
    out.extend((0..n).map(|k| {
        let (d, r, g, h, m) = (acc[k], acc[n + k], acc[2 * n + k], acc[3 * n + k], acc[4 * n + k]);
        let m_terms = (m - 1.0).max(0.0);
        // (h 2^-1074 by `eta_multiple`, without a product that underflows: an upper bound
        // of h η' where η' = 2^-1074 >= η is the bound's own unit)
        let e = (r + (3.03 + 1.03 * m_terms) * C * g + eta_multiple(h)) * (1.0 + 1.0 / 1_099_511_627_776.0);
        Mr::from_centre_radius(d, e)
    }));
}

/// `len` zeros: the front of the zeroed array `stack` where it is long enough, else `heap`
/// resized.
fn zeroed<'a, const N: usize>(stack: &'a mut [f64; N], heap: &'a mut Vec<f64>, len: usize) -> &'a mut [f64] {
    if len <= N {
        &mut stack[..len]
    } else {
        heap.resize(len, 0.0);
        heap
    }
}

/// `len` values `f(0), f(1), ..`: the front of `stack` where it is long enough, else `heap`.
fn filled<'a, T: Copy, const N: usize>(
    stack: &'a mut [T; N],
    heap: &'a mut Vec<T>,
    len: usize,
    f: impl Fn(usize) -> T,
) -> &'a mut [T] {
    if len <= N {
        for (i, x) in stack[..len].iter_mut().enumerate() {
            *x = f(i);
        }
        &mut stack[..len]
    } else {
        heap.extend((0..len).map(f));
        heap
    }
}

/// The rows of the points for [`pair_sum_f64`]: centres and radii of the a_i and w_i, and
/// exact-zero flags as all-ones bit masks.
struct PairRows<'a> {
    a: &'a [f64],
    w: &'a [f64],
    ra: &'a [f64],
    rw: &'a [f64],
    an: &'a [f64],
    wn: &'a [f64],
}

/// The five summands of the pair (i, l) in [`pair_sum_f64`] with the coefficient `pc`: its
/// centre term pc (a_l w_i - a_i w_l), and unless a factor of each product is an exact zero
/// (then +0.0 each, which leaves the nonnegative sums as they are) its radius terms, pa S, its
/// η share and its count.
#[inline(always)]
fn pair_term(pts: &PairRows, i: usize, l: usize, pc: Mr) -> [f64; 5] {
    let (a_l, w_i, a_i, w_l) = (pts.a[l], pts.w[i], pts.a[i], pts.w[l]);
    let (ra_l, rw_i, ra_i, rw_l) = (pts.ra[l], pts.rw[i], pts.ra[i], pts.rw[l]);
    let x1 = a_l * w_i;
    let x2 = a_i * w_l;
    let v = pc.mid() * (x1 - x2);
    let rho1 = a_l.abs() * rw_i + w_i.abs() * ra_l + ra_l * rw_i;
    let rho2 = a_i.abs() * rw_l + w_l.abs() * ra_i + ra_i * rw_l;
    let flag = |x: f64| x.to_bits() != 0;
    let zero = (flag(pts.an[l]) || flag(pts.wn[i])) && (flag(pts.an[i]) || flag(pts.wn[l]));
    let (pa, pr) = (pc.mid().abs(), pc.rad());
    let sum = x1.abs() + x2.abs();
    if zero {
        return [v, 0.0, 0.0, 0.0, 0.0];
    }
    [
        v,
        pr * (1.01 * sum + rho1 + rho2) + pa * (rho1 + rho2),
        pa * sum,
        10.0 * (pr + pa) + 17.0,
        1.0,
    ]
}

/// [`pair_term`] for l = i + 1 + x .. i + 1 + x + 4 in the four lanes of AVX2 registers, each
/// added to its sum k = 2i + x + lane (row r of `acc` at r n + k): per lane the same IEEE
/// operations in the same order (products and sums unfused), the exact-zero case by a bit
/// mask (+0.0), so bit for bit the scalar results (`pair_sum_lanes_are_scalar_terms`).
#[cfg(all(target_arch = "x86_64", target_feature = "avx2"))]
#[inline(always)]
unsafe fn pair_terms4(pts: &PairRows, i: usize, x: usize, pcs: &[Mr], acc: &mut [f64], n: usize) {
    use std::arch::x86_64::*;
    let l = i + 1 + x;
    let k = 2 * i + x;
    // (bounds checked once: four values of each row)
    let (a_l, w_l, ra_l, rw_l) = (&pts.a[l..l + 4], &pts.w[l..l + 4], &pts.ra[l..l + 4], &pts.rw[l..l + 4]);
    let (an_l, wn_l) = (&pts.an[l..l + 4], &pts.wn[l..l + 4]);
    let pcs = &pcs[..4];
    let rows = &mut acc[..5 * n];
    let _ = &rows[4 * n + k..4 * n + k + 4];
    // SAFETY: AVX2 is enabled at compile time (the caller's cfg); loads and stores of four
    // f64 from slices of at least four elements (checked above), register arithmetic.
    unsafe {
        let ld = |s: &[f64]| _mm256_loadu_pd(s.as_ptr());
        let set1 = _mm256_set1_pd;
        let sign = set1(-0.0);
        let abs = |x: __m256d| _mm256_andnot_pd(sign, x);
        let (a_l, w_l, ra_l, rw_l) = (ld(a_l), ld(w_l), ld(ra_l), ld(rw_l));
        let (w_i, a_i, rw_i, ra_i) = (set1(pts.w[i]), set1(pts.a[i]), set1(pts.rw[i]), set1(pts.ra[i]));
        let pcm = _mm256_set_pd(pcs[3].mid(), pcs[2].mid(), pcs[1].mid(), pcs[0].mid());
        let pr = _mm256_set_pd(pcs[3].rad(), pcs[2].rad(), pcs[1].rad(), pcs[0].rad());
        let x1 = _mm256_mul_pd(a_l, w_i);
        let x2 = _mm256_mul_pd(a_i, w_l);
        let v = _mm256_mul_pd(pcm, _mm256_sub_pd(x1, x2));
        let rho1 = _mm256_add_pd(
            _mm256_add_pd(_mm256_mul_pd(abs(a_l), rw_i), _mm256_mul_pd(abs(w_i), ra_l)),
            _mm256_mul_pd(ra_l, rw_i),
        );
        let rho2 = _mm256_add_pd(
            _mm256_add_pd(_mm256_mul_pd(abs(a_i), rw_l), _mm256_mul_pd(abs(w_l), ra_i)),
            _mm256_mul_pd(ra_i, rw_l),
        );
        // zero = (an_l | wn_i) & (an_i | wn_l), as all-ones masks
        let zero = _mm256_and_pd(
            _mm256_or_pd(ld(an_l), set1(pts.wn[i])),
            _mm256_or_pd(set1(pts.an[i]), ld(wn_l)),
        );
        let keep = |t: __m256d| _mm256_andnot_pd(zero, t);
        let pa = abs(pcm);
        let sum = _mm256_add_pd(abs(x1), abs(x2));
        let rr = _mm256_add_pd(rho1, rho2);
        let r = _mm256_add_pd(
            _mm256_mul_pd(pr, _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(set1(1.01), sum), rho1), rho2)),
            _mm256_mul_pd(pa, rr),
        );
        let g = _mm256_mul_pd(pa, sum);
        let h = _mm256_add_pd(_mm256_mul_pd(set1(10.0), _mm256_add_pd(pr, pa)), set1(17.0));
        let terms = [v, keep(r), keep(g), keep(h), keep(set1(1.0))];
        for (r, t) in terms.into_iter().enumerate() {
            let p = rows.as_mut_ptr().add(r * n + k);
            _mm256_storeu_pd(p, _mm256_add_pd(_mm256_loadu_pd(p), t));
        }
    }
}

/// The degree up to which [`f_from_ddi`] computes F in double-double: its integer factors
/// (l - i) C(p, i) C(p, l) and C(2p - 2, m) stay below 2^53, exact in f64.
const F_DDI_MAX_DEGREE: usize = 20;

/// F's Bernstein coefficients (see [`SpanPoly`]) from the shifted segment `dseg` in [`Ddi`],
/// each rounded outward to an `Mr` ([`Mr::from_ddi`]): the rational pair sums
/// F_m = sum_{i<l, i+l-1=m} (l - i) C(p,i) C(p,l) / C(2p-2,m) (a_l w_i - a_i w_l) (the same
/// formula as [`pair_sum_f64`]; Farin, sec. 13), the polynomial differences a_{i+1} - a_i.
/// Every `Ddi` operation encloses its exact result, so each coefficient encloses the exact
/// one. `None` above [`F_DDI_MAX_DEGREE`].
fn f_from_ddi(dseg: &BezierSeg<Ddi>) -> Option<Vec<Mr>> {
    let p = dseg.degree;
    if p > F_DDI_MAX_DEGREE || p == 0 {
        return None;
    }
    let q = &dseg.pts;
    if !dseg.rational {
        return Some(q.windows(2).map(|w| Mr::from_ddi(w[1] - w[0])).collect());
    }
    // C(n, k) exactly (n <= 2 F_DDI_MAX_DEGREE - 2: below 2^53)
    let binom = |n: usize, k: usize| crate::num::binom_exact(n, k);
    let mut acc = vec![Ddi::exact(0.0); 2 * p - 1];
    for i in 0..p {
        let (ai, wi) = (q[2 * i], q[2 * i + 1]);
        for l in i + 1..=p {
            let (al, wl) = (q[2 * l], q[2 * l + 1]);
            // (l - i) C(p, i) C(p, l) <= 20 * C(20, 10)^2 < 2^53: exact
            let num = Ddi::exact((l - i) as f64 * binom(p, i)? * binom(p, l)?);
            let den = Ddi::exact(binom(2 * p - 2, i + l - 1)?);
            let d = al * wi - ai * wl;
            acc[i + l - 1] = acc[i + l - 1] + num * d / den;
        }
    }
    Some(acc.into_iter().map(Mr::from_ddi).collect())
}

/// The Cartesian points (x_i - c) of homogeneous one-coordinate points.
fn cartesian<S: Scalar>(q: Vec<S>, rational: bool) -> Vec<S> {
    // one coordinate row (and the weight row): the shared kernel with dim = 1
    crate::spline::bezier::cartesian(q, 1, rational)
}

/// The degree up to which [`restrict_hull_f64`] restricts (its error bound assumes
/// 11 n u < 2^-40; above it the caller restricts in `Mr`).
const F64_RESTRICT_MAX: usize = 255;

/// An enclosure of the range over [t0, t1] (0 <= t0 < t1 <= 1) of every polynomial whose
/// Bernstein coefficients (degree n = `co.len() - 1`) lie in the `Mr` enclosures `co`: the
/// hull of the coefficients restricted to the box by de Casteljau (NURBS Book A1.5) in plain
/// f64 on the midpoints, widened by an a-priori error bound; about a tenth of the cost of the
/// same splits in `Mr` (one rounding per operation, no radius to carry). `None` for degrees
/// above [`F64_RESTRICT_MAX`] (the caller then restricts in `Mr`).
///
/// The splits. Left part at t1 (unless t1 = 1): coefficients b_0^r, r = 0..=n, of the
/// triangle; it is P(t1 τ), τ in [0, 1]. Right part of that at s = max(0, next_down(fl(t0 /
/// t1))) (unless t0 = 0): coefficients b_{n-r}^r; it is P over [s t1, t1]. Round to nearest
/// errs by at most half an ulp, so next_down gives s <= t0 / t1 (also for a power of two,
/// where the ulp below is half the one above): [s t1, t1] contains [t0, t1], and the convex
/// hull property (Bernstein polynomials >= 0, summing to 1) gives the range over [t0, t1]
/// within the hull of the exact restricted coefficients.
///
/// Error bound (u = 2^-53, η = 2^-1075 the underflow error of a product). With exact
/// coefficients β_i, midpoints m_i (|β_i - m_i| <= R = max radius) and M = max |m_i|: the
/// restriction is linear with nonnegative weights summing to 1 per coefficient, so restricting
/// β instead of m moves each coefficient by at most R. A de Casteljau step of the f64 kernel
/// computes fl(fl(t fl(hi - lo)) + lo) (`Scalar::lerp` for f64; t in [0, 1] exact): with d =
/// hi - lo, |d| <= 2 M̄ (M̄ bounds every computed value), its error against lo + t d is at
/// most |t d δ1| + |t fl(d) δ2| + η + |lo + fl(t fl(d))| δ3 <= 5.01 u M̄ + 1.01 η, and the
/// errors of the inputs pass on through a convex combination without growing. So after the
/// two splits (2n levels) every coefficient is within 10.02 n u M̄ + 2.02 n η of the exact
/// restriction of m; for n <= 255, M̄ <= M (1 + 11 n u) + 3 n η (11 n u < 2^-40), hence
/// within 12 n u M + n 2^-1073. The result widens the f64 hull by
/// E = up(2^-49 n M + n 2^-1073 + R) >= 16 n u M + n 2^-1073 + R (Lemma B of
/// [`crate::num::ddi`]: a product, an f64 and an f64; 2^-49 n and n 2^-1073 are exact), in
/// outward-rounded interval arithmetic (returned with E). A non-finite value anywhere gives
/// ENTIRE. Tested against exact rational restrictions (`f64_restriction_bound_holds_exactly`).
///
/// The third value says whether the f64 coefficients straddle 0 by more than E (lowest < -E,
/// highest > E): then so do the exact restricted coefficients, and no enclosure built from
/// coefficients over the box (such as the `Mr` restriction) can exclude 0 either.
fn restrict_hull_f64(co: &[Mr], t0: f64, t1: f64) -> Option<(Interval, f64, bool)> {
    if !(0.0 <= t0 && t0 < t1 && t1 <= 1.0) {
        return None;
    }
    restricted_f64::<1, _>(co, t0, t1, |b, e| {
        let e = e[0];
        let (lo, hi) = b.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| {
            (lo.min(x), hi.max(x))
        });
        (widened(lo, hi, e), e, lo < -e && hi > e)
    })
}

/// The value at t in [0, 1] of every polynomial whose Bernstein coefficients lie in the `Mr`
/// enclosures `co`, with an a-priori bound E (returned with the enclosure): up to degree
/// [`VS_MAX`] by the O(n) scheme of [`value_vs_f64`] (its own bound, about half this one);
/// above, de Casteljau's algorithm (NURBS Book A1.5) in plain f64 on the midpoints,
/// widened by the same a-priori bound E as [`restrict_hull_f64`] (returned with E); `None` as
/// there. The value is the last coefficient of the left part at t, i.e. the first split of
/// [`restrict_in_place`] with t0 = 0 (n levels, where the bound's proof allows 2n); about a
/// tenth of the cost of the same evaluation in `Mr`. (At t = 1 there is no split: the value is
/// the last coefficient, exact up to its radius.)
fn value_f64(co: &[Mr], t: f64) -> Option<(Interval, f64)> {
    if !(0.0..=1.0).contains(&t) {
        return None;
    }
    if co.len() <= VS_MAX + 1 {
        return value_vs_f64(co, t);
    }
    restricted_f64::<1, _>(co, 0.0, t, |b, e| {
        let v = b[b.len() - 1];
        (widened(v, v, e[0]), e[0])
    })
}

/// The degree up to which [`value_f64`] evaluates by [`value_vs_f64`] (every binomial
/// coefficient C(n, j) below 2^127: exact in u128, rounded to f64 once).
const VS_MAX: usize = 127;

/// C(n, j) for n <= [`VS_MAX`], rounded to nearest f64 (exact below 2^53), by Pascal's rule in
/// u128 at compile time.
static BINOMIALS: [[f64; VS_MAX + 1]; VS_MAX + 1] = {
    let mut u = [[0u128; VS_MAX + 1]; VS_MAX + 1];
    let mut f = [[0.0f64; VS_MAX + 1]; VS_MAX + 1];
    let mut n = 0;
    while n <= VS_MAX {
        let mut j = 0;
        while j <= n {
            u[n][j] = if j == 0 || j == n { 1 } else { u[n - 1][j - 1] + u[n - 1][j] };
            f[n][j] = u[n][j] as f64;
            j += 1;
        }
        n += 1;
    }
    f
};

/// [`value_f64`] in O(n) instead of de Casteljau's O(n^2): the value at t in [0, 1] of every
/// polynomial whose Bernstein coefficients (degree n <= [`VS_MAX`]) lie in the `Mr` enclosures
/// `co`, with an a-priori bound E (returned with the enclosure). The Volk–Schumaker scheme
/// without division (a Horner scheme in s = 1 - t that carries the powers of x = t):
/// acc_0 = b_0, acc_j = acc_{j-1} s + (C(n, j) x^j) b_j (one FMA), so acc_n = sum_j b_j C(n, j) x^j
/// s^(n-j) = B(t), on the midpoints b_j. For t > 1/2 it runs mirrored (coefficients reversed,
/// x = 1 - t, exact by Sterbenz's lemma, s = t), so that |acc_j| stays below 2^n M.
///
/// Error bound (u = 2^-53, η = 2^-1075, M = max |b_j|, R = max radius). Each f64 operation
/// errs by at most u |result| (+ η for a product); the f64 C(n, j) is within u C(n, j) of the
/// integer (exact below 2^53). Without underflow the computed value is
/// sum_j b_j C(n, j) x^j s^(n-j) (1 + θ_j), where term j meets the rounding of its binomial, j
/// products for x^j, two for its coefficient, its addition, and per later step the rounding of
/// s (if t <= 1/2, s = fl(1 - t)), of the product and of the sum (an FMA rounds product and
/// sum once, one rounding fewer than counted here): at most 3n + 4 roundings,
/// |θ_j| <= γ_{3n+4} <= 1.01 (3n + 4) u. The exact weights C(n, j) x^j (1 - x)^(n-j) are
/// nonnegative and sum to 1, so the error is at most 1.01 (3n + 4) u M. Underflow adds at most
/// j η to x^j, times C(n, j) (1 + u) and |b_j| <= M, and η per later product: in all below
/// 1.01 sum_j (j + 1) C(n, j) η M + (3n + 3) η, at most 1.01 (n + 1) 2^n η M + (3n + 3) η,
/// so at most 2^-940 M + (3n + 3) η for n <= 127. The midpoints are within R of the exact coefficients,
/// and the weights sum to 1: + R. So E = up(((4n + 6) 2^-52 + 2^-900) M + n 2^-1070 + R),
/// at least (8n + 12) u M + 2^-900 M + 32 n η + R, covers both with the cross terms (Lemma B of
/// [`crate::num::ddi`]: a product of a sum and an f64, a product and an f64; (4n + 6) 2^-52
/// and n 2^-1070 are exact); for n = 0 the value is b_0 itself. (|acc_j| <= 2^n M: an
/// overflow gives a non-finite value.) A non-finite value or bound gives ENTIRE. Tested against exact
/// rational evaluation (`vs_value_bound_holds_exactly`).
pub(crate) fn value_vs_f64(co: &[Mr], t: f64) -> Option<(Interval, f64)> {
    vs_row(co, 1, 0, t)
}

/// [`value_vs_f64`] on row `row` of `h` interleaved rows (coefficient j at `co[j h + row]`).
fn vs_row(co: &[Mr], h: usize, row: usize, t: f64) -> Option<(Interval, f64)> {
    vs_scheme::<false>(co, h, row, t)
}

/// The VS scheme of [`value_vs_f64`] on row `row` of `h` interleaved rows, with the plain
/// bound (largest coefficient and radius) or, for `WEIGHTED`, the bound weighted by the basis
/// at t ([`value_vs_f64_weighted`]: a second accumulator with the same weights and roundings);
/// one loop for both, compiled without the second accumulator where it is not asked for.
fn vs_scheme<const WEIGHTED: bool>(
    co: &[Mr],
    h: usize,
    row: usize,
    t: f64,
) -> Option<(Interval, f64)> {
    let n = (co.len() / h).checked_sub(1)?;
    if n > VS_MAX || !(0.0..=1.0).contains(&t) || co.len() % h != 0 {
        return None;
    }
    let rev = t > 0.5;
    // (1 - t is exact for t in [1/2, 1]: Sterbenz)
    let (x, s) = if rev { (1.0 - t, t) } else { (t, 1.0 - t) };
    let binom = &BINOMIALS[n];
    let (first, step) = if rev {
        (n * h + row, -(h as isize))
    } else {
        (row, h as isize)
    };
    let nf = n as f64;
    // (the weighted bound's a_j = r_j + (8n + 12) u |b_j|)
    let kappa = (4.0 * nf + 6.0) * f64::EPSILON;
    let weight = |c: Mr| c.rad() + kappa * c.mid().abs();
    let c0 = co[first];
    let (mut m, mut r) = (c0.mid().abs(), c0.rad());
    let (mut acc, mut xp) = (c0.mid(), 1.0f64);
    let mut accw = if WEIGHTED { weight(c0) } else { 0.0 };
    let mut ma = accw;
    let mut i = first as isize;
    for &bj in &binom[1..=n] {
        i += step;
        let c = co[i as usize];
        let b = c.mid();
        m = m.max(b.abs());
        r = r.max(c.rad());
        xp *= x;
        let w = bj * xp;
        acc = acc.mul_add(s, w * b);
        if WEIGHTED {
            let a = weight(c);
            ma = ma.max(a);
            accw = accw.mul_add(s, w * a);
        }
    }
    let e = if WEIGHTED {
        up(accw + accw * P2_M40 + P2_M900 * (ma + m) + f64::from_bits(16 * (n as u64 + 1)))
    } else {
        up(((4.0 * nf + 6.0) * f64::EPSILON + P2_M900) * m + f64::from_bits(16 * n as u64) + r)
    };
    Some((widened(acc, acc, e), e))
}

/// [`value_vs_f64`] with its bound weighted by the basis at t instead of taken from the
/// largest coefficient and radius: where F's coefficients near t are tiny against those far
/// away (a zero of F close to an end of the span, next to coefficients a million times larger
/// at the other end), the plain bound swamps a value that this one still decides. About
/// twice the plain evaluation; used only where the plain one cannot prove a sign
/// ([`SpanPoly::f_has_sign`]).
///
/// Error bound. With the notation of [`value_vs_f64`] (W_j = C(n, j) x^j (1 - x)^(n-j) >= 0,
/// summing to 1; γ = γ_{3n+4}; M the largest |b_j|), the computed value ŷ satisfies
/// |ŷ - sum_j β_j W_j| <= sum_j r_j W_j + γ sum_j |b_j| W_j + U_y for the exact coefficients
/// β_j (|β_j - b_j| <= r_j), with U_y <= 2^-940 M + (3n + 3) η the underflow part. Both sums are
/// at most A = sum_j a_j W_j with a_j = r_j + κ |b_j|, κ = (8n + 12) u >= γ. The scheme runs a
/// second accumulator on â_j = fl(r_j + fl(κ |b_j|)) >= (1 - u)^2 a_j - η, with the same
/// weights and roundings as the value's; its terms are nonnegative, so it is
/// Â >= (1 - γ) sum_j â_j W_j - U_a (U_a <= 2^-940 max â_j + (3n + 3) η, as U_y). Hence
/// A <= (Â + U_a + η) / ((1 - γ)(1 - u)^2) <= (Â + U_a + η)(1 + 2^-40) (γ < 2^-43 for n <= 127),
/// and the error is at most E = up(Â + 2^-40 Â + 2^-900 (max â_j + M) + 16 (n + 1) η):
/// (1 + 2^-40) 2^-940 <= 2^-900, (1 + 2^-40)(3n + 4) η + (3n + 3) η <= 16 (n + 1) η, and
/// Lemma B of [`crate::num::ddi`] for the final sum (products of f64 with f64 or with a sum).
/// A non-finite value or bound gives ENTIRE. Tested against exact rational evaluation
/// (`weighted_vs_value_bound_holds_exactly`).
fn value_vs_f64_weighted(co: &[Mr], t: f64) -> Option<(Interval, f64)> {
    vs_scheme::<true>(co, 1, 0, t)
}

/// 2^-40 (exact).
const P2_M40: f64 = f64::from_bits((1023 - 40) << 52);

/// 2^-900 and 2^-106 (exact; constants rather than `powi`, a library call with a loop).
const P2_M900: f64 = f64::from_bits((1023 - 900) << 52);
const P2_M106: f64 = f64::from_bits((1023 - 106) << 52);

/// The degree up to which [`value_vs_dw`] runs (every binomial coefficient exact in f64).
pub(crate) const VS_DW_MAX: usize = 56;

/// The values at t in [0, 1] of the polynomials whose Bernstein coefficients (degree
/// n <= [`VS_DW_MAX`]) lie in the `Ddi` enclosures of the first R of `h` interleaved rows of
/// `co` (coefficient j of row i at `co[j h + i]`), in plain double-word arithmetic ([`Dw`]: no bound
/// carried per operation) with one a-priori bound: the scheme of [`value_vs_f64`] (Horner in
/// s = 1 - t carrying the powers of x = t, mirrored for t > 1/2), a few times cheaper than
/// the same scheme in `Ddi` ([`bernstein_value_s`], a running bound per operation), for the
/// point values of [`SpanPoly::tight_over`]. `None` above [`VS_DW_MAX`] or for t outside
/// [0, 1]; ENTIRE where something is not finite.
///
/// Error bound (u = 2^-53, η = 2^-1075, M = max |hi_j| of the coefficients' centres
/// hi_j + lo_j, R = max radius). The centres are taken as normalised double words (TwoSum,
/// exact), |hi_j + lo_j| <= (1 + u) |hi_j|. x and s are exact (x = t or 1 - t, exact by
/// Sterbenz's lemma for t >= 1/2; s = 1 - t as the double word TwoSum(1, -t), or t), and
/// x + s = 1 exactly; the binomials are exact (n <= 56). The double-word operations of
/// [`crate::num::dw`] err by at most 7.1 u^2 |a| |b| + 5 η (product) and 3.02 u^2 (|a| + |b|)
/// (sum), so (as in [`value_vs_f64`]) without underflow the computed value is
/// sum_j b_j C(n, j) x^j s^(n-j) (1 + θ_j) with term j meeting j products for x^j, two for
/// its coefficient and per later step one product and one sum: |θ_j| <= (1 + 2^-90)
/// (7.1 (n + 2) + 3.02 n) u^2 <= (10.2 n + 14.3) u^2. The weights C(n, j) x^j s^(n-j) are
/// nonnegative and sum to 1, so the error is at most (10.2 n + 14.3) u^2 (1 + u) M
/// <= (12 n + 16) 2^-106 M. Underflow: each of the at most 3n products adds at most 5 η, which
/// the later factors (C(n, j) |b_j| <= 2^n (1 + u) M at most) amplify: below
/// 5 (3n) 2^n 1.01 M η + 15 n η <= 2^-900 M + n 2^-1070 for n <= 56. The centres are within R
/// of the exact coefficients: + R. So E = up(((12 n + 16) 2^-106 + 2^-900) M + n 2^-1070 + R)
/// (Lemma B of [`crate::num::ddi`]; (12 n + 16) 2^-106 and n 2^-1070 are exact), and the
/// result is the `Ddi` with the computed centre and radius E. (|partial sums| <= 2^n M: no
/// overflow below 2^1000 M.) Tested against exact rational evaluation
/// (`vs_dw_value_bound_holds_exactly`).
#[inline(always)]
pub(crate) fn value_vs_dw<const R: usize>(co: &[Ddi], h: usize, t: f64) -> Option<[Ddi; R]> {
    use crate::num::dw::Dw;
    let n = (co.len() / h).checked_sub(1)?;
    if n > VS_DW_MAX || !(0.0..=1.0).contains(&t) || co.len() % h != 0 || R > h {
        return None;
    }
    let rev = t > 0.5;
    // (x + s = 1 exactly: 1 - t is exact for t in [1/2, 1] (Sterbenz), and a double word
    // (TwoSum) below)
    let (x, s) = if rev {
        (Dw::from_parts(1.0 - t, 0.0), Dw::from_parts(t, 0.0))
    } else {
        (Dw::from_parts(t, 0.0), Dw::from_parts(1.0, -t))
    };
    let binom = &BINOMIALS[n];
    let at = |j: usize| if rev { (n - j) * h } else { j * h };
    // (the R rows side by side: independent chains, whose latencies overlap)
    let (mut m, mut r) = ([0.0f64; R], [0.0f64; R]);
    let mut acc = [Dw::from_parts(0.0, 0.0); R];
    for row in 0..R {
        let (hi, lo, rad) = co[at(0) + row].parts();
        (m[row], r[row]) = (hi.abs(), rad);
        acc[row] = Dw::from_parts(hi, lo);
    }
    let mut xp = Dw::from_parts(1.0, 0.0);
    for (j, &bj) in binom.iter().enumerate().take(n + 1).skip(1) {
        xp = xp * x;
        let w = Dw::from_parts(bj, 0.0) * xp;
        for row in 0..R {
            let (hi, lo, rad) = co[at(j) + row].parts();
            m[row] = m[row].max(hi.abs());
            r[row] = r[row].max(rad);
            acc[row] = acc[row] * s + w * Dw::from_parts(hi, lo);
        }
    }
    let nf = n as f64;
    Some(std::array::from_fn(|row| {
        let e = up(((12.0 * nf + 16.0) * P2_M106 + P2_M900) * m[row]
            + f64::from_bits(16 * n as u64)
            + r[row]);
        let (vh, vl) = acc[row].parts();
        Ddi::from_parts(vh, vl, e)
    }))
}

/// [lo - e, hi + e] rounded outward (ENTIRE for non-finite ends or bound): each end in round
/// to nearest, which errs by at most half an ulp (an overflow goes to ±inf, beyond f64::MAX on
/// its side), then stepped one ulp outward (without inari's addition, which switches the
/// rounding mode per operation; this runs for every f64 value and restriction).
fn widened(lo: f64, hi: f64, e: f64) -> Interval {
    if !(lo.is_finite() && hi.is_finite() && e.is_finite()) {
        return Interval::ENTIRE;
    }
    iv::span((lo - e).next_down(), (hi + e).next_up())
}

/// The common body of [`restrict_hull_f64`], [`value_f64`] and [`segment_values_f64`]: the
/// midpoints of the coefficients `co` (`h` interleaved rows, each a polynomial of degree n)
/// restricted to [t0, t1] ([`restrict_in_place`]) and per row the bound E of
/// [`restrict_hull_f64`] (from that row's largest midpoint and radius: the rows are
/// independent polynomials split at the same parameters) handed to `done` (E = inf for
/// non-finite data); `None` for no coefficient or a degree above [`F64_RESTRICT_MAX`].
fn restricted_f64<const H: usize, R>(
    co: &[Mr],
    t0: f64,
    t1: f64,
    done: impl FnOnce(&[f64], &[f64; H]) -> R,
) -> Option<R> {
    let n = (co.len() / H).checked_sub(1)?;
    if n > F64_RESTRICT_MAX || co.len() % H != 0 {
        return None;
    }
    // (stack buffers for the usual degrees, heap ones above)
    const STACK: usize = 64;
    let len = co.len();
    let (mut sb, mut so) = ([0.0f64; STACK], [0.0f64; STACK]);
    let (mut hb, mut ho) = (Vec::new(), Vec::new());
    let (b, out) = if len <= STACK {
        (&mut sb[..len], &mut so[..len])
    } else {
        hb.resize(len, 0.0);
        ho.resize(len, 0.0);
        (&mut hb[..], &mut ho[..])
    };
    // per row the largest |midpoint| and radius
    let (mut m, mut r) = ([0.0f64; H], [0.0f64; H]);
    for (i, (x, c)) in b.iter_mut().zip(co).enumerate() {
        *x = c.mid();
        m[i % H] = m[i % H].max(x.abs());
        r[i % H] = r[i % H].max(c.rad());
    }
    if !m.iter().chain(&r).all(|v| v.is_finite()) {
        return Some(done(b, &[f64::INFINITY; H]));
    }
    restrict_in_place::<f64, H>(b, out, t0, t1);
    // (midpoints near f64::MAX of opposite signs overflow a difference hi - lo: an infinite
    // or NaN coefficient voids the bound, whose proof assumes every computed value finite,
    // and a NaN would be skipped by the min / max of a hull: E = inf, so ENTIRE)
    if !b.iter().all(|x| x.is_finite()) {
        return Some(done(b, &[f64::INFINITY; H]));
    }
    let nf = n as f64;
    let e = std::array::from_fn(|row| {
        up(nf * (1.0 / 562_949_953_421_312.0) * m[row] + f64::from_bits(2 * n as u64) + r[row])
    });
    Some(done(b, &e))
}

/// The splits of [`restrict_hull_f64`] in place on the coefficients `b` (`h` interleaved rows;
/// `out`: a buffer of the same length): left part at t1 (unless t1 = 1), then its right part
/// at s = max(0, next_down(fl(t0 / t1))) (unless t0 = 0), so that `b` ends as the
/// coefficients over [s t1, t1], which contains [t0, t1]. Generic so that the test runs the
/// same splits in exact arithmetic.
fn restrict_in_place<S: Scalar, const H: usize>(b: &mut [S], out: &mut [S], t0: f64, t1: f64) {
    let (h, n) = (H, b.len() / H - 1);
    if t1 < 1.0 {
        out[..h].clone_from_slice(&b[..h]);
        de_casteljau_levels(b, h, &S::from_f64(t1), |lv, b| {
            out[lv * h..(lv + 1) * h].clone_from_slice(&b[..h])
        });
        b.clone_from_slice(out);
    }
    if t0 > 0.0 {
        let s = (t0 / t1).next_down().max(0.0);
        out[n * h..].clone_from_slice(&b[n * h..]);
        de_casteljau_levels(b, h, &S::from_f64(s), |lv, b| {
            let k = (n - lv) * h;
            out[k..k + h].clone_from_slice(&b[k..k + h])
        });
        b.clone_from_slice(out);
    }
}

/// Interval hull of enclosures (ENTIRE if any is unbounded).
fn hull<S: Scalar>(v: &[S]) -> Interval {
    v.iter()
        .fold(Interval::EMPTY, |h, x| h.convex_hull(x.to_interval()))
}

/// The shift c of [`SpanPoly`]: the most frequent of the local control point coordinates
/// (the smallest such; the median when all differ). Any value is sound; this one makes flat
/// runs exact zeros.
fn span_shift(xs: &mut [f64]) -> f64 {
    xs.sort_by(f64::total_cmp);
    let (mut best, mut run) = (xs[xs.len() / 2], 1);
    let mut i = 0;
    while i < xs.len() {
        let e = i + xs[i..].iter().take_while(|&&x| x == xs[i]).count();
        if e - i > run {
            (best, run) = (xs[i], e - i);
        }
        i = e;
    }
    best
}

/// `pair[i (p + 1) + l]` = (l - i) C(p, i) C(p, l) / C(2p - 2, i + l - 1) for i < l (see
/// [`SpanPoly`]), enclosed: binomials as exact integers while below 2^53, beyond by Pascal's
/// rule in [`Mr`]. They depend on p only: computed once per degree and thread, then shared
/// (the p^2 / 2 enclosed quotients cost more than a span's Bernstein form at p = 10).
pub(crate) fn pair_coefficients(p: usize) -> std::rc::Rc<[Mr]> {
    thread_local! {
        static PAIRS: std::cell::RefCell<Vec<(usize, std::rc::Rc<[Mr]>)>> =
            const { std::cell::RefCell::new(Vec::new()) };
    }
    // (shared, not copied: (p + 1)^2 values, 10 kB at p = 24, per curve)
    PAIRS.with(|cache| {
        let mut cache = cache.borrow_mut();
        if let Some((_, v)) = cache.iter().find(|(q, _)| *q == p) {
            return v.clone();
        }
        let v: std::rc::Rc<[Mr]> = pair_coefficients_uncached(p).into();
        if cache.len() < 64 {
            cache.push((p, v.clone()));
        }
        v
    })
}

/// The pair coefficients from exact integers: the binomial rows by the multiplicative
/// recurrence C(n, k + 1) = C(n, k) (n - k) / (k + 1) in u128 (the division exact:
/// C(n, k) (n - k) = C(n, k + 1) (k + 1)), the numerators (l - i) C(p, i) C(p, l) exact too,
/// each quotient enclosed once ([`Mr::ratio`]: one correctly rounded division where both
/// integers are below 2^53) instead of a chain of `Mr` products and a quotient, each
/// rounded. `None` where a product would overflow u128.
fn pair_coefficients_exact(p: usize) -> Option<Vec<Mr>> {
    let row = |n: usize| -> Option<Vec<u128>> {
        let mut r = Vec::with_capacity(n + 1);
        let mut c: u128 = 1;
        for k in 0..=n {
            r.push(c);
            if k < n {
                c = c.checked_mul((n - k) as u128)? / (k as u128 + 1);
            }
        }
        Some(r)
    };
    let (bp, b2) = (row(p)?, row((2 * p).checked_sub(2)?)?);
    let mut pair = vec![Mr::from_f64(0.0); (p + 1) * (p + 1)];
    for i in 0..p {
        for l in i + 1..=p {
            let num = ((l - i) as u128).checked_mul(bp[i])?.checked_mul(bp[l])?;
            pair[i * (p + 1) + l] = Mr::ratio(num, b2[i + l - 1])?;
        }
    }
    Some(pair)
}

/// [`pair_coefficients`], computed: from exact integers where they fit in u128 (degrees up
/// to 63, [`pair_coefficients_exact`]), else with binomials in `Mr`.
fn pair_coefficients_uncached(p: usize) -> Vec<Mr> {
    pair_coefficients_exact(p).unwrap_or_else(|| pair_coefficients_fallback(p))
}

/// The pair coefficients with the binomials in `Mr`, for the degrees whose integers overflow
/// u128 (p >= 64): each binomial row by Pascal's rule on one row in place, from the right (the
/// same sums as row by row; exact while the values stay below 2^53, enclosed beyond).
fn pair_coefficients_fallback(p: usize) -> Vec<Mr> {
    let binom = |n: usize| {
        let mut row = vec![Mr::from_f64(1.0); n + 1];
        for m in 2..=n {
            for i in (1..m).rev() {
                row[i] = row[i - 1] + row[i];
            }
        }
        row
    };
    let (bp, b2) = (binom(p), binom(2 * p - 2));
    let mut pair = vec![Mr::from_f64(0.0); (p + 1) * (p + 1)];
    for i in 0..p {
        for l in i + 1..=p {
            pair[i * (p + 1) + l] = Mr::from_usize(l - i) * bp[i] * bp[l] / b2[i + l - 1];
        }
    }
    pair
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::bspline::HSpline;
    use crate::spline::eval::CurveEval;

    fn curve1(p: usize, knots: Vec<f64>, x: &[f64], w: Option<Vec<f64>>) -> NurbsCurve {
        NurbsCurve::new(p, knots, x.iter().map(|&v| vec![v]).collect(), w).unwrap()
    }

    /// The reference for [`shifted_from_points`]: the shifted piece's homogeneous Bézier
    /// segment by Boehm knot insertion of the shifted local control points ((x_i - c) w_i, w_i)
    /// or x_i - c in S ([`HSpline::bezier_segment`]), the route `SpanPoly` took before.
    fn shifted_segment<S: Scalar>(c: &NurbsCurve, j: usize, k: usize, shift: f64) -> BezierSeg<S> {
        let p = c.degree();
        let rational = c.is_rational();
        let cs = S::from_f64(shift);
        let mut pts = Vec::with_capacity((p + 1) * (1 + rational as usize));
        for i in k - p..=k {
            let x = S::from_f64(c.control_point(i)[j]) - cs.clone();
            if rational {
                let w = S::from_f64(c.weight(i));
                pts.push(x * w.clone());
                pts.push(w);
            } else {
                pts.push(x);
            }
        }
        let local = HSpline {
            degree: p,
            knots: c.knots()[k - p..=k + p + 1].to_vec(),
            dim: 1,
            rational,
            pts,
        };
        local.bezier_segment(p)
    }

    /// The cached pair coefficients enclose the exact rationals (l - i) C(p, i) C(p, l) /
    /// C(2p - 2, i + l - 1) for i < l, degrees 1..=40 and some up to 80: from exact u128
    /// integers while they fit (p <= 63), beyond by the binomials in `Mr`; both routes where
    /// both run, the exact one within four ulps of the quotient.
    #[test]
    fn pair_coefficients_enclose_the_exact_ratios() {
        use num_bigint::BigInt;
        use num_rational::BigRational;
        let binom = |n: usize, k: usize| -> BigInt {
            (0..k).fold(BigInt::from(1), |b, i| b * (n - i) / (i + 1))
        };
        let mut exact_route = 0;
        for p in (1..=40usize).chain([47, 55, 61, 62, 63, 64, 70, 80]) {
            let pair = pair_coefficients(p);
            assert_eq!(pair.len(), (p + 1) * (p + 1));
            let exact = pair_coefficients_exact(p);
            if let Some(ex) = &exact {
                exact_route += 1;
                assert_eq!(&ex[..], &pair[..], "p {p}: the cache holds the exact route's");
            }
            // every route that runs at this degree
            let fallback = pair_coefficients_fallback(p);
            let routes = exact.iter().chain(std::iter::once(&fallback));
            for (r, route) in routes.enumerate() {
                for i in 0..p {
                    for l in i + 1..=p {
                        let want = crate::num::Exact::from_ratio(BigRational::new(
                            BigInt::from(l - i) * binom(p, i) * binom(p, l),
                            binom(2 * p - 2, i + l - 1),
                        ));
                        let m = route[i * (p + 1) + l];
                        let (lo, hi) = m.bounds();
                        assert!(
                            want.cmp_f64(lo) != Some(std::cmp::Ordering::Less)
                                && want.cmp_f64(hi) != Some(std::cmp::Ordering::Greater),
                            "p {p}, route {r}, ({i}, {l}): [{lo}, {hi}]"
                        );
                        if r == 0 && exact.is_some() {
                            // one rounding (or three above 2^53): a few ulps of the quotient
                            assert!(m.rad() <= 4.01 * crate::num::ulp(m.mid()), "p {p} ({i}, {l})");
                        }
                    }
                }
            }
        }
        // the exact route up to p = 63, the fallback above (a product beyond u128)
        assert_eq!(exact_route, 40 + 5);
        assert!(pair_coefficients_exact(64).is_none() && pair_coefficients_exact(80).is_none());
    }

    /// The pair coefficients of `c` (empty without weights) and its non-empty spans.
    fn pair_and_spans(c: &NurbsCurve) -> (Vec<Mr>, Vec<usize>) {
        let p = c.degree();
        let pair = if c.is_rational() {
            pair_coefficients(p).to_vec()
        } else {
            Vec::new()
        };
        let kn = c.knots();
        let spans = (p..c.num_points()).filter(|&k| kn[k] < kn[k + 1]).collect();
        (pair, spans)
    }

    /// A random curve of degree 1..=10 and dimension 1..=3 ([`random_curve`]) with flat runs
    /// (some control values repeated), and its dimension.
    ///
    /// [`random_curve`]: crate::spline::tight::tests::random_curve
    fn curve_with_flat_runs(rng: &mut rand_chacha::ChaCha8Rng) -> (NurbsCurve, usize) {
        use rand::Rng;
        let dim = rng.random_range(1..=3usize);
        let c0 = crate::spline::tight::tests::random_curve(rng, dim);
        let mut pts: Vec<Vec<f64>> = (0..c0.num_points())
            .map(|i| c0.control_point(i).to_vec())
            .collect();
        for i in 1..pts.len() {
            if rng.random_bool(0.3) {
                let j = rng.random_range(0..dim);
                pts[i][j] = pts[i - 1][j];
            }
        }
        let w = c0
            .is_rational()
            .then(|| (0..c0.num_points()).map(|i| c0.weight(i)).collect());
        (NurbsCurve::new(c0.degree(), c0.knots().to_vec(), pts, w).unwrap(), dim)
    }

    /// The form's Bézier points from the span's shared double-double points enclose the same
    /// exact points as the shifted rows' own knot insertion (`shifted_segment`, in `Mr` and in
    /// `Ddi`): each of its `Mr` and `Ddi` points intersects the reference's, on random curves of
    /// degree 1..=10 (both extraction routes of `Ddi`) with flat runs. (F and F' are built
    /// from these points by the code checked in `span_poly_derivative_numerator_matches_f64`.)
    /// (Fails if a row, the weight index or the shift's sign is wrong.)
    #[test]
    fn shared_points_give_the_same_forms() {
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(21);
        let meet = |a: Interval, b: Interval| !a.intersection(b).is_empty();
        let mut checked = 0;
        for _ in 0..150 {
            let (c, dim) = curve_with_flat_runs(&mut rng);
            let (pair, spans) = pair_and_spans(&c);
            let tight = crate::spline::tight::TightEval::new(&c);
            for k in spans {
                for j in 0..dim {
                    let a = SpanPoly::new(&c, j, k, &pair, tight.bezier_points(k));
                    let mr = shifted_segment::<Mr>(&c, j, k, a.c);
                    let dd = shifted_segment::<Ddi>(&c, j, k, a.c);
                    assert_eq!(a.seg.pts.len(), mr.pts.len());
                    assert_eq!(a.dseg.pts.len(), dd.pts.len());
                    for (u, v) in a.seg.pts.iter().zip(&mr.pts) {
                        assert!(meet(u.to_interval(), v.to_interval()), "{c:?} k={k} j={j}");
                    }
                    for (u, v) in a.dseg.pts.iter().zip(&dd.pts) {
                        assert!(meet(u.to_interval(), v.to_interval()), "{c:?} k={k} j={j}");
                    }
                    checked += 1;
                }
            }
        }
        assert!(checked > 300, "{checked}");
    }

    /// The lean form ([`SpanProof`], `bezier`'s proof) is the full form's ([`SpanPoly`]) as far
    /// as that proof reads it: the same F bit for bit, the same bounds `dfmax` and `wmin`, the
    /// same critical boxes and the same tight enclosures and values over them, on random curves
    /// of degree 1..=10 with flat runs (both forms built from the span's shared double-double
    /// points). (Fails where the lean form computes F, a bound, or the shift otherwise.)
    #[test]
    fn lean_form_proves_as_the_full_form() {
        use rand::SeedableRng;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(23);
        let (mut checked, mut boxes) = (0, 0);
        for _ in 0..200 {
            let (c, dim) = curve_with_flat_runs(&mut rng);
            let (pair, spans) = pair_and_spans(&c);
            let tight = crate::spline::tight::TightEval::new(&c);
            let h = dim + c.is_rational() as usize;
            for k in spans {
                let q = tight.bezier_points(k);
                for j in 0..dim {
                    let full = SpanPoly::new(&c, j, k, &pair, q);
                    let lean = SpanProof::new(&c, j, k, &pair, |i| (q[i * h + j], q[i * h + h - 1]))
                        .expect("F is known");
                    let at = format!("{c:?} k={k} j={j}");
                    assert_eq!(full.f.pts, lean.f.pts, "{at}");
                    assert_eq!(full.c.to_bits(), lean.shift.to_bits(), "{at}");
                    assert_eq!(full.dfmax.to_bits(), lean.dfmax.to_bits(), "{at}");
                    assert_eq!(full.wmin.to_bits(), lean.wmin.to_bits(), "{at}");
                    let found = full.critical_boxes(1.0 / 1_099_511_627_776.0);
                    assert_eq!(found, lean.numerator().critical_boxes(1.0 / 1_099_511_627_776.0), "{at}");
                    for &(x0, x1) in found.iter().flatten() {
                        let (a, b) = (full.box_tight(x0, x1), lean.box_tight(x0, x1));
                        assert_eq!(a.is_some(), b.is_some(), "{at}");
                        if let (Some((ea, va)), Some((eb, vb))) = (a, b) {
                            assert_eq!((ea.inf(), ea.sup()), (eb.inf(), eb.sup()), "{at}");
                            assert_eq!(va.parts(), vb.parts(), "{at}");
                            boxes += 1;
                        }
                    }
                    checked += 1;
                }
            }
        }
        assert!(checked > 300 && boxes > 100, "{checked} {boxes}");
    }

    /// `SpanPoly::tight_over` encloses the piece on its box (degrees 1..=10 and 30..=40): at
    /// random parameters of random boxes (widths from 2^-50 to 1/2, and boxes of two
    /// neighbouring doubles, evaluated at their lower end) the piece's value by
    /// double-double de Casteljau on the shifted rows (an independent enclosure of the exact value, about 2^-100 wide) lies in
    /// `enc`, its value at the box's midpoint meets `v`, and `v0` is the first Bézier point;
    /// the cheap values of [`SpanPoly::values`] contain the same values (below 2^-20 the O(p)
    /// form of `values_small`), and F' over the box meets F' at each sample. (Fails with the mean-value term e left out: `enc` is then the
    /// midpoint's value alone; with `values_small`'s r L term left out; and with the local
    /// weight bound's slope term r max |W'| left out, or that bound halved.)
    #[test]
    fn tight_over_encloses_the_piece() {
        use crate::spline::bezier::de_casteljau_eval_in_place;
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(22);
        let piece = |sp: &SpanPoly, t: f64| -> Ddi {
            let seg = &sp.dseg;
            let h = if seg.rational { 2 } else { 1 };
            let mut x: Vec<Ddi> = seg.pts.iter().step_by(h).copied().collect();
            let xv = de_casteljau_eval_in_place(&mut x, &Ddi::exact(t));
            let v = if seg.rational {
                let mut w: Vec<Ddi> = seg.pts.iter().skip(1).step_by(2).copied().collect();
                xv / de_casteljau_eval_in_place(&mut w, &Ddi::exact(t))
            } else {
                xv
            };
            v + Ddi::exact(sp.c)
        };
        let (mut boxes, mut wide, mut small, mut ulp_boxes) = (0, 0, 0, 0);
        for n in 0..230 {
            let dim = rng.random_range(1..=2usize);
            let c = if n < 200 {
                crate::spline::tight::tests::random_curve(&mut rng, dim)
            } else {
                // degrees 30..=40 (the double-word points from degree 32 on), two spans
                let p = rng.random_range(30..=40usize);
                let mut kn = vec![0.0; p + 1];
                kn.push(rng.random_range(0.2..0.8));
                kn.extend(vec![1.0; p + 1]);
                let pts = (0..p + 2)
                    .map(|_| (0..dim).map(|_| rng.random_range(-10.0..10.0)).collect())
                    .collect();
                let w = rng
                    .random_bool(0.5)
                    .then(|| (0..p + 2).map(|_| rng.random_range(0.5..2.0)).collect());
                NurbsCurve::new(p, kn, pts, w).unwrap()
            };
            let (pair, spans) = pair_and_spans(&c);
            let tight = crate::spline::tight::TightEval::new(&c);
            for k in spans {
                let sp = SpanPoly::new(&c, 0, k, &pair, tight.bezier_points(k));
                for it in 0..5 {
                    let w = 2f64.powf(rng.random_range(-50.0..-1.0));
                    let t0 = rng.random_range(0.0..1.0 - w);
                    // (and a box of two neighbouring doubles, as the search leaves them at
                    // machine precision: no double strictly inside)
                    let t = if it == 4 { T::new(t0, t0.next_up()) } else { T::new(t0, t0 + w) };
                    // the cheap values too (below 2^-20 the O(p) value at the midpoint widened
                    // by r max |C'|, `values_small`; above, the restriction)
                    let cheap = sp.values(t);
                    small += (w <= 1.0 / 1_048_576.0 && sp.values_small(t).is_some()) as usize;
                    // and F' over the box (below 2^-20 first the mean value form about the
                    // midpoint) meets F' at every sample (`Mr` enclosures of the same value)
                    let dfx = sp.df(t);
                    for i in 0..=8 {
                        let s = (t.lo + (t.hi - t.lo) * i as f64 / 8.0).clamp(t.lo, t.hi);
                        let x = piece(&sp, s);
                        assert!(cheap.contains(x.hi()), "{c:?} k={k} t={t:?} s={s}");
                        let d = bernstein_value_s(&sp.df.pts, s).to_interval();
                        assert!(!dfx.intersection(d).is_empty(), "{c:?} k={k} t={t:?} s={s}");
                    }
                    let Some((enc, v, v0)) = sp.tight_over(t) else {
                        continue;
                    };
                    boxes += 1;
                    wide += (it < 4 && w > 1e-3) as usize;
                    ulp_boxes += (it == 4) as usize;
                    let mid = midpoint(t.lo, t.hi);
                    let tm = if t.lo < mid && mid < t.hi { mid } else { t.lo };
                    let at = piece(&sp, tm);
                    assert!(!at.to_interval().intersection(v.to_interval()).is_empty());
                    for i in 0..=8 {
                        let s = (t.lo + (t.hi - t.lo) * i as f64 / 8.0).clamp(t.lo, t.hi);
                        let x = piece(&sp, s);
                        assert!(
                            enc.contains(x.hi()),
                            "{c:?} k={k} t={t:?} s={s} enc=[{}, {}] x={x:?}",
                            enc.inf(),
                            enc.sup()
                        );
                    }
                    let first = piece(&sp, 0.0);
                    assert!(!first.to_interval().intersection(v0.to_interval()).is_empty());
                }
            }
        }
        assert!(
            boxes > 500 && wide > 100 && small > 300 && ulp_boxes > 100,
            "{boxes} {wide} {small} {ulp_boxes}"
        );
    }

    #[test]
    fn span_poly_derivative_numerator_matches_f64() {
        // F(t) against A_t W - A W_t (rational) / A_t / p (polynomial) from f64 de Boor
        // derivatives of the shifted homogeneous rows, scaled to the local parameter.
        let p = 5;
        let kn = vec![
            0., 0., 0., 0., 0., 0., 0.2, 0.45, 0.5, 1., 1., 1., 1., 1., 1.,
        ];
        let x: Vec<f64> = (0..9).map(|i| ((i * 37) % 11) as f64 / 7.0 - 0.6).collect();
        let w: Vec<f64> = (0..9).map(|i| 0.3 + ((i * 5) % 7) as f64).collect();
        for wt in [None, Some(w)] {
            let c = curve1(p, kn.clone(), &x, wt);
            let pair = if c.is_rational() {
                pair_coefficients(p).to_vec()
            } else {
                Vec::new()
            };
            let ev = CurveEval::<f64>::new(&c, 2);
            let k0 = c.knots().iter().position(|&u| u > 0.0).unwrap() - 1;
            for k in k0..c.num_points() {
                let (a, b) = (c.knots()[k], c.knots()[k + 1]);
                if a == b {
                    continue;
                }
                let tight = crate::spline::tight::TightEval::new(&c);
                let sp = SpanPoly::new(&c, 0, k, &pair, tight.bezier_points(k));
                for i in 0..=10 {
                    let t = i as f64 / 10.0;
                    let u = a + (b - a) * t;
                    let mut buf = Vec::new();
                    let rows: &[usize] = if c.is_rational() { &[0, 1] } else { &[0] };
                    let h0 = ev.level(0).eval_span_rows(k, &u, rows, &mut buf).to_vec();
                    let h1 = ev
                        .level(1)
                        .eval_span_rows(k - 1, &u, rows, &mut buf)
                        .to_vec();
                    let (l, sc) = (b - a, if c.is_rational() { 1.0 } else { p as f64 });
                    let want = if c.is_rational() {
                        // shifted: A - c W; (A - cW)_t W - (A - cW) W_t = A_t W - A W_t
                        (h1[0] * h0[1] - h0[0] * h1[1]) * l
                    } else {
                        h1[0] * l / sc
                    };
                    let got = sp.f(T::new(t, t));
                    let tol = 1e-12 * (1.0 + want.abs());
                    assert!(
                        got.inf() - tol <= want && want <= got.sup() + tol,
                        "k {k} u {u}: {got:?} vs {want}"
                    );
                    // F over a box contains F at its points; F' by a difference quotient
                    let (t0, t1) = (t.min(0.999), t.min(0.999) + 1e-3);
                    let (f0, f1) = (sp.f(T::new(t0, t0)).mid(), sp.f(T::new(t1, t1)).mid());
                    let d = sp.df(T::new(t0, t1));
                    // mean value theorem: the difference quotient is a value of F'
                    let q = (f1 - f0) / (t1 - t0);
                    let e = 1e-9 * (1.0 + q.abs());
                    assert!(d.inf() - e <= q && q <= d.sup() + e, "{d:?} {q}");
                    // a box in the mean value form's range (width 2^-30) contains F' at its
                    // ends and midpoint (dropping the F'' term would miss them)
                    let (s0, s1) = (t.min(0.9), t.min(0.9) + 2f64.powi(-30));
                    let ds = sp.df(T::new(s0, s1));
                    for s in [s0, 0.5 * (s0 + s1), s1] {
                        let v = sp.df(T::new(s, s)).mid();
                        assert!(ds.contains(v), "k {k} [{s0}, {s1}]: {ds:?} vs F'({s}) {v}");
                    }
                    assert!(sp.f(T::new(t0, t1)).contains(f0) && sp.f(T::new(t0, t1)).contains(f1));
                    // the piece's value at u(t), and u([t0, t1]) covers u(t0), u(t1)
                    let y = c.point::<f64>(u).unwrap()[0];
                    let vt = sp.values_tight(T::new(t, t)).1;
                    assert!(vt.inf() - 1e-12 <= y && y <= vt.sup() + 1e-12, "{vt:?} {y}");
                    let U { lo, hi } = sp.to_u(T::new(t0, t1));
                    assert!(lo <= a + t0 * l && a + t1 * l <= hi && a <= lo && hi <= b);
                }
                // values over the span contain the f64 points of the piece
                let v = sp.values(T::new(0.0, 1.0));
                for i in 0..=10 {
                    let u = a + (b - a) * i as f64 / 10.0;
                    let y = c.point::<f64>(u).unwrap()[0];
                    assert!(v.inf() - 1e-12 <= y && y <= v.sup() + 1e-12, "{v:?} {y}");
                }
            }
        }
    }

    /// Asserts that the exact value x lies in the enclosure g (within its radius of its centre).
    fn assert_encloses(x: &crate::num::Exact, g: &Mr, what: std::fmt::Arguments) {
        use crate::num::Exact;
        let dev = x.clone() - Exact::of(g.mid());
        assert!(
            !dev.gt_f64(g.rad()) && !(Exact::of(0.0) - dev).gt_f64(g.rad()),
            "{what}: centre {:e} radius {:e}",
            g.mid(),
            g.rad()
        );
    }

    /// F's coefficients from double-double points (`SpanPoly::refined`) against exact
    /// rational pair sums and differences, on segments with extreme weights and cancelling
    /// terms (the cases it is for), degrees 1 to F_DDI_MAX_DEGREE: each exact coefficient
    /// within the radius of the centre, each radius that of the f64 centre's rounding plus
    /// 2^-80 of the terms (the f64 sums' is 2^-53 of the terms), and `None` above the degree
    /// limit.
    #[test]
    fn f_from_ddi_encloses_the_exact_coefficients() {
        use crate::num::Exact;
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(29);
        let mut checked = 0;
        for it in 0..300 {
            let p = rng.random_range(1..=F_DDI_MAX_DEGREE);
            let rational = it % 4 != 0;
            let pts: Vec<f64> = (0..=p)
                .flat_map(|i| {
                    let a = match it % 3 {
                        // nearly equal points: the differences cancel
                        0 => 1.0 + (i as f64) * 1e-13 * rng.random_range(0.5..1.5),
                        _ => rng.random_range(-1.0..1.0),
                    };
                    let w = 10f64.powf(rng.random_range(-6.0..6.0));
                    if rational {
                        vec![a * w, w]
                    } else {
                        vec![a]
                    }
                })
                .collect();
            let dseg = BezierSeg {
                a: 0.0,
                b: 1.0,
                degree: p,
                dim: 1,
                rational,
                pts: pts.iter().map(|&x| Ddi::exact(x)).collect(),
            };
            let got = f_from_ddi(&dseg).expect("within the degree limit");
            let q: Vec<Exact> = pts.iter().map(|&x| Exact::of(x)).collect();
            let binom_f64 = |n: usize, k: usize| crate::num::binom_exact(n, k).expect("exact");
            let binom = |n: usize, k: usize| Exact::of(binom_f64(n, k));
            let (want, scale): (Vec<Exact>, Vec<f64>) = if rational {
                let mut d = vec![Exact::of(0.0); 2 * p - 1];
                let mut sc = vec![0.0f64; 2 * p - 1];
                for i in 0..p {
                    for l in i + 1..=p {
                        let t = q[2 * l].clone() * q[2 * i + 1].clone()
                            - q[2 * i].clone() * q[2 * l + 1].clone();
                        let c = Exact::of((l - i) as f64) * binom(p, i) * binom(p, l)
                            / binom(2 * p - 2, i + l - 1);
                        d[i + l - 1] = d[i + l - 1].clone() + c * t;
                        let cf = (l - i) as f64 * binom_f64(p, i) * binom_f64(p, l)
                            / binom_f64(2 * p - 2, i + l - 1);
                        sc[i + l - 1] += cf
                            * ((pts[2 * l] * pts[2 * i + 1]).abs()
                                + (pts[2 * i] * pts[2 * l + 1]).abs());
                    }
                }
                (d, sc)
            } else {
                let d = (0..p).map(|i| q[i + 1].clone() - q[i].clone()).collect();
                (d, (0..p).map(|i| pts[i].abs() + pts[i + 1].abs()).collect())
            };
            assert_eq!(got.len(), want.len());
            for (k, ((g, x), sc)) in got.iter().zip(&want).zip(&scale).enumerate() {
                assert_encloses(x, g, format_args!("it {it} p {p} k {k}"));
                // (the rounding of the double-double value to an f64 centre, and 2^-80 of the
                // terms where they cancel)
                let bound = g.mid().abs() * f64::EPSILON + sc * 2f64.powi(-80) + 1e-300;
                assert!(g.rad() <= bound, "it {it} p {p} k {k}: radius {:e}", g.rad());
                checked += 1;
            }
        }
        assert!(checked > 2000, "{checked}");
        let big = BezierSeg {
            a: 0.0,
            b: 1.0,
            degree: F_DDI_MAX_DEGREE + 1,
            dim: 1,
            rational: true,
            pts: vec![Ddi::exact(1.0); 2 * F_DDI_MAX_DEGREE + 4],
        };
        assert!(f_from_ddi(&big).is_none());
    }

    /// The pair sums as one loop over the interleaved points, term by term in the order of i
    /// (the form [`pair_sum_f64`] had before its rows and lanes): the reference its results
    /// must equal bit for bit.
    fn pair_sum_reference(q: &[Mr], pair: &[Mr], p: usize) -> Vec<Mr> {
        const C: f64 = f64::EPSILON / 2.0;
        let n = 2 * p - 1;
        let mut acc = vec![(0.0f64, 0.0f64, 0.0f64, 0.0f64, 0.0f64); n];
        for i in 0..p {
            let (ai, wi) = (q[2 * i], q[2 * i + 1]);
            for l in i + 1..=p {
                let (al, wl) = (q[2 * l], q[2 * l + 1]);
                let pc = pair[i * (p + 1) + l];
                let (a_l, w_i, a_i, w_l) = (al.mid(), wi.mid(), ai.mid(), wl.mid());
                let x1 = a_l * w_i;
                let x2 = a_i * w_l;
                let v = pc.mid() * (x1 - x2);
                let rho1 = a_l.abs() * wi.rad() + w_i.abs() * al.rad() + al.rad() * wi.rad();
                let rho2 = a_i.abs() * wl.rad() + w_l.abs() * ai.rad() + ai.rad() * wl.rad();
                let nil = |x: Mr| x.mid() == 0.0 && x.rad() == 0.0;
                let zero = (nil(al) || nil(wi)) && (nil(ai) || nil(wl));
                let (pa, pr) = (pc.mid().abs(), pc.rad());
                let sum = x1.abs() + x2.abs();
                let e = &mut acc[i + l - 1];
                e.0 += v;
                if !zero {
                    e.1 += pr * (1.01 * sum + rho1 + rho2) + pa * (rho1 + rho2);
                    e.2 += pa * sum;
                    e.3 += 10.0 * (pr + pa) + 17.0;
                    e.4 += 1.0;
                }
            }
        }
        acc.into_iter()
            .map(|(d, r, g, h, m)| {
                let m_terms = (m - 1.0).max(0.0);
                let e = (r + (3.03 + 1.03 * m_terms) * C * g + eta_multiple(h)) * (1.0 + 1.0 / 1_099_511_627_776.0);
                Mr::from_centre_radius(d, e)
            })
            .collect()
    }

    /// [`pair_sum_f64`]'s rows and AVX2 lanes give the sums of [`pair_sum_reference`] bit for
    /// bit: 3,000 random cases, degrees 1-40, magnitudes 2^-300..2^300, exact zeros, zero
    /// centres with radii, wide radii, the true pair coefficients or random ones. Fails with a
    /// reassociated radius term or an unmasked zero term.
    #[test]
    fn pair_sum_lanes_are_scalar_terms() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(31);
        for it in 0..3000 {
            let p = if it % 10 == 3 { rng.random_range(13..=40) } else { rng.random_range(1..=12) };
            let mag = 2f64.powi(rng.random_range(-300..=300));
            let pick = |rng: &mut rand_chacha::ChaCha8Rng, scale: f64| -> Mr {
                match rng.random_range(0..10) {
                    // exact zeros (flat runs), and zero centres with a radius
                    0 => Mr::from_f64(0.0),
                    1 => Mr::from_centre_radius(0.0, scale * 1e-17),
                    _ => {
                        let c = rng.random_range(-1.0..1.0) * scale;
                        Mr::from_centre_radius(c, c.abs() * [0.0, 1e-30, 1e-16, 1e-3][rng.random_range(0..4)])
                    }
                }
            };
            let q: Vec<Mr> = (0..=p)
                .flat_map(|_| {
                    let a = pick(&mut rng, mag);
                    let w = if rng.random_range(0..8) == 0 { pick(&mut rng, 1.0) } else { pick(&mut rng, 10.0) };
                    [a, w]
                })
                .collect();
            let pair: Vec<Mr> = if it % 2 == 0 {
                pair_coefficients(p).to_vec()
            } else {
                (0..(p + 1) * (p + 1)).map(|_| pick(&mut rng, 1e3)).collect()
            };
            let mut got = Vec::new();
            pair_sum_f64(&q, &pair, p, &mut got);
            let want = pair_sum_reference(&q, &pair, p);
            assert_eq!(got.len(), want.len());
            for (k, (g, w)) in got.iter().zip(&want).enumerate() {
                assert!(
                    g.mid().to_bits() == w.mid().to_bits() && g.rad().to_bits() == w.rad().to_bits(),
                    "p {p}, sum {k}: {g:?} != {w:?}"
                );
            }
        }
    }

    /// `second_hull` holds F'''s exact Bernstein coefficients (m - 1)(D'_{i+1} - D'_i) for
    /// the corners D'_i = c_i ± r_i of the enclosures (exact rational arithmetic), on random,
    /// cancelling, exact (all of them, in a fifth of the cases) and wide coefficients of
    /// magnitudes 2^±300 (tiny ones too), and is
    /// the whole line where something is not finite; `mag_bound` is the largest `Mr::mag`,
    /// bit for bit. Fails without the radii's term, or with the largest magnitude not
    /// stepped up. (The rounding's term and the outward step are margins a random test does
    /// not reach: the f64 hull errs by at most about 1.5 ulps there.)
    #[test]
    fn second_hull_and_mag_bound_hold() {
        use crate::num::Exact;
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(53);
        for it in 0..3000 {
            let m = rng.random_range(1..=24usize);
            let mag = 2f64.powi(rng.random_range(-300..=300));
            let base = rng.random_range(-1.0..1.0) * mag;
            let co: Vec<Mr> = (0..m)
                .map(|_| {
                    let c = match it % 4 {
                        // nearly equal: the differences cancel
                        0 => base * (1.0 + rng.random_range(-1e-12..1e-12)),
                        1 => rng.random_range(-8.0f64..8.0).round() * mag,
                        _ => rng.random_range(-1.0..1.0) * mag,
                    };
                    let r = match rng.random_range(0..4) {
                        // (every fifth case exact centres only: the rounding's term alone)
                        _ if it % 5 == 4 => 0.0,
                        0 => 0.0,
                        1 => c.abs() * 1e-16,
                        2 => c.abs() * rng.random_range(0.0..1e-3),
                        _ => f64::from_bits(rng.random_range(1..64)),
                    };
                    Mr::from_centre_radius(c, r)
                })
                .collect();
            let want = co.iter().fold(0.0f64, |a, x| a.max(x.mag()));
            assert_eq!(mag_bound(co.iter().copied()).to_bits(), want.to_bits(), "{co:?}");
            let h = second_hull(&co);
            if m < 2 {
                assert_eq!((h.inf(), h.sup()), (0.0, 0.0));
                continue;
            }
            let nm = Exact::of((m - 1) as f64);
            for _ in 0..4 {
                let d: Vec<Exact> = co
                    .iter()
                    .map(|x| {
                        let s = [-1.0, 0.0, 1.0][rng.random_range(0..3)];
                        Exact::of(x.mid()) + Exact::of(s) * Exact::of(x.rad())
                    })
                    .collect();
                for w in d.windows(2) {
                    let x = nm.clone() * (w[1].clone() - w[0].clone());
                    assert!(
                        !x.gt_f64(h.sup()) && !(Exact::of(0.0) - x).gt_f64(-h.inf()),
                        "{co:?}: {h:?}"
                    );
                }
            }
        }
        let mut co = vec![Mr::from_f64(1.0), Mr::from_f64(2.0)];
        co.push(Mr::ENTIRE);
        assert!(second_hull(&co).is_entire());
        co[2] = Mr::from_f64(f64::MAX);
        co[0] = Mr::from_f64(-f64::MAX);
        assert!(second_hull(&co).is_entire());
    }

    /// The a-priori bound of [`pair_sum_f64`] holds against exact rational sums: for inputs
    /// anywhere in their enclosures (centres, and corners at ± the radius, of the points and
    /// of the pair coefficients), every exact D_k lies within the returned radius of the
    /// centre; degrees 1 to 40, magnitudes 2^±60, radii from 0 to 2^-30 relative, exact zeros
    /// (flat runs, which must stay exact zeros), cancelling and alternating values.
    #[test]
    fn pair_sum_bound_holds_exactly() {
        use crate::num::Exact;
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(23);
        let (mut checked, mut zeros) = (0, 0);
        for it in 0..600 {
            let p = if it % 50 == 7 { rng.random_range(13..=40) } else { rng.random_range(1..=12) };
            let mag = 2f64.powi(rng.random_range(-60..=60));
            let rel = [0.0, 1e-30, 1e-17, 1e-10][it % 4];
            // (every 9th case: zero centres with subnormal radii next to weights near 1e-214,
            // whose radius products underflow to 0 in f64)
            let tiny = it % 9 == 4;
            let q: Vec<Mr> = (0..=p)
                .flat_map(|i| {
                    let a = match it % 5 {
                        0 if i % 3 != 2 => 0.0, // a flat run: exact zeros
                        1 => mag * if i % 2 == 0 { 1.0 } else { -0.999 },
                        2 => mag * (1.0 + rng.random_range(-1e-12..1e-12)),
                        _ => rng.random_range(-1.0..1.0) * mag,
                    };
                    let (a, w): (f64, f64) = if tiny {
                        (0.0, 1e-214 * rng.random_range(0.5..2.0))
                    } else {
                        (a, rng.random_range(0.01..100.0))
                    };
                    let ra = if tiny {
                        f64::from_bits(rng.random_range(1..64))
                    } else if a == 0.0 {
                        0.0
                    } else {
                        a.abs() * rel * rng.random_range(0.0..1.0)
                    };
                    let rw = w * rel * rng.random_range(0.0..1.0);
                    [Mr::from_centre_radius(a, ra), Mr::from_centre_radius(w, rw)]
                })
                .collect();
            let mut pair = pair_coefficients(p).to_vec();
            if it % 3 == 1 {
                // (wider pair enclosures than the cached ones, so that their radius counts)
                for x in &mut pair {
                    *x = Mr::from_centre_radius(x.mid(), x.mid().abs() * 1e-12);
                }
            }
            let mut got = Vec::new();
            pair_sum_f64(&q, &pair, p, &mut got);
            assert_eq!(got.len(), 2 * p - 1);
            for trial in 0..3 {
                // an exact value in each enclosure: the centre or a corner
                let mut pick = |x: &Mr| {
                    let s = if trial == 0 { 0.0 } else { [-1.0, 0.0, 1.0][rng.random_range(0..3)] };
                    Exact::of(x.mid()) + Exact::of(s) * Exact::of(x.rad())
                };
                let qe: Vec<Exact> = q.iter().map(&mut pick).collect();
                let pe: Vec<Exact> = pair.iter().map(&mut pick).collect();
                let mut d = vec![Exact::of(0.0); 2 * p - 1];
                for i in 0..p {
                    for l in i + 1..=p {
                        let t = qe[2 * l].clone() * qe[2 * i + 1].clone()
                            - qe[2 * i].clone() * qe[2 * l + 1].clone();
                        d[i + l - 1] = d[i + l - 1].clone() + pe[i * (p + 1) + l].clone() * t;
                    }
                }
                for (k, (x, g)) in d.iter().zip(&got).enumerate() {
                    assert_encloses(x, g, format_args!("it {it} p {p} k {k}"));
                    checked += 1;
                }
            }
            if it % 5 == 0 && rel == 0.0 {
                // a coefficient whose every term has a zero factor is an exact zero
                for (k, g) in got.iter().enumerate() {
                    let all_zero = (0..p).all(|i| {
                        (i + 1..=p).filter(|&l| i + l - 1 == k).all(|l| {
                            let nil = |x: &Mr| x.mid() == 0.0 && x.rad() == 0.0;
                            (nil(&q[2 * l]) || nil(&q[2 * i + 1]))
                                && (nil(&q[2 * i]) || nil(&q[2 * l + 1]))
                        })
                    });
                    if all_zero {
                        assert_eq!((g.mid(), g.rad()), (0.0, 0.0), "p {p} k {k}");
                        zeros += 1;
                    }
                }
            }
        }
        assert!(checked > 10_000 && zeros > 20, "{checked} {zeros}");
    }

    /// The restriction of interleaved rows (`segment_values_f64`'s homogeneous rows x w, w)
    /// gives each row's one-row restriction bit for bit (so the one-row bound, tested exactly
    /// below, holds per row), and the values' enclosure contains the piece's f64 values
    /// over the box: random rows, degrees 1 to 40, boxes anywhere in [0, 1].
    #[test]
    fn interleaved_rows_restrict_as_single_rows() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(31);
        for _ in 0..2000 {
            let n = rng.random_range(1..=40usize);
            let rows: Vec<f64> = (0..=n)
                .flat_map(|_| [rng.random_range(-10.0..10.0), rng.random_range(0.1..10.0)])
                .collect();
            let (a, b): (f64, f64) = (rng.random_range(0.0..1.0), rng.random_range(0.0..1.0));
            let (t0, t1) = (a.min(b), a.max(b));
            if t0 >= t1 {
                continue;
            }
            let mut both = rows.clone();
            let mut out = vec![0.0; both.len()];
            restrict_in_place::<f64, 2>(&mut both, &mut out, t0, t1);
            for r in 0..2 {
                let mut one: Vec<f64> = rows.iter().skip(r).step_by(2).copied().collect();
                let mut out1 = vec![0.0; one.len()];
                restrict_in_place::<f64, 1>(&mut one, &mut out1, t0, t1);
                let got: Vec<f64> = both.iter().skip(r).step_by(2).copied().collect();
                assert_eq!(got, one, "row {r}, n {n}, [{t0}, {t1}]");
            }
            // the rational piece's values over the box lie in the enclosure
            let seg = BezierSeg {
                a: 0.0,
                b: 1.0,
                degree: n,
                dim: 1,
                rational: true,
                pts: rows.iter().map(|&x| Mr::from_f64(x)).collect(),
            };
            let v = segment_values_f64(&seg, t0, t1).unwrap();
            for i in 0..=8 {
                let t = t0 + (t1 - t0) * i as f64 / 8.0;
                let x: Vec<f64> = rows.iter().step_by(2).copied().collect();
                let w: Vec<f64> = rows.iter().skip(1).step_by(2).copied().collect();
                let y = crate::spline::bezier::bernstein_value(&x, t)
                    / crate::spline::bezier::bernstein_value(&w, t);
                let tol = 1e-9 * (1.0 + y.abs());
                assert!(v.inf() - tol <= y && y <= v.sup() + tol, "{v:?} {y}");
            }
        }
    }

    /// The a-priori bound of [`restrict_hull_f64`] holds against exact rational
    /// restrictions: every exact restricted coefficient (of the midpoints, at the same split
    /// parameters) lies in the returned enclosure, on random, clustered, cancelling,
    /// alternating and extreme-magnitude coefficients, degrees 1 to 63 and a few up to 255, and boxes at the ends,
    /// tiny, near 1 and wide.
    #[test]
    fn f64_restriction_bound_holds_exactly() {
        use crate::num::Exact;
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        let mut slack = f64::INFINITY;
        for it in 0..1500 {
            let n = match it % 4 {
                // (a few degrees up to the limit, far above the usual ones: the exact
                // arithmetic of the check grows with the square of the degree)
                _ if it % 100 == 3 => rng.random_range(64..=F64_RESTRICT_MAX),
                0 => rng.random_range(1..=4),
                1 => rng.random_range(5..=20),
                2 => rng.random_range(21..=63),
                _ => 19,
            };
            // (every 7th case near f64::MAX, where a difference of two coefficients of opposite
            // signs overflows: the restriction must then answer ENTIRE, never skip a NaN)
            let mag = if it % 7 == 5 {
                f64::MAX * rng.random_range(0.3..1.0)
            } else {
                2f64.powi(rng.random_range(-60..=60))
            };
            let base: f64 = rng.random_range(-1.0..1.0) * mag;
            let c: Vec<f64> = (0..=n)
                .map(|i| match it % 5 {
                    0 => base + rng.random_range(-1.0..1.0) * mag * 1e-9,
                    1 => if i % 2 == 0 { mag } else { -mag * rng.random_range(0.5..1.0) },
                    2 => rng.random_range(-8.0f64..8.0).round() * mag / 8.0,
                    _ => rng.random_range(-1.0..1.0) * mag,
                })
                .collect();
            let (t0, t1) = match it % 6 {
                0 => (0.0, rng.random_range(0.0..1.0)),
                1 => (rng.random_range(0.0..1.0), 1.0),
                2 => {
                    let a = rng.random_range(0.0..1.0);
                    (a, a + rng.random_range(0.0..1e-9))
                }
                3 => (1.0 - rng.random_range(0.0..1e-6), 1.0 - rng.random_range(0.0..1e-12)),
                _ => {
                    let (a, b): (f64, f64) = (rng.random_range(0.0..1.0), rng.random_range(0.0..1.0));
                    (a.min(b), a.max(b))
                }
            };
            if !(t0 < t1 && t1 <= 1.0) {
                continue;
            }
            let co: Vec<Mr> = c.iter().map(|&x| Mr::from_f64(x)).collect();
            let (got, _, _) = restrict_hull_f64(&co, t0, t1).unwrap();
            // exact restriction at the same parameters (the same splits in exact arithmetic)
            let mut b: Vec<Exact> = c.iter().map(|&x| Exact::of(x)).collect();
            let mut out = b.clone();
            restrict_in_place::<_, 1>(&mut b, &mut out, t0, t1);
            for x in &b {
                assert!(
                    !x.gt_f64(got.sup()) && !(Exact::of(got.inf()) - x.clone()).gt_f64(0.0),
                    "n = {n}, [{t0}, {t1}], {c:?}: {:e} .. {:e}",
                    got.inf(),
                    got.sup()
                );
            }
            // the point value at t1 (the last coefficient of the exact left part at t1)
            let (pv, _) = value_f64(&co, t1).unwrap();
            let mut b: Vec<Exact> = c.iter().map(|&x| Exact::of(x)).collect();
            let mut out = b.clone();
            restrict_in_place::<_, 1>(&mut b, &mut out, 0.0, t1);
            let v = &b[n];
            assert!(
                !v.gt_f64(pv.sup()) && !(Exact::of(pv.inf()) - v.clone()).gt_f64(0.0),
                "n = {n}, at {t1}, {c:?}: {:e} .. {:e}",
                pv.inf(),
                pv.sup()
            );
            // how far inside the enclosure the exact extreme coefficients stay, relative to the
            // scale: the bound must not be vacuous either
            let w = got.sup() - got.inf();
            slack = slack.min(w / mag);
        }
        assert!(slack.is_finite());
    }

    /// The exact value at t of the polynomial whose Bernstein coefficients are the `co`
    /// enclosures' corners on the side `sign` (centre + sign * radius): the left part of exact
    /// de Casteljau at t ends in it.
    fn exact_corner_value(co: &[Mr], sign: f64, t: f64) -> crate::num::Exact {
        use crate::num::Exact;
        let mut b: Vec<Exact> = co
            .iter()
            .map(|x| Exact::of(x.mid()) + Exact::of(sign * x.rad()))
            .collect();
        let mut out = b.clone();
        restrict_in_place::<_, 1>(&mut b, &mut out, 0.0, t);
        b.pop().unwrap()
    }

    /// Both corners' exact values ([`exact_corner_value`]: every coefficient at the same end of
    /// its enclosure) lie in the enclosure `got` of a VS scheme at t; where `track`, the error of
    /// its midpoint relative to its bound `e` raises `worst` (how much of the bound is used).
    fn check_corners(co: &[Mr], t: f64, (got, e): (Interval, f64), track: bool, worst: &mut f64) {
        use crate::num::Exact;
        for sign in [-1.0, 1.0] {
            let v = exact_corner_value(co, sign, t);
            assert!(
                !v.gt_f64(got.sup()) && !(Exact::of(got.inf()) - v.clone()).gt_f64(0.0),
                "n = {}, at {t}, {:?}: {:e} .. {:e}",
                co.len() - 1,
                co.iter().map(|x| (x.mid(), x.rad())).collect::<Vec<_>>(),
                got.inf(),
                got.sup()
            );
            if track && e > 0.0 {
                let mid = 0.5 * got.inf() + 0.5 * got.sup();
                let err = (v - Exact::of(mid)).round_up().abs();
                *worst = worst.max(err / e);
            }
        }
    }

    /// For the tests of the VS schemes: whether case `it` is one of the few of degree above 56
    /// (whose binomials round; the exact check grows with the square of the degree and the
    /// bits of t), its degree n and its magnitude (2^-60 .. 2^60, subnormal, or near the
    /// overflow).
    fn vs_degree_and_scale(rng: &mut rand_chacha::ChaCha8Rng, it: usize) -> (bool, usize, f64) {
        use rand::Rng;
        let high = it % 150 == 7;
        let n = match it % 3 {
            _ if high => rng.random_range(57..=VS_MAX),
            0 => rng.random_range(0..=4),
            1 => rng.random_range(5..=24),
            _ => rng.random_range(25..=56),
        };
        let mag = match it % 9 {
            7 => f64::MAX * rng.random_range(0.01..0.5),
            8 => 2f64.powi(rng.random_range(-1060..=-1000)),
            _ => 2f64.powi(rng.random_range(-60..=60)),
        };
        (high, n, mag)
    }

    /// A parameter of the point-value tests, by the iteration `it`: near 0, near 1, near 1/2,
    /// tiny (underflowing powers), exactly 0, 1/2 or 1, or uniform.
    fn vs_test_param(rng: &mut rand_chacha::ChaCha8Rng, it: usize) -> f64 {
        use rand::Rng;
        match it % 7 {
            0 => rng.random_range(0.0..1e-6),
            1 => 1.0 - rng.random_range(0.0..1e-6),
            2 => 0.5 + rng.random_range(-1e-12..1e-12),
            3 => 2f64.powi(-rng.random_range(20..=1000)),
            4 => [0.0, 0.5, 1.0][it % 3],
            _ => rng.random_range(0.0..1.0),
        }
    }

    /// The a-priori bound of [`value_vs_dw`] (the VS scheme in plain double words) holds
    /// against exact rational evaluation: degrees 0 ..= 56, one of two interleaved rows,
    /// double-word centres (a genuine low part) with and without radii, magnitudes from
    /// 2^-1060 to 2^60, alternating and clustered coefficients, parameters near 0, 1/2, 1 and
    /// tiny ones; and it is not vacuous (the worst observed error is a sizeable share of it,
    /// and the bound is below 2^-90 of the coefficients).
    #[test]
    fn vs_dw_value_bound_holds_exactly() {
        use crate::num::Exact;
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(29);
        let mut worst: f64 = 0.0;
        for it in 0..2000 {
            let n = match it % 3 {
                0 => rng.random_range(0..=4),
                1 => rng.random_range(5..=24),
                _ => rng.random_range(25..=VS_DW_MAX),
            };
            let mag = match it % 9 {
                8 => 2f64.powi(rng.random_range(-1060..=-1000)),
                _ => 2f64.powi(rng.random_range(-60..=60)),
            };
            let base: f64 = rng.random_range(-1.0..1.0) * mag;
            let (h, row) = if it % 2 == 0 { (1, 0) } else { (2, it / 2 % 2) };
            let rad = if it % 4 == 1 { mag * 1e-35 } else { 0.0 };
            let co: Vec<Ddi> = (0..(n + 1) * h)
                .map(|i| {
                    let x = match it % 5 {
                        0 => base + rng.random_range(-1.0..1.0) * mag * 1e-9,
                        1 => if i % 2 == 0 { mag } else { -mag * rng.random_range(0.5..1.0) },
                        _ => rng.random_range(-1.0..1.0) * mag,
                    };
                    // (a double word: the exact product of two f64, then its radius)
                    let d = Ddi::exact(x) * Ddi::exact(1.0 + rng.random_range(0.0..1.0));
                    let (hi, lo, _) = d.parts();
                    Ddi::from_parts(hi, lo, rad)
                })
                .collect();
            let t = vs_test_param(&mut rng, it);
            let got = if h == 1 {
                value_vs_dw::<1>(&co, h, t).map(|[v]| v)
            } else {
                value_vs_dw::<2>(&co, h, t).map(|v| v[row])
            }
            .expect("a degree in range");
            let (gh, gl, e) = got.parts();
            assert!(got.to_interval().is_common_interval(), "n = {n}, t = {t}");
            let m = (0..=n).fold(0.0f64, |a, j| a.max(co[j * h + row].parts().0.abs()));
            assert!(e <= m * 2f64.powi(-90) + rad + 1e-300, "n = {n}: bound {e:e} of {m:e}");
            let centre = Exact::of(gh) + Exact::of(gl);
            for sign in [-1.0, 1.0] {
                let mut b: Vec<Exact> = (0..=n)
                    .map(|j| {
                        let (hi, lo, _) = co[j * h + row].parts();
                        Exact::of(hi) + Exact::of(lo) + Exact::of(sign * rad)
                    })
                    .collect();
                let mut out = b.clone();
                restrict_in_place::<_, 1>(&mut b, &mut out, 0.0, t);
                let d = b[n].clone() - centre.clone();
                assert!(
                    !d.gt_f64(e) && !(Exact::of(0.0) - d.clone()).gt_f64(e),
                    "n = {n}, row {row} of {h}, at {t}: off by more than {e:e}"
                );
                if rad == 0.0 && e > 0.0 {
                    worst = worst.max(d.round_up().abs() / e);
                }
            }
        }
        // (the rounding errors reach a noticeable share of the bound somewhere)
        assert!(worst > 1e-3, "{worst}");
    }

    /// The bound of [`value_vs_f64`] holds against exact rational evaluation (the left part
    /// of exact de Casteljau at t ends in B(t)): degrees 0 ..= 56, coefficients with radii,
    /// magnitudes from 2^-1060 to near f64::MAX, alternating and nearly constant signs,
    /// parameters near 0, 1/2 and 1 and tiny ones (underflowing powers); and it is not
    /// vacuous (the worst observed error is a sizeable share of it).
    #[test]
    fn vs_value_bound_holds_exactly() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(23);
        let mut worst: f64 = 0.0;
        for it in 0..3000 {
            let (high, n, mag) = vs_degree_and_scale(&mut rng, it);
            let base: f64 = rng.random_range(-1.0..1.0) * mag;
            let c: Vec<f64> = (0..=n)
                .map(|i| match it % 5 {
                    0 => base + rng.random_range(-1.0..1.0) * mag * 1e-9,
                    1 => if i % 2 == 0 { mag } else { -mag * rng.random_range(0.5..1.0) },
                    _ => rng.random_range(-1.0..1.0) * mag,
                })
                .collect();
            let rad = if it % 4 == 0 { mag * 1e-20 } else { 0.0 };
            let t = vs_test_param(&mut rng, it);
            let t = if high {
                (t * 4096.0).round() / 4096.0
            } else {
                t
            };
            // (the exact coefficient at a corner of its enclosure)
            let co: Vec<Mr> = c.iter().map(|&x| Mr::from_centre_radius(x, rad)).collect();
            let Some((got, e)) = value_vs_f64(&co, t) else {
                panic!("n = {n}: no value");
            };
            if !got.is_common_interval() {
                assert!(it % 9 == 7, "n = {n}, t = {t}: {:e}", e);
                continue;
            }
            check_corners(&co, t, (got, e), rad == 0.0, &mut worst);
        }
        // (the rounding errors reach a noticeable share of the bound somewhere)
        assert!(worst > 1e-3, "{worst}");
    }

    /// The weighted bound of [`value_vs_f64_weighted`] holds against exact rational evaluation:
    /// degrees 0 ..= 127, coefficients graded over up to 2^-60 from one end to the other (F
    /// near a zero next to an end of the span) as well as random, alternating and clustered
    /// ones, each with its own radius (the exact coefficient at a corner of its enclosure),
    /// magnitudes from 2^-1060 to near the overflow, parameters near 0, 1/2, 1 and tiny ones.
    /// It is not vacuous: the rounding errors reach a sizeable share of it somewhere, and on
    /// graded coefficients it is far below the plain bound of [`value_vs_f64`].
    #[test]
    fn weighted_vs_value_bound_holds_exactly() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(29);
        let (mut worst, mut sharper): (f64, f64) = (0.0, 1.0);
        for it in 0..3000 {
            let (high, n, mag) = vs_degree_and_scale(&mut rng, it);
            let base: f64 = rng.random_range(-1.0..1.0) * mag;
            // (graded: |c_j| falls from mag by 2^-(60 j / n), towards either end)
            let up_end = rng.random_bool(0.5);
            let c: Vec<f64> = (0..=n)
                .map(|i| match it % 5 {
                    0 => base + rng.random_range(-1.0..1.0) * mag * 1e-9,
                    1 => if i % 2 == 0 { mag } else { -mag * rng.random_range(0.5..1.0) },
                    2 | 3 => {
                        let k = if up_end { n - i } else { i } as f64;
                        let g = 2f64.powf(-60.0 * k / (n.max(1) as f64));
                        rng.random_range(-1.0..1.0) * mag * g
                    }
                    _ => rng.random_range(-1.0..1.0) * mag,
                })
                .collect();
            let rads: Vec<f64> = c
                .iter()
                .map(|&x| if it % 4 == 0 { 0.0 } else { x.abs() * 2f64.powi(-rng.random_range(20..=60)) })
                .collect();
            let t = vs_test_param(&mut rng, it);
            let t = if high {
                (t * 4096.0).round() / 4096.0
            } else {
                t
            };
            let co: Vec<Mr> = c
                .iter()
                .zip(&rads)
                .map(|(&x, &r)| Mr::from_centre_radius(x, r))
                .collect();
            let Some((got, e)) = value_vs_f64_weighted(&co, t) else {
                panic!("n = {n}: no value");
            };
            if !got.is_common_interval() {
                assert!(it % 9 == 7, "n = {n}, t = {t}: {:e}", e);
                continue;
            }
            if let Some((_, plain)) = value_vs_f64(&co, t) {
                if it % 5 >= 2 && it % 5 <= 3 && plain > 0.0 {
                    sharper = sharper.min(e / plain);
                }
            }
            check_corners(&co, t, (got, e), it % 4 == 0, &mut worst);
        }
        assert!(worst > 1e-3, "{worst}");
        assert!(sharper < 1e-9, "{sharper}");
    }

    /// The bound of [`halving_bound`] holds against the same halvings in exact arithmetic, for
    /// pieces of depth 1 .. 12 of degrees 1 ..= 40 with radii, near-cancelling coefficients and
    /// magnitudes down to the subnormal range; and it is not vacuous.
    #[test]
    fn halving_bound_holds_exactly() {
        use crate::num::Exact;
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(29);
        let mut worst: f64 = 0.0;
        for it in 0..400 {
            let n = rng.random_range(1..=40usize);
            let mag = match it % 6 {
                5 => 2f64.powi(rng.random_range(-1074..=-1000)),
                _ => 2f64.powi(rng.random_range(-60..=60)),
            };
            let c: Vec<f64> = (0..=n)
                .map(|i| match it % 3 {
                    0 => mag * (1.0 + rng.random_range(-1e-9..1e-9)) * if i % 2 == 0 { 1.0 } else { -1.0 },
                    _ => rng.random_range(-1.0..1.0) * mag,
                })
                .collect();
            let rad = if it % 4 == 1 { mag * 1e-18 } else { 0.0 };
            let m = c.iter().fold(0.0f64, |a, x| a.max(x.abs()));
            let depth = rng.random_range(1..=12u32);
            let (mut v, mut x): (Vec<f64>, Vec<Exact>) =
                (c.clone(), c.iter().map(|&y| Exact::of(y) + Exact::of(rad)).collect());
            for _ in 0..depth {
                let go_left = rng.random_bool(0.5);
                let (mut l, mut r) = (v.clone(), v.clone());
                halve(&mut v, &mut l, &mut r);
                let (mut le, mut re) = (x.clone(), x.clone());
                halve(&mut x, &mut le, &mut re);
                (v, x) = if go_left { (l, le) } else { (r, re) };
            }
            let e = halving_bound(n, depth, m, rad);
            for (a, b) in v.iter().zip(&x) {
                let lo = Exact::of(*a) - Exact::of(e);
                let hi = Exact::of(*a) + Exact::of(e);
                assert!(
                    !(lo.clone() - b.clone()).gt_f64(0.0) && !(b.clone() - hi).gt_f64(0.0),
                    "n = {n}, depth {depth}, {c:?}"
                );
                if rad == 0.0 && e > 0.0 {
                    let err = (b.clone() - Exact::of(*a)).round_up().abs();
                    worst = worst.max(err / e);
                }
            }
        }
        assert!(worst > 1e-3, "{worst}");
    }

    /// The span form whose F is k prod (t - r_i) (`roots`), exact in Bernstein form, then
    /// rounded to enclosures (only F is set; the rest is what the zero estimation ignores).
    fn span_poly_of_roots(roots: &[f64], k: f64) -> SpanPoly {
        use crate::num::Exact;
        // F = k * prod (t - r): Bernstein coefficients by products of linear factors
        // (-r, 1 - r), degree-elevating each product exactly
        let mut f: Vec<Exact> = vec![Exact::of(k)];
        for &r in roots {
            let g = [Exact::of(-r), Exact::of(1.0) - Exact::of(r)];
            let m = f.len() - 1;
            let mut h = vec![Exact::of(0.0); m + 2];
            for (i, fi) in f.iter().enumerate() {
                for (j, gj) in g.iter().enumerate() {
                    // C(m, i) C(1, j) / C(m + 1, i + j)
                    let w = Exact::of(if j == 0 { (m + 1 - i) as f64 } else { (i + 1) as f64 })
                        / Exact::of((m + 1) as f64);
                    h[i + j] = h[i + j].clone() + w * fi.clone() * gj.clone();
                }
            }
            f = h;
        }
        let fco: Vec<Mr> = f
            .iter()
            .map(|x| {
                let (lo, hi) = (x.round_down(), x.round_up());
                Mr::from_centre_radius(0.5 * lo + 0.5 * hi, (hi - lo) * 0.5 + 1e-300)
            })
            .collect();
        let n = fco.len() - 1;
        let poly = |pts: Vec<Mr>| BezierSeg {
            a: 0.0,
            b: 1.0,
            degree: pts.len() - 1,
            dim: 1,
            rational: false,
            pts,
        };
        SpanPoly {
            k: 0,
            c: 0.0,
            seg: poly(vec![Mr::from_f64(0.0); 2]),
            f: poly(fco),
            df: poly(vec![Mr::ENTIRE; n.max(1)]),
            d2: Interval::ENTIRE,
            fmax: f64::INFINITY,
            dfmax: f64::INFINITY,
            wmin: 1.0,
            dseg: BezierSeg {
                a: 0.0,
                b: 1.0,
                degree: 1,
                dim: 1,
                rational: false,
                pts: vec![Ddi::exact(0.0); 2],
            },
        }
    }

    /// The end rule's box widened to 2^-30: F = (t - 0.3)(t - 1) with its last coefficient
    /// (F(1) = 0) enclosed 1e-12 wide, so that F(1 - 2^-40) ~ -6e-13 cannot be told from 0 by
    /// any bound, while F(1 - 2^-30) ~ -7e-10 can. The estimation with h = 2^-40 still proves
    /// everything: the zero at 0.3 in its narrow box, the end's zero in [1 - 2^-30, 1], the
    /// rest zero-free (fails without the wider box: the end is then left unproven).
    #[test]
    fn end_rule_widens_its_box_where_the_end_is_noisy() {
        let mut sp = span_poly_of_roots(&[0.3, 1.0], 1.0);
        let n = sp.f.pts.len() - 1;
        let last = sp.f.pts[n];
        sp.f.pts[n] = Mr::from_centre_radius(last.mid(), 1e-12);
        let h = 1.0 / 1_099_511_627_776.0; // 2^-40
        let (mut est, mut free) = (Vec::new(), Vec::new());
        assert!(sp.zero_estimates(&mut est, 2 * n + 2, h, &mut free));
        assert!(
            est.iter().any(|&(r, hr)| r == 1.0 && hr == FLOAT_FIRST_H),
            "{est:?}"
        );
        // every point of [0, 1] is free or in a box
        let mut boxes: Vec<(f64, f64)> = est
            .iter()
            .map(|&(r, hr)| ((r - hr).max(0.0), (r + hr).min(1.0)))
            .collect();
        boxes.extend(free.iter().copied());
        boxes.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut reach = 0.0f64;
        for (lo, hi) in boxes {
            assert!(lo <= reach, "a gap before {lo}: {est:?} {free:?}");
            reach = reach.max(hi);
        }
        assert_eq!(reach, 1.0, "{est:?} {free:?}");
    }

    /// A zero where F's slope is too small for its signs 2^-40 away to show through the
    /// coefficients' error bound (a tiny span: slope ~4e-6 against radii ~7e-15, as on the
    /// clustered-knots family) is located in a box widened to 2^-30, instead of leaving gaps
    /// that hold its neighbourhood (fails without the wider box); a steep zero keeps the
    /// narrow one.
    #[test]
    fn a_flat_zero_gets_a_wider_box() {
        let h = 1.0 / 1_099_511_627_776.0;
        for (r, k, rad, want) in [(2.1e-7, 3.8e-6, 7e-15, FLOAT_FIRST_H), (0.4, 3.8e-6, 7e-15, FLOAT_FIRST_H), (0.4, 3.0, 7e-15, h)] {
            let mut sp = span_poly_of_roots(&[r, 5.0], k);
            for x in sp.f.pts.iter_mut() {
                *x = Mr::from_centre_radius(x.mid(), rad);
            }
            let boxes = sp.critical_boxes(h).unwrap_or_else(|| panic!("{r} {k}: not located"));
            assert_eq!(boxes.len(), 1, "{boxes:?}");
            let (lo, hi) = boxes[0];
            assert!(lo <= r && r <= hi, "{r} outside {boxes:?}");
            assert!(hi - lo <= 2.0 * want * (1.0 + 1e-9) && hi - lo > want, "{boxes:?}");
        }
    }

    /// A zero of F exactly at an end of the span (a knot where C_j' vanishes, F's end
    /// coefficient rounding noise) beside interior zeros: the piece with one sign change
    /// and the noisy end is halved, so that `critical_boxes` locates both (the end's zero by
    /// the end rule), instead of leaving a gap that holds the end's zero (fails without the
    /// halving).
    #[test]
    fn a_zero_at_the_end_beside_interior_zeros_is_located() {
        for (roots, end) in [
            (vec![0.3, 1.0], 1.0),
            (vec![0.0, 0.7], 0.0),
            (vec![0.2, 0.55, 1.0], 1.0),
            (vec![0.0, 0.35, 0.8], 0.0),
        ] {
            let sp = span_poly_of_roots(&roots, 1.5);
            let boxes = sp
                .critical_boxes(1.0 / 1_099_511_627_776.0)
                .unwrap_or_else(|| panic!("{roots:?}: not located"));
            for &r in &roots {
                assert!(boxes.iter().any(|&(lo, hi)| lo <= r && r <= hi), "{r} outside {boxes:?}");
            }
            assert!(boxes.iter().any(|&(lo, hi)| lo == end || hi == end), "{boxes:?}");
        }
    }

    /// Every zero of F lies outside the intervals that [`Numerator::zero_estimates`] proves
    /// zero-free: F = prod (t - r_i) (times a constant) in Bernstein form, exact, then rounded
    /// to enclosures; roots random, in pairs 1e-6 .. 1e-15 apart (a near-double zero), at the
    /// dyadic piece ends 1/2 and 1/4, at the span's ends and 1e-8 .. 1e-15 inside or outside
    /// them (the end rule), in pairs straddling an end, and just outside [0, 1]. The proof must also find
    /// something to claim (else the test would pass vacuously).
    #[test]
    fn zero_free_intervals_hold_no_zero() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(31);
        let (mut claimed, mut excluded) = (0usize, 0usize);
        for it in 0..300 {
            let mut roots: Vec<f64> = (0..rng.random_range(1..=5usize))
                .map(|_| rng.random_range(-0.1..1.1))
                .collect();
            match it % 4 {
                0 => {
                    let r = rng.random_range(0.0..1.0);
                    roots.push(r);
                    roots.push(r + 10f64.powi(-rng.random_range(6..=15)));
                }
                1 => roots.push([0.5, 0.25, 0.75][it % 3]),
                2 => {
                    // a zero at or next to an end of the span (the end rule), inside or just
                    // outside its box of 2^-30
                    let d = if it % 3 == 0 { 0.0 } else { 10f64.powi(-rng.random_range(8..=15)) };
                    let d = if it % 5 == 0 { -d } else { d };
                    roots.push(if it % 2 == 0 { d } else { 1.0 - d });
                }
                _ => {
                    // a pair straddling an end, the inner zero outside the end's box: F at
                    // the end is rounding noise, and only the sign of F at the box's inner end
                    // shows the zero before it
                    let (d, d2) = (
                        10f64.powi(-rng.random_range(7..=8)),
                        10f64.powi(-rng.random_range(6..=9)),
                    );
                    if it % 8 == 3 {
                        roots.extend([1.0 - d, 1.0 + d2]);
                    } else {
                        roots.extend([d, -d2]);
                    }
                }
            }
            let sp = span_poly_of_roots(&roots, rng.random_range(0.5..2.0));
            let n = sp.f.pts.len() - 1;
            let (mut est, mut free) = (Vec::new(), Vec::new());
            sp.zero_estimates(&mut est, 2 * n + 2, 1.0 / 1_073_741_824.0, &mut free);
            for w in free.windows(2) {
                assert!(w[0].1 < w[1].0, "{free:?}");
            }
            for &(lo, hi) in &free {
                claimed += 1;
                for &r in &roots {
                    assert!(!(lo <= r && r <= hi), "root {r} in [{lo}, {hi}], roots {roots:?}");
                }
            }
            // the located critical points (`critical_boxes`, the zero-free intervals and the
            // gaps excluded by enclosures of F): every root in [0, 1] lies in a box
            let h = 1.0 / 1_099_511_627_776.0;
            let (mut bx, mut gaps) = (Vec::new(), Vec::new());
            let had_gaps = sp.zero_boxes(h, n + 2, (&mut est, &mut free), &mut bx, &mut gaps)
                && !gaps.is_empty();
            if let Some(boxes) = sp.critical_boxes(h) {
                excluded += had_gaps as usize;
                for &r in roots.iter().filter(|r| (0.0..=1.0).contains(*r)) {
                    assert!(
                        boxes.iter().any(|&(lo, hi)| lo <= r && r <= hi),
                        "root {r} outside {boxes:?}, roots {roots:?}"
                    );
                }
            }
        }
        assert!(claimed > 300, "{claimed}");
        assert!(excluded > 20, "{excluded}");
    }

    #[test]
    fn span_shift_prefers_flat_runs() {
        assert_eq!(span_shift(&mut [3.0, 1.0, 1.0, 2.0, 1.0]), 1.0);
        assert_eq!(span_shift(&mut [3.0, 1.0, 2.0]), 2.0);
        assert_eq!(span_shift(&mut [-0.5]), -0.5);
    }
}
