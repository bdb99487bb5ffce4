//! Surfaces against a 256-bit reference (feature `mpfr`): a dense search in MPFR for the exact
//! extrema (boundary and knot-line curves by the curve reference, interior critical points by
//! a grid in every Bézier span pair polished by Newton's method on grad S_j = 0, all in MPFR),
//! then every strategy's box must contain it and `newton` and `bezier` must lie within one ulp
//! (of the coordinate scale) of it.
#![cfg(feature = "mpfr")]

use nurbs_box::enclose::Settings;
use nurbs_box::surface::enclose::all_surface_strategies;
use nurbs_box::surface::gen::{families, random_surface};
use nurbs_box::surface::{NurbsSurface, SurfaceEval};
use nurbs_box::testkit::reference::{reference_box, ulps_outside};
use rug::Float;

/// Extrema (lo, hi) per coordinate: values the surface attains (so `hi` is a lower bound of the
/// exact maximum) found by a search dense enough to be the exact extrema on these surfaces.
fn reference(s: &NurbsSurface) -> Vec<(Float, Float)> {
    let ((a, b), (c, d)) = s.domain();
    let dim = s.dim();
    let mut out: Vec<(Float, Float)> = (0..dim)
        .map(|_| {
            (
                Float::with_val(256, f64::INFINITY),
                Float::with_val(256, f64::NEG_INFINITY),
            )
        })
        .collect();
    let take = |j: usize, x: &Float, out: &mut Vec<(Float, Float)>| {
        if *x < out[j].0 {
            out[j].0 = x.clone();
        }
        if *x > out[j].1 {
            out[j].1 = x.clone();
        }
    };
    // lines: clamped sides and knot lines of multiplicity >= the degree are row / column curves
    let t = s.transposed();
    for (surf, lo, hi, kinks) in [(s, a, b, s.kink_knots_u()), (&t, c, d, s.kink_knots_v())] {
        let mut xs = vec![lo, hi];
        xs.extend(kinks);
        for x in xs {
            for left in [false, true] {
                if let Some(r) = surf.exact_row_at(x, left) {
                    let rb = reference_box(&surf.row_curve(r));
                    for j in 0..dim {
                        take(j, &rb.lo[j], &mut out);
                        take(j, &rb.hi[j], &mut out);
                    }
                }
            }
        }
    }
    // interior: grid + Newton polish per span pair
    let ev = SurfaceEval::<Float>::new(s, 2, 2, 2);
    let net = ev.net();
    let g = 12usize;
    for ku in net.spans_u() {
        for kv in net.spans_v() {
            let (u0, u1) = (net.ku[ku], net.ku[ku + 1]);
            let (v0, v1) = (net.kv[kv], net.kv[kv + 1]);
            for i in 1..g {
                for k in 1..g {
                    let u = Float::with_val(256, u0)
                        + (Float::with_val(256, u1) - u0) * i as f64 / g as f64;
                    let v = Float::with_val(256, v0)
                        + (Float::with_val(256, v1) - v0) * k as f64 / g as f64;
                    let val = ev.derivs_in_span(ku, kv, &u, &v, (0, 0, 0));
                    for j in 0..dim {
                        take(j, &val[0][0].as_ref().unwrap()[j], &mut out);
                    }
                    // Newton on grad S_j from every grid point (cheap at this size)
                    for j in 0..dim {
                        let (mut uu, mut vv) = (u.clone(), v.clone());
                        let mut ok = false;
                        for _ in 0..60 {
                            let dv = ev.derivs_in_span(ku, kv, &uu, &vv, (2, 2, 2));
                            let gq = |a: usize, b: usize| dv[a][b].as_ref().unwrap()[j].clone();
                            let (gu, gv) = (gq(1, 0), gq(0, 1));
                            let (huu, huv, hvv) = (gq(2, 0), gq(1, 1), gq(0, 2));
                            let det = huu.clone() * &hvv - huv.clone() * &huv;
                            if det.is_zero() {
                                break;
                            }
                            let du = (hvv * &gu - huv.clone() * &gv) / &det;
                            let dvv = (huu * &gv - huv * &gu) / &det;
                            uu -= &du;
                            vv -= &dvv;
                            if uu < u0 || uu > u1 || vv < v0 || vv > v1 {
                                break;
                            }
                            if du.clone().abs() < 1e-70 && dvv.clone().abs() < 1e-70 {
                                ok = true;
                                break;
                            }
                        }
                        if ok {
                            let val = ev.derivs_in_span(ku, kv, &uu, &vv, (0, 0, 0));
                            take(j, &val[0][0].as_ref().unwrap()[j], &mut out);
                        }
                    }
                }
            }
        }
    }
    out
}

