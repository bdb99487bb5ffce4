//! Root-isolating fast path for one rational quadratic Bézier segment (a conic arc: a single
//! clamped rational quadratic, or a span of a rational quadratic spline), the rational
//! counterpart of [`super::single`]'s proof for polynomial cubics, whose derivative is a
//! quadratic too.
//!
//! For one coordinate x(t) = X(t) / W(t), t in [0, 1], with homogeneous Bernstein coefficients
//! X_i = w_i x_i and W_i > 0 (i = 0, 1, 2; enclosed in [`Ddi`]), the quotient rule gives
//! x' = N / W^2 with N = X' W - X W'. The cubic terms of N cancel, and N / 2 has the Bernstein
//! coefficients (Farin, *Curves and Surfaces for CAGD*, the derivative of a rational Bézier
//! curve, here for degree 2)
//!
//!   e_0 = X_1 W_0 - X_0 W_1,   e_1 = (X_2 W_0 - X_0 W_2) / 2,   e_2 = X_2 W_1 - X_1 W_2
//!
//! (N(0) = 2 (X_1 - X_0) W_0 - 2 X_0 (W_1 - W_0) = 2 e_0, likewise N(1) = 2 e_2, and the value
//! at t = 1/2 fixes e_1; `conic_numerator_matches_the_quotient_rule` checks them in exact
//! arithmetic). Since W^2 > 0, x' has the sign of q = N / 2, a quadratic: the steps of
//! [`super::single`] apply to q in place of the cubic's x', with the value x = X / W in place
//! of the polynomial's:
//!
//! 1. Power form q = β_0 + β_1 t + β_2 t^2, β_0 = e_0, β_1 = 2 (e_1 - e_0),
//!    β_2 = e_2 - 2 e_1 + e_0: in f64 from the enclosures' centres, with one a-priori bound
//!    for the three coefficients' errors ([`numerator_f64`]), as the f64 filter
//!    [`Deriv::from_coefficients`]; enclosed in `Ddi` only where the filter leaves a sign open.
//! 2. f64 root estimates of q and the test points around them ([`test_points`]); the sign of
//!    q proven at each (the filter, else a `Ddi` Horner enclosure excluding 0), or give up.
//! 3. Root counting: q is a non-zero polynomial of degree <= 2, so at most 2 roots. If at
//!    least one interval between test points shows a sign change, each such interval holds
//!    exactly one root and every other interval none (as in `single`'s step 4, with R = 2);
//!    with no sign change a proven negative discriminant e_1^2 - e_0 e_2 is needed (no real
//!    root), else give up.
//! 4. So max x = max(x(0), x(1), max over the intervals where q changes from + to -). Over
//!    such a bracket B with midpoint m and radius r, the mean value theorem gives
//!    |x(t) - x(m)| <= r max_B |x'| <= 2 r (|q(m)| + r max |q'|) / W_min^2, with |q(m)| <=
//!    |y(m)| + err (the filter), max |q'| over [0, 1] <= |β_1| + 2 |β_2|, and W >= W_min =
//!    min_i W_i on [0, 1] (a convex combination of the W_i). x(m) = X(m) / W(m) enclosed in
//!    `Ddi` ([`value_at`]) is a value the curve attains (inner bound). With r = 2^-40 the correction is
//!    ~2^-80 of the scale times (max W / min W)^2: about one ulp unless the weights differ by
//!    many orders of magnitude, where the caller's gap test sends the curve to the general
//!    path.
//!
//! No near tie is settled here (the cubic's exact comparison has no rational counterpart
//! yet): a bound that the attained value leaves open goes to the full certification, as on
//! the general path. Every step is proven, rounding included; where one is not, the caller
//! falls back.

use super::single::{extremum, sign, square_below, test_points, Deriv, RawSide};
use super::CandidateKind;
use crate::num::ddi::{dist_up, up, Ddi, U1};
use crate::num::horner;

/// One coordinate of a rational quadratic Bézier segment over the parameter interval [a, b].
pub(crate) struct ConicSeg {
    /// the homogeneous coefficients X_0, X_1, X_2 (w_i x_i), enclosed
    pub x: [Ddi; 3],
    /// the weights' coefficients W_0, W_1, W_2, enclosed
    pub w: [Ddi; 3],
    /// the end values x(0) = X_0 / W_0 and x(1) = X_2 / W_2, enclosed (exact where known)
    pub ends: [Ddi; 2],
    pub a: f64,
    pub b: f64,
    /// what the ends are (domain end, knot)
    pub end_kinds: [CandidateKind; 2],
}

