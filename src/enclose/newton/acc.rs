//! The candidate accumulator: every candidate parameter box ([`Cand`]) is evaluated by the
//! engine and added to [`Acc`], the running hull of the outer enclosures and of the values the
//! curve attains, which [`Acc::finish`] turns into the coordinate's [`CoordBox`].

use smallvec::SmallVec;
use super::param::{T, U};
use crate::enclose::{CandidateKind, CoordBox, Extremum, Stats, Termination};
use crate::num::ddi::Ddi;
use inari::Interval;

/// A candidate: parameter box `u` inside the closed span `k`, evaluated with that span's
/// polynomial piece.
#[derive(Debug, Clone, Copy)]
pub(super) struct Cand {
    pub(super) k: usize,
    /// the box of the global parameter u (a point for the end points and knots)
    pub(super) u: U,
    pub(super) kind: CandidateKind,
    pub(super) unique: bool,
    /// whether the curve attains the value of span k's piece at the point(s) evaluated (false
    /// for the left limit at a discontinuity)
    pub(super) attained: bool,
    /// the box in the span's local parameter t, whose image u([t0, t1]) is in `u`
    /// (boxes of a search on the Bernstein form)
    pub(super) t: Option<T>,
}

impl Cand {
    /// A single parameter value q evaluated with span k's piece.
    pub(super) fn point(k: usize, q: f64, kind: CandidateKind, attained: bool) -> Self {
        Cand {
            k,
            u: U::new(q, q),
            kind,
            unique: false,
            attained,
            t: None,
        }
    }
}

/// Running hull of candidate enclosures.
pub(super) struct Acc {
    lo: f64,
    hi: f64,
    /// the curve attains a value <= `inner_lo` (and >= `inner_hi`)
    pub(super) inner_lo: f64,
    pub(super) inner_hi: f64,
    /// strict witnesses: the curve reaches a value < `witness_lo` (and > `witness_hi`)
    witness_lo: f64,
    witness_hi: f64,
    cands: SmallVec<[(Extremum, Interval); 8]>,
}

impl Acc {
    pub(super) fn new() -> Self {
        Acc {
            lo: f64::INFINITY,
            hi: f64::NEG_INFINITY,
            inner_lo: f64::INFINITY,
            inner_hi: f64::NEG_INFINITY,
            witness_lo: f64::INFINITY,
            witness_hi: f64::NEG_INFINITY,
            cands: SmallVec::new(),
        }
    }

    /// Add candidate `cd` with the outer enclosure `e` of its values, enclosures of values
    /// the curve attains (EMPTY for none), and a double-double enclosure `w` of a value the
    /// curve attains (if any): the largest double strictly below it is a strict witness for the
    /// maximum, the smallest strictly above it one for the minimum (the certificate's first
    /// rule then needs no evaluation of its own).
    pub(super) fn add(&mut self, cd: &Cand, e: Interval, attained: [Interval; 2], w: Option<Ddi>) {
        if let Some(v) = w {
            self.witness_hi = self.witness_hi.max(v.strictly_below());
            self.witness_lo = self.witness_lo.min(-(-v).strictly_below());
        }
        // An empty enclosure cannot occur (every value evaluated is a real number); treat it
        // as "anything" to stay sound.
        let e = if e.is_empty() { Interval::ENTIRE } else { e };
        self.lo = self.lo.min(e.inf());
        self.hi = self.hi.max(e.sup());
        for v in attained.into_iter().filter(|v| !v.is_empty()) {
            // The curve attains a value inside v: it reaches <= sup v and >= inf v.
            self.inner_lo = self.inner_lo.min(v.sup());
            self.inner_hi = self.inner_hi.max(v.inf());
        }
        self.cands.push((
            Extremum {
                u_lo: cd.u.lo,
                u_hi: cd.u.hi,
                unique: cd.unique,
                kind: cd.kind,
            },
            e,
        ));
    }

    /// The coordinate box: the hull, the inner bounds, and the candidates reaching them.
    pub(super) fn finish(self, stats: Stats, termination: Termination) -> CoordBox {
        let (ilo, ihi) = (self.inner_lo, self.inner_hi);
        let argmin = self
            .cands
            .iter()
            .filter(|(_, e)| e.inf() <= ilo)
            .map(|c| c.0)
            .collect();
        let argmax = self
            .cands
            .iter()
            .filter(|(_, e)| e.sup() >= ihi)
            .map(|c| c.0)
            .collect();
        CoordBox {
            lo: self.lo,
            hi: self.hi,
            inner_lo: ilo.max(self.lo),
            inner_hi: ihi.min(self.hi),
            argmin,
            argmax,
            stats,
            termination,
            optimal_lo: false,
            optimal_hi: false,
            witness_lo: self.witness_lo,
            witness_hi: self.witness_hi,
        }
    }
}
