//! [`Ddi`]: a rigorous double-double enclosure ("double-double interval", midpoint-radius form).
//!
//! A `Ddi` is a set `[c - r, c + r]` of reals with centre `c = hi + lo` (an unevaluated sum of
//! two f64, a *double-word*) and radius `r >= 0` (one f64). It implements [`Scalar`], so every
//! generic kernel of the crate (de Boor, derivative control points, rational derivatives, de
//! Casteljau) runs on it unchanged and returns a verified enclosure about 2^-100 relative wide
//! instead of the 2^-50 of f64 interval arithmetic. [`Scalar::to_interval`] then rounds the set
//! outward to f64, which is where a final width of one ulp (or zero, for an exact result) comes
//! from.
//!
//! # Soundness contract
//!
//! For every operation `z = x op y`: for all reals `a` in `x` and `b` in `y`, `a op b` lies in
//! `z`. The centre is computed with error-free transformations and double-word algorithms; every
//! rounding error that is not removed exactly is bounded from above and added to the radius,
//! together with the propagated radii. Overflow or NaN anywhere (centre or radius) turns the
//! result into [`Ddi::ENTIRE`] (all reals); division by a set that may contain 0 does too.
//!
//! # Error-free transformations (binary64, round to nearest, no overflow)
//!
//! * TwoSum (Knuth; Møller 1965; Shewchuk 1997 Thm. 7; Muller et al., *Handbook of
//!   Floating-Point Arithmetic*, 2nd ed. 2018, Alg. 4.4): `s = fl(a+b)`, `e` with `a + b = s + e`
//!   exactly, `|e| <= ulp(s)/2`. Exact even with subnormals (additions never underflow).
//! * TwoProd with FMA (Handbook Alg. 4.8; Dekker 1971 without FMA): `p = fl(ab)`,
//!   `e = fl(ab - p)`; `ab = p + e` exactly unless underflow: if `e_a + e_b <= e_min + 52`
//!   the error term may be inexact, by at most `eta = 2^-1075` (half the subnormal spacing).
//!
//! Every f64 operation `o` in round-to-nearest satisfies `|fl(o) - o| <= u|o| + eta` with
//! `u = 2^-53`, the `eta` only for products, quotients and FMA (sums are exact in the subnormal
//! range). Bounds in terms of the *computed* result use `u|o| <= u/(1-u) |fl(o)| <= U1 |fl(o)|`,
//! `U1 = u (1 + 2^-50)`.
//!
//! # Lemma B (rounding of the radius formulas)
//!
//! Let `T >= 0` be a real expression that is a sum of at most 8 terms, each term either a
//! nonnegative f64, a sum of at most 8 nonnegative f64, or a product or quotient of two such sums
//! (a quotient's divisor a positive f64), and let `R` be its value evaluated in binary64
//! round-to-nearest, with `R` finite. Then [`up`]`(R) = fl(fl(R * INFL) + FLOOR) >= T`, with
//! `INFL = 1 + 2^-46`, `FLOOR = 2^-1068`.
//!
//! *Proof.* All quantities are nonnegative, so each rounding lowers a value by at most a factor
//! `(1-u)` and, for a product or quotient, an absolute `eta`; no product is multiplied further.
//! Hence `R >= T (1-u)^15 - 8 eta` (at most 7 + 1 + 7 roundings on any path, at most 8
//! products). `y = fl(R * INFL) >= R INFL (1-u) - eta >= T (1-u)^16 (1 + 2^-46) - 10 eta
//! >= T (1 + 100u) - 10 eta` (since `2^-46 = 128u`). Case `y + FLOOR < 2^-1021`: both are
//! multiples of `2^-1074` below `2^-1021`, so the sum is exact and `y + FLOOR >= T + 118 eta`.
//! Otherwise `y > 2^-1022`, so `100u y >= 10 eta`, `T <= (y + 10 eta)/(1 + 100u) <= y`, and
//! `fl(y + FLOOR) >= y` (monotonicity of rounding). ∎
//!
//! If the formula contains no product or quotient (a plain sum of nonnegative f64), [`up_sum`]
//! `(R) = fl(R * INFL)` suffices and keeps an exact zero: if `R < 2^-1021` every partial sum is
//! below `2^-1021` and exact, so `R = T`; otherwise `fl(R * INFL) >= R (1 + 2^-46)(1 - u) >=
//! T (1 - u)^8 (1 + 127u) >= T`.

use crate::num::Scalar;
use inari::Interval;
use std::cmp::Ordering;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// The degree from which the Bézier extraction of a span runs in double words
/// ([`crate::num::dw`], about five times cheaper than with running bounds at high degree).
/// Every degree that needs an insertion: at degrees 2 to 5 the extraction with running bounds
/// was the largest single cost of `newton` on ordinary B-splines (callgrind, `clamped_uniform`
/// -12.5% instructions with double words, `bezier` -6.4%), and the running bounds' one
/// advantage there, exact Bézier points of dyadic data, showed in no bound or certificate
/// (`tightness`: 100% optimal and certified on every family, `ties` included; the span's end
/// points are made exact by `fraction_free::snap_exact_ends` either way).
pub(crate) const DW_MIN_DEGREE: usize = 2;

/// Unit roundoff u = 2^-53.
const U: f64 = 1.0 / 9_007_199_254_740_992.0;
/// U1 = u (1 + 2^-50) >= u / (1 - u) (exact: 53-bit significand 1 + 2^-50).
pub(crate) const U1: f64 = U * (1.0 + 1.0 / 1_125_899_906_842_624.0);
/// Radius inflation 1 + 2^-46 (Lemma B).
pub(crate) const INFL: f64 = 1.0 + 1.0 / 70_368_744_177_664.0;
/// 2^-1068 (Lemma B): 64 times the smallest subnormal (checked by a unit test).
pub(crate) const FLOOR: f64 = 3.16e-322;
/// 16 eta = 2^-1071: bound for the underflow errors of one double-word product (4 products with
/// at most 2 eta each). Checked by a unit test.
pub(crate) const ETA16: f64 = 3.95e-323;
/// Below this magnitude a TwoProd may be inexact (e_a + e_b <= e_min + 52 means |ab| < 2^-969).
const TWOPROD_SAFE: f64 = 4.008_336_720_017_946e-292; // 2^-968

/// Upper bound of a radius formula (Lemma B in the module docs).
#[inline(always)]
pub(crate) fn up(r: f64) -> f64 {
    r * INFL + FLOOR
}

/// An upper bound of k 2^-1074 for k >= 0 (a count of underflow errors of products, each at
/// most 2^-1074), formed without a floating-point product whose result is subnormal: such a
/// product takes a microcode assist of about 45 ns per operation on Intel cores (measured on
/// this project's Xeon machine, against 0.7 ns for a normal result), which the a-priori
/// bounds would otherwise pay per coefficient. For k <= 2^52 the value is ceil(k) 2^-1074,
/// exact as the bit pattern ceil(k) (a subnormal or 2^-1022); above, the product itself
/// (normal then); NaN stays NaN.
#[inline]
pub(crate) fn eta_multiple(k: f64) -> f64 {
    if k <= 4_503_599_627_370_496.0 {
        // (k >= 0 here, so ceil(k) is an integer in [0, 2^52], exactly the bits of
        // ceil(k) 2^-1074)
        f64::from_bits(k.max(0.0).ceil() as u64)
    } else {
        k * f64::from_bits(1)
    }
}

/// Upper bound of a sum of nonnegative f64 (Lemma B, second part); keeps 0 exact.
#[inline(always)]
fn up_sum(r: f64) -> f64 {
    r * INFL
}

/// An upper bound of |a - b| for f64 a, b: RN(|a - b|) has relative error <= u and no
/// underflow error (subtraction), so up_sum covers it (Lemma B, second part).
#[inline]
pub(crate) fn dist_up(a: f64, b: f64) -> f64 {
    up_sum((a - b).abs())
}

/// TwoSum (Knuth / Møller; Handbook Alg. 4.4): s + e = a + b exactly (no overflow).
#[inline(always)]
pub(crate) fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (s, e)
}

/// TwoProd with FMA (Handbook Alg. 4.8): p + e = a b exactly unless |ab| < 2^-969, then within
/// eta = 2^-1075.
#[inline(always)]
pub(crate) fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    let e = a.mul_add(b, -p);
    (p, e)
}

/// The sign of the exact sum of `xs` (at most 8 values), by Shewchuk's Grow-Expansion (1997,
/// Thm. 10): the components form a nonoverlapping expansion with the same exact sum, so its
/// sign is the sign of the largest non-zero component. Falls back to exact rationals when an
/// intermediate is not finite (overflow); `None` for a NaN or infinite input.
pub(crate) fn sum_sign(xs: &[f64]) -> Option<Ordering> {
    if xs.len() > 8 || xs.iter().any(|x| !x.is_finite()) {
        return None;
    }
    let mut e = [0.0f64; 8];
    for (n, &x) in xs.iter().enumerate() {
        let mut q = x;
        for c in e[..n].iter_mut() {
            let (s, r) = two_sum(q, *c);
            *c = r;
            q = s;
        }
        e[n] = q;
    }
    let e = &e[..xs.len()];
    if e.iter().all(|c| c.is_finite()) {
        let top = e.iter().rev().find(|c| **c != 0.0).copied().unwrap_or(0.0);
        return top.partial_cmp(&0.0);
    }
    let sum = xs.iter().fold(crate::num::Exact::of(0.0), |a, &x| {
        a + crate::num::Exact::of(x)
    });
    sum.cmp_f64(0.0)
}

