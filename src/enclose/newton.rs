//! The thesis's interval Newton box enclosure (ch. 6; listings `inewtonKNRH` and `main` of
//! sec. 7.1.2), made sound and tight.
//!
//! Per coordinate j, the extreme values of C_j over the domain are attained at
//! (a) the domain end points, (b) the non-differentiable knots (multiplicity >= p, thesis ch. 6),
//! or (c) zeros of C_j'. Zeros of C_j' are searched per knot span (where the curve is one
//! polynomial / rational piece) with the interval Newton method (thesis sec. 5.2, theorem 5.1;
//! Moore, Hansen): N(X) = m - f(m) / f'(X), intersected with X, with the extended (two-piece)
//! division (thesis `divideKNR`, eq. in sec. 5.1; inari `mul_rev_to_pair`).
//!
//! Differences to the thesis, all for soundness or tightness (the [`Newton::thesis`] preset turns
//! the optional ones off):
//! * nothing is ever dropped: a box Newton cannot resolve within the limits is enclosed as a
//!   whole (the thesis drops boxes whose radius is still above `tol` after 20 steps);
//! * discontinuities (interior multiplicity p + 1) contribute both one-sided limits;
//! * by default f is the numerator g = A_j' w - A_j w' of C_j' = g / w^2 (same zeros, as w > 0;
//!   a polynomial, so no quotient-rule overestimation), with g' = A_j'' w - A_j w'';
//!   the thesis's C_j' / C_j'' (listing `Diff_intKNR`, eq. 3.10) is [`DerivForm::Quotient`];
//! * cheap monotonicity pre-tests skip most spans, and a span whose local control points lie
//!   inside the box found so far is skipped (convex hull property, thesis prop. 2.1);
//! * by default f, f' and the values over a box come from the span's Bernstein form
//!   ([`Newton::bernstein`]: the Bézier points of C_j - c, c a control point value of the
//!   span, and the Bernstein coefficients of the derivative numerator, restricted to the box by
//!   de Casteljau): no dependency-effect growth of interval de Boor over wide boxes, and no
//!   cancellation for nearly flat coordinates (extreme weights, flat runs), where interval
//!   de Boor on the homogeneous rows cannot tell f from 0 and the search used to stop at its
//!   limits with the control-hull bound;
//! * candidate values use the mean-value form C(m) + C'(X)(X - m), which is tight at a
//!   critical point (C' ~ 0 there).

use super::{
    BoxEncloser, CandidateKind, CoordBox, Enclosure, Extremum, Guarantee, Stats, Termination,
};
use crate::num::ddi::Ddi;
use crate::num::mr::Mr;
use crate::num::{iv, Scalar};
use crate::spline::bspline::{BezierSeg, HSpline};
use crate::spline::curve::NurbsCurve;
use crate::spline::eval::CurveEval;
use crate::spline::knots::multiplicity;
use crate::spline::tight::TightEval;
use inari::Interval;
use std::time::Instant;

/// How a box is subdivided when a Newton step makes too little progress.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Split {
    /// two halves
    Bisect,
    /// this many equal pieces (at least 2)
    Pieces(usize),
    /// 2p equal pieces (thesis listing `inewtonKNRH`, its split when a Newton step is empty)
    TwiceDegree,
}

/// Which function the Newton iteration is applied to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DerivForm {
    /// f = A_j' w - A_j w' (numerator of C_j' = f / w^2), f' = A_j'' w - A_j w'': polynomials.
    Numerator,
    /// f = C_j', f' = C_j'' by the quotient rule (thesis `Diff_intKNR`, eq. 3.10).
    Quotient,
}

/// Settings of the interval Newton strategy.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Newton {
    /// Stop refining a box when its radius is <= `tol` times the length of its knot span
    /// (thesis: `tol` on the radius, absolute, with domains [0, 1]; relative to the span, tiny
    /// spans, where C' is huge, still get small boxes).
    pub tol: f64,
    /// Keep iterating on a box with a uniqueness proof until the Newton step makes no progress
    /// (machine precision; costs one or two quadratically convergent steps).
    pub refine_unique: bool,
    /// Newton steps per box (thesis: 20).
    pub max_iter: u32,
    /// Boxes per coordinate; the rest is enclosed as a whole.
    pub max_boxes: usize,
    /// Work budget per coordinate, in evaluations times (p + 1)^2 (the cost of one interval
    /// de Boor evaluation), plus an allowance per span of [`EVALS_PER_SPAN`] evaluations but
    /// at most [`WORK_PER_SPAN`] units (and at least 8 evaluations in all):
    /// once spent, every box still to search is enclosed as a whole (sound, maybe less tight;
    /// reported as [`Termination::WorkLimit`]). Bounds the time of high-degree curves, whose
    /// interval evaluations are expensive and overestimate a lot.
    pub max_work: u64,
    /// Split rule when a step makes too little progress.
    pub split: Split,
    /// Split when a step leaves more than this fraction of the width (1.0: only when it makes
    /// no progress at all, as the thesis).
    pub min_shrink: f64,
    /// Splits per span (the thesis splits once, into 2p pieces; then a box that makes no
    /// progress just runs out of steps and is enclosed whole).
    pub max_splits: u32,
    /// Drop a Newton box whose values provably lie between values the curve attains (branch
    /// and bound; not in the thesis).
    pub drop_covered: bool,
    /// Function iterated on.
    pub form: DerivForm,
    /// Skip spans that are provably monotone (local control points monotone, or 0 outside the
    /// enclosure of f over the span).
    pub pretest: bool,
    /// Skip spans whose local control points lie inside the box found so far.
    pub prune: bool,
    /// Per span, before the Newton search, extract the Bézier points (Boehm knot insertion in
    /// fast midpoint-radius arithmetic, [`crate::Mr`]) and skip the span if they are monotone
    /// (with `pretest`) or lie inside the box found so far (with `prune`): far sharper than the
    /// B-spline control points at high degree, where p + 1 local control points spread over
    /// p + 1 spans (not in the thesis).
    pub bezier_pretest: bool,
    /// Evaluate f, f' and the values of C_j over Newton boxes from the span's Bernstein form
    /// (Bézier points of C_j - c with c a control point value of the
    /// span, and the Bernstein coefficients of the derivative numerator, in [`Mr`]) instead of
    /// interval de Boor over the box: the hull of the coefficients of the form restricted to a
    /// box (de Casteljau) overestimates the range by O(width^2), and the shift by c removes the
    /// cancellation of nearly flat coordinates (extreme weights, flat runs), where interval
    /// de Boor on the homogeneous rows cannot tell f from 0. The search then runs in the
    /// span's local parameter t in [0, 1] (finer than the f64 values of u on tiny spans far
    /// from 0), and the candidate boxes also get the double-double hull of their Bézier points.
    /// Also a pre-test: coefficients of one sign prove the span monotone. Degrees up to 256 (above, interval de Boor; not in
    /// the thesis).
    pub bernstein: bool,
    /// Measure the time spent in derivative evaluations (two clock reads per evaluation).
    pub time_derivatives: bool,
}

/// Default of [`Newton::max_work`] (a few tenths of a second of interval evaluations: one unit, a
/// corner cut of the value and of a derivative level, costs ~100-200 ns).
pub const DEFAULT_MAX_WORK: u64 = 2_000_000;

/// Evaluations allowed per span on top of [`Newton::max_work`], so that the budget grows with
/// the size of the input.
pub const EVALS_PER_SPAN: u64 = 64;

/// Highest degree for `Newton::bernstein` (the binomial ratios of the derivative numerator
/// stay far from overflow; above, interval de Boor is used).
pub(crate) const BERNSTEIN_MAX_DEGREE: usize = 256;

/// Cap of the per-span allowance in work units (64 evaluations of a degree-40 span).
pub const WORK_PER_SPAN: u64 = 64 * 41 * 41;

