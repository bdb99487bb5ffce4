//! B-spline curves in homogeneous coordinates, generic over the number type: the one copy of
//! de Boor corner cutting, basis functions, derivative control points, knot insertion and
//! Bézier extraction that the whole crate uses, for f64, intervals and MPFR alike.

use crate::num::Scalar;
use crate::spline::curve::NurbsCurve;
use crate::spline::knots::find_span;
use smallvec::SmallVec;

/// A (non-rational) B-spline curve whose control points have `hdim` coordinates of type `S`.
///
/// A NURBS curve is represented by its homogeneous form Pw_i = (w_i P_i, w_i) (thesis eq. 3.7,
/// helper `H`): then `hdim = dim + 1` and the last row is the weight function w(u). For a
/// non-rational curve the weight row is left out (`rational == false`, w = 1).
/// Knots are f64 and exact: all knot differences are formed in `S`.
#[derive(Debug, Clone)]
pub struct HSpline<S> {
    /// degree (may reach 0 for high derivatives)
    pub degree: usize,
    /// knot vector, `npts + degree + 1` values
    pub knots: Vec<f64>,
    /// number of Cartesian coordinates d
    pub dim: usize,
    /// whether the last row is the weight row (hdim = dim + 1)
    pub rational: bool,
    /// control points, row-major, `hdim` values each
    pub pts: Vec<S>,
}

impl<S: Scalar> HSpline<S> {
    /// Homogeneous form of a NURBS curve (thesis helper `H`, eq. 3.7). For intervals the products
    /// w_i * P_ij are outward rounded, so the spline encloses the exact homogeneous curve.
    pub fn from_curve(c: &NurbsCurve) -> Self {
        let dim = c.dim();
        let rational = c.is_rational();
        let hdim = dim + rational as usize;
        let mut pts = Vec::with_capacity(c.num_points() * hdim);
        for i in 0..c.num_points() {
            let w = c.weight(i);
            for &x in c.control_point(i) {
                if rational {
                    pts.push(S::from_f64(w) * S::from_f64(x));
                } else {
                    pts.push(S::from_f64(x));
                }
            }
            if rational {
                pts.push(S::from_f64(w));
            }
        }
        HSpline {
            degree: c.degree(),
            knots: c.knots().to_vec(),
            dim,
            rational,
            pts,
        }
    }

    /// Coordinates per control point.
    #[inline]
    pub fn hdim(&self) -> usize {
        self.dim + self.rational as usize
    }

    /// Number of control points.
    #[inline]
    pub fn npts(&self) -> usize {
        self.pts.len() / self.hdim()
    }

    /// Exact span index of an f64 parameter.
    #[inline]
    pub fn span(&self, u: f64) -> usize {
        find_span(&self.knots, self.degree, self.npts() - 1, u)
    }

    /// de Boor corner cutting on span `k` (thesis CurvePntByCornerCut / NURBS Book A5.1-style
    /// triangle), all homogeneous rows, written into `out` (`hdim` values).
    ///
    /// This is [`HSpline::de_boor_column`] run to the end (a column of one point); both use the
    /// single level step [`HSpline::corner_cut_level`].
    /// For an interval `u` inside [u_k, u_{k+1}] the result encloses the curve over all of `u`
    /// (the polynomial piece is the same there; inclusion isotonicity of interval arithmetic).
    pub fn eval_span(&self, k: usize, u: &S, out: &mut Vec<S>) {
        self.de_boor_into(k, u, 1, out);
    }

    /// The de Boor scheme on span `k` stopped early (lab course "B-Spline-Kurven", sec. 3.1,
    /// method `de_boor(t, stop)`): the corner cutting runs until a column holds only `stop`
    /// points, and that column d^r_{k-p+r} .. d^r_k (r = p + 1 - stop) is returned, row-major,
    /// `hdim` values per point.
    ///
    /// `stop = p + 1` returns the control points of the span, `stop = 1` the curve point, and
    /// `stop = 2` the two points whose difference is the tangent direction (thesis sec. 7.2,
    /// listing `tang`). `stop` is clamped to `1..=p + 1`.
    /// The same enclosure property as [`HSpline::eval_span`] holds for interval `u`: each
    /// intermediate point is a polynomial in u over the span.
    pub fn de_boor_column(&self, k: usize, u: &S, stop: usize) -> Vec<S> {
        let mut out = Vec::new();
        self.de_boor_into(k, u, stop, &mut out);
        out
    }

    /// Shared body of [`HSpline::eval_span`] and [`HSpline::de_boor_column`].
    fn de_boor_into(&self, k: usize, u: &S, stop: usize, out: &mut Vec<S>) {
        let p = self.degree;
        let h = self.hdim();
        let levels = p + 1 - stop.clamp(1, p + 1);
        out.clear();
        out.extend_from_slice(&self.pts[(k - p) * h..(k + 1) * h]);
        for r in 1..=levels {
            self.corner_cut_level(k, r, u, out);
        }
        out.drain(..levels * h);
    }

    /// One level r (1 <= r <= p) of de Boor corner cutting on span `k`, in place on the
    /// triangle buffer `col` of p + 1 homogeneous points: position j (r <= j <= p, point index
    /// i = k - p + j) becomes d^r_i = alpha (d^{r-1}_i - d^{r-1}_{i-1}) + d^{r-1}_{i-1} with
    /// alpha = (u - u_i) / (u_{i+p+1-r} - u_i) (alpha_j^k of the lab course "B-Spline-Kurven",
    /// sec. 2.2; NURBS Book A5.1 triangle). Positions below r are left as they were.
    ///
    /// The convex combination is [`Scalar::lerp`] (thesis sec. 5.1 form, intersected with the
    /// convex form for intervals). The denominators u_{i+p+1-r} - u_i are >= u_{k+1} - u_k > 0.
    pub fn corner_cut_level(&self, k: usize, r: usize, u: &S, col: &mut [S]) {
        corner_cut_level(&self.knots, self.degree, k, r, u, self.hdim(), col);
    }

