//! Many curves at once: [`enclose_batch`] for curves in memory, and [`process_stream`], the
//! bounded-memory parallel pipeline behind the command line.
//!
//! The pipeline reads a chunk of raw records (at most [`StreamOptions::chunk_size`] curves and
//! about [`StreamOptions::chunk_bytes`] bytes), then parses, processes and formats the chunk's
//! records in parallel on a rayon pool, then writes their output in input order. Only the
//! splitting of the input into records and the writing are sequential, so the work (parsing
//! included) scales with the threads; memory is bounded by one chunk whatever the input size.
//! With [`StreamOptions::group`] a chunk is parsed first and its records are processed grouped
//! by kind of curve ([`kind_key`]), their output still written in input order.

use crate::enclose::{BoxEncloser, Enclosure};
use crate::io::Shape;
use crate::io::{
    write_enclosure_record, write_error_record, InputError, ParseOptions, RawRecord, RecordReader,
};
use crate::spline::curve::NurbsCurve;
use crate::surface::SurfaceEncloser;
use rayon::prelude::*;
use std::io::{self, Read, Write};
use thiserror::Error;

/// A rayon pool with `threads` threads (0: one per core).
pub fn thread_pool(threads: usize) -> Result<rayon::ThreadPool, StreamError> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| StreamError::ThreadPool(e.to_string()))
}

/// Enclose every curve with `strategy`, in parallel on `threads` threads (0: rayon's global
/// pool, one thread per core). The result is in the order of `curves`. If a pool of the
/// requested size cannot be created the work runs on the global pool instead (same results).
pub fn enclose_batch(
    curves: &[NurbsCurve],
    strategy: &dyn BoxEncloser,
    threads: usize,
) -> Vec<Enclosure> {
    let run = || curves.par_iter().map(|c| strategy.enclose(c)).collect();
    match (threads > 0).then(|| thread_pool(threads)) {
        Some(Ok(pool)) => pool.install(run),
        _ => run(),
    }
}

/// Settings of [`process_stream`].
#[derive(Debug, Clone)]
pub struct StreamOptions {
    /// most curves per chunk (default 4096)
    pub chunk_size: usize,
    /// a chunk is closed once it holds this many input bytes (default 64 MiB)
    pub chunk_bytes: usize,
    /// worker threads (0: one per core)
    pub threads: usize,
    /// show a progress bar on stderr (only if stderr is a terminal)
    pub progress: bool,
    /// input size in bytes, if known (progress bar length)
    pub total_bytes: Option<u64>,
    /// parser options
    pub parse: ParseOptions,
    /// Process the records of a chunk grouped by kind of curve ([`kind_key`]: single Bézier
    /// segments of degree <= 3 first, then by weights, degree, dimension and number of
    /// control points; input order within a kind), after parsing the whole chunk; the output
    /// order is the input order either way. Curves of one kind take the same code paths with
    /// the same loop counts, so a search strategy meets them with its branch predictors and
    /// instruction caches warm: on a mixed batch (the speed report's) the `newton` and
    /// `bezier` commands take ~6% less time. For `hull` alone, whose work per curve is a scan of
    /// the control points, it costs ~2% (the parsed curves are then visited out of memory
    /// order), so the command line groups unless `hull` is the only strategy. Default off.
    pub group: bool,
}

impl Default for StreamOptions {
    fn default() -> Self {
        StreamOptions {
            chunk_size: 4096,
            chunk_bytes: 64 << 20,
            threads: 0,
            progress: false,
            total_bytes: None,
            parse: ParseOptions::default(),
            group: false,
        }
    }
}

/// Counts of a finished stream.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct StreamSummary {
    /// input curves (records) seen
    pub curves: u64,
    /// curves for which at least one error record was written
    pub failed: u64,
}

