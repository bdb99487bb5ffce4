//! Exact values of a span's Bézier form in integers (fraction-free Boehm insertion, NURBS Book
//! A5.1; thesis eq. 4.12, on the kernels of [`crate::num::ffint`]): the certificate's exact
//! Bernstein coefficients, and exact curve values at knots, with which the double-double
//! Bézier segments get exact end points where the curve's value there is a double
//! ([`snap_exact_ends`]).

use crate::num::ffint::{clamp_span_ints, clamp_span_ints_ends, dyadic_ints, dyadic_parts, FfInt};
use crate::num::{ulp, Ddi};
use crate::spline::curve::NurbsCurve;
use num_bigint::BigInt;

/// The integer coefficients of the certificate's exact Bernstein rule for any span k:
/// f_i = sign a_i - t w_i of the span's homogeneous Bézier points (a_i, w_i), times one
/// positive factor, without a
/// gcd. f is linear in the homogeneous rows, so it is the Bézier form of the single row
/// g_i = w_i (sign P_ij - t) of the span's local control points (exact dyadic products). That
/// row and the span's 2p + 2 local knots are brought to integers (each over one common power
/// of two: the knots' ratios do not change), and the span is clamped at both ends by
/// Boehm's insertion as [`crate::spline::bspline`]'s `clamp_left` does it (NURBS Book A5.1;
/// thesis eq. 4.12), fraction-free: at insertion level l the cut points become
/// ((t_b - u) q_i + (u - t_a) q_{i+1}) / (t_b - t_a), and instead of dividing, every point of
/// the level is multiplied by the product of the level's denominators t_b - t_a > 0 (the cut
/// ones by the product of the others), so all points keep one common positive denominator,
/// which is dropped; a common power of two is divided out after each level. (As the
/// certificate's `split_integer` does for de Casteljau. The rationals of `HSpline<Exact>`,
/// reduced by a gcd after every operation, cost ~100x more on a cubic span with 53-bit knots.) `None` for a
/// non-positive denominator (not a valid span) or undefined data.
pub(crate) fn bezier_coefficients_fraction_free(
    c: &NurbsCurve,
    k: usize,
    j: usize,
    sign: f64,
    t: f64,
) -> Option<Vec<BigInt>> {
    // (in i128 first, every operation checked: short data such as small integer knots and
    // few-bit control values never needs more; an overflow, or an invalid span, repeats the
    // same steps in BigInt)
    if let Some(q) = bezier_coefficients_ff::<i128>(c, k, j, sign, t) {
        return Some(q.into_iter().map(BigInt::from).collect());
    }
    bezier_coefficients_ff::<BigInt>(c, k, j, sign, t)
}

/// [`bezier_coefficients_fraction_free`] in the integer type `T` (`None` also where an
/// operation overflows `T`).
pub(crate) fn bezier_coefficients_ff<T: FfInt>(
    c: &NurbsCurve,
    k: usize,
    j: usize,
    sign: f64,
    t: f64,
) -> Option<Vec<T>> {
    let p = c.degree();
    // (the same coefficients as `span_rows_integer(..).minus(t)`, up to a positive factor,
    // but from one clamped row instead of two: the rule runs on every straddle, and the
    // two-row form cost the ties ~15% more certification time)
    // g_i = w_i (sign P_ij - t): (sign P_ij, t) over one power of two, the difference times
    // w_i (an integer over its own power of two), then all over the smallest one
    let mut q: Vec<T> = Vec::with_capacity(p + 1);
    let mut exps: smallvec::SmallVec<[i64; 8]> = smallvec::SmallVec::new();
    let (mt, et) = dyadic_parts(t)?;
    for i in k - p..=k {
        // (sign P_ij - t over the smaller of the two exponents, times the weight's integer)
        let (mx, ex) = dyadic_parts(sign * c.control_point(i)[j])?;
        let (mw, ew) = dyadic_parts(c.weight(i))?;
        let e_d = if mx == 0 {
            et
        } else if mt == 0 {
            ex
        } else {
            ex.min(et)
        };
        let x = T::from_i64(mx).shl((ex - e_d).max(0) as u64)?;
        let y = T::from_i64(mt).shl((et - e_d).max(0) as u64)?;
        q.push(x.sub(&y)?.mul(&T::from_i64(mw))?);
        exps.push(e_d + ew);
    }
    let e0 = *exps.iter().min()?;
    for (x, e) in q.iter_mut().zip(&exps) {
        *x = x.shl((e - e0) as u64)?;
    }
    clamp_span_ints(p, &c.knots()[k - p..=k + p + 1], &mut [&mut q])?;
    Some(q)
}

