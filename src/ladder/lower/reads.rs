//! LDmicro's peripheral reads in the lowering: `READ_ADC`, `UART_RECV`, the UART's status contacts, `I2C_RD` and `PERSIST`'s load from EEPROM, each a write of a named free integer input (see [`crate::ladder::readings`]).

use super::Lowering;
use crate::ladder::ldmicro::Element;
use crate::program::{BoolExpr, CmpOp, Compare, IntExpr, IntType, canonical};

impl Lowering<'_> {
    /// A peripheral read (ldmicro.md §4): when the power is on, `READ_ADC` and `I2C_RD`
    /// write the reading, a free integer input, and pass the power; `UART_RECV` writes
    /// the received value only when a byte arrived (a free 1-bit input) and gives the
    /// power and-ed with that arrival; `I2C_RD` with no target writes only when a byte
    /// arrived, and on an ARM target writes -1 when none did (`ladder::i2c_read`); a
    /// status contact gives the power and-ed with its flag.
    pub(super) fn read(&mut self, e: &Element, input: BoolExpr) -> BoolExpr {
        let index = self.element_index(e);
        let Some(r) = self.readings.get(&index).cloned() else { return input };
        let is = |name: &str, v: i64| {
            let (a, b) = (IntExpr::Var(canonical(name)), IntExpr::Const(v));
            BoolExpr::Compare(Box::new(Compare { op: CmpOp::Eq, ty: IntType::BIT, a, b }))
        };
        let power = match r.gate() {
            Some(gate) => self.temp(BoolExpr::and(input, is(gate, 1))),
            None => input,
        };
        let message = match (&r.var, &r.arrived) {
            (Some(var), Some(ready)) if r.once.is_some() => format!(
                "a peripheral read: {var} is loaded once from EEPROM, the free input {}, at \
                 the first scan its input is on and {ready} = 1 (the EEPROM ready)",
                r.value
            ),
            (None, _) => format!(
                "a peripheral read: the UART's flag is the free input {}, the output is the \
                 input and {} = 1",
                r.value, r.value
            ),
            (Some(var), None) => format!("a peripheral read: {var} is the free input {}", r.value),
            (Some(var), Some(got)) => match r.fallback {
                Some(none) => format!(
                    "a peripheral read: {var} is the free input {} when {got} = 1 (a byte \
                     arrived), else {none}",
                    r.value
                ),
                None => format!(
                    "a peripheral read: {var} is the free input {}, written when {got} = 1 (a \
                     byte arrived)",
                    r.value
                ),
            },
        };
        self.warn(e.span, e.kind.keyword(), &message);
        // PERSIST loads the variable once, at the first scan its input is on and the
        // EEPROM ready (intcode.cpp `ELEM_PERSIST`: its one-shot `isInit`).
        let write = match (&r.once, r.write_gate()) {
            (Some(once), Some(ready)) => {
                self.temp(BoolExpr::and(BoolExpr::and(power.clone(), is(once, 0)), is(ready, 1)))
            }
            (None, Some(got)) if !r.gated => self.temp(BoolExpr::and(power.clone(), is(got, 1))),
            _ => power.clone(),
        };
        let value = IntExpr::Var(canonical(&r.value));
        let value = match (r.fallback, &r.arrived) {
            (Some(none), Some(got)) => IntExpr::ite(is(got, 1), value, IntExpr::Const(none)),
            _ => value,
        };
        if let Some(var) = &r.var {
            self.set_int(e, var, &write, value);
        }
        if let Some(once) = &r.once {
            self.set_int(e, once, &write, IntExpr::Const(1));
        }
        power
    }
}
