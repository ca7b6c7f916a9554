//! Reader for LDmicro `.ld` ladder files (see `shared/formats/ldmicro.md`, §8): text → [`LdProgram`].
//!
//! The reader accepts every header version (`LDmicro0.1`, `LDmicro0.2`, a bare
//! `LDmicro`, `LDmicro v0.2`), CRLF or LF line ends, the short (orig 2.x) and
//! long (fork 3.x–5.x) argument lists of every element, and `SERIES` directly
//! inside a series (flattened). It rejects, with a located [`LadderError`]:
//! unknown keywords (with a "did you mean"), too few arguments, malformed
//! numeric arguments, `PARALLEL` directly inside `PARALLEL`, stray `END`s,
//! non-`RUNG` lines between rungs, truncated files and files without
//! `PROGRAM`. It never panics.

use std::collections::{BTreeMap, BTreeSet};
use std::sync::Arc;

use crate::diag::{FileId, Sources, Span, did_you_mean};

use super::LadderError;

/// The deepest SERIES/PARALLEL nesting the reader accepts (LDmicro's own editor stays far below).
pub const MAX_DEPTH: usize = 64;

/// Which header the file carries; it selects the default timer adjust (§6.3) and the counter semantics (§6.4).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum HeaderVersion {
    /// `LDmicro0.1`: written by orig 2.x, and by the new fork's "v2.3 compatible" save.
    V0_1,
    /// Anything else after `LDmicro` (`0.2`, empty, ` v0.2`, …): the new fork treats it as 0.2.
    /// The text after `LDmicro` is kept.
    V0_2(String),
    /// No `LDmicro…` line at all (orig never checks it). Treated like `0.1`.
    Missing,
}

impl HeaderVersion {
    /// True for files read with orig (2.x) semantics: `LDmicro0.1` or no header.
    pub fn is_orig(&self) -> bool {
        matches!(self, HeaderVersion::V0_1 | HeaderVersion::Missing)
    }
    /// The header as it is named in messages: `LDmicro0.1`, `LDmicro0.2`, `headerless`.
    pub fn label(&self) -> String {
        match self {
            HeaderVersion::V0_1 => "LDmicro0.1".into(),
            HeaderVersion::V0_2(rest) => format!("LDmicro{rest}"),
            HeaderVersion::Missing => "headerless".into(),
        }
    }
    /// The timer adjust used when a timer has no adjust field: -1 for 0.1, 0 otherwise.
    pub fn default_adjust(&self) -> i64 {
        if self.is_orig() { -1 } else { 0 }
    }
}

/// One line of the `IO LIST` section: `name at pin [modbusSlave modbusAddr]`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct IoEntry {
    /// The I/O name; its first letter gives the kind (`X` input, `Y` output, `A` ADC, …).
    pub name: String,
    /// The pin as written: a number (`0` = not assigned) or a pin name (PC-port target).
    pub pin: String,
    /// The whole line.
    pub span: Span,
}

impl IoEntry {
    /// The pin number, if the pin is written as a number.
    pub fn pin_number(&self) -> Option<u32> {
        self.pin.parse().ok()
    }
}

/// A whole `.ld` file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LdProgram {
    /// The header version (selects timer adjust and counter semantics).
    pub version: HeaderVersion,
    /// The scan period in µs: the leading integer of `CYCLE=`, 10000 when absent.
    pub cycle_us: u64,
    /// The `MICRO=` target, if any.
    pub micro: Option<String>,
    /// The `IO LIST` entries in file order (optional metadata: the rungs define the signals).
    pub io_list: Vec<IoEntry>,
    /// The rungs in scan order (shared: a slice of the program and its simulators hold
    /// the same rungs).
    pub rungs: Vec<Arc<Rung>>,
    /// Warnings (lines skipped before `PROGRAM`, `PLACEHOLDER`s, …); never errors.
    pub warnings: Vec<LadderError>,
    /// The bits the outside world writes, for front ends that declare them (PLCopen
    /// input variables); `None`: LDmicro's rule, names starting with `X`, `I` or `M`.
    pub inputs: Option<BTreeSet<String>>,
    /// The storage size in bytes (1–4) of the integers the `VAR LIST` declares (new
    /// files): `N bytes NAME`, or `NAME signed BITS bit variable`.
    pub var_bytes: BTreeMap<String, u32>,
    /// What [`LdProgram::slice`] walks, built at the first slice (no part of the
    /// program's value: equal, and empty in a clone).
    pub slicing: super::SliceIndex,
}

/// One rung: a series circuit between the power rails.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Rung {
    /// 1-based position in the file (comment rungs count).
    pub number: usize,
    /// The number written after `RUNG`, if any (informational only).
    pub label: Option<u64>,
    /// From the `RUNG` line to its `END`.
    pub span: Span,
    /// Always a [`Circuit::Series`] (possibly empty).
    pub body: Circuit,
}

/// A circuit: elements in series (AND, left to right), in parallel (OR of branches), or one element.
///
/// Normalisation done by the reader: a `SERIES` directly inside a series is
/// spliced into it; a `PARALLEL` with one branch is replaced by that branch; a
/// `SERIES` with one element inside a `PARALLEL` is replaced by the element.
/// Empty series (power passes) and empty parallels (no branch conducts) are kept.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Circuit {
    /// Left to right; output of one is input of the next. Empty = a wire.
    Series(Vec<Circuit>),
    /// Every branch gets the same input; the output is the OR of the branch outputs.
    Parallel(Vec<Circuit>),
    /// One leaf element.
    Element(Element),
}

impl Circuit {
    /// Every element in execution order.
    pub fn elements(&self) -> Vec<&Element> {
        let mut out = Vec::new();
        self.collect(&mut out);
        out
    }
    fn collect<'a>(&'a self, out: &mut Vec<&'a Element>) {
        match self {
            Circuit::Series(items) | Circuit::Parallel(items) => {
                items.iter().for_each(|c| c.collect(out))
            }
            Circuit::Element(e) => out.push(e),
        }
    }
}

impl Rung {
    /// Every element of the rung in execution order.
    pub fn elements(&self) -> Vec<&Element> {
        self.body.elements()
    }
    /// Whether LDmicro skips this rung as a comment: for orig (`version.is_orig()`)
    /// a rung holding exactly one COMMENT; for new, any rung whose first element (of
    /// its top-level series: a PARALLEL starting with a COMMENT still runs) is a COMMENT.
    pub fn is_comment(&self, version: &HeaderVersion) -> bool {
        let Circuit::Series(items) = &self.body else { return false };
        let first_is_comment = matches!(
            items.first(),
            Some(Circuit::Element(Element { kind: ElementKind::Comment(_), .. }))
        );
        if version.is_orig() { items.len() == 1 && first_is_comment } else { first_is_comment }
    }
}

/// One leaf line of a rung.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Element {
    /// What the element is.
    pub kind: ElementKind,
    /// The whole line.
    pub span: Span,
}

/// The kind of a coil.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CoilKind {
    /// `name := i`.
    Normal,
    /// `name := ¬i`.
    Negated,
    /// `if i { name := 1 }`.
    Set,
    /// `if i { name := 0 }`.
    Reset,
    /// On a rising edge of `i`, `name := ¬name` (new fork, 4.0.3).
    Toggle,
}

/// The kind of a timer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TimerKind {
    /// On-delay.
    Ton,
    /// Off-delay.
    Tof,
    /// Retentive on-delay.
    Rto,
    /// Retentive, accumulating while the input is low (new).
    Rtl,
    /// Pulse on the rising edge (new).
    Thi,
    /// Low pulse on the falling edge (new).
    Tlo,
    /// Square wave while the input is true (new).
    Tcy,
}

