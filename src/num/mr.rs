//! [`Mr`]: a rigorous midpoint-radius interval on plain f64 (centre `c`, radius `r`: the set
//! `[c - r, c + r]`), the fast verified number type for O(p^2) kernels at high degree.
//!
//! inari's `Interval` is exact to the last bit at the ends but every operation is an
//! out-of-line call; `Ddi` is double-word. Midpoint-radius arithmetic with a running rounding
//! bound (Rump, "Fast and parallel interval arithmetic", BIT 39(3), 1999, sec. 3; the radius
//! formulas below) costs a few inlined flops per operation, and with the convex-form
//! [`Scalar::lerp`] corner cutting (de Boor, Boehm knot insertion, de Casteljau) does not grow
//! the radius: a degree-40 Bézier extraction is ~20x faster than with `Interval` and its
//! points are a few hundred ulps wide (what the Newton strategy's span pre-tests need; final
//! values come from `TightEval`).
//!
//! # Soundness
//!
//! For `z = x op y`: for all reals `a` in x and `b` in y, `a op b` lies in z. The centre is the
//! f64 result; its rounding error is at most `u |exact| + eta <= U1 |fl| + eta` (u = 2^-53,
//! eta = 2^-1075 for products/quotients only, `U1 = u (1 + 2^-50)`; see ddi.rs), and the
//! propagated radii are the textbook midpoint-radius bounds. Every radius formula is a sum of
//! nonnegative f64 terms and products of two of them, rounded up by `up` (Lemma B of ddi.rs).
//! Anything non-finite (overflow, NaN, division by a set that may contain 0) gives
//! [`Mr::ENTIRE`].

use crate::num::ddi::{dist_up, two_sum, up, Ddi, ETA16, U1};
use crate::num::Scalar;
use inari::Interval;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// Midpoint-radius enclosure `[c - r, c + r]` (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mr {
    c: f64,
    r: f64,
}

impl Mr {
    /// The set of all reals.
    pub const ENTIRE: Mr = Mr {
        c: 0.0,
        r: f64::INFINITY,
    };

    /// Build from parts; anything non-finite (or a negative/NaN radius) gives ENTIRE.
    #[inline(always)]
    fn checked(c: f64, r: f64) -> Mr {
        if c.is_finite() && (0.0..f64::INFINITY).contains(&r) {
            Mr { c, r }
        } else {
            Mr::ENTIRE
        }
    }

    /// An enclosure of the real interval [lo, hi] (finite lo <= hi; otherwise ENTIRE): the
    /// centre c = RN(lo/2 + hi/2) kept in [lo, hi] (halves first: no overflow), the radius an
    /// upper bound of max(c - lo, hi - c) ([`dist_up`]), so [c - r, c + r] contains [lo, hi].
    pub fn from_bounds(lo: f64, hi: f64) -> Mr {
        if lo.partial_cmp(&hi).is_none_or(|o| o.is_gt()) {
            return Mr::ENTIRE; // (also for a NaN end)
        }
        let c = (0.5 * lo + 0.5 * hi).clamp(lo, hi);
        Mr::checked(c, dist_up(c, lo).max(dist_up(hi, c)))
    }

