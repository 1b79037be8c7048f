//! A whitespace tokenizer over a text file that remembers line numbers, shared by the Medit and
//! Gmsh readers. Numbers may be split across lines; every error names the file and line.

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
    pub fn int_with<T: FromStr + TryFrom<i64>>(&mut self, what: &dyn Fn() -> String) -> Result<T> {
        let Some((t, _)) = self.next_token() else {
            return Err(self.err(format!("unexpected end of file while reading {}", what())));
        };
        // The common case, 1 to 18 decimal digits without a sign, read directly; anything else
        // (signs, out-of-range values, errors) goes through `str::parse`, with its results.
        if let Some(v) = plain_digits(t) {
            if let Ok(v) = T::try_from(v) {
                return Ok(v);
            }
        }
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
    pub fn real_with(&mut self, what: &dyn Fn() -> String) -> Result<f64> {
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

/// The value of a token of 1 to 18 ASCII digits (no sign), which fits in an `i64`; `None` for
/// any other token.
fn plain_digits(t: &str) -> Option<i64> {
    let b = t.as_bytes();
    if b.is_empty() || b.len() > 18 {
        return None;
    }
    let mut v: i64 = 0;
    for &c in b {
        let d = c.wrapping_sub(b'0');
        if d > 9 {
            return None;
        }
        v = v * 10 + i64::from(d);
    }
    Some(v)
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

/// Formats a float so that it reads back exactly (shortest round-trip form) and is accepted by C
/// `strtod`/`fscanf` (plain decimal for moderate magnitudes, exponent form otherwise).
pub(crate) fn fmt_f64(x: f64) -> String {
    let mut b = Vec::with_capacity(32);
    push_f64(&mut b, x);
    // Only ASCII digits, signs, '.' and 'e' are written.
    String::from_utf8(b).unwrap_or_default()
}

/// Appends [`fmt_f64`]'s text of `x` to `buf` without allocating per number: the shortest
/// round-trip digits (ryu), laid out as Rust's `{x}` for `1e-5 <= |x| < 1e15` and zero, and
/// as `{x:e}` otherwise: `format!`'s text, except that where two shortest digit strings are
/// equally close to `x` the last digit may differ (both read back to `x`).
pub(crate) fn push_f64(buf: &mut Vec<u8>, x: f64) {
    let a = x.abs();
    if !x.is_finite() || (1e15..1e16).contains(&a) {
        // Not written by the mesh writers (non-finite) or where ryu's layout differs: rare.
        use std::io::Write;
        let _ = if x == 0.0 || (1e-5..1e15).contains(&a) {
            write!(buf, "{x}")
        } else {
            write!(buf, "{x:e}")
        };
        return;
    }
    let mut r = ryu::Buffer::new();
    let s = r.format_finite(x).as_bytes();
    // ryu writes integral values as "3.0" and "-0.0"; Rust's Display writes "3" and "-0".
    let s = s.strip_suffix(b".0").unwrap_or(s);
    buf.extend_from_slice(s);
}

/// Appends the decimal text of an integer to `buf` (the same text as `{v}`).
pub(crate) fn push_int<I: itoa::Integer>(buf: &mut Vec<u8>, v: I) {
    buf.extend_from_slice(itoa::Buffer::new().format(v).as_bytes());
}

/// A text writer that formats numbers straight into one byte buffer and hands it to the
/// underlying writer in large blocks (no allocation per number or per line).
pub(crate) struct Out<'w> {
    w: &'w mut dyn std::io::Write,
    buf: Vec<u8>,
}

impl<'w> Out<'w> {
    const BLOCK: usize = 1 << 16;

    /// A buffered text writer over `w`.
    pub fn new(w: &'w mut dyn std::io::Write) -> Self {
        Out {
            w,
            buf: Vec::with_capacity(Self::BLOCK + 256),
        }
    }

    /// Appends text.
    pub fn text(&mut self, s: &str) {
        self.buf.extend_from_slice(s.as_bytes());
    }

    /// Appends a float in [`fmt_f64`]'s form.
    pub fn real(&mut self, x: f64) {
        push_f64(&mut self.buf, x);
    }

    /// Appends an integer.
    pub fn int<I: itoa::Integer>(&mut self, v: I) {
        push_int(&mut self.buf, v);
    }

    /// Appends integers separated by single spaces.
    pub fn ints(&mut self, vs: &[i64]) {
        for (k, &v) in vs.iter().enumerate() {
            if k > 0 {
                self.buf.push(b' ');
            }
            push_int(&mut self.buf, v);
        }
    }

    /// Ends a line, passing the buffer on once it holds a full block.
    pub fn line(&mut self) -> std::io::Result<()> {
        self.buf.push(b'\n');
        if self.buf.len() >= Self::BLOCK {
            self.w.write_all(&self.buf)?;
            self.buf.clear();
        }
        Ok(())
    }

    /// Writes what remains.
    pub fn finish(mut self) -> std::io::Result<()> {
        self.w.write_all(&self.buf)?;
        self.buf.clear();
        Ok(())
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

    #[test]
    fn floats_round_trip() {
        for x in [
            0.0,
            0.1,
            -1.0 / 3.0,
            1e-20,
            6.02e23,
            f64::MIN_POSITIVE,
            1e15,
            123456.789,
        ] {
            let s = fmt_f64(x);
            assert_eq!(s.parse::<f64>().unwrap(), x, "{s}");
        }
        assert_eq!(fmt_f64(1e-20), "1e-20");
    }

    /// The buffer writer gives `format!`'s layout and digit count and the same bits back, including
    /// subnormals, extreme magnitudes, signed zero and the decimal/exponent switch points.
    #[test]
    fn push_f64_matches_format_and_round_trips() {
        let reference = |x: f64| {
            let a = x.abs();
            if x == 0.0 || (1e-5..1e15).contains(&a) {
                format!("{x}")
            } else {
                format!("{x:e}")
            }
        };
        let mut xs = vec![
            0.0,
            -0.0,
            1.0,
            -3.0,
            1e-300,
            -1e300,
            1e300,
            f64::MIN_POSITIVE,
            f64::MIN_POSITIVE / 3.0,
            5e-324,
            -5e-324,
            f64::MAX,
            f64::MIN,
            1e-5,
            9.999999999999999e-6,
            1e-7,
            1e15,
            9.999999999999998e14,
            1.5e15,
            1e16,
            123456.789,
            0.1 + 0.2,
        ];
        // A deterministic spread of bit patterns over the whole finite range.
        let mut s: u64 = 0x9E37_79B9_7F4A_7C15;
        for _ in 0..200_000 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            let x = f64::from_bits(s);
            if x.is_finite() {
                xs.push(x);
            }
            // Also moderate magnitudes, where the decimal layout applies.
            xs.push((s >> 11) as f64 / (1u64 << 53) as f64 * 10f64.powi((s % 40) as i32 - 20));
        }
        let mut buf = Vec::new();
        for (x, t) in [
            (-0.0, "-0"),
            (1e-7, "1e-7"),
            (1e15, "1e15"),
            (2.5, "2.5"),
            (3.0, "3"),
        ] {
            buf.clear();
            push_f64(&mut buf, x);
            assert_eq!(std::str::from_utf8(&buf).unwrap(), t);
        }
        for x in xs {
            buf.clear();
            push_f64(&mut buf, x);
            let t = std::str::from_utf8(&buf).unwrap();
            let r = reference(x);
            assert_eq!(t.len(), r.len(), "{t} vs {r}");
            assert_eq!(t.contains('e'), r.contains('e'), "{t} vs {r}");
            let back: f64 = t.parse().unwrap();
            assert_eq!(back.to_bits(), x.to_bits(), "{t}");
        }
        for v in [0i64, 1, -1, 42, i64::MAX, i64::MIN] {
            buf.clear();
            push_int(&mut buf, v);
            assert_eq!(std::str::from_utf8(&buf).unwrap(), v.to_string());
        }
    }
}
