//! The JSON curve format and the record formats of the command line (`docs/formats.md`).
//!
//! * [`parse_curve`] turns one JSON object into a validated [`NurbsCurve`], or into an
//!   [`InputError`] that names the field and position (`knots[3]: expected a number, got a
//!   string "x" (line 1, column 40)`).
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

#[cfg(feature = "parallel")]
pub mod batch;

use crate::enclose::{Enclosure, Termination};
use crate::error::CurveError;
use crate::spline::curve::NurbsCurve;
use inari::Interval;
use serde::de::{self, DeserializeSeed, IgnoredAny, MapAccess, SeqAccess, Visitor};
use std::cell::RefCell;
use std::fmt;
use std::io::{self, BufRead, BufReader, Read};
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
    /// A field the format does not define (see [`ParseOptions::allow_unknown_fields`]).
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
    #[error("degree: expected an integer >= 1, got {got} ({at})")]
    InvalidDegree {
        /// the value as written
        got: String,
        /// position
        at: Position,
    },
    /// A record longer than [`ParseOptions::max_record_bytes`].
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
        }
    }
}

/// Options of the curve parser.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ParseOptions {
    /// Ignore fields other than degree / knots / control_points / weights (default: reject).
    pub allow_unknown_fields: bool,
    /// Longest record accepted, in bytes (default 256 MiB); longer ones are skipped with
    /// [`InputError::TooLarge`]. Bounds the reader's memory.
    pub max_record_bytes: usize,
}

impl Default for ParseOptions {
    fn default() -> Self {
        ParseOptions {
            allow_unknown_fields: false,
            max_record_bytes: 256 << 20,
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Parsing one curve: serde visitors that know their field path.
//
// A visitor that rejects a value stores a structured error in a shared slot and returns a
// placeholder serde error; serde_json attaches the position to the placeholder, and
// `convert_error` joins the two.

/// Where a value sits in the curve object.
#[derive(Debug, Clone, Copy)]
enum Loc {
    Curve,
    Field(&'static str),
    Elem(&'static str, usize),
    Coord(usize, usize),
}

impl fmt::Display for Loc {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Loc::Curve => f.write_str("curve"),
            Loc::Field(s) => f.write_str(s),
            Loc::Elem(s, i) => write!(f, "{s}[{i}]"),
            Loc::Coord(i, j) => write!(f, "control_points[{i}][{j}]"),
        }
    }
}

/// An error found by a visitor, still without a position.
enum DataErr {
    WrongType {
        path: String,
        expected: &'static str,
        got: String,
    },
    Missing(&'static str),
    Unknown(String),
    Duplicate(&'static str),
    Degree(String),
}

type Slot<'a> = &'a RefCell<Option<DataErr>>;

fn fail<E: de::Error>(slot: Slot<'_>, e: DataErr) -> E {
    *slot.borrow_mut() = Some(e);
    E::custom("invalid curve")
}

/// At most `n` characters of `s`, with an ellipsis when cut.
fn shorten(s: &str, n: usize) -> String {
    match s.char_indices().nth(n) {
        Some((i, _)) => format!("{}...", &s[..i]),
        None => s.to_string(),
    }
}

fn wrong<E: de::Error>(slot: Slot<'_>, loc: Loc, expected: &'static str, got: String) -> E {
    fail(
        slot,
        DataErr::WrongType {
            path: loc.to_string(),
            expected,
            got,
        },
    )
}

/// The visitor methods for values of a type the visitor does not accept: each reports
/// `expected X, got <what was found>`.
macro_rules! reject_scalars {
    ($($method:ident($ty:ty) => $got:expr;)*) => {
        $(fn $method<E: de::Error>(self, v: $ty) -> Result<Self::Value, E> {
            #[allow(clippy::redundant_closure_call)]
            let got: String = ($got)(v);
            Err(wrong(self.slot, self.loc, self.expected(), got))
        })*
    };
}

/// Visitor methods for the JSON types a visitor does not accept (`reject!(text, unit, ...)`),
/// plus `expecting` from the visitor's `expected()`.
macro_rules! reject {
    ($($what:ident),*) => {
        fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            f.write_str(self.expected())
        }
        $(reject!(@ $what);)*
    };
    (@text) => {
        reject_scalars! {
            visit_bool(bool) => |v| format!("the boolean {v}");
            visit_str(&str) => |v: &str| format!("a string {:?}", shorten(v, 40));
        }
    };
    (@numbers) => {
        reject_scalars! {
            visit_u64(u64) => |v| format!("the number {v}");
            visit_i64(i64) => |v| format!("the number {v}");
            visit_f64(f64) => |v| format!("the number {v}");
        }
    };
    (@unit) => {
        fn visit_unit<E: de::Error>(self) -> Result<Self::Value, E> {
            Err(wrong(self.slot, self.loc, self.expected(), "null".into()))
        }
    };
    (@map) => {
        fn visit_map<A: MapAccess<'de>>(self, _: A) -> Result<Self::Value, A::Error> {
            Err(wrong(self.slot, self.loc, self.expected(), "an object".into()))
        }
    };
    (@seq) => {
        fn visit_seq<A: SeqAccess<'de>>(self, _: A) -> Result<Self::Value, A::Error> {
            Err(wrong(self.slot, self.loc, self.expected(), "an array".into()))
        }
    };
}

/// A `DeserializeSeed` that lets the visitor itself see any JSON value (so that it can name
/// what it got when the type is wrong).
macro_rules! seed_via_any {
    ($t:ident, $v:ty) => {
        impl<'de> DeserializeSeed<'de> for $t<'_> {
            type Value = $v;
            fn deserialize<D: de::Deserializer<'de>>(self, d: D) -> Result<$v, D::Error> {
                d.deserialize_any(self)
            }
        }
    };
    ($(#[$doc:meta])* $t:ident -> $v:ty, $expected:expr) => {
        $(#[$doc])*
        struct $t<'a> {
            slot: Slot<'a>,
            loc: Loc,
        }
        impl $t<'_> {
            fn expected(&self) -> &'static str {
                $expected
            }
        }
        seed_via_any!($t, $v);
    };
}

seed_via_any! {
    /// One finite number (serde_json never yields a non-finite f64: overflow is a syntax error).
    Num -> f64, "a number"
}

impl<'de> Visitor<'de> for Num<'_> {
    type Value = f64;
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<f64, E> {
        Ok(v)
    }
    // `as` rounds an integer to the nearest f64 (ties to even): the correctly rounded value.
    fn visit_u64<E: de::Error>(self, v: u64) -> Result<f64, E> {
        Ok(v as f64)
    }
    fn visit_i64<E: de::Error>(self, v: i64) -> Result<f64, E> {
        Ok(v as f64)
    }
    reject!(text, unit, map, seq);
}

/// An array of numbers (`knots`, `weights`, one control point). `nullable`: `null` means absent.
struct Nums<'a> {
    slot: Slot<'a>,
    loc: Loc,
    nullable: bool,
}

impl Nums<'_> {
    fn expected(&self) -> &'static str {
        match self.loc {
            Loc::Elem("control_points", _) => "an array of coordinates (numbers)",
            _ => "an array of numbers",
        }
    }
    /// The location of element i.
    fn elem(&self, i: usize) -> Loc {
        match self.loc {
            Loc::Field(f) => Loc::Elem(f, i),
            Loc::Elem(_, k) => Loc::Coord(k, i),
            other => other,
        }
    }
}

seed_via_any!(Nums, Option<Vec<f64>>);

