//! Root-isolating fast path of the `bezier` strategy for one polynomial Bézier segment of
//! degree 2 or 3: a single clamped segment without weights (the common 2-D cubic Bézier), and
//! the spans of non-rational quadratic / cubic splines (segments from double-double knot
//! insertion, `HSpline::<Ddi>::bezier_segment`).
//!
//! For one coordinate x(t) = sum_i c_i B_i^p(t), t in [0, 1] (the curve's image does not
//! depend on the parametrisation, so the local parameter is used throughout), with control
//! values c_i that are exact f64 (a single segment) or `Ddi` enclosures of the exact ones (a
//! span; then every step below holds for the exact polynomial, the end slopes' signs come from
//! the filter of step 3 instead of exact comparisons, and the end values are enclosures; the
//! value at the right end counts as attained only where the curve is continuous):
//!
//! 1. Power form x(t) = a_0 + a_1 t + a_2 t^2 + a_3 t^3 from the forward differences
//!    a_k = binom(p, k) Δ^k c_0 (Farin, *Curves and Surfaces for CAGD*, monomial form of a
//!    Bézier curve), in [`Ddi`]: the first differences Δc_i are exact double-words (TwoSum)
//!    for f64 data, so every coefficient encloses the exact one about 2^-100 relative wide.
//! 2. f64 estimates of the roots of x' (quadratic formula in the cancellation-free form).
//!    Nothing about soundness depends on them: they only choose test points.
//! 3. Test points 0 = z_0 < z_1 < ... < z_k = 1: both ends and r ± h around each estimate r
//!    (h = 2^-40). The sign of x'(z_i) is *proven* at each point (an f64 filter with an
//!    a-priori error bound, [`Deriv`], else a `Ddi` Horner enclosure excluding 0); if any sign
//!    is not proven the fast path gives up.
//! 4. Root counting. x' is a non-zero polynomial (it has a proven non-zero value) of degree
//!    p - 1, so it has at most R = p - 1 real roots, counted with multiplicity; R = 0 when the
//!    discriminant Δc_1^2 - Δc_0 Δc_2 of the cubic's x'/3 (Bernstein form d_0 (1-t)^2 +
//!    2 d_1 t (1-t) + d_2 t^2, roots real iff d_1^2 - d_0 d_2 >= 0) is proven negative. By
//!    the intermediate value theorem an interval (z_i, z_{i+1}) whose end signs differ holds
//!    an odd number of roots, one whose end signs agree an even number. If c intervals show a
//!    sign change and c >= R - 1, each of them holds exactly one root and every other
//!    interval none (the c odd counts use up at least c of the R roots; at most R - c <= 1
//!    remain, and an even number <= 1 is 0). Otherwise the fast path gives up.
//! 5. So on every maximal run of intervals without sign change x' has one constant non-zero
//!    sign except at isolated points: x is strictly monotone there and its extrema over the
//!    run are at the run's ends, which are 0, 1 or ends of sign-change intervals. Hence
//!    max x = max(x(0), x(1), max over the sign-change intervals), the same for min. More
//!    sharply, a global maximiser inside (0, 1) is a root of x' where x' does not change from
//!    negative to positive (that root would be a strict local minimum, and x is not
//!    constant): so only the intervals where x' changes from positive to negative count for
//!    the maximum, and those from negative to positive for the minimum.
//!    x(0) = c_0 and x(1) = c_p exactly (clamped ends). Over a sign-change interval B with
//!    midpoint m the second-order Taylor form (Moore 1966; Neumaier 1990, sec. 2.3)
//!    x(B) ⊆ x(m) + x'(m) (B - m) + (x''(B) / 2) (B - m)^2 is evaluated in `Ddi` and rounded
//!    outward; x(m) is a value the curve attains (inner bound). With h = 2^-40 the correction
//!    terms are ~2^-75 of the coordinate scale, so the bound is that of x(m), about one ulp.
//! 6. The result is used only if each side's certified gap (bound minus attained value) is at
//!    most `max_gap` (two ulps of the scale by default); otherwise — a root estimate too poor
//!    for its bracket, a (near) double root, a flat coordinate — the caller runs the general
//!    branch and bound. The fast path is thus never looser than the general one's stopping
//!    rule, and never wrong: every step above is proven, rounding included.

use super::{CandidateKind, Extremum, Side, Stats, Termination};
use crate::num::ddi::{dist_up, up, Ddi};
use crate::num::horner;
use crate::num::Scalar;
use crate::spline::bezier::power_from_differences_in_place;

