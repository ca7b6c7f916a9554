//! The scan model's integer types: a width and signedness, IEC `REAL` and `LREAL` as bit patterns, and `TIME` in nanoseconds; their ranges, wrapping, comparison and how a value reads.

use super::{CmpOp, real};

/// A two's-complement integer type: its width and signedness; or IEC `REAL` (IEEE 754
/// binary32), whose values are stored as their 32-bit patterns ([`IntType::REAL`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct IntType {
    /// Width in bits (1 to 63).
    pub bits: u32,
    /// Signed (two's complement) or unsigned.
    pub signed: bool,
    /// Whether the value is a `REAL`: the 32-bit pattern of an IEEE 754 binary32 number
    /// (`bits` 32, `signed` false), compared and converted as floating-point numbers,
    /// never computed with integer arithmetic.
    pub real: bool,
    /// Whether the value is an IEC `TIME`, in nanoseconds ([`IntType::TIME`]).
    pub time: bool,
}

impl IntType {
    /// A two's-complement integer type of `bits` bits.
    pub const fn int(bits: u32, signed: bool) -> IntType {
        IntType { bits, signed, real: false, time: false }
    }

    /// LDmicro's 16-bit signed integers (IEC `INT`).
    pub const I16: IntType = IntType::int(16, true);

    /// IEC `REAL`: IEEE 754 binary32, stored as its bit pattern (`2.5` is `0x4020_0000`).
    pub const REAL: IntType = IntType { bits: 32, signed: false, real: true, time: false };

    /// C's `double` (IEEE 754 binary64), in which the C matiec writes computes an
    /// operation of a `REAL` and a real literal: stored as its bit pattern (as an `i64`;
    /// `signed` so that every pattern is a value of the type). No variable has it: only
    /// the values of expressions ([`IntExpr::ToReal`] converts to and from it).
    pub const LREAL: IntType = IntType { bits: 64, signed: true, real: true, time: false };

    /// IEC `TIME`, as a signed count of nanoseconds, in its widest form. Only values
    /// that cannot leave their range are computed (literals, a timer's elapsed time,
    /// choices between them), never arithmetic, whose overflow in matiec's
    /// `{tv_sec, tv_nsec}` differs: so a value is held in the fewest bits that hold
    /// every value it takes ([`IntType::time_for`]), and two meet in the wider.
    pub const TIME: IntType = IntType { bits: 63, signed: true, real: false, time: true };

    /// The narrowest `TIME` that holds every duration from 0 to `ns` ns.
    pub fn time_for(ns: u64) -> IntType {
        let bits = (65 - ns.leading_zeros()).min(63);
        IntType { bits, ..IntType::TIME }
    }

    /// One unsigned bit (0 or 1): a peripheral's flag, a hidden one-shot.
    pub const BIT: IntType = IntType::int(1, false);

    /// The smallest value.
    pub fn min(self) -> i64 {
        if self.signed { -(1i64 << (self.bits - 1)) } else { 0 }
    }

    /// The largest value (computed wide: `(1 << 63) - 1` is the largest 63-bit one).
    pub fn max(self) -> i64 {
        let bits = if self.signed { self.bits - 1 } else { self.bits };
        ((1i128 << bits) - 1) as i64
    }

    /// Whether `v` is a value of the type.
    pub fn contains(self, v: i64) -> bool {
        (self.min()..=self.max()).contains(&v)
    }

    /// `v` reduced into the type as the runtime's arithmetic wraps it.
    pub fn wrap(self, v: i64) -> i64 {
        // In 128 bits: the 63-bit type a comparison with a wide literal uses reaches
        // `1 << 63`, out of i64.
        let m = i128::from(v) & ((1i128 << self.bits) - 1);
        let r =
            if self.signed && m > i128::from(self.max()) { m - (1i128 << self.bits) } else { m };
        r as i64
    }

    /// Whether `a op b` for two values of the type (compared as floating-point numbers
    /// for a `REAL`).
    pub fn holds(self, op: CmpOp, a: i64, b: i64) -> bool {
        match (self.real, self.bits) {
            (true, 64) => real::holds_double(op, a, b),
            (true, _) => real::holds(op, a, b),
            _ => op.holds(a, b),
        }
    }

    /// A value of the type as people read it (`2.5` for a `REAL`).
    pub fn show(self, v: i64) -> String {
        if self.time {
            return crate::syntax::print::signed_duration_ns(v);
        }
        match (self.real, self.bits) {
            (true, 64) => real::show_double(v),
            (true, _) => real::show(v),
            _ => v.to_string(),
        }
    }

    /// `INT`-style name for messages: `a 16-bit signed integer`.
    pub fn describe(self) -> String {
        if self.real {
            return "a REAL".into();
        }
        if self.time {
            return "a TIME".into();
        }
        format!("a {}-bit {} integer", self.bits, if self.signed { "signed" } else { "unsigned" })
    }
}