impl<'de> Visitor<'de> for Nums<'_> {
    type Value = Option<Vec<f64>>;
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        // No preallocation from size hints: memory grows with the elements actually present.
        let mut v = Vec::new();
        while let Some(x) = seq.next_element_seed(Num {
            slot: self.slot,
            loc: self.elem(v.len()),
        })? {
            v.push(x);
        }
        Ok(Some(v))
    }
    fn visit_unit<E: de::Error>(self) -> Result<Self::Value, E> {
        if self.nullable {
            Ok(None)
        } else {
            Err(wrong(self.slot, self.loc, self.expected(), "null".into()))
        }
    }
    reject!(text, map, numbers);
}

seed_via_any! {
    /// `control_points`: an array of arrays of numbers.
    Points -> Vec<Vec<f64>>, "an array of points (arrays of numbers)"
}

impl<'de> Visitor<'de> for Points<'_> {
    type Value = Vec<Vec<f64>>;
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        let mut v = Vec::new();
        while let Some(p) = seq.next_element_seed(Nums {
            slot: self.slot,
            loc: Loc::Elem("control_points", v.len()),
            nullable: false,
        })? {
            v.push(p.unwrap_or_default());
        }
        Ok(v)
    }
    reject!(text, unit, map, numbers);
}

seed_via_any! {
    /// `degree`: a non-negative integer (an integral float is accepted).
    Degree -> usize, "an integer >= 1"
}

impl<'de> Visitor<'de> for Degree<'_> {
    type Value = usize;
    fn visit_u64<E: de::Error>(self, v: u64) -> Result<usize, E> {
        usize::try_from(v).map_err(|_| fail(self.slot, DataErr::Degree(v.to_string())))
    }
    fn visit_i64<E: de::Error>(self, v: i64) -> Result<usize, E> {
        usize::try_from(v).map_err(|_| fail(self.slot, DataErr::Degree(v.to_string())))
    }
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<usize, E> {
        // Exact: an integral f64 below 2^53 converts without rounding; larger ones are
        // rejected rather than truncated.
        if v.fract() == 0.0 && (0.0..9007199254740992.0).contains(&v) {
            self.visit_u64(v as u64)
        } else {
            Err(fail(self.slot, DataErr::Degree(v.to_string())))
        }
    }
    reject!(text, unit, map, seq);
}

/// A key of the curve object.
enum Key {
    Degree,
    Knots,
    ControlPoints,
    Weights,
    Other(String),
}

struct KeySeed;

impl<'de> DeserializeSeed<'de> for KeySeed {
    type Value = Key;
    fn deserialize<D: de::Deserializer<'de>>(self, d: D) -> Result<Key, D::Error> {
        d.deserialize_str(self)
    }
}

impl<'de> Visitor<'de> for KeySeed {
    type Value = Key;
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a field name")
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<Key, E> {
        Ok(match v {
            "degree" => Key::Degree,
            "knots" => Key::Knots,
            "control_points" => Key::ControlPoints,
            "weights" => Key::Weights,
            other => Key::Other(shorten(other, 40)),
        })
    }
}

/// The fields of a curve object, before validation.
struct RawCurve {
    degree: usize,
    knots: Vec<f64>,
    control_points: Vec<Vec<f64>>,
    weights: Option<Vec<f64>>,
}

struct CurveSeed<'a> {
    slot: Slot<'a>,
    loc: Loc,
    allow_unknown: bool,
}

impl CurveSeed<'_> {
    fn expected(&self) -> &'static str {
        "a curve object {\"degree\": ..., \"knots\": [...], \"control_points\": [...]}"
    }
}

seed_via_any!(CurveSeed, RawCurve);

impl<'de> Visitor<'de> for CurveSeed<'_> {
    type Value = RawCurve;
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<RawCurve, A::Error> {
        let slot = self.slot;
        let (mut degree, mut knots, mut points, mut weights) = (None, None, None, None);
        fn once<T, E: de::Error>(
            slot: Slot<'_>,
            dst: &mut Option<T>,
            name: &'static str,
            v: T,
        ) -> Result<(), E> {
            if dst.is_some() {
                return Err(fail(slot, DataErr::Duplicate(name)));
            }
            *dst = Some(v);
            Ok(())
        }
        while let Some(key) = map.next_key_seed(KeySeed)? {
            match key {
                Key::Degree => {
                    let loc = Loc::Field("degree");
                    once(
                        slot,
                        &mut degree,
                        "degree",
                        map.next_value_seed(Degree { slot, loc })?,
                    )?
                }
                Key::Knots => {
                    let seed = Nums {
                        slot,
                        loc: Loc::Field("knots"),
                        nullable: false,
                    };
                    let v = map.next_value_seed(seed)?.unwrap_or_default();
                    once(slot, &mut knots, "knots", v)?
                }
                Key::ControlPoints => {
                    let loc = Loc::Field("control_points");
                    let v = map.next_value_seed(Points { slot, loc })?;
                    once(slot, &mut points, "control_points", v)?
                }
                Key::Weights => {
                    let seed = Nums {
                        slot,
                        loc: Loc::Field("weights"),
                        nullable: true,
                    };
                    let v = map.next_value_seed(seed)?;
                    once(slot, &mut weights, "weights", v)?
                }
                Key::Other(name) => {
                    if !self.allow_unknown {
                        return Err(fail(slot, DataErr::Unknown(name)));
                    }
                    map.next_value::<IgnoredAny>()?;
                }
            }
        }
        let missing = |f| fail::<A::Error>(slot, DataErr::Missing(f));
        Ok(RawCurve {
            degree: degree.ok_or_else(|| missing("degree"))?,
            knots: knots.ok_or_else(|| missing("knots"))?,
            control_points: points.ok_or_else(|| missing("control_points"))?,
            weights: weights.flatten(),
        })
    }
    reject!(text, unit, numbers, seq);
}

/// Parse one curve object (the whole of `bytes`, surrounding whitespace allowed) and validate it.
///
/// Positions in errors count from line 1, column 1 of `bytes`.
pub fn parse_curve(bytes: &[u8]) -> Result<NurbsCurve, InputError> {
    parse_curve_at(
        bytes,
        Position { line: 1, column: 1 },
        &ParseOptions::default(),
    )
}

/// [`parse_curve`] for a record that starts at `start` of a larger input, with options.
pub fn parse_curve_at(
    bytes: &[u8],
    start: Position,
    opts: &ParseOptions,
) -> Result<NurbsCurve, InputError> {
    let slot = RefCell::new(None);
    let mut de = serde_json::Deserializer::from_slice(bytes);
    let seed = CurveSeed {
        slot: &slot,
        loc: Loc::Curve,
        allow_unknown: opts.allow_unknown_fields,
    };
    let raw = seed
        .deserialize(&mut de)
        .and_then(|raw| de.end().map(|()| raw))
        .map_err(|e| convert_error(bytes, start, &e, slot.take()))?;
    Ok(NurbsCurve::new(
        raw.degree,
        raw.knots,
        raw.control_points,
        raw.weights,
    )?)
}

/// Byte offset of serde_json's (line, column) in `bytes` (column = bytes since the line start).
fn offset_of(bytes: &[u8], line: usize, column: usize) -> usize {
    let mut start = 0;
    if line > 1 {
        if let Some((i, _)) = bytes
            .iter()
            .enumerate()
            .filter(|(_, &b)| b == b'\n')
            .nth(line - 2)
        {
            start = i + 1;
        }
    }
    (start + column).min(bytes.len())
}

