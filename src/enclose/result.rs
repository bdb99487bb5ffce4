//! What a strategy returns: per coordinate the outer and inner bounds, where the extrema are,
//! what it cost and why it stopped ([`Enclosure`], [`CoordBox`], [`Stats`], [`Termination`]).

use smallvec::SmallVec;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// Candidate locations of one side of a coordinate ([`CoordBox::argmin`] / `argmax`): inline
/// storage for the usual single candidate (no heap allocation; ties spill to the heap), a
/// slice to read.
pub type Extrema = SmallVec<[Extremum; 1]>;

/// The per-coordinate results of an [`Enclosure`]: inline storage up to three coordinates (no
/// heap allocation for 2-D and 3-D curves), a slice to read.
pub type Coords = SmallVec<[CoordBox; 3]>;

/// Whether the strategies read the clock (`Stats::time_total`, `Stats::time_derivatives`).
static TIMING: AtomicBool = AtomicBool::new(false);

/// Ask every strategy to measure its time (`Stats::time_total`, and `time_derivatives` of
/// the strategies that split it out), process-wide. Off by default: two clock reads per
/// coordinate cost more than a whole cubic's box. The command line's `--timings` and the
/// reproduction harness switch it on; `Newton::time_derivatives` still decides the
/// per-evaluation timing of the Newton search.
pub fn set_timing(on: bool) {
    TIMING.store(on, Ordering::Relaxed);
}

/// Whether timing was asked for ([`set_timing`]).
#[inline]
pub fn timing() -> bool {
    TIMING.load(Ordering::Relaxed)
}

/// A stopwatch that reads the clock only when timing was asked for ([`set_timing`]).
#[derive(Debug, Clone, Copy)]
pub struct Clock(Option<Instant>);

impl Clock {
    /// Start (a clock read if timing is on, nothing otherwise).
    #[inline]
    pub fn start() -> Clock {
        Clock(timing().then(Instant::now))
    }
    /// Time since the start, and restart; zero when timing is off.
    #[inline]
    pub fn lap(&mut self) -> Duration {
        match &mut self.0 {
            Some(t) => {
                let now = Instant::now();
                let d = now - *t;
                *t = now;
                d
            }
            None => Duration::ZERO,
        }
    }
    /// Time since the start; zero when timing is off.
    #[inline]
    pub fn elapsed(&self) -> Duration {
        self.0.map_or(Duration::ZERO, |t| t.elapsed())
    }
}

/// What a strategy promises about its box.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Guarantee {
    /// lo <= C(u) <= hi for every u in the domain, rounding included.
    Verified,
    /// No containment guarantee (a heuristic, e.g. the thesis's search region).
    Heuristic,
}

/// Why a strategy stopped working on a coordinate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum Termination {
    /// Every sub-problem was resolved to the tolerance.
    #[default]
    Converged,
    /// The per-box iteration limit was reached somewhere; the unresolved boxes were enclosed
    /// as a whole (sound, maybe less tight).
    IterationLimit,
    /// The limit on the number of boxes / segments was reached; the rest was enclosed as a
    /// whole (sound, maybe less tight).
    BoxLimit,
    /// The subdivision depth limit was reached (sound, maybe less tight).
    DepthLimit,
    /// The work budget (evaluations weighted by their cost, which grows with the degree) was
    /// spent; what was left was enclosed as a whole (sound, maybe less tight).
    WorkLimit,
    /// Nothing to iterate (e.g. the control hull needs no search).
    Direct,
}

/// Where a candidate extremum lies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CandidateKind {
    /// a domain end point
    EndPoint,
    /// a non-differentiable knot (multiplicity >= p)
    Knot,
    /// a zero of C_j' found by a search
    Critical,
    /// a parameter box that could not be resolved (enclosed as a whole)
    Unresolved,
    /// a control point (hull strategy)
    ControlPoint,
}

/// A parameter interval that contains a point where a coordinate attains its bound.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extremum {
    /// parameter interval start
    pub u_lo: f64,
    /// parameter interval end
    pub u_hi: f64,
    /// whether exactly one zero of C_j' in [u_lo, u_hi] was proved (interval Newton:
    /// N(X) in the interior of X)
    pub unique: bool,
    /// what kind of candidate it is
    pub kind: CandidateKind,
}

