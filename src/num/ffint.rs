//! Exact integer kernels of the fraction-free algorithms (the certificate's exact Bernstein
//! rule and end game, exact values at knots): f64 values as integers over a common power of
//! two ([`dyadic_integers`]), and Boehm's knot insertion that clamps a span (NURBS Book A5.1;
//! thesis eq. 4.12) on integer rows, fraction-free ([`clamp_span_ints`]). Generic over
//! [`FfInt`]: `BigInt`, or `i128` with every operation checked, so that short data (small
//! integer knots, few-bit values) runs without allocation and anything longer falls back to
//! big integers with the same steps.

use num_bigint::{BigInt, Sign};

/// The integers of the fraction-free kernels ([`clamp_left_integer`]): `BigInt`, or `i128`
/// with every operation checked (`None` on overflow), for short data.
pub(crate) trait FfInt: Clone {
    fn from_i64(x: i64) -> Self;
    fn add(&self, o: &Self) -> Option<Self>;
    fn sub(&self, o: &Self) -> Option<Self>;
    fn mul(&self, o: &Self) -> Option<Self>;
    fn neg(&self) -> Option<Self>;
    /// self 2^k
    fn shl(&self, k: u64) -> Option<Self>;
    /// self / 2^k for a multiple of 2^k
    fn shr_exact(&self, k: u64) -> Self;
    /// the exponent of the largest power of two dividing self (`None` for 0)
    fn trailing_zeros(&self) -> Option<u64>;
    fn is_positive(&self) -> bool;
    fn is_eq(&self, o: &Self) -> bool;
}

impl FfInt for BigInt {
    fn from_i64(x: i64) -> Self {
        BigInt::from(x)
    }
    fn add(&self, o: &Self) -> Option<Self> {
        Some(self + o)
    }
    fn sub(&self, o: &Self) -> Option<Self> {
        Some(self - o)
    }
    fn mul(&self, o: &Self) -> Option<Self> {
        Some(self * o)
    }
    fn neg(&self) -> Option<Self> {
        Some(-self)
    }
    fn shl(&self, k: u64) -> Option<Self> {
        Some(self << k)
    }
    fn shr_exact(&self, k: u64) -> Self {
        self >> k
    }
    fn trailing_zeros(&self) -> Option<u64> {
        BigInt::trailing_zeros(self)
    }
    fn is_positive(&self) -> bool {
        self.sign() == Sign::Plus
    }
    fn is_eq(&self, o: &Self) -> bool {
        self == o
    }
}

impl FfInt for i128 {
    fn from_i64(x: i64) -> Self {
        x as i128
    }
    fn add(&self, o: &Self) -> Option<Self> {
        self.checked_add(*o)
    }
    fn sub(&self, o: &Self) -> Option<Self> {
        self.checked_sub(*o)
    }
    fn mul(&self, o: &Self) -> Option<Self> {
        self.checked_mul(*o)
    }
    fn neg(&self) -> Option<Self> {
        self.checked_neg()
    }
    fn shl(&self, k: u64) -> Option<Self> {
        // (exact only while no bit, the sign bit included, is shifted out)
        if *self == 0 {
            return Some(0);
        }
        let room = self.unsigned_abs().leading_zeros() as u64;
        (k < room).then(|| self << k)
    }
    fn shr_exact(&self, k: u64) -> Self {
        self >> k
    }
    fn trailing_zeros(&self) -> Option<u64> {
        (*self != 0).then(|| i128::trailing_zeros(*self) as u64)
    }
    fn is_positive(&self) -> bool {
        *self > 0
    }
    fn is_eq(&self, o: &Self) -> bool {
        self == o
    }
}

/// Clamps a span of degree p at both ends ([`clamp_left_integer`] from the left, then from the
/// right on the reversed, negated knots), given its 2p + 2 local knots u_{k-p} ..= u_{k+p+1}
/// (f64, brought to integers over one power of two: their ratios do not change): the rows of
/// integer values of the span's local control points become the rows of its Bézier points,
/// all times one common positive factor. `None` for an invalid span or an overflow of `T`.
pub(crate) fn clamp_span_ints<T: FfInt>(
    p: usize,
    knots: &[f64],
    rows: &mut [&mut [T]],
) -> Option<()> {
    clamp_span_ints_with(p, knots, rows, None)
}

