//! A reference scan simulator of PLCopen LD/FBD programs, written from the format note (§5–§8) and matiec's standard function blocks, over the PLCopen objects directly (not through the rung model).
//!
//! One [`PlcSimulator::step`] is one scan at time `scan × cycle`: inputs are
//! latched, then the statements run in evaluation order. Values flow along the
//! wires; a block is called at its first use in the scan (its inputs evaluated
//! then) and its outputs are kept; a block reached again while its own inputs
//! are computed (feedback) gives its previous outputs. TON/TOF/TP follow matiec's
//! time-based state machines on a clock that advances one cycle per scan; SR,
//! RS, R_TRIG and F_TRIG are their IEC definitions; integers, their blocks and the
//! counters are computed concretely as matiec's C does (`simulate/ints.rs`). Under
//! `EN` FALSE a function block does not run (outputs kept) and a function returns
//! 0/FALSE with its `ENO` FALSE (matiec's `TEST_EN`); an output variable fed straight
//! from a block whose `EN` has a wire is written only under that block's `ENO`
//! (Beremiz's `GetUsedEno`). Other
//! blocks are not modelled: their Boolean outputs read FALSE (the prover leaves them
//! unconstrained), and names depending on them are reported by
//! [`PlcSimulator::unknown`].

use std::collections::{BTreeMap, BTreeSet};

use super::{Edge, ObjKind, Operand, PinIn, PlcProgram, Source, Std, Storage};

mod ints;
mod text;

#[derive(Clone, Copy, Debug, Default)]
struct Timer {
    state: u8,
    prev_in: bool,
    start: u64,
    q: bool,
}

/// The PLCopen scan simulator.
pub struct PlcSimulator {
    p: PlcProgram,
    /// Declared BOOL variables and hidden variables.
    bits: BTreeMap<String, bool>,
    timers: BTreeMap<String, Timer>,
    /// Edge-detector memories (`M` of R_TRIG/F_TRIG), by owner and pin.
    memory: BTreeMap<(usize, String), bool>,
    /// Per scan: blocks called, edge values computed.
    called: BTreeSet<usize>,
    in_progress: BTreeSet<usize>,
    /// While the inputs of a block with an `executionOrderId` are read: blocks not yet
    /// called are not called (their outputs are read as they stand).
    no_pull: bool,
    edges: BTreeMap<(usize, String), bool>,
    /// The edge detector each one-shot of the lowering stands for, by index
    /// ([`super::Lowered::edges`]), where given ([`PlcSimulator::showing`]).
    one_shots: Vec<super::EdgeKey>,
    visiting: BTreeSet<usize>,
    /// Blocks whose EN was off in this scan (their outputs kept).
    scans: u64,
    unknown: BTreeSet<String>,
    /// The simulators of inlined function block instances (they run on this one's bits).
    subs: BTreeMap<usize, PlcSimulator>,
    /// The scan-model simulators of text block instances (`simulate/text.rs`).
    texts: BTreeMap<usize, text::Instance>,
    /// Integer variables, block outputs and counts: value and C type.
    ints: BTreeMap<String, (i64, ints::CType)>,
    /// TIME variables (by declared name): their value in µs, `None` once written with a
    /// value that is not a literal duration or another TIME variable's.
    times: BTreeMap<String, Option<u64>>,
    /// The free inputs of `REAL_TO_*` blocks, this body's and its inlined ones' (the
    /// run's value where C leaves a block's result undefined), and those that stand for
    /// what peripherals give.
    undefined: Vec<(String, String)>,
}

/// The free inputs of the `REAL_TO_*` blocks of `p` and of its inlined bodies, and of
/// what its peripherals give.
fn undefined_inputs(p: &PlcProgram) -> Vec<(String, String)> {
    let mut out = p.undefined_inputs();
    out.extend(p.peripheral_inputs());
    out.extend(p.subs.values().flat_map(undefined_inputs));
    out
}

