//! Tests of the binary64 (`double`) circuits of `float.rs`, the conversions between `float` and `double`, and the square root of both, against Rust's `f64` and `f32` arithmetic (`program/real.rs`'s references).

use super::{
    Bits, Namer, add_real, compare_real, constant, div_real, mul_real, narrow_real, quotient_real,
    sqrt_real, widen_real,
};
use crate::program::logic::L;
use crate::program::{CmpOp, IntType, RealOp, real};
use proptest::prelude::*;

fn eval(t: &L) -> bool {
    match t {
        L::Zero => false,
        L::One => true,
        L::Not(x) => !eval(x),
        L::And(xs) => xs.iter().all(eval),
        L::Or(xs) => xs.iter().any(eval),
        _ => panic!("not a constant term: {t:?}"),
    }
}

fn value(bits: &[L]) -> u64 {
    bits.iter().enumerate().fold(0u64, |acc, (k, b)| acc | (u64::from(eval(b)) << k))
}

fn bits(v: u64) -> Bits {
    constant(v as i64, 64)
}

/// A circuit of two `double`s.
type Circuit = fn(&[L], &[L], Namer) -> Bits;

const OPS: [(RealOp, Circuit); 5] = [
    (RealOp::Add, |a, b, n| add_real(a, b, false, n)),
    (RealOp::Sub, |a, b, n| add_real(a, b, true, n)),
    (RealOp::Mul, mul_real),
    (RealOp::Div, div_real),
    (RealOp::Quotient, quotient_real),
];

/// Every operation's circuit on `x` and `y`, against `f64` ([`real::double_op`]).
fn computes(x: u64, y: u64) -> Result<(), TestCaseError> {
    for (op, circuit) in OPS {
        let got = value(&circuit(&bits(x), &bits(y), &mut |t| t));
        let want = real::double_op(op, x as i64, y as i64) as u64;
        let (p, q) = (f64::from_bits(x), f64::from_bits(y));
        prop_assert_eq!(got, want, "{:?} {:?} {:?}: {:016x}, not {:016x}", p, op, q, got, want);
    }
    Ok(())
}

/// Every comparison's circuit on `x` and `y`, against `f64`'s.
fn compares(x: u64, y: u64) -> Result<(), TestCaseError> {
    let ops = [CmpOp::Eq, CmpOp::Ne, CmpOp::Lt, CmpOp::Le, CmpOp::Gt, CmpOp::Ge];
    for op in ops {
        let got = eval(&compare_real(op, &bits(x), &bits(y), &mut |t| t));
        let want = op.compares(f64::from_bits(x), f64::from_bits(y));
        prop_assert_eq!(got, want, "{:?} {:?} {:?}", f64::from_bits(x), op, f64::from_bits(y));
    }
    Ok(())
}

/// The conversion of the `float` `x` to `double`, against `f64::from` (NaNs: x86's).
fn widens(x: u32) -> Result<(), TestCaseError> {
    let got = value(&widen_real(&constant(i64::from(x), 32), &mut |t| t));
    let want = real::widen(i64::from(x)) as u64;
    prop_assert_eq!(got, want, "{:?}", f32::from_bits(x));
    if !f32::from_bits(x).is_nan() {
        prop_assert_eq!(got, f64::from(f32::from_bits(x)).to_bits());
    }
    Ok(())
}

/// The conversion of the `double` `x` to `float`, against `as f32` (NaNs: x86's).
fn narrows(x: u64) -> Result<(), TestCaseError> {
    let got = value(&narrow_real(&bits(x), &mut |t| t)) as u32;
    let want = real::narrow(x as i64) as u32;
    prop_assert_eq!(got, want, "{:?}: {:08x}, not {:08x}", f64::from_bits(x), got, want);
    let f = f64::from_bits(x);
    if !f.is_nan() {
        prop_assert_eq!(got, (f as f32).to_bits());
    } else {
        prop_assert!(f32::from_bits(got).is_nan());
    }
    Ok(())
}

/// Zeros, subnormals, the ends of the normals, infinities, NaNs (quiet, signalling),
/// `2^53 + 1`'s neighbours, and values whose results round, overflow or underflow;
/// each with its negation.
fn hard() -> Vec<u64> {
    let mut v: Vec<u64> = vec![0, 1, 0x000F_FFFF_FFFF_FFFF, 0x0010_0000_0000_0000];
    v.extend([0x7FEF_FFFF_FFFF_FFFF, 0x7FF0_0000_0000_0000, 0x7FF8_0000_0000_0000]);
    v.extend([0x7FF0_0000_0000_0001, 0x7FF8_1234_5678_9ABC, 0x3FF0_0000_0000_0001]);
    let numbers = [1.0, 0.1, 3.0, 2.5, 9007199254740993.0, 9007199254740992.0, 1e308, 1e-310];
    v.extend(numbers.map(f64::to_bits));
    v.extend(
        [f64::from(0.1f32), f64::from(f32::MAX), 2f64.powi(-1022), 2f64.powi(-1074)]
            .map(f64::to_bits),
    );
    let negatives: Vec<u64> = v.iter().map(|x| x | 1 << 63).collect();
    v.extend(negatives);
    v
}

#[test]
fn hard_values_compute_and_compare_as_f64() {
    for &x in &hard() {
        for &y in &hard() {
            computes(x, y).unwrap();
            compares(x, y).unwrap();
        }
    }
}