    /// `(1 - A) lo + A hi` for every A in the parameter set [t - ra, t + ra] with centre t in
    /// [0, 1] (corner cutting at an f64 parameter, ra = 0, or at an enclosed knot ratio, ra
    /// tiny: de Casteljau, knot insertion), in about a dozen flops.
    ///
    /// Soundness: let X in [x - rx, x + rx], Y in [y - ry, y + ry] (x = lo.c, y = hi.c) and
    /// |A - t| <= ra. Then (1 - A) X + A Y = (1 - t) X + t Y + (A - t)(Y - X), where
    /// (1 - t) X + t Y = (1 - t) x + t y + e with |e| <= (1 - t) rx + t ry (t in [0, 1]) and
    /// |(A - t)(Y - X)| <= ra (|x| + |y| + rx + ry). The centre is c = fl(t d + x) (one FMA)
    /// with d = fl(y - x): |d - (y - x)| <= u |y - x| <= U1 |d| (a difference has no
    /// underflow error) and |c - (t d + x)| <= U1 |c| + eta, so
    /// |c - ((1 - t) x + t y)| <= U1 |c| + t U1 |d| + eta. The radius bound
    /// T = U1 (|c| + t |d|) + fl(1 - t) rx + t ry + ra (|x| + |y| + rx + ry) + ETA16
    /// (ETA16 >= eta) is evaluated with nonnegative intermediates only; fl(1 - t) >=
    /// (1 - t)(1 - u) is one more rounding by a factor at most (1 - u) of a nonnegative exact
    /// value, which is what Lemma B counts (at most 15 roundings on a path, here 7), so `up`
    /// bounds it from above. Exact cases stay exact: for an exact parameter (ra = 0) t = 0 or 1
    /// returns an end and equal ends return that set (a convex combination of two points of one
    /// interval lies in it); equal exact ends (rx = 0) return that point for any A; and exact
    /// data whose result is exact stays exact ([`exact_lerp`]). Anything non-finite gives
    /// ENTIRE (`checked`). The radius does not grow along a corner-cutting chain beyond the
    /// convex combination of the radii and the few rounding units added here.
    #[inline(always)]
    fn lerp_narrow(t: f64, ra: f64, lo: &Mr, hi: &Mr) -> Mr {
        if lo == hi && (ra == 0.0 || lo.r == 0.0) {
            return *lo;
        }
        if ra == 0.0 {
            if t == 0.0 {
                return *lo;
            }
            if t == 1.0 {
                return *hi;
            }
        }
        let d = hi.c - lo.c;
        let c = t.mul_add(d, lo.c);
        if ra == 0.0 && lo.r == 0.0 && hi.r == 0.0 && exact_lerp(t, lo.c, hi.c, d, c) {
            return Mr::checked(c, 0.0);
        }
        let r = U1 * (c.abs() + t * d.abs())
            + (1.0 - t) * lo.r
            + t * hi.r
            + ra * (lo.c.abs() + hi.c.abs() + lo.r + hi.r)
            + ETA16;
        Mr::checked(c, up(r))
    }

    /// An enclosure of the set of a [`Ddi`] (centre hi + lo, radius rad): centre hi, radius
    /// up(|lo| + rad) >= |lo| + rad (Lemma B of `ddi.rs`: a sum of nonnegative f64), so
    /// [hi - r, hi + r] contains [hi + lo - rad, hi + lo + rad]. A single f64 (lo = rad = 0)
    /// stays exact; ENTIRE stays ENTIRE.
    pub fn from_ddi(x: Ddi) -> Mr {
        let (hi, lo, rad) = x.parts();
        if lo == 0.0 && rad == 0.0 {
            return Mr::checked(hi, 0.0);
        }
        Mr::checked(hi, up(lo.abs() + rad))
    }

    /// The set [c - r, c + r] for a centre and a radius that a caller proved (an a-priori
    /// bound); anything non-finite, or a negative or NaN radius, gives [`Mr::ENTIRE`].
    #[inline]
    pub(crate) fn from_centre_radius(c: f64, r: f64) -> Mr {
        Mr::checked(c, r)
    }

    /// An enclosure of the rational num / den (integers, den > 0; `None` for den = 0): the
    /// quotient q = fl(fl(num) / fl(den)) of the integers rounded to nearest (Rust's integer
    /// to float conversion). Both below 2^53 (exact as f64): q is the correctly rounded
    /// quotient, |q - num/den| <= u |num/den| <= U1 |q| (no underflow: q >= 1/den >= 2^-53),
    /// and exact (radius 0) where the FMA residual num - q den is 0. Otherwise each conversion
    /// and the division round once: |q - num/den| <= ((1 + u)^2 / (1 - u) - 1) |num/den|
    /// <= 4 U1 |q| (as in the f64 knot ratio of the `Scalar` impl below; num, den < 2^128, so
    /// no overflow and q >= 2^-128 no underflow). The radius is rounded up (Lemma B).
    pub(crate) fn ratio(num: u128, den: u128) -> Option<Mr> {
        if den == 0 {
            return None;
        }
        if num == 0 {
            return Some(Mr::checked(0.0, 0.0));
        }
        const EXACT: u128 = 1 << 53;
        let (n, d) = (num as f64, den as f64);
        let q = n / d;
        if num <= EXACT && den <= EXACT {
            if (-q).mul_add(d, n) == 0.0 {
                return Some(Mr::checked(q, 0.0));
            }
            return Some(Mr::checked(q, up(U1 * q)));
        }
        Some(Mr::checked(q, up(4.0 * U1 * q)))
    }

    /// Centre.
    #[inline]
    pub fn mid(&self) -> f64 {
        self.c
    }

    /// Radius bound.
    #[inline]
    pub fn rad(&self) -> f64 {
        self.r
    }

