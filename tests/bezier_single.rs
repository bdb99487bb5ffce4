//! The float-first fast path for single polynomial Bézier segments of degree 2 and 3
//! (src/enclose/bezier/single.rs, shared by `bezier` and `newton` through `fast_sides`, with the
//! cheap exits), and its conic counterpart in the driver's lane (src/enclose/bezier/conic.rs:
//! conic arcs and rational quadratic splines): soundness and tightness against the 256-bit
//! reference on random, structured and near-degenerate quadratics, cubics and conics (double
//! roots of C', extrema at the ends, flat coordinates), each strategy compared with its
//! general search (`fast_path: false`: the branch and bound, the interval Newton search).

use nurbs_box::enclose::Newton;
use nurbs_box::{BoxEncloser, Enclosure, NurbsCurve};
use rand::{Rng, SeedableRng};

mod common;

/// The registered strategies with the fast path, each followed by the same without it.
fn strategies() -> [Box<dyn BoxEncloser>; 4] {
    common::fast_and_general()
}

/// A Bézier curve of degree p = pts.len() - 1 over [a, b].
fn bezier(pts: Vec<Vec<f64>>, a: f64, b: f64) -> NurbsCurve {
    let p = pts.len() - 1;
    let mut k = vec![a; p + 1];
    k.extend(vec![b; p + 1]);
    NurbsCurve::new(p, k, pts, None).unwrap()
}

#[cfg_attr(not(feature = "mpfr"), allow(dead_code))]
/// Random single-segment quadratics and cubics of many shapes (one coordinate per shape
/// kind, so every curve mixes them).
fn random_single(rng: &mut impl Rng) -> NurbsCurve {
    let p = if rng.random_bool(0.8) { 3 } else { 2 };
    let dim = rng.random_range(1..=3usize);
    let mag = match rng.random_range(0..6) {
        0 => 10f64.powi(rng.random_range(-300..=300)),
        1 => 2f64.powi(rng.random_range(-20..=20)),
        _ => 100.0,
    };
    let coord = |rng: &mut dyn rand::RngCore| -> Vec<f64> {
        let mut r = |lo: f64, hi: f64| rng.random_range(lo..hi);
        let kind = r(0.0, 9.0) as u32;
        let mut c: Vec<f64> = match kind {
            // small integers: exact double roots, extrema exactly at test points
            0 => (0..=p).map(|_| (r(-4.0, 4.0)).round()).collect(),
            // extremum at an end: c_1 == c_0 (x'(0) = 0)
            1 => {
                let x = r(-1.0, 1.0);
                let mut v = vec![x, x];
                v.extend((2..=p).map(|_| r(-1.0, 1.0)));
                v
            }
            // degree-elevated quadratic: tiny (rounded) leading coefficient
            2 if p == 3 => {
                let (q0, q1, q2) = (r(-1.0, 1.0), r(-1.0, 1.0), r(-1.0, 1.0));
                vec![q0, (q0 + 2.0 * q1) / 3.0, (2.0 * q1 + q2) / 3.0, q2]
            }
            // flat, or flat but for one point
            3 => {
                let x = r(-1.0, 1.0);
                let mut v = vec![x; p + 1];
                if r(0.0, 1.0) < 0.5 {
                    let i = r(0.0, (p + 1) as f64) as usize;
                    v[i.min(p)] += r(-1.0, 1.0) * 10f64.powf(-r(0.0, 15.0));
                }
                v
            }
            // two close critical points (tiny bump)
            4 if p == 3 => {
                let e = 10f64.powf(-r(1.0, 12.0));
                vec![0.0, 1.0, 1.0 - 2.0 - e, 1.0 - 2.0 - e + 1.0]
            }
            _ => (0..=p).map(|_| r(-1.0, 1.0)).collect(),
        };
        for x in c.iter_mut() {
            *x *= mag;
        }
        c
    };
    let cols: Vec<Vec<f64>> = (0..dim).map(|_| coord(rng)).collect();
    let pts = (0..=p)
        .map(|i| cols.iter().map(|c| c[i]).collect())
        .collect();
    let (a, b) = if rng.random_bool(0.5) {
        (0.0, 1.0)
    } else {
        let a = rng.random_range(-10.0..10.0);
        (a, a + 10f64.powf(rng.random_range(-6.0..3.0)))
    };
    bezier(pts, a, b)
}

