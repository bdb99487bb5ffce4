//! Knot removal (The NURBS Book A5.8; thesis sec. 4.2.2): insert-then-remove gives the curve
//! back (bit for bit when the arithmetic is exact), the generic kernel encloses the exact
//! inverse of an insertion, and a removal within tolerance t moves no point of the curve by
//! more than its reported verified bound <= t (checked against MPFR samples).

use inari::Interval;
use nurbs_box::{multiplicity, HSpline, NurbsCurve};
use proptest::prelude::*;

mod common;
use common::config;

/// Moderate curves: degree 1..=5, dimension 1..=3, 0..6 interior knots (some repeated),
/// coordinates in [-100, 100], optional weights in [0.2, 5].
fn curves() -> impl Strategy<Value = NurbsCurve> {
    (1usize..=5, 1usize..=3, 0usize..6, any::<bool>()).prop_flat_map(|(p, d, ni, rational)| {
        let n = p + 1 + ni;
        (
            prop::collection::vec(0.05f64..1.0, ni),
            prop::collection::vec(0usize..3, ni),
            prop::collection::vec(-100.0f64..100.0, n * d),
            prop::collection::vec(0.2f64..5.0, n),
        )
            .prop_map(move |(gaps, rep, pts, w)| {
                // interior knots: increasing, each possibly repeated (multiplicity <= p)
                let mut interior = Vec::new();
                let mut x = 0.0;
                for (g, r) in gaps.iter().zip(&rep) {
                    x += g;
                    for _ in 0..=(*r).min(p - 1) {
                        interior.push(x);
                    }
                }
                interior.truncate(ni);
                let end = x + 0.5;
                let mut knots = vec![0.0; p + 1];
                knots.extend(&interior);
                knots.extend(vec![end; p + 1]);
                let npts = knots.len() - p - 1;
                let pts = pts[..npts * d].to_vec();
                let w = rational.then(|| w[..npts].to_vec());
                NurbsCurve::from_flat(p, d, knots, pts, w).unwrap()
            })
    })
}

/// A parameter strictly inside the domain, at least 1% of it away from every knot, or (`on`)
/// an existing interior knot when there is one.
fn pick_u(c: &NurbsCurve, f: f64, on: bool) -> f64 {
    let (a, b) = c.domain();
    let interior: Vec<f64> = c
        .knots()
        .iter()
        .copied()
        .filter(|&k| a < k && k < b)
        .collect();
    if on && !interior.is_empty() {
        return interior[((f * interior.len() as f64) as usize).min(interior.len() - 1)];
    }
    let mut u = a + (b - a) * (0.02 + 0.96 * f);
    for _ in 0..50 {
        if c.knots().iter().all(|k| (k - u).abs() > 0.01 * (b - a)) {
            break;
        }
        u = a + (u - a + 0.013 * (b - a)) % (b - a);
    }
    u
}

fn scale(c: &NurbsCurve) -> f64 {
    c.points_flat().iter().fold(1.0f64, |m, x| m.max(x.abs()))
}

