//! The rung compiler: an LDmicro program ([`LdProgram`]) → ground hypotheses of the II algebra (exact equations) that hold at every scan of what the PLC runs (`shared/spec/semantics.md`, "Programs, scan by scan").
//!
//! # Model
//!
//! A scan runs every rung once, top to bottom; inputs are constant during it, and
//! each read sees the last write before it in the scan. Power flows as in LDmicro
//! (ldmicro.md §6.2): series is `·`, parallel is `+`, a contact is its signal
//! or its complement, `SHORT` is `1*`, `OPEN`/`PLACEHOLDER` is `0*`, and
//! elements after a false still execute: a coil in the middle of a series gets
//! the power at that point. A rung's rung-in is the master-relay bit, modelled
//! exactly (§6.6: `MASTER_RELAY` with input `i` makes it `¬mcr + i`; it is `1*`
//! at the start of every scan).
//!
//! # Reads
//!
//! Bits are written only by coils (timers, counters, `RES`, `MOVE` and the integer
//! elements write integers, a separate name space, so a bit and a timer may share a
//! name). Every bit written by coils is tracked through the scan. Its value at a
//! point of the scan is a Boolean function of its previous-scan value `pre X`
//! (`shared/spec/semantics.md`: `X` at the end of the previous scan, 0 before the
//! first): each coil on `X` composes one step (plain `X := i`, negated `X := ¬i`, set
//! `X := i + X`, reset `X := ¬i · X`, toggle `X := e·¬X + ¬e·X` with `e = i · ¬pre M`
//! the rising edge of its power). Hence:
//!
//! * before the first coil on `X` a read sees `pre X`, exactly;
//! * after the last coil on `X` a read sees the signal `X` itself (exact);
//! * between two coils on `X` (several plain coils, a set rung and a later reset
//!   rung, …) a read sees the intermediate value, inlined **exactly**;
//! * a bit that no coil writes and that is not an input (`X` pins, `I`/`M` Modbus
//!   bits) keeps its power-up value: reads see `0*`, and `unwritten_X: X = 0*`
//!   is a hypothesis.
//!
//! While the scan is compiled, `pre X` is an internal name (`pre_X`, unique among the
//! program's names); every emitted term has it replaced by `pre X`.
//!
//! # Edges
//!
//! A one-shot keeps the power it saw in a hidden bit, 0 at power-up (ldmicro.md §4):
//! it compiles to a memory `M = i` (an [`SignalKind::EdgeMemory`] named `OSR_r5`,
//! stated with its rung) and `OSR` is `i · ¬pre M`, `OSF` `¬i · pre M`, `ODR`
//! `¬(i · ¬pre M)`; when the power is one signal `X`, `pre X` is used directly. A
//! toggle coil's edge is the same. `ODF` and `OSC` stay fresh.
//!
//! # Equations and memories
//!
//! At the last coil on `X` the end-of-scan value is `G(pre X)` (a seal-in contact
//! reads `pre X` too). If `pre X` does not occur, `X = G` exactly. If it occurs only
//! as a pointwise Boolean argument and `G0 = G[pre X:=0*] ⇒ G1 = G[pre X:=1*]`
//! (checked by truth table over the rung's atoms, at most
//! [`MAX_ATOMS`](super::logic::MAX_ATOMS)), then `G = G0 + pre X · G1`, which is the
//! scan recurrence of `SR(G0, ¬G1)`: `X` is a memory. It is written in the most
//! readable equivalent form: `RS(S, ¬Y)` with `Y = G1` and `S` = the factors of `G0`
//! not implied by `G1` (the `(S + Q)·Y` seal-in), or `SR(S, ¬Y)` with `S = G0` and `Y`
//! = the summands of `G1` that do not imply `G0` (the `S + Q·Y` form); the form that
//! drops something wins, then the smaller one, then `SR`. Every candidate is checked
//! against `G` by truth table before it is used. Set/reset coils are the same
//! composition, so a set rung followed by a reset rung gives `RS(S, R)` and the
//! other order `SR(S, R)`; several set (reset) coils sum their powers. The recurrence
//! itself is stated too, as `Lnn_scan: X = G(pre X)` ([`HypothesisKind::Recurrence`]):
//! it is what induction over scans reads.
//!
//! Otherwise (not monotone, e.g. a coil reading its own complement; or `pre X`
//! under a timer) `X = G(pre X)`.
//!
//! No bounds free of `pre` are emitted beside an equation that mentions it: what they
//! would say (`L03_hi: X ⇒ RS(s, r')`, say) follows from the exact equation, and the
//! prover derives it where a proof needs it (by the Boolean skeleton, or by
//! induction over scans with the memories' scan laws).
//!
//! # Timers and the rest
//!
//! A TON/TOF with a literal delay of `us` µs counts `P = floor(us / cycle) + adjust`
//! scans (ldmicro.md §6.3; the adjust field, else -1 for `LDmicro0.1` and 0
//! otherwise): its output is on from the (P+1)-th consecutive scan of its input
//! (TON), or for P scans after the input falls (TOF). On scan runs that is exactly
//! `d/IN` and `IN/d` with `d = P · cycle` ([`TimerModel::Plc`], the default; a
//! timer whose `d` differs from the written delay is named in a warning), and the
//! input itself when `P ≤ 0`. [`TimerModel::Ideal`] uses the written delay (the
//! paper's idealisation). The output continues the series. A timer whose accumulator is also
//! written by another element (RES, MOVE, a second timer of the same name, …), a
//! variable delay, a zero delay or a zero cycle, and RTO/RTL/THI/TLO/TCY give a
//! fresh, unconstrained output. So do counters (orig CTC passes its input,
//! exactly), the one-shots ODF and OSC, comparisons (`IN · fresh`) and every peripheral or
//! control-flow element; integer side effects (MOVE, math, RES) pass the power
//! and have no Boolean meaning. Every such case is a [`CompileWarning`] naming
//! the rung and the element: nothing is dropped silently.
//!
//! # Refused
//!
//! Elements that change which rungs run (`GOTO`, `GOSUB`, `SUBPROG`/`ENDSUB`,
//! `RETURN`, `LOCK`, `SLEEP`) refuse the program with a located
//! [`LadderError::Unsupported`]: equations of a plain top-to-bottom scan would be
//! wrong for it. `LABEL` alone only marks a place and passes the power.
//!
//! # Names
//!
//! Signals keep their exact LDmicro names (a back quote, which `.ii` cannot
//! quote, becomes `'`). Edge memories are `OSR_r5` (keyword and file rung number),
//! fresh outputs `CTU_Cpieces`, `RTO_Tfoo` (keyword and variable), `GEQ_r3`; a clash
//! with a program name adds `_2`, `_3`, …. An
//! intermediate value larger than 2 000 nodes is not inlined: reads see a fresh
//! `X_r7` instead (with a warning). Hypotheses are named after the logic rung
//! (rungs LDmicro skips as comments are not counted; `L{:02}`, wider for 100
//! rungs or more): a rung yielding one equation gives `L06`, several give `L06a`,
//! `L06b`, … in coil order, and a recurrence is `L03_scan`. An equation
//! is stated at the rung of the variable's *last* coil, so a set rung followed
//! by a reset rung yields one memory, named after the reset rung, and the set
//! rung's name is unused.
#![warn(missing_docs)]

