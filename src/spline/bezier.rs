//! Bézier / Bernstein kernels, each written once and generic over [`Scalar`]: de Casteljau
//! evaluation and subdivision, the hodograph (derivative control points), forward differences
//! and the Bernstein-to-power basis change, and homogeneous-to-Cartesian conversion of
//! one-coordinate segments. [`crate::spline::BezierSeg`] and the enclosure strategies call
//! these; with a verified `S` (intervals, `Ddi`, `Mr`) every result encloses the exact one.
//!
//! Control points are stored row-major with `h` homogeneous rows per point (as in
//! [`crate::spline::BezierSeg`]); the single-row kernels take one polynomial's coefficients.

use crate::num::{binom_s, Scalar};

/// de Casteljau subdivision (lecture "Modellierung mit Kurven") of the p + 1 points `pts` (`h`
/// rows each) at local t: the control points of the halves over [0, t] and [t, 1]. Convex
/// combinations by [`Scalar::lerp`] (the thesis's a*(R1-R2)+R2 form; intersected with the
/// convex form for intervals). For verified types (also an interval t) both halves enclose the
/// exact halves for every real t in `t` (each new point is a polynomial in t and the old
/// points; inclusion isotonicity).
pub fn de_casteljau_split<S: Scalar>(pts: &[S], h: usize, t: &S) -> (Vec<S>, Vec<S>) {
    let n = pts.len() / h;
    let p = n - 1;
    let mut b = pts.to_vec();
    let mut left = Vec::with_capacity(b.len());
    let mut right = vec![S::zero(); b.len()];
    left.extend_from_slice(&b[0..h]);
    right[p * h..(p + 1) * h].clone_from_slice(&b[p * h..(p + 1) * h]);
    de_casteljau_levels(&mut b, h, t, |r, b| {
        left.extend_from_slice(&b[0..h]);
        right[(p - r) * h..(p - r + 1) * h].clone_from_slice(&b[(p - r) * h..(p - r + 1) * h]);
    });
    (left, right)
}

/// The corner cuts of de Casteljau's triangle, in place on the points `b` (`h` rows each):
/// level r = 1..=p turns entry k = i h + c (point i, row c) into lerp(t, b_k, b_{k+h}) in
/// increasing k (so b_{k+h} is still the previous level's), in one flat loop; `level(r, b)` is
/// called after each level (points 0..=p - r of `b` are that level's). Afterwards the first
/// `h` entries are the value at t (NURBS Book A1.5).
#[inline]
pub fn de_casteljau_levels<S: Scalar>(
    b: &mut [S],
    h: usize,
    t: &S,
    mut level: impl FnMut(usize, &[S]),
) {
    let p = (b.len() / h).saturating_sub(1);
    for r in 1..=p {
        let len = (p - r + 1) * h;
        let lv = &mut b[..len + h];
        // Blocks of four entries (`Scalar::CUT_BLOCKS`: f64), every read of a block before its
        // writes: in the scalar order entry x is read (as `lo` of x, as `hi` of x - h) at or
        // before its own write, never after, so the block gives the scalar loop's values
        // exactly. A block compiles to vector instructions (the levels are short, and the
        // scalar tail of the compiler's own vectorised loop took most of them).
        let mut k = 0;
        while S::CUT_BLOCKS && k + 4 <= len {
            let (lo, hi) = (&lv[k..k + 4], &lv[k + h..k + h + 4]);
            let v: [S; 4] = std::array::from_fn(|m| S::lerp(t, &lo[m], &hi[m]));
            lv[k..k + 4].clone_from_slice(&v);
            k += 4;
        }
        for k in k..len {
            let hi = lv[k + h].clone();
            lv[k] = S::lerp(t, &lv[k], &hi);
        }
        level(r, b);
    }
}

