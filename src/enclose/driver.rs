//! The driver every strategy runs under ([`drive`], called by `BoxEncloser::enclose`): exact
//! power-of-two rescaling of extreme curves before enclosing them.
//!
//! A valid curve may have coordinates near 1e±300, weights near 1e±300 or a parameter domain of
//! length 1e-300. The strategies then work on intermediates that overflow or underflow (the
//! homogeneous points w_i P_i, derivatives ~ p^2 w^2 P / Δu^2, double-double low parts): the
//! results stay sound (intervals overflow to ±inf, never to a wrong finite value) but can be
//! infinite or loose. [`drive`] maps such a curve to an equivalent well-scaled one, encloses
//! that, and maps the box back.
//!
//! # Why the map is exact
//!
//! Multiplying an f64 by 2^k is exact whenever the result is a normal finite number (only the
//! exponent changes); it can round only when the result is subnormal (or overflows). Each of
//! the three maps below is applied only when every value stays exact, except the coordinate
//! map, whose subnormal rounding is accounted for explicitly:
//!
//! * **Coordinates** C_j -> 2^-e_j C_j: C_j(u) = sum_i R_i(u) P_ij with rational basis
//!   functions R_i >= 0, sum R_i = 1 (thesis def. 3.1) that do not depend on the coordinates,
//!   so the scaled control points give exactly the scaled curve, and the scaled box times 2^e_j
//!   is the box. If some scaled coordinate rounds (a value 2^1000 times smaller than the
//!   largest one of that coordinate falls into the subnormal range), it moves by at most
//!   half the smallest subnormal 2^-1075, hence (convex combination) so does the scaled curve
//!   at every u; the scaled outer bounds are then widened by one subnormal step (>= 2^-1074)
//!   and the inner bounds narrowed by one, which covers that error.
//! * **Weights** w_i -> 2^-f w_i: R_i = N_i w_i / sum_l N_l w_l is unchanged when all weights
//!   are multiplied by the same positive constant (thesis eq. 3.2). Applied only if exact.
//! * **Knots** u_i -> 2^-s u_i: the B-spline basis of the scaled knot vector is the basis of
//!   the original one at the scaled parameter, N_{i,p}(t; 2^-s U) = N_{i,p}(2^s t; U)
//!   (Cox-de Boor recursion, NURBS Book eq. 2.5, is invariant under a common scaling of u and
//!   the knots), so the scaled curve is a reparametrisation with the same image. Applied only
//!   if exact; parameters in the result (argmin / argmax) are mapped back outward.
//!
//! Mapping bounds back multiplies by 2^e again, with directed rounding where the result is
//! subnormal or overflows ([`scale_outward`]). Curves whose magnitudes are moderate (the
//! common case) are passed through untouched, so their results are bit-for-bit unchanged.
//!
//! # Rounded coordinates
//!
//! When a scaled control point coordinate is not exact (it fell into the subnormal range), the
//! curve is enclosed twice: once with every such coordinate rounded down, once rounded up
//! (each a curve C_dn <= C <= C_up at every u, because the rational basis functions are >= 0
//! and sum to 1). The lower bound and the attained upper value come from C_dn, the upper bound
//! and the attained lower value from C_up: all four stay valid for C, with no widening.
//!
//! # The knot scaling, and what it cannot do
//!
//! The knot exponent s is the one that maps the domain to a length in [1/2, 1), clamped to
//! the range where 2^-s u is exact for every knot: s <= t(u) + 1074 for the lowest set bit
//! 2^t(u) of each knot (scaling down), and 2^-s |u| < 2^1020 (scaling up; also keeps every
//! knot difference below 2^1021, so no kernel overflows). An ordinary knot such as 0.1
//! (t = -56) still allows s up to 1018. A curve whose knots cannot be brought into the
//! moderate range exactly (a knot with a 2^-1074 bit next to knots near ±f64::MAX: no exact
//! affine map of such a vector has a spread below f64::MAX) goes span by span through
//! [`super::segments`] instead: each span's piece becomes Bézier curves over [0, 1].
//!
//! # Facts applied to every result
//!
//! The control-point box is an exact outer box (convex hull property, thesis prop. 2.1), so
//! every outer bound is clamped to it: a bound of a finite curve is finite, and a NaN or an
//! infinity from an overflow can never survive as a bound. At a clamped end the curve takes
//! the end control point exactly ([`NurbsCurve::clamped_ends`]), an attained value for the
//! inner bounds (this makes an end value such as f64::MAX an exact, attained bound).

use super::{BoxEncloser, CoordBox, Enclosure, Guarantee, Termination};
use crate::spline::curve::NurbsCurve;

/// Values whose binary exponent lies within ±`WINDOW` of 0 are left alone: with coordinates
/// below 2^80 ~ 1e24, weights below 2^30 and domains of length 2^±30, every intermediate of
/// the strategies (products of up to four such factors with p^2 and Δu^-2 for spans down to
/// 1e-12 of the domain) stays far inside the f64 range.
pub(crate) const COORD_WINDOW: i32 = 80;
const WEIGHT_WINDOW: i32 = 30;
const KNOT_WINDOW: i32 = 30;

