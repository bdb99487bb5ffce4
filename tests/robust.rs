//! Robustness: extreme valid curves get sound, finite boxes from every strategy in bounded time;
//! arbitrary f64 bit patterns give a sound box or a typed error, never a panic; the fuzz corpus and
//! every fuzz finding replay as regression tests.
//!
//! Containment is checked with interval evaluation at dense parameters
//! (`validate::check_containment`) and, with `--features mpfr`, against the 256-bit reference
//! box (`reference::reference_box`).

use nurbs_box::enclose::{all_strategies, Guarantee, Termination};
use nurbs_box::testkit::robust::{
    check_all_strategies, check_enclosure, check_params, raw_strategies, targets,
};
use nurbs_box::{Enclosure, NurbsCurve};
use proptest::prelude::*;
use std::time::{Duration, Instant};

mod common;
use common::config;

/// Clamped uniform knots for `npts` points of degree p on [a, b].
fn clamped(p: usize, npts: usize, a: f64, b: f64) -> Vec<f64> {
    let ni = npts - p - 1;
    (0..npts + p + 1)
        .map(|i| {
            let t = i.saturating_sub(p).min(ni + 1) as f64 / (ni + 1) as f64;
            if t == 1.0 {
                b
            } else {
                a + t * (b - a)
            }
        })
        .collect()
}

/// Deterministic wiggly values in [-1, 1].
fn wiggle(i: usize, j: usize) -> f64 {
    ((i * 7 + j * 3) % 11) as f64 / 5.0 - 1.0 + 0.1 * ((i + j) as f64 * 0.37).sin()
}

fn curve(p: usize, knots: Vec<f64>, pts: Vec<Vec<f64>>, w: Option<Vec<f64>>) -> NurbsCurve {
    NurbsCurve::new(p, knots, pts, w).expect("valid test curve")
}

/// Extreme valid curves (name, curve): magnitudes at the ends of the f64 range, extreme
/// weights, narrow spans, tiny and huge domains, flat coordinates, jumps, ten dimensions, and
/// degrees up to 150.
fn extreme_curves() -> Vec<(&'static str, NurbsCurve)> {
    let mut v = Vec::new();
    // coordinates 1e300 .. 1e-300 with weights 1e6 .. 1e-6: w P overflows without rescaling
    v.push((
        "huge_and_tiny_coordinates_extreme_weights",
        curve(
            3,
            clamped(3, 6, 0.0, 1.0),
            (0..6)
                .map(|i| vec![1e300 * wiggle(i, 0), 1e-300 * wiggle(i, 1), wiggle(i, 2)])
                .collect(),
            Some(vec![1e6, 1e-6, 3.0, 1e6, 0.5, 1e-6]),
        ),
    ));
    // one coordinate holding both 1e300 and subnormal values: the exact rescaling rounds the
    // subnormal ones and widens the box by one subnormal step (of the scaled coordinate)
    v.push((
        "huge_and_subnormal_in_one_coordinate",
        curve(
            2,
            clamped(2, 6, 0.0, 1.0),
            vec![
                vec![-3e-320, 1.0],
                vec![1e300, -4e-320],
                vec![7e-322, 5e-324],
                vec![-1e-310, 2.0],
                vec![-2e-323, -1e-300],
                vec![1e-320, 0.0],
            ],
            Some(vec![1.0, 1e-6, 2.0, 1.0, 1e6, 3.0]),
        ),
    ));
    // weight ratio 1e600 with coordinates near the f64 limit
    v.push((
        "weight_ratio_1e600",
        curve(
            2,
            clamped(2, 3, 0.0, 1.0),
            vec![
                vec![1e308, -1e308],
                vec![-1.7e308, 1.7e308],
                vec![1e-320, 0.0],
            ],
            Some(vec![1e300, 1e-300, 1.0]),
        ),
    ));
    // coordinates near the top of the f64 range
    v.push((
        "near_max_coordinates",
        curve(
            2,
            clamped(2, 5, 0.0, 1.0),
            (0..5).map(|i| vec![1.5e308 * wiggle(i, 0)]).collect(),
            Some(vec![1.0, 2.0, 0.5, 4.0, 1.0]),
        ),
    ));
    // subnormal coordinates
    v.push((
        "subnormal_coordinates",
        curve(
            2,
            clamped(2, 4, 0.0, 1.0),
            vec![
                vec![5e-324, 0.0],
                vec![-3e-320, 1e-310],
                vec![7e-323, -2e-315],
                vec![0.0, 4e-324],
            ],
            Some(vec![1.0, 3.0, 1.0, 2.0]),
        ),
    ));
    // knot spans of 1e-12 between ordinary ones
    v.push((
        "narrow_spans",
        curve(
            3,
            vec![
                0.,
                0.,
                0.,
                0.,
                0.3,
                0.3 + 1e-12,
                0.3 + 2e-12,
                0.7,
                0.7 + 1e-12,
                1.,
                1.,
                1.,
                1.,
            ],
            (0..9).map(|i| vec![wiggle(i, 0), wiggle(i, 1)]).collect(),
            Some((0..9).map(|i| 1.0 + (i % 3) as f64).collect()),
        ),
    ));
    // weights 1e-6 .. 1e6
    v.push((
        "extreme_weights",
        curve(
            3,
            clamped(3, 8, 0.0, 1.0),
            (0..8).map(|i| vec![wiggle(i, 0), wiggle(i, 1)]).collect(),
            Some(vec![1e-6, 1e6, 1e-6, 1e6, 1.0, 1e-3, 1e3, 1e-6]),
        ),
    ));
    // degree 40, rational
    v.push((
        "degree_40",
        curve(
            40,
            clamped(40, 45, 0.0, 1.0),
            (0..45).map(|i| vec![wiggle(i, 0), wiggle(i, 1)]).collect(),
            Some((0..45).map(|i| 1.0 + (i % 4) as f64 * 0.5).collect()),
        ),
    ));
    // flat coordinates: constant everywhere / on whole spans
    v.push((
        "flat_coordinates",
        curve(
            3,
            clamped(3, 9, 0.0, 1.0),
            (0..9)
                .map(|i| {
                    vec![
                        0.25,
                        if (2..7).contains(&i) {
                            -1.5
                        } else {
                            wiggle(i, 1)
                        },
                    ]
                })
                .collect(),
            Some((0..9).map(|i| 1.0 + (i % 2) as f64).collect()),
        ),
    ));
    // symmetric: the maximum of coordinate 0 is exactly at the middle knot 0; coordinate 1
    // is monotone (extrema at the end points)
    v.push((
        "extrema_at_knot_and_ends",
        curve(
            2,
            vec![-1., -1., -1., -0.5, 0., 0.5, 1., 1., 1.],
            vec![
                vec![0., -2.],
                vec![1., -1.],
                vec![3., 0.],
                vec![3., 1.],
                vec![1., 2.],
                vec![0., 3.],
            ],
            None,
        ),
    ));
    // unclamped, shifted domain
    v.push((
        "unclamped",
        curve(
            3,
            (0..11).map(|i| 1e4 + i as f64 * 0.75).collect(),
            (0..7).map(|i| vec![wiggle(i, 0)]).collect(),
            Some((0..7).map(|i| 0.5 + (i % 3) as f64).collect()),
        ),
    ));
    // discontinuous (interior multiplicity p + 1)
    v.push((
        "discontinuous",
        curve(
            2,
            vec![0., 0., 0., 0.5, 0.5, 0.5, 1., 1., 1.],
            vec![
                vec![0.],
                vec![2.],
                vec![1.],
                vec![-1.],
                vec![-3.],
                vec![0.5],
            ],
            None,
        ),
    ));
    // 10-D with mixed magnitudes
    v.push((
        "ten_dimensional",
        curve(
            4,
            clamped(4, 12, -2.0, 3.0),
            (0..12)
                .map(|i| {
                    (0..10)
                        .map(|j| wiggle(i, j) * 10f64.powi(60 * j as i32 - 270))
                        .collect()
                })
                .collect(),
            Some((0..12).map(|i| 1.0 + (i % 5) as f64).collect()),
        ),
    ));
    // tiny and huge parameter domains
    v.push((
        "tiny_domain",
        curve(
            3,
            clamped(3, 7, 0.0, 1e-300),
            (0..7).map(|i| vec![wiggle(i, 0), wiggle(i, 1)]).collect(),
            Some((0..7).map(|i| 1.0 + (i % 3) as f64).collect()),
        ),
    ));
    v.push((
        "huge_domain",
        curve(
            3,
            clamped(3, 7, -1e300, 1e300),
            (0..7).map(|i| vec![wiggle(i, 0), wiggle(i, 1)]).collect(),
            None,
        ),
    ));
    // large common offset (cancellation) in a coordinate
    v.push((
        "offset_coordinates",
        curve(
            3,
            clamped(3, 8, 0.0, 1.0),
            (0..8)
                .map(|i| vec![1e12 + wiggle(i, 0), -7e15 + wiggle(i, 1)])
                .collect(),
            None,
        ),
    ));
    v
}

