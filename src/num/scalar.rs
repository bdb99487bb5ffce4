//! The crate's own small number trait.
//!
//! Every numeric kernel (basis functions, de Boor, derivative control points, knot insertion,
//! de Casteljau) is written once, generic over [`Scalar`], and instantiated with
//!
//! * `f64` — fast floating-point values (no guarantee),
//! * [`inari::Interval`] — verified enclosures with outward rounding,
//! * `rug::Float` at [`MPFR_PREC`] bits (or more, `with_mpfr_prec`) (feature `mpfr`) — high-precision reference values.
//!
//! We deliberately do not use `num_traits::Float`: intervals are not totally ordered, and the
//! kernels need nothing but the field operations and exact embedding of f64 data.

use inari::Interval;
use std::fmt::Debug;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// Default precision (bits) of the `rug::Float` instance used for reference values; see
/// [`mpfr_prec`] for the precision actually in effect.
pub const MPFR_PREC: u32 = 256;

#[cfg(feature = "mpfr")]
thread_local! {
    static PREC: std::cell::Cell<u32> = const { std::cell::Cell::new(MPFR_PREC) };
}

/// The precision (bits) at which `rug::Float` values are created on this thread:
/// [`MPFR_PREC`] unless raised by [`with_mpfr_prec`] (the reference raises it for
/// ill-conditioned curves, e.g. weight ratios of 1e300, see `reference::working_prec`).
#[cfg(feature = "mpfr")]
pub fn mpfr_prec() -> u32 {
    PREC.with(std::cell::Cell::get)
}

/// Run `f` with `rug::Float` values created at `prec` bits on this thread (restored after,
/// also when `f` panics).
#[cfg(feature = "mpfr")]
pub fn with_mpfr_prec<R>(prec: u32, f: impl FnOnce() -> R) -> R {
    struct Restore(u32);
    impl Drop for Restore {
        fn drop(&mut self) {
            PREC.with(|p| p.set(self.0));
        }
    }
    let _restore = Restore(PREC.with(|p| p.replace(prec)));
    f()
}

