//! The search engine of the Newton-based strategies: knot spans, candidates (domain ends,
//! non-differentiable knots, the knot rule), the pre-tests, and the interval Newton loop with
//! the extended division and the split rules (thesis `inewtonKNRH`), with the argument why
//! nothing is missed ([`Engine::coord`]).
//!
//! Every evaluation of C_j, f and f' takes a [`SpanParam`]: a box of the curve parameter u
//! (interval de Boor) or of the span's local parameter t (its Bernstein form, [`SpanPoly`]).

use super::acc::{Acc, Cand};
use super::bernstein::{pair_coefficients, SpanPoly};
use super::param::{can_split, midpoint, Space, SpanParam, T, U};
use super::{DerivForm, Newton, Split, BERNSTEIN_MAX_DEGREE, EVALS_PER_SPAN, WORK_PER_SPAN};
use crate::enclose::{CandidateKind, CoordBox, Stats, Termination};
use crate::num::ddi::Ddi;
use crate::num::{iv, pool, Scalar};
use crate::num::mr::Mr;
use crate::spline::curve::NurbsCurve;
use crate::spline::eval::CurveEval;
use crate::spline::knots::multiplicity;
use crate::spline::tight::TightEval;
use inari::Interval;
use smallvec::SmallVec;
use std::time::Instant;

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

/// A box the Newton search kept.
#[derive(Debug, Clone, Copy)]
struct ZeroBox {
    /// the box, in the space of the span's search
    x: SpanParam,
    unique: bool,
}

pool::pooled!(ZeroBox => ZERO_BOX_POOL);

/// Shared machinery of the Newton-based strategies (`newton`, `search-region`,
/// `search-region-verified`): one per curve, reused over the coordinates.
pub(crate) struct Engine<'a> {
    c: &'a NurbsCurve,
    s: &'a Newton,
    /// interval de Boor on the derivative splines, built on first use (a search in the local
    /// parameter through the span's Bernstein form never needs it)
    ev: std::cell::OnceCell<CurveEval<Interval>>,
    p: usize,
    d: usize,
    rational: bool,
    /// non-empty spans of the domain: (k, u_k, u_{k+1}), in order
    pub(crate) spans: Vec<(usize, f64, f64)>,
    /// `nd[i]`: the knot between spans i and i + 1 is non-differentiable (multiplicity >= p)
    nd: Vec<bool>,
    /// tight candidate evaluation
    tight: TightEval<'a>,
    /// scratch for de Boor
    buf: Vec<Interval>,
    /// Newton box stack
    stack: Vec<(f64, f64)>,
    /// scratch for the f64 zero estimates of the float-first seeding
    est: Vec<super::bernstein::Estimate>,
    /// the zero-free intervals of `seed_float_first` (reused)
    free: Vec<(f64, f64)>,
    /// the boxes and the gaps of `seed_float_first` (reused)
    seed_boxes: Vec<(f64, f64)>,
    seed_gaps: Vec<(f64, f64, u32)>,
    /// coordinate currently worked on
    j: usize,
    /// Bernstein form of the span being worked on ([`Newton::bezier_pretest`],
    /// [`Newton::bernstein`])
    poly: Option<SpanPoly>,
    /// whether the Newton search evaluates through `poly` ([`Newton::bernstein`])
    bern: bool,
    /// `pair[i (p + 1) + l]` (i < l): (l - i) C(p, i) C(p, l) / C(2p - 2, i + l - 1), the
    /// coefficients of the rational derivative numerator (see [`SpanPoly::new`])
    pair: Option<std::rc::Rc<[Mr]>>,
    stats: Stats,
    /// evaluations allowed for the current coordinate ([`Newton::max_work`])
    budget: u64,
}

/// The engine's vectors go back to this thread's pool (`num::pool`) for the next curve.
impl Drop for Engine<'_> {
    fn drop(&mut self) {
        pool::give(std::mem::take(&mut self.spans));
        pool::give(std::mem::take(&mut self.nd));
        pool::give(std::mem::take(&mut self.buf));
        pool::give(std::mem::take(&mut self.stack));
        pool::give(std::mem::take(&mut self.est));
        pool::give(std::mem::take(&mut self.free));
        pool::give(std::mem::take(&mut self.seed_boxes));
        pool::give(std::mem::take(&mut self.seed_gaps));
    }
}

