//! Reader for PLCopen TC6 XML (1.0, 2.0, 2.01; `shared/formats/plcopen-xml.md`): XML text → a typed AST of POUs, variables, tasks and LD/FBD objects, every node with its [`Span`] in the file.
//!
//! The reader accepts the three namespaces (decided from the root element's own
//! namespace), a UTF-8 byte-order mark, children in any order, missing
//! positions, and the vendor deviations of §5.1 (`formalParameter` on wires from
//! rails and contacts, empty `formalParameter`). It never panics; every problem is
//! a [`PlcError`] with a span into the XML. [`select()`] checks one POU and
//! resolves its names, wires and evaluation order into a [`PlcProgram`], which the
//! lowering ([`lower()`]) and the scan simulator ([`simulate`]) both consume.

mod ast;
pub mod ints;
pub mod lower;
mod peripherals;
mod read;
mod select;
mod sfc;
pub mod simulate;
mod text;

use crate::diag::{Report, Severity, Span};

pub use ast::*;
pub use ints::IntBlock;
pub use lower::{EdgeKey, Lowered, lower};
pub use peripherals::StringSource;
pub use read::*;
pub use select::*;
pub use sfc::order_dispute as chart_order_dispute;
pub use simulate::PlcSimulator;
pub use text::{TextBlock, TextCall, prepare_text_blocks, st_program};

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

/// A PLCopen program as the reference of its lowering: its scan simulator, which also
/// shows the memory of each one-shot the lowering made.
pub struct PlcReference {
    /// The program.
    pub program: PlcProgram,
    /// What each one-shot of the lowering stands for ([`Lowered::edges`]).
    pub edges: Vec<EdgeKey>,
}
