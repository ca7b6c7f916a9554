//! IEC 61131-3 literals shared by the front ends: durations (`T#5s`, `TIME#1h2m`, 1.0's `00:00:00.100`) in microseconds (a part finer than 1 µs is dropped), and in nanoseconds as matiec's C computes them; string literals and matiec's conversions of them to BOOL and integers.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

/// An IEC duration literal (`T#5s`, `TIME#1h2m`, `t#1.5s`, `T#-0s`) or a 1.0 interval
/// (`00:00:00.100000`), in microseconds.
pub fn parse_duration(text: &str) -> Option<u64> {
    let t = text.trim();
    if let Some((h, rest)) = t.split_once(':') {
        let (m, s) = rest.split_once(':')?;
        let (h, m): (u64, u64) = (h.parse().ok()?, m.parse().ok()?);
        let secs = parse_decimal(s, 1_000_000)?;
        return (h * 3600 + m * 60).checked_mul(1_000_000)?.checked_add(secs);
    }
    let upper = t.to_ascii_uppercase();
    let body = upper
        .strip_prefix("TIME#")
        .or_else(|| upper.strip_prefix("T#"))
        .or_else(|| upper.strip_prefix("LTIME#"))
        .or_else(|| upper.strip_prefix("LT#"))?;
    let body: String = body.chars().filter(|c| *c != '_').collect();
    if body.is_empty() || body.starts_with('-') {
        return None;
    }
    let units: [(&str, u64); 7] = [
        ("MS", 1_000),
        ("US", 1),
        ("NS", 0),
        ("D", 86_400_000_000),
        ("H", 3_600_000_000),
        ("M", 60_000_000),
        ("S", 1_000_000),
    ];
    let mut rest = body.as_str();
    let mut total: u64 = 0;
    while !rest.is_empty() {
        let n = rest.find(|c: char| !(c.is_ascii_digit() || c == '.')).unwrap_or(rest.len());
        let (num, after) = rest.split_at(n);
        if num.is_empty() {
            return None;
        }
        let (unit, scale) = units.iter().find(|(u, _)| after.starts_with(u))?;
        let v = if *scale == 0 { Some(0) } else { parse_decimal(num, *scale) }?;
        total = total.checked_add(v)?;
        rest = &after[unit.len()..];
    }
    Some(total)
}

/// The nanoseconds matiec's C gives the duration literal `text` (`T#25.7ms`): `iec2c`
/// writes its parts as written (`__time_to_timespec(1, 25.7, 0, 0, 0, 0)`: ms, s, m, h,
/// d), each a C `double`, and the macro computes `((d*24 + h)*60 + m)*60 + s + ms/1e3`
/// in `long double` (x87's 64-bit significand, each operation rounded to nearest), then
/// `tv_sec` and `tv_nsec` truncated toward zero: `T#25.7ms` is 25,699,999 ns, `T#1400ms`
/// 1,399,999,999. `None` for a part in `us` or `ns` (which matiec does not read), a
/// negative one, or a 1.0 interval.
pub fn matiec_duration_ns(text: &str) -> Option<i64> {
    let upper = text.trim().to_ascii_uppercase();
    let (_, body) = upper.split_once('#')?;
    let body: String = body.chars().filter(|c| *c != '_').collect();
    let units = ["MS", "D", "H", "M", "S"];
    let mut parts: [BigRational; 5] = Default::default();
    let mut rest = body.as_str();
    while !rest.is_empty() {
        let n = rest.find(|c: char| !(c.is_ascii_digit() || c == '.')).unwrap_or(rest.len());
        let (num, after) = rest.split_at(n);
        let k = units.iter().position(|u| after.starts_with(u))?;
        if num.is_empty() || after.starts_with("US") || after.starts_with("NS") {
            return None;
        }
        let (int, frac) = num.split_once('.').unwrap_or((num, ""));
        let digits: BigInt = format!("{int}{frac}").parse().ok()?;
        let exact = BigRational::new(digits, BigInt::from(10).pow(frac.len() as u32));
        parts[k] = round(&exact, 53);
        rest = &after[units[k].len()..];
    }
    let [ms, d, h, m, s] = parts;
    let x = |r: BigRational| round(&r, 64);
    let k = |v: i64| BigRational::from_integer(BigInt::from(v));
    let total = x(x(x(x(x(x(d * k(24)) + h) * k(60)) + m) * k(60)) + s) + x(ms / k(1000));
    let total = x(total);
    let sec = total.trunc();
    let ns = x(x(total - sec.clone()) * k(1_000_000_000)).trunc();
    (sec * k(1_000_000_000) + ns).to_integer().to_i64()
}

