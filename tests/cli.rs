//! The `nurbs-box` binary against the contract of `docs/formats.md`: records, indices, exit
//! statuses, hostile input, both stream forms, order with several threads.

use inari::Interval;
use serde_json::Value;

#[allow(dead_code)] // the proptest config is not used here
mod common;

/// Run the binary with `args`, feeding `stdin`; (exit code, stdout records, stderr).
fn run(args: &[&str], stdin: &[u8]) -> (i32, Vec<Value>, String) {
    let (code, stdout, stderr) = common::run_bin(args, stdin);
    let records = stdout
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("bad record {l:?}: {e}")))
        .collect();
    (code, records, stderr)
}

const LINE: &str = r#"{"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0, 5], [2, -1]]}"#;
/// The quarter of the unit circle ((1-t^2)/(1+t^2), 2t/(1+t^2)), t in [0, 1]: in Bernstein form
/// x w = 1 - t^2 -> (1, 1, 0), y w = 2t -> (0, 1, 2), w = 1 + t^2 -> (1, 1, 2), so the control
/// points (1,0), (1,1), (0,1) with weights 1, 1, 2 are exact and so is the circle.
const QUARTER: &str = r#"{"degree": 2, "knots": [0, 0, 0, 1, 1, 1], "control_points": [[1, 0], [1, 1], [0, 1]], "weights": [1, 1, 2]}"#;

fn f(v: &Value) -> f64 {
    match v {
        Value::String(s) if s == "inf" => f64::INFINITY,
        Value::String(s) if s == "-inf" => f64::NEG_INFINITY,
        _ => v.as_f64().unwrap_or_else(|| panic!("not a number: {v}")),
    }
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array().unwrap().iter().map(f).collect()
}

#[test]
fn mixed_json_lines_get_indexed_records_and_exit_1() {
    let input = format!("{LINE}\n\n{{\"degree\": 1}}\n{QUARTER}\nnot json at all\n{LINE}\n");
    let (code, recs, _) = run(&["enclose", "--strategy", "hull"], input.as_bytes());
    assert_eq!(code, 1);
    assert_eq!(recs.len(), 5);
    for (i, r) in recs.iter().enumerate() {
        assert_eq!(r["index"], i);
    }
    assert_eq!(recs[1]["error"]["kind"], "missing_field");
    assert_eq!(recs[3]["error"]["kind"], "invalid_json");
    for i in [0, 2, 4] {
        assert_eq!(recs[i]["strategy"], "hull");
        assert_eq!(recs[i]["verified"], true);
        for key in [
            "newton_iterations",
            "derivative_evaluations",
            "point_evaluations",
            "subdivisions",
        ] {
            assert!(recs[i]["stats"][key].is_u64(), "{key}");
        }
        assert!(recs[i]["stats"]["termination"].is_string());
    }
    assert_eq!(floats(&recs[0]["lo"]), [0.0, -1.0]);
    assert_eq!(floats(&recs[0]["hi"]), [2.0, 5.0]);
    assert_eq!(floats(&recs[0]["inner_lo"]), [0.0, -1.0]);
    assert_eq!(floats(&recs[0]["inner_hi"]), [2.0, 5.0]);
    // the hull of a line is attained at both ends: every bound certified optimal
    assert_eq!(recs[0]["optimal_lo"], serde_json::json!([true, true]));
    assert_eq!(recs[0]["optimal_hi"], serde_json::json!([true, true]));

    // all valid -> 0
    let (code, recs, _) = run(
        &["enclose", "--strategy", "hull", "-"],
        format!("{LINE}\n{QUARTER}").as_bytes(),
    );
    assert_eq!((code, recs.len()), (0, 2));
    // empty input -> no records, 0
    let (code, recs, _) = run(&["enclose", "--strategy", "hull"], b"");
    assert_eq!((code, recs.len()), (0, 0));
}

#[test]
fn array_form_gives_the_same_records_as_json_lines() {
    let lines = [LINE, QUARTER, "{\"degree\": 2, \"knots\": [1]}", LINE];
    let jsonl = lines.join("\n");
    let array = format!("[\n  {}\n]\n", lines.join(",\n  "));
    let (c1, r1, _) = run(&["enclose", "--strategy", "hull"], jsonl.as_bytes());
    let (c2, r2, _) = run(&["enclose", "--strategy", "hull"], array.as_bytes());
    assert_eq!((c1, c2), (1, 1));
    assert_eq!(r1.len(), 4);
    // identical apart from the line/column in the error message
    for (a, b) in r1.iter().zip(&r2) {
        assert_eq!(a["index"], b["index"]);
        assert_eq!(a.get("lo"), b.get("lo"));
        assert_eq!(a.get("hi"), b.get("hi"));
        assert_eq!(a["error"]["kind"], b["error"]["kind"]);
    }
    assert_eq!(r2[2]["error"]["kind"], "missing_field");
}

