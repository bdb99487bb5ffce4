//! Error positions: where in the record an error is (byte offset, line and column) and which
//! field it is in (`knots[3]`), found by scanning the record's JSON structure.

use super::error::{shorten, InputError, Position};
use super::parse::DataErr;
use super::scan::{Lexeme, Lexer};

/// Byte offset of serde_json's (line, column) in `bytes` (column = bytes since the line start).
fn offset_of(bytes: &[u8], line: usize, column: usize) -> usize {
    let mut start = 0;
    if line > 1 {
        if let Some((i, _)) = bytes
            .iter()
            .enumerate()
            .filter(|(_, &b)| b == b'\n')
            .nth(line - 2)
        {
            start = i + 1;
        }
    }
    (start + column).min(bytes.len())
}

/// Absolute position of byte `off` of a record starting at `start`.
fn abs_position(bytes: &[u8], start: Position, off: usize) -> Position {
    let before = &bytes[..off.min(bytes.len())];
    match before.iter().rposition(|&b| b == b'\n') {
        None => Position {
            line: start.line,
            column: start.column + off as u64,
        },
        Some(nl) => Position {
            line: start.line + before.iter().filter(|&&b| b == b'\n').count() as u64,
            column: (off - nl) as u64,
        },
    }
}

/// Field path (`knots[3]`, `control_points[1][0]`, `curve`) of byte `off`, found by scanning the
/// JSON structure before it (strings and escapes tracked by the shared [`Lexer`]; no recursion,
/// any depth).
fn path_at(bytes: &[u8], off: usize) -> String {
    enum Frame {
        Obj {
            key: Option<(usize, usize)>,
            in_value: bool,
        },
        Arr {
            index: usize,
        },
    }
    let mut stack: Vec<Frame> = Vec::new();
    let (mut lexer, mut str_start) = (Lexer::default(), 0);
    for (i, &b) in bytes[..off.min(bytes.len())].iter().enumerate() {
        let b = match lexer.step(b) {
            Lexeme::Open => {
                str_start = i + 1;
                continue;
            }
            Lexeme::InString => continue,
            Lexeme::Close => {
                if let Some(Frame::Obj {
                    key,
                    in_value: false,
                }) = stack.last_mut()
                {
                    *key = Some((str_start, i));
                }
                continue;
            }
            Lexeme::Code(b) => b,
        };
        match b {
            b'{' => stack.push(Frame::Obj {
                key: None,
                in_value: false,
            }),
            b'[' => stack.push(Frame::Arr { index: 0 }),
            b'}' | b']' => {
                stack.pop();
            }
            b':' => {
                if let Some(Frame::Obj { in_value, .. }) = stack.last_mut() {
                    *in_value = true;
                }
            }
            b',' => match stack.last_mut() {
                Some(Frame::Arr { index }) => *index += 1,
                Some(Frame::Obj { key, in_value }) => {
                    *key = None;
                    *in_value = false;
                }
                None => {}
            },
            _ => {}
        }
    }
    let mut path = String::new();
    for (depth, f) in stack.iter().enumerate() {
        if depth == 8 {
            path.push_str("...");
            break;
        }
        match f {
            Frame::Obj {
                key: Some((a, b)), ..
            } => {
                if depth > 0 {
                    path.push('.');
                }
                path.push_str(&shorten(&String::from_utf8_lossy(&bytes[*a..*b]), 40));
            }
            Frame::Obj { .. } => break,
            Frame::Arr { index } => {
                if depth == 0 {
                    path.push_str("curve");
                }
                path.push_str(&format!("[{index}]"));
            }
        }
    }
    if path.is_empty() {
        path.push_str("curve");
    }
    path
}

/// The token around byte `i` made of bytes satisfying `f`.
fn token_at(bytes: &[u8], i: usize, f: impl Fn(u8) -> bool) -> &[u8] {
    if i >= bytes.len() || !f(bytes[i]) {
        return &[];
    }
    let a = bytes[..i].iter().rposition(|&b| !f(b)).map_or(0, |k| k + 1);
    let b = bytes[i..]
        .iter()
        .position(|&b| !f(b))
        .map_or(bytes.len(), |k| i + k);
    &bytes[a..b]
}