impl<'a> Engine<'a> {
    /// Precompute derivative splines and the span structure of `c`.
    pub(crate) fn new(c: &'a NurbsCurve, s: &'a Newton) -> Self {
        let p = c.degree();
        let kn = c.knots();
        // (the vectors from this thread's pool, `num::pool`, handed back on drop)
        let mut spans: Vec<(usize, f64, f64)> = pool::take(c.num_points() - p);
        spans.extend(
            (p..c.num_points())
                .filter(|&k| kn[k] < kn[k + 1])
                .map(|k| (k, kn[k], kn[k + 1])),
        );
        let mut nd = pool::take(spans.len());
        nd.extend(spans.windows(2).map(|w| multiplicity(kn, w[0].2) >= p));
        Engine {
            c,
            s,
            ev: std::cell::OnceCell::new(),
            p,
            d: c.dim(),
            rational: c.is_rational(),
            spans,
            nd,
            tight: TightEval::sweeping(c),
            buf: pool::take(2 * (p + 1)),
            stack: pool::take(0),
            est: pool::take(0),
            free: pool::take(0),
            seed_boxes: pool::take(0),
            seed_gaps: pool::take(0),
            j: 0,
            poly: None,
            bern: s.bernstein && (1..=BERNSTEIN_MAX_DEGREE).contains(&p),
            pair: if c.is_rational()
                && (s.bernstein || s.bezier_pretest)
                && (1..=BERNSTEIN_MAX_DEGREE).contains(&p)
            {
                Some(pair_coefficients(p))
            } else {
                None
            },
            stats: Stats::default(),
            budget: u64::MAX,
        }
    }

    /// Span indices (into `spans`) with the spans meeting the supports of the control points
    /// `first` in front, then all others in order (a vector from this thread's pool: hand it
    /// back with `num::pool::give` after use).
    pub(crate) fn order_with_first(&self, first: &[usize]) -> Vec<usize> {
        let p = self.p;
        let near = |k: usize| first.iter().any(|&i| k >= i && k <= i + p);
        let mut order: Vec<usize> = pool::take(self.spans.len());
        order.extend((0..self.spans.len()).filter(|&s| near(self.spans[s].0)));
        order.extend((0..self.spans.len()).filter(|&s| !near(self.spans[s].0)));
        order
    }

    /// (A_j^(l), w^(l)) over / at `u` (inside the closed span k), l <= 2.
    fn level(&mut self, l: usize, k: usize, u: Interval) -> (Interval, Interval) {
        if l > self.p {
            return (iv::point(0.0), iv::point(0.0));
        }
        let c = self.c;
        let (j, d) = (self.j, self.d);
        let rows: &[usize] = if self.rational { &[j, d] } else { &[j] };
        let v = self
            .ev
            .get_or_init(|| CurveEval::new(c, 2))
            .level(l)
            .eval_span_rows(k - l, &u, rows, &mut self.buf);
        // a polynomial curve: w = 1, so w' = w'' = 0
        let w = match v.get(1) {
            Some(&w) => w,
            None => iv::point(if l == 0 { 1.0 } else { 0.0 }),
        };
        (v[0], w)
    }

    /// The Bernstein form of span k, if it is the one at hand.
    fn span_poly(&self, k: usize) -> Option<&SpanPoly> {
        self.poly.as_ref().filter(|sp| sp.k == k)
    }

    /// The Bernstein form of span k for an evaluation over a box `t` of its local parameter.
    /// Boxes of t are only made by the search of span k after building that form, so it is
    /// always there; if not, nothing is known (ENTIRE, sound) and debug builds panic.
    fn local(&self, k: usize, t: T) -> Option<&SpanPoly> {
        let sp = self.span_poly(k);
        debug_assert!(
            sp.is_some(),
            "local parameter {t:?} without span {k}'s Bernstein form"
        );
        sp
    }