impl PlcSimulator {
    /// A simulator at power-up: every BOOL at its initial value (FALSE unless declared).
    pub fn new(p: &PlcProgram) -> PlcSimulator {
        let mut bits = BTreeMap::new();
        for v in p.vars.values().filter(|v| v.ty == super::Ty::Bool) {
            let init = v.init.as_deref().is_some_and(|i| {
                matches!(
                    i.trim().to_ascii_uppercase().as_str(),
                    "TRUE" | "1" | "BOOL#TRUE" | "BOOL#1"
                )
            });
            bits.insert(v.name.clone(), init);
        }
        for n in p.hidden.values().chain(p.latches.values()).chain(&p.started) {
            bits.insert(n.clone(), false);
        }
        let texts = text::simulators(p);
        for (_, names) in texts.values() {
            bits.extend(names.iter().map(|n| (n.clone(), false)));
        }
        let subs: BTreeMap<usize, PlcSimulator> =
            p.subs.iter().map(|(k, child)| (*k, PlcSimulator::new(child))).collect();
        for sub in subs.values() {
            bits.extend(sub.bits.iter().map(|(n, v)| (n.clone(), *v)));
        }
        let mut ints = BTreeMap::new();
        PlcSimulator::init_ints(p, &mut ints);
        // The latch of an integer is an integer input, not a bit.
        for (x, latch) in &p.latches {
            if let Some((_, ct)) = ints.get(x).copied() {
                bits.remove(latch);
                ints.insert(latch.clone(), (0, ct));
            }
        }
        // A TIME variable starts at its initial value, T#0s when none is declared.
        let times = p
            .vars
            .values()
            .filter(|v| matches!(&v.ty, super::Ty::Other(t) if t.eq_ignore_ascii_case("TIME")))
            .map(|v| (v.name.clone(), v.init.as_deref().map_or(Some(0), super::parse_duration)))
            .collect();
        PlcSimulator {
            ints,
            times,
            subs,
            texts,
            p: p.clone(),
            bits,
            timers: BTreeMap::new(),
            memory: BTreeMap::new(),
            called: BTreeSet::new(),
            in_progress: BTreeSet::new(),
            no_pull: false,
            edges: BTreeMap::new(),
            one_shots: Vec::new(),
            visiting: BTreeSet::new(),
            scans: 0,
            unknown: BTreeSet::new(),
            undefined: undefined_inputs(p),
        }
    }

    /// Runs one scan with the given input values (missing inputs keep their value).
    pub fn step(&mut self, inputs: &BTreeMap<String, bool>) {
        for (n, v) in inputs {
            if self.p.is_input(n) {
                self.bits.insert(n.clone(), *v);
            }
        }
        self.read_int_inputs(inputs);
        // A retained variable starts with the value it kept (given as its start input).
        if self.scans == 0 {
            for (x, start) in &self.p.starts {
                if let Some(s) = start {
                    let v = self.bit(s);
                    self.bits.insert(x.clone(), v);
                }
            }
        }
        // A latched input is the outside value at the start of the scan.
        for (x, latch) in &self.p.latches {
            if let Some(v) = self.ints.get(latch).copied() {
                self.ints.insert(x.clone(), v);
            } else {
                let v = self.bit(latch);
                self.bits.insert(x.clone(), v);
            }
        }
        self.body();
        if let Some(started) = &self.p.started {
            self.bits.insert(started.clone(), true);
        }
        self.scans += 1;
    }

    /// One execution of the body: every statement in evaluation order.
    fn body(&mut self) {
        self.called.clear();
        self.edges.clear();
        self.in_progress.clear();
        let order = self.p.order.clone();
        for k in order {
            self.statement(k);
        }
    }

    /// A bit's value at the end of the last scan.
    pub fn bit(&self, name: &str) -> bool {
        self.bits.get(name).copied().unwrap_or(false)
    }

    /// Every bit (declared BOOLs and hidden variables).
    pub fn bits(&self) -> &BTreeMap<String, bool> {
        &self.bits
    }

    /// Whether the simulator has the bit or integer.
    pub fn is_known(&self, name: &str) -> bool {
        self.bits.contains_key(name) || self.ints.contains_key(name)
    }

    /// Scans run so far.
    pub fn scans(&self) -> u64 {
        self.scans
    }

    /// The memory (`M`, the input it saw at its last evaluation, FALSE before) of the
    /// edge detector `pin` of object `owner` in the inlined body at `path` (`""` for a
    /// contact or variable, `"COIL"` for a coil, `"M"` for an R_TRIG/F_TRIG block, the
    /// pin name for a block input): what a one-shot of the lowering remembers.
    pub fn edge_memory_of(&self, path: &[usize], owner: usize, pin: &str) -> Option<bool> {
        match path.split_first() {
            Some((k, rest)) => self.subs.get(k)?.edge_memory_of(rest, owner, pin),
            None => Some(self.memory.get(&(owner, pin.to_string())).copied().unwrap_or(false)),
        }
    }

