//! Functions and conversions with an integer or Boolean result in Structured Text and Instruction List, as matiec's library computes them: the `*_TO_*` conversions (`TIME_TO_*`, `STRING_TO_*` of a literal, `<from>_TO_BOOL`), `MIN`/`MAX`/`LIMIT`/`SEL`/`ABS`/`MOVE` and the arithmetic functions; what is not computed is opaque, with the reason.

use super::Lowering;
use super::ints::{ByZero, Int, Opaque, int_type, no_time_arithmetic};
use crate::diag::Span;
use crate::iec::ast::{self, Arg, BinOp};
use crate::program::{BoolExpr, C_INT, CmpOp, Fresh, IntExpr, IntType, library, promoted};

impl Lowering<'_> {
    /// A function with an integer result: conversions, MIN/MAX/LIMIT/SEL/ABS/MOVE and the
    /// arithmetic functions.
    pub(super) fn int_function(
        &mut self,
        f: &ast::Ident,
        args: &[Arg],
        e: &ast::Expr,
    ) -> Result<Int, Opaque> {
        let call_args = args;
        let args = match self.std_args(f, args) {
            Ok(args) => args,
            Err(why) => {
                let eno = call_args.iter().find_map(|a| match a {
                    Arg::Output(n, _, _) if n.key() == "ENO" => Some(n.span),
                    _ => None,
                });
                if let Some(span) = eno {
                    let what = format!("the ENO of `{}`", f.name);
                    self.refuse(span, &what, &why);
                }
                return Err(why);
            }
        };
        let en = args.en.map(|x| self.bool_expr(x));
        self.std_eno(f, call_args, &args.values, en.clone());
        let value = self.int_function_of(f, &args.values, e)?;
        let Some(en) = en else { return Ok(value) };
        // Where `EN` is FALSE matiec's `TEST_EN` returns the type's initial value, 0.
        let Some(t) = value.ty else {
            return Err(format!("`{}` of literals alone under `EN` is not computed", f.name));
        };
        Ok(Int::of(IntExpr::ite(en, value.in_type(t), IntExpr::Const(0)), Some(t)))
    }

    fn int_function_of(
        &mut self,
        f: &ast::Ident,
        values: &[&ast::Expr],
        e: &ast::Expr,
    ) -> Result<Int, Opaque> {
        let name = f.key();
        if let Some(to) = name.strip_prefix("TIME_TO_") {
            return self.time_conversion(f, to, values, e.span);
        }
        if let Some(to) = name.strip_prefix("STRING_TO_") {
            return string_conversion(f, to, values);
        }
        if let Some((from, to)) = name.split_once("_TO_") {
            let (Some(from), Some(to)) = (library::number_type(from), library::number_type(to))
            else {
                return Err(format!("the conversion {} is not computed", f.name));
            };
            let [x] = values else {
                return Err(format!("{} takes one argument", f.name));
            };
            let x = self.int_expr(x)?;
            self.unify(&x, &Int::of(IntExpr::Const(0), Some(from)), e.span)?;
            if from.real || to.real {
                return Ok(self.real_conversion(&f.name, x, (from, to), e.span));
            }
            // The argument is a value of `from` (converted as C passes it), then `to`.
            // A value of `to` in any context: converted from `from`, then wrapped to `to`.
            let v = IntExpr::Cast(Box::new(IntExpr::Cast(Box::new(x.in_type(from)), from)), to);
            return Ok(Int::of(v, Some(to)));
        }
        let mut ints = Vec::new();
        let skip = usize::from(name == "SEL" || name == "MUX");
        for x in values.iter().skip(skip) {
            ints.push(self.int_expr(x)?);
        }
        // Literals alone are folded as numbers (typed where they are used, as matiec
        // types them): `MIN(4294967295, 1)` is 1 whatever C `int` would make of it.
        let literals: Option<Vec<i128>> = ints
            .iter()
            .map(|x| match (&x.e, x.ty) {
                (IntExpr::Const(k), None) => Some(i128::from(*k)),
                _ => None,
            })
            .collect();
        if let Some(ks) = literals
            && name != "SEL"
        {
            let folded = match (name.as_str(), ks.as_slice()) {
                ("MOVE", [k]) => Some(*k),
                ("ABS", [k]) => Some(k.abs()),
                ("MIN", [_, _, ..]) => ks.iter().min().copied(),
                ("MAX", [_, _, ..]) => ks.iter().max().copied(),
                ("LIMIT", [mn, x, mx]) => {
                    Some(if x > mn { if x < mx { *x } else { *mx } } else { *mn })
                }
                _ => None,
            };
            if let Some(k) = folded {
                return Ok(Int::literal(k));
            }
        }
        // The arguments' one type (literals take it).
        let mut ty = ints.iter().find_map(|x| x.ty);
        if !matches!(name.as_str(), "MOVE" | "MIN" | "MAX" | "LIMIT" | "SEL") {
            no_time_arithmetic(&ints.iter().collect::<Vec<_>>())?;
        }
        // (Durations meet in the widest of their types: `unify` gives it.)
        for x in &ints {
            ty = self.unify(&Int::of(IntExpr::Const(0), ty), x, e.span)?;
        }
        let t = ty.unwrap_or(C_INT);
        let value = |x: &Int| x.clone().in_type(t);
        let e2 = match (name.as_str(), ints.as_slice()) {
            ("MOVE", [x]) => value(x),
            ("ABS", [x]) => {
                // `-op` of the least `DINT` overflows.
                let (lo, _) = x.bounds();
                let undefined = (promoted(t) == C_INT && lo <= i128::from(C_INT.min()))
                    .then(|| self.overflow_input("ABS", e.span));
                library::abs(t, value(x), undefined)
            }
            ("MIN" | "MAX", [_, rest @ ..]) if !rest.is_empty() => {
                let vals: Vec<IntExpr> = ints.iter().map(value).collect();
                library::extreme(name == "MIN", t, &vals)
            }
            ("LIMIT", [mn, x, mx]) => library::limit(t, value(mn), value(x), value(mx)),
            ("SEL", [a, b]) => {
                let g = self.bool_expr(values[0]);
                IntExpr::ite(g, value(b), value(a))
            }
            ("ADD" | "MUL" | "SUB" | "DIV" | "MOD", [first, rest @ ..]) if !rest.is_empty() => {
                let op = match name.as_str() {
                    "ADD" => BinOp::Add,
                    "MUL" => BinOp::Mul,
                    "SUB" => BinOp::Sub,
                    "DIV" => BinOp::Div,
                    _ => BinOp::Mod,
                };
                if rest.len() > 1 && !matches!(op, BinOp::Add | BinOp::Mul) {
                    return Err(format!("{} takes two arguments", f.name));
                }
                if t.real {
                    let vals: Vec<IntExpr> = ints.iter().map(value).collect();
                    return super::reals::real_function(op, vals).map(|v| Int::of(v, ty));
                }
                // Each step is `op1 = op1 OP op2` of the function's type (C `int` for a
                // narrower one, then wrapped to it): `MUL` of three `INT`s cannot overflow.
                let mut acc = first.clone();
                for x in rest {
                    let step = self.arithmetic(op, acc, x.clone(), e.span, ByZero::Zero)?;
                    acc = Int::of(IntExpr::Cast(Box::new(step.in_type(t)), t), Some(t));
                }
                acc.in_type(t)
            }
            ("SQRT", [x]) if t.real => IntExpr::Sqrt(Box::new(value(x))),
            _ => return Err(format!("the function {} is not computed", f.name)),
        };
        if t.real {
            return Ok(Int::of(e2, ty));
        }
        // A function returns a value of its type: computed (its arguments passed) in `t`.
        Ok(Int::of(IntExpr::Cast(Box::new(e2), t), ty))
    }

    /// matiec's `TIME_TO_*` (`to`: the target type's name) of the one argument in
    /// `values`: `__time_to_int`, the whole seconds (`tv_sec`, truncated toward zero),
    /// converted as C converts a `LINT` to the type.
    fn time_conversion(
        &mut self,
        f: &ast::Ident,
        to: &str,
        values: &[&ast::Expr],
        span: Span,
    ) -> Result<Int, Opaque> {
        let Some(to) = int_type(to) else {
            return Err(format!("the conversion {} is not computed", f.name));
        };
        let [x] = values else {
            return Err(format!("{} takes one argument", f.name));
        };
        let x = self.int_expr(x)?;
        let from = self.unify(&x, &Int::of(IntExpr::Const(0), Some(IntType::time_for(0))), span)?;
        let from = from.unwrap_or(IntType::TIME);
        let seconds = IntExpr::Div(Box::new(x.e), 1_000_000_000);
        let v = IntExpr::Cast(Box::new(IntExpr::Cast(Box::new(seconds), from)), to);
        Ok(Int::of(v, Some(to)))
    }

    /// matiec's `<from>_TO_BOOL` of `x` (`lib/C/iec_std_functions.h`): `op == 0 ? 0 : 1`
    /// for a number or bit string, `__string_to_bool` for a string literal; an
    /// unconstrained value with the reason where `x` is not computed.
    pub(super) fn conversion_to_bool(
        &mut self,
        f: &ast::Ident,
        from: &str,
        x: &ast::Expr,
        span: Span,
    ) -> BoolExpr {
        if from == "STRING" {
            return match string_body(x) {
                Some(body) => BoolExpr::Const(crate::iec::literal::matiec_string_to_bool(&body)),
                None => self.unknown_conversion(
                    f,
                    span,
                    "its argument is not a string literal, and ii-prove computes no STRING",
                ),
            };
        }
        let value = self.int_expr(x);
        self.value_to_bool(f, from, value, span)
    }

    /// `<from>_TO_BOOL` of the integer `value` (IL's current result, or an ST argument).
    pub(super) fn value_to_bool(
        &mut self,
        f: &ast::Ident,
        from: &str,
        value: Result<Int, Opaque>,
        span: Span,
    ) -> BoolExpr {
        let Some(ty) = library::number_type(from) else {
            let why = format!("{from} is not a type ii-prove computes");
            return self.unknown_conversion(f, span, &why);
        };
        let value = value.and_then(|x| {
            self.unify(&x, &Int::of(IntExpr::Const(0), Some(ty)), span)?;
            Ok(x)
        });
        match value {
            Ok(x) => {
                // The argument as C passes it: a value of `from`.
                let v = match ty.real {
                    true => self.real_conversion(&f.name, x, (ty, ty), span),
                    false => Int::of(IntExpr::Cast(Box::new(x.in_type(ty)), ty), Some(ty)),
                };
                let zero = Int::of(IntExpr::Const(0), Some(ty));
                self.int_compare_values(CmpOp::Ne, v, zero, span)
            }
            Err(why) => self.unknown_conversion(f, span, &why),
        }
    }

    /// An unconstrained value for the conversion `f` at `span`, with the reason.
    fn unknown_conversion(&mut self, f: &ast::Ident, span: Span, why: &str) -> BoolExpr {
        BoolExpr::Fresh(Box::new(Fresh {
            base: format!("{}_L{:02}", f.key(), self.line),
            keyword: f.key(),
            why: format!("the conversion `{}` is not computed: {why}", self.text(span)),
            span,
            peripheral: false,
        }))
    }
}