use std::collections::{BTreeMap, BTreeSet};

use super::LadderError;
use super::ldmicro::{
    Circuit, CoilKind, CounterKind, EdgeKind, Element, ElementKind, LdProgram, Rung, TimerDelay,
    TimerKind,
};
use super::logic::{L, Tables, factors, product, simp, sum, summands};
use crate::diag::{Report, Severity, Sources, Span};
use crate::kernel::{Axiom, Rel};
use crate::syntax::print::{
    GoalKeyword, Notation, delay_to_string, goal_statement_to_string, name_to_string,
};
use crate::syntax::{Goal, Relation, Statement};
use crate::term::{Delay, Expr, Term, root};

/// What a signal of a compiled program is.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum SignalKind {
    /// An input bit the outside world writes (an `X` pin, an `I` or `M` Modbus bit): free.
    Input,
    /// Read but never written, and not an input: it keeps its power-up value `0*` (exact).
    Unwritten,
    /// Written by coils, name starting with `Y`: an output pin.
    Output,
    /// Written by coils, any other name (usually `R`): an internal relay.
    Relay,
    /// The memory of a one-shot or toggle coil: its input at the end of the scan, whose
    /// previous-scan value `pre` the edge compares with (LDmicro's hidden bit, 0 at first).
    EdgeMemory {
        /// File rung number (1-based, comment rungs counted).
        rung: usize,
        /// The element keyword (`OSR`, `OSF`, `ODR`, `COIL` for a toggle).
        element: String,
        /// The element's position among all the program's elements, in file order.
        index: usize,
    },
    /// The output of an element the algebra cannot express; unconstrained.
    Fresh {
        /// File rung number (1-based, comment rungs counted).
        rung: usize,
        /// The element keyword.
        element: String,
    },
}

impl SignalKind {
    /// Whether the program leaves this signal unconstrained (fresh outputs).
    pub fn is_unconstrained(&self) -> bool {
        matches!(self, SignalKind::Fresh { .. })
    }
}

/// What a hypothesis says about its rung.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HypothesisKind {
    /// `X = term`: exact.
    Equation,
    /// `X = G(pre X)`: a memory's value from its previous-scan value (the same rung as its
    /// `SR`/`RS` equation, named `Lnn_scan`).
    Recurrence,
}

/// One compiled fact about the program.
#[derive(Clone, Debug)]
pub struct Hypothesis {
    /// The name printed in proof traces (`L06a`, `L03_scan`).
    pub name: String,
    /// File rung number (1-based, comment rungs counted).
    pub rung: usize,
    /// The rung's span.
    pub span: Span,
    /// Equation or bound.
    pub kind: HypothesisKind,
    /// Left side.
    pub lhs: Expr,
    /// `=` or `⇒`.
    pub rel: Rel,
    /// Right side.
    pub rhs: Expr,
}

impl Hypothesis {
    /// The hypothesis as a goal of the `.ii` language (what `show` prints).
    pub fn goal(&self) -> Goal {
        let relation = match self.rel {
            Rel::Eq => Relation::Equals,
            Rel::Implies => Relation::Implies,
        };
        Goal { lhs: self.lhs.clone(), relation, rhs: self.rhs.clone(), after: None, pattern: None }
    }

    /// The hypothesis as a ground kernel axiom.
    pub fn axiom(&self) -> Axiom {
        Axiom::ground(self.name.clone(), self.lhs.clone(), self.rel, self.rhs.clone())
    }
}

/// Something the compiler could not express exactly; it is never dropped silently.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CompileWarning {
    /// File rung number (1-based, comment rungs counted).
    pub rung: usize,
    /// The logic rung name (`L07`), if the rung is not a comment rung.
    pub logic: Option<String>,
    /// The element's line (or the rung's span).
    pub span: Span,
    /// The element keyword (`OSR`, `CTU`, `COIL`, …).
    pub element: String,
    /// What was done about it.
    pub message: String,
}

impl CompileWarning {
    /// `rung 12 (L07)`: the rung, as printed in messages.
    pub fn rung_label(&self) -> String {
        match &self.logic {
            Some(l) => format!("rung {} ({l})", self.rung),
            None => format!("rung {}", self.rung),
        }
    }
}

impl CompileWarning {
    /// The whole warning with its place: `water.ld:80:5: rung 12 (L07): OSR: …`.
    pub fn describe(&self, sources: &Sources) -> String {
        format!("{}: {}", sources.location(self.span), Report::message(self))
    }

    /// The 1-based line of the element in its file.
    pub fn line(&self, sources: &Sources) -> usize {
        sources.line_col(self.span.file, self.span.start).0
    }
}

impl Report for CompileWarning {
    fn span(&self) -> Option<Span> {
        Some(self.span)
    }
    fn message(&self) -> String {
        format!("{}: {}: {}", self.rung_label(), self.element, self.message)
    }
    fn label(&self) -> String {
        "not expressed exactly".into()
    }
    fn severity(&self) -> Severity {
        Severity::Warning
    }
}

/// How TON/TOF delays are compiled.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum TimerModel {
    /// What the runtime counts (ldmicro.md §6.3): `P = floor(delay / cycle) + adjust` scans,
    /// so the term's delay is `P · cycle` (exact on every scan run).
    #[default]
    Plc,
    /// The paper's idealisation: the nominal delay as written, whatever the cycle.
    Ideal,
}

impl TimerModel {
    /// `plc` or `ideal`, as on the command line and in the JSON report.
    pub fn as_str(self) -> &'static str {
        match self {
            TimerModel::Plc => "plc",
            TimerModel::Ideal => "ideal",
        }
    }
}

/// Options of the rung compiler.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct CompileOptions {
    /// How timer delays are compiled.
    pub timers: TimerModel,
}