impl Default for Newton {
    fn default() -> Self {
        Newton {
            tol: 1e-12,
            refine_unique: true,
            max_iter: 40,
            max_boxes: 2000,
            max_work: DEFAULT_MAX_WORK,
            split: Split::Bisect,
            min_shrink: 0.5,
            max_splits: u32::MAX,
            drop_covered: true,
            form: DerivForm::Numerator,
            pretest: true,
            prune: true,
            bezier_pretest: true,
            bernstein: true,
            time_derivatives: false,
        }
    }
}

impl Newton {
    /// The thesis's settings (sec. 7.1.2, listing `inewtonKNRH`): C' / C'' by the quotient
    /// rule, split once per span into 2p pieces when a step makes no progress, 20 steps per box,
    /// stop at radius <= tol (the thesis does not state its tol; 1e-6 is assumed), every span
    /// searched (no pre-tests, no pruning), derivative time measured (its tables' columns).
    /// Unlike the thesis, unresolved boxes are kept (enclosed as a whole), so it stays sound.
    pub fn thesis() -> Self {
        Newton {
            tol: 1e-6,
            refine_unique: false,
            max_iter: 20,
            max_boxes: 10_000,
            max_work: DEFAULT_MAX_WORK,
            split: Split::TwiceDegree,
            min_shrink: 1.0,
            max_splits: 1,
            drop_covered: false,
            form: DerivForm::Quotient,
            pretest: false,
            prune: false,
            bezier_pretest: false,
            bernstein: false,
            time_derivatives: true,
        }
    }

    /// Default settings with another tolerance.
    /// A negative or NaN `tol` is replaced by the default.
    pub fn with_tol(tol: f64) -> Self {
        let d = Newton::default();
        Newton {
            tol: if tol >= 0.0 { tol } else { d.tol },
            ..d
        }
    }
}

impl BoxEncloser for Newton {
    fn name(&self) -> &'static str {
        "newton"
    }
    fn guarantee(&self) -> Guarantee {
        Guarantee::Verified
    }
    fn enclose(&self, c: &NurbsCurve) -> Enclosure {
        let mut e = Engine::new(c, self);
        let mode = if self.prune {
            SpanMode::Prune
        } else {
            SpanMode::Search
        };
        let mut modes = vec![mode; e.spans.len()];
        let coords = (0..c.dim())
            .map(|j| {
                // Search the spans around the extreme control points first: their candidates
                // make the box big early, so pruning skips more of the others.
                let first = [extreme_point(c, j, true), extreme_point(c, j, false)];
                let order = e.order_with_first(&first);
                modes.iter_mut().for_each(|m| *m = mode);
                e.coord(j, &order, &modes)
            })
            .collect();
        Enclosure {
            strategy: self.name(),
            verified: true,
            coords,
        }
    }
}

/// Index of the largest (`max`) or smallest control point coordinate j.
fn extreme_point(c: &NurbsCurve, j: usize, max: bool) -> usize {
    let mut best = 0;
    for i in 1..c.num_points() {
        let (x, b) = (c.control_point(i)[j], c.control_point(best)[j]);
        if (max && x > b) || (!max && x < b) {
            best = i;
        }
    }
    best
}

/// What to do with a knot span.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum SpanMode {
    /// pre-test, then Newton
    Search,
    /// skip if the local control points lie in the box so far, else as `Search`
    Prune,
    /// ignore (heuristic search region only: unsound)
    Skip,
}

/// What became of a span (for the knot-candidate rule in [`Engine::coord`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Status {
    /// its values lie in the box (control hull) or it was skipped
    Covered,
    /// C_j is non-decreasing (`inc`) and/or non-increasing (`dec`) on the closed span
    Mono { inc: bool, dec: bool },
    /// searched by Newton (every zero of C_j' in the closed span is in a kept box)
    Searched,
}

/// A candidate: parameter box [lo, hi] inside the closed span `k`, evaluated with that span's
/// polynomial piece.
#[derive(Debug, Clone, Copy)]
struct Cand {
    k: usize,
    lo: f64,
    hi: f64,
    kind: CandidateKind,
    unique: bool,
    /// whether the curve attains the value of span k's piece at the point(s) evaluated (false
    /// for the left limit at a discontinuity)
    attained: bool,
    /// the box in the span's local parameter t, whose image u([t0, t1]) is in [lo, hi]
    /// (boxes of a search on the Bernstein form)
    t: Option<(f64, f64)>,
}

impl Cand {
    /// A single parameter value q evaluated with span k's piece.
    fn point(k: usize, q: f64, kind: CandidateKind, attained: bool) -> Self {
        Cand {
            k,
            lo: q,
            hi: q,
            kind,
            unique: false,
            attained,
            t: None,
        }
    }
}

/// A box the Newton search kept.
#[derive(Debug, Clone, Copy)]
struct ZeroBox {
    lo: f64,
    hi: f64,
    unique: bool,
}

/// Shared machinery of the Newton-based strategies (`newton`, `search-region`,
/// `search-region-verified`): one per curve, reused over the coordinates.
pub(crate) struct Engine<'a> {
    c: &'a NurbsCurve,
    s: &'a Newton,
    ev: CurveEval<Interval>,
    p: usize,
    d: usize,
    rational: bool,
    /// non-empty spans of the domain: (k, u_k, u_{k+1}), in order
    pub(crate) spans: Vec<(usize, f64, f64)>,
    /// `nd[i]`: the knot between spans i and i + 1 is non-differentiable (multiplicity >= p)
    nd: Vec<bool>,
    /// tight candidate evaluation
    tight: TightEval,
    /// scratch for de Boor
    buf: Vec<Interval>,
    /// Newton box stack
    stack: Vec<(f64, f64)>,
    /// coordinate currently worked on
    j: usize,
    /// Bernstein form of the span being worked on ([`Newton::bezier_pretest`],
    /// [`Newton::bernstein`])
    poly: Option<SpanPoly>,
    /// whether the Newton search evaluates through `poly` ([`Newton::bernstein`])
    bern: bool,
    /// whether the search of the current span evaluates through `poly`: `bern`, unless the
    /// span's F is swamped by its rounding ([`SpanPoly::f_swamped`]; then interval de Boor)
    bern_span: bool,
    /// `pair[i (p + 1) + l]` (i < l): (l - i) C(p, i) C(p, l) / C(2p - 2, i + l - 1), the
    /// coefficients of the rational derivative numerator (see [`SpanPoly::new`])
    pair: Vec<Mr>,
    stats: Stats,
    /// evaluations allowed for the current coordinate ([`Newton::max_work`])
    budget: u64,
}

impl<'a> Engine<'a> {
    /// Precompute derivative splines and the span structure of `c`.
    pub(crate) fn new(c: &'a NurbsCurve, s: &'a Newton) -> Self {
        let p = c.degree();
        let kn = c.knots();
        let spans: Vec<(usize, f64, f64)> = (p..c.num_points())
            .filter(|&k| kn[k] < kn[k + 1])
            .map(|k| (k, kn[k], kn[k + 1]))
            .collect();
        let nd = spans
            .windows(2)
            .map(|w| multiplicity(kn, w[0].2) >= p)
            .collect();
        Engine {
            c,
            s,
            ev: CurveEval::new(c, 2),
            p,
            d: c.dim(),
            rational: c.is_rational(),
            spans,
            nd,
            tight: TightEval::new(c),
            buf: Vec::with_capacity(2 * (p + 1)),
            stack: Vec::new(),
            j: 0,
            poly: None,
            bern: s.bernstein && (1..=BERNSTEIN_MAX_DEGREE).contains(&p),
            bern_span: false,
            pair: if c.is_rational()
                && (s.bernstein || s.bezier_pretest)
                && (1..=BERNSTEIN_MAX_DEGREE).contains(&p)
            {
                pair_coefficients(p)
            } else {
                Vec::new()
            },
            stats: Stats::default(),
            budget: u64::MAX,
        }
    }

