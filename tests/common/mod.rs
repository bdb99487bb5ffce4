//! Shared by the integration tests (`mod common;`).

use proptest::test_runner::Config as ProptestConfig;

/// Proptest configuration with `default_cases` cases unless the `PROPTEST_CASES` environment
/// variable says otherwise (CI sets it; see `.ci/run`).
#[allow(dead_code)] // not every test crate runs proptests
pub fn config(default_cases: u32) -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default_cases);
    ProptestConfig {
        cases,
        ..ProptestConfig::default()
    }
}

/// `bezier` and `newton` with their defaults (fast paths and the driver's lane), each followed
/// by the same without them (`fast_path: false`: the Bézier branch and bound, the interval
/// Newton search), whose `enclose` runs under the driver like the registry's.
#[allow(dead_code)] // not every test crate compares the fast paths
pub fn fast_and_general() -> [Box<dyn nurbs_box::BoxEncloser>; 4] {
    use nurbs_box::enclose::{BezierSubdivision, Newton};
    [
        Box::new(BezierSubdivision::default()),
        Box::new(BezierSubdivision {
            fast_path: false,
            ..Default::default()
        }),
        Box::new(Newton::default()),
        Box::new(Newton {
            fast_path: false,
            ..Default::default()
        }),
    ]
}

/// Run the `nurbs-box` binary with `args`, feeding `stdin` (from another thread: the child may
/// fill its stdout pipe before reading all input); returns (exit code, stdout, stderr) and
/// fails if the binary panicked.
#[allow(dead_code)] // not every test crate runs the binary
pub fn run_bin(args: &[&str], stdin: &[u8]) -> (i32, String, String) {
    use std::io::Write;
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_nurbs-box"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start nurbs-box");
    let mut sin = child.stdin.take().unwrap();
    let input = stdin.to_vec();
    let writer = std::thread::spawn(move || {
        let _ = sin.write_all(&input);
    });
    let out = child.wait_with_output().unwrap();
    writer.join().unwrap();
    let stdout = String::from_utf8(out.stdout).expect("stdout is UTF-8");
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(
        !stderr.contains("panicked"),
        "the binary panicked: {stderr}"
    );
    (out.status.code().expect("exit code"), stdout, stderr)
}

/// Run every registered strategy on `c`: no panic, the checks of `robust::check_enclosure` at
/// dense parameters (`per_span` per span), each call within `limit`; for the verified ones
/// finite boxes with ordered inner bounds (lo <= inner_lo <= hi, lo <= inner_hi <= hi).
/// Returns every strategy's result.
#[allow(dead_code)] // not every test crate checks strategies
pub fn check_registry(
    name: &str,
    c: &nurbs_box::NurbsCurve,
    per_span: usize,
    limit: std::time::Duration,
) -> Vec<nurbs_box::Enclosure> {
    use nurbs_box::enclose::{all_strategies, Guarantee};
    use nurbs_box::testkit::robust::{check_enclosure, check_params};
    let params = check_params(c, per_span, &[]);
    let mut out = Vec::new();
    for s in all_strategies(None) {
        let t = std::time::Instant::now();
        let e = s.enclose(c);
        let dt = t.elapsed();
        assert!(dt < limit, "{name}: {} took {dt:?}", s.name());
        if let Err(m) = check_enclosure(c, &e, s.guarantee(), &params) {
            panic!("{name}: {}: {m}", s.name());
        }
        if s.guarantee() == Guarantee::Verified {
            for (j, cb) in e.coords.iter().enumerate() {
                assert!(
                    cb.lo.is_finite() && cb.hi.is_finite(),
                    "{name}: {} coordinate {j}: box [{:e}, {:e}] is not finite",
                    s.name(),
                    cb.lo,
                    cb.hi
                );
                assert!(
                    cb.lo <= cb.inner_lo && cb.inner_lo <= cb.hi,
                    "{name}: {} {j}: {cb:?}",
                    s.name()
                );
                assert!(
                    cb.lo <= cb.inner_hi && cb.inner_hi <= cb.hi,
                    "{name}: {} {j}: {cb:?}",
                    s.name()
                );
            }
        }
        out.push(e);
    }
    out
}

/// Against the exact (MPFR) box of `c`: every verified enclosure in `encs` contains it and its
/// inner bounds are reached (both asserted, naming `name`, the strategy and the coordinate).
/// Returns per verified enclosure and coordinate `(strategy, j, dlo, dhi, termination)`, the
/// distances of the outer bounds in ulps of the coordinate scale, for the caller's tightness
/// rule.
#[cfg(feature = "mpfr")]
#[allow(dead_code)] // not every test crate checks against the reference
pub fn check_reference(
    name: &str,
    c: &nurbs_box::NurbsCurve,
    encs: &[nurbs_box::Enclosure],
) -> Vec<(&'static str, usize, f64, f64, nurbs_box::Termination)> {
    use nurbs_box::testkit::reference::{
        check_certificates, inner_reached, reference_box, ulps_outside,
    };
    let rb = reference_box(c);
    let mut out = Vec::new();
    for e in encs {
        // every optimality certificate agrees with MPFR's rounding of the exact extremum
        check_certificates(c, &rb, e).unwrap_or_else(|m| panic!("{name}: {m}"));
    }
    for e in encs.iter().filter(|e| e.verified) {
        for (j, cb) in e.coords.iter().enumerate() {
            let scale = c.coord_scale(j);
            let dlo = ulps_outside(cb.lo, &rb.lo[j], scale, false);
            let dhi = ulps_outside(cb.hi, &rb.hi[j], scale, true);
            assert!(
                dlo >= 0.0 && dhi >= 0.0,
                "{name}: {} coordinate {j}: box [{:e}, {:e}] misses the exact [{}, {}]",
                e.strategy,
                cb.lo,
                cb.hi,
                rb.lo[j],
                rb.hi[j]
            );
            assert!(
                inner_reached(&rb, j, cb.inner_lo, cb.inner_hi, scale),
                "{name}: {} coordinate {j}: inner [{:e}, {:e}] not reached, exact [{}, {}]",
                e.strategy,
                cb.inner_lo,
                cb.inner_hi,
                rb.lo[j],
                rb.hi[j]
            );
            out.push((e.strategy, j, dlo, dhi, cb.termination));
        }
    }
    out
}
