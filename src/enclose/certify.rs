//! Certificates of optimal bounds: `optimal_hi` proves hi = RU(max_u C_j(u)), `optimal_lo`
//! proves lo = RD(min_u C_j(u)) ([`certify`], applied by the driver to the result of every
//! verified strategy).
//!
//! # Why a certificate is a proof
//!
//! A verified strategy has proved C_j(u) <= hi for every u in the domain, so the exact maximum
//! (the supremum, for a curve with a jump) M satisfies M <= hi. If moreover some parameter u has
//! C_j(u) > t := next_down(hi), then t < M <= hi: no f64 lies in [M, hi) and hi is the smallest
//! f64 >= M, i.e. hi = RU(M). `optimal_hi` is set `true` exactly when one of these was shown:
//!
//! 1. **An attained value equal to hi**: `inner_hi == hi` (the strategy, or the driver's facts
//!    such as a clamped end control point, proved that the curve reaches a value >= inner_hi);
//!    then M = hi.
//! 2. **A verified enclosure above t**: a double-double enclosure ([`Ddi`], rigorous, about
//!    2^-100 relative wide) of C_j(u) at an f64 parameter u whose lower end (compared exactly)
//!    is > t.
//! 3. **An exact value above t**: the exact rational C_j(u) ([`Exact`]: the generic de Boor and
//!    derivative kernels run on big rationals, no rounding) at an f64 or dyadic parameter u is
//!    > t (compared exactly).
//!
//! The lower bound is the same statement for -C_j. Nothing else sets a flag, so a wrong `true`
//! would need a wrong outer bound, a wrong inner bound or a wrong enclosure / exact value, all
//! of which are the crate's soundness guarantees already.
//!
//! # Choosing u (Ziv's strategy)
//!
//! The strategy's candidates (`argmax` / `argmin`: parameter intervals whose enclosures reach
//! the bound; at most [`MAX_CANDIDATES`]) say where to look. Per candidate:
//!
//! * the `Ddi` value at its midpoint (or its point, for a knot or an end);
//! * up to [`NEWTON_STEPS`] Newton steps u <- u - g'(u)/g''(u) on g = ±C_j with double-double
//!   derivatives (only to *choose* u, never part of the proof), then the `Ddi` value at u and
//!   its two f64 neighbours. At the f64 u nearest the extremum u*, g(u) = M - O(g'' ulp(u)^2),
//!   i.e. ~2^-106 relative below M: this decides every bound with M - t above ~2^-100 M;
//! * if that fails (a near-tie: M within ~2^-100 relative above t) and the degree is at most
//!   [`EXACT_MAX_DEGREE`]: the exact value at u, then Newton steps in exact arithmetic whose
//!   iterates are truncated to dyadic parameters of [`ZIV_BITS`] binary digits (each level
//!   doubles the precision, as Newton's quadratic convergence allows), the exact value at each.
//!   A near-tie M - t down to about 2^-(2 * 480) relative is decided this way.
//!
//! # Limits (bounded work)
//!
//! At most [`MAX_CANDIDATES`] candidates, [`NEWTON_STEPS`] double-double Newton steps, and the
//! exact stage only for the 2 best candidates, degree <= [`EXACT_MAX_DEGREE`], two exact Newton
//! steps per level of [`ZIV_BITS`]. When these are spent the answer is `false` ("not proved").
//! The other outcome of a Ziv loop, proving M <= t and lowering the bound, is not attempted: a
//! strategy's bound that is one ulp above RU(M) stays, with `optimal_hi = false` (it is not
//! optimal, and the flag says so honestly). A heuristic strategy always reports `false`.

use super::{CoordBox, Enclosure, Extremum};
use crate::num::{Ddi, Exact, Scalar};
use crate::spline::curve::NurbsCurve;
use crate::spline::eval::CurveEval;

