//! [`Dw`]: plain double-word arithmetic (a value `hi + lo`, no error bound carried), for the
//! "float first, prove after" Bézier extraction of [`Ddi`] curves:
//! [`clamp_span_dw`] runs the generic Boehm extraction ([`clamp_span`], NURBS Book A5.1) on
//! double words and then encloses every result with one a-priori error bound, instead of a
//! running bound per operation (the [`Ddi`] arithmetic); about five times cheaper at high degree.
//!
//! # The operations (u = 2^-53, eta = 2^-1075)
//!
//! Values are normalised double words, |lo| <= u |hi| (every result ends with TwoSum). Each f64
//! operation in round to nearest errs by at most u |result| (+ eta for products, quotients and
//! FMAs: underflow; additions are exact in the subnormal range). TwoSum is exact; TwoProd (FMA)
//! is exact up to eta.
//!
//! * **Sum** x + y (SloppyDWPlusDW with a final TwoSum; Joldes, Muller, Popescu, ACM TOMS
//!   44(2), 2017, Alg. 4): (s, e) = TwoSum(xh, yh), t = fl(xl + yl), v = fl(e + t),
//!   z = TwoSum(s, v). Only t and v round: |t - (xl + yl)| <= u (|xl| + |yl|) <= u^2 (|xh| + |yh|);
//!   |e| <= u |s| <= u (|xh| + |yh|) and |t| <= (1 + u) u (|xh| + |yh|), so
//!   |v - (e + t)| <= (2 + u) u^2 (|xh| + |yh|). Error <= 3.01 u^2 (|xh| + |yh|)
//!   <= 3.02 u^2 (|x| + |y|): relative to the operands, not to the (possibly cancelled) sum.
//! * **Product** x y: (p, e) = TwoProd(xh, yh), t = fl(xh yl + fl(xl yh)) (FMA),
//!   v = fl(e + t), z = TwoSum(p, v). Dropped xl yl <= u^2 |xh yh|; fl(xl yh) errs by
//!   <= u^2 |xh yh| + eta; |t| <= 2.01 u |xh yh| + eta and the FMA errs by at most
//!   2.01 u^2 |xh yh| plus 2 eta; |e| <= u |p| + eta, so v errs by <= 3.02 u^2 |xh yh| + eta. With TwoProd's eta:
//!   error <= 7.03 u^2 |xh yh| + 5 eta <= 7.1 u^2 |x| |y| + 5 eta.
//! * **Knot ratio** Q = (u - a) / (b - a) of f64 knots with a < b, u in [a, b]
//!   (`Dw`'s [`Scalar::knot_ratio_f64`]): n = TwoSum(u, -a), d = TwoSum(b, -a) are exact; q1 = fl(nh / dh);
//!   r = fl(nh - q1 dh) (FMA) is exact, the remainder of a correctly rounded quotient
//!   (Boldo and Daumas 2003; needs nh = 0 or |nh| >= 2^-969, guaranteed by the caller's
//!   guard below); R = n - q1 d = r + nl - q1 dl exactly, |R| <= 3.01 u |nh|;
//!   r2 = fl(fma(-q1, dl, fl(r + nl))) errs by <= 5.1 u^2 |nh| + eta; q2 = fl(r2 / dh) errs by
//!   <= u |q2| + eta; (qh, ql) = TwoSum(q1, q2). Then Q - q1 - q2 = (R/d - R/dh) + (R - r2)/dh
//!   + (r2/dh - q2), with |R/d - R/dh| <= u |R| / |d|: altogether <= 11.2 u^2 |Q| (1 + 2u)
//!   + eta (1 + 1/|dh|) <= 12 u^2 for Q <= 1 and |dh| >= 2^-900 (the guard).
//!
//! # The extraction's bound ([`clamp_span_dw`])
//!
//! Every Boehm step is the corner cut z = lo + α (hi - lo) ([`Dw`]'s [`Scalar::lerp`], the
//! thesis form) with an exact ratio α in [0, 1], computed as d = hi - lo, m = α̂ d, z = lo + m.
//! With S = |lo| + |hi| (the computed operands): d errs by <= 3.02 u^2 S (|d| <= 1.01 S), the
//! product by <= 7.1 u^2 |α̂| |d| + 5 eta <= 7.2 u^2 S + 5 eta, the sum by
//! <= 3.02 u^2 (|lo| + |m|) <= 6.1 u^2 S, α̂ d's error in d by <= 3.1 u^2 S, and the ratio's
//! error moves the cut by <= 12 u^2 S: a new error of at most 28.2 u^2 S + 5 eta against the
//! exact cut of the computed operands. Errors e_lo, e_hi already in the operands pass into
//! (1 - α̂) e_lo + α̂ e_hi <= (1 + 24 u^2) max(e_lo, e_hi) (a convex combination up to the
//! ratio's error). So each value carries a bound e of its distance from the exact extraction
//! of the exact inputs, updated per step as
//!
//!   e' = up(max(e_lo, e_hi) + 2^-100 max(e_lo, e_hi) + 29 u^2 S + 2^-1072)
//!
//! (Lemma B of [`crate::num::ddi`]: two terms and two products; 24 u^2 <= 2^-100,
//! 5 eta <= 2^-1072), starting from the inputs' radii (an input's exact value is within its
//! radius of its centre; the steps are the same convex combinations for both). This running
//! bound in plain f64 follows the local magnitudes (a point with a tiny weight keeps a tiny
//! radius next to huge ones) at a few flops per value, against the double-word arithmetic
//! with interval radii of [`Ddi`]. The result is the `Ddi` centre hi + lo with radius e.
//!
//! The guard (else the caller runs the `Ddi` extraction): every local knot finite with
//! |t| < 2^1000 (no difference overflows) and every non-zero difference of two local knots at
//! least 2^-900 (the ratio's conditions above); every input finite and below 2^1000 in
//! magnitude with its radius (no intermediate overflows: the values are convex combinations);
//! every output and bound finite. Tested against exact rational extraction
//! (`dw_extraction_bound_holds_exactly`).