    /// Span indices (into `spans`) with the spans meeting the supports of the control points
    /// `first` in front, then all others in order.
    pub(crate) fn order_with_first(&self, first: &[usize]) -> Vec<usize> {
        let p = self.p;
        let near = |k: usize| first.iter().any(|&i| k >= i && k <= i + p);
        let mut order: Vec<usize> = (0..self.spans.len())
            .filter(|&s| near(self.spans[s].0))
            .collect();
        order.extend((0..self.spans.len()).filter(|&s| !near(self.spans[s].0)));
        order
    }

    /// (A_j^(l), w^(l)) over / at `u` (inside the closed span k), l <= 2.
    fn level(&mut self, l: usize, k: usize, u: Interval) -> (Interval, Interval) {
        if !self.rational {
            if l > self.p {
                return (iv::point(0.0), iv::point(0.0));
            }
            let v = self
                .ev
                .level(l)
                .eval_span_rows(k - l, &u, &[self.j], &mut self.buf);
            let w = if l == 0 {
                iv::point(1.0)
            } else {
                iv::point(0.0)
            };
            return (v[0], w);
        }
        if l > self.p {
            return (iv::point(0.0), iv::point(0.0));
        }
        let v = self
            .ev
            .level(l)
            .eval_span_rows(k - l, &u, &[self.j, self.d], &mut self.buf);
        (v[0], v[1])
    }

    /// Enclosure of C_j over / at `u` in the closed span k. With the Bernstein form
    /// ([`Newton::bernstein`]) here and in [`Engine::f`], [`Engine::df`] `u` is the local
    /// parameter t in [0, 1] of the span (the search then runs in t).
    fn value(&mut self, k: usize, u: Interval) -> Interval {
        self.stats.point_evaluations += 1;
        if let Some(sp) = self.poly.as_ref().filter(|sp| self.bern_span && sp.k == k) {
            return sp.values(u.inf(), u.sup());
        }
        let (a, w) = self.level(0, k, u);
        if self.rational {
            a / w
        } else {
            a
        }
    }

    /// Enclosures of (C_j, C_j') over `u` in the closed span k (eq. 3.10:
    /// C' = (A' - w' C) / w).
    fn value_and_slope(&mut self, k: usize, u: Interval) -> (Interval, Interval) {
        let (a, w) = self.level(0, k, u);
        let (a1, w1) = self.level(1, k, u);
        if !self.rational {
            return (a, a1);
        }
        let c0 = a / w;
        (c0, (a1 - w1 * c0) / w)
    }

    /// f at / over `u` (see [`DerivForm`]): its zeros in span k are the critical points of C_j.
    fn f(&mut self, k: usize, u: Interval) -> Interval {
        let t = self.s.time_derivatives.then(Instant::now);
        self.stats.derivative_evaluations += 1;
        let bern = self.poly.as_ref().filter(|sp| self.bern_span && sp.k == k);
        let r = match self.s.form {
            // the Bernstein form's F(t): same sign and zeros as C_j' (see SpanPoly)
            _ if bern.is_some() => bern.map_or(Interval::ENTIRE, |sp| sp.f(u.inf(), u.sup())),
            DerivForm::Quotient => self.value_and_slope(k, u).1,
            // (non-rational: f = A_j', no level-0 evaluation)
            DerivForm::Numerator if !self.rational => self.level(1, k, u).0,
            DerivForm::Numerator => {
                let (a, w) = self.level(0, k, u);
                let (a1, w1) = self.level(1, k, u);
                a1 * w - a * w1
            }
        };
        if let Some(t) = t {
            self.stats.time_derivatives += t.elapsed();
        }
        r
    }

    /// f' over `u` in span k.
    fn df(&mut self, k: usize, u: Interval) -> Interval {
        let t = self.s.time_derivatives.then(Instant::now);
        self.stats.derivative_evaluations += 1;
        let bern = self.poly.as_ref().filter(|sp| self.bern_span && sp.k == k);
        let r = if let Some(sp) = bern {
            // F'(t), the derivative of the f above
            sp.df(u.inf(), u.sup())
        } else if !self.rational {
            self.level(2, k, u).0
        } else {
            let (a, w) = self.level(0, k, u);
            let (a2, w2) = self.level(2, k, u);
            match self.s.form {
                DerivForm::Numerator => a2 * w - a * w2,
                DerivForm::Quotient => {
                    // eq. 3.10 with k = 2: C'' = (A'' - 2 w' C' - w'' C) / w
                    let (a1, w1) = self.level(1, k, u);
                    let c0 = a / w;
                    let c1 = (a1 - w1 * c0) / w;
                    (a2 - iv::point(2.0) * w1 * c1 - w2 * c0) / w
                }
            }
        };
        if let Some(t) = t {
            self.stats.time_derivatives += t.elapsed();
        }
        r
    }

    /// Outer enclosure of C_j over the candidate box, and enclosures of values the curve
    /// attains (if `attained`; EMPTY for none).
    fn eval_cand(&mut self, cd: &Cand) -> (Interval, [Interval; 2]) {
        let k = cd.k;
        // Convex hull of the local control points (thesis prop. 2.1): exact and always sound
        // for every value of span k's piece on the closed span (also the limit at its end);
        // it also caps evaluations that overflowed.
        let (hmin, hmax) = self.local_hull(k);
        let hull = iv::span(hmin, hmax);
        self.stats.point_evaluations += 1;
        let (enc, at) = if cd.lo == cd.hi && !cd.attained {
            // Left limit at a discontinuity q: span k's piece on [q-, q] (q- the float below
            // q, still in span k) contains it; TightEval adds the curve's value C(q) there,
            // itself a candidate, so the outer box does not grow from it.
            let q = cd.lo;
            let v = self.tight.coord_over(self.j, f64::next_down(q), q);
            (v, [v, Interval::EMPTY])
        } else if cd.lo == cd.hi {
            // C(q) about one ulp wide (TightEval, double-double Horner); the curve's value at q
            // is span k's piece there (k is q's span, or the curve is continuous at q)
            let v = self.tight.coord_at(self.j, cd.lo);
            (v, [v, Interval::EMPTY])
        } else {
            // C over the box (TightEval: second-order Taylor form around the midpoint m,
            // about one ulp wide near a critical point); m is in [lo, hi) inside span k, where
            // the curve is this piece, so C(m) is attained. So is C(lo) (lo < hi <= u_{k+1}),
            // evaluated too when lo is the knot u_k (Bernstein boxes, whose parameter maps are
            // rounded outward): a critical point at a knot is often the extremum, and the
            // boxes on both sides only reach it at an end.
            self.stats.point_evaluations += 1;
            let m = midpoint(cd.lo, cd.hi);
            let at_knot = cd.t.is_some() && cd.lo == self.c.knots()[k];
            let cm = [
                self.tight.coord_at(self.j, m),
                if at_knot {
                    self.stats.point_evaluations += 1;
                    self.tight.coord_at(self.j, cd.lo)
                } else {
                    Interval::EMPTY
                },
            ];
            let mut enc = self.tight.coord_over(self.j, cd.lo, cd.hi);
            let mut cm = cm;
            if let (Some((t0, t1)), Some(sp)) = (cd.t, self.poly.as_ref().filter(|sp| sp.k == k)) {
                // The hull of the Bézier points of the piece over [t0, t1] (convex hull
                // property, see SpanPoly::values): also an enclosure of its values on the box,
                // and far tighter than [lo, hi] when the span is below the f64 resolution of
                // u (a 1e-12 span at u ~ 6: C'' ~ 1e24 times ulp(u)^2). The piece's value at
                // u(t_mid), a real in the span, is attained.
                let (b, at) = sp.values_tight(self.c, self.j, t0, t1);
                if !b.intersection(enc).is_empty() {
                    enc = enc.intersection(b);
                }
                if cm[1].is_empty() {
                    cm[1] = at;
                }
            }
            (enc, cm)
        };
        // Both are enclosures of span k's values on the candidate (coord_over may also contain
        // the next piece's value at an interior knot ending the box, a curve value as well).
        let mut enc = enc.intersection(hull);
        if enc.is_empty() {
            // cannot happen mathematically (both contain the range); stay sound anyway
            enc = hull;
        }
        let at = at.map(|v| {
            if cd.attained {
                v.intersection(hull)
            } else {
                Interval::EMPTY
            }
        });
        (enc, at)
    }