/// `r` rounded to the nearest number with a `bits`-bit significand (ties to even), as
/// IEEE arithmetic rounds (no exponent limits: the durations here are far from them).
fn round(r: &BigRational, bits: u32) -> BigRational {
    if r.is_zero() {
        return r.clone();
    }
    let a = r.abs();
    let two = BigRational::from_integer(BigInt::from(2));
    let (lo, hi) = (BigInt::one() << (bits - 1), BigInt::one() << bits);
    let mut e: i64 = a.numer().bits() as i64 - a.denom().bits() as i64 - i64::from(bits);
    let scaled = |e: i64| {
        if e >= 0 { &a / two.pow(e as i32) } else { &a * two.pow((-e) as i32) }
    };
    let mut m = scaled(e);
    while m.floor().to_integer() < lo {
        e -= 1;
        m = scaled(e);
    }
    while m.floor().to_integer() >= hi {
        e += 1;
        m = scaled(e);
    }
    let floor = m.floor();
    let frac = &m - &floor;
    let half = BigRational::new(BigInt::one(), BigInt::from(2));
    let odd = floor.to_integer() % 2 != BigInt::zero();
    let n = if frac > half || (frac == half && odd) { floor + BigRational::one() } else { floor };
    let v = if e >= 0 { n * two.pow(e as i32) } else { n / two.pow((-e) as i32) };
    if r.is_negative() { -v } else { v }
}

/// `12.5` × `scale`, truncated.
fn parse_decimal(s: &str, scale: u64) -> Option<u64> {
    let (int, frac) = s.split_once('.').unwrap_or((s, ""));
    let int: u64 = if int.is_empty() { 0 } else { int.parse().ok()? };
    let mut v = int.checked_mul(scale)?;
    let mut unit = scale;
    for c in frac.chars() {
        unit /= 10;
        v = v.checked_add(u64::from(c.to_digit(10)?) * unit)?;
    }
    Some(v)
}

/// An IEC integer literal as PLCopen and ST write it (`5`, `-5`, `16#FF`, `2#1010_0101`,
/// `INT#-3`, `DINT#16#FF`): its value and the type name its prefix gives (upper case),
/// if any. `None` for anything else (reals, booleans, durations).
pub fn int_literal(text: &str) -> Option<(i128, Option<String>)> {
    let t = text.trim();
    let (ty, value) = match t.split_once('#') {
        Some((ty, v)) if ty.chars().all(|c| c.is_ascii_alphabetic()) && !ty.is_empty() => {
            (Some(ty.to_ascii_uppercase()), v)
        }
        _ => (None, t),
    };
    let digits: String = value.chars().filter(|c| *c != '_').collect();
    let (negative, digits) = match digits.strip_prefix('-') {
        Some(d) => (true, d.to_string()),
        None => (false, digits.strip_prefix('+').unwrap_or(&digits).to_string()),
    };
    let v = match digits.split_once('#') {
        Some((base, d)) => {
            let b: u32 = base.parse().ok().filter(|b| [2, 8, 16].contains(b))?;
            if d.is_empty() || d.starts_with(['-', '+']) {
                return None;
            }
            i128::from_str_radix(d, b).ok()?
        }
        None if !digits.is_empty() && digits.chars().all(|c| c.is_ascii_digit()) => {
            digits.parse::<i128>().ok()?
        }
        None => return None,
    };
    Some((if negative { -v } else { v }, ty))
}

