//! Soundness at the corners of the f64 range: knot vectors whose spans overflow (knots near
//! ±f64::MAX), subnormal knots among huge ones, coordinates at ±f64::MAX and subnormal sizes,
//! jumps at knots of multiplicity p + 1, and bounded work at degree 1,000.
//!
//! Every strategy of the registry, on every curve: the checks of `robust::check_enclosure`
//! (interval evaluation at dense parameters: no outer bound beyond a value the curve provably
//! takes), finite boxes, ordered inner bounds; with `--features mpfr` also against the exact
//! box (reference at enough bits for exact knot differences): no outer miss, no inner bound the
//! curve does not reach, and `newton` / `bezier` within a few ulps where they converge.

use nurbs_box::enclose::{all_strategies, Guarantee, Termination};
use nurbs_box::testkit::gen::{self, Family};
use nurbs_box::{parse_curve, Enclosure, NurbsCurve};
use std::time::Duration;

/// The curves an adversary found (wrong verified bounds before the overflow-safe knot
/// arithmetic, the segment path and the range facts of the driver).
const FOUND: &[(&str, &str)] = &[
    (
        "bezier_outer_miss",
        r#"{"degree": 3, "knots": [-1.7976931348623157e+308, -1.7976931348623157e+308, -1.7976931348623157e+308, -1.7976931348623157e+308, -4.4942328371557893e+307, 5e-324, 2.2471164185778946e+307, 4.4942328371557893e+307, 6.741349255733684e+307, 1.1235582092889472e+308, 1.7976931348623157e+308, 1.7976931348623157e+308, 1.7976931348623157e+308, 1.7976931348623157e+308], "control_points": [[5.0], [5.0], [3.0], [1.0], [2.0], [1.0], [3.0], [5.0], [-1.0], [4.0]]}"#,
    ),
    (
        "bezier_false_inner",
        r#"{"degree": 2, "knots": [-1.7976931348623157e+308, -1.7976931348623157e+308, -1.7976931348623157e+308, 5e-324, 8.988465674311579e+307, 1.3482698511467367e+308, 1.3482698511467367e+308, 1.3482698511467367e+308], "control_points": [[-0.05550951284776673, -240.76955335254445], [-0.5800903872570458, -24.286686951704837], [0.7866340851152702, -220.3823859577318], [0.2148759925705206, 534.315258295924], [0.39166573353688694, -467.3388790854809]]}"#,
    ),
    (
        "max_end_point",
        r#"{"degree": 2, "knots": [0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0], "control_points": [[0.0, 8.453e-321, 6.370192998856131e-302], [1e-320, 5.845e-321, -1.2591779949217282e-301], [1.7976931348623157e+308, 7.102766244247816e-301, 3.9302663627707674e-301], [1.7976931348623157e+308, 5.891160777143012e+307, -2.59767507677386e-301]]}"#,
    ),
    (
        "min_end_point",
        r#"{"degree":1,"knots":[0,0,1,1],"control_points":[[-1.7976931348623157e308],[1e-300]]}"#,
    ),
    (
        "jump",
        r#"{"degree":2,"knots":[0,0,0,0.5,0.5,0.5,1,1,1],"control_points":[[0],[1],[3],[-5],[0],[0]]}"#,
    ),
];

fn found(name: &str) -> NurbsCurve {
    let text = FOUND.iter().find(|(n, _)| *n == name).unwrap().1;
    parse_curve(text.as_bytes()).unwrap()
}

mod common;

/// Every registered strategy on `c` (`common::check_registry`).
fn check(name: &str, c: &NurbsCurve, limit: Duration) -> Vec<Enclosure> {
    common::check_registry(name, c, 16, limit)
}

#[test]
fn found_curves_are_sound_and_finite() {
    for (name, _) in FOUND {
        let c = found(name);
        let encs = check(name, &c, Duration::from_secs(10));
        #[cfg(feature = "mpfr")]
        mpfr::against_reference(name, &c, &encs, true);
        let _ = encs;
    }
}

