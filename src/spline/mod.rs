//! The spline core: the curve model and its validation, knots, the homogeneous B-spline
//! (de Boor corner cutting, derivatives, knot insertion, Bézier extraction), the Bézier
//! segment, point and derivative evaluation, refinement, the tight (~1 ulp) evaluator and knot
//! removal. Every kernel is written once, generic over [`crate::num::Scalar`].

pub(crate) mod bezier;
pub(crate) mod bspline;
pub(crate) mod curve;
pub(crate) mod eval;
pub(crate) mod fraction_free;
pub mod knot_removal;
pub(crate) mod knots;
pub(crate) mod refine;
pub(crate) mod tight;

pub use bezier::{
    bernstein_to_power, cartesian, de_casteljau_eval, de_casteljau_eval_in_place,
    de_casteljau_split, forward_differences, hodograph, power_from_differences,
};
pub use bspline::{basis_funs, knot_quotient, knot_ratio, BezierSeg, HSpline};
pub use curve::NurbsCurve;
pub use eval::{project, CurveEval};
pub use knots::{find_span, multiplicity};
pub use tight::TightEval;