    /// `[c - r, c + r]` rounded outward, as plain f64 ends (those of [`Scalar::to_interval`],
    /// without building an inari interval): fl(c - r) is within half an ulp of c - r, so its
    /// predecessor is below it (and symmetrically above); exact for r = 0; (-inf, inf) for
    /// ENTIRE.
    #[inline]
    pub fn bounds(&self) -> (f64, f64) {
        if self.r == 0.0 {
            return (self.c, self.c);
        }
        ((self.c - self.r).next_down(), (self.c + self.r).next_up())
    }

    /// An upper bound of |x| for every x in the set: the larger magnitude of its ends
    /// ([`Mr::bounds`]); +inf for ENTIRE.
    #[inline]
    pub fn mag(&self) -> f64 {
        let (lo, hi) = self.bounds();
        (-lo).max(hi)
    }
}

/// Whether c = fl(t d + x) with d = fl(y - x) is exactly x + t (y - x) (exact data stays
/// exact along corner cutting, as with the exactness tests of `Mr`'s `+` and `*`): d is exact
/// when its TwoSum error term is 0; then t d is exact when its TwoProd error term is 0 and the
/// product cannot have lost bits to underflow (|fl(t d)| >= 1e-290 > 2^-964, or d = 0: a
/// product that underflows to 0 is not exact); then c is exact
/// when the TwoSum error of fl(t d) + x is 0 (and then c equals the FMA's result).
#[inline]
fn exact_lerp(t: f64, x: f64, y: f64, d: f64, c: f64) -> bool {
    let two_sum_exact = |a: f64, b: f64, s: f64| {
        let bb = s - a;
        (a - (s - bb)) + (b - bb) == 0.0
    };
    if !two_sum_exact(y, -x, d) {
        return false;
    }
    let p = t * d;
    if t.mul_add(d, -p) != 0.0 || (d != 0.0 && p.abs() < 1e-290) {
        return false;
    }
    let s = p + x;
    s == c && two_sum_exact(p, x, s)
}

impl Add for Mr {
    type Output = Mr;
    /// |fl(s) - s| <= U1 |fl(s)| (sums have no underflow error), plus both radii: Lemma B.
    #[inline]
    fn add(self, y: Mr) -> Mr {
        let c = self.c + y.c;
        if self.r == 0.0 && y.r == 0.0 {
            // exact when the TwoSum error term is 0 (keeps exact data exact)
            let bb = c - self.c;
            if (self.c - (c - bb)) + (y.c - bb) == 0.0 {
                return Mr::checked(c, 0.0);
            }
        }
        Mr::checked(c, up(self.r + y.r + U1 * c.abs()))
    }
}

impl Sub for Mr {
    type Output = Mr;
    #[inline]
    fn sub(self, y: Mr) -> Mr {
        self + (-y)
    }
}

impl Neg for Mr {
    type Output = Mr;
    /// Exact.
    #[inline]
    fn neg(self) -> Mr {
        Mr {
            c: -self.c,
            r: self.r,
        }
    }
}

impl Mul for Mr {
    type Output = Mr;
    /// For a = x.c + da, b = y.c + db (|da| <= x.r, |db| <= y.r):
    /// |ab - x.c y.c| <= |x.c| y.r + |y.c| x.r + x.r y.r, and |x.c y.c - fl(x.c y.c)| <=
    /// U1 |fl| + eta (ETA16 >= eta). Five terms, products of two f64: Lemma B.
    #[inline]
    fn mul(self, y: Mr) -> Mr {
        let c = self.c * y.c;
        if self.r == 0.0 && y.r == 0.0 && self.c.mul_add(y.c, -c) == 0.0 && c.abs() >= 1e-290 {
            // TwoProd error term 0 and no underflow: exact
            return Mr::checked(c, 0.0);
        }
        let r = self.c.abs() * y.r + y.c.abs() * self.r + self.r * y.r + U1 * c.abs() + ETA16;
        Mr::checked(c, up(r))
    }
}

