//! Replay a fuzz input: `robust_replay structured|json FILE`. Prints each curve (JSON) and,
//! per strategy, the time, termination and any violated guarantee.
use nurbs_box::enclose::all_strategies;
use nurbs_box::io::{curve_to_json, read_curves};
use nurbs_box::testkit::robust::{check_params, check_strategy, curve_from_bytes};
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let bytes = std::fs::read(&args[2]).expect("readable input");
    let curves: Vec<_> = if args[1] == "json" {
        read_curves(&bytes)
            .into_iter()
            .map(|(_, r)| r.map_err(|e| e.to_string()))
            .collect()
    } else {
        vec![curve_from_bytes(&bytes).map_err(|e| e.to_string())]
    };
    for c in curves {
        let c = match c {
            Ok(c) => c,
            Err(e) => {
                println!("error: {e}");
                continue;
            }
        };
        println!("{}", curve_to_json(&c));
        let params = check_params(&c, 4, &[]);
        for s in all_strategies(None) {
            let t = Instant::now();
            let r = check_strategy(s.as_ref(), &c, &params);
            let dt = t.elapsed().as_secs_f64();
            match r {
                Ok(e) => println!(
                    "  {} {dt:.3}s {:?} lo={:?} hi={:?} stats={:?}",
                    s.name(),
                    e.termination(),
                    e.lo(),
                    e.hi(),
                    e.stats()
                ),
                Err(v) => println!("  {} {dt:.3}s VIOLATION {}", s.name(), v.what),
            }
        }
    }
}