/// The argmin / argmax records lie in the domain, are ordered and exist.
fn check_args(c: &NurbsCurve, e: &Enclosure) -> Result<(), String> {
    let (a, b) = c.domain();
    for cb in &e.coords {
        for x in cb.argmin.iter().chain(&cb.argmax) {
            if !(a <= x.u_lo && x.u_lo <= x.u_hi && x.u_hi <= b) {
                return Err(format!("bad argument record {x:?} on [{a}, {b}]"));
            }
        }
        if cb.argmin.is_empty() || cb.argmax.is_empty() {
            return Err("no argument record".into());
        }
    }
    Ok(())
}

#[test]
fn the_fast_path_takes_most_random_cubics() {
    // (random 2-D cubics as in the bench: no subdivision means fast path or hull shortcut)
    let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    let s = &strategies()[0];
    let mut fast = 0;
    for _ in 0..1000 {
        let p: Vec<Vec<f64>> = (0..4)
            .map(|_| vec![r.random_range(-100.0..100.0), r.random_range(-100.0..100.0)])
            .collect();
        let c = bezier(p, 0.0, 1.0);
        let e = s.enclose(&c);
        fast += (e.stats().subdivisions == 0) as usize;
        check_args(&c, &e).unwrap();
    }
    assert!(fast >= 990, "{fast} of 1000");
}

#[test]
fn hand_made_cases() {
    // symmetric bump: max 0.75 exactly at t = 1/2 (x'(1/2) = 0 exactly)
    let c = bezier(vec![vec![0.0], vec![1.0], vec![1.0], vec![0.0]], 0.0, 1.0);
    let e = strategies()[0].enclose(&c);
    assert_eq!(e.coords[0].lo, 0.0);
    assert!(e.coords[0].hi >= 0.75 && e.coords[0].inner_hi <= 0.75);
    assert!(
        e.coords[0].hi - 0.75 <= 2.0 * f64::EPSILON,
        "{:?}",
        e.coords[0]
    );
    assert!(e.coords[0].argmax.iter().any(|x| x.unique));
    // parabola: max 0.5 at t = 1/2
    let c = bezier(vec![vec![0.0], vec![1.0], vec![0.0]], 2.0, 4.0);
    let e = strategies()[0].enclose(&c);
    assert!(e.coords[0].hi >= 0.5 && e.coords[0].hi - 0.5 <= f64::EPSILON);
    let x = e.coords[0].argmax[0];
    assert!(x.u_lo <= 3.0 && 3.0 <= x.u_hi, "{x:?}");
}

/// Without the reference: every variant's box contains the interval enclosures of the curve at
/// dense parameters (a miss is proven when a point's enclosure lies beyond a bound), and each
/// fast variant's outer bounds are within two ulps of the scale of its general search's.
fn check_dense(c: &NurbsCurve) -> Result<(), String> {
    use nurbs_box::testkit::robust::{check_enclosure, check_params};
    let params = check_params(c, 200, &[]);
    let encs: Vec<Enclosure> = strategies().iter().map(|s| s.enclose(c)).collect();
    for (s, e) in strategies().iter().zip(&encs) {
        check_enclosure(c, e, s.guarantee(), &params).map_err(|m| format!("{}: {m}", s.name()))?;
        check_args(c, e)?;
    }
    for pair in [0, 2] {
        for (j, (f, g)) in encs[pair]
            .coords
            .iter()
            .zip(&encs[pair + 1].coords)
            .enumerate()
        {
            let tol = 2.0 * nurbs_box::num::ulp(c.coord_scale(j));
            let ok = f.lo >= g.lo - tol && f.hi <= g.hi + tol; // (false for NaN)
            if !ok {
                return Err(format!(
                    "variant {pair} coord {j}: fast [{}, {}] looser than general [{}, {}]\n{}",
                    f.lo,
                    f.hi,
                    g.lo,
                    g.hi,
                    nurbs_box::curve_to_json(c)
                ));
            }
        }
    }
    Ok(())
}

