//! Integer elements of PLCopen LD/FBD bodies, as read from the XML: which blocks compute integers (comparisons, arithmetic, MIN/MAX/LIMIT/ABS, conversions, integer MOVE/SEL, counters), the integer type of a declared variable, and which wires carry integers.

use super::{ObjKind, PinIn, PlcProgram, Source, Ty};
use crate::iec::literal::int_literal;
use crate::program::CmpOp;

/// An arithmetic block.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Arith {
    /// `ADD` (extensible).
    Add,
    /// `SUB`.
    Sub,
    /// `MUL` (extensible).
    Mul,
    /// `DIV`.
    Div,
    /// `MOD`.
    Mod,
}

/// A standard block over integers.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum IntBlock {
    /// `GT`, `GE`, `EQ`, `NE`, `LT`, `LE` (extensible): a BOOL `OUT`.
    Compare(CmpOp),
    /// `ADD`, `SUB`, `MUL`, `DIV`, `MOD`.
    Arith(Arith),
    /// `MIN` (extensible).
    Min,
    /// `MAX` (extensible).
    Max,
    /// `LIMIT(MN, IN, MX)`.
    Limit,
    /// `ABS`.
    Abs,
    /// `MOVE` of an integer.
    Move,
    /// `SEL(G, IN0, IN1)` of integers.
    Sel,
    /// `MUX(K, IN0, IN1, …)` of integers (`K` an integer of its own type).
    Mux,
    /// `FROM_TO_TO` between two integer types (upper-case names).
    Convert(String, String),
    /// `CTU`, `CTD`, `CTUD` and their typed variants (the type name).
    Counter(String),
}

impl IntBlock {
    /// The integer block of a `typeName` (`MOVE`/`SEL` are integer ones only when their
    /// data inputs carry integers: see [`PlcProgram::int_block`]).
    pub fn of(type_name: &str) -> Option<IntBlock> {
        let upper = type_name.to_ascii_uppercase();
        Some(match upper.as_str() {
            "GT" => IntBlock::Compare(CmpOp::Gt),
            "GE" => IntBlock::Compare(CmpOp::Ge),
            "EQ" => IntBlock::Compare(CmpOp::Eq),
            "NE" => IntBlock::Compare(CmpOp::Ne),
            "LT" => IntBlock::Compare(CmpOp::Lt),
            "LE" => IntBlock::Compare(CmpOp::Le),
            "ADD" => IntBlock::Arith(Arith::Add),
            "SUB" => IntBlock::Arith(Arith::Sub),
            "MUL" => IntBlock::Arith(Arith::Mul),
            "DIV" => IntBlock::Arith(Arith::Div),
            "MOD" => IntBlock::Arith(Arith::Mod),
            "MIN" => IntBlock::Min,
            "MAX" => IntBlock::Max,
            "LIMIT" => IntBlock::Limit,
            "ABS" => IntBlock::Abs,
            "MOVE" => IntBlock::Move,
            "SEL" => IntBlock::Sel,
            "MUX" => IntBlock::Mux,
            t if matches!(t.split('_').next(), Some("CTU" | "CTD" | "CTUD")) => {
                IntBlock::Counter(upper.clone())
            }
            t => {
                let (from, to) = t.split_once("_TO_")?;
                IntBlock::Convert(from.to_string(), to.to_string())
            }
        })
    }

    /// Whether it is a function block (an instance with state).
    pub fn is_fb(&self) -> bool {
        matches!(self, IntBlock::Counter(_))
    }

    /// Whether input `pin` is a BOOL (the others are integers): `BOOL_TO_*`'s `IN` among
    /// them.
    pub fn bool_input(&self, pin: &str) -> bool {
        match self {
            IntBlock::Counter(_) => matches!(pin, "CU" | "CD" | "R" | "LD"),
            IntBlock::Sel => pin == "G",
            IntBlock::Convert(from, _) => from == "BOOL" && pin == "IN",
            _ => false,
        }
    }

    /// Whether its `OUT` is a BOOL: a comparison's, a conversion `*_TO_BOOL`'s.
    pub fn bool_out(&self) -> bool {
        match self {
            IntBlock::Compare(_) => true,
            IntBlock::Convert(_, to) => to == "BOOL",
            _ => false,
        }
    }
}

