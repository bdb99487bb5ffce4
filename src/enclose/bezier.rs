//! The `bezier` strategy: Bézier decomposition with subdivision (NURBS Book A5.6, then
//! branch and bound on the Bernstein coefficients).
//!
//! 1. Knot insertion turns every non-empty span into a Bézier segment, in verified
//!    midpoint-radius arithmetic (`HSpline<Mr>::bezier_segment`, NURBS Book A5.6), so the
//!    coefficients enclose the exact ones.
//! 2. Per segment and coordinate the Cartesian Bernstein coefficients b_i = (w P_j)_i / w_i
//!    bound the segment: min b_i <= C_j <= max b_i (convex hull property; for a rational segment
//!    valid because all w_i > 0, so C_j is a convex combination of the ratios b_i).
//! 3. If the largest coefficient is an end coefficient, the segment's maximum is that end value
//!    (b_0 = C(s0), b_p = C(s1)), which is evaluated tightly at the exact f64 end parameter.
//! 4. Otherwise the segment is subdivided: at an f64 estimate t* of the critical point (then the
//!    outer pieces have their maximum at the end next to t*, and the tiny middle piece
//!    [t* - d, t* + d] is bounded by a mean-value form), or by bisection when no estimate is
//!    found. Sub-segments are defined by *exact f64* global parameters [s0, s1], and their
//!    coefficients are recomputed from the span's segment by two de Casteljau splits with
//!    interval local parameters (so rounding does not accumulate over the depth and the end
//!    values are values of the curve at exact f64 parameters).
//!
//! 5. If the side's bound then exceeds its attained value by more than an ulp, the pieces that
//!    set it are searched again in their span's local parameter on the double-double Bézier
//!    segment (`refine_local`): pieces cut at f64 values of u cannot resolve a maximiser on a
//!    span only a few thousand doubles of u wide, nor can midpoint-radius points a few hundred
//!    ulps wide (extreme weights) resolve a sharp peak.
//!
//! Soundness: every segment that is not fully resolved contributes its coefficient bound (or a
//! tighter verified enclosure over its parameter range); segments are dropped only when their
//! coefficient bound is <= a value the curve provably attains.
//!
//! Two shortcuts in front of the interval work (speed; same guarantees):
//!
//! * A single polynomial Bézier segment of degree 2 or 3 (a plain quadratic / cubic Bézier
//!   curve) goes through [`single`]: f64 root estimates of C_j', proven derivative signs at a
//!   few test points (an f64 filter with an a-priori error bound, `Ddi` where it is unsure),
//!   root counting, and a `Ddi` Taylor enclosure over each tiny bracket. It hands the curve to
//!   the branch and bound below when it cannot prove a result within two ulps.
//! * Before a span's `Mr` segment is built and split, the hull of its double-double Bézier
//!   points ([`span_points`]; extracted in blocks by one sweep of Boehm insertion and shared
//!   with the tight evaluations, `TightEval::bezier_points`; for a rational curve the
//!   outward-rounded quotients of its homogeneous points) gives a cheap, sound upper bound
//!   and an attained value, which prune most spans of long splines without the search.
//!   A span that this hull leaves first in the best-first order goes to the root-isolating
//!   proofs: [`single`] (non-rational, degree 2 or 3) or the general fast path ([`Critical`],
//!   degree 2 to 64 otherwise), before any `Mr` segment is built.
//!
//! The minimum is computed as the maximum of -C_j (negation is exact).

use super::{
    BoxEncloser, CandidateKind, CoordBox, Enclosure, Extremum, Guarantee, Stats, Termination,
};
use crate::num::pool;
use crate::num::ddi::Ddi;
use smallvec::SmallVec;
use crate::num::iv;
use crate::num::mr::Mr;
use crate::num::Scalar;
use crate::spline::bezier::{bernstein_value as bern, cartesian, hodograph};
use crate::spline::bspline::BezierSeg;
use crate::spline::curve::NurbsCurve;
use crate::enclose::newton::bernstein::{SpanPoly, SpanProof};
use crate::spline::tight::TightEval;
use inari::Interval;

pub(crate) mod conic;
pub(crate) mod rational;
pub(crate) mod single;

/// Settings of the Bézier-subdivision strategy.
#[derive(Debug, Clone, Copy)]
pub struct BezierSubdivision {
    /// Stop refining a piece when its bound exceeds a provably attained value by at most
    /// `tol * coord_scale` (relative gap tolerance).
    pub tol: f64,
    /// Maximum subdivision depth per span.
    pub max_depth: u32,
    /// Maximum number of pieces examined per coordinate and side; the rest is bounded by
    /// coefficient bounds (sound) and reported as [`Termination::BoxLimit`].
    pub max_pieces: usize,
    /// Work budget per coordinate and side, in pieces times (p + 1)^2 (the cost of one
    /// piece's de Casteljau splits), plus per span 64 pieces but at most
    /// [`super::WORK_PER_SPAN`] units; pieces beyond it are bounded as a whole and reported as
    /// [`Termination::WorkLimit`]. Bounds the time of high-degree curves (about 1 s per
    /// coordinate at degree 1000).
    pub max_work: u64,
    /// Use the root-isolating fast path (module `single`; default true) for a single
    /// polynomial Bézier segment of degree 2 or 3, and on the spans of non-rational curves of
    /// degree 2 or 3. It falls back to the branch and bound by itself whenever it cannot prove
    /// a tight result; switching it off is for comparisons.
    pub fast_path: bool,
}

impl Default for BezierSubdivision {
    fn default() -> Self {
        BezierSubdivision {
            tol: f64::EPSILON,
            max_depth: 80,
            max_pieces: 20_000,
            max_work: super::DEFAULT_MAX_WORK,
            fast_path: true,
        }
    }
}

impl BezierSubdivision {
    /// The largest certified gap the `single` fast path may return for coordinate j: the
    /// tolerance, but at least two ulps of the scale (the resolution the reference tests use).
    fn max_gap(&self, c: &NurbsCurve, j: usize) -> f64 {
        let scale = c.coord_scale(j);
        (self.tol * scale).max(2.0 * crate::num::ulp(scale))
    }

    /// Default settings with a given relative tolerance.
    pub fn with_tol(tol: f64) -> Self {
        BezierSubdivision {
            tol: if tol.is_finite() && tol >= 0.0 {
                tol
            } else {
                f64::EPSILON
            },
            ..Default::default()
        }
    }
}

/// The fraction of a span split off at its end where the Taylor form about the end
/// ([`Values::end_bound`]) cannot localise a maximum sitting there: over a piece this short
/// C'' usually has a sign (as the Taylor forms of `coord_over` take boxes up to this width).
const END_PIECE: f64 = 1.0 / 256.0;

/// Tight evaluation of one coordinate at exact parameters and over small parameter boxes
/// ([`TightEval`]: rigorous double-double, ~1 ulp; its per-span data are built lazily).
struct Values<'a> {
    curve: &'a NurbsCurve,
    tight: TightEval<'a>,
}

impl<'a> Values<'a> {
    fn new(curve: &'a NurbsCurve) -> Self {
        Values {
            curve,
            tight: TightEval::sweeping(curve),
        }
    }
    /// Enclosure of sign * C_j(u) at the exact f64 u, and a strict witness below it: the
    /// largest double strictly below the double-double enclosure of sign * C_j(u) behind the
    /// interval (-inf where there is none), so that sign * C_j(u) > witness.
    fn at(&self, j: usize, u: f64, sign: f64) -> (Interval, f64) {
        let (v, d) = self.tight.coord_at_tight(j, u);
        let w = d.map_or(f64::NEG_INFINITY, |d| {
            if sign > 0.0 { d } else { -d }.strictly_below()
        });
        (iv::point(sign) * v, w)
    }
    /// Enclosure of C_j over [a, b].
    fn over(&self, j: usize, a: f64, b: f64) -> Interval {
        self.tight.coord_over(j, a, b)
    }

    /// A piece [s0, s1] of span k that ends at a span end (`at_hi`: at s1 = u_{k+1}, else at
    /// s0 = u_k), bounded by the Taylor form centred at that end ([`TightEval::end_form`]) if
    /// the bound (at most the piece's own bound `u`) is within `accept` of the side's attained
    /// value and localises the maximum (C'' has its sign, or the piece is at most
    /// [`END_PIECE`] of the span): then the bound and where the maximum can lie are recorded
    /// on `side` and `true` is returned; else `false` and the caller splits the piece. Either
    /// way C_j at the end is recorded as attained, with its strict witness (`jump1`: s1 is a
    /// jump, where C_j(s1) of span k is a left limit only and is not attained).
    ///
    /// Why: at a symmetric curve's extremum at a knot, sign * C_j' vanishes at the span end,
    /// so the piece's last two Bézier coefficients are equal in exact arithmetic and their
    /// `Mr` enclosures overlap: neither the end-value rule nor the critical-point split
    /// resolves it, and halving towards the end took ~26 levels per side (until the pieces
    /// were 2^-26 of the span) on rational curves, 130-170 subdivisions on one curve. The form
    /// about the end has |C'(e)| ~ 0, so its bound is C(e) to about an ulp.
    ///
    /// Where the maximum of g = sign * C_j over X = [s0, s1] lies: if g'' <= -κ < 0 on X
    /// (`second`), g' decreases strictly, so at e = s1 either g'(s1) >= 0 (the maximum is at
    /// s1) or the maximiser u* has g'(u*) = 0 (or u* = s0), and g'(s1) - g'(u*) <= -κ (s1 - u*)
    /// gives s1 - u* <= |g'(s1)| / κ <= G / κ (G = `slope` >= |C_j'(s1)|); the same at s0.
    /// So the candidate is [s1 - δ, s1] (or [s0, s0 + δ]) with δ >= G / κ rounded up, and the
    /// whole piece without a sign of g''.
    #[allow(clippy::too_many_arguments)]
    fn end_bound(
        &self,
        c: &NurbsCurve,
        j: usize,
        k: usize,
        sign: f64,
        (s0, s1): (f64, f64),
        at_hi: bool,
        jump1: bool,
        u: f64,
        side: &mut Side,
        accept: f64,
    ) -> bool {
        let kn = c.knots();
        let (a, b) = (kn[k], kn[k + 1]);
        let Some(f) = self.tight.end_form(j, k, s0, s1, at_hi) else {
            return false;
        };
        // C_j(e) is a value of the curve (unless e = s1 is a jump): attained, with its strict
        // witness, before the test (it may be what brings the bound within `accept`)
        if !(at_hi && jump1) {
            let v = if sign > 0.0 { f.value } else { -f.value };
            side.attain(v.to_interval());
            side.witness = side.witness.max(v.strictly_below());
        }
        let sg = iv::point(sign);
        // (`u`, the piece's own bound, holds too)
        let bound = (sg * f.range).sup().min(u);
        let within = bound - side.attained <= accept;
        if !within {
            return false;
        }
        let second = sg * f.second;
        let concave = second.sup() < 0.0;
        if !concave && s1 - s0 > (b - a) * END_PIECE {
            // not localised: the caller splits off the end's END_PIECE of the span
            return false;
        }
        let (lo, hi) = if concave {
            // δ = up(G / κ) >= G / κ (Lemma B of `num::ddi`, one division)
            let delta = crate::num::ddi::up(f.slope / -second.sup());
            if at_hi {
                // (s1 - δ rounded, then one double down: <= the exact difference)
                ((s1 - delta).next_down().max(s0), s1)
            } else {
                (s0, (s0 + delta).next_up().min(s1))
            }
        } else {
            (s0, s1)
        };
        let lo = if lo.is_nan() { s0 } else { lo };
        let hi = if hi.is_nan() { s1 } else { hi };
        let e = if at_hi { s1 } else { s0 };
        side.stats.point_evaluations += 1;
        side.bound(
            bound,
            Extremum {
                u_lo: lo,
                u_hi: hi,
                unique: false,
                kind: if lo == hi { end_kind(c, e) } else { CandidateKind::Critical },
            },
        );
        true
    }
    /// The Bézier segment of span k in double-double: the shared points of
    /// [`TightEval::bezier_points`] (extracted in blocks of spans by one sweep of Boehm
    /// insertion, NURBS Book A5.6; end values that are exactly doubles made exact).
    fn segment(&self, k: usize) -> BezierSeg<Ddi> {
        let c = self.curve;
        BezierSeg {
            a: c.knots()[k],
            b: c.knots()[k + 1],
            degree: c.degree(),
            dim: c.dim(),
            rational: c.is_rational(),
            pts: self.tight.bezier_points(k).to_vec(),
        }
    }
}

/// Whether the right end u_{k+1} of span k (`last`: the last non-empty span) is a value of
/// span k's piece: unless it is a jump, a knot of multiplicity p + 1 inside the domain, where
/// C(u_{k+1}) belongs to the next piece and span k's piece only approaches its end value.
pub(crate) fn right_end_attained(kn: &[f64], p: usize, k: usize, last: usize) -> bool {
    k == last || crate::spline::knots::multiplicity(kn, kn[k + 1]) <= p
}