/// Why a stream could not be processed to its end (as opposed to a bad curve, which is an
/// error record in the output).
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum StreamError {
    /// reading the input failed
    #[error("cannot read the input: {0}")]
    Read(String),
    /// writing the output failed
    #[error("cannot write the output: {0}")]
    Write(#[from] io::Error),
    /// the worker threads could not be started
    #[error("cannot start worker threads: {0}")]
    ThreadPool(String),
}

/// Run `work` on every curve of `input` (either stream form) and write what it produces to
/// `out`, in input order.
///
/// `work(index, curve_or_error, buf)` appends its output records (each ending in `\n`) to `buf`
/// and returns whether the curve was handled without error. It runs in parallel, so it must be
/// `Sync`. The output of a chunk is flushed before the next chunk is read.
pub fn process_stream<R, W, F>(
    input: R,
    out: W,
    opts: &StreamOptions,
    work: F,
) -> Result<StreamSummary, StreamError>
where
    R: Read,
    W: Write,
    F: Fn(usize, Result<NurbsCurve, InputError>, &mut Vec<u8>) -> bool + Sync,
{
    process_with(input, out, opts, RawRecord::parse, work, |r| {
        r.as_ref().map_or(u64::MAX, kind_key)
    })
}

/// [`process_stream`] for a mixed stream of curves and surfaces: `work` gets each record as a
/// [`Shape`] ([`RawRecord::parse_shape`]).
pub fn process_shapes<R, W, F>(
    input: R,
    out: W,
    opts: &StreamOptions,
    work: F,
) -> Result<StreamSummary, StreamError>
where
    R: Read,
    W: Write,
    F: Fn(usize, Result<Shape, InputError>, &mut Vec<u8>) -> bool + Sync,
{
    process_with(
        input,
        out,
        opts,
        RawRecord::parse_shape,
        work,
        |r| match r {
            Ok(Shape::Curve(c)) => kind_key(c),
            // (surfaces and invalid records after the curves, in input order)
            _ => u64::MAX,
        },
    )
}

/// The grouping key of a curve for [`StreamOptions::group`]: single polynomial Bézier
/// segments of degree <= 3 (the strategies' allocation-free lane) first, then by weights,
/// degree, dimension and number of control points (each saturated to its field).
pub fn kind_key(c: &NurbsCurve) -> u64 {
    let (p, d, n) = (c.degree(), c.dim(), c.num_points());
    let segment = p <= 3 && n == p + 1 && !c.is_rational();
    let field = |x: usize, bits: u32| (x as u64).min((1 << bits) - 1);
    (u64::from(!segment) << 62)
        | (u64::from(c.is_rational()) << 61)
        | (field(p, 12) << 48)
        | (field(d, 8) << 40)
        | field(n, 40)
}

/// Whether a stream enclosed with `strategies` is best processed grouped
/// ([`StreamOptions::group`]): unless `hull`, the control-point box, is the only strategy
/// (its work per curve, a scan of the control points, gains nothing from warm code paths and
/// pays ~2% for the out-of-order visits of the parsed curves). The command line's rule.
pub fn group_for(strategies: &[Box<dyn BoxEncloser>]) -> bool {
    strategies
        .iter()
        .any(|s| s.lane() != Some(crate::enclose::lane::Lane::Hull))
}

/// The room reserved for one record's output lines: a 2-D or 3-D curve's enclosure record is
/// 400-550 bytes, so the buffer is allocated once instead of growing from empty in six steps
/// (8, 16, .., 512 bytes: five reallocations per record, ~6% of `hull`'s instructions on a
/// spline suite).
const RECORD_BYTES: usize = 640;

/// The pipeline, with the record parser `parse` and the grouping key `key`
/// ([`StreamOptions::group`]).
fn process_with<R, W, T, P, F, K>(
    input: R,
    out: W,
    opts: &StreamOptions,
    parse: P,
    work: F,
    key: K,
) -> Result<StreamSummary, StreamError>
where
    R: Read,
    W: Write,
    T: Send,
    K: Fn(&Result<T, InputError>) -> u64 + Sync,
    P: Fn(&RawRecord, &ParseOptions) -> Result<T, InputError> + Sync,
    F: Fn(usize, Result<T, InputError>, &mut Vec<u8>) -> bool + Sync,
{
    let pool = thread_pool(opts.threads)?;
    let mut reader = RecordReader::with_options(input, &opts.parse);
    let mut out = io::BufWriter::with_capacity(1 << 16, out);
    let bar = progress_bar(opts);
    let mut summary = StreamSummary::default();
    let chunk_size = opts.chunk_size.max(1);
    let mut read_error = None;
    loop {
        let mut chunk: Vec<RawRecord> = Vec::with_capacity(chunk_size.min(4096));
        let mut bytes = 0usize;
        while chunk.len() < chunk_size && bytes < opts.chunk_bytes {
            let Some(r) = reader.next() else { break };
            if let Err(InputError::Io(msg)) = &r.bytes {
                read_error = Some(msg.clone());
                break;
            }
            bytes += r.bytes.as_ref().map_or(0, |b| b.len());
            chunk.push(r);
        }
        if chunk.is_empty() {
            break;
        }
        let results: Vec<(Vec<u8>, bool)> = pool.install(|| {
            if !opts.group {
                return chunk
                    .par_iter()
                    .map(|r| {
                        let mut buf = Vec::with_capacity(RECORD_BYTES);
                        let ok = work(r.index, parse(r, &opts.parse), &mut buf);
                        (buf, ok)
                    })
                    .collect();
            }
            // Grouped: parse the chunk, order its records by kind (a stable sort: input order
            // within a kind), process them in that order, put each output at its record's place.
            let parsed: Vec<Result<T, InputError>> =
                chunk.par_iter().map(|r| parse(r, &opts.parse)).collect();
            let mut order: Vec<(u64, usize)> = parsed
                .iter()
                .enumerate()
                .map(|(i, p)| (key(p), i))
                .collect();
            order.sort_by_key(|&(k, _)| k);
            let mut slots: Vec<Option<Result<T, InputError>>> =
                parsed.into_iter().map(Some).collect();
            let items: Vec<(usize, Result<T, InputError>)> = order
                .iter()
                .filter_map(|&(_, i)| slots[i].take().map(|t| (i, t)))
                .collect();
            let done: Vec<(usize, Vec<u8>, bool)> = items
                .into_par_iter()
                .map(|(i, t)| {
                    let mut buf = Vec::with_capacity(RECORD_BYTES);
                    let ok = work(chunk[i].index, t, &mut buf);
                    (i, buf, ok)
                })
                .collect();
            let mut res: Vec<(Vec<u8>, bool)> = vec![(Vec::new(), true); chunk.len()];
            for (i, buf, ok) in done {
                res[i] = (buf, ok);
            }
            res
        });
        for (buf, ok) in &results {
            out.write_all(buf)?;
            summary.curves += 1;
            summary.failed += u64::from(!ok);
        }
        out.flush()?;
        if let Some(b) = &bar {
            b.set_position(if opts.total_bytes.is_some() {
                reader.bytes_read()
            } else {
                summary.curves
            });
        }
        if read_error.is_some() {
            break;
        }
    }
    out.flush()?;
    if let Some(b) = bar {
        b.finish_and_clear();
    }
    match read_error {
        Some(msg) => Err(StreamError::Read(msg)),
        None => Ok(summary),
    }
}

/// No progress bar without the `progress` feature.
#[cfg(not(feature = "progress"))]
struct NoBar;

#[cfg(not(feature = "progress"))]
impl NoBar {
    fn set_position(&self, _: u64) {}
    fn finish_and_clear(&self) {}
}

#[cfg(not(feature = "progress"))]
fn progress_bar(_: &StreamOptions) -> Option<NoBar> {
    None
}

#[cfg(feature = "progress")]
fn progress_bar(opts: &StreamOptions) -> Option<indicatif::ProgressBar> {
    use std::io::IsTerminal;
    if !opts.progress || !io::stderr().is_terminal() {
        return None;
    }
    let bar = match opts.total_bytes {
        Some(n) => {
            let b = indicatif::ProgressBar::new(n);
            if let Ok(s) = indicatif::ProgressStyle::with_template(
                "{bar:40} {bytes}/{total_bytes} ({bytes_per_sec}, eta {eta})",
            ) {
                b.set_style(s);
            }
            b
        }
        None => {
            let b = indicatif::ProgressBar::new_spinner();
            if let Ok(s) = indicatif::ProgressStyle::with_template("{spinner} {pos} curves") {
                b.set_style(s);
            }
            b
        }
    };
    bar.set_draw_target(indicatif::ProgressDrawTarget::stderr());
    Some(bar)
}

/// The output lines of `enclose` for one curve: one record per strategy (in the order of
/// `strategies`), or one error record for an invalid curve (or for a strategy that panicked,
/// kind `internal_error`). Returns whether every record is a box.
/// `timings` adds times to the stats (non-reproducible).
pub fn enclose_records(
    index: usize,
    curve: Result<NurbsCurve, InputError>,
    strategies: &[Box<dyn BoxEncloser>],
    timings: bool,
    buf: &mut Vec<u8>,
) -> bool {
    match curve {
        Ok(c) => {
            let mut ok = true;
            for s in strategies {
                // Defence in depth: a strategy must never panic, but if one does, this
                // curve gets an error record and every other curve still gets its boxes.
                match std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| s.enclose(&c))) {
                    Ok(e) => write_enclosure_record(buf, index, &e, timings),
                    Err(p) => {
                        ok = false;
                        let msg = p
                            .downcast_ref::<&str>()
                            .map(|s| s.to_string())
                            .or_else(|| p.downcast_ref::<String>().cloned())
                            .unwrap_or_default();
                        let extra = format!("\"strategy\":\"{}\"", s.name());
                        let text = format!(
                            "internal error: strategy {} failed on this curve ({msg}); please report it with the curve",
                            s.name()
                        );
                        write_error_record(buf, index, &extra, "internal_error", &text);
                    }
                }
                buf.push(b'\n');
            }
            ok
        }
        Err(e) => {
            input_error_line(index, &e, buf);
            false
        }
    }
}