/// Work counters (the thesis's table columns and more).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Stats {
    /// interval Newton steps
    pub newton_iterations: u64,
    /// evaluations of C' / C'' enclosures
    pub derivative_evaluations: u64,
    /// evaluations of C (points or enclosures)
    pub point_evaluations: u64,
    /// subdivisions (box splits, de Casteljau splits)
    pub subdivisions: u64,
    /// resolved by a cheap exit: coordinate sides whose extreme control value is an attained
    /// end value (exact, no search), and spans of the Newton search pruned by their f64 Bézier
    /// points with an a-priori error bound
    pub fast_exits: u64,
    /// proven by the float-first path (f64 zero estimates, then proofs): coordinate sides of
    /// a single quadratic / cubic Bézier segment, and spans of the Newton search whose
    /// complement of the tiny zero boxes was excluded
    pub fast_proofs: u64,
    /// where the float-first path could not prove everything and the general search ran:
    /// coordinate sides (`bezier`), spans (`newton`)
    pub fast_fallbacks: u64,
    /// time spent evaluating derivatives (zero unless timing was asked for: [`set_timing`],
    /// [`crate::enclose::Newton::time_derivatives`])
    pub time_derivatives: Duration,
    /// total time (zero unless timing was asked for: [`set_timing`])
    pub time_total: Duration,
}

impl Stats {
    /// Add another set of counters.
    pub fn add(&mut self, o: &Stats) {
        self.newton_iterations += o.newton_iterations;
        self.derivative_evaluations += o.derivative_evaluations;
        self.point_evaluations += o.point_evaluations;
        self.subdivisions += o.subdivisions;
        self.fast_exits += o.fast_exits;
        self.fast_proofs += o.fast_proofs;
        self.fast_fallbacks += o.fast_fallbacks;
        self.time_derivatives += o.time_derivatives;
        self.time_total += o.time_total;
    }
}

/// The result for one coordinate.
#[derive(Debug, Clone, PartialEq)]
pub struct CoordBox {
    /// outer lower bound
    pub lo: f64,
    /// outer upper bound
    pub hi: f64,
    /// the curve provably reaches a value <= inner_lo
    pub inner_lo: f64,
    /// the curve provably reaches a value >= inner_hi
    pub inner_hi: f64,
    /// where the minimum is attained (candidates whose enclosure reaches `lo`)
    pub argmin: Extrema,
    /// where the maximum is attained
    pub argmax: Extrema,
    /// work done on this coordinate
    pub stats: Stats,
    /// why the search stopped
    pub termination: Termination,
    /// `true` is a proof that `lo` is the optimal double, lo = RD(min_u C_j(u)) (the largest
    /// f64 <= the exact minimum); `false` says only that it was not proved. Set by the driver's
    /// certification (`enclose::certify`); strategies construct it `false`.
    pub optimal_lo: bool,
    /// `true` is a proof that hi = RU(max_u C_j(u)) (the smallest f64 >= the exact maximum).
    pub optimal_hi: bool,
    /// A strict witness for the certificate: the curve provably reaches a value < witness_lo
    /// (`+inf` when none is known). Strategies that enclose a value the curve attains far more
    /// tightly than an f64 interval (a double-double value at a proved critical point) record
    /// it here, so that the certification need not evaluate the curve again.
    pub witness_lo: f64,
    /// The curve provably reaches a value > witness_hi (`-inf` when none is known).
    pub witness_hi: f64,
}

/// One side of a coordinate, sign-adjusted (the min side is the max side of -C_j), as the
/// strategies hand it to [`CoordBox::from_sides`].
#[derive(Debug, Clone)]
pub(crate) struct SideData {
    /// proven upper bound of the side's function
    pub upper: f64,
    /// the function provably reaches a value >= attained
    pub attained: f64,
    /// the function provably reaches a value > witness
    pub witness: f64,
    /// candidates where the bound is reached
    pub args: Extrema,
}

