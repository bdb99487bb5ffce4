//! Reproduction harness: the thesis's two timing tables (ch. 6), every strategy side by side,
//! a containment check of every enclosure, the sweeps continued beyond the thesis, and the
//! comparison plots. Run with no arguments:
//!
//! ```text
//! cargo run --release --bin reproduce
//! ```
//!
//! Writes `results/knot_sweep.csv`, `results/degree_sweep.csv`, `results/tables.md` and SVG
//! plots; exits non-zero if any verified strategy misses the curve or (feature `mpfr`) a
//! certificate of optimality is false. Every strategy is also timed without certification
//! (`enclose::drive_with(s, c, false)`) in the same loop, for the cost of the certificate.

mod certs;
#[path = "plots.rs"]
#[allow(dead_code)] // shared by several binaries, each uses a part
mod plots;
mod surface_sweep;

use certs::{cost_pct, time_on_off, CertCounts, Timing};

use clap::Parser;
use indicatif::{ProgressBar, ProgressStyle};
use nurbs_box::enclose::{all_strategies, BoxEncloser, Enclosure, Guarantee};
use nurbs_box::testkit::gen;
use nurbs_box::testkit::report::Provenance;
use nurbs_box::testkit::validate::{check_containment, dense_params, gap_ulps};
use nurbs_box::NurbsCurve;
use rayon::prelude::*;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Duration;

#[derive(Parser, Debug, Clone)]
#[command(
    about = "Reproduce the thesis's timing tables with every strategy, check containment, plot"
)]
struct Args {
    /// Output directory for CSV, Markdown and SVG files.
    #[arg(long, default_value = "results")]
    out: PathBuf,
    /// Seeded random curves per table row.
    #[arg(long, default_value_t = 5)]
    curves: usize,
    /// Base seed of the curve generator.
    #[arg(long, default_value_t = 2009)]
    seed: u64,
    /// Largest number of control points in the continued knot-count sweep (10^3 .. this).
    #[arg(long, default_value_t = 100_000)]
    max_points: usize,
    /// Largest degree in the continued degree sweep.
    #[arg(long, default_value_t = 20)]
    max_degree: usize,
    /// Minimum measuring time per curve and strategy, in milliseconds.
    #[arg(long, default_value_t = 5)]
    min_ms: u64,
    /// Dense containment check: sample parameters per knot span.
    #[arg(long, default_value_t = 16)]
    per_span: usize,
    /// Largest number of control points for which the 256-bit reference is computed
    /// (feature `mpfr`); larger rows report the certified gap.
    #[arg(long, default_value_t = 20_000)]
    ref_max_points: usize,
}

/// Thesis, ch. 6, first table: 1-D curve, p = 3, n = last control point index.
/// Columns: n, total [s], derivatives [s], difference [s], avg. Newton iterations.
/// (The n = 50 row is printed as in the thesis, where "derivatives" exceeds "total".)
#[allow(clippy::approx_constant)] // 0.3927 is the thesis's measured time, not pi/8
const THESIS_KNOTS: &[(usize, f64, f64, f64, f64)] = &[
    (4, 0.1864, 0.1466, 0.0402, 1.0),
    (5, 0.4081, 0.3927, 0.0517, 1.0),
    (6, 5.0832, 4.9275, 0.1557, 4.0),
    (10, 6.2673, 5.9185, 0.3488, 3.0),
    (20, 18.2956, 17.8586, 0.4261, 2.0),
    (50, 26.2364, 27.57925, 0.6435, 2.0),
    (70, 168.2395, 166.4215, 1.8180, 1.0),
    (100, 303.7653, 301.0075, 2.7578, 2.0),
];

/// Thesis, ch. 6, second table: NURBS with 11 control points ("10 Punkte"), p = 2 .. 10.
const THESIS_DEGREES: &[(usize, f64, f64, f64, f64)] = &[
    (2, 15.5633, 15.2486, 0.3153, 3.0),
    (3, 18.5922, 18.174, 0.4182, 6.0),
    (4, 2.2887, 2.2294, 0.0592, 1.0),
    (5, 2.2617, 2.2212, 0.0405, 1.0),
    (6, 2.2017, 2.161, 0.0407, 1.0),
    (7, 2.0157, 2.0396, 0.0192, 1.0),
    (8, 1.8101, 1.7197, 0.0182, 1.0),
    (9, 1.4035, 1.3917, 0.0118, 1.0),
    (10, 0.8234, 0.8157, 0.0077, 1.0),
];

