//! `REAL` values of Structured Text in the scan model, as the C matiec writes computes them on x86-64: a `REAL` variable is a C `float`, a real literal (`0.5`) a C `double` constant, so an operation of a `REAL` and a literal is computed in `double` (binary64: [`IntType::LREAL`]), and so is every operation on its result, until C converts it to `float` (stored, passed to a function) or compares it (in `double`). Exact: all of these; what a function computes beyond them (`SQRT`, …) stays opaque where the front end says so.

use super::Lowering;
use super::ints::{Int, Opaque};
use crate::diag::Span;
use crate::iec::StError;
use crate::iec::ast::BinOp;
use crate::program::{BitOp, BoolExpr, CmpOp, IntExpr, IntType, RealOp, library, real};

/// A `REAL` value the generated C computes in `double`.
#[derive(Clone, Debug)]
pub(super) enum Double {
    /// A real literal: a C `double` constant, of this value.
    Literal(f64),
    /// A value computed in `double`: this [`IntType::LREAL`] expression. The `Int`'s own
    /// expression is its value as C converts it to `float` (stored, passed to a function).
    Wide(IntExpr),
}

impl Int {
    /// A real literal of value `v` (a C `double`): as a stored `REAL`, `(float)v`.
    fn double_literal(v: f64) -> Int {
        let mut x = Int::of(IntExpr::Const(real::of_f32(v as f32)), Some(IntType::REAL));
        x.double = Some(Double::Literal(v));
        x
    }

    /// Whether the value is a `REAL`.
    pub(super) fn is_real(&self) -> bool {
        self.ty.is_some_and(|t| t.real)
    }

    /// A real literal as written (`0.5`, `1.0E3`: a C `double`; `REAL#0.5`: a `float`),
    /// or `None` if `text` is not one.
    pub(super) fn real_literal(text: &str) -> Option<Int> {
        let v = real::literal_value(text)?;
        Some(if text.contains('#') {
            Int::of(IntExpr::Const(real::of_f32(v as f32)), Some(IntType::REAL))
        } else {
            Int::double_literal(v)
        })
    }

    /// `-x` of a `REAL`: C flips the sign bit (of a `double` too, which commutes with
    /// the conversion to `float`).
    pub(super) fn real_negated(self) -> Int {
        let flip = |e: IntExpr, bit: u32| {
            IntExpr::Bitwise(BitOp::Xor, Box::new(e), Box::new(IntExpr::Const(1 << bit)))
        };
        match self.double {
            Some(Double::Literal(v)) => Int::double_literal(-v),
            Some(Double::Wide(w)) => {
                let mut negated = Int::of(flip(self.e, 31), self.ty);
                negated.double = Some(Double::Wide(flip(w, 63)));
                negated
            }
            None => Int::of(flip(self.e, 31), self.ty),
        }
    }

    /// The value as C computes it in `double`: a `REAL` promoted (exactly), a literal
    /// itself, a value computed in `double` as it is.
    fn wide(&self) -> IntExpr {
        match &self.double {
            Some(Double::Literal(v)) => IntExpr::Const(real::of_f64(*v)),
            Some(Double::Wide(w)) => w.clone(),
            None => IntExpr::ToReal(Box::new(self.e.clone()), IntType::REAL),
        }
    }

    /// A value computed in `double` (`w`, of [`IntType::LREAL`]); as a `REAL`, `e` if
    /// given (a `float` computation of the same value), else `w` rounded to `float`.
    fn computed_in_double(w: IntExpr, e: Option<IntExpr>) -> Int {
        let e = e.unwrap_or_else(|| IntExpr::ToReal(Box::new(w.clone()), IntType::LREAL));
        let mut x = Int::of(e, Some(IntType::REAL));
        x.double = Some(Double::Wide(w));
        x
    }
}

/// Whether the `double` `v` is a `float` value.
fn is_float(v: f64) -> bool {
    f64::from(v as f32) == v || v.is_nan()
}

