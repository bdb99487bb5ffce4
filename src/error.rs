//! Typed errors. Invalid input is always an error value, never a panic and never a wrong box.

use thiserror::Error;

/// Why a curve description is not a valid NURBS curve (see `docs/formats.md`).
///
/// Every variant names the field and, where it applies, the position.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum CurveError {
    /// `degree` must be an integer >= 1.
    #[error("degree: expected an integer >= 1, got {0}")]
    InvalidDegree(u64),
    /// Fewer than p + 1 control points.
    #[error("control_points: a curve of degree {degree} needs at least {needed} control points, got {got}")]
    TooFewControlPoints {
        /// the degree p
        degree: usize,
        /// p + 1
        needed: usize,
        /// number given
        got: usize,
    },
    /// Control points of dimension 0.
    #[error("control_points[{index}]: a point needs at least one coordinate")]
    ZeroDimension {
        /// the first empty point
        index: usize,
    },
    /// Points of different dimensions.
    #[error(
        "control_points[{index}]: has {got} coordinates, but control_points[0] has {expected}"
    )]
    DimensionMismatch {
        /// position of the offending point
        index: usize,
        /// dimension of point 0
        expected: usize,
        /// dimension of this point
        got: usize,
    },
    /// NaN or infinite coordinate.
    #[error("control_points[{index}][{coord}]: expected a finite number, got {value}")]
    NonFiniteCoordinate {
        /// point index
        index: usize,
        /// coordinate index
        coord: usize,
        /// the value
        value: f64,
    },
    /// Wrong knot count.
    #[error("knots: expected {expected} knots (control points + degree + 1), got {got}")]
    KnotCount {
        /// n + p + 2
        expected: usize,
        /// number given
        got: usize,
    },
    /// NaN or infinite knot.
    #[error("knots[{index}]: expected a finite number, got {value}")]
    NonFiniteKnot {
        /// knot index
        index: usize,
        /// the value
        value: f64,
    },
    /// Knots decrease.
    #[error("knots[{index}]: knots must be non-decreasing, but {value} < knots[{}] = {previous}", index - 1)]
    DecreasingKnots {
        /// index of the smaller knot
        index: usize,
        /// its value
        value: f64,
        /// the knot before it
        previous: f64,
    },
    /// A knot repeated more than p + 1 times.
    #[error("knots[{index}]: the value {value} is repeated {multiplicity} times, at most degree + 1 = {max} allowed")]
    KnotMultiplicity {
        /// first index of the run
        index: usize,
        /// the repeated value
        value: f64,
        /// its multiplicity
        multiplicity: usize,
        /// p + 1
        max: usize,
    },
    /// Wrong weight count.
    #[error("weights: expected one weight per control point ({expected}), got {got}")]
    WeightCount {
        /// number of control points
        expected: usize,
        /// number of weights
        got: usize,
    },
    /// Non-positive, NaN or infinite weight.
    #[error("weights[{index}]: expected a finite number > 0, got {value}")]
    InvalidWeight {
        /// weight index
        index: usize,
        /// the value
        value: f64,
    },
    /// The domain [u_p, u_{n+1}] has zero length.
    #[error("knots: the parameter domain [knots[{p}], knots[{}]] = [{start}, {end}] is empty", n + 1)]
    EmptyDomain {
        /// the degree (index of the first domain knot)
        p: usize,
        /// index of the last control point
        n: usize,
        /// u_p
        start: f64,
        /// u_{n+1}
        end: f64,
    },
}

impl CurveError {
    /// A short machine-readable kind, used in JSON error records.
    pub fn kind(&self) -> &'static str {
        match self {
            CurveError::InvalidDegree(_) => "invalid_degree",
            CurveError::TooFewControlPoints { .. } => "too_few_control_points",
            CurveError::ZeroDimension { .. } => "zero_dimension",
            CurveError::DimensionMismatch { .. } => "dimension_mismatch",
            CurveError::NonFiniteCoordinate { .. } => "non_finite_coordinate",
            CurveError::KnotCount { .. } => "knot_count",
            CurveError::NonFiniteKnot { .. } => "non_finite_knot",
            CurveError::DecreasingKnots { .. } => "decreasing_knots",
            CurveError::KnotMultiplicity { .. } => "knot_multiplicity",
            CurveError::WeightCount { .. } => "weight_count",
            CurveError::InvalidWeight { .. } => "invalid_weight",
            CurveError::EmptyDomain { .. } => "empty_domain",
        }
    }
}

/// Errors of evaluation requests on a valid curve.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum EvalError {
    /// Parameter outside [u_p, u_{n+1}] (or NaN).
    #[error("param: {param} is outside the curve's domain [{start}, {end}]")]
    ParamOutOfDomain {
        /// the requested parameter
        param: f64,
        /// domain start
        start: f64,
        /// domain end
        end: f64,
    },
}

impl EvalError {
    /// A short machine-readable kind, used in JSON error records.
    pub fn kind(&self) -> &'static str {
        match self {
            EvalError::ParamOutOfDomain { .. } => "param_out_of_domain",
        }
    }
}
