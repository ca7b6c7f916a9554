//! Comparison atoms of properties, `[Cparts >= 10]`: each is a signal of its own, defined by an exact equation over the bits of the program's integers, so proofs cite it by the name the user wrote.
//!
//! A property's `[a op b]` resolves (through [`Scope::comparison`]) to the signal named
//! by its canonical text, recorded in the program's [`Atoms`]; before its properties are
//! checked, [`CompiledProgram::with_atoms`] adds one equation per atom, named by the
//! comparison without its brackets (`Cparts >= 10`), that states its value at every scan
//! as a Boolean function of the integers' bits ([`super::bitvec::compare`]). The equation
//! defines a name nothing else uses, so it adds no constraint on the program's runs.

use std::collections::BTreeMap;
use std::sync::{Arc, Mutex};

use super::bitvec::{self, Bits};
use super::compile::{CompiledProgram, Hypothesis, HypothesisKind, SignalKind};
use super::logic::L;
use super::{CmpOp, IntType};
use crate::diag::Span;
use crate::kernel::Rel;
use crate::syntax::IntOperand;

/// Why a timer's `ET` may be missing: where it is computed.
const ET_HELP: &str = "a timer's elapsed time is computed where the program reads it, or where \
     a property file given with the program names it (`ii-prove prog.st props.ii`; in the REPL, \
     a file whose `program \"prog.st\"` header loads the program): a timer instance called once \
     a scan with a duration literal as PT";

/// At most this many integer bounds are offered to the invariant search as candidates.
pub const BOUND_HINTS: usize = 256;

/// The comparison atoms properties have used, by signal name; the copies of one compiled
/// program share them.
#[derive(Clone, Debug, Default)]
pub struct Atoms(Arc<Mutex<BTreeMap<String, Atom>>>);

/// One comparison of integers: sides already resolved to canonical variables.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Atom {
    op: CmpOp,
    ty: IntType,
    a: IntOperand,
    b: IntOperand,
}

impl CompiledProgram {
    /// The integer variable a property names `name` (exactly, or without its LDmicro kind
    /// prefix).
    fn integer(&self, name: &str) -> Result<String, (String, Option<String>)> {
        if let Some((inst, pin)) = name.split_once('.') {
            return self.pin_integer(inst, pin);
        }
        if self.integers.contains_key(name) {
            return Ok(name.to_string());
        }
        let short: Vec<&String> = self
            .integers
            .keys()
            .filter(|x| !self.exact_names && super::short_name(x).as_deref() == Some(name))
            .collect();
        if let [one] = short.as_slice() {
            return Ok((*one).clone());
        }
        let reason = if self.signals.contains_key(name) || self.lookup_bit(name) {
            format!("`{name}` is a bit, not an integer: compare integers, or use the bit itself")
        } else {
            format!("unknown integer `{name}`")
        };
        let names: Vec<&str> = self.integers.keys().map(String::as_str).collect();
        let help = match crate::diag::did_you_mean(name, names.iter().copied()) {
            Some(s) => Some(format!("did you mean `{s}`?")),
            None if name.to_ascii_uppercase().ends_with("_ET") => Some(ET_HELP.into()),
            None if names.is_empty() => {
                Some("the program computes no integer (counters, MOVE, arithmetic)".into())
            }
            None => Some(format!("the program's integers: {}", names.join(", "))),
        };
        Err((reason, help))
    }