    /// The simulator that also shows the memory of each one-shot of the lowering, by its
    /// index ([`PlcSimulator::edge_memory`]): `one_shots` the lowering's
    /// [`super::Lowered::edges`].
    pub fn showing(mut self, one_shots: Vec<super::EdgeKey>) -> PlcSimulator {
        self.one_shots = one_shots;
        self
    }

    /// The memory of the lowering's one-shot with this index after the last scan: its
    /// edge detector's, `None` where not given or inside a text block (whose memories
    /// are its own program's).
    pub fn edge_memory(&self, index: usize) -> Option<bool> {
        let (path, owner, pin) = self.one_shots.get(index)?;
        if pin.starts_with("TEXT") {
            return None;
        }
        self.edge_memory_of(path, *owner, pin)
    }

    /// Names written from values the simulator does not model (counters, comparisons…).
    pub fn unknown(&self) -> &BTreeSet<String> {
        &self.unknown
    }

    fn now(&self) -> u64 {
        self.scans.saturating_mul(self.p.cycle_us)
    }

    fn operand(&mut self, op: &Operand) -> bool {
        match op {
            Operand::Bool(n) => self.bit(n),
            Operand::Const(b) => *b,
            Operand::Member(inst, pin) => {
                let name = format!("{inst}_{pin}");
                let hidden =
                    self.p.hidden.values().find(|h| h.eq_ignore_ascii_case(&name)).cloned();
                hidden.is_some_and(|h| self.bit(&h))
            }
            // An integer literal of value 0 or 1 where a BOOL is expected is FALSE or TRUE
            // (matiec's `fill_candidate_datatypes.cc` keeps BOOL among its types).
            Operand::Other(t) => super::bool_of_int_literal(t) == Some(true),
            Operand::Duration(_) => false,
        }
    }

    fn resolve(&self, text: &str) -> Operand {
        let upper = text.trim().to_ascii_uppercase();
        match upper.as_str() {
            "TRUE" => Operand::Const(true),
            "FALSE" => Operand::Const(false),
            _ => match self.p.vars.get(&upper) {
                Some(v) if v.ty == super::Ty::Bool => Operand::Bool(v.name.clone()),
                _ => Operand::Other(text.to_string()),
            },
        }
    }

    /// The value at a consumer pin: the OR of its wires (unconnected: FALSE).
    fn pin_power(&mut self, pin: &PinIn) -> bool {
        if let Some((text, _)) = &pin.expr {
            let op = self.resolve(text);
            return self.operand(&op);
        }
        let mut any = false;
        for c in &pin.conns {
            if let Some(src) = self.p.source(c) {
                // Every wire is evaluated (for its block calls), then ORed.
                any |= self.source(src, 0);
            }
        }
        any
    }

    fn trigger(&mut self, owner: usize, pin: &str, edge: Edge, v: bool) -> bool {
        if edge == Edge::None {
            return v;
        }
        let key = (owner, pin.to_string());
        if let Some(q) = self.edges.get(&key) {
            return *q;
        }
        let m = self.memory.get(&key).copied().unwrap_or(false);
        // R_TRIG: Q := CLK ∧ ¬M; M := CLK. F_TRIG: Q := ¬CLK ∧ ¬M; M := ¬CLK.
        let clk = if edge == Edge::Rising { v } else { !v };
        let q = clk && !m;
        self.memory.insert(key.clone(), clk);
        self.edges.insert(key, q);
        if let Some(h) = self.p.hidden_name(owner, pin).map(str::to_string) {
            self.bits.insert(h, q);
        }
        q
    }

    fn source(&mut self, src: Source, depth: usize) -> bool {
        if depth > 10_000 {
            return false;
        }
        match src {
            Source::Rail => true,
            Source::Object(k) => self.object(k),
            Source::BlockOut(k, pin) => {
                let (name, negated) = self.p.output_pin(k, pin);
                let v = self.output(k, &name);
                v != negated
            }
            Source::BlockPin(k, pin) => self.output(k, pin),
        }
    }