impl CoordBox {
    /// A box to be filled in place: nothing bounded, nothing attained, no candidates, no
    /// certificates. A constant, so that appending it to a result copies it from read-only
    /// data: a box built on the stack just before and then moved in is read back by wide
    /// loads from the narrow stores just made, which wait for those to reach the cache (most
    /// of the lane's cost of writing its result).
    pub(crate) const BLANK: CoordBox = CoordBox {
        lo: f64::NEG_INFINITY,
        hi: f64::INFINITY,
        inner_lo: f64::INFINITY,
        inner_hi: f64::NEG_INFINITY,
        argmin: Extrema::new_const(),
        argmax: Extrema::new_const(),
        stats: Stats {
            newton_iterations: 0,
            derivative_evaluations: 0,
            point_evaluations: 0,
            subdivisions: 0,
            fast_exits: 0,
            fast_proofs: 0,
            fast_fallbacks: 0,
            time_derivatives: Duration::ZERO,
            time_total: Duration::ZERO,
        },
        termination: Termination::Converged,
        optimal_lo: false,
        optimal_hi: false,
        witness_lo: f64::INFINITY,
        witness_hi: f64::NEG_INFINITY,
    };

    /// The coordinate box of the max side `hi` (of C_j) and the min side `lo` (of -C_j), with
    /// unproved certificates (`false`: the driver's certification sets them).
    pub(crate) fn from_sides(
        hi: SideData,
        lo: SideData,
        stats: Stats,
        termination: Termination,
    ) -> CoordBox {
        let mut cb = CoordBox::BLANK;
        cb.set_sides(hi, lo);
        cb.stats = stats;
        cb.termination = termination;
        cb
    }

    /// The bounds, attained values, witnesses and candidates of the max side `hi` (of C_j)
    /// and the min side `lo` (of -C_j), written to this box in place (the lane fills its
    /// result's boxes this way, [`CoordBox::BLANK`]); stats, termination and certificates
    /// are left as they are.
    pub(crate) fn set_sides(&mut self, hi: SideData, lo: SideData) {
        self.lo = -lo.upper;
        self.hi = hi.upper;
        self.inner_lo = -lo.attained;
        self.inner_hi = hi.attained;
        self.argmin = lo.args;
        self.argmax = hi.args;
        self.witness_lo = -lo.witness;
        self.witness_hi = hi.witness;
    }

    /// Certified overestimation bound: max(inner_lo - lo, hi - inner_hi).
    pub fn gap(&self) -> f64 {
        (self.inner_lo - self.lo).max(self.hi - self.inner_hi)
    }
}

/// A box enclosure of a curve, one [`CoordBox`] per coordinate.
#[derive(Debug, Clone, PartialEq)]
pub struct Enclosure {
    /// strategy name
    pub strategy: &'static str,
    /// whether the containment guarantee holds
    pub verified: bool,
    /// per-coordinate results
    pub coords: Coords,
}

impl Enclosure {
    /// Outer lower corner.
    pub fn lo(&self) -> Vec<f64> {
        self.coords.iter().map(|c| c.lo).collect()
    }
    /// Outer upper corner.
    pub fn hi(&self) -> Vec<f64> {
        self.coords.iter().map(|c| c.hi).collect()
    }
    /// Inner lower corner.
    pub fn inner_lo(&self) -> Vec<f64> {
        self.coords.iter().map(|c| c.inner_lo).collect()
    }
    /// Inner upper corner.
    pub fn inner_hi(&self) -> Vec<f64> {
        self.coords.iter().map(|c| c.inner_hi).collect()
    }
    /// Counters summed over coordinates.
    pub fn stats(&self) -> Stats {
        let mut s = Stats::default();
        for c in &self.coords {
            s.add(&c.stats);
        }
        s
    }
    /// The "worst" termination over coordinates (anything but Converged/Direct wins).
    pub fn termination(&self) -> Termination {
        self.coords
            .iter()
            .map(|c| c.termination)
            .find(|t| !matches!(t, Termination::Converged | Termination::Direct))
            .unwrap_or_else(|| {
                self.coords
                    .first()
                    .map_or(Termination::Direct, |c| c.termination)
            })
    }
    /// Whether the box contains the point (closed box).
    pub fn contains(&self, x: &[f64]) -> bool {
        self.coords
            .iter()
            .zip(x)
            .all(|(c, &v)| c.lo <= v && v <= c.hi)
    }
}