/// Half-width (in the local parameter t in [0, 1]) of the test-point pairs around root
/// estimates. The Taylor correction over such a bracket is about |x''| h^2 / 2, far below an
/// ulp; f64 root estimates of simple roots are far more accurate than h unless x' has a near
/// double root (then the fast path gives up).
const H: f64 = 1.0 / 1_099_511_627_776.0; // 2^-40

/// The proven sign of an enclosure: `Some(true)` if every value is > 0, `Some(false)` if every
/// value is < 0, `None` if it may contain 0.
#[inline]
fn sign(x: Ddi) -> Option<bool> {
    // abs_lower is Some only if |hi| exceeds |lo| + rad (rounded up), so all values share the
    // sign of hi.
    Ddi::abs_lower(x).map(|_| x.hi() > 0.0)
}

/// Up to 4 power coefficients of x, enclosed.
struct Poly {
    /// degree p (2 or 3)
    p: usize,
    /// x: a_0 .. a_p (a_3 = 0 for p = 2)
    x: [Ddi; 4],
    /// first differences Δc_0 .. Δc_{p-1}
    d: [Ddi; 3],
}

/// Whether a `Ddi` is a single f64 value.
fn is_f64(x: &Ddi) -> bool {
    x.lo() == 0.0 && x.rad() == 0.0
}

impl Poly {
    /// Power form of sum_i c_i B_i^p(t) (p = 2 or 3) from enclosed coefficients: the first
    /// differences are exact double-words (TwoSum) when the c_i are f64 values, enclosures
    /// otherwise; higher differences are enclosed by `Ddi` sums.
    fn new(c: &[Ddi]) -> Poly {
        let p = c.len() - 1;
        let z = Ddi::exact(0.0);
        let d: [Ddi; 3] = std::array::from_fn(|i| {
            if i >= p {
                z
            } else if is_f64(&c[i]) && is_f64(&c[i + 1]) {
                Ddi::diff(c[i + 1].hi(), c[i].hi())
            } else {
                c[i + 1] - c[i]
            }
        });
        // a_1 = p Δc_0, a_2 = C(p, 2) Δ^2 c_0, (p = 3) a_3 = Δ^3 c_0 = Δc_2 - 2 Δc_1 + Δc_0,
        // by the shared kernel from these first differences (on the stack).
        let mut x = [c[0], z, z, z];
        x[1..=p].copy_from_slice(&d[..p]);
        power_from_differences_in_place(&mut x[1..=p]);
        Poly { p, x, d }
    }
    fn x(&self, t: Ddi) -> Ddi {
        horner(&self.x[..=self.p], &t)
    }
    /// x'(t) enclosed (the slow, sharp sign test behind [`Deriv::sign`]).
    fn dx(&self, t: Ddi) -> Ddi {
        let a = &self.x;
        let d1 = [a[1], Ddi::exact(2.0) * a[2], Ddi::exact(3.0) * a[3]];
        horner(&d1[..self.p], &t)
    }
}

/// x'(t) = b_0 + b_1 t + b_2 t^2 in f64 with an a-priori error bound valid for all t in [0, 1]
/// (a floating-point filter: one FMA Horner step per coefficient and a comparison).
/// A separate f64 copy of Horner's rule on purpose: an f64 filter with the error bound below
/// (which assumes exactly this FMA evaluation order); the generic kernel is [`crate::num::horner`],
/// used for the `Ddi` fallback [`Poly::dx`].
///
/// Error bound. Let α_k be the exact power coefficients of x, enclosed by the `Ddi` a_k
/// (|α_k - (hi_k + lo_k)| <= rad_k), and β_k = k α_k those of x'. We use b̂_k = fl(k hi_k):
/// exact for k = 1, 2 (powers of two), and |3 hi_3 - b̂_2| <= u |3 hi_3| + η <= U1 |b̂_2| + η
/// for k = 3 (u = 2^-53, U1 = u (1 + 2^-50) >= u / (1 - u), η = 2^-1075 the underflow error of
/// a product). So |β_k - b̂_{k-1}| <= k (|lo_k| + rad_k) + U1 |b̂_{k-1}| + η.
/// Horner with FMA, y = fl(fl(b̂_2 t + b̂_1) t + b̂_0), t in [0, 1]: each FMA is one rounding,
/// s_1 = (b̂_2 t + b̂_1)(1 + δ_1) + η_1, y = (s_1 t + b̂_0)(1 + δ_2) + η_2 with |δ_i| <= u,
/// |η_i| <= η, hence (Higham, *Accuracy and Stability of Numerical Algorithms*, sec. 5.1,
/// specialised) |y - sum b̂_k t^k| <= u (|b̂_2| t^2 + |b̂_1| t) + u |s_1 t + b̂_0| + 2 η
/// <= (2u + u^2) (|b̂_0| + |b̂_1| + |b̂_2|) + 3 η, using |s_1| <= (|b̂_2| t + |b̂_1|)(1 + u) + η
/// and t <= 1. Altogether, with 4u >= U1 + 2u + u^2 and 4η = 2^-1073,
///
///   |x'(t) - y| <= T = sum_k k (|lo_k| + rad_k) + 4u (|b̂_0| + |b̂_1| + |b̂_2|) + 2^-1073,
///
/// a sum of five terms, each a product of an f64 with a sum of nonnegative f64: Lemma B of
/// [`crate::num::ddi`] gives `err = up(fl(T)) >= T`. A non-finite value anywhere makes every test
/// fail (comparisons with NaN or inf are false), never pass.
struct Deriv {
    b: [f64; 3],
    err: f64,
}