/// [`clamp_span_ints`], and `factor` (if given) multiplied by the rows' common positive
/// factor: a constant row (every value `factor`, e.g. the weights 1 of a non-rational curve)
/// clamped with the rows is that row afterwards, without its corner cuts (a corner cut of two
/// equal values is that value times the sum of its two multipliers, which is the level's
/// denominator: so each level multiplies a constant row by the product of the level's
/// denominators, as it does the rows' other values, and shifts it with them).
pub(crate) fn clamp_span_ints_with<T: FfInt>(
    p: usize,
    knots: &[f64],
    rows: &mut [&mut [T]],
    factor: Option<&mut T>,
) -> Option<()> {
    clamp_span_ints_ends(p, knots, rows, factor, [true, true])
}

/// [`clamp_span_ints_with`] at the ends in `ends` ([left, right]) only. A clamp at one end
/// makes the row's point there the piece's value at that knot (times the common factor) by
/// itself: Boehm's insertion of u_k (u_{k+1}) up to multiplicity p gives the blossom value
/// f(u_k, ..., u_k) (f(u_{k+1}, ..., u_{k+1})) whatever was inserted at the other end (the
/// blossom is symmetric and multi-affine; NURBS Book sec. 5.2), and the other end's clamp only
/// multiplies that point, like every other value and `factor`, by positive level factors. So a
/// caller that reads the end points of one end only needs that end's clamp (the other points
/// are then not the Bézier points).
pub(crate) fn clamp_span_ints_ends<T: FfInt>(
    p: usize,
    knots: &[f64],
    rows: &mut [&mut [T]],
    mut factor: Option<&mut T>,
    ends: [bool; 2],
) -> Option<()> {
    let (mut kn, _) = dyadic_ints::<T>(knots.iter().copied())?;
    if ends[0] {
        clamp_left_integer(p, &mut kn, rows, factor.as_deref_mut())?;
    }
    if !ends[1] {
        return Some(());
    }
    rows.iter_mut().for_each(|q| q.reverse());
    kn.reverse();
    for x in kn.iter_mut() {
        *x = x.neg()?;
    }
    clamp_left_integer(p, &mut kn, rows, factor)?;
    rows.iter_mut().for_each(|q| q.reverse());
    Some(())
}

/// `bspline::clamp_left` on one row of integers over a common positive denominator, with
/// integer knots, fraction-free (the certificate's `bezier_coefficients_fraction_free`): the same cut
/// points in the same order (point i of level l from points i and i + 1 of level l - 1),
/// each value multiplied by one positive factor per level; `factor` (a constant row's value,
/// see [`clamp_span_ints_with`]) multiplied by the same factors.
pub(crate) fn clamp_left_integer<T: FfInt>(
    p: usize,
    t: &mut [T],
    rows: &mut [&mut [T]],
    mut factor: Option<&mut T>,
) -> Option<()> {
    let u = t[p].clone();
    let s = t[..=p].iter().rev().take_while(|x| x.is_eq(&u)).count();
    if s >= p {
        return Some(());
    }
    let one = T::from_i64(1);
    for l in 1..=p - s {
        let n = p - l - s;
        let den: smallvec::SmallVec<[T; 8]> = (0..=n)
            .map(|i| t[i + p + 1].sub(&t[l + i]))
            .collect::<Option<_>>()?;
        if den.iter().any(|d| !d.is_positive()) {
            return None;
        }
        // cofactor of den_i: the product of the level's other denominators
        let mut pre: smallvec::SmallVec<[T; 8]> = smallvec::smallvec![one.clone(); n + 2];
        for i in 0..=n {
            pre[i + 1] = pre[i].mul(&den[i])?;
        }
        let mut suf: smallvec::SmallVec<[T; 8]> = smallvec::smallvec![one.clone(); n + 2];
        for i in (0..=n).rev() {
            suf[i] = suf[i + 1].mul(&den[i])?;
        }
        // (every row the same cuts and factors: their common positive factor stays one; the
        // cuts' multipliers and the cofactors once per level, not per row)
        let mut cuts: smallvec::SmallVec<[(T, T, T); 8]> = smallvec::SmallVec::new();
        for i in 0..=n {
            let left = t[i + p + 1].sub(&u)?;
            let right = u.sub(&t[l + i])?;
            cuts.push((left, right, pre[i].mul(&suf[i + 1])?));
        }
        for q in rows.iter_mut() {
            for (i, (left, right, cof)) in cuts.iter().enumerate() {
                let v = left.mul(&q[i])?.add(&right.mul(&q[i + 1])?)?;
                q[i] = v.mul(cof)?;
            }
            for x in &mut q[n + 1..=p] {
                *x = x.mul(&pre[n + 1])?;
            }
        }
        if let Some(f) = factor.as_deref_mut() {
            *f = f.mul(&pre[n + 1])?;
        }
        // (a common power of two out of every row and the factor: a positive factor)
        let tz = rows
            .iter()
            .flat_map(|q| q.iter())
            .chain(factor.as_deref())
            .filter_map(|x| x.trailing_zeros())
            .min()
            .unwrap_or(0);
        if tz > 0 {
            for q in rows.iter_mut() {
                q.iter_mut().for_each(|x| *x = x.shr_exact(tz));
            }
            if let Some(f) = factor.as_deref_mut() {
                *f = f.shr_exact(tz);
            }
        }
    }
    let first = t[p - s].clone();
    t[0] = first;
    t[1..=p].iter_mut().for_each(|x| *x = u.clone());
    Some(())
}

