//! Tightness and soundness of every strategy against the 256-bit reference (the crate's tightness
//! target: every bound of `newton` / `bezier` within 4 ulps of the coordinate scale of the exact
//! extremum, median <= 1 ulp), per strategy and per `gen` family.
//!
//! Run: `cargo run --release --features mpfr --bin tightness [-- --curves N --seed S
//! --max-points M --family F --strategies a,b --dump DIR]` (defaults: 100 curves per family,
//! seed 1, reference for curves with at most 400 control points, every family and strategy).
//! Deterministic given the seed. Prints Markdown tables. `--family` / `--strategies` restrict
//! the run (and then write no plot); `--dump DIR` writes every curve with a non-optimal bound
//! or a certification cost above 50% (of a verified strategy) as one JSON file to DIR, and
//! a line per such bound or curve to stderr (for diagnosis).
//!
//! Columns: `ulps_outside` (`nurbs_box::testkit::reference::ulps_outside`) of every outer bound, in ulps
//! of `NurbsCurve::coord_scale(j)`: positive = on the safe side, negative = a containment miss.
//! `ref miss` counts bounds with `ulps_outside < 0` (against the box of the closure of the
//! curve, which every span-wise strategy encloses), `pt miss` counts proven misses at dense
//! parameters and the reference argmin/argmax (`validate::check_containment`), `inner bad`
//! counts inner bounds not reached (inner_lo < exact min or inner_hi > exact max),
//! `curves missed` the curves with any miss. Time: median and mean wall time of one
//! `enclose` call with certification (each curve enclosed repeatedly, with and without
//! certification alternately, for >= 0.1 ms each, three times, sequentially; the fastest of
//! the three per curve).
//!
//! Optimality: `optimal` is the share of bounds equal to the optimal double (RD(min) /
//! RU(max) of the reference, `reference::optimal_bound`), `certified` the share with
//! `optimal_lo` / `optimal_hi` true, `false cert` the certificates whose bound is not the
//! optimal double (must be 0; a bound within the reference's resolution, 2^-160 of the scale
//! at 256 bits, finer with `reference::range_bits` and `reference::weight_bits`, of the exact
//! value is not counted:
//! `reference::false_certificate`). `cert +%`: the mean
//! time with certification over the mean time of the same calls without it
//! (`enclose::drive_with(s, c, false)`), minus 1, timed alternately on the same curves. The family `ties` is `testkit::ties` (extrema exactly
//! doubles or within 2^-60 .. 2^-110 relative of one, circles, corners, unclamped ends).
//!
//! Also writes `results/tightness.svg`: per verified strategy the ECDF of the distance of every
//! bound to the optimal double, in ulps of the value (f64 steps), over all families.

#[cfg(not(feature = "mpfr"))]
fn main() {
    eprintln!("the tightness example needs the reference: run it with --features mpfr");
    std::process::exit(2);
}

#[cfg(feature = "mpfr")]
fn main() {
    imp::main();
}

#[cfg(feature = "mpfr")]
#[path = "plots.rs"]
#[allow(dead_code)] // shared by several binaries, each uses a part
mod plots;

#[cfg(feature = "mpfr")]
#[allow(dead_code)] // shared with `reproduce`, which uses a part this binary does not
mod certs;

#[cfg(feature = "mpfr")]
mod imp {
    use super::certs::{cost_pct, time_on_off, CertCounts, Timing};
    use super::plots;
    use nurbs_box::enclose::all_strategies;
    use nurbs_box::testkit::gen::{self, Family, GenParams};
    use nurbs_box::testkit::reference::{reference_box, ulps_outside, ReferenceBox};
    use nurbs_box::testkit::report::Provenance;
    use nurbs_box::testkit::ties::tie_curve;
    use nurbs_box::testkit::validate::{check_containment, dense_params};
    use nurbs_box::{BoxEncloser, Enclosure, NurbsCurve};
    use rayon::prelude::*;
    use std::time::Duration;

    struct Args {
        curves: usize,
        seed: u64,
        max_points: usize,
        family: Option<String>,
        strategies: Option<Vec<String>>,
        dump: Option<std::path::PathBuf>,
    }

