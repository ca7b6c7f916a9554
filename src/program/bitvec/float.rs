//! IEEE 754 floating-point circuits on Boolean terms of a number's bits (least significant first: the fraction, the exponent, the sign), for `REAL` (binary32, C's `float`) and C's `double` (binary64), as C computes and compares them on x86-64: a NaN is unordered (every comparison false but `<>`), `-0 = +0`. The format of an operand is told by its width (32 or 64 bits).

use super::super::logic::{L, simplify};
use super::super::{CmpOp, IntType};
use super::{Bits, Namer, add, compare, constant, mux, resize, sub};

/// An IEEE 754 binary format: the widths of its exponent and fraction.
#[derive(Clone, Copy)]
struct Format {
    exponent: usize,
    fraction: usize,
}

/// binary32 (`float`, `REAL`).
const SINGLE: Format = Format { exponent: 8, fraction: 23 };
/// binary64 (`double`).
const DOUBLE: Format = Format { exponent: 11, fraction: 52 };

impl Format {
    /// The format of a number of `width` bits (32 or 64).
    fn of(width: usize) -> Format {
        match width {
            32 => SINGLE,
            64 => DOUBLE,
            _ => panic!("no IEEE 754 format of {width} bits"),
        }
    }

    /// The bits without the sign (also the sign's index).
    fn magnitude(self) -> usize {
        self.exponent + self.fraction
    }

    /// The exponent bias (127, 1023).
    fn bias(self) -> i64 {
        (1 << (self.exponent - 1)) - 1
    }

    /// The biased exponent of `∞` and NaNs (255, 2047).
    fn top(self) -> i64 {
        (1 << self.exponent) - 1
    }

    /// The magnitude bits of `+∞`.
    fn infinity(self) -> i64 {
        self.top() << self.fraction
    }

    /// x86's default NaN (`0xFFC00000`, `0xFFF8000000000000`), with its sign.
    fn default_nan(self) -> i64 {
        (-1i64 << (self.fraction - 1)) & (((1i128 << (self.magnitude() + 1)) - 1) as i64)
    }

    /// The width of the exponents of [`unpack`] and [`round_pack`] (two's complement).
    fn wide_bits(self) -> u32 {
        if self.exponent == 8 { 12 } else { 15 }
    }

    /// The type of those exponents.
    fn wide_ty(self) -> IntType {
        IntType::int(self.wide_bits(), true)
    }

    /// `v` as such an exponent.
    fn wide(self, v: i64) -> Bits {
        constant(v, self.wide_bits())
    }
}

/// The number of doublings that reach `n` (5 for 24 to 32, 6 for 33 to 64).
fn log2_up(n: usize) -> usize {
    (usize::BITS - (n - 1).leading_zeros()) as usize
}

/// Whether a number is a NaN: its exponent all ones and its fraction not 0.
fn is_nan(v: &[L], f: Format) -> L {
    let exponent_ones = L::And(v[f.fraction..f.magnitude()].to_vec().into());
    let fraction = L::Or(v[..f.fraction].to_vec().into());
    simplify(exponent_ones.and(fraction))
}

/// `a op b` for two numbers of one format (`REAL`s or `double`s).
///
/// Apart from NaNs, the order of the numbers is the order of their magnitudes (the bits
/// below the sign, as an unsigned integer) for two positive numbers, reversed for two
/// negative ones, and a negative number is below a positive one unless both are zeros.
pub fn compare_real(op: CmpOp, a: &[L], b: &[L], name: Namer) -> L {
    let f = Format::of(a.len());
    let n = f.magnitude();
    let magnitude = IntType::int(n as u32, false);
    let (ma, mb) = (&a[..n], &b[..n]);
    let (sa, sb) = (a[n].clone(), b[n].clone());
    let lt = compare(CmpOp::Lt, magnitude, ma, mb, name);
    let lt = name(lt);
    let gt = compare(CmpOp::Lt, magnitude, mb, ma, name);
    let gt = name(gt);
    let zeros = simplify(L::And(ma.iter().chain(mb).map(|x| x.clone().negate()).collect()));
    let ordered = name(simplify(is_nan(a, f).or(is_nan(b, f)).negate()));
    let (pa, pb) = (sa.clone().negate(), sb.clone().negate());
    let same_sign = pa.clone().and(pb.clone()).or(sa.clone().and(sb.clone()));
    let same_magnitude = lt.clone().negate().and(gt.clone().negate());
    let eq = ordered.clone().and(zeros.clone().or(same_sign.and(same_magnitude)));
    let below = |sx: &L, px: &L, sy: &L, py: &L, lt: &L, gt: &L| {
        let signs = sx.clone().and(py.clone());
        let positive = px.clone().and(py.clone()).and(lt.clone());
        let negative = sx.clone().and(sy.clone()).and(gt.clone());
        ordered
            .clone()
            .and(zeros.clone().negate())
            .and(L::Or(vec![signs, positive, negative].into()))
    };
    let less = || below(&sa, &pa, &sb, &pb, &lt, &gt);
    let greater = || below(&sb, &pb, &sa, &pa, &gt, &lt);
    simplify(match op {
        CmpOp::Eq => eq,
        CmpOp::Ne => eq.negate(),
        CmpOp::Lt => less(),
        CmpOp::Gt => greater(),
        CmpOp::Le => less().or(eq),
        CmpOp::Ge => greater().or(eq),
    })
}

/// Shifts `m` left until its top bit is 1 (unless it is 0), by halving steps (16, 8, 4,
/// 2, 1 places for `m` at most 32 bits wide; from 32 for at most 64): the number of
/// places, in `width` bits.
fn normalize(m: &mut Bits, width: u32, name: Namer) -> Bits {
    let w = m.len();
    let mut count = vec![L::Zero; width as usize];
    for k in (0..log2_up(w)).rev() {
        let step = 1usize << k;
        let top_zero = name(simplify(L::Or(m[w - step..].to_vec().into()).negate()));
        let shifted: Bits =
            std::iter::repeat_n(L::Zero, step).chain(m[..w - step].iter().cloned()).collect();
        *m = m.iter().zip(&shifted).map(|(p, s)| name(mux(&top_zero, s, p))).collect();
        count[k] = top_zero;
    }
    count
}

