//! The XML reader: roxmltree nodes → the AST, every problem a located `PlcError`; durations such as `T#20ms`.

use super::*;
use crate::diag::{FileId, Sources, Span};
use std::collections::BTreeMap;

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
        let text = matches!(lang, Lang::St | Lang::Il).then(|| text_of_body(self.text, content));
        Some(Body { lang, objects, text, span: self.tag(content) })
    }

    fn vars(&mut self, list: Node, class: VarClass, out: &mut Vec<Var>) {
        let kept = |a: &str| list.attribute(a).is_some_and(|v| matches!(v, "true" | "1"));
        let retain = kept("retain") || kept("persistent");
        for v in children(list, "variable") {
            let name = self.required(v, "name");
            let ty = type_of(child(v, "type"));
            let init = child(v, "initialValue")
                .and_then(|i| child(i, "simpleValue"))
                .and_then(|s| s.attribute("value"))
                .map(str::to_string);
            let address = v.attribute("address").map(str::to_string);
            out.push(Var {
                name,
                class,
                ty,
                address,
                init,
                retain,
                range: None,
                span: self.tag(v),
            });
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
        // A function's return variable, named like it.
        let result = child(p, "interface")
            .and_then(|i| child(i, "returnType"))
            .filter(|_| kind == PouKind::Function)
            .map(|t| Var {
                name: name.clone(),
                class: VarClass::Output,
                ty: type_of(Some(t)),
                address: None,
                init: None,
                retain: false,
                range: None,
                span: self.tag(t),
            });
        let body = child(p, "body").and_then(|b| self.body(b));
        let errors = self.errors.split_off(before);
        Pou { name, kind, vars, result, body, errors, span: self.tag(p) }
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
                    let single = t.attribute("single").map(|_| r.attr_span(t, "single"));
                    tasks.push(Task {
                        name: t.attribute("name").unwrap_or_default().into(),
                        interval,
                        single,
                        instances,
                    });
                }
                let free: Vec<_> =
                    children(d, "pouInstance").map(|i| pou_instance(&mut r, i)).collect();
                if !free.is_empty() {
                    tasks.push(Task {
                        name: String::new(),
                        interval: None,
                        single: None,
                        instances: free,
                    });
                }
            }
            _ => {}
        }
    }
    let types = user_types(root);
    let vars = pous.iter_mut().flat_map(|p| p.vars.iter_mut().chain(p.result.as_mut()));
    for v in vars.chain(globals.iter_mut()) {
        resolve_type(v, &types);
    }
    if r.errors.is_empty() {
        Ok(Project { file, version, pous, tasks, globals, span, text_blocks: Default::default() })
    } else {
        Err(r.errors)
    }
}

/// A user data type that variables of it are read through, with the type's initial
/// value: a subrange of an integer type (its base type, an XML element name such as
/// `INT`, and its limits), or another name of a type (`datatype0` of `BOOL`).
enum UserType {
    Subrange(String, i64, i64, Option<String>),
    Alias(Ty, Option<String>),
}

/// How many names of one type are followed (`a` of `b` of `BOOL`) before the type
/// stays derived (a loop of names).
const MAX_ALIASES: usize = 16;

/// The elementary types a `dataType` may give another name (the XML's element names).
const ELEMENTARY: [&str; 21] = [
    "BOOL", "SINT", "INT", "DINT", "LINT", "USINT", "UINT", "UDINT", "ULINT", "BYTE", "WORD",
    "DWORD", "LWORD", "REAL", "LREAL", "TIME", "DATE", "TOD", "DT", "string", "wstring",
];

/// The type a `type`, `baseType` or `returnType` element names.
fn type_of(t: Option<Node>) -> Ty {
    match t.and_then(|t| t.children().find(|c| c.is_element())) {
        Some(t) if t.tag_name().name() == "BOOL" => Ty::Bool,
        Some(t) if t.tag_name().name() == "derived" => {
            Ty::Derived(t.attribute("name").unwrap_or_default().to_string())
        }
        Some(t) => Ty::Other(t.tag_name().name().to_string()),
        None => Ty::Other("?".into()),
    }
}