impl Div for Mr {
    type Output = Mr;
    /// With ymin <= min |y| over the set (ENTIRE if the set may contain 0) and c = fl(x.c / y.c):
    /// a / b - c = (a - c b) / b and |a - c b| <= |x.c - c y.c| + x.r + |c| y.r. The residual
    /// e = fma(-c, y.c, x.c) is the exact residual E rounded once: |E| <= |e| + U1 |e| + 2 eta.
    /// The numerator bound n (five terms) and the quotient n / ymin are each rounded up by
    /// Lemma B.
    #[inline]
    fn div(self, y: Mr) -> Mr {
        let Some(ymin) = Ddi::abs_lower(Ddi::new(y.c, 0.0, y.r)) else {
            return Mr::ENTIRE;
        };
        let c = self.c / y.c;
        let e = (-c).mul_add(y.c, self.c);
        if self.r == 0.0 && y.r == 0.0 && e == 0.0 && self.c.abs() >= 1e-270 {
            // exact quotient: a non-zero residual is a multiple of ulp(c) ulp(y.c) >= 2^-1003
            // when |x.c| >= 2^-897, so it cannot round to 0
            return Mr::checked(c, 0.0);
        }
        let n = up(e.abs() + U1 * e.abs() + self.r + c.abs() * y.r + ETA16);
        Mr::checked(c, up(n / ymin))
    }
}

impl Scalar for Mr {
    #[inline]
    fn from_f64(x: f64) -> Self {
        Mr::checked(x, 0.0)
    }

    /// (u - a) / (b - a) in plain f64 with an a-priori bound, instead of two `Mr` differences
    /// and an `Mr` quotient (the knot ratios are half the work of a knot insertion at high
    /// degree). With n = u - a and d = b - a (0 < d < 2^1022, `bspline::may_overflow`: no
    /// overflow; else the default, which halves the operands), fl(n) = n (1 + δ1) and fl(d) = d (1 + δ2),
    /// |δi| <= u, exactly so where the result is subnormal (a subtraction's subnormal result is
    /// exact); q = fl(fl(n) / fl(d)) = (fl(n) / fl(d)) (1 + δ3) + η3, |δ3| <= u, |η3| <= 2^-1075
    /// (an underflowing quotient). So |q - n/d| <= |n/d| ((1 + u)^2 / (1 - u) - 1) + η3
    /// <= 3.01 u |n/d| + η3, and |n/d| <= (|q| + η3) / (1 - 3.01 u), hence
    /// |q - n/d| <= 3.02 u |q| + 2 η3 <= 4 U1 |q| + ETA16, rounded up ([`up`], Lemma B of
    /// [`crate::num::ddi`]). Exact (radius 0) where both differences are exact (their TwoSum
    /// errors vanish) and the quotient's FMA residual is 0 with |n| >= 2^-897 (then a nonzero
    /// residual, a multiple of ulp(q) ulp(d), cannot round to 0; as in the `Mr` quotient).
    /// Tested against exact rationals (`knot_ratio_f64_encloses_exact_ratios`).
    #[inline]
    fn knot_ratio_f64(u: f64, a: f64, b: f64) -> Self {
        let ((n, en), (d, ed)) = (two_sum(u, -a), two_sum(b, -a));
        // (u in [a, b], so |n| <= d: no overflow once d is below 2^1022)
        if d.is_nan() || d <= 0.0 || crate::spline::bspline::may_overflow(a, b) {
            return crate::spline::bspline::knot_ratio(&Mr::from_f64(u), a, b);
        }
        let q = n / d;
        if en == 0.0 && ed == 0.0 && (-q).mul_add(d, n) == 0.0 && (n == 0.0 || n.abs() >= 1e-270) {
            return Mr::checked(q, 0.0);
        }
        Mr::checked(q, up(4.0 * U1 * q.abs() + ETA16))
    }

    /// `lo + a (hi - lo)` as whichever of the thesis form `a (hi - lo) + lo` and the convex form
    /// `(1 - a) lo + a hi` has the smaller radius (both enclose it; see the `Ddi` impl: the
    /// convex form does not grow the radii along a corner-cutting chain).
    /// For a point-like `a` (radius <= 2^-40 |a|: corner cutting at an f64 parameter, the
    /// common case) only the convex form is computed; its radius is then never more than a
    /// few rounding units above the thesis form's.
    // (always: the corner-cutting loops of de Casteljau and knot insertion are its hot callers;
    // an out-of-line call there cost the degree-10 span a third more time)
    #[inline(always)]
    fn lerp(a: &Self, lo: &Self, hi: &Self) -> Self {
        // (a point-like parameter, radius <= 2^-40 |a|, with its centre in [0, 1]: the
        // convex form in a dozen flops; otherwise both forms as below)
        if a.r <= a.c.abs() * (1.0 / 1_099_511_627_776.0) && (0.0..=1.0).contains(&a.c) {
            return Mr::lerp_narrow(a.c, a.r, lo, hi);
        }
        let convex = (Mr::from_f64(1.0) - *a) * *lo + *a * *hi;
        if a.r <= a.c.abs() * (1.0 / 1_099_511_627_776.0) {
            return convex;
        }
        let thesis = *a * (*hi - *lo) + *lo;
        if convex.r <= thesis.r {
            convex
        } else {
            thesis
        }
    }