    /// min / max of coordinate j of the local control points P_{k-p} .. P_k (exact).
    fn local_hull(&self, k: usize) -> (f64, f64) {
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        for i in k - self.p..=k {
            let x = self.c.control_point(i)[self.j];
            lo = lo.min(x);
            hi = hi.max(x);
        }
        (lo, hi)
    }

    /// Whether coordinate j of the local control points of span k is non-decreasing /
    /// non-increasing. Then C_j is monotone on the closed span, also for NURBS: knot insertion
    /// (thesis eq. 4.12) puts each new point between two old ones (positive weights), so the
    /// Bézier points of the span stay monotone, and the rational Bézier derivative numerator
    /// sum_{i<l} (l-i) C(p,i) C(p,l) / C(2p-2,i+l-1) w_i w_l (x_l - x_i) B^{2p-2}_{i+l-1}(t)
    /// then has coefficients of one sign. Exact f64 comparisons: no rounding.
    fn monotone(&self, k: usize) -> (bool, bool) {
        let mut inc = true;
        let mut dec = true;
        let mut prev = self.c.control_point(k - self.p)[self.j];
        for i in k - self.p + 1..=k {
            let x = self.c.control_point(i)[self.j];
            inc &= x >= prev;
            dec &= x <= prev;
            prev = x;
        }
        (inc, dec)
    }

    /// Interval Newton on f over the closed span k = [a, b] (thesis `inewtonKNRH`): every zero
    /// of f in [a, b] ends up in a box pushed to `out`, or in a box dropped because its values
    /// provably lie in `covered` (= [inner_lo, inner_hi] so far, values the curve attains on
    /// both sides, so the box's values are inside the final outer box anyway).
    fn search(
        &mut self,
        k: usize,
        a: f64,
        b: f64,
        covered: (f64, f64),
        out: &mut Vec<ZeroBox>,
    ) -> Termination {
        let s = *self.s;
        // relative to the span: a span of 1e-12 needs boxes far below 1e-12 of the domain
        let tol = s.tol * (b - a);
        let mut term = Termination::Converged;
        let hull = {
            let (h0, h1) = self.local_hull(k);
            iv::span(h0, h1)
        };
        self.stack.clear();
        self.stack.push((a, b));
        let mut boxes = 0usize;
        let mut splits = 0u32;
        while let Some((mut x0, mut x1)) = self.stack.pop() {
            boxes += 1;
            let keep = |x0: f64, x1: f64, unique: bool, out: &mut Vec<ZeroBox>| {
                out.push(ZeroBox {
                    lo: x0,
                    hi: x1,
                    unique,
                })
            };
            let spent = self.stats.derivative_evaluations + self.stats.point_evaluations;
            if boxes > s.max_boxes || spent > self.budget {
                // Box or work limit: keep the box whole (sound).
                keep(x0, x1, false, out);
                term = if spent > self.budget {
                    Termination::WorkLimit
                } else {
                    Termination::BoxLimit
                };
                continue;
            }
            if s.drop_covered && boxes > 1 {
                let v = self.value(k, iv::span(x0, x1)).intersection(hull);
                if !v.is_empty() && v.inf() >= covered.0 && v.sup() <= covered.1 {
                    continue;
                }
            }
            let mut unique = false;
            let mut it = 0;
            loop {
                let small = 0.5 * (x1 - x0) <= tol;
                if small && !(unique && s.refine_unique) {
                    keep(x0, x1, unique, out);
                    break;
                }
                let over =
                    self.stats.derivative_evaluations + self.stats.point_evaluations > self.budget;
                if it >= s.max_iter || over {
                    if !(small || unique) && term == Termination::Converged {
                        term = if over {
                            Termination::WorkLimit
                        } else {
                            Termination::IterationLimit
                        };
                    }
                    keep(x0, x1, unique, out);
                    break;
                }
                it += 1;
                self.stats.newton_iterations += 1;
                let m = midpoint(x0, x1);
                let x = iv::span(x0, x1);
                let fm = self.f(k, iv::point(m));
                let dx = self.df(k, x);
                // N(X) = m - f(m) / f'(X) with the extended division (thesis divideKNR):
                // mul_rev_to_pair gives the (at most two) pieces of {z : f(m) = y z, y in f'(X)}.
                // Theorem 5.1: every zero of f in X lies in N(X) ∩ X. An empty operand would
                // come from an invalid operation, never from a proof: then learn nothing.
                let (y1, y2) = if fm.is_empty() || dx.is_empty() {
                    (x, Interval::EMPTY)
                } else {
                    let [q1, q2] = dx.mul_rev_to_pair(fm);
                    let mi = iv::point(m);
                    ((mi - q1).intersection(x), (mi - q2).intersection(x))
                };
                let (y1, y2) = if y1.is_empty() { (y2, y1) } else { (y1, y2) };
                if y1.is_empty() {
                    // Theorem 5.1: no zero in X.
                    break;
                }
                if !y2.is_empty() {
                    // Two pieces: iterate on one, keep the other (listing `inewtonKNRH`, its
                    // two-piece case).
                    self.stats.subdivisions += 1;
                    self.stack.push((y2.inf(), y2.sup()));
                    (x0, x1) = (y1.inf(), y1.sup());
                    unique = false;
                    continue;
                }
                // One piece. N(X) in the interior of X with 0 not in f'(X): exactly one zero
                // (Moore; Hansen, theorem 9.6.8). y1 = N ∩ X, so y1 inside int X means N is.
                if !dx.contains(0.0) && y1.inf() > x0 && y1.sup() < x1 {
                    unique = true;
                }
                let (n0, n1) = (y1.inf(), y1.sup());
                let stalled = n0 == x0 && n1 == x1;
                if stalled && unique {
                    // machine precision reached
                    keep(x0, x1, unique, out);
                    break;
                }
                let weak = stalled || (!unique && n1 - n0 > s.min_shrink * (x1 - x0));
                if weak && splits < s.max_splits && can_split(n0, n1) {
                    splits += 1;
                    self.split_box(n0, n1);
                    break;
                }
                if stalled && !can_split(x0, x1) {
                    // a box of one or two ulps: as resolved as it gets
                    keep(x0, x1, unique, out);
                    break;
                }
                // otherwise iterate on (the thesis: until its 20 steps are used up)
                (x0, x1) = (n0, n1);
            }
        }
        term
    }

    /// Push the pieces of [x0, x1] (split rule) on the stack. Piece ends are rounded f64 values
    /// forced to be monotone, and the first and last are x0 and x1: the pieces cover [x0, x1].
    fn split_box(&mut self, x0: f64, x1: f64) {
        self.stats.subdivisions += 1;
        let n = match self.s.split {
            Split::Bisect => 2,
            Split::Pieces(n) => n.max(2),
            Split::TwiceDegree => (2 * self.p).max(2),
        };
        let w = x1 - x0;
        let mut hi = x1;
        // pushed right to left, so the leftmost piece is processed first
        for i in (0..n).rev() {
            let lo = if i == 0 {
                x0
            } else {
                (x0 + w * (i as f64 / n as f64)).clamp(x0, hi)
            };
            if lo < hi || (i == 0 && lo == hi) {
                self.stack.push((lo, hi));
            }
            hi = lo;
        }
    }

