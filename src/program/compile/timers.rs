//! Timers in the II compiler: a timer as the runtime counts its scans (`d/IN`, `IN/d` over the scans it counts), and timers and edge detectors called under a condition, which the runtime runs only at the scans they are called.

use super::super::logic::{L, simp, simplify};
use super::super::{EdgeKind, Preset, Timer, TimerModel};
use super::{CompileError, Compiler, Pending, SignalKind, TimerInfo, canonical, simp_sum};
use crate::syntax::delay_to_string;
use crate::term::Delay;
use num_traits::ToPrimitive;

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
        let next = simplify(g.clone().and(input.clone()).or(g.negate().and(L::Var(pre.clone()))));
        let (rhs, recurrence) = self.finish_var(&pre, next, None);
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
        match self.timer_delay(t) {
            Err(fresh) => fresh,
            Ok(None) => input,
            Ok(Some(d)) if t.on_delay => simplify(L::Ton(d, Box::new(input))),
            Ok(Some(d)) => simplify(L::Tof(Box::new(input), d)),
        }
    }

    /// The delay `P · cycle` a timer counts (`None`: `P ≤ 0`, the output is the input),
    /// with the warnings on how the runtime counts it; else the unconstrained signal that
    /// stands for its output, and why.
    fn timer_delay(&mut self, t: &Timer) -> Result<Option<Delay>, L> {
        let keyword = t.keyword.clone();
        let name = &t.accumulator;
        let cycle = self.program.cycle_us;
        let why = match &t.preset {
            _ if self.shared_timers.contains(name) && !self.repeated.contains_key(name) => {
                Some(format!(
                    "the accumulator {name} is also written by another element (RES, MOVE, a SHIFT_REGISTER stage, PERSIST at power-up, another timer, …)"
                ))
            }
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
        let (Preset::Micros { us, adjust, default_of, .. }, None) = (&t.preset, &why) else {
            let why = why.unwrap_or_else(|| "the delay is not expressible".into());
            return Err(self.new_fresh(&format!("{keyword}_{name}"), &keyword, t.span, &why));
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
            return Err(self.new_fresh(&format!("{keyword}_{name}"), &keyword, t.span, why));
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
        Ok(d)
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
        EdgeKind::Rising => simplify(input.and(prev.negate())),
        EdgeKind::Falling => simplify(input.negate().and(prev)),
        EdgeKind::NotRising => simplify(input.and(prev.negate()).negate()),
    }
}

/// An IEC timer instance called at several places in the scan
/// ([`Program::repeated_timers`](super::super::Program::repeated_timers)), as the
/// compiler follows it through the scan. The runtime runs the block call by call
/// (`lib/timer.txt`): a `TON` starts at a call with `IN` after one without and is done at
/// a call `K = ⌈PT / cycle⌉` scans or more after the start; a `TOF` likewise from a call
/// without `IN` after one with. So what a call gives depends on the input the last call
/// gave (held between calls and scans), on whether a call earlier in this scan broke the
/// run, and on how long the run had gone on at the end of the last scan.
pub(super) struct Repeated {
    on_delay: bool,
    /// The calls not compiled yet.
    left: usize,
    /// `E`: the input the last call gave it, at the end of the scan (0 at first).
    held: String,
    /// Scan-local (a key of `current`, 0 at the start of the scan): whether a call so far
    /// in this scan broke the run (gave a TON a FALSE, a TOF a TRUE).
    broken: String,
    /// `K`, once the first call has told it (`Some(None)`: the output is unconstrained).
    scans: Option<Option<u64>>,
    /// `D`, the signal whose previous value tells a call how the run stood at the end of
    /// the last scan.
    due: String,
    /// Whether its equations are stated.
    stated: bool,
}

impl Compiler<'_> {
    /// The instances called at several places, each with its held input and its
    /// scan-local break, ready for the first call.
    pub(super) fn prepare_repeated(&mut self) {
        if self.options.any_state {
            return;
        }
        for (name, (calls, on_delay)) in self.program.repeated_timers() {
            let base = canonical(&name);
            let held = self.unique(&format!("{base}_IN"));
            let pre = self.pre_name(&held);
            self.current.insert(held.clone(), L::Var(pre));
            let broken = self.unique(&format!("{base}_broken"));
            self.current.insert(broken.clone(), L::Zero);
            let due = held.clone();
            let (left, scans, stated) = (calls, None, false);
            let r = Repeated { on_delay, left, held, broken, scans, due, stated };
            self.repeated.insert(name, r);
        }
    }

    /// A call of an instance called at several places: what its output `Q` is given.
    ///
    /// With `E` the input the last call gave (before this one), `b` whether a call earlier
    /// in this scan broke the run, and `pre D` how the run stood at the end of the last
    /// scan, a call with input `i` gives
    /// - a TON: `i · ¬b · pre D`, `D` being 1 where the run has gone on since the end of
    ///   scan `K − 1` before (`D = E` for `K = 1`, else `D = (K − 2)·cycle / U` with
    ///   `U = pre E · E · ¬b` at the end of the scan: the run went on through it);
    /// - a TOF: `i + b + pre D`, `D` being 1 where it was on or fell less than `K − 1`
    ///   scans before (`D = E` for `K = 1`, else `D = E + F/(K − 2)·cycle` with
    ///   `F = ¬E · (pre E + b)`: it fell in the scan);
    /// - with a preset of 0 (`K = 0`) a later call in the scan that started the run sees
    ///   it done: a TON gives `i · E`, a TOF `i + E`.
    pub(super) fn repeated_call(&mut self, t: &Timer, input: L) -> L {
        let name = &t.accumulator;
        let Some(r) = self.repeated.get(name) else { return self.timer(t, input) };
        let (held, broken, known) = (r.held.clone(), r.broken.clone(), r.scans);
        let scans = match known {
            Some(k) => k,
            None => {
                let k = self.repeated_scans(t);
                let rung = self.block().number;
                let due = match k {
                    Ok(k) if k >= 2 => {
                        let suffix = if t.on_delay { "due" } else { "holds" };
                        self.unique(&format!("{}_{suffix}", canonical(name)))
                    }
                    _ => held.clone(),
                };
                for n in [&held, &due] {
                    self.fresh.insert(n.clone(), SignalKind::HeldInput { rung });
                }
                if let Some(r) = self.repeated.get_mut(name) {
                    (r.scans, r.due) = (Some(k.as_ref().ok().copied()), due);
                }
                match k {
                    Ok(k) => Some(k),
                    Err(fresh) => {
                        self.after_call(name, &input);
                        return fresh;
                    }
                }
            }
        };
        let Some(scans) = scans else {
            self.after_call(name, &input);
            return self.timer(t, input);
        };
        let e = self.read(&held);
        let b = self.read(&broken);
        let due = self.repeated.get(name).map(|r| r.due.clone()).unwrap_or_default();
        let pre_due = L::Var(self.pre_name(&due));
        let q = match (t.on_delay, scans) {
            (true, 0) => input.clone().and(e),
            (false, 0) => input.clone().or(e),
            (true, _) => L::And(vec![input.clone(), b.negate(), pre_due].into()),
            (false, _) => simp_sum(vec![input.clone(), b, pre_due]),
        };
        self.after_call(name, &input);
        simp(&q)
    }

    /// `K`, the scans after its start at which a call sees the timer done (0 for a
    /// preset of 0), with the warnings on how the runtime counts them; else the
    /// unconstrained signal standing for this call's output.
    fn repeated_scans(&mut self, t: &Timer) -> Result<u64, L> {
        if matches!(t.preset, Preset::Micros { zero: true, .. }) {
            return Ok(0);
        }
        let d = self.timer_delay(t)?;
        let cycle = Delay::from_micros(self.program.cycle_us).ok();
        let k = d.zip(cycle).and_then(|(d, c)| (d.seconds() / c.seconds()).to_integer().to_u64());
        match k {
            Some(k) if k >= 1 => Ok(k),
            _ => Err(self.new_fresh(
                &format!("{}_{}", t.keyword, t.accumulator),
                &t.keyword,
                t.span,
                "the preset counts no whole scan",
            )),
        }
    }

    /// After a call with input `i`: the held input is `i`, and the run is broken in this
    /// scan if `i` breaks it.
    fn after_call(&mut self, name: &str, input: &L) {
        let Some(r) = self.repeated.get_mut(name) else { return };
        r.left = r.left.saturating_sub(1);
        let (held, broken, on_delay) = (r.held.clone(), r.broken.clone(), r.on_delay);
        let b = self.read(&broken);
        let breaks = if on_delay { input.clone().negate() } else { input.clone() };
        self.current.insert(broken, simplify(b.or(breaks)));
        self.current.insert(held, input.clone());
    }

    /// At the end of a block: the equations of each instance whose last call it holds
    /// (`E`, and `D` with its parts), stated with the block.
    pub(super) fn state_repeated(&mut self) {
        let done: Vec<String> = self
            .repeated
            .iter()
            .filter(|(_, r)| r.left == 0 && !r.stated)
            .map(|(n, _)| n.clone())
            .collect();
        for name in done {
            let Some(r) = self.repeated.get_mut(&name) else { continue };
            r.stated = true;
            let (held, broken, due, on_delay) =
                (r.held.clone(), r.broken.clone(), r.due.clone(), r.on_delay);
            let scans = r.scans.flatten();
            let end = self.read(&held);
            let b = self.read(&broken);
            self.state(held.clone(), end, None);
            let Some(k) = scans.filter(|k| *k >= 2) else { continue };
            let e = L::var(&held);
            let pre_e = L::Var(self.pre_name(&held));
            // The part `U` (TON) or `F` (TOF), timed over K − 2 more scans.
            let part = if on_delay {
                L::And(vec![pre_e, e.clone(), b.negate()].into())
            } else {
                e.clone().negate().and(pre_e.or(b))
            };
            let part = simp(&part);
            let timed = match Delay::from_micros((k - 2).saturating_mul(self.program.cycle_us)) {
                _ if k == 2 => part,
                Ok(d) if on_delay => {
                    let runs = self.unique(&format!("{}_runs", canonical(&name)));
                    let rung = self.block().number;
                    self.fresh.insert(runs.clone(), SignalKind::HeldInput { rung });
                    self.pending.push(Pending { var: runs.clone(), rhs: part, recurrence: None });
                    // `U · d/U` (= `d/U`): the run going on now, stated where the
                    // Boolean case splits, which keep timers opaque, can read it.
                    L::And(vec![L::var(&runs), L::Ton(d, Box::new(L::var(&runs)))].into())
                }
                Ok(d) => L::Tof(Box::new(part), d),
                Err(_) => {
                    let (span, why) = (self.block().span, "the delay is too large to express");
                    self.new_fresh(&format!("TIMER_{name}"), "TIMER", span, why)
                }
            };
            let rhs = if on_delay { timed } else { simp_sum(vec![e, timed]) };
            self.pending.push(Pending { var: due, rhs: simp(&rhs), recurrence: None });
        }
    }
}