/// Absolute position of byte `off` of a record starting at `start`.
fn abs_position(bytes: &[u8], start: Position, off: usize) -> Position {
    let before = &bytes[..off.min(bytes.len())];
    match before.iter().rposition(|&b| b == b'\n') {
        None => Position {
            line: start.line,
            column: start.column + off as u64,
        },
        Some(nl) => Position {
            line: start.line + before.iter().filter(|&&b| b == b'\n').count() as u64,
            column: (off - nl) as u64,
        },
    }
}

/// Field path (`knots[3]`, `control_points[1][0]`, `curve`) of byte `off`, found by scanning the
/// JSON structure before it (strings and escapes tracked; no recursion, any depth).
fn path_at(bytes: &[u8], off: usize) -> String {
    enum Frame {
        Obj {
            key: Option<(usize, usize)>,
            in_value: bool,
        },
        Arr {
            index: usize,
        },
    }
    let mut stack: Vec<Frame> = Vec::new();
    let (mut in_str, mut esc, mut str_start) = (false, false, 0);
    for (i, &b) in bytes[..off.min(bytes.len())].iter().enumerate() {
        if in_str {
            if esc {
                esc = false;
            } else if b == b'\\' {
                esc = true;
            } else if b == b'"' {
                in_str = false;
                if let Some(Frame::Obj {
                    key,
                    in_value: false,
                }) = stack.last_mut()
                {
                    *key = Some((str_start, i));
                }
            }
            continue;
        }
        match b {
            b'"' => {
                in_str = true;
                str_start = i + 1;
            }
            b'{' => stack.push(Frame::Obj {
                key: None,
                in_value: false,
            }),
            b'[' => stack.push(Frame::Arr { index: 0 }),
            b'}' | b']' => {
                stack.pop();
            }
            b':' => {
                if let Some(Frame::Obj { in_value, .. }) = stack.last_mut() {
                    *in_value = true;
                }
            }
            b',' => match stack.last_mut() {
                Some(Frame::Arr { index }) => *index += 1,
                Some(Frame::Obj { key, in_value }) => {
                    *key = None;
                    *in_value = false;
                }
                None => {}
            },
            _ => {}
        }
    }
    let mut path = String::new();
    for (depth, f) in stack.iter().enumerate() {
        if depth == 8 {
            path.push_str("...");
            break;
        }
        match f {
            Frame::Obj {
                key: Some((a, b)), ..
            } => {
                if depth > 0 {
                    path.push('.');
                }
                path.push_str(&shorten(&String::from_utf8_lossy(&bytes[*a..*b]), 40));
            }
            Frame::Obj { .. } => break,
            Frame::Arr { index } => {
                if depth == 0 {
                    path.push_str("curve");
                }
                path.push_str(&format!("[{index}]"));
            }
        }
    }
    if path.is_empty() {
        path.push_str("curve");
    }
    path
}

/// The token around byte `i` made of bytes satisfying `f`.
fn token_at(bytes: &[u8], i: usize, f: impl Fn(u8) -> bool) -> &[u8] {
    if i >= bytes.len() || !f(bytes[i]) {
        return &[];
    }
    let a = bytes[..i].iter().rposition(|&b| !f(b)).map_or(0, |k| k + 1);
    let b = bytes[i..]
        .iter()
        .position(|&b| !f(b))
        .map_or(bytes.len(), |k| i + k);
    &bytes[a..b]
}

/// What byte `i` is, for messages.
fn describe_byte(bytes: &[u8], i: usize) -> String {
    match bytes.get(i) {
        None => "the end of the input".into(),
        Some(&b) if b.is_ascii_graphic() => format!("'{}'", b as char),
        Some(&b) => format!("the byte 0x{b:02x}"),
    }
}

/// Turn a serde_json error (plus the visitor's structured error, if any) into an [`InputError`].
fn convert_error(
    bytes: &[u8],
    start: Position,
    e: &serde_json::Error,
    data: Option<DataErr>,
) -> InputError {
    use serde_json::error::Category;
    // serde_json's column is the byte count from the line start to the index just after the
    // offending byte (see its `position_of_index`), so the culprit is at offset - 1.
    let off = offset_of(bytes, e.line(), e.column());
    let culprit = off.saturating_sub(1);
    let at = abs_position(bytes, start, culprit);
    if let Some(d) = data {
        return match d {
            DataErr::WrongType {
                path,
                expected,
                got,
            } => InputError::WrongType {
                path,
                at,
                expected,
                got,
            },
            DataErr::Missing(field) => InputError::MissingField { field, at },
            DataErr::Unknown(field) => InputError::UnknownField { field, at },
            DataErr::Duplicate(field) => InputError::DuplicateField { field, at },
            DataErr::Degree(got) => InputError::InvalidDegree { got, at },
        };
    }
    let msg = e.to_string();
    let detail = msg
        .strip_suffix(&format!(" at line {} column {}", e.line(), e.column()))
        .unwrap_or(&msg)
        .to_string();
    if e.classify() == Category::Eof {
        return InputError::Truncated {
            path: path_at(bytes, bytes.len()),
            at: abs_position(bytes, start, bytes.len()),
        };
    }
    let path = path_at(bytes, culprit);
    if detail.starts_with("number out of range") {
        let lit = token_at(bytes, culprit, |b| {
            b.is_ascii_digit() || matches!(b, b'e' | b'E' | b'+' | b'-' | b'.')
        });
        return InputError::NumberOutOfRange {
            path,
            at,
            literal: shorten(&String::from_utf8_lossy(lit), 40),
        };
    }
    let word = token_at(bytes, culprit, |b| {
        b.is_ascii_alphanumeric() || matches!(b, b'+' | b'-' | b'.')
    });
    let bare = String::from_utf8_lossy(word).to_ascii_lowercase();
    let bare = bare.trim_start_matches(['+', '-']);
    if matches!(bare, "nan" | "inf" | "infinity") {
        return InputError::NonFiniteLiteral {
            path,
            at,
            token: shorten(&String::from_utf8_lossy(word), 40),
        };
    }
    InputError::Syntax {
        path,
        at,
        detail: format!("{detail}, found {}", describe_byte(bytes, culprit)),
    }
}

// ---------------------------------------------------------------------------------------------
// Streams.

/// The two stream forms of `docs/formats.md`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StreamForm {
    /// one curve per line (blank lines skipped)
    JsonLines,
    /// one JSON array of curves
    Array,
}

/// The raw bytes of one input record (one curve), with its index and start position.
#[derive(Debug, Clone, PartialEq)]
pub struct RawRecord {
    /// curve index, from 0, in input order
    pub index: usize,
    /// where the record starts in the input
    pub start: Position,
    /// the record's bytes, or why there are none (too large, empty array element, ...)
    pub bytes: Result<Vec<u8>, InputError>,
}

