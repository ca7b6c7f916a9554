//! Lowering of a checked PLCopen program ([`PlcProgram`]) into the scan model ([`Program`]), statement by statement in evaluation order.
//!
//! Each statement becomes one block: a coil or output variable is a write of its
//! power, a block call is one write per output it sets. Block outputs, FB instance
//! pins and edge detectors are hidden variables (`TON0_Q`, `SR0_S1`, `_TMP_AND7_OUT`,
//! `_TRIG12`, see `docs/plcopen.md`), so a value computed once per scan is read by
//! every consumer, and a read before the writer sees the previous scan, exactly as in
//! the scan model. Negation of a compound value is pushed to the variables (De
//! Morgan). Integers are the scan model's (`lower/ints.rs`); a function block under a
//! wired `EN` runs its body under its instance's `ENO` (`lower/fbs.rs`). What the
//! algebra cannot express (library blocks not modelled, non-Boolean values in a Boolean
//! place) becomes an unconstrained value, which the compiler names with a warning
//! naming the block.

use std::collections::{BTreeMap, BTreeSet};

use super::{
    Edge, ObjKind, Operand, PinIn, PlcError, PlcProgram, Source, Std, Storage, unconnected,
};
use crate::diag::Span;
use crate::program::{Block, BoolExpr, Fresh, Inputs, IntVar, Memory, Program, Stmt, WriteKind};

mod durations;
mod en;
mod fbs;
mod ints;
mod strings;
mod text;

/// A lowered program: the scan model and the warnings of reading and lowering.
pub struct Lowered {
    /// The program, one block per statement, in scan order.
    pub program: Program,
    /// Warnings (order decisions, defaults), each located in the XML.
    pub warnings: Vec<PlcError>,
    /// For each one-shot of `program` (its memory's index), the edge detector it stands for:
    /// the path of inlined block indices, the owning object and the pin (see
    /// [`PlcSimulator::edge_memory_of`](super::PlcSimulator::edge_memory_of)).
    pub edges: Vec<EdgeKey>,
}

/// Which edge detector of a PLCopen program a one-shot element stands for.
pub type EdgeKey = (Vec<usize>, usize, String);

struct Lower<'p> {
    p: &'p PlcProgram,
    blocks: Vec<Block>,
    called: BTreeSet<usize>,
    in_progress: BTreeSet<usize>,
    /// While the inputs of a block with an `executionOrderId` are computed: blocks not
    /// yet called are not called, their outputs read as they stand (Beremiz's
    /// `GenerateBlock(order=True)`); they run at their own place in the order.
    no_pull: bool,
    trigs: BTreeSet<(usize, String)>,
    visiting: BTreeSet<usize>,
    errors: Vec<PlcError>,
    warnings: Vec<PlcError>,
    /// Names a coil has written so far in the scan.
    emitted: BTreeSet<String>,
    /// Function outputs inlined into their one reader.
    inlined: BTreeMap<usize, BoolExpr>,
    /// Functions whose output was read while their inputs were computed (feedback).
    fed_back: BTreeSet<usize>,
    /// The path of inlined block indices to this body.
    path: Vec<usize>,
    /// The edge detectors of the one-shot elements emitted so far, in order.
    edges: Vec<EdgeKey>,
    /// The block called as a statement of its own (its reader comes later, after other
    /// statements: never inlined).
    direct: Option<usize>,
    /// The integers computed so far (declared ones, block outputs, counts).
    ints: BTreeMap<String, IntVar>,
    /// Integers not computed, with the reason (from the previous pass).
    opaque: BTreeMap<String, String>,
    /// Integers found not computed in this pass.
    new_opaque: BTreeMap<String, String>,
    /// The next scan-local value's index.
    next_temp: usize,
    /// The free integers standing for what C leaves undefined ([`Program::undefined`]).
    undefined: BTreeSet<String>,
}

fn one() -> BoolExpr {
    BoolExpr::Const(true)
}

fn zero() -> BoolExpr {
    BoolExpr::Const(false)
}

fn contact(name: &str, negated: bool) -> BoolExpr {
    let v = BoolExpr::var(name);
    if negated { BoolExpr::negate(v) } else { v }
}

fn is_one(c: &BoolExpr) -> bool {
    matches!(c, BoolExpr::Const(true))
}

fn and(items: Vec<BoolExpr>) -> BoolExpr {
    let mut items = items.into_iter().filter(|c| !is_one(c));
    let first = items.next().unwrap_or_else(one);
    items.fold(first, BoolExpr::and)
}

