//! `nurbs-box`: verified box enclosures of NURBS curves from the command line.
//!
//! The formats and exit statuses are the contract of `docs/formats.md`:
//! exit 0 when every curve got its records, 1 when some curve got an error record, 2 when the
//! command itself could not run (bad flag, unreadable input, write failure).
//!
//! The library keeps the algorithms and their typed results; this binary does the argument
//! parsing, the reading, the writing of records and the exit codes, one module per
//! subcommand ([`enclose`], [`eval`], [`interpolate`], [`remove_knot`], [`font`], [`serve`]).
//!
//! Adding a subcommand: a module with its `Args` struct and a `run` function returning
//! `Result<Outcome, Fatal>`, and one variant in [`Command`]; the shared input/threads flags are
//! [`InputArgs`], and [`run_stream`] runs a per-curve closure over the input in parallel.

mod enclose;
mod eval;
#[cfg(feature = "font")]
mod font;
mod interpolate;
mod remove_knot;
#[cfg(feature = "serve")]
mod serve;

use clap::{Args, Parser, Subcommand};
use nurbs_box::enclose::STRATEGY_NAMES;
use nurbs_box::io::batch::{process_shapes, StreamError, StreamOptions, StreamSummary};
use nurbs_box::io::{InputError, ParseOptions, Shape};
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
    Eval(eval::EvalArgs),
    /// Box enclosures of whole curves.
    Enclose(enclose::EncloseArgs),
    /// Cubic spline or Lagrange interpolants of point sets, written as curves (pipe into `enclose`).
    Interpolate(interpolate::InterpolateArgs),
    /// Remove a knot as often as the curve allows within a tolerance; writes the curves.
    RemoveKnot(remove_knot::RemoveKnotArgs),
    /// Verified glyph boxes of a TrueType/OpenType font vs the boxes the font stores.
    #[cfg(feature = "font")]
    Font(font::FontArgs),
    /// Serve the interactive page (edit a curve, watch its verified box) and its JSON API on
    /// 127.0.0.1.
    #[cfg(feature = "serve")]
    Serve(serve::ServeArgs),
}

/// Flags shared by the subcommands that read a stream of curves.
#[derive(Args, Debug)]
pub(crate) struct InputArgs {
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

/// How a command that ran to its end went.
pub(crate) enum Outcome {
    /// every curve got its records
    AllOk,
    /// some curve got an error record
    SomeErrors,
}

/// Why a command could not run (exit status 2).
pub(crate) struct Fatal(pub(crate) String);

impl From<StreamError> for Fatal {
    fn from(e: StreamError) -> Self {
        Fatal(e.to_string())
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse(); // usage errors exit with status 2 (clap's convention)
    let result = match cli.command {
        Command::Eval(a) => eval::run(a),
        Command::Enclose(a) => enclose::run(a),
        Command::Interpolate(a) => interpolate::run(a),
        Command::RemoveKnot(a) => remove_knot::run(a),
        #[cfg(feature = "font")]
        Command::Font(a) => font::run(a),
        #[cfg(feature = "serve")]
        Command::Serve(a) => serve::run(a),
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
pub(crate) fn open_input(path: &PathBuf) -> Result<(Box<dyn Read + Send>, Option<u64>), Fatal> {
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
/// `group`: process each chunk grouped by kind of curve (`StreamOptions::group`; the output
/// order is the input order either way).
pub(crate) fn run_stream<F>(args: &InputArgs, group: bool, work: F) -> Result<Outcome, Fatal>
where
    F: Fn(usize, Result<Shape, InputError>, &mut Vec<u8>) -> bool + Sync,
{
    let (input, total_bytes) = open_input(&args.input)?;
    let opts = StreamOptions {
        group,
        threads: args.threads,
        progress: !args.no_progress,
        total_bytes,
        parse: ParseOptions {
            allow_unknown_fields: args.allow_unknown_fields,
            ..ParseOptions::default()
        },
        ..StreamOptions::default()
    };
    match process_shapes(input, io::stdout().lock(), &opts, work) {
        Ok(StreamSummary { failed: 0, .. }) => Ok(Outcome::AllOk),
        Ok(_) => Ok(Outcome::SomeErrors),
        // The reader of our output went away (`| head`): stop quietly.
        Err(StreamError::Write(e)) if e.kind() == io::ErrorKind::BrokenPipe => {
            Err(Fatal(String::new()))
        }
        Err(e) => Err(e.into()),
    }
}

/// The default strategy: the thesis's interval Newton when it is built in.
pub(crate) fn default_strategy() -> &'static str {
    if STRATEGY_NAMES.contains(&"newton") {
        "newton"
    } else {
        STRATEGY_NAMES[0]
    }
}

/// `--report FILE` of the curve-writing commands.
pub(crate) fn create_report(path: Option<&PathBuf>) -> Result<Option<io::BufWriter<File>>, Fatal> {
    path.map(|p| {
        File::create(p)
            .map(io::BufWriter::new)
            .map_err(|e| Fatal(format!("--report: cannot create {}: {e}", p.display())))
    })
    .transpose()
}

/// Exit status of a command that writes curves to stdout and error records to stderr.
pub(crate) fn finish_curve_command(
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