/// de Casteljau evaluation (NURBS Book A1.5) of the Bernstein polynomial with coefficients
/// `b` at t, in place (`b` is overwritten; no allocation, so callers may pass a stack buffer):
/// b_i = lerp(t, b_i, b_{i+1}) level by level, the value ends in b_0. An empty polynomial is 0.
/// For f64 each step is fl(fl(t fl(b_{i+1} - b_i)) + b_i); for verified types the value
/// encloses the polynomial at every real in `t`.
#[inline]
pub fn de_casteljau_eval_in_place<S: Scalar>(b: &mut [S], t: &S) -> S {
    de_casteljau_levels(b, 1, t, |_, _| {});
    b.first().cloned().unwrap_or_else(S::zero)
}

/// f64 value of the Bernstein polynomial with coefficients `c` at t in [0, 1] in O(n) operations
/// (for estimates only: root finding, where the O(n^2) de Casteljau steps dominated): the
/// Horner scheme in s = t / (1 - t) of sum c_i C(n, i) s^i, times (1 - t)^n, mirrored for
/// t > 1/2 (so s <= 1 and no term grows); the binomials are built on the fly by
/// C(n, i + 1) = C(n, i) (n - i) / (i + 1). Schumaker and Volk, "Efficient evaluation of
/// multivariate polynomials", CAGD 3 (1986) (the "VS algorithm"); Farin, "Curves and Surfaces
/// for CAGD", sec. 5. Its error is a few ulps of sum |c_i| B_i(t), like de Casteljau's.
pub fn bernstein_value(c: &[f64], t: f64) -> f64 {
    let n = match c.len() {
        0 => return 0.0,
        len => len - 1,
    };
    if n == 0 {
        return c[0];
    }
    let (s, q, rev) = if t <= 0.5 {
        (t / (1.0 - t), 1.0 - t, false)
    } else {
        ((1.0 - t) / t, t, true)
    };
    let coef = |i: usize| if rev { c[n - i] } else { c[i] };
    // sum_i coef(i) C(n, i) s^i by Horner from the top: acc = coef(n); acc = acc s + C(n, i)
    // coef(i); the binomials from the table (no division in the loop: the recurrence's
    // dependent divisions took most of the time), above its degree generated downwards by
    // C(n, i - 1) = C(n, i) i / (n - i + 1).
    let mut acc = coef(n);
    if n <= BINOM_TABLE_MAX {
        let row = &BINOM_TABLE[n * (n + 1) / 2..n * (n + 1) / 2 + n + 1];
        for i in (0..n).rev() {
            acc = acc * s + row[i] * coef(i);
        }
    } else {
        let mut binom = 1.0f64; // C(n, n)
        for i in (0..n).rev() {
            binom = binom * (i + 1) as f64 / (n - i) as f64;
            acc = acc * s + binom * coef(i);
        }
    }
    acc * powu(q, n)
}

/// x^n by squaring (`powi` is a library call with a loop).
#[inline]
fn powu(mut x: f64, mut n: usize) -> f64 {
    let mut r = 1.0;
    while n > 0 {
        if n & 1 == 1 {
            r *= x;
        }
        x *= x;
        n >>= 1;
    }
    r
}

/// [`bernstein_value`] of `c` (degree n) and of `d` (degree n - 1, e.g. the hodograph) at the
/// same t, in one pass: the two Horner chains run side by side (they are independent, so
/// their latencies overlap) and share s and the powers of 1 - t (for estimates only: the
/// Newton steps of root finding). Falls back to two calls where the degrees do not fit.
pub fn bernstein_value_pair(c: &[f64], d: &[f64], t: f64) -> (f64, f64) {
    let n = c.len().wrapping_sub(1);
    if c.len() < 2 || d.len() != n || n > BINOM_TABLE_MAX {
        return (bernstein_value(c, t), bernstein_value(d, t));
    }
    let m = n - 1;
    let (s, q, rev) = if t <= 0.5 {
        (t / (1.0 - t), 1.0 - t, false)
    } else {
        ((1.0 - t) / t, t, true)
    };
    let cc = |i: usize| if rev { c[n - i] } else { c[i] };
    let dd = |i: usize| if rev { d[m - i] } else { d[i] };
    let rc = &BINOM_TABLE[n * (n + 1) / 2..n * (n + 1) / 2 + n + 1];
    let rd = &BINOM_TABLE[m * (m + 1) / 2..m * (m + 1) / 2 + m + 1];
    let mut a = cc(n).mul_add(s, rc[m] * cc(m));
    let mut b = dd(m);
    for i in (0..m).rev() {
        a = a.mul_add(s, rc[i] * cc(i));
        b = b.mul_add(s, rd[i] * dd(i));
    }
    let qm = powu(q, m);
    (a * (qm * q), b * qm)
}

