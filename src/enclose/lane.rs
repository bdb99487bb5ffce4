//! The driver's lane for the commonest input: one clamped polynomial Bézier segment of degree
//! 1 to 5 (a line, a font's quadratic, a cubic Bézier) with moderate magnitudes, a polynomial
//! spline of degree 2 to 5 with moderate knots, a rational curve of degree 2 to 5 (one clamped
//! segment or a spline: conic arcs, a NURBS circle, rational cubics) with moderate weights
//! (splines clamped or not: an unclamped spline's end values are those of its end spans, for
//! `bezier` and `newton`; `hull`'s lane takes clamped curves), and any polyline
//! (degree 1, rational or not, clamped or not, jumps at double knots, any magnitude)
//! ([`Simple::of`]).
//! Such a curve needs none of the general machinery (rescaling, the curve-wide Bézier sweep,
//! the per-curve search state), so the driver answers it here directly, with the same
//! guarantees and the same reasoning as the general path, and for a polynomial segment up to
//! degree 3 or a single conic arc without any heap allocation:
//!
//! * **`hull`** ([`Lane::Hull`]): the box of the control points (convex hull property, thesis
//!   prop. 2.1; exact), the end control points as attained values (a clamped end is a control
//!   point: `NurbsCurve::clamped_ends`).
//! * **`bezier` and `newton`** ([`Lane::Tight`]): per coordinate side first the cheap exit (the
//!   extreme control value is an end value: exact and attained), on a polyline the extreme
//!   control value itself (a curve value at a knot, or its left limit at a jump:
//!   `polyline_side`), else the root-isolating proof
//!   of the `bezier` strategy's fast path (`bezier::single`, degree 2 and 3: f64 root estimates
//!   of C_j', proven derivative signs at test points by an f64 filter with an a-priori error
//!   bound, root counting, a double-double Taylor enclosure over each tiny bracket; degree 4
//!   and 5: the same proof with the zeros of C_j' counted by the sign changes of its Bernstein
//!   coefficients, `bezier::single`'s quartic and quintic route, and where that fails its
//!   general fast path, `bezier::coefficient_side`, the zeros of C_j' located by
//!   Bernstein subdivision with proven sign counts; a rational conic: `bezier::conic`, the
//!   same root isolation on the quadratic numerator of C_j' = N / W^2 and a mean value bound
//!   over each bracket; a rational curve of degree 3 to 5: the general fast path on the
//!   homogeneous rows, its numerator N of degree 2p - 2), on splines only for the spans that
//!   f64 Bézier coefficients with an a-priori bound leave open (`spline_side`). Where that proof
//!   does not give a bound within two ulps of the coordinate scale, the lane returns `None` and
//!   the general path runs (`Stats::fast_fallbacks` counts it there).
//!
//! The driver's facts are applied as in [`super::drive_with`]: outer bounds clamped to the
//! control-point box, a clamped curve's end values attained, inner bounds consistent with
//! outer ones. The
//! optimality certificate's first rule (an attained value equal to the bound, or a strict
//! witness above the next double down) and its cheap refusal (the strategy's own attained
//! value more than a few ulps of the scale below its bound: `certify::quick`) are decided
//! here; any side they leave open goes to the full certification (`certify::certify`), so the
//! flags are those of the general path.

use super::bezier::conic::{conic_sides, ConicSeg};
use super::bezier::rational::{rational_sides_into, RationalSeg};
use super::bezier::single::{
    descartes_sides_into, extremum, f64_sides, raw_sides_into, RawSide, Segment,
};
use super::bezier::{span_bounds, CoefficientProof};
use super::driver::apply_facts;
use super::driver::{pow2, COORD_WINDOW};
use super::Termination;
use super::{certify, CandidateKind, Clock, CoordBox, Enclosure, Extrema, Extremum};
use crate::num::ddi::Ddi;
use crate::num::Scalar;
use crate::spline::bspline::clamp_span;
use crate::spline::curve::NurbsCurve;
use smallvec::SmallVec;

/// Which answer a strategy gives on a [`Simple`] curve.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Lane {
    /// the control-point box (`hull`)
    Hull,
    /// the tight verified box (`bezier`, `newton`)
    Tight,
}

/// The domain ends must lie below 2^KNOT_EXP in magnitude (their difference stays finite).
const KNOT_EXP: i32 = 1000;

/// The highest degree the lane takes (polynomial segments and splines; above degree 3 every
/// span goes through the general fast path's proof, `bezier::coefficient_side`).
pub const LANE_MAX_DEGREE: usize = 5;

/// A curve the lane takes: one clamped polynomial Bézier segment of degree 1..=5 over [a, b],
/// a polynomial spline of degree 2..=5 (clamped or not), or a rational curve of degree 2..=5
/// (one clamped segment or a spline, moderate weights), every coordinate moderate; or a
/// polyline.
#[derive(Debug, Clone, Copy)]
pub struct Simple<'a> {
    curve: &'a NurbsCurve,
    p: usize,
    /// the last control point's index (n = p: a single segment)
    n: usize,
    d: usize,
    a: f64,
    b: f64,
    /// whether the end control points are the curve's end values (a clamped curve, or a
    /// polyline with non-empty end spans); an unclamped spline's ends are values of its end
    /// spans, which only the tight lane reads (`hull`'s lane takes clamped curves alone)
    clamped: bool,
    pts: &'a [f64],
    /// the weights of a rational curve of degree 2 to 5, `None` otherwise (a rational
    /// polyline's weights are not needed: its bounds are control values)
    w: Option<&'a [f64]>,
    knots: &'a [f64],
    /// per coordinate the exact control-point range (min, max)
    range: [(f64, f64); MAX_DIM],
    /// per coordinate the first indices of the smallest and of the largest control value
    extreme_at: [(usize, usize); MAX_DIM],
}

impl Simple<'_> {
    /// The rows per point of [`span_coefficients_rows`]: the coordinates, and a rational
    /// spline's weights.
    #[inline]
    fn stride(&self) -> usize {
        self.d + self.w.is_some() as usize
    }
}

/// Whether an interior knot of the spline's domain [u_p, u_{n+1}] has multiplicity above p (a
/// run of p + 1 equal knots in u_p ..= u_{n+1} that ends before u_{n+1}): the knots do not
/// decrease, so u_i = u_{i+p} says that u_i ..= u_{i+p} are equal. One comparison per knot
/// without a branch (i = p ..= n + 1 - p; none where n + 1 < 2p), where counting the runs
/// took a dependent jump per knot (`jump_knot_matches_the_run_count`).
#[inline]
fn jump_knot(k: &[f64], p: usize, n: usize) -> bool {
    let b = k[n + 1];
    let m = (n + 2).saturating_sub(2 * p);
    let (lo, hi) = (&k[p..p + m], &k[2 * p..2 * p + m]);
    lo.iter()
        .zip(hi)
        .fold(false, |any, (&x, &y)| any | ((x == y) & (y < b)))
}

/// `exponent(x) > KNOT_EXP` (`driver::exponent`: |x| in [2^(e-1), 2^e)) as one comparison with
/// a power of two: |x| >= 2^KNOT_EXP (exact).
#[inline]
fn beyond_knot_window(x: f64) -> bool {
    const LIMIT: f64 = pow2(KNOT_EXP);
    x.abs() >= LIMIT
}

/// `exponent(m).abs() > COORD_WINDOW` for m > 0 as two comparisons with powers of two:
/// e > W iff m >= 2^W, e < -W iff m < 2^(-W-1) (exact; subnormal m lie below).
#[inline]
fn beyond_coord_window(m: f64) -> bool {
    const HI: f64 = pow2(COORD_WINDOW);
    const LO: f64 = pow2(-COORD_WINDOW - 1);
    !(LO..HI).contains(&m)
}

/// The lane takes curves of dimension up to this (the result's inline storage holds three).
pub(crate) const MAX_DIM: usize = 4;

/// A rational curve's weights must lie in [2^-WEIGHT_EXP, 2^WEIGHT_EXP) ([`Simple::of`]).
const WEIGHT_EXP: i32 = 100;

/// A rational curve's largest weight is at most 2^WEIGHT_SPREAD times its smallest
/// ([`Simple::of`]).
const WEIGHT_SPREAD: i32 = 12;

impl<'a> Simple<'a> {
    /// The curve as a [`Simple`] one, or `None`: rational (degree 2 to 5) with a weight
    /// outside [2^-100, 2^100) or weights spread over more than 2^12,
    /// degree above [`LANE_MAX_DEGREE`], dimension above [`MAX_DIM`], extreme magnitudes; and a curve of
    /// several spans unless it is a continuous (interior knot multiplicities at most p) spline
    /// of degree 2 to [`LANE_MAX_DEGREE`] with moderate knots (clamped or not; a single segment
    /// must be clamped).
    #[inline]
    pub fn of(c: &'a NurbsCurve) -> Option<Simple<'a>> {
        let p = c.degree();
        let k = c.knots();
        let n = c.num_points() - 1;
        if !(1..=LANE_MAX_DEGREE).contains(&p) || n < p {
            return None;
        }
        // A rational curve (degree 2 to 5, one segment or a spline): every weight within
        // [2^-WEIGHT_EXP, 2^WEIGHT_EXP) (exact comparisons with powers of two; a NaN fails),
        // so that the homogeneous coefficients and their products stay far from overflow and
        // underflow with the coordinates' window; and the largest weight at most
        // 2^WEIGHT_SPREAD times the smallest (the conic proof's correction grows with the
        // square of that ratio, the f64 filter's quotient bound with the ratio: beyond it the
        // general path, whose enclosures do not, answers).
        let w = match c.weights() {
            Some(w) if p >= 2 => {
                const LO: f64 = pow2(-WEIGHT_EXP);
                const HI: f64 = pow2(WEIGHT_EXP);
                const SPREAD: f64 = pow2(WEIGHT_SPREAD);
                let (lo, hi) = w
                    .iter()
                    .fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
                // (lo * SPREAD is exact: a power of two times a double far from the extremes)
                if !(lo >= LO && hi < HI && hi <= lo * SPREAD) {
                    return None;
                }
                Some(w)
            }
            _ => None,
        };
        let ((a, b), clamped) = if p == 1 {
            // A polyline (degree 1, weights or not, clamped or not): on span [u_i, u_{i+1}]
            // the curve is (w_{i-1} P_{i-1} N_{i-1,1} + w_i P_i N_{i,1}) / (w_{i-1} N_{i-1,1} +
            // w_i N_{i,1}) with N_{i-1,1} = (u_{i+1} - u) / (u_{i+1} - u_i), N_{i,1} = 1 - that,
            // both >= 0: with positive weights a convex combination of P_{i-1} and P_i moving
            // from one to the other (the segment between them, each coordinate monotone), and
            // C(u_{i+1}) = P_i exactly where u_{i+1} < u_{i+2} (NURBS Book eq. 2.5 and 4.2).
            // At a double knot u_{i+1} = u_{i+2} (multiplicity p + 1, a jump) P_i is the left
            // limit there, approached strictly monotonically from P_{i-1} (attained at u_i <
            // u_{i+1}), and C(u_{i+1}) = P_{i+1}. Taken: the domain [u_1, u_{n+1}] with
            // non-empty end spans (P_0 = C(a), P_n = C(b)) and no interior knot of multiplicity
            // above 2 (a triple knot would leave a control point that the curve never
            // approaches). Then every control point is a value of the curve or such a limit,
            // and every value lies between two of them: the box is the control-point box,
            // each bound a control value (`polyline_side`). Only the knot values are read (no
            // arithmetic), so no magnitude window applies.
            let (a, b) = (k[1], k[n + 1]);
            if !(k[1] < k[2] && k[n] < k[n + 1])
                || k[1..=n + 1].windows(3).any(|w| w[0] == w[2])
                || k[1..=n + 1].windows(2).any(|w| w[1] < w[0])
            {
                return None;
            }
            ((a, b), true)
        } else {
            // the domain [u_p, u_{n+1}], a < b (validation guarantees a non-empty domain;
            // checked again, as every other assumption here); clamped: knots a^(p+1) ...
            // b^(p+1). An unclamped curve only as a spline (n > p), whose spans p ..= n read the
            // knots u_0 .. u_{n+p+1} and the control points as a clamped spline's do (Boehm's
            // insertion and the closed forms are the same), its end values b_0 of span p and
            // b_p of span n, not control points.
            let (a, b) = (k[p], k[n + 1]);
            if a >= b || a.is_nan() {
                return None;
            }
            let clamped = k[0] == a && k[k.len() - 1] == b;
            if !clamped && n == p {
                return None;
            }
            ((a, b), clamped)
        };
        if p == 1 {
            // (the polyline above: nothing more to check)
        } else if n == p {
            if beyond_knot_window(a) || beyond_knot_window(b) {
                return None;
            }
        } else {
            // a spline: degree 2 to LANE_MAX_DEGREE, no interior knot of multiplicity above p
            // (so the curve is continuous and both end coefficients of every span are curve
            // values), knots that the driver would not rescale (every knot difference is finite
            // and normal enough for the a-priori bound of the f64 span coefficients)
            if super::driver::knot_scaling(c) != (0, true) {
                return None;
            }
            if jump_knot(k, p, n) {
                return None;
            }
        }
        let d = c.dim();
        if d > MAX_DIM {
            return None;
        }
        let pts = c.points_flat();
        let mut range = [(0.0, 0.0); MAX_DIM];
        let mut extreme_at = [(0, 0); MAX_DIM];
        // (the scan with the dimension a compile-time constant: the loop over a point's
        // coordinates unrolled, no index arithmetic per value)
        match d {
            1 => scan::<1>(pts, &mut range, &mut extreme_at),
            2 => scan::<2>(pts, &mut range, &mut extreme_at),
            3 => scan::<3>(pts, &mut range, &mut extreme_at),
            4 => scan::<4>(pts, &mut range, &mut extreme_at),
            _ => return None,
        }
        for &(lo, hi) in &range[..d] {
            let m = if -lo > hi { -lo } else { hi };
            // (a NaN or infinite coordinate is rejected by validation; checked again; a
            // polyline's bounds are control values, exact at any magnitude)
            if !m.is_finite() || (p > 1 && m != 0.0 && beyond_coord_window(m)) {
                return None;
            }
        }
        Some(Simple {
            curve: c,
            p,
            n,
            d,
            a,
            b,
            clamped,
            pts,
            w,
            knots: k,
            range,
            extreme_at,
        })
    }
}

/// Per coordinate of the points `pts` (D coordinates each, at least one point) the range
/// (min, max) and the first indices of the smallest and of the largest value.
///
/// Without branches on the data: on random curves whether a point is a new minimum is a coin
/// toss, and the mispredicted branches of a compare-and-jump scan cost more than the rest of
/// the `hull` lane. The running min (max) is `if x < lo { x } else { lo }`, the select that
/// x86's `minsd` computes (the first strict minimum is kept, a later equal value, also the
/// other zero, is not: the same as the jump); its index is taken by a bit mask. The result is
/// the same as that of the compare-and-jump scan, bit for bit
/// (`scan_matches_the_compare_and_jump_scan`).
#[inline]
fn scan<const D: usize>(
    pts: &[f64],
    range: &mut [(f64, f64); MAX_DIM],
    extreme_at: &mut [(usize, usize); MAX_DIM],
) {
    let (first, rest) = pts.split_at(D);
    let (mut lo, mut hi) = ([0.0f64; D], [0.0f64; D]);
    lo.copy_from_slice(first);
    hi.copy_from_slice(first);
    let (mut ilo, mut ihi) = ([0usize; D], [0usize; D]);
    // (the mask of a condition: all ones if it holds, else 0)
    let mask = |b: bool| (b as usize).wrapping_neg();
    for (i, q) in rest.chunks_exact(D).enumerate() {
        for j in 0..D {
            let x = q[j];
            let (below, above) = (x < lo[j], x > hi[j]);
            lo[j] = if below { x } else { lo[j] };
            hi[j] = if above { x } else { hi[j] };
            ilo[j] ^= (ilo[j] ^ (i + 1)) & mask(below);
            ihi[j] ^= (ihi[j] ^ (i + 1)) & mask(above);
        }
    }
    for j in 0..D {
        range[j] = (lo[j], hi[j]);
        extreme_at[j] = (ilo[j], ihi[j]);
    }
}

/// Writes one side of a coordinate box in place, sign-adjusted (the min side is the max side
/// of -C_j): `sign` 1 sets `hi`, `inner_hi`, `witness_hi`, -1 sets `lo`, `inner_lo`,
/// `witness_lo` to the negated values, and adds the counters [fast_exits, fast_proofs,
/// derivative_evaluations, point_evaluations] to the box's stats. (In place rather than
/// returned: the moves of a returned side and its candidates through the stack, read back by
/// wide loads from narrow stores, cost more than the cheap exits themselves.)
#[inline]
fn put(
    cb: &mut CoordBox,
    sign: f64,
    (upper, attained, witness): (f64, f64, f64),
    counts: [u32; 4],
) {
    if sign > 0.0 {
        cb.hi = upper;
        cb.inner_hi = attained;
        cb.witness_hi = witness;
    } else {
        cb.lo = -upper;
        cb.inner_lo = -attained;
        cb.witness_lo = -witness;
    }
    let st = &mut cb.stats;
    st.fast_exits += counts[0] as u64;
    st.fast_proofs += counts[1] as u64;
    st.derivative_evaluations += counts[2] as u64;
    st.point_evaluations += counts[3] as u64;
}

/// The candidate list of the side `sign` of a coordinate box (`argmax` for 1, `argmin` for -1).
#[inline]
fn args_of(cb: &mut CoordBox, sign: f64) -> &mut Extrema {
    if sign > 0.0 {
        &mut cb.argmax
    } else {
        &mut cb.argmin
    }
}

/// The end-point extremum at parameter u.
fn end(u: f64) -> Extremum {
    Extremum {
        u_lo: u,
        u_hi: u,
        unique: false,
        kind: CandidateKind::EndPoint,
    }
}

/// The cheap exit for the side `sign` (1: max, -1: min) of coordinate j: the extreme control
/// value is an end value (exact and attained at a clamped end; convex hull property, thesis
/// prop. 2.1): the sign-adjusted value and the end's parameter, or `None`.
#[inline]
fn cheap_exit(s: &Simple, j: usize, sign: f64) -> Option<(f64, f64)> {
    let (lo, hi) = s.range[j];
    let m = if sign > 0.0 { hi } else { -lo };
    // (both tests evaluated and combined without jumps: whether an end holds the extreme
    // control value is a coin toss on random curves)
    let (first, last) = (sign * s.pts[j] == m, sign * s.pts[s.n * s.d + j] == m);
    let u = if first { s.a } else { s.b };
    // (an unclamped spline's end control points are no curve values)
    ((first | last) & s.clamped).then_some((m, u))
}

/// The side `sign` of `cb` from its cheap exit (m, u) ([`cheap_exit`]): `fast_exits`.
fn put_exit(cb: &mut CoordBox, sign: f64, (m, u): (f64, f64)) {
    put(cb, sign, (m, m, f64::NEG_INFINITY), [1, 0, 0, 0]);
    args_of(cb, sign).push(end(u));
}

/// The candidates of a side whose bound reaches its attained value, or the whole domain,
/// appended to `args` (empty).
fn reaching<'e>(
    s: &Simple,
    attained: f64,
    cands: impl Iterator<Item = &'e (f64, Extremum)>,
    args: &mut Extrema,
) {
    for (x, e) in cands {
        // (a knot that ends one proved span and starts the next is the same candidate twice:
        // kept once, so that the usual single candidate stays in the box's inline room)
        if *x >= attained && !args.contains(e) {
            args.push(*e);
        }
    }
    if args.is_empty() {
        args.push(unresolved(s));
    }
}

