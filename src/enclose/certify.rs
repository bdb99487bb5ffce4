//! Certificates of optimal bounds: `optimal_hi` proves hi = RU(max_u C_j(u)), `optimal_lo`
//! proves lo = RD(min_u C_j(u)) ([`certify`], applied by the driver to the result of every
//! verified strategy).
//!
//! # Why a certificate is a proof
//!
//! A verified strategy has proved C_j(u) <= hi for every u in the domain, so the exact maximum
//! (the supremum, for a curve with a jump) M satisfies M <= hi. If moreover some parameter u has
//! C_j(u) > t := next_down(hi), then t < M <= hi: no f64 lies in [M, hi) and hi is the smallest
//! f64 >= M, i.e. hi = RU(M). `optimal_hi` is set `true` exactly when one of these was shown:
//!
//! 1. **An attained value equal to hi**: `inner_hi == hi` (the strategy, or the driver's facts
//!    such as a clamped end control point, proved that the curve reaches a value >= inner_hi);
//!    then M = hi. Or a clamped end's value (the end control point, exact) above t, or the
//!    value of a span's piece at a knot of multiplicity >= p (a control point, exact: a curve
//!    value, or at a jump the left limit of curve values; `Evals::knot_value`) above t. Or the
//!    strategy's strict witness `witness_hi >= t` (the strategy proved
//!    that the curve reaches a value > witness_hi, e.g. by a double-double value at a proved
//!    critical point: [`Ddi::strictly_below`]); then M > t. This costs nothing extra.
//! 2. **A verified enclosure above t**: a double-double enclosure ([`Ddi`], rigorous, about
//!    2^-100 relative wide) of C_j(u) at an f64 parameter u whose lower end (compared exactly)
//!    is > t.
//!    Or **a left limit above t**: at a jump (a knot u of multiplicity p + 1) the supremum
//!    can be the left limit, which no curve value attains; the piece of the span ending at u,
//!    evaluated at u in `Ddi`, is that limit, and curve values come arbitrarily close to it,
//!    so a lower end above t shows some curve value above t.
//! 3. **An exact value above t**: the exact rational C_j(u) ([`Exact`]: the generic de Boor and
//!    derivative kernels run on big rationals, no rounding) at an f64 or dyadic parameter u is
//!    > t (compared exactly).
//!
//! The lower bound is the same statement for -C_j. Nothing else sets a flag, so a wrong `true`
//! would need a wrong outer bound, a wrong inner bound or a wrong enclosure / exact value, all
//! of which are the crate's soundness guarantees already.
//!
//! # Extreme magnitudes
//!
//! A curve the driver rescales (`Rescaling`: coordinates beyond 2^±80, weights beyond 2^±30,
//! knots far from a domain of length ~1) is certified on rescaled copies, built per coordinate
//! j and side (`Rescaling::apply_coord`):
//!
//! * the knots multiplied by the driver's exact power of two 2^-k: an exact reparametrisation
//!   with the same image (the driver's module docs), so the same extrema; the strategy's
//!   candidates are mapped to the new parameters, rounded outward (they only say where to
//!   look). Parameters that are a few subnormals apart (a domain [0, 2^-1068]) become
//!   parameters of ~1: f64 points and boxes between the knots, Newton steps that converge;
//! * the weights multiplied by the driver's exact power of two: the same curve;
//! * coordinate j multiplied by 2^-s, s chosen so that the values near the bound are near 1
//!   (`coord_exponent`: double-double enclosures ~2^-100 relative narrow, which values near
//!   f64::MAX, with overflowing error terms, or subnormal values, with no bits below 2^-1074,
//!   are not). C_j = sum_i R_i P_ij with rational basis functions R_i >= 0, sum R_i = 1, that
//!   do not depend on the coordinates (thesis def. 3.1), so exact scaled control values give
//!   exactly 2^-s C_j. Where a scaled control value is not exact (it fell into the subnormal
//!   range), it is rounded down in one copy and up in another: C_dn <= 2^-s C_j <= C_up at
//!   every u (a convex combination of values each moved down, or up). A value above a target
//!   is then proved on the copy below g = ±C_j (C_dn for the maximum, C_up for the minimum),
//!   g <= t on the copy above it ([`Curves`]); with exact values both copies are one curve.
//!
//! A proof about the scaled g against t 2^-s rounded up (for "above") or a target rounded
//! down (for "at most") is then the same proof about g ([`scale_outward`]).
//!
//! The exact values (a clamped end's control point, the value at a knot of multiplicity at
//! least p, the control points of a span's strong convex hull) are always the enclosed curve's
//! own control points, compared with the bound or target in its own units: no scaling
//! rounds them (a subnormal maximum next to values near f64::MAX stays exact). In the Bézier
//! rule of a lowering proof the piece's end point is such a value, its other points come
//! from the copy above; this is a hull of the curve's own piece too, since the piece's
//! points of the copy above are >= its own scaled points (both are the same convex
//! combinations, of the B-spline control points or, for a rational piece, of the homogeneous
//! ones w_i P_i with the same weights, and C_up's control values are >= 2^-s P_ij).
//!
//! # Choosing u (Ziv's strategy)
//!
//! The strategy's candidates (`argmax` / `argmin`: parameter intervals whose enclosures reach
//! the bound; at most [`MAX_CANDIDATES`]) say where to look. Per candidate:
//!
//! * the `Ddi` value at its midpoint (or its point, for a knot or an end);
//! * up to [`NEWTON_STEPS`] Newton steps u <- u - g'(u)/g''(u) on g = ±C_j with double-double
//!   derivatives (only to *choose* u, never part of the proof), then the `Ddi` value at u and
//!   its two f64 neighbours; then the same in the local parameter s of the candidates' spans
//!   (`bezier_search`: the span's Bézier form in double-double, Newton steps on s, values by
//!   de Casteljau), which needs no derivative with respect to u (those over- or underflow
//!   for knots near ±f64::MAX or spans of a few subnormals). At the f64 u nearest the extremum u*, g(u) = M - O(g'' ulp(u)^2),
//!   i.e. ~2^-106 relative below M: this decides every bound with M - t above ~2^-100 M;
//! * if that fails with t inside some enclosure (a near-tie: M within ~2^-100 relative above
//!   t) and the degree is at most [`EXACT_MAX_DEGREE`] ([`EXACT_MAX_DEGREE_RATIONAL`] for a
//!   rational curve): the exact value at u, then Newton steps in exact arithmetic whose
//!   iterates are truncated to dyadic parameters of [`ZIV_BITS`] binary digits (each level
//!   doubles the precision, as Newton's quadratic convergence allows), the exact value at each.
//!   A near-tie M - t down to about 2^-(2 * 480) relative is decided this way.
//!
//! # Lowering a bound (the other branch of the Ziv loop)
//!
//! When no value above t is found, the bound may not be optimal: M <= t. If some value seen
//! lies within [`LOWER_WITHIN_ULPS`] doubles of the bound, `prove_at_most` tries to prove
//! g <= t' on the whole domain for t' = the double just above the values seen (RU(M) when
//! the search found the extremum), else for t' = t; on success the bound becomes t' (still a
//! proved bound) and the certificate is tried again, at most [`MAX_LOWERINGS`] times. The
//! proof is a branch and bound over every span (each polynomial / rational piece on its closed
//! span, which covers every value of the curve, jumps included). A span is first tested by the
//! strong convex hull of its B-spline control points, then of its Bézier pieces
//! (`bezier_rule`: the span's Bézier form in double-double, halved by de Casteljau; at a
//! clamped domain end the end point is the end control point exactly, so a maximum attained
//! there, an exact tie with t, is decided without rounding error, at any degree). What the
//! pieces leave undecided goes to these rules per parameter box X:
//!
//! * f64 interval enclosures (inari, outward rounded) of g over X, natural and mean value form
//!   g(m) + g'(X)(X - m): upper end <= t' (most boxes, away from the extremum);
//! * the same in double-double;
//! * monotonicity: g'(X) >= 0 (or <= 0) proved, so max_X g is the value at an end, which is
//!   decided as a point (an exact end control point at a clamped end, a double-double
//!   enclosure, or the exact rational value);
//! * concavity: g''(X) < 0 proved, so g lies below its tangent at every point of X, hence
//!   below the intersection T of the tangents at two points m1 < m2 with g'(m1) >= 0 >=
//!   g'(m2); T is enclosed in double-double, or computed exactly at dyadic points from exact
//!   Newton steps (this proves M <= t' also when M = t' exactly, e.g. a double extremum at
//!   u = 1/2); only near the strategy's candidates;
//! * a value above t' ends the attempt (t' is not a bound), otherwise the box is split.
//!
//! Lowering first without exact arithmetic, then (if the exact stage did not certify) with it;
//! on a rescaled curve (extreme magnitudes) the first lowering proof has the exact rules
//! already and is not repeated. A proof that met a value above its target is not repeated
//! with exact rules (that value stands); one that ran out of boxes is followed by the exact
//! Bernstein rule before the second branch and bound. A double-double value seen in one round
//! proves a later round's lower target without the double-double stage running again.
//!
//! # Straddles and the exact Bernstein rule
//!
//! A straddle (t inside a double-double enclosure of a value seen: the extremum is exactly a
//! double or within ~2^-100 relative of one) cannot be lowered with double-double rules, so
//! for degree <= [`EXACT_MAX_DEGREE`] (rational or not) it goes straight to
//! [`exact_at_most`]: per span whose control points exceed t, the exact Bernstein
//! coefficients of f = A - t W (the piece's numerator and weight in its local Bézier
//! parameter, W > 0: f <= 0 iff g <= t), subdivided exactly, first at the candidate
//! maximiser, where an exact tie is a double root of f ([`exact_bernstein_rule`]). It
//! answers g <= t (the bound becomes t) or a curve value above t (the certificate), with no
//! rounding. The same rule is a lowering attempt when the box rules fail (degree 6,
//! extreme weights, clustered knots): before the exact branch and bound when the first one
//! ran out of boxes, else last.
//!
//! # Extrema far below a scale near f64::MAX (the local stage)
//!
//! On a rescaled curve a strategy's bound can lie within its tolerance of the coordinate scale
//! (an ulp of ~1e308 is ~2e292) but many doubles of its own size above the extremum: a minimum
//! -0.5476 next to control values ~7e307, found at a local parameter ~1e-77 of a span ~4e307
//! wide, where the strategy stopped at a control value -0.9116. Before the rounds above, such
//! a side (more than [`LOWER_WITHIN_ULPS`] doubles of its bound above the attained value, but
//! within the lowering window of the scale) is searched again ([`local_stage`]): every span whose
//! control values exceed the attained value, in its local parameter, on its double-double
//! Bézier segment of the copy scaled for this side (values near the bound ~1, ~2^-100
//! relative narrow), by `bezier`'s best-first local search (convex hull bounds of de Casteljau
//! pieces, splits at critical-point estimates; with rounded copies the bound from the copy
//! above g, the attained value and witness from the copy below). Its bound lowers the side's
//! bound (rounded up into the curve's units), its values raise the attained value and the
//! witness, and its pieces become the first candidates; the rounds then certify, usually by
//! the first rule (their search in the Bézier form, `bezier_search`, is skipped after it: the
//! local stage searched the same spans in the same parameter, to more pieces). Sound for the
//! same reasons as the strategies' own search: the pieces cover every span whose control hull
//! is not already below a value attained.
//!
//! # The exact end game
//!
//! Every stage above runs on copies of the curve scaled into the f64 range. A coordinate with
//! values ~1e-320 next to values ~1e308 (or knots whose differences overflow) fits no single
//! scaling: the copy's rounded control values blur the extremum by far more than its ulp. A
//! bound these stages leave undecided, but within the lowering window of the scale, goes last
//! to [`exact_endgame`], on the enclosed curve itself: each span's piece g = 2^d A / W as two
//! integer Bernstein rows (exact, fraction-free Boehm insertion; [`span_rows_integer`]), A
//! a lower bound of sup g (the attained value, then the exact values of the pieces at their
//! ends, and at exact Newton iterates towards the critical point of the most promising span's
//! piece), and t = RU(A) tried as the bound with the exact Bernstein rule on every span whose
//! control values exceed t (and whose Bézier points, enclosed in f64 intervals, do not all lie
//! at or below the attained value, which bounds the piece below every t tried). All spans at
//! most t: sup g <= t = RU(A) <= RU(sup g), so t is the optimal bound, certified. A value
//! above t at a split point: the next, larger A, with Newton iterates from that point. At most
//! [`ENDGAME_ROUNDS`] rounds. (Where the rule rounds long coefficients up, it keeps each
//! coefficient's leading bits rather than a fixed number below the largest one, so that the
//! small coefficients that decide a piece near a subnormal extremum keep their signs, and a
//! refutation at a piece's end is checked by the exact value there.)
//!
//! The Newton iterates ([`crate::num::sturm::newton_critical`], on the quotient rule's
//! numerator A'W - AW' in integers, each iterate rounded to a dyadic grid) are only points to
//! try; their grid is chosen for the value sought ([`newton_bits`]: near a simple maximiser
//! g(s) falls short of the maximum by ~|g''| d^2 at a distance d, which must stay below the
//! value's ulp), the finest one (2^-1100) when a value comes out at the grid's own error (a
//! maximum at 0). With A that close, RU(A) is RU(sup g) unless sup g is itself a double (a
//! tie: f = 2^d A - t W then touches 0 at the maximiser, a double root). The Bernstein rule
//! decides a tie at a rational point by splitting there (the root of gcd(f, f'), from the
//! integer Sturm sequence), and where its subdivision cannot decide (a tie at an irrational
//! point, or a near-tie whose pieces would have to be shorter than its split budget allows:
//! a value at the split point within 2^-[`NEAR_TIE_BITS`] of the coefficients) Sturm's
//! theorem does ([`sturm_rule`]: the distinct roots of f in (0, 1) counted and isolated
//! exactly, f's sign between them; [`crate::num::sturm`]).
//!
//! # Far ties (an extremum far below the coordinate scale)
//!
//! A curve tangent to an axis (a spline touching y = 0 inside a span), or any extremum much
//! smaller than the coordinate's scale, has a bound the strategy proves to within ~2^-100 of
//! the scale, while the doubles near the extremum are far finer: no double-double value tells
//! them apart, and the stages above would spend their boxes and exact evaluations (0.5-3 ms a
//! side) before the end game decided it anyway, or fail (an exact tangency stayed ~1e-31 below
//! 0). A bound nearly proved, more than two of its ulps above the attained value, with its
//! ulp below 2^-[`FAR_TIE_BITS`] of the scale goes to the end game first (and not again at
//! the end if it fails there).
//!
//! # Limits (bounded work)
//!
//! At most [`MAX_CANDIDATES`] candidates, [`NEWTON_STEPS`] double-double Newton steps, the
//! exact stage only for the best candidate and degree <= [`EXACT_MAX_DEGREE`] (its exact
//! Newton levels only for a value within 2^-96 of t, two exact Newton steps per level of
//! [`ZIV_BITS`]); lowering by the box rules only up to degree [`LOWER_MAX_DEGREE`] (a
//! straddle goes to the exact Bernstein rule up to its own degree limit, and above
//! [`LOWER_MAX_DEGREE`] the strategies refine a side more than an ulp of its bound loose
//! themselves: `bezier`'s local refinement, which `newton` hands such sides to), a lowering proof at most
//! [`MAX_BOXES`] boxes ([`MAX_BOXES_RESCALED`] for a curve the driver rescales),
//! [`MAX_PIECES`] Bézier halvings and [`MAX_EXACT_TRIES`] exact concavity arguments (above
//! [`LOWER_MAX_DEGREE`] a lowering is tried only when a clamped end's value is the largest
//! value seen, where the Bézier rule decides cheaply); no search at all above degree
//! [`SEARCH_MAX_DEGREE`] (only the attained-value rule). The exact Bernstein rule: at most
//! [`MAX_EXACT_SPANS`] spans and [`MAX_EXACT_SPLITS`] subdivisions per span, only spans whose
//! data lie within 2^±[`EXACT_RULE_MAX_EXP`] (`exact_is_cheap`), coefficients rounded up above
//! [`EXACT_RULE_ROUND_BITS`] bits. Exact values with derivatives only on spans whose knots
//! and control values are short rationals (`exact_value_is_cheap`: no knot or value near
//! ±f64::MAX or with a subnormal bit, whose exact quotients have thousands of bits), at most
//! [`MAX_EXACT_EVALS`] per evaluated curve and [`MAX_EXACT_POINTS`] box-end values per lowering
//! proof. The local stage: at most [`LOCAL_MAX_SPANS`] spans and [`LOCAL_PIECES`] pieces. The
//! end game: degree at most [`ENDGAME_MAX_DEGREE`] ([`ENDGAME_MAX_DEGREE_RATIONAL`] for a
//! rational curve), at most [`MAX_EXACT_SPANS`] spans and
//! [`ENDGAME_ROUNDS`] rounds, each rule within [`MAX_EXACT_SPLITS`] splits, then Sturm's
//! theorem on coefficients of at most [`STURM_MAX_BITS`] bits and at most 4,096 bisections.
//! When these are spent the answer is `false` ("not proved") and the bound stays as it is (sound, maybe one ulp or a few above
//! optimal). A heuristic strategy always reports `false`.

use super::driver::{exponent, Rescaling};
use super::{scale_outward, CandidateKind, CoordBox, Enclosure, Extremum};
pub(crate) use crate::num::ffint::dyadic_integers;
use crate::num::ffint::{clamp_span_ints, clamp_span_ints_with, FfInt};
use crate::num::{iv, Ddi, Exact, Scalar};
use crate::spline::bezier::{bernstein_value, de_casteljau_eval, de_casteljau_split, hodograph};
use crate::spline::bspline::{BezierSeg, HSpline};
use crate::spline::curve::NurbsCurve;
use crate::spline::eval::CurveEval;
#[cfg(test)]
use crate::spline::fraction_free::bezier_coefficients_ff;
use crate::spline::fraction_free::bezier_coefficients_fraction_free;
use crate::spline::knots::multiplicity;
use inari::Interval;
use num_bigint::{BigInt, Sign};
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, ToPrimitive, Zero};
use smallvec::SmallVec;
use std::cmp::Ordering;

/// Candidates per side that are examined (in the strategy's order).
pub const MAX_CANDIDATES: usize = 8;
/// Double-double Newton steps per candidate.
pub const NEWTON_STEPS: usize = 4;
/// Highest degree for which the double-double stages (and the lowering) run: one evaluation
/// costs ~(p + 1)^2 corner cuts; above, only the attained-value rule is used.
pub const SEARCH_MAX_DEGREE: usize = 64;
/// Highest degree for which exact rational evaluation is attempted (the rationals of a de
/// Boor triangle grow with the degree).
pub const EXACT_MAX_DEGREE: usize = 6;
/// Highest degree of the end game ([`exact_endgame`]; on integer Bézier rows, no de Boor
/// triangles of rationals: its cost grows like that of the exact Bernstein rule) for a
/// polynomial curve. Measured on random tangencies (y = K (t - r)^2 m(t), up to four knots
/// inserted, exact or rounded data; the generator of the test
/// `random_tangencies_are_sound_and_certified` at degrees 11-31, every side certified), time
/// per enclosure: median 0.7-1.2 ms at degree 11-12 (at most 1.9 ms), 1.3-2.0 ms at 13-16 (at
/// most 3.5 ms), 2.6-3.4 ms at 17-20 (at most 8.3 ms), 4.4-15 ms at 21-30 (at most 62 ms);
/// without the end game 0.2-0.5 ms, not certified. So up to 20.
pub const ENDGAME_MAX_DEGREE: usize = 20;
/// The end game's highest degree for a rational curve: its numerator A'W - AW' has degree
/// 2p - 2 and the products of the weights' rows lengthen every integer, so the Sturm sequences
/// cost far more (one rounded tangency of a Bézier: degree 16 1.6 ms, 24 5 ms, 32 10-13 ms,
/// against 0.3-0.8 ms uncertified).
pub const ENDGAME_MAX_DEGREE_RATIONAL: usize = 12;
/// The same for rational curves: the quotient rule multiplies the denominators of the exact
/// values (a cubic's second derivative reached 10^4 bits and milliseconds per evaluation);
/// conics (the circle's exact-double extrema) stay exact.
pub const EXACT_MAX_DEGREE_RATIONAL: usize = 2;
/// Binary digits (relative to the parameter magnitude) of the dyadic parameters of the exact
/// Ziv levels.
pub const ZIV_BITS: [u32; 3] = [120, 240, 480];
/// Highest degree for which a bound is lowered (the branch-and-bound proof costs up to
/// [`MAX_BOXES`] double-double evaluations per side, which above this degree costs many times
/// the strategy's own run).
pub const LOWER_MAX_DEGREE: usize = 5;
/// How often a side's bound may be lowered by one ulp (after a proof that max <= next_down).
pub const MAX_LOWERINGS: usize = 2;
/// A lowering is tried only when some value seen has an upper end within this many doubles
/// of the bound, or within this many ulps of the coordinate scale (a strategy's tolerance is
/// relative to the scale, so near zero its bound can be many doubles of the value away).
pub const LOWER_WITHIN_ULPS: usize = 8;
/// The same for a curve the driver rescaled (extreme magnitudes): the strategies then work on
/// a rescaled copy, or span by span on Bézier segments whose control points are enclosures,
/// and their attained values lie up to ~20 ulps below their bounds (`range_limits`).
pub const LOWER_WITHIN_ULPS_RESCALED: usize = 32;
/// Parameter boxes per lowering proof (branch and bound over the whole domain).
pub const MAX_BOXES: usize = 64;
/// The same for a curve the driver rescaled (extreme weight ratios and spans next to each
/// other whose box enclosures converge slowly; the cost stays with such curves).
pub const MAX_BOXES_RESCALED: usize = 256;
/// Spans searched in their Bézier form per side ([`bezier_search`]).
const BEZIER_SEARCH_SPANS: usize = 2;
/// Subintervals of a candidate whose ends are f64 starting points of [`bezier_search`].
const SEARCH_SAMPLES: usize = 16;
/// Rounds of narrower samples around the best one in [`bezier_search`].
const ZOOM_ROUNDS: usize = 4;
/// Bézier halvings per lowering proof ([`bezier_rule`], towards clamped domain ends).
pub const MAX_PIECES: usize = 96;
/// Halving depth of the Bézier rule at a clamped domain end.
const BEZIER_DEPTH: u32 = 48;
/// Halving depth of the Bézier rule elsewhere (an interior maximum is left to the box rules,
/// whose mean value and concavity forms converge faster there).
const BEZIER_DEPTH_INTERIOR: u32 = 6;
/// Bisection depth per span in a lowering proof.
const MAX_DEPTH: u32 = 64;
/// Exact concavity arguments per lowering proof.
pub const MAX_EXACT_TRIES: usize = 4;
/// Exact values (with derivatives, at f64 or dyadic parameters: [`Evals::exact_in`]) per
/// evaluated curve, i.e. per coordinate (both sides, every round): a near-tie on a rational
/// curve with extreme weights ran 96 of them at ~0.3 ms each through the exact stage's and the
/// concavity rule's Newton levels.
pub const MAX_EXACT_EVALS: usize = 24;

/// Exact point values per lowering proof (the end of a monotone box whose double-double value
/// holds the target): each costs a de Boor triangle in big rationals, milliseconds with knots
/// near ±f64::MAX next to subnormal ones (2,000-bit numbers), where 256 boxes took 0.4 s.
pub const MAX_EXACT_POINTS: usize = 16;

/// What a lowering proof may still spend in exact arithmetic: concavity arguments
/// ([`MAX_EXACT_TRIES`]) and point values ([`MAX_EXACT_POINTS`]).
#[derive(Default)]
struct ExactBudget {
    tries: usize,
    points: usize,
}

impl ExactBudget {
    /// No exact arithmetic at all.
    const SPENT: ExactBudget = ExactBudget {
        tries: MAX_EXACT_TRIES,
        points: MAX_EXACT_POINTS,
    };
}

/// Candidates that go to the exact stage.
const EXACT_CANDIDATES: usize = 1;

/// Set `optimal_lo` / `optimal_hi` of every coordinate of a result of `c` (see the module
/// docs), lowering a bound where a proof shows that a smaller double is a bound too. A
/// heuristic result (`verified == false`) gets `false` everywhere and is left unchanged.
pub fn certify(c: &NurbsCurve, e: &mut Enclosure) {
    certify_with(c, e, Rescaling::of(c).as_ref());
}

/// [`certify`] with the driver's rescaling of `c` (`Rescaling::of(c)`, computed once by the
/// driver): the proofs run on the rescaled curve(s) (module docs, "Extreme magnitudes").
pub(crate) fn certify_with(c: &NurbsCurve, e: &mut Enclosure, r: Option<&Rescaling>) {
    certify_with_first(c, e, r, true);
}

