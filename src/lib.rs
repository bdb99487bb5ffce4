//! # nurbs-box
//!
//! Verified, optimal axis-aligned box enclosures of NURBS curves.
//!
//! A [`NurbsCurve`] of any degree and dimension is enclosed by a [`BoxEncloser`] strategy
//! (see [`enclose`]); the result says per coordinate what the outer bound is, what the curve
//! provably reaches (the inner bound), where the extrema are and what it cost. The kernels
//! (span search, basis functions, de Boor corner cutting, derivatives, knot insertion, Bézier
//! extraction, de Casteljau) are written once, generic over [`Scalar`]: `f64`,
//! [`inari::Interval`] with outward rounding, and `rug::Float` under the `mpfr` feature.
//!
//! Sources: the 2009 diploma thesis "Optimale Box-Einschließungen von NURBS Kurven"
//! (Universität Wien) and The NURBS Book (Piegl & Tiller); each algorithm cites its source, and
//! `docs/sources.md` in the repository maps every algorithm to its citation. The JSON formats and
//! the command-line contract: `docs/formats.md`.
//!
#![doc = include_str!("guarantees.md")]
#![warn(missing_docs)]

pub mod batch;
pub mod bezier_tools;
mod bspline;
mod curve;
mod ddi;
pub mod enclose;
mod error;
mod eval;
pub mod families;
pub mod font;
pub mod gen;
pub mod interpolate;
pub mod io;
pub mod knot_removal;
pub mod knot_vectors;
mod knots;
pub mod lagrange;
mod mr;
#[cfg(feature = "mpfr")]
pub mod reference;
mod refine;
pub mod report;
pub mod robust;
pub mod scalar;
#[cfg(feature = "serve")]
pub mod serve;
mod tight;
pub mod tridiagonal;
pub mod validate;

pub use bspline::{basis_funs, BezierSeg, HSpline};
pub use curve::NurbsCurve;
pub use ddi::Ddi;
pub use enclose::{
    all_strategies, strategy_by_name, strategy_with_work, BoxEncloser, CandidateKind, CoordBox,
    Enclosure, Extremum, Guarantee, Stats, Termination,
};
pub use error::{CurveError, EvalError};
pub use eval::{project, CurveEval};
pub use io::{curve_to_json, parse_curve, CurveReader, InputError};
pub use knots::{find_span, multiplicity};
pub use mr::Mr;
pub use scalar::Scalar;
pub use tight::TightEval;