/// The whole domain as an unresolved candidate (a side none of whose candidates reaches its
/// attained value).
#[inline]
fn unresolved(s: &Simple) -> Extremum {
    Extremum {
        u_lo: s.a,
        u_hi: s.b,
        unique: false,
        kind: CandidateKind::Unresolved,
    }
}

/// The side `sign` (1: max, -1: min) of coordinate j of a polyline (degree 1, see
/// [`Simple::of`]): the bound is the extreme control value m (exact; every value of the curve
/// lies between two control values). Each control point P_i with value m is a candidate at
/// the knot u_{i+1} (a domain end, or a knot of multiplicity >= p = 1). P_i is attained there
/// unless u_{i+1} = u_{i+2} < b, where it is the left limit at a jump: if no control point
/// with value m is attained, the curve still comes arbitrarily close to m from below (the
/// segment from the attained P_{i-1} < m rises strictly to m), so it reaches a value above
/// next_down(m), a strict witness; the attained value is then the largest attained control
/// value. Counted in `fast_exits`, as the end-value exit. Written to the side `sign` of `cb`.
fn polyline_side(s: &Simple, j: usize, sign: f64, cb: &mut CoordBox) {
    let (lo, hi) = s.range[j];
    let m = if sign > 0.0 { hi } else { -lo };
    let args = args_of(cb, sign);
    let mut attained = f64::NEG_INFINITY;
    for i in 0..=s.n {
        let v = sign * s.pts[i * s.d + j];
        let u = s.knots[i + 1];
        let reached = i == s.n || u < s.knots[i + 2];
        if reached && v > attained {
            attained = v;
        }
        if v == m {
            let kind = if i == 0 || i == s.n {
                CandidateKind::EndPoint
            } else {
                CandidateKind::Knot
            };
            args.push(Extremum {
                u_lo: u,
                u_hi: u,
                unique: false,
                kind,
            });
        }
    }
    let witness = if attained < m {
        m.next_down()
    } else {
        f64::NEG_INFINITY
    };
    put(cb, sign, (m, attained, witness), [1, 0, 0, 0]);
}

/// Calls `f` with each index i in 0 ..= n, ascending, whose control value sign * P_ij exceeds
/// `t`: blocks of eight values tested at once without a jump per value, then the values of a
/// block that has one (most control values lie below the attained value that `t` is).
#[inline]
fn each_above(s: &Simple, j: usize, sign: f64, t: f64, mut f: impl FnMut(usize)) {
    const BLOCK: usize = 8;
    let d = s.d;
    let pts = &s.pts[..(s.n + 1) * d];
    if d == 1 {
        // (one coordinate: a block is eight consecutive values, tested by vector compares)
        let blocks = pts.chunks_exact(BLOCK);
        let rest = blocks.remainder();
        for (b, block) in blocks.enumerate() {
            let block: &[f64; BLOCK] = block.try_into().expect("a block of eight");
            if block.iter().fold(false, |any, &v| any | (sign * v > t)) {
                for (o, &v) in block.iter().enumerate() {
                    if sign * v > t {
                        f(b * BLOCK + o);
                    }
                }
            }
        }
        let base = pts.len() - rest.len();
        for (o, &v) in rest.iter().enumerate() {
            if sign * v > t {
                f(base + o);
            }
        }
        return;
    }
    for (b, block) in pts.chunks(BLOCK * d).enumerate() {
        let any = block
            .chunks_exact(d)
            .fold(false, |any, q| any | (sign * q[j] > t));
        if any {
            for (o, q) in block.chunks_exact(d).enumerate() {
                if sign * q[j] > t {
                    f(b * BLOCK + o);
                }
            }
        }
    }
}

/// What the ends u_k and u_{k+1} of the non-empty span k of a spline in the lane are
/// (`bezier::end_kind`: a domain end, a knot of multiplicity >= p, or neither), from the
/// knots next to them: the run of u_k ends at index k and that of u_{k+1} starts at k + 1
/// (u_k < u_{k+1}), so u_k has multiplicity >= p iff u_{k+1-p} = u_k, and u_{k+1} iff
/// u_{k+p} = u_{k+1} (the knots do not decrease), without a search of the knot vector
/// (`span_end_kinds_match_end_kind`).
#[inline]
fn span_end_kinds(s: &Simple, k: usize) -> [CandidateKind; 2] {
    let (p, kn) = (s.p, s.knots);
    let kind = |u: f64, multiple: bool| {
        if u == s.a || u == s.b {
            CandidateKind::EndPoint
        } else if multiple {
            CandidateKind::Knot
        } else {
            CandidateKind::Critical
        }
    };
    [
        kind(kn[k], kn[k + 1 - p] == kn[k]),
        kind(kn[k + 1], kn[k + p] == kn[k + 1]),
    ]
}

/// The `newton` and `bezier` stopping rule: a gap of at most two ulps of the coordinate scale.
fn max_gap(s: &Simple, j: usize) -> f64 {
    let (lo, hi) = s.range[j];
    let scale = lo.abs().max(hi.abs()).max(f64::MIN_POSITIVE);
    2.0 * crate::num::ulp(scale)
}

/// The tight sides of coordinate j, written to the blank box `cb`, or `None` (fall back to the
/// general path; `cb` is then unspecified).
fn tight_sides(
    s: &Simple,
    j: usize,
    cb: &mut CoordBox,
    cache: &mut Option<SpanCache>,
) -> Option<()> {
    let exits = [cheap_exit(s, j, 1.0), cheap_exit(s, j, -1.0)];
    // (both exits: a monotone coordinate, or a line; a polyline or a spline side by side)
    // (a single segment above degree 3 goes the spline's way too: its one span)
    // (a rational curve too: its proof runs on the homogeneous coefficients)
    if (exits[0].is_some() && exits[1].is_some())
        || s.n > s.p
        || s.p == 1
        || s.p > 3
        || s.w.is_some()
    {
        for (ex, sign) in exits.into_iter().zip([1.0, -1.0]) {
            match ex {
                Some(ex) => put_exit(cb, sign, ex),
                None if s.p == 1 => polyline_side(s, j, sign, cb),
                // (the cache made only here: a single cubic, the hot path, needs none)
                None => spline_side(s, j, sign, cb, cache.get_or_insert_with(Default::default))?,
            }
        }
        return Some(());
    }
    let p = s.p;
    let need = [exits[0].is_none(), exits[1].is_none()];
    let fv: [f64; 4] = std::array::from_fn(|i| if i <= p { s.pts[i * s.d + j] } else { 0.0 });
    let pr = f64_sides(&fv, p, true, need)?;
    let gap = max_gap(s, j);
    // (both sides tested, combined by `&` and `|`: no jump on each side's outcome)
    let loose = |i: usize| need[i] & !pr.sides[i].tight(gap);
    if loose(0) | loose(1) {
        return None;
    }
    for (((ex, sign), f), de) in exits
        .into_iter()
        .zip([1.0, -1.0])
        .zip(&pr.sides)
        .zip([pr.derivative_evaluations, 0])
    {
        match ex {
            Some(ex) => put_exit(cb, sign, ex),
            None => {
                let pe = f.crit.is_some() as u32;
                put(cb, sign, (f.upper, f.attained, f.witness), [0, 1, de, pe]);
                // the candidates: the end values (c_0 at a, c_p at b, sign-adjusted) and the
                // bracket, those whose bound reaches the attained value (as `reaching`, each
                // candidate built where it is pushed: a list of candidates built on the stack
                // and copied from there was read back by wide loads from narrow stores, which
                // the processor cannot forward)
                let args = args_of(cb, sign);
                let a = f.attained;
                if sign * fv[0] >= a {
                    args.push(end(s.a));
                }
                if sign * fv[p] >= a {
                    args.push(end(s.b));
                }
                if let Some((ub, t0, t1)) = f.crit {
                    if ub >= a {
                        args.push(extremum(s.a, s.b, t0, t1, true, CandidateKind::Critical));
                    }
                }
                if args.is_empty() {
                    args.push(unresolved(s));
                }
            }
        }
    }
    Some(())
}

/// The tight sides of coordinate j of a single rational conic (one clamped rational quadratic
/// segment, n = p = 2), written to the blank box `cb`, or `None` (fall back): the sides
/// without a cheap exit (`exits`) by the proof of `bezier::conic` on the exact data (the
/// homogeneous coefficients w_i x_i as exact double-word products, the weights, the end
/// values x_0 and x_2, which a clamped segment attains), both sides at once; each within the
/// stopping rule's gap ([`max_gap`]), or the lane gives up. A side whose extreme control
/// value is an end value exits cheaply, as in [`tight_sides`].
fn conic_segment(s: &Simple, w: &[f64], j: usize, cb: &mut CoordBox) -> Option<()> {
    let exits = [cheap_exit(s, j, 1.0), cheap_exit(s, j, -1.0)];
    let x = |i: usize| s.pts[i * s.d + j];
    let seg = ConicSeg {
        x: std::array::from_fn(|i| Ddi::exact(w[i]) * Ddi::exact(x(i))),
        w: std::array::from_fn(|i| Ddi::exact(w[i])),
        ends: [Ddi::exact(x(0)), Ddi::exact(x(2))],
        a: s.a,
        b: s.b,
        end_kinds: [CandidateKind::EndPoint; 2],
    };
    let need = [exits[0].is_none(), exits[1].is_none()];
    if !(need[0] | need[1]) {
        // (both sides exit: a monotone coordinate)
        exits
            .into_iter()
            .zip([1.0, -1.0])
            .for_each(|(ex, sign)| ex.into_iter().for_each(|ex| put_exit(cb, sign, ex)));
        return Some(());
    }
    let sides = conic_sides(&seg, need)?;
    let gap = max_gap(s, j);
    // (the shared sign tests are counted once, on the first side proved)
    let mut de = sides[0].derivative_evaluations as u32;
    for ((ex, sign), r) in exits.into_iter().zip([1.0, -1.0]).zip(&sides) {
        match ex {
            Some(ex) => put_exit(cb, sign, ex),
            None => {
                if !r.tight(gap) {
                    return None;
                }
                let counts = [0, 1, std::mem::take(&mut de), r.point_evaluations as u32];
                put(
                    cb,
                    sign,
                    (r.upper.max(r.attained), r.attained, r.witness),
                    counts,
                );
                reaching(s, r.attained, r.cands[..r.n].iter(), args_of(cb, sign));
            }
        }
    }
    Some(())
}

/// One side (`side`: 0 the max side, 1 the min side) of a root-isolating proof that fills
/// both sides' slots (`prove(need, out)`, asked for this side only): the side if the proof
/// succeeds within the gap `gap`, else `None` (the general fast path follows).
#[inline(always)]
fn one_side(
    side: usize,
    gap: f64,
    prove: impl FnOnce([bool; 2], &mut [RawSide; 2]) -> Option<()>,
) -> Option<RawSide> {
    let mut need = [false; 2];
    need[side] = true;
    let mut raw = [RawSide::new(), RawSide::new()];
    prove(need, &mut raw)
        .filter(|()| raw[side].tight(gap))
        .map(|()| raw[side])
}

