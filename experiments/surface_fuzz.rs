//! A surface fuzz campaign without libFuzzer (`cargo fuzz` needs a nightly toolchain): the
//! body of the `surface` fuzz target (`robust::targets::surface`: decode, every surface
//! strategy, containment and flag checks) on random byte strings and on mutations of a pool
//! of inputs (bit flips, the decoder's special bytes, raw f64 bit patterns, splices,
//! truncations), with a cheap feedback: an input joins the pool when its decoded surface has
//! a new (degrees, dimension, rational, net size, termination) signature.
//!
//! `cargo run --release --bin surface_fuzz -- SECONDS [FINDINGS_DIR [CORPUS_DIR]]`: prints the
//! executions and findings; writes every panic (`crash-*`), every input slower than 10 s
//! (`slow-unit-*`) and the slowest input (`slowest-*`) to FINDINGS_DIR, and one input per
//! signature (at most 40) to CORPUS_DIR.
use nurbs_box::testkit::robust::{surface_from_bytes, targets};
use std::collections::HashSet;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// xorshift64: the campaign's randomness (reproducible from the seed).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// FNV-1a, the name of a saved input.
fn fnv(b: &[u8]) -> String {
    let h = b.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &x| {
        (h ^ u64::from(x)).wrapping_mul(0x100_0000_01b3)
    });
    format!("{h:016x}")
}

/// f64 bit patterns that stress the decoder and the strategies.
const PATTERNS: &[f64] = &[
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    f64::MAX,
    f64::MIN_POSITIVE,
    5e-324,
    1e300,
    -1e300,
    1e-300,
    f64::INFINITY,
    f64::NAN,
    1.0 + f64::EPSILON,
    1.0 - f64::EPSILON / 2.0,
    0.1,
    1.0 / 3.0,
];

fn mutate(rng: &mut Rng, src: &[u8], pool: &[Vec<u8>]) -> Vec<u8> {
    let mut b = src.to_vec();
    for _ in 0..1 + rng.below(4) {
        if b.is_empty() {
            b.push(rng.next() as u8);
        }
        let i = rng.below(b.len());
        match rng.below(8) {
            0 => b[i] ^= 1 << rng.below(8),
            1 => b[i] = rng.next() as u8,
            // the decoder's special tail bytes: flat runs (250, 251), perturbations (240..249)
            2 => b[i] = 240 + rng.below(12) as u8,
            3 => {
                let x = PATTERNS[rng.below(PATTERNS.len())].to_le_bytes();
                let at = i.min(b.len().saturating_sub(8));
                for (k, y) in x.iter().enumerate() {
                    if at + k < b.len() {
                        b[at + k] = *y;
                    }
                }
            }
            4 => {
                let n = 1 + rng.below(16);
                b.truncate(b.len().saturating_sub(n).max(1));
            }
            5 => {
                let extra: Vec<u8> = (0..1 + rng.below(32)).map(|_| rng.next() as u8).collect();
                b.splice(i..i, extra);
            }
            6 if !pool.is_empty() => {
                let o = &pool[rng.below(pool.len())];
                let j = rng.below(o.len());
                b.truncate(i);
                b.extend_from_slice(&o[j..]);
            }
            _ => b[0] = rng.next() as u8,
        }
    }
    b.truncate(2048);
    b
}

/// The signature of an input for the feedback (`None`: not a valid surface): degrees,
/// dimension, weights, net size, work-limit mode and magnitude of the net.
fn signature(b: &[u8]) -> Option<String> {
    let Some(Ok(s)) = surface_from_bytes(b) else {
        return None;
    };
    let size = |n: usize| n.min(8);
    let mag = (0..s.dim())
        .map(|j| s.coord_scale(j))
        .fold(0.0f64, f64::max)
        .log2()
        .clamp(-1100.0, 1100.0) as i64
        / 64;
    Some(format!(
        "{} {} {} {} {} {} {} {mag}",
        s.degree_u().min(6),
        s.degree_v().min(6),
        s.dim().min(4),
        s.is_rational(),
        size(s.rows()),
        size(s.cols()),
        b[0] % 4 == 1,
    ))
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let secs: u64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(60);
    let findings = args.get(2).map(PathBuf::from);
    let corpus = args.get(3).map(PathBuf::from);
    for d in findings.iter().chain(corpus.iter()) {
        std::fs::create_dir_all(d).expect("writable directory");
    }
    std::panic::set_hook(Box::new(|_| {}));
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let (mut pool, mut seen): (Vec<Vec<u8>>, HashSet<String>) = (Vec::new(), HashSet::new());
    let start = Instant::now();
    let (mut execs, mut valid, mut crashes, mut slow) = (0u64, 0u64, 0u64, 0u64);
    let mut slowest = (Duration::ZERO, Vec::new());
    let mut last = Instant::now();
    while start.elapsed() < Duration::from_secs(secs) {
        let input = if pool.is_empty() || rng.below(4) == 0 {
            let len = 20 + rng.below(400);
            let mut b: Vec<u8> = (0..len).map(|_| rng.next() as u8).collect();
            // most inputs ordinary (as `surface_target_on_random_bytes`)
            if rng.below(3) != 0 {
                for x in b.iter_mut().skip(1) {
                    *x = (*x).min(239);
                }
            }
            b
        } else {
            let src = pool[rng.below(pool.len())].clone();
            mutate(&mut rng, &src, &pool)
        };
        let t = Instant::now();
        let r = catch_unwind(AssertUnwindSafe(|| targets::surface(&input)));
        let dt = t.elapsed();
        execs += 1;
        let save = |dir: &Option<PathBuf>, kind: &str, b: &[u8]| {
            if let Some(d) = dir {
                let _ = std::fs::write(d.join(format!("{kind}-{}", fnv(b))), b);
            }
        };
        if r.is_err() {
            crashes += 1;
            eprintln!("crash: {}", fnv(&input));
            save(&findings, "crash", &input);
            continue;
        }
        if dt > Duration::from_secs(10) {
            slow += 1;
            eprintln!("slow unit ({dt:?}): {}", fnv(&input));
            save(&findings, "slow-unit", &input);
        }
        if dt > slowest.0 {
            slowest = (dt, input.clone());
        }
        if let Some(sig) = signature(&input) {
            valid += 1;
            if seen.insert(sig) {
                if seen.len() <= 40 {
                    save(&corpus, "seed", &input);
                }
                pool.push(input);
            }
        }
        if last.elapsed() > Duration::from_secs(60) {
            last = Instant::now();
            eprintln!(
                "{:.0}s: {execs} executions, {valid} valid surfaces, {} signatures, {crashes} crashes, {slow} slow units, slowest {:?}",
                start.elapsed().as_secs_f64(),
                seen.len(),
                slowest.0
            );
        }
    }
    if !slowest.1.is_empty() {
        // the slowest input, to replay (bounded time) with the findings
        let kind = format!("slowest-{}ms", slowest.0.as_millis());
        let d = findings.as_ref();
        if let Some(d) = d {
            let _ = std::fs::write(d.join(format!("{kind}-{}", fnv(&slowest.1))), &slowest.1);
        }
    }
    println!(
        "{execs} executions in {:.0} s, {valid} valid surfaces, {} signatures, {crashes} crashes, {slow} slow units (> 10 s), slowest input {:?} ({})",
        start.elapsed().as_secs_f64(),
        seen.len(),
        slowest.0,
        fnv(&slowest.1)
    );
}