/// Run every strategy on `c` (`common::check_registry`: sound at dense parameters, finite and
/// ordered boxes, within `limit`). Returns the verified results.
fn check_curve(name: &str, c: &NurbsCurve, per_span: usize, limit: Duration) -> Vec<Enclosure> {
    common::check_registry(name, c, per_span, limit)
        .into_iter()
        .filter(|e| e.verified)
        .collect()
}

#[test]
fn extreme_curves_get_sound_finite_boxes() {
    for (name, c) in extreme_curves() {
        let encs = check_curve(name, &c, 20, Duration::from_secs(30));
        #[cfg(feature = "mpfr")]
        mpfr::check_reference(name, &c, &encs);
        let _ = encs;
    }
}

#[test]
fn hundred_thousand_control_points() {
    let n = 100_000;
    let c = curve(
        3,
        clamped(3, n, 0.0, 1.0),
        (0..n).map(|i| vec![wiggle(i, 0)]).collect(),
        None,
    );
    let encs = check_curve("1e5_points", &c, 1, Duration::from_secs(60));
    // every verified strategy but the hull finds the exact extremes here (the curve passes
    // close to the control points) within a few ulps
    for e in &encs[1..] {
        assert!(
            e.coords[0].gap() < 1e-12,
            "{}: gap {:e}",
            e.strategy,
            e.coords[0].gap()
        );
    }
}