use super::ddi::{two_prod, two_sum, up, Ddi};
use super::Scalar;
use crate::spline::bspline::{clamp_span, run_end, sweep_spans};
use inari::Interval;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A double word `hi + lo` (normalised: |lo| <= ulp(hi) / 2) with the extraction's running
/// error bound `e` (module docs). Only [`Scalar::lerp`] maintains `e` (and negation, which
/// is exact, keeps it); every other operation gives NaN there (no bound is claimed for it, and [`clamp_span_dw`] then falls back), so
/// the type cannot silently produce an unproved radius.
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C)]
pub(crate) struct Dw {
    hi: f64,
    lo: f64,
    e: f64,
}

impl Dw {
    /// The normalised double word hi + lo (exact), with no bound.
    #[inline(always)]
    fn norm(hi: f64, lo: f64) -> Dw {
        let (h, l) = two_sum(hi, lo);
        Dw {
            hi: h,
            lo: l,
            e: f64::NAN,
        }
    }
    /// The normalised double word of the exact sum hi + lo (TwoSum), with no bound (for
    /// kernels that bound their error a priori, such as `bernstein::value_vs_dw`).
    #[inline(always)]
    pub(crate) fn from_parts(hi: f64, lo: f64) -> Dw {
        Dw::norm(hi, lo)
    }
    /// (hi, lo).
    #[inline(always)]
    pub(crate) fn parts(self) -> (f64, f64) {
        (self.hi, self.lo)
    }
}

