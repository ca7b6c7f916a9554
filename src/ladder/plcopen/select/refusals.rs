//! Constructs whose meaning depends on the tool that runs the file (modifiers on
//! variables, negated edges, unconnected pins) or that the body's language does not
//! have (contacts and coils in FBD): the located refusals, each with its reason.

use super::super::*;
use super::Std;
use crate::diag::Span;

pub(super) fn fbd_only(o: &Obj) -> PlcError {
    PlcError::Unsupported {
        span: o.span,
        what: format!("a `{}` in an FBD body", o.tag()),
        reason: "contacts and coils belong to LD bodies".into(),
    }
}
/// The unconnected input pins of a block whose meaning depends on the tool: Beremiz's
/// generator leaves an unconnected pin out of the call (and drops a function none of
/// whose inputs is connected, its output then keeping its value), where the standard
/// gives the pin its default value, FALSE, and applies its modifiers to it.
pub(super) fn unconnected_pins(o: &Obj, type_name: &str, inputs: &[PinIn]) -> Vec<PlcError> {
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
pub(super) fn negated_edge(span: Span, what: &str) -> PlcError {
    PlcError::Unsupported {
        span,
        what: format!("a {what} both negated and edge-triggered"),
        reason: "Beremiz and OpenPLC apply only the negation (their generator ignores the \
                 edge then); use an R_TRIG/F_TRIG block and a NOT"
            .into(),
    }
}

/// A modifier on a variable object: its meaning depends on the tool that runs the file.
pub(super) fn variable_modifier(o: &Obj, what: &str) -> PlcError {
    PlcError::Unsupported {
        span: o.span,
        what: format!("a `{what}` modifier on an `{}`", o.tag()),
        reason: "Beremiz and OpenPLC generate code that ignores it (their generator applies \
                 modifiers only to contacts, coils and block pins) while other tools apply it; \
                 use a NOT or R_TRIG/F_TRIG block, or the modifier on the block's pin"
            .into(),
    }
}