/// [`certify_with`], with the first rounds decided before the evaluators and scaled copies
/// are built (`first`, the default) or inside [`certify_side`] only (the tests' reference).
fn certify_with_first(c: &NurbsCurve, e: &mut Enclosure, r: Option<&Rescaling>, first: bool) {
    let verified = e.verified;
    if !verified {
        for cb in &mut e.coords {
            cb.optimal_lo = false;
            cb.optimal_hi = false;
        }
        return;
    }
    // the exact values at clamped ends and knots of multiplicity >= p: (min, max) per coordinate
    let mut exact: SmallVec<[usize; 16]> = SmallVec::new();
    knot_points(c, |i| exact.push(i));
    let exact_range = |j: usize| {
        exact
            .iter()
            .map(|&i| c.control_point(i)[j])
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            })
    };
    let Some(r) = r else {
        // moderate magnitudes (the common case): the curve itself. Each side's first round
        // from the exact values at knots and ends and the scale ([`first_round`]); the
        // evaluators only for the sides it leaves open.
        let mut ev: Option<Evals> = None;
        for (j, cb) in e.coords.iter_mut().enumerate() {
            let (xlo, xhi) = exact_range(j);
            let window = (c.coord_scale(j), LOWER_WITHIN_ULPS);
            let quick_hi =
                first_round(cb.hi, cb.inner_hi, cb.witness_hi, xhi, window).filter(|_| first);
            let quick_lo =
                first_round(-cb.lo, -cb.inner_lo, -cb.witness_lo, -xlo, window).filter(|_| first);
            for (max_side, q) in [(true, quick_hi), (false, quick_lo)] {
                let ok = match q {
                    Some(ok) => ok,
                    None => {
                        let mut cv = Curves {
                            dn: ev.get_or_insert_with(|| Evals::new(c, c, 0)),
                            up: None,
                        };
                        certify_side(&mut cv, j, cb, max_side, &Scaling::NONE)
                    }
                };
                if max_side {
                    cb.optimal_hi = ok;
                } else {
                    cb.optimal_lo = ok;
                }
            }
        }
        return;
    };
    for (j, cb) in e.coords.iter_mut().enumerate() {
        // The first rule (an attained value equal to the bound, or a strict witness at or
        // above next_down(bound)) needs no curve: a side it decides builds no scaled copies.
        cb.optimal_hi = attained_rule(cb.hi, cb.inner_hi, cb.witness_hi);
        cb.optimal_lo = attained_rule(-cb.lo, -cb.inner_lo, -cb.witness_lo);
        // (and, before any scaled copy is built, what round 0 of `certify_side` decides from
        // the curve's own data: [`first_round`] on twice the curve's scale)
        let (xlo, xhi) = exact_range(j);
        let window = (2.0 * c.coord_scale(j), LOWER_WITHIN_ULPS_RESCALED);
        let mut decided = [cb.optimal_hi, cb.optimal_lo];
        for (max_side, (bound, inner, witness, x)) in [
            (true, (cb.hi, cb.inner_hi, cb.witness_hi, xhi)),
            (false, (-cb.lo, -cb.inner_lo, -cb.witness_lo, -xlo)),
        ] {
            let k = usize::from(!max_side);
            if decided[k] || !first {
                continue;
            }
            if let Some(ok) = first_round(bound, inner, witness, x, window) {
                decided[k] = true;
                if max_side {
                    cb.optimal_hi = ok;
                } else {
                    cb.optimal_lo = ok;
                }
            }
        }
        let open = |max_side: bool| !decided[usize::from(!max_side)];
        // one exponent per side (the same for both sides in most cases: one pair of curves)
        let e_m = exponent(c.coord_scale(j));
        let s_hi = coord_exponent(e_m, cb.hi, cb.inner_hi);
        let s_lo = coord_exponent(e_m, cb.lo, cb.inner_lo);
        let sides: &[(i32, &[bool])] = match (open(true), open(false)) {
            (false, false) => &[],
            (true, false) => &[(s_hi, &[true])],
            (false, true) => &[(s_lo, &[false])],
            (true, true) if s_hi == s_lo => &[(s_hi, &[true, false])],
            (true, true) => &[(s_hi, &[true]), (s_lo, &[false])],
        };
        for &(s, which) in sides {
            // the curve with coordinate j scaled down, rounded down, and a copy rounded up if
            // some value rounded; the original curve if scaling fails (not expected)
            let dn = r.apply_coord(c, j, s, false);
            let (s, knot_exp, cdn, rounded) = match dn {
                Some((cs, rounded)) => (s, r.knot_exp, cs, rounded),
                None => (0, 0, c.clone(), false),
            };
            let cup = rounded
                .then(|| r.apply_coord(c, j, s, true))
                .flatten()
                .map(|x| x.0);
            if rounded && cup.is_none() {
                for &max_side in which {
                    if max_side {
                        cb.optimal_hi = false;
                    } else {
                        cb.optimal_lo = false;
                    }
                }
                continue;
            }
            let mut ev_dn = Evals::new(&cdn, c, s);
            let mut ev_up = cup.as_ref().map(|cu| Evals::new(cu, c, s));
            let sc = Scaling {
                coord_exp: s,
                knot_exp,
                within: LOWER_WITHIN_ULPS_RESCALED,
                boxes: MAX_BOXES_RESCALED,
                exact_first: true,
                local: true,
            };
            for &max_side in which {
                let mut cv = Curves {
                    dn: &mut ev_dn,
                    up: ev_up.as_mut(),
                };
                let ok = certify_side(&mut cv, j, cb, max_side, &sc);
                if max_side {
                    cb.optimal_hi = ok;
                } else {
                    cb.optimal_lo = ok;
                }
            }
        }
    }
}

/// Coordinates whose largest control value lies within 2^±COORD_WINDOW are not scaled.
const COORD_WINDOW: i32 = super::driver::COORD_WINDOW;
/// The largest scaled control value of a coordinate is at most 2^COORD_HEADROOM: room for
/// the weights (below 2^30 after the driver's scaling), the sums of the corner cuts and the
/// double-double error terms, which must not overflow.
const COORD_HEADROOM: i32 = 900;

/// The exponent s of the power of two 2^-s that coordinate j is multiplied by for one side's
/// certificate: 0 for a coordinate of moderate magnitude (largest control value 2^`e_m`
/// within 2^±[`COORD_WINDOW`]) with a bound of moderate magnitude; otherwise the bound's (or
/// the attained value's, whichever is larger) binary exponent, so that the values near the extremum are near 1 and their
/// double-double enclosures ~2^-100 relative narrow (which values near f64::MAX, with
/// overflowing error terms, or subnormal values, with no bits below 2^-1074, are not), but at
/// least e_m - [`COORD_HEADROOM`] (no overflow). Any s is sound (module docs); this one only
/// decides what can be resolved.
fn coord_exponent(e_m: i32, bound: f64, inner: f64) -> i32 {
    let mag = |x: f64| if x.is_finite() { x.abs() } else { 0.0 };
    let m = mag(bound).max(mag(inner));
    let e_b = if m > 0.0 { exponent(m) } else { e_m };
    if e_m.abs() <= COORD_WINDOW && e_b.abs() <= COORD_WINDOW {
        return 0;
    }
    e_b.max(e_m - COORD_HEADROOM)
}

/// How the evaluated curve relates to the enclosed one ([`certify_with`]): coordinate j
/// multiplied by 2^-`coord_exp`, knots (parameters) by 2^-`knot_exp`; `within` is the
/// lowering window in ulps ([`LOWER_WITHIN_ULPS`], [`LOWER_WITHIN_ULPS_RESCALED`]), `boxes`
/// the box budget of a lowering proof ([`MAX_BOXES`], [`MAX_BOXES_RESCALED`]).
struct Scaling {
    coord_exp: i32,
    knot_exp: i32,
    within: usize,
    boxes: usize,
    /// whether the first lowering proof has the exact rules already: on a rescaled curve
    /// (extreme magnitudes) the double-double rules alone mostly spend their boxes where an
    /// exact concavity argument decides at once, and a second run with them repeated the
    /// whole branch and bound (on the range-limits curves whose certificate costs most: 11%
    /// fewer certification instructions)
    exact_first: bool,
    /// whether a bound many doubles of its own size above the attained value is searched
    /// again span by span in the local parameter first ([`local_stage`]; rescaled curves)
    local: bool,
}

impl Scaling {
    const NONE: Scaling = Scaling {
        coord_exp: 0,
        knot_exp: 0,
        within: LOWER_WITHIN_ULPS,
        boxes: MAX_BOXES,
        exact_first: false,
        local: false,
    };
}

/// The evaluators of one coordinate's certificate: `dn` of the curve with coordinate j
/// rounded down where it rounded, `up` rounded up (`None`: nothing rounded, `dn` is exact).
/// C_dn <= C_j <= C_up at every u (module docs), so a value above t is shown on the curve
/// below g = sign * C_j, and g <= t on the curve above it.
struct Curves<'e, 'a> {
    dn: &'e mut Evals<'a>,
    up: Option<&'e mut Evals<'a>>,
}

impl<'a> Curves<'_, 'a> {
    /// The curve whose g is <= the enclosed curve's g everywhere (for "g(u) > t" proofs).
    fn below(&mut self, sign: f64) -> &mut Evals<'a> {
        match (&mut self.up, sign > 0.0) {
            (Some(up), false) => up,
            _ => &mut *self.dn,
        }
    }

    /// The curve whose g is >= the enclosed curve's g everywhere (for "g <= t" proofs).
    fn above(&mut self, sign: f64) -> &mut Evals<'a> {
        match (&mut self.up, sign > 0.0) {
            (Some(up), true) => up,
            _ => &mut *self.dn,
        }
    }
}

/// Lazily built evaluators of the curve (double-double with two derivative levels, exact).
struct Evals<'a> {
    c: &'a NurbsCurve,
    /// the enclosed curve itself, whose coordinate j is 2^s times `c`'s (exactly, or between
    /// two copies rounded down and up): its control points are the exact values at clamped
    /// ends and knots of multiplicity >= p, in the curve's own units
    orig: &'a NurbsCurve,
    s: i32,
    iv: Option<CurveEval<Interval>>,
    ddi: Option<CurveEval<Ddi>>,
    /// the double-double Bézier segments of the spans met so far (both sides, every round
    /// and every lowering proof of the curve use the same span's segment)
    ddi_segs: Vec<(usize, BezierSeg<Ddi>)>,
    /// f64 evaluation with two derivative levels, only to choose Newton points
    approx: Option<CurveEval<f64>>,
    /// the homogeneous curve alone in Ddi (no derivative control points: most certificates
    /// need one value, and the derivative levels cost several times that value)
    ddi0: Option<HSpline<Ddi>>,
    buf: Vec<Ddi>,
    exact: Option<CurveEval<Exact>>,
    /// exact values computed so far ([`MAX_EXACT_EVALS`])
    exact_evals: usize,
}

impl<'a> Evals<'a> {
    fn new(c: &'a NurbsCurve, orig: &'a NurbsCurve, s: i32) -> Self {
        Evals {
            c,
            orig,
            s,
            iv: None,
            ddi: None,
            ddi_segs: Vec::new(),
            approx: None,
            ddi0: None,
            buf: Vec::new(),
            exact: None,
            exact_evals: 0,
        }
    }

    /// g(u) = sign * C_j(u) at the f64 parameter u of the domain, in Ddi: de Boor corner
    /// cutting (NURBS Book A5.1 on the homogeneous curve, thesis eq. 3.7) of the rows of
    /// coordinate j and the weight only, then C_j = A_j / w. The same kernel and the same
    /// enclosure property as the full evaluation ([`CurveEval::derivs`] with k = 0).
    fn ddi_value(&mut self, j: usize, sign: f64, u: f64) -> Option<Ddi> {
        let c = self.c;
        let (a, b) = c.domain();
        if !(a <= u && u <= b) {
            return None;
        }
        let h = self.ddi0.get_or_insert_with(|| HSpline::from_curve(c));
        let rows = [j, h.dim];
        let rows = &rows[..1 + h.rational as usize];
        let v = h.eval_span_rows(h.span(u), &Ddi::from_f64(u), rows, &mut self.buf);
        let x = if h.rational { v[0] / v[1] } else { v[0] };
        Some(x.signed(sign))
    }

    /// The Bézier segment of span k in double-double (Boehm insertion on the homogeneous curve,
    /// [`HSpline::bezier_segment`]), computed once per span and kept.
    fn ddi_segment(&mut self, k: usize) -> BezierSeg<Ddi> {
        if let Some((_, seg)) = self.ddi_segs.iter().find(|x| x.0 == k) {
            return seg.clone();
        }
        let c = self.c;
        let h = self.ddi0.get_or_insert_with(|| HSpline::from_curve(c));
        // (running error bounds: near ties need every bit the double double has; end values
        // that are exactly doubles made exact, `snap_exact_ends`)
        let mut seg = h.bezier_segment_tight(k);
        crate::spline::fraction_free::snap_exact_ends(c, k, &mut seg.pts);
        self.ddi_segs.push((k, seg.clone()));
        seg
    }

    /// g, g', g'' (k = 2) or g alone (k = 0) at the f64 parameter u, g = sign * C_j, in plain
    /// f64 (the same kernels, rounded: only to choose Newton points, whose values are then
    /// enclosed; near a simple maximiser an error of a few ulps in u changes g by a second
    /// order amount, far below the double-double enclosures' width).
    fn approx(&mut self, j: usize, sign: f64, u: f64, k: usize) -> Option<Vec<f64>> {
        let c = self.c;
        let (a, b) = c.domain();
        if !(a <= u && u <= b) {
            return None;
        }
        let e = self.approx.get_or_insert_with(|| CurveEval::new(c, 2));
        let v = e.coord_derivs_in_span(e.span(u), &u, k, j);
        Some(v.into_iter().map(|d| sign * d).collect())
    }

    /// g, g', g'' (k = 2) or g (k = 0) exactly at the rational parameter u of the domain, in
    /// the span the curve's own evaluation uses (`None` if u is outside or cannot be placed).
    fn exact(&mut self, j: usize, sign: f64, u: &Exact, k: usize) -> Option<Vec<Exact>> {
        let c = self.c;
        let (a, b) = c.domain();
        if u.cmp_f64(a)?.is_lt() || u.cmp_f64(b)?.is_gt() {
            return None;
        }
        let ua = u.to_f64().clamp(a, b);
        let kn = c.knots();
        // the span of u by the convention of `find_span` (u_k <= u < u_{k+1}, the last span
        // for u = b): find it from an f64 near u, then check it exactly
        let last = c.find_span(b);
        let mut span = c.find_span(ua);
        for _ in 0..4 {
            if span > c.degree() && u.cmp_f64(kn[span])?.is_lt() {
                span -= 1;
            } else if span < last && !u.cmp_f64(kn[span + 1])?.is_lt() {
                span += 1;
            } else {
                break;
            }
        }
        let fits = !u.cmp_f64(kn[span])?.is_lt()
            && (u.cmp_f64(kn[span + 1])?.is_lt() || (u.cmp_f64(b)?.is_eq() && span == last));
        if !fits || kn[span] >= kn[span + 1] {
            return None;
        }
        self.exact_in(span, j, sign, u, k)
    }

    /// g, g', g'' (k = 2) or g (k = 0) of the polynomial (or rational) piece of span `span`,
    /// exactly at the rational u (which the caller keeps in the closed span).
    fn exact_in(
        &mut self,
        span: usize,
        j: usize,
        sign: f64,
        u: &Exact,
        k: usize,
    ) -> Option<Vec<Exact>> {
        if !self.exact_possible()
            || !exact_value_is_cheap(self.c, span, j, u)
            || self.exact_evals >= MAX_EXACT_EVALS
        {
            return None;
        }
        self.exact_evals += 1;
        let c = self.c;
        let e = self.exact.get_or_insert_with(|| CurveEval::new(c, 2));
        let v = e.coord_derivs_in_span(span, u, k, j);
        Some(
            v.into_iter()
                .map(|d| if sign < 0.0 { -d } else { d })
                .collect(),
        )
    }

    /// Whether the piece of the span ending at the interior knot u has, at u, a value above t
    /// (in Ddi): that value is the left limit of the curve at u, approached by curve values
    /// (the piece is continuous on its closed span), so some u' < u has g(u') > t. This
    /// certifies a bound reached only as the limit at a jump (a knot of multiplicity p + 1),
    /// which no curve value attains.
    fn left_limit_above(&mut self, j: usize, sign: f64, u: f64, t: f64) -> bool {
        let kn = self.c.knots();
        let (a, b) = self.c.domain();
        // (at the domain end b the left piece's value is the curve's own, looked at anyway)
        if !(a < u && u < b) {
            return false;
        }
        // only at an interior jump (elsewhere the left limit is the curve's value, looked at anyway)
        if multiplicity(kn, u) <= self.c.degree() {
            return false;
        }
        // the span k with u_k < u_{k+1} = u
        let Some(k) = (self.c.degree()..kn.len() - 1).find(|&k| kn[k] < u && kn[k + 1] == u) else {
            return false;
        };
        self.ddi_in(k, j, sign, Ddi::exact(u), 0)[0].is_above(t)
    }

    /// Whether exact evaluation is tried for this curve at all ([`EXACT_MAX_DEGREE`],
    /// [`EXACT_MAX_DEGREE_RATIONAL`]).
    fn exact_possible(&self) -> bool {
        let max_degree = if self.c.is_rational() {
            EXACT_MAX_DEGREE_RATIONAL
        } else {
            EXACT_MAX_DEGREE
        };
        self.c.degree() <= max_degree
    }

    /// Whether [`exact_bernstein_rule`] is tried for this curve: degree at most
    /// [`EXACT_MAX_DEGREE`], rational or not (the rule works on the homogeneous
    /// coefficients, with no quotient rule, so a rational curve costs what a polynomial one of
    /// one more row does).
    fn exact_rule_possible(&self) -> bool {
        self.c.degree() <= EXACT_MAX_DEGREE
    }

    /// C_j(u) exactly when u is a clamped end of the domain: the end control point
    /// ([`NurbsCurve::clamped_ends`]; the last span's piece there is the curve's value). In
    /// the enclosed curve's own units (its control point, `orig`); u is a parameter of `c`
    /// (the same knot indices, the same multiplicities).
    fn clamped_end_value(&self, j: usize, u: f64) -> Option<f64> {
        let (a, b) = self.c.domain();
        let cl = self.c.clamped_ends();
        if u == a && cl[0] {
            Some(self.orig.control_point(0)[j])
        } else if u == b && cl[1] {
            Some(self.orig.control_point(self.orig.num_points() - 1)[j])
        } else {
            None
        }
    }

    /// A double <= v 2^-s (v in the curve's own units, e.g. an exact value of
    /// [`Evals::knot_value`]): a lower bound of that value on the evaluated curve's scale.
    fn scaled_below(&self, v: f64) -> f64 {
        scale_outward(v, -self.s, false)
    }

    /// The value of the piece of span k at an end u of the span, exactly, when u is a knot of
    /// multiplicity >= p (or a clamped domain end), in the curve's own units (the control point
    /// of `orig`, as [`Evals::clamped_end_value`]): there a single basis function is nonzero
    /// (NURBS Book P2.1, P2.2 applied on the span; eq. 2.5 with m >= p), so the piece's value
    /// is a control point, also for a rational curve (R_i = w_i N_i / sum w_l N_l = 1 for
    /// that i). At the span's start u_k it is P_{k-p} (the value C(u_k), as for a clamped
    /// start, P_0); at its end u_{k+1} it is P_k (the left limit at u_{k+1}, equal to C(u_{k+1})
    /// unless u_{k+1} has multiplicity p + 1, a jump; as for a clamped end, P_n).
    fn knot_value(&self, j: usize, k: usize, u: f64) -> Option<f64> {
        let c = self.c;
        let (kn, p) = (c.knots(), c.degree());
        let i = if u == kn[k] {
            k - p
        } else if u == kn[k + 1] {
            k
        } else {
            return None;
        };
        (multiplicity(kn, u) >= p).then(|| self.orig.control_point(i)[j])
    }

    /// C_j(u) exactly when u is a clamped domain end or a knot of multiplicity >= p (the
    /// value of the span `find_span` assigns to u, [`Evals::knot_value`]).
    fn exact_value(&self, j: usize, u: f64) -> Option<f64> {
        let c = self.c;
        let (a, b) = c.domain();
        if !(a <= u && u <= b) {
            return None;
        }
        self.clamped_end_value(j, u)
            .or_else(|| self.knot_value(j, c.find_span(u), u))
    }

    /// The largest of sign * v over the exact values v of every span's piece at its ends that
    /// are knots of multiplicity >= p ([`Evals::knot_value`]): curve values, or left limits
    /// of curve values at a jump; -inf if there are none ([`knot_points`]).
    fn max_knot_value(&self, j: usize, sign: f64) -> f64 {
        let mut best = f64::NEG_INFINITY;
        knot_points(self.c, |i| {
            best = best.max(sign * self.orig.control_point(i)[j]);
        });
        best
    }

    /// g, g', g'' (k = 2) of the piece of span `span` over the interval `u` inside the closed
    /// span, in f64 interval arithmetic (inari: outward rounding): the cheap first tier of the
    /// branch and bound.
    fn iv_in(&mut self, span: usize, j: usize, sign: f64, u: Interval, k: usize) -> Vec<Interval> {
        let c = self.c;
        let e = self.iv.get_or_insert_with(|| CurveEval::new(c, 2));
        e.coord_derivs_in_span(span, &u, k, j)
            .into_iter()
            .map(|d| if sign < 0.0 { -d } else { d })
            .collect()
    }

    /// g, g', g'' (k = 2; g alone for k = 0) of the piece of span `span` over the parameter
    /// set `u` (a point or an interval inside the closed span), in Ddi: rigorous enclosures.
    fn ddi_in(&mut self, span: usize, j: usize, sign: f64, u: Ddi, k: usize) -> Vec<Ddi> {
        let c = self.c;
        let e = self.ddi.get_or_insert_with(|| CurveEval::new(c, 2));
        e.coord_derivs_in_span(span, &u, k, j)
            .into_iter()
            .map(|d| d.signed(sign))
            .collect()
    }
}

/// Calls `f(i)` for the index i of every control point that is the value of a span's piece at
/// one of its ends that is a knot of multiplicity >= p ([`Evals::knot_value`]; the clamped
/// ends among them).
///
/// One pass over the runs of equal knots (O(m), no search): a run kn[s..e] of the value u
/// with e - s >= p ends the span k = s - 1 (kn[s - 1] < u = kn[s], the piece's value P_k)
/// and starts the span k = e - 1 (kn[e - 1] = u < kn[e], the value P_{k-p}), each where
/// p <= k <= n: exactly the pairs (span, end) of `knot_value` with multiplicity >= p.
pub(crate) fn knot_points(c: &NurbsCurve, mut f: impl FnMut(usize)) {
    let (kn, p, n) = (c.knots(), c.degree(), c.num_points() - 1);
    let mut s = 0;
    while s < kn.len() {
        let mut e = s + 1;
        while e < kn.len() && kn[e] == kn[s] {
            e += 1;
        }
        if e - s >= p {
            // (the span ending at u: k = s - 1)
            if s > p && s - 1 <= n {
                f(s - 1);
            }
            // (the span starting at u: k = e - 1, and kn[e] > u exists as k <= n)
            if e > p && e - 1 <= n {
                f(e - 1 - p);
            }
        }
        s = e;
    }
}

/// The first round of [`certify_side`], decided per coordinate from O(m + n) data before any
/// evaluator or scaled copy is built: `bound`, `inner`, `witness` of the side (sign-adjusted),
/// `exact` the largest sign-adjusted exact value of the curve itself at clamped ends and knots
/// of multiplicity >= p ([`knot_points`]), `scale` and `within` the refusal's scale and window.
/// `None` sends the side to `certify_side`. Round 0 checks, in this order: a finite bound;
/// rules 1 and 1b (`attained_rule`); rule 1c (`exact` above t = next_down(bound)); rule 1d, the
/// left limit at a jump knot u, which never holds once 1c has failed: the left piece's value
/// at u is P_k (u has multiplicity > p >= p, [`Evals::knot_value`]), one of the exact values,
/// and its double-double enclosure lies above t only if P_k > t; then the refusal of a loose
/// bound (`far_below` with the attained and exact values).
///
/// * A curve of moderate magnitudes (its own units, `scale` its coordinate scale, window
///   [`LOWER_WITHIN_ULPS`]): `Some` exactly where round 0 decides, with the same answer; after
///   a refusal nothing else runs (the local stage is for rescaled curves only, and the end
///   game refuses the same bound: the same test with `inner` alone, on the same scale).
/// * A rescaled curve (`scale` twice the curve's own, window [`LOWER_WITHIN_ULPS_RESCALED`]):
///   the answers are sound on their own (a bound that is not finite is not certified, an exact
///   curve value above next_down(bound) proves bound = RU(max)), and a refusal here is one of
///   `certify_side` as well: its scale, the scaled copy's scale scaled back and rounded up, is
///   below twice the curve's (the copy's largest coordinate is near 1, rounded by at most an
///   ulp), so its refusal test holds, the local stage (which needs a bound within that test)
///   does not run, and the end game refuses the bound on the curve's own scale.
#[inline]
fn first_round(
    bound: f64,
    inner: f64,
    witness: f64,
    exact: f64,
    window: (f64, usize),
) -> Option<bool> {
    match first_round_flags(bound, inner, witness, exact, window) {
        (true, _) => Some(true),
        (_, true) => None,
        _ => Some(false),
    }
}