    /// The enclosure of one coordinate: candidates from end points, non-differentiable knots,
    /// Newton boxes and the knot rule, spans processed in `order` with `modes`.
    ///
    /// Why nothing is missed (for the max; the min is symmetric). Let u* be a maximizer. If it
    /// is a domain end or non-differentiable knot, it is a candidate. Otherwise C_j is C^1 at
    /// u* and C_j'(u*) = 0. If u* lies in a closed span that was searched, a kept Newton box
    /// contains it; if in a covered span, the box contains the span's control hull. Otherwise
    /// u* lies in a run of monotone spans: moving u* right through non-decreasing spans and
    /// left through non-increasing ones keeps it a maximizer, and it ends at a run end
    /// (handled above) or at a knot with a non-decreasing span on the left and a span on the
    /// right that is not non-decreasing: exactly the knots the rule below adds.
    pub(crate) fn coord(&mut self, j: usize, order: &[usize], modes: &[SpanMode]) -> CoordBox {
        let t0 = Instant::now();
        self.j = j;
        self.stats = Stats::default();
        self.poly = None;
        let want_poly = (self.s.bezier_pretest && (self.s.pretest || self.s.prune)) || self.bern;
        let (a, b) = self.c.domain();
        let ns = self.spans.len();
        let cost = ((self.p + 1) as u64).pow(2);
        let per_span = EVALS_PER_SPAN.min(WORK_PER_SPAN / cost);
        self.budget = (self.s.max_work / cost)
            .saturating_add(per_span.saturating_mul(ns as u64))
            .max(8);
        let mut cands: Vec<Cand> = Vec::with_capacity(8);
        cands.push(Cand::point(
            self.spans[0].0,
            a,
            CandidateKind::EndPoint,
            true,
        ));
        cands.push(Cand::point(
            self.spans[ns - 1].0,
            b,
            CandidateKind::EndPoint,
            true,
        ));
        for i in 0..ns - 1 {
            if self.nd[i] {
                let q = self.spans[i].2;
                cands.push(Cand::point(
                    self.spans[i + 1].0,
                    q,
                    CandidateKind::Knot,
                    true,
                ));
                if multiplicity(self.c.knots(), q) > self.p {
                    // Discontinuity: the left limit is not attained, but values come
                    // arbitrarily close to it, so the outer box must contain it.
                    cands.push(Cand::point(self.spans[i].0, q, CandidateKind::Knot, false));
                }
            }
        }
        let mut acc = Acc::new();
        for cd in &cands {
            let (e, at) = self.eval_cand(cd);
            acc.add(cd, e, at);
        }
        let mut status = vec![Status::Covered; ns];
        let mut term = Termination::Converged;
        let mut boxes: Vec<ZeroBox> = Vec::new();
        for &si in order {
            let (k, sa, sb) = self.spans[si];
            self.bern_span = false;
            let mode = modes[si];
            if mode == SpanMode::Skip {
                continue;
            }
            if mode == SpanMode::Prune {
                let (hmin, hmax) = self.local_hull(k);
                // Values the curve attains on both sides (inner bounds): the span's values lie
                // between them, so inside the final outer box, and the extremes are elsewhere.
                if hmin >= acc.inner_lo && hmax <= acc.inner_hi {
                    continue;
                }
            }
            if self.s.pretest {
                let (inc, dec) = self.monotone(k);
                if inc || dec {
                    status[si] = Status::Mono { inc, dec };
                    continue;
                }
            }
            if want_poly {
                let sp = SpanPoly::new(self.c, self.j, k, &self.pair);
                self.poly = None;
                let bp = self.s.bezier_pretest;
                let (blo, bhi, inc, dec) = sp.bezier_points();
                if bp && mode == SpanMode::Prune && blo >= acc.inner_lo && bhi <= acc.inner_hi {
                    // as the local-hull prune above, with the span's own Bézier hull
                    continue;
                }
                if bp && self.s.pretest && (inc || dec) {
                    status[si] = Status::Mono { inc, dec };
                    continue;
                }
                let (inc, dec) = sp.f_signs();
                if self.bern && self.s.pretest && (inc || dec) {
                    // F >= 0 (or <= 0) on the closed span, and sign F = sign C_j'
                    status[si] = Status::Mono { inc, dec };
                    continue;
                }
                // A swamped F (every coefficient's enclosure contains 0) can prove nothing
                // (every de Casteljau value contains 0 too): the Bernstein search would split
                // down to `tol` everywhere and use up the work budget of the coordinate. Then
                // search this span with interval de Boor on the derivative splines, whose control
                // points are differences of the original ones (no cancellation on tiny spans,
                // where the Bézier points of C_j all agree to the last few ulps). Either path
                // is sound; this only picks the one that can make progress.
                self.bern_span = self.bern && !sp.f_swamped();
                self.poly = Some(sp);
            }
            if self.s.pretest && !self.bern_span {
                let fx = self.f(k, iv::span(sa, sb));
                if !fx.is_empty() && !fx.contains(0.0) {
                    // f has one sign on the closed span, and sign f = sign C_j'.
                    status[si] = Status::Mono {
                        inc: fx.inf() > 0.0,
                        dec: fx.sup() < 0.0,
                    };
                    continue;
                }
            }
            status[si] = Status::Searched;
            boxes.clear();
            // the Bernstein form is searched in the local parameter t in [0, 1]
            let bern = self.bern_span;
            let (x0, x1) = if bern { (0.0, 1.0) } else { (sa, sb) };
            let t = self.search(k, x0, x1, (acc.inner_lo, acc.inner_hi), &mut boxes);
            if term == Termination::Converged {
                term = t;
            }
            if t == Termination::WorkLimit && boxes.len() > 1 {
                // Out of budget: the boxes left are enclosed as one (their hull, still inside
                // the span), so that the work after the limit is one evaluation per span, not
                // one per box (2p boxes of O(p^2) each took minutes at degree 800).
                let lo = boxes.iter().map(|zb| zb.lo).fold(f64::INFINITY, f64::min);
                let hi = boxes
                    .iter()
                    .map(|zb| zb.hi)
                    .fold(f64::NEG_INFINITY, f64::max);
                boxes.clear();
                boxes.push(ZeroBox {
                    lo,
                    hi,
                    unique: false,
                });
            }
            for zb in &boxes {
                let (lo, hi, t) = match self.poly.as_ref().filter(|_| bern) {
                    Some(sp) => {
                        let (lo, hi) = sp.to_u(zb.lo, zb.hi);
                        (lo, hi, Some((zb.lo, zb.hi)))
                    }
                    None => (zb.lo, zb.hi, None),
                };
                let cd = Cand {
                    k,
                    lo,
                    hi,
                    kind: CandidateKind::Critical,
                    unique: zb.unique,
                    attained: true,
                    t,
                };
                let (e, at) = self.eval_cand(&cd);
                acc.add(&cd, e, at);
            }
        }
        // Knot rule (see the doc comment): smooth knots between two monotone spans.
        for i in 0..ns - 1 {
            if self.nd[i] {
                continue;
            }
            if let (Status::Mono { inc: li, dec: ld }, Status::Mono { inc: ri, dec: rd }) =
                (status[i], status[i + 1])
            {
                if (li && !ri) || (ld && !rd) {
                    let q = self.spans[i].2;
                    let cd = Cand::point(self.spans[i + 1].0, q, CandidateKind::Knot, true);
                    let (e, at) = self.eval_cand(&cd);
                    acc.add(&cd, e, at);
                }
            }
        }
        let mut stats = self.stats;
        stats.time_total = t0.elapsed();
        acc.finish(stats, term)
    }
}

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
///   sum as in [`Engine::monotone`]). C_j' = F / (W^2 (b - a)) (or p F / (b - a)): F has the
///   sign and the zeros of C_j' on the closed span;
/// * `df`: F' = n sum (F_{i+1} - F_i) B_i^{n-1} (the hodograph).
///
/// Ranges over a box come from the hull of the coefficients restricted to it by de Casteljau
/// (convex hull property: Bernstein polynomials are >= 0 and sum to 1; for the rational values
/// the positive weights make the point a convex combination of the Cartesian Bézier points).
/// Every Mr operation encloses its exact result, so every coefficient encloses the exact one.
struct SpanPoly {
    /// span index k
    k: usize,
    /// the shift c (a control point coordinate, exact)
    c: f64,
    /// homogeneous Bézier segment of C_j - c over [a, b]
    seg: BezierSeg<Mr>,
    /// F, degree n
    f: BezierSeg<Mr>,
    /// F', degree n - 1 (one zero coefficient for n = 0)
    df: BezierSeg<Mr>,
}