/// The side `sign` of coordinate j of a spline (degree 2 to 5, several spans, or a single
/// segment above degree 3; a rational conic, one segment or several, as below), best first
/// over the spans, as the `bezier` strategy's branch and bound does with its shortcuts, on
/// stack buffers:
///
/// 1. Every span k starts with the bound max_i sign P_ij over its p + 1 local control values
///    (exact; the curve on the span is a convex combination of them). The clamped end values
///    are attained. Only spans whose bound exceeds the attained value matter, and those are
///    found from the control values above it (after step 2 on the spans of the largest
///    control value has raised the attained value), not from a bound of every span.
///    A span whose control values above the attained value A are only at its end positions
///    (P_{k-p} or P_k) is skipped when its neighbour on that side is a non-empty span: the
///    Bézier points b_i = f(u_k^{p-i}, u_{k+1}^i) of span k (f the blossom of its piece) are
///    convex combinations of its local control values, and P_k does not enter b_0 .. b_{p-1}
///    (on span k its basis function is (u - u_k)^p / prod_j (u_{k+j} - u_k), whose blossom
///    vanishes when an argument is u_k), nor P_{k-p} b_1 .. b_p (likewise at u_{k+1}). So
///    every b_i is at most A except b_p = C(u_{k+1}) (if P_k > A) and b_0 = C(u_k) (if
///    P_{k-p} > A), and those are curve values of the neighbouring spans: C(u_{k+1}) is the
///    first Bézier point of span k + 1, whose local control values contain P_k at an inner
///    position, so that span is taken here (never skipped) and its bound, whether below the
///    attained value in step 2 or proved in step 3, covers C(u_{k+1}); the same on the left.
///    For the same reason a span's key in the best-first order below is the largest of its
///    inner control values and of those end values that no non-empty neighbour covers: a span
///    whose inner values fall below the attained value once it has risen is left out.
/// 2. The span with the largest bound above the attained value gets its f64 Bézier
///    coefficients (in closed form from the knot intervals, [`span_coefficients`]) within the
///    a-priori error bound of `bezier::span_bounds`: an upper bound of the span and two
///    attained values (b_0 = C(u_k), b_p = C(u_{k+1}): the curve is continuous, no interior
///    knot has multiplicity above p). A span whose bound is at most the attained value is
///    done.
/// 3. Otherwise the span's Bézier coefficients are enclosed in double-double (the same
///    closed form in `Ddi`; above degree 3 by the insertion, [`SpanCache::get_ddi`]) and the
///    root-isolating proof (`bezier::single`, degree 2 to 5) bounds it, within two ulps of the
///    scale; where the closed-form proof of a quadratic or cubic span fails (an end slope not
///    proven non-zero: an extremum at or next to a knot), the Descartes route (`bezier::single`,
///    as on the spans of degree 4 and 5) with that end left open, on the coefficients by the
///    insertion; where that fails too (a double zero of C_j' inside; more sign changes of
///    C_j''s Bernstein coefficients than zeros found), the general fast path's proof
///    (`bezier::coefficient_side`) on the coefficients by the insertion in `Ddi`; or the lane
///    gives up.
///
/// A rational curve: step 1 as above (with positive weights the piece on a span is a convex
/// combination of its local control points, NURBS Book eq. 4.11, and the skip argument holds
/// for the homogeneous Bézier points, whose Cartesian quotients are convex combinations of
/// the same local control values); step 2 from the f64 homogeneous coefficients with the
/// written bound of the quotients ([`quotient_filter`]: a conic's rows by the closed form,
/// [`conic_rows`], above degree 2 by the insertion, [`span_coefficients_rows`]); step 3 from
/// the `Ddi` rows (a conic's [`ConicSpan`], else [`rational_span`]: the end-coefficient rule
/// on the Cartesian quotients, else the proof of `bezier::conic` for this side, above degree 2
/// the root-isolating proof of `bezier::rational` on the homogeneous rows, where that fails
/// the general fast path's on them). A rational side above degree 2 that the certificate's
/// first rule would leave open goes to the general path.
/// 4. When no span's bound exceeds the attained value, the side's bound is the largest bound
///    of the spans proved in step 3 and the attained value (spans left over or done in step 2
///    are below the attained value, which is below the exact maximum).
fn spline_side(
    s: &Simple,
    j: usize,
    sign: f64,
    cb: &mut CoordBox,
    cache: &mut SpanCache,
) -> Option<()> {
    let (p, d, n, kn) = (s.p, s.d, s.n, s.knots);
    let x = |i: usize| sign * s.pts[i * d + j];
    // (the end values of a clamped spline, its end control points, are attained; an
    // unclamped spline's come in with its end spans' coefficients, b_0 of span p and b_p of
    // span n, in steps 2 and 3)
    let mut attained = if s.clamped {
        x(0).max(x(n))
    } else {
        f64::NEG_INFINITY
    };
    let mut upper = f64::NEG_INFINITY;
    let mut witness = f64::NEG_INFINITY;
    // (the two ends, then up to three per proved span and one per end-coefficient span: 16
    // inline keep a spline of the thesis's size off the heap)
    let mut cands: SmallVec<[(f64, Extremum); 16]> = SmallVec::new();
    if s.clamped {
        for (u, v) in [(s.a, x(0)), (s.b, x(n))] {
            cands.push((v, end(u)));
        }
    }
    let mut counts = [0u32, 1, 0, 0];
    // keys: the bounds' total order as integers (for the heap below)
    let key = |b: f64| {
        let bits = b.to_bits();
        if bits >> 63 == 0 {
            bits | (1 << 63)
        } else {
            !bits
        }
    };
    // step 2 for span k: the f64 coefficients and their a-priori bound (upper bound, attained)
    let filter = |cache: &mut SpanCache, k: usize| -> Option<(f64, f64)> {
        if let Some(w) = s.w {
            // a rational curve: its Cartesian coefficients with their bound (a conic's by the
            // closed form, [`conic_coefficients_f64`]; above degree 2 by the insertion of the
            // homogeneous rows, [`rational_coefficients_f64`])
            let q = if p == 2 {
                conic_coefficients_f64(s, w, cache.conic(s, w, k), j, k)
            } else {
                rational_coefficients_f64(s, w, cache.get(s, k), j, k)
            };
            return quotient_filter(p, &q?, sign);
        }
        let q = if p > 3 {
            let rows = cache.get(s, k);
            std::array::from_fn(|i| if i <= p { rows[i * d + j] } else { 0.0 })
        } else {
            span_coefficients::<f64>(s, j, k)
        };
        let m = (k - p..=k).fold(0.0f64, |m, i| m.max(x(i).abs()));
        let signed = q.map(|v| sign * v);
        span_bounds(&signed[..=p], m, true)
    };
    // (span k = [u_k, u_{k+1}], p <= k <= n, has the local control values k - p ..= k, so
    // control value i lies in the spans max(i, p) ..= min(i + p, n); empty spans are skipped)
    let spans_of = |i: usize| i.max(p)..=(i + p).min(n);
    let nonempty = |k: usize| kn[k] < kn[k + 1];
    // Step 1, in two passes over the control values instead of a bound for every span. A
    // span's bound (the largest of its control values) exceeds a value A iff one of its
    // control values does. First the spans around the largest control value i_max go through
    // step 2 (the maximum is usually near it), which raises the attained value; then only
    // the spans with a control value above that attained value enter the heap, with their
    // control-value bounds. Spans left out have bound <= attained: they are done.
    // (the first index of the largest sign * P_ij: found with the range in `Simple::of`)
    let i_max = if sign > 0.0 {
        s.extreme_at[j].1
    } else {
        s.extreme_at[j].0
    };
    debug_assert_eq!(
        i_max,
        (1..=n).fold(0, |b, i| if x(i) > x(b) { i } else { b })
    );
    let first = spans_of(i_max);
    let mut filtered: SmallVec<[(f64, usize); LANE_MAX_DEGREE + 1]> = SmallVec::new();
    if x(i_max) > attained {
        for k in first.clone().filter(|&k| nonempty(k)) {
            let (ub, at) = filter(cache, k)?;
            attained = attained.max(at);
            filtered.push((ub, k));
        }
    }
    let mut spans: SmallVec<[(u64, usize, bool); 16]> = filtered
        .iter()
        .filter(|&&(ub, _)| ub > attained)
        .map(|&(ub, k)| (key(ub), k, true))
        .collect();
    let mut next = p; // the first span not yet looked at (the passes go left to right)
    each_above(s, j, sign, attained, |i| {
        for k in spans_of(i) {
            if k < next || first.contains(&k) || !nonempty(k) {
                continue;
            }
            // A span whose only control values above the attained value are at its end
            // positions is covered by its neighbours (see step 1 in the docs above): skipped.
            // (the control values are finite: a comparison, not `f64::max` and its NaN rule)
            let inner = (k - p + 1..k).fold(f64::NEG_INFINITY, |b, l| {
                let v = x(l);
                if v > b {
                    v
                } else {
                    b
                }
            });
            if inner <= attained
                && (x(k - p) <= attained || (k > p && nonempty(k - 1)))
                && (x(k) <= attained || (k < n && nonempty(k + 1)))
            {
                continue;
            }
            // The span's key: its inner control values, and an end position's value only where
            // no non-empty neighbour covers it (the same argument as the skip above: P_{k-p}
            // enters only b_0 = C(u_k), P_k only b_p = C(u_{k+1}), values of the neighbouring
            // spans, which hold those control values at inner positions and are taken here
            // whenever they exceed the attained value). So a span whose inner values are
            // below the attained value once it has risen is not filtered at all.
            let mut b = inner;
            if !(k > p && nonempty(k - 1)) {
                b = b.max(x(k - p));
            }
            if !(k < n && nonempty(k + 1)) {
                b = b.max(x(k));
            }
            spans.push((key(b), k, false));
        }
        next = next.max(i + p + 1);
    });
    // best first: the spans sorted by key, the largest taken from the end (the order of a
    // max-heap on the same tuples, kept on the stack: a filtered span goes back at its sorted
    // place)
    spans.sort_unstable();
    let gap = max_gap(s, j);
    while let Some((bk, k, filtered)) = spans.pop() {
        if bk <= key(attained) {
            break;
        }
        // (a span whose local control values are all equal: the coordinate is that constant
        // there, a convex combination with positive weights, every value attained and
        // bounding it, as in the `bezier` strategy's search; its derivative vanishes on the
        // whole span, where the proofs below would fail)
        let v = x(k);
        if (k - p..k).all(|i| x(i) == v) {
            attained = attained.max(v);
            upper = upper.max(v);
            cands.push((
                v,
                Extremum {
                    u_lo: kn[k],
                    u_hi: kn[k + 1],
                    unique: false,
                    kind: CandidateKind::Critical,
                },
            ));
            continue;
        }
        // step 2: f64 coefficients and their a-priori bound; the span goes back with that
        // bound, so that the double-double stage runs only on the span whose f64 bound is the
        // largest left (usually the one with the maximum)
        if !filtered {
            let (ub, at) = filter(cache, k)?;
            attained = attained.max(at);
            if ub > attained {
                let item = (key(ub), k, true);
                spans.insert(spans.partition_point(|x| *x < item), item);
            }
            continue;
        }
        // step 3: double-double coefficients and the root-isolating proof
        // (a rational curve: its homogeneous rows X and W, and their quotients as the span's
        // coefficients; a conic's from `ConicSpan`, made once per span and coordinate, above
        // degree 2 from `rational_span`, per side: a cache of those per span and coordinate,
        // tried, cost more in the larger `SpanCache` than the p + 1 divisions it saved)
        let conic =
            s.w.filter(|_| p == 2)
                .map(|w| cache.conic_ddi(s, w, k).coordinate(s, w, k, j));
        let mut hom = None;
        let qd = if let Some((_, _, q)) = conic {
            let mut r = [Ddi::exact(0.0); LANE_MAX_DEGREE + 1];
            r[..3].copy_from_slice(&q);
            r
        } else if s.w.is_some() {
            let (x, w, q) = rational_span(s, cache.get_ddi(s, k), j, k);
            hom = Some((x, w));
            q
        } else if p > 3 || (!s.clamped && (kn[k] == s.a || kn[k + 1] == s.b)) {
            // (and an unclamped spline's end spans: their end values at the domain ends, no
            // control points, are made exact where they are doubles, `SpanCache::get_ddi`)
            cache.coordinate_ddi(s, k, j)
        } else {
            step3_coefficients(s, j, k)
        };
        // (the end-coefficient rule of the `bezier` strategy first: if an end coefficient has
        // the largest upper end, the span's maximum is at most that, and the end coefficient is
        // a value of the curve, C(u_k) or C(u_{k+1}); its enclosure is about an ulp wide. The
        // end is the candidate where the maximum is attained only if it is exact (the maximum
        // is then its value) or every other coefficient lies strictly below it (every inner
        // value of the piece, a convex combination with a positive share of those, is then
        // below the end's value); otherwise the maximiser may lie inside the span, next to the
        // end (a symmetric extremum at a knot, moved by a few ulps), and the proof below
        // brackets it.)
        let signed = qd.map(|v| if sign > 0.0 { v } else { -v });
        // (the ends of `to_interval`, each computed alone: `upper_end`, `lower_end`)
        let sups: [f64; LANE_MAX_DEGREE + 1] = std::array::from_fn(|i| {
            if i <= p {
                signed[i].upper_end()
            } else {
                f64::NEG_INFINITY
            }
        });
        let (mut top, mut at) = (f64::NEG_INFINITY, 0);
        for (i, &sup) in sups.iter().enumerate().take(p + 1) {
            // (a NaN upper end fails every comparison and ends in the proof below)
            if sup > top || (i == p && sup == top) {
                (top, at) = (sup, i);
            }
        }
        if at == 0 || at == p {
            let v = signed[at];
            let inf = v.lower_end();
            let others = (0..=p)
                .filter(|&i| i != at)
                .fold(f64::NEG_INFINITY, |m, i| m.max(sups[i]));
            if top - inf <= gap && (inf == top || others < inf) {
                let u = kn[if at == 0 { k } else { k + 1 }];
                let kind = span_end_kinds(s, k)[if at == 0 { 0 } else { 1 }];
                attained = attained.max(inf);
                upper = upper.max(top);
                witness = witness.max(v.strictly_below());
                cands.push((
                    top,
                    Extremum {
                        u_lo: u,
                        u_hi: u,
                        unique: false,
                        kind,
                    },
                ));
                continue;
            }
        }
        // The proof of this side: on a conic `bezier::conic`'s, on a polynomial span (degree 2
        // to 5) the root-isolating proof of `bezier::single` (`None` here where it fails), on
        // the rest the general fast path's below.
        let side = if sign > 0.0 { 0 } else { 1 };
        let r = if let Some((xs, ws, q)) = conic {
            // (a rational conic: the proof of `bezier::conic` on the homogeneous coefficients,
            // for this side: the other side's extremum lies in another span as a rule)
            let seg = ConicSeg {
                x: xs,
                w: ws,
                ends: [q[0], q[2]],
                a: kn[k],
                b: kn[k + 1],
                end_kinds: span_end_kinds(s, k),
            };
            let mut need = [false; 2];
            need[side] = true;
            Some(conic_sides(&seg, need)?[side])
        } else if hom.is_none() {
            let seg = Segment {
                c: &qd[..=p],
                a: kn[k],
                b: kn[k + 1],
                end_kinds: span_end_kinds(s, k),
                right_attained: true,
            };
            one_side(side, gap, |need, raw| raw_sides_into(&seg, need, raw)).or_else(|| {
                // (a quadratic or cubic span whose closed-form proof failed, as a rule at an end
                // slope not proven non-zero, an extremum at or next to a knot: the Descartes
                // route, which leaves such an end open (`bezier::single`'s step 4b), on the
                // coefficients by the insertion, whose end values that are doubles are exact
                // (`SpanCache::get_ddi`: the closed form's wider ends would leave an inner bound
                // an ulp farther); they are cached for the general fast path's proof below)
                if p > 3 {
                    return None;
                }
                let q = cache.coordinate_ddi(s, k, j);
                let seg = Segment { c: &q[..=p], ..seg };
                one_side(side, gap, |need, raw| descartes_sides_into(&seg, need, raw))
            })
        } else if let Some((xh, wh)) = &hom {
            // (a rational span of degree 3 to 5: the root-isolating proof of
            // `bezier::rational` on the homogeneous rows, its ends the Cartesian end values)
            let seg = RationalSeg {
                x: &xh[..=p],
                w: &wh[..=p],
                ends: [qd[0], qd[p]],
                a: kn[k],
                b: kn[k + 1],
                end_kinds: span_end_kinds(s, k),
            };
            one_side(side, gap, |need, raw| rational_sides_into(&seg, need, raw))
        } else {
            None
        };
        let Some(r) = r else {
            // The general fast path's proof on the span's coefficients (the zeros of C_j'
            // located by Bernstein subdivision with proven sign counts): on a rational curve
            // above degree 2, and where the proof of a polynomial span fails (a double zero of
            // C_j' inside the span or a loose count of zeros; a near-degenerate cubic; at or
            // next to a knot where the Descartes route above gives up too), as the general path's search tries it after
            // `single` (before, the lane gave such a curve up to the general path, which
            // repeated the work done so far). A quadratic or cubic then takes its coefficients
            // by the insertion, whose end values that are exactly doubles are made exact
            // (`SpanCache::get_ddi`, as the general path's points: the same bounds, attained
            // values and certificates as there on the 4,437 curves compared; the closed form's
            // wider ends gave inner bounds an ulp farther on four).
            let qd = if p <= 3 && hom.is_none() {
                cache.coordinate_ddi(s, k, j)
            } else {
                qd
            };
            let proof = cache.proof(k, j);
            let hom = hom.as_ref().map(|(x, w)| (&x[..=p], &w[..=p]));
            let sd =
                super::bezier::coefficient_side(s.curve, j, k, &qd[..=p], hom, sign, gap, proof)?;
            attained = attained.max(sd.attained);
            upper = upper.max(sd.upper);
            witness = witness.max(sd.witness);
            cands.extend_from_slice(&sd.cands);
            counts[2] += sd.stats.derivative_evaluations as u32;
            counts[3] += sd.stats.point_evaluations as u32;
            continue;
        };
        if !r.tight(gap) {
            return None;
        }
        attained = attained.max(r.attained);
        upper = upper.max(r.upper);
        witness = witness.max(r.witness);
        cands.extend_from_slice(&r.cands[..r.n]);
        counts[2] += r.derivative_evaluations as u32;
        counts[3] += r.point_evaluations as u32;
    }
    let upper = upper.max(attained);
    if s.w.is_some() && p > 2 {
        // A rational side that the certificate's first round would leave open (bound and
        // values within the gap, yet no attained value or witness at the bound's next double
        // down) goes to the general path: where the mean value form over a box is wider than
        // an ulp (weights spread, clustered knots), its second-order Taylor form from the
        // curve-wide sweep usually closes it, at a fraction of the full certification's cost.
        let (lo, hi) = s.range[j];
        let scale = lo.abs().max(hi.abs()).max(f64::MIN_POSITIVE);
        if certify::quick_flags(upper, attained, witness, f64::NEG_INFINITY, scale).1 {
            return None;
        }
    }
    put(cb, sign, (upper, attained, witness), counts);
    reaching(s, attained, cands.iter(), args_of(cb, sign));
    Some(())
}