/// Whether x is a (normal) power of two, +-2^k.
#[inline]
fn is_pow2(x: f64) -> bool {
    x.is_normal() && x.to_bits() & ((1u64 << 52) - 1) == 0
}

/// The next f64 below a finite x (-MAX goes to -inf; +inf to MAX; NaN and -inf to NaN).
/// (Without a branch on the sign of x: [`crate::num::next_down`].)
#[inline]
fn next_down(x: f64) -> f64 {
    if x == f64::NEG_INFINITY {
        f64::NAN
    } else {
        crate::num::next_down(x)
    }
}

/// A lower f64 bound of a + b + c (a, b, c finite), as tight as round-downward when c is small
/// against a + b, else at most a few ulps below.
///
/// Tight case: with (s, e) = TwoSum(a, b), (d, e1) = TwoSum(e, c), (s2, e2) = TwoSum(s, d) we
/// have exactly a + b + c = s2 + e2 + e1, and f = fl(e2 + e1) has the sign of e2 + e1 (round-to-
/// nearest of a sum of two floats is zero only if the sum is). If f >= 0, s2 is a lower bound.
/// If f < 0 we return the predecessor of s2, which is a lower bound if |e1 + e2| <= g, the gap
/// below s2: e2 < 0 means s + d was rounded up to s2, so |e2| <= g/2; if e2 >= 0 then
/// |e1 + e2| <= |e1|; and |e1| <= u|d|. We require |d| <= |s2|/4, so u|d| <= u|s2|/4 <= g/2
/// (g >= ulp(s2)/2 >= u|s2|/2 for normal s2; in the subnormal range all three sums are exact,
/// e1 = e2 = 0).
///
/// General case (c not small): still a + b + c = s2 + E, E = e2 + e1 exactly, and
/// next_down(fl(E)) <= E (the predecessor of the nearest float of E is <= E), so
/// next_down(fl(s2 + next_down(f))) <= s2 + E: about two ulps below.
/// Non-finite intermediates give NaN, which the caller maps to ENTIRE.
#[inline]
fn lower_sum3(a: f64, b: f64, c: f64) -> f64 {
    let (s, e) = two_sum(a, b);
    let (d, e1) = two_sum(e, c);
    let (s2, e2) = two_sum(s, d);
    let f = e2 + e1;
    if !(s2.is_finite() && f.is_finite()) {
        return f64::NAN;
    }
    if d.abs() <= s2.abs() * 0.25 {
        if f < 0.0 {
            next_down(s2)
        } else {
            s2
        }
    } else {
        next_down(s2 + next_down(f))
    }
}

/// A rigorous double-double enclosure `[hi + lo - rad, hi + lo + rad]` (see the module docs for
/// the error analysis). `Copy`, 24 bytes, no allocation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ddi {
    hi: f64,
    lo: f64,
    rad: f64,
}

impl Ddi {
    /// The set of all reals (result of overflow, NaN, or division by a set containing 0).
    pub const ENTIRE: Ddi = Ddi {
        hi: 0.0,
        lo: 0.0,
        rad: f64::INFINITY,
    };

    /// The exact value `x` (non-finite x gives [`Ddi::ENTIRE`]).
    #[inline]
    pub fn exact(x: f64) -> Ddi {
        if x.is_finite() {
            Ddi {
                hi: x,
                lo: 0.0,
                rad: 0.0,
            }
        } else {
            Ddi::ENTIRE
        }
    }

    /// The set `[hi + lo - rad, hi + lo + rad]` (the pair is renormalised exactly with TwoSum).
    /// Non-finite input or a negative radius gives [`Ddi::ENTIRE`].
    pub fn new(hi: f64, lo: f64, rad: f64) -> Ddi {
        let (h, l) = two_sum(hi, lo);
        Ddi::checked(h, l, rad)
    }

    /// The exact difference `x - y` of two f64 (a double-word, by TwoSum).
    #[inline]
    pub fn diff(x: f64, y: f64) -> Ddi {
        let (s, e) = two_sum(x, -y);
        Ddi::checked(s, e, 0.0)
    }

    /// The same centre with the radius enlarged by `extra >= 0` (rounded upward); a negative or
    /// NaN `extra` gives ENTIRE.
    #[inline]
    pub fn widen(self, extra: f64) -> Ddi {
        if extra == 0.0 {
            return self;
        }
        if extra.is_nan() || extra < 0.0 {
            return Ddi::ENTIRE; // NaN or negative: no valid radius
        }
        // A sum of two nonnegative f64: Lemma B (up_sum).
        Ddi::checked(self.hi, self.lo, up_sum(self.rad + extra))
    }

    /// A `Ddi` containing the interval `x` (ENTIRE if `x` is empty or unbounded).
    pub fn from_interval(x: Interval) -> Ddi {
        if x.is_empty() {
            return Ddi::ENTIRE;
        }
        Ddi::from_bounds(x.inf(), x.sup())
    }

    /// A `Ddi` containing the real interval [a, b] (ENTIRE if a > b or either is not finite).
    #[inline]
    pub fn from_bounds(a: f64, b: f64) -> Ddi {
        if !(a.is_finite() && b.is_finite() && a <= b) {
            return Ddi::ENTIRE;
        }
        if a == b {
            return Ddi::exact(a);
        }
        // Any c in [a, b] will do: a + (b - a)/2 rounded, clamped. The distances are bounded by
        // dist_up (an overflowing b - a gives an infinite radius, hence ENTIRE).
        let c = (a + 0.5 * (b - a)).clamp(a, b);
        Ddi::checked(c, 0.0, dist_up(c, a).max(dist_up(b, c)))
    }

    /// High part of the centre.
    #[inline]
    pub fn hi(&self) -> f64 {
        self.hi
    }

    /// Low part of the centre (the centre is `hi + lo` exactly).
    #[inline]
    pub fn lo(&self) -> f64 {
        self.lo
    }

    /// Radius bound.
    #[inline]
    pub fn rad(&self) -> f64 {
        self.rad
    }

    /// An upper bound of |x| over the set (inf for ENTIRE).
    #[inline]
    pub fn abs_upper(&self) -> f64 {
        // A sum of three nonnegative f64: Lemma B (up_sum).
        up_sum(self.hi.abs() + self.lo.abs() + self.rad)
    }

    /// Whether this is the set of all reals.
    #[inline]
    pub fn is_entire(&self) -> bool {
        self.rad == f64::INFINITY
    }

    /// Whether every value of the set lies strictly above the f64 `t`: hi + lo - rad - t > 0,
    /// decided exactly ([`sum_sign`]); ENTIRE never does.
    pub fn is_above(&self, t: f64) -> bool {
        !self.is_entire() && sum_sign(&[self.hi, self.lo, -self.rad, -t]) == Some(Ordering::Greater)
    }

    /// Whether every value of the set lies at or below the f64 `t`: hi + lo + rad - t <= 0,
    /// decided exactly; ENTIRE never does.
    pub fn is_at_most(&self, t: f64) -> bool {
        !self.is_entire()
            && matches!(
                sum_sign(&[self.hi, self.lo, self.rad, -t]),
                Some(Ordering::Less | Ordering::Equal)
            )
    }

    /// The largest f64 w strictly below every value of the set (so a quantity enclosed by the
    /// set is provably > w), or -inf when there is none to give (ENTIRE, NaN, or a lower end
    /// at or below -MAX). `to_interval().inf()` is a double c <= the lower end L (at most one
    /// step below RD(L)); the exact comparisons [`Ddi::is_above`] then pick next_up(c) if it
    /// is still < L, else c if c < L, else (c = L exactly) next_down(c).
    pub fn strictly_below(&self) -> f64 {
        // Fast path from the parts, lower end L = h + (l - r), for a non-zero finite h (the
        // sign of fl(l - r) is that of the exact l - r: a rounded difference is 0 only if the
        // operands are equal):
        // * l - r > 0 and l < g = next_up(h) - h (exact: neighbours): h < L <= h + l < next_up(h),
        //   so h is the largest double below L;
        // * l = r: L = h exactly, the answer is next_down(h);
        // * l - r < 0 and (r - l) < h - next_down(h) (exact gap; r - l <= fl(r - l)(1 + 2^-50),
        //   as in `to_interval`): next_down(h) < L < h.
        // Otherwise the general rule below.
        let (h, l, r) = (self.hi, self.lo, self.rad);
        if h != 0.0 && h.is_finite() && r.is_finite() {
            let t = l - r;
            if t > 0.0 {
                if l < h.next_up() - h {
                    return h;
                }
            } else if t == 0.0 {
                return next_down(h);
            } else {
                let below = next_down(h);
                if -t * (1.0 + 1.0 / 1_125_899_906_842_624.0) < h - below {
                    return below;
                }
            }
        }
        let c = self.lower_end();
        if !c.is_finite() || self.is_entire() {
            return f64::NEG_INFINITY;
        }
        let above = c.next_up();
        if above.is_finite() && self.is_above(above) {
            above
        } else if self.is_above(c) {
            c
        } else {
            next_down(c)
        }
    }

