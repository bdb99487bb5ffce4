//! `nurbs-box interpolate`: cubic spline or Lagrange interpolants of point sets, written as
//! curves (pipe into `enclose`), with error records on stderr and an optional `--report`.

use crate::{create_report, finish_curve_command, open_input, Fatal, Outcome};
use clap::Args;
use nurbs_box::build::interpolate::{
    interpolate_cubic_with, InterpolationOptions, Parametrization,
};
use nurbs_box::build::lagrange::{LagrangeBezier, LagrangeCurve, LagrangeError};
use nurbs_box::io::{write_curve, write_error_record, write_nums};
use nurbs_box::NurbsCurve;
use std::io;
use std::path::PathBuf;

#[derive(Args, Debug)]
pub(crate) struct InterpolateArgs {
    /// Parametrisation: uniform, chordal, centripetal or foley (2-D only).
    #[arg(long, default_value = "chordal")]
    param: String,
    /// Interpolant: `cubic` (natural cubic spline) or `lagrange` (one polynomial of degree
    /// points - 1 through all points, written as one Bézier segment; see `--report`).
    #[arg(long, default_value = "cubic", value_parser = ["cubic", "lagrange"])]
    basis: String,
    /// Write one JSON record per converted point set to this file: for `lagrange` the
    /// parameters and `coefficient_radius`, the per-coordinate amount by which a verified box
    /// of the written curve must be widened to enclose the exact Lagrange curve.
    #[arg(long)]
    report: Option<PathBuf>,
    /// Point sets: a JSON array of points, a JSON array of point sets, or JSON Lines with one
    /// point set per line; `-` for stdin. Errors go to stderr as records with the set's index.
    #[arg(default_value = "-")]
    input: PathBuf,
}

pub(crate) fn run(a: InterpolateArgs) -> Result<Outcome, Fatal> {
    let param: Parametrization = a.param.parse().map_err(|e| Fatal(format!("--{e}")))?;
    let (input, _) = open_input(&a.input)?;
    let mut report = create_report(a.report.as_ref())?;
    let (out, err) = (&mut io::stdout().lock(), &mut io::stderr());
    // one report line per converted set, written to `--report` once the curves are out
    let mut rep = Vec::new();
    let res = match a.basis.as_str() {
        "lagrange" => convert_point_sets(input, out, err, |i, pts| {
            let fail = |e: LagrangeError| (e.kind(), e.to_string());
            let lc = LagrangeCurve::interpolate(pts, param).map_err(fail)?;
            let lb = lc.to_bezier().map_err(fail)?;
            write_lagrange_report(&mut rep, i, &lc, &lb);
            rep.push(b'\n');
            Ok(lb.curve)
        }),
        _ => convert_point_sets(input, out, err, |i, pts| {
            let opts = InterpolationOptions {
                param,
                ..Default::default()
            };
            let it = interpolate_cubic_with(pts, &opts).map_err(|e| (e.kind(), e.to_string()))?;
            rep.extend_from_slice(
                format!("{{\"index\":{i},\"basis\":\"cubic\",\"params\":").as_bytes(),
            );
            write_nums(&mut rep, it.params.iter().copied());
            rep.extend_from_slice(b"}\n");
            Ok(it.curve)
        }),
    };
    let res = match report.as_mut() {
        Some(f) => res.and_then(|ok| io::Write::write_all(f, &rep).map(|()| ok)),
        None => res,
    };
    finish_curve_command(res, report)
}

/// One report record of `--basis lagrange --report FILE` (no newline):
/// `{"index":i,"basis":"lagrange","degree":g,"params":[...],"coefficient_radius":[...]}`; the
/// `coefficient_radius` is what a box of the written curve must be widened by (see
/// [`nurbs_box::build::lagrange::widen_enclosure`]) to enclose the Lagrange curve itself.
fn write_lagrange_report(out: &mut Vec<u8>, index: usize, lc: &LagrangeCurve, lb: &LagrangeBezier) {
    out.extend_from_slice(
        format!(
            "{{\"index\":{index},\"basis\":\"lagrange\",\"degree\":{},\"params\":",
            lc.degree()
        )
        .as_bytes(),
    );
    write_nums(out, lc.params().iter().copied());
    out.extend_from_slice(b",\"coefficient_radius\":");
    write_nums(out, lb.radius.iter().copied());
    out.push(b'}');
}

