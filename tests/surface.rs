//! Surfaces: containment and tightness of every surface strategy against dense verified
//! sampling and closed forms, the CLI and parser contract, hostile input.

mod common;

use inari::Interval;
use nurbs_box::enclose::{Enclosure, Guarantee, Settings, Termination};
use nurbs_box::io::{parse_record, Shape};
use nurbs_box::num::ulp;
use nurbs_box::surface::enclose::all_surface_strategies;
use nurbs_box::surface::gen::{families, random_surface};
use nurbs_box::surface::{surface_strategy_by_name, NurbsSurface, SURFACE_STRATEGY_NAMES};
use proptest::prelude::*;

/// Verified point enclosures on an n x n grid of the domain plus the Greville-like midpoints.
fn samples(s: &NurbsSurface, n: usize) -> Vec<Vec<Interval>> {
    let ((a, b), (c, d)) = s.domain();
    let mut out = Vec::with_capacity((n + 1) * (n + 1));
    for i in 0..=n {
        for j in 0..=n {
            let u = if i == n {
                b
            } else {
                a + (b - a) * i as f64 / n as f64
            };
            let v = if j == n {
                d
            } else {
                c + (d - c) * j as f64 / n as f64
            };
            out.push(s.enclose_derivative(u, v, 0, 0).unwrap());
        }
    }
    out
}

/// Containment (no sample provably outside the box) and consistency of the inner bounds
/// (lo <= inner_lo, inner_hi <= hi, and some sample comes within `slack` of each inner bound).
fn check(name: &str, s: &NurbsSurface, e: &Enclosure, pts: &[Vec<Interval>], slack: f64) {
    assert!(e.verified, "{name} {}", e.strategy);
    for (j, cb) in e.coords.iter().enumerate() {
        assert!(
            cb.lo.is_finite() && cb.hi.is_finite(),
            "{name} {}",
            e.strategy
        );
        assert!(
            cb.lo <= cb.inner_lo && cb.inner_hi <= cb.hi,
            "{name} {} {j}",
            e.strategy
        );
        let mut smin = f64::INFINITY;
        let mut smax = f64::NEG_INFINITY;
        for p in pts {
            assert!(
                p[j].sup() >= cb.lo && p[j].inf() <= cb.hi,
                "{name} {}: coordinate {j} sample [{}, {}] outside [{}, {}]",
                e.strategy,
                p[j].inf(),
                p[j].sup(),
                cb.lo,
                cb.hi
            );
            smin = smin.min(p[j].inf());
            smax = smax.max(p[j].sup());
        }
        let sl = slack * s.coord_scale(j);
        assert!(
            smin <= cb.inner_lo + sl,
            "{name} {} {j}: min sample {smin} vs inner {}",
            e.strategy,
            cb.inner_lo
        );
        assert!(
            smax >= cb.inner_hi - sl,
            "{name} {} {j}: max sample {smax} vs inner {}",
            e.strategy,
            cb.inner_hi
        );
    }
}