    /// `RD(hi + lo - rad)` or a double at most one step below it (-inf for ENTIRE): the lower
    /// end of [`Scalar::to_interval`], without the upper one. Fast path: the lower end is
    /// v = hi + t with t = lo - rad exactly. RN(lo - rad) has the sign of t (a rounded
    /// difference of two floats is 0 only if they are equal): if t >= 0, hi <= v is the lower
    /// bound. Else, with g = hi - next_down(hi) (exact: neighbours), |t| <= |fl(t)| / (1 - u)
    /// <= fl(|fl(t)| (1 + 2^-50)) (no underflow error: a tiny difference is exact), so if that
    /// is <= g then next_down(hi) <= v. Otherwise (large radius) the general `lower_sum3`.
    #[inline(always)]
    pub fn lower_end(&self) -> f64 {
        if self.is_entire() {
            return f64::NEG_INFINITY;
        }
        let (h, l, r) = (self.hi, self.lo, self.rad);
        let t = l - r;
        // (both fast cases decided first and the answer taken by a select: whether t >= 0 is
        // a coin toss on random data; only the rare general case branches)
        let below = next_down(h);
        let nonneg = t >= 0.0;
        let within = -t * (1.0 + 1.0 / 1_125_899_906_842_624.0) <= h - below;
        if !(nonneg | within) {
            return lower_sum3(h, l, -r);
        }
        if nonneg {
            h
        } else {
            below
        }
    }

    /// The upper end of [`Scalar::to_interval`] (+inf for ENTIRE): [`Ddi::lower_end`] of the
    /// negation, negated (negation is exact).
    #[inline(always)]
    pub fn upper_end(&self) -> f64 {
        -(-*self).lower_end()
    }

    /// Whether the set is the single f64 value `hi` (lo = rad = 0).
    #[inline]
    fn is_f64(&self) -> bool {
        self.lo == 0.0 && self.rad == 0.0
    }

    /// Whether the set is exactly {0}.
    #[inline]
    fn is_zero(&self) -> bool {
        self.hi == 0.0 && self.is_f64()
    }

    /// The centre `hi + lo` and the radius.
    #[inline]
    pub(crate) fn parts(&self) -> (f64, f64, f64) {
        (self.hi, self.lo, self.rad)
    }

    /// The set with centre `hi + lo` and radius `rad` ([`Ddi::ENTIRE`] if a part is not finite
    /// or the radius negative): the caller vouches that it encloses what it stands for.
    #[inline]
    pub(crate) fn from_parts(hi: f64, lo: f64, rad: f64) -> Ddi {
        Ddi::checked(hi, lo, rad)
    }

    /// Build from parts; anything non-finite (or a negative/NaN radius) gives ENTIRE.
    #[inline(always)]
    fn checked(hi: f64, lo: f64, rad: f64) -> Ddi {
        if hi.is_finite() && lo.is_finite() && (0.0..f64::INFINITY).contains(&rad) {
            Ddi { hi, lo, rad }
        } else {
            Ddi::ENTIRE
        }
    }

    /// Sum. Exact cases first (a zero operand; two f64: TwoSum is error-free). Otherwise the
    /// double-word addition "SloppyDWPlusDW" (Joldes, Muller, Popescu, "Tight and rigorous error
    /// bounds for basic building blocks of double-word arithmetic", ACM TOMS 44(2), 2017,
    /// Alg. 4; Dekker 1971 add2) with the final Fast2Sum replaced by TwoSum, and a running error
    /// bound: only the two plain additions `v` and `w` round, each by at most U1 times its
    /// computed value (additions have no underflow error). The bound is relative to the
    /// operands, not to the (possibly cancelled) result: about 2^-104 max(|x|, |y|), which is
    /// all the curve kernels need (their error budget is an ulp of the coordinate scale).
    ///
    /// Exact sum of the centres: xh + yh + xl + yl = sh + sl + v - e1 = sh + w - e2 - e1
    /// = zh + zl - e1 - e2, |e1| <= U1 |v|, |e2| <= U1 |w|.
    #[inline]
    fn add_impl(x: Ddi, y: Ddi) -> Ddi {
        if y.is_zero() {
            return x;
        }
        if x.is_zero() {
            return y;
        }
        if x.is_f64() && y.is_f64() {
            let (s, e) = two_sum(x.hi, y.hi);
            return Ddi::checked(s, e, 0.0);
        }
        let (sh, sl) = two_sum(x.hi, y.hi);
        let v = x.lo + y.lo;
        let w = sl + v;
        let (zh, zl) = two_sum(sh, w);
        // Two terms plus a product of U1 and a sum of two nonnegative f64: Lemma B. Except
        // where nothing was rounded: two exact operands (radius 0) whose low parts cancel
        // exactly (fl(x.lo + y.lo) = 0 only if x.lo + y.lo = 0, with gradual underflow), so
        // that w = sl and the sum (zh, zl) = x + y is exact: radius 0, not Lemma B's floor
        // 2^-1068 (a subnormal radius makes every later operation on it take a microcode
        // assist, ~45 ns each on Intel cores: an exact quotient's residual x - q y is such a
        // sum).
        let r = if x.rad == 0.0 && y.rad == 0.0 && v == 0.0 {
            0.0
        } else {
            up(x.rad + y.rad + U1 * (v.abs() + w.abs()))
        };
        Ddi::checked(zh, zl, r)
    }

    /// Product (double-word times double-word with FMA, JMP 2017 Alg. 12 "DWTimesDW3", with a
    /// running error bound instead of the a-priori 5u^2).
    ///
    /// Centres X = xh + xl, Y = yh + yl: XY = xh yh + (xh yl + xl yh + xl yl).
    /// (ph, pl) = TwoProd(xh, yh); tl0 = fl(xl yl); tl1 = fl(xh yl + tl0); cl2 = fl(xl yh + tl1);
    /// cl3 = fl(pl + cl2); (zh, zl) = TwoSum(ph, cl3). Then |XY - (zh + zl)| <=
    /// U1 (|tl0| + |tl1| + |cl2| + |cl3|) + 16 eta (three products/FMAs at u|o| + eta each,
    /// converted to computed values with U1 and 2 eta; one addition; TwoProd within eta).
    /// Radii: for a = X + da, b = Y + db, |ab - XY| <= |X| ry + |Y| rx + rx ry, |X| <= |xh| + |xl|.
    #[inline]
    fn mul_impl(x: Ddi, y: Ddi) -> Ddi {
        // Exact special cases (keep exact results exact, radius 0):
        if x.is_zero() || y.is_zero() {
            // 0 * y = 0 for every real y (and y is not ENTIRE-with-NaN: rad is finite or inf,
            // but 0 * any real is 0, so {0} is a valid enclosure either way).
            return Ddi::exact(0.0);
        }
        if x.is_f64() && y.is_f64() {
            let (p, e) = two_prod(x.hi, y.hi);
            // TwoProd is exact unless |xh yh| < 2^-969 (then within eta <= ETA16); |e| <=
            // ulp(p)/2, so (p, e) is already a double-word.
            let r = if p.abs() >= TWOPROD_SAFE { 0.0 } else { ETA16 };
            return Ddi::checked(p, e, r);
        }
        // Scaling by a power of two is exact unless a part underflows (1 * y, 0.5 * y, ...).
        if x.is_f64() && is_pow2(x.hi) {
            if let Some(z) = y.scale_exact(x.hi) {
                return z;
            }
        }
        if y.is_f64() && is_pow2(y.hi) {
            if let Some(z) = x.scale_exact(y.hi) {
                return z;
            }
        }
        let (ph, pl) = two_prod(x.hi, y.hi);
        let tl0 = x.lo * y.lo;
        let tl1 = x.hi.mul_add(y.lo, tl0);
        let cl2 = x.lo.mul_add(y.hi, tl1);
        let cl3 = pl + cl2;
        let (zh, zl) = two_sum(ph, cl3);
        // Five terms, each a product of two sums of nonnegative f64 or one f64: Lemma B.
        let r = (x.hi.abs() + x.lo.abs()) * y.rad
            + (y.hi.abs() + y.lo.abs()) * x.rad
            + x.rad * y.rad
            + U1 * (tl0.abs() + tl1.abs() + cl2.abs() + cl3.abs())
            + ETA16;
        Ddi::checked(zh, zl, up(r))
    }

