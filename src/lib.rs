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

pub mod build;
pub mod enclose;
mod error;
#[cfg(feature = "font")]
pub mod font;
pub mod io;
pub mod num;
#[cfg(feature = "serve")]
pub mod serve;
pub mod spline;
pub mod surface;
#[cfg(feature = "testkit")]
pub mod testkit;

pub use enclose::{
    all_strategies, strategy_by_name, BoxEncloser, CandidateKind, CoordBox, Enclosure, Extremum,
    Guarantee, Stats, Termination,
};
pub use error::{CurveError, EvalError};
pub use io::{curve_to_json, parse_curve, CurveReader, InputError};
pub use num::{Ddi, Mr, Scalar};
pub use spline::{
    basis_funs, find_span, multiplicity, project, BezierSeg, CurveEval, HSpline, NurbsCurve,
    TightEval,
};
pub use surface::{NurbsSurface, SurfaceEncloser, SurfaceError};
