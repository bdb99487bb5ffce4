//! Root-isolating fast path of the `bezier` strategy for one polynomial Bézier segment of
//! degree 2 or 3: a single clamped segment without weights (the common 2-D cubic Bézier), and
//! the spans of non-rational quadratic / cubic splines (segments from double-double knot
//! insertion, `HSpline::<Ddi>::bezier_segment`); and, for the driver's lane, the spans of
//! quartic and quintic splines, with the zeros of x' counted by the sign changes of its
//! Bernstein coefficients ([`descartes_sides_into`]; also the lane's quadratic and cubic spans
//! with an extremum at or next to a knot, where the closed-form route gives up).
//!
//! For one coordinate x(t) = sum_i c_i B_i^p(t), t in [0, 1] (the curve's image does not
//! depend on the parametrisation, so the local parameter is used throughout), with control
//! values c_i that are exact f64 (a single segment) or `Ddi` enclosures of the exact ones (a
//! span; then every step below holds for the exact polynomial, the end slopes' signs come from
//! the filter of step 3 instead of exact comparisons, and the end values are enclosures; the
//! value at the right end counts as attained only where the curve is continuous; at a jump it
//! is a left limit, which the piece approaches, so every double below it is exceeded):
//!
//! 1. Power form x(t) = a_0 + a_1 t + a_2 t^2 + a_3 t^3 from the forward differences
//!    a_k = binom(p, k) Δ^k c_0 (Farin, *Curves and Surfaces for CAGD*, monomial form of a
//!    Bézier curve), in [`Ddi`]: the first differences Δc_i are exact double-words (TwoSum)
//!    for f64 data, so every coefficient encloses the exact one about 2^-100 relative wide.
//!    Built only where needed: for enclosed coefficients (spans), and for a derivative sign
//!    the f64 filter of step 3 leaves open; the values x(m) of step 5 from f64 data come
//!    from the compensated de Casteljau algorithm instead ([`Ddi::de_casteljau_f64`], an
//!    a-priori bound of 2^-99 of the scale).
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
//!    x(B) ⊆ x(m) + x'(m) (B - m) + (x''(B) / 2) (B - m)^2 is evaluated in `Ddi` (x(m) as in step 1) and rounded
//!    outward; x(m) is a value the curve attains (inner bound). With h = 2^-40 the correction
//!    terms are ~2^-75 of the coordinate scale, so the bound is that of x(m), about one ulp.
//!    5b. A near-tie: where the bound of a bracket and its values leave the optimal double
//!    open (the attained value below the bound and no witness at d = next_down(bound): the
//!    extremum M is within ~2^-80 relative of d, ~2^-27 of generic cases), the sign of M - d
//!    is computed exactly in integers ([`bracket_max_cmp`]: M = x(t*) at the bracket's only
//!    zero t* of x', by the pseudo-remainder of x - d by x'). M <= d lowers the bound to d
//!    (M = d: d is attained as well, e.g. the maximum (a + b) / 2 of the symmetric arc P0 =
//!    P2 = a, P1 = b at t = 1/2); M > d makes d a witness (the curve exceeds it). Either way
//!    the bound is then the optimal double and its certificate costs nothing. At most twice
//!    per bracket. A far tie: M near zero against the coefficients' scale (a curve tangent
//!    to an axis, M = 0 exactly at a t* that is no double, or such data rounded), where the
//!    doubles around M are far finer than the bracket's double-double value, so that the
//!    bound lies many doubles above the attained value although both agree to 2^-40 of the
//!    scale. Each exact comparison also returns an estimate of M - d, accurate to a few ulps
//!    of it (a Newton step on x' in the same integers); d = 0 first where it lies between
//!    them, then the doubles the estimate points to, at most [`FAR_TIES`] comparisons, until
//!    the bound is attained or the next double down is a witness.
//! 6. The result is used only if each side's certified gap (bound minus attained value) is at
//!    most `max_gap` (two ulps of the scale by default); otherwise — a root estimate too poor
//!    for its bracket, a (near) double root, a flat coordinate — the caller runs the general
//!    branch and bound. The fast path is thus never looser than the general one's stopping
//!    rule, and never wrong: every step above is proven, rounding included.

use super::{CandidateKind, Extremum, Side, Termination};
use crate::enclose::newton::bernstein::locate_by;
use crate::num::ddi::{dist_up, up, Ddi, U1};
use crate::num::horner;
use crate::num::Scalar;
use crate::spline::bezier::power_from_differences_in_place;
use std::cmp::Ordering;

/// Half-width (in the local parameter t in [0, 1]) of the test-point pairs around root
/// estimates. The Taylor correction over such a bracket is about |x''| h^2 / 2, far below an
/// ulp; f64 root estimates of simple roots are far more accurate than h unless x' has a near
/// double root (then the fast path gives up).
pub(super) const H: f64 = 1.0 / 1_099_511_627_776.0; // 2^-40

/// At most this many exact comparisons decide a far tie (step 5b): the first (at 0, or
/// next_down(bound)) gives an estimate of M within a few ulps, the next ones the doubles
/// around it.
const FAR_TIES: usize = 8;

/// The proven sign of an enclosure: `Some(true)` if every value is > 0, `Some(false)` if every
/// value is < 0, `None` if it may contain 0.
#[inline]
pub(super) fn sign(x: Ddi) -> Option<bool> {
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
}

/// Whether a `Ddi` is a single f64 value.
fn is_f64(x: &Ddi) -> bool {
    x.lo() == 0.0 && x.rad() == 0.0
}

/// The first differences Δc_0 .. Δc_{p-1} (zero beyond): exact double-words (TwoSum) when the
/// c_i are f64 values, enclosures otherwise.
fn first_differences(c: &[Ddi]) -> [Ddi; 3] {
    let p = c.len() - 1;
    std::array::from_fn(|i| {
        if i >= p {
            Ddi::exact(0.0)
        } else if is_f64(&c[i]) && is_f64(&c[i + 1]) {
            Ddi::diff(c[i + 1].hi(), c[i].hi())
        } else {
            c[i + 1] - c[i]
        }
    })
}

impl Poly {
    /// Power form of sum_i c_i B_i^p(t) (p = 2 or 3) from enclosed coefficients: higher
    /// differences of the first differences are enclosed by `Ddi` sums.
    fn new(c: &[Ddi]) -> Poly {
        let p = c.len() - 1;
        let d = first_differences(c);
        if p == 3 && d.iter().all(|x| x.rad() == 0.0) {
            // The common case (exact first differences of f64 data), written out: the same
            // forward differences and binomial factors as the shared kernel below, without its
            // loops and binomial recurrences (this runs once per interior extremum of a cubic).
            let e0 = d[1] - d[0];
            let e1 = d[2] - d[1];
            let three = Ddi::exact(3.0);
            return Poly {
                p,
                x: [c[0], three * d[0], three * e0, e1 - e0],
            };
        }
        // a_1 = p Δc_0, a_2 = C(p, 2) Δ^2 c_0, (p = 3) a_3 = Δ^3 c_0 = Δc_2 - 2 Δc_1 + Δc_0,
        // by the shared kernel from these first differences (on the stack).
        let z = Ddi::exact(0.0);
        let mut x = [c[0], z, z, z];
        x[1..=p].copy_from_slice(&d[..p]);
        power_from_differences_in_place(&mut x[1..=p]);
        Poly { p, x }
    }
    /// x'(t) enclosed (the slow, sharp sign test behind [`Deriv::sign`]).
    fn dx(&self, t: Ddi) -> Ddi {
        let a = &self.x;
        let d1 = [a[1], Ddi::exact(2.0) * a[2], Ddi::exact(3.0) * a[3]];
        horner(&d1[..self.p], &t)
    }
}

/// An f64 polynomial y(t) = b_0 + b_1 t + b_2 t^2 and a bound `err` with |s x'(t) - y(t)| <= err
/// for every t in [0, 1] and a known positive factor s (so y decides the sign of x' wherever
/// |y| > err): a floating-point filter, one FMA Horner step per coefficient and a comparison.
/// A separate f64 copy of Horner's rule on purpose: an f64 filter with the error bounds below
/// (which assume exactly this FMA evaluation order); the generic kernel is
/// [`crate::num::horner`], used for the `Ddi` fallback [`Poly::dx`].
pub(super) struct Deriv {
    b: [f64; 3],
    err: f64,
}

impl Deriv {
    /// From the enclosed power coefficients (s = 1).
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
    /// [`crate::num::ddi`] gives `err = up(fl(T)) >= T`. A non-finite value anywhere makes every
    /// test fail (comparisons with NaN or inf are false), never pass.
    fn new(poly: &Poly) -> Deriv {
        let a = &poly.x;
        let b = [a[1].hi(), 2.0 * a[2].hi(), 3.0 * a[3].hi()];
        let e = |k: f64, x: &Ddi| k * (x.lo().abs() + x.rad());
        Deriv::with_error(b, e(1.0, &a[1]) + e(2.0, &a[2]) + e(3.0, &a[3]))
    }

    /// The filter on f64 coefficients `b` whose exact polynomial q differs from
    /// sum_k b_k t^k by at most `e` on [0, 1] (`e` an f64 sum of the form of Lemma B): with
    /// Horner's FMA error, err = up(fl(e + 4u (|b_0| + |b_1| + |b_2|) + 2^-1073)) (the bound
    /// of [`Deriv::new`] and [`Deriv::from_coefficients`]).
    fn with_error(b: [f64; 3], e: f64) -> Deriv {
        let t = e + 4.0 * f64::EPSILON / 2.0 * (b[0].abs() + b[1].abs() + b[2].abs())
            + f64::from_bits(2);
        Deriv { b, err: up(t) }
    }

    /// Straight from exact f64 coefficients c_0 .. c_p (p = 2, 3), without the `Ddi` power
    /// form: y approximates q = x' / p (s = 1 / p), whose Bernstein coefficients are the exact
    /// differences D_i = c_{i+1} - c_i, so q(t) = D_0 + (p - 1) (D_1 - D_0) t
    /// + (D_2 - 2 D_1 + D_0) t^2 (the last term for p = 3 only).
    ///
    /// Error bound. Sums have no underflow error, and round-to-nearest gives
    /// |fl(o) - o| <= U1 |fl(o)|. With d_i = fl(D_i), k_1 = fl(d_1 - d_0), e = fl(d_2 - d_1),
    /// k_2 = fl(e - k_1) and the coefficients b = (d_0, (p - 1) k_1, k_2) ((p - 1) k_1 is an exact
    /// doubling or the value itself):
    ///
    /// * |D_0 - b_0| <= U1 |d_0|;
    /// * |(p - 1)(D_1 - D_0) - b_1| is at most 2 (|D_1 - d_1| + |D_0 - d_0| + |d_1 - d_0 - k_1|),
    ///   hence at most 2 U1 (|d_0| + |d_1| + |k_1|);
    /// * |(D_2 - D_1) - (D_1 - D_0) - k_2| is at most the sum of |D_2 - d_2|, 2 |D_1 - d_1|,
    ///   |D_0 - d_0|, |d_2 - d_1 - e|, |d_1 - d_0 - k_1| and |e - k_1 - k_2|, hence at most
    ///   U1 (|d_0| + 2 |d_1| + |d_2| + |e| + |k_1| + |k_2|);
    /// * Horner with FMA as in [`Deriv::new`]: at most (2u + u^2)(|b_1| + |b_2|) + u |d_0| + 3 η,
    ///   with |b_1| <= 2 |k_1|.
    ///
    /// Summed per quantity (d_0: 5 U1, d_1: 4 U1, d_2, e: U1, k_1: 2 U1 + U1 + 4 (2u + u^2)
    /// <= 12 U1, k_2: U1 + 2u + u^2 <= 4 U1):
    ///
    ///   |q(t) - y| <= T = 12 U1 (|d_0| + |d_1| + |d_2| + |e| + |k_1| + |k_2|) + 2^-1073,
    ///
    /// (p = 2: the same with d_2 = e = k_2 = 0), a product of an f64 with a sum of nonnegative
    /// f64 plus a term: Lemma B gives `err = up(fl(T)) >= T`. Non-finite values fail every test.
    fn from_f64(c: &[f64]) -> Deriv {
        let p = c.len() - 1;
        let d0 = c[1] - c[0];
        let d1 = c[2] - c[1];
        let k1 = d1 - d0;
        let (d2, e, k2) = if p == 3 {
            let d2 = c[3] - c[2];
            let e = d2 - d1;
            (d2, e, e - k1)
        } else {
            (0.0, 0.0, 0.0)
        };
        let b1 = if p == 3 { 2.0 * k1 } else { k1 };
        let s = d0.abs() + d1.abs() + d2.abs() + e.abs() + k1.abs() + k2.abs();
        let t = 12.0 * U1 * s + f64::from_bits(2);
        Deriv {
            b: [d0, b1, k2],
            err: up(t),
        }
    }