/// The binary exponent e with |x| in [2^(e-1), 2^e), for finite non-zero x (0 for 0).
#[inline]
pub(crate) fn exponent(x: f64) -> i32 {
    let x = x.abs();
    if x == 0.0 || !x.is_finite() {
        return 0;
    }
    let (m, bias) = if x < f64::MIN_POSITIVE {
        (x * 2f64.powi(64), 64) // exact: subnormal times 2^64 is normal
    } else {
        (x, 0)
    };
    ((m.to_bits() >> 52) & 0x7ff) as i32 - 1022 - bias
}

/// The exponent t of the lowest set bit of a finite non-zero x (x = m 2^t with m odd):
/// x 2^-s is exact for s <= t + 1074 (no bit falls below the smallest subnormal 2^-1074).
pub(crate) fn low_exp(x: f64) -> i32 {
    let b = x.abs().to_bits();
    let e = (b >> 52) as i32;
    let m = b & ((1u64 << 52) - 1);
    if e == 0 {
        m.trailing_zeros() as i32 - 1074
    } else {
        (m | (1u64 << 52)).trailing_zeros() as i32 + e - 1075
    }
}

/// Knots are kept below 2^KNOT_MAX_EXP in magnitude, so that every difference of two knots
/// (and of a knot and a parameter) is below 2^(KNOT_MAX_EXP + 1) and cannot overflow.
const KNOT_MAX_EXP: i32 = 1019;

/// x * 2^k (round to nearest; two steps so that 2^k itself never over/underflows).
fn ldexp(mut x: f64, mut k: i32) -> f64 {
    if !x.is_finite() || x == 0.0 {
        return x;
    }
    // upward: products by 2^1023 are exact until one overflows (and stays ±inf)
    while k > 1023 {
        x *= pow2(1023);
        k -= 1023;
    }
    if k >= -1022 {
        return x * pow2(k); // 2^k is a normal f64: one correctly rounded product
    }
    // downward below 2^-1022: exact steps that keep x normal (by 2^-1022 while |x| >= 1, then
    // a step a with |x 2^a| >= 2^(e - 1 + a) >= 2^-1022 where |x| < 2^e), then the one
    // rounding; a rest below 2^-1022 makes |x 2^k| < 2^(e + k) <= 2^-2043, which rounds to ±0
    while k < -1022 && x.abs() >= 1.0 {
        x *= pow2(-1022);
        k += 1022;
    }
    if k >= -1022 {
        return x * pow2(k);
    }
    let e = exponent(x); // <= 0 here: -1021 - e >= -1021
    let a = k.max(-1021 - e);
    let rest = k - a;
    if rest < -1022 {
        return x * 0.0;
    }
    x * pow2(a) * pow2(rest)
}

/// 2^k for -1022 <= k <= 1023 (a normal f64), built from its bits (`powi` is a library call
/// with a loop, which showed in the profiles of rescaled curves).
#[inline]
pub(crate) const fn pow2(k: i32) -> f64 {
    debug_assert!(-1022 <= k && k <= 1023);
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// x * 2^k exactly, or `None` if the product is not exactly representable.
pub(crate) fn ldexp_exact(x: f64, k: i32) -> Option<f64> {
    let y = ldexp(x, k);
    // A finite result that is normal (or an exact zero from a zero) is exact; otherwise
    // check by scaling back (a subnormal y may still be exact).
    (y.is_finite() && (y == 0.0) == (x == 0.0) && ldexp(y, -k) == x).then_some(y)
}

/// x * 2^k rounded toward -inf (`up` false) or +inf (`up` true), for scaling control points
/// (an overflow gives ±inf): exact unless the product is subnormal, where the nearest value is moved one step if
/// it lies on the wrong side (the check scales back exactly: y 2^-k is normal or exact).
fn ldexp_directed(x: f64, k: i32, up: bool) -> f64 {
    let y = ldexp(x, k);
    if ldexp_exact(x, k).is_some() {
        return y;
    }
    let back = ldexp(y, -k);
    if up && back < x {
        y.next_up()
    } else if !up && back > x {
        y.next_down()
    } else {
        y
    }
}

/// x * 2^k rounded upward (`up`) or downward: a bound that is still a bound after scaling.
///
/// The round-to-nearest product is exact unless it is subnormal (or zero from a non-zero x) or
/// it overflowed. An overflow goes to ±inf or ±MAX by the direction. A subnormal (or zero)
/// product y is compared with x exactly, by scaling it back (only a product scaled down,
/// k < 0, can round, and y 2^-k then scales y up: exact, as y has at most 52 significant
/// bits and |y 2^-k| is within a step of |x|); y is kept if it already lies on the required side, else moved one step:
/// the result is RU(x 2^k) or RD(x 2^k), the tightest double on that side (a step further
/// than the nearest when the nearest is on the right side anyway would lose one subnormal
/// step of every bound restored into that range).
pub fn scale_outward(x: f64, k: i32, up: bool) -> f64 {
    if !x.is_finite() || x == 0.0 || k == 0 {
        return x;
    }
    let y = ldexp(x, k);
    if y.is_infinite() {
        // |x 2^k| > MAX: rounding toward the bound's side gives ±inf or ±MAX
        return match (y > 0.0, up) {
            (true, true) | (false, false) => y,
            (true, false) => f64::MAX,
            (false, true) => -f64::MAX,
        };
    }
    if y.abs() >= f64::MIN_POSITIVE {
        return y; // normal, so exact
    }
    // (`ldexp_directed`: y if exact or on the required side, else one step towards it)
    ldexp_directed(x, k, up)
}

/// The exponents of an exact power-of-two rescaling of a curve (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Rescaling {
    /// coordinate j is multiplied by 2^-coord_exp[j]
    pub coord_exp: Vec<i32>,
    /// whether some control point coordinate j rounded (enclosed rounded down and up)
    pub coord_rounded: Vec<bool>,
    /// weights are multiplied by 2^-weight_exp
    pub weight_exp: i32,
    /// knots are multiplied by 2^-knot_exp
    pub knot_exp: i32,
    /// whether the scaled knots are moderate (domain length within 2^±30 of 1, no knot
    /// difference can overflow); if not, the curve is enclosed span by span
    /// ([`super::segments`])
    pub knots_moderate: bool,
}

