//! Reader for PLCopen TC6 XML (1.0, 2.0, 2.01; `shared/formats/plcopen-xml.md`): XML text → a typed AST of POUs, variables, tasks and LD/FBD objects, every node with its [`Span`] in the file.
//!
//! The reader accepts the three namespaces (decided from the root element's own
//! namespace), a UTF-8 byte-order mark, children in any order, missing
//! positions, and the vendor deviations of §5.1 (`formalParameter` on wires from
//! rails and contacts, empty `formalParameter`). It never panics; every problem is
//! a [`PlcError`] with a span into the XML. [`select`] checks one POU and
//! resolves its names, wires and evaluation order into a [`PlcProgram`], which the
//! lowering ([`lower`]) and the scan simulator ([`simulate`]) both consume.

pub mod lower;
pub mod simulate;

use std::collections::{BTreeMap, BTreeSet};

use crate::diag::{FileId, Report, Severity, Sources, Span, did_you_mean};

pub use lower::lower;
pub use simulate::PlcSimulator;

/// Which PLCopen version the root element's namespace names.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Version {
    /// `http://www.plcopen.org/xml/tc6.xsd`.
    V1_0,
    /// `http://www.plcopen.org/xml/tc6_0200`.
    V2_0,
    /// `http://www.plcopen.org/xml/tc6_0201`.
    V2_01,
}

impl Version {
    /// The version of a namespace URI, if it is a PLCopen TC6 one.
    pub fn of_namespace(ns: &str) -> Option<Version> {
        match ns.trim_end_matches('/') {
            "http://www.plcopen.org/xml/tc6.xsd" => Some(Version::V1_0),
            "http://www.plcopen.org/xml/tc6_0200" => Some(Version::V2_0),
            "http://www.plcopen.org/xml/tc6_0201" => Some(Version::V2_01),
            _ => None,
        }
    }
}

/// Whether `text` is a PLCopen document: an XML document whose root is `project` in a
/// TC6 namespace. Cheap: looks only at the root start tag.
pub fn is_plcopen(text: &str) -> bool {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut rest = text.trim_start();
    // Skip the declaration, comments and processing instructions before the root.
    loop {
        if let Some(r) = rest.strip_prefix("<?") {
            let Some(end) = r.find("?>") else { return false };
            rest = r[end + 2..].trim_start();
        } else if let Some(r) = rest.strip_prefix("<!--") {
            let Some(end) = r.find("-->") else { return false };
            rest = r[end + 3..].trim_start();
        } else {
            break;
        }
    }
    let Some(tag) = rest.strip_prefix('<') else { return false };
    let end = tag.find('>').unwrap_or(tag.len());
    let head = &tag[..end];
    let name = head.split(|c: char| c.is_whitespace() || c == '/').next().unwrap_or("");
    let (prefix, local) = match name.split_once(':') {
        Some((p, l)) => (Some(p), l),
        None => (None, name),
    };
    if local != "project" {
        return false;
    }
    let attr = match prefix {
        Some(p) => format!("xmlns:{p}="),
        None => "xmlns=".to_string(),
    };
    let mut from = 0;
    while let Some(at) = head[from..].find(&attr) {
        let start = from + at;
        let before_ok = start == 0 || head[..start].ends_with(char::is_whitespace);
        let value = &head[start + attr.len()..];
        if before_ok {
            let quote = value.chars().next().unwrap_or('"');
            let uri = value[1.min(value.len())..].split(quote).next().unwrap_or("");
            return Version::of_namespace(uri).is_some();
        }
        from = start + attr.len();
    }
    false
}