/// A number type the NURBS kernels can run on.
///
/// Soundness contract for verified types: every operation returns a value that encloses the
/// exact real result for all reals enclosed by the operands (inari guarantees this with
/// outward rounding), and [`Scalar::from_f64`] embeds an f64 exactly.
pub trait Scalar:
    Clone
    + Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// Whether the corner cuts of [`crate::spline::bezier::de_casteljau_levels`] run in
    /// blocks of four (which compile to vector instructions for f64; for the verified types a
    /// block only moves more data).
    const CUT_BLOCKS: bool = false;
    /// Whether the corner cuts of the span sweep ([`crate::spline::bspline::sweep_spans`]) run
    /// in blocks of four through [`Scalar::lerp4`] (a type whose four-lane form compiles to
    /// vector instructions).
    const SWEEP_BLOCKS: bool = false;
    /// Four corner cuts [`Scalar::lerp`] at once, on four consecutive entries of each operand
    /// (the default: one after the other). Contiguous blocks rather than four references, so
    /// that a vector form loads each operand whole (one bounds check per block).
    #[inline]
    fn lerp4(a: &[Self; 4], lo: &[Self; 4], hi: &[Self; 4]) -> [Self; 4] {
        std::array::from_fn(|l| Self::lerp(&a[l], &lo[l], &hi[l]))
    }
    /// Exact embedding of an f64 value (the curve data are f64 and are taken as exact).
    fn from_f64(x: f64) -> Self;
    /// Additive identity.
    fn zero() -> Self {
        Self::from_f64(0.0)
    }
    /// Multiplicative identity.
    fn one() -> Self {
        Self::from_f64(1.0)
    }
    /// Exact embedding of a small integer (binomial coefficients, degrees).
    fn from_usize(k: usize) -> Self {
        // Integers up to 2^53 are exact in f64; degrees and binomials used here are far below.
        Self::from_f64(k as f64)
    }
    /// The corner-cutting step lo + a (hi - lo) of de Boor, de Casteljau and knot insertion.
    ///
    /// The default is the thesis's form a*(R1 - R2) + R2 (sec. 5.1), which overestimates less
    /// than (1 - a) R2 + a R1 when `a` is a wide interval and the R's are (near) points.
    /// Intervals override this with the intersection of both forms: when the R's are wide and
    /// `a` is narrow, the thesis form grows widths by up to 3x per step (R2 occurs twice)
    /// while the convex form does not, and both forms are enclosures, so their intersection is.
    fn lerp(a: &Self, lo: &Self, hi: &Self) -> Self {
        a.clone() * (hi.clone() - lo.clone()) + lo.clone()
    }
    /// The Horner step `acc * t + c` of [`crate::num::horner`]. The default is a product and a
    /// sum (for f64 no FMA: the values stay those of the plain formula); `Ddi` overrides it with
    /// its fused [`crate::num::Ddi::mul_add`] (one enclosure of the whole step, tighter).
    #[inline]
    fn horner_step(acc: &Self, t: &Self, c: &Self) -> Self {
        acc.clone() * t.clone() + c.clone()
    }
    /// The knot ratio (u - a) / (b - a) of Boehm's knot insertion (NURBS Book A5.1) for an f64
    /// parameter u and knots a < b with u in [a, b]: by default
    /// [`crate::spline::bspline::knot_ratio`] on the embedded u (which halves the operands
    /// where the difference may overflow); `Mr` overrides it with one f64 quotient and its
    /// a-priori error bound.
    #[inline]
    fn knot_ratio_f64(u: f64, a: f64, b: f64) -> Self {
        crate::spline::bspline::knot_ratio(&Self::from_f64(u), a, b)
    }
    /// The Bézier extraction of one span ([`crate::spline::bspline::clamp_span`]) by a faster
    /// route of the type's own, with the same guarantee: `true` if `t` and `q` now hold the
    /// result, `false` (nothing changed) for none. The default has none; `Ddi` computes in
    /// double words and encloses the result with an a-priori bound ([`crate::num::dw`]).
    #[inline]
    fn clamp_span_fast(_p: usize, _h: usize, _t: &mut [f64], _q: &mut [Self]) -> bool {
        false
    }
    /// A faster route for the Bézier points of a block of spans
    /// ([`crate::spline::bspline::sweep_spans`]): `true` if it emitted every span, `false`
    /// (nothing emitted) for none. The default has none; `Ddi` sweeps in double words with
    /// the running bound of [`crate::num::dw`].
    #[inline]
    fn sweep_fast(
        _p: usize,
        _h: usize,
        _knots: &[f64],
        _pts: &[Self],
        _k0: usize,
        _count: usize,
        _emit: &mut dyn FnMut(usize, &[Self]),
    ) -> bool {
        false
    }
    /// An f64 interval that contains the value (outward rounded for `rug::Float`).
    fn to_interval(&self) -> Interval;
    /// A representative f64 (midpoint for intervals, nearest for MPFR).
    fn to_f64(&self) -> f64;
    /// Whether the value is exactly zero (a point interval `[0, 0]` counts, a wider one does not).
    fn is_exact_zero(&self) -> bool;
}

impl Scalar for f64 {
    const CUT_BLOCKS: bool = true;
    #[inline]
    fn from_f64(x: f64) -> Self {
        x
    }
    #[inline]
    fn to_interval(&self) -> Interval {
        Interval::try_from((*self, *self)).unwrap_or(Interval::ENTIRE)
    }
    #[inline]
    fn to_f64(&self) -> f64 {
        *self
    }
    #[inline]
    fn is_exact_zero(&self) -> bool {
        *self == 0.0
    }
}

impl Scalar for Interval {
    #[inline]
    fn lerp(a: &Self, lo: &Self, hi: &Self) -> Self {
        // [thesis form] ∩ [convex form]; both enclose lo + a (hi - lo) for all reals enclosed.
        let thesis = *a * (*hi - *lo) + *lo;
        let convex = (iv::point(1.0) - *a) * *lo + *a * *hi;
        let m = thesis.intersection(convex);
        // Both contain the exact set, so the intersection is non-empty unless an operand is
        // empty or something overflowed to NaN-free ENTIRE; fall back to the thesis form then.
        if m.is_empty() {
            thesis
        } else {
            m
        }
    }
    #[inline]
    fn from_f64(x: f64) -> Self {
        // A finite f64 is a valid singleton; non-finite data never reach the kernels (the curve
        // constructor rejects them), but stay sound anyway: ENTIRE encloses everything.
        Interval::try_from((x, x)).unwrap_or(Interval::ENTIRE)
    }
    #[inline]
    fn to_interval(&self) -> Interval {
        *self
    }
    #[inline]
    fn to_f64(&self) -> f64 {
        self.mid()
    }
    #[inline]
    fn is_exact_zero(&self) -> bool {
        self.inf() == 0.0 && self.sup() == 0.0
    }
}

