//! `nurbs-box`: verified box enclosures of NURBS curves from the command line.
//!
//! The formats and exit statuses are the contract of `docs/formats.md`:
//! exit 0 when every curve got its records, 1 when some curve got an error record, 2 when the
//! command itself could not run (bad flag, unreadable input, write failure).
//!
//! Adding a subcommand: one variant in [`Command`] (with its `Args` struct) and one `run_*`
//! function returning `Result<Outcome, Fatal>`; the shared input/threads flags are
//! [`InputArgs`], and [`run_stream`] runs a per-curve closure over the input in parallel.

use clap::{Args, Parser, Subcommand};
use nurbs_box::enclose::{strategy_by_name, BoxEncloser, STRATEGY_NAMES};
use nurbs_box::io::batch::{
    enclose_records, input_error_line, process_stream, StreamError, StreamOptions, StreamSummary,
};
use nurbs_box::io::{eval_fields, write_error_record, write_eval_record, InputError, ParseOptions};
use nurbs_box::num::iv;
use nurbs_box::{NurbsCurve, TightEval};
use std::fs::File;
use std::io::{self, Read};
use std::path::PathBuf;
use std::process::ExitCode;

/// Verified, optimal axis-aligned box enclosures of NURBS curves.
///
/// Input: a file or `-` (stdin) holding JSON Lines (one curve per line) or one JSON array of
/// curves. Output: JSON Lines on stdout, one record per curve (and strategy / parameter).
#[derive(Parser, Debug)]
#[command(name = "nurbs-box", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Verified enclosures of points C(U) or derivatives C^(K)(U).
    Eval(EvalArgs),
    /// Box enclosures of whole curves.
    Enclose(EncloseArgs),
    /// Cubic spline or Lagrange interpolants of point sets, written as curves (pipe into `enclose`).
    Interpolate(InterpolateArgs),
    /// Remove a knot as often as the curve allows within a tolerance; writes the curves.
    RemoveKnot(RemoveKnotArgs),
    /// Verified glyph boxes of a TrueType/OpenType font vs the boxes the font stores.
    Font(FontArgs),
    /// Serve the interactive page (edit a curve, watch its verified box) and its JSON API on
    /// 127.0.0.1.
    #[cfg(feature = "serve")]
    Serve(ServeArgs),
}

#[cfg(feature = "serve")]
#[derive(Args, Debug)]
struct ServeArgs {
    /// TCP port (default: a free one; the address is printed on start).
    #[arg(long, default_value_t = 0)]
    port: u16,
}

