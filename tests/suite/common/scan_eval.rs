//! An evaluator of compiled hypotheses on scan runs, written from `shared/spec/semantics.md` ("Programs, scan by scan") alone; shared by the differential tests of every front end.
//!
//! `·`, `+`, `¬` pointwise; memories and timers by their scan recurrences (`n = ceil(d / δ)`
//! scans for `d/f`, `f/d`); program bits and previous values are read from the reference
//! simulator's scans (`Src`); fresh signals are existential (the set of reachable
//! evaluator states under some run of them is kept).
#![allow(dead_code)]

use std::collections::BTreeSet;

use ii_prove::kernel::Rel;
use ii_prove::ladder::{CompiledProgram, SignalKind};
use ii_prove::syntax::{Notation, term_to_string};
use ii_prove::term::Language as _;
use ii_prove::term::{Expr, Term};
use num_rational::BigRational;
use num_traits::ToPrimitive;

/// One node of a hypothesis, ready to evaluate scan by scan.
#[derive(Clone, Copy)]
pub enum Node {
    Const(bool),
    /// A program bit or `pre_` value: index into the scan's values.
    Known(usize),
    /// A fresh signal: bit of the valuation.
    Free(usize),
    Not(usize),
    And(usize, usize),
    Or(usize, usize),
    /// Memory: children, state slot.
    Sr(usize, usize, usize),
    Rs(usize, usize, usize),
    /// `d/f`: f, n = ceil(d/δ), state slot (consecutive true scans, capped at n + 1).
    Ton(usize, u32, usize),
    /// `f/d`: f, n, state slot (0: f never true; else 1 + scans since f was last true, capped).
    Tof(usize, u32, usize),
    /// `pre f`: f, state slot (f's value at the previous scan; before the first, the
    /// value f has with every variable, timer and memory 0).
    Pre(usize, usize),
}

/// The known values' sources, each at its slot, with an index of them.
#[derive(Clone, Debug, Default)]
pub struct Known {
    list: Vec<Src>,
    index: std::collections::HashMap<Src, usize>,
}

impl std::ops::Deref for Known {
    type Target = Vec<Src>;
    fn deref(&self) -> &Vec<Src> {
        &self.list
    }
}

impl<'a> IntoIterator for &'a Known {
    type Item = &'a Src;
    type IntoIter = std::slice::Iter<'a, Src>;
    fn into_iter(self) -> Self::IntoIter {
        self.list.iter()
    }
}

impl Known {
    /// The slot of `src`, if it has one.
    pub fn position(&self, src: &Src) -> Option<usize> {
        self.index.get(src).copied()
    }
}

/// Where the value of a known name comes from at each scan.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Src {
    /// The simulator's bit at the end of this scan.
    Bit(String),
    /// The simulator's hidden edge memory of the `k`-th element (file order).
    Edge(usize),
    /// Bit `bit` of the simulator's integer `of`, xor `start` (the compiled bits of an
    /// integer are its value xor its start value).
    IntBit { of: String, bit: u32, start: bool },
    /// A name the compiled program defines by an equation (an intermediate value or a
    /// comparison atom): its value is that equation's right side at each scan
    /// ([`Hyp::run`]).
    Defined(String),
    /// A defined name's value at the end of the previous scan (0 before the first),
    /// kept by [`Carry`].
    PreDefined(String),
}

/// The defined names' values carried from the end of a scan to their `pre` at the next.
#[derive(Clone, Debug, Default)]
pub struct Carry {
    /// Each `pre` slot with the slot of its name.
    pairs: Vec<(usize, usize)>,
    last: Vec<bool>,
}

impl Carry {
    pub fn new(known: &Known) -> Carry {
        let pairs: Vec<(usize, usize)> = known
            .iter()
            .enumerate()
            .filter_map(|(k, src)| match src {
                Src::PreDefined(n) => Some((k, known.position(&Src::Defined(n.clone()))?)),
                _ => None,
            })
            .collect();
        Carry { last: vec![false; pairs.len()], pairs }
    }

    /// At the start of a scan: each `pre` of a defined name.
    pub fn fill(&self, values: &mut [bool]) {
        for ((p, _), v) in self.pairs.iter().zip(&self.last) {
            values[*p] = *v;
        }
    }