/// Candidates per side that are examined (in the strategy's order).
pub const MAX_CANDIDATES: usize = 8;
/// Double-double Newton steps per candidate.
pub const NEWTON_STEPS: usize = 4;
/// Highest degree for which exact rational evaluation is attempted (the rationals of a de
/// Boor triangle grow with the degree).
pub const EXACT_MAX_DEGREE: usize = 24;
/// Binary digits (relative to the parameter magnitude) of the dyadic parameters of the exact
/// Ziv levels.
pub const ZIV_BITS: [u32; 3] = [120, 240, 480];
/// Candidates that go to the exact stage.
const EXACT_CANDIDATES: usize = 2;

/// Set `optimal_lo` / `optimal_hi` of every coordinate of a result of `c` (see the module
/// docs). A heuristic result (`verified == false`) gets `false` everywhere.
pub fn certify(c: &NurbsCurve, e: &mut Enclosure) {
    let verified = e.verified;
    let mut ev = Evals::new(c);
    for (j, cb) in e.coords.iter_mut().enumerate() {
        if !verified {
            cb.optimal_lo = false;
            cb.optimal_hi = false;
            continue;
        }
        cb.optimal_hi = certify_side(&mut ev, j, 1.0, cb, true);
        cb.optimal_lo = certify_side(&mut ev, j, -1.0, cb, false);
    }
}

/// Lazily built evaluators of the curve (double-double with two derivative levels, exact).
struct Evals<'a> {
    c: &'a NurbsCurve,
    ddi: Option<CurveEval<Ddi>>,
    exact: Option<CurveEval<Exact>>,
}

impl<'a> Evals<'a> {
    fn new(c: &'a NurbsCurve) -> Self {
        Evals {
            c,
            ddi: None,
            exact: None,
        }
    }

    /// g, g', g'' (k = 2) or g alone (k = 0) at the f64 parameter u, g = sign * C_j, in Ddi.
    fn ddi(&mut self, j: usize, sign: f64, u: f64, k: usize) -> Option<Vec<Ddi>> {
        let c = self.c;
        let e = self.ddi.get_or_insert_with(|| CurveEval::new(c, 2));
        let v = e.derivs(u, k).ok()?;
        Some(v.into_iter().map(|d| signed(d[j], sign)).collect())
    }

    /// g, g', g'' (k = 2) or g (k = 0) exactly at the rational parameter u of the domain, in
    /// the span the curve's own evaluation uses (`None` if u is outside or cannot be placed).
    fn exact(&mut self, j: usize, sign: f64, u: &Exact, k: usize) -> Option<Vec<Exact>> {
        let c = self.c;
        let (a, b) = c.domain();
        if u.cmp_f64(a)?.is_lt() || u.cmp_f64(b)?.is_gt() {
            return None;
        }
        let e = self.exact.get_or_insert_with(|| CurveEval::new(c, 2));
        let ua = u.to_f64().clamp(a, b);
        let kn = c.knots();
        // the span of u by the convention of `find_span` (u_k <= u < u_{k+1}, the last span
        // for u = b): find it from an f64 near u, then check it exactly
        let mut span = e.span(ua);
        for _ in 0..4 {
            if u.cmp_f64(kn[span])?.is_lt() {
                span -= 1;
            } else if u.cmp_f64(b)?.is_lt() && !u.cmp_f64(kn[span + 1])?.is_lt() {
                span += 1;
            } else {
                break;
            }
        }
        let fits = !u.cmp_f64(kn[span])?.is_lt()
            && (u.cmp_f64(kn[span + 1])?.is_lt() || (u.cmp_f64(b)?.is_eq() && span == e.span(b)));
        if !fits || span < c.degree() || kn[span] >= kn[span + 1] {
            return None;
        }
        let v = e.derivs_in_span(span, u, k);
        Some(
            v.into_iter()
                .map(|d| {
                    let x = d[j].clone();
                    if sign < 0.0 {
                        -x
                    } else {
                        x
                    }
                })
                .collect(),
        )
    }
}