/// A problem in a PLCopen file: the file is refused (errors) or loaded with a note (warnings).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PlcError {
    /// The text is not well-formed XML.
    Xml {
        /// Where the XML parser stopped.
        span: Span,
        /// What it said.
        message: String,
    },
    /// Well-formed XML, but not a PLCopen project.
    NotPlcopen {
        /// The root element.
        span: Span,
        /// What the root is.
        found: String,
    },
    /// A missing or malformed attribute, child or text.
    Malformed {
        /// Where.
        span: Span,
        /// What is wrong.
        what: String,
        /// What was expected.
        expected: String,
    },
    /// A name that does not resolve.
    Unknown {
        /// The name as written.
        span: Span,
        /// What kind of thing (`variable`, `POU`, `object id`).
        kind: String,
        /// The name.
        name: String,
        /// Candidates: the nearest ("did you mean") or all of them (ambiguity).
        candidates: Vec<String>,
        /// Whether the name matched several candidates.
        ambiguous: bool,
    },
    /// Something the prover does not model soundly: the program is refused.
    Unsupported {
        /// Where.
        span: Span,
        /// What it is (`jump`, `user function block FOO`, `ST body`).
        what: String,
        /// Why it cannot be modelled.
        reason: String,
    },
    /// Warning: loaded, but the user should know (order ambiguity, defaults used).
    Note {
        /// Where.
        span: Span,
        /// What was done.
        message: String,
    },
}

impl Report for PlcError {
    fn span(&self) -> Option<Span> {
        Some(match self {
            PlcError::Xml { span, .. }
            | PlcError::NotPlcopen { span, .. }
            | PlcError::Malformed { span, .. }
            | PlcError::Unknown { span, .. }
            | PlcError::Unsupported { span, .. }
            | PlcError::Note { span, .. } => *span,
        })
    }

    fn message(&self) -> String {
        match self {
            PlcError::Xml { message, .. } => format!("malformed XML: {message}"),
            PlcError::NotPlcopen { found, .. } => format!(
                "not a PLCopen TC6 project: the root is {found}, expected `project` in the \
                 namespace tc6_0201, tc6_0200 or tc6.xsd"
            ),
            PlcError::Malformed { what, expected, .. } => format!("{what}: expected {expected}"),
            PlcError::Unknown { kind, name, ambiguous: true, .. } => {
                format!("ambiguous {kind} `{name}`")
            }
            PlcError::Unknown { kind, name, .. } => format!("unknown {kind} `{name}`"),
            PlcError::Unsupported { what, reason, .. } => {
                format!("{what} is not supported: {reason}")
            }
            PlcError::Note { message, .. } => message.clone(),
        }
    }

    fn label(&self) -> String {
        match self {
            PlcError::Xml { .. } => "here".into(),
            PlcError::NotPlcopen { .. } => "expected a PLCopen `project`".into(),
            PlcError::Malformed { expected, .. } => format!("expected {expected}"),
            PlcError::Unknown { kind, .. } => format!("expected a declared {kind}"),
            PlcError::Unsupported { .. } => "the program is refused here".into(),
            PlcError::Note { .. } => "note".into(),
        }
    }

    fn notes(&self) -> Vec<String> {
        match self {
            PlcError::Unknown { candidates, ambiguous: true, .. } => {
                vec![format!("candidates: {}", candidates.join(", "))]
            }
            PlcError::Unknown { candidates, .. } if candidates.len() == 1 => {
                vec![format!("did you mean `{}`?", candidates[0])]
            }
            PlcError::Unknown { candidates, .. } if !candidates.is_empty() => {
                vec![format!("candidates: {}", candidates.join(", "))]
            }
            _ => Vec::new(),
        }
    }

    fn severity(&self) -> Severity {
        match self {
            PlcError::Note { .. } => Severity::Warning,
            _ => Severity::Error,
        }
    }
}

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
}

/// A task and the program instances it runs.
#[derive(Clone, Debug)]
pub struct Task {
    /// Its name (empty for instances directly in a resource).
    pub name: String,
    /// The `interval` attribute as written, and where.
    pub interval: Option<(String, Span)>,
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

// ---------------------------------------------------------------------------------
// Reading
// ---------------------------------------------------------------------------------

type Node<'a, 'i> = roxmltree::Node<'a, 'i>;

struct Reader<'t> {
    file: FileId,
    /// Bytes stripped from the front of the text (a BOM).
    shift: usize,
    text: &'t str,
    errors: Vec<PlcError>,
}