    /// At the end of a scan: the defined names' values, for the next.
    pub fn keep(&mut self, values: &[bool]) {
        for ((_, d), v) in self.pairs.iter().zip(self.last.iter_mut()) {
            *v = values[*d];
        }
    }
}

impl Src {
    /// The value at the end of the scan, from a simulator's bits, edge memories and
    /// integers; `Defined` names read 0 here (their equations set them).
    pub fn read(
        &self,
        bit: &dyn Fn(&str) -> bool,
        edge: &dyn Fn(usize) -> Option<bool>,
        int: &dyn Fn(&str) -> Option<i64>,
    ) -> bool {
        match self {
            Src::Bit(n) => bit(n),
            Src::Edge(k) => edge(*k).unwrap_or(false),
            Src::IntBit { of, bit, start } => int(of).is_some_and(|v| v >> bit & 1 == 1) != *start,
            Src::Defined(_) | Src::PreDefined(_) => false,
        }
    }
}

/// Why a hypothesis was not checked.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Skip {
    /// More than [`MAX_FREE`] fresh signals.
    TooManyFresh,
    /// The set of evaluator states reachable under the fresh signals grew over [`MAX_STATES`].
    TooManyStates,
    /// A delay that is not a literal, or a zero cycle.
    Delay,
}

pub const MAX_FREE: usize = 8;
pub const MAX_STATES: usize = 256;

pub struct Hyp {
    pub name: String,
    pub text: String,
    pub rel: Rel,
    pub nodes: Vec<Node>,
    pub lhs: usize,
    pub rhs: usize,
    pub n_free: usize,
    /// Whether a fresh signal occurs under a timer or memory.
    pub temporal_free: bool,
    pub states: BTreeSet<Vec<u32>>,
    pub skip: Option<Skip>,
    /// Scans on which the hypothesis held (for every live state) — all of them unless it failed.
    pub checked_scans: u64,
    /// Whether it has a `d/f` or `f/d` with `n > 0`, and whether one was on (`d/f`) or
    /// holding after its input fell (`f/d`) at some scan.
    pub has_timer: bool,
    pub timer_fired: bool,
    /// For the equation of a defined name, that name's slot among the known values.
    pub defines: Option<usize>,
}

/// How often the hypotheses' timers were on, counted over all reachable states.
#[derive(Default, Clone, Copy, Debug)]
pub struct TimerStats {
    /// Scans on which a `d/f` (d > 0) was 1.
    pub ton_on: u64,
    /// Scans on which an `f/d` was 1 while `f` was 0 (the hold after the fall).
    pub tof_hold: u64,
}

/// `ceil(d / δ)` for a delay in seconds and a cycle in µs.
pub fn ceil_scans(d: &ii_prove::term::Delay, cycle_us: u64) -> Option<u32> {
    if cycle_us == 0 {
        return None;
    }
    let cycle = BigRational::new(cycle_us.into(), 1_000_000u64.into());
    (d.seconds() / cycle).ceil().to_integer().to_u32()
}

/// The hypotheses in an order where each runs after the equations of the defined names
/// (intermediate values, atoms, held timer inputs) it reads: a defined name reads 0 until
/// its equation has run in the scan, and its `pre` keeps the value read. The equations
/// hold together, so any order is theirs; where defined names read each other in a
/// cycle, the rest keep the compiler's order.
pub fn in_order(hyps: Vec<Hyp>, known: &Known) -> Vec<Hyp> {
    let defined = |slot: usize| matches!(known.get(slot), Some(Src::Defined(_)));
    let reads: Vec<BTreeSet<usize>> = hyps
        .iter()
        .map(|h| {
            h.nodes
                .iter()
                .filter_map(|n| match n {
                    Node::Known(k) if defined(*k) && h.defines != Some(*k) => Some(*k),
                    _ => None,
                })
                .collect()
        })
        .collect();
    // Per defined name, how many of its equations have not run yet.
    let mut waiting: std::collections::HashMap<usize, usize> = std::collections::HashMap::new();
    for d in hyps.iter().filter_map(|h| h.defines) {
        *waiting.entry(d).or_default() += 1;
    }
    let mut left: Vec<Option<Hyp>> = hyps.into_iter().map(Some).collect();
    let mut out = Vec::with_capacity(left.len());
    loop {
        let mut placed = Vec::new();
        for (k, slot) in left.iter_mut().enumerate() {
            // A name is done once every equation of it has run (in an earlier round).
            let ready = reads[k].iter().all(|r| waiting.get(r).is_none_or(|w| *w == 0));
            if let Some(h) = slot.take_if(|_| ready) {
                placed.extend(h.defines);
                out.push(h);
            }
        }
        if placed.is_empty() {
            break;
        }
        for d in placed {
            if let Some(w) = waiting.get_mut(&d) {
                *w -= 1;
            }
        }
    }
    out.extend(left.into_iter().flatten());
    out
}