/// The Bernstein polynomial with coefficients `c` at the f64 t in [0, 1] in any [`Scalar`], in
/// O(n) operations: the VS algorithm of [`bernstein_value`] (Schumaker and Volk, CAGD 3, 1986),
/// with t, 1 - t, s = t / (1 - t) (or the mirrored forms for t > 1/2), the binomials
/// ([`crate::num::binom_s`]: exact integers up to 2^53, enclosed above) and (1 - t)^n all formed
/// in `S`. For a verified type every step encloses its exact result, and the expression is
/// sum c_i B_i(t) exactly, so the value encloses the polynomial at t. Its width is that of de
/// Casteljau's (sum B_i(t) r_i <= max r_i for coefficient radii r_i, plus a few rounding errors
/// of sum |c_i| B_i(t)), at n instead of n (n + 1) / 2 operations: for the point values of
/// high-degree Bernstein forms.
pub fn bernstein_value_s<S: Scalar>(c: &[S], t: f64) -> S {
    let n = match c.len() {
        0 => return S::zero(),
        len => len - 1,
    };
    if n == 0 {
        return c[0].clone();
    }
    let rev = t > 0.5;
    let (num, q) = if rev {
        (S::one() - S::from_f64(t), S::from_f64(t))
    } else {
        (S::from_f64(t), S::one() - S::from_f64(t))
    };
    let s = num / q.clone();
    let coef = |i: usize| if rev { &c[n - i] } else { &c[i] };
    // (the table's rows are exact up to n = 56, where C(n, i) < 2^53; above, the enclosed
    // recurrence C(n, i) = C(n, i + 1) (i + 1) / (n - i), downwards from C(n, n) = 1)
    let mut acc = coef(n).clone();
    let mut b = S::one();
    for i in (0..n).rev() {
        let bi = if n <= 56 {
            S::from_f64(BINOM_TABLE[n * (n + 1) / 2 + i])
        } else {
            b = b * S::from_usize(i + 1) / S::from_usize(n - i);
            b.clone()
        };
        acc = acc * s.clone() + bi * coef(i).clone();
    }
    // q^n by squaring
    let (mut pw, mut base, mut e) = (S::one(), q, n);
    while e > 0 {
        if e & 1 == 1 {
            pw = pw * base.clone();
        }
        e >>= 1;
        if e > 0 {
            base = base.clone() * base;
        }
    }
    acc * pw
}

/// Highest degree of [`BINOM_TABLE`].
const BINOM_TABLE_MAX: usize = 64;

/// Binomial coefficients C(n, i), n <= [`BINOM_TABLE_MAX`], row n at n (n + 1) / 2 (Pascal's
/// triangle in f64: exact up to n = 56, where C(n, i) < 2^53; rounded above, which the
/// estimates of [`bernstein_value`] do not mind).
static BINOM_TABLE: [f64; (BINOM_TABLE_MAX + 1) * (BINOM_TABLE_MAX + 2) / 2] = {
    let mut t = [0.0f64; (BINOM_TABLE_MAX + 1) * (BINOM_TABLE_MAX + 2) / 2];
    let mut n = 0;
    while n <= BINOM_TABLE_MAX {
        let row = n * (n + 1) / 2;
        t[row] = 1.0;
        t[row + n] = 1.0;
        let mut i = 1;
        while i < n {
            let prev = (n - 1) * n / 2;
            t[row + i] = t[prev + i - 1] + t[prev + i];
            i += 1;
        }
        n += 1;
    }
    t
};