/// The knot exponent (see the module docs) and whether the scaled knots are moderate.
pub(crate) fn knot_scaling(c: &NurbsCurve) -> (i32, bool) {
    let kn = c.knots();
    let (a, b) = c.domain();
    // b/2 - a/2 cannot overflow; halving may round only for subnormals (irrelevant here:
    // the exponent is only a choice, exactness is checked on the knots themselves)
    let want = exponent(0.5 * b - 0.5 * a) + 1;
    // (knots are non-decreasing, so the largest |u| is at an end: one look instead of a
    // pass; `exponent` is monotone in |u| > 0, and the larger end is non-zero for a non-empty
    // domain: the exponent of max(|u_0|, |u_m|), not the larger of the two exponents, since
    // `exponent(0)` is 0, which for a domain [0, 2^-1068] would claim knots near 1)
    let max_e = exponent(kn[0].abs().max(kn[kn.len() - 1].abs()));
    if want.abs() <= KNOT_WINDOW && max_e <= KNOT_MAX_EXP {
        return (0, true);
    }
    // exact range: s <= low_exp(u) + 1074 for every non-zero knot, s >= max_e - KNOT_MAX_EXP
    let s_hi = kn
        .iter()
        .filter(|&&u| u != 0.0)
        .map(|&u| low_exp(u) + 1074)
        .min()
        .unwrap_or(i32::MAX);
    let s_lo = max_e - KNOT_MAX_EXP;
    let s = want.clamp(s_lo.min(s_hi), s_hi);
    let exact = kn.iter().all(|&u| ldexp_exact(u, -s).is_some());
    if !exact {
        return (0, false);
    }
    let moderate = (want - s).abs() <= KNOT_WINDOW && max_e - s <= KNOT_MAX_EXP;
    (s, moderate)
}

impl Rescaling {
    /// The rescaling a curve needs, or `None` if its magnitudes are moderate.
    pub fn of(c: &NurbsCurve) -> Option<Rescaling> {
        let d = c.dim();
        let pts = c.points_flat();
        let coord_e = |j: usize| {
            exponent(
                pts.iter()
                    .skip(j)
                    .step_by(d)
                    .fold(0.0f64, |m, x| m.max(x.abs())),
            )
        };
        // (checked first without allocating, in one pass over the points: moderate curves are
        // the common case; the per-coordinate exponents are recomputed below only when needed)
        let coords_moderate = if d <= 4 {
            let mut m = [0.0f64; 4];
            for p in pts.chunks_exact(d) {
                for (mj, x) in m.iter_mut().zip(p) {
                    *mj = mj.max(x.abs());
                }
            }
            m[..d].iter().all(|&x| exponent(x).abs() <= COORD_WINDOW)
        } else {
            (0..d).all(|j| coord_e(j).abs() <= COORD_WINDOW)
        };
        let mut weight_exp = 0;
        if let Some(w) = c.weights() {
            let e = exponent(w.iter().fold(0.0f64, |m, &x| m.max(x)));
            if e.abs() > WEIGHT_WINDOW && w.iter().all(|&x| ldexp_exact(x, -e).is_some()) {
                weight_exp = e;
            }
        }
        let (knot_exp, knots_moderate) = knot_scaling(c);
        if coords_moderate && weight_exp == 0 && knot_exp == 0 && knots_moderate {
            return None;
        }
        let mut coord_exp = vec![0; d];
        let mut coord_rounded = vec![false; d];
        for j in 0..d {
            let e = coord_e(j);
            if e.abs() > COORD_WINDOW {
                coord_exp[j] = e;
                coord_rounded[j] = pts
                    .iter()
                    .skip(j)
                    .step_by(d)
                    .any(|&x| ldexp_exact(x, -e).is_none());
            }
        }
        Some(Rescaling {
            coord_exp,
            coord_rounded,
            weight_exp,
            knot_exp,
            knots_moderate,
        })
    }