#[derive(Debug, Clone, Copy, PartialEq)]
enum Sweep {
    Knots,
    Degrees,
}

/// One table row's work: a family of curves.
struct RowSpec {
    sweep: Sweep,
    /// thesis n (last control point index) for the knot sweep, degree p for the degree sweep
    key: usize,
    degree: usize,
    points: usize,
    curves: Vec<NurbsCurve>,
    thesis: Option<(f64, f64, f64, f64)>,
}

/// Measured result of one strategy on one curve.
#[derive(Clone)]
struct Measure {
    time: Duration,
    /// the same call without certification (`drive_with(s, c, false)`)
    time_off: Duration,
    /// the fastest call with and without certification
    fastest: (Duration, Duration),
    enc: Enclosure,
    /// certified bounds; against the reference (feature `mpfr`): optimal and falsely certified
    cert: CertCounts,
    /// tightness in ulps of the coordinate scale: against the 256-bit reference (worst bound)
    /// when available, else the certified gap (outer - inner)
    ulps: f64,
    vs_reference: bool,
    checked: usize,
    misses: usize,
}

/// Aggregated row for one strategy.
struct Row {
    sweep: Sweep,
    key: usize,
    degree: usize,
    points: usize,
    strategy: &'static str,
    verified: bool,
    curves: usize,
    median_time: Duration,
    /// median over the curves of the time without certification
    median_time_off: Duration,
    /// certification cost in percent: the curves' summed fastest times with over those without,
    /// minus 1
    cert_cost_pct: f64,
    cert: CertCounts,
    deriv_time: Duration,
    newton_iters_avg: f64,
    ulps_median: f64,
    ulps_max: f64,
    vs_reference: bool,
    checked: usize,
    misses: usize,
    thesis: Option<(f64, f64, f64, f64)>,
}

fn median<T: Copy + PartialOrd>(v: &mut [T]) -> T {
    v.sort_by(|a, b| a.partial_cmp(b).unwrap());
    v[v.len() / 2]
}

/// One strategy on one curve: median per-call time of `s.enclose(c)`, of the same call without
/// certification (`drive_with(s, c, false)`), the fastest call of each (`certs::OnOff::fastest`,
/// for the cost of certification), and the enclosure.
type Timed = (Duration, Duration, (Duration, Duration), Enclosure);

/// [`Timed`], single calls alternating with and without certification, repeating for at least
/// `min` (and 3 calls each, fewer once 0.5 s has passed; of 2 calls the faster is the median).
fn time_enclose(s: &dyn BoxEncloser, c: &NurbsCurve, min: Duration) -> Timed {
    let mut t = time_on_off(
        s,
        c,
        Timing {
            batch: Duration::ZERO,
            max_batch: 1,
            min_rounds: 3,
            max_rounds: 10_000,
            min_total: min,
            // curves whose calls take more than ~80 ms (10^4 and 10^5 points, `newton-thesis`
            // at p > 10) are timed once or twice each way, not three times: the loop with
            // both sides takes about as long as the loop of certified calls alone did
            max_total: Duration::from_millis(500),
        },
    );
    let fastest = t.fastest();
    let lower_median = |v: &mut [Duration]| {
        v.sort();
        v[(v.len() - 1) / 2]
    };
    (
        lower_median(&mut t.on),
        lower_median(&mut t.off),
        fastest,
        t.enc,
    )
}

/// Tightness against the 256-bit reference: the worst distance (ulps of the coordinate scale)
/// of an outer bound from the exact extremum; negative means a miss.
#[cfg(feature = "mpfr")]
fn reference_ulps(
    c: &NurbsCurve,
    enc: &Enclosure,
    r: &nurbs_box::testkit::reference::ReferenceBox,
) -> (f64, bool) {
    use nurbs_box::testkit::reference::ulps_outside;
    let mut worst = 0.0f64;
    let mut miss = false;
    for (j, cb) in enc.coords.iter().enumerate() {
        let s = c.coord_scale(j);
        for d in [
            ulps_outside(cb.hi, &r.hi[j], s, true),
            ulps_outside(cb.lo, &r.lo[j], s, false),
        ] {
            if d < 0.0 {
                miss = true;
            }
            worst = worst.max(d.abs());
        }
    }
    (worst, miss)
}