/// de Casteljau evaluation of one Bernstein polynomial at t (copying the coefficients; see
/// [`de_casteljau_eval_in_place`]).
pub fn de_casteljau_eval<S: Scalar>(c: &[S], t: &S) -> S {
    de_casteljau_eval_in_place(&mut c.to_vec(), t)
}

/// The hodograph: Bernstein coefficients of the derivative (degree n - 1, with respect to the
/// local parameter) of a polynomial of degree n, n (c_{i+1} - c_i) (Farin, *Curves and Surfaces
/// for CAGD*, derivatives of a Bézier curve). Degree 0 gives the zero polynomial `[0]`.
/// For verified types each coefficient encloses the exact one (n is exact).
pub fn hodograph<S: Scalar>(c: &[S]) -> Vec<S> {
    let n = c.len().saturating_sub(1);
    if n == 0 {
        return vec![S::zero()];
    }
    hodograph_iter(c).collect()
}

/// The coefficients of [`hodograph`] (at least two input coefficients; nothing for fewer),
/// one after the other, for callers that keep them in their own storage.
pub fn hodograph_iter<S: Scalar>(c: &[S]) -> impl Iterator<Item = S> + '_ {
    let nf = S::from_usize(c.len().saturating_sub(1));
    c.windows(2)
        .map(move |w| nf.clone() * (w[1].clone() - w[0].clone()))
}

/// Forward differences in place: afterwards `d[k] = Δ^k d_0` (Δ^{k+1} b_i = Δ^k b_{i+1} -
/// Δ^k b_i), the differences of [`bernstein_to_power`]. One subtraction per entry and level,
/// the same operations as the triangle scheme of the lecture's basis change.
pub fn forward_differences<S: Scalar>(d: &mut [S]) {
    let p = d.len().saturating_sub(1);
    for k in 1..=p {
        for i in (k..=p).rev() {
            d[i] = d[i].clone() - d[i - 1].clone();
        }
    }
}

/// Basis change Bernstein -> power form of the local parameter (lecture "Modellierung mit
/// Kurven", "Basistransformation", T_{M<-B}; Farin, monomial form of a Bézier curve):
/// a_k = C(p, k) Δ^k b_0, row-wise for p + 1 points of `h` rows (row-major in, row-major out),
/// by [`power_from_differences`] on the first differences b_{i+1} - b_i of each row.
/// For verified types every a_k encloses the exact one.
pub fn bernstein_to_power<S: Scalar>(pts: &[S], h: usize) -> Vec<S> {
    let n = pts.len() / h;
    let mut out = vec![S::zero(); pts.len()];
    for r in 0..h {
        let row = |i: usize| pts[i * h + r].clone();
        let diffs = (1..n).map(|i| row(i) - row(i - 1)).collect();
        for (k, ak) in power_from_differences(row(0), diffs)
            .into_iter()
            .enumerate()
        {
            out[k * h + r] = ak;
        }
    }
    out
}

/// The power coefficients a_0 = b_0, a_k = C(p, k) Δ^k b_0 (k = 1..=p) of one Bernstein
/// polynomial of degree p from b_0 and its p first differences Δb_0 .. Δb_{p-1} (which the
/// caller may have formed more accurately, e.g. as exact double-words): the higher differences
/// by [`forward_differences`], the binomials by [`binom_s`] (exact f64 where f64 is, else
/// enclosed); a factor C(p, p) = 1 is not multiplied in. For verified types every a_k encloses
/// the exact one when the given differences enclose the exact differences.
pub fn power_from_differences<S: Scalar>(b0: S, mut diffs: Vec<S>) -> Vec<S> {
    power_from_differences_in_place(&mut diffs);
    let mut out = Vec::with_capacity(diffs.len() + 1);
    out.push(b0);
    out.extend(diffs);
    out
}

