//! The control-hull box: the box of the control points (convex hull property, thesis
//! prop. 2.1; valid for NURBS because the weights are positive, so C(u) is a convex
//! combination of the P_i). Computed exactly: min/max of f64 values involve no rounding.

use super::{
    BoxEncloser, CandidateKind, Clock, CoordBox, Coords, Enclosure, Extremum, Guarantee, Stats,
    Termination,
};
use crate::spline::curve::NurbsCurve;
use smallvec::smallvec;

/// Box of the control points; inner bound: the curve's end points (enclosed with intervals).
#[derive(Debug, Clone, Copy, Default)]
pub struct ControlHull;

impl BoxEncloser for ControlHull {
    fn name(&self) -> &'static str {
        "hull"
    }
    fn guarantee(&self) -> Guarantee {
        Guarantee::Verified
    }
    fn lane(&self) -> Option<super::lane::Lane> {
        Some(super::lane::Lane::Hull)
    }
    fn enclose_prepared(&self, c: &NurbsCurve) -> Enclosure {
        let t0 = Clock::start();
        // The end points are reached by the curve: their enclosures' upper (lower) ends bound
        // a value the curve attains from above (below). At a clamped end the end value is the
        // end control point exactly (`NurbsCurve::clamped_ends`): no evaluation, no allocation.
        let cl = c.clamped_ends();
        let n = c.num_points() - 1;
        let ends = (!(cl[0] && cl[1])).then(|| c.end_values());
        let end = |k: usize, j: usize| -> (f64, f64) {
            match &ends {
                Some(e) => (e[k][j].inf(), e[k][j].sup()),
                None => {
                    let x = c.control_point(if k == 0 { 0 } else { n })[j];
                    (x, x)
                }
            }
        };
        let mut coords = control_point_box(
            c,
            |j, lo, hi| {
                let ((a_lo, a_hi), (b_lo, b_hi)) = (end(0, j), end(1, j));
                (a_hi.min(b_hi).max(lo), a_lo.max(b_lo).min(hi))
            },
            Termination::Direct,
            2,
        );
        let el = t0.elapsed();
        if let Some(c0) = coords.first_mut() {
            c0.stats.time_total = el;
        }
        Enclosure {
            strategy: self.name(),
            verified: true,
            coords,
        }
    }
}

/// Per coordinate j the box [lo, hi] of the control points (exact: min / max of f64 data), with
/// the inner bounds `inner(j, lo, hi)` (the caller's reason why the curve reaches them),
/// argmin / argmax at the supports of the extreme control points, and `termination`. O(n d):
/// shared by [`ControlHull`] and the high-degree fallback (`driver::degree_fallback`).
#[inline]
pub(crate) fn control_point_box(
    c: &NurbsCurve,
    inner: impl Fn(usize, f64, f64) -> (f64, f64),
    termination: Termination,
    point_evaluations: u64,
) -> Coords {
    let (a, b) = c.domain();
    // Only the control points whose basis functions are non-zero somewhere on the domain
    // matter: all of them for a valid curve (each N_{i,p} has support meeting [u_p, u_{n+1}]).
    let at = |i: usize| {
        let k = &c.knots()[i..=i + c.degree() + 1];
        Extremum {
            u_lo: k[0].max(a),
            u_hi: k[k.len() - 1].min(b),
            unique: false,
            kind: CandidateKind::ControlPoint,
        }
    };
    let d = c.dim();
    let pts = c.points_flat();
    let mut out = Coords::new();
    for j in 0..d {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        let (mut ilo, mut ihi) = (0, 0);
        for i in 0..pts.len() / d {
            let x = pts[i * d + j];
            if x < lo {
                lo = x;
                ilo = i;
            }
            if x > hi {
                hi = x;
                ihi = i;
            }
        }
        let (inner_lo, inner_hi) = inner(j, lo, hi);
        out.push(CoordBox {
            lo,
            hi,
            inner_lo,
            inner_hi,
            argmin: smallvec![at(ilo)],
            argmax: smallvec![at(ihi)],
            stats: Stats {
                point_evaluations,
                ..Default::default()
            },
            termination,
            optimal_lo: false,
            optimal_hi: false,
            witness_lo: f64::INFINITY,
            witness_hi: f64::NEG_INFINITY,
        });
    }
    out
}
