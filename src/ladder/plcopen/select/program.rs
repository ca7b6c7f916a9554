//! The checked program as lowering and simulation read it: `PlcProgram` (its objects,
//! names, wires, hidden variables, inputs, latches and start values), the standard blocks
//! the prover interprets (`Std`), what a wire reads (`Source`), resolved operands.

use std::collections::{BTreeMap, BTreeSet};

use super::super::*;
use crate::diag::FileId;

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
    /// The set and reset pins of `SR` (`S1`, `R`) and `RS` (`S`, `R1`), the inputs its
    /// instance keeps.
    pub fn set_reset(self) -> Option<(&'static str, &'static str)> {
        match self {
            Std::Sr => Some(("S1", "R")),
            Std::Rs => Some(("S", "R1")),
            _ => None,
        }
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
    /// base type (see [`hmi_base`](super::hmi_base)); they are inputs (or latched, when written).
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
    /// The calls of user function blocks whose body is text, by block object.
    pub text_calls: BTreeMap<usize, crate::ladder::plcopen::text::TextCall>,
    /// Warnings.
    pub warnings: Vec<PlcError>,
    /// The library blocks that are peripherals (`peripherals`), by block object: their
    /// Boolean outputs are free inputs.
    pub peripherals: BTreeSet<usize>,
}

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

    /// The variable holding the integer output `pin` of the block at `k`: its hidden
    /// variable, or a text block's output variable.
    pub fn int_output_name(&self, k: usize, pin: &str) -> Option<&str> {
        self.hidden_name(k, pin).or_else(|| {
            let call = self.text_calls.get(&k)?;
            call.int_outputs.get(&pin.to_ascii_uppercase()).map(String::as_str)
        })
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

    /// Whether block `k` is a `MUX` of BOOL inputs drawn without `EN`/`ENO` (its data
    /// inputs carry no integer), whose `OUT` is a hidden BOOL.
    pub fn bool_mux(&self, k: usize) -> bool {
        matches!(&self.obj(k).map(|o| &o.kind), Some(ObjKind::Block { type_name, .. })
            if type_name.eq_ignore_ascii_case("MUX"))
            && self.int_block(k).is_none()
            && self.hidden_name(k, "ENO").is_none()
            && self.hidden_name(k, "OUT").is_some()
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
        if let Some(t) = self.text_calls.get(&k) {
            let upper = pin.to_ascii_uppercase();
            return match output {
                true => t.outputs.get(&upper).map(String::as_str),
                false => t.inputs.get(&upper).filter(|(_, int)| !int).map(|(n, _)| n.as_str()),
            };
        }
        let v = self.subs.get(&k)?.vars.get(&pin.to_ascii_uppercase())?;
        let class_ok =
            if output { v.class == VarClass::Output } else { v.class == VarClass::Input };
        (class_ok && v.ty == Ty::Bool).then_some(v.name.as_str())
    }

    /// The integer input variable of an inlined block's interface (`IN1` of the
    /// instance at `k`), if it is one.
    pub fn sub_int_input(&self, k: usize, pin: &str) -> Option<&str> {
        if let Some(t) = self.text_calls.get(&k) {
            let input = t.inputs.get(&pin.to_ascii_uppercase());
            return input.filter(|(_, int)| *int).map(|(n, _)| n.as_str());
        }
        let sub = self.subs.get(&k)?;
        let v = sub.vars.get(&pin.to_ascii_uppercase())?;
        (v.class == VarClass::Input && sub.int_var_type(&v.name).is_some())
            .then_some(v.name.as_str())
    }

    /// The limits of the subrange type of an inlined block's integer input (`IN1` of the
    /// instance at `k`), if it is of one: Beremiz passes it in a formal call
    /// (`inst(IN1 := …)`), where matiec's C holds it within them (`__CHECK_…`).
    pub fn sub_int_range(&self, k: usize, pin: &str) -> Option<(i64, i64)> {
        self.subs.get(&k)?.vars.get(&pin.to_ascii_uppercase())?.range
    }
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

/// The value of an integer literal matiec types as BOOL where a BOOL is expected (an
/// input variable `0` or `1` wired into a contact, a coil or a Boolean pin): one
/// without a sign and untyped or `BOOL#`, of value 0 or 1 in any base. From matiec's
/// `stage3/fill_candidate_datatypes.cc`: an integer literal (`integer_c`,
/// `binary_integer_c`, …) has BOOL among its candidate types, which
/// `remove_incompatible_datatypes` drops when its value is above 1; a negative one
/// (`neg_integer_c`) never has it.
pub fn bool_of_int_literal(text: &str) -> Option<bool> {
    let t = text.trim();
    if t.starts_with(['-', '+']) {
        return None;
    }
    match crate::iec::literal::int_literal(t)? {
        (v @ 0..=1, None) => Some(v == 1),
        (v @ 0..=1, Some(ty)) if ty == "BOOL" => Some(v == 1),
        _ => None,
    }
}