/// The lanes of `Dw`'s [`Scalar::lerp4`] in AVX2 / FMA registers: per lane the same IEEE operations in
/// the same order as [`Scalar::lerp`] (TwoSum, TwoProd by a fused multiply-subtract, the FMA
/// of the product's low part, the bound's products and sums unfused), so bit for bit its
/// results (`lerp4_is_four_lerps`).
#[cfg(all(
    target_arch = "x86_64",
    target_feature = "avx2",
    target_feature = "fma"
))]
#[inline(always)]
unsafe fn lerp4_avx(
    [ah, al]: [std::arch::x86_64::__m256d; 2],
    [lh, ll, le]: [std::arch::x86_64::__m256d; 3],
    [hh, hl, he]: [std::arch::x86_64::__m256d; 3],
) -> [std::arch::x86_64::__m256d; 3] {
    use std::arch::x86_64::*;
    // SAFETY: the target features are enabled at compile time (the cfg above); register
    // arithmetic only.
    unsafe {
        let two_sum = |a: __m256d, b: __m256d| {
            let s = _mm256_add_pd(a, b);
            let bb = _mm256_sub_pd(s, a);
            let e = _mm256_add_pd(_mm256_sub_pd(a, _mm256_sub_pd(s, bb)), _mm256_sub_pd(b, bb));
            (s, e)
        };
        let sign = _mm256_set1_pd(-0.0);
        let neg = |x: __m256d| _mm256_xor_pd(x, sign);
        let abs = |x: __m256d| _mm256_andnot_pd(sign, x);
        // d = hi - lo (`Add` of the negation)
        let (s, e) = two_sum(hh, neg(lh));
        let t = _mm256_add_pd(hl, neg(ll));
        let (dh, dl) = two_sum(s, _mm256_add_pd(e, t));
        // m = a d (`Mul`: TwoProd, then a.hi d.lo + a.lo d.hi by one FMA)
        let p = _mm256_mul_pd(ah, dh);
        let e = _mm256_fmsub_pd(ah, dh, p);
        let t = _mm256_fmadd_pd(ah, dl, _mm256_mul_pd(al, dh));
        let (mh, ml) = two_sum(p, _mm256_add_pd(e, t));
        // z = lo + m (`Add`)
        let (s, e) = two_sum(lh, mh);
        let t = _mm256_add_pd(ll, ml);
        let (zh, zl) = two_sum(s, _mm256_add_pd(e, t));
        // the running bound: up(m + C100 m + C29 (|lo| + |hi|) + 2^-1072), unfused
        let m = _mm256_max_pd(le, he);
        let sm = _mm256_add_pd(abs(lh), abs(hh));
        let r = _mm256_add_pd(
            _mm256_add_pd(
                _mm256_add_pd(m, _mm256_mul_pd(_mm256_set1_pd(C100), m)),
                _mm256_mul_pd(_mm256_set1_pd(C29), sm),
            ),
            _mm256_set1_pd(f64::from_bits(4)),
        );
        let ze = _mm256_add_pd(
            _mm256_mul_pd(r, _mm256_set1_pd(super::ddi::INFL)),
            _mm256_set1_pd(super::ddi::FLOOR),
        );
        [zh, zl, ze]
    }
}

/// Four consecutive `Dw` (hi, lo, e; `repr(C)`: twelve f64 in a row) as the three registers
/// of their parts, [h0 h1 h2 h3], [l0 l1 l2 l3], [e0 e1 e2 e3]: three loads of the twelve
/// values (v0 = [h0 l0 e0 h1], v1 = [l1 e1 h2 l2], v2 = [e2 h3 l3 e3]), then per part two
/// blends that pick its lanes and one permutation that orders them (instead of twelve
/// scalar loads and inserts).
#[cfg(all(
    target_arch = "x86_64",
    target_feature = "avx2",
    target_feature = "fma"
))]
#[inline(always)]
fn load4(x: &[Dw; 4]) -> [std::arch::x86_64::__m256d; 3] {
    use std::arch::x86_64::*;
    let p = x.as_ptr() as *const f64;
    // SAFETY: `Dw` is `repr(C)` with three f64 fields (size 24, no padding), so the array is
    // twelve consecutive f64; unaligned loads of 4 + 4 + 4 of them; AVX2 is enabled at
    // compile time (the cfg above).
    unsafe {
        let (v0, v1, v2) = (
            _mm256_loadu_pd(p),
            _mm256_loadu_pd(p.add(4)),
            _mm256_loadu_pd(p.add(8)),
        );
        // h: v0[0], v0[3], v1[2], v2[1] -> [v0_0, v2_1, v1_2, v0_3], lanes 0 3 2 1
        let h = _mm256_blend_pd::<0b0010>(_mm256_blend_pd::<0b0100>(v0, v1), v2);
        let h = _mm256_permute4x64_pd::<0b01_10_11_00>(h);
        // l: v0[1], v1[0], v1[3], v2[2] -> [v1_0, v0_1, v2_2, v1_3], lanes 1 0 3 2
        let l = _mm256_blend_pd::<0b0100>(_mm256_blend_pd::<0b0010>(v1, v0), v2);
        let l = _mm256_permute4x64_pd::<0b10_11_00_01>(l);
        // e: v0[2], v1[1], v2[0], v2[3] -> [v2_0, v1_1, v0_2, v2_3], lanes 2 1 0 3
        let e = _mm256_blend_pd::<0b0010>(_mm256_blend_pd::<0b0100>(v2, v0), v1);
        let e = _mm256_permute4x64_pd::<0b11_00_01_10>(e);
        [h, l, e]
    }
}