proptest::proptest! {
    #![proptest_config(common::config(64))]
    /// Random and structured quadratics / cubics (see [`random_single`]) by dense sampling.
    #[test]
    fn single_segments_contain_dense_samples(seed in proptest::prelude::any::<u64>()) {
        let c = random_single(&mut rand_chacha::ChaCha8Rng::seed_from_u64(seed));
        if let Err(m) = check_dense(&c) {
            proptest::prop_assert!(false, "{m}");
        }
    }
}

#[test]
fn newton_counts_its_fast_paths() {
    let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    let (mut proofs, mut exits, mut falls) = (0, 0, 0);
    for _ in 0..200 {
        let p: Vec<Vec<f64>> = (0..4)
            .map(|_| vec![r.random_range(-100.0..100.0), r.random_range(-100.0..100.0)])
            .collect();
        let st = Newton::default().enclose(&bezier(p, 0.0, 1.0)).stats();
        proofs += st.fast_proofs;
        exits += st.fast_exits;
        falls += st.fast_fallbacks;
        assert_eq!(
            st.fast_proofs + st.fast_exits + st.fast_fallbacks,
            4,
            "{st:?}"
        );
    }
    assert!(
        proofs > 100 && exits > 100 && falls < 20,
        "{proofs} {exits} {falls}"
    );
    // the thesis preset never takes it
    let c = bezier(vec![vec![0.0], vec![1.0], vec![1.0], vec![0.0]], 0.0, 1.0);
    let st = Newton::thesis().enclose(&c).stats();
    assert_eq!(st.fast_proofs + st.fast_exits + st.fast_fallbacks, 0);
}

#[cfg(feature = "mpfr")]
mod mpfr {
    use super::*;
    use nurbs_box::testkit::gen::{self, Family, GenParams};
    use nurbs_box::testkit::reference::{reference_box, ulps_outside};
    use proptest::prelude::{any, prop_assert, proptest};

    /// Every bound of the fast path must be within this many ulps of the coordinate scale of
    /// the exact extremum (the fast path's own acceptance rule is a certified gap of 2 ulps;
    /// the measured maximum is about one ulp). Curves it hands to the general branch and
    /// bound are only checked for soundness here.
    const FAST_MAX_ULPS: f64 = 2.0;

    /// [`check`], and no false optimality certificate of any variant against the reference.
    fn check_with_certificates(c: &NurbsCurve) -> Result<Vec<f64>, String> {
        let d = check(c)?;
        let rb = reference_box(c);
        for s in strategies() {
            nurbs_box::testkit::reference::check_certificates(c, &rb, &s.enclose(c))
                .map_err(|m| format!("{m}\n{}", nurbs_box::curve_to_json(c)))?;
        }
        Ok(d)
    }

    /// Soundness (outer bounds contain the exact box, inner bounds are reached) for both
    /// variants, and tightness of the default one: within [`FAST_MAX_ULPS`], or no looser than
    /// the general branch and bound (to which the fast path hands the curves it cannot prove
    /// tight). Returns the default variant's distances.
    fn check(c: &NurbsCurve) -> Result<Vec<f64>, String> {
        let rb = reference_box(c);
        let curve = nurbs_box::curve_to_json(c);
        let mut dist = Vec::new();
        for (k, s) in strategies().iter().enumerate() {
            let e = s.enclose(c);
            check_args(c, &e)?;
            let mut d = Vec::new();
            for (j, cb) in e.coords.iter().enumerate() {
                let sc = c.coord_scale(j);
                let dl = ulps_outside(cb.lo, &rb.lo[j], sc, false);
                let dh = ulps_outside(cb.hi, &rb.hi[j], sc, true);
                let sound = dl >= 0.0 && dh >= 0.0; // (false for NaN)
                if !sound {
                    return Err(format!(
                        "variant {k} coord {j}: MISS [{}, {}] ({dl}, {dh} ulps) exact [{}, {}]\n{curve}",
                        cb.lo, cb.hi, rb.lo[j], rb.hi[j]
                    ));
                }
                // (inner bounds reached, up to the reference's resolution, see ulps_outside:
                // a curve attaining an f64 end value exactly may have a reference a few
                // 2^-250 beyond it)
                let il = ulps_outside(cb.inner_lo, &rb.lo[j], sc, true);
                let ih = ulps_outside(cb.inner_hi, &rb.hi[j], sc, false);
                let reached = il >= 0.0 && ih >= 0.0;
                if !reached {
                    return Err(format!(
                        "variant {k} coord {j}: inner [{}, {}] not reached, exact [{}, {}]\n{curve}",
                        cb.inner_lo, cb.inner_hi, rb.lo[j], rb.hi[j]
                    ));
                }
                d.extend([dl, dh]);
            }
            dist.push(d);
        }
        for pair in [0, 2] {
            for (i, (&f, &g)) in dist[pair].iter().zip(&dist[pair + 1]).enumerate() {
                let ok = f <= FAST_MAX_ULPS.max(g); // (false for NaN)
                if !ok {
                    return Err(format!(
                        "variant {pair} bound {i}: {f} ulps outside the exact box \
                         (general path: {g})\n{curve}"
                    ));
                }
            }
        }
        // (both fast variants' distances)
        let newton = dist.swap_remove(2);
        let mut d = dist.swap_remove(0);
        d.extend(newton);
        Ok(d)
    }

