//! Lowering of a checked PLCopen program ([`PlcProgram`]) into the rung model the one rung compiler reads ([`LdProgram`]), statement by statement in evaluation order.
//!
//! Each statement becomes one rung fed by the rail: a coil or output variable is
//! `power → COIL`, a block call is one rung per output it writes. Block outputs,
//! FB instance pins and edge detectors are hidden variables written by coils
//! (`TON0_Q`, `SR0_S1`, `_TMP_AND7_OUT`, `_TRIG12`, see `docs/plcopen.md`), so a
//! value computed once per scan is read by every consumer, and a read before the
//! writer sees the previous scan, exactly as in the scan model. Negation of a
//! compound value is pushed to the contacts (De Morgan). What the algebra cannot
//! express (TP, counters, comparisons, blocks run under a wired `EN`, non-Boolean
//! values in a Boolean place) becomes a fresh element, which the compiler turns
//! into an unconstrained signal with a warning naming the block.

use std::collections::{BTreeMap, BTreeSet};

use super::{
    Edge, ObjKind, Operand, PinIn, PlcError, PlcProgram, Source, Std, Storage, unconnected,
};
use crate::diag::Span;
use crate::ladder::ldmicro::{
    Circuit, CoilKind, CompareOp, CounterEdge, CounterKind, EdgeKind, Element, ElementKind,
    HeaderVersion, LdProgram, Operand as LdOperand, Rung, TimerDelay, TimerKind,
};

/// A lowered program: the rung model and the warnings of reading and lowering.
pub struct Lowered {
    /// The rungs, one per statement, in scan order.
    pub ld: LdProgram,
    /// Warnings (order decisions, defaults), each located in the XML.
    pub warnings: Vec<PlcError>,
    /// For each one-shot element of `ld`, in file order, the edge detector it stands for:
    /// the path of inlined block indices, the owning object and the pin (see
    /// [`PlcSimulator::edge_memory_of`](super::PlcSimulator::edge_memory_of)).
    pub edges: Vec<EdgeKey>,
}

/// Which edge detector of a PLCopen program a one-shot element stands for.
pub type EdgeKey = (Vec<usize>, usize, String);

/// The number of scans a TON/TOF with preset `pt_us` counts on a `cycle_us` tick (matiec's
/// time-based blocks: the output changes at the first scan whose time is `≥ start + PT`,
/// and never at the scan that starts the timer): `max(1, ceil(PT / cycle))`.
pub fn timer_scans(pt_us: u64, cycle_us: u64) -> u64 {
    if cycle_us == 0 {
        return 1;
    }
    pt_us.div_ceil(cycle_us).max(1)
}

struct Lower<'p> {
    p: &'p PlcProgram,
    rungs: Vec<Rung>,
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
    inlined: BTreeMap<usize, Circuit>,
    /// Functions whose output was read while their inputs were computed (feedback).
    fed_back: BTreeSet<usize>,
    /// The path of inlined block indices to this body.
    path: Vec<usize>,
    /// The edge detectors of the one-shot elements emitted so far, in order.
    edges: Vec<EdgeKey>,
    /// The block called as a statement of its own (its reader comes later, after other
    /// statements: never inlined).
    direct: Option<usize>,
}

fn one() -> Circuit {
    Circuit::Series(Vec::new())
}

fn el(kind: ElementKind, span: Span) -> Circuit {
    Circuit::Element(Element { kind, span })
}

fn contact(name: &str, negated: bool, span: Span) -> Circuit {
    el(ElementKind::Contacts { name: name.to_string(), negated }, span)
}

fn is_one(c: &Circuit) -> bool {
    matches!(c, Circuit::Series(v) if v.is_empty())
}

fn and(items: Vec<Circuit>) -> Circuit {
    let mut out = Vec::new();
    for c in items {
        match c {
            Circuit::Series(v) => out.extend(v),
            c => out.push(c),
        }
    }
    if out.len() == 1 { out.pop().unwrap_or_else(one) } else { Circuit::Series(out) }
}

fn or(mut items: Vec<Circuit>) -> Circuit {
    if items.len() == 1 {
        return items.pop().unwrap_or_else(one);
    }
    if items.iter().any(is_one) {
        return one();
    }
    Circuit::Parallel(items)
}

