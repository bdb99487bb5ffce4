//! Long-run soundness audit against the exact extremum: random byte strings are decoded into
//! extreme curves (`robust::curve_from_bytes`: degree up to 40, dimension up to 10, magnitudes
//! 1e±300, raw f64 bit patterns, weights 1e±6, flat runs, clustered / multiple / unclamped knots),
//! or, with `--curves lane`, curves drawn at the edges of the driver's lane
//! (`gen::lane_edge_curve`: moderate curves of degree 2 to 5 at its magnitude and weight
//! windows' limits, with ties, tangents, symmetric extrema at knots, subnormal and huge
//! domains), which the byte strings rarely hit; every registered verified strategy encloses
//! each valid curve (the same `strategy_by_name` objects the command line uses), every outer
//! bound is compared with the 256-bit reference box (`reference::reference_box`), every inner
//! bound with the exact extremum, and every optimality certificate with the optimal double of
//! the exact extremum (`reference::check_certificates`). The fuzz targets check against sampled
//! interval evaluations; this checks against the extremum itself, which sampling can miss by a
//! hair.
//!
//! Run: `cargo run --release --features mpfr --bin reference_audit [-- --cases N --seed S
//! --seconds T --curves bytes|lane --show-worst 1]`, or as in the README `... >
//! results/reference_audit.md` (defaults: 2000 cases, seed 1, no time limit, byte strings).
//! Prints a summary per strategy (worst and median distance in ulps of the coordinate scale,
//! certificates, terminations) and, for every violation or false certificate, the curve as
//! JSON; exits 1 if there was one.

#[cfg(not(feature = "mpfr"))]
fn main() {
    eprintln!("the reference audit needs the reference: run it with --features mpfr");
    std::process::exit(2);
}

#[cfg(feature = "mpfr")]
fn main() {
    imp::main();
}

#[cfg(feature = "mpfr")]
mod imp {
    use nurbs_box::enclose::{all_strategies, Guarantee};
    use nurbs_box::testkit::gen::lane_edge_curve;
    use nurbs_box::testkit::reference::{
        check_certificates, inner_reached, reference_box, ulps_outside,
    };
    use nurbs_box::testkit::robust::curve_from_bytes;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use std::collections::BTreeMap;
    use std::time::{Duration, Instant};

    fn arg(name: &str) -> Option<String> {
        let a: Vec<String> = std::env::args().collect();
        a.iter()
            .position(|x| x == name)
            .and_then(|i| a.get(i + 1).cloned())
    }

    #[derive(Default)]
    struct Tally {
        dists: Vec<f64>,
        terminations: BTreeMap<String, usize>,
        violations: usize,
        /// certificates (`optimal_lo` / `optimal_hi` set) and false ones (the bound is not the
        /// optimal double of the exact extremum: `check_certificates`)
        certificates: usize,
        false_certificates: usize,
        /// the loosest bound so far: (ulps, coordinate, curve JSON)
        worst: Option<(f64, usize, String)>,
    }