#[derive(Args, Debug)]
struct InterpolateArgs {
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

#[derive(Args, Debug)]
struct RemoveKnotArgs {
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

#[derive(Args, Debug)]
struct FontArgs {
    /// The font file (.ttf / .otf).
    file: PathBuf,
    /// Strategy name (default as for `enclose`).
    #[arg(long)]
    strategy: Option<String>,
    /// Tolerance of the iterative strategies.
    #[arg(long, allow_negative_numbers = true)]
    tol: Option<f64>,
}

/// Flags shared by the subcommands that read a stream of curves.
#[derive(Args, Debug)]
struct InputArgs {
    /// Input file, or `-` for stdin.
    #[arg(default_value = "-")]
    input: PathBuf,
    /// Worker threads (0 = one per core).
    #[arg(long, default_value_t = 0)]
    threads: usize,
    /// Ignore unknown fields in curve objects instead of rejecting the curve.
    #[arg(long)]
    allow_unknown_fields: bool,
    /// Never show a progress bar (it is shown only when stderr is a terminal anyway).
    #[arg(long)]
    no_progress: bool,
}

#[derive(Args, Debug)]
struct EvalArgs {
    /// Parameter value U (repeatable); must be finite.
    #[arg(long = "param", required = true, allow_negative_numbers = true)]
    params: Vec<f64>,
    /// Derivative order K (0 = the point itself). At most 50: the rational-derivative formula
    /// uses binomial coefficients that must be exact in f64.
    #[arg(long, default_value_t = 0, value_parser = clap::value_parser!(u8).range(0..=50))]
    derivative: u8,
    #[command(flatten)]
    input: InputArgs,
}

#[derive(Args, Debug)]
struct EncloseArgs {
    /// Strategy name, or `all` for one record per strategy (default: newton if built in,
    /// otherwise the first registered strategy).
    #[arg(long)]
    strategy: Option<String>,
    /// Tolerance of the iterative strategies (finite, > 0; default: each strategy's own).
    #[arg(long, allow_negative_numbers = true)]
    tol: Option<f64>,
    /// Add time_total_s / time_derivatives_s to the stats (makes output non-reproducible).
    #[arg(long)]
    timings: bool,
    #[command(flatten)]
    input: InputArgs,
}

/// How a command that ran to its end went.
enum Outcome {
    /// every curve got its records
    AllOk,
    /// some curve got an error record
    SomeErrors,
}

/// Why a command could not run (exit status 2).
struct Fatal(String);

impl From<StreamError> for Fatal {
    fn from(e: StreamError) -> Self {
        Fatal(e.to_string())
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse(); // usage errors exit with status 2 (clap's convention)
    let result = match cli.command {
        Command::Eval(a) => run_eval(a),
        Command::Enclose(a) => run_enclose(a),
        Command::Interpolate(a) => run_interpolate(a),
        Command::RemoveKnot(a) => run_remove_knot(a),
        Command::Font(a) => run_font(a),
        #[cfg(feature = "serve")]
        Command::Serve(a) => run_serve(a),
    };
    match result {
        Ok(Outcome::AllOk) => ExitCode::SUCCESS,
        Ok(Outcome::SomeErrors) => ExitCode::from(1),
        Err(Fatal(msg)) => {
            if !msg.is_empty() {
                eprintln!("nurbs-box: {msg}");
            }
            ExitCode::from(2)
        }
    }
}

/// Open the input (`-` = stdin); also returns its size when it is a regular file.
fn open_input(path: &PathBuf) -> Result<(Box<dyn Read + Send>, Option<u64>), Fatal> {
    if path.as_os_str() == "-" {
        return Ok((Box::new(io::stdin()), None));
    }
    let f = File::open(path).map_err(|e| Fatal(format!("cannot open {}: {e}", path.display())))?;
    let meta = f
        .metadata()
        .map_err(|e| Fatal(format!("cannot open {}: {e}", path.display())))?;
    if meta.is_dir() {
        return Err(Fatal(format!(
            "cannot read {}: it is a directory",
            path.display()
        )));
    }
    let size = meta.is_file().then_some(meta.len());
    Ok((Box::new(f), size))
}

/// Run `work` on every curve of the input in parallel, writing to stdout in input order.
fn run_stream<F>(args: &InputArgs, work: F) -> Result<Outcome, Fatal>
where
    F: Fn(usize, Result<NurbsCurve, InputError>, &mut Vec<u8>) -> bool + Sync,
{
    let (input, total_bytes) = open_input(&args.input)?;
    let opts = StreamOptions {
        threads: args.threads,
        progress: !args.no_progress,
        total_bytes,
        parse: ParseOptions {
            allow_unknown_fields: args.allow_unknown_fields,
            ..ParseOptions::default()
        },
        ..StreamOptions::default()
    };
    match process_stream(input, io::stdout().lock(), &opts, work) {
        Ok(StreamSummary { failed: 0, .. }) => Ok(Outcome::AllOk),
        Ok(_) => Ok(Outcome::SomeErrors),
        // The reader of our output went away (`| head`): stop quietly.
        Err(StreamError::Write(e)) if e.kind() == io::ErrorKind::BrokenPipe => {
            Err(Fatal(String::new()))
        }
        Err(e) => Err(e.into()),
    }
}

fn run_eval(a: EvalArgs) -> Result<Outcome, Fatal> {
    if let Some(u) = a.params.iter().find(|u| !u.is_finite()) {
        return Err(Fatal(format!("--param: expected a finite number, got {u}")));
    }
    let k = usize::from(a.derivative);
    run_stream(&a.input, |index, curve, buf| {
        let c = match curve {
            Ok(c) => c,
            Err(e) => {
                input_error_line(index, &e, buf);
                return false;
            }
        };
        // K = 0: the double-double evaluator gives ~1-ulp boxes (src/tight.rs); built once
        // per curve, only when needed.
        let tight = (k == 0).then(|| TightEval::new(&c));
        let mut ok = true;
        for &u in &a.params {
            // Verified: interval de Boor on the exact f64 parameter (eval.rs); it also checks
            // the domain. For K = 0 it is intersected with the TightEval enclosure: both contain
            // the exact value, so their intersection does too.
            match c.enclose_derivative(iv::point(u), k) {
                Ok(mut v) => {
                    if let Some(t) = &tight {
                        for (x, y) in v.iter_mut().zip(t.point(u)) {
                            *x = x.intersection(y);
                        }
                    }
                    write_eval_record(buf, index, u, k, &v)
                }
                Err(e) => {
                    ok = false;
                    write_error_record(buf, index, &eval_fields(u, k), e.kind(), &e.to_string());
                }
            }
            buf.push(b'\n');
        }
        ok
    })
}

/// The default strategy: the thesis's interval Newton when it is built in.
fn default_strategy() -> &'static str {
    if STRATEGY_NAMES.contains(&"newton") {
        "newton"
    } else {
        STRATEGY_NAMES[0]
    }
}

fn run_enclose(a: EncloseArgs) -> Result<Outcome, Fatal> {
    if let Some(t) = a.tol {
        if !(t.is_finite() && t > 0.0) {
            return Err(Fatal(format!(
                "--tol: expected a finite number > 0, got {t}"
            )));
        }
    }
    let name = a.strategy.as_deref().unwrap_or_else(|| default_strategy());
    let names: Vec<&str> = if name == "all" {
        STRATEGY_NAMES.to_vec()
    } else {
        vec![name]
    };
    let strategies: Vec<Box<dyn BoxEncloser>> = names
        .iter()
        .map(|n| {
            strategy_by_name(n, a.tol).ok_or_else(|| {
                Fatal(format!(
                    "unknown strategy {n:?}; known strategies: {}, all",
                    STRATEGY_NAMES.join(", ")
                ))
            })
        })
        .collect::<Result<_, _>>()?;
    let timings = a.timings;
    run_stream(&a.input, |index, curve, buf| {
        enclose_records(index, curve, &strategies, timings, buf)
    })
}

fn run_interpolate(a: InterpolateArgs) -> Result<Outcome, Fatal> {
    let param: nurbs_box::build::interpolate::Parametrization =
        a.param.parse().map_err(|e| Fatal(format!("--{e}")))?;
    let (input, _) = open_input(&a.input)?;
    let mut report = create_report(a.report.as_ref())?;
    let (out, err) = (&mut io::stdout().lock(), &mut io::stderr());
    let res = match a.basis.as_str() {
        "lagrange" => nurbs_box::build::lagrange::run_cli(
            input,
            param,
            out,
            err,
            report.as_mut().map(|f| f as &mut dyn io::Write),
        ),
        _ => {
            let mut rep = Vec::new();
            let res = nurbs_box::build::interpolate::run_cli_with(input, out, err, |i, pts| {
                let opts = nurbs_box::build::interpolate::InterpolationOptions {
                    param,
                    ..Default::default()
                };
                let it = nurbs_box::build::interpolate::interpolate_cubic_with(pts, &opts)
                    .map_err(|e| (e.kind(), e.to_string()))?;
                rep.extend_from_slice(
                    format!("{{\"index\":{i},\"basis\":\"cubic\",\"params\":").as_bytes(),
                );
                nurbs_box::io::write_nums(&mut rep, it.params.iter().copied());
                rep.extend_from_slice(b"}\n");
                Ok(it.curve)
            });
            match report.as_mut() {
                Some(f) => res.and_then(|ok| io::Write::write_all(f, &rep).map(|()| ok)),
                None => res,
            }
        }
    };
    finish_curve_command(res, report)
}

/// `--report FILE` of the curve-writing commands.
fn create_report(path: Option<&PathBuf>) -> Result<Option<io::BufWriter<File>>, Fatal> {
    path.map(|p| {
        File::create(p)
            .map(io::BufWriter::new)
            .map_err(|e| Fatal(format!("--report: cannot create {}: {e}", p.display())))
    })
    .transpose()
}

/// Exit status of a command that writes curves to stdout and error records to stderr.
fn finish_curve_command(
    res: io::Result<bool>,
    report: Option<io::BufWriter<File>>,
) -> Result<Outcome, Fatal> {
    let res = res.and_then(|ok| {
        if let Some(mut f) = report {
            io::Write::flush(&mut f)?;
        }
        Ok(ok)
    });
    match res {
        Ok(true) => Ok(Outcome::AllOk),
        Ok(false) => Ok(Outcome::SomeErrors),
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => Err(Fatal(String::new())),
        Err(e) => Err(Fatal(e.to_string())),
    }
}

fn run_remove_knot(a: RemoveKnotArgs) -> Result<Outcome, Fatal> {
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
    let res = nurbs_box::spline::knot_removal::run_cli(
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

fn run_font(a: FontArgs) -> Result<Outcome, Fatal> {
    let name = a.strategy.as_deref().unwrap_or_else(|| default_strategy());
    let strategy = strategy_by_name(name, a.tol).ok_or_else(|| {
        Fatal(format!(
            "unknown strategy {name:?}; known strategies: {}",
            STRATEGY_NAMES.join(", ")
        ))
    })?;
    let bytes = std::fs::read(&a.file)
        .map_err(|e| Fatal(format!("cannot read {}: {e}", a.file.display())))?;
    nurbs_box::font::run_cli(&bytes, strategy.as_ref(), &mut io::stdout().lock())
        .map(|()| Outcome::AllOk)
        .map_err(|e| match e.downcast_ref::<io::Error>() {
            // the reader of our output went away (`| head`): stop quietly
            Some(io) if io.kind() == io::ErrorKind::BrokenPipe => Fatal(String::new()),
            _ => Fatal(e.to_string()),
        })
}

#[cfg(feature = "serve")]
fn run_serve(a: ServeArgs) -> Result<Outcome, Fatal> {
    use nurbs_box::serve::{Limits, Server};
    use std::io::Write;
    let server = Server::bind(a.port, Limits::default())
        .map_err(|e| Fatal(format!("cannot listen on 127.0.0.1:{}: {e}", a.port)))?;
    let mut out = io::stdout().lock();
    writeln!(out, "nurbs-box serve: {} (Ctrl-C stops it)", server.url())
        .and_then(|()| out.flush())
        .map_err(|e| Fatal(e.to_string()))?;
    drop(out);
    server.run();
    Ok(Outcome::AllOk)
}
