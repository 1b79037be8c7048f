//! Plain decimal numbers read straight from the bytes of a text file, exactly: the same value as
//! `str::parse` (correctly rounded, round half to even) for the numbers mesh files are made of,
//! without a separate pass to find the end of the token.
//!
//! [`scan_f64`] takes `[+-]digits[.digits][(e|E)[+-]digits]` with at most 19 significant digits
//! and a value `w · 10^e` (`w` the digits as an integer) with `-19 <= e <= 19`, or `w < 2^53`
//! and `|e| <= 22`; anything else (more digits, larger exponents, `inf`, `nan`, malformed text)
//! is left to the caller's general path. The value is computed exactly before its one rounding:
//! `w · 10^e` as a 128-bit integer product for `e >= 0`; for `e < 0`, the 128-bit quotient of
//! `w` (shifted to 128 bits) by `10^-e` with the remainder kept as a sticky bit, so the rounding
//! of the quotient to 53 bits is that of the exact value; with `w < 2^53` and `|e| <= 22`,
//! Clinger's fast path (one IEEE multiplication or division of two exact doubles).

/// `10^k` for `k = 0..=19` (all below `2^64`).
const POW10_U64: [u64; 20] = {
    let mut t = [1u64; 20];
    let mut k = 1;
    while k < 20 {
        t[k] = t[k - 1] * 10;
        k += 1;
    }
    t
};

/// `10^k` for `k = 0..=22`, each exact as a double.
const POW10_F64: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// A plain unsigned integer of 1 to 18 digits at the start of `b`: its value and its length in
/// bytes; `None` when `b` does not start with a digit or the run of digits is longer.
#[inline]
pub(crate) fn scan_uint(b: &[u8]) -> Option<(i64, usize)> {
    let mut v: i64 = 0;
    let mut i = 0;
    while i < b.len() {
        let d = b[i].wrapping_sub(b'0');
        if d > 9 {
            break;
        }
        v = v * 10 + i64::from(d);
        i += 1;
        if i > 18 {
            return None;
        }
    }
    (i > 0).then_some((v, i))
}

/// The value of the 8 ASCII digits at `b[i..i + 8]`, or `None` if any of them is not a digit
/// (or fewer than 8 bytes are left): all eight at once in one word (SWAR).
#[inline]
fn eight_digits(b: &[u8], i: usize) -> Option<u64> {
    let chunk: [u8; 8] = b.get(i..i + 8)?.try_into().ok()?;
    let v = u64::from_le_bytes(chunk);
    let d = v.wrapping_sub(0x3030_3030_3030_3030);
    // A byte below b'0' wraps to a high bit in `d`; one above b'9' carries into a high bit of
    // `v + 0x46`.
    if (v.wrapping_add(0x4646_4646_4646_4646) | d) & 0x8080_8080_8080_8080 != 0 {
        return None;
    }
    // Pairs of digits, then groups of four, then all eight (the first byte is the leading digit).
    let d = d.wrapping_mul(10).wrapping_add(d >> 8);
    let lo = (d & 0x0000_00FF_0000_00FF).wrapping_mul(100 + (1_000_000 << 32));
    let hi = ((d >> 16) & 0x0000_00FF_0000_00FF).wrapping_mul(1 + (10_000 << 32));
    Some(lo.wrapping_add(hi) >> 32)
}

/// Reads the run of digits at `b[*i..]` into `w`, all of them significant (leading zeros are
/// skipped by the caller), with `nd` counting the significant digits; returns the number of
/// digits read, or `None` past 19 significant digits.
#[inline]
fn digits(b: &[u8], i: &mut usize, w: &mut u64, nd: &mut u32) -> Option<usize> {
    let start = *i;
    while *nd + 8 <= 19 {
        match eight_digits(b, *i) {
            Some(v) => {
                *w = *w * 100_000_000 + v;
                *nd += 8;
                *i += 8;
            }
            None => break,
        }
    }
    while let Some(&c) = b.get(*i) {
        let d = c.wrapping_sub(b'0');
        if d > 9 {
            break;
        }
        if *nd >= 19 {
            return None;
        }
        *w = *w * 10 + u64::from(d);
        *nd += 1;
        *i += 1;
    }
    Some(*i - start)
}