/// A fresh (unconstrained) element named after `keyword`; never one the compiler passes through.
fn fresh(keyword: &str, what: &str, span: Span) -> Circuit {
    let mut k = keyword.to_ascii_uppercase();
    let reserved = ["GOTO", "GOSUB", "SUBPROG", "ENDSUB", "RETURN", "LOCK", "SLEEP", "LABEL"];
    if crate::ladder::ldmicro::PASS_THROUGH.contains(&k.as_str()) || reserved.contains(&k.as_str())
    {
        k.push_str("_BLOCK");
    }
    el(ElementKind::Other { keyword: k, args: vec![what.to_string()] }, span)
}

/// A Boolean output of a block the algebra does not express: counters and comparisons
/// as the compiler's own elements (so its warning says what they are), anything else fresh.
fn opaque(type_name: &str, instance: Option<&str>, pin: &str, span: Span) -> Circuit {
    let upper = type_name.to_ascii_uppercase();
    let name = instance.unwrap_or(type_name).to_string();
    let counter = |kind| ElementKind::Counter {
        kind,
        name: name.clone(),
        limit: LdOperand::Literal(0),
        init: LdOperand::Literal(0),
        edge: CounterEdge::Rising,
    };
    let compare =
        |op| ElementKind::Compare { op, a: LdOperand::Literal(0), b: LdOperand::Literal(0) };
    let kind = match upper.split('_').next().unwrap_or("") {
        "CTU" => counter(CounterKind::Ctu),
        "CTD" | "CTUD" => counter(CounterKind::Ctd),
        "GT" => compare(CompareOp::Grt),
        "GE" => compare(CompareOp::Geq),
        "EQ" => compare(CompareOp::Equ),
        "NE" => compare(CompareOp::Neq),
        "LT" => compare(CompareOp::Les),
        "LE" => compare(CompareOp::Leq),
        _ => return fresh(type_name, &format!("{name}.{pin}"), span),
    };
    el(kind, span)
}

/// `¬c`, pushed down to the contacts.
fn not(c: Circuit) -> Circuit {
    match c {
        Circuit::Series(v) if v.is_empty() => {
            Circuit::Element(Element { kind: ElementKind::Open, span: Span::new(0, 0..0) })
        }
        Circuit::Series(v) => or(v.into_iter().map(not).collect()),
        Circuit::Parallel(v) => and(v.into_iter().map(not).collect()),
        Circuit::Element(e) => match e.kind {
            ElementKind::Contacts { name, negated } => {
                el(ElementKind::Contacts { name, negated: !negated }, e.span)
            }
            ElementKind::Open => one(),
            ElementKind::Other { keyword, args } => {
                el(ElementKind::Other { keyword, args }, e.span)
            }
            kind => el(kind, e.span),
        },
    }
}

/// `R_TRIG(v).Q` or `F_TRIG(v).Q` as matiec defines them (`Q := CLK ∧ ¬M; M := CLK`, with
/// `CLK = ¬v` for F_TRIG, `M` FALSE at power-up): a rising one-shot of `v` or of `¬v`.
/// (An F_TRIG pulses at the first scan when `v` is FALSE; a one-shot of `¬v` does too.)
fn trig(edge: Edge, v: Circuit, span: Span) -> Circuit {
    let clk = if edge == Edge::Falling { not(v) } else { v };
    and(vec![clk, el(ElementKind::Edge { kind: EdgeKind::Osr }, span)])
}

fn xor(a: Circuit, b: Circuit) -> Circuit {
    or(vec![and(vec![a.clone(), not(b.clone())]), and(vec![not(a), b])])
}