/// Adversarial curves for the work limits: each enclose call finishes quickly (generous
/// bound for a loaded machine) with a sound box, and a limit reached is reported.
#[test]
fn adversarial_curves_finish_quickly() {
    let mut cases: Vec<(&str, NurbsCurve)> = Vec::new();
    // many near-double roots of C': a constant plus alternating perturbations of an ulp
    let n = 400;
    cases.push((
        "near_double_roots",
        curve(
            3,
            clamped(3, n, 0.0, 1.0),
            (0..n)
                .map(|i| vec![1.0 + if i % 2 == 0 { 0.0 } else { f64::EPSILON }])
                .collect(),
            Some(
                (0..n)
                    .map(|i| 1.0 + (i % 3) as f64 * f64::EPSILON)
                    .collect(),
            ),
        ),
    ));
    // high degree with ulp noise: C' is tiny and sign-changing everywhere
    cases.push((
        "degree_40_ulp_noise",
        curve(
            40,
            clamped(40, 60, 0.0, 1.0),
            (0..60)
                .map(|i| vec![1.0 + (i % 3) as f64 * f64::EPSILON, wiggle(i, 1)])
                .collect(),
            None,
        ),
    ));
    // beyond the fuzz decoder's degree range (up to 40): degree 150, one span (expensive
    // evaluations)
    cases.push((
        "degree_150",
        curve(
            150,
            clamped(150, 151, 0.0, 1.0),
            (0..151).map(|i| vec![wiggle(i, 0)]).collect(),
            None,
        ),
    ));
    // flat coordinate with sub-ulp-sized weight variation
    cases.push((
        "flat_with_weights",
        curve(
            5,
            clamped(5, 200, 0.0, 1.0),
            (0..200).map(|i| vec![0.1, wiggle(i, 1)]).collect(),
            Some((0..200).map(|i| 1.0 + (i % 7) as f64 * 1e-3).collect()),
        ),
    ));
    for (name, c) in cases {
        check_curve(name, &c, 3, Duration::from_secs(20));
    }
    // the budget is reported: with a work budget that degree 150 exhausts, the side newton
    // leaves loose goes to the `bezier` search, which either resolves it (then the coordinate
    // is converged, within the stopping gap, and the rescue is counted) or reports its own
    // limit; with the default budget newton converges within the stopping gap or reports it
    let c = curve(
        150,
        clamped(150, 151, 0.0, 1.0),
        (0..151).map(|i| vec![wiggle(i, 0)]).collect(),
        None,
    );
    let gap = 2.0 * nurbs_box::num::ulp(c.coord_scale(0));
    for max_work in [nurbs_box::enclose::DEFAULT_MAX_WORK, 151 * 151 * 40] {
        let e = nurbs_box::enclose::strategy_with_work("newton", None, max_work)
            .unwrap()
            .enclose(&c);
        let cb = &e.coords[0];
        match e.termination() {
            Termination::WorkLimit => {}
            Termination::Converged => {
                if max_work < nurbs_box::enclose::DEFAULT_MAX_WORK {
                    assert!(cb.stats.fast_fallbacks >= 1, "{:?}", cb.stats);
                }
                assert!(cb.gap() <= gap, "gap {} > {gap}", cb.gap());
            }
            t => panic!("termination {t:?} (max_work {max_work})"),
        }
    }

    // above MAX_SEARCH_DEGREE: the control-point box at once, from every strategy
    let p = nurbs_box::enclose::MAX_SEARCH_DEGREE + 500;
    let c = curve(
        p,
        clamped(p, p + 1, 0.0, 1.0),
        (0..=p).map(|i| vec![wiggle(i, 0), wiggle(i, 1)]).collect(),
        Some((0..=p).map(|i| 1.0 + (i % 3) as f64).collect()),
    );
    let params = [0.0, 0.3, 1.0];
    for s in all_strategies(None) {
        let t = Instant::now();
        let e = s.enclose(&c);
        assert!(t.elapsed() < Duration::from_secs(1), "{}", s.name());
        assert_eq!(e.termination(), Termination::WorkLimit);
        check_enclosure(&c, &e, s.guarantee(), &params).unwrap();
    }
}

/// An f64 from a mix of hostile bit patterns and nice values.
fn any_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => any::<u64>().prop_map(f64::from_bits),
        1 => prop::sample::select(vec![
            0.0, -0.0, 1.0, -1.0, 0.5, 5e-324, -5e-324, f64::MIN_POSITIVE, f64::MAX, -f64::MAX,
            1e300, -1e300, 1e-300, f64::EPSILON, 1.0 + f64::EPSILON, f64::NAN, f64::INFINITY,
        ]),
        2 => -4.0..4.0f64,
    ]
}

/// Raw curve data from arbitrary bit patterns; knots sorted (by total order) most of the time
/// so that many cases are valid curves.
/// (degree, knots, control points, weights) before validation.
type RawCurve = (usize, Vec<f64>, Vec<Vec<f64>>, Option<Vec<f64>>);

fn raw_curve() -> impl Strategy<Value = RawCurve> {
    (1usize..=4, 0usize..5, 1usize..=3).prop_flat_map(|(p, extra, d)| {
        let np = p + 1 + extra;
        (
            Just(p),
            prop::collection::vec(any_f64(), np + p + 1),
            any::<u8>(),
            prop::collection::vec(prop::collection::vec(any_f64(), d), np),
            prop::option::of(prop::collection::vec(any_f64(), np)),
        )
            .prop_map(|(p, mut k, sort, pts, w)| {
                if sort % 4 != 0 {
                    k.sort_by(f64::total_cmp);
                }
                // positive weights most of the time (abs keeps NaN / 0 / inf: still invalid)
                let w = w.map(|w| {
                    w.into_iter()
                        .map(|x| if sort % 8 == 1 { x } else { x.abs() })
                        .collect()
                });
                (p, k, pts, w)
            })
    })
}

