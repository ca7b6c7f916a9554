//! Selection: one POU of a project checked, with its names, wires, inputs, hidden variables and evaluation order resolved into a `PlcProgram`.

use std::collections::{BTreeMap, BTreeSet};

use super::*;
use crate::diag::{FileId, Span, did_you_mean};
use crate::program::library;

/// The standard blocks the prover interprets (`shared/formats/plcopen-xml.md` §5.4).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Std {
    /// `AND`, `OR`, `XOR` over `IN1..INn`; `NOT`, `MOVE` of `IN`; `SEL(G, IN0, IN1)`.
    And,
    /// Or.
    Or,
    /// Xor.
    Xor,
    /// Not.
    Not,
    /// Move.
    Move,
    /// Sel.
    Sel,
    /// On-delay timer.
    Ton,
    /// Off-delay timer.
    Tof,
    /// Pulse timer.
    Tp,
    /// Set-dominant latch.
    Sr,
    /// Reset-dominant latch.
    Rs,
    /// Rising-edge detector.
    RTrig,
    /// Falling-edge detector.
    FTrig,
}

impl Std {
    /// The block type of a `typeName`, if it is one the prover interprets.
    pub fn of(type_name: &str) -> Option<Std> {
        Some(match type_name.to_ascii_uppercase().as_str() {
            "AND" => Std::And,
            "OR" => Std::Or,
            "XOR" => Std::Xor,
            "NOT" => Std::Not,
            "MOVE" => Std::Move,
            "SEL" => Std::Sel,
            "TON" => Std::Ton,
            "TOF" => Std::Tof,
            "TP" => Std::Tp,
            "SR" => Std::Sr,
            "RS" => Std::Rs,
            "R_TRIG" => Std::RTrig,
            "F_TRIG" => Std::FTrig,
            _ => return None,
        })
    }
    /// Whether it is a function block (has an instance and state).
    pub fn is_fb(self) -> bool {
        matches!(self, Std::Ton | Std::Tof | Std::Tp | Std::Sr | Std::Rs | Std::RTrig | Std::FTrig)
    }
    /// Its Boolean output pin.
    pub fn output(self) -> &'static str {
        match self {
            Std::And | Std::Or | Std::Xor | Std::Not | Std::Move | Std::Sel => "OUT",
            Std::Sr | Std::Rs => "Q1",
            _ => "Q",
        }
    }
}

/// Standard blocks whose outputs the prover does not interpret (counters, comparisons,
/// arithmetic, conversions…): Boolean outputs are unconstrained, others are ignored.
pub fn is_known_library_block(type_name: &str) -> bool {
    const KNOWN: &[&str] = &[
        "CTU",
        "CTD",
        "CTUD",
        "GT",
        "GE",
        "EQ",
        "NE",
        "LE",
        "LT",
        "ADD",
        "SUB",
        "MUL",
        "DIV",
        "MOD",
        "EXPT",
        "ABS",
        "SQRT",
        "MAX",
        "MIN",
        "LIMIT",
        "MUX",
        "SHL",
        "SHR",
        "ROL",
        "ROR",
        "RTC",
        "SEMA",
        "LN",
        "LOG",
        "EXP",
        "SIN",
        "COS",
        "TAN",
        "ASIN",
        "ACOS",
        "ATAN",
        "TRUNC",
        "LEN",
        "LEFT",
        "RIGHT",
        "MID",
        "CONCAT",
        "INSERT",
        "DELETE",
        "REPLACE",
        "FIND",
        "CTU_DINT",
        "CTU_UDINT",
        "CTU_LINT",
        "CTU_ULINT",
        "CTD_DINT",
        "CTD_UDINT",
        "CTD_LINT",
        "CTD_ULINT",
        "CTUD_DINT",
        "CTUD_UDINT",
        "CTUD_LINT",
        "CTUD_ULINT",
    ];
    let upper = type_name.to_ascii_uppercase();
    KNOWN.contains(&upper.as_str()) || upper.contains("_TO_") || upper.starts_with("TRUNC")
}

/// What a wire reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Source {
    /// The left rail: TRUE.
    Rail,
    /// Object index `usize` (a contact, coil, in/inOut variable).
    Object(usize),
    /// Output pin `pin` (index into the block's outputs) of the block at object index.
    BlockOut(usize, usize),
    /// An unconnected block output chosen by the wire: `(block, pin name)` (e.g. `ENO` not drawn).
    BlockPin(usize, &'static str),
}

/// A resolved operand of a contact, coil or variable object.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Operand {
    /// A declared BOOL variable, by its declared name.
    Bool(String),
    /// A Boolean output of a modelled FB instance: `(instance, pin)`, read as its hidden variable.
    Member(String, String),
    /// The literal TRUE or FALSE.
    Const(bool),
    /// A duration literal (µs).
    Duration(u64),
    /// A variable or literal that is not Boolean (integers, times, unmodelled members).
    Other(String),
}

/// How evaluation order was decided (§8).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OrderRule {
    /// `executionOrderId` on every statement.
    ExecutionOrder,
    /// Beremiz's geometric rule (rows top to bottom, then left to right).
    Layout,
    /// Document order (no positions, CODESYS).
    Document,
}

/// A checked program POU ready to lower or simulate.
#[derive(Clone, Debug)]
pub struct PlcProgram {
    /// The file.
    pub file: FileId,
    /// The POU.
    pub pou: Pou,
    /// The scan period in µs.
    pub cycle_us: u64,
    /// Declared variables visible in the POU, by upper-case name.
    pub vars: BTreeMap<String, Var>,
    /// Object index by `localId`.
    pub index: BTreeMap<u64, usize>,
    /// The statements (coils, out/inOut variables, blocks, connectors) in evaluation order.
    pub order: Vec<usize>,
    /// The rule that produced `order`.
    pub rule: OrderRule,
    /// The same statements in the order Beremiz since its Python 3 port (2022) runs
    /// them: ordered ones first, then outputs, blocks and connectors in document order
    /// (its position comparator compares nothing since then). Equal to `order` unless
    /// positions reorder them.
    pub document_order: Vec<usize>,
    /// Hidden variable names: `(object, pin)` → name (pin `""` for a contact's or variable's edge).
    pub hidden: BTreeMap<(usize, String), String>,
    /// Resolved operands of contacts, coils and variable objects, by object index.
    pub operands: BTreeMap<usize, Operand>,
    /// The names the outside world writes at the start of every scan: declared inputs
    /// (input, in-out, external and global variables, `%I`/`%M` located variables, BOOLs
    /// declared TRUE that nothing writes), and for each such variable the program also
    /// writes, its latch instead (see `latches`).
    pub inputs: BTreeSet<String>,
    /// Inputs the program also writes (BOOLs and integers): variable → the hidden name
    /// of the value latched from outside at the start of the scan (`In0_IN`); reads
    /// before the program's first write see the latch, not the previous scan. Those of
    /// inlined function blocks are here too, under their prefixed names.
    pub latches: BTreeMap<String, String>,
    /// Variables of Beremiz's SVGHMI types (`HMI_INT`, …), which the HMI writes at the
    /// start of any scan: variable → the declared type's name. Their `Var::ty` is the
    /// base type (see [`hmi_base`]); they are inputs (or latched, when written).
    pub hmi: BTreeMap<String, String>,
    /// Written BOOLs that do not start FALSE: variable → `None` when it starts TRUE (its
    /// declared initial value), or the hidden input whose value it starts with (a
    /// retained variable after a warm restart: any value, `Lamp_START`).
    pub starts: BTreeMap<String, Option<String>>,
    /// With `starts`: the hidden relay that is 0 before the first scan and 1 from its
    /// end on (`STARTED`), so that the first scan can be told from the others.
    pub started: Option<String>,
    /// User function blocks inlined per instance: block index → the instance's body,
    /// its names prefixed with the instance's (`Pump0_Running`).
    pub subs: BTreeMap<usize, PlcProgram>,
    /// Warnings.
    pub warnings: Vec<PlcError>,
}

