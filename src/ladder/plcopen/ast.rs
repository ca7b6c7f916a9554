//! The PLCopen AST: a project's POUs, variables, tasks and LD/FBD objects, each with its span in the XML.

use super::*;
use crate::diag::{FileId, Span};

/// A whole PLCopen project.
#[derive(Clone, Debug)]
pub struct Project {
    /// The file it was read from.
    pub file: FileId,
    /// The version its namespace names.
    pub version: Version,
    /// Every POU, from `types/pous` and CODESYS resource `addData`.
    pub pous: Vec<Pou>,
    /// Every task of every resource, and the task-less `pouInstance`s (as a task without interval).
    pub tasks: Vec<Task>,
    /// Configuration and resource globals.
    pub globals: Vec<Var>,
    /// The root element.
    pub span: Span,
    /// The user function blocks with a text body, lowered for the graphical bodies that
    /// call them (by upper-case name; the reason when one cannot be run exactly): filled
    /// by [`prepare_text_blocks`], empty until then.
    pub text_blocks: std::collections::BTreeMap<String, Result<TextBlock, String>>,
}

/// A task and the program instances it runs.
#[derive(Clone, Debug)]
pub struct Task {
    /// Its name (empty for instances directly in a resource).
    pub name: String,
    /// The `interval` attribute as written, and where.
    pub interval: Option<(String, Span)>,
    /// Where its `single` attribute is: an event task, run when its trigger rises.
    pub single: Option<Span>,
    /// `(instance name, POU type name, span)`.
    pub instances: Vec<(String, String, Span)>,
}

/// What a POU is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PouKind {
    /// `program`.
    Program,
    /// `functionBlock`.
    FunctionBlock,
    /// `function`.
    Function,
}

/// One POU.
#[derive(Clone, Debug)]
pub struct Pou {
    /// Its name.
    pub name: String,
    /// Program, function block or function.
    pub kind: PouKind,
    /// Every declared variable.
    pub vars: Vec<Var>,
    /// A function's return variable: named like the function, of its `returnType`, an
    /// output of the call (the block's `OUT` pin).
    pub result: Option<Var>,
    /// The first body, if any.
    pub body: Option<Body>,
    /// What is malformed in this POU's interface or body (reported only when it is checked).
    pub errors: Vec<PlcError>,
    /// The `pou` start tag.
    pub span: Span,
}

/// Which variable list a variable comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum VarClass {
    /// `inputVars`.
    Input,
    /// `outputVars`.
    Output,
    /// `inOutVars`.
    InOut,
    /// `localVars`.
    Local,
    /// `tempVars`.
    Temp,
    /// `externalVars`.
    External,
    /// `globalVars` (in a POU, a resource or a configuration).
    Global,
    /// `accessVars`.
    Access,
}

/// A variable's type, as far as the prover cares.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Ty {
    /// `BOOL`.
    Bool,
    /// A function-block or user type: `derived name=...`.
    Derived(String),
    /// Any other elementary or constructed type (its element name).
    Other(String),
}

impl Ty {
    /// The type's name as the IEC front end declares it (upper case).
    pub fn iec_name(&self) -> String {
        match self {
            Ty::Bool => "BOOL".into(),
            Ty::Derived(n) | Ty::Other(n) => n.to_ascii_uppercase(),
        }
    }
}

/// One declared variable.
#[derive(Clone, Debug)]
pub struct Var {
    /// The name as declared.
    pub name: String,
    /// The list it is in.
    pub class: VarClass,
    /// Its type.
    pub ty: Ty,
    /// A located address such as `%IX0.0`.
    pub address: Option<String>,
    /// The `simpleValue` of its initial value.
    pub init: Option<String>,
    /// Declared in a `retain="true"` or `persistent="true"` list: after a warm restart
    /// it keeps the value it had.
    pub retain: bool,
    /// The limits of its subrange type (a `dataType` with `subrangeSigned` or
    /// `subrangeUnsigned`), whose base type `ty` then names.
    pub range: Option<(i64, i64)>,
    /// The `variable` element.
    pub span: Span,
}

/// The language of a body.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lang {
    /// Ladder diagram.
    Ld,
    /// Function block diagram.
    Fbd,
    /// Structured text.
    St,
    /// Instruction list.
    Il,
    /// Sequential function chart.
    Sfc,
}

impl Lang {
    /// `LD`, `FBD`, …
    pub fn as_str(self) -> &'static str {
        match self {
            Lang::Ld => "LD",
            Lang::Fbd => "FBD",
            Lang::St => "ST",
            Lang::Il => "IL",
            Lang::Sfc => "SFC",
        }
    }
}

/// A POU body: for LD and FBD the bag of graphical objects.
#[derive(Clone, Debug)]
pub struct Body {
    /// Its language.
    pub lang: Lang,
    /// The objects in document order (empty for text and SFC bodies).
    pub objects: Vec<Obj>,
    /// A text body (ST, IL): where its text is, and the text with the XML's entities
    /// decoded. The range is into the file when the text stands there as it is (CDATA,
    /// no entity), else `None`.
    pub text: Option<(Option<std::ops::Range<usize>>, String)>,
    /// The language element (`LD`, `FBD`, …).
    pub span: Span,
}