#[test]
fn every_strategy_contains_dense_samples_of_every_family() {
    for (name, s, exact) in families() {
        let pts = samples(&s, 48);
        for st in all_surface_strategies(&Settings::default()) {
            let e = st.enclose(&s);
            // the grid has spacing 1/48: the surface comes within ~1e-2 of every extremum there
            let slack = if st.name() == "hull" { 10.0 } else { 2e-2 };
            check(name, &s, &e, &pts, slack);
            if let Some(ex) = &exact {
                for (j, cb) in e.coords.iter().enumerate() {
                    // the closed forms hold up to the rounding of the control points (1e-15)
                    let t = 4e-15 * s.coord_scale(j);
                    assert!(
                        cb.lo <= ex[j].0 + t && ex[j].1 - t <= cb.hi,
                        "{name} {} {j}",
                        st.name()
                    );
                    if st.name() != "hull" {
                        assert!(
                            cb.inner_lo >= ex[j].0 - t && cb.inner_hi <= ex[j].1 + t,
                            "{name} {} {j}: false inner bound",
                            st.name()
                        );
                        assert!(
                            cb.inner_lo <= ex[j].0 + t && cb.inner_hi >= ex[j].1 - t,
                            "{name} {} {j}: loose inner bound",
                            st.name()
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn newton_and_bezier_are_tight() {
    // (weights 1e-150 .. 1e150 make S nearly piecewise constant with sharp fronts: the interval
    // derivative enclosures are too wide for newton's own search, which ends at its limit and
    // takes the bezier bounds, a few tens of ulps; that family is checked on its own below)
    for (name, s, _) in families().into_iter().filter(|f| f.0 != "extreme_weights") {
        for (st, rel) in [("newton", 8.0 * f64::EPSILON), ("bezier", 1e-13)] {
            let e = surface_strategy_by_name(st, None).unwrap().enclose(&s);
            for (j, cb) in e.coords.iter().enumerate() {
                let scale = s.coord_scale(j);
                assert!(
                    cb.gap() <= rel * scale + ulp(scale),
                    "{name} {st} {j}: gap {} ({:?})",
                    cb.gap(),
                    cb.termination
                );
            }
        }
    }
}

#[test]
fn extreme_weights_stay_sound_and_beat_the_net_box() {
    let fam = families();
    let s = &fam.iter().find(|f| f.0 == "extreme_weights").unwrap().1;
    let hull = surface_strategy_by_name("hull", None).unwrap().enclose(s);
    for st in ["bezier", "newton"] {
        let e = surface_strategy_by_name(st, None).unwrap().enclose(s);
        let w = |e: &Enclosure| e.coords.iter().map(|c| c.hi - c.lo).sum::<f64>();
        assert!(w(&e) <= w(&hull), "{st}");
        eprintln!(
            "extreme weights, {st}: gaps {:?}, {:?}",
            e.coords.iter().map(|c| c.gap()).collect::<Vec<_>>(),
            e.termination()
        );
    }
}

#[test]
fn interior_maximum_ridge_and_pole_are_exact() {
    let fam = families();
    let get = |n: &str| fam.iter().find(|f| f.0 == n).unwrap().1.clone();
    let newton = surface_strategy_by_name("newton", None).unwrap();
    // the bump's interior maximum 1 (net maximum 4) and the ridge's maximum 1 on a line
    for name in ["bump", "ridge"] {
        let e = newton.enclose(&get(name));
        assert!(
            e.coords[2].hi - 1.0 <= 2.0 * f64::EPSILON,
            "{name} {}",
            e.coords[2].hi
        );
        assert!(e.coords[2].inner_hi <= 1.0 && e.coords[2].inner_hi >= 1.0 - 2.0 * f64::EPSILON);
        assert_ne!(e.coords[2].termination, Termination::WorkLimit, "{name}");
    }
    // the sphere octant: the pole row collapses to (0, 0, 1), z reaches 1 exactly there
    let e = newton.enclose(&get("sphere_pole"));
    assert_eq!((e.coords[2].hi, e.coords[2].inner_hi), (1.0, 1.0));
    assert_eq!(e.coords[0].lo, 0.0);
    // the bezier strategy gets the bump from the vertex test after one subdivision
    let b = surface_strategy_by_name("bezier", None)
        .unwrap()
        .enclose(&get("bump"));
    assert_eq!((b.coords[2].hi, b.coords[2].inner_hi), (1.0, 1.0));
}

#[test]
fn parser_errors_are_typed_and_positioned() {
    let ok = r#"{"degree_u": 2, "degree_v": 1, "knots_u": [0, 0, 0, 1, 1, 1], "knots_v": [0, 0, 1, 1], "control_points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 2], [1, 1, 2]], [[2, 0, 0], [2, 1, 0]]], "weights": [[1, 1], [0.5, 0.5], [1, 1]]}"#;
    let Shape::Surface(s) = parse_record(ok.as_bytes()).unwrap() else {
        panic!("a surface")
    };
    assert_eq!((s.rows(), s.cols(), s.dim()), (3, 2, 3));
    // a curve in the same parser
    assert!(matches!(
        parse_record(br#"{"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0], [1]]}"#),
        Ok(Shape::Curve(_))
    ));
    let cases: &[(&str, &str, &str, &str)] = &[
        (
            r#"[[1, 0, 2], [1, 1, 2]]"#,
            r#"[[1, 0, 2]]"#,
            "ragged_net",
            "control_points[1]:",
        ),
        (
            r#"[1, 1, 2]]"#,
            r#"[1, 1, "y"]]"#,
            "wrong_type",
            "control_points[1][1][2]:",
        ),
        (
            r#"[1, 1, 2]]"#,
            r#"[1, 1, 2, 3]]"#,
            "dimension_mismatch",
            "control_points[1][1]:",
        ),
        (
            r#"[1, 1, 2]]"#,
            r#"[1, 1, 1e400]]"#,
            "number_out_of_range",
            "control_points[1][1][2]:",
        ),
        (r#"[0, 0, 1, 1]"#, r#"[0, 0, 1]"#, "knot_count", "knots_v:"),
        (
            r#"[0, 0, 0, 1, 1, 1]"#,
            r#"[0, 0, 0.5, 0.2, 1, 1]"#,
            "decreasing_knots",
            "knots_u[3]",
        ),
        (
            r#"[0.5, 0.5]"#,
            r#"[0.5, 0]"#,
            "invalid_weight",
            "weights[1][1]",
        ),
        (r#"[0.5, 0.5]"#, r#"[0.5]"#, "weight_count", "weights[1]"),
        (
            r#"[[1, 1], [0.5, 0.5], [1, 1]]"#,
            r#"[1, 0.5, 1]"#,
            "wrong_type",
            "weights[0]",
        ),
        (
            r#""degree_v": 1"#,
            r#""degree_v": -1"#,
            "invalid_degree",
            "degree_v",
        ),
        (
            r#""degree_v": 1"#,
            r#""degree_v": 1, "degree": 1"#,
            "unknown_field",
            "\"degree\"",
        ),
        (
            r#""degree_v": 1"#,
            r#""degree_v": 1, "colour": 1"#,
            "unknown_field",
            "\"colour\"",
        ),
        (r#""degree_v": 1, "#, "", "missing_field", "degree_v"),
        (
            r#""degree_v": 1"#,
            r#""degree_v": 1, "degree_v": 1"#,
            "duplicate_field",
            "degree_v",
        ),
    ];
    for &(from, to, kind, start) in cases {
        assert!(ok.contains(from), "{from}");
        let bad = ok.replacen(from, to, 1);
        let e = parse_record(bad.as_bytes()).expect_err(&bad);
        assert_eq!(e.kind(), kind, "{bad}: {e}");
        assert!(e.to_string().starts_with(start), "{bad}: {e}");
    }
    // the curve parser still rejects surface fields as before
    let e = nurbs_box::io::parse_curve(ok.as_bytes()).unwrap_err();
    assert_eq!(e.kind(), "unknown_field");
}

#[test]
fn cli_encloses_and_evaluates_mixed_streams() {
    let input = concat!(
        r#"{"degree_u": 2, "degree_v": 1, "knots_u": [0, 0, 0, 1, 1, 1], "knots_v": [0, 0, 1, 1], "control_points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 2], [1, 1, 2]], [[2, 0, 0], [2, 1, 0]]], "weights": [[1, 1], [0.5, 0.5], [1, 1]]}"#,
        "\n",
        r#"{"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0, 5], [2, -1]]}"#,
        "\n"
    );
    let (code, out, _) = common::run_bin(&["enclose"], input.as_bytes());
    assert_eq!(code, 0, "{out}");
    let lines: Vec<serde_json::Value> = out
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 2);
    assert_eq!(lines[0]["strategy"], "newton");
    // the maximum of z: 2 * 2 u (1 - u) * 0.5 / (1 - u + u^2 ...) = 2/3 at u = 1/2
    let hi = lines[0]["hi"][2].as_f64().unwrap();
    let ihi = lines[0]["inner_hi"][2].as_f64().unwrap();
    assert!(
        ihi <= 2.0 / 3.0 + 1e-16 && hi >= 2.0 / 3.0 - 1e-16 && hi - ihi <= 4e-16,
        "{hi} {ihi}"
    );
    let (code, out, _) = common::run_bin(
        &["enclose", "--strategy", "search-region"],
        input.as_bytes(),
    );
    assert_eq!(code, 1);
    assert!(
        out.lines().next().unwrap().contains("unsupported_strategy"),
        "{out}"
    );
    let (code, out, _) = common::run_bin(&["enclose", "--strategy", "all"], input.as_bytes());
    assert_eq!(code, 0);
    assert_eq!(
        out.lines().count(),
        SURFACE_STRATEGY_NAMES.len() + nurbs_box::enclose::STRATEGY_NAMES.len()
    );
    let (code, out, _) = common::run_bin(
        &["eval", "--param", "0.5,0.25", "--derivative", "0,1"],
        input.as_bytes(),
    );
    assert_eq!(code, 0, "{out}");
    let l: Vec<&str> = out.lines().collect();
    let r: serde_json::Value = serde_json::from_str(l[0]).unwrap();
    assert_eq!(r["param"], serde_json::json!([0.5, 0.25]));
    assert_eq!(r["derivative"], serde_json::json!([0, 1]));
    // S_v = (0, 1, 0): y = v along the columns
    assert_eq!(r["lo"], serde_json::json!([-0.0, 1.0, -0.0]));
    assert!(
        l[1].starts_with(r#"{"index":1,"param":0.5,"derivative":0,"#),
        "{}",
        l[1]
    );
    let (code, out, _) = common::run_bin(&["eval", "--param", "2,0"], input.as_bytes());
    assert_eq!(code, 1);
    assert!(out.contains("param_out_of_domain"));
    let (code, _, err) = common::run_bin(&["eval", "--param", "0.5,x"], input.as_bytes());
    assert_eq!(code, 2, "{err}");
}

/// Containment on random nets for every strategy, and newton's certified gap.
fn prop_check(s: &NurbsSurface) {
    let pts = samples(s, 12);
    for st in all_surface_strategies(&Settings::default()) {
        let e = st.enclose(s);
        check("random", s, &e, &pts, 10.0);
        if st.name() == "newton" && e.termination() == Termination::Converged {
            for (j, cb) in e.coords.iter().enumerate() {
                assert!(
                    cb.gap() <= 8.0 * f64::EPSILON * s.coord_scale(j) + ulp(s.coord_scale(j)),
                    "coordinate {j}: [{}, {}] inner [{}, {}] of {s:?}",
                    cb.lo,
                    cb.hi,
                    cb.inner_lo,
                    cb.inner_hi
                );
            }
        }
    }
}

proptest! {
    #![proptest_config(common::config(24))]

    #[test]
    fn random_nets_are_contained(seed in any::<u64>(), p in 1usize..4, q in 1usize..4, extra in 0usize..3, rational in any::<bool>()) {
        prop_check(&random_surface(seed, p, q, extra, rational));
    }

    /// Hostile JSON: byte mutations of a valid surface record never panic the parser, and a
    /// record that still parses is enclosed without panicking.
    #[test]
    fn hostile_json_never_panics(cuts in proptest::collection::vec((0usize..400, any::<u8>()), 1..6), trunc in 0usize..400) {
        let ok = br#"{"degree_u": 2, "degree_v": 1, "knots_u": [0, 0, 0, 1, 1, 1], "knots_v": [0, 0, 1, 1], "control_points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 2], [1, 1, 2]], [[2, 0, 0], [2, 1, 0]]], "weights": [[1, 1], [0.5, 0.5], [1, 1]]}"#;
        let mut b = ok.to_vec();
        for (i, x) in cuts {
            let i = i % b.len();
            // mostly structural bytes and digits, sometimes anything
            let alphabet = b"[]{},:0123456789.-e\"x ";
            b[i] = if x < 200 { alphabet[x as usize % alphabet.len()] } else { x };
        }
        if trunc < b.len() && trunc % 3 == 0 {
            b.truncate(trunc);
        }
        if let Ok(Shape::Surface(s)) = parse_record(&b) {
            for st in all_surface_strategies(&Settings { max_work: 200, ..Settings::default() }) {
                let e = st.enclose(&s);
                prop_assert!(e.coords.iter().all(|c| c.lo <= c.hi));
            }
        }
    }
}

#[test]
fn high_degree_stays_bounded_and_sound() {
    // degree 40 x 2: the budgets scale down with the cost of an evaluation
    let s = random_surface(9, 40, 2, 0, true);
    let pts = samples(&s, 10);
    for st in all_surface_strategies(&Settings::default()) {
        let e = st.enclose(&s);
        check("degree 40", &s, &e, &pts, 10.0);
    }
    // above the search degree: the control-net box, reported as a work limit
    let n = 1002;
    let net: Vec<Vec<Vec<f64>>> = (0..n)
        .map(|i| vec![vec![(i as f64).sin(), 0.0], vec![(i as f64).cos(), 1.0]])
        .collect();
    let mut ku = vec![0.0; n];
    ku.extend(vec![1.0; n]);
    let s = NurbsSurface::new(n - 1, 1, ku, vec![0., 0., 1., 1.], net, None).unwrap();
    let e = surface_strategy_by_name("newton", None)
        .unwrap()
        .enclose(&s);
    assert_eq!(e.termination(), Termination::WorkLimit);
    assert_eq!((e.coords[1].lo, e.coords[1].hi), (0.0, 1.0));
}

/// The optimality flags of a surface: `true` exactly where the bound is attained (inner ==
/// outer), on every family and strategy; the rational example of `docs/formats.md` has its
/// corner bounds certified and its interior z maximum (2/3, not a double) not.
#[test]
fn optimality_flags_mark_exactly_the_attained_or_witnessed_bounds() {
    for (name, s, _) in families() {
        for e in all_surface_strategies(&Settings::default()) {
            let r = e.enclose(&s);
            for (j, c) in r.coords.iter().enumerate() {
                let what = format!("{name} {} coordinate {j}", e.name());
                // a strict witness lies inside the box: S_j < witness_lo somewhere and
                // S_j >= lo everywhere, so witness_lo > lo (likewise hi)
                assert!(
                    c.witness_lo > c.lo && c.witness_hi < c.hi,
                    "{what}: witness"
                );
                // the attained rule, or a strict witness within one ulp (`Ddi::strictly_below`)
                let lo = c.inner_lo == c.lo || c.witness_lo <= c.lo.next_up();
                let hi = c.inner_hi == c.hi || c.witness_hi >= c.hi.next_down();
                assert_eq!(
                    c.optimal_lo,
                    e.guarantee() == Guarantee::Verified && lo,
                    "{what}: optimal_lo"
                );
                assert_eq!(
                    c.optimal_hi,
                    e.guarantee() == Guarantee::Verified && hi,
                    "{what}: optimal_hi"
                );
            }
        }
    }
    let text = r#"{"degree_u": 2, "degree_v": 1, "knots_u": [0, 0, 0, 1, 1, 1], "knots_v": [0, 0, 1, 1],
        "control_points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 2], [1, 1, 2]], [[2, 0, 0], [2, 1, 0]]],
        "weights": [[1, 1], [0.5, 0.5], [1, 1]]}"#;
    let Ok(Shape::Surface(s)) = parse_record(text.as_bytes()) else {
        panic!("the example is a surface")
    };
    let r = surface_strategy_by_name("newton", None)
        .unwrap()
        .enclose(&s);
    let lo: Vec<bool> = r.coords.iter().map(|c| c.optimal_lo).collect();
    let hi: Vec<bool> = r.coords.iter().map(|c| c.optimal_hi).collect();
    assert_eq!(lo, [true, true, true]);
    // z's maximum 2/3 is not a float: certified by the fast path's double-double witness,
    // hi = RU(2/3) (the f64 nearest 2/3 lies below it)
    assert_eq!(hi, [true, true, true]);
    assert!(2.0 / 3.0 < r.coords[2].hi && r.coords[2].inner_hi <= 2.0 / 3.0);
    assert_eq!(r.coords[2].hi, (2.0f64 / 3.0).next_up());
}

/// The float-first fast path of `bezier` and `newton` on shapes with a known answer: an
/// interior maximum that is a float (exact), a saddle, a corner-extreme patch (vertex test),
/// rational patches (one ulp), and a ridge (no strict concavity: proven by the ridge test,
/// concave along one direction, constant along the other), without the general search.
#[test]
fn fast_path_proves_interior_saddle_corner_rational_and_ridge() {
    use nurbs_box::surface::gen::bezier_patch;
    let fam = families();
    let get = |n: &str| fam.iter().find(|f| f.0 == n).unwrap().1.clone();
    // a bicubic bump 1 + 16 u(1-u) v(1-v)-like interior maximum at a non-dyadic point
    let bump3 = bezier_patch(
        3,
        3,
        (0..4)
            .map(|r| {
                (0..4)
                    .map(|c| {
                        let z = if (1..=2).contains(&r) && (1..=2).contains(&c) {
                            2.0 + 0.3 * r as f64 - 0.1 * c as f64
                        } else {
                            0.1 * (r + c) as f64
                        };
                        vec![r as f64 / 3.0, c as f64 / 3.0, z]
                    })
                    .collect()
            })
            .collect(),
        None,
    );
    let corner = bezier_patch(
        3,
        3,
        (0..4)
            .map(|r| {
                (0..4)
                    .map(|c| vec![r as f64, c as f64, (r * r + c) as f64 * 0.1])
                    .collect()
            })
            .collect(),
        None,
    );
    let rational = random_surface(11, 3, 3, 0, true);
    let rational2 = random_surface(12, 2, 2, 2, true);
    for name in ["bezier", "newton"] {
        let st = surface_strategy_by_name(name, None).unwrap();
        // the bump's top z = 1 at (1/2, 1/2): exact
        let e = st.enclose(&get("bump"));
        assert_eq!((e.coords[2].hi, e.coords[2].inner_hi), (1.0, 1.0), "{name}");
        assert!(e.coords[2].stats.fast_proofs >= 1, "{name}");
        // the corner patch: every extreme is a corner coefficient, no search at all
        let e = st.enclose(&corner);
        let h = surface_strategy_by_name("hull", None)
            .unwrap()
            .enclose(&corner);
        assert_eq!(e.lo(), h.lo());
        assert_eq!(e.hi(), h.hi());
        assert!(e.coords.iter().all(|c| c.gap() == 0.0), "{name}");
        assert_eq!(e.stats().fast_exits, 6, "{name}");
        // interior maximum at a non-dyadic point, saddle, rational patches: one ulp
        for (label, s) in [
            ("bump3", &bump3),
            ("saddle", &get("saddle")),
            ("rational", &rational),
            ("rational2", &rational2),
        ] {
            let e = st.enclose(s);
            check(label, s, &e, &samples(s, 40), 2e-2);
            for (j, cb) in e.coords.iter().enumerate() {
                let u = ulp(s.coord_scale(j));
                assert!(
                    cb.gap() <= u,
                    "{name} {label} {j}: gap {} ulps",
                    cb.gap() / u
                );
            }
            assert_eq!(e.stats().fast_fallbacks, 0, "{name} {label}");
        }
        // the ridge z = 4 u (1 - u): maximum 1 on the line u = 1/2, proven float first (no
        // fallback to the general search) and exact; also along v (transposed)
        let ridge = get("ridge");
        for (label, s) in [("ridge", ridge.clone()), ("ridge_v", ridge.transposed())] {
            let e = st.enclose(&s);
            check(label, &s, &e, &samples(&s, 40), 2e-2);
            assert_eq!(e.stats().fast_fallbacks, 0, "{name} {label}");
            assert_eq!(
                (e.coords[2].hi, e.coords[2].inner_hi),
                (1.0, 1.0),
                "{name} {label}"
            );
        }
    }
}

/// Ridges of every kind the fast path meets in CAD data: a bicubic ridge at a non-dyadic
/// line, a ridge across a two-patch surface, a rational one (a cylinder patch: x = cos
/// along the arc, constant along the axis), and ridges of both signs. Each side must be
/// proven float first (no fallback), within one ulp of the closed form, and contain dense
/// verified samples.
#[test]
fn fast_path_proves_ridges() {
    use nurbs_box::surface::gen::bezier_patch;
    // z = g(u) with g's Bernstein coefficients 0, 1.3, 0.7, 0.2: an interior maximum of g at
    // a non-dyadic u, constant along v (every column equal)
    let g = [0.0, 1.3, 0.7, 0.2];
    let gmax = {
        // g(u) = sum g_i B_i(u): maximise by bisection on g' (closed form is a quadratic root)
        let dg = |u: f64| {
            let d = [g[1] - g[0], g[2] - g[1], g[3] - g[2]];
            3.0 * (d[0] * (1.0 - u) * (1.0 - u) + 2.0 * d[1] * u * (1.0 - u) + d[2] * u * u)
        };
        let (mut a, mut b) = (0.0f64, 1.0f64);
        for _ in 0..200 {
            let m = 0.5 * (a + b);
            if dg(m) > 0.0 {
                a = m
            } else {
                b = m
            }
        }
        let u = 0.5 * (a + b);
        g[0] * (1.0 - u).powi(3)
            + 3.0 * g[1] * u * (1.0 - u).powi(2)
            + 3.0 * g[2] * u * u * (1.0 - u)
            + g[3] * u.powi(3)
    };
    let cubic = bezier_patch(
        3,
        2,
        (0..4)
            .map(|r| {
                (0..3)
                    .map(|c| vec![r as f64 / 3.0, c as f64 / 2.0, g[r]])
                    .collect()
            })
            .collect(),
        None,
    );
    // the same profile negated (a valley: the minimum side) and on two patches in v
    let valley = bezier_patch(
        3,
        2,
        (0..4)
            .map(|r| {
                (0..3)
                    .map(|c| vec![r as f64 / 3.0, c as f64 / 2.0, -g[r]])
                    .collect()
            })
            .collect(),
        None,
    );
    let two = NurbsSurface::new(
        3,
        2,
        vec![0., 0., 0., 0., 1., 1., 1., 1.],
        vec![0., 0., 0., 0.4, 1., 1., 1.],
        (0..4)
            .map(|r| {
                (0..4)
                    .map(|c| vec![r as f64 / 3.0, c as f64 / 3.0, g[r]])
                    .collect()
            })
            .collect(),
        None,
    )
    .unwrap();
    // a quarter cylinder: (cos t, sin t) along u (rational quadratic arc), the axis along v
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let arc = [(1.0, 0.0, 1.0), (1.0, 1.0, h), (0.0, 1.0, 1.0)];
    let cyl = bezier_patch(
        2,
        1,
        arc.iter()
            .map(|&(x, y, _)| (0..2).map(|c| vec![x, y, c as f64]).collect())
            .collect(),
        Some(arc.iter().map(|&(_, _, w)| vec![w; 2]).collect()),
    );
    // a rotated quarter: x = cos t over t in [-45°, 45°] has its ridge x = 1 inside
    let arc2 = [(h, -h, 1.0), (2.0 * h, 0.0, h), (h, h, 1.0)];
    let cyl2 = bezier_patch(
        2,
        1,
        arc2.iter()
            .map(|&(x, y, _)| (0..2).map(|c| vec![x, y, c as f64]).collect())
            .collect(),
        Some(arc2.iter().map(|&(_, _, w)| vec![w; 2]).collect()),
    );
    for name in ["bezier", "newton"] {
        let st = surface_strategy_by_name(name, None).unwrap();
        for (label, s, j, hi, want) in [
            ("cubic", &cubic, 2, true, gmax),
            ("valley", &valley, 2, false, -gmax),
            ("two patches", &two, 2, true, gmax),
            ("cubic v", &cubic.transposed(), 2, true, gmax),
            ("cylinder2", &cyl2, 0, true, 1.0),
        ] {
            let e = st.enclose(s);
            check(label, s, &e, &samples(s, 40), 2e-2);
            let cb = &e.coords[j];
            let (b, inner) = if hi {
                (cb.hi, cb.inner_hi)
            } else {
                (cb.lo, cb.inner_lo)
            };
            let u = ulp(s.coord_scale(j));
            assert!(
                (b - want).abs() <= 4.0 * u && (inner - want).abs() <= 4.0 * u,
                "{name} {label}: [{inner}, {b}] vs {want}"
            );
            assert!(cb.gap() <= u, "{name} {label}: gap {}", cb.gap() / u);
            assert_eq!(e.stats().fast_fallbacks, 0, "{name} {label}");
        }
        let e = st.enclose(&cyl);
        check("cylinder", &cyl, &e, &samples(&cyl, 40), 2e-2);
        assert_eq!(e.stats().fast_fallbacks, 0, "{name} cylinder");
    }
}

/// The fast path against the general search (both sound): each one's attained values lie
/// inside the other's outer box, and the fast path is at least as tight.
#[test]
fn fast_path_agrees_with_the_general_search() {
    use nurbs_box::surface::enclose::{BezierPatches, SurfaceNewton};
    use nurbs_box::surface::SurfaceEncloser;
    for seed in 0..12u64 {
        let p = 1 + (seed as usize % 4);
        let s = random_surface(300 + seed, p, p, seed as usize % 3, seed % 2 == 1);
        let slow = SurfaceNewton {
            fast_path: false,
            ..Default::default()
        }
        .enclose(&s);
        let fast = [
            SurfaceNewton::default().enclose(&s),
            BezierPatches::default().enclose(&s),
        ];
        for e in &fast {
            for (j, (a, b)) in e.coords.iter().zip(&slow.coords).enumerate() {
                assert!(
                    a.lo <= b.inner_lo && b.lo <= a.inner_lo,
                    "{seed} {} {j} lo",
                    e.strategy
                );
                assert!(
                    a.inner_hi <= b.hi && b.inner_hi <= a.hi,
                    "{seed} {} {j} hi",
                    e.strategy
                );
                assert!(a.gap() <= b.gap().max(ulp(s.coord_scale(j))), "{seed} {j}");
            }
        }
    }
}

/// Ridges not along parameter lines (the families `ridge_diagonal`, `valley_antidiagonal`,
/// `ridge_rotated`, `ridge_irrational`, `ridge_diagonal_spans`: a maximum or a minimum on a
/// whole line of the domain, across knot lines in the last one) end in a proven bound within
/// one ulp of the closed form, attained to within one ulp, without the general search
/// (the fast path's chord proof, `Prover::ridge_line`).
#[test]
fn fast_path_proves_ridges_off_the_parameter_lines() {
    let fam = families();
    let exact = |n: &str| -> (NurbsSurface, Vec<(f64, f64)>) {
        let f = fam.iter().find(|f| f.0 == n).unwrap();
        (f.1.clone(), f.2.clone().unwrap())
    };
    for name in [
        "ridge_diagonal",
        "valley_antidiagonal",
        "ridge_rotated",
        "ridge_irrational",
        "ridge_diagonal_spans",
    ] {
        let (s, ex) = exact(name);
        for st in ["bezier", "newton"] {
            let e = surface_strategy_by_name(st, None).unwrap().enclose(&s);
            check(name, &s, &e, &samples(&s, 40), 2e-2);
            assert_eq!(e.stats().fast_fallbacks, 0, "{name} {st}");
            let cb = &e.coords[2];
            // (16 / sqrt 3 rounds twice in f64: within one ulp of the exact value)
            let u = ulp(ex[2].1);
            for (b, want, what) in [
                (cb.lo, ex[2].0, "lo"),
                (cb.inner_lo, ex[2].0, "inner_lo"),
                (cb.hi, ex[2].1, "hi"),
                (cb.inner_hi, ex[2].1, "inner_hi"),
            ] {
                assert!(
                    (b - want).abs() <= 2.0 * u,
                    "{name} {st} {what}: {b} vs {want}"
                );
            }
            assert!(cb.gap() <= u, "{name} {st}: gap {}", cb.gap() / u);
            assert_ne!(cb.termination, Termination::WorkLimit, "{name} {st}");
        }
    }
}

/// A ridge along a curve (`gen::ridge_circle`: z has its maximum 0 on an arc) is not proven
/// tight by the chord proof, but it must still end in a sound box far below the net box (net
/// maximum 9): containment of dense samples, hi >= 0 (the exact maximum), hi < 1e-3.
#[test]
fn a_curved_ridge_ends_in_a_sound_box_not_the_net_box() {
    let s = nurbs_box::surface::gen::ridge_circle();
    let pts = samples(&s, 40);
    for st in ["bezier", "newton"] {
        let e = surface_strategy_by_name(st, None).unwrap().enclose(&s);
        check("ridge_circle", &s, &e, &pts, 2e-2);
        let cb = &e.coords[2];
        assert!(cb.hi >= 0.0 && cb.hi < 1e-3, "{st}: hi {}", cb.hi);
        assert!(cb.inner_hi <= 0.0, "{st}: inner_hi {}", cb.inner_hi);
    }
}