impl Hyp {
    pub fn new(
        h: &ii_prove::ladder::Hypothesis,
        c: &CompiledProgram,
        cycle_us: u64,
        known: &mut Known,
        loose: &BTreeSet<String>,
    ) -> Hyp {
        let mut nodes = Vec::new();
        let mut free: Vec<String> = Vec::new();
        let mut n_state = 0;
        let mut skip = None;
        let mut temporal_free = false;
        // Each `pre` slot's value before the first scan.
        let mut init: Vec<(usize, u32)> = Vec::new();
        let mut build = |e: &Expr, nodes: &mut Vec<Node>| -> usize {
            let base = nodes.len();
            let terms = e.as_ref();
            // Each node's value before the first scan: every variable, timer and memory
            // 0, the Boolean operators applied (semantics.md).
            let mut before: Vec<bool> = Vec::with_capacity(terms.len());
            // Whether each node lies under a timer or memory.
            let mut under = vec![false; terms.len()];
            for (i, t) in terms.iter().enumerate().rev() {
                let temporal = matches!(
                    t,
                    Term::Ton(_) | Term::Tof(_) | Term::Sr(_) | Term::Rs(_) | Term::Pre(_)
                );
                for ch in t.children() {
                    under[usize::from(*ch)] |= under[i] || temporal;
                }
            }
            for (i, t) in terms.iter().enumerate() {
                let at = |id: &ii_prove::term::Id| base + usize::from(*id);
                let node = match t {
                    Term::Zero => Node::Const(false),
                    Term::One => Node::Const(true),
                    Term::Not(a) => Node::Not(at(a)),
                    Term::And([a, b]) => Node::And(at(a), at(b)),
                    Term::Or([a, b]) => Node::Or(at(a), at(b)),
                    Term::Sr([s, r]) | Term::Rs([s, r]) => {
                        n_state += 1;
                        if matches!(t, Term::Sr(_)) {
                            Node::Sr(at(s), at(r), n_state - 1)
                        } else {
                            Node::Rs(at(s), at(r), n_state - 1)
                        }
                    }
                    Term::Ton([d, f]) | Term::Tof([f, d]) => {
                        let n = match &terms[usize::from(*d)] {
                            Term::Delay(d) => ceil_scans(d, cycle_us),
                            _ => None,
                        };
                        let n = n.unwrap_or_else(|| {
                            skip = Some(Skip::Delay);
                            0
                        });
                        n_state += 1;
                        if matches!(t, Term::Ton(_)) {
                            Node::Ton(at(f), n, n_state - 1)
                        } else {
                            Node::Tof(at(f), n, n_state - 1)
                        }
                    }
                    Term::Name(s) => {
                        let s = s.as_str();
                        match c.signals.get(s) {
                            Some(SignalKind::Fresh { .. }) => {
                                temporal_free |= under[i];
                                let k = free.iter().position(|f| f == s).unwrap_or_else(|| {
                                    free.push(s.to_string());
                                    free.len() - 1
                                });
                                Node::Free(k)
                            }
                            Some(SignalKind::EdgeMemory { index, .. }) => {
                                Node::Known(slot(known, Src::Edge(*index)))
                            }
                            Some(SignalKind::IntBit { of, bit, start, .. }) => {
                                let src = Src::IntBit { of: of.clone(), bit: *bit, start: *start };
                                Node::Known(slot(known, src))
                            }
                            // A held timer input is computed from its recurrence, as the
                            // timer's output it decides is checked against the simulator.
                            Some(
                                SignalKind::Intermediate { .. }
                                | SignalKind::Atom
                                | SignalKind::HeldInput { .. },
                            ) if !loose.contains(s) => {
                                Node::Known(slot(known, Src::Defined(s.to_string())))
                            }
                            // Defined from an unconstrained signal: as free as it is.
                            Some(
                                SignalKind::Intermediate { .. }
                                | SignalKind::Atom
                                | SignalKind::HeldInput { .. },
                            ) => {
                                temporal_free |= under[i];
                                let k = free.iter().position(|f| f == s).unwrap_or_else(|| {
                                    free.push(s.to_string());
                                    free.len() - 1
                                });
                                Node::Free(k)
                            }
                            _ => Node::Known(slot(known, Src::Bit(s.to_string()))),
                        }
                    }
                    // The previous value of a defined name: its value at the end of the
                    // last scan, whichever order the equations run in ([`Carry`]).
                    Term::Pre(a)
                        if let Node::Known(k) = nodes[at(a)]
                            && let Some(Src::Defined(n)) = known.get(k) =>
                    {
                        Node::Known(slot(known, Src::PreDefined(n.clone())))
                    }
                    Term::Pre(a) => {
                        n_state += 1;
                        let v = before[usize::from(*a)];
                        init.push((n_state - 1, u32::from(v)));
                        Node::Pre(at(a), n_state - 1)
                    }
                    // Delays are read by their timer only.
                    Term::Delay(_) | Term::DMax(_) | Term::DMin(_) | Term::DAdd(_) => {
                        Node::Const(false)
                    }
                };
                let b = |id: &ii_prove::term::Id| before[usize::from(*id)];
                let value = match t {
                    Term::One => true,
                    Term::Not(a) => !b(a),
                    Term::And([x, y]) => b(x) && b(y),
                    Term::Or([x, y]) => b(x) || b(y),
                    Term::Pre(a) => b(a),
                    _ => false,
                };
                before.push(value);
                nodes.push(node);
            }
            nodes.len() - 1
        };
        let lhs = build(&h.lhs, &mut nodes);
        let rhs = build(&h.rhs, &mut nodes);
        let has_timer =
            nodes.iter().any(|n| matches!(n, Node::Ton(_, k, _) | Node::Tof(_, k, _) if *k > 0));
        if free.len() > MAX_FREE {
            skip = Some(Skip::TooManyFresh);
        }
        let rel = if h.rel == Rel::Eq { "=" } else { "⇒" };
        let defines = match &h.lhs[ii_prove::term::root(&h.lhs)] {
            Term::Name(n) => known.position(&Src::Defined(n.as_str().into())),
            _ => None,
        };
        Hyp {
            defines,
            name: h.name.clone(),
            text: format!(
                "{} {rel} {}",
                term_to_string(&h.lhs, Notation::Paper),
                term_to_string(&h.rhs, Notation::Paper)
            ),
            rel: h.rel,
            nodes,
            lhs,
            rhs,
            n_free: free.len(),
            temporal_free,
            states: {
                let mut start = vec![0; n_state];
                for (slot, v) in init {
                    start[slot] = v;
                }
                [start].into_iter().collect()
            },
            skip,
            checked_scans: 0,
            has_timer,
            timer_fired: false,
        }
    }