    fn args() -> Args {
        let mut a = Args {
            curves: 100,
            seed: 1,
            max_points: 400,
            family: None,
            strategies: None,
            dump: None,
        };
        let v: Vec<String> = std::env::args().skip(1).collect();
        let mut i = 0;
        while i < v.len() {
            let val = v.get(i + 1).and_then(|x| x.parse::<u64>().ok());
            let text = v.get(i + 1).cloned();
            match (v[i].as_str(), val, text) {
                ("--curves", Some(x), _) => a.curves = x as usize,
                ("--seed", Some(x), _) => a.seed = x,
                ("--max-points", Some(x), _) => a.max_points = x as usize,
                ("--family", _, Some(f)) => a.family = Some(f),
                ("--strategies", _, Some(s)) => {
                    a.strategies = Some(s.split(',').map(str::to_string).collect())
                }
                ("--dump", _, Some(d)) => a.dump = Some(d.into()),
                _ => {
                    eprintln!(
                        "usage: tightness [--curves N] [--seed S] [--max-points M] [--family F] \
                         [--strategies a,b] [--dump DIR]"
                    );
                    std::process::exit(2);
                }
            }
            i += 2;
        }
        a
    }

    /// Per (family, strategy) accumulator.
    #[derive(Default, Clone)]
    struct Acc {
        curves: usize,
        ulps: Vec<f64>,
        ref_miss: usize,
        pt_miss: usize,
        inner_bad: usize,
        curves_missed: usize,
        times: Vec<Duration>,
        /// times of the same calls without certification
        times_off: Vec<Duration>,
        /// certified, optimal and falsely certified bounds
        cert: CertCounts,
        /// distance of every bound to the optimal double, in f64 steps
        dist: Vec<f64>,
    }

    impl Acc {
        fn merge(&mut self, o: &Acc) {
            self.curves += o.curves;
            self.ulps.extend_from_slice(&o.ulps);
            self.ref_miss += o.ref_miss;
            self.pt_miss += o.pt_miss;
            self.inner_bad += o.inner_bad;
            self.curves_missed += o.curves_missed;
            self.times.extend_from_slice(&o.times);
            self.times_off.extend_from_slice(&o.times_off);
            self.cert.add(&o.cert);
            self.dist.extend_from_slice(&o.dist);
        }

        fn row(&self, family: &str, strategy: &str) -> String {
            let mut u = self.ulps.clone();
            u.sort_by(f64::total_cmp);
            let q = |f: f64| {
                if u.is_empty() {
                    f64::NAN
                } else {
                    u[((u.len() - 1) as f64 * f).round() as usize]
                }
            };
            let mut t = self.times.clone();
            t.sort();
            let tmed = t.get(t.len() / 2).copied().unwrap_or_default();
            let tmean = t.iter().sum::<Duration>() / (t.len().max(1) as u32);
            let off = self.times_off.iter().sum::<Duration>();
            let on = self.times.iter().sum::<Duration>();
            format!(
                "| {family} | {strategy} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {:.1} | {:.1} | {:+.1} |",
                self.curves,
                u.len(),
                fmt(q(0.5)),
                fmt(q(0.9)),
                fmt(q(1.0)),
                self.ref_miss,
                self.pt_miss,
                self.inner_bad,
                self.curves_missed,
                self.cert.optimal_pct(),
                self.cert.certified_pct(),
                self.cert.false_cert,
                tmed.as_secs_f64() * 1e6,
                tmean.as_secs_f64() * 1e6,
                cost_pct(on, off),
            )
        }
    }

    fn fmt(x: f64) -> String {
        if x.is_nan() {
            "-".into()
        } else if x.is_infinite() {
            if x > 0.0 { "inf" } else { "-inf" }.into()
        } else if x.abs() >= 1e4 {
            format!("{x:.2e}")
        } else {
            format!("{x:.2}")
        }
    }

