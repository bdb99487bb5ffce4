//! The [`BoxEncloser`] trait, the [`Enclosure`] it returns, the strategy registry and the
//! driver that every strategy runs under.
//!
//! Invariant of a *verified* strategy (see `guarantees.md`): for every coordinate j and every u
//! in the domain, `lo[j] <= C_j(u) <= hi[j]` exactly, rounding included; and the curve reaches
//! the inner bounds: some u has `C_j(u) <= inner_lo[j]`, some u' has `C_j(u') >= inner_hi[j]`.
//!
//! # Adding a strategy
//!
//! One file `src/enclose/NAME.rs` with a type implementing [`BoxEncloser`] (its
//! `enclose_prepared`), and one line in the [`registry!`] call below. The command line
//! (`--strategy NAME`, `--strategy all`), the `serve` API, the reproduction harness, the benches,
//! the robustness and fuzz lists and the property tests all take their strategies from the
//! registry; `tests/docs.rs` checks that `src/guarantees.md` and `docs/formats.md` list it.
//!
//! # The driver
//!
//! [`BoxEncloser::enclose`] is provided: it runs the strategy's `enclose_prepared` under
//! [`driver::drive`] (exact power-of-two rescaling of extreme curves, span-by-span Bézier
//! pieces for knot vectors no exact scaling can tame, the control-point box above
//! [`MAX_SEARCH_DEGREE`], and the facts applied to every result). So `Newton::default()
//! .enclose(c)` and `strategy_by_name("newton", None).enclose(c)` are the same computation.

use crate::spline::curve::NurbsCurve;

pub mod certify;
pub mod driver;
pub mod lane;
mod result;
mod segments;

pub(crate) use bezier::single::{raw_sides, root_estimates, Segment};
pub use bezier::BezierSubdivision;
pub use driver::{degree_fallback, drive, drive_with, scale_outward, Rescaling, MAX_SEARCH_DEGREE};
pub use hull::ControlHull;
pub use newton::{DerivForm, Newton, Split, DEFAULT_MAX_WORK, EVALS_PER_SPAN, WORK_PER_SPAN};
pub(crate) use result::SideData;
pub use result::{
    set_timing, timing, CandidateKind, Clock, CoordBox, Coords, Enclosure, Extrema, Extremum,
    Guarantee, Stats, Termination,
};
pub use search_region::SearchRegion;

/// A box-enclosure strategy (one required method, like argmin's solvers).
pub trait BoxEncloser: Send + Sync {
    /// Short name used on the command line and in results (`newton`, `hull`, ...).
    fn name(&self) -> &'static str;
    /// What the strategy promises.
    fn guarantee(&self) -> Guarantee;
    /// The strategy's own algorithm, on a curve the driver has prepared: magnitudes in a
    /// moderate range, degree <= [`MAX_SEARCH_DEGREE`]. Never fails and never panics: when a
    /// work limit is reached the strategy falls back to a coarser sound bound and says so in
    /// `termination`. Implement this one; call [`BoxEncloser::enclose`].
    fn enclose_prepared(&self, curve: &NurbsCurve) -> Enclosure;
    /// How the strategy answers a clamped polynomial Bézier segment or a spline of degree <= 5,
    /// or a rational curve of degree 2 to 5 (splines clamped or not; unclamped ones and curves
    /// scaled into the magnitude window only for the tight lane), with moderate magnitudes ([`lane::Simple`]), which the
    /// driver then encloses directly in its lane ([`lane`]) instead of calling
    /// [`BoxEncloser::enclose_prepared`]; `None` (the default): always the general path. A strategy returns a lane only if the lane's answer
    /// is its own (the control-point box, or the tight box its fast path proves).
    fn lane(&self) -> Option<lane::Lane> {
        None
    }
    /// Enclose any valid curve: [`BoxEncloser::enclose_prepared`] under the driver
    /// ([`driver::drive`]). The result is an enclosure of `curve` itself.
    fn enclose(&self, curve: &NurbsCurve) -> Enclosure {
        drive(self, curve)
    }
}

/// What the registry's constructors may set: the tolerance (`None`: each strategy's default)
/// and the work budget per coordinate of the searching strategies ([`Newton::max_work`],
/// [`BezierSubdivision::max_work`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// relative tolerance, or the strategy's default
    pub tol: Option<f64>,
    /// work budget per coordinate
    pub max_work: u64,
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            tol: None,
            max_work: DEFAULT_MAX_WORK,
        }
    }
}

