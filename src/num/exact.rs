//! [`Exact`]: exact rational arithmetic (big integers, `num-rational`), a [`Scalar`] for the
//! certificates of optimal bounds (`enclose::certify`).
//!
//! A NURBS curve with f64 data evaluated at a rational parameter has a rational value: every
//! step of de Boor corner cutting (thesis CurvePntByCornerCut, NURBS Book A5.1), of the
//! derivative control points (thesis eq. 2.7) and of the rational quotient rule (thesis eq.
//! 3.10) is a field operation on rationals (knots, weights and coordinates are f64, hence
//! dyadic rationals, embedded exactly by [`Scalar::from_f64`]). So the generic kernels of
//! `crate::spline`, run on `Exact`, return the exact value C^(k)(u), with no rounding at all.
//!
//! A division by zero (which the kernels never perform on valid curves: knot differences of a
//! non-empty span and weight functions are > 0) gives the *undefined* value instead of a
//! panic; every operation with an undefined operand is undefined, its [`Scalar::to_interval`]
//! is ENTIRE, and every comparison with it is false, so it can never certify anything.

use crate::num::Scalar;
use inari::Interval;
use num_bigint::{BigInt, Sign};
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};
use std::cmp::Ordering;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// An exact rational number, or *undefined* (the result of a division by zero). A defined
/// value has a positive denominator (the arithmetic below relies on it), and every result of
/// the arithmetic is in lowest terms.
#[derive(Clone, Debug, PartialEq)]
pub struct Exact(Option<BigRational>);

impl Exact {
    /// The exact value of a finite f64 (undefined for NaN or an infinity).
    pub fn of(x: f64) -> Exact {
        Exact(ratio_of_f64(x))
    }

    /// A rational as an exact value (with a positive denominator).
    pub fn from_ratio(q: BigRational) -> Exact {
        Exact(Some(if q.denom().is_negative() {
            BigRational::new_raw(-q.numer(), -q.denom())
        } else {
            q
        }))
    }

    /// The rational itself (`None` if undefined).
    pub fn value(&self) -> Option<&BigRational> {
        self.0.as_ref()
    }

    /// Whether the value is defined and strictly greater than the f64 `x` (false for NaN x;
    /// `x = -inf` is below every rational, `+inf` above).
    pub fn gt_f64(&self, x: f64) -> bool {
        self.cmp_f64(x) == Some(Ordering::Greater)
    }

    /// Exact comparison with an f64 (`None` if undefined or x is NaN).
    pub fn cmp_f64(&self, x: f64) -> Option<Ordering> {
        let q = self.0.as_ref()?;
        if x.is_nan() {
            return None;
        }
        if x == f64::INFINITY {
            return Some(Ordering::Less);
        }
        if x == f64::NEG_INFINITY {
            return Some(Ordering::Greater);
        }
        Some(q.cmp(&ratio_of_f64(x)?))
    }

    /// The largest f64 <= the value (-inf below -f64::MAX; NaN if undefined).
    pub fn round_down(&self) -> f64 {
        let Some(q) = self.0.as_ref() else {
            return f64::NAN;
        };
        // (by cross-multiplication, denominators > 0: `Ratio`'s own comparison divides, a
        // chain of big divisions for the unreduced rationals of the certificates' end game)
        let below = |x: f64| -> bool {
            let r = ratio_of_f64(x).expect("finite");
            q.numer() * r.denom() < r.numer() * q.denom()
        };
        let mut x = approx(q);
        if x == f64::INFINITY {
            x = f64::MAX;
        }
        if x == f64::NEG_INFINITY {
            x = -f64::MAX;
        }
        // x is finite and within a few steps of the value: walk to RD(value) (each comparison
        // exact)
        while below(x) {
            x = x.next_down();
            if x == f64::NEG_INFINITY {
                return x;
            }
        }
        loop {
            let y = x.next_up();
            if y == f64::INFINITY || below(y) {
                return x;
            }
            x = y;
        }
    }

    /// The smallest f64 >= the value (+inf above f64::MAX; NaN if undefined).
    pub fn round_up(&self) -> f64 {
        -(-self.clone()).round_down()
    }

