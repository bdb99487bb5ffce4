//! `bezier`: Bézier patch decomposition (Boehm knot insertion in u and v, NURBS Book A5.6 per
//! direction), tensor Bernstein bounds and subdivision (de Casteljau in u and v), branch and
//! bound per coordinate and side.
//!
//! * **Fast path first.** Every side goes through the float-first proofs of module `fast`
//!   (shared with `newton`); only a side they do not prove runs the branch and bound below
//!   (the patches are extracted in interval arithmetic only then).
//! * **Bounds.** A Bézier patch lies in the box of its coefficients (tensor Bernstein
//!   polynomials are >= 0 and sum to 1). For a rational patch with every weight coefficient
//!   w_rc > 0 the value S_j = A_j / w is a convex combination of the ratios b_rc / w_rc
//!   (Narkawicz, Garloff, Smith & Muñoz 2012: the range of p / q lies in [min b_i / d_i,
//!   max b_i / d_i] when every d_i > 0). The coefficients are interval enclosures of the exact
//!   ones (extraction and subdivision in outward-rounded interval arithmetic), so the bounds
//!   are the infima / suprema over the intervals. A weight coefficient not provably > 0 gives
//!   an unbounded patch (sound; it is subdivided or, at the work limit, left to the driver's
//!   net-box clamp).
//! * **Attained values.** The corner coefficients are the surface values at the patch corners
//!   (Zettler & Garloff 1998 vertex test: a bound attained at a corner coefficient is exact), so
//!   `sup` of a corner ratio bounds an attained value from above: the inner bound.
//! * **Convergence.** The bounds of a polynomial patch converge quadratically in the patch
//!   width under subdivision (Garloff 1986); the search stops when the smallest lower bound is
//!   within `tol` times the coordinate's scale of the best attained value, at the depth limit,
//!   or at the work limit (sound: the bound is the smallest over all open patches).

use super::fast::FastSurface;
use super::{coord_box, enclosure, SurfaceEncloser};
use crate::enclose::{Enclosure, Guarantee, Settings, Stats, Termination};
use crate::num::Scalar;
use crate::surface::eval::Patch;
use crate::surface::model::NurbsSurface;
use inari::Interval;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Bézier patch subdivision with Bernstein (ratio) bounds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BezierPatches {
    /// relative tolerance: stop when a bound is within `tol * scale` of an attained value
    pub tol: f64,
    /// patch splits per coordinate and side for a bicubic patch (scaled to the degree)
    pub max_work: u64,
    /// deepest subdivision (halvings per direction)
    pub max_depth: u32,
    /// float first, prove after (the `fast` module: vertex test, f64 candidates, proofs on
    /// f64 Bernstein coefficients with an a-priori error bound); a side it cannot prove goes
    /// through the branch and bound below. Off only for comparisons.
    pub fast_path: bool,
}

impl Default for BezierPatches {
    fn default() -> Self {
        BezierPatches {
            tol: f64::EPSILON,
            max_work: 2000,
            max_depth: 40,
            fast_path: true,
        }
    }
}

impl BezierPatches {
    /// With the registry's settings (tolerance; work budget capped at the default).
    pub fn with_settings(s: &Settings) -> Self {
        let d = BezierPatches::default();
        BezierPatches {
            tol: s
                .tol
                .filter(|t| t.is_finite() && *t >= 0.0)
                .unwrap_or(d.tol),
            max_work: s.max_work.clamp(1, d.max_work),
            ..d
        }
    }
}

/// Bounds of coordinate j (times `sign`, so the maximum is a minimum of -S_j) on a patch:
/// (lower bound, smallest upper bound of a corner value).
fn bounds(pa: &Patch<Interval>, j: usize, rational: bool, sign: f64) -> (f64, f64) {
    let d = pa.h - 1;
    let sg = Interval::try_from((sign, sign)).unwrap_or(Interval::ENTIRE);
    let val = |c: &[Interval]| -> Interval {
        let cj = c[j].to_interval();
        if !rational {
            return sg * cj;
        }
        let w = c[d].to_interval();
        if w.inf() > 0.0 {
            sg * (cj / w)
        } else {
            Interval::ENTIRE
        }
    };
    let mut lo = f64::INFINITY;
    for r in 0..=pa.p {
        for c in 0..=pa.q {
            lo = lo.min(val(pa.coef(r, c)).inf());
        }
    }
    let mut best = f64::INFINITY;
    for (r, c) in [(0, 0), (0, pa.q), (pa.p, 0), (pa.p, pa.q)] {
        best = best.min(val(pa.coef(r, c)).sup());
    }
    // a NaN (never expected from a valid surface) must not look like a bound
    (if lo.is_nan() { f64::NEG_INFINITY } else { lo }, best)
}

/// The patch of coordinate j alone: rows (w P_j, w), or (P_j).
fn coordinate_patch(pa: &Patch<Interval>, j: usize, rational: bool) -> Patch<Interval> {
    let d = pa.h - 1;
    let mut pts = Vec::with_capacity((pa.p + 1) * (pa.q + 1) * (1 + rational as usize));
    for c in pa.pts.chunks(pa.h) {
        pts.push(c[j]);
        if rational {
            pts.push(c[d]);
        }
    }
    Patch {
        h: 1 + rational as usize,
        pts,
        ..pa.clone()
    }
}

