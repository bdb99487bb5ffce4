//! Surfaces against a 256-bit reference (feature `mpfr`; `testkit::reference::surface_reference`:
//! a dense search in MPFR for the exact extrema, boundary and knot-line curves by the curve
//! reference, interior critical points by a grid in every Bézier span pair polished by
//! Newton's method on grad S_j = 0): every strategy's box must contain it and `newton` and
//! `bezier` must lie within one ulp (of the coordinate scale) of it.
#![cfg(feature = "mpfr")]

use nurbs_box::enclose::Settings;
use nurbs_box::surface::enclose::all_surface_strategies;
use nurbs_box::surface::gen::{families, random_surface};
use nurbs_box::surface::NurbsSurface;
use nurbs_box::testkit::reference::{surface_reference as reference, ulps_outside};

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