fn or(mut items: Vec<BoolExpr>) -> BoolExpr {
    if items.len() == 1 {
        return items.pop().unwrap_or_else(one);
    }
    if items.iter().any(is_one) {
        return one();
    }
    BoolExpr::Or(items)
}

/// An unconstrained value standing for `what`, named after `keyword` and its block.
fn fresh(keyword: &str, what: &str, span: Span) -> BoolExpr {
    let keyword = keyword.to_ascii_uppercase();
    BoolExpr::Fresh(Box::new(Fresh {
        base: keyword.clone(),
        keyword,
        why: format!("{what} is not expressible in the algebra"),
        span,
        peripheral: false,
    }))
}

/// An unconstrained value for the reason `why`, named after `keyword`.
fn fresh_because(keyword: &str, why: String, span: Span) -> BoolExpr {
    free(keyword, why, span, false)
}

/// A free value for the reason `why`, named after `keyword`: unconstrained, or a
/// peripheral read.
fn free(keyword: &str, why: String, span: Span, peripheral: bool) -> BoolExpr {
    let keyword = keyword.to_ascii_uppercase();
    BoolExpr::Fresh(Box::new(Fresh { base: keyword.clone(), keyword, why, span, peripheral }))
}

/// What output `pin` of the peripheral library block `type_name` is: `the output ACK of
/// py1 (PYTHON_EVAL): its outputs are set when …`.
fn peripheral_output(type_name: &str, instance: Option<&str>, pin: &str) -> String {
    let out = super::peripherals::output_of(type_name, instance, pin);
    let what = super::peripherals::peripheral(type_name).unwrap_or("it answers from outside");
    format!("{out}: {what}")
}

/// A Boolean output of a library block that is a peripheral (`peripherals`): a free
/// input, with what it follows.
fn peripheral(type_name: &str, instance: Option<&str>, pin: &str, span: Span) -> BoolExpr {
    let out = peripheral_output(type_name, instance, pin);
    free(type_name, format!("a peripheral: {out}, which ii-prove does not model"), span, true)
}

/// A Boolean output of a block the algebra does not express (counters, comparisons, …).
fn opaque(type_name: &str, instance: Option<&str>, pin: &str, span: Span) -> BoolExpr {
    let upper = type_name.to_ascii_uppercase();
    let kind = upper.split('_').next().unwrap_or("");
    let name = instance.unwrap_or(type_name);
    let what = match kind {
        "CTU" | "CTD" | "CTUD" => format!("the counter {name} ({upper})"),
        "GT" | "GE" | "EQ" | "NE" | "LT" | "LE" => format!("the integer comparison {upper}"),
        _ => match instance {
            Some(i) => format!("the output {pin} of {i} ({upper})"),
            None => format!("the function {upper}"),
        },
    };
    fresh(type_name, &what, span)
}

/// `¬c`, pushed down to the variables.
fn not(c: BoolExpr) -> BoolExpr {
    match c {
        BoolExpr::Const(b) => BoolExpr::Const(!b),
        BoolExpr::And(a, b) => or(vec![not(*a), not(*b)]),
        BoolExpr::Or(v) => and(v.into_iter().map(not).collect()),
        BoolExpr::Not(x) => *x,
        // The negation of an unconstrained value is as unconstrained.
        f @ BoolExpr::Fresh(_) => f,
        x => BoolExpr::negate(x),
    }
}

/// `R_TRIG(v).Q` or `F_TRIG(v).Q` as matiec defines them (`Q := CLK ∧ ¬M; M := CLK`, with
/// `CLK = ¬v` for F_TRIG, `M` FALSE at power-up): a rising one-shot of `v` or of `¬v`.
/// (An F_TRIG pulses at the first scan when `v` is FALSE; a one-shot of `¬v` does too.)
fn trig(edge: Edge, v: BoolExpr, index: usize) -> BoolExpr {
    let clk = if edge == Edge::Falling { not(v) } else { v };
    let memory = Memory { base: "OSR".into(), element: "OSR".into(), index };
    BoolExpr::Edge {
        kind: crate::program::EdgeKind::Rising,
        input: Box::new(clk),
        memory: Box::new(memory),
    }
}

fn xor(a: BoolExpr, b: BoolExpr) -> BoolExpr {
    or(vec![and(vec![a.clone(), not(b.clone())]), and(vec![not(a), b])])
}