fn signed(x: Ddi, sign: f64) -> Ddi {
    if sign < 0.0 {
        -x
    } else {
        x
    }
}

/// Whether the set `x` lies strictly above the f64 `t` (its lower end hi + lo - rad compared
/// exactly; ENTIRE never does).
fn ddi_above(x: &Ddi, t: f64) -> bool {
    if x.is_entire() {
        return false;
    }
    // cheap rejection: the centre is clearly not above t (false is always a safe answer)
    if x.hi() < t && t - x.hi() > 2.0 * (x.lo().abs() + x.rad()) {
        return false;
    }
    (Exact::of(x.hi()) + Exact::of(x.lo()) - Exact::of(x.rad())).gt_f64(t)
}

/// The certificate of one side: `sign` = 1 for the maximum (bound hi), -1 for the minimum
/// (bound lo, handled as the maximum of -C_j).
fn certify_side(ev: &mut Evals, j: usize, sign: f64, cb: &CoordBox, max_side: bool) -> bool {
    let (bound, inner, cands) = if max_side {
        (cb.hi, cb.inner_hi, &cb.argmax)
    } else {
        (-cb.lo, -cb.inner_lo, &cb.argmin)
    };
    if !bound.is_finite() {
        return false;
    }
    // 1. attained value equal to the bound
    if inner == bound {
        return true;
    }
    let t = bound.next_down();
    let (a, b) = ev.c.domain();
    let cands: Vec<Extremum> = cands.iter().take(MAX_CANDIDATES).copied().collect();
    // 2. double-double enclosures at chosen f64 parameters
    let mut best: Vec<(f64, f64)> = Vec::new(); // (centre of g, u)
    for x in &cands {
        let (lo, hi) = (x.u_lo.max(a), x.u_hi.min(b));
        if !(lo <= hi) {
            continue;
        }
        let mid = (lo + 0.5 * (hi - lo)).clamp(lo, hi);
        let Some(g) = ev.ddi(j, sign, mid, 0) else {
            continue;
        };
        if ddi_above(&g[0], t) {
            return true;
        }
        let mut u = mid;
        let mut top = (g[0].to_f64(), mid);
        if lo < hi {
            for _ in 0..NEWTON_STEPS {
                let Some(d) = ev.ddi(j, sign, u, 2) else {
                    break;
                };
                let (d1, d2) = (d[1].to_f64(), d[2].to_f64());
                if !(d2 < 0.0) || !d1.is_finite() {
                    break;
                }
                let next = (u - d1 / d2).clamp(lo, hi);
                if !next.is_finite() || next == u {
                    break;
                }
                u = next;
            }
            for v in [u, u.next_down(), u.next_up()] {
                if v < a || v > b {
                    continue;
                }
                let Some(g) = ev.ddi(j, sign, v, 0) else {
                    continue;
                };
                if ddi_above(&g[0], t) {
                    return true;
                }
                if g[0].to_f64() > top.0 {
                    top = (g[0].to_f64(), v);
                }
            }
        }
        best.push(top);
    }
    // 3. exact values (Ziv levels), for the best candidates
    if ev.c.degree() > EXACT_MAX_DEGREE {
        return false;
    }
    best.sort_by(|x, y| y.0.total_cmp(&x.0));
    let scale = exponent_of(a.abs().max(b.abs()).max(b - a));
    for &(_, u0) in best.iter().take(EXACT_CANDIDATES) {
        let mut u = Exact::of(u0);
        let Some(g) = ev.exact(j, sign, &u, 0) else {
            continue;
        };
        if g[0].gt_f64(t) {
            return true;
        }
        'levels: for bits in ZIV_BITS {
            for _ in 0..2 {
                let Some(d) = ev.exact(j, sign, &u, 2) else {
                    break 'levels;
                };
                if d[1].is_exact_zero() {
                    break 'levels; // at a critical point already: nothing more to gain here
                }
                if d[2].signum() != Some(std::cmp::Ordering::Less) {
                    break 'levels;
                }
                let next = (u.clone() - d[1].clone() / d[2].clone()).truncate_to(scale, bits);
                let Some(g) = ev.exact(j, sign, &next, 0) else {
                    break 'levels;
                };
                if g[0].gt_f64(t) {
                    return true;
                }
                u = next;
            }
        }
    }
    false
}

