//! STRING and peripherals where a PLCopen LD/FBD body turns them into a BOOL or an integer: `STRING_TO_*` of a string literal as matiec's C converts it; of a peripheral's string (what a Python thread, a socket or a broker answers) and a peripheral's integer output stored in a variable, peripheral reads: any value of the type.

use super::Lower;
use super::ints::{IntVal, Value};
use crate::diag::Span;
use crate::iec::literal::{matiec_string_to_bool, matiec_string_to_lint};
use crate::ladder::plcopen::ints::ConvType;
use crate::ladder::plcopen::{ObjKind, PinIn, PlcProgram, StringSource};
use crate::program::{BoolExpr, IntExpr, IntType, IntVar, Stmt, library};

impl Lower<'_> {
    /// `STRING_TO_<to>` of block `k` whose `OUT` is `out`: matiec's `__string_to_bool` or
    /// `__string_to_sint` of a literal; of a peripheral's string, a free value of `to`
    /// (every value of an integer type is the conversion of its decimal digits, and
    /// `TRUE` and `FALSE` of `'TRUE'` and `'0'`), said where it is found in `stmts`.
    /// `None` where the string is neither (the block is then not computed), `Err` where
    /// it is not computed for the reason given.
    pub(super) fn string_conversion(
        &mut self,
        k: usize,
        to: &str,
        out: &str,
        stmts: &mut Vec<Stmt>,
        span: Span,
    ) -> Option<Result<Value, String>> {
        let source = self.p.string_input(k)?;
        let to = match (to, ConvType::of(to)) {
            ("BOOL", _) => None,
            (_, Ok(ConvType::Int(t))) if !t.real => Some(t),
            _ => return None,
        };
        Some(match (source, to) {
            (StringSource::Literal(body), None) => {
                Ok(Value::Bool(BoolExpr::Const(matiec_string_to_bool(&body))))
            }
            (StringSource::Literal(body), Some(t)) => match matiec_string_to_lint(&body) {
                Some(v) => Ok(Value::Int(IntExpr::Const(t.wrap(v)), t)),
                None => {
                    Err("the C that reads this literal overflows, which C leaves undefined"
                        .to_string())
                }
            },
            (StringSource::Peripheral(j, pin), None) => {
                let why = format!("a peripheral: STRING_TO_BOOL of {}", self.what(j, &pin)?);
                Ok(Value::Bool(super::free("STRING_TO_BOOL", why, span, true)))
            }
            (StringSource::Peripheral(j, pin), Some(t)) => {
                let free = PlcProgram::peripheral_conversion_input(out);
                self.ints.insert(free.clone(), IntVar { ty: t, input: true, init: 0 });
                let message = format!(
                    "a peripheral read: its OUT is the free input {free}, any {}: the conversion \
                     of {}",
                    library::type_name(t),
                    self.what(j, &pin)?
                );
                let element = format!("STRING_TO_{}", library::type_name(t));
                stmts.push(Stmt::Warn { span, element, message });
                Ok(Value::Int(IntExpr::var(&free), t))
            }
        })
    }

    /// The integer a peripheral block's output wired to `input` gives, stored in a
    /// variable of type `t`: a free input of `t`, said where it is found. `None` when
    /// `input` is not wired to a peripheral's output.
    pub(super) fn peripheral_int(
        &mut self,
        input: &PinIn,
        t: IntType,
        span: Span,
    ) -> Option<IntVal> {
        let (j, pin) = self.p.peripheral_output(input)?;
        let free = self.p.peripheral_input(j, &pin);
        self.ints.insert(free.clone(), IntVar { ty: t, input: true, init: 0 });
        let message = format!(
            "a peripheral read: the free input {free}, any {}, is {}",
            library::type_name(t),
            self.what(j, &pin)?
        );
        let element = match self.p.obj(j).map(|o| &o.kind) {
            Some(ObjKind::Block { type_name, .. }) => type_name.to_ascii_uppercase(),
            _ => "BLOCK".into(),
        };
        self.push_block(vec![Stmt::Warn { span, element, message }], span);
        Some(Ok((IntExpr::var(&free), Some(t))))
    }

    /// What output `pin` of the peripheral block `j` is: `the output RESULT of py
    /// (PYTHON_POLL): its outputs are set when …`.
    fn what(&self, j: usize, pin: &str) -> Option<String> {
        let ObjKind::Block { type_name, instance, .. } = &self.p.obj(j)?.kind else { return None };
        Some(super::peripheral_output(type_name, instance.as_deref(), pin))
    }
}