fn children<'a, 'i>(n: Node<'a, 'i>, name: &'a str) -> impl Iterator<Item = Node<'a, 'i>> + 'a {
    n.children().filter(move |c| c.is_element() && c.tag_name().name() == name)
}

fn child<'a, 'i>(n: Node<'a, 'i>, name: &str) -> Option<Node<'a, 'i>> {
    n.children().find(|c| c.is_element() && c.tag_name().name() == name)
}

fn flag(n: Node, name: &str) -> bool {
    matches!(n.attribute(name), Some("true" | "1"))
}

impl Reader<'_> {
    fn span(&self, r: std::ops::Range<usize>) -> Span {
        Span::new(self.file, r.start + self.shift..r.end + self.shift)
    }

    /// The start tag's name: `<contact`.
    fn tag(&self, n: Node) -> Span {
        let start = n.range().start;
        let len = 1 + n.tag_name().name().len();
        let end = (start + len).min(self.text.len());
        self.span(start..end.max(start))
    }

    fn attr_span(&self, n: Node, name: &str) -> Span {
        n.attributes()
            .find(|a| a.name() == name)
            .map_or_else(|| self.tag(n), |a| self.span(a.range_value()))
    }

    fn malformed(&mut self, span: Span, what: impl Into<String>, expected: impl Into<String>) {
        self.errors.push(PlcError::Malformed {
            span,
            what: what.into(),
            expected: expected.into(),
        });
    }

    fn required(&mut self, n: Node, name: &str) -> String {
        match n.attribute(name) {
            Some(v) => v.to_string(),
            None => {
                let tag = n.tag_name().name().to_string();
                self.malformed(
                    self.tag(n),
                    format!("`{tag}` without `{name}`"),
                    format!("a `{name}` attribute"),
                );
                String::new()
            }
        }
    }

    fn text_of(&self, n: Node) -> (String, Span) {
        let text: String =
            n.descendants().filter(|d| d.is_text()).filter_map(|d| d.text()).collect();
        let span = n
            .descendants()
            .find(|d| d.is_text() && d.text().is_some_and(|t| !t.trim().is_empty()))
            .map_or_else(
                || self.tag(n),
                |d| {
                    let r = d.range();
                    // Point at the trimmed text when it is written plainly.
                    let raw = &self.text[r.clone()];
                    let lead = raw.len() - raw.trim_start().len();
                    let trail = raw.len() - raw.trim_end().len();
                    if raw.trim() == text.trim() {
                        self.span(r.start + lead..r.end - trail)
                    } else {
                        self.span(r)
                    }
                },
            );
        (text.trim().to_string(), span)
    }

    fn edge(&mut self, n: Node, name: &str) -> Edge {
        match n.attribute(name) {
            None | Some("none") => Edge::None,
            Some("rising") => Edge::Rising,
            Some("falling") => Edge::Falling,
            Some(v) => {
                let span = self.attr_span(n, name);
                self.malformed(span, format!("`{name}=\"{v}\"`"), "`none`, `rising` or `falling`");
                Edge::None
            }
        }
    }

    fn storage(&mut self, n: Node, name: &str) -> Storage {
        match n.attribute(name) {
            None | Some("none") => Storage::None,
            Some("set") => Storage::Set,
            Some("reset") => Storage::Reset,
            Some(v) => {
                let span = self.attr_span(n, name);
                self.malformed(span, format!("`{name}=\"{v}\"`"), "`none`, `set` or `reset`");
                Storage::None
            }
        }
    }

    fn conns(&mut self, point: Node) -> Vec<Conn> {
        let mut out = Vec::new();
        for c in children(point, "connection") {
            let span = self.tag(c);
            let Some(raw) = c.attribute("refLocalId") else {
                self.malformed(span, "`connection` without `refLocalId`", "a `refLocalId`");
                continue;
            };
            let Ok(from) = raw.trim().parse::<u64>() else {
                let span = self.attr_span(c, "refLocalId");
                self.malformed(span, format!("`refLocalId=\"{raw}\"`"), "an unsigned integer");
                continue;
            };
            let formal =
                c.attribute("formalParameter").filter(|f| !f.is_empty()).map(str::to_string);
            out.push(Conn { from, formal, span });
        }
        out
    }

    /// The `connectionPointIn` child of `n` (none: an unconnected pin).
    fn pin_in(&mut self, n: Node, name: String, owner: Node) -> PinIn {
        let point = child(n, "connectionPointIn");
        let conns = point.map(|p| self.conns(p)).unwrap_or_default();
        let expr = point.and_then(|p| child(p, "expression")).map(|e| self.text_of(e));
        PinIn {
            name,
            conns,
            expr,
            negated: flag(owner, "negated"),
            edge: self.edge(owner, "edge"),
            in_out: false,
            span: self.tag(owner),
        }
    }

    fn position(&self, n: Node) -> Option<(i64, i64)> {
        let p = child(n, "position")?;
        let x = p.attribute("x")?.trim().parse::<f64>().ok()?;
        let y = p.attribute("y")?.trim().parse::<f64>().ok()?;
        Some((x as i64, y as i64))
    }

    fn object(&mut self, n: Node) -> Option<Obj> {
        let tag = n.tag_name().name();
        let span = self.tag(n);
        let kind = match tag {
            "leftPowerRail" => ObjKind::LeftRail,
            "rightPowerRail" => ObjKind::RightRail,
            "contact" | "coil" => {
                let var = match child(n, "variable") {
                    Some(v) => self.text_of(v),
                    None => {
                        self.malformed(span, format!("`{tag}` without `variable`"), "a `variable`");
                        (String::new(), span)
                    }
                };
                let input = self.pin_in(n, String::new(), n);
                if tag == "contact" {
                    ObjKind::Contact {
                        var,
                        negated: input.negated,
                        edge: input.edge,
                        input: PinIn { negated: false, edge: Edge::None, ..input },
                    }
                } else {
                    ObjKind::Coil {
                        var,
                        negated: input.negated,
                        storage: self.storage(n, "storage"),
                        edge: input.edge,
                        input: PinIn { negated: false, edge: Edge::None, ..input },
                    }
                }
            }
            "inVariable" | "outVariable" | "inOutVariable" => {
                let expr = match child(n, "expression") {
                    Some(e) => self.text_of(e),
                    None => {
                        self.malformed(
                            span,
                            format!("`{tag}` without `expression`"),
                            "an `expression`",
                        );
                        (String::new(), span)
                    }
                };
                match tag {
                    "inVariable" => ObjKind::InVar {
                        expr,
                        negated: flag(n, "negated"),
                        edge: self.edge(n, "edge"),
                    },
                    "outVariable" => {
                        let input = self.pin_in(n, String::new(), n);
                        ObjKind::OutVar {
                            expr,
                            negated: input.negated,
                            storage: self.storage(n, "storage"),
                            edge: input.edge,
                            input: PinIn { negated: false, edge: Edge::None, ..input },
                        }
                    }
                    _ => {
                        let input = self.pin_in(n, String::new(), n);
                        if flag(n, "negatedIn") || flag(n, "negatedOut") {
                            self.errors.push(PlcError::Unsupported {
                                span,
                                what: "a negated `inOutVariable`".into(),
                                reason: "only plain in-out variables are modelled".into(),
                            });
                        }
                        ObjKind::InOutVar {
                            expr,
                            input: PinIn { negated: false, edge: Edge::None, ..input },
                        }
                    }
                }
            }
            "block" => {
                let type_name = self.required(n, "typeName");
                let instance =
                    n.attribute("instanceName").filter(|s| !s.is_empty()).map(str::to_string);
                let mut inputs = Vec::new();
                let mut outputs = Vec::new();
                for list in ["inputVariables", "inOutVariables"] {
                    for l in children(n, list) {
                        for v in children(l, "variable") {
                            let name = self.required(v, "formalParameter");
                            let pin = self.pin_in(v, name, v);
                            inputs.push(PinIn { in_out: list == "inOutVariables", ..pin });
                        }
                    }
                }
                for l in children(n, "outputVariables") {
                    for v in children(l, "variable") {
                        let name = self.required(v, "formalParameter");
                        let expr = child(v, "connectionPointOut")
                            .and_then(|p| child(p, "expression"))
                            .map(|e| self.text_of(e));
                        outputs.push(PinOut {
                            name,
                            negated: flag(v, "negated"),
                            expr,
                            span: self.tag(v),
                        });
                    }
                }
                ObjKind::Block { type_name, instance, inputs, outputs }
            }
            "connector" => {
                let name = self.required(n, "name");
                ObjKind::Connector { input: self.pin_in(n, String::new(), n), name }
            }
            "continuation" => ObjKind::Continuation { name: self.required(n, "name") },
            "jump" | "label" | "return" => ObjKind::ControlFlow { tag: tag.to_string() },
            _ => ObjKind::Ignored,
        };
        let id = match n.attribute("localId") {
            Some(raw) => match raw.trim().parse::<u64>() {
                Ok(id) => id,
                Err(_) => {
                    let s = self.attr_span(n, "localId");
                    self.malformed(s, format!("`localId=\"{raw}\"`"), "an unsigned integer");
                    return None;
                }
            },
            None if matches!(kind, ObjKind::Ignored) => u64::MAX,
            None => {
                self.malformed(span, format!("`{tag}` without `localId`"), "a `localId` attribute");
                return None;
            }
        };
        let order =
            n.attribute("executionOrderId").and_then(|v| v.trim().parse().ok()).unwrap_or(0);
        Some(Obj { id, kind, order, pos: self.position(n), span })
    }

    fn body(&mut self, b: Node) -> Option<Body> {
        let content = b.children().find(|c| c.is_element())?;
        let lang = match content.tag_name().name() {
            "LD" => Lang::Ld,
            "FBD" => Lang::Fbd,
            "ST" => Lang::St,
            "IL" => Lang::Il,
            "SFC" => Lang::Sfc,
            _ => return None,
        };
        let mut objects = Vec::new();
        if matches!(lang, Lang::Ld | Lang::Fbd) {
            for o in content.children().filter(|c| c.is_element()) {
                if let Some(obj) = self.object(o) {
                    objects.push(obj);
                }
            }
        }
        Some(Body { lang, objects, span: self.tag(content) })
    }

    fn vars(&mut self, list: Node, class: VarClass, out: &mut Vec<Var>) {
        for v in children(list, "variable") {
            let name = self.required(v, "name");
            let ty = match child(v, "type").and_then(|t| t.children().find(|c| c.is_element())) {
                Some(t) if t.tag_name().name() == "BOOL" => Ty::Bool,
                Some(t) if t.tag_name().name() == "derived" => {
                    Ty::Derived(t.attribute("name").unwrap_or_default().to_string())
                }
                Some(t) => Ty::Other(t.tag_name().name().to_string()),
                None => Ty::Other("?".into()),
            };
            let init = child(v, "initialValue")
                .and_then(|i| child(i, "simpleValue"))
                .and_then(|s| s.attribute("value"))
                .map(str::to_string);
            let address = v.attribute("address").map(str::to_string);
            out.push(Var { name, class, ty, address, init, span: self.tag(v) });
        }
    }

    fn pou(&mut self, p: Node) -> Pou {
        let name = self.required(p, "name");
        let before = self.errors.len();
        let kind = match p.attribute("pouType") {
            Some("functionBlock") => PouKind::FunctionBlock,
            Some("function") => PouKind::Function,
            _ => PouKind::Program,
        };
        let mut vars = Vec::new();
        if let Some(i) = child(p, "interface") {
            for l in i.children().filter(|c| c.is_element()) {
                let class = match l.tag_name().name() {
                    "inputVars" => VarClass::Input,
                    "outputVars" => VarClass::Output,
                    "inOutVars" => VarClass::InOut,
                    "localVars" => VarClass::Local,
                    "tempVars" => VarClass::Temp,
                    "externalVars" => VarClass::External,
                    "globalVars" => VarClass::Global,
                    "accessVars" => VarClass::Access,
                    _ => continue,
                };
                self.vars(l, class, &mut vars);
            }
        }
        let body = child(p, "body").and_then(|b| self.body(b));
        let errors = self.errors.split_off(before);
        Pou { name, kind, vars, body, errors, span: self.tag(p) }
    }
}