/// x = X / W at the double t, enclosed: X(t) and W(t) by Horner's rule with `Ddi`'s fused
/// step on the power forms (a_0 + a_1 t + a_2 t^2 with a_1 = 2 (c_1 - c_0) and
/// a_2 = c_2 - 2 c_1 + c_0: Farin, *Curves and Surfaces for CAGD*, monomial form of a Bézier
/// curve), every operation enclosing its exact result.
fn value_at(x: &[Ddi; 3], w: &[Ddi; 3], t: f64) -> Ddi {
    let power = |c: &[Ddi; 3]| {
        let d0 = c[1] - c[0];
        let d1 = c[2] - c[1];
        [c[0], d0 * Ddi::exact(2.0), d1 - d0]
    };
    let t = Ddi::exact(t);
    horner(&power(x), &t) / horner(&power(w), &t)
}

/// The f64 power coefficients b_k of q = N / 2 from the centres of the enclosures X_i, W_i,
/// and a bound E_b with |β_k - b_k| <= E_b for the exact β_k (module docs, step 1).
///
/// Error bound. Write X_a = X̂_a + ξ_a, W_b = Ŵ_b + ζ_b with X̂, Ŵ the centres' leading parts
/// and |ξ_a| <= ρ_a = |lo| + rad, |ζ_b| <= ω_b. Then |X_a W_b - X̂_a Ŵ_b| <= |X̂_a| ω_b + ρ_a
/// (|Ŵ_b| + ω_b) <= δ = X ω + ρ (W + ω) with the maxima X, W, ρ, ω over the coefficients;
/// the product p_ab = fl(X̂_a Ŵ_b) errs by at most U1 |p_ab| + η (u = 2^-53, U1 >= u / (1 - u),
/// η = 2^-1075 an underflow), a difference by U1 times its result, a halving by η at most.
/// So each ẽ_k (e_0 = X_1 W_0 - X_0 W_1 from p_10 - p_01, e_1 half of p_20 - p_02, e_2 from
/// p_21 - p_12) is within
///
///   E_e = 6 δ + U1 (|p_10| + |p_01| + |p_20| + |p_02| + |p_21| + |p_12|)
///         + U1 (|ẽ_0| + |ẽ_1| + |ẽ_2|) + 2^-1022
///
/// of e_k (2^-1022 covers every η). With t_1 = fl(ẽ_1 - ẽ_0), b_1 = 2 t_1 (exact),
/// t_2 = fl(ẽ_2 - 2 ẽ_1), b_2 = fl(t_2 + ẽ_0): |β_0 - b_0| <= E_e,
/// |β_1 - b_1| <= 2 (2 E_e + U1 |t_1|), |β_2 - b_2| <= 4 E_e + U1 (|t_2| + |b_2|), all at most
/// E_b = 4 E_e + 2 U1 (|t_1| + |t_2| + |b_2|). Both are formulas of Lemma B of
/// [`crate::num::ddi`], bounded by `up` (δ by its own `up`, a nonnegative f64 after it).
/// Tested against exact arithmetic (`numerator_bound_holds`).
fn numerator_f64(x: &[Ddi; 3], w: &[Ddi; 3]) -> ([f64; 3], f64) {
    let xh = x.map(|v| v.hi());
    let wh = w.map(|v| v.hi());
    let radius = |v: &Ddi| v.lo().abs() + v.rad();
    let big = |v: &[f64; 3]| v[0].abs().max(v[1].abs()).max(v[2].abs());
    let (xm, wm) = (big(&xh), big(&wh));
    let rx = x.iter().fold(0.0f64, |m, v| m.max(radius(v)));
    let rw = w.iter().fold(0.0f64, |m, v| m.max(radius(v)));
    let delta = up(xm * rw + rx * (wm + rw));
    let p = |a: usize, b: usize| xh[a] * wh[b];
    let (p10, p01, p20, p02, p21, p12) = (p(1, 0), p(0, 1), p(2, 0), p(0, 2), p(2, 1), p(1, 2));
    let e0 = p10 - p01;
    let e1 = 0.5 * (p20 - p02);
    let e2 = p21 - p12;
    let t1 = e1 - e0;
    let t2 = e2 - 2.0 * e1;
    let b = [e0, 2.0 * t1, t2 + e0];
    let ps = p10.abs() + p01.abs() + p20.abs() + p02.abs() + p21.abs() + p12.abs();
    let es = e0.abs() + e1.abs() + e2.abs();
    let ee = up(6.0 * delta + U1 * ps + U1 * es + f64::MIN_POSITIVE);
    let eb = up(4.0 * ee + 2.0 * U1 * (t1.abs() + t2.abs() + b[2].abs()));
    (b, eb)
}