    /// Point and first derivative (Cartesian, `dim` values each) on span `k` by corner cutting,
    /// without derivative control points (thesis sec. 7.2, listing `tang`, made exact):
    /// the de Boor column with two points R0, R1 gives the homogeneous derivative
    /// A'(u) = p (R1 - R0) / (u_{k+1} - u_k) (blossoming; Farin, Curves and Surfaces, sec. on
    /// derivatives of B-splines), the last level gives the point A(u). For a rational curve
    /// C = A/w and C' = (A' - w' C) / w (thesis eq. 3.10 with k = 1).
    ///
    /// For degree 0 the derivative is 0. For an interval `u` inside the closed span both results
    /// enclose the exact values over all of `u` (every step is a rational function evaluated in
    /// interval arithmetic).
    pub fn tangent_span(&self, k: usize, u: &S) -> (Vec<S>, Vec<S>) {
        let p = self.degree;
        let h = self.hdim();
        let d = self.dim;
        if p == 0 {
            let pt = self.pts[k * h..(k + 1) * h].to_vec();
            return (
                crate::spline::eval::project(pt, d, self.rational),
                vec![S::zero(); d],
            );
        }
        let two = self.de_boor_column(k, u, 2);
        let f = knot_quotient(S::from_usize(p), self.knots[k], self.knots[k + 1]);
        let dh: Vec<S> = (0..h)
            .map(|c| f.clone() * (two[h + c].clone() - two[c].clone()))
            .collect();
        // The last level, on the two-point column placed at positions p-1, p of a triangle.
        let mut col = vec![S::zero(); (p - 1) * h];
        col.extend(two);
        self.corner_cut_level(k, p, u, &mut col);
        let ph = col[p * h..].to_vec();
        if !self.rational {
            return (ph, dh);
        }
        // C = A / w, C' = (A' - 1 w' C) / w: the shared quotient rule (the factor binom(1, 1)
        // = 1 is exact, so values are those of (A' - w' C) / w).
        let mut c = crate::spline::eval::quotient_rule(&[ph, dh], d).into_iter();
        let pt = c.next().unwrap();
        (pt, c.next().unwrap())
    }

    /// Like [`HSpline::eval_span`] but only for the homogeneous rows listed in `rows` (e.g. one
    /// coordinate and the weight row), without allocating once `buf` has grown: the values are
    /// returned as the slice `buf[p * rows.len()..]`, in the order of `rows`.
    pub fn eval_span_rows<'b>(
        &self,
        k: usize,
        u: &S,
        rows: &[usize],
        buf: &'b mut Vec<S>,
    ) -> &'b [S] {
        let p = self.degree;
        let h = self.hdim();
        let nr = rows.len();
        buf.clear();
        for i in k - p..=k {
            buf.extend(rows.iter().map(|&r| self.pts[i * h + r].clone()));
        }
        corner_cut(&self.knots, p, k, u, nr, buf);
        &buf[p * nr..]
    }

    /// Evaluate at an f64 parameter (span found exactly).
    pub fn eval(&self, u: f64) -> Vec<S> {
        let mut out = Vec::new();
        self.eval_span(self.span(u), &S::from_f64(u), &mut out);
        out
    }

    /// Derivative as a B-spline of degree p - 1 on knots u_1 .. u_{m-1} (thesis eq. 2.7):
    /// Q_i = p (P_{i+1} - P_i) / (u_{i+p+1} - u_{i+1}). A zero denominator means N_{i,p-1} == 0,
    /// and Q_i is set to 0 (the 0/0 := 0 convention of def. 1.2).
    /// The span index of u in the derivative is one less than in `self`.
    pub fn derivative(&self) -> HSpline<S> {
        let p = self.degree;
        let h = self.hdim();
        let n = self.npts();
        if p == 0 || n < 2 {
            // derivative of a piecewise constant: zero (no knots inside a span)
            return HSpline {
                degree: 0,
                knots: self.knots.clone(),
                dim: self.dim,
                rational: self.rational,
                pts: vec![S::zero(); self.pts.len()],
            };
        }
        let mut pts = Vec::with_capacity((n - 1) * h);
        let pp = S::from_usize(p);
        for i in 0..n - 1 {
            let d = self.knots[i + p + 1] - self.knots[i + 1];
            if d == 0.0 {
                pts.extend(std::iter::repeat_with(S::zero).take(h));
                continue;
            }
            let f = knot_quotient(pp.clone(), self.knots[i + 1], self.knots[i + p + 1]);
            for c in 0..h {
                pts.push(
                    f.clone() * (self.pts[(i + 1) * h + c].clone() - self.pts[i * h + c].clone()),
                );
            }
        }
        HSpline {
            degree: p - 1,
            knots: self.knots[1..self.knots.len() - 1].to_vec(),
            dim: self.dim,
            rational: self.rational,
            pts,
        }
    }

    /// The Bézier segment of span k (u_k < u_{k+1}) in homogeneous form, by clamping the local
    /// curve (p + 1 points, 2p + 2 knots, one span) at both ends with Boehm knot insertion
    /// (NURBS Book A5.1 CurveKnotIns applied locally; equivalent to A5.6 DecomposeCurve for one
    /// segment). Works for clamped and unclamped knot vectors alike. O(p^2).
    pub fn bezier_segment(&self, k: usize) -> BezierSeg<S> {
        self.bezier_segment_by(k, true)
    }

    /// [`HSpline::bezier_segment`] without the type's faster route
    /// ([`Scalar::clamp_span_fast`]): for `Ddi`, every corner cut with its own running error
    /// bound (tighter than the double-word route's a-priori bound, which is sized for the
    /// largest point; what the optimality certificate's double-double stage needs on near
    /// ties at high degree).
    pub fn bezier_segment_tight(&self, k: usize) -> BezierSeg<S> {
        self.bezier_segment_by(k, false)
    }

    fn bezier_segment_by(&self, k: usize, fast: bool) -> BezierSeg<S> {
        let p = self.degree;
        let h = self.hdim();
        let mut q: Vec<S> = self.pts[(k - p) * h..(k + 1) * h].to_vec();
        let mut t: SmallVec<[f64; 24]> = SmallVec::from_slice(&self.knots[k - p..=k + p + 1]);
        if fast {
            clamp_span(p, h, &mut t, &mut q);
        } else {
            clamp_span_by(p, h, &mut t, &mut q);
        }
        BezierSeg {
            a: self.knots[k],
            b: self.knots[k + 1],
            degree: p,
            dim: self.dim,
            rational: self.rational,
            pts: q,
        }
    }

    /// The Bézier segments' points of up to `count` consecutive non-empty spans from span k0
    /// (u_{k0} < u_{k0+1}), each handed to `emit(k, points)` in order, by one sweep of Boehm
    /// insertion (NURBS Book A5.6, [`sweep_spans`]; the type's faster route
    /// [`Scalar::sweep_fast`] where it applies). The same points as
    /// [`HSpline::bezier_segment`] of each span (enclosures of the same exact points), at
    /// about half its cost per span from the second span of the block on.
    pub fn bezier_sweep(&self, k0: usize, count: usize, emit: &mut dyn FnMut(usize, &[S])) {
        let (p, h) = (self.degree, self.hdim());
        if !S::sweep_fast(p, h, &self.knots, &self.pts, k0, count, emit) {
            sweep_spans(p, h, &self.knots, &self.pts, k0, count, emit);
        }
    }

    /// Insert the knot u `r` times (NURBS Book A5.1 CurveKnotIns; thesis eqs. 4.12, 4.15/4.16).
    /// Requires u in the domain; insertions beyond multiplicity p are ignored. The new points
    /// are convex combinations alpha*(Q_i - Q_{i-1}) + Q_{i-1}.
    pub fn insert_knot(&self, u: f64, r: usize) -> HSpline<S> {
        let p = self.degree;
        let h = self.hdim();
        let k = self.span(u);
        let total = crate::spline::knots::multiplicity(&self.knots, u);
        let r = r.min(p.saturating_sub(total));
        // A5.1 wants s = the copies of u among u_{k-p} ..= u_k (u in [u_k, u_{k+1})). At the
        // right end of the domain, u = u_{k+1} lies in the closed last span k and no copy of u
        // is at or below k (u_k < u_{k+1}): s = 0 there (Boehm's formula holds on the closed
        // span). Using the total multiplicity instead changed the curve of an unclamped
        // domain end.
        let s = if u == self.knots[k + 1] { 0 } else { total };
        if r == 0 {
            return self.clone();
        }
        let (knots, pts) = knot_ins(p, h, &self.knots, &self.pts, k, s, u, r);
        HSpline {
            degree: p,
            knots,
            dim: self.dim,
            rational: self.rational,
            pts,
        }
    }

    /// Bézier decomposition (NURBS Book A5.6 DecomposeCurve): one segment per non-empty span of
    /// the domain, in order.
    pub fn decompose(&self) -> Vec<BezierSeg<S>> {
        let p = self.degree;
        let n = self.npts() - 1;
        (p..=n)
            .filter(|&k| self.knots[k] < self.knots[k + 1])
            .map(|k| self.bezier_segment(k))
            .collect()
    }
}

