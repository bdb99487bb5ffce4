//! Stream splitting: [`RecordReader`] cuts a stream (JSON Lines, or one JSON array of curves)
//! into the raw bytes of one curve each, in bounded memory; [`CurveReader`] also parses them.

use super::error::{InputError, Position};
use super::parse::{parse_curve_at, parse_record_at, ParseOptions, Shape};
use super::scan::{Lexeme, Lexer};
use crate::spline::curve::NurbsCurve;
use std::io::{self, BufRead, BufReader, Read};

/// The two stream forms of `docs/formats.md`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StreamForm {
    /// one curve per line (blank lines skipped)
    JsonLines,
    /// one JSON array of curves
    Array,
}

/// The raw bytes of one input record (one curve), with its index and start position.
#[derive(Debug, Clone, PartialEq)]
pub struct RawRecord {
    /// curve index, from 0, in input order
    pub index: usize,
    /// where the record starts in the input
    pub start: Position,
    /// the record's bytes, or why there are none (too large, empty array element, ...)
    pub bytes: Result<Vec<u8>, InputError>,
}

impl RawRecord {
    /// Parse and validate the record.
    pub fn parse(&self, opts: &ParseOptions) -> Result<NurbsCurve, InputError> {
        match &self.bytes {
            Ok(b) => parse_curve_at(b, self.start, opts),
            Err(e) => Err(e.clone()),
        }
    }

