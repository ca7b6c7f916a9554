//! LDmicro's bit operations (new files) as exact integer writes of the scan model: AND, OR, XOR, NOT, NEG, SHL and MOD on every target, SHR, SR0, ROL, ROR and BIN2BCD on AVR targets, from LDmicro's `avr.cpp` and `ansic.cpp`.
//!
//! `OP dest a [b]` computes in the destination's size, its operands sign-extended or cut
//! to it (`avr.cpp`, `INT_SET_VARIABLE_AND`…: `CopyArgToReg(r20, sov, a)` with `sov`
//! the destination's size), and writes the result there. AND, OR, XOR, NOT (`COM`
//! each byte) and NEG (two's complement) give the same low bytes on every target, so
//! does SHL by a literal (`a << k` in C, `k` times `LSL` on AVR: zeros in). MOD by a
//! literal that is not 0 is C's remainder (`%`), with DIV's condition (no operand
//! wider than the destination). The others differ by target, and are computed for AVR
//! targets only (`MICRO=Atmel AVR …`), `k` a literal the AVR loop runs `k` times
//! (`DEC`, `BRMI`: 0 to 127):
//!
//! * SHR: `ASR` — right, copies of the sign bit in; the C code's `>>` agrees, LDmicro's
//!   simulator too;
//! * SR0: `CLC`, `ROR` — right, zeros in (C's `>>` copies the sign);
//! * ROL / ROR: a rotation of the destination's bits (C's `rolN`/`rorN` rotate the
//!   source's size);
//! * BIN2BCD of a 1-byte source (`avr.cpp`, `INT_SET_BIN2BCD`, `bin2bcd8`; any other
//!   source size is a compile error): the source as an unsigned byte `u`, the result
//!   `(u / 10) · 16 + u % 10` — packed tens and units, where LDmicro's simulator puts a
//!   digit per byte.
//!
//! SWAP, OPPOSITE and BCD2BIN `dest src` have no AVR or PIC code that agrees with
//! LDmicro's C code (`avr.cpp` refuses BCD2BIN and OPPOSITE, swaps bytes or nibbles for
//! SWAP; `pic16.cpp` swaps nibbles; LDmicro's simulator swaps bytes, reverses the bits
//! for OPPOSITE and reads unpacked BCD). The C code (`ansic.cpp`: `dest = swap(src)`,
//! `opposite`, `bcd2bin`) calls `LIBRARIES_FOR/Arm/*/Lib_usr.c` on ARM targets (`MICRO=St
//! ARM …`, which have only the C code) and `LIBRARIES_FOR/Avr/UsrLib.c` on AVR, the
//! same functions:
//!
//! * `uint8_t bcd2bin(uint8_t var)`: `10 * (var / 16) + (var % 16)`, the source's low
//!   byte as packed BCD, the result a byte (0 to 165) — on ARM and AVR targets;
//! * `int16_t opposite(int16_t var)`: `-var`, the source cut to 16 bits, the result
//!   wrapped to 16 bits — on ARM and AVR targets;
//! * `uint16_t swap(uint16_t var)`: bit `i` of the source's low 16 bits to bit `15 - i`
//!   — on ARM targets (AVR's own code swaps bytes).
//!
//! Each result is then converted to the destination's size, as C's assignment does.

use super::sizes;
use crate::ladder::ldmicro::{Element, ElementKind, Operand, operand};
use crate::program::{BitOp, IntExpr, IntType, canonical};

/// A bit operation of LDmicro.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Op {
    Bitwise(BitOp),
    Not,
    Neg,
    Mod,
    Shl,
    Shr,
    Sr0,
    Rol,
    Ror,
    Bin2Bcd,
    Bcd2Bin,
    Opposite,
    Swap,
}

/// `OP dest a [b]`.
pub(super) struct BitElem {
    pub op: Op,
    pub keyword: String,
    pub dest: String,
    pub a: Operand,
    pub b: Option<Operand>,
}

