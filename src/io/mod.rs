//! The JSON curve format and the record formats of the command line (`docs/formats.md`).
//!
//! * [`parse_curve`] turns one JSON object into a validated
//!   [`NurbsCurve`](crate::spline::curve::NurbsCurve), or into an
//!   [`InputError`] that names the field and position (`knots[3]: expected a number, got a
//!   string "x" (line 1, column 40)`).
//! * [`parse_record`] does the same for the records of a mixed stream: a curve or a
//!   [`NurbsSurface`](crate::surface::NurbsSurface) (an object with `degree_u`), as a
//!   [`Shape`].
//! * [`RecordReader`] splits a stream (a file or stdin) into the raw bytes of one curve each, in
//!   bounded memory, for both stream forms (JSON Lines, or one JSON array of curves);
//!   [`CurveReader`] also parses them.
//! * [`curve_to_json`] writes a curve back; `write_*_record` write the output records.
//!
//! # Parsing rules
//!
//! Numbers are parsed by serde_json with its `float_roundtrip` feature, i.e. correctly rounded to
//! the nearest f64 (integer literals beyond 2^64 too). A literal that overflows f64 (`1e400`) is
//! an error, never infinity; `NaN` / `Infinity` tokens are not JSON and are reported as such; the
//! string `"NaN"` where a number belongs is a type error. `degree` must be an integer (an
//! integral float such as `3.0` is accepted); `weights` may be absent or `null`.
//!
//! Unknown fields are **rejected** by default (a misspelt `"weight"` would otherwise silently
//! turn a rational curve into a polynomial one, and its box would be right for the wrong curve);
//! [`ParseOptions::allow_unknown_fields`] ignores them instead. Duplicate fields are rejected.
//!
//! Nothing is allocated in proportion to a *value* in the input (a degree of 10^9 costs
//! nothing); memory is proportional to the record's length, and a record longer than
//! [`ParseOptions::max_record_bytes`] is skipped with an error. Nesting deeper than serde_json's
//! recursion limit (128) is an error, not a stack overflow.
//!
//! # Layout
//!
//! * [`error`]: [`InputError`] and [`Position`].
//! * [`parse`]: [`parse_curve`] and [`ParseOptions`] (serde visitors that know their field
//!   path).
//! * `position` (internal): where an error is (line, column and field path), found by
//!   scanning the record.
//! * [`stream`]: [`RecordReader`] and [`CurveReader`] (JSON Lines or one array of curves).
//! * [`records`]: [`curve_to_json`] and the output records, with their number formatting.
//! * `batch` (feature `parallel`): many curves at once, on all cores.
//!
//! Every item is also re-exported here, so `nurbs_box::io::parse_curve` and the like are the
//! paths to use. The two byte scanners (field paths in `position`, array elements in `stream`)
//! share one lexer, `scan::Lexer`, for strings and escapes.

#[cfg(feature = "parallel")]
pub mod batch;
pub mod error;
pub mod parse;
mod position;
pub mod records;
mod scan;
pub mod stream;

pub use error::{InputError, Position};
pub use parse::{parse_curve, parse_curve_at, parse_record, parse_record_at, ParseOptions, Shape};
pub use records::{
    curve_to_json, eval_fields, surface_eval_fields, termination_name, write_curve,
    write_enclosure_record, write_error_record, write_eval_record, write_num, write_nums,
    write_str, write_surface_eval_record,
};
pub use stream::{read_curves, CurveReader, RawRecord, RecordReader, StreamForm};