impl Deriv {
    fn new(poly: &Poly) -> Deriv {
        let a = &poly.x;
        let b = [a[1].hi(), 2.0 * a[2].hi(), 3.0 * a[3].hi()];
        let e = |k: f64, x: &Ddi| k * (x.lo().abs() + x.rad());
        let t = e(1.0, &a[1])
            + e(2.0, &a[2])
            + e(3.0, &a[3])
            + 4.0 * f64::EPSILON / 2.0 * (b[0].abs() + b[1].abs() + b[2].abs())
            + f64::from_bits(2);
        Deriv { b, err: up(t) }
    }
    /// The f64 value y with |x'(t) - y| <= err (t in [0, 1]).
    #[inline]
    fn approx(&self, t: f64) -> f64 {
        self.b[2].mul_add(t, self.b[1]).mul_add(t, self.b[0])
    }
    /// The proven sign of x'(t), t in [0, 1]: by the filter, else by a `Ddi` evaluation.
    fn sign(&self, poly: &Poly, t: f64) -> Option<bool> {
        let y = self.approx(t);
        if y.abs() > self.err {
            // |x'(t) - y| <= err < |y|: x'(t) has the sign of y
            return Some(y > 0.0);
        }
        sign(poly.dx(Ddi::exact(t)))
    }
}

/// f64 estimates of the real roots of b_0 + b_1 t + b_2 t^2 (at most two, unordered).
fn root_estimates(b0: f64, b1: f64, b2: f64) -> ([f64; 2], usize) {
    let mut r = [0.0; 2];
    let mut n = 0;
    let mut push = |x: f64| {
        if x.is_finite() {
            r[n] = x;
            n += 1;
        }
    };
    if b2 == 0.0 {
        push(-b0 / b1);
        return (r, n);
    }
    // q = -(b1 + sign(b1) sqrt(disc)) / 2, roots q / b2 and b0 / q (no cancellation).
    let disc = (b1 * b1 - 4.0 * b0 * b2).max(0.0);
    let q = -0.5 * (b1 + disc.sqrt().copysign(b1));
    push(q / b2);
    if q != 0.0 {
        push(b0 / q);
    }
    (r, n)
}

/// Extremum record for the parameter interval [t0, t1] of the local parameter, mapped to the
/// segment's [a, b] outward (u = a + t (b - a) enclosed in `Ddi`).
fn extremum(a: f64, b: f64, t0: f64, t1: f64, unique: bool, kind: CandidateKind) -> Extremum {
    let map = |t: f64| -> (f64, f64) {
        if a == 0.0 && b == 1.0 {
            return (t, t);
        }
        let u = (Ddi::exact(a) + Ddi::exact(t) * Ddi::diff(b, a)).to_interval();
        (u.inf().max(a), u.sup().min(b))
    };
    Extremum {
        u_lo: map(t0).0,
        u_hi: map(t1).1,
        unique,
        kind,
    }
}

/// One polynomial Bézier segment of one coordinate: coefficients c_0 .. c_p (p = 2 or 3; f64
/// values, or enclosures of the exact ones) over the parameter interval [a, b].
pub(super) struct Segment<'a> {
    pub c: &'a [Ddi],
    pub a: f64,
    pub b: f64,
    /// what the ends are (domain end, knot)
    pub end_kinds: [CandidateKind; 2],
    /// whether the curve attains its value at b (false at a jump knot, where c_p is a left
    /// limit only; it still bounds the segment)
    pub right_attained: bool,
}