/// An f64 estimate of a critical point of C_j in (s0, s1) on the coordinate segment `seg`:
/// Newton's method on the numerator N = A' w - A w' of C_j' (N = A' if non-rational), using
/// the midpoints of the interval coefficients (`Scalar::to_f64`). (A segment with a = 0,
/// b = 1 gives the estimate in the local parameter.) `None` if Newton leaves the piece. The estimate
/// is only a place to split; nothing about soundness depends on it.
fn critical<S: Scalar>(seg: &BezierSeg<S>, s0: f64, s1: f64, ends: bool) -> Option<f64> {
    let (a, b) = (seg.a, seg.b);
    let (av, wv): (Vec<f64>, Vec<f64>) = if seg.rational {
        seg.pts.chunks(2).map(|c| (c[0].to_f64(), c[1].to_f64())).unzip()
    } else {
        (
            seg.pts.iter().map(|x| x.to_f64()).collect(),
            vec![1.0; seg.pts.len()],
        )
    };
    if av.len() < 3 {
        return None; // linear: no interior critical point
    }
    let (a1, w1) = (hodograph(&av), hodograph(&wv));
    let (a2, w2) = (hodograph(&a1), hodograph(&w1));
    let (t0, t1) = ((s0 - a) / (b - a), (s1 - a) / (b - a));
    let newton = |mut t: f64| -> Option<f64> {
        for _ in 0..40 {
            let (n, dn) = if seg.rational {
                let (aa, ww, da, dw) = (bern(&av, t), bern(&wv, t), bern(&a1, t), bern(&w1, t));
                (da * ww - aa * dw, bern(&a2, t) * ww - aa * bern(&w2, t))
            } else {
                (bern(&a1, t), bern(&a2, t))
            };
            if !(dn.is_finite() && dn != 0.0 && n.is_finite()) {
                return None;
            }
            let nt = t - n / dn;
            if !(nt > t0 && nt < t1) {
                return None;
            }
            let done = (nt - t).abs() <= 4.0 * f64::EPSILON * t.abs().max(f64::MIN_POSITIVE);
            t = nt;
            if done {
                break;
            }
        }
        Some(t)
    };
    // From the middle, else (`ends`) from either end: a zero within an ulp of the middle's
    // size from an end (a local parameter ~1e-309 next to coefficients ~1e270) is out of reach
    // of steps t - n / dn taken at t ~ 0.5, whose result rounds to the end itself; from the
    // end the step is the zero's own size. (Without it [`local_search`] halved its pieces
    // towards such a zero: 512 pieces, a millisecond per side, in the certificate's local
    // stage. The search in u does not ask: there a split so close to a piece's end leaves a
    // piece as wide as before; one range-limits curve's search then left 20,403 pieces to
    // refine, in subnormal arithmetic, 0.7 ms -> 100 ms.)
    let t = newton(0.5 * (t0 + t1))
        .or_else(|| ends.then(|| newton(t0).or_else(|| newton(t1))).flatten())?;
    Some(a + t * (b - a))
}

/// Sign-adjusted Cartesian coefficient enclosures of `seg` (one coordinate, homogeneous rows)
/// restricted to the global parameter range [s0, s1] inside [seg.a, seg.b].
///
/// The corner cutting runs in midpoint-radius arithmetic ([`Mr`]: a few inlined flops per
/// step, where inari's `Interval` makes every operation an out-of-line call); the local
/// parameters are enclosed in `Interval` (one division each) and converted exactly
/// ([`Mr::from_bounds`] encloses the interval), and only the final coefficients are rounded
/// outward to `Interval` ([`Scalar::to_interval`]). Every step encloses its exact result, so
/// the coefficients enclose the exact ones over [s0, s1] (see [`BezierSeg::sub_points`]).
fn sub_coeffs(seg: &BezierSeg<Mr>, s0: f64, s1: f64, sign: f64) -> Vec<Interval> {
    let (a, b) = (seg.a, seg.b);
    let (pa, pb, p0, p1) = (iv::point(a), iv::point(b), iv::point(s0), iv::point(s1));
    let mr = |x: Interval| Mr::from_bounds(x.inf(), x.sup());
    // local t1 = (s1 - a) / (b - a); t0 relative to [a, s1]: (s0 - a) / (s1 - a), enclosed
    let t1 = (s1 < b).then(|| mr((p1 - pa) / (pb - pa)));
    let t0 = (s0 > a).then(|| mr((p0 - pa) / (p1 - pa)));
    let pts = seg.sub_points(t1.as_ref(), t0.as_ref());
    let s = iv::point(sign);
    // (the Cartesian coefficients x / w of the rows (w x, w) as in `cartesian`, written out:
    // no intermediate vector)
    if seg.rational {
        pts.chunks_exact(2)
            .map(|r| s * (r[0] / r[1]).to_interval())
            .collect()
    } else {
        pts.iter().map(|x| s * x.to_interval()).collect()
    }
}

/// An upper bound of sign * C_j over the piece [s0, s1] of the coordinate segment `seg` from
/// f64 restrictions of its rows with their a-priori error bound
/// ([`segment_values_f64`](super::newton::bernstein::segment_values_f64)), over the local box
/// [T0, T1] that contains (s0 - a) / (b - a) .. (s1 - a) / (b - a) (outward-rounded interval
/// quotients): a tenth of the cost of [`sub_coeffs`]. `None` where it does not apply.
fn piece_bound_f64(seg: &BezierSeg<Mr>, s0: f64, s1: f64, sign: f64) -> Option<f64> {
    let (pa, pb) = (iv::point(seg.a), iv::point(seg.b));
    let len = pb - pa;
    let t0 = ((iv::point(s0) - pa) / len).inf().max(0.0);
    let t1 = ((iv::point(s1) - pa) / len).sup().min(1.0);
    let v = super::newton::bernstein::segment_values_f64(seg, t0, t1)?;
    let b = (iv::point(sign) * v).sup();
    b.is_finite().then_some(b)
}

pub(crate) struct Side {
    /// largest lower end of enclosures of values the curve attains (sign-adjusted)
    pub(super) attained: f64,
    /// upper bound so far (sign-adjusted)
    pub(super) upper: f64,
    /// the curve provably reaches a value > witness (sign-adjusted; see
    /// [`CoordBox::witness_hi`])
    pub(super) witness: f64,
    pub(super) cands: SmallVec<[(f64, Extremum); 4]>,
    pub(super) stats: Stats,
    term: Termination,
}

impl Side {
    pub(crate) fn new() -> Side {
        Side {
            attained: f64::NEG_INFINITY,
            upper: f64::NEG_INFINITY,
            witness: f64::NEG_INFINITY,
            cands: Default::default(),
            stats: Stats::default(),
            term: Termination::Converged,
        }
    }
    /// Record a value the curve attains, or a lower bound of one (NaN is ignored).
    fn attain_f64(&mut self, v: f64) {
        if v > self.attained {
            self.attained = v;
        }
    }
    fn attain(&mut self, v: Interval) {
        // (an empty interval has inf = +inf and must never count as attained)
        if !v.is_empty() && v.inf() > self.attained {
            self.attained = v.inf();
        }
    }
    fn bound(&mut self, ub: f64, e: Extremum) {
        if ub > self.upper {
            self.upper = ub;
        }
        self.cands.push((ub, e));
    }
    /// Merge a span's proven side (a fast path's): its attained value, its strict witness (a
    /// value of the curve inside that span, so the certificate needs no evaluation of its own
    /// there), its candidates and counters.
    fn absorb(&mut self, s: Side) {
        self.attain_f64(s.attained);
        self.witness = self.witness.max(s.witness);
        for (ub, e) in s.cands {
            self.bound(ub, e);
        }
        self.stats.add(&s.stats);
    }
}

/// A work item of the branch and bound, ordered by its upper bound `pri`.
struct Item {
    pri: f64,
    /// span index in the curve; `piece` is None while the span is only known by its local
    /// control-point hull (not yet converted to a Bézier segment)
    span: usize,
    piece: Option<(f64, f64, u32, Vec<Interval>)>,
    /// whether `pri` of a span item (piece None) is already the hull filter's bound
    filtered: bool,
}

/// The per-curve data of the branch and bound, built when some coordinate side needs it.
struct Ctx<'a> {
    vals: Values<'a>,
    /// whether the `single` fast path runs on spans (non-rational curves of degree 2 or 3)
    single: bool,
    /// whether the general fast path ([`Critical`]) runs on spans (every other curve of
    /// degree >= 2 up to [`GENERAL_MAX_DEGREE`])
    general: bool,
    /// non-empty spans
    spans: Vec<usize>,
    /// the spans' `Mr` segments (from the double-double points of `vals`), built on first use
    segs: Vec<Option<BezierSeg<Mr>>>,
    /// per span, the general fast path's result for coordinate `.0` (`None` inside: it
    /// proved nothing), kept for the other side of that coordinate
    crit: Vec<Option<(usize, Option<Critical>)>>,
    /// per span, its Bézier points' hull for coordinate `.0` (the hull filter's data, kept for
    /// the other side of that coordinate)
    hulls: Vec<Option<(usize, SpanPoints)>>,
    /// the pair coefficients of the rational derivative numerator (built on first use)
    pair: Option<std::rc::Rc<[Mr]>>,
}

/// `len` times `None` in a vector from the thread's pool.
fn blank<T>(len: usize) -> Vec<Option<T>>
where
    Option<T>: pool::Pooled,
{
    let mut v = pool::take(len);
    v.resize_with(len, || None);
    v
}

impl Drop for Ctx<'_> {
    fn drop(&mut self) {
        pool::give(std::mem::take(&mut self.spans));
        pool::give(std::mem::take(&mut self.segs));
        pool::give(std::mem::take(&mut self.crit));
        pool::give(std::mem::take(&mut self.hulls));
    }
}

// (per-thread pools of the branch and bound's per-curve vectors and work items: a batch
// took six heap blocks per curve of the general path, some of several KB)
pool::pooled!(
    Option<BezierSeg<Mr>> => SEG_POOL,
    Option<(usize, Option<Critical>)> => CRIT_POOL,
    Option<(usize, SpanPoints)> => HULL_POOL,
    Item => ITEM_POOL
);

/// The degree up to which the general fast path runs (its derivative numerator, of degree at
/// most 2p - 2, is then evaluated by the O(n) scheme of `newton`'s Bernstein form).
const GENERAL_MAX_DEGREE: usize = 64;

impl<'a> Ctx<'a> {
    /// `fast`: whether to use the fast paths on spans.
    fn new(c: &'a NurbsCurve, fast: bool) -> Ctx<'a> {
        let (p, n) = (c.degree(), c.num_points() - 1);
        let kn = c.knots();
        let single = fast && !c.is_rational() && (2..=3).contains(&p);
        // (indexed by k - p, spans p ..= n: a high-degree curve has few spans and many
        // control points; the vectors come from and go back to the thread's pools, `Drop`)
        let mut spans = pool::take(n + 1 - p);
        spans.extend((p..=n).filter(|&k| kn[k] < kn[k + 1]));
        Ctx {
            vals: Values::new(c),
            single,
            general: fast && !single && (2..=GENERAL_MAX_DEGREE).contains(&p),
            spans,
            segs: blank(n + 1 - p),
            crit: blank(n + 1 - p),
            hulls: blank(n + 1 - p),
            pair: None,
        }
    }
}

/// The general fast path on one span k and coordinate j ("float first, prove after" at any
/// degree, with `newton`'s Bernstein form of the span, `SpanPoly`): the zeros of the
/// derivative numerator F (degree 2p - 2 rational, p - 1 polynomial; sign and zeros of C_j' on
/// the closed span) located by Bernstein subdivision with proven sign counts, so that every
/// zero lies in one of a few boxes of half-width 2^-40 of the span's local parameter and F
/// provably has none elsewhere (`SpanPoly::critical_boxes`: pieces with one proven sign,
/// or one proven sign change and F of opposite proven signs at the ends of the piece's box;
/// Descartes' rule of signs for the Bernstein basis). The extremes of C_j over the closed span
/// are then among its end values and its values over the boxes, each enclosed about one ulp
/// wide (a mean value form from the span's double-double points).
struct Critical {
    /// C_j at the span's left end and the limit at its right end (`TightEval::end_value`)
    ends: [Ddi; 2],
    boxes: SmallVec<[CriticalBox; 4]>,
}

/// A box of [`Critical`]: the local parameters [x0, x1] and the box in u, an enclosure of the piece's values
/// over it, and (where it was needed) the enclosure of a value the piece attains in it.
struct CriticalBox {
    x0: f64,
    x1: f64,
    /// the box in u, rounded outward (its candidate record)
    at: Extremum,
    enc: Interval,
    v: Option<Ddi>,
}

/// Half-width of the general fast path's boxes in the local parameter (as `single`'s): f64
/// estimates of simple zeros are far closer; the mean value enclosure over such a box is
/// about |C''| 2^-80 wide.
const GENERAL_H: f64 = 1.0 / 1_099_511_627_776.0; // 2^-40

impl Critical {
    /// The proof on span k for coordinate j, or `None` where some step is not proven: the
    /// lean form first ([`Critical::lean`]), the full one where that leaves it open.
    fn of(vals: &Values, pair: &[Mr], j: usize, k: usize) -> Option<Critical> {
        let c = vals.curve;
        let pts = vals.tight.bezier_points(k);
        // (the end values after the boxes: a span without a proof needs none)
        let ends = || [vals.tight.end_value(j, k, false), vals.tight.end_value(j, k, true)];
        let h = c.dim() + c.is_rational() as usize;
        let located = match SpanProof::new(c, j, k, pair, |i| (pts[i * h + j], pts[i * h + h - 1])) {
            Some(sp) => match Self::lean(&sp, c, k, ends, false) {
                Ok(found) => return Some(found),
                Err(located) => located,
            },
            None => true,
        };
        let sp = SpanPoly::new(c, j, k, pair, pts);
        Self::prove(sp, c, k, ends, |at| Some(vals.tight.coord_over(j, at.u_lo, at.u_hi)), located)
    }

    /// The proof from the lean form `sp` of span k of `c` (F and the tight enclosures alone,
    /// [`SpanProof`]: the same boxes and the same tight enclosures as [`Critical::prove`],
    /// which also makes the cheap enclosures of the boxes that cannot hold an extreme; here
    /// every box gets its tight one, a value the piece attains in it included), with the
    /// piece's enclosed end values `ends`. `Err(located)` where it leaves the proof to the
    /// full form: `located` false where F's boxes were not located (the full form then tries
    /// F from the double-double points at once, [`SpanPoly::refined`]), true where a box's
    /// enclosure is wider than an ulp and `wide` does not accept that (the full form's Taylor
    /// enclosure may be narrower).
    fn lean(
        sp: &SpanProof,
        c: &NurbsCurve,
        k: usize,
        ends: impl FnOnce() -> [Ddi; 2],
        wide: bool,
    ) -> Result<Critical, bool> {
        let num = sp.numerator();
        let found = match (!num.swamped()).then(|| num.critical_boxes(GENERAL_H)).flatten() {
            Some(found) => found,
            None => return Err(false),
        };
        let kn = c.knots();
        let mut boxes: SmallVec<[CriticalBox; 4]> = SmallVec::new();
        let mut open = None;
        for &(x0, x1) in &found {
            let Some((enc, v)) = sp.box_tight(x0, x1) else {
                open = Some(true);
                break;
            };
            if !wide && enc.sup() > enc.inf().next_up() {
                open = Some(true);
                break;
            }
            boxes.push(CriticalBox {
                x0,
                x1,
                at: single::extremum(kn[k], kn[k + 1], x0, x1, false, CandidateKind::Critical),
                enc,
                v: Some(v),
            });
        }
        // (the boxes' vector back to this thread's pool)
        crate::num::pool::give(found);
        match open {
            Some(located) => Err(located),
            None => Ok(Critical { ends: ends(), boxes }),
        }
    }

