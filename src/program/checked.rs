//! C's signed arithmetic in the scan model: an operation whose exact result does not fit its signed type is one C leaves undefined, so its value there is a free integer's, never a wrapped one.

use super::{IntExpr, IntType};

/// `a op b` of two values of the signed type `ty` (C's 32-bit `int`, what matiec's C
/// computes `DINT`s and every narrower type in), as C computes it: the exact result where
/// it fits `ty`; where it does not (`+`, `-` or `*` overflowing; `/` or `%` of the type's
/// least value by −1), which C leaves undefined, the value of the free integer
/// `undefined` (an input of type `ty`: any value at every scan).
#[derive(Clone, Debug)]
pub struct Checked {
    /// The operation.
    pub op: CheckedOp,
    /// Left operand, computed in `ty`.
    pub a: IntExpr,
    /// Right operand, computed in `ty`.
    pub b: IntExpr,
    /// The signed type the operation is computed in.
    pub ty: IntType,
    /// The free integer whose value the result takes where C leaves it undefined.
    pub undefined: String,
}

/// The operation of a [`Checked`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CheckedOp {
    /// `a + b`.
    Add,
    /// `a - b`.
    Sub,
    /// `a * b`.
    Mul,
    /// `a / b` truncated toward zero, and 0 for `b = 0` (matiec's `DIV`; a front end
    /// writes C's `/` here only with a divisor that is not 0).
    Div,
    /// `a % b` with the sign of `a`, and 0 for `b = 0` (matiec's `MOD`).
    Mod,
}

impl CheckedOp {
    /// The exact result for two values, `None` where it does not fit `ty` (where C
    /// leaves it undefined).
    pub fn apply(self, a: i64, b: i64, ty: IntType) -> Option<i64> {
        let (x, y) = (i128::from(a), i128::from(b));
        let exact = match self {
            CheckedOp::Add => x + y,
            CheckedOp::Sub => x - y,
            CheckedOp::Mul => x * y,
            CheckedOp::Div | CheckedOp::Mod if y == 0 => 0,
            CheckedOp::Div => x / y,
            // `MIN % -1` is 0, yet C computes it by the division that overflows.
            CheckedOp::Mod => {
                i64::try_from(x / y).ok().filter(|q| ty.contains(*q))?;
                x % y
            }
        };
        i64::try_from(exact).ok().filter(|v| ty.contains(*v))
    }

    /// The bounds of the exact result for operands within these bounds (inclusive), so a
    /// front end knows where no overflow can happen.
    pub fn bounds(self, a: (i128, i128), b: (i128, i128)) -> (i128, i128) {
        let corners = |f: fn(i128, i128) -> i128| {
            let v = [f(a.0, b.0), f(a.0, b.1), f(a.1, b.0), f(a.1, b.1)];
            (v.iter().copied().min().unwrap_or(0), v.iter().copied().max().unwrap_or(0))
        };
        match self {
            CheckedOp::Add => corners(|x, y| x + y),
            CheckedOp::Sub => corners(|x, y| x - y),
            CheckedOp::Mul => corners(|x, y| x * y),
            // |a / b| <= |a|; only a divisor -1 reaches -a, and the quotient is what
            // overflows for `%` too.
            CheckedOp::Div | CheckedOp::Mod => {
                let m = a.0.abs().max(a.1.abs());
                let by_minus_one = b.0 <= -1 && -1 <= b.1;
                let hi = if by_minus_one { m } else { m.min(a.1.max(-a.0 - 1)).max(0) };
                (-m, hi)
            }
        }
    }
}

/// C's `int` on the machines matiec's C runs on: what `DINT`s and every narrower type
/// are computed in (integer promotion).
pub const C_INT: IntType = IntType::int(32, true);

/// The type C computes a value of type `t` in (integer promotion).
pub fn promoted(t: IntType) -> IntType {
    if t.bits < 32 && !t.real { C_INT } else { t }
}

