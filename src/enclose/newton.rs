//! The thesis's interval Newton box enclosure (ch. 6; listings `inewtonKNRH` and `main`,
//! thesis lines 1766-1990), made sound and tight.
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
//! * candidate values use the mean-value form C(m) + C'(X)(X - m), which is tight at a
//!   critical point (C' ~ 0 there).

use super::{
    BoxEncloser, CandidateKind, CoordBox, Enclosure, Extremum, Guarantee, Stats, Termination,
};
use crate::curve::NurbsCurve;
use crate::eval::CurveEval;
use crate::knots::multiplicity;
use crate::scalar::iv;
use inari::Interval;
use std::time::Instant;

/// How a box is subdivided when a Newton step makes too little progress.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Split {
    /// two halves
    Bisect,
    /// this many equal pieces (at least 2)
    Pieces(usize),
    /// 2p equal pieces (thesis `inewtonKNRH`, lines 1815-1825)
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
    /// Stop refining a box when its radius is <= `tol` times the domain length (thesis: `tol`
    /// on the radius, the thesis's domains being [0, 1]).
    pub tol: f64,
    /// Keep iterating on a box with a uniqueness proof until the Newton step makes no progress
    /// (machine precision; costs one or two quadratically convergent steps).
    pub refine_unique: bool,
    /// Newton steps per box (thesis: 20).
    pub max_iter: u32,
    /// Boxes per coordinate; the rest is enclosed as a whole.
    pub max_boxes: usize,
    /// Split rule when a step makes too little progress.
    pub split: Split,
    /// Split when a step leaves more than this fraction of the width (1.0: only when it makes
    /// no progress at all, as the thesis).
    pub min_shrink: f64,
    /// Function iterated on.
    pub form: DerivForm,
    /// Skip spans that are provably monotone (local control points monotone, or 0 outside the
    /// enclosure of f over the span).
    pub pretest: bool,
    /// Skip spans whose local control points lie inside the box found so far.
    pub prune: bool,
    /// Measure the time spent in derivative evaluations (two clock reads per evaluation).
    pub time_derivatives: bool,
}

impl Default for Newton {
    fn default() -> Self {
        Newton {
            tol: 1e-12,
            refine_unique: true,
            max_iter: 40,
            max_boxes: 4000,
            split: Split::Bisect,
            min_shrink: 0.5,
            form: DerivForm::Numerator,
            pretest: true,
            prune: true,
            time_derivatives: false,
        }
    }
}

impl Newton {
    /// The thesis's settings (listing `inewtonKNRH`, lines 1766-1850): C' / C'' by the quotient
    /// rule, split into 2p pieces only when a step makes no progress, at most 20 steps per box,
    /// stop at radius <= tol (the thesis does not state its tol; 1e-6 is assumed), every span
    /// searched (no pre-tests, no pruning), derivative time measured (its tables' columns).
    /// Unlike the thesis, unresolved boxes are kept (enclosed as a whole), so it stays sound.
    pub fn thesis() -> Self {
        Newton {
            tol: 1e-6,
            refine_unique: false,
            max_iter: 20,
            max_boxes: 100_000,
            split: Split::TwiceDegree,
            min_shrink: 1.0,
            form: DerivForm::Quotient,
            pretest: false,
            prune: false,
            time_derivatives: true,
        }
    }

