//! Function calls that write the caller's variables (`=>` outputs, `ENO =>`) inside a statement: ii-prove runs them before the statement, where matiec's C runs them while it evaluates it; refused where the two may differ.

use super::Lowering;
use crate::diag::Span;
use crate::iec::StError;
use crate::iec::ast::{self, Arg, BinOp, ExprKind, StmtKind};

/// What a statement's expressions read and what their function calls write.
#[derive(Default)]
struct Effects {
    /// Each variable read (upper case), with where.
    reads: Vec<(String, Span)>,
    /// Each `=>` of a function call: the variable written (upper case, `None` for a
    /// target that is not a plain variable), the output pin, whether C may skip the
    /// call or make it twice.
    writes: Vec<(Option<String>, Span, bool)>,
}

impl Effects {
    /// Walks `e`; `skippable`: whether `e` is an operand of a Boolean `AND`, `OR` or
    /// `XOR`, which matiec writes as C's `&&` and `||` (`XOR` evaluating its operands
    /// twice), or a condition C evaluates only when the ones before it are FALSE.
    fn walk(&mut self, e: &ast::Expr, skippable: bool) {
        match &e.kind {
            ExprKind::Var(id) => self.reads.push((id.key(), id.span)),
            ExprKind::Member(x, _) | ExprKind::Unary(_, x) => self.walk(x, skippable),
            ExprKind::Index(x, ix) => {
                self.walk(x, skippable);
                ix.iter().for_each(|i| self.walk(i, skippable));
            }
            ExprKind::Binary(op, a, b) => {
                let short = skippable || matches!(op, BinOp::And | BinOp::Or | BinOp::Xor);
                self.walk(a, short);
                self.walk(b, short);
            }
            ExprKind::Call(_, args) => {
                for a in args {
                    match a {
                        Arg::Positional(x) | Arg::Input(_, x) => self.walk(x, skippable),
                        Arg::Output(pin, _, target) => {
                            let written = match &target.kind {
                                ExprKind::Var(id) => Some(id.key()),
                                _ => None,
                            };
                            self.writes.push((written, pin.span, skippable));
                        }
                    }
                }
            }
            ExprKind::Bool(_) | ExprKind::Int(_) | ExprKind::Time(_) | ExprKind::Literal(_) => {}
        }
    }
}

impl Lowering<'_> {
    /// Refuses, with a located error, a function call's `=>` in `s` that C may skip or
    /// make twice (in an operand of `AND`, `OR`, `XOR`, in an `ELSIF` condition), and
    /// one whose variable the statement also reads or writes with another `=>` (C
    /// leaves the order of a call's arguments and of `=` operands open).
    pub(super) fn check_effects(&mut self, s: &ast::Stmt) {
        let mut fx = Effects::default();
        match &s.kind {
            StmtKind::Assign(_, value) => fx.walk(value, false),
            StmtKind::Call(_, args) => args.iter().for_each(|a| match a {
                Arg::Positional(x) | Arg::Input(_, x) => fx.walk(x, false),
                Arg::Output(..) => {}
            }),
            StmtKind::If(branches, _) => {
                for (k, (c, _)) in branches.iter().enumerate() {
                    fx.walk(c, k > 0);
                }
            }
            StmtKind::Case(x, _, _) | StmtKind::While(x, _) | StmtKind::Repeat(_, x) => {
                fx.walk(x, false);
            }
            StmtKind::For(_, a, b, c, _) => {
                [Some(a), Some(b), c.as_ref()]
                    .into_iter()
                    .flatten()
                    .for_each(|x| fx.walk(x, false));
            }
            _ => {}
        }
        for (k, (written, pin, skippable)) in fx.writes.iter().enumerate() {
            let why = if *skippable {
                "matiec's C evaluates this call in an operand of && or || (or an ELSIF condition), so it may be skipped or made twice"
            } else if written.is_none() {
                // Refused where it is copied.
                continue;
            } else if fx.reads.iter().any(|(r, _)| Some(r) == written.as_ref())
                || fx.writes.iter().enumerate().any(|(j, (w, ..))| j != k && w == written)
            {
                "the statement reads this variable or writes it again, in an order C leaves open; assign the call's result first"
            } else {
                continue;
            };
            if self.errors.iter().any(|e| e.span == *pin) {
                continue;
            }
            self.errors.push(StError::new(
                *pin,
                "a function call's output written inside this statement is not modelled yet",
                why,
            ));
        }
    }
}
