//! A timer's elapsed time `T1.ET` (TON, TOF, TP) in Structured Text and IL: a TIME integer the scan model computes from a hidden count of scans, for a timer called once at every scan with a known preset; otherwise not computed, with the reason.

use super::ints::{Int, Opaque};
use super::{Lowering, Ty};
use crate::diag::Span;
use crate::iec::StError;
use crate::iec::{ast, literal};
use crate::program::library::{Elapsed, ElapsedTime};
use crate::program::{BoolExpr, IntType, Stmt, WriteKind};

impl Lowering<'_> {
    /// A read of `inst.ET` for the timer instance `inst`: its value as the last call
    /// left it (`T#0s` before any call), or why it is not computed.
    pub(super) fn elapsed_read(&mut self, inst: &str) -> Result<Int, Opaque> {
        let t = *self.elapsed.entry(inst.to_ascii_uppercase()).or_insert(IntType::TIME);
        let et = self.hidden_int(inst, "ET", t);
        match self.opaque.get(&et) {
            Some((why, _)) => Err(format!("the elapsed time {inst}.ET is not computed: {why}")),
            None => Ok(Int::var(&et, t)),
        }
    }

    /// The preset `pt` of a call in ns, as matiec's C computes it, where it is a
    /// duration literal.
    pub(super) fn preset_ns(&self, pt: Option<&ast::Expr>) -> Option<i64> {
        match pt.map(|e| (&e.kind, e.span)) {
            Some((ast::ExprKind::Time(_), at)) => literal::matiec_duration_ns(&self.text(at)),
            _ => None,
        }
    }

    /// At a call of the timer `inst` (of kind `kind`, preset `pt_ns` where it is a
    /// duration literal, reading `input` as `IN`): where a statement reads its `ET`, the
    /// statements that update it, and then `Some(Q)`, the output from the same count
    /// (so that what is proved of one holds of the other).
    pub(super) fn elapsed_call(
        &mut self,
        inst: &str,
        kind: Elapsed,
        pt_ns: Option<i64>,
        input: &BoolExpr,
        out: &mut Vec<Stmt>,
        span: Span,
    ) -> Option<BoolExpr> {
        let key = inst.to_ascii_uppercase();
        let t = self.elapsed.get(&key).copied()?;
        let et = self.hidden_int(inst, "ET", t);
        if self.opaque.contains_key(&et) {
            return None;
        }
        let cycle = self.cycle_us as i64 * 1000;
        // The scans until it runs out, or why its elapsed time is not computed.
        let found = if self.multi.contains(&key) {
            Err("its timer is called more than once in a scan")
        } else if cycle == 0 {
            Err("the cycle is 0")
        } else {
            match pt_ns {
                None => Err("its timer's preset is not a duration literal in the call"),
                Some(pt) => match (pt.max(0) as u64).div_ceil(cycle as u64).max(1) {
                    n if n >= 1 << 60 => {
                        Err("its timer's preset is beyond the TIME values computed")
                    }
                    n => Ok((pt, n as i64)),
                },
            }
        };
        let (pt, n) = match found {
            Ok(x) => x,
            Err(why) => {
                self.make_opaque(&et, why.into(), span);
                return None;
            }
        };
        // Read as a TIME of the bits its values (0 to PT) need, from the next lowering on.
        self.elapsed.insert(key, IntType::time_for(pt.max(0) as u64));
        let bits = 64 - (n + 2).leading_zeros();
        let count = IntType::int(bits, false);
        let scans = self.hidden_int(inst, "ET_SCANS", count);
        // TOF starts on a falling edge: `IN` at the last call, in a hidden bit.
        let before = (kind == Elapsed::Off).then(|| self.hidden(inst, "ET_IN"));
        let model = ElapsedTime { kind, scans: &scans, count, n, pt_ns: pt, cycle_ns: cycle };
        let last = before.as_deref().map_or(BoolExpr::Const(false), BoolExpr::var);
        let next = model.next(input.clone(), last);
        out.push(Stmt::SetInt { target: scans.clone(), value: next, span });
        out.push(Stmt::SetInt { target: et, value: model.value(), span });
        if let Some(target) = before {
            let value = input.clone();
            out.push(Stmt::Write { target, kind: WriteKind::Assign, value, span });
        }
        Some(model.q(input.clone()))
    }

    /// `ET => target` of a call of the timer `inst`: the elapsed time into the TIME
    /// variable `target` (not computed: TIME variables are not), or a type error.
    pub(super) fn elapsed_output(
        &mut self,
        inst: &str,
        target: &ast::Expr,
        span: Span,
    ) -> Vec<Stmt> {
        let Some(id) = self.written_variable(target, "a TIME variable") else { return Vec::new() };
        let Some(sym) = self.lookup(id) else { return Vec::new() };
        match sym.ty {
            Ty::Other(t) if t == "TIME" => {
                vec![super::ints::integer_write(span, "=>", &t, &sym.name)]
            }
            _ => {
                self.errors.push(StError::new(
                    target.span,
                    format!("`{}` takes the TIME {inst}.ET", sym.name),
                    "expected a TIME variable",
                ));
                Vec::new()
            }
        }
    }

    /// After lowering: the timers whose elapsed time is counted under a condition (a
    /// branch, a loop, a statement after a `RETURN`, an IL jump), so not at every scan,
    /// get it not computed (lowering runs again).
    pub(super) fn elapsed_conditional(&mut self) {
        let counts: Vec<(String, String)> = self
            .hidden
            .iter()
            .filter(|((_, pin), _)| pin == "ET_SCANS")
            .filter_map(|((inst, _), n)| {
                let et = self.hidden.get(&(inst.clone(), "ET".to_string()))?;
                Some((n.clone(), et.clone()))
            })
            .collect();
        let mut found = Vec::new();
        for b in &self.blocks {
            under_condition(&b.stmts, false, &mut |target, span| {
                if let Some((_, et)) = counts.iter().find(|(n, _)| n == target) {
                    found.push((et.clone(), span));
                }
            });
        }
        for (et, span) in found {
            let why = "its timer is called under a condition, not at every scan, and the \
                       time that passes between its calls is not counted";
            self.make_opaque(&et, why.into(), span);
        }
    }
}

/// Calls `f` on the target of every integer write of `stmts` that stands inside an `IF`
/// (`inside`: `stmts` do).
fn under_condition(stmts: &[Stmt], inside: bool, f: &mut dyn FnMut(&str, Span)) {
    for s in stmts {
        match s {
            Stmt::If { branches, otherwise, .. } => {
                for (_, b) in branches {
                    under_condition(b, true, f);
                }
                under_condition(otherwise, true, f);
            }
            Stmt::SetInt { target, span, .. } if inside => f(target, *span),
            _ => {}
        }
    }
}