    /// Wall time of one `enclose` call with and without certification: the fastest of three
    /// rounds of >= 0.1 ms batches each (`certs::time_on_off`, alternating;
    /// `certs::OnOff::fastest`, as the reproduction harness: other jobs on a shared machine
    /// only ever add time, and a mean of two rounds moved a family's certification cost by
    /// ±10 points from run to run).
    fn time_enclose(s: &dyn BoxEncloser, c: &NurbsCurve) -> (Duration, Duration, Enclosure) {
        let t = time_on_off(
            s,
            c,
            Timing {
                batch: Duration::from_micros(100),
                max_batch: 500,
                min_rounds: 3,
                max_rounds: 3,
                min_total: Duration::ZERO,
                max_total: Duration::MAX,
            },
        );
        let (on, off) = t.fastest();
        (on, off, t.enc)
    }

    /// The position of an f64 in the ordered sequence of all f64 (adjacent doubles differ by 1;
    /// -0 and +0 coincide).
    fn ord(x: f64) -> i64 {
        let b = x.to_bits() as i64;
        if b < 0 {
            -(b & i64::MAX)
        } else {
            b
        }
    }

    fn measure(c: &NurbsCurve, e: &Enclosure, rb: &ReferenceBox, acc: &mut Acc) {
        let mut missed = false;
        for (j, cb) in e.coords.iter().enumerate() {
            let sc = c.coord_scale(j);
            for d in [
                ulps_outside(cb.lo, &rb.lo[j], sc, false),
                ulps_outside(cb.hi, &rb.hi[j], sc, true),
            ] {
                if d < 0.0 {
                    acc.ref_miss += 1;
                    missed = true;
                }
                acc.ulps.push(d);
            }
            if !nurbs_box::testkit::reference::inner_reached(
                rb,
                j,
                cb.inner_lo,
                cb.inner_hi,
                c.coord_scale(j),
            ) {
                acc.inner_bad += 1;
            }
        }
        let dist = &mut acc.dist;
        let k = CertCounts::against(c, e, rb, |bound, opt| {
            dist.push((ord(bound) - ord(opt)).unsigned_abs() as f64)
        });
        acc.cert.add(&k);
        let mut pts = dense_params(c, 16);
        pts.extend(rb.argmin.iter().chain(&rb.argmax));
        let chk = check_containment(c, e, &pts);
        if !chk.misses.is_empty() {
            acc.pt_miss += chk.misses.len();
            missed = true;
        }
        acc.curves += 1;
        acc.curves_missed += missed as usize;
    }

    /// `--dump`: a line per non-optimal bound and per curve whose certification cost more
    /// than half the time without it (verified strategies only), and the curve as JSON in
    /// `dir` (named family-index.json).
    fn dump(
        dir: &std::path::Path,
        (family, index, strategy): (&str, usize, &str),
        c: &NurbsCurve,
        e: &Enclosure,
        rb: &ReferenceBox,
        (t, t_off): (Duration, Duration),
    ) {
        use nurbs_box::testkit::reference::optimal_bound;
        if !e.verified {
            return;
        }
        let mut lines = Vec::new();
        for (j, cb) in e.coords.iter().enumerate() {
            let sc = c.coord_scale(j);
            for (side, bound, exact, up, flag) in [
                ("lo", cb.lo, &rb.lo[j], false, cb.optimal_lo),
                ("hi", cb.hi, &rb.hi[j], true, cb.optimal_hi),
            ] {
                let opt = optimal_bound(exact, sc, up);
                if bound != opt || !flag {
                    lines.push(format!(
                        "{family} {index} {strategy} coord {j} {side}: bound {bound:e} optimal \
                         {opt:e} ({} steps) certified {flag}",
                        ord(bound) - ord(opt)
                    ));
                }
            }
        }
        let ratio = t.as_secs_f64() / t_off.as_secs_f64().max(1e-9);
        if ratio > 1.5 {
            lines.push(format!(
                "{family} {index} {strategy} cost: {:.1} us with, {:.1} us without certification",
                t.as_secs_f64() * 1e6,
                t_off.as_secs_f64() * 1e6
            ));
        }
        if lines.is_empty() {
            return;
        }
        for l in &lines {
            eprintln!("{l}");
        }
        let _ = std::fs::create_dir_all(dir);
        let path = dir.join(format!("{family}-{index}.json"));
        let _ = std::fs::write(path, nurbs_box::io::records::curve_to_json(c));
    }