#[test]
fn hostile_inputs_are_error_records_with_their_index() {
    let cases: &[(&[u8], &str)] = &[
        (br#"{"degree": 1, "knots": [0, 0, 1"#, "truncated_json"),
        (b"\x00\xff\xfe\x01binary\x7f", "invalid_json"),
        (
            br#"{"degree": 1000000000, "knots": [0, 0, 1, 1], "control_points": [[0], [1]]}"#,
            "too_few_control_points",
        ),
        (
            br#"{"degree": 1, "knots": [0, 0, 1, 1e400], "control_points": [[0], [1]]}"#,
            "number_out_of_range",
        ),
        (
            br#"{"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0], [NaN]]}"#,
            "non_finite_literal",
        ),
        (
            br#"{"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0], ["NaN"]]}"#,
            "wrong_type",
        ),
        (
            br#"{"degree": "one", "knots": [0, 0, 1, 1], "control_points": [[0], [1]]}"#,
            "wrong_type",
        ),
        (
            br#"{"degree": 1, "knots": [], "control_points": []}"#,
            "too_few_control_points",
        ),
        (
            br#"{"degree": -3, "knots": [0, 0, 1, 1], "control_points": [[0], [1]]}"#,
            "invalid_degree",
        ),
        (
            br#"{"degree": 2.5, "knots": [0, 0, 1, 1], "control_points": [[0], [1]]}"#,
            "invalid_degree",
        ),
        (br#"{}"#, "missing_field"),
        (br#"[]"#, "wrong_type"),
        (br#"null"#, "wrong_type"),
    ];
    let mut input = Vec::new();
    for (c, _) in cases {
        input.extend_from_slice(LINE.as_bytes());
        input.push(b'\n');
        input.extend_from_slice(c);
        input.push(b'\n');
    }
    // huge nesting, on its own line
    input.extend_from_slice(LINE.as_bytes());
    input.push(b'\n');
    input.extend_from_slice(b"{\"degree\": ");
    input.extend_from_slice(&b"[".repeat(500_000));
    input.push(b'\n');
    let (code, recs, _) = run(&["enclose", "--strategy", "hull"], &input);
    assert_eq!(code, 1);
    assert_eq!(recs.len(), 2 * cases.len() + 2);
    for (k, (c, kind)) in cases.iter().enumerate() {
        let good = &recs[2 * k];
        let bad = &recs[2 * k + 1];
        assert_eq!(good["index"], 2 * k);
        assert!(good.get("lo").is_some());
        assert_eq!(bad["index"], 2 * k + 1);
        assert_eq!(
            bad["error"]["kind"],
            *kind,
            "{}",
            String::from_utf8_lossy(c)
        );
        assert!(!bad["error"]["message"].as_str().unwrap().is_empty());
    }
    let last = recs.last().unwrap();
    assert_eq!(last["index"], 2 * cases.len() + 1);
    assert!(last.get("error").is_some());

    // the same hostile elements inside the array form, with a truncated end
    let mut array = b"[".to_vec();
    for (c, _) in cases.iter().skip(1) {
        array.extend_from_slice(LINE.as_bytes());
        array.push(b',');
        array.extend_from_slice(c);
        array.push(b',');
    }
    array.extend_from_slice(cases[0].0);
    let (code, recs, _) = run(&["enclose", "--strategy", "hull"], &array);
    assert_eq!(code, 1);
    for (i, r) in recs.iter().enumerate() {
        assert_eq!(r["index"], i);
    }
    assert_eq!(recs.last().unwrap()["error"]["kind"], "truncated_json");
}

#[test]
fn exit_2_when_the_command_cannot_run() {
    let input = LINE.as_bytes();
    for args in [
        &["enclose", "--strategy", "no-such-strategy"][..],
        &["enclose", "--tol", "-1"],
        &["enclose", "--tol", "nan"],
        &["enclose", "--bogus-flag"],
        &["enclose", "/no/such/file.jsonl"],
        &["enclose", "/"],
        &["eval", "--param", "nan"],
        &["eval"],
        &["eval", "--param", "0.5", "--derivative", "51"],
        &["eval", "--param", "abc"],
        &["frobnicate"],
    ] {
        let (code, recs, stderr) = run(args, input);
        assert_eq!(code, 2, "{args:?}");
        assert!(recs.is_empty(), "{args:?}");
        assert!(!stderr.trim().is_empty(), "{args:?}: no message");
    }
    let (_, _, stderr) = run(&["enclose", "--strategy", "no-such-strategy"], input);
    assert!(
        stderr.contains("unknown strategy") && stderr.contains("hull"),
        "{stderr}"
    );
}

#[test]
fn strategy_all_gives_one_record_per_strategy() {
    let (code, recs, _) = run(
        &["enclose", "--strategy", "all"],
        format!("{LINE}\n{QUARTER}").as_bytes(),
    );
    assert_eq!(code, 0);
    let n = nurbs_box::enclose::STRATEGY_NAMES.len();
    assert_eq!(recs.len(), 2 * n);
    for (k, r) in recs.iter().enumerate() {
        assert_eq!(r["index"], k / n);
        assert_eq!(r["strategy"], nurbs_box::enclose::STRATEGY_NAMES[k % n]);
    }
}

#[test]
fn eval_encloses_the_exact_circle() {
    let params = [
        "0",
        "0.1",
        "0.25",
        "0.3333333333333333",
        "0.5",
        "0.7",
        "0.9999999999999999",
        "1",
    ];
    let mut args = vec!["eval"];
    for p in &params {
        args.push("--param");
        args.push(p);
    }
    let (code, recs, _) = run(&args, QUARTER.as_bytes());
    assert_eq!(code, 0);
    assert_eq!(recs.len(), params.len());
    for (r, p) in recs.iter().zip(&params) {
        assert_eq!(r["index"], 0);
        assert_eq!(f(&r["param"]), p.parse::<f64>().unwrap());
        assert_eq!(r["derivative"], 0);
        let (lo, hi) = (floats(&r["lo"]), floats(&r["hi"]));
        let x = Interval::try_from((lo[0], hi[0])).unwrap();
        let y = Interval::try_from((lo[1], hi[1])).unwrap();
        // The box encloses the exact point, which lies on the unit circle; interval arithmetic
        // over the box can only widen |C|^2, so it must contain 1.
        let r2 = x.sqr() + y.sqr();
        assert!(r2.contains(1.0), "param {p}: |C|^2 in {r2:?}");
        // and the box is tight (a few ulps)
        assert!(x.wid() < 1e-15 && y.wid() < 1e-15, "param {p}: {x:?} {y:?}");
    }
    // exact end points
    assert_eq!(floats(&recs[0]["lo"])[0], 1.0);
    assert_eq!(floats(&recs[7]["hi"])[1], 1.0);

    // C'(0) = (0, 2), C'(1) = (-1, 0) (x' = -4t/(1+t^2)^2, y' = 2(1-t^2)/(1+t^2)^2)
    let (code, recs, _) = run(
        &["eval", "--derivative", "1", "--param", "0", "--param", "1"],
        QUARTER.as_bytes(),
    );
    assert_eq!(code, 0);
    let want = [[0.0, 2.0], [-1.0, 0.0]];
    for (r, w) in recs.iter().zip(want) {
        assert_eq!(r["derivative"], 1);
        let (lo, hi) = (floats(&r["lo"]), floats(&r["hi"]));
        for j in 0..2 {
            assert!(lo[j] <= w[j] && w[j] <= hi[j], "{r}");
        }
    }
}

#[test]
fn eval_parameter_outside_the_domain_is_an_error_record() {
    let input = format!("{QUARTER}\n{{\"degree\": 1}}\n{LINE}\n");
    let (code, recs, _) = run(
        &[
            "eval", "--param", "0.5", "--param", "1.5", "--param", "-0.5",
        ],
        input.as_bytes(),
    );
    assert_eq!(code, 1);
    // 3 params for curve 0, one error record for curve 1, 3 params for curve 2
    assert_eq!(recs.len(), 7);
    let idx: Vec<u64> = recs.iter().map(|r| r["index"].as_u64().unwrap()).collect();
    assert_eq!(idx, [0, 0, 0, 1, 2, 2, 2]);
    assert!(recs[0].get("lo").is_some());
    for r in [&recs[1], &recs[2], &recs[5], &recs[6]] {
        assert_eq!(r["error"]["kind"], "param_out_of_domain");
        assert!(r["param"].is_f64());
    }
    assert_eq!(recs[3]["error"]["kind"], "missing_field");
}

/// Many different curves, some invalid.
fn many_curves(n: usize) -> String {
    let mut s = String::new();
    for i in 0..n {
        if i % 1000 == 999 {
            s.push_str("{\"degree\": 1, \"knots\": \"oops\"}\n");
            continue;
        }
        let a = i as f64 * 0.5;
        s.push_str(&format!(
            "{{\"degree\": 2, \"knots\": [0, 0, 0, 0.5, 1, 1, 1], \"control_points\": [[{a}, 1], [2, {}], [3, -1], [{}, 0]], \"weights\": [1, {}, 1, 1]}}\n",
            -a,
            a + 1.0,
            1.0 + (i % 7) as f64
        ));
    }
    s
}

#[test]
fn threads_keep_input_order() {
    let input = many_curves(20_000); // several chunks
    let (c1, r1, _) = run(
        &["enclose", "--strategy", "hull", "--threads", "1"],
        input.as_bytes(),
    );
    let (c2, r2, _) = run(
        &["enclose", "--strategy", "hull", "--threads", "2"],
        input.as_bytes(),
    );
    assert_eq!((c1, c2), (1, 1));
    assert_eq!(r1.len(), 20_000);
    assert_eq!(r1, r2);
    for (i, r) in r2.iter().enumerate() {
        assert_eq!(r["index"], i);
        assert_eq!(r.get("error").is_some(), i % 1000 == 999);
        if i % 1000 != 999 {
            assert_eq!(f(&r["lo"][0]), (i as f64 * 0.5).min(2.0));
        }
    }
}

#[test]
fn large_json_array_is_streamed() {
    let lines = many_curves(30_000);
    let array = format!("[{}]", lines.trim_end().replace('\n', ",\n"));
    let (code, recs, _) = run(
        &["enclose", "--strategy", "hull", "--threads", "2"],
        array.as_bytes(),
    );
    assert_eq!(code, 1);
    assert_eq!(recs.len(), 30_000);
    for (i, r) in recs.iter().enumerate() {
        assert_eq!(r["index"], i);
    }
    let (_, from_lines, _) = run(&["enclose", "--strategy", "hull"], lines.as_bytes());
    for (a, b) in recs.iter().zip(&from_lines) {
        assert_eq!(a.get("hi"), b.get("hi"));
    }
}

#[test]
fn input_file_argument() {
    let dir = std::env::temp_dir().join(format!("nurbs-box-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("curves.json");
    std::fs::write(&path, format!("[{LINE}, {QUARTER}]")).unwrap();
    let (code, recs, _) = run(
        &["enclose", "--strategy", "hull", path.to_str().unwrap()],
        b"",
    );
    std::fs::remove_dir_all(&dir).unwrap();
    assert_eq!((code, recs.len()), (0, 2));
}

// ---- `interpolate` and `font` ----

#[test]
fn interpolate_pipes_into_enclose() {
    let input = b"[[0,0],[1,2],[3,1],[4,4]]\n[[0,0,0],[1,0,1],[2,1,0]]\n";
    for param in ["uniform", "chordal", "centripetal", "foley"] {
        let (code, curves, err) = run(&["interpolate", "--param", param], input);
        if param == "foley" {
            // the 3-D set cannot use Foley's rule: an error record with its index on stderr
            assert_eq!(code, 1);
            let e: Value = serde_json::from_str(err.trim()).unwrap();
            assert_eq!(e["index"], 1);
            assert_eq!(e["error"]["kind"], "foley_needs_2d");
            assert_eq!(curves.len(), 1);
            continue;
        }
        assert_eq!(code, 0, "{err}");
        assert_eq!(curves.len(), 2);
        let text: String = curves.iter().map(|c| format!("{c}\n")).collect();
        let (code, b, err) = run(&["enclose", "--strategy", "bezier"], text.as_bytes());
        assert_eq!(code, 0, "{err}");
        assert_eq!(b.len(), 2);
        // the interpolant passes through the data, so its box contains every data point
        let lo: Vec<f64> = serde_json::from_value(b[0]["lo"].clone()).unwrap();
        let hi: Vec<f64> = serde_json::from_value(b[0]["hi"].clone()).unwrap();
        assert!(lo[0] <= 0.0 && lo[1] <= 0.0 && hi[0] >= 4.0 && hi[1] >= 4.0);
    }
    let (code, _, err) = run(&["interpolate", "--param", "bogus"], b"");
    assert_eq!(code, 2);
    assert!(err.contains("uniform"), "{err}");
    let (code, _, _) = run(&["interpolate", "/nonexistent/points.json"], b"");
    assert_eq!(code, 2);
}

#[test]
fn font_writes_one_record_per_glyph() {
    let font = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/Inconsolata.otf");
    let (code, r, err) = run(&["font", font, "--strategy", "bezier"], b"");
    assert_eq!(code, 0, "{err}");
    assert!(r.len() > 100);
    assert!(r
        .iter()
        .all(|g| g["verified"] == true && g["stored_bbox"].is_null()));
    let (code, _, err) = run(&["font", env!("CARGO_MANIFEST_DIR")], b"");
    assert_eq!(code, 2, "{err}");
}