/// `x` with every bit of `pattern` where `c` holds (per bit: `c ? pattern : x`).
fn choose(c: &L, pattern: &[L], x: &[L], name: Namer) -> Bits {
    pattern.iter().zip(x).map(|(p, q)| name(mux(c, p, q))).collect()
}

/// Whether all of `v` is 0.
fn all_zero(v: &[L]) -> L {
    simplify(L::Or(v.to_vec().into()).negate())
}

/// An operand taken apart.
struct Unpacked {
    /// The significand, its leading 1 at the top (a subnormal one shifted up).
    m: Bits,
    /// The biased exponent of that leading 1 (below 1 for a subnormal number), in
    /// [`Format::wide_bits`] bits.
    e: Bits,
    zero: L,
    inf: L,
    nan: L,
}

/// A number of format `f` read from its bits: its exponent bits, whether it is
/// subnormal (or 0), and the significand with its hidden bit on top, not normalised.
struct Classes<'a> {
    exponent: &'a [L],
    subnormal: L,
    m: Bits,
    zero: L,
    inf: L,
    nan: L,
}

fn classify<'a>(v: &'a [L], f: Format, name: Namer) -> Classes<'a> {
    let (fraction, exponent) = (&v[..f.fraction], &v[f.fraction..f.magnitude()]);
    let subnormal = all_zero(exponent);
    let ones = simplify(L::And(exponent.to_vec().into()));
    let no_fraction = all_zero(fraction);
    let zero = name(simplify(subnormal.clone().and(no_fraction.clone())));
    let inf = name(simplify(ones.clone().and(no_fraction.clone())));
    let nan = name(simplify(ones.and(no_fraction.negate())));
    let mut m: Bits = fraction.to_vec();
    m.push(subnormal.clone().negate());
    Classes { exponent, subnormal, m, zero, inf, nan }
}

fn unpack(v: &[L], f: Format, name: Namer) -> Unpacked {
    let Classes { exponent, subnormal, mut m, zero, inf, nan } = classify(v, f, name);
    let count = normalize(&mut m, f.wide_bits(), name);
    let pad = f.wide_bits() as usize - f.exponent;
    let e: Bits = exponent.iter().cloned().chain(std::iter::repeat_n(L::Zero, pad)).collect();
    let e = choose(&subnormal, &f.wide(1), &e, name);
    Unpacked { m, e: sub(&e, &count, name), zero, inf, nan }
}

/// The finite result `1.s × 2^(e - bias)` (`s` the fraction's width + 4 bits, its
/// leading 1 at the top; `sticky`: whether anything below them is not 0) rounded to the
/// bits of a number without the sign: shifted right where it is subnormal (`e ≤ 0`, the
/// bits shifted out joining `sticky`), rounded on the guard bit, the bits below it and
/// the last bit kept (ties to even), `∞` where it overflows.
fn round_pack(e: &[L], mut s: Bits, mut sticky: L, f: Format, name: Namer) -> Bits {
    let wide = f.wide_ty();
    let overflow = compare(CmpOp::Ge, wide, e, &f.wide(f.top()), name);
    let overflow = name(overflow);
    // Subnormal: shifted right by 1 - e places (all of it from 2^steps on).
    let steps = log2_up(s.len());
    let t = sub(&f.wide(1), e, name);
    let tiny = compare(CmpOp::Ge, wide, &t, &f.wide(1), name);
    let tiny = name(tiny);
    let far = compare(CmpOp::Ge, wide, &t, &f.wide(1 << steps), name);
    let all_out = name(tiny.clone().and(far));
    for (j, amount) in t.iter().take(steps).enumerate() {
        let step = 1usize << j;
        let on = name(simplify(tiny.clone().and(amount.clone())));
        sticky = name(simplify(sticky.or(on.clone().and(L::Or(s[..step].to_vec().into())))));
        let down: Bits =
            s[step..].iter().cloned().chain(std::iter::repeat_n(L::Zero, step)).collect();
        s = choose(&on, &down, &s, name);
    }
    sticky = name(simplify(sticky.or(all_out.clone().and(L::Or(s.clone().into())))));
    s = choose(&all_out, &constant(0, s.len() as u32), &s, name);
    let exponent = choose(&tiny, &constant(0, f.exponent as u32), &e[..f.exponent], name);
    let fraction = &s[3..3 + f.fraction];
    let sticky = simplify(sticky.or(s[1].clone()).or(s[0].clone()));
    let round = name(simplify(s[2].clone().and(sticky.or(fraction[0].clone()))));
    let unrounded: Bits = fraction.iter().chain(&exponent).cloned().collect();
    let n = f.magnitude() as u32;
    let result = add(&unrounded, &constant(0, n), round, name);
    choose(&overflow, &constant(f.infinity(), n), &result, name)
}

/// `v` made a quiet NaN (its fraction's top bit set), as x86 returns a NaN operand.
fn quiet(v: &[L], f: Format) -> Bits {
    let q = f.fraction - 1;
    v.iter().enumerate().map(|(i, x)| if i == q { L::One } else { x.clone() }).collect()
}

/// The result `±v` (the magnitude bits, then the sign).
fn signed(v: i64, sign: &L, f: Format) -> Bits {
    constant(v, f.magnitude() as u32).into_iter().chain([sign.clone()]).collect()
}

