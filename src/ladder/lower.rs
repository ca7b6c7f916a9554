//! Lowering of an LDmicro program ([`LdProgram`]) into the scan model ([`Program`]): LDmicro's power flow, master relay and elements as blocks of statements, one block per rung.
//!
//! Power flows as in LDmicro (ldmicro.md §6.2): series is `·`, parallel is `+`, a
//! contact is its signal or its complement, `SHORT` is `1*`, `OPEN`/`PLACEHOLDER` is
//! `0*`, and elements after a false still execute: a coil in the middle of a series
//! gets the power at that point. The power after each element is a scan-local value
//! ([`Stmt::Let`]), so every read happens where the PLC makes it. A rung's rung-in is
//! the master-relay bit, modelled exactly (§6.6: `MASTER_RELAY` with input `i` makes it
//! `¬mcr + i`; it is `1*` at the start of every scan). Bits are written only by coils
//! (timers, counters, `RES`, `MOVE` and the integer elements write integers, a separate
//! name space). A TON/TOF with a literal delay is a timer of the scan model; RTO, RTL,
//! THI, TLO, TCY, a TON with a variable delay and a TON/TOF whose accumulator another
//! element writes or reads count their accumulator as an exact integer, as LDmicro's
//! code does ([`timers`]). Integers have LDmicro's sizes ([`sizes`]); the bit
//! operations are computed where LDmicro's targets agree ([`bits`]). What the scan
//! model does not compute is an unconstrained value with the reason (counters and
//! comparisons over integers not computed, the one-shots ODF and OSC, text elements,
//! UART_SEND and FORMATTED_STRING, whose outputs
//! follow the UART's transmission); integer side effects (MOVE, math, RES) over integers
//! not computed and the peripheral writes (SET_PWM, I2C, SPI, segment and bus elements)
//! pass the power with a note. The peripheral reads (READ_ADC, UART_RECV, the UART's
//! status contacts, I2C_RD and PERSIST's load from EEPROM) are free integer inputs
//! holding what the hardware gives ([`reads`], [`super::readings`]). Elements that change which
//! rungs run (`GOTO`, `GOSUB`, `SUBPROG`/`ENDSUB`, `RETURN`, `LOCK`, `SLEEP`) and coils
//! on bits the outside world writes refuse the program with a located error.
#![warn(missing_docs)]

mod bits;
mod reads;
mod sizes;
mod timers;

use std::collections::{BTreeMap, BTreeSet};

use super::LadderError;
use super::ldmicro::{
    Circuit, CoilKind, CompareOp, CounterEdge, CounterKind, EdgeKind, Element, ElementKind,
    LdProgram, MathOp, Operand, TimerDelay, TimerKind,
};
use crate::program::{
    Block, BoolExpr, CmpOp, Compare, Fresh, Inputs, IntExpr, IntType, IntVar, Memory, Preset,
    Program, Stmt, Temp, Timer, WriteKind, canonical,
};

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

/// The bits the outside world writes: the program's declared inputs if it has them, else
/// LDmicro's rule (ldmicro.md §5).
fn inputs(program: &LdProgram) -> Inputs {
    match &program.inputs {
        Some(set) => Inputs::Declared(set.clone()),
        None => Inputs::ByPrefix,
    }
}