/// The bytes of an IEC single-byte string literal (`'Tank $'A$''`, its quotes included,
/// or typed: `STRING#'12'`)
/// as matiec's C holds them: `$$`, `$'`, `$N` (LF), `$P` (FF), `$R` (CR), `$T` (tab) and
/// `$hh` decoded as its `single_byte_character_string_c` visitor writes them
/// (`stage4/generate_c/generate_c_base.cc`). `None` for what that C does not hold as
/// written: `$L` (the visitor writes a raw line feed inside the C string), `$hh` or
/// `$N` (written `\x0A`) followed by a hex digit (C reads the longer escape), a body past `STR_MAX_LEN` (126
/// bytes), a byte outside printable ASCII.
pub fn string_literal(text: &str) -> Option<Vec<u8>> {
    let text = text.trim();
    let text = match text.split_once('#') {
        Some((ty, s)) if ty.eq_ignore_ascii_case("STRING") => s,
        _ => text,
    };
    let body = text.strip_prefix('\'')?.strip_suffix('\'')?.as_bytes();
    let mut out = Vec::new();
    let mut k = 0;
    while k < body.len() {
        let c = body[k];
        k += 1;
        if !(b' '..=b'~').contains(&c) {
            return None;
        }
        if c == b'\'' {
            return None;
        }
        if c != b'$' {
            out.push(c);
            continue;
        }
        let e = *body.get(k)?;
        k += 1;
        let hex_next = body.get(k).is_some_and(|b| b.is_ascii_hexdigit());
        out.push(match e.to_ascii_uppercase() {
            b'$' | b'\'' => e,
            // Written `\x0A`: a hex digit after it would continue C's escape.
            b'N' if hex_next => return None,
            b'N' => b'\n',
            b'P' => 0x0c,
            b'R' => b'\r',
            b'T' => b'\t',
            _ => {
                let hex = |b: u8| (b as char).to_digit(16);
                let (hi, lo) = (hex(e)?, hex(*body.get(k)?)?);
                k += 1;
                if body.get(k).is_some_and(|b| hex(*b).is_some()) {
                    return None;
                }
                (hi * 16 + lo) as u8
            }
        });
    }
    (out.len() <= 126).then_some(out)
}

/// matiec's `__string_to_bool` (`lib/C/iec_std_lib.h`): `"1"`, or `TRUE` in any case.
pub fn matiec_string_to_bool(body: &[u8]) -> bool {
    match body.len() {
        1 => body == b"1",
        4 => body.eq_ignore_ascii_case(b"TRUE"),
        _ => false,
    }
}