/// An edge modifier.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Edge {
    /// None.
    None,
    /// Rising (P).
    Rising,
    /// Falling (N).
    Falling,
}

/// A coil's storage modifier.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Storage {
    /// Plain.
    None,
    /// Set (latch).
    Set,
    /// Reset (unlatch).
    Reset,
}

/// A wire, stored at its consumer: the producing object and, for blocks, its output pin.
#[derive(Clone, Debug)]
pub struct Conn {
    /// The producer's `localId`.
    pub from: u64,
    /// `formalParameter`, if given and not empty.
    pub formal: Option<String>,
    /// The `connection` element.
    pub span: Span,
}

/// A consumer pin (`connectionPointIn`), with its modifiers when it is a block pin.
#[derive(Clone, Debug)]
pub struct PinIn {
    /// The formal parameter (block pins), else empty.
    pub name: String,
    /// Its wires (several: a wired OR).
    pub conns: Vec<Conn>,
    /// A textual operand instead of wires.
    pub expr: Option<(String, Span)>,
    /// `negated`.
    pub negated: bool,
    /// `edge`.
    pub edge: Edge,
    /// Whether it is an in-out pin (VAR_IN_OUT: the block may write what is wired to it).
    pub in_out: bool,
    /// The pin element.
    pub span: Span,
}

/// An output pin of a block.
#[derive(Clone, Debug)]
pub struct PinOut {
    /// The formal parameter.
    pub name: String,
    /// `negated`.
    pub negated: bool,
    /// A CODESYS output-pin assignment target.
    pub expr: Option<(String, Span)>,
    /// The pin element.
    pub span: Span,
}

/// What a graphical object is.
#[derive(Clone, Debug)]
pub enum ObjKind {
    /// `leftPowerRail`: TRUE.
    LeftRail,
    /// `rightPowerRail`: a sink.
    RightRail,
    /// `contact`.
    Contact {
        /// The operand as written and where.
        var: (String, Span),
        /// NC contact.
        negated: bool,
        /// P/N contact.
        edge: Edge,
        /// Its predecessors.
        input: PinIn,
    },
    /// `coil`.
    Coil {
        /// The target as written and where.
        var: (String, Span),
        /// Negated coil.
        negated: bool,
        /// Set/reset.
        storage: Storage,
        /// P/N coil.
        edge: Edge,
        /// Its power.
        input: PinIn,
    },
    /// `inVariable`.
    InVar {
        /// The expression text and where.
        expr: (String, Span),
        /// Negated output.
        negated: bool,
        /// Edge on the output.
        edge: Edge,
    },
    /// `outVariable`.
    OutVar {
        /// The target text and where.
        expr: (String, Span),
        /// Negated.
        negated: bool,
        /// Set/reset.
        storage: Storage,
        /// Edge.
        edge: Edge,
        /// Its value.
        input: PinIn,
    },
    /// `inOutVariable`: assigned from its input, then readable.
    InOutVar {
        /// The variable text and where.
        expr: (String, Span),
        /// Its value.
        input: PinIn,
    },
    /// `block`.
    Block {
        /// `typeName`.
        type_name: String,
        /// `instanceName`.
        instance: Option<String>,
        /// Input pins (in-out pins included).
        inputs: Vec<PinIn>,
        /// Output pins.
        outputs: Vec<PinOut>,
    },
    /// `connector` (consumes what the continuation of the same name produces).
    Connector {
        /// The link name.
        name: String,
        /// Its input.
        input: PinIn,
    },
    /// `continuation`.
    Continuation {
        /// The link name.
        name: String,
    },
    /// No logic (`comment`, `vendorElement`, `actionBlock`, SFC objects…).
    Ignored,
    /// Control flow the prover refuses (`jump`, `label`, `return`).
    ControlFlow {
        /// The element name.
        tag: String,
    },
}

/// One graphical object.
#[derive(Clone, Debug)]
pub struct Obj {
    /// `localId`.
    pub id: u64,
    /// What it is.
    pub kind: ObjKind,
    /// `executionOrderId` (0 when absent).
    pub order: u64,
    /// `position` (x, y), if given.
    pub pos: Option<(i64, i64)>,
    /// The element's start tag.
    pub span: Span,
}

impl Obj {
    /// The element name, as in messages.
    pub fn tag(&self) -> &str {
        match &self.kind {
            ObjKind::LeftRail => "leftPowerRail",
            ObjKind::RightRail => "rightPowerRail",
            ObjKind::Contact { .. } => "contact",
            ObjKind::Coil { .. } => "coil",
            ObjKind::InVar { .. } => "inVariable",
            ObjKind::OutVar { .. } => "outVariable",
            ObjKind::InOutVar { .. } => "inOutVariable",
            ObjKind::Block { .. } => "block",
            ObjKind::Connector { .. } => "connector",
            ObjKind::Continuation { .. } => "continuation",
            ObjKind::Ignored => "comment",
            ObjKind::ControlFlow { tag } => tag,
        }
    }
}
