//! The scan model's simulator: runs a [`Program`] scan by scan, bit by bit, timers counting scans as the runtime counts them — the reference for languages without a simulator of their own, and a check of the compiler's symbolic reading of the same model.
//!
//! Values are concrete: a read sees the last write before it in the scan (the previous
//! scan's value before the first write, `0` for a bit nothing writes and the outside does
//! not drive); a one-shot compares its power with the power it saw at the previous scan
//! (`0` at power-up); a TON is on from the (P+1)-th consecutive scan with its input on, a
//! TOF stays on for P scans after its input falls, `P = floor(delay / cycle) + adjust`
//! (or `delay / cycle` with [`TimerModel::Ideal`]), and the output follows the input when
//! `P ≤ 0`. What the model leaves unconstrained (an unconstrained value, a timer with a
//! variable preset or whose accumulator another element writes) makes every bit computed
//! from it unknown ([`Simulator::is_known`]): the simulator never invents a value.

use std::collections::{BTreeMap, BTreeSet};

use super::{
    BoolExpr, EdgeKind, IntExpr, IntType, Preset, Program, Stmt, Temp, Timer, TimerModel,
    WriteKind, walk,
};

/// A value and whether the simulator knows it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct V {
    value: bool,
    known: bool,
}

/// An integer value and whether the simulator knows it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct N {
    value: i64,
    known: bool,
}

impl V {
    const ZERO: V = V { value: false, known: true };
    fn of(value: bool) -> V {
        V { value, known: true }
    }
}

/// A scan-model program running, from power-up.
#[derive(Clone, Debug)]
pub struct Simulator {
    program: std::sync::Arc<Program>,
    timers_model: TimerModel,
    /// Timer accumulators written by more than one element (not simulated).
    shared: BTreeSet<String>,
    /// Every bit at the end of the last scan.
    bits: BTreeMap<String, V>,
    /// Every integer, as it stands in the scan (its power-up value before the first write).
    ints: BTreeMap<String, N>,
    /// Per stateful element, in the order a scan meets them (every branch of an `If`
    /// included, run or not): a timer's count, a one-shot's last power.
    counts: Vec<Count>,
    memories: Vec<V>,
    /// A one-shot's memory by its index in the front end's order.
    by_index: BTreeMap<usize, V>,
    /// The one-shots' memories before the first scan where not 0 (`start_from`).
    edge_starts: BTreeMap<usize, bool>,
    // During a scan.
    current: BTreeMap<String, V>,
    temps: BTreeMap<Temp, V>,
    next_count: usize,
    next_memory: usize,
    /// The timer instances called at several places, by name: each runs as the
    /// runtime's block does, call by call.
    blocks: BTreeMap<String, Block>,
    /// The calls of those met in this scan so far, run or passed, in order.
    met: Vec<String>,
    /// The scans run so far.
    scan: u64,
    /// Whether the free integers of what the runtime leaves undefined
    /// ([`Program::undefined`]) are unknown rather than given by their bits.
    undefined_unknown: bool,
}

/// A timer's state: the count of consecutive scans that make it run (input on for a
/// TON, off for a TOF) up to its last call, whether it is known, whether that call made
/// it run, and that call's scan.
#[derive(Clone, Copy, Debug)]
struct Count {
    count: u64,
    known: bool,
    runs: bool,
    at: u64,
}

/// A timer instance called at several places: the state of the runtime's block
/// (`lib/timer.txt`): `STATE` (0 idle, 1 timing, 2 done), `PREV_IN`, the scan of its
/// `START_TIME`, `Q`, and whether they are known.
#[derive(Clone, Copy, Debug)]
struct Block {
    state: u8,
    prev_in: bool,
    start: u64,
    q: bool,
    known: bool,
}

