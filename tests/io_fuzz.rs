//! The parser and stream reader never panic, whatever the bytes; valid curves round-trip
//! through `curve_to_json` bit for bit; both stream forms give the same curves.

use nurbs_box::io::{curve_to_json, parse_curve, read_curves, CurveReader};
use nurbs_box::testkit::gen;
use nurbs_box::NurbsCurve;
use proptest::prelude::*;
use std::io::Read;

/// JSON-ish fragments: structure, numbers (also hostile ones), field names, junk.
fn token() -> impl Strategy<Value = String> {
    prop_oneof![
        prop::sample::select(vec![
            "{",
            "}",
            "[",
            "]",
            ",",
            ":",
            "\"",
            "\\",
            " ",
            "\n",
            "null",
            "true",
            "-",
            "e",
            ".",
            "NaN",
            "Infinity",
            "-Infinity",
            "1e400",
            "-1e999",
            "1e-400",
            "\"degree\"",
            "\"knots\"",
            "\"control_points\"",
            "\"weights\"",
            "\"x\"",
            "\"\\u0000\"",
            "\"\\uD800\"",
            "0",
            "1",
            "2",
            "3",
            "0.5",
            "-1",
            "1000000000",
            "18446744073709551616",
            "\u{feff}",
            "\u{1F600}",
        ])
        .prop_map(String::from),
        any::<f64>().prop_map(|x| format!("{x:?}")),
        any::<i64>().prop_map(|x| x.to_string()),
    ]
}

fn jsonish() -> impl Strategy<Value = String> {
    prop::collection::vec(token(), 0..60).prop_map(|v| v.concat())
}

/// A valid curve from the crate's generator of nasty cases (all families, any seed).
fn curve() -> impl Strategy<Value = NurbsCurve> {
    any::<u64>().prop_map(|seed| gen::nasty_curve(&mut gen::rng(seed)).1)
}

/// Reads in pieces of the given sizes (to move buffer boundaries around).
struct Pieces<'a> {
    data: &'a [u8],
    sizes: Vec<usize>,
    k: usize,
}

impl Read for Pieces<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let want = self.sizes[self.k % self.sizes.len()].max(1);
        self.k += 1;
        let n = want.min(buf.len()).min(self.data.len());
        buf[..n].copy_from_slice(&self.data[..n]);
        self.data = &self.data[n..];
        Ok(n)
    }
}

proptest! {
    #[test]
    fn arbitrary_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        let _ = parse_curve(&bytes);
        let all = read_curves(&bytes);
        for (i, (idx, _)) in all.iter().enumerate() {
            prop_assert_eq!(i, *idx);
        }
        // the array form as well
        let mut arr = b"[".to_vec();
        arr.extend_from_slice(&bytes);
        let _ = read_curves(&arr);
    }

    #[test]
    fn jsonish_text_never_panics(text in jsonish(), sizes in prop::collection::vec(1usize..9, 1..4)) {
        if let Err(e) = parse_curve(text.as_bytes()) {
            prop_assert!(!e.kind().is_empty());
            prop_assert!(!e.to_string().is_empty());
        }
        let whole = read_curves(text.as_bytes());
        let pieces: Vec<_> = CurveReader::new(Pieces { data: text.as_bytes(), sizes, k: 0 }).collect();
        prop_assert_eq!(whole, pieces);
    }

    #[test]
    fn damaged_curves_never_panic(c in curve(), cut in any::<prop::sample::Index>(),
                                  junk in token(), del in 0usize..6) {
        let s = curve_to_json(&c);
        let i = cut.index(s.len() + 1);
        let damaged = format!("{}{}{}", &s[..i], junk, &s[(i + del).min(s.len())..]);
        let _ = parse_curve(damaged.as_bytes());
        let _ = read_curves(format!("[{damaged}, {s}]").as_bytes());
        let truncated = &s[..i];
        if i < s.len() {
            prop_assert!(parse_curve(truncated.as_bytes()).is_err());
        }
    }

    #[test]
    fn curves_round_trip_bit_for_bit(c in curve()) {
        let back = parse_curve(curve_to_json(&c).as_bytes()).unwrap();
        prop_assert_eq!(back.knots().iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
                        c.knots().iter().map(|x| x.to_bits()).collect::<Vec<_>>());
        prop_assert_eq!(back, c);
    }

    #[test]
    fn both_stream_forms_agree(cs in prop::collection::vec(curve(), 0..6), bad in 0usize..7) {
        let mut items: Vec<String> = cs.iter().map(curve_to_json).collect();
        if bad < items.len() {
            items[bad] = "{\"degree\": [\"x\"]}".into();
        }
        let lines = read_curves(items.join("\n").as_bytes());
        let array = read_curves(format!("[{}]", items.join(" ,\n")).as_bytes());
        prop_assert_eq!(lines.len(), items.len());
        prop_assert_eq!(array.len(), items.len());
        for ((i, a), (j, b)) in lines.iter().zip(&array) {
            prop_assert_eq!(i, j);
            match (a, b) {
                (Ok(x), Ok(y)) => prop_assert_eq!(x, y),
                (Err(x), Err(y)) => prop_assert_eq!(x.kind(), y.kind()),
                _ => prop_assert!(false, "forms disagree at {}", i),
            }
        }
    }
}
