//! Reference scan-cycle simulator: runs an [`LdProgram`] the way LDmicro's generated code does (§6 of `shared/formats/ldmicro.md`).
//!
//! This is an independent, executable statement of the semantics, used to test
//! the rung compiler and the examples. One [`Simulator::step`] is one scan:
//!
//! * `$mcr` is set at the start of the scan; each rung starts with power `$mcr`;
//! * rungs run top to bottom; a coil written in rung *k* is seen by later
//!   elements of the same scan, earlier rungs see it next scan;
//! * series: left to right, and elements after a false still execute with input
//!   false (a plain coil writes 0, a TON resets, a TOF times, an OSR updates);
//! * parallel: every branch runs, in order, with the same input; the output is
//!   the OR; side effects of earlier branches are visible to later ones;
//! * comment rungs are skipped (orig: a rung that is exactly one COMMENT; new:
//!   any rung whose first element is a COMMENT).
//!
//! Modelled exactly: CONTACTS, COIL (plain, negated, set, reset, toggle), SHORT,
//! OPEN, PLACEHOLDER (as OPEN), COMMENT (as a wire), MASTER_RELAY, TON, TOF, RTO,
//! RTL (§6.3 scan arithmetic, `P = floor(delay/cycle) + adjust`, TOF starting at
//! `P`: new sets it before the first scan, orig as the first TOF of the name runs,
//! per its `intcode.cpp`; a variable delay is `P` scans; a zero cycle makes timers never expire),
//! OSR, OSF, ODR, CTU/CTD/CTC (orig semantics for `LDmicro0.1`/headerless files,
//! new semantics otherwise; CTR always new), RES, EQU…LEQ, MOVE and
//! ADD/SUB/MUL/DIV with two's-complement wrap to the destination's size (orig: 16 bits;
//! new: the `VAR LIST`'s 1 to 4 bytes, a counter's and a timer's as LDmicro sizes them,
//! 2 by default; comparisons of the values as stored), the peripheral reads READ_ADC,
//! UART_RECV, the UART's status contacts and PERSIST's load from EEPROM, whose values
//! and flags are free integer inputs given in `step`'s input map ([`super::readings`]
//! names them), and the peripheral writes that pass their input (SET_PWM, I2C, SPI,
//! segments, BUS: `ldmicro::PASS_THROUGH`).
//!
//! THI, TLO and TCY count their accumulator with their state bits as `intcode.cpp`
//! does; bit operations run as LDmicro's AVR code runs them (see `bit_op`).
//!
//! Everything else (ODF, OSC, the other integer, peripheral and
//! text elements, division by zero) is **not modelled**: the simulator keeps a
//! best guess (the output follows the input; written values are left unchanged)
//! and marks what it affects as *unknown*. Unknown-ness propagates: a contact on
//! an unknown bit gives unknown power, a coil written with unknown power becomes
//! unknown, and so on. [`Simulator::is_known`] tells whether a value is exact;
//! [`Simulator::unmodelled`] lists the keywords met.
//!
//! Control flow (GOTO, GOSUB, SUBPROG/ENDSUB, RETURN, LOCK, SLEEP) changes which
//! rungs run, and the format note does not pin down how (label scope, jumps into
//! or out of subroutines). The simulator does not guess: from the first scan of a
//! program that contains any of them, **no** value is exact ([`Simulator::is_known`]
//! is false for every name). `LABEL` alone is a wire.

mod bits_and_pulses;
mod reads;
mod replay;

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::sync::Arc;

pub use replay::RunRecord;

use super::ldmicro::{
    Circuit, CoilKind, CompareOp, CounterEdge, CounterKind, EdgeKind, Element, ElementKind,
    LdProgram, MathOp, Operand, Rung, TimerDelay, TimerKind,
};

/// Power flowing through a rung: its value, and whether that value is exact.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Pow {
    on: bool,
    sure: bool,
}

impl Pow {
    const OFF: Pow = Pow { on: false, sure: true };
    /// `self ∧ v` where `v` is a condition with exactness `vs`.
    fn and(self, v: bool, vs: bool) -> Pow {
        Pow { on: self.on && v, sure: (self.sure && !self.on) || (vs && !v) || (self.sure && vs) }
    }
    fn or(self, o: Pow) -> Pow {
        Pow { on: self.on || o.on, sure: (self.sure && (o.sure || self.on)) || (o.sure && o.on) }
    }
    fn unknown(self) -> Pow {
        Pow { on: self.on, sure: false }
    }
}

/// Whether LDmicro skips a rung (ldmicro.md §4, COMMENT): orig skips a rung that is
/// exactly one COMMENT, new any rung whose first element is a COMMENT. "First element"
/// is the first item of the rung's top-level series, as the editor builds rungs.
fn skipped(rung: &Rung, orig: bool) -> bool {
    let Circuit::Series(items) = &rung.body else { return false };
    let comment = matches!(items.first(), Some(Circuit::Element(e)) if matches!(e.kind, ElementKind::Comment(_)));
    comment && (!orig || items.len() == 1)
}

fn wrap16(v: i64) -> i64 {
    i64::from(v as i16)
}

/// `v` as an integer of `bytes` bytes keeps it: its low bytes, sign-extended.
fn wrap_bytes(v: i64, bytes: u32) -> i64 {
    let shift = 64 - 8 * bytes.clamp(1, 4);
    (v << shift) >> shift
}

/// The bytes of `byteNeeded(v)` (LDmicro's `compilercommon.cpp`).
fn byte_needed(v: i64) -> u32 {
    [1u32, 2, 3, 4].into_iter().find(|b| wrap_bytes(v, *b) == v).unwrap_or(4)
}