    /// The rescaled curve (same image up to the coordinate scaling, see the module docs);
    /// coordinates that round are rounded down (`up` false) or up, or to nearest (`None`).
    pub fn apply_directed(&self, c: &NurbsCurve, up: Option<bool>) -> NurbsCurve {
        let d = c.dim();
        let pts: Vec<f64> = c
            .points_flat()
            .iter()
            .enumerate()
            .map(|(k, &x)| {
                let e = -self.coord_exp[k % d];
                match up {
                    Some(up) if self.coord_rounded[k % d] => ldexp_directed(x, e, up),
                    _ => ldexp(x, e),
                }
            })
            .collect();
        // Scaling by powers of two keeps every validity condition: knots stay non-decreasing
        // with the same multiplicities (exact), weights stay > 0, coordinates finite (the
        // largest maps to [0.5, 1)). Should it ever fail, the original curve is used.
        self.with_points(c, pts).unwrap_or_else(|| c.clone())
    }

    /// `c` with the control coordinates `pts` (row-major) and its knots and weights scaled by
    /// 2^-knot_exp and 2^-weight_exp (exact), or `None` if that is not a valid curve.
    fn with_points(&self, c: &NurbsCurve, pts: Vec<f64>) -> Option<NurbsCurve> {
        let knots: Vec<f64> = c
            .knots()
            .iter()
            .map(|&u| ldexp(u, -self.knot_exp))
            .collect();
        let weights = c
            .weights()
            .map(|w| w.iter().map(|&x| ldexp(x, -self.weight_exp)).collect());
        NurbsCurve::from_flat(c.degree(), c.dim(), knots, pts, weights).ok()
    }

    /// The curve the certificate of coordinate j evaluates ([`super::certify`]): knots and
    /// weights scaled as by [`Rescaling::apply`] (exact), coordinate j multiplied by 2^-`s`,
    /// rounded down (`up` false) or up where the product is not exact (so the curve's
    /// coordinate j is below, or above, 2^-s C_j at every u: the argument of "Rounded
    /// coordinates"), the other coordinates unchanged; and whether some value of coordinate
    /// j rounded. `None` if a scaled value is not finite (or the curve not valid).
    pub(crate) fn apply_coord(
        &self,
        c: &NurbsCurve,
        j: usize,
        s: i32,
        up: bool,
    ) -> Option<(NurbsCurve, bool)> {
        let d = c.dim();
        let mut rounded = false;
        let pts: Vec<f64> = c
            .points_flat()
            .iter()
            .enumerate()
            .map(|(k, &x)| {
                if k % d != j {
                    return x;
                }
                rounded |= ldexp_exact(x, -s).is_none();
                ldexp_directed(x, -s, up)
            })
            .collect();
        Some((self.with_points(c, pts)?, rounded))
    }

    /// The rescaled curve, coordinates rounded to nearest (see [`Rescaling::apply_directed`]).
    pub fn apply(&self, c: &NurbsCurve) -> NurbsCurve {
        self.apply_directed(c, None)
    }

    /// Enclose `c` with `s` through this rescaling: scaled curve(s) enclosed (span by span if
    /// the knots are not moderate), rounded coordinates from the curves rounded down and up,
    /// the result mapped back.
    pub fn enclose_with<S: BoxEncloser + ?Sized>(&self, s: &S, c: &NurbsCurve) -> Enclosure {
        let run = |cc: &NurbsCurve| {
            if self.knots_moderate {
                s.enclose_prepared(cc)
            } else {
                super::segments::enclose_by_segments(s, cc)
            }
        };
        if !self.coord_rounded.contains(&true) {
            return self.restore(run(&self.apply(c)));
        }
        let mut dn = run(&self.apply_directed(c, Some(false)));
        let up = run(&self.apply_directed(c, Some(true)));
        for (j, (cd, cu)) in dn.coords.iter_mut().zip(up.coords).enumerate() {
            if self.coord_rounded[j] {
                // C_dn <= C <= C_up: lo and the attained max from C_dn, hi and the attained
                // min from C_up (see the module docs)
                cd.hi = cu.hi;
                cd.inner_lo = cu.inner_lo;
                cd.witness_lo = cu.witness_lo;
                cd.argmax = cu.argmax;
                cd.stats.add(&cu.stats);
                if cd.termination == Termination::Converged {
                    cd.termination = cu.termination;
                }
            }
        }
        self.restore(dn)
    }