impl Simulator {
    /// A new run of `program` from power-up, timers counted as `timers` says.
    pub fn new(program: &Program, timers: TimerModel) -> Simulator {
        Simulator {
            program: std::sync::Arc::new(program.clone()),
            timers_model: timers,
            shared: program.shared_timers(),
            bits: BTreeMap::new(),
            ints: program
                .integers
                .iter()
                .map(|(n, v)| (n.clone(), N { value: v.init, known: true }))
                .collect(),
            counts: Vec::new(),
            memories: Vec::new(),
            by_index: BTreeMap::new(),
            edge_starts: BTreeMap::new(),
            current: BTreeMap::new(),
            temps: BTreeMap::new(),
            next_count: 0,
            next_memory: 0,
            blocks: program
                .repeated_timers()
                .into_keys()
                .map(|n| (n, Block { state: 0, prev_in: false, start: 0, q: false, known: true }))
                .collect(),
            met: Vec::new(),
            scan: 0,
            undefined_unknown: false,
        }
    }

    /// From now on, the free integers of what the runtime leaves undefined (a signed
    /// overflow's value) are unknown, and so is what they decide: for comparing a run
    /// with the runtime's own, which may compute anything there.
    pub fn leave_undefined_unknown(&mut self) {
        self.undefined_unknown = true;
    }

    /// Runs one scan with these input values (inputs not given are `0`).
    pub fn step(&mut self, inputs: &BTreeMap<String, bool>) {
        self.current = std::mem::take(&mut self.bits);
        for (n, v) in inputs {
            if self.program.inputs.contains(n) {
                self.current.insert(n.clone(), V::of(*v));
            }
        }
        // An input integer is given by its bits (those not given are 0).
        for (x, var) in self.program.integers.iter().filter(|(_, v)| v.input) {
            let bits: Vec<bool> = (0..var.ty.bits)
                .map(|k| inputs.get(&Program::int_bit(x, k)).copied().unwrap_or(false))
                .collect();
            let value = super::bitvec::value_of(&bits, var.ty);
            let known = !(self.undefined_unknown && self.program.undefined.contains(x));
            self.ints.insert(x.clone(), N { value, known });
        }
        self.temps.clear();
        self.met.clear();
        self.scan += 1;
        self.next_count = 0;
        self.next_memory = 0;
        let program = self.program.clone();
        for (_, s) in program.stmts() {
            self.stmt(s, true);
        }
        self.bits = std::mem::take(&mut self.current);
    }

    /// A bit's value at the end of the last scan (`0` if unknown or never written).
    pub fn bit(&self, name: &str) -> bool {
        self.bits.get(name).is_some_and(|v| v.value)
    }

    /// Whether the simulator computes the bit or integer (it is not derived from an
    /// unconstrained value).
    pub fn is_known(&self, name: &str) -> bool {
        self.bits.get(name).is_none_or(|v| v.known) && self.ints.get(name).is_none_or(|v| v.known)
    }

    /// An integer's value at the end of the last scan (`None` if the program has no such
    /// integer).
    pub fn int(&self, name: &str) -> Option<i64> {
        self.ints.get(name).map(|v| v.value)
    }

    /// The memory of the one-shot with this index after the last scan.
    pub fn edge_memory(&self, index: usize) -> Option<bool> {
        self.by_index.get(&index).filter(|v| v.known).map(|v| v.value)
    }