/// A running LDmicro program: every bit, integer and hidden edge memory.
#[derive(Clone, Debug)]
pub struct Simulator {
    rungs: Vec<Arc<Rung>>,
    orig: bool,
    comment_rungs: Vec<bool>,
    cycle_us: u64,
    bits: HashMap<String, bool>,
    ints: BTreeMap<String, i64>,
    /// Per element (in execution order): edge memory and whether it is exact.
    hidden: Vec<(bool, bool)>,
    counter_init: BTreeMap<String, Operand>,
    /// orig: the TOF names whose "antiglitch" bit is set (`$T_antiglitch` of LDmicro
    /// 2.x's `intcode.cpp`): the first TOF of a name to run loads `T := P` once.
    antiglitch: BTreeSet<String>,
    unknown: BTreeSet<String>,
    unmodelled: BTreeSet<String>,
    mcr: Pow,
    scans: u64,
    /// The program contains control flow: which rungs run is not modelled.
    control_flow: bool,
    /// The peripheral reads, by element index: what the outside world gives them.
    readings: BTreeMap<usize, super::Reading>,
    /// new: the bytes LDmicro stores each integer in, when not 2 (ldmicro.md §5).
    sizes: BTreeMap<String, u32>,
    /// The target is an AVR (`MICRO=Atmel AVR …`), whose code the bit operations follow.
    avr: bool,
    /// Whether the target is an ARM (`MICRO=St ARM …`), which runs LDmicro's C code only.
    arm: bool,
    /// THI, TLO and TCY's state bits (`$once_…` of `intcode.cpp`), integers 0 or 1 by
    /// the names [`super::timer_bits`] gives them.
    timer_bits: BTreeMap<(usize, u8), String>,
    /// The rungs run from a recorded run rather than executed
    /// ([`LdProgram::slice_near`](super::LdProgram::slice_near)).
    replay: Option<replay::Replay>,
}

/// Elements that change which rungs run or stop the scan (ldmicro.md §4, last table).
const CONTROL_FLOW: &[&str] = &["GOTO", "GOSUB", "SUBPROG", "ENDSUB", "RETURN", "LOCK", "SLEEP"];

impl Simulator {
    /// A simulator at power-up: every bit and integer 0, except, for new-semantics
    /// files, TOF counts (`P`, the last TOF of a name wins) and counters with a literal
    /// `init`; an orig TOF loads its count `P` when the first TOF of its name runs.
    pub fn new(program: &LdProgram) -> Simulator {
        let orig = program.version.is_orig();
        let mut sim = Simulator {
            rungs: program.rungs.clone(),
            orig,
            comment_rungs: program.rungs.iter().map(|r| skipped(r, orig)).collect(),
            cycle_us: program.cycle_us,
            bits: program.signals().into_iter().map(|s| (s, false)).collect(),
            ints: BTreeMap::new(),
            hidden: vec![(false, true); program.elements().count()],
            counter_init: BTreeMap::new(),
            antiglitch: BTreeSet::new(),
            unknown: BTreeSet::new(),
            unmodelled: BTreeSet::new(),
            mcr: Pow { on: true, sure: true },
            scans: 0,
            control_flow: false,
            readings: super::readings(program),
            sizes: if orig { BTreeMap::new() } else { program.var_bytes.clone() },
            avr: program.micro.as_deref().is_some_and(|m| m.starts_with("Atmel AVR")),
            arm: program.micro.as_deref().is_some_and(|m| m.starts_with("St ARM")),
            timer_bits: super::timer_bits(program),
            replay: None,
        };
        // Only the rungs that run: a comment rung's timers and counters do not initialise
        // anything, and its control flow never executes.
        let live = program.rungs.iter().filter(|r| !skipped(r, orig));
        for e in live.flat_map(|r| r.elements()) {
            // new sizes a timer's count for its period (`CalcDelay`: `byteNeeded` of
            // delay/cycle) and a counter for its literal start value and limit
            // (`intcode.cpp`, the counters' `SetSizeOfVar`).
            match &e.kind {
                ElementKind::Timer { name, delay: TimerDelay::Micros(d), .. } if !orig => {
                    let n = d.checked_div(sim.cycle_us).unwrap_or(0);
                    sim.sizes.insert(name.clone(), byte_needed(i64::try_from(n).unwrap_or(0)));
                }
                ElementKind::Counter {
                    name,
                    init: Operand::Literal(i),
                    limit: Operand::Literal(l),
                    ..
                } if !orig => {
                    sim.sizes.insert(name.clone(), byte_needed(*i).max(byte_needed(*l)));
                }
                _ => {}
            }
            match &e.kind {
                ElementKind::Other { keyword, .. } if CONTROL_FLOW.contains(&keyword.as_str()) => {
                    sim.control_flow = true;
                    sim.unmodelled.insert(keyword.clone());
                }
                // new initialises a TOF's count before the first scan (`InitVarsCircuit`);
                // orig loads it as the TOF first runs (see `timer`).
                ElementKind::Timer { kind: TimerKind::Tof, name, delay, adjust, .. } if !orig => {
                    let (p, _) = sim.period(delay, *adjust);
                    sim.ints.insert(name.clone(), p);
                }
                ElementKind::Counter { name, init, .. } if !orig => {
                    sim.counter_init.insert(name.clone(), init.clone());
                    if let Operand::Literal(v) = init {
                        sim.ints.insert(name.clone(), *v);
                    }
                }
                _ => {}
            }
        }
        sim
    }

    /// Runs one scan. `inputs` gives input bits (normally the `X…` names); they
    /// are written before the first rung and are constant during the scan unless
    /// the program itself writes them. Names not given keep their previous value.
    pub fn step(&mut self, inputs: &BTreeMap<String, bool>) {
        self.scan(inputs, &mut |_, _| {});
    }