/// `finite` (the magnitude bits) with its sign, unless a special case decides: `zero`
/// gives `±0`, `inf` gives `±∞`, `invalid` the default NaN, a NaN operand itself made
/// quiet (`a`'s first), as x86's `mulss`/`divss` (`mulsd`/`divsd`) do.
#[allow(clippy::too_many_arguments)]
fn special(
    finite: Bits,
    sign: &L,
    (zero, inf, invalid): (L, L, L),
    (a, nan_a): (&[L], &L),
    (b, nan_b): (&[L], &L),
    f: Format,
    name: Namer,
) -> Bits {
    let mut out: Bits = finite.into_iter().chain([sign.clone()]).collect();
    out = choose(&zero, &signed(0, sign, f), &out, name);
    out = choose(&inf, &signed(f.infinity(), sign, f), &out, name);
    out = choose(&invalid, &constant(f.default_nan(), a.len() as u32), &out, name);
    out = choose(nan_b, &quiet(b, f), &out, name);
    choose(nan_a, &quiet(a, f), &out, name)
}

/// `a / b` for two `REAL`s as C computes it on x86-64 (`divss`: the nearest number,
/// ties to even, subnormal results kept), and `+0.0` when `b` is `±0.0`, where matiec's
/// `DIV` returns `__INIT_REAL` (`TEST_EN_COND(REAL, op2 == 0)`). A NaN result is the
/// first NaN operand made quiet, else (`∞/∞`) the default NaN `0xFFC00000`. Of two
/// `double`s, the same in binary64 (`divsd`).
///
/// The significands ([`unpack`]) are divided by restoring division into the fraction's
/// width + 4 quotient bits and a remainder; the quotient, its leading 1 brought to the
/// top, is rounded by [`round_pack`].
pub fn div_real(a: &[L], b: &[L], name: Namer) -> Bits {
    let (y_zero, out) = divide(a, b, false, name);
    choose(&y_zero, &constant(0, a.len() as u32), &out, name)
}

/// `a / b` for two `REAL`s as C's `/` computes it on x86-64 (`divss`), as [`div_real`]
/// but with `b` `±0.0` too: `±∞` for a number, the default NaN for `±0.0` (Structured
/// Text's `/`, which matiec writes as C's). Of two `double`s, `divsd`.
pub fn quotient_real(a: &[L], b: &[L], name: Namer) -> Bits {
    divide(a, b, true, name).1
}

/// `a / b` (`by_zero`: with IEEE 754's `±∞` and NaN where `b` is `±0.0`), and whether
/// `b` is `±0.0`.
fn divide(a: &[L], b: &[L], by_zero: bool, name: Namer) -> (L, Bits) {
    let f = Format::of(a.len());
    let (x, y) = (unpack(a, f, name), unpack(b, f, name));
    let sign = super::xor(&a[f.magnitude()], &b[f.magnitude()]);
    // Restoring division: fraction + 4 quotient bits, most significant first.
    let (qw, rw) = (f.fraction + 4, f.fraction + 3);
    let divisor: Bits = y.m.iter().cloned().chain([L::Zero, L::Zero]).collect();
    let mut r: Bits = x.m.iter().cloned().chain([L::Zero, L::Zero]).collect();
    let mut q = vec![L::Zero; qw];
    for bit in (0..qw).rev() {
        let diff = sub(&r, &divisor, name);
        let fits = name(diff[rw - 1].clone().negate());
        r = choose(&fits, &diff, &r, name);
        q[bit] = fits;
        if bit > 0 {
            r = std::iter::once(L::Zero).chain(r[..rw - 1].iter().cloned()).collect();
        }
    }
    let rest = name(simplify(L::Or(r.into())));
    // The leading 1 at the top (a quotient below 1 is shifted up once).
    let top = q[qw - 1].clone();
    let shifted: Bits = std::iter::once(L::Zero).chain(q[..qw - 1].iter().cloned()).collect();
    let s = choose(&top, &q, &shifted, name);
    let below_one = choose(&top, &f.wide(f.bias()), &f.wide(f.bias() - 1), name);
    let e = add(&sub(&x.e, &y.e, name), &below_one, L::Zero, name);
    let finite = round_pack(&e, s, rest, f, name);
    let to_zero = name(simplify(x.zero.clone().or(y.inf.clone())));
    let (mut inf, mut invalid) = (x.inf.clone(), simplify(x.inf.and(y.inf)));
    if by_zero {
        inf = name(simplify(inf.or(y.zero.clone())));
        invalid = simplify(invalid.or(x.zero.and(y.zero.clone())));
    }
    let specials = (to_zero, inf, invalid);
    let out = special(finite, &sign, specials, (a, &x.nan), (b, &y.nan), f, name);
    (y.zero, out)
}

