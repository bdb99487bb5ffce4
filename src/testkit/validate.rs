//! Validation of enclosures: containment checks against verified point enclosures, and
//! tightness measures. Used by the tests and by the reproduction harness.

use crate::enclose::Enclosure;
use crate::num::iv;
use crate::spline::curve::NurbsCurve;
use crate::spline::eval::CurveEval;
use inari::Interval;

/// A proven containment miss: at `param`, coordinate `coord` of the curve lies in
/// `[value_lo, value_hi]` (verified), which is entirely outside `[bound_lo, bound_hi]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Miss {
    /// parameter
    pub param: f64,
    /// coordinate index
    pub coord: usize,
    /// verified enclosure of C_coord(param)
    pub value_lo: f64,
    /// verified enclosure of C_coord(param)
    pub value_hi: f64,
    /// the box's lower bound
    pub bound_lo: f64,
    /// the box's upper bound
    pub bound_hi: f64,
}

/// Result of [`check_containment`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Containment {
    /// parameters checked
    pub checked: usize,
    /// proven misses (empty for a sound box)
    pub misses: Vec<Miss>,
}

/// Parameters for a dense check: the domain ends, every distinct knot, and `per_span` equally
/// spaced interior points of every non-empty span.
pub fn dense_params(c: &NurbsCurve, per_span: usize) -> Vec<f64> {
    let bp = c.breakpoints();
    let mut out = Vec::with_capacity(bp.len() * (per_span + 1));
    for w in bp.windows(2) {
        out.push(w[0]);
        for i in 1..=per_span {
            let t = i as f64 / (per_span + 1) as f64;
            out.push(w[0] + t * (w[1] - w[0]));
        }
    }
    out.extend(bp.last());
    out
}

/// Check that the box of `enc` is not proven to miss the curve at any of `params` (in the
/// domain; others are skipped). A miss is *proven* when the verified interval enclosure of
/// C_j(u) lies entirely above `hi` or below `lo`; this is the only kind of miss that can be
/// established with f64 evaluation (a tight box may be narrower than a point enclosure).
pub fn check_containment(c: &NurbsCurve, enc: &Enclosure, params: &[f64]) -> Containment {
    let ev = CurveEval::<Interval>::new(c, 0);
    let (a, b) = c.domain();
    let mut out = Containment::default();
    for &u in params {
        if !(u >= a && u <= b) {
            continue;
        }
        out.checked += 1;
        let v = &ev.derivs_in_span(ev.span(u), &iv::point(u), 0)[0];
        for (j, cb) in enc.coords.iter().enumerate() {
            if v[j].inf() > cb.hi || v[j].sup() < cb.lo {
                out.misses.push(Miss {
                    param: u,
                    coord: j,
                    value_lo: v[j].inf(),
                    value_hi: v[j].sup(),
                    bound_lo: cb.lo,
                    bound_hi: cb.hi,
                });
            }
        }
    }
    out
}

pub use crate::num::ulp;

/// Certified gap of each coordinate (outer minus inner, the larger side) in ulps of the
/// coordinate scale (largest |control point coordinate|).
pub fn gap_ulps(c: &NurbsCurve, enc: &Enclosure) -> Vec<f64> {
    enc.coords
        .iter()
        .enumerate()
        .map(|(j, cb)| cb.gap() / ulp(c.coord_scale(j)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::enclose::{BoxEncloser, ControlHull, CoordBox, Termination};

    #[test]
    fn detects_a_wrong_box() {
        let c = NurbsCurve::new(
            2,
            vec![0., 0., 0., 1., 1., 1.],
            vec![vec![0.], vec![2.], vec![0.]],
            None,
        )
        .unwrap();
        let good = ControlHull.enclose(&c);
        assert!(check_containment(&c, &good, &dense_params(&c, 50))
            .misses
            .is_empty());
        let mut bad = good.clone();
        bad.coords[0] = CoordBox {
            hi: 0.9,
            ..bad.coords[0].clone()
        };
        let r = check_containment(&c, &bad, &dense_params(&c, 50));
        assert!(!r.misses.is_empty());
        assert_eq!(bad.coords[0].termination, Termination::Direct);
        assert_eq!(ulp(1.0), f64::EPSILON);
    }
}