    pub fn main() {
        let cases: usize = arg("--cases").map_or(2000, |s| s.parse().expect("--cases N"));
        let seed: u64 = arg("--seed").map_or(1, |s| s.parse().expect("--seed S"));
        let limit = arg("--seconds")
            .map(|s| Duration::from_secs_f64(s.parse().expect("--seconds T")))
            .unwrap_or(Duration::MAX);
        // the curves: decoded random bytes (the default), or the lane's edges
        let lane = match arg("--curves").as_deref() {
            None | Some("bytes") => false,
            Some("lane") => true,
            Some(o) => panic!("--curves bytes|lane, not {o}"),
        };
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let strategies = all_strategies(None);
        let mut tally: BTreeMap<&str, Tally> = BTreeMap::new();
        let (mut valid, mut invalid, mut done) = (0usize, 0usize, 0usize);
        let t0 = Instant::now();
        for _ in 0..cases {
            if t0.elapsed() > limit {
                break;
            }
            done += 1;
            let (c, bytes) = if lane {
                (lane_edge_curve(&mut rng), Vec::new())
            } else {
                let len = rng.random_range(1..300);
                let bytes: Vec<u8> = (0..len).map(|_| rng.random()).collect();
                (curve_from_bytes(&bytes).ok(), bytes)
            };
            let Some(c) = c else {
                invalid += 1;
                continue;
            };
            valid += 1;
            let rb = reference_box(&c);
            for s in &strategies {
                if s.guarantee() != Guarantee::Verified {
                    continue;
                }
                let e = s.enclose(&c);
                let t = tally.entry(s.name()).or_default();
                // every certificate agrees with MPFR's rounding of the exact extremum
                t.certificates += e
                    .coords
                    .iter()
                    .map(|cb| cb.optimal_lo as usize + cb.optimal_hi as usize)
                    .sum::<usize>();
                if let Err(m) = check_certificates(&c, &rb, &e) {
                    t.false_certificates += 1;
                    println!(
                        "FALSE CERTIFICATE {m}\n  {}",
                        nurbs_box::io::curve_to_json(&c)
                    );
                }
                for (j, cb) in e.coords.iter().enumerate() {
                    let scale = c.coord_scale(j);
                    let dlo = ulps_outside(cb.lo, &rb.lo[j], scale, false);
                    let dhi = ulps_outside(cb.hi, &rb.hi[j], scale, true);
                    // inner bounds: values the curve reaches, so min <= inner_lo, inner_hi <= max,
                    // up to the reference's resolution (2^-160 of the scale at 256 bits, see
                    // ulps_outside: a clamped end value of 6e3 in a coordinate of scale 2e226
                    // is below it)
                    let inner_ok = inner_reached(&rb, j, cb.inner_lo, cb.inner_hi, scale);
                    *t.terminations
                        .entry(format!("{:?}", cb.termination))
                        .or_default() += 1;
                    let d = dlo.max(dhi);
                    t.dists.push(d);
                    if t.worst.as_ref().is_none_or(|w| d > w.0) {
                        t.worst = Some((d, j, nurbs_box::io::curve_to_json(&c)));
                    }
                    if !(dlo >= 0.0 && dhi >= 0.0 && inner_ok) {
                        t.violations += 1;
                        println!(
                            "VIOLATION {} coordinate {j}: lo {:e} hi {:e} inner [{:e}, {:e}] \
                             exact [{}, {}] (ulps outside {dlo:e} / {dhi:e})\n  bytes {bytes:?}\n  {}",
                            s.name(),
                            cb.lo,
                            cb.hi,
                            cb.inner_lo,
                            cb.inner_hi,
                            rb.lo[j],
                            rb.hi[j],
                            nurbs_box::io::curve_to_json(&c)
                        );
                    }
                }
            }
        }
        let prov = nurbs_box::testkit::report::Provenance::collect();
        println!(
            "# Reference audit: {} vs the exact box\n",
            if lane {
                "curves at the edges of the driver's lane"
            } else {
                "random extreme curves"
            }
        );
        println!(
            "command: `{}`, commit {}, {} ({} cores)\n",
            prov.command, prov.commit, prov.cpu, prov.cores
        );
        println!(
            "{done} {}, {valid} valid curves, {invalid} typed errors, {:.1} s (seed {seed}); \
             distances in ulps of the coordinate scale (outer bound minus exact extremum, \
             positive = safe side); certificates: the optimality flags set, false ones those \
             whose bound is not the optimal double of the exact extremum\n",
            if lane {
                "draws (`lane_edge_curve`)"
            } else {
                "byte strings"
            },
            t0.elapsed().as_secs_f64()
        );
        println!(
            "| strategy | bounds | violations | certificates | false certificates | median ulps | \
             p99 ulps | max ulps | terminations |"
        );
        println!("|---|---:|---:|---:|---:|---:|---:|---:|---|");
        let mut bad = 0;
        for (name, t) in &mut tally {
            t.dists.sort_by(f64::total_cmp);
            let q = |f: f64| {
                t.dists
                    .get(((t.dists.len() as f64 - 1.0) * f).round() as usize)
                    .copied()
                    .unwrap_or(f64::NAN)
            };
            println!(
                "| {name} | {} | {} | {} | {} | {:.3} | {:.3e} | {:.3e} | {:?} |",
                t.dists.len(),
                t.violations,
                t.certificates,
                t.false_certificates,
                q(0.5),
                q(0.99),
                q(1.0),
                t.terminations
            );
            bad += t.violations + t.false_certificates;
        }
        if arg("--show-worst").is_some() {
            for (name, t) in &tally {
                if let Some((d, j, json)) = &t.worst {
                    println!("worst {name}: {d:.3e} ulps, coordinate {j}: {json}");
                }
            }
        }
        if bad > 0 {
            std::process::exit(1);
        }
    }
}
