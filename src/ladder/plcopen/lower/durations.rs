//! A timer's `PT` in a graphical body: a literal duration, or a TIME variable whose every write (its initial value, each output or in-out variable object writing it, any in-out pin wired to it) gives the same literal duration, which it then holds at every read; any other variable with the reason it may change.

use super::super::{ObjKind, Operand, PinIn, PlcProgram, Source, Ty, VarClass};
use super::Lower;
use crate::program::durations::{TimeWrite, constant_value};

/// Why a timer's `PT` is not one known duration: the TIME variable it reads and why that
/// may hold another value, or `None` for a value that is not a variable's.
pub(super) type NotConstant = Option<(String, String)>;

impl Lower<'_> {
    /// The preset of the timer block at `k`, in µs, when it is one known duration.
    pub(super) fn preset(&mut self, k: usize) -> Result<u64, NotConstant> {
        let Some(pin) = self.p.pin(k, "PT") else { return Err(None) };
        if let Some((text, _)) = &pin.expr {
            return match super::super::parse_duration(text) {
                Some(us) => Ok(us),
                None => self.time_variable(text),
            };
        }
        let [c] = pin.conns.as_slice() else { return Err(None) };
        match self.p.source(c) {
            Some(Source::Object(j)) => match self.p.operands.get(&j) {
                Some(Operand::Duration(us)) => Ok(*us),
                Some(Operand::Other(text)) => self.time_variable(text),
                _ => Err(None),
            },
            Some(Source::BlockOut(j, _) | Source::BlockPin(j, _)) => {
                self.call(j);
                Err(None)
            }
            Some(Source::Rail) | None => Err(None),
        }
    }

    /// The duration the TIME variable named `text` holds at every read, or why it may
    /// hold another.
    fn time_variable(&self, text: &str) -> Result<u64, NotConstant> {
        let p = self.p;
        let Some(v) = p.vars.get(&text.trim().to_ascii_uppercase()) else { return Err(None) };
        if !matches!(&v.ty, Ty::Other(t) if t.eq_ignore_ascii_case("TIME")) {
            return Err(None);
        }
        let why = |w: &str| Err(Some((v.name.clone(), w.to_string())));
        match v.class {
            VarClass::Input | VarClass::InOut => {
                return why("it is an input, written from outside");
            }
            VarClass::External | VarClass::Global | VarClass::Access => {
                return why("it is a global variable, which other programs may write");
            }
            VarClass::Local | VarClass::Temp | VarClass::Output => {}
        }
        if let Some(a) = &v.address {
            return why(&format!("it is located at {a}, which the outside world may write"));
        }
        if v.retain {
            return why("it is retained: after a warm restart it keeps the value it had");
        }
        if p.is_input(&v.name) || p.hmi.contains_key(&v.name) {
            return why("the outside world writes it");
        }
        let init = match v.init.as_deref() {
            None => 0,
            Some(t) => match super::super::parse_duration(t) {
                Some(us) => us,
                None => return why(&format!("its initial value `{t}` is not a literal duration")),
            },
        };
        constant_value(init, &writes(p, &v.name)).or_else(|w| why(&w))
    }
}

/// Every write of the variable `name` in the body of `p`.
fn writes(p: &PlcProgram, name: &str) -> Vec<TimeWrite> {
    let names_it = |j: usize| {
        matches!(p.operands.get(&j), Some(Operand::Other(t))
            if p.vars.get(&t.trim().to_ascii_uppercase()).is_some_and(|v| v.name == name))
    };
    let mut out = Vec::new();
    for (k, o) in p.objects().iter().enumerate() {
        let at = format!("by the {} with localId {}", o.tag(), o.id);
        match &o.kind {
            ObjKind::OutVar { input, .. } | ObjKind::InOutVar { input, .. } if names_it(k) => {
                out.push(written(p, input, &at));
            }
            ObjKind::Block { inputs, .. } => {
                let wired = |pin: &&PinIn| {
                    pin.conns
                        .iter()
                        .any(|c| matches!(p.source(c), Some(Source::Object(j)) if names_it(j)))
                };
                if let Some(pin) = inputs.iter().filter(|pin| pin.in_out).find(wired) {
                    out.push(TimeWrite::Other(format!("the in-out pin {} {at}", pin.name)));
                }
            }
            _ => {}
        }
    }
    out
}

/// What the output or in-out variable object whose input is `input` writes.
fn written(p: &PlcProgram, input: &PinIn, at: &str) -> TimeWrite {
    let literal = match (&input.expr, input.conns.as_slice()) {
        (Some((text, _)), _) => super::super::parse_duration(text),
        (None, [c]) => match p.source(c) {
            Some(Source::Object(j)) => match p.operands.get(&j) {
                Some(Operand::Duration(us)) => Some(*us),
                _ => None,
            },
            _ => None,
        },
        _ => None,
    };
    match literal {
        Some(us) => TimeWrite::Literal(us, at.to_string()),
        None => TimeWrite::Other(format!("a value that is not a literal {at}")),
    }
}