/// What the user asks for: which POU, which cycle.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Selection {
    /// `--pou NAME`.
    pub pou: Option<String>,
    /// `--cycle`, in µs.
    pub cycle_us: Option<u64>,
    /// `--cold-start`: retained variables start at their declared initial values, as
    /// after a cold restart (by default they start with any value, as after a warm one).
    pub cold_start: bool,
    /// `--order`: which editor's statement order, when positions and document order
    /// differ (by default such a file is refused if the two orders compile differently).
    pub order: Option<StatementOrder>,
}

/// The statement order of LD/FBD bodies whose positions and document order differ.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum StatementOrder {
    /// By position, rows top to bottom, each left to right (Beremiz before its 2022
    /// Python 3 port, the OpenPLC editor built on it).
    Layout,
    /// Document order (Beremiz since 2022).
    Document,
}

/// The cycle used when neither the task nor the command line gives one (Beremiz's default task interval is 20 ms... the OpenPLC runtime's default tick).
pub const DEFAULT_CYCLE_US: u64 = 20_000;

impl PlcProgram {
    /// The objects of the body.
    pub fn objects(&self) -> &[Obj] {
        self.pou.body.as_ref().map_or(&[], |b| &b.objects)
    }

    /// The object at index `k`.
    pub fn obj(&self, k: usize) -> Option<&Obj> {
        self.objects().get(k)
    }

    /// The hidden variable of `(object, pin)`.
    pub fn hidden_name(&self, k: usize, pin: &str) -> Option<&str> {
        self.hidden.get(&(k, pin.to_string())).map(String::as_str)
    }

    /// The producer of a wire.
    pub fn source(&self, c: &Conn) -> Option<Source> {
        let k = *self.index.get(&c.from)?;
        let o = self.obj(k)?;
        match &o.kind {
            ObjKind::LeftRail => Some(Source::Rail),
            ObjKind::Block { outputs, .. } => {
                let pin = match &c.formal {
                    Some(f) => outputs.iter().position(|p| p.name.eq_ignore_ascii_case(f)),
                    None => outputs.iter().position(|p| !p.name.eq_ignore_ascii_case("ENO")),
                };
                match (pin, &c.formal) {
                    (Some(p), _) => Some(Source::BlockOut(k, p)),
                    (None, Some(f)) if f.eq_ignore_ascii_case("ENO") => {
                        Some(Source::BlockPin(k, "ENO"))
                    }
                    (None, None) => {
                        outputs.iter().position(|_| true).map(|p| Source::BlockOut(k, p))
                    }
                    _ => None,
                }
            }
            ObjKind::Continuation { name } => {
                // The connector of the same name produces it: read through its input.
                let j = self.objects().iter().position(
                    |o| matches!(&o.kind, ObjKind::Connector { name: n, .. } if n.eq_ignore_ascii_case(name)),
                )?;
                Some(Source::Object(j))
            }
            ObjKind::RightRail | ObjKind::Ignored | ObjKind::ControlFlow { .. } => None,
            _ => Some(Source::Object(k)),
        }
    }

    /// The name (upper case) and negation of output pin `pin` of block `k`.
    pub fn output_pin(&self, k: usize, pin: usize) -> (String, bool) {
        match self.obj(k).map(|o| &o.kind) {
            Some(ObjKind::Block { outputs, .. }) => outputs
                .get(pin)
                .map_or((String::new(), false), |o| (o.name.to_ascii_uppercase(), o.negated)),
            _ => (String::new(), false),
        }
    }

    /// The wired `EN` pin of a block, if any.
    pub fn en_pin(&self, k: usize) -> Option<&PinIn> {
        match &self.obj(k)?.kind {
            ObjKind::Block { inputs, .. } => inputs.iter().find(|p| {
                p.name.eq_ignore_ascii_case("EN") && (!p.conns.is_empty() || p.expr.is_some())
            }),
            _ => None,
        }
    }

    /// The input pin `name` of block `k`.
    pub fn pin<'a>(&'a self, k: usize, name: &str) -> Option<&'a PinIn> {
        match &self.obj(k)?.kind {
            ObjKind::Block { inputs, .. } => {
                inputs.iter().find(|p| p.name.eq_ignore_ascii_case(name))
            }
            _ => None,
        }
    }

    /// The Boolean data inputs of an `AND`/`OR`/`XOR` block: `IN1`, `IN2`, … (every non-EN input).
    pub fn data_inputs(&self, k: usize) -> Vec<&PinIn> {
        match self.obj(k).map(|o| &o.kind) {
            Some(ObjKind::Block { inputs, .. }) => {
                inputs.iter().filter(|p| !p.name.eq_ignore_ascii_case("EN")).collect()
            }
            _ => Vec::new(),
        }
    }

    /// The interpreted standard block at `k`, if it is one.
    pub fn std_block(&self, k: usize) -> Option<Std> {
        match &self.obj(k)?.kind {
            ObjKind::Block { type_name, .. } => Std::of(type_name),
            _ => None,
        }
    }

    /// Whether a declared name is an input the outside world writes.
    pub fn is_input(&self, name: &str) -> bool {
        self.inputs.contains(name)
    }
}

/// The refusal of a configuration whose tasks run several graphical programs: at the
/// task whose interval differs from the first's (running each at its own rate is not
/// modelled), else at the configuration (programs composed in one cycle are not).
fn several_programs<'p>(
    several: &[&'p Pou],
    task_of: &dyn Fn(&Pou) -> Option<&'p Task>,
) -> PlcError {
    let names: Vec<&str> = several.iter().map(|p| p.name.as_str()).collect();
    let choose = format!("choose one with --pou (candidates: {})", names.join(", "));
    let interval = |p: &Pou| -> Option<(u64, Span)> {
        let (text, span) = task_of(p)?.interval.as_ref()?;
        let us = parse_duration(text).or_else(|| parse_duration(&format!("T#{}", text.trim())))?;
        Some((us, *span))
    };
    let first = interval(several[0]);
    let other = several[1..].iter().find_map(|p| match (interval(p), first) {
        (Some((us, span)), Some((f, _))) if us != f => Some((p, us, span)),
        _ => None,
    });
    if let (Some((p, us, span)), Some((f, _))) = (other, first) {
        let ms = |us: u64| format!("{} ms", us as f64 / 1000.0);
        return PlcError::Unsupported {
            span,
            what: format!(
                "a configuration whose tasks run at different intervals (`{}` every {}, `{}` every {})",
                several[0].name,
                ms(f),
                p.name,
                ms(us)
            ),
            reason: format!("running each program at its own rate is not modelled yet; {choose}"),
        };
    }
    PlcError::Unsupported {
        span: task_of(several[1])
            .and_then(|t| t.instances.first())
            .map_or(several[1].span, |i| i.2),
        what: format!(
            "a configuration running {} graphical programs ({})",
            names.len(),
            names.join(", ")
        ),
        reason: format!("composing LD/FBD programs in one cycle is not modelled yet; {choose}"),
    }
}

/// A program run by an event task (`single`) runs when the trigger rises, not every
/// cycle: refused at the task, saying so.
pub(super) fn event_task(pou: &Pou, task: Option<&Task>) -> Result<(), Vec<PlcError>> {
    match task.and_then(|t| t.single.map(|s| (t, s))) {
        Some((t, span)) => Err(vec![PlcError::Unsupported {
            span,
            what: format!("the event task `{}` running `{}`", t.name, pou.name),
            reason: "a program an event triggers runs on some cycles only, which is not modelled yet; choose a cyclic program with --pou".into(),
        }]),
        None => Ok(()),
    }
}