    /// `known`: whether the statement's effect is known (false inside a choice whose
    /// condition is not).
    fn stmt(&mut self, s: &Stmt, known: bool) {
        match s {
            Stmt::Let { temp, value } => {
                let v = self.eval(value);
                self.temps.insert(*temp, v);
            }
            Stmt::Write { target, kind, value, .. } => {
                let v = self.eval(value);
                let old = self.read(target);
                let new = match kind {
                    WriteKind::Assign => v,
                    WriteKind::AssignNot => V { value: !v.value, known: v.known },
                    // A write without power keeps the bit; one whose power is unknown
                    // leaves it known only where it already holds what it would write.
                    WriteKind::Set | WriteKind::Reset if v.known && !v.value => old,
                    WriteKind::Set | WriteKind::Reset => {
                        let value = *kind == WriteKind::Set;
                        V { value, known: v.known || (old.known && old.value == value) }
                    }
                    WriteKind::Toggle(memory) => {
                        let last = self.memory(v, memory.index);
                        let edge = v.value && !last.value;
                        let known = v.known && last.known && old.known;
                        V { value: if edge { !old.value } else { old.value }, known }
                    }
                };
                let new = V { value: new.value, known: new.known && known };
                self.current.insert(target.clone(), new);
            }
            Stmt::If { branches, otherwise, .. } => {
                // Every condition, as the compiler reads them; the first that holds
                // chooses the branch.
                let conditions: Vec<V> = branches.iter().map(|(c, _)| self.eval(c)).collect();
                let mut known = known;
                let mut chosen = branches.len();
                for (k, c) in conditions.iter().enumerate() {
                    known &= c.known;
                    if c.value {
                        chosen = k;
                        break;
                    }
                }
                if !known {
                    // Which branch runs is not known: whatever any branch writes is not.
                    let (mut written, mut ints) = (Vec::new(), Vec::new());
                    for s in branches.iter().flat_map(|(_, b)| b).chain(otherwise) {
                        s.visit(
                            &mut |s| match s {
                                Stmt::Write { target, .. } => written.push(target.clone()),
                                Stmt::SetInt { target, .. } => ints.push(target.clone()),
                                _ => {}
                            },
                            &mut |_| {},
                        );
                    }
                    for x in written {
                        self.current.insert(x, V { value: false, known: false });
                    }
                    for x in ints {
                        if let Some(v) = self.ints.get_mut(&x) {
                            v.known = false;
                        }
                    }
                }
                // The timers and one-shots of a branch that does not run are not called:
                // they keep their state (unknown where which branch runs is not known).
                let bodies =
                    branches.iter().map(|(_, b)| b.as_slice()).chain([otherwise.as_slice()]);
                for (k, body) in bodies.enumerate() {
                    if k != chosen {
                        self.skip(body, known);
                        continue;
                    }
                    let first = self.mark();
                    for s in body {
                        self.stmt(s, known);
                    }
                    if !known {
                        self.forget(first);
                    }
                }
            }
            Stmt::SetInt { target, value, .. } => {
                let Some(ty) = self.program.integers.get(target).map(|v| v.ty) else { return };
                let v = self.int_value(value, ty);
                self.ints.insert(target.clone(), N { value: v.value, known: v.known && known });
            }
            Stmt::Warn { .. } => {}
        }
    }