    /// A random conic arc (one rational quadratic segment, the driver's conic lane): weights
    /// 0.2..5 (a NURBS circle's pattern now and then), one coordinate kind per coordinate as
    /// in [`random_single`] (small integers with exact ties, an extremum at an end, flat,
    /// generic), magnitudes 2^-20..2^20 or 100.
    fn random_conic(rng: &mut impl Rng) -> NurbsCurve {
        let dim = rng.random_range(1..=3usize);
        let mag = if rng.random_bool(0.3) {
            2f64.powi(rng.random_range(-20..=20))
        } else {
            100.0
        };
        let cols: Vec<Vec<f64>> = (0..dim)
            .map(|_| {
                let mut c: Vec<f64> = match rng.random_range(0..5u32) {
                    0 => (0..3)
                        .map(|_| rng.random_range(-4.0..4.0f64).round())
                        .collect(),
                    1 => {
                        let x = rng.random_range(-1.0..1.0);
                        vec![x, x, rng.random_range(-1.0..1.0)]
                    }
                    2 => vec![0.5; 3],
                    _ => (0..3).map(|_| rng.random_range(-1.0..1.0)).collect(),
                };
                c.iter_mut().for_each(|x| *x *= mag);
                c
            })
            .collect();
        let pts = (0..3)
            .map(|i| cols.iter().map(|c| c[i]).collect())
            .collect();
        let w = if rng.random_bool(0.2) {
            vec![1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0]
        } else {
            (0..3).map(|_| rng.random_range(0.2..5.0)).collect()
        };
        let (a, b) = if rng.random_bool(0.5) {
            (0.0, 1.0)
        } else {
            let a = rng.random_range(-10.0..10.0);
            (a, a + 10f64.powf(rng.random_range(-6.0..3.0)))
        };
        let mut k = vec![a; 3];
        k.extend(vec![b; 3]);
        NurbsCurve::new(2, k, pts, Some(w)).unwrap()
    }

