//! Integers as vectors of Boolean terms: two's-complement arithmetic and comparisons built from `·`, `+` and `¬`, least significant bit first, as the II compiler bit-blasts the scan model's integers.
//!
//! Every operation wraps to the width of its operands, as the runtime's arithmetic does.
//! Terms are trees, so a value read twice is copied: the callers pass a `name` function
//! that may replace a large term by a signal defined as equal to it (the compiler's
//! intermediate values), which keeps every result linear in the width.
#![warn(missing_docs)]

#[cfg(test)]
mod double_tests;
mod float;

pub use float::{
    add_real, compare_real, div_real, int_to_real, mul_real, narrow_real, quotient_real,
    real_to_int, sqrt_real, widen_real,
};

use super::CmpOp;
use super::IntType;
use super::logic::{L, simplify};

/// A value of some width: its bits, least significant first.
pub type Bits = Vec<L>;

/// Names a large term (or returns it as it is).
pub type Namer<'a> = &'a mut dyn FnMut(L) -> L;

/// `a ⊕ b`.
pub fn xor(a: &L, b: &L) -> L {
    match (a, b) {
        (L::Zero, x) | (x, L::Zero) => x.clone(),
        (L::One, x) | (x, L::One) => x.clone().negate(),
        _ => simplify(a.clone().and(b.clone().negate()).or(a.clone().negate().and(b.clone()))),
    }
}

/// `c · a + ¬c · b`.
pub fn mux(c: &L, a: &L, b: &L) -> L {
    match c {
        L::One => a.clone(),
        L::Zero => b.clone(),
        _ if a == b => a.clone(),
        _ => simplify(c.clone().and(a.clone()).or(c.clone().negate().and(b.clone()))),
    }
}

/// The bits of `v` in `width` bits (two's complement).
pub fn constant(v: i64, width: u32) -> Bits {
    (0..width).map(|k| if v >> k.min(63) & 1 == 1 { L::One } else { L::Zero }).collect()
}

/// The value of `bits` (each `true` or `false`) read in `ty`.
pub fn value_of(bits: &[bool], ty: IntType) -> i64 {
    let raw = bits.iter().enumerate().fold(0i64, |acc, (k, b)| acc | (i64::from(*b) << k));
    ty.wrap(raw)
}

/// `v` of type `from` in type `to`: sign- or zero-extended, or truncated.
pub fn resize(mut v: Bits, from: IntType, to: IntType) -> Bits {
    let fill = if from.signed { v.last().cloned().unwrap_or(L::Zero) } else { L::Zero };
    v.resize(to.bits as usize, fill);
    v
}

/// Bitwise `¬a`.
pub fn not(a: &[L]) -> Bits {
    a.iter().map(|x| x.clone().negate()).collect()
}

/// `a + b + carry` wrapped to the width of `a` (`b` as wide).
pub fn add(a: &[L], b: &[L], carry: L, name: Namer) -> Bits {
    let mut c = carry;
    let mut out = Vec::with_capacity(a.len());
    for (k, (x, y)) in a.iter().zip(b).enumerate() {
        let half = name(xor(x, y));
        out.push(name(xor(&half, &c)));
        if k + 1 < a.len() {
            // The carry: x · y + c · (x ⊕ y).
            c = name(simplify(x.clone().and(y.clone()).or(c.and(half))));
        }
    }
    out
}

/// `a - b` wrapped.
pub fn sub(a: &[L], b: &[L], name: Namer) -> Bits {
    add(a, &not(b), L::One, name)
}

/// `a · b` wrapped to the width of `a` (shift and add).
pub fn mul(a: &[L], b: &[L], name: Namer) -> Bits {
    let width = a.len();
    let mut acc = constant(0, width as u32);
    for (k, y) in b.iter().enumerate().take(width) {
        if *y == L::Zero {
            continue;
        }
        // a · y shifted by k.
        let mut partial = constant(0, width as u32);
        for j in k..width {
            partial[j] = simplify(a[j - k].clone().and(y.clone()));
        }
        acc = add(&acc, &partial, L::Zero, name);
    }
    acc
}

/// `a / k` for a value `a` of type `ty` and a literal `k ≠ 0`: truncated toward zero and
/// wrapped to the width of `a` (so `min / −1` is `min`), by restoring division of the
/// magnitudes and the sign put back.
pub fn div(a: &[L], k: i64, ty: IntType, name: Namer) -> Bits {
    let (q, _, _) = divide(a, &Divisor::literal(k, a.len()), ty, name);
    q
}