#[cfg(feature = "mpfr")]
impl Scalar for rug::Float {
    fn from_f64(x: f64) -> Self {
        rug::Float::with_val(mpfr_prec(), x)
    }
    fn from_usize(k: usize) -> Self {
        rug::Float::with_val(mpfr_prec(), k)
    }
    fn to_interval(&self) -> Interval {
        // Round the MPFR value down and up to f64: the pair encloses it.
        let lo = self.to_f64_round(rug::float::Round::Down);
        let hi = self.to_f64_round(rug::float::Round::Up);
        Interval::try_from((lo, hi)).unwrap_or(Interval::ENTIRE)
    }
    fn to_f64(&self) -> f64 {
        rug::Float::to_f64(self)
    }
    fn is_exact_zero(&self) -> bool {
        self.is_zero()
    }
}

/// Helpers on intervals used throughout the verified code.
pub mod iv {
    use inari::Interval;

    /// The singleton [x, x] (ENTIRE for a non-finite x, which keeps every use sound).
    #[inline]
    pub fn point(x: f64) -> Interval {
        Interval::try_from((x, x)).unwrap_or(Interval::ENTIRE)
    }

    /// [a, b] for a <= b (ENTIRE when the pair is not a valid interval).
    #[inline]
    pub fn span(a: f64, b: f64) -> Interval {
        Interval::try_from((a, b)).unwrap_or(Interval::ENTIRE)
    }

    /// x + y with the ends rounded outward exactly as inari's addition (the largest double at
    /// most the exact lower sum, the smallest at least the upper one), without switching the
    /// rounding mode: each end in round to nearest, then moved one step only where TwoSum's
    /// exact error says the rounded sum lies on the wrong side. A sum that overflows (or a
    /// non-finite end) gives ENTIRE. Tested against inari's addition.
    #[inline]
    pub fn add(x: Interval, y: Interval) -> Interval {
        if x.is_empty() || y.is_empty() {
            return Interval::EMPTY;
        }
        let (lo, elo) = crate::num::ddi::two_sum(x.inf(), y.inf());
        let (hi, ehi) = crate::num::ddi::two_sum(x.sup(), y.sup());
        if !(lo.is_finite() && hi.is_finite() && elo.is_finite() && ehi.is_finite()) {
            return Interval::ENTIRE;
        }
        let lo = if elo < 0.0 { lo.next_down() } else { lo };
        let hi = if ehi > 0.0 { hi.next_up() } else { hi };
        span(lo, hi)
    }

    /// An upper bound of a b for a, b >= 0: the product in round to nearest (at most half an
    /// ulp off, also where it underflows) stepped one ulp up; +inf for an overflow or a NaN
    /// (0 inf).
    #[inline]
    pub fn mul_up(a: f64, b: f64) -> f64 {
        step_up(a * b)
    }

    /// One ulp above a round-to-nearest result x (which is within half an ulp of the exact
    /// one, or beyond f64::MAX on its side where it overflowed): an upper bound; +inf for NaN.
    #[inline]
    fn step_up(x: f64) -> f64 {
        if x.is_nan() {
            f64::INFINITY
        } else {
            x.next_up()
        }
    }

