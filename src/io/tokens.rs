//! A whitespace tokenizer over a text file that remembers line numbers, shared by the Medit and
//! Gmsh readers. Numbers may be split across lines; every error names the file and line.

use super::decimal::{scan_f64, scan_uint};
use crate::error::{Error, Result};
use std::path::Path;
use std::str::FromStr;

/// Reads a file as text (invalid UTF-8 bytes become U+FFFD and fail later with a line number).
pub(crate) fn read_text(path: &Path) -> Result<String> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    Ok(match String::from_utf8(bytes) {
        Ok(s) => s,
        Err(e) => String::from_utf8_lossy(e.as_bytes()).into_owned(),
    })
}

/// Whitespace-separated tokens with their 1-based line numbers.
pub(crate) struct Tokens<'a> {
    path: &'a Path,
    text: &'a str,
    pos: usize,
    line: usize,
    /// Line of the last token returned (for errors after it).
    tok_line: usize,
    comment: Option<u8>,
}

impl<'a> Tokens<'a> {
    /// Tokens of `text`; `comment` starts a comment running to the end of the line.
    pub fn new(path: &'a Path, text: &'a str, comment: Option<u8>) -> Self {
        Tokens {
            path,
            text,
            pos: 0,
            line: 1,
            tok_line: 1,
            comment,
        }
    }

    /// Line of the last token read.
    pub fn token_line(&self) -> usize {
        self.tok_line
    }

    /// A parse error at `line`.
    pub fn err_at(&self, line: usize, msg: impl Into<String>) -> Error {
        Error::parse(self.path, line, msg)
    }

    /// A parse error at the line of the last token.
    pub fn err(&self, msg: impl Into<String>) -> Error {
        self.err_at(self.tok_line, msg)
    }

    fn skip_space(&mut self) {
        let b = self.text.as_bytes();
        let mut pos = self.pos;
        while pos < b.len() {
            let c = b[pos];
            if c == b'\n' {
                self.line += 1;
                pos += 1;
            } else if c <= b' ' && c.is_ascii_whitespace() {
                pos += 1;
            } else if Some(c) == self.comment {
                while pos < b.len() && b[pos] != b'\n' {
                    pos += 1;
                }
            } else {
                break;
            }
        }
        self.pos = pos;
    }

    /// The next token and its line, or `None` at the end of the file.
    pub fn next_token(&mut self) -> Option<(&'a str, usize)> {
        self.skip_space();
        let b = self.text.as_bytes();
        if self.pos >= b.len() {
            return None;
        }
        let start = self.pos;
        // Bytes above b' ' are never whitespace: only those at or below it need the full test.
        let comment = self.comment.unwrap_or(b' ');
        let mut pos = start;
        while pos < b.len() {
            let c = b[pos];
            if (c <= b' ' && c.is_ascii_whitespace()) || c == comment {
                break;
            }
            pos += 1;
        }
        self.pos = pos;
        self.tok_line = self.line;
        // Token boundaries are ASCII bytes, so slicing is on char boundaries.
        Some((&self.text[start..self.pos], self.line))
    }

    /// The number at the next token read by `scan` straight from the text, with its length in
    /// bytes, when it takes the whole token (see [`super::decimal`]); nothing but the whitespace
    /// before it is consumed.
    #[inline]
    fn scan_next<T>(&mut self, scan: fn(&[u8]) -> Option<(T, usize)>) -> Option<(T, usize)> {
        self.skip_space();
        let b = &self.text.as_bytes()[self.pos..];
        let (v, n) = scan(b)?;
        match b.get(n) {
            Some(&c) if !((c <= b' ' && c.is_ascii_whitespace()) || Some(c) == self.comment) => {
                None
            }
            _ => Some((v, n)),
        }
    }

    /// Consumes the `n` bytes of a token found by [`Tokens::scan_next`].
    #[inline]
    fn consume(&mut self, n: usize) {
        self.pos += n;
        self.tok_line = self.line;
    }