/// What a conversion `FROM_TO_TO` reads or gives, as its type name says.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ConvType {
    /// `BOOL`: 0 or 1 as an integer, `<> 0` as a BOOL.
    Bool,
    /// An integer type matiec declares in at most 32 bits, or `REAL`
    /// ([`IntType::REAL`](crate::program::IntType::REAL)).
    Int(crate::program::IntType),
}

impl ConvType {
    /// The side of a conversion named `t` (upper case), or why ii-prove does not compute
    /// it: the reason names what the type is.
    pub fn of(t: &str) -> Result<ConvType, String> {
        if t == "BOOL" {
            return Ok(ConvType::Bool);
        }
        if let Some(ty) = crate::program::library::number_type(t) {
            return Ok(ConvType::Int(ty));
        }
        Err(match t {
            "LINT" | "ULINT" | "LWORD" => {
                format!("{t} is 64 bits wide, which ii-prove does not compute")
            }
            "LREAL" => format!(
                "{t} is a 64-bit floating-point type, wider than the 63 bits of ii-prove's \
                 numbers: ii-prove computes no {t}"
            ),
            "STRING" | "WSTRING" => {
                format!("{t} is a character string, not an integer: ii-prove computes no {t}")
            }
            "TIME" | "DATE" | "TOD" | "DT" | "TIME_OF_DAY" | "DATE_AND_TIME" => {
                format!("{t} is a time or date, not an integer: ii-prove computes no {t}")
            }
            t if t.contains("BCD") => {
                "it converts to or from BCD, which ii-prove does not compute".to_string()
            }
            // A subrange of an integer type is read as that type (`read.rs`).
            _ => format!(
                "{t} is not a type ii-prove computes: a derived type (an enumeration, a \
                 structure, an array, or a subrange of a 64-bit type or with limits outside \
                 its base type) is not modelled"
            ),
        })
    }
}

/// A conversion between an unsigned integer type and BCD, by its name's two sides: the
/// integer type's name, whether it converts to BCD, and the bit string's name where the
/// name gives it (`BCD_TO_UINT` and `UINT_TO_BCD` in Beremiz's library; matiec's typed
/// `WORD_BCD_TO_UINT` and `UINT_TO_BCD_WORD`). `None` for another conversion.
pub fn bcd_conversion<'a>(from: &'a str, to: &'a str) -> Option<(&'a str, bool, Option<&'a str>)> {
    match (from.strip_suffix("BCD"), to.strip_prefix("BCD")) {
        (_, Some("")) => Some((from, true, None)),
        (_, Some(bits)) => Some((from, true, Some(bits.strip_prefix('_')?))),
        (Some(""), None) => Some((to, false, None)),
        (Some(bits), None) => Some((to, false, Some(bits.strip_suffix('_')?))),
        (None, None) => None,
    }
}

/// The free integer input that stands for the result of a `REAL_TO_*` block whose `OUT`
/// is the hidden variable `out` where C leaves the conversion undefined.
pub fn undefined_input(out: &str) -> String {
    format!("{out}_UNDEFINED")
}

/// Whether an IEC type name (upper case) is an integer type, 64-bit ones included.
pub fn is_int_type_name(t: &str) -> bool {
    matches!(
        t,
        "SINT"
            | "INT"
            | "DINT"
            | "LINT"
            | "USINT"
            | "UINT"
            | "UDINT"
            | "ULINT"
            | "BYTE"
            | "WORD"
            | "DWORD"
            | "LWORD"
    )
}

/// Whether an IEC type name (upper case) is an integer type or `REAL`.
fn is_number_type_name(t: &str) -> bool {
    is_int_type_name(t) || t == "REAL"
}

impl PlcProgram {
    /// The declared variable named `name` (its declared name, or in an inlined body
    /// its prefixed one), if it is of an integer type or `REAL` (a number the scan model
    /// stores in the bits of an integer): the type's name (upper case).
    pub fn int_var_type(&self, name: &str) -> Option<String> {
        let v = self
            .vars
            .get(&name.to_ascii_uppercase())
            .or_else(|| self.vars.values().find(|v| v.name == name))?;
        match &v.ty {
            Ty::Other(t) if is_number_type_name(&t.to_ascii_uppercase()) => {
                Some(t.to_ascii_uppercase())
            }
            _ => None,
        }
    }