/// Lowers an LDmicro program into the scan model. Never panics; refuses, with located
/// errors, what a plain top-to-bottom scan cannot describe.
pub fn lower(program: &LdProgram) -> Result<Program, Vec<LadderError>> {
    let ins = inputs(program);
    let refused: Vec<LadderError> = program
        .elements()
        .filter_map(|e| {
            if let ElementKind::Coil { name, .. } = &e.kind
                && ins.contains(&canonical(name))
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
    let mut l = Lowering::new(program);
    l.run();
    Ok(l.finish(ins))
}

struct Lowering<'a> {
    program: &'a LdProgram,
    /// Each element's position among all the program's elements, in file order (the
    /// simulator's key of a one-shot's memory).
    /// Built at the first one-shot or toggle (most programs have none).
    index: std::cell::OnceCell<std::collections::HashMap<*const Element, usize>>,
    /// The timers whose accumulator is an integer of the scan model
    /// ([`timers::integer_timers`]).
    int_timers: BTreeSet<String>,
    blocks: Vec<Block>,
    stmts: Vec<Stmt>,
    next_temp: Temp,
    /// The master-relay bit.
    mcr: Temp,
    /// The current rung's number.
    number: usize,
    /// The integers computed exactly (signed, of LDmicro's sizes), with their
    /// power-up values; the others (a timer's count, what a peripheral or `DIV` writes,
    /// and what is computed from those) are not modelled.
    ints: BTreeMap<String, IntVar>,
    /// Why each integer that is not computed is not (see [`integers`]).
    opaque: BTreeMap<String, String>,
    /// The peripheral reads, by element index (see [`super::readings`]).
    readings: BTreeMap<usize, super::Reading>,
    /// THI, TLO and TCY's state bits (see [`super::timer_bits`]).
    timer_bits: BTreeMap<(usize, u8), String>,
    /// The hidden 1-bit integers the lowering made (THI, TLO and TCY's state bits).
    hidden_bits: BTreeSet<String>,
}

impl<'a> Lowering<'a> {
    fn new(program: &'a LdProgram) -> Lowering<'a> {
        let int_timers = timers::integer_timers(&live(program));
        let readings = super::readings(program);
        let (ints, opaque) = integers(program, &readings);
        Lowering {
            program,
            index: std::cell::OnceCell::new(),
            int_timers,
            blocks: Vec::new(),
            stmts: Vec::new(),
            next_temp: 1,
            mcr: 0,
            number: 0,
            ints,
            opaque,
            readings,
            timer_bits: super::timer_bits(program),
            hidden_bits: BTreeSet::new(),
        }
    }

    /// Whether every integer the element reads or writes is computed exactly.
    fn exact(&self, e: &Element) -> bool {
        let ints = int_names(e);
        !ints.is_empty() && ints.iter().all(|n| self.ints.contains_key(&canonical(n)))
    }

    /// Why the element reads or writes an integer that is not computed exactly, for its
    /// warning: the first such integer and its cause.
    fn opaque_why(&self, e: &Element) -> String {
        let names = int_names(e);
        match names.iter().find_map(|n| Some((n, self.opaque.get(n)?))) {
            Some((n, why)) => format!("{n}, which ii-prove does not compute: {why}"),
            None => "no integer".into(),
        }
    }

    fn operand(&self, op: &Operand) -> IntExpr {
        match op {
            Operand::Literal(v) => IntExpr::Const(*v),
            Operand::Var(v) => IntExpr::Var(canonical(v)),
        }
    }

    /// The type an operand is read in: a variable's own, a literal's in a new file as
    /// many bytes as it needs (`sizes::literal_type`), in orig 16 bits.
    fn ty(&self, op: &Operand) -> IntType {
        match op {
            Operand::Var(v) => self.ints.get(&canonical(v)).map_or(IntType::I16, |x| x.ty),
            Operand::Literal(_) if self.program.version.is_orig() => IntType::I16,
            Operand::Literal(v) => sizes::literal_type(*v),
        }
    }

    /// The comparison `a op b` of two operands, in the larger of their types.
    fn compare(&self, op: CmpOp, a: &Operand, b: &Operand) -> BoolExpr {
        let ty = sizes::wider(self.ty(a), self.ty(b));
        let (a, b) = (self.operand(a), self.operand(b));
        BoolExpr::Compare(Box::new(Compare { op, ty, a, b }))
    }

    /// `if power then x := value`.
    fn set_int(&mut self, e: &Element, x: &str, power: &BoolExpr, value: IntExpr) {
        let x = canonical(x);
        let value = IntExpr::ite(power.clone(), value, IntExpr::Var(x.clone()));
        self.stmts.push(Stmt::SetInt { target: x, value, span: e.span });
    }

    /// A counter, exactly as the runtime counts (ldmicro.md §6.4): its output.
    fn counter(&mut self, e: &Element, input: BoolExpr) -> BoolExpr {
        let ElementKind::Counter { kind, name, limit, init, edge } = &e.kind else { return input };
        let orig = self.program.version.is_orig();
        let c = || IntExpr::Var(canonical(name));
        let count = Operand::Var(name.clone());
        let c_ty = self.ty(&count);
        let ty = sizes::wider(c_ty, self.ty(limit));
        let limit = self.operand(limit);
        let cmp =
            |op, a: IntExpr, b: IntExpr| BoolExpr::Compare(Box::new(Compare { op, ty, a, b }));
        let one = || IntExpr::Const(1);
        // What makes it count; the hidden bit keeps the power of the previous scan.
        let trigger = match edge {
            CounterEdge::Rising | CounterEdge::Falling => {
                let memory = self.memory(format!("{}_r{}", e.kind.keyword(), self.number), e);
                let kind = if *edge == CounterEdge::Rising {
                    crate::program::EdgeKind::Rising
                } else {
                    crate::program::EdgeKind::Falling
                };
                BoolExpr::Edge { kind, input: Box::new(input.clone()), memory: Box::new(memory) }
            }
            CounterEdge::High => input.clone(),
            CounterEdge::Low => BoolExpr::negate(input.clone()),
        };
        let trigger = self.temp(trigger);
        // CTC and CTR reload this element's own start value (§6.4); orig has none (0).
        let init = if orig { IntExpr::Const(0) } else { self.operand(init) };
        match (kind, orig) {
            (CounterKind::Ctu | CounterKind::Ctd, _) => {
                let up = *kind == CounterKind::Ctu;
                let step = if up { IntExpr::plus(c(), one()) } else { IntExpr::minus(c(), one()) };
                // new: CTU stops at max, CTD at its floor.
                let power = if orig {
                    trigger
                } else {
                    let room = cmp(if up { CmpOp::Lt } else { CmpOp::Gt }, c(), limit.clone());
                    self.temp(BoolExpr::and(trigger, room))
                };
                self.set_int(e, name, &power, step);
                let op = if !orig && !up { CmpOp::Gt } else { CmpOp::Ge };
                self.temp(cmp(op, c(), limit))
            }
            (CounterKind::Ctc | CounterKind::Ctr, _) => {
                let up = *kind == CounterKind::Ctc;
                let step = if up { IntExpr::plus(c(), one()) } else { IntExpr::minus(c(), one()) };
                // The count is incremented (wrapping to its size) before the comparison
                // (`intcode.cpp`, `ELEM_CTC`: `INT_INCREMENT_VARIABLE`, then `INT_IF_GRT`).
                let stored = IntExpr::Cast(Box::new(step.clone()), c_ty);
                let past = cmp(if up { CmpOp::Gt } else { CmpOp::Lt }, stored, limit);
                let past = self.temp(past);
                // CTC wraps to 0 (orig) or init (new); CTR reloads init.
                let reload = if up && orig { IntExpr::Const(0) } else { init };
                let next = IntExpr::ite(past.clone(), reload, step);
                self.set_int(e, name, &trigger, next);
                // orig CTC passes its input; new CTC and CTR pulse on the reload.
                if up && orig { input } else { self.temp(BoolExpr::and(trigger, past)) }
            }
        }
    }

    fn run(&mut self) {
        let program = self.program;
        let version = &program.version;
        let n_logic = program.rungs.iter().filter(|r| !r.is_comment(version)).count();
        let width = n_logic.to_string().len().max(2);
        self.stmts.push(Stmt::Let { temp: self.mcr, value: BoolExpr::Const(true) });
        let mut k = 0;
        for rung in &program.rungs {
            self.number = rung.number;
            let label = if rung.is_comment(version) {
                let extra =
                    rung.elements().iter().any(|e| !matches!(e.kind, ElementKind::Comment(_)));
                if extra {
                    self.warn(
                        rung.span,
                        "COMMENT",
                        "LDmicro skips a rung whose first element is a COMMENT; \
                         its other elements are not compiled",
                    );
                }
                None
            } else {
                k += 1;
                // The rung-in as the rung starts (a master relay in it changes the bit).
                let rung_in = self.temp(BoolExpr::Temp(self.mcr));
                self.circuit(&rung.body, rung_in);
                Some(format!("L{k:0width$}"))
            };
            let stmts = std::mem::take(&mut self.stmts);
            self.blocks.push(Block { number: rung.number, label, span: rung.span, stmts });
        }
    }

    fn finish(self, inputs: Inputs) -> Program {
        let program = self.program;
        let version = &program.version;
        let mut read: Vec<&str> = Vec::new();
        let mut written: Vec<String> = Vec::new();
        for e in program.elements() {
            read.extend(e.names_read());
            written.extend(e.names_written());
        }
        read.sort_unstable();
        read.dedup();
        let mut all: Vec<String> =
            read.into_iter().chain(written.iter().map(String::as_str)).map(canonical).collect();
        all.sort_unstable();
        all.dedup();
        let mut names: BTreeSet<String> = all.into_iter().collect();
        for r in self.readings.values() {
            names.extend(r.names().map(|n| canonical(n)));
        }
        names.extend(self.hidden_bits.iter().cloned());
        // PERSIST's one-shot and the timers' state bits are the lowering's own integers,
        // never outputs to compare.
        let mut hidden: BTreeSet<String> =
            self.readings.values().flat_map(|r| &r.once).map(|n| canonical(n)).collect();
        hidden.extend(self.hidden_bits.iter().cloned());
        let skipped = program
            .rungs
            .iter()
            .filter(|r| r.is_comment(version))
            .flat_map(|r| {
                r.elements().into_iter().filter_map(move |e| match &e.kind {
                    ElementKind::Contacts { name, .. } | ElementKind::Coil { name, .. } => {
                        Some((canonical(name), r.number))
                    }
                    _ => None,
                })
            })
            .collect();
        Program {
            cycle_us: program.cycle_us,
            blocks: self.blocks,
            inputs,
            signals: program.signals().iter().map(|s| canonical(s)).collect(),
            names,
            skipped,
            integer_writers: BTreeMap::new(),
            integers: self.ints,
            exact_names: program.inputs.is_some(),
            block_noun: "rung",
            language: "an LDmicro",
            started: None,
            hidden,
            // LDmicro's runtime wraps its 16-bit arithmetic: nothing is undefined.
            undefined: BTreeSet::new(),
        }
    }

    fn warn(&mut self, span: crate::diag::Span, element: &str, message: &str) {
        self.stmts.push(Stmt::Warn { span, element: element.into(), message: message.into() });
    }

    /// A new scan-local value, computed here.
    fn temp(&mut self, value: BoolExpr) -> BoolExpr {
        let temp = self.next_temp;
        self.next_temp += 1;
        self.stmts.push(Stmt::Let { temp, value });
        BoolExpr::Temp(temp)
    }

    fn fresh(&mut self, base: String, e: &Element, why: &str) -> BoolExpr {
        self.free(base, e, why, false)
    }

    /// A free value for `e`'s output: unconstrained, or a peripheral read.
    fn free(&mut self, base: String, e: &Element, why: &str, peripheral: bool) -> BoolExpr {
        let keyword = e.kind.keyword().into();
        let fresh = Fresh { base, keyword, why: why.into(), span: e.span, peripheral };
        self.temp(BoolExpr::Fresh(Box::new(fresh)))
    }

    /// The element's position among all the program's elements, in file order.
    fn element_index(&self, e: &Element) -> usize {
        let index = self.index.get_or_init(|| {
            let elements = self.program.elements().enumerate();
            elements.map(|(k, e)| (e as *const Element, k)).collect()
        });
        index.get(&(e as *const Element)).copied().unwrap_or(usize::MAX)
    }

    fn memory(&self, base: String, e: &Element) -> Memory {
        let index = self.element_index(e);
        Memory { base, element: e.kind.keyword().into(), index }
    }

    /// The power out of circuit `c` fed with `input` (a value already computed).
    fn circuit(&mut self, c: &Circuit, input: BoolExpr) -> BoolExpr {
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
                             to them",
                        );
                    }
                }
                items.iter().fold(input, |power, item| self.circuit(item, power))
            }
            Circuit::Parallel(branches) if branches.iter().all(is_pure) => {
                // Pure conditions: `i · (c1 + c2 + …)`, the readable factored form.
                let outs: Vec<BoolExpr> =
                    branches.iter().map(|b| self.circuit(b, BoolExpr::Const(true))).collect();
                self.temp(BoolExpr::and(input, BoolExpr::Or(outs)))
            }
            Circuit::Parallel(branches) => {
                let outs: Vec<BoolExpr> =
                    branches.iter().map(|b| self.circuit(b, input.clone())).collect();
                self.temp(BoolExpr::Or(outs))
            }
            Circuit::Element(e) => self.element(e, input),
        }
    }

    fn element(&mut self, e: &Element, input: BoolExpr) -> BoolExpr {
        let number = self.number;
        match &e.kind {
            // LDmicro ≥ 2016 sets this relay when an ADD, SUB or a counter overflows
            // (`intcode.cpp`), which the scan model does not compute.
            ElementKind::Contacts { name, .. }
                if name == OVERFLOW_FLAG && !self.program.version.is_orig() =>
            {
                let why = "ROverflowFlagV is set by LDmicro when integer arithmetic \
                           overflows, which ii-prove does not model";
                let f = self.fresh(format!("{name}_r{number}"), e, why);
                self.temp(BoolExpr::and(input, f))
            }
            ElementKind::Contacts { name, negated } => {
                let v = BoolExpr::var(&canonical(name));
                let v = if *negated { BoolExpr::negate(v) } else { v };
                self.temp(BoolExpr::and(input, v))
            }
            ElementKind::Coil { name, kind } => {
                let kind = match kind {
                    CoilKind::Normal => WriteKind::Assign,
                    CoilKind::Negated => WriteKind::AssignNot,
                    CoilKind::Set => WriteKind::Set,
                    CoilKind::Reset => WriteKind::Reset,
                    CoilKind::Toggle => {
                        // On a rising edge of the power the bit flips (ldmicro.md §4, COIL
                        // ttrigger): the edge is `i · ¬pre i` over the coil's hidden bit.
                        WriteKind::Toggle(Box::new(self.memory(format!("TOGGLE_r{number}"), e)))
                    }
                };
                let target = canonical(name);
                self.stmts.push(Stmt::Write { target, kind, value: input.clone(), span: e.span });
                input
            }
            ElementKind::Short | ElementKind::Comment(_) => input,
            ElementKind::Open => BoolExpr::Const(false),
            ElementKind::Placeholder => {
                self.warn(e.span, "PLACEHOLDER", "an empty editor slot, read as OPEN (0*)");
                BoolExpr::Const(false)
            }
            ElementKind::MasterRelay => {
                let mcr =
                    BoolExpr::Or(vec![BoolExpr::negate(BoolExpr::Temp(self.mcr)), input.clone()]);
                self.stmts.push(Stmt::Let { temp: self.mcr, value: mcr });
                input
            }
            ElementKind::Timer { name, .. } if self.int_timers.contains(name) => {
                self.int_timer(e, input)
            }
            ElementKind::Timer { kind, name, delay, adjust, adjust_given } => {
                let keyword = e.kind.keyword();
                let why = match kind {
                    TimerKind::Ton | TimerKind::Tof => {
                        let preset = match delay {
                            TimerDelay::Micros(us) => Preset::Micros {
                                us: *us,
                                adjust: *adjust,
                                default_of: (!adjust_given).then(|| self.program.version.label()),
                                zero: false,
                            },
                            TimerDelay::Variable(v) => {
                                Preset::Variable { name: v.clone(), why: None }
                            }
                        };
                        let timer = Timer {
                            on_delay: *kind == TimerKind::Ton,
                            keyword: keyword.into(),
                            accumulator: name.clone(),
                            preset,
                            input,
                            span: e.span,
                            // LDmicro has no conditional statements.
                            called: false,
                        };
                        return self.temp(BoolExpr::Timer(Box::new(timer)));
                    }
                    _ => format!("the {keyword} timer is not modelled"),
                };
                self.fresh(format!("{keyword}_{name}"), e, &why)
            }
            ElementKind::Edge { kind: kind @ (EdgeKind::Osr | EdgeKind::Osf | EdgeKind::Odr) } => {
                let memory = self.memory(format!("{}_r{number}", e.kind.keyword()), e);
                let kind = match kind {
                    EdgeKind::Osr => crate::program::EdgeKind::Rising,
                    EdgeKind::Osf => crate::program::EdgeKind::Falling,
                    _ => crate::program::EdgeKind::NotRising,
                };
                self.temp(BoolExpr::Edge { kind, input: Box::new(input), memory: Box::new(memory) })
            }
            ElementKind::Edge { .. } => {
                let base = format!("{}_r{number}", e.kind.keyword());
                self.fresh(base, e, "this one-shot is not expressible in the algebra")
            }
            ElementKind::Counter { .. } if self.exact(e) => self.counter(e, input),
            ElementKind::Res { name } if self.ints.contains_key(&canonical(name)) => {
                // orig clears to 0, new to the counter's start value (§6.5), a timer's
                // count to 0.
                let init = if self.int_timers.contains(name) {
                    0
                } else {
                    self.ints[&canonical(name)].init
                };
                self.set_int(e, name, &input, IntExpr::Const(init));
                input
            }
            ElementKind::Compare { op, a, b } if self.exact(e) => {
                let op = match op {
                    CompareOp::Equ => CmpOp::Eq,
                    CompareOp::Neq => CmpOp::Ne,
                    CompareOp::Grt => CmpOp::Gt,
                    CompareOp::Geq => CmpOp::Ge,
                    CompareOp::Les => CmpOp::Lt,
                    CompareOp::Leq => CmpOp::Le,
                };
                // A `LDmicro0.1` file's literal that does not fit 16 bits (`0xffff`):
                // orig (2.2, intcode.cpp `CheckMakeNumber`) reads it with `atoi` (`0xffff`
                // is 0) or refuses it out of range; new puts it in a temporary whose size
                // it chooses (`VarFromExpr`): 65535 in two bytes reads as -1, in three as
                // 65535. Which LDmicro runs the file is not known. New compares both sides sign-extended to the larger size, a
                // literal as wide as it needs (`NEW_CMP`, see `sizes`): exactly.
                let orig = self.program.version.is_orig();
                let wide = [a, b].iter().find_map(|o| match o {
                    Operand::Literal(v) if orig && !IntType::I16.contains(*v) => Some(*v),
                    _ => None,
                });
                if let Some(v) = wide {
                    let why = format!(
                        "the literal {v} does not fit 16 bits: orig LDmicro reads a hex \
                         literal with atoi (0xffff as 0) and refuses a decimal one, new \
                         LDmicro puts it in a temporary of a size it chooses (so it reads as \
                         {} or {v}), and which LDmicro runs this LDmicro0.1 file is not known",
                        IntType::I16.wrap(v)
                    );
                    let f = self.fresh(format!("{}_r{number}", e.kind.keyword()), e, &why);
                    return self.temp(BoolExpr::and(input, f));
                }
                let c = self.compare(op, a, b);
                self.temp(BoolExpr::and(input, c))
            }
            ElementKind::Move { dest, src } if self.exact(e) => {
                let src = self.operand(src);
                self.set_int(e, dest, &input, src);
                input
            }
            ElementKind::Math { op, dest, a, b }
                if self.exact(e) && (*op != MathOp::Div || nonzero_literal(b).is_some()) =>
            {
                let divisor = nonzero_literal(b);
                let (a, b) = (self.operand(a), self.operand(b));
                let value = match (op, divisor) {
                    (MathOp::Add, _) => IntExpr::plus(a, b),
                    (MathOp::Sub, _) => IntExpr::minus(a, b),
                    (MathOp::Div, Some(k)) => IntExpr::Div(Box::new(a), k),
                    _ => IntExpr::Mul(Box::new(a), Box::new(b)),
                };
                self.set_int(e, dest, &input, value);
                input
            }
            ElementKind::Counter { kind, name, .. } => {
                if *kind == CounterKind::Ctc && self.program.version.is_orig() {
                    self.warn(
                        e.span,
                        "CTC",
                        &format!(
                            "the count of {name} is not modelled; the output passes its \
                             input (orig CTC), exactly"
                        ),
                    );
                    input
                } else {
                    let base = format!("{}_{}", e.kind.keyword(), name);
                    let why = format!("the count {name} depends on {}", self.opaque_why(e));
                    self.fresh(base, e, &why)
                }
            }
            ElementKind::Res { name } => {
                let message =
                    format!("resets the count of {name}: no Boolean effect; the power passes");
                self.warn(e.span, "RES", &message);
                input
            }
            ElementKind::Compare { .. } => {
                let base = format!("{}_r{number}", e.kind.keyword());
                let why = format!("the comparison reads {}", self.opaque_why(e));
                let f = self.fresh(base, e, &why);
                self.temp(BoolExpr::and(input, f))
            }
            ElementKind::Move { dest, .. } | ElementKind::Math { dest, .. } => {
                let message =
                    format!("writes the integer {dest}: no Boolean effect; the power passes");
                self.warn(e.span, e.kind.keyword(), &message);
                input
            }
            // A label only marks a place to jump to (jumps are refused, see `lower`).
            ElementKind::Other { keyword, .. } if keyword == "LABEL" => input,
            ElementKind::Other { keyword, .. }
                if is_read(keyword) && (self.exact(e) || e.names_written().is_empty()) =>
            {
                self.read(e, input)
            }
            ElementKind::Other { .. } if self.exact(e) && bits::BitElem::of(e).is_some() => {
                if let Some(b) = bits::BitElem::of(e) {
                    let d = self.ty(&Operand::Var(b.dest.clone()));
                    self.set_int(e, &b.dest, &input, b.value(d));
                }
                input
            }
            ElementKind::Other { args, .. } if self.exact(e) => {
                // SHIFT_REGISTER (ldmicro.md §4): on the rising edge of the power,
                // `name{k} := name{k-1}` for k = stages-1 down to 1; the power passes.
                let stages = shift_stages(e).unwrap_or(0);
                let memory = self.memory(format!("SHIFT_REGISTER_r{}", self.number), e);
                let rising = BoolExpr::Edge {
                    kind: crate::program::EdgeKind::Rising,
                    input: Box::new(input.clone()),
                    memory: Box::new(memory),
                };
                let rising = self.temp(rising);
                for k in (1..stages).rev() {
                    let from = IntExpr::Var(canonical(&format!("{}{}", args[0], k - 1)));
                    self.set_int(e, &format!("{}{k}", args[0]), &rising, from);
                }
                input
            }
            // A reading not computed (its target's ADC range is not known): the value is
            // opaque, but READ_ADC passes its input all the same (ldmicro.md §4).
            ElementKind::Other { keyword, .. } if keyword == "READ_ADC" => {
                let why = format!("a peripheral read: it writes {}", self.opaque_why(e));
                self.warn(e.span, keyword, &why);
                input
            }
            ElementKind::Other { keyword, .. } => {
                if super::ldmicro::PASS_THROUGH.contains(&keyword.as_str()) {
                    self.warn(
                        e.span,
                        keyword,
                        "integer or peripheral operation: no Boolean effect; the power passes",
                    );
                    input
                } else {
                    let uart = matches!(keyword.as_str(), "UART_SEND" | "FORMATTED_STRING");
                    let why = if uart {
                        "a peripheral: its output follows the UART's transmission, which the \
                         hardware times and ii-prove does not model"
                    } else {
                        "an integer, peripheral or text element is not expressible"
                    };
                    self.free(format!("{keyword}_r{number}"), e, why, uart)
                }
            }
        }
    }
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

