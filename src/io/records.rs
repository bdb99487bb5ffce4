//! Output records: curves in the input format ([`curve_to_json`], [`write_curve`]), the
//! `enclose` / `eval` / error records of the command line, and their number formatting.

use crate::enclose::{Enclosure, Termination};
use crate::spline::curve::NurbsCurve;
use inari::Interval;

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
/// `{"index","strategy","verified","lo","hi","inner_lo","inner_hi","optimal_lo","optimal_hi",
/// "stats":{...}}` (`optimal_*`: the certificates of `enclose::certify`, one boolean per
/// coordinate).
/// With `timings`, stats also has `time_total_s` and `time_derivatives_s` (off by default so
/// that output is reproducible).
pub fn write_enclosure_record(out: &mut Vec<u8>, index: usize, e: &Enclosure, timings: bool) {
    use std::io::Write as _;
    // (written into `out` directly: no allocation per record; writing to a Vec cannot fail)
    let _ = write!(out, "{{\"index\":{index},\"strategy\":");
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
    out.extend_from_slice(b",\"optimal_lo\":");
    write_bools(out, e.coords.iter().map(|c| c.optimal_lo));
    out.extend_from_slice(b",\"optimal_hi\":");
    write_bools(out, e.coords.iter().map(|c| c.optimal_hi));
    let s = e.stats();
    let _ = write!(
        out,
        ",\"stats\":{{\"newton_iterations\":{},\"derivative_evaluations\":{},\
         \"point_evaluations\":{},\"subdivisions\":{},\"termination\":\"{}\"",
        s.newton_iterations,
        s.derivative_evaluations,
        s.point_evaluations,
        s.subdivisions,
        termination_name(e.termination())
    );
    if timings {
        out.extend_from_slice(b",\"time_total_s\":");
        write_num(out, s.time_total.as_secs_f64());
        out.extend_from_slice(b",\"time_derivatives_s\":");
        write_num(out, s.time_derivatives.as_secs_f64());
    }
    out.extend_from_slice(b"}}");
}

/// Append a JSON array of booleans.
fn write_bools(out: &mut Vec<u8>, xs: impl Iterator<Item = bool>) {
    out.push(b'[');
    for (i, x) in xs.enumerate() {
        if i > 0 {
            out.push(b',');
        }
        out.extend_from_slice(if x { b"true" } else { b"false" });
    }
    out.push(b']');
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
    write_lo_hi(out, value);
}

/// The `lo` array (already opened), `"hi"` and the closing brace of an eval record.
fn write_lo_hi(out: &mut Vec<u8>, value: &[Interval]) {
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

/// Append a surface `eval` record (no newline):
/// `{"index","param":[U,V],"derivative":[K,L],"lo","hi"}` from the enclosure `value` of
/// d^(K+L) S / du^K dv^L at (U, V).
pub fn write_surface_eval_record(
    out: &mut Vec<u8>,
    index: usize,
    param: (f64, f64),
    derivative: (usize, usize),
    value: &[Interval],
) {
    out.extend_from_slice(format!("{{\"index\":{index},").as_bytes());
    out.extend_from_slice(surface_eval_fields(param, derivative).as_bytes());
    out.extend_from_slice(b",\"lo\":");
    write_lo_hi(out, value);
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

/// The `"param":[U,V],"derivative":[K,L]` fields of surface eval records.
pub fn surface_eval_fields(param: (f64, f64), derivative: (usize, usize)) -> String {
    let mut out = b"\"param\":".to_vec();
    write_nums(&mut out, [param.0, param.1]);
    out.extend_from_slice(
        format!(",\"derivative\":[{},{}]", derivative.0, derivative.1).as_bytes(),
    );
    String::from_utf8(out).expect("ASCII")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::enclose::BoxEncloser;
    use crate::io::parse_curve;

    const GOOD: &str = r#"{"degree": 3, "knots": [0, 0, 0, 0, 0.5, 1, 1, 1, 1], "control_points": [[0, 0], [1, 2], [2, -1], [3, 3], [4, 0]], "weights": [1, 1, 2, 1, 1]}"#;

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