proptest! {
    #![proptest_config(config(64))]

    /// Insert u r times (f64, A5.1), then remove it with a tolerance of 1e-9 of the data
    /// scale: it goes away as often as it was inserted, the knots are the original ones, the
    /// control points are the original ones up to rounding, and the verified bound is tiny.
    /// Where the f64 insertion was exact (the interval insertion gives singletons), removal
    /// with tolerance 0 gives the original back bit for bit.
    #[test]
    fn insert_then_remove(c in curves(), f in 0.0f64..1.0, on in any::<bool>(), r0 in 1usize..=5) {
        let p = c.degree();
        let u = pick_u(&c, f, on);
        let s = multiplicity(c.knots(), u);
        prop_assume!(s < p);
        let r = r0.min(p - s);
        let ins = c.insert_knot(u, r).unwrap();
        let tol = 1e-9 * scale(&c);
        let rem = ins.remove_knot(u, r, tol).unwrap();
        prop_assert_eq!(rem.removed, r);
        prop_assert_eq!(rem.curve.knots(), c.knots());
        prop_assert_eq!(rem.curve.is_rational(), c.is_rational());
        for (x, y) in rem.curve.points_flat().iter().zip(c.points_flat()) {
            prop_assert!((x - y).abs() <= 1e-9 * scale(&c), "{} vs {}", x, y);
        }
        prop_assert!(rem.error_bound.iter().all(|&b| b <= tol));
        let exact = HSpline::<Interval>::from_curve(&c)
            .insert_knot(u, r)
            .pts
            .iter()
            .all(|x| x.inf() == x.sup());
        if exact {
            let rem0 = ins.remove_knot(u, r, 0.0).unwrap();
            prop_assert_eq!(rem0.removed, r);
            prop_assert_eq!(&rem0.curve, &c);
        }
    }

    /// Dyadic data (integer control points, uniform integer knots, degree 1, 2 or 4, so every
    /// alpha of the insertion and of the removal is dyadic for u on a quarter grid): insertion is exact, and exact
    /// removal (tolerance 0) gives the curve before the insertion bit for bit, with bound 0.
    #[test]
    fn exact_removal_is_bit_for_bit(
        pi in 0usize..3,
        extra in 0usize..5,
        d in 1usize..=3,
        pts in prop::collection::vec(-1000i32..1000, 10 * 3),
        q in 1usize..100,
        r0 in 1usize..=4,
    ) {
        let p = [1usize, 2, 4][pi];
        let n = p + 1 + extra;
        let knots: Vec<f64> = (0..n + p + 1).map(|i| i as f64).collect();
        let pts: Vec<f64> = pts[..n * d].iter().map(|&x| x as f64).collect();
        let c = NurbsCurve::from_flat(p, d, knots, pts, None).unwrap();
        let (a, b) = c.domain();
        let u = a + ((q as f64 / 4.0) % (b - a));
        prop_assume!(a < u && u < b);
        let s = multiplicity(c.knots(), u);
        prop_assume!(s < p);
        // one insertion (alphas (u - u_i) / p), or two for p = 2 (then (u - u_i) / 1): dyadic
        let r = if p == 2 { r0.min(2 - s) } else { 1 };
        let exact = HSpline::<Interval>::from_curve(&c)
            .insert_knot(u, r)
            .pts
            .iter()
            .all(|x| x.inf() == x.sup());
        prop_assert!(exact, "the insertion is exact by construction");
        let ins = c.insert_knot(u, r).unwrap();
        let rem = ins.remove_knot(u, r, 0.0).unwrap();
        prop_assert_eq!(rem.removed, r);
        prop_assert_eq!(&rem.curve, &c);
        prop_assert_eq!(rem.error_bound, vec![0.0; d]);
    }

    /// The generic kernel in interval arithmetic: insertion and removal both run on intervals,
    /// and the result encloses the control points before the insertion (the exact inverse of
    /// the exact insertion lies in every interval). A wrong alpha or a wrong index would fail.
    #[test]
    fn interval_removal_encloses_the_original(c in curves(), f in 0.0f64..1.0, on in any::<bool>(), r0 in 1usize..=5) {
        let p = c.degree();
        let u = pick_u(&c, f, on);
        let s = multiplicity(c.knots(), u);
        prop_assume!(s < p);
        let r = r0.min(p - s);
        let h = HSpline::<Interval>::from_curve(&c);
        let (back, removed) = h.insert_knot(u, r).remove_knot(u, r, f64::INFINITY).unwrap();
        prop_assert_eq!(removed, r);
        prop_assert_eq!(&back.knots, &h.knots);
        for (x, y) in back.pts.iter().zip(&h.pts) {
            // y is the (enclosure of the) original point: a singleton unless rational
            prop_assert!(!x.intersection(*y).is_empty(), "{:?} does not enclose {:?}", x, y);
            if y.inf() == y.sup() {
                prop_assert!(x.contains(y.inf()));
            }
        }
    }

    /// Removal of an existing knot with a random tolerance: the reported bound is <= tol, and
    /// the result is within the bound of the input everywhere (sampled in f64 intervals; the
    /// MPFR version below samples exactly).
    #[test]
    fn removal_respects_the_tolerance(c in curves(), f in 0.0f64..1.0, lt in -6.0f64..0.5) {
        let u = pick_u(&c, f, true);
        let (a, b) = c.domain();
        prop_assume!(a < u && u < b && multiplicity(c.knots(), u) > 0);
        let tol = 10f64.powf(lt) * scale(&c);
        let rem = c.remove_knot(u, usize::MAX, tol).unwrap();
        prop_assert!(rem.removed <= rem.multiplicity);
        prop_assert_eq!(rem.curve.knots().len() + rem.removed, c.knots().len());
        prop_assert!(rem.error_bound.iter().all(|&e| e <= tol));
        for i in 0..=100 {
            let t = (a + (b - a) * i as f64 / 100.0).min(b);
            let x = c.enclose_point(Interval::try_from((t, t)).unwrap()).unwrap();
            let y = rem.curve.enclose_point(Interval::try_from((t, t)).unwrap()).unwrap();
            for j in 0..c.dim() {
                let gap = (x[j] - y[j]).mag();
                // both enclosures are ~1e-14 wide; the exact distance is <= error_bound
                prop_assert!(gap <= rem.error_bound[j] + 1e-12 * scale(&c), "t={} j={} gap {} > {}", t, j, gap, rem.error_bound[j]);
            }
        }
    }
}