/// `√a` of a `REAL` as matiec's `SQRT` computes it (C's `sqrt` of the `float` made a
/// `double`, the result made a `float` again: the nearest `float` to the root, as
/// `sqrtss` gives it, since a `double` holds more than twice a `float`'s bits): `-0.0`
/// of `-0.0`, `+∞` of `+∞`, the default NaN `0xFFC00000` of a number below 0 (`-∞`
/// too), a NaN operand made quiet. Of a `double`, `sqrtsd`.
///
/// The significand ([`unpack`]), doubled where the exponent is odd, is a number in
/// `[1, 4)` whose root, in the fraction's width + 4 bits, is taken a bit at a time
/// (restoring square root: two bits of the radicand brought down per root bit, the
/// trial `4·root + 1` subtracted where it fits); the remainder joins the sticky bit of
/// [`round_pack`], the exponent is halved.
pub fn sqrt_real(a: &[L], name: Namer) -> Bits {
    let f = Format::of(a.len());
    let x = unpack(a, f, name);
    let sign = a[f.magnitude()].clone();
    // The unbiased exponent, its parity, and its half rounded down (an arithmetic shift).
    let e = sub(&x.e, &f.wide(f.bias()), name);
    let odd = e[0].clone();
    let top = e[e.len() - 1].clone();
    let half: Bits = e[1..].iter().cloned().chain([top]).collect();
    let exponent = add(&half, &f.wide(f.bias()), L::Zero, name);
    // The radicand: the significand (fraction + 1 bits) shifted up by fraction + 6
    // places, one more where the exponent is odd: 2n bits for an n-bit root.
    let n = f.fraction + 4;
    let shift = |by: usize| -> Bits {
        let mut r: Bits = std::iter::repeat_n(L::Zero, by).chain(x.m.iter().cloned()).collect();
        r.resize(2 * n, L::Zero);
        r
    };
    let radicand = choose(&odd, &shift(f.fraction + 7), &shift(f.fraction + 6), name);
    // The remainder stays below 2^(n + 2): one bit more holds the trial's sign.
    let w = n + 3;
    let mut rem = vec![L::Zero; w];
    let mut root = vec![L::Zero; n];
    for i in (0..n).rev() {
        rem = [radicand[2 * i].clone(), radicand[2 * i + 1].clone()]
            .into_iter()
            .chain(rem[..w - 2].iter().cloned())
            .collect();
        let mut trial: Bits =
            [L::One, L::Zero].into_iter().chain(root[i + 1..].iter().cloned()).collect();
        trial.resize(w, L::Zero);
        let diff = sub(&rem, &trial, name);
        let fits = name(diff[w - 1].clone().negate());
        rem = choose(&fits, &diff, &rem, name);
        root[i] = fits;
    }
    let sticky = name(simplify(L::Or(rem.into())));
    let finite = round_pack(&exponent, root, sticky, f, name);
    let mut out: Bits = finite.into_iter().chain([L::Zero]).collect();
    out = choose(&x.inf, &signed(f.infinity(), &L::Zero, f), &out, name);
    let below = name(simplify(sign.and(x.zero.clone().negate()).and(x.nan.clone().negate())));
    out = choose(&below, &constant(f.default_nan(), a.len() as u32), &out, name);
    out = choose(&x.zero, a, &out, name);
    choose(&x.nan, &quiet(a, f), &out, name)
}

/// `a * b` for two `REAL`s as C computes it on x86-64 (`mulss`: the nearest number,
/// ties to even, subnormal results kept; a NaN result is the first NaN operand made
/// quiet, else (`0 × ∞`) the default NaN `0xFFC00000`); of two `double`s, `mulsd`. Of
/// two NaN operands the C compiler may put either first (the product commutes): which
/// NaN results is then taken to be `a`'s, a choice no comparison, conversion to BOOL or
/// other operation on it can tell apart.
///
/// The product of the significands ([`unpack`]), its leading 1 brought to the top,
/// keeps its top fraction + 4 bits, the rest joining the sticky bit of [`round_pack`].
pub fn mul_real(a: &[L], b: &[L], name: Namer) -> Bits {
    let f = Format::of(a.len());
    let (x, y) = (unpack(a, f, name), unpack(b, f, name));
    let sign = super::xor(&a[f.magnitude()], &b[f.magnitude()]);
    let p = f.fraction + 1;
    let widen =
        |m: &[L]| -> Bits { m.iter().cloned().chain(std::iter::repeat_n(L::Zero, p)).collect() };
    let product = super::mul(&widen(&x.m), &widen(&y.m), name);
    let top = product[2 * p - 1].clone();
    let shifted: Bits =
        std::iter::once(L::Zero).chain(product[..2 * p - 1].iter().cloned()).collect();
    let product = choose(&top, &product, &shifted, name);
    let low = f.fraction - 2;
    let sticky = name(simplify(L::Or(product[..low].to_vec().into())));
    let s = product[low..].to_vec();
    // 1.s × 2^(ea - bias) × 1.t × 2^(eb - bias), the product's leading 1 at 2^1 or 2^0.
    let offset = choose(&top, &f.wide(1 - f.bias()), &f.wide(-f.bias()), name);
    let e = add(&add(&x.e, &y.e, L::Zero, name), &offset, L::Zero, name);
    let finite = round_pack(&e, s, sticky, f, name);
    let zero = simplify(x.zero.clone().or(y.zero.clone()));
    let inf = simplify(x.inf.clone().or(y.inf.clone()));
    let invalid = name(simplify(zero.clone().and(inf.clone())));
    let specials = (name(zero), name(inf), invalid);
    special(finite, &sign, specials, (a, &x.nan), (b, &y.nan), f, name)
}