/// The inverse of [`load4`]: the parts' registers as four consecutive `Dw`.
#[cfg(all(
    target_arch = "x86_64",
    target_feature = "avx2",
    target_feature = "fma"
))]
#[inline(always)]
fn store4([h, l, e]: [std::arch::x86_64::__m256d; 3]) -> [Dw; 4] {
    use std::arch::x86_64::*;
    let mut out = [Dw {
        hi: 0.0,
        lo: 0.0,
        e: 0.0,
    }; 4];
    let p = out.as_mut_ptr() as *mut f64;
    // SAFETY: as in `load4` (twelve consecutive f64 in `out`); AVX2 enabled at compile time.
    unsafe {
        // back to lane order of each register's blend (the permutations of `load4` inverted)
        // h = [h0, h3, h2, h1], l = [l1, l0, l3, l2], e = [e2, e1, e0, e3]
        let h = _mm256_permute4x64_pd::<0b01_10_11_00>(h);
        let l = _mm256_permute4x64_pd::<0b10_11_00_01>(l);
        let e = _mm256_permute4x64_pd::<0b11_00_01_10>(e);
        // v0 = [h0 l0 e0 h1]: h lanes 0, 3; l lane 1; e lane 2
        let v0 = _mm256_blend_pd::<0b0100>(_mm256_blend_pd::<0b0010>(h, l), e);
        // v1 = [l1 e1 h2 l2]: l lanes 0, 3; e lane 1; h lane 2
        let v1 = _mm256_blend_pd::<0b0100>(_mm256_blend_pd::<0b0010>(l, e), h);
        // v2 = [e2 h3 l3 e3]: e lanes 0, 3; h lane 1; l lane 2
        let v2 = _mm256_blend_pd::<0b0100>(_mm256_blend_pd::<0b0010>(e, h), l);
        _mm256_storeu_pd(p, v0);
        _mm256_storeu_pd(p.add(4), v1);
        _mm256_storeu_pd(p.add(8), v2);
    }
    out
}

impl Add for Dw {
    type Output = Dw;
    #[inline(always)]
    fn add(self, y: Dw) -> Dw {
        let (s, e) = two_sum(self.hi, y.hi);
        let t = self.lo + y.lo;
        Dw::norm(s, e + t)
    }
}

impl Sub for Dw {
    type Output = Dw;
    #[inline(always)]
    fn sub(self, y: Dw) -> Dw {
        self + (-y)
    }
}

impl Neg for Dw {
    type Output = Dw;
    #[inline(always)]
    /// Exact, so the bound stays.
    fn neg(self) -> Dw {
        Dw {
            hi: -self.hi,
            lo: -self.lo,
            ..self
        }
    }
}

impl Mul for Dw {
    type Output = Dw;
    #[inline(always)]
    fn mul(self, y: Dw) -> Dw {
        let (p, e) = two_prod(self.hi, y.hi);
        let t = self.hi.mul_add(y.lo, self.lo * y.hi);
        Dw::norm(p, e + t)
    }
}

impl Div for Dw {
    type Output = Dw;
    /// The quotient q1 + r2 / yh of the module docs' knot ratio (its bound holds for the exact
    /// double-word knot differences there; no bound is claimed for other operands).
    #[inline(always)]
    fn div(self, y: Dw) -> Dw {
        let q1 = self.hi / y.hi;
        let r = (-q1).mul_add(y.hi, self.hi);
        let r2 = (-q1).mul_add(y.lo, r + self.lo);
        Dw::norm(q1, r2 / y.hi)
    }
}