#[test]
fn strategies_contain_the_reference_and_newton_is_within_ulps() {
    let mut surfaces: Vec<(String, NurbsSurface)> = families()
        .into_iter()
        // (unclamped sides have no exact row curve for the reference; extreme weights are
        // covered by tests/surface.rs)
        .filter(|f| f.0 != "unclamped" && f.0 != "extreme_weights")
        .map(|f| (f.0.to_string(), f.1))
        .collect();
    for seed in 0..6 {
        surfaces.push((
            format!("random{seed}"),
            random_surface(500 + seed, 1 + (seed as usize % 3), 2, 1, seed % 2 == 0),
        ));
    }
    let mut worst = 0.0f64;
    // (attained bounds, certified bounds, bounds)
    let mut flags = (0usize, 0usize, 0usize);
    for (name, s) in &surfaces {
        let r = reference(s);
        for st in all_surface_strategies(&Settings::default()) {
            let e = st.enclose(s);
            for (j, cb) in e.coords.iter().enumerate() {
                let scale = s.coord_scale(j);
                let dlo = ulps_outside(cb.lo, &r[j].0, scale, false);
                let dhi = ulps_outside(cb.hi, &r[j].1, scale, true);
                assert!(
                    dlo >= 0.0 && dhi >= 0.0,
                    "{name} {} {j}: [{}, {}] misses [{}, {}]",
                    st.name(),
                    cb.lo,
                    cb.hi,
                    r[j].0,
                    r[j].1
                );
                // inner bounds are attained values: beyond the reference only if the search
                // missed an extremum (then the outer-bound check above is the weaker one)
                let ilo = ulps_outside(cb.inner_lo, &r[j].0, scale, true);
                let ihi = ulps_outside(cb.inner_hi, &r[j].1, scale, false);
                assert!(
                    ilo >= 0.0 && ihi >= 0.0,
                    "{name} {} {j}: inner [{}, {}] beyond [{}, {}]",
                    st.name(),
                    cb.inner_lo,
                    cb.inner_hi,
                    r[j].0,
                    r[j].1
                );
                // every optimality flag is true: lo = RD(min) (min < next_up(lo); lo <= min
                // is the containment above), hi = RU(max)
                if cb.optimal_lo {
                    assert!(
                        r[j].0 < cb.lo.next_up(),
                        "{name} {} {j}: optimal_lo on {} but the minimum is {}",
                        st.name(),
                        cb.lo,
                        r[j].0
                    );
                }
                if cb.optimal_hi {
                    assert!(
                        r[j].1 > cb.hi.next_down(),
                        "{name} {} {j}: optimal_hi on {} but the maximum is {}",
                        st.name(),
                        cb.hi,
                        r[j].1
                    );
                }
                // (the attained rule alone, the rule before strict witnesses, for the count)
                flags.0 += (cb.inner_lo == cb.lo) as usize + (cb.inner_hi == cb.hi) as usize;
                flags.1 += cb.optimal_lo as usize + cb.optimal_hi as usize;
                flags.2 += 2;
                if st.name() != "hull" {
                    worst = worst.max(dlo).max(dhi);
                    eprintln!("{name} {} {j}: {dlo} / {dhi} ulps", st.name());
                    assert!(
                        dlo <= 1.0 && dhi <= 1.0,
                        "{name} {} {j}: {dlo} / {dhi} ulps from the reference",
                        st.name()
                    );
                }
            }
        }
    }
    eprintln!(
        "newton and bezier: worst distance to the reference {worst} ulps of the coordinate scale"
    );
    eprintln!(
        "optimal bounds (all strategies): {} of {} certified, {} of them by the attained rule alone",
        flags.1, flags.2, flags.0
    );
}