impl RawRecord {
    /// Parse and validate the record.
    pub fn parse(&self, opts: &ParseOptions) -> Result<NurbsCurve, InputError> {
        match &self.bytes {
            Ok(b) => parse_curve_at(b, self.start, opts),
            Err(e) => Err(e.clone()),
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    Start,
    Lines,
    /// inside the array; `need_sep`: an element was just read
    Array {
        need_sep: bool,
        after_comma: bool,
    },
    /// after the closing bracket
    Closed,
    Done,
}

fn is_ws(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\n' | b'\r')
}

/// Splits an input stream into [`RawRecord`]s, one per curve, in bounded memory (one record
/// plus the read buffer).
///
/// The form is chosen by the first non-whitespace byte (a UTF-8 byte-order mark is skipped):
/// `[` starts a JSON array of curves, anything else is JSON Lines. In the array form the
/// elements are cut out by a small scanner that tracks strings, escapes and bracket depth, and
/// each element is parsed on its own, so millions of curves stream through.
///
/// A read error ends the stream with one record whose error is [`InputError::Io`].
pub struct RecordReader<R> {
    inner: BufReader<R>,
    mode: Mode,
    next_index: usize,
    /// position of the next unread byte
    pos: Position,
    consumed: u64,
    max_record: usize,
}

impl<R: Read> RecordReader<R> {
    /// A reader with the default record size limit.
    pub fn new(r: R) -> Self {
        Self::with_options(r, &ParseOptions::default())
    }

    /// A reader with the record size limit of `opts`.
    pub fn with_options(r: R, opts: &ParseOptions) -> Self {
        RecordReader {
            inner: BufReader::with_capacity(1 << 18, r),
            mode: Mode::Start,
            next_index: 0,
            pos: Position { line: 1, column: 1 },
            consumed: 0,
            max_record: opts.max_record_bytes,
        }
    }

    /// Bytes consumed so far (for progress reports).
    pub fn bytes_read(&self) -> u64 {
        self.consumed
    }

    /// The stream form, once the first record has been requested.
    pub fn form(&self) -> Option<StreamForm> {
        match self.mode {
            Mode::Start => None,
            Mode::Lines => Some(StreamForm::JsonLines),
            Mode::Array { .. } | Mode::Closed => Some(StreamForm::Array),
            Mode::Done => None,
        }
    }

    /// Consume `n` buffered bytes (`seen` are those bytes), keeping the position.
    fn advance(&mut self, n: usize) {
        let buf = self.inner.buffer();
        let seen = &buf[..n];
        match seen.iter().rposition(|&b| b == b'\n') {
            None => self.pos.column += n as u64,
            Some(k) => {
                self.pos.line += seen.iter().filter(|&&b| b == b'\n').count() as u64;
                self.pos.column = (n - k) as u64;
            }
        }
        self.consumed += n as u64;
        self.inner.consume(n);
    }

    /// Fill the buffer; `Ok(false)` at end of input. Interrupted reads are retried.
    fn fill(&mut self) -> io::Result<bool> {
        loop {
            match self.inner.fill_buf() {
                Ok(b) => return Ok(!b.is_empty()),
                Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(e),
            }
        }
    }

    /// Skip whitespace; the next byte, or `None` at end of input.
    fn skip_ws(&mut self) -> io::Result<Option<u8>> {
        loop {
            if !self.fill()? {
                return Ok(None);
            }
            let buf = self.inner.buffer();
            match buf.iter().position(|&b| !is_ws(b)) {
                Some(k) => {
                    let b = buf[k];
                    self.advance(k);
                    return Ok(Some(b));
                }
                None => {
                    let n = buf.len();
                    self.advance(n);
                }
            }
        }
    }

    fn record(&mut self, start: Position, bytes: Result<Vec<u8>, InputError>) -> RawRecord {
        let index = self.next_index;
        self.next_index += 1;
        RawRecord {
            index,
            start,
            bytes,
        }
    }

    /// One line (without the newline), bounded; `None` at end of input.
    fn read_line(&mut self) -> io::Result<Option<(Position, Vec<u8>, bool)>> {
        let start = self.pos;
        let (mut line, mut too_long, mut any) = (Vec::new(), false, false);
        while self.fill()? {
            any = true;
            let buf = self.inner.buffer();
            let (n, done) = match buf.iter().position(|&b| b == b'\n') {
                Some(k) => (k, true),
                None => (buf.len(), false),
            };
            if line.len() + n > self.max_record {
                too_long = true;
                line = Vec::new();
            } else if !too_long {
                line.extend_from_slice(&buf[..n]);
            }
            self.advance(n + done as usize);
            if done {
                break;
            }
        }
        Ok(any.then_some((start, line, too_long)))
    }

    fn next_line_record(&mut self) -> io::Result<Option<RawRecord>> {
        loop {
            let Some((start, line, too_long)) = self.read_line()? else {
                self.mode = Mode::Done;
                return Ok(None);
            };
            if too_long {
                let limit = self.max_record;
                return Ok(Some(
                    self.record(start, Err(InputError::TooLarge { limit, at: start })),
                ));
            }
            let Some(a) = line.iter().position(|&b| !is_ws(b)) else {
                continue; // blank line
            };
            let b = line.iter().rposition(|&b| !is_ws(b)).map_or(a, |k| k + 1);
            let start = Position {
                line: start.line,
                column: start.column + a as u64,
            };
            return Ok(Some(self.record(start, Ok(line[a..b].to_vec()))));
        }
    }

    /// Cut out one array element: bytes up to a ',' or ']' at bracket depth 0 outside strings
    /// (not consumed). Returns (bytes, too_long, cut short: the input ended inside a string or
    /// an open bracket, or `None` if the element ended normally or at a balanced end of input).
    fn scan_element(&mut self) -> io::Result<(Vec<u8>, bool, Option<bool>)> {
        let (mut depth, mut in_str, mut esc) = (0u64, false, false);
        let (mut out, mut too_long) = (Vec::new(), false);
        loop {
            if !self.fill()? {
                return Ok((out, too_long, Some(in_str || depth > 0)));
            }
            let buf = self.inner.buffer();
            let mut end = None;
            for (i, &b) in buf.iter().enumerate() {
                if in_str {
                    if esc {
                        esc = false;
                    } else if b == b'\\' {
                        esc = true;
                    } else if b == b'"' {
                        in_str = false;
                    }
                    continue;
                }
                match b {
                    b'"' => in_str = true,
                    b'[' | b'{' => depth += 1,
                    b']' if depth == 0 => {
                        end = Some(i);
                        break;
                    }
                    b',' if depth == 0 => {
                        end = Some(i);
                        break;
                    }
                    // a '}' at depth 0 is left in the element for the parser to report
                    b']' | b'}' => depth = depth.saturating_sub(1),
                    _ => {}
                }
            }
            let n = end.unwrap_or(buf.len());
            if out.len() + n > self.max_record {
                too_long = true;
                out = Vec::new();
            } else if !too_long {
                out.extend_from_slice(&buf[..n]);
            }
            self.advance(n);
            if end.is_some() {
                return Ok((out, too_long, None));
            }
        }
    }

    fn next_array_record(
        &mut self,
        mut need_sep: bool,
        mut after_comma: bool,
    ) -> io::Result<Option<RawRecord>> {
        loop {
            match self.skip_ws()? {
                None => {
                    self.mode = Mode::Done;
                    let at = self.pos;
                    return Ok(Some(self.record(at, Err(InputError::UnclosedArray { at }))));
                }
                Some(b']') => {
                    let at = self.pos;
                    self.advance(1);
                    if after_comma {
                        // `[..., ]`: report the trailing comma, then check what follows
                        self.mode = Mode::Closed;
                        return Ok(Some(self.record(at, Err(InputError::EmptyElement { at }))));
                    }
                    return self.next_closed();
                }
                Some(b',') if need_sep => {
                    self.advance(1);
                    need_sep = false;
                    after_comma = true;
                }
                Some(b',') => {
                    // `[,` or `,,`: an empty element
                    let at = self.pos;
                    self.advance(1);
                    self.mode = Mode::Array {
                        need_sep: false,
                        after_comma: true,
                    };
                    return Ok(Some(self.record(at, Err(InputError::EmptyElement { at }))));
                }
                Some(_) => {
                    let start = self.pos;
                    let (mut bytes, too_long, eof) = self.scan_element()?;
                    // After a truncated element nothing more is reported (no second error
                    // for the missing ']'); after a complete last element the next call
                    // reports the unclosed array.
                    self.mode = if eof == Some(true) {
                        Mode::Done
                    } else {
                        Mode::Array {
                            need_sep: true,
                            after_comma: false,
                        }
                    };
                    if too_long {
                        let limit = self.max_record;
                        let e = InputError::TooLarge { limit, at: start };
                        return Ok(Some(self.record(start, Err(e))));
                    }
                    while bytes.last().is_some_and(|&b| is_ws(b)) {
                        bytes.pop();
                    }
                    return Ok(Some(self.record(start, Ok(bytes))));
                }
            }
        }
    }

    /// After the closing bracket: only whitespace may follow.
    fn next_closed(&mut self) -> io::Result<Option<RawRecord>> {
        self.mode = Mode::Done;
        match self.skip_ws()? {
            None => Ok(None),
            Some(_) => {
                let at = self.pos;
                Ok(Some(self.record(at, Err(InputError::TrailingData { at }))))
            }
        }
    }

    fn next_record(&mut self) -> io::Result<Option<RawRecord>> {
        match self.mode {
            Mode::Done => Ok(None),
            Mode::Start => {
                // Skip a UTF-8 byte-order mark, byte by byte (reads may be short); a partial one
                // is dropped too, the rest of the record is invalid anyway.
                for bom in [0xEF, 0xBB, 0xBF] {
                    if !(self.fill()? && self.inner.buffer()[0] == bom) {
                        break;
                    }
                    self.consumed += 1;
                    self.inner.consume(1);
                }
                match self.skip_ws()? {
                    Some(b'[') => {
                        self.advance(1);
                        self.mode = Mode::Array {
                            need_sep: false,
                            after_comma: false,
                        };
                    }
                    Some(_) => self.mode = Mode::Lines,
                    None => {
                        self.mode = Mode::Done;
                        return Ok(None);
                    }
                }
                self.next_record()
            }
            Mode::Lines => self.next_line_record(),
            Mode::Array {
                need_sep,
                after_comma,
            } => self.next_array_record(need_sep, after_comma),
            Mode::Closed => self.next_closed(),
        }
    }
}

impl<R: Read> Iterator for RecordReader<R> {
    type Item = RawRecord;
    fn next(&mut self) -> Option<RawRecord> {
        match self.next_record() {
            Ok(r) => r,
            Err(e) => {
                self.mode = Mode::Done;
                let at = self.pos;
                Some(self.record(at, Err(InputError::Io(e.to_string()))))
            }
        }
    }
}

/// Parsed curves of a stream: `(index, curve or error)` in input order (see [`RecordReader`]).
pub struct CurveReader<R> {
    records: RecordReader<R>,
    opts: ParseOptions,
}

impl<R: Read> CurveReader<R> {
    /// Read curves from `r` with default options.
    pub fn new(r: R) -> Self {
        Self::with_options(r, ParseOptions::default())
    }
    /// Read curves from `r`.
    pub fn with_options(r: R, opts: ParseOptions) -> Self {
        CurveReader {
            records: RecordReader::with_options(r, &opts),
            opts,
        }
    }
}

impl<R: Read> Iterator for CurveReader<R> {
    type Item = (usize, Result<NurbsCurve, InputError>);
    fn next(&mut self) -> Option<Self::Item> {
        let r = self.records.next()?;
        Some((r.index, r.parse(&self.opts)))
    }
}

/// Read every curve of a byte slice (either stream form).
pub fn read_curves(bytes: &[u8]) -> Vec<(usize, Result<NurbsCurve, InputError>)> {
    CurveReader::new(bytes).collect()
}

// ---------------------------------------------------------------------------------------------
// Writing.

/// Append a finite f64 as the shortest decimal that round-trips (serde_json uses ryu), and a
/// non-finite one as the string "inf" / "-inf" (`docs/formats.md`, "Numbers"). A NaN would be
/// written as "nan", but the record writers replace NaN by the trivially sound infinity first.
pub fn write_num(out: &mut Vec<u8>, x: f64) {
    if x.is_finite() {
        // Writing into a Vec cannot fail.
        let _ = serde_json::to_writer(&mut *out, &x);
    } else if x > 0.0 {
        out.extend_from_slice(b"\"inf\"");
    } else if x < 0.0 {
        out.extend_from_slice(b"\"-inf\"");
    } else {
        out.extend_from_slice(b"\"nan\"");
    }
}

/// Append a JSON string.
pub fn write_str(out: &mut Vec<u8>, s: &str) {
    let _ = serde_json::to_writer(&mut *out, s);
}

/// Append a JSON array of numbers (see [`write_num`]).
pub fn write_nums(out: &mut Vec<u8>, xs: impl IntoIterator<Item = f64>) {
    out.push(b'[');
    for (i, x) in xs.into_iter().enumerate() {
        if i > 0 {
            out.push(b',');
        }
        write_num(out, x);
    }
    out.push(b']');
}

/// Which side of a bound a value is, to replace a NaN by the value that is trivially sound:
/// an outer lower bound by -inf, an outer upper bound by +inf, an inner lower bound (the curve
/// reaches something <= it) by +inf, an inner upper bound by -inf.
#[derive(Clone, Copy)]
enum Side {
    Low,
    High,
}

fn sound(x: f64, side: Side) -> f64 {
    match (x.is_nan(), side) {
        (false, _) => x,
        (true, Side::Low) => f64::NEG_INFINITY,
        (true, Side::High) => f64::INFINITY,
    }
}

/// Append a curve as a JSON object in the input format (`weights` only if rational).
pub fn write_curve(out: &mut Vec<u8>, c: &NurbsCurve) {
    out.extend_from_slice(b"{\"degree\":");
    out.extend_from_slice(c.degree().to_string().as_bytes());
    out.extend_from_slice(b",\"knots\":");
    write_nums(out, c.knots().iter().copied());
    out.extend_from_slice(b",\"control_points\":[");
    for i in 0..c.num_points() {
        if i > 0 {
            out.push(b',');
        }
        write_nums(out, c.control_point(i).iter().copied());
    }
    out.push(b']');
    if let Some(w) = c.weights() {
        out.extend_from_slice(b",\"weights\":");
        write_nums(out, w.iter().copied());
    }
    out.push(b'}');
}

/// A curve as one line of JSON in the input format; `parse_curve` of it gives back the same
/// curve bit for bit (shortest round-trip decimals).
pub fn curve_to_json(c: &NurbsCurve) -> String {
    let mut out = Vec::new();
    write_curve(&mut out, c);
    String::from_utf8(out).expect("JSON output is ASCII")
}

/// snake_case name of a termination reason (`IterationLimit` -> `iteration_limit`).
pub fn termination_name(t: Termination) -> String {
    let mut s = String::new();
    for (i, ch) in format!("{t:?}").chars().enumerate() {
        if ch.is_ascii_uppercase() {
            if i > 0 {
                s.push('_');
            }
            s.push(ch.to_ascii_lowercase());
        } else {
            s.push(ch);
        }
    }
    s
}

/// Append an `enclose` record (no newline):
/// `{"index","strategy","verified","lo","hi","inner_lo","inner_hi","stats":{...}}`.
/// With `timings`, stats also has `time_total_s` and `time_derivatives_s` (off by default so
/// that output is reproducible).
pub fn write_enclosure_record(out: &mut Vec<u8>, index: usize, e: &Enclosure, timings: bool) {
    out.extend_from_slice(format!("{{\"index\":{index},\"strategy\":").as_bytes());
    write_str(out, e.strategy);
    out.extend_from_slice(if e.verified {
        b",\"verified\":true,\"lo\":"
    } else {
        b",\"verified\":false,\"lo\":"
    });
    write_nums(out, e.coords.iter().map(|c| sound(c.lo, Side::Low)));
    out.extend_from_slice(b",\"hi\":");
    write_nums(out, e.coords.iter().map(|c| sound(c.hi, Side::High)));
    out.extend_from_slice(b",\"inner_lo\":");
    write_nums(out, e.coords.iter().map(|c| sound(c.inner_lo, Side::High)));
    out.extend_from_slice(b",\"inner_hi\":");
    write_nums(out, e.coords.iter().map(|c| sound(c.inner_hi, Side::Low)));
    let s = e.stats();
    out.extend_from_slice(
        format!(
            ",\"stats\":{{\"newton_iterations\":{},\"derivative_evaluations\":{},\
             \"point_evaluations\":{},\"subdivisions\":{},\"termination\":\"{}\"",
            s.newton_iterations,
            s.derivative_evaluations,
            s.point_evaluations,
            s.subdivisions,
            termination_name(e.termination())
        )
        .as_bytes(),
    );
    if timings {
        out.extend_from_slice(b",\"time_total_s\":");
        write_num(out, s.time_total.as_secs_f64());
        out.extend_from_slice(b",\"time_derivatives_s\":");
        write_num(out, s.time_derivatives.as_secs_f64());
    }
    out.extend_from_slice(b"}}");
}

/// Append an `eval` record (no newline): `{"index","param","derivative","lo","hi"}` from the
/// enclosure `value` of C^(derivative)(param). An empty or NaN interval end is written as the
/// trivially sound -inf / inf.
pub fn write_eval_record(
    out: &mut Vec<u8>,
    index: usize,
    param: f64,
    derivative: usize,
    value: &[Interval],
) {
    out.extend_from_slice(format!("{{\"index\":{index},\"param\":").as_bytes());
    write_num(out, param);
    out.extend_from_slice(format!(",\"derivative\":{derivative},\"lo\":").as_bytes());
    let ends = |x: &Interval| {
        if x.is_empty() {
            (f64::NEG_INFINITY, f64::INFINITY)
        } else {
            (sound(x.inf(), Side::Low), sound(x.sup(), Side::High))
        }
    };
    write_nums(out, value.iter().map(|x| ends(x).0));
    out.extend_from_slice(b",\"hi\":");
    write_nums(out, value.iter().map(|x| ends(x).1));
    out.push(b'}');
}

/// Append an error record (no newline): `{"index": i, <extra fields>, "error": {"kind",
/// "message"}}`. `extra` is written verbatim after the index (e.g. `"param":2.0,"derivative":0`)
/// and may be empty.
pub fn write_error_record(out: &mut Vec<u8>, index: usize, extra: &str, kind: &str, message: &str) {
    out.extend_from_slice(format!("{{\"index\":{index},").as_bytes());
    if !extra.is_empty() {
        out.extend_from_slice(extra.as_bytes());
        out.push(b',');
    }
    out.extend_from_slice(b"\"error\":{\"kind\":");
    write_str(out, kind);
    out.extend_from_slice(b",\"message\":");
    write_str(out, message);
    out.extend_from_slice(b"}}");
}

/// The `"param":U,"derivative":K` fields of eval records, for [`write_error_record`].
pub fn eval_fields(param: f64, derivative: usize) -> String {
    let mut out = b"\"param\":".to_vec();
    write_num(&mut out, param);
    out.extend_from_slice(format!(",\"derivative\":{derivative}").as_bytes());
    String::from_utf8(out).expect("ASCII")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::enclose::BoxEncloser;

    const GOOD: &str = r#"{"degree": 3, "knots": [0, 0, 0, 0, 0.5, 1, 1, 1, 1], "control_points": [[0, 0], [1, 2], [2, -1], [3, 3], [4, 0]], "weights": [1, 1, 2, 1, 1]}"#;

    fn err(s: &str) -> InputError {
        parse_curve(s.as_bytes()).expect_err(s)
    }

    /// (input, expected kind, expected message start)
    const BAD: &[(&str, &str, &str)] = &[
        (
            r#"{"degree": 3, "knots": [0, 0, 0, "x"], "control_points": []}"#,
            "wrong_type",
            "knots[3]: expected a number, got a string \"x\"",
        ),
        (
            r#"{"degree": 1, "knots": [0, 0, 1, 1e400], "control_points": [[0], [1]]}"#,
            "number_out_of_range",
            "knots[3]: the number 1e400",
        ),
        (
            r#"{"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0], [-1e999]]}"#,
            "number_out_of_range",
            "control_points[1][0]: the number -1e999",
        ),
        (
            r#"{"degree": 1, "knots": [0, 0, NaN, 1], "control_points": [[0], [1]]}"#,
            "non_finite_literal",
            "knots[2]: NaN is not",
        ),
        (
            r#"{"degree": 1, "knots": [0, 0, -Infinity, 1], "control_points": [[0], [1]]}"#,
            "non_finite_literal",
            "knots[2]: -Infinity",
        ),
        (
            r#"{"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0], [1]], "weights": [1, inf]}"#,
            "non_finite_literal",
            "weights[1]: inf",
        ),
        (
            r#"{"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0], [1, "NaN"]]}"#,
            "wrong_type",
            "control_points[1][1]: expected a number, got a string \"NaN\"",
        ),
        (
            r#"{"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0], [1]"#,
            "truncated_json",
            "control_points",
        ),
        (r#"{"degree": 1, "kno"#, "truncated_json", "curve"),
        ("", "truncated_json", "curve"),
        (
            "{\"degree\": 1, \x00\x01\x7f",
            "invalid_json",
            "curve: invalid JSON: key must be a string, found the byte 0x00",
        ),
        ("\u{1F600}", "invalid_json", "curve: invalid JSON"),
        (
            r#"{"degree": -1, "knots": [0, 0, 1, 1], "control_points": [[0], [1]]}"#,
            "invalid_degree",
            "degree: expected an integer >= 1, got -1",
        ),
        (
            r#"{"degree": 1.5, "knots": [0, 0, 1, 1], "control_points": [[0], [1]]}"#,
            "invalid_degree",
            "degree: expected an integer >= 1, got 1.5",
        ),
        (
            r#"{"degree": 1e300, "knots": [0, 0, 1, 1], "control_points": [[0], [1]]}"#,
            "invalid_degree",
            "degree",
        ),
        (
            r#"{"degree": "3", "knots": [0, 0, 1, 1], "control_points": [[0], [1]]}"#,
            "wrong_type",
            "degree: expected an integer >= 1, got a string \"3\"",
        ),
        (
            r#"{"degree": 1000000000, "knots": [0, 0, 1, 1], "control_points": [[0], [1]]}"#,
            "too_few_control_points",
            "control_points: a curve of degree 1000000000",
        ),
        (
            r#"{"degree": 18446744073709551615, "knots": [0, 0, 1, 1], "control_points": [[0], [1]]}"#,
            "invalid_degree",
            "degree",
        ),
        (
            r#"{"degree": 0, "knots": [0, 1], "control_points": [[0]]}"#,
            "invalid_degree",
            "degree",
        ),
        (
            r#"{"degree": 1, "knots": [], "control_points": []}"#,
            "too_few_control_points",
            "control_points",
        ),
        (
            r#"{"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[], []]}"#,
            "zero_dimension",
            "control_points[0]",
        ),
        (
            r#"{"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0], [1]], "weights": []}"#,
            "weight_count",
            "weights",
        ),
        (
            r#"{"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0], [1]], "weight": [1, 2]}"#,
            "unknown_field",
            "\"weight\": unknown field",
        ),
        (
            r#"{"degree": 1, "knots": [0, 0, 1, 1], "knots": [0, 0, 1, 1], "control_points": [[0], [1]]}"#,
            "duplicate_field",
            "knots: the field appears twice",
        ),
        (
            r#"{"knots": [0, 0, 1, 1], "control_points": [[0], [1]]}"#,
            "missing_field",
            "degree: missing field",
        ),
        (
            r#"{"degree": 1, "knots": [0, 0, 1, 1], "control_points": [0, 1]}"#,
            "wrong_type",
            "control_points[0]: expected an array of coordinates (numbers), got the number 0",
        ),
        (
            r#"{"degree": 1, "knots": {"a": 1}, "control_points": [[0], [1]]}"#,
            "wrong_type",
            "knots: expected an array of numbers, got an object",
        ),
        (
            r#"{"degree": 1, "knots": [0, 0, [1], 1], "control_points": [[0], [1]]}"#,
            "wrong_type",
            "knots[2]: expected a number, got an array",
        ),
        (
            r#"{"degree": 1, "knots": [0, 0, 1, 1], "control_points": null}"#,
            "wrong_type",
            "control_points: expected an array of points (arrays of numbers), got null",
        ),
        (r#"[1, 2]"#, "wrong_type", "curve: expected a curve object"),
        (r#"true"#, "wrong_type", "curve: expected a curve object"),
        (
            r#"{"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0], [1]]} x"#,
            "invalid_json",
            "curve: invalid JSON: trailing characters, found 'x'",
        ),
        (
            r#"{"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0], [1]], "weights": [1, 0]}"#,
            "invalid_weight",
            "weights[1]",
        ),
        (
            r#"{"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0], [1]], "weights": [1, -0.0]}"#,
            "invalid_weight",
            "weights[1]",
        ),
        (
            r#"{"degree": 1, "knots": [0, 1, 0, 1], "control_points": [[0], [1]]}"#,
            "decreasing_knots",
            "knots[2]",
        ),
        (
            r#"{"degree": 1, "knots": [0, 0.5, 0.5, 1], "control_points": [[0], [1]]}"#,
            "empty_domain",
            "knots",
        ),
        (
            r#"{"degree": 1, "knots": [0, 0, 0, 1], "control_points": [[0], [1]]}"#,
            "knot_multiplicity",
            "knots[0]",
        ),
        (
            r#"{"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0, 1], [1]]}"#,
            "dimension_mismatch",
            "control_points[1]",
        ),
        (
            r#"{"degree": 1, "knots": [0, 0, 1, 1,], "control_points": [[0], [1]]}"#,
            "invalid_json",
            "knots[4]: invalid JSON: trailing comma",
        ),
        (
            r#"{"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0], [1]], "x": "\uD800"}"#,
            "unknown_field",
            "\"x\"",
        ),
        (
            r#"{"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0], [1]], "weights": [1, 1], }"#,
            "invalid_json",
            "curve: invalid JSON: trailing comma",
        ),
    ];

    #[test]
    fn bad_curves_have_kind_path_and_position() {
        for (input, kind, start) in BAD {
            let e = err(input);
            let msg = e.to_string();
            assert_eq!(e.kind(), *kind, "{input}: {msg}");
            assert!(msg.starts_with(start), "{input}: {msg}");
        }
    }

    #[test]
    fn positions_are_absolute() {
        let input =
            "{\"degree\": 1,\n \"knots\": [0, 0, \"a\", 1], \"control_points\": [[0], [1]]}";
        let e = parse_curve_at(
            input.as_bytes(),
            Position { line: 7, column: 3 },
            &ParseOptions::default(),
        )
        .unwrap_err();
        assert!(
            matches!(
                e,
                InputError::WrongType {
                    at: Position {
                        line: 8,
                        column: 20
                    },
                    ..
                }
            ),
            "{e:?}"
        );
        let e = parse_curve_at(
            br#"{"degree": 1, "knots": [NaN]}"#,
            Position { line: 2, column: 5 },
            &ParseOptions::default(),
        )
        .unwrap_err();
        // NaN starts at byte 24 of the record, i.e. column 5 + 24
        assert!(
            matches!(
                e,
                InputError::NonFiniteLiteral {
                    at: Position {
                        line: 2,
                        column: 29
                    },
                    ..
                }
            ),
            "{e:?}"
        );
    }

    #[test]
    fn huge_nesting_is_an_error_not_a_crash() {
        // The visitors reject a nested array where a number belongs at once, before any
        // recursion.
        for depth in [200, 100_000] {
            let s = "[".repeat(depth) + &"]".repeat(depth);
            assert_eq!(err(&s).kind(), "wrong_type", "depth {depth}");
            let s = format!("{{\"degree\": 1, \"knots\": {}", "[".repeat(depth));
            assert_eq!(err(&s).kind(), "wrong_type");
            let s = format!(
                "{{\"degree\":1,\"knots\":[0,0,1,1],\"control_points\":[[0],[1]],\"x\":{}}}",
                "[".repeat(depth) + &"]".repeat(depth)
            );
            let opts = ParseOptions {
                allow_unknown_fields: true,
                ..ParseOptions::default()
            };
            // serde_json skips ignored values iteratively: any depth is fine
            assert!(parse_curve_at(s.as_bytes(), Position::default(), &opts).is_ok());
        }
    }

    #[test]
    #[allow(clippy::excessive_precision)] // the literal is the classic hard case, as written
    fn numbers_are_correctly_rounded() {
        // 2^53 + 1 is a tie between 2^53 and 2^53 + 2: ties to even gives 2^53.
        // 0.1 must be the nearest f64; 1e23 is a classic hard case for naive parsers;
        // an integer beyond u64 goes through the float path; -0 keeps its sign.
        let s = r#"{"degree": 1, "knots": [-0, 0.1, 1e23, 100000000000000000000000000001],
                   "control_points": [[9007199254740993], [2.2250738585072011e-308]]}"#;
        let c = parse_curve(s.as_bytes()).unwrap();
        let k = c.knots();
        assert!(k[0] == 0.0 && k[0].is_sign_negative());
        assert_eq!(k[1], 0.1);
        assert_eq!(k[2], 1e23);
        assert_eq!(k[3], 1e29);
        assert_eq!(c.control_point(0)[0], 9007199254740992.0);
        assert_eq!(c.control_point(1)[0], 2.2250738585072011e-308);
    }

    #[test]
    fn lenient_options_and_null_weights() {
        let s = r#"{"name": "x", "degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0], [1]], "weights": null, "meta": {"a": [1, {"b": null}]}}"#;
        assert_eq!(err(s).kind(), "unknown_field");
        let opts = ParseOptions {
            allow_unknown_fields: true,
            ..ParseOptions::default()
        };
        let c = parse_curve_at(s.as_bytes(), Position::default(), &opts).unwrap();
        assert!(!c.is_rational());
        let c = parse_curve(br#" {"degree": 3.0, "knots": [0,0,0,0,1,1,1,1], "control_points": [[0],[1],[2],[3]]} "#).unwrap();
        assert_eq!(c.degree(), 3);
    }

    /// Reads at most `n` bytes per call, to exercise buffer boundaries.
    struct Trickle<'a>(&'a [u8], usize);
    impl Read for Trickle<'_> {
        fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
            let n = self.1.min(buf.len()).min(self.0.len());
            buf[..n].copy_from_slice(&self.0[..n]);
            self.0 = &self.0[n..];
            Ok(n)
        }
    }

    fn kinds(input: &[u8]) -> Vec<String> {
        let all: Vec<_> = read_curves(input);
        let trickled: Vec<_> = CurveReader::new(Trickle(input, 1)).collect();
        assert_eq!(all, trickled, "byte-by-byte reading differs");
        all.iter()
            .enumerate()
            .map(|(i, (idx, r))| {
                assert_eq!(i, *idx);
                match r {
                    Ok(_) => "ok".to_string(),
                    Err(e) => e.kind().to_string(),
                }
            })
            .collect()
    }

    const C1: &str = r#"{"degree":1,"knots":[0,0,1,1],"control_points":[[0],[1]]}"#;

    #[test]
    fn json_lines_stream() {
        let input = format!("\n{C1}\n  \n\r\n{{\"degree\": 1}}\n  {C1}  \r\nnot json\n{C1}");
        assert_eq!(
            kinds(input.as_bytes()),
            ["ok", "missing_field", "ok", "invalid_json", "ok"]
        );
        let recs: Vec<RawRecord> = RecordReader::new(input.as_bytes()).collect();
        assert_eq!(recs[2].start, Position { line: 6, column: 3 });
        assert_eq!(recs[3].start, Position { line: 7, column: 1 });
        assert_eq!(kinds(b""), Vec::<String>::new());
        assert_eq!(kinds(b"  \n\n "), Vec::<String>::new());
        // a byte-order mark is skipped
        assert_eq!(kinds(format!("\u{feff}{C1}").as_bytes()), ["ok"]);
        // binary junk: one error per line, never a panic
        assert_eq!(
            kinds(b"\xff\xfe\x00\n\x80{\n"),
            ["invalid_json", "invalid_json"]
        );
    }

    #[test]
    fn array_stream() {
        let input = format!("[\n {C1},\n {{\"degree\": 1, \"knots\": [\"]\", \"{{\"]}},\n{C1} ]\n");
        assert_eq!(kinds(input.as_bytes()), ["ok", "wrong_type", "ok"]);
        let recs: Vec<RawRecord> = RecordReader::new(input.as_bytes()).collect();
        assert_eq!(recs[2].start, Position { line: 4, column: 1 });
        assert_eq!(kinds(b"[]"), Vec::<String>::new());
        assert_eq!(kinds(b" [ ] \n"), Vec::<String>::new());
        assert_eq!(
            kinds(format!("[{C1},,{C1}]").as_bytes()),
            ["ok", "empty_element", "ok"]
        );
        assert_eq!(
            kinds(format!("[{C1},]").as_bytes()),
            ["ok", "empty_element"]
        );
        assert_eq!(
            kinds(format!("[,{C1}]").as_bytes()),
            ["empty_element", "ok"]
        );
        assert_eq!(kinds(format!("[{C1}").as_bytes()), ["ok", "unclosed_array"]);
        assert_eq!(
            kinds(format!("[{C1},").as_bytes()),
            ["ok", "unclosed_array"]
        );
        assert_eq!(kinds(b"["), ["unclosed_array"]);
        assert_eq!(
            kinds(format!("[{C1}] x").as_bytes()),
            ["ok", "trailing_data"]
        );
        assert_eq!(
            kinds(format!("[{C1}]\n[{C1}]").as_bytes()),
            ["ok", "trailing_data"]
        );
        // a truncated element is one error, with no second one for the missing ']'
        assert_eq!(
            kinds(format!("[{C1}, {{\"degree\": 1, \"kn").as_bytes()),
            ["ok", "truncated_json"]
        );
        // escaped quotes and brackets inside strings do not end an element
        let tricky =
            r#"[{"degree":1,"knots":[0,0,1,1],"control_points":[[0],[1]],"weights":"\"],["}, 5]"#;
        assert_eq!(kinds(tricky.as_bytes()), ["wrong_type", "wrong_type"]);
        // missing comma between elements: the parser reports trailing characters
        assert_eq!(kinds(format!("[{C1} {C1}]").as_bytes()), ["invalid_json"]);
        // a '}' too many stays in its element
        assert_eq!(
            kinds(format!("[{C1}}}, {C1}]").as_bytes()),
            ["invalid_json", "ok"]
        );
        // deep nesting in the splitter: a counter, no recursion
        let deep = "[".repeat(100_000) + &"]".repeat(100_000);
        assert_eq!(kinds(deep.as_bytes()), ["wrong_type"]);
        let deep = format!("[{}]", "{\"a\":[".repeat(100_000) + &"]}".repeat(100_000));
        assert_eq!(kinds(deep.as_bytes()), ["unknown_field"]);
    }

    #[test]
    fn oversized_records_are_skipped() {
        let opts = ParseOptions {
            max_record_bytes: 80,
            ..ParseOptions::default()
        };
        let long = format!(
            "{{\"degree\":1,\"knots\":[0,0,1,1],\"control_points\":[[0],[1]],\"weights\":[{}1,1]}}",
            "1,".repeat(50)
        );
        for input in [
            format!("{C1}\n{long}\n{C1}\n"),
            format!("[{C1}, {long}, {C1}]"),
        ] {
            let k: Vec<_> = CurveReader::with_options(Trickle(input.as_bytes(), 7), opts)
                .map(|(_, r)| r.map_or_else(|e| e.kind(), |_| "ok"))
                .collect();
            assert_eq!(k, ["ok", "record_too_large", "ok"]);
        }
    }

    #[test]
    fn read_errors_end_the_stream() {
        struct Broken;
        impl Read for Broken {
            fn read(&mut self, _: &mut [u8]) -> io::Result<usize> {
                Err(io::Error::other("boom"))
            }
        }
        let v: Vec<_> = CurveReader::new(Broken).collect();
        assert_eq!(v.len(), 1);
        assert!(matches!(&v[0].1, Err(InputError::Io(m)) if m.contains("boom")));
    }

    #[test]
    fn records_are_well_formed_json() {
        let c = parse_curve(GOOD.as_bytes()).unwrap();
        let e = crate::enclose::ControlHull.enclose(&c);
        let mut out = Vec::new();
        write_enclosure_record(&mut out, 7, &e, true);
        let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
        assert_eq!(v["index"], 7);
        assert_eq!(v["strategy"], "hull");
        assert_eq!(v["stats"]["termination"], "direct");
        assert!(v["stats"]["time_total_s"].is_number());
        let mut out = Vec::new();
        let iv = |a, b| Interval::try_from((a, b)).unwrap();
        write_eval_record(
            &mut out,
            0,
            0.25,
            1,
            &[iv(f64::NEG_INFINITY, 1.5), Interval::EMPTY],
        );
        assert_eq!(
            String::from_utf8(out).unwrap(),
            r#"{"index":0,"param":0.25,"derivative":1,"lo":["-inf","-inf"],"hi":[1.5,"inf"]}"#
        );
        let mut out = Vec::new();
        write_error_record(
            &mut out,
            3,
            &eval_fields(2.0, 0),
            "k",
            "a \"quoted\"\nmessage",
        );
        let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
        assert_eq!(v["error"]["message"], "a \"quoted\"\nmessage");
        assert_eq!(v["param"], 2.0);
        assert_eq!(
            termination_name(Termination::IterationLimit),
            "iteration_limit"
        );
    }

    #[test]
    fn good_curve_round_trips() {
        let c = parse_curve(GOOD.as_bytes()).unwrap();
        assert_eq!(c.degree(), 3);
        assert_eq!(c.weights(), Some(&[1.0, 1.0, 2.0, 1.0, 1.0][..]));
        let back = parse_curve(curve_to_json(&c).as_bytes()).unwrap();
        assert_eq!(back, c);
    }
}
