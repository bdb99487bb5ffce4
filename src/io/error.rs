//! Error types of the input side: [`InputError`] (what is wrong with one record, and where) and
//! [`Position`] (line and column in the input).

use crate::error::CurveError;
use crate::surface::SurfaceError;
use std::fmt;
use thiserror::Error;

/// A place in the input stream: 1-based line and byte column.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Position {
    /// line number, from 1
    pub line: u64,
    /// byte column, from 1
    pub column: u64,
}

impl fmt::Display for Position {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}, column {}", self.line, self.column)
    }
}

/// Why one input record could not be turned into a curve.
///
/// Every variant says what is wrong and where: the field path (`knots[3]`,
/// `control_points[2][1]`, or `curve` for the record as a whole) and the position in the input.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum InputError {
    /// Not valid JSON (stray characters, binary junk, bad escapes, nesting too deep, ...).
    #[error("{path}: invalid JSON: {detail} ({at})")]
    Syntax {
        /// field path where the error was found
        path: String,
        /// position of the error
        at: Position,
        /// what the JSON parser expected, and what it found
        detail: String,
    },
    /// The record ends in the middle of a value.
    #[error("{path}: the input ends in the middle of the curve ({at}); is the JSON truncated?")]
    Truncated {
        /// the innermost open field
        path: String,
        /// where the input ends
        at: Position,
    },
    /// A number literal outside the finite f64 range (e.g. `1e400`).
    #[error("{path}: the number {literal} is outside the range of f64 (about ±1.8e308); curves must have finite values ({at})")]
    NumberOutOfRange {
        /// field path
        path: String,
        /// position
        at: Position,
        /// the literal as written (shortened if long)
        literal: String,
    },
    /// `NaN`, `Infinity` and the like are not JSON numbers.
    #[error("{path}: {token} is not a JSON number, and curves must have finite values ({at})")]
    NonFiniteLiteral {
        /// field path
        path: String,
        /// position
        at: Position,
        /// the token as written
        token: String,
    },
    /// A value of the wrong JSON type.
    #[error("{path}: expected {expected}, got {got} ({at})")]
    WrongType {
        /// field path
        path: String,
        /// position (just after the value)
        at: Position,
        /// what the format requires
        expected: &'static str,
        /// what was found
        got: String,
    },
    /// A required field is absent.
    #[error(
        "{field}: missing field; a curve needs \"degree\", \"knots\" and \"control_points\" ({at})"
    )]
    MissingField {
        /// the field
        field: &'static str,
        /// end of the curve object
        at: Position,
    },
    /// A required field of a surface is absent.
    #[error(
        "{field}: missing field; a surface needs \"degree_u\", \"degree_v\", \"knots_u\", \"knots_v\" and \"control_points\" ({at})"
    )]
    MissingSurfaceField {
        /// the field
        field: &'static str,
        /// end of the surface object
        at: Position,
    },
    /// A field of the other kind of object: a curve field in a surface (`degree`, `knots`) or
    /// the other way round.
    #[error("{field:?}: not a field of a {kind}; a surface has \"degree_u\", \"degree_v\", \"knots_u\", \"knots_v\", \"control_points\" and optional \"weights\", a curve \"degree\", \"knots\", \"control_points\" and optional \"weights\" ({at})")]
    MixedFields {
        /// the field name
        field: &'static str,
        /// `curve` or `surface`: what the object is (by its other fields)
        kind: &'static str,
        /// end of the object
        at: Position,
    },
    /// A field the format does not define (see
    /// [`ParseOptions::allow_unknown_fields`](super::ParseOptions::allow_unknown_fields)).
    #[error("{field:?}: unknown field; a curve has \"degree\", \"knots\", \"control_points\" and optional \"weights\" ({at})")]
    UnknownField {
        /// the field name (shortened if long)
        field: String,
        /// position
        at: Position,
    },
    /// A field given twice.
    #[error("{field}: the field appears twice ({at})")]
    DuplicateField {
        /// the field
        field: &'static str,
        /// position of the second occurrence
        at: Position,
    },
    /// `degree` is not a non-negative integer that fits the machine (negative, fractional,
    /// astronomically large). Zero and values too large for the control points are reported
    /// by the curve check ([`CurveError`]).
    #[error("{field}: expected an integer >= 1, got {got} ({at})")]
    InvalidDegree {
        /// the field (`degree`, `degree_u`, `degree_v`)
        field: &'static str,
        /// the value as written
        got: String,
        /// position
        at: Position,
    },
    /// A record longer than
    /// [`ParseOptions::max_record_bytes`](super::ParseOptions::max_record_bytes).
    #[error("curve: the record starting at {at} is longer than {limit} bytes; it was skipped")]
    TooLarge {
        /// the limit
        limit: usize,
        /// start of the record
        at: Position,
    },
    /// An empty element in the JSON array of curves (`[{...},,{...}]` or a trailing comma).
    #[error("curve: expected a curve object before the ',' or ']' ({at})")]
    EmptyElement {
        /// position of the stray comma or bracket
        at: Position,
    },
    /// The JSON array of curves is not closed.
    #[error("curve: the input ends before the closing ']' of the array of curves ({at}); is it truncated?")]
    UnclosedArray {
        /// end of the input
        at: Position,
    },
    /// Data after the closing `]` of the array of curves.
    #[error("curve: unexpected data after the closing ']' of the array of curves ({at})")]
    TrailingData {
        /// position of the first extra byte
        at: Position,
    },
    /// Reading the input failed (the stream stops here).
    #[error("cannot read the input: {0}")]
    Io(String),
    /// Well-formed JSON, but not a valid NURBS curve.
    #[error(transparent)]
    Curve(#[from] CurveError),
    /// Well-formed JSON, but not a valid NURBS surface.
    #[error(transparent)]
    Surface(#[from] SurfaceError),
}

impl InputError {
    /// A short machine-readable kind, used in JSON error records. For [`InputError::Curve`] it is
    /// the curve error's kind.
    pub fn kind(&self) -> &'static str {
        match self {
            InputError::Syntax { .. } => "invalid_json",
            InputError::Truncated { .. } => "truncated_json",
            InputError::NumberOutOfRange { .. } => "number_out_of_range",
            InputError::NonFiniteLiteral { .. } => "non_finite_literal",
            InputError::WrongType { .. } => "wrong_type",
            InputError::MissingField { .. } => "missing_field",
            InputError::UnknownField { .. } => "unknown_field",
            InputError::DuplicateField { .. } => "duplicate_field",
            InputError::InvalidDegree { .. } => "invalid_degree",
            InputError::TooLarge { .. } => "record_too_large",
            InputError::EmptyElement { .. } => "empty_element",
            InputError::UnclosedArray { .. } => "unclosed_array",
            InputError::TrailingData { .. } => "trailing_data",
            InputError::Io(_) => "io_error",
            InputError::Curve(e) => e.kind(),
            InputError::Surface(e) => e.kind(),
            InputError::MissingSurfaceField { .. } => "missing_field",
            InputError::MixedFields { .. } => "unknown_field",
        }
    }
}

/// At most `n` characters of `s`, with an ellipsis when cut (for names and literals quoted in
/// messages).
pub(super) fn shorten(s: &str, n: usize) -> String {
    match s.char_indices().nth(n) {
        Some((i, _)) => format!("{}...", &s[..i]),
        None => s.to_string(),
    }
}