    /// The dyadic rational nearest below-or-at the value with `bits` binary digits after the
    /// point of `scale` (a power of two), i.e. a multiple of `scale * 2^-bits` (undefined stays
    /// undefined). Used to keep Newton iterates of the parameter short.
    pub fn truncate_to(&self, scale_exp: i32, bits: u32) -> Exact {
        let Some(q) = self.0.as_ref() else {
            return Exact(None);
        };
        // grid step 2^g, g = scale_exp - bits: floor(q / 2^g) * 2^g
        let g = scale_exp as i64 - bits as i64;
        Exact(Some(floor_to_grid(q.numer().clone(), q.denom(), g)))
    }

    /// The Newton point u - g1 / g2 truncated as by [`Exact::truncate_to`], without forming the
    /// quotient in lowest terms: with g1 / g2 = n / d (d > 0), u - n / d = (u_n d - n u_d) /
    /// (u_d d) goes to the grid by one integer floor division (no gcd of the long numerators
    /// of data spanning many binades). Undefined if an operand is, or g2 = 0.
    pub fn newton_truncated(u: &Exact, g1: &Exact, g2: &Exact, scale_exp: i32, bits: u32) -> Exact {
        let (Some(u), Some(x), Some(y)) = (u.value(), g1.value(), g2.value()) else {
            return Exact(None);
        };
        if y.is_zero() {
            return Exact(None);
        }
        let (n, d) = (x.numer() * y.denom(), x.denom() * y.numer());
        let (n, d) = if d.is_negative() { (-n, -d) } else { (n, d) };
        let top = u.numer() * &d - n * u.denom();
        let bot = u.denom() * d;
        let g = scale_exp as i64 - bits as i64;
        Exact(Some(floor_to_grid(top, &bot, g)))
    }

    /// The size of the value in bits: those of its numerator and denominator (0 if
    /// undefined); a measure of what arithmetic on it costs.
    pub fn bits(&self) -> u64 {
        self.0
            .as_ref()
            .map_or(0, |q| q.numer().bits() + q.denom().bits())
    }

    /// An estimate e of log2 |value| (|value| within [2^(e-1), 2^(e+1)]); `None` if undefined
    /// or zero.
    pub fn log2_estimate(&self) -> Option<i64> {
        let q = self.0.as_ref().filter(|q| !q.is_zero())?;
        Some(q.numer().bits() as i64 - q.denom().bits() as i64)
    }

    /// The smallest multiple of 2^g that is >= the value (undefined stays undefined).
    pub fn ceil_to(&self, g: i64) -> Exact {
        let Some(q) = self.0.as_ref() else {
            return Exact(None);
        };
        // ceil(q / 2^g) 2^g = -(floor(-q / 2^g) 2^g)
        Exact(Some(-floor_to_grid(-q.numer(), q.denom(), g)))
    }

    /// The sign of the value (`None` if undefined).
    pub fn signum(&self) -> Option<Ordering> {
        self.0.as_ref().map(|q| q.numer().sign().cmp(&Sign::NoSign))
    }
}

/// floor(top / (bot 2^g)) 2^g (bot > 0) in lowest terms: one integer floor division, the
/// result a dyadic rational reduced by trailing zeros.
fn floor_to_grid(top: BigInt, bot: &BigInt, g: i64) -> BigRational {
    if g >= 0 {
        let f = top.div_floor(&(bot << g as u64));
        BigRational::from_integer(f << g as u64)
    } else {
        let f = (top << (-g) as u64).div_floor(bot);
        dyadic(f, (-g) as u64)
    }
}

/// The exact rational of a finite f64 (`None` for NaN / infinities).
fn ratio_of_f64(x: f64) -> Option<BigRational> {
    if !x.is_finite() {
        return None;
    }
    if x == 0.0 {
        return Some(BigRational::zero());
    }
    let bits = x.to_bits();
    let e = ((bits >> 52) & 0x7ff) as i64;
    let frac = bits & ((1u64 << 52) - 1);
    // x = m 2^k with integer m
    let (m, k) = if e == 0 {
        (frac, -1074)
    } else {
        (frac | (1u64 << 52), e - 1075)
    };
    // in lowest terms without a gcd: the denominator is a power of two, so dividing out the
    // numerator's factors of two (m > 0) reduces the fraction
    let z = (m.trailing_zeros() as i64).min((-k).max(0));
    let (m, k) = (m >> z, k + z);
    let m = BigInt::from(m);
    let m = if x < 0.0 { -m } else { m };
    Some(if k >= 0 {
        BigRational::from_integer(m << (k as u64))
    } else {
        BigRational::new_raw(m, BigInt::one() << ((-k) as u64))
    })
}