/// A Bézier segment over [a, b] in homogeneous coordinates (local parameter t in [0, 1]).
#[derive(Debug, Clone)]
pub struct BezierSeg<S> {
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
    /// p + 1 homogeneous control points, row-major
    pub pts: Vec<S>,
}

impl<S: Scalar> BezierSeg<S> {
    /// Coordinates per control point.
    #[inline]
    pub fn hdim(&self) -> usize {
        self.dim + self.rational as usize
    }

    /// de Casteljau evaluation at local t (lecture "Modellierung mit Kurven"; all rows): the
    /// first point of the right half of the split at t, by the same corner cuts
    /// ([`crate::spline::bezier::de_casteljau_levels`]) without storing the halves.
    pub fn eval_local(&self, t: &S) -> Vec<S> {
        let h = self.hdim();
        let mut b = self.pts.clone();
        crate::spline::bezier::de_casteljau_levels(&mut b, h, t, |_, _| {});
        b.truncate(h);
        b
    }

    /// de Casteljau subdivision at local t: the control points of the halves over [0, t] and
    /// [t, 1], by the shared kernel [`crate::spline::bezier::de_casteljau_split`] (convex
    /// combinations in the a*(R1-R2)+R2 form; for intervals, also an interval t, both halves
    /// enclose the exact halves for every real t in `t`).
    pub fn split_points(&self, t: &S) -> (Vec<S>, Vec<S>) {
        crate::spline::bezier::de_casteljau_split(&self.pts, self.hdim(), t)
    }

    /// The control points of the piece over the local range [t0, t1] inside [0, 1], by two de
    /// Casteljau splits ([`BezierSeg::split_points`]): at `t1` (left part, over [0, t1]), then
    /// at `t0_rel` = t0 / t1 (right part of that). `None` skips a split (t1 = 1, t0 = 0). The
    /// callers pass enclosures of the split parameters (computing t0 / t1 in one step, e.g.
    /// (s0 - a) / (s1 - a), keeps it tight); for every exact parameter in them each split
    /// encloses the exact sub-segment, so the result encloses the points over [t0, t1].
    pub fn sub_points(&self, t1: Option<&S>, t0_rel: Option<&S>) -> Vec<S> {
        let h = self.hdim();
        // One-sided splits: the same corner cuts as `split_points` (so the same enclosures),
        // without building the half that is dropped. The left part's point r is entry 0 of
        // level r; the right part's point i is entry i of level p - i, which later levels
        // (entries below it only) leave in place, so the right part is the triangle computed
        // in place.
        let mut b = self.pts.clone();
        if let Some(t) = t1 {
            let mut left = Vec::with_capacity(b.len());
            left.extend_from_slice(&b[..h]);
            crate::spline::bezier::de_casteljau_levels(&mut b, h, t, |_, lv| {
                left.extend_from_slice(&lv[..h]);
            });
            b = left;
        }
        if let Some(t) = t0_rel {
            crate::spline::bezier::de_casteljau_levels(&mut b, h, t, |_, _| {});
        }
        b
    }