    pub fn main() {
        let a = args();
        let prov = Provenance::collect();
        let strategies: Vec<_> = all_strategies(None)
            .into_iter()
            .filter(|s| {
                a.strategies
                    .as_ref()
                    .is_none_or(|v| v.iter().any(|x| x == s.name()))
            })
            .collect();
        let partial = a.family.is_some() || a.strategies.is_some();
        // None: moderate random curves; Some(None): the constructed ties
        let families: Vec<(String, Option<Option<Family>>)> =
            std::iter::once(("moderate".into(), None))
                .chain(
                    Family::ALL
                        .iter()
                        .chain(&[Family::RangeLimits])
                        .map(|f| (f.name().to_string(), Some(Some(*f)))),
                )
                .chain(std::iter::once(("ties".into(), Some(None))))
                .collect();
        let header = "| family | strategy | curves | bounds | median | p90 | max | ref miss | pt miss | inner bad | curves missed | optimal % | certified % | false cert | µs/curve (median) | µs/curve (mean) | cert +% |\n|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|";
        println!("# Tightness: ulps_outside of every bound vs the 256-bit reference\n");
        println!(
            "command: `{}`, commit {}, {} ({} cores)\n",
            prov.command, prov.commit, prov.cpu, prov.cores
        );
        println!("{header}");
        let mut totals = vec![Acc::default(); strategies.len()];
        let mut skipped = 0usize;
        for (fi, (fname, fam)) in families.iter().enumerate() {
            if a.family.as_ref().is_some_and(|f| f != fname) {
                continue;
            }
            let mut r = gen::rng(a.seed.wrapping_mul(1000).wrapping_add(fi as u64));
            let curves: Vec<NurbsCurve> = (0..a.curves)
                .map(|_| match fam {
                    Some(Some(f)) => f.curve(&mut r),
                    Some(None) => tie_curve(&mut r).1,
                    None => gen::random_curve(&mut r, &GenParams::default()),
                })
                .collect();
            let before = curves.len();
            let curves: Vec<NurbsCurve> = curves
                .into_iter()
                .filter(|c| c.num_points() <= a.max_points)
                .collect();
            skipped += before - curves.len();
            let refs: Vec<ReferenceBox> = curves.par_iter().map(reference_box).collect();
            for (si, s) in strategies.iter().enumerate() {
                let mut acc = Acc::default();
                for (ci, (c, rb)) in curves.iter().zip(&refs).enumerate() {
                    let (t, t_off, e) = time_enclose(s.as_ref(), c);
                    if let Some(dir) = &a.dump {
                        dump(dir, (fname, ci, s.name()), c, &e, rb, (t, t_off));
                    }
                    acc.times.push(t);
                    acc.times_off.push(t_off);
                    measure(c, &e, rb, &mut acc);
                }
                println!("{}", acc.row(fname, s.name()));
                totals[si].merge(&acc);
            }
        }
        println!("\n## All families\n\n{header}");
        for (s, acc) in strategies.iter().zip(&totals) {
            println!("{}", acc.row("all", s.name()));
        }
        if skipped > 0 {
            println!(
                "\n{skipped} curves with more than {} control points skipped",
                a.max_points
            );
        }
        println!(
            "\nTightness target for newton, bezier, search-region-verified: max <= 4, median <= 1, \
             0 misses. search-region is the thesis heuristic (allowed to miss). Optimality goal \
             for newton and bezier: optimal 100%, certified >= 99.9%, 0 false certificates, \
             cert +% <= 20."
        );
        if partial {
            return;
        }
        let ecdf: Vec<(String, Vec<f64>)> = strategies
            .iter()
            .zip(&totals)
            .map(|(s, acc)| (s.name().to_string(), acc.dist.clone()))
            .collect();
        let svg = std::path::Path::new("results").join("tightness.svg");
        plots::ecdf_plot(
            &svg,
            "Distance of each bound to the optimal double (all families)",
            "1 + distance to the optimal double [ulps of the value, log scale]",
            &ecdf,
            &format!("{}, commit {}, {}", prov.command, prov.commit, prov.cpu),
        );
        eprintln!("wrote {}", svg.display());
    }
}