impl<'p> Lower<'p> {
    fn new(p: &'p PlcProgram) -> Lower<'p> {
        Lower {
            p,
            blocks: Vec::new(),
            called: BTreeSet::new(),
            in_progress: BTreeSet::new(),
            no_pull: false,
            trigs: BTreeSet::new(),
            visiting: BTreeSet::new(),
            errors: Vec::new(),
            warnings: Vec::new(),
            emitted: BTreeSet::new(),
            inlined: BTreeMap::new(),
            fed_back: BTreeSet::new(),
            direct: None,
            path: Vec::new(),
            edges: Vec::new(),
            ints: BTreeMap::new(),
            opaque: BTreeMap::new(),
            new_opaque: BTreeMap::new(),
            next_temp: 0,
            undefined: BTreeSet::new(),
        }
    }

    /// Hands the state one scan shares (blocks so far, names, one-shots, integers) from
    /// `self` to `other`.
    fn hand_over(&mut self, other: &mut Lower<'_>) {
        other.blocks = std::mem::take(&mut self.blocks);
        other.emitted = std::mem::take(&mut self.emitted);
        other.edges = std::mem::take(&mut self.edges);
        other.ints = std::mem::take(&mut self.ints);
        other.opaque = std::mem::take(&mut self.opaque);
        other.new_opaque = std::mem::take(&mut self.new_opaque);
        other.next_temp = self.next_temp;
    }

    /// `trig(edge, v)`, recording which detector of the program it stands for.
    fn trig_of(&mut self, owner: usize, pin: &str, edge: Edge, v: BoolExpr) -> BoolExpr {
        self.edges.push((self.path.clone(), owner, pin.to_string()));
        trig(edge, v, self.edges.len() - 1)
    }

    /// Whether the value of the object at `k` is read exactly once per scan: one wire
    /// from it, into a block, an output variable, a coil that feeds nothing, or a contact
    /// whose own value is read exactly once (not into a connector, whose continuations
    /// may be read by several statements, nor a coil chain, which re-reads it).
    fn single_use(&self, k: usize) -> bool {
        self.read_once(k, 0)
    }

    fn read_once(&self, k: usize, depth: usize) -> bool {
        let Some(id) = self.p.obj(k).map(|o| o.id) else { return false };
        if depth > 64 {
            return false;
        }
        let mut readers = Vec::new();
        for (j, o) in self.p.objects().iter().enumerate() {
            let pins: Vec<&PinIn> = match &o.kind {
                ObjKind::Contact { input, .. }
                | ObjKind::Coil { input, .. }
                | ObjKind::OutVar { input, .. }
                | ObjKind::InOutVar { input, .. }
                | ObjKind::Connector { input, .. } => vec![input],
                ObjKind::Block { inputs, .. } => inputs.iter().collect(),
                _ => Vec::new(),
            };
            let n = pins.iter().flat_map(|p| &p.conns).filter(|c| c.from == id).count();
            readers.extend(std::iter::repeat_n(j, n));
        }
        let [j] = readers.as_slice() else { return false };
        match self.p.obj(*j).map(|o| &o.kind) {
            Some(ObjKind::Block { .. } | ObjKind::OutVar { .. } | ObjKind::InOutVar { .. }) => true,
            Some(ObjKind::Coil { .. }) => self.nothing_reads(*j),
            Some(ObjKind::Contact { .. }) => self.read_once(*j, depth + 1),
            _ => false,
        }
    }

    /// Whether no object reads the value of the object at `k` (right rails do not read).
    fn nothing_reads(&self, k: usize) -> bool {
        let Some(id) = self.p.obj(k).map(|o| o.id) else { return true };
        !self.p.objects().iter().any(|o| match &o.kind {
            ObjKind::Contact { input, .. }
            | ObjKind::Coil { input, .. }
            | ObjKind::OutVar { input, .. }
            | ObjKind::InOutVar { input, .. }
            | ObjKind::Connector { input, .. } => input.conns.iter().any(|c| c.from == id),
            ObjKind::Block { inputs, .. } => {
                inputs.iter().any(|p| p.conns.iter().any(|c| c.from == id))
            }
            _ => false,
        })
    }

    /// Whether every bit `c` reads is settled: a declared variable or input (nothing
    /// writes one between a block call and the statement that triggered it), or a
    /// hidden variable already written in this scan.
    fn settled(&self, c: &BoolExpr) -> bool {
        let mut settled = true;
        crate::program::walk(c, &mut |e| {
            if let BoolExpr::Var(name) = e {
                settled &= self.emitted.contains(name)
                    || self.p.vars.values().any(|v| v.name == *name)
                    || self.p.inputs.contains(name);
            }
        });
        settled
    }

    /// A function's output: inlined into its one reader when nothing it reads can change
    /// before that reader runs, else a hidden variable written here.
    fn function_out(&mut self, k: usize, out: BoolExpr, span: Span) {
        let inline = self.direct != Some(k) && !self.fed_back.contains(&k);
        if inline && self.single_use(k) && self.settled(&out) {
            self.inlined.insert(k, out);
        } else {
            let name = self.p.hidden_name(k, "OUT").unwrap_or_default().to_string();
            self.coil(out, &name, WriteKind::Assign, span);
        }
    }

    /// The statements of the body, in evaluation order.
    fn run(&mut self) {
        for &k in &self.p.order {
            self.statement(k);
        }
    }

    fn span_of(&self, k: usize) -> Span {
        self.p.obj(k).map_or(Span::new(self.p.file, 0..0), |o| o.span)
    }

    /// A block of its own writing `name`.
    fn coil(&mut self, mut power: BoolExpr, name: &str, kind: WriteKind, span: Span) {
        self.emitted.insert(name.to_string());
        let number = self.blocks.len() + 1;
        // What the compiler names (unconstrained values, one-shot memories) is named
        // after the block that computes it.
        crate::program::walk_mut(&mut power, &mut |e| match e {
            BoolExpr::Fresh(f) => f.base = format!("{}_r{number}", f.base),
            BoolExpr::Edge { memory, .. } => memory.base = format!("{}_r{number}", memory.base),
            _ => {}
        });
        let write = Stmt::Write { target: name.to_string(), kind, value: power, span };
        self.blocks.push(Block { number, label: None, span, stmts: vec![write] });
    }

    /// The value an operand reads, as a circuit.
    fn operand(&mut self, k: usize, op: &Operand, span: Span) -> BoolExpr {
        match op {
            Operand::Bool(n) => contact(n, false),
            Operand::Const(true) => one(),
            Operand::Const(false) => zero(),
            // `0` and `1` where a BOOL is expected: FALSE and TRUE, as matiec types them.
            Operand::Other(t) if super::bool_of_int_literal(t).is_some() => {
                BoolExpr::Const(super::bool_of_int_literal(t) == Some(true))
            }
            Operand::Member(inst, pin) => match self.member_writer(inst) {
                Some(j) => {
                    let name = self.p.hidden_name(j, pin).unwrap_or_default().to_string();
                    contact(&name, false)
                }
                None => fresh(
                    "MEMBER",
                    &format!("the member {inst}.{pin} of an instance not modelled"),
                    span,
                ),
            },
            Operand::Duration(_) | Operand::Other(_) => {
                let what = match op {
                    Operand::Other(t) => t.clone(),
                    _ => "a duration".into(),
                };
                let _ = k;
                fresh("VALUE", &format!("the value of `{what}`"), span)
            }
        }
    }

    /// The modelled block writing instance `inst`'s hidden outputs, if any.
    fn member_writer(&self, inst: &str) -> Option<usize> {
        self.p.objects().iter().enumerate().map(|(j, _)| j).find(|j| {
            matches!(&self.p.obj(*j).map(|o| &o.kind), Some(ObjKind::Block { instance: Some(i), type_name, .. })
                if self.p.vars.get(&i.to_ascii_uppercase()).is_some_and(|v| v.name.eq_ignore_ascii_case(inst))
                    && Std::of(type_name).is_some_and(Std::is_fb))
                && self.en_const(*j, 0)
        })
    }

    /// The power at a consumer pin: the OR of its wires, or its expression (unconnected: FALSE).
    fn pin_power(&mut self, pin: &PinIn, owner: usize) -> BoolExpr {
        if let Some((text, span)) = &pin.expr {
            let op = self.resolve(text, *span);
            return self.operand(owner, &op, *span);
        }
        if pin.conns.is_empty() {
            return zero();
        }
        let values: Vec<BoolExpr> = pin
            .conns
            .iter()
            .map(|c| match self.p.source(c) {
                Some(src) => self.source(src, c.span),
                None => zero(),
            })
            .collect();
        or(values)
    }

    fn resolve(&self, text: &str, span: Span) -> Operand {
        let _ = span;
        let upper = text.trim().to_ascii_uppercase();
        match upper.as_str() {
            "TRUE" => return Operand::Const(true),
            "FALSE" => return Operand::Const(false),
            _ => {}
        }
        if let Some(us) = super::parse_duration(text) {
            return Operand::Duration(us);
        }
        match self.p.vars.get(&upper) {
            Some(v) if v.ty == super::Ty::Bool => Operand::Bool(v.name.clone()),
            _ => Operand::Other(text.trim().to_string()),
        }
    }

    /// A block input pin's value with its modifiers (negation, edge detector).
    fn pin_value(&mut self, k: usize, pin: &PinIn) -> BoolExpr {
        let v = self.pin_power(pin, k);
        let v = if pin.negated { not(v) } else { v };
        self.edge(k, &pin.name.to_ascii_uppercase(), pin.edge, v, pin.span)
    }

    /// `v` through the hidden edge detector of `(k, pin)`, computed once per scan at its first use.
    fn edge(&mut self, k: usize, pin: &str, edge: Edge, v: BoolExpr, span: Span) -> BoolExpr {
        if edge == Edge::None {
            return v;
        }
        let Some(name) = self.p.hidden_name(k, pin).map(str::to_string) else {
            return fresh("EDGE", &format!("the edge detector of pin {pin}"), span);
        };
        if self.trigs.insert((k, pin.to_string())) {
            let power = self.trig_of(k, pin, edge, v);
            self.coil(power, &name, WriteKind::Assign, span);
        }
        contact(&name, false)
    }

    /// What a wire's producer puts on it.
    fn source(&mut self, src: Source, span: Span) -> BoolExpr {
        match src {
            Source::Rail => one(),
            Source::Object(k) => {
                if !self.visiting.insert(k) {
                    self.errors.push(PlcError::Unsupported {
                        span: self.span_of(k),
                        what: "a wire loop through this object".into(),
                        reason: "a loop must pass through a block, whose output is then read from the previous scan".into(),
                    });
                    return zero();
                }
                let out = self.object_value(k);
                self.visiting.remove(&k);
                out
            }
            Source::BlockOut(k, pin) => {
                let (name, negated) = self.p.output_pin(k, pin);
                let v = self.block_output(k, &name, span);
                if negated { not(v) } else { v }
            }
            Source::BlockPin(k, pin) => self.block_output(k, pin, span),
        }
    }

    fn object_value(&mut self, k: usize) -> BoolExpr {
        let p = self.p;
        let Some(o) = p.obj(k) else { return zero() };
        let op = p.operands.get(&k).cloned();
        match &o.kind {
            ObjKind::Contact { negated, edge, input, var } => {
                let pred = self.pin_power(input, k);
                let v = match &op {
                    Some(op) => self.operand(k, op, var.1),
                    None => fresh("CONTACT", &format!("the value of `{}`", var.0), var.1),
                };
                let v = if *negated { not(v) } else { v };
                // Beremiz's PLCGenerator.py makes one R_TRIG/F_TRIG per path through an
                // edge contact, each called where its statement is computed: two paths
                // see the variable at two places of the scan, with two memories.
                if *edge != Edge::None && !self.single_use(k) {
                    self.errors.push(PlcError::Unsupported {
                        span: o.span,
                        what: "an edge contact on more than one path".into(),
                        reason: "the generated code makes one edge detector per path, each \
                                 called at its own statement and with its own memory, which \
                                 ii-prove does not model yet; give each path its own contact"
                            .into(),
                    });
                }
                let v = self.edge(k, "", *edge, v, o.span);
                and(vec![pred, v])
            }
            ObjKind::Coil { input, .. } if input.conns.len() > 1 => {
                // Beremiz's generator reads a coil's wires as a series when the coil's
                // output feeds another element (`GeneratePaths` appends them as a list).
                self.errors.push(PlcError::Unsupported {
                    span: o.span,
                    what: "a coil fed by several wires whose output feeds another element".into(),
                    reason: "Beremiz and OpenPLC generate code that ANDs the wires into this coil \
                             where the power flow ORs them; put the OR before a contact, or \
                             feed the next element from the wires directly"
                        .into(),
                });
                zero()
            }
            ObjKind::Coil { input, .. } | ObjKind::Connector { input, .. } => {
                self.pin_power(input, k)
            }
            ObjKind::InVar { negated, edge, expr } => {
                let v = match &op {
                    Some(op) => self.operand(k, op, expr.1),
                    None => fresh("VALUE", &format!("the value of `{}`", expr.0), expr.1),
                };
                let v = if *negated { not(v) } else { v };
                self.edge(k, "", *edge, v, o.span)
            }
            ObjKind::InOutVar { expr, .. } | ObjKind::OutVar { expr, .. } => match &op {
                Some(op) => self.operand(k, op, expr.1),
                None => fresh("VALUE", &format!("the value of `{}`", expr.0), expr.1),
            },
            _ => zero(),
        }
    }

    /// The value of output `pin` of block `k` (calling the block at its first use this scan).
    fn block_output(&mut self, k: usize, pin: &str, span: Span) -> BoolExpr {
        let before = self.no_pull && !self.called.contains(&k);
        if self.in_progress.contains(&k) || before {
            // Read before its call: its output is the variable as it stands.
            self.fed_back.insert(k);
        }
        if !before {
            self.call(k);
        }
        if let Some(c) = self.inlined.get(&k).filter(|_| !pin.eq_ignore_ascii_case("ENO")) {
            return c.clone();
        }
        let Some(ObjKind::Block { type_name, instance, .. }) = self.p.obj(k).map(|o| &o.kind)
        else {
            return zero();
        };
        let under_en = self.p.text_calls.get(&k).and_then(|c| c.enable.as_deref());
        let runs = self.en_const(k, 0) || under_en.is_some() || self.fb_eno(k).is_some();
        if pin.eq_ignore_ascii_case("ENO") {
            if let Some(eno) = self.p.hidden_name(k, "ENO").or(under_en) {
                return contact(eno, false);
            }
            return if runs {
                one()
            } else {
                fresh(type_name, &format!("the ENO of {type_name} run under a wired EN"), span)
            };
        }
        if let Some(var) = self.p.sub_var(k, pin, true).filter(|_| runs) {
            return contact(var, false);
        }
        if let Some(b) = self.p.int_block(k) {
            let boolean = match &b {
                super::IntBlock::Counter(_) => {
                    ["Q", "QU", "QD"].iter().any(|q| pin.eq_ignore_ascii_case(q))
                }
                b => b.bool_out() && pin.eq_ignore_ascii_case("OUT"),
            };
            // A function with a BOOL OUT (a comparison, `*_TO_BOOL`) under a wired EN
            // writes FALSE when it does not run (`lower/ints.rs`).
            let written = runs || b.bool_out();
            return match self.p.hidden_name(k, &pin.to_ascii_uppercase()) {
                Some(n) if written && boolean => contact(n, false),
                _ => opaque(type_name, instance.as_deref(), pin, span),
            };
        }
        if self.p.bool_mux(k) && pin.eq_ignore_ascii_case("OUT") {
            return contact(self.p.hidden_name(k, "OUT").unwrap_or_default(), false);
        }
        match Std::of(type_name) {
            Some(s) if (runs || !s.is_fb()) && s.output().eq_ignore_ascii_case(pin) => {
                match self.p.hidden_name(k, s.output()) {
                    Some(n) => contact(n, false),
                    None => fresh(type_name, &format!("the output {pin} of {type_name}"), span),
                }
            }
            _ if self.p.peripherals.contains(&k) => {
                peripheral(type_name, instance.as_deref(), pin, span)
            }
            _ => opaque(type_name, instance.as_deref(), pin, span),
        }
    }

    /// Emits the rungs of block `k`'s call, once (a block reached again while its inputs
    /// are computed, a feedback loop, reads its outputs from the previous scan).
    fn call(&mut self, k: usize) {
        if self.called.contains(&k) || !self.in_progress.insert(k) {
            return;
        }
        let p = self.p;
        let Some(o) = p.obj(k) else { return };
        let ObjKind::Block { type_name, inputs, .. } = &o.kind else { return };
        let span = o.span;
        let outer = std::mem::replace(&mut self.no_pull, o.order > 0);
        let runs = self.en_const(k, 0);
        // A function under a wired EN returns FALSE when EN is FALSE (matiec's
        // `TEST_EN(BOOL)`): its output is EN and-ed with its value.
        let std = Std::of(type_name).filter(|s| runs || !s.is_fb() || self.fb_eno(k).is_some());
        // Inputs are computed first, `EN` then the others in document order, as the scan
        // simulator does; the block's own rungs come after every call they trigger.
        let en = p.en_pin(k).map(|pin| self.pin_value(k, pin));
        if let Some(b) = p.int_block(k) {
            let en = if runs { one() } else { en.unwrap_or_else(one) };
            self.int_call(k, &b, en, span);
            self.no_pull = outer;
            self.in_progress.remove(&k);
            self.called.insert(k);
            return;
        }
        let mut vals: BTreeMap<String, BoolExpr> = BTreeMap::new();
        let mut preset = Err(None);
        for pin in inputs {
            let n = pin.name.to_ascii_uppercase();
            match n.as_str() {
                "EN" => {}
                "PT" => preset = self.preset(k),
                _ => {
                    let v = self.pin_value(k, pin);
                    vals.insert(n, v);
                }
            }
        }
        if p.bool_mux(k) {
            let out = self.bool_mux(k, &vals, span);
            self.function_out(k, out, span);
        }
        let value =
            |_: &mut Self, name: &str| -> BoolExpr { vals.get(name).cloned().unwrap_or_else(zero) };
        let gate = en.clone().filter(|_| !runs);
        let gated = |out: BoolExpr| match &gate {
            Some(en) => and(vec![en.clone(), out]),
            None => out,
        };
        let mut start = self.fb_enable(k, en.clone(), span);
        match std {
            Some(s @ (Std::And | Std::Or | Std::Xor)) => {
                let pins = p.data_inputs(k);
                let vals: Vec<BoolExpr> =
                    pins.iter().map(|pin| value(self, &pin.name.to_ascii_uppercase())).collect();
                let out = match s {
                    Std::And => and(vals),
                    Std::Or => or(vals),
                    _ if vals.len() > 4 => fresh("XOR", "an XOR of more than 4 inputs", span),
                    _ => {
                        let mut it = vals.into_iter();
                        let first = it.next().unwrap_or_else(zero);
                        it.fold(first, xor)
                    }
                };
                self.function_out(k, gated(out), span);
            }
            Some(s @ (Std::Not | Std::Move)) => {
                let v = value(self, "IN");
                let v = if s == Std::Not { not(v) } else { v };
                self.function_out(k, gated(v), span);
            }
            Some(Std::Sel) => {
                let g = value(self, "G");
                let a = value(self, "IN0");
                let b = value(self, "IN1");
                let out = or(vec![and(vec![not(g.clone()), a]), and(vec![g, b])]);
                self.function_out(k, gated(out), span);
            }
            Some(s) => start = self.std_fb(k, s, &vals, preset, span),
            None if p.text_calls.contains_key(&k) => {
                self.text_call(k, inputs, &vals, en.clone().filter(|_| !runs), span)
            }
            // An inlined user function block: its inputs are assigned, then its body runs.
            None if (runs || self.fb_eno(k).is_some()) && p.subs.contains_key(&k) => {
                for pin in inputs {
                    let n = pin.name.to_ascii_uppercase();
                    if let (Some(var), Some(v)) = (p.sub_var(k, &n, false), vals.get(&n)) {
                        self.coil(v.clone(), var, WriteKind::Assign, span);
                    } else if let Some(var) = p.sub_int_input(k, &n) {
                        self.int_assign(var, pin, span);
                        if let Some(range) = p.sub_int_range(k, &n) {
                            self.subrange_check(var, range, span);
                        }
                    }
                }
                start = self.blocks.len();
                if let Some(child) = p.subs.get(&k) {
                    let mut sub = Lower::new(child);
                    self.hand_over(&mut sub);
                    sub.path = [self.path.as_slice(), &[k]].concat();
                    sub.run();
                    sub.hand_over(self);
                    self.errors.append(&mut sub.errors);
                    self.warnings.append(&mut sub.warnings);
                }
            }
            // Not interpreted (or run under a wired EN): only its inputs were computed.
            None => {}
        }
        self.under_eno(k, start, runs);
        // A function's `_TMP_…_ENO`: matiec's `TEST_EN` sets it to EN.
        if let Some(eno) = p.hidden_name(k, "ENO").filter(|_| self.fb_eno(k).is_none()) {
            self.coil(en.unwrap_or_else(one), eno, WriteKind::Assign, span);
        }
        self.no_pull = outer;
        self.in_progress.remove(&k);
        self.called.insert(k);
    }

    fn statement(&mut self, k: usize) {
        let p = self.p;
        let Some(o) = p.obj(k) else { return };
        let span = o.span;
        if unconnected(&o.kind) {
            return;
        }
        match &o.kind {
            ObjKind::OutVar { input, .. } | ObjKind::InOutVar { input, .. } if matches!(p.operands.get(&k), Some(super::Operand::Other(n)) if p.int_var_type(n).is_some()) => {
                if let Some(super::Operand::Other(name)) = p.operands.get(&k) {
                    self.int_assign(&p.vars[&name.to_ascii_uppercase()].name.clone(), input, span);
                }
            }
            ObjKind::Coil { input, negated, storage, edge, .. }
            | ObjKind::OutVar { input, negated, storage, edge, .. } => {
                let power = self.pin_power(input, k);
                // A non-Boolean target has no Boolean effect (its inputs were computed).
                if let Some(Operand::Bool(name)) = p.operands.get(&k) {
                    let name = name.clone();
                    let guard = match &o.kind {
                        ObjKind::OutVar { .. } => self.eno_guard(input),
                        _ => None,
                    };
                    let write = (*negated, *storage, *edge);
                    self.assign(k, power, &name, write, guard, span);
                }
            }
            ObjKind::InOutVar { input, .. } => {
                let power = self.pin_power(input, k);
                if let Some(Operand::Bool(name)) = p.operands.get(&k) {
                    let name = name.clone();
                    let guard = self.eno_guard(input);
                    self.assign(k, power, &name, (false, Storage::None, Edge::None), guard, span);
                }
            }
            ObjKind::Block { .. } => {
                self.direct = Some(k);
                self.call(k);
                self.direct = None;
            }
            ObjKind::Connector { input, .. } => {
                let _ = self.pin_power(input, k);
            }
            _ => {}
        }
    }
}

/// Lowers a checked program into the scan model, in evaluation order. Never panics.
pub fn lower(p: &PlcProgram) -> Result<Lowered, Vec<PlcError>> {
    // Integers found not computed make what reads them unconstrained: lowered again
    // until no new one is found.
    let mut opaque = BTreeMap::new();
    loop {
        let mut l = Lower::new(p);
        l.opaque = opaque.clone();
        l.declare_ints(p);
        l.declare_text_ints(p);
        lower_pass(&mut l);
        if l.new_opaque.is_empty() || !l.errors.is_empty() {
            return finish(p, l);
        }
        opaque.append(&mut l.new_opaque);
    }
}

/// One pass of the lowering: start values, latches, the statements.
fn lower_pass(l: &mut Lower<'_>) {
    let p = l.p;
    let file_span = p.pou.span;
    // Start values: on the first scan (STARTED still 0) each such variable is set to its
    // start value before any statement reads it; STARTED is 1 from then on.
    if let Some(started) = &p.started {
        for (x, start) in &p.starts {
            let first = contact(started, true);
            match start {
                None => l.coil(first, x, WriteKind::Set, file_span),
                Some(s) => {
                    let on = and(vec![first.clone(), contact(s, false)]);
                    l.coil(on, x, WriteKind::Set, file_span);
                    let off = and(vec![first, contact(s, true)]);
                    l.coil(off, x, WriteKind::Reset, file_span);
                }
            }
        }
        l.coil(one(), started, WriteKind::Assign, file_span);
    }
    l.latch_inputs(p, file_span);
    l.text_clocks(p);
    l.run();
}

/// The program and warnings of the last pass.
fn finish(p: &PlcProgram, mut l: Lower<'_>) -> Result<Lowered, Vec<PlcError>> {
    if !l.errors.is_empty() {
        l.errors.dedup();
        return Err(l.errors);
    }
    let mut blocks = l.blocks;
    let width = blocks.len().to_string().len().max(2);
    for (k, b) in blocks.iter_mut().enumerate() {
        b.label = Some(format!("L{:0width$}", k + 1));
    }
    let signals = crate::program::bits(&blocks);
    let mut names = signals.clone();
    names.extend(p.vars.values().map(|v| v.name.clone()));
    let declared: BTreeSet<&String> = p.vars.values().map(|v| &v.name).collect();
    let hidden =
        signals.iter().chain(l.ints.keys()).filter(|n| !declared.contains(n)).cloned().collect();
    let program = Program {
        cycle_us: p.cycle_us,
        blocks,
        inputs: Inputs::Declared(p.inputs.clone()),
        signals,
        names,
        skipped: Vec::new(),
        integer_writers: BTreeMap::new(),
        integers: std::mem::take(&mut l.ints),
        exact_names: true,
        block_noun: "rung",
        language: "a PLCopen",
        started: p.started.clone(),
        hidden,
        undefined: std::mem::take(&mut l.undefined),
    };
    let mut warnings = p.warnings.clone();
    warnings.append(&mut l.warnings);
    for (x, why) in &l.opaque {
        // Its declared type (`the REAL Temp`), else a block's output.
        let what = match p.declared_type(x) {
            Some(t) => format!("the {t} {x}"),
            None => format!("the block output {x}"),
        };
        warnings.push(PlcError::Note {
            span: p.span_of_name(x),
            message: format!("{what} is not computed ({why}): what reads it is unconstrained"),
        });
    }
    Ok(Lowered { program, warnings, edges: l.edges })
}