fn measure_row(
    spec: &RowSpec,
    strategies: &[Box<dyn BoxEncloser>],
    args: &Args,
    pb: &ProgressBar,
) -> Vec<Row> {
    let min = Duration::from_millis(args.min_ms);
    // 1. timing, sequential (no other work competing for the cores)
    let mut runs: Vec<Vec<Timed>> = Vec::new();
    for s in strategies {
        let mut v = Vec::new();
        for c in &spec.curves {
            v.push(time_enclose(s.as_ref(), c, min));
            pb.inc(1);
        }
        runs.push(v);
    }
    // 2. reference and containment, in parallel
    #[cfg(feature = "mpfr")]
    let refs: Vec<Option<nurbs_box::testkit::reference::ReferenceBox>> = spec
        .curves
        .par_iter()
        .map(|c| {
            (c.num_points() <= args.ref_max_points)
                .then(|| nurbs_box::testkit::reference::reference_box(c))
        })
        .collect();
    let mut rows = Vec::new();
    for (si, s) in strategies.iter().enumerate() {
        let ms: Vec<Measure> = spec
            .curves
            .par_iter()
            .enumerate()
            .map(|(ci, c)| {
                let (time, time_off, fastest, enc) = runs[si][ci].clone();
                #[allow(unused_mut)]
                let mut params = dense_params(c, args.per_span);
                #[allow(unused_mut)]
                let mut cert = CertCounts::of(&enc);
                #[allow(unused_mut)]
                let mut ulps = gap_ulps(c, &enc).into_iter().fold(0.0, f64::max);
                #[allow(unused_mut)]
                let mut vs_reference = false;
                #[allow(unused_mut)]
                let mut ref_miss = 0;
                #[cfg(feature = "mpfr")]
                if let Some(r) = &refs[ci] {
                    params.extend(r.argmin.iter().chain(&r.argmax));
                    let (u, miss) = reference_ulps(c, &enc, r);
                    ulps = u;
                    vs_reference = true;
                    ref_miss = miss as usize;
                    cert = CertCounts::against(c, &enc, r, |_, _| {});
                }
                let chk = check_containment(c, &enc, &params);
                Measure {
                    time,
                    time_off,
                    fastest,
                    enc,
                    cert,
                    ulps,
                    vs_reference,
                    checked: chk.checked,
                    misses: chk.misses.len() + ref_miss,
                }
            })
            .collect();
        // The median curve's time, and its derivative time as the fraction of its own enclose
        // call spent in derivative evaluation (both from the same curve and call).
        let mut tf: Vec<(Duration, f64)> = ms
            .iter()
            .map(|m| {
                let st = m.enc.stats();
                let frac = if st.time_total.is_zero() {
                    0.0
                } else {
                    (st.time_derivatives.as_secs_f64() / st.time_total.as_secs_f64()).min(1.0)
                };
                (m.time, frac)
            })
            .collect();
        tf.sort_by_key(|a| a.0);
        let (med_time, med_frac) = tf[tf.len() / 2];
        let spans = |c: &NurbsCurve| (c.breakpoints().len() - 1) * c.dim();
        let iters: f64 = ms
            .iter()
            .zip(&spec.curves)
            .map(|(m, c)| m.enc.stats().newton_iterations as f64 / spans(c) as f64)
            .sum::<f64>()
            / ms.len() as f64;
        let mut ul: Vec<f64> = ms.iter().map(|m| m.ulps).collect();
        let ulps_max = ul.iter().cloned().fold(0.0, f64::max);
        let mut off: Vec<Duration> = ms.iter().map(|m| m.time_off).collect();
        let mut cert = CertCounts::default();
        for m in &ms {
            cert.add(&m.cert);
        }
        rows.push(Row {
            sweep: spec.sweep,
            key: spec.key,
            degree: spec.degree,
            points: spec.points,
            strategy: s.name(),
            verified: s.guarantee() == Guarantee::Verified,
            curves: ms.len(),
            median_time: med_time,
            median_time_off: median(&mut off),
            // from each curve's fastest calls: medians of a few calls of several ms vary by
            // +-50% on a loaded machine, the minima by a few percent
            cert_cost_pct: cost_pct(
                ms.iter().map(|m| m.fastest.0).sum(),
                ms.iter().map(|m| m.fastest.1).sum(),
            ),
            cert,
            deriv_time: med_time.mul_f64(med_frac),
            newton_iters_avg: iters,
            ulps_median: median(&mut ul),
            ulps_max,
            vs_reference: ms.iter().all(|m| m.vs_reference),
            checked: ms.iter().map(|m| m.checked).sum(),
            misses: ms.iter().map(|m| m.misses).sum(),
            thesis: spec.thesis,
        });
    }
    rows
}