proptest! {
    #![proptest_config(config(64))]

    /// Every strategy returns a sound box (or the curve is a typed error); never a panic.
    #[test]
    fn arbitrary_bit_patterns_give_a_sound_box_or_a_typed_error((p, k, pts, w) in raw_curve()) {
        match NurbsCurve::new(p, k, pts, w) {
            Err(e) => {
                prop_assert!(!e.kind().is_empty());
                prop_assert!(!e.to_string().is_empty());
            }
            Ok(c) => {
                let v = check_all_strategies(&c, 6, &[]);
                prop_assert!(v.is_empty(), "{:?}\n{}", v, nurbs_box::curve_to_json(&c));
                // the strategies without the rescaling wrapper must be sound as well (their
                // intermediates may overflow)
                let v = nurbs_box::testkit::robust::check_strategies(&raw_strategies(), &c, 6, &[]);
                prop_assert!(v.is_empty(), "raw: {:?}\n{}", v, nurbs_box::curve_to_json(&c));
                // and through the JSON format
                let back = nurbs_box::parse_curve(nurbs_box::curve_to_json(&c).as_bytes());
                prop_assert_eq!(back.as_ref(), Ok(&c));
            }
        }
    }
}

/// A magnitude for the jump curves below: tiny, moderate or huge, either sign (0 included).
fn magnitude() -> impl Strategy<Value = f64> {
    prop_oneof![
        prop::sample::select(vec![0.0, 5e-324, 1e-320, 1e-300, 1e300, 1.9e94, f64::MAX]),
        -1e3..1e3f64,
        (-308i32..=308, -1.0..1.0f64).prop_map(|(e, m)| m * 10f64.powi(e)),
    ]
}

proptest! {
    // (at most 64 cases also when PROPTEST_CASES asks for more: a case takes ~75 ms in a
    // release build, every strategy with and without the driver in subnormal arithmetic)
    #![proptest_config(ProptestConfig { cases: config(64).cases.min(64), ..config(64) })]

    /// Curves with a jump (an interior knot of multiplicity p + 1) and weights whose products
    /// with the control values overflow or underflow, next to spans as narrow as a few
    /// subnormals: both one-sided limits at the jump must be in every verified box, with and
    /// without the driver (the class of the end-coefficient fault in
    /// `subnormal_knots_and_weights_with_an_overflowing_homogeneous_point`).
    #[test]
    fn jumps_next_to_overflowing_weights_stay_in_the_box(
        p in 1usize..=3,
        tiny in any::<bool>(),
        xs in prop::collection::vec(magnitude(), 8),
        ws in prop::collection::vec(prop::sample::select(vec![5e-324, 1e-300, 1.0, 3.0, 1e214, 1e300]), 8),
    ) {
        // clamped, p + 1 points on each side of the jump at 0
        let np = 2 * (p + 1);
        let (a, b) = if tiny { (-1e-323, 1e-323) } else { (-1.0, 1.0) };
        let mut kn = vec![a; p + 1];
        kn.extend(vec![0.0; p + 1]);
        kn.extend(vec![b; p + 1]);
        let pts: Vec<Vec<f64>> = (0..np).map(|i| vec![xs[i % xs.len()], 0.0]).collect();
        let w: Vec<f64> = (0..np).map(|i| ws[i % ws.len()]).collect();
        let c = NurbsCurve::new(p, kn, pts, Some(w)).unwrap();
        let v = nurbs_box::testkit::robust::check_strategies(&raw_strategies(), &c, 6, &[0.0]);
        prop_assert!(v.is_empty(), "raw: {:?}\n{}", v, nurbs_box::curve_to_json(&c));
        let v = check_all_strategies(&c, 6, &[0.0]);
        prop_assert!(v.is_empty(), "{:?}\n{}", v, nurbs_box::curve_to_json(&c));
    }
}

proptest! {
    #![proptest_config(config(24))]

    /// Structured fuzz decoder on random bytes (the fuzz target's body, in a plain test).
    #[test]
    fn structured_decoder_on_random_bytes(bytes in prop::collection::vec(any::<u8>(), 0..200)) {
        targets::structured(&bytes);
    }
}

/// A fuzz target body.
type Target = fn(&[u8]);

/// Replay every file of the given directories (relative to the crate) through the fuzz
/// target bodies; returns the number of inputs.
fn replay(dirs: &[(&str, Target)]) -> usize {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut n = 0;
    for (dir, run) in dirs {
        // a missing directory is an error, not a silent skip
        let rd = std::fs::read_dir(root.join(dir))
            .unwrap_or_else(|e| panic!("fuzz directory {dir} is missing: {e}"));
        for f in rd.flatten() {
            // (a fuzzer running meanwhile may remove files)
            let Ok(bytes) = std::fs::read(f.path()) else {
                continue;
            };
            let t = Instant::now();
            run(&bytes);
            // bounded work, not speed: a hang would take hours; the slowest finding takes
            // ~10 s over all strategies in release, more in a loaded test build
            assert!(
                t.elapsed() < Duration::from_secs(120),
                "{}: {:?}",
                f.path().display(),
                t.elapsed()
            );
            n += 1;
        }
    }
    n
}

/// Every fuzz finding (crash, timeout, slow unit) replays without a violation, in bounded time.
#[test]
fn fuzz_findings_replay() {
    // (the json target's corpus replays in `fuzz_corpus_replays`)
    let n = replay(&[
        ("tests/data/fuzz/structured", targets::structured),
        ("tests/data/fuzz/surface", targets::surface),
    ]);
    assert!(n > 0, "no fuzz findings found");
}