    /// The value of `e` computed in `ty` (every operation wraps to it).
    fn int_value(&mut self, e: &IntExpr, ty: IntType) -> N {
        let both = |a: N, b: N, f: fn(i64, i64) -> i64| N {
            value: ty.wrap(f(a.value, b.value)),
            known: a.known && b.known,
        };
        match e {
            IntExpr::Const(v) => N { value: ty.wrap(*v), known: true },
            IntExpr::Var(x) => {
                let v = self.ints.get(x).copied().unwrap_or(N { value: 0, known: false });
                N { value: ty.wrap(v.value), known: v.known }
            }
            IntExpr::Add(a, b) => {
                let (a, b) = (self.int_value(a, ty), self.int_value(b, ty));
                both(a, b, i64::wrapping_add)
            }
            IntExpr::Sub(a, b) => {
                let (a, b) = (self.int_value(a, ty), self.int_value(b, ty));
                both(a, b, i64::wrapping_sub)
            }
            IntExpr::Mul(a, b) => {
                let (a, b) = (self.int_value(a, ty), self.int_value(b, ty));
                both(a, b, i64::wrapping_mul)
            }
            IntExpr::Div(a, k) => {
                let a = self.int_value(a, ty);
                N { value: ty.wrap(a.value.wrapping_div(*k)), known: a.known }
            }
            IntExpr::Mod(a, k) => {
                let a = self.int_value(a, ty);
                N { value: ty.wrap(a.value.wrapping_rem(*k)), known: a.known }
            }
            // matiec's DIV and MOD give 0 for a divisor 0.
            IntExpr::DivBy(a, b) => {
                let (a, b) = (self.int_value(a, ty), self.int_value(b, ty));
                both(a, b, |x, y| if y == 0 { 0 } else { x.wrapping_div(y) })
            }
            IntExpr::ModBy(a, b) => {
                let (a, b) = (self.int_value(a, ty), self.int_value(b, ty));
                both(a, b, |x, y| if y == 0 { 0 } else { x.wrapping_rem(y) })
            }
            IntExpr::Cast(a, inner) => {
                let a = self.int_value(a, *inner);
                N { value: ty.wrap(a.value), known: a.known }
            }
            IntExpr::Real(op, a, b) => {
                let (a, b) = (self.int_value(a, ty), self.int_value(b, ty));
                N { value: op.apply_in(ty, a.value, b.value), known: a.known && b.known }
            }
            IntExpr::Sqrt(a) => {
                let a = self.int_value(a, ty);
                N { value: super::real::sqrt_in(ty, a.value), known: a.known }
            }
            IntExpr::FromReal(a, unsigned) => {
                let a = self.int_value(a, IntType::REAL);
                let v = super::real::to_int(a.value, *unsigned).unwrap_or(0);
                N { value: ty.wrap(v), known: a.known }
            }
            IntExpr::ToReal(a, inner) => {
                let a = self.int_value(a, *inner);
                N { value: super::real::convert(a.value, *inner, ty), known: a.known }
            }
            IntExpr::Bitwise(op, a, b) => {
                let (a, b) = (self.int_value(a, ty), self.int_value(b, ty));
                N { value: ty.wrap(op.apply(a.value, b.value)), known: a.known && b.known }
            }
            IntExpr::Shift(a, k) => {
                let a = self.int_value(a, ty);
                N { value: ty.wrap(super::shift(a.value, *k)), known: a.known }
            }
            IntExpr::Checked(c) => {
                let (a, b) = (self.int_value(&c.a, c.ty), self.int_value(&c.b, c.ty));
                let v = match c.op.apply(a.value, b.value, c.ty) {
                    Some(v) => N { value: v, known: true },
                    None => self.int_value(&IntExpr::Var(c.undefined.clone()), c.ty),
                };
                N { value: ty.wrap(v.value), known: v.known && a.known && b.known }
            }
            IntExpr::Ite(c, a, b) => {
                let c = self.eval(c);
                let (a, b) = (self.int_value(a, ty), self.int_value(b, ty));
                let v = if c.value { a } else { b };
                N { value: v.value, known: v.known && (c.known || a == b) }
            }
        }
    }

    fn read(&self, name: &str) -> V {
        self.current.get(name).copied().unwrap_or(V::ZERO)
    }

    /// The one-shot memory met next in the scan: its value from the previous scan, then
    /// `power` kept for the next.
    fn memory(&mut self, power: V, index: usize) -> V {
        let k = self.next_memory_slot(index);
        let last = self.memories[k];
        self.memories[k] = power;
        self.by_index.insert(index, power);
        last
    }