#[test]
fn end_values_at_the_range_limits_are_exact_attained_bounds() {
    // x: clamped end P_n = f64::MAX is the maximum, P_0 = 0 the minimum: both exact, attained
    let c = found("max_end_point");
    let c2 = found("min_end_point");
    for s in all_strategies(None) {
        if s.guarantee() != Guarantee::Verified {
            continue;
        }
        let e = s.enclose(&c);
        let x = &e.coords[0];
        assert_eq!((x.lo, x.hi), (0.0, f64::MAX), "{}", s.name());
        assert_eq!((x.inner_lo, x.inner_hi), (0.0, f64::MAX), "{}", s.name());
        // y: the clamped start value P_0 = 8.453e-321 (subnormal) is attained exactly
        let y = &e.coords[1];
        assert!(y.inner_lo <= 8.453e-321, "{}: {y:?}", s.name());
        assert!(
            y.lo >= 5.845e-321,
            "{}: lo below the control points",
            s.name()
        );
        let e = s.enclose(&c2);
        let x = &e.coords[0];
        assert_eq!((x.lo, x.hi), (-f64::MAX, 1e-300), "{}", s.name());
        assert_eq!(
            (x.inner_lo, x.inner_hi),
            (-f64::MAX, 1e-300),
            "{}",
            s.name()
        );
    }
}

#[test]
fn overflowing_spans_converge_without_a_work_limit() {
    // the outer miss curve: every strategy but the hull finds the minimum
    // 1.3643515984042635878... (in the span [5e-324, 2.247e307]) and converges
    let c = found("bezier_outer_miss");
    let exact = 1.364_351_598_404_263_6_f64;
    for s in all_strategies(None) {
        if s.name() == "hull" {
            continue;
        }
        let e = s.enclose(&c);
        let x = &e.coords[0];
        assert!(
            x.lo <= exact && x.lo >= exact - 4.0 * f64::EPSILON,
            "{}: lo {}",
            s.name(),
            x.lo
        );
        assert!(x.inner_lo >= exact - f64::EPSILON && x.inner_lo <= exact + 4.0 * f64::EPSILON);
        assert!(
            !matches!(
                x.termination,
                Termination::WorkLimit | Termination::BoxLimit | Termination::IterationLimit
            ),
            "{}: {:?}",
            s.name(),
            x.termination
        );
    }
}

#[test]
fn a_left_limit_at_a_jump_is_not_attained() {
    // C < 3 on [0, 0.5), C(0.5) = -5, C <= 0 after: sup 3 is not reached, max C = 0
    let c = found("jump");
    for s in all_strategies(None) {
        if s.guarantee() != Guarantee::Verified {
            continue;
        }
        let e = s.enclose(&c);
        let x = &e.coords[0];
        assert!(x.hi >= 3.0, "{}: hi {}", s.name(), x.hi);
        assert!(x.inner_hi < 3.0, "{}: inner_hi {}", s.name(), x.inner_hi);
        assert_eq!(x.lo, -5.0, "{}", s.name());
        if s.name() != "hull" {
            // C(0.5) = -5 is the right piece's value: attained (the hull has only end values)
            assert_eq!(x.inner_lo, -5.0, "{}", s.name());
        }
    }
    // and a family of jump curves: the left limit is the maximum but never attained
    for k in 1..=4usize {
        let p = k;
        let mut knots = vec![0.0; p + 1];
        knots.extend(std::iter::repeat_n(0.5, p + 1));
        knots.extend(std::iter::repeat_n(1.0, p + 1));
        let mut pts: Vec<Vec<f64>> = (0..=p).map(|i| vec![i as f64]).collect();
        pts.extend((0..=p).map(|i| vec![-1.0 - i as f64]));
        let c = NurbsCurve::new(p, knots, pts, None).unwrap();
        for s in all_strategies(None) {
            if s.guarantee() != Guarantee::Verified {
                continue;
            }
            let x = &s.enclose(&c).coords[0];
            // max of the values taken: sup of the left piece p (not attained); attained: at
            // most the left piece's values below p, or -1 after the jump
            assert!(x.hi >= p as f64, "{} p={p}", s.name());
            assert!(x.inner_hi < p as f64, "{} p={p}: {}", s.name(), x.inner_hi);
        }
    }
}