    /// `s * self` for a power of two `s`, if every part stays exact: a nonzero part whose scaled
    /// value is normal (or infinite, caught by `checked`) was scaled exactly.
    #[inline]
    fn scale_exact(self, s: f64) -> Option<Ddi> {
        let (h, l, r) = (self.hi * s, self.lo * s, self.rad * s.abs());
        let ok = |a: f64, b: f64| a == 0.0 || b.abs() >= f64::MIN_POSITIVE;
        if ok(self.hi, h) && ok(self.lo, l) && ok(self.rad, r) {
            Some(Ddi::checked(h, l, r))
        } else {
            None
        }
    }

    /// `self * y + c` in one step (the Horner step), more accurate and cheaper than a product
    /// followed by a sum. Exact special case: a zero factor returns `c`.
    ///
    /// Centres: XY + C = xh yh + (xh yl + xl yh + xl yl) + ch + cl. With (ph, pl) =
    /// TwoProd(xh, yh), (sh, sl) = TwoSum(ph, ch), t0 = fl(xl yl), t1 = fl(xh yl + t0),
    /// t2 = fl(xl yh + t1), t3 = fl(pl + cl), t4 = fl(t2 + t3), t5 = fl(sl + t4),
    /// (zh, zl) = TwoSum(sh, t5): XY + C = zh + zl up to the six roundings, each at most
    /// U1 |t_i| (+ 2 eta for the three products/FMAs, eta for TwoProd: <= ETA16 in all).
    /// Radii as in the product, plus rc.
    #[inline]
    pub fn mul_add(self, y: Ddi, c: Ddi) -> Ddi {
        let x = self;
        if x.is_zero() || y.is_zero() {
            return c;
        }
        let (ph, pl) = two_prod(x.hi, y.hi);
        let (sh, sl) = two_sum(ph, c.hi);
        let t0 = x.lo * y.lo;
        let t1 = x.hi.mul_add(y.lo, t0);
        let t2 = x.lo.mul_add(y.hi, t1);
        let t3 = pl + c.lo;
        let t4 = t2 + t3;
        let t5 = sl + t4;
        let (zh, zl) = two_sum(sh, t5);
        // Six terms; products of two sums of at most six nonnegative f64: Lemma B.
        let r = (x.hi.abs() + x.lo.abs()) * y.rad
            + (y.hi.abs() + y.lo.abs()) * x.rad
            + x.rad * y.rad
            + c.rad
            + U1 * (t0.abs() + t1.abs() + t2.abs() + t3.abs() + t4.abs() + t5.abs())
            + ETA16;
        Ddi::checked(zh, zl, up(r))
    }

    /// The value at t of the Bernstein polynomial of degree n <= 3 with *exact f64* coefficients
    /// `c` (n + 1 of them), for an f64 t in [0, 1], enclosed about 2^-99 relative to max |c_i|
    /// wide: the compensated de Casteljau algorithm (Jiang, Li, Luo and Wang, "A compensated de
    /// Casteljau algorithm for evaluating polynomials in Bernstein basis", 2010; de Casteljau
    /// as in NURBS Book A1.5), at a fraction of the cost of de Casteljau or Horner in `Ddi`
    /// (no radius propagation per step: the error bound is a priori). Anything else (more than
    /// four coefficients, t outside [0, 1], a non-finite value) gives [`Ddi::ENTIRE`].
    ///
    /// Algorithm. (r, ρ) = TwoSum(1, -t), so r + ρ = 1 - t exactly. Level by level,
    /// (s, π1) = TwoProd(r, b̂_i), (v, π2) = TwoProd(t, b̂_{i+1}), (b̂'_i, σ) = TwoSum(s, v),
    /// ŵ = fl(ρ b̂_i + fl(fl(π1 + π2) + σ)) (an FMA), b̃'_i = fl(r b̃_i + fl(t b̃_{i+1} + ŵ))
    /// (two FMAs); b̂ starts as c, b̃ as 0; the result is the double-word b̂_0 + b̃_0.
    ///
    /// Error bound (u = 2^-53, η = 2^-1075; no overflow). Let β^j be the exact de Casteljau
    /// values, e^j = β^j - b̂^j, M = max |c_i|. (1) |b̂^j| <= (1 + u)^{3j} M + 3jη =: M̄ <=
    /// (1 + 10u) M + 10η. (2) With the exact residuals π* = r b̂ - s (the computed π is within
    /// η of it) the recurrence is exact: e'_i = w*_i + (1 - t) e_i + t e_{i+1},
    /// w* = π1* + π2* + σ + ρ b̂_i, and |w*| <= u (r + t + 1 + 1) M̄ + 2η <= W := 3.01 u M̄ + 2η
    /// (|ρ| <= u, r <= (1 - t)(1 + u), |σ| <= U1 |b̂'|); so |e^j| <= j W (convex combinations).
    /// (3) With δ = e - b̃ and (1 - t) = r + ρ: δ'_i = (w* - ŵ) + (1 - t) δ_i + t δ_{i+1} +
    /// ρ b̃_i - ε_i, ε the two FMA roundings of b̃'. Here |w* - ŵ| <= 3.01 u W + 3η, the
    /// term |ρ b̃_i| <= u (j - 1) W' and |ε| <= 2 u j W' + 2η at level j (|b̃^{j-1}| <=
    /// (j - 1) W' with W' = W (1 + 4u) + |δ|, the δ part of order u^2). Summed over the
    /// levels, |δ^n| <= u W (3.01 n (n + 1) / 2 + 2.01 n) + 5nη, i.e. <= 24.1 u W + 15η for
    /// n = 3 (13.1 u W + 10η for n = 2), so |p(t) - (b̂_0 + b̃_0)| <= 73 u^2 M + 16η, which
    /// is at most 2^-99 M + 2^-1071 (128 u^2 = 2^-99). The radius is up(fl(2^-99 M) +
    /// 2^-1071) (Lemma B: a product and a term). Checked against exact rationals in the
    /// tests.
    pub fn de_casteljau_f64(c: &[f64], t: f64) -> Ddi {
        if !(0.0..=1.0).contains(&t) {
            return Ddi::ENTIRE;
        }
        // (one body, instantiated per length so that the levels unroll)
        match c.len() {
            1 => Ddi::de_casteljau_n::<1>(c, t),
            2 => Ddi::de_casteljau_n::<2>(c, t),
            3 => Ddi::de_casteljau_n::<3>(c, t),
            4 => Ddi::de_casteljau_n::<4>(c, t),
            _ => Ddi::ENTIRE,
        }
    }

    /// [`Ddi::de_casteljau_f64`] for `L` = n + 1 coefficients (`c.len() == L`, t in [0, 1]).
    #[inline(always)]
    fn de_casteljau_n<const L: usize>(c: &[f64], t: f64) -> Ddi {
        let mut bh = [0.0f64; L];
        let mut bt = [0.0f64; L];
        let mut m = 0.0f64;
        for (b, &x) in bh.iter_mut().zip(c) {
            *b = x;
            m = m.max(x.abs());
        }
        let (r, rho) = two_sum(1.0, -t);
        for j in 1..L {
            for i in 0..L - j {
                let (s, p1) = two_prod(r, bh[i]);
                let (v, p2) = two_prod(t, bh[i + 1]);
                let (h, sg) = two_sum(s, v);
                let w = rho.mul_add(bh[i], (p1 + p2) + sg);
                bt[i] = r.mul_add(bt[i], t.mul_add(bt[i + 1], w));
                bh[i] = h;
            }
        }
        // 2^-99 and 2^-1071 (exact constants)
        const E99: f64 = 1.0 / 633_825_300_114_114_700_748_351_602_688.0;
        Ddi::new(bh[0], bt[0], up(E99 * m + ETA16))
    }

    /// A lower bound of min |y| over the set y, or `None` if the set may contain 0 (or is so
    /// close to 0 that bounding the quotient is pointless: below 2^-1000).
    ///
    /// |y| >= |yh| - (|yl| + ry) >= |yh| - s with s = up_sum(|yl| + ry) (Lemma B). D = |yh| - s is
    /// computed as d = fl(D) <= D (1 + u) (a subtraction is exact near the underflow range), and
    /// fl(d (1 - 2^-50)) <= D (1 + u)^2 (1 - 2^-50) < D for d >= 2^-1000 (no underflow).
    #[inline]
    pub(crate) fn abs_lower(y: Ddi) -> Option<f64> {
        let s = up_sum(y.lo.abs() + y.rad);
        let d = y.hi.abs() - s;
        if d >= 9.332_636_185_032_189e-302 {
            // 9.33e-302 ~ 2^-1000
            Some(d * (1.0 - 1.0 / 1_125_899_906_842_624.0))
        } else {
            None
        }
    }