/// `b op a` for `a op b`.
fn swapped(op: CmpOp) -> CmpOp {
    match op {
        CmpOp::Lt => CmpOp::Gt,
        CmpOp::Le => CmpOp::Ge,
        CmpOp::Gt => CmpOp::Lt,
        CmpOp::Ge => CmpOp::Le,
        same => same,
    }
}

impl Lowering<'_> {
    /// `a op b` (`+ - * /`) where one side is a `REAL`, as C computes it.
    pub(super) fn real_arithmetic(
        &mut self,
        op: BinOp,
        a: Int,
        b: Int,
        span: Span,
    ) -> Result<Int, Opaque> {
        self.unify(&a, &b, span)?;
        let rop = match op {
            BinOp::Add => RealOp::Add,
            BinOp::Sub => RealOp::Sub,
            BinOp::Mul => RealOp::Mul,
            BinOp::Div => RealOp::Quotient,
            _ => {
                self.errors.push(StError::new(
                    span,
                    "MOD of REAL values",
                    "MOD takes integers (the C matiec writes for it, `a % b`, does not compile with REALs)",
                ));
                return Err("a type error".into());
            }
        };
        match (&a.double, &b.double) {
            // Two literals: folded in `double`, as the C compiler folds them.
            (Some(Double::Literal(x)), Some(Double::Literal(y))) => {
                let (x, y) = (*x, *y);
                Ok(Int::double_literal(match rop {
                    RealOp::Add => x + y,
                    RealOp::Sub => x - y,
                    RealOp::Mul => x * y,
                    _ => x / y,
                }))
            }
            (None, None) => {
                Ok(Int::of(IntExpr::Real(rop, Box::new(a.e), Box::new(b.e)), Some(IntType::REAL)))
            }
            _ => {
                let w = IntExpr::Real(rop, Box::new(a.wide()), Box::new(b.wide()));
                // One operation of a `float` and a literal a `float` holds: rounding the
                // exact result through `double` to `float` gives the `float` operation's
                // (53 ≥ 2·24 + 2), a smaller circuit for the value as a `REAL`.
                let single = match (&a.double, &b.double) {
                    (Some(Double::Literal(k)), None) | (None, Some(Double::Literal(k)))
                        if is_float(*k) =>
                    {
                        Some(IntExpr::Real(rop, Box::new(a.e.clone()), Box::new(b.e.clone())))
                    }
                    _ => None,
                };
                Ok(Int::computed_in_double(w, single))
            }
        }
    }

    /// `a op b` where one side is a `REAL`: as C compares a `float` (exactly a `double`
    /// when promoted) with a `double` literal; in `double` where a side is computed in
    /// `double`.
    pub(super) fn real_compare(&mut self, op: CmpOp, a: Int, b: Int, span: Span) -> BoolExpr {
        if let Err(why) = self.unify(&a, &b, span) {
            return self.unknown_comparison(op, span, &why);
        }
        match (&a.double, &b.double) {
            (Some(Double::Literal(x)), Some(Double::Literal(y))) => {
                BoolExpr::Const(op.compares(*x, *y))
            }
            (None, None) => library::compare(op, IntType::REAL, a.e, b.e),
            (None, Some(Double::Literal(k))) => compare_with_literal(op, a.e, *k),
            (Some(Double::Literal(k)), None) => compare_with_literal(swapped(op), b.e, *k),
            // A value computed in `double`: compared in `double`.
            _ => library::compare(op, IntType::LREAL, a.wide(), b.wide()),
        }
    }
}

impl Lowering<'_> {
    /// `F(x)` for a conversion `F` (`from` to `to`) with a `REAL` side, as matiec's C
    /// converts: an integer to the nearest `float`; a `REAL` to the rounded integer where
    /// C defines it, else a free input of `to` ([`library::real_to_int`]).
    pub(super) fn real_conversion(
        &mut self,
        f: &str,
        x: Int,
        (from, to): (IntType, IntType),
        span: Span,
    ) -> Int {
        let v = x.in_type(from);
        if !from.real {
            return Int::of(IntExpr::ToReal(Box::new(v), from), Some(to));
        }
        if to.real {
            return Int::of(v, Some(to));
        }
        let free = self.unique(&format!("{}_UNDEFINED_L{:02}", f.to_ascii_uppercase(), self.line));
        self.ints.insert(free.clone(), crate::program::IntVar { ty: to, input: true, init: 0 });
        self.undefined.insert(free.clone());
        self.warnings.push(StError::warning(
            span,
            format!(
                "{f}: {}, its value is the free input {free}: any {}",
                library::real_to_int_undefined(!to.signed),
                library::type_name(to)
            ),
        ));
        let e = library::real_to_int(v, !to.signed, &free);
        Int::of(IntExpr::Cast(Box::new(e), to), Some(to))
    }
}