/// One point set of the input: the points, or why the input could not be read as one
/// (error kind, message).
type PointSetInput = Result<Vec<Vec<f64>>, (&'static str, String)>;

/// Read point sets: a JSON array of points (one point set, e.g. `[[0,0],[1,2],[3,1]]`), a JSON
/// array of such arrays (several sets), or JSON Lines with one point set per line (blank lines
/// skipped). Point sets are numbered from 0 in input order.
fn parse_point_sets(text: &str) -> Vec<PointSetInput> {
    use serde_json::Value;
    fn to_points(v: &Value) -> PointSetInput {
        let bad = |m: String| Err(("invalid_points", m));
        let Some(arr) = v.as_array() else {
            return bad("points: expected a JSON array of points (arrays of numbers)".into());
        };
        let mut out = Vec::with_capacity(arr.len());
        for (i, p) in arr.iter().enumerate() {
            let Some(coords) = p.as_array() else {
                return bad(format!(
                    "points[{i}]: expected an array of numbers, got {p}"
                ));
            };
            let mut q = Vec::with_capacity(coords.len());
            for (j, x) in coords.iter().enumerate() {
                match x.as_f64() {
                    Some(f) => q.push(f),
                    None => return bad(format!("points[{i}][{j}]: expected a number, got {x}")),
                }
            }
            out.push(q);
        }
        Ok(out)
    }
    // A list of point sets has arrays at depth 3: [[[x, y], ...], ...].
    let is_list = |v: &Value| {
        v.as_array()
            .and_then(|a| a.first())
            .and_then(|p| p.as_array())
            .and_then(|p| p.first())
            .is_some_and(|x| x.is_array())
    };
    let text = text.trim();
    if text.is_empty() {
        return Vec::new();
    }
    if let Ok(v) = serde_json::from_str::<Value>(text) {
        return if is_list(&v) {
            v.as_array().unwrap().iter().map(to_points).collect()
        } else {
            vec![to_points(&v)]
        };
    }
    // JSON Lines: one point set per non-blank line; a malformed line keeps its index.
    text.lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| match serde_json::from_str::<Value>(l) {
            Ok(v) => to_points(&v),
            Err(e) => Err(("invalid_json", format!("line is not valid JSON: {e}"))),
        })
        .collect()
}

/// Read point sets (see [`parse_point_sets`]) from `input`, build a curve from each with
/// `build(index, points)` and write it as one curve line (the curve JSON of
/// `docs/formats.md`) to `out`, so the output can be piped into `nurbs-box enclose`. A set
/// that cannot be read or converted produces no curve on `out` but a record
/// `{"index": i, "error": {"kind": ..., "message": ...}}` on `err` (keeping `out` a pure curve
/// stream). Returns `Ok(true)` when every set gave a curve.
fn convert_point_sets<R: io::Read, W: io::Write, E: io::Write>(
    mut input: R,
    out: &mut W,
    err: &mut E,
    mut build: impl FnMut(usize, &[Vec<f64>]) -> Result<NurbsCurve, (&'static str, String)>,
) -> io::Result<bool> {
    let mut text = String::new();
    input.read_to_string(&mut text)?;
    let mut all_ok = true;
    for (i, set) in parse_point_sets(&text).into_iter().enumerate() {
        let res = set.and_then(|pts| build(i, &pts));
        let mut line = Vec::new();
        match res {
            Ok(c) => {
                write_curve(&mut line, &c);
                line.push(b'\n');
                out.write_all(&line)?;
            }
            Err((kind, message)) => {
                all_ok = false;
                write_error_record(&mut line, i, "", kind, &message);
                line.push(b'\n');
                err.write_all(&line)?;
            }
        }
    }
    Ok(all_ok)
}