    /// `[c - r, c + r]` rounded outward: fl(c - r) is within half an ulp of c - r, so its
    /// predecessor is below it (and symmetrically above); exact for r = 0.
    /// (the ends of [`Mr::bounds`])
    #[inline]
    fn to_interval(&self) -> Interval {
        if self.r == f64::INFINITY {
            return Interval::ENTIRE;
        }
        Interval::try_from(self.bounds()).unwrap_or(Interval::ENTIRE)
    }

    #[inline]
    fn to_f64(&self) -> f64 {
        self.c
    }

    #[inline]
    fn is_exact_zero(&self) -> bool {
        self.c == 0.0 && self.r == 0.0
    }
}

#[cfg(test)]
mod tests {
    /// `Mr::from_ddi` contains the set of the `Ddi` (checked exactly, by the signs of exact
    /// sums), and keeps single doubles exact and ENTIRE entire. (A radius without |lo| fails
    /// it.)
    #[test]
    fn from_ddi_contains_the_set() {
        use super::Mr;
        use crate::num::ddi::Ddi;
        use crate::num::Scalar;
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(4);
        for _ in 0..20_000 {
            let x = rng.random_range(-1e3..1e3) * 10f64.powi(rng.random_range(-300..300));
            let y = rng.random_range(-1.0..1.0);
            // a double-double with a low part and a radius (a product or a quotient of doubles)
            let d = match rng.random_range(0..3) {
                0 => Ddi::exact(x) * Ddi::exact(y),
                1 => Ddi::exact(x) / Ddi::exact(3.0),
                // (an exact double-word: radius 0, the low part alone must be covered)
                _ => Ddi::exact(x) + Ddi::exact(y * 1e-20 * x),
            };
            let m = Mr::from_ddi(d);
            // exactly: [hi + lo - rad, hi + lo + rad] within [c - r, c + r], i.e.
            // |hi + lo - c| + rad <= r (signs of exact sums)
            let (hi, lo, rad) = d.parts();
            let (c, r) = (m.mid(), m.rad());
            for s in [1.0, -1.0] {
                let excess = crate::num::ddi::sum_sign(&[s * hi, s * lo, -s * c, rad, -r]);
                assert_ne!(excess, Some(std::cmp::Ordering::Greater), "{d:?} {m:?}");
            }
        }
        assert_eq!(Mr::from_ddi(Ddi::exact(0.1)), Mr::from_f64(0.1));
        assert_eq!(Mr::from_ddi(Ddi::ENTIRE).rad(), f64::INFINITY);
    }

    /// `Mr::knot_ratio_f64` contains the exact (u - a) / (b - a) (rationals) for knots of every
    /// magnitude (clustered, subnormal, near 2^1022, equal to u) and is about an ulp wide; a
    /// bound of 1 ulp instead of 4 fails it.
    #[test]
    fn knot_ratio_f64_encloses_exact_ratios() {
        use super::Mr;
        use crate::num::exact::Exact;
        use crate::num::Scalar;
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let mut inexact = 0;
        for k in 0..40_000 {
            let scale = [1.0, 1e-300, 1e300, 4e-320, 1.0e-12, 3e307][k % 6];
            let mut v: Vec<f64> = (0..3)
                .map(|_| rng.random_range(-1.0..1.0) * scale + [0.0, 1.0, 0.1][k % 3])
                .collect();
            if k % 7 == 0 {
                v[2] = v[0]; // u at a knot
            }
            v.sort_by(f64::total_cmp);
            let (a, u, b) = if k % 2 == 0 {
                (v[0], v[2], v[1])
            } else {
                (v[0], v[1], v[2])
            };
            let (a, u, b) = (a, u.clamp(a, b.max(a)), b.max(a));
            if a >= b || !(b - a).is_finite() {
                continue;
            }
            let z = Mr::knot_ratio_f64(u, a, b);
            let ex = (Exact::of(u) - Exact::of(a)) / (Exact::of(b) - Exact::of(a));
            // exactly inside [c - r, c + r] (not only its outward-rounded interval)
            let off = ex - Exact::of(z.c);
            assert_ne!(
                off.cmp_f64(z.r),
                Some(std::cmp::Ordering::Greater),
                "{u} {a} {b}"
            );
            assert_ne!(
                off.cmp_f64(-z.r),
                Some(std::cmp::Ordering::Less),
                "{u} {a} {b}"
            );
            assert!(off.cmp_f64(0.0).is_some(), "{u} {a} {b}: undefined");
            assert!(
                z.r <= 8.0 * f64::EPSILON * z.c.abs() + 1e-300,
                "{u} {a} {b}: wide"
            );
            inexact += (z.r > 0.0) as usize;
        }
        assert!(inexact > 10_000, "only {inexact} inexact ratios checked");
    }

