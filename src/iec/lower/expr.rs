//! Boolean expressions of Structured Text in the scan model: variables and FB outputs, `NOT`/`AND`/`OR`/`XOR`, `=`/`<>` between BOOLs, the Boolean functions, integer comparisons (`ints`), `CASE` labels and `FOR` bounds.

use super::enable::std_arg;
use super::flow::MAX_ITERATIONS;
use super::{Lowering, Sym, Ty};
use crate::diag::Span;
use crate::iec::StError;
use crate::iec::ast::{self, Arg, BinOp, ExprKind, Ident, UnOp};
use crate::program::{BoolExpr, CmpOp, Fresh};

impl Lowering<'_> {
    /// Whether `e` is Boolean (so `=` between two such is an equivalence).
    pub(super) fn is_bool(&self, e: &ast::Expr) -> bool {
        match &e.kind {
            ExprKind::Bool(_) => true,
            ExprKind::Var(id) => matches!(self.syms.get(&id.key()), Some(Sym { ty: Ty::Bool, .. })),
            ExprKind::Member(of, field) => match &of.kind {
                ExprKind::Var(id) => match self.syms.get(&id.key()) {
                    Some(Sym { ty: Ty::Fb(fb, _), .. }) => {
                        fb.outputs().contains(&field.key().as_str())
                    }
                    Some(Sym { ty: Ty::User(_), name, .. }) => self.member(name, field).is_some(),
                    _ => false,
                },
                _ => false,
            },
            // matiec reads an integer literal 0 or 1 as a BOOL where a BOOL fits.
            ExprKind::Unary(UnOp::Not, x) => self.is_bool(x) || bit_literal(x).is_some(),
            ExprKind::Binary(BinOp::And | BinOp::Or | BinOp::Xor, a, b) => match bit_literal(a) {
                Some(_) => self.is_bool(b) || bit_literal(b).is_some(),
                None => self.is_bool(a),
            },
            ExprKind::Binary(
                BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge,
                ..,
            ) => true,
            ExprKind::Call(f, args) if f.key() == "SEL" => {
                match (std_arg("SEL", args, 1), std_arg("SEL", args, 2)) {
                    (Some(x), Some(y)) if bit_literal(x).is_some() => {
                        self.is_bool(y) || bit_literal(y).is_some()
                    }
                    (Some(x), _) => self.is_bool(x),
                    _ => true,
                }
            }
            ExprKind::Call(f, _) => {
                ["AND", "OR", "XOR", "NOT", "GT", "GE", "EQ", "NE", "LT", "LE"]
                    .contains(&f.key().as_str())
                    || f.key().ends_with("_TO_BOOL")
                    || self.bool_function(f)
            }
            _ => false,
        }
    }

    pub(super) fn text(&self, span: Span) -> String {
        let t = self.sources.text(span.file).get(span.range()).unwrap_or("");
        t.split_whitespace().collect::<Vec<_>>().join(" ")
    }

    /// An integer comparison: unconstrained, named after its operator and line.
    pub(super) fn comparison(&mut self, op: &str, span: Span) -> BoolExpr {
        BoolExpr::Fresh(Box::new(Fresh {
            base: format!("{op}_L{:02}", self.line),
            keyword: op.to_string(),
            why: format!(
                "the integer comparison `{}` is not expressible in the algebra",
                self.text(span)
            ),
            span,
            peripheral: false,
        }))
    }

    pub(super) fn not_bool(&mut self, e: &ast::Expr, what: &str) -> BoolExpr {
        self.errors.push(StError::new(
            e.span,
            format!("{what} where a BOOL is expected"),
            "expected a BOOL",
        ));
        BoolExpr::Const(false)
    }

    pub(super) fn bool_expr(&mut self, e: &ast::Expr) -> BoolExpr {
        match &e.kind {
            ExprKind::Bool(b) => BoolExpr::Const(*b),
            ExprKind::Var(id) => match self.lookup(id) {
                Some(Sym { ty: Ty::Bool, name, .. }) => BoolExpr::Var(name),
                Some(Sym { ty: Ty::Fb(_, t) | Ty::User(t), name, .. }) => {
                    self.not_bool(e, &format!("the {t} instance `{name}`"))
                }
                Some(Sym { ty, name, .. }) if ty.value_type().is_some() => {
                    let t = ty.value_type().unwrap_or_default();
                    self.not_bool(e, &format!("the {t} variable `{name}`"))
                }
                Some(Sym { ty: Ty::Int(_) | Ty::Other(_), .. }) => BoolExpr::Const(false),
                None => BoolExpr::Const(false),
            },
            ExprKind::Member(of, field) => {
                let ExprKind::Var(id) = &of.kind else { return self.not_bool(e, "this member") };
                match self.lookup(id) {
                    Some(Sym { ty: Ty::Fb(fb, _), name, .. })
                        if fb.outputs().contains(&field.key().as_str()) =>
                    {
                        BoolExpr::var(&self.hidden(&name, &field.key()))
                    }
                    Some(Sym { ty: Ty::User(_), name, .. })
                        if self.member(&name, field).is_some() =>
                    {
                        BoolExpr::var(&self.member(&name, field).unwrap_or_default())
                    }
                    Some(Sym { ty: Ty::Fb(_, t), name, .. }) => self.not_bool(
                        e,
                        &format!("`{name}.{}` (not a BOOL output of {t})", field.name),
                    ),
                    Some(_) => self.not_bool(e, &format!("`{}.{}`", id.name, field.name)),
                    None => BoolExpr::Const(false),
                }
            }
            ExprKind::Unary(UnOp::Not, x) => BoolExpr::negate(self.bool_expr(x)),
            ExprKind::Binary(op @ (BinOp::And | BinOp::Or | BinOp::Xor), a, b) => {
                let (a, b) = (self.bool_expr(a), self.bool_expr(b));
                match op {
                    BinOp::And => BoolExpr::and(a, b),
                    BinOp::Or => BoolExpr::Or(vec![a, b]),
                    _ => xor(a, b),
                }
            }
            ExprKind::Binary(op @ (BinOp::Eq | BinOp::Ne), a, b)
                if self.is_bool(a) && (self.is_bool(b) || bit_literal(b).is_some())
                    || bit_literal(a).is_some() && self.is_bool(b) =>
            {
                let (a, b) = (self.bool_expr(a), self.bool_expr(b));
                if *op == BinOp::Ne { xor(a, b) } else { BoolExpr::negate(xor(a, b)) }
            }
            ExprKind::Binary(
                op @ (BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge),
                a,
                b,
            ) => self.int_compare(comparison_op(*op), a, b, e.span),
            ExprKind::Call(f, args) => self.function(f, args, e),
            ExprKind::Int(_) if bit_literal(e).is_some() => {
                BoolExpr::Const(bit_literal(e) == Some(true))
            }
            ExprKind::Int(_) | ExprKind::Time(_) | ExprKind::Literal(_) => {
                self.not_bool(e, "a literal that is not TRUE, FALSE, 0 or 1")
            }
            ExprKind::Binary(..) | ExprKind::Unary(UnOp::Neg, _) => self.not_bool(e, "arithmetic"),
            ExprKind::Index(..) => {
                self.refuse(e.span, "an array element", "arrays are not modelled yet");
                BoolExpr::Const(false)
            }
        }
    }

    pub(super) fn function(&mut self, f: &Ident, args: &[Arg], e: &ast::Expr) -> BoolExpr {
        let name = f.key();
        if name.contains('.') {
            let what = format!("the method call `{}(…)`", f.name);
            self.refuse(f.span, &what, "methods (object-oriented extensions) are not read");
            return BoolExpr::Const(false);
        }
        if self.user.get(&name).is_some_and(|p| p.kind == ast::PouKind::Function) {
            return match self.user_function(f, None, args) {
                Some(v) => v,
                None => self.not_bool(e, &format!("the result of `{}`", f.name)),
            };
        }
        let call_args = args;
        let args = match self.std_args(f, args) {
            Ok(args) => args,
            Err(why) => {
                let help = "give the inputs by position or each by its parameter's name";
                self.errors.push(StError::new(f.span, why, help));
                return BoolExpr::Const(false);
            }
        };
        // Where `EN` is FALSE matiec's `TEST_EN` returns FALSE.
        let en = args.en.map(|x| self.bool_expr(x));
        self.std_eno(f, call_args, &args.values, en.clone());
        let value = self.std_function(f, &args.values, e);
        match en {
            Some(en) => BoolExpr::and(en, value),
            None => value,
        }
    }

    fn std_function(&mut self, f: &Ident, values: &[&ast::Expr], e: &ast::Expr) -> BoolExpr {
        let name = f.key();
        match name.as_str() {
            "AND" | "OR" | "XOR" if values.len() >= 2 => {
                let vs: Vec<BoolExpr> = values.iter().map(|x| self.bool_expr(x)).collect();
                let mut it = vs.into_iter();
                let first = it.next().unwrap_or(BoolExpr::Const(false));
                match name.as_str() {
                    "AND" => it.fold(first, BoolExpr::and),
                    "OR" => BoolExpr::Or(std::iter::once(first).chain(it).collect()),
                    _ => it.fold(first, xor),
                }
            }
            "NOT" if values.len() == 1 => BoolExpr::negate(self.bool_expr(values[0])),
            "SEL" if values.len() == 3 => {
                let g = self.bool_expr(values[0]);
                let (a, b) = (self.bool_expr(values[1]), self.bool_expr(values[2]));
                BoolExpr::Or(vec![
                    BoolExpr::and(BoolExpr::negate(g.clone()), a),
                    BoolExpr::and(g, b),
                ])
            }
            "GT" | "GE" | "EQ" | "NE" | "LT" | "LE" if values.len() >= 2 => {
                let op = match name.as_str() {
                    "GT" => CmpOp::Gt,
                    "GE" => CmpOp::Ge,
                    "EQ" => CmpOp::Eq,
                    "NE" => CmpOp::Ne,
                    "LT" => CmpOp::Lt,
                    _ => CmpOp::Le,
                };
                // Extensible: `GT(a, b, c)` is `a > b AND b > c`.
                let all: Vec<BoolExpr> =
                    values.windows(2).map(|w| self.int_compare(op, w[0], w[1], e.span)).collect();
                all.into_iter().reduce(BoolExpr::and).unwrap_or(BoolExpr::Const(true))
            }
            n if n.ends_with("_TO_BOOL") && values.len() == 1 => {
                self.conversion_to_bool(f, &n[..n.len() - "_TO_BOOL".len()], values[0], e.span)
            }
            _ => {
                self.refuse(f.span, &format!("the function `{}`", f.name), "the Boolean functions AND, OR, XOR, NOT, SEL, the comparisons and the conversions `*_TO_BOOL` are computed");
                BoolExpr::Const(false)
            }
        }
    }
}