    /// [`step`](Self::step), `after` called after each rung with its index.
    fn scan(&mut self, inputs: &BTreeMap<String, bool>, after: &mut dyn FnMut(&Simulator, usize)) {
        for (name, value) in inputs {
            match self.bits.get_mut(name) {
                Some(b) => *b = *value,
                None => {
                    self.bits.insert(name.clone(), *value);
                }
            }
            self.unknown.remove(name);
        }
        // A peripheral read's value is a free integer input given, like every integer
        // input, as the bits `NAME_b0`, `NAME_b1`, … of its type (0 when absent): an
        // unsigned reading of the ADC's resolution or of one byte, or 16 bits.
        let readings: Vec<super::Reading> = self.readings.values().cloned().collect();
        for r in readings {
            let bit = |name: &str, k: u32| inputs.get(&format!("{name}_b{k}")).copied();
            let value = (0..r.ty.bits)
                .fold(0i64, |v, k| v | i64::from(bit(&r.value, k) == Some(true)) << k);
            self.set_int(&r.value, r.ty.wrap(value), true);
            if let Some(got) = &r.arrived {
                self.set_int(got, i64::from(bit(got, 0) == Some(true)), true);
            }
        }
        if self.scans == 0 && !self.orig {
            // New counters copy a variable `init` on the first scan.
            let inits: Vec<(String, Operand)> = self
                .counter_init
                .iter()
                .filter(|(_, op)| matches!(op, Operand::Var(_)))
                .map(|(n, op)| (n.clone(), op.clone()))
                .collect();
            for (name, op) in inits {
                let (v, s) = self.value(&op);
                self.set_int(&name, self.wrap(&name, v), s);
            }
        }
        self.mcr = Pow { on: true, sure: true };
        let rungs = std::mem::take(&mut self.rungs);
        let mut idx = 0;
        for (i, (rung, &skip)) in rungs.iter().zip(&self.comment_rungs.clone()).enumerate() {
            let replayed = self.replay.as_ref().and_then(|r| r.rung(i));
            if skip || replayed.is_some() {
                idx += rung.elements().len();
                if let Some(k) = replayed {
                    self.replay_rung(k);
                }
            } else {
                let power = self.mcr;
                self.circuit(&rung.body, power, &mut idx);
            }
            after(self, i);
        }
        self.rungs = rungs;
        self.scans += 1;
    }

    /// The value of a bit (false if never written).
    pub fn bit(&self, name: &str) -> bool {
        self.bits.get(name).copied().unwrap_or(false)
    }

    /// The value of an integer variable, timer count or counter (0 if never written).
    pub fn int(&self, name: &str) -> i64 {
        self.ints.get(name).copied().unwrap_or(0)
    }

    /// How many scans have run.
    pub fn scans(&self) -> u64 {
        self.scans
    }

    /// The hidden edge memory of the `k`-th element of the program (file order): the
    /// power an OSR, OSF, ODR or toggle coil saw at the last scan (a best guess where
    /// that power is not exact, like every bit).
    pub fn edge_memory(&self, k: usize) -> Option<bool> {
        self.hidden.get(k).map(|(on, _)| *on)
    }

    /// Whether the run can tell `input` held at 0 from `input` never given: it is a
    /// name of the program's contacts and coils, or one given before, or its value is
    /// not exact. Any other name reads 0 and is exact either way.
    pub fn reads(&self, input: &str) -> bool {
        self.bits.contains_key(input) || self.unknown.contains(input)
    }

    /// Every name [`reads`](Self::reads) holds of.
    pub fn read_names(&self) -> Vec<&str> {
        self.bits.keys().chain(&self.unknown).map(String::as_str).collect()
    }

    /// Before the first scan: every bit, hidden edge memory and integer of `state`
    /// instead of its power-up value. `false` (nothing changed) after the first scan or
    /// when an edge memory's index is not an element's.
    pub fn start_from(&mut self, state: &crate::program::any_state::StartState) -> bool {
        if self.scans > 0 || state.edges.keys().any(|k| *k >= self.hidden.len()) {
            return false;
        }
        for (n, v) in &state.bits {
            self.bits.insert(n.clone(), *v);
        }
        for (&k, &v) in &state.edges {
            self.hidden[k].0 = v;
        }
        for (n, v) in &state.ints {
            self.ints.insert(n.clone(), *v);
        }
        true
    }

    /// Every bit: the program's contact and coil names and every input given so far, in
    /// name order (a copy).
    pub fn bits(&self) -> BTreeMap<String, bool> {
        self.bits.iter().map(|(n, v)| (n.clone(), *v)).collect()
    }

    /// Whether the current value of `name` (bit or integer) is exact, i.e. not
    /// influenced by an element the simulator does not model.
    pub fn is_known(&self, name: &str) -> bool {
        !self.control_flow && !self.unknown.contains(name)
    }

    /// Whether the program contains control flow (GOTO, GOSUB, …), which the simulator
    /// does not model: then no value is exact.
    pub fn has_control_flow(&self) -> bool {
        self.control_flow
    }

    /// The names whose values are not exact (see the module documentation).
    pub fn unknown(&self) -> &BTreeSet<String> {
        &self.unknown
    }

    /// The keywords of the elements met that the simulator does not model.
    pub fn unmodelled(&self) -> &BTreeSet<String> {
        &self.unmodelled
    }

    fn mark(&mut self, name: &str, sure: bool) {
        if sure {
            self.unknown.remove(name);
        } else {
            if !self.unknown.contains(name) {
                self.unknown.insert(name.to_string());
            }
        }
    }

    fn set_bit(&mut self, name: &str, v: bool, sure: bool) {
        match self.bits.get_mut(name) {
            Some(b) => *b = v,
            None => {
                self.bits.insert(name.to_string(), v);
            }
        }
        self.mark(name, sure);
    }

    fn set_int(&mut self, name: &str, v: i64, sure: bool) {
        match self.ints.get_mut(name) {
            Some(x) => *x = v,
            None => {
                self.ints.insert(name.to_string(), v);
            }
        }
        self.mark(name, sure);
    }