/// A timer's delay.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TimerDelay {
    /// A literal delay in microseconds.
    Micros(u64),
    /// A variable holding the delay as a number of scans (new, 4.4.1).
    Variable(String),
}

/// The kind of a one-shot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgeKind {
    /// One-scan pulse on a rising edge.
    Osr,
    /// One-scan pulse on a falling edge.
    Osf,
    /// Normally true, drops for one scan on a rising edge (new).
    Odr,
    /// Normally true, drops for one scan on a falling edge (new; `OSL` is the old name).
    Odf,
    /// Toggles every scan while the input is true (new).
    Osc,
}

/// The kind of a counter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CounterKind {
    /// Count up.
    Ctu,
    /// Count down.
    Ctd,
    /// Circular counter 0..max.
    Ctc,
    /// Reversible circular counter counting down (new).
    Ctr,
}

/// What makes a counter count (new ≥ 4.4.1; the last field of the counter line).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CounterEdge {
    /// `/`: the rising edge of the input (the default, and orig behaviour).
    Rising,
    /// `\`: the falling edge.
    Falling,
    /// `-`: every scan while the input is high.
    High,
    /// `o`: every scan while the input is low.
    Low,
}

/// A comparison element.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CompareOp {
    /// `EQU`: `a == b`.
    Equ,
    /// `NEQ`: `a != b`.
    Neq,
    /// `GRT`: `a > b`.
    Grt,
    /// `GEQ`: `a >= b`.
    Geq,
    /// `LES`: `a < b`.
    Les,
    /// `LEQ`: `a <= b`.
    Leq,
}

/// An orig arithmetic element.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MathOp {
    /// `ADD dest a b`.
    Add,
    /// `SUB dest a b`.
    Sub,
    /// `MUL dest a b`.
    Mul,
    /// `DIV dest a b` (truncating).
    Div,
}

/// An integer operand: a literal or a variable name.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Operand {
    /// A literal: decimal, `'c'`, or `0x`/`0o`/`0b`-prefixed.
    Literal(i64),
    /// A variable name.
    Var(String),
}

impl Operand {
    /// The variable name, if this operand is one.
    pub fn var(&self) -> Option<&str> {
        match self {
            Operand::Var(v) => Some(v),
            Operand::Literal(_) => None,
        }
    }

    /// A literal beyond 16 bits: orig LDmicro puts it in a temporary whose size it
    /// chooses (intcode.cpp `VarFromExpr`), so a comparison or a DIV of it is not known.
    pub fn beyond_16_bits(&self) -> bool {
        matches!(self, Operand::Literal(v) if !(-32768..=32767).contains(v))
    }
}

/// What a leaf element is, with its arguments decoded.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ElementKind {
    /// `CONTACTS name neg [set1]`: `o = i ∧ name` or `o = i ∧ ¬name`.
    Contacts {
        /// The bit read.
        name: String,
        /// `]/[` (normally closed).
        negated: bool,
    },
    /// `COIL name neg set reset [ttrigger]`; `o = i`.
    Coil {
        /// The bit written.
        name: String,
        /// Plain, negated, set, reset or toggle.
        kind: CoilKind,
    },
    /// `SHORT`: `o = i`.
    Short,
    /// `OPEN`: `o = 0`.
    Open,
    /// `PLACEHOLDER`: an empty editor slot (LDmicro refuses to compile it); reported as a warning.
    Placeholder,
    /// `COMMENT text` with escapes decoded; no semantics.
    Comment(String),
    /// `MASTER_RELAY` (§6.6).
    MasterRelay,
    /// `TON/TOF/RTO/RTL/THI/TLO/TCY name delay [adjust]`.
    Timer {
        /// Which timer.
        kind: TimerKind,
        /// The accumulator variable (`T…`).
        name: String,
        /// The delay.
        delay: TimerDelay,
        /// The scan adjust: the field if present, else the header default (-1 for 0.1, 0 otherwise).
        adjust: i64,
        /// Whether the file gives the adjust field (else it is the header's default).
        adjust_given: bool,
    },
    /// `OSR`, `OSF`, `ODR`, `ODF`/`OSL`, `OSC`.
    Edge {
        /// Which one-shot.
        kind: EdgeKind,
    },
    /// `CTU/CTD/CTC/CTR name max [init [kind]]`.
    Counter {
        /// Which counter.
        kind: CounterKind,
        /// The count variable (`C…`).
        name: String,
        /// The limit (`max`, or `min` for CTR).
        limit: Operand,
        /// The start value (new); 0 when absent.
        init: Operand,
        /// What makes it count; rising edge when absent.
        edge: CounterEdge,
    },
    /// `RES name`: reset a timer or counter.
    Res {
        /// The timer or counter.
        name: String,
    },
    /// `EQU/NEQ/GRT/GEQ/LES/LEQ a b`: `o = i ∧ (a op b)`.
    Compare {
        /// The comparison.
        op: CompareOp,
        /// Left operand.
        a: Operand,
        /// Right operand.
        b: Operand,
    },
    /// `MOVE dest src`.
    Move {
        /// Written.
        dest: String,
        /// Read.
        src: Operand,
    },
    /// `ADD/SUB/MUL/DIV dest a b`.
    Math {
        /// The operation.
        op: MathOp,
        /// Written.
        dest: String,
        /// Left operand.
        a: Operand,
        /// Right operand.
        b: Operand,
    },
    /// Any other known element (integer ops, tables, peripherals, text, control flow):
    /// an unconstrained output for the prover. Keyword and raw arguments are kept for warnings.
    Other {
        /// The keyword as written.
        keyword: String,
        /// The raw argument tokens.
        args: Vec<String>,
    },
}

impl ElementKind {
    /// The LDmicro keyword of this element.
    pub fn keyword(&self) -> &str {
        match self {
            ElementKind::Contacts { .. } => "CONTACTS",
            ElementKind::Coil { .. } => "COIL",
            ElementKind::Short => "SHORT",
            ElementKind::Open => "OPEN",
            ElementKind::Placeholder => "PLACEHOLDER",
            ElementKind::Comment(_) => "COMMENT",
            ElementKind::MasterRelay => "MASTER_RELAY",
            ElementKind::Timer { kind, .. } => match kind {
                TimerKind::Ton => "TON",
                TimerKind::Tof => "TOF",
                TimerKind::Rto => "RTO",
                TimerKind::Rtl => "RTL",
                TimerKind::Thi => "THI",
                TimerKind::Tlo => "TLO",
                TimerKind::Tcy => "TCY",
            },
            ElementKind::Edge { kind } => match kind {
                EdgeKind::Osr => "OSR",
                EdgeKind::Osf => "OSF",
                EdgeKind::Odr => "ODR",
                EdgeKind::Odf => "ODF",
                EdgeKind::Osc => "OSC",
            },
            ElementKind::Counter { kind, .. } => match kind {
                CounterKind::Ctu => "CTU",
                CounterKind::Ctd => "CTD",
                CounterKind::Ctc => "CTC",
                CounterKind::Ctr => "CTR",
            },
            ElementKind::Res { .. } => "RES",
            ElementKind::Compare { op, .. } => match op {
                CompareOp::Equ => "EQU",
                CompareOp::Neq => "NEQ",
                CompareOp::Grt => "GRT",
                CompareOp::Geq => "GEQ",
                CompareOp::Les => "LES",
                CompareOp::Leq => "LEQ",
            },
            ElementKind::Move { .. } => "MOVE",
            ElementKind::Math { op, .. } => match op {
                MathOp::Add => "ADD",
                MathOp::Sub => "SUB",
                MathOp::Mul => "MUL",
                MathOp::Div => "DIV",
            },
            ElementKind::Other { keyword, .. } => keyword,
        }
    }