    /// de Casteljau split at local t into the segments over [0, t] and [t, 1] (the parameter
    /// bounds a, b of the halves are f64 approximations of the split point).
    pub fn split(&self, t: f64) -> (BezierSeg<S>, BezierSeg<S>) {
        let (left, right) = self.split_points(&S::from_f64(t));
        let m = self.a + t * (self.b - self.a);
        (
            BezierSeg {
                b: m,
                pts: left,
                ..self.clone_meta()
            },
            BezierSeg {
                a: m,
                pts: right,
                ..self.clone_meta()
            },
        )
    }

    /// The one-coordinate segment of Cartesian coordinate j: rows (w P_j, w), or (P_j).
    pub fn coord(&self, j: usize) -> BezierSeg<S> {
        let h = self.hdim();
        let mut pts = Vec::with_capacity((self.degree + 1) * (1 + self.rational as usize));
        for c in self.pts.chunks(h) {
            pts.push(c[j].clone());
            if self.rational {
                pts.push(c[self.dim].clone());
            }
        }
        BezierSeg {
            dim: 1,
            pts,
            ..self.clone_meta()
        }
    }

    fn clone_meta(&self) -> BezierSeg<S> {
        BezierSeg {
            a: self.a,
            b: self.b,
            degree: self.degree,
            dim: self.dim,
            rational: self.rational,
            pts: Vec::new(),
        }
    }
}

/// Reverse the order of the points of `q` (`h` rows each; rows stay together).
#[inline]
pub(crate) fn reverse_points<S: Clone>(h: usize, q: &mut [S]) {
    let n = q.len() / h;
    for i in 0..n / 2 {
        for c in 0..h {
            q.swap(i * h + c, (n - 1 - i) * h + c);
        }
    }
}

/// The Bézier points of one span in place (the body of [`HSpline::bezier_segment`], for
/// callers with their own, e.g. stack, buffers): `t` holds the 2p + 2 knots u_{k-p} ..= u_{k+p+1}
/// around the span, `q` its p + 1 local points (`h` values each, row-major); both ends are
/// clamped by Boehm knot insertion ([`clamp_left`], then the same on the mirrored curve:
/// reversed points, knots t'_j = -t_{2p+1-j}, negation is exact), after which `q` holds the
/// span's Bézier points. `t` is left in an unspecified state.
#[inline]
pub(crate) fn clamp_span<S: Scalar>(p: usize, h: usize, t: &mut [f64], q: &mut [S]) {
    if !S::clamp_span_fast(p, h, t, q) {
        clamp_span_by(p, h, t, q);
    }
}

/// [`clamp_span`] by the generic corner cuts in `S` itself (no faster route).
fn clamp_span_by<S: Scalar>(p: usize, h: usize, t: &mut [f64], q: &mut [S]) {
    clamp_left(p, h, t, q);
    reverse_points(h, q);
    t.reverse();
    t.iter_mut().for_each(|x| *x = -*x);
    clamp_left(p, h, t, q);
    reverse_points(h, q);
}

/// The four entries of `v` from `at` (one bounds check for the block, [`Scalar::lerp4`]).
#[inline(always)]
fn block4<S>(v: &[S], at: usize) -> &[S; 4] {
    v[at..at + 4].try_into().expect("a block of four entries")
}

/// Point i of a row-major buffer (`h` values per point) becomes the convex combination
/// lerp(alpha, P_i, P_{i+1}) (the corner cut of Boehm's knot insertion, NURBS Book A5.1).
#[inline]
fn lerp_next<S: Scalar>(buf: &mut [S], i: usize, h: usize, alpha: &S) {
    // (split once, then zipped rows: no index arithmetic or bounds check per value, which
    // cost more than a value's `Mr` lerp in the knot insertion of high-degree spans)
    let (lo, hi) = buf[i * h..(i + 2) * h].split_at_mut(h);
    for (l, r) in lo.iter_mut().zip(hi.iter()) {
        *l = S::lerp(alpha, l, r);
    }
}

/// Clamp a one-span local curve (p + 1 points, knots t_0..t_{2p+1}, span index p) at its left
/// end u = t_p by inserting u until its multiplicity is p, keeping only the p + 1 points and
/// 2p + 2 knots that still influence the span, in place.
///
/// This is NURBS Book A5.1 CurveKnotIns with k = p, s = the copies of u among t_0..t_p and
/// r = p - s insertions, specialised to what survives the cut: the points with index >= r of
/// A5.1's result are exactly the local points after the in-place steps
/// `P_i <- lerp(alpha, P_i, P_{i+1})`, i = 0..=p-j-s, for j = 1..=r, with
/// alpha = (u - t_{j+i}) / (t_{i+p+1} - t_{j+i}) on the original knots (A5.1 writes step j's
/// `Rw[0]` and `Rw[p-j-s]` to Q_j and Q_{p+r-j-s}; index m = p-s-j of the kept points is last
/// touched by step j, later steps touch smaller indices only); the kept knots are
/// t_{p-s}, u (p times), t_{p+1}..t_{2p+1}.
#[inline]
fn clamp_left<S: Scalar>(p: usize, h: usize, t: &mut [f64], q: &mut [S]) {
    let u = t[p];
    let s = t[..=p].iter().rev().take_while(|&&x| x == u).count();
    if s >= p {
        return;
    }
    let r = p - s;
    let mut aexp: SmallVec<[S; 64]> = SmallVec::new();
    for j in 1..=r {
        if S::SWEEP_BLOCKS {
            // (ascending: Q_{i+1} is still the previous step's when Q_i is cut; blocks of four
            // entries read x and x + h before their writes, as `sweep_spans`' blocks)
            aexp.clear();
            for i in 0..=p - j - s {
                let a = S::knot_ratio_f64(u, t[j + i], t[i + p + 1]);
                for _ in 0..h {
                    aexp.push(a.clone());
                }
            }
            let end = aexp.len();
            let mut x = 0;
            while x + 4 <= end {
                let v = S::lerp4(block4(&aexp, x), block4(q, x), block4(q, x + h));
                q[x..x + 4].clone_from_slice(&v);
                x += 4;
            }
            for x in x..end {
                q[x] = S::lerp(&aexp[x], &q[x], &q[x + h]);
            }
            continue;
        }
        for i in 0..=p - j - s {
            lerp_next(q, i, h, &S::knot_ratio_f64(u, t[j + i], t[i + p + 1]));
        }
    }
    t[0] = t[p - s];
    t[1..=p].iter_mut().for_each(|x| *x = u);
}