impl Settings {
    /// Newton's defaults with these settings.
    pub fn newton(&self) -> Newton {
        Newton {
            max_work: self.max_work,
            ..self.tol.map_or_else(Newton::default, Newton::with_tol)
        }
    }
    /// The thesis preset with this work budget (its own tolerance, the thesis's).
    pub fn newton_thesis(&self) -> Newton {
        Newton {
            max_work: self.max_work,
            ..Newton::thesis()
        }
    }
    /// The Bézier subdivision's defaults with these settings.
    pub fn bezier(&self) -> BezierSubdivision {
        BezierSubdivision {
            max_work: self.max_work,
            ..self
                .tol
                .map_or_else(BezierSubdivision::default, BezierSubdivision::with_tol)
        }
    }
}

/// One registered strategy: its name and how to build it from [`Settings`].
#[derive(Clone, Copy)]
pub struct Entry {
    /// the name (`--strategy NAME`)
    pub name: &'static str,
    /// the constructor
    pub build: fn(&Settings) -> Box<dyn BoxEncloser>,
}

impl std::fmt::Debug for Entry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Entry").field("name", &self.name).finish()
    }
}

/// Declares the strategy modules and the registry: `mod FILE { "NAME" => |settings| VALUE, ... }`.
macro_rules! registry {
    ($(mod $m:ident { $($name:literal => |$s:pat_param| $build:expr),+ $(,)? })*) => {
        $(mod $m;)*
        /// The registry, in the order `--strategy all` uses.
        pub const REGISTRY: &[Entry] = &[
            $($(Entry { name: $name, build: |$s: &Settings| Box::new($build) },)+)*
        ];
        /// Names of all strategies, in the order `--strategy all` uses.
        pub const STRATEGY_NAMES: &[&str] = &[$($($name,)+)*];
    };
}

// The registry: one line per strategy.
registry! {
    mod hull { "hull" => |_| ControlHull }
    mod bezier { "bezier" => |s| s.bezier() }
    mod newton {
        "newton" => |s| s.newton(),
        // the thesis's own settings (listing `inewtonKNRH`): reproduces its tables
        "newton-thesis" => |s| Renamed("newton-thesis", s.newton_thesis()),
    }
    mod search_region {
        "search-region" => |s| SearchRegion::thesis(s.newton()),
        "search-region-verified" => |s| SearchRegion::verified(s.newton()),
    }
}

/// The strategy called `name` (see [`STRATEGY_NAMES`]), with tolerance `tol` where the strategy
/// has one (`None`: its default). `None` if the name is unknown.
pub fn strategy_by_name(name: &str, tol: Option<f64>) -> Option<Box<dyn BoxEncloser>> {
    strategy_with(
        name,
        &Settings {
            tol,
            ..Settings::default()
        },
    )
}

/// The strategy called `name` built with `settings`; `None` if the name is unknown.
pub fn strategy_with(name: &str, settings: &Settings) -> Option<Box<dyn BoxEncloser>> {
    REGISTRY
        .iter()
        .find(|e| e.name == name)
        .map(|e| (e.build)(settings))
}

/// [`strategy_by_name`] with the work budget `max_work` (per coordinate) of the searching
/// strategies, for callers that bound the time of one call (the `serve` API).
pub fn strategy_with_work(
    name: &str,
    tol: Option<f64>,
    max_work: u64,
) -> Option<Box<dyn BoxEncloser>> {
    strategy_with(name, &Settings { tol, max_work })
}

/// Every registered strategy built with `settings`, in registry order.
pub fn all_strategies_with(settings: &Settings) -> Vec<Box<dyn BoxEncloser>> {
    REGISTRY.iter().map(|e| (e.build)(settings)).collect()
}

/// All strategies (see [`STRATEGY_NAMES`]).
pub fn all_strategies(tol: Option<f64>) -> Vec<Box<dyn BoxEncloser>> {
    all_strategies_with(&Settings {
        tol,
        ..Settings::default()
    })
}

/// A strategy under another name (a preset of a configurable strategy).
struct Renamed<E>(&'static str, E);

impl<E: BoxEncloser> BoxEncloser for Renamed<E> {
    fn name(&self) -> &'static str {
        self.0
    }
    fn guarantee(&self) -> Guarantee {
        self.1.guarantee()
    }
    fn enclose_prepared(&self, curve: &NurbsCurve) -> Enclosure {
        let mut e = self.1.enclose_prepared(curve);
        e.strategy = self.0;
        e
    }
    fn lane(&self) -> Option<lane::Lane> {
        self.1.lane()
    }
}