/// `a % k` as C computes it (truncated division: the remainder takes the sign of `a`),
/// for a value `a` of type `ty` and a literal `k ≠ 0`, in the width of `a`.
pub fn rem(a: &[L], k: i64, ty: IntType, name: Namer) -> Bits {
    let (_, r, negative) = divide(a, &Divisor::literal(k, a.len()), ty, name);
    signed_rem(r, &negative, a.len(), name)
}

/// `a / b` for two values of type `ty`, truncated toward zero and wrapped (`min / −1` is
/// `min`), and `0` when `b` is 0: a divider circuit (restoring division of the
/// magnitudes, the sign put back), then the zero divisor masked.
pub fn div_by(a: &[L], b: &[L], ty: IntType, name: Namer) -> Bits {
    let d = Divisor::value(b, ty, name);
    let (q, _, _) = divide(a, &d, ty, name);
    unless_zero(q, b)
}

/// `a % b` for two values of type `ty` as C computes it (the remainder takes the sign of
/// `a`), and `0` when `b` is 0.
pub fn rem_by(a: &[L], b: &[L], ty: IntType, name: Namer) -> Bits {
    let d = Divisor::value(b, ty, name);
    let (_, r, negative) = divide(a, &d, ty, name);
    unless_zero(signed_rem(r, &negative, a.len(), name), b)
}

/// `v`, or 0 where every bit of `b` is 0.
fn unless_zero(v: Bits, b: &[L]) -> Bits {
    let nonzero = simplify(L::Or(b.to_vec().into()));
    v.iter().map(|x| simplify(x.clone().and(nonzero.clone()))).collect()
}

/// The remainder of magnitude `r` (in `w + 2` bits) in `w` bits, negated when the
/// dividend is `negative`.
fn signed_rem(r: Bits, negative: &L, w: usize, name: Namer) -> Bits {
    let r: Bits = r[..w].to_vec();
    let minus_r = sub(&constant(0, w as u32), &r, name);
    r.iter().zip(&minus_r).map(|(x, y)| mux(negative, y, x)).collect()
}

/// A divisor of a dividend `w` bits wide: its magnitude in `w + 2` bits, whether it is
/// negative, and the width the remainder's steps need: `w + 2`, or for a literal one bit
/// more than its magnitude (the remainder stays below `|d|`, twice it plus a bit below
/// `2·|d|`).
struct Divisor {
    magnitude: Bits,
    negative: L,
    steps: usize,
}

impl Divisor {
    /// The literal `k`.
    fn literal(k: i64, w: usize) -> Divisor {
        let magnitude = constant(k.unsigned_abs() as i64, (w + 2) as u32);
        let steps = (65 - k.unsigned_abs().leading_zeros() as usize).min(w + 2);
        Divisor { magnitude, negative: if k < 0 { L::One } else { L::Zero }, steps }
    }

    /// The value `b` of type `ty` (`|min|` fits in `w + 2` bits).
    fn value(b: &[L], ty: IntType, name: Namer) -> Divisor {
        let (magnitude, negative) = magnitude(b, ty, b.len() + 2, name);
        Divisor { magnitude, negative, steps: b.len() + 2 }
    }
}

/// `|v|` for a value of type `ty`, in `width > ty.bits` bits, and whether `v` is negative.
fn magnitude(v: &[L], ty: IntType, width: usize, name: Namer) -> (Bits, L) {
    let negative = if ty.signed { v.last().cloned().unwrap_or(L::Zero) } else { L::Zero };
    let ext = resize(v.to_vec(), ty, IntType::int(width as u32, ty.signed));
    let minus = sub(&constant(0, width as u32), &ext, name);
    let m = ext.iter().zip(&minus).map(|(x, y)| name(mux(&negative, y, x))).collect();
    (m, negative)
}