impl Scalar for Dw {
    const SWEEP_BLOCKS: bool = true;
    /// Four corner cuts ([`Scalar::lerp`]) lane by lane: in AVX2 / FMA registers where the
    /// target has them ([`lerp4_avx`], per lane exactly the operations of `lerp`, in the same
    /// order: the same results and the same bound), else one after the other.
    #[inline(always)]
    fn lerp4(a: &[Self; 4], lo: &[Self; 4], hi: &[Self; 4]) -> [Self; 4] {
        #[cfg(all(
            target_arch = "x86_64",
            target_feature = "avx2",
            target_feature = "fma"
        ))]
        {
            let [ah, al, _] = load4(a);
            // SAFETY: AVX2 and FMA are enabled at compile time (the cfg above).
            store4(unsafe { lerp4_avx([ah, al], load4(lo), load4(hi)) })
        }
        #[cfg(not(all(
            target_arch = "x86_64",
            target_feature = "avx2",
            target_feature = "fma"
        )))]
        {
            std::array::from_fn(|l| <Dw as Scalar>::lerp(&a[l], &lo[l], &hi[l]))
        }
    }
    #[inline(always)]
    fn from_f64(x: f64) -> Self {
        Dw {
            hi: x,
            lo: 0.0,
            e: 0.0,
        }
    }
    /// The corner cut of the module docs, with its running bound.
    #[inline(always)]
    fn lerp(a: &Self, lo: &Self, hi: &Self) -> Self {
        let z = *lo + *a * (*hi - *lo);
        let m = lo.e.max(hi.e);
        // 29 u^2 = 29 * 2^-106; 2^-100; 2^-1072
        let s = lo.hi.abs() + hi.hi.abs();
        let e = up(m + C100 * m + C29 * s + f64::from_bits(4));
        Dw { e, ..z }
    }
    /// The knot ratio of the module docs (exact double-word numerator and denominator).
    #[inline(always)]
    fn knot_ratio_f64(u: f64, a: f64, b: f64) -> Self {
        // exact double-word differences (TwoSum), then the quotient; its error, <= 12 u^2, is
        // part of the corner cut's bound
        Dw {
            e: 0.0,
            ..Dw::norm(u, -a) / Dw::norm(b, -a)
        }
    }
    /// Not an enclosure (no bound is carried): the nearest interval of hi + lo's two parts.
    fn to_interval(&self) -> Interval {
        let v = self.hi + self.lo;
        Interval::try_from((v.next_down(), v.next_up())).unwrap_or(Interval::ENTIRE)
    }
    fn to_f64(&self) -> f64 {
        self.hi
    }
    fn is_exact_zero(&self) -> bool {
        self.hi == 0.0 && self.lo == 0.0
    }
}

/// 2^1000 and 2^-900: the guard of the module docs.
const BIG: f64 = f64::from_bits((1023 + 1000) << 52);
const TINY_GAP: f64 = f64::from_bits((1023 - 900) << 52);
/// 2^-100 and 29 u^2 = 29 * 2^-106 (exact).
const C100: f64 = f64::from_bits((1023 - 100) << 52);
const C29: f64 = 29.0 * f64::from_bits((1023 - 106) << 52);

/// The guard of the module docs on the knots: every one finite and below 2^1000, distinct
/// ones at least 2^-900 apart (sorted, so the consecutive gaps are the smallest differences).
pub(crate) fn knots_guarded(t: &[f64]) -> bool {
    t.iter().all(|x| x.abs() < BIG) && !t.windows(2).any(|w| w[1] != w[0] && w[1] - w[0] < TINY_GAP)
}

/// The `Ddi` inputs as double words carrying their radii, or `None` where the guard of the
/// module docs fails (a non-finite or huge value).
fn to_dw<const N: usize>(q: &[Ddi], buf: &mut smallvec::SmallVec<[Dw; N]>) -> bool
where
    [Dw; N]: smallvec::Array<Item = Dw>,
{
    // (into the caller's buffer: a returned inline buffer of 96 double words is 2.3 kB moved
    // per call)
    buf.clear();
    buf.reserve(q.len());
    for x in q {
        let (hi, lo, rad) = x.parts();
        // (a NaN fails the comparison too)
        if hi.is_nan() || rad.is_nan() || hi.abs() + rad >= BIG {
            return false;
        }
        buf.push(Dw { hi, lo, e: rad });
    }
    true
}