impl<'p> Lower<'p> {
    fn new(p: &'p PlcProgram) -> Lower<'p> {
        Lower {
            p,
            rungs: Vec::new(),
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
        }
    }

    /// `trig(edge, v)`, recording which detector of the program it stands for.
    fn trig_of(&mut self, owner: usize, pin: &str, edge: Edge, v: Circuit, span: Span) -> Circuit {
        self.edges.push((self.path.clone(), owner, pin.to_string()));
        trig(edge, v, span)
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
    fn settled(&self, c: &Circuit) -> bool {
        c.elements().iter().all(|e| match &e.kind {
            ElementKind::Contacts { name, .. } => {
                self.emitted.contains(name)
                    || self.p.vars.values().any(|v| v.name == *name)
                    || self.p.inputs.contains(name)
            }
            _ => true,
        })
    }

    /// A function's output: inlined into its one reader when nothing it reads can change
    /// before that reader runs, else a hidden variable written here.
    fn function_out(&mut self, k: usize, out: Circuit, span: Span) {
        let inline = self.direct != Some(k) && !self.fed_back.contains(&k);
        if inline && self.single_use(k) && self.settled(&out) {
            self.inlined.insert(k, out);
        } else {
            let name = self.p.hidden_name(k, "OUT").unwrap_or_default().to_string();
            self.coil(out, &name, CoilKind::Normal, span);
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

    fn rung(&mut self, body: Vec<Circuit>, span: Span) {
        let number = self.rungs.len() + 1;
        self.rungs.push(Rung { number, label: None, span, body: Circuit::Series(body) });
    }

    fn coil(&mut self, power: Circuit, name: &str, kind: CoilKind, span: Span) {
        self.emitted.insert(name.to_string());
        let c = el(ElementKind::Coil { name: name.to_string(), kind }, span);
        let body = match power {
            Circuit::Series(mut v) => {
                v.push(c);
                v
            }
            p => vec![p, c],
        };
        self.rung(body, span);
    }

    /// The value an operand reads, as a circuit.
    fn operand(&mut self, k: usize, op: &Operand, span: Span) -> Circuit {
        match op {
            Operand::Bool(n) => contact(n, false, span),
            Operand::Const(true) => one(),
            Operand::Const(false) => el(ElementKind::Open, span),
            Operand::Member(inst, pin) => match self.member_writer(inst) {
                Some(j) => {
                    let name = self.p.hidden_name(j, pin).unwrap_or_default().to_string();
                    contact(&name, false, span)
                }
                None => fresh("MEMBER", &format!("{inst}.{pin}"), span),
            },
            Operand::Duration(_) | Operand::Other(_) => {
                let what = match op {
                    Operand::Other(t) => t.clone(),
                    _ => "a duration".into(),
                };
                let _ = k;
                fresh("VALUE", &what, span)
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

    /// Whether block `k` runs every scan: its `EN` is unwired or fed by the rail or by the
    /// `ENO` of a block that runs every scan.
    fn en_const(&self, k: usize, depth: usize) -> bool {
        let Some(pin) = self.p.en_pin(k) else { return true };
        if depth > 64 || pin.expr.is_some() || pin.negated || pin.edge != Edge::None {
            return false;
        }
        pin.conns.len() == 1
            && pin.conns.iter().all(|c| match self.p.source(c) {
                Some(Source::Rail) => true,
                Some(Source::BlockPin(j, _)) => self.en_const(j, depth + 1),
                Some(Source::BlockOut(j, pin)) => {
                    matches!(self.p.obj(j).map(|o| &o.kind), Some(ObjKind::Block { outputs, .. })
                        if outputs.get(pin).is_some_and(|o| o.name.eq_ignore_ascii_case("ENO") && !o.negated))
                        && self.en_const(j, depth + 1)
                }
                _ => false,
            })
    }

    /// The power at a consumer pin: the OR of its wires, or its expression (unconnected: FALSE).
    fn pin_power(&mut self, pin: &PinIn, owner: usize) -> Circuit {
        if let Some((text, span)) = &pin.expr {
            let op = self.resolve(text, *span);
            return self.operand(owner, &op, *span);
        }
        if pin.conns.is_empty() {
            return el(ElementKind::Open, pin.span);
        }
        let values: Vec<Circuit> = pin
            .conns
            .iter()
            .map(|c| match self.p.source(c) {
                Some(src) => self.source(src, c.span),
                None => el(ElementKind::Open, c.span),
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
    fn pin_value(&mut self, k: usize, pin: &PinIn) -> Circuit {
        let v = self.pin_power(pin, k);
        let v = if pin.negated { not(v) } else { v };
        self.edge(k, &pin.name.to_ascii_uppercase(), pin.edge, v, pin.span)
    }

    /// `v` through the hidden edge detector of `(k, pin)`, computed once per scan at its first use.
    fn edge(&mut self, k: usize, pin: &str, edge: Edge, v: Circuit, span: Span) -> Circuit {
        if edge == Edge::None {
            return v;
        }
        let Some(name) = self.p.hidden_name(k, pin).map(str::to_string) else {
            return fresh("EDGE", pin, span);
        };
        if self.trigs.insert((k, pin.to_string())) {
            let power = self.trig_of(k, pin, edge, v, span);
            self.coil(power, &name, CoilKind::Normal, span);
        }
        contact(&name, false, span)
    }

    /// What a wire's producer puts on it.
    fn source(&mut self, src: Source, span: Span) -> Circuit {
        match src {
            Source::Rail => one(),
            Source::Object(k) => {
                if !self.visiting.insert(k) {
                    self.errors.push(PlcError::Unsupported {
                        span: self.span_of(k),
                        what: "a wire loop through this object".into(),
                        reason: "a loop must pass through a block, whose output is then read from the previous scan".into(),
                    });
                    return el(ElementKind::Open, span);
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

    fn object_value(&mut self, k: usize) -> Circuit {
        let p = self.p;
        let Some(o) = p.obj(k) else { return el(ElementKind::Open, Span::new(p.file, 0..0)) };
        let op = p.operands.get(&k).cloned();
        match &o.kind {
            ObjKind::Contact { negated, edge, input, var } => {
                let pred = self.pin_power(input, k);
                let v = match &op {
                    Some(op) => self.operand(k, op, var.1),
                    None => fresh("CONTACT", &var.0, var.1),
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
                el(ElementKind::Open, o.span)
            }
            ObjKind::Coil { input, .. } | ObjKind::Connector { input, .. } => {
                self.pin_power(input, k)
            }
            ObjKind::InVar { negated, edge, expr } => {
                let v = match &op {
                    Some(op) => self.operand(k, op, expr.1),
                    None => fresh("VALUE", &expr.0, expr.1),
                };
                let v = if *negated { not(v) } else { v };
                self.edge(k, "", *edge, v, o.span)
            }
            ObjKind::InOutVar { expr, .. } | ObjKind::OutVar { expr, .. } => match &op {
                Some(op) => self.operand(k, op, expr.1),
                None => fresh("VALUE", &expr.0, expr.1),
            },
            _ => el(ElementKind::Open, o.span),
        }
    }

    /// The value of output `pin` of block `k` (calling the block at its first use this scan).
    fn block_output(&mut self, k: usize, pin: &str, span: Span) -> Circuit {
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
            return el(ElementKind::Open, span);
        };
        let runs = self.en_const(k, 0);
        if pin.eq_ignore_ascii_case("ENO") {
            return if runs { one() } else { fresh(type_name, "ENO", span) };
        }
        if let Some(var) = self.p.sub_var(k, pin, true).filter(|_| runs) {
            return contact(var, false, span);
        }
        match Std::of(type_name) {
            Some(s) if runs && s.output().eq_ignore_ascii_case(pin) => {
                match self.p.hidden_name(k, s.output()) {
                    Some(n) => contact(n, false, span),
                    None => fresh(type_name, pin, span),
                }
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
        let ObjKind::Block { type_name, instance, inputs, .. } = &o.kind else { return };
        let span = o.span;
        let outer = std::mem::replace(&mut self.no_pull, o.order > 0);
        let runs = self.en_const(k, 0);
        let std = Std::of(type_name).filter(|_| runs);
        // Inputs are computed first, `EN` then the others in document order, as the scan
        // simulator does; the block's own rungs come after every call they trigger.
        if let Some(pin) = p.en_pin(k) {
            let _ = self.pin_value(k, pin);
        }
        let mut vals: BTreeMap<String, Circuit> = BTreeMap::new();
        let mut preset = None;
        for pin in inputs {
            let n = pin.name.to_ascii_uppercase();
            match n.as_str() {
                "EN" => {}
                "PT" => preset = self.preset(k, span),
                _ => {
                    let v = self.pin_value(k, pin);
                    vals.insert(n, v);
                }
            }
        }
        let value = |_: &mut Self, name: &str| -> Circuit {
            vals.get(name).cloned().unwrap_or_else(|| el(ElementKind::Open, span))
        };
        let hidden = |pin: &str| p.hidden_name(k, pin).unwrap_or_default().to_string();
        match std {
            Some(s @ (Std::And | Std::Or | Std::Xor)) => {
                let pins = p.data_inputs(k);
                let vals: Vec<Circuit> =
                    pins.iter().map(|pin| value(self, &pin.name.to_ascii_uppercase())).collect();
                let out = match s {
                    Std::And => and(vals),
                    Std::Or => or(vals),
                    _ if vals.len() > 4 => fresh("XOR", "more than 4 inputs", span),
                    _ => {
                        let mut it = vals.into_iter();
                        let first = it.next().unwrap_or_else(|| el(ElementKind::Open, span));
                        it.fold(first, xor)
                    }
                };
                self.function_out(k, out, span);
            }
            Some(s @ (Std::Not | Std::Move)) => {
                let v = value(self, "IN");
                let v = if s == Std::Not { not(v) } else { v };
                self.function_out(k, v, span);
            }
            Some(Std::Sel) => {
                let g = value(self, "G");
                let a = value(self, "IN0");
                let b = value(self, "IN1");
                let out = or(vec![and(vec![not(g.clone()), a]), and(vec![g, b])]);
                self.function_out(k, out, span);
            }
            Some(s @ (Std::Ton | Std::Tof)) => {
                let input = value(self, "IN");
                let delay = preset;
                // The instance's variable name (prefixed inside an inlined block).
                let inst = instance.as_deref().map_or_else(String::new, |i| {
                    p.vars.get(&i.to_ascii_uppercase()).map_or(i.to_string(), |v| v.name.clone())
                });
                let kind = if s == Std::Ton { TimerKind::Ton } else { TimerKind::Tof };
                let (delay, adjust) = match delay {
                    // PT = 0 still takes one scan (the starting scan never switches):
                    // the delay of one cycle, counted exactly.
                    Some(0) => {
                        self.warnings.push(PlcError::Note {
                            span,
                            message: format!(
                                "{} {inst} has PT = 0: matiec's timer still switches one scan \
                                 later, so it is compiled with the delay of one cycle",
                                type_name.to_ascii_uppercase()
                            ),
                        });
                        (TimerDelay::Micros(p.cycle_us), 0)
                    }
                    Some(us) => {
                        let scans = timer_scans(us, p.cycle_us);
                        let floor = us.checked_div(p.cycle_us).unwrap_or(0);
                        (TimerDelay::Micros(us), scans as i64 - floor as i64)
                    }
                    None => (TimerDelay::Variable(format!("{inst}.PT")), 0),
                };
                let timer = el(
                    ElementKind::Timer { kind, name: inst, delay, adjust, adjust_given: true },
                    span,
                );
                self.coil(and(vec![input, timer]), &hidden("Q"), CoilKind::Normal, span);
            }
            Some(Std::Tp) => {
                let out = fresh("TP", instance.as_deref().unwrap_or(""), span);
                self.coil(out, &hidden("Q"), CoilKind::Normal, span);
            }
            Some(s @ (Std::Sr | Std::Rs)) => {
                let (set, reset) = if s == Std::Sr { ("S1", "R") } else { ("S", "R1") };
                let sv = value(self, set);
                let rv = value(self, reset);
                let (hs, hr, q) = (hidden(set), hidden(reset), hidden("Q1"));
                self.coil(sv, &hs, CoilKind::Normal, span);
                self.coil(rv, &hr, CoilKind::Normal, span);
                let set_rung = (contact(&hs, false, span), CoilKind::Set);
                let reset_rung = (contact(&hr, false, span), CoilKind::Reset);
                // SR: Q1 := S1 + ¬R·Q1 (reset, then set); RS: Q1 := ¬R1·(S + Q1) (set, then reset).
                let rungs =
                    if s == Std::Sr { [reset_rung, set_rung] } else { [set_rung, reset_rung] };
                for (c, kind) in rungs {
                    self.coil(c, &q, kind, span);
                }
            }
            Some(s @ (Std::RTrig | Std::FTrig)) => {
                let clk = value(self, "CLK");
                let edge = if s == Std::RTrig { Edge::Rising } else { Edge::Falling };
                let q = self.trig_of(k, "M", edge, clk, span);
                self.coil(q, &hidden("Q"), CoilKind::Normal, span);
            }
            // An inlined user function block: its inputs are assigned, then its body runs.
            None if runs && p.subs.contains_key(&k) => {
                for pin in inputs {
                    let n = pin.name.to_ascii_uppercase();
                    if let (Some(var), Some(v)) = (p.sub_var(k, &n, false), vals.get(&n)) {
                        self.coil(v.clone(), var, CoilKind::Normal, span);
                    }
                }
                if let Some(child) = p.subs.get(&k) {
                    let mut sub = Lower::new(child);
                    sub.rungs = std::mem::take(&mut self.rungs);
                    sub.emitted = std::mem::take(&mut self.emitted);
                    sub.edges = std::mem::take(&mut self.edges);
                    sub.path = [self.path.as_slice(), &[k]].concat();
                    sub.run();
                    self.rungs = std::mem::take(&mut sub.rungs);
                    self.emitted = std::mem::take(&mut sub.emitted);
                    self.edges = std::mem::take(&mut sub.edges);
                    self.errors.append(&mut sub.errors);
                    self.warnings.append(&mut sub.warnings);
                }
            }
            // Not interpreted (or run under a wired EN): only its inputs were computed.
            None => {}
        }
        self.no_pull = outer;
        self.in_progress.remove(&k);
        self.called.insert(k);
    }

    /// The preset of a timer block, in µs, when it is a literal.
    fn preset(&mut self, k: usize, _span: Span) -> Option<u64> {
        let pin = self.p.pin(k, "PT")?;
        if let Some((text, _)) = &pin.expr {
            return super::parse_duration(text);
        }
        let [c] = pin.conns.as_slice() else { return None };
        match self.p.source(c)? {
            Source::Object(j) => match self.p.operands.get(&j) {
                Some(Operand::Duration(us)) => Some(*us),
                _ => None,
            },
            Source::BlockOut(j, _) | Source::BlockPin(j, _) => {
                self.call(j);
                None
            }
            Source::Rail => None,
        }
    }

    fn statement(&mut self, k: usize) {
        let p = self.p;
        let Some(o) = p.obj(k) else { return };
        let span = o.span;
        if unconnected(&o.kind) {
            return;
        }
        match &o.kind {
            ObjKind::Coil { input, negated, storage, edge, .. }
            | ObjKind::OutVar { input, negated, storage, edge, .. } => {
                let power = self.pin_power(input, k);
                // A non-Boolean target has no Boolean effect (its inputs were computed).
                if let Some(Operand::Bool(name)) = p.operands.get(&k) {
                    let name = name.clone();
                    self.assign(k, power, &name, *negated, *storage, *edge, span);
                }
            }
            ObjKind::InOutVar { input, .. } => {
                let power = self.pin_power(input, k);
                if let Some(Operand::Bool(name)) = p.operands.get(&k) {
                    let name = name.clone();
                    self.assign(k, power, &name, false, Storage::None, Edge::None, span);
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

    #[allow(clippy::too_many_arguments)]
    fn assign(
        &mut self,
        k: usize,
        power: Circuit,
        name: &str,
        negated: bool,
        storage: Storage,
        edge: Edge,
        span: Span,
    ) {
        let kind = match (negated, storage) {
            (true, _) => CoilKind::Negated,
            (_, Storage::Set) => CoilKind::Set,
            (_, Storage::Reset) => CoilKind::Reset,
            _ => CoilKind::Normal,
        };
        let power =
            if edge == Edge::None { power } else { self.trig_of(k, "COIL", edge, power, span) };
        self.coil(power, name, kind, span);
    }
}

/// Lowers a checked program into rungs, in evaluation order. Never panics.
pub fn lower(p: &PlcProgram) -> Result<Lowered, Vec<PlcError>> {
    let mut l = Lower::new(p);
    let file_span = p.pou.span;
    // Start values: on the first scan (STARTED still 0) each such variable is set to its
    // start value before any statement reads it; STARTED is 1 from then on.
    if let Some(started) = &p.started {
        for (x, start) in &p.starts {
            let first = contact(started, true, file_span);
            match start {
                None => l.coil(first, x, CoilKind::Set, file_span),
                Some(s) => {
                    let on = and(vec![first.clone(), contact(s, false, file_span)]);
                    l.coil(on, x, CoilKind::Set, file_span);
                    let off = and(vec![first, contact(s, true, file_span)]);
                    l.coil(off, x, CoilKind::Reset, file_span);
                }
            }
        }
        l.coil(one(), started, CoilKind::Normal, file_span);
    }
    for (x, latch) in &p.latches {
        l.coil(contact(latch, false, file_span), x, CoilKind::Normal, file_span);
    }
    l.run();
    if !l.errors.is_empty() {
        l.errors.dedup();
        return Err(l.errors);
    }
    let ld = LdProgram {
        version: HeaderVersion::V0_2(String::new()),
        cycle_us: p.cycle_us,
        micro: None,
        io_list: Vec::new(),
        rungs: l.rungs,
        warnings: Vec::new(),
        inputs: Some(p.inputs.clone()),
    };
    let mut warnings = p.warnings.clone();
    warnings.append(&mut l.warnings);
    Ok(Lowered { ld, warnings, edges: l.edges })
}