/// `a + b` for two `REAL`s as C computes it on x86-64 (`addss`: the nearest number,
/// ties to even, subnormal results kept; an exact zero sum is `+0.0` unless both are
/// `-0.0`; a NaN result is the first NaN operand made quiet, else (`∞ - ∞`) the default
/// NaN `0xFFC00000`); of two `double`s, `addsd`. Of two NaN operands the C compiler may
/// put either first: which NaN results is taken to be `a`'s, as for [`mul_real`].
/// `subtract` gives `a - b` (`b`'s sign flipped, a NaN `b` kept as it is, as `subss`
/// does).
///
/// The operand of the larger magnitude first; the other's significand, with three bits
/// more (guard, round and a sticky bit collecting what is shifted out), shifted right
/// by the difference of the exponents; added or subtracted; a carry shifted back, a
/// cancellation normalised; then rounded by [`round_pack`].
pub fn add_real(a: &[L], b: &[L], subtract: bool, name: Namer) -> Bits {
    let f = Format::of(a.len());
    let n = f.magnitude();
    let sb = if subtract { b[n].clone().negate() } else { b[n].clone() };
    let b_signed: Bits = b[..n].iter().cloned().chain([sb]).collect();
    let magnitude = IntType::int(n as u32, false);
    let swap = compare(CmpOp::Lt, magnitude, &a[..n], &b[..n], name);
    let swap = name(swap);
    let (big, small) = (choose(&swap, &b_signed, a, name), choose(&swap, a, &b_signed, name));
    let pad = f.wide_bits() as usize - f.exponent;
    // Unpacked without normalising: `m × 2^(e - bias - fraction - 3)`, `e` at least 1.
    let parts = |v: &[L], name: Namer| -> (Bits, Bits) {
        let subnormal = all_zero(&v[f.fraction..n]);
        let m: Bits = [L::Zero, L::Zero, L::Zero]
            .into_iter()
            .chain(v[..f.fraction].iter().cloned())
            .chain([subnormal.clone().negate()])
            .collect();
        let e: Bits =
            v[f.fraction..n].iter().cloned().chain(std::iter::repeat_n(L::Zero, pad)).collect();
        (m, choose(&subnormal, &f.wide(1), &e, name))
    };
    let (mx, ex) = parts(&big, name);
    let (mut my, ey) = parts(&small, name);
    let width = mx.len();
    let steps = log2_up(width);
    let d = sub(&ex, &ey, name);
    // Shifted right by d, what leaves kept as a sticky bit 0.
    let far = compare(CmpOp::Ge, f.wide_ty(), &d, &f.wide(1 << steps), name);
    let far = name(far);
    let mut sticky = L::Zero;
    for (j, amount) in d.iter().take(steps).enumerate() {
        let step = 1usize << j;
        sticky = name(simplify(sticky.or(amount.clone().and(L::Or(my[..step].to_vec().into())))));
        let down: Bits =
            my[step..].iter().cloned().chain(std::iter::repeat_n(L::Zero, step)).collect();
        my = choose(amount, &down, &my, name);
    }
    sticky = name(simplify(sticky.or(far.clone().and(L::Or(my.clone().into())))));
    my = choose(&far, &constant(0, width as u32), &my, name);
    my[0] = simplify(my[0].clone().or(sticky));
    let same = name(simplify(super::xor(&big[n], &small[n]).negate()));
    let (mx1, my1): (Bits, Bits) = (
        mx.iter().cloned().chain([L::Zero]).collect(),
        my.iter().cloned().chain([L::Zero]).collect(),
    );
    let sum = add(&mx1, &my1, L::Zero, name);
    let difference = sub(&mx1, &my1, name);
    let total = choose(&same, &sum, &difference, name);
    // A carry: shifted right once (its last bit kept as sticky), the exponent one up.
    let carry = total[width].clone();
    let mut down: Bits = total[1..].to_vec();
    down[0] = simplify(down[0].clone().or(total[0].clone()));
    let mut s = choose(&carry, &down, &total[..width], name);
    let e = add(&ex, &constant(0, f.wide_bits()), carry, name);
    let cancelled = all_zero(&s);
    let count = normalize(&mut s, f.wide_bits(), name);
    let e = sub(&e, &count, name);
    let finite = round_pack(&e, s, L::Zero, f, name);
    let (x, y) = (unpack(a, f, name), unpack(b, f, name));
    let inf = simplify(x.inf.clone().or(y.inf.clone()));
    // An exact zero: -0.0 only for two negative zeros (same signs).
    let exact_zero = name(simplify(cancelled.and(inf.clone().negate())));
    let zero_sign = simplify(same.clone().and(big[n].clone()));
    let sign = choose(&exact_zero, &[zero_sign], &[big[n].clone()], name).remove(0);
    let opposite_inf = simplify(x.inf.and(y.inf).and(same.negate()));
    // `±∞` takes the sign of the infinite operand, which the larger magnitude is.
    let specials = (exact_zero, name(inf), name(opposite_inf));
    special(finite, &sign, specials, (a, &x.nan), (b, &y.nan), f, name)
}

/// `a`, a `REAL` (32 bits), as a `double` (64 bits), as C promotes a `float`
/// (`cvtss2sd`): exactly, a subnormal number normalised; a NaN keeps its sign and
/// fraction (shifted to the top of the wider one) and is made quiet.
pub fn widen_real(a: &[L], name: Namer) -> Bits {
    let x = unpack(a, SINGLE, name);
    // The leading 1 of `x.m` dropped; the exponent rebiased (1023 - 127) into 11 bits.
    let e = add(&x.e, &constant(DOUBLE.bias() - SINGLE.bias(), 12), L::Zero, name);
    let low = DOUBLE.fraction - SINGLE.fraction;
    let finite: Bits = std::iter::repeat_n(L::Zero, low)
        .chain(x.m[..SINGLE.fraction].iter().cloned())
        .chain(e[..DOUBLE.exponent].iter().cloned())
        .collect();
    let nan: Bits = std::iter::repeat_n(L::Zero, low)
        .chain(quiet(&a[..SINGLE.fraction], SINGLE))
        .chain(std::iter::repeat_n(L::One, DOUBLE.exponent))
        .collect();
    let mut out = choose(&x.zero, &constant(0, 63), &finite, name);
    out = choose(&x.inf, &constant(DOUBLE.infinity(), 63), &out, name);
    out = choose(&x.nan, &nan, &out, name);
    out.push(a[31].clone());
    out
}