/// Append the error record (and newline) of an invalid input curve.
pub fn input_error_line(index: usize, e: &InputError, buf: &mut Vec<u8>) {
    write_error_record(buf, index, "", e.kind(), &e.to_string());
    buf.push(b'\n');
}

/// One surface strategy per requested name: `Err(name)` when the name has no surface
/// version (the curve-only strategies); such a surface gets an `unsupported_strategy` error
/// record for it.
pub type SurfaceStrategies = Vec<Result<Box<dyn SurfaceEncloser>, &'static str>>;

/// The output lines of `enclose` for one record of a mixed stream: a curve as
/// [`enclose_records`], a surface with `surface_strategies` (same record fields).
pub fn enclose_shape_records(
    index: usize,
    shape: Result<Shape, InputError>,
    strategies: &[Box<dyn BoxEncloser>],
    surface_strategies: &[Result<Box<dyn SurfaceEncloser>, &'static str>],
    timings: bool,
    buf: &mut Vec<u8>,
) -> bool {
    let s = match shape {
        Ok(Shape::Surface(s)) => s,
        Ok(Shape::Curve(c)) => return enclose_records(index, Ok(c), strategies, timings, buf),
        Err(e) => return enclose_records(index, Err(e), strategies, timings, buf),
    };
    let mut ok = true;
    for st in surface_strategies {
        match st {
            Ok(st) => {
                match std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| st.enclose(&s))) {
                    Ok(e) => write_enclosure_record(buf, index, &e, timings),
                    Err(_) => {
                        ok = false;
                        let extra = format!("\"strategy\":\"{}\"", st.name());
                        let text = format!(
                        "internal error: strategy {} failed on this surface; please report it with the surface",
                        st.name()
                    );
                        write_error_record(buf, index, &extra, "internal_error", &text);
                    }
                }
            }
            Err(name) => {
                ok = false;
                let extra = format!("\"strategy\":\"{name}\"");
                let text = format!(
                    "strategy: {name} encloses curves only; the surface strategies are {}",
                    crate::surface::SURFACE_STRATEGY_NAMES.join(", ")
                );
                write_error_record(buf, index, &extra, "unsupported_strategy", &text);
            }
        }
        buf.push(b'\n');
    }
    ok
}