/// The exact power coefficients β of q enclosed in `Ddi` (module docs, step 1), and the
/// coefficients e_0, e_1, e_2: the filter's fallback.
fn numerator_ddi(x: &[Ddi; 3], w: &[Ddi; 3]) -> ([Ddi; 3], [Ddi; 3]) {
    let [x0, x1, x2] = *x;
    let [w0, w1, w2] = *w;
    let two = Ddi::exact(2.0);
    let e0 = x1 * w0 - x0 * w1;
    let e1 = (x2 * w0 - x0 * w2) * Ddi::exact(0.5);
    let e2 = x2 * w1 - x1 * w2;
    ([e0, (e1 - e0) * two, e2 - e1 * two + e0], [e0, e1, e2])
}

/// Both sides of x over the segment (module docs), `[max side, min side]` as sign-adjusted
/// [`RawSide`]s (the min side is the max side of -x): upper bound, attained value, witness
/// and candidates; a side not in `need` comes back without its brackets and must not be used.
/// `None` where a step is not proven (then the caller falls back). The caller checks the gaps.
pub(crate) fn conic_sides(seg: &ConicSeg, need: [bool; 2]) -> Option<[RawSide; 2]> {
    let [w0, w1, w2] = seg.w;
    // W_min > 0: a lower bound of W on [0, 1] (a NaN lower end fails the test)
    let wmin = w0.lower_end().min(w1.lower_end()).min(w2.lower_end());
    if !(wmin > 0.0 && wmin.is_finite()) {
        return None;
    }
    let (b, eb) = numerator_f64(&seg.x, &seg.w);
    let deriv = Deriv::from_coefficients(b, eb);
    // (the `Ddi` coefficients only where the filter leaves a sign open)
    let mut exact: Option<([Ddi; 3], [Ddi; 3])> = None;
    let mut proven = |t: f64| -> Option<bool> {
        let y = deriv.approx(t);
        if y.abs() > deriv.err() {
            // |q(t) - y| <= err < |y|: q(t) has the sign of y
            return Some(y > 0.0);
        }
        let (beta, _) = exact.get_or_insert_with(|| numerator_ddi(&seg.x, &seg.w));
        sign(horner(&beta[..], &Ddi::exact(t)))
    };
    let (z, k) = test_points(&deriv);
    let mut s = [false; 6];
    let mut derivative_evaluations = 0;
    for (i, si) in s.iter_mut().enumerate().take(k) {
        derivative_evaluations += 1;
        *si = proven(z[i])?;
    }
    let changes = (1..k).filter(|&i| s[i] != s[i - 1]).count();
    // (step 3: with no sign change, two roots could hide in one interval unless there are
    // no real roots at all)
    if changes == 0 {
        let (_, [e0, e1, e2]) = exact.unwrap_or_else(|| numerator_ddi(&seg.x, &seg.w));
        if sign(e1 * e1 - e0 * e2) != Some(false) {
            return None;
        }
    }
    let mut out = [RawSide::new(), RawSide::new()];
    // (both ends are values of the curve: the segment is a continuous piece)
    RawSide::ends_into(&mut out, (seg.a, seg.b), seg.ends, seg.end_kinds);
    // max |q'| over [0, 1] <= |β_1| + 2 |β_2| <= |b_1| + 2 |b_2| + 3 E_b (Lemma B)
    let m1 = up(b[1].abs() + 2.0 * b[2].abs() + 3.0 * eb);
    // W_min^2 from below
    let w2min = square_below(wmin);
    for i in 1..k {
        // + to -: a strict local maximum, which bounds the max side only; - to + a strict
        // local minimum, the min side's (module docs, step 4)
        let is_max = s[i - 1] && !s[i];
        if s[i] == s[i - 1] || !need[if is_max { 0 } else { 1 }] {
            continue;
        }
        let (t0, t1) = (z[i - 1], z[i]);
        let m = (t0 + 0.5 * (t1 - t0)).clamp(t0, t1);
        let r = dist_up(m, t0).max(dist_up(t1, m));
        // |q| over the bracket <= |y(m)| + err + r m1; every step rounded upward (`up` of one
        // rounded operation on nonnegative operands bounds its exact result)
        derivative_evaluations += 1;
        let qb = up(up(deriv.approx(m).abs() + deriv.err()) + up(m1 * r));
        let corr = up(up(2.0 * up(qb * r)) / w2min);
        let xm = value_at(&seg.x, &seg.w, m);
        let e = extremum(seg.a, seg.b, t0, t1, true, CandidateKind::Critical);
        if is_max {
            out[0].bracket(xm, corr, e);
        } else {
            out[1].bracket(-xm, corr, e);
        }
    }
    out[0].derivative_evaluations = derivative_evaluations;
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::exact::Exact;
    use crate::num::Scalar;

    /// `numerator_f64`'s bound against exact arithmetic: for enclosed X_i, W_i (exact values
    /// drawn inside the enclosures, radii 0, up to 2^-90 or up to 2^-40 relative; magnitudes
    /// 2^-80 .. 2^100; near-cancelling coefficients, X_1 W_0 close to X_0 W_1) every f64
    /// coefficient b_k lies within E_b of the exact β_k, and the bound is not vacuous (errors
    /// of more than E_b / 64 occur); the f64 filter on them (`Deriv::from_coefficients`)
    /// errs by at most its bound at t = 0, 1/2, 1 and a random t. Fails with E_b = E_e (the
    /// cancellation in β_2 exceeds it), without the input radii's term δ, and with the filter's
    /// coefficient term dropped.
    #[test]
    fn numerator_bound_holds() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(12);
        let ex = Exact::from_f64;
        let mut worst = 0.0f64;
        for case in 0..20_000 {
            let sx = 2f64.powi(rng.random_range(-80..=80));
            let sw = 2f64.powi(rng.random_range(-20..=20));
            let mut xv: [f64; 3] = std::array::from_fn(|_| rng.random_range(-1.0..1.0) * sx);
            let wv: [f64; 3] = std::array::from_fn(|_| rng.random_range(0.25..4.0) * sw);
            if case % 3 == 0 {
                // near cancellation: x_1 / w_1 close to x_0 / w_0, x_2 / w_2 to both
                let c = xv[0] / wv[0];
                xv[1] = c * wv[1] * (1.0 + rng.random_range(-1e-12..1e-12));
                xv[2] = c * wv[2] * (1.0 + rng.random_range(-1e-9..1e-9));
            }
            let wide = case % 2 == 1;
            // (radii far below the rounding errors, as from double-double insertion, or
            // above them, where the input term of the bound dominates)
            let rel = if case % 4 == 1 { 90 } else { 40 };
            // an enclosure of each value and an exact value inside it
            let mut draw = |v: f64| -> (Ddi, Exact) {
                if !wide {
                    return (Ddi::exact(v), ex(v));
                }
                let lo = v * 2f64.powi(-60) * rng.random_range(-1.0..1.0);
                let rad = (v * 2f64.powi(-rel)).abs() * rng.random_range(0.0..1.0);
                let d = Ddi::new(v, lo, rad);
                let (h, l, r) = d.parts();
                let theta = rng.random_range(-1.0..1.0f64);
                (d, ex(h) + ex(l) + ex(theta) * ex(r))
            };
            let xs: [(Ddi, Exact); 3] = std::array::from_fn(|i| draw(xv[i]));
            let ws: [(Ddi, Exact); 3] = std::array::from_fn(|i| draw(wv[i]));
            let (b, eb) = numerator_f64(&xs.clone().map(|v| v.0), &ws.clone().map(|v| v.0));
            let (x, w) = (xs.map(|v| v.1), ws.map(|v| v.1));
            let e0 = x[1].clone() * w[0].clone() - x[0].clone() * w[1].clone();
            let e1 = (x[2].clone() * w[0].clone() - x[0].clone() * w[2].clone()) * ex(0.5);
            let e2 = x[2].clone() * w[1].clone() - x[1].clone() * w[2].clone();
            let beta = [
                e0.clone(),
                (e1.clone() - e0.clone()) * ex(2.0),
                e2 - e1 * ex(2.0) + e0,
            ];
            for (bk, bb) in beta.iter().zip(b) {
                let d = bk.clone() - ex(bb);
                let above = (d.clone() - ex(eb)).signum();
                let below = (d.clone() + ex(eb)).signum();
                assert!(
                    above != Some(std::cmp::Ordering::Greater)
                        && below != Some(std::cmp::Ordering::Less),
                    "case {case}: coefficient {bb:e} off by more than {eb:e}"
                );
                worst = worst.max(d.to_f64().abs() / eb);
            }
            // the filter built on them: |q(t) - y(t)| <= err at t in [0, 1]
            let deriv = Deriv::from_coefficients(b, eb);
            for t in [0.0, 1.0, rng.random_range(0.0..1.0), 0.5] {
                let q = beta[0].clone()
                    + beta[1].clone() * ex(t)
                    + beta[2].clone() * ex(t) * ex(t);
                let d = q - ex(deriv.approx(t));
                assert!(
                    d.cmp_f64(deriv.err()) != Some(std::cmp::Ordering::Greater)
                        && d.cmp_f64(-deriv.err()) != Some(std::cmp::Ordering::Less),
                    "case {case}: the filter errs by more than {:e} at {t}",
                    deriv.err()
                );
            }
        }
        assert!(worst > 1.0 / 64.0, "the bound is loose beyond use: {worst}");
    }

    /// The Bernstein coefficients e_0, e_1, e_2 of N / 2 = (X' W - X W') / 2 (module docs)
    /// against the quotient rule in exact rational arithmetic, at t = 0, 1/3, 1/2, 0.7, 1, for
    /// random integer and fractional coefficients.
    #[test]
    fn conic_numerator_matches_the_quotient_rule() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        for _ in 0..500 {
            let xs: [f64; 3] = std::array::from_fn(|_| rng.random_range(-8.0..8.0f64).round() / 4.0);
            let ws: [f64; 3] = std::array::from_fn(|_| rng.random_range(1.0..8.0f64).round() / 2.0);
            let ex = |v: f64| Exact::from_f64(v);
            let [x0, x1, x2] = xs.map(ex);
            let [w0, w1, w2] = ws.map(ex);
            let e0 = x1.clone() * w0.clone() - x0.clone() * w1.clone();
            let e1 = (x2.clone() * w0.clone() - x0.clone() * w2.clone()) * ex(0.5);
            let e2 = x2.clone() * w1.clone() - x1.clone() * w2.clone();
            for t in [0.0, 1.0 / 3.0, 0.5, 0.7, 1.0] {
                let t = ex(t);
                let u = ex(1.0) - t.clone();
                let bern = |c: [Exact; 3]| {
                    c[0].clone() * u.clone() * u.clone()
                        + ex(2.0) * c[1].clone() * u.clone() * t.clone()
                        + c[2].clone() * t.clone() * t.clone()
                };
                // derivative of a quadratic Bernstein form: 2 ((c_1 - c_0) u + (c_2 - c_1) t)
                let dbern = |c: [Exact; 3]| {
                    ex(2.0)
                        * ((c[1].clone() - c[0].clone()) * u.clone()
                            + (c[2].clone() - c[1].clone()) * t.clone())
                };
                let xs = [x0.clone(), x1.clone(), x2.clone()];
                let ws = [w0.clone(), w1.clone(), w2.clone()];
                let n = dbern(xs.clone()) * bern(ws.clone()) - bern(xs) * dbern(ws);
                let q = bern([e0.clone(), e1.clone(), e2.clone()]);
                let diff = n - ex(2.0) * q;
                assert_eq!(diff.signum(), Some(std::cmp::Ordering::Equal), "N / 2 differs");
            }
        }
    }
}
