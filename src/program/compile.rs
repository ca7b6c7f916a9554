//! The II compiler: a program of the scan model ([`Program`]) → ground hypotheses of the II algebra (exact equations) that hold at every scan of what the PLC runs (`shared/spec/semantics.md`, "Programs, scan by scan").
//!
//! # Model
//!
//! A scan runs every block once, top to bottom; inputs are constant during it, and
//! each read sees the last write before it in the scan. Expressions are read as
//! the algebra reads them: `·`, `+`, `¬`, constants, timers as `d/f` and `f/d`,
//! one-shots over hidden memories; the front ends turn their languages into them
//! (LDmicro's power flow, its master relay and its elements: `ladder::lower`;
//! PLCopen's statements: `ladder::plcopen::lower`).
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
//! Under `--timers ideal` a delay that is not a whole number of cycles refuses the
//! program with a located [`CompileError`]. (The front ends refuse what changes which
//! blocks run: LDmicro's `GOTO`, `GOSUB`, …)
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

mod ints;
pub mod start;
mod text;
mod timers;

use std::collections::{BTreeMap, BTreeSet};

use super::fast_hash::{FastMap as HashMap, FastSet as HashSet};

use super::logic::{
    L, Name, Tables, factors, product, simp, simp_and, simp_sum, simplify, sum, summands,
};
use super::{Block, BoolExpr, Memory, Program, Stmt, Temp, WriteKind};
use crate::diag::{Report, Severity, Sources, Span};
use crate::kernel::{Axiom, Rel};
use crate::syntax::{Goal, Relation};
use crate::term::{Delay, Expr, Symbol, Term, root};
pub use text::program_to_ii;
use timers::edge_of;

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
    /// Bit `bit` of an integer variable's stored value: the value itself, or the value
    /// xor its power-up value when that is not 0 (`start` is that bit of it), so that
    /// every bit starts at 0.
    IntBit {
        /// The variable.
        of: String,
        /// Which bit (0 the least significant).
        bit: u32,
        /// The bit of the power-up value the stored bit is flipped by.
        start: bool,
        /// Whether the outside world writes the variable.
        input: bool,
    },
    /// A comparison atom of the properties (`[Cparts >= 10]`), defined by an equation
    /// over the integers' bits.
    Atom,
    /// The input a timer called under a condition last received (`H = g·i + ¬g·pre H`
    /// for the call's condition `g` and input `i`, 0 at first): what the runtime's timer
    /// times between its calls. Also the parts of the state of a timer called at several
    /// places (`T_runs`, `T_due`, `T_holds`: how its run stood at the end of the scan).
    HeldInput {
        /// File rung number (1-based, comment rungs counted).
        rung: usize,
    },
    /// A part of an integer computation too large to copy into every read, named and
    /// defined by an exact equation stated with its block.
    Intermediate {
        /// File rung number (1-based, comment rungs counted).
        rung: usize,
    },
    /// Under `--any-state`: `1*` at every scan, so that its `pre` is 0 at the first scan
    /// only (where the state's free start values are read).
    Started,
    /// The output of an element the algebra cannot express, or a peripheral read;
    /// unconstrained.
    Fresh {
        /// File rung number (1-based, comment rungs counted).
        rung: usize,
        /// The element keyword.
        element: String,
        /// Whether it is what the world outside the scan answers (a peripheral read),
        /// free by nature, rather than an element ii-prove leaves out.
        peripheral: bool,
    },
}

impl SignalKind {
    /// Whether the program leaves this signal unconstrained (fresh outputs).
    pub fn is_unconstrained(&self) -> bool {
        matches!(self, SignalKind::Fresh { .. })
    }

    /// Whether the outside world sets this signal at every scan: an input, or a bit of
    /// an integer input.
    pub fn is_input(&self) -> bool {
        matches!(self, SignalKind::Input | SignalKind::IntBit { input: true, .. })
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
        let (lhs, rhs, relation) = (self.lhs.clone(), self.rhs.clone(), self.relation());
        Goal { lhs, relation, rhs, after: None, pattern: None }
    }