    /// One scan from `state` with the fresh signals `valuation`: (lhs, rhs).
    pub fn step(
        &self,
        state: &mut [u32],
        known: &[bool],
        valuation: u32,
        vals: &mut Vec<bool>,
        stats: &mut TimerStats,
    ) -> (bool, bool) {
        vals.clear();
        for node in &self.nodes {
            let v = match *node {
                Node::Const(b) => b,
                Node::Known(k) => known[k],
                Node::Free(k) => valuation >> k & 1 == 1,
                Node::Not(a) => !vals[a],
                Node::And(a, b) => vals[a] && vals[b],
                Node::Or(a, b) => vals[a] || vals[b],
                Node::Sr(s, r, st) => {
                    let q = vals[s] || (!vals[r] && state[st] == 1);
                    state[st] = u32::from(q);
                    q
                }
                Node::Rs(s, r, st) => {
                    let q = !vals[r] && (vals[s] || state[st] == 1);
                    state[st] = u32::from(q);
                    q
                }
                Node::Ton(f, n, st) => {
                    state[st] = if vals[f] { (state[st] + 1).min(n + 1) } else { 0 };
                    let on = state[st] > n;
                    if on && n > 0 {
                        stats.ton_on += 1;
                    }
                    on
                }
                Node::Pre(f, st) => {
                    let v = state[st] == 1;
                    state[st] = u32::from(vals[f]);
                    v
                }
                Node::Tof(f, n, st) => {
                    if vals[f] {
                        state[st] = 1;
                    } else if state[st] > 0 {
                        state[st] = (state[st] + 1).min(n + 2);
                    }
                    let on = state[st] >= 1 && state[st] - 1 <= n;
                    if on && !vals[f] {
                        stats.tof_hold += 1;
                    }
                    on
                }
            };
            vals.push(v);
        }
        (vals[self.lhs], vals[self.rhs])
    }