/// What `eval` returns at a knot (`src/guarantees.md`, "Values at knots"): inside the domain the
/// right limit (the span starting at u), at the right end of the domain the left limit.
#[test]
fn values_at_knots_are_the_right_limit_and_the_left_limit_at_the_end() {
    // jump at 0.5: the left piece tends to 3, C(0.5) = -5 (right piece); C(1) = 0
    let c = found("jump");
    let at = |u: f64| c.enclose_point(nurbs_box::num::iv::point(u)).unwrap()[0];
    let v = at(0.5);
    assert!(
        v.inf() == -5.0 && v.sup() == -5.0,
        "C(0.5) = [{}, {}]",
        v.inf(),
        v.sup()
    );
    let v = at(1.0);
    assert!(
        v.inf() == 0.0 && v.sup() == 0.0,
        "C(1) = [{}, {}]",
        v.inf(),
        v.sup()
    );
    let f: Vec<f64> = c.point(0.5).unwrap();
    assert_eq!(f[0], -5.0);
    // an unclamped end: the last span's left limit at u_{n+1}
    let u = NurbsCurve::new(
        2,
        vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0],
        vec![vec![0.0], vec![4.0], vec![0.0]],
        None,
    )
    .unwrap();
    let (_, b) = u.domain();
    let v = u.enclose_point(nurbs_box::num::iv::point(b)).unwrap()[0];
    // C(3) on the span [2, 3] of degree 2: (P_1 + P_2) / 2 = 2
    assert!(
        v.inf() <= 2.0 && 2.0 <= v.sup(),
        "C(b) = [{}, {}]",
        v.inf(),
        v.sup()
    );
}

#[test]
fn the_range_limit_family_is_sound() {
    let mut r = gen::rng(0x7a11);
    let n = std::env::var("RANGE_CURVES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(60);
    for i in 0..n {
        let c = Family::RangeLimits.curve(&mut r);
        let name = format!("range_limits #{i}");
        let encs = check(&name, &c, Duration::from_secs(10));
        #[cfg(feature = "mpfr")]
        mpfr::against_reference(&name, &c, &encs, false);
        let _ = encs;
    }
}

#[test]
fn degree_1000_is_bounded_for_every_strategy() {
    let p = 1000;
    let pts: Vec<Vec<f64>> = (0..=p)
        .map(|i| {
            let x = i as f64;
            vec![(x * 0.7).sin(), (x * 1.3).cos() * 0.5]
        })
        .collect();
    let mut knots = vec![0.0; p + 1];
    knots.extend(std::iter::repeat_n(1.0, p + 1));
    let c = NurbsCurve::new(p, knots, pts, None).unwrap();
    // (the goal is 10 s per curve; the limit here allows for a loaded test machine)
    check("degree_1000", &c, Duration::from_secs(30));
}

#[cfg(feature = "mpfr")]
mod mpfr {
    use super::*;

    /// No verified outer bound misses the exact box, every inner bound is reached
    /// (`common::check_reference`); with `tight`, converged `newton` / `bezier` bounds are
    /// within 4 ulps of the scale.
    pub fn against_reference(name: &str, c: &NurbsCurve, encs: &[Enclosure], tight: bool) {
        for (strategy, j, dlo, dhi, term) in common::check_reference(name, c, encs) {
            if tight && term == Termination::Converged && matches!(strategy, "newton" | "bezier") {
                assert!(
                    dlo <= 4.0 && dhi <= 4.0,
                    "{name}: {strategy} {j}: {dlo} / {dhi} ulps"
                );
            }
        }
    }
}
