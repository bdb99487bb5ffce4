//! Typed parameter boxes: the global curve parameter u and a span's local parameter t.
//!
//! The Newton search of a span runs either in u (interval de Boor on the derivative splines)
//! or, with the span's Bernstein form ([`super::Newton::bernstein`]), in the local parameter
//! t = (u - u_k) / (u_{k+1} - u_k) in [0, 1] of span k. A box of one space is never read as
//! one of the other: [`U`] and [`T`] are distinct types, a box of either is a [`SpanParam`],
//! and the only map from t to u is [`super::bernstein::SpanPoly::to_u`] (rounded outward).

use crate::num::iv;
use inari::Interval;

/// A box [lo, hi] (a point for lo == hi) of the global curve parameter u.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct U {
    pub(super) lo: f64,
    pub(super) hi: f64,
}

/// A box [lo, hi] (a point for lo == hi) of span k's local parameter t in [0, 1]
/// (meaningful only together with that span's [`super::bernstein::SpanPoly`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct T {
    pub(super) lo: f64,
    pub(super) hi: f64,
}

impl U {
    /// The box [lo, hi] of u.
    pub(super) fn new(lo: f64, hi: f64) -> Self {
        U { lo, hi }
    }

    /// The box as an interval, for interval de Boor (ENTIRE if it is not a valid interval).
    pub(super) fn interval(self) -> Interval {
        iv::span(self.lo, self.hi)
    }
}

impl T {
    /// The box [lo, hi] of t.
    pub(super) fn new(lo: f64, hi: f64) -> Self {
        T { lo, hi }
    }
}

/// The space a span search runs in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Space {
    /// the curve's parameter u, over the span [u_k, u_{k+1}]
    Global,
    /// the span's local parameter t, over [0, 1]
    Local,
}

/// A parameter box of a span search, tagged with its space: what [`super::engine::Engine`]'s
/// evaluations of C_j, f and f' take.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum SpanParam {
    /// a box of u: evaluated by interval de Boor
    Global(U),
    /// a box of t: evaluated on the span's Bernstein form
    Local(T),
}

impl Space {
    /// The box [lo, hi] of this space.
    pub(super) fn param(self, lo: f64, hi: f64) -> SpanParam {
        match self {
            Space::Global => SpanParam::Global(U::new(lo, hi)),
            Space::Local => SpanParam::Local(T::new(lo, hi)),
        }
    }
}

impl SpanParam {
    /// Its space.
    pub(super) fn space(self) -> Space {
        match self {
            SpanParam::Global(_) => Space::Global,
            SpanParam::Local(_) => Space::Local,
        }
    }

    /// Its bounds, in its own space.
    pub(super) fn bounds(self) -> (f64, f64) {
        match self {
            SpanParam::Global(U { lo, hi }) | SpanParam::Local(T { lo, hi }) => (lo, hi),
        }
    }
}

/// A midpoint of [x0, x1] inside it (no overflow for huge bounds).
#[inline]
pub(super) fn midpoint(x0: f64, x1: f64) -> f64 {
    (0.5 * x0 + 0.5 * x1).clamp(x0, x1)
}

/// Whether [x0, x1] has an f64 strictly inside.
#[inline]
pub(super) fn can_split(x0: f64, x1: f64) -> bool {
    let m = midpoint(x0, x1);
    x0 < m && m < x1
}