/// An f64 near q (within a few ulps; ±inf or 0 when out of range): [`approx_ratio`] of its
/// numerator and denominator.
fn approx(q: &BigRational) -> f64 {
    approx_ratio(q.numer(), q.denom(), 0)
}

/// An f64 near n / d 2^e (within a few ulps; ±inf or 0 when out of range, NaN for d = 0): the
/// integer part of |n| 2^s / |d| for an s that leaves ~64 significant bits, scaled back by
/// 2^(e - s) in steps that cannot overflow or underflow prematurely. An estimate, no bound.
pub(crate) fn approx_ratio(n: &BigInt, d: &BigInt, e: i64) -> f64 {
    if d.is_zero() {
        return f64::NAN;
    }
    if n.is_zero() {
        return 0.0;
    }
    let s = 64 - (n.bits() as i64 - d.bits() as i64);
    let (na, da) = (n.abs(), d.abs());
    let m = if s >= 0 {
        (na << (s as u64)) / da
    } else {
        na / (da << ((-s) as u64))
    };
    let mut x = m.to_f64().unwrap_or(f64::INFINITY);
    let mut k = e.saturating_sub(s);
    while k > 0 && x.is_finite() {
        let st = k.min(1000);
        x *= 2f64.powi(st as i32);
        k -= st;
    }
    while k < 0 && x != 0.0 {
        let st = (-k).min(1000);
        x *= 2f64.powi(-(st as i32));
        k += st;
    }
    if n.is_negative() != d.is_negative() {
        -x
    } else {
        x
    }
}

fn lift(
    a: Exact,
    b: Exact,
    f: impl FnOnce(BigRational, BigRational) -> Option<BigRational>,
) -> Exact {
    match (a.0, b.0) {
        (Some(x), Some(y)) => Exact(f(x, y)),
        _ => Exact(None),
    }
}

// Dyadic fast paths. f64 data are dyadic rationals n / 2^e, and so are the values of the
// kernels at a dyadic parameter as long as every divisor is ± a power of two (uniform or
// integer knots). num-rational reduces every result by a gcd; for a power-of-two denominator
// Stein's binary gcd takes O(bits) subtract-and-shift rounds of O(bits) each, which made one
// exact evaluation cost millions of instructions at 500-bit parameters. On dyadic operands
// the results below are computed directly and reduced by trailing zeros alone (O(bits)):
// n / 2^e with n odd or e = 0 is the canonical reduced form (gcd(n, 2^e) = 2^min(tz(n), e)),
// so the `BigRational` is the same value num-rational would have produced (checked by a
// unit test against the general operations).

/// Whether a > b, for rationals with positive denominators in any terms (unreduced ones too),
/// exactly. Cross-multiplication of long unreduced values (thousands of bits, range-limit
/// data) is the costly part, so it runs only where a cheap estimate cannot decide:
///
/// * different signs (or zeros) decide at once;
/// * for one non-zero sign, |a| and |b| are compared by estimates of their logarithms.
///   For an integer x > 0 with B bits, L(x) = log2(top) + sh with sh = max(B - 64, 0) and
///   top = floor(x / 2^sh) satisfies 0 <= log2 x - log2(top) - sh < log2(1 + 2^-63) (top >=
///   2^63 when sh > 0). Rounding top to f64 (relative 2^-53), the library's log2 (a few ulps
///   of a value <= 64) and the three f64 sums and differences of values at most S = max
///   L + 1 in magnitude (each within ulp(4S)) move the estimate
///   D = (L(num a) - L(den a)) - (L(num b) - L(den b)) by less than 2^-30 + 2^-46 S from
///   log2 |a| - log2 |b|. So D beyond the margin 2^-20 + 2^-40 S (about a thousand times
///   that) decides the comparison; only inside it are the products formed.
pub(crate) fn ratio_gt(a: &BigRational, b: &BigRational) -> bool {
    frac_gt((a.numer(), a.denom()), (b.numer(), b.denom()))
}