impl SpanPoly {
    /// The form of coordinate j of `c` on span k; `pair` from [`pair_coefficients`] (rational;
    /// empty: F is left unknown, ENTIRE).
    fn new(c: &NurbsCurve, j: usize, k: usize, pair: &[Mr]) -> Self {
        let p = c.degree();
        let rational = c.is_rational();
        let shift = span_shift((k - p..=k).map(|i| c.control_point(i)[j]).collect());
        let seg = shifted_segment(c, j, k, shift);
        let q = &seg.pts;
        let fco: Vec<Mr> = if rational && pair.is_empty() {
            // degree above BERNSTEIN_MAX_DEGREE: F unknown
            vec![Mr::ENTIRE]
        } else if rational {
            let mut d = vec![Mr::from_f64(0.0); 2 * p - 1];
            for i in 0..p {
                for l in i + 1..=p {
                    let (ai, wi, al, wl) = (q[2 * i], q[2 * i + 1], q[2 * l], q[2 * l + 1]);
                    d[i + l - 1] = d[i + l - 1] + pair[i * (p + 1) + l] * (al * wi - ai * wl);
                }
            }
            d
        } else {
            q.windows(2).map(|w| w[1] - w[0]).collect()
        };
        let n = fco.len() - 1;
        let dco: Vec<Mr> = if rational && pair.is_empty() {
            vec![Mr::ENTIRE]
        } else if n == 0 {
            vec![Mr::from_f64(0.0)]
        } else {
            let nm = Mr::from_usize(n);
            fco.windows(2).map(|w| nm * (w[1] - w[0])).collect()
        };
        let poly = |pts: Vec<Mr>| BezierSeg {
            a: seg.a,
            b: seg.b,
            degree: pts.len() - 1,
            dim: 1,
            rational: false,
            pts,
        };
        SpanPoly {
            k,
            c: shift,
            f: poly(fco),
            df: poly(dco),
            seg,
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

    /// F over [t0, t1] (at t0 for a point): de Casteljau value, or the coefficient hull.
    fn f(&self, t0: f64, t1: f64) -> Interval {
        if t0 == t1 {
            return self.f.eval_local(&Mr::from_f64(t0))[0].to_interval();
        }
        hull(&Self::restrict(&self.f, t0, t1))
    }

    /// F' over [t0, t1] (at t0 for a point).
    fn df(&self, t0: f64, t1: f64) -> Interval {
        if t0 == t1 {
            return self.df.eval_local(&Mr::from_f64(t0))[0].to_interval();
        }
        hull(&Self::restrict(&self.df, t0, t1))
    }

    /// The values of the piece C_j over [t0, t1]: hull of the Cartesian Bézier points of the
    /// restricted segment, shifted back by c.
    fn values(&self, t0: f64, t1: f64) -> Interval {
        let q = Self::restrict(&self.seg, t0, t1);
        hull(&cartesian(q, self.seg.rational)) + iv::point(self.c)
    }

    /// As [`SpanPoly::values`], and C_j at the parameter u(t_mid) (a real in the closed span:
    /// a value of the piece there), in double-double intervals ([`Ddi`]): for the candidate
    /// boxes, where the few hundred ulps of the Mr points would show in the bounds.
    fn values_tight(&self, c: &NurbsCurve, j: usize, t0: f64, t1: f64) -> (Interval, Interval) {
        let seg: BezierSeg<Ddi> = shifted_segment(c, j, self.k, self.c);
        let r = self.seg.rational;
        let over = hull(&cartesian(Self::restrict(&seg, t0, t1), r));
        let at = hull(&cartesian(
            seg.eval_local(&Ddi::from_f64(midpoint(t0, t1))),
            r,
        ));
        let sh = iv::point(self.c);
        (over + sh, at + sh)
    }

    /// An f64 box [lo, hi] inside [a, b] that contains u([t0, t1]), u(t) = a + t (b - a)
    /// (outward-rounded interval arithmetic; u(t) is in [a, b] for t in [0, 1]).
    fn to_u(&self, t0: f64, t1: f64) -> (f64, f64) {
        let (a, b) = (self.seg.a, self.seg.b);
        let len = iv::point(b) - iv::point(a);
        let lo = (iv::point(a) + iv::point(t0) * len).inf();
        let hi = (iv::point(a) + iv::point(t1) * len).sup();
        (lo.clamp(a, b), hi.clamp(a, b))
    }

    /// Coordinate j of the span's Bézier points, enclosed: their hull [lo, hi] and whether
    /// they are non-decreasing / non-increasing (for every choice of the exact points in the
    /// enclosures: each upper bound <= the next lower bound).
    ///
    /// Why this is sound: the new weights of knot insertion are convex combinations of
    /// positive weights, so positive. A rational Bézier curve with positive weights lies in
    /// the convex hull of its points (thesis prop. 2.1, on the closed span, the right-end limit
    /// included), and is monotone if its points are (the argument of [`Engine::monotone`]).
    fn bezier_points(&self) -> (f64, f64, bool, bool) {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        let (mut inc, mut dec) = (true, true);
        let mut prev = Interval::EMPTY;
        for x in cartesian(self.seg.pts.clone(), self.seg.rational) {
            let x = x.to_interval() + iv::point(self.c);
            if x.is_empty() || x.is_entire() {
                return (f64::NEG_INFINITY, f64::INFINITY, false, false);
            }
            lo = lo.min(x.inf());
            hi = hi.max(x.sup());
            if !prev.is_empty() {
                inc &= x.inf() >= prev.sup();
                dec &= x.sup() <= prev.inf();
            }
            prev = x;
        }
        (lo, hi, inc, dec)
    }

    /// Whether every coefficient enclosure of F contains 0 (and F is not exactly 0): the
    /// rounding of the Bernstein form swamps F, so no box of the span can be excluded with it
    /// (e.g. a span of 1e-14 where the Bézier points agree to a few ulps and F, their
    /// differences, is below their rounding errors).
    fn f_swamped(&self) -> bool {
        let zero = self.f.pts.iter().all(|x| x.mid() == 0.0 && x.rad() == 0.0);
        !zero && self.f.pts.iter().all(|x| x.to_interval().contains(0.0))
    }

    /// Whether F >= 0 / F <= 0 on the whole span (all coefficients of one sign), i.e. C_j
    /// non-decreasing / non-increasing on the closed span.
    fn f_signs(&self) -> (bool, bool) {
        let h = hull(&self.f.pts);
        (h.inf() >= 0.0, h.sup() <= 0.0)
    }
}

/// The homogeneous Bézier segment of the shifted piece C_j - c on span k of `c`: rows
/// ((x_i - c) w_i, w_i) (rational) or x_i - c, by Boehm knot insertion on the p + 1 local
/// control points ([`HSpline::bezier_segment`]). Each x_i - c is exact for x_i = c (and
/// within a factor 2 of c, Sterbenz), else enclosed by S.
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

/// The Cartesian points (x_i - c) of homogeneous one-coordinate points.
fn cartesian<S: Scalar>(q: Vec<S>, rational: bool) -> Vec<S> {
    if rational {
        q.chunks_exact(2)
            .map(|h| h[0].clone() / h[1].clone())
            .collect()
    } else {
        q
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
fn span_shift(mut xs: Vec<f64>) -> f64 {
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
/// [`SpanPoly`]), enclosed: binomials by Pascal's rule in [`Mr`] (exact while below 2^53).
fn pair_coefficients(p: usize) -> Vec<Mr> {
    let binom = |n: usize| {
        let mut row = vec![Mr::from_f64(1.0)];
        for _ in 0..n {
            let mut next = vec![Mr::from_f64(1.0); row.len() + 1];
            for i in 1..row.len() {
                next[i] = row[i - 1] + row[i];
            }
            row = next;
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

/// A midpoint of [x0, x1] inside it (no overflow for huge bounds).
#[inline]
fn midpoint(x0: f64, x1: f64) -> f64 {
    (0.5 * x0 + 0.5 * x1).clamp(x0, x1)
}

/// Whether [x0, x1] has an f64 strictly inside.
#[inline]
fn can_split(x0: f64, x1: f64) -> bool {
    let m = midpoint(x0, x1);
    x0 < m && m < x1
}

/// Running hull of candidate enclosures.
struct Acc {
    lo: f64,
    hi: f64,
    inner_lo: f64,
    inner_hi: f64,
    cands: Vec<(Extremum, Interval)>,
}

impl Acc {
    fn new() -> Self {
        Acc {
            lo: f64::INFINITY,
            hi: f64::NEG_INFINITY,
            inner_lo: f64::INFINITY,
            inner_hi: f64::NEG_INFINITY,
            cands: Vec::new(),
        }
    }

    fn add(&mut self, cd: &Cand, e: Interval, attained: [Interval; 2]) {
        // An empty enclosure cannot occur (every value evaluated is a real number); treat it
        // as "anything" to stay sound.
        let e = if e.is_empty() { Interval::ENTIRE } else { e };
        self.lo = self.lo.min(e.inf());
        self.hi = self.hi.max(e.sup());
        for v in attained.into_iter().filter(|v| !v.is_empty()) {
            // The curve attains a value inside v: it reaches <= sup v and >= inf v.
            self.inner_lo = self.inner_lo.min(v.sup());
            self.inner_hi = self.inner_hi.max(v.inf());
        }
        self.cands.push((
            Extremum {
                u_lo: cd.lo,
                u_hi: cd.hi,
                unique: cd.unique,
                kind: cd.kind,
            },
            e,
        ));
    }

    fn finish(self, stats: Stats, termination: Termination) -> CoordBox {
        let (ilo, ihi) = (self.inner_lo, self.inner_hi);
        let argmin = self
            .cands
            .iter()
            .filter(|(_, e)| e.inf() <= ilo)
            .map(|c| c.0)
            .collect();
        let argmax = self
            .cands
            .iter()
            .filter(|(_, e)| e.sup() >= ihi)
            .map(|c| c.0)
            .collect();
        CoordBox {
            lo: self.lo,
            hi: self.hi,
            inner_lo: ilo.max(self.lo),
            inner_hi: ihi.min(self.hi),
            argmin,
            argmax,
            stats,
            termination,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::enclose::{BezierSubdivision, ControlHull};
    use crate::testkit::validate::{check_containment, dense_params, ulp};

    fn curve1(p: usize, knots: Vec<f64>, x: &[f64], w: Option<Vec<f64>>) -> NurbsCurve {
        NurbsCurve::new(p, knots, x.iter().map(|&v| vec![v]).collect(), w).unwrap()
    }

    /// The 9-point rational quadratic unit circle (NURBS Book ex. 7.2), affinely mapped.
    fn ellipse(m: [[f64; 2]; 2], t: [f64; 2]) -> NurbsCurve {
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let pts = [
            [1., 0.],
            [1., 1.],
            [0., 1.],
            [-1., 1.],
            [-1., 0.],
            [-1., -1.],
            [0., -1.],
            [1., -1.],
            [1., 0.],
        ];
        NurbsCurve::new(
            2,
            vec![0., 0., 0., 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1., 1., 1.],
            pts.iter()
                .map(|q| {
                    (0..2)
                        .map(|r| m[r][0] * q[0] + m[r][1] * q[1] + t[r])
                        .collect()
                })
                .collect(),
            Some(vec![1., s, 1., s, 1., s, 1., s, 1.]),
        )
        .unwrap()
    }

    /// Soundness checks shared by the tests: dense containment, inner inside outer, inside
    /// the control hull.
    fn sound(c: &NurbsCurve, e: &Enclosure) {
        let ch = check_containment(c, e, &dense_params(c, 200));
        assert!(ch.misses.is_empty(), "{:?}", &ch.misses[..1]);
        let hull = ControlHull.enclose(c);
        for (j, cb) in e.coords.iter().enumerate() {
            assert!(cb.lo <= cb.inner_lo && cb.inner_hi <= cb.hi, "{cb:?}");
            assert!(hull.coords[j].lo <= cb.lo && cb.hi <= hull.coords[j].hi);
        }
    }

    fn all() -> Vec<Newton> {
        vec![
            Newton::default(),
            Newton::thesis(),
            Newton {
                form: DerivForm::Quotient,
                ..Default::default()
            },
            Newton {
                pretest: false,
                prune: false,
                ..Default::default()
            },
        ]
    }

    #[test]
    fn circle_box_is_unit_square() {
        let c = ellipse([[1., 0.], [0., 1.]], [0., 0.]);
        for n in all() {
            let e = n.enclose(&c);
            sound(&c, &e);
            // the extremes are at the knots 0, 0.25, 0.5, 0.75 where C is a control point
            for cb in &e.coords {
                assert!(cb.lo <= -1.0 && cb.hi >= 1.0);
                assert!(cb.gap() <= 4.0 * ulp(1.0), "{cb:?}");
            }
        }
    }

    #[test]
    fn rotated_ellipses_match_closed_form() {
        for k in 0..24 {
            let phi = 0.1 + k as f64 * 0.37;
            let (a, b) = (3.0, 0.5 + 0.1 * k as f64);
            let (cs, sn) = (phi.cos(), phi.sin());
            // x = a cos(phi) cos t - b sin(phi) sin t, y = a sin(phi) cos t + b cos(phi) sin t
            let c = ellipse([[a * cs, -b * sn], [a * sn, b * cs]], [1.0, -2.0]);
            let hw = [
                (a * a * cs * cs + b * b * sn * sn).sqrt(),
                (a * a * sn * sn + b * b * cs * cs).sqrt(),
            ];
            for n in all() {
                let e = n.enclose(&c);
                sound(&c, &e);
                for (j, cb) in e.coords.iter().enumerate() {
                    let ctr = [1.0, -2.0][j];
                    // the data (weight 1/sqrt 2, rotated points) are rounded: the curve is an
                    // ellipse only up to ~1e-15 relative
                    let eps = if n.tol > 1e-9 { 1e-9 } else { 1e-14 } * a;
                    assert!((cb.hi - (ctr + hw[j])).abs() < eps, "{j} {cb:?} {}", hw[j]);
                    assert!((cb.lo - (ctr - hw[j])).abs() < eps, "{j} {cb:?}");
                    if n.tol < 1e-9 {
                        assert!(cb.gap() <= 4.0 * ulp(c.coord_scale(j)), "{cb:?}");
                    }
                    assert!(cb.termination == Termination::Converged);
                }
                if n == Newton::default() {
                    let cb = &e.coords[0];
                    assert!(cb.argmax.iter().any(|x| x.unique), "{cb:?}");
                }
            }
        }
    }

    #[test]
    fn spike_between_close_knots() {
        let c = curve1(
            3,
            vec![0., 0., 0., 0., 0.5, 0.5 + 1e-5, 0.5 + 2e-5, 1., 1., 1., 1.],
            &[0., 0., 0., 10., 0., 0., 0.],
            None,
        );
        let bz = BezierSubdivision::default().enclose(&c);
        for n in all() {
            let e = n.enclose(&c);
            sound(&c, &e);
            let cb = &e.coords[0];
            // sandwich against the Bézier strategy (both verified): each one's outer bound is
            // >= the other's inner bound
            assert!(cb.hi >= bz.coords[0].inner_hi && bz.coords[0].hi >= cb.inner_hi);
            if n.tol < 1e-9 {
                assert!(cb.gap() <= 4.0 * ulp(10.0), "{cb:?}");
            }
            assert!(cb.hi > 1.0);
        }
    }

    #[test]
    fn flat_coordinate_is_exact_and_quick() {
        for w in [None, Some(vec![1., 5., 0.5, 2., 1e-3])] {
            let c = NurbsCurve::new(
                3,
                vec![0., 0., 0., 0., 0.3, 1., 1., 1., 1.],
                (0..5).map(|i| vec![i as f64, 3.0]).collect(),
                w,
            )
            .unwrap();
            let e = Newton::default().enclose(&c);
            sound(&c, &e);
            let cb = &e.coords[1];
            assert_eq!((cb.lo, cb.hi), (3.0, 3.0));
            assert_eq!(cb.stats.newton_iterations, 0);
            // also without pre-tests (Newton on f = 0 exactly: N(X) = X ∩ ENTIRE, splits)
            let n = Newton {
                pretest: false,
                prune: false,
                ..Default::default()
            };
            let e = n.enclose(&c);
            sound(&c, &e);
            assert!(e.coords[1].lo <= 3.0 && e.coords[1].hi >= 3.0);
            assert!(e.coords[1].hi - e.coords[1].lo <= 4.0 * ulp(3.0));
        }
    }

    #[test]
    fn extremum_exactly_at_a_smooth_knot() {
        // both spans monotone; the max 1 is at the knot 0.5 (C^1 there, C'(0.5) = 0)
        let c = curve1(
            2,
            vec![0., 0., 0., 0.5, 1., 1., 1.],
            &[0., 1., 1., 0.],
            None,
        );
        for n in all() {
            let e = n.enclose(&c);
            sound(&c, &e);
            assert_eq!(e.coords[0].hi, 1.0);
            assert_eq!(e.coords[0].inner_hi, 1.0);
        }
    }

    #[test]
    fn c0_corner_and_discontinuity() {
        let c = curve1(
            2,
            vec![0., 0., 0., 0.5, 0.5, 1., 1., 1.],
            &[0., 1., 2., 1., 0.],
            None,
        );
        let e = Newton::default().enclose(&c);
        sound(&c, &e);
        assert_eq!((e.coords[0].hi, e.coords[0].inner_hi), (2.0, 2.0));
        // interior multiplicity p + 1: the left piece tends to 3 (not attained), the right one
        // starts at -5
        let c = curve1(
            2,
            vec![0., 0., 0., 0.5, 0.5, 0.5, 1., 1., 1.],
            &[0., 1., 3., -5., 0., 0.],
            None,
        );
        for n in all() {
            let e = n.enclose(&c);
            sound(&c, &e);
            let cb = &e.coords[0];
            assert!(cb.hi >= 3.0 && cb.lo <= -5.0, "{cb:?}");
            assert!(
                cb.inner_hi < 3.0,
                "the left limit 3 is not attained: {cb:?}"
            );
        }
    }

    #[test]
    fn high_degree_and_extreme_scales() {
        // degree 30 Bézier with scattered points and weights 1e-6 .. 1e6
        let p = 30;
        let x: Vec<f64> = (0..=p)
            .map(|i| ((i * 7919) % 31) as f64 / 15.0 - 1.0)
            .collect();
        let mut kn = vec![0.0; p + 1];
        kn.extend(vec![1.0; p + 1]);
        let w: Vec<f64> = (0..=p).map(|i| 10f64.powi((i % 13) as i32 - 6)).collect();
        for wt in [None, Some(w)] {
            let c = curve1(p, kn.clone(), &x, wt);
            let e = Newton::default().enclose(&c);
            sound(&c, &e);
            for cb in &e.coords {
                assert_eq!(cb.termination, Termination::Converged);
                assert!(cb.gap() < 1e-13, "{cb:?}");
            }
        }
        // huge coordinates: may overflow inside, must stay sound
        let c = curve1(
            3,
            vec![0., 0., 0., 0., 1e-12, 1., 1., 1., 1.],
            &[1e300, -1e300, 1e300, -1e300, 1e300],
            None,
        );
        let e = Newton::default().enclose(&c);
        sound(&c, &e);
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
                pair_coefficients(p)
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
                let sp = SpanPoly::new(&c, 0, k, &pair);
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
                    let got = sp.f(t, t);
                    let tol = 1e-12 * (1.0 + want.abs());
                    assert!(
                        got.inf() - tol <= want && want <= got.sup() + tol,
                        "k {k} u {u}: {got:?} vs {want}"
                    );
                    // F over a box contains F at its points; F' by a difference quotient
                    let (t0, t1) = (t.min(0.999), t.min(0.999) + 1e-3);
                    let (f0, f1) = (sp.f(t0, t0).mid(), sp.f(t1, t1).mid());
                    let d = sp.df(t0, t1);
                    // mean value theorem: the difference quotient is a value of F'
                    let q = (f1 - f0) / (t1 - t0);
                    let e = 1e-9 * (1.0 + q.abs());
                    assert!(d.inf() - e <= q && q <= d.sup() + e, "{d:?} {q}");
                    assert!(sp.f(t0, t1).contains(f0) && sp.f(t0, t1).contains(f1));
                    // the piece's value at u(t), and u([t0, t1]) covers u(t0), u(t1)
                    let y = c.point::<f64>(u).unwrap()[0];
                    let vt = sp.values_tight(&c, 0, t, t).1;
                    assert!(vt.inf() - 1e-12 <= y && y <= vt.sup() + 1e-12, "{vt:?} {y}");
                    let (lo, hi) = sp.to_u(t0, t1);
                    assert!(lo <= a + t0 * l && a + t1 * l <= hi && a <= lo && hi <= b);
                }
                // values over the span contain the f64 points of the piece
                let v = sp.values(0.0, 1.0);
                for i in 0..=10 {
                    let u = a + (b - a) * i as f64 / 10.0;
                    let y = c.point::<f64>(u).unwrap()[0];
                    assert!(v.inf() - 1e-12 <= y && y <= v.sup() + 1e-12, "{v:?} {y}");
                }
            }
        }
    }

    #[test]
    fn span_shift_prefers_flat_runs() {
        assert_eq!(span_shift(vec![3.0, 1.0, 1.0, 2.0, 1.0]), 1.0);
        assert_eq!(span_shift(vec![3.0, 1.0, 2.0]), 2.0);
        assert_eq!(span_shift(vec![-0.5]), -0.5);
    }

    #[test]
    fn search_region_finds_what_it_searches() {
        use crate::enclose::SearchRegion;
        // extremes near the extreme control points: heuristic = verified = newton
        let c = curve1(
            3,
            vec![0., 0., 0., 0., 0.2, 0.4, 0.6, 0.8, 1., 1., 1., 1.],
            &[0., 1., 5., 1., 0., -4., 0., 1.],
            None,
        );
        let nb = Newton::default().enclose(&c);
        for s in [
            SearchRegion::thesis(Newton::default()),
            SearchRegion::verified(Newton::default()),
        ] {
            let e = s.enclose(&c);
            assert_eq!(e.verified, s.verified);
            sound(&c, &e);
            assert_eq!(e.lo(), nb.lo());
            assert_eq!(e.hi(), nb.hi());
        }
    }
}