/// [`first_round`] as two flags, (certified, open): `Some(true)` is (true, false), `None`
/// (false, true), `Some(false)` (false, false). Computed without branches on the data (every
/// rule evaluated, combined by `&` and `|`; next_down by [`crate::num::next_down`]): on random
/// curves whether a side is attained, and the sign of its bound, are coin tosses, and the
/// mispredicted jumps of the short-circuit form cost more than the `hull` lane's whole box.
/// Where the bound is not finite both flags are false whatever the other rules give (they are
/// masked by `finite`), as the first rule's `Some(false)`.
#[inline]
pub(crate) fn first_round_flags(
    bound: f64,
    inner: f64,
    witness: f64,
    exact: f64,
    (scale, within): (f64, usize),
) -> (bool, bool) {
    let finite = bound.is_finite();
    let nd = crate::num::next_down(bound);
    // rules 1, 1b (`attained_rule`) and 1c
    let attained = (inner == bound) | (witness >= nd) | (exact > nd);
    let far = far_below(bound, inner.max(exact), scale, within);
    (finite & attained, finite & !attained & !far)
}

/// The certificate's cheap part for one side, sign-adjusted (the strategy proved max g <=
/// `bound`, that g reaches a value >= `inner` and one > `witness`; `exact` is the largest
/// exact value of g at a knot of multiplicity >= p that the caller knows, from
/// [`knot_points`], or -inf; `scale` is the coordinate scale): `Some(true)` by the first rule
/// of the module docs, `Some(false)` where [`certify_side`] answers `false` at once (the
/// attained values more than [`LOWER_WITHIN_ULPS`] ulps of the scale below the bound: no
/// search, no lowering), `None` where the full certification must decide: [`first_round`]
/// (the `tight` lane passes -inf: its clamped ends and span ends are among its attained values
/// already, and a side that an interior knot's exact value would decide is left to the full
/// certification; the `hull` lane passes the control values at such knots, which the curve
/// passes through).
#[cfg(test)]
pub(crate) fn quick(bound: f64, inner: f64, witness: f64, exact: f64, scale: f64) -> Option<bool> {
    first_round(bound, inner, witness, exact, (scale, LOWER_WITHIN_ULPS))
}

/// [`quick`] as the flags of [`first_round_flags`] (certified, open), without branches on the
/// data: the lanes' form.
#[inline]
pub(crate) fn quick_flags(
    bound: f64,
    inner: f64,
    witness: f64,
    exact: f64,
    scale: f64,
) -> (bool, bool) {
    first_round_flags(bound, inner, witness, exact, (scale, LOWER_WITHIN_ULPS))
}

/// The first rule: an attained value equal to the bound, or a strict witness at or above
/// next_down(bound) (the curve exceeds it), proves bound = RU(max).
#[inline]
fn attained_rule(bound: f64, inner: f64, witness: f64) -> bool {
    inner == bound || witness >= bound.next_down()
}

/// Whether the attained value is more than [`LOWER_WITHIN_ULPS`] ulps of the scale
/// (max(|bound|, `scale`)) below the bound: a loose bound, which the search stages do not try
/// to complete.
#[inline]
pub(crate) fn far_below(bound: f64, inner: f64, scale: f64, within: usize) -> bool {
    bound - inner > within as f64 * crate::num::ulp(bound.abs().max(scale))
}

/// The certificate of one side (`max_side`: hi, as the maximum of g = C_j; otherwise lo, as the
/// maximum of g = -C_j), lowering the bound where [`prove_at_most`] allows it.
///
/// `cv` evaluates the curve with coordinate j multiplied by 2^-s (s = `sc.coord_exp`) and its
/// parameters by 2^-`sc.knot_exp` (module docs, "Extreme magnitudes"; s = 0 and no
/// reparametrisation for a curve of moderate magnitudes); bounds, attained values and
/// witnesses stay in the curve's own units, the strategy's candidates are mapped to the
/// scaled parameters (rounded outward; they only say where to look). A proof that the scaled
/// g (of the curve below it, [`Curves::below`]) exceeds up(t) >= t 2^-s (t 2^-s rounded up)
/// shows g > t; a proof that the scaled g (of the curve above it) is <= dn(t') <= t' 2^-s
/// (rounded down) shows g <= t' ([`scale_outward`]; identities for s = 0).
fn certify_side(
    cv: &mut Curves,
    j: usize,
    cb: &mut CoordBox,
    max_side: bool,
    sc: &Scaling,
) -> bool {
    let sign = if max_side { 1.0 } else { -1.0 };
    let s = sc.coord_exp;
    let up = |x: f64| scale_outward(x, -s, true);
    let dn = |x: f64| scale_outward(x, -s, false);
    // (a scaled value seen, back in the curve's units: only to choose lowering targets)
    let back = |x: f64| scale_outward(x, s, true);
    let (mut bound, mut inner, mut witness) = if max_side {
        (cb.hi, cb.inner_hi, cb.witness_hi)
    } else {
        (-cb.lo, -cb.inner_lo, -cb.witness_lo)
    };
    // The exact values at clamped ends and at knots of multiplicity >= p (control points of
    // the curve itself, compared in its own units), and the coordinate scale: properties of
    // the curve, the same in every round.
    // (a clamped end is a run of p equal knots at the domain's end: `max_knot_value` counts it)
    let (end_value, scale) = {
        let ev = cv.below(sign);
        (ev.max_knot_value(j, sign), back(ev.c.coord_scale(j)))
    };
    let all: &[Extremum] = if max_side { &cb.argmax } else { &cb.argmin };
    let mut cands: Vec<Extremum> = all[..all.len().min(MAX_CANDIDATES)]
        .iter()
        .map(|x| Extremum {
            u_lo: scale_outward(x.u_lo, -sc.knot_exp, false),
            u_hi: scale_outward(x.u_hi, -sc.knot_exp, true),
            ..*x
        })
        .collect();
    let mut local_done = false;
    // (0. on a rescaled curve, a bound many doubles of its own size above the attained value,
    // within the strategy's tolerance of a scale near f64::MAX: the spans searched again in
    // their local parameter on the copy scaled for this side, `local_stage`)
    // (only where the strategy's gap is within `within` ulps of the scale, as for the search
    // stages below: a loose bound such as the control hull's stays as it is)
    if sc.local
        && bound.is_finite()
        && far_below(bound, inner, 0.0, LOWER_WITHIN_ULPS)
        && !far_below(
            bound,
            inner,
            back(cv.below(sign).c.coord_scale(j)),
            sc.within,
        )
    {
        if let Some(r) = local_stage(cv, j, sign, dn(inner)) {
            local_done = true;
            // (bounds of the copy above g, rounded up; values of the copy below g, rounded down)
            bound = bound.min(scale_outward(r.upper, s, true));
            inner = inner.max(scale_outward(r.attained, s, false));
            witness = witness.max(scale_outward(r.witness, s, false));
            let found: Vec<Extremum> = r.cands.into_iter().take(MAX_CANDIDATES).collect();
            cands.splice(0..0, found);
            cands.truncate(MAX_CANDIDATES);
            if max_side {
                cb.inner_hi = cb.inner_hi.max(inner);
                cb.witness_hi = cb.witness_hi.max(witness);
            } else {
                cb.inner_lo = cb.inner_lo.min(-inner);
                cb.witness_lo = cb.witness_lo.min(-witness);
            }
        }
    }
    let cands = &cands[..];
    let within = sc.within;
    let mut proved = false;
    // the double-double value of the curve below g with the largest centre seen so far, in
    // its scaled units (`DdiOutcome::top`)
    let mut top_seen: Option<Ddi> = None;
    let mut endgame_tried = false;
    for round in 0..=MAX_LOWERINGS {
        if !bound.is_finite() {
            break;
        }
        // 1. an attained value equal to the bound; 2. a double-double value above
        // next_down(bound)
        let t = bound.next_down();
        // (1b. the strategy's strict witness: g(u) > witness >= t for some u)
        if attained_rule(bound, inner, witness) {
            proved = true;
            break;
        }
        // (1c. a clamped end's value, exactly the end control point, above t: after a
        // lowering the end value is often the new bound's witness)
        // (and the same for the values at knots of multiplicity >= p, control points too)
        if end_value > t {
            proved = true;
            break;
        }
        // A far tie: a bound the strategy nearly proved (within its tolerance of the scale)
        // but not attained, whose doubles are far finer than the coordinate scale (an
        // extremum far smaller than the scale: a curve tangent to an axis, a maximum near 0):
        // no double-double value of the curve (~2^-100 of the scale) tells them apart, so
        // the stages below could only spend their boxes and exact evaluations before the end
        // game decided it anyway. The end game first.
        if round == 0
            && !far_below(bound, inner.max(end_value), scale, within)
            && far_below(bound, inner, 0.0, 2)
            && crate::num::ulp(bound.abs()) < scale * 2f64.powi(-FAR_TIE_BITS)
        {
            endgame_tried = true;
            if let Some(t) = exact_endgame(cv.dn.orig, j, sign, bound, inner) {
                bound = t;
                proved = true;
                break;
            }
        }
        let ev = cv.below(sign);
        // The search stages only try to complete what the strategy nearly proved: when its
        // own attained value is more than LOWER_WITHIN_ULPS ulps of the coordinate scale below
        // the bound (a loose bound such as the control hull's), the answer is `false` at once.
        // This keeps the certificate's cost a small part of a loose strategy's (cheap) run; a
        // tight strategy's gap is within its tolerance, about an ulp of the scale.
        // (1d. a bound reached only as the limit at a jump: the left piece's value there)
        if cands
            .iter()
            .any(|x| x.u_lo == x.u_hi && ev.left_limit_above(j, sign, x.u_lo, up(t)))
        {
            proved = true;
            break;
        }
        // (an exact end or knot value counts as attained here: a maximum at a knot of
        // multiplicity >= p that the strategy did not record is nearly proved as well)
        if far_below(bound, inner.max(end_value), scale, within) {
            break;
        }
        let near_scale = within as f64 * crate::num::ulp(bound.abs().max(scale));
        // (a value seen in an earlier round above the lowered target: that round's stage 2
        // found it, and would find it again at the same points)
        if top_seen.is_some_and(|g| g.is_above(up(t))) {
            proved = true;
            break;
        }
        let mut d = ddi_stage(ev, j, sign, up(t), cands, local_done);
        if let Some(g) = d.top {
            keep_top(&mut top_seen, g);
        }
        let guess = back(d.guess);
        if d.proved {
            proved = true;
            break;
        }
        // the other branch of the Ziv loop: a proof of max g <= t' for some t' < bound makes
        // t' a bound too. Only for a bound within a few ulps of the values seen (a loose
        // bound, e.g. the control hull's, is far from optimal and stays as it is). Try the
        // double just above the values seen first (RU(max) when the search found the
        // extremum), then one ulp below the bound; double-double rules first, then the exact
        // stage (3.) and the exact concavity rule.
        let target = guess.max(inner).max(end_value);
        // A value whose double-double enclosure holds t (a straddle) has g within ~2^-100
        // relative of t, so max g <= t could only be shown in exact arithmetic (double-double
        // enclosures near the maximiser straddle t as well): without the exact stage for this
        // curve, a lowering proof would spend its boxes and fail.
        // (above LOWER_MAX_DEGREE only when a clamped end's value is the largest value seen,
        // the likely maximum, which the Bézier rule decides with a few halvings of the end
        // spans)
        let ev_rule_possible = ev.exact_rule_possible();
        let at_clamped_end = end_value.is_finite() && end_value >= nth_down(guess, 2);
        let may_lower = round < MAX_LOWERINGS
            && (!d.straddle || ev.exact_possible() || ev.exact_rule_possible())
            && (target >= nth_down(bound, within) || bound - target <= near_scale);
        let lower = may_lower && (ev.c.degree() <= LOWER_MAX_DEGREE || at_clamped_end);
        // how the first lowering proof ended, and whether it had the exact rules
        let first_run = std::cell::Cell::new(None);
        let try_lower = |ev: &mut Evals, exact: bool| -> Option<f64> {
            if !lower {
                return None;
            }
            // first the double just above the values seen (the likely RU(max)); one ulp below
            // the bound only as the last resort, with every rule
            let goal = if target.is_finite() && target < t {
                target
            } else {
                t
            };
            // (the run with exact rules only after one without them that could not decide a
            // box or ran out of boxes: a refutation stands; on a rescaled curve the first run
            // has the exact rules already, `Scaling::exact_first`, and is not repeated)
            let first = first_run.get();
            let skip = exact && first.is_some_and(|(r, ex)| ex || r == Lowering::Refuted);
            if !skip {
                let ex = exact || sc.exact_first;
                let r = prove_at_most(ev, j, sign, (dn(goal), goal), cands, ex, sc.boxes);
                if !exact {
                    first_run.set(Some((r, ex)));
                }
                if r == Lowering::Proved {
                    return Some(goal);
                }
            }
            // (one ulp below the bound leads to a certificate only if some value seen can
            // reach the next double below a bound lowered by at most the rounds left: with
            // every value seen further below, that proof, often the costliest step of a
            // failing certificate, is skipped; the bound stays as it is, still proved)
            let reachable = target >= nth_down(bound, MAX_LOWERINGS - round + 1);
            (exact
                && goal < t
                && reachable
                && prove_at_most(ev, j, sign, (dn(t), t), cands, true, sc.boxes)
                    == Lowering::Proved)
                .then_some(t)
        };
        // A straddle (some value within ~2^-100 relative of t) with exact arithmetic
        // available: the exact Bernstein rule decides at once, on every span whose control
        // points exceed t, either g <= t (the bound is lowered to t) or a value above t
        // (the certificate). The double-double lowering cannot succeed here (every
        // enclosure of the straddling value holds t) and is skipped. (Up to the exact rule's
        // own degree limit, above LOWER_MAX_DEGREE too: its work is bounded by its own
        // limits, not by the box rules' evaluations.)
        if d.straddle && may_lower && ev.exact_rule_possible() {
            match exact_at_most(cv.above(sign), j, sign, (dn(t), t), cands) {
                Some(true) => {
                    bound = t;
                    continue;
                }
                // (a value of the curve above dn(t) is one above t when the curve evaluated is
                // the enclosed one, exactly scaled, and t is scaled without rounding)
                Some(false) if cv.up.is_none() && dn(t) == up(t) => {
                    proved = true;
                    break;
                }
                _ => {}
            }
        }
        if let Some(nb) = try_lower(cv.above(sign), false) {
            bound = nb;
            continue;
        }
        // (the search in the Bézier form, put off by the double-double stage: now that the
        // lowering proof failed)
        if d.deferred {
            let mut top = d.top;
            let found = bezier_search(
                cv.below(sign),
                j,
                sign,
                up(t),
                cands,
                &mut d.guess,
                &mut top,
            );
            if let Some(g) = top {
                keep_top(&mut top_seen, g);
            }
            if found {
                proved = true;
                break;
            }
        }
        if exact_stage(cv.below(sign), j, sign, up(t), &d) {
            proved = true;
            break;
        }
        // The exact Bernstein rule for a bound the box rules could not lower (a degree above
        // LOWER_MAX_DEGREE, extreme weights whose interval derivatives are wide, or clustered
        // knots): the same targets as `try_lower`, without the degree limit. Before the
        // lowering proof with exact concavity rules when the first one ran out of boxes (its
        // enclosures too wide: the exact rule does not depend on them, and a second branch
        // and bound over the same boxes mostly ran out as well), after it otherwise.
        let exact_ok = round < MAX_LOWERINGS
            && !d.straddle
            && ev_rule_possible
            && (target >= nth_down(bound, within) || bound - target <= near_scale);
        let goal = if target.is_finite() && target < t {
            target
        } else {
            t
        };
        let spent = first_run.get().is_some_and(|(r, _)| r == Lowering::Spent);
        if exact_ok
            && spent
            && exact_at_most(cv.above(sign), j, sign, (dn(goal), goal), cands) == Some(true)
        {
            bound = goal;
            continue;
        }
        if let Some(nb) = try_lower(cv.above(sign), true) {
            bound = nb;
            continue;
        }
        if exact_ok
            && !spent
            && exact_at_most(cv.above(sign), j, sign, (dn(goal), goal), cands) == Some(true)
        {
            bound = goal;
            continue;
        }
        break;
    }
    // (the end game in exact arithmetic on the enclosed curve itself, where the stages above,
    // on copies scaled into the f64 range, could not decide: a nearly proved bound only)
    if !proved && bound.is_finite() && !endgame_tried {
        let own = cv.dn.orig;
        if !far_below(bound, inner, own.coord_scale(j), sc.within) {
            if let Some(t) = exact_endgame(own, j, sign, bound, inner) {
                bound = t;
                proved = true;
            }
        }
    }
    if max_side {
        cb.hi = bound;
    } else {
        cb.lo = -bound;
    }
    proved
}

/// The finest grid of [`SpanRows::newton_points`] (2^-1100: a maximum's value within ~2^-2200 of
/// the scale, below the subnormal spacing for any f64 scale).
const NEWTON_MAX_BITS: u64 = 1100;

/// The grid [`SpanRows::newton_points`] needs for a value A near a maximum of g on a coordinate
/// of scale `scale` (f64 estimates; only a cost choice, never part of a proof): near a simple
/// maximiser g loses ~|g''| d^2 ~ scale d^2 at a distance d, which must stay below A's ulp
/// (2^-1074 for A near 0) for RU(A) to settle; so about (log2 scale - log2 ulp(A)) / 2 bits,
/// with a margin of 24.
fn newton_bits(a: f64, scale: f64) -> u64 {
    let e = |x: f64| exponent(x.abs().max(f64::from_bits(1)));
    let need = (e(scale) - e(crate::num::ulp(a.abs()))).max(0) / 2 + 24;
    (need as u64).clamp(64, NEWTON_MAX_BITS)
}

/// A nearly proved bound whose ulp is below 2^-FAR_TIE_BITS of the coordinate scale, more than
/// two of its ulps above the value attained, is a far tie ([`certify_side`]: the end game
/// first): double-double values (~2^-100 of the scale) cannot tell its doubles apart.
const FAR_TIE_BITS: i32 = 96;

/// Whether g = sign C_j <= v on span k's piece, by the convex hull of its Bézier points enclosed
/// in f64 intervals (`h` the curve's interval B-spline: Boehm insertion on outward rounded
/// intervals, NURBS Book A5.6; for a rational piece the quotients Q_i = Q^w_i / w_i with
/// weights enclosed above 0; the piece is a convex combination of them, NURBS Book P4.3).
/// `false` means only "not shown".
fn span_at_most(h: &HSpline<Interval>, k: usize, j: usize, sign: f64, v: f64) -> bool {
    let seg = h.bezier_segment(k);
    let (hd, dim) = (seg.hdim(), seg.dim);
    (0..=seg.degree).all(|i| {
        let x = seg.pts[i * hd + j];
        let q = if seg.rational {
            let w = seg.pts[i * hd + dim];
            if w.is_empty() || w.inf() <= 0.0 {
                return false;
            }
            x / w
        } else {
            x
        };
        let g = if sign > 0.0 { q } else { -q };
        // (an empty interval, whose sup is -inf, proves nothing)
        !g.is_empty() && g.sup() <= v
    })
}

/// Rounds of [`exact_endgame`].
pub const ENDGAME_ROUNDS: usize = 4;

/// The end game of a certificate (the Ziv loop of the module docs, finished in exact
/// arithmetic): for a bound that the double-double stages could not decide, on the enclosed
/// curve `c` itself, whose data are exact in rational arithmetic at any magnitude (values at
/// 1e-320 next to 1e308, knots whose differences overflow f64, which no scaling brings into the
/// f64 range together).
///
/// With A an exact lower bound of sup g (the attained value `inner`, then the exact values of
/// each span's piece at its ends and at the points where a round found g above its target),
/// t = RU(A) is tried as the bound: the exact Bernstein rule ([`sign_rule`] on f = sign A_j -
/// t W, [`span_rows_integer`]) on every span whose control values exceed t either proves g <= t
/// on all of them (spans whose control values are <= t are bounded by them: convex hull
/// property, weights > 0), so sup g <= t and, as A <= sup g and t = RU(A), t = RU(sup g): the
/// optimal bound, certified; or it finds an exact value g(s) > t, the next A. At most
/// [`ENDGAME_ROUNDS`] rounds over at most [`MAX_EXACT_SPANS`] spans of degree at most
/// [`EXACT_MAX_DEGREE`], each rule within its split limit; `None` (the bound stays, not
/// certified) otherwise. t is never above `bound` (A <= sup g <= bound, and `bound` is a double).
fn exact_endgame(c: &NurbsCurve, j: usize, sign: f64, bound: f64, inner: f64) -> Option<f64> {
    let (p, n) = (c.degree(), c.num_points() - 1);
    let kn = c.knots();
    let max_degree = if c.is_rational() {
        ENDGAME_MAX_DEGREE_RATIONAL
    } else {
        ENDGAME_MAX_DEGREE
    };
    if p > max_degree || !inner.is_finite() {
        return None;
    }
    let scale = c.coord_scale(j);
    let top = |k: usize| {
        (k - p..=k)
            .map(|i| sign * c.control_point(i)[j])
            .fold(f64::NEG_INFINITY, f64::max)
    };
    // The spans that can hold a value above the attained one: not those whose B-spline
    // control values are <= inner (strong convex hull, exact comparisons), nor those whose
    // Bézier points, enclosed in f64 intervals (the span's Bézier segment by Boehm insertion
    // on outward rounded intervals, NURBS Book A5.6; for a rational piece the quotients
    // Q_i = Q^w_i / w_i with weights enclosed above 0), all lie <= inner: the piece is a
    // convex combination of those points (NURBS Book P4.3). Every target t of the rounds
    // below is >= inner (t = RU(A), A >= inner), so g <= t on such spans in every round.
    // (The cheap filter first: the exact rows of a span cost far more.)
    let mut hs: Option<HSpline<Interval>> = None;
    let mut below_inner = |k: usize| {
        let h = hs.get_or_insert_with(|| HSpline::from_curve(c));
        span_at_most(h, k, j, sign, inner)
    };
    let spans: Vec<usize> = (p..=n)
        .filter(|&k| kn[k] < kn[k + 1] && top(k) > inner && !below_inner(k))
        .collect();
    if spans.len() > MAX_EXACT_SPANS {
        return None;
    }
    let rows: Vec<(usize, SpanRows)> = spans
        .iter()
        .map(|&k| Some((k, span_rows_integer(c, k, j, sign)?)))
        .collect::<Option<_>>()?;
    let mut best = Exact::of(inner).value()?.clone();
    // (rationals compared by a logarithm estimate, else cross-multiplication, denominators > 0
    // (`ratio_gt`): `Ratio`'s comparison divides, a chain of big divisions on these unreduced
    // values)
    let raise = |best: &mut BigRational, g: BigRational| {
        if crate::num::exact::ratio_gt(&g, best) {
            *best = g;
        }
    };
    // Newton from s towards the piece's critical point, with the grid A needs
    // ([`newton_bits`]): the value at the last iterate raises A
    // (returns the point of an exact tie at 0 found on the way, the sign rule's split point)
    let refine = |r: &SpanRows, mut s: BigRational, best: &mut BigRational| {
        let (mut from, mut to) = (
            64,
            newton_bits(Exact::from_ratio(best.clone()).to_f64(), scale),
        );
        while let Some(x) = r.newton_points(&s, (from, to)).pop() {
            if let Some(g) = r.value(&x) {
                raise(best, g);
            }
            // A value above the grid's own error (~scale 2^-2to at the grid's distance from
            // the maximiser; 2^32 of margin) is resolved: its RU settled. One below it came
            // out as near 0 as the grid allows: a maximum at 0 or within the grid's error of
            // it, where each finer A would ask for more again; on with the finest grid.
            let a = Exact::from_ratio(best.clone()).to_f64().abs();
            let resolved = a > scale * 2f64.powi(32 - 2 * to as i32);
            if resolved || to >= NEWTON_MAX_BITS {
                break;
            }
            // (a maximum exactly 0 at a rational point is a double root of the numerator A,
            // a root of gcd(A, A'): its exact value 0 is then A at once, without the finest
            // grid's long iterates)
            let zero = r
                .minus(0.0)
                .as_deref()
                .and_then(rational_double_root)
                .filter(|x| *x >= BigRational::zero() && *x <= BigRational::one())
                .and_then(|x| Some((x.clone(), r.value(&x)?)));
            if let Some((x, g)) = zero {
                let tie = g.is_zero();
                raise(best, g);
                if tie {
                    return Some(x);
                }
            }
            (from, to, s) = (2 * to, NEWTON_MAX_BITS, x);
        }
        None
    };
    for (_, r) in &rows {
        for i in [0, p] {
            if let Some(g) = r.ratio(r.a[i].clone(), &r.w[i]) {
                raise(&mut best, g);
            }
        }
    }
    // (and the values at exact Newton iterates to the critical point near the f64 maximiser
    // of each span's f for the attained value: with the extremum in the span's interior, A is
    // then within ~2^-2000 of it, and the first round's t = RU(A) is RU(sup g) already)
    // (Newton only from the span whose maximiser has the largest value)
    let t0 = Exact::from_ratio(best.clone()).round_down();
    let mut start: Option<(usize, &SpanRows, BigRational, BigRational)> = None;
    for (k, r) in &rows {
        let Some(s) = r.minus(t0).as_deref().and_then(f64_maximiser) else {
            continue;
        };
        let Some(s) = Exact::of(s).value().cloned() else {
            continue;
        };
        let Some(g) = r.value(&s) else {
            continue;
        };
        if start
            .as_ref()
            .is_none_or(|(_, _, _, top)| crate::num::exact::ratio_gt(&g, top))
        {
            start = Some((*k, r, s, g));
        }
    }
    // (span and point of an exact tie at 0)
    let mut tie: Option<(usize, BigRational)> = None;
    if let Some((k, r, s, g)) = start {
        raise(&mut best, g);
        // (the value at the last iterate, the most accurate one)
        tie = refine(r, s, &mut best).map(|x| (k, x));
    }
    for _ in 0..ENDGAME_ROUNDS {
        let t = Exact::from_ratio(best.clone()).round_up();
        if t.is_nan() || t > bound {
            return None;
        }
        let mut raised = false;
        for (k, r) in &rows {
            if top(*k) <= t {
                continue;
            }
            // (at t = 0 the tie's point, where f = 2^d A has its double root, is the split)
            let hint = tie
                .as_ref()
                .filter(|(at, _)| t == 0.0 && at == k)
                .map(|(_, x)| x.clone());
            match sign_rule_with(r.minus(t)?, hint) {
                Rule::AtMost => {}
                Rule::Above(s) => {
                    // f(s) > 0: g(s) > t >= A, a larger exact lower bound; and the values at
                    // exact Newton iterates from s towards the piece's critical point (s is
                    // near the maximiser: the split point of the sign rule, or a point where
                    // f just turned positive), which bring A within ~2^-1000 relative of a
                    // maximum there, so that RU(A) is RU(max g) at the next round
                    raise(&mut best, r.value(&s)?);
                    if let Some(x) = refine(r, s, &mut best) {
                        tie = Some((*k, x));
                    }
                    raised = true;
                    break;
                }
                Rule::Undecided => return None,
            }
        }
        if !raised {
            return Some(t);
        }
    }
    None
}