/// The Bézier coefficients b_0 .. b_p of coordinate j on span k = [u_k, u_{k+1}] of a spline
/// of degree 2 or 3 (the lane's splines), in `S`, in closed form from the knot intervals
/// d_i = u_{i+1} - u_i (the B-spline to Bézier conversion of quadratic and cubic splines; Farin,
/// *Curves and Surfaces for CAGD*, the chapters on quadratic and cubic B-splines; the same
/// points as Boehm's insertion of u_k and u_{k+1} up to multiplicity p, NURBS Book A5.6):
///
/// * p = 2: b_1 = P_{k-1}; b_0 = C(u_k) divides the leg P_{k-2} P_{k-1} in the ratio
///   d_{k-1} : d_k, b_2 = C(u_{k+1}) the leg P_{k-1} P_k in the ratio d_k : d_{k+1}.
/// * p = 3: b_1 and b_2 divide the leg P_{k-2} P_{k-1} in the ratios d_{k-1} : d_k : d_{k+1};
///   L, the last inner point of span k - 1, divides the leg P_{k-3} P_{k-2} in the ratios
///   d_{k-2} : d_{k-1} : d_k (L at (d_{k-2} + d_{k-1}) / (d_{k-2} + d_{k-1} + d_k)), and
///   b_0 = C(u_k) divides L b_1 in the ratio d_{k-1} : d_k; b_3 likewise with R on the leg
///   P_{k-1} P_k (at d_k / (d_k + d_{k+1} + d_{k+2})) and b_2, in the ratio d_k : d_{k+1}.
///
/// Every denominator is a sum of knot intervals that contains d_k > 0, and every ratio lies in
/// [0, 1] (zero intervals, i.e. multiple knots, give the clamped and C^1 / C^0 cases: a triple
/// knot makes b_0 = P_{k-3}). Five divisions and six corner cuts instead of the p(p+1) of the
/// insertion (each with its own division), on the stack.
///
/// For `Ddi` every operation encloses its exact result, so the coefficients enclose the exact
/// ones. For f64 (the lane's moderate knots: every difference finite and normal), with
/// u = 2^-53 and M the largest |local control value|: a knot interval is fl(u_{i+1} - u_i) =
/// d_i (1 + δ), a ratio of sums of at most three intervals is within (1 + γ_6) of the exact
/// one (γ_n = n u / (1 - n u)), and a cut fl(lo + fl(r fl(hi - lo))) with |hi - lo| <= 2 M
/// errs by at most 2 M (γ_6 + 2 u) + M u <= 17.1 u M against the exact cut of its computed
/// ends; a cut of two computed points (b_0, b_3) adds at most 17.1 u M to the larger of their
/// errors (a convex combination does not amplify them). So every coefficient is within
/// 34.3 u M < 35 u M of the exact one, below the bound 2p 8 ε M >= 64 u M of
/// `bezier::span_bounds` for p >= 2, which the caller applies (plus f64::MIN_POSITIVE for
/// underflowing products). Tested against exact rational insertion
/// (`closed_form_span_coefficients_match_exact_insertion`).
///
/// Degree 4 and 5: Boehm's insertion itself (`bspline::clamp_span`, NURBS Book A5.1 at both
/// ends of the span), on the stack, of every coordinate at once ([`span_coefficients_rows`]:
/// the same operations on each row, with the knot ratios shared). Every step is a corner cut fl(lo + fl(α fl(hi - lo))) with
/// α = fl(fl(u - t_a) / fl(t_b - t_a)) in [0, 1] (a ratio of knot differences: within
/// (1 + γ_3) of the exact one, up to an absolute 2^-1074 where it underflows), so a cut errs
/// by at most 2 M (γ_3 + 2u + u^2) + u M + 2^-1073 M <= 11.1 u M against the exact cut of its
/// computed ends (M the largest |local control value|: every point of the insertion is a
/// convex combination of those), and the exact cut (α exact, in [0, 1]) does not amplify the
/// ends' errors. A coefficient is at most p - 1 cuts deep at each end (the left end has
/// multiplicity s >= 1 among the span's knots, so p - s insertions), so it is within
/// 2 (p - 1) 11.1 u M <= 89 u M (p = 5) of the exact one, below the bound 2p 8 ε M = 32 p u M
/// of `bezier::span_bounds` (underflowing products: at most 2^-1075 each, within its
/// f64::MIN_POSITIVE). Tested against exact insertion
/// (`inserted_span_coefficients_are_within_their_bound`).
fn span_coefficients<S: Scalar>(s: &Simple, j: usize, k: usize) -> [S; LANE_MAX_DEGREE + 1] {
    debug_assert!(s.w.is_none(), "a polynomial spline's coefficients");
    let kn = s.knots;
    if s.p > 3 {
        // (row j of the insertion of every row, `span_coefficients_rows`, which the lane uses)
        let mut q: [S; LANE_MAX_DEGREE + 1] = std::array::from_fn(|_| S::zero());
        let rows = span_coefficients_rows::<S>(s, k);
        for (i, v) in q.iter_mut().enumerate().take(s.p + 1) {
            *v = rows[i * s.d + j].clone();
        }
        return q;
    }
    closed_form(s, j, k, |(u, a, b), lo, hi| {
        S::lerp(&sum_ratio::<S>(kn, u, a, b), lo, hi)
    })
}

/// The knot ratio (u_u - u_a) / (u_b - u_a) (indices a < u < b) of the closed forms as a
/// quotient of sums of the knot intervals d_i = u_{i+1} - u_i, added from the left: the
/// numerator d_a + .. + d_{u-1}, the denominator the numerator plus d_u + .. + d_{b-1} (the
/// form of [`span_coefficients`]' error bound; exact differences and sums in `Ddi`).
#[inline]
fn sum_ratio<S: Scalar>(kn: &[f64], u: usize, a: usize, b: usize) -> S {
    let d = |i: usize| S::from_f64(kn[i + 1]) - S::from_f64(kn[i]);
    let mut num = d(a);
    for i in a + 1..u {
        num = num + d(i);
    }
    let mut den = num.clone();
    for i in u..b {
        den = den + d(i);
    }
    num / den
}

/// The closed form of [`span_coefficients`] for degree 2 and 3, with the corner cuts
/// lo + r (hi - lo) by the knot ratio r = (u_u - u_a) / (u_b - u_a) given by
/// `cut((u, a, b), lo, hi)`: every coefficient is a cut of local control values (or of two
/// cuts) by such a ratio in [0, 1] (u_a <= u_u < u_b: the span k is not empty).
#[inline]
fn closed_form<S: Scalar>(
    s: &Simple,
    j: usize,
    k: usize,
    mut cut: impl FnMut((usize, usize, usize), &S, &S) -> S,
) -> [S; LANE_MAX_DEGREE + 1] {
    let pt = |i: usize| S::from_f64(s.pts[i * s.d + j]);
    let mut q: [S; LANE_MAX_DEGREE + 1] = std::array::from_fn(|_| S::zero());
    if s.p == 2 {
        // b_1 = P_{k-1}; b_0 divides the leg P_{k-2} P_{k-1} in the ratio d_{k-1} : d_k, b_2
        // the leg P_{k-1} P_k in the ratio d_k : d_{k+1}
        let (p0, p1, p2) = (pt(k - 2), pt(k - 1), pt(k));
        q[0] = cut((k, k - 1, k + 1), &p0, &p1);
        q[2] = cut((k + 1, k, k + 2), &p1, &p2);
        q[1] = p1;
        return q;
    }
    let (p0, p1, p2, p3) = (pt(k - 3), pt(k - 2), pt(k - 1), pt(k));
    let b1 = cut((k, k - 1, k + 2), &p1, &p2);
    let b2 = cut((k + 1, k - 1, k + 2), &p1, &p2);
    let l = cut((k, k - 2, k + 1), &p0, &p1);
    let r = cut((k + 1, k, k + 3), &p2, &p3);
    q[0] = cut((k, k - 1, k + 1), &l, &b1);
    q[3] = cut((k + 1, k, k + 2), &b2, &r);
    q[1] = b1;
    q[2] = b2;
    q
}

/// Span k's `Ddi` coefficients of coordinate j for step 3 of [`spline_side`] (a polynomial
/// spline of degree 2 or 3): the closed form ([`closed_form`]) in double words with the
/// a-priori running bound of `num::dw`, whose proof covers it: every step is a corner cut of
/// the extraction there, z = lo + α (hi - lo) with α = (u_u - u_a) / (u_b - u_a) a ratio of
/// exact knot differences in [0, 1] computed by `Dw::knot_ratio_f64` (within 12 u^2), of
/// exact inputs (radius 0) or of earlier cuts; the result is the `Ddi` centre hi + lo with
/// radius e. About a third of the `Ddi` arithmetic's cost. A ratio that is exactly 0 or 1
/// (u_u = u_a or u_u = u_b at a repeated knot) takes its end as it is, the exact cut.
///
/// The `Ddi` closed form itself ([`span_coefficients`]) where the guard of `num::dw` fails
/// (knots, values), a result is not finite, or a cut of two exact values may be exact (equal
/// values, or a ratio that may be a double: `Dw::knot_ratio_may_be_exact`): the `Ddi` closed
/// form keeps such a cut exact, and the proof reads exact coefficients as such (all of them
/// doubles: the exact proof of `bezier::single`; an end value: attained at its bound), where
/// the double words carry a bound > 0. Elsewhere the `Ddi` coefficients are not exact either
/// (an exact `Ddi` value is a dyadic rational, and a ratio of two doubles that is dyadic is a
/// double), so the two routes differ only in the last bits of the centres and in the radii.
/// (`dw_closed_form_encloses_the_exact_coefficients`)
fn step3_coefficients(s: &Simple, j: usize, k: usize) -> [Ddi; LANE_MAX_DEGREE + 1] {
    use crate::num::dw::{knots_guarded, Dw};
    let (p, kn) = (s.p, s.knots);
    let fast = || -> Option<[Ddi; LANE_MAX_DEGREE + 1]> {
        // (the knots the ratios read, u_{k+1-p} ..= u_{k+p}, and the local control values)
        if !knots_guarded(&kn[k + 1 - p..=k + p])
            || !(k - p..=k).all(|i| Dw::guarded(s.pts[i * s.d + j]))
        {
            return None;
        }
        let mut exact_cut = false;
        let q = closed_form(s, j, k, |(u, a, b), lo: &Dw, hi: &Dw| {
            let (tu, ta, tb) = (kn[u], kn[a], kn[b]);
            if tu == ta {
                *lo
            } else if tu == tb {
                *hi
            } else {
                exact_cut |= lo.is_exact()
                    && hi.is_exact()
                    && (lo == hi || Dw::knot_ratio_may_be_exact(tu, ta, tb));
                // (once a cut may be exact the `Ddi` closed form runs: no more cuts here)
                if exact_cut {
                    *lo
                } else {
                    Dw::lerp(&Dw::knot_ratio_f64(tu, ta, tb), lo, hi)
                }
            }
        });
        if exact_cut {
            return None;
        }
        let mut out = [Ddi::exact(0.0); LANE_MAX_DEGREE + 1];
        for (o, x) in out.iter_mut().zip(&q[..=p]) {
            *o = x.to_ddi_checked()?;
        }
        Some(out)
    };
    fast().unwrap_or_else(|| span_coefficients::<Ddi>(s, j, k))
}

/// The knot ratios of a quadratic span k (as in [`closed_form`]): d_{k-1} / (d_{k-1} + d_k) and
/// d_k / (d_k + d_{k+1}) (shared by every row of the span).
fn quadratic_ratios<S: Scalar>(kn: &[f64], k: usize) -> [S; 2] {
    [
        sum_ratio(kn, k, k - 1, k + 1),
        sum_ratio(kn, k + 1, k, k + 2),
    ]
}

/// The cuts of a quadratic span (as in [`closed_form`]) with the ratios `r` on the local values
/// P_{k-2}, P_{k-1}, P_k.
fn quadratic_cuts<S: Scalar>(r: &[S; 2], [p0, p1, p2]: [S; 3]) -> [S; 3] {
    let b0 = S::lerp(&r[0], &p0, &p1);
    let b2 = S::lerp(&r[1], &p1, &p2);
    [b0, p1, b2]
}

/// A rational conic's local values on span k for the cuts: the products w_i x_i of coordinate
/// j (`Some(j)`, exact double-words for `Ddi`) or the weights (`None`).
fn conic_values<S: Scalar>(s: &Simple, w: &[f64], k: usize, j: Option<usize>) -> [S; 3] {
    std::array::from_fn(|l| {
        let i = k - 2 + l;
        match j {
            Some(j) => S::from_f64(w[i]) * S::from_f64(s.pts[i * s.d + j]),
            None => S::from_f64(w[i]),
        }
    })
}

