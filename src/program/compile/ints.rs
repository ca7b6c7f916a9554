//! The integer part of the II compiler: each integer variable of the scan model is compiled into the bits of its value (bit-blasting), so its writes become bit writes the compiler already states exactly, and comparisons Boolean functions of those bits.
//!
//! An integer `X` of `w` bits is the signals `X_b0 … X_b{w-1}` ([`SignalKind::IntBit`]),
//! least significant first. A variable that starts at a value `v ≠ 0` (a counter's
//! `init`) is stored as `X xor v`, so that every bit starts at 0 as the algebra's `pre`
//! does: reads flip the bits that are 1 in `v`, writes flip them back. Arithmetic wraps to
//! the variable's width ([`super::super::bitvec`]). A bit term larger than
//! [`MAX_INT_TERM`] nodes is named: an intermediate signal ([`SignalKind::Intermediate`])
//! defined by an exact equation stated with its block, so sums and products stay linear
//! in the width.

use super::super::bitvec::{self, Bits};
use super::super::logic::{L, simp};
use super::super::{
    BitOp, BoolExpr, Checked, CheckedOp, Compare, IntExpr, IntType, IntVar, Program, RealOp, Stmt,
    WriteKind,
};
use super::{CompileError, Compiler, Pending, SignalKind};
use crate::diag::Span;

/// The largest bit term of an integer value inlined into later reads.
pub(super) const MAX_INT_TERM: usize = 200;

/// The size beyond which a term inside a division is named (see [`MAX_INT_TERM`]).
const MAX_DIV_TERM: usize = 12;