/// [`ratio_gt`] on numerators and denominators: whether n_a / d_a > n_b / d_b (d_a, d_b > 0).
pub(crate) fn frac_gt((na, da): (&BigInt, &BigInt), (nb, db): (&BigInt, &BigInt)) -> bool {
    let (sa, sb) = (na.sign(), nb.sign());
    if sa != sb || sa == Sign::NoSign {
        // (Minus < NoSign < Plus)
        return sa > sb;
    }
    let l = |x: &BigInt| -> f64 {
        let sh = x.bits().saturating_sub(64);
        let top = (x.magnitude() >> sh).to_u64().unwrap_or(u64::MAX);
        (top as f64).log2() + sh as f64
    };
    let (lna, lda, lnb, ldb) = (l(na), l(da), l(nb), l(db));
    let d = (lna - lda) - (lnb - ldb);
    let s = lna.max(lda).max(lnb).max(ldb) + 1.0;
    let margin = 1.0 / 1_048_576.0 + s / 1_099_511_627_776.0;
    if d.is_finite() && d.abs() > margin {
        // |a| > |b| iff d > 0; for negative values the order flips
        return (d > 0.0) == (sa == Sign::Plus);
    }
    na * db > nb * da
}

/// The exponent e of a denominator d = 2^e (`None` if d is not a power of two).
fn pow2_exp(d: &BigInt) -> Option<u64> {
    let tz = d.trailing_zeros()?;
    (d.is_positive() && tz + 1 == d.bits()).then_some(tz)
}

/// The reduced dyadic rational n / 2^e.
pub(crate) fn dyadic(n: BigInt, e: u64) -> BigRational {
    reduced(n, BigInt::one(), e)
}

/// x + y, or x - y (`neg`), by the dyadic fast path when both are dyadic, else over the
/// common denominator lcm(o_x, o_y) 2^max(e_x, e_y) (odd o).
fn add_sub(x: BigRational, y: BigRational, neg: bool) -> BigRational {
    if let (Some(ex), Some(ey)) = (pow2_exp(x.denom()), pow2_exp(y.denom())) {
        let e = ex.max(ey);
        let a = x.numer() << (e - ex);
        let b = y.numer() << (e - ey);
        return dyadic(if neg { a - b } else { a + b }, e);
    }
    // (a gcd of the odd parts, which are short: products of knot differences' odd parts)
    let ((ox, ex), (oy, ey)) = (split2(x.denom()), split2(y.denom()));
    let e = ex.max(ey);
    let g = ox.gcd(&oy);
    let (fx, fy) = (&oy / &g, &ox / &g);
    let a = (x.numer() * &fx) << (e - ex);
    let b = (y.numer() * &fy) << (e - ey);
    reduced(if neg { a - b } else { a + b }, fx * ox, e)
}

/// The odd part o and the exponent e of d = o 2^e (d > 0).
fn split2(d: &BigInt) -> (BigInt, u64) {
    let e = d.trailing_zeros().unwrap_or(0);
    (d >> e, e)
}

/// n / (o 2^e) in lowest terms (o odd, > 0), as num-rational's `Ratio::new` would give it, but
/// without its gcd of n and the whole denominator (Stein's binary gcd costs O(bits^2) on the
/// ~2,000-bit numerators of data spanning 2^-1074 .. 2^1023): the common factor is
/// 2^min(tz(n), e) times gcd(n, o) = gcd(n mod o, o), a gcd of the odd part's length, none
/// for o = 1 (o odd: gcd(n, o 2^e) = gcd(n, o) gcd(n, 2^e)). Dividing both out leaves gcd = 1:
/// n / g and o / g are coprime, and n / g keeps n's factors of two (g is odd). The dyadic
/// fast paths are its case o = 1 without splitting the denominators.
fn reduced(n: BigInt, o: BigInt, e: u64) -> BigRational {
    if n.is_zero() {
        return BigRational::zero();
    }
    let z = n.trailing_zeros().unwrap_or(0).min(e);
    // (n is divisible by 2^z: the shift is exact also for negative n)
    let (mut n, e) = (n >> z, e - z);
    let mut o = o;
    if !o.is_one() {
        let g = n.mod_floor(&o).gcd(&o);
        if !g.is_one() {
            n /= &g;
            o /= &g;
        }
    }
    BigRational::new_raw(n, o << e)
}