    /// The quotient for a divisor set y whose magnitude is below 2^-1000 (a difference of
    /// subnormal knots, say), where [`Ddi::abs_lower`] gives up: a / b = (a 2^600) / (b 2^600)
    /// for every a in x and b in y, and scaling a `Ddi` up by a power of two is exact (each
    /// part is multiplied exactly unless it overflows, which `scale_exact` / `checked` turn
    /// into `None` / ENTIRE). After the scaling |yh| >= 2^-474, so the quotient is formed
    /// normally (no further recursion); a set y that may contain 0 still gives ENTIRE.
    #[inline(never)]
    fn div_tiny(x: Ddi, y: Ddi) -> Ddi {
        const S: f64 = 4.149_515_568_880_993e180; // 2^600
        if y.is_entire() || y.hi == 0.0 || y.hi.abs() >= 9.332_636_185_032_189e-302 {
            return Ddi::ENTIRE;
        }
        match (x.scale_exact(S), y.scale_exact(S)) {
            (Some(xs), Some(ys)) if !xs.is_entire() && !ys.is_entire() => {
                match Ddi::abs_lower(ys) {
                    Some(_) => Ddi::div_impl(xs, ys),
                    None => Ddi::ENTIRE,
                }
            }
            _ => Ddi::ENTIRE,
        }
    }

    /// Quotient. An approximate double-word quotient q is computed (Dekker-style correction
    /// q1 = xh / yh, q2 = (x - q1 y) / yh), then the residual set R = x - q y is enclosed with the
    /// rigorous `Ddi` product and difference (it contains a - q b for all a in x, b in y), and
    /// for every such pair a / b - q = (a - q b) / b, so |a/b - q| <= (|R_c| + R_r) / min|y|.
    /// The residual is tiny (~2^-104 |x|) because q is accurate, so the radius is ~2^-104 |q|.
    /// Set y possibly containing 0: ENTIRE.
    #[inline]
    fn div_impl(x: Ddi, y: Ddi) -> Ddi {
        let ymin = match Ddi::abs_lower(y) {
            Some(m) => m,
            None => return Ddi::div_tiny(x, y),
        };
        if x.is_zero() {
            return Ddi::exact(0.0);
        }
        // Division by +-2^k is a scaling by the exact power of two 1/y (if that is normal).
        if y.is_f64() && is_pow2(y.hi) {
            let s = 1.0 / y.hi;
            if is_pow2(s) {
                if let Some(z) = x.scale_exact(s) {
                    return z;
                }
            }
        }
        let q1 = x.hi / y.hi;
        let (ph, pl) = two_prod(q1, y.hi);
        let rr = (((x.hi - ph) - pl) + x.lo) - q1 * y.lo;
        let q2 = rr / y.hi;
        let (qh, ql) = two_sum(q1, q2);
        let q = Ddi::checked(qh, ql, 0.0);
        if q.is_entire() {
            return Ddi::ENTIRE;
        }
        let res = x - q * y;
        // One quotient of a sum of three nonnegative f64 by the f64 ymin: Lemma B. An exactly
        // zero residual (sum 0 means every term 0) gives an exact quotient.
        let num = res.hi.abs() + res.lo.abs() + res.rad;
        let r = if num == 0.0 { 0.0 } else { up(num / ymin) };
        Ddi::checked(qh, ql, r)
    }
}

impl Add for Ddi {
    type Output = Ddi;
    #[inline]
    fn add(self, y: Ddi) -> Ddi {
        Ddi::add_impl(self, y)
    }
}

impl Sub for Ddi {
    type Output = Ddi;
    #[inline]
    fn sub(self, y: Ddi) -> Ddi {
        Ddi::add_impl(self, -y)
    }
}

impl Ddi {
    /// `-self` where `sign` < 0, else `self` (exact: the parts of [`Neg`]), by products with
    /// +-1 rather than a branch on the sign (for callers whose sign is a coin toss on random
    /// data); the sign-adjusted values of the min side (the max side of -C_j).
    #[inline]
    pub fn signed(self, sign: f64) -> Ddi {
        let s = if sign < 0.0 { -1.0 } else { 1.0 };
        Ddi {
            hi: s * self.hi,
            lo: s * self.lo,
            rad: self.rad,
        }
    }
}

impl Neg for Ddi {
    type Output = Ddi;
    /// Exact.
    #[inline]
    fn neg(self) -> Ddi {
        Ddi {
            hi: -self.hi,
            lo: -self.lo,
            rad: self.rad,
        }
    }
}

impl Mul for Ddi {
    type Output = Ddi;
    #[inline]
    fn mul(self, y: Ddi) -> Ddi {
        Ddi::mul_impl(self, y)
    }
}

impl Div for Ddi {
    type Output = Ddi;
    #[inline]
    fn div(self, y: Ddi) -> Ddi {
        Ddi::div_impl(self, y)
    }
}

impl Scalar for Ddi {
    #[inline]
    fn from_f64(x: f64) -> Self {
        Ddi::exact(x)
    }

    /// From degree [`DW_MIN_DEGREE`] on, the extraction in double words with one a-priori
    /// bound ([`crate::num::dw`]), where its guard holds (else the running bounds of `Ddi`).
    #[inline]
    fn clamp_span_fast(p: usize, h: usize, t: &mut [f64], q: &mut [Self]) -> bool {
        p >= DW_MIN_DEGREE && crate::num::dw::clamp_span_dw(p, h, t, q)
    }

    /// From degree [`DW_MIN_DEGREE`] on, the sweep in double words ([`crate::num::dw`]),
    /// where its guard holds.
    #[inline]
    fn sweep_fast(
        p: usize,
        h: usize,
        knots: &[f64],
        pts: &[Self],
        k0: usize,
        count: usize,
        emit: &mut dyn FnMut(usize, &[Self]),
    ) -> bool {
        p >= DW_MIN_DEGREE && crate::num::dw::sweep_dw(p, h, knots, pts, k0, count, emit)
    }

    /// The fused Horner step [`Ddi::mul_add`].
    #[inline]
    fn horner_step(acc: &Self, t: &Self, c: &Self) -> Self {
        acc.mul_add(*t, *c)
    }

    /// The corner-cutting step `lo + a (hi - lo)`, as whichever of the two enclosures
    /// `a (hi - lo) + lo` (thesis sec. 5.1) and `(1 - a) lo + a hi` (convex form) has the smaller
    /// radius (both are `Ddi` evaluations of the same real expression, so both enclose it).
    ///
    /// Why both: in midpoint-radius form the thesis form propagates the radii as
    /// `|a| (r_hi + r_lo) + r_lo`, i.e. up to 2x per step for a in [0, 1] (lo occurs twice),
    /// so a chain of p corner cuts (de Boor, Boehm knot insertion for Bézier extraction) grows
    /// the radius like 2^p: at p = 40 the Bézier points of a span came out ~1e-13 relative wide
    /// instead of ~2^-100. The convex form propagates `(1 - a) r_lo + a r_hi <= max(r_lo, r_hi)`
    /// for a point-like a in [0, 1] (no growth); the thesis form is better when `a` is a wide set
    /// and hi ~ lo (its `rad(a)` term is `rad(a) |hi - lo|`, not `rad(a) (|lo| + |hi|)`).
    ///
    /// At an exact parameter t in [0, 1] (corner cutting at an f64 parameter, the common case)
    /// only the convex form is computed: its radius, (1 - t) r_lo + t r_hi plus rounding, is
    /// then never above the thesis form's t (r_lo + r_hi) + r_lo plus rounding, so the choice
    /// is the same and the thesis form's work is saved; t = 0 and t = 1 return the end itself
    /// (exactly the value of both forms), and so do equal ends (a convex combination of two
    /// points of one interval lies in it; the thesis form's exact case, hi - lo = 0). Equal
    /// exact ends are returned for any parameter. A narrow parameter (radius <= 2^-40 |a|,
    /// centre in [0, 1]) also takes the convex form only.
    // (always: the corner-cutting loops of de Casteljau and knot insertion are its hot callers;
    // an out-of-line call there cost the degree-10 span a third more time)
    #[inline(always)]
    fn lerp(a: &Self, lo: &Self, hi: &Self) -> Self {
        if lo == hi && lo.rad == 0.0 {
            return *lo; // x + a (x - x) = x for every a
        }
        // an exact or narrow parameter (an enclosed knot ratio, radius ~2^-105 |a|): the
        // thesis form can only win by about rad(a) (|lo| + |hi|), far below the f64 resolution
        if a.rad <= a.hi.abs() * (1.0 / 1_099_511_627_776.0) && (0.0..=1.0).contains(&a.hi) {
            if a.is_f64() {
                if a.hi == 0.0 || lo == hi {
                    return *lo;
                }
                if a.hi == 1.0 {
                    return *hi;
                }
            }
            return a.mul_add(*hi, (Ddi::exact(1.0) - *a) * *lo);
        }
        let thesis = a.mul_add(*hi - *lo, *lo);
        let convex = a.mul_add(*hi, (Ddi::exact(1.0) - *a) * *lo);
        if convex.rad <= thesis.rad {
            convex
        } else {
            thesis
        }
    }

    /// `[RD(hi + lo - rad), RU(hi + lo + rad)]`: one ulp wide (or a point) whenever the radius is
    /// small against the centre; the comments in the code (and on `lower_sum3`) say why the
    /// bounds hold.
    #[inline]
    fn to_interval(&self) -> Interval {
        Interval::try_from((self.lower_end(), self.upper_end())).unwrap_or(Interval::ENTIRE)
    }