/// The surface fuzz target's body on pseudo-random inputs (a replay of what `cargo fuzz run
/// surface` does, without libFuzzer): the decoder must reach valid, rational and ridge
/// surfaces (so the target is not vacuous), and every strategy's box must pass the target's
/// checks (no provable containment miss, no contradictory bounds).
#[test]
fn surface_target_on_random_bytes() {
    use nurbs_box::testkit::robust::surface_from_bytes;
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let (mut valid, mut rational, mut ridge) = (0, 0, 0);
    for k in 0..400 {
        let len = 40 + k % 160;
        let mut bytes: Vec<u8> = (0..len)
            .map(|_| {
                seed ^= seed << 13;
                seed ^= seed >> 7;
                seed ^= seed << 17;
                (seed >> 24) as u8
            })
            .collect();
        // keep most inputs ordinary (small degrees, finite values, small nets)
        if k % 3 != 0 {
            for b in bytes.iter_mut().skip(1) {
                *b = (*b).min(239);
            }
        }
        if let Some(Ok(s)) = surface_from_bytes(&bytes) {
            valid += 1;
            rational += s.is_rational() as usize;
            // constant along v: every row of the net one point
            let flat_v = (0..s.rows())
                .all(|i| (0..s.cols()).all(|j| s.control_point(i, j) == s.control_point(i, 0)));
            ridge += flat_v as usize;
        }
        targets::surface(&bytes);
    }
    assert!(
        valid >= 100 && rational >= 10 && ridge >= 5,
        "{valid} {rational} {ridge}"
    );
}

/// The whole committed fuzz corpus (`fuzz/corpus`) replays without a violation. Slow (a
/// minute or two): `cargo test --test robust -- --ignored`.
#[test]
#[ignore]
fn fuzz_corpus_replays() {
    let n = replay(&[
        ("fuzz/corpus/json", targets::json),
        ("fuzz/corpus/structured", targets::structured),
        ("fuzz/corpus/surface", targets::surface),
    ]);
    assert!(n > 0, "no fuzz corpus found");
}

#[cfg(feature = "mpfr")]
mod mpfr {
    use super::*;

    /// Every verified box contains the exact box and reaches its inner bounds
    /// (`common::check_reference`), and is close to it (see `allowed`). `ROBUST_PRINT=1` prints
    /// the distances.
    pub fn check_reference(name: &str, c: &NurbsCurve, encs: &[Enclosure]) {
        for (strategy, j, dlo, dhi, term) in common::check_reference(name, c, encs) {
            if std::env::var("ROBUST_PRINT").is_ok() {
                eprintln!(
                    "{name} {strategy} j={j} {term:?} ulps outside: lo {dlo:.3e} hi {dhi:.3e}"
                );
            }
            // Tightness: the Bézier and the (Bernstein-form) Newton strategies are within a
            // few ulps of the coordinate scale; the hull is not tight at all.
            let allowed = match strategy {
                "hull" => f64::INFINITY,
                // the thesis preset keeps the thesis's 20-step limit per box: sound (checked
                // above) but it may stop far from the extremum on such curves
                "newton-thesis" => f64::INFINITY,
                "bezier" | "newton" | "search-region-verified" => 64.0,
                _ => 1e11,
            };
            assert!(
                dlo <= allowed && dhi <= allowed,
                "{name}: {strategy} coordinate {j}: {dlo} / {dhi} ulps outside the exact box"
            );
        }
    }
}

/// The exact rescaling is what makes overflowing curves finite: the raw strategies overflow
/// (soundly, to infinite bounds) on w P ~ 1e306, the registered (rescaled) ones do not.
#[test]
fn rescaling_keeps_overflowing_curves_finite() {
    use nurbs_box::enclose::{BezierSubdivision, BoxEncloser, Newton};
    let c = curve(
        3,
        clamped(3, 6, 0.0, 1.0),
        (0..6).map(|i| vec![1.5e308 * wiggle(i, 0) / 1.1]).collect(),
        Some(vec![1e6, 1e-6, 3.0, 1e6, 0.5, 1e-6]),
    );
    // the mixed-magnitude extreme curve does exercise the rounded (widened) coordinate path
    let (_, mixed) = extreme_curves()
        .into_iter()
        .find(|(n, _)| *n == "huge_and_subnormal_in_one_coordinate")
        .unwrap();
    let r = nurbs_box::enclose::Rescaling::of(&mixed).unwrap();
    assert!(r.coord_rounded[0] && r.coord_exp[0] > 900 && r.coord_exp[1] == 0);
    let raw: [&dyn BoxEncloser; 2] = [&Newton::default(), &BezierSubdivision::default()];
    let params = check_params(&c, 50, &[]);
    for s in raw {
        // sound even where w P overflows, just loose or infinite
        let e = s.enclose(&c);
        check_enclosure(&c, &e, s.guarantee(), &params).unwrap();
    }
    for name in ["newton", "bezier"] {
        let e = nurbs_box::strategy_by_name(name, None).unwrap().enclose(&c);
        let cb = &e.coords[0];
        assert!(
            cb.lo.is_finite() && cb.hi.is_finite(),
            "{name}: [{:e}, {:e}]",
            cb.lo,
            cb.hi
        );
        // (the weight ratio 1e12 costs the Newton-based strategies ~6 digits; see above)
        assert!(
            cb.gap() <= 1e-5 * c.coord_scale(0),
            "{name}: gap {:e}",
            cb.gap()
        );
    }
}