    /// True for the Boolean core the II algebra models exactly: contacts, coils
    /// (not toggle), SHORT, OPEN, COMMENT, TON and TOF.
    pub fn is_boolean_core(&self) -> bool {
        match self {
            ElementKind::Contacts { .. }
            | ElementKind::Short
            | ElementKind::Open
            | ElementKind::Comment(_) => true,
            ElementKind::Coil { kind, .. } => *kind != CoilKind::Toggle,
            ElementKind::Timer { kind, .. } => matches!(kind, TimerKind::Ton | TimerKind::Tof),
            _ => false,
        }
    }
}

/// Whether a token looks like a variable name (not a literal, not `(none)`).
fn is_name(token: &str) -> bool {
    let mut chars = token.chars();
    match chars.next() {
        Some(c) if c.is_ascii_alphabetic() || c == '_' || c == '#' || c == '@' || c == '$' => {}
        _ => return false,
    }
    chars.all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '@' | '#' | '$' | '.'))
}

impl Element {
    /// Every variable name (bit or integer) the element reads. For [`ElementKind::Other`]
    /// this is a best-effort guess from the argument positions.
    pub fn names_read(&self) -> Vec<&str> {
        let mut out: Vec<&str> = Vec::new();
        match &self.kind {
            ElementKind::Contacts { name, .. } => out.push(name),
            ElementKind::Coil { name, kind: CoilKind::Toggle } => out.push(name),
            ElementKind::Timer { name, delay, .. } => {
                out.push(name);
                if let TimerDelay::Variable(v) = delay {
                    out.push(v);
                }
            }
            ElementKind::Counter { name, limit, init, .. } => {
                out.push(name);
                out.extend(limit.var());
                out.extend(init.var());
            }
            ElementKind::Compare { a, b, .. } => {
                out.extend(a.var());
                out.extend(b.var());
            }
            ElementKind::Move { src, .. } => out.extend(src.var()),
            ElementKind::Math { a, b, .. } => {
                out.extend(a.var());
                out.extend(b.var());
            }
            ElementKind::Other { keyword, args } => {
                let read: &[String] = match keyword.as_str() {
                    "FORMATTED_STRING" | "UART_SEND" | "PERSIST" | "IF_BIT_SET"
                    | "IF_BIT_CLEAR" | "SET_BIT" | "CLEAR_BIT" => &args[..args.len().min(1)],
                    "SET_PWM" => &args[..args.len().min(2)],
                    "LOOK_UP_TABLE" | "PIECEWISE_LINEAR" | "STRING" => {
                        args.get(1..2).unwrap_or(&[])
                    }
                    k if other_writes_first(k) => args.get(1..).unwrap_or(&[]),
                    _ => &[],
                };
                out.extend(read.iter().map(String::as_str).filter(|a| is_name(a)));
            }
            _ => {}
        }
        out
    }

    /// Every variable name (bit or integer) the element writes, at a scan or at
    /// start-up (formats/ldmicro.md §4): a `SHIFT_REGISTER name n` writes `name0` …
    /// `name{n-1}`, a `PERSIST var` loads `var` at power-up; an element whose writes are
    /// not listed there (SPI, I²C, steppers, pulse trains, encoders, unknown keywords) is
    /// taken to write every name among its arguments.
    pub fn names_written(&self) -> Vec<String> {
        match &self.kind {
            ElementKind::Coil { name, .. }
            | ElementKind::Timer { name, .. }
            | ElementKind::Counter { name, .. }
            | ElementKind::Res { name } => vec![name.clone()],
            ElementKind::Move { dest, .. } | ElementKind::Math { dest, .. } => vec![dest.clone()],
            ElementKind::Other { keyword, args } => other_writes(keyword, args),
            _ => Vec::new(),
        }
    }
}

/// What an [`ElementKind::Other`] element writes ([`Element::names_written`]).
fn other_writes(keyword: &str, args: &[String]) -> Vec<String> {
    let names = |list: &[String]| list.iter().filter(|a| is_name(a)).cloned().collect();
    match keyword {
        "SHIFT_REGISTER" => match (args.first(), args.get(1).and_then(|n| n.parse::<u32>().ok())) {
            (Some(name), Some(stages)) => (0..stages).map(|k| format!("{name}{k}")).collect(),
            _ => names(args),
        },
        "PERSIST" => names(&args[..args.len().min(1)]),
        // `I2C_RD name send recv mode address registr first bitrate` (`loadsave.cpp`)
        // writes `recv`; `I2C_WR` writes the bus's name only in the C code of targets
        // without an I2C library (`ansic.cpp`: `name = I2C_SEND(…)`).
        "I2C_RD" => names(args.get(2..3).unwrap_or(&[])),
        "I2C_WR" => names(&args[..args.len().min(1)]),
        k if !other_writes_first(k) => Vec::new(),
        "UART_RECV" | "READ_ADC" | "RANDOM" | "SEED_RANDOM" | "LOOK_UP_TABLE"
        | "PIECEWISE_LINEAR" | "STRING" | "7SEGMENTS" | "9SEGMENTS" | "14SEGMENTS"
        | "16SEGMENTS" | "BUS" | "BIN2BCD" | "BCD2BIN" | "SWAP" | "OPPOSITE" | "NOT" | "NEG"
        | "SET_BIT" | "CLEAR_BIT" | "RSFR" | "TIME2COUNT" | "MOD" | "AND" | "OR" | "XOR"
        | "SHL" | "SHR" | "SR0" | "ROL" | "ROR" => names(&args[..args.len().min(1)]),
        "WSFR" | "SSFR" | "CSFR" | "TSFR" | "TCSFR" => Vec::new(),
        _ => names(args),
    }
}

/// Whether an [`ElementKind::Other`] keyword writes its first argument.
fn other_writes_first(keyword: &str) -> bool {
    !matches!(
        keyword,
        "FORMATTED_STRING"
            | "UART_SEND"
            | "PERSIST"
            | "SET_PWM"
            | "IF_BIT_SET"
            | "IF_BIT_CLEAR"
            | "UART_SEND_READY"
            | "UART_RECV_AVAIL"
            | "UART_SEND_BUSY"
            | "UART_UDRE"
            | "GOTO"
            | "GOSUB"
            | "LABEL"
            | "SUBPROG"
            | "ENDSUB"
            | "RETURN"
            | "SLEEP"
            | "CLRWDT"
            | "LOCK"
            | "DELAY"
            | "TIME2DELAY"
    )
}

impl LdProgram {
    /// Every bit name used by a contact or a coil, sorted.
    pub fn signals(&self) -> BTreeSet<String> {
        let mut out: Vec<&str> = Vec::new();
        for rung in &self.rungs {
            for e in rung.elements() {
                match &e.kind {
                    ElementKind::Contacts { name, .. } | ElementKind::Coil { name, .. } => {
                        out.push(name);
                    }
                    _ => {}
                }
            }
        }
        out.sort_unstable();
        out.dedup();
        out.into_iter().map(str::to_string).collect()
    }
    /// `P`, the number of scans a timer with a literal delay counts to (§6.3):
    /// `floor(delay / cycle) + adjust`. `None` for a variable delay (then `P` is
    /// the variable's run-time value) or a zero cycle (timers never expire).
    /// A TON turns on at the (P+1)-th consecutive true scan; a TOF holds P scans.
    pub fn timer_scans(&self, delay: &TimerDelay, adjust: i64) -> Option<i64> {
        match delay {
            TimerDelay::Micros(d) => {
                let n = i64::try_from(d.checked_div(self.cycle_us)?).ok()?;
                Some(n.saturating_add(adjust))
            }
            TimerDelay::Variable(_) => None,
        }
    }
    /// Every element in the program, in scan order.
    pub fn elements(&self) -> impl Iterator<Item = &Element> {
        self.rungs.iter().flat_map(|r| r.elements())
    }
}