    #[inline]
    fn to_f64(&self) -> f64 {
        self.hi
    }

    #[inline]
    fn is_exact_zero(&self) -> bool {
        self.is_zero()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// `eta_multiple` is an upper bound of k 2^-1074, exact for integers up to 2^52, the
    /// product itself above, NaN for NaN; checked against exact rational products.
    #[test]
    fn eta_multiple_bounds_the_product() {
        use crate::num::Exact;
        let tiny = Exact::of(f64::from_bits(1));
        for k in [
            0.0,
            1.0,
            17.0,
            27.5,
            1e3 + 0.25,
            4_503_599_627_370_495.5,
            4_503_599_627_370_496.0,
            1e17,
            1e300,
        ] {
            let got = eta_multiple(k);
            let exact = Exact::of(k) * tiny.clone();
            assert!(!exact.gt_f64(got), "{k}: {got:e}");
            if k.fract() == 0.0 && k <= 4_503_599_627_370_496.0 {
                assert_eq!(got.to_bits(), k as u64, "{k}");
            }
            // (at most one unit of 2^-1074 above, or one rounding for the normal products)
            assert!(
                got <= k * f64::from_bits(1) + f64::from_bits(1) || got == k * f64::from_bits(1),
                "{k}"
            );
        }
        assert!(eta_multiple(f64::NAN).is_nan());
        assert_eq!(eta_multiple(f64::INFINITY), f64::INFINITY);
    }

    #[test]
    fn lerp_encloses_exact_convex_combinations() {
        // (1 - A) X + A Y in exact rationals at the corners of the parameter and point sets (a
        // multilinear function: its extremes over the box are at corners) must lie in the
        // result: exact, narrow (an enclosed knot ratio) and wide parameters, equal ends.
        use crate::num::exact::Exact;
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        for k in 0..6000 {
            let t: f64 = rng.random_range(0.0..1.0);
            let ra = [0.0, t * 1e-31, t * 1e-3][k % 3];
            let a = Ddi::new(t, t * 1e-17 * (k % 2) as f64, ra);
            let x = rng.random_range(-1.0..1.0) * 10f64.powi(rng.random_range(-20..20));
            let y = if k % 7 == 0 {
                x
            } else {
                rng.random_range(-1.0..1.0)
            };
            let rx = if k % 5 == 0 { 0.0 } else { x.abs() * 1e-25 };
            let ry = if k % 5 == 0 { 0.0 } else { y.abs() * 1e-25 };
            let lo = Ddi::new(x, x * 1e-18, rx);
            let hi = if x == y { lo } else { Ddi::new(y, 0.0, ry) };
            let z = <Ddi as Scalar>::lerp(&a, &lo, &hi);
            if lo == hi && rx == 0.0 {
                assert_eq!(z, lo, "equal exact ends are returned for any parameter");
            }
            let ex = |d: Ddi, s: f64| {
                Exact::of(d.hi) + Exact::of(d.lo) + Exact::of(s) * Exact::of(d.rad)
            };
            let zc = Exact::of(z.hi) + Exact::of(z.lo);
            for sa in [-1.0, 1.0] {
                for sx in [-1.0, 1.0] {
                    for sy in [-1.0, 1.0] {
                        let (av, xv, yv) = (ex(a, sa), ex(lo, sx), ex(hi, sy));
                        let v = (Exact::of(1.0) - av.clone()) * xv + av * yv;
                        let dev = v - zc.clone();
                        let ok = (dev.clone() - Exact::of(z.rad)).signum()
                            != Some(Ordering::Greater)
                            && (dev + Exact::of(z.rad)).signum() != Some(Ordering::Less);
                        assert!(ok, "lerp({a:?}, {lo:?}, {hi:?}) = {z:?}");
                    }
                }
            }
        }
    }

    /// `strictly_below` is the largest f64 below the exact lower end (checked with exact
    /// rationals), on random sets, sets whose lower end is a double, and tiny radii.
    #[test]
    fn strictly_below_is_the_largest_double_under_the_lower_end() {
        use crate::num::Exact;
        let mut r = ChaCha8Rng::seed_from_u64(11);
        let check = |x: Ddi| {
            let w = x.strictly_below();
            let lower = Exact::of(x.hi()) + Exact::of(x.lo()) - Exact::of(x.rad());
            assert!(
                lower.gt_f64(w),
                "{:?}: {w} not below",
                (x.hi(), x.lo(), x.rad())
            );
            assert!(
                !lower.gt_f64(w.next_up()),
                "{:?}: {w} not the largest",
                (x.hi(), x.lo(), x.rad())
            );
        };
        for _ in 0..2000 {
            let hi: f64 = r.random_range(-1e3..1e3);
            let ulp = crate::num::ulp(hi);
            let lo = r.random_range(-0.5..0.5) * ulp * [1.0, 1e-10, 0.0][r.random_range(0..3)];
            let rad = [0.0, ulp * 1e-12, ulp * r.random_range(0.0..3.0)][r.random_range(0..3)];
            check(Ddi::new(hi, lo, rad));
        }
        // powers of two, where the gaps above and below differ (the fast path's cases)
        for hi in [1.0, -1.0, 0.125, -0.125, 2f64.powi(60), -(2f64.powi(-70))] {
            let (up, dn) = (hi.next_up() - hi, hi - hi.next_down());
            for lo in [0.0, 0.5 * up, -0.5 * dn, 0.25 * dn, -0.25 * up, 1e-3 * dn] {
                for rad in [0.0, lo.abs(), 0.5 * dn, 0.75 * up, 2.0 * dn, 1e-5 * up] {
                    check(Ddi::new(hi, lo, rad));
                }
            }
        }
        // lower end exactly a double: hi = 1, lo = 2^-60, rad = 2^-60
        check(Ddi::new(1.0, 2f64.powi(-60), 2f64.powi(-60)));
        check(Ddi::exact(0.0));
        check(Ddi::exact(-f64::MIN_POSITIVE));
        assert_eq!(Ddi::ENTIRE.strictly_below(), f64::NEG_INFINITY);
    }

    /// The compensated de Casteljau value encloses the exact value of the polynomial (exact
    /// rationals), on random, clustered and cancelling coefficients of magnitudes 2^-80..2^80
    /// and subnormal / huge mixes, at parameters 0, 1, tiny, near 1, dyadic and random; and
    /// its radius is an error bound, not a vacuous one (the observed error reaches a fair part
    /// of it, and the uncorrected de Casteljau value lies outside it).
    #[test]
    fn de_casteljau_f64_encloses_exact_values() {
        use crate::num::Exact;
        let mut r = ChaCha8Rng::seed_from_u64(11);
        let mut worst = 0.0f64;
        let mut corrections_matter = 0;
        for it in 0..6000 {
            let n = 1 + it % 3;
            let mag = 2f64.powi(r.random_range(-80..=80));
            let base = rnd(&mut r, 0) * mag;
            let c: Vec<f64> = (0..=n)
                .map(|k| match it % 5 {
                    // clustered: the value is a tiny difference of large terms
                    0 => base + rnd(&mut r, 0) * mag * 2f64.powi(-40),
                    1 => r.random_range(-8.0f64..8.0).round() * mag,
                    2 if k == 1 => f64::from_bits(r.random_range(1..1u64 << 52)),
                    _ => rnd(&mut r, 0) * mag,
                })
                .collect();
            let t = match it % 7 {
                0 => 0.0,
                1 => 1.0,
                2 => r.random_range(0.0..1e-12),
                3 => 1.0 - r.random_range(0.0..1e-9),
                4 => r.random_range(0..1024) as f64 / 1024.0,
                5 => f64::from_bits(r.random_range(1..1u64 << 40)),
                _ => r.random_range(0.0..1.0),
            };
            let v = Ddi::de_casteljau_f64(&c, t);
            assert!(!v.is_entire(), "{c:?} {t}");
            // exact value: sum c_k C(n, k) t^k (1 - t)^(n - k)
            let (te, se) = (Exact::of(t), Exact::of(1.0) - Exact::of(t));
            let mut exact = Exact::of(0.0);
            for (k, &ck) in c.iter().enumerate() {
                let mut term = Exact::of(ck) * Exact::of(crate::num::binom(n, k));
                for _ in 0..k {
                    term = term * te.clone();
                }
                for _ in k..n {
                    term = term * se.clone();
                }
                exact = exact + term;
            }
            let dev = exact.clone() - Exact::of(v.hi()) - Exact::of(v.lo());
            assert!(
                (dev.clone() - Exact::of(v.rad())).signum() != Some(Ordering::Greater)
                    && (dev.clone() + Exact::of(v.rad())).signum() != Some(Ordering::Less),
                "{c:?} at {t}: {v:?}"
            );
            let m = c.iter().fold(0.0f64, |a, x| a.max(x.abs()));
            let err = dev.round_up().abs().max(dev.round_down().abs());
            if m > 1e-300 {
                worst = worst.max(err / (m * 2f64.powi(-99)));
            }
            // the correction term matters: without it the centre would lie outside the
            // enclosure (a mutation dropping the compensation fails the containment above)
            if v.lo().abs() > 2.0 * v.rad() {
                corrections_matter += 1;
            }
        }
        assert!(worst <= 1.0, "observed error {worst} of the bound");
        assert!(
            worst > 1e-4,
            "the bound is far from the observed errors: {worst}"
        );
        assert!(corrections_matter > 1000, "{corrections_matter}");
        // outside [0, 1], too many coefficients, non-finite data: ENTIRE
        assert!(Ddi::de_casteljau_f64(&[1.0, 2.0], 1.5).is_entire());
        assert!(Ddi::de_casteljau_f64(&[1.0; 5], 0.5).is_entire());
        assert!(Ddi::de_casteljau_f64(&[1.0, f64::NAN], 0.5).is_entire());
    }

    #[test]
    fn constants_are_what_the_proofs_use() {
        assert_eq!(FLOOR.to_bits(), 64); // 2^-1068 = 64 * 2^-1074
        assert_eq!(ETA16.to_bits(), 8); // 2^-1071
        assert_eq!(TWOPROD_SAFE, 2f64.powi(-968));
        assert_eq!(U, 2f64.powi(-53));
        assert_eq!(U1, 2f64.powi(-53) + 2f64.powi(-103));
        assert_eq!(INFL, 1.0 + 2f64.powi(-46));
        let ratio = U / (1.0 - U);
        assert!(U1 >= ratio);
    }

    /// Random finite f64 with random sign and an exponent in [-e, e].
    fn rnd(rng: &mut ChaCha8Rng, e: i32) -> f64 {
        let m: f64 = rng.random_range(1.0..2.0);
        let s = if rng.random_bool(0.5) { -1.0 } else { 1.0 };
        s * m * 2f64.powi(rng.random_range(-e..=e))
    }

    /// A random Ddi: an exact f64, a double-word (result of an exact TwoSum), or one with radius.
    fn rnd_ddi(rng: &mut ChaCha8Rng, e: i32) -> Ddi {
        let h = rnd(rng, e);
        match rng.random_range(0..4) {
            0 => Ddi::exact(h),
            1 => Ddi::new(h, h * rnd(rng, 2) * 1e-17, 0.0),
            2 => Ddi::new(h, h * rnd(rng, 2) * 1e-17, (h * 1e-31).abs()),
            _ => Ddi::exact(h) / Ddi::exact(rnd(rng, e)),
        }
    }

    #[test]
    fn exact_ops_stay_exact() {
        let a = Ddi::exact(3.0);
        let b = Ddi::exact(0.1);
        for z in [a + b, a - b, a * b, Ddi::exact(6.0) / a] {
            assert_eq!(z.rad(), 0.0, "{z:?}");
        }
        assert_eq!(
            (Ddi::exact(6.0) / a).to_interval(),
            crate::num::iv::point(2.0)
        );
        // 3 + 0.1 is exact as a double-word and rounds outward to one ulp.
        let s = (a + b).to_interval();
        assert!(s.inf() < s.sup() && s.sup() == f64::from_bits(s.inf().to_bits() + 1));
        assert!(s.contains(3.0 + 0.1));
        assert_eq!(
            (Ddi::exact(0.0) * Ddi::ENTIRE).to_interval(),
            crate::num::iv::point(0.0)
        );
    }

    /// Sums of exact double-words (radius 0): where the low parts cancel exactly the sum is
    /// exact with radius 0 (no subnormal floor, which would make every later operation on the
    /// radius take a microcode assist), so an exact quotient (w x) / w of an exact product is
    /// x itself, radius 0; where they do not cancel, the radius still covers the rounding of
    /// the low parts (exact rational arithmetic at both ends).
    #[test]
    fn cancelling_exact_sums_are_exact() {
        use crate::num::exact::Exact;
        let mut rng = ChaCha8Rng::seed_from_u64(29);
        let (mut exact, mut rounded) = (0, 0);
        for _ in 0..20000 {
            let (a, b) = (rnd(&mut rng, 60), rnd(&mut rng, 60));
            let x = Ddi::exact(a) * Ddi::exact(b);
            let q = x / Ddi::exact(b);
            assert_eq!((q.hi(), q.lo(), q.rad()), (a, 0.0, 0.0), "{a} * {b} / {b}");
            // y: another exact double-word, its low part cancelling x's or not
            let yh = rnd(&mut rng, 60);
            let yl = if rng.random_bool(0.5) {
                -x.lo()
            } else {
                yh * rnd(&mut rng, 2) * 1e-17
            };
            let (yh, yl) = two_sum(yh, yl);
            let y = Ddi::new(yh, yl, 0.0);
            let z = x + y;
            let want = Exact::of(x.hi()) + Exact::of(x.lo()) + Exact::of(yh) + Exact::of(yl);
            let c = Exact::of(z.hi()) + Exact::of(z.lo());
            let err = want - c;
            assert!(
                err.cmp_f64(z.rad()) != Some(Ordering::Greater)
                    && err.cmp_f64(-z.rad()) != Some(Ordering::Less),
                "{x:?} + {y:?} -> {z:?}"
            );
            if x.lo() + y.lo() == 0.0 {
                assert_eq!(z.rad(), 0.0, "{x:?} + {y:?} -> {z:?}");
                exact += 1;
            } else {
                rounded += 1;
            }
        }
        assert!(
            exact > 4000 && rounded > 4000,
            "{exact} exact, {rounded} rounded"
        );
    }

    #[test]
    fn overflow_and_zero_division_give_entire() {
        let big = Ddi::exact(f64::MAX);
        assert!((big + big).is_entire());
        assert!((big * Ddi::exact(2.0)).is_entire());
        assert!((Ddi::exact(1.0) / Ddi::exact(0.0)).is_entire());
        assert!((Ddi::exact(1.0) / Ddi::new(1e-20, 0.0, 1e-20)).is_entire());
        assert!(Ddi::exact(f64::NAN).is_entire());
        assert!((Ddi::ENTIRE + Ddi::exact(1.0)).is_entire());
        assert!((Ddi::exact(1.0) / Ddi::ENTIRE).is_entire());
        assert_eq!(Ddi::ENTIRE.to_interval(), Interval::ENTIRE);
        // Tiny operands: underflow is covered, not ignored.
        let t = Ddi::exact(1e-200) * Ddi::exact(1e-200);
        assert!(t.to_interval().contains(0.0) && t.rad() > 0.0);
    }

    /// Quotients by sets below 2^-1000 (differences of subnormal knots) are scaled, not given
    /// up: 3 2^-1074 / 7 2^-1074 = 3/7 to double-word accuracy; a tiny set holding 0 stays
    /// ENTIRE, and a quotient beyond f64::MAX too.
    #[test]
    fn tiny_divisors_are_scaled() {
        let sub = |k: u64| Ddi::exact(f64::from_bits(k));
        let q = sub(3) / sub(7);
        let third = Ddi::exact(3.0) / Ddi::exact(7.0);
        assert!(!q.is_entire() && q.rad() <= 1e-30);
        assert!(q.to_interval().subset(third.to_interval()));
        // -0.75 2^-100 / (3 2^-1074) = -2^972 exactly
        let q = Ddi::exact(-0.75 * 2f64.powi(-100)) / (sub(4) - sub(1));
        assert_eq!(
            q.to_interval(),
            Interval::try_from((-2f64.powi(972), -2f64.powi(972))).unwrap()
        );
        assert!((Ddi::exact(1.0) / Ddi::new(f64::from_bits(3), 0.0, 1e-320)).is_entire());
        assert!((Ddi::exact(1.0) / sub(1)).is_entire());
        let q = Ddi::exact(1e-310) / sub(1);
        assert!(!q.is_entire() && q.to_interval().contains(1e-310 / 5e-324));
    }

    /// Against inari on f64 operands: the Ddi result must intersect the inari enclosure of the
    /// exact result, lie within it up to the outward rounding (<= 1 ulp each side), and be a
    /// point or one ulp wide.
    #[test]
    fn agrees_with_inari_on_f64_operands() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        for _ in 0..20000 {
            let (a, b) = (rnd(&mut rng, 40), rnd(&mut rng, 40));
            let (ia, ib) = (crate::num::iv::point(a), crate::num::iv::point(b));
            let (da, db) = (Ddi::exact(a), Ddi::exact(b));
            for (z, iz) in [
                (da + db, ia + ib),
                (da - db, ia - ib),
                (da * db, ia * ib),
                (da / db, ia / ib),
            ] {
                let zi = z.to_interval();
                assert!(zi.subset(iz), "{a} {b}: {zi:?} not in {iz:?}");
                let ulps = zi.sup().to_bits().abs_diff(zi.inf().to_bits());
                assert!(ulps <= 1, "{a} {b}: {zi:?} ({ulps} ulps)");
            }
        }
    }