/// Span k's piece of g = sign C_j in integers ([`span_rows_integer`]): g(s) = 2^d A(s) / W(s)
/// with A = sum a_i B_i, W = sum w_i B_i (Bernstein polynomials of degree p on s in [0, 1]),
/// a and w the exact Bézier rows times one common positive factor.
struct SpanRows {
    a: Vec<BigInt>,
    w: Vec<BigInt>,
    d: i64,
}

impl SpanRows {
    /// g(s) exactly at the rational s in [0, 1] (`None` if W(s) is not > 0: not a valid piece).
    fn value(&self, s: &BigRational) -> Option<BigRational> {
        let (va, _) = eval_integer(&self.a, s);
        let (vw, _) = eval_integer(&self.w, s);
        self.ratio(va, &vw)
    }

    /// Points near a critical point of the piece from s ([`crate::num::sturm::newton_critical`]
    /// on A / W; the factor 2^d changes no critical point).
    fn newton_points(&self, s: &BigRational, bits: (u64, u64)) -> Vec<BigRational> {
        use crate::num::sturm::{newton_critical, power_form};
        newton_critical(&power_form(&self.a), &power_form(&self.w), s, bits)
    }

    /// 2^d va / vw for values va, vw of A and W at one point (the same scale; at the span's
    /// ends their end coefficients): `None` unless vw > 0. Unreduced: a gcd of the thousands
    /// of bits of range-limit data costs milliseconds, and comparisons do not need lowest terms.
    fn ratio(&self, va: BigInt, vw: &BigInt) -> Option<BigRational> {
        if vw.sign() != Sign::Plus {
            return None;
        }
        let sh = self.d.unsigned_abs();
        Some(if self.d >= 0 {
            BigRational::new_raw(va << sh, vw.clone())
        } else {
            BigRational::new_raw(va, vw << sh)
        })
    }

    /// The integer coefficients of f = 2^d A - t W (times a positive factor): f <= 0 iff
    /// g <= t on the piece (W > 0).
    fn minus(&self, t: f64) -> Option<Vec<BigInt>> {
        let (m, e_t) = dyadic_integers(std::iter::once(t))?;
        let e0 = self.d.min(e_t);
        let (sa, sw) = ((self.d - e0) as u64, (e_t - e0) as u64);
        Some(
            self.a
                .iter()
                .zip(&self.w)
                .map(|(a, w)| (a << sa) - ((&m[0] * w) << sw))
                .collect(),
        )
    }
}

/// The rows of span k's piece of g = sign C_j ([`SpanRows`]): the homogeneous values w_i sign
/// P_ij and the weights w_i of the span's local control points as integers (each row over one
/// power of two, exact), clamped together at both ends by fraction-free Boehm insertion
/// ([`clamp_span_integer`]: the same positive factor for both rows).
fn span_rows_integer(c: &NurbsCurve, k: usize, j: usize, sign: f64) -> Option<SpanRows> {
    let p = c.degree();
    let mut a = Vec::with_capacity(p + 1);
    let mut w = Vec::with_capacity(p + 1);
    for i in k - p..=k {
        let (x, e_x) = dyadic_integers(std::iter::once(sign * c.control_point(i)[j]))?;
        let (v, e_v) = dyadic_integers(std::iter::once(c.weight(i)))?;
        a.push((&x[0] * &v[0], e_x + e_v));
        w.push((v[0].clone(), e_v));
    }
    let common = |row: Vec<(BigInt, i64)>| -> Option<(Vec<BigInt>, i64)> {
        let e0 = row.iter().map(|x| x.1).min()?;
        Some((
            row.into_iter().map(|(m, e)| m << (e - e0) as u64).collect(),
            e0,
        ))
    };
    let (mut a, e_a) = common(a)?;
    let (mut w, e_w) = common(w)?;
    if c.is_rational() {
        clamp_span_integer(c, k, &mut [&mut a, &mut w])?;
    } else {
        // (the weights are all 1: a constant row, clamped as the common factor alone,
        // `clamp_span_ints_with`, without its corner cuts: half the big products)
        let mut f = w[0].clone();
        clamp_span_ints_with(
            p,
            &c.knots()[k - p..=k + p + 1],
            &mut [&mut a],
            Some(&mut f),
        )?;
        w.iter_mut().for_each(|x| *x = f.clone());
    }
    Some(SpanRows { a, w, d: e_a - e_w })
}

/// Spans per side searched by [`local_stage`] (more: the stage is skipped).
pub const LOCAL_MAX_SPANS: usize = 32;
/// Pieces per curve and side of [`local_stage`]'s search.
pub const LOCAL_PIECES: usize = 512;

/// What [`local_stage`] found, in the scaled units of the evaluated curves: a bound of g on
/// the curve above it, a value attained and a strict witness on the curve below it, and the
/// pieces (as parameter ranges of the evaluated curve) whose bounds exceed that value.
struct LocalFound {
    upper: f64,
    attained: f64,
    witness: f64,
    cands: Vec<Extremum>,
}

/// The search stage for a bound of a rescaled curve that lies many doubles of its own size
/// above the attained value: the strategies stop within an ulp of the coordinate scale, and a
/// scale near f64::MAX leaves an extremum ~1 (or 1e-300) anywhere below it; the search in u
/// cannot narrow such an extremum either where it lies at a local parameter ~1e-77 of a span
/// ~1e307 wide. So every span whose control values exceed `attained` (g of the copy above g,
/// scaled: a value the enclosed curve reaches, rounded down) is searched in its local
/// parameter t in [0, 1] on its double-double Bézier segment ([`Evals::ddi_segment`]; the
/// copy scaled for this side, so that values near the bound are near 1 and ~2^-100 relative
/// narrow), by `bezier`'s local search ([`crate::enclose::bezier::local_search`]: best-first,
/// convex hull bounds, splits at critical-point estimates). Its bound covers every span
/// (a span left out has control values, which bound it by the convex hull property with
/// weights > 0, at most `attained`); with two copies (rounded coordinates) the bound comes
/// from the copy above g, the values and witness from a second search on the copy below g.
/// `None` where the stage does not apply (degree < 2, too many spans, a non-finite bound).
fn local_stage(cv: &mut Curves, j: usize, sign: f64, attained: f64) -> Option<LocalFound> {
    let search = |ev: &mut Evals, attained: f64| {
        let c = ev.c;
        let (kn, p, n) = (c.knots(), c.degree(), c.num_points() - 1);
        if p < 2 {
            return None;
        }
        let last = (p..=n).rev().find(|&k| kn[k] < kn[k + 1])?;
        let start: Vec<(usize, f64, f64)> = (p..=n)
            .filter(|&k| kn[k] < kn[k + 1])
            .filter(|&k| {
                (k - p..=k)
                    .map(|i| sign * c.control_point(i)[j])
                    .fold(f64::NEG_INFINITY, f64::max)
                    > attained
            })
            .map(|k| (k, 0.0, 1.0))
            .collect();
        if start.len() > LOCAL_MAX_SPANS {
            return None;
        }
        let segs: Vec<(usize, BezierSeg<Ddi>)> = start
            .iter()
            .map(|&(k, _, _)| {
                let mut s = ev.ddi_segment(k).coord(j);
                (s.a, s.b) = (0.0, 1.0);
                (k, s)
            })
            .collect();
        let right_attained = |k: usize| crate::enclose::bezier::right_end_attained(kn, p, k, last);
        let r = crate::enclose::bezier::local_search(
            p,
            sign,
            &segs,
            &start,
            &right_attained,
            (attained, f64::NEG_INFINITY),
            LOCAL_PIECES,
        );
        let upper = r.upper();
        if !upper.is_finite() {
            return None;
        }
        let mut cands: Vec<(f64, Extremum)> = r
            .bounds
            .iter()
            .filter(|b| b.0 >= r.attained)
            .filter_map(|&(b, k, t0, t1, kind)| {
                let (u_lo, u_hi) = crate::enclose::newton::local_to_u(kn[k], kn[k + 1], t0, t1);
                (u_lo <= u_hi).then_some((
                    b,
                    Extremum {
                        u_lo,
                        u_hi,
                        unique: false,
                        kind,
                    },
                ))
            })
            .collect();
        cands.sort_by(|a, b| b.0.total_cmp(&a.0));
        Some(LocalFound {
            upper,
            attained: r.attained,
            witness: r.witness,
            cands: cands.into_iter().map(|x| x.1).collect(),
        })
    };
    let mut found = search(cv.above(sign), attained)?;
    if cv.up.is_some() {
        // (values of the copy above g are not values of the enclosed curve)
        let below = search(cv.below(sign), attained)?;
        found.attained = below.attained;
        found.witness = below.witness;
    }
    Some(found)
}

/// Keep in `top` the enclosure with the larger centre.
fn keep_top(top: &mut Option<Ddi>, g: Ddi) {
    if top.is_none_or(|x| g.to_f64() > x.to_f64()) {
        *top = Some(g);
    }
}

/// What the double-double stage found.
#[derive(Default)]
struct DdiOutcome {
    /// some u has g(u) > t (proved)
    proved: bool,
    /// the largest upper end of a value seen
    guess: f64,
    /// the value seen with the largest centre: some curve value lies in it, so it proves the
    /// certificate for every later target it is above (after a lowering)
    top: Option<Ddi>,
    /// whether some enclosure had t inside (undecided at double-double precision)
    straddle: bool,
    /// per candidate (centre of the best g, its u), for the exact stage
    best: Vec<(f64, f64)>,
    /// whether the search in the Bézier form (`bezier_search`) was put off: a value seen
    /// within [`NEAR_BITS`] bits of t below it, proved <= t (the candidates' Newton points
    /// reached the extremum, which is then most likely <= t: the lowering proof decides
    /// first, and the search runs only if it fails)
    deferred: bool,
}

/// A value proved <= t but within 2^-NEAR_BITS ulps of t below it counts as having reached
/// the extremum (`DdiOutcome::deferred`): f64 Newton points lie ~2^-106 relative below the
/// maximum, and a search elsewhere cannot find a value above t unless the maximum exceeds t
/// by less than that gap.
const NEAR_BITS: i32 = 40;

/// Stage 2 of the module docs: whether some u provably has g(u) > t, by double-double
/// enclosures at the candidates and at f64 Newton points.
fn ddi_stage(
    ev: &mut Evals,
    j: usize,
    sign: f64,
    t: f64,
    cands: &[Extremum],
    local_done: bool,
) -> DdiOutcome {
    let mut out = DdiOutcome {
        guess: f64::NEG_INFINITY,
        ..Default::default()
    };
    if ev.c.degree() > SEARCH_MAX_DEGREE {
        return out;
    }
    let guess = &mut out.guess;
    let mut seen_top = None;
    let seen = &mut seen_top;
    // g(u) in double-double; the largest upper end seen goes to `guess`, the value with the
    // largest centre to `seen`
    let look = |ev: &mut Evals, u: f64, guess: &mut f64, seen: &mut Option<Ddi>| -> Option<Ddi> {
        // at a clamped end the value is the end control point, exactly (a point set: an exact
        // tie with t is then no straddle, and the lowering proof decides it exactly)
        // (rounded down to the evaluated curve's scale: a lower bound of the scaled value)
        let g = match ev.exact_value(j, u) {
            Some(x) => Ddi::exact(ev.scaled_below(sign * x)),
            None => ev.ddi_value(j, sign, u)?,
        };
        *guess = guess.max(g.to_interval().sup());
        keep_top(seen, g);
        Some(g)
    };
    let mut straddle = false;
    // (a value proved <= t within 2^-NEAR_BITS ulps of it: `DdiOutcome::deferred`)
    let near_t = t - crate::num::ulp(t) * 2f64.powi(-NEAR_BITS);
    let mut near = false;
    // (only where the doubles resolve u's span finely, 2^NEAR_BITS of them or more: in a
    // span a few thousand doubles of u wide, e.g. at clustered knots, the f64 Newton points
    // cannot reach the extremum, and the search in the local parameter can)
    let fine = |c: &NurbsCurve, u: f64| {
        let kn = c.knots();
        let k = c.find_span(u);
        crate::num::ulp(u) <= (kn[k + 1] - kn[k]) * 2f64.powi(-NEAR_BITS)
    };
    let (a, b) = ev.c.domain();
    let p = ev.c.degree();
    // 2. double-double enclosures at chosen f64 parameters
    let mut best: Vec<(f64, f64)> = Vec::new(); // (centre of g, u)
    for x in cands {
        let (lo, hi) = (x.u_lo.max(a), x.u_hi.min(b));
        if lo.partial_cmp(&hi).is_none_or(Ordering::is_gt) {
            continue;
        }
        if x.kind == CandidateKind::ControlPoint {
            // the support of an extreme control point (hull): the curve reaches the control
            // point only at a knot of multiplicity >= p inside it; nothing to search
            let kn = ev.c.knots();
            for (i, &u) in kn.iter().enumerate() {
                let first = i == 0 || kn[i - 1] < u;
                if first
                    && lo <= u
                    && u <= hi
                    && multiplicity(kn, u) >= p
                    && look(ev, u, guess, seen).is_some_and(|g| g.is_above(t))
                {
                    out.proved = true;
                    return out;
                }
            }
            continue;
        }
        let mid = (lo + 0.5 * (hi - lo)).clamp(lo, hi);
        let Some(g) = look(ev, mid, guess, seen) else {
            continue;
        };
        if g.is_above(t) {
            out.proved = true;
            return out;
        }
        straddle |= !g.is_at_most(t);
        near |= g.is_at_most(t) && g.to_interval().sup() >= near_t && fine(ev.c, mid);
        let mut u = mid;
        let mut top = (g.to_f64(), mid);
        if lo < hi {
            for _ in 0..NEWTON_STEPS {
                let Some(d) = ev.approx(j, sign, u, 2) else {
                    break;
                };
                let (d1, d2) = (d[1], d[2]);
                if d2.is_nan() || d2 >= 0.0 || !d1.is_finite() {
                    break;
                }
                let next = (u - d1 / d2).clamp(lo, hi);
                if !next.is_finite() || next == u {
                    break;
                }
                u = next;
            }
            for v in [u, u.next_down(), u.next_up()] {
                if v < a || v > b {
                    continue;
                }
                let Some(g) = look(ev, v, guess, seen) else {
                    continue;
                };
                if g.is_above(t) {
                    out.proved = true;
                    return out;
                }
                straddle |= !g.is_at_most(t);
                near |= g.is_at_most(t) && g.to_interval().sup() >= near_t && fine(ev.c, v);
                if g.to_f64() > top.0 {
                    top = (g.to_f64(), v);
                }
            }
        }
        best.push(top);
    }
    // 2b. the same in the local parameter of the candidates' spans (Bézier form); not after
    // a straddle on a curve that is not rescaled and that the exact Bernstein rule takes
    // (which decides the straddle either way, `certify_side`)
    // (nor after the local stage, which searched every span in its local parameter already)
    // (and put off after a value seen near t: `DdiOutcome::deferred`)
    let exact_next = straddle && ev.exact_rule_possible() && std::ptr::eq(ev.c, ev.orig);
    let search = !exact_next && !local_done;
    out.deferred = search && near && !straddle;
    if search && !out.deferred && bezier_search(ev, j, sign, t, cands, guess, seen) {
        out.proved = true;
        return out;
    }
    out.top = *seen;
    out.straddle = straddle;
    out.best = best;
    out
}

/// Stage 2b: double-double values of the candidates' span pieces in their Bézier form
/// ([`HSpline::bezier_segment`], NURBS Book A5.6; thesis sec. 4.2), at a local parameter s in
/// [0, 1] chosen by f64 Newton steps on g(s) from the best of [`SEARCH_SAMPLES`] + 1 f64
/// samples over the candidate, refined by [`ZOOM_ROUNDS`] rounds of narrower samples around
/// the best one (only to choose s; g = A / W with A, W the Bernstein polynomials
/// of the coordinate and weight rows, the coordinate row scaled by a power of two,
/// g' = (A' - g W') / W, g'' = (A'' - 2 g' W' - g W'') / W from the hodographs), and at s = 0
/// and s = 1 (the values at the span's knots). The parameter u = u_k + (u_{k+1} -
/// u_k) s is never formed, so this works where derivatives with respect to u over- or
/// underflow (knots near ±f64::MAX, spans of a few subnormals).
///
/// Why a value above t proves the certificate: de Casteljau evaluation in [`Ddi`] at the exact
/// s encloses A(s) and W(s) of the exact segment (its coefficients are enclosed, and every
/// step is inclusion isotone), so A(s) / W(s) encloses the piece's value at some real u of the
/// closed span. That is a curve value, or (at s = 1 before a jump) the left limit of curve
/// values; either way some curve value exceeds t when the enclosure's lower end does.
/// At most [`BEZIER_SEARCH_SPANS`] spans; the largest upper end seen goes to `guess`, the
/// value with the largest centre to `top`.
fn bezier_search(
    ev: &mut Evals,
    j: usize,
    sign: f64,
    t: f64,
    cands: &[Extremum],
    guess: &mut f64,
    top: &mut Option<Ddi>,
) -> bool {
    let c = ev.c;
    let (p, n) = (c.degree(), c.num_points() - 1);
    let kn = c.knots();
    let mut done: Vec<usize> = Vec::new();
    for x in cands {
        for k in p..=n {
            let (ua, ub) = (kn[k], kn[k + 1]);
            if ua >= ub || ua > x.u_hi || ub < x.u_lo || done.contains(&k) {
                continue;
            }
            if done.len() >= BEZIER_SEARCH_SPANS {
                return false;
            }
            done.push(k);
            let seg = ev.ddi_segment(k);
            let hd = seg.hdim();
            let row = |r: usize| -> Vec<Ddi> { (0..=p).map(|i| seg.pts[i * hd + r]).collect() };
            let a = row(j);
            let w = seg.rational.then(|| row(seg.dim));
            // f64 rows (signed) and their hodographs, only to choose s; the coordinate row
            // scaled by a power of two to magnitudes near 1 (rows near f64::MAX overflow in
            // the hodographs' differences)
            let big = a.iter().fold(0.0f64, |m, d| m.max(d.to_f64().abs()));
            let norm = if big.is_finite() && big > 0.0 {
                2f64.powi(-exponent_of(big).clamp(-1000, 1000))
            } else {
                1.0
            };
            let af: Vec<f64> = a.iter().map(|d| sign * norm * d.to_f64()).collect();
            let wf: Vec<f64> = match &w {
                Some(w) => w.iter().map(Ddi::to_f64).collect(),
                None => vec![1.0; p + 1],
            };
            let (a1, w1) = (hodograph(&af), hodograph(&wf));
            let (a2, w2) = (hodograph(&a1), hodograph(&w1));
            // the candidate's midpoint in the local parameter (halved: no overflow)
            let (lo, hi) = (x.u_lo.max(ua), x.u_hi.min(ub));
            let local = |u: f64, dflt: f64| {
                let s = (0.5 * u - 0.5 * ua) / (0.5 * ub - 0.5 * ua);
                if s.is_finite() {
                    s.clamp(0.0, 1.0)
                } else {
                    dflt
                }
            };
            let (s_lo, s_hi) = (local(lo, 0.0), local(hi, 1.0));
            // (f64 values in O(p) operations, `bernstein_value`: only to choose s; W = 1 without
            // weights)
            let value = |s: f64| {
                let a = bernstein_value(&af, s);
                if w.is_some() {
                    a / bernstein_value(&wf, s)
                } else {
                    a
                }
            };
            // Newton from the largest f64 value among the candidate's midpoint and
            // SEARCH_SAMPLES + 1 points evenly over it (from the midpoint alone, a piece
            // that is convex there stops Newton at once)
            let mut s = local(0.5 * lo + 0.5 * hi, 0.5);
            let mut best = value(s);
            for i in 0..=SEARCH_SAMPLES {
                let f = i as f64 / SEARCH_SAMPLES as f64;
                let v = (s_lo + f * (s_hi - s_lo)).clamp(0.0, 1.0);
                let g = value(v);
                if g > best {
                    (s, best) = (v, g);
                }
            }
            // then SEARCH_SAMPLES + 1 points over the two sample intervals around the best,
            // ZOOM_ROUNDS times, each round 8 times narrower (a narrow peak next to a convex
            // stretch, e.g. near a weight much smaller than its neighbours', where Newton from
            // the best sample stops at once)
            let mut h = (s_hi - s_lo) / SEARCH_SAMPLES as f64;
            for _ in 0..ZOOM_ROUNDS {
                let c = s;
                for i in 0..=SEARCH_SAMPLES {
                    let f = 2.0 * i as f64 / SEARCH_SAMPLES as f64 - 1.0;
                    let v = (c + f * h).clamp(s_lo, s_hi).clamp(0.0, 1.0);
                    let g = value(v);
                    if g > best {
                        (s, best) = (v, g);
                    }
                }
                h /= 8.0;
            }
            for _ in 0..2 * NEWTON_STEPS {
                let ev = |b: &[f64]| bernstein_value(b, s);
                let (wv, w1v, w2v) = if w.is_some() {
                    (ev(&wf), ev(&w1), ev(&w2))
                } else {
                    (1.0, 0.0, 0.0)
                };
                let g = ev(&af) / wv;
                let g1 = (ev(&a1) - g * w1v) / wv;
                let g2 = (ev(&a2) - 2.0 * g1 * w1v - g * w2v) / wv;
                if g2.is_nan() || g2 >= 0.0 || !g1.is_finite() {
                    break;
                }
                let next = (s - g1 / g2).clamp(0.0, 1.0);
                if !next.is_finite() || next == s {
                    break;
                }
                s = next;
            }
            // (and the piece's two ends, the values at the span's knots: where the piece's
            // maximum is at an end, e.g. a convex piece, Newton stops at the midpoint)
            for (i, v) in [s, s.next_down(), s.next_up(), 0.0, 1.0]
                .into_iter()
                .enumerate()
            {
                if !(0.0..=1.0).contains(&v) || (i > 2 && (v - s).abs() <= f64::EPSILON) {
                    continue;
                }
                // at a clamped domain end the end control point, exactly (as in
                // `ddi_stage`: its upper end would otherwise hide that value as the largest
                // one seen, and the lowering would aim one ulp too high)
                let end = match v {
                    0.0 => ev.knot_value(j, k, ua),
                    1.0 => ev.knot_value(j, k, ub),
                    _ => None,
                };
                let g = match end {
                    Some(x) => Ddi::exact(ev.scaled_below(sign * x)),
                    None => {
                        let vd = Ddi::exact(v);
                        let num = de_casteljau_eval(&a, &vd);
                        let g = match &w {
                            Some(w) => num / de_casteljau_eval(w, &vd),
                            None => num,
                        };
                        g.signed(sign)
                    }
                };
                *guess = guess.max(g.to_interval().sup());
                keep_top(top, g);
                if g.is_above(t) {
                    return true;
                }
            }
        }
    }
    false
}

