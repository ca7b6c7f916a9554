//! A timer's elapsed time `T1.ET` (TON, TOF, TP) in Structured Text and IL: a TIME integer the scan model computes from a hidden count of scans for a timer called once at every scan, or, for one called more than once or under a condition, from matiec's own state (`STATE`, `PREV_IN`) and the scans since its start; otherwise not computed, with the reason.

use std::collections::BTreeSet;

use super::ints::{Int, Opaque};
use super::{Lowering, Ty};
use crate::diag::Span;
use crate::iec::StError;
use crate::iec::{ast, literal};
use crate::program::library::{Elapsed, ElapsedTime, compare};
use crate::program::{Block, BoolExpr, CmpOp, IntExpr, IntType, Stmt, WriteKind};

/// What the calls of a timer whose `ET` is read tell of it (grows while lowering, which
/// then runs again).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(super) struct Wanted {
    /// The type `ET` is read in (the bits its values need), once a call gave it.
    ty: Option<IntType>,
    /// Called more than once in a scan, or under a condition: `ET` follows matiec's
    /// function block call by call, with the scans since its start counted at the start
    /// of every scan.
    clocked: bool,
    /// The presets its calls give or keep, in ns.
    presets: BTreeSet<i64>,
    /// Clocked: the scans until it runs out.
    scans: Option<i64>,
    /// Its first call.
    at: Option<Span>,
}