/// Decodes bytes as Latin-1 (every byte is one char), the way LDmicro's CP1252 files must be read.
pub fn decode_latin1(bytes: &[u8]) -> String {
    bytes.iter().map(|&b| char::from(b)).collect()
}

/// One trimmed, non-blank line.
#[derive(Clone, Copy)]
struct Line<'a> {
    text: &'a str,
    start: usize,
}

impl<'a> Line<'a> {
    fn span(&self, file: FileId) -> Span {
        Span::new(file, self.start..self.start + self.text.len())
    }
    /// Whitespace-separated tokens with their spans.
    fn tokens(&self, file: FileId) -> Vec<(&'a str, Span)> {
        let mut out = Vec::new();
        let text = self.text;
        let mut i = 0;
        let bytes = text.as_bytes();
        while i < bytes.len() {
            while i < bytes.len() && (bytes[i] as char).is_ascii_whitespace() {
                i += 1;
            }
            let s = i;
            while i < bytes.len() && !(bytes[i] as char).is_ascii_whitespace() {
                i += 1;
            }
            if i > s {
                // Token boundaries are ASCII whitespace, hence char boundaries.
                if let Some(tok) = text.get(s..i) {
                    out.push((tok, Span::new(file, self.start + s..self.start + s + tok.len())));
                }
            }
        }
        out
    }
    fn first(&self) -> &'a str {
        self.text.split_ascii_whitespace().next().unwrap_or("")
    }
}

fn split_lines(text: &str) -> Vec<Line<'_>> {
    let mut out = Vec::new();
    let mut offset = 0;
    for raw in text.split('\n') {
        let line_start = offset;
        offset += raw.len() + 1;
        let trimmed_start = raw.trim_start();
        let lead = raw.len() - trimmed_start.len();
        let trimmed = trimmed_start.trim_end();
        if !trimmed.is_empty() {
            out.push(Line { text: trimmed, start: line_start + lead });
        }
    }
    out
}

/// Element keywords other than the typed ones: (keyword, minimum argument count, usage).
const OTHER_KEYWORDS: &[(&str, usize, &str)] = &[
    ("MOD", 3, "MOD dest a b"),
    ("AND", 3, "AND dest a b"),
    ("OR", 3, "OR dest a b"),
    ("XOR", 3, "XOR dest a b"),
    ("SHL", 3, "SHL dest a b"),
    ("SHR", 3, "SHR dest a b"),
    ("SR0", 3, "SR0 dest a b"),
    ("ROL", 3, "ROL dest a b"),
    ("ROR", 3, "ROR dest a b"),
    ("NOT", 2, "NOT dest a"),
    ("NEG", 2, "NEG dest a"),
    ("BIN2BCD", 2, "BIN2BCD dest src"),
    ("BCD2BIN", 2, "BCD2BIN dest src"),
    ("SWAP", 2, "SWAP dest src"),
    ("OPPOSITE", 2, "OPPOSITE dest src"),
    ("SET_BIT", 2, "SET_BIT var bit"),
    ("CLEAR_BIT", 2, "CLEAR_BIT var bit"),
    ("IF_BIT_SET", 2, "IF_BIT_SET var bit"),
    ("IF_BIT_CLEAR", 2, "IF_BIT_CLEAR var bit"),
    ("SHIFT_REGISTER", 2, "SHIFT_REGISTER name stages"),
    ("LOOK_UP_TABLE", 4, "LOOK_UP_TABLE dest index count asString v0 … [name]"),
    ("PIECEWISE_LINEAR", 3, "PIECEWISE_LINEAR dest index count x0 y0 … [name]"),
    ("RANDOM", 1, "RANDOM name"),
    ("SEED_RANDOM", 2, "SEED_RANDOM dest src"),
    ("RSFR", 2, "RSFR a b"),
    ("WSFR", 2, "WSFR a b"),
    ("SSFR", 2, "SSFR a b"),
    ("CSFR", 2, "CSFR a b"),
    ("TSFR", 2, "TSFR a b"),
    ("TCSFR", 2, "TCSFR a b"),
    ("READ_ADC", 1, "READ_ADC name [refs]"),
    ("SET_PWM", 2, "SET_PWM duty freq [name [resolution]]"),
    ("UART_SEND", 1, "UART_SEND var [bytes wait]"),
    ("UART_RECV", 1, "UART_RECV var [bytes wait]"),
    ("UART_SEND_READY", 0, "UART_SEND_READY"),
    ("UART_RECV_AVAIL", 0, "UART_RECV_AVAIL"),
    ("UART_SEND_BUSY", 0, "UART_SEND_BUSY"),
    ("UART_UDRE", 0, "UART_UDRE"),
    ("PERSIST", 1, "PERSIST var"),
    ("FORMATTED_STRING", 2, "FORMATTED_STRING var N c1 … cN"),
    ("STRING", 3, "STRING dest var N c1 … cN"),
    ("7SEGMENTS", 3, "7SEGMENTS dest src C|A"),
    ("9SEGMENTS", 3, "9SEGMENTS dest src C|A"),
    ("14SEGMENTS", 3, "14SEGMENTS dest src C|A"),
    ("16SEGMENTS", 3, "16SEGMENTS dest src C|A"),
    ("BUS", 10, "BUS dest src b7 … b0"),
    ("SPI", 8, "SPI name send recv … (8 fields)"),
    ("SPI_WR", 8, "SPI_WR name send recv … (8 fields)"),
    ("I2C_RD", 8, "I2C_RD name recv … (8 fields)"),
    ("I2C_WR", 8, "I2C_WR name send … (8 fields)"),
    ("STEPPER", 6, "STEPPER … (6 fields)"),
    ("PULSER", 5, "PULSER … (5 fields)"),
    ("NPULSE", 3, "NPULSE … (3 fields)"),
    ("NPULSE_OFF", 0, "NPULSE_OFF …"),
    ("QUAD_ENCOD", 8, "QUAD_ENCOD … (8 fields)"),
    ("GOTO", 1, "GOTO label"),
    ("GOSUB", 1, "GOSUB label"),
    ("LABEL", 1, "LABEL label"),
    ("SUBPROG", 1, "SUBPROG label"),
    ("ENDSUB", 1, "ENDSUB label"),
    ("RETURN", 0, "RETURN"),
    ("SLEEP", 0, "SLEEP"),
    ("CLRWDT", 0, "CLRWDT"),
    ("LOCK", 0, "LOCK"),
    ("TIME2COUNT", 2, "TIME2COUNT name delay"),
    ("TIME2DELAY", 2, "TIME2DELAY name delay"),
    ("DELAY", 1, "DELAY name"),
];

