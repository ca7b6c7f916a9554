//! `EN`/`ENO` of PLCopen blocks in the scan model: which blocks run every scan, and the guard Beremiz's generator puts around an output variable fed by a block with a wired `EN` (see `docs/plcopen.md`).

use super::{
    BoolExpr, Edge, Lower, ObjKind, PinIn, Source, Span, Storage, WriteKind, and, contact,
    fresh_because, not, or,
};
use crate::ladder::plcopen::ints::{Arith, IntBlock};

impl Lower<'_> {
    /// Whether block `k` runs every scan: its `EN` is unwired or fed by the rail or by the
    /// `ENO` of a block that runs every scan.
    pub(super) fn en_const(&self, k: usize, depth: usize) -> bool {
        let Some(pin) = self.p.en_pin(k) else { return true };
        if depth > 64 || pin.expr.is_some() || pin.negated || pin.edge != Edge::None {
            return false;
        }
        pin.conns.len() == 1
            && pin.conns.iter().all(|c| match self.p.source(c) {
                Some(Source::Rail) => true,
                Some(Source::BlockPin(j, _)) => self.en_const(j, depth + 1) && !self.divides(j),
                Some(Source::BlockOut(j, pin)) => {
                    matches!(self.p.obj(j).map(|o| &o.kind), Some(ObjKind::Block { outputs, .. })
                        if outputs.get(pin).is_some_and(|o| o.name.eq_ignore_ascii_case("ENO") && !o.negated))
                        && self.en_const(j, depth + 1)
                        && !self.divides(j)
                }
                _ => false,
            })
    }

    /// The guard Beremiz puts around an output variable fed by one wire straight from a
    /// block whose `EN` is wired: `IF _TMP_ADD7_ENO THEN x := …; END_IF;`
    /// (`PLCGenerator.py`, `GetUsedEno` and its use in `ComputeProgram`). Only where the
    /// block's ENO is computed (an integer function's `_TMP_…_ENO`, a text block's EN
    /// bit); the other blocks under a wired EN give unconstrained outputs, which need no
    /// guard.
    pub(super) fn eno_guard(&self, input: &PinIn) -> Option<BoolExpr> {
        let [c] = input.conns.as_slice() else { return None };
        let j = *self.p.index.get(&c.from)?;
        let Some(ObjKind::Block { inputs, .. }) = self.p.obj(j).map(|o| &o.kind) else {
            return None;
        };
        let wired = inputs.iter().any(|p| p.name.eq_ignore_ascii_case("EN") && !p.conns.is_empty());
        // A text block run under its EN bit: `IF B1.ENO THEN …`, its ENO that bit.
        let text = self.p.text_calls.get(&j).and_then(|c| c.enable.as_deref());
        let eno = self.p.hidden_name(j, "ENO").or(text).filter(|_| wired)?;
        Some(contact(eno, false))
    }

    /// Whether block `k` is a DIV or a MUX, whose ENO matiec clears for a divisor 0 or a
    /// `K` past the inputs (`TEST_EN_COND(TYPENAME, op2 == 0)`, `TEST_EN_COND(…, K >=
    /// param_count)`, `lib/C/iec_std_functions.h`).
    fn divides(&self, k: usize) -> bool {
        matches!(self.p.int_block(k), Some(IntBlock::Arith(Arith::Div) | IntBlock::Mux))
    }

    /// The write of a coil or output variable: `(negated, storage, edge)` as drawn, under
    /// the `guard` of [`Lower::eno_guard`] (the variable keeps its value when it is FALSE).
    pub(super) fn assign(
        &mut self,
        k: usize,
        power: BoolExpr,
        name: &str,
        (negated, storage, edge): (bool, Storage, Edge),
        guard: Option<BoolExpr>,
        span: Span,
    ) {
        let kind = match (negated, storage) {
            (true, _) => WriteKind::AssignNot,
            (_, Storage::Set) => WriteKind::Set,
            (_, Storage::Reset) => WriteKind::Reset,
            _ => WriteKind::Assign,
        };
        let Some(g) = guard else {
            let power =
                if edge == Edge::None { power } else { self.trig_of(k, "COIL", edge, power) };
            self.coil(power, name, kind, span);
            return;
        };
        if edge != Edge::None {
            let why = format!("{name} is written through an edge detector under its block's ENO");
            self.coil(fresh_because("ENO", why, span), name, WriteKind::Assign, span);
            return;
        }
        let (kind, power) = match kind {
            WriteKind::Set | WriteKind::Reset => (kind, and(vec![g, power])),
            _ => {
                let power = if matches!(kind, WriteKind::AssignNot) { not(power) } else { power };
                let kept = and(vec![not(g.clone()), contact(name, false)]);
                (WriteKind::Assign, or(vec![and(vec![g, power]), kept]))
            }
        };
        self.coil(power, name, kind, span);
    }
}
