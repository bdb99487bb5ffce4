//! The `interpolate` and `font` subcommands of the binary: output parses as curves / glyph
//! records, errors keep their index, exit statuses follow `shared/formats.md`.

use serde_json::Value;
use std::io::Write;
use std::process::{Command, Stdio};

const BIN: &str = env!("CARGO_BIN_EXE_nurbs-box");

fn run(args: &[&str], stdin: &[u8]) -> (i32, String, String) {
    let mut child = Command::new(BIN)
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
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!stderr.contains("panicked"), "{stderr}");
    (
        out.status.code().unwrap(),
        String::from_utf8(out.stdout).unwrap(),
        stderr,
    )
}

fn records(s: &str) -> Vec<Value> {
    s.lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

#[test]
fn interpolate_pipes_into_enclose() {
    let input = b"[[0,0],[1,2],[3,1],[4,4]]\n[[0,0,0],[1,0,1],[2,1,0]]\n";
    for param in ["uniform", "chordal", "centripetal", "foley"] {
        let (code, out, err) = run(&["interpolate", "--param", param], input);
        if param == "foley" {
            // the 3-D set cannot use Foley's rule: an error record with its index on stderr
            assert_eq!(code, 1);
            let e = records(&err);
            assert_eq!(e[0]["index"], 1);
            assert_eq!(e[0]["error"]["kind"], "foley_needs_2d");
            assert_eq!(out.lines().count(), 1);
            continue;
        }
        assert_eq!(code, 0, "{err}");
        assert_eq!(out.lines().count(), 2);
        let (code, boxes, err) = run(&["enclose", "--strategy", "bezier"], out.as_bytes());
        assert_eq!(code, 0, "{err}");
        let b = records(&boxes);
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
    let (code, out, err) = run(&["font", font, "--strategy", "bezier"], b"");
    assert_eq!(code, 0, "{err}");
    let r = records(&out);
    assert!(r.len() > 100);
    assert!(r
        .iter()
        .all(|g| g["verified"] == true && g["stored_bbox"].is_null()));
    let (code, _, err) = run(&["font", env!("CARGO_MANIFEST_DIR")], b"");
    assert_eq!(code, 2, "{err}");
}
