//! Integers of Structured Text in the scan model, as matiec compiles them to C: the IEC integer types (`SINT` … `UDINT`, `BYTE` … `DWORD`), literals and constants, `+ - * / MOD`, unary `-`, comparisons, stores (the functions and conversions are in `int_functions.rs`); values narrower than 32 bits are computed as C `int`, as the generated C does. An integer whose value cannot be computed exactly (a division by a variable, a `TIME` or `REAL` operand, a 64-bit type) is *opaque*: what reads it is an unconstrained value, with the reason.

use super::reals::Double;
use super::{Fb, Lowering, Sym, Ty};
use crate::diag::Span;
use crate::iec::StError;
use crate::iec::ast::{self, BinOp, ExprKind, UnOp};
use crate::program::{
    BoolExpr, C_INT, Checked, CheckedOp, CmpOp, Compare, Fresh, IntExpr, IntType, IntVar, Stmt,
    library, promoted,
};

pub(super) use crate::program::library::{counter_type, int_type, type_name};

/// What the C matiec writes for a division computes for a divisor 0.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum ByZero {
    /// 0: the `DIV` and `MOD` functions (`TEST_EN_COND(…, op2 == 0)`, `if (op2 == 0)
    /// return 0;`) and Structured Text's `MOD` (`((b == 0)?0:a % b)`).
    Zero,
    /// Nothing defined (C's `/` and `%`: Structured Text's `/`, Instruction List's `DIV`
    /// and `MOD`): the division is computed only by a literal that is not 0.
    Undefined,
}

/// A typed integer expression: its value, its type (`None`: a literal, typed by where
/// it is used) and whether it divides (its result then depends on the width it is
/// computed in).
#[derive(Clone, Debug)]
pub(super) struct Int {
    pub e: IntExpr,
    pub ty: Option<IntType>,
    divides: bool,
    /// A `REAL` the generated C computes in `double` ([`Double`]).
    pub(super) double: Option<Double>,
    /// The bounds of the value C computes (in `int` for a narrower type) where they are
    /// not the type's: an arithmetic result's, which tell where it cannot overflow.
    bounds: Option<(i128, i128)>,
}

impl Int {
    /// The value `e`, of type `ty` (`None`: an integer literal).
    pub(super) fn of(e: IntExpr, ty: Option<IntType>) -> Int {
        Int { e, ty, divides: false, double: None, bounds: None }
    }

    /// The variable `name` of type `t`.
    pub(super) fn var(name: &str, t: IntType) -> Int {
        Int::of(IntExpr::Var(name.to_string()), Some(t))
    }

    pub(super) fn literal(v: i128) -> Int {
        Int::of(IntExpr::Const(v.clamp(i64::MIN.into(), i64::MAX.into()) as i64), None)
    }

    /// The bounds of the value C computes.
    pub(super) fn bounds(&self) -> (i128, i128) {
        match (self.bounds, &self.e, self.ty) {
            (Some(b), ..) => b,
            (None, IntExpr::Const(k), _) => (i128::from(*k), i128::from(*k)),
            (None, _, t) => {
                let t = t.unwrap_or(C_INT);
                (t.min().into(), t.max().into())
            }
        }
    }

    /// The value as C computes it, read in a context of the type `t` it has: computed
    /// in `int` where a division makes the width matter, else in `t` itself (sums,
    /// differences and products wrap alike in any width at least `t`'s).
    pub(super) fn in_type(self, t: IntType) -> IntExpr {
        if self.divides && promoted(t) != t {
            IntExpr::Cast(Box::new(self.e), promoted(t))
        } else {
            self.e
        }
    }
}

/// Why an integer is not computed (said where it is read).
pub(super) type Opaque = String;