/// The integer names an element reads or writes.
fn int_names(e: &Element) -> Vec<String> {
    let vars = |ops: &[&Operand]| -> Vec<String> {
        ops.iter().filter_map(|o| o.var().map(str::to_string)).collect()
    };
    match &e.kind {
        ElementKind::Counter { name, limit, init, .. } => {
            let mut v = vars(&[limit, init]);
            v.push(name.clone());
            v
        }
        ElementKind::Res { name } => vec![name.clone()],
        ElementKind::Timer { name, delay, .. } => {
            let mut v = vec![name.clone()];
            if let TimerDelay::Variable(d) = delay {
                v.push(d.clone());
            }
            v
        }
        ElementKind::Compare { a, b, .. } => vars(&[a, b]),
        ElementKind::Move { dest, src } => {
            let mut v = vars(&[src]);
            v.push(dest.clone());
            v
        }
        ElementKind::Math { dest, a, b, .. } => {
            let mut v = vars(&[a, b]);
            v.push(dest.clone());
            v
        }
        ElementKind::Other { keyword, .. } if is_read(keyword) => e.names_written(),
        ElementKind::Other { .. } if let Some(b) = bits::BitElem::of(e) => b.names(),
        ElementKind::Other { keyword, .. } if shift_stages(e).is_some() => {
            debug_assert_eq!(keyword, "SHIFT_REGISTER");
            e.names_written()
        }
        _ => Vec::new(),
    }
}

