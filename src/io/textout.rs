//! Text output for the mesh and field writers: floats in their shortest round-trip form and
//! integers, formatted straight into one byte buffer that is handed to the file in large blocks.

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
    if push_short_decimal(buf, x) {
        return;
    }
    let mut r = ryu::Buffer::new();
    let s = r.format_finite(x).as_bytes();
    // ryu writes integral values as "3.0" and "-0.0"; Rust's Display writes "3" and "-0".
    let s = s.strip_suffix(b".0").unwrap_or(s);
    buf.extend_from_slice(s);
}

/// Appends `x` when it is a decimal `m / 10^k` with `k <= 4` fractional digits (`0 < |m| <
/// 10^15`) that reads back exactly, with the fewest such digits: the text ryu gives (the shortest
/// round-trip digits; here they are unique, as two decimals with `k <= 4` fractional digits are
/// at least `10^-4` apart, far more than the rounding interval of `x`), for a fraction of its
/// cost. Mesh coordinates on grids often are such decimals. Returns whether it wrote `x`.
#[inline]
fn push_short_decimal(buf: &mut Vec<u8>, x: f64) -> bool {
    const P: [f64; 5] = [1.0, 10.0, 100.0, 1e3, 1e4];
    let a = x.abs();
    if !(1e-4..1e11).contains(&a) {
        return false;
    }
    for (k, &p) in P.iter().enumerate() {
        // The nearest integer to a·p < 10^15 (the sum is exact there; a truncating conversion
        // instead of `round`, which is a library call on baseline x86-64).
        let mi = (a * p + 0.5) as u64;
        let m = mi as f64;
        // m < 10^15 < 2^53 and p are exact, so m / p is the correctly rounded value of the
        // decimal: equal to `a` exactly when the decimal reads back as `a`. The fewest digits
        // never end in 0 (then k - 1 digits would have done); anything else is left to ryu.
        if m / p == a {
            if k > 0 && mi % 10 == 0 {
                return false;
            }
            let mut digits = itoa::Buffer::new();
            let d = digits.format(mi).as_bytes();
            if x < 0.0 {
                buf.push(b'-');
            }
            if k == 0 {
                buf.extend_from_slice(d);
            } else if d.len() > k {
                let (int, frac) = d.split_at(d.len() - k);
                buf.extend_from_slice(int);
                buf.push(b'.');
                buf.extend_from_slice(frac);
            } else {
                buf.extend_from_slice(b"0.");
                buf.resize(buf.len() + k - d.len(), b'0');
                buf.extend_from_slice(d);
            }
            return true;
        }
    }
    false
}

/// Appends the decimal text of an integer to `buf` (the same text as `{v}`).
pub(crate) fn push_int<I: itoa::Integer>(buf: &mut Vec<u8>, v: I) {
    buf.extend_from_slice(itoa::Buffer::new().format(v).as_bytes());
}

/// The two-digit decimal texts of 0 to 99, back to back.
const PAIRS: [u8; 200] = {
    let mut t = [0u8; 200];
    let mut k = 0;
    while k < 100 {
        t[2 * k] = b'0' + (k / 10) as u8;
        t[2 * k + 1] = b'0' + (k % 10) as u8;
        k += 1;
    }
    t
};

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
        // Formatted right to left into one small buffer, appended at once (one copy per line
        // rather than per number).
        let mut line = [0u8; 8 * 21];
        if vs.len() > 8 {
            for (k, &v) in vs.iter().enumerate() {
                if k > 0 {
                    self.buf.push(b' ');
                }
                push_int(&mut self.buf, v);
            }
            return;
        }
        let mut at = line.len();
        for (k, &v) in vs.iter().enumerate().rev() {
            let mut u = v.unsigned_abs();
            while u >= 100 {
                let r = 2 * (u % 100) as usize;
                u /= 100;
                at -= 2;
                line[at..at + 2].copy_from_slice(&PAIRS[r..r + 2]);
            }
            if u >= 10 {
                at -= 2;
                line[at..at + 2].copy_from_slice(&PAIRS[2 * u as usize..2 * u as usize + 2]);
            } else {
                at -= 1;
                line[at] = b'0' + u as u8;
            }
            if v < 0 {
                at -= 1;
                line[at] = b'-';
            }
            if k > 0 {
                at -= 1;
                line[at] = b' ';
            }
        }
        self.buf.extend_from_slice(&line[at..]);
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
        // Short decimals (written without ryu) give ryu's digits exactly.
        let ryu_text = |x: f64| {
            let mut r = ryu::Buffer::new();
            let t = r.format_finite(x);
            t.strip_suffix(".0").unwrap_or(t).to_string()
        };
        for _ in 0..200_000 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            let k = (s % 7) as i32;
            let m = (s >> 20) % 10u64.pow((s >> 8) as u32 % 13 + 1);
            let m = if s & 1 == 1 { -(m as f64) } else { m as f64 };
            for x in [
                m / 10f64.powi(k),
                m * 0.1f64.powi(k),
                (m + 0.5) / 10f64.powi(k),
            ] {
                buf.clear();
                push_f64(&mut buf, x);
                assert_eq!(std::str::from_utf8(&buf).unwrap(), ryu_text(x), "{x:e}");
            }
        }
        let mut out = Vec::new();
        let mut o = Out::new(&mut out);
        o.ints(&[0, 7, -12, 1234567, i64::MIN, i64::MAX, 10, -1]);
        o.ints(&[1, 2, 3, 4, 5, 6, 7, 8, 9]);
        o.finish().unwrap();
        assert_eq!(
            std::str::from_utf8(&out).unwrap(),
            format!(
                "0 7 -12 1234567 {} {} 10 -11 2 3 4 5 6 7 8 9",
                i64::MIN,
                i64::MAX
            )
        );
        for v in [0i64, 1, -1, 42, i64::MAX, i64::MIN] {
            buf.clear();
            push_int(&mut buf, v);
            assert_eq!(std::str::from_utf8(&buf).unwrap(), v.to_string());
        }
    }
}