/// The command line on hostile lines interleaved with extreme valid curves: one error record
/// of the expected kind per invalid line, a finite sound box from every verified strategy for
/// every valid curve, exit status 1, nothing on stderr about panics.
#[test]
fn cli_hostile_lines_between_extreme_curves() {
    use serde_json::Value;
    use std::io::Write;
    use std::process::{Command, Stdio};
    let ok = r#"{"degree":1,"knots":[0,0,1,1],"control_points":[[0],[1]]}"#;
    let hostile: &[(&str, &str)] = &[
        (
            r#"{"degree":18446744073709551616,"knots":[0,0,1,1],"control_points":[[0],[1]]}"#,
            "invalid_degree",
        ),
        (
            r#"{"degree":1e400,"knots":[0,0,1,1],"control_points":[[0],[1]]}"#,
            "number_out_of_range",
        ),
        (
            r#"{"degree":0,"knots":[0,1],"control_points":[[0]]}"#,
            "invalid_degree",
        ),
        (
            r#"{"degree":1,"knots":[0,0,1,1],"control_points":[[0],[1]],"weights":[1,0]}"#,
            "invalid_weight",
        ),
        (
            r#"{"degree":1,"knots":[0,0,1,1],"control_points":[[0],[1]],"weights":[1,-1e-300]}"#,
            "invalid_weight",
        ),
        (
            r#"{"degree":1,"knots":[0,0,1,1],"control_points":[[0],[1]],"weights":[1]}"#,
            "weight_count",
        ),
        (
            r#"{"degree":1,"knots":[0,1,0.5,1],"control_points":[[0],[1]]}"#,
            "decreasing_knots",
        ),
        (
            r#"{"degree":1,"knots":[0,0,0,1,1],"control_points":[[0],[1],[2]]}"#,
            "knot_multiplicity",
        ),
        (
            r#"{"degree":2,"knots":[0,0,1,1,2,2],"control_points":[[0],[1],[2]]}"#,
            "empty_domain",
        ),
        (
            r#"{"degree":1,"knots":[0,0,1,1],"control_points":[[],[]]}"#,
            "zero_dimension",
        ),
        (
            r#"{"degree":1,"knots":[0,0,1,1],"control_points":[[1,2],[3]]}"#,
            "dimension_mismatch",
        ),
        (
            r#"{"degree":1,"knots":[0,0,1,1],"control_points":[[[1]],[2]]}"#,
            "wrong_type",
        ),
        (
            r#"{"degree":1,"knots":"0,0,1,1","control_points":[[0],[1]]}"#,
            "wrong_type",
        ),
        (
            r#"{"degree":1,"knots":[0,0,1,1],"control_points":[[0],[1]],"weight":[1,2]}"#,
            "unknown_field",
        ),
        (
            r#"{"degree":1,"degree":1,"knots":[0,0,1,1],"control_points":[[0],[1]]}"#,
            "duplicate_field",
        ),
        (
            r#"{"degree":1,"knots":[0,0,1,1],"control_points":[[0],[1]]} x"#,
            "invalid_json",
        ),
        (
            r#"{"degree":1,"knots":[0,0,1,1],"control_points":[[0],[1e309]]}"#,
            "number_out_of_range",
        ),
        (
            r#"{"degree":1,"knots":[0,0,1,1],"control_points":[[0],[-Infinity]]}"#,
            "non_finite_literal",
        ),
        (
            r#"{"degree":1,"knots":[0,0,1,1],"control_points":[[0],[1]],"weights":{}}"#,
            "wrong_type",
        ),
        (
            r#"{"degree":1,"knots":[0,0,1,1],"control_points":[[0],[1]],"weights":[1,"2"]}"#,
            "wrong_type",
        ),
        (
            r#"{"degree":3,"knots":[],"control_points":[]}"#,
            "too_few_control_points",
        ),
        (
            r#"{"degree":1,"knots":[0,0,1],"control_points":[[0],[1]]}"#,
            "knot_count",
        ),
        (
            r#"{"degree":1,"knots":[0,0,1,1,1],"control_points":[[0],[1]]}"#,
            "knot_count",
        ),
        (
            r#"{"degree":1,"knots":[0,0,1,1],"control_points":[[0],[1]],"weights":[1,NaN]}"#,
            "non_finite_literal",
        ),
        (
            r#"{"knots":[0,0,1,1],"control_points":[[0],[1]]}"#,
            "missing_field",
        ),
        (
            r#"{"degree":1,"knots":[0,0,1,1],"control_points":[[0],[1]"#,
            "truncated_json",
        ),
        ("\u{0}\u{1}\u{7f}\u{fffd}", "invalid_json"),
        ("\"a string\"", "wrong_type"),
        ("12345", "wrong_type"),
    ];
    let big_literal = format!(
        r#"{{"degree":1,"knots":[0,0,1,1],"control_points":[[0],[1{}]]}}"#,
        "0".repeat(400)
    );
    let mut input = String::new();
    let mut expect: Vec<Option<&str>> = Vec::new();
    let extreme = extreme_curves();
    for (k, (line, kind)) in hostile.iter().enumerate() {
        let (_, c) = &extreme[k % extreme.len()];
        input.push_str(&nurbs_box::curve_to_json(c));
        input.push_str("\r\n"); // CRLF is whitespace
        expect.push(None);
        input.push_str(line);
        input.push('\n');
        expect.push(Some(kind));
    }
    input.push_str(&big_literal);
    input.push('\n');
    expect.push(Some("number_out_of_range"));
    input.push_str(ok);
    input.push('\n');
    expect.push(None);
    let mut child = Command::new(env!("CARGO_BIN_EXE_nurbs-box"))
        .args(["enclose", "--strategy", "all", "--threads", "2"])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut sin = child.stdin.take().unwrap();
    let bytes = input.clone().into_bytes();
    let w = std::thread::spawn(move || sin.write_all(&bytes));
    let out = child.wait_with_output().unwrap();
    w.join().unwrap().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    let recs: Vec<Value> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let curves: Vec<_> = nurbs_box::io::read_curves(input.as_bytes());
    let n_strat = all_strategies(None).len();
    let mut r = recs.iter();
    for (i, want) in expect.iter().enumerate() {
        match want {
            Some(kind) => {
                let rec = r.next().unwrap();
                assert_eq!(rec["index"], i);
                assert_eq!(rec["error"]["kind"], *kind, "line {i}: {rec}");
                assert!(rec["error"]["message"].as_str().unwrap().len() > 10);
            }
            None => {
                let c = curves[i].1.as_ref().unwrap();
                for _ in 0..n_strat {
                    let rec = r.next().unwrap();
                    assert_eq!(rec["index"], i);
                    if rec["verified"] != true {
                        continue;
                    }
                    let lo: Vec<f64> = rec["lo"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .map(|v| v.as_f64().unwrap())
                        .collect();
                    let hi: Vec<f64> = rec["hi"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .map(|v| v.as_f64().unwrap())
                        .collect();
                    // as_f64 fails on the strings "inf" / "-inf": boxes are finite
                    let e = Enclosure {
                        strategy: "cli",
                        verified: true,
                        coords: lo
                            .iter()
                            .zip(&hi)
                            .map(|(&lo, &hi)| nurbs_box::CoordBox {
                                lo,
                                hi,
                                inner_lo: hi,
                                inner_hi: lo,
                                argmin: Default::default(),
                                argmax: Default::default(),
                                stats: Default::default(),
                                termination: Termination::Converged,
                                optimal_lo: false,
                                optimal_hi: false,
                                witness_lo: f64::INFINITY,
                                witness_hi: f64::NEG_INFINITY,
                            })
                            .collect(),
                    };
                    let m = nurbs_box::testkit::validate::check_containment(
                        c,
                        &e,
                        &check_params(c, 20, &[]),
                    );
                    assert!(
                        m.misses.is_empty(),
                        "line {i} {}: {:?}",
                        rec["strategy"],
                        m.misses[0]
                    );
                }
            }
        }
    }
    assert!(r.next().is_none());
}

/// Defence in depth: a strategy that panics gives an `internal_error` record for that curve
/// and strategy; the other strategies' records are still written.
#[test]
fn a_panicking_strategy_becomes_an_error_record() {
    use nurbs_box::enclose::{BoxEncloser, ControlHull};
    struct Boom;
    impl BoxEncloser for Boom {
        fn name(&self) -> &'static str {
            "boom"
        }
        fn guarantee(&self) -> Guarantee {
            Guarantee::Verified
        }
        fn enclose_prepared(&self, _: &NurbsCurve) -> Enclosure {
            panic!("deliberate test panic")
        }
    }
    let c = curve(1, vec![0., 0., 1., 1.], vec![vec![0.], vec![1.]], None);
    let strategies: Vec<Box<dyn BoxEncloser>> = vec![Box::new(Boom), Box::new(ControlHull)];
    let mut buf = Vec::new();
    let ok = nurbs_box::io::batch::enclose_records(7, Ok(c), &strategies, false, &mut buf);
    assert!(!ok);
    let text = String::from_utf8(buf).unwrap();
    let lines: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 2);
    assert_eq!(lines[0]["index"], 7);
    assert_eq!(lines[0]["strategy"], "boom");
    assert_eq!(lines[0]["error"]["kind"], "internal_error");
    assert!(lines[0]["error"]["message"]
        .as_str()
        .unwrap()
        .contains("deliberate test panic"));
    assert_eq!(lines[1]["strategy"], "hull");
    assert_eq!(lines[1]["hi"][0], 1.0);
}