/// Where a roxmltree error points, as a byte offset.
fn error_offset(text: &str, e: &roxmltree::Error) -> usize {
    let pos = e.pos();
    let mut offset = 0;
    for (k, line) in text.split_inclusive('\n').enumerate() {
        if k + 1 == pos.row as usize {
            let col = (pos.col as usize).saturating_sub(1);
            return offset + line.char_indices().nth(col).map_or(line.len(), |(i, _)| i);
        }
        offset += line.len();
    }
    text.len()
}

/// Reads a PLCopen project. Never panics.
pub fn read_plcopen(sources: &Sources, file: FileId) -> Result<Project, Vec<PlcError>> {
    let full = sources.text(file);
    let text = full.strip_prefix('\u{feff}').unwrap_or(full);
    let shift = full.len() - text.len();
    let options = roxmltree::ParsingOptions { allow_dtd: true, ..Default::default() };
    let doc = match roxmltree::Document::parse_with_options(text, options) {
        Ok(doc) => doc,
        Err(e) => {
            let at = error_offset(text, &e) + shift;
            let end = (at + 1).min(full.len());
            let end = (at..=end).rev().find(|i| full.is_char_boundary(*i)).unwrap_or(at);
            return Err(vec![PlcError::Xml {
                span: Span::new(file, at..end),
                message: e.to_string(),
            }]);
        }
    };
    let mut r = Reader { file, shift, text, errors: Vec::new() };
    let root = doc.root_element();
    let span = r.tag(root);
    let version = root.tag_name().namespace().and_then(Version::of_namespace);
    let Some(version) = version.filter(|_| root.tag_name().name() == "project") else {
        let found = match root.tag_name().namespace() {
            Some(ns) => format!("`{}` in namespace `{ns}`", root.tag_name().name()),
            None => format!("`{}` without a namespace", root.tag_name().name()),
        };
        return Err(vec![PlcError::NotPlcopen { span, found }]);
    };
    let mut pous = Vec::new();
    let mut tasks = Vec::new();
    let mut globals = Vec::new();
    for d in root.descendants().filter(|d| d.is_element()) {
        match d.tag_name().name() {
            // POUs in `types/pous` and in CODESYS resource `addData` containers.
            "pou"
                if d.parent_element()
                    .is_some_and(|p| matches!(p.tag_name().name(), "pous" | "data")) =>
            {
                pous.push(r.pou(d));
            }
            "globalVars"
                if d.parent_element().is_some_and(|p| {
                    matches!(p.tag_name().name(), "configuration" | "resource")
                }) =>
            {
                r.vars(d, VarClass::Global, &mut globals);
            }
            "resource" => {
                for t in children(d, "task") {
                    let interval = t
                        .attribute("interval")
                        .map(|v| (v.to_string(), r.attr_span(t, "interval")));
                    let instances =
                        children(t, "pouInstance").map(|i| pou_instance(&mut r, i)).collect();
                    tasks.push(Task {
                        name: t.attribute("name").unwrap_or_default().into(),
                        interval,
                        instances,
                    });
                }
                let free: Vec<_> =
                    children(d, "pouInstance").map(|i| pou_instance(&mut r, i)).collect();
                if !free.is_empty() {
                    tasks.push(Task { name: String::new(), interval: None, instances: free });
                }
            }
            _ => {}
        }
    }
    if r.errors.is_empty() {
        Ok(Project { file, version, pous, tasks, globals, span })
    } else {
        Err(r.errors)
    }
}