    /// The next token without consuming it.
    pub fn peek(&mut self) -> Option<&'a str> {
        let (pos, line, last) = (self.pos, self.line, self.tok_line);
        let t = self.next_token().map(|(t, _)| t);
        self.pos = pos;
        self.line = line;
        self.tok_line = last;
        t
    }

    /// The next token, or an "unexpected end of file" error mentioning `what`.
    pub fn expect(&mut self, what: &str) -> Result<&'a str> {
        match self.next_token() {
            Some((t, _)) => Ok(t),
            None => Err(self.err(format!("unexpected end of file while reading {what}"))),
        }
    }

    /// The next token parsed as `T` (an integer type); `what` names the quantity in errors.
    pub fn int<T: FromStr + TryFrom<i64>>(&mut self, what: &str) -> Result<T> {
        self.int_with(&|| what.to_string())
    }

    /// As [`Tokens::int`], with the name built only for an error (no allocation per item).
    #[inline]
    pub fn int_with<T: FromStr + TryFrom<i64>>(&mut self, what: &dyn Fn() -> String) -> Result<T> {
        // The common case, 1 to 18 decimal digits without a sign, read straight from the text;
        // anything else (signs, out-of-range values, errors) goes through `str::parse`, with its
        // results.
        if let Some((v, n)) = self.scan_next(scan_uint) {
            if let Ok(v) = T::try_from(v) {
                self.consume(n);
                return Ok(v);
            }
        }
        self.int_token(what)
    }

    /// [`Tokens::int_with`] on the next token through `str::parse`.
    #[inline(never)]
    fn int_token<T: FromStr>(&mut self, what: &dyn Fn() -> String) -> Result<T> {
        let Some((t, _)) = self.next_token() else {
            return Err(self.err(format!("unexpected end of file while reading {}", what())));
        };
        t.parse::<T>().map_err(|_| {
            let what = what();
            if t.parse::<i128>().is_ok() {
                self.err(format!("{what}: integer '{t}' is out of range"))
            } else {
                self.err(format!(
                    "{what}: expected an integer, found '{}'",
                    shorten(t)
                ))
            }
        })
    }

    /// A non-negative count (rejects negative numbers with a clear message).
    pub fn count(&mut self, what: &str) -> Result<usize> {
        let t = self.expect(what)?;
        match t.parse::<i128>() {
            Ok(v) if v < 0 => Err(self.err(format!("{what}: negative count {v}"))),
            Ok(v) if v > u32::MAX as i128 => {
                Err(self.err(format!("{what}: count {v} is too large")))
            }
            Ok(v) => Ok(v as usize),
            Err(_) => Err(self.err(format!("{what}: expected a count, found '{}'", shorten(t)))),
        }
    }

    /// The next token as a finite `f64`.
    pub fn real(&mut self, what: &str) -> Result<f64> {
        self.real_with(&|| what.to_string())
    }

    /// As [`Tokens::real`], with the name built only for an error (no allocation per item).
    #[inline]
    pub fn real_with(&mut self, what: &dyn Fn() -> String) -> Result<f64> {
        // Plain decimals read straight from the text (exactly as `str::parse` reads them).
        if let Some((x, n)) = self.scan_next(scan_f64) {
            self.consume(n);
            return Ok(x);
        }
        self.real_token(what)
    }

    /// [`Tokens::real_with`] on the next token through `str::parse`.
    #[inline(never)]
    fn real_token(&mut self, what: &dyn Fn() -> String) -> Result<f64> {
        let Some((t, _)) = self.next_token() else {
            return Err(self.err(format!("unexpected end of file while reading {}", what())));
        };
        match t.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            Ok(_) => Err(self.err(format!(
                "{}: non-finite value '{t}' (NaN or infinity)",
                what()
            ))),
            Err(_) => Err(self.err(format!(
                "{}: expected a number, found '{}'",
                what(),
                shorten(t)
            ))),
        }
    }

    /// A double-quoted string (Gmsh physical names); returns its content.
    pub fn quoted(&mut self, what: &str) -> Result<&'a str> {
        self.skip_space();
        let b = self.text.as_bytes();
        if self.pos >= b.len() || b[self.pos] != b'"' {
            let t = self.expect(what)?;
            return Err(self.err(format!(
                "{what}: expected a quoted name, found '{}'",
                shorten(t)
            )));
        }
        self.tok_line = self.line;
        let start = self.pos + 1;
        let mut end = start;
        while end < b.len() && b[end] != b'"' && b[end] != b'\n' {
            end += 1;
        }
        if end >= b.len() || b[end] != b'"' {
            return Err(self.err(format!("{what}: unterminated quoted name")));
        }
        self.pos = end + 1;
        Ok(&self.text[start..end])
    }

    /// A cap for `Vec::with_capacity` from a count read in the file, so that a corrupt count
    /// cannot trigger a huge allocation: at most one item per two remaining bytes.
    pub fn capacity(&self, count: usize, per_item: usize) -> usize {
        count.min((self.text.len() - self.pos) / (2 * per_item.max(1)) + 1)
    }
}

/// First 40 characters of a token, for messages.
pub(crate) fn shorten(t: &str) -> String {
    if t.chars().count() > 40 {
        let s: String = t.chars().take(40).collect();
        format!("{s}...")
    } else {
        t.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_track_lines_and_comments() {
        let p = Path::new("t.mesh");
        let mut t = Tokens::new(p, "a 1 # c 2\n\n  -3.5e1\n\"x y\" z", Some(b'#'));
        assert_eq!(t.next_token(), Some(("a", 1)));
        assert_eq!(t.int::<i32>("n").unwrap(), 1);
        assert_eq!(t.real("x").unwrap(), -35.0);
        assert_eq!(t.token_line(), 3);
        assert_eq!(t.quoted("name").unwrap(), "x y");
        assert_eq!(t.peek(), Some("z"));
        assert_eq!(t.next_token(), Some(("z", 4)));
        let e = t.real("coordinate").unwrap_err().to_string();
        assert!(e.contains("t.mesh:4") && e.contains("end of file"), "{e}");
    }

    #[test]
    fn numbers_are_checked() {
        let p = Path::new("f");
        let mut t = Tokens::new(p, "-3 nan 1x 99999999999", None);
        assert!(t
            .count("n")
            .unwrap_err()
            .to_string()
            .contains("negative count -3"));
        assert!(t.real("x").unwrap_err().to_string().contains("non-finite"));
        assert!(t
            .real("x")
            .unwrap_err()
            .to_string()
            .contains("expected a number, found '1x'"));
        assert!(t
            .int::<u32>("i")
            .unwrap_err()
            .to_string()
            .contains("out of range"));
    }
}