    /// `v` as the integer `name` stores it: wrapped to its size (16 bits in orig and by
    /// default), as the generated code keeps a variable's low bytes.
    fn wrap(&self, name: &str, v: i64) -> i64 {
        wrap_bytes(v, self.sizes.get(name).copied().unwrap_or(2))
    }

    fn value(&self, op: &Operand) -> (i64, bool) {
        match op {
            Operand::Literal(v) => (*v, true),
            Operand::Var(n) => (self.int(n), self.is_known(n)),
        }
    }

    /// `P` for a timer, and whether it is exact.
    fn period(&self, delay: &TimerDelay, adjust: i64) -> (i64, bool) {
        match delay {
            TimerDelay::Micros(d) => {
                let n = d
                    .checked_div(self.cycle_us)
                    .map_or(i64::MAX / 2, |n| i64::try_from(n).unwrap_or(i64::MAX / 2));
                (n.saturating_add(adjust), true)
            }
            TimerDelay::Variable(v) => (self.int(v), self.is_known(v)),
        }
    }

    fn circuit(&mut self, c: &Circuit, input: Pow, idx: &mut usize) -> Pow {
        match c {
            Circuit::Series(items) => {
                items.iter().fold(input, |p, item| self.circuit(item, p, idx))
            }
            Circuit::Parallel(branches) => {
                let mut out = Pow::OFF;
                for b in branches {
                    let o = self.circuit(b, input, idx);
                    out = out.or(o);
                }
                out
            }
            Circuit::Element(e) => {
                let k = *idx;
                *idx += 1;
                self.element(e, input, k)
            }
        }
    }

    /// Updates the hidden edge memory of element `k` with `i`; returns the old value.
    fn remember(&mut self, k: usize, i: Pow) -> Pow {
        let slot = self.hidden.get_mut(k);
        match slot {
            Some(slot) => {
                let old = Pow { on: slot.0, sure: slot.1 };
                *slot = (i.on, i.sure);
                old
            }
            None => Pow::OFF.unknown(),
        }
    }