impl Compiler<'_> {
    /// The variable `x`, or an error at `span` when the program does not declare it.
    fn int_var(&mut self, x: &str, span: Span) -> Option<IntVar> {
        if let Some(v) = self.program.integers.get(x) {
            return Some(*v);
        }
        if !self.errors.iter().any(|e| e.span == span) {
            self.errors.push(CompileError {
                span,
                keyword: "INT".into(),
                reason: format!("the integer {x} has no declared type"),
            });
        }
        None
    }

    /// A `REAL` where the scan model has only integer arithmetic, or an integer where a
    /// `REAL` is expected: an error at `span` (a front end converts with its own
    /// operations), and 0.
    fn not_real(&mut self, ty: IntType, span: Span) -> Bits {
        if !self.errors.iter().any(|e| e.span == span) {
            self.errors.push(CompileError {
                span,
                keyword: "REAL".into(),
                reason: "a REAL is computed only by comparisons, choices, copies and \
                         operations on its bits, never by integer arithmetic or casts"
                    .into(),
            });
        }
        bitvec::constant(0, ty.bits)
    }

    /// The value of `e` in type `ty` at this point of the scan.
    pub(super) fn int(&mut self, e: &IntExpr, ty: IntType, span: Span) -> Bits {
        let w = ty.bits;
        let real_op = !matches!(
            e,
            IntExpr::Const(_)
                | IntExpr::Var(_)
                | IntExpr::Ite(..)
                | IntExpr::Bitwise(..)
                | IntExpr::ToReal(..)
                | IntExpr::Real(..)
                | IntExpr::Sqrt(..)
        );
        if ty.real && real_op {
            return self.not_real(ty, span);
        }
        match e {
            IntExpr::Const(v) => bitvec::constant(ty.wrap(*v), w),
            IntExpr::Var(x) => {
                let Some(var) = self.int_var(x, span) else { return bitvec::constant(0, w) };
                if var.ty.real != ty.real || (ty.real && var.ty.bits != ty.bits) {
                    return self.not_real(ty, span);
                }
                let stored = var.value(x, &mut |b| self.read(b));
                bitvec::resize(stored, var.ty, ty)
            }
            IntExpr::Add(a, b) | IntExpr::Sub(a, b) | IntExpr::Mul(a, b) => {
                let a = self.int(a, ty, span);
                let b = self.int(b, ty, span);
                let mut name = |t: L| self.intermediate(t);
                match e {
                    IntExpr::Add(..) => bitvec::add(&a, &b, L::Zero, &mut name),
                    IntExpr::Sub(..) => bitvec::sub(&a, &b, &mut name),
                    _ => bitvec::mul(&a, &b, &mut name),
                }
            }
            IntExpr::Div(a, k) => {
                // Each step of the division reads the remainder's bits several times:
                // anything beyond a few nodes is named, or the terms grow with every step.
                let a = self.int(a, ty, span);
                bitvec::div(&a, *k, ty, &mut |t: L| self.intermediate_over(t, MAX_DIV_TERM))
            }
            IntExpr::Mod(a, k) => {
                let a = self.int(a, ty, span);
                bitvec::rem(&a, *k, ty, &mut |t: L| self.intermediate_over(t, MAX_DIV_TERM))
            }
            IntExpr::DivBy(a, b) | IntExpr::ModBy(a, b) => {
                let a = self.int(a, ty, span);
                let b = self.int(b, ty, span);
                let mut name = |t: L| self.intermediate_over(t, MAX_DIV_TERM);
                match e {
                    IntExpr::DivBy(..) => bitvec::div_by(&a, &b, ty, &mut name),
                    _ => bitvec::rem_by(&a, &b, ty, &mut name),
                }
            }
            IntExpr::Cast(_, inner) if inner.real => self.not_real(ty, span),
            IntExpr::ToReal(_, inner) if !ty.real || (inner.real && inner.bits == ty.bits) => {
                self.not_real(ty, span)
            }
            IntExpr::ToReal(_, inner) if !inner.real && ty.bits != 32 => self.not_real(ty, span),
            IntExpr::Real(..) if !ty.real => self.not_real(ty, span),
            IntExpr::Real(op, a, b) => {
                let (a, b) = (self.int(a, ty, span), self.int(b, ty, span));
                // Each step of the division reads the remainder's bits several times.
                let mut name = |t: L| self.intermediate_over(t, MAX_DIV_TERM);
                match op {
                    RealOp::Add => bitvec::add_real(&a, &b, false, &mut name),
                    RealOp::Sub => bitvec::add_real(&a, &b, true, &mut name),
                    RealOp::Mul => bitvec::mul_real(&a, &b, &mut name),
                    RealOp::Div => bitvec::div_real(&a, &b, &mut name),
                    RealOp::Quotient => bitvec::quotient_real(&a, &b, &mut name),
                }
            }
            IntExpr::Sqrt(_) if !ty.real => self.not_real(ty, span),
            IntExpr::Sqrt(a) => {
                let a = self.int(a, ty, span);
                // Each step of the root reads the remainder's bits several times.
                bitvec::sqrt_real(&a, &mut |t: L| self.intermediate_over(t, MAX_DIV_TERM))
            }
            IntExpr::FromReal(a, unsigned) => {
                let a = self.int(a, IntType::REAL, span);
                let mut name = |t: L| self.intermediate(t);
                bitvec::real_to_int(&a, *unsigned, w, &mut name)
            }
            IntExpr::ToReal(a, inner) => {
                let a = self.int(a, *inner, span);
                let mut name = |t: L| self.intermediate(t);
                match (inner.real, inner.bits) {
                    (false, _) => bitvec::int_to_real(&a, *inner, &mut name),
                    (true, 32) => bitvec::widen_real(&a, &mut name),
                    (true, _) => bitvec::narrow_real(&a, &mut name),
                }
            }
            IntExpr::Cast(a, inner) => {
                let a = self.int(a, *inner, span);
                bitvec::resize(a, *inner, ty)
            }
            IntExpr::Bitwise(op, a, b) => {
                let (a, b) = (self.int(a, ty, span), self.int(b, ty, span));
                let bit = |x: &L, y: &L| match op {
                    BitOp::And => x.clone().and(y.clone()),
                    BitOp::Or => x.clone().or(y.clone()),
                    BitOp::Xor => bitvec::mux(x, &y.clone().negate(), y),
                };
                a.iter().zip(&b).map(|(x, y)| bit(x, y)).collect()
            }
            IntExpr::Shift(a, k) => {
                let a = self.int(a, ty, span);
                let n = k.unsigned_abs().min(w) as usize;
                let w = w as usize;
                if *k >= 0 {
                    std::iter::repeat_n(L::Zero, n).chain(a[..w - n].iter().cloned()).collect()
                } else {
                    let fill = if ty.signed { a[w - 1].clone() } else { L::Zero };
                    a[n..].iter().cloned().chain(std::iter::repeat_n(fill, n)).collect()
                }
            }
            IntExpr::Checked(c) => {
                let value = self.checked(c, span);
                bitvec::resize(value, c.ty, ty)
            }
            IntExpr::Ite(c, a, b) => {
                // The condition is read by every bit: named unless it is a literal.
                let c = self.eval(c);
                let c = if c.size() > 2 {
                    let label = self.block().label.clone().unwrap_or_else(|| "v".into());
                    self.define(&format!("{label}_v"), c)
                } else {
                    c
                };
                let a = self.int(a, ty, span);
                let b = self.int(b, ty, span);
                a.iter().zip(&b).map(|(x, y)| bitvec::mux(&c, x, y)).collect()
            }
        }
    }

    /// A [`Checked`] operation's value in its type: the result's bits where it fits,
    /// the free integer's where it overflows (the condition named, as every bit reads it).
    fn checked(&mut self, c: &Checked, span: Span) -> Bits {
        let w = c.ty.bits as usize;
        let a = self.int(&c.a, c.ty, span);
        let b = self.int(&c.b, c.ty, span);
        let (sa, sb) = (a[w - 1].clone(), b[w - 1].clone());
        let differ = |x: &L, y: &L| bitvec::mux(x, &y.clone().negate(), y);
        let mut name = |t: L| self.intermediate(t);
        let (value, overflow) = match c.op {
            // `-b`: only the least value overflows.
            CheckedOp::Sub if matches!(c.a, IntExpr::Const(0)) => {
                let r = bitvec::sub(&a, &b, &mut name);
                let rest = b[..w - 1].iter().map(|x| x.clone().negate());
                (r, L::And(std::iter::once(sb).chain(rest).collect()))
            }
            // Operands of one sign (of two signs, for `-`) and a result of the other.
            CheckedOp::Add | CheckedOp::Sub => {
                let r = if c.op == CheckedOp::Add {
                    bitvec::add(&a, &b, L::Zero, &mut name)
                } else {
                    bitvec::sub(&a, &b, &mut name)
                };
                let signs = differ(&sa, &sb);
                let signs = if c.op == CheckedOp::Add { signs.negate() } else { signs };
                let overflow = signs.and(differ(&r[w - 1], &sa));
                (r, overflow)
            }
            // The exact product in twice the width: it fits where its high half copies
            // the sign of its low half.
            CheckedOp::Mul => {
                let extend = |x: &Bits, s: &L| {
                    x.iter().cloned().chain(std::iter::repeat_n(s.clone(), w)).collect::<Bits>()
                };
                let p = bitvec::mul(&extend(&a, &sa), &extend(&b, &sb), &mut name);
                let overflow = L::Or(p[w..].iter().map(|x| differ(x, &p[w - 1])).collect());
                (p[..w].to_vec(), overflow)
            }
            // Only the least value divided by −1 overflows.
            CheckedOp::Div | CheckedOp::Mod => {
                let r = if c.op == CheckedOp::Div {
                    bitvec::div_by(&a, &b, c.ty, &mut |t: L| {
                        self.intermediate_over(t, MAX_DIV_TERM)
                    })
                } else {
                    bitvec::rem_by(&a, &b, c.ty, &mut |t: L| {
                        self.intermediate_over(t, MAX_DIV_TERM)
                    })
                };
                let least = bitvec::constant(c.ty.min(), c.ty.bits);
                let all = |x: &Bits, k: &Bits| {
                    L::And(x.iter().zip(k).map(|(x, k)| differ(x, k).negate()).collect())
                };
                let minus_one = bitvec::constant(-1, c.ty.bits);
                (r, all(&a, &least).and(all(&b, &minus_one)))
            }
        };
        let overflow = simp(&overflow);
        let overflow = if overflow.size() > 2 {
            let label = self.block().label.clone().unwrap_or_else(|| "v".into());
            self.define(&format!("{label}_overflow"), overflow)
        } else {
            overflow
        };
        let free = self.int(&IntExpr::Var(c.undefined.clone()), c.ty, span);
        value.iter().zip(&free).map(|(x, f)| bitvec::mux(&overflow, f, x)).collect()
    }

    /// A comparison, as a Boolean term of the bits.
    pub(super) fn compare(&mut self, c: &Compare, span: Span) -> L {
        let a = self.int(&c.a, c.ty, span);
        let b = self.int(&c.b, c.ty, span);
        let mut name = |t: L| self.intermediate(t);
        let t = if c.ty.real {
            bitvec::compare_real(c.op, &a, &b, &mut name)
        } else {
            bitvec::compare(c.op, c.ty, &a, &b, &mut name)
        };
        simp(&t)
    }

    /// `target := value`: one write per bit, in order.
    pub(super) fn set_int(&mut self, target: &str, value: &IntExpr, span: Span) {
        let Some(var) = self.int_var(target, span) else { return };
        let bits = self.int(value, var.ty, span);
        let label = self.block().label.clone().unwrap_or_else(|| "v".into());
        for (k, bit) in bits.into_iter().enumerate() {
            let k = k as u32;
            let stored = if var.start_bit(k) { bit.negate() } else { bit };
            let x = Program::int_bit(target, k);
            // A value later writes replace is read under its own name
            // (`Cparts_L01_b3`: the bit after this block's write).
            let last = self.depth == 0 && self.last_write.get(&x) == Some(&self.write_index);
            let stored = if !last && stored.size() > 2 {
                self.define(&format!("{target}_{label}_b{k}"), stored)
            } else {
                stored
            };
            self.write(span, &x, &WriteKind::Assign, &stored);
        }
    }

    /// `t`, or a new signal defined as equal to it (stated with this block) when it is
    /// too large to copy into every read.
    pub(super) fn intermediate(&mut self, t: L) -> L {
        self.intermediate_over(t, MAX_INT_TERM)
    }

    /// [`Self::intermediate`] with its own limit on the size of a term.
    fn intermediate_over(&mut self, t: L, limit: usize) -> L {
        if t.size() <= limit {
            return t;
        }
        let label = self.block().label.clone().unwrap_or_else(|| "v".into());
        self.define(&format!("{label}_v"), t)
    }

    /// A new signal (named after `base`) defined as equal to `t`, stated with this block.
    fn define(&mut self, base: &str, t: L) -> L {
        let name = self.unique(base);
        let rung = self.block().number;
        self.fresh.insert(name.clone(), SignalKind::Intermediate { rung });
        self.pending.push(Pending { var: name.clone(), rhs: t, recurrence: None });
        L::Var(name.into())
    }

    /// The kind of the bit signal `name`, if it is one.
    pub(super) fn int_bit_kind(&self, name: &str) -> Option<SignalKind> {
        let (of, k) = name.rsplit_once("_b")?;
        let bit: u32 = k.parse().ok()?;
        let var = self.program.integers.get(of)?;
        (bit < var.ty.bits && Program::int_bit(of, bit) == name).then(|| SignalKind::IntBit {
            of: of.to_string(),
            bit,
            start: var.start_bit(bit),
            input: var.input,
        })
    }
}