impl Lowering<'_> {
    /// A read of `inst.ET` for the timer instance `inst`: its value as the last call
    /// left it (`T#0s` before any call), or why it is not computed.
    pub(super) fn elapsed_read(&mut self, inst: &str) -> Result<Int, Opaque> {
        let w = self.elapsed.entry(inst.to_ascii_uppercase()).or_default();
        let t = w.ty.unwrap_or(IntType::TIME);
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

    /// At a call of the timer `inst` (of kind `kind`, giving the preset `pt`, reading
    /// `input` as `IN`): where a statement reads its `ET`, the
    /// statements that update it, and then `Some(Q)`, the output from the same state
    /// (so that what is proved of one holds of the other).
    pub(super) fn elapsed_call(
        &mut self,
        inst: &str,
        kind: Elapsed,
        pt: Option<&ast::Expr>,
        input: &BoolExpr,
        out: &mut Vec<Stmt>,
        span: Span,
    ) -> Option<BoolExpr> {
        let key = inst.to_ascii_uppercase();
        // A call that leaves the preset out is followed call by call too (the preset it
        // keeps is a hidden bit's business).
        let clocked = self.elapsed.get(&key)?.clocked || self.call_by_call(&key) || pt.is_none();
        let t = self.elapsed.get(&key)?.ty.unwrap_or(IntType::TIME);
        let et = self.hidden_int(inst, "ET", t);
        if self.opaque.contains_key(&et) {
            return None;
        }
        let cycle = self.cycle_us as i64 * 1000;
        // The preset where it is a duration literal. A clocked timer's call that leaves it
        // out: the one literal the calls that give it give (`Wanted::presets`; T#0s while
        // none has run, a hidden bit tells), 0 while none is known.
        let omitted = pt.is_none() && clocked;
        let pt_ns = match pt {
            Some(e) => self.preset_ns(Some(e)),
            None if clocked => Some(self.elapsed.get(&key)?.presets.first().copied().unwrap_or(0)),
            None => None,
        };
        // The scans until it runs out, or why its elapsed time is not computed.
        let found = if cycle == 0 {
            Err("the cycle is 0")
        } else {
            match pt_ns {
                None => Err("its timer's preset is not a duration literal"),
                Some(pt) if pt < 0 => Err("its timer's preset is negative"),
                Some(pt) => match (pt as u64).div_ceil(cycle as u64) {
                    n if n >= 1 << 60 => {
                        Err("its timer's preset is beyond the TIME values computed")
                    }
                    n if clocked => Ok((pt, n as i64)),
                    n => Ok((pt, n.max(1) as i64)),
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
        if let Some(w) = self.elapsed.get_mut(&key) {
            let t = IntType::time_for(pt as u64);
            w.ty = Some(w.ty.filter(|w| w.bits > t.bits).unwrap_or(t));
            if !omitted {
                w.presets.insert(pt);
            }
            w.clocked |= clocked;
            w.at.get_or_insert(span);
            if clocked {
                w.scans = Some(n);
            }
        }
        if clocked {
            // Whether a call that gives the preset has run.
            let given = self.hidden(inst, "PT_GIVEN");
            let timer = Clocked { kind, et: &et, pt_ns: pt, n, cycle_ns: cycle, given, omitted };
            return Some(self.clocked_call(inst, &timer, input, out, span));
        }
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

    /// A call of a clocked timer reading `input` (a scan-local value) as `IN`: matiec's
    /// body of `TON`, `TOF` or `TP` (`lib/timer.txt`) over its `STATE` (0 idle, 1
    /// running, 2 run out), `PREV_IN` and `ET`, where `CURRENT_TIME - START_TIME` is
    /// the scans since its start (`AGE`, which every scan's start counts up to `n`)
    /// times the cycle, and `START_TIME + PT <= CURRENT_TIME` is `AGE >= n`. Then `Q`.
    fn clocked_call(
        &mut self,
        inst: &str,
        timer: &Clocked,
        input: &BoolExpr,
        out: &mut Vec<Stmt>,
        span: Span,
    ) -> BoolExpr {
        let state_t = IntType::int(2, false);
        let state = self.hidden_int(inst, "STATE", state_t);
        let prev = self.hidden(inst, "PREV_IN");
        let age_t = Clocked::age_type(timer.n);
        let age = self.hidden_int(inst, "AGE", age_t);
        let k = IntExpr::Const;
        let is = |v: i64| compare(CmpOp::Eq, state_t, IntExpr::var(&state), k(v));
        let mut run_out = compare(CmpOp::Ge, age_t, IntExpr::var(&age), k(timer.n));
        let mut pt = k(timer.pt_ns);
        let given = BoolExpr::var(&timer.given);
        if timer.omitted {
            // T#0s runs out at once.
            run_out = BoolExpr::Or(vec![BoolExpr::negate(given.clone()), run_out]);
            pt = IntExpr::ite(given, pt, k(0));
        } else {
            // Kept whatever the call's EN, like the preset itself.
            let given = Stmt::Write {
                target: timer.given.clone(),
                kind: WriteKind::Assign,
                value: BoolExpr::Const(true),
                span,
            };
            self.keep(out, [given]);
        }
        let (on, off) = (input.clone(), BoolExpr::negate(input.clone()));
        let was = BoolExpr::var(&prev);
        // The call's edge: TON and TP start on a rising one, TOF on a falling one.
        let edge = match timer.kind {
            Elapsed::Off => BoolExpr::and(was, off.clone()),
            _ => BoolExpr::and(BoolExpr::negate(was), on.clone()),
        };
        let start = self.temp(out, BoolExpr::and(is(0), edge));
        let running = self.temp(out, is(1));
        let done = self.temp(out, BoolExpr::and(running.clone(), run_out));
        let elapsed = IntExpr::Mul(
            Box::new(IntExpr::Cast(Box::new(IntExpr::var(&age)), age_t)),
            Box::new(k(timer.cycle_ns)),
        );
        let timed = IntExpr::ite(done.clone(), pt, elapsed);
        let timed = IntExpr::ite(running, timed, IntExpr::var(timer.et));
        let to_state = IntExpr::ite(done, k(2), IntExpr::var(&state));
        let (et, st) = match timer.kind {
            // Not started: IN off (TON) or on (TOF) resets, else a running one times.
            Elapsed::On | Elapsed::Off => {
                let resets = if timer.kind == Elapsed::On { off.clone() } else { on.clone() };
                let et = IntExpr::ite(resets.clone(), k(0), timed);
                (et, IntExpr::ite(resets, k(0), to_state))
            }
            // Not started: a running one times; then run out and IN off: idle.
            Elapsed::Pulse => (timed, to_state),
        };
        let et = IntExpr::ite(start.clone(), IntExpr::var(timer.et), et);
        let st = IntExpr::ite(start.clone(), k(1), st);
        out.push(Stmt::SetInt { target: timer.et.to_string(), value: et, span });
        out.push(Stmt::SetInt { target: state.clone(), value: st, span });
        if timer.kind == Elapsed::Pulse {
            let idle = self.temp(out, BoolExpr::and(is(2), off));
            let et = IntExpr::ite(idle.clone(), k(0), IntExpr::var(timer.et));
            out.push(Stmt::SetInt { target: timer.et.to_string(), value: et, span });
            let st = IntExpr::ite(idle, k(0), IntExpr::var(&state));
            out.push(Stmt::SetInt { target: state.clone(), value: st, span });
        }
        let age_now = IntExpr::ite(start, k(0), IntExpr::var(&age));
        out.push(Stmt::SetInt { target: age, value: age_now, span });
        out.push(Stmt::Write { target: prev, kind: WriteKind::Assign, value: on.clone(), span });
        match timer.kind {
            Elapsed::On => is(2),
            Elapsed::Off => BoolExpr::Or(vec![on, is(1)]),
            Elapsed::Pulse => is(1),
        }
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
    /// are clocked (lowering runs again); a clocked timer given two presets gets it not
    /// computed; and every scan starts by counting each clocked timer's scans since its
    /// start.
    pub(super) fn elapsed_after_lowering(&mut self) {
        let counts: Vec<(String, String)> = self
            .hidden
            .iter()
            .filter(|((_, pin), _)| pin == "ET_SCANS")
            .map(|((inst, _), n)| (n.clone(), inst.clone()))
            .collect();
        let mut found = Vec::new();
        for b in &self.blocks {
            under_condition(&b.stmts, false, &mut |target, _| {
                if let Some((_, inst)) = counts.iter().find(|(n, _)| n == target) {
                    found.push(inst.clone());
                }
            });
        }
        for inst in found {
            if let Some(w) = self.elapsed.get_mut(&inst) {
                w.clocked = true;
            }
        }
        let mut ages = Vec::new();
        for (key, w) in &self.elapsed {
            let Some(et) = self.hidden.get(&(key.clone(), "ET".to_string())) else { continue };
            let at = w.at.unwrap_or(Span::new(0, 0..0));
            if w.clocked && w.presets.len() > 1 {
                let why = "its timer is called with different presets, or leaves out one \
                           that is not one duration literal";
                ages.push(Err((et.clone(), why, at)));
                continue;
            }
            if let (true, Some(n), Some(age)) =
                (w.clocked, w.scans, self.hidden.get(&(key.clone(), "AGE".to_string())))
            {
                ages.push(Ok((age.clone(), n, at)));
            }
        }
        let mut stmts = Vec::new();
        for a in ages {
            match a {
                Ok((age, n, span)) => {
                    let t = Clocked::age_type(n);
                    let (k, var) = (IntExpr::Const, || IntExpr::var(&age));
                    let full = compare(CmpOp::Ge, t, var(), k(n));
                    let value = IntExpr::ite(full, k(n), IntExpr::plus(var(), k(1)));
                    stmts.push(Stmt::SetInt { target: age, value, span });
                }
                Err((et, why, at)) => self.make_opaque(&et, why.into(), at),
            }
        }
        if let Some(Stmt::SetInt { span, .. }) = stmts.first() {
            let (span, label) = (*span, Some(Block::CLOCK.to_string()));
            self.blocks.insert(0, Block { number: 0, label, span, stmts });
        }
    }
}

/// A timer called call by call ([`Lowering::clocked_call`]).
struct Clocked<'a> {
    kind: Elapsed,
    /// Its `ET`'s name.
    et: &'a str,
    /// The preset, in ns (as matiec's C computes its literal).
    pt_ns: i64,
    /// The scans from its start until it runs out (`ceil(PT / cycle)`).
    n: i64,
    /// The cycle, in ns.
    cycle_ns: i64,
    /// The hidden bit set by every call that gives the preset.
    given: String,
    /// This call leaves the preset out: it is `pt_ns` once a call gave it, else T#0s.
    omitted: bool,
}

impl Clocked<'_> {
    /// The type of the scans since a start, counted up to `n`.
    fn age_type(n: i64) -> IntType {
        IntType::int((64 - n.leading_zeros()).max(1), false)
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