    /// The integer type of an input the outside world writes: an integer variable's, or
    /// for the latch of one the program also writes (`N0_IN`), that variable's.
    pub fn input_int_type(&self, name: &str) -> Option<String> {
        self.int_var_type(name).or_else(|| {
            let (x, _) = self.latches.iter().find(|(_, latch)| *latch == name)?;
            self.int_var_type(x)
        })
    }

    /// Whether the operand text names an integer (or a `REAL`): a literal or a
    /// variable.
    pub fn int_text(&self, text: &str) -> bool {
        int_literal(text).is_some_and(|(_, t)| t.is_none_or(|t| is_int_type_name(&t)))
            || crate::program::real::literal(text).is_some()
            || self.int_var_type(text.trim()).is_some()
    }

    /// The free integer inputs of this body's `REAL_TO_*` blocks ([`undefined_input`]),
    /// with their types' names: each block's result where C leaves it undefined.
    pub fn undefined_inputs(&self) -> Vec<(String, String)> {
        (0..self.objects().len())
            .filter_map(|k| match self.int_block(k)? {
                IntBlock::Convert(from, to) if from == "REAL" && ConvType::of(&to).is_ok() => {
                    Some((undefined_input(self.hidden_name(k, "OUT")?), to))
                }
                _ => None,
            })
            .filter(|(_, to)| !matches!(to.as_str(), "BOOL" | "REAL"))
            .collect()
    }

    /// The integer block at `k`, if it is one: its kind by type name, `MOVE` and `SEL`
    /// only when their data inputs carry integers.
    pub fn int_block(&self, k: usize) -> Option<IntBlock> {
        self.int_block_at(k, 0)
    }

    fn int_block_at(&self, k: usize, depth: usize) -> Option<IntBlock> {
        let ObjKind::Block { type_name, .. } = &self.obj(k)?.kind else { return None };
        let b = IntBlock::of(type_name)?;
        let carries = |pin: &str| self.pin(k, pin).is_some_and(|p| self.carries_int(p, depth));
        match &b {
            IntBlock::Move if !carries("IN") => None,
            IntBlock::Sel | IntBlock::Mux if !carries("IN0") && !carries("IN1") => None,
            _ => Some(b),
        }
    }

    /// Whether the value at a consumer pin is an integer (by what produces it).
    pub fn carries_int(&self, pin: &PinIn, depth: usize) -> bool {
        if depth > 64 {
            return false;
        }
        if let Some((text, _)) = &pin.expr {
            return self.int_text(text);
        }
        let [c] = pin.conns.as_slice() else { return false };
        match self.source(c) {
            Some(Source::Object(j)) => match self.obj(j).map(|o| &o.kind) {
                Some(ObjKind::InVar { expr, .. } | ObjKind::InOutVar { expr, .. }) => {
                    self.int_text(&expr.0)
                }
                Some(ObjKind::Connector { input, .. }) => self.carries_int(input, depth + 1),
                _ => false,
            },
            Some(Source::BlockOut(j, p)) => {
                let (name, _) = self.output_pin(j, p);
                match self.int_block_at(j, depth + 1) {
                    None => false,
                    Some(b) if b.bool_out() => false,
                    Some(IntBlock::Counter(_)) => name == "CV",
                    Some(_) => name == "OUT",
                }
            }
            _ => false,
        }
    }
}

impl PlcProgram {
    /// The declared type (upper case) of the variable `name` (its declared name, or in an
    /// inlined body its prefixed one), if it is declared here or in an inlined body.
    pub fn declared_type(&self, name: &str) -> Option<String> {
        match self.vars.values().find(|v| v.name == name).map(|v| &v.ty) {
            Some(Ty::Other(t) | Ty::Derived(t)) => Some(t.to_ascii_uppercase()),
            Some(Ty::Bool) => Some("BOOL".into()),
            None => self.subs.values().find_map(|sub| sub.declared_type(name)),
        }
    }

    /// Where the variable or hidden variable `name` comes from: its declaration, or the
    /// block it is an output of (in this body or an inlined one), else the POU.
    pub fn span_of_name(&self, name: &str) -> crate::diag::Span {
        if let Some(v) = self.vars.values().find(|v| v.name == name) {
            return v.span;
        }
        if let Some(((k, _), _)) = self.hidden.iter().find(|(_, h)| *h == name)
            && let Some(o) = self.obj(*k)
        {
            return o.span;
        }
        for sub in self.subs.values() {
            let s = sub.span_of_name(name);
            if s != sub.pou.span {
                return s;
            }
        }
        self.pou.span
    }
}