    /// `Mr::ratio` encloses num / den exactly (rationals), on random integers of every size
    /// up to u128 (both below 2^53: one rounding; above: three), quotients that are exact
    /// (radius 0 only then), powers of two and neighbours of 2^53; den = 0 gives `None`.
    #[test]
    fn ratio_encloses_integer_quotients() {
        use super::Mr;
        use crate::num::exact::Exact;
        use num_bigint::BigInt;
        use num_rational::BigRational;
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(13);
        let (mut exact, mut big) = (0, 0);
        assert!(Mr::ratio(5, 0).is_none());
        for k in 0..20_000 {
            let bits = |r: &mut rand_chacha::ChaCha8Rng| r.random_range(1..=127u32);
            let int = |r: &mut rand_chacha::ChaCha8Rng| -> u128 {
                let b = bits(r);
                r.random::<u128>() >> (128 - b)
            };
            let (mut num, mut den) = (int(&mut rng), int(&mut rng).max(1));
            match k % 5 {
                0 => num = den.saturating_mul(rng.random_range(1..1000)),
                1 => (num, den) = ((1 << 53) + rng.random_range(0..3u128), (1 << 53) - 1),
                2 => den = 1 << rng.random_range(0..100),
                _ => {}
            }
            let z = Mr::ratio(num, den).unwrap();
            let want = Exact::from_ratio(BigRational::new(BigInt::from(num), BigInt::from(den)));
            let off = want - Exact::of(z.c);
            assert_ne!(
                off.cmp_f64(z.r),
                Some(std::cmp::Ordering::Greater),
                "{num} / {den}"
            );
            assert_ne!(
                off.cmp_f64(-z.r),
                Some(std::cmp::Ordering::Less),
                "{num} / {den}"
            );
            if z.r == 0.0 {
                assert_eq!(off.cmp_f64(0.0), Some(std::cmp::Ordering::Equal));
                exact += 1;
            }
            big += usize::from(num > 1 << 53 || den > 1 << 53);
            assert!(z.r <= 4.01 * crate::num::ulp(z.c), "{num} / {den}: wide");
        }
        assert!(exact > 2000 && big > 5000, "{exact} {big}");
    }

    #[test]
    fn from_bounds_encloses_the_range() {
        let cases = [
            (0.0, 1.0),
            (0.1, 0.30000000000000004),
            (-f64::MAX, f64::MAX),
            (f64::from_bits(1), f64::from_bits(3)),
            (1e300, 1e300),
            (-2.5, -2.5),
            (0.49999999999999994, 0.5),
        ];
        for (a, b) in cases {
            let x = Mr::from_bounds(a, b).to_interval();
            assert!(
                x.inf() <= a && b <= x.sup(),
                "[{a}, {b}] -> [{}, {}]",
                x.inf(),
                x.sup()
            );
        }
        assert_eq!(Mr::from_bounds(1.0, 0.0), Mr::ENTIRE);
        assert_eq!(Mr::from_bounds(f64::NAN, 0.0), Mr::ENTIRE);
    }

    use super::*;
    use crate::spline::bspline::HSpline;
    use crate::spline::curve::NurbsCurve;
    use rand::{Rng, SeedableRng};