/// The user types of `types/dataTypes` variables are read through, by upper-case name:
/// a `dataType` whose base type is a `subrangeSigned` or `subrangeUnsigned` of an
/// integer type matiec allows one of, with limits in order and within that type; one
/// whose base type is an elementary type or names another type. Others (enumerations,
/// arrays, structures) stay derived types, opaque.
fn user_types(root: Node) -> BTreeMap<String, UserType> {
    let mut out = BTreeMap::new();
    let in_list = |d: &Node| d.parent_element().is_some_and(|p| p.tag_name().name() == "dataTypes");
    for d in root.descendants().filter(|d| d.tag_name().name() == "dataType" && in_list(d)) {
        let Some(name) = d.attribute("name") else { continue };
        let init = child(d, "initialValue")
            .and_then(|i| child(i, "simpleValue"))
            .and_then(|s| s.attribute("value"))
            .map(str::to_string);
        let base = child(d, "baseType");
        let element = base.and_then(|b| b.children().find(|c| c.is_element()));
        let element = element.map(|e| e.tag_name().name()).unwrap_or_default();
        if ELEMENTARY.contains(&element) || element == "derived" {
            out.insert(name.to_ascii_uppercase(), UserType::Alias(type_of(base), init));
            continue;
        }
        let Some(range) =
            base.and_then(|b| child(b, "subrangeSigned").or_else(|| child(b, "subrangeUnsigned")))
        else {
            continue;
        };
        let base = child(range, "baseType").and_then(|b| b.children().find(|c| c.is_element()));
        let base = base.map(|b| b.tag_name().name().to_string()).unwrap_or_default();
        let limit = |a: &str| {
            child(range, "range")
                .and_then(|r| r.attribute(a))
                .and_then(|v| v.trim().parse::<i64>().ok())
        };
        let (Some(lo), Some(hi)) = (limit("lower"), limit("upper")) else { continue };
        let fits = crate::program::library::int_type(&base)
            .filter(|_| !matches!(base.as_str(), "BYTE" | "WORD" | "DWORD"))
            .is_some_and(|t| t.min() <= lo && lo <= hi && hi <= t.max());
        if fits {
            out.insert(name.to_ascii_uppercase(), UserType::Subrange(base, lo, hi, init));
        }
    }
    out
}

/// A variable of a user type takes the type it names (through other names of it), and
/// starts at the type's initial value when it gives none (matiec's `__INIT_VAR`); of a
/// subrange type, its base type and limits, and else the lower limit.
fn resolve_type(v: &mut Var, types: &BTreeMap<String, UserType>) {
    for _ in 0..MAX_ALIASES {
        let Ty::Derived(name) = &v.ty else { return };
        match types.get(&name.to_ascii_uppercase()) {
            Some(UserType::Subrange(base, lo, hi, init)) => {
                v.ty = Ty::Other(base.clone());
                v.range = Some((*lo, *hi));
                if v.init.is_none() {
                    v.init = Some(init.clone().unwrap_or_else(|| lo.to_string()));
                }
                return;
            }
            Some(UserType::Alias(ty, init)) => {
                v.ty = ty.clone();
                if v.init.is_none() {
                    v.init = init.clone();
                }
            }
            None => return,
        }
    }
}

fn pou_instance(r: &mut Reader, i: Node) -> (String, String, Span) {
    let name = i.attribute("name").unwrap_or_default().to_string();
    // 1.0 writes the POU name in `type`.
    let ty =
        i.attribute("typeName").or_else(|| i.attribute("type")).unwrap_or_default().to_string();
    (name, ty, r.tag(i))
}

pub use crate::iec::literal::parse_duration;

/// The text of a textual body or condition `content` (`ST`, `IL`): its text nodes
/// (usually one, in `xhtml:p`, often CDATA; whitespace between the tags is no part of
/// it), decoded, with where it stands in `text` when it stands there as it is.
pub(super) fn text_of_body(text: &str, content: Node) -> (Option<std::ops::Range<usize>>, String) {
    let nodes: Vec<Node> = content
        .descendants()
        .filter(|d| d.is_text() && d.text().is_some_and(|t| !t.trim().is_empty()))
        .collect();
    let decoded: String = nodes.iter().filter_map(|d| d.text()).collect();
    let raw = match nodes.as_slice() {
        [one] => {
            let r = one.range();
            let raw = text.get(r.clone()).unwrap_or("");
            raw.find(decoded.as_str())
                .filter(|_| !decoded.is_empty())
                .map(|k| r.start + k..r.start + k + decoded.len())
        }
        _ => None,
    };
    (raw, decoded)
}