    /// `=` or `⇒`, as the `.ii` language writes it.
    pub fn relation(&self) -> Relation {
        match self.rel {
            Rel::Eq => Relation::Equals,
            Rel::Implies => Relation::Implies,
        }
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
    /// What a block is called (`rung`, `line`).
    pub noun: &'static str,
    /// What was done about it.
    pub message: String,
}

impl CompileWarning {
    /// `rung 12 (L07)`: the rung, as printed in messages.
    pub fn rung_label(&self) -> String {
        match &self.logic {
            Some(l) => format!("{} {} ({l})", self.noun, self.rung),
            None => format!("{} {}", self.noun, self.rung),
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
    /// Whether the program's state starts arbitrary instead of at its power-up values
    /// (`equiv --any-state`; see [`start`]).
    pub any_state: bool,
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
    /// The source language, as `show` names it (`an LDmicro`, `a PLCopen`).
    pub language: &'static str,
    /// What a block of the source is called (`rung`, `line`).
    pub block_noun: &'static str,
    /// The short-name index of [`names`](super::names), built on first use from `signals`.
    pub(super) short_names: std::sync::OnceLock<BTreeMap<String, Vec<String>>>,
    /// The short names a property, script or REPL line has used: those print short.
    pub(super) spelled_short: super::names::Spellings,
    /// The equations' index ([`CompiledProgram::equation_index`]), built on first use.
    pub(super) equation_index: std::sync::OnceLock<EquationIndex>,
    /// The integer variables, compiled into bits ([`SignalKind::IntBit`]).
    pub integers: BTreeMap<String, super::IntVar>,
    /// The comparison atoms properties have used ([`CompiledProgram::with_atoms`]).
    pub(super) atoms: super::atoms::Atoms,
    /// Under `--any-state` ([`CompileOptions::any_state`]): each free start value, by its
    /// name, and the state it is the value of at the first scan.
    pub starts: BTreeMap<String, start::StartOf>,
    /// Under `--any-state`: the signal that is 1 at every scan, whose `pre` is 0 only at
    /// the first scan.
    pub started: Option<String>,
    /// Under `--any-state`: the front end's start-up flag ([`Program::started`]), which
    /// starts at 1.
    pub start_flag: Option<String>,
    /// How many scans a run may need before an integer reaches a constant of the program
    /// (`2·|k| + 2` for the largest constant `k`, at most 10,000; 0 without integers): a
    /// counter counting edges needs two scans per step. The bounded searches go that far.
    pub int_depth: usize,
    /// The program's integer constants ([`CompiledProgram::bound_hints`] compares its
    /// integers with them).
    pub constants: Vec<i64>,
}

/// The program's equations `X = term` in scan order, and which define each name.
#[derive(Clone, Debug, Default)]
pub struct EquationIndex {
    /// Per equation in scan order: the name it defines and the index of its hypothesis.
    pub equations: Vec<(String, usize)>,
    /// Per name: the positions in `equations` of those that define it.
    pub defining: HashMap<String, Vec<usize>>,
    /// Per name: the hypotheses (any kind, by index) that mention it, in order.
    pub mentioning: HashMap<Symbol, Vec<usize>>,
    /// The hypotheses that mention no name.
    pub nameless: Vec<usize>,
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
                let mut named = BTreeSet::new();
                for node in h.lhs.as_ref().iter().chain(h.rhs.as_ref()) {
                    if let Term::Name(n) = node {
                        named.insert(*n);
                    }
                }
                if named.is_empty() {
                    index.nameless.push(i);
                }
                for n in named {
                    index.mentioning.entry(n).or_default().push(i);
                }
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

/// The canonical `.ii` name of a source name (a back quote cannot be quoted; it becomes `'`).
pub fn canonical(name: &str) -> String {
    name.replace('`', "'")
}

/// What the equations cannot describe soundly with the options asked for: the program is
/// refused, at the element.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CompileError {
    /// The element.
    pub span: Span,
    /// Its keyword.
    pub keyword: String,
    /// Why, and what to do instead.
    pub reason: String,
}

/// Compiles a program. Never panics. Everything not expressed exactly is a sound
/// over-approximation and a warning; what the options make inexpressible (a delay that is
/// not a whole number of cycles under `--timers ideal`) refuses the program.
pub fn compile(
    program: &Program,
    options: &CompileOptions,
) -> Result<CompiledProgram, Vec<CompileError>> {
    compile_then(program, options, true, |c| c.finish())
}

/// Whether [`compile`] accepts the program (else its errors), without stating the
/// equations: for a caller that only asks whether a body can be compiled.
pub fn accepts(program: &Program, options: &CompileOptions) -> Result<(), Vec<CompileError>> {
    compile_then(program, options, false, |_| ())
}

/// Runs the compiler over the program (stating its equations if `equations`), then
/// `then` on it, or the errors that refuse the program.
fn compile_then<T>(
    program: &Program,
    options: &CompileOptions,
    equations: bool,
    then: impl FnOnce(Compiler<'_>) -> T,
) -> Result<T, Vec<CompileError>> {
    // From an arbitrary state the power-up values play no part: integers are stored
    // as their values, every bit of them a start value.
    let arbitrary;
    let program = match options.any_state {
        true => {
            arbitrary = start::without_start_values(program);
            &arbitrary
        }
        false => program,
    };
    let mut c = Compiler::new(program, *options);
    c.equations = equations;
    c.run();
    if !c.errors.is_empty() {
        return Err(std::mem::take(&mut c.errors));
    }
    Ok(then(c))
}

struct Pending {
    var: String,
    rhs: L,
    /// For a memory, its scan recurrence `X = G(pre X)` (what induction over scans reads).
    recurrence: Option<L>,
}

struct Compiler<'a> {
    program: &'a Program,
    options: CompileOptions,
    /// Whether the equations are stated (else only the errors are looked for).
    equations: bool,
    /// Per written variable, the global index of its last write.
    last_write: HashMap<String, usize>,
    /// Bits read but never written and not inputs: they stay `0*`; first reading block.
    unwritten: BTreeMap<String, usize>,
    /// Timer accumulators written by more than one element.
    shared_timers: BTreeSet<String>,
    /// The IEC timer instances called at several places, followed call by call.
    repeated: BTreeMap<String, timers::Repeated>,
    /// Every name the program uses (for fresh-name uniqueness).
    taken: HashSet<String>,
    /// Per base name, the suffix [`Compiler::unique`] tries next (the ones below are taken).
    suffixes: crate::program::unique::Suffixes,
    /// Per variable, the internal name standing for its previous-scan value while the
    /// scan is compiled (`pre_X`); [`Compiler::exact`] turns each into `pre X`.
    pre_names: HashMap<String, Name>,
    /// The inverse: internal previous-value name → the variable (or internal name) it is of.
    pre_of: HashMap<Name, String>,
    fresh: BTreeMap<String, SignalKind>,
    // Scan state.
    write_index: usize,
    /// How many `If`s the statement being compiled is inside.
    depth: usize,
    /// The condition under which the statement being compiled runs (its `If`s' branch
    /// conditions; `1` outside them).
    guard: L,
    /// The outermost `If` being compiled.
    if_span: Option<Span>,
    /// What a read of each written bit sees at this point of the scan, as a
    /// function of its previous-scan value `pre_X` (the signal `X` after its last write).
    current: HashMap<String, L>,
    /// The scan-local values still to be read.
    temps: HashMap<Temp, L>,
    /// Per block (by index), the scan-local values no later block reads: dropped once
    /// the block is compiled.
    temps_done: Vec<Vec<Temp>>,
    // Current block.
    block: usize,
    pending: Vec<Pending>,
    // Output.
    hypotheses: Vec<Hypothesis>,
    warnings: Vec<CompileWarning>,
    /// What the equations cannot describe soundly with these options: the program is refused.
    errors: Vec<CompileError>,
    timer_info: Vec<TimerInfo>,
    /// Under `--any-state`: per variable whose previous-scan value is read, its free
    /// start value; and the signal telling the first scan.
    starts: BTreeMap<String, String>,
    started: Option<String>,
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
    fn new(program: &'a Program, options: CompileOptions) -> Compiler<'a> {
        let mut c = Compiler {
            program,
            options,
            equations: true,
            last_write: HashMap::default(),
            unwritten: BTreeMap::new(),
            shared_timers: BTreeSet::new(),
            repeated: BTreeMap::new(),
            taken: HashSet::default(),
            suffixes: Default::default(),
            pre_names: HashMap::default(),
            pre_of: HashMap::default(),
            fresh: BTreeMap::new(),
            write_index: 0,
            depth: 0,
            guard: L::One,
            if_span: None,
            current: HashMap::default(),
            temps: HashMap::default(),
            temps_done: Vec::new(),
            block: 0,
            pending: Vec::new(),
            hypotheses: Vec::new(),
            warnings: Vec::new(),
            errors: Vec::new(),
            timer_info: Vec::new(),
            starts: BTreeMap::new(),
            started: None,
        };
        c.prepass();
        if options.any_state {
            c.started = Some(c.unique("started"));
        }
        c
    }

    fn prepass(&mut self) {
        let program = self.program;
        self.taken.reserve(program.names.len() + program.signals.len());
        self.taken.extend(program.names.iter().cloned());
        self.taken.extend(program.signals.iter().cloned());
        // Writes are numbered in scan order (an `If`'s branches in order), as `run`
        // meets them; reads are listed with their block.
        let mut writes: Vec<String> = Vec::new();
        let mut reads: Vec<(String, usize)> = Vec::new();
        let int_reads = |e: &super::IntExpr, reads: &mut Vec<(String, usize)>, number| {
            e.visit(
                &mut |x| {
                    let w = program.integers.get(x).map_or(0, |v| v.ty.bits);
                    reads.extend((0..w).map(|k| (Program::int_bit(x, k), number)));
                },
                &mut |_| {},
            );
        };
        // The last block defining or reading each scan-local value.
        let mut temp_last: HashMap<Temp, usize> = HashMap::default();
        for (idx, b) in program.blocks.iter().enumerate() {
            let (mut lets, mut temp_reads) = (Vec::new(), Vec::new());
            for s in &b.stmts {
                let mut int_writes: Vec<(String, u32)> = Vec::new();
                let mut set_reads: Vec<super::IntExpr> = Vec::new();
                s.visit(
                    &mut |s| match s {
                        Stmt::Let { temp, .. } => lets.push(*temp),
                        Stmt::Write { target, .. } => writes.push(target.clone()),
                        Stmt::SetInt { target, value, .. } => {
                            let w = program.integers.get(target).map_or(0, |v| v.ty.bits);
                            writes.extend((0..w).map(|k| Program::int_bit(target, k)));
                            int_writes.push((target.clone(), w));
                            set_reads.push(value.clone());
                        }
                        _ => {}
                    },
                    &mut |x| match x {
                        BoolExpr::Temp(t) => temp_reads.push(*t),
                        BoolExpr::Var(n) => reads.push((n.clone(), b.number)),
                        BoolExpr::Compare(c) => {
                            int_reads(&c.a, &mut reads, b.number);
                            int_reads(&c.b, &mut reads, b.number);
                        }
                        _ => {}
                    },
                );
                for e in &set_reads {
                    int_reads(e, &mut reads, b.number);
                }
            }
            temp_last.extend(lets.into_iter().chain(temp_reads).map(|t| (t, idx)));
        }
        let n = writes.len();
        self.last_write.reserve(n);
        self.pre_names.reserve(n);
        self.pre_of.reserve(n);
        self.current.reserve(n);
        for (k, target) in writes.into_iter().enumerate() {
            self.last_write.insert(target, k);
        }
        self.temps_done = vec![Vec::new(); program.blocks.len()];
        for (t, idx) in temp_last {
            self.temps_done[idx].push(t);
        }
        // A bit that nothing writes and that is not an input stays 0*: a bit read in the
        // scan (first such block named), or one named only in code the PLC skips.
        for (n, number) in reads.into_iter().chain(program.skipped.iter().cloned()) {
            if !self.last_write.contains_key(&n) && !self.is_input(&n) {
                self.unwritten.entry(n).or_insert(number);
            }
        }
        self.shared_timers = program.shared_timers();
        self.prepare_repeated();
        let mut written: Vec<String> = self.last_write.keys().cloned().collect();
        written.sort_unstable();
        for x in written {
            let pre = self.pre_name(&x);
            self.current.insert(x, L::Var(pre));
        }
        for x in self.unwritten.keys() {
            self.current.insert(x.clone(), L::Zero);
        }
    }

    /// Whether the outside world writes the bit `n` (an input, or a bit of an input
    /// integer).
    fn is_input(&self, n: &str) -> bool {
        self.program.inputs.contains(n)
            || matches!(self.int_bit_kind(n), Some(SignalKind::IntBit { input: true, .. }))
    }

    /// The internal name of `x`'s previous-scan value (made on first use).
    fn pre_name(&mut self, x: &str) -> Name {
        if let Some(p) = self.pre_names.get(x) {
            return p.clone();
        }
        let pre: Name = self.unique(&format!("pre_{x}")).into();
        if self.options.any_state && self.program.started.as_deref() != Some(x) {
            let start = self.unique(&format!("start_{x}"));
            self.starts.insert(x.to_string(), start);
        }
        self.pre_names.insert(x.to_string(), pre.clone());
        self.pre_of.insert(pre.clone(), x.to_string());
        pre
    }

    /// A term of the scan with every internal previous-value name replaced by `pre X`.
    fn exact(&self, e: &L) -> L {
        e.substitute(&|p| {
            let x = self.pre_of.get(p)?;
            let of = L::Pre(Box::new(self.exact(&L::var(x))));
            Some(self.start_or(x, of))
        })
    }

    /// The previous-scan value of the power `input` at this point of the scan (a
    /// one-shot's hidden bit, 0 before the first scan): `pre X` when the power is one
    /// signal `X`, else `pre M` for a new memory `M = input` stated with this block.
    fn previous_power(&mut self, memory: &Memory, input: &L) -> L {
        // From an arbitrary state the hidden bit is not the power's previous value.
        if let (L::Var(x), false) = (input, self.options.any_state) {
            return L::Var(self.pre_name(x));
        }
        let m = self.unique(&canonical(&memory.base));
        let rung = self.block().number;
        let element = memory.element.clone();
        self.fresh.insert(m.clone(), SignalKind::EdgeMemory { rung, element, index: memory.index });
        let pre = self.pre_name(&m);
        self.pending.push(Pending { var: m, rhs: input.clone(), recurrence: None });
        L::Var(pre)
    }

    /// `base`, else the first of `base_2`, `base_3`, … not taken: a new name.
    fn unique(&mut self, base: &str) -> String {
        let taken = &self.taken;
        let name = self.suffixes.unique(base, |n| taken.contains(n));
        self.taken.insert(name.clone());
        name
    }

    fn block(&self) -> &'a Block {
        &self.program.blocks[self.block]
    }

    fn warn(&mut self, span: Span, element: &str, message: String) {
        let block = self.block();
        self.warnings.push(CompileWarning {
            rung: block.number,
            logic: block.label.clone(),
            span,
            element: element.to_string(),
            noun: self.program.block_noun,
            message,
        });
    }

    fn new_fresh(&mut self, base: &str, keyword: &str, span: Span, why: &str) -> L {
        self.new_free(base, keyword, span, why, false)
    }

    /// A free signal: the output of an element the algebra cannot express, or a
    /// peripheral read.
    fn new_free(
        &mut self,
        base: &str,
        keyword: &str,
        span: Span,
        why: &str,
        peripheral: bool,
    ) -> L {
        let base = if base.starts_with(|c: char| c.is_ascii_digit()) {
            format!("_{base}")
        } else {
            base.to_string()
        };
        let name = self.unique(&canonical(&base));
        let rung = self.block().number;
        let element = keyword.to_string();
        self.fresh.insert(name.clone(), SignalKind::Fresh { rung, element, peripheral });
        let what = if peripheral { "the free input" } else { "the unconstrained signal" };
        self.warn(span, keyword, format!("{why}; it is modelled with {what} {name}"));
        L::Var(name.into())
    }

    fn run(&mut self) {
        let program = self.program;
        for (idx, block) in program.blocks.iter().enumerate() {
            self.block = idx;
            for s in &block.stmts {
                self.stmt(s);
            }
            self.flush_block();
            for t in std::mem::take(&mut self.temps_done[idx]) {
                self.temps.remove(&t);
            }
        }
    }

    fn stmt(&mut self, s: &Stmt) {
        match s {
            Stmt::Let { temp, value } => {
                let v = self.eval(value);
                self.temps.insert(*temp, v);
            }
            Stmt::Write { target, kind, value, span } => {
                let v = self.eval(value);
                self.write(*span, target, kind, &v);
            }
            Stmt::If { branches, otherwise, span } => self.choice(branches, otherwise, *span),
            Stmt::SetInt { target, value, span } => self.set_int(target, value, *span),
            Stmt::Warn { span, element, message } => self.warn(*span, element, message.clone()),
        }
    }

    /// An `If`: each branch from the state before it, then the values merged by the
    /// conditions (`c1 · v1 + ¬c1 · (c2 · v2 + ¬c2 · v3)`). The equation of a bit whose
    /// last write is inside is stated once the whole outermost `If` is done.
    fn choice(&mut self, branches: &[(BoolExpr, Vec<Stmt>)], otherwise: &[Stmt], span: Span) {
        let first_write = self.write_index;
        if self.depth == 0 {
            self.if_span = Some(span);
        }
        self.depth += 1;
        let conditions: Vec<L> = branches.iter().map(|(c, _)| self.eval(c)).collect();
        let entry = self.current.clone();
        let outer = self.guard.clone();
        let mut outcomes = Vec::new();
        let mut none_before = L::One;
        for (k, body) in branches.iter().map(|(_, b)| b.as_slice()).chain([otherwise]).enumerate() {
            // A branch runs where no earlier condition holds and its own does.
            let own = conditions.get(k).cloned().unwrap_or(L::One);
            self.guard =
                simplify(L::And(vec![outer.clone(), none_before.clone(), own.clone()].into()));
            none_before = simplify(none_before.and(own.negate()));
            self.current = entry.clone();
            for s in body {
                self.stmt(s);
            }
            outcomes.push(std::mem::take(&mut self.current));
        }
        self.guard = outer;
        self.depth -= 1;
        let Some(mut merged) = outcomes.pop() else { return };
        for (c, outcome) in conditions.iter().zip(outcomes).rev() {
            let mut outcome: Vec<(String, L)> = outcome.into_iter().collect();
            outcome.sort_unstable_by(|a, b| a.0.cmp(&b.0));
            for (x, v) in outcome {
                let other = merged.get(&x).cloned().unwrap_or(L::Zero);
                if v != other {
                    let mux = c.clone().and(v).or(c.clone().negate().and(other));
                    let g = simp(&mux);
                    let g = self.bounded(&x, g, span);
                    merged.insert(x, g);
                }
            }
        }
        self.current = merged;
        if self.depth > 0 {
            return;
        }
        // The bits whose last write was inside: their end-of-scan values.
        let mut last: Vec<String> = self
            .last_write
            .iter()
            .filter(|(_, k)| (first_write..self.write_index).contains(*k))
            .map(|(x, _)| x.clone())
            .collect();
        last.sort_unstable();
        for x in last {
            let g = self.current.get(&x).cloned().unwrap_or(L::Zero);
            self.state(x, g, None);
        }
    }

    fn read(&mut self, name: &str) -> L {
        if let Some(v) = self.current.get(name) {
            return v.clone();
        }
        L::var(name)
    }

    fn eval(&mut self, e: &BoolExpr) -> L {
        match e {
            BoolExpr::Const(true) => L::One,
            BoolExpr::Const(false) => L::Zero,
            BoolExpr::Var(n) => self.read(n),
            BoolExpr::Temp(t) => self.temps.get(t).cloned().unwrap_or(L::Zero),
            BoolExpr::Not(x) => self.eval(x).negate(),
            BoolExpr::And(a, b) => {
                let a = self.eval(a);
                let b = self.eval(b);
                simp_and(a, b)
            }
            BoolExpr::Or(xs) => {
                let outs: Vec<L> = xs.iter().map(|x| self.eval(x)).collect();
                simp_sum(outs)
            }
            BoolExpr::Timer(t) if self.repeated.contains_key(&t.accumulator) => {
                let input = self.eval(&t.input);
                self.repeated_call(t, input)
            }
            BoolExpr::Timer(t) if self.depth > 0 && t.called && !self.options.any_state => {
                let input = self.eval(&t.input);
                let rung = self.block().number;
                let base = format!("{}_IN", canonical(&t.accumulator));
                let held = self.held_input(&base, &input, SignalKind::HeldInput { rung });
                self.timer(t, L::var(&held))
            }
            BoolExpr::Edge { kind, input, memory } if self.depth > 0 && !self.options.any_state => {
                let input = self.eval(input);
                let rung = self.block().number;
                let element = memory.element.clone();
                let kind_of = SignalKind::EdgeMemory { rung, element, index: memory.index };
                let held = self.held_input(&canonical(&memory.base), &input, kind_of);
                let prev = L::Var(self.pre_name(&held));
                edge_of(*kind, input, prev)
            }
            BoolExpr::Timer(_) | BoolExpr::Edge { .. } if self.depth > 0 => {
                self.conditional_memory();
                L::Zero
            }
            BoolExpr::Timer(t) => {
                let input = self.eval(&t.input);
                self.timer(t, input)
            }
            BoolExpr::Edge { kind, input, memory } => {
                // A hidden bit keeps the input of the previous scan (0 at first): rising
                // `i · ¬pre i`, falling `¬i · pre i`, not rising `¬(i · ¬pre i)`.
                let input = self.eval(input);
                let prev = self.previous_power(memory, &input);
                edge_of(*kind, input, prev)
            }
            BoolExpr::Fresh(f) => self.new_free(&f.base, &f.keyword, f.span, &f.why, f.peripheral),
            BoolExpr::Compare(c) => {
                let span = self.block().span;
                self.compare(c, span)
            }
        }
    }

    fn write(&mut self, span: Span, x: &str, kind: &WriteKind, input: &L) {
        let x = x.to_string();
        let k = self.write_index;
        self.write_index += 1;
        // A plain coil does not read the value it replaces: no copy of it.
        let old = match kind {
            WriteKind::Assign | WriteKind::AssignNot => {
                self.current.contains_key(&x).then_some(L::Zero)
            }
            _ => self.current.get(&x).cloned(),
        };
        let Some(old) = old else {
            return;
        };
        // Which write kind dominates (the last set or reset), for the memory's form.
        let dominant = match kind {
            WriteKind::Set => Some(false),
            WriteKind::Reset => Some(true),
            _ => None,
        };
        let g = match kind {
            WriteKind::Assign => input.clone(),
            WriteKind::AssignNot => input.clone().negate(),
            // Powers in scan order, the kept previous value last: `S1 + S2 + pre_X`.
            WriteKind::Set => {
                let (with_pre, rest): (Vec<L>, Vec<L>) = summands(&old.or(input.clone()))
                    .into_iter()
                    .partition(|t| self.pre_names.get(&x).is_some_and(|p| t.mentions(p)));
                sum(rest.into_iter().chain(with_pre).collect())
            }
            WriteKind::Reset => input.clone().negate().and(old),
            WriteKind::Toggle(_) if self.depth > 0 => {
                self.conditional_memory();
                old
            }
            WriteKind::Toggle(memory) => {
                // On a rising edge of the power the bit flips: the edge is `i · ¬pre i`
                // over the hidden bit.
                let prev = self.previous_power(memory, input);
                let edge = simplify(input.clone().and(prev.negate()));
                let flip = edge.clone().and(old.clone().negate());
                flip.or(edge.negate().and(old))
            }
        };
        let g = simp(&g);
        if self.depth > 0 {
            // Inside an `If`: the value for now; the outermost `If` states the equation.
            let g = self.bounded(&x, g, span);
            self.current.insert(x, g);
            return;
        }
        if self.last_write.get(&x) == Some(&k) {
            self.state(x, g, dominant);
        } else {
            let g = self.bounded(&x, g, span);
            self.current.insert(x, g);
        }
    }

    /// An intermediate value of `x` as later reads see it: `g`, or an unconstrained
    /// signal (with a warning) when `g` is too large to inline.
    fn bounded(&mut self, x: &str, g: L, span: Span) -> L {
        if g.size() <= MAX_INLINE {
            return g;
        }
        let name = self.unique(&format!("{x}_r{}", self.block().number));
        let rung = self.block().number;
        let element = "COIL".into();
        self.fresh.insert(name.clone(), SignalKind::Fresh { rung, element, peripheral: false });
        self.warn(
            span,
            "COIL",
            format!(
                "the intermediate value of {x} is too large to inline; later reads \
                 until its next coil see the unconstrained signal {name}"
            ),
        );
        L::Var(name.into())
    }

    /// `x`'s last write is done: its end-of-scan value `g` is stated with this block
    /// (as a memory where it is one), and later reads see the signal `x` itself.
    fn state(&mut self, x: String, g: L, dominant: Option<bool>) {
        let pre = self.pre_names.get(&x).cloned().unwrap_or_default();
        let (rhs, recurrence) = self.finish_var(&pre, g, dominant);
        self.current.insert(x.clone(), L::var(&x));
        self.pending.push(Pending { var: x, rhs, recurrence });
    }

    /// The end-of-scan value `g(pre)` of `x` as a term: an equation, or a memory; with
    /// the scan recurrence `g` itself where it differs from that term.
    fn finish_var(&self, pre: &str, g: L, prefer_rs: Option<bool>) -> (L, Option<L>) {
        // `SR`/`RS` start at 0: from an arbitrary state the scan recurrence is the equation.
        if !g.mentions(pre) || g.mentions_temporally(pre) || self.options.any_state {
            return (g, None);
        }
        let g0 = simplify(g.subst(pre, &L::Zero));
        let g1 = simplify(g.subst(pre, &L::One));
        let Some(t) = Tables::new(&[&g0, &g1]) else {
            return (g, None);
        };
        if !t.implies(0, 1) {
            return (g, None);
        }
        match memory_form(&g, pre, g0, g1, prefer_rs) {
            Some(m) => {
                let recurrence = (m != g).then_some(g);
                (m, recurrence)
            }
            None => (g, None),
        }
    }

    fn flush_block(&mut self) {
        self.state_repeated();
        let pending = std::mem::take(&mut self.pending);
        if pending.is_empty() || !self.equations {
            return;
        }
        let block = self.block();
        let base = block.label.clone().unwrap_or_default();
        let several = pending.len() > 1;
        for (k, p) in pending.into_iter().enumerate() {
            let name = if several { format!("{base}{}", letters(k)) } else { base.clone() };
            let var = L::var(&p.var).to_expr();
            let rhs = self.exact(&p.rhs).to_expr();
            let recurrence = p.recurrence.as_ref().map(|g| self.exact(g).to_expr());
            let mut push = |name: String, kind, lhs: Expr, rel, rhs: Expr| {
                self.hypotheses.push(Hypothesis {
                    name,
                    rung: block.number,
                    span: block.span,
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
        for (x, number) in std::mem::take(&mut self.unwritten) {
            let block = self.program.blocks.iter().find(|b| b.number == number);
            let name = self.unique(&format!("unwritten_{x}"));
            self.hypotheses.push(Hypothesis {
                name,
                rung: number,
                span: block.map_or(Span::new(0, 0..0), |b| b.span),
                kind: HypothesisKind::Equation,
                lhs: L::var(&x).to_expr(),
                rel: Rel::Eq,
                rhs: L::Zero.to_expr(),
            });
            self.fresh.insert(x, SignalKind::Unwritten);
        }
        self.state_start();
        let mut signals: BTreeMap<String, SignalKind> = BTreeMap::new();
        let written = &self.last_write;
        let classify = |n: &str| -> SignalKind {
            if let Some(k) = self.fresh.get(n) {
                return k.clone();
            }
            if let Some(k) = self.int_bit_kind(n) {
                return k;
            }
            if written.contains_key(n) {
                if n.starts_with('Y') { SignalKind::Output } else { SignalKind::Relay }
            } else {
                SignalKind::Input
            }
        };
        for s in &self.program.signals {
            signals.insert(s.clone(), classify(s));
        }
        let mut seen: HashSet<Symbol> = HashSet::default();
        for h in &self.hypotheses {
            for side in [&h.lhs, &h.rhs] {
                for node in side.as_ref() {
                    if let crate::term::Term::Name(n) = node
                        && seen.insert(*n)
                    {
                        let n = n.as_str();
                        if !signals.contains_key(n) {
                            signals.insert(n.to_string(), classify(n));
                        }
                    }
                }
            }
        }
        for (name, kind) in &self.fresh {
            if matches!(kind, SignalKind::Fresh { .. } | SignalKind::Intermediate { .. }) {
                signals.insert(name.clone(), kind.clone());
            }
        }
        // Every bit of every integer, so that properties may compare any of them.
        for (x, v) in &self.program.integers {
            for k in 0..v.ty.bits {
                let n = Program::int_bit(x, k);
                if let Some(kind) = self.int_bit_kind(&n) {
                    signals.insert(n, kind);
                }
            }
        }
        let starts = self.start_targets(&signals);
        let constants = ints::constants(self.program);
        CompiledProgram {
            hypotheses: self.hypotheses,
            signals,
            warnings: self.warnings,
            timers: self.options.timers,
            timer_info: self.timer_info,
            cycle_us: self.program.cycle_us,
            exact_names: self.program.exact_names,
            language: self.program.language,
            block_noun: self.program.block_noun,
            short_names: std::sync::OnceLock::new(),
            spelled_short: Default::default(),
            equation_index: std::sync::OnceLock::new(),
            integers: self.program.integers.clone(),
            atoms: Default::default(),
            int_depth: ints::int_depth(self.program, &constants),
            constants,
            starts,
            started: self.started.clone(),
            start_flag: self.started.as_ref().and(self.program.started.clone()),
        }
    }
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
        L::And(xs) => inner(xs).map_or_else(|| simplify(y.clone().negate()), |v| simplify(sum(v))),
        L::Or(xs) => {
            inner(xs).map_or_else(|| simplify(y.clone().negate()), |v| simplify(product(v)))
        }
        _ => simplify(y.clone().negate()),
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
    let s_rs = simplify(product(kept));
    // SR(S, ¬Y): S = g0, Y = the summands of g1 that do not imply g0.
    let s_sr = g0.clone();
    let f1 = summands(&g1);
    let kept: Vec<L> =
        f1.iter().filter(|f| super::logic::implies(f, &g0) != Some(true)).cloned().collect();
    let sr_dropped = kept.len() < f1.len();
    let y_sr = simplify(sum(kept));
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
            return Some(simplify(if is_rs { L::Rs(s, r) } else { L::Sr(s, r) }));
        }
    }
    let fallback = L::Sr(Box::new(g0), Box::new(simplify(g1.negate())));
    Some(simp(&fallback))
}