/// The exponent e with |x| < 2^e (x finite, > 0; 0 otherwise).
fn exponent_of(x: f64) -> i32 {
    if !(x > 0.0) || !x.is_finite() {
        return 0;
    }
    let mut e = x.log2().ceil() as i32;
    while 2f64.powi(e) <= x {
        e += 1;
    }
    e
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::enclose::{BoxEncloser, Newton};

    fn quad(p0: f64, p1: f64, p2: f64) -> NurbsCurve {
        NurbsCurve::new(
            2,
            vec![0., 0., 0., 1., 1., 1.],
            vec![vec![p0], vec![p1], vec![p2]],
            None,
        )
        .unwrap()
    }

    #[test]
    fn exponent_bounds() {
        assert_eq!(exponent_of(1.0), 1);
        assert_eq!(exponent_of(0.75), 0);
        assert_eq!(exponent_of(3.0), 2);
    }

    #[test]
    fn symmetric_quadratic_with_double_maximum_is_certified() {
        // C(u) = 2 * 2u(1-u) * P1: max at u = 1/2 equals P1 exactly (P0 = P2 = 0): a double
        let c = quad(0.0, 0.75, 0.0);
        let mut e = Newton::default().enclose(&c);
        assert!(e.coords[0].optimal_lo);
        assert_eq!(e.coords[0].optimal_hi, e.coords[0].hi == 0.375);
        // with the optimal bound (and no attained inner value) the certificate holds
        e.coords[0].hi = 0.375;
        e.coords[0].inner_hi = 0.25;
        certify(&c, &mut e);
        assert!(e.coords[0].optimal_hi);
    }

    #[test]
    fn ends_and_a_tiny_double_maximum() {
        // P0 = P2 = -1, P1 = 1 + eps: min -1 at both (clamped) ends, max C(1/2) = eps / 2
        let c = quad(-1.0, 1.0 + f64::EPSILON, -1.0);
        let e = Newton::default().enclose(&c);
        assert_eq!(e.coords[0].lo, -1.0);
        assert!(e.coords[0].optimal_lo);
        assert_eq!(e.coords[0].optimal_hi, e.coords[0].hi == f64::EPSILON / 2.0);
    }

    #[test]
    fn near_tie_decided_by_the_exact_stage() {
        // P0 = 3 d, P1 = 1, P2 = d with d = 2^-110: the maximum is about 1/2 + 2^-111 at a
        // non-dyadic u* near 1/2, so RU(max) = next_up(1/2), and only a value within ~2^-111
        // of the maximum proves it (double-double enclosures are ~2^-100 wide).
        let d = 2f64.powi(-110);
        let c = quad(3.0 * d, 1.0, d);
        let e = Newton::default().enclose(&c);
        let cb = &e.coords[0];
        if cb.hi == 0.5f64.next_up() {
            assert!(cb.optimal_hi, "exact stage must decide the near-tie");
        } else {
            assert!(!cb.optimal_hi);
        }
        // the certificate by itself, on a box with the optimal bound
        let mut forced = e.clone();
        forced.coords[0].hi = 0.5f64.next_up();
        forced.coords[0].inner_hi = 0.5;
        certify(&c, &mut forced);
        assert!(forced.coords[0].optimal_hi);
        // and a bound one ulp too high is never certified
        forced.coords[0].hi = 0.5f64.next_up().next_up();
        certify(&c, &mut forced);
        assert!(!forced.coords[0].optimal_hi);
    }
}