    // (default proptest config: 256 cases, or PROPTEST_CASES)
    proptest! {
        /// Conic arcs (see [`random_conic`]) in the lane, against the reference.
        #[test]
        fn conic_arcs_against_the_reference(seed in any::<u64>()) {
            let c = random_conic(&mut gen::rng(seed));
            if let Err(m) = check(&c) {
                prop_assert!(false, "{m}");
            }
        }

        /// Rational splines of degree 2 to 5 of the test families (weights 10^-1 .. 10^1 as
        /// the families draw them: most in the lane, wider spreads on the general path).
        #[test]
        fn rational_splines_against_the_reference(seed in any::<u64>()) {
            let mut r = gen::rng(seed);
            let fam = [Family::ClampedUniform, Family::MultipleKnots, Family::ClusteredKnots,
                Family::ExtremaAtKnots, Family::FlatCoordinates][r.random_range(0..5usize)];
            let params = GenParams { degree: 2..=5, rational: 1.0, ..fam.params() };
            let c = gen::random_curve(&mut r, &params);
            if let Err(m) = check(&c) {
                prop_assert!(false, "{m}");
            }
        }

        /// Unclamped splines of degree 2 to 5, polynomial and rational (the lane takes them
        /// with their end values from the end spans' coefficients): sound, tight, and every
        /// optimality certificate true, with the lane's answer and the general path's bounds
        /// and certificates the same.
        #[test]
        fn unclamped_splines_against_the_reference(seed in any::<u64>()) {
            let mut r = gen::rng(seed);
            let params = GenParams { degree: 2..=5, ..Family::Unclamped.params() };
            let c = gen::random_curve(&mut r, &params);
            if let Err(m) = check_with_certificates(&c) {
                prop_assert!(false, "{m}");
            }
        }

        /// Splines of degree 2 to 5 (polynomial and rational) with their coordinates scaled
        /// exactly by 2^e far outside the lane's window, down to where bounds are subnormal
        /// and up to near f64::MAX (the driver scales them back into the lane; a certified
        /// bound carries over only where its scaling back is exact): sound, tight, no false
        /// certificate.
        #[test]
        fn scaled_splines_against_the_reference(seed in any::<u64>()) {
            let mut r = gen::rng(seed);
            let fam = [Family::ClampedUniform, Family::Mixed, Family::Unclamped][r.random_range(0..3usize)];
            let params = GenParams { degree: 2..=5, ..fam.params() };
            let c = gen::random_curve(&mut r, &params);
            let e = match r.random_range(0..4) {
                0 => r.random_range(-1070..-1000),
                1 => r.random_range(-900..-100),
                2 => r.random_range(100..900),
                _ => r.random_range(1000..1022),
            };
            let pts: Vec<Vec<f64>> = (0..c.num_points())
                .map(|i| c.control_point(i).iter().map(|&x| x * 2f64.powi(e / 2) * 2f64.powi(e - e / 2)).collect())
                .collect();
            // (only an exact scaling: every value back to itself)
            let exact = pts.iter().zip(0..c.num_points()).all(|(q, i)| {
                q.iter().zip(c.control_point(i)).all(|(&y, &x)| {
                    y.is_finite() && y * 2f64.powi(-e / 2) * 2f64.powi(-(e - e / 2)) == x
                })
            });
            if exact {
                let w = c.weights().map(|w| w.to_vec());
                let sc = NurbsCurve::new(c.degree(), c.knots().to_vec(), pts, w).unwrap();
                if let Err(m) = check_with_certificates(&sc) {
                    prop_assert!(false, "{m}");
                }
            }
        }

        /// Random and structured quadratics / cubics (see [`random_single`]).
        #[test]
        fn single_segments_against_the_reference(seed in any::<u64>()) {
            let c = random_single(&mut gen::rng(seed));
            if let Err(m) = check(&c) {
                prop_assert!(false, "{m}");
            }
        }

        /// Quadratic and cubic B-splines with several spans (clamped, unclamped, repeated and
        /// jump knots, clustered knots): the fast path runs span by span.
        #[test]
        fn splines_against_the_reference(seed in any::<u64>()) {
            let mut r = gen::rng(seed);
            let fam = [Family::ClampedUniform, Family::MultipleKnots, Family::Unclamped,
                Family::ClusteredKnots, Family::ExtremaAtKnots, Family::FlatCoordinates,
                Family::ExtremeMagnitudes][r.random_range(0..7usize)];
            let params = GenParams { degree: 2..=3, rational: 0.0, ..fam.params() };
            let c = gen::random_curve(&mut r, &params);
            if let Err(m) = check(&c) {
                prop_assert!(false, "{m}");
            }
        }

        /// The generator's near-degenerate cubics (near double roots of x', cusps; some
        /// rational or with an inserted knot, which take the general path).
        #[test]
        fn near_degenerate_cubics_against_the_reference(seed in any::<u64>()) {
            let c = gen::near_degenerate_cubic(&mut gen::rng(seed));
            if let Err(m) = check(&c) {
                prop_assert!(false, "{m}");
            }
        }
    }

    /// The distribution of the fast path's distances on many random curves (median well
    /// below one ulp, every one within [`FAST_MAX_ULPS`]).
    #[test]
    fn fast_path_tightness_summary() {
        let mut r = gen::rng(11);
        let mut d = Vec::new();
        for _ in 0..300 {
            d.extend(check(&random_single(&mut r)).unwrap_or_else(|m| panic!("{m}")));
        }
        d.sort_by(f64::total_cmp);
        let med = d[d.len() / 2];
        assert!(med <= 0.5, "median {med}");
    }
}
