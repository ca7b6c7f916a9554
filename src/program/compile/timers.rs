//! Timers in the II compiler: a timer as the runtime counts its scans (`d/IN`, `IN/d` over the scans it counts), and timers and edge detectors called under a condition, which the runtime runs only at the scans they are called.

use super::super::logic::{L, simp};
use super::super::{EdgeKind, Preset, Timer, TimerModel};
use super::{CompileError, Compiler, Pending, SignalKind, TimerInfo};
use crate::syntax::delay_to_string;
use crate::term::Delay;

impl Compiler<'_> {
    /// A timer block or edge detector called under a condition (inside an `If`, whose
    /// branch conditions make the guard `g`): the runtime runs it only at the scans it is
    /// called. A memory `H = g·i + ¬g·pre H` holds the input `i` its last call gave it
    /// (0 before the first, as the runtime's `PREV_IN`): a timer times `H` (the runtime's
    /// timer measures the time since the call that started it, and sees no input between
    /// calls), an edge compares `i` with `pre H`. What it gives at a call is read there;
    /// the `If` keeps what its outputs were given at the last call otherwise.
    pub(super) fn held_input(&mut self, base: &str, input: &L, kind: SignalKind) -> String {
        let h = self.unique(base);
        self.fresh.insert(h.clone(), kind);
        let pre = self.pre_name(&h);
        let g = self.guard.clone();
        let next = simp(&g.clone().and(input.clone()).or(g.negate().and(L::Var(pre.clone()))));
        let rhs = self.finish_var(&pre, next.clone(), None);
        let recurrence = (rhs != next).then_some(next);
        self.pending.push(Pending { var: h.clone(), rhs, recurrence });
        h
    }

    /// A timer, one-shot or toggle inside an `If` that ii-prove does not model: refused
    /// (its memory would update only on the scans its branch runs).
    pub(super) fn conditional_memory(&mut self) {
        let span = self.if_span.unwrap_or(self.block().span);
        if self.errors.iter().any(|e| e.span == span) {
            return;
        }
        self.errors.push(CompileError {
            span,
            keyword: "IF".into(),
            reason: "a pulse timer (TP) longer than a scan, a toggle, or under --any-state a \
                     timer or edge detector, inside a conditional statement updates its memory \
                     only on the scans its branch runs, which ii-prove does not model yet; call \
                     it unconditionally and use its output in the branch"
                .into(),
        });
    }

    pub(super) fn timer(&mut self, t: &Timer, input: L) -> L {
        if self.options.any_state {
            return self.timer_from_any_state(t);
        }
        let keyword = t.keyword.clone();
        let name = &t.accumulator;
        let cycle = self.program.cycle_us;
        let why = match &t.preset {
            _ if self.shared_timers.contains(name) => Some(format!(
                "the accumulator {name} is also written by another element (RES, MOVE, a SHIFT_REGISTER stage, PERSIST at power-up, another timer, …)"
            )),
            Preset::Variable { name, why } => Some(match why {
                Some(why) => {
                    format!("a delay given by the variable {name} is not a constant: {why}")
                }
                None => format!("a delay given by the variable {name} is not a constant"),
            }),
            Preset::Micros { us: 0, .. } => Some("a zero delay is not a delay".into()),
            Preset::Micros { .. } if cycle == 0 => {
                Some("with a zero cycle the timer never expires".into())
            }
            Preset::Micros { .. } => None,
        };
        let (Preset::Micros { us, adjust, default_of }, None) = (&t.preset, &why) else {
            let why = why.unwrap_or_else(|| "the delay is not expressible".into());
            return self.new_fresh(&format!("{keyword}_{name}"), &keyword, t.span, &why);
        };
        let (us, adjust) = (*us, *adjust);
        // The runtime counts P = floor(delay / cycle) + adjust scans; a TON is on from
        // the (P+1)-th consecutive scan with its input on, a TOF stays on for P scans
        // after its input falls. On scan runs that is exactly `d/IN` and `IN/d` with
        // d = P · cycle; with P ≤ 0 the output is the input.
        let scans = i64::try_from(us / cycle).unwrap_or(i64::MAX).saturating_add(adjust);
        let nominal = Delay::from_micros(us).ok();
        let plc = u64::try_from(scans)
            .ok()
            .filter(|p| *p > 0)
            .and_then(|p| p.checked_mul(cycle))
            .and_then(|d| Delay::from_micros(d).ok());
        if self.options.timers == TimerModel::Ideal && us % cycle != 0 {
            // On scans only a whole number of cycles has one reading (semantics.md).
            let (below, above) = (us / cycle * cycle, (us / cycle + 1) * cycle);
            let nearest = if below == 0 {
                format!("the shortest whole multiple is {above} µs")
            } else {
                format!("the nearest whole multiples are {below} µs and {above} µs")
            };
            self.errors.push(CompileError {
                span: t.span,
                keyword: keyword.clone(),
                reason: format!(
                    "with --timers ideal the delay is used as written, and {us} µs is not a \
                     whole number of {cycle} µs scan cycles ({nearest}); the default \
                     --timers plc uses the scans the runtime counts"
                ),
            });
        }
        let d = match self.options.timers {
            TimerModel::Plc if scans < 1 => None,
            TimerModel::Plc => plc.clone(),
            TimerModel::Ideal => nominal.clone(),
        };
        if d.is_none() && (scans >= 1 || self.options.timers == TimerModel::Ideal) {
            let why = "the delay is too large to express";
            return self.new_fresh(&format!("{keyword}_{name}"), &keyword, t.span, why);
        }
        if scans < 1 {
            self.warn(
                t.span,
                &keyword,
                format!(
                    "the runtime counts P = floor({us} µs / {cycle} µs) {} = {scans} scans: \
                     LDmicro 2.x refuses to compile this timer, and the new LDmicro runs it \
                     with its output following its input{}",
                    signed(adjust),
                    if self.options.timers == TimerModel::Plc {
                        ", as compiled here"
                    } else {
                        "; --timers ideal uses the delay as written"
                    }
                ),
            );
        } else if self.options.timers == TimerModel::Plc && plc != nominal {
            let effective = plc.as_ref().map_or_else(String::new, delay_to_string);
            let nominal = nominal.as_ref().map_or_else(|| format!("{us} µs"), delay_to_string);
            self.warn(
                t.span,
                &keyword,
                format!(
                    "the runtime counts P = floor({us} µs / {cycle} µs) {} = {scans} scans of \
                     the cycle, so {name} times {effective}, not the {nominal} written{}; the \
                     equation uses {effective} (--timers ideal uses {nominal})",
                    signed(adjust),
                    match default_of {
                        Some(file) => format!(" (the default adjust of an {file} file)"),
                        None => String::new(),
                    }
                ),
            );
        }
        self.timer_info.push(TimerInfo {
            rung: self.block().number,
            keyword: keyword.clone(),
            name: name.to_string(),
            delay_us: us,
            adjust,
            scans,
            effective: d.clone(),
        });
        match (d, t.on_delay) {
            (None, _) => input,
            (Some(d), true) => simp(&L::Ton(d, Box::new(input))),
            (Some(d), false) => simp(&L::Tof(Box::new(input), d)),
        }
    }
}

/// An adjust as written in a formula: `+ 5`, `- 1`.
fn signed(v: i64) -> String {
    if v < 0 { format!("- {}", v.unsigned_abs()) } else { format!("+ {v}") }
}

/// The edge of `kind` of the input `input` against its previous value `prev`: rising
/// `i · ¬prev`, falling `¬i · prev`, not rising `¬(i · ¬prev)`.
pub(super) fn edge_of(kind: EdgeKind, input: L, prev: L) -> L {
    match kind {
        EdgeKind::Rising => simp(&input.and(prev.negate())),
        EdgeKind::Falling => simp(&input.negate().and(prev)),
        EdgeKind::NotRising => simp(&input.and(prev.negate()).negate()),
    }
}
