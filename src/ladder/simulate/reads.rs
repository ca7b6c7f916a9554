//! The reference simulator's peripheral reads (ldmicro.md §4, LDmicro's `intcode.cpp` and the C code of `ansic.cpp`): READ_ADC, UART_RECV, the UART's status contacts, I2C_RD and PERSIST, each writing the free input the scan's input map gives.

use super::{Pow, Simulator};
use crate::ladder::Reading;

impl Simulator {
    /// The read `r` with input `i`: its output.
    ///
    /// * READ_ADC writes the reading and passes its input (`ELEM_READ_ADC`);
    /// * UART_RECV writes the received value only when a byte arrived, and its output is
    ///   its input and-ed with that arrival (`ELEM_UART_RECV`);
    /// * a status contact (UART_RECV_AVAIL, UART_SEND_READY and its aliases) is its
    ///   input and-ed with the UART's flag (`if (in) in = flag`);
    /// * I2C_RD (`ELEM_I2C_RD`: `if (in) { INT_I2C_READ; }`, its output its input)
    ///   writes `recv = I2C_Recv(…)`: the byte the bus gives, on an ARM target -1 when
    ///   none came (`LibI2C_ReadLast`); with no target, as LDmicro's simulator, the
    ///   typed byte only when one is queued;
    /// * PERSIST, while its input is on and its one-shot `isInit` clear, the first scan
    ///   the EEPROM is ready sets `isInit` and loads the variable from EEPROM; its
    ///   output is its input (`ELEM_PERSIST`).
    pub(super) fn read(&mut self, r: &Reading, i: Pow) -> Pow {
        let flag = |s: &Self, name: &Option<String>| name.as_ref().map(|n| s.int(n) == 1);
        let o = match &r.var {
            None => i.and(self.int(&r.value) == 1, true),
            Some(_) if r.gated => i.and(flag(self, &r.arrived) == Some(true), true),
            Some(_) => i,
        };
        let write = match (&r.once, flag(self, &r.arrived), r.fallback) {
            (Some(once), Some(ready), _) => o.and(self.int(once) == 0 && ready, true),
            (None, Some(got), None) => o.and(got, true),
            _ => o,
        };
        if let Some(var) = &r.var {
            let v = match (flag(self, &r.arrived), r.fallback) {
                (Some(false), Some(none)) => none,
                _ => self.int(&r.value),
            };
            let v = self.wrap(var, v);
            self.assign(var, write, v, true);
        }
        if let Some(once) = &r.once {
            self.assign(once, write, 1, true);
        }
        o
    }
}