/// The typed keywords: (keyword, minimum argument count, usage).
const TYPED_KEYWORDS: &[(&str, usize, &str)] = &[
    ("CONTACTS", 2, "CONTACTS name neg [set1]"),
    ("COIL", 4, "COIL name neg set reset [ttrigger]"),
    ("SHORT", 0, "SHORT"),
    ("OPEN", 0, "OPEN"),
    ("PLACEHOLDER", 0, "PLACEHOLDER"),
    ("COMMENT", 0, "COMMENT text"),
    ("MASTER_RELAY", 0, "MASTER_RELAY"),
    ("TON", 2, "TON name delay_us [adjust]"),
    ("TOF", 2, "TOF name delay_us [adjust]"),
    ("RTO", 2, "RTO name delay_us [adjust]"),
    ("RTL", 2, "RTL name delay_us [adjust]"),
    ("THI", 2, "THI name delay_us [adjust]"),
    ("TLO", 2, "TLO name delay_us [adjust]"),
    ("TCY", 2, "TCY name delay_us [adjust]"),
    ("OSR", 0, "OSR"),
    ("OSF", 0, "OSF"),
    ("ODR", 0, "ODR"),
    ("ODF", 0, "ODF"),
    ("OSL", 0, "OSL"),
    ("OSC", 0, "OSC"),
    ("CTU", 2, "CTU name max [init [kind]]"),
    ("CTD", 2, "CTD name max [init [kind]]"),
    ("CTC", 2, "CTC name max [init [kind]]"),
    ("CTR", 2, "CTR name min [init [kind]]"),
    ("RES", 1, "RES name"),
    ("EQU", 2, "EQU a b"),
    ("NEQ", 2, "NEQ a b"),
    ("GRT", 2, "GRT a b"),
    ("GEQ", 2, "GEQ a b"),
    ("LES", 2, "LES a b"),
    ("LEQ", 2, "LEQ a b"),
    ("MOVE", 2, "MOVE dest src"),
    ("ADD", 3, "ADD dest a b"),
    ("SUB", 3, "SUB dest a b"),
    ("MUL", 3, "MUL dest a b"),
    ("DIV", 3, "DIV dest a b"),
];

fn lookup(keyword: &str) -> Option<(usize, &'static str)> {
    TYPED_KEYWORDS
        .iter()
        .chain(OTHER_KEYWORDS)
        .find(|(k, _, _)| *k == keyword)
        .map(|(_, min, usage)| (*min, *usage))
}

/// Every keyword that may start a line inside a rung (elements and structure).
fn all_keywords() -> impl Iterator<Item = &'static str> {
    TYPED_KEYWORDS
        .iter()
        .chain(OTHER_KEYWORDS)
        .map(|(k, _, _)| *k)
        .chain(["SERIES", "PARALLEL", "END"])
}

/// Parses an integer literal: decimal with sign, `'c'`, `0x…`, `0o…`, `0b…`.
fn parse_int(token: &str) -> Option<i64> {
    let b = token.as_bytes();
    if b.len() == 3 && b[0] == b'\'' && b[2] == b'\'' {
        return Some(i64::from(b[1]));
    }
    let (neg, digits) = match token.strip_prefix('-') {
        Some(rest) => (true, rest),
        None => (false, token.strip_prefix('+').unwrap_or(token)),
    };
    let lower = digits.to_ascii_lowercase();
    let value = if let Some(h) = lower.strip_prefix("0x") {
        i64::from_str_radix(h, 16).ok()?
    } else if let Some(o) = lower.strip_prefix("0o") {
        i64::from_str_radix(o, 8).ok()?
    } else if let Some(bin) = lower.strip_prefix("0b") {
        i64::from_str_radix(bin, 2).ok()?
    } else if !digits.is_empty() && digits.bytes().all(|c| c.is_ascii_digit()) {
        digits.parse().ok()?
    } else {
        return None;
    };
    Some(if neg { value.checked_neg()? } else { value })
}

/// An argument as an operand: a literal (see `parse_int`) or a variable name.
pub fn operand(token: &str) -> Operand {
    match parse_int(token) {
        Some(v) => Operand::Literal(v),
        None => Operand::Var(token.to_string()),
    }
}

/// Decodes the escapes of COMMENT text (`\n`, `\r`, `\t`, `\\`, …; unknown escapes are kept).
fn unescape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars();
    while let Some(c) = chars.next() {
        if c != '\\' {
            out.push(c);
            continue;
        }
        match chars.next() {
            Some('n') => out.push('\n'),
            Some('r') => out.push('\r'),
            Some('t') => out.push('\t'),
            Some('\\') => out.push('\\'),
            Some('\'') => out.push('\''),
            Some('"') => out.push('"'),
            Some(other) => {
                out.push('\\');
                out.push(other);
            }
            None => out.push('\\'),
        }
    }
    out
}

/// Where we are when a structural error stops the parse.
struct Fatal;

struct Parser<'a> {
    file: FileId,
    lines: Vec<Line<'a>>,
    pos: usize,
    version: HeaderVersion,
    errors: Vec<LadderError>,
    warnings: Vec<LadderError>,
    var_bytes: BTreeMap<String, u32>,
}