    fn element(&mut self, e: &Element, i: Pow, k: usize) -> Pow {
        match &e.kind {
            ElementKind::Contacts { name, negated } => {
                let v = self.bit(name) != *negated;
                i.and(v, self.is_known(name))
            }
            ElementKind::Coil { name, kind } => {
                match kind {
                    CoilKind::Normal => self.set_bit(name, i.on, i.sure),
                    CoilKind::Negated => self.set_bit(name, !i.on, i.sure),
                    CoilKind::Set | CoilKind::Reset => {
                        let target = *kind == CoilKind::Set;
                        if i.on {
                            self.set_bit(name, target, i.sure);
                        } else if !i.sure && self.bit(name) != target {
                            self.mark(name, false);
                        }
                    }
                    CoilKind::Toggle => {
                        let prev = self.remember(k, i);
                        let trig = i.on && !prev.on;
                        let sure = i.sure && prev.sure && self.is_known(name);
                        let v = self.bit(name) != trig;
                        self.set_bit(name, v, sure);
                    }
                }
                i
            }
            ElementKind::Short | ElementKind::Comment(_) => i,
            ElementKind::Open | ElementKind::Placeholder => Pow::OFF,
            ElementKind::MasterRelay => {
                self.mcr = if self.mcr.on {
                    Pow { on: i.on, sure: i.sure && self.mcr.sure }
                } else {
                    Pow { on: true, sure: self.mcr.sure }
                };
                i
            }
            ElementKind::Timer { kind, name, delay, adjust, .. } => {
                self.timer(*kind, name, delay, *adjust, i, k)
            }
            ElementKind::Edge { kind } => match kind {
                EdgeKind::Osr | EdgeKind::Osf | EdgeKind::Odr => {
                    let prev = self.remember(k, i);
                    let sure = i.sure && prev.sure;
                    let on = match kind {
                        EdgeKind::Osr => i.on && !prev.on,
                        EdgeKind::Osf => !i.on && prev.on,
                        _ => !i.on || prev.on,
                    };
                    Pow { on, sure }
                }
                EdgeKind::Odf | EdgeKind::Osc => {
                    self.unmodelled.insert(e.kind.keyword().to_string());
                    i.unknown()
                }
            },
            ElementKind::Counter { kind, name, limit, init, edge } => {
                let prev = self.remember(k, i);
                let trig = match edge {
                    CounterEdge::Rising => i.on && !prev.on,
                    CounterEdge::Falling => !i.on && prev.on,
                    CounterEdge::High => i.on,
                    CounterEdge::Low => !i.on,
                };
                let trig_sure = i.sure && prev.sure;
                let (max, max_sure) = self.value(limit);
                let (init, init_sure) = if self.orig { (0, true) } else { self.value(init) };
                let c0 = self.int(name);
                let c_sure = self.is_known(name) && trig_sure && max_sure;
                let (c, on) = match (kind, self.orig) {
                    (CounterKind::Ctu, true) => {
                        let c = if trig { wrap16(c0.wrapping_add(1)) } else { c0 };
                        (c, c >= max)
                    }
                    (CounterKind::Ctd, true) => {
                        let c = if trig { wrap16(c0.wrapping_sub(1)) } else { c0 };
                        (c, c >= max)
                    }
                    (CounterKind::Ctc, true) => {
                        let mut c = c0;
                        if trig {
                            c = wrap16(c.wrapping_add(1));
                            if c > max {
                                c = 0;
                            }
                        }
                        (c, i.on)
                    }
                    (CounterKind::Ctu, false) => {
                        let c = if trig && c0 < max { c0.wrapping_add(1) } else { c0 };
                        (c, c >= max)
                    }
                    (CounterKind::Ctd, false) => {
                        let c = if trig && c0 > max { c0.wrapping_sub(1) } else { c0 };
                        (c, c > max)
                    }
                    (CounterKind::Ctc, false) => {
                        if trig {
                            let c = self.wrap(name, c0.wrapping_add(1));
                            if c > max { (init, true) } else { (c, false) }
                        } else {
                            (c0, false)
                        }
                    }
                    (CounterKind::Ctr, _) => {
                        if trig {
                            let c = self.wrap(name, c0.wrapping_sub(1));
                            if c < max { (init, true) } else { (c, false) }
                        } else {
                            (c0, false)
                        }
                    }
                };
                let sure = c_sure && init_sure;
                self.set_int(name, c, sure);
                let out_sure = if matches!((kind, self.orig), (CounterKind::Ctc, true)) {
                    i.sure
                } else {
                    sure
                };
                Pow { on, sure: out_sure }
            }
            ElementKind::Res { name } => {
                if i.on {
                    let (v, s) = match self.counter_init.get(name).cloned() {
                        Some(op) if !self.orig => self.value(&op),
                        _ => (0, true),
                    };
                    self.set_int(name, v, s && i.sure);
                } else if !i.sure {
                    self.mark(name, false);
                }
                i
            }
            ElementKind::Compare { op, a, b } => {
                // orig: a literal beyond 16 bits goes through a temporary whose size
                // LDmicro chooses (`VarFromExpr`): 0xffff may read as -1 or as 65535.
                // new compares the sign-extended values (`NEW_CMP`): exactly.
                let wide = self.orig && (a.beyond_16_bits() || b.beyond_16_bits());
                let (a, a_sure) = self.value(a);
                let (b, b_sure) = self.value(b);
                let v = match op {
                    CompareOp::Equ => a == b,
                    CompareOp::Neq => a != b,
                    CompareOp::Grt => a > b,
                    CompareOp::Geq => a >= b,
                    CompareOp::Les => a < b,
                    CompareOp::Leq => a <= b,
                };
                i.and(v, a_sure && b_sure && !wide)
            }
            ElementKind::Move { dest, src } => {
                let (v, s) = self.value(src);
                self.assign(dest, i, self.wrap(dest, v), s);
                i
            }
            ElementKind::Math { op, dest, a, b } => {
                let wide =
                    self.orig && *op == MathOp::Div && (a.beyond_16_bits() || b.beyond_16_bits());
                let (a, a_sure) = self.value(a);
                let (b, b_sure) = self.value(b);
                let r = match op {
                    MathOp::Add => Some(a.wrapping_add(b)),
                    MathOp::Sub => Some(a.wrapping_sub(b)),
                    MathOp::Mul => Some(a.wrapping_mul(b)),
                    MathOp::Div => (b != 0).then(|| a.wrapping_div(b)),
                };
                match r {
                    Some(r) => self.assign(dest, i, self.wrap(dest, r), a_sure && b_sure && !wide),
                    None => {
                        // Division by zero: undefined in LDmicro.
                        self.unmodelled.insert("DIV by zero".into());
                        if i.on || !i.sure {
                            self.mark(dest, false);
                        }
                    }
                }
                i
            }
            // A label only marks a place to jump to.
            ElementKind::Other { keyword, .. } if keyword == "LABEL" => i,
            // ldmicro.md §4: on the rising edge of `i`, `name{k} := name{k-1}` for
            // k = stages-1 down to 1 (`name0` is the program's to set).
            ElementKind::Other { keyword, args } if keyword == "SHIFT_REGISTER" => {
                let prev = self.remember(k, i);
                let stages = args.get(1).and_then(|n| n.parse::<usize>().ok()).unwrap_or(0);
                let (name, edge) = (args.first().cloned().unwrap_or_default(), i.on && !prev.on);
                let edge_sure = i.sure && prev.sure;
                for s in (1..stages).rev() {
                    let (from, to) = (format!("{name}{}", s - 1), format!("{name}{s}"));
                    let (v, v_sure) = (self.int(&from), self.is_known(&from));
                    if edge {
                        self.set_int(&to, self.wrap(&to, v), v_sure && edge_sure);
                    } else if !edge_sure {
                        self.mark(&to, false);
                    }
                }
                i
            }
            ElementKind::Other { .. } if self.readings.contains_key(&k) => {
                let r = self.readings[&k].clone();
                self.read(&r, i)
            }
            ElementKind::Other { keyword, args } if self.bit_op(keyword, args).is_some() => {
                if let Some((dest, v, s)) = self.bit_op(keyword, args) {
                    self.assign(&dest, i, v, s);
                }
                i
            }
            // A PERSIST that names no variable (every other one is a reading above):
            // saving to EEPROM changes nothing here.
            ElementKind::Other { keyword, .. } if keyword == "PERSIST" => i,
            ElementKind::Other { keyword, args } => {
                self.unmodelled.insert(keyword.clone());
                // Whatever it writes is not known: every name among its arguments.
                for n in args.iter().filter(|a| a.starts_with(|c: char| c.is_ascii_alphabetic())) {
                    if i.on || !i.sure {
                        self.unknown.insert(n.to_string());
                    }
                }
                if crate::ladder::ldmicro::PASS_THROUGH.contains(&keyword.as_str()) {
                    i
                } else {
                    i.unknown()
                }
            }
        }
    }

    /// `if i { dest := v }`, tracking exactness.
    fn assign(&mut self, dest: &str, i: Pow, v: i64, v_sure: bool) {
        if i.on {
            self.set_int(dest, v, v_sure && i.sure);
        } else if !i.sure {
            self.mark(dest, false);
        }
    }