    fn object(&mut self, k: usize) -> bool {
        if !self.visiting.insert(k) {
            return false;
        }
        let v = self.object_value(k);
        self.visiting.remove(&k);
        v
    }

    fn object_value(&mut self, k: usize) -> bool {
        let Some(o) = self.p.obj(k).cloned() else { return false };
        let op = self.p.operands.get(&k).cloned();
        match &o.kind {
            ObjKind::Contact { negated, edge, input, .. } => {
                let pred = self.pin_power(input);
                let v = op.as_ref().is_some_and(|op| self.operand(op));
                let v = self.trigger(k, "", *edge, v != *negated);
                pred && v
            }
            ObjKind::Coil { input, .. } | ObjKind::Connector { input, .. } => self.pin_power(input),
            ObjKind::InVar { negated, edge, .. } => {
                let v = op.as_ref().is_some_and(|op| self.operand(op));
                self.trigger(k, "", *edge, v != *negated)
            }
            ObjKind::InOutVar { .. } | ObjKind::OutVar { .. } => {
                op.as_ref().is_some_and(|op| self.operand(op))
            }
            _ => false,
        }
    }

    fn en(&mut self, k: usize) -> bool {
        match self.p.en_pin(k).cloned() {
            Some(pin) => {
                let v = self.pin_power(&pin);
                self.trigger(k, "EN", pin.edge, v != pin.negated)
            }
            None => true,
        }
    }

    /// Output `pin` of block `k`, calling it at its first use.
    fn output(&mut self, k: usize, pin: &str) -> bool {
        let enabled = if self.no_pull && !self.called.contains(&k) && !self.in_progress.contains(&k)
        {
            true
        } else {
            self.call(k)
        };
        if pin.eq_ignore_ascii_case("ENO") {
            // An integer function's `_TMP_…_ENO` variable, as its last call left it.
            if let Some(h) = self.p.hidden_name(k, "ENO") {
                return self.bit(h);
            }
            return enabled;
        }
        if let Some(var) = self.p.sub_var(k, pin, true) {
            return self.bit(var);
        }
        if self.p.int_block(k).is_some() || self.p.bool_mux(k) {
            let boolean = ["OUT", "Q", "QU", "QD"].iter().any(|q| pin.eq_ignore_ascii_case(q));
            return boolean
                && self.p.hidden_name(k, &pin.to_ascii_uppercase()).is_some_and(|h| self.bit(h));
        }
        match self.p.std_block(k) {
            Some(s) if s.output().eq_ignore_ascii_case(pin) => {
                self.p.hidden_name(k, s.output()).is_some_and(|h| self.bit(h))
            }
            _ => false,
        }
    }

    fn input(&mut self, k: usize, name: &str) -> bool {
        match self.p.pin(k, name).cloned() {
            Some(pin) => {
                let v = self.pin_power(&pin);
                let v = v != pin.negated;
                self.trigger(k, &pin.name.to_ascii_uppercase(), pin.edge, v)
            }
            None => false,
        }
    }

    /// The `PT` of the timer block at `k` as it reads now: a literal, or a TIME
    /// variable's current value (`None` when the simulator does not know it).
    fn preset(&mut self, k: usize) -> Option<u64> {
        let Some(pin) = self.p.pin(k, "PT").cloned() else { return Some(0) };
        if let Some((text, _)) = &pin.expr {
            return self.duration(text);
        }
        let mut us = Some(0);
        for c in &pin.conns {
            match self.p.source(c) {
                Some(Source::Object(j)) => match self.p.operands.get(&j) {
                    Some(Operand::Duration(d)) => us = Some(*d),
                    Some(Operand::Other(t)) => us = self.duration(&t.clone()),
                    _ => {}
                },
                Some(src @ (Source::BlockOut(..) | Source::BlockPin(..))) => {
                    let _ = self.source(src, 0);
                    us = None;
                }
                _ => {}
            }
        }
        us
    }

    /// The duration `text` stands for: a literal, or a TIME variable's current value.
    fn duration(&self, text: &str) -> Option<u64> {
        if let Some(us) = super::parse_duration(text) {
            return Some(us);
        }
        let v = self.p.vars.get(&text.trim().to_ascii_uppercase())?;
        self.times.get(&v.name).copied().flatten()
    }