    fn eval(&mut self, e: &BoolExpr) -> V {
        match e {
            BoolExpr::Const(b) => V::of(*b),
            BoolExpr::Var(n) => self.read(n),
            BoolExpr::Temp(t) => self.temps.get(t).copied().unwrap_or(V::ZERO),
            BoolExpr::Not(x) => {
                let v = self.eval(x);
                V { value: !v.value, known: v.known }
            }
            BoolExpr::And(a, b) => {
                let (a, b) = (self.eval(a), self.eval(b));
                let value = a.value && b.value;
                // A known 0 decides the product.
                let decides = |v: V| v.known && !v.value;
                let known = (a.known && b.known) || decides(a) || decides(b);
                V { value, known }
            }
            BoolExpr::Or(xs) => {
                let vs: Vec<V> = xs.iter().map(|x| self.eval(x)).collect();
                let value = vs.iter().any(|v| v.value);
                let known = vs.iter().all(|v| v.known) || vs.iter().any(|v| v.known && v.value);
                V { value, known }
            }
            BoolExpr::Timer(t) => {
                let input = self.eval(&t.input);
                self.timer(t, input)
            }
            BoolExpr::Edge { kind, input, memory } => {
                let input = self.eval(input);
                let last = self.memory(input, memory.index);
                let rising = input.value && !last.value;
                let value = match kind {
                    EdgeKind::Rising => rising,
                    EdgeKind::Falling => !input.value && last.value,
                    EdgeKind::NotRising => !rising,
                };
                V { value, known: input.known && last.known }
            }
            BoolExpr::Fresh(_) => V { value: false, known: false },
            BoolExpr::Compare(c) => {
                let (a, b) = (self.int_value(&c.a, c.ty), self.int_value(&c.b, c.ty));
                V { value: c.ty.holds(c.op, a.value, b.value), known: a.known && b.known }
            }
        }
    }

    /// The slot of the timer met next in the scan.
    fn next_timer(&mut self, on_delay: bool) -> usize {
        let k = self.next_count;
        self.next_count += 1;
        if self.counts.len() <= k {
            // A TOF has been off "forever" at power-up: its output is off.
            let count = if on_delay { 0 } else { u64::MAX };
            self.counts.push(Count { count, known: true, runs: !on_delay, at: 0 });
        }
        k
    }

    /// The one-shot memory met next in the scan.
    fn next_memory_slot(&mut self, index: usize) -> usize {
        let k = self.next_memory;
        self.next_memory += 1;
        if self.memories.len() <= k {
            self.memories.push(V::of(self.edge_starts.get(&index).copied().unwrap_or(false)));
        }
        k
    }

    /// The timers and one-shots of `body`, a branch that does not run: passed, their
    /// state kept (made unknown unless `known`: whether the branch runs is not known).
    fn skip(&mut self, body: &[Stmt], known: bool) {
        let first = self.mark();
        for s in body {
            match s {
                Stmt::Let { value, .. } => self.skip_expr(value),
                Stmt::Write { value, kind, .. } => {
                    self.skip_expr(value);
                    if let WriteKind::Toggle(memory) = kind {
                        self.next_memory_slot(memory.index);
                    }
                }
                Stmt::If { branches, otherwise, .. } => {
                    for (c, _) in branches {
                        self.skip_expr(c);
                    }
                    for (_, b) in branches {
                        self.skip(b, known);
                    }
                    self.skip(otherwise, known);
                }
                Stmt::SetInt { value, .. } => self.skip_int(value),
                Stmt::Warn { .. } => {}
            }
        }
        if !known {
            self.forget(first);
        }
    }

    /// [`Self::skip`] of an expression: its timers and one-shots passed in the order
    /// [`Self::eval`] meets them (operands first, as [`walk`] goes).
    fn skip_expr(&mut self, e: &BoolExpr) {
        walk(e, &mut |b| self.pass(b));
    }

    /// [`Self::skip_expr`] of the conditions inside an integer expression.
    fn skip_int(&mut self, e: &IntExpr) {
        e.visit(&mut |_| {}, &mut |b| self.pass(b));
    }

    /// The slot of a timer or one-shot `b` passed, its state kept.
    fn pass(&mut self, b: &BoolExpr) {
        match b {
            BoolExpr::Timer(t) => {
                self.next_timer(t.on_delay);
                if self.blocks.contains_key(&t.accumulator) {
                    self.met.push(t.accumulator.clone());
                }
            }
            BoolExpr::Edge { memory, .. } => {
                self.next_memory_slot(memory.index);
            }
            _ => {}
        }
    }