/// The last index e of the run of knots equal to u_{k+1}: span e = [u_e, u_{e+1}] is the
/// non-empty span after span k, if e <= n ([`sweep_spans`]' stepping).
pub(crate) fn run_end(knots: &[f64], k: usize) -> usize {
    let mut e = k + 1;
    while e + 1 < knots.len() && knots[e + 1] == knots[k + 1] {
        e += 1;
    }
    e
}

/// The Bézier points of up to `count` consecutive non-empty spans, the first being span k0
/// (u_{k0} < u_{k0+1}), handed to `emit(k, points)` in order (`h` values per point, row-major):
/// NURBS Book A5.6 DecomposeCurve, started at any span of any (also unclamped) knot vector.
///
/// Span k0's local points are first clamped at its left end ([`clamp_left`]). Then, span by
/// span, the right end u_{k+1} (multiplicity `mult` among the knots that follow) is inserted
/// until its multiplicity is p: with the left end already of multiplicity p, the ratio of every
/// corner cut is (u_{k+1} - u_k) / (u_{k+j} - u_k), so the p - mult ratios are formed once per
/// span (A5.6's `alphas`), and the points that step j of the insertion leaves at the right
/// end are the next span's left points (A5.6's `Qw[nb+1][save]`; its other points are the
/// original P_{e-p+i}, i >= p - mult, e the run's last index). Each span thus costs one end's
/// insertion, (p - mult)(p - mult + 1)/2 corner cuts of `h` values and p - mult ratios, against
/// both ends' and a ratio per corner cut in [`clamp_span`].
///
/// Every step is a corner cut lerp(alpha, Q_{i-1}, Q_i) with alpha in [0, 1] a ratio of knot
/// differences ([`Scalar::knot_ratio_f64`]: u_k < u_{k+1} <= u_{k+j}), as in [`clamp_left`]: so
/// enclosing types (`Ddi`, `Mr`, intervals) enclose the exact points, and the double words
/// of `num::dw` keep their running bound (its guard checked by the caller). The chain of
/// operations behind a span's points grows with its position in the sweep (a span's left
/// points come from its predecessor's), which is why callers sweep short blocks.
pub(crate) fn sweep_spans<S: Scalar>(
    p: usize,
    h: usize,
    knots: &[f64],
    pts: &[S],
    k0: usize,
    count: usize,
    emit: &mut dyn FnMut(usize, &[S]),
) {
    let n = pts.len() / h - 1;
    debug_assert!(p <= k0 && k0 <= n && knots[k0] < knots[k0 + 1]);
    // (on the stack for the usual degrees and dimensions)
    let mut q: SmallVec<[S; 32]> = pts[(k0 - p) * h..(k0 + 1) * h].iter().cloned().collect();
    let mut t: SmallVec<[f64; 24]> = SmallVec::from_slice(&knots[k0 - p..=k0 + p + 1]);
    clamp_left(p, h, &mut t, &mut q);
    let mut next = q.clone();
    let mut alphas: SmallVec<[S; 16]> = SmallVec::new();
    let mut aexp: SmallVec<[S; 64]> = SmallVec::new();
    let (mut k, mut done) = (k0, 0);
    loop {
        let (a, ub) = (knots[k], knots[k + 1]);
        let e = run_end(knots, k);
        let mult = e - k;
        // (span e = [u_e, u_{e+1}] is the next non-empty span if e <= n)
        let more = done + 1 < count && e <= n;
        if mult < p {
            alphas.clear();
            // alphas[j - mult - 1] = (u_{k+1} - u_k) / (u_{k+j} - u_k), j = mult + 1 ..= p
            alphas.extend((mult + 1..=p).map(|j| S::knot_ratio_f64(ub, a, knots[k + j])));
            let r = p - mult;
            if S::SWEEP_BLOCKS {
                // (per entry its ratio: entry m h + row of a step starting at point s has
                // alphas[m], so the blocks below read them without a division by h)
                aexp.clear();
                for a in &alphas {
                    for _ in 0..h {
                        aexp.push(a.clone());
                    }
                }
            }
            // (slices taken once: indexing the small vectors themselves tests where their
            // storage is at every access)
            let ae: &[S] = &aexp;
            for j in 1..=r {
                let s = mult + j;
                let qs: &mut [S] = &mut q;
                // (descending: Q_{i-1} is still the previous step's when Q_i is cut)
                let (start, mut end) = (s * h, (p + 1) * h);
                // Blocks of four entries from the top (`Scalar::SWEEP_BLOCKS`), every read of a
                // block (entries x and x - h, none above the block) before its writes: each
                // entry is cut from the previous step's values exactly as in the order below.
                while S::SWEEP_BLOCKS && end >= start + 4 {
                    let b = end - 4;
                    let v = S::lerp4(block4(ae, b - start), block4(qs, b - h), block4(qs, b));
                    qs[b..end].clone_from_slice(&v);
                    end = b;
                }
                // (the points below the blocks: from the one holding entry end - 1 down, the
                // entries at or above `end` being done)
                let top = if end > start {
                    ((end - 1) / h).min(p)
                } else {
                    0
                };
                for i in (s..=top).rev() {
                    let (lo, hi) = qs[(i - 1) * h..(i + 1) * h].split_at_mut(h);
                    for (row, (x, l)) in hi.iter_mut().zip(lo.iter()).enumerate() {
                        if i * h + row < end {
                            *x = S::lerp(&alphas[i - s], l, x);
                        }
                    }
                }
                if more {
                    next[(r - j) * h..(r - j + 1) * h].clone_from_slice(&qs[p * h..(p + 1) * h]);
                }
            }
        }
        emit(k, &q);
        done += 1;
        if !more {
            return;
        }
        let first = p.saturating_sub(mult);
        next[first * h..].clone_from_slice(&pts[(e + first - p) * h..(e + 1) * h]);
        std::mem::swap(&mut q, &mut next);
        k = e;
    }
}