#[cfg(feature = "mpfr")]
mod mpfr {
    use super::*;
    use rug::Float;

    fn dist(a: &[Float], b: &[Float]) -> Vec<f64> {
        a.iter()
            .zip(b)
            .map(|(x, y)| Float::with_val(256, x - y).abs().to_f64())
            .collect()
    }

    /// Sample parameters: the knots inside the domain, their neighbours, and a dense grid.
    fn samples(c: &NurbsCurve) -> Vec<f64> {
        let (a, b) = c.domain();
        let mut t: Vec<f64> = (0..=300)
            .map(|i| (a + (b - a) * i as f64 / 300.0).min(b))
            .collect();
        for &k in c.knots() {
            if a <= k && k <= b {
                t.extend([k, k.next_down().max(a), k.next_up().min(b)]);
            }
        }
        t
    }

    proptest! {
        #![proptest_config(config(48))]

        /// A perturbed insertion removed within a random tolerance: at every MPFR sample the
        /// exact distance between input and result is <= the reported bound <= tol; and when
        /// the perturbation is far below the tolerance, every inserted copy goes away.
        #[test]
        fn removal_moves_no_point_by_more_than_tol(
            c in curves(),
            f in 0.0f64..1.0,
            r0 in 1usize..=5,
            noise_exp in -14.0f64..-2.0,
            tol_exp in -8.0f64..-1.0,
            seed in any::<u64>(),
        ) {
            let p = c.degree();
            let u = pick_u(&c, f, false);
            let s = multiplicity(c.knots(), u);
            prop_assume!(s < p);
            let r = r0.min(p - s);
            let ins = c.insert_knot(u, r).unwrap();
            // perturb the inserted curve's control points by up to noise * scale
            let sc = scale(&c);
            let noise = 10f64.powf(noise_exp) * sc;
            let mut x = seed;
            let pts: Vec<f64> = ins.points_flat().iter().map(|&v| {
                x = x.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                v + noise * (((x >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0)
            }).collect();
            let noisy = NurbsCurve::from_flat(p, c.dim(), ins.knots().to_vec(), pts, ins.weights().map(<[f64]>::to_vec)).unwrap();
            let tol = 10f64.powf(tol_exp) * sc;
            let rem = noisy.remove_knot(u, r, tol).unwrap();
            prop_assert!(rem.error_bound.iter().all(|&e| e <= tol));
            for t in samples(&noisy) {
                let a: Vec<Float> = noisy.point(t).unwrap();
                let b: Vec<Float> = rem.curve.point(t).unwrap();
                for (j, dj) in dist(&a, &b).into_iter().enumerate() {
                    prop_assert!(dj <= rem.error_bound[j] * (1.0 + 1e-12) + 1e-60 * sc,
                        "t={} j={}: moved {} > bound {}", t, j, dj, rem.error_bound[j]);
                }
            }
            if noise * 1e8 < tol && !c.is_rational() {
                prop_assert_eq!(rem.removed, r, "noise {} tol {}", noise, tol);
            }
        }

        /// The generic kernel in MPFR: insertion and removal at 256 bits give the original
        /// control points back to ~2^-240 relative.
        #[test]
        fn mpfr_insert_then_remove(c in curves(), f in 0.0f64..1.0, r0 in 1usize..=5) {
            let p = c.degree();
            let u = pick_u(&c, f, false);
            let s = multiplicity(c.knots(), u);
            prop_assume!(s < p);
            let r = r0.min(p - s);
            let h = HSpline::<Float>::from_curve(&c);
            let (back, removed) = h.insert_knot(u, r).remove_knot(u, r, 1e-60).unwrap();
            prop_assert_eq!(removed, r);
            for (x, y) in back.pts.iter().zip(&h.pts) {
                let e = Float::with_val(256, x - y).abs().to_f64();
                prop_assert!(e <= 1e-65 * scale(&c), "{} vs {}", x, y);
            }
        }
    }
}

// ---- the `remove-knot` command ----

fn run(args: &[&str], stdin: &str) -> (i32, String, String) {
    common::run_bin(args, stdin.as_bytes())
}

#[test]
fn cli_removes_an_inserted_knot_and_reports() {
    let c = NurbsCurve::new(
        2,
        vec![0., 0., 0., 1., 2., 3., 3., 3.],
        vec![
            vec![0., 1.],
            vec![2., 5.],
            vec![4., -3.],
            vec![7., 2.],
            vec![9., 0.],
        ],
        None,
    )
    .unwrap();
    // 1.5 twice: alphas 3/4, 1/4, then 1/2 (dyadic), so insertion and removal are exact
    let ins = c.insert_knot(1.5, 2).unwrap();
    // a second curve where 1.5 is not a knot: error record on stderr, exit 1
    let input = format!(
        "{}\n{}\n",
        nurbs_box::curve_to_json(&ins),
        nurbs_box::curve_to_json(&c)
    );
    let dir = std::env::temp_dir().join(format!("nurbs-box-rk-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let rep = dir.join("report.jsonl");
    let (code, out, err) = run(
        &[
            "remove-knot",
            "--knot",
            "1.5",
            "--report",
            rep.to_str().unwrap(),
        ],
        &input,
    );
    assert_eq!(code, 1, "{err}");
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 1);
    assert_eq!(nurbs_box::parse_curve(lines[0].as_bytes()).unwrap(), c);
    let e: serde_json::Value = serde_json::from_str(err.trim()).unwrap();
    assert_eq!(e["index"], 1);
    assert_eq!(e["error"]["kind"], "knot_not_present");
    let r: serde_json::Value =
        serde_json::from_str(std::fs::read_to_string(&rep).unwrap().trim()).unwrap();
    assert_eq!(r["index"], 0);
    assert_eq!(r["multiplicity"], 2);
    assert_eq!(r["removed"], 2);
    assert_eq!(r["error_bound"], serde_json::json!([0.0, 0.0]));
    // --times 1; the output pipes into enclose
    let (code, out, _) = run(
        &["remove-knot", "--knot", "1.5", "--times", "1"],
        &input[..input.find('\n').unwrap()],
    );
    assert_eq!(code, 0);
    let one = nurbs_box::parse_curve(out.trim().as_bytes()).unwrap();
    assert_eq!(multiplicity(one.knots(), 1.5), 1);
    let (code, boxes, _) = run(&["enclose"], &out);
    assert_eq!(code, 0);
    assert!(boxes.contains("\"verified\":true"));
    // a needed knot stays at tol 0 and goes with a large tol
    let (_, out0, _) = run(
        &["remove-knot", "--knot", "1"],
        &nurbs_box::curve_to_json(&c),
    );
    assert_eq!(nurbs_box::parse_curve(out0.trim().as_bytes()).unwrap(), c);
    let (_, out1, _) = run(
        &["remove-knot", "--knot", "2", "--tol", "100"],
        &nurbs_box::curve_to_json(&c),
    );
    assert_eq!(
        nurbs_box::parse_curve(out1.trim().as_bytes())
            .unwrap()
            .num_points(),
        4
    );
    // bad flags: exit 2
    assert_eq!(run(&["remove-knot", "--knot", "1", "--tol", "-1"], "").0, 2);
    assert_eq!(run(&["remove-knot", "--knot", "nan"], "").0, 2);
    assert_eq!(run(&["remove-knot"], "").0, 2);
    let _ = std::fs::remove_dir_all(&dir);
}