impl Lowering<'_> {
    /// The integer expression `e`, typed; `Err` with the reason when its value is not
    /// computed exactly (type errors are also pushed as errors).
    pub(super) fn int_expr(&mut self, e: &ast::Expr) -> Result<Int, Opaque> {
        match &e.kind {
            ExprKind::Int(v) => Ok(Int::literal(*v)),
            ExprKind::Literal(s) => self.typed_literal(s, e.span),
            ExprKind::Var(id) => {
                let Some(sym) = self.lookup(id) else { return Err("an unknown variable".into()) };
                self.int_var(&sym, e.span)
            }
            ExprKind::Member(of, field) => {
                let ExprKind::Var(id) = &of.kind else {
                    return Err(format!("`{}` is not modelled", self.text(e.span)));
                };
                let Some(sym) = self.lookup(id) else { return Err("an unknown variable".into()) };
                match (&sym.ty, field.key().as_str()) {
                    (Ty::Fb(super::calls::Fb::Counter, ty), "CV") => match counter_type(ty) {
                        Some(t) => {
                            let cv = self.counter_value(&sym.name, t);
                            self.int_read(cv, t)
                        }
                        None => Err(format!(
                            "the count of the {ty} `{}` is 64 bits, which ii-prove does not compute",
                            sym.name
                        )),
                    },
                    (Ty::Fb(Fb::Ton | Fb::Tof | Fb::Tp, _), "ET") => self.elapsed_read(&sym.name),
                    (Ty::User(_), _) => match self
                        .instances
                        .get(&sym.name)
                        .and_then(|t| t.get(&field.key()))
                        .cloned()
                    {
                        Some(s) => self.int_var(&s, e.span),
                        None => {
                            Err(format!("`{}` is not an integer of `{}`", field.name, sym.name))
                        }
                    },
                    _ => Err(format!("`{}` is not modelled", self.text(e.span))),
                }
            }
            ExprKind::Unary(UnOp::Neg, x) => {
                let x = self.int_expr(x)?;
                no_time_arithmetic(&[&x])?;
                if x.is_real() {
                    return Ok(x.real_negated());
                }
                match x.e {
                    IntExpr::Const(v) if x.ty.is_none() => Ok(Int::literal(-i128::from(v))),
                    _ => self.c_arithmetic(CheckedOp::Sub, Int::literal(0), x, e.span, "NEG"),
                }
            }
            ExprKind::Binary(
                op @ (BinOp::Add | BinOp::Sub | BinOp::Mul | BinOp::Div | BinOp::Mod),
                a,
                b,
            ) => {
                let (a, b) = (self.int_expr(a)?, self.int_expr(b)?);
                no_time_arithmetic(&[&a, &b])?;
                if a.is_real() || b.is_real() {
                    return self.real_arithmetic(*op, a, b, e.span);
                }
                // matiec writes `MOD` as `((b == 0)?0:a % b)` and `/` as C's `/`.
                let zero = if *op == BinOp::Mod { ByZero::Zero } else { ByZero::Undefined };
                self.arithmetic(*op, a, b, e.span, zero)
            }
            ExprKind::Binary(BinOp::Pow, ..) => Err("`**` computes in REAL".into()),
            ExprKind::Call(f, args) => self.int_function(f, args, e),
            ExprKind::Time(_) => {
                match crate::iec::literal::matiec_duration_ns(&self.text(e.span)) {
                    Some(ns) if IntType::TIME.contains(ns) => {
                        Ok(Int::of(IntExpr::Const(ns), Some(IntType::time_for(ns as u64))))
                    }
                    _ => Err(format!(
                        "the TIME literal `{}` is not computed (a part in us or ns, which matiec \
                     does not read, or beyond 2^62 ns)",
                        self.text(e.span)
                    )),
                }
            }
            _ => {
                self.errors.push(StError::new(
                    e.span,
                    "a BOOL where an integer is expected",
                    "expected an integer",
                ));
                Err("a type error".into())
            }
        }
    }

    /// A read of the variable `sym`.
    fn int_var(&mut self, sym: &Sym, span: Span) -> Result<Int, Opaque> {
        match &sym.ty {
            Ty::Int(t) => {
                if let Some(v) = self.constants.get(&sym.name) {
                    return Ok(Int::of(IntExpr::Const(*v), Some(*t)));
                }
                if let Some((why, _)) = self.opaque.get(&sym.name) {
                    return Err(format!("{} is not computed: {why}", sym.name));
                }
                self.int_read(sym.name.clone(), *t)
            }
            Ty::Other(t) => Err(format!("the {t} variable {} is not computed", sym.name)),
            Ty::Bool => {
                self.errors.push(StError::new(
                    span,
                    format!("the BOOL `{}` where an integer is expected", sym.name),
                    "expected an integer (convert with BOOL_TO_INT)",
                ));
                Err("a type error".into())
            }
            Ty::Fb(_, t) | Ty::User(t) => {
                Err(format!("the {t} instance {} is not a value", sym.name))
            }
        }
    }

    fn int_read(&mut self, name: String, t: IntType) -> Result<Int, Opaque> {
        Ok(Int::var(&name, t))
    }

    /// `INT#5`, `DINT#16#FF`, `UINT#-0` and such.
    fn typed_literal(&mut self, s: &str, span: Span) -> Result<Int, Opaque> {
        if let Some(x) = Int::real_literal(s) {
            return Ok(x);
        }
        let Some((ty, value)) = s.split_once('#') else {
            return Err(format!("the literal `{s}` is not an integer"));
        };
        let Some(t) = int_type(&ty.to_ascii_uppercase()) else {
            return Err(format!("the literal `{s}` is not computed"));
        };
        let digits: String = value.chars().filter(|c| *c != '_').collect();
        let (negative, digits) = match digits.strip_prefix('-') {
            Some(d) => (true, d.to_string()),
            None => (false, digits.trim_start_matches('+').to_string()),
        };
        let parsed = match digits.split_once('#') {
            Some((base, d)) => {
                base.parse::<u32>().ok().and_then(|b| i128::from_str_radix(d, b).ok())
            }
            None => digits.parse::<i128>().ok(),
        };
        let Some(v) = parsed.map(|v| if negative { -v } else { v }) else {
            self.errors.push(StError::new(
                span,
                format!("`{s}` is not an integer literal"),
                "expected digits",
            ));
            return Err("a bad literal".into());
        };
        Ok(Int::of(IntExpr::Const(t.wrap(v as i64)), Some(t)))
    }

    /// The type two operands share (a literal takes the other's).
    pub(super) fn unify(
        &mut self,
        a: &Int,
        b: &Int,
        span: Span,
    ) -> Result<Option<IntType>, Opaque> {
        if (a.is_real() && b.ty.is_none()) || (b.is_real() && a.ty.is_none()) {
            self.errors.push(StError::new(
                span,
                "an integer literal where a REAL is expected",
                "write it as a real literal (`50.0`): matiec's type check refuses an integer one",
            ));
            return Err("a type error".into());
        }
        match (a.ty, b.ty) {
            // Durations: each held in the bits its values need, compared in the wider.
            (Some(x), Some(y)) if x.time && y.time => Ok(Some(x.max_by_bits(y))),
            (Some(x), Some(y)) if x != y => {
                let mut e = StError::new(
                    span,
                    format!("this mixes {} and {}", type_name(x), type_name(y)),
                    "operands of different integer types",
                );
                e.notes.push(format!(
                    "IEC 61131-3 (and matiec) want one type: convert one side, e.g. {}_TO_{}(…)",
                    type_name(x.min_by_bits(y)),
                    type_name(x.max_by_bits(y))
                ));
                self.errors.push(e);
                Err("a type error".into())
            }
            (x, y) => Ok(x.or(y)),
        }
    }

    pub(super) fn arithmetic(
        &mut self,
        op: BinOp,
        a: Int,
        b: Int,
        span: Span,
        zero: ByZero,
    ) -> Result<Int, Opaque> {
        let ty = self.unify(&a, &b, span)?;
        if let (IntExpr::Const(x), IntExpr::Const(y), None) = (&a.e, &b.e, ty) {
            // Two literals: folded (as C folds them, in a wide type).
            let (x, y) = (i128::from(*x), i128::from(*y));
            let v = match op {
                BinOp::Add => Some(x + y),
                BinOp::Sub => Some(x - y),
                BinOp::Mul => x.checked_mul(y),
                BinOp::Div if y != 0 => Some(x / y),
                BinOp::Mod if y != 0 => Some(x % y),
                _ => None,
            };
            if let Some(v) = v {
                return Ok(Int::literal(v));
            }
        }
        let (cop, keyword) = match op {
            BinOp::Add => (CheckedOp::Add, "ADD"),
            BinOp::Sub => (CheckedOp::Sub, "SUB"),
            BinOp::Mul => (CheckedOp::Mul, "MUL"),
            BinOp::Div => (CheckedOp::Div, "DIV"),
            _ => (CheckedOp::Mod, "MOD"),
        };
        if matches!(op, BinOp::Div | BinOp::Mod) {
            let k = match (&b.e, ty) {
                (IntExpr::Const(k), Some(t)) => t.wrap(*k),
                (IntExpr::Const(k), None) => *k,
                // A divisor 0 gives 0 (`DivBy`, `ModBy`).
                _ if zero == ByZero::Zero => return self.c_arithmetic(cop, a, b, span, keyword),
                _ => {
                    return Err(format!(
                        "`{}` divides by a variable, which may be 0 (a run-time error of the PLC)",
                        self.text(span)
                    ));
                }
            };
            if k == 0 && zero == ByZero::Zero {
                return Ok(Int::of(IntExpr::Const(0), ty));
            }
            if k == 0 {
                return Err(format!("`{}` divides by 0", self.text(span)));
            }
            let b = Int::of(IntExpr::Const(k), b.ty);
            return self.c_arithmetic(cop, a, b, span, keyword);
        }
        self.c_arithmetic(cop, a, b, span, keyword)
    }

    /// `a op b` (operands of one type, a divisor a literal that is not 0) as the C
    /// matiec writes computes it: in the type's promoted type, C's `int` for `DINT` and
    /// every narrower type, where a result beyond `int` is undefined: there it is the
    /// value of a free input (named after `keyword` and the line, with a warning), unless
    /// the operands' bounds show it cannot happen (`INT + INT` never overflows `int`).
    fn c_arithmetic(
        &mut self,
        op: CheckedOp,
        a: Int,
        b: Int,
        span: Span,
        keyword: &str,
    ) -> Result<Int, Opaque> {
        let ty = self.unify(&a, &b, span)?;
        let divides = a.divides || b.divides || matches!(op, CheckedOp::Div | CheckedOp::Mod);
        let c = ty.map_or(C_INT, promoted);
        let (lo, hi) = op.bounds(a.bounds(), b.bounds());
        let fits = i128::from(c.min()) <= lo && hi <= i128::from(c.max());
        if c == C_INT && !fits {
            let undefined = self.overflow_input(keyword, span);
            let e =
                IntExpr::Checked(Box::new(Checked { op, a: a.e, b: b.e, ty: C_INT, undefined }));
            let bounds = Some((C_INT.min().into(), C_INT.max().into()));
            return Ok(Int { e, ty, divides, double: None, bounds });
        }
        let (x, y) = (Box::new(a.e), Box::new(b.e));
        let e = match (op, &*y) {
            (CheckedOp::Add, _) => IntExpr::Add(x, y),
            (CheckedOp::Sub, _) => IntExpr::Sub(x, y),
            (CheckedOp::Mul, _) => IntExpr::Mul(x, y),
            (CheckedOp::Div, IntExpr::Const(k)) => IntExpr::Div(x, *k),
            (CheckedOp::Mod, IntExpr::Const(k)) => IntExpr::Mod(x, *k),
            (CheckedOp::Div, _) => IntExpr::DivBy(x, y),
            (CheckedOp::Mod, _) => IntExpr::ModBy(x, y),
        };
        // Unsigned arithmetic wraps (C defines it): any value of the type.
        let bounds = fits.then_some((lo, hi));
        Ok(Int { e, ty, divides, double: None, bounds })
    }

    /// A new free integer of C's `int`, the value of the operation at `span` where it
    /// overflows (which C leaves undefined), with a warning that says so.
    pub(super) fn overflow_input(&mut self, keyword: &str, span: Span) -> String {
        let free = self.unique(&format!("{keyword}_OVERFLOW_L{:02}", self.line_of(span)));
        self.ints.insert(free.clone(), IntVar { ty: C_INT, input: true, init: 0 });
        self.undefined.insert(free.clone());
        self.warnings.push(StError::warning(
            span,
            format!(
                "`{}` may overflow the 32-bit `int` the generated C computes it in, which C \
                 leaves undefined: there its value is the free input {free}",
                self.text(span)
            ),
        ));
        free
    }

    /// `a op b` for integers: exact, else an unconstrained value with the reason.
    pub(super) fn int_compare(
        &mut self,
        op: CmpOp,
        a: &ast::Expr,
        b: &ast::Expr,
        span: Span,
    ) -> BoolExpr {
        let values = self.int_expr(a).and_then(|a| Ok((a, self.int_expr(b)?)));
        match values {
            Ok((a, b)) => self.int_compare_values(op, a, b, span),
            Err(why) => self.unknown_comparison(op, span, &why),
        }
    }

    /// `a op b` for integer values already lowered.
    pub(super) fn int_compare_values(&mut self, op: CmpOp, a: Int, b: Int, span: Span) -> BoolExpr {
        if a.is_real() || b.is_real() {
            return self.real_compare(op, a, b, span);
        }
        let ty = match self.unify(&a, &b, span) {
            Ok(t) => t,
            Err(why) => return self.unknown_comparison(op, span, &why),
        };
        if let (IntExpr::Const(x), IntExpr::Const(y), None) = (&a.e, &b.e, ty) {
            return BoolExpr::Const(op.holds(*x, *y));
        }
        // Values of literals alone (`MIN(3, 5)`) are C `int`s.
        let t = ty.unwrap_or(C_INT);
        // As C compares: in `int` for narrow types (no wrap of `a + 1`), unless both
        // sides are plain values, which compare alike in their own type.
        let within = |x: &Int| {
            matches!(x.e, IntExpr::Const(k) if t.contains(k)) || matches!(x.e, IntExpr::Var(_))
        };
        let cty = if within(&a) && within(&b) { t } else { promoted(t) };
        BoolExpr::Compare(Box::new(Compare { op, ty: cty, a: a.e, b: b.e }))
    }

    /// An unconstrained comparison, with the reason its operands are not computed.
    pub(super) fn unknown_comparison(&mut self, op: CmpOp, span: Span, why: &str) -> BoolExpr {
        let keyword = match op {
            CmpOp::Eq => "EQ",
            CmpOp::Ne => "NE",
            CmpOp::Lt => "LT",
            CmpOp::Le => "LE",
            CmpOp::Gt => "GT",
            CmpOp::Ge => "GE",
        };
        BoolExpr::Fresh(Box::new(Fresh {
            base: format!("{keyword}_L{:02}", self.line),
            keyword: keyword.to_string(),
            why: format!("the comparison `{}` is not computed: {why}", self.text(span)),
            span,
            peripheral: false,
        }))
    }

    /// `target := value` for the integer `target` of type `t` (its name in the scan
    /// model): exact, else `target` becomes opaque (lowered again without it).
    pub(super) fn int_assign(
        &mut self,
        target: &str,
        t: IntType,
        value: &ast::Expr,
        span: Span,
    ) -> Vec<Stmt> {
        let v = self.int_expr(value);
        self.int_store(target, t, v, value.span, span)
    }

    /// `target := v` for the integer `target` of type `t`, `v` lowered already (`at`
    /// its source): exact, else `target` becomes opaque.
    pub(super) fn int_store(
        &mut self,
        target: &str,
        t: IntType,
        v: Result<Int, Opaque>,
        at: Span,
        span: Span,
    ) -> Vec<Stmt> {
        if self.opaque.contains_key(target) {
            return Vec::new();
        }
        match v.and_then(|v| {
            self.unify(&v, &Int::of(IntExpr::Const(0), Some(t)), at)?;
            Ok(v)
        }) {
            Ok(v) => vec![Stmt::SetInt { target: target.to_string(), value: v.in_type(t), span }],
            Err(why) => {
                self.make_opaque(target, why, span);
                Vec::new()
            }
        }
    }

    /// An Instruction List arithmetic instruction (`ADD x`, …) on the current result
    /// `cr`: matiec's C computes `CR op= x` in the current result's type, so the value
    /// wraps to that type at each instruction.
    pub(super) fn il_arithmetic(
        &mut self,
        op: BinOp,
        cr: Int,
        x: Int,
        span: Span,
    ) -> Result<Int, Opaque> {
        // matiec's C: `CR /= x`, `CR %= x`.
        let v = self.arithmetic(op, cr, x, span, ByZero::Undefined)?;
        Ok(match v.ty {
            Some(t) => Int::of(IntExpr::Cast(Box::new(v.in_type(t)), t), Some(t)),
            None => v,
        })
    }

    /// The integer `v` kept in a hidden variable written here (so later writes leave
    /// what it read); a literal stays as it is.
    pub(super) fn int_temp(&mut self, out: &mut Vec<Stmt>, v: Int, span: Span) -> Int {
        let (false, Some(t)) = (matches!(v.e, IntExpr::Const(_)), v.ty) else { return v };
        let name = self.unique("_IL_CR");
        self.ints.insert(name.clone(), IntVar { ty: t, input: false, init: 0 });
        out.push(Stmt::SetInt { target: name.clone(), value: v.in_type(t), span });
        Int::var(&name, t)
    }

    /// The value of `e` here, computed as C computes it (in `int` at least), when the
    /// values it reads are known before the scan; else what is not known.
    pub(super) fn known_value(&mut self, e: &ast::Expr) -> Result<i64, String> {
        let v = self.int_expr(e)?;
        if v.is_real() {
            return Err("a REAL".into());
        }
        let t = v.ty.map_or(C_INT, promoted);
        self.known_int(&v.in_type(t), t).map_err(|x| format!("it reads {x}"))
    }

    /// The value of `e` for an integer input of type `t` (an FB's `PV`), or why not.
    pub(super) fn int_input(&mut self, e: &ast::Expr, t: IntType) -> Result<IntExpr, Opaque> {
        let v = self.int_expr(e)?;
        self.unify(&v, &Int::of(IntExpr::Const(0), Some(t)), e.span)?;
        Ok(v.in_type(t))
    }

    /// Marks `x` as opaque for `why`, found at `at` (the program is then lowered again).
    pub(super) fn make_opaque(&mut self, x: &str, why: Opaque, at: Span) {
        self.opaque.entry(x.to_string()).or_insert((why, at));
    }
}