/// Which of the candidate end values `cands` = (i, j, h) (i = 0: the value of span k's piece
/// of C_j at u_k, i = p: at u_{k+1}) are exactly the doubles h, for a non-rational curve: the
/// span's local control values of every coordinate (each row over its own power of two 2^e_j)
/// and a row of ones (the weights) clamped at both ends together, fraction-free
/// ([`clamp_span_ints`]: every row times one common positive factor F), so the Bézier end
/// points are A_ij 2^e_j / W_i with W_i = F; C_j = h = m 2^e iff A_ij 2^e_j = m 2^e W_i, compared
/// over the smaller exponent. `None` where T overflows or the data are not valid.
fn exact_end_values<T: FfInt>(
    c: &NurbsCurve,
    k: usize,
    cands: &[(usize, usize, f64)],
) -> Option<[bool; 8]> {
    let (p, d) = (c.degree(), c.dim());
    // Only the rows of the coordinates asked about, and only the clamps of the ends asked about
    // (`clamp_span_ints_ends`: an end's point needs that end's clamp alone); every row and
    // the factor get the same positive factors, so the comparisons below do not change.
    let wanted = |j: usize| cands.iter().any(|x| x.1 == j);
    let ends = [0, p].map(|i| cands.iter().any(|x| x.0 == i));
    // (row of coordinate j at `slot[j]`)
    let mut slot: smallvec::SmallVec<[usize; 8]> = smallvec::smallvec![usize::MAX; d];
    let mut rows: Vec<Vec<T>> = Vec::with_capacity(d);
    let mut exps: Vec<i64> = Vec::with_capacity(d);
    for j in (0..d).filter(|&j| wanted(j)) {
        let (row, e) = dyadic_ints::<T>((k - p..=k).map(|i| c.control_point(i)[j]))?;
        slot[j] = rows.len();
        rows.push(row);
        exps.push(e);
    }
    // (the weights' row of ones is a constant row: clamped as the common factor alone,
    // `clamp_span_ints_ends`)
    let mut f = T::from_i64(1);
    {
        let mut refs: Vec<&mut [T]> = rows.iter_mut().map(|r| r.as_mut_slice()).collect();
        clamp_span_ints_ends(
            p,
            &c.knots()[k - p..=k + p + 1],
            &mut refs,
            Some(&mut f),
            ends,
        )?;
    }
    let mut out = [false; 8];
    for (o, &(i, j, h)) in out.iter_mut().zip(cands) {
        let (m, e) = dyadic_parts(h)?;
        let r = *slot.get(j)?;
        let ej = exps[r];
        let e0 = ej.min(e);
        let lhs = rows[r][i].shl((ej - e0) as u64)?;
        let rhs = f.mul(&T::from_i64(m))?.shl((e - e0) as u64)?;
        *o = lhs.is_eq(&rhs);
    }
    Some(out)
}