/// matiec's `__pstring_to_sint` (`lib/C/iec_std_lib.h`), the `LINT` that every
/// `STRING_TO_<integer>` casts to its type: `2#`, `8#`, `16#` bodies read from their last
/// digit, other characters skipped; otherwise decimal digits read from the last, at most
/// 20, a character from `.` up that is not a digit starting again, negative when the
/// body starts with `-`. `None` where that C overflows (undefined behaviour): a `2#`
/// digit shifted 31 places or more, an `8#` digit 30 or more (it shifts an `int`), more
/// than 18 decimal digits.
pub fn matiec_string_to_lint(body: &[u8]) -> Option<i64> {
    let radix = |prefix: &[u8], bits: u32, max_shift: u32| -> Option<i64> {
        let mut res: u64 = 0;
        let mut shift = 0u32;
        for &c in body[prefix.len()..].iter().rev() {
            if shift >= 64 {
                break;
            }
            if let Some(d) = (c as char).to_digit(1 << bits) {
                if shift > max_shift {
                    return None;
                }
                res |= u64::from(d) << shift;
                shift += bits;
            }
        }
        Some(res as i64)
    };
    if body.is_empty() {
        return Some(0);
    }
    if body.len() > 1 && body.starts_with(b"2#") {
        return radix(b"2#", 1, 30);
    }
    if body.len() > 1 && body.starts_with(b"8#") {
        return radix(b"8#", 3, 27);
    }
    if body.len() > 2 && body.starts_with(b"16#") {
        return radix(b"16#", 4, 60);
    }
    let sign: i64 = if body[0] == b'-' { -1 } else { 1 };
    let (mut res, mut fac, mut digits) = (0i64, sign, 0u32);
    for &c in body.iter().rev() {
        if digits >= 20 {
            break;
        }
        if c.is_ascii_digit() {
            if digits >= 18 {
                return None;
            }
            res += i64::from(c - b'0') * fac;
            fac *= 10;
            digits += 1;
        } else if (b'.'..0x80).contains(&c) {
            // C's `char` is signed: a byte from 0x80 up is below `'.'`.
            (res, fac, digits) = (0, sign, 0);
        }
    }
    Some(res)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Values gcc gives matiec's `__time_to_timespec` macro (x86-64, `long double`) for
    /// these literals' parts, `tv_sec * 10^9 + tv_nsec` (tools: a C file with the macro
    /// and `printf("%ld %ld")`).
    #[test]
    fn durations_are_what_matiec_s_macro_computes() {
        for (text, ns) in [
            ("T#300ms", 300_000_000),
            ("T#25.7ms", 25_699_999),
            ("T#1400ms", 1_399_999_999),
            ("T#0.5ms", 499_999),
            ("T#0.3s", 299_999_999),
            ("T#1.1s", 1_100_000_000),
            ("T#2.9s", 2_899_999_999),
            ("T#2500ms", 2_500_000_000),
            ("T#1m30s", 90_000_000_000),
            ("TIME#1h_2m", 3_720_000_000_000),
        ] {
            assert_eq!(matiec_duration_ns(text), Some(ns), "{text}");
        }
        assert_eq!(matiec_duration_ns("T#5us"), None);
        assert_eq!(matiec_duration_ns("T#-5s"), None);
    }

    /// What matiec's `__string_to_bool` and `__string_to_sint` (`lib/C/iec_std_lib.h`)
    /// return for these bodies: a C file including the library header, built by gcc
    /// (x86-64), printed each `(body, bool, LINT)`.
    #[test]
    fn string_conversions_are_what_matiec_s_library_computes() {
        let cases: &[(&[u8], i32, i64)] = &[
            (b"", 0, 0),
            (b"1", 1, 1),
            (b"0", 0, 0),
            (b"TRUE", 1, 0),
            (b"true", 1, 0),
            (b"TrUe", 1, 0),
            (b"True ", 0, 0),
            (b"yes", 0, 0),
            (b"12", 0, 12),
            (b"-12", 0, -12),
            (b"+7", 0, 7),
            (b"1_000", 0, 1),
            (b"-1_000", 0, -1),
            (b"12.5", 0, 12),
            (b"3.14abc", 0, 3),
            (b"a12", 0, 0),
            (b"12a", 0, 12),
            (b"1,234", 0, 1234),
            (b" 42 ", 0, 42),
            (b"--5", 0, -5),
            (b"5-", 0, 5),
            (b"99999", 0, 99999),
            (b"65535", 0, 65535),
            (b"-32769", 0, -32769),
            (b"2#1010", 0, 10),
            (b"2#1111_0000", 0, 240),
            (b"2#", 0, 0),
            (b"2#12", 0, 1),
            (b"8#777", 0, 511),
            (b"8#19", 0, 1),
            (b"16#FF", 0, 255),
            (b"16#ff", 0, 255),
            (b"16#DEAD_beef", 0, 3735928559),
            (b"16#G1", 0, 1),
            (b"16#", 0, 0),
            (b"16#FFFFFFFFFFFFFFFF", 0, -1),
            (b"123456789012345678", 0, 123456789012345678),
            (b"x1y2", 0, 0),
            (b"1.2.3", 0, 1),
            (b"7/8", 0, 7),
            (b"9:30", 0, 9),
            (b"-", 0, 0),
            (b".", 0, 0),
            (b"1e5", 0, 1),
        ];
        for (body, b, v) in cases {
            let text = String::from_utf8_lossy(body);
            assert_eq!(matiec_string_to_bool(body), *b == 1, "STRING_TO_BOOL('{text}')");
            assert_eq!(matiec_string_to_lint(body), Some(*v), "STRING_TO_LINT('{text}')");
        }
        // Where that C overflows (undefined), no value.
        for body in [
            &b"2#1000_0000_0000_0000_0000_0000_0000_0000"[..],
            b"8#77777777777",
            b"1234567890123456789",
        ] {
            assert_eq!(matiec_string_to_lint(body), None);
        }
    }

    /// The bytes matiec's visitor writes into the C string for each escape.
    #[test]
    fn string_literals_are_decoded_as_matiec_writes_them() {
        assert_eq!(string_literal("'a$Nx$$c$'d$Te$72'"), Some(b"a\nx$c'd\ter".to_vec()));
        assert_eq!(string_literal("''"), Some(Vec::new()));
        // A raw line feed inside the C string, a longer hex escape, too long, unclosed.
        for text in ["'$L'", "'$41B'", "'$N8'", &format!("'{}'", "x".repeat(127)), "'abc", "'a'b'"]
        {
            assert_eq!(string_literal(text), None, "{text}");
        }
    }
}
