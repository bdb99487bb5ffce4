//! The lexical layer shared by the two byte scanners of `io`: `position::path_at` (the field
//! path of an error) and `RecordReader::scan_element` (cutting an array of curves into
//! elements).
//!
//! Both must know which bytes are inside a JSON string, so that a `"]"` or `"{"` in a string
//! is not taken for structure; that is the whole of what they share. What each does with the
//! structural bytes differs on purpose and stays with it: `path_at` keeps a stack of frames
//! (object key, array index) over a finished record, `scan_element` keeps a bracket count over
//! a stream read in pieces, stops at a `,` or `]` at depth 0 and leaves a stray `}` to the
//! parser. The lexer keeps its state between calls, so a string may span read buffers.
//!
//! It is deliberately lenient: it never fails, whatever the bytes (invalid UTF-8, control
//! characters, bad escapes); the parser reports those. A backslash escapes exactly the next
//! byte, which is all that matters for finding the closing quote (`\uXXXX` has no quote in it).

/// What one byte is, lexically (see [`Lexer::step`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Lexeme {
    /// The opening quote of a string.
    Open,
    /// A byte inside a string, escapes and backslashes included.
    InString,
    /// The closing quote of a string.
    Close,
    /// A byte outside strings (structure, whitespace, a literal or anything else).
    Code(u8),
}

/// Whether the scan is inside a JSON string, and just after a backslash in it.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(super) struct Lexer {
    in_str: bool,
    esc: bool,
}

impl Lexer {
    /// Classify the next byte `b` and advance.
    #[inline]
    pub(super) fn step(&mut self, b: u8) -> Lexeme {
        if self.in_str {
            if self.esc {
                self.esc = false;
            } else if b == b'\\' {
                self.esc = true;
            } else if b == b'"' {
                self.in_str = false;
                return Lexeme::Close;
            }
            Lexeme::InString
        } else if b == b'"' {
            self.in_str = true;
            Lexeme::Open
        } else {
            Lexeme::Code(b)
        }
    }

    /// Inside a string (the input ended there if the scan stops now).
    pub(super) fn in_string(&self) -> bool {
        self.in_str
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lex(s: &[u8]) -> Vec<Lexeme> {
        let mut l = Lexer::default();
        s.iter().map(|&b| l.step(b)).collect()
    }

    #[test]
    fn strings_and_escapes() {
        use Lexeme::*;
        assert_eq!(
            lex(br#"["a\"]",{"#),
            [
                Code(b'['),
                Open,
                InString,
                InString,
                InString,
                InString,
                Close,
                Code(b','),
                Code(b'{')
            ]
        );
        // an escaped backslash does not escape the quote after it
        assert_eq!(lex(br#""\\"x"#)[3..], [Close, Code(b'x')]);
        // state carries over between pieces
        let mut l = Lexer::default();
        for &b in br#""ab\"# {
            l.step(b);
        }
        assert!(l.in_string());
        assert_eq!(l.step(b'"'), Lexeme::InString);
        assert_eq!(l.step(b'"'), Lexeme::Close);
        assert!(!l.in_string());
        // any byte is accepted
        assert_eq!(
            lex(b"\xff\x00\"\xff"),
            [Code(0xff), Code(0), Open, InString]
        );
    }
}
