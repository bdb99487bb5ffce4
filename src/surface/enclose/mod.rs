//! Box strategies for surfaces: the [`SurfaceEncloser`] trait (the surface counterpart of
//! [`crate::BoxEncloser`], returning the same [`Enclosure`]), the registry and the driver.
//!
//! Invariant of a verified strategy: for every coordinate j and every (u, v) in the domain,
//! `lo[j] <= S_j(u, v) <= hi[j]` exactly, rounding included; and the surface reaches the inner
//! bounds (some (u, v) has `S_j <= inner_lo[j]`, some has `S_j >= inner_hi[j]`).
//!
//! The strategies: [`NetHull`] (`hull`), [`BezierPatches`] (`bezier`), [`SurfaceNewton`]
//! (`newton`). Adding one is one file and one line in the registry below. `bezier` and
//! `newton` share a float-first fast path (module `fast`: vertex test, f64 candidates, proofs
//! on f64 Bernstein coefficients with a-priori error bounds) and run their own search only for
//! the sides it does not prove.

use crate::enclose::MAX_SEARCH_DEGREE;
use crate::enclose::{CoordBox, Enclosure, Guarantee, Settings, Stats, Termination};
use crate::num::iv;
use crate::surface::model::NurbsSurface;
use inari::Interval;

mod bezier;
mod fast;
mod hull;
mod newton;

pub use bezier::BezierPatches;
pub use hull::NetHull;
pub use newton::SurfaceNewton;

/// A box-enclosure strategy for surfaces (one required method, like [`crate::BoxEncloser`]).
pub trait SurfaceEncloser: Send + Sync {
    /// Short name (`hull`, `bezier`, `newton`).
    fn name(&self) -> &'static str;
    /// What the strategy promises.
    fn guarantee(&self) -> Guarantee;
    /// The strategy's algorithm on a surface of degrees <= [`MAX_SEARCH_DEGREE`]. Never
    /// panics; a work limit ends in a sound bound and its [`Termination`].
    fn enclose_prepared(&self, s: &NurbsSurface) -> Enclosure;
    /// Enclose any valid surface: [`SurfaceEncloser::enclose_prepared`] under [`drive`].
    fn enclose(&self, s: &NurbsSurface) -> Enclosure {
        drive(self, s)
    }
}

/// One registered surface strategy.
#[derive(Clone, Copy)]
pub struct SurfaceEntry {
    /// the name (`--strategy NAME`)
    pub name: &'static str,
    /// the constructor
    pub build: fn(&Settings) -> Box<dyn SurfaceEncloser>,
}

impl std::fmt::Debug for SurfaceEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SurfaceEntry")
            .field("name", &self.name)
            .finish()
    }
}

/// The surface strategies, in the order `--strategy all` uses (one line each).
pub const SURFACE_REGISTRY: &[SurfaceEntry] = &[
    SurfaceEntry {
        name: "hull",
        build: |_| Box::new(NetHull),
    },
    SurfaceEntry {
        name: "bezier",
        build: |s| Box::new(BezierPatches::with_settings(s)),
    },
    SurfaceEntry {
        name: "newton",
        build: |s| Box::new(SurfaceNewton::with_settings(s)),
    },
];

/// Names of the surface strategies.
pub const SURFACE_STRATEGY_NAMES: &[&str] = &["hull", "bezier", "newton"];

/// The surface strategy called `name` with `settings`; `None` if there is none of that name
/// (the curve-only strategies `newton-thesis`, `search-region`, `search-region-verified`).
pub fn surface_strategy_with(name: &str, settings: &Settings) -> Option<Box<dyn SurfaceEncloser>> {
    SURFACE_REGISTRY
        .iter()
        .find(|e| e.name == name)
        .map(|e| (e.build)(settings))
}

/// [`surface_strategy_with`] with default settings and tolerance `tol`.
pub fn surface_strategy_by_name(name: &str, tol: Option<f64>) -> Option<Box<dyn SurfaceEncloser>> {
    surface_strategy_with(
        name,
        &Settings {
            tol,
            ..Settings::default()
        },
    )
}

/// Every surface strategy built with `settings`.
pub fn all_surface_strategies(settings: &Settings) -> Vec<Box<dyn SurfaceEncloser>> {
    SURFACE_REGISTRY
        .iter()
        .map(|e| (e.build)(settings))
        .collect()
}

/// The budget `max` (set for a bicubic patch) scaled to the cost of one evaluation of `s`:
/// a tensor de Boor step costs ~(p + 1)^2 (q + 1) + (q + 1)^2 corner cuts, 80 for p = q = 3,
/// so a degree-1000 surface gets a budget of a few evaluations (then the sound fallback)
/// instead of minutes of work.
pub(crate) fn scaled_budget(max: u64, s: &NurbsSurface) -> u64 {
    let (p, q) = (s.degree_u() as u64 + 1, s.degree_v() as u64 + 1);
    let cost = (p * p * q + q * q).max(p * q * q + p * p).max(1);
    max.saturating_mul(80) / cost
}