/// What byte `i` is, for messages.
fn describe_byte(bytes: &[u8], i: usize) -> String {
    match bytes.get(i) {
        None => "the end of the input".into(),
        Some(&b) if b.is_ascii_graphic() => format!("'{}'", b as char),
        Some(&b) => format!("the byte 0x{b:02x}"),
    }
}

/// Turn a serde_json error (plus the visitor's structured error, if any) into an [`InputError`].
pub(super) fn convert_error(
    bytes: &[u8],
    start: Position,
    e: &serde_json::Error,
    data: Option<DataErr>,
) -> InputError {
    use serde_json::error::Category;
    // serde_json's column is the byte count from the line start to the index just after the
    // offending byte (see its `position_of_index`), so the culprit is at offset - 1.
    let off = offset_of(bytes, e.line(), e.column());
    let culprit = off.saturating_sub(1);
    let at = abs_position(bytes, start, culprit);
    if let Some(d) = data {
        return match d {
            DataErr::WrongType {
                path,
                expected,
                got,
            } => InputError::WrongType {
                path,
                at,
                expected,
                got,
            },
            DataErr::Missing(field) => InputError::MissingField { field, at },
            DataErr::Unknown(field) => InputError::UnknownField { field, at },
            DataErr::Duplicate(field) => InputError::DuplicateField { field, at },
            DataErr::Degree(field, got) => InputError::InvalidDegree { field, got, at },
            DataErr::MissingSurface(field) => InputError::MissingSurfaceField { field, at },
            DataErr::Mixed(field, kind) => InputError::MixedFields { field, kind, at },
        };
    }
    let msg = e.to_string();
    let detail = msg
        .strip_suffix(&format!(" at line {} column {}", e.line(), e.column()))
        .unwrap_or(&msg)
        .to_string();
    if e.classify() == Category::Eof {
        return InputError::Truncated {
            path: path_at(bytes, bytes.len()),
            at: abs_position(bytes, start, bytes.len()),
        };
    }
    let path = path_at(bytes, culprit);
    if detail.starts_with("number out of range") {
        let lit = token_at(bytes, culprit, |b| {
            b.is_ascii_digit() || matches!(b, b'e' | b'E' | b'+' | b'-' | b'.')
        });
        return InputError::NumberOutOfRange {
            path,
            at,
            literal: shorten(&String::from_utf8_lossy(lit), 40),
        };
    }
    let word = token_at(bytes, culprit, |b| {
        b.is_ascii_alphanumeric() || matches!(b, b'+' | b'-' | b'.')
    });
    let bare = String::from_utf8_lossy(word).to_ascii_lowercase();
    let bare = bare.trim_start_matches(['+', '-']);
    if matches!(bare, "nan" | "inf" | "infinity") {
        return InputError::NonFiniteLiteral {
            path,
            at,
            token: shorten(&String::from_utf8_lossy(word), 40),
        };
    }
    InputError::Syntax {
        path,
        at,
        detail: format!("{detail}, found {}", describe_byte(bytes, culprit)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::io::{parse_curve_at, ParseOptions};

    #[test]
    fn positions_are_absolute() {
        let input =
            "{\"degree\": 1,\n \"knots\": [0, 0, \"a\", 1], \"control_points\": [[0], [1]]}";
        let e = parse_curve_at(
            input.as_bytes(),
            Position { line: 7, column: 3 },
            &ParseOptions::default(),
        )
        .unwrap_err();
        assert!(
            matches!(
                e,
                InputError::WrongType {
                    at: Position {
                        line: 8,
                        column: 20
                    },
                    ..
                }
            ),
            "{e:?}"
        );
        let e = parse_curve_at(
            br#"{"degree": 1, "knots": [NaN]}"#,
            Position { line: 2, column: 5 },
            &ParseOptions::default(),
        )
        .unwrap_err();
        // NaN starts at byte 24 of the record, i.e. column 5 + 24
        assert!(
            matches!(
                e,
                InputError::NonFiniteLiteral {
                    at: Position {
                        line: 2,
                        column: 29
                    },
                    ..
                }
            ),
            "{e:?}"
        );
    }
}