impl Add for Exact {
    type Output = Exact;
    fn add(self, o: Exact) -> Exact {
        lift(self, o, |x, y| Some(add_sub(x, y, false)))
    }
}

impl Sub for Exact {
    type Output = Exact;
    fn sub(self, o: Exact) -> Exact {
        lift(self, o, |x, y| Some(add_sub(x, y, true)))
    }
}

impl Mul for Exact {
    type Output = Exact;
    fn mul(self, o: Exact) -> Exact {
        lift(self, o, |x, y| {
            if let (Some(ex), Some(ey)) = (pow2_exp(x.denom()), pow2_exp(y.denom())) {
                return Some(dyadic(x.numer() * y.numer(), ex + ey));
            }
            let ((ox, ex), (oy, ey)) = (split2(x.denom()), split2(y.denom()));
            Some(reduced(x.numer() * y.numer(), ox * oy, ex + ey))
        })
    }
}

impl Div for Exact {
    type Output = Exact;
    fn div(self, o: Exact) -> Exact {
        // (num-rational panics on a zero divisor: undefined instead)
        lift(self, o, |x, y| {
            if y.is_zero() {
                return None;
            }
            // (n_x / 2^ex) / (±2^m / 2^ey) = ±n_x 2^(ey - ex - m): dyadic
            if let (Some(ex), Some(ey), Some(m)) = (
                pow2_exp(x.denom()),
                pow2_exp(y.denom()),
                pow2_exp(&y.numer().abs()),
            ) {
                let n = if y.is_negative() {
                    -x.numer().clone()
                } else {
                    x.numer().clone()
                };
                let k = ey as i128 - ex as i128 - m as i128;
                return Some(if k >= 0 {
                    dyadic(n << (k as u64), 0)
                } else {
                    dyadic(n, (-k) as u64)
                });
            }
            // (n_x / (o_x 2^e_x)) / (n_y / (o_y 2^e_y)) with n_y = ±o 2^t (o odd):
            // ±n_x o_y 2^e_y / (o_x o 2^(e_x + t))
            let ((ox, ex), (oy, ey)) = (split2(x.denom()), split2(y.denom()));
            let (o, t) = split2(&y.numer().abs());
            let n = (x.numer() * oy) << ey;
            let n = if y.is_negative() { -n } else { n };
            Some(reduced(n, ox * o, ex + t))
        })
    }
}

impl Neg for Exact {
    type Output = Exact;
    fn neg(self) -> Exact {
        Exact(self.0.map(|x| -x))
    }
}

