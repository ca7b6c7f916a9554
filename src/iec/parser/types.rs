//! `TYPE … END_TYPE`: subrange types (`LEVEL : INT (0..100) := 5;`) read, then resolved into the declarations of their variables (the base type, the limits, the type's initial value); other derived types are refused with a located error.

use super::Parser;
use crate::diag::Span;
use crate::iec::StError;
use crate::iec::ast::*;
use crate::iec::lexer::Tok;

/// A subrange type: `name : base (lo..hi) := init;`.
pub(super) struct Subrange {
    name: Ident,
    /// The base type, upper-cased.
    base: Ident,
    lo: i64,
    hi: i64,
    init: Option<Expr>,
}

/// The base types matiec's grammar allows a subrange of (IEC 61131-3's `integer_type_name`:
/// `BYTE (1..3)` is a syntax error in `iec2c`).
const BASES: &[&str] = &["SINT", "INT", "DINT", "LINT", "USINT", "UINT", "UDINT", "ULINT"];

impl Parser<'_> {
    /// The declarations of a `TYPE` block, after `TYPE`, through `END_TYPE`.
    pub(super) fn types(&mut self, out: &mut Vec<Subrange>) -> Result<(), StError> {
        let start = self.toks[self.at.saturating_sub(1)].span;
        loop {
            if self.peek().is_kw("END_TYPE") || self.peek().tok == Tok::Eof {
                self.expect_kw("END_TYPE", Some(("TYPE", start)))?;
                return Ok(());
            }
            let name = self.ident("a type name or `END_TYPE`")?;
            self.expect_sym(":", "and the type's definition")?;
            let t = self.peek().clone();
            let base = match &t.tok {
                Tok::Ident(b) if BASES.contains(&b.to_ascii_uppercase().as_str()) => {
                    self.bump();
                    Ident { name: b.to_ascii_uppercase(), span: t.span }
                }
                _ => return Err(self.other_type(&name, t.span)),
            };
            if !self.is_sym("(") {
                return Err(self.other_type(&name, t.span));
            }
            self.bump();
            let lo = self.bound()?;
            self.expect_sym("..", "the lower limit")?;
            let hi = self.bound()?;
            let close = self.expect_sym(")", "the upper limit")?;
            let span = t.span.to(close);
            if lo.0 > hi.0 {
                return Err(StError::new(
                    lo.1.to(hi.1),
                    format!(
                        "the subrange's lower limit ({}) is larger than its upper limit ({})",
                        lo.0, hi.0
                    ),
                    "matiec refuses it",
                ));
            }
            let t = crate::program::library::int_type(&base.name);
            if let Some(t) = t
                && (lo.0 < t.min().into() || hi.0 > t.max().into())
            {
                return Err(StError::new(
                    span,
                    format!(
                        "the limits {}..{} are not all values of {}: ii-prove does not model the check matiec generates for them (it compares values of {} with limits they cannot reach)",
                        lo.0, hi.0, base.name, base.name
                    ),
                    "give limits within the base type",
                ));
            }
            let init = if self.eat_sym(":=") { Some(self.expr()?) } else { None };
            self.expect_sym(";", "after the type declaration")?;
            let (lo, hi) = (lo.0 as i64, hi.0 as i64);
            if out.iter().any(|s: &Subrange| s.name.key() == name.key()) {
                return Err(StError::new(name.span, "this type is declared twice", "again"));
            }
            out.push(Subrange { name, base, lo, hi, init });
        }
    }

    /// A subrange limit: an integer with an optional sign, and where it is.
    fn bound(&mut self) -> Result<(i128, Span), StError> {
        let start = self.peek().span;
        let negative = if self.eat_sym("-") {
            true
        } else {
            self.eat_sym("+");
            false
        };
        let t = self.peek().clone();
        let Tok::Int(v) = t.tok else { return Err(self.unexpected("an integer limit")) };
        self.bump();
        let v = if negative { -v } else { v };
        if v < i64::MIN.into() || v > i64::MAX.into() {
            return Err(StError::new(start.to(t.span), "this limit is out of range", "too large"));
        }
        Ok((v, start.to(t.span)))
    }

    /// The refusal of a derived type that is not a subrange.
    fn other_type(&self, name: &Ident, at: Span) -> StError {
        StError::new(
            name.span.to(at),
            format!(
                "`{}` is not a subrange of an integer type (`{} : INT (0..100);`): ii-prove reads only subrange types yet, not enumerations, structures, arrays or other derived types",
                name.name, name.name
            ),
            "not supported",
        )
    }
}

/// Every declaration of a variable of a subrange type in `unit` takes the base type, the
/// limits and, when it gives none, the type's initial value; a function's result type
/// the base type.
pub(super) fn resolve(unit: &mut Unit, types: &[Subrange]) {
    if types.is_empty() {
        return;
    }
    let find = |ty: &Ident| types.iter().find(|s| s.name.key() == ty.key());
    let vars = unit
        .pous
        .iter_mut()
        .flat_map(|p| p.vars.iter_mut())
        .chain(unit.configs.iter_mut().flat_map(|c| c.globals.iter_mut()));
    for v in vars {
        if let Some(s) = find(&v.ty) {
            v.ty = Ident { name: s.base.name.clone(), span: v.ty.span };
            v.range = Some((s.lo, s.hi));
            if v.init.is_none() {
                v.init = s.init.clone();
            }
        }
    }
    for p in &mut unit.pous {
        if let Some(r) = &mut p.result
            && let Some(s) = find(r)
        {
            *r = Ident { name: s.base.name.clone(), span: r.span };
        }
    }
}