/// Stage 3 of the module docs: exact values at the best candidates' parameters and at exact
/// Newton iterates on dyadic parameters of [`ZIV_BITS`] bits; only when the double-double
/// stage left t undecided (`straddle`): otherwise every value seen is provably <= t and the
/// exact values at the same points are too (Newton moves the parameter by ~2^-106 relative
/// only, gaining ~2^-200 in value).
fn exact_stage(ev: &mut Evals, j: usize, sign: f64, t: f64, d: &DdiOutcome) -> bool {
    if !ev.exact_possible() || !d.straddle {
        return false;
    }
    let (a, b) = ev.c.domain();
    let mut best = d.best.clone();
    best.sort_by(|x, y| y.0.total_cmp(&x.0));
    let scale = exponent_of(a.abs().max(b.abs()).max(b - a));
    for &(_, u0) in best.iter().take(EXACT_CANDIDATES) {
        let mut u = Exact::of(u0);
        let Some(g) = ev.exact(j, sign, &u, 0) else {
            continue;
        };
        if g[0].gt_f64(t) {
            return true;
        }
        // exact Newton gains only what the f64 parameter misses (~2^-106 relative): go on
        // only for a value within 2^-96 of the scale below t (a near-tie)
        let gap = (Exact::of(t) - g[0].clone()).to_f64();
        let near = 2f64.powi(-96) * t.abs().max(ev.c.coord_scale(j));
        if gap.is_nan() || gap > near {
            continue;
        }
        'levels: for bits in ZIV_BITS {
            for _ in 0..2 {
                let Some(d) = ev.exact(j, sign, &u, 2) else {
                    break 'levels;
                };
                if d[1].is_exact_zero() {
                    break 'levels; // at a critical point already: nothing more to gain here
                }
                if d[2].signum() != Some(std::cmp::Ordering::Less) {
                    break 'levels;
                }
                let next = Exact::newton_truncated(&u, &d[1], &d[2], scale, bits);
                let Some(g) = ev.exact(j, sign, &next, 0) else {
                    break 'levels;
                };
                if g[0].gt_f64(t) {
                    return true;
                }
                u = next;
            }
        }
    }
    false
}

/// How a lowering proof ([`prove_at_most`]) ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Lowering {
    /// g <= t on the whole domain
    Proved,
    /// a value of g above t was met (rigorously): t is no bound, with or without exact rules
    Refuted,
    /// a box only an exact concavity argument could decide (none was allowed or left)
    Stuck,
    /// the box, depth or piece budget was spent
    Spent,
}

/// Whether g <= t on the whole domain, proved by branch and bound over every span (the
/// lowering branch of the Ziv loop; see the module docs for the rules). At most
/// `max_boxes` boxes and [`MAX_EXACT_TRIES`] exact concavity arguments; anything but
/// [`Lowering::Proved`] when they are spent or a value above t is met.
fn prove_at_most(
    ev: &mut Evals,
    j: usize,
    sign: f64,
    (t, t_own): (f64, f64),
    cands: &[Extremum],
    exact: bool,
    max_boxes: usize,
) -> Lowering {
    let c = ev.c;
    if c.degree() > SEARCH_MAX_DEGREE {
        return Lowering::Spent;
    }
    let (p, n) = (c.degree(), c.num_points() - 1);
    let kn = c.knots();
    let mut boxes = 0usize;
    let mut pieces = MAX_PIECES;
    // (without `exact`: no exact evaluation at all)
    let mut exact_tries = if exact {
        ExactBudget::default()
    } else {
        ExactBudget::SPENT
    };
    // spans nearest the candidates first: an early failure costs least
    let mut spans: Vec<usize> = (p..=n).filter(|&k| kn[k] < kn[k + 1]).collect();
    let near = |k: usize| cands.iter().any(|x| x.u_lo <= kn[k + 1] && x.u_hi >= kn[k]);
    spans.sort_by_key(|&k| !near(k));
    for k in spans {
        // Strong convex hull property (NURBS Book P4.3; thesis prop. 2.1 on one span): on
        // [u_k, u_{k+1}] the piece is a convex combination of P_{k-p} .. P_k (weights > 0),
        // so g <= max of their signed coordinates there; exact f64 comparisons, no box spent.
        // (the enclosed curve's own control points against the target in its own units)
        let local = (k - p..=k)
            .map(|i| sign * ev.orig.control_point(i)[j])
            .fold(f64::NEG_INFINITY, f64::max);
        if local <= t_own {
            continue;
        }
        // the span's Bézier pieces first (exact values at clamped domain ends); what they
        // leave undecided goes to the box rules
        let Some(rest) = bezier_rule(ev, k, j, sign, (t, t_own), &mut pieces) else {
            return Lowering::Refuted;
        };
        let mut stack: Vec<(f64, f64, u32)> =
            rest.into_iter().map(|(lo, hi)| (lo, hi, 0)).collect();
        while let Some((lo, hi, depth)) = stack.pop() {
            boxes += 1;
            if boxes > max_boxes {
                return Lowering::Spent;
            }
            // the concavity rules only near a candidate of the strategy (where the extremum
            // is): elsewhere splitting is cheaper
            let near_cand = cands.iter().any(|x| x.u_lo <= hi && x.u_hi >= lo);
            match box_at_most(
                ev,
                k,
                j,
                sign,
                (t, t_own),
                lo,
                hi,
                near_cand,
                &mut exact_tries,
            ) {
                BoxVerdict::Below => {}
                BoxVerdict::Above => return Lowering::Refuted,
                BoxVerdict::Stuck => return Lowering::Stuck,
                BoxVerdict::Split => {
                    let m = lo + 0.5 * (hi - lo);
                    if depth >= MAX_DEPTH || !(lo < m && m < hi) {
                        return Lowering::Spent;
                    }
                    stack.push((lo, m, depth + 1));
                    stack.push((m, hi, depth + 1));
                }
            }
        }
    }
    Lowering::Proved
}

/// The Bézier rule of the lowering proof on span k: whether g <= t on the span's piece, by the
/// strong convex hull property of its Bézier form (NURBS Book A5.6 DecomposeCurve via
/// [`HSpline::bezier_segment`], then de Casteljau halving, thesis sec. 4.2; for a rational
/// piece the Cartesian points Q_i = Q^w_i / w_i with weights w_i > 0, so every value of a
/// piece is a convex combination of its Q_i, NURBS Book P4.3). A piece is decided when every
/// Q_i (enclosed in [`Ddi`]: the Boehm insertions, the halvings at the exact t = 1/2 and the
/// division are rigorous enclosures, ~2^-100 relative wide) is <= t.
///
/// The first point of a piece is the curve's value at the piece's start (end interpolation of
/// a Bézier curve), the last its value at the end. At a clamped domain end that value is the
/// end control point exactly ([`NurbsCurve::clamped_ends`]), so there it is compared with t
/// exactly instead of through its enclosure: this decides a maximum attained at a clamped end
/// (the common exact tie g = t there) without any rounding error. Pieces at such an end are
/// halved towards it (at most [`MAX_PIECES`] halvings per proof, depth [`BEZIER_DEPTH`]): near
/// the end the other control points approach the end value along the end tangent, so they
/// drop below t once the piece is short enough (for g'(end) pointing into the domain below
/// t). So are the pieces of a span with extreme knots (beyond 2^±900, where the box rules'
/// derivatives in u over- or underflow). Other pieces are halved to depth
/// [`BEZIER_DEPTH_INTERIOR`] only (the control points
/// converge to the curve quadratically in the piece length, also for extreme weights, where
/// interval derivatives of the quotient are wide). Every undecided piece is returned as a
/// parameter box (its range in u, rounded outward and clamped to the span) for the box
/// rules. `None`: a piece's end value is above t
/// (t is not a bound).
fn bezier_rule(
    ev: &mut Evals,
    k: usize,
    j: usize,
    sign: f64,
    (t, t_own): (f64, f64),
    pieces: &mut usize,
) -> Option<Vec<(f64, f64)>> {
    let c = ev.c;
    let kn = c.knots();
    let (ua, ub) = (kn[k], kn[k + 1]);
    // (and at an interior knot of multiplicity >= p, where the piece's end value is a control
    // point too: [`Evals::knot_value`]; the enclosed curve's own control points, compared
    // with the target in its own units)
    let exact_start = ev
        .knot_value(j, k, ua)
        .or_else(|| ev.clamped_end_value(j, ua))
        .map(|x| sign * x);
    let exact_end = ev
        .knot_value(j, k, ub)
        .or_else(|| ev.clamped_end_value(j, ub))
        .map(|x| sign * x);
    let seg = ev.ddi_segment(k);
    let (hd, dim, rational, p) = (seg.hdim(), seg.dim, seg.rational, seg.degree);
    let half = Ddi::exact(0.5);
    // a span whose parameter boxes the box rules cannot handle (its length or its knots
    // beyond 2^±900: derivatives in u over- or underflow there) is halved as deep as an end
    let big = 2f64.powi(900);
    let extreme = !(ub - ua < big && ub - ua > 1.0 / big && ua.abs() < big && ub.abs() < big);
    let mut out = Vec::new();
    // (points, local start, local end, depth); local parameters are dyadic, so exact
    let mut stack = vec![(seg.pts, 0.0f64, 1.0f64, 0u32)];
    while let Some((pts, s0, s1, depth)) = stack.pop() {
        let mut below = true;
        for i in 0..=p {
            let x = if rational {
                pts[i * hd + j] / pts[i * hd + dim]
            } else {
                pts[i * hd + j]
            };
            let x = x.signed(sign);
            let exact = match i {
                0 if s0 == 0.0 => exact_start,
                _ if i == p && s1 == 1.0 => exact_end,
                _ => None,
            };
            let ok = exact.map_or_else(|| x.is_at_most(t), |v| v <= t_own);
            if !ok {
                // an end point is a curve value: above t refutes t
                if (i == 0 || i == p) && exact.map_or_else(|| x.is_above(t), |v| v > t_own) {
                    return None;
                }
                below = false;
                break;
            }
        }
        if below {
            continue;
        }
        let at_end = (s0 == 0.0 && exact_start.is_some()) || (s1 == 1.0 && exact_end.is_some());
        let max_depth = if at_end || extreme {
            BEZIER_DEPTH
        } else {
            BEZIER_DEPTH_INTERIOR
        };
        if depth < max_depth && *pieces > 0 {
            *pieces -= 1;
            let (l, r) = de_casteljau_split(&pts, hd, &half);
            let m = 0.5 * (s0 + s1); // exact: s0, s1 dyadic with few bits
            stack.push((r, m, s1, depth + 1));
            stack.push((l, s0, m, depth + 1));
        } else {
            // the piece's parameter range ua + (ub - ua) [s0, s1], rounded outward (an
            // overflow gives ENTIRE, i.e. the whole span)
            let at = |s: f64| iv::point(ua) + (iv::point(ub) - iv::point(ua)) * iv::point(s);
            let lo = at(s0).inf().max(ua);
            let hi = at(s1).sup().min(ub);
            out.push((
                if lo <= hi { lo } else { ua },
                if lo <= hi { hi } else { ub },
            ));
        }
    }
    Some(out)
}

/// Spans per [`exact_at_most`] (beyond, `None`).
const MAX_EXACT_SPANS: usize = 8;

/// Whether g <= t on the whole domain (`Some(true)`), or some value of the curve exceeds t
/// (`Some(false)`), decided by the strong convex hull of each span's control points (exact f64
/// comparisons, as in [`prove_at_most`]), then the double-double Bézier rule ([`bezier_rule`]:
/// its `None` is a rigorous enclosure of a piece's end value, a curve value, above t) and,
/// on the spans these leave, the exact Bernstein rule ([`exact_bernstein_rule`]); `None`: undecided (more than [`MAX_EXACT_SPANS`] such
/// spans, or a span undecided within its splits). `t` is on the evaluated curve's scale,
/// `t_own` the same target in the enclosed curve's units (for its own control points).
fn exact_at_most(
    ev: &mut Evals,
    j: usize,
    sign: f64,
    (t, t_own): (f64, f64),
    cands: &[Extremum],
) -> Option<bool> {
    let c = ev.c;
    let (p, n) = (c.degree(), c.num_points() - 1);
    let kn = c.knots();
    let mut spans: Vec<usize> = (p..=n)
        .filter(|&k| kn[k] < kn[k + 1])
        .filter(|&k| {
            (k - p..=k)
                .map(|i| sign * ev.orig.control_point(i)[j])
                .fold(f64::NEG_INFINITY, f64::max)
                > t_own
        })
        .collect();
    if spans.len() > MAX_EXACT_SPANS {
        return None;
    }
    let near = |k: usize| cands.iter().any(|x| x.u_lo <= kn[k + 1] && x.u_hi >= kn[k]);
    spans.sort_by_key(|&k| !near(k));
    let mut undecided = false;
    let mut pieces = MAX_PIECES;
    for k in spans {
        // the double-double Bézier rule first on the spans away from the candidates: it
        // decides them at a fraction of the exact rule's cost (near a candidate the value
        // straddles t, which only the exact rule decides)
        match (!near(k)).then(|| bezier_rule(ev, k, j, sign, (t, t_own), &mut pieces)) {
            Some(None) => return Some(false),
            Some(Some(rest)) if rest.is_empty() => continue,
            _ => {}
        }
        match exact_bernstein_rule(ev, k, j, sign, t) {
            Some(true) => {}
            Some(false) => return Some(false),
            None => undecided = true,
        }
    }
    (!undecided).then_some(true)
}

/// Coefficients longer than this (numerator and denominator bits) are not tried by
/// [`exact_bernstein_rule`] at all.
const EXACT_RULE_MAX_BITS: u64 = 12_000;
/// Largest binary exponent (in magnitude) of a span's data for [`exact_bernstein_rule`].
const EXACT_RULE_MAX_EXP: i32 = 300;
/// Pieces whose coefficients are longer than this are rounded up ([`exact_bernstein_rule`]).
const EXACT_RULE_ROUND_BITS: u64 = 512;
/// Significant bits kept of each coefficient when rounding up.
const EXACT_RULE_KEEP_BITS: u64 = 256;
/// Coefficients more than this many bits below a piece's largest one are rounded up to that
/// granularity when rounding (so that a piece's coefficients stay within this many bits).
const EXACT_RULE_SPREAD_BITS: u64 = 3072;

/// Splits per span of [`exact_bernstein_rule`].
const MAX_EXACT_SPLITS: usize = 48;

/// The exact Bernstein rule of a lowering proof on span k: whether g <= t on the span's piece,
/// decided in exact rational arithmetic. `Some(true)`: proved; `Some(false)`: a value of the
/// piece exceeds t (t is not a bound); `None`: undecided within [`MAX_EXACT_SPLITS`] splits.
///
/// The piece is A(s) / W(s) (s in [0, 1] its local parameter; W = 1 for a polynomial curve)
/// with A, W Bernstein polynomials whose coefficients are the span's Bézier segment
/// ([`HSpline::bezier_segment`], Boehm knot insertion, NURBS Book A5.1 / A5.6; run on
/// [`Exact`], so exact). All weights are > 0, so W(s) > 0 (a convex combination of positive
/// segment weights) and g(s) <= t iff f(s) := sign A(s) - t W(s) <= 0: a polynomial with exact
/// Bernstein coefficients f_i = sign A_i - t W_i. By the convex hull property of the Bernstein
/// basis (B_i >= 0, sum B_i = 1; thesis sec. 4.2) f <= max_i f_i on [0, 1], and the same on
/// every piece from exact de Casteljau subdivision (NURBS Book A1.5 at a rational point, no
/// rounding). A piece whose coefficients are all <= 0 is proved; an end coefficient > 0 is a
/// value f(s) > 0, i.e. a curve value (or a left limit of curve values) above t.
///
/// A tie, max g = t exactly, makes f touch 0 at the maximiser s* (a double root): no piece
/// containing s* in its interior has all coefficients <= 0, but pieces with s* as an end do,
/// once short enough (f(s*) = f'(s*) = 0 makes the first two coefficients 0 and the rest
/// ~ f''(s*) h^2 < 0). So the piece is split at s* first: s* is chosen as the best (largest
/// exact f) of the f64 maximiser of f's rounded coefficients (only to choose a point) and of
/// exact Newton steps on f' from it (exact for a quadratic; rounded to dyadic grids of
/// 2^-60 and 2^-200 for higher degrees, which hit a dyadic maximiser such as 1/2 exactly).
/// The pieces next to s* are then halved towards it. A near-tie below t (f(s*) < 0 within
/// 2^-100 relative) is decided the same way, with pieces of width ~ |f(s*) / f'(s*)|.
fn exact_bernstein_rule(ev: &mut Evals, k: usize, j: usize, sign: f64, t: f64) -> Option<bool> {
    let c = ev.c;
    if !exact_is_cheap(c, k, j, t) {
        return None;
    }
    let p = c.degree();
    // The coefficients as integers over a common positive denominator, which is dropped
    // (only signs matter): no gcd per operation, the cost of big rationals.
    let fi = bezier_coefficients_fraction_free(c, k, j, sign, t)?;
    debug_assert_eq!(fi.len(), p + 1);
    match sign_rule(fi) {
        Rule::AtMost => Some(true),
        Rule::Above(_) => Some(false),
        Rule::Undecided => None,
    }
}

/// What [`sign_rule`] showed for a Bernstein polynomial f on [0, 1].
enum Rule {
    /// f <= 0 on [0, 1]
    AtMost,
    /// f(s) > 0 at this s in [0, 1] (exactly)
    Above(BigRational),
    /// undecided within [`MAX_EXACT_SPLITS`] splits (or coefficients too long)
    Undecided,
}

/// The sign rule of [`exact_bernstein_rule`] on the integer Bernstein coefficients `fi` of f
/// (the exact ones times a positive factor): f <= 0 on [0, 1] when every coefficient of every
/// piece of an exact subdivision is <= 0 (convex hull property), f(s) > 0 at a piece's end s
/// whose end coefficient (the value there) is > 0. Where coefficients were rounded up, an end
/// coefficient > 0 is checked by the exact value of f at that end (de Casteljau in integers).
fn sign_rule(fi: Vec<BigInt>) -> Rule {
    sign_rule_with(fi, None)
}

/// [`sign_rule`], with a known zero of f as its split point when `hint` is one (a double root
/// found already: the tie of the end game), else the best split ([`best_split`]).
fn sign_rule_with(fi: Vec<BigInt>, hint: Option<BigRational>) -> Rule {
    let p = fi.len() - 1;
    let pos = |x: &BigInt| x.sign() == Sign::Plus;
    if fi.iter().all(|x| !pos(x)) {
        return Rule::AtMost;
    }
    let end = |i: usize| BigRational::from_integer(BigInt::from(i));
    if pos(&fi[0]) {
        return Rule::Above(end(0));
    }
    if pos(&fi[p]) {
        return Rule::Above(end(1));
    }
    if fi.iter().map(BigInt::bits).max().unwrap_or(0) > EXACT_RULE_MAX_BITS {
        return sturm_rule(&fi);
    }
    let hint = hint.filter(|x| eval_integer(&fi, x).0.is_zero());
    let known_zero = hint.is_some();
    let split_point = match hint {
        Some(x) => Some(Exact::from_ratio(x)),
        None => best_split(&fi),
    };
    // A near-tie: f at the split point (the best candidate for the maximiser) not 0 but within
    // 2^-NEAR_TIE_BITS of the largest coefficient. The pieces beside it would be decided
    // only once shorter than ~sqrt of that (f ~ f(s*) + f''(s*) h^2 there): more halvings
    // than the split budget allows, so Sturm's theorem first (an exact tie at the split point
    // itself, f(s*) = 0, is the subdivision's: two pieces ending there, a few halvings; a
    // hint is such a zero already).
    if let Some(x) = split_point
        .as_ref()
        .filter(|_| !known_zero)
        .and_then(Exact::value)
    {
        let (v, sc) = eval_integer(&fi, x);
        let big = fi.iter().map(BigInt::bits).max().unwrap_or(0);
        if !v.is_zero() && v.bits() + NEAR_TIE_BITS < big + sc.bits() {
            match sturm_rule(&fi) {
                Rule::Undecided => {}
                r => return r,
            }
        }
    }
    let exact = fi.clone();
    let mut stack = vec![(fi, Exact::of(0.0), Exact::of(1.0))];
    // whether some coefficients were rounded up (then an end coefficient > 0 refutes nothing)
    let mut rounded = false;
    let mut splits = 0usize;
    let half = Exact::of(0.5);
    while let Some((mut b, s0, s1)) = stack.pop() {
        // Long coefficients (extreme magnitudes, or many splits at a non-dyadic point) are
        // rounded up, each to [`EXACT_RULE_KEEP_BITS`] significant bits (but not finer than
        // [`EXACT_RULE_SPREAD_BITS`] bits below the largest one), and then the power of two
        // that divides all of them is divided out (a positive common factor): upper bounds of
        // the Bernstein coefficients bound f from above on the piece (B_i >= 0), and de
        // Casteljau's corner cuts at r in [0, 1] are convex combinations, so the pieces'
        // coefficients computed from upper bounds bound the exact pieces'. (Relative, not
        // absolute rounding: a coefficient far below the largest keeps its sign and size,
        // which decide the pieces where the largest one's basis function vanishes, as at a
        // value ~1e-320 next to a control value ~1e308.)
        let long = b.iter().map(BigInt::bits).max().unwrap_or(0);
        if long > EXACT_RULE_ROUND_BITS {
            let floor = long.saturating_sub(EXACT_RULE_SPREAD_BITS);
            for x in b.iter_mut() {
                let g = x.bits().saturating_sub(EXACT_RULE_KEEP_BITS).max(floor);
                if g > 0 {
                    // ceil(x / 2^g) 2^g (the shift of a negative BigInt rounds down)
                    *x = -((-&*x) >> g) << g;
                }
            }
            let tz = b
                .iter()
                .filter_map(|x| x.trailing_zeros())
                .min()
                .unwrap_or(0);
            if tz > 0 {
                b.iter_mut().for_each(|x| *x = &*x >> tz);
            }
            rounded = true;
        }
        if b.iter().all(|x| !pos(x)) {
            continue;
        }
        if pos(&b[0]) || pos(&b[p]) {
            let at = if pos(&b[0]) { s0 } else { s1 };
            let at = at.value().cloned();
            // (rounded coefficients: the exact value of f at that end decides)
            let above = at
                .as_ref()
                .is_some_and(|x| !rounded || eval_integer(&exact, x).0.sign() == Sign::Plus);
            return match (above, at) {
                (true, Some(x)) => Rule::Above(x),
                _ => sturm_rule(&exact),
            };
        }
        splits += 1;
        if splits > MAX_EXACT_SPLITS {
            return sturm_rule(&exact);
        }
        // split at s* when it lies strictly inside, else halve
        let positive = |x: Exact| x.signum() == Some(Ordering::Greater);
        let inside = split_point
            .as_ref()
            .filter(|x| positive((*x).clone() - s0.clone()) && positive(s1.clone() - (*x).clone()));
        let r = match inside {
            Some(x) => (x.clone() - s0.clone()) / (s1.clone() - s0.clone()),
            None => half.clone(),
        };
        let m = s0.clone() + r.clone() * (s1.clone() - s0.clone());
        let Some(r) = r.value() else {
            return sturm_rule(&exact);
        };
        let (l, rt) = split_integer(&b, r);
        stack.push((rt, m.clone(), s1));
        stack.push((l, s0, m));
    }
    Rule::AtMost
}