    /// Parse and validate the record as a curve or a surface (mixed streams).
    pub fn parse_shape(&self, opts: &ParseOptions) -> Result<Shape, InputError> {
        match &self.bytes {
            Ok(b) => parse_record_at(b, self.start, opts),
            Err(e) => Err(e.clone()),
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mode {
    Start,
    Lines,
    /// inside the array; `need_sep`: an element was just read
    Array {
        need_sep: bool,
        after_comma: bool,
    },
    /// after the closing bracket
    Closed,
    Done,
}

fn is_ws(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\n' | b'\r')
}

/// Splits an input stream into [`RawRecord`]s, one per curve, in bounded memory (one record
/// plus the read buffer).
///
/// The form is chosen by the first non-whitespace byte (a UTF-8 byte-order mark is skipped):
/// `[` starts a JSON array of curves, anything else is JSON Lines. In the array form the
/// elements are cut out by a small scanner that tracks strings, escapes and bracket depth, and
/// each element is parsed on its own, so millions of curves stream through.
///
/// A read error ends the stream with one record whose error is [`InputError::Io`].
pub struct RecordReader<R> {
    inner: BufReader<R>,
    mode: Mode,
    next_index: usize,
    /// position of the next unread byte
    pos: Position,
    consumed: u64,
    max_record: usize,
}

impl<R: Read> RecordReader<R> {
    /// A reader with the default record size limit.
    pub fn new(r: R) -> Self {
        Self::with_options(r, &ParseOptions::default())
    }

    /// A reader with the record size limit of `opts`.
    pub fn with_options(r: R, opts: &ParseOptions) -> Self {
        RecordReader {
            inner: BufReader::with_capacity(1 << 18, r),
            mode: Mode::Start,
            next_index: 0,
            pos: Position { line: 1, column: 1 },
            consumed: 0,
            max_record: opts.max_record_bytes,
        }
    }

    /// Bytes consumed so far (for progress reports).
    pub fn bytes_read(&self) -> u64 {
        self.consumed
    }

    /// The stream form, once the first record has been requested.
    pub fn form(&self) -> Option<StreamForm> {
        match self.mode {
            Mode::Start => None,
            Mode::Lines => Some(StreamForm::JsonLines),
            Mode::Array { .. } | Mode::Closed => Some(StreamForm::Array),
            Mode::Done => None,
        }
    }

    /// Consume `n` buffered bytes (`seen` are those bytes), keeping the position.
    fn advance(&mut self, n: usize) {
        let buf = self.inner.buffer();
        let seen = &buf[..n];
        match seen.iter().rposition(|&b| b == b'\n') {
            None => self.pos.column += n as u64,
            Some(k) => {
                self.pos.line += seen.iter().filter(|&&b| b == b'\n').count() as u64;
                self.pos.column = (n - k) as u64;
            }
        }
        self.consumed += n as u64;
        self.inner.consume(n);
    }

    /// Fill the buffer; `Ok(false)` at end of input. Interrupted reads are retried.
    fn fill(&mut self) -> io::Result<bool> {
        loop {
            match self.inner.fill_buf() {
                Ok(b) => return Ok(!b.is_empty()),
                Err(e) if e.kind() == io::ErrorKind::Interrupted => continue,
                Err(e) => return Err(e),
            }
        }
    }

    /// Skip whitespace; the next byte, or `None` at end of input.
    fn skip_ws(&mut self) -> io::Result<Option<u8>> {
        loop {
            if !self.fill()? {
                return Ok(None);
            }
            let buf = self.inner.buffer();
            match buf.iter().position(|&b| !is_ws(b)) {
                Some(k) => {
                    let b = buf[k];
                    self.advance(k);
                    return Ok(Some(b));
                }
                None => {
                    let n = buf.len();
                    self.advance(n);
                }
            }
        }
    }

    fn record(&mut self, start: Position, bytes: Result<Vec<u8>, InputError>) -> RawRecord {
        let index = self.next_index;
        self.next_index += 1;
        RawRecord {
            index,
            start,
            bytes,
        }
    }

    /// One line (without the newline), bounded; `None` at end of input.
    fn read_line(&mut self) -> io::Result<Option<(Position, Vec<u8>, bool)>> {
        let start = self.pos;
        let (mut line, mut too_long, mut any) = (Vec::new(), false, false);
        while self.fill()? {
            any = true;
            let buf = self.inner.buffer();
            let (n, done) = match buf.iter().position(|&b| b == b'\n') {
                Some(k) => (k, true),
                None => (buf.len(), false),
            };
            if line.len() + n > self.max_record {
                too_long = true;
                line = Vec::new();
            } else if !too_long {
                line.extend_from_slice(&buf[..n]);
            }
            self.advance(n + done as usize);
            if done {
                break;
            }
        }
        Ok(any.then_some((start, line, too_long)))
    }

    fn next_line_record(&mut self) -> io::Result<Option<RawRecord>> {
        loop {
            let Some((start, line, too_long)) = self.read_line()? else {
                self.mode = Mode::Done;
                return Ok(None);
            };
            if too_long {
                let limit = self.max_record;
                return Ok(Some(
                    self.record(start, Err(InputError::TooLarge { limit, at: start })),
                ));
            }
            let Some(a) = line.iter().position(|&b| !is_ws(b)) else {
                continue; // blank line
            };
            let b = line.iter().rposition(|&b| !is_ws(b)).map_or(a, |k| k + 1);
            let start = Position {
                line: start.line,
                column: start.column + a as u64,
            };
            return Ok(Some(self.record(start, Ok(line[a..b].to_vec()))));
        }
    }

    /// Cut out one array element: bytes up to a ',' or ']' at bracket depth 0 outside strings
    /// (not consumed). Returns (bytes, too_long, cut short: the input ended inside a string or
    /// an open bracket, or `None` if the element ended normally or at a balanced end of input).
    fn scan_element(&mut self) -> io::Result<(Vec<u8>, bool, Option<bool>)> {
        let (mut depth, mut lexer) = (0u64, Lexer::default());
        let (mut out, mut too_long) = (Vec::new(), false);
        loop {
            if !self.fill()? {
                return Ok((out, too_long, Some(lexer.in_string() || depth > 0)));
            }
            let buf = self.inner.buffer();
            let mut end = None;
            for (i, &b) in buf.iter().enumerate() {
                let Lexeme::Code(b) = lexer.step(b) else {
                    continue; // a string, its quotes included
                };
                match b {
                    b'[' | b'{' => depth += 1,
                    b']' if depth == 0 => {
                        end = Some(i);
                        break;
                    }
                    b',' if depth == 0 => {
                        end = Some(i);
                        break;
                    }
                    // a '}' at depth 0 is left in the element for the parser to report
                    b']' | b'}' => depth = depth.saturating_sub(1),
                    _ => {}
                }
            }
            let n = end.unwrap_or(buf.len());
            if out.len() + n > self.max_record {
                too_long = true;
                out = Vec::new();
            } else if !too_long {
                out.extend_from_slice(&buf[..n]);
            }
            self.advance(n);
            if end.is_some() {
                return Ok((out, too_long, None));
            }
        }
    }

    fn next_array_record(
        &mut self,
        mut need_sep: bool,
        mut after_comma: bool,
    ) -> io::Result<Option<RawRecord>> {
        loop {
            match self.skip_ws()? {
                None => {
                    self.mode = Mode::Done;
                    let at = self.pos;
                    return Ok(Some(self.record(at, Err(InputError::UnclosedArray { at }))));
                }
                Some(b']') => {
                    let at = self.pos;
                    self.advance(1);
                    if after_comma {
                        // `[..., ]`: report the trailing comma, then check what follows
                        self.mode = Mode::Closed;
                        return Ok(Some(self.record(at, Err(InputError::EmptyElement { at }))));
                    }
                    return self.next_closed();
                }
                Some(b',') if need_sep => {
                    self.advance(1);
                    need_sep = false;
                    after_comma = true;
                }
                Some(b',') => {
                    // `[,` or `,,`: an empty element
                    let at = self.pos;
                    self.advance(1);
                    self.mode = Mode::Array {
                        need_sep: false,
                        after_comma: true,
                    };
                    return Ok(Some(self.record(at, Err(InputError::EmptyElement { at }))));
                }
                Some(_) => {
                    let start = self.pos;
                    let (mut bytes, too_long, eof) = self.scan_element()?;
                    // After a truncated element nothing more is reported (no second error
                    // for the missing ']'); after a complete last element the next call
                    // reports the unclosed array.
                    self.mode = if eof == Some(true) {
                        Mode::Done
                    } else {
                        Mode::Array {
                            need_sep: true,
                            after_comma: false,
                        }
                    };
                    if too_long {
                        let limit = self.max_record;
                        let e = InputError::TooLarge { limit, at: start };
                        return Ok(Some(self.record(start, Err(e))));
                    }
                    while bytes.last().is_some_and(|&b| is_ws(b)) {
                        bytes.pop();
                    }
                    return Ok(Some(self.record(start, Ok(bytes))));
                }
            }
        }
    }

    /// After the closing bracket: only whitespace may follow.
    fn next_closed(&mut self) -> io::Result<Option<RawRecord>> {
        self.mode = Mode::Done;
        match self.skip_ws()? {
            None => Ok(None),
            Some(_) => {
                let at = self.pos;
                Ok(Some(self.record(at, Err(InputError::TrailingData { at }))))
            }
        }
    }

    fn next_record(&mut self) -> io::Result<Option<RawRecord>> {
        match self.mode {
            Mode::Done => Ok(None),
            Mode::Start => {
                // Skip a UTF-8 byte-order mark, byte by byte (reads may be short); a partial one
                // is dropped too, the rest of the record is invalid anyway.
                for bom in [0xEF, 0xBB, 0xBF] {
                    if !(self.fill()? && self.inner.buffer()[0] == bom) {
                        break;
                    }
                    self.consumed += 1;
                    self.inner.consume(1);
                }
                match self.skip_ws()? {
                    Some(b'[') => {
                        self.advance(1);
                        self.mode = Mode::Array {
                            need_sep: false,
                            after_comma: false,
                        };
                    }
                    Some(_) => self.mode = Mode::Lines,
                    None => {
                        self.mode = Mode::Done;
                        return Ok(None);
                    }
                }
                self.next_record()
            }
            Mode::Lines => self.next_line_record(),
            Mode::Array {
                need_sep,
                after_comma,
            } => self.next_array_record(need_sep, after_comma),
            Mode::Closed => self.next_closed(),
        }
    }
}

impl<R: Read> Iterator for RecordReader<R> {
    type Item = RawRecord;
    fn next(&mut self) -> Option<RawRecord> {
        match self.next_record() {
            Ok(r) => r,
            Err(e) => {
                self.mode = Mode::Done;
                let at = self.pos;
                Some(self.record(at, Err(InputError::Io(e.to_string()))))
            }
        }
    }
}

/// Parsed curves of a stream: `(index, curve or error)` in input order (see [`RecordReader`]).
pub struct CurveReader<R> {
    records: RecordReader<R>,
    opts: ParseOptions,
}

impl<R: Read> CurveReader<R> {
    /// Read curves from `r` with default options.
    pub fn new(r: R) -> Self {
        Self::with_options(r, ParseOptions::default())
    }
    /// Read curves from `r`.
    pub fn with_options(r: R, opts: ParseOptions) -> Self {
        CurveReader {
            records: RecordReader::with_options(r, &opts),
            opts,
        }
    }
}

impl<R: Read> Iterator for CurveReader<R> {
    type Item = (usize, Result<NurbsCurve, InputError>);
    fn next(&mut self) -> Option<Self::Item> {
        let r = self.records.next()?;
        Some((r.index, r.parse(&self.opts)))
    }
}

/// Read every curve of a byte slice (either stream form).
pub fn read_curves(bytes: &[u8]) -> Vec<(usize, Result<NurbsCurve, InputError>)> {
    CurveReader::new(bytes).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reads at most `n` bytes per call, to exercise buffer boundaries.
    struct Trickle<'a>(&'a [u8], usize);
    impl Read for Trickle<'_> {
        fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
            let n = self.1.min(buf.len()).min(self.0.len());
            buf[..n].copy_from_slice(&self.0[..n]);
            self.0 = &self.0[n..];
            Ok(n)
        }
    }