    /// What the output or in-out variable object with input `input` writes to a TIME
    /// variable: a literal, another TIME variable's value, else not known.
    fn time_written(&self, input: &PinIn) -> Option<u64> {
        if let Some((text, _)) = &input.expr {
            return self.duration(text);
        }
        let [c] = input.conns.as_slice() else { return None };
        match self.p.source(c)? {
            Source::Object(j) => match self.p.operands.get(&j)? {
                Operand::Duration(us) => Some(*us),
                Operand::Other(t) => self.duration(t),
                _ => None,
            },
            _ => None,
        }
    }

    fn set_hidden(&mut self, k: usize, pin: &str, v: bool) {
        if let Some(h) = self.p.hidden_name(k, pin).map(str::to_string) {
            self.bits.insert(h, v);
        }
    }

    /// Calls block `k` once per scan; returns its ENO.
    fn call(&mut self, k: usize) -> bool {
        if self.called.contains(&k) || self.in_progress.contains(&k) {
            return self.edges.get(&(k, "ENO".into())).copied().unwrap_or(false);
        }
        self.in_progress.insert(k);
        let ordered = self.p.obj(k).is_some_and(|o| o.order > 0);
        let outer = std::mem::replace(&mut self.no_pull, ordered);
        let std = self.p.std_block(k);
        let inst = match self.p.obj(k).map(|o| &o.kind) {
            Some(ObjKind::Block { instance, .. }) => {
                instance.clone().unwrap_or_default().to_ascii_uppercase()
            }
            _ => String::new(),
        };
        // Inputs are evaluated whether or not the block runs (their blocks are called).
        let names: Vec<PinIn> = match self.p.obj(k).map(|o| &o.kind) {
            Some(ObjKind::Block { inputs, .. }) => inputs.clone(),
            _ => Vec::new(),
        };
        // Two passes, as the generated code runs: first every block call and edge
        // detector the inputs reach, in wire order; then the inputs are read.
        let _ = self.en(k);
        for pin in &names {
            match pin.name.to_ascii_uppercase().as_str() {
                "EN" => {}
                "PT" => {
                    let _ = self.preset(k);
                }
                n => {
                    let _ = self.input(k, n);
                }
            }
        }
        let en = self.en(k);
        let mut values: BTreeMap<String, bool> = BTreeMap::new();
        let mut preset = Some(0);
        for pin in &names {
            let n = pin.name.to_ascii_uppercase();
            if n == "EN" {
                continue;
            }
            if n == "PT" {
                preset = self.preset(k);
                continue;
            }
            let v = self.input(k, &n);
            values.insert(n, v);
        }
        self.no_pull = outer;
        self.kept_inputs(k, (std, en), &names, &values);
        let get = |n: &str| values.get(n).copied().unwrap_or(false);
        if let Some(b) = self.p.int_block(k) {
            self.int_exec(k, &b, en, &values);
        } else if self.p.bool_mux(k) {
            let v = self.bool_mux(k, &values);
            self.set_hidden(k, "OUT", v);
        } else if let Some(s) = std.filter(|s| !en && !s.is_fb()) {
            // A function under EN = FALSE returns FALSE (matiec's `TEST_EN(BOOL)`).
            self.set_hidden(k, s.output(), false);
        } else if en {
            let now = self.now();
            match std {
                Some(Std::And) => {
                    let v = self.p.data_inputs(k).iter().all(|p| get(&p.name.to_ascii_uppercase()));
                    self.set_hidden(k, "OUT", v);
                }
                Some(Std::Or) => {
                    let v = self.p.data_inputs(k).iter().any(|p| get(&p.name.to_ascii_uppercase()));
                    self.set_hidden(k, "OUT", v);
                }
                Some(Std::Xor) => {
                    let v = self
                        .p
                        .data_inputs(k)
                        .iter()
                        .fold(false, |acc, p| acc != get(&p.name.to_ascii_uppercase()));
                    self.set_hidden(k, "OUT", v);
                }
                Some(Std::Not) => self.set_hidden(k, "OUT", !get("IN")),
                Some(Std::Move) => self.set_hidden(k, "OUT", get("IN")),
                Some(Std::Sel) => {
                    let v = if get("G") { get("IN1") } else { get("IN0") };
                    self.set_hidden(k, "OUT", v);
                }
                Some(s @ (Std::Ton | Std::Tof | Std::Tp)) => {
                    let input = get("IN");
                    // A PT the simulator does not know: the timer's output is not known.
                    if preset.is_none()
                        && let Some(q) = self.p.hidden_name(k, "Q")
                    {
                        self.unknown.insert(q.to_string());
                    }
                    let preset = preset.unwrap_or(0);
                    let t = self.timers.entry(inst).or_default();
                    let due = t.start.saturating_add(preset) <= now;
                    match s {
                        Std::Ton => {
                            if t.state == 0 && !t.prev_in && input {
                                t.state = 1;
                                t.q = false;
                                t.start = now;
                            } else if !input {
                                t.q = false;
                                t.state = 0;
                            } else if t.state == 1 && due {
                                t.state = 2;
                                t.q = true;
                            }
                        }
                        Std::Tof => {
                            if t.state == 0 && t.prev_in && !input {
                                t.state = 1;
                                t.start = now;
                            } else if input {
                                t.state = 0;
                            } else if t.state == 1 && due {
                                t.state = 2;
                            }
                            t.q = input || t.state == 1;
                        }
                        _ => {
                            if t.state == 0 && !t.prev_in && input {
                                t.state = 1;
                                t.q = true;
                                t.start = now;
                            } else if t.state == 1 && due {
                                t.state = 2;
                                t.q = false;
                            }
                            if t.state == 2 && !input {
                                t.state = 0;
                            }
                        }
                    }
                    t.prev_in = input;
                    let (q, done) = (t.q, t.state == 2);
                    self.set_hidden(k, "Q", q);
                    if s == Std::Tp {
                        // matiec's TP: its PREV_IN, and whether the pulse is over while IN
                        // is still on (STATE 2).
                        self.memory.insert((k, "TP_IN".into()), input);
                        self.set_hidden(k, "DONE", done);
                    }
                }
                Some(s @ (Std::Sr | Std::Rs)) => {
                    let (set, reset) = s.set_reset().unwrap_or_default();
                    let (sv, rv) = (get(set), get(reset));
                    let q = self.p.hidden_name(k, "Q1").is_some_and(|h| self.bit(h));
                    let q = if s == Std::Sr { sv || (!rv && q) } else { !rv && (sv || q) };
                    self.set_hidden(k, "Q1", q);
                }
                Some(s @ (Std::RTrig | Std::FTrig)) => {
                    let key = (k, "M".to_string());
                    let m = self.memory.get(&key).copied().unwrap_or(false);
                    let clk = if s == Std::RTrig { get("CLK") } else { !get("CLK") };
                    self.memory.insert(key, clk);
                    self.set_hidden(k, "Q", clk && !m);
                }
                None if self.p.text_calls.contains_key(&k) => {
                    self.text_call(k, &names, &values, true);
                }
                None => {
                    // An inlined user function block: its body runs on the same bits, at
                    // this scan's time (its inputs assigned above).
                    if let Some(mut sub) = self.subs.remove(&k) {
                        sub.bits = std::mem::take(&mut self.bits);
                        sub.ints = std::mem::take(&mut self.ints);
                        sub.scans = self.scans;
                        sub.body();
                        self.bits = std::mem::take(&mut sub.bits);
                        self.ints = std::mem::take(&mut sub.ints);
                        self.subs.insert(k, sub);
                    }
                }
            }
        } else if self.p.text_calls.get(&k).is_some_and(|c| c.enable.is_some()) {
            // A text block under EN = FALSE: its body does not run, but its clock (and
            // the runtime's) runs on: a scan of its program with its EN bit FALSE.
            self.text_call(k, &names, &values, false);
        }
        if self.p.int_block(k).is_none() {
            // A function's `_TMP_…_ENO` (an integer one's is written by `int_exec`).
            self.set_hidden(k, "ENO", en);
        }
        self.edges.insert((k, "ENO".into()), en);
        self.in_progress.remove(&k);
        self.called.insert(k);
        en
    }