/// The number of stages of a `SHIFT_REGISTER name stages` (`None` for anything else).
fn shift_stages(e: &Element) -> Option<u32> {
    match &e.kind {
        ElementKind::Other { keyword, args } if keyword == "SHIFT_REGISTER" && args.len() == 2 => {
            args[1].parse().ok()
        }
        _ => None,
    }
}

/// The integers computed exactly: every integer the counters, comparisons, `MOVE`,
/// `ADD`/`SUB`/`MUL`/`DIV`, bit operations and `RES` of the rungs that run read or write, except those
/// something else writes (a timer's count, a `DIV` by a variable or 0, a peripheral
/// ii-prove does not read), those computed from such, and counters whose limit or start value is not
/// a literal or exact integer, or whose size or operation LDmicro's targets compute differently; those come back with why. Each is signed of its size (16 bits in orig); a counter of a new file starts at its `init`
/// (the last counter of that name wins, as the runtime initialises them in order).
fn integers(
    program: &LdProgram,
    readings: &BTreeMap<usize, super::Reading>,
) -> (BTreeMap<String, IntVar>, BTreeMap<String, String>) {
    let orig = program.version.is_orig();
    let adc = super::adc_bits(program.micro.as_deref());
    // A peripheral read whose values are known (see `super::readings`).
    let known = |keyword: &str| keyword != "READ_ADC" || adc.is_ok();
    let live = live(program);
    let timers = timers::Accumulators::new(program, &live);
    // Each integer ii-prove does not compute, with why (the first cause found).
    let mut opaque: BTreeMap<String, String> = BTreeMap::new();
    let mut used: BTreeSet<String> = BTreeSet::new();
    let mut init: BTreeMap<String, i64> = BTreeMap::new();
    let mut cause = |name: &str, why: String| {
        opaque.entry(name.to_string()).or_insert(why);
    };
    for (name, why) in &timers.causes {
        cause(name, why.clone());
    }
    for e in &live {
        match &e.kind {
            ElementKind::Counter { name, .. } if timers.names.contains(name) => {
                cause(name, "it is both a counter's and a timer's count".into());
            }
            ElementKind::Math { op: MathOp::Div, dest, b, .. } if nonzero_literal(b).is_none() => {
                let why = match b {
                    Operand::Var(v) => format!(
                        "it is written by a DIV by {v}, which may be 0 (a division by 0 is \
                         undefined)"
                    ),
                    Operand::Literal(v) => format!("it is written by a DIV by {v}"),
                };
                cause(dest, why);
            }
            ElementKind::Math { op: MathOp::Div, dest, a, b }
                if orig && (a.beyond_16_bits() || b.beyond_16_bits()) =>
            {
                cause(dest, "it is written by a DIV of a literal beyond 16 bits (orig)".into());
            }
            // What a peripheral or an operation ii-prove does not compute writes.
            ElementKind::Other { keyword, .. }
                if shift_stages(e).is_none()
                    && bits::BitElem::of(e).is_none()
                    && !(is_read(keyword) && known(keyword)) =>
            {
                let why = if let (true, Err(why)) = (is_read(keyword), &adc) {
                    format!("it is written by {keyword}, and {why}")
                } else {
                    format!("it is written by {keyword}, which ii-prove does not compute")
                };
                for n in e.names_written() {
                    cause(&n, why.clone());
                }
            }
            ElementKind::Counter { name, limit, init: start, .. } => {
                // orig's integers are 16-bit; new sizes a counter for its literals.
                let fits = if orig { IntType::I16 } else { IntType::int(32, true) };
                let literal = |o: &Operand| matches!(o, Operand::Literal(v) if !fits.contains(*v));
                if literal(limit) || (!orig && (start.var().is_some() || literal(start))) {
                    let why =
                        format!("its limit or start value is not a {}-bit literal", fits.bits);
                    cause(name, why);
                }
                if !orig && let Operand::Literal(v) = start {
                    init.insert(name.clone(), *v);
                }
            }
            _ => {}
        }
        used.extend(int_names(e));
    }
    init.extend(timers.init.iter().map(|(n, p)| (n.clone(), *p)));
    // LDmicro ≥ 2016 stores an integer in 1 to 4 bytes, each a signed integer of its
    // size (`sizes`); orig's are all 16-bit.
    let mut types: BTreeMap<String, IntType> = BTreeMap::new();
    if !orig {
        let bytes = sizes::sizes(program, &live, &timers.bytes);
        for n in &used {
            match bytes.get(n).map(|b| sizes::int_type(*b, program.micro.as_deref())) {
                Some(Ok(ty)) => {
                    types.insert(n.clone(), ty);
                }
                Some(Err(why)) => cause(n, why),
                None => {}
            }
        }
        let ty = |o: &Operand| sizes::operand_type(&types, o);
        // A DIV computes in its destination's size on AVR (its operands cut to it
        // first) but in C's `int` (then cut): the same only when neither is wider.
        for e in &live {
            if let ElementKind::Math { op: MathOp::Div, dest, a, b } = &e.kind {
                let d = types.get(dest).copied().unwrap_or(IntType::I16);
                if ty(a).bits > d.bits || ty(b).bits > d.bits {
                    let why = "it is written by a DIV of operands wider than it, which \
                               LDmicro's AVR code cuts to its size before dividing and its C \
                               code after"
                        .to_string();
                    cause(dest, why);
                }
            }
        }
    }
    // The bit operations ii-prove computes for these sizes and this target (`bits`).
    for b in live.iter().filter_map(|e| bits::BitElem::of(e)) {
        let ty = |o: &Operand| sizes::operand_type(&types, o);
        if let Some(why) = b.why_not(&ty, program.micro.as_deref()) {
            cause(&b.dest, why);
        }
    }
    // What is computed from an opaque integer is opaque.
    loop {
        let before = opaque.len();
        for e in &live {
            let names = int_names(e);
            if let Some(from) = names.iter().find(|n| opaque.contains_key(*n)).cloned() {
                for w in e.names_written().into_iter().filter(|w| names.contains(w)) {
                    opaque.entry(w).or_insert_with(|| format!("it is computed from {from}"));
                }
            }
        }
        if opaque.len() == before {
            break;
        }
    }
    let mut ints: BTreeMap<String, IntVar> = used
        .into_iter()
        .filter(|n| !opaque.contains_key(n))
        .map(|n| {
            let start = init.get(&n).copied().unwrap_or(0);
            let ty = types.get(&n).copied().unwrap_or(IntType::I16);
            (canonical(&n), IntVar { ty, input: false, init: start })
        })
        .collect();
    // The values peripheral reads give the integers computed exactly: free inputs.
    for r in readings.values() {
        if r.var.as_ref().is_some_and(|var| !ints.contains_key(&canonical(var))) {
            continue;
        }
        ints.insert(canonical(&r.value), IntVar { ty: r.ty, input: true, init: 0 });
        if let Some(got) = &r.arrived {
            ints.insert(canonical(got), IntVar { ty: IntType::BIT, input: true, init: 0 });
        }
        if let Some(once) = &r.once {
            ints.insert(canonical(once), IntVar { ty: IntType::BIT, input: false, init: 0 });
        }
    }
    (ints, opaque)
}