/// Room for a rational conic's span rows: the homogeneous rows X (w_i x_i) of every coordinate,
/// then the weights' row W, three coefficients each.
const CONIC_ROWS: usize = 3 * (MAX_DIM + 1);

/// A rational conic's homogeneous Bézier coefficients on span k, in `S`: for coordinate j the
/// row X at 3 j (of the products w_i x_i), the row W at 3 d (of the weights), each by the
/// closed form of a quadratic span ([`closed_form`]) (Boehm's insertion of the homogeneous spline, NURBS Book
/// A5.6 on P^w). In f64 for the filter, in exact arithmetic in the tests; [`ConicSpan`] forms
/// the same rows in `Ddi` (one coordinate's on first use).
fn conic_rows<S: Scalar>(s: &Simple, w: &[f64], k: usize) -> [S; CONIC_ROWS] {
    let mut q: [S; CONIC_ROWS] = std::array::from_fn(|_| S::zero());
    let d = s.d;
    let r = quadratic_ratios::<S>(s.knots, k);
    for j in 0..d {
        let row = quadratic_cuts(&r, conic_values(s, w, k, Some(j)));
        q[3 * j..3 * j + 3].clone_from_slice(&row);
    }
    let row = quadratic_cuts(&r, conic_values(s, w, k, None));
    q[3 * d..3 * d + 3].clone_from_slice(&row);
    q
}

/// The f64 filter (step 2 of [`spline_side`]) of a rational span k of degree p, side `sign`,
/// from coordinate j's Cartesian coefficients with their bounds `q` ([`conic_coefficients_f64`],
/// [`rational_coefficients_f64`]): an upper bound of the span and an attained value (a lower
/// bound of C_j(u_k) or C_j(u_{k+1}), sign-adjusted), or `None` (a non-finite value).
///
/// Error bound. Let X_i, W_i be the exact homogeneous coefficients and X̃_i, W̃_i the f64 ones;
/// Mx = max |fl(w_l x_l)| and Mw = max w_l over the span's local control points l = k - p ..= k,
/// M = max |x_l|, u = 2^-53. A computed product is within u |w_l x_l| (+ 2^-1075 where it
/// underflows) of the exact one; for a conic a corner cut errs by at most 17.1 u times the
/// largest magnitude of its computed ends against the exact cut of those ends (the bound of
/// [`span_coefficients`]; at degree 2 one cut per end coefficient, b_1 = P_{k-1} uncut), and
/// the exact cut (a convex combination) does not amplify its ends' errors. So
/// |X̃_i - X_i| <= EX = 19 u Mx + 2^-1022 and |W̃_i - W_i| <= EW = 18 u Mw + 2^-1022 (above
/// degree 2 the insertion's constants, [`rational_coefficients_f64`]). The exact
/// Cartesian coefficient b_i = X_i / W_i is a convex combination of the local x_l (W_i > 0
/// a convex combination of positive weights, NURBS Book eq. 4.11), so |b_i| <= M, and
///
///   X̃_i / W̃_i - X_i / W_i = ((X̃_i - X_i) - b_i (W̃_i - W_i)) / W̃_i,
///
/// at most (EX + M EW) / W̃_i in magnitude for W̃_i > 0; the division fl(X̃_i / W̃_i) adds
/// u |b̃_i| (+ 2^-1075). Each bound is formed with every step rounded upward (`ddi::up` of one
/// rounded operation on nonnegative operands bounds its exact result). The span lies in the
/// convex hull of its Cartesian Bézier points, b_0 = C(u_k) and b_p = C(u_{k+1}) are curve
/// values (tested against exact insertion and de Boor's evaluation:
/// `conic_span_coefficients_are_within_their_bound`, `rational_span_coefficients_are_within_their_bound`).
fn quotient_filter(
    p: usize,
    q: &[(f64, f64); LANE_MAX_DEGREE + 1],
    sign: f64,
) -> Option<(f64, f64)> {
    let (mut ub, mut at) = (f64::NEG_INFINITY, f64::NEG_INFINITY);
    for (i, &(b, err)) in q.iter().enumerate().take(p + 1) {
        let b = sign * b;
        ub = ub.max((b + err).next_up());
        if i == 0 || i == p {
            at = at.max((b - err).next_down());
        }
    }
    (ub.is_finite() && at.is_finite()).then_some((ub, at))
}

/// The Cartesian coefficients b̃_i = fl(X̃_i / W̃_i) of coordinate j on a rational conic's span
/// k with their error bounds err_i (|b̃_i - b_i| <= err_i, see [`quotient_filter`]: at degree 2
/// one cut per end coefficient, so EX = 19 u Mx, EW = 18 u Mw), or `None` (a non-finite value,
/// a weight coefficient not positive).
fn conic_coefficients_f64(
    s: &Simple,
    w: &[f64],
    rows: &[f64; CONIC_ROWS],
    j: usize,
    k: usize,
) -> Option<[(f64, f64); LANE_MAX_DEGREE + 1]> {
    let d = s.d;
    quotient_coefficients_f64(s, w, j, k, (19.0, 18.0), |i| {
        (rows[3 * j + i], rows[3 * d + i])
    })
}

/// The Cartesian coefficients b̃_i = fl(X̃_i / W̃_i) of coordinate j on span k of a rational
/// spline of degree 3 to 5 from the f64 homogeneous rows of [`span_coefficients_rows`], with
/// their error bounds err_i (see [`quotient_filter`]), or `None`. The rows are Boehm's
/// insertion of the homogeneous control points (w_l x_l, w_l), with the bound of
/// [`span_coefficients`]: every coefficient within 2 (p - 1) 11.1 u M of the exact insertion
/// of its computed inputs (M the row's largest |input|); the products fl(w_l x_l) are within
/// u |w_l x_l| (+ 2^-1075 where they underflow) of the exact ones, and the exact insertion, a
/// convex combination, does not amplify that. So EX = (22.2 (p - 1) + 2) u Mx (one u for the
/// products, one for |w_l x_l| <= (1 + u) Mx), EW = 22.2 (p - 1) u Mw.
fn rational_coefficients_f64(
    s: &Simple,
    w: &[f64],
    rows: &[f64; SPAN_ROWS],
    j: usize,
    k: usize,
) -> Option<[(f64, f64); LANE_MAX_DEGREE + 1]> {
    let (h, d) = (s.stride(), s.d);
    let cuts = 22.2 * (s.p - 1) as f64;
    quotient_coefficients_f64(s, w, j, k, (cuts + 2.0, cuts), |i| {
        (rows[i * h + j], rows[i * h + d])
    })
}

/// The Cartesian coefficients b̃_i = fl(X̃_i / W̃_i), i = 0 ..= p, of coordinate j on span k of
/// a rational spline (degree p = 2 ..= 5) from its f64 homogeneous coefficients
/// `row(i)` = (X̃_i, W̃_i), with their error bounds err_i (|b̃_i - b_i| <= err_i, see
/// [`quotient_filter`]), where |X̃_i - X_i| <= cx u Mx and |W̃_i - W_i| <= cw u Mw (plus
/// 2^-1022 each for underflow), or `None` (a non-finite value, a weight coefficient not
/// positive).
fn quotient_coefficients_f64(
    s: &Simple,
    w: &[f64],
    j: usize,
    k: usize,
    (cx, cw): (f64, f64),
    row: impl Fn(usize) -> (f64, f64),
) -> Option<[(f64, f64); LANE_MAX_DEGREE + 1]> {
    use crate::num::ddi::up;
    const U: f64 = f64::EPSILON / 2.0;
    let p = s.p;
    let (mut mx, mut mw, mut m) = (0.0f64, 0.0f64, 0.0f64);
    for (l, &wl) in w.iter().enumerate().take(k + 1).skip(k - p) {
        let x = s.pts[l * s.d + j];
        mx = mx.max((wl * x).abs());
        mw = mw.max(wl);
        m = m.max(x.abs());
    }
    let ex = up(up(cx * U) * mx) + f64::MIN_POSITIVE;
    let ew = up(up(cw * U) * mw) + f64::MIN_POSITIVE;
    let e = up(ex + up(m * ew));
    let mut out = [(0.0, 0.0); LANE_MAX_DEGREE + 1];
    for (i, o) in out.iter_mut().enumerate().take(p + 1) {
        let (xi, wi) = row(i);
        // (a NaN fails the test)
        if !(wi > 0.0 && xi.is_finite()) {
            return None;
        }
        let b = xi / wi;
        *o = (b, up(up(e / wi) + up(U * b.abs())) + f64::MIN_POSITIVE);
    }
    Some(out)
}

/// Coordinate j's homogeneous rows X (w x_j) and W on span k of a rational spline of degree 3
/// to 5 from the span's `Ddi` rows of [`span_coefficients_rows`] (enclosures of the exact
/// ones), and the Cartesian coefficients X_i / W_i, their ends taken exactly at knots of
/// multiplicity >= p ([`snap_control_ends`]).
fn rational_span(s: &Simple, rows: &[Ddi; SPAN_ROWS], j: usize, k: usize) -> RationalRows {
    let (p, h, d) = (s.p, s.stride(), s.d);
    let zero = Ddi::exact(0.0);
    let one = Ddi::exact(1.0);
    let x: [Ddi; LANE_MAX_DEGREE + 1] =
        std::array::from_fn(|i| if i <= p { rows[i * h + j] } else { zero });
    let w: [Ddi; LANE_MAX_DEGREE + 1] =
        std::array::from_fn(|i| if i <= p { rows[i * h + d] } else { one });
    let mut q: [Ddi; LANE_MAX_DEGREE + 1] =
        std::array::from_fn(|i| if i <= p { x[i] / w[i] } else { zero });
    snap_control_ends(s, k, j, &mut q[..=p]);
    (x, w, q)
}

/// The Cartesian coefficients `q` (p + 1 of them) of coordinate j on span k of a rational
/// spline of degree p with their ends b_0 = C(u_k), b_p = C(u_{k+1}) replaced by the control
/// points P_{k-p} and P_k themselves where the knot has multiplicity >= p (NURBS Book eq. 2.5
/// and A5.1 on P^w: the homogeneous end point is the control point P^w_{k-p}, resp. P^w_k, so
/// its quotient is the control point's coordinate exactly, which the quotient's enclosure only
/// straddles).
fn snap_control_ends(s: &Simple, k: usize, j: usize, q: &mut [Ddi]) {
    let (p, d, kn) = (q.len() - 1, s.d, s.knots);
    if kn[k + 1 - p] == kn[k] {
        q[0] = Ddi::exact(s.pts[(k - p) * d + j]);
    }
    if kn[k + p] == kn[k + 1] {
        q[p] = Ddi::exact(s.pts[k * d + j]);
    }
}

/// A rational conic's span k in `Ddi` for step 3 of [`spline_side`]: the rows of
/// [`conic_rows`], and per coordinate (made on first use) the Cartesian coefficients
/// X_i / W_i, whose ends b_0 = C(u_k), b_2 = C(u_{k+1}) are exact where the knot is double (or
/// the clamped end): there the cut's ratio is exactly 0 or 1 and the end is the control point
/// P_{k-2} (P_k) itself, whose coordinate is taken exactly instead of the quotient's
/// enclosure (the extrema of a NURBS circle lie there).
struct ConicSpan {
    ratios: [Ddi; 2],
    w: [Ddi; 3],
    /// per coordinate the row X and the Cartesian coefficients, made on first use
    coords: [Option<([Ddi; 3], [Ddi; 3])>; MAX_DIM],
}

impl ConicSpan {
    fn new(s: &Simple, w: &[f64], k: usize) -> ConicSpan {
        let ratios = quadratic_ratios::<Ddi>(s.knots, k);
        ConicSpan {
            ratios,
            w: quadratic_cuts(&ratios, conic_values(s, w, k, None)),
            coords: [None; MAX_DIM],
        }
    }

    /// Coordinate j's homogeneous row X, the row W, and the Cartesian coefficients (the rows
    /// of [`conic_rows`], the coordinate's made here on first use).
    fn coordinate(
        &mut self,
        s: &Simple,
        w: &[f64],
        k: usize,
        j: usize,
    ) -> ([Ddi; 3], [Ddi; 3], [Ddi; 3]) {
        let (r, wr) = (self.ratios, self.w);
        let (x, cart) = *self.coords[j].get_or_insert_with(|| {
            let x = quadratic_cuts(&r, conic_values(s, w, k, Some(j)));
            let mut q: [Ddi; 3] = std::array::from_fn(|i| x[i] / wr[i]);
            snap_control_ends(s, k, j, &mut q);
            (x, q)
        });
        (x, wr, cart)
    }
}

/// Every coordinate's Bézier coefficients on span k of a spline above degree 3 (point i's
/// coordinate j at i d + j), by the insertion and with the bound of [`span_coefficients`]
/// (per row the operations of a one-row insertion; the knot ratios, the costly part, formed
/// once instead of once per coordinate and side).
///
/// A rational spline (degree 3 to 5): the rows of the homogeneous control points
/// P^w_i = (w_i x_i, w_i) (NURBS Book A5.6 on P^w), point i's row w x_j at i (d + 1) + j and its
/// weight at i (d + 1) + d ([`Simple::stride`]); the products w_i x_i in `S` (exact
/// double-words in `Ddi`, rounded in f64: see [`rational_coefficients_f64`]).
fn span_coefficients_rows<S: Scalar>(s: &Simple, k: usize) -> [S; SPAN_ROWS] {
    let (p, d, h) = (s.p, s.d, s.stride());
    let mut t = [0.0f64; 2 * LANE_MAX_DEGREE + 2];
    t[..2 * p + 2].copy_from_slice(&s.knots[k - p..=k + p + 1]);
    let mut q: [S; SPAN_ROWS] = std::array::from_fn(|_| S::zero());
    let len = (p + 1) * h;
    match s.w {
        Some(w) => {
            for (i, row) in q[..len].chunks_exact_mut(h).enumerate() {
                let l = k - p + i;
                let wl = S::from_f64(w[l]);
                for (v, &x) in row.iter_mut().zip(&s.pts[l * d..(l + 1) * d]) {
                    *v = wl.clone() * S::from_f64(x);
                }
                row[d] = wl;
            }
        }
        None => {
            for (v, &x) in q.iter_mut().zip(&s.pts[(k - p) * d..(k + 1) * d]) {
                *v = S::from_f64(x);
            }
        }
    }
    clamp_span(p, h, &mut t[..2 * p + 2], &mut q[..len]);
    q
}

/// Room for one span's coefficients of every row ([`span_coefficients_rows`]: the
/// coordinates, and a rational spline's weights).
const SPAN_ROWS: usize = (LANE_MAX_DEGREE + 1) * (MAX_DIM + 1);

/// The spans whose coefficients a spline above degree 3 has needed so far, shared by its
/// coordinates and both sides (a few spans per side: short lists searched in order): in f64
/// for the filter (step 2 of [`spline_side`]), in `Ddi` for the proof (step 3).
/// (Inline room for eight spans, or span and coordinate pairs: uninitialised stack space,
/// where a list that outgrew two took a heap block of 3 KB, and then more, per curve.)
#[derive(Default)]
struct SpanCache {
    rows: SmallVec<[(usize, [f64; SPAN_ROWS]); 8]>,
    ddi: SmallVec<[(usize, [Ddi; SPAN_ROWS]); 8]>,
    /// the proofs of step 3 by span and coordinate (a single segment's two sides prove the
    /// same span)
    proofs: SmallVec<[ProofSlot; 8]>,
    /// a rational conic's rows in f64 (step 2) and in `Ddi` (step 3)
    conic: SmallVec<[(usize, [f64; CONIC_ROWS]); 8]>,
    conic_ddi: SmallVec<[(usize, ConicSpan); 8]>,
}