fn pou_instance(r: &mut Reader, i: Node) -> (String, String, Span) {
    let name = i.attribute("name").unwrap_or_default().to_string();
    // 1.0 writes the POU name in `type`.
    let ty =
        i.attribute("typeName").or_else(|| i.attribute("type")).unwrap_or_default().to_string();
    (name, ty, r.tag(i))
}

// ---------------------------------------------------------------------------------
// Durations
// ---------------------------------------------------------------------------------

/// An IEC duration literal (`T#5s`, `TIME#1h2m`, `t#1.5s`, `T#-0s`) or a 1.0 interval
/// (`00:00:00.100000`), in microseconds.
pub fn parse_duration(text: &str) -> Option<u64> {
    let t = text.trim();
    if let Some((h, rest)) = t.split_once(':') {
        let (m, s) = rest.split_once(':')?;
        let (h, m): (u64, u64) = (h.parse().ok()?, m.parse().ok()?);
        let secs = parse_decimal(s, 1_000_000)?;
        return (h * 3600 + m * 60).checked_mul(1_000_000)?.checked_add(secs);
    }
    let upper = t.to_ascii_uppercase();
    let body = upper
        .strip_prefix("TIME#")
        .or_else(|| upper.strip_prefix("T#"))
        .or_else(|| upper.strip_prefix("LTIME#"))
        .or_else(|| upper.strip_prefix("LT#"))?;
    let body: String = body.chars().filter(|c| *c != '_').collect();
    if body.is_empty() || body.starts_with('-') {
        return None;
    }
    let units: [(&str, u64); 7] = [
        ("MS", 1_000),
        ("US", 1),
        ("NS", 0),
        ("D", 86_400_000_000),
        ("H", 3_600_000_000),
        ("M", 60_000_000),
        ("S", 1_000_000),
    ];
    let mut rest = body.as_str();
    let mut total: u64 = 0;
    while !rest.is_empty() {
        let n = rest.find(|c: char| !(c.is_ascii_digit() || c == '.')).unwrap_or(rest.len());
        let (num, after) = rest.split_at(n);
        if num.is_empty() {
            return None;
        }
        let (unit, scale) = units.iter().find(|(u, _)| after.starts_with(u))?;
        let v = if *scale == 0 { Some(0) } else { parse_decimal(num, *scale) }?;
        total = total.checked_add(v)?;
        rest = &after[unit.len()..];
    }
    Some(total)
}