/// The quotient (in the width of `a`), the remainder's magnitude (in `w + 2` bits) and
/// whether `a` is negative, by restoring division of magnitudes (a divisor 0 gives a
/// quotient of all ones, which the callers mask).
fn divide(a: &[L], d: &Divisor, ty: IntType, name: Namer) -> (Bits, Bits, L) {
    let w = a.len();
    // |a| in w + 1 bits (|min| fits there), the remainder in `d.steps` bits (it stays
    // below 2·|d|), then given in w + 2.
    let (wide, rw) = (w + 1, d.steps);
    let (magnitude, negative) = magnitude(a, ty, wide, name);
    let unsigned = IntType::int(rw as u32, false);
    let divisor = &d.magnitude[..rw];
    let mut r = constant(0, rw as u32);
    let mut q = vec![L::Zero; wide];
    for i in (0..wide).rev() {
        // r := 2·r + bit i of |a|; if r ≥ |d| then r := r − |d| and bit i of q is 1.
        let mut shifted = vec![magnitude[i].clone()];
        shifted.extend(r[..rw - 1].iter().cloned());
        let fits = compare(CmpOp::Ge, unsigned, &shifted, divisor, name);
        let fits = name(fits);
        let less = sub(&shifted, divisor, name);
        r = shifted.iter().zip(&less).map(|(x, y)| name(mux(&fits, y, x))).collect();
        q[i] = fits;
    }
    // The quotient is negative when exactly one side is.
    let flip = name(xor(&negative, &d.negative));
    let minus_q = sub(&constant(0, wide as u32), &q, name);
    let q = q.iter().zip(&minus_q).take(w).map(|(x, y)| mux(&flip, y, x)).collect();
    r.resize(w + 2, L::Zero);
    (q, r, negative)
}