pub(super) fn xor(a: BoolExpr, b: BoolExpr) -> BoolExpr {
    BoolExpr::Or(vec![
        BoolExpr::and(a.clone(), BoolExpr::negate(b.clone())),
        BoolExpr::and(BoolExpr::negate(a), b),
    ])
}

impl Lowering<'_> {
    /// Whether `selector` matches a `CASE` label (`a` or `a..b`): for a BOOL selector an
    /// equivalence, else integer comparisons.
    pub(super) fn case_label(
        &mut self,
        selector: &ast::Expr,
        (a, b): &(ast::Expr, Option<ast::Expr>),
    ) -> BoolExpr {
        if b.is_none() && self.is_bool(selector) && self.is_bool(a) {
            let (s, v) = (self.bool_expr(selector), self.bool_expr(a));
            return BoolExpr::negate(xor(s, v));
        }
        match b {
            None => self.int_compare(CmpOp::Eq, selector, a, a.span),
            Some(b) => {
                let span = a.span.to(b.span);
                let low = self.int_compare(CmpOp::Ge, selector, a, span);
                let high = self.int_compare(CmpOp::Le, selector, b, span);
                BoolExpr::and(low, high)
            }
        }
    }

    /// A `FOR` loop's first value, step and number of iterations: its bounds and step
    /// must be known before the scan (literals, constants, values fixed by assignments
    /// earlier in the scan).
    pub(super) fn iterations(
        &mut self,
        var: &Ident,
        from: &ast::Expr,
        to: &ast::Expr,
        by: Option<&ast::Expr>,
        span: Span,
    ) -> Option<(i64, i64, u64)> {
        let _ = self.lookup(var)?;
        let bounds = [Some(from), Some(to), by];
        let mut values = Vec::new();
        for e in bounds.into_iter().flatten() {
            let errors = self.errors.len();
            match self.known_value(e) {
                Ok(v) => values.push(i128::from(v)),
                Err(_) if self.errors.len() > errors => return None,
                Err(detail) => {
                    self.errors.push(StError::new(
                        e.span,
                        format!("this FOR loop's bound or step is not known before the scan: {detail}"),
                        "ii-prove unrolls a loop only when the values that count its iterations are fixed by assignments earlier in the same scan",
                    ));
                    return None;
                }
            }
        }
        let (a, b, step) = (values[0], values[1], values.get(2).copied().unwrap_or(1));
        if step == 0 {
            self.errors.push(StError::new(
                by.map_or(span, |e| e.span),
                "a FOR loop with a step of 0 never ends",
                "expected a step other than 0",
            ));
            return None;
        }
        let n = if (step > 0 && a > b) || (step < 0 && a < b) { 0 } else { (b - a) / step + 1 };
        if n == 1 {
            // matiec tests `i + step` against the bound before the first iteration.
            self.refuse(
                span,
                "a FOR loop of one iteration",
                "matiec (Beremiz, OpenPLC) runs it zero times where IEC 61131-3 runs it once; write its statements without the loop",
            );
            return None;
        }
        if n > i128::from(MAX_ITERATIONS) {
            self.refuse(
                span,
                &format!("a FOR loop of {n} iterations"),
                &format!("ii-prove unrolls loops of at most {MAX_ITERATIONS} iterations"),
            );
            return None;
        }
        Some((i64::try_from(a).ok()?, i64::try_from(step).ok()?, u64::try_from(n).ok()?))
    }
}

/// The comparison of a comparison operator (`=`, `<>`, `<`, `<=`, `>`, `>=`).
pub(super) fn comparison_op(op: BinOp) -> CmpOp {
    match op {
        BinOp::Eq => CmpOp::Eq,
        BinOp::Ne => CmpOp::Ne,
        BinOp::Lt => CmpOp::Lt,
        BinOp::Le => CmpOp::Le,
        BinOp::Gt => CmpOp::Gt,
        _ => CmpOp::Ge,
    }
}

/// An integer literal 0 or 1 (in any base), which matiec reads as FALSE or TRUE where a
/// BOOL is expected.
fn bit_literal(e: &ast::Expr) -> Option<bool> {
    match e.kind {
        ExprKind::Int(0) => Some(false),
        ExprKind::Int(1) => Some(true),
        _ => None,
    }
}
