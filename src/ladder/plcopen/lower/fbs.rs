//! The standard function blocks of a graphical body in the scan model (TON, TOF, TP, SR, RS, R_TRIG, F_TRIG), and a function block's call under a wired `EN`: matiec's body starts `if (!EN) { ENO := FALSE; return; } else ENO := TRUE;` (`lib/C/iec_std_FB.h`, and the same for user blocks), so the call writes the instance's ENO, then its body's rungs run under `IF ENO`, its outputs, memories and timers' runs kept while it is FALSE.

use std::collections::BTreeMap;

use super::durations::NotConstant;
use super::{
    BoolExpr, Edge, Lower, ObjKind, PlcError, Span, Std, Stmt, WriteKind, contact, fresh, one, zero,
};
use crate::ladder::plcopen::ints::IntBlock;
use crate::program::{Memory, Preset, Timer};

impl<'p> Lower<'p> {
    /// The instance's ENO of the function block at `k` (a standard one, a counter, an
    /// inlined user block) where it is drawn with a wired `EN` or an `ENO`.
    pub(super) fn fb_eno(&self, k: usize) -> Option<&'p str> {
        let Some(ObjKind::Block { type_name, .. }) = self.p.obj(k).map(|o| &o.kind) else {
            return None;
        };
        let fb = match Std::of(type_name) {
            Some(s) => s.is_fb(),
            None => {
                matches!(self.p.int_block(k), Some(IntBlock::Counter(_)))
                    || self.p.subs.contains_key(&k)
            }
        };
        fb.then(|| self.p.hidden_name(k, "ENO")).flatten()
    }

    /// The start of the call of the function block at `k` under `en` (its EN, `None`
    /// where unwired): the instance's ENO written. Returns where its body's blocks start.
    pub(super) fn fb_enable(&mut self, k: usize, en: Option<BoolExpr>, span: Span) -> usize {
        if let Some(eno) = self.fb_eno(k) {
            self.coil(en.unwrap_or_else(one), eno, WriteKind::Assign, span);
        }
        self.blocks.len()
    }

    /// Puts the blocks from `start` on (the body of the function block at `k`) under
    /// `IF ENO`, where it does not run every scan (`runs` false).
    pub(super) fn under_eno(&mut self, k: usize, start: usize, runs: bool) {
        let Some(eno) = self.fb_eno(k).filter(|_| !runs) else { return };
        let guard = contact(eno, false);
        for b in self.blocks.iter_mut().skip(start) {
            let stmts = std::mem::take(&mut b.stmts);
            b.stmts = Stmt::guarded(&guard, stmts, b.span);
        }
    }

    /// The body of the standard function block `s` at `k` with its Boolean inputs `vals`
    /// and its `preset` (TON, TOF, TP). Returns where the body's blocks start (after the
    /// inputs an instance keeps, SR's `S1` and `R`, which are written whatever its EN).
    pub(super) fn std_fb(
        &mut self,
        k: usize,
        s: Std,
        vals: &BTreeMap<String, BoolExpr>,
        preset: Result<u64, NotConstant>,
        span: Span,
    ) -> usize {
        let p = self.p;
        let mut start = self.blocks.len();
        let Some(ObjKind::Block { type_name, instance, .. }) = p.obj(k).map(|o| &o.kind) else {
            return start;
        };
        let value = |name: &str| vals.get(name).cloned().unwrap_or_else(zero);
        let hidden = |pin: &str| p.hidden_name(k, pin).unwrap_or_default().to_string();
        match s {
            s @ (Std::Ton | Std::Tof) => {
                let input = value("IN");
                let delay = preset;
                // The instance's variable name (prefixed inside an inlined block).
                let inst = instance.as_deref().map_or_else(String::new, |i| {
                    p.vars.get(&i.to_ascii_uppercase()).map_or(i.to_string(), |v| v.name.clone())
                });
                let preset = match delay {
                    // PT = 0 still takes one scan (the starting scan never switches):
                    // the delay of one cycle, counted exactly.
                    Ok(0) => {
                        self.warnings.push(PlcError::Note {
                            span,
                            message: format!(
                                "{} {inst} has PT = 0: matiec's timer still switches one scan \
                                 later, so it is compiled with the delay of one cycle",
                                type_name.to_ascii_uppercase()
                            ),
                        });
                        Preset::iec(0, p.cycle_us)
                    }
                    Ok(us) => Preset::iec(us, p.cycle_us),
                    Err(None) => Preset::Variable { name: format!("{inst}.PT"), why: None },
                    Err(Some((name, why))) => Preset::Variable { name, why: Some(why) },
                };
                let timer = Timer {
                    on_delay: s == Std::Ton,
                    keyword: if s == Std::Ton { "TON" } else { "TOF" }.into(),
                    accumulator: inst,
                    preset,
                    input,
                    span,
                    called: true,
                };
                let q = BoolExpr::Timer(Box::new(timer));
                self.coil(q, &hidden("Q"), WriteKind::Assign, span);
            }
            Std::Tp => {
                let inst = instance.as_deref().map_or_else(String::new, |i| {
                    p.vars.get(&i.to_ascii_uppercase()).map_or(i.to_string(), |v| v.name.clone())
                });
                let Ok(pt) = preset else {
                    let what = match preset {
                        Err(Some((var, why))) => format!(
                            "the pulse timer {inst} with a PT given by the variable {var}, \
                             which is not a constant: {why}"
                        ),
                        _ => format!("the pulse timer {inst} with a PT that is not a literal"),
                    };
                    self.coil(fresh("TP", &what, span), &hidden("Q"), WriteKind::Assign, span);
                    return start;
                };
                let mut stmts = Vec::new();
                let v = value("IN");
                let input = self.temp(&mut stmts, v);
                // matiec's TP remembers IN (`PREV_IN`) to see its rising edge.
                self.edges.push((self.path.clone(), k, "TP_IN".into()));
                let memory = Memory {
                    base: "OSR".into(),
                    element: "OSR".into(),
                    index: self.edges.len() - 1,
                };
                let edge = crate::program::EdgeKind::Rising;
                let rise = BoolExpr::Edge {
                    kind: edge,
                    input: Box::new(input.clone()),
                    memory: Box::new(memory),
                };
                let rise = self.temp(&mut stmts, rise);
                let (q, done) = (hidden("Q"), hidden("DONE"));
                let pulse = crate::program::library::Pulse {
                    keyword: "TP",
                    instance: &inst,
                    q: &q,
                    done: &done,
                    pt_us: pt,
                    cycle_us: p.cycle_us,
                    span,
                };
                stmts.extend(pulse.call(input, rise, &mut |out, e| self.temp(out, e)));
                self.push_block(stmts, span);
            }
            s @ (Std::Sr | Std::Rs) => {
                let (set, reset) = s.set_reset().unwrap_or_default();
                let sv = value(set);
                let rv = value(reset);
                let (hs, hr, q) = (hidden(set), hidden(reset), hidden("Q1"));
                self.coil(sv, &hs, WriteKind::Assign, span);
                self.coil(rv, &hr, WriteKind::Assign, span);
                // The inputs are the instance's, written whatever its EN.
                start = self.blocks.len();
                let set_rung = (contact(&hs, false), WriteKind::Set);
                let reset_rung = (contact(&hr, false), WriteKind::Reset);
                // SR: Q1 := S1 + ¬R·Q1 (reset, then set); RS: Q1 := ¬R1·(S + Q1) (set, then reset).
                let rungs =
                    if s == Std::Sr { [reset_rung, set_rung] } else { [set_rung, reset_rung] };
                for (c, kind) in rungs {
                    self.coil(c, &q, kind, span);
                }
            }
            s @ (Std::RTrig | Std::FTrig) => {
                let clk = value("CLK");
                let edge = if s == Std::RTrig { Edge::Rising } else { Edge::Falling };
                let q = self.trig_of(k, "M", edge, clk);
                self.coil(q, &hidden("Q"), WriteKind::Assign, span);
            }
            _ => {}
        }
        start
    }
}