    /// The integer a property names `inst.pin` (`T1.ET`, `C0.CV`): the hidden integer
    /// `inst_pin` the front end computes for that pin, its case as IEC ignores it.
    fn pin_integer(&self, inst: &str, pin: &str) -> Result<String, (String, Option<String>)> {
        let wanted = format!("{inst}_{pin}");
        if self.integers.contains_key(&wanted) {
            return Ok(wanted);
        }
        // Else the one integer of that name in another case (IEC names ignore it).
        let found: Vec<&String> =
            self.integers.keys().filter(|x| x.eq_ignore_ascii_case(&wanted)).collect();
        match found.as_slice() {
            [one] => return Ok((*one).clone()),
            [_, _, ..] => {
                let names: Vec<&str> = found.iter().map(|x| x.as_str()).collect();
                return Err((
                    format!("`{inst}.{pin}` could name any of {}", names.join(", ")),
                    Some("write the integer's name as the program spells it".into()),
                ));
            }
            [] => {}
        }
        // The pins of integers the program computes (`T1.ET`, `B1.Count`; not the hidden
        // count `T1_ET_SCANS`), as a property may name them.
        let pins: Vec<String> = self
            .integers
            .keys()
            .filter(|x| !x.ends_with("_ET_SCANS"))
            .filter_map(|x| x.rsplit_once('_'))
            .filter(|(i, p)| !i.is_empty() && !p.is_empty())
            .map(|(i, p)| format!("{i}.{p}"))
            .collect();
        let asked = format!("{inst}.{pin}");
        let mine: Vec<&str> = pins
            .iter()
            .filter(|p| p.split_once('.').is_some_and(|(i, _)| i.eq_ignore_ascii_case(inst)))
            .map(String::as_str)
            .collect();
        let help = match crate::diag::did_you_mean(&asked, pins.iter().map(String::as_str)) {
            Some(s) => format!("did you mean `{s}`?"),
            None if pin.eq_ignore_ascii_case("ET") => ET_HELP.into(),
            None if mine.is_empty() => format!(
                "the program computes no integer pin of `{inst}` (a timer's ET, a counter's CV)"
            ),
            None => format!("the pins of `{inst}` the program computes: {}", mine.join(", ")),
        };
        Err((
            format!("unknown pin `{asked}`: the program computes no integer `{wanted}`"),
            Some(help),
        ))
    }

    fn lookup_bit(&self, name: &str) -> bool {
        matches!(crate::syntax::Scope::lookup(self, name), crate::syntax::Lookup::Signal(_))
    }

    /// The signal of the atom `[a op b]`, recorded for [`CompiledProgram::with_atoms`].
    pub fn comparison_atom(
        &self,
        op: CmpOp,
        a: &IntOperand,
        b: &IntOperand,
    ) -> Result<String, (String, Option<String>)> {
        type Side = (IntOperand, Option<IntType>);
        let side = |o: &IntOperand| -> Result<Side, (String, Option<String>)> {
            match o {
                IntOperand::Var(v) => {
                    let x = self.integer(v)?;
                    let ty = self.integers[&x].ty;
                    Ok((IntOperand::Var(x), Some(ty)))
                }
                IntOperand::Int(k) => Ok((IntOperand::Int(*k), None)),
                IntOperand::Time(us) => Ok((IntOperand::Time(*us), Some(IntType::TIME))),
            }
        };
        let (a, ta) = side(a)?;
        let (b, tb) = side(b)?;
        let time = |t: Option<IntType>| t.is_some_and(|t| t.time);
        let zero = |o: &IntOperand| matches!(o, IntOperand::Int(0));
        if time(ta) != time(tb) && !(tb.is_none() && zero(&b)) && !(ta.is_none() && zero(&a)) {
            let help = match (ta.or(tb), [&a, &b].iter().any(|o| matches!(o, IntOperand::Int(_)))) {
                (Some(t), true) if t.time => "write the duration as `T#2s`, `T#150ms`",
                _ => "compare a TIME with a TIME or a duration, an integer with an integer",
            };
            return Err(("this compares a TIME with an integer".into(), Some(help.into())));
        }
        if [ta, tb].iter().flatten().any(|t| t.real) {
            return Err((
                "a property compares integers only, and this one is a REAL".into(),
                Some("compare the REAL in the program (GT, LT, …) and name its BOOL result".into()),
            ));
        }
        let ty = match (ta, tb) {
            _ if time(ta) || time(tb) => IntType::TIME,
            (Some(x), Some(y)) if x == y => x,
            (Some(_), Some(_)) => IntType::int(63, true),
            (Some(t), None) | (None, Some(t)) => t,
            (None, None) => {
                return Err((
                    "this comparison has no integer variable: it is a constant".into(),
                    Some("write `1*` or `0*`".into()),
                ));
            }
        };
        for side in [&a, &b] {
            if let IntOperand::Int(k) | IntOperand::Time(k) = side
                && !ty.contains(*k)
            {
                return Err((
                    format!("{k} is not a value of {}", ty.describe()),
                    Some(format!("its values are {} to {}", ty.min(), ty.max())),
                ));
            }
        }
        let name = format!("[{a} {} {b}]", op.symbol());
        if let Ok(mut atoms) = self.atoms.0.lock() {
            atoms.insert(name.clone(), Atom { op, ty, a, b });
        }
        Ok(name)
    }