/// A value at the split point within 2^-NEAR_TIE_BITS of the largest coefficient, not zero, is
/// a near-tie ([`sign_rule`]: Sturm's theorem first).
const NEAR_TIE_BITS: u64 = 40;

/// Coefficients longer than this are not given to [`sturm_rule`].
const STURM_MAX_BITS: u64 = 4096;

/// The decision of [`sign_rule`] where its subdivision gave none (an exact tie at an
/// irrational or non-dyadic point, which no split point holds; a near-tie whose pieces would
/// have to be shorter than the split budget allows): Sturm's theorem on f's power form
/// ([`crate::num::sturm`]: f <= 0 on [0, 1], or an exact point where f > 0).
fn sturm_rule(fi: &[BigInt]) -> Rule {
    use crate::num::sturm::{at_most_zero, power_form, Decision};
    if fi.iter().map(BigInt::bits).max().unwrap_or(0) > STURM_MAX_BITS {
        return Rule::Undecided;
    }
    match at_most_zero(&power_form(fi)) {
        Decision::AtMost => Rule::AtMost,
        Decision::Above(s) => Rule::Above(s),
        Decision::Undecided => Rule::Undecided,
    }
}

/// Whether the data of span k (coordinate j and weights of its control points, its knots
/// relative to the span's length, the target t) have binary exponents within
/// +-[`EXACT_RULE_MAX_EXP`]: an f64 m 2^e is a rational of about 53 + |e| bits, and the
/// exact Bézier segment of data spanning 2^+-1000 (range limits) has coefficients of
/// thousands of bits, whose arithmetic costs milliseconds.
fn exact_is_cheap(c: &NurbsCurve, k: usize, j: usize, t: f64) -> bool {
    let p = c.degree();
    let kn = c.knots();
    let ok = short_dyadic;
    let len = kn[k + 1] - kn[k];
    ok(t)
        && ok(len)
        && (k - p..=k).all(|i| ok(c.control_point(i)[j]) && ok(c.weight(i)))
        && kn[k - p + 1..=k + p]
            .iter()
            .all(|&u| ok(u) && ok((u - kn[k]) / len))
}

/// Whether x is 0 or a short rational: finite with a binary exponent within
/// +-[`EXACT_RULE_MAX_EXP`], so at most about 53 + [`EXACT_RULE_MAX_EXP`] bits on either side
/// of the binary point (its lowest set bit is at or above 2^-(EXACT_RULE_MAX_EXP + 53)). A
/// knot near f64::MAX, or a subnormal one such as 6e-323 (a 2^-1072 bit), makes every exact
/// quotient with it a rational of over a thousand bits, however ordinary the f64 quotient
/// looks.
fn short_dyadic(x: f64) -> bool {
    x == 0.0 || (x.is_finite() && exponent_of(x.abs()).abs() <= EXACT_RULE_MAX_EXP)
}

/// Whether an exact value of coordinate j of span k's piece at u ([`Evals::exact_in`]) is
/// cheap enough: the span's 2p knots, its p + 1 control values of coordinate j and weights are
/// short rationals ([`short_dyadic`]) and u has a binary exponent within
/// +-[`EXACT_RULE_MAX_EXP`] (or is 0; u itself may be a dyadic of the exact Newton levels,
/// a few hundred bits). (A cubic Bézier with control values from 1e-320 to 8.8e307 — after
/// the driver's scaling, 2^-1074 next to 2^0 — ran 24 exact values at 0.4 ms each, 10 ms for
/// a bound it did not certify, against 13 µs for the enclosure.)
/// The de Boor triangle's alphas are quotients of knot differences; knots near ±f64::MAX next
/// to subnormal ones (2^±1074) make rationals of thousands of bits, and one value with
/// derivatives cost milliseconds (a lowering proof on such a span took 0.4 s).
fn exact_value_is_cheap(c: &NurbsCurve, k: usize, j: usize, u: &Exact) -> bool {
    let p = c.degree();
    let kn = c.knots();
    short_dyadic(u.to_f64())
        && kn[k + 1 - p..=k + p].iter().all(|&x| short_dyadic(x))
        && (k - p..=k).all(|i| short_dyadic(c.control_point(i)[j]) && short_dyadic(c.weight(i)))
}

/// Clamps span k of `c` at both ends ([`clamp_span_ints`] on the span's 2p + 2 local knots).
fn clamp_span_integer<T: FfInt>(c: &NurbsCurve, k: usize, rows: &mut [&mut [T]]) -> Option<()> {
    let p = c.degree();
    clamp_span_ints(p, &c.knots()[k - p..=k + p + 1], rows)
}

/// De Casteljau subdivision (NURBS Book A1.5) of the Bernstein coefficients `b` (over a common
/// positive denominator) at the rational r = m / n in (0, 1), n > 0, in integers: each corner
/// cut (1 - r) x + r y is (n - m) x + m y over n times the denominator, and the two halves'
/// coefficients from level l are multiplied by n^(p - l) to share the denominator n^p. Exact:
/// the returned integers are the halves' coefficients times one positive factor each.
fn split_integer(b: &[BigInt], r: &BigRational) -> (Vec<BigInt>, Vec<BigInt>) {
    let p = b.len() - 1;
    let (m, n) = (r.numer().clone(), r.denom().clone());
    let nm = &n - &m;
    let mut lvl = b.to_vec();
    let mut left = vec![lvl[0].clone()];
    let mut right = vec![lvl[p].clone()];
    for l in 1..=p {
        for i in 0..=p - l {
            lvl[i] = &nm * &lvl[i] + &m * &lvl[i + 1];
        }
        left.push(lvl[0].clone());
        right.push(lvl[p - l].clone());
    }
    // level l was scaled by n^l: bring every entry to n^p
    let pow: Vec<BigInt> = (0..=p)
        .scan(BigInt::one(), |acc, _| {
            let v = acc.clone();
            *acc *= &n;
            Some(v)
        })
        .collect();
    let left = left
        .iter()
        .enumerate()
        .map(|(l, x)| x * &pow[p - l])
        .collect();
    // right[i] came from level p - i (the right half's coefficient i)
    let mut right: Vec<BigInt> = right
        .iter()
        .enumerate()
        .map(|(l, x)| x * &pow[p - l])
        .collect();
    right.reverse();
    (left, right)
}

/// The maximiser of the Bernstein polynomial with integer coefficients `fi` on [0, 1], roughly:
/// the best of 16 samples of its coefficients rounded to f64 (normalised), then f64 Newton
/// steps on f' (only a point to try: whoever uses it evaluates exactly there). `None` for
/// coefficients that do not round to finite f64 even after a shift.
fn f64_maximiser(fi: &[BigInt]) -> Option<f64> {
    let ff: Vec<f64> = fi.iter().map(|x| x.to_f64().unwrap_or(f64::NAN)).collect();
    let big = ff.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    // normalise (only to choose a point; f64 rounding is harmless here); coefficients
    // beyond f64 are shifted first
    let ff: Vec<f64> = if big.is_finite() && big > 0.0 {
        ff.iter().map(|x| x / big).collect()
    } else {
        let shift = fi
            .iter()
            .map(BigInt::bits)
            .max()
            .unwrap_or(0)
            .saturating_sub(60);
        fi.iter()
            .map(|x| (x >> shift).to_f64().unwrap_or(f64::NAN))
            .collect()
    };
    if ff.iter().any(|x| !x.is_finite()) {
        return None;
    }
    let (f1, f2) = (hodograph(&ff), hodograph(&hodograph(&ff)));
    let mut s = 0.5;
    let mut best = bernstein_value(&ff, s);
    for i in 1..SEARCH_SAMPLES {
        let v = i as f64 / SEARCH_SAMPLES as f64;
        let g = bernstein_value(&ff, v);
        if g > best {
            (s, best) = (v, g);
        }
    }
    for _ in 0..2 * NEWTON_STEPS {
        let (d1, d2) = (bernstein_value(&f1, s), bernstein_value(&f2, s));
        if d2.is_nan() || d2 >= 0.0 || !d1.is_finite() {
            break;
        }
        let next = (s - d1 / d2).clamp(0.0, 1.0);
        if next == s {
            break;
        }
        s = next;
    }
    Some(s)
}

/// The split point s* of [`exact_bernstein_rule`] for the Bernstein coefficients `f` on [0, 1]:
/// the candidate in (0, 1) with the largest exact value (`None` if none lies inside).
fn best_split(fi: &[BigInt]) -> Option<Exact> {
    // (coefficients of thousands of bits, range-limit data: no exact quadratic critical point,
    // whose numerator and denominator are as long and make every later split as costly (the
    // grid points below instead), and no double-root search, whose gcds cost milliseconds)
    let long = fi.iter().map(BigInt::bits).max().unwrap_or(0) > EXACT_SPLIT_MAX_BITS;
    // (the integer coefficients, the exact ones times a positive factor: the same signs,
    // maximisers and double roots)
    let s = f64_maximiser(fi)?;
    let zero = BigRational::from_integer(BigInt::from(0));
    let one = BigRational::one();
    let inside = |x: &BigRational| *x > zero && *x < one;
    let se = Exact::of(s).value()?.clone();
    // exact Newton on f' from s (for a quadratic, f' is linear: the exact critical point)
    let mut cands = Vec::new();
    let h1: Vec<BigInt> = fi.windows(2).map(|w| &w[1] - &w[0]).collect();
    let h2: Vec<BigInt> = h1.windows(2).map(|w| &w[1] - &w[0]).collect();
    let p = fi.len() - 1;
    if p >= 2 {
        let (d1, sc1) = eval_integer(&h1, &se);
        let (d2, sc2) = eval_integer(&h2, &se);
        if d2.sign() == Sign::Minus {
            // f' = p sum h1_i B_i, f'' = p (p - 1) sum h2_i B_i; step = f'/f'' = num / den
            let (num, den) = (d1 * &sc2, d2 * &sc1 * BigInt::from(p - 1));
            if p == 2 && !long {
                cands.push(&se - BigRational::new(num, den));
            } else {
                // the Newton point n = se - num / den = top / bot (bot > 0), unreduced: only
                // its nearest points on the grids are needed
                let (sn, sd) = (se.numer(), se.denom());
                let (top, bot) = (sn * &den - &num * sd, sd * &den);
                let (top, bot) = if bot.sign() == Sign::Minus {
                    (-top, -bot)
                } else {
                    (top, bot)
                };
                cands.push(se);
                for bits in [60u64, 200] {
                    // the nearest point of the grid 2^-bits: floor((2 top 2^bits + bot) /
                    // (2 bot)) / 2^bits, a dyadic rational in lowest terms without a gcd
                    let r = ((top.clone() << (bits + 1)) + &bot).div_floor(&(&bot << 1u64));
                    cands.push(crate::num::exact::dyadic(r, bits));
                }
            }
        } else {
            cands.push(se);
        }
    } else {
        cands.push(se);
    }
    // the first with f = 0 exactly (a tie: split there), else the largest f (values v / sc
    // with sc > 0, compared by cross products: no reduction)
    let mut best: Option<(BigInt, BigInt, BigRational)> = None;
    for x in cands.into_iter().filter(inside) {
        let (v, sc) = eval_integer(fi, &x);
        if v.sign() == Sign::NoSign {
            return Some(Exact::from_ratio(x));
        }
        if best
            .as_ref()
            .is_none_or(|(bv, bsc, _)| crate::num::exact::frac_gt((&v, &sc), (bv, bsc)))
        {
            best = Some((v, sc, x));
        }
    }
    // an exact tie at a rational parameter that no grid holds (the extremum a double at
    // s* = 2/3, say): a double root of f, hence a root of gcd(f, f'). Not sought when f has
    // a double root at an end already (f_0 = f_1 = 0 or f_{p-1} = f_p = 0: the tie at a knot
    // or a domain end, whose pieces next to that end the splits at the best candidate
    // decide): Euclid's algorithm on rational coefficients costs far more than those
    // splits (a degree-5 span: ~8M instructions, against ~0.3M for the rest of the rule).
    let zero_at = |i: usize| fi[i].sign() == Sign::NoSign;
    let end_tie = p >= 1 && ((zero_at(0) && zero_at(1)) || (zero_at(p) && zero_at(p - 1)));
    // (nor for coefficients of thousands of bits, range-limit data: the gcds of Euclid's
    // rationals cost milliseconds there)
    if let Some(r) = (!end_tie && !long)
        .then(|| rational_double_root(fi))
        .flatten()
        .filter(inside)
    {
        return Some(Exact::from_ratio(r));
    }
    best.map(|(_, _, x)| Exact::from_ratio(x))
}

/// Coefficients longer than this are not searched for a rational double root, and a quadratic
/// with such coefficients is not split at its exact critical point ([`best_split`]).
const EXACT_SPLIT_MAX_BITS: u64 = 1024;

/// A rational double root of f, the Bernstein polynomial with integer coefficients `fi`
/// (degree 2 ..= 8): the root of gcd(f, f') when that gcd is linear (a root of f and f', so
/// f vanishes there exactly; rational arithmetic, no rounding). Only a split point for
/// [`exact_bernstein_rule`]: whatever it returns, the rule's proof is the signs of exact
/// coefficients. On the power form (a_k = binom(p, k) Δ^k f_0,
/// Farin's monomial form of a Bézier curve) in exact rationals: for a cubic the rational
/// roots of the quadratic f' (a square discriminant), else Euclid's algorithm for the gcd.
/// Both only where the power form modulo a prime has a repeated factor
/// ([`squarefree_mod_prime`]): otherwise f has no double root at all, and the rational
/// gcd, whose coefficients grow at every step (milliseconds on long coefficients), is not
/// computed.
fn rational_double_root(fi: &[BigInt]) -> Option<BigRational> {
    let p = fi.len().checked_sub(1)?;
    if !(2..=8).contains(&p) {
        return None;
    }
    let ai = crate::num::sturm::power_form(fi);
    if squarefree_mod_prime(&ai) {
        return None;
    }
    if p == 3 && !ai[3].is_zero() {
        // f' = c + b s + a s^2 (integers: c = a_1, b = 2 a_2, a = 3 a_3): a double root of f
        // is a root of f', rational only if the discriminant is a square, and one where f
        // vanishes too
        let (c0, b1, a2) = (
            ai[1].clone(),
            BigInt::from(2) * &ai[2],
            BigInt::from(3) * &ai[3],
        );
        let disc = &b1 * &b1 - BigInt::from(4) * &a2 * &c0;
        if disc.sign() == Sign::Minus {
            return None;
        }
        let r = disc.sqrt();
        if &r * &r != disc {
            return None;
        }
        // (the root of f' where f vanishes too, if either is one)
        let two_a = BigInt::from(2) * &a2;
        let roots = [(-&b1 + &r), (-&b1 - &r)].map(|n| BigRational::new(n, two_a.clone()));
        return roots
            .into_iter()
            .find(|x| eval_integer(fi, x).0.sign() == Sign::NoSign);
    }
    // (Euclid on the integer primitive pseudo-remainders: no rational reductions)
    let a = crate::num::sturm::gcd_with_derivative(&ai);
    (a.len() == 2).then(|| BigRational::new(-&a[0], a[1].clone()))
}

/// The greatest common divisor of two polynomials with rational power coefficients (lowest
/// first), up to a constant factor, by Euclid's algorithm: the last non-zero remainder
/// (empty when both are zero). (The tests' oracle for the integer one,
/// [`crate::num::sturm::gcd_with_derivative`].)
#[cfg(test)]
fn rational_gcd(a: Vec<BigRational>, b: Vec<BigRational>) -> Vec<BigRational> {
    let trim = |mut v: Vec<BigRational>| {
        while v.last().is_some_and(|x| x.is_zero()) {
            v.pop();
        }
        v
    };
    let (mut a, mut b) = (trim(a), trim(b));
    while !b.is_empty() {
        // a mod b (b's leading coefficient is non-zero after trimming)
        let lead = b[b.len() - 1].clone();
        while a.len() >= b.len() {
            let q = &a[a.len() - 1] / &lead;
            let off = a.len() - b.len();
            for (i, bi) in b.iter().enumerate() {
                a[off + i] -= &q * bi;
            }
            a.pop();
            a = trim(a);
        }
        std::mem::swap(&mut a, &mut b);
    }
    a
}

/// Whether the integer polynomial f = sum a_k t^k (`a`, power form) provably has no repeated
/// factor over the rationals, in particular no double root: decided modulo the prime
/// q = 2^61 - 1, where gcd(f mod q, f' mod q) is a non-zero constant (Euclid's algorithm in
/// the field Z/q, on machine words). `false` means only "not proved" (a repeated factor, or
/// the rare prime that divides the leading coefficient).
///
/// Proof. Let n be the degree of f (a_n its leading coefficient, a_n != 0 mod q) and suppose
/// f = g^2 h over Q with g of degree >= 1. By Gauss's lemma g can be taken primitive in Z[t]
/// with h in Z[t]; lc(g)^2 divides a_n, so q does not divide lc(g) and g mod q keeps its
/// degree >= 1. Reducing f = g^2 h and f' = g (2 g' h + g h') modulo q, g mod q divides both,
/// so their gcd has degree >= 1. (The derivative's coefficients k a_k, k <= 8 < q, reduce to
/// those of (f mod q)', and its leading one n a_n is non-zero mod q.) Hence a constant gcd
/// modulo q excludes a repeated factor, and with it a rational double root.
fn squarefree_mod_prime(a: &[BigInt]) -> bool {
    const Q: u64 = (1 << 61) - 1;
    let mul = |x: u64, y: u64| ((x as u128 * y as u128) % Q as u128) as u64;
    let sub = |x: u64, y: u64| if x >= y { x - y } else { x + Q - y };
    let inv = |x: u64| {
        // x^(q - 2) = x^-1 (Fermat; x != 0 mod q)
        let (mut r, mut b, mut e) = (1u64, x, Q - 2);
        while e > 0 {
            if e & 1 == 1 {
                r = mul(r, b);
            }
            b = mul(b, b);
            e >>= 1;
        }
        r
    };
    let Some(n) = a.iter().rposition(|x| !x.is_zero()) else {
        return false;
    };
    let q = BigInt::from(Q);
    let f: Vec<u64> = a[..=n]
        .iter()
        .map(|x| x.mod_floor(&q).to_u64().unwrap_or(0))
        .collect();
    if f[n] == 0 || n > 8 {
        return false;
    }
    if n <= 1 {
        // a constant or a line: no repeated factor
        return true;
    }
    let df: Vec<u64> = (1..=n).map(|k| mul(k as u64, f[k])).collect();
    let trim = |v: &mut Vec<u64>| {
        while v.last() == Some(&0) {
            v.pop();
        }
    };
    let (mut x, mut y) = (f, df);
    while !y.is_empty() {
        // x mod y (y's leading coefficient non-zero after trimming)
        let li = inv(y[y.len() - 1]);
        while x.len() >= y.len() {
            let c = mul(x[x.len() - 1], li);
            let off = x.len() - y.len();
            for (i, &yi) in y.iter().enumerate() {
                x[off + i] = sub(x[off + i], mul(c, yi));
            }
            x.pop();
            trim(&mut x);
        }
        std::mem::swap(&mut x, &mut y);
    }
    // x is the gcd modulo q: a non-zero constant proves f square-free
    x.len() == 1
}

/// The value at the rational x = m / n (n > 0) of the Bernstein polynomial with integer
/// coefficients `b`, as (v, n^p) with value v / n^p: de Casteljau in integers (each corner
/// cut (n - m) a + m b over n).
pub(crate) fn eval_integer(b: &[BigInt], x: &BigRational) -> (BigInt, BigInt) {
    let (m, n) = (x.numer().clone(), x.denom().clone());
    let nm = &n - &m;
    let mut lvl = b.to_vec();
    let mut scale = BigInt::one();
    for l in 1..lvl.len() {
        for i in 0..lvl.len() - l {
            lvl[i] = &nm * &lvl[i] + &m * &lvl[i + 1];
        }
        scale *= &n;
    }
    (lvl.swap_remove(0), scale)
}

/// What one box of the branch and bound showed.
#[derive(Debug)]
enum BoxVerdict {
    /// g <= t on the box
    Below,
    /// g > t somewhere (so t is not a bound)
    Above,
    /// undecided: split it
    Split,
    /// undecided, and splitting cannot help (the deciding value is one point's)
    Stuck,
}

/// g <= t on [lo, hi] inside span k? Rules (each a proof for the piece of span k on the closed
/// box, which covers every curve value there, also at a jump):
/// the natural double-double enclosure; monotonicity (g' of one sign: the maximum is at an
/// end, evaluated as a point); the mean value form g(m) + g'(X)(X - m); concavity (g'' < 0 on
/// X: g lies below its tangents at two exact points m1 <= m2 with g'(m1) >= 0 >= g'(m2), so
/// below their intersection, computed exactly).
#[allow(clippy::too_many_arguments)]
fn box_at_most(
    ev: &mut Evals,
    k: usize,
    j: usize,
    sign: f64,
    (t, t_own): (f64, f64),
    lo: f64,
    hi: f64,
    near_cand: bool,
    exact_tries: &mut ExactBudget,
) -> BoxVerdict {
    // f64 intervals first (natural and mean value forms): boxes away from the extremum end
    // here, at a fraction of the double-double cost
    let xi = iv::span(lo, hi);
    let gi = ev.iv_in(k, j, sign, xi, 2);
    let m = (lo + 0.5 * (hi - lo)).clamp(lo, hi);
    if gi[0].sup() <= t {
        return BoxVerdict::Below;
    }
    let gmi = ev.iv_in(k, j, sign, iv::point(m), 0);
    if (gmi[0] + gi[1] * (xi - iv::point(m))).sup() <= t {
        return BoxVerdict::Below;
    }
    let x = Ddi::from_bounds(lo, hi);
    let g = ev.ddi_in(k, j, sign, x, 2);
    if g[0].is_at_most(t) {
        return BoxVerdict::Below;
    }
    let point_at_most = |ev: &mut Evals, u: f64, budget: &mut ExactBudget| -> Option<bool> {
        if let Some(x) = ev
            .knot_value(j, k, u)
            .or_else(|| ev.clamped_end_value(j, u))
        {
            // the end control point, exactly (`NurbsCurve::clamped_ends`; the enclosed
            // curve's own, against the target in its own units)
            return Some(sign * x <= t_own);
        }
        let v = ev.ddi_in(k, j, sign, Ddi::exact(u), 0);
        if v[0].is_at_most(t) {
            return Some(true);
        }
        if v[0].is_above(t) {
            return Some(false);
        }
        if budget.points >= MAX_EXACT_POINTS {
            return None;
        }
        budget.points += 1;
        let e = ev.exact_in(k, j, sign, &Exact::of(u), 0)?;
        Some(!e[0].gt_f64(t))
    };
    let d1 = g[1].to_interval();
    if d1.inf() >= 0.0 || d1.sup() <= 0.0 {
        // monotone on the box: the maximum is at one end
        let end = if d1.inf() >= 0.0 { hi } else { lo };
        return match point_at_most(ev, end, exact_tries) {
            Some(true) => BoxVerdict::Below,
            Some(false) => BoxVerdict::Above,
            None => BoxVerdict::Stuck,
        };
    }
    let gm = ev.ddi_in(k, j, sign, Ddi::exact(m), 2);
    if gm[0].is_above(t) {
        return BoxVerdict::Above;
    }
    let mvf = gm[0] + g[1] * (x - Ddi::exact(m));
    if mvf.is_at_most(t) {
        return BoxVerdict::Below;
    }
    if !near_cand {
        return BoxVerdict::Split;
    }
    if g[2].to_interval().sup() < 0.0 {
        // concave on the box: tangents first in double-double, then exactly
        match concave_ddi(ev, k, j, sign, t, lo, hi, m, &gm) {
            Concave::Decided(v) => {
                return if v {
                    BoxVerdict::Below
                } else {
                    BoxVerdict::Above
                };
            }
            // A point u of the box whose double-double value holds t: every Ddi rule on a
            // box containing u encloses g(u) too, so none can show g <= t there, however
            // the box is split (an exact tie at a critical point, e.g. a symmetric curve's
            // maximum at a knot). Only the exact rule below can; without exact tries left,
            // the proof stops here instead of halving towards u to the depth limit.
            Concave::Straddle if exact_tries.tries >= MAX_EXACT_TRIES => return BoxVerdict::Stuck,
            _ => {}
        }
    }
    if g[2].to_interval().sup() < 0.0 && exact_tries.tries < MAX_EXACT_TRIES {
        exact_tries.tries += 1;
        if let Some(v) =
            concave_at_most(ev, k, j, sign, t, lo, hi, gm[1].to_f64(), gm[2].to_f64(), m)
        {
            return if v {
                BoxVerdict::Below
            } else {
                BoxVerdict::Above
            };
        }
    }
    BoxVerdict::Split
}