/// The integer constants of a program: start values, and the literals of its integer
/// writes and comparisons (divisors included), in increasing order; none of a `REAL`.
pub(super) fn constants(program: &Program) -> Vec<i64> {
    fn walk(e: &IntExpr, out: &mut std::collections::BTreeSet<i64>) {
        match e {
            IntExpr::Const(k) => {
                out.insert(*k);
            }
            IntExpr::Var(_) => {}
            IntExpr::Div(a, k) | IntExpr::Mod(a, k) => {
                out.insert(*k);
                walk(a, out);
            }
            IntExpr::Cast(a, _)
            | IntExpr::Shift(a, _)
            | IntExpr::ToReal(a, _)
            | IntExpr::Sqrt(a)
            | IntExpr::FromReal(a, _) => walk(a, out),
            IntExpr::Add(a, b)
            | IntExpr::Bitwise(_, a, b)
            | IntExpr::Sub(a, b)
            | IntExpr::Mul(a, b)
            | IntExpr::DivBy(a, b)
            | IntExpr::ModBy(a, b)
            | IntExpr::Real(_, a, b)
            | IntExpr::Ite(_, a, b) => {
                walk(a, out);
                walk(b, out);
            }
            IntExpr::Checked(c) => {
                walk(&c.a, out);
                walk(&c.b, out);
            }
        }
    }
    let mut out: std::collections::BTreeSet<i64> =
        program.integers.values().filter(|v| !v.ty.real).map(|v| v.init).collect();
    for (_, s) in program.stmts() {
        let (mut sets, mut cmps) = (Vec::new(), Vec::new());
        s.visit(
            // A `REAL`'s literals are bit patterns, no count an integer reaches.
            &mut |s| {
                if let Stmt::SetInt { value, target, .. } = s
                    && program.integers.get(target).is_none_or(|v| !v.ty.real)
                {
                    sets.push(value.clone());
                }
            },
            &mut |e| {
                if let BoolExpr::Compare(c) = e
                    && !c.ty.real
                {
                    cmps.push(c.a.clone());
                    cmps.push(c.b.clone());
                }
            },
        );
        sets.iter().chain(&cmps).for_each(|e| walk(e, &mut out));
    }
    out.into_iter().collect()
}

/// [`CompiledProgram::int_depth`] of a program with these [`constants`].
pub(super) fn int_depth(program: &Program, constants: &[i64]) -> usize {
    if program.integers.is_empty() {
        return 0;
    }
    let largest = constants.iter().map(|k| k.unsigned_abs()).max().unwrap_or(0);
    usize::try_from(largest.saturating_mul(2).saturating_add(2)).unwrap_or(usize::MAX).min(10_000)
}