/// `12.5` × `scale`, truncated.
fn parse_decimal(s: &str, scale: u64) -> Option<u64> {
    let (int, frac) = s.split_once('.').unwrap_or((s, ""));
    let int: u64 = if int.is_empty() { 0 } else { int.parse().ok()? };
    let mut v = int.checked_mul(scale)?;
    let mut unit = scale;
    for c in frac.chars() {
        unit /= 10;
        v = v.checked_add(u64::from(c.to_digit(10)?) * unit)?;
    }
    Some(v)
}

// ---------------------------------------------------------------------------------
// Selection: one POU, checked, with names, wires and order resolved
// ---------------------------------------------------------------------------------

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
    /// Pulse timer (its output is unconstrained for the prover).
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
    /// Hidden variable names: `(object, pin)` → name (pin `""` for a contact's or variable's edge).
    pub hidden: BTreeMap<(usize, String), String>,
    /// Resolved operands of contacts, coils and variable objects, by object index.
    pub operands: BTreeMap<usize, Operand>,
    /// The names the outside world writes at the start of every scan: declared inputs
    /// (input, in-out, external and global variables, `%I`/`%M` located variables, BOOLs
    /// declared TRUE that nothing writes), and for each such variable the program also
    /// writes, its latch instead (see `latches`).
    pub inputs: BTreeSet<String>,
    /// Inputs the program also writes: variable → the hidden name of the value latched
    /// from outside at the start of the scan (`In0_IN`); reads before the program's
    /// first write see the latch, not the previous scan.
    pub latches: BTreeMap<String, String>,
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