    fn kinds(input: &[u8]) -> Vec<String> {
        let all: Vec<_> = read_curves(input);
        let trickled: Vec<_> = CurveReader::new(Trickle(input, 1)).collect();
        assert_eq!(all, trickled, "byte-by-byte reading differs");
        all.iter()
            .enumerate()
            .map(|(i, (idx, r))| {
                assert_eq!(i, *idx);
                match r {
                    Ok(_) => "ok".to_string(),
                    Err(e) => e.kind().to_string(),
                }
            })
            .collect()
    }

    const C1: &str = r#"{"degree":1,"knots":[0,0,1,1],"control_points":[[0],[1]]}"#;

    #[test]
    fn json_lines_stream() {
        let input = format!("\n{C1}\n  \n\r\n{{\"degree\": 1}}\n  {C1}  \r\nnot json\n{C1}");
        assert_eq!(
            kinds(input.as_bytes()),
            ["ok", "missing_field", "ok", "invalid_json", "ok"]
        );
        let recs: Vec<RawRecord> = RecordReader::new(input.as_bytes()).collect();
        assert_eq!(recs[2].start, Position { line: 6, column: 3 });
        assert_eq!(recs[3].start, Position { line: 7, column: 1 });
        assert_eq!(kinds(b""), Vec::<String>::new());
        assert_eq!(kinds(b"  \n\n "), Vec::<String>::new());
        // a byte-order mark is skipped
        assert_eq!(kinds(format!("\u{feff}{C1}").as_bytes()), ["ok"]);
        // binary junk: one error per line, never a panic
        assert_eq!(
            kinds(b"\xff\xfe\x00\n\x80{\n"),
            ["invalid_json", "invalid_json"]
        );
    }