fn build_specs(args: &Args) -> Vec<RowSpec> {
    let mut specs = Vec::new();
    let seed = |k: usize, i: usize| {
        args.seed
            .wrapping_mul(1_000_003)
            .wrapping_add((k * 1000 + i) as u64)
    };
    // Knot-count sweep (thesis notation: n + 1 control points), then continued.
    #[allow(clippy::type_complexity)]
    let mut ns: Vec<(usize, Option<(f64, f64, f64, f64)>)> = THESIS_KNOTS
        .iter()
        .map(|r| (r.0, Some((r.1, r.2, r.3, r.4))))
        .collect();
    let mut big = 1000;
    while big <= args.max_points {
        ns.push((big - 1, None));
        big *= 10;
    }
    for (n, thesis) in ns {
        let count = if n + 1 >= 10_000 {
            args.curves.min(2)
        } else {
            args.curves
        };
        let curves = (0..count)
            .map(|i| gen::thesis_curve_1d(n + 1, 3, seed(n, i)).expect("valid thesis curve"))
            .collect();
        specs.push(RowSpec {
            sweep: Sweep::Knots,
            key: n,
            degree: 3,
            points: n + 1,
            curves,
            thesis,
        });
    }
    // Degree sweep: 11 control points, p = 2 .. 10; continued to max_degree with 21 points.
    for p in 2..=args.max_degree.max(10) {
        let thesis = THESIS_DEGREES
            .iter()
            .find(|r| r.0 == p)
            .map(|r| (r.1, r.2, r.3, r.4));
        let points = if p <= 10 { 11 } else { 21 };
        if p + 1 > points {
            continue;
        }
        let curves = (0..args.curves)
            .map(|i| {
                gen::thesis_curve_2d_nurbs_with(points, p, seed(10_000 + p, i))
                    .expect("valid thesis curve")
            })
            .collect();
        specs.push(RowSpec {
            sweep: Sweep::Degrees,
            key: p,
            degree: p,
            points,
            curves,
            thesis,
        });
    }
    specs
}

fn fmt_time(d: Duration) -> String {
    let s = d.as_secs_f64();
    if s >= 1.0 {
        format!("{s:.3} s")
    } else if s >= 1e-3 {
        format!("{:.3} ms", s * 1e3)
    } else {
        format!("{:.2} µs", s * 1e6)
    }
}

fn fmt_ulps(x: f64) -> String {
    if x >= 1e4 {
        format!("{x:.1e}")
    } else {
        format!("{x:.1}")
    }
}