/// The surface strategies of the same names as `strategies` (default settings).
pub fn surface_counterparts(strategies: &[Box<dyn BoxEncloser>]) -> SurfaceStrategies {
    strategies
        .iter()
        .map(|s| crate::surface::surface_strategy_by_name(s.name(), None).ok_or(s.name()))
        .collect()
}

/// The `enclose` pipeline on a mixed stream: [`process_shapes`] with
/// [`enclose_shape_records`]; surfaces get the surface strategies of the same names
/// ([`surface_counterparts`]).
pub fn enclose_stream<R: Read, W: Write>(
    input: R,
    out: W,
    strategies: &[Box<dyn BoxEncloser>],
    opts: &StreamOptions,
    timings: bool,
) -> Result<StreamSummary, StreamError> {
    let surf = surface_counterparts(strategies);
    process_shapes(input, out, opts, |index, shape, buf| {
        enclose_shape_records(index, shape, strategies, &surf, timings, buf)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::enclose::ControlHull;

    fn line(i: usize) -> String {
        format!(
            "{{\"degree\":1,\"knots\":[0,0,1,1],\"control_points\":[[{i}],[{}]]}}\n",
            i + 1
        )
    }

    #[test]
    fn stream_keeps_order_over_chunks_and_threads() {
        let mut input = String::new();
        for i in 0..1000 {
            input.push_str(&line(i));
            if i % 97 == 0 {
                input.push_str("{\"degree\": 1}\n");
            }
        }
        let opts = StreamOptions {
            chunk_size: 64,
            threads: 2,
            ..Default::default()
        };
        let mut out = Vec::new();
        let s = enclose_stream(
            input.as_bytes(),
            &mut out,
            &[Box::new(ControlHull)],
            &opts,
            false,
        )
        .unwrap();
        assert_eq!(s.curves, 1000 + 11);
        assert_eq!(s.failed, 11);
        let text = String::from_utf8(out).unwrap();
        let mut k = 0;
        for (idx, l) in text.lines().enumerate() {
            let v: serde_json::Value = serde_json::from_str(l).unwrap();
            assert_eq!(v["index"], idx);
            if v.get("error").is_some() {
                assert_eq!(v["error"]["kind"], "missing_field");
            } else {
                assert_eq!(v["lo"][0].as_f64().unwrap(), k as f64);
                assert_eq!(v["hi"][0].as_f64().unwrap(), k as f64 + 1.0);
                k += 1;
            }
        }
        assert_eq!(k, 1000);
    }

    /// Grouped processing (`StreamOptions::group`) writes the same bytes as the plain
    /// pipeline: a stream mixing curves of many kinds (every test family: Bézier segments,
    /// splines, NURBS, high degree, extreme magnitudes), a surface and invalid records, in
    /// chunks that split kinds, on one and two threads, with `hull`, `bezier` and `newton`
    /// (whose records carry counters and candidates' values: a record written to another
    /// record's place, or a lost one, shows). `kind_key` puts single Bézier segments first.
    #[test]
    fn grouped_processing_keeps_every_record_in_place() {
        use crate::enclose::strategy_by_name;
        use crate::io::curve_to_json;
        use crate::testkit::gen::{self, Family};
        let mut r = gen::rng(41);
        let mut input = String::new();
        let mut kinds = std::collections::BTreeSet::new();
        for i in 0..240 {
            let c = if i % 31 == 5 {
                gen::range_limit_curve(&mut r)
            } else {
                Family::ALL[i % Family::ALL.len()].curve(&mut r)
            };
            kinds.insert(kind_key(&c));
            input.push_str(&curve_to_json(&c));
            input.push('\n');
            match i % 53 {
                7 => input.push_str("{\"degree\": 1}\n"),
                19 => input.push_str(
                    "{\"degree_u\":1,\"degree_v\":1,\"knots_u\":[0,0,1,1],\"knots_v\":[0,0,1,1],\
                     \"control_points\":[[[0,0,0],[1,0,2]],[[0,1,1],[1,1,3]]]}\n",
                ),
                _ => {}
            }
        }
        assert!(kinds.len() > 30, "{} kinds", kinds.len());
        for name in ["hull", "bezier", "newton"] {
            let st: Vec<Box<dyn BoxEncloser>> = vec![strategy_by_name(name, None).unwrap()];
            for threads in [1, 2] {
                let run = |group: bool| {
                    let opts = StreamOptions {
                        chunk_size: 50,
                        threads,
                        group,
                        ..Default::default()
                    };
                    let mut out = Vec::new();
                    let s = enclose_stream(input.as_bytes(), &mut out, &st, &opts, false).unwrap();
                    (s.curves, s.failed, out)
                };
                let (plain, grouped) = (run(false), run(true));
                assert_eq!(plain.0, 240 + 5 + 5);
                assert_eq!(plain.1, 5, "the invalid records");
                assert!(plain == grouped, "{name}, {threads} threads");
            }
        }
        // single Bézier segments of degree <= 3 first, then by weights and degree
        let seg = gen::near_degenerate_cubic(&mut r);
        assert_eq!((seg.degree(), seg.num_points()), (3, 4));
        for _ in 0..20 {
            let spline = Family::ClampedUniform.curve(&mut r);
            assert!(kind_key(&seg) < kind_key(&spline));
        }
    }

    #[test]
    fn batch_matches_sequential() {
        let curves: Vec<NurbsCurve> = (0..300)
            .map(|i| crate::io::parse_curve(line(i).as_bytes()).unwrap())
            .collect();
        let par = enclose_batch(&curves, &ControlHull, 2);
        for (c, e) in curves.iter().zip(&par) {
            assert_eq!(e.lo(), ControlHull.enclose(c).lo());
        }
        assert_eq!(enclose_batch(&curves, &ControlHull, 0).len(), 300);
    }

    #[test]
    fn read_error_stops_the_stream() {
        struct Failing(usize);
        impl Read for Failing {
            fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
                if self.0 == 0 {
                    return Err(io::Error::other("disk on fire"));
                }
                self.0 -= 1;
                let l = line(0);
                buf[..l.len()].copy_from_slice(l.as_bytes());
                Ok(l.len())
            }
        }
        let mut out = Vec::new();
        let r = enclose_stream(
            Failing(3),
            &mut out,
            &[Box::new(ControlHull)],
            &StreamOptions::default(),
            false,
        );
        assert!(matches!(r, Err(StreamError::Read(m)) if m.contains("disk on fire")));
        // the curves before the failure were still written
        assert_eq!(String::from_utf8(out).unwrap().lines().count(), 3);
    }
}