/// Picks the program to check: `--pou`, else the POU the configuration's task runs, else the only program.
pub(super) fn pick<'p>(
    project: &'p Project,
    sel: &Selection,
) -> Result<(&'p Pou, Option<&'p Task>), Vec<PlcError>> {
    let programs: Vec<&Pou> = project.pous.iter().filter(|p| p.kind == PouKind::Program).collect();
    let candidates = |kind: &str, name: &str, pous: &[&Pou]| PlcError::Unknown {
        span: project.span,
        kind: kind.into(),
        name: name.into(),
        candidates: match did_you_mean(name, pous.iter().map(|p| p.name.as_str())) {
            Some(near) => vec![near.to_string()],
            None => pous.iter().map(|p| p.name.clone()).collect(),
        },
        ambiguous: false,
    };
    let task_of = |pou: &Pou| {
        project
            .tasks
            .iter()
            .find(|t| t.instances.iter().any(|(_, ty, _)| ty.eq_ignore_ascii_case(&pou.name)))
    };
    if let Some(want) = &sel.pou {
        let found: Vec<&Pou> =
            project.pous.iter().filter(|p| p.name.eq_ignore_ascii_case(want)).collect();
        return match found.as_slice() {
            [p] => Ok((p, task_of(p))),
            [] => Err(vec![candidates("POU (--pou)", want, &programs)]),
            many => Err(vec![PlcError::Unknown {
                span: project.span,
                kind: "POU (--pou)".into(),
                name: want.clone(),
                candidates: many.iter().map(|p| p.name.clone()).collect(),
                ambiguous: true,
            }]),
        };
    }
    let run: Vec<&Pou> = programs.iter().copied().filter(|p| task_of(p).is_some()).collect();
    match (run.as_slice(), programs.as_slice()) {
        ([p], _) => Ok((p, task_of(p))),
        ([], [p]) => Ok((p, None)),
        ([], []) => {
            let graphical: Vec<&Pou> = project
                .pous
                .iter()
                .filter(|p| p.body.as_ref().is_some_and(|b| matches!(b.lang, Lang::Ld | Lang::Fbd)))
                .collect();
            Err(vec![if graphical.is_empty() {
                PlcError::Unsupported {
                    span: project.span,
                    what: "a project without a program POU".into(),
                    reason: "there is nothing to scan, and no POU has an LD or FBD body".into(),
                }
            } else {
                PlcError::Unsupported {
                    span: project.span,
                    what: "a project without a program POU".into(),
                    reason: format!(
                        "choose the function block to check with --pou (candidates: {})",
                        graphical.iter().map(|p| p.name.as_str()).collect::<Vec<_>>().join(", ")
                    ),
                }
            }])
        }
        (several, _) if !several.is_empty() => Err(vec![several_programs(several, &task_of)]),
        (_, all) => Err(vec![PlcError::Unknown {
            span: project.span,
            kind: "program to check: no task runs one and there are several; choose one with --pou, e.g. --pou".into(),
            name: all[0].name.clone(),
            candidates: all.iter().map(|p| p.name.clone()).collect(),
            ambiguous: true,
        }]),
    }
}

/// Checks the chosen POU and resolves it into a [`PlcProgram`].
pub fn select(project: &Project, sel: &Selection) -> Result<PlcProgram, Vec<PlcError>> {
    let (pou, task) = pick(project, sel)?;
    event_task(pou, task)?;
    if !pou.errors.is_empty() {
        return Err(pou.errors.clone());
    }
    let mut warnings = Vec::new();
    let mut errors = Vec::new();
    if pou.body.is_none() {
        return Err(vec![PlcError::Unsupported {
            span: pou.span,
            what: format!("POU `{}` without a body", pou.name),
            reason: "there is nothing to scan".into(),
        }]);
    }
    // The cycle: --cycle, else the task interval, else the default.
    let cycle_us = match (sel.cycle_us, task.and_then(|t| t.interval.as_ref())) {
        (Some(c), _) => c,
        // `T#20ms`, 1.0's `00:00:00.020000`, or a bare `20ms`.
        (None, Some((text, span))) => {
            match parse_duration(text).or_else(|| parse_duration(&format!("T#{}", text.trim()))) {
                Some(c) if c > 0 => c,
                _ => {
                    errors.push(PlcError::Malformed {
                        span: *span,
                        what: format!("task interval `{text}`"),
                        expected: "a positive duration such as `T#20ms` (or give --cycle)".into(),
                    });
                    DEFAULT_CYCLE_US
                }
            }
        }
        (None, None) => {
            warnings.push(PlcError::Note {
                span: pou.span,
                message: format!(
                    "no task with an interval runs `{}`: the scan cycle is taken to be {} ms \
                     (give --cycle to choose it)",
                    pou.name,
                    DEFAULT_CYCLE_US / 1000
                ),
            });
            DEFAULT_CYCLE_US
        }
    };
    if !errors.is_empty() {
        return Err(errors);
    }
    let mut program = check_pou(project, pou, cycle_us, 0)?;
    if let Some(choice) = sel.order {
        program.choose_order(choice);
    }
    warnings.append(&mut program.warnings);
    program.start_retained(sel.cold_start, &mut warnings);
    program.warnings = warnings;
    Ok(program)
}

/// How deep user function blocks are inlined into each other.
const MAX_INLINE_DEPTH: usize = 8;