impl Dw {
    /// Whether `x` is an input the module docs' bound covers (finite, below 2^1000).
    #[inline]
    pub(crate) fn guarded(x: f64) -> bool {
        x.abs() < BIG
    }
    /// The value with its bound as a `Ddi` (centre hi + lo, radius e), or `None` where a part
    /// is not finite (the bound then covers nothing).
    #[inline]
    pub(crate) fn to_ddi_checked(self) -> Option<Ddi> {
        (self.hi.is_finite() && self.lo.is_finite() && self.e.is_finite()).then(|| to_ddi(&self))
    }
    /// An exact value: bound 0 (an input, [`Scalar::from_f64`]).
    #[inline]
    pub(crate) fn is_exact(&self) -> bool {
        self.e == 0.0
    }
    /// Whether the knot ratio (u - a) / (b - a) of f64 knots (a < u < b) may be exactly a
    /// double: `false` only where u - a and b - a are doubles (TwoSum without error) and the
    /// remainder u - a - q (b - a) of the rounded quotient q is not zero (a ratio of two
    /// doubles that is a dyadic rational is a double, the rounded quotient itself).
    #[inline]
    pub(crate) fn knot_ratio_may_be_exact(u: f64, a: f64, b: f64) -> bool {
        let (nh, nl) = two_sum(u, -a);
        let (dh, dl) = two_sum(b, -a);
        let q = nh / dh;
        nl != 0.0 || dl != 0.0 || (-q).mul_add(dh, nh) == 0.0
    }
}

/// Whether every part of every result is finite (else the caller runs the `Ddi` route).
fn all_finite(d: &[Dw]) -> bool {
    d.iter()
        .all(|x| x.hi.is_finite() && x.lo.is_finite() && x.e.is_finite())
}

/// A double word with its bound as the `Ddi` centre hi + lo and radius e.
fn to_ddi(d: &Dw) -> Ddi {
    Ddi::from_parts(d.hi, d.lo, d.e)
}

/// The Bézier extraction of one span ([`clamp_span`]) of `Ddi` points in double words with the
/// running bound of the module docs; `false` (nothing changed) where the guard fails, and the
/// caller runs the `Ddi` extraction.
pub(crate) fn clamp_span_dw(p: usize, h: usize, t: &mut [f64], q: &mut [Ddi]) -> bool {
    if !knots_guarded(t) {
        return false;
    }
    let mut buf = smallvec::SmallVec::<[Dw; 96]>::new();
    if !to_dw(q, &mut buf) {
        return false;
    }
    let mut tt: smallvec::SmallVec<[f64; 96]> = smallvec::SmallVec::new();
    tt.extend_from_slice(t);
    clamp_span(p, h, &mut tt, &mut buf);
    if !all_finite(&buf) {
        return false;
    }
    for (x, d) in q.iter_mut().zip(&buf) {
        *x = to_ddi(d);
    }
    t.copy_from_slice(&tt);
    true
}

