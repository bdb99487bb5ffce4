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
//!
//! Layout: this module holds the settings ([`Newton`], [`Split`], [`DerivForm`], the budget
//! constants) and the [`BoxEncloser`] impl; `engine` the search (spans, candidates, pre-tests,
//! the Newton loop, the knot rule and why nothing is missed); `bernstein` the per-span
//! Bernstein back-end; `acc` the candidate accumulator; `param` the typed parameter boxes
//! (global u, a span's local t) every evaluation takes.

mod acc;
pub(crate) mod bernstein;
mod engine;
mod param;
#[cfg(test)]
mod tests;

pub(crate) use engine::{Engine, SpanMode};
pub(crate) use param::{local_to_u, u_to_local};

use super::{BoxEncloser, Enclosure, Guarantee};
use crate::spline::curve::NurbsCurve;

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
    /// (machine precision; costs one or two quadratically convergent steps). Off by default:
    /// a box with its zero proved unique and its radius within `tol` is kept as it is (the
    /// float-first boxes, 2^-30 around an f64 estimate, come out of their first step about
    /// 2^-45 wide), since the tight forms that enclose the candidate's values (the mean value
    /// form from the span's double-double points, `SpanPoly::tight_over`, or the Taylor form
    /// in u) are about one ulp wide on such a box already: only the candidate's parameter
    /// interval is wider.
    pub refine_unique: bool,
    /// Newton steps per box (thesis: 20).
    pub max_iter: u32,
    /// Boxes per coordinate; the rest is enclosed as a whole.
    pub max_boxes: usize,
    /// Work budget per coordinate, in evaluations times (p + 1)^2 (the cost of one interval
    /// de Boor evaluation), plus an allowance per span of [`EVALS_PER_SPAN`] evaluations but
    /// at most [`WORK_PER_SPAN`] units (and at least 8 evaluations in all):
    /// once spent, every box still to search is enclosed as a whole (sound, maybe less tight;
    /// reported as [`super::Termination::WorkLimit`]). Bounds the time of high-degree curves, whose
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
    /// (Bézier points of C_j - c with c a control point value of the span, and the Bernstein
    /// coefficients of the derivative numerator, in [`crate::Mr`]) instead of interval de Boor
    /// over the box: the hull of the coefficients of the form restricted to a box
    /// (de Casteljau) overestimates the range by O(width^2), and the shift by c removes the
    /// cancellation of nearly flat coordinates (extreme weights, flat runs), where interval
    /// de Boor on the homogeneous rows cannot tell f from 0. The search then runs in the
    /// span's local parameter t in [0, 1] (finer than the f64 values of u on tiny spans far
    /// from 0), and the candidate boxes also get the double-double hull of their Bézier points.
    /// Also a pre-test: coefficients of one sign prove the span monotone. Degrees up to 256
    /// (above, interval de Boor; not in the thesis).
    pub bernstein: bool,
    /// Measure the time spent in derivative evaluations (two clock reads per evaluation).
    pub time_derivatives: bool,
    /// Float first, prove after (not in the thesis; off in [`Newton::thesis`]): per coordinate
    /// side, the cheap exit (the extreme control value is an attained end value) and, for a
    /// single quadratic / cubic Bézier segment, the root-isolating proof of the `bezier`
    /// strategy (f64 root estimates of C_j', proven signs of C_j' around them, root
    /// counting, a double-double Taylor enclosure over each tiny bracket:
    /// `crate::enclose::bezier` `fast_sides`). A coordinate whose two sides are not both
    /// proven within two ulps goes through the interval Newton search, which then also
    /// starts float first: per span, f64 estimates of the zeros of C_j' (Bernstein
    /// subdivision), a tiny box around each for the interval Newton steps (the first one
    /// proves the zero unique), and the rest of the span excluded by the sign of the enclosed
    /// Bernstein coefficients of the derivative numerator; only what is not excluded is
    /// searched from the whole box as before (`Engine::seed_float_first`). Spans of
    /// non-rational curves are first pruned by the hull of their double-double Bézier points
    /// (`bezier::span_points`). Counted in `Stats::fast_exits` /
    /// `fast_proofs` / `fast_fallbacks`.
    pub fast_path: bool,
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
            refine_unique: false,
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
            fast_path: true,
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
            fast_path: false,
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
    fn lane(&self) -> Option<super::lane::Lane> {
        // (the lane's tight answer is this strategy's own fast path, switched on by default)
        self.fast_path.then_some(super::lane::Lane::Tight)
    }
    fn enclose_prepared(&self, c: &NurbsCurve) -> Enclosure {
        let mode = if self.prune {
            SpanMode::Prune
        } else {
            SpanMode::Search
        };
        if self.fast_path && has_tiny_span(c) {
            // (see `has_tiny_span`: the bezier search, whose local refinement works in each
            // span's local parameter, as newton's own fallback for loose sides does)
            let mut e = super::bezier::BezierSubdivision::default().enclose_prepared(c);
            e.strategy = self.name();
            for cb in &mut e.coords {
                cb.stats.fast_fallbacks += 1;
            }
            return e;
        }
        // Built only when some coordinate needs the search.
        let mut engine: Option<(Engine, smallvec::SmallVec<[SpanMode; 32]>)> = None;
        let (a, b) = c.domain();
        let mut coords = super::Coords::new();
        for j in 0..c.dim() {
            if self.fast_path {
                let clock = super::Clock::start();
                let gap = 2.0 * crate::num::ulp(c.coord_scale(j));
                if let [Some((mut hi, ph)), Some((mut lo, pl))] =
                    super::bezier::fast_sides(c, j, gap)
                {
                    ph.count(&mut hi);
                    pl.count(&mut lo);
                    coords.push(super::bezier::coord_box(hi, lo, a, b, clock.elapsed()));
                    continue;
                }
            }
            let (e, modes) = engine.get_or_insert_with(|| {
                let e = Engine::new(c, self);
                let n = e.spans.len();
                (e, smallvec::SmallVec::<[SpanMode; 32]>::from_elem(mode, n))
            });
            // Search the spans around the extreme control points first: their candidates
            // make the box big early, so pruning skips more of the others.
            let first = [extreme_point(c, j, true), extreme_point(c, j, false)];
            let order = e.order_with_first(&first);
            modes.iter_mut().for_each(|m| *m = mode);
            let mut cb = e.coord(j, &order, modes);
            crate::num::pool::give(order);
            if self.fast_path {
                // A side the search left more than an ulp of the scale loose (it ran out of
                // boxes), or, above the degree where the certificate lowers bounds, more than
                // an ulp of the bound or without a witness within one (`bezier`'s refinement
                // test): the `bezier` search with its double-double refinement takes it over.
                let scale = c.coord_scale(j);
                let p = c.degree();
                let high = p > super::certify::LOWER_MAX_DEGREE;
                let test = |b: f64, a: f64, w: f64| {
                    super::certify::far_below(b, a, scale, 1)
                        || (high && super::bezier::needs_refinement(c, b, a, w, scale))
                };
                let need = [
                    test(cb.hi, cb.inner_hi, cb.witness_hi),
                    test(-cb.lo, -cb.inner_lo, -cb.witness_lo),
                ];
                if need.contains(&true) {
                    super::bezier::tighten(c, j, &mut cb, need);
                    let tight = !super::certify::far_below(cb.hi, cb.inner_hi, scale, 1)
                        && !super::certify::far_below(-cb.lo, -cb.inner_lo, scale, 1);
                    if tight {
                        cb.termination = super::Termination::Converged;
                    }
                }
            }
            coords.push(cb);
        }
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

/// Whether some non-empty span of `c` is narrower than 2^-1000 (knots a few subnormals apart,
/// or a span of ~1e-308 after the driver's knot scaling). The tight evaluation that the search
/// uses to settle stalled boxes and to bound candidates ([`crate::spline::tight::TightEval`]:
/// Taylor forms in u with radii of at least 2^-1000) cannot resolve such a span: its
/// derivatives with respect to u are ~1e300, so every enclosure over a box there is wide, and
/// the search halved rounding noise down to its box limit (2,000 boxes, ~70 ms for one
/// range-limits curve). Such curves go to the `bezier` search (its local refinement runs in
/// each span's local parameter), counted as `fast_fallbacks`; `newton-thesis` keeps its own
/// search.
fn has_tiny_span(c: &NurbsCurve) -> bool {
    const TINY: f64 = 9.332636185032189e-302; // 2^-1000
    let kn = c.knots();
    let (p, n) = (c.degree(), c.num_points() - 1);
    (p..=n).any(|k| kn[k] < kn[k + 1] && kn[k + 1] - kn[k] < TINY)
}