fn csv(rows: &[Row], sweep: Sweep, prov: &Provenance) -> String {
    let mut s = prov.csv_comment();
    s.push_str("sweep,n,points,degree,strategy,verified,curves,median_time_s,derivative_time_s,difference_s,newton_iterations_avg,tightness_ulps_median,tightness_ulps_max,tightness_basis,checked_params,misses,bounds,certified_bounds,optimal_bounds,false_certificates,median_time_uncertified_s,certification_cost_pct,thesis_total_s,thesis_derivatives_s,thesis_difference_s,thesis_newton_iterations\n");
    for r in rows.iter().filter(|r| r.sweep == sweep) {
        let (tt, td, tf, ti) = r.thesis.map_or(
            (String::new(), String::new(), String::new(), String::new()),
            |t| {
                (
                    t.0.to_string(),
                    t.1.to_string(),
                    t.2.to_string(),
                    t.3.to_string(),
                )
            },
        );
        // empty without the reference (no `mpfr`, or more points than `--ref-max-points`)
        let (opt, fc) = if r.cert.vs_reference > 0 {
            (r.cert.optimal.to_string(), r.cert.false_cert.to_string())
        } else {
            (String::new(), String::new())
        };
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{:e},{:e},{:e},{},{},{},{},{},{},{},{},{},{},{:e},{:.2},{},{},{},{}",
            if sweep == Sweep::Knots {
                "knots"
            } else {
                "degree"
            },
            r.points - 1,
            r.points,
            r.degree,
            r.strategy,
            r.verified,
            r.curves,
            r.median_time.as_secs_f64(),
            r.deriv_time.as_secs_f64(),
            r.median_time.saturating_sub(r.deriv_time).as_secs_f64(),
            r.newton_iters_avg,
            r.ulps_median,
            r.ulps_max,
            if r.vs_reference { "reference" } else { "gap" },
            r.checked,
            r.misses,
            r.cert.bounds,
            r.cert.certified,
            opt,
            fc,
            r.median_time_off.as_secs_f64(),
            r.cert_cost_pct,
            tt,
            td,
            tf,
            ti
        );
    }
    s
}

/// The thesis columns for the interval Newton strategy, ours beside the thesis's.
fn thesis_table(rows: &[Row], sweep: Sweep) -> String {
    let mut s = String::new();
    let key = if sweep == Sweep::Knots {
        "n (n+1 points)"
    } else {
        "p (points)"
    };
    let _ = writeln!(s, "| {key} | total | derivatives | difference | avg. Newton it. | thesis total | thesis deriv. | thesis diff. | thesis it. | thesis / ours |");
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|---|");
    for r in rows
        .iter()
        .filter(|r| r.sweep == sweep && r.strategy == "newton-thesis")
    {
        let k = format!("{} ({})", r.key, r.points);
        let (tt, td, tf, ti, ratio) = match r.thesis {
            Some(t) => (
                format!("{} s", t.0),
                format!("{} s", t.1),
                format!("{} s", t.2),
                format!("{}", t.3),
                format!("{:.1e}", t.0 / r.median_time.as_secs_f64()),
            ),
            None => ("–".into(), "–".into(), "–".into(), "–".into(), "–".into()),
        };
        let _ = writeln!(
            s,
            "| {k} | {} | {} | {} | {:.2} | {tt} | {td} | {tf} | {ti} | {ratio} |",
            fmt_time(r.median_time),
            fmt_time(r.deriv_time),
            fmt_time(r.median_time.saturating_sub(r.deriv_time)),
            r.newton_iters_avg
        );
    }
    s
}