/// [`power_from_differences`] in place, without allocating (callers may pass a stack
/// buffer): the p first differences Δb_0 .. Δb_{p-1} become the power coefficients
/// a_1 .. a_p (a_0 = b_0 is the caller's).
pub fn power_from_differences_in_place<S: Scalar>(diffs: &mut [S]) {
    let p = diffs.len();
    forward_differences(diffs);
    for (i, d) in diffs.iter_mut().enumerate() {
        let k = i + 1;
        if k != p {
            *d = binom_s::<S>(p, k) * d.clone();
        }
    }
}

/// Homogeneous -> Cartesian (the one copy): points of `dim + 1` values (w P, w) become P =
/// (w P) / w when `rational` (one division per coordinate, correctly / outward rounded), else
/// the values (`dim` each) are returned as they are. Works on one point or a row-major list.
pub fn cartesian<S: Scalar>(homogeneous: Vec<S>, dim: usize, rational: bool) -> Vec<S> {
    if !rational {
        return homogeneous;
    }
    homogeneous
        .chunks_exact(dim + 1)
        .flat_map(|h| {
            let w = &h[dim];
            h[..dim].iter().map(move |x| x.clone() / w.clone())
        })
        .collect()
}

#[cfg(test)]
mod tests {
    /// The f64 corner cuts in blocks of four give the one-entry-at-a-time loop's values bit
    /// for bit, at every level (the callback's view) and at the end: 1 to 5 rows, 1 to 40
    /// points, random data and parameters (a block that read an entry after its write would
    /// differ).
    #[test]
    fn blocked_corner_cuts_equal_the_scalar_loop() {
        use rand::Rng;
        let mut r = crate::testkit::gen::rng(3);
        for _ in 0..3000 {
            let h = r.random_range(1..=5usize);
            let np = r.random_range(1..=40usize);
            let t: f64 = r.random_range(0.0..=1.0);
            let b0: Vec<f64> = (0..np * h).map(|_| r.random_range(-1e3..1e3)).collect();
            let mut want = b0.clone();
            let mut want_levels = Vec::new();
            for lvl in 1..np {
                let len = (np - lvl) * h;
                for k in 0..len {
                    want[k] = t * (want[k + h] - want[k]) + want[k];
                }
                want_levels.push(want[..len].to_vec());
            }
            let mut got = b0.clone();
            let mut got_levels = Vec::new();
            super::de_casteljau_levels(&mut got, h, &t, |lvl, b| {
                got_levels.push(b[..(np - lvl) * h].to_vec());
            });
            assert_eq!(got_levels, want_levels, "h {h} points {np} t {t}");
            assert_eq!(got, want);
        }
    }

    #[test]
    fn bernstein_value_matches_de_casteljau() {
        // the binomial table is Pascal's triangle: exact where f64 holds C(n, i) exactly
        for n in 0..=56usize {
            for i in 0..=n {
                let row = n * (n + 1) / 2;
                assert_eq!(
                    super::BINOM_TABLE[row + i],
                    crate::num::binom(n, i),
                    "C({n}, {i})"
                );
            }
        }
        // degrees in the table and above it (the recurrence)
        for n in (0..30usize).chain([63, 64, 65, 80]) {
            let c: Vec<f64> = (0..=n).map(|i| ((i * 7919) % 13) as f64 - 6.3).collect();
            let scale: f64 = c.iter().map(|x| x.abs()).sum::<f64>().max(1.0);
            for k in 0..=64 {
                let t = k as f64 / 64.0;
                let (a, b) = (
                    super::bernstein_value(&c, t),
                    super::de_casteljau_eval(&c, &t),
                );
                assert!((a - b).abs() <= 1e-12 * scale, "n {n} t {t}: {a} vs {b}");
                // the fused pair: the same value and the hodograph's (the derivative / n)
                if n >= 1 {
                    let d = hodograph(&c);
                    let (pa, pd) = super::bernstein_value_pair(&c, &d, t);
                    let want_d = super::de_casteljau_eval(&d, &t);
                    let dscale: f64 = d.iter().map(|x| x.abs()).sum::<f64>().max(1.0);
                    assert!(
                        (pa - b).abs() <= 1e-12 * scale,
                        "pair n {n} t {t}: {pa} vs {b}"
                    );
                    assert!((pd - want_d).abs() <= 1e-12 * dscale, "pair' n {n} t {t}");
                }
            }
        }
    }