    /// The inputs the instance at `k` keeps, which a call writes whatever its EN (matiec
    /// writes them, then the body returns at once where EN is FALSE): SR's and RS's
    /// set and reset, an inlined user block's inputs (an integer one takes the value
    /// wired to its pin).
    fn kept_inputs(
        &mut self,
        k: usize,
        (std, en): (Option<Std>, bool),
        names: &[PinIn],
        values: &BTreeMap<String, bool>,
    ) {
        let get = |n: &str| values.get(n).copied().unwrap_or(false);
        if let Some((set, reset)) = std.and_then(Std::set_reset) {
            self.set_hidden(k, set, get(set));
            self.set_hidden(k, reset, get(reset));
        }
        // A user block whose EN has no ENO of its own to run under is not run.
        let modelled = en || self.p.hidden_name(k, "ENO").is_some();
        if std.is_some() || !self.subs.contains_key(&k) || !modelled {
            return;
        }
        for (n, v) in values {
            if let Some(var) = self.p.sub_var(k, n, false) {
                self.bits.insert(var.to_string(), *v);
            }
        }
        for pin in names {
            let n = pin.name.to_ascii_uppercase();
            if let Some(var) = self.p.sub_int_input(k, &n).map(str::to_string) {
                self.int_assign(&var, pin);
                if let Some(range) = self.p.sub_int_range(k, &n) {
                    self.subrange_check(&var, range);
                }
            }
        }
    }