    /// From f64 power coefficients b_0, b_1, b_2 of a quadratic q with |β_k - b_k| <= `coeff_err`
    /// for its exact coefficients β_k (s = 1, q in place of x': the conic path's derivative
    /// numerator, [`super::conic`]).
    ///
    /// Error bound. |q(t) - sum_k b_k t^k| <= 3 `coeff_err` for t in [0, 1], and Horner with FMA
    /// on the b_k errs by at most (2u + u^2)(|b_0| + |b_1| + |b_2|) + 3 η (as in
    /// [`Deriv::new`]), so
    ///
    ///   |q(t) - y| <= T = 3 coeff_err + 4u (|b_0| + |b_1| + |b_2|) + 2^-1073,
    ///
    /// a formula of Lemma B of [`crate::num::ddi`]: `err = up(fl(T)) >= T`. A non-finite value
    /// makes every test fail.
    pub(super) fn from_coefficients(b: [f64; 3], coeff_err: f64) -> Deriv {
        Deriv::with_error(b, 3.0 * coeff_err)
    }

    /// The error bound of [`Deriv::approx`].
    #[inline]
    pub(super) fn err(&self) -> f64 {
        self.err
    }

    /// The f64 value y with |s x'(t) - y| <= err (t in [0, 1]).
    #[inline]
    pub(super) fn approx(&self, t: f64) -> f64 {
        self.b[2].mul_add(t, self.b[1]).mul_add(t, self.b[0])
    }
}

/// The coefficients of one coordinate, with the `Ddi` power form built on first use (the f64
/// filter decides most questions without it).
struct Coeffs<'a> {
    c: &'a [Ddi],
    poly: Option<Poly>,
}

impl Coeffs<'_> {
    fn poly(&mut self) -> &Poly {
        self.poly.get_or_insert_with(|| Poly::new(self.c))
    }
    /// The proven sign of x'(t), t in [0, 1]: by the filter, else by a `Ddi` evaluation.
    fn sign(&mut self, deriv: &Deriv, t: f64) -> Option<bool> {
        let y = deriv.approx(t);
        if y.abs() > deriv.err {
            // |s x'(t) - y| <= err < |y| with s > 0: x'(t) has the sign of y
            return Some(y > 0.0);
        }
        sign(self.poly().dx(Ddi::exact(t)))
    }
}

/// The sign of M - d, M = max x over [t0, t1], for exact f64 coefficients c_0 .. c_p
/// (p = 2, 3) of x and f64 t0 < t1 in [0, 1] where x'(t0) > 0 > x'(t1) and x' has exactly one
/// root t* in [t0, t1] (step 4): then x increases up to t* and decreases after it, M = x(t*).
/// Exact, in integers (`None` only for non-finite data); with it an f64 estimate of M - d
/// (no bound is claimed for it: it only chooses the next d to compare with, step 5b):
///
/// * c_i = C_i 2^e and d = D 2^e over one power of two (a positive factor, dropped); the power
///   form f(t) = x(t) - d = f_0 + a_1 t + a_2 t^2 + a_3 t^3 (Farin, *Curves and Surfaces for
///   CAGD*, monomial form of a Bézier curve: a_1 = p ΔC_0, a_2 = C(p, 2) Δ^2 C_0,
///   a_3 = Δ^3 C_0, f_0 = C_0 - D) and x' = Q(t) = q_0 + q_1 t + q_2 t^2 = a_1 + 2 a_2 t + 3 a_3 t^2.
/// * Q linear (q_2 = 0, a_2 != 0 since x' changes sign): t* = -a_1 / (2 a_2) and
///   f(t*) = f_0 - a_1^2 / (4 a_2), so sign f(t*) = sign(4 a_2 f_0 - a_1^2) sign(a_2) (and
///   the estimate is that quotient itself).
/// * Q quadratic: the pseudo-remainder of f by Q, q_2^2 f = (q_2 a_3 t + b_2) Q + r_1 t + r_0
///   (b_2 = q_2 a_2 - a_3 q_1, b_1 = q_2 a_1 - a_3 q_0, b_0 = q_2 f_0, r_1 = q_2 b_1 - b_2 q_1,
///   r_0 = q_2 b_0 - b_2 q_0), so q_2^2 f(t*) = r_1 t* + r_0 = r_1 (t* - t_R) with
///   t_R = -r_0 / r_1 (sign r_0 if r_1 = 0). Where t_R lies: at or left of t0 (then t_R < t*),
///   at or right of t1 (t_R > t*), or inside, where Q > 0 on [t0, t*) and Q < 0 on (t*, t1],
///   so the sign of r_1^2 Q(t_R) = q_2 r_0^2 - q_1 r_0 r_1 + q_0 r_1^2 tells (0: t_R = t*,
///   f(t*) = 0, an exact tie). The estimate: t* by one Newton step on Q from t_R inside the
///   bracket, r_1 (t* - t_R) ~ -r_1 Q(t_R) / Q'(t_R) = -(r_1^2 Q(t_R)) / (q_1 r_1 - 2 q_2 r_0)
///   (accurate to a few ulps of M - d where f(t*) is small: the step's error is of second
///   order in t* - t_R); outside, t* by the bracket's midpoint.
///
/// Step 5b of the module docs; it runs only for a tie (~2^-27 of generic brackets).
#[cold]
#[inline(never)]
fn bracket_max_cmp(c: &[f64], t0: f64, t1: f64, d: f64) -> Option<(Ordering, f64)> {
    use crate::enclose::certify::dyadic_integers;
    use crate::num::exact::approx_ratio;
    use num_bigint::{BigInt, Sign};
    let sgn = |x: &BigInt| match x.sign() {
        Sign::Minus => Ordering::Less,
        Sign::NoSign => Ordering::Equal,
        Sign::Plus => Ordering::Greater,
    };
    let mul = |a: Ordering, b: Ordering| match (a, b) {
        (Ordering::Equal, _) | (_, Ordering::Equal) => Ordering::Equal,
        _ if a == b => Ordering::Greater,
        _ => Ordering::Less,
    };
    let p = c.len().checked_sub(1)?;
    let (ci, e) = dyadic_integers(c.iter().copied().chain(std::iter::once(d)))?;
    let f0 = &ci[0] - &ci[p + 1];
    let (d0, d1) = (&ci[1] - &ci[0], &ci[2] - &ci[1]);
    let e0 = &d1 - &d0;
    let (a1, a2, a3): (BigInt, BigInt, BigInt) = match p {
        2 => (d0 * 2u32, e0, BigInt::from(0)),
        3 => {
            let e1 = (&ci[3] - &ci[2]) - &d1;
            (d0 * 3u32, &e0 * 3u32, e1 - e0)
        }
        _ => return None,
    };
    let (q0, q1, q2): (BigInt, BigInt, BigInt) = (a1.clone(), &a2 * 2u32, &a3 * 3u32);
    if q2.sign() == Sign::NoSign {
        // (a2 = 0 too would make x' constant, with no root to bracket: not a maximum here)
        if a2.sign() == Sign::NoSign {
            return None;
        }
        let v = &a2 * &f0 * 4u32 - &a1 * &a1;
        let den = &a2 * 4u32;
        return Some((mul(sgn(&v), sgn(&a2)), approx_ratio(&v, &den, e)));
    }
    let b2 = &q2 * &a2 - &a3 * &q1;
    let b1 = &q2 * &a1 - &a3 * &q0;
    let b0 = &q2 * &f0;
    let r1 = &q2 * &b1 - &b2 * &q1;
    let r0 = &q2 * &b0 - &b2 * &q0;
    let q22 = &q2 * &q2;
    if r1.sign() == Sign::NoSign {
        return Some((sgn(&r0), approx_ratio(&r0, &q22, e)));
    }
    // r_1 t + r_0 for an f64 t = T 2^et: (r_1 T + r_0 2^-et) 2^et, or exactly an integer
    let at_t = |t: f64| -> Option<(BigInt, i64)> {
        let (ti, et) = dyadic_integers(std::iter::once(t))?;
        let rt = &r1 * &ti[0];
        Some(if et >= 0 {
            (&r0 + (rt << et as u64), 0)
        } else {
            ((&r0 << (-et) as u64) + rt, et)
        })
    };
    // sign(t_R - t) = sign(-(r_0 + r_1 t)) sign(r_1)
    let beside = |t: f64| -> Option<Ordering> {
        let (v, _) = at_t(t)?;
        Some(mul(sgn(&v).reverse(), sgn(&r1)))
    };
    // (outside the bracket: the estimate with t* ~ its midpoint)
    let outside = || -> Option<f64> {
        let (v, et) = at_t(t0 + 0.5 * (t1 - t0))?;
        Some(approx_ratio(&v, &q22, e + et))
    };
    // where t_R lies relative to t*
    let (at, est) = if beside(t0)? != Ordering::Greater {
        (Ordering::Less, outside()?)
    } else if beside(t1)? != Ordering::Less {
        (Ordering::Greater, outside()?)
    } else {
        let q_at = &q2 * &r0 * &r0 - &q1 * &r0 * &r1 + &q0 * &r1 * &r1;
        let slope = &q1 * &r1 - (&q2 * &r0) * 2u32;
        (sgn(&q_at).reverse(), approx_ratio(&-&q_at, &(&q22 * &slope), e))
    };
    // sign f(t*) = sign(r_1) sign(t* - t_R)
    Some((mul(sgn(&r1), at.reverse()), est))
}