impl<'a> Parser<'a> {
    fn peek(&self) -> Option<Line<'a>> {
        self.lines.get(self.pos).copied()
    }
    fn eof_span(&self) -> Span {
        match self.lines.last() {
            Some(l) => l.span(self.file),
            None => Span::new(self.file, 0..0),
        }
    }
    fn truncated(&mut self, open: &str, opened_at: Span) -> Fatal {
        let span = self.eof_span();
        self.errors.push(LadderError::Truncated { span, open: open.to_string(), opened_at });
        Fatal
    }

    /// A `VAR LIST` line: `N bytes NAME` or `NAME signed BITS bit variable` (anything
    /// after a TAB is a note).
    fn var_entry(&mut self, entry: Line<'a>) {
        let words: Vec<&str> =
            entry.text.split('\t').next().unwrap_or("").split_whitespace().collect();
        let size = match words.as_slice() {
            [n, "bytes", name] => n.parse::<u32>().ok().map(|n| (name.to_string(), n)),
            [name, "signed", bits, "bit", "variable"] => {
                bits.parse::<u32>().ok().map(|b| (name.to_string(), b / 8))
            }
            _ => None,
        };
        match size {
            Some((name, n)) if n > 0 => {
                self.var_bytes.insert(name, n);
            }
            _ => self.warnings.push(LadderError::IgnoredLine {
                span: entry.span(self.file),
                reason:
                    "expected `N bytes NAME` or `NAME signed BITS bit variable` in the VAR LIST"
                        .into(),
            }),
        }
    }

    fn header(&mut self) -> (u64, Option<String>, Vec<IoEntry>, bool) {
        let mut cycle = None;
        let mut micro = None;
        let mut io = Vec::new();
        let mut saw_header = false;
        let file = self.file;
        while let Some(line) = self.peek() {
            let text = line.text;
            if text == "PROGRAM" {
                return (cycle.unwrap_or(10000), micro, io, saw_header);
            }
            self.pos += 1;
            if let Some(rest) = text.strip_prefix("LDmicro") {
                if saw_header {
                    self.warnings.push(LadderError::IgnoredLine {
                        span: line.span(file),
                        reason: "a second `LDmicro` header line".into(),
                    });
                } else {
                    saw_header = true;
                    self.version = if rest == "0.1" {
                        HeaderVersion::V0_1
                    } else {
                        HeaderVersion::V0_2(rest.to_string())
                    };
                }
            } else if matches!(text, "IO LIST" | "VAR LIST" | "PULL-UP LIST") {
                let opened_at = line.span(file);
                let is_io = text == "IO LIST";
                loop {
                    let Some(entry) = self.peek() else {
                        let _ = self.truncated(text, opened_at);
                        return (cycle.unwrap_or(10000), micro, io, saw_header);
                    };
                    if entry.text == "PROGRAM" {
                        self.errors.push(LadderError::Unexpected {
                            span: entry.span(file),
                            found: "PROGRAM".into(),
                            expected: format!("`END` closing the `{text}` opened earlier"),
                        });
                        return (cycle.unwrap_or(10000), micro, io, saw_header);
                    }
                    self.pos += 1;
                    if entry.text == "END" {
                        break;
                    }
                    if text == "VAR LIST" {
                        self.var_entry(entry);
                    }
                    if is_io {
                        let toks = entry.tokens(file);
                        if toks.len() >= 3 && toks[1].0 == "at" {
                            io.push(IoEntry {
                                name: toks[0].0.to_string(),
                                pin: toks[2].0.to_string(),
                                span: entry.span(file),
                            });
                        } else {
                            self.warnings.push(LadderError::IgnoredLine {
                                span: entry.span(file),
                                reason: "expected `name at pin` in the IO LIST".into(),
                            });
                        }
                    }
                }
            } else if let Some((key, value)) = text.split_once('=') {
                match key {
                    "CYCLE" => {
                        let digits: String =
                            value.chars().take_while(|c| c.is_ascii_digit()).collect();
                        match digits.parse::<u64>() {
                            Ok(0) => self.errors.push(LadderError::BadArgument {
                                span: line.span(file),
                                keyword: "CYCLE".into(),
                                found: value.trim().to_string(),
                                expected: "a scan cycle of at least 1 µs (the program runs in \
                                           scans of this length)"
                                    .into(),
                            }),
                            Ok(v) => cycle = Some(v),
                            Err(_) => self.warnings.push(LadderError::IgnoredLine {
                                span: line.span(file),
                                reason: "CYCLE= without a leading integer; using 10000 µs".into(),
                            }),
                        }
                    }
                    "MICRO" => micro = Some(value.trim().to_string()),
                    "CRYSTAL" | "BAUD" | "COMPILED" | "COMPILER" | "PARTITION" => {}
                    _ => self.warnings.push(LadderError::IgnoredLine {
                        span: line.span(file),
                        reason: format!("unknown header key `{key}=`"),
                    }),
                }
            } else {
                self.warnings.push(LadderError::IgnoredLine {
                    span: line.span(file),
                    reason: "not a header line, section or `PROGRAM`".into(),
                });
            }
        }
        let span = self.eof_span();
        self.errors.push(LadderError::MissingProgram { span, saw_header });
        (cycle.unwrap_or(10000), micro, io, saw_header)
    }

    fn rungs(&mut self) -> Result<Vec<Arc<Rung>>, Fatal> {
        let file = self.file;
        let mut rungs = Vec::new();
        while let Some(line) = self.peek() {
            self.pos += 1;
            let toks = line.tokens(file);
            if toks.first().map(|t| t.0) != Some("RUNG") {
                self.errors.push(LadderError::Unexpected {
                    span: toks.first().map(|t| t.1).unwrap_or(line.span(file)),
                    found: line.first().to_string(),
                    expected: "`RUNG` (each rung is `RUNG` … `END`)".into(),
                });
                return Err(Fatal);
            }
            let label = toks.get(1).and_then(|t| t.0.parse().ok());
            let opened_at = line.span(file);
            let items = self.series(1, "RUNG", opened_at)?;
            let end = self.lines[self.pos - 1].span(file);
            rungs.push(Arc::new(Rung {
                number: rungs.len() + 1,
                label,
                span: opened_at.to(end),
                body: Circuit::Series(items),
            }));
        }
        Ok(rungs)
    }

    /// Parses a series body up to and including its `END`.
    fn series(&mut self, depth: usize, open: &str, opened_at: Span) -> Result<Vec<Circuit>, Fatal> {
        let file = self.file;
        let mut items = Vec::new();
        loop {
            let Some(line) = self.peek() else {
                return Err(self.truncated(open, opened_at));
            };
            self.pos += 1;
            match line.first() {
                "END" => {
                    items.shrink_to_fit();
                    return Ok(items);
                }
                "SERIES" => {
                    let inner =
                        self.nested(depth, line, |p, d| p.series(d, "SERIES", line.span(file)))?;
                    items.extend(inner);
                }
                "PARALLEL" => {
                    let mut branches =
                        self.nested(depth, line, |p, d| p.parallel(d, line.span(file)))?;
                    if branches.len() == 1 {
                        match branches.pop() {
                            Some(Circuit::Series(inner)) => items.extend(inner),
                            Some(other) => items.push(other),
                            None => {}
                        }
                    } else {
                        items.push(Circuit::Parallel(branches));
                    }
                }
                "RUNG" | "PROGRAM" => {
                    self.errors.push(LadderError::Unexpected {
                        span: line.span(file),
                        found: line.first().to_string(),
                        expected: format!("an element or the `END` of the `{open}` opened earlier"),
                    });
                    return Err(Fatal);
                }
                _ if line.text.starts_with(';') => {}
                _ => {
                    if let Some(e) = self.leaf(line) {
                        items.push(Circuit::Element(e));
                    }
                }
            }
        }
    }

    /// Parses a parallel body up to and including its `END`.
    fn parallel(&mut self, depth: usize, opened_at: Span) -> Result<Vec<Circuit>, Fatal> {
        let file = self.file;
        let mut branches = Vec::new();
        loop {
            let Some(line) = self.peek() else {
                return Err(self.truncated("PARALLEL", opened_at));
            };
            self.pos += 1;
            match line.first() {
                "END" => {
                    branches.shrink_to_fit();
                    return Ok(branches);
                }
                "SERIES" => {
                    let mut inner =
                        self.nested(depth, line, |p, d| p.series(d, "SERIES", line.span(file)))?;
                    if inner.len() == 1 {
                        branches.extend(inner.pop());
                    } else {
                        branches.push(Circuit::Series(inner));
                    }
                }
                "PARALLEL" => {
                    self.errors.push(LadderError::Unexpected {
                        span: line.span(file),
                        found: "PARALLEL".into(),
                        expected: "an element or `SERIES` (a PARALLEL directly inside a PARALLEL is not allowed)".into(),
                    });
                    return Err(Fatal);
                }
                "RUNG" | "PROGRAM" => {
                    self.errors.push(LadderError::Unexpected {
                        span: line.span(file),
                        found: line.first().to_string(),
                        expected: "an element or the `END` of the `PARALLEL` opened earlier".into(),
                    });
                    return Err(Fatal);
                }
                _ if line.text.starts_with(';') => {}
                _ => {
                    if let Some(e) = self.leaf(line) {
                        branches.push(Circuit::Element(e));
                    }
                }
            }
        }
    }

    fn nested<T>(
        &mut self,
        depth: usize,
        line: Line<'a>,
        body: impl FnOnce(&mut Self, usize) -> Result<T, Fatal>,
    ) -> Result<T, Fatal> {
        if depth >= MAX_DEPTH {
            self.errors.push(LadderError::TooDeep { span: line.span(self.file), limit: MAX_DEPTH });
            return Err(Fatal);
        }
        body(self, depth + 1)
    }

    /// Parses one element line; pushes an error and returns `None` if it is malformed.
    fn leaf(&mut self, line: Line<'a>) -> Option<Element> {
        let file = self.file;
        let span = line.span(file);
        let toks = line.tokens(file);
        let (keyword, kw_span) = *toks.first()?;
        let args: Vec<&str> = toks[1..].iter().map(|t| t.0).collect();
        let Some((min, usage)) = lookup(keyword) else {
            self.errors.push(LadderError::UnknownKeyword {
                span: kw_span,
                keyword: keyword.to_string(),
                suggestion: did_you_mean(keyword, all_keywords()).map(str::to_string),
            });
            return None;
        };
        if keyword == "COMMENT" {
            let rest = line.text.get(keyword.len()..).unwrap_or("").trim_start();
            return Some(Element { kind: ElementKind::Comment(unescape(rest)), span });
        }
        if args.len() < min {
            self.errors.push(LadderError::Arity {
                span,
                keyword: keyword.to_string(),
                min,
                found: args.len(),
                usage: usage.to_string(),
            });
            return None;
        }
        let arg_span = |i: usize| toks.get(i + 1).map(|t| t.1).unwrap_or(span);
        let mut bad: Option<LadderError> = None;
        let flag = |i: usize, bad: &mut Option<LadderError>| -> bool {
            match args.get(i) {
                None => false,
                Some(a) => match parse_int(a) {
                    Some(v) => v != 0,
                    None => {
                        bad.get_or_insert(LadderError::BadArgument {
                            span: arg_span(i),
                            keyword: keyword.to_string(),
                            found: a.to_string(),
                            expected: "an integer flag (0 or 1)".into(),
                        });
                        false
                    }
                },
            }
        };
        let name = |i: usize| args.get(i).copied().unwrap_or("").to_string();
        let kind = match keyword {
            "CONTACTS" => ElementKind::Contacts { name: name(0), negated: flag(1, &mut bad) },
            "COIL" => {
                let neg = flag(1, &mut bad);
                let set = flag(2, &mut bad);
                let reset = flag(3, &mut bad);
                let toggle = flag(4, &mut bad);
                let kind = if neg {
                    CoilKind::Negated
                } else if set {
                    CoilKind::Set
                } else if reset {
                    CoilKind::Reset
                } else if toggle {
                    CoilKind::Toggle
                } else {
                    CoilKind::Normal
                };
                ElementKind::Coil { name: name(0), kind }
            }
            "SHORT" => ElementKind::Short,
            "OPEN" => ElementKind::Open,
            "PLACEHOLDER" => {
                self.warnings.push(LadderError::Placeholder { span });
                ElementKind::Placeholder
            }
            "MASTER_RELAY" => ElementKind::MasterRelay,
            "TON" | "TOF" | "RTO" | "RTL" | "THI" | "TLO" | "TCY" => {
                let kind = match keyword {
                    "TON" => TimerKind::Ton,
                    "TOF" => TimerKind::Tof,
                    "RTO" => TimerKind::Rto,
                    "RTL" => TimerKind::Rtl,
                    "THI" => TimerKind::Thi,
                    "TLO" => TimerKind::Tlo,
                    _ => TimerKind::Tcy,
                };
                let delay = match parse_int(args[1]) {
                    Some(v) if v >= 0 => TimerDelay::Micros(v.unsigned_abs()),
                    None if is_name(args[1]) => TimerDelay::Variable(args[1].to_string()),
                    _ => {
                        bad = Some(LadderError::BadArgument {
                            span: arg_span(1),
                            keyword: keyword.to_string(),
                            found: args[1].to_string(),
                            expected: "a delay in µs (a non-negative integer) or a variable name"
                                .into(),
                        });
                        TimerDelay::Micros(0)
                    }
                };
                let adjust = match args.get(2) {
                    None => self.version.default_adjust(),
                    Some(a) => match parse_int(a) {
                        Some(v) => v,
                        None => {
                            bad = Some(LadderError::BadArgument {
                                span: arg_span(2),
                                keyword: keyword.to_string(),
                                found: a.to_string(),
                                expected: "an integer scan adjust (e.g. -1 or 0)".into(),
                            });
                            0
                        }
                    },
                };
                ElementKind::Timer {
                    kind,
                    name: name(0),
                    delay,
                    adjust,
                    adjust_given: args.len() > 2,
                }
            }
            "OSR" => ElementKind::Edge { kind: EdgeKind::Osr },
            "OSF" => ElementKind::Edge { kind: EdgeKind::Osf },
            "ODR" => ElementKind::Edge { kind: EdgeKind::Odr },
            "ODF" | "OSL" => ElementKind::Edge { kind: EdgeKind::Odf },
            "OSC" => ElementKind::Edge { kind: EdgeKind::Osc },
            "CTU" | "CTD" | "CTC" | "CTR" => {
                let kind = match keyword {
                    "CTU" => CounterKind::Ctu,
                    "CTD" => CounterKind::Ctd,
                    "CTC" => CounterKind::Ctc,
                    _ => CounterKind::Ctr,
                };
                let edge = match args.get(3).copied() {
                    None | Some("/") => CounterEdge::Rising,
                    Some("\\") => CounterEdge::Falling,
                    Some("-") => CounterEdge::High,
                    Some("o") => CounterEdge::Low,
                    Some(other) => {
                        bad = Some(LadderError::BadArgument {
                            span: arg_span(3),
                            keyword: keyword.to_string(),
                            found: other.to_string(),
                            expected: "a counter kind: `/`, `\\`, `-` or `o`".into(),
                        });
                        CounterEdge::Rising
                    }
                };
                ElementKind::Counter {
                    kind,
                    name: name(0),
                    limit: operand(args[1]),
                    init: args.get(2).map_or(Operand::Literal(0), |a| operand(a)),
                    edge,
                }
            }
            "RES" => ElementKind::Res { name: name(0) },
            "EQU" | "NEQ" | "GRT" | "GEQ" | "LES" | "LEQ" => ElementKind::Compare {
                op: match keyword {
                    "EQU" => CompareOp::Equ,
                    "NEQ" => CompareOp::Neq,
                    "GRT" => CompareOp::Grt,
                    "GEQ" => CompareOp::Geq,
                    "LES" => CompareOp::Les,
                    _ => CompareOp::Leq,
                },
                a: operand(args[0]),
                b: operand(args[1]),
            },
            "MOVE" => ElementKind::Move { dest: name(0), src: operand(args[1]) },
            "ADD" | "SUB" | "MUL" | "DIV" => ElementKind::Math {
                op: match keyword {
                    "ADD" => MathOp::Add,
                    "SUB" => MathOp::Sub,
                    "MUL" => MathOp::Mul,
                    _ => MathOp::Div,
                },
                dest: name(0),
                a: operand(args[1]),
                b: operand(args[2]),
            },
            _ => ElementKind::Other {
                keyword: keyword.to_string(),
                args: args.iter().map(|a| a.to_string()).collect(),
            },
        };
        if let Some(e) = bad {
            self.errors.push(e);
            return None;
        }
        Some(Element { kind, span })
    }
}