/// One TON/TOF timer as compiled: what the file says and the delay the equations use.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TimerInfo {
    /// File rung number.
    pub rung: usize,
    /// `TON` or `TOF`.
    pub keyword: String,
    /// The accumulator name.
    pub name: String,
    /// The delay field, in µs.
    pub delay_us: u64,
    /// The scan adjust (the field, or the header's default).
    pub adjust: i64,
    /// `P`, the scans the runtime counts (`floor(delay / cycle) + adjust`).
    pub scans: i64,
    /// The delay of the compiled term (`None`: the output follows the input, `P ≤ 0`).
    pub effective: Option<Delay>,
}

/// A compiled program: hypotheses in rung order, every signal, and warnings.
#[derive(Clone, Debug, Default)]
pub struct CompiledProgram {
    /// Equations and recurrences, in rung order.
    pub hypotheses: Vec<Hypothesis>,
    /// Every canonical signal name (program bits, `pre_` and fresh signals) and its kind.
    pub signals: BTreeMap<String, SignalKind>,
    /// Everything not expressed exactly, each naming its rung and element.
    pub warnings: Vec<CompileWarning>,
    /// How timer delays were compiled.
    pub timers: TimerModel,
    /// Every TON/TOF compiled as a timer term, in scan order.
    pub timer_info: Vec<TimerInfo>,
    /// The scan cycle, in µs (what `pre` steps back).
    pub cycle_us: u64,
    /// Whether names are used exactly, without LDmicro's one-letter kind prefixes being
    /// dropped for display and lookup (front ends with declared inputs: PLCopen).
    pub exact_names: bool,
    /// The short-name index of [`names`](super::names), built on first use from `signals`.
    pub(super) short_names: std::sync::OnceLock<BTreeMap<String, Vec<String>>>,
    /// The short names a property, script or REPL line has used: those print short.
    pub(super) spelled_short: super::names::Spellings,
    /// The equations' index ([`CompiledProgram::equation_index`]), built on first use.
    pub(super) equation_index: std::sync::OnceLock<EquationIndex>,
}

/// The program's equations `X = term` in scan order, and which define each name.
#[derive(Clone, Debug, Default)]
pub struct EquationIndex {
    /// Per equation in scan order: the name it defines and the index of its hypothesis.
    pub equations: Vec<(String, usize)>,
    /// Per name: the positions in `equations` of those that define it.
    pub defining: std::collections::HashMap<String, Vec<usize>>,
}

impl CompiledProgram {
    /// The scan cycle as a delay (`None` for a zero cycle).
    pub fn cycle(&self) -> Option<crate::term::Delay> {
        crate::term::Delay::from_micros(self.cycle_us).ok()
    }

    /// The scan cycle the kernel counts delays in. The readers refuse a zero cycle (an
    /// LDmicro `CYCLE=0`, a PLCopen interval of 0); a program built another way with one
    /// gets a cycle of 1 µs, which admits only delays of whole microseconds and no law
    /// whose side condition names the cycle beyond what 1 µs allows.
    pub fn scan_cycle(&self) -> crate::term::Delay {
        self.cycle().unwrap_or_else(|| crate::term::Delay::from_micros(1).expect("1 µs"))
    }

    /// Every hypothesis as a ground kernel axiom.
    pub fn axioms(&self) -> Vec<Axiom> {
        self.hypotheses.iter().map(Hypothesis::axiom).collect()
    }

    /// The equations `X = term` (kind equation, `=`, a name on the left) in scan order,
    /// indexed by name; built once.
    pub fn equation_index(&self) -> &EquationIndex {
        self.equation_index.get_or_init(|| {
            let mut index = EquationIndex::default();
            for (i, h) in self.hypotheses.iter().enumerate() {
                if h.kind != HypothesisKind::Equation || h.rel != Rel::Eq {
                    continue;
                }
                if let Term::Name(n) = &h.lhs[root(&h.lhs)] {
                    let at = index.equations.len();
                    index.defining.entry(n.as_str().to_string()).or_default().push(at);
                    index.equations.push((n.as_str().to_string(), i));
                }
            }
            index
        })
    }

    /// The hypothesis called `name`.
    pub fn hypothesis(&self, name: &str) -> Option<&Hypothesis> {
        self.hypotheses.iter().find(|h| h.name == name)
    }
}

/// The largest intermediate value (in nodes) inlined into later reads.
const MAX_INLINE: usize = 2_000;

/// Elements that change which rungs run (or stop the scan): a program using them is
/// refused, since the equations would describe a plain top-to-bottom scan.
const CONTROL_FLOW: &[(&str, &str)] = &[
    ("GOTO", "a jump skips rungs, which then keep their previous values"),
    ("GOSUB", "a subroutine call runs rungs out of order"),
    ("SUBPROG", "a subroutine body runs only when called, not in the scan"),
    ("ENDSUB", "a subroutine body runs only when called, not in the scan"),
    ("RETURN", "a return skips the rest of a subroutine or of the scan"),
    ("LOCK", "the program stops scanning here"),
    ("SLEEP", "the processor sleeps in the middle of the scan"),
];

/// Names the outside world writes: the program's declared inputs if it has them
/// ([`LdProgram::inputs`], PLCopen), else LDmicro's (ldmicro.md §5): `X` input pins,
/// `I` Modbus discrete inputs and `M` Modbus coils. Any other bit that no coil writes
/// stays `0*`.
fn is_external_input(program: &LdProgram, name: &str) -> bool {
    match &program.inputs {
        Some(inputs) => inputs.contains(name),
        None => name.starts_with(['X', 'I', 'M']),
    }
}

/// The canonical `.ii` name of an LDmicro name (a back quote cannot be quoted; it becomes `'`).
pub fn canonical(name: &str) -> String {
    name.replace('`', "'")
}

/// Compiles a program with the default options (PLC timer counts).
pub fn compile(program: &LdProgram) -> Result<CompiledProgram, Vec<LadderError>> {
    compile_with(program, &CompileOptions::default())
}