/// Checks one POU's body: names, wires, blocks (inlining user function blocks), order.
/// `depth` > 0 for the body of an inlined function block, whose interface variables
/// are then written by the caller, not by the outside world.
fn check_pou(
    project: &Project,
    pou: &Pou,
    cycle_us: u64,
    depth: usize,
) -> Result<PlcProgram, Vec<PlcError>> {
    let mut warnings = Vec::new();
    let mut errors = Vec::new();
    if !pou.errors.is_empty() {
        return Err(pou.errors.clone());
    }
    let Some(body) = &pou.body else {
        return Err(vec![PlcError::Unsupported {
            span: pou.span,
            what: format!("POU `{}` without a body", pou.name),
            reason: "there is nothing to scan".into(),
        }]);
    };
    if !matches!(body.lang, Lang::Ld | Lang::Fbd) {
        return Err(vec![PlcError::Unsupported {
            span: body.span,
            what: format!("the {} body of `{}`", body.lang.as_str(), pou.name),
            reason: "only LD and FBD bodies are read".into(),
        }]);
    }
    // Names: POU variables shadow globals; case-insensitive; two spellings of one name are ambiguous.
    let mut vars: BTreeMap<String, Var> = BTreeMap::new();
    let mut spellings: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for v in &pou.vars {
        let key = v.name.to_ascii_uppercase();
        spellings.entry(key.clone()).or_default().insert(v.name.clone());
        vars.insert(key, v.clone());
    }
    for v in &project.globals {
        vars.entry(v.name.to_ascii_uppercase()).or_insert_with(|| v.clone());
    }
    let mut hmi = BTreeMap::new();
    for v in vars.values_mut() {
        if let Ty::Derived(t) = &v.ty
            && let Some(base) = hmi_base(t)
        {
            hmi.insert(v.name.clone(), t.to_ascii_uppercase());
            v.ty = base;
        }
    }
    let mut inputs = BTreeSet::new();
    for v in vars.values() {
        let addr = v.address.as_deref().unwrap_or("").to_ascii_uppercase();
        let interface = matches!(v.class, VarClass::Input | VarClass::InOut) && depth == 0;
        let external = interface
            || matches!(v.class, VarClass::External | VarClass::Global | VarClass::Access)
            || addr.starts_with("%I")
            || addr.starts_with("%M")
            || hmi.contains_key(&v.name);
        if external {
            inputs.insert(v.name.clone());
        }
    }
    let objects = &body.objects;
    let mut index = BTreeMap::new();
    for (k, o) in objects.iter().enumerate() {
        if matches!(o.kind, ObjKind::Ignored) {
            continue;
        }
        if let Some(first) = index.insert(o.id, k) {
            errors.push(PlcError::Malformed {
                span: o.span,
                what: format!(
                    "two objects with `localId=\"{}\"` (the first at object {})",
                    o.id,
                    first + 1
                ),
                expected: "unique ids".into(),
            });
        }
        if let ObjKind::ControlFlow { tag } = &o.kind {
            errors.push(PlcError::Unsupported {
                span: o.span,
                what: format!("`{tag}`"),
                reason: "control flow inside a body skips statements; ii-prove models a plain scan"
                    .into(),
            });
        }
    }
    let user_pous: BTreeSet<String> =
        project.pous.iter().map(|p| p.name.to_ascii_uppercase()).collect();
    let mut program = PlcProgram {
        file: project.file,
        pou: pou.clone(),
        cycle_us,
        vars,
        index,
        order: Vec::new(),
        rule: OrderRule::Document,
        document_order: Vec::new(),
        hidden: BTreeMap::new(),
        operands: BTreeMap::new(),
        inputs,
        latches: BTreeMap::new(),
        hmi,
        starts: BTreeMap::new(),
        started: None,
        subs: BTreeMap::new(),
        warnings: Vec::new(),
    };
    // Check every wire, block type and operand.
    let mut taken: BTreeSet<String> = program.vars.keys().cloned().collect();
    let hide = |taken: &mut BTreeSet<String>, base: String| -> String {
        let mut name = base.clone();
        let mut k = 2;
        while taken.contains(&name.to_ascii_uppercase()) {
            name = format!("{base}_{k}");
            k += 1;
        }
        taken.insert(name.to_ascii_uppercase());
        name
    };
    // One block per function block instance: a second call of the same instance would
    // share its state in ways the rung model does not follow.
    let mut called: BTreeMap<String, Span> = BTreeMap::new();
    for o in objects {
        if let ObjKind::Block { instance: Some(inst), .. } = &o.kind
            && called.insert(inst.to_ascii_uppercase(), o.span).is_some()
        {
            errors.push(PlcError::Unsupported {
                span: o.span,
                what: format!("a second call of the instance `{inst}`"),
                reason: "another block already calls it; give each block its own instance".into(),
            });
        }
    }
    for (k, o) in objects.iter().enumerate() {
        let mut pins: Vec<&PinIn> = Vec::new();
        match &o.kind {
            ObjKind::Contact { var, edge, input, negated } => {
                pins.push(input);
                if *negated && *edge != Edge::None {
                    errors.push(negated_edge(o.span, "contact"));
                }
                if body.lang == Lang::Fbd {
                    errors.push(fbd_only(o));
                }
                match program.operand(&var.0, var.1, &spellings) {
                    Ok(op @ (Operand::Bool(_) | Operand::Member(..) | Operand::Const(_))) => {
                        program.operands.insert(k, op);
                    }
                    Ok(Operand::Other(n)) if is_member(&n) => {
                        program.operands.insert(k, Operand::Other(n));
                    }
                    Ok(_) => errors.push(not_bool(var)),
                    Err(e) => errors.push(e),
                }
                if *edge != Edge::None {
                    let n = hide(&mut taken, format!("_TRIG{}", o.id));
                    program.hidden.insert((k, String::new()), n);
                }
            }
            ObjKind::Coil { var, negated, storage, edge, input } => {
                pins.push(input);
                if body.lang == Lang::Fbd {
                    errors.push(fbd_only(o));
                }
                if *negated && (*storage != Storage::None || *edge != Edge::None) {
                    errors.push(PlcError::Unsupported {
                        span: o.span,
                        what: "a negated coil with a storage or edge modifier".into(),
                        reason:
                            "the combination has no agreed meaning (Beremiz lets `negated` win)"
                                .into(),
                    });
                }
                match program.operand(&var.0, var.1, &spellings) {
                    Ok(op @ Operand::Bool(_)) => {
                        program.operands.insert(k, op);
                    }
                    Ok(_) => errors.push(PlcError::Unsupported {
                        span: var.1,
                        what: format!("a coil on `{}`", var.0),
                        reason: "a coil must write a declared BOOL variable of the POU".into(),
                    }),
                    Err(e) => errors.push(e),
                }
            }
            ObjKind::InVar { expr, edge, negated } => {
                if *negated || *edge != Edge::None {
                    errors.push(variable_modifier(o, if *negated { "negated" } else { "edge" }));
                }
                match program.operand(&expr.0, expr.1, &spellings) {
                    Ok(op) => {
                        program.operands.insert(k, op);
                    }
                    Err(e) => errors.push(e),
                }
                if *edge != Edge::None {
                    let n = hide(&mut taken, format!("_TRIG{}", o.id));
                    program.hidden.insert((k, String::new()), n);
                }
            }
            ObjKind::OutVar { expr, input, negated, storage, edge } => {
                pins.push(input);
                if *negated || *storage != Storage::None || *edge != Edge::None {
                    let what = match (negated, storage) {
                        (true, _) => "negated",
                        (_, Storage::None) => "edge",
                        _ => "storage",
                    };
                    errors.push(variable_modifier(o, what));
                }
                match program.operand(&expr.0, expr.1, &spellings) {
                    Ok(Operand::Const(_) | Operand::Duration(_) | Operand::Member(..)) => errors
                        .push(PlcError::Unsupported {
                            span: expr.1,
                            what: format!("an assignment to `{}`", expr.0),
                            reason: "an output variable must name a declared variable".into(),
                        }),
                    Ok(op) => {
                        program.operands.insert(k, op);
                    }
                    Err(e) => errors.push(e),
                }
            }
            ObjKind::InOutVar { expr, input } => {
                pins.push(input);
                match program.operand(&expr.0, expr.1, &spellings) {
                    Ok(op @ (Operand::Bool(_) | Operand::Other(_))) => {
                        program.operands.insert(k, op);
                    }
                    Ok(_) => errors.push(not_bool(expr)),
                    Err(e) => errors.push(e),
                }
            }
            ObjKind::Connector { input, .. } => pins.push(input),
            ObjKind::Block { type_name, instance, inputs, outputs } => {
                pins.extend(inputs);
                errors.extend(unconnected_pins(o, type_name, inputs));
                if let Some(p) = outputs.iter().find(|p| p.expr.is_some()) {
                    errors.push(PlcError::Unsupported {
                        span: p.span,
                        what: "an expression on a block's output pin".into(),
                        reason: "wire the output to an `outVariable` instead".into(),
                    });
                }
                match Std::of(type_name) {
                    Some(s) if s.is_fb() => {
                        let Some(inst) = instance else {
                            errors.push(PlcError::Malformed {
                                span: o.span,
                                what: format!("a `{type_name}` block without `instanceName`"),
                                expected: "the name of its instance variable".into(),
                            });
                            continue;
                        };
                        let declared = program.vars.get(&inst.to_ascii_uppercase());
                        let inst_name = declared.map_or(inst.clone(), |v| v.name.clone());
                        match declared.map(|v| &v.ty) {
                            Some(Ty::Derived(t)) if t.eq_ignore_ascii_case(type_name) => {}
                            _ => {
                                errors.push(PlcError::Unknown {
                                    span: o.span,
                                    kind: format!("{type_name} instance"),
                                    name: inst.clone(),
                                    candidates: program
                                        .vars
                                        .values()
                                        .filter(|v| matches!(&v.ty, Ty::Derived(t) if t.eq_ignore_ascii_case(type_name)))
                                        .map(|v| v.name.clone())
                                        .collect(),
                                    ambiguous: false,
                                });
                                continue;
                            }
                        }
                        let mut pins_of = vec![s.output().to_string()];
                        if matches!(s, Std::Sr) {
                            pins_of.extend(["S1".into(), "R".into()]);
                        }
                        if matches!(s, Std::Rs) {
                            pins_of.extend(["S".into(), "R1".into()]);
                        }
                        if matches!(s, Std::Tp) {
                            pins_of.push("DONE".into());
                        }
                        for pin in pins_of {
                            if program
                                .hidden
                                .values()
                                .any(|h| h.eq_ignore_ascii_case(&format!("{inst_name}_{pin}")))
                            {
                                // A second block on the same instance shares its hidden variables.
                                let existing = program
                                    .hidden
                                    .iter()
                                    .find(|(_, h)| {
                                        h.eq_ignore_ascii_case(&format!("{inst_name}_{pin}"))
                                    })
                                    .map(|(_, h)| h.clone())
                                    .unwrap_or_default();
                                program.hidden.insert((k, pin), existing);
                                continue;
                            }
                            let n = hide(&mut taken, format!("{inst_name}_{pin}"));
                            program.hidden.insert((k, pin), n);
                        }
                    }
                    Some(s) => {
                        let n = hide(
                            &mut taken,
                            format!(
                                "_TMP_{}{}_{}",
                                type_name.to_ascii_uppercase(),
                                o.id,
                                s.output()
                            ),
                        );
                        program.hidden.insert((k, s.output().to_string()), n);
                    }
                    None if let Some(b) = IntBlock::of(type_name) => {
                        let inst = instance.as_deref().and_then(|i| {
                            let v = program.vars.get(&i.to_ascii_uppercase())?;
                            matches!(&v.ty, Ty::Derived(t) if t.eq_ignore_ascii_case(type_name))
                                .then(|| v.name.clone())
                        });
                        match (&b, inst) {
                            (IntBlock::Counter(ty), Some(inst)) => {
                                let kind = library::Counter::of(ty);
                                let outs = kind.map_or(&[][..], library::Counter::outputs);
                                for pin in outs.iter().chain(&["CV"]) {
                                    let n = hide(&mut taken, format!("{inst}_{pin}"));
                                    program.hidden.insert((k, pin.to_string()), n);
                                }
                            }
                            (IntBlock::Counter(_), None) => {}
                            _ => {
                                let upper = type_name.to_ascii_uppercase();
                                let n = hide(&mut taken, format!("_TMP_{upper}{}_OUT", o.id));
                                program.hidden.insert((k, "OUT".into()), n);
                            }
                        }
                    }
                    None if is_known_library_block(type_name) => {}
                    None if let Some(child) = inline(
                        project,
                        type_name,
                        instance.as_deref(),
                        &program,
                        cycle_us,
                        depth,
                        &mut warnings,
                        o.span,
                    )
                    .transpose()
                    .unwrap_or_else(|mut e| {
                        errors.append(&mut e);
                        None
                    }) =>
                    {
                        for n in child.names() {
                            if !taken.insert(n.to_ascii_uppercase()) {
                                errors.push(PlcError::Unsupported {
                                    span: o.span,
                                    what: format!(
                                        "the instance `{}` of `{type_name}`",
                                        instance.as_deref().unwrap_or("")
                                    ),
                                    reason: format!(
                                        "its variable `{n}` clashes with a name of the program"
                                    ),
                                });
                            }
                        }
                        program.inputs.extend(child.inputs.iter().cloned());
                        program.latches.extend(child.latches.clone());
                        program.subs.insert(k, child);
                    }
                    None => {
                        // An opaque block (a user POU, a vendor library block): it can
                        // change the program's variables only through in-out pins (the
                        // globals it might write are inputs already).
                        let user = user_pous.contains(&type_name.to_ascii_uppercase());
                        let what = if user { "user block" } else { "library block" };
                        let wired =
                            |p: &&PinIn| p.in_out && (!p.conns.is_empty() || p.expr.is_some());
                        match inputs.iter().find(wired) {
                            Some(p) => errors.push(PlcError::Unsupported {
                                span: p.span,
                                what: format!(
                                    "the in-out pin `{}` of the {what} `{type_name}`",
                                    p.name
                                ),
                                reason: "the block may write what is wired to it, and its body is \
                                         not modelled"
                                    .into(),
                            }),
                            None => warnings.push(PlcError::Note {
                                span: o.span,
                                message: format!(
                                    "the {what} `{type_name}` is not modelled: its Boolean outputs \
                                     are unconstrained signals"
                                ),
                            }),
                        }
                    }
                }
                // A function drawn with EN/ENO: Beremiz's `_TMP_…_ENO` variable, which the
                // call writes (`ENO => _TMP_ADD7_ENO`, `PLCGenerator.py` `GenerateBlock`).
                let function = Std::of(type_name).map(|s| !s.is_fb()).unwrap_or_else(|| {
                    IntBlock::of(type_name).is_some_and(|b| !matches!(b, IntBlock::Counter(_)))
                });
                if function
                    && (inputs.iter().any(|p| p.name.eq_ignore_ascii_case("EN"))
                        || outputs.iter().any(|p| p.name.eq_ignore_ascii_case("ENO")))
                {
                    let upper = type_name.to_ascii_uppercase();
                    let n = hide(&mut taken, format!("_TMP_{upper}{}_ENO", o.id));
                    program.hidden.insert((k, "ENO".into()), n);
                }
                for p in inputs.iter().filter(|p| p.edge != Edge::None) {
                    let n = hide(&mut taken, format!("_TRIG{}_{}", o.id, p.name));
                    program.hidden.insert((k, p.name.to_ascii_uppercase()), n);
                }
            }
            _ => {}
        }
        for p in pins {
            if body.lang == Lang::Fbd && p.conns.len() > 1 {
                errors.push(PlcError::Unsupported {
                    span: p.span,
                    what: "several wires into one FBD input".into(),
                    reason: "a wired OR exists only in LD; use an OR block".into(),
                });
            }
            for c in &p.conns {
                if program.source(c).is_none() {
                    let what = match program.index.get(&c.from).and_then(|j| program.obj(*j)) {
                        Some(o) => format!(
                            "a wire from `{}` {} (pin `{}`)",
                            o.tag(),
                            c.from,
                            c.formal.as_deref().unwrap_or("")
                        ),
                        None => format!("a wire from `refLocalId=\"{}\"`", c.from),
                    };
                    errors.push(PlcError::Malformed {
                        span: c.span,
                        what,
                        expected: "the localId of an object with an output (and, for a block, one of its output pins)".into(),
                    });
                }
            }
            if let Some((text, span)) = &p.expr
                && let Err(e) = program.operand(text, *span, &spellings)
            {
                errors.push(e);
            }
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    let written: BTreeSet<String> = program
        .operands
        .iter()
        .filter(|(k, _)| {
            matches!(
                program.obj(**k).map(|o| &o.kind),
                Some(ObjKind::Coil { .. } | ObjKind::OutVar { .. } | ObjKind::InOutVar { .. })
            )
        })
        .filter_map(|(_, op)| match op {
            Operand::Bool(n) => Some(n.clone()),
            _ => None,
        })
        .collect();
    // A BOOL declared TRUE, or retained (any value after a warm restart): unwritten,
    // it is a free input (sound); written, it starts with that value before the first
    // scan (`starts`, which the lowering sets on the first scan).
    let vars: Vec<Var> = program.vars.values().cloned().collect();
    for v in vars {
        let starts_true = v.init.as_deref().is_some_and(is_true);
        if v.ty != Ty::Bool || !(starts_true || v.retain) || program.inputs.contains(&v.name) {
            continue;
        }
        if !written.contains(&v.name) {
            program.inputs.insert(v.name.clone());
        } else if v.retain {
            let start = hide(&mut taken, format!("{}_START", v.name));
            program.inputs.insert(start.clone());
            program.starts.insert(v.name.clone(), Some(start));
        } else {
            program.starts.insert(v.name.clone(), None);
        }
        if program.started.is_none() {
            program.started = Some(hide(&mut taken, "STARTED".into()));
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    // Inputs the program also writes (BOOLs by coils and output variables, integers by
    // output variables) are latched from outside at the start of every scan.
    let written_ints = program.operands.iter().filter_map(|(k, op)| match (program.obj(*k), op) {
        (Some(o), Operand::Other(n))
            if matches!(o.kind, ObjKind::OutVar { .. } | ObjKind::InOutVar { .. })
                && !unconnected(&o.kind)
                && program.int_var_type(n).is_some() =>
        {
            program.vars.get(&n.to_ascii_uppercase()).map(|v| v.name.clone())
        }
        _ => None,
    });
    // An HMI input of an inlined block is written by its caller when the pin is wired.
    let passed = program.hmi.keys().filter(|x| {
        depth > 0
            && program.vars.get(&x.to_ascii_uppercase()).is_some_and(|v| v.class == VarClass::Input)
    });
    let written: BTreeSet<String> = written
        .into_iter()
        .chain(written_ints.collect::<Vec<_>>())
        .chain(passed.cloned())
        .collect();
    let written: Vec<String> = written.into_iter().filter(|n| program.inputs.contains(n)).collect();
    for x in written {
        let latch = hide(&mut taken, format!("{x}_IN"));
        program.inputs.remove(&x);
        program.inputs.insert(latch.clone());
        program.latches.insert(x, latch);
    }
    warnings.extend(program.hmi_notes(depth));
    program.order_statements(&mut warnings)?;
    program.warnings = warnings;
    Ok(program)
}

/// The base type of one of Beremiz's SVGHMI types (`svghmi/pous.xml`: `HMI_INT` is a
/// derived type of `INT`, `HMI_BOOL` and `HMI_NODE` of `BOOL`, …), which the project
/// file names without declaring. `HMI_REAL` and `HMI_STRING` stay opaque, as `REAL`
/// and `STRING` variables are.
pub fn hmi_base(type_name: &str) -> Option<Ty> {
    let upper = type_name.to_ascii_uppercase();
    let base = upper.strip_prefix("HMI_")?;
    Some(match base {
        "BOOL" | "NODE" => Ty::Bool,
        "SINT" | "INT" | "DINT" | "LINT" | "USINT" | "UINT" | "UDINT" | "ULINT" => {
            Ty::Other(base.to_string())
        }
        _ => return None,
    })
}

/// Whether an assignment (coil, output or in-out variable) has nothing wired to it:
/// Beremiz generates no statement for it, so it writes nothing.
pub fn unconnected(kind: &ObjKind) -> bool {
    match kind {
        ObjKind::Coil { input, .. }
        | ObjKind::OutVar { input, .. }
        | ObjKind::InOutVar { input, .. } => input.conns.is_empty() && input.expr.is_none(),
        _ => false,
    }
}

/// Whether an initial value is TRUE.
pub fn is_true(init: &str) -> bool {
    bool_literal(init) == Some(true)
}

/// The value of a BOOL initial value as PLCopen files write it (`TRUE`, `1`, `BOOL#0`, …).
pub fn bool_literal(init: &str) -> Option<bool> {
    match init.trim().to_ascii_uppercase().as_str() {
        "TRUE" | "1" | "BOOL#TRUE" | "BOOL#1" => Some(true),
        "FALSE" | "0" | "BOOL#FALSE" | "BOOL#0" => Some(false),
        _ => None,
    }
}

/// The body of a user function block instance, checked and with its names prefixed,
/// when it can be inlined: an LD/FBD function block without in-out variables, whose
/// body writes no input (a global), instantiated by a declared instance of its type.
#[allow(clippy::too_many_arguments)]
fn inline(
    project: &Project,
    type_name: &str,
    instance: Option<&str>,
    program: &PlcProgram,
    cycle_us: u64,
    depth: usize,
    warnings: &mut Vec<PlcError>,
    span: Span,
) -> Option<Result<PlcProgram, Vec<PlcError>>> {
    let fb = project
        .pous
        .iter()
        .find(|p| p.name.eq_ignore_ascii_case(type_name) && p.kind == PouKind::FunctionBlock)?;
    let graphical = fb.body.as_ref().is_some_and(|b| matches!(b.lang, Lang::Ld | Lang::Fbd));
    let inst = program.vars.get(&instance?.to_ascii_uppercase())?;
    let typed = matches!(&inst.ty, Ty::Derived(t) if t.eq_ignore_ascii_case(type_name));
    if !graphical || !typed || fb.vars.iter().any(|v| v.class == VarClass::InOut) {
        return None;
    }
    if depth + 1 > MAX_INLINE_DEPTH {
        return Some(Err(vec![PlcError::Unsupported {
            span,
            what: format!("the user block `{type_name}`"),
            reason: format!(
                "function blocks nest more than {MAX_INLINE_DEPTH} deep (a recursive type?)"
            ),
        }]));
    }
    let mut child = match check_pou(project, fb, cycle_us, depth + 1) {
        Ok(c) => c,
        Err(e) => return Some(Err(e)),
    };
    // Latches of the outside world's writes run at the start of the scan, before the
    // caller: only those of variables the body owns (not globals) are hoisted to it.
    let owned = |x: &String| {
        child.vars.get(&x.to_ascii_uppercase()).is_some_and(|v| {
            !matches!(v.class, VarClass::External | VarClass::Global | VarClass::Access)
        })
    };
    if !child.latches.keys().all(owned) || !child.starts.is_empty() {
        return None;
    }
    // The same note at the same place, once for all instances.
    for w in std::mem::take(&mut child.warnings) {
        if !warnings.contains(&w) {
            warnings.push(w);
        }
    }
    child.prefix_names(&format!("{}_", inst.name));
    Some(Ok(child))
}

impl PlcProgram {
    /// After a cold restart (`cold`) a retained variable starts at its declared value;
    /// otherwise with any value. Either way a note says which, at the variable.
    fn start_retained(&mut self, cold: bool, warnings: &mut Vec<PlcError>) {
        let retained: Vec<(String, String)> = self
            .starts
            .iter()
            .filter_map(|(x, s)| s.as_ref().map(|s| (x.clone(), s.clone())))
            .collect();
        for (x, start) in retained {
            let Some(v) = self.vars.values().find(|v| v.name == x) else { continue };
            let declared = v.init.as_deref().is_some_and(is_true);
            let message = if cold {
                format!(
                    "`{x}` is retained; with --cold-start it starts at its declared value \
                     ({})",
                    if declared { "TRUE" } else { "FALSE" }
                )
            } else {
                format!(
                    "`{x}` is retained: after a warm restart it starts with the value it had, \
                     so it may be TRUE or FALSE at the first scan (`{start}`); --cold-start \
                     starts it at its declared value"
                )
            };
            warnings.push(PlcError::Note { span: v.span, message });
            if cold {
                self.inputs.remove(&start);
                if declared {
                    self.starts.insert(x, None);
                } else {
                    self.starts.remove(&x);
                }
            }
        }
    }

    /// Prefixes every name this body owns (not the globals it refers to), recursively.
    fn prefix_names(&mut self, prefix: &str) {
        let mut map: BTreeMap<String, String> = BTreeMap::new();
        for v in self.vars.values_mut() {
            if !matches!(v.class, VarClass::External | VarClass::Global | VarClass::Access) {
                let new = format!("{prefix}{}", v.name);
                map.insert(v.name.clone(), new.clone());
                v.name = new;
            }
        }
        // A latch is of a variable this body or an inlined one owns (see `inline`).
        for (x, l) in &self.latches {
            map.insert(x.clone(), format!("{prefix}{x}"));
            map.insert(l.clone(), format!("{prefix}{l}"));
        }
        let rename = |n: &String| map.get(n).cloned().unwrap_or_else(|| n.clone());
        self.latches = self.latches.iter().map(|(x, l)| (rename(x), rename(l))).collect();
        self.hmi = self.hmi.iter().map(|(x, t)| (rename(x), t.clone())).collect();
        for op in self.operands.values_mut() {
            match op {
                Operand::Bool(n) => *n = rename(n),
                Operand::Member(i, _) => *i = rename(i),
                _ => {}
            }
        }
        for h in self.hidden.values_mut() {
            *h = format!("{prefix}{h}");
        }
        self.inputs = self.inputs.iter().map(rename).collect();
        for sub in self.subs.values_mut() {
            sub.prefix_names(prefix);
        }
    }

    /// What the program's HMI variables are (those it owns, and at `depth` 0 the
    /// globals): a note at each declaration.
    fn hmi_notes(&self, depth: usize) -> Vec<PlcError> {
        let mut notes = Vec::new();
        for (x, ty) in &self.hmi {
            let Some(v) = self.vars.get(&x.to_ascii_uppercase()) else { continue };
            let global = matches!(v.class, VarClass::Global | VarClass::Access);
            if v.class == VarClass::External || (global && depth > 0) {
                continue;
            }
            let base = match &v.ty {
                Ty::Bool => "BOOL".to_string(),
                Ty::Derived(t) | Ty::Other(t) => t.to_ascii_uppercase(),
            };
            let mut message = format!(
                "`{x}` is an {ty}: Beremiz's SVGHMI server may write it before any scan, so \
                 the outside world writes it: a free {base} input"
            );
            if let Some(latch) = self.latches.get(x) {
                message.push_str(&format!(
                    "; the program writes it too, so each scan starts with the value from \
                     outside (`{latch}`) and then sees the program's writes"
                ));
            }
            notes.push(PlcError::Note { span: v.span, message });
        }
        notes
    }

    /// Every name this body owns (its variables and hidden variables, recursively).
    pub fn names(&self) -> Vec<String> {
        let mut out: Vec<String> = self
            .vars
            .values()
            .filter(|v| {
                !matches!(v.class, VarClass::External | VarClass::Global | VarClass::Access)
            })
            .map(|v| v.name.clone())
            .chain(self.hidden.values().cloned())
            .chain(self.latches.values().cloned())
            .collect();
        for sub in self.subs.values() {
            out.extend(sub.names());
        }
        // An inlined body's latches are its caller's too.
        out.sort();
        out.dedup();
        out
    }

    /// The variable of an inlined block's interface (`IN1` of the instance at `k`), if
    /// it is a BOOL of that class.
    pub fn sub_var(&self, k: usize, pin: &str, output: bool) -> Option<&str> {
        let v = self.subs.get(&k)?.vars.get(&pin.to_ascii_uppercase())?;
        let class_ok =
            if output { v.class == VarClass::Output } else { v.class == VarClass::Input };
        (class_ok && v.ty == Ty::Bool).then_some(v.name.as_str())
    }

    /// The integer input variable of an inlined block's interface (`IN1` of the
    /// instance at `k`), if it is one.
    pub fn sub_int_input(&self, k: usize, pin: &str) -> Option<&str> {
        let sub = self.subs.get(&k)?;
        let v = sub.vars.get(&pin.to_ascii_uppercase())?;
        (v.class == VarClass::Input && sub.int_var_type(&v.name).is_some())
            .then_some(v.name.as_str())
    }
}

fn is_member(n: &str) -> bool {
    n.contains('.')
}

fn fbd_only(o: &Obj) -> PlcError {
    PlcError::Unsupported {
        span: o.span,
        what: format!("a `{}` in an FBD body", o.tag()),
        reason: "contacts and coils belong to LD bodies".into(),
    }
}

fn not_bool(var: &(String, Span)) -> PlcError {
    PlcError::Unsupported {
        span: var.1,
        what: format!("the operand `{}`", var.0),
        reason: "a contact reads a BOOL variable or a Boolean output of a standard block".into(),
    }
}

impl PlcProgram {
    /// Resolves the text of an operand.
    fn operand(
        &self,
        text: &str,
        span: Span,
        spellings: &BTreeMap<String, BTreeSet<String>>,
    ) -> Result<Operand, PlcError> {
        let t = text.trim();
        let upper = t.to_ascii_uppercase();
        match upper.as_str() {
            "TRUE" | "BOOL#TRUE" | "BOOL#1" => return Ok(Operand::Const(true)),
            "FALSE" | "BOOL#FALSE" | "BOOL#0" => return Ok(Operand::Const(false)),
            _ => {}
        }
        if let Some(us) = parse_duration(t) {
            return Ok(Operand::Duration(us));
        }
        if t.starts_with(|c: char| {
            c.is_ascii_digit() || c == '-' || c == '+' || c == '\'' || c == '"'
        }) || upper.contains('#')
        {
            return Ok(Operand::Other(t.to_string()));
        }
        if let Some(addr) = t.strip_prefix('%') {
            let found = self.vars.values().find(|v| {
                v.address
                    .as_deref()
                    .is_some_and(|a| a.trim_start_matches('%').eq_ignore_ascii_case(addr))
            });
            return match found {
                Some(v) if v.ty == Ty::Bool => Ok(Operand::Bool(v.name.clone())),
                Some(v) => Ok(Operand::Other(v.name.clone())),
                None => Err(PlcError::Unsupported {
                    span,
                    what: format!("the direct address `{t}`"),
                    reason: "no declared variable is located there; declare one with this address"
                        .into(),
                }),
            };
        }
        let is_ident = |s: &str| {
            let mut cs = s.chars();
            cs.next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
                && cs.all(|c| c.is_ascii_alphanumeric() || c == '_')
        };
        if let Some((inst, pin)) = t.split_once('.')
            && is_ident(inst)
            && is_ident(pin)
        {
            let Some(v) = self.vars.get(&inst.to_ascii_uppercase()) else {
                return Err(self.unknown(span, inst, spellings));
            };
            return Ok(match &v.ty {
                Ty::Derived(ty) => match Std::of(ty) {
                    Some(s) if s.is_fb() && s.output().eq_ignore_ascii_case(pin) => {
                        Operand::Member(v.name.clone(), s.output().to_string())
                    }
                    _ => Operand::Other(format!("{}.{pin}", v.name)),
                },
                _ => Operand::Other(format!("{}.{pin}", v.name)),
            });
        }
        if !is_ident(t) {
            return Ok(Operand::Other(t.to_string()));
        }
        if let Some(s) = spellings.get(&upper).filter(|s| s.len() > 1) {
            return Err(PlcError::Unknown {
                span,
                kind: "variable".into(),
                name: t.to_string(),
                candidates: s.iter().cloned().collect(),
                ambiguous: true,
            });
        }
        match self.vars.get(&upper) {
            Some(v) if v.ty == Ty::Bool => Ok(Operand::Bool(v.name.clone())),
            Some(v) => Ok(Operand::Other(v.name.clone())),
            None => Err(self.unknown(span, t, spellings)),
        }
    }

    fn unknown(&self, span: Span, name: &str, _s: &BTreeMap<String, BTreeSet<String>>) -> PlcError {
        let names: Vec<&str> = self.vars.values().map(|v| v.name.as_str()).collect();
        PlcError::Unknown {
            span,
            kind: "variable".into(),
            name: name.to_string(),
            candidates: did_you_mean(name, names).map(str::to_string).into_iter().collect(),
            ambiguous: false,
        }
    }

    /// This program with the statements of every body in the order `choice` gives.
    pub fn with_order(&self, choice: StatementOrder) -> PlcProgram {
        let mut p = self.clone();
        p.choose_order(choice);
        p
    }

    fn choose_order(&mut self, choice: StatementOrder) {
        if choice == StatementOrder::Document && self.order != self.document_order {
            self.order = self.document_order.clone();
            self.rule = OrderRule::Document;
        }
        for child in self.subs.values_mut() {
            child.choose_order(choice);
        }
    }

    /// Where the two editors' statement orders first differ, in this body or an inlined
    /// one: the error to report if the difference changes what the program does.
    pub fn order_dispute(&self) -> Option<PlcError> {
        let first = self.order.iter().zip(&self.document_order).find(|(a, b)| a != b);
        if let Some((a, b)) = first {
            let (oa, ob) = (&self.objects()[*a], &self.objects()[*b]);
            return Some(PlcError::Unsupported {
                span: oa.span,
                what: format!(
                    "a statement order that depends on the editor (this `{}` runs before the \
                     `{}` {} by position, after it in document order, and the program computes \
                     differently)",
                    oa.tag(),
                    ob.tag(),
                    ob.id
                ),
                reason: "Beremiz before 2022 and the OpenPLC editor run statements by position, \
                         Beremiz since 2022 in document order; choose with `--order layout` or \
                         `--order document`"
                    .into(),
            });
        }
        self.subs.values().find_map(PlcProgram::order_dispute)
    }

    /// Orders the statements as Beremiz's `PLCGenerator.ComputeProgram` does (§8).
    fn order_statements(&mut self, warnings: &mut Vec<PlcError>) -> Result<(), Vec<PlcError>> {
        let mut errors = Vec::new();
        let objects = self.objects();
        let mut ordered: Vec<(u64, usize)> = Vec::new();
        let mut outputs: Vec<usize> = Vec::new();
        let mut blocks: Vec<usize> = Vec::new();
        let mut connectors: Vec<usize> = Vec::new();
        for (k, o) in objects.iter().enumerate() {
            match &o.kind {
                ObjKind::OutVar { .. } | ObjKind::InOutVar { .. } | ObjKind::Block { .. }
                    if o.order > 0 =>
                {
                    ordered.push((o.order, k))
                }
                ObjKind::OutVar { .. } | ObjKind::InOutVar { .. } | ObjKind::Coil { .. } => {
                    outputs.push(k)
                }
                ObjKind::Block { .. } => blocks.push(k),
                ObjKind::Connector { .. } => connectors.push(k),
                _ => {}
            }
        }
        ordered.sort();
        let positioned = outputs.iter().chain(&blocks).all(|k| objects[*k].pos.is_some());
        let distinct: BTreeSet<(i64, i64)> =
            outputs.iter().chain(&blocks).filter_map(|k| objects[*k].pos).collect();
        let layout = positioned && distinct.len() > 1;
        let rule = if !ordered.is_empty() && outputs.is_empty() && blocks.is_empty() {
            OrderRule::ExecutionOrder
        } else if layout {
            OrderRule::Layout
        } else {
            OrderRule::Document
        };
        if layout {
            let mut rows_of = |list: &mut Vec<usize>| {
                let amb = match geometric(list, objects) {
                    Ok(amb) => amb,
                    Err((a, b)) => {
                        errors.push(PlcError::Unsupported {
                            span: objects[b].span,
                            what: format!(
                                "a statement order by position among 64 or more objects where this `{}` and the `{}` {} lie less than 10 units apart in height",
                                objects[b].tag(),
                                objects[a].tag(),
                                objects[a].id
                            ),
                            reason: "Beremiz's position comparison is no order there, and what its sort makes of it is not reproduced for so many objects; align the two or move them 10 units apart".into(),
                        });
                        None
                    }
                };
                if let Some((a, b)) = amb {
                    warnings.push(PlcError::Note {
                        span: objects[b].span,
                        message: format!(
                            "evaluation order: this `{}` and the `{}` at line-of-sight (object {}) lie \
                             within 10 units of height of each other, so they count as one row and are \
                             ordered left to right (Beremiz's rule); move one to make the order explicit",
                            objects[b].tag(),
                            objects[a].tag(),
                            objects[a].id
                        ),
                    });
                }
            };
            rows_of(&mut outputs);
            rows_of(&mut blocks);
        } else if outputs.len() + blocks.len() > 1 {
            let span = self.pou.body.as_ref().map_or(self.pou.span, |b| b.span);
            warnings.push(PlcError::Note {
                span,
                message: "evaluation order: the objects have no distinct positions, so the \
                          statements run in document order"
                    .into(),
            });
        }
        let mut order: Vec<usize> = ordered.into_iter().map(|(_, k)| k).collect();
        let mut document = order.clone();
        document.extend(outputs.iter().copied().collect::<BTreeSet<usize>>());
        document.extend(blocks.iter().copied().collect::<BTreeSet<usize>>());
        document.extend(&connectors);
        self.document_order = document;
        order.extend(outputs);
        order.extend(blocks);
        order.extend(connectors);
        self.order = order;
        self.rule = rule;
        if errors.is_empty() { Ok(()) } else { Err(errors) }
    }
}

/// The unconnected input pins of a block whose meaning depends on the tool: Beremiz's
/// generator leaves an unconnected pin out of the call (and drops a function none of
/// whose inputs is connected, its output then keeping its value), where the standard
/// gives the pin its default value, FALSE, and applies its modifiers to it.
fn unconnected_pins(o: &Obj, type_name: &str, inputs: &[PinIn]) -> Vec<PlcError> {
    let open = |p: &&PinIn| p.conns.is_empty() && p.expr.is_none();
    let data: Vec<&PinIn> = inputs.iter().filter(|p| !p.name.eq_ignore_ascii_case("EN")).collect();
    let mut errors: Vec<PlcError> = inputs
        .iter()
        .filter(|p| p.negated && p.edge != Edge::None)
        .map(|p| negated_edge(p.span, "pin"))
        .collect();
    for p in inputs.iter().filter(open) {
        if p.negated || p.edge != Edge::None {
            errors.push(PlcError::Unsupported {
                span: p.span,
                what: format!("a modifier on the unconnected pin `{}`", p.name),
                reason: "Beremiz and OpenPLC leave an unconnected pin out of the call, so the \
                         modifier is lost; the standard applies it to FALSE; connect the pin \
                         or remove the modifier"
                    .into(),
            });
        }
    }
    let function = Std::of(type_name).is_some_and(|s| !s.is_fb());
    if function && !data.is_empty() && data.iter().all(open) {
        errors.push(PlcError::Unsupported {
            span: o.span,
            what: format!("a `{type_name}` block with no input connected"),
            reason: "Beremiz and OpenPLC drop the call (its output keeps its value); the \
                     standard computes it from FALSE inputs; connect an input or remove it"
                .into(),
        });
    } else if function {
        // The generated call leaves an unconnected input out: a positional call then
        // shifts the later arguments into its place, a formal call of an extensible
        // function is compiled by matiec with fewer arguments than it counts, and an AND
        // loses an operand the standard makes FALSE. Only trailing OR/XOR inputs,
        // where leaving out is FALSE, agree everywhere.
        let trailing_ok = matches!(Std::of(type_name), Some(Std::Or | Std::Xor));
        let last_connected = data.iter().rposition(|p| !open(p)).unwrap_or(0);
        if let Some((_, p)) =
            data.iter().enumerate().find(|(j, p)| open(p) && (!trailing_ok || *j < last_connected))
        {
            errors.push(PlcError::Unsupported {
                span: p.span,
                what: format!("the unconnected input `{}` of the `{type_name}` block", p.name),
                reason: "Beremiz and OpenPLC leave it out of the call (the arguments after it \
                         shift, or the result is undefined), where the standard gives it \
                         FALSE; connect it or remove the pin"
                    .into(),
            });
        }
    }
    errors
}

/// A contact or pin both negated and edge-triggered.
fn negated_edge(span: Span, what: &str) -> PlcError {
    PlcError::Unsupported {
        span,
        what: format!("a {what} both negated and edge-triggered"),
        reason: "Beremiz and OpenPLC apply only the negation (their generator ignores the \
                 edge then); use an R_TRIG/F_TRIG block and a NOT"
            .into(),
    }
}

/// A modifier on a variable object: its meaning depends on the tool that runs the file.
fn variable_modifier(o: &Obj, what: &str) -> PlcError {
    PlcError::Unsupported {
        span: o.span,
        what: format!("a `{what}` modifier on an `{}`", o.tag()),
        reason: "Beremiz and OpenPLC generate code that ignores it (their generator applies \
                 modifiers only to contacts, coils and block pins) while other tools apply it; \
                 use a NOT or R_TRIG/F_TRIG block, or the modifier on the block's pin"
            .into(),
    }
}

/// Sorts `list` as Beremiz's `SortInstances` does: two objects less than 10 units apart
/// in height by `x`, others by `y`. That comparison is no order (a ~ b and b ~ c by the
/// 10-unit rule while a < c by height), so the result is the sorting algorithm's:
/// CPython's `list.sort`, which for fewer than 64 items takes the first run (reversed if
/// strictly descending) and inserts the rest by binary search. Returns a pair whose order
/// depended on the 10-unit rule (different heights, one row), if any; `Err` with such a
/// pair for a longer list, where the merges of the algorithm are not reproduced here.
fn geometric(
    list: &mut Vec<usize>,
    objects: &[Obj],
) -> Result<Option<(usize, usize)>, (usize, usize)> {
    let pos = |k: usize| objects[k].pos.unwrap_or((0, 0));
    let lt = |a: usize, b: usize| {
        let ((ax, ay), (bx, by)) = (pos(a), pos(b));
        if (ay - by).abs() < 10 { ax < bx } else { ay < by }
    };
    let mut ambiguous = None;
    for (i, &a) in list.iter().enumerate() {
        for &b in &list[i + 1..] {
            let dy = (pos(a).1 - pos(b).1).abs();
            if dy > 0 && dy < 10 && ambiguous.is_none() {
                ambiguous = Some((a, b));
            }
        }
    }
    if list.len() >= 64 {
        return match ambiguous {
            Some(pair) => Err(pair),
            // Without such a pair the comparison is (y, x), an order: any sort agrees.
            None => {
                list.sort_by_key(|k| (pos(*k).1, pos(*k).0));
                Ok(None)
            }
        };
    }
    let n = list.len();
    if n < 2 {
        return Ok(None);
    }
    let mut run = 2;
    if lt(list[1], list[0]) {
        while run < n && lt(list[run], list[run - 1]) {
            run += 1;
        }
        list[..run].reverse();
    } else {
        while run < n && !lt(list[run], list[run - 1]) {
            run += 1;
        }
    }
    for start in run..n {
        let pivot = list[start];
        let (mut l, mut r) = (0, start);
        while l < r {
            let p = l + (r - l) / 2;
            if lt(pivot, list[p]) {
                r = p;
            } else {
                l = p + 1;
            }
        }
        list.remove(start);
        list.insert(l, pivot);
    }
    Ok(ambiguous)
}