/// `a`, a `double` (64 bits), as a `REAL` (32 bits), as C converts a `double` to `float`
/// (`cvtsd2ss`): the nearest number, ties to even, subnormal results kept, `±∞` beyond
/// the largest; a NaN keeps its sign and the top of its fraction and is made quiet.
///
/// The significand is not normalised: a subnormal `double` (below `2^-1022`) is far
/// below half the least subnormal `float`, and [`round_pack`] shifts it out to `±0`.
pub fn narrow_real(a: &[L], name: Namer) -> Bits {
    let Classes { exponent, subnormal, m, zero, inf, nan } = classify(a, DOUBLE, name);
    // The significand's top 27 bits (the leading 1 at bit 26, a subnormal's lower), the
    // rest sticky.
    let cut = DOUBLE.fraction + 1 - (SINGLE.fraction + 4);
    let sticky = name(simplify(L::Or(m[..cut].to_vec().into())));
    let s = m[cut..].to_vec();
    let e: Bits = exponent.iter().cloned().chain([L::Zero]).collect();
    let e = choose(&subnormal, &constant(1, 12), &e, name);
    // Biased exponents of doubles (1 to 2046) minus 896 fit the 12 bits of binary32's.
    let e = sub(&e, &constant(DOUBLE.bias() - SINGLE.bias(), 12), name);
    let finite = round_pack(&e, s, sticky, SINGLE, name);
    let quiet_nan: Bits = quiet(&a[DOUBLE.fraction - SINGLE.fraction..DOUBLE.fraction], SINGLE)
        .into_iter()
        .chain(std::iter::repeat_n(L::One, SINGLE.exponent))
        .collect();
    let mut out = choose(&zero, &constant(0, 31), &finite, name);
    out = choose(&inf, &constant(SINGLE.infinity(), 31), &out, name);
    out = choose(&nan, &quiet_nan, &out, name);
    out.push(a[63].clone());
    out
}

/// `a`, an integer of type `ty` (at most 32 bits), as the nearest `REAL` (ties to
/// even), as C converts an integer to `float`.
///
/// The magnitude (in 32 bits: `-(-2^31)` is `2^31` there) is normalised so that its
/// leading 1 is bit 31, counting the shift; the 23 bits below the leading 1 are the
/// fraction, the next bit decides the rounding with the bits below it (sticky) and the
/// fraction's last bit (ties to even); the rounding is added to the exponent and
/// fraction together, so that a fraction carried over raises the exponent.
pub fn int_to_real(a: &[L], ty: IntType, name: Namer) -> Bits {
    let word = IntType::int(32, ty.signed);
    let x = resize(a.to_vec(), ty, word);
    let sign = if ty.signed { name(x[31].clone()) } else { L::Zero };
    let negated = sub(&constant(0, 32), &x, name);
    let mut m: Bits = x.iter().zip(&negated).map(|(p, n)| name(mux(&sign, n, p))).collect();
    let zero = name(simplify(L::Or(m.clone().into()).negate()));
    let count = normalize(&mut m, 8, name);
    // The leading 1 at bit 31 - count: exponent 127 + 31 - count.
    let exponent = sub(&constant(158, 8), &count, name);
    let fraction = &m[8..31];
    let guard = &m[7];
    let sticky = L::Or(m[..7].to_vec().into());
    let round = name(simplify(guard.clone().and(sticky.or(fraction[0].clone()))));
    let unrounded: Bits = fraction.iter().chain(&exponent).cloned().collect();
    let rounded = add(&unrounded, &constant(0, 31), round, name);
    let not_zero = zero.negate();
    rounded
        .iter()
        .chain(std::iter::once(&sign))
        .map(|b| simplify(b.clone().and(not_zero.clone())))
        .collect()
}

/// `a`, a `REAL`, as matiec's `REAL_TO_*` converts it ([`IntExpr::FromReal`]
/// (crate::program::IntExpr::FromReal)): rounded to the nearest integer, ties to even,
/// in `w` bits (the integer wrapped to them); with `unsigned` 0 for a negative number.
/// Where C leaves the conversion undefined (a NaN or `±∞`, `|a| ≥ 2^63`) the result is 0,
/// as it is for `-2^63` (0 modulo `2^w`).
///
/// A number of biased exponent `e ≥ 126` (`|a| ≥ 0.5`) is its significand `1.f` (24
/// bits) shifted left by `e - 126` in a fixed-point number of `24 + w` bits, 24 of them
/// below the point (the bits shifted past the top only add multiples of `2^w`); the
/// integer part is rounded on the first bit below the point, the bits below it and its
/// own last bit (ties to even). Smaller numbers, subnormal ones among them, round to 0.
pub fn real_to_int(a: &[L], unsigned: bool, w: u32, name: Namer) -> Bits {
    let w = w as usize;
    let width = 24 + w;
    let e: Bits = a[23..31].iter().cloned().chain(std::iter::repeat_n(L::Zero, 4)).collect();
    let (wide, ty) = (|v| SINGLE.wide(v), SINGLE.wide_ty());
    let shift = sub(&e, &wide(126), name);
    let half = compare(CmpOp::Ge, ty, &shift, &wide(0), name);
    let far = compare(CmpOp::Ge, ty, &shift, &wide(64), name);
    let rounds = name(simplify(half.and(far.negate())));
    let mut f: Bits = a[..23].to_vec();
    f.push(L::One);
    f.extend(std::iter::repeat_n(L::Zero, w));
    for (j, on) in shift.iter().take(6).enumerate() {
        let step = 1usize << j;
        let up: Bits = std::iter::repeat_n(L::Zero, step.min(width))
            .chain(f[..width.saturating_sub(step)].iter().cloned())
            .collect();
        f = choose(on, &up, &f, name);
    }
    let sticky = L::Or(f[..23].to_vec().into());
    let round = name(simplify(f[23].clone().and(sticky.or(f[24].clone()))));
    let magnitude = add(&f[24..], &constant(0, w as u32), round, name);
    let magnitude: Bits =
        magnitude.iter().map(|b| simplify(b.clone().and(rounds.clone()))).collect();
    let sign = a[31].clone();
    if unsigned {
        return magnitude.iter().map(|b| simplify(b.clone().and(sign.clone().negate()))).collect();
    }
    let negated = sub(&constant(0, w as u32), &magnitude, name);
    choose(&sign, &negated, &magnitude, name)
}

#[cfg(test)]
mod tests {
    use super::super::constant;
    use super::*;
    use crate::program::real;
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