/// The concavity rule in double-double (g'' < 0 on [lo, hi], proved by the caller): f64
/// Newton steps from m (only to choose points) give u ~ the critical point; m1 < u < m2 a few
/// ulps apart with g'(m1) > 0 > g'(m2) proved; then g lies below both tangents on the box,
/// so below T = g(m1) + g'(m1)(x - m1) at their intersection x, all enclosed in Ddi.
/// `Decided(true)`: T <= t; `Decided(false)`: a value above t; `Straddle`: undecided, and the
/// value at the Newton point u (in the box) holds t; `Undecided` otherwise.
#[allow(clippy::too_many_arguments)]
fn concave_ddi(
    ev: &mut Evals,
    k: usize,
    j: usize,
    sign: f64,
    t: f64,
    lo: f64,
    hi: f64,
    m: f64,
    gm: &[Ddi],
) -> Concave {
    let mut u = m;
    let mut d = gm.to_vec();
    for _ in 0..4 {
        let (d1, d2) = (d[1].to_f64(), d[2].to_f64());
        if d2.is_nan() || d2 >= 0.0 || !d1.is_finite() {
            return Concave::Undecided;
        }
        let next = (u - d1 / d2).clamp(lo, hi);
        if next == u || !next.is_finite() {
            break;
        }
        u = next;
        d = ev.ddi_in(k, j, sign, Ddi::exact(u), 2);
    }
    if d[0].is_above(t) {
        return Concave::Decided(false);
    }
    // The Newton point stopped at an end of the box with the slope there pointing out of it:
    // g' is decreasing on X (g'' < 0 there), so g'(lo) <= 0 gives g' <= 0 on all of X and
    // max_X g = g(lo); likewise g'(hi) >= 0 gives max_X g = g(hi). (The critical point lies
    // beyond that end, where no tangent pair inside X brackets it.)
    let slope = d[1].to_interval();
    if (u == lo && slope.sup() <= 0.0) || (u == hi && slope.inf() >= 0.0) {
        if d[0].is_at_most(t) {
            return Concave::Decided(true);
        }
        return Concave::Straddle;
    }
    let mut step = (u.abs().max(hi - lo) * f64::EPSILON).max(f64::from_bits(1));
    for _ in 0..6 {
        let (m1, m2) = ((u - step).max(lo), (u + step).min(hi));
        let a = ev.ddi_in(k, j, sign, Ddi::exact(m1), 1);
        let b = ev.ddi_in(k, j, sign, Ddi::exact(m2), 1);
        let (s1, s2) = (a[1].to_interval(), b[1].to_interval());
        if s1.inf() >= 0.0 && s2.sup() <= 0.0 {
            let denom = a[1] - b[1];
            if denom.to_interval().inf() <= 0.0 {
                // slopes too small to intersect the tangents safely. g lies below its
                // tangent at m1: g(u) <= g(m1) + g'(m1)(u - m1), which is <= g(m1) left of
                // m1 and <= g(m1) + g'(m1)(m2 - m1) on [m1, m2] (and bounds g(m2)); right
                // of m2, g(u) <= g(m2) + g'(m2)(u - m2) <= g(m2): so this bounds all of X
                let top = a[0] + a[1] * (Ddi::exact(m2) - Ddi::exact(m1));
                if top.is_at_most(t) {
                    return Concave::Decided(true);
                }
                break;
            }
            let x = (b[0] - a[0] + a[1] * Ddi::exact(m1) - b[1] * Ddi::exact(m2)) / denom;
            let top = a[0] + a[1] * (x - Ddi::exact(m1));
            if top.is_at_most(t) {
                return Concave::Decided(true);
            }
            break;
        }
        step *= 8.0;
    }
    if d[0].is_at_most(t) {
        Concave::Undecided
    } else {
        Concave::Straddle
    }
}

/// What [`concave_ddi`] showed.
enum Concave {
    Decided(bool),
    Straddle,
    Undecided,
}

/// The concavity rule on [lo, hi] (g'' < 0 there, proved by the caller): exact Newton steps
/// from m find dyadic m1 <= m2 in the box bracketing the critical point (g'(m1) >= 0 >=
/// g'(m2)); then max g <= T, the intersection of the two tangents (or g(m1) if g'(m1) = 0).
/// `Some(true)`: T <= t; `Some(false)`: g(m1) > t; `None`: undecided.
#[allow(clippy::too_many_arguments)]
fn concave_at_most(
    ev: &mut Evals,
    k: usize,
    j: usize,
    sign: f64,
    t: f64,
    lo: f64,
    hi: f64,
    d1: f64,
    d2: f64,
    m: f64,
) -> Option<bool> {
    let inside = |u: &Exact| {
        matches!(u.cmp_f64(lo), Some(Ordering::Greater | Ordering::Equal))
            && matches!(u.cmp_f64(hi), Some(Ordering::Less | Ordering::Equal))
    };
    let scale = exponent_of(lo.abs().max(hi.abs()).max(hi - lo));
    // an f64 start near the critical point
    let u0 = if d2 < 0.0 && d1.is_finite() {
        (m - d1 / d2).clamp(lo, hi)
    } else {
        m
    };
    let mut u = Exact::of(u0);
    for bits in ZIV_BITS {
        for _ in 0..2 {
            let d = ev.exact_in(k, j, sign, &u, 2)?;
            let (g0, g1, g2) = (&d[0], &d[1], &d[2]);
            if g0.gt_f64(t) {
                return Some(false);
            }
            if g1.is_exact_zero() {
                // the critical point itself: max g on the box = g(u)
                return Some(true);
            }
            if g2.signum() != Some(Ordering::Less) {
                return None;
            }
            // the Newton point (on the grid) and a dyadic on its other side: a bracket [m1, m2]
            let newton = Exact::newton_truncated(&u, g1, g2, scale, bits);
            let step = Exact::of(2f64.powi(scale - bits as i32));
            let other = if g1.signum() == Some(Ordering::Greater) {
                newton.clone() + step
            } else {
                newton.clone()
            };
            if inside(&other) {
                let e = ev.exact_in(k, j, sign, &other, 2)?;
                let (h0, h1) = (&e[0], &e[1]);
                if h0.gt_f64(t) {
                    return Some(false);
                }
                let opposite = h1.is_exact_zero() || h1.signum() != g1.signum();
                if opposite {
                    // tangents at u (slope g1) and at other (slope h1) intersect at
                    // x = (h0 - g0 + g1 u - h1 other) / (g1 - h1); T = g0 + g1 (x - u)
                    let bound = if h1.is_exact_zero() {
                        h0.clone()
                    } else {
                        let x = (h0.clone() - g0.clone() + g1.clone() * u.clone()
                            - h1.clone() * other.clone())
                            / (g1.clone() - h1.clone());
                        g0.clone() + g1.clone() * (x - u.clone())
                    };
                    if !bound.gt_f64(t) && bound.value().is_some() {
                        return Some(true);
                    }
                }
            }
            let next = newton;
            if !inside(&next) {
                return None;
            }
            u = next;
        }
    }
    None
}

/// x moved down by k doubles.
fn nth_down(mut x: f64, k: usize) -> f64 {
    for _ in 0..k {
        x = x.next_down();
    }
    x
}