    /// The proof on the span of `sp` (span k of `c`) with the piece's enclosed end values
    /// (`ends`: C_j at u_k, the limit at u_{k+1}), and `taylor`, a second enclosure of the
    /// piece's values over a box in u (or `None`), for boxes whose mean value form is wider
    /// than an ulp. `located`: false where the lean form found F's boxes not located (the same
    /// F as this form's, so the same answer): then F from the double-double points at once.
    fn prove(
        mut sp: SpanPoly,
        c: &NurbsCurve,
        k: usize,
        ends: impl FnOnce() -> [Ddi; 2],
        taylor: impl Fn(&Extremum) -> Option<Interval>,
        located: bool,
    ) -> Option<Critical> {
        // (where F's `Mr` coefficients are too wide for the proof, it is tried once more with
        // F from the double-double points, `SpanPoly::refined`: cheaper by far than the
        // subdivision that runs otherwise)
        let first = located && !sp.f_swamped();
        let found = match first.then(|| sp.critical_boxes(GENERAL_H)).flatten() {
            Some(found) => found,
            None => {
                sp = sp.refined()?;
                if sp.f_swamped() {
                    return None;
                }
                sp.critical_boxes(GENERAL_H)?
            }
        };
        let [left, right] = ends();
        // Every box's values cheaply first (O(p)); the tight enclosure only for boxes that
        // may hold an extreme of the piece: a box whose cheap values lie strictly between values
        // the piece attains (the left end, the boxes' own cheap ends: every value over a box is
        // attained) holds neither its maximum nor its minimum, and its cheap enclosure bounds it.
        let kn = c.knots();
        let mut boxes: SmallVec<[CriticalBox; 4]> = found
            .iter()
            .map(|&(x0, x1)| CriticalBox {
                x0,
                x1,
                at: single::extremum(kn[k], kn[k + 1], x0, x1, false, CandidateKind::Critical),
                enc: sp.box_values(x0, x1),
                v: None,
            })
            .collect();
        crate::num::pool::give(found);
        let l = left.to_interval();
        let (att_hi, att_lo) = boxes.iter().fold((l.inf(), l.sup()), |(h, lo), b| {
            (h.max(b.enc.inf()), lo.min(b.enc.sup()))
        });
        for b in boxes.iter_mut() {
            if !(b.enc.sup() < att_hi && b.enc.inf() > att_lo) {
                let (mut enc, v) = sp.box_tight(b.x0, b.x1)?;
                if enc.sup() > enc.inf().next_up() {
                    // (the mean value form's r |F| / wmin^2 is wide where weights are tiny:
                    // then also the second-order Taylor form over the box in u, `TightEval`'s;
                    // both enclose the piece's values over the box; wider than one ulp of the
                    // value, as `newton` decides: a bound an ulp or two above the optimal
                    // double costs the certificate a lowering proof)
                    if let Some(t) = taylor(&b.at) {
                        let both = enc.intersection(t);
                        if !both.is_empty() {
                            enc = both;
                        }
                    }
                }
                b.enc = enc;
                b.v = Some(v);
            }
        }
        Some(Critical {
            ends: [left, right],
            boxes,
        })
    }