impl Lowering<'_> {
    /// matiec's `__CHECK_R(value)` on the integer `name` of type `t` just written, when
    /// it is of a subrange type (`generate_c_typedecl.cc`): below the lower limit it
    /// takes the lower limit, above the upper one the upper one. matiec calls it where a
    /// call passes a value into a variable of a subrange type — a function block's
    /// input, an output given with `=>` — not on `:=` or an IL `ST` (docs/iec.md).
    pub(super) fn subrange_check(&self, name: &str, t: IntType, span: Span) -> Option<Stmt> {
        let &(lo, hi) = self.ranges.get(name)?;
        let value = library::subrange_check(t, IntExpr::var(name), lo, hi);
        Some(Stmt::SetInt { target: name.to_string(), value, span })
    }
}

trait ByBits {
    fn min_by_bits(self, o: IntType) -> IntType;
    fn max_by_bits(self, o: IntType) -> IntType;
}

impl ByBits for IntType {
    fn min_by_bits(self, o: IntType) -> IntType {
        if self.bits <= o.bits { self } else { o }
    }
    fn max_by_bits(self, o: IntType) -> IntType {
        if self.bits <= o.bits { o } else { self }
    }
}

impl Lowering<'_> {
    /// Declares the integer `name` of type `t` (`v` its declaration): its start value,
    /// whether the outside world writes it, or its constant value.
    pub(super) fn declare_int(&mut self, v: &ast::VarDecl, name: &str, t: IntType, input: bool) {
        // A subrange variable starts at its lower limit (matiec's `__INIT_VAR`).
        let init = match &v.init {
            None => Some(v.range.map_or(0, |r| r.0)),
            Some(e) => match self.int_expr(e) {
                Ok(Int { e: IntExpr::Const(k), ty, .. }) if ty.map_or(!t.real, |x| x == t) => {
                    Some(t.wrap(k))
                }
                _ => None,
            },
        };
        if let Some(r) = v.range {
            self.ranges.insert(name.to_string(), r);
        }
        let Some(init) = init else {
            let why = format!(
                "its initial value `{}` is not {}",
                self.text(v.init.as_ref().map_or(v.name.span, |e| e.span)),
                if t.real { "a real literal" } else { "an integer literal" }
            );
            self.make_opaque(name, why, v.name.span);
            return;
        };
        if v.constant {
            self.constants.insert(name.to_string(), init);
            return;
        }
        let input = input
            || v.location.as_deref().is_some_and(|l| l.to_ascii_uppercase().starts_with("%I"));
        self.ints
            .insert(name.to_string(), IntVar { ty: t, input, init: if input { 0 } else { init } });
    }
}