/// The elements of the rungs that run (not comment rungs), in scan order.
fn live(program: &LdProgram) -> Vec<&Element> {
    program
        .rungs
        .iter()
        .filter(|r| !r.is_comment(&program.version))
        .flat_map(|r| r.elements())
        .collect()
}

/// Whether `keyword` is a peripheral read, modelled as a free integer input when the
/// values it gives are known (see [`super::readings`]).
fn is_read(keyword: &str) -> bool {
    matches!(keyword, "READ_ADC" | "UART_RECV" | "PERSIST" | "I2C_RD")
        || super::STATUS_CONTACTS.contains(&keyword)
}

/// The relay LDmicro ≥ 2016 sets on an integer overflow.
const OVERFLOW_FLAG: &str = "ROverflowFlagV";

/// How many bytes LDmicro gives an integer that must hold `v` (`byteNeeded`).
fn bytes_needed(v: i64) -> u32 {
    match v {
        -128..=127 => 1,
        -32768..=32767 => 2,
        -8388608..=8388607 => 3,
        _ => 4,
    }
}

/// The divisor of a DIV when it is a 16-bit literal other than 0 (a division ii-prove
/// computes exactly).
fn nonzero_literal(b: &Operand) -> Option<i64> {
    match b {
        Operand::Literal(v) if *v != 0 && IntType::I16.contains(*v) => Some(*v),
        _ => None,
    }
}