/// A proptest finding: degree 1 with a double knot at 0 (a jump), subnormal knots and weights
/// next to a weight of ~1e214, so that the homogeneous control point overflows. The piece left
/// of the jump approaches the control value 1.9e94; its end coefficient overflowed to ENTIRE,
/// which contains the next piece's value 0 at the knot, and `bezier`'s end rule took that
/// value for the piece's limit (box [0, 0] for both `bezier` and `newton`, which hands such
/// tiny spans to it, without the driver).
#[test]
fn subnormal_knots_and_weights_with_an_overflowing_homogeneous_point() {
    let json = r#"{"degree":1,"knots":[-1.5e-323,-1e-323,-1e-323,0.0,0.0,5e-324,5e-324,0.5],"control_points":[[0.0,0.0],[0.0,0.0],[1.894462644243321e+94,0.0],[0.0,0.0],[-0.0,0.0],[0.0,0.0]],"weights":[5e-324,5e-324,9.489198112852437e+213,5e-324,5e-324,5e-324]}"#;
    let c = nurbs_box::parse_curve(json.as_bytes()).unwrap();
    let v = nurbs_box::testkit::robust::check_strategies(&raw_strategies(), &c, 6, &[0.0]);
    assert!(v.is_empty(), "raw: {v:?}");
    let v = check_all_strategies(&c, 6, &[0.0]);
    assert!(v.is_empty(), "{v:?}");
}

