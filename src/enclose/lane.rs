//! The driver's lane for the commonest input: one clamped polynomial Bézier segment of degree
//! 1, 2 or 3 (a line, a font's quadratic, a cubic Bézier) with moderate magnitudes
//! ([`Simple::of`]). Such a curve needs none of the general machinery (rescaling, knot
//! insertion, branch and bound), so the driver answers it here directly, with the same
//! guarantees and the same reasoning as the general path, and without any heap allocation:
//!
//! * **`hull`** ([`Lane::Hull`]): the box of the control points (convex hull property, thesis
//!   prop. 2.1; exact), the end control points as attained values (a clamped end is a control
//!   point: `NurbsCurve::clamped_ends`).
//! * **`bezier` and `newton`** ([`Lane::Tight`]): per coordinate side first the cheap exit (the
//!   extreme control value is an end value: exact and attained), else the root-isolating proof
//!   of the `bezier` strategy's fast path (`bezier::single`: f64 root estimates of C_j', proven
//!   derivative signs at test points by an f64 filter with an a-priori error bound, root
//!   counting, a double-double Taylor enclosure over each tiny bracket). Where that proof does
//!   not give a bound within two ulps of the coordinate scale, the lane returns `None` and the
//!   general path runs (`Stats::fast_fallbacks` counts it there).
//!
//! The driver's facts are applied as in [`super::drive_with`]: outer bounds clamped to the
//! control-point box, the end values attained, inner bounds consistent with outer ones. The
//! optimality certificate's first rule (an attained value equal to the bound, or a strict
//! witness above the next double down) and its cheap refusal (the strategy's own attained
//! value more than a few ulps of the scale below its bound: `certify::quick`) are decided
//! here; any side they leave open goes to the full certification (`certify::certify`), so the
//! flags are those of the general path.

use super::bezier::single::{raw_sides, RawSide, Segment};
use super::driver::{exponent, COORD_WINDOW};
use super::{certify, CandidateKind, Clock, CoordBox, Coords, Enclosure, Extrema, Extremum};
use super::{SideData, Stats, Termination};
use crate::num::ddi::Ddi;
use crate::spline::curve::NurbsCurve;

/// Which answer a strategy gives on a [`Simple`] curve.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Lane {
    /// the control-point box (`hull`)
    Hull,
    /// the tight verified box (`bezier`, `newton`)
    Tight,
}

/// The domain ends must lie below 2^KNOT_EXP in magnitude (their difference stays finite).
const KNOT_EXP: i32 = 1000;

/// A curve the lane takes: one clamped polynomial Bézier segment of degree 1..=3 over [a, b],
/// every coordinate moderate.
#[derive(Debug, Clone, Copy)]
pub struct Simple<'a> {
    p: usize,
    d: usize,
    a: f64,
    b: f64,
    pts: &'a [f64],
}

