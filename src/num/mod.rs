//! Number types: the [`Scalar`] trait every kernel is generic over, and the verified types
//! beside [`inari::Interval`]: [`Ddi`] (rigorous double-double intervals), [`Mr`] (rigorous
//! midpoint-radius f64) and [`Exact`] (exact rationals, for the optimality certificates).
//!
//! `scalar` holds the trait and its f64 / interval / MPFR instances; `ddi` and `mr` define the
//! semantics of their types on top of error-free transformations and directed error bounds.

pub mod ddi;
pub(crate) mod dw;
pub mod exact;
pub(crate) mod ffint;
pub mod mr;
mod poly;
pub(crate) mod pool;
mod scalar;
pub(crate) mod sturm;

pub use ddi::Ddi;
pub use exact::Exact;
pub use mr::Mr;
pub(crate) use poly::binom_small;
pub use poly::{binom, binom_exact, binom_s, binomials, binomials_s, horner};
pub use scalar::*;