impl Scalar for Exact {
    fn from_f64(x: f64) -> Self {
        Exact::of(x)
    }
    fn to_interval(&self) -> Interval {
        if self.0.is_none() {
            return Interval::ENTIRE;
        }
        Interval::try_from((self.round_down(), self.round_up())).unwrap_or(Interval::ENTIRE)
    }
    fn to_f64(&self) -> f64 {
        self.0.as_ref().map_or(f64::NAN, approx)
    }
    fn is_exact_zero(&self) -> bool {
        self.0.as_ref().is_some_and(Zero::is_zero)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `ratio_gt` against cross-multiplication: values of up to ~3000 bits of both signs and
    /// zero, in lowest and in unreduced terms (the same value as k a / k b, which must compare
    /// as equal both ways), and pairs one unit of a long numerator apart (inside the estimate's
    /// margin: the exact path), and far apart (the estimate).
    #[test]
    fn ratio_comparison_matches_cross_multiplication() {
        use rand::{Rng, SeedableRng};
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let big = |r: &mut rand_chacha::ChaCha8Rng, words: usize| -> BigInt {
            let mut x = BigInt::from(r.random_range(0u64..1 << 62));
            for _ in 0..words {
                x = (x << 64u32) + BigInt::from(r.random::<u64>());
            }
            x
        };
        let (mut fast, mut exact) = (0, 0);
        for round in 0..3000 {
            let (wa, wb) = (r.random_range(0..48usize), r.random_range(0..48usize));
            let sign = |r: &mut rand_chacha::ChaCha8Rng| -> i32 {
                [1, 1, 1, -1, -1, -1, 0][r.random_range(0..7usize)]
            };
            let na = big(&mut r, wa) * sign(&mut r);
            let da = big(&mut r, wb) + 1;
            let (nb, db) = match round % 4 {
                // the same value, unreduced
                0 => {
                    let w = r.random_range(0..8usize);
                    let k = big(&mut r, w) + 1;
                    (&na * &k, &da * &k)
                }
                // one unit apart in a long numerator
                1 => {
                    let k = big(&mut r, 20) + 1;
                    (&na * &k + [1, -1][r.random_range(0..2usize)], &da * &k)
                }
                _ => {
                    let w = r.random_range(0..48usize);
                    let n = big(&mut r, w) * sign(&mut r);
                    (n, big(&mut r, wa) + 1)
                }
            };
            let (a, b) = (BigRational::new_raw(na, da), BigRational::new_raw(nb, db));
            for (x, y) in [(&a, &b), (&b, &a)] {
                let want = x.numer() * y.denom() > y.numer() * x.denom();
                assert_eq!(ratio_gt(x, y), want, "{x} > {y}");
            }
            // (how often the estimate decided: the far pairs)
            let l = |x: &BigInt| x.bits() as f64;
            let d = (l(a.numer()) - l(a.denom())) - (l(b.numer()) - l(b.denom()));
            if d.abs() > 2.0 {
                fast += 1;
            } else {
                exact += 1;
            }
        }
        assert!(fast > 500 && exact > 1000, "{fast} {exact}");
    }

    #[test]
    fn f64_round_trip_and_directed_rounding() {
        for x in [
            0.0,
            -0.0,
            1.0,
            0.1,
            -3.75,
            f64::MAX,
            -f64::MAX,
            f64::MIN_POSITIVE,
            f64::from_bits(1),
            -f64::from_bits(7),
            1e300,
            1e-300,
        ] {
            let e = Exact::of(x);
            assert_eq!(e.round_down(), x);
            assert_eq!(e.round_up(), x);
            assert_eq!(e.cmp_f64(x), Some(Ordering::Equal));
            assert_eq!(e.to_f64(), x);
        }
        // 1/3: the two neighbours
        let t = Exact::of(1.0) / Exact::of(3.0);
        let (d, u) = (t.round_down(), t.round_up());
        assert_eq!(u, d.next_up());
        assert!(t.gt_f64(d) && !t.gt_f64(u));
        assert!(d <= 1.0 / 3.0 && 1.0 / 3.0 <= u);
        // beyond the range, and below the smallest subnormal
        let big = Exact::of(f64::MAX) * Exact::of(2.0);
        assert_eq!(
            (big.round_down(), big.round_up()),
            (f64::MAX, f64::INFINITY)
        );
        let tiny = Exact::of(f64::from_bits(1)) / Exact::of(3.0);
        assert_eq!(
            (tiny.round_down(), tiny.round_up()),
            (0.0, f64::from_bits(1))
        );
        let ntiny = -tiny;
        assert_eq!(
            (ntiny.round_down(), ntiny.round_up()),
            (-f64::from_bits(1), 0.0)
        );
        // division by zero is undefined, never a panic, and certifies nothing
        let z = Exact::of(1.0) / Exact::of(0.0);
        assert!(!z.gt_f64(f64::NEG_INFINITY));
        assert_eq!(z.to_interval(), Interval::ENTIRE);
        assert!(!(z + Exact::of(1.0)).is_exact_zero());
    }

    /// The dyadic fast paths and the general operations (odd-part gcds only) give exactly
    /// num-rational's reduced results, numerator and denominator; a rational with a negative
    /// denominator is taken with its sign moved up.
    #[test]
    fn arithmetic_matches_num_rational_in_lowest_terms() {
        use rand::{Rng, SeedableRng};
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let pick = |r: &mut rand_chacha::ChaCha8Rng| -> f64 {
            match r.random_range(0..5) {
                0 => 0.0,
                1 => {
                    2f64.powi(r.random_range(-60..60)) * if r.random_bool(0.5) { -1.0 } else { 1.0 }
                }
                2 => r.random_range(-8..8) as f64,
                3 => r.random_range(-1e3..1e3),
                _ => r.random_range(-1.0..1.0) * 2f64.powi(r.random_range(-200..200)),
            }
        };
        let minus_third =
            Exact::from_ratio(BigRational::new_raw(BigInt::from(1), BigInt::from(-3)));
        let sum = (minus_third + Exact::of(1.0)).0.expect("defined");
        assert_eq!(
            (sum.numer(), sum.denom()),
            (&BigInt::from(2), &BigInt::from(3))
        );
        for _ in 0..3000 {
            let (a, b) = (pick(&mut r), pick(&mut r));
            let (x, y) = (ratio_of_f64(a).unwrap(), ratio_of_f64(b).unwrap());
            // a non-dyadic operand too (thirds), to cover the mixed cases
            let third = BigRational::new(BigInt::from(1), BigInt::from(3));
            let odd = BigRational::new(BigInt::from(-35), BigInt::from(3 * 7 * 11));
            for (x, y) in [
                (x.clone(), y.clone()),
                (x.clone() * &third, y.clone()),
                (x.clone(), y.clone() * &third),
                (x.clone() * &odd, y.clone() * &third),
                (x * &third, y * &odd),
            ] {
                let (ex, ey) = (Exact(Some(x.clone())), Exact(Some(y.clone())));
                // the same value in the same (lowest) terms
                let same = |a: Exact, b: BigRational| {
                    let a = a.0.expect("defined");
                    assert_eq!((a.numer(), a.denom()), (b.numer(), b.denom()));
                };
                same(ex.clone() + ey.clone(), &x + &y);
                same(ex.clone() - ey.clone(), &x - &y);
                same(ex.clone() * ey.clone(), &x * &y);
                if !y.is_zero() {
                    same(ex / ey, &x / &y);
                }
            }
        }
    }

    #[test]
    fn truncation_to_a_dyadic_grid() {
        let t = Exact::of(1.0) / Exact::of(3.0);
        let q = t.truncate_to(0, 10);
        // floor(2^10 / 3) / 2^10 = 341 / 1024
        assert_eq!(q, Exact::of(341.0 / 1024.0));
        let n = (-t).truncate_to(0, 10);
        assert_eq!(n, Exact::of(-342.0 / 1024.0));
        assert_eq!(Exact::of(6.0).truncate_to(3, 1), Exact::of(4.0));
    }

    /// The grid roundings and the truncated Newton point equal the same operations written
    /// with num-rational's reduced arithmetic (value, numerator and denominator), on dyadic and
    /// non-dyadic operands of many magnitudes and on both sides of 0.
    #[test]
    fn grid_roundings_match_reduced_rational_arithmetic() {
        use rand::{Rng, SeedableRng};
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(9);
        let pow = |g: i64| -> BigRational {
            let p = BigRational::from_integer(BigInt::one() << g.unsigned_abs());
            if g >= 0 {
                p
            } else {
                p.recip()
            }
        };
        let floor_ref = |q: &BigRational, g: i64| (q / pow(g)).floor() * pow(g);
        let ceil_ref = |q: &BigRational, g: i64| (q / pow(g)).ceil() * pow(g);
        let same = |a: Exact, b: BigRational| {
            let a = a.0.expect("defined");
            assert_eq!((a.numer(), a.denom()), (b.numer(), b.denom()));
        };
        for _ in 0..2000 {
            let mut pick = || -> BigRational {
                let x = r.random_range(-1.0..1.0) * 2f64.powi(r.random_range(-300..300));
                let q = ratio_of_f64(x).unwrap();
                match r.random_range(0..3) {
                    0 => q,
                    1 => {
                        q / BigRational::from_integer(BigInt::from(r.random_range(1..1000) * 2 + 1))
                    }
                    _ => q * BigRational::new(BigInt::from(7), BigInt::from(-45)),
                }
            };
            let (u, g1, g2) = (pick(), pick(), pick());
            let (scale, bits) = (r.random_range(-400..400), r.random_range(0..300u32));
            let g = scale as i64 - bits as i64;
            let eu = Exact(Some(u.clone()));
            same(eu.truncate_to(scale, bits), floor_ref(&u, g));
            same(eu.ceil_to(g), ceil_ref(&u, g));
            if !g2.is_zero() {
                let n = Exact::newton_truncated(
                    &eu,
                    &Exact(Some(g1.clone())),
                    &Exact(Some(g2.clone())),
                    scale,
                    bits,
                );
                same(n, floor_ref(&(&u - &g1 / &g2), g));
            }
        }
        // a zero divisor is undefined
        let z = Exact::of(0.0);
        assert!(Exact::newton_truncated(&z, &z, &z, 0, 10).value().is_none());
    }
}