/// `a op b` for two values of the integer type `t` (a literal's its own) as matiec's
/// standard functions compute one step, `op1 = op1 OP op2`: in [`promoted`]`(t)`, a
/// [`Checked`] operation with the free integer `undefined` where that is C's `int` and
/// two such operands can overflow it (`DINT + DINT`, `UINT * UINT`), else the plain
/// operation (`INT + INT`, every `UDINT` one, which C wraps). `None` for a division by the
/// literal 0, which a front end treats itself.
pub fn c_operation(
    op: CheckedOp,
    a: IntExpr,
    b: IntExpr,
    t: IntType,
    undefined: &str,
) -> Option<IntExpr> {
    let bounds = |x: &IntExpr| match x {
        IntExpr::Const(k) => (i128::from(*k), i128::from(*k)),
        _ => (i128::from(t.min()), i128::from(t.max())),
    };
    let (lo, hi) = op.bounds(bounds(&a), bounds(&b));
    if promoted(t) == C_INT && (lo < i128::from(C_INT.min()) || hi > i128::from(C_INT.max())) {
        let undefined = undefined.to_string();
        return Some(IntExpr::Checked(Box::new(Checked { op, a, b, ty: C_INT, undefined })));
    }
    let (x, y) = (Box::new(a), Box::new(b));
    Some(match (op, *y) {
        (CheckedOp::Add, y) => IntExpr::Add(x, Box::new(y)),
        (CheckedOp::Sub, y) => IntExpr::Sub(x, Box::new(y)),
        (CheckedOp::Mul, y) => IntExpr::Mul(x, Box::new(y)),
        (CheckedOp::Div | CheckedOp::Mod, IntExpr::Const(0)) => return None,
        (CheckedOp::Div, IntExpr::Const(k)) => IntExpr::Div(x, k),
        (CheckedOp::Mod, IntExpr::Const(k)) => IntExpr::Mod(x, k),
        (CheckedOp::Div, y) => IntExpr::DivBy(x, Box::new(y)),
        (CheckedOp::Mod, y) => IntExpr::ModBy(x, Box::new(y)),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const EDGES: [i64; 9] =
        [i32::MIN as i64, i32::MIN as i64 + 1, -65536, -2, -1, 0, 1, 46341, i32::MAX as i64];

    /// What C's `int` computes where it defines it: Rust's checked `i32` operations (a
    /// division by 0 is matiec's 0).
    fn c_int(op: CheckedOp, a: i32, b: i32) -> Option<i32> {
        match op {
            CheckedOp::Add => a.checked_add(b),
            CheckedOp::Sub => a.checked_sub(b),
            CheckedOp::Mul => a.checked_mul(b),
            CheckedOp::Div | CheckedOp::Mod if b == 0 => Some(0),
            CheckedOp::Div => a.checked_div(b),
            CheckedOp::Mod => a.checked_rem(b),
        }
    }

    const OPS: [CheckedOp; 5] =
        [CheckedOp::Add, CheckedOp::Sub, CheckedOp::Mul, CheckedOp::Div, CheckedOp::Mod];

    #[test]
    fn defined_where_c_int_defines_it() {
        for op in OPS {
            for a in EDGES {
                for b in EDGES {
                    let want = c_int(op, a as i32, b as i32).map(i64::from);
                    assert_eq!(op.apply(a, b, C_INT), want, "{op:?} {a} {b}");
                }
            }
        }
    }

    #[test]
    fn bounds_hold_every_result() {
        // Small intervals around the edges: every exact result of operands within them
        // lies within the bounds.
        for op in OPS {
            for lo_a in EDGES {
                for lo_b in EDGES {
                    let (a, b) = ((lo_a, lo_a.saturating_add(3)), (lo_b, lo_b.saturating_add(3)));
                    let (lo, hi) = op.bounds((a.0.into(), a.1.into()), (b.0.into(), b.1.into()));
                    for x in a.0..=a.1 {
                        for y in b.0..=b.1 {
                            let wide = IntType::int(63, true);
                            let Some(v) = op.apply(x, y, wide) else { continue };
                            let v = i128::from(v);
                            assert!(lo <= v && v <= hi, "{op:?} {x} {y}: {v} not in {lo}..={hi}");
                            if op.apply(x, y, C_INT).is_none() {
                                assert!(
                                    lo < i128::from(i32::MIN) || hi > i128::from(i32::MAX),
                                    "{op:?} {x} {y} overflows within bounds {lo}..={hi}"
                                );
                            }
                        }
                    }
                }
            }
        }
    }
}