/// Makes the end points of span k's double-double Bézier segment exact where they are exactly
/// doubles: `pts` are the p + 1 points of a non-rational curve (dim values each, row-major),
/// enclosures of the exact ones. An end value whose enclosure holds the double h = hi and
/// nothing else within 2^-40 ulps of h (lo = 0, a radius of a few subnormals: the data were
/// exact and only the operations' underflow terms widened it) is checked exactly
/// (a control point at a knot of multiplicity >= p, else [`exact_end_values`] in i128) and
/// replaced by h where C_j there is
/// h: the enclosure loses nothing, and an extremum at an unclamped end or a knot that is
/// exactly a double (the end value (P0 + P1) / 2 of a uniform quadratic) is then bound and
/// attained value at once instead of straddled. Rational segments (homogeneous points w C,
/// whose end points need not be doubles) are left as they are.
pub fn snap_exact_ends(c: &NurbsCurve, k: usize, pts: &mut [Ddi]) {
    let (p, d) = (c.degree(), c.dim());
    if c.is_rational() || pts.len() != (p + 1) * d {
        return;
    }
    let mut cands = [(0usize, 0usize, 0.0f64); 8];
    let mut n = 0;
    for i in [0, p] {
        for j in 0..d {
            let v = pts[i * d + j];
            let h = v.hi();
            let near = v.lo() == 0.0
                && v.rad() > 0.0
                && h.is_finite()
                && v.rad() <= ulp(h) * (1.0 / 1_099_511_627_776.0); // 2^-40
            if near && n < cands.len() {
                cands[n] = (i, j, h);
                n += 1;
            }
        }
    }
    if n == 0 {
        return;
    }
    // At a knot of multiplicity >= p the piece's end value is a control point (NURBS Book
    // eq. 2.5 / A5.1: the clamped span's end point is P_{k-p} at u_k, P_k at u_{k+1}): compared
    // directly. Otherwise the integer clamp, in i128 only (data long enough to overflow it
    // are left as they are: exact knot values of such data are rare, and big integers cost
    // more than the straddle they would save).
    let kn = c.knots();
    let control = |i: usize, j: usize| {
        let (u, at) = if i == 0 {
            (kn[k], k - p)
        } else {
            (kn[k + 1], k)
        };
        (crate::spline::knots::multiplicity(kn, u) >= p).then(|| c.control_point(at)[j])
    };
    let mut rest = [(0usize, 0usize, 0.0f64); 8];
    let mut m = 0;
    for &(i, j, h) in &cands[..n] {
        match control(i, j) {
            Some(x) if x == h => pts[i * d + j] = Ddi::exact(h),
            Some(_) => {}
            None => {
                rest[m] = (i, j, h);
                m += 1;
            }
        }
    }
    let rest = &rest[..m];
    if rest.is_empty() {
        return;
    }
    let Some(exact) = exact_end_values::<i128>(c, k, rest) else {
        return;
    };
    for (&(i, j, h), &x) in rest.iter().zip(&exact) {
        if x {
            pts[i * d + j] = Ddi::exact(h);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::{Exact, Scalar};
    use crate::spline::bspline::HSpline;
    use crate::spline::eval::CurveEval;
    use rand::{Rng, SeedableRng};

    /// Snapped end points are the exact values of the span's piece at its knots (exact
    /// rational de Boor), and every other end point still encloses its exact value: random
    /// non-rational splines of degree 1..=5, small integer knots and few-bit control values
    /// (whose knot values are often doubles, so snapping happens), unclamped and clamped, with
    /// interior knots of every multiplicity.
    #[test]
    fn snapped_ends_are_the_exact_knot_values() {
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(41);
        let (mut snapped, mut checked, mut compared) = (0, 0, 0);
        for it in 0..400 {
            let p = r.random_range(1..=5usize);
            let n = p + r.random_range(0..5usize);
            let mut kn: Vec<f64> = (0..n + p + 2)
                .map(|_| r.random_range(0..8) as f64)
                .collect();
            kn.sort_by(f64::total_cmp);
            if it % 3 == 0 {
                // clamped ends
                for i in 0..=p {
                    kn[i] = kn[0];
                    let m = kn.len() - 1;
                    kn[m - i] = kn[m];
                }
            }
            let d = r.random_range(1..=3usize);
            let pts: Vec<Vec<f64>> = (0..=n)
                .map(|_| {
                    (0..d)
                        .map(|_| r.random_range(-512i32..512) as f64 / 8.0)
                        .collect()
                })
                .collect();
            let Ok(c) = NurbsCurve::new(p, kn.clone(), pts, None) else {
                continue;
            };
            let h = HSpline::<Ddi>::from_curve(&c);
            let ex = CurveEval::<Exact>::new(&c, 0);
            for k in p..=n {
                if kn[k] >= kn[k + 1] {
                    continue;
                }
                let before = h.bezier_segment(k).pts;
                let mut pts = before.clone();
                snap_exact_ends(&c, k, &mut pts);
                for (i, u) in [(0, kn[k]), (p, kn[k + 1])] {
                    for j in 0..d {
                        let exact = ex.coord_derivs_in_span(k, &Exact::of(u), 0, j)[0].clone();
                        let v = pts[i * d + j];
                        let iv = v.to_interval();
                        assert!(
                            exact.cmp_f64(iv.inf()).unwrap().is_ge()
                                && exact.cmp_f64(iv.sup()).unwrap().is_le(),
                            "p {p} k {k} i {i} j {j} {kn:?}"
                        );
                        if v != before[i * d + j] {
                            assert_eq!(exact.cmp_f64(v.hi()), Some(std::cmp::Ordering::Equal));
                            snapped += 1;
                        }
                        checked += 1;
                        // the exact comparison itself, in both integer types, against the
                        // rational value: at the nearest double and its two neighbours
                        let x = before[i * d + j].hi();
                        for h in [x.next_down(), x, x.next_up()] {
                            let want = exact.cmp_f64(h) == Some(std::cmp::Ordering::Equal);
                            let big = exact_end_values::<BigInt>(&c, k, &[(i, j, h)]).unwrap()[0];
                            assert_eq!(big, want, "p {p} k {k} i {i} j {j} h {h:e}");
                            if let Some(small) = exact_end_values::<i128>(&c, k, &[(i, j, h)]) {
                                assert_eq!(small[0], want);
                            }
                            compared += want as usize;
                        }
                    }
                }
            }
        }
        assert!(
            snapped > 200 && checked > 1000 && compared > 500,
            "{snapped} of {checked}, {compared}"
        );
    }
}