    /// Enclosure of C_j over / at `x` in the closed span k: interval de Boor for a box of u,
    /// the span's Bernstein form ([`Newton::bernstein`]) for a box of its local parameter t.
    fn value(&mut self, k: usize, x: SpanParam) -> Interval {
        self.stats.point_evaluations += 1;
        let u = match x {
            SpanParam::Local(t) => {
                return self.local(k, t).map_or(Interval::ENTIRE, |sp| sp.values(t))
            }
            SpanParam::Global(u) => u.interval(),
        };
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

    /// f at / over `x` (see [`DerivForm`]; over a box of t, the Bernstein form's F): its zeros
    /// in span k are the critical points of C_j.
    fn f(&mut self, k: usize, x: SpanParam) -> Interval {
        let t = self.s.time_derivatives.then(Instant::now);
        self.stats.derivative_evaluations += 1;
        let r = match (x, self.s.form) {
            // the Bernstein form's F(t): same sign and zeros as C_j' (see SpanPoly)
            (SpanParam::Local(tx), _) => self.local(k, tx).map_or(Interval::ENTIRE, |sp| sp.f(tx)),
            (SpanParam::Global(u), DerivForm::Quotient) => self.value_and_slope(k, u.interval()).1,
            // (non-rational: f = A_j', no level-0 evaluation)
            (SpanParam::Global(u), DerivForm::Numerator) if !self.rational => {
                self.level(1, k, u.interval()).0
            }
            (SpanParam::Global(u), DerivForm::Numerator) => {
                let u = u.interval();
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

    /// f at the point m for the Newton step N(X) = m - f(m) / f'(X) (`dx` = f'(X)), with the
    /// box tolerance `tol`. In the local parameter the f64 value with its a-priori bound
    /// ([`SpanPoly::f_value_f64`]) is taken where it is as good as the sharp one for the
    /// step: when it excludes 0, or when its width is far below the tolerance against |f'(X)|
    /// (N(X) is then within 2 E / mig f'(X) <= tol / 8 of m, so the box reaches the tolerance
    /// in the same step; any enclosure of f(m) gives a sound N(X), Theorem 5.1). Otherwise, and
    /// in the global parameter, [`Engine::f`].
    fn f_newton(&mut self, k: usize, space: Space, m: f64, dx: Interval, tol: f64) -> Interval {
        if space == Space::Local {
            let t = self.s.time_derivatives.then(Instant::now);
            let fast = self.span_poly(k).and_then(|sp| sp.f_value_f64(m));
            if let Some(t) = t {
                self.stats.time_derivatives += t.elapsed();
            }
            if let Some((v, e)) = fast {
                if !v.contains(0.0) || 16.0 * e <= dx.mig() * tol {
                    self.stats.derivative_evaluations += 1;
                    return v;
                }
            }
        }
        self.f(k, space.param(m, m))
    }

    /// f' over `x` in span k (over a box of t, the Bernstein form's F').
    fn df(&mut self, k: usize, x: SpanParam) -> Interval {
        let t = self.s.time_derivatives.then(Instant::now);
        self.stats.derivative_evaluations += 1;
        let r = match x {
            // F'(t), the derivative of the f above
            SpanParam::Local(tx) => self.local(k, tx).map_or(Interval::ENTIRE, |sp| sp.df(tx)),
            SpanParam::Global(u) if !self.rational => self.level(2, k, u.interval()).0,
            SpanParam::Global(u) => self.df_rational(k, u.interval()),
        };
        if let Some(t) = t {
            self.stats.time_derivatives += t.elapsed();
        }
        r
    }

    /// f' of a rational curve over `u` in span k by interval de Boor.
    fn df_rational(&mut self, k: usize, u: Interval) -> Interval {
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
    }

    /// Outer enclosure of C_j over the candidate box, enclosures of values the curve attains
    /// (if `attained`; EMPTY for none), and the double-double enclosure of one of those values
    /// where there is one (for strict witnesses, [`Acc::add`]).
    fn eval_cand(&mut self, cd: &Cand) -> (Interval, [Interval; 2], Option<Ddi>) {
        let k = cd.k;
        // Convex hull of the local control points (thesis prop. 2.1): exact and always sound
        // for every value of span k's piece on the closed span (also the limit at its end);
        // it also caps evaluations that overflowed.
        let (hmin, hmax) = self.local_hull(k);
        let hull = iv::span(hmin, hmax);
        self.stats.point_evaluations += 1;
        let U { lo, hi } = cd.u;
        let mut tight = None;
        let (enc, at) = if lo == hi && !cd.attained {
            // Left limit at a discontinuity q: span k's piece on [q-, q] (q- the float below
            // q, still in span k) contains it; TightEval adds the curve's value C(q) there,
            // itself a candidate, so the outer box does not grow from it.
            let q = lo;
            let v = self.tight.coord_over(self.j, f64::next_down(q), q);
            (v, [v, Interval::EMPTY])
        } else if lo == hi {
            // C(q) about one ulp wide (TightEval, double-double Horner); the curve's value at q
            // is span k's piece there (k is q's span, or the curve is continuous at q)
            let (v, d) = self.tight.coord_at_tight(self.j, lo);
            tight = d;
            (v, [v, Interval::EMPTY])
        } else if let Some((enc, v, v0)) = cd
            .t
            .zip(self.span_poly(k))
            .and_then(|(t, sp)| sp.tight_over(t))
            .filter(|(enc, ..)| enc.sup() <= enc.inf().next_up().next_up())
        {
            // A box of the Bernstein search in span k's local parameter t, enclosed from the
            // span's double-double points by the mean value form around its midpoint
            // (`SpanPoly::tight_over`; about one ulp wide on a converged box, so the Taylor
            // expansions of the span that the form below builds are not needed). The curve
            // attains v (a parameter inside the span) and, at the span's start u_k, v0 (as
            // `coord_at(lo)` below, for a box that starts at the knot).
            self.stats.point_evaluations += 1;
            tight = Some(v);
            // (two ulps wide: the mean value form's r |F| / wmin^2 is wide where weights are
            // tiny; then also the Taylor form over the box in u, `TightEval::coord_over`, as the
            // `bezier` strategy's fast path does: both enclose the piece's values over the box,
            // and a bound one ulp looser costs the certificate a lowering proof)
            let enc = if enc.sup() > enc.inf().next_up() {
                let both = enc.intersection(self.tight.coord_over(self.j, lo, hi));
                if both.is_empty() {
                    enc
                } else {
                    both
                }
            } else {
                enc
            };
            let at_knot = lo == self.c.knots()[k];
            let cm = [
                v.to_interval(),
                if at_knot {
                    self.stats.point_evaluations += 1;
                    v0.to_interval()
                } else {
                    Interval::EMPTY
                },
            ];
            (enc, cm)
        } else {
            // C over the box (TightEval: second-order Taylor form around the midpoint m,
            // about one ulp wide near a critical point); m is in [lo, hi) inside span k, where
            // the curve is this piece, so C(m) is attained. So is C(lo) (lo < hi <= u_{k+1}),
            // evaluated too when lo is the knot u_k (Bernstein boxes, whose parameter maps are
            // rounded outward): a critical point at a knot is often the extremum, and the
            // boxes on both sides only reach it at an end.
            self.stats.point_evaluations += 1;
            let m = midpoint(lo, hi);
            let at_knot = cd.t.is_some() && lo == self.c.knots()[k];
            let (vm, d) = self.tight.coord_at_tight(self.j, m);
            tight = d;
            let cm = [
                vm,
                if at_knot {
                    self.stats.point_evaluations += 1;
                    self.tight.coord_at(self.j, lo)
                } else {
                    Interval::EMPTY
                },
            ];
            let mut enc = self.tight.coord_over(self.j, lo, hi);
            let mut cm = cm;
            // (skipped when the Taylor enclosure is already within two ulps: the Bézier hull
            // below cannot make it narrower than the f64 resolution, and C(m) above is
            // already an attained value)
            let narrow = enc.sup() <= enc.inf().next_up().next_up();
            if let (false, Some(t), Some(sp)) = (narrow, cd.t, self.span_poly(k)) {
                // The hull of the Bézier points of the piece over [t0, t1] (convex hull
                // property, see SpanPoly::values): also an enclosure of its values on the box,
                // and far tighter than [lo, hi] when the span is below the f64 resolution of
                // u (a 1e-12 span at u ~ 6: C'' ~ 1e24 times ulp(u)^2). The piece's value at
                // u(t_mid), a real in the span, is attained.
                let (b, at) = sp.values_tight(t);
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
        (enc, at, tight.filter(|_| cd.attained))
    }

    /// min / max of coordinate j of the local control points P_{k-p} .. P_k (exact).
    fn local_hull(&self, k: usize) -> (f64, f64) {
        self.c.coord_range(self.j, k - self.p..=k)
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

    /// Interval Newton on f over the closed span k, given as the box `span` = [a, b] in the
    /// space the search runs in ([u_k, u_{k+1}] of u, or [0, 1] of t; every box of the search
    /// is in that space) (thesis `inewtonKNRH`): every zero of f in [a, b] ends up in a box
    /// pushed to `out`, or in a box dropped because its values provably lie in `covered`
    /// (= [inner_lo, inner_hi] so far, values the curve attains on both sides, so the box's
    /// values are inside the final outer box anyway).
    fn search(
        &mut self,
        k: usize,
        span: SpanParam,
        covered: (f64, f64),
        out: &mut Vec<ZeroBox>,
    ) -> Termination {
        let s = *self.s;
        let space = span.space();
        let (a, b) = span.bounds();
        // relative to the span: a span of 1e-12 needs boxes far below 1e-12 of the domain
        let tol = s.tol * (b - a);
        let mut term = Termination::Converged;
        let hull = {
            let (h0, h1) = self.local_hull(k);
            iv::span(h0, h1)
        };
        self.stack.clear();
        if !(s.fast_path && space == Space::Local && self.seed_float_first(k, a, b)) {
            self.stack.push((a, b));
        }
        let mut boxes = 0usize;
        let mut splits = 0u32;
        while let Some((mut x0, mut x1)) = self.stack.pop() {
            boxes += 1;

            let keep = |x0: f64, x1: f64, unique: bool, out: &mut Vec<ZeroBox>| {
                out.push(ZeroBox {
                    x: space.param(x0, x1),
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
                let v = self.value(k, space.param(x0, x1)).intersection(hull);
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
                let dx = self.df(k, space.param(x0, x1));
                let fm = self.f_newton(k, space, m, dx, tol);
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
                if weak && s.fast_path && self.settled(k, space, (a, b), n0, n1) {
                    // (no zero proved or excluded, but the curve's values over the box are
                    // already known to the stopping gap: keep it whole instead of halving it
                    // down to the tolerance)
                    keep(n0, n1, false, out);
                    break;
                }
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

    /// Whether the values of C_j over the box [x0, x1] (in `space`, of the span with bounds
    /// `(a, b)` there) are known to within the stopping gap (two ulps of the coordinate scale)
    /// by the tight enclosure ([`TightEval::coord_over`], a second-order Taylor form): then a
    /// box on which the Newton step stalls (f(m) not separated from 0, e.g. next to a zero of
    /// C_j' at a knot, where the derivative numerator cancels to rounding noise) is kept whole,
    /// and its candidate (enclosed by the same form in `eval_cand`) is as tight as the
    /// tolerance-sized boxes that halving it would produce, without the thousands of boxes.
    /// Only boxes below 2^-20 of their span are tried (there the Taylor form is tight; on wider
    /// boxes the test would cost an evaluation and fail).
    fn settled(&mut self, k: usize, space: Space, (a, b): (f64, f64), x0: f64, x1: f64) -> bool {
        if x1 - x0 > (b - a) * (1.0 / 1_048_576.0) || x1.is_nan() || x0.is_nan() {
            return false;
        }
        let (u0, u1) = match space {
            Space::Local => {
                let kn = self.c.knots();
                super::param::local_to_u(kn[k], kn[k + 1], x0, x1)
            }
            Space::Global => (x0, x1),
        };
        self.stats.point_evaluations += 1;
        let v = self.tight.coord_over(self.j, u0, u1);
        let gap = 2.0 * crate::num::ulp(self.c.coord_scale(self.j));
        v.sup() - v.inf() <= gap
    }

    /// Float first, prove after ([`Newton::fast_path`], Bernstein search of span k over the
    /// local parameter [a, b] = [0, 1]): seed the Newton stack with a partition of [a, b]
    /// instead of the whole span. f64 estimates r_i of the zeros of F
    /// ([`SpanPoly::zero_estimates`]) get tiny boxes [r_i - h, r_i + h] (h = 2^-30, far above
    /// the error of an estimate of a simple zero), which go on the stack: the first interval
    /// Newton step on such a box proves a zero there unique (N(X) in the interior of X, the
    /// test of the loop below; Moore; Hansen thm. 9.6.8) and shrinks it to about 2^-45, within
    /// the tolerance (further steps to machine precision only with [`Newton::refine_unique`]).
    /// The parts of the gaps between the boxes (and the ends) that the
    /// estimation's own proofs do not cover (`free` intervals: pieces of its subdivision whose
    /// coefficients have one proven sign, or one proven sign change with F of opposite proven
    /// signs at the ends of the piece's box, so that Descartes' rule of signs leaves the box
    /// the piece's only zero; [`SpanPoly::zero_estimates`]) are each excluded if the
    /// enclosure of F over it (hull of its Bernstein coefficients restricted to the gap by
    /// de Casteljau in `Mr`, every coefficient enclosing the exact one: the rounding error is
    /// inside the enclosure, no separate a-priori bound needed) excludes 0, after at most
    /// two halvings. If some gap is not excluded, nothing is pushed and the whole span is
    /// searched as without the seeding (the fallback); before that, where F's `Mr`
    /// coefficients are wide against their own size ([`SpanPoly::refined`]), the same once
    /// more with F recomputed from the span's double-double points, which the search then
    /// uses too (the same polynomial, enclosed more tightly). Sound: the boxes and gaps cover
    /// [a, b], and a dropped gap holds no zero of F, i.e. of C_j' (same sign and zeros on the
    /// closed span). Returns whether the stack was seeded; counts the span in
    /// `Stats::fast_proofs` (seeded) or `Stats::fast_fallbacks` (estimates, but a gap not
    /// excluded).
    fn seed_float_first(&mut self, k: usize, a: f64, b: f64) -> bool {
        const H: f64 = super::bernstein::FLOAT_FIRST_H; // 2^-30
        let (mut bx, mut gaps) = (std::mem::take(&mut self.seed_boxes), std::mem::take(&mut self.seed_gaps));
        let (mut seeded, mut estimated) = (false, false);
        // (the span's form, then, where F's `Mr` coefficients were too wide for the proof,
        // against the small ones next to a zero or altogether, once more with F from the
        // span's double-double points, `SpanPoly::refined`, which then also serves the search;
        // the `bezier` strategy's general fast path does the same)
        let local = a == 0.0 && b == 1.0;
        for retry in [false, true].into_iter().filter(|_| local) {
            if retry {
                match self.span_poly(k).and_then(SpanPoly::refined) {
                    Some(r) if !r.f_swamped() => self.poly = Some(r),
                    _ => break,
                }
            }
            let (mut est, mut free) = (std::mem::take(&mut self.est), std::mem::take(&mut self.free));
            let ok = match self.span_poly(k) {
                Some(sp) => sp.zero_boxes(H, 2 * self.p + 2, (&mut est, &mut free), &mut bx, &mut gaps),
                None => false,
            };
            (self.est, self.free) = (est, free);
            estimated |= ok;
            seeded = ok && self.exclude_gaps(k, &mut gaps);
            if seeded {
                break;
            }
        }
        if seeded {
            self.stack.extend(bx.iter().copied());
            self.stats.fast_proofs += 1;
        } else if estimated {
            self.stats.fast_fallbacks += 1;
        }
        (self.seed_boxes, self.seed_gaps) = (bx, gaps);
        seeded
    }

    /// The gaps of [`Engine::seed_float_first`] on span k excluded (F has no zero in them:
    /// [`SpanPoly::exclude_gaps`]), or `false` (then counted in `Stats::fast_fallbacks` by the
    /// caller): see there. `gaps` is used up. (A gap not excluded: the whole span is searched
    /// as without the seeding; a gap whose end is next to a zero just outside it would make
    /// the Newton steps crawl towards that end.)
    fn exclude_gaps(&mut self, k: usize, gaps: &mut Vec<(f64, f64, u32)>) -> bool {
        let Some(sp) = self.local(k, T::new(0.0, 1.0)) else {
            return false;
        };
        // (the evaluations of F: one per gap and halving, as the search counts them)
        let mut n = 0;
        let ok = sp.exclude_gaps(gaps, &mut n);
        self.stats.derivative_evaluations += n;
        ok
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
    /// contains it; if in a covered span whose control hull lies between values the curve
    /// attains, the extremes are elsewhere; a span covered because its Bézier points peak at
    /// an end on each side they leave open (`SpanPoints::end_peaked`) holds no maximizer
    /// but a domain end or a non-differentiable knot (the piece's maximum over the span is at
    /// such an end, where C_j' is not zero: a smooth knot there is no maximizer). Otherwise
    /// u* lies in a run of monotone spans: moving u* right through non-decreasing spans and
    /// left through non-increasing ones keeps it a maximizer, and it ends at a run end
    /// (handled above) or at a knot with a non-decreasing span on the left and a span on the
    /// right that is not non-decreasing: exactly the knots the rule below adds.
    pub(crate) fn coord(&mut self, j: usize, order: &[usize], modes: &[SpanMode]) -> CoordBox {
        let t0 = crate::enclose::Clock::start();
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
        let mut cands: SmallVec<[Cand; 8]> = SmallVec::new();
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
            let (e, at, w) = self.eval_cand(cd);
            acc.add(cd, e, at, w);
        }
        let mut status: SmallVec<[Status; 16]> = SmallVec::from_elem(Status::Covered, ns);
        let mut term = Termination::Converged;
        // values the curve attains on both sides: the accumulator's inner bounds (kept up to
        // date below after each candidate) and the cheap bounds of the Newton boxes
        let (mut cheap_lo, mut cheap_hi) = (acc.inner_lo, acc.inner_hi);
        let mut boxes: Vec<ZeroBox> = pool::take(0);
        for &si in order {
            let (k, sa, sb) = self.spans[si];
            // whether the search of this span evaluates through `poly`: `bern`, unless the
            // span's F is swamped by its rounding ([`SpanPoly::f_swamped`]; then interval
            // de Boor); it then runs in the local parameter t
            let mut bern_span = false;
            let mode = modes[si];
            if mode == SpanMode::Skip {
                continue;
            }
            if mode == SpanMode::Prune {
                let (hmin, hmax) = self.local_hull(k);
                // Values the curve attains on both sides (inner bounds): the span's values lie
                // between them, so inside the final outer box, and the extremes are elsewhere.
                if hmin >= cheap_lo && hmax <= cheap_hi {
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
                // The span's Bézier points from its double-double points, shared with the
                // other coordinates and the candidates' values (`TightEval::bezier_points`):
                // their hull and monotonicity (`bezier::span_points`: convex hull property,
                // each point enclosed, the quotients of the homogeneous points for a rational
                // curve). Inside the values the curve attains on both sides, the span is
                // covered as by the local hull above, without building its Bernstein form.
                let pts = self.tight.bezier_points(k);
                let sp = crate::enclose::bezier::span_points(pts, self.p, j, self.rational);
                let (blo, bhi, inc, dec) = (sp.lo, sp.hi, sp.inc, sp.dec);
                let bp = self.s.bezier_pretest;
                if (self.s.fast_path || bp)
                    && mode == SpanMode::Prune
                    && blo >= cheap_lo
                    && bhi <= cheap_hi
                {
                    self.stats.fast_exits += self.s.fast_path as u64;
                    continue;
                }
                self.poly = None;
                if bp && self.s.pretest && (inc || dec) {
                    status[si] = Status::Mono { inc, dec };
                    continue;
                }
                // A span that the Bézier points leave open only on sides where they peak at
                // an end (`SpanPoints::end_peaked`): on such a side the piece's extreme over
                // the closed span is an end value, at an end where the piece's derivative is
                // not zero. At a domain end or a non-differentiable knot that value is a
                // candidate already (for a jump at u_{k+1}, b_p is the left limit, also one);
                // at a smooth knot (multiplicity < p, C^1) C_j' is not zero there, so the
                // neighbouring span holds larger (smaller) values and no extreme lies in this
                // span. A side the prune test's values attained enclose needs nothing either.
                // So the span holds no extreme but at candidates: covered, as in the argument
                // above, without its Bernstein form.
                if mode == SpanMode::Prune
                    && (self.s.fast_path || bp)
                    && (bhi <= cheap_hi || sp.end_peaked(1.0))
                    && (blo >= cheap_lo || sp.end_peaked(-1.0))
                {
                    self.stats.fast_exits += 1;
                    continue;
                }
                // (built only for a span the Bézier points leave open: O(p^2) per coordinate)
                let sp = SpanPoly::new(self.c, self.j, k, self.pair.as_deref().unwrap_or(&[]), pts);
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
                bern_span = self.bern && !sp.f_swamped();
                self.poly = Some(sp);
            }
            if self.s.pretest && !bern_span {
                let fx = self.f(k, SpanParam::Global(U::new(sa, sb)));
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
            let span = if bern_span {
                SpanParam::Local(T::new(0.0, 1.0))
            } else {
                SpanParam::Global(U::new(sa, sb))
            };
            let t = self.search(k, span, (cheap_lo, cheap_hi), &mut boxes);
            if term == Termination::Converged {
                term = t;
            }
            if t == Termination::WorkLimit && boxes.len() > 1 {
                // Out of budget: the boxes left are enclosed as one (their hull, still inside
                // the span), so that the work after the limit is one evaluation per span, not
                // one per box (2p boxes of O(p^2) each took minutes at degree 800).
                let lo = boxes
                    .iter()
                    .map(|zb| zb.x.bounds().0)
                    .fold(f64::INFINITY, f64::min);
                let hi = boxes
                    .iter()
                    .map(|zb| zb.x.bounds().1)
                    .fold(f64::NEG_INFINITY, f64::max);
                boxes.clear();
                boxes.push(ZeroBox {
                    x: span.space().param(lo, hi),
                    unique: false,
                });
            }
            // Values the curve attains, from the cheap enclosures of this span's boxes too:
            // a box's values all lie in v = [SpanPoly::values], and the curve takes a value in
            // the (non-empty) box, so it attains a value >= inf v and one <= sup v.
            let cheap: SmallVec<[Interval; 8]> = boxes
                .iter()
                .map(|zb| match (zb.x, self.span_poly(k)) {
                    (SpanParam::Local(t), Some(sp)) => sp.values(t),
                    _ => Interval::ENTIRE,
                })
                .collect();
            for v in cheap.iter().filter(|v| !v.is_empty() && v.is_common_interval()) {
                cheap_lo = cheap_lo.min(v.sup());
                cheap_hi = cheap_hi.max(v.inf());
            }
            for (zb, v) in boxes.iter().zip(&cheap) {
                // A box whose values lie strictly between values the curve attains holds
                // neither a maximizer nor a minimizer of C_j (if u* in it maximized C_j, then
                // max = C_j(u*) <= sup v < cheap_hi <= max), so the candidates elsewhere
                // (evaluated, or kept by the same test) cover both extremes: it needs no tight
                // evaluation (which builds the span's double-double Taylor data, the largest
                // cost of a high-degree span).
                if !v.is_empty() && v.inf() > cheap_lo && v.sup() < cheap_hi {
                    self.stats.fast_exits += 1;
                    continue;
                }
                let (u, t) = match zb.x {
                    SpanParam::Global(u) => (u, None),
                    SpanParam::Local(t) => match self.local(k, t) {
                        Some(sp) => (sp.to_u(t), Some(t)),
                        // (cannot happen, see Engine::local) the whole span is sound
                        None => (U::new(sa, sb), None),
                    },
                };
                let cd = Cand {
                    k,
                    u,
                    kind: CandidateKind::Critical,
                    unique: zb.unique,
                    attained: true,
                    t,
                };
                let (e, at, w) = self.eval_cand(&cd);
                acc.add(&cd, e, at, w);
                cheap_lo = cheap_lo.min(acc.inner_lo);
                cheap_hi = cheap_hi.max(acc.inner_hi);
            }
        }
        pool::give(boxes);
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
                    let (e, at, w) = self.eval_cand(&cd);
                    acc.add(&cd, e, at, w);
                }
            }
        }
        let mut stats = self.stats;
        stats.time_total = t0.elapsed();
        acc.finish(stats, term)
    }
}