/// `float`s whose doubles are hard: zeros, subnormals, the largest, NaNs.
fn hard_floats() -> Vec<u32> {
    let mut v = vec![0, 1, 0x007F_FFFF, 0x0080_0000, 0x7F7F_FFFF, 0x7F80_0000, 0x7FC0_0000];
    v.extend([0x7F80_0001, 0x7FBF_FFFF, 0x7FC1_2345, 0x3DCC_CCCD, 0x0000_1234]);
    let negatives: Vec<u32> = v.iter().map(|x| x | 0x8000_0000).collect();
    v.extend(negatives);
    v
}

#[test]
fn hard_values_widen_and_narrow_as_c() {
    for x in hard_floats() {
        widens(x).unwrap();
    }
    let mut ds = hard();
    // Around the `float`s: exact ones, ties (even and odd), just above and below.
    for x in hard_floats() {
        let d = f64::from(f32::from_bits(x)).to_bits();
        let up = |k: u64| d.wrapping_add(k);
        ds.extend([d, up(1 << 28), up(3 << 28), up((1 << 28) + 1), up((1 << 28) - 1)]);
    }
    // Where `float`s overflow, become subnormal, or vanish.
    for p in [127, 128, -126, -127, -149, -150, -151, -160] {
        let d = 2f64.powi(p).to_bits();
        ds.extend([d, d - 1, d + 1, d | 1 << 63, d + (1 << 51), d - (1 << 28)]);
    }
    ds.push((f64::from(f32::MAX) + 2f64.powi(103)).to_bits());
    ds.push((f64::from(f32::MAX) + 2f64.powi(103)).to_bits() - 1);
    for d in ds {
        narrows(d).unwrap();
    }
}

/// The root circuit on the `double` `x`, against C's `sqrt` ([`real::sqrt_in`]), and
/// that reference against Rust's own root (NaNs: x86's).
fn roots(x: u64) -> Result<(), TestCaseError> {
    let got = value(&sqrt_real(&bits(x), &mut |t| t));
    let want = real::sqrt_in(IntType::LREAL, x as i64) as u64;
    prop_assert_eq!(got, want, "√{:?}: {:016x}, not {:016x}", f64::from_bits(x), got, want);
    let f = f64::from_bits(x);
    if !f.sqrt().is_nan() {
        prop_assert_eq!(got, f.sqrt().to_bits());
    }
    Ok(())
}

/// The root circuit on the `float` `x`, against C's `sqrt` of it made a `double`
/// ([`real::sqrt_in`]), and that against `f32`'s own root, correctly rounded as well.
fn roots_float(x: u32) -> Result<(), TestCaseError> {
    let got = value(&sqrt_real(&constant(i64::from(x), 32), &mut |t| t)) as u32;
    let want = real::sqrt_in(IntType::REAL, i64::from(x)) as u32;
    prop_assert_eq!(got, want, "√{:?}: {:08x}, not {:08x}", f32::from_bits(x), got, want);
    let f = f32::from_bits(x);
    if !f.sqrt().is_nan() {
        prop_assert_eq!(got, f.sqrt().to_bits());
    } else {
        prop_assert!(f32::from_bits(got).is_nan());
    }
    Ok(())
}

#[test]
fn hard_values_have_the_roots_c_gives() {
    for x in hard() {
        roots(x).unwrap();
    }
    // Perfect squares, their neighbours, and the largest below a power of 4.
    for x in
        hard_floats().into_iter().chain([4.0f32, 9.0, 2.0, 0.25, 1e-45, 3.4e38].map(f32::to_bits))
    {
        for k in [0u32, 1, 2] {
            roots_float(x.wrapping_add(k)).unwrap();
            roots_float(x.wrapping_sub(k)).unwrap();
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]
    #[test]
    fn random_values_have_the_roots_c_gives(x in any::<u64>(), y in any::<u32>(), k in 1u32..4096) {
        roots(x)?;
        roots_float(y)?;
        // Squares of short integers, exact roots, and the numbers next to them.
        let square = (k * k) as f32;
        roots_float(square.to_bits())?;
        roots_float(square.to_bits() + 1)?;
        roots_float(square.to_bits() - 1)?;
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]
    #[test]
    fn random_values_compute_as_f64(x in any::<u64>(), y in any::<u64>(), ey in 0u64..60, low in 0u32..53) {
        computes(x, y)?;
        // Exponents near each other (cancellation, ties), and short significands.
        let e = ((x >> 52) & 0x7FF) + ey;
        let near = (y & 0x800F_FFFF_FFFF_FFFF) | (e.min(2046) << 52);
        computes(x, near)?;
        computes(x >> low << low, near >> low << low)?;
        compares(x, y)?;
        compares(x, x ^ 1 << 63)?;
        compares(x, x.wrapping_add(u64::from(low % 3)))?;
    }

    #[test]
    fn random_scalings_compute_as_f64(x in any::<i16>(), k in 0usize..6) {
        // A `float` read from an integer, promoted, scaled by a literal, rounded back.
        let scale = [0.1, 0.01, 0.001, 0.3, 1.0 / 3.0, 27.6][k];
        let w = real::widen(real::of_f32(f32::from(x)));
        computes(w as u64, f64::to_bits(scale))?;
        narrows(real::double_op(RealOp::Mul, w, real::of_f64(scale)) as u64)?;
    }

    #[test]
    fn random_values_widen_and_narrow_as_c(x in any::<u32>(), y in any::<u64>(), e in 0u64..300) {
        widens(x)?;
        narrows(y)?;
        // Exponents near `float`'s range (896 + 1 to 254, subnormal, overflowing).
        narrows((y & 0x800F_FFFF_FFFF_FFFF) | ((1023 - 127 - 30 + e) << 52))?;
    }
}
