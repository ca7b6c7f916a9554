//! The reference simulator's bit operations (as LDmicro's AVR code runs them, in the destination's size) and pulse timers THI, TLO and TCY (as its `intcode.cpp` does): the elements of LDmicro ≥ 2016 that count with sizes and state.

use super::{Pow, Simulator, byte_needed, wrap_bytes};
use crate::ladder::ldmicro::{Operand, TimerKind};

impl Simulator {
    /// A bit operation `OP dest a [b]` as LDmicro's AVR code runs it (`avr.cpp`,
    /// `INT_SET_VARIABLE_AND`…: in the destination's size, operands sign-extended or cut
    /// to it; shifts and rotations `k` times for a literal `k` of 0 to 127): the
    /// destination, the value written and whether it is exact. None where the targets
    /// differ and the target is not an AVR (SHR, SR0, ROL, ROR, BIN2BCD), for BIN2BCD
    /// off 1-byte operands (`bin2bcd8`), and for MOD by 0, a variable or wider operands.
    /// SWAP, OPPOSITE and BCD2BIN as the C library of ARM and AVR targets computes them
    /// (`LIBRARIES_FOR/Arm/*/Lib_usr.c`, `LIBRARIES_FOR/Avr/UsrLib.c`; the AVR code has
    /// no BCD2BIN and OPPOSITE and swaps bytes for SWAP): BCD2BIN and OPPOSITE on ARM
    /// and AVR, SWAP on ARM; None elsewhere, where the targets differ.
    pub(super) fn bit_op(&self, keyword: &str, args: &[String]) -> Option<(String, i64, bool)> {
        let dest = args.first()?.clone();
        let size = |n: &str| match crate::ladder::ldmicro::operand(n) {
            Operand::Literal(v) => byte_needed(v),
            Operand::Var(n) => self.sizes.get(&n).copied().unwrap_or(2),
        };
        let d = size(&dest);
        let bits = 8 * d;
        let (a, a_sure) = self.value(&crate::ladder::ldmicro::operand(args.get(1)?));
        let cut = wrap_bytes(a, d);
        let unsigned = cut & ((1i64 << bits) - 1);
        let literal = || match crate::ladder::ldmicro::operand(args.get(2)?) {
            Operand::Literal(k) => Some(k),
            Operand::Var(_) => None,
        };
        let count = || literal().filter(|k| (0..=127).contains(k));
        let second = || Some(self.value(&crate::ladder::ldmicro::operand(args.get(2)?)));
        let v: i64 = match (keyword, args.len()) {
            ("AND" | "OR" | "XOR", 3) => {
                let (b, b_sure) = second()?;
                let r = match keyword {
                    "AND" => a & b,
                    "OR" => a | b,
                    _ => a ^ b,
                };
                return Some((dest.clone(), wrap_bytes(r, d), a_sure && b_sure));
            }
            ("NOT", 2) => !a,
            ("NEG", 2) => a.wrapping_neg(),
            ("SHL", 3) => {
                let k = count()?;
                if k >= 64 { 0 } else { a << k }
            }
            ("MOD", 3) => {
                let k = literal().filter(|k| *k != 0)?;
                if size(&args[1]) > d || byte_needed(k) > d {
                    return None;
                }
                cut.wrapping_rem(k)
            }
            ("SHR", 3) if self.avr => cut >> count()?.min(63),
            ("SR0", 3) if self.avr => unsigned >> count()?.min(63),
            ("ROL" | "ROR", 3) if self.avr => {
                let k = count()? % i64::from(bits);
                let r = if keyword == "ROL" { k } else { (i64::from(bits) - k) % i64::from(bits) };
                (unsigned << r) | (unsigned >> (i64::from(bits) - r))
            }
            // `uint8_t bcd2bin(uint8_t var) { return 10 * (var / 16) + (var % 16); }`
            ("BCD2BIN", 2) if self.avr || self.arm => {
                let u = a & 0xff;
                (10 * (u / 16) + u % 16) & 0xff
            }
            // `int16_t opposite(int16_t var) { return (-var); }`
            ("OPPOSITE", 2) if self.avr || self.arm => wrap_bytes(-wrap_bytes(a, 2), 2),
            // `uint16_t swap(uint16_t var)`: `if (var & (1 << i)) res |= 1 << (15 - i)`.
            ("SWAP", 2) if self.arm => {
                (0..16).filter(|i| a & (1 << i) != 0).fold(0, |res, i| res | 1 << (15 - i))
            }
            ("BIN2BCD", 2) if self.avr && d == 1 && size(&args[1]) == 1 => {
                let u = a & 0xff;
                (u / 10) * 16 + u % 10
            }
            _ => return None,
        };
        Some((dest, wrap_bytes(v, d), a_sure))
    }

    /// THI, TLO and TCY as `intcode.cpp` runs them (`ELEM_THI`, `ELEM_TLO`, `ELEM_TCY`
    /// with `NEW_TON` undefined), `k` the element's index: its output.
    pub(super) fn pulse_timer(
        &mut self,
        kind: TimerKind,
        name: &str,
        period: (i64, bool),
        i: Pow,
        k: usize,
    ) -> Pow {
        let (p, p_sure) = period;
        let names = [0, 1].map(|b| self.timer_bits.get(&(k, b)).cloned().unwrap_or_default());
        let bit = |n: &str| (self.int(n) == 1, self.is_known(n));
        let ((mut s, s_sure), (mut h, h_sure)) = (bit(&names[0]), bit(&names[1]));
        let mut t = self.int(name);
        let sure = i.sure && p_sure && s_sure && h_sure && self.is_known(name);
        let out = match kind {
            TimerKind::Thi => {
                if i.on {
                    s = true;
                }
                if s {
                    if t < p {
                        t += 1;
                        true
                    } else {
                        if !i.on {
                            t = 0;
                            s = false;
                        }
                        false
                    }
                } else {
                    false
                }
            }
            TimerKind::Tlo => {
                if !i.on {
                    if h {
                        s = true;
                    }
                } else {
                    h = true;
                }
                if s {
                    if t < p {
                        t += 1;
                        false
                    } else {
                        if i.on {
                            t = 0;
                            s = false;
                        }
                        true
                    }
                } else {
                    h || i.on
                }
            }
            _ => {
                if i.on {
                    if t < p {
                        t += 1;
                    } else {
                        t = 0;
                        s = !s;
                    }
                    s
                } else {
                    t = 0;
                    false
                }
            }
        };
        for (name, v) in names.iter().zip([s, h]).filter(|(n, _)| !n.is_empty()) {
            self.set_int(name, i64::from(v), sure);
        }
        let t = self.wrap(name, t);
        self.set_int(name, t, sure);
        Pow { on: out, sure }
    }
}