/// A coordinate's homogeneous rows X, W and Cartesian coefficients on one span of a rational
/// spline ([`rational_span`]).
type RationalRows = (
    [Ddi; LANE_MAX_DEGREE + 1],
    [Ddi; LANE_MAX_DEGREE + 1],
    [Ddi; LANE_MAX_DEGREE + 1],
);

/// A proof slot of [`SpanCache`]: (span, coordinate), and the proof once made.
type ProofSlot = ((usize, usize), Option<CoefficientProof>);

/// The entry for key k (a span, or a span and a coordinate) of a short list, made by `new` on
/// first use.
fn cached<'a, K: PartialEq + 'a, T: 'a, A: smallvec::Array<Item = (K, T)>>(
    list: &'a mut SmallVec<A>,
    k: K,
    new: impl FnOnce() -> T,
) -> &'a mut T {
    let at = match list.iter().position(|r| r.0 == k) {
        Some(i) => i,
        None => {
            list.push((k, new()));
            list.len() - 1
        }
    };
    &mut list[at].1
}

impl SpanCache {
    /// Span k's f64 coefficients ([`span_coefficients_rows`]).
    fn get(&mut self, s: &Simple, k: usize) -> &[f64; SPAN_ROWS] {
        cached(&mut self.rows, k, || span_coefficients_rows(s, k))
    }

    /// A rational conic's span k: its f64 rows ([`conic_rows`]).
    fn conic(&mut self, s: &Simple, w: &[f64], k: usize) -> &[f64; CONIC_ROWS] {
        cached(&mut self.conic, k, || conic_rows(s, w, k))
    }

    /// A rational conic's span k in `Ddi` ([`ConicSpan`]).
    fn conic_ddi(&mut self, s: &Simple, w: &[f64], k: usize) -> &mut ConicSpan {
        cached(&mut self.conic_ddi, k, || ConicSpan::new(s, w, k))
    }

    /// The slot of the proof on span k for coordinate j (empty until the first side asks).
    fn proof(&mut self, k: usize, j: usize) -> &mut Option<CoefficientProof> {
        cached(&mut self.proofs, (k, j), || None)
    }

    /// Coordinate j's row of [`SpanCache::get_ddi`] (a polynomial spline's), zeros past p.
    fn coordinate_ddi(&mut self, s: &Simple, k: usize, j: usize) -> [Ddi; LANE_MAX_DEGREE + 1] {
        let (p, d) = (s.p, s.d);
        let rows = self.get_ddi(s, k);
        std::array::from_fn(|i| {
            if i <= p {
                rows[i * d + j]
            } else {
                Ddi::exact(0.0)
            }
        })
    }

    /// Span k's `Ddi` coefficients ([`span_coefficients_rows`]), end values that are exactly
    /// doubles made exact (`fraction_free::snap_exact_ends`, as the curve-wide sweep of
    /// `TightEval` does: an extremum at a knot whose value is a double is then attained at its
    /// bound).
    fn get_ddi(&mut self, s: &Simple, k: usize) -> &[Ddi; SPAN_ROWS] {
        cached(&mut self.ddi, k, || {
            let mut q = span_coefficients_rows::<Ddi>(s, k);
            let len = (s.p + 1) * s.d;
            crate::spline::fraction_free::snap_exact_ends(s.curve, k, &mut q[..len]);
            q
        })
    }
}

/// The same coefficients by the generic insertion (`bspline::clamp_span`), for the tests.
#[cfg(test)]
fn span_coefficients_by_insertion<S: Scalar>(
    s: &Simple,
    j: usize,
    k: usize,
) -> [S; LANE_MAX_DEGREE + 1] {
    let p = s.p;
    let mut t = [0.0f64; 2 * LANE_MAX_DEGREE + 2];
    t[..2 * p + 2].copy_from_slice(&s.knots[k - p..=k + p + 1]);
    let mut q: [S; LANE_MAX_DEGREE + 1] = std::array::from_fn(|_| S::zero());
    for (i, v) in q.iter_mut().enumerate().take(p + 1) {
        *v = S::from_f64(s.pts[(k - p + i) * s.d + j]);
    }
    clamp_span(p, 1, &mut t[..2 * p + 2], &mut q[..=p]);
    q
}

/// The `hull` coordinate box of coordinate j, written to the blank box `cb`: the control-point box (convex
/// hull property, thesis prop. 2.1; exact), the end control points as attained values (a
/// clamped end is a control point), each bound's extremum the support of the first control
/// point that attains it (`Simple::extreme_at`; the whole domain for a single segment). The
/// driver's facts hold by construction (the bounds are the control-point range, the inner
/// bounds end values inside it).
fn hull_coord(s: &Simple, j: usize, cb: &mut CoordBox) {
    let (lo, hi) = s.range[j];
    let (e0, e1) = (s.pts[j], s.pts[s.n * s.d + j]);
    let arg = |i: usize| {
        let (mut u_lo, mut u_hi) = (s.a, s.b);
        if s.n > s.p {
            u_lo = s.knots[i].max(s.a);
            u_hi = s.knots[i + s.p + 1].min(s.b);
        }
        Extremum {
            u_lo,
            u_hi,
            unique: false,
            kind: CandidateKind::ControlPoint,
        }
    };
    let (emax, emin) = if e0 > e1 { (e0, e1) } else { (e1, e0) };
    let (i_min, i_max) = s.extreme_at[j];
    cb.lo = lo;
    cb.hi = hi;
    cb.inner_lo = emin;
    cb.inner_hi = emax;
    cb.argmin.push(arg(i_min));
    cb.argmax.push(arg(i_max));
    cb.stats.point_evaluations = 2;
    cb.termination = Termination::Direct;
}

/// A blank coordinate box ([`CoordBox::BLANK`]) appended to `e`, to be filled in place.
#[inline]
fn blank_slot(e: &mut Enclosure) -> &mut CoordBox {
    e.coords.push(CoordBox::BLANK);
    let last = e.coords.len() - 1;
    &mut e.coords[last]
}

/// The certificate's first round on both sides of `cb` (`certify::quick`), with the
/// coordinate's control-point range (its scale) and the (min, max) of the exact values at
/// knots of multiplicity >= p that the caller reads ((inf, -inf) for none): sets the flags it
/// proves, and returns whether a side is left to the full certification.
#[inline]
fn first_rounds(cb: &mut CoordBox, (plo, phi): (f64, f64), (klo, khi): (f64, f64)) -> bool {
    let scale = plo.abs().max(phi.abs()).max(f64::MIN_POSITIVE);
    let (ok_hi, open_hi) = certify::quick_flags(cb.hi, cb.inner_hi, cb.witness_hi, khi, scale);
    let (ok_lo, open_lo) = certify::quick_flags(-cb.lo, -cb.inner_lo, -cb.witness_lo, -klo, scale);
    cb.optimal_hi = ok_hi;
    cb.optimal_lo = ok_lo;
    open_hi | open_lo
}

/// The `hull` lane's coordinates, written to `e` (empty): [`hull_coord`] per coordinate, with
/// the certificates when `certify`. The driver's facts (`apply_facts`) hold by construction
/// and are not applied again: the outer bounds are the control-point range itself, the inner
/// bounds the end control points, which lie in it. The certificate's cheap part is the full
/// certification's first round ([`first_rounds`], `certify::quick`) with the hull's values (no witness:
/// -inf; attained: the end control points) and the exact values at knots of multiplicity p
/// (on a spline the curve passes through those control points: `certify::knot_points`):
/// `true` when a control point the curve passes through attains the bound, `false` when
/// those values lie more than a few ulps of the scale below it, the full certification
/// (`certify::certify`) otherwise: the general path's flags.
fn hull_into(e: &mut Enclosure, c: &NurbsCurve, s: &Simple, certify: bool) {
    let mut open = false;
    // per coordinate the (min, max) of the control values at knots of multiplicity >= p
    let mut knot_values = [(f64::INFINITY, f64::NEG_INFINITY); MAX_DIM];
    if certify && s.n > s.p {
        certify::knot_points(c, |i| {
            let q = &s.pts[i * s.d..(i + 1) * s.d];
            for (kv, &x) in knot_values.iter_mut().zip(q) {
                *kv = (kv.0.min(x), kv.1.max(x));
            }
        });
    }
    for (j, &kv) in knot_values.iter().enumerate().take(s.d) {
        let clock = Clock::start();
        let cb = blank_slot(e);
        hull_coord(s, j, cb);
        if certify {
            open |= first_rounds(cb, s.range[j], kv);
        }
        cb.stats.time_total = clock.elapsed();
    }
    if open {
        certify::certify(c, e);
    }
}

