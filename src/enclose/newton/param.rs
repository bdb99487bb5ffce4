//! Typed parameter boxes: the global curve parameter u and a span's local parameter t.
//!
//! The Newton search of a span runs either in u (interval de Boor on the derivative splines)
//! or, with the span's Bernstein form ([`super::Newton::bernstein`]), in the local parameter
//! t = (u - u_k) / (u_{k+1} - u_k) in [0, 1] of span k. A box of one space is never read as
//! one of the other: [`U`] and [`T`] are distinct types, a box of either is a [`SpanParam`],
//! and the only map from t to u is [`local_to_u`] (rounded outward; `SpanPoly::to_u`).

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

/// The box of the curve parameter u that contains u(t) = a + t (b - a) for every t in
/// [t0, t1] inside [0, 1], for the span [a, b]: the map from a span's local parameter back to
/// u ([`super::bernstein::SpanPoly::to_u`], and the local refinement of `bezier`).
///
/// Rounding: every operation is in outward-rounded interval arithmetic, so `len` encloses
/// the exact b - a (its upper bound is +inf if b - a overflows), a + t0 len encloses the
/// exact u(t0) and its lower bound is <= u(t0); likewise the upper bound of a + t1 len is at
/// least u(t1). As u is increasing, [lo, hi] contains u([t0, t1]). Clamping to [a, b] loses
/// nothing, as u(t) is in [a, b] for t in [0, 1], and keeps the box inside the closed span
/// (where the span's piece is the curve).
pub(crate) fn local_to_u(a: f64, b: f64, t0: f64, t1: f64) -> (f64, f64) {
    let len = iv::point(b) - iv::point(a);
    let lo = (iv::point(a) + iv::point(t0) * len).inf();
    let hi = (iv::point(a) + iv::point(t1) * len).sup();
    (lo.clamp(a, b), hi.clamp(a, b))
}

/// The box [t0, t1] of the local parameter t = (u - a) / (b - a) of the span [a, b] that
/// contains t(u) for every u in [u0, u1] inside [a, b]: outward-rounded interval quotients
/// (monotone in u), clamped to [0, 1] (t(u) lies there); [0, 1] itself where a quotient is not
/// finite (b - a overflows or is subnormal-small), which contains every t.
pub(crate) fn u_to_local(a: f64, b: f64, u0: f64, u1: f64) -> (f64, f64) {
    let len = iv::point(b) - iv::point(a);
    let t0 = if u0 <= a {
        0.0
    } else {
        ((iv::point(u0) - iv::point(a)) / len).inf()
    };
    let t1 = if u1 >= b {
        1.0
    } else {
        ((iv::point(u1) - iv::point(a)) / len).sup()
    };
    if !(t0.is_finite() && t1.is_finite()) {
        return (0.0, 1.0);
    }
    (t0.clamp(0.0, 1.0), t1.clamp(0.0, 1.0))
}