    fn timer(
        &mut self,
        kind: TimerKind,
        name: &str,
        delay: &TimerDelay,
        adjust: i64,
        i: Pow,
        k: usize,
    ) -> Pow {
        let (p, p_sure) = self.period(delay, adjust);
        if kind == TimerKind::Tof && self.orig && self.antiglitch.insert(name.to_string()) {
            self.set_int(name, p, p_sure);
        }
        let t = self.int(name);
        let t_sure = self.is_known(name);
        let (t, on, sure) = match kind {
            TimerKind::Ton => {
                if i.on {
                    if t < p { (t.wrapping_add(1), false, t_sure) } else { (t, true, t_sure) }
                } else {
                    (0, false, true)
                }
            }
            TimerKind::Tof => {
                if !i.on {
                    if t < p { (t.wrapping_add(1), true, t_sure) } else { (t, false, t_sure) }
                } else {
                    (0, true, true)
                }
            }
            TimerKind::Rto => {
                if t < p {
                    (if i.on { t.wrapping_add(1) } else { t }, false, t_sure)
                } else {
                    (t, true, t_sure)
                }
            }
            TimerKind::Rtl => {
                if t < p {
                    (if i.on { t } else { t.wrapping_add(1) }, false, t_sure)
                } else {
                    (t, true, t_sure)
                }
            }
            TimerKind::Thi | TimerKind::Tlo | TimerKind::Tcy => {
                return self.pulse_timer(kind, name, (p, p_sure), i, k);
            }
        };
        let sure = sure && i.sure && p_sure;
        self.set_int(name, t, sure);
        Pow { on, sure }
    }
}