    /// Where the scan stands: the next timer and one-shot slots, and the calls met so far
    /// of the timer instances called at several places.
    fn mark(&self) -> (usize, usize, usize) {
        (self.next_count, self.next_memory, self.met.len())
    }

    /// The timers, one-shot memories and timer instances met since `from` made unknown.
    fn forget(&mut self, from: (usize, usize, usize)) {
        for c in &mut self.counts[from.0..self.next_count] {
            c.known = false;
        }
        for m in &mut self.memories[from.1..self.next_memory] {
            m.known = false;
        }
        for name in &self.met[from.2..] {
            if let Some(b) = self.blocks.get_mut(name) {
                b.known = false;
            }
        }
    }

    /// A timer's output at a call: the runtime's timer runs only when it is called, and
    /// measures the time since the call that started it (the scans since then, held
    /// input included: a call under a condition sees nothing between its calls).
    fn timer(&mut self, t: &Timer, input: V) -> V {
        let k = self.next_timer(t.on_delay);
        if self.blocks.contains_key(&t.accumulator) {
            self.met.push(t.accumulator.clone());
            return self.block_call(t, input);
        }
        let cycle = self.program.cycle_us;
        let scans = match &t.preset {
            _ if self.shared.contains(&t.accumulator) || cycle == 0 => None,
            Preset::Micros { us: 0, .. } | Preset::Variable { .. } => None,
            Preset::Micros { us, adjust, .. } => Some(match self.timers_model {
                TimerModel::Plc => {
                    i64::try_from(us / cycle).unwrap_or(i64::MAX).saturating_add(*adjust)
                }
                TimerModel::Ideal => i64::try_from(us / cycle).unwrap_or(i64::MAX),
            }),
        };
        // The count of consecutive scans that make the timer run (input on for a TON, off
        // for a TOF) up to this call, the input of the last call held between calls: a
        // known reset restarts it, an unknown input leaves it unknown.
        let scan = self.scan;
        let Count { count, known, runs: ran, at } = &mut self.counts[k];
        let runs = if t.on_delay { input.value } else { !input.value };
        if !runs && input.known {
            (*count, *known) = (0, true);
        } else {
            let since = scan.saturating_sub(*at).max(1);
            *count = match (runs, *ran) {
                (true, true) => count.saturating_add(since),
                (true, false) => 1,
                (false, _) => 0,
            };
            *known &= input.known;
        }
        (*ran, *at) = (runs, scan);
        let Some(p) = scans else { return V { value: false, known: false } };
        if p <= 0 {
            return input;
        }
        let p = p as u64;
        let value = if t.on_delay { *count > p } else { *count <= p };
        V { value, known: *known }
    }

    /// A call of a timer instance called at several places, as the runtime's `TON` or
    /// `TOF` block runs it, the time being the scan's (`START_TIME + PT <= CURRENT_TIME`
    /// is the scans since the start reaching `⌈PT / cycle⌉`, counted as the timer model
    /// says).
    fn block_call(&mut self, t: &Timer, input: V) -> V {
        let cycle = self.program.cycle_us;
        let scans = match &t.preset {
            Preset::Micros { zero: true, .. } => Some(0),
            _ if cycle == 0 => None,
            Preset::Micros { us: 0, .. } | Preset::Variable { .. } => None,
            Preset::Micros { us, adjust, .. } => match self.timers_model {
                TimerModel::Plc => i64::try_from(us / cycle)
                    .ok()
                    .and_then(|p| p.checked_add(*adjust))
                    .and_then(|p| u64::try_from(p).ok()),
                TimerModel::Ideal => Some(us / cycle),
            },
        };
        let scan = self.scan;
        let unknown = V { value: false, known: false };
        let Some(b) = self.blocks.get_mut(&t.accumulator) else { return unknown };
        let i = input.value;
        let (Some(k), true) = (scans, input.known) else {
            b.known = false;
            return unknown;
        };
        // A call that ends the run (a TON's FALSE, a TOF's TRUE) sets every part of the
        // state that matters: from an unknown state, the block is known again.
        let ends = if t.on_delay { !i } else { i };
        if !b.known && !ends {
            return unknown;
        }
        if t.on_delay {
            if b.state == 0 && !b.prev_in && i {
                (b.state, b.q, b.start) = (1, false, scan);
            } else if !i {
                (b.q, b.state) = (false, 0);
            } else if b.state == 1 && scan - b.start >= k {
                (b.state, b.q) = (2, true);
            }
        } else {
            if b.state == 0 && b.prev_in && !i {
                (b.state, b.start) = (1, scan);
            } else if i {
                b.state = 0;
            } else if b.state == 1 && scan - b.start >= k {
                b.state = 2;
            }
            b.q = i || b.state == 1;
        }
        b.prev_in = i;
        b.known = true;
        V::of(b.q)
    }
}