/// A degree-26 spline whose coordinate 1 has one control value -f64::MAX among values ~1e-80,
/// knots up to 6e225 (found by `structured_decoder_on_random_bytes`): without the driver's
/// rescaling, the f64 restriction of `newton`'s Bernstein search (`restrict_hull_f64`)
/// computed differences of coefficients near -MAX and +MAX, which overflowed to inf and then
/// NaN, and the hull's min / max skipped the NaN: a box around the true minimum -1.08e308 was
/// excluded and the bound was -4.35e300. An overflowed restriction now gives ENTIRE.
#[test]
fn overflowing_f64_restrictions_exclude_nothing() {
    let json = r#"{"degree":26,"knots":[0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,0.0,1.6093749999999998e+225,5.125e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225,6.124999999999999e+225],"control_points":[[-1.0,2.0214386979187532e-80,-1.15625],[1.734375,-1.7976931348623157e+308,0.78125],[1.046875,1.1230214988437518e-80,-1.234375],[-1.09375,1.6684890839964313e-80,0.640625],[1.890625,-2.8556832399169687e-80,1.140625],[0.015625,-4.0749637243759e-80,1.203125],[0.03125,-3.465323482146434e-80,-1.140625],[1.515625,-2.2139566691491107e-80,-0.40625],[-1.046875,-1.0909351703053589e-80,-0.375],[0.046875,-7.700718849214298e-81,-0.453125],[-1.328125,2.695251597225004e-80,-0.859375],[0.6875,-3.208632853839291e-82,-0.390625],[0.84375,1.76474806961161e-80,-0.78125],[0.75,-1.732661741073217e-80,0.421875],[-0.546875,-2.6310789401482183e-80,0.140625],[0.078125,1.411798455689288e-80,-0.75],[0.3125,9.305035276133943e-81,0.65625],[-0.953125,-1.2192804844589306e-80,-1.015625],[1.9e-322,3.946618410222328e-80,0.125],[0.0,-2.727337925763397e-80,0.8125],[1.125,3.3048918394544696e-80,-1.046875],[-0.671875,1.379712127150895e-80,1.859375],[0.5,2.9519422255321475e-80,1.65625],[-0.40625,-1.76474806961161e-80,1.796875],[-1.515625,2.791510582840183e-80,0.046875],[-0.390625,-2.8556832399169687e-80,1.109375],[-1.65625,-3.112373868224112e-80,1.421875],[-1.609375,3.2728055109160767e-80,0.328125],[-0.34375,-2.887769568455362e-81,1.796875]]}"#;
    let c = nurbs_box::parse_curve(json.as_bytes()).unwrap();
    let v = nurbs_box::testkit::robust::check_strategies(&raw_strategies(), &c, 4, &[]);
    assert!(v.is_empty(), "raw: {v:?}");
    let v = check_all_strategies(&c, 4, &[]);
    assert!(v.is_empty(), "{v:?}");
}

/// A quadratic NURBS whose first piece has a weight of 1e214 and a control value -5.4e226 and
/// whose second piece (after a jump knot) is an ordinary arch up to 1315 (found by
/// `jumps_next_to_overflowing_weights_stay_in_the_box`): after the driver's rescaling the second
/// piece's homogeneous points are zero centres with subnormal radii next to weights near
/// 1e-214, and `newton`'s f64 sum of the derivative numerator (`pair_sum_f64`) took a term as
/// exactly zero because its computed radius products had underflowed to 0. F came out as an
/// exact zero, the arch was taken as flat, and the upper bound was 0 (certified optimal). Now
/// only exact zero factors (centre and radius 0) make a term exactly zero.
#[test]
fn underflowing_radius_products_do_not_flatten_a_piece() {
    let json = r#"{"degree":2,"knots":[-1.0,-1.0,-1.0,0.0,0.0,0.0,1.0,1.0,1.0],"control_points":[[0.0,0.0],[-5.356699823829085e+226,0.0],[0.0,0.0],[0.0,0.0],[2630.8732680534463,0.0],[0.0,0.0]],"weights":[1.0,1.0,1e+214,1.0,1.0,1.0]}"#;
    let c = nurbs_box::parse_curve(json.as_bytes()).unwrap();
    let v = check_all_strategies(&c, 4, &[]);
    assert!(v.is_empty(), "{v:?}");
    let v = nurbs_box::testkit::robust::check_strategies(&raw_strategies(), &c, 4, &[]);
    assert!(v.is_empty(), "raw: {v:?}");
}

/// Control values at -f64::MAX next to zeros (the proptest case that found it): the
/// subdivision of the zero estimation overflows (differences of coefficients near f64::MAX),
/// and an infinite piece coefficient must not pass as a proven sign; without the driver's
/// rescaling `newton` and `bezier` reported an upper bound 9e305 below a value of the curve.
#[test]
fn overflowing_zero_estimation_proves_nothing() {
    let m = -f64::MAX;
    let c = curve(
        4,
        vec![
            -2.950856608435965,
            -1.8817884591644178,
            -1.8801112406652707,
            -1.4303234254590993,
            -0.8067902275626213,
            0.0,
            0.0,
            0.0,
            0.0,
            0.0,
            5e-324,
            7.9915485645182525e-25,
            0.1932478333888893,
        ],
        [0.0, 0.0, m, 0.0, m, 0.0, 0.0, 0.0]
            .iter()
            .map(|&x| vec![x])
            .collect(),
        None,
    );
    let v = nurbs_box::testkit::robust::check_strategies(
        &raw_strategies(),
        &c,
        6,
        &[-0.3457672403839806],
    );
    assert!(v.is_empty(), "{v:?}");
    let v = check_all_strategies(&c, 6, &[-0.3457672403839806]);
    assert!(v.is_empty(), "{v:?}");
}
