//! Span-by-span enclosure of curves whose knots cannot be rescaled exactly (see the module docs
//! of `rescale`): a knot vector with knots near ±f64::MAX, whose differences overflow, and a
//! knot with a 2^-1074 bit, which no power-of-two scaling maps exactly.
//!
//! The image of the curve is the union of the images of its spans, and on span [u_k, u_{k+1}] the
//! curve is a rational Bézier piece in the local parameter t in [0, 1] (NURBS Book A5.6
//! DecomposeCurve; thesis sec. 4.2, "Zerlegen einer B-Spline-Kurve in Bézier-Segmente"). Its
//! Bernstein coefficients are extracted once in interval arithmetic ([`HSpline::bezier_segment`],
//! whose alphas are overflow-safe: [`crate::spline::bspline::knot_ratio`]), so every quantity is an
//! enclosure: Cartesian points P_i in boxes [P_i^lo, P_i^hi], weights w_i in intervals.
//!
//! # Why the pieces' boxes bound the curve
//!
//! Let ŵ_i be an f64 inside the enclosure of w_i (its midpoint) and C^hi, C^lo the rational
//! Bézier curves with weights ŵ and the points P^hi, P^lo (ordinary f64 curves on the knots
//! [0, ..., 0, 1, ..., 1]). With λ_i = w_i B_i / sum_l w_l B_l the true curve is
//! C(t) = sum λ_i P_i, and λ̂_i for ŵ likewise. With ρ_i = w_i / ŵ_i in [ρmin, ρmax]:
//! λ_i / λ̂_i = ρ_i / sum_l ρ_l λ̂_l lies in [ρmin/ρmax, ρmax/ρmin], so
//! |λ_i - λ̂_i| <= κ λ̂_i with κ = ρmax/ρmin - 1, and since both λ sum to 1, for any c
//! |sum (λ_i - λ̂_i) P_i| = |sum (λ_i - λ̂_i)(P_i - c)| <= κ max_i |P_i - c| = κ R,
//! R = (max_i P_i - min_i P_i) / 2 with c the midrange. Hence, per coordinate,
//!
//!   C(t) <= sum λ_i P_i^hi <= C^hi(t) + κ R^hi,    C(t) >= C^lo(t) - κ R^lo.
//!
//! So hi(C^hi) + κ R^hi bounds C from above and lo(C^lo) - κ R^lo from below; where C^lo
//! reaches >= v, C reaches >= v - κ R^lo (an attained value), and where C^hi reaches <= v,
//! C reaches <= v + κ R^hi. For a polynomial curve κ = 0. Each piece is enclosed by the
//! same strategy (so every strategy keeps its own character and convergence), rounding up or
//! down every correction. The pieces are not certified (`drive_with(s, piece, false)`): their
//! flags would not carry over to the curve, and the driver certifies (and where it can,
//! lowers) the curve's own bounds once; certifying every piece cost several times the
//! pieces' enclosure and left the same bounds.
//!
//! The piece at t = 1 is the left limit at u_{k+1}: at a knot of multiplicity >= p + 1 inside
//! the domain (a possible jump) it is not attained, so such a span contributes only its start
//! value C(u_k) = P_0 of the piece to the inner bounds.
//!
//! Argmin / argmax are reported per span (the whole span [u_k, u_{k+1}]), since the map
//! t -> u is what overflows here.

use super::{drive_with, BoxEncloser, CoordBox, Enclosure, Extremum, Termination};
use crate::num::{iv, Ddi, Scalar};
use crate::spline::bspline::{BezierSeg, HSpline};
use crate::spline::curve::NurbsCurve;
use crate::spline::knots::multiplicity;
use inari::Interval;

/// Outer and attained values of one coordinate over one span.
struct SpanBox {
    lo: f64,
    hi: f64,
    inner_lo: f64,
    inner_hi: f64,
    argmin_kind: Option<super::CandidateKind>,
    argmax_kind: Option<super::CandidateKind>,
}