/// Runs `program` from power-up over `input_trace` (one map of inputs per scan)
/// and returns every bit after each scan.
pub fn run(
    program: &LdProgram,
    input_trace: &[BTreeMap<String, bool>],
) -> Vec<BTreeMap<String, bool>> {
    let mut sim = Simulator::new(program);
    input_trace
        .iter()
        .map(|inputs| {
            sim.step(inputs);
            sim.bits()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diag::Sources;
    use crate::ladder::read_ldmicro;

    fn program(header: &str, rungs: &str) -> LdProgram {
        let mut s = Sources::new();
        let f = s.add("t.ld", format!("{header}\nCYCLE=10000\nPROGRAM\n{rungs}"));
        match read_ldmicro(&s, f) {
            Ok(p) => p,
            Err(e) => panic!("{e:?}"),
        }
    }

    fn inputs(pairs: &[(&str, bool)]) -> BTreeMap<String, bool> {
        pairs.iter().map(|(n, v)| (n.to_string(), *v)).collect()
    }

    /// The scan (1-based) on which `out` first becomes true with `x` held true.
    fn first_true(p: &LdProgram, x: &str, out: &str, limit: u64) -> Option<u64> {
        let mut sim = Simulator::new(p);
        let on = inputs(&[(x, true)]);
        (1..=limit).find(|_| {
            sim.step(&on);
            sim.bit(out)
        })
    }

    const TON: &str = "RUNG\nCONTACTS Xa 0\nTON Tt 50000\nCOIL Yq 0 0 0\nEND\n";

    #[test]
    fn ton_fires_on_scan_p_plus_one() {
        // 0.2: adjust 0, N = 50000/10000 = 5 = P, so the 6th consecutive true scan.
        assert_eq!(first_true(&program("LDmicro0.2", TON), "Xa", "Yq", 20), Some(6));
        // 0.1: adjust -1, P = 4: the 5th scan.
        assert_eq!(first_true(&program("LDmicro0.1", TON), "Xa", "Yq", 20), Some(5));
        // An explicit adjust field wins over the header default.
        let p = program("LDmicro0.1", "RUNG\nCONTACTS Xa 0\nTON Tt 50000 0\nCOIL Yq 0 0 0\nEND\n");
        assert_eq!(first_true(&p, "Xa", "Yq", 20), Some(6));
    }

    #[test]
    fn ton_resets_when_the_input_drops() {
        let p = program("LDmicro0.2", TON);
        let mut sim = Simulator::new(&p);
        for _ in 0..5 {
            sim.step(&inputs(&[("Xa", true)]));
        }
        assert!(!sim.bit("Yq"));
        assert_eq!(sim.int("Tt"), 5);
        sim.step(&inputs(&[("Xa", false)]));
        assert_eq!(sim.int("Tt"), 0);
        for _ in 0..5 {
            sim.step(&inputs(&[("Xa", true)]));
            assert!(!sim.bit("Yq"));
        }
        sim.step(&inputs(&[("Xa", true)]));
        assert!(sim.bit("Yq"));
        sim.step(&inputs(&[("Xa", false)]));
        assert!(!sim.bit("Yq"), "a TON output falls with its input");
    }

    #[test]
    fn tof_starts_false_and_holds_p_scans() {
        let p = program("LDmicro0.2", "RUNG\nCONTACTS Xa 0\nTOF Tt 30000\nCOIL Yq 0 0 0\nEND\n");
        let mut sim = Simulator::new(&p);
        assert_eq!(sim.int("Tt"), 3, "TOF count starts at P");
        sim.step(&inputs(&[("Xa", false)]));
        assert!(!sim.bit("Yq"), "a TOF does not start true");
        sim.step(&inputs(&[("Xa", true)]));
        assert!(sim.bit("Yq"));
        // P = 3: true for 3 more scans after the fall, false on the 4th.
        for _ in 0..3 {
            sim.step(&inputs(&[("Xa", false)]));
            assert!(sim.bit("Yq"));
        }
        sim.step(&inputs(&[("Xa", false)]));
        assert!(!sim.bit("Yq"));
        assert_eq!(sim.scans(), 6);
    }

    #[test]
    fn seal_in_behaves_as_reset_dominant_rs() {
        let p = program(
            "LDmicro0.1",
            "RUNG\nPARALLEL\nCONTACTS XS 0\nCONTACTS Y 0\nEND\nCONTACTS XR 1\nCOIL Y 0 0 0\nEND\n",
        );
        let trace: Vec<_> = [
            (false, false, false),
            (true, false, true),
            (false, false, true),
            (false, true, false),
            (false, false, false),
            (true, true, false),
            (true, false, true),
            (false, false, true),
        ]
        .iter()
        .map(|&(s, r, _)| inputs(&[("XS", s), ("XR", r)]))
        .collect();
        let out = run(&p, &trace);
        let expected = [false, true, true, false, false, false, true, true];
        let got: Vec<bool> = out.iter().map(|b| b["Y"]).collect();
        assert_eq!(got, expected);
    }

    #[test]
    fn set_and_reset_coils() {
        let p = program(
            "LDmicro0.1",
            "RUNG\nCONTACTS XS 0\nCOIL Y 0 1 0\nEND\nRUNG\nCONTACTS XR 0\nCOIL Y 0 0 1\nEND\nRUNG\nCONTACTS XN 0\nCOIL Yn 1 0 0\nEND\n",
        );
        let mut sim = Simulator::new(&p);
        sim.step(&inputs(&[("XS", true)]));
        assert!(sim.bit("Y"));
        assert!(sim.bit("Yn"), "a negated coil is true when its input is false");
        sim.step(&inputs(&[("XS", false)]));
        assert!(sim.bit("Y"), "set holds");
        sim.step(&inputs(&[("XS", true), ("XR", true)]));
        assert!(!sim.bit("Y"), "the later reset rung wins");
        sim.step(&inputs(&[("XS", false), ("XR", false), ("XN", true)]));
        assert!(!sim.bit("Y"));
        assert!(!sim.bit("Yn"));
    }

    #[test]
    fn osr_pulses_on_the_first_scan_and_on_rising_edges() {
        let p = program(
            "LDmicro0.2",
            "RUNG 1\nOSR\nCOIL Rfirst 0 0 0\nEND\nRUNG 2\nCONTACTS Xa 0\nOSR\nCOIL Rup 0 0 0\nEND\nRUNG 3\nCONTACTS Xa 0\nOSF\nCOIL Rdown 0 0 0\nEND\n",
        );
        let a = [true, true, false, true, false, false];
        let trace: Vec<_> = a.iter().map(|&v| inputs(&[("Xa", v)])).collect();
        let out = run(&p, &trace);
        let col = |n: &str| out.iter().map(|b| b[n]).collect::<Vec<_>>();
        assert_eq!(col("Rfirst"), [true, false, false, false, false, false]);
        assert_eq!(col("Rup"), [true, false, false, true, false, false]);
        assert_eq!(col("Rdown"), [false, false, true, false, true, false]);
    }

    #[test]
    fn rung_order_decides_same_scan_or_previous_scan() {
        let p = program(
            "LDmicro0.1",
            "RUNG\nCONTACTS Rlater 0\nCOIL Rearly 0 0 0\nEND\nRUNG\nCONTACTS Xa 0\nCOIL Rlater 0 0 0\nEND\nRUNG\nCONTACTS Rlater 0\nCOIL Rsame 0 0 0\nEND\n",
        );
        let mut sim = Simulator::new(&p);
        sim.step(&inputs(&[("Xa", true)]));
        assert!(sim.bit("Rlater"));
        assert!(sim.bit("Rsame"), "a later rung sees the coil in the same scan");
        assert!(!sim.bit("Rearly"), "an earlier rung sees it one scan later");
        sim.step(&inputs(&[("Xa", true)]));
        assert!(sim.bit("Rearly"));
    }

    #[test]
    fn parallel_branches_see_earlier_branches() {
        let p = program(
            "LDmicro0.2",
            "RUNG 1\nPARALLEL\nSERIES\nCONTACTS Xa 0\nCOIL R1 0 0 0\nEND\nSERIES\nCONTACTS R1 0\nCOIL R2 0 0 0\nEND\nEND\nCOIL Rout 0 0 0\nEND\n",
        );
        let mut sim = Simulator::new(&p);
        sim.step(&inputs(&[("Xa", true)]));
        assert!(sim.bit("R2"));
        assert!(sim.bit("Rout"));
    }

    #[test]
    fn elements_after_a_false_still_execute() {
        let p = program(
            "LDmicro0.2",
            "RUNG 1\nCONTACTS Xa 0\nCONTACTS Xb 0\nTON Tt 20000\nCOIL Yq 0 0 0\nEND\n",
        );
        let mut sim = Simulator::new(&p);
        sim.step(&inputs(&[("Xa", true), ("Xb", true)]));
        assert_eq!(sim.int("Tt"), 1);
        sim.step(&inputs(&[("Xa", false), ("Xb", true)]));
        assert_eq!(sim.int("Tt"), 0, "the TON ran with input false and reset");
    }

    #[test]
    fn master_relay_zone() {
        let p = program(
            "LDmicro0.1",
            "RUNG\nCONTACTS Xen 0\nMASTER_RELAY\nEND\nRUNG\nCOIL Yin 0 0 0\nEND\nRUNG\nMASTER_RELAY\nEND\nRUNG\nCOIL Yout 0 0 0\nEND\n",
        );
        let mut sim = Simulator::new(&p);
        sim.step(&inputs(&[("Xen", false)]));
        assert!(!sim.bit("Yin"));
        assert!(sim.bit("Yout"));
        sim.step(&inputs(&[("Xen", true)]));
        assert!(sim.bit("Yin"));
        assert!(sim.bit("Yout"));
    }

    #[test]
    fn counters_follow_the_header_version() {
        let rungs = "RUNG\nCONTACTS Xa 0\nCTC Cc 2\nCOIL Yc 0 0 0\nEND\nRUNG\nCONTACTS Xa 0\nCTU Cu 2\nCOIL Yu 0 0 0\nEND\n";
        let pulses: Vec<_> = (0..8).map(|k| inputs(&[("Xa", k % 2 == 0)])).collect();
        // orig: CTC passes its input; CTU counts without bound.
        let p = program("LDmicro0.1", rungs);
        let mut sim = Simulator::new(&p);
        let mut yc = Vec::new();
        for i in &pulses {
            sim.step(i);
            yc.push(sim.bit("Yc"));
        }
        assert_eq!(yc, [true, false, true, false, true, false, true, false]);
        assert_eq!(sim.int("Cu"), 4);
        assert_eq!(sim.int("Cc"), 1, "0→1→2→(3>2)0→1");
        assert!(sim.bit("Yu"));
        // new: CTC gives a one-scan carry pulse; CTU saturates.
        let p = program("LDmicro0.2", rungs);
        let mut sim = Simulator::new(&p);
        let mut yc = Vec::new();
        for i in &pulses {
            sim.step(i);
            yc.push(sim.bit("Yc"));
        }
        assert_eq!(yc, [false, false, false, false, true, false, false, false]);
        assert_eq!(sim.int("Cu"), 2);
    }

    #[test]
    fn rto_accumulates_until_res() {
        let p = program(
            "LDmicro0.2",
            "RUNG 1\nCONTACTS Xa 0\nRTO Tr 20000\nCOIL Yq 0 0 0\nEND\nRUNG 2\nCONTACTS Xr 0\nRES Tr\nEND\n",
        );
        let mut sim = Simulator::new(&p);
        for v in [true, false, true] {
            sim.step(&inputs(&[("Xa", v)]));
            assert!(!sim.bit("Yq"));
        }
        assert_eq!(sim.int("Tr"), 2, "non-consecutive true scans accumulate");
        sim.step(&inputs(&[("Xa", false)]));
        assert!(sim.bit("Yq"), "once T = P the output is on, whatever the input");
        sim.step(&inputs(&[("Xa", false)]));
        assert!(sim.bit("Yq"), "retentive: stays on with the input off");
        sim.step(&inputs(&[("Xr", true)]));
        assert_eq!(sim.int("Tr"), 0);
        sim.step(&inputs(&[("Xr", false)]));
        assert!(!sim.bit("Yq"));
    }

    #[test]
    fn integers_compare_and_wrap() {
        let p = program(
            "LDmicro0.1",
            "RUNG\nMOVE x 32767\nEND\nRUNG\nCONTACTS Xa 0\nADD x x 1\nEND\nRUNG\nLES x 0\nCOIL Yneg 0 0 0\nEND\nRUNG\nDIV y x 0\nEND\n",
        );
        let mut sim = Simulator::new(&p);
        sim.step(&inputs(&[("Xa", true)]));
        assert_eq!(sim.int("x"), -32768);
        assert!(sim.bit("Yneg"));
        assert!(sim.is_known("Yneg"));
        assert!(!sim.is_known("y"), "division by zero is undefined");
    }

    #[test]
    fn unmodelled_elements_make_their_results_unknown() {
        let p = program(
            "LDmicro0.2",
            "RUNG 1\nCONTACTS Xa 0\nODF\nCOIL Yq 0 0 0\nEND\nRUNG 2\nCONTACTS Yq 0\nCOIL Yr 0 0 0\nEND\nRUNG 3\nCONTACTS Xa 0\nCOIL Ys 0 0 0\nEND\n",
        );
        let mut sim = Simulator::new(&p);
        sim.step(&inputs(&[("Xa", true)]));
        assert!(!sim.is_known("Yq"));
        assert!(!sim.is_known("Yr"));
        assert!(sim.is_known("Ys"));
        assert!(sim.unmodelled().contains("ODF"));
    }

    #[test]
    fn control_flow_makes_every_value_unknown() {
        let p = program(
            "LDmicro0.2",
            "RUNG 1\nCONTACTS Xskip 0\nGOTO Lend\nEND\nRUNG 2\nCONTACTS Xa 0\nCOIL Yout 0 0 0\nEND\nRUNG 3\nLABEL Lend\nEND\n",
        );
        let mut sim = Simulator::new(&p);
        assert!(sim.has_control_flow());
        sim.step(&inputs(&[("Xskip", true), ("Xa", true)]));
        assert!(!sim.is_known("Yout"), "the jump may skip rung 2");
        assert!(!sim.is_known("Xa"));
        assert!(sim.unmodelled().contains("GOTO"));
        // A label alone is a wire.
        let p = program("LDmicro0.2", "RUNG 1\nCONTACTS Xa 0\nLABEL Lx\nCOIL Yq 0 0 0\nEND\n");
        let mut sim = Simulator::new(&p);
        sim.step(&inputs(&[("Xa", true)]));
        assert!(sim.bit("Yq") && sim.is_known("Yq") && !sim.has_control_flow());
    }

    #[test]
    fn a_skipped_rung_initialises_nothing() {
        // The TOF of the comment rung (P = -1) must not set the count of the live one (P = 3).
        let p = program(
            "LDmicro0.2",
            "RUNG 1\nCONTACTS Xa 0\nTOF Ta 30000\nCOIL Yq 0 0 0\nEND\nRUNG 2\nCOMMENT skipped\nTOF Ta 10000 -2\nGOTO L1\nEND\n",
        );
        let mut sim = Simulator::new(&p);
        assert_eq!(sim.int("Ta"), 3);
        assert!(!sim.has_control_flow());
        sim.step(&inputs(&[("Xa", false)]));
        assert!(!sim.bit("Yq"));
        assert!(sim.is_known("Yq"));
    }

    #[test]
    fn comment_rungs_are_skipped() {
        let p = program(
            "LDmicro0.2",
            "RUNG 1\nCOMMENT note\nCOIL Yx 0 0 0\nEND\nRUNG 2\nCONTACTS Xa 1\nCOIL Yy 0 0 0\nEND\n",
        );
        let mut sim = Simulator::new(&p);
        sim.step(&BTreeMap::new());
        assert!(!sim.bit("Yx"), "new skips a rung whose first element is a COMMENT");
        assert!(sim.bit("Yy"));
    }
}