/// The exponent e with |x| < 2^e (x finite, > 0; 0 otherwise).
fn exponent_of(x: f64) -> i32 {
    if x.is_nan() || x <= 0.0 || !x.is_finite() {
        return 0;
    }
    // (x in [2^(e-1), 2^e), from the bits)
    exponent(x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::enclose::{BoxEncloser, Newton};

    /// The branch-free first round against its short-circuit definition: the flags agree with
    /// `Some(true)` / `None` / `Some(false)` of the rules taken in order (bounds, attained
    /// values and witnesses at and next to each other, zeros, subnormals, the extremes,
    /// infinities and NaN).
    #[test]
    fn branch_free_first_round_is_the_short_circuit_one() {
        use rand::{Rng, SeedableRng};
        let reference =
            |bound: f64, inner: f64, witness: f64, exact: f64, (scale, within): (f64, usize)| {
                if !bound.is_finite() {
                    return Some(false);
                }
                if inner == bound || witness >= bound.next_down() || exact > bound.next_down() {
                    return Some(true);
                }
                far_below(bound, inner.max(exact), scale, within).then_some(false)
            };
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(43);
        let mut specials = vec![
            0.0,
            -0.0,
            f64::MIN_POSITIVE,
            f64::from_bits(1),
            f64::MAX,
            1.0,
            0.5,
            3.0,
        ];
        for k in [-1074, -1022, -1, 0, 1, 52, 1023] {
            let p = 2f64.powi(k);
            specials.extend([p, p.next_up(), p.next_down()]);
        }
        let specials: Vec<f64> = specials.iter().flat_map(|&x| [x, -x]).collect();
        let pick = |r: &mut rand_chacha::ChaCha8Rng, b: f64| -> f64 {
            match r.random_range(0..8) {
                0 => b,
                1 => b.next_down(),
                2 => b.next_down().next_down(),
                3 => b - 8.0 * crate::num::ulp(b) * r.random_range(0.5..2.0),
                4 => f64::NEG_INFINITY,
                5 => f64::NAN,
                6 => specials[r.random_range(0..specials.len())],
                _ => b - r.random_range(0.0..1e-3),
            }
        };
        for _ in 0..200_000 {
            let bound = match r.random_range(0..10) {
                0 => [f64::INFINITY, f64::NEG_INFINITY, f64::NAN][r.random_range(0..3)],
                1..=3 => specials[r.random_range(0..specials.len())],
                _ => r.random_range(-10.0..10.0),
            };
            let (inner, witness, exact) = (
                pick(&mut r, bound),
                pick(&mut r, bound),
                pick(&mut r, bound),
            );
            let window = (
                [1.0, 1e-300, 5.0, f64::MIN_POSITIVE][r.random_range(0..4)],
                [LOWER_WITHIN_ULPS, LOWER_WITHIN_ULPS_RESCALED][r.random_range(0..2)],
            );
            let want = reference(bound, inner, witness, exact, window);
            let flags = first_round_flags(bound, inner, witness, exact, window);
            assert_eq!(
                flags,
                (want == Some(true), want.is_none()),
                "{bound:e} {inner:e} {witness:e} {exact:e}"
            );
            assert_eq!(first_round(bound, inner, witness, exact, window), want);
        }
    }

    /// The i128 fraction-free Bézier coefficients are the BigInt ones wherever no operation
    /// overflows (the same steps), and an overflow is reported, never wrapped: random
    /// B-spline spans of degree 1..=5 with short data (small integer knots, few-bit values,
    /// where i128 must succeed) and long data (53-bit knots and values, tiny weights).
    #[test]
    fn fraction_free_coefficients_agree_in_i128_and_bigint() {
        use rand::{Rng, SeedableRng};
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(33);
        let (mut small, mut fell_back) = (0, 0);
        for it in 0..1500 {
            let p = r.random_range(1..=5usize);
            let n = p + r.random_range(0..4usize);
            let short = it % 2 == 0;
            let mut kn: Vec<f64> = (0..n + p + 2)
                .map(|_| {
                    if short {
                        r.random_range(0..12) as f64
                    } else {
                        r.random_range(-1.0..1.0)
                    }
                })
                .collect();
            kn.sort_by(f64::total_cmp);
            let pts: Vec<Vec<f64>> = (0..=n)
                .map(|_| {
                    let x = if short {
                        r.random_range(-4096..4096) as f64 / 64.0
                    } else {
                        r.random_range(-1e3..1e3)
                    };
                    vec![x]
                })
                .collect();
            let w: Option<Vec<f64>> = (it % 3 == 0).then(|| {
                (0..=n)
                    .map(|_| {
                        if short {
                            r.random_range(1..8) as f64
                        } else {
                            r.random_range(1e-9..2.0)
                        }
                    })
                    .collect()
            });
            let Ok(c) = NurbsCurve::new(p, kn.clone(), pts, w) else {
                continue;
            };
            let t = if short {
                1.5
            } else {
                r.random_range(-1e3..1e3)
            };
            for k in p..=n {
                if kn[k] >= kn[k + 1] {
                    continue;
                }
                let big = bezier_coefficients_ff::<BigInt>(&c, k, 0, 1.0, t);
                match bezier_coefficients_ff::<i128>(&c, k, 0, 1.0, t) {
                    Some(q) => {
                        let q: Vec<BigInt> = q.into_iter().map(BigInt::from).collect();
                        assert_eq!(Some(q), big, "p {p} k {k} {kn:?}");
                        small += 1;
                    }
                    None => {
                        assert!(
                            !short || big.is_none(),
                            "short data overflowed i128: {kn:?}"
                        );
                        fell_back += 1;
                    }
                }
            }
        }
        assert!(small > 500 && fell_back > 100, "{small} {fell_back}");
    }

    /// The one-pass `max_knot_value` equals the definition span by span (every span's two
    /// ends through `knot_value`, which looks up each knot's multiplicity): degrees 1..=5,
    /// knot vectors drawn from a few values (multiplicities up to p + 1 and beyond, clamped,
    /// unclamped and jump knots), both signs, every coordinate.
    #[test]
    fn max_knot_value_matches_the_span_by_span_definition() {
        // the definition: the largest sign * value over both ends of every non-empty span
        fn span_by_span(ev: &Evals, kn: &[f64], p: usize, n: usize, j: usize, sign: f64) -> f64 {
            (p..=n)
                .filter(|&k| kn[k] < kn[k + 1])
                .flat_map(|k| [(k, kn[k]), (k, kn[k + 1])])
                .filter_map(|(k, u)| ev.knot_value(j, k, u))
                .map(|x| sign * x)
                .fold(f64::NEG_INFINITY, f64::max)
        }
        use rand::{Rng, SeedableRng};
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(41);
        let (mut checked, mut found) = (0, 0);
        for _ in 0..3000 {
            let p = r.random_range(1..=5usize);
            let n = p + r.random_range(0..6usize);
            let mut kn: Vec<f64> = (0..n + p + 2)
                .map(|_| r.random_range(0..5) as f64)
                .collect();
            kn.sort_by(f64::total_cmp);
            let pts: Vec<Vec<f64>> = (0..=n)
                .map(|_| vec![r.random_range(-9.0..9.0), r.random_range(-9.0..9.0)])
                .collect();
            let Ok(c) = NurbsCurve::new(p, kn.clone(), pts, None) else {
                continue;
            };
            let ev = Evals::new(&c, &c, 0);
            for j in 0..2 {
                for sign in [1.0, -1.0] {
                    let want = span_by_span(&ev, &kn, p, n, j, sign);
                    let got = ev.max_knot_value(j, sign);
                    // (a clamped end's value is among them: `certify_side` relies on it)
                    let (a, b) = c.domain();
                    for u in [a, b] {
                        if let Some(x) = ev.clamped_end_value(j, u) {
                            assert!(sign * x <= got, "clamped end {u} missing: {kn:?}");
                        }
                    }
                    assert_eq!(
                        got.to_bits(),
                        want.to_bits(),
                        "p {p} {kn:?} j {j} sign {sign}"
                    );
                    checked += 1;
                    found += usize::from(want.is_finite());
                }
            }
        }
        assert!(
            checked > 5000 && found > 1000 && found < checked,
            "{checked} {found}"
        );
        // and at the corners of the f64 range (knots at +-f64::MAX and a few subnormals apart,
        // unclamped vectors), where runs of equal knots sit next to overflowing differences
        let mut r = crate::testkit::gen::rng(43);
        for _ in 0..300 {
            let c = crate::testkit::gen::Family::RangeLimits.curve(&mut r);
            let (kn, p, n) = (c.knots(), c.degree(), c.num_points() - 1);
            let ev = Evals::new(&c, &c, 0);
            for j in 0..c.dim() {
                for sign in [1.0, -1.0] {
                    let want = span_by_span(&ev, kn, p, n, j, sign);
                    assert_eq!(
                        ev.max_knot_value(j, sign).to_bits(),
                        want.to_bits(),
                        "{c:?}"
                    );
                }
            }
        }
    }

    /// The per-coordinate first round of the moderate path ([`first_round`] from the exact
    /// knot values) decides every side exactly as `certify_side` itself does: the same flags
    /// and the same bounds, for `hull`, `bezier` and `newton` on every test family, ties and
    /// jump knots included.
    #[test]
    fn first_round_agrees_with_certify_side() {
        use crate::enclose::{drive_with, strategy_by_name};
        use crate::testkit::gen::{self, Family};
        let mut r = gen::rng(57);
        let (mut sides, mut quick, mut moved) = (0, 0, 0);
        let mut curves: Vec<NurbsCurve> = Vec::new();
        for f in Family::ALL {
            curves.extend((0..25).map(|_| f.curve(&mut r)));
        }
        curves.extend((0..40).map(|_| crate::testkit::ties::tie_curve(&mut r).1));
        for name in ["hull", "bezier", "newton"] {
            let s = strategy_by_name(name, None).unwrap();
            for c in curves.iter().filter(|c| Rescaling::of(c).is_none()) {
                let e0 = drive_with(s.as_ref(), c, false);
                let mut fast = e0.clone();
                certify_with(c, &mut fast, None);
                let mut slow = e0.clone();
                certify_with_first(c, &mut slow, None, false);
                let mut ev = Evals::new(c, c, 0);
                assert_same_certificates(name, c, &fast, &slow);
                for (j, c0) in e0.coords.iter().enumerate() {
                    let scale = c.coord_scale(j);
                    for (sign, bound, inner, wit) in [
                        (1.0, c0.hi, c0.inner_hi, c0.witness_hi),
                        (-1.0, -c0.lo, -c0.inner_lo, -c0.witness_lo),
                    ] {
                        sides += 1;
                        let ex = max_exact(c, j, sign);
                        let q = first_round(bound, inner, wit, ex, (scale, LOWER_WITHIN_ULPS));
                        quick += usize::from(q.is_some());
                    }
                    // bounds moved around the refusal threshold (k ulps of the scale above
                    // the attained value): the first round and the whole side agree
                    if name == "newton" && j == 0 {
                        let u = crate::num::ulp(c0.hi.abs().max(scale));
                        for k in [1.0, 3.0, 5.0, 7.0, 8.5, 9.0, 16.0] {
                            let mut cb = c0.clone();
                            cb.hi = (cb.inner_hi + k * u).max(cb.inner_hi);
                            let ex = max_exact(c, 0, 1.0);
                            let window = (scale, LOWER_WITHIN_ULPS);
                            let q = first_round(cb.hi, cb.inner_hi, cb.witness_hi, ex, window);
                            let mut cv = Curves {
                                dn: &mut ev,
                                up: None,
                            };
                            let full = certify_side(&mut cv, 0, &mut cb, true, &Scaling::NONE);
                            if let Some(x) = q {
                                assert_eq!(x, full, "k {k}: {c:?}");
                                moved += 1;
                            }
                        }
                    }
                }
            }
        }
        // (most sides are decided by the first round: a test that reaches the other branch too)
        assert!(
            sides > 1500 && quick > sides / 2 && quick < sides,
            "{sides} {quick}"
        );
        assert!(moved > 300, "{moved}");
    }

    /// On rescaled curves (extreme magnitudes, the corners of the f64 range) the first round
    /// decided before the scaled copies are built changes no flag and no bound of the full
    /// certificate: `hull`, `bezier` and `newton`.
    #[test]
    fn rescaled_first_round_agrees_with_the_full_certificate() {
        use crate::enclose::{drive_with, strategy_by_name};
        use crate::testkit::gen::{self, Family};
        let mut r = gen::rng(58);
        let mut curves: Vec<NurbsCurve> = Vec::new();
        for f in [Family::ExtremeMagnitudes, Family::RangeLimits] {
            curves.extend((0..40).map(|_| f.curve(&mut r)));
        }
        let (mut sides, mut decided) = (0, 0);
        for name in ["hull", "bezier", "newton"] {
            let s = strategy_by_name(name, None).unwrap();
            for c in &curves {
                let Some(rs) = Rescaling::of(c) else { continue };
                let e0 = drive_with(s.as_ref(), c, false);
                let mut fast = e0.clone();
                certify_with_first(c, &mut fast, Some(&rs), true);
                let mut slow = e0.clone();
                certify_with_first(c, &mut slow, Some(&rs), false);
                assert_same_certificates(name, c, &fast, &slow);
                for (j, c0) in e0.coords.iter().enumerate() {
                    let scale = c.coord_scale(j);
                    for (sign, bound, inner, wit) in [
                        (1.0, c0.hi, c0.inner_hi, c0.witness_hi),
                        (-1.0, -c0.lo, -c0.inner_lo, -c0.witness_lo),
                    ] {
                        sides += 1;
                        let ex = max_exact(c, j, sign);
                        let window = (2.0 * scale, LOWER_WITHIN_ULPS_RESCALED);
                        let attained = attained_rule(bound, inner, wit);
                        let q = first_round(bound, inner, wit, ex, window);
                        decided += usize::from(!attained && q.is_some());
                    }
                }
            }
        }
        assert!(
            sides > 300 && decided > 30 && decided < sides,
            "{sides} {decided}"
        );
    }

    /// The flags and bounds of two certificates of the same enclosure agree, coordinate by
    /// coordinate.
    fn assert_same_certificates(name: &str, c: &NurbsCurve, a: &Enclosure, b: &Enclosure) {
        for (j, (a, b)) in a.coords.iter().zip(&b.coords).enumerate() {
            let what = format!("{name} coordinate {j} of {c:?}");
            assert_eq!(
                (a.optimal_lo, a.optimal_hi),
                (b.optimal_lo, b.optimal_hi),
                "{what}"
            );
            assert_eq!(
                (a.lo.to_bits(), a.hi.to_bits()),
                (b.lo.to_bits(), b.hi.to_bits()),
                "{what}"
            );
        }
    }

    /// The largest sign-adjusted exact knot or end value of coordinate j (the test's own
    /// reduction over [`knot_points`]).
    fn max_exact(c: &NurbsCurve, j: usize, sign: f64) -> f64 {
        let mut m = f64::NEG_INFINITY;
        knot_points(c, |i| m = m.max(sign * c.control_point(i)[j]));
        m
    }

    /// `dyadic_integers` from the bits agrees with exact rationals: every x is its integer
    /// times 2^e0, on signed normals, subnormals, zeros, integers and values near f64::MAX.
    #[test]
    fn dyadic_integers_are_exact() {
        use rand::{Rng, SeedableRng};
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(21);
        for _ in 0..2000 {
            let xs: Vec<f64> = (0..r.random_range(1..6))
                .map(|_| match r.random_range(0..6) {
                    0 => 0.0,
                    1 => f64::from_bits(r.random_range(1..1u64 << 52)),
                    2 => r.random_range(-1000i64..1000) as f64,
                    3 => f64::MAX * r.random_range(-1.0..1.0),
                    _ => f64::from_bits(
                        r.random::<u64>() & !(0x7ffu64 << 52) | (r.random_range(1..2046u64) << 52),
                    ),
                })
                .collect();
            let (ints, e0) = dyadic_integers(xs.iter().copied()).unwrap();
            let scale = if e0 >= 0 {
                BigRational::from_integer(BigInt::one() << e0 as u64)
            } else {
                BigRational::new(BigInt::one(), BigInt::one() << (-e0) as u64)
            };
            for (x, m) in xs.iter().zip(&ints) {
                let q = Exact::of(*x);
                assert_eq!(
                    q.value().unwrap(),
                    &(BigRational::from_integer(m.clone()) * &scale),
                    "{x:e}"
                );
            }
        }
        assert!(dyadic_integers([1.0, f64::NAN].into_iter()).is_none());
    }

    /// The rational double roots of Bernstein polynomials with integer coefficients: a cubic
    /// (3t - 2)^2 (2 - t) (the quadratic f' branch), a quartic (3t - 1)^2 (t - 2)(t + 1)
    /// (Euclid's gcd), none for simple roots (t = 1/2, 3/4) or a linear f'.
    #[test]
    fn rational_double_roots() {
        let b = |v: &[i64]| v.iter().map(|&x| BigInt::from(x)).collect::<Vec<_>>();
        let r = |n: i64, d: i64| BigRational::new(BigInt::from(n), BigInt::from(d));
        assert_eq!(rational_double_root(&b(&[24, -4, -2, 3])), Some(r(2, 3)));
        assert_eq!(
            rational_double_root(&b(&[-24, 9, 20, -36, -96])),
            Some(r(1, 3))
        );
        assert_eq!(rational_double_root(&b(&[18, -5, -2, 3])), None);
        // f = 1 + 3t: f' constant, no root
        assert_eq!(rational_double_root(&b(&[1, 2, 3, 4])), None);
    }

    /// `span_at_most` against the curve itself: on random curves of the test families
    /// (rational ones included), both signs, the level v the median control value: wherever it
    /// says g <= v on a span, the interval value of its piece at 17 parameters of the span has its
    /// lower end <= v (a wrong sign or a missing weight division shows as values above v).
    #[test]
    fn span_at_most_is_a_bound_of_the_piece() {
        use crate::testkit::gen::{self, Family};
        let mut r = gen::rng(37);
        let (mut said, mut checked) = (0, 0);
        for fam in [
            Family::ClampedUniform,
            Family::ExtremeWeights,
            Family::Mixed,
        ] {
            for _ in 0..40 {
                let c = fam.curve(&mut r);
                let h = HSpline::<Interval>::from_curve(&c);
                let kn = c.knots();
                let (p, n) = (c.degree(), c.num_points() - 1);
                for j in 0..c.dim() {
                    let mut vals: Vec<f64> = (0..=n).map(|i| c.control_point(i)[j]).collect();
                    vals.sort_by(f64::total_cmp);
                    for sign in [1.0, -1.0] {
                        let v = sign * vals[vals.len() / 2];
                        for k in (p..=n).filter(|&k| kn[k] < kn[k + 1]) {
                            if !span_at_most(&h, k, j, sign, v) {
                                continue;
                            }
                            said += 1;
                            for i in 0..=16 {
                                let u = kn[k] + (kn[k + 1] - kn[k]) * i as f64 / 16.0;
                                let u = u.clamp(kn[k], kn[k + 1]);
                                // (span k's own piece, also at its right end: a jump
                                // there belongs to the next span's piece)
                                let mut pt = Vec::new();
                                h.eval_span(k, &Interval::from_f64(u), &mut pt);
                                let x = if c.is_rational() {
                                    pt[j] / pt[c.dim()]
                                } else {
                                    pt[j]
                                };
                                let g = if sign > 0.0 { x } else { -x };
                                assert!(g.inf() <= v, "{fam:?} k {k} j {j} sign {sign} i {i} u {u} g [{}, {}] v {v} {}", g.inf(), g.sup(), crate::curve_to_json(&c));
                                checked += 1;
                            }
                        }
                    }
                }
            }
        }
        assert!(said > 50 && checked > 800, "{said} {checked}");
    }

    /// The modular square-free test against exact rational Euclid: polynomials with a squared
    /// factor (a linear one with a rational root, or an irreducible quadratic) times a random
    /// cofactor are never called square-free, whatever the size and sign of their
    /// coefficients (up to ~600 bits, negative ones included: the reduction modulo q); random
    /// polynomials are called square-free exactly when the rational gcd of f and f' is a
    /// constant (the oracle), and the rare "not proved" never hides a double root.
    #[test]
    fn squarefree_mod_prime_matches_rational_euclid() {
        use rand::{Rng, SeedableRng};
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(61);
        let mul = |a: &[BigInt], b: &[BigInt]| -> Vec<BigInt> {
            let mut c = vec![BigInt::from(0); a.len() + b.len() - 1];
            for (i, x) in a.iter().enumerate() {
                for (j, y) in b.iter().enumerate() {
                    c[i + j] += x * y;
                }
            }
            c
        };
        // the degree of gcd(f, f') over Q (Euclid on exact rationals)
        let gcd_degree = |a: &[BigInt]| -> usize {
            let f: Vec<BigRational> = a.iter().cloned().map(BigRational::from_integer).collect();
            let df: Vec<BigRational> = (1..f.len())
                .map(|k| &f[k] * BigRational::from_integer(BigInt::from(k)))
                .collect();
            let d = rational_gcd(f, df).len().saturating_sub(1);
            // (the integer one that `rational_double_root` uses agrees)
            let int = crate::num::sturm::gcd_with_derivative(a);
            assert_eq!(int.len().saturating_sub(1), d, "{a:?}");
            d
        };
        let big = |r: &mut rand_chacha::ChaCha8Rng, bits: u32| -> BigInt {
            let mut x = BigInt::from(r.random_range(-1000i64..=1000));
            for _ in 0..bits / 60 {
                x = (x << 60u32) + BigInt::from(r.random_range(0u64..1 << 60));
            }
            if x.is_zero() {
                BigInt::from(7)
            } else {
                x
            }
        };
        let (mut proved, mut squared) = (0, 0);
        for round in 0..200 {
            let bits = [0, 60, 240, 600][round % 4];
            let deg_h = r.random_range(0..=4usize);
            let h: Vec<BigInt> = (0..=deg_h).map(|_| big(&mut r, bits)).collect();
            if round % 2 == 0 {
                // a squared factor: (v t - u)^2 or (t^2 + c)^2 with c > 0
                let g: Vec<BigInt> = if round % 4 == 0 {
                    vec![-big(&mut r, bits), big(&mut r, bits)]
                } else {
                    vec![
                        num_traits::Signed::abs(&big(&mut r, bits)) + 1,
                        BigInt::from(0),
                        BigInt::from(1),
                    ]
                };
                let f = mul(&mul(&g, &g), &h);
                assert!(!squarefree_mod_prime(&f), "{f:?}");
                squared += 1;
            } else {
                let f: Vec<BigInt> = (0..=r.random_range(2..=8usize))
                    .map(|_| big(&mut r, bits))
                    .collect();
                let sf = squarefree_mod_prime(&f);
                assert_eq!(sf, gcd_degree(&f) == 0, "{f:?}");
                proved += sf as usize;
            }
        }
        assert!(proved >= 95 && squared == 100, "{proved} {squared}");
        // exact small cases: (3t - 1)^2 (t - 2)(t + 1) and t^2 - 2 (irrational simple roots)
        let b = |v: &[i64]| v.iter().map(|&x| BigInt::from(x)).collect::<Vec<_>>();
        assert!(!squarefree_mod_prime(&mul(
            &mul(&b(&[-1, 3]), &b(&[-1, 3])),
            &b(&[-2, -1, 1])
        )));
        assert!(squarefree_mod_prime(&b(&[-2, 0, 1])));
        assert!(squarefree_mod_prime(&b(&[5, 3])));
        assert!(!squarefree_mod_prime(&b(&[0, 0, 0])));
    }

    fn quad(p0: f64, p1: f64, p2: f64) -> NurbsCurve {
        NurbsCurve::new(
            2,
            vec![0., 0., 0., 1., 1., 1.],
            vec![vec![p0], vec![p1], vec![p2]],
            None,
        )
        .unwrap()
    }

    /// The concavity rule on a box that the critical point lies beyond: on g = -1 + 4u - 4u^2
    /// (maximum 0 at u = 1/2, g'' = -8) the boxes [0.6, 0.7] and [0.3, 0.4] have their
    /// maxima g = -0.04 at the end nearer 1/2, where the slope points out of the box. No
    /// tangent pair inside the box brackets the critical point, so only the end-slope rule
    /// decides them (`Undecided` without it); a target below that end value is refuted.
    #[test]
    fn concavity_with_the_critical_point_beyond_the_box() {
        let c = quad(-1.0, 1.0, -1.0);
        let mut ev = Evals::new(&c, &c, 0);
        for (lo, hi) in [(0.6, 0.7), (0.3, 0.4)] {
            let m = lo + 0.5 * (hi - lo);
            let gm = ev.ddi_in(2, 0, 1.0, Ddi::exact(m), 2);
            let at_most =
                |ev: &mut Evals, t: f64| match concave_ddi(ev, 2, 0, 1.0, t, lo, hi, m, &gm) {
                    Concave::Decided(v) => Some(v),
                    _ => None,
                };
            assert_eq!(at_most(&mut ev, -0.03), Some(true), "[{lo}, {hi}]");
            assert_eq!(at_most(&mut ev, -0.05), Some(false), "[{lo}, {hi}]");
        }
    }

    #[test]
    fn exponent_bounds() {
        assert_eq!(exponent_of(1.0), 1);
        assert_eq!(exponent_of(0.75), 0);
        assert_eq!(exponent_of(3.0), 2);
    }

    #[test]
    fn symmetric_quadratic_with_double_maximum_is_certified() {
        // C(u) = 2 * 2u(1-u) * P1: max at u = 1/2 equals P1 exactly (P0 = P2 = 0): a double
        let c = quad(0.0, 0.75, 0.0);
        let mut e = Newton::default().enclose(&c);
        assert!(e.coords[0].optimal_lo);
        // (the strategy's bound may be one ulp above; the lowering proof removes it)
        assert_eq!(e.coords[0].hi, 0.375);
        assert!(e.coords[0].optimal_hi);
        // with the optimal bound (and no attained inner value equal to it) the certificate
        // holds
        e.coords[0].hi = 0.375;
        e.coords[0].inner_hi = 0.375f64.next_down().next_down();
        certify(&c, &mut e);
        assert!(e.coords[0].optimal_hi);
    }

    #[test]
    fn ends_and_a_tiny_double_maximum() {
        // P0 = P2 = -1, P1 = 1 + eps: min -1 at both (clamped) ends, max C(1/2) = eps / 2
        let c = quad(-1.0, 1.0 + f64::EPSILON, -1.0);
        let e = Newton::default().enclose(&c);
        assert_eq!(e.coords[0].lo, -1.0);
        assert!(e.coords[0].optimal_lo);
        assert_eq!(e.coords[0].hi, f64::EPSILON / 2.0);
        assert!(e.coords[0].optimal_hi);
    }

    #[test]
    fn near_tie_decided_by_the_exact_stage() {
        // P0 = 3 d, P1 = 1, P2 = d with d = 2^-110: the maximum is about 1/2 + 2^-111 at a
        // non-dyadic u* near 1/2, so RU(max) = next_up(1/2), and only a value within ~2^-111
        // of the maximum proves it (double-double enclosures are ~2^-100 wide).
        let d = 2f64.powi(-110);
        let c = quad(3.0 * d, 1.0, d);
        let e = Newton::default().enclose(&c);
        let cb = &e.coords[0];
        if cb.hi == 0.5f64.next_up() {
            assert!(cb.optimal_hi, "exact stage must decide the near-tie");
        } else {
            assert!(!cb.optimal_hi);
        }
        // the certificate by itself, on a box with the optimal bound
        let mut forced = e.clone();
        forced.coords[0].hi = 0.5f64.next_up();
        forced.coords[0].inner_hi = 0.5;
        certify(&c, &mut forced);
        assert!(forced.coords[0].optimal_hi);
        // a bound a few ulps too high is lowered (max <= next_up(1/2) proved), then certified
        forced.coords[0].hi = 0.5f64.next_up().next_up().next_up();
        forced.coords[0].optimal_hi = false;
        certify(&c, &mut forced);
        assert_eq!(forced.coords[0].hi, 0.5f64.next_up());
        assert!(forced.coords[0].optimal_hi);
    }

    /// The exact Bernstein rule decides exact ties both ways: a symmetric quadratic with the
    /// double maximum 3/8 at u = 1/2 is <= 3/8 (the double root of f = g - 3/8 is split at),
    /// not <= next_down(3/8); a symmetric cubic likewise (maximum (a + 3b)/4 at u = 1/2, hit
    /// by the exact Newton step rounded to a dyadic grid); a quadratic whose maximiser
    /// 1/3 is no double (P0 = 0, P1 = 1, P2 = -1: C = 2u(1-u) - u^2, max 1/3 at u = 1/3)
    /// is <= RU(1/3) and not <= RD(1/3).
    #[test]
    fn exact_bernstein_rule_decides_ties() {
        let cubic = |a: f64, b: f64| {
            NurbsCurve::new(
                3,
                vec![0., 0., 0., 0., 1., 1., 1., 1.],
                vec![vec![a], vec![b], vec![b], vec![a]],
                None,
            )
            .unwrap()
        };
        // 1/3 rounds down in f64 (binary 0.0101...01|0101...)
        let (third_dn, third_up) = (1.0f64 / 3.0, (1.0f64 / 3.0).next_up());
        let cases = [
            (quad(0.0, 0.75, 0.0), 0.375, 0.375f64.next_down()),
            (cubic(-1.0, 3.0), 2.0, 2.0f64.next_down()),
            (quad(0.0, 1.0, -1.0), third_up, third_dn),
        ];
        for (c, good, bad) in cases {
            let mut ev = Evals::new(&c, &c, 0);
            assert_eq!(
                exact_bernstein_rule(&mut ev, c.degree(), 0, 1.0, good),
                Some(true)
            );
            assert_eq!(
                exact_bernstein_rule(&mut ev, c.degree(), 0, 1.0, bad),
                Some(false)
            );
            // and the minimum side of -C (sign -1)
            let neg = NurbsCurve::new(
                c.degree(),
                c.knots().to_vec(),
                (0..c.num_points())
                    .map(|i| vec![-c.control_point(i)[0]])
                    .collect(),
                None,
            )
            .unwrap();
            let mut ev = Evals::new(&neg, &neg, 0);
            assert_eq!(
                exact_bernstein_rule(&mut ev, c.degree(), 0, -1.0, good),
                Some(true),
                "{good}"
            );
        }
    }

    /// The direct integer coefficients of a Bézier span are the exact segment's (from exact
    /// knot insertion) times one positive factor, for a rational curve and either side.
    /// Integers N_i with f_i = N_i / D for one D > 0 (the least common multiple of the
    /// denominators); `None` if some value is undefined.
    fn integer_numerators(f: &[Exact]) -> Option<Vec<BigInt>> {
        let vals: Vec<&BigRational> = f.iter().map(Exact::value).collect::<Option<_>>()?;
        let d = vals.iter().fold(BigInt::one(), |acc, q| acc.lcm(q.denom()));
        Some(vals.iter().map(|q| q.numer() * (&d / q.denom())).collect())
    }

    /// The fraction-free integer extraction equals the rational one of `HSpline<Exact>` up to
    /// one positive factor (every ratio and every sign), on the spans of rational and
    /// polynomial splines of degree 2 to 5 with irregular, multiple and unclamped knots.
    /// The sign rule on long coefficients (which it rounds up) against exact values of f:
    /// every `AtMost` holds at 65 rational points of [0, 1], every `Above(s)` has f(s) > 0
    /// exactly (and no refutation where only the rounded coefficients are positive).
    /// Coefficients spread over ~2,100 bits as at the range limits (a value -1/2
    /// next to -2^1023 and a subnormal one), and the piece the rule's old rounding (256 bits
    /// below the largest coefficient) left undecided: f = (-tiny, -1/2, 13/16, -2^1023) in
    /// units of 2^-1074 is <= 0 on [0, 1] and is proved so.
    #[test]
    fn the_sign_rule_on_long_coefficients_agrees_with_exact_values() {
        use rand::Rng;
        let big = |e: u64, m: i64| BigInt::from(m) << e;
        let fi = vec![big(0, -5), big(1073, -1), big(1070, 13), big(2097, -1)];
        assert!(matches!(sign_rule(fi), Rule::AtMost));
        // (-K - 3, K + 2, -K - 3), K = 2^2000: f(1/2) = -1/2 < 0, but from the coefficients
        // rounded up, f(1/2) > 0: no refutation there without the exact check
        let k = big(2000, 1);
        let fi = vec![-&k - 3, &k + 2, -&k - 3];
        if let Rule::Above(x) = sign_rule(fi.clone()) {
            assert_eq!(eval_integer(&fi, &x).0.sign(), Sign::Plus, "refuted at {x}");
        }
        let mut r = crate::testkit::gen::rng(23);
        let (mut at_most, mut above) = (0, 0);
        for _ in 0..300 {
            let p = r.random_range(2..=4);
            let fi: Vec<BigInt> = (0..=p)
                .map(|_| {
                    let m: i64 = r.random_range(-1_000_000..1_000_000);
                    big(r.random_range(0..2100), m)
                })
                .collect();
            match sign_rule(fi.clone()) {
                Rule::AtMost => {
                    at_most += 1;
                    for i in 0..=64u32 {
                        let x = BigRational::new(BigInt::from(i), BigInt::from(64));
                        assert!(
                            eval_integer(&fi, &x).0.sign() != Sign::Plus,
                            "{fi:?} at {i}/64"
                        );
                    }
                }
                Rule::Above(x) => {
                    above += 1;
                    assert_eq!(eval_integer(&fi, &x).0.sign(), Sign::Plus, "{fi:?} at {x}");
                }
                Rule::Undecided => {}
            }
        }
        assert!(
            at_most > 20 && above > 20,
            "{at_most} proved, {above} refuted"
        );
    }

    #[test]
    fn fraction_free_coefficients_match_the_exact_segment() {
        use rand::{Rng, SeedableRng};
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let mut spans = 0;
        for it in 0..60 {
            let p = 2 + it % 4;
            let n = p + r.random_range(0..4);
            let mut kn: Vec<f64> = (0..n + p + 2).map(|_| r.random_range(-3.0..5.0)).collect();
            kn.sort_by(f64::total_cmp);
            if it % 3 == 0 {
                // a double interior knot and clamped ends
                kn[n / 2 + 1] = kn[n / 2];
                for i in 0..=p {
                    kn[i] = kn[p];
                    let m = kn.len() - 1 - i;
                    kn[m] = kn[n + 1];
                }
            }
            let pts: Vec<Vec<f64>> = (0..=n)
                .map(|_| vec![r.random_range(-2.0..2.0), r.random_range(-1e3..1e3)])
                .collect();
            let w = (it % 2 == 0).then(|| (0..=n).map(|_| r.random_range(0.1..4.0)).collect());
            let Ok(c) = NurbsCurve::new(p, kn, pts, w) else {
                continue;
            };
            let h: HSpline<Exact> = HSpline::from_curve(&c);
            for k in p..=n {
                if c.knots()[k] >= c.knots()[k + 1] {
                    continue;
                }
                let seg = h.bezier_segment(k);
                let hd = seg.hdim();
                for (j, sign, t) in [(0, 1.0, 0.25), (1, -1.0, -17.5)] {
                    let d = bezier_coefficients_fraction_free(&c, k, j, sign, t).unwrap();
                    let f: Vec<Exact> = (0..=p)
                        .map(|i| {
                            let a = seg.pts[i * hd + j].clone();
                            let a = if sign < 0.0 { -a } else { a };
                            let w = if seg.rational {
                                seg.pts[i * hd + 2].clone()
                            } else {
                                Exact::of(1.0)
                            };
                            a - Exact::of(t) * w
                        })
                        .collect();
                    let e = integer_numerators(&f).unwrap();
                    // one positive factor: equal signs and equal cross products
                    let l = (0..=p).find(|&i| e[i].sign() != Sign::NoSign).unwrap();
                    for i in 0..=p {
                        assert_eq!(d[i].sign(), e[i].sign(), "span {k} b_{i}");
                        assert_eq!(&d[i] * &e[l], &e[i] * &d[l], "span {k} b_{i}");
                    }
                    spans += 1;
                }
            }
        }
        assert!(spans > 100, "only {spans} spans checked");
    }

    /// An exact tie at an interior knot (a symmetric quintic, `extrema_at_knots`: the maximum
    /// 1.9312094010166787 of x is attained at the double knot u = 0, where C' = 0): a box
    /// ending at the knot holds the maximiser, whose double-double value straddles the
    /// target. Without exact tries the box is stuck at once (no halving to the depth limit);
    /// with them the exact concavity rule proves it.
    #[test]
    fn tie_at_a_knot_is_stuck_without_exact_tries_and_proved_with_them() {
        let pts = [
            [-0.9143550990509568, -0.8517801029854772],
            [0.937797423850653, 0.9491875263731124],
            [-0.9019469390372032, -0.2612406701040677],
            [2.875594847701306, 0.4219571279133927],
        ];
        let pts: Vec<Vec<f64>> = pts
            .iter()
            .chain(pts.iter().rev())
            .map(|x| x.to_vec())
            .collect();
        let mut kn = vec![-1.0; 6];
        kn.extend([0.0, 0.0]);
        kn.extend([1.0; 6]);
        let c = NurbsCurve::new(5, kn, pts, None).unwrap();
        let t = 1.9312094010166787;
        let mut ev = Evals::new(&c, &c, 0);
        // (exact tries used up, then none used)
        for (tries, stuck) in [(MAX_EXACT_TRIES, true), (0, false)] {
            let mut budget = ExactBudget { tries, points: 0 };
            let v = box_at_most(
                &mut ev,
                5,
                0,
                1.0,
                (t, t),
                -0.015625,
                0.0,
                true,
                &mut budget,
            );
            assert!(if stuck {
                matches!(v, BoxVerdict::Stuck)
            } else {
                matches!(v, BoxVerdict::Below)
            });
        }
        // and the certificate of the whole curve holds
        let e = Newton::default().enclose(&c);
        assert_eq!(e.coords[0].hi, t);
        assert!(e.coords[0].optimal_hi);
    }

    /// The cost guard of exact arithmetic: a subnormal knot (a 2^-1072 bit) or one near
    /// f64::MAX makes exact values of the spans next to it unavailable (rationals of thousands
    /// of bits), ordinary knots do not; the Bernstein rule's guard likewise.
    #[test]
    fn exact_values_are_refused_next_to_range_limit_knots() {
        assert!(short_dyadic(0.1) && short_dyadic(0.0) && short_dyadic(-3.5e50));
        assert!(!short_dyadic(6e-323) && !short_dyadic(f64::MAX) && !short_dyadic(1e-200));
        let mut kn = vec![0.0; 3];
        kn.extend([6e-323, 0.5, 0.75]);
        kn.extend([1.0; 3]);
        let pts: Vec<Vec<f64>> = (0..6).map(|i| vec![i as f64, 1.0]).collect();
        let c = NurbsCurve::new(2, kn, pts, None).unwrap();
        let u = Exact::of(0.6);
        // span [0.5, 0.75] (k = 4) reads knots 6e-323 .. 1; span [0.75, 1] (k = 5) does not
        assert!(!exact_value_is_cheap(&c, 4, 0, &u));
        assert!(exact_value_is_cheap(&c, 5, 0, &Exact::of(0.8)));
        assert!(!exact_is_cheap(&c, 4, 0, 0.5));
        let mut ev = Evals::new(&c, &c, 0);
        assert!(ev.exact_in(4, 0, 1.0, &u, 0).is_none());
        assert!(ev.exact_in(5, 0, 1.0, &Exact::of(0.8), 0).is_some());
        // at most MAX_EXACT_EVALS per evaluated curve (one used above)
        for _ in 1..MAX_EXACT_EVALS {
            assert!(ev.exact_in(5, 0, 1.0, &Exact::of(0.8), 0).is_some());
        }
        assert!(ev.exact_in(5, 0, 1.0, &Exact::of(0.8), 0).is_none());
        // a control value with a subnormal bit (or near f64::MAX) in the span's coordinate j
        // refuses that coordinate only
        let pts: Vec<Vec<f64>> = (0..6)
            .map(|i| vec![if i == 4 { 1e-320 } else { i as f64 }, 1.0])
            .collect();
        let mut kn = vec![0.0; 3];
        kn.extend([0.25, 0.5, 0.75]);
        kn.extend([1.0; 3]);
        let c = NurbsCurve::new(2, kn, pts, None).unwrap();
        let u = Exact::of(0.8);
        assert!(!exact_value_is_cheap(&c, 5, 0, &u));
        assert!(exact_value_is_cheap(&c, 5, 1, &u));
        // (span k = 3, [0.25, 0.5], has control points 1..=3)
        assert!(exact_value_is_cheap(&c, 3, 0, &Exact::of(0.3)));
    }

    /// The box-end exact values of a lowering proof ([`MAX_EXACT_POINTS`]): a monotone box
    /// whose end value equals the target exactly, a double reached at the non-dyadic local
    /// parameter 1/3 (so its double-double enclosure holds the target), is decided below the
    /// target by an exact value while the budget lasts, and left stuck when it is spent.
    #[test]
    fn box_end_exact_values_stop_at_their_budget() {
        // x(u) = 9 (u / 3)^2 on [0, 3]: x(1) = 1 exactly, increasing
        let c = NurbsCurve::new(
            2,
            vec![0.0, 0.0, 0.0, 3.0, 3.0, 3.0],
            vec![vec![0.0], vec![0.0], vec![9.0]],
            None,
        )
        .unwrap();
        let mut ev = Evals::new(&c, &c, 0);
        for (points, below) in [(0, true), (MAX_EXACT_POINTS, false)] {
            let mut budget = ExactBudget { tries: 0, points };
            let v = box_at_most(&mut ev, 2, 0, 1.0, (1.0, 1.0), 0.5, 1.0, true, &mut budget);
            assert!(
                if below {
                    matches!(v, BoxVerdict::Below) && budget.points == 1
                } else {
                    matches!(v, BoxVerdict::Stuck) && budget.points == MAX_EXACT_POINTS
                },
                "points {points}: {v:?}"
            );
        }
    }
}