/// `ADD`, `SUB`, `MUL` or `DIV` (`op`) of `REAL` arguments (each converted to `REAL` as
/// passed): `float` operations, `DIV` by `±0.0` giving `0.0` (matiec's `DIV`).
pub(super) fn real_function(op: BinOp, args: Vec<IntExpr>) -> Result<IntExpr, Opaque> {
    let rop = match op {
        BinOp::Add => RealOp::Add,
        BinOp::Sub => RealOp::Sub,
        BinOp::Mul => RealOp::Mul,
        BinOp::Div => RealOp::Div,
        _ => return Err("MOD of REAL values is not computed (MOD takes integers)".into()),
    };
    let mut it = args.into_iter();
    let first = it.next().unwrap_or(IntExpr::Const(0));
    Ok(it.fold(first, |acc, x| IntExpr::Real(rop, Box::new(acc), Box::new(x))))
}

/// `(double)x op k` for a `REAL` `x` and a `double` `k`: a `float` comparison, with `k`
/// itself where a `float` holds it, else with the greatest `float` below `k` (no `float`
/// lies between them: `x > k` is `x > lo`, `x < k` is `x <= lo`, `x = k` never).
fn compare_with_literal(op: CmpOp, x: IntExpr, k: f64) -> BoolExpr {
    if is_float(k) {
        return library::compare(op, IntType::REAL, x, IntExpr::Const(real::of_f32(k as f32)));
    }
    let nearest = k as f32;
    let lo = if f64::from(nearest) < k { nearest } else { nearest.next_down() };
    let lo = IntExpr::Const(real::of_f32(lo));
    match op {
        CmpOp::Eq => BoolExpr::Const(false),
        CmpOp::Ne => BoolExpr::Const(true),
        CmpOp::Gt | CmpOp::Ge => library::compare(CmpOp::Gt, IntType::REAL, x, lo),
        CmpOp::Lt | CmpOp::Le => library::compare(CmpOp::Le, IntType::REAL, x, lo),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every comparison of a `float` with a `double` literal no `float` holds, over the
    /// `float`s around it, as C compares them (the `float` promoted).
    #[test]
    fn comparisons_with_double_literals_are_exact() {
        let values = |k: f64| {
            let f = k as f32;
            let mut v = vec![f, f.next_up(), f.next_down(), 0.0, -0.0, f32::NAN];
            v.extend([f32::INFINITY, f32::NEG_INFINITY, f32::MAX, f32::MIN_POSITIVE]);
            v.extend([f32::from_bits(1), -f32::from_bits(1), f.next_up().next_up()]);
            v
        };
        let ops = [CmpOp::Eq, CmpOp::Ne, CmpOp::Lt, CmpOp::Le, CmpOp::Gt, CmpOp::Ge];
        for k in [0.1, -0.1, 1e-50, -1e-50, 1e39, -1e39, 3.4028235677973366e38, 16777217.0] {
            assert!(!is_float(k), "{k}");
            for x in values(k) {
                for op in ops {
                    let got = match compare_with_literal(op, IntExpr::Var("x".into()), k) {
                        BoolExpr::Const(c) => c,
                        BoolExpr::Compare(c) => match c.b {
                            IntExpr::Const(lo) => c.ty.holds(c.op, real::of_f32(x), lo),
                            _ => panic!("{op:?} {k}: not a comparison with a constant"),
                        },
                        _ => panic!("{op:?} {k}: not a comparison"),
                    };
                    assert_eq!(got, op.compares(f64::from(x), k), "{x:?} {op:?} {k}");
                }
            }
        }
    }
}