/// The Bézier points of a block of consecutive spans ([`sweep_spans`], NURBS Book A5.6) of
/// `Ddi` points in double words with the running bound of the module docs (its corner cuts
/// are those of the proof above: ratios of exact knot differences in [0, 1]); `false`
/// (nothing emitted) where the guard fails on the knots or points the block reads, or a
/// result is not finite, and the caller runs the `Ddi` sweep.
pub(crate) fn sweep_dw(
    p: usize,
    h: usize,
    knots: &[f64],
    pts: &[Ddi],
    k0: usize,
    count: usize,
    emit: &mut dyn FnMut(usize, &[Ddi]),
) -> bool {
    // the block's last span (the sweep's own stepping), for the knots and points it reads:
    // knots u_{k0-p} ..= u_{k0+p+1} and u_{k+j} (j <= p) of every span k, points
    // P_{k0-p} ..= P_{last}
    let n = pts.len() / h - 1;
    let (mut last, mut done) = (k0, 1);
    while done < count {
        let e = run_end(knots, last);
        if e > n {
            break;
        }
        (last, done) = (e, done + 1);
    }
    let kend = (last + p).max(k0 + p + 1).min(knots.len() - 1);
    if !knots_guarded(&knots[k0 - p..=kend]) {
        return false;
    }
    let mut buf = smallvec::SmallVec::<[Dw; 96]>::new();
    if !to_dw(&pts[(k0 - p) * h..(last + 1) * h], &mut buf) {
        return false;
    }
    // the sweep on the block's points alone (span k0 - p + i of the block's local indices)
    let off = k0 - p;
    if done == 1 {
        // (a single span, the usual block of a search: its points converted straight from the
        // sweep's buffer to the caller's, on the stack, not copied into a list first)
        let mut conv: smallvec::SmallVec<[Ddi; 48]> = smallvec::SmallVec::new();
        let (mut span, mut finite) = (0, false);
        sweep_spans(p, h, &knots[off..], &buf, p, 1, &mut |k, q| {
            (span, finite) = (k + off, all_finite(q));
            if finite {
                conv.extend(q.iter().map(to_ddi));
            }
        });
        if finite {
            emit(span, &conv);
        }
        return finite;
    }
    // (the block's spans converted into one buffer, emitted once all are known finite)
    let len = (p + 1) * h;
    let mut ks: smallvec::SmallVec<[usize; 8]> = smallvec::SmallVec::new();
    // (from and back to the thread's pool: a block of spans took a heap block of ~1 KB)
    let mut conv: Vec<Ddi> = crate::num::pool::take(done * len);
    let mut finite = true;
    sweep_spans(p, h, &knots[off..], &buf, p, done, &mut |k, q| {
        finite &= all_finite(q);
        if finite {
            ks.push(k + off);
            conv.extend(q.iter().map(to_ddi));
        }
    });
    if finite {
        for (k, q) in ks.iter().zip(conv.chunks_exact(len)) {
            emit(*k, q);
        }
    }
    crate::num::pool::give(conv);
    finite
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::Exact;
    use rand::{Rng, SeedableRng};

    /// The four-lane corner cut gives bit for bit the results of four scalar ones (the
    /// module's bound is proved for those).
    #[test]
    fn lerp4_is_four_lerps() {
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let dw = |r: &mut rand_chacha::ChaCha8Rng| {
            let x = r.random_range(-1.0..1.0) * 2f64.powi(r.random_range(-60..60));
            let y = x * r.random_range(0.0..1.0) * 1e-17;
            Dw {
                e: r.random_range(0.0..1e-30),
                ..Dw::norm(x, y)
            }
        };
        for _ in 0..20000 {
            // (ratios of knot differences with a low part: knots that are not dyadic)
            let a: [Dw; 4] = std::array::from_fn(|_| {
                let (k0, k1) = (r.random_range(-3.0..1.0), r.random_range(1.0..5.0));
                Dw::knot_ratio_f64(r.random_range(k0..k1), k0, k1)
            });
            let lo: [Dw; 4] = std::array::from_fn(|_| dw(&mut r));
            let hi: [Dw; 4] = std::array::from_fn(|_| dw(&mut r));
            let got = <Dw as Scalar>::lerp4(&a, &lo, &hi);
            for l in 0..4 {
                let want = Dw::lerp(&a[l], &lo[l], &hi[l]);
                assert_eq!(
                    (got[l].hi.to_bits(), got[l].lo.to_bits(), got[l].e.to_bits()),
                    (want.hi.to_bits(), want.lo.to_bits(), want.e.to_bits())
                );
            }
        }
    }

    /// The a-priori bound of [`clamp_span_dw`] holds against the exact rational extraction of
    /// the input centres (the same generic kernel on [`Exact`]): degrees 2..=24, one to three
    /// rows, uniform, clustered (gaps down to 1e-13 of the knots), multiple and huge knots,
    /// coordinates from 2^-80 to 2^80 with double-word inputs and radii; and the bound is not
    /// vacuous (the observed errors are within a small factor of it).
    #[test]
    fn dw_extraction_bound_holds_exactly() {
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(17);
        let mut worst: f64 = 0.0;
        let (mut ran, mut swept) = (0, 0);
        for it in 0..300 {
            let p = r.random_range(2..=24usize);
            let h = r.random_range(1..=3usize);
            let scale = 2f64.powi(r.random_range(-40..=40));
            let base: f64 = if it % 7 == 0 {
                1e200
            } else {
                r.random_range(-5.0..5.0)
            };
            // (up to five more points and knots: a multi-span curve for the sweep below,
            // whose first span's window is the one-span extraction's input)
            let extra = r.random_range(0..=5usize);
            let mut t: Vec<f64> = (0..2 * p + 2 + extra)
                .map(|_| match it % 4 {
                    0 => base + r.random_range(0..=(2 * p + 2)) as f64 * scale,
                    1 => base * (1.0 + r.random_range(0.0..1e-13)),
                    2 => base + (r.random_range(0..4) as f64) * scale,
                    _ => base + r.random_range(0.0..1.0) * scale,
                })
                .collect();
            t.sort_by(f64::total_cmp);
            if t[p] >= t[p + 1] {
                continue;
            }
            let mag = 2f64.powi(r.random_range(-80..=80));
            let q_all: Vec<Ddi> = (0..(p + 1 + extra) * h)
                .map(|i| {
                    // (some points 2^40 times larger or smaller: weights spread widely)
                    let spread = match i % 5 {
                        0 => 2f64.powi(40),
                        1 => 2f64.powi(-40),
                        _ => 1.0,
                    };
                    let x = Ddi::exact(r.random_range(-1.0..1.0) * mag * spread);
                    match i % 3 {
                        0 => x,
                        // a double word (an exact product of two f64)
                        1 => x * Ddi::exact(1.0 + r.random_range(0.0..1.0)),
                        // with a radius
                        _ => {
                            let (hi, lo, _) = x.parts();
                            Ddi::from_parts(hi, lo, mag * 1e-30)
                        }
                    }
                })
                .collect();
            let q = q_all[..(p + 1) * h].to_vec();
            let mut qd = q.clone();
            let mut td = t[..2 * p + 2].to_vec();
            if !clamp_span_dw(p, h, &mut td, &mut qd) {
                continue;
            }
            ran += 1;
            let mut qe: Vec<Exact> = q
                .iter()
                .map(|x| {
                    let (hi, lo, _) = x.parts();
                    Exact::of(hi) + Exact::of(lo)
                })
                .collect();
            let mut te = t[..2 * p + 2].to_vec();
            clamp_span(p, h, &mut te, &mut qe);
            assert_eq!(te, td, "knots");
            let mut within = |e: &Exact, d: &Ddi| {
                let (hi, lo, rad) = d.parts();
                let diff = e.clone() - Exact::of(hi) - Exact::of(lo);
                assert!(
                    !(diff.clone() - Exact::of(rad)).gt_f64(0.0)
                        && !(Exact::of(-rad) - diff.clone()).gt_f64(0.0),
                    "p = {p}, h = {h}, knots {t:?}: error {} > radius {rad}",
                    diff.to_f64()
                );
                worst = worst.max(diff.to_f64().abs() / rad.max(f64::MIN_POSITIVE));
            };
            for (e, d) in qe.iter().zip(&qd) {
                within(e, d);
            }
            // The sweep over every span from span p (NURBS Book A5.6, `sweep_dw`), against
            // the exact sweep of the input centres (itself the exact per-span extraction:
            // `bspline`'s sweep test); up to degree 14 (the exact rationals of longer chains
            // grow large).
            if p > 14 {
                continue;
            }
            let centres: Vec<Exact> = q_all
                .iter()
                .map(|x| {
                    let (hi, lo, _) = x.parts();
                    Exact::of(hi) + Exact::of(lo)
                })
                .collect();
            let mut exact = Vec::new();
            sweep_spans(p, h, &t, &centres, p, usize::MAX, &mut |k, q| {
                exact.push((k, q.to_vec()))
            });
            let mut dws = Vec::new();
            if sweep_dw(p, h, &t, &q_all, p, usize::MAX, &mut |k, q| {
                dws.push((k, q.to_vec()))
            }) {
                swept += 1;
                assert_eq!(dws.len(), exact.len());
                for ((k, d), (ke, e)) in dws.iter().zip(&exact) {
                    assert_eq!(k, ke);
                    for (x, y) in e.iter().zip(d) {
                        within(x, y);
                    }
                }
            }
            // a block of one span (its own path in `sweep_dw`): the first and the last span
            // alone
            for (ke, e) in [&exact[0], &exact[exact.len() - 1]] {
                let mut one = Vec::new();
                if sweep_dw(p, h, &t, &q_all, *ke, 1, &mut |k, q| {
                    one.push((k, q.to_vec()))
                }) {
                    assert_eq!(one.len(), 1);
                    assert_eq!(one[0].0, *ke);
                    for (x, y) in e.iter().zip(&one[0].1) {
                        within(x, y);
                    }
                }
            }
        }
        assert!(swept > 80, "{swept} sweeps ran");
        assert!(ran > 150, "{ran} extractions ran");
        eprintln!("dw extraction: {ran} spans, worst error {worst:.3e} of the radius");
        // not vacuous: the radius is within a factor 2^20 of the worst error seen
        assert!(worst > 1e-6 && worst <= 1.0, "{worst}");
    }
}
