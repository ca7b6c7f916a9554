//! IEC `REAL` values (IEEE 754 binary32) as the scan model stores them: the 32-bit pattern of the number in an integer of type [`IntType::REAL`](super::IntType::REAL); literals, display and comparisons of concrete values, computed with Rust's `f32` (what matiec's C computes on x86-64).

use super::CmpOp;

/// The number a stored `REAL` value (its bit pattern) stands for.
pub fn to_f32(v: i64) -> f32 {
    f32::from_bits(v as u32)
}

/// The stored value (bit pattern) of `x`.
pub fn of_f32(x: f32) -> i64 {
    i64::from(x.to_bits())
}

/// Whether `a op b` for two stored `REAL` values, as C compares floats: IEEE 754 order,
/// `-0.0 = +0.0`, and a NaN compares false with everything (true for `<>`).
pub fn holds(op: CmpOp, a: i64, b: i64) -> bool {
    op.compares(to_f32(a), to_f32(b))
}

/// `op(x, y)` of two stored `REAL` values, computed with `f32`, its NaN as x86's SSE
/// instructions give it (`addss`, `subss`, `mulss`, `divss`): the first NaN operand made
/// quiet, else the default NaN `0xFFC00000` (Rust, like LLVM, leaves a NaN's bits
/// open). Of two NaNs the C compiler may put either first in a sum or product, which no
/// comparison tells apart: `a`'s is taken.
fn sse(a: i64, b: i64, op: fn(f32, f32) -> f32) -> i64 {
    let (x, y) = (to_f32(a), to_f32(b));
    match op(x, y) {
        _ if x.is_nan() => a | 0x0040_0000,
        _ if y.is_nan() => b | 0x0040_0000,
        r if r.is_nan() => 0xFFC0_0000,
        r => of_f32(r),
    }
}

/// `a + b` of two stored `REAL` values.
pub fn add(a: i64, b: i64) -> i64 {
    sse(a, b, |x, y| x + y)
}

/// `a - b` of two stored `REAL` values.
pub fn sub(a: i64, b: i64) -> i64 {
    sse(a, b, |x, y| x - y)
}

/// `a * b` of two stored `REAL` values.
pub fn mul(a: i64, b: i64) -> i64 {
    sse(a, b, |x, y| x * y)
}

/// `a / b` of two stored `REAL` values, `+0.0` for `b = ±0.0` (matiec's `DIV`).
pub fn div(a: i64, b: i64) -> i64 {
    if to_f32(b) == 0.0 { 0 } else { sse(a, b, |x, y| x / y) }
}

/// The stored value of an IEC real literal (`2.5`, `-0.5`, `1.0E3`, `1_000.0e-2`,
/// `REAL#2.5`): matiec prints the literal's digits into the C code, where the C compiler
/// reads them as a `double` (correctly rounded) and converts that to `float` (round to
/// nearest even). `None` for anything else (an integer literal, `LREAL#…`).
pub fn literal(text: &str) -> Option<i64> {
    let t = text.trim();
    let t = match t.split_once('#') {
        Some((ty, rest)) if ty.eq_ignore_ascii_case("REAL") => rest,
        Some(_) => return None,
        None => t,
    };
    let (sign, digits) = match t.strip_prefix('-') {
        Some(rest) => (-1.0, rest),
        None => (1.0, t.strip_prefix('+').unwrap_or(t)),
    };
    // IEC 61131-3 `real_literal`: integer `.` integer, then an optional exponent.
    let digits = digits.replace('_', "");
    let (mantissa, exponent) = match digits.split_once(['e', 'E']) {
        Some((m, e)) => (m.to_string(), Some(e.to_string())),
        None => (digits.clone(), None),
    };
    let (int, frac) = mantissa.split_once('.')?;
    let all_digits = |s: &str| !s.is_empty() && s.bytes().all(|c| c.is_ascii_digit());
    let exponent_ok =
        exponent.as_deref().is_none_or(|e| all_digits(e.strip_prefix(['+', '-']).unwrap_or(e)));
    if !all_digits(int) || !all_digits(frac) || !exponent_ok {
        return None;
    }
    let double: f64 = digits.parse().ok()?;
    Some(of_f32((sign * double) as f32))
}

/// A stored `REAL` value as people read it (`2.5`, `100.0`, `-0.0`, `inf`, `NaN`).
pub fn show(v: i64) -> String {
    format!("{:?}", to_f32(v))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn literals_are_read_as_c_reads_them() {
        assert_eq!(literal("2.5"), Some(0x4020_0000));
        assert_eq!(literal("REAL#-0.5"), Some(of_f32(-0.5)));
        assert_eq!(literal("1.0E3"), Some(of_f32(1000.0)));
        assert_eq!(literal("1_000.0e-2"), Some(of_f32(10.0)));
        assert_eq!(literal("-0.0"), Some(of_f32(-0.0)));
        assert_eq!(literal("0.1"), Some(of_f32(0.1f64 as f32)));
        for no in ["3", "1E3", ".5", "5.", "LREAL#1.0", "1.0E", "x.5", "16#FF"] {
            assert_eq!(literal(no), None, "{no}");
        }
    }

    #[test]
    fn comparisons_follow_ieee() {
        let (nan, zero, neg_zero) = (of_f32(f32::NAN), of_f32(0.0), of_f32(-0.0));
        assert!(holds(CmpOp::Eq, zero, neg_zero));
        assert!(!holds(CmpOp::Eq, nan, nan));
        assert!(holds(CmpOp::Ne, nan, nan));
        assert!(!holds(CmpOp::Le, nan, zero));
        assert!(holds(CmpOp::Lt, of_f32(-1.0), of_f32(0.5)));
        assert_eq!(show(of_f32(2.5)), "2.5");
        assert_eq!(show(of_f32(100.0)), "100.0");
    }
}
