#![doc = include_str!("../README.md")]
#![warn(missing_docs)]

pub mod bezier_tools;
mod bspline;
mod curve;
pub mod enclose;
mod error;
mod eval;
pub mod families;
pub mod font;
pub mod interpolate;
pub mod knot_vectors;
mod knots;
mod refine;
pub mod report;
pub mod scalar;
pub mod tridiagonal;
pub mod validate;

pub use bspline::{basis_funs, BezierSeg, HSpline};
pub use curve::NurbsCurve;
pub use enclose::{
    BoxEncloser, CandidateKind, CoordBox, Enclosure, Extremum, Guarantee, Stats, Termination,
};
pub use error::{CurveError, EvalError};
pub use eval::{project, CurveEval};
pub use knots::{find_span, multiplicity};
pub use scalar::Scalar;