impl BitElem {
    /// The element as a bit operation, if it is one this module knows.
    pub(super) fn of(e: &Element) -> Option<BitElem> {
        let ElementKind::Other { keyword, args } = &e.kind else { return None };
        let (op, binary) = match keyword.as_str() {
            "AND" => (Op::Bitwise(BitOp::And), true),
            "OR" => (Op::Bitwise(BitOp::Or), true),
            "XOR" => (Op::Bitwise(BitOp::Xor), true),
            "NOT" => (Op::Not, false),
            "NEG" => (Op::Neg, false),
            "MOD" => (Op::Mod, true),
            "SHL" => (Op::Shl, true),
            "SHR" => (Op::Shr, true),
            "SR0" => (Op::Sr0, true),
            "ROL" => (Op::Rol, true),
            "ROR" => (Op::Ror, true),
            "BIN2BCD" => (Op::Bin2Bcd, false),
            "BCD2BIN" => (Op::Bcd2Bin, false),
            "OPPOSITE" => (Op::Opposite, false),
            "SWAP" => (Op::Swap, false),
            _ => return None,
        };
        let (dest, a, b) = match (args.as_slice(), binary) {
            ([d, a], false) => (d, operand(a), None),
            ([d, a, b], true) => (d, operand(a), Some(operand(b))),
            _ => return None,
        };
        if !matches!(operand(dest), Operand::Var(_)) {
            return None;
        }
        Some(BitElem { op, keyword: keyword.clone(), dest: dest.clone(), a, b })
    }

    /// The variables it reads and writes.
    pub(super) fn names(&self) -> Vec<String> {
        let mut v: Vec<String> = [Some(&self.a), self.b.as_ref()]
            .into_iter()
            .flatten()
            .filter_map(|o| o.var())
            .map(str::to_string)
            .collect();
        v.push(self.dest.clone());
        v
    }

    /// Why its result is not computed (None: it is), given the types of its operands
    /// and the target.
    pub(super) fn why_not(
        &self,
        ty: &dyn Fn(&Operand) -> IntType,
        micro: Option<&str>,
    ) -> Option<String> {
        let avr = micro.is_some_and(|m| m.starts_with("Atmel AVR"));
        let arm = micro.is_some_and(|m| m.starts_with("St ARM"));
        let d = ty(&Operand::Var(self.dest.clone()));
        let count = match &self.b {
            Some(Operand::Literal(k)) => Some(*k),
            _ => None,
        };
        let keyword = &self.keyword;
        match self.op {
            Op::Bitwise(_) | Op::Not | Op::Neg => None,
            Op::Bcd2Bin | Op::Opposite if arm || avr => None,
            Op::Swap if arm => None,
            Op::Swap => Some(format!(
                "it is written by SWAP, which LDmicro's targets compute differently (its C \
                 library reverses the low 16 bits, its AVR, PIC and simulator code swap bytes \
                 or nibbles), and the target {} is not ARM",
                micro.unwrap_or("(none)")
            )),
            Op::Bcd2Bin | Op::Opposite => Some(format!(
                "it is written by {keyword}, which LDmicro's targets compute differently (its C \
                 library, which ARM and AVR targets run, its PIC code and its simulator \
                 disagree), and the target {} is neither ARM nor AVR",
                micro.unwrap_or("(none)")
            )),
            Op::Mod => match count {
                Some(k)
                    if k != 0
                        && ty(&self.a).bits <= d.bits
                        && sizes::literal_type(k).bits <= d.bits =>
                {
                    None
                }
                _ => Some(format!(
                    "it is written by a MOD by {}, not a literal other than 0 and no wider than \
                     it (a remainder by 0 is undefined; a wider one LDmicro's AVR code cuts \
                     before dividing and its C code after)",
                    self.b.as_ref().map_or("?".to_string(), show)
                )),
            },
            _ if self.op != Op::Shl && self.op != Op::Bin2Bcd && !avr => Some(format!(
                "it is written by {keyword}, which LDmicro's targets compute differently \
                 (its AVR code in the destination's size, its C code and simulator in the \
                 source's, SR0 with C's sign-copying `>>`), and the target {} is not AVR",
                micro.unwrap_or("(none)")
            )),
            Op::Bin2Bcd if !avr || ty(&self.a).bits != 8 || d.bits != 8 => Some(
                "it is written by BIN2BCD, which LDmicro's AVR code computes for a 1-byte \
                 source and destination only (packed tens and units; a wider destination \
                 gets the tens again as its high byte) and its simulator a digit per byte"
                    .to_string(),
            ),
            Op::Bin2Bcd => None,
            _ => match count {
                Some(0..=127) => None,
                _ => Some(format!(
                    "it is written by {keyword} by {}, not a literal count of 0 to 127",
                    self.b.as_ref().map_or("?".to_string(), show)
                )),
            },
        }
    }