    /// The side (sign * C_j, sign = +-1) of span k = [u0, u1] from the proof: the end values
    /// (the right one attained only if `right_attained`, else a left limit that the curve
    /// approaches; it bounds the span either way) and the boxes' enclosures; `None` unless its
    /// certified gap is at most `max_gap`.
    fn side(
        &self,
        c: &NurbsCurve,
        k: usize,
        sign: f64,
        right_attained: bool,
        max_gap: f64,
    ) -> Option<Side> {
        let kn = c.knots();
        let (u0, u1) = (kn[k], kn[k + 1]);
        let neg = sign < 0.0;
        let mut side = Side::new();
        for (i, &e) in self.ends.iter().enumerate() {
            let v = if neg { -e } else { e };
            if i == 0 || right_attained {
                side.attain_f64(v.lower_end());
                side.witness = side.witness.max(v.strictly_below());
            } else {
                // The left limit L at a jump u1 is no value of the curve, but the piece is
                // continuous on the closed span and equals the curve on [u0, u1): its values
                // come arbitrarily close to L. So the curve exceeds every number w < L: the
                // largest double strictly below the enclosure of L (`Ddi::strictly_below`, -inf
                // when there is none) is a strict witness and a value reached (a value above it
                // is).
                let w = v.strictly_below();
                side.attain_f64(w);
                side.witness = side.witness.max(w);
            }
            let (t, u) = if i == 0 { (0.0, u0) } else { (1.0, u1) };
            let ub = v.to_interval().sup();
            side.bound(ub, single::extremum(u0, u1, t, t, false, end_kind(c, u)));
        }
        for b in &self.boxes {
            let enc = if neg { -b.enc } else { b.enc };
            if let Some(v) = b.v {
                let v = if neg { -v } else { v };
                side.attain_f64(v.lower_end());
                side.witness = side.witness.max(v.strictly_below());
            }
            side.bound(enc.sup(), b.at);
        }
        let gap = side.upper - side.attained;
        if gap.is_nan() || gap > max_gap {
            return None;
        }
        side.stats.fast_proofs += 1;
        side.stats.point_evaluations += (2 + self.boxes.len()) as u64;
        side.term = Termination::Converged;
        Some(side)
    }
}
/// One side (sign * C_j, sign = +-1) of span k of a curve `c` by the general fast path
/// ([`Critical`]) from the span's double-double Bézier coefficients of coordinate j alone
/// (enclosures of the exact ones; the driver's lane computes them per span without the
/// curve-wide sweep of [`TightEval`]): `q` the Cartesian coefficients, and for a rational
/// curve `hom` its homogeneous rows (w x_j, w) (then q_i encloses their quotient). The end
/// coefficients q_0 and q_p are the piece's values at the span's ends (C(u_k), and at u_{k+1}
/// the curve's value: the lane's splines are continuous), and the boxes' mean value forms from
/// the same points bound the rest. `None` where the proof fails or leaves a gap above
/// `max_gap` (without the Taylor form in u that the `bezier` strategy adds for wide boxes).
///
/// The proof itself ([`CoefficientProof`]) does not depend on the side: `proof` keeps it for
/// the other side of the same span and coordinate (`None` inside: it proved nothing).
#[allow(clippy::too_many_arguments)]
pub(crate) fn coefficient_side(
    c: &NurbsCurve,
    j: usize,
    k: usize,
    q: &[Ddi],
    hom: Option<(&[Ddi], &[Ddi])>,
    sign: f64,
    max_gap: f64,
    proof: &mut Option<CoefficientProof>,
) -> Option<Side> {
    let pr = proof.get_or_insert_with(|| {
        let p = q.len() - 1;
        let ends = || [q[0], q[p]];
        // (the pair coefficients of a rational span; none, and no allocation, otherwise)
        let pair = hom.map(|_| crate::enclose::newton::bernstein::pair_coefficients(c.degree()));
        let pair: &[Mr] = pair.as_deref().unwrap_or(&[]);
        let row = |i: usize| match hom {
            Some((x, w)) => (x[i], w[i]),
            None => (q[i], Ddi::exact(1.0)),
        };
        // (the lean form first; without a Taylor form here, a wide box is taken as it is)
        let located = match SpanProof::new(c, j, k, pair, row) {
            Some(sp) => match Critical::lean(&sp, c, k, ends, true) {
                Ok(found) => return CoefficientProof(Some(found)),
                Err(located) => located,
            },
            None => true,
        };
        let sp = match hom {
            Some((x, w)) => SpanPoly::from_homogeneous(c, j, k, pair, x, w),
            None => SpanPoly::from_coefficients(c, j, k, q),
        };
        CoefficientProof(Critical::prove(sp, c, k, ends, |_| None, located))
    });
    pr.0.as_ref()?.side(c, k, sign, true, max_gap)
}

/// The general fast path's proof on one span and coordinate ([`coefficient_side`]), or
/// `None` where it proved nothing.
pub(crate) struct CoefficientProof(Option<Critical>);

impl PartialEq for Item {
    fn eq(&self, o: &Self) -> bool {
        self.pri.total_cmp(&o.pri).is_eq()
    }
}
impl Eq for Item {}
impl PartialOrd for Item {
    fn partial_cmp(&self, o: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Item {
    fn cmp(&self, o: &Self) -> std::cmp::Ordering {
        self.pri.total_cmp(&o.pri)
    }
}

impl BezierSubdivision {
    /// Maximum of sign * C_j over the domain, by best-first branch and bound.
    ///
    /// Spans enter with the bound max_i sign * P_ij over their p + 1 local control points
    /// (exact f64; the curve on span k is a convex combination of P_{k-p} .. P_k, weights > 0),
    /// and are converted to Bézier segments (verified knot insertion) only when that bound
    /// exceeds the largest value found so far. Once the best remaining bound is <= a value
    /// the curve provably attains, everything left is pruned (soundly: see `Side`).
    fn maximize(&self, ctx: &mut Ctx, j: usize, sign: f64) -> Side {
        let Ctx {
            vals,
            single,
            general,
            spans,
            segs,
            crit,
            hulls,
            pair,
        } = ctx;
        let c = vals.curve;
        let p = c.degree();
        let scale = c.coord_scale(j);
        let gap_tol = self.tol * scale;
        let sg = iv::point(sign);
        let mut side = Side::new();
        // Spans enter with the bound of their local control values. A span where those are
        // all equal (the coordinate is that constant there: a convex combination, weights
        // > 0; interval Bézier coefficients of a rational span would be a few ulps wide, so
        // that subdivision could never resolve it) is done at once: its value is attained and
        // bounds it. (Taken from the heap instead, it came after the spans next to it whose
        // bound it often equals, and each of those was then searched up to the knot where it
        // meets the constant with a zero of C_j'.)
        let mut items: Vec<Item> = pool::take(spans.len());
        for &k in spans.iter() {
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for i in k - p..=k {
                let x = sign * c.control_point(i)[j];
                lo = lo.min(x);
                hi = hi.max(x);
            }
            if lo < hi {
                items.push(Item {
                    pri: hi,
                    span: k,
                    piece: None,
                    filtered: false,
                });
            } else if hi > side.attained {
                // (one candidate per value: a constant coordinate has many such spans)
                side.attain_f64(hi);
                side.bound(
                    hi,
                    Extremum {
                        u_lo: c.knots()[k],
                        u_hi: c.knots()[k + 1],
                        unique: false,
                        kind: CandidateKind::Critical,
                    },
                );
            }
        }
        let mut heap = std::collections::BinaryHeap::from(items);
        let ub = |c: &[Interval]| c.iter().fold(f64::NEG_INFINITY, |m, x| m.max(x.sup()));
        let mut pieces = 0usize;
        // (built on the first piece: most sides end before any subdivision)
        let mut csegs: Vec<Option<BezierSeg<Mr>>> = Vec::new();
        let cost = ((p + 1) as u64).pow(2);
        // a piece costs about four de Casteljau passes of (p + 1)^2 / 2 steps plus evaluations
        // (plus an allowance per span that also shrinks with the cost, as newton's: a fixed
        // 64 pieces took 17 s at degree 1000)
        let per_span = super::newton::EVALS_PER_SPAN.min(super::newton::WORK_PER_SPAN / cost);
        let work_pieces = (self.max_work / (4 * cost))
            .saturating_add(per_span.saturating_mul(spans.len() as u64))
            .min(usize::MAX as u64) as usize;
        while let Some(item) = heap.pop() {
            // Best-first: every remaining bound is <= item.pri <= a value the curve attains.
            if item.pri <= side.attained {
                break;
            }
            let k = item.span;
            if item.piece.is_none() {
                // Hull filter: a cheap upper bound of the span and a value it attains from its
                // double-double Bézier points (`span_points`; the quotients of the homogeneous
                // points for a rational curve), before any proof and before the `Mr` segment
                // and its pieces.
                if !item.filtered {
                    let last = k == spans[spans.len() - 1];
                    let hull = match hulls[k - p] {
                        Some((jj, h)) if jj == j => h,
                        _ => {
                            let pts = vals.tight.bezier_points(k);
                            let h = span_points(pts, p, j, c.is_rational());
                            hulls[k - p] = Some((j, h));
                            h
                        }
                    };
                    let (pri, at) = hull.side(sign, last);
                    side.attain_f64(at);
                    heap.push(Item {
                        pri: pri.min(item.pri),
                        span: k,
                        piece: None,
                        filtered: true,
                    });
                    continue;
                }
                // A span that peaks at an end on this side (`SpanPoints::end_peaked`, as
                // `newton`'s span filter): every inner Bézier point lies strictly below the
                // larger end point, so the piece's maximum over the closed span is an end value,
                // max(b_0, b_p) (convex hull property, positive weights). Its side is then the
                // fast path's proof with no critical box (`Critical::side` on the ends'
                // double-double enclosures, `TightEval::end_value`): each end bounds the span,
                // b_0 = C(u_k) is attained, b_p only where u_{k+1} is no jump; `None` beyond
                // the gap tolerance (a peak at an unattained left limit), and the search below
                // runs. No Bernstein form and no critical boxes.
                if let Some((jj, h)) = hulls[k - p] {
                    if jj == j && h.end_peaked(sign) {
                        let cr = Critical {
                            ends: [false, true].map(|right| vals.tight.end_value(j, k, right)),
                            boxes: SmallVec::new(),
                        };
                        let ra = right_end_attained(c.knots(), p, k, spans[spans.len() - 1]);
                        if let Some(s) = cr.side(c, k, sign, ra, self.max_gap(c, j)) {
                            side.absorb(s);
                            continue;
                        }
                    }
                }
                // The root-isolating fast path on the span's double-double Bézier segment
                // (non-rational, p = 2 or 3): a proven result for the whole span, or nothing.
                // (the points of `TightEval::bezier_points`, end values that are exactly
                // doubles made exact: `snap_exact_ends`)
                if *single {
                    let q = vals.tight.bezier_points(k);
                    let h = c.dim();
                    let mut v = [Ddi::exact(0.0); 4];
                    for (i, x) in v.iter_mut().enumerate().take(p + 1) {
                        *x = q[i * h + j];
                    }
                    let kn = c.knots();
                    let (u0, u1) = (kn[k], kn[k + 1]);
                    let seg = single::Segment {
                        c: &v[..=p],
                        a: u0,
                        b: u1,
                        end_kinds: [end_kind(c, u0), end_kind(c, u1)],
                        right_attained: right_end_attained(kn, p, k, spans[spans.len() - 1]),
                    };
                    let i = if sign > 0.0 { 0 } else { 1 };
                    let mut need = [false; 2];
                    need[i] = true;
                    if let Some(mut sd) = single::coord_sides(&seg, self.max_gap(c, j), need) {
                        side.absorb(std::mem::replace(&mut sd[i], Side::new()));
                        continue;
                    }
                }
                // The general fast path (any other degree up to GENERAL_MAX_DEGREE, rational or
                // not) once the span's Bézier hull comes first (it may hold the extreme; most
                // spans are pruned by that hull before): a proven result for the whole span, or
                // nothing (then the `Mr` segment and its subdivision follow). Its proof is
                // shared by both sides of the coordinate.
                if *general {
                    if !matches!(crit[k - p], Some((jj, _)) if jj == j) {
                        let pr = pair.get_or_insert_with(|| {
                            if c.is_rational() {
                                super::newton::bernstein::pair_coefficients(p)
                            } else {
                                std::rc::Rc::from([])
                            }
                        });
                        crit[k - p] = Some((j, Critical::of(vals, pr, j, k)));
                    }
                    if let Some((_, Some(cr))) = &crit[k - p] {
                        let last = spans[spans.len() - 1];
                        let ra = right_end_attained(c.knots(), p, k, last);
                        if let Some(s) = cr.side(c, k, sign, ra, self.max_gap(c, j)) {
                            side.absorb(s);
                            continue;
                        }
                    }
                }
            }
            // (coordinate j's rows of the span's segment, kept for the pieces that follow)
            if csegs.is_empty() {
                csegs.resize(segs.len(), None);
            }
            let seg = &*csegs[k - p].get_or_insert_with(|| {
                segs[k - p]
                    .get_or_insert_with(|| {
                        let seg = vals.segment(k);
                        BezierSeg {
                            pts: seg.pts.iter().map(|&x| Mr::from_ddi(x)).collect(),
                            a: seg.a,
                            b: seg.b,
                            degree: seg.degree,
                            dim: seg.dim,
                            rational: seg.rational,
                        }
                    })
                    .coord(j)
            });
            // The last coefficient at the span's right end is the left limit there: a value of
            // the curve unless that end is a jump
            let right_attained = right_end_attained(c.knots(), p, k, spans[spans.len() - 1]);
            // A piece pushed with its f64 bound only (`push` below) gets its `Mr` coefficients
            // when it comes first: it may still be pruned, which the cheap bound decided
            // without them for every piece left in the heap at the end.
            if let Some((s0, s1, depth, co)) = &item.piece {
                if co.is_empty() {
                    let co = sub_coeffs(seg, *s0, *s1, sign);
                    heap.push(Item {
                        pri: ub(&co).min(item.pri),
                        span: k,
                        piece: Some((*s0, *s1, *depth, co)),
                        filtered: true,
                    });
                    continue;
                }
            }
            let Some((s0, s1, depth, co)) = item.piece else {
                let co = sub_coeffs(seg, seg.a, seg.b, sign);
                side.attain(co[0]);
                if right_attained {
                    side.attain(co[co.len() - 1]);
                }
                heap.push(Item {
                    pri: ub(&co),
                    span: k,
                    piece: Some((seg.a, seg.b, 0, co)),
                    filtered: true,
                });
                continue;
            };
            let u = item.pri;
            pieces += 1;
            let (e0, e1) = (co[0], co[p]);
            side.attain(e0);
            let jump1 = s1 == seg.b && !right_attained;
            if !jump1 {
                side.attain(e1);
            }
            let inner = co[1..p]
                .iter()
                .fold(f64::NEG_INFINITY, |m, x| m.max(x.sup()));
            // (`jump`: s is the span's right end at a discontinuity, a knot of multiplicity
            // p + 1 inside the domain: C(s) belongs to the next piece and this piece only
            // approaches its end coefficient e, so e itself, the closure value, bounds the
            // piece and is not attained. It must not be intersected with C(s): an e that
            // overflowed to ENTIRE contains the next piece's value, and the intersection
            // would replace this piece's limit by it.)
            let seg_end = |s: f64, e: Interval, jump: bool, side: &mut Side| {
                if e.sup() > side.attained {
                    let v = if jump {
                        e
                    } else {
                        side.stats.point_evaluations += 1;
                        let (v, w) = vals.at(j, s, sign);
                        // (enclosures of the same value cannot be disjoint; if they were, e
                        // bounds the piece all the same)
                        let v = v.intersection(e);
                        if v.is_empty() {
                            e
                        } else {
                            // (C(s) is a value of the curve: its strict witness too)
                            side.attain(v);
                            side.witness = side.witness.max(w);
                            v
                        }
                    };
                    side.bound(
                        v.sup(),
                        Extremum {
                            u_lo: s,
                            u_hi: s,
                            unique: false,
                            kind: end_kind(c, s),
                        },
                    );
                }
            };
            if inner <= e0.inf().max(e1.inf()) {
                // max over the piece = max(C(s0), C(s1)): both are attained values.
                seg_end(s0, e0, false, &mut side);
                seg_end(s1, e1, jump1, &mut side);
                continue;
            }
            // Half-width of the middle piece around a critical point; pieces this narrow are
            // bounded by the mean-value form, which is then as tight as point evaluation.
            let d = (seg.b - seg.a) * 2f64.powi(-26);
            // (A gap of two ulps of the scale is accepted whatever `tol` says.)
            let close_enough =
                u - side.attained <= gap_tol.max(2.0 * f64::EPSILON * scale) || s1 - s0 <= 2.0 * d;
            // (a child piece first enters with the bound of its f64 coefficients, restricted
            // with an a-priori error bound: `piece_bound_f64`; its `Mr` coefficients, which the
            // processing below needs, are computed only if it is taken from the heap)
            let push = |a: f64, b: f64, heap: &mut std::collections::BinaryHeap<Item>| {
                let (pri, co) = match piece_bound_f64(seg, a, b, sign) {
                    Some(pri) => (pri, Vec::new()),
                    None => {
                        let co = sub_coeffs(seg, a, b, sign);
                        (ub(&co), co)
                    }
                };
                heap.push(Item {
                    pri,
                    span: k,
                    piece: Some((a, b, depth + 1, co)),
                    filtered: true,
                });
            };
            let accept = gap_tol.max(4.0 * f64::EPSILON * scale);
            // A piece whose maximum sits at a span end (the end value within `accept` of the
            // piece's bound) that is not yet proved optimal (no witness at the double below the
            // bound): bounded by the form about that end, which also localises the maximum
            // ([`Values::end_bound`]), else the end's 2^-8 of the span is split off, where
            // C'' usually has a sign and that form resolves it. Bounding the piece as a whole
            // would leave all of it to the refinement and the certificate, and halving towards
            // the end took ~26 levels.
            let top_hi = s1 == seg.b && e1.sup() >= u - accept;
            let top_lo = s0 == seg.a && e0.sup() >= u - accept;
            if (top_hi || top_lo) && u > side.attained && side.witness < u.next_down() {
                let at_hi = top_hi && (!top_lo || e1.sup() >= e0.sup());
                if vals.end_bound(c, j, k, sign, (s0, s1), at_hi, jump1, u, &mut side, accept) {
                    continue;
                }
                let w = (seg.b - seg.a) * END_PIECE;
                let m = if at_hi { s1 - w } else { s0 + w };
                if s1 - s0 > 2.0 * w && s0 < m && m < s1 {
                    side.stats.subdivisions += 1;
                    push(s0, m, &mut heap);
                    push(m, s1, &mut heap);
                    continue;
                }
            }
            if close_enough
                || depth >= self.max_depth
                || pieces >= self.max_pieces
                || pieces >= work_pieces
            {
                if !close_enough {
                    side.term = if depth >= self.max_depth {
                        Termination::DepthLimit
                    } else if pieces >= self.max_pieces {
                        Termination::BoxLimit
                    } else {
                        Termination::WorkLimit
                    };
                }
                self.finish(vals, j, sg, s0, s1, u, &mut side);
                seg_end(s0, e0, false, &mut side);
                seg_end(s1, e1, jump1, &mut side);
                continue;
            }
            side.stats.subdivisions += 1;
            side.stats.derivative_evaluations += 1;
            // (a critical point within d of an end of the piece makes the middle piece end
            // there: halving towards it, as without an estimate, took ~26 levels for a zero
            // 1e-9 from a knot; the piece is wider than 2 d here, so one side is left)
            let crit = critical(seg, s0, s1, false).filter(|&t| t > s0 && t < s1);
            if let Some(t) = crit {
                let (m0, m1) = ((t - d).max(s0), (t + d).min(s1));
                let (v, w) = vals.at(j, t, sign);
                side.stats.point_evaluations += 1;
                side.attain(v);
                side.witness = side.witness.max(w);
                if m0 > s0 {
                    push(s0, m0, &mut heap);
                }
                if m1 < s1 {
                    push(m1, s1, &mut heap);
                }
                // Accept the middle piece when its bound is as good as the point evaluation at
                // t* itself (further splitting cannot beat the evaluation accuracy). The tight
                // enclosure over it (a Taylor form, about an ulp wide around t*) usually is;
                // the `Mr` coefficients of the piece (a de Casteljau restriction in `Mr`, the
                // costlier of the two) are computed only when it is not.
                let over = (sg * vals.over(j, m0, m1)).sup();
                let (bm, mid) = if over - v.sup() <= accept {
                    (over, Vec::new())
                } else {
                    let mid = sub_coeffs(seg, m0, m1, sign);
                    (over.min(ub(&mid)), mid)
                };
                if bm - v.sup() <= accept {
                    side.bound(
                        bm,
                        Extremum {
                            u_lo: m0,
                            u_hi: m1,
                            unique: false,
                            kind: CandidateKind::Critical,
                        },
                    );
                } else {
                    heap.push(Item {
                        pri: ub(&mid),
                        span: k,
                        piece: Some((m0, m1, depth + 1, mid)),
                        filtered: true,
                    });
                }
            } else {
                let m = 0.5 * (s0 + s1);
                // No critical point estimate and a numerically flat piece (the coefficients
                // differ by no more than their enclosure widths, e.g. a constant rational
                // coordinate): splitting cannot shrink rounding-dominated widths, so bound the
                // piece as it is.
                let wmax = co.iter().fold(0.0f64, |m, x| m.max(x.wid()));
                let (mlo, mhi) = crate::num::min_max(co.iter().map(|x| x.mid()));
                // (likewise a piece at a span end whose bound is within a few coefficient
                // widths of the attained value: an extremum at the knot where C_j' vanishes,
                // whose next-to-end coefficient equals the end coefficient up to the `Mr`
                // rounding, so that halving cannot separate them; the refinement in double
                // double, `refine_local`, takes over if that leaves the side loose)
                let at_end = s0 == seg.a || s1 == seg.b;
                if m <= s0
                    || m >= s1
                    || mhi - mlo <= 2.0 * wmax
                    || (at_end && u - side.attained <= 8.0 * wmax)
                {
                    self.finish(vals, j, sg, s0, s1, u, &mut side);
                    continue;
                }
                push(s0, m, &mut heap);
                push(m, s1, &mut heap);
            }
        }
        pool::give(heap.into_vec());
        // Every piece was either bounded (<= upper) or pruned (<= attained <= max C), so
        // max C <= max(upper, attained).
        side.upper = side.upper.max(side.attained);
        if needs_refinement(c, side.upper, side.attained, side.witness, scale) {
            let mut dseg = |k: usize| vals.segment(k).coord(j);
            refine_local(c, spans, sign, &mut dseg, &mut side);
        }
        side
    }

    /// Bound an unresolved piece [s0, s1] by the smaller of its coefficient bound `u` and a
    /// verified mean-value enclosure.
    #[allow(clippy::too_many_arguments)]
    fn finish(
        &self,
        vals: &Values,
        j: usize,
        sg: Interval,
        s0: f64,
        s1: f64,
        u: f64,
        side: &mut Side,
    ) {
        side.stats.point_evaluations += 1;
        let b = (sg * vals.over(j, s0, s1)).sup().min(u);
        side.bound(
            b,
            Extremum {
                u_lo: s0,
                u_hi: s1,
                unique: false,
                kind: CandidateKind::Unresolved,
            },
        );
    }
}

/// Whether the gap between a side's bound and its attained value is more than one ulp of
/// max(|bound|, `scale`) (`certify::far_below` with a window of 1): a bound that is not yet
/// the optimal double, or one that pieces the subdivision in u cannot resolve left loose.
/// [`refine_local`] then takes those pieces over, so that the certificate finds the bound
/// proved (a strict double-double witness) instead of searching and lowering it.
fn loose(bound: f64, attained: f64, scale: f64) -> bool {
    super::certify::far_below(bound, attained, scale, 1)
}

/// Whether a bound within an ulp of the scale above its attained value is still not shown to
/// be the optimal double by the certificate's first rule (the attained value equal to it, or a
/// strict witness at or above the double below it): an extremum whose enclosure spans two
/// doubles of its own size, below the resolution of [`loose`]. [`refine_local`] then
/// searches the pieces again in double double, which usually leaves such a witness; otherwise
/// the certificate has to lower the bound itself, a proof in exact arithmetic that cost up to
/// a millisecond on extreme weights.
fn unproved_within_an_ulp(bound: f64, attained: f64, witness: f64) -> bool {
    // (only a gap of a few doubles of the bound's own size: an extremum tiny next to the
    // coordinate's scale, e.g. ~1 among values ~1e308, is many doubles from its attained value
    // and beyond what double double resolves)
    bound.is_finite()
        && bound > attained
        && witness < bound.next_down()
        && bound - attained <= 4.0 * crate::num::ulp(bound)
}

/// Whether a bound more than an ulp of its own size above the attained value is beyond what
/// the certificate corrects: it lowers bounds only up to degree
/// [`super::certify::LOWER_MAX_DEGREE`], so above, a bound that is within the stopping gap of
/// the scale but many doubles of a small extremum (a maximum ~4e-3 on a coordinate of scale 1)
/// would stay that far from the optimal double. Only where double double resolves the
/// extremum's doubles (their spacing at least 2^-80 of the scale).
fn beyond_lowering(c: &NurbsCurve, bound: f64, attained: f64, scale: f64) -> bool {
    let u = crate::num::ulp(bound);
    c.degree() > super::certify::LOWER_MAX_DEGREE
        && bound.is_finite()
        && bound - attained > u
        && u >= scale * (1.0 / 1_208_925_819_614_629_174_706_176.0)
}

/// Whether a side goes to the local refinement ([`refine_local`]): [`loose`] against the
/// scale, [`unproved_within_an_ulp`], or [`beyond_lowering`]. Also `newton`'s test for handing
/// a side to the `bezier` search ([`tighten`]).
pub(crate) fn needs_refinement(
    c: &NurbsCurve,
    bound: f64,
    attained: f64,
    witness: f64,
    scale: f64,
) -> bool {
    loose(bound, attained, scale)
        || unproved_within_an_ulp(bound, attained, witness)
        || beyond_lowering(c, bound, attained, scale)
}

/// Pieces per side of the local refinement ([`refine_local`]).
const REFINE_PIECES: usize = 256;

/// Whether a piece of [`local_search`] with the sign-adjusted points `co` and a `gap` between
/// its bound and the attained value is bounded by rounding alone: the point that sets the
/// bound (the largest upper end) is at least half the gap wide, and that width is not small
/// against the point itself (2^-10 of its magnitude: a value that cancelled, e.g. ~0 from terms
/// ~1, whose enclosure no split narrows; points 2^-60 wide, e.g. from clustered knots, still
/// narrow as the pieces shrink). Wide enclosures of other points (~2^-53 of 1e270
/// next to an extremum ~1e-38) do not count: they narrow, or drop out of the bound, as the
/// pieces shrink towards the extremum.
fn rounding_bound(co: &[Ddi], gap: f64) -> bool {
    let top = co
        .iter()
        .map(|x| x.to_interval())
        .max_by(|a, b| a.sup().total_cmp(&b.sup()));
    top.is_some_and(|i| 2.0 * i.wid() >= gap && i.wid() >= i.mag() * (1.0 / 1024.0))
}

/// A piece of the local search: span k over its local parameter range [t0, t1], its
/// sign-adjusted Cartesian Bézier points (double-double) and their largest upper end `pri`.
#[derive(Default)]
struct LocalPiece {
    pri: f64,
    k: usize,
    t0: f64,
    t1: f64,
    co: Vec<Ddi>,
}

/// The key of `f64::total_cmp` as an integer (for the refinement's heap of piece indices).
fn total_key(x: f64) -> i64 {
    let b = x.to_bits() as i64;
    b ^ ((((b >> 63) as u64) >> 1) as i64)
}

/// The outcome of [`local_search`]: every piece left with a bound above the attained value
/// (`bounds`: bound, span, local range, kind), the largest lower end of a value attained
/// (`attained`, sign-adjusted) and the largest strict witness (`witness`: the curve exceeds it).
pub(crate) struct LocalResult {
    pub bounds: Vec<(f64, usize, f64, f64, CandidateKind)>,
    pub attained: f64,
    pub witness: f64,
    pub stats: Stats,
}

impl LocalResult {
    /// The bound of everything searched: max(largest piece bound, attained value).
    pub fn upper(&self) -> f64 {
        self.bounds
            .iter()
            .fold(self.attained, |m, x| m.max(x.0))
    }
}

/// Best-first search for max sign * C_j over pieces of spans in their local parameter t in
/// [0, 1], on the spans' Bézier segments in double-double (`segs`: span k, coordinate j's
/// homogeneous rows of [`HSpline::bezier_segment`] with a = 0, b = 1; NURBS Book A5.6, thesis
/// sec. 4.2), starting from the pieces `start` (span, t0, t1), with splits at f64
/// critical-point estimates ([`critical`]) at exact f64 local parameters. `right_attained(k)`:
/// whether span k's value at t = 1 is a curve value (not the left limit at a jump). Used by
/// `bezier`'s local refinement ([`refine_local`]) and by the certificate's search of curves
/// with extreme magnitudes (`certify`), at most `max_pieces` pieces.
///
/// Soundness: every piece is bounded by the hull of its Cartesian Bézier points (convex hull
/// property, weights > 0; the de Casteljau splits at exact f64 t1 and at an enclosure of
/// t0 / t1 enclose the exact sub-segment, [`BezierSeg::sub_points`]) or, when no inner point
/// exceeds its end points, by its end values; a piece is dropped only when its bound is <= a
/// value attained. Values count as attained at t0 (a value of the span's piece at an exact
/// parameter, or the first point of the span) and at t1 < 1 or at a span end that is no jump,
/// and at the split points (de Casteljau evaluation, [`BezierSeg::eval_local`]). So the
/// maximum over the start pieces is <= [`LocalResult::upper`].
///
/// Splits: at the critical-point estimate ([`critical`], inside the piece), else at the middle.
/// A piece is bounded as it is when it is optimal already, resolved to rounding (its points
/// within two doubles, or its bound set by rounding alone: [`rounding_bound`]), or out of
/// pieces.
pub(crate) fn local_search(
    p: usize,
    sign: f64,
    segs: &[(usize, BezierSeg<Ddi>)],
    start: &[(usize, f64, f64)],
    right_attained: &dyn Fn(usize) -> bool,
    (attained, witness): (f64, f64),
    max_pieces: usize,
) -> LocalResult {
    let signed = |x: Ddi| if sign < 0.0 { -x } else { x };
    let mut out = LocalResult {
        bounds: Vec::new(),
        attained,
        witness,
        stats: Stats::default(),
    };
    let seg_of = |k: usize| &segs.iter().find(|s| s.0 == k).unwrap().1;
    // (the pieces, and a max-heap of (key of pri, index))
    let mut store: Vec<LocalPiece> = Vec::new();
    let mut heap = std::collections::BinaryHeap::new();
    type Heap = std::collections::BinaryHeap<(i64, usize)>;
    let ub = |co: &[Ddi]| co.iter().fold(f64::NEG_INFINITY, |m, x| m.max(x.to_interval().sup()));
    // a piece of span k's segment over [t0, t1]: its sign-adjusted Cartesian points, pushed
    let push = |heap: &mut Heap, store: &mut Vec<LocalPiece>, k: usize, t0: f64, t1: f64| {
        let seg = seg_of(k);
        let t1s = (t1 < 1.0).then(|| Ddi::exact(t1));
        let t0s = (t0 > 0.0).then(|| Ddi::exact(t0) / Ddi::exact(t1));
        let co: Vec<Ddi> = cartesian(seg.sub_points(t1s.as_ref(), t0s.as_ref()), 1, seg.rational)
            .into_iter()
            .map(signed)
            .collect();
        heap.push((total_key(ub(&co)), store.len()));
        store.push(LocalPiece {
            pri: ub(&co),
            k,
            t0,
            t1,
            co,
        });
    };
    for &(k, t0, t1) in start {
        if t0 < t1 {
            push(&mut heap, &mut store, k, t0, t1);
        }
    }
    let attain = |out: &mut LocalResult, v: Ddi| {
        let iv = v.to_interval();
        // (an empty interval has inf = +inf and must never count as attained)
        if !iv.is_empty() {
            if iv.inf() > out.attained {
                out.attained = iv.inf();
            }
            out.witness = out.witness.max(v.strictly_below());
        }
    };
    let mut pieces = 0usize;
    while let Some((_, i)) = heap.pop() {
        if store[i].pri <= out.attained {
            break;
        }
        let LocalPiece { pri, k, t0, t1, co } = std::mem::take(&mut store[i]);
        let seg = seg_of(k);
        pieces += 1;
        let (e0, e1) = (co[0], co[p]);
        attain(&mut out, e0);
        if t1 < 1.0 || right_attained(k) {
            attain(&mut out, e1);
        }
        let (i0, i1) = (e0.to_interval(), e1.to_interval());
        let inner = co[1..p]
            .iter()
            .fold(f64::NEG_INFINITY, |m, x| m.max(x.to_interval().sup()));
        if inner <= i0.inf().max(i1.inf()) {
            // the piece's maximum is an end value
            out.bounds
                .push((i0.sup().max(i1.sup()), k, t0, t1, CandidateKind::Critical));
            continue;
        }
        let m = critical(seg, t0, t1, true).unwrap_or(0.5 * t0 + 0.5 * t1);
        let lowest = co.iter().fold(f64::INFINITY, |m, x| m.min(x.to_interval().inf()));
        if pri <= out.attained.next_up()
            || pri <= lowest.next_up().next_up()
            || rounding_bound(&co, pri - out.attained)
            || pieces >= max_pieces
            || !(t0 < m && m < t1)
        {
            // optimal already (no double between the attained value and the bound), resolved
            // to rounding (all points within two doubles: a near-tie with a double, which only
            // the certificate's exact stages decide), out of pieces, or no f64 parameter inside
            out.bounds.push((pri, k, t0, t1, CandidateKind::Unresolved));
            continue;
        }
        let v = cartesian(seg.eval_local(&Ddi::exact(m)), 1, seg.rational)[0];
        attain(&mut out, signed(v));
        out.stats.point_evaluations += 1;
        out.stats.subdivisions += 1;
        for (a, b) in [(t0, m), (m, t1)] {
            push(&mut heap, &mut store, k, a, b);
        }
    }
    // pieces left in the heap are bounded by their points (or pruned: <= attained)
    for (_, i) in heap {
        let x = &store[i];
        if x.pri > out.attained {
            out.bounds
                .push((x.pri, x.k, x.t0, x.t1, CandidateKind::Unresolved));
        }
    }
    out
}

/// The local refinement of a loose side ([`loose`]): the pieces of the branch and bound whose
/// bounds exceed the attained value are searched again in the local parameter t in [0, 1] of
/// their span ([`local_search`], on the span's Bézier segment in double-double, `dseg(k)`:
/// coordinate j's rows of [`HSpline::bezier_segment`]).
///
/// Why: pieces of the search in u are cut at f64 values of u. On a span a few thousand
/// doubles of u wide (clustered knots) the maximiser lies between two of them, and no piece
/// can resolve it; where extreme weights make the [`Mr`] points of a piece a few hundred ulps
/// wide, the pieces stay "numerically flat" and are bounded as a whole. In t, f64 parameters
/// are dense over the span, and double-double points are ~2^-100 relative narrow.
///
/// Soundness: the refined pieces cover the old ones (`u_to_local` rounds outward; on [t0, t1]
/// the segment is the curve on the span's closed parameter range, its right end the left limit
/// at a jump), and [`local_search`] bounds them. The old bounds of the refined pieces are
/// replaced only if the side's bound goes down.
fn refine_local(
    c: &NurbsCurve,
    spans: &[usize],
    sign: f64,
    dseg: &mut impl FnMut(usize) -> BezierSeg<Ddi>,
    side: &mut Side,
) {
    let kn = c.knots();
    let p = c.degree();
    if p < 2 {
        return;
    }
    let last = spans[spans.len() - 1];
    let right_attained = |k: usize| right_end_attained(kn, p, k, last);
    let mut segs: Vec<(usize, BezierSeg<Ddi>)> = Vec::new();
    let mut kept: SmallVec<[(f64, Extremum); 4]> = SmallVec::new();
    let mut start: Vec<(usize, f64, f64)> = Vec::new();
    for &(b, e) in &side.cands {
        let k = spans
            .iter()
            .copied()
            .find(|&k| kn[k] <= e.u_lo && e.u_hi <= kn[k + 1]);
        let (true, Some(k)) = (b > side.attained && e.u_lo < e.u_hi, k) else {
            kept.push((b, e));
            continue;
        };
        let (t0, t1) = crate::enclose::newton::u_to_local(kn[k], kn[k + 1], e.u_lo, e.u_hi);
        if t0 >= t1 {
            kept.push((b, e));
            continue;
        }
        if !segs.iter().any(|x| x.0 == k) {
            let mut s = dseg(k);
            // (the local parameter itself: `critical` then estimates t)
            (s.a, s.b) = (0.0, 1.0);
            segs.push((k, s));
        }
        start.push((k, t0, t1));
    }
    let r = local_search(
        p,
        sign,
        &segs,
        &start,
        &right_attained,
        (side.attained, side.witness),
        REFINE_PIECES,
    );
    let mut out = Side::new();
    out.attained = r.attained;
    out.witness = r.witness;
    for &(b, k, t0, t1, kind) in &r.bounds {
        let (u_lo, u_hi) = crate::enclose::newton::local_to_u(kn[k], kn[k + 1], t0, t1);
        out.bound(
            b,
            Extremum {
                u_lo,
                u_hi,
                unique: false,
                kind,
            },
        );
    }
    for (b, e) in kept {
        out.bound(b, e);
    }
    out.upper = out.upper.max(out.attained);
    if out.upper < side.upper {
        side.upper = out.upper;
        side.cands = out.cands;
    }
    side.attained = side.attained.max(out.attained);
    side.witness = side.witness.max(out.witness);
    side.stats.add(&r.stats);
}

/// Coordinate j of the Bézier point i of a span from its points `pts` (`d` rows each,
/// homogeneous (w x, w) for a `rational` curve), enclosed in f64: the point's enclosure, or
/// for a rational curve the outward-rounded quotient of the enclosures of w x_j and w
/// ([`iv::div_positive`]: the whole line unless the weight's enclosure is positive).
fn cartesian_point(pts: &[Ddi], d: usize, i: usize, j: usize, rational: bool) -> Interval {
    let (lo, hi) = cartesian_ends(pts, d, i, j, rational);
    iv::span(lo, hi)
}

/// The ends of [`cartesian_point`] as two f64, (-inf, inf) for the whole line: the same ends
/// as its interval (a `Ddi`'s enclosure is [`Ddi::lower_end`], [`Ddi::upper_end`], the whole
/// line where those do not make an interval; a quotient by a positive weight the quotients of
/// ends stepped one ulp outward, as [`iv::div_positive`]), without building the intervals
/// (the span filter converts every Bézier point of every span it meets).
#[inline]
fn cartesian_ends(pts: &[Ddi], d: usize, i: usize, j: usize, rational: bool) -> (f64, f64) {
    const WHOLE: (f64, f64) = (f64::NEG_INFINITY, f64::INFINITY);
    // (inari's rule for an interval [a, b]: a <= b, a < inf, b > -inf; NaN fails it)
    let ends = |x: &Ddi| {
        let (a, b) = (x.lower_end(), x.upper_end());
        if a <= b && a < f64::INFINITY && b > f64::NEG_INFINITY {
            (a, b)
        } else {
            WHOLE
        }
    };
    // (zero ends signed as an interval's: inf -0, sup +0; `-((-x) + 0)` and `x + 0` change
    // nothing else)
    let signed = |(a, b): (f64, f64)| (-((-a) + 0.0), b + 0.0);
    let (xl, xu) = ends(&pts[i * d + j]);
    if !rational {
        return signed((xl, xu));
    }
    match iv::div_positive_ends((xl, xu), ends(&pts[i * d + d - 1])) {
        Some((lo, hi)) if lo <= hi && lo < f64::INFINITY && hi > f64::NEG_INFINITY => {
            signed((lo, hi))
        }
        _ => WHOLE,
    }
}

/// Coordinate j of a span's Bézier points, enclosed ([`span_points`]): from its points `pts`
/// (`TightEval::bezier_points`: `Ddi` enclosures of the exact points, `pts.len() / (p + 1)`
/// rows each, homogeneous (w x, w) for a rational curve). The span's values lie in the hull
/// of its exact Bézier points (convex hull property, NURBS Book P5.x; for a rational span
/// with the Cartesian points x_i = (w x)_i / w_i, thesis prop. 2.1, the weights of knot
/// insertion being convex combinations of positive weights, so positive), so the extreme ends
/// of the enclosures, rounded outward, bound them (an overflowed enclosure, or a weight not
/// proven positive, is the whole line, which bounds nothing).
#[derive(Debug, Clone, Copy)]
pub(crate) struct SpanPoints {
    /// the hull of the enclosures (the whole line if one is empty or unbounded)
    pub lo: f64,
    pub hi: f64,
    /// whether the exact points are non-decreasing / non-increasing
    pub inc: bool,
    pub dec: bool,
    /// the enclosures of the first and the last point: C(u_k), and the left limit at u_{k+1}
    pub first: Interval,
    pub last: Interval,
    /// the hull of the enclosures of the inner points b_1 .. b_{p-1} (empty: (inf, -inf))
    pub inner_lo: f64,
    pub inner_hi: f64,
}

impl SpanPoints {
    /// The hull filter's `(upper bound, attained value)` of sign * C_j on the span: the hull's
    /// end on that side, and C(u_k) = b_0, which is attained (right-continuous; b_p =
    /// C(u_{k+1}) only on the last span `last_span`, elsewhere it may be a left limit at a
    /// jump), so the lower end of its enclosure is a value the curve reaches.
    pub(crate) fn side(&self, sign: f64, last_span: bool) -> (f64, f64) {
        let end = |x: Interval| if sign > 0.0 { x.inf() } else { -x.sup() };
        let at = if last_span {
            end(self.first).max(end(self.last))
        } else {
            end(self.first)
        };
        (if sign > 0.0 { self.hi } else { -self.lo }, at)
    }

    /// Whether every inner Bézier point b_1 .. b_{p-1} lies strictly below the larger end
    /// point (`sign` 1), or strictly above the smaller one (-1), proven by the enclosures
    /// (always for p = 1). Then the piece's extreme on that side over the closed span is an
    /// end value, max(b_0, b_p) (convex hull property), and each end that reaches it lies
    /// strictly beyond its neighbour point (b_1 or b_{p-1}), so the piece's derivative there
    /// is not zero: at C(u_k) = b_0 it points into the span away from the extreme, at b_p
    /// out of it towards larger values (`newton`'s span filter, `Engine::coord`).
    pub(crate) fn end_peaked(&self, sign: f64) -> bool {
        let (f, l) = (self.first, self.last);
        // (an empty or unbounded enclosure has an infinite end and fails)
        if sign > 0.0 {
            self.inner_hi < f.inf().max(l.inf())
        } else {
            self.inner_lo > f.sup().min(l.sup())
        }
    }
}

/// Coordinate j of a span's Bézier points ([`SpanPoints`]): the hull of their enclosures, the
/// enclosures of the end points, and whether the exact points are non-decreasing /
/// non-increasing for every choice of them in their enclosures (each upper end at most the
/// next lower end); the span's piece is then monotone too (a Bézier curve with positive
/// weights and monotone points is, the argument of `newton`'s monotone pretest). An empty or
/// unbounded enclosure gives the whole line and neither.
pub(crate) fn span_points(pts: &[Ddi], p: usize, j: usize, rational: bool) -> SpanPoints {
    let d = pts.len() / (p + 1);
    let mut out = SpanPoints {
        lo: f64::INFINITY,
        hi: f64::NEG_INFINITY,
        inc: true,
        dec: true,
        first: cartesian_point(pts, d, 0, j, rational),
        last: cartesian_point(pts, d, p, j, rational),
        inner_lo: f64::INFINITY,
        inner_hi: f64::NEG_INFINITY,
    };
    // (the ends as f64 pairs, [`cartesian_ends`]: never NaN, (-inf, inf) for the whole line)
    let mut prev = (f64::NEG_INFINITY, f64::INFINITY);
    for i in 0..=p {
        let (vl, vu) = match i {
            0 => (out.first.inf(), out.first.sup()),
            _ if i == p => (out.last.inf(), out.last.sup()),
            _ => cartesian_ends(pts, d, i, j, rational),
        };
        if vl == f64::NEG_INFINITY && vu == f64::INFINITY {
            (out.lo, out.hi, out.inc, out.dec) = (f64::NEG_INFINITY, f64::INFINITY, false, false);
            (out.inner_lo, out.inner_hi) = (f64::NEG_INFINITY, f64::INFINITY);
            return out;
        }
        if i > 0 && i < p {
            out.inner_lo = out.inner_lo.min(vl);
            out.inner_hi = out.inner_hi.max(vu);
        }
        out.lo = out.lo.min(vl);
        out.hi = out.hi.max(vu);
        if i > 0 {
            out.inc &= vl >= prev.1;
            out.dec &= vu <= prev.0;
        }
        prev = (vl, vu);
    }
    out
}

/// `(upper bound, attained value)` of a span from f64 Bézier coefficients `v` (sign-adjusted)
/// that are within E = 2p 8ε M + MIN_POSITIVE of the exact ones (`m` = M, the largest
/// magnitude of the span's p + 1 control values; the caller's a-priori bound must be below E:
/// the closed-form coefficients of the lane's splines, `lane::span_coefficients`, err by at
/// most 35 u M, below E = 64 u M for p >= 2), with `last` whether b_p is a value of the curve
/// (else only b_0 is), or `None` if something is not finite. The span's values lie in the hull
/// of its exact Bézier coefficients (convex hull property, NURBS Book P5.x), so max v_i + E
/// bounds it, and C(u_k) = b_0 (right-continuous) is attained, b_0 - E below it. Results are
/// rounded outward by one step.
pub(crate) fn span_bounds(v: &[f64], m: f64, last: bool) -> Option<(f64, f64)> {
    let p = v.len() - 1;
    let e = (2 * p) as f64 * (8.0 * f64::EPSILON) * m + f64::MIN_POSITIVE;
    // (f64::max skips a NaN: a NaN or infinite coefficient, from an overflow, voids the
    // a-priori bound, so the span goes to the interval path)
    if !v.iter().all(|x| x.is_finite()) {
        return None;
    }
    let vmax = v.iter().fold(f64::NEG_INFINITY, |a, &x| a.max(x));
    let at = if last { v[0].max(v[p]) } else { v[0] };
    if !(vmax.is_finite() && e.is_finite() && at.is_finite()) {
        return None;
    }
    Some(((vmax + e).next_up(), (at - e).next_down()))
}

pub(crate) fn end_kind(c: &NurbsCurve, s: f64) -> CandidateKind {
    let (a, b) = c.domain();
    if s == a || s == b {
        CandidateKind::EndPoint
    } else if crate::spline::knots::multiplicity(c.knots(), s) >= c.degree() {
        // (an interior knot of multiplicity >= p: `NurbsCurve::non_differentiable_knots`,
        // without building the list)
        CandidateKind::Knot
    } else {
        CandidateKind::Critical
    }
}

/// Which path resolved a coordinate side of a single polynomial segment ([`fast_sides`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum FastPath {
    /// the extreme control coordinate is an end value: exact, attained, no search
    CheapExit,
    /// proven by the root-isolating fast path (`single`)
    Proof,
}

impl FastPath {
    /// Count the side in the stats of the side that took this path.
    pub(crate) fn count(self, s: &mut Side) {
        match self {
            FastPath::CheapExit => s.stats.fast_exits += 1,
            FastPath::Proof => s.stats.fast_proofs += 1,
        }
    }
}

/// The float-first part shared by `bezier` and `newton` for coordinate j: per side
/// `[max, min]` a resolved, sign-adjusted [`Side`] with the path that resolved it, or `None`
/// where the caller's general search must run.
///
/// 1. Cheap exit (any curve): if the largest (smallest) control coordinate is the value of a
///    clamped end, that end value is attained (`NurbsCurve::clamped_ends`: C = P_0 / P_n
///    exactly there) and bounds the curve (convex hull property, thesis prop. 2.1; positive
///    weights): the exact extremum, with no rounding at all. This covers every coordinate whose
///    control values are monotone, and fonts, whose designers put on-curve points at the
///    extrema.
/// 2. For a single polynomial Bézier segment of degree 2 or 3 (`n == p`, both ends clamped, no
///    weights: a plain quadratic / cubic Bézier), the root-isolating fast path (`single`,
///    whose module docs carry its proof and error bounds): f64 root estimates of C_j', proven
///    derivative signs (an f64 filter with an a-priori error bound, `Ddi` where it is unsure),
///    root counting, and a `Ddi` Taylor enclosure over each tiny bracket. It returns nothing
///    unless both asked sides are proven with a certified gap <= `max_gap`.
pub(crate) fn fast_sides(c: &NurbsCurve, j: usize, max_gap: f64) -> [Option<(Side, FastPath)>; 2] {
    let (p, n) = (c.degree(), c.num_points() - 1);
    let (a, b) = c.domain();
    let cl = c.clamped_ends();
    let pts = c.points_flat();
    let d = c.dim();
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for x in pts.iter().skip(j).step_by(d) {
        lo = lo.min(*x);
        hi = hi.max(*x);
    }
    let (x0, xn) = (pts[j], pts[n * d + j]);
    // Shortcut: the extreme control coordinate is an exactly attained end value.
    let shortcut = |sign: f64, m: f64| -> Option<(Side, FastPath)> {
        let u = if cl[0] && x0 == m {
            a
        } else if cl[1] && xn == m {
            b
        } else {
            return None;
        };
        let mut s = Side::new();
        s.attain_f64(sign * m);
        s.bound(
            sign * m,
            Extremum {
                u_lo: u,
                u_hi: u,
                unique: false,
                kind: CandidateKind::EndPoint,
            },
        );
        Some((s, FastPath::CheapExit))
    };
    let mut out = [shortcut(1.0, hi), shortcut(-1.0, lo)];
    let need = [out[0].is_none(), out[1].is_none()];
    let single_segment = !c.is_rational() && n == p && cl == [true, true] && (2..=3).contains(&p);
    if single_segment && need.contains(&true) {
        let mut v = [Ddi::exact(0.0); 4];
        for (i, x) in v.iter_mut().enumerate().take(p + 1) {
            *x = Ddi::exact(pts[i * d + j]);
        }
        let seg = single::Segment {
            c: &v[..=p],
            a,
            b,
            end_kinds: [CandidateKind::EndPoint; 2],
            right_attained: true,
        };
        if let Some([h, l]) = single::coord_sides(&seg, max_gap, need) {
            for (o, sd) in out.iter_mut().zip([h, l]) {
                if o.is_none() {
                    *o = Some((sd, FastPath::Proof));
                }
            }
        }
    }
    out
}

/// The `bezier` search ([`BezierSubdivision::maximize`], with its double-double refinement)
/// on the sides of coordinate j that another verified strategy left loose (`need`: [hi, lo]),
/// merged into that strategy's result `cb`: both are enclosures of the same extrema, so the
/// smaller upper bound, the larger attained value and the larger strict witness are all
/// valid. Used by `newton` for the rare sides its search cannot resolve (a critical point of
/// C_j' at a knot where the boxes straddling it stall, up to its box limit), which it would
/// otherwise report hundreds of ulps loose. Counted as `fast_fallbacks`.
pub(crate) fn tighten(c: &NurbsCurve, j: usize, cb: &mut CoordBox, need: [bool; 2]) {
    let strategy = BezierSubdivision::default();
    let mut ctx = Ctx::new(c, true);
    for (k, sign) in [(0, 1.0), (1, -1.0)] {
        if !need[k] {
            continue;
        }
        let mut s = strategy.maximize(&mut ctx, j, sign);
        s.upper = s.upper.max(s.attained);
        let (bound, inner, witness, args) = if k == 0 {
            (&mut cb.hi, &mut cb.inner_hi, &mut cb.witness_hi, &mut cb.argmax)
        } else {
            (&mut cb.lo, &mut cb.inner_lo, &mut cb.witness_lo, &mut cb.argmin)
        };
        // (sign-adjusted: the min side's values are those of -C_j)
        let (up, at, wi) = (sign * s.upper, sign * s.attained, sign * s.witness);
        let better = |x: f64, y: f64| if sign > 0.0 { x < y } else { x > y };
        if better(up, *bound) {
            *bound = up;
            args.clear();
            for (x, e) in &s.cands {
                if *x >= s.attained {
                    args.push(*e);
                }
            }
            if args.is_empty() {
                let (a, b) = c.domain();
                args.push(Extremum {
                    u_lo: a,
                    u_hi: b,
                    unique: false,
                    kind: CandidateKind::Unresolved,
                });
            }
        }
        if better(*inner, at) {
            *inner = at;
        }
        if better(*witness, wi) {
            *witness = wi;
        }
        s.stats.fast_fallbacks += 1;
        cb.stats.add(&s.stats);
    }
    // (the attained value stays between the bounds: clamp as the driver does)
    cb.inner_lo = cb.inner_lo.min(cb.hi).max(cb.lo);
    cb.inner_hi = cb.inner_hi.max(cb.lo).min(cb.hi);
}

/// The coordinate box from the two sign-adjusted sides (max side `hi`, min side `lo`) over the
/// domain [a, b]: outer bounds, attained values, and the candidates reaching them.
pub(crate) fn coord_box(
    hi: Side,
    lo: Side,
    a: f64,
    b: f64,
    time: std::time::Duration,
) -> CoordBox {
    // If no recorded candidate reaches the attained value (it came from an end coefficient of
    // a piece pruned right away), the whole domain is reported: it certainly contains the
    // argument of the extremum.
    let pick = |s: &Side| {
        let mut v = super::Extrema::new();
        for (x, e) in &s.cands {
            if *x >= s.attained {
                v.push(*e);
            }
        }
        if v.is_empty() {
            v.push(Extremum {
                u_lo: a,
                u_hi: b,
                unique: false,
                kind: CandidateKind::Unresolved,
            });
        }
        v
    };
    let mut stats = hi.stats;
    stats.add(&lo.stats);
    stats.time_total = time;
    let term = if hi.term != Termination::Converged {
        hi.term
    } else {
        lo.term
    };
    // (The driver intersects the result with the control-point box, which guarantees the
    // sandwich hull ⊇ bezier: `driver::drive`.)
    let side = |s: &Side| super::SideData {
        upper: s.upper,
        attained: s.attained,
        witness: s.witness,
        args: pick(s),
    };
    CoordBox::from_sides(side(&hi), side(&lo), stats, term)
}

impl BoxEncloser for BezierSubdivision {
    fn name(&self) -> &'static str {
        "bezier"
    }
    fn guarantee(&self) -> Guarantee {
        Guarantee::Verified
    }
    fn lane(&self) -> Option<super::lane::Lane> {
        // (the lane's tight answer is this strategy's own fast path, switched on by default)
        self.fast_path.then_some(super::lane::Lane::Tight)
    }
    fn enclose_prepared(&self, c: &NurbsCurve) -> Enclosure {
        let (a, b) = c.domain();
        // Built only when some coordinate side needs a search.
        let mut ctx: Option<Ctx> = None;
        let mut coords = super::Coords::new();
        let mut clock = super::Clock::start();
        for j in 0..c.dim() {
            // Cheap exits, and for a single quadratic / cubic Bézier segment the
            // root-isolating fast path (`fast_sides`), which falls back to the branch and
            // bound below when it cannot prove a tight result.
            let [f_hi, f_lo] = if self.fast_path {
                fast_sides(c, j, self.max_gap(c, j))
            } else {
                [None, None]
            };
            let mut side = |f: Option<(Side, FastPath)>, sign: f64| -> Side {
                if let Some((mut s, path)) = f {
                    path.count(&mut s);
                    return s;
                }
                let ctx = ctx.get_or_insert_with(|| Ctx::new(c, self.fast_path));
                let mut s = self.maximize(ctx, j, sign);
                s.stats.fast_fallbacks += 1;
                s
            };
            let hi = side(f_hi, 1.0);
            let lo = side(f_lo, -1.0);
            // (time per coordinate, when asked for: one clock read per coordinate boundary)
            coords.push(coord_box(hi, lo, a, b, clock.lap()));
        }
        Enclosure {
            strategy: self.name(),
            verified: true,
            coords,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `SpanPoints::end_peaked` claims a side only where every inner point's enclosure lies
    /// strictly beyond the larger (smaller) end's: exact points with a peak at either end, a
    /// tie with an inner point (not a peak: C' is zero at that end), an inner peak, points
    /// enclosed an ulp wide that overlap the end's enclosure (not proven), and p = 1 (no inner
    /// point: always). Fails with a non-strict comparison, or with the other end of an
    /// enclosure.
    #[test]
    fn end_peaked_needs_a_proven_strict_peak() {
        let pts = |v: &[(f64, f64)]| -> Vec<Ddi> {
            // (centre, radius): one coordinate, not rational
            v.iter().map(|&(x, r)| Ddi::from_parts(x, 0.0, r)).collect()
        };
        let sp = |v: &[(f64, f64)]| span_points(&pts(v), v.len() - 1, 0, false);
        let e = |x: f64| (x, 0.0);
        // peak at the right end, the minimum inside
        let s = sp(&[e(0.3), e(0.5), e(0.2), e(1.0)]);
        assert!(s.end_peaked(1.0) && !s.end_peaked(-1.0));
        // peak at the left end; minimum at the right end
        let s = sp(&[e(2.0), e(1.0), e(1.5), e(-1.0)]);
        assert!(s.end_peaked(1.0) && s.end_peaked(-1.0));
        // a tie of the end with its neighbour is no peak (either side)
        let s = sp(&[e(0.0), e(1.0), e(1.0)]);
        assert!(!s.end_peaked(1.0) && s.end_peaked(-1.0));
        let s = sp(&[e(0.0), e(0.0), e(1.0)]);
        assert!(s.end_peaked(1.0) && !s.end_peaked(-1.0));
        // an inner peak
        let s = sp(&[e(0.0), e(3.0), e(1.0)]);
        assert!(!s.end_peaked(1.0));
        // enclosures that overlap: the inner point may reach the end's value
        let u = f64::EPSILON;
        let s = sp(&[(0.0, 0.0), (1.0 - u, u), (1.0, 0.0)]);
        assert!(!s.end_peaked(1.0));
        let s = sp(&[(0.0, 0.0), (1.0 - 4.0 * u, u), (1.0, 4.0 * u)]);
        assert!(!s.end_peaked(1.0));
        let s = sp(&[(0.0, 0.0), (1.0 - 8.0 * u, u), (1.0, u)]);
        assert!(s.end_peaked(1.0));
        let s = sp(&[(1.0, u), (1.0 - 8.0 * u, u), (0.0, 0.0)]);
        assert!(s.end_peaked(1.0));
        let s = sp(&[(-1.0, u), (-1.0 + 2.0 * u, u), (0.0, 0.0)]);
        assert!(!s.end_peaked(-1.0));
        // p = 1: no inner point
        let s = sp(&[e(0.0), e(1.0)]);
        assert!(s.end_peaked(1.0) && s.end_peaked(-1.0));
    }

    /// The span filter's end pairs are the ends of the intervals the filter built before:
    /// the `Ddi` enclosure's interval, and for a rational point the quotient by the weight's
    /// interval (`iv::div_positive`); the whole line for exactly the same points (unbounded or
    /// overflowed parts, weights not proven positive). Random points of every magnitude,
    /// double-word parts and radii, zero, negative, tiny and unbounded weights, ENTIRE.
    #[test]
    fn cartesian_ends_are_the_interval_route_s_ends() {
        use rand::{Rng, SeedableRng};
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let ddi = |r: &mut rand_chacha::ChaCha8Rng| -> Ddi {
            match r.random_range(0..12) {
                0 => Ddi::ENTIRE,
                1 => Ddi::exact(0.0),
                _ => {
                    let h = r.random_range(-1.0..1.0) * 2f64.powi(r.random_range(-1074..1024));
                    let l = h * r.random_range(-1.0..1.0) * 1e-17;
                    let rad = match r.random_range(0..4) {
                        0 => 0.0,
                        1 => h.abs() * 1e-30,
                        2 => h.abs() * r.random_range(0.0..2.0),
                        _ => f64::from_bits(r.random_range(1..100)),
                    };
                    Ddi::from_parts(h, l, rad)
                }
            }
        };
        let (mut whole, mut finite) = (0, 0);
        for _ in 0..200_000 {
            let pts = [ddi(&mut r), ddi(&mut r)];
            for rational in [false, true] {
                let x = pts[0].to_interval();
                let want = if rational {
                    iv::div_positive(x, pts[1].to_interval())
                } else {
                    x
                };
                let got = cartesian_ends(&pts, 2, 0, 0, rational);
                assert_eq!(
                    (got.0.to_bits(), got.1.to_bits()),
                    (want.inf().to_bits(), want.sup().to_bits()),
                    "{pts:?} rational {rational}"
                );
                if want.is_entire() {
                    whole += 1;
                } else {
                    finite += 1;
                }
            }
        }
        assert!(whole > 10_000 && finite > 100_000, "{whole} {finite}");
    }

    /// A symmetric curve's extremum at a simple knot, where C_j' vanishes: the pieces ending
    /// there have equal last coefficients in exact arithmetic, so only the form about the span
    /// end resolves them ([`Values::end_bound`]). Both curves (a rational quadratic and a
    /// cubic B-spline, mirror-symmetric about u = 0) get a box equal to `newton`'s, with every
    /// candidate of the extremal side at most 1e-20 wide and touching u = 0, in a few
    /// subdivisions. Before the form the rational curve took 170 halvings towards the knot
    /// and left candidates 3e-9 wide, the cubic whole spans as candidates (leaving the search
    /// to the certificate: 1.4 ms).
    #[test]
    fn extremum_at_a_knot_is_localised_by_the_form_about_the_span_end() {
        let rational = crate::spline::tight::tests::symmetric_at_a_knot();
        let p0 = vec![-0.016961445022445787, -0.28011497410670394, 0.8267767663545693];
        let p1 = vec![-0.49477064966508033, -0.46350307447337835, -0.18037872595062465];
        let p2 = vec![-0.8444131538248487, 0.00814113619952117, -0.6926557192853666];
        let cubic = NurbsCurve::new(
            3,
            vec![-1.0, -1.0, -1.0, -1.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            vec![p0.clone(), p1.clone(), p2, p1, p0],
            None,
        )
        .unwrap();
        // (curve, [side of each coordinate whose extremum is at u = 0: true = max], most
        // subdivisions)
        for (c, at_knot, most) in [
            (&rational, [false, true, false], 12),
            (&cubic, [false, true, false], 12),
        ] {
            // (the search itself, without the fast paths, which would take these spans: the
            // general one localises such an extremum to its box of 2^-40 of the span, below)
            let search = BezierSubdivision {
                fast_path: false,
                ..BezierSubdivision::default()
            };
            let e = crate::enclose::drive_with(&search, c, false);
            let f = crate::enclose::drive_with(&BezierSubdivision::default(), c, false);
            let n = crate::enclose::drive_with(&crate::enclose::Newton::default(), c, false);
            assert!(e.stats().subdivisions <= most, "{:?}", e.stats());
            for (j, ((cb, fb), nb)) in e.coords.iter().zip(&f.coords).zip(&n.coords).enumerate() {
                assert_eq!((cb.lo, cb.hi), (nb.lo, nb.hi), "coordinate {j}");
                assert_eq!((cb.lo, cb.hi), (fb.lo, fb.hi), "coordinate {j}");
                for (b, width) in [(cb, 1e-20), (fb, 1e-12)] {
                    let args = if at_knot[j] { &b.argmax } else { &b.argmin };
                    for x in args {
                        assert!(
                            x.u_hi - x.u_lo <= width && x.u_lo <= 0.0 && 0.0 <= x.u_hi,
                            "coordinate {j}: {args:?}"
                        );
                    }
                }
            }
        }
    }

    /// The localisation of [`Values::end_bound`] off the symmetric case: the rational quadratic
    /// of the test above with its fourth control point moved by 2^-k (k = 44 .. 56) in its
    /// second coordinate, so that the maximum moves off the knot u = 0 by 1e-14 .. 1e-18 (from
    /// k = 50 on too close to the knot for the critical-point estimate: the form about the
    /// end places the candidate). Some candidate [u_lo, u_hi] of `bezier`'s must bracket the
    /// maximiser, C'(u_lo) >= 0 >= C'(u_hi) not excluded by double-double de Boor enclosures
    /// (the maximiser lies 9.62999e-17 right of the knot at k = 50 by 256-bit MPFR; the
    /// candidate there is [0, 9.6303e-17], where f64 Newton on C' says 1.04e-16), the
    /// candidates stay narrow, and the bounds agree with `newton`'s. (Fails with δ = 0, the
    /// candidate then being the knot alone, and with the candidate on the wrong side.)
    #[test]
    fn knot_extremum_candidates_hold_the_moved_maximiser() {
        let base = crate::spline::tight::tests::symmetric_at_a_knot();
        for k in (44..=56).step_by(2) {
            let mut pts: Vec<Vec<f64>> = (0..base.num_points())
                .map(|i| base.control_point(i).to_vec())
                .collect();
            pts[3][1] += 2f64.powi(-k);
            let w = (0..base.num_points()).map(|i| base.weight(i)).collect();
            let c = NurbsCurve::new(2, base.knots().to_vec(), pts, Some(w)).unwrap();
            let e = crate::enclose::drive_with(&BezierSubdivision::default(), &c, false);
            let n = crate::enclose::drive_with(&crate::enclose::Newton::default(), &c, false);
            let (cb, nb) = (&e.coords[1], &n.coords[1]);
            assert_eq!((cb.lo, cb.hi), (nb.lo, nb.hi), "k={k}");
            let f = crate::spline::eval::CurveEval::<Ddi>::new(&c, 1);
            let slope = |u: f64| f.derivs(u, 1).unwrap()[1][1].to_interval();
            assert!(
                cb.argmax
                    .iter()
                    .any(|y| slope(y.u_lo).sup() >= 0.0 && slope(y.u_hi).inf() <= 0.0),
                "k={k}: bezier {:?}",
                cb.argmax
            );
            assert!(
                cb.argmax.iter().all(|y| y.u_hi - y.u_lo <= 1e-6),
                "k={k}: {:?}",
                cb.argmax
            );
        }
    }

    /// A critical point within d = 2^-26 of the span width from a knot (the minimum of this
    /// rational quadratic with weights from 4e-4 to 5e5 lies 9e-10 before the knot 0.75): the
    /// middle piece around the estimate ends at the knot, where the estimate used to be
    /// discarded and the piece halved towards the knot (42 subdivisions instead of 18, with
    /// the same box as `newton`'s).
    #[test]
    fn critical_point_next_to_a_knot_is_split_off_not_halved_towards() {
        let c = NurbsCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 0.25, 0.5, 0.75, 1.0, 1.0, 1.0],
            [
                -0.6902999830268475,
                0.8997322289200547,
                0.5381948554551244,
                -0.9924163984561925,
                0.7481092902640918,
                -0.001867081025085593,
            ]
            .iter()
            .map(|&x| vec![x])
            .collect(),
            Some(vec![
                0.010660443509636094,
                0.0004034037413684456,
                485776.0733760156,
                15.78474243585209,
                0.0007804392202859371,
                0.000593991239259757,
            ]),
        )
        .unwrap();
        let e = crate::enclose::drive_with(&BezierSubdivision::default(), &c, false);
        let n = crate::enclose::drive_with(&crate::enclose::Newton::default(), &c, false);
        assert_eq!((e.coords[0].lo, e.coords[0].hi), (n.coords[0].lo, n.coords[0].hi));
        assert!(e.stats().subdivisions <= 24, "{:?}", e.stats());
    }

    /// The hull filter's bounds (`span_points` and `SpanPoints::side`) against the curve: on random
    /// curves of the families with the hardest knot vectors, rational ones (extreme weights)
    /// included, every sampled value of a span (interval de Boor at 33 parameters, its
    /// enclosure's far end) lies within the bound, the attained value is at most the curve's
    /// value at the span's start (and at its end on the last span), and a span whose points
    /// are found non-decreasing (non-increasing) has non-decreasing (non-increasing) samples.
    /// Taking b_p as attained on every span fails it, and so does a monotonicity flag that
    /// ignores the points.
    #[test]
    fn span_hull_bounds_the_span_and_attains_its_value() {
        use crate::testkit::gen::{self, Family};
        let mut r = gen::rng(13);
        let (mut checked, mut rational, mut monotone) = (0, 0, 0);
        for fam in [
            Family::ClampedUniform,
            Family::ClusteredKnots,
            Family::MultipleKnots,
            Family::Unclamped,
            Family::ExtremaAtKnots,
            Family::ExtremeWeights,
            Family::Mixed,
        ] {
            for _ in 0..25 {
                let c = fam.curve(&mut r);
                let ev = TightEval::sweeping(&c);
                let (p, n, kn) = (c.degree(), c.num_points() - 1, c.knots());
                let spans: Vec<usize> = (p..=n).filter(|&k| kn[k] < kn[k + 1]).collect();
                for &k in &spans {
                    let last = k == spans[spans.len() - 1];
                    let pts = ev.bezier_points(k);
                    for j in 0..c.dim() {
                        let sp = span_points(pts, p, j, c.is_rational());
                        // (the span's own piece: at its right end the left limit, so that end
                        // only on the last span)
                        let xs: Vec<Interval> = (0..=32)
                            .filter(|&i| i < 32 || last)
                            .map(|i| {
                                let u = (kn[k] + (kn[k + 1] - kn[k]) * (i as f64 / 32.0))
                                    .clamp(kn[k], kn[k + 1]);
                                c.point::<Interval>(u)
                                    .map(|p| p[j])
                                    .unwrap_or(Interval::ENTIRE)
                            })
                            .collect();
                        for w in xs.windows(2) {
                            if sp.inc {
                                assert!(w[1].sup() >= w[0].inf(), "span {k} coord {j}: not increasing");
                            }
                            if sp.dec {
                                assert!(w[1].inf() <= w[0].sup(), "span {k} coord {j}: not decreasing");
                            }
                        }
                        monotone += (sp.inc || sp.dec) as usize;
                        for sign in [1.0, -1.0] {
                            let (ub, at) = sp.side(sign, last);
                            for x in &xs {
                                let far = if sign > 0.0 { x.inf() } else { -x.sup() };
                                assert!(far <= ub, "span {k} coord {j}: {far:e} > {ub:e}");
                            }
                            let v = ev.coord_at(j, kn[k]);
                            let near = if sign > 0.0 { v.sup() } else { -v.inf() };
                            let mut ok = at <= near;
                            if last {
                                let w = ev.coord_at(j, kn[k + 1]);
                                ok |= at <= if sign > 0.0 { w.sup() } else { -w.inf() };
                            }
                            assert!(ok, "span {k} coord {j}: attained {at:e} above the curve");
                            checked += 1;
                            rational += c.is_rational() as usize;
                        }
                    }
                }
            }
        }
        assert!(checked > 500 && rational > 200 && monotone > 50, "{checked} {rational} {monotone}");
    }

    /// The general fast path ([`Critical`]) on spans of degree 4 .. 40, rational and not
    /// (weights over orders of magnitude, clustered and multiple knots): it proves most of the
    /// span sides it meets (`fast_proofs`); its boxes contain double-double values of the curve
    /// sampled along the domain and around the extremes that the search without fast paths
    /// finds (fails without the critical boxes in the sides: an interior extremum above the
    /// bound); and its bounds are those of that search to two ulps of the scale.
    #[test]
    fn general_fast_path_is_sound_and_as_tight_as_the_search() {
        use crate::testkit::gen::Family;
        let mut rng = crate::testkit::gen::rng(41);
        let fast = BezierSubdivision::default();
        let slow = BezierSubdivision {
            fast_path: false,
            ..BezierSubdivision::default()
        };
        let (mut proofs, mut curves) = (0u64, 0);
        for fam in [
            Family::HighDegree,
            Family::ExtremeWeights,
            Family::ClusteredKnots,
            Family::MultipleKnots,
            Family::Mixed,
        ] {
            for _ in 0..12 {
                let c = fam.curve(&mut rng);
                if c.degree() < 4 && !c.is_rational() {
                    continue;
                }
                curves += 1;
                let (e, r) = (fast.enclose(&c), slow.enclose(&c));
                proofs += e.stats().fast_proofs;
                let tight = TightEval::new(&c);
                let (a, b) = c.domain();
                for (j, (cb, rb)) in e.coords.iter().zip(&r.coords).enumerate() {
                    let gap = 2.0 * crate::num::ulp(c.coord_scale(j));
                    assert!(
                        (cb.hi - rb.hi).abs() <= gap && (cb.lo - rb.lo).abs() <= gap,
                        "{fam:?} j = {j}: [{}, {}] vs [{}, {}]",
                        cb.lo,
                        cb.hi,
                        rb.lo,
                        rb.hi
                    );
                    let mut us: Vec<f64> = (0..=400).map(|i| a + (b - a) * i as f64 / 400.0).collect();
                    for x in rb.argmax.iter().chain(&rb.argmin) {
                        for i in 0..=8 {
                            us.push(x.u_lo + (x.u_hi - x.u_lo) * i as f64 / 8.0);
                        }
                    }
                    for u in us.into_iter().filter(|u| (a..=b).contains(u)) {
                        let v = tight.coord_at(j, u);
                        assert!(
                            cb.lo <= v.sup() && v.inf() <= cb.hi,
                            "{fam:?} j = {j} u = {u}: [{:e}, {:e}] outside [{:e}, {:e}]",
                            v.inf(),
                            v.sup(),
                            cb.lo,
                            cb.hi
                        );
                    }
                }
            }
        }
        assert!(proofs as usize >= curves, "{proofs} proofs on {curves} curves");
    }

    /// Extreme weights (1e-6 .. 1e6) make F's `Mr` coefficients wide (products ~1e6 that
    /// cancel to ~1e-6), too wide for the general fast path's sign proofs next to a zero; F
    /// recomputed from the double-double points (`SpanPoly::refined`) proves those spans, so
    /// that the subdivision runs on almost none of them (81 subdivisions on these 100 curves
    /// without it, 1 with it), with bounds within two ulps of the scale of the search without
    /// fast paths.
    #[test]
    fn extreme_weights_spans_are_proven_without_subdivision() {
        use crate::testkit::gen::Family;
        let mut rng = crate::testkit::gen::rng(11);
        let fast = BezierSubdivision::default();
        let slow = BezierSubdivision {
            fast_path: false,
            ..BezierSubdivision::default()
        };
        let mut subdivisions = 0;
        for _ in 0..100 {
            let c = Family::ExtremeWeights.curve(&mut rng);
            let e = fast.enclose(&c);
            subdivisions += e.stats().subdivisions;
            let r = slow.enclose(&c);
            for (j, (cb, rb)) in e.coords.iter().zip(&r.coords).enumerate() {
                let gap = 2.0 * crate::num::ulp(c.coord_scale(j));
                assert!(
                    (cb.hi - rb.hi).abs() <= gap && (cb.lo - rb.lo).abs() <= gap,
                    "j = {j}: [{}, {}] vs [{}, {}]",
                    cb.lo,
                    cb.hi,
                    rb.lo,
                    rb.hi
                );
            }
        }
        assert!(subdivisions <= 10, "{subdivisions} subdivisions");
    }

    #[test]
    fn cubic_bezier_box_contains_samples_and_is_tight() {
        let c = NurbsCurve::new(
            3,
            vec![0., 0., 0., 0., 1., 1., 1., 1.],
            vec![vec![0., 0.], vec![1., 2.], vec![2., -1.], vec![3., 0.5]],
            None,
        )
        .unwrap();
        let e = BezierSubdivision::default().enclose(&c);
        for i in 0..=10000 {
            let u = i as f64 / 10000.0;
            let p = c.enclose_point(iv::point(u)).unwrap();
            #[allow(clippy::needless_range_loop)]
            for j in 0..2 {
                // a containment miss is proven when the point's enclosure lies beyond a bound
                assert!(
                    e.coords[j].lo <= p[j].sup() && p[j].inf() <= e.coords[j].hi,
                    "u={u} j={j} [{}, {}] vs box [{}, {}]",
                    p[j].inf(),
                    p[j].sup(),
                    e.coords[j].lo,
                    e.coords[j].hi
                );
            }
        }
        for cb in &e.coords {
            assert!(cb.lo <= cb.inner_lo && cb.inner_hi <= cb.hi);
            assert!(cb.gap() <= 8.0 * f64::EPSILON * 2.0, "gap {}", cb.gap());
        }
    }

    #[test]
    fn discontinuity_uses_the_left_limit_not_an_empty_intersection() {
        // Knot 0.5 of multiplicity p + 1: the left piece approaches 3 at 0.5, C(0.5) = 1.
        let c = NurbsCurve::new(
            2,
            vec![0., 0., 0., 0.5, 0.5, 0.5, 1., 1., 1.],
            vec![vec![0.], vec![2.], vec![3.], vec![1.], vec![0.5], vec![0.]],
            None,
        )
        .unwrap();
        let e = BezierSubdivision::default().enclose(&c);
        let cb = &e.coords[0];
        assert!(cb.hi >= 3.0 && cb.inner_hi <= 3.0, "{cb:?}");
        assert!(cb.lo <= 0.0 && cb.inner_lo >= 0.0, "{cb:?}");
    }

    /// `local_search` on a piece whose values cancelled to rounding (every point an enclosure
    /// [-1, 1] around an exact 0: no split narrows them) stops at once with a sound bound
    /// ([`rounding_bound`]); without the rule it halved to its piece limit. Points that are
    /// narrow against their size are split on: a quadratic with a maximum 1/4 at t = 1/2
    /// is resolved to its double.
    #[test]
    fn local_search_stops_on_rounding_and_resolves_a_maximum() {
        let seg = |pts: Vec<Ddi>| BezierSeg {
            a: 0.0,
            b: 1.0,
            degree: 2,
            dim: 1,
            rational: false,
            pts,
        };
        let wide = seg(vec![Ddi::from_bounds(-1.0, 1.0); 3]);
        let r = local_search(2, 1.0, &[(0, wide)], &[(0, 0.0, 1.0)], &|_| true, (f64::NEG_INFINITY, f64::NEG_INFINITY), 512);
        assert_eq!(r.stats.subdivisions, 0);
        assert!(r.upper() >= 1.0);
        // t (1 - t) in Bernstein form: 0, 1/2, 0; max 1/4 at t = 1/2
        let bump = seg(vec![Ddi::exact(0.0), Ddi::exact(0.5), Ddi::exact(0.0)]);
        let r = local_search(2, 1.0, &[(0, bump)], &[(0, 0.0, 1.0)], &|_| true, (f64::NEG_INFINITY, f64::NEG_INFINITY), 512);
        assert!(r.upper() >= 0.25 && r.upper() <= 0.25f64.next_up());
        assert!(r.attained <= 0.25 && r.witness < 0.25);
    }
}