/// NURBS Book A5.1 CurveKnotIns: insert u (in span k, multiplicity s) r times, r + s <= p.
/// Returns the new knots and points.
#[allow(clippy::too_many_arguments)]
fn knot_ins<S: Scalar>(
    p: usize,
    h: usize,
    up: &[f64],
    pw: &[S],
    k: usize,
    s: usize,
    u: f64,
    r: usize,
) -> (Vec<f64>, Vec<S>) {
    let np = pw.len() / h - 1;
    let nq = np + r;
    let mut uq = Vec::with_capacity(up.len() + r);
    uq.extend_from_slice(&up[..=k]);
    uq.extend(std::iter::repeat_n(u, r));
    uq.extend_from_slice(&up[k + 1..]);
    let mut qw: Vec<S> = vec![S::zero(); (nq + 1) * h];
    qw[..(k - p + 1) * h].clone_from_slice(&pw[..(k - p + 1) * h]);
    for i in k - s..=np {
        qw[(i + r) * h..(i + r + 1) * h].clone_from_slice(&pw[i * h..(i + 1) * h]);
    }
    let mut rw: Vec<S> = pw[(k - p) * h..(k - s + 1) * h].to_vec();
    let mut l = 0;
    for j in 1..=r {
        l = k - p + j;
        for i in 0..=p - j - s {
            lerp_next(
                &mut rw,
                i,
                h,
                &S::knot_ratio_f64(u, up[l + i], up[i + k + 1]),
            );
        }
        qw[l * h..(l + 1) * h].clone_from_slice(&rw[0..h]);
        let e = k + r - j - s;
        qw[e * h..(e + 1) * h].clone_from_slice(&rw[(p - j - s) * h..(p - j - s + 1) * h]);
    }
    for i in l + 1..k - s {
        qw[i * h..(i + 1) * h].clone_from_slice(&rw[(i - l) * h..(i - l + 1) * h]);
    }
    (uq, qw)
}

/// de Boor corner cutting (thesis CurvePntByCornerCut, NURBS Book A5.1-style triangle) in place
/// on `buf`, which holds the p + 1 local control points P_{k-p} .. P_k of span k with `h` rows
/// each; afterwards the value at `u` is in `buf[p * h..(p + 1) * h]`.
///
/// Each step is the convex combination written as alpha*(R1 - R2) + R2 (thesis sec. 5.1),
/// which in interval arithmetic overestimates less than alpha*R1 + (1 - alpha)*R2.
/// The denominators u_{i+p+1-r} - u_i are >= u_{k+1} - u_k > 0, so never zero.
/// For an interval `u` inside [u_k, u_{k+1}] the result encloses the piece over all of `u`
/// (the polynomial piece is the same there; inclusion isotonicity of interval arithmetic).
pub fn corner_cut<S: Scalar>(knots: &[f64], p: usize, k: usize, u: &S, h: usize, buf: &mut [S]) {
    for r in 1..=p {
        corner_cut_level(knots, p, k, r, u, h, buf);
    }
}

/// One level r of de Boor corner cutting on span k (see [`HSpline::corner_cut_level`]), on a
/// buffer of p + 1 points with `h` rows each.
pub fn corner_cut_level<S: Scalar>(
    knots: &[f64],
    p: usize,
    k: usize,
    r: usize,
    u: &S,
    h: usize,
    col: &mut [S],
) {
    // alpha for level r, position j (i = k - p + j): (u - u_i) / (u_{i+p+1-r} - u_i)
    for j in (r..=p).rev() {
        let i = k - p + j;
        let a = knot_ratio(u, knots[i], knots[i + p + 1 - r]);
        for c in 0..h {
            let hi = col[j * h + c].clone();
            let lo = col[(j - 1) * h + c].clone();
            col[j * h + c] = S::lerp(&a, &lo, &hi);
        }
    }
}

/// Below this magnitude a knot difference cannot overflow (2^1022, half of the f64 range).
const HALF_MAX: f64 = 4.494_232_837_155_79e307; // 2^1022 exactly

/// Whether a difference of the knots (or parameters) a and b may overflow f64: |b - a| >= 2^1022
/// (an f64 difference that rounds to inf compares as >= too; a NaN cannot arise from finite
/// knots, and would count as overflowing).
#[inline]
pub(crate) fn may_overflow(a: f64, b: f64) -> bool {
    !(b - a).abs().lt(&HALF_MAX)
}

/// x - a, or x/2 - a/2 when `half` (see [`knot_ratio`]).
#[inline]
fn knot_diff<S: Scalar>(x: S, a: f64, half: bool) -> S {
    if half {
        let h = S::from_f64(0.5);
        x * h.clone() - S::from_f64(a) * h
    } else {
        x - S::from_f64(a)
    }
}