    /// Default settings with another tolerance.
    pub fn with_tol(tol: f64) -> Self {
        Newton {
            tol,
            ..Default::default()
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
    /// scratch for de Boor
    buf: Vec<Interval>,
    /// Newton box stack
    stack: Vec<(f64, f64)>,
    /// coordinate currently worked on
    j: usize,
    stats: Stats,
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
            buf: Vec::with_capacity(2 * (p + 1)),
            stack: Vec::new(),
            j: 0,
            stats: Stats::default(),
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

    /// Enclosure of C_j over / at `u` in the closed span k.
    fn value(&mut self, k: usize, u: Interval) -> Interval {
        self.stats.point_evaluations += 1;
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
        let r = match self.s.form {
            DerivForm::Quotient => self.value_and_slope(k, u).1,
            DerivForm::Numerator => {
                let (a, w) = self.level(0, k, u);
                let (a1, w1) = self.level(1, k, u);
                if self.rational {
                    a1 * w - a * w1
                } else {
                    a1
                }
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
        let (a, w) = self.level(0, k, u);
        let (a2, w2) = self.level(2, k, u);
        let r = if !self.rational {
            a2
        } else {
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

    /// Outer enclosure of C_j over the candidate box, and an enclosure of a value the curve
    /// attains (if `attained`).
    fn eval_cand(&mut self, cd: &Cand) -> (Interval, Option<Interval>) {
        let k = cd.k;
        if cd.lo == cd.hi {
            let v = self.value(k, iv::point(cd.lo));
            return (v, cd.attained.then_some(v));
        }
        // Mean-value form (Moore): for u in X, C(u) = C(m) + C'(xi)(u - m) with xi in X, so
        // C(X) is inside C(m) + C'(X)(X - m). Intersected with the direct enclosure C(X) (both
        // contain the range). m lies in [lo, hi) inside span k, where the curve is this piece.
        let m = midpoint(cd.lo, cd.hi);
        let x = iv::span(cd.lo, cd.hi);
        let cm = self.value(k, iv::point(m));
        self.stats.point_evaluations += 1;
        let (cx, dx) = self.value_and_slope(k, x);
        let mv = cm + dx * (x - iv::point(m));
        let mut enc = mv.intersection(cx);
        // Convex hull of the local control points (thesis prop. 2.1): exact and always sound;
        // guards against overflowed (infinite) interval evaluations.
        let (hmin, hmax) = self.local_hull(k);
        enc = enc.intersection(iv::span(hmin, hmax));
        if enc.is_empty() {
            // cannot happen mathematically (all three contain the range); stay sound anyway
            enc = iv::span(hmin, hmax);
        }
        (enc, cd.attained.then_some(cm))
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
    /// of f in [a, b] ends up in a box pushed to `out`. Returns false if a limit was hit.
    fn search(&mut self, k: usize, a: f64, b: f64, out: &mut Vec<ZeroBox>) -> Termination {
        let s = *self.s;
        let (d0, d1) = self.c.domain();
        let tol = s.tol * (d1 - d0);
        let mut term = Termination::Converged;
        self.stack.clear();
        self.stack.push((a, b));
        let mut boxes = 0usize;
        while let Some((mut x0, mut x1)) = self.stack.pop() {
            boxes += 1;
            if boxes > s.max_boxes {
                // Box limit: keep the box whole (sound).
                out.push(ZeroBox {
                    lo: x0,
                    hi: x1,
                    unique: false,
                });
                term = Termination::BoxLimit;
                continue;
            }
            let mut unique = false;
            let mut it = 0;
            loop {
                let small = 0.5 * (x1 - x0) <= tol;
                if small && !(unique && s.refine_unique) {
                    out.push(ZeroBox {
                        lo: x0,
                        hi: x1,
                        unique,
                    });
                    break;
                }
                if it >= s.max_iter {
                    if !(small || unique) && term == Termination::Converged {
                        term = Termination::IterationLimit;
                    }
                    out.push(ZeroBox {
                        lo: x0,
                        hi: x1,
                        unique,
                    });
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
                    // Two pieces: iterate on one, keep the other (thesis lines 70-100).
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
                if n0 == x0 && n1 == x1 {
                    // no progress at all
                    if unique || !can_split(x0, x1) {
                        out.push(ZeroBox {
                            lo: x0,
                            hi: x1,
                            unique,
                        });
                        break;
                    }
                    self.split_box(x0, x1);
                    break;
                }
                if !unique && n1 - n0 > s.min_shrink * (x1 - x0) && can_split(n0, n1) {
                    self.split_box(n0, n1);
                    break;
                }
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
        let (a, b) = self.c.domain();
        let ns = self.spans.len();
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
            let mode = modes[si];
            if mode == SpanMode::Skip {
                continue;
            }
            if mode == SpanMode::Prune {
                let (hmin, hmax) = self.local_hull(k);
                if hmin >= acc.lo && hmax <= acc.hi {
                    continue;
                }
            }
            if self.s.pretest {
                let (inc, dec) = self.monotone(k);
                if inc || dec {
                    status[si] = Status::Mono { inc, dec };
                    continue;
                }
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
            let t = self.search(k, sa, sb, &mut boxes);
            if term == Termination::Converged {
                term = t;
            }
            for zb in &boxes {
                let cd = Cand {
                    k,
                    lo: zb.lo,
                    hi: zb.hi,
                    kind: CandidateKind::Critical,
                    unique: zb.unique,
                    attained: true,
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

    fn add(&mut self, cd: &Cand, e: Interval, attained: Option<Interval>) {
        // An empty enclosure cannot occur (every value evaluated is a real number); treat it
        // as "anything" to stay sound.
        let e = if e.is_empty() { Interval::ENTIRE } else { e };
        self.lo = self.lo.min(e.inf());
        self.hi = self.hi.max(e.sup());
        if let Some(v) = attained.filter(|v| !v.is_empty()) {
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
