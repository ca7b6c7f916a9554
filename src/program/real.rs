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

/// `a / b` of two stored `REAL` values as C's `/` computes it: `±∞` or NaN for a
/// divisor `±0.0`.
pub fn quotient(a: i64, b: i64) -> i64 {
    sse(a, b, |x, y| x / y)
}

/// `√a` of a stored value of the real type `ty` as matiec's `SQRT` computes it: C's
/// `sqrt` (of a `REAL` made a `double`, the root made a `float` again), its NaN as
/// x86's SSE instructions give it (a NaN operand made quiet, the default NaN for a
/// number below 0).
pub fn sqrt_in(ty: super::IntType, a: i64) -> i64 {
    if ty.bits == 64 {
        sse_double(a, a, |x, _| x.sqrt())
    } else {
        sse(a, a, |x, _| f64::from(x).sqrt() as f32)
    }
}

/// The number a stored `double` (an [`IntType::LREAL`](super::IntType::LREAL) value: its
/// bit pattern) stands for.
pub fn to_f64(v: i64) -> f64 {
    f64::from_bits(v as u64)
}

/// The stored value (bit pattern) of the `double` `x`.
pub fn of_f64(x: f64) -> i64 {
    x.to_bits() as i64
}

/// `op(x, y)` of two stored `double`s, its NaN as x86's SSE instructions give it
/// (`addsd`, `subsd`, `mulsd`, `divsd`), as [`sse`] for `float`s: the first NaN operand
/// made quiet, else the default NaN `0xFFF8000000000000`.
fn sse_double(a: i64, b: i64, op: fn(f64, f64) -> f64) -> i64 {
    let (x, y) = (to_f64(a), to_f64(b));
    match op(x, y) {
        _ if x.is_nan() => a | 1 << 51,
        _ if y.is_nan() => b | 1 << 51,
        r if r.is_nan() => of_f64(f64::from_bits(0xFFF8_0000_0000_0000)),
        r => of_f64(r),
    }
}

/// `op(a, b)` of two stored `double`s as C computes it (`Div`: `+0.0` for `b = ±0.0`,
/// as matiec's `DIV`; `Quotient`: C's `/`).
pub fn double_op(op: super::RealOp, a: i64, b: i64) -> i64 {
    use super::RealOp;
    match op {
        RealOp::Add => sse_double(a, b, |x, y| x + y),
        RealOp::Sub => sse_double(a, b, |x, y| x - y),
        RealOp::Mul => sse_double(a, b, |x, y| x * y),
        RealOp::Div if to_f64(b) == 0.0 => 0,
        RealOp::Div | RealOp::Quotient => sse_double(a, b, |x, y| x / y),
    }
}

/// The stored `REAL` `v` as a stored `double`, as C promotes a `float` (`cvtss2sd`):
/// exactly; a NaN keeps its sign and fraction (at the top of the wider one), made quiet.
pub fn widen(v: i64) -> i64 {
    let x = to_f32(v);
    if x.is_nan() {
        let sign = (v >> 31 & 1) << 63;
        return sign | 0x7FF8_0000_0000_0000 | (v & 0x007F_FFFF) << 29;
    }
    of_f64(f64::from(x))
}

/// The stored `double` `v` as a stored `REAL`, as C converts a `double` to `float`
/// (`cvtsd2ss`): the nearest, ties to even, `±∞` beyond the largest; a NaN keeps its
/// sign and the top of its fraction, made quiet.
pub fn narrow(v: i64) -> i64 {
    let x = to_f64(v);
    if x.is_nan() {
        let u = v as u64;
        return ((u >> 63) << 31 | 0x7FC0_0000 | (u >> 29) & 0x007F_FFFF) as i64;
    }
    of_f32(x as f32)
}

/// [`IntExpr::ToReal`](super::IntExpr::ToReal) of the value `v` of type `from` into the
/// real type `to`: an integer to the nearest `float` (Rust's `as f32` rounds to nearest,
/// ties to even, as C does), a `float` to `double` or back.
pub fn convert(v: i64, from: super::IntType, to: super::IntType) -> i64 {
    match (from.real, from.bits, to.bits) {
        (true, 32, 64) => widen(v),
        (true, 64, 32) => narrow(v),
        (true, _, _) => v,
        (false, _, 64) => of_f64(v as f64),
        (false, _, _) => of_f32(v as f32),
    }
}

/// Whether `a op b` for two stored `double`s, as C compares them.
pub fn holds_double(op: CmpOp, a: i64, b: i64) -> bool {
    op.compares(to_f64(a), to_f64(b))
}