/// Picks the program to check: `--pou`, else the POU the configuration's task runs, else the only program.
fn pick<'p>(
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
        (several, _) if !several.is_empty() => Err(vec![PlcError::Unknown {
            span: project.span,
            kind: "program to check: the tasks run several; choose one with --pou, e.g. --pou".into(),
            name: several[0].name.clone(),
            candidates: several.iter().map(|p| p.name.clone()).collect(),
            ambiguous: true,
        }]),
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
    warnings.append(&mut program.warnings);
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
    let mut inputs = BTreeSet::new();
    for v in vars.values() {
        let addr = v.address.as_deref().unwrap_or("").to_ascii_uppercase();
        let interface = matches!(v.class, VarClass::Input | VarClass::InOut) && depth == 0;
        let external = interface
            || matches!(v.class, VarClass::External | VarClass::Global | VarClass::Access)
            || addr.starts_with("%I")
            || addr.starts_with("%M");
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
        hidden: BTreeMap::new(),
        operands: BTreeMap::new(),
        inputs,
        latches: BTreeMap::new(),
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
            ObjKind::Contact { var, edge, input, .. } => {
                pins.push(input);
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
            ObjKind::InVar { expr, edge, .. } => {
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
                if *negated && (*storage != Storage::None || *edge != Edge::None) {
                    errors.push(PlcError::Unsupported {
                        span: o.span,
                        what: "a negated output with a storage or edge modifier".into(),
                        reason: "the combination has no agreed meaning".into(),
                    });
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
    // A BOOL declared TRUE: unwritten, it is a free input (sound); written, its first
    // scan would read TRUE where the scan model starts every bit at 0.
    for v in program.vars.values() {
        if v.ty == Ty::Bool
            && v.init.as_deref().is_some_and(is_true)
            && !program.inputs.contains(&v.name)
        {
            if written.contains(&v.name) {
                errors.push(PlcError::Unsupported {
                    span: v.span,
                    what: format!("the initial value TRUE of `{}`", v.name),
                    reason: "the program writes it, and the scan model starts every written bit at FALSE".into(),
                });
            } else {
                program.inputs.insert(v.name.clone());
            }
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    // Inputs the program also writes are latched from outside at the start of every scan.
    let written: Vec<String> = written.into_iter().filter(|n| program.inputs.contains(n)).collect();
    for x in written {
        let latch = hide(&mut taken, format!("{x}_IN"));
        program.inputs.remove(&x);
        program.inputs.insert(latch.clone());
        program.latches.insert(x, latch);
    }
    program.order_statements(&mut warnings);
    program.warnings = warnings;
    Ok(program)
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
    matches!(init.trim().to_ascii_uppercase().as_str(), "TRUE" | "1" | "BOOL#TRUE" | "BOOL#1")
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
    if !child.latches.is_empty() {
        return None;
    }
    warnings.append(&mut child.warnings);
    child.prefix_names(&format!("{}_", inst.name));
    Some(Ok(child))
}

impl PlcProgram {
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
        let rename = |n: &String| map.get(n).cloned().unwrap_or_else(|| n.clone());
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
            .collect();
        for sub in self.subs.values() {
            out.extend(sub.names());
        }
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

    /// Orders the statements as Beremiz's `PLCGenerator.ComputeProgram` does (§8).
    fn order_statements(&mut self, warnings: &mut Vec<PlcError>) {
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
                let amb = geometric(list, objects);
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
        order.extend(outputs);
        order.extend(blocks);
        order.extend(connectors);
        self.order = order;
        self.rule = rule;
    }
}

/// Sorts `list` as Beremiz's `SortInstances` does: rows of objects within 10 units
/// of height, top to bottom, each left to right. Returns a pair whose order depended
/// on the 10-unit row rule (different heights, same row), if any.
fn geometric(list: &mut [usize], objects: &[Obj]) -> Option<(usize, usize)> {
    let pos = |k: usize| objects[k].pos.unwrap_or((0, 0));
    list.sort_by_key(|k| (pos(*k).1, pos(*k).0));
    let mut rows: Vec<Vec<usize>> = Vec::new();
    for &k in list.iter() {
        match rows.last_mut() {
            Some(row) if (pos(k).1 - pos(row[0]).1).abs() < 10 => row.push(k),
            _ => rows.push(vec![k]),
        }
    }
    let mut ambiguous = None;
    for row in &mut rows {
        row.sort_by_key(|k| pos(*k).0);
        for w in row.windows(2) {
            if pos(w[0]).1 != pos(w[1]).1 && ambiguous.is_none() {
                ambiguous = Some((w[0], w[1]));
            }
        }
    }
    for (slot, k) in list.iter_mut().zip(rows.into_iter().flatten()) {
        *slot = k;
    }
    ambiguous
}
