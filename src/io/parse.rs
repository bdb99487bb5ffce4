//! Parsing one curve: [`parse_curve`] and its options, with serde visitors that know their
//! field path.

use super::error::{shorten, InputError, Position};
use super::position::convert_error;
use crate::spline::curve::NurbsCurve;
use crate::surface::NurbsSurface;
use serde::de::{self, DeserializeSeed, IgnoredAny, MapAccess, SeqAccess, Visitor};
use std::cell::RefCell;
use std::fmt;

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

// The visitors know their field path. A visitor that rejects a value stores a structured error
// in a shared slot and returns a placeholder serde error; serde_json attaches the position to
// the placeholder, and `convert_error` (in `position`) joins the two.

/// Where a value sits in the curve object.
#[derive(Debug, Clone, Copy)]
enum Loc {
    Curve,
    Field(&'static str),
    Elem(&'static str, usize),
    Coord(usize, usize),
    /// `control_points[i][j]` of a surface (its coordinates are `Coord3`)
    Point2(usize, usize),
    Coord3(usize, usize, usize),
    /// `weights[i]` of a surface (its elements are `Elem2`)
    Row(&'static str, usize),
    Elem2(&'static str, usize, usize),
}

impl fmt::Display for Loc {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Loc::Curve => f.write_str("curve"),
            Loc::Field(s) => f.write_str(s),
            Loc::Elem(s, i) => write!(f, "{s}[{i}]"),
            Loc::Coord(i, j) | Loc::Point2(i, j) => write!(f, "control_points[{i}][{j}]"),
            Loc::Coord3(i, j, k) => write!(f, "control_points[{i}][{j}][{k}]"),
            Loc::Row(s, i) => write!(f, "{s}[{i}]"),
            Loc::Elem2(s, i, j) => write!(f, "{s}[{i}][{j}]"),
        }
    }
}

/// An error found by a visitor, still without a position.
pub(super) enum DataErr {
    WrongType {
        path: String,
        expected: &'static str,
        got: String,
    },
    Missing(&'static str),
    Unknown(String),
    Duplicate(&'static str),
    Degree(&'static str, String),
    MissingSurface(&'static str),
    Mixed(&'static str, &'static str),
}

type Slot<'a> = &'a RefCell<Option<DataErr>>;

fn fail<E: de::Error>(slot: Slot<'_>, e: DataErr) -> E {
    *slot.borrow_mut() = Some(e);
    E::custom("invalid curve")
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
            Loc::Elem("control_points", _) | Loc::Point2(..) => "an array of coordinates (numbers)",
            _ => "an array of numbers",
        }
    }
    /// The location of element i.
    fn elem(&self, i: usize) -> Loc {
        match self.loc {
            Loc::Field(f) => Loc::Elem(f, i),
            Loc::Elem(_, k) => Loc::Coord(k, i),
            Loc::Point2(a, b) => Loc::Coord3(a, b, i),
            Loc::Row(f, a) => Loc::Elem2(f, a, i),
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
        usize::try_from(v)
            .map_err(|_| fail(self.slot, DataErr::Degree(self.field(), v.to_string())))
    }
    fn visit_i64<E: de::Error>(self, v: i64) -> Result<usize, E> {
        usize::try_from(v)
            .map_err(|_| fail(self.slot, DataErr::Degree(self.field(), v.to_string())))
    }
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<usize, E> {
        // Exact: an integral f64 below 2^53 converts without rounding; larger ones are
        // rejected rather than truncated.
        if v.fract() == 0.0 && (0.0..9007199254740992.0).contains(&v) {
            self.visit_u64(v as u64)
        } else {
            Err(fail(
                self.slot,
                DataErr::Degree(self.field(), v.to_string()),
            ))
        }
    }
    reject!(text, unit, map, seq);
}

impl Degree<'_> {
    fn field(&self) -> &'static str {
        match self.loc {
            Loc::Field(f) => f,
            _ => "degree",
        }
    }
}

/// A key of the curve (or surface) object.
enum Key {
    Degree,
    Knots,
    ControlPoints,
    Weights,
    DegreeU,
    DegreeV,
    KnotsU,
    KnotsV,
    Other(String),
}

/// `surfaces`: the surface keys are known (the record parser); otherwise they are unknown
/// fields, as for [`parse_curve`].
struct KeySeed {
    surfaces: bool,
}

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
            "degree_u" if self.surfaces => Key::DegreeU,
            "degree_v" if self.surfaces => Key::DegreeV,
            "knots_u" if self.surfaces => Key::KnotsU,
            "knots_v" if self.surfaces => Key::KnotsV,
            other => Key::Other(shorten(other, 40)),
        })
    }
}