    /// Against inari on random double-word operands (with radii): the outward-rounded Ddi
    /// result lies inside inari's enclosure up to one ulp on each side (inari's bound is exact
    /// when the image's end is a float; the Ddi set may exceed the image by ~1e-30 relative).
    #[test]
    fn within_inari_on_ddi_operands() {
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let step = |x: f64, up: bool| {
            let b = x.to_bits();
            let t = if (x >= 0.0) == up { b + 1 } else { b - 1 };
            if x == 0.0 {
                if up {
                    f64::from_bits(1)
                } else {
                    -f64::from_bits(1)
                }
            } else {
                f64::from_bits(t)
            }
        };
        for _ in 0..20000 {
            let (x, y) = (rnd_ddi(&mut rng, 40), rnd_ddi(&mut rng, 40));
            let (ix, iy) = (x.to_interval(), y.to_interval());
            for (z, iz) in [
                (x + y, ix + iy),
                (x - y, ix - iy),
                (x * y, ix * iy),
                (x / y, ix / iy),
            ] {
                let zi = z.to_interval();
                assert!(
                    zi.inf() >= step(iz.inf(), false) && zi.sup() <= step(iz.sup(), true),
                    "{x:?} {y:?}: {zi:?} vs {iz:?}"
                );
            }
        }
    }