/// A reference scan simulator of a front end: the counterexample search confirms
/// candidates on it, the differential tests check the compiled equations against it.
pub trait ScanSimulator {
    /// Runs one scan with these input values.
    fn step(&mut self, inputs: &BTreeMap<String, bool>);
    /// A bit's value at the end of the last scan.
    fn bit(&self, name: &str) -> bool;
    /// Whether the simulator computes the bit.
    fn is_known(&self, name: &str) -> bool;
    /// Whether a run can tell `input` held at 0 from `input` left out of
    /// [`step`](Self::step)'s map (by default, any input): a simulator of part of a
    /// program need not be given the inputs it never reads.
    fn reads(&self, input: &str) -> bool {
        let _ = input;
        true
    }
    /// Every name [`reads`](Self::reads) holds of, when that is not every input (a
    /// simulator of part of a program); `None`, the default, for every input.
    fn read_names(&self) -> Option<Vec<&str>> {
        None
    }
    /// The hidden memory of the one-shot with this index (the front end's order, the
    /// scan model's [`Memory::index`](super::Memory::index)) after the last scan; `None`
    /// when the simulator cannot tell which of its memories that is.
    fn edge_memory(&self, _index: usize) -> Option<bool> {
        None
    }
    /// An integer's value after the last scan; `None` when the simulator does not keep it.
    fn int(&self, _name: &str) -> Option<i64> {
        None
    }
    /// Before the first scan: starts the run from `state` instead of the power-up
    /// values (`equiv --any-state`); `false` when the simulator cannot, and then its
    /// run is not one from that state.
    fn start_from(&mut self, _state: &super::any_state::StartState) -> bool {
        false
    }
}

/// What a program's counterexamples are replayed on: a front end's own simulator of the
/// program as it read it, or the scan model's.
pub trait Reference: Send + Sync {
    /// A new run from power-up.
    fn simulator(&self) -> Box<dyn ScanSimulator>;

    /// A new run from power-up whose values of `names` are those [`simulator`]'s run
    /// gives (other names may be left out): a front end may run only the part of the
    /// program that can write them. By default, the whole program.
    ///
    /// [`simulator`]: Reference::simulator
    fn simulator_for(&self, names: &std::collections::BTreeSet<String>) -> Box<dyn ScanSimulator> {
        let _ = names;
        self.simulator()
    }

    /// A run from power-up on `inputs` (one map a scan) of the part of the program that
    /// can write `names` (as [`simulator_for`](Reference::simulator_for) runs it),
    /// recorded for [`simulator_near`](Reference::simulator_near); `None` (the default)
    /// when the front end keeps no such record.
    fn record(
        &self,
        names: &std::collections::BTreeSet<String>,
        inputs: &[BTreeMap<String, bool>],
    ) -> Option<Recording> {
        let _ = (names, inputs);
        None
    }

