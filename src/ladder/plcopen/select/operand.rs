//! Operands: the text of a contact's, coil's, variable's or pin's expression resolved to
//! a declared variable (by name or direct address), a member of a function block
//! instance, or a literal, with "did you mean" for an unknown name.

use std::collections::{BTreeMap, BTreeSet};

use super::super::*;
use super::{Operand, PlcProgram, Std};
use crate::diag::{Span, did_you_mean};

pub(super) fn is_member(n: &str) -> bool {
    n.contains('.')
}

pub(super) fn not_bool(var: &(String, Span)) -> PlcError {
    PlcError::Unsupported {
        span: var.1,
        what: format!("the operand `{}`", var.0),
        reason: "a contact reads a BOOL variable or a Boolean output of a standard block".into(),
    }
}
impl PlcProgram {
    /// Resolves the text of an operand.
    pub(super) fn operand(
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
}