/// Compiles a program. Never panics. An element whose effect the equations cannot
/// describe soundly (control flow) refuses the program with a located error;
/// everything else not expressed exactly is a sound over-approximation and a warning.
pub fn compile_with(
    program: &LdProgram,
    options: &CompileOptions,
) -> Result<CompiledProgram, Vec<LadderError>> {
    let refused: Vec<LadderError> = program
        .elements()
        .filter_map(|e| {
            if let ElementKind::Coil { name, .. } = &e.kind
                && is_external_input(program, &canonical(name))
            {
                return Some(LadderError::Unsupported {
                    span: e.span,
                    keyword: "COIL".into(),
                    reason: format!(
                        "`{name}` is also written from outside the program ({}): what a rung \
                         reads depends on when that write comes, which ii-prove does not \
                         model; write a relay (`R…`) or an output (`Y…`) instead",
                        match (&program.inputs, name.chars().next()) {
                            (Some(_), _) => "a declared input",
                            (None, Some('X')) => "an input pin",
                            (None, Some('I')) => "a Modbus discrete input",
                            _ => "a Modbus coil, which the master writes",
                        }
                    ),
                });
            }
            let ElementKind::Other { keyword, .. } = &e.kind else { return None };
            let (_, why) = CONTROL_FLOW.iter().find(|(k, _)| k == keyword)?;
            Some(LadderError::Unsupported {
                span: e.span,
                keyword: keyword.clone(),
                reason: format!(
                    "{why}; ii-prove compiles only programs that run every rung once per scan, \
                     top to bottom"
                ),
            })
        })
        .collect();
    if !refused.is_empty() {
        return Err(refused);
    }
    let mut c = Compiler::new(program, *options);
    c.run();
    if !c.errors.is_empty() {
        return Err(std::mem::take(&mut c.errors));
    }
    Ok(c.finish())
}

struct Pending {
    var: String,
    rhs: L,
    /// For a memory, its scan recurrence `X = G(pre X)` (what induction over scans reads).
    recurrence: Option<L>,
}

struct Compiler<'a> {
    program: &'a LdProgram,
    options: CompileOptions,
    /// Logic rung names by rung index (None for comment rungs).
    logic: Vec<Option<String>>,
    /// Per coil-written variable, the global index of its last coil.
    last_coil: BTreeMap<String, usize>,
    /// Bits read but never written and not inputs: they stay `0*`; first reading rung.
    unwritten: BTreeMap<String, usize>,
    /// Timer accumulators written by more than one element.
    shared_timers: BTreeSet<String>,
    /// Every name the program uses (for fresh-name uniqueness).
    taken: BTreeSet<String>,
    /// Per variable, the internal name standing for its previous-scan value while the
    /// scan is compiled (`pre_X`); [`Compiler::exact`] turns each into `pre X`.
    pre_names: BTreeMap<String, String>,
    /// The inverse: internal previous-value name → the variable (or internal name) it is of.
    pre_of: BTreeMap<String, String>,
    fresh: BTreeMap<String, SignalKind>,
    // Scan state.
    coil_index: usize,
    /// What a read of each coil-written bit sees at this point of the scan, as a
    /// function of its previous-scan value `pre_X` (the signal `X` after its last coil).
    current: BTreeMap<String, L>,
    mcr: L,
    // Current rung.
    rung_idx: usize,
    pending: Vec<Pending>,
    // Output.
    hypotheses: Vec<Hypothesis>,
    warnings: Vec<CompileWarning>,
    /// What the equations cannot describe soundly with these options: the program is refused.
    errors: Vec<LadderError>,
    timer_info: Vec<TimerInfo>,
}

/// A circuit of conditions only (no side effects, no state): its output is `input · conductance`.
fn is_pure(c: &Circuit) -> bool {
    match c {
        Circuit::Series(items) | Circuit::Parallel(items) => items.iter().all(is_pure),
        Circuit::Element(e) => matches!(
            e.kind,
            ElementKind::Contacts { .. }
                | ElementKind::Short
                | ElementKind::Open
                | ElementKind::Comment(_)
        ),
    }
}

fn letters(mut k: usize) -> String {
    // 0 → a, 25 → z, 26 → aa, …
    let mut out = Vec::new();
    loop {
        out.push(b'a' + (k % 26) as u8);
        if k < 26 {
            break;
        }
        k = k / 26 - 1;
    }
    out.reverse();
    String::from_utf8(out).unwrap_or_default()
}