    /// Map an enclosure of the rescaled curve back to the original curve.
    pub fn restore(&self, mut e: Enclosure) -> Enclosure {
        for (j, cb) in e.coords.iter_mut().enumerate() {
            let k = self.coord_exp[j];
            cb.lo = scale_outward(cb.lo, k, false);
            cb.hi = scale_outward(cb.hi, k, true);
            // inner bounds: the curve reaches <= inner_lo and >= inner_hi, so round inner_lo up
            // and inner_hi down; keep lo <= inner_lo and inner_hi <= hi
            cb.inner_lo = scale_outward(cb.inner_lo, k, true).max(cb.lo);
            cb.inner_hi = scale_outward(cb.inner_hi, k, false).min(cb.hi);
            // strict witnesses: C_j > w scaled by 2^k is C_j 2^k > w 2^k >= RD(w 2^k), and
            // likewise below (exact unless subnormal; an overflow to ±inf only loses the witness)
            cb.witness_lo = scale_outward(cb.witness_lo, k, true);
            cb.witness_hi = scale_outward(cb.witness_hi, k, false);
            for x in cb.argmin.iter_mut().chain(cb.argmax.iter_mut()) {
                x.u_lo = scale_outward(x.u_lo, self.knot_exp, false);
                x.u_hi = scale_outward(x.u_hi, self.knot_exp, true);
            }
        }
        e
    }
}

/// Above this degree every strategy returns the control-point box ([`degree_fallback`]): one
/// interval evaluation costs ~(p + 1)^2 corner cuts (a second at p = 3000), so a search would
/// take minutes per curve, and a small input (a few KB of JSON per thousand degrees) could
/// stall a batch. The formats allow any degree.
pub const MAX_SEARCH_DEGREE: usize = 1000;

/// The control-point box of `c` (convex hull property, thesis prop. 2.1; exact) as the result
/// of strategy `s`, in O(n d) time: the fallback above [`MAX_SEARCH_DEGREE`], reported as
/// [`Termination::WorkLimit`].
///
/// Inner bounds without evaluating the curve: every u has lo <= C_j(u) <= hi, so the curve
/// reaches a value <= hi and one >= lo; the attained end values are added by
/// [`drive`].
pub fn degree_fallback<S: BoxEncloser + ?Sized>(s: &S, c: &NurbsCurve) -> Enclosure {
    let coords = super::hull::control_point_box(c, |_, lo, hi| (hi, lo), Termination::WorkLimit, 0);
    Enclosure {
        strategy: s.name(),
        verified: s.guarantee() == Guarantee::Verified,
        coords,
    }
}

/// The driver's facts for one coordinate (see the module docs): the outer bounds clamped to the
/// exact control-point range `(plo, phi)`; for a verified result also the values at clamped
/// ends (`ends`, the end control points) as attained values, and the inner bounds made
/// consistent with the outer ones. Shared by [`drive_with`] and the lane (`super::lane`).
#[inline]
pub(crate) fn apply_facts(
    cb: &mut CoordBox,
    (plo, phi): (f64, f64),
    ends: [Option<f64>; 2],
    verified: bool,
) {
    // (f64::max/min return the non-NaN operand: a NaN bound becomes the hull's)
    cb.lo = cb.lo.max(plo);
    cb.hi = cb.hi.min(phi);
    if !verified {
        return;
    }
    for x in ends.into_iter().flatten() {
        cb.inner_lo = cb.inner_lo.min(x);
        cb.inner_hi = cb.inner_hi.max(x);
    }
    cb.inner_lo = cb.inner_lo.min(cb.hi).max(cb.lo);
    cb.inner_hi = cb.inner_hi.max(cb.lo).min(cb.hi);
}

/// Enclose `c` with `s`, rescaling it first if its magnitudes are extreme (see the module
/// docs); the result is an enclosure of `c` itself. Above [`MAX_SEARCH_DEGREE`] the result is
/// the control-point box ([`degree_fallback`]).
///
/// Then the facts of the module docs are applied: outer bounds clamped to the control-point
/// box, the end control points of clamped ends taken as attained values, and the inner
/// bounds made consistent with the outer ones: every u has lo <= C_j(u) <= hi, so the curve
/// reaches a value <= hi and a value >= lo, and `inner_lo = min(inner_lo, hi)`,
/// `inner_hi = max(inner_hi, lo)` stay valid (a constant coordinate may otherwise get an inner
/// bound one rounding beyond the exact outer one).
///
/// Last, every verified result gets its optimality certificates `optimal_lo` / `optimal_hi`
/// ([`super::certify`], the one place for every strategy); `drive_with(s, c, false)` skips
/// them (all `false`), which is how the cost of certification is measured.
pub fn drive<S: BoxEncloser + ?Sized>(s: &S, c: &NurbsCurve) -> Enclosure {
    drive_with(s, c, true)
}