/// Reads an LDmicro `.ld` file already registered in `sources` (decode the bytes
/// with [`decode_latin1`] first). Returns the program (with warnings in
/// [`LdProgram::warnings`]) or every error found, each located in the file.
pub fn read_ldmicro(sources: &Sources, file: FileId) -> Result<LdProgram, Vec<LadderError>> {
    let text = sources.text(file);
    let mut p = Parser {
        file,
        lines: split_lines(text),
        pos: 0,
        version: HeaderVersion::Missing,
        errors: Vec::new(),
        warnings: Vec::new(),
        var_bytes: BTreeMap::new(),
    };
    let (cycle_us, micro, io_list, _) = p.header();
    if !p.errors.is_empty() {
        return Err(p.errors);
    }
    // Skip the PROGRAM line.
    p.pos += 1;
    let rungs = p.rungs();
    match rungs {
        Ok(rungs) if p.errors.is_empty() => Ok(LdProgram {
            version: p.version,
            cycle_us,
            micro,
            io_list,
            rungs,
            warnings: p.warnings,
            inputs: None,
            var_bytes: p.var_bytes,
            slicing: Default::default(),
        }),
        _ => Err(p.errors),
    }
}

/// The integer and peripheral elements that LDmicro runs only when their input is true
/// and that pass their input through unchanged (`o = i`, ldmicro.md §4). The peripheral
/// writes among them (`SET_PWM` to `BUS`) are `if (in) { … }` blocks that leave the
/// power as it is in LDmicro's `intcode.cpp` (`ELEM_SET_PWM`, `ELEM_I2C_RD`,
/// `ELEM_I2C_WR`, `ELEM_SPI`, `ELEM_SPI_WR`, `ELEM_STRING`, `ELEM_7SEG` … `ELEM_16SEG`,
/// `ELEM_BUS`); what they read or write in the peripheral is not computed.
pub const PASS_THROUGH: &[&str] = &[
    "SET_PWM",
    "I2C_RD",
    "I2C_WR",
    "SPI",
    "SPI_WR",
    "STRING",
    "7SEGMENTS",
    "9SEGMENTS",
    "14SEGMENTS",
    "16SEGMENTS",
    "BUS",
    "MOD",
    "AND",
    "OR",
    "XOR",
    "SHL",
    "SHR",
    "SR0",
    "ROL",
    "ROR",
    "NOT",
    "NEG",
    "BIN2BCD",
    "BCD2BIN",
    "SWAP",
    "OPPOSITE",
    "SET_BIT",
    "CLEAR_BIT",
    "SHIFT_REGISTER",
    "LOOK_UP_TABLE",
    "PIECEWISE_LINEAR",
    "RANDOM",
    "SEED_RANDOM",
    "PERSIST",
];

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<LdProgram, Vec<LadderError>> {
        let mut s = Sources::new();
        let f = s.add("t.ld", text);
        read_ldmicro(&s, f)
    }

    #[test]
    fn reads_a_small_orig_file() {
        let p = read(
            "LDmicro0.1\r\nCYCLE=10000\r\n\r\nIO LIST\r\n    X0 at 2\r\nEND\r\n\r\nPROGRAM\r\nRUNG\r\n    PARALLEL\r\n        CONTACTS X0 0\r\n        CONTACTS Y0 0\r\n    END\r\n    TON T0 500000\r\n    COIL Y0 0 0 0\r\nEND\r\n",
        )
        .unwrap();
        assert_eq!(p.version, HeaderVersion::V0_1);
        assert_eq!(p.cycle_us, 10000);
        assert_eq!(p.io_list[0].name, "X0");
        assert_eq!(p.io_list[0].pin_number(), Some(2));
        let e = p.rungs[0].elements();
        assert_eq!(e.len(), 4);
        assert!(matches!(
            &e[2].kind,
            ElementKind::Timer {
                kind: TimerKind::Ton,
                delay: TimerDelay::Micros(500000),
                adjust: -1,
                ..
            }
        ));
        assert_eq!(p.signals().into_iter().collect::<Vec<_>>(), ["X0", "Y0"]);
    }

    #[test]
    fn long_forms_and_flattening() {
        let p = read(
            "LDmicro0.2\nCYCLE=1000 us at Timer0, YPlcCycleDuty:1\nPROGRAM\nRUNG 1\n  SERIES\n    CONTACTS Xa 1 0\n  END\n  ; not for release\n  TOF Tx 5000 0\n  CTU Cx var 5 o\n  COIL Ry 0 0 0 1\nEND\n",
        )
        .unwrap();
        assert_eq!(p.cycle_us, 1000);
        let r = &p.rungs[0];
        assert_eq!(r.label, Some(1));
        let Circuit::Series(items) = &r.body else { panic!() };
        assert_eq!(items.len(), 4);
        let e = r.elements();
        assert!(matches!(&e[0].kind, ElementKind::Contacts { negated: true, .. }));
        assert!(matches!(&e[1].kind, ElementKind::Timer { adjust: 0, .. }));
        assert!(matches!(
            &e[2].kind,
            ElementKind::Counter {
                limit: Operand::Var(_),
                init: Operand::Literal(5),
                edge: CounterEdge::Low,
                ..
            }
        ));
        assert!(matches!(&e[3].kind, ElementKind::Coil { kind: CoilKind::Toggle, .. }));
    }

    #[test]
    fn unknown_keyword_suggests() {
        let errs = read("LDmicro0.1\nPROGRAM\nRUNG\n  CONTACT X0 0\nEND\n").unwrap_err();
        match &errs[0] {
            LadderError::UnknownKeyword { suggestion, .. } => {
                assert_eq!(suggestion.as_deref(), Some("CONTACTS"))
            }
            e => panic!("{e:?}"),
        }
    }

    #[test]
    fn comment_escapes() {
        let p = read("LDmicro\nPROGRAM\nRUNG\n  COMMENT a\\r\\nb \\\\ c\nEND\n").unwrap();
        assert!(
            matches!(&p.rungs[0].elements()[0].kind, ElementKind::Comment(t) if t == "a\r\nb \\ c")
        );
        assert!(p.rungs[0].is_comment(&p.version));
    }

    #[test]
    fn header_versions_and_defaults() {
        let p = read("LDmicro\nPROGRAM\nRUNG 1\n  TON T0 100000\nEND\n").unwrap();
        assert_eq!(p.version, HeaderVersion::V0_2(String::new()));
        assert_eq!(p.cycle_us, 10000, "CYCLE defaults to 10 ms");
        assert!(matches!(&p.rungs[0].elements()[0].kind, ElementKind::Timer { adjust: 0, .. }));
        let p = read("LDmicro v0.2\nCYCLE=1000000\nPROGRAM\n").unwrap();
        assert_eq!(p.version, HeaderVersion::V0_2(" v0.2".into()));
        assert_eq!(p.cycle_us, 1000000);
        assert!(p.rungs.is_empty());
        let p = read("PROGRAM\nRUNG\nEND\n").unwrap();
        assert_eq!(p.version, HeaderVersion::Missing);
        assert_eq!(p.version.default_adjust(), -1);
        assert_eq!(p.rungs[0].body, Circuit::Series(vec![]));
    }

    #[test]
    fn normalisation_of_nesting() {
        let p = read(
            "LDmicro0.1\nPROGRAM\nRUNG\n  PARALLEL\n    SERIES\n      CONTACTS Xa 0\n    END\n    CONTACTS Xb 0\n  END\n  PARALLEL\n    SERIES\n      CONTACTS Xc 0\n      CONTACTS Xd 0\n    END\n  END\n  PARALLEL\n  END\n  COIL Yq 0 0 0\nEND\n",
        )
        .unwrap();
        let Circuit::Series(items) = &p.rungs[0].body else { panic!() };
        // PARALLEL(Xa, Xb), then the one-branch parallel spliced (Xc, Xd), the empty parallel, the coil.
        assert_eq!(items.len(), 5);
        assert!(
            matches!(&items[0], Circuit::Parallel(b) if b.len() == 2 && matches!(b[0], Circuit::Element(_)))
        );
        assert!(matches!(&items[1], Circuit::Element(_)));
        assert!(matches!(&items[2], Circuit::Element(_)));
        assert_eq!(items[3], Circuit::Parallel(vec![]));
    }

    #[test]
    fn leaf_errors_are_all_reported() {
        let errs = read("LDmicro0.1\nPROGRAM\nRUNG\n  CONTACTS X0\n  FOO\n  TON T0 abc!\nEND\n")
            .unwrap_err();
        assert_eq!(errs.len(), 3, "{errs:?}");
        assert!(matches!(errs[0], LadderError::Arity { .. }));
        assert!(matches!(errs[1], LadderError::UnknownKeyword { .. }));
        assert!(matches!(errs[2], LadderError::BadArgument { .. }));
    }

    #[test]
    fn header_warnings_and_names() {
        let p = read(
            "LDmicro0.1\nFOO=1\nsomething odd\nEND\nIO LIST\n  Xa at 2 0 0\n  junk\nEND\nPROGRAM\nRUNG\n  PLACEHOLDER\n  MOVE Cx Ty\n  READ_ADC Ain\n  COIL Yq 0 0 0\nEND\n",
        )
        .unwrap();
        assert_eq!(p.warnings.len(), 5, "{:?}", p.warnings);
        assert_eq!(p.io_list.len(), 1);
        let e = p.rungs[0].elements();
        assert_eq!(e[1].names_read(), ["Ty"]);
        assert_eq!(e[1].names_written(), ["Cx"]);
        assert_eq!(e[2].names_written(), ["Ain"]);
        assert!(e[2].names_read().is_empty());
        assert_eq!(e[3].names_written(), ["Yq"]);
        assert_eq!(e[2].kind.keyword(), "READ_ADC");
    }
}