/// Both sides of a coordinate on one polynomial Bézier segment: `[max side, min side]` as
/// sign-adjusted [`Side`]s (see the module docs), or `None` when the fast path cannot prove a
/// result whose gap is at most `max_gap` on every side it is asked for (`need`: [max, min];
/// a side not needed comes back incomplete and must not be used).
pub(super) fn coord_sides(seg: &Segment, max_gap: f64, need: [bool; 2]) -> Option<[Side; 2]> {
    let Segment { c, a, b, .. } = *seg;
    let p = c.len().checked_sub(1)?;
    if !(2..=3).contains(&p) {
        return None;
    }
    let poly = Poly::new(c);
    let deriv = Deriv::new(&poly);
    let mut stats = Stats::default();
    // Test points and proven signs of x' there.
    let mut z = [0.0f64; 6];
    let mut k = 0;
    z[k] = 0.0;
    k += 1;
    {
        let (mut r, nr) = root_estimates(deriv.b[0], deriv.b[1], deriv.b[2]);
        r[..nr].sort_by(f64::total_cmp);
        for &ri in &r[..nr] {
            for t in [ri - H, ri + H] {
                if t > z[k - 1] && t < 1.0 {
                    z[k] = t;
                    k += 1;
                }
            }
        }
    }
    z[k] = 1.0;
    k += 1;
    // Signs at the ends. For f64 coefficients they are exact comparisons: x'(0) = p (c_1 - c_0),
    // x'(1) = p (c_p - c_{p-1}).
    // If x'(0) = 0 exactly, x' = t q(t) with q of degree p - 2 and q(0) = (p - 1)(c_2 - c_1)
    // (Bernstein coefficients of x' / p: Δc_0 = 0, Δc_1, ...; divide out t), so x' has the sign
    // of c_2 - c_1 just right of 0 and the roots of x' in (0, 1] are those of q: one fewer.
    // The same at t = 1 with c_{p-1} - c_{p-2}. The sign of q at the end replaces that of x'
    // there, and the counting of step 4 runs on q (x' = t q or (1 - t) q or t (1 - t) q has
    // the sign of q inside (0, 1)).
    // (For enclosed coefficients the filter of `Deriv` decides, and an end slope that may be
    // zero gives up.)
    let mut max_roots = p - 1;
    let (s0, s1) = if c.iter().all(is_f64) {
        let cmp =
            |x: &Ddi, y: &Ddi| -> Option<bool> { (x.hi() != y.hi()).then_some(x.hi() > y.hi()) };
        let mut end_sign = |i: usize, j: usize, k: usize| -> Option<bool> {
            cmp(&c[j], &c[i]).or_else(|| {
                max_roots -= 1;
                cmp(&c[k], &c[j])
            })
        };
        (end_sign(0, 1, 2)?, end_sign(p, p - 1, p - 2).map(|up| !up)?)
    } else {
        (deriv.sign(&poly, 0.0)?, deriv.sign(&poly, 1.0)?)
    };
    let mut s = [false; 6];
    s[0] = s0;
    s[k - 1] = s1;
    for i in 1..k - 1 {
        stats.derivative_evaluations += 1;
        s[i] = deriv.sign(&poly, z[i])?;
    }
    let changes = (1..k).filter(|&i| s[i] != s[i - 1]).count();
    // Upper bound R of the number of real roots (module docs, step 4): p - 1 less the exact
    // zeros at the ends, or 0 for a cubic whose discriminant is proven negative (only needed
    // when there are few changes).
    if changes + 1 < max_roots {
        let d = &poly.d;
        if sign(d[1] * d[1] - d[0] * d[2]) != Some(false) {
            return None;
        }
    }
    // Candidates: the end values and the enclosures over the sign-change intervals.
    let mut hi = Side::new();
    let mut lo = Side::new();
    for (t, v, kind, attained) in [
        (0.0, c[0], seg.end_kinds[0], true),
        (1.0, c[p], seg.end_kinds[1], seg.right_attained),
    ] {
        let e = extremum(a, b, t, t, false, kind);
        let v = v.to_interval();
        if attained {
            hi.attain_f64(v.inf());
            lo.attain_f64(-v.sup());
        }
        hi.bound(v.sup(), e);
        lo.bound(-v.inf(), e);
    }
    // max |x''(ξ) / 2| over [0, 1] <= |α_2| + 3 |α_3| <= m2 (Lemma B: a term and a product).
    let m2 = up(poly.x[2].abs_upper() + 3.0 * poly.x[3].abs_upper());
    for i in 1..k {
        // A sign change from + to - brackets a strict local maximum, which is not a global
        // minimum (x is not constant), so it matters for the max side only; - to + likewise
        // for the min side (module docs, step 5).
        let is_max = s[i - 1] && !s[i];
        if s[i] == s[i - 1] || !need[if is_max { 0 } else { 1 }] {
            continue;
        }
        let (t0, t1) = (z[i - 1], z[i]);
        // Taylor form around an f64 m in [t0, t1], |t - m| <= r for t in [t0, t1]:
        // x(t) = x(m) + x'(m) (t - m) + x''(ξ) / 2 (t - m)^2 (Lagrange remainder), so
        // |x(t) - x(m)| <= (|y| + err) r + m2 r^2 <= corr (Lemma B, with r2 >= r^2).
        let m = (t0 + 0.5 * (t1 - t0)).clamp(t0, t1);
        let r = dist_up(m, t0).max(dist_up(t1, m));
        let r2 = up(r * r);
        stats.derivative_evaluations += 1;
        let corr = up((deriv.approx(m).abs() + deriv.err) * r + m2 * r2);
        stats.point_evaluations += 1;
        let xm = poly.x(Ddi::exact(m));
        let e = extremum(a, b, t0, t1, true, CandidateKind::Critical);
        let vb = xm.widen(corr).to_interval();
        if is_max {
            hi.attain_ddi(xm);
            hi.bound(vb.sup(), e);
        } else {
            lo.attain_ddi(-xm);
            lo.bound(-vb.inf(), e);
        }
    }
    hi.stats = stats;
    for (sd, &nd) in [&hi, &lo].into_iter().zip(&need) {
        let tight = sd.upper - sd.attained <= max_gap; // (false for a NaN gap)
        if nd && !tight {
            return None;
        }
    }
    hi.term = Termination::Converged;
    lo.term = Termination::Converged;
    Some([hi, lo])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn power_form_matches_bernstein() {
        let c = [1.0, -2.0, 4.0, 0.5];
        let poly = Poly::new(&c.map(Ddi::exact));
        for i in 0..=8 {
            let t = i as f64 / 8.0;
            let bern = (1.0 - t).powi(3) * c[0]
                + 3.0 * t * (1.0 - t).powi(2) * c[1]
                + 3.0 * t * t * (1.0 - t) * c[2]
                + t.powi(3) * c[3];
            let v = poly.x(Ddi::exact(t)).to_interval();
            assert!((v.mid() - bern).abs() < 1e-14, "{t}: {v:?} {bern}");
        }
    }

    fn sides(c: &[f64]) -> Option<[Side; 2]> {
        let c: Vec<Ddi> = c.iter().map(|&x| Ddi::exact(x)).collect();
        let seg = Segment {
            c: &c,
            a: 0.0,
            b: 1.0,
            end_kinds: [CandidateKind::EndPoint; 2],
            right_attained: true,
        };
        coord_sides(&seg, 1e-15, [true; 2])
    }

    #[test]
    fn interior_extrema_and_give_ups() {
        // x = 3 t (1 - t)^2 * 2 - ... : max of a symmetric bump
        let [hi, lo] = sides(&[0.0, 1.0, 1.0, 0.0]).unwrap();
        // exact max 0.75 at t = 0.5, min 0 at the ends
        assert!(hi.upper >= 0.75 && hi.attained <= 0.75 && hi.upper - 0.75 < 1e-15);
        assert_eq!(-lo.upper, 0.0);
        // a double root of x' (x = t^3 shape around 1/2): not provable, gives up
        assert!(sides(&[0.0, 1.0, 0.0, 1.0]).is_none());
        let flat = sides(&[2.0, 2.0, 2.0, 2.0]);
        assert!(flat.is_none());
        // a monotone cubic with an interior control maximum: exact ends
        let [hi, lo] = sides(&[0.0, 1.0, 0.9, 0.95]).unwrap();
        assert_eq!((hi.upper, hi.attained), (0.95, 0.95));
        assert_eq!((lo.upper, lo.attained), (0.0, 0.0));
    }
}