impl Lowering<'_> {
    /// A warning for each opaque integer, where it was found not computed.
    pub(super) fn warn_opaque(&mut self) {
        for (x, (why, at)) in &self.opaque {
            // Its declared type (`the REAL Level`), else an integer (a counter's count).
            let ty = self.syms.values().find(|s| s.name == *x).and_then(|s| s.ty.value_type());
            let what = ty.as_deref().unwrap_or("integer");
            self.warnings.push(StError::warning(
                *at,
                format!("the {what} {x} is not computed ({why}): what reads it is unconstrained"),
            ));
        }
    }
}

impl Lowering<'_> {
    /// `target := source` for the integer `source` of type `t` (an FB output given with
    /// `=>`): exact, else `target` is opaque too.
    pub(super) fn int_copy(
        &mut self,
        target: &ast::Expr,
        source: &str,
        t: IntType,
        span: Span,
    ) -> Vec<Stmt> {
        let Some(id) = self.written_variable(target, "an integer variable") else {
            return Vec::new();
        };
        let Some(sym) = self.lookup(id) else { return Vec::new() };
        match sym.ty {
            Ty::Int(u) if u == t => {
                if let Some((why, _)) = self.opaque.get(source).cloned() {
                    self.make_opaque(
                        &sym.name,
                        format!("it takes {source}, which is not computed: {why}"),
                        span,
                    );
                    return Vec::new();
                }
                if self.opaque.contains_key(&sym.name) {
                    return Vec::new();
                }
                let mut out = vec![Stmt::SetInt {
                    target: sym.name.clone(),
                    value: IntExpr::var(source),
                    span,
                }];
                out.extend(self.subrange_check(&sym.name, t, span));
                out
            }
            _ => {
                self.errors.push(StError::new(
                    id.span,
                    format!("`{}` is not a {} variable", id.name, type_name(t)),
                    "the output's type",
                ));
                Vec::new()
            }
        }
    }
}

/// A write of a variable of a type ii-prove does not compute (`STRING`, `TIME`, …): no
/// effect in the scan model (what reads it is not computed), with a warning at `element`.
pub(super) fn integer_write(span: Span, element: &str, ty: &str, name: &str) -> Stmt {
    Stmt::Warn {
        span,
        element: element.to_string(),
        message: format!(
            "writes the {ty} variable {name}, which is not computed: what reads it is not \
             computed either"
        ),
    }
}

/// `Err` where one of `values` is a TIME: its arithmetic is not computed (matiec adds
/// `{tv_sec, tv_nsec}` pairs, whose overflow the scan model's integers do not follow).
pub(super) fn no_time_arithmetic(values: &[&Int]) -> Result<(), Opaque> {
    match values.iter().any(|x| x.ty.is_some_and(|t| t.time)) {
        true => Err("TIME arithmetic is not computed".into()),
        false => Ok(()),
    }
}