    /// Whether an output variable fed by `input` is written: Beremiz's `PLCGenerator.py`
    /// (`GetUsedEno`) writes `IF <ENO> THEN x := …; END_IF;` when its one wire comes
    /// straight from a block whose `EN` has a wire.
    fn eno_allows(&mut self, input: &PinIn) -> bool {
        let [c] = input.conns.as_slice() else { return true };
        let Some(&j) = self.p.index.get(&c.from) else { return true };
        let wired = match self.p.obj(j).map(|o| &o.kind) {
            Some(ObjKind::Block { inputs, .. }) => {
                inputs.iter().any(|p| p.name.eq_ignore_ascii_case("EN") && !p.conns.is_empty())
            }
            _ => false,
        };
        !wired || self.output(j, "ENO")
    }

    fn statement(&mut self, k: usize) {
        let Some(o) = self.p.obj(k).cloned() else { return };
        if super::unconnected(&o.kind) {
            return;
        }
        let int_target = match self.p.operands.get(&k) {
            Some(Operand::Other(n)) => {
                self.p.vars.get(&n.to_ascii_uppercase()).map(|v| v.name.clone())
            }
            _ => None,
        }
        .filter(|n| self.ints.contains_key(n));
        let time_target = match self.p.operands.get(&k) {
            Some(Operand::Other(n)) => {
                self.p.vars.get(&n.to_ascii_uppercase()).map(|v| v.name.clone())
            }
            _ => None,
        }
        .filter(|n| self.times.contains_key(n));
        match &o.kind {
            ObjKind::OutVar { input, .. } | ObjKind::InOutVar { input, .. }
                if let Some(target) = &time_target =>
            {
                let _ = self.pin_power(input);
                if self.eno_allows(input) {
                    let v = self.time_written(input);
                    self.times.insert(target.clone(), v);
                }
            }
            ObjKind::OutVar { input, .. } | ObjKind::InOutVar { input, .. }
                if let Some(target) = &int_target =>
            {
                let _ = self.pin_power(input);
                if self.eno_allows(input) {
                    self.int_assign(target, input);
                }
            }
            ObjKind::Coil { input, negated, storage, edge, .. }
            | ObjKind::OutVar { input, negated, storage, edge, .. } => {
                let _ = self.pin_power(input);
                let power = self.pin_power(input);
                let coil = matches!(o.kind, ObjKind::Coil { .. });
                if let Some(Operand::Bool(name)) = self.p.operands.get(&k).cloned()
                    && (coil || self.eno_allows(input))
                {
                    let power = self.trigger(k, "COIL", *edge, power);
                    let old = self.bit(&name);
                    let new = match (negated, storage) {
                        (true, _) => !power,
                        (_, Storage::Set) => old || power,
                        (_, Storage::Reset) => old && !power,
                        _ => power,
                    };
                    self.bits.insert(name, new);
                }
            }
            ObjKind::InOutVar { input, .. } => {
                let _ = self.pin_power(input);
                let power = self.pin_power(input);
                if let Some(Operand::Bool(name)) = self.p.operands.get(&k).cloned()
                    && self.eno_allows(input)
                {
                    self.bits.insert(name, power);
                }
            }
            ObjKind::Block { .. } => {
                self.call(k);
            }
            ObjKind::Connector { input, .. } => {
                let _ = self.pin_power(input);
            }
            _ => {}
        }
    }
}