    /// An upper bound of a / b for a >= 0 and b > 0 (as [`mul_up`]; +inf for a NaN or b <= 0).
    #[inline]
    pub fn div_up(a: f64, b: f64) -> f64 {
        if b.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return f64::INFINITY;
        }
        step_up(a / b)
    }

    /// An upper bound of a + b for a, b >= 0 (as [`mul_up`]).
    #[inline]
    pub fn add_up(a: f64, b: f64) -> f64 {
        step_up(a + b)
    }

    /// An enclosure of x / w for an interval w > 0 (`w.inf() > 0`; ENTIRE otherwise, and for
    /// an empty x), without switching the rounding mode as inari's division does (a change
    /// of the control register per operation, which showed in the profiles of the span
    /// filters): for w > 0 the quotient is monotone in each argument, so its ends are
    /// quotients of ends (lower: x_lo / w_hi if x_lo >= 0, else x_lo / w_lo; upper: x_hi / w_lo
    /// if x_hi >= 0, else x_hi / w_hi), each computed in round to nearest, which errs by at
    /// most half an ulp (also where it underflows, or overflows to ±inf, which lies beyond
    /// f64::MAX on the same side), and then stepped one ulp outward (`next_down` /
    /// `next_up`): at most one ulp wider than the tightest enclosure. A NaN end (inf / inf,
    /// for unbounded x and w) gives ENTIRE. Tested against inari's division.
    #[inline]
    pub fn div_positive(x: Interval, w: Interval) -> Interval {
        if x.is_empty() || w.is_empty() {
            return Interval::ENTIRE;
        }
        match div_positive_ends((x.inf(), x.sup()), (w.inf(), w.sup())) {
            Some((lo, hi)) => span(lo, hi),
            None => Interval::ENTIRE,
        }
    }

    /// The ends of [`div_positive`] from the operands' ends (xl <= xu, wl <= wu): the
    /// quotients of ends stepped one ulp outward, or `None` (the whole line) unless wl > 0.
    /// Not yet checked to make an interval (a NaN end, inf / inf, is left to the caller).
    #[inline]
    pub fn div_positive_ends((xl, xu): (f64, f64), (wl, wu): (f64, f64)) -> Option<(f64, f64)> {
        if wl.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return None;
        }
        // (the divisors by selects, and the outward steps without branches: the signs of the
        // ends are coin tosses on random data, and this runs for every Bézier point of every
        // span that `newton`'s filter meets)
        let lo = xl / if xl >= 0.0 { wu } else { wl };
        let hi = xu / if xu >= 0.0 { wl } else { wu };
        Some((super::next_down(lo), super::next_up(hi)))
    }
}

/// `x.next_down()` (IEEE nextDown: the largest double below x; NaN and -inf stay, +inf goes to
/// f64::MAX, both zeros to -2^-1074), without a branch on the sign of x: the step in the
/// bits is down for x > 0 and up for x < 0, taken from the sign bit (`neg | 1` is 1 or all
/// ones, so `bits - (neg | 1)` is bits - 1 or bits + 1), the zeros by a select. On random
/// data the sign is a coin toss, and the mispredicted branch of `f64::next_down` cost more
/// than the step (in the lanes' certificate and every `Ddi` rounding). Equal to
/// `f64::next_down` bit for bit (`next_steps_are_the_std_ones`).
#[inline]
pub fn next_down(x: f64) -> f64 {
    // (rare, so a predictable branch)
    if x.is_nan() || x == f64::NEG_INFINITY {
        return x;
    }
    let bits = x.to_bits();
    let neg = ((bits as i64) >> 63) as u64;
    let stepped = bits.wrapping_sub(neg | 1);
    f64::from_bits(if bits << 1 == 0 {
        0x8000_0000_0000_0001
    } else {
        stepped
    })
}

/// `x.next_up()` (IEEE nextUp), without a branch on the sign of x: -[`next_down`](-x)
/// (negation is exact; NaN and +inf stay, -inf goes to -f64::MAX, both zeros to 2^-1074).
#[inline]
pub fn next_up(x: f64) -> f64 {
    -next_down(-x)
}

/// The spacing of f64 numbers just above |x| (the ulp of x, used to report widths and
/// distances "in ulps of a scale"): 2^(e - 52) for a normal |x| with exponent e, 2^-1074 for a
/// zero or subnormal |x|; for non-finite |x| (and f64::MAX) the spacing below f64::MAX.
#[inline]
pub fn ulp(x: f64) -> f64 {
    let s = x.abs();
    if !s.is_finite() || s == f64::MAX {
        return f64::MAX - f64::from_bits(f64::MAX.to_bits() - 1);
    }
    // next float up minus s: exact (Sterbenz) and equal to the spacing above s.
    f64::from_bits(s.to_bits() + 1) - s
}

/// (min, max) of f64 values ((inf, -inf) for none; a NaN is skipped, as by `f64::min`).
pub fn min_max(values: impl IntoIterator<Item = f64>) -> (f64, f64) {
    values
        .into_iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
            (lo.min(x), hi.max(x))
        })
}

#[cfg(test)]
mod tests {
    use super::iv;
    use inari::Interval;
    use rand::{Rng, SeedableRng};

