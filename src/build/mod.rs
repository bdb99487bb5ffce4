//! Construction tools that make curves: cubic spline interpolation through points (with its
//! tridiagonal solver and the interpolation knot vectors), Lagrange interpolation curves, and
//! conversions between the Bézier, monomial and Hermite forms.

pub mod bezier_tools;
pub mod interpolate;
pub mod knot_vectors;
pub mod lagrange;
pub mod tridiagonal;
