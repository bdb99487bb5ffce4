//! NURBS surfaces (tensor products, thesis def. 2.2 and 3.2): the model and its validation,
//! evaluation of points and partial derivatives generic over [`crate::num::Scalar`], Bézier
//! patches, and the verified box strategies for surfaces ([`enclose`]).
//!
//! The curve kernels do the work: a net is handled as a curve in u whose control points are
//! the rows, so de Boor, derivative control points, knot insertion, Bézier extraction and de
//! Casteljau are the curve's own code ([`eval`]); a clamped boundary row and a knot line of
//! multiplicity >= the degree are exactly [`crate::NurbsCurve`]s
//! ([`NurbsSurface::row_curve`], [`NurbsSurface::exact_row_at`]), enclosed by the curve
//! strategies themselves.

pub mod enclose;
pub mod eval;
pub mod gen;
mod model;

pub use enclose::{
    surface_strategy_by_name, surface_strategy_with, SurfaceEncloser, SURFACE_STRATEGY_NAMES,
};
pub use eval::{Net, Patch, SurfaceEval};
pub use model::{Dir, NurbsSurface, SurfaceError};