    #[test]
    fn operations_enclose_sampled_reals() {
        // Compare against inari on the same sets: the Mr result must contain inari's hull of
        // the exact results of sampled operands (sampled as f64, exact in both).
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        for _ in 0..20_000 {
            let e = |rng: &mut rand_chacha::ChaCha8Rng| 10f64.powi(rng.random_range(-30..30));
            let x = Mr::checked(rng.random_range(-1.0..1.0) * e(&mut rng), 0.0);
            let y = Mr::checked(rng.random_range(-1.0..1.0) * e(&mut rng), 0.0);
            let (xr, yr) = (rng.random_range(0.0..1e-3), rng.random_range(0.0..1e-3));
            let x = Mr::checked(x.c, xr * x.c.abs());
            let y = Mr::checked(y.c, yr * y.c.abs());
            for t in [-1.0, -0.3, 0.0, 0.7, 1.0] {
                let a = iv(x.c + t * x.r);
                let b = iv(y.c - t * y.r);
                for (z, w) in [
                    (x + y, a + b),
                    (x - y, a - b),
                    (x * y, a * b),
                    (x / y, a / b),
                ] {
                    if !w.is_empty() && !w.is_entire() && x.c + t * x.r >= x.c - x.r {
                        let zi = z.to_interval();
                        // a, b are in x, y only if the sampled points are (rounding of c + t r)
                        let inside = |v: f64, m: Mr| (v - m.c).abs() <= m.r;
                        if inside(a.inf(), x) && inside(b.inf(), y) {
                            assert!(zi.inf() <= w.inf() && w.sup() <= zi.sup(), "{z:?} {w:?}");
                        }
                    }
                }
            }
        }
    }

    fn iv(x: f64) -> Interval {
        Interval::try_from((x, x)).unwrap()
    }

    #[test]
    fn degree_40_bezier_extraction_stays_narrow_and_encloses() {
        let (p, n) = (40, 60);
        let inner = n - p - 1;
        let mut kn = vec![0.0; p + 1];
        kn.extend((1..=inner).map(|i| i as f64 / (inner + 1) as f64));
        kn.extend(vec![1.0; p + 1]);
        let pts = (0..n).map(|i| vec![(i as f64 * 0.37).sin()]).collect();
        let w = (0..n).map(|i| 1.0 + 0.5 * (i as f64).sin()).collect();
        let c = NurbsCurve::new(p, kn, pts, Some(w)).unwrap();
        let hm = HSpline::<Mr>::from_curve(&c);
        let hi = HSpline::<Interval>::from_curve(&c);
        for k in p..n {
            let (sm, si) = (hm.bezier_segment(k), hi.bezier_segment(k));
            for (m, i) in sm.pts.iter().zip(&si.pts) {
                // both enclose the exact point: they must overlap; and Mr stays narrow
                assert!(!m.to_interval().intersection(*i).is_empty(), "{m:?} {i:?}");
                assert!(m.rad() <= 1e-12 * m.mid().abs().max(1.0), "{m:?}");
            }
        }
    }

    #[test]
    fn point_lerp_encloses_exact_convex_combinations() {
        // (1 - t) X + t Y in exact rationals at the corners X = x +- rx, Y = y +- ry (a linear
        // function of X, Y: its extremes over the box are at corners) must lie in the result.
        use crate::num::exact::Exact;
        use std::cmp::Ordering;
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        let mags = [1e-310, 1e-300, 1e-20, 1.0, 1e20, 1e300, 8e307];
        for k in 0..20_000 {
            let m = |rng: &mut rand_chacha::ChaCha8Rng| mags[rng.random_range(0..mags.len())];
            let x = rng.random_range(-1.0..1.0) * m(&mut rng);
            let y = if k % 5 == 0 {
                x * (1.0 + rng.random_range(-1e-15..1e-15))
            } else {
                rng.random_range(-1.0..1.0) * m(&mut rng)
            };
            let rad = |rng: &mut rand_chacha::ChaCha8Rng, v: f64| match rng.random_range(0..3) {
                0 => 0.0,
                1 => f64::from_bits(rng.random_range(1..1000)),
                _ => v.abs() * rng.random_range(0.0..1e-10),
            };
            let (rx, ry) = (rad(&mut rng, x), rad(&mut rng, y));
            let t = match k % 4 {
                0 => rng.random_range(0.0..1.0),
                1 => rng.random_range(0.0..1e-300),
                2 => 1.0 - rng.random_range(0.0..1e-15),
                _ => [0.0, 1.0, 0.5, 0.25][rng.random_range(0..4)],
            };
            let (lo, hi) = (Mr::checked(x, rx), Mr::checked(y, ry));
            // an exact parameter, or one enclosed with a tiny radius (a knot ratio)
            let ra = if k % 3 == 0 { t * 1e-16 } else { 0.0 };
            let a = Mr::checked(t, ra);
            let z = <Mr as Scalar>::lerp(&a, &lo, &hi);
            if x == y && rx == 0.0 && ry == 0.0 {
                assert_eq!(z, lo, "equal exact ends are returned for any parameter");
            }
            if z.r == f64::INFINITY {
                continue;
            }
            for st in [-1.0, 1.0] {
                let et = Exact::of(t) + Exact::of(st) * Exact::of(ra);
                for sx in [-1.0, 1.0] {
                    for sy in [-1.0, 1.0] {
                        let xe = Exact::of(x) + Exact::of(sx) * Exact::of(rx);
                        let ye = Exact::of(y) + Exact::of(sy) * Exact::of(ry);
                        let v = (Exact::of(1.0) - et.clone()) * xe + et.clone() * ye;
                        let dev = v - Exact::of(z.c);
                        let ok = (dev.clone() - Exact::of(z.r)).signum() != Some(Ordering::Greater)
                            && (dev + Exact::of(z.r)).signum() != Some(Ordering::Less);
                        assert!(ok, "lerp({t} +- {ra}, {lo:?}, {hi:?}) = {z:?}");
                    }
                }
            }
        }
    }

