//! Exact power-of-two rescaling of extreme curves before enclosing them (issue 6).
//!
//! A valid curve may have coordinates near 1e±300, weights near 1e±300 or a parameter domain of
//! length 1e-300. The strategies then work on intermediates that overflow or underflow (the
//! homogeneous points w_i P_i, derivatives ~ p^2 w^2 P / Δu^2, double-double low parts): the
//! results stay sound (intervals overflow to ±inf, never to a wrong finite value) but can be
//! infinite or loose. [`Rescaled`] maps such a curve to an equivalent well-scaled one, encloses
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

use super::{BoxEncloser, Enclosure, Guarantee, Termination};
use crate::curve::NurbsCurve;

/// Values whose binary exponent lies within ±`WINDOW` of 0 are left alone: with coordinates
/// below 2^80 ~ 1e24, weights below 2^30 and domains of length 2^±30, every intermediate of
/// the strategies (products of up to four such factors with p^2 and Δu^-2 for spans down to
/// 1e-12 of the domain) stays far inside the f64 range.
const COORD_WINDOW: i32 = 80;
const WEIGHT_WINDOW: i32 = 30;
const KNOT_WINDOW: i32 = 30;

/// The binary exponent e with |x| in [2^(e-1), 2^e), for finite non-zero x (0 for 0).
fn exponent(x: f64) -> i32 {
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

/// x * 2^k (round to nearest; two steps so that 2^k itself never over/underflows).
fn ldexp(x: f64, k: i32) -> f64 {
    if (-1022..=1023).contains(&k) {
        return x * 2f64.powi(k); // 2^k is a normal f64: one correctly rounded product
    }
    let h = k / 2;
    x * 2f64.powi(h) * 2f64.powi(k - h)
}

/// x * 2^k exactly, or `None` if the product is not exactly representable.
fn ldexp_exact(x: f64, k: i32) -> Option<f64> {
    let y = ldexp(x, k);
    // A finite result that is normal (or an exact zero from a zero) is exact; otherwise
    // check by scaling back (a subnormal y may still be exact).
    (y.is_finite() && (y == 0.0) == (x == 0.0) && ldexp(y, -k) == x).then_some(y)
}

/// x * 2^k rounded upward (`up`) or downward: a bound that is still a bound after scaling.
///
/// The round-to-nearest product is exact unless it is subnormal (or zero from a non-zero x) or
/// it overflowed; in those cases it is moved one step in the required direction, which covers
/// the rounding error (at most half a subnormal step, or the overflow to ±inf).
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
    if y.abs() >= f64::MIN_POSITIVE || ldexp_exact(x, k).is_some() {
        return y; // normal (so exact), or checked exact
    }
    if up {
        y.next_up()
    } else {
        y.next_down()
    }
}