/// [`drive`] with the certification switched on (`certify`, the default) or off (every
/// `optimal_lo` / `optimal_hi` stays `false`).
pub fn drive_with<S: BoxEncloser + ?Sized>(s: &S, c: &NurbsCurve, certify: bool) -> Enclosure {
    // One result variable, written in place by the lane or the general path (the lane's
    // former `Option<Enclosure>` cost two copies of the inline coordinates per call).
    let mut e = Enclosure {
        strategy: s.name(),
        verified: true,
        coords: Default::default(),
    };
    // The lane for a clamped polynomial segment or spline of degree <= 5, or a clamped
    // rational curve of degree 2 to 5, with moderate magnitudes (`lane`: the same facts and
    // certificates, computed directly).
    let laned = s.lane().is_some_and(|l| {
        super::lane::Simple::of(c).is_some_and(|simple| {
            super::lane::enclose_into(&mut e, l, s.name(), c, &simple, certify)
        })
    });
    if !laned {
        general(s, c, certify, &mut e);
    }
    e
}

/// Whether an optimality certificate of the bound `b` of a curve whose coordinate was scaled
/// by 2^-k carries over to the bound b 2^k of the curve itself: b and b 2^k strictly inside
/// the normal range (MIN_POSITIVE < |x| < MAX, so that their neighbours are normal and finite)
/// and b 2^k exact (it scales back to b). Then scaling by 2^k maps b and its two neighbours
/// onto b 2^k and its two neighbours (the neighbours of a normal double x of exponent e are
/// x ± 2^(e-52), x - 2^(e-53) below a power of two; those of x 2^k, exponent e + k, are the
/// same times 2^k), so prev(b) < M' <= b, b = RU(M'), gives prev(b 2^k) < M' 2^k <= b 2^k,
/// b 2^k = RU(M' 2^k), and likewise for RD. A subnormal b does not carry: the subnormals lie
/// 2^-1074 apart, and 2^k maps them 2^(k-1074) apart, coarser than the normal doubles there,
/// so RU(M') 2^k can lie doubles above RU(M' 2^k) (found by the reference audit: a maximum
/// ~9.2e-285 of a coordinate scaled by 2^-81, certified an ulp above the optimal double).
fn certificate_carries(b: f64, k: i32) -> bool {
    let inside = |x: f64| x.abs() > f64::MIN_POSITIVE && x.abs() < f64::MAX;
    let y = ldexp(b, k);
    inside(b) && inside(y) && ldexp(y, -k) == b
}

/// The tight lane on a curve whose coordinates alone lie beyond the lane's magnitude window
/// (`lane::Simple::of`), scaled into it exactly: `r` scales coordinate j by 2^-coord_exp[j]
/// with no value rounded, knots and weights unscaled, so the scaled curve is the curve with
/// coordinate j multiplied by 2^-coord_exp[j] exactly, and its enclosure, mapped back by
/// [`Rescaling::restore`] (outward where a value is not exact), encloses the curve. An
/// optimality certificate of the scaled curve, bound b' = RU(max C'_j) (RD(min)), carries
/// over where [`certificate_carries`]: b' and b = b' 2^k both normal with normal neighbours,
/// b exact. Otherwise (a bound at zero, subnormal on either side, overflowing when mapped
/// back) the scaled lane's answer is dropped and the general path runs. `false` (`e` then
/// unspecified): not taken. For the tight lane alone (`hull`'s general path is the
/// control-point box, cheaper than building the scaled curve).
fn scaled_lane<S: BoxEncloser + ?Sized>(
    s: &S,
    c: &NurbsCurve,
    r: &Rescaling,
    certify: bool,
    e: &mut Enclosure,
) -> bool {
    let Some(lane) = s.lane().filter(|&l| l == super::lane::Lane::Tight) else {
        return false;
    };
    // (and the lane's degree and dimension, before the scaled curve is built: a curve the
    // lane refuses for those would build it a second time on the general path)
    if r.knot_exp != 0
        || r.weight_exp != 0
        || !r.knots_moderate
        || r.coord_rounded.contains(&true)
        || c.degree() > super::lane::LANE_MAX_DEGREE
        || c.dim() > super::lane::MAX_DIM
    {
        return false;
    }
    let rc = r.apply(c);
    let Some(simple) = super::lane::Simple::of(&rc) else {
        return false;
    };
    if !super::lane::enclose_into(e, lane, s.name(), &rc, &simple, certify) {
        return false;
    }
    for (cb, &k) in e.coords.iter().zip(&r.coord_exp) {
        if (cb.optimal_lo && !certificate_carries(cb.lo, k))
            || (cb.optimal_hi && !certificate_carries(cb.hi, k))
        {
            return false;
        }
    }
    let scaled = std::mem::replace(
        e,
        Enclosure {
            strategy: s.name(),
            verified: true,
            coords: Default::default(),
        },
    );
    *e = r.restore(scaled);
    true
}