    /// The branch-free steps equal `f64::next_down` / `f64::next_up` bit for bit: zeros,
    /// subnormals, powers of two and their neighbours, the extremes, infinities, NaN and
    /// random bits.
    #[test]
    fn next_steps_are_the_std_ones() {
        use super::{next_down, next_up};
        let mut xs = vec![
            0.0,
            f64::MIN_POSITIVE,
            f64::from_bits(1),
            f64::MAX,
            f64::INFINITY,
            1.0,
            3.0,
        ];
        for k in [-1074, -1073, -1023, -1022, -1, 0, 1, 52, 1023] {
            let p = 2f64.powi(k);
            xs.extend([p, p.next_up(), p.next_down()]);
        }
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(47);
        xs.extend((0..200_000).map(|_| f64::from_bits(r.random::<u64>())));
        for x in xs.iter().flat_map(|&x| [x, -x]) {
            if x.is_nan() {
                assert!(next_down(x).is_nan() && next_up(x).is_nan());
                continue;
            }
            assert_eq!(next_down(x).to_bits(), x.next_down().to_bits(), "{x:e}");
            assert_eq!(next_up(x).to_bits(), x.next_up().to_bits(), "{x:e}");
        }
    }

    /// `iv::div_positive` contains inari's division (the tightest enclosure, by directed
    /// rounding) and is at most one step wider at each end: random intervals of every sign,
    /// magnitudes from subnormal to near f64::MAX (quotients that underflow and overflow),
    /// unbounded ones, and a denominator that is not positive (the whole line).
    #[test]
    fn positive_division_contains_the_directed_one() {
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(31);
        let val = |r: &mut rand_chacha::ChaCha8Rng| -> f64 {
            match r.random_range(0..10) {
                0 => f64::MAX * r.random_range(0.5..1.0),
                1 => f64::from_bits(r.random_range(1..1u64 << 52)),
                2 => 0.0,
                _ => r.random_range(-1.0..1.0) * 2f64.powi(r.random_range(-1074..=1023)),
            }
        };
        let steps = |a: f64, b: f64| a.to_bits().abs_diff(b.to_bits());
        for it in 0..200_000 {
            let (a, b) = (val(&mut r), val(&mut r));
            let x = match it % 13 {
                0 => Interval::ENTIRE,
                1 => iv::span(a.min(b), f64::INFINITY),
                _ => iv::span(a.min(b), a.max(b)),
            };
            let (c, d) = (val(&mut r).abs(), val(&mut r).abs());
            let w = match it % 17 {
                0 => iv::span(c.min(d), f64::INFINITY),
                _ => iv::span(c.min(d), c.max(d)),
            };
            let got = iv::div_positive(x, w);
            if w.inf() <= 0.0 {
                assert_eq!(got, Interval::ENTIRE);
                continue;
            }
            let want = x / w;
            assert!(want.subset(got), "{x:?} / {w:?}: {got:?} misses {want:?}");
            if want.inf().is_finite() && got.inf().is_finite() && got.inf() != 0.0 {
                assert!(
                    steps(got.inf(), want.inf()) <= 1 || got.inf().signum() != want.inf().signum(),
                    "{x:?} / {w:?}"
                );
            }
            if want.sup().is_finite() && got.sup().is_finite() && got.sup() != 0.0 {
                assert!(
                    steps(got.sup(), want.sup()) <= 1 || got.sup().signum() != want.sup().signum(),
                    "{x:?} / {w:?}"
                );
            }
        }
        assert_eq!(
            iv::div_positive(iv::point(1.0), iv::span(-1.0, 1.0)),
            Interval::ENTIRE
        );
        assert_eq!(
            iv::div_positive(Interval::EMPTY, iv::point(1.0)),
            Interval::ENTIRE
        );
        // the sum: exactly inari's where finite; the upper bounds of products, quotients, sums
        for _ in 0..200_000 {
            let (a, b, c, d) = (val(&mut r), val(&mut r), val(&mut r), val(&mut r));
            let (x, y) = (iv::span(a.min(b), a.max(b)), iv::span(c.min(d), c.max(d)));
            let (got, want) = (iv::add(x, y), x + y);
            if want.is_common_interval() {
                assert_eq!(got, want, "{x:?} + {y:?}");
            } else {
                assert!(want.subset(got), "{x:?} + {y:?}");
            }
            let (a, b) = (a.abs(), c.abs());
            for (got, want) in [
                (iv::mul_up(a, b), iv::point(a) * iv::point(b)),
                (iv::add_up(a, b), iv::point(a) + iv::point(b)),
            ] {
                assert!(got >= want.sup(), "{a:e} {b:e}: {got:e} < {:e}", want.sup());
            }
            if b > 0.0 {
                let want = iv::point(a) / iv::point(b);
                assert!(iv::div_up(a, b) >= want.sup(), "{a:e} / {b:e}");
            }
        }
    }
}
