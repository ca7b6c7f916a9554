//! LDmicro's integer sizes (new files): how many bytes each integer is stored in, and the scan model's type of that size, as LDmicro's generated code computes with it.
//!
//! LDmicro ≥ 2016 stores an integer in 1 to 4 bytes (`SizeOfVar`): the `VAR LIST` gives
//! a variable's size (2 by default), a counter with a literal start value and limit
//! gets as many as they need (`intcode.cpp`, `ELEM_CTU`…: `byteNeeded`), a timer as many
//! as its period in scans (`CalcDelay`). The generated code (`avr.cpp`: `CopyVarToReg`
//! sign-extends a narrower variable, `CopyRegToVar` keeps the low bytes; `ansic.cpp`
//! declares `SBYTE`/`SWORD`/`SDWORD`) makes every integer a signed two's-complement
//! value of its size: an operation writes its destination wrapped to the
//! destination's size, and a comparison (`INT_IF_EQU`… under `NEW_CMP`) sign-extends
//! both sides to the larger size, a literal counting the bytes `byteNeeded` gives it,
//! so it compares the values exactly. A 3-byte integer is 24 bits in the AVR and PIC
//! code but an `SDWORD` (32 bits) in the C code: it is computed only for AVR and PIC
//! targets.

use std::collections::BTreeMap;

use super::bytes_needed;
use crate::ladder::ldmicro::{Element, ElementKind, LdProgram, Operand};
use crate::program::IntType;

/// The size in bytes LDmicro gives each integer of a new file whose size is not 2: the
/// `VAR LIST`'s, then, in scan order, each counter with a literal start value and
/// limit (`byteNeeded` of both), and each timer's from `timers` (see
/// `timers::Accumulators::bytes`).
pub(super) fn sizes(
    program: &LdProgram,
    live: &[&Element],
    timers: &BTreeMap<String, u32>,
) -> BTreeMap<String, u32> {
    let mut bytes = program.var_bytes.clone();
    bytes.extend(timers.iter().map(|(n, b)| (n.clone(), *b)));
    for e in live {
        if let ElementKind::Counter {
            name,
            limit: Operand::Literal(l),
            init: Operand::Literal(i),
            ..
        } = &e.kind
        {
            bytes.insert(name.clone(), bytes_needed(*i).max(bytes_needed(*l)));
        }
    }
    bytes
}

/// The scan model's type of an integer LDmicro stores in `bytes` bytes on the target
/// `micro`; Err: why it is not computed.
pub(super) fn int_type(bytes: u32, micro: Option<&str>) -> Result<IntType, String> {
    let avr_or_pic =
        micro.is_some_and(|m| m.starts_with("Atmel AVR") || m.starts_with("Microchip PIC"));
    match bytes {
        1 | 2 | 4 => Ok(IntType::int(8 * bytes, true)),
        3 if avr_or_pic => Ok(IntType::int(24, true)),
        3 => Err(format!(
            "LDmicro stores it in 3 bytes, which its AVR and PIC code computes in 24 bits and \
             its C code in 32, and the target {} is neither AVR nor PIC",
            micro.unwrap_or("(none)")
        )),
        n => Err(format!("LDmicro stores it in {n} bytes, more than the 4 of an integer")),
    }
}

/// The type of a literal in a comparison of a new file: as many bytes as `byteNeeded`
/// gives it (`SizeOfVar` of a number).
pub(super) fn literal_type(v: i64) -> IntType {
    IntType::int(8 * bytes_needed(v), true)
}

/// The larger of two signed types: the one a comparison sign-extends both sides to.
pub(super) fn wider(a: IntType, b: IntType) -> IntType {
    IntType::int(a.bits.max(b.bits), true)
}

/// The type of an operand given the integers' types (16 bits by default): a literal's
/// as many bytes as it needs.
pub(super) fn operand_type(types: &BTreeMap<String, IntType>, o: &Operand) -> IntType {
    match o {
        Operand::Literal(v) => literal_type(*v),
        Operand::Var(n) => types.get(n).copied().unwrap_or(IntType::I16),
    }
}