    /// This program with an equation for every comparison atom its properties have
    /// used (see the module documentation).
    pub fn with_atoms(&self) -> CompiledProgram {
        let atoms = self.atoms.0.lock().map(|a| a.clone()).unwrap_or_default();
        let mut out = self.clone();
        out.short_names = std::sync::OnceLock::new();
        out.equation_index = std::sync::OnceLock::new();
        for (name, atom) in atoms {
            if out.signals.contains_key(&name) {
                continue;
            }
            let value = |o: &IntOperand| -> Bits {
                match o {
                    IntOperand::Int(k) | IntOperand::Time(k) => bitvec::constant(*k, atom.ty.bits),
                    IntOperand::Var(x) => self.int_bits(x, atom.ty),
                }
            };
            let mut keep = |t: L| t;
            let term =
                bitvec::compare(atom.op, atom.ty, &value(&atom.a), &value(&atom.b), &mut keep);
            out.signals.insert(name.clone(), SignalKind::Atom);
            out.hypotheses.push(Hypothesis {
                name: name[1..name.len() - 1].to_string(),
                rung: 0,
                span: Span::new(0, 0..0),
                kind: HypothesisKind::Equation,
                lhs: L::var(&name).to_expr(),
                rel: Rel::Eq,
                rhs: super::logic::simp(&term).to_expr(),
            });
        }
        out
    }

    /// Whether a property has used a comparison atom this program has no equation for
    /// yet: [`CompiledProgram::with_atoms`] gives it one.
    pub fn atoms_pending(&self) -> bool {
        let Ok(atoms) = self.atoms.0.lock() else { return false };
        atoms.keys().any(|name| !self.signals.contains_key(name))
    }

    /// The value of the atom `name` when the integers have the values `int` gives (`None`
    /// for a name that is no atom, or an integer `int` does not know).
    pub fn atom_value(&self, name: &str, int: &dyn Fn(&str) -> Option<i64>) -> Option<bool> {
        let atom = self.atoms.0.lock().ok()?.get(name)?.clone();
        let value = |o: &IntOperand| match o {
            IntOperand::Int(k) | IntOperand::Time(k) => Some(*k),
            IntOperand::Var(x) => int(x),
        };
        Some(atom.ty.holds(atom.op, value(&atom.a)?, value(&atom.b)?))
    }

    /// Candidate invariants for the invariant search over scans (untrusted: it keeps only
    /// those it finds inductive, and the kernel checks what it keeps): each integer the
    /// program computes against each of the program's constants, `x <= k` and `x >= k`,
    /// as Boolean functions of the integer's bits. At most [`BOUND_HINTS`], the integers
    /// in name order.
    pub fn bound_hints(&self) -> Vec<crate::term::Expr> {
        let mut out = Vec::new();
        for (x, var) in self.integers.iter().filter(|(_, v)| !v.input) {
            let bits = self.int_bits(x, var.ty);
            for &k in self.constants.iter().filter(|k| var.ty.contains(**k)) {
                for op in [CmpOp::Le, CmpOp::Ge] {
                    if out.len() == BOUND_HINTS {
                        return out;
                    }
                    let k = bitvec::constant(k, var.ty.bits);
                    let term = bitvec::compare(op, var.ty, &bits, &k, &mut |t: L| t);
                    out.push(super::logic::simp(&term).to_expr());
                }
            }
        }
        out
    }

    /// The value of integer `x` at the end of a scan, in `ty`, from its bit signals.
    fn int_bits(&self, x: &str, ty: IntType) -> Bits {
        let Some(var) = self.integers.get(x) else { return bitvec::constant(0, ty.bits) };
        bitvec::resize(var.value(x, &mut L::var), var.ty, ty)
    }
}