impl<'a> Simple<'a> {
    /// The curve as a [`Simple`] one, or `None` (rational, several spans, unclamped, degree
    /// above 3, extreme magnitudes).
    #[inline]
    pub fn of(c: &'a NurbsCurve) -> Option<Simple<'a>> {
        let p = c.degree();
        let k = c.knots();
        if c.is_rational() || !(1..=3).contains(&p) || c.num_points() != p + 1 {
            return None;
        }
        // knots {a^(p+1), b^(p+1)}, a < b (validation guarantees a non-empty domain; checked
        // again, as every other assumption here)
        let (a, b) = (k[0], k[k.len() - 1]);
        if k.len() != 2 * p + 2 || k[p] != a || k[p + 1] != b || a >= b || a.is_nan() {
            return None;
        }
        if exponent(a) > KNOT_EXP || exponent(b) > KNOT_EXP {
            return None;
        }
        let d = c.dim();
        let pts = c.points_flat();
        for j in 0..d {
            let m = pts
                .iter()
                .skip(j)
                .step_by(d)
                .fold(0.0f64, |m, x| m.max(x.abs()));
            // (a NaN or infinite coordinate is rejected by validation; m > MAX fails here too)
            if !m.is_finite() || (m != 0.0 && exponent(m).abs() > COORD_WINDOW) {
                return None;
            }
        }
        Some(Simple { p, d, a, b, pts })
    }

    /// The control values of coordinate j.
    #[inline]
    fn values(&self, j: usize) -> [f64; 4] {
        let mut v = [0.0; 4];
        for (i, x) in v.iter_mut().enumerate().take(self.p + 1) {
            *x = self.pts[i * self.d + j];
        }
        v
    }
}

/// One side of a coordinate, sign-adjusted (the min side is the max side of -C_j), and its
/// counters.
struct SideOut {
    data: SideData,
    stats: Stats,
}

/// The end-point extremum at parameter u.
fn end(u: f64) -> Extremum {
    Extremum {
        u_lo: u,
        u_hi: u,
        unique: false,
        kind: CandidateKind::EndPoint,
    }
}

/// The cheap exit for the max side of values v[..=p]: the largest value is an end value (exact,
/// attained: `fast_exits`).
fn cheap_exit(s: &Simple, v: &[f64]) -> Option<SideOut> {
    let p = s.p;
    let m = v[1..p].iter().fold(v[0].max(v[p]), |m, &x| m.max(x));
    let u = if v[0] == m {
        s.a
    } else if v[p] == m {
        s.b
    } else {
        return None;
    };
    let mut args = Extrema::new();
    args.push(end(u));
    Some(SideOut {
        data: SideData {
            upper: m,
            attained: m,
            witness: f64::NEG_INFINITY,
            args,
        },
        stats: Stats {
            fast_exits: 1,
            ..Stats::default()
        },
    })
}

/// A proven side from the root isolation (`fast_proofs`).
fn proven(s: &Simple, r: &RawSide) -> SideOut {
    let mut args: Extrema = r.reaching().copied().collect();
    if args.is_empty() {
        args.push(Extremum {
            u_lo: s.a,
            u_hi: s.b,
            unique: false,
            kind: CandidateKind::Unresolved,
        });
    }
    SideOut {
        data: SideData {
            upper: r.upper,
            attained: r.attained,
            witness: r.witness,
            args,
        },
        stats: Stats {
            fast_proofs: 1,
            derivative_evaluations: r.derivative_evaluations,
            point_evaluations: r.point_evaluations,
            ..Stats::default()
        },
    }
}

/// The tight sides `[max, min]` of coordinate j, or `None` (fall back to the general path).
fn tight_sides(s: &Simple, j: usize) -> Option<[SideOut; 2]> {
    let v = s.values(j);
    let p = s.p;
    let neg = v.map(|x| -x);
    let (hi, lo) = (cheap_exit(s, &v[..=p]), cheap_exit(s, &neg[..=p]));
    if hi.is_some() && lo.is_some() {
        // (both exits: a monotone coordinate, or a line)
        return Some([hi?, lo?]);
    }
    let need = [hi.is_none(), lo.is_none()];
    let c = v.map(Ddi::exact);
    let seg = Segment {
        c: &c[..=p],
        a: s.a,
        b: s.b,
        end_kinds: [CandidateKind::EndPoint; 2],
        right_attained: true,
    };
    let raw = raw_sides(&seg, need)?;
    // the `newton` and `bezier` stopping rule: a gap of at most two ulps of the scale
    let scale = v[..=p]
        .iter()
        .fold(f64::MIN_POSITIVE, |m, x| m.max(x.abs()));
    let max_gap = 2.0 * crate::num::ulp(scale);
    let mut out = [hi, lo];
    for (o, r) in out.iter_mut().zip(&raw) {
        if o.is_none() {
            if !r.tight(max_gap) {
                return None;
            }
            *o = Some(proven(s, r));
        }
    }
    let [hi, lo] = out;
    Some([hi?, lo?])
}

/// The hull sides `[max, min]` of coordinate j: control-point box, attained end values.
fn hull_sides(s: &Simple, j: usize) -> [SideOut; 2] {
    let v = s.values(j);
    let p = s.p;
    let side = |sign: f64| {
        let m = v[..=p]
            .iter()
            .fold(f64::NEG_INFINITY, |m, &x| m.max(sign * x));
        let mut args = Extrema::new();
        // every control point of a single segment is supported on the whole domain
        args.push(Extremum {
            u_lo: s.a,
            u_hi: s.b,
            unique: false,
            kind: CandidateKind::ControlPoint,
        });
        SideOut {
            data: SideData {
                upper: m,
                attained: (sign * v[0]).max(sign * v[p]),
                witness: f64::NEG_INFINITY,
                args,
            },
            stats: Stats::default(),
        }
    };
    let mut out = [side(1.0), side(-1.0)];
    out[0].stats.point_evaluations = 2;
    out
}

/// The enclosure of a [`Simple`] curve by a strategy named `name` answering with `lane`, with
/// the certificates when `certify` (see the module docs); `None` sends the curve to the
/// general path.
pub fn enclose(
    lane: Lane,
    name: &'static str,
    c: &NurbsCurve,
    s: &Simple,
    certify: bool,
) -> Option<Enclosure> {
    let mut coords = Coords::new();
    let mut open = false;
    for j in 0..s.d {
        let clock = Clock::start();
        let ([hi, lo], term) = match lane {
            Lane::Hull => (hull_sides(s, j), Termination::Direct),
            Lane::Tight => (tight_sides(s, j)?, Termination::Converged),
        };
        let v = s.values(j);
        let (plo, phi) = v[..=s.p]
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &x| {
                (l.min(x), h.max(x))
            });
        let mut stats = hi.stats;
        stats.add(&lo.stats);
        stats.time_total = clock.elapsed();
        let mut cb = CoordBox::from_sides(hi.data, lo.data, stats, term);
        // the driver's facts: clamp to the control-point box, the clamped end values are
        // attained, inner bounds consistent with the outer ones
        cb.lo = cb.lo.max(plo);
        cb.hi = cb.hi.min(phi);
        let (e0, e1) = (v[0], v[s.p]);
        cb.inner_lo = cb.inner_lo.min(e0).min(e1).min(cb.hi).max(cb.lo);
        cb.inner_hi = cb.inner_hi.max(e0).max(e1).max(cb.lo).min(cb.hi);
        if certify {
            let scale = plo.abs().max(phi.abs()).max(f64::MIN_POSITIVE);
            let q_hi = certify::quick(cb.hi, cb.inner_hi, cb.witness_hi, scale);
            let q_lo = certify::quick(-cb.lo, -cb.inner_lo, -cb.witness_lo, scale);
            cb.optimal_hi = q_hi == Some(true);
            cb.optimal_lo = q_lo == Some(true);
            open |= q_hi.is_none() || q_lo.is_none();
        }
        coords.push(cb);
    }
    let mut e = Enclosure {
        strategy: name,
        verified: true,
        coords,
    };
    if open {
        certify::certify(c, &mut e);
    }
    Some(e)
}