/// The enclosure of a [`Simple`] curve by a strategy named `name` answering with `lane`, with
/// the certificates when `certify` (see the module docs), written to `e` (whose coordinates
/// are replaced); `false` sends the curve to the general path (`e` is then unspecified).
/// (An out-parameter rather than an `Option<Enclosure>`: the caller's result is built in
/// place, without moving the inline per-coordinate storage.)
#[inline]
pub fn enclose_into(
    e: &mut Enclosure,
    lane: Lane,
    name: &'static str,
    c: &NurbsCurve,
    s: &Simple,
    certify: bool,
) -> bool {
    e.strategy = name;
    e.verified = true;
    if !e.coords.is_empty() {
        e.coords.clear();
    }
    if lane == Lane::Hull {
        // (the control-point box's attained values are the end control points: a clamped
        // curve's alone)
        if !s.clamped {
            return false;
        }
        hull_into(e, c, s, certify);
        return true;
    }
    let mut cache = None;
    // (a single conic arc by its own path: a branch here rather than in `tight_sides`, whose
    // code for the cubic it made longer, +90 instructions per 2-D cubic)
    let arc = s.w.filter(|_| s.n == s.p && s.p == 2);
    for j in 0..s.d {
        let clock = Clock::start();
        // (written in place into the blank box, whose termination is `Converged`)
        let cb = blank_slot(e);
        let done = match arc {
            Some(w) => conic_segment(s, w, j, cb),
            None => tight_sides(s, j, cb, &mut cache),
        };
        if done.is_none() {
            return false;
        }
        cb.stats.time_total = clock.elapsed();
    }
    let mut open = false;
    for (j, cb) in e.coords.iter_mut().enumerate() {
        let (plo, phi) = s.range[j];
        let ends = [s.pts[j], s.pts[s.n * s.d + j]].map(|x| s.clamped.then_some(x));
        apply_facts(cb, (plo, phi), ends, true);
        if certify {
            open |= first_rounds(cb, (plo, phi), (f64::INFINITY, f64::NEG_INFINITY));
        }
    }
    if open {
        certify::certify(c, e);
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::exact::Exact;
    use crate::testkit::gen::{self, Family};
    use std::cmp::Ordering;

    /// The windows by comparisons equal the exponent tests they replace: powers of two and
    /// their neighbours around both thresholds, subnormals, the extremes and random values.
    #[test]
    fn window_comparisons_match_the_exponent_tests() {
        use crate::enclose::driver::exponent;
        let mut xs = vec![f64::MIN_POSITIVE, f64::from_bits(1), f64::MAX, 1.0, 0.75];
        for k in [-82, -81, -80, -79, 79, 80, 81, 999, 1000, 1001] {
            let p = 2f64.powi(k);
            xs.extend([p, p.next_up(), p.next_down(), 1.5 * p]);
        }
        let mut r = gen::rng(29);
        use rand::Rng;
        xs.extend((0..2000).map(|_| f64::from_bits(r.random_range(1..0x7ff0_0000_0000_0000u64))));
        for x in xs {
            assert_eq!(
                beyond_coord_window(x),
                exponent(x).abs() > COORD_WINDOW,
                "{x:e}"
            );
            for y in [x, -x] {
                assert_eq!(beyond_knot_window(y), exponent(y) > KNOT_EXP, "{y:e}");
            }
        }
    }

    /// [`span_end_kinds`] against `bezier::end_kind` on every non-empty span of random
    /// splines of the lane (clamped or not, knots of every multiplicity up to p).
    #[test]
    fn span_end_kinds_match_end_kind() {
        use rand::Rng;
        let mut r = gen::rng(47);
        let mut kinds = [0usize; 3];
        for _ in 0..3000 {
            let p = r.random_range(2..=5);
            let n = r.random_range(p + 1..=p + 10);
            let mut k: Vec<f64> = Vec::with_capacity(n + p + 2);
            let clamped = r.random_bool(0.5);
            if clamped {
                k.extend(std::iter::repeat_n(0.0, p + 1));
            }
            let mut u = 1.0;
            while k.len() < n + 1 + (!clamped as usize) * (p + 1) {
                let m = r
                    .random_range(1..=p)
                    .min(n + 1 + (!clamped as usize) * (p + 1) - k.len());
                k.extend(std::iter::repeat_n(u, m));
                u += 1.0;
            }
            k.truncate(n + 1 + (!clamped as usize) * (p + 1));
            let last = u;
            while k.len() < n + p + 2 {
                k.push(if clamped { last } else { u });
                if !clamped {
                    u += 1.0;
                }
            }
            let pts: Vec<Vec<f64>> = (0..=n).map(|i| vec![i as f64, (i * i) as f64]).collect();
            let Ok(c) = NurbsCurve::new(p, k.clone(), pts, None) else {
                continue;
            };
            let Some(s) = Simple::of(&c) else {
                continue;
            };
            for sp in p..=n {
                if k[sp] < k[sp + 1] {
                    let want = [sp, sp + 1].map(|i| crate::enclose::bezier::end_kind(&c, k[i]));
                    assert_eq!(span_end_kinds(&s, sp), want, "span {sp} of {k:?}");
                    for kd in want {
                        kinds[match kd {
                            CandidateKind::EndPoint => 0,
                            CandidateKind::Knot => 1,
                            _ => 2,
                        }] += 1;
                    }
                }
            }
        }
        assert!(kinds.iter().all(|&m| m > 100), "{kinds:?}");
    }

    /// [`each_above`] calls back exactly the indices whose sign-adjusted control value exceeds
    /// the threshold, ascending: random splines of 1 to 4 coordinates and 4 to 40 control
    /// points (blocks of eight and the remainder), both signs, thresholds at and between the
    /// values.
    #[test]
    fn each_above_finds_the_values_above() {
        use rand::Rng;
        let mut r = gen::rng(59);
        for _ in 0..3000 {
            let (d, npts) = (r.random_range(1..=4), r.random_range(4..=40));
            let pts: Vec<Vec<f64>> = (0..npts)
                .map(|_| (0..d).map(|_| r.random_range(-8i32..8) as f64).collect())
                .collect();
            let mut k = vec![0.0; 4];
            k.extend((1..npts - 3).map(|i| i as f64));
            k.extend([(npts - 3) as f64; 4]);
            let c = NurbsCurve::new(3, k, pts.clone(), None).expect("a clamped cubic spline");
            let s = Simple::of(&c).expect("in the lane");
            let j = r.random_range(0..d);
            let sign = if r.random_bool(0.5) { 1.0 } else { -1.0 };
            let t = r.random_range(-9i32..9) as f64 + if r.random_bool(0.5) { 0.5 } else { 0.0 };
            let want: Vec<usize> = (0..npts).filter(|&i| sign * pts[i][j] > t).collect();
            let mut got = Vec::new();
            each_above(&s, j, sign, t, |i| got.push(i));
            assert_eq!(got, want, "d = {d}, j = {j}, sign {sign}, t = {t}");
        }
    }

    /// [`jump_knot`] against the run count it replaced: random non-decreasing knot vectors
    /// with runs of every length up to p + 2 (inside the domain, at its ends and beyond them),
    /// p = 2 ..= 5.
    #[test]
    fn jump_knot_matches_the_run_count() {
        use rand::Rng;
        fn reference(k: &[f64], p: usize, n: usize) -> bool {
            let b = k[n + 1];
            let mut run = 1;
            for w in k[p..=n + 1].windows(2) {
                run = if w[1] == w[0] { run + 1 } else { 1 };
                if run > p && w[1] < b {
                    return true;
                }
            }
            false
        }
        let mut r = gen::rng(43);
        let mut seen = [0usize; 2];
        for _ in 0..20_000 {
            let p = r.random_range(2..=5);
            let n = r.random_range(p + 1..=p + 12);
            let mut k = Vec::with_capacity(n + p + 2);
            let mut u = 0.0;
            while k.len() < n + p + 2 {
                let m = r.random_range(1..=p + 2).min(n + p + 2 - k.len());
                k.extend(std::iter::repeat_n(u, m));
                u += 1.0;
            }
            let want = reference(&k, p, n);
            assert_eq!(jump_knot(&k, p, n), want, "p = {p}, n = {n}, {k:?}");
            seen[want as usize] += 1;
        }
        assert!(seen[0] > 1000 && seen[1] > 1000, "{seen:?}");
    }

    /// The branch-free `scan` against the compare-and-jump scan it replaced, bit for bit:
    /// random points with many ties, both zeros, subnormals and the extremes, D = 1..4.
    #[test]
    fn scan_matches_the_compare_and_jump_scan() {
        use rand::Rng;
        type Scan<const D: usize> = ([(u64, u64); D], [(usize, usize); D]);
        fn reference<const D: usize>(pts: &[f64]) -> Scan<D> {
            let mut range = [(0.0f64, 0.0f64); D];
            let mut at = [(0usize, 0usize); D];
            for (j, r) in range.iter_mut().enumerate() {
                *r = (pts[j], pts[j]);
            }
            for (i, q) in pts[D..].chunks_exact(D).enumerate() {
                for j in 0..D {
                    let x = q[j];
                    if x < range[j].0 {
                        range[j].0 = x;
                        at[j].0 = i + 1;
                    }
                    if x > range[j].1 {
                        range[j].1 = x;
                        at[j].1 = i + 1;
                    }
                }
            }
            (range.map(|(a, b)| (a.to_bits(), b.to_bits())), at)
        }
        fn check<const D: usize>(pts: &[f64]) {
            let (mut range, mut at) = ([(0.0, 0.0); MAX_DIM], [(0, 0); MAX_DIM]);
            scan::<D>(pts, &mut range, &mut at);
            let (want_range, want_at) = reference::<D>(pts);
            for j in 0..D {
                assert_eq!(
                    (range[j].0.to_bits(), range[j].1.to_bits()),
                    want_range[j],
                    "{pts:?}"
                );
                assert_eq!(at[j], want_at[j], "{pts:?}");
            }
        }
        let mut r = gen::rng(41);
        let pool = [
            0.0,
            -0.0,
            1.0,
            -1.0,
            2.5,
            f64::MIN_POSITIVE,
            f64::from_bits(1),
            -f64::MAX,
            f64::MAX,
            1e-300,
        ];
        for it in 0..20_000 {
            let n = r.random_range(1..9);
            let d = 1 + it % 4;
            let pts: Vec<f64> = (0..n * d)
                .map(|_| {
                    if r.random_range(0..3) == 0 {
                        r.random_range(-1e3..1e3)
                    } else {
                        pool[r.random_range(0..pool.len())]
                    }
                })
                .collect();
            match d {
                1 => check::<1>(&pts),
                2 => check::<2>(&pts),
                3 => check::<3>(&pts),
                _ => check::<4>(&pts),
            }
        }
    }

    /// `hull_coord` against its definition: the bounds the exact control-point range, the
    /// inner bounds the end control points, each bound's extremum the support of the first
    /// control point equal to it (searched here), on single segments and splines of several
    /// families, with repeated extreme values (flat coordinates).
    #[test]
    fn hull_coordinates_match_their_definition() {
        let mut r = gen::rng(23);
        let mut checked = 0;
        for fam in [
            Family::ClampedUniform,
            Family::MultipleKnots,
            Family::FlatCoordinates,
            Family::Mixed,
        ] {
            for _ in 0..400 {
                let c = fam.curve(&mut r);
                let Some(s) = Simple::of(&c) else { continue };
                for j in 0..s.d {
                    let mut cb = CoordBox::BLANK;
                    hull_coord(&s, j, &mut cb);
                    let (lo, hi) = c.coord_range(j, 0..=s.n);
                    assert_eq!((cb.lo, cb.hi), (lo, hi));
                    let (e0, e1) = (c.control_point(0)[j], c.control_point(s.n)[j]);
                    assert_eq!((cb.inner_lo, cb.inner_hi), (e0.min(e1), e0.max(e1)));
                    for (m, args) in [(lo, &cb.argmin), (hi, &cb.argmax)] {
                        let i = (0..=s.n).find(|&i| c.control_point(i)[j] == m).unwrap();
                        let (u_lo, u_hi) = if s.n > s.p {
                            (s.knots[i].max(s.a), s.knots[i + s.p + 1].min(s.b))
                        } else {
                            (s.a, s.b)
                        };
                        assert_eq!(args.len(), 1);
                        assert_eq!((args[0].u_lo, args[0].u_hi), (u_lo, u_hi), "{fam:?} {c:?}");
                    }
                    checked += 1;
                }
            }
        }
        assert!(checked > 200, "{checked}");
    }

    /// The quadratic and cubic spline spans whose closed-form proof gives up (splines of the
    /// `extrema_at_knots` family: symmetric about a knot, whose end slope there is zero) are
    /// proved by the Descartes route on the insertion's coefficients, as `spline_side` retries
    /// them, rather than left to the general fast path: of the sides the closed form leaves
    /// open on the spans of 300 such splines, nine in ten within the lane's gap. Fails when the
    /// route gives an open end up.
    #[test]
    fn the_descartes_route_takes_the_closed_form_s_open_ends() {
        let mut r = gen::rng(43);
        let (mut curves, mut open, mut proved) = (0, 0, 0);
        while curves < 300 {
            let c = Family::ExtremaAtKnots.curve(&mut r);
            if !(2..=3).contains(&c.degree()) || c.is_rational() {
                continue;
            }
            let Some(s) = Simple::of(&c) else {
                continue;
            };
            if s.n == s.p {
                continue;
            }
            curves += 1;
            let mut cache = SpanCache::default();
            for j in 0..s.d {
                let gap = max_gap(&s, j);
                for k in (s.p..=s.n).filter(|&k| s.knots[k] < s.knots[k + 1]) {
                    let qd = step3_coefficients(&s, j, k);
                    let seg = Segment {
                        c: &qd[..=s.p],
                        a: s.knots[k],
                        b: s.knots[k + 1],
                        end_kinds: span_end_kinds(&s, k),
                        right_attained: true,
                    };
                    for side in 0..2 {
                        if one_side(side, gap, |need, raw| raw_sides_into(&seg, need, raw))
                            .is_some()
                        {
                            continue;
                        }
                        open += 1;
                        let q = cache.coordinate_ddi(&s, k, j);
                        let seg = Segment {
                            c: &q[..=s.p],
                            ..seg
                        };
                        let r =
                            one_side(side, gap, |need, raw| descartes_sides_into(&seg, need, raw));
                        proved += r.is_some() as usize;
                    }
                }
            }
        }
        eprintln!("OPEN {open} PROVED {proved}");
        assert!(
            open >= 100 && proved * 10 >= open * 9,
            "{proved} of {open} proved"
        );
    }

    /// The `hull` lane's whole result (bounds, attained values, extrema, certificates) is the
    /// general path's: `ControlHull` under the driver against the same strategy without the
    /// lane (so `apply_facts` and the full certification run), on the families the lane
    /// takes, flat coordinates and ties between end and interior control values included.
    #[test]
    fn hull_lane_equals_the_general_path() {
        use crate::enclose::{drive_with, BoxEncloser, ControlHull, Guarantee};
        struct NoLane;
        impl BoxEncloser for NoLane {
            fn name(&self) -> &'static str {
                "hull"
            }
            fn guarantee(&self) -> Guarantee {
                Guarantee::Verified
            }
            fn enclose_prepared(&self, c: &NurbsCurve) -> Enclosure {
                ControlHull.enclose_prepared(c)
            }
        }
        let mut r = gen::rng(31);
        let (mut taken, mut optimal, mut open) = (0, 0, 0);
        for fam in [
            Family::ClampedUniform,
            Family::MultipleKnots,
            Family::FlatCoordinates,
            Family::NearDegenerateCubic,
            Family::Mixed,
        ] {
            for i in 0..300 {
                let mut c = fam.curve(&mut r);
                if i % 3 == 0 {
                    // an interior control value one double above the largest end value: the
                    // quick rule leaves it to the full certification
                    let n = c.num_points() - 1;
                    let (e0, e1) = (c.control_point(0)[0], c.control_point(n)[0]);
                    let mut pts = c.control_points();
                    if pts.len() > 2 {
                        pts[1][0] = e0.max(e1).next_up();
                        let w = c.weights().map(|w| w.to_vec());
                        c = NurbsCurve::new(c.degree(), c.knots().to_vec(), pts, w).unwrap();
                    }
                }
                if Simple::of(&c).is_none() {
                    continue;
                }
                taken += 1;
                for certify in [true, false] {
                    let lane = drive_with(&ControlHull, &c, certify);
                    let general = drive_with(&NoLane, &c, certify);
                    assert_eq!(lane, general, "{fam:?} {c:?}");
                }
                let e = drive_with(&ControlHull, &c, true);
                optimal += e.coords.iter().filter(|cb| cb.optimal_hi).count();
                let scale = c.coord_scale(0).max(f64::MIN_POSITIVE);
                let cb = &e.coords[0];
                open += usize::from(
                    certify::quick(
                        cb.hi,
                        cb.inner_hi,
                        f64::NEG_INFINITY,
                        f64::NEG_INFINITY,
                        scale,
                    )
                    .is_none(),
                );
            }
        }
        assert!(
            taken > 300 && optimal > 100 && open > 20,
            "{taken} {optimal} {open}"
        );
    }

    /// The families of the closed-form tests: uniform, clustered and multiple knots, flat runs,
    /// extrema at knots, everything at once.
    const SPLINE_FAMILIES: [Family; 6] = [
        Family::ClampedUniform,
        Family::ClusteredKnots,
        Family::MultipleKnots,
        Family::FlatCoordinates,
        Family::ExtremaAtKnots,
        Family::Mixed,
    ];

    /// Calls `f(s, j, k)` for every coordinate j and non-empty span k of the polynomial splines
    /// (n > p >= 2) among `curves` that the lane takes.
    fn each_spline_span(curves: &[NurbsCurve], mut f: impl FnMut(&Simple, usize, usize)) {
        for c in curves {
            let Some(s) = Simple::of(c) else { continue };
            // (single segments and polylines have no closed-form spans; rational splines
            // have homogeneous rows: `rational_span_coefficients_are_within_their_bound`)
            if s.n == s.p || s.p == 1 || s.w.is_some() {
                continue;
            }
            for j in 0..s.d {
                for k in s.p..=s.n {
                    if s.knots[k] < s.knots[k + 1] {
                        f(&s, j, k);
                    }
                }
            }
        }
    }

    /// The closed form equals the exact insertion in rational arithmetic (so the formula is
    /// right), its f64 values are within the a-priori bound of `bezier::span_bounds` of the
    /// exact ones, and its `Ddi` values enclose them: quadratic and cubic splines with
    /// clustered, multiple and uniform knots.
    #[test]
    fn closed_form_span_coefficients_match_exact_insertion() {
        let mut r = gen::rng(17);
        let mut spans = 0;
        for fam in SPLINE_FAMILIES {
            let curves: Vec<NurbsCurve> = (0..60).map(|_| fam.curve(&mut r)).collect();
            each_spline_span(&curves, |s, j, k| {
                spans += 1;
                let ex = span_coefficients::<Exact>(s, j, k);
                let ins = span_coefficients_by_insertion::<Exact>(s, j, k);
                let f = span_coefficients::<f64>(s, j, k);
                let dd = span_coefficients::<Ddi>(s, j, k);
                let m = (k - s.p..=k).fold(0.0f64, |m, i| m.max(s.pts[i * s.d + j].abs()));
                let e = (2 * s.p) as f64 * (8.0 * f64::EPSILON) * m + f64::MIN_POSITIVE;
                for i in 0..=s.p {
                    assert!(ex[i] == ins[i], "{fam:?} span {k} coefficient {i}");
                    let err = ex[i].clone() - Exact::of(f[i]);
                    assert!(
                        err.cmp_f64(e) != Some(Ordering::Greater)
                            && err.cmp_f64(-e) != Some(Ordering::Less),
                        "{fam:?} span {k} b_{i}: f64 error above the bound"
                    );
                    let iv = dd[i].to_interval();
                    assert_eq!(ex[i].cmp_f64(iv.sup()).map(|o| o.is_le()), Some(true));
                    assert_eq!(ex[i].cmp_f64(iv.inf()).map(|o| o.is_ge()), Some(true));
                }
            });
        }
        assert!(spans > 500, "only {spans} spans checked");
    }

    /// The step-3 coefficients in double words ([`step3_coefficients`]) enclose the exact ones
    /// within their radius (hi + lo ± rad, compared in rational arithmetic, not rounded to f64),
    /// and are exact exactly where the `Ddi` closed form's are, with the same values: the
    /// families of the test above, and splines with small integer knots (repeated) and
    /// control values on a grid of 1/8 or of 2^-52 (cuts by ratios 1/2, 1/3, .. of values
    /// that are often exact), degree 2 and 3.
    #[test]
    fn dw_closed_form_encloses_the_exact_coefficients() {
        use rand::Rng;
        let mut r = gen::rng(53);
        let mut curves: Vec<NurbsCurve> = Vec::new();
        for fam in SPLINE_FAMILIES {
            curves.extend((0..60).map(|_| fam.curve(&mut r)));
        }
        for it in 0..400 {
            let p = r.random_range(2..=3);
            let n = r.random_range(p + 1..=p + 8);
            let mut k = vec![0.0; p + 1];
            let mut u = 0.0;
            while k.len() < n + 1 {
                u += r.random_range(1..=3) as f64;
                let m = r.random_range(1..=p).min(n + 1 - k.len());
                k.extend(std::iter::repeat_n(u, m));
            }
            k.extend(std::iter::repeat_n(u + 1.0, p + 1));
            let grid = if it % 2 == 0 {
                0.125
            } else {
                f64::EPSILON / 2.0
            };
            let pts: Vec<Vec<f64>> = (0..=n)
                .map(|_| vec![r.random_range(-64i64..64) as f64 * grid * 7.0])
                .collect();
            curves.extend(NurbsCurve::new(p, k, pts, None));
        }
        let (mut spans, mut exact, mut fast) = (0, 0, 0);
        each_spline_span(&curves, |s, j, k| {
            if s.p > 3 {
                return;
            }
            spans += 1;
            let ex = span_coefficients::<Exact>(s, j, k);
            let dw = step3_coefficients(s, j, k);
            let dd = span_coefficients::<Ddi>(s, j, k);
            fast += (0..=s.p).any(|i| dw[i] != dd[i]) as usize;
            for i in 0..=s.p {
                let (h, l, rad) = dw[i].parts();
                let err = ex[i].clone() - Exact::of(h) - Exact::of(l);
                assert!(
                    err.cmp_f64(rad) != Some(Ordering::Greater)
                        && err.cmp_f64(-rad) != Some(Ordering::Less),
                    "span {k} b_{i}: {:?} misses the exact value",
                    dw[i]
                );
                assert_eq!(
                    rad == 0.0,
                    dd[i].rad() == 0.0,
                    "span {k} b_{i}: {:?} against {:?}",
                    dw[i],
                    dd[i]
                );
                if rad == 0.0 {
                    assert_eq!(dw[i], dd[i]);
                    exact += 1;
                }
            }
        });
        assert!(
            spans > 1500 && exact > 1000 && fast > 400,
            "{spans} spans, {exact} exact, {fast} by double words"
        );
    }

    /// Above degree 3 the coefficients come from the insertion itself: exactly (in rational
    /// arithmetic) the piece that de Boor's evaluation gives, in f64 within the bound its doc
    /// derives, 2 (p - 1) 11.1 u M, of the exact ones, and the `Ddi` values (as computed, and
    /// with exact ends snapped, as the proof reads them) enclose them.
    /// Quartic and quintic splines with clustered knots (down to a few ulps apart), knots of
    /// multiplicity up to p, uneven intervals, domains moved and scaled across the knot window
    /// and magnitudes across the coordinate window.
    /// Knots and control points of a random clamped spline of degree p for the coefficient
    /// tests: interior knots clustered down to a few ulps or to 1e-9, or spread, a third of them
    /// repeated up to multiplicity p; the domain moved and scaled within the lane's knot window
    /// half the time ([off, off + 2^w], knots rounded there, so their differences are not the
    /// unit ones); 1-3 coordinates of magnitude 2^-70..2^70.
    fn random_spline(r: &mut impl rand::Rng, p: usize) -> (Vec<f64>, Vec<Vec<f64>>) {
        let mut inner: Vec<f64> = Vec::new();
        let base = r.random_range(0.1..0.9);
        for _ in 0..r.random_range(1..8) {
            let u = match r.random_range(0..4) {
                0 => base + r.random_range(-4.0..4.0) * f64::EPSILON,
                1 => base + r.random_range(-1.0..1.0) * 1e-9,
                _ => r.random_range(0.0..1.0),
            };
            let m = if r.random_range(0..3) == 0 {
                r.random_range(1..=p)
            } else {
                1
            };
            inner.extend(std::iter::repeat_n(u, m));
        }
        inner.retain(|&u| u > 0.0 && u < 1.0);
        inner.sort_by(f64::total_cmp);
        // (no interior multiplicity above p)
        let mut knots = vec![0.0; p + 1];
        for &u in &inner {
            if knots.iter().filter(|&&v| v == u).count() < p {
                knots.push(u);
            }
        }
        knots.extend(vec![1.0; p + 1]);
        if r.random_range(0..2) == 0 {
            let w = 2f64.powi(r.random_range(-25..=25));
            let off = [0.0, -w * 0.3, w * 1e6, -w * 3e3][r.random_range(0..4usize)];
            knots.iter_mut().for_each(|u| *u = off + *u * w);
        }
        let n = knots.len() - p - 2;
        let d = r.random_range(1..=3usize);
        let mag = 2f64.powi(r.random_range(-70..70));
        let pts = (0..=n)
            .map(|_| (0..d).map(|_| r.random_range(-1.0..1.0) * mag).collect())
            .collect();
        (knots, pts)
    }

    /// A rational spline of degree p on [`random_spline`]'s knots and points, weights spread
    /// over up to 2^12 at scales 2^-90..2^90, and its weights (`None`: not a valid curve).
    fn random_rational_spline(r: &mut impl rand::Rng, p: usize) -> Option<(NurbsCurve, Vec<f64>)> {
        let (knots, pts) = random_spline(r, p);
        let ws = 2f64.powi(r.random_range(-90..=90));
        let weights: Vec<f64> = (0..pts.len())
            .map(|_| ws * 2f64.powf(r.random_range(-6.0..6.0)))
            .collect();
        let c = NurbsCurve::new(p, knots, pts, Some(weights.clone())).ok()?;
        Some((c, weights))
    }

    /// The exact homogeneous rows `xr`, `wr` of coordinate j on span k = [a, b] give de Boor's
    /// exact value of the curve (`eval`, independent code, with the quotient rule) at the
    /// span's ends and inside.
    fn check_exact_rows(
        eval: &crate::spline::eval::CurveEval<Exact>,
        (k, j): (usize, usize),
        (a, b): (f64, f64),
        xr: &[Exact],
        wr: &[Exact],
    ) {
        for u in [a, b, a + 0.375 * (b - a)] {
            let want = eval.coord_derivs_in_span(k, &Exact::of(u), 0, j)[0].clone();
            let t = (Exact::of(u) - Exact::of(a)) / (Exact::of(b) - Exact::of(a));
            let got = crate::spline::bezier::de_casteljau_eval(xr, &t)
                / crate::spline::bezier::de_casteljau_eval(wr, &t);
            assert!(got == want, "span {k} coordinate {j} at {u}");
        }
    }

    /// The f64 Cartesian coefficients `f` (with their bounds) within their bounds of the exact
    /// quotients of the rows `xr`, `wr`, and the `Ddi` rows and quotients `d` enclosing the
    /// exact ones; `worst` the largest error as a share of its bound.
    fn check_quotients(
        (xr, wr): (&[Exact], &[Exact]),
        f: &[(f64, f64)],
        d: (&[Ddi], &[Ddi], &[Ddi]),
        worst: &mut f64,
    ) {
        for i in 0..xr.len() {
            let bi = xr[i].clone() / wr[i].clone();
            let (bf, e) = f[i];
            let err = bi.clone() - Exact::of(bf);
            assert!(
                err.cmp_f64(e) != Some(Ordering::Greater)
                    && err.cmp_f64(-e) != Some(Ordering::Less),
                "b_{i}: f64 error above the bound {e:e}"
            );
            if e > 0.0 {
                *worst = worst.max((bi.to_f64() - bf).abs() / e);
            }
            for (v, x) in [(d.0[i], &xr[i]), (d.1[i], &wr[i]), (d.2[i], &bi)] {
                let iv = v.to_interval();
                assert_eq!(x.cmp_f64(iv.sup()).map(|o| o.is_le()), Some(true));
                assert_eq!(x.cmp_f64(iv.inf()).map(|o| o.is_ge()), Some(true));
            }
        }
    }

    /// A rational conic's span coefficients ([`conic_rows`], [`conic_coefficients_f64`],
    /// [`ConicSpan`]) on 300 random rational quadratic splines (clustered knots down to a few
    /// ulps, double knots, domains moved and scaled across the knot window, coordinates
    /// 2^-70..2^70, weights spread over up to 2^12 at scales 2^-90..2^90, 1-3 coordinates):
    /// the exact homogeneous coefficients (the closed form in exact arithmetic) give de Boor's
    /// exact value of the curve (`CurveEval`, independent code, with the quotient rule) at the
    /// span's ends and inside; the f64 Cartesian coefficients lie within their bounds of the
    /// exact ones; the `Ddi` rows and Cartesian coefficients (ends snapped at double knots)
    /// enclose them; and the bound is not vacuous (errors above a hundredth of it occur).
    /// Fails with the weights' error term dropped, and with the end snapped at a simple knot.
    #[test]
    fn conic_span_coefficients_are_within_their_bound() {
        let mut r = gen::rng(43);
        let (mut spans, mut worst) = (0, 0.0f64);
        for _ in 0..300 {
            let p = 2;
            let Some((c, weights)) = random_rational_spline(&mut r, p) else {
                continue;
            };
            let (n, d) = (c.num_points() - 1, c.dim());
            let Some(s) = Simple::of(&c) else { continue };
            let w = &weights[..];
            let eval = crate::spline::eval::CurveEval::<Exact>::new(&c, 0);
            for k in p..=n {
                if s.knots[k] >= s.knots[k + 1] {
                    continue;
                }
                spans += 1;
                let exact = conic_rows::<Exact>(&s, w, k);
                let rows = conic_rows::<f64>(&s, w, k);
                let mut dspan = ConicSpan::new(&s, w, k);
                let (a, b) = (s.knots[k], s.knots[k + 1]);
                for j in 0..d {
                    let xr = &exact[3 * j..3 * j + 3];
                    let wr = &exact[3 * d..3 * d + 3];
                    check_exact_rows(&eval, (k, j), (a, b), xr, wr);
                    let f = conic_coefficients_f64(&s, w, &rows, j, k).expect("finite");
                    let (dx, dw, dq) = dspan.coordinate(&s, w, k, j);
                    check_quotients((xr, wr), &f, (&dx, &dw, &dq), &mut worst);
                }
            }
        }
        assert!(spans > 500, "only {spans} spans checked");
        assert!(worst > 0.01, "largest error {worst} of the bound");
    }

    /// A rational spline's span coefficients above degree 2 ([`span_coefficients_rows`] on the
    /// homogeneous rows, [`rational_coefficients_f64`], [`rational_span`]) on 200 random
    /// rational splines of degree 3 to 5 (clustered knots down to a few ulps, knots of
    /// multiplicity up to p, domains moved and scaled across the knot window, coordinates
    /// 2^-70..2^70, weights spread over up to 2^12 at scales 2^-90..2^90, 1-3 coordinates): the
    /// exact homogeneous coefficients give de Boor's exact value of the curve (`CurveEval`,
    /// independent code, with the quotient rule) at the span's ends and inside; the f64
    /// Cartesian coefficients lie within their bounds of the exact ones; the `Ddi` rows and
    /// Cartesian coefficients (ends snapped at knots of multiplicity p) enclose them; and the
    /// bound is not vacuous (errors above a hundredth of it occur).
    #[test]
    fn rational_span_coefficients_are_within_their_bound() {
        use rand::Rng;
        let mut r = gen::rng(47);
        let (mut spans, mut worst, mut worst_cut) = (0, 0.0f64, 0.0f64);
        for _ in 0..200 {
            let p = r.random_range(3..=LANE_MAX_DEGREE);
            let Some((c, weights)) = random_rational_spline(&mut r, p) else {
                continue;
            };
            let (n, d) = (c.num_points() - 1, c.dim());
            let Some(s) = Simple::of(&c) else { continue };
            let w = &weights[..];
            let h = d + 1;
            let eval = crate::spline::eval::CurveEval::<Exact>::new(&c, 0);
            for k in p..=n {
                if s.knots[k] >= s.knots[k + 1] {
                    continue;
                }
                spans += 1;
                let exact = span_coefficients_rows::<Exact>(&s, k);
                let rows = span_coefficients_rows::<f64>(&s, k);
                let drows = *SpanCache::default().get_ddi(&s, k);
                let (a, b) = (s.knots[k], s.knots[k + 1]);
                for j in 0..d {
                    let xr: Vec<Exact> = (0..=p).map(|i| exact[i * h + j].clone()).collect();
                    let wr: Vec<Exact> = (0..=p).map(|i| exact[i * h + d].clone()).collect();
                    check_exact_rows(&eval, (k, j), (a, b), &xr, &wr);
                    let f = rational_coefficients_f64(&s, w, &rows, j, k).expect("finite");
                    let (dx, dw, dq) = rational_span(&s, &drows, j, k);
                    // (the rows themselves within the insertion's bound per cut, 2 (p - 1)
                    // cuts of 11.1 u M each, M the row's largest |input|; the products' own
                    // rounding, one u M more, on X)
                    let (mut mx, mut mw) = (0.0f64, 0.0f64);
                    for (l, &wl) in w.iter().enumerate().take(k + 1).skip(k - p) {
                        mx = mx.max((wl * s.pts[l * d + j]).abs());
                        mw = mw.max(wl);
                    }
                    let cut = 2.0 * (p - 1) as f64 * (f64::EPSILON / 2.0);
                    for i in 0..=p {
                        for (row, x, m, extra) in [(j, &xr[i], mx, 1.0), (d, &wr[i], mw, 0.0)] {
                            let e = (11.1 * cut + extra * f64::EPSILON / 2.0) * m;
                            let err = x.clone() - Exact::of(rows[i * h + row]);
                            assert!(
                                err.cmp_f64(e + f64::MIN_POSITIVE) != Some(Ordering::Greater)
                                    && err.cmp_f64(-e - f64::MIN_POSITIVE) != Some(Ordering::Less),
                                "p {p} span {k} row {row} coefficient {i}: above the bound"
                            );
                            if m > 0.0 {
                                worst_cut = worst_cut
                                    .max((x.to_f64() - rows[i * h + row]).abs() / (cut * m));
                            }
                        }
                    }
                    check_quotients((&xr, &wr), &f, (&dx, &dw, &dq), &mut worst);
                }
            }
        }
        assert!(spans > 400, "only {spans} spans checked");
        assert!(worst > 0.01, "largest error {worst} of the bound");
        // (the rows' bound is not vacuous: errors of a few u M per cut do occur)
        assert!(worst_cut > 0.1, "largest error per cut {worst_cut} u M");
    }

    #[test]
    fn inserted_span_coefficients_are_within_their_bound() {
        use rand::Rng;
        let mut r = gen::rng(41);
        let (mut spans, mut worst) = (0, 0.0f64);
        for _ in 0..200 {
            let p = r.random_range(4..=LANE_MAX_DEGREE);
            let (knots, pts) = random_spline(&mut r, p);
            let (n, d) = (pts.len() - 1, pts[0].len());
            let Ok(c) = NurbsCurve::new(p, knots, pts, None) else {
                continue;
            };
            let Some(s) = Simple::of(&c) else { continue };
            let eval = crate::spline::eval::CurveEval::<Exact>::new(&c, 0);
            for k in p..=n {
                if s.knots[k] >= s.knots[k + 1] {
                    continue;
                }
                spans += 1;
                let mut cache = SpanCache::default();
                let drows = *cache.get_ddi(&s, k);
                let (a, b) = (s.knots[k], s.knots[k + 1]);
                for j in 0..d {
                    let ex = span_coefficients::<Exact>(&s, j, k);
                    // (the insertion against de Boor's evaluation, independent code, exactly:
                    // the Bézier polynomial of the coefficients at t = (u - a) / (b - a) is
                    // C_j(u) at the span's ends and inside)
                    for u in [a, b, a + 0.375 * (b - a)] {
                        let want = eval.coord_derivs_in_span(k, &Exact::of(u), 0, j)[0].clone();
                        let t = (Exact::of(u) - Exact::of(a)) / (Exact::of(b) - Exact::of(a));
                        let got = crate::spline::bezier::de_casteljau_eval(&ex[..=p], &t);
                        assert!(got == want, "p {p} span {k} coordinate {j} at {u}");
                    }
                    let f = span_coefficients::<f64>(&s, j, k);
                    let dd = span_coefficients::<Ddi>(&s, j, k);
                    let m = (k - p..=k).fold(0.0f64, |m, i| m.max(s.pts[i * d + j].abs()));
                    let e = 2.0 * (p - 1) as f64 * 11.1 * (f64::EPSILON / 2.0) * m;
                    for i in 0..=p {
                        let err = ex[i].clone() - Exact::of(f[i]);
                        assert!(
                            err.cmp_f64(e + f64::MIN_POSITIVE) != Some(Ordering::Greater)
                                && err.cmp_f64(-e - f64::MIN_POSITIVE) != Some(Ordering::Less),
                            "p {p} span {k} b_{i}: f64 error above the bound"
                        );
                        if m > 0.0 {
                            let rel = (ex[i].to_f64() - f[i]).abs() / (m * f64::EPSILON / 2.0);
                            worst = worst.max(rel / (2.0 * (p - 1) as f64));
                        }
                        for v in [dd[i], drows[i * d + j]] {
                            let iv = v.to_interval();
                            assert_eq!(ex[i].cmp_f64(iv.sup()).map(|o| o.is_le()), Some(true));
                            assert_eq!(ex[i].cmp_f64(iv.inf()).map(|o| o.is_ge()), Some(true));
                        }
                    }
                }
            }
        }
        assert!(spans > 500, "only {spans} spans checked");
        // (the bound is not vacuous: errors of a few u M per cut do occur)
        assert!(worst > 0.1, "largest error per cut {worst} u M");
    }
}