/// An element that is a number (of a curve) or an array of numbers (of a surface).
#[derive(Debug)]
enum Elem {
    N(f64),
    V(Vec<f64>),
}

/// One element of `control_points` or `weights` when the object may be either kind: a number
/// (reported at `num_loc`) or an array of numbers (at `seq_loc`, elements below it).
struct NumOrSeq<'a> {
    slot: Slot<'a>,
    num_loc: Loc,
    seq_loc: Loc,
}

impl NumOrSeq<'_> {
    fn expected(&self) -> &'static str {
        "a number or an array of numbers"
    }
}

seed_via_any!(NumOrSeq, Elem);

impl<'de> Visitor<'de> for NumOrSeq<'_> {
    type Value = Elem;
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Elem, E> {
        Ok(Elem::N(v))
    }
    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Elem, E> {
        Ok(Elem::N(v as f64))
    }
    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Elem, E> {
        Ok(Elem::N(v as f64))
    }
    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Elem, A::Error> {
        Nums {
            slot: self.slot,
            loc: self.seq_loc,
            nullable: false,
        }
        .visit_seq(seq)
        .map(|v| Elem::V(v.unwrap_or_default()))
    }
    fn visit_bool<E: de::Error>(self, v: bool) -> Result<Elem, E> {
        Err(wrong(
            self.slot,
            self.num_loc,
            self.expected(),
            format!("the boolean {v}"),
        ))
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<Elem, E> {
        let got = format!("a string {:?}", shorten(v, 40));
        Err(wrong(self.slot, self.num_loc, self.expected(), got))
    }
    fn visit_unit<E: de::Error>(self) -> Result<Elem, E> {
        Err(wrong(
            self.slot,
            self.num_loc,
            self.expected(),
            "null".into(),
        ))
    }
    fn visit_map<A: MapAccess<'de>>(self, _: A) -> Result<Elem, A::Error> {
        Err(wrong(
            self.slot,
            self.num_loc,
            self.expected(),
            "an object".into(),
        ))
    }
    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.expected())
    }
}

/// A sequence of [`NumOrSeq`] elements: `control_points[i]` (`row = Some(i)`) or `weights`.
struct Elems<'a> {
    slot: Slot<'a>,
    loc: Loc,
    row: Option<usize>,
    nullable: bool,
}

impl Elems<'_> {
    fn expected(&self) -> &'static str {
        match self.row {
            Some(_) => "a point (array of numbers) or a row of points (array of arrays)",
            None => "an array of weights (numbers, or rows of numbers)",
        }
    }
}

seed_via_any!(Elems, Option<Vec<Elem>>);

impl<'de> Visitor<'de> for Elems<'_> {
    type Value = Option<Vec<Elem>>;
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        let mut v = Vec::new();
        loop {
            let k = v.len();
            let (num_loc, seq_loc) = match self.row {
                Some(i) => (Loc::Coord(i, k), Loc::Point2(i, k)),
                None => (Loc::Elem("weights", k), Loc::Row("weights", k)),
            };
            let seed = NumOrSeq {
                slot: self.slot,
                num_loc,
                seq_loc,
            };
            match seq.next_element_seed(seed)? {
                Some(e) => v.push(e),
                None => return Ok(Some(v)),
            }
        }
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
    /// `control_points` when the object may be a curve or a surface.
    Net -> Vec<Vec<Elem>>, "an array of points (arrays of numbers) or of rows of points"
}

impl<'de> Visitor<'de> for Net<'_> {
    type Value = Vec<Vec<Elem>>;
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        let mut v = Vec::new();
        while let Some(p) = seq.next_element_seed(Elems {
            slot: self.slot,
            loc: Loc::Elem("control_points", v.len()),
            row: Some(v.len()),
            nullable: false,
        })? {
            v.push(p.unwrap_or_default());
        }
        Ok(v)
    }
    reject!(text, unit, map, numbers);
}

/// A parsed and validated input record: a curve or a surface.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// an object with `degree`
    Curve(NurbsCurve),
    /// an object with `degree_u` (and the other surface fields)
    Surface(NurbsSurface),
}

/// The fields of an object, before validation.
struct RawCurve {
    degree: Option<usize>,
    knots: Option<Vec<f64>>,
    degree_u: Option<usize>,
    degree_v: Option<usize>,
    knots_u: Option<Vec<f64>>,
    knots_v: Option<Vec<f64>>,
    control_points: Vec<Vec<Elem>>,
    weights: Option<Vec<Elem>>,
}

