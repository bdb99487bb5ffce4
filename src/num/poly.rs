//! Scalar helpers shared by the polynomial kernels: binomial coefficients and Horner's rule,
//! each written once (generic over [`Scalar`] where the number type matters).

use crate::num::Scalar;

/// The binomial coefficient C(n, k) as an f64 when it is exactly representable (at most 2^53),
/// `None` otherwise (and for k > n: `Some(0.0)`).
///
/// Computed in exact integer arithmetic (u128, C(n, i) (n - i) / (i + 1) is an integer at
/// every step), so the value is exact, not a rounded product: all C(n, k) with n <= 56 fit,
/// and for larger n the coefficients near the ends still do.
pub fn binom_exact(n: usize, k: usize) -> Option<f64> {
    if k > n {
        return Some(0.0);
    }
    if n < SMALL_N {
        // (the kernels' usual degrees: a table, no division loop)
        return Some(SMALL_BINOMS[n][k]);
    }
    let k = k.min(n - k);
    if n < 2048 {
        // (the same in u64, much faster than u128 division: c <= 2^53 before each step and
        // n - i < 2^11, so c (n - i) < 2^64)
        let mut c: u64 = 1;
        for i in 0..k {
            c = c * (n - i) as u64 / (i as u64 + 1);
            if c > 1u64 << 53 {
                return None;
            }
        }
        return Some(c as f64);
    }
    let mut c: u128 = 1;
    for i in 0..k {
        c = c.checked_mul((n - i) as u128)? / (i as u128 + 1);
        if c > 1u128 << 53 {
            return None;
        }
    }
    Some(c as f64)
}

/// Rows n < SMALL_N of Pascal's triangle are tabulated ([`SMALL_BINOMS`]).
const SMALL_N: usize = 24;

/// C(n, k) for k <= n < 24 as an f64, in a `const` context (for tables of constants). Exact:
/// c (n - i) <= C(23, 11) 23 < 2^53 is an exact integer and each quotient c (n - i) / (i + 1)
/// is the integer C(n, i + 1).
pub(crate) const fn binom_small(n: usize, k: usize) -> f64 {
    assert!(k <= n && n < SMALL_N);
    let mut c = 1.0;
    let mut i = 0;
    while i < k {
        c = c * (n - i) as f64 / (i + 1) as f64;
        i += 1;
    }
    c
}

/// C(n, k) for k <= n < [`SMALL_N`] ([`binom_small`]; 0 above the diagonal).
const SMALL_BINOMS: [[f64; SMALL_N]; SMALL_N] = {
    let mut b = [[0.0; SMALL_N]; SMALL_N];
    let mut n = 0;
    while n < SMALL_N {
        let mut k = 0;
        while k <= n {
            b[n][k] = binom_small(n, k);
            k += 1;
        }
        n += 1;
    }
    b
};

/// Binomial coefficient C(n, k) in f64: exact where f64 is ([`binom_exact`]), else the
/// nearest-ish f64 of the multiplicative recurrence (only for estimates; the verified code
/// uses [`binom_s`]).
pub fn binom(n: usize, k: usize) -> f64 {
    binom_exact(n, k).unwrap_or_else(|| {
        (0..k)
            .fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
            .round()
    })
}

/// All binomials C(p, 0..=p) in f64 ([`binom`]: exact up to where f64 is exact).
pub fn binomials(p: usize) -> Vec<f64> {
    (0..=p).map(|k| binom(p, k)).collect()
}

/// Binomial coefficient in S: the exact f64 when there is one ([`binom_exact`]), else built by
/// the multiplicative recurrence C(n, i+1) = C(n, i) (n - i) / (i + 1) in S itself, so that for
/// verified types it encloses the exact integer whatever its size (and for MPFR it is exact
/// while the integers fit the precision).
pub fn binom_s<S: Scalar>(n: usize, k: usize) -> S {
    if let Some(b) = binom_exact(n, k) {
        return S::from_f64(b);
    }
    (0..k).fold(S::one(), |acc, i| {
        acc * S::from_usize(n - i) / S::from_usize(i + 1)
    })
}

/// All binomials C(n, 0..=n) in S ([`binom_s`]).
pub fn binomials_s<S: Scalar>(n: usize) -> Vec<S> {
    (0..=n).map(|k| binom_s(n, k)).collect()
}

/// Horner's rule for sum_k c_k t^k (lecture "Modellierung mit Kurven", "Hornerschema":
/// f = c_g; for i = g-1..0: f = c_i + t f), one [`Scalar::horner_step`] per coefficient (for
/// `Ddi` the fused, more accurate [`crate::num::Ddi::mul_add`]). An empty polynomial is 0.
/// For verified types the value encloses the polynomial at every real in `t`.
#[inline]
pub fn horner<S: Scalar>(coeffs: &[S], t: &S) -> S {
    match coeffs.split_last() {
        None => S::zero(),
        Some((last, rest)) => rest
            .iter()
            .rev()
            .fold(last.clone(), |acc, ck| S::horner_step(&acc, t, ck)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn binomials_are_exact_where_f64_is() {
        assert_eq!(binom(10, 3), 120.0);
        assert_eq!(binom(3, 5), 0.0);
        assert_eq!(binomials(4), vec![1.0, 4.0, 6.0, 4.0, 1.0]);
        // C(56, 28) = 7648690600760440 < 2^53, C(57, 28) = 15297381201520880 > 2^53
        assert_eq!(binom_exact(56, 28), Some(7648690600760440.0));
        assert_eq!(binom_exact(57, 28), None);
        assert_eq!(binom_exact(200, 2), Some(19900.0));
        // the table rows against exact integers (Pascal's rule in u64)
        let mut row = vec![1u64];
        for n in 0..SMALL_N {
            for (k, &c) in row.iter().enumerate() {
                assert_eq!(binom_exact(n, k), Some(c as f64), "C({n}, {k})");
                assert_eq!(binom_small(n, k), c as f64, "C({n}, {k})");
            }
            assert_eq!(binom_exact(n, n + 1), Some(0.0));
            row = (0..=n + 1)
                .map(|k| {
                    if k == 0 || k == n + 1 {
                        1
                    } else {
                        row[k - 1] + row[k]
                    }
                })
                .collect();
        }
        let b: inari::Interval = binom_s(60, 30);
        assert!(b.contains(118264581564861424.0));
    }

    #[test]
    fn horner_matches_direct_sum() {
        let c = [1.0, -2.0, 0.5, 3.0];
        let t = 0.75f64;
        let direct: f64 = c
            .iter()
            .enumerate()
            .map(|(k, x)| x * t.powi(k as i32))
            .sum();
        assert!((horner(&c, &t) - direct).abs() < 1e-15);
        assert_eq!(horner::<f64>(&[], &t), 0.0);
    }
}