    #[test]
    fn array_stream() {
        let input = format!("[\n {C1},\n {{\"degree\": 1, \"knots\": [\"]\", \"{{\"]}},\n{C1} ]\n");
        assert_eq!(kinds(input.as_bytes()), ["ok", "wrong_type", "ok"]);
        let recs: Vec<RawRecord> = RecordReader::new(input.as_bytes()).collect();
        assert_eq!(recs[2].start, Position { line: 4, column: 1 });
        assert_eq!(kinds(b"[]"), Vec::<String>::new());
        assert_eq!(kinds(b" [ ] \n"), Vec::<String>::new());
        assert_eq!(
            kinds(format!("[{C1},,{C1}]").as_bytes()),
            ["ok", "empty_element", "ok"]
        );
        assert_eq!(
            kinds(format!("[{C1},]").as_bytes()),
            ["ok", "empty_element"]
        );
        assert_eq!(
            kinds(format!("[,{C1}]").as_bytes()),
            ["empty_element", "ok"]
        );
        assert_eq!(kinds(format!("[{C1}").as_bytes()), ["ok", "unclosed_array"]);
        assert_eq!(
            kinds(format!("[{C1},").as_bytes()),
            ["ok", "unclosed_array"]
        );
        assert_eq!(kinds(b"["), ["unclosed_array"]);
        assert_eq!(
            kinds(format!("[{C1}] x").as_bytes()),
            ["ok", "trailing_data"]
        );
        assert_eq!(
            kinds(format!("[{C1}]\n[{C1}]").as_bytes()),
            ["ok", "trailing_data"]
        );
        // a truncated element is one error, with no second one for the missing ']'
        assert_eq!(
            kinds(format!("[{C1}, {{\"degree\": 1, \"kn").as_bytes()),
            ["ok", "truncated_json"]
        );
        // escaped quotes and brackets inside strings do not end an element
        let tricky =
            r#"[{"degree":1,"knots":[0,0,1,1],"control_points":[[0],[1]],"weights":"\"],["}, 5]"#;
        assert_eq!(kinds(tricky.as_bytes()), ["wrong_type", "wrong_type"]);
        // missing comma between elements: the parser reports trailing characters
        assert_eq!(kinds(format!("[{C1} {C1}]").as_bytes()), ["invalid_json"]);
        // a '}' too many stays in its element
        assert_eq!(
            kinds(format!("[{C1}}}, {C1}]").as_bytes()),
            ["invalid_json", "ok"]
        );
        // deep nesting in the splitter: a counter, no recursion
        let deep = "[".repeat(100_000) + &"]".repeat(100_000);
        assert_eq!(kinds(deep.as_bytes()), ["wrong_type"]);
        let deep = format!("[{}]", "{\"a\":[".repeat(100_000) + &"]}".repeat(100_000));
        assert_eq!(kinds(deep.as_bytes()), ["unknown_field"]);
    }

    #[test]
    fn oversized_records_are_skipped() {
        let opts = ParseOptions {
            max_record_bytes: 80,
            ..ParseOptions::default()
        };
        let long = format!(
            "{{\"degree\":1,\"knots\":[0,0,1,1],\"control_points\":[[0],[1]],\"weights\":[{}1,1]}}",
            "1,".repeat(50)
        );
        for input in [
            format!("{C1}\n{long}\n{C1}\n"),
            format!("[{C1}, {long}, {C1}]"),
        ] {
            let k: Vec<_> = CurveReader::with_options(Trickle(input.as_bytes(), 7), opts)
                .map(|(_, r)| r.map_or_else(|e| e.kind(), |_| "ok"))
                .collect();
            assert_eq!(k, ["ok", "record_too_large", "ok"]);
        }
    }

    #[test]
    fn read_errors_end_the_stream() {
        struct Broken;
        impl Read for Broken {
            fn read(&mut self, _: &mut [u8]) -> io::Result<usize> {
                Err(io::Error::other("boom"))
            }
        }
        let v: Vec<_> = CurveReader::new(Broken).collect();
        assert_eq!(v.len(), 1);
        assert!(matches!(&v[0].1, Err(InputError::Io(m)) if m.contains("boom")));
    }
}
