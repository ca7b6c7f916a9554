//! The call of a user function block or function whose body is text: its wired inputs given to one scan of the scan model's simulator running the block's program for this instance (its state kept between scans; for a function, a copy of the simulator not yet run, so that every call starts from power-up), then every variable of the instance read back — the same reading the IEC text front end's programs are checked on.

use std::collections::BTreeMap;

use super::PlcSimulator;
use super::ints::CType;
use crate::ladder::plcopen::PinIn;
use crate::program::simulate::Simulator;
use crate::program::{Program, TimerModel};

/// A text block instance's simulator and the bits its program names.
pub(super) type Instance = (Simulator, Vec<String>);

/// The simulators of a body's text block instances, by block object.
pub(super) fn simulators(p: &crate::ladder::plcopen::PlcProgram) -> BTreeMap<usize, Instance> {
    let instance = |c: &crate::ladder::plcopen::TextCall| {
        let mut bits = crate::program::bits(&c.program.blocks);
        bits.extend(c.program.signals.iter().cloned());
        (Simulator::new(&c.program, TimerModel::Plc), bits.into_iter().collect())
    };
    p.text_calls.iter().map(|(k, c)| (*k, instance(c))).collect()
}

impl PlcSimulator {
    /// Runs the text block at `k` once: `pins` the block's input pins, `values` their
    /// Boolean values, `en` its EN (read by a program that runs under it).
    pub(super) fn text_call(
        &mut self,
        k: usize,
        pins: &[PinIn],
        values: &BTreeMap<String, bool>,
        en: bool,
    ) {
        let Some(call) = self.p.text_calls.get(&k) else { return };
        let mut given = BTreeMap::new();
        if let Some(bit) = &call.enable {
            given.insert(bit.clone(), en);
        }
        let mut ints = Vec::new();
        for pin in pins {
            let n = pin.name.to_ascii_uppercase();
            match call.inputs.get(&n) {
                Some((var, false)) => {
                    given.insert(var.clone(), values.get(&n).copied().unwrap_or(false));
                }
                Some((var, true)) => ints.push((var.clone(), pin.clone())),
                None => {}
            }
        }
        for (var, pin) in ints {
            let Some(ty) = self.p.text_calls[&k].program.integers.get(&var).map(|v| v.ty) else {
                continue;
            };
            match self.int_pin(&pin) {
                Some((x, _)) => {
                    let v = ty.wrap(x);
                    for b in 0..ty.bits {
                        given.insert(Program::int_bit(&var, b), v >> b & 1 == 1);
                    }
                }
                None => {
                    self.unknown.insert(var);
                }
            }
        }
        let Some((kept, bits)) = self.texts.get_mut(&k) else { return };
        let call = &self.p.text_calls[&k];
        // A function runs from power-up at each call: a copy of its simulator as built.
        let mut fresh = call.function.then(|| kept.clone());
        let sim = fresh.as_mut().unwrap_or(kept);
        sim.step(&given);
        for n in bits.iter() {
            self.bits.insert(n.clone(), sim.bit(n));
            if !sim.is_known(n) {
                self.unknown.insert(n.clone());
            }
        }
        for (n, v) in &call.program.integers {
            if let Some(x) = sim.int(n) {
                self.ints.insert(n.clone(), (x, CType::of_int(v.ty)));
            }
            if !sim.is_known(n) {
                self.unknown.insert(n.clone());
            }
        }
    }
}