/// The knot ratio (x - a) / (b - a) of de Boor's and Boehm's alphas, for knots a < b and x in
/// [a, b], without overflow.
///
/// Knots are finite, but the difference of two of opposite sign near ±f64::MAX is not: in
/// f64 it becomes inf and the ratio 0 or NaN (a wrong but finite-looking point), in interval
/// arithmetic [MAX, inf] (sound, but useless). When |b - a| >= 2^1022 both differences are
/// formed from halved operands instead, (x/2 - a/2) / (b/2 - a/2), which equals the ratio in
/// exact arithmetic and cannot overflow (|b/2 - a/2| <= MAX). Halving is exact except for a
/// subnormal operand, where it rounds by at most 2^-1075; a verified `S` (intervals, `Ddi`,
/// `Mr`) encloses that rounding (outward rounded products, underflow included), and against
/// a denominator >= 2^1021 it is far below one ulp of the ratio.
#[inline]
pub fn knot_ratio<S: Scalar>(x: &S, a: f64, b: f64) -> S {
    let half = may_overflow(a, b);
    knot_diff(x.clone(), a, half) / knot_diff(S::from_f64(b), a, half)
}

/// num / (b - a) for knots a < b without overflow: (num / 2) / (b/2 - a/2) when the
/// difference may overflow (the derivative factors p / (u_{i+p+1} - u_{i+1}) of eq. 2.7).
#[inline]
pub fn knot_quotient<S: Scalar>(num: S, a: f64, b: f64) -> S {
    let half = may_overflow(a, b);
    if half {
        num * S::from_f64(0.5) / knot_diff(S::from_f64(b), a, true)
    } else {
        num / (S::from_f64(b) - S::from_f64(a))
    }
}