impl<'a> Compiler<'a> {
    fn new(program: &'a LdProgram, options: CompileOptions) -> Compiler<'a> {
        let n_logic = program.rungs.iter().filter(|r| !r.is_comment(&program.version)).count();
        let width = n_logic.to_string().len().max(2);
        let mut k = 0;
        let logic = program
            .rungs
            .iter()
            .map(|r| {
                if r.is_comment(&program.version) {
                    None
                } else {
                    k += 1;
                    Some(format!("L{k:0width$}"))
                }
            })
            .collect();
        let mut c = Compiler {
            program,
            options,
            logic,
            last_coil: BTreeMap::new(),
            unwritten: BTreeMap::new(),
            shared_timers: BTreeSet::new(),
            taken: BTreeSet::new(),
            pre_names: BTreeMap::new(),
            pre_of: BTreeMap::new(),
            fresh: BTreeMap::new(),
            coil_index: 0,
            current: BTreeMap::new(),
            mcr: L::One,
            rung_idx: 0,
            pending: Vec::new(),
            hypotheses: Vec::new(),
            warnings: Vec::new(),
            errors: Vec::new(),
            timer_info: Vec::new(),
        };
        c.prepass();
        c
    }

    fn live_rungs(&self) -> impl Iterator<Item = (usize, &'a Rung)> + 'a {
        let version = &self.program.version;
        self.program.rungs.iter().enumerate().filter(move |(_, r)| !r.is_comment(version))
    }

    fn prepass(&mut self) {
        for e in self.program.elements() {
            for n in e.names_read() {
                self.taken.insert(canonical(n));
            }
            for n in e.names_written() {
                self.taken.insert(canonical(&n));
            }
        }
        self.taken.extend(self.program.signals().iter().map(|s| canonical(s)));
        // Bits are written only by coils; timers, counters, RES, MOVE and the integer
        // elements write integers, a separate name space (ldmicro.md §5).
        let mut int_writers: BTreeMap<String, usize> = BTreeMap::new();
        let mut k = 0;
        let rungs: Vec<(usize, &Rung)> = self.live_rungs().collect();
        for (_, rung) in &rungs {
            for e in rung.elements() {
                match &e.kind {
                    ElementKind::Coil { name, .. } => {
                        self.last_coil.insert(canonical(name), k);
                        k += 1;
                    }
                    _ => {
                        for n in e.names_written() {
                            *int_writers.entry(canonical(&n)).or_default() += 1;
                        }
                    }
                }
            }
        }
        // A bit that no live coil writes and that is not an input stays 0*: a bit read in
        // a live rung (first such rung named), or one that occurs only in rungs LDmicro
        // skips (comment rungs).
        let live = rungs.iter().map(|(_, r)| *r);
        for rung in live.chain(&self.program.rungs) {
            for e in rung.elements() {
                if let ElementKind::Contacts { name, .. } | ElementKind::Coil { name, .. } = &e.kind
                {
                    let n = canonical(name);
                    if !self.last_coil.contains_key(&n) && !is_external_input(self.program, &n) {
                        self.unwritten.entry(n).or_insert(rung.number);
                    }
                }
            }
        }
        for e in self.program.elements() {
            if let ElementKind::Timer { name, .. } = &e.kind
                && int_writers.get(&canonical(name)).copied().unwrap_or(0) > 1
            {
                self.shared_timers.insert(canonical(name));
            }
        }
        let written: Vec<String> = self.last_coil.keys().cloned().collect();
        for x in written {
            let pre = self.pre_name(&x);
            self.current.insert(x, L::Var(pre));
        }
        for x in self.unwritten.keys() {
            self.current.insert(x.clone(), L::Zero);
        }
    }

    /// The internal name of `x`'s previous-scan value (made on first use).
    fn pre_name(&mut self, x: &str) -> String {
        if let Some(p) = self.pre_names.get(x) {
            return p.clone();
        }
        let pre = self.unique(&format!("pre_{x}"));
        self.pre_names.insert(x.to_string(), pre.clone());
        self.pre_of.insert(pre.clone(), x.to_string());
        pre
    }

    /// A term of the scan with every internal previous-value name replaced by `pre X`.
    fn exact(&self, e: &L) -> L {
        let mut names = Vec::new();
        e.names(&mut names);
        names.into_iter().filter(|n| self.pre_of.contains_key(n)).fold(e.clone(), |acc, p| {
            let of = self.exact(&L::Var(self.pre_of[&p].clone()));
            acc.subst(&p, &L::Pre(Box::new(of)))
        })
    }

    /// The previous-scan value of the power `input` at this point of the scan (LDmicro's
    /// hidden edge bit, 0 before the first scan): `pre X` when the power is one signal
    /// `X`, else `pre M` for a new memory `M = input` stated with this rung.
    fn previous_power(&mut self, e: &Element, base: &str, input: &L) -> L {
        if let L::Var(x) = input {
            return L::Var(self.pre_name(x));
        }
        let m = self.unique(&canonical(base));
        let rung = self.rung().number;
        let element = e.kind.keyword().to_string();
        let index = self.program.elements().position(|x| std::ptr::eq(x, e)).unwrap_or(usize::MAX);
        self.fresh.insert(m.clone(), SignalKind::EdgeMemory { rung, element, index });
        let pre = self.pre_name(&m);
        self.pending.push(Pending { var: m, rhs: input.clone(), recurrence: None });
        L::Var(pre)
    }

    fn unique(&mut self, base: &str) -> String {
        let mut name = base.to_string();
        let mut k = 2;
        while self.taken.contains(&name) {
            name = format!("{base}_{k}");
            k += 1;
        }
        self.taken.insert(name.clone());
        name
    }

    fn rung(&self) -> &'a Rung {
        &self.program.rungs[self.rung_idx]
    }

    fn warn(&mut self, span: Span, element: &str, message: String) {
        let rung = self.rung();
        self.warnings.push(CompileWarning {
            rung: rung.number,
            logic: self.logic.get(self.rung_idx).cloned().flatten(),
            span,
            element: element.to_string(),
            message,
        });
    }

    fn new_fresh(&mut self, base: &str, e: &Element, why: &str) -> L {
        let base = if base.starts_with(|c: char| c.is_ascii_digit()) {
            format!("_{base}")
        } else {
            base.to_string()
        };
        let name = self.unique(&canonical(&base));
        let rung = self.rung().number;
        let keyword = e.kind.keyword().to_string();
        self.fresh.insert(name.clone(), SignalKind::Fresh { rung, element: keyword.clone() });
        self.warn(
            e.span,
            &keyword,
            format!("{why}; it is modelled with the unconstrained signal {name}"),
        );
        L::Var(name)
    }

    fn run(&mut self) {
        let program = self.program;
        let version = &program.version;
        for idx in 0..self.program.rungs.len() {
            self.rung_idx = idx;
            let rung = self.rung();
            if rung.is_comment(version) {
                let extra =
                    rung.elements().iter().any(|e| !matches!(e.kind, ElementKind::Comment(_)));
                if extra {
                    self.warn(
                        rung.span,
                        "COMMENT",
                        "LDmicro skips a rung whose first element is a COMMENT; \
                         its other elements are not compiled"
                            .into(),
                    );
                }
                continue;
            }
            let input = self.mcr.clone();
            self.circuit(&rung.body, input);
            self.flush_rung();
        }
    }

    fn circuit(&mut self, c: &'a Circuit, input: L) -> L {
        match c {
            Circuit::Series(items) => {
                let is_coil = |item: &Circuit| {
                    matches!(item, Circuit::Element(Element { kind: ElementKind::Coil { .. }, .. }))
                };
                let last_other = items.iter().rposition(|item| !is_coil(item)).unwrap_or(0);
                for item in &items[..last_other] {
                    if let Circuit::Element(e) = item
                        && is_coil(item)
                    {
                        self.warn(
                            e.span,
                            e.kind.keyword(),
                            "a coil before other elements of its series: LDmicro's editor \
                             keeps coils at the end of a rung; here the power passes through it \
                             to them"
                                .into(),
                        );
                    }
                }
                items.iter().fold(input, |power, item| self.circuit(item, power))
            }
            Circuit::Parallel(branches) if branches.iter().all(is_pure) => {
                // Pure conditions: `i · (c1 + c2 + …)`, the readable factored form.
                let outs: Vec<L> = branches.iter().map(|b| self.circuit(b, L::One)).collect();
                simp(&input.and(sum(outs)))
            }
            Circuit::Parallel(branches) => {
                let outs: Vec<L> =
                    branches.iter().map(|b| self.circuit(b, input.clone())).collect();
                simp(&sum(outs))
            }
            Circuit::Element(e) => self.element(e, input),
        }
    }

    fn read(&mut self, name: &str) -> L {
        let name = canonical(name);
        if let Some(v) = self.current.get(&name) {
            return v.clone();
        }
        L::Var(name)
    }

    fn element(&mut self, e: &'a Element, input: L) -> L {
        match &e.kind {
            ElementKind::Contacts { name, negated } => {
                let v = self.read(name);
                let v = if *negated { v.negate() } else { v };
                simp(&input.and(v))
            }
            ElementKind::Coil { name, kind } => {
                self.coil(e, name, *kind, &input);
                input
            }
            ElementKind::Short | ElementKind::Comment(_) => input,
            ElementKind::Open => L::Zero,
            ElementKind::Placeholder => {
                self.warn(e.span, "PLACEHOLDER", "an empty editor slot, read as OPEN (0*)".into());
                L::Zero
            }
            ElementKind::MasterRelay => {
                self.mcr = simp(&self.mcr.clone().negate().or(input.clone()));
                input
            }
            ElementKind::Timer { kind, name, delay, adjust, adjust_given } => {
                self.timer(e, *kind, name, delay, (*adjust, *adjust_given), input)
            }
            ElementKind::Edge { kind: kind @ (EdgeKind::Osr | EdgeKind::Osf | EdgeKind::Odr) } => {
                // ldmicro.md §4: a hidden bit keeps the input of the previous scan (0 at
                // first): OSR `i · ¬pre i`, OSF `¬i · pre i`, ODR `¬(i · ¬pre i)`.
                let base = format!("{}_r{}", e.kind.keyword(), self.rung().number);
                let prev = self.previous_power(e, &base, &input);
                match kind {
                    EdgeKind::Osr => simp(&input.and(prev.negate())),
                    EdgeKind::Osf => simp(&input.negate().and(prev)),
                    _ => simp(&input.and(prev.negate()).negate()),
                }
            }
            ElementKind::Edge { .. } => {
                let base = format!("{}_r{}", e.kind.keyword(), self.rung().number);
                self.new_fresh(&base, e, "this one-shot is not expressible in the algebra")
            }
            ElementKind::Counter { kind, name, .. } => {
                if *kind == CounterKind::Ctc && self.program.version.is_orig() {
                    self.warn(
                        e.span,
                        "CTC",
                        format!(
                            "the count of {name} is not modelled; the output passes its \
                             input (orig CTC), exactly"
                        ),
                    );
                    input
                } else {
                    let base = format!("{}_{}", e.kind.keyword(), name);
                    self.new_fresh(&base, e, "a counter is not expressible in the algebra")
                }
            }
            ElementKind::Res { name } => {
                self.warn(
                    e.span,
                    "RES",
                    format!("resets the count of {name}: no Boolean effect; the power passes"),
                );
                input
            }
            ElementKind::Compare { .. } => {
                let base = format!("{}_r{}", e.kind.keyword(), self.rung().number);
                let f = self.new_fresh(&base, e, "a comparison of integers is not expressible");
                simp(&input.and(f))
            }
            ElementKind::Move { dest, .. } | ElementKind::Math { dest, .. } => {
                self.warn(
                    e.span,
                    e.kind.keyword(),
                    format!("writes the integer {dest}: no Boolean effect; the power passes"),
                );
                input
            }
            // A label only marks a place to jump to (jumps are refused, see `compile_with`).
            ElementKind::Other { keyword, .. } if keyword == "LABEL" => input,
            ElementKind::Other { keyword, .. } => {
                if crate::ladder::ldmicro::PASS_THROUGH.contains(&keyword.as_str()) {
                    self.warn(
                        e.span,
                        keyword,
                        "integer or peripheral operation: no Boolean effect; the power passes"
                            .into(),
                    );
                    input
                } else {
                    let why = "an integer, peripheral or text element is not expressible";
                    let base = format!("{keyword}_r{}", self.rung().number);
                    self.new_fresh(&base, e, why)
                }
            }
        }
    }

    fn timer(
        &mut self,
        e: &Element,
        kind: TimerKind,
        name: &str,
        delay: &TimerDelay,
        (adjust, adjust_given): (i64, bool),
        input: L,
    ) -> L {
        let keyword = e.kind.keyword().to_string();
        let cycle = self.program.cycle_us;
        let why = match (kind, delay) {
            _ if self.shared_timers.contains(&canonical(name)) => Some(format!(
                "the accumulator {name} is also written by another element (RES, MOVE, a SHIFT_REGISTER stage, PERSIST at power-up, another timer, …)"
            )),
            (TimerKind::Ton | TimerKind::Tof, TimerDelay::Variable(v)) => {
                Some(format!("a delay given by the variable {v} is not a constant"))
            }
            (TimerKind::Ton | TimerKind::Tof, TimerDelay::Micros(0)) => {
                Some("a zero delay is not a delay".into())
            }
            (TimerKind::Ton | TimerKind::Tof, _) if cycle == 0 => {
                Some("with a zero cycle the timer never expires".into())
            }
            (TimerKind::Ton | TimerKind::Tof, TimerDelay::Micros(_)) => None,
            _ => Some(format!("the {keyword} timer is not expressible in the algebra")),
        };
        let (TimerDelay::Micros(us), None) = (delay, &why) else {
            let why = why.unwrap_or_else(|| "the delay is not expressible".into());
            return self.new_fresh(&format!("{keyword}_{name}"), e, &why);
        };
        let us = *us;
        // ldmicro.md §6.3: the runtime counts P = floor(delay / cycle) + adjust scans; a
        // TON is on from the (P+1)-th consecutive scan with its input on, a TOF stays on
        // for P scans after its input falls. On scan runs that is exactly `d/IN` and
        // `IN/d` with d = P · cycle; with P ≤ 0 the output is the input.
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
            self.errors.push(LadderError::Unsupported {
                span: e.span,
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
            return self.new_fresh(&format!("{keyword}_{name}"), e, why);
        }
        if scans < 1 {
            self.warn(
                e.span,
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
                e.span,
                &keyword,
                format!(
                    "the runtime counts P = floor({us} µs / {cycle} µs) {} = {scans} scans of \
                     the cycle, so {name} times {effective}, not the {nominal} written{}; the \
                     equation uses {effective} (--timers ideal uses {nominal})",
                    signed(adjust),
                    if !adjust_given {
                        format!(" (the default adjust of an {} file)", self.program.version.label())
                    } else {
                        String::new()
                    }
                ),
            );
        }
        self.timer_info.push(TimerInfo {
            rung: self.rung().number,
            keyword: keyword.clone(),
            name: name.to_string(),
            delay_us: us,
            adjust,
            scans,
            effective: d.clone(),
        });
        match (d, kind) {
            (None, _) => input,
            (Some(d), TimerKind::Ton) => simp(&L::Ton(d, Box::new(input))),
            (Some(d), _) => simp(&L::Tof(Box::new(input), d)),
        }
    }

    fn coil(&mut self, e: &Element, name: &str, kind: CoilKind, input: &L) {
        let x = canonical(name);
        let k = self.coil_index;
        self.coil_index += 1;
        let Some(old) = self.current.get(&x).cloned() else {
            return;
        };
        // Which coil kind dominates (the last set or reset coil), for the memory's form.
        let dominant = match kind {
            CoilKind::Set => Some(false),
            CoilKind::Reset => Some(true),
            _ => None,
        };
        let g = match kind {
            CoilKind::Normal => input.clone(),
            CoilKind::Negated => input.clone().negate(),
            // Powers in file order, the kept previous value last: `S1 + S2 + pre_X`.
            CoilKind::Set => {
                let (with_pre, rest): (Vec<L>, Vec<L>) = summands(&old.or(input.clone()))
                    .into_iter()
                    .partition(|t| self.pre_names.get(&x).is_some_and(|p| t.mentions(p)));
                sum(rest.into_iter().chain(with_pre).collect())
            }
            CoilKind::Reset => input.clone().negate().and(old),
            CoilKind::Toggle => {
                // On a rising edge of the power the bit flips (ldmicro.md §4, COIL
                // ttrigger): the edge is `i · ¬pre i` over the coil's hidden bit.
                let base = format!("TOGGLE_r{}", self.rung().number);
                let prev = self.previous_power(e, &base, input);
                let edge = simp(&input.clone().and(prev.negate()));
                let flip = edge.clone().and(old.clone().negate());
                flip.or(edge.negate().and(old))
            }
        };
        let g = simp(&g);
        let pre = self.pre_names.get(&x).cloned().unwrap_or_default();
        if self.last_coil.get(&x) == Some(&k) {
            let rhs = self.finish_var(&pre, g.clone(), dominant);
            self.current.insert(x.clone(), L::Var(x.clone()));
            let recurrence = (rhs != g).then_some(g);
            self.pending.push(Pending { var: x, rhs, recurrence });
        } else if g.size() > MAX_INLINE {
            let name = self.unique(&format!("{x}_r{}", self.rung().number));
            let rung = self.rung().number;
            self.fresh.insert(name.clone(), SignalKind::Fresh { rung, element: "COIL".into() });
            self.warn(
                e.span,
                "COIL",
                format!(
                    "the intermediate value of {x} is too large to inline; later reads \
                     until its next coil see the unconstrained signal {name}"
                ),
            );
            self.current.insert(x, L::Var(name));
        } else {
            self.current.insert(x, g);
        }
    }

    /// The end-of-scan value `g(pre)` of `x` as a term: an equation, or a memory.
    fn finish_var(&self, pre: &str, g: L, prefer_rs: Option<bool>) -> L {
        if !g.mentions(pre) || g.mentions_temporally(pre) {
            return g;
        }
        let g0 = simp(&g.subst(pre, &L::Zero));
        let g1 = simp(&g.subst(pre, &L::One));
        let Some(t) = Tables::new(&[&g0, &g1]) else {
            return g;
        };
        if !t.implies(0, 1) {
            return g;
        }
        memory_form(&g, pre, g0, g1, prefer_rs).unwrap_or(g)
    }

    fn flush_rung(&mut self) {
        let pending = std::mem::take(&mut self.pending);
        if pending.is_empty() {
            return;
        }
        let rung = self.rung();
        let base = self.logic.get(self.rung_idx).cloned().flatten().unwrap_or_default();
        let several = pending.len() > 1;
        for (k, p) in pending.into_iter().enumerate() {
            let name = if several { format!("{base}{}", letters(k)) } else { base.clone() };
            let var = L::Var(p.var.clone()).to_expr();
            let rhs = self.exact(&p.rhs).to_expr();
            let recurrence = p.recurrence.as_ref().map(|g| self.exact(g).to_expr());
            let mut push = |name: String, kind, lhs: Expr, rel, rhs: Expr| {
                self.hypotheses.push(Hypothesis {
                    name,
                    rung: rung.number,
                    span: rung.span,
                    kind,
                    lhs,
                    rel,
                    rhs,
                });
            };
            push(name.clone(), HypothesisKind::Equation, var.clone(), Rel::Eq, rhs);
            if let Some(g) = recurrence {
                let n = format!("{name}_scan");
                push(n, HypothesisKind::Recurrence, var.clone(), Rel::Eq, g);
            }
        }
    }

    fn finish(mut self) -> CompiledProgram {
        // A bit nobody writes keeps its power-up value: reads saw `0*`, and the
        // equation lets properties mention it.
        for (x, rung) in std::mem::take(&mut self.unwritten) {
            let idx = self.program.rungs.iter().position(|r| r.number == rung).unwrap_or(0);
            let name = self.unique(&format!("unwritten_{x}"));
            self.hypotheses.push(Hypothesis {
                name,
                rung,
                span: self.program.rungs.get(idx).map_or(Span::new(0, 0..0), |r| r.span),
                kind: HypothesisKind::Equation,
                lhs: L::Var(x.clone()).to_expr(),
                rel: Rel::Eq,
                rhs: L::Zero.to_expr(),
            });
            self.fresh.insert(x, SignalKind::Unwritten);
        }
        let mut signals: BTreeMap<String, SignalKind> = BTreeMap::new();
        let written: BTreeSet<&String> = self.last_coil.keys().collect();
        let classify = |n: &str| -> SignalKind {
            if let Some(k) = self.fresh.get(n) {
                return k.clone();
            }
            if written.contains(&n.to_string()) {
                if n.starts_with('Y') { SignalKind::Output } else { SignalKind::Relay }
            } else {
                SignalKind::Input
            }
        };
        for s in self.program.signals() {
            let s = canonical(&s);
            let kind = classify(&s);
            signals.insert(s, kind);
        }
        for h in &self.hypotheses {
            for side in [&h.lhs, &h.rhs] {
                for node in side.as_ref() {
                    if let crate::term::Term::Name(n) = node {
                        let n = n.as_str();
                        if !signals.contains_key(n) {
                            signals.insert(n.to_string(), classify(n));
                        }
                    }
                }
            }
        }
        for (name, kind) in &self.fresh {
            if matches!(kind, SignalKind::Fresh { .. }) {
                signals.insert(name.clone(), kind.clone());
            }
        }
        CompiledProgram {
            hypotheses: self.hypotheses,
            signals,
            warnings: self.warnings,
            timers: self.options.timers,
            timer_info: self.timer_info,
            cycle_us: self.program.cycle_us,
            exact_names: self.program.inputs.is_some(),
            short_names: std::sync::OnceLock::new(),
            spelled_short: Default::default(),
            equation_index: std::sync::OnceLock::new(),
        }
    }
}

/// An adjust as written in a formula: `+ 5`, `- 1`.
fn signed(v: i64) -> String {
    if v < 0 { format!("- {}", v.unsigned_abs()) } else { format!("+ {v}") }
}

/// `¬y`, with De Morgan applied when every operand of `y` is a complement
/// (`¬(¬a · ¬b)` is written `a + b`).
fn readable_not(y: &L) -> L {
    let inner = |xs: &[L]| -> Option<Vec<L>> {
        xs.iter()
            .map(|x| match x {
                L::Not(i) => Some((**i).clone()),
                _ => None,
            })
            .collect()
    };
    match y {
        L::And(xs) => inner(xs).map_or_else(|| simp(&y.clone().negate()), |v| simp(&sum(v))),
        L::Or(xs) => inner(xs).map_or_else(|| simp(&y.clone().negate()), |v| simp(&product(v))),
        _ => simp(&y.clone().negate()),
    }
}

/// The memory `SR(g0, ¬g1)` (valid when `g0 ⇒ g1`) in its most readable checked form.
fn memory_form(g: &L, pre: &str, g0: L, g1: L, prefer_rs: Option<bool>) -> Option<L> {
    let p = L::var(pre);
    // RS(S, ¬Y): Y = g1, S = the factors of g0 not implied by g1.
    let y_rs = g1.clone();
    let f0 = factors(&g0);
    let kept: Vec<L> =
        f0.iter().filter(|f| super::logic::implies(&y_rs, f) != Some(true)).cloned().collect();
    let rs_dropped = kept.len() < f0.len();
    let s_rs = simp(&product(kept));
    // SR(S, ¬Y): S = g0, Y = the summands of g1 that do not imply g0.
    let s_sr = g0.clone();
    let f1 = summands(&g1);
    let kept: Vec<L> =
        f1.iter().filter(|f| super::logic::implies(f, &g0) != Some(true)).cloned().collect();
    let sr_dropped = kept.len() < f1.len();
    let y_sr = simp(&sum(kept));
    let rs = (s_rs.clone(), y_rs.clone());
    let sr = (s_sr.clone(), y_sr.clone());
    let size = |(s, y): &(L, L)| s.size() + y.size();
    let prefer_rs = match (rs_dropped, sr_dropped) {
        (true, false) => true,
        (false, true) => false,
        _ => prefer_rs.unwrap_or(size(&rs) < size(&sr)),
    };
    let candidates = if prefer_rs { [(true, rs), (false, sr)] } else { [(false, sr), (true, rs)] };
    for (is_rs, (s, y)) in candidates {
        let recurrence = if is_rs {
            s.clone().or(p.clone()).and(y.clone())
        } else {
            s.clone().or(p.clone().and(y.clone()))
        };
        if super::logic::equivalent(&recurrence, g) == Some(true) {
            let r = Box::new(readable_not(&y));
            let s = Box::new(s);
            return Some(simp(&if is_rs { L::Rs(s, r) } else { L::Sr(s, r) }));
        }
    }
    let fallback = L::Sr(Box::new(g0), Box::new(simp(&g1.negate())));
    Some(simp(&fallback))
}

type KindFilter = fn(&SignalKind) -> bool;

/// The compiled program as `.ii` text: a header comment, `input` lines declaring
/// every signal, the warnings as `//` comments naming their rung, and one
/// `assume` per hypothesis. It parses back with
/// [`parse_document`](crate::syntax::parse_document) and
/// [`NoProgram`](crate::syntax::NoProgram) to the same hypotheses.
pub fn program_to_ii(compiled: &CompiledProgram, notation: Notation) -> String {
    let mut out = String::new();
    out.push_str(&format!(
        "// Compiled from {} program by ii-prove (timers: {}).\n",
        if compiled.exact_names { "a PLCopen" } else { "an LDmicro" },
        match compiled.timers {
            TimerModel::Plc => "plc, the scans the runtime counts",
            TimerModel::Ideal => "ideal, the delays as written",
        }
    ));
    let count =
        |n: usize, one: &str, many: &str| format!("{n} {}", if n == 1 { one } else { many });
    out.push_str(&format!(
        "// {}, {}, {}. `pre X` is X's value at the previous scan (0 before the\n",
        count(compiled.hypotheses.len(), "hypothesis", "hypotheses"),
        count(compiled.signals.len(), "signal", "signals"),
        count(compiled.warnings.len(), "warning", "warnings")
    ));
    out.push_str("// first); with it this text describes scans, and reads back with a program.\n");
    let groups: [(&str, KindFilter); 6] = [
        ("inputs", |k| *k == SignalKind::Input),
        ("outputs", |k| *k == SignalKind::Output),
        ("relays", |k| *k == SignalKind::Relay),
        ("edge memories (the input of a one-shot or toggle coil)", |k| {
            matches!(k, SignalKind::EdgeMemory { .. })
        }),
        ("fresh outputs of unsupported elements (unconstrained)", |k| {
            matches!(k, SignalKind::Fresh { .. })
        }),
        ("bits no coil writes (always 0*)", |k| *k == SignalKind::Unwritten),
    ];
    for (title, pick) in groups {
        let names: Vec<String> = compiled
            .signals
            .iter()
            .filter(|(_, k)| pick(k))
            .map(|(n, _)| name_to_string(n))
            .collect();
        if names.is_empty() {
            continue;
        }
        out.push_str(&format!("\n// {title}\n"));
        for chunk in names.chunks(8) {
            out.push_str(&format!("input {}\n", chunk.join(", ")));
        }
    }
    if !compiled.timer_info.is_empty() {
        out.push_str(&format!("\n// timers (--timers {})\n", compiled.timers.as_str()));
        for t in &compiled.timer_info {
            let effective = match &t.effective {
                Some(d) => delay_to_string(d),
                None => "none: the output follows the input".into(),
            };
            out.push_str(&format!(
                "// rung {}: {} {} {} µs, adjust {}: P = {} scan{}; effective delay {}\n",
                t.rung,
                t.keyword,
                t.name,
                t.delay_us,
                t.adjust,
                t.scans,
                if t.scans == 1 { "" } else { "s" },
                effective
            ));
        }
    }
    if !compiled.warnings.is_empty() {
        out.push_str("\n// warnings\n");
        for w in &compiled.warnings {
            let text = format!("{}: {}: {}", w.rung_label(), w.element, w.message);
            let text: String = text.chars().map(|c| if c.is_control() { ' ' } else { c }).collect();
            out.push_str(&format!("// warning: {text}\n"));
        }
    }
    out.push('\n');
    let dummy = Span::new(0, 0..0);
    for h in &compiled.hypotheses {
        let statement =
            Statement { name: h.name.clone(), name_span: dummy, span: dummy, value: h.goal() };
        out.push_str(&goal_statement_to_string(GoalKeyword::Assume, &statement, notation));
        out.push('\n');
    }
    out
}