    use super::*;

    /// The O(n) value in `Mr` and in `Ddi` encloses the exact value (rationals) at f64 points
    /// on both sides of 1/2, at degrees in the binomial table and above it (78, the F of a
    /// degree-40 rational span), and is about as narrow as de Casteljau's in `Mr`.
    #[test]
    fn bernstein_value_s_encloses_exact_values() {
        use crate::num::ddi::Ddi;
        use crate::num::exact::Exact;
        use crate::num::mr::Mr;
        use rand::Rng;
        let mut r = crate::testkit::gen::rng(11);
        for n in [1usize, 2, 5, 19, 40, 56, 57, 78] {
            for _ in 0..6 {
                let c: Vec<f64> = (0..=n).map(|_| r.random_range(-1.0..1.0) * 3.0).collect();
                let t = r.random_range(0.0..1.0);
                let exact = (0..=n).fold(Exact::of(0.0), |acc, i| {
                    let b = (1..=i).fold(Exact::of(1.0), |a, k| {
                        a * Exact::of((n + 1 - k) as f64) / Exact::of(k as f64)
                    });
                    let mut term = b * Exact::of(c[i]);
                    for _ in 0..i {
                        term = term * Exact::of(t);
                    }
                    for _ in 0..n - i {
                        term = term * (Exact::of(1.0) - Exact::of(t));
                    }
                    acc + term
                });
                let mr: Vec<Mr> = c.iter().map(|&x| Mr::from_f64(x)).collect();
                let dd: Vec<Ddi> = c.iter().map(|&x| Ddi::from_f64(x)).collect();
                let v = bernstein_value_s(&mr, t).to_interval();
                let w = bernstein_value_s(&dd, t).to_interval();
                for (name, iv) in [("Mr", v), ("Ddi", w)] {
                    assert!(
                        !exact.gt_f64(iv.sup())
                            && exact.cmp_f64(iv.inf()).is_some_and(|o| o.is_ge()),
                        "{name} n={n} t={t}: [{:e}, {:e}]",
                        iv.inf(),
                        iv.sup()
                    );
                }
                let dc = de_casteljau_eval(&mr, &Mr::from_f64(t)).to_interval();
                assert!(
                    v.wid() <= 16.0 * dc.wid().max(f64::EPSILON),
                    "n={n} t={t}: width {:e} vs de Casteljau {:e}",
                    v.wid(),
                    dc.wid()
                );
            }
        }
    }

    #[test]
    fn power_form_hodograph_and_de_casteljau_agree() {
        let c = [1.0, -2.0, 4.0, 0.5];
        let a = bernstein_to_power(&c, 1);
        // p = 3: a = (b0, 3 Δb0, 3 Δ^2 b0, Δ^3 b0)
        assert_eq!(a, vec![1.0, -9.0, 27.0, -18.5]);
        for i in 0..=8 {
            let t = i as f64 / 8.0;
            let v = de_casteljau_eval(&c, &t);
            assert!((crate::num::horner(&a, &t) - v).abs() < 1e-13);
            let (l, r) = de_casteljau_split(&c, 1, &t);
            assert_eq!(l[3], r[0]);
            assert!((l[3] - v).abs() < 1e-13);
        }
        assert_eq!(hodograph(&c), vec![-9.0, 18.0, -10.5]);
        assert_eq!(hodograph(&[2.0]), vec![0.0]);
        assert_eq!(cartesian(vec![2.0, 4.0, 3.0, 1.0], 1, true), vec![0.5, 3.0]);
    }
}