/// Finite f64 values as integers over one common power of two 2^e0, and e0 (each x = m 2^e
/// exactly with an odd m or m = 0, from its bits; shifted to the smallest exponent: a positive
/// common factor, no gcd); `None` for a value that is not finite.
pub(crate) fn dyadic_integers(xs: impl Iterator<Item = f64>) -> Option<(Vec<BigInt>, i64)> {
    dyadic_ints(xs)
}

/// [`dyadic_integers`] in the integer type `T` (`None` also where a value overflows `T`).
pub(crate) fn dyadic_ints<T: FfInt>(xs: impl Iterator<Item = f64>) -> Option<(Vec<T>, i64)> {
    // (few values per call: on the stack up to 8)
    let parts: smallvec::SmallVec<[(i64, i64); 8]> = xs.map(dyadic_parts).collect::<Option<_>>()?;
    let e0 = parts
        .iter()
        .filter(|x| x.0 != 0)
        .map(|x| x.1)
        .min()
        .unwrap_or(0);
    let ints = parts
        .into_iter()
        .map(|(m, e)| T::from_i64(m).shl((e - e0) as u64))
        .collect::<Option<_>>()?;
    Some((ints, e0))
}

/// A finite x as m 2^e exactly, m odd (or m = e = 0 for x = 0): the significand's bits with the
/// implicit one (none for a subnormal, exponent -1074), trailing zeros moved to e.
pub(crate) fn dyadic_parts(x: f64) -> Option<(i64, i64)> {
    if !x.is_finite() {
        return None;
    }
    if x == 0.0 {
        return Some((0, 0));
    }
    let b = x.to_bits();
    let (be, frac) = (((b >> 52) & 0x7ff) as i64, b & ((1u64 << 52) - 1));
    let (m, e) = if be == 0 {
        (frac, -1074)
    } else {
        (frac | (1u64 << 52), be - 1075)
    };
    let tz = m.trailing_zeros();
    let m = (m >> tz) as i64;
    Some((if x < 0.0 { -m } else { m }, e + tz as i64))
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::Rng;

    /// A constant row clamped as the common factor alone (`clamp_span_ints_with`) is the row
    /// the full clamping gives, and the other rows are the same integers: random spans of
    /// degree 1 to 5 with multiple knots, knots at the corners of the f64 range (subnormal,
    /// near MAX) and ordinary ones. (A factor left out of a level, or out of the common power
    /// of two, fails it.)
    #[test]
    fn constant_row_as_factor_matches_the_full_clamping() {
        let mut rng = crate::testkit::gen::rng(41);
        let mut checked = 0;
        for _ in 0..600 {
            let p = rng.random_range(1..=5usize);
            let mut kn: Vec<f64> = (0..2 * p + 2)
                .map(|_| match rng.random_range(0..4) {
                    0 => f64::from_bits(rng.random_range(1..64)),
                    1 => f64::MAX * rng.random_range(-1.0..1.0),
                    2 => rng.random_range(0..8) as f64,
                    _ => rng.random_range(-4.0..4.0),
                })
                .collect();
            kn.sort_by(f64::total_cmp);
            if kn[p] >= kn[p + 1] {
                continue;
            }
            let row: Vec<BigInt> = (0..=p)
                .map(|_| BigInt::from(rng.random_range(-1_000_000i64..1_000_000)))
                .collect();
            let c = BigInt::from(rng.random_range(1..100i64));
            let (mut full, mut ones) = (row.clone(), vec![c.clone(); p + 1]);
            let a = clamp_span_ints(p, &kn, &mut [&mut full, &mut ones]);
            let (mut alone, mut f) = (row.clone(), c.clone());
            let b = clamp_span_ints_with(p, &kn, &mut [&mut alone], Some(&mut f));
            assert_eq!(a.is_some(), b.is_some());
            if a.is_some() {
                assert_eq!(full, alone, "{kn:?}");
                assert!(ones.iter().all(|x| *x == f), "{kn:?} {ones:?} {f}");
                checked += 1;
            }
        }
        assert!(checked > 300, "{checked}");
    }
}
