//! The call of a user function block or function whose body is text: a function's variables set to their power-up values (it keeps nothing between calls), its wired inputs written to the instance's (or call's) variables, then the blocks of its program (lowered by the IEC text front end, every name prefixed by the instance's) at the call's place in the scan.

use std::collections::BTreeMap;

use super::{BoolExpr, Lower, PinIn, PlcProgram, Span, Stmt, WriteKind};
use crate::program::rename::Renaming;
use crate::program::{IntExpr, IntVar, Program};

impl Lower<'_> {
    /// The integers of the text blocks' instances: written by their calls, so none is an
    /// input of the program (a wired input the caller cannot compute is made one at the
    /// call).
    pub(super) fn declare_text_ints(&mut self, p: &PlcProgram) {
        for call in p.text_calls.values() {
            for (x, v) in &call.program.integers {
                // What C leaves undefined stays free in the caller.
                let input = call.program.undefined.contains(x);
                self.ints.insert(x.clone(), IntVar { input, ..*v });
            }
            self.undefined.extend(call.program.undefined.iter().cloned());
        }
        for sub in p.subs.values() {
            self.declare_text_ints(sub);
        }
    }

    /// The call of the text block at `k`: `vals` the Boolean values of its pins, `en`
    /// its EN where it is wired and not always TRUE (its program then runs under the
    /// instance's EN bit, [`crate::ladder::plcopen::TextCall::enable`], or, where it
    /// has none, the block is not run).
    pub(super) fn text_call(
        &mut self,
        k: usize,
        inputs: &[PinIn],
        vals: &BTreeMap<String, BoolExpr>,
        en: Option<BoolExpr>,
        span: Span,
    ) {
        let p = self.p;
        let Some(call) = p.text_calls.get(&k) else { return };
        if en.is_some() && call.enable.is_none() {
            return self.text_not_run(k);
        }
        if call.function {
            self.push_block(power_up(&call.program, span), span);
        }
        for pin in inputs {
            let n = pin.name.to_ascii_uppercase();
            let Some((var, int)) = call.inputs.get(&n) else { continue };
            if !int {
                if let Some(v) = vals.get(&n) {
                    self.coil(v.clone(), var, WriteKind::Assign, span);
                }
                continue;
            }
            let Some(target) = self.ints.get(var).copied() else { continue };
            match self.int_pin(pin) {
                Ok((e, ty)) if ty.is_none_or(|t| t == target.ty) => {
                    let value = super::ints::coerce(e, target.ty);
                    self.push_block(vec![Stmt::SetInt { target: var.clone(), value, span }], span);
                }
                Ok(_) | Err(_) => {
                    // The block still runs on the value it is given: any value of its type.
                    self.ints.insert(var.clone(), IntVar { input: true, init: 0, ..target });
                    let message = format!(
                        "the integer wired to `{}` is not computed exactly here: the block's \
                         input `{var}` is a free input of its type",
                        pin.name
                    );
                    let warn = Stmt::Warn { span: pin.span, element: pin.name.clone(), message };
                    self.push_block(vec![warn], span);
                }
            }
        }
        // matiec writes EN with the other inputs, then the body returns at once where it
        // is FALSE.
        if let Some(bit) = &call.enable {
            self.coil(en.unwrap_or(BoolExpr::Const(true)), bit, WriteKind::Assign, span);
        }
        // The block's one-shots are this program's, after those met so far.
        let base = self.edges.len();
        let used = call.program.edges_used();
        self.edges.extend((0..used).map(|i| (self.path.clone(), k, format!("TEXT{i}"))));
        let mut edge = |i: usize| base + i;
        let same = |n: &str| n.to_string();
        let presets = BTreeMap::new();
        let mut renaming =
            Renaming { name: &same, temps: self.next_temp, edge: &mut edge, presets: &presets };
        let blocks = renaming.blocks(&call.program.blocks);
        self.next_temp += call.program.temps_used();
        // The clock runs at the start of the scan ([`Self::text_clocks`]).
        for b in blocks.into_iter().filter(|b| !b.is_clock()) {
            self.push_block(b.stmts, b.span);
        }
    }

    /// The text block at `k` under a wired EN whose body cannot run under it (a
    /// function, or a body the lowering under EN refuses): its integer outputs are not
    /// computed (its BOOL outputs are unconstrained, as for any block
    /// whose EN is wired).
    pub(super) fn text_not_run(&mut self, k: usize) {
        let Some(call) = self.p.text_calls.get(&k) else { return };
        for (pin, var) in &call.int_outputs {
            let why = format!("the block of its pin {pin} runs under a wired EN, not followed");
            self.make_opaque(var, why);
        }
    }

    /// At the start of the scan: every text block instance's clock block, which counts
    /// the scans since its timers called call by call started, whether it is called in
    /// this scan or not (the runtime's clock runs on).
    pub(super) fn text_clocks(&mut self, p: &PlcProgram) {
        for call in p.text_calls.values() {
            for b in call.program.blocks.iter().filter(|b| b.is_clock()) {
                self.push_block(b.stmts.clone(), b.span);
            }
        }
        for sub in p.subs.values() {
            self.text_clocks(sub);
        }
    }
}

/// Writes that put `program`'s state back to power-up: every bit 0 (its start-up bit
/// among them, so that its first-scan block sets the BOOLs declared TRUE again) and
/// every integer its initial value, but the free values of what C leaves undefined.
fn power_up(program: &Program, span: Span) -> Vec<Stmt> {
    let int_bits: std::collections::BTreeSet<String> = program
        .integers
        .iter()
        .flat_map(|(x, v)| (0..v.ty.bits).map(|k| Program::int_bit(x, k)))
        .collect();
    let mut bits = crate::program::bits(&program.blocks);
    bits.extend(program.signals.iter().cloned());
    let bits = bits.into_iter().filter(|n| !int_bits.contains(n));
    let mut out: Vec<Stmt> = bits
        .map(|target| Stmt::Write {
            target,
            kind: WriteKind::Assign,
            value: BoolExpr::Const(false),
            span,
        })
        .collect();
    for (x, v) in program.integers.iter().filter(|(x, _)| !program.undefined.contains(*x)) {
        out.push(Stmt::SetInt { target: x.clone(), value: IntExpr::Const(v.init), span });
    }
    out
}