    const OPS: [CmpOp; 6] = [CmpOp::Eq, CmpOp::Ne, CmpOp::Lt, CmpOp::Le, CmpOp::Gt, CmpOp::Ge];

    /// The circuit on the constant bits of `x` and `y`, against `f32`'s comparisons.
    fn agrees(x: u32, y: u32) -> Result<(), TestCaseError> {
        let (a, b) = (constant(i64::from(x), 32), constant(i64::from(y), 32));
        for op in OPS {
            let got = eval(&compare_real(op, &a, &b, &mut |t| t));
            let want = real::holds(op, i64::from(x), i64::from(y));
            prop_assert_eq!(got, want, "{:?} {:?} {:?}", f32::from_bits(x), op, f32::from_bits(y));
        }
        Ok(())
    }

    /// The hard values: zeros, the smallest and largest subnormals and normals,
    /// infinities, NaNs (quiet, signalling, negative), `2^24 + 1` and its neighbours.
    fn hard() -> Vec<u32> {
        let mut v = vec![0, 1, 0x007f_ffff, 0x0080_0000, 0x7f7f_ffff, 0x7f80_0000, 0x7fc0_0000];
        v.extend([0x7f80_0001, 0x7fff_ffff, 16_777_217f32.to_bits(), 16_777_216f32.to_bits()]);
        v.extend([1.0f32.to_bits(), 2.5f32.to_bits(), 0.1f32.to_bits()]);
        let negatives: Vec<u32> = v.iter().map(|x| x | 0x8000_0000).collect();
        v.extend(negatives);
        v
    }

    #[test]
    fn hard_values_compare_as_f32() {
        for &x in &hard() {
            for &y in &hard() {
                agrees(x, y).unwrap();
            }
        }
    }

    /// The conversion on the constant bits of `v` (a value of `ty`), against Rust's `as
    /// f32` (round to nearest, ties to even).
    fn converts(v: i64, ty: IntType) -> Result<(), TestCaseError> {
        let bits = constant(v, ty.bits);
        let got = int_to_real(&bits, ty, &mut |t| t);
        let got = got.iter().enumerate().fold(0u32, |acc, (k, b)| acc | (u32::from(eval(b)) << k));
        prop_assert_eq!(f32::from_bits(got).to_bits(), (v as f32).to_bits(), "{} in {:?}", v, ty);
        Ok(())
    }

    const TYPES: [(u32, bool); 6] =
        [(8, true), (8, false), (16, true), (16, false), (32, true), (32, false)];

    #[test]
    fn hard_integers_convert_as_c() {
        let near = |k: i64| [k - 1, k, k + 1];
        let mut vs = vec![0, 1, -1, 127, -128, 255, 32767, -32768, 65535];
        for p in [24, 25, 26, 30, 31, 32] {
            vs.extend(near(1 << p));
            vs.extend(near(-(1 << p)));
            vs.extend(near((1 << p) + (1 << (p - 24))));
            vs.extend(near((1 << p) + 3 * (1 << (p - 24))));
        }
        vs.extend([i64::from(i32::MAX), i64::from(i32::MIN), i64::from(u32::MAX)]);
        for (bits, signed) in TYPES {
            let ty = IntType::int(bits, signed);
            for &v in &vs {
                if ty.contains(v) {
                    converts(v, ty).unwrap();
                }
            }
        }
    }

    /// The conversion to an integer of `w` bits on the constant bits of `x`, against
    /// [`real::to_int`] wrapped to `w` bits (0 where C leaves it undefined).
    fn rounds(x: u32, unsigned: bool, w: u32) -> Result<(), TestCaseError> {
        let got = real_to_int(&constant(i64::from(x), 32), unsigned, w, &mut |t| t);
        let got = got.iter().enumerate().fold(0i64, |acc, (k, b)| acc | (i64::from(eval(b)) << k));
        let ty = IntType::int(w, false);
        let want = ty.wrap(real::to_int(i64::from(x), unsigned).unwrap_or(0));
        prop_assert_eq!(got, want, "{:?} {} in {} bits", f32::from_bits(x), unsigned, w);
        Ok(())
    }

    /// The widths of the types `REAL_TO_*` converts to, and the scan model's widest.
    const WIDTHS: [u32; 4] = [8, 16, 32, 63];

    #[test]
    fn hard_values_convert_to_integers_as_matiec() {
        let mut vs = hard_operands();
        let near = [0.5f32, 1.5, 2.5, -0.5, -2.5, 8_388_607.5, 8_388_608.5, 4_194_304.5];
        vs.extend(near.iter().flat_map(|x| [x.to_bits(), x.to_bits() + 1, x.to_bits() - 1]));
        for p in [23, 24, 31, 32, 52, 53, 62, 63, 64] {
            let x = 2f32.powi(p).to_bits();
            vs.extend([x - 1, x, x + 1, x | 0x8000_0000, (x - 1) | 0x8000_0000]);
        }
        for &x in &vs {
            for w in WIDTHS {
                rounds(x, false, w).unwrap();
                rounds(x, true, w).unwrap();
            }
        }
    }

    /// A circuit of two `REAL`s.
    type Circuit<'a> = &'a dyn Fn(&[L], &[L], Namer) -> Bits;

    /// An operation's circuit on the constant bits of `x` and `y`, against its `f32`
    /// reference (`program/real.rs`).
    fn computes(
        x: u32,
        y: u32,
        circuit: Circuit,
        reference: fn(i64, i64) -> i64,
    ) -> Result<(), TestCaseError> {
        let (a, b) = (constant(i64::from(x), 32), constant(i64::from(y), 32));
        let got = circuit(&a, &b, &mut |t| t);
        let got = got.iter().enumerate().fold(0u32, |acc, (k, b)| acc | (u32::from(eval(b)) << k));
        let want = reference(i64::from(x), i64::from(y)) as u32;
        let (p, q) = (f32::from_bits(x), f32::from_bits(y));
        prop_assert_eq!(got, want, "{:?}, {:?}: {:08x}, not {:08x}", p, q, got, want);
        Ok(())
    }

