//! `nurbs-box remove-knot`: remove a knot from each curve as often as the tolerance allows,
//! writing the curves (and, with `--report`, what was removed and the verified error bound).

use crate::{create_report, finish_curve_command, open_input, Fatal, Outcome};
use clap::Args;
use nurbs_box::io::{write_curve, write_error_record, write_num, write_nums, CurveReader};
use std::io;
use std::path::PathBuf;

#[derive(Args, Debug)]
pub(crate) struct RemoveKnotArgs {
    /// The knot value U to remove (an interior knot of each curve).
    #[arg(long, allow_negative_numbers = true)]
    knot: f64,
    /// Remove at most N times (default: as often as possible).
    #[arg(long)]
    times: Option<usize>,
    /// Tolerance: no coordinate of the curve may move by more than T (verified), >= 0.
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    tol: f64,
    /// Write one JSON record per curve to this file: multiplicity, requested, removed and the
    /// verified per-coordinate `error_bound` of the removal.
    #[arg(long)]
    report: Option<PathBuf>,
    /// Input file (curves, JSON Lines or one JSON array), or `-` for stdin. Errors go to
    /// stderr as records with the curve's index.
    #[arg(default_value = "-")]
    input: PathBuf,
}

pub(crate) fn run(a: RemoveKnotArgs) -> Result<Outcome, Fatal> {
    if !a.knot.is_finite() {
        return Err(Fatal(format!(
            "--knot: expected a finite number, got {}",
            a.knot
        )));
    }
    if !(a.tol.is_finite() && a.tol >= 0.0) {
        return Err(Fatal(format!(
            "--tol: expected a finite number >= 0, got {}",
            a.tol
        )));
    }
    let (input, _) = open_input(&a.input)?;
    let mut report = create_report(a.report.as_ref())?;
    let res = remove_knot_stream(
        input,
        a.knot,
        a.times,
        a.tol,
        &mut io::stdout().lock(),
        &mut io::stderr(),
        report.as_mut().map(|f| f as &mut dyn io::Write),
    );
    finish_curve_command(res, report)
}

/// Read curves (either stream form
/// of `docs/formats.md`) from `input`, remove the knot `u` from each as often as
/// [`nurbs_box::NurbsCurve::remove_knot`] allows (at most `times`, default its multiplicity) within `tol`,
/// and write the resulting curves, one per line, to `out` (pipe into `enclose`). An input that
/// is not a valid curve, or whose knot cannot be removed at all (not a knot, not interior),
/// gets an error record on `err` and no curve. When `report` is given, one line per curve
/// goes there: `{"index":i,"knot":u,"multiplicity":s,"requested":N,"removed":k,
/// "error_bound":[...]}` (a verified bound per coordinate on how far the curve moved).
/// Returns `Ok(true)` when every input gave a curve.
fn remove_knot_stream<R: io::Read, W: io::Write, E: io::Write>(
    input: R,
    u: f64,
    times: Option<usize>,
    tol: f64,
    out: &mut W,
    err: &mut E,
    mut report: Option<&mut dyn io::Write>,
) -> io::Result<bool> {
    let mut all_ok = true;
    for (index, curve) in CurveReader::new(input) {
        let mut line = Vec::new();
        let res = curve.map_err(|e| (e.kind(), e.to_string())).and_then(|c| {
            c.remove_knot(u, times.unwrap_or(usize::MAX), tol)
                .map_err(|e| (e.kind(), e.to_string()))
        });
        match res {
            Ok(rem) => {
                write_curve(&mut line, &rem.curve);
                line.push(b'\n');
                out.write_all(&line)?;
                if let Some(rep) = report.as_deref_mut() {
                    line.clear();
                    line.extend_from_slice(format!("{{\"index\":{index},\"knot\":").as_bytes());
                    write_num(&mut line, u);
                    line.extend_from_slice(
                        format!(
                            ",\"multiplicity\":{},\"requested\":{},\"removed\":{},\"error_bound\":",
                            rem.multiplicity, rem.requested, rem.removed
                        )
                        .as_bytes(),
                    );
                    write_nums(&mut line, rem.error_bound.iter().copied());
                    line.extend_from_slice(b"}\n");
                    rep.write_all(&line)?;
                }
            }
            Err((kind, message)) => {
                all_ok = false;
                write_error_record(&mut line, index, "", kind, &message);
                line.push(b'\n');
                err.write_all(&line)?;
            }
        }
    }
    Ok(all_ok)
}