struct Item {
    lo: f64,
    depth: u32,
    patch: Patch<Interval>,
}
impl PartialEq for Item {
    fn eq(&self, o: &Self) -> bool {
        self.lo.total_cmp(&o.lo) == Ordering::Equal
    }
}
impl Eq for Item {}
impl PartialOrd for Item {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Item {
    // BinaryHeap is a max-heap: the smallest lower bound first
    fn cmp(&self, o: &Self) -> Ordering {
        o.lo.total_cmp(&self.lo)
    }
}

impl BezierPatches {
    /// Branch and bound for min_j (sign 1) or -max_j (sign -1): (outer, attained, stats,
    /// termination) in the signed coordinate.
    #[allow(clippy::too_many_arguments)]
    fn search(
        &self,
        budget: u64,
        patches: &[Patch<Interval>],
        j: usize,
        rational: bool,
        sign: f64,
        scale: f64,
    ) -> (f64, f64, Stats, Termination) {
        let mut st = Stats::default();
        let mut heap = BinaryHeap::new();
        let mut best = f64::INFINITY;
        for pa in patches {
            let (lo, b) = bounds(pa, j, rational, sign);
            best = best.min(b);
            heap.push(Item {
                lo,
                depth: 0,
                patch: pa.clone(),
            });
        }
        st.point_evaluations += patches.len() as u64;
        let tol = self.tol * scale;
        let mut disc = f64::INFINITY; // smallest lower bound of a dropped patch
        let mut work = 0;
        while let Some(it) = heap.pop() {
            // it.lo is the smallest lower bound of every open patch: with the dropped ones it
            // bounds the whole domain from below
            let lo = it.lo.min(disc);
            let term = if it.lo >= best - tol {
                Some(Termination::Converged)
            } else if work >= budget {
                Some(Termination::WorkLimit)
            } else if it.depth >= self.max_depth {
                Some(Termination::DepthLimit)
            } else {
                None
            };
            if let Some(t) = term {
                return (lo, best, st, t);
            }
            work += 1;
            st.subdivisions += 1;
            let (a, b) = it.patch.split_u(0.5);
            for half in [a, b] {
                let (c, d) = half.split_v(0.5);
                for ch in [c, d] {
                    let (clo, cb) = bounds(&ch, j, rational, sign);
                    st.point_evaluations += 1;
                    best = best.min(cb);
                    if clo >= best {
                        disc = disc.min(clo);
                    } else {
                        heap.push(Item {
                            lo: clo,
                            depth: it.depth + 1,
                            patch: ch,
                        });
                    }
                }
            }
        }
        (disc, best, st, Termination::Converged)
    }
}

impl SurfaceEncloser for BezierPatches {
    fn name(&self) -> &'static str {
        "bezier"
    }
    fn guarantee(&self) -> Guarantee {
        Guarantee::Verified
    }
    fn enclose_prepared(&self, s: &NurbsSurface) -> Enclosure {
        let t0 = crate::enclose::Clock::start();
        let fast = self.fast_path.then(|| FastSurface::new(s)).flatten();
        // (Interval, not the faster Mr: Mr's radii after many subdivisions cost tens of ulps
        // at the vertex test); extracted only if some side needs the branch and bound
        let mut patches: Option<Vec<Patch<Interval>>> = None;
        let rational = s.is_rational();
        let mut coords: Vec<_> = (0..s.dim())
            .map(|j| {
                let mut st = Stats::default();
                // per side: (outer, attained, termination) of sign * S_j's maximum
                let mut sides = [None, None];
                // the fast path's strict witnesses (sign-adjusted; `Ddi::strictly_below`)
                let mut wit = [f64::NEG_INFINITY; 2];
                for (k, sign) in [(0, -1.0), (1, 1.0)] {
                    if let Some((b, at, w)) = fast.as_ref().and_then(|f| f.side(j, sign, &mut st)) {
                        sides[k] = Some((b, at, Termination::Converged));
                        wit[k] = w;
                    }
                }
                for (k, sign) in [(0, 1.0), (1, -1.0)] {
                    if sides[k].is_some() {
                        continue;
                    }
                    let all = patches.get_or_insert_with(|| s.bezier_patches::<Interval>());
                    // the search subdivides coordinate j (and the weight row) only
                    let pj: Vec<Patch<Interval>> = all
                        .iter()
                        .map(|pa| coordinate_patch(pa, j, rational))
                        .collect();
                    let budget = super::scaled_budget(self.max_work, s);
                    // (the search minimises sign * S_j: its results are minus the maximum
                    // of -sign * S_j)
                    let scale = s.coord_scale(j);
                    let (lo, ilo, st2, t) = self.search(budget, &pj, 0, rational, sign, scale);
                    st.add(&st2);
                    sides[k] = Some((-lo, -ilo, t));
                }
                let [(nlo, nilo, t1), (hi, ihi, t2)] = sides.map(|x| x.expect("both sides"));
                let term = if t1 == Termination::Converged { t2 } else { t1 };
                let mut cb = coord_box(-nlo, hi, -nilo, ihi, st, term);
                (cb.witness_lo, cb.witness_hi) = (-wit[0], wit[1]);
                cb
            })
            .collect();
        if let Some(c) = coords.first_mut() {
            c.stats.time_total = t0.elapsed();
        }
        enclosure(self.name(), true, coords)
    }
}