/// f64 estimates of the real roots of b_0 + b_1 t + b_2 t^2 (at most two, unordered).
pub(crate) fn root_estimates(b0: f64, b1: f64, b2: f64) -> ([f64; 2], usize) {
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
pub(crate) fn extremum(
    a: f64,
    b: f64,
    t0: f64,
    t1: f64,
    unique: bool,
    kind: CandidateKind,
) -> Extremum {
    let map = |t: f64| -> (f64, f64) {
        // (the ends map exactly: u(0) = a, u(1) = b; on [0, 1], u = t)
        if t == 0.0 {
            return (a, a);
        }
        if t == 1.0 {
            return (b, b);
        }
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
pub(crate) struct Segment<'a> {
    pub c: &'a [Ddi],
    pub a: f64,
    pub b: f64,
    /// what the ends are (domain end, knot)
    pub end_kinds: [CandidateKind; 2],
    /// whether the curve attains its value at b (false at a jump knot, where c_p is a left
    /// limit only; it still bounds the segment)
    pub right_attained: bool,
}

/// One sign-adjusted side of a coordinate on a segment, as plain data (no allocation): the
/// upper bound, the largest attained lower bound, the strict witness (see
/// [`super::super::CoordBox::witness_hi`]) and up to three candidates (upper bound, where).
#[derive(Clone, Copy)]
pub(crate) struct RawSide {
    pub upper: f64,
    pub attained: f64,
    pub witness: f64,
    pub cands: [(f64, Extremum); 3],
    pub n: usize,
    pub derivative_evaluations: u64,
    pub point_evaluations: u64,
}

impl RawSide {
    /// An empty side (no bound, nothing attained, no candidate).
    pub(crate) fn new() -> RawSide {
        let e = Extremum {
            u_lo: 0.0,
            u_hi: 0.0,
            unique: false,
            kind: CandidateKind::EndPoint,
        };
        RawSide {
            upper: f64::NEG_INFINITY,
            attained: f64::NEG_INFINITY,
            witness: f64::NEG_INFINITY,
            cands: [(f64::NEG_INFINITY, e); 3],
            n: 0,
            derivative_evaluations: 0,
            point_evaluations: 0,
        }
    }
    pub(super) fn attain(&mut self, v: f64) {
        if v > self.attained {
            self.attained = v;
        }
    }
    /// A double-double enclosure of an attained value: its lower end is attained, the largest
    /// f64 strictly below it a witness.
    pub(super) fn attain_ddi(&mut self, v: Ddi) {
        // (a NaN lower end, after an overflow, is ignored by `attain`)
        self.attain(v.lower_end());
        self.witness = self.witness.max(v.strictly_below());
    }
    pub(super) fn bound(&mut self, ub: f64, e: Extremum) {
        if ub > self.upper {
            self.upper = ub;
        }
        if self.n < self.cands.len() {
            self.cands[self.n] = (ub, e);
            self.n += 1;
        }
    }
    /// Whether the certified gap (bound minus attained value) is at most `max_gap` (false for
    /// a NaN gap).
    pub fn tight(&self, max_gap: f64) -> bool {
        self.upper - self.attained <= max_gap
    }
    /// A sign-change bracket's candidate: `v` encloses the side's (sign-adjusted) value at the
    /// bracket's midpoint, which the curve attains, and every value over the bracket lies
    /// within `corr` of it; the bound is the upper end of v ± corr, rounded outward (a NaN end,
    /// after an overflow, bounds nothing: +inf).
    #[inline(always)]
    pub(super) fn bracket(&mut self, v: Ddi, corr: f64, e: Extremum) {
        let ub = v.widen(corr).upper_end();
        self.point_evaluations += 1;
        self.attain_ddi(v);
        self.bound(if ub.is_nan() { f64::INFINITY } else { ub }, e);
    }
    /// Candidate `i`, an end value's (of [`RawSide::ends_into`]), widened to a bracket at
    /// that end: `v` encloses the side's value at the bracket's midpoint, every value over the
    /// bracket lies within `corr` of it (as [`RawSide::bracket`]); the candidate's bound is the
    /// larger of the two, its place the bracket `e` (which holds the end).
    #[inline(always)]
    pub(super) fn widen_end(&mut self, i: usize, v: Ddi, corr: f64, e: Extremum) {
        let ub = v.widen(corr).upper_end();
        let ub = if ub.is_nan() { f64::INFINITY } else { ub };
        self.point_evaluations += 1;
        self.attain_ddi(v);
        if ub > self.upper {
            self.upper = ub;
        }
        let c = &mut self.cands[i];
        *c = (c.0.max(ub), e);
    }
    /// The end values of a continuous rational segment over [a, b] as candidates of both
    /// sides (`out`: [max side, min side], the min side's values negated, exactly): each end
    /// value (enclosed: `ends`, at the local parameters 0 and 1, of the kinds `end_kinds`) is
    /// attained and bounds its end (a NaN upper end, after an overflow, bounds nothing:
    /// +inf). Shared by the conic and the rational proofs.
    #[inline(always)]
    pub(super) fn ends_into(
        out: &mut [RawSide; 2],
        (a, b): (f64, f64),
        ends: [Ddi; 2],
        end_kinds: [CandidateKind; 2],
    ) {
        for (t, v, kind) in [(0.0, ends[0], end_kinds[0]), (1.0, ends[1], end_kinds[1])] {
            let e = extremum(a, b, t, t, false, kind);
            for (side, v) in out.iter_mut().zip([v, -v]) {
                side.attain_ddi(v);
                let ub = v.upper_end();
                side.bound(if ub.is_nan() { f64::INFINITY } else { ub }, e);
            }
        }
    }
}

/// w^2 from below for w >= 0 (the squared lower bound of a rational segment's weight, the
/// divisor of the conic and rational proofs' mean value bounds): fl(w^2) is within half an
/// ulp of it, or 2^-1075 where it underflows, and the next double down lies below both (0:
/// the correction divided by it is infinite).
#[inline(always)]
pub(super) fn square_below(w: f64) -> f64 {
    (w * w).next_down().max(0.0)
}

/// Both sides of a coordinate on one polynomial Bézier segment: `[max side, min side]` as
/// sign-adjusted [`Side`]s (see the module docs), or `None` when the fast path cannot prove a
/// result whose gap is at most `max_gap` on every side it is asked for (`need`: [max, min];
/// a side not needed comes back incomplete and must not be used).
pub(super) fn coord_sides(seg: &Segment, max_gap: f64, need: [bool; 2]) -> Option<[Side; 2]> {
    let raw = raw_sides(seg, need)?;
    let mut out = [Side::new(), Side::new()];
    for ((sd, r), &nd) in out.iter_mut().zip(&raw).zip(&need) {
        if nd && !r.tight(max_gap) {
            return None;
        }
        sd.attain_f64(r.attained);
        sd.witness = r.witness;
        for &(ub, e) in &r.cands[..r.n] {
            sd.bound(ub, e);
        }
        sd.term = Termination::Converged;
    }
    out[0].stats.derivative_evaluations = raw[0].derivative_evaluations;
    out[0].stats.point_evaluations = raw[0].point_evaluations + raw[1].point_evaluations;
    Some(out)
}

/// The proof of the module docs on one segment, both sides as plain data `[max, min]`
/// (a side not in `need` comes back incomplete), or `None` where a step cannot be proven.
/// The caller checks the gaps.
pub(crate) fn raw_sides(seg: &Segment, need: [bool; 2]) -> Option<[RawSide; 2]> {
    let mut out = [RawSide::new(), RawSide::new()];
    raw_sides_into(seg, need, &mut out)?;
    Some(out)
}

/// [`raw_sides`] written to `out` (`[max, min]`, each starting as `RawSide::new()`), for
/// callers that keep the result in place (no move of the candidate arrays); `None` where a
/// step cannot be proven (`out` is then unspecified).
pub(crate) fn raw_sides_into(seg: &Segment, need: [bool; 2], out: &mut [RawSide; 2]) -> Option<()> {
    let Segment { c, a, b, .. } = *seg;
    let p = c.len().checked_sub(1)?;
    if (4..=5).contains(&p) {
        return descartes_sides_into(seg, need, out);
    }
    if !(2..=3).contains(&p) {
        return None;
    }
    if c.iter().all(is_f64) {
        // exact f64 coefficients: the proof of [`f64_sides`], its compact sides mapped to
        // candidate records (the ends, then the bracket, as below)
        let fv: [f64; 4] = std::array::from_fn(|i| c.get(i).map_or(0.0, |x| x.hi()));
        let pr = f64_sides(&fv, p, seg.right_attained, need)?;
        for ((side, f), sign) in out.iter_mut().zip(&pr.sides).zip([1.0, -1.0]) {
            for (t, v, kind) in [(0.0, fv[0], seg.end_kinds[0]), (1.0, fv[p], seg.end_kinds[1])] {
                side.bound(sign * v, extremum(a, b, t, t, false, kind));
            }
            if let Some((ub, t0, t1)) = f.crit {
                side.bound(ub, extremum(a, b, t0, t1, true, CandidateKind::Critical));
                side.point_evaluations = 1;
            }
            (side.upper, side.attained, side.witness) = (f.upper, f.attained, f.witness);
        }
        out[0].derivative_evaluations = pr.derivative_evaluations as u64;
        return Some(());
    }
    let mut co = Coeffs { c, poly: None };
    // The f64 filter from the `Ddi` power form of the enclosed coefficients (approximating x').
    let deriv = Deriv::new(co.poly());
    let mut derivative_evaluations = 0;
    // Test points and proven signs of x' there.
    let (z, k) = test_points(&deriv);
    // Signs at the ends, by the filter (an end slope that may be zero gives up: the lane's
    // closed-form cubic coefficients have wider ends than the insertion's, whose end values
    // that are doubles are made exact, and an open end's side would keep an inner bound an ulp
    // farther; the lane then runs the Descartes route, which opens such ends, on the
    // insertion's coefficients)
    let max_roots = p - 1;
    let (s0, s1) = (co.sign(&deriv, 0.0)?, co.sign(&deriv, 1.0)?);
    let mut s = [false; 6];
    s[0] = s0;
    s[k - 1] = s1;
    derivative_evaluations += proven_signs(&z[..k], &mut s, |t| (deriv.approx(t), deriv.err), |t| {
        sign(co.poly().dx(Ddi::exact(t)))
    })?;
    let changes = (1..k).filter(|&i| s[i] != s[i - 1]).count();
    // Upper bound R of the number of real roots (module docs, step 4): p - 1, or 0 for a
    // cubic whose discriminant is proven negative (only needed when there are few changes).
    if changes + 1 < max_roots && !no_real_roots(c) {
        return None;
    }
    // Candidates: the end values and the enclosures over the sign-change intervals.
    end_candidates(seg, out);
    // (the Taylor forms from the enclosed power form; the filter approximates x' itself)
    let pw = co.poly().x;
    let slope = |m: f64| deriv.approx(m).abs() + deriv.err;
    let m2 = second_bound(&pw[..=p]);
    derivative_evaluations += bracket_candidates(seg, &z[..k], &s[..k], need, &slope, &pw[..=p], m2, out)?;
    out[0].derivative_evaluations = derivative_evaluations;
    Some(())
}

/// The end candidates of an enclosed segment (module docs, step 5) on both sides of `out`
/// (`[max, min]`): c_0 at t = 0 (attained), c_p at t = 1 (attained if `right_attained`, else a
/// left limit at a jump), each bounding its side.
fn end_candidates(seg: &Segment, out: &mut [RawSide; 2]) {
    let Segment { c, a, b, .. } = *seg;
    let p = c.len() - 1;
    let [hi, lo] = out;
    for (t, v, kind, attained) in [
        (0.0, c[0], seg.end_kinds[0], true),
        (1.0, c[p], seg.end_kinds[1], seg.right_attained),
    ] {
        let e = extremum(a, b, t, t, false, kind);
        let (vl, vu) = if is_f64(&v) {
            (v.hi(), v.hi())
        } else {
            let v = v.to_interval();
            (v.inf(), v.sup())
        };
        if attained {
            hi.attain(vl);
            lo.attain(-vu);
        } else {
            // a left limit L at a jump: no value of the curve, but the piece equals the curve
            // left of the knot and is continuous there, so its values come arbitrarily close
            // to L and exceed (fall below) every number below (above) it: the doubles strictly
            // outside the enclosure of L are strict witnesses and values reached
            for (side, w) in [(&mut *hi, v.strictly_below()), (&mut *lo, (-v).strictly_below())] {
                side.attain(w);
                side.witness = side.witness.max(w);
            }
        }
        hi.bound(vu, e);
        lo.bound(-vl, e);
    }
}

/// The bracket candidates of an enclosed segment (module docs, step 5) on the sides of `out`
/// that `need` asks for: over each sign-change interval of the proven signs `s` at the test
/// points `z`, the Taylor form about its midpoint m ([`taylor_radius`] with `slope(m)`, an
/// upper bound of |x'(m)|) around the `Ddi` Horner value x(m) on the enclosed power form `pw`
/// (a_0 .. a_p), with max |x''(ξ) / 2| over [0, 1] <= m2 = sum_{k>=2} C(k, 2) |α_k|
/// (t^(k-2) <= 1; Lemma B: at most four products; [`second_bound`], the caller's). At most
/// one bracket per side (two, possible above degree 3, give up: a side's candidate list has
/// room for one). Returns the number of derivative evaluations, or `None`.
#[allow(clippy::too_many_arguments)]
fn bracket_candidates(
    seg: &Segment,
    z: &[f64],
    s: &[bool],
    need: [bool; 2],
    slope: &impl Fn(f64) -> f64,
    pw: &[Ddi],
    m2: f64,
    out: &mut [RawSide; 2],
) -> Option<u64> {
    let [hi, lo] = out;
    let mut evaluations = 0;
    let (brackets, nb) = side_brackets(z, s, need)?;
    for &(which, t0, t1) in &brackets[..nb] {
        let is_max = which == 0;
        // Taylor form around the midpoint m
        let (m, corr) = taylor_radius(slope, 1.0, m2, t0, t1);
        evaluations += 1;
        let xm = horner(pw, &Ddi::exact(m));
        let e = extremum(seg.a, seg.b, t0, t1, true, CandidateKind::Critical);
        // the side's upper end of x(m) ± corr (of -x for the min side)
        if is_max {
            hi.bracket(xm, corr, e);
        } else {
            lo.bracket(-xm, corr, e);
        }
    }
    Some(evaluations)
}

/// m2 >= max |x''(ξ) / 2| over [0, 1] from the enclosed power form `pw` (a_0 .. a_p):
/// sum_{k>=2} C(k, 2) |α_k| (t^(k-2) <= 1; Lemma B: at most four products).
#[inline(always)]
fn second_bound(pw: &[Ddi]) -> f64 {
    up((2..pw.len()).fold(0.0, |m, k| m + (k * (k - 1) / 2) as f64 * pw[k].abs_upper()))
}

/// The end brackets of a segment's open ends over [a, b] (module docs, step 4b; shared by the
/// rational route): over [0, h] (or [1 - h, 1]) the route's own enclosure `form(t0, t1)` =
/// (x(m), corr), x within corr of x(m) over the bracket (here the Taylor form about its
/// midpoint as in [`bracket_candidates`], the same m2; the rational route's mean value form),
/// bounds both sides that `need` asks for (the bracket may hold a maximum, a minimum or
/// neither), and the end's candidate (`at_end[side]`: the index of the end value at 0 in each
/// side's list, the one at 1 next) is widened to it.
#[inline(always)]
pub(super) fn widen_open_ends(
    (a, b): (f64, f64),
    open: [bool; 2],
    at_end: [usize; 2],
    need: [bool; 2],
    out: &mut [RawSide; 2],
    mut form: impl FnMut(f64, f64) -> (Ddi, f64),
) {
    for (end, (t0, t1)) in [(0.0, H), (1.0 - H, 1.0)].into_iter().enumerate() {
        if !open[end] {
            continue;
        }
        let (xm, corr) = form(t0, t1);
        let e = extremum(a, b, t0, t1, false, CandidateKind::Critical);
        for which in (0..2).filter(|&w| need[w]) {
            let v = if which == 0 { xm } else { -xm };
            out[which].widen_end(at_end[which] + end, v, corr, e);
        }
    }
}

/// The test points of a segment with open ends (module docs, step 4b; [`points_around`]
/// where none is open): the ascending estimates `r` without those within 2h of an open end,
/// the pairs r ± h around them, and the point h (1 - h) next to an open end 0 (1), whose
/// bracket [0, h] ([1 - h, 1]) holds the zero about that end. At most four estimates; returns
/// how many points there are.
pub(super) fn points_with_open_ends(r: &[f64], open: [bool; 2], z: &mut [f64; 12]) -> usize {
    let mut rr = [0.0f64; 4];
    let mut n = 0;
    for &t in r {
        if !((open[0] && t <= 2.0 * H) || (open[1] && t >= 1.0 - 2.0 * H)) {
            rr[n] = t;
            n += 1;
        }
    }
    let mut k = points_around(&rr[..n], &mut z[..10]);
    if open[0] {
        z.copy_within(1..k, 2);
        z[1] = H;
        k += 1;
    }
    if open[1] {
        z[k] = 1.0;
        z[k - 1] = 1.0 - H;
        k += 1;
    }
    k
}

/// Step 4 with open ends (module docs, step 4b; `bezier::rational`'s the same): c, the sign
/// changes among the proven signs `s` at the test points (all but an open end's, whose
/// derivative sign is not proven), against V: `v`, the sign changes of the coefficients other
/// than the open ends', plus one for each open end whose test point's proven sign (at h or
/// 1 - h) differs from `inner`, the proven sign of the coefficient next to that end. The count
/// holds where c <= V <= c + 1 (parity: exactly one zero in each sign-change interval, none
/// elsewhere). Returns the range i0 ..= i1 of the test points with proven signs, or `None`.
#[inline(always)]
pub(super) fn count_with_open_ends(
    s: &[bool],
    open: [bool; 2],
    inner: [bool; 2],
    v: usize,
) -> Option<(usize, usize)> {
    let k = s.len();
    let (i0, i1) = (open[0] as usize, k - 1 - open[1] as usize);
    let changes = (i0 + 1..=i1).filter(|&i| s[i] != s[i - 1]).count();
    let v = v + (open[0] && s[1] != inner[0]) as usize + (open[1] && s[k - 2] != inner[1]) as usize;
    (changes <= v && v <= changes + 1).then_some((i0, i1))
}

/// Up to two sign-change brackets (side, t0, t1): one per side.
pub(super) type Brackets = [(usize, f64, f64); 2];

/// The sign-change brackets (side, t0, t1) among the test points `z` with the proven signs
/// `s` of x' there, for the sides that `need` asks for: a change from + to - brackets a strict
/// local maximum, which is not a global minimum (x is not constant), so it matters for the
/// max side (0) only; - to + likewise for the min side (1) (module docs, step 5). At most one
/// per side: `None` for a second (two local maxima in one segment, possible above degree 3;
/// a side's candidate list has room for one).
#[inline(always)]
pub(super) fn side_brackets(
    z: &[f64],
    s: &[bool],
    need: [bool; 2],
) -> Option<(Brackets, usize)> {
    let mut out = [(0, 0.0, 0.0); 2];
    let (mut n, mut seen) = (0, [false; 2]);
    for i in 1..z.len() {
        let which = if s[i - 1] { 0 } else { 1 };
        if s[i] == s[i - 1] || !need[which] {
            continue;
        }
        if seen[which] {
            return None;
        }
        seen[which] = true;
        out[n] = (which, z[i - 1], z[i]);
        n += 1;
    }
    Some((out, n))
}

/// The f64 filter of the Descartes route ([`descartes_sides_into`], degree 2 to 5): the polynomial y(t) with
/// coefficients b_0 .. b_{m} (m = p - 1 <= 4, `n` = p of them) and |x'(t) - y(t)| <= `err`
/// for every t in [0, 1].
struct DerivN {
    b: [f64; 5],
    n: usize,
    err: f64,
}

impl DerivN {
    /// From the enclosed power coefficients a_0 .. a_p of x (2 <= p <= 5).
    ///
    /// Error bound (the argument of [`Deriv::new`] at degree m = p - 1 <= 4). With α_k the
    /// exact power coefficients (|α_k - (hi_k + lo_k)| <= rad_k) and b̂_{k-1} = fl(k hi_k)
    /// (exact for k = 1, 2, 4; for k = 3, 5 within U1 |b̂| + η): |k α_k - b̂_{k-1}| <=
    /// k (|lo_k| + rad_k) + U1 |b̂_{k-1}| + η. Horner with FMA, s_m = b̂_m, s_j =
    /// fl(s_{j+1} t + b̂_j) = (s_{j+1} t + b̂_j)(1 + δ_j) + η_j (one rounding per step,
    /// |δ_j| <= u, |η_j| <= η): the computed y is the sum of b̂_k t^k times at most m factors
    /// (1 + δ), plus the sum of η_j t^j times at most m such factors, so for t in [0, 1] it
    /// differs from the sum of b̂_k t^k by at most γ_m (|b̂_0| + .. + |b̂_m|) plus m η (1 + γ_m),
    /// with γ_4 = 4u / (1 - 4u) < 4.001 u (Higham, *Accuracy and Stability of Numerical
    /// Algorithms*, sec. 5.1). Altogether, with U1 + γ_4 < 6u and 2η + 4.01η < 8η = 2^-1072,
    ///
    ///   |x'(t) - y| <= T = sum_k k (|lo_k| + rad_k) + 6u (|b̂_0| + .. + |b̂_m|) + 2^-1072,
    ///
    /// at most seven terms of Lemma B of [`crate::num::ddi`] (products of an f64 with a sum of
    /// nonnegative f64, and a constant): `err = up(fl(T)) >= T`. A non-finite value anywhere
    /// fails every test (comparisons with NaN or inf are false), never passes.
    fn new(a: &[Ddi]) -> DerivN {
        let p = a.len() - 1;
        let mut b = [0.0f64; 5];
        let mut e = 0.0;
        let mut sum = 0.0;
        for k in 1..=p {
            let kf = k as f64;
            b[k - 1] = kf * a[k].hi();
            e += kf * (a[k].lo().abs() + a[k].rad());
            sum += b[k - 1].abs();
        }
        // 6u = 6 * 2^-53 (exact) and 2^-1072 (the bits of 4 * 2^-1074)
        let t = e + 6.0 * (f64::EPSILON / 2.0) * sum + f64::from_bits(4);
        DerivN { b, n: p, err: up(t) }
    }

    /// The f64 value y(t) (Horner with FMA, the order the bound assumes).
    #[inline]
    fn approx(&self, t: f64) -> f64 {
        self.b[..self.n]
            .iter()
            .rev()
            .fold(0.0, |acc: f64, &bk| acc.mul_add(t, bk))
    }

    /// y'(t) in f64 (no bound: only for the root estimates).
    fn slope(&self, t: f64) -> f64 {
        (1..self.n)
            .rev()
            .fold(0.0, |acc: f64, k| acc.mul_add(t, k as f64 * self.b[k]))
    }

    /// f64 estimates of the zeros of y in [0, 1], ascending, at most four (`None` if there seem
    /// to be more): sign changes of y at t = i / 16, each located by Newton's method safeguarded
    /// by bisection, and the samples where y is exactly 0. Nothing about soundness depends on
    /// them (they only choose test points); zeros they miss (two within a sixteenth) leave the
    /// root count of the proof short, which then gives up.
    fn zero_estimates(&self) -> Option<([f64; 4], usize)> {
        let mut r = [0.0f64; 4];
        let mut nr = 0;
        let mut push = |x: f64| -> Option<()> {
            if nr == 4 {
                return None;
            }
            r[nr] = x;
            nr += 1;
            Some(())
        };
        let (mut t0, mut y0) = (0.0, self.approx(0.0));
        for i in 1..=16 {
            let t1 = i as f64 / 16.0;
            let y1 = self.approx(t1);
            if y1 == 0.0 && t1 < 1.0 {
                push(t1)?;
            } else if y0 != 0.0 && y1 != 0.0 && (y0 > 0.0) != (y1 > 0.0) {
                // (Newton safeguarded by bisection from the midpoint, the loop of the general
                // fast path's estimates)
                let yd = |t: f64| (self.approx(t), self.slope(t));
                push(locate_by(yd, y0 > 0.0, t0, t1, 0.5 * (t0 + t1)))?;
            }
            (t0, y0) = (t1, y1);
        }
        Some((r, nr))
    }
}

/// The Descartes route: [`raw_sides_into`] on a polynomial segment of degree 4 or 5 with
/// enclosed coefficients (the spans of the lane's quartic and quintic splines, and its single
/// segments of those degrees), and on a quadratic or cubic span of the lane where the
/// closed-form route of the module docs gave up (an end slope not proven non-zero: an extremum
/// at or next to a knot; called there on the span's coefficients by the insertion, whose end
/// values that are doubles are exact, `SpanCache::get_ddi`): the proof of the module docs with
/// these changes.
///
/// * Step 1: the power form a_0 .. a_p in `Ddi` (forward differences, as for p <= 3).
/// * Step 2: f64 estimates of the zeros of the filter's polynomial y ≈ x' (degree p - 1 <= 4):
///   sign changes at sixteen sample points, located by safeguarded Newton
///   ([`DerivN::zero_estimates`]).
/// * Step 3: test points 0, r ± h, 1 with proven signs of x' (the filter [`DerivN`] with its
///   written bound, else a `Ddi` Horner enclosure of x' excluding 0); x'(0) = p Δc_0 and
///   x'(1) = p Δc_{p-1} by the proven signs of those differences (else step 4b).
/// * Step 4: the bound R on the zeros of x' in (0, 1) is the number V of sign changes of the
///   Bernstein coefficients Δc_0 .. Δc_{p-1} of x' / p (each enclosure proven non-zero, or
///   exactly zero and skipped; the end ones proven non-zero, so x' has no zero at 0 or 1):
///   Descartes' rule of signs for the Bernstein basis (the zeros in (0, 1), counted with
///   multiplicity, number at most V; Farin, *Curves and Surfaces for CAGD*, the variation
///   diminishing property). With c sign-change intervals among the test points and c >= V - 1,
///   each of them holds exactly one zero and every other interval none, as in step 4 of the
///   module docs. Otherwise (or with an inner enclosure that may be zero) the proof gives up.
/// * Step 4b: an end difference whose sign is not proven (Δc_0 or Δc_{p-1} about zero, or
///   exactly zero: an extremum at or next to a knot) leaves that end open, as in
///   `bezier::rational`'s step 4b: the test point h from it comes in, V counts the sign
///   changes of the other differences (a zero that a non-zero Δc_0 adds to Descartes' bound
///   lies in (0, h) where the proven sign of x'(h) is that of the next non-zero difference;
///   Δc_0 = 0 exactly deflates, x' / p = t q with q's coefficients positive multiples of the
///   others), one more where that sign differs, and the bracket [0, h] (or [1 - h, 1]) is
///   bounded for both sides by the Taylor form of step 5, the end's candidate widened to it
///   ([`widen_open_ends`]). The closed-form quadratic and cubic route does not open an
///   end: the lane's closed-form coefficients have wider ends than the exact end values of the
///   insertion, and the inner bound would be an ulp farther; the lane hands such a span to
///   this route on the insertion's coefficients instead.
/// * Step 5: as there, with |x''(ξ) / 2| <= sum_{k>=2} C(k, 2) |α_k| from the power form and
///   x(m) by Horner in `Ddi`; at most one bracket per side (a second one, two local maxima in
///   one span, gives up: the side's candidate list has room for one).
///
/// No tie rule (step 5b): a tie is left to the certificate, as on every enclosed segment.
// (not inlined: inlined, it changed the register allocation of the cubic's `f64_sides`, +85
// instructions per 2-D cubic)
#[inline(never)]
pub(crate) fn descartes_sides_into(seg: &Segment, need: [bool; 2], out: &mut [RawSide; 2]) -> Option<()> {
    let c = seg.c;
    let p = c.len() - 1;
    // Δc_i, and their sign changes V (an exact zero skipped, an enclosure that may hold 0 gives
    // up; the end ones must have a proven sign)
    let mut d = [Ddi::exact(0.0); 5];
    for (i, di) in d.iter_mut().enumerate().take(p) {
        *di = if is_f64(&c[i]) && is_f64(&c[i + 1]) {
            Ddi::diff(c[i + 1].hi(), c[i].hi())
        } else {
            c[i + 1] - c[i]
        };
    }
    // (an end difference whose sign is not proven, an exact zero included, leaves that end
    // open: step 4b; V counts the changes of the others, `inner` the signs next to the ends)
    let (e0, e1) = (sign(d[0]), sign(d[p - 1]));
    let open = [e0.is_none(), e1.is_none()];
    let mut v = 0;
    let mut inner: [Option<bool>; 2] = [None; 2];
    for di in &d[open[0] as usize..p - open[1] as usize] {
        if di.hi() == 0.0 && di.lo() == 0.0 && di.rad() == 0.0 {
            continue;
        }
        let si = sign(*di)?;
        if let Some(l) = inner[1] {
            v += (si != l) as usize;
        } else {
            inner[0] = Some(si);
        }
        inner[1] = Some(si);
    }
    let inner = [inner[0]?, inner[1]?];
    // the power form a_0 .. a_p (a_k = C(p, k) Δ^k c_0)
    let mut pw = [Ddi::exact(0.0); 6];
    pw[0] = c[0];
    pw[1..=p].copy_from_slice(&d[..p]);
    power_from_differences_in_place(&mut pw[1..=p]);
    let pw = &pw[..=p];
    let deriv = DerivN::new(pw);
    let (r, nr) = if v == 0 { ([0.0; 4], 0) } else { deriv.zero_estimates()? };
    // test points 0 < r_1 - h < r_1 + h < ... < 1 (of each pair only what lies inside (0, 1)
    // and beyond the last point; h, 1 - h next to an open end)
    let mut z = [0.0f64; 12];
    let k = points_with_open_ends(&r[..nr], open, &mut z);
    // proven signs of x' at the test points
    let dpw: [Ddi; 5] =
        std::array::from_fn(|i| if i < p { Ddi::exact((i + 1) as f64) * pw[i + 1] } else { Ddi::exact(0.0) });
    let mut s = [false; 12];
    s[0] = e0.unwrap_or(false);
    s[k - 1] = e1.unwrap_or(false);
    let mut derivative_evaluations = proven_signs(&z[..k], &mut s, |t| (deriv.approx(t), deriv.err), |t| {
        sign(horner(&dpw[..p], &Ddi::exact(t)))
    })?;
    // (the sign changes among the proven signs: all but an open end's; step 4b: one more
    // zero for an open end whose test point's sign is not that of the difference next to it)
    let (i0, i1) = count_with_open_ends(&s[..k], open, inner, v)?;
    // Candidates: the end values and the enclosures over the sign-change intervals.
    end_candidates(seg, out);
    let at_end = [out[0].n - 2, out[1].n - 2];
    // (the filter approximates x' itself: scale 1)
    let slope = |m: f64| deriv.approx(m).abs() + deriv.err;
    let m2 = second_bound(pw);
    derivative_evaluations += bracket_candidates(seg, &z[i0..=i1], &s[i0..=i1], need, &slope, pw, m2, out)?;
    widen_open_ends((seg.a, seg.b), open, at_end, need, out, |t0, t1| {
        let (m, corr) = taylor_radius(slope, 1.0, m2, t0, t1);
        derivative_evaluations += 1;
        (horner(pw, &Ddi::exact(m)), corr)
    });
    out[0].derivative_evaluations = derivative_evaluations;
    Some(())
}

/// The proven signs of x' at the inner test points z[1] .. z[k-2] into `s` (the ends are the
/// caller's): the filter's value y with its bound e (`filter(t)` = (y, e), |x' / scale - y| <=
/// e for a positive scale) where |y| > e, else the sign from `exact(t)`; `None` where neither
/// proves one. Returns the number of points tested.
#[inline]
fn proven_signs(
    z: &[f64],
    s: &mut [bool],
    filter: impl Fn(f64) -> (f64, f64),
    mut exact: impl FnMut(f64) -> Option<bool>,
) -> Option<u64> {
    let k = z.len();
    for i in 1..k - 1 {
        let (y, e) = filter(z[i]);
        s[i] = if y.abs() > e { y > 0.0 } else { exact(z[i])? };
    }
    Some(k.saturating_sub(2) as u64)
}

/// The test points of step 3 (module docs): 0, the pairs r ± h around the f64 root estimates
/// of the filter's polynomial inside (0, 1), ascending, and 1; and how many there are.
#[inline]
pub(super) fn test_points(deriv: &Deriv) -> ([f64; 6], usize) {
    let mut z = [0.0f64; 6];
    let (mut r, nr) = root_estimates(deriv.b[0], deriv.b[1], deriv.b[2]);
    // (ascending; at most two, both finite)
    if nr == 2 && r[1] < r[0] {
        r.swap(0, 1);
    }
    let k = points_around(&r[..nr], &mut z);
    (z, k)
}

/// Fills `z` (z[0] = 0) with the pairs r ± h around the ascending estimates `r` that lie
/// inside (0, 1) in increasing order (an estimate closer than 2h to the last point adds what
/// lies beyond it), then 1; returns how many points there are.
#[inline]
pub(super) fn points_around(r: &[f64], z: &mut [f64]) -> usize {
    let mut k = 1;
    for &ri in r {
        for t in [ri - H, ri + H] {
            if t > z[k - 1] && t < 1.0 {
                z[k] = t;
                k += 1;
            }
        }
    }
    z[k] = 1.0;
    k + 1
}

/// Whether the cubic's x' / 3 (Bernstein coefficients Δc_0, Δc_1, Δc_2) has a proven negative
/// discriminant Δc_1^2 - Δc_0 Δc_2, i.e. no real root (module docs, step 4); false for p = 2
/// (Δc_2 = 0: the discriminant is a square) and where the sign is not proven.
#[cold]
#[inline(never)]
fn no_real_roots(c: &[Ddi]) -> bool {
    let d = first_differences(c);
    sign(d[1] * d[1] - d[0] * d[2]) == Some(false)
}

/// The Taylor form's midpoint m of a bracket [t0, t1] and the radius `corr` with
/// |x(t) - x(m)| <= corr for every t in it (module docs, step 5): with |t - m| <= r,
/// x(t) = x(m) + x'(m) (t - m) + x''(ξ) / 2 (t - m)^2 (Lagrange remainder), so
/// |x(t) - x(m)| <= dscale (|y| + err) r + m2 r^2 <= corr (Lemma B of [`crate::num::ddi`],
/// with r2 >= r^2; `slope(m)` = |y(m)| + err for a filter y with |x'(m) / dscale - y(m)| <= err,
/// `dscale` the filter's scale back to x': 1, or 4 >= p for the filter of x' / p, a power of
/// two, so the scaling of the product term is exact).
#[inline]
fn taylor_radius(slope: impl Fn(f64) -> f64, dscale: f64, m2: f64, t0: f64, t1: f64) -> (f64, f64) {
    let m = (t0 + 0.5 * (t1 - t0)).clamp(t0, t1);
    let r = dist_up(m, t0).max(dist_up(t1, m));
    let r2 = up(r * r);
    let corr = up(dscale * (slope(m) * r) + m2 * r2);
    (m, corr)
}

/// One side of [`f64_sides`], sign-adjusted as [`RawSide`] (the min side is the max side of
/// -x): the upper bound (of the end values and the bracket), the largest attained value, the
/// strict witness, and the side's sign-change bracket (its bound, t0, t1), if it has one.
#[derive(Clone, Copy, Debug)]
pub(crate) struct F64Side {
    pub upper: f64,
    pub attained: f64,
    pub witness: f64,
    pub crit: Option<(f64, f64, f64)>,
}

impl F64Side {
    /// Whether the certified gap (bound minus attained value) is at most `max_gap` (false for
    /// a NaN gap).
    pub fn tight(&self, max_gap: f64) -> bool {
        self.upper - self.attained <= max_gap
    }
}

/// Both sides of [`f64_sides`] (`[max, min]`) and the number of derivative evaluations.
#[derive(Clone, Copy, Debug)]
pub(crate) struct F64Proof {
    pub sides: [F64Side; 2],
    pub derivative_evaluations: u32,
}

/// The proof of the module docs for exact f64 coefficients c_0 .. c_p (`fv[..=p]`, p = 2 or
/// 3), in f64 and double-double on the stack, without candidate records: the form the lane
/// reads directly (a cubic Bézier's coordinate), and [`raw_sides_into`] maps to [`RawSide`]s.
/// The end values are c_0 (attained) and c_p (attained if `right_attained`, else a left limit
/// at a jump, approached: its next double down reached and a strict witness); each side has at
/// most one sign-change bracket (the sign changes alternate, and there are at most R <= 2 of
/// them; a second one for a side, impossible, gives up). `None` where a step cannot be proven;
/// a side not in `need` comes back with its end values only. The caller checks the gaps.
#[inline]
pub(crate) fn f64_sides(
    fv: &[f64; 4],
    p: usize,
    right_attained: bool,
    need: [bool; 2],
) -> Option<F64Proof> {
    if !(2..=3).contains(&p) {
        return None;
    }
    let c = &fv[..=p];
    // The f64 filter straight from the data, approximating x' / p; only signs are read from
    // it, and the Taylor correction scales it back by 4 >= p.
    let deriv = Deriv::from_f64(c);
    let (z, k) = test_points(&deriv);
    // Signs at the ends: exact comparisons, x'(0) = p (c_1 - c_0), x'(1) = p (c_p - c_{p-1}).
    // If x'(0) = 0 exactly, x' = t q(t) with q of degree p - 2 and q(0) = (p - 1)(c_2 - c_1)
    // (Bernstein coefficients of x' / p: Δc_0 = 0, Δc_1, ...; divide out t), so x' has the sign
    // of c_2 - c_1 just right of 0 and the roots of x' in (0, 1] are those of q: one fewer.
    // The same at t = 1 with c_{p-1} - c_{p-2}. The sign of q at the end replaces that of x'
    // there, and the counting of step 4 runs on q (x' = t q or (1 - t) q or t (1 - t) q has
    // the sign of q inside (0, 1)).
    let mut max_roots = p - 1;
    let mut end_sign = |x: f64, y: f64, x2: f64, y2: f64| -> Option<bool> {
        if x != y {
            return Some(x > y);
        }
        max_roots -= 1;
        (x2 != y2).then_some(x2 > y2)
    };
    let s0 = end_sign(c[1], c[0], c[2], c[1])?;
    let s1 = end_sign(c[p], c[p - 1], c[p - 1], c[p - 2])?;
    let mut s = [false; 6];
    s[0] = s0;
    s[k - 1] = s1;
    let mut derivative_evaluations = 0;
    // |x'(t) / p - y| <= err < |y|: x'(t) has the sign of y; else a `Ddi` evaluation
    derivative_evaluations += proven_signs(&z[..k], &mut s, |t| (deriv.approx(t), deriv.err), |t| {
        exact_sign_of_slope(c, t)
    })? as u32;
    let changes = (1..k).filter(|&i| s[i] != s[i - 1]).count();
    // Upper bound R of the number of real roots (module docs, step 4): p - 1 less the exact
    // zeros at the ends, or 0 for a cubic whose discriminant is proven negative.
    if changes + 1 < max_roots {
        let cd: [Ddi; 4] = fv.map(Ddi::exact);
        if !no_real_roots(&cd[..=p]) {
            return None;
        }
    }
    let (c0, cp) = (c[0], c[p]);
    // (c_p is a value of the curve if `right_attained`, else a left limit at a jump that the
    // piece approaches, continuous on [0, 1] and equal to the curve left of the knot: every
    // double below it is exceeded, next_down(c_p) a strict witness and a value reached)
    let end_side = |v0: f64, vp: f64| {
        let (att, witness) = if right_attained {
            (vp, f64::NEG_INFINITY)
        } else {
            (vp.next_down(), vp.next_down())
        };
        F64Side {
            upper: v0.max(vp),
            attained: v0.max(att),
            witness,
            crit: None,
        }
    };
    let mut sides = [end_side(c0, cp), end_side(-c0, -cp)];
    // max |x''(ξ) / 2| over [0, 1] <= m2: x''/2 = p (p - 1)/2 sum_i (D_{i+1} - D_i) B_i^{p-2}
    // with |D_i| <= (1 + U1) |d_i|, so |x''/2| <= p (p - 1) (1 + U1) max |d_i|
    // <= up(p (p - 1) (|d_0| + |d_1| + |d_2|)) (Lemma B), d_i = fl(D_i).
    let d = (1..=p).fold(0.0, |s, i| s + (c[i] - c[i - 1]).abs());
    let m2 = up((p * (p - 1)) as f64 * d);
    for i in 1..k {
        // A sign change from + to - brackets a strict local maximum, which is not a global
        // minimum (x is not constant), so it matters for the max side only; - to + likewise
        // for the min side (module docs, step 5).
        let is_max = s[i - 1];
        let which = if is_max { 0 } else { 1 };
        if s[i] == s[i - 1] || !need[which] {
            continue;
        }
        let (t0, t1) = (z[i - 1], z[i]);
        let (m, corr) = taylor_radius(|m| deriv.approx(m).abs() + deriv.err, 4.0, m2, t0, t1);
        derivative_evaluations += 1;
        // x(m) by the compensated de Casteljau algorithm (a priori bound, no power form)
        let xm = Ddi::de_casteljau_f64(c, m);
        // (-xm by products with the sign, exact as the negation, without a jump on the side:
        // which side a bracket serves is a coin toss on random data)
        let v = xm.signed(if is_max { 1.0 } else { -1.0 });
        let side = &mut sides[which];
        if side.crit.is_some() {
            return None;
        }
        // the side's upper end of x(m) ± corr, rounded outward
        let mut ub = v.widen(corr).upper_end();
        // x(m) is attained: its lower end (a NaN one, after an overflow, is ignored by max),
        // and the largest f64 strictly below it a witness
        side.attained = side.attained.max(v.lower_end());
        side.witness = side.witness.max(v.strictly_below());
        // A tie (module docs, step 5b): the bound and the values seen leave the optimal double
        // open (the attained value below the bound, no witness at next_down(bound)). The exact
        // sign of M - d for a double d, M the bracket's maximum, decides: M <= d lowers the
        // bound to d (M = d: also attained), M > d makes d a witness. A near tie (the
        // bracket's own value within two doubles of its bound) takes d = next_down(bound), at
        // most twice. A far tie: the bracket's value is the side's largest and within 2^-40
        // of the coefficients' scale of its bound, yet more than two doubles below it (M
        // near zero against the coordinate's scale, where the doubles are far finer than
        // any enclosure from the coefficients, e.g. a curve tangent to an axis: M = 0
        // exactly). There d is chosen from the estimate of M that each comparison returns
        // (the first d is 0 if it lies in range: the exact tie), inside the open interval
        // (witness, bound) and not below the bracket's value (M >= it); each comparison
        // shrinks that interval, at most FAR_TIES times. (A wide bracket's loose bound is
        // no tie.) Without this the certificate had to decide such a side by the general
        // certification's exact search, 10^2-10^3 times the whole enclosure's time.
        let own = v.lower_end();
        let far = own < ub.next_down().next_down()
            && own >= side.attained
            && ub - own <= fv[..=p].iter().fold(0.0f64, |m, x| m.max(x.abs())) * H;
        let mut est = f64::NAN;
        for i in 0..if far { FAR_TIES } else { 2 } {
            let next = ub.next_down();
            if !(ub.is_finite() && side.attained < ub && side.witness < next) {
                break;
            }
            let d = if own >= next.next_down() {
                next
            } else if far {
                let lo = own.max(side.witness.next_up());
                let guess = if est.is_finite() {
                    est
                } else if i == 0 && lo <= 0.0 && 0.0 <= next {
                    // (signed as the side: the min side's bound -0 is the box's lo +0)
                    if is_max {
                        0.0
                    } else {
                        -0.0
                    }
                } else {
                    next
                };
                // (lo <= next: the witness lies below next, the bracket's value more than
                // two doubles below the bound; max / min rather than a clamp, which would
                // panic on anything else)
                guess.max(lo).min(next)
            } else {
                break;
            };
            let signed: [f64; 4] = std::array::from_fn(|i| if is_max { fv[i] } else { -fv[i] });
            match bracket_max_cmp(&signed[..=p], t0, t1, d) {
                Some((ord, diff)) => {
                    est = d + diff;
                    match ord {
                        Ordering::Less => ub = d,
                        Ordering::Equal => {
                            ub = d;
                            side.attained = side.attained.max(d);
                        }
                        Ordering::Greater => side.witness = d,
                    }
                }
                None => break,
            }
        }
        // (a NaN end, after an overflow, bounds nothing: +inf)
        let ub = if ub.is_nan() { f64::INFINITY } else { ub };
        side.upper = side.upper.max(ub);
        side.crit = Some((ub, t0, t1));
    }
    Some(F64Proof {
        sides,
        derivative_evaluations,
    })
}

/// The proven sign of x'(t) for exact f64 coefficients by a `Ddi` Horner evaluation on the
/// enclosed power form (where the f64 filter leaves it open; rare).
#[cold]
#[inline(never)]
fn exact_sign_of_slope(c: &[f64], t: f64) -> Option<bool> {
    let cd: [Ddi; 4] = std::array::from_fn(|i| Ddi::exact(c.get(i).copied().unwrap_or(0.0)));
    sign(Poly::new(&cd[..c.len()]).dx(Ddi::exact(t)))
}

#[cfg(test)]
pub(super) mod tests {
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
            let v = horner(&poly.x[..=poly.p], &Ddi::exact(t)).to_interval();
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

    /// The filter's a-priori bound of `Deriv::from_f64` holds against exact rational
    /// arithmetic: |q(t) - y(t)| <= err for q = x' / p, on random, clustered, cancelling and
    /// extreme-magnitude coefficients and parameters t in [0, 1] (ends, tiny, near 1).
    #[test]
    fn f64_filter_bound_holds_exactly() {
        use crate::num::Exact;
        use rand::{Rng, SeedableRng};
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let mut worst: f64 = 0.0;
        for it in 0..4000 {
            let p = if it % 3 == 0 { 2 } else { 3 };
            let mag = 2f64.powi(r.random_range(-80..=80));
            let base: f64 = r.random_range(-1.0..1.0) * mag;
            let c: Vec<f64> = (0..=p)
                .map(|_| match it % 4 {
                    // clustered: differences cancel in the second differences
                    0 => base + r.random_range(-1.0..1.0) * mag * 1e-12,
                    1 => r.random_range(-8.0f64..8.0).round() * mag,
                    _ => r.random_range(-1.0..1.0) * mag,
                })
                .collect();
            let dv = Deriv::from_f64(&c);
            let t = match it % 5 {
                0 => 0.0,
                1 => 1.0,
                2 => r.random_range(0.0..1e-12),
                3 => 1.0 - r.random_range(0.0..1e-12),
                _ => r.random_range(0.0..1.0),
            };
            // q(t) = sum_i D_i B_i^{p-1}(t) exactly, D_i = c_{i+1} - c_i
            let (te, one) = (Exact::of(t), Exact::of(1.0));
            let s = one - te.clone();
            let d: Vec<Exact> = (0..p).map(|i| Exact::of(c[i + 1]) - Exact::of(c[i])).collect();
            let q = if p == 2 {
                d[0].clone() * s + d[1].clone() * te
            } else {
                d[0].clone() * s.clone() * s.clone()
                    + Exact::of(2.0) * d[1].clone() * s * te.clone()
                    + d[2].clone() * te.clone() * te
            };
            let y = dv.approx(t);
            let (lo, hi) = (Exact::of(y) - Exact::of(dv.err), Exact::of(y) + Exact::of(dv.err));
            assert!(
                !(lo.clone() - q.clone()).gt_f64(0.0) && !(q.clone() - hi).gt_f64(0.0),
                "{c:?} at {t}: y = {y}, err = {}",
                dv.err
            );
            worst = worst.max(dv.err / mag);
        }
        // the bound is an error bound, not a vacuous one: a few hundred u of the scale at most
        assert!(worst < 1e-12, "{worst}");
    }

    /// Random coefficient sets of degree p0 and p0 + 1 (alternating; quartic and quintic, or
    /// quadratic and cubic) for the tests of [`descartes_sides_into`]: f64 values (random, clustered around a base, small
    /// integers times a power of two, a symmetric peak, a near-double zero of x', monotone),
    /// each either exact or enclosed with a double-word part and a radius as the lane's
    /// extraction leaves them; and exact coefficients inside every enclosure (centre, or an
    /// end of the radius).
    ///
    /// `flat`: every case made flat at an end, x'(0) = 0 (`(index / 6) % 3` = 0: c_1 = c_0),
    /// x'(1) = 0 (1: c_{p-1} = c_p) or both (2), half of them with that end above every other
    /// value (a flat maximum there: an extremum at a knot); the enclosed ones then hold exact
    /// coefficients whose end slope is tiny, of either sign, or zero.
    fn descartes_cases(seed: u64, count: usize, flat: bool, p0: usize) -> Vec<(Vec<Ddi>, Vec<crate::num::Exact>)> {
        use crate::num::Exact;
        use rand::{Rng, SeedableRng};
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        (0..count)
            .map(|it| {
                let p = p0 + it % 2;
                let mag = 2f64.powi(r.random_range(-60..=60));
                let base: f64 = r.random_range(-1.0..1.0) * mag;
                let c: Vec<f64> = (0..=p)
                    .map(|i| match it % 6 {
                        0 => base + r.random_range(-1.0..1.0) * mag * 1e-9,
                        1 => r.random_range(-8.0f64..8.0).round() * mag,
                        // a symmetric peak (x' zero at 1/2)
                        2 => {
                            let m = p as f64 / 2.0;
                            mag * (1.0 - ((i as f64 - m) / m).powi(2))
                        }
                        // a near-double zero of x': a flat top perturbed by a few ulps
                        3 => {
                            let v = [0.0, 1.0, 1.0, 1.0, 1.0, 0.0][i.min(5)];
                            mag * v + r.random_range(-4.0..4.0) * mag * f64::EPSILON
                        }
                        // monotone
                        4 => mag * i as f64 + r.random_range(0.0..0.5) * mag,
                        _ => r.random_range(-1.0..1.0) * mag,
                    })
                    .collect();
                let mut c = c;
                // (which ends are flat: 0 the first, 1 the last, 2 both)
                let ends = (it / 6) % 3;
                if flat {
                    let top = c.iter().fold(0.0f64, |m, x| m.max(x.abs())) + 0.5 * mag;
                    if ends != 1 {
                        if it % 2 == 0 {
                            c[0] = top;
                        }
                        c[1] = c[0];
                    }
                    if ends != 0 {
                        if it % 2 == 0 {
                            c[p] = top;
                        }
                        c[p - 1] = c[p];
                    }
                }
                let enclosed = it % 3 != 0;
                let side: f64 = [-1.0, 0.0, 1.0][it % 3];
                let mut pairs: Vec<(Ddi, Exact)> = c
                    .iter()
                    .map(|&x| {
                        if enclosed {
                            let lo = x * r.random_range(-1.0..1.0) * f64::EPSILON * 0.25;
                            let rad = x.abs() * 2f64.powi(-100);
                            let d = Ddi::from_parts(x, lo, rad);
                            let e = Exact::of(x) + Exact::of(lo) + Exact::of(side) * Exact::of(rad);
                            (d, e)
                        } else {
                            (Ddi::exact(x), Exact::of(x))
                        }
                    })
                    .collect();
                if flat {
                    // (a flat end's two coefficients the same enclosure and exact value: the
                    // end difference encloses 0 and is 0)
                    if ends != 1 {
                        pairs[1] = pairs[0].clone();
                    }
                    if ends != 0 {
                        pairs[p - 1] = pairs[p].clone();
                    }
                }
                pairs.into_iter().unzip()
            })
            .collect()
    }

    /// Checks that each open end's bracket of the sides `out` (step 4b: [0, h] or [1 - h, 1],
    /// its candidate, the first (second) of each side, spanning it) is bounded within `slack`
    /// (an ulp of the scale) above the end value's own bound (`ends`: the end values' enclosures,
    /// the candidates before they were widened); returns how many were checked.
    pub(crate) fn open_ends_within_an_ulp(out: &[RawSide; 2], ends: [Ddi; 2], slack: f64, case: &str) -> usize {
        use crate::num::Exact;
        let mut checked = 0;
        for (sd, sign) in out.iter().zip([1.0, -1.0]) {
            for (end, &v) in ends.iter().enumerate() {
                let (b, e) = sd.cands[end];
                if e.u_lo < e.u_hi {
                    let own = if sign > 0.0 { v } else { -v }.upper_end();
                    let over = Exact::of(b) - Exact::of(own);
                    assert!(!over.gt_f64(slack), "{case}: end {end}: {b} over {own} by {:e}", over.to_f64());
                    checked += 1;
                }
            }
        }
        checked
    }

    /// The points t = i / 256 and, on each sample interval where the exact sign `sg` of a
    /// derivative changes, the ends of its bracket bisected to 2^-60 (the exact extremes of a
    /// segment lie among the values there, up to ~2^-120 of the scale).
    pub(crate) fn samples_and_zeros(sg: impl Fn(f64) -> Option<Ordering>) -> Vec<f64> {
        let ts: Vec<f64> = (0..=256).map(|i| i as f64 / 256.0).collect();
        let mut pts = ts.clone();
        for w in ts.windows(2) {
            let (mut a, mut b) = (w[0], w[1]);
            let (sa, sb) = (sg(a), sg(b));
            if sa == sb || sa == Some(Ordering::Equal) || sb == Some(Ordering::Equal) {
                continue;
            }
            for _ in 0..60 {
                let m = 0.5 * (a + b);
                if m <= a || m >= b {
                    break;
                }
                if sg(m) == sa {
                    a = m;
                } else {
                    b = m;
                }
            }
            pts.extend([a, b]);
        }
        pts
    }

    /// The exact value at t of the Bernstein polynomial with exact coefficients `c`.
    pub(crate) fn bernstein_exact(c: &[crate::num::Exact], t: f64) -> crate::num::Exact {
        use crate::num::Exact;
        let n = c.len() - 1;
        let (te, se) = (Exact::of(t), Exact::of(1.0) - Exact::of(t));
        let mut sum = Exact::of(0.0);
        for (k, ck) in c.iter().enumerate() {
            let mut term = ck.clone() * Exact::of(crate::num::binom(n, k));
            for _ in 0..k {
                term = term * te.clone();
            }
            for _ in k..n {
                term = term * se.clone();
            }
            sum = sum + term;
        }
        sum
    }

    /// The filter of degree 1 to 4 ([`DerivN`], segments of degree 2 to 5) against exact
    /// arithmetic: |x'(t) - y(t)| <= err for the exact coefficients anywhere in the enclosures
    /// (centres and radius ends), at t = 0, 1, tiny, near 1 and random; and the bound is an
    /// error bound, not a vacuous one.
    #[test]
    fn quintic_filter_bound_holds_exactly() {
        use crate::num::Exact;
        let mut worst: f64 = 0.0;
        let ts = [0.0, 1.0, 1e-13, 1.0 - 1e-12, 0.5, 0.3, 0.9];
        for (c, ce) in descartes_cases(17, 3000, false, 4).into_iter().chain(descartes_cases(18, 3000, false, 2)) {
            let p = c.len() - 1;
            let mut pw = [Ddi::exact(0.0); 6];
            pw[0] = c[0];
            for i in 0..p {
                pw[i + 1] = c[i + 1] - c[i];
            }
            power_from_differences_in_place(&mut pw[1..=p]);
            let dv = DerivN::new(&pw[..=p]);
            let d: Vec<Exact> = (0..p).map(|i| ce[i + 1].clone() - ce[i].clone()).collect();
            let scale = c.iter().fold(0.0f64, |m, x| m.max(x.hi().abs()));
            for &t in &ts {
                // x'(t) = p sum_i Δc_i B_i^{p-1}(t)
                let q = Exact::of(p as f64) * bernstein_exact(&d, t);
                let y = dv.approx(t);
                let dev = q - Exact::of(y);
                assert!(
                    !dev.gt_f64(dv.err) && !(-dev).gt_f64(dv.err),
                    "{c:?} at {t}: y = {y}, err = {}",
                    dv.err
                );
            }
            if scale > 0.0 {
                worst = worst.max(dv.err / scale);
            }
        }
        assert!(worst < 1e-11, "{worst}");
    }

    /// [`descartes_sides_into`] against exact arithmetic, on segments of degree 4 and 5 and
    /// (as the lane hands it quadratic and cubic spans with an open end) of degree 2 and 3: on
    /// every side it proves, every
    /// exact value of the polynomial (the exact coefficients inside the enclosures) at 257
    /// points and at its zeros of x' (located by exact bisection to 2^-60) lies at or below the
    /// bound, and the attained value at or below the exact maximum. Most cases are proved with
    /// both gaps within a few ulps of the scale (the path is not vacuous); the near-double
    /// zeros may give up. The same on 600 cases flat at an end (`descartes_cases` with `flat`),
    /// two in five of each kind proved within 8 ulps, and every open end's bracket bounded
    /// within an ulp of the scale above the end value's own bound: fails when an open end gives
    /// up (0 of 200), when every open end adds one to V, and when an open end's correction is
    /// 2^30 times larger.
    #[test]
    fn descartes_sides_bound_the_exact_extremes() {
        for (p0, seeds) in [(4, (23, 24)), (2, (25, 26))] {
            check_descartes_sides(p0, seeds);
        }
    }

    fn check_descartes_sides(p0: usize, (s0, s1): (u64, u64)) {
        use crate::num::Exact;
        let mut proved = 0;
        let mut cases = descartes_cases(s0, 1200, false, p0);
        let n = cases.len();
        cases.extend(descartes_cases(s1, 600, true, p0));
        // (per kind of case: proved within 8 ulps; per kind of flat end)
        let (mut kinds, mut flat, mut open_ends) = ([0usize; 6], [0usize; 3], 0);
        for (ci, (c, ce)) in cases.into_iter().enumerate() {
            let p = c.len() - 1;
            let seg = Segment {
                c: &c,
                a: 0.0,
                b: 1.0,
                end_kinds: [CandidateKind::EndPoint; 2],
                right_attained: true,
            };
            let mut out = [RawSide::new(), RawSide::new()];
            if descartes_sides_into(&seg, [true, true], &mut out).is_none() {
                continue;
            }
            // the exact extremes: samples and the zeros of x' (exact bisection on sign changes
            // of x' between samples)
            let d: Vec<Exact> = (0..p).map(|i| ce[i + 1].clone() - ce[i].clone()).collect();
            let pts = samples_and_zeros(|t| bernstein_exact(&d, t).signum());
            let scale = c.iter().fold(0.0f64, |m, x| m.max(x.hi().abs()));
            let (mut max_seen, mut min_seen) = (f64::NEG_INFINITY, f64::INFINITY);
            for &t in &pts {
                let v = bernstein_exact(&ce, t);
                assert!(!v.gt_f64(out[0].upper), "{c:?}: x({t}) above {}", out[0].upper);
                assert!(!(-v.clone()).gt_f64(out[1].upper), "{c:?}: x({t}) below {}", -out[1].upper);
                max_seen = max_seen.max(v.round_up());
                min_seen = min_seen.min(-(-v).round_up());
            }
            // attained values are values the curve reaches (at most its exact extremes, which
            // the values at the refined zeros, 2^-60 from them, miss by ~2^-120 of the scale:
            // one ulp of slack for a double in between)
            let slack = crate::num::ulp(scale);
            assert!(out[0].attained <= max_seen + slack, "{c:?}: {} > {max_seen}", out[0].attained);
            assert!(-out[1].attained >= min_seen - slack, "{c:?}: {} < {min_seen}", -out[1].attained);
            // (a sign change over a wide interval, where an estimate is missing, is bounded
            // soundly but loosely: the lane then gives the span to the general fast path)
            let ok = out.iter().all(|sd| sd.upper - sd.attained <= 8.0 * crate::num::ulp(scale));
            if ci < n {
                proved += ok as usize;
                kinds[ci % 6] += ok as usize;
            } else {
                flat[((ci - n) / 6) % 3] += ok as usize;
            }
            // (the radii are 2^-100 of the values: tight data)
            open_ends += open_ends_within_an_ulp(&out, [c[0], c[p]], slack, &format!("{c:?}"));
        }
        // (the open ends' brackets checked within an ulp: 1,330 (degree 4 and 5) and 1,312
        // (2 and 3) when written)
        assert!(open_ends >= 600, "only {open_ends} open ends bounded");
        // every symmetric peak and every monotone case; random coefficients often have more
        // sign changes in their Bernstein differences than zeros of x' in [0, 1] (Descartes'
        // bound is loose there), and those give up to the general fast path
        assert!(kinds[2] == n / 6 && kinds[4] == n / 6, "{kinds:?}");
        assert!(proved * 2 >= n, "only {proved} of {n} proved within 8 ulps: {kinds:?}");
        // the flat ends (an end difference not provably non-zero, the end's bracket of step
        // 4b): about as many as of the cases without one (127, 153, 186 of 200 at degree 4 and
        // 5, 196, 181, 158 at 2 and 3 when written)
        assert!(flat.iter().all(|&f| f * 5 >= 2 * 200), "flat ends proved: {flat:?} of 200 each");
    }

    /// Exact ties at the critical point (step 5b): symmetric quadratics and cubics with few-bit
    /// control values get bound = attained value = the exact extremum, (a + b) / 2 and
    /// (a + 3 b) / 4; a near-tie (the extremum ~2^-70 relative off a double) and a generic
    /// arc keep a bound strictly above their attained value.
    #[test]
    fn exact_ties_at_the_critical_point_are_bound_exactly() {
        use rand::{Rng, SeedableRng};
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(9);
        let mut fired = 0;
        for _ in 0..200 {
            let a = r.random_range(-4096i32..4096) as f64 / 64.0;
            let b = a + r.random_range(1i32..4096) as f64 / 64.0;
            for (c, v) in [(vec![a, b, a], (a + b) / 2.0), (vec![a, b, b, a], (a + 3.0 * b) / 4.0)] {
                let [hi, lo] = sides(&c).unwrap();
                assert_eq!((hi.upper, hi.attained), (v, v), "{c:?}");
                fired += 1;
                // the mirror image: the minimum
                let m: Vec<f64> = c.iter().map(|x| -x).collect();
                let [_, lo2] = sides(&m).unwrap();
                assert_eq!((-lo2.upper, -lo2.attained), (-v, -v), "{m:?}");
                // the other side is an end value (exact anyway)
                assert_eq!(-lo.upper, a);
            }
        }
        assert_eq!(fired, 400);
        // near-tie: P0 = 2^-70, P1 = 1, P2 = 0: max (1 - 0) / (2 - 2^-70) ~ 1/2 + 2^-72, not a
        // double; generic: max of (0, 1, 0.3) not a double
        for c in [[2f64.powi(-70), 1.0, 0.0], [0.0, 1.0, 0.3]] {
            let [hi, _] = sides(&c).unwrap();
            assert!(hi.upper > hi.attained, "{c:?}");
        }
    }

    /// `bracket_max_cmp` (pseudo-remainder and root location) against an independent exact
    /// computation: t* isolated by bisection on the sign of x' at rational points to a width
    /// w = 2^-220, then M = x(t*) lies in [v, v + L w] with v the larger of the values at the
    /// ends of that interval and L = |q_0| + |q_1| + |q_2| >= |x'| on [0, 1] (x rises up to t*
    /// and falls after it). Near-tie quadratics and cubics (the extremum within 2^-60 ..
    /// 2^-110 of a double, both sides) and random ones, d the doubles around M; and exact ties
    /// (symmetric arcs), where M = d must come out as `Equal`.
    #[test]
    fn bracket_comparison_matches_bisection() {
        use num_bigint::BigInt;
        use num_rational::BigRational;
        use num_traits::{Signed, ToPrimitive, Zero};
        use rand::{Rng, SeedableRng};
        let q = |x: f64| BigRational::from_float(x).unwrap();
        // x(t) and x'(t) exactly (de Casteljau / hodograph in rationals)
        let bern = |c: &[BigRational], t: &BigRational| -> BigRational {
            let mut b = c.to_vec();
            for k in 1..b.len() {
                for i in 0..b.len() - k {
                    b[i] = &b[i] * (BigRational::from_integer(1.into()) - t) + &b[i + 1] * t;
                }
            }
            b[0].clone()
        };
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(17);
        let (mut decided, mut near, mut proofs, mut optimal) = (0, 0, 0, 0);
        for it in 0..200 {
            let p = if it % 2 == 0 { 2 } else { 3 };
            let s = 2f64.powi(r.random_range(-30..=30)) * if r.random_bool(0.5) { 1.0 } else { -1.0 };
            let mut e = || {
                let m = r.random_range(1..=7) as f64;
                m * 2f64.powi(-r.random_range(60..=110)) * if r.random_bool(0.5) { 1.0 } else { -1.0 }
            };
            let c: Vec<f64> = match (it % 4 < 2, p) {
                (true, 2) => vec![s * e(), s, s * e()],
                (true, _) => vec![s * e(), s, s, s * e()],
                _ => (0..=p).map(|_| r.random_range(-1.0..1.0) * s.abs()).collect(),
            };
            // the max side of x or of -x, whichever has an interior maximum
            for sg in [1.0, -1.0] {
                let cs: Vec<f64> = c.iter().map(|x| sg * x).collect();
                let cq: Vec<BigRational> = cs.iter().map(|&x| q(x)).collect();
                let dq: Vec<BigRational> = cq.windows(2).map(|w| &w[1] - &w[0]).collect();
                let dv = Deriv::from_f64(&cs);
                let (roots, nr) = root_estimates(dv.b[0], dv.b[1], dv.b[2]);
                for &rt in &roots[..nr] {
                    let (t0, t1) = (rt - H, rt + H);
                    if !(0.0 < t0 && t1 < 1.0) {
                        continue;
                    }
                    // a max bracket with one root: x' > 0 at t0, < 0 at t1, the other root far
                    let (a0, a1) = (bern(&dq, &q(t0)), bern(&dq, &q(t1)));
                    if !(a0.is_positive() && a1.is_negative()) {
                        continue;
                    }
                    if nr == 2 && (roots[0] - roots[1]).abs() < 1e-6 {
                        continue;
                    }
                    let (mut lo, mut hi) = (q(t0), q(t1));
                    for _ in 0..220 {
                        let mid = (&lo + &hi) / BigRational::from_integer(2.into());
                        if bern(&dq, &mid).is_positive() {
                            lo = mid;
                        } else {
                            hi = mid;
                        }
                    }
                    let v = std::cmp::max(bern(&cq, &lo), bern(&cq, &hi));
                    let lip: BigRational = dq.iter().map(|x| x.abs()).sum::<BigRational>()
                        * BigRational::from_integer(BigInt::from(p));
                    let top = &v + lip * (&hi - &lo);
                    let m = v.to_f64().unwrap_or(0.0);
                    // the proof's bound over this bracket (step 5, with the near-tie rule of
                    // step 5b) is at least M, its attained value and witness at most M
                    let mut fv = [0.0; 4];
                    fv[..=p].copy_from_slice(&cs);
                    if let Some(pr) = f64_sides(&fv, p, true, [true, false]) {
                        let sd = pr.sides[0];
                        if let Some((ub, b0, b1)) = sd.crit {
                            assert_eq!((b0, b1), (t0, t1));
                            assert!(q(ub) >= v, "{cs:?}: bound {ub:e} below the maximum");
                            // (the side's values include the end values)
                            let gtop = [q(cs[0]), q(cs[p])].into_iter().fold(top.clone(), std::cmp::max);
                            assert!(q(sd.attained) <= gtop && q(sd.witness) < gtop, "{cs:?}");
                            proofs += 1;
                            optimal += (q(ub.next_down()) < v) as usize;
                        }
                    }
                    for d in [m.next_down().next_down(), m.next_down(), m, m.next_up(), m.next_up().next_up()] {
                        let dq_ = q(d);
                        let want = if v > dq_ {
                            Ordering::Greater
                        } else if top < dq_ {
                            Ordering::Less
                        } else {
                            continue; // undecided by the bisection (d within 2^-200 of M)
                        };
                        near += (((&v - &dq_).abs() / dq_.abs().max(BigRational::from_float(1e-300).unwrap()))
                            < BigRational::from_float(2f64.powi(-58)).unwrap()) as usize;
                        assert_eq!(bracket_max_cmp(&cs, t0, t1, d).map(|r| r.0), Some(want), "{cs:?} [{t0}, {t1}] d = {d:e}");
                        decided += 1;
                    }
                }
            }
        }
        assert!(decided > 300 && near > 60, "{decided} {near}");
        // (the near-tie rule makes the bracket's bound the optimal double on most of them)
        assert!(proofs > 100 && optimal * 10 > proofs * 9, "{proofs} {optimal}");
        // exact ties: (a, b, a) has M = (a + b) / 2 at 1/2, (a, b, b, a) M = (a + 3 b) / 4
        for (c, m) in [(vec![1.0, 3.0, 1.0], 2.0), (vec![0.5, 2.5, 2.5, 0.5], 2.0)] {
            let (t0, t1) = (0.5 - H, 0.5 + H);
            assert_eq!(bracket_max_cmp(&c, t0, t1, m).map(|r| r.0), Some(Ordering::Equal));
            assert_eq!(bracket_max_cmp(&c, t0, t1, m.next_up()).map(|r| r.0), Some(Ordering::Less));
            assert_eq!(bracket_max_cmp(&c, t0, t1, m.next_down()).map(|r| r.0), Some(Ordering::Greater));
        }
        let _ = BigRational::zero();
    }

    /// Far ties (step 5b): an interior extremum M near zero against the coefficients' scale,
    /// where the doubles around M are far finer than the bracket's double-double enclosure:
    /// quadratics and cubics tangent to zero at a rational t* that is no double (M = 0
    /// exactly: (k m^2, -k m n, k n^2), and K (alpha t - beta)^2 (gamma t + delta) in
    /// Bernstein form), the same with one coefficient moved by an ulp (M tiny, either sign),
    /// and quadratics (a, -sqrt(a c), c) rounded (M ~ 1e-17 a). Each side comes back sound
    /// against the exact M (a rational for quadratics, 0 for exact tangencies; otherwise an
    /// exact bisection on the sign of x' near t*, to 2^-80 of |M| or 2^-1400, as in
    /// [`bracket_comparison_matches_bisection`]'s reference) and with the optimal
    /// double proved by the first rule (the bound attained, or a strict witness at
    /// next_down(bound)): no certification search is left to do. An exact zero comes out
    /// attained, as +0 on the box's lo side.
    #[test]
    fn far_ties_give_the_optimal_double_at_once() {
        use num_bigint::BigInt;
        use num_rational::BigRational;
        use num_traits::{Signed, Zero};
        use rand::{Rng, SeedableRng};
        let q = |x: f64| BigRational::from_float(x).unwrap();
        let int = |k: i64| BigRational::from_integer(BigInt::from(k));
        let bern = |c: &[BigRational], t: &BigRational| -> BigRational {
            let mut b = c.to_vec();
            for k in 1..b.len() {
                for i in 0..b.len() - k {
                    b[i] = &b[i] * (int(1) - t) + &b[i + 1] * t;
                }
            }
            b[0].clone()
        };
        // the exact interior minimum, as an interval [lo, hi] of rationals: a quadratic's in
        // closed form (lo = hi); a cubic's by bisection at the root t* of x' where it turns
        // from - to + within 2^-30 of `near` (checked exactly; the other root is then a local
        // maximum, so that the minimum over [0, 1] is this one or an end value)
        let exact_min = |c: &[f64], near: &BigRational| -> (BigRational, BigRational) {
            let cq: Vec<BigRational> = c.iter().map(|&x| q(x)).collect();
            let dq: Vec<BigRational> = cq.windows(2).map(|w| &w[1] - &w[0]).collect();
            if c.len() == 3 {
                let den = &cq[0] - &cq[1] * int(2) + &cq[2];
                let m = (&cq[0] * &cq[2] - &cq[1] * &cq[1]) / den;
                return (m.clone(), m);
            }
            // x' < 0 left of t*, > 0 right of it: bisection on its sign
            let w = BigRational::new(BigInt::from(1), BigInt::from(1u64 << 30));
            let (mut lo, mut hi) = (near - &w, near + &w);
            assert!(bern(&dq, &lo).is_negative() && bern(&dq, &hi).is_positive(), "{c:?}");
            let lip: BigRational = dq.iter().map(|x| x.abs()).sum::<BigRational>() * int(3);
            // (to 2^-80 of |M| at least, for minima as small as subnormals)
            for i in 0.. {
                let mid = (&lo + &hi) / int(2);
                if bern(&dq, &mid).is_negative() {
                    lo = mid;
                } else {
                    hi = mid;
                }
                if i >= 220 && i % 20 == 0 {
                    let v = std::cmp::min(bern(&cq, &lo), bern(&cq, &hi));
                    let tol = v.abs() / BigRational::from_integer(BigInt::from(1) << 80u32);
                    if &lip * (&hi - &lo) <= tol || i > 1400 {
                        break;
                    }
                }
            }
            let v = std::cmp::min(bern(&cq, &lo), bern(&cq, &hi));
            (&v - lip * (&hi - &lo), v)
        };
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(36);
        let (mut cases, mut zeros) = (0, 0);
        for it in 0..600 {
            let k = 2f64.powi(r.random_range(-40..=40));
            let mut near = int(0);
            let mut c: Vec<f64> = match it % 3 {
                0 => {
                    let (m, n) = (r.random_range(1..=2000) as f64, r.random_range(1..=2000) as f64);
                    vec![k * m * m, -k * m * n, k * n * n]
                }
                1 => {
                    // K (alpha t - beta)^2 (gamma t + delta), power coefficients times 3
                    // (Bernstein coefficients b_i = sum_j C(i, j) / C(3, j) a_j are then
                    // integers), t* = beta / alpha in (0, 1), gamma t + delta > 0 there
                    let alpha = r.random_range(2..=60i64);
                    let beta = r.random_range(1..alpha);
                    let delta = r.random_range(1..=50i64);
                    let gamma = r.random_range(-delta + 1..=50);
                    near = BigRational::new(BigInt::from(beta), BigInt::from(alpha));
                    let (s2, s1, s0) = (alpha * alpha, -2 * alpha * beta, beta * beta);
                    let a = [3 * s0 * delta, 3 * (s1 * delta + s0 * gamma), 3 * (s2 * delta + s1 * gamma), 3 * s2 * gamma];
                    let b = [a[0], a[0] + a[1] / 3, a[0] + 2 * a[1] / 3 + a[2] / 3, a[0] + a[1] + a[2] + a[3]];
                    b.iter().map(|&x| k * x as f64).collect()
                }
                _ => {
                    let (a, cc) = (r.random_range(0.01..1.0) * k, r.random_range(0.01..1.0) * k);
                    vec![a, -(a * cc).sqrt(), cc]
                }
            };
            // every other exact tangency moved by an ulp at one coefficient: M tiny, either sign
            if it % 3 != 2 && it % 2 == 1 {
                let i = r.random_range(0..c.len());
                c[i] = if r.random_bool(0.5) { c[i].next_up() } else { c[i].next_down() };
            }
            let p = c.len() - 1;
            // (an exact tangency's M is 0: the bisection's interval would only contain it)
            let tangent = it % 3 == 1 && it % 2 == 0;
            let (mlo, mhi) = if tangent { (int(0), int(0)) } else { exact_min(&c, &near) };
            // only interior minima far below the ends (as built)
            let end_min = q(c[0].min(c[p]));
            if mhi >= end_min {
                continue;
            }
            let mut fv = [0.0; 4];
            fv[..=p].copy_from_slice(&c);
            let pr = f64_sides(&fv, p, true, [false, true]).unwrap_or_else(|| panic!("{c:?}"));
            // the min side is the max side of -x: its exact maximum is -M
            let sd = pr.sides[1];
            let (bound, attained, witness) = (-sd.upper, -sd.attained, -sd.witness);
            assert!(q(bound) <= mlo, "{c:?}: lower bound {bound:e} above the minimum");
            assert!(q(attained) >= mhi && q(witness) > mhi, "{c:?}: {attained:e} {witness:e}");
            // the first rule: attained, or a strict witness at the next double up
            assert!(
                sd.attained == sd.upper || sd.witness >= sd.upper.next_down(),
                "{c:?}: bound {bound:e} attained {attained:e} witness {witness:e} (M in [{:e}, {:e}])",
                num_traits::ToPrimitive::to_f64(&mlo).unwrap(),
                num_traits::ToPrimitive::to_f64(&mhi).unwrap()
            );
            if mlo.is_zero() && mhi.is_zero() {
                assert_eq!((bound.to_bits(), attained.to_bits()), (0, 0), "{c:?}");
                zeros += 1;
            }
            cases += 1;
        }
        assert!(cases > 500 && zeros > 100, "{cases} {zeros}");
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