/// The general path of [`drive_with`] (everything but the lane), written to `e`.
fn general<S: BoxEncloser + ?Sized>(s: &S, c: &NurbsCurve, certify: bool, e: &mut Enclosure) {
    let rescaling = Rescaling::of(c);
    if let Some(r) = &rescaling {
        if scaled_lane(s, c, r, certify, e) {
            return;
        }
    }
    *e = if c.degree() > MAX_SEARCH_DEGREE {
        degree_fallback(s, c)
    } else {
        match &rescaling {
            None => s.enclose_prepared(c),
            Some(r) => r.enclose_with(s, c),
        }
    };
    let n = c.num_points() - 1;
    let cl = c.clamped_ends();
    let verified = s.guarantee() == Guarantee::Verified;
    for (j, cb) in e.coords.iter_mut().enumerate() {
        let ends = [(0, 0), (1, n)].map(|(end, i)| cl[end].then(|| c.control_point(i)[j]));
        apply_facts(cb, c.coord_range(j, 0..=n), ends, verified);
    }
    if certify {
        super::certify::certify_with(c, e, rescaling.as_ref());
    } else {
        for cb in &mut e.coords {
            cb.optimal_lo = false;
            cb.optimal_hi = false;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::enclose::ControlHull;

    /// Where a certificate carries over from the scaled curve ([`certificate_carries`]), the
    /// scaling maps the bound's neighbours onto the scaled-back bound's neighbours (the claim
    /// its proof rests on), checked on random doubles and exponents and at the edges; a
    /// subnormal bound never carries, and for one the neighbours do not map (the case the
    /// reference audit found: its certificate was false).
    #[test]
    fn certificates_carry_only_where_the_neighbours_map() {
        use rand::Rng;
        let mut r = crate::testkit::gen::rng(9);
        let mut carried = 0;
        for _ in 0..50_000 {
            let b = f64::from_bits(r.random_range(0..0x7ff0_0000_0000_0000u64))
                * if r.random_bool(0.5) { -1.0 } else { 1.0 };
            let k = r.random_range(-1100..=1100);
            if certificate_carries(b, k) {
                carried += 1;
                let y = ldexp(b, k);
                assert_eq!(ldexp(b.next_up(), k), y.next_up(), "{b:e} 2^{k}");
                assert_eq!(ldexp(b.next_down(), k), y.next_down(), "{b:e} 2^{k}");
            }
        }
        assert!(carried > 10_000, "{carried}");
        // the edges: the smallest normal, subnormals, zero, the largest double, overflow
        let tiny = f64::MIN_POSITIVE;
        for (b, k) in [
            (tiny, 10),
            (tiny / 4.0, 81),
            (-tiny / 3.0, 81),
            (0.0, 5),
            (f64::MAX, -5),
        ] {
            assert!(!certificate_carries(b, k), "{b:e} 2^{k}");
        }
        assert!(!certificate_carries(1.0, 1024));
        assert!(certificate_carries(tiny.next_up(), 10));
        assert!(certificate_carries(1.5, -1021));
        // a subnormal bound scaled up: its upper neighbour maps two doubles above the scaled
        // bound (the certificate of the scaled curve says nothing about the double between)
        let b = f64::from_bits(0x000a_0000_0000_0000); // 0.625 2^-1022, subnormal
        let y = ldexp(b, 81);
        assert_ne!(ldexp(b.next_up(), 81), y.next_up());
        assert_eq!(ldexp(b.next_up(), 81), y.next_up().next_up());
    }

    #[test]
    fn exponent_and_outward_scaling() {
        assert_eq!(exponent(1.0), 1);
        assert_eq!(exponent(0.75), 0);
        assert_eq!(exponent(f64::MAX), 1024);
        assert_eq!(exponent(f64::from_bits(1)), -1073);
        assert_eq!(ldexp(1.0, 2000), f64::INFINITY);
        assert_eq!(ldexp(1.0, -2000), 0.0);
        // against an exact reference (the result as a rational compared with x 2^k): every
        // power of two and products near the subnormal range, in both directions
        let tiny = f64::from_bits(1);
        assert_eq!(ldexp(tiny, 2047), pow2(973));
        assert_eq!(ldexp(tiny, 2097), pow2(1023));
        assert_eq!(ldexp(tiny, 2098), f64::INFINITY);
        assert_eq!(ldexp(f64::MAX, -2098), tiny);
        assert_eq!(ldexp(f64::MAX, -2099), 0.0);
        assert_eq!(ldexp(-f64::MAX, -3000), -0.0);
        assert!(ldexp(-f64::MAX, -3000).is_sign_negative());
        for k in -1022..=1023 {
            assert_eq!(pow2(k), 2f64.powi(k));
        }
        // random doubles and exponents against the exact product x 2^k (rationals): y is
        // one of its two neighbouring doubles, the nearer one (or the exact product)
        use crate::num::exact::Exact;
        use num_bigint::BigInt;
        use num_rational::BigRational;
        use num_traits::Signed;
        use rand::Rng;
        let pow2_exact = |k: i32| {
            let p = BigInt::from(1) << k.unsigned_abs();
            Exact::from_ratio(if k >= 0 {
                BigRational::from_integer(p)
            } else {
                BigRational::new(BigInt::from(1), p)
            })
        };
        let mut r = crate::testkit::gen::rng(5);
        for _ in 0..20_000 {
            let x = f64::from_bits(r.random_range(1..0x7fef_ffff_ffff_ffffu64));
            let x = if r.random_bool(0.5) { -x } else { x };
            let k = r.random_range(-2200..=2200);
            let y = ldexp(x, k);
            let ex = Exact::of(x) * pow2_exact(k);
            let (lo, hi) = (ex.round_down(), ex.round_up());
            // the directed scaling of bounds is exactly RD / RU (no step beyond them)
            assert_eq!(scale_outward(x, k, false), lo, "RD({x:e} 2^{k})");
            assert_eq!(scale_outward(x, k, true), hi, "RU({x:e} 2^{k})");
            assert!(
                y == lo || y == hi,
                "ldexp({x:e}, {k}) = {y:e}, not in [{lo:e}, {hi:e}]"
            );
            if lo.is_finite() && hi.is_finite() && lo != hi {
                let dist = |v: f64| (ex.clone() - Exact::of(v)).value().unwrap().abs();
                let other = if y == lo { hi } else { lo };
                assert!(
                    dist(y) <= dist(other),
                    "ldexp({x:e}, {k}) = {y:e} not the nearest"
                );
            }
        }
        // exact cases
        assert_eq!(scale_outward(3.0, -5, true), 3.0 / 32.0);
        // subnormal results: directed
        let x = 3.0 * f64::from_bits(1); // 3 * 2^-1074
        let lo = scale_outward(x, -1, false);
        let hi = scale_outward(x, -1, true);
        assert!(lo <= 1.5 * f64::from_bits(1) && 1.5 * f64::from_bits(1) <= hi);
        assert!(lo < hi);
        // overflow: upper bound -> inf, lower bound -> MAX
        assert_eq!(scale_outward(1.5, 1024, true), f64::INFINITY);
        assert_eq!(scale_outward(1.5, 1024, false), f64::MAX);
        assert_eq!(scale_outward(-1.5, 1024, false), f64::NEG_INFINITY);
        assert_eq!(scale_outward(-1.5, 1024, true), -f64::MAX);
        assert_eq!(ldexp_exact(f64::from_bits(3), -1), None);
        assert_eq!(ldexp_exact(f64::from_bits(2), -1), Some(f64::from_bits(1)));
    }

    #[test]
    fn a_subnormal_domain_from_zero_is_scaled_to_a_moderate_one() {
        // knots [0, 2^-1068]: a zero knot must not count as a knot of magnitude ~1 (which
        // limited the scaling to 2^1019, a domain of 2^-49, enclosed span by span)
        let d = f64::from_bits(64);
        let c = NurbsCurve::new(
            2,
            vec![0.0, 0.0, 0.0, d, d, d],
            vec![vec![1.0], vec![2.0], vec![0.5]],
            None,
        )
        .unwrap();
        let (s, moderate) = knot_scaling(&c);
        assert!(moderate);
        let b = ldexp_exact(d, -s).unwrap();
        assert!((0.5..1.0).contains(&b), "domain length {b:e}");
        let r = Rescaling::of(&c).unwrap();
        assert!(r.knots_moderate && r.knot_exp == s);
    }

    #[test]
    fn moderate_curves_are_untouched_and_extreme_ones_map_back() {
        let c = NurbsCurve::new(
            2,
            vec![0., 0., 0., 1., 1., 1.],
            vec![vec![1e-3, 4.0], vec![2.0, -1e6], vec![0.5, 3.0]],
            Some(vec![1.0, 3.0, 0.5]),
        )
        .unwrap();
        assert!(Rescaling::of(&c).is_none());
        let big = NurbsCurve::new(
            2,
            vec![0., 0., 0., 1e-200, 1e-200, 1e-200],
            vec![
                vec![1e300, -1e-300],
                vec![-1e300, 1e-310],
                vec![1e-300, 0.0],
            ],
            Some(vec![1e300, 1e-10, 3.0]),
        )
        .unwrap();
        let r = Rescaling::of(&big).unwrap();
        assert!(r.coord_exp[0] > 900 && r.coord_exp[1] < -900);
        assert!(r.coord_rounded[0] && !r.coord_rounded[1]);
        assert!(r.weight_exp == 0, "1e-10 * 2^-997 is not exact");
        assert!(r.knot_exp < -600);
        let s = r.apply(&big);
        assert_eq!(s.domain().1, ldexp(1e-200, -r.knot_exp));
        // (without the certification, which may lower a bound after a proof)
        let e = drive_with(&ControlHull, &big, false);
        let h = ControlHull.enclose_prepared(&big);
        // the hull is exact: the rescaled one may only be wider by the subnormal steps
        for j in 0..2 {
            assert!(e.coords[j].lo <= h.coords[j].lo && e.coords[j].hi >= h.coords[j].hi);
            assert!(e.coords[j].lo >= h.coords[j].lo * (1.0 + 1e-15) - 1e-300);
        }
        assert_eq!(e.coords[1].lo, -1e-300);
        assert_eq!(e.coords[1].hi, 1e-310);
    }
}