    /// Double-word quality: for well-conditioned operations the radius is ~1e-30 relative.
    #[test]
    fn radius_is_double_word_sized() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        for _ in 0..20000 {
            let x = Ddi::new(rnd(&mut rng, 30), 0.0, 0.0) / Ddi::exact(rnd(&mut rng, 30));
            let y = Ddi::new(rnd(&mut rng, 30), 0.0, 0.0) / Ddi::exact(rnd(&mut rng, 30));
            for z in [x * y, x / y] {
                assert!(z.rad() <= 1e-30 * z.hi().abs(), "{x:?} {y:?} {z:?}");
            }
            if x.hi() * y.hi() > 0.0 {
                let z = x + y;
                assert!(z.rad() <= 1e-30 * z.hi().abs(), "{x:?} {y:?} {z:?}");
            }
        }
    }

    /// Containment across the whole exponent range (subnormals, underflowing products,
    /// overflow): every result either contains the exact value (MPFR with enough bits to hold
    /// any double-word exactly) or is ENTIRE.
    #[cfg(feature = "mpfr")]
    #[test]
    fn contains_mpfr_values_at_extreme_exponents() {
        use rug::Float;
        let prec = 4400;
        let mut rng = ChaCha8Rng::seed_from_u64(33);
        let any = |rng: &mut ChaCha8Rng| -> Ddi {
            let e = rng.random_range(-1074..1024);
            let m: f64 = rng.random_range(1.0..2.0);
            let h = (if rng.random_bool(0.5) { -m } else { m }) * 2f64.powi(e);
            let h = if h.is_finite() { h } else { f64::MAX };
            match rng.random_range(0..5) {
                0 => Ddi::exact(h),
                1 => Ddi::exact(f64::from_bits(rng.random_range(1..1u64 << 52))), // subnormal
                2 => Ddi::new(h, h * 1e-17, (h * 1e-30).abs()),
                3 => Ddi::exact(0.0),
                _ => Ddi::exact(h) / Ddi::exact(3.0),
            }
        };
        let exact = |d: &Ddi, t: i32| -> Float {
            Float::with_val(prec, d.hi()) + d.lo() + Float::with_val(prec, d.rad()) * t
        };
        let inside = |z: &Ddi, v: &Float| -> bool {
            if z.is_entire() {
                return true;
            }
            let c = Float::with_val(prec, z.hi()) + z.lo();
            (c.clone() - z.rad()) <= *v && *v <= (c + z.rad())
        };
        for _ in 0..20000 {
            let (x, y, w) = (any(&mut rng), any(&mut rng), any(&mut rng));
            for tx in [-1, 0, 1] {
                for ty in [-1, 0, 1] {
                    let (a, b) = (exact(&x, tx), exact(&y, ty));
                    let c = exact(&w, 0);
                    let s = Float::with_val(prec, &a + &b);
                    assert!(inside(&(x + y), &s), "{x:?} + {y:?} = {:?}", x + y);
                    let p = Float::with_val(prec, &a * &b);
                    assert!(inside(&(x * y), &p), "{x:?} * {y:?} = {:?}", x * y);
                    let f = Float::with_val(prec, &p + &c);
                    assert!(inside(&x.mul_add(y, w), &f), "{x:?} * {y:?} + {w:?}");
                    if !b.is_zero() {
                        let q = Float::with_val(prec, &a / &b);
                        assert!(inside(&(x / y), &q), "{x:?} / {y:?} = {:?}", x / y);
                    }
                }
            }
            for z in [x + y, x * y, x / y, x.mul_add(y, w)] {
                let i = z.to_interval();
                if !z.is_entire() {
                    let c = Float::with_val(prec, z.hi()) + z.lo();
                    assert!(
                        i.inf() <= c.clone() - z.rad() && c + z.rad() <= i.sup(),
                        "{z:?} -> {i:?}"
                    );
                }
            }
        }
    }

    /// `to_interval` of sets with every radius size (tight path and general path) contains the
    /// exact ends, computed in MPFR; the general path is at most a few ulps loose.
    #[cfg(feature = "mpfr")]
    #[test]
    fn to_interval_contains_exact_ends() {
        use rug::Float;
        let mut rng = ChaCha8Rng::seed_from_u64(21);
        for _ in 0..50000 {
            let h = rnd(&mut rng, 300);
            let l = h * rnd(&mut rng, 2) * 1e-17;
            let r = (h * 10f64.powf(rng.random_range(-40.0..2.0))).abs();
            let d = Ddi::new(h, l, r);
            let i = d.to_interval();
            let c = Float::with_val(1200, d.hi()) + d.lo();
            let (lo, hi) = (c.clone() - d.rad(), c + d.rad());
            assert!(i.inf() <= lo && hi <= i.sup(), "{d:?} -> {i:?}");
            // at most 4 ulps beyond the exact ends (the general path is about 2)
            let (a, b) = (
                lo.to_f64_round(rug::float::Round::Down),
                hi.to_f64_round(rug::float::Round::Up),
            );
            assert!(
                a.to_bits().abs_diff(i.inf().to_bits()) <= 4 || a.signum() != i.inf().signum(),
                "{d:?}"
            );
            assert!(
                b.to_bits().abs_diff(i.sup().to_bits()) <= 4 || b.signum() != i.sup().signum(),
                "{d:?}"
            );
        }
    }

    /// Containment against 256-bit MPFR at the centre and both ends of every operand.
    #[cfg(feature = "mpfr")]
    #[test]
    fn contains_mpfr_values() {
        use rug::Float;
        let prec = 600; // wide enough to hold sums of double-words exactly for |exp| <= 60
        let ends = |d: &Ddi| -> Vec<Float> {
            let c = Float::with_val(prec, d.hi()) + d.lo();
            vec![c.clone(), c.clone() - d.rad(), c + d.rad()]
        };
        let inside = |z: &Ddi, v: &Float| -> bool {
            let c = Float::with_val(prec, z.hi()) + z.lo();
            let lo = c.clone() - z.rad();
            let hi = c + z.rad();
            lo <= *v && *v <= hi
        };
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let mut max_rel: f64 = 0.0;
        for _ in 0..20000 {
            let x = rnd_ddi(&mut rng, 60);
            let y = rnd_ddi(&mut rng, 60);
            let w = rnd_ddi(&mut rng, 60);
            let (ex, ey) = (ends(&x), ends(&y));
            // x * y + w at every corner and the centre of w as well
            let fma = x.mul_add(y, w);
            for a in &ex {
                for b in &ey {
                    for c in ends(&w) {
                        let v = Float::with_val(prec, a * b) + c;
                        assert!(
                            inside(&fma, &v),
                            "mul_add: {x:?} {y:?} {w:?} -> {fma:?} misses {v}"
                        );
                    }
                }
            }
            for (op, z) in [(0, x + y), (1, x - y), (2, x * y), (3, x / y)] {
                for a in &ex {
                    for b in &ey {
                        let v = match op {
                            0 => Float::with_val(prec, a + b),
                            1 => Float::with_val(prec, a - b),
                            2 => Float::with_val(prec, a * b),
                            _ => Float::with_val(prec, a / b),
                        };
                        assert!(inside(&z, &v), "op {op}: {x:?} {y:?} -> {z:?} misses {v}");
                        let zi = z.to_interval();
                        assert!(zi.inf() <= v && v <= zi.sup(), "to_interval op {op}");
                    }
                }
                if x.rad() == 0.0 && y.rad() == 0.0 && z.hi() != 0.0 {
                    max_rel = max_rel.max(z.rad() / z.hi().abs());
                }
            }
        }
        // Point operands (relative width over all four ops, cancellation excluded by the
        // random exponents except rarely): double-word accuracy.
        assert!(max_rel < 1e-28, "max relative radius {max_rel}");
    }
}