/// One line per sweep row, for every strategy the columns `cols` (the first prefixed by the
/// strategy's name, aligned by `align`, e.g. `---` or `--:`) filled by `cells`; `–` where a
/// strategy has no result.
fn per_strategy_table(
    rows: &[Row],
    sweep: Sweep,
    names: &[&'static str],
    cols: &[&str],
    align: &str,
    cells: impl Fn(&Row) -> Vec<String>,
) -> String {
    let mut s = String::new();
    let key = if sweep == Sweep::Knots {
        "n+1 points"
    } else {
        "p"
    };
    let _ = write!(s, "| {key} |");
    for n in names {
        let _ = write!(s, " {n}: {} |", cols.join(" | "));
    }
    s.push('\n');
    s.push_str("|---|");
    for _ in names {
        for _ in cols {
            let _ = write!(s, "{align}|");
        }
    }
    s.push('\n');
    let mut keys: Vec<usize> = rows
        .iter()
        .filter(|r| r.sweep == sweep)
        .map(|r| r.key)
        .collect();
    keys.dedup();
    for k in keys {
        let lead = rows
            .iter()
            .find(|r| r.sweep == sweep && r.key == k)
            .unwrap();
        let _ = write!(
            s,
            "| {} |",
            if sweep == Sweep::Knots {
                lead.points
            } else {
                k
            }
        );
        for n in names {
            let found = rows
                .iter()
                .find(|r| r.sweep == sweep && r.key == k && r.strategy == *n);
            let v = found.map_or_else(|| vec!["–".to_string(); cols.len()], &cells);
            for c in v {
                let _ = write!(s, " {c} |");
            }
        }
        s.push('\n');
    }
    s
}

/// All strategies side by side: median time, tightness, containment.
fn strategy_table(rows: &[Row], sweep: Sweep, names: &[&'static str]) -> String {
    let cols = ["time", "ulps med/max", "misses"];
    per_strategy_table(rows, sweep, names, &cols, "---", |r| {
        let miss = if r.misses == 0 {
            "0".to_string()
        } else if r.verified {
            format!("**{} MISSED**", r.misses)
        } else {
            format!("{} (heuristic)", r.misses)
        };
        vec![
            fmt_time(r.median_time),
            format!(
                "{} / {}{}",
                fmt_ulps(r.ulps_median),
                fmt_ulps(r.ulps_max),
                if r.vs_reference { "" } else { " (gap)" }
            ),
            miss,
        ]
    })
}

/// Optimality certificates per strategy: share of certified-optimal bounds, with the reference
/// (feature `mpfr`) the share of optimal bounds and the false certificates, and the cost of
/// certification (time with over time without, same run).
fn cert_table(rows: &[Row], sweep: Sweep, names: &[&'static str]) -> String {
    let mpfr = cfg!(feature = "mpfr");
    let cols: &[&str] = if mpfr {
        &["certified %", "optimal %", "false cert.", "cert. cost"]
    } else {
        &["certified %", "cert. cost"]
    };
    per_strategy_table(rows, sweep, names, cols, "--:", |r| {
        let mut v = vec![r.cert.certified_pct()];
        if mpfr {
            if r.cert.vs_reference == 0 {
                v.extend(["–".to_string(), "–".to_string()]);
            } else if r.cert.false_cert == 0 {
                v.extend([r.cert.optimal_pct(), "0".to_string()]);
            } else {
                v.extend([
                    r.cert.optimal_pct(),
                    format!("**{} FALSE**", r.cert.false_cert),
                ]);
            }
        }
        v.push(format!("{:+.1}%", r.cert_cost_pct));
        v
    })
}

fn main() {
    let args = Args::parse();
    // the tables report the time spent in derivative evaluations as a fraction of the total
    nurbs_box::enclose::set_timing(true);
    let prov = Provenance::collect();
    std::fs::create_dir_all(&args.out).expect("create output directory");
    let strategies = all_strategies(None);
    let names: Vec<&'static str> = strategies.iter().map(|s| s.name()).collect();
    let specs = build_specs(&args);
    let total: u64 = specs
        .iter()
        .map(|s| (s.curves.len() * strategies.len()) as u64)
        .sum();
    eprintln!(
        "reproduce: {} rows, {} curves, strategies {:?}; reference: {}",
        specs.len(),
        specs.iter().map(|s| s.curves.len()).sum::<usize>(),
        names,
        if cfg!(feature = "mpfr") {
            "256-bit MPFR"
        } else {
            "none (certified gap; build with --features mpfr for ulps vs exact)"
        }
    );
    let pb = ProgressBar::new(total);
    pb.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} {msg} [{elapsed_precise}]").unwrap(),
    );
    let mut rows = Vec::new();
    for spec in &specs {
        pb.set_message(format!(
            "{} {}",
            if spec.sweep == Sweep::Knots {
                "n+1 ="
            } else {
                "p ="
            },
            if spec.sweep == Sweep::Knots {
                spec.points
            } else {
                spec.key
            }
        ));
        rows.extend(measure_row(spec, &strategies, &args, &pb));
    }
    pb.finish_and_clear();

    let mut md = String::new();
    let _ = writeln!(md, "# Reproduction of the thesis's timing tables\n");
    let _ = writeln!(md, "_{}_\n", prov.line());
    let _ = writeln!(
        md,
        "Times are medians per curve over {} seeded random curves per row (fewer for >= 10^4 points); \
         a curve's time is the median of its calls (at least 3 and {} ms, fewer after 0.5 s; of 2, the faster). \
         The thesis's numbers were measured in MATLAB + INTLAB on an Intel Pentium Dual T2390 @ 1.58 GHz \
         (2009): a different machine and language, so the ratio column compares implementations, not \
         algorithms alone. Tightness: distance of the outer bounds from the exact extrema in ulps of the \
         coordinate scale (largest |control point coordinate|){}. \
         Containment: every box is checked against verified point enclosures on a dense grid{}; a miss is \
         a proven one. Optimality certificates (last two tables): `certified %` is the share of bounds \
         (lo and hi of every coordinate of every curve) the driver proved optimal (`optimal_lo` / \
         `optimal_hi`: lo = RD(min), hi = RU(max)); {} `cert. cost` is the time of the row's curves with \
         certification over their time without it (`enclose::drive_with(s, c, false)`, single calls \
         alternating with those timed above), minus 1, each curve's time being its fastest call (other \
         jobs on the machine only add time); heuristic strategies get no \
         certificates, so their cost is timing noise.\n",
        args.curves,
        args.min_ms,
        if cfg!(feature = "mpfr") { ", against a 256-bit MPFR reference" } else { "; without the `mpfr` feature the certified gap (outer - inner) is shown, marked (gap)" },
        if cfg!(feature = "mpfr") { " plus the reference extremum locations, and against the reference extrema" } else { "" },
        if cfg!(feature = "mpfr") {
            format!(
                "`optimal %` is the share of bounds equal to the optimal double of the 256-bit \
                 reference extremum, `false cert.` counts certificates whose bound is not the \
                 reference's rounding (must be 0; both – for rows above {} control points, which \
                 have no reference);",
                args.ref_max_points
            )
        } else {
            "the share of optimal bounds and the count of false certificates against the exact \
             extrema are n/a without mpfr (`cargo run --release --features mpfr --bin reproduce`);"
                .to_string()
        }
    );
    let _ = writeln!(
        md,
        "## Table 1: knot count (1-D, degree 3) — interval Newton with the thesis's settings (`newton-thesis`), thesis columns\n"
    );
    md.push_str(&thesis_table(&rows, Sweep::Knots));
    let _ = writeln!(md, "\n## Table 2: degree (2-D NURBS, 11 control points; 21 for p > 10) — interval Newton with the thesis's settings (`newton-thesis`), thesis columns\n");
    md.push_str(&thesis_table(&rows, Sweep::Degrees));
    let _ = writeln!(md, "\n## All strategies, knot-count sweep\n");
    md.push_str(&strategy_table(&rows, Sweep::Knots, &names));
    let _ = writeln!(md, "\n## All strategies, degree sweep\n");
    md.push_str(&strategy_table(&rows, Sweep::Degrees, &names));
    let _ = writeln!(md, "\n## Optimality certificates, knot-count sweep\n");
    md.push_str(&cert_table(&rows, Sweep::Knots, &names));
    let _ = writeln!(md, "\n## Optimality certificates, degree sweep\n");
    md.push_str(&cert_table(&rows, Sweep::Degrees, &names));
    let verified_misses: usize = rows.iter().filter(|r| r.verified).map(|r| r.misses).sum();
    let heuristic_misses: usize = rows.iter().filter(|r| !r.verified).map(|r| r.misses).sum();
    let checked: usize = rows.iter().map(|r| r.checked).sum();
    let _ = writeln!(
        md,
        "\n**Containment:** {checked} parameter checks; verified strategies: {verified_misses} misses; heuristic strategies: {heuristic_misses} misses.\n"
    );
    let mut cert = CertCounts::default();
    for r in rows.iter().filter(|r| r.verified) {
        cert.add(&r.cert);
    }
    let false_certs = rows.iter().map(|r| r.cert.false_cert).sum::<usize>();
    let _ = write!(
        md,
        "**Certificates:** verified strategies: {} of {} bounds certified optimal ({}%)",
        cert.certified,
        cert.bounds,
        cert.certified_pct()
    );
    if cfg!(feature = "mpfr") {
        let _ = writeln!(
            md,
            "; against the reference {} of {} bounds optimal ({}%), {false_certs} false certificates.\n",
            cert.optimal,
            cert.vs_reference,
            cert.optimal_pct()
        );
    } else {
        let _ = writeln!(
            md,
            "; optimal share and false certificates n/a without mpfr.\n"
        );
    }
    let _ = writeln!(md, "Plots: `time_vs_n.svg`, `time_vs_p.svg`, `thesis_figure.svg`, `coordinate_functions.svg` (`tightness.svg`, the ECDF of the distance to the optimal double, comes from the `tightness` binary).");

    let write = |name: &str, s: &str| {
        let p = args.out.join(name);
        std::fs::write(&p, s).unwrap_or_else(|e| panic!("write {}: {e}", p.display()));
        p
    };
    write("knot_sweep.csv", &csv(&rows, Sweep::Knots, &prov));
    write("degree_sweep.csv", &csv(&rows, Sweep::Degrees, &prov));
    let mdp = write("tables.md", &md);

    let series = |sweep: Sweep| -> Vec<(String, Vec<(f64, f64)>)> {
        names
            .iter()
            .map(|n| {
                let pts = rows
                    .iter()
                    .filter(|r| r.sweep == sweep && r.strategy == *n)
                    .map(|r| {
                        (
                            if sweep == Sweep::Knots {
                                r.points as f64
                            } else {
                                r.key as f64
                            },
                            r.median_time.as_secs_f64() * 1e6,
                        )
                    })
                    .collect();
                (n.to_string(), pts)
            })
            .collect()
    };
    let foot = prov.line();
    plots::time_plot(
        &args.out.join("time_vs_n.svg"),
        "Time per curve vs number of control points (1-D, p = 3)",
        "control points n+1",
        &series(Sweep::Knots),
        true,
        &foot,
    );
    plots::time_plot(
        &args.out.join("time_vs_p.svg"),
        "Time per curve vs degree (2-D NURBS)",
        "degree p",
        &series(Sweep::Degrees),
        false,
        &foot,
    );
    // The thesis's figure: a 2-D NURBS (degree 3, 11 points) with its box and extremum points,
    // and one plot per coordinate function with its extrema.
    let fig_curve = gen::thesis_curve_2d_nurbs(3, args.seed).expect("valid thesis curve");
    let fig_strategy = strategies
        .iter()
        .find(|s| s.name() == "newton")
        .unwrap_or(&strategies[0]);
    let fig_enc = fig_strategy.enclose(&fig_curve);
    plots::curve_figure(
        &args.out.join("thesis_figure.svg"),
        &fig_curve,
        &fig_enc,
        &foot,
    );
    plots::coordinate_functions(
        &args.out.join("coordinate_functions.svg"),
        &fig_curve,
        &fig_enc,
        &foot,
    );

    print!("{md}");
    eprintln!(
        "wrote {} and CSV/SVG files in {}",
        mdp.display(),
        args.out.display()
    );
    // surfaces: sweep over degree and net size, families, containment checks
    // (results/surfaces.md, results/surface_figure.svg)
    let surface_misses = surface_sweep::run(false, &args.out);
    if surface_misses > 0 {
        eprintln!("\n!!! CONTAINMENT FAILURE: verified surface strategies missed {surface_misses} times !!!");
    }
    if verified_misses > 0 {
        eprintln!("\n!!! CONTAINMENT FAILURE: verified strategies missed the curve {verified_misses} times !!!");
        for r in rows.iter().filter(|r| r.verified && r.misses > 0) {
            eprintln!(
                "!!!   {} on {:?} row {}: {} misses",
                r.strategy, r.sweep, r.key, r.misses
            );
        }
    }
    // a certificate whose bound is not the reference's rounding is as wrong as a miss
    if false_certs > 0 {
        eprintln!("\n!!! FALSE CERTIFICATES: {false_certs} certified bounds are not the optimal double !!!");
        for r in rows.iter().filter(|r| r.cert.false_cert > 0) {
            eprintln!(
                "!!!   {} on {:?} row {}: {} false certificates",
                r.strategy, r.sweep, r.key, r.cert.false_cert
            );
        }
    }
    if surface_misses > 0 || verified_misses > 0 || false_certs > 0 {
        std::process::exit(1);
    }
}