    /// One scan: the equation of a defined name sets that name's value in `known` (its
    /// right side, when the state and the fresh signals determine it), any other
    /// hypothesis is checked ([`Hyp::scan`]).
    pub fn run(
        &mut self,
        known: &mut [bool],
        vals: &mut Vec<bool>,
        stats: &mut TimerStats,
    ) -> bool {
        if let Some(slot) = self.defines
            && self.skip.is_none()
            && self.n_free == 0
            && self.states.len() == 1
        {
            let mut state = self.states.iter().next().cloned().unwrap_or_default();
            let (_, rhs) = self.step(&mut state, known, 0, vals, stats);
            known[slot] = rhs;
            self.states = [state].into_iter().collect();
            self.checked_scans += 1;
            return true;
        }
        self.scan(known, vals, stats)
    }

    /// Advances every reachable state by one scan; false if the hypothesis fails
    /// for every run of the fresh signals.
    pub fn scan(&mut self, known: &[bool], vals: &mut Vec<bool>, stats: &mut TimerStats) -> bool {
        if self.skip.is_some() {
            return true;
        }
        let mut next = BTreeSet::new();
        let mut local = TimerStats::default();
        for state in &self.states {
            for valuation in 0..(1u32 << self.n_free) {
                let mut s = state.clone();
                let (l, r) = self.step(&mut s, known, valuation, vals, &mut local);
                let holds = match self.rel {
                    Rel::Eq => l == r,
                    Rel::Implies => !l || r,
                };
                if holds {
                    next.insert(s);
                }
            }
        }
        // Timer activity per reachable run, counted once per scan when the set is a singleton.
        if self.states.len() == 1 && self.n_free == 0 {
            stats.ton_on += local.ton_on;
            stats.tof_hold += local.tof_hold;
        }
        self.timer_fired |= local.ton_on + local.tof_hold > 0;
        if next.is_empty() {
            return false;
        }
        if next.len() > MAX_STATES {
            self.skip = Some(Skip::TooManyStates);
        }
        self.states = next;
        self.checked_scans += 1;
        true
    }
}

/// The defined names (intermediate values, atoms) that depend, through their equations
/// and transitively, on an unconstrained signal (or have no equation).
pub fn loose_names(c: &CompiledProgram) -> BTreeSet<String> {
    let defined = |n: &str| {
        matches!(
            c.signals.get(n),
            Some(SignalKind::Intermediate { .. } | SignalKind::Atom | SignalKind::HeldInput { .. })
        )
    };
    let mut equations: std::collections::BTreeMap<&str, &ii_prove::ladder::Hypothesis> =
        std::collections::BTreeMap::new();
    for h in &c.hypotheses {
        if let Term::Name(x) = &h.lhs[ii_prove::term::root(&h.lhs)]
            && defined(x.as_str())
        {
            equations.entry(x.as_str()).or_insert(h);
        }
    }
    let mut loose: BTreeSet<String> = c
        .signals
        .keys()
        .filter(|n| defined(n) && !equations.contains_key(n.as_str()))
        .cloned()
        .collect();
    // To a fixpoint: each round adds the names whose equation reads a loose one.
    loop {
        let before = loose.len();
        for (n, h) in &equations {
            if loose.contains(*n) {
                continue;
            }
            let reads_loose = h.rhs.as_ref().iter().any(|t| match t {
                Term::Name(x) => match c.signals.get(x.as_str()) {
                    Some(SignalKind::Fresh { .. }) => true,
                    Some(
                        SignalKind::Intermediate { .. }
                        | SignalKind::Atom
                        | SignalKind::HeldInput { .. },
                    ) => loose.contains(x.as_str()),
                    _ => false,
                },
                _ => false,
            });
            if reads_loose {
                loose.insert(n.to_string());
            }
        }
        if loose.len() == before {
            return loose;
        }
    }
}