/// Enclose `c` span by span (see the module docs) with strategy `s`.
pub fn enclose_by_segments<S: BoxEncloser + ?Sized>(s: &S, c: &NurbsCurve) -> Enclosure {
    let (p, n, d) = (c.degree(), c.num_points() - 1, c.dim());
    let kn = c.knots();
    let (_, b) = c.domain();
    let hs = HSpline::<Interval>::from_curve(c);
    let hd = HSpline::<Ddi>::from_curve(c);
    let mut coords: super::Coords = (0..d)
        .map(|_| CoordBox {
            lo: f64::INFINITY,
            hi: f64::NEG_INFINITY,
            inner_lo: f64::INFINITY,
            inner_hi: f64::NEG_INFINITY,
            argmin: Default::default(),
            argmax: Default::default(),
            stats: Default::default(),
            termination: Termination::Direct,
            optimal_lo: false,
            optimal_hi: false,
            witness_lo: f64::INFINITY,
            witness_hi: f64::NEG_INFINITY,
        })
        .collect();
    let mut spans: Vec<(usize, Vec<SpanBox>)> = Vec::new();
    for k in p..=n {
        if kn[k] >= kn[k + 1] {
            continue;
        }
        // left limit at u_{k+1} attained unless a possible jump inside the domain
        let right_attained = kn[k + 1] == b || multiplicity(kn, kn[k + 1]) <= p;
        let boxes = span_boxes(s, c, (&hs, &hd), k, right_attained, &mut coords);
        spans.push((k, boxes));
    }
    // merge: outer and attained values over the spans
    for (_, bx) in &spans {
        for (j, sb) in bx.iter().enumerate() {
            let cb = &mut coords[j];
            cb.lo = cb.lo.min(sb.lo);
            cb.hi = cb.hi.max(sb.hi);
            cb.inner_lo = cb.inner_lo.min(sb.inner_lo);
            cb.inner_hi = cb.inner_hi.max(sb.inner_hi);
        }
    }
    // argmin / argmax: the spans whose outer bound reaches past the attained value
    for (k, bx) in &spans {
        for (j, sb) in bx.iter().enumerate() {
            let cb = &mut coords[j];
            let span = |kind| Extremum {
                u_lo: kn[*k],
                u_hi: kn[*k + 1],
                unique: false,
                kind,
            };
            if sb.lo <= cb.inner_lo {
                cb.argmin.push(span(
                    sb.argmin_kind.unwrap_or(super::CandidateKind::Unresolved),
                ));
            }
            if sb.hi >= cb.inner_hi {
                cb.argmax.push(span(
                    sb.argmax_kind.unwrap_or(super::CandidateKind::Unresolved),
                ));
            }
        }
    }
    Enclosure {
        strategy: s.name(),
        verified: s.guarantee() == super::Guarantee::Verified,
        coords,
    }
}

/// The Bézier segment of span k with every homogeneous coefficient enclosed twice, by the
/// extraction in f64 intervals and in double-double ([`Ddi`], ~2^-100 relative, rounded
/// outward to f64 by `to_interval`), and the two enclosures intersected: both contain the
/// exact coefficient (the same Boehm insertions, each arithmetic inclusion isotone), so their
/// intersection does. The double-double one keeps the pieces' control points within an ulp
/// (the f64 one loses a few ulps per insertion, which the pieces' bounds inherit); the f64 one
/// stays finite where double-double error terms overflow (magnitudes near f64::MAX).
fn extract(hs: &HSpline<Interval>, hd: &HSpline<Ddi>, k: usize) -> BezierSeg<Interval> {
    let mut seg = hs.bezier_segment(k);
    let fine = hd.bezier_segment(k);
    for (x, y) in seg.pts.iter_mut().zip(&fine.pts) {
        let both = x.intersection(y.to_interval());
        // (never empty for enclosures of the same number; kept as is if it were)
        if !both.is_empty() {
            *x = both;
        }
    }
    seg
}

/// x + y rounded up (y an interval bound of a correction term).
fn add_up(x: f64, y: Interval) -> f64 {
    (iv::point(x) + y).sup()
}
/// x - y rounded down.
fn sub_down(x: f64, y: Interval) -> f64 {
    (iv::point(x) - y).inf()
}