/// All non-zero basis functions N_{k-p,p}(u) .. N_{k,p}(u) on span k (NURBS Book A2.2
/// BasisFuns; thesis CurvePoint2). The denominator right[r+1] + left[j-r] is formed directly as
/// the knot difference u_{k+r+1} - u_{k+1-j+r} (no u in it), which avoids the interval
/// dependency problem; it is > 0 for a non-empty span.
pub fn basis_funs<S: Scalar>(knots: &[f64], k: usize, u: &S, p: usize) -> Vec<S> {
    let mut n = vec![S::zero(); p + 1];
    n[0] = S::one();
    let mut left = vec![S::zero(); p + 1];
    let mut right = vec![S::zero(); p + 1];
    // All differences below are of the knots u_{k+1-p} ..= u_{k+p} and u in [u_k, u_{k+1}]:
    // halved together when their spread may overflow (see `knot_ratio`); every N is a ratio
    // of such differences, so the common factor cancels.
    let half = may_overflow(knots[k + 1 - p], knots[k + p]);
    let d = |x: S, a: f64| knot_diff(x, a, half);
    for j in 1..=p {
        left[j] = d(u.clone(), knots[k + 1 - j]);
        right[j] = -d(u.clone(), knots[k + j]);
        let mut saved = S::zero();
        for r in 0..j {
            let temp = n[r].clone() / d(S::from_f64(knots[k + r + 1]), knots[k + 1 - j + r]);
            n[r] = saved + right[r + 1].clone() * temp.clone();
            saved = left[j - r].clone() * temp;
        }
        n[j] = saved;
    }
    n
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::iv;
    use inari::Interval;

    /// The sweep of NURBS Book A5.6 gives each span's Bézier points: on exact rationals the
    /// very points of the per-span extraction `bezier_segment` (every start span, blocks of
    /// 1, 2, 3 and all spans), on random curves of the test families (unclamped, multiple and
    /// clustered knots, weights); and the `Ddi` sweep (its double-word route from degree 2, and
    /// the `Ddi` arithmetic itself) and the `Mr` sweep enclose those exact points.
    #[test]
    fn sweep_gives_every_span_s_bezier_points() {
        use crate::num::ddi::Ddi;
        use crate::num::exact::Exact;
        use crate::num::mr::Mr;
        use crate::testkit::gen::Family;
        use rand::SeedableRng;
        let contains = |x: &Exact, v: Interval| {
            x.cmp_f64(v.inf()) != Some(std::cmp::Ordering::Less)
                && x.cmp_f64(v.sup()) != Some(std::cmp::Ordering::Greater)
        };
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(23);
        let (mut spans, mut fast) = (0, 0);
        let fams = [
            Family::ClampedUniform,
            Family::ClusteredKnots,
            Family::MultipleKnots,
            Family::Unclamped,
            Family::ExtremeWeights,
            Family::ExtremaAtKnots,
            Family::Mixed,
        ];
        for it in 0..140 {
            let c = fams[it % fams.len()].curve(&mut r);
            if c.degree() > 9 {
                continue;
            }
            let (he, hd, hm) = (
                HSpline::<Exact>::from_curve(&c),
                HSpline::<Ddi>::from_curve(&c),
                HSpline::<Mr>::from_curve(&c),
            );
            let (p, n) = (c.degree(), c.num_points() - 1);
            let kn = c.knots();
            let nonempty: Vec<usize> = (p..=n).filter(|&k| kn[k] < kn[k + 1]).collect();
            for (i, &k0) in nonempty.iter().enumerate() {
                for count in [1, 2, 3, usize::MAX] {
                    let mut want: Vec<usize> = nonempty[i..].to_vec();
                    want.truncate(count);
                    let mut got = Vec::new();
                    he.bezier_sweep(k0, count, &mut |k, q| got.push((k, q.to_vec())));
                    let ks: Vec<usize> = got.iter().map(|g| g.0).collect();
                    assert_eq!(ks, want, "spans of the sweep from {k0}, count {count}");
                    for (k, q) in &got {
                        assert!(
                            *q == he.bezier_segment(*k).pts,
                            "exact points of span {k} (from {k0}), curve {c:?}"
                        );
                    }
                    let mut check = |k: usize, v: Vec<Interval>| {
                        let q = &got[ks.iter().position(|&x| x == k).unwrap()].1;
                        for (x, iv) in q.iter().zip(&v) {
                            assert!(contains(x, *iv), "span {k}: {iv:?} misses the exact point");
                        }
                        spans += 1;
                    };
                    let mut dd = Vec::new();
                    let fast_ran =
                        Ddi::sweep_fast(p, hd.hdim(), kn, &hd.pts, k0, count, &mut |k, q| {
                            dd.push((k, q.iter().map(Ddi::to_interval).collect::<Vec<_>>()))
                        });
                    fast += fast_ran as usize;
                    sweep_spans(p, hd.hdim(), kn, &hd.pts, k0, count, &mut |k, q| {
                        dd.push((k, q.iter().map(Ddi::to_interval).collect()))
                    });
                    hm.bezier_sweep(k0, count, &mut |k, q| {
                        dd.push((k, q.iter().map(Mr::to_interval).collect()))
                    });
                    assert_eq!(dd.len(), got.len() * (2 + fast_ran as usize));
                    for (k, v) in dd {
                        check(k, v);
                    }
                }
            }
        }
        assert!(
            spans > 2000 && fast > 300,
            "{spans} spans, {fast} double-word sweeps"
        );
    }

    /// The one-sided splits of `sub_points` give exactly the points of the two full splits
    /// they replace (the same corner cuts in the same order), for `Mr` and `Ddi`, rational and
    /// polynomial, with and without either split.
    #[test]
    fn sub_points_equal_the_two_full_splits() {
        use crate::num::ddi::Ddi;
        use crate::num::mr::Mr;
        fn check<S: Scalar + PartialEq + std::fmt::Debug>(seg: &BezierSeg<S>, t1: S, t0: S) {
            let full = |t1: Option<&S>, t0: Option<&S>| {
                let pts = t1.map_or(seg.pts.clone(), |t| seg.split_points(t).0);
                match t0 {
                    Some(t) => {
                        BezierSeg {
                            pts,
                            ..seg.clone_meta()
                        }
                        .split_points(t)
                        .1
                    }
                    None => pts,
                }
            };
            for (a, b) in [
                (Some(&t1), Some(&t0)),
                (Some(&t1), None),
                (None, Some(&t0)),
                (None, None),
            ] {
                assert_eq!(seg.sub_points(a, b), full(a, b));
            }
        }
        let rational = {
            let c = cubic();
            let pts = (0..c.num_points())
                .map(|i| c.control_point(i).to_vec())
                .collect();
            let w = vec![1.0, 0.3, 2.5, 0.7, 1.1, 0.9];
            NurbsCurve::new(3, c.knots().to_vec(), pts, Some(w)).unwrap()
        };
        for c in [cubic(), rational] {
            for k in 3..=5 {
                let seg = HSpline::<Mr>::from_curve(&c).bezier_segment(k);
                check(&seg, Mr::from_bounds(0.7, 0.7 + 1e-15), Mr::from_f64(0.3));
                let seg = HSpline::<Ddi>::from_curve(&c).bezier_segment(k);
                check(&seg, Ddi::from_f64(0.7), Ddi::from_f64(1.0 / 3.0));
            }
        }
    }

    fn cubic() -> NurbsCurve {
        NurbsCurve::new(
            3,
            vec![0., 0., 0., 0., 0.3, 0.7, 1., 1., 1., 1.],
            vec![
                vec![0., 0.],
                vec![1., 2.],
                vec![2., -1.],
                vec![3., 3.],
                vec![4., 0.],
                vec![5., 1.],
            ],
            Some(vec![1., 2., 0.5, 1., 3., 1.]),
        )
        .unwrap()
    }

    #[test]
    fn de_boor_columns_shrink_to_the_point() {
        let h = HSpline::<f64>::from_curve(&cubic());
        let u = 0.45;
        let k = h.span(u);
        let hd = h.hdim();
        assert_eq!(
            h.de_boor_column(k, &u, 4),
            h.pts[(k - 3) * hd..(k + 1) * hd].to_vec()
        );
        for stop in 1..=4 {
            assert_eq!(h.de_boor_column(k, &u, stop).len(), stop * hd);
        }
        assert_eq!(h.de_boor_column(k, &u, 1), h.eval(u));
        // stop beyond p + 1 is clamped
        assert_eq!(h.de_boor_column(k, &u, 9).len(), 4 * hd);
        // the point lies on the segment between the two points of the stop = 2 column
        let two = h.de_boor_column(k, &u, 2);
        let a = (u - h.knots[k]) / (h.knots[k + 1] - h.knots[k]);
        let pt = h.eval(u);
        for c in 0..hd {
            assert!((two[c] + a * (two[hd + c] - two[c]) - pt[c]).abs() < 1e-14);
        }
    }

    #[test]
    fn tangent_by_corner_cutting_matches_derivative_splines() {
        let c = cubic();
        let hf = HSpline::<f64>::from_curve(&c);
        let hi = HSpline::<Interval>::from_curve(&c);
        for i in 0..=50 {
            let u = i as f64 / 50.0;
            let k = hf.span(u);
            let (p, d) = hf.tangent_span(k, &u);
            let want: Vec<f64> = c.derivative(u, 1).unwrap();
            let wp: Vec<f64> = c.point(u).unwrap();
            let (pi, di) = hi.tangent_span(k, &iv::point(u));
            for j in 0..2 {
                assert!(
                    (d[j] - want[j]).abs() < 1e-11 * (1.0 + want[j].abs()),
                    "u={u}"
                );
                assert!((p[j] - wp[j]).abs() < 1e-13);
                assert!(di[j].contains(d[j]) && pi[j].contains(p[j]));
            }
        }
        // an interval parameter inside a span encloses the samples
        let k = hf.span(0.4);
        let (_, di) = hi.tangent_span(k, &iv::span(0.35, 0.6));
        for i in 0..=20 {
            let u = 0.35 + 0.25 * i as f64 / 20.0;
            let (_, d) = hf.tangent_span(k, &u);
            assert!(di[0].inf() <= d[0] + 1e-12 && d[0] - 1e-12 <= di[0].sup());
        }
    }
}