/// The one place a surface [`CoordBox`] is built (argmin / argmax stay empty: the curve's
/// [`crate::Extremum`] holds a u range only).
pub(crate) fn coord_box(
    lo: f64,
    hi: f64,
    inner_lo: f64,
    inner_hi: f64,
    stats: Stats,
    termination: Termination,
) -> CoordBox {
    CoordBox {
        lo,
        hi,
        inner_lo,
        inner_hi,
        argmin: Default::default(),
        argmax: Default::default(),
        stats,
        termination,
        optimal_lo: false,
        optimal_hi: false,
        witness_lo: f64::INFINITY,
        witness_hi: f64::NEG_INFINITY,
    }
}

/// The one place a surface [`Enclosure`] is built.
pub(crate) fn enclosure(
    strategy: &'static str,
    verified: bool,
    coords: Vec<CoordBox>,
) -> Enclosure {
    Enclosure {
        strategy,
        verified,
        coords: coords.into_iter().collect(),
    }
}

/// The control-net box with inner bounds `inner[j]` (the net box is exact: the tensor-product
/// basis functions are >= 0 and sum to 1, weights > 0, so S(u, v) is a convex combination of
/// the P_ij; min / max of f64 data are exact).
pub(crate) fn net_box(
    s: &NurbsSurface,
    inner: &[(f64, f64)],
    termination: Termination,
    point_evaluations: u64,
) -> Vec<CoordBox> {
    (0..s.dim())
        .map(|j| {
            let (lo, hi) = s.coord_range(j);
            coord_box(
                lo,
                hi,
                inner[j].0,
                inner[j].1,
                Stats {
                    point_evaluations,
                    ..Default::default()
                },
                termination,
            )
        })
        .collect()
}

/// Verified enclosures of S at the four domain corners (u_p, v_q), (u_p, v_{m+1}),
/// (u_{n+1}, v_q), (u_{n+1}, v_{m+1}): the control point itself where both directions are
/// clamped there (the only non-zero basis products are N_r N_c = 1; the weights cancel),
/// interval evaluation otherwise. Values the surface takes, so inner-bound material.
pub(crate) fn corner_values(s: &NurbsSurface) -> Vec<Vec<Interval>> {
    let ((a, b), (c, d)) = s.domain();
    let mut out = Vec::with_capacity(4);
    for (u, ul) in [(a, false), (b, true)] {
        for (v, vl) in [(c, false), (d, true)] {
            match (s.exact_row_at(u, ul), s.exact_column_at(v, vl)) {
                (Some(r), Some(k)) => out.push(
                    s.control_point(r, k)
                        .iter()
                        .map(|&x| iv::point(x))
                        .collect(),
                ),
                _ => out.push(
                    s.enclose_derivative(u, v, 0, 0)
                        .unwrap_or_else(|_| vec![Interval::ENTIRE; s.dim()]),
                ),
            }
        }
    }
    out
}

/// Enclose `s` with `e`: the control-net box above [`MAX_SEARCH_DEGREE`] (reported as
/// [`Termination::WorkLimit`]), the strategy otherwise; then the facts applied to every result:
/// outer bounds clamped to the exact net box (a NaN or an overflow never survives as a bound),
/// and the inner bounds kept inside the outer box (every (u, v) has lo <= S_j <= hi, so the
/// surface reaches a value <= hi and one >= lo).
pub fn drive<E: SurfaceEncloser + ?Sized>(e: &E, s: &NurbsSurface) -> Enclosure {
    let mut r = if s.degree_u().max(s.degree_v()) > MAX_SEARCH_DEGREE {
        let inner: Vec<(f64, f64)> = (0..s.dim())
            .map(|j| {
                let (lo, hi) = s.coord_range(j);
                (hi, lo)
            })
            .collect();
        enclosure(
            e.name(),
            e.guarantee() == Guarantee::Verified,
            net_box(s, &inner, Termination::WorkLimit, 0),
        )
    } else {
        e.enclose_prepared(s)
    };
    for (j, cb) in r.coords.iter_mut().enumerate() {
        let (plo, phi) = s.coord_range(j);
        cb.lo = cb.lo.max(plo);
        cb.hi = cb.hi.min(phi);
        cb.inner_lo = cb.inner_lo.min(cb.hi).max(cb.lo);
        cb.inner_hi = cb.inner_hi.max(cb.lo).min(cb.hi);
        // The certificate's first rule (as for curves, `enclose::certify`): S_j provably
        // reaches a value <= inner_lo and never goes below lo, so inner_lo == lo means
        // min S_j = lo exactly, hence lo = RD(min); or it provably reaches a value
        // < witness_lo (a double-double value of the fast path, `Ddi::strictly_below`), and
        // witness_lo <= next_up(lo) means lo <= min < next_up(lo), hence lo = RD(min);
        // likewise hi. (No search for witnesses beyond what the strategies computed.)
        cb.optimal_lo = r.verified && (cb.inner_lo == cb.lo || cb.witness_lo <= cb.lo.next_up());
        cb.optimal_hi = r.verified && (cb.inner_hi == cb.hi || cb.witness_hi >= cb.hi.next_down());
    }
    r
}