    /// A new run from power-up, of at most `scans` scans whose inputs are those of the
    /// run `base` recorded except `changed`, whose values of `names` are those
    /// [`simulator`]'s run gives: a front end may run only the part of the program
    /// that `changed` can change, and take what that part reads from elsewhere from its
    /// record. `None` (the default) when it cannot: then
    /// [`simulator_for`](Reference::simulator_for).
    ///
    /// [`simulator`]: Reference::simulator
    fn simulator_near(
        &self,
        names: &std::collections::BTreeSet<String>,
        base: &Recording,
        changed: &std::collections::BTreeSet<String>,
        scans: usize,
    ) -> Option<Box<dyn ScanSimulator>> {
        let _ = (names, base, changed, scans);
        None
    }
}

/// A front end's record of a run of the whole program ([`Reference::record`]), which
/// only that front end reads.
pub type Recording = std::sync::Arc<dyn std::any::Any + Send + Sync>;

/// The scan model as its own reference (languages without a simulator of their own),
/// timers counted as the runtime counts them.
impl Reference for Program {
    fn simulator(&self) -> Box<dyn ScanSimulator> {
        Box::new(Simulator::new(self, TimerModel::Plc))
    }
}

impl ScanSimulator for Simulator {
    fn step(&mut self, inputs: &BTreeMap<String, bool>) {
        Simulator::step(self, inputs)
    }
    fn bit(&self, name: &str) -> bool {
        Simulator::bit(self, name)
    }
    fn is_known(&self, name: &str) -> bool {
        Simulator::is_known(self, name)
    }
    fn int(&self, name: &str) -> Option<i64> {
        Simulator::int(self, name)
    }
    fn edge_memory(&self, index: usize) -> Option<bool> {
        Simulator::edge_memory(self, index)
    }
    fn start_from(&mut self, state: &super::any_state::StartState) -> bool {
        for (n, v) in &state.bits {
            self.bits.insert(n.clone(), V::of(*v));
        }
        for (&index, &v) in &state.edges {
            self.edge_starts.insert(index, v);
        }
        // An integer starts from its value reduced into its type; `false` for one the
        // program does not have.
        state.ints.iter().all(|(n, v)| {
            let Some(var) = self.program.integers.get(n) else { return false };
            self.ints.insert(n.clone(), N { value: var.ty.wrap(*v), known: true });
            true
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diag::Span;
    use crate::program::{Block, IntType, IntVar};

    /// `Y := X + 1` with `X` an INT input driven through its bits (a value outside
    /// the type given by its low 16 bits, as a 16-bit input register holds it).
    #[test]
    fn an_integer_input_is_driven_by_its_bits() {
        let span = Span::new(0, 0..1);
        let int = |input| IntVar { ty: IntType::I16, input, init: 0 };
        let mut program = Program::default();
        program.integers.insert("X".into(), int(true));
        program.integers.insert("Y".into(), int(false));
        let value = IntExpr::Add(Box::new(IntExpr::Var("X".into())), Box::new(IntExpr::Const(1)));
        let stmts = vec![Stmt::SetInt { target: "Y".into(), value, span }];
        program.blocks.push(Block { number: 1, label: Some("L1".into()), span, stmts });
        let mut sim = Simulator::new(&program, TimerModel::Plc);
        let mut got = Vec::new();
        for x in [5_i64, -3, 40_000, 32_767] {
            let bits = (0..16).map(|k| (Program::int_bit("X", k), x >> k & 1 == 1)).collect();
            sim.step(&bits);
            got.push((sim.int("X"), sim.int("Y")));
        }
        let want = [(5, 6), (-3, -2), (-25_536, -25_535), (32_767, -32_768)];
        assert_eq!(got, want.map(|(x, y)| (Some(x), Some(y))));
        // Bits not given are 0.
        sim.step(&BTreeMap::new());
        assert_eq!((sim.int("X"), sim.int("Y")), (Some(0), Some(1)));
    }
}