    #[test]
    fn exact_corner_cuts_stay_exact() {
        let m = Mr::from_f64;
        let cut = |t: f64, a: f64, b: f64| <Mr as Scalar>::lerp(&m(t), &m(a), &m(b));
        // exact results keep radius 0 (t = 0, 1, equal ends, an exact FMA step)
        assert_eq!(cut(0.5, 1.0, 3.0), m(2.0));
        assert_eq!(cut(0.25, 0.0, 1.0), m(0.25));
        assert_eq!(cut(0.0, -7.0, 1e300), m(-7.0));
        assert_eq!(cut(1.0, -7.0, 1e300), m(1e300));
        assert_eq!(cut(0.3, 2.5, 2.5), m(2.5));
        // an inexact one does not, and encloses the exact value
        let z = cut(0.1, 0.0, 1.0 / 3.0);
        assert!(z.rad() > 0.0);
        // a product that underflows to 0 is not exact
        let z = cut(1e-300, 0.0, 1e-300);
        assert!(z.rad() > 0.0 && z.to_interval().contains(0.0));
    }

    /// `Mr::bounds` and `Mr::mag` enclose the set [c - r, c + r] exactly (checked by the
    /// exact error terms of c - r and c + r, TwoSum), are the ends of `to_interval`, keep a
    /// point exact and ENTIRE entire. (Ends without the outward step fail it.)
    #[test]
    fn bounds_and_mag_enclose_the_set() {
        use crate::num::ddi::two_sum;
        use rand::Rng;
        let mut rng = crate::testkit::gen::rng(31);
        for it in 0..100_000 {
            let c = rng.random_range(-1.0..1.0) * 10f64.powi(rng.random_range(-300..300));
            let r = match it % 4 {
                0 => 0.0,
                1 => c.abs() * 10f64.powi(rng.random_range(-17..-12)),
                2 => f64::from_bits(rng.random_range(1..1u64 << 52)),
                _ => rng.random_range(0.0..1.0) * 10f64.powi(rng.random_range(-300..300)),
            };
            let x = Mr::from_centre_radius(c, r);
            let (lo, hi) = x.bounds();
            let (s0, e0) = two_sum(c, -r);
            let (s1, e1) = two_sum(c, r);
            assert!(lo < s0 || (lo == s0 && e0 >= 0.0), "{x:?} {lo}");
            assert!(hi > s1 || (hi == s1 && e1 <= 0.0), "{x:?} {hi}");
            assert!(x.mag() >= -lo && x.mag() >= hi && x.mag() >= c.abs());
            let i = x.to_interval();
            assert_eq!((i.inf(), i.sup()), (lo, hi));
            if r == 0.0 {
                assert_eq!((lo, hi), (c, c));
            }
        }
        assert_eq!(Mr::ENTIRE.bounds(), (f64::NEG_INFINITY, f64::INFINITY));
        assert_eq!(Mr::ENTIRE.mag(), f64::INFINITY);
    }

    #[test]
    fn special_values() {
        let z = Mr::from_f64(0.0);
        assert!((Mr::from_f64(1.0) / z).r == f64::INFINITY);
        assert!((Mr::from_f64(f64::MAX) * Mr::from_f64(2.0)).r == f64::INFINITY);
        assert_eq!(Mr::from_f64(3.0) * Mr::from_f64(0.5), Mr::from_f64(1.5));
        assert_eq!(Mr::from_f64(3.0) / Mr::from_f64(0.5), Mr::from_f64(6.0));
        assert_eq!(Mr::ENTIRE.to_interval(), Interval::ENTIRE);
        let t = (Mr::from_f64(1.0) / Mr::from_f64(3.0)).to_interval();
        assert!(t.inf() <= 1.0 / 3.0 && t.sup() >= 1.0 / 3.0 && t.wid() < 1e-15);
    }
}