pub fn slot(known: &mut Known, src: Src) -> usize {
    if let Some(k) = known.position(&src) {
        return k;
    }
    known.list.push(src.clone());
    known.index.insert(src, known.list.len() - 1);
    known.list.len() - 1
}

/// What random programs checked with [`check_scans`] add up to: the counts of the runs
/// and the failures, each with its seed and the program's text.
#[derive(Default, Debug)]
pub struct Tally {
    /// The runs' counts, summed.
    pub totals: Checked,
    /// `seed S: error` and the program, per failure.
    pub failures: Vec<String>,
}

impl Tally {
    /// Adds one program's run, or its failure.
    pub fn add(&mut self, seed: u64, text: &str, run: Result<Checked, String>) {
        match run {
            Ok(c) => {
                self.totals.scans += c.scans;
                self.totals.hypotheses += c.hypotheses;
                self.totals.fired += c.fired;
            }
            Err(e) => self.fail(seed, text, &e),
        }
    }

    /// Records a failure of the program drawn from `seed`.
    pub fn fail(&mut self, seed: u64, text: &str, error: &str) {
        self.failures.push(format!("seed {seed}: {error}\n{text}"));
    }

    /// Prints `summary` with the number of disagreements; fails with the first three.
    pub fn finish(&self, summary: &str) {
        eprintln!("{summary}; {} disagreements", self.failures.len());
        assert!(
            self.failures.is_empty(),
            "{}",
            self.failures.iter().take(3).cloned().collect::<Vec<_>>().join("\n\n")
        );
    }
}

/// What [`check_scans`] counted.
#[derive(Default, Clone, Copy, Debug)]
pub struct Checked {
    /// Scans run.
    pub scans: u64,
    /// Hypotheses checked at every scan.
    pub hypotheses: u64,
    /// Timer hypotheses whose timer was on or holding at some scan.
    pub fired: u64,
}

/// Runs `program` on the scan model's simulator (PLC timers) for `schedule`, checking
/// at every scan that every bit the hypotheses read is known and that every compiled
/// hypothesis holds; `each(scan, simulator)` may compare more after each scan. The
/// first failure is returned as a text.
pub fn check_scans(
    program: &ii_prove::program::Program,
    compiled: &CompiledProgram,
    cycle_us: u64,
    schedule: &[std::collections::BTreeMap<String, bool>],
    each: &mut dyn FnMut(usize, &ii_prove::program::simulate::Simulator) -> Result<(), String>,
) -> Result<Checked, String> {
    let mut known = Known::default();
    let loose = loose_names(compiled);
    let hyps: Vec<Hyp> = compiled
        .hypotheses
        .iter()
        .map(|h| Hyp::new(h, compiled, cycle_us, &mut known, &loose))
        .collect();
    let mut hyps = in_order(hyps, &known);
    let mut carry = Carry::new(&known);
    let mut sim =
        ii_prove::program::simulate::Simulator::new(program, ii_prove::ladder::TimerModel::Plc);
    let mut vals = Vec::new();
    let mut stats = TimerStats::default();
    let mut scans = 0;
    for (scan, inputs) in schedule.iter().enumerate() {
        sim.step(inputs);
        scans += 1;
        for src in &known {
            if let Src::Bit(n) = src
                && !sim.is_known(n)
            {
                return Err(format!("{n} is unknown to the simulator at scan {scan}"));
            }
        }
        let mut values: Vec<bool> = known
            .iter()
            .map(|src| src.read(&|n| sim.bit(n), &|k| sim.edge_memory(k), &|n| sim.int(n)))
            .collect();
        carry.fill(&mut values);
        for h in hyps.iter_mut() {
            if !h.run(&mut values, &mut vals, &mut stats) {
                return Err(format!(
                    "{}: {} fails at scan {scan}\n{}",
                    h.name,
                    h.text,
                    ii_prove::ladder::program_to_ii(compiled, Notation::Paper)
                ));
            }
        }
        carry.keep(&values);
        each(scan, &sim)?;
    }
    Ok(Checked {
        scans,
        hypotheses: hyps.len() as u64,
        fired: hyps.iter().filter(|h| h.has_timer && h.timer_fired).count() as u64,
    })
}