/// A stored `double` as people read it.
pub fn show_double(v: i64) -> String {
    format!("{:?}", to_f64(v))
}

/// `-2^63` and `2^63` as stored `REAL`s: the ends of the 64-bit `LINT` range through
/// which matiec's `REAL_TO_*` converts.
pub const LINT_RANGE: (i64, i64) = (0xDF00_0000, 0x5F00_0000);

/// The integer matiec's `REAL_TO_*` gives for the stored `REAL` `v`, before it is
/// wrapped to the target type (`lib/C/iec_std_lib.h`: `__real_to_sint` for a signed
/// target; `__real_to_uint` and `__real_to_bit`, `unsigned`, for an unsigned or
/// bit-string one, where `IN >= 0` fails for a negative number or a NaN, which give 0):
/// the number rounded to the nearest integer, ties to even (`__real_round` of `IN ± 0.5`),
/// as a 64-bit `LINT`. `None` where C leaves the conversion to `LINT` undefined: a NaN or
/// `±∞` to a signed type, `+∞` to an unsigned one, a number outside `[-2^63, 2^63)`.
pub fn to_int(v: i64, unsigned: bool) -> Option<i64> {
    let x = to_f32(v);
    // `IN >= 0` fails for a negative number and for a NaN.
    if unsigned && (x < 0.0 || x.is_nan()) {
        return Some(0);
    }
    let (low, end) = LINT_RANGE;
    let in_range = holds(CmpOp::Ge, v, low) && holds(CmpOp::Lt, v, end);
    in_range.then(|| x.round_ties_even() as i64)
}

/// The stored value of an IEC real literal (`2.5`, `-0.5`, `1.0E3`, `1_000.0e-2`,
/// `REAL#2.5`): matiec prints the literal's digits into the C code, where the C compiler
/// reads them as a `double` (correctly rounded) and converts that to `float` (round to
/// nearest even). `None` for anything else (an integer literal, `LREAL#…`).
pub fn literal(text: &str) -> Option<i64> {
    literal_value(text).map(|v| of_f32(v as f32))
}

/// The value of the real literal `text` as C reads the constant matiec writes for it:
/// a `double` (what [`literal`] converts to a stored `REAL`), or `None` if it is not one.
pub fn literal_value(text: &str) -> Option<f64> {
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
    Some(sign * double)
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

    /// matiec's `__preal_to_sint` / `__preal_to_uint` as its C reads (the `REAL`
    /// promoted to `double`, `IN ± 0.5`, `fmod(…, 1) == 0 ? ((LINT)… / 2) * 2 : (LINT)…`),
    /// `None` where the cast to `LINT` is undefined (C11 6.3.1.4: a NaN, or an integral
    /// part outside the type).
    fn matiec(v: i64, unsigned: bool) -> Option<i64> {
        let x = f64::from(to_f32(v));
        let y = match x >= 0.0 {
            true => x + 0.5,
            false if unsigned => return Some(0),
            false => x - 0.5,
        };
        let t = y.trunc();
        if t.is_nan() || t < -(2f64.powi(63)) || t >= 2f64.powi(63) {
            return None;
        }
        Some(if y % 1.0 == 0.0 { (y as i64) / 2 * 2 } else { y as i64 })
    }

    #[test]
    fn conversions_to_integers_round_as_matiec() {
        let mut vs: Vec<u32> = [0.0f32, 0.5, 1.5, 2.5, 3.5, 0.49999997, 1.0, 8_388_608.5]
            .iter()
            .flat_map(|x| [x.to_bits(), (-x).to_bits()])
            .collect();
        vs.extend([1, 0x007f_ffff, 0x7f80_0000, 0xff80_0000, 0x7fc0_0000, 0xffc0_0001]);
        vs.extend([0x5eff_ffff, 0x5f00_0000, 0xdf00_0000, 0xdf00_0001, 0x4f00_0000, 0xcf00_0000]);
        let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
        for _ in 0..20_000 {
            state = state.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            vs.push((state >> 32) as u32);
        }
        for v in vs {
            for unsigned in [false, true] {
                let v = i64::from(v);
                assert_eq!(to_int(v, unsigned), matiec(v, unsigned), "{} {unsigned}", show(v));
            }
        }
        assert_eq!(to_int(of_f32(2.5), false), Some(2));
        assert_eq!(to_int(of_f32(-2.5), false), Some(-2));
        assert_eq!(to_int(of_f32(-2.5), true), Some(0));
        assert_eq!(to_int(of_f32(f32::NAN), true), Some(0));
        assert_eq!(to_int(of_f32(f32::NAN), false), None);
        assert_eq!(to_int(of_f32(f32::INFINITY), true), None);
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