/// `a op b` for two values of type `ty`.
pub fn compare(op: CmpOp, ty: IntType, a: &[L], b: &[L], name: Namer) -> L {
    let eq = || simplify(L::And(a.iter().zip(b).map(|(x, y)| xor(x, y).negate()).collect()));
    // Signed order is the unsigned order of the values with their sign bits flipped.
    let flip = |v: &[L]| -> Bits {
        let mut v = v.to_vec();
        if ty.signed
            && let Some(top) = v.last_mut()
        {
            *top = top.clone().negate();
        }
        v
    };
    let less = |x: &[L], y: &[L], name: Namer| -> L {
        // From the least significant bit up: x < y on bits 0..=k.
        let mut lt = L::Zero;
        for (p, q) in x.iter().zip(y) {
            let strictly = p.clone().negate().and(q.clone());
            let same = xor(p, q).negate();
            lt = name(simplify(strictly.or(same.and(lt))));
        }
        lt
    };
    let (fa, fb) = (flip(a), flip(b));
    match op {
        CmpOp::Eq => eq(),
        CmpOp::Ne => simplify(eq().negate()),
        CmpOp::Lt => less(&fa, &fb, name),
        CmpOp::Gt => less(&fb, &fa, name),
        CmpOp::Le => simplify(less(&fb, &fa, name).negate()),
        CmpOp::Ge => simplify(less(&fa, &fb, name).negate()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eval(t: &L, env: &dyn Fn(&str) -> bool) -> bool {
        match t {
            L::Zero => false,
            L::One => true,
            L::Var(n) => env(n),
            L::Not(x) => !eval(x, env),
            L::And(xs) => xs.iter().all(|x| eval(x, env)),
            L::Or(xs) => xs.iter().any(|x| eval(x, env)),
            _ => panic!("not Boolean"),
        }
    }

    fn vars(p: &str, w: u32) -> Bits {
        (0..w).map(|k| L::var(&format!("{p}{k}"))).collect()
    }

    /// Every operation on every pair of 4-bit values, signed and unsigned, against
    /// Rust's wrapping arithmetic.
    #[test]
    fn four_bit_arithmetic_is_exact() {
        let w = 4;
        for signed in [false, true] {
            let ty = IntType::int(w, signed);
            let (a, b) = (vars("a", w), vars("b", w));
            let mut keep = |t: L| t;
            let sum = add(&a, &b, L::Zero, &mut keep);
            let diff = sub(&a, &b, &mut keep);
            let prod = mul(&a, &b, &mut keep);
            let ops = [CmpOp::Eq, CmpOp::Ne, CmpOp::Lt, CmpOp::Le, CmpOp::Gt, CmpOp::Ge];
            let cmps: Vec<L> = ops.iter().map(|op| compare(*op, ty, &a, &b, &mut keep)).collect();
            for x in 0..16i64 {
                for y in 0..16i64 {
                    let env = |n: &str| {
                        let k: u32 = n[1..].parse().unwrap();
                        let v = if n.starts_with('a') { x } else { y };
                        v >> k & 1 == 1
                    };
                    let read = |bits: &Bits| {
                        value_of(&bits.iter().map(|t| eval(t, &env)).collect::<Vec<_>>(), ty)
                    };
                    let (vx, vy) = (ty.wrap(x), ty.wrap(y));
                    assert_eq!(read(&sum), ty.wrap(vx + vy), "{vx} + {vy}");
                    assert_eq!(read(&diff), ty.wrap(vx - vy), "{vx} - {vy}");
                    assert_eq!(read(&prod), ty.wrap(vx * vy), "{vx} * {vy}");
                    for (op, c) in ops.iter().zip(&cmps) {
                        assert_eq!(eval(c, &env), op.holds(vx, vy), "{vx} {op:?} {vy}");
                    }
                    if vy != 0 {
                        let quotient = div(&a, vy, ty, &mut keep);
                        assert_eq!(read(&quotient), ty.wrap(vx.wrapping_div(vy)), "{vx} / {vy}");
                        let remainder = rem(&a, vy, ty, &mut keep);
                        assert_eq!(read(&remainder), ty.wrap(vx.wrapping_rem(vy)), "{vx} % {vy}");
                    }
                }
            }
        }
    }

    /// A circuit's named terms, evaluated 64 input pairs at a time.
    struct Circuit {
        defs: Vec<L>,
    }

    impl Circuit {
        fn namer(&mut self) -> impl FnMut(L) -> L + '_ {
            |t: L| match t {
                L::Zero | L::One | L::Var(_) => t,
                t => {
                    self.defs.push(t);
                    L::var(&format!("t{}", self.defs.len() - 1))
                }
            }
        }

        /// The outputs' bits on lanes whose inputs `a{k}`/`b{k}` are the words given.
        fn run(&self, a: &[u64], b: &[u64], outs: &[&Bits]) -> Vec<Vec<u64>> {
            fn word(t: &L, a: &[u64], b: &[u64], defs: &[u64]) -> u64 {
                match t {
                    L::Zero => 0,
                    L::One => !0,
                    L::Var(n) => {
                        let k: usize = n[1..].parse().unwrap();
                        match &n[..1] {
                            "a" => a[k],
                            "b" => b[k],
                            _ => defs[k],
                        }
                    }
                    L::Not(x) => !word(x, a, b, defs),
                    L::And(xs) => xs.iter().fold(!0, |acc, x| acc & word(x, a, b, defs)),
                    L::Or(xs) => xs.iter().fold(0, |acc, x| acc | word(x, a, b, defs)),
                    _ => panic!("not Boolean"),
                }
            }
            let mut defs = Vec::with_capacity(self.defs.len());
            for d in &self.defs {
                let v = word(d, a, b, &defs);
                defs.push(v);
            }
            outs.iter().map(|o| o.iter().map(|t| word(t, a, b, &defs)).collect()).collect()
        }
    }

    /// `a / b` and `a % b` by variables of type `ty`, as circuits.
    fn divider(ty: IntType) -> (Circuit, Bits, Bits) {
        let mut c = Circuit { defs: Vec::new() };
        let (a, b) = (vars("a", ty.bits), vars("b", ty.bits));
        let q = div_by(&a, &b, ty, &mut c.namer());
        let r = rem_by(&a, &b, ty, &mut c.namer());
        (c, q, r)
    }

    /// matiec's `DIV`/`MOD` of two values of `ty` (read as `i64`): Rust's checked
    /// division, 0 for a divisor 0, and the wrapped `min / −1`.
    fn expected(ty: IntType, x: i64, y: i64) -> (i64, i64) {
        macro_rules! checked {
            ($t:ty) => {{
                let (x, y) = (x as $t, y as $t);
                let q = x.checked_div(y).unwrap_or(if y == 0 { 0 } else { x.wrapping_div(y) });
                let r = x.checked_rem(y).unwrap_or(if y == 0 { 0 } else { x.wrapping_rem(y) });
                (q as i64, r as i64)
            }};
        }
        match (ty.bits, ty.signed) {
            (8, true) => checked!(i8),
            (8, false) => checked!(u8),
            (16, true) => checked!(i16),
            (16, false) => checked!(u16),
            (32, true) => checked!(i32),
            _ => checked!(u32),
        }
    }

    /// Reads lane `l` of the output words as a value of `ty`.
    fn lane(words: &[u64], l: usize, ty: IntType) -> i64 {
        let bits: Vec<bool> = words.iter().map(|w| w >> l & 1 == 1).collect();
        value_of(&bits, ty)
    }

    /// Division and remainder by a variable, on every pair of 8-bit values, signed and
    /// unsigned, bit-exactly against Rust's `checked_div`/`checked_rem` (0 for a divisor 0).
    #[test]
    fn eight_bit_division_by_a_variable_is_exact() {
        for signed in [false, true] {
            let ty = IntType::int(8, signed);
            let (c, q, r) = divider(ty);
            for chunk in 0..(65536 / 64) {
                let pair = |l: usize| (chunk * 64 + l) as i64;
                let bit = |v: &dyn Fn(i64) -> i64, k: usize| {
                    (0..64).fold(0u64, |acc, l| acc | (((v(pair(l)) >> k) & 1) as u64) << l)
                };
                let a: Vec<u64> = (0..8).map(|k| bit(&|p| p >> 8, k)).collect();
                let b: Vec<u64> = (0..8).map(|k| bit(&|p| p & 255, k)).collect();
                let out = c.run(&a, &b, &[&q, &r]);
                for l in 0..64 {
                    let (x, y) = (ty.wrap(pair(l) >> 8), ty.wrap(pair(l) & 255));
                    let got = (lane(&out[0], l, ty), lane(&out[1], l, ty));
                    assert_eq!(got, expected(ty, x, y), "{ty:?}: {x} / {y}");
                }
            }
        }
    }

    /// The 16- and 32-bit dividers, unsigned then signed, built once.
    static WIDE_DIVIDERS: std::sync::LazyLock<Vec<(Circuit, Bits, Bits)>> =
        std::sync::LazyLock::new(|| {
            [16, 32]
                .into_iter()
                .flat_map(|bits| [false, true].map(|signed| divider(IntType::int(bits, signed))))
                .collect()
        });

    proptest::proptest! {
        /// The same on random 16- and 32-bit values, divisors 0, ±1 and the smallest
        /// value included.
        #[test]
        fn wide_division_by_a_variable_is_exact(
            bits in proptest::sample::select(vec![16u32, 32]),
            signed: bool,
            x: i64,
            y in proptest::prop_oneof![
                proptest::prelude::any::<i64>(),
                proptest::sample::select(vec![0i64, 1, -1, i64::MIN, 2, -2]),
            ],
        ) {
            let ty = IntType::int(bits, signed);
            let (x, y) = (ty.wrap(x), ty.wrap(if y == i64::MIN { ty.min() } else { y }));
            let (c, q, r) = &WIDE_DIVIDERS[usize::from(bits == 32) * 2 + usize::from(signed)];
            let word = |v: i64| -> Vec<u64> {
                (0..bits).map(|k| if v >> k & 1 == 1 { !0 } else { 0 }).collect()
            };
            let out = c.run(&word(x), &word(y), &[q, r]);
            let got = (lane(&out[0], 0, ty), lane(&out[1], 0, ty));
            proptest::prop_assert_eq!(got, expected(ty, x, y), "{:?}: {} / {}", ty, x, y);
        }
    }

    proptest::proptest! {
        /// Division and remainder by a literal (its remainder in one bit more than the
        /// literal) on random 16- and 32-bit values, literals of every size.
        #[test]
        fn wide_division_by_a_literal_is_exact(
            bits in proptest::sample::select(vec![16u32, 32]),
            signed: bool,
            x: i64,
            k: i64,
            shift in 0u32..40,
        ) {
            let ty = IntType::int(bits, signed);
            let (x, k) = (ty.wrap(x), ty.wrap(k >> shift));
            if k != 0 {
                let mut c = Circuit { defs: Vec::new() };
                let a = vars("a", bits);
                let q = div(&a, k, ty, &mut c.namer());
                let r = rem(&a, k, ty, &mut c.namer());
                let word: Vec<u64> = (0..bits).map(|j| if x >> j & 1 == 1 { !0 } else { 0 }).collect();
                let out = c.run(&word, &[], &[&q, &r]);
                let got = (lane(&out[0], 0, ty), lane(&out[1], 0, ty));
                proptest::prop_assert_eq!(got, expected(ty, x, k), "{:?}: {} / {}", ty, x, k);
            }
        }
    }

    #[test]
    fn constants_fold() {
        let ty = IntType::I16;
        let mut keep = |t: L| t;
        let s = add(&constant(1234, 16), &constant(-34, 16), L::Zero, &mut keep);
        let bits: Vec<bool> = s.iter().map(|t| *t == L::One).collect();
        assert!(s.iter().all(|t| *t == L::One || *t == L::Zero));
        assert_eq!(value_of(&bits, ty), 1200);
        let c = compare(CmpOp::Ge, ty, &constant(-3, 16), &constant(2, 16), &mut keep);
        assert_eq!(c, L::Zero);
    }
}