    /// The division (0 for a divisor ±0, as matiec's `DIV`), and C's `/`.
    fn divides(x: u32, y: u32) -> Result<(), TestCaseError> {
        computes(x, y, &|a, b, n| div_real(a, b, n), real::div)?;
        computes(x, y, &|a, b, n| quotient_real(a, b, n), real::quotient)
    }

    /// The product.
    fn multiplies(x: u32, y: u32) -> Result<(), TestCaseError> {
        computes(x, y, &|a, b, n| mul_real(a, b, n), real::mul)
    }

    /// The sum, or the difference.
    fn adds(x: u32, y: u32, subtract: bool) -> Result<(), TestCaseError> {
        let reference = if subtract { real::sub } else { real::add };
        computes(x, y, &|a, b, n| add_real(a, b, subtract, n), reference)
    }

    #[test]
    fn hard_values_add_as_f32() {
        for &x in &hard_operands() {
            for &y in &hard_operands() {
                adds(x, y, false).unwrap();
                adds(x, y, true).unwrap();
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(3000))]
        #[test]
        fn random_values_add_as_f32(x in any::<u32>(), y in any::<u32>(), ey in 0u32..40, low in 0u32..24) {
            adds(x, y, false)?;
            adds(x, y, true)?;
            // Exponents near each other (cancellation, carries, ties) and far apart.
            let near = (x & 0x807f_ffff) | ((((x >> 23) & 0xff) + ey).min(254) << 23);
            adds(x, near, false)?;
            adds(x, near, true)?;
            adds(x, (x ^ 0x8000_0000) >> low << low, false)?;
            adds(x, x.wrapping_add(low), true)?;
        }
    }

    #[test]
    fn hard_values_multiply_as_f32() {
        for &x in &hard_operands() {
            for &y in &hard_operands() {
                multiplies(x, y).unwrap();
            }
        }
    }

    /// [`hard`], and values whose quotients and products round, overflow or underflow.
    fn hard_operands() -> Vec<u32> {
        let mut vs = hard();
        vs.extend(
            [3.0f32, 7.0, 0.75, 1e-40, 1e38, 1.1754942e-38, 2.9e-39, 6e-45].map(f32::to_bits),
        );
        vs.extend([0x7fc0_1234, 0xffbf_0001, 0x3f80_0001, 0x3fff_ffff, 0x1f80_0001, 0x2000_0000]);
        vs
    }

    #[test]
    fn hard_values_divide_as_f32() {
        let mut vs = hard();
        vs.extend(
            [3.0f32, 7.0, 0.75, 1e-40, 1e38, 1.1754942e-38, 2.9e-39, 6e-45].map(f32::to_bits),
        );
        vs.extend([0x7fc0_1234, 0xffbf_0001, 0x3f80_0001, 0x3fff_ffff]);
        for &x in &vs {
            for &y in &vs {
                divides(x, y).unwrap();
            }
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]
        #[test]
        fn random_values_divide_as_f32(x in any::<u32>(), y in any::<u32>(), ex in 0u32..255, ey in 0u32..255) {
            divides(x, y)?;
            // Exponents near each other and near the ends: results that are subnormal,
            // overflow, or round.
            let near = |v: u32, e: u32| v & 0x807f_ffff | (e << 23);
            divides(near(x, ex), near(y, ex.saturating_sub(ey % 30)))?;
            divides(near(x, ex % 40), near(y, 200 + ey % 55))?;
            divides(near(x, 200 + ex % 55), near(y, ey % 60))?;
        }

        #[test]
        fn random_values_multiply_as_f32(x in any::<u32>(), y in any::<u32>(), ex in 0u32..255, ey in 0u32..255) {
            multiplies(x, y)?;
            // Exponents whose sum is near the ends: products that are subnormal, overflow,
            // or round.
            let near = |v: u32, e: u32| v & 0x807f_ffff | (e << 23);
            multiplies(near(x, ex), near(y, (254u32 + 127).saturating_sub(ex + ey % 30).min(254)))?;
            multiplies(near(x, ex % 80), near(y, (127u32 + ey % 40).saturating_sub(ex % 80 + 20)))?;
            multiplies(near(x, 120 + ex % 20), near(y, ey))?;
        }

        #[test]
        fn random_integers_convert_as_c(v in any::<i64>(), t in 0usize..6, low in 0u32..32) {
            let (bits, signed) = TYPES[t];
            let ty = IntType::int(bits, signed);
            converts(ty.wrap(v), ty)?;
            // Values of few significant bits, where ties are frequent.
            converts(ty.wrap(v >> low << low), ty)?;
        }

        #[test]
        fn random_values_convert_to_integers_as_matiec(x in any::<u32>(), e in 110u32..200, w in 0usize..4) {
            rounds(x, false, WIDTHS[w])?;
            rounds(x, true, WIDTHS[w])?;
            // Exponents where the number rounds: halves, ties, the LINT range's end.
            let near = x & 0x807f_ffff | (e << 23);
            rounds(near, false, WIDTHS[w])?;
            rounds(near, true, WIDTHS[w])?;
        }

        #[test]
        fn random_values_compare_as_f32(x in any::<u32>(), y in any::<u32>(), near in 0u32..4) {
            agrees(x, y)?;
            // Neighbours: equal magnitudes, opposite signs, adjacent patterns.
            agrees(x, x ^ 0x8000_0000)?;
            agrees(x, x.wrapping_add(near))?;
        }

        #[test]
        fn numbers_compare_as_f32(x in any::<f32>(), y in any::<i16>()) {
            agrees(x.to_bits(), f32::from(y).to_bits())?;
        }
    }
}