    /// The value it writes, in the destination's type `d` (see the module's note).
    pub(super) fn value(&self, d: IntType) -> IntExpr {
        let v = |o: &Operand| match o {
            Operand::Literal(k) => IntExpr::Const(*k),
            Operand::Var(n) => IntExpr::Var(canonical(n)),
        };
        let a = v(&self.a);
        let b = || self.b.as_ref().map_or(IntExpr::Const(0), v);
        let k = match &self.b {
            Some(Operand::Literal(k)) => i32::try_from(*k).unwrap_or(0),
            _ => 0,
        };
        let unsigned = IntType::int(d.bits, false);
        let cast = |e: IntExpr, t: IntType| IntExpr::Cast(Box::new(e), t);
        let shift = |e: IntExpr, k: i32| IntExpr::Shift(Box::new(e), k);
        let w = d.bits as i32;
        match self.op {
            Op::Bitwise(op) => IntExpr::Bitwise(op, Box::new(a), Box::new(b())),
            Op::Not => IntExpr::Bitwise(BitOp::Xor, Box::new(a), Box::new(IntExpr::Const(-1))),
            Op::Neg => IntExpr::minus(IntExpr::Const(0), a),
            Op::Mod => IntExpr::Mod(Box::new(a), i64::from(k)),
            Op::Shl => shift(a, k),
            Op::Shr => shift(a, -k),
            Op::Sr0 => cast(shift(a, -k), unsigned),
            Op::Rol | Op::Ror => {
                let r = if self.op == Op::Rol { k % w } else { (w - k % w) % w };
                let rot = IntExpr::Bitwise(
                    BitOp::Or,
                    Box::new(shift(a.clone(), r)),
                    Box::new(shift(a, r - w)),
                );
                cast(rot, unsigned)
            }
            Op::Bin2Bcd => {
                // In 16 bits, the source an unsigned byte.
                let u = || cast(a.clone(), IntType::int(8, false));
                let tens = IntExpr::Mul(
                    Box::new(IntExpr::Div(Box::new(u()), 10)),
                    Box::new(IntExpr::Const(16)),
                );
                cast(IntExpr::plus(tens, IntExpr::Mod(Box::new(u()), 10)), IntType::I16)
            }
            Op::Bcd2Bin => {
                // `uint8_t bcd2bin(uint8_t var)`, in a byte.
                let byte = IntType::int(8, false);
                let u = || cast(a.clone(), byte);
                let tens = IntExpr::Mul(
                    Box::new(IntExpr::Div(Box::new(u()), 16)),
                    Box::new(IntExpr::Const(10)),
                );
                cast(IntExpr::plus(tens, IntExpr::Mod(Box::new(u()), 16)), byte)
            }
            // `int16_t opposite(int16_t var)`.
            Op::Opposite => {
                cast(IntExpr::minus(IntExpr::Const(0), cast(a, IntType::I16)), IntType::I16)
            }
            Op::Swap => {
                // `uint16_t swap(uint16_t var)`: bit i to bit 15 - i.
                let u16 = IntType::int(16, false);
                let x = cast(a, u16);
                let bit = |i: i32| {
                    let one = Box::new(IntExpr::Const(1));
                    shift(IntExpr::Bitwise(BitOp::And, Box::new(shift(x.clone(), -i)), one), 15 - i)
                };
                let rev = (1..16).fold(bit(0), |acc, i| {
                    IntExpr::Bitwise(BitOp::Or, Box::new(acc), Box::new(bit(i)))
                });
                cast(rev, u16)
            }
        }
    }
}

fn show(o: &Operand) -> String {
    match o {
        Operand::Literal(k) => k.to_string(),
        Operand::Var(n) => n.clone(),
    }
}