/// The boxes of every coordinate over span k (module docs), with the pieces' work added to
/// `coords`.
fn span_boxes<S: BoxEncloser + ?Sized>(
    s: &S,
    c: &NurbsCurve,
    (hs, hd): (&HSpline<Interval>, &HSpline<Ddi>),
    k: usize,
    right_attained: bool,
    coords: &mut [CoordBox],
) -> Vec<SpanBox> {
    let (p, d, rational) = (c.degree(), c.dim(), c.is_rational());
    let seg = extract(hs, hd, k);
    let h = seg.hdim();
    // Cartesian point enclosures and weights
    let w: Vec<Interval> = (0..=p)
        .map(|i| {
            if rational {
                seg.pts[i * h + d]
            } else {
                iv::point(1.0)
            }
        })
        .collect();
    let pt = |i: usize, j: usize| -> Interval {
        if rational {
            seg.pts[i * h + j] / w[i]
        } else {
            seg.pts[i * h + j]
        }
    };
    let pts: Vec<Interval> = (0..=p)
        .flat_map(|i| (0..d).map(move |j| (i, j)))
        .map(|(i, j)| pt(i, j))
        .collect();
    let usable = w.iter().all(|x| x.inf() > 0.0 && x.sup().is_finite())
        && pts
            .iter()
            .all(|x| x.inf().is_finite() && x.sup().is_finite());
    if !usable {
        // An enclosure overflowed: the span's control points bound its piece (convex hull
        // property, exact); attained: its start value only if that is a clamped-exact point.
        return local_hull_boxes(c, k, coords);
    }
    // weights ŵ_i = midpoints, κ = ρmax / ρmin - 1 (rounded up; 0 for polynomial pieces)
    let what: Vec<f64> = w.iter().map(|x| x.mid()).collect();
    let kappa = if rational {
        let rho: Vec<Interval> = w
            .iter()
            .zip(&what)
            .map(|(x, &m)| *x / iv::point(m))
            .collect();
        let rmax = rho
            .iter()
            .map(|r| r.sup())
            .fold(f64::NEG_INFINITY, f64::max);
        let rmin = rho.iter().map(|r| r.inf()).fold(f64::INFINITY, f64::min);
        (iv::point(rmax) / iv::point(rmin) - iv::point(1.0))
            .sup()
            .max(0.0)
    } else {
        0.0
    };
    let side = |up: bool| -> Vec<f64> {
        pts.iter()
            .map(|x| if up { x.sup() } else { x.inf() })
            .collect()
    };
    let (phi, plo) = (side(true), side(false));
    let exact = phi == plo && kappa == 0.0;
    let piece = |q: &[f64]| {
        let knots: Vec<f64> = std::iter::repeat_n(0.0, p + 1)
            .chain(std::iter::repeat_n(1.0, p + 1))
            .collect();
        let weights = rational.then(|| what.clone());
        NurbsCurve::from_flat(p, d, knots, q.to_vec(), weights).ok()
    };
    let (Some(chi), Some(clo)) = (piece(&phi), piece(&plo)) else {
        return local_hull_boxes(c, k, coords);
    };
    let ehi = drive_with(s, &chi, false);
    let elo = if exact {
        ehi.clone()
    } else {
        drive_with(s, &clo, false)
    };
    let radius = |q: &[f64], j: usize| -> Interval {
        let (mn, mx) = crate::num::min_max((0..=p).map(|i| q[i * d + j]));
        let r = ((iv::point(mx) - iv::point(mn)) * iv::point(0.5)).sup();
        iv::point(kappa) * iv::point(r)
    };
    (0..d)
        .map(|j| {
            let (bh, bl) = (&ehi.coords[j], &elo.coords[j]);
            coords[j].stats.add(&bh.stats);
            if !exact {
                coords[j].stats.add(&bl.stats);
            }
            for t in [bh.termination, bl.termination] {
                // the worst over the pieces: a limit, else Converged, else Direct (hull)
                let cur = coords[j].termination;
                if cur == Termination::Direct
                    || (cur == Termination::Converged && t != Termination::Direct)
                {
                    coords[j].termination = t;
                }
            }
            let (rh, rl) = (radius(&phi, j), radius(&plo, j));
            let (mut inner_lo, mut inner_hi) = (add_up(bh.inner_lo, rh), sub_down(bl.inner_hi, rl));
            if !right_attained {
                // only the start value C(u_k), enclosed by [P_0^lo, P_0^hi] (exact when the
                // extraction was), corrected like the rest for the weights
                inner_lo = add_up(phi[j], rh);
                inner_hi = sub_down(plo[j], rl);
            }
            SpanBox {
                lo: sub_down(bl.lo, rl),
                hi: add_up(bh.hi, rh),
                inner_lo,
                inner_hi,
                argmin_kind: bl.argmin.first().map(|e| e.kind),
                argmax_kind: bh.argmax.first().map(|e| e.kind),
            }
        })
        .collect()
}

/// Fallback for a span whose Bézier extraction overflowed: the box of its p + 1 control
/// points P_{k-p} ..= P_k (exact); no attained values (the curve's inner bounds come from
/// the other spans and from the driver's clamped end values).
fn local_hull_boxes(c: &NurbsCurve, k: usize, coords: &mut [CoordBox]) -> Vec<SpanBox> {
    let p = c.degree();
    (0..c.dim())
        .map(|j| {
            coords[j].termination = Termination::WorkLimit;
            let (lo, hi) = c.coord_range(j, k - p..=k);
            SpanBox {
                lo,
                hi,
                inner_lo: f64::INFINITY,
                inner_hi: f64::NEG_INFINITY,
                argmin_kind: None,
                argmax_kind: None,
            }
        })
        .collect()
}