/// The exponents of an exact power-of-two rescaling of a curve (see the module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Rescaling {
    /// coordinate j is multiplied by 2^-coord_exp[j]
    pub coord_exp: Vec<i32>,
    /// whether some control point coordinate j rounded (widen the box by one subnormal step)
    pub coord_rounded: Vec<bool>,
    /// weights are multiplied by 2^-weight_exp
    pub weight_exp: i32,
    /// knots are multiplied by 2^-knot_exp
    pub knot_exp: i32,
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
        // (checked first without allocating: moderate curves are the common case)
        let coords_moderate = (0..d).all(|j| coord_e(j).abs() <= COORD_WINDOW);
        let mut weight_exp = 0;
        if let Some(w) = c.weights() {
            let e = exponent(w.iter().fold(0.0f64, |m, &x| m.max(x)));
            if e.abs() > WEIGHT_WINDOW && w.iter().all(|&x| ldexp_exact(x, -e).is_some()) {
                weight_exp = e;
            }
        }
        let mut knot_exp = 0;
        let (a, b) = c.domain();
        // b/2 - a/2 cannot overflow; halving may round only for subnormals (irrelevant here:
        // the exponent is only a choice, exactness is checked on the knots themselves)
        let e = exponent(0.5 * b - 0.5 * a) + 1;
        if e.abs() > KNOT_WINDOW && c.knots().iter().all(|&x| ldexp_exact(x, -e).is_some()) {
            knot_exp = e;
        }
        if coords_moderate && weight_exp == 0 && knot_exp == 0 {
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
        let r = Rescaling {
            coord_exp,
            coord_rounded,
            weight_exp,
            knot_exp,
        };
        (r.coord_exp.iter().any(|&e| e != 0) || r.weight_exp != 0 || r.knot_exp != 0).then_some(r)
    }

    /// The rescaled curve (same image up to the coordinate scaling, see the module docs).
    pub fn apply(&self, c: &NurbsCurve) -> NurbsCurve {
        let d = c.dim();
        let pts: Vec<f64> = c
            .points_flat()
            .iter()
            .enumerate()
            .map(|(k, &x)| ldexp(x, -self.coord_exp[k % d]))
            .collect();
        let knots: Vec<f64> = c
            .knots()
            .iter()
            .map(|&u| ldexp(u, -self.knot_exp))
            .collect();
        let weights = c
            .weights()
            .map(|w| w.iter().map(|&x| ldexp(x, -self.weight_exp)).collect());
        // Scaling by powers of two keeps every validity condition: knots stay non-decreasing
        // with the same multiplicities (exact), weights stay > 0, coordinates finite (the
        // largest maps to [0.5, 1)). Should it ever fail, the original curve is used.
        NurbsCurve::from_flat(c.degree(), d, knots, pts, weights).unwrap_or_else(|_| c.clone())
    }

    /// Map an enclosure of the rescaled curve back to the original curve.
    pub fn restore(&self, mut e: Enclosure) -> Enclosure {
        for (j, cb) in e.coords.iter_mut().enumerate() {
            let k = self.coord_exp[j];
            if self.coord_rounded[j] {
                // one subnormal step covers the <= 2^-1075 rounding of the scaled points
                cb.lo = cb.lo.next_down();
                cb.hi = cb.hi.next_up();
                cb.inner_lo = cb.inner_lo.next_up();
                cb.inner_hi = cb.inner_hi.next_down();
            }
            cb.lo = scale_outward(cb.lo, k, false);
            cb.hi = scale_outward(cb.hi, k, true);
            // inner bounds: the curve reaches <= inner_lo and >= inner_hi, so round inner_lo up
            // and inner_hi down; keep lo <= inner_lo and inner_hi <= hi
            cb.inner_lo = scale_outward(cb.inner_lo, k, true).max(cb.lo);
            cb.inner_hi = scale_outward(cb.inner_hi, k, false).min(cb.hi);
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
/// stall a batch. The formats allow any degree; issue 6 asks for degrees up to 40.
pub const MAX_SEARCH_DEGREE: usize = 1000;

/// The control-point box of `c` (convex hull property, thesis prop. 2.1; exact) as the result
/// of strategy `s`, in O(n d) time: the fallback above [`MAX_SEARCH_DEGREE`], reported as
/// [`Termination::WorkLimit`].
///
/// Inner bounds without evaluating the curve: every u has lo <= C_j(u) <= hi, so the curve
/// reaches a value <= hi and one >= lo; at a clamped end (p + 1 equal knots) the curve
/// interpolates the end control point exactly (NURBS Book eq. 2.3 / property P4.1), whose
/// coordinates are then attained values.
pub fn degree_fallback(s: &dyn BoxEncloser, c: &NurbsCurve) -> Enclosure {
    let (p, n) = (c.degree(), c.num_points() - 1);
    let kn = c.knots();
    let (a, b) = c.domain();
    let mut ends = Vec::new();
    if kn[..=p].iter().all(|&u| u == a) {
        ends.push(0);
    }
    if kn[n + 1..].iter().all(|&u| u == b) {
        ends.push(n);
    }
    let coords = super::hull::control_point_box(
        c,
        |j, lo, hi| {
            ends.iter()
                .map(|&i| c.control_point(i)[j])
                .fold((hi, lo), |(l, h), x| (l.min(x), h.max(x)))
        },
        Termination::WorkLimit,
        0,
    );
    Enclosure {
        strategy: s.name(),
        verified: s.guarantee() == Guarantee::Verified,
        coords,
    }
}

/// Enclose `c` with `s`, rescaling it first if its magnitudes are extreme (see the module
/// docs); the result is an enclosure of `c` itself. Above [`MAX_SEARCH_DEGREE`] the result is
/// the control-point box ([`degree_fallback`]).
///
/// For a verified strategy the inner bounds are also made consistent with the outer ones:
/// every u has lo <= C_j(u) <= hi, so the curve reaches a value <= hi and a value >= lo, and
/// `inner_lo = min(inner_lo, hi)`, `inner_hi = max(inner_hi, lo)` stay valid (a constant
/// coordinate may otherwise get an inner bound one rounding beyond the exact outer one).
pub fn enclose_rescaled(s: &dyn BoxEncloser, c: &NurbsCurve) -> Enclosure {
    if c.degree() > MAX_SEARCH_DEGREE {
        return degree_fallback(s, c);
    }
    let mut e = match Rescaling::of(c) {
        None => s.enclose(c),
        Some(r) => r.restore(s.enclose(&r.apply(c))),
    };
    if s.guarantee() == Guarantee::Verified {
        for cb in &mut e.coords {
            cb.inner_lo = cb.inner_lo.min(cb.hi);
            cb.inner_hi = cb.inner_hi.max(cb.lo);
        }
    }
    e
}

/// A strategy that rescales extreme curves first ([`enclose_rescaled`]); same name and
/// guarantee as the wrapped strategy. [`super::strategy_by_name`] wraps every strategy in it.
#[derive(Debug, Clone, Copy, Default)]
pub struct Rescaled<S>(pub S);

impl<S: BoxEncloser> BoxEncloser for Rescaled<S> {
    fn name(&self) -> &'static str {
        self.0.name()
    }
    fn guarantee(&self) -> Guarantee {
        self.0.guarantee()
    }
    fn enclose(&self, c: &NurbsCurve) -> Enclosure {
        enclose_rescaled(&self.0, c)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::enclose::ControlHull;

    #[test]
    fn exponent_and_outward_scaling() {
        assert_eq!(exponent(1.0), 1);
        assert_eq!(exponent(0.75), 0);
        assert_eq!(exponent(f64::MAX), 1024);
        assert_eq!(exponent(f64::from_bits(1)), -1073);
        assert_eq!(ldexp(1.0, 2000), f64::INFINITY);
        assert_eq!(ldexp(1.0, -2000), 0.0);
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
        let e = enclose_rescaled(&ControlHull, &big);
        let h = ControlHull.enclose(&big);
        // the hull is exact: the rescaled one may only be wider by the subnormal steps
        for j in 0..2 {
            assert!(e.coords[j].lo <= h.coords[j].lo && e.coords[j].hi >= h.coords[j].hi);
            assert!(e.coords[j].lo >= h.coords[j].lo * (1.0 + 1e-15) - 1e-300);
        }
        assert_eq!(e.coords[1].lo, -1e-300);
        assert_eq!(e.coords[1].hi, 1e-310);
    }
}