/// The number of `b'0'` bytes at `b[*i..]`, skipped.
#[inline]
fn zeros(b: &[u8], i: &mut usize) -> usize {
    let start = *i;
    while b.get(*i) == Some(&b'0') {
        *i += 1;
    }
    *i - start
}

/// `2^k` for `-1022 <= k <= 1023`.
#[inline]
fn pow2(k: i32) -> f64 {
    f64::from_bits(((1023 + k) as u64) << 52)
}

/// A plain decimal number at the start of `b` (see the module documentation): its value and its
/// length in bytes, or `None` to leave it to the general parser. The caller checks that the
/// number ends there (whitespace, a comment or the end of the text).
#[inline]
pub(crate) fn scan_f64(b: &[u8]) -> Option<(f64, usize)> {
    let mut i = 0;
    let neg = match b.first() {
        Some(b'-') => {
            i = 1;
            true
        }
        Some(b'+') => {
            i = 1;
            false
        }
        _ => false,
    };
    let (mut w, mut nd) = (0u64, 0u32);
    let int_digits = zeros(b, &mut i) + digits(b, &mut i, &mut w, &mut nd)?;
    let mut e10: i32 = 0;
    let mut frac_digits = 0;
    if b.get(i) == Some(&b'.') {
        i += 1;
        // Zeros before the first significant digit only shift the exponent.
        let lead = if nd == 0 { zeros(b, &mut i) } else { 0 };
        frac_digits = lead + digits(b, &mut i, &mut w, &mut nd)?;
        e10 = -(frac_digits.min(1 << 20) as i32);
    }
    if int_digits + frac_digits == 0 {
        return None;
    }
    if b.get(i).is_some_and(|&c| c | 0x20 == b'e') {
        i += 1;
        let eneg = match b.get(i) {
            Some(b'-') => {
                i += 1;
                true
            }
            Some(b'+') => {
                i += 1;
                false
            }
            _ => false,
        };
        let start = i;
        let mut e: i32 = 0;
        while i < b.len() && b[i].is_ascii_digit() && i - start < 4 {
            e = e * 10 + i32::from(b[i] - b'0');
            i += 1;
        }
        if i == start || b.get(i).is_some_and(u8::is_ascii_digit) {
            return None;
        }
        e10 += if eneg { -e } else { e };
    }
    let x = if w == 0 {
        0.0
    } else if w < 1 << 53 && (-22..=22).contains(&e10) {
        if e10 >= 0 {
            w as f64 * POW10_F64[e10 as usize]
        } else {
            w as f64 / POW10_F64[(-e10) as usize]
        }
    } else if (0..=19).contains(&e10) {
        // Exact product below 10^38 < 2^128; the conversion rounds to nearest, ties to even.
        (u128::from(w) * u128::from(POW10_U64[e10 as usize])) as f64
    } else if (-19..0).contains(&e10) {
        // w / 10^-e = q · 2^-(64 + lz) with q = (w << lz) · 2^64 / 10^-e, at least 2^63: its
        // rounding to 53 bits is decided by its top 54 bits and whether anything below is
        // non-zero, which bit 0 (set when the division has a remainder) carries.
        let lz = w.leading_zeros();
        let n = u128::from(w << lz) << 64;
        let d = u128::from(POW10_U64[(-e10) as usize]);
        let q = n / d;
        let sticky = u128::from(q * d != n);
        (q | sticky) as f64 * pow2(-64 - lz as i32)
    } else {
        return None;
    };
    Some((if neg { -x } else { x }, i))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whatever `scan_f64` accepts in full, it reads as `str::parse` does, bit for bit.
    fn agrees(s: &str) -> bool {
        match scan_f64(s.as_bytes()) {
            Some((x, n)) if n == s.len() => {
                let y: f64 = s.parse().unwrap_or_else(|e| panic!("{s}: {e}"));
                assert_eq!(x.to_bits(), y.to_bits(), "{s}: {x} against {y}");
                true
            }
            _ => false,
        }
    }

    #[test]
    fn plain_decimals_read_exactly() {
        for s in [
            "0",
            "-0",
            "0.0",
            "-0.0",
            "1",
            "+1.5",
            "1.",
            ".5",
            "0.1",
            "0.30000000000000004",
            "-0.7135234567890123",
            "9007199254740993",
            "9007199254740993.0",
            "0.9007199254740993",
            "1844674407370955161",
            "184467440737095516.5",
            "1e-19",
            "9999999999999999999e-19",
            "1.7976931348623157e19",
            "2.2250738585072014e-3",
            "5e-1",
            "1E+5",
            "123456789012345678e-2",
            "0.000001234567890123456",
            "5.e3",
            "+.5",
            "-.5e-1",
            "00.5",
            "0e0",
            "-0e-5",
            "1e0005",
        ] {
            assert!(agrees(s), "{s} not read");
        }
        // More than 19 significant digits: left to the general parser.
        assert!(scan_f64(b"18446744073709551615").is_none());
        assert!(scan_f64(b"1844674407370955161.5").is_none());
        assert!(scan_f64(b"7.000000000000000444089209850062616169452667236328125e-1").is_none());
        // Halfway cases between two doubles near 1, 2^53 and below 1.
        for s in [
            "1.00000000000000011102230246251565",
            "9007199254740993e-3",
            "0.50000000000000005551115123125783",
            "4503599627370496.5",
            "4503599627370497.5",
        ] {
            agrees(s);
        }
        for s in [
            "", "-", ".", "e5", "1e", "1e+", "1.e", "+-1", "nan", "inf", "-x", "1e12345",
        ] {
            assert!(
                scan_f64(s.as_bytes()).map_or(true, |(_, n)| n < s.len()),
                "{s}"
            );
        }
        assert_eq!(scan_f64(b"2.5 7"), Some((2.5, 3)));
        assert_eq!(eight_digits(b"12345678", 0), Some(12_345_678));
        assert_eq!(eight_digits(b"00000009x", 0), Some(9));
        for bad in [&b"1234567/"[..], b"1234567:", b"1234 678", b"123"] {
            assert_eq!(eight_digits(bad, 0), None);
        }
        assert_eq!(scan_uint(b"12 3"), Some((12, 2)));
        assert_eq!(scan_uint(b"x"), None);
        assert_eq!(scan_uint(b"1234567890123456789"), None);
    }

    /// Shortest round-trip texts of a spread of doubles, and random decimal strings of 1 to 19
    /// digits with exponents over the whole fast range, read bit for bit as `str::parse`.
    #[test]
    fn random_decimals_read_exactly() {
        let mut s: u64 = 0x2545_F491_4F6C_DD1D;
        let mut rnd = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            s
        };
        let mut read = 0;
        for _ in 0..100_000 {
            let r = rnd();
            let x = (r >> 11) as f64 / (1u64 << 53) as f64 * 10f64.powi((r % 30) as i32 - 15);
            let x = if r & 1 == 1 { -x } else { x };
            read += usize::from(agrees(&format!("{x}")));
            read += usize::from(agrees(&format!("{x:e}")));
            let nd = (rnd() % 19 + 1) as usize;
            let digits: String = (0..nd)
                .map(|_| char::from(b'0' + (rnd() % 10) as u8))
                .collect();
            let e = (rnd() % 50) as i32 - 25;
            read += usize::from(agrees(&format!("{digits}e{e}")));
            let cut = (rnd() as usize) % (nd + 1);
            read += usize::from(agrees(&format!("{}.{}", &digits[..cut], &digits[cut..])));
        }
        // Most of them take the fast path (the rest are left to the general one).
        assert!(read > 200_000, "{read}");
    }
}