/// The bytes of `x` if it is a string literal (`'True'`, `STRING#'12'`) matiec's C holds
/// as written ([`literal::string_literal`](crate::iec::literal::string_literal)).
pub(super) fn string_body(x: &ast::Expr) -> Option<Vec<u8>> {
    let ast::ExprKind::Literal(text) = &x.kind else { return None };
    crate::iec::literal::string_literal(text)
}

/// matiec's `STRING_TO_<to>` of a string literal: its `__string_to_sint` (or `_uint`,
/// `_bit`, the same `LINT`) cast to `to` as C casts. Not computed for a string that is
/// not a literal (ii-prove computes no STRING) nor for `REAL`s (`__string_to_real`).
fn string_conversion(f: &ast::Ident, to: &str, values: &[&ast::Expr]) -> Result<Int, Opaque> {
    let not = |why: &str| Err(format!("the conversion {} is not computed: {why}", f.name));
    let to = match library::number_type(to) {
        Some(t) if !t.real => t,
        _ => return not("its result type is not an integer ii-prove computes"),
    };
    let [x] = values else { return Err(format!("{} takes one argument", f.name)) };
    let Some(body) = string_body(x) else {
        return not("its argument is not a string literal, and ii-prove computes no STRING");
    };
    match crate::iec::literal::matiec_string_to_lint(&body) {
        Some(v) => Ok(Int::of(IntExpr::Const(to.wrap(v)), Some(to))),
        None => not("the C that reads this literal overflows, which C leaves undefined"),
    }
}
