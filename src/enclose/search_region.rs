//! The thesis's search-region heuristic (listing `suchbereich`, thesis sec. 7.1.3, described in
//! ch. 6) and a verified variant.
//!
//! `suchbereich` takes, per coordinate, the control points with the two largest and the two
//! smallest coordinate values (all ties), collects the knots u_i .. u_{i+p+1} of their supports,
//! and `main` (thesis sec. 7.1.2) runs interval Newton on each interval between consecutive
//! collected knots, i.e. on all of [min, max] of them. Candidates are then the Newton zeros,
//! the domain end points and the non-differentiable knots. Outside the region nothing is looked
//! at, so an extremum there is missed: the heuristic is **not** verified.
//!
//! The verified variant searches the region first and then proves that the remaining spans
//! cannot leave the box found: a span whose local control points lie inside the box is done
//! (convex hull property, thesis prop. 2.1); any other span is treated exactly as by
//! [`Newton`] (monotonicity pre-test, then Newton), so the result carries the same guarantee.

use super::newton::{Engine, SpanMode};
use super::{BoxEncloser, Enclosure, Guarantee, Newton};
use crate::spline::curve::NurbsCurve;

/// Search-region strategy: the thesis heuristic (`verified == false`, name `search-region`) or
/// the verified variant (`search-region-verified`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SearchRegion {
    /// Newton settings used inside the region (and outside, for the verified variant).
    pub newton: Newton,
    /// Whether to prove the rest of the domain (verified variant).
    pub verified: bool,
}

impl SearchRegion {
    /// The thesis heuristic with the given Newton settings (not verified).
    pub fn thesis(newton: Newton) -> Self {
        SearchRegion {
            newton,
            verified: false,
        }
    }

    /// The verified variant with the given Newton settings.
    pub fn verified(newton: Newton) -> Self {
        SearchRegion {
            newton,
            verified: true,
        }
    }
}

/// The thesis's search region of coordinate j: the parameter interval [min, max] of the knots
/// collected by `suchbereich` (0-based translation of the listing).
///
/// Reproduced as written, including two quirks of the listing: a control point index above
/// n - 2 is clamped to n - 2 before its support knots are taken (the listing's
/// `if hv(i) > m-p-2, hv(i) = m-p-2` with m = n + p + 1, 1-based), and the point marked as used
/// (`Pbea(hv(i)) = NaN`) is the clamped index, so a largest value at one of the last two points
/// is found again in the second round.
pub fn thesis_region(c: &NurbsCurve, j: usize) -> (f64, f64) {
    let n = c.num_points() - 1;
    let p = c.degree();
    let kn = c.knots();
    let clamp_at = n.saturating_sub(2);
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for largest in [true, false] {
        // Pbea: the coordinates, None = NaN (removed)
        let mut pbea: Vec<Option<f64>> = (0..=n).map(|i| Some(c.control_point(i)[j])).collect();
        for _round in 0..2 {
            // Matlab max/min ignore NaN; all NaN gives NaN and find(... == NaN) finds nothing.
            let ext = pbea.iter().flatten().copied().reduce(|a, b| {
                if (largest && b > a) || (!largest && b < a) {
                    b
                } else {
                    a
                }
            });
            let Some(ext) = ext else { break };
            let hits: Vec<usize> = (0..=n).filter(|&i| pbea[i] == Some(ext)).collect();
            for i in hits {
                let i0 = i.min(clamp_at);
                for &u in &kn[i0..=i0 + p + 1] {
                    lo = lo.min(u);
                    hi = hi.max(u);
                }
                pbea[i0] = None;
            }
        }
    }
    (lo, hi)
}

impl BoxEncloser for SearchRegion {
    fn name(&self) -> &'static str {
        if self.verified {
            "search-region-verified"
        } else {
            "search-region"
        }
    }
    fn guarantee(&self) -> Guarantee {
        if self.verified {
            Guarantee::Verified
        } else {
            Guarantee::Heuristic
        }
    }
    fn enclose_prepared(&self, c: &NurbsCurve) -> Enclosure {
        let mut e = Engine::new(c, &self.newton);
        let ns = e.spans.len();
        let mut modes = vec![SpanMode::Skip; ns];
        let coords = (0..c.dim())
            .map(|j| {
                let (rlo, rhi) = thesis_region(c, j);
                let mut order = Vec::with_capacity(ns);
                for (si, &(_, a, b)) in e.spans.iter().enumerate() {
                    // spans meeting the open region (a single-point region: the span holding it)
                    let inside = (a < rhi && b > rlo) || (rlo == rhi && a <= rlo && rlo <= b);
                    modes[si] = if inside {
                        order.push(si);
                        SpanMode::Search
                    } else if self.verified {
                        SpanMode::Prune
                    } else {
                        SpanMode::Skip
                    };
                }
                if self.verified {
                    order.extend((0..ns).filter(|&si| modes[si] == SpanMode::Prune));
                }
                e.coord(j, &order, &modes)
            })
            .collect();
        Enclosure {
            strategy: self.name(),
            verified: self.verified,
            coords,
        }
    }
}