struct CurveSeed<'a> {
    slot: Slot<'a>,
    loc: Loc,
    allow_unknown: bool,
    surfaces: bool,
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
        let (mut du, mut dv, mut ku, mut kv) = (None, None, None, None);
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
        let nums = |name: &'static str| Nums {
            slot,
            loc: Loc::Field(name),
            nullable: false,
        };
        while let Some(key) = map.next_key_seed(KeySeed {
            surfaces: self.surfaces,
        })? {
            match key {
                Key::Degree | Key::DegreeU | Key::DegreeV => {
                    let (name, dst) = match key {
                        Key::Degree => ("degree", &mut degree),
                        Key::DegreeU => ("degree_u", &mut du),
                        _ => ("degree_v", &mut dv),
                    };
                    let loc = Loc::Field(name);
                    once(slot, dst, name, map.next_value_seed(Degree { slot, loc })?)?
                }
                Key::Knots | Key::KnotsU | Key::KnotsV => {
                    let (name, dst) = match key {
                        Key::Knots => ("knots", &mut knots),
                        Key::KnotsU => ("knots_u", &mut ku),
                        _ => ("knots_v", &mut kv),
                    };
                    let v = map.next_value_seed(nums(name))?.unwrap_or_default();
                    once(slot, dst, name, v)?
                }
                Key::ControlPoints => {
                    let loc = Loc::Field("control_points");
                    let v = if self.surfaces {
                        map.next_value_seed(Net { slot, loc })?
                    } else {
                        map.next_value_seed(Points { slot, loc })?
                            .into_iter()
                            .map(|p| p.into_iter().map(Elem::N).collect())
                            .collect()
                    };
                    once(slot, &mut points, "control_points", v)?
                }
                Key::Weights => {
                    let v = if self.surfaces {
                        map.next_value_seed(Elems {
                            slot,
                            loc: Loc::Field("weights"),
                            row: None,
                            nullable: true,
                        })?
                    } else {
                        let seed = Nums {
                            slot,
                            loc: Loc::Field("weights"),
                            nullable: true,
                        };
                        map.next_value_seed(seed)?
                            .map(|w| w.into_iter().map(Elem::N).collect())
                    };
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
        let surface = du.is_some() || dv.is_some() || ku.is_some() || kv.is_some();
        let fail_with = |e| fail::<A::Error>(slot, e);
        if surface {
            if !self.allow_unknown {
                for (f, present) in [("degree", degree.is_some()), ("knots", knots.is_some())] {
                    if present {
                        return Err(fail_with(DataErr::Mixed(f, "surface")));
                    }
                }
            }
            for (f, present) in [
                ("degree_u", du.is_some()),
                ("degree_v", dv.is_some()),
                ("knots_u", ku.is_some()),
                ("knots_v", kv.is_some()),
                ("control_points", points.is_some()),
            ] {
                if !present {
                    return Err(fail_with(DataErr::MissingSurface(f)));
                }
            }
        } else {
            let missing = |f| fail::<A::Error>(slot, DataErr::Missing(f));
            degree.ok_or_else(|| missing("degree"))?;
            knots.as_ref().ok_or_else(|| missing("knots"))?;
            points.as_ref().ok_or_else(|| missing("control_points"))?;
        }
        Ok(RawCurve {
            degree,
            knots,
            degree_u: du,
            degree_v: dv,
            knots_u: ku,
            knots_v: kv,
            control_points: points.unwrap_or_default(),
            weights: weights.flatten(),
        })
    }
    reject!(text, unit, numbers, seq);
}

/// The wrong-kind element of a curve or surface array (`want_seq`: a surface wants arrays).
fn shape_error(path: String, want_seq: bool, e: &Elem) -> DataErr {
    DataErr::WrongType {
        path,
        expected: if want_seq {
            "an array of numbers (a surface's point or row of weights)"
        } else {
            "a number (a curve's coordinate or weight)"
        },
        got: match e {
            Elem::N(x) => format!("the number {x}"),
            Elem::V(_) => "an array".into(),
        },
    }
}

impl RawCurve {
    /// Split into the curve or surface fields; a wrong-kind element is a [`DataErr`].
    fn into_shape(self) -> Result<Result<Shape, InputError>, DataErr> {
        if let (Some(p), Some(knots)) = (self.degree, self.knots.clone()) {
            if self.degree_u.is_none()
                && self.degree_v.is_none()
                && self.knots_u.is_none()
                && self.knots_v.is_none()
            {
                let mut pts = Vec::with_capacity(self.control_points.len());
                for (i, row) in self.control_points.into_iter().enumerate() {
                    let mut pt = Vec::with_capacity(row.len());
                    for (j, e) in row.into_iter().enumerate() {
                        match e {
                            Elem::N(x) => pt.push(x),
                            other => {
                                return Err(shape_error(
                                    Loc::Coord(i, j).to_string(),
                                    false,
                                    &other,
                                ))
                            }
                        }
                    }
                    pts.push(pt);
                }
                let w = match self.weights {
                    None => None,
                    Some(w) => Some(
                        w.into_iter()
                            .enumerate()
                            .map(|(i, e)| match e {
                                Elem::N(x) => Ok(x),
                                other => Err(shape_error(format!("weights[{i}]"), false, &other)),
                            })
                            .collect::<Result<Vec<f64>, DataErr>>()?,
                    ),
                };
                return Ok(NurbsCurve::new(p, knots, pts, w)
                    .map(Shape::Curve)
                    .map_err(InputError::from));
            }
        }
        let mut net = Vec::with_capacity(self.control_points.len());
        for (i, row) in self.control_points.into_iter().enumerate() {
            let mut r = Vec::with_capacity(row.len());
            for (j, e) in row.into_iter().enumerate() {
                match e {
                    Elem::V(v) => r.push(v),
                    other => return Err(shape_error(Loc::Coord(i, j).to_string(), true, &other)),
                }
            }
            net.push(r);
        }
        let w = match self.weights {
            None => None,
            Some(w) => Some(
                w.into_iter()
                    .enumerate()
                    .map(|(i, e)| match e {
                        Elem::V(v) => Ok(v),
                        other => Err(shape_error(format!("weights[{i}]"), true, &other)),
                    })
                    .collect::<Result<Vec<Vec<f64>>, DataErr>>()?,
            ),
        };
        Ok(NurbsSurface::new(
            self.degree_u.unwrap_or(0),
            self.degree_v.unwrap_or(0),
            self.knots_u.unwrap_or_default(),
            self.knots_v.unwrap_or_default(),
            net,
            w,
        )
        .map(Shape::Surface)
        .map_err(InputError::from))
    }
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
/// Surface fields are unknown fields here (see [`parse_record_at`] for mixed streams).
pub fn parse_curve_at(
    bytes: &[u8],
    start: Position,
    opts: &ParseOptions,
) -> Result<NurbsCurve, InputError> {
    match parse_at(bytes, start, opts, false)? {
        Shape::Curve(c) => Ok(c),
        // unreachable: without the surface keys every object is a curve or an error
        Shape::Surface(_) => Err(InputError::UnknownField {
            field: "degree_u".into(),
            at: start,
        }),
    }
}

/// Parse one object of a mixed stream: a curve (`degree`) or a surface (`degree_u`,
/// `degree_v`, `knots_u`, `knots_v`, a net `control_points[i][j]`, optional `weights[i][j]`),
/// validated; errors name the field and position as for curves.
pub fn parse_record_at(
    bytes: &[u8],
    start: Position,
    opts: &ParseOptions,
) -> Result<Shape, InputError> {
    parse_at(bytes, start, opts, true)
}

/// [`parse_record_at`] from line 1, column 1.
pub fn parse_record(bytes: &[u8]) -> Result<Shape, InputError> {
    parse_record_at(
        bytes,
        Position { line: 1, column: 1 },
        &ParseOptions::default(),
    )
}

fn parse_at(
    bytes: &[u8],
    start: Position,
    opts: &ParseOptions,
    surfaces: bool,
) -> Result<Shape, InputError> {
    let slot = RefCell::new(None);
    let mut de = serde_json::Deserializer::from_slice(bytes);
    let seed = CurveSeed {
        slot: &slot,
        loc: Loc::Curve,
        allow_unknown: opts.allow_unknown_fields,
        surfaces,
    };
    let raw = seed
        .deserialize(&mut de)
        .and_then(|raw| de.end().map(|()| raw))
        .map_err(|e| convert_error(bytes, start, &e, slot.take()))?;
    match raw.into_shape() {
        Ok(r) => r,
        Err(d) => {
            // a shape error found after the whole object was read: positioned at its end
            let e = <serde_json::Error as de::Error>::custom("invalid curve");
            let mut err = convert_error(bytes, start, &e, Some(d));
            let end = end_position(bytes, start);
            if let InputError::WrongType { at, .. } = &mut err {
                *at = end;
            }
            Err(err)
        }
    }
}

/// The position just after the last non-whitespace byte of the record.
fn end_position(bytes: &[u8], start: Position) -> Position {
    let n = bytes
        .iter()
        .rposition(|b| !b.is_ascii_whitespace())
        .map_or(0, |i| i + 1);
    let (mut line, mut column) = (start.line, start.column);
    for &b in &bytes[..n] {
        if b == b'\n' {
            line += 1;
            column = 1;
        } else {
            column += 1;
        }
    }
    Position { line, column }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
