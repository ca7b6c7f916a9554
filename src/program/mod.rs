//! The scan model: a program as the PLC runs it, one scan after another — the one representation every front end lowers into, and the only one the II compiler reads.
//!
//! A [`Program`] is a sequence of [`Block`]s (an LDmicro rung, a PLCopen statement)
//! run top to bottom once per scan. Each block is a sequence of [`Stmt`]s: scan-local
//! values ([`Stmt::Let`], the power at a point of a rung), writes of bits
//! ([`Stmt::Write`]: assignment, negated assignment, set, reset, toggle) and notes the
//! front end wants said at that place ([`Stmt::Warn`]). A read ([`BoolExpr::Var`]) sees
//! the last write before it in the scan, or the previous scan's value; timers, one-shots
//! and what the algebra cannot express are expressions of their input
//! ([`BoolExpr::Timer`], [`BoolExpr::Edge`], [`BoolExpr::Fresh`]), so that a front end
//! never has to pretend to be another language. [`compile`] turns a program into the
//! equations that hold at every scan.
#![warn(missing_docs)]

pub mod any_state;
pub mod atoms;
pub mod bitvec;
mod checked;
pub mod compile;
pub mod durations;
pub mod fast_hash;
mod int_type;
pub mod library;
pub mod logic;
pub mod names;
pub mod product;
pub mod real;
pub mod rename;
pub mod simulate;
pub mod unique;

use std::collections::{BTreeMap, BTreeSet};

use crate::diag::Span;

pub use checked::{C_INT, Checked, CheckedOp, c_operation, promoted};
pub use compile::{
    CompileError, CompileOptions, CompileWarning, CompiledProgram, EquationIndex, Hypothesis,
    HypothesisKind, SignalKind, TimerInfo, TimerModel, canonical, compile, program_to_ii,
};
pub use names::{Spellings, short_name};

/// A program as the PLC runs it.
#[derive(Clone, Debug)]
pub struct Program {
    /// The scan cycle in µs (what `pre` steps back; timers count it).
    pub cycle_us: u64,
    /// The blocks in scan order.
    pub blocks: Vec<Block>,
    /// Which bits the outside world writes.
    pub inputs: Inputs,
    /// Every bit the source names (canonical names), also in code the PLC skips.
    pub signals: BTreeSet<String>,
    /// Every name the source uses, of any kind: names the compiler makes avoid them.
    pub names: BTreeSet<String>,
    /// Bits named only in code the PLC skips (an LDmicro comment rung), with the number of
    /// the first block naming them: they keep their power-up value.
    pub skipped: Vec<(String, usize)>,
    /// Per integer variable (a timer's accumulator), how many elements other than timers
    /// write it: a timer whose accumulator something else writes does not time alone.
    pub integer_writers: BTreeMap<String, usize>,
    /// Whether names are used exactly, without LDmicro's one-letter kind prefixes being
    /// dropped for display and lookup (front ends with declared variables).
    pub exact_names: bool,
    /// What a block is called in messages (`rung`, `line`).
    pub block_noun: &'static str,
    /// The language, as `show` names it (`an LDmicro`, `a PLCopen`).
    pub language: &'static str,
    /// The integer variables the program computes exactly (canonical names): each is
    /// compiled into the bits of its two's-complement value ([`Program::int_bit`]).
    pub integers: BTreeMap<String, IntVar>,
    /// The bit the front end writes 1 at every scan to tell the first scan (start-up
    /// values keyed to it): under `--any-state` it starts at 1, as after power-up.
    pub started: Option<String>,
    /// Bits and integers the front end made itself, not declared in the source (a
    /// function block instance's pins and count, the start-up bit, guard bits, kept
    /// integers): never an output a user sees, though they are state like any other.
    pub hidden: BTreeSet<String>,
    /// Free integers standing for what the runtime leaves undefined (a signed overflow
    /// of C, a `REAL_TO_INT` of a NaN): inputs of this program alone, which no outside
    /// world writes and no other program shares.
    pub undefined: BTreeSet<String>,
}

/// An integer variable of the scan model.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct IntVar {
    /// Its type.
    pub ty: IntType,
    /// Whether the outside world writes it (an analog reading): free at every scan.
    pub input: bool,
    /// Its value at power-up (a value of `ty`).
    pub init: i64,
}

impl IntVar {
    /// Whether bit `k` of the power-up value is 1: the compiled bit `k` is the value's
    /// bit xor this, so that every compiled bit starts at 0.
    pub fn start_bit(&self, k: u32) -> bool {
        self.init >> k & 1 == 1
    }

    /// The value of the variable `x` from its compiled bits as `read` gives them (each
    /// flipped back by the start value), least significant first.
    pub fn value(&self, x: &str, read: &mut dyn FnMut(&str) -> logic::L) -> bitvec::Bits {
        (0..self.ty.bits)
            .map(|k| {
                let bit = read(&Program::int_bit(x, k));
                if self.start_bit(k) { bit.negate() } else { bit }
            })
            .collect()
    }
}

pub use int_type::IntType;

pub use crate::syntax::CmpOp;

/// An integer value at a point of the scan, in the type of the statement or comparison
/// that computes it (every operation wraps to that type, as the runtime's does).
#[derive(Clone, Debug)]
pub enum IntExpr {
    /// A literal (already a value of the type).
    Const(i64),
    /// An integer variable as it stands at this point of the scan.
    Var(String),
    /// `a + b`, wrapped.
    Add(Box<IntExpr>, Box<IntExpr>),
    /// `a - b`, wrapped.
    Sub(Box<IntExpr>, Box<IntExpr>),
    /// `a · b`, wrapped.
    Mul(Box<IntExpr>, Box<IntExpr>),
    /// `a / k` truncated toward zero, wrapped (`−min / −1` is `min`), for a literal
    /// `k` that is not 0: a division by 0 is what a runtime leaves undefined, so a front
    /// end lowers only divisions by nonzero literals here.
    Div(Box<IntExpr>, i64),
    /// `a % k` for a literal `k` that is not 0, as C computes it: the remainder of the
    /// division truncated toward zero, with the sign of `a`.
    Mod(Box<IntExpr>, i64),
    /// `a / b` for a divisor that is not a literal, as matiec's `DIV` function computes
    /// it (`lib/C/iec_std_functions.h`, `__div`): truncated toward zero, wrapped, and `0`
    /// when `b` is 0 (`TEST_EN_COND(TYPENAME, op2 == 0)` returns the type's initial
    /// value).
    DivBy(Box<IntExpr>, Box<IntExpr>),
    /// `a % b` for a divisor that is not a literal, as matiec's `MOD` function computes it
    /// (`__mod`: `if (op2 == 0) return 0; return op1 % op2;`): the sign of `a`.
    ModBy(Box<IntExpr>, Box<IntExpr>),
    /// `a` computed in the type given (every operation wraps to it), then converted into
    /// the type of the context (sign- or zero-extended, or wrapped): C's arithmetic in
    /// `int` for values narrower than 32 bits, and the `*_TO_*` conversions.
    Cast(Box<IntExpr>, IntType),
    /// `if c then a else b`.
    Ite(Box<BoolExpr>, Box<IntExpr>, Box<IntExpr>),
    /// `a & b`, `a | b` or `a ^ b`, bit by bit in the type.
    Bitwise(BitOp, Box<IntExpr>, Box<IntExpr>),
    /// `a` shifted by `k` bits within the type: left for `k > 0` (zeros in), right for
    /// `k < 0` (copies of the sign bit in a signed type, zeros in an unsigned one).
    Shift(Box<IntExpr>, i32),
    /// `a`, an integer computed in the type given, converted to a `REAL` (the context's
    /// type) as C converts an integer to `float`: the nearest number, ties to even
    /// (matiec's `*_TO_REAL`). Of a real type to the other ([`IntType::REAL`],
    /// [`IntType::LREAL`]): C's conversion of a `float` to `double` (exact) or of a
    /// `double` to `float` (the nearest, ties to even: [`real::widen`], [`real::narrow`]).
    ToReal(Box<IntExpr>, IntType),
    /// `a`, a `REAL`, converted to an integer (the context's type) as matiec's
    /// `REAL_TO_*` converts it ([`real::to_int`]: rounded to the nearest integer, ties to
    /// even, through a 64-bit `LINT`, then wrapped to the type; `true`: to an unsigned or
    /// bit-string type, where a negative number or a NaN gives 0). Where C leaves the
    /// conversion undefined the value here is 0: a front end gives the program a free
    /// value there ([`library::real_to_int`]).
    FromReal(Box<IntExpr>, bool),
    /// `a + b`, `a - b`, `a * b` or `a / b` of two `REAL`s as C computes it (IEEE 754,
    /// the nearest number, ties to even; [`RealOp`]).
    Real(RealOp, Box<IntExpr>, Box<IntExpr>),
    /// `√a` of a `REAL` (or `double`) as matiec's `SQRT` computes it: the nearest number
    /// to the root, a NaN below 0 ([`real::sqrt_in`], [`bitvec::sqrt_real`]).
    Sqrt(Box<IntExpr>),
    /// A signed operation as C computes it ([`Checked`]): exact where its result fits the
    /// signed type, a free integer's value where C leaves it undefined (an overflow);
    /// then converted to the context's type.
    Checked(Box<Checked>),
}

/// An operation of two `REAL`s.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RealOp {
    /// `a + b` (of two NaNs, `a` made quiet: [`bitvec::add_real`]).
    Add,
    /// `a - b`.
    Sub,
    /// `a * b` (of two NaNs, `a` made quiet: [`bitvec::mul_real`]).
    Mul,
    /// `a / b`, and `+0.0` when `b` is `±0.0`: matiec's `DIV` returns `__INIT_REAL` then
    /// (`TEST_EN_COND(REAL, op2 == 0)`).
    Div,
    /// `a / b` as C's `/` computes it: `±∞`, or NaN for `0.0 / 0.0`, when `b` is `±0.0`
    /// (Structured Text's `/`, which matiec writes as C's).
    Quotient,
}

impl RealOp {
    /// The operation on two stored values of the real type `ty`: `REAL`s computed with
    /// `f32`, `double`s ([`IntType::LREAL`]) with `f64`.
    pub fn apply_in(self, ty: IntType, a: i64, b: i64) -> i64 {
        if ty.bits == 64 { real::double_op(self, a, b) } else { self.apply(a, b) }
    }

    /// The operation on two stored `REAL` values, computed with `f32`.
    pub fn apply(self, a: i64, b: i64) -> i64 {
        match self {
            RealOp::Add => real::add(a, b),
            RealOp::Sub => real::sub(a, b),
            RealOp::Mul => real::mul(a, b),
            RealOp::Div => real::div(a, b),
            RealOp::Quotient => real::quotient(a, b),
        }
    }
}

/// A bitwise operation of two integers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BitOp {
    /// `&`.
    And,
    /// `|`.
    Or,
    /// `^`.
    Xor,
}

impl BitOp {
    /// The operation on two values.
    pub fn apply(self, a: i64, b: i64) -> i64 {
        match self {
            BitOp::And => a & b,
            BitOp::Or => a | b,
            BitOp::Xor => a ^ b,
        }
    }
}

/// `a` shifted by `k` bits as [`IntExpr::Shift`] says, before the wrap to the type
/// (`a` a value of a type of at most 63 bits).
pub fn shift(a: i64, k: i32) -> i64 {
    match k {
        0.. => a.checked_shl(k.unsigned_abs()).filter(|_| k < 64).unwrap_or(0),
        _ => a >> k.unsigned_abs().min(63),
    }
}

impl IntExpr {
    /// A variable read.
    pub fn var(name: &str) -> IntExpr {
        IntExpr::Var(name.to_string())
    }

    /// `a + b`.
    pub fn plus(a: IntExpr, b: IntExpr) -> IntExpr {
        IntExpr::Add(Box::new(a), Box::new(b))
    }

    /// `a - b`.
    pub fn minus(a: IntExpr, b: IntExpr) -> IntExpr {
        IntExpr::Sub(Box::new(a), Box::new(b))
    }

    /// `if c then a else b`.
    pub fn ite(c: BoolExpr, a: IntExpr, b: IntExpr) -> IntExpr {
        IntExpr::Ite(Box::new(c), Box::new(a), Box::new(b))
    }

    /// Calls `int` on every integer variable read and `boolean` on every Boolean
    /// expression (a choice's condition), operands first.
    pub fn visit(&self, int: &mut dyn FnMut(&str), boolean: &mut dyn FnMut(&BoolExpr)) {
        match self {
            IntExpr::Const(_) => {}
            IntExpr::Var(n) => int(n),
            IntExpr::Add(a, b)
            | IntExpr::Sub(a, b)
            | IntExpr::Mul(a, b)
            | IntExpr::DivBy(a, b)
            | IntExpr::ModBy(a, b)
            | IntExpr::Real(_, a, b)
            | IntExpr::Bitwise(_, a, b) => {
                a.visit(int, boolean);
                b.visit(int, boolean);
            }
            IntExpr::Div(a, _)
            | IntExpr::Mod(a, _)
            | IntExpr::Cast(a, _)
            | IntExpr::ToReal(a, _)
            | IntExpr::FromReal(a, _)
            | IntExpr::Sqrt(a)
            | IntExpr::Shift(a, _) => a.visit(int, boolean),
            IntExpr::Ite(c, a, b) => {
                walk(c, boolean);
                a.visit(int, boolean);
                b.visit(int, boolean);
            }
            IntExpr::Checked(c) => {
                c.a.visit(int, boolean);
                c.b.visit(int, boolean);
                int(&c.undefined);
            }
        }
    }
}

/// A comparison of two integers of one type.
#[derive(Clone, Debug)]
pub struct Compare {
    /// The operator.
    pub op: CmpOp,
    /// The type both sides are computed in.
    pub ty: IntType,
    /// Left side.
    pub a: IntExpr,
    /// Right side.
    pub b: IntExpr,
}

/// Which bits the outside world writes.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum Inputs {
    /// LDmicro's rule (ldmicro.md §5): names starting with `X` (input pins), `I` (Modbus
    /// discrete inputs) or `M` (Modbus coils).
    #[default]
    ByPrefix,
    /// The declared input variables.
    Declared(BTreeSet<String>),
}

impl Inputs {
    /// Whether the outside world writes `name`.
    pub fn contains(&self, name: &str) -> bool {
        match self {
            Inputs::ByPrefix => name.starts_with(['X', 'I', 'M']),
            Inputs::Declared(set) => set.contains(name),
        }
    }
}

/// One block of the scan: an LDmicro rung, a PLCopen statement.
#[derive(Clone, Debug)]
pub struct Block {
    /// Its number in the source (1-based; an LDmicro file's rungs, comments counted).
    pub number: usize,
    /// The name its equations are stated under (`L06`); `None` for a block the PLC skips.
    pub label: Option<String>,
    /// Where it is in the source.
    pub span: Span,
    /// What it does, in order.
    pub stmts: Vec<Stmt>,
}

impl Block {
    /// The label of the block that starts every scan by counting the scans since each
    /// timer called call by call started (a front end's; a caller that runs the
    /// program's blocks at a call of it runs this one at the start of its own scan).
    pub const CLOCK: &'static str = "L00_clock";

    /// Whether this is the [`Block::CLOCK`] block.
    pub fn is_clock(&self) -> bool {
        self.label.as_deref() == Some(Block::CLOCK)
    }
}

/// A scan-local value: the power at some point of a block (never a signal).
pub type Temp = usize;

/// One step of a block.
#[derive(Clone, Debug)]
pub enum Stmt {
    /// A scan-local value, computed here from what the reads see at this point.
    Let {
        /// Its index (unique in the program).
        temp: Temp,
        /// Its value.
        value: BoolExpr,
    },
    /// A write of a bit.
    Write {
        /// The bit (canonical name).
        target: String,
        /// How it is written.
        kind: WriteKind,
        /// The power of the write.
        value: BoolExpr,
        /// The element that writes (a coil, an output variable).
        span: Span,
    },
    /// A choice: the statements of the first branch whose condition holds, else
    /// `otherwise`. Conditions are read before any branch runs; no timer, one-shot or
    /// toggle runs inside a branch (its memory would update only on some scans).
    If {
        /// The conditions and their statements, in order (`IF`, then each `ELSIF`).
        branches: Vec<(BoolExpr, Vec<Stmt>)>,
        /// The `ELSE` statements.
        otherwise: Vec<Stmt>,
        /// The whole statement.
        span: Span,
    },
    /// A write of an integer variable (its type is the program's
    /// [`integers`](Program::integers) entry).
    SetInt {
        /// The variable (canonical name).
        target: String,
        /// Its new value.
        value: IntExpr,
        /// The element that writes.
        span: Span,
    },
    /// A note the front end attaches to this place (an element passed through, …).
    Warn {
        /// The element.
        span: Span,
        /// Its keyword.
        element: String,
        /// What is not modelled, and how it is read instead.
        message: String,
    },
}

/// How a bit is written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum WriteKind {
    /// `X := power`.
    Assign,
    /// `X := ¬power`.
    AssignNot,
    /// `IF power THEN X := 1`.
    Set,
    /// `IF power THEN X := 0`.
    Reset,
    /// On a rising edge of the power `X` flips (the edge over a hidden memory).
    Toggle(Box<Memory>),
}

/// The hidden memory of a one-shot: the power it saw at the previous scan, 0 at power-up.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Memory {
    /// The base of its name (`OSR_r5`).
    pub base: String,
    /// The element keyword (`OSR`, `COIL` for a toggle).
    pub element: String,
    /// The element's index in the front end's order (its scan simulator's key).
    pub index: usize,
}

/// A Boolean value at a point of the scan.
#[derive(Clone, Debug)]
pub enum BoolExpr {
    /// `1*` or `0*`.
    Const(bool),
    /// A bit as it stands at this point of the scan.
    Var(String),
    /// A scan-local value.
    Temp(Temp),
    /// Negation.
    Not(Box<BoolExpr>),
    /// Conjunction (the first operand is computed first).
    And(Box<BoolExpr>, Box<BoolExpr>),
    /// Disjunction, operands in order.
    Or(Vec<BoolExpr>),
    /// An on- or off-delay timer of its input.
    Timer(Box<Timer>),
    /// A one-shot of its input.
    Edge {
        /// Which one.
        kind: EdgeKind,
        /// The power it watches.
        input: Box<BoolExpr>,
        /// Its hidden memory.
        memory: Box<Memory>,
    },
    /// A value the algebra cannot express: an unconstrained signal, with a warning.
    Fresh(Box<Fresh>),
    /// A comparison of integers, exact: a Boolean function of their bits.
    Compare(Box<Compare>),
}

// The scan model holds one per node of every rung: a one-shot's memory is boxed so that
// the other nodes are not as large as it.
#[cfg(target_pointer_width = "64")]
const _: () = assert!(std::mem::size_of::<BoolExpr>() <= 32);

impl BoolExpr {
    /// A bit read.
    pub fn var(name: &str) -> BoolExpr {
        BoolExpr::Var(name.to_string())
    }

    /// `a · b`.
    pub fn and(a: BoolExpr, b: BoolExpr) -> BoolExpr {
        BoolExpr::And(Box::new(a), Box::new(b))
    }

    /// `¬a`.
    pub fn negate(a: BoolExpr) -> BoolExpr {
        BoolExpr::Not(Box::new(a))
    }
}

/// The one-shots.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EdgeKind {
    /// Rising: `i · ¬pre i`.
    Rising,
    /// Falling: `¬i · pre i`.
    Falling,
    /// Not rising: `¬(i · ¬pre i)` (LDmicro's ODR).
    NotRising,
}

/// A timer element.
#[derive(Clone, Debug)]
pub struct Timer {
    /// On-delay (TON) or off-delay (TOF).
    pub on_delay: bool,
    /// The element keyword (`TON`, `TOF`).
    pub keyword: String,
    /// The accumulator (the instance's name).
    pub accumulator: String,
    /// The preset.
    pub preset: Preset,
    /// Its input.
    pub input: BoolExpr,
    /// The element.
    pub span: Span,
    /// Whether it is a timer block by itself (an IEC `TON`/`TOF` call), which the
    /// runtime runs only when it is called: under a condition it times the input its last
    /// call gave it. `false` for a part of a larger element (the scans a `TP`'s pulse has
    /// lasted), which is refused under a condition.
    pub called: bool,
}

/// A timer's preset.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Preset {
    /// A literal delay: the runtime counts `P = floor(us / cycle) + adjust` scans.
    Micros {
        /// The delay, in µs.
        us: u64,
        /// The scan adjust.
        adjust: i64,
        /// When the adjust is a default of the file rather than written: which (for the
        /// warning, "the default adjust of an LDmicro0.1 file").
        default_of: Option<String>,
        /// An IEC preset of 0 (`T#0s`), counted as one cycle: a call once a scan sees the
        /// timer expire one scan after it starts, but a second call in the scan that
        /// started it sees it expired already.
        zero: bool,
    },
    /// A delay given by a variable whose value is not known to be one duration: its
    /// name, and why not where the front end knows (`Delay` is also written with T#3s).
    Variable {
        /// The variable (or the pin, `T1.PT`).
        name: String,
        /// Why its value is not one literal duration.
        why: Option<String>,
    },
}

impl Preset {
    /// An IEC TON/TOF preset of `pt_us` as matiec's time-based blocks run it on a
    /// `cycle_us` tick: the output changes at the first scan whose time is `≥ start + PT`,
    /// and never at the scan that starts the timer, so it counts `max(1, ⌈PT / cycle⌉)`
    /// scans (a preset of 0 still takes one scan: the delay of one cycle).
    pub fn iec(pt_us: u64, cycle_us: u64) -> Preset {
        if pt_us == 0 || cycle_us == 0 {
            return Preset::Micros { us: cycle_us, adjust: 0, default_of: None, zero: pt_us == 0 };
        }
        let scans = pt_us.div_ceil(cycle_us).max(1);
        let adjust = i64::try_from(scans).unwrap_or(i64::MAX)
            - i64::try_from(pt_us / cycle_us).unwrap_or(i64::MAX);
        Preset::Micros { us: pt_us, adjust, default_of: None, zero: false }
    }
}

/// A value the algebra cannot express.
#[derive(Clone, Debug)]
pub struct Fresh {
    /// The base of the unconstrained signal's name (`CTU_Cpieces`, `GEQ_r3`).
    pub base: String,
    /// The element keyword.
    pub keyword: String,
    /// Why it is not expressible.
    pub why: String,
    /// The element.
    pub span: Span,
    /// Whether it is a peripheral read: what the world outside the scan answers (a
    /// UART's transmission, a Python thread, a socket), free by nature rather than left
    /// out by ii-prove.
    pub peripheral: bool,
}

/// Calls `f` on every expression of `e` (itself included), operands first.
pub fn walk(e: &BoolExpr, f: &mut dyn FnMut(&BoolExpr)) {
    match e {
        BoolExpr::Not(x) => walk(x, f),
        BoolExpr::And(a, b) => {
            walk(a, f);
            walk(b, f);
        }
        BoolExpr::Or(xs) => xs.iter().for_each(|x| walk(x, f)),
        BoolExpr::Timer(t) => walk(&t.input, f),
        BoolExpr::Edge { input, .. } => walk(input, f),
        BoolExpr::Compare(c) => {
            for side in [&c.a, &c.b] {
                side.visit(&mut |_| {}, &mut |x| f(x));
            }
        }
        BoolExpr::Const(_) | BoolExpr::Var(_) | BoolExpr::Temp(_) | BoolExpr::Fresh(_) => {}
    }
    f(e)
}

/// [`walk`], changing each expression in place.
pub fn walk_mut(e: &mut BoolExpr, f: &mut dyn FnMut(&mut BoolExpr)) {
    match e {
        BoolExpr::Not(x) => walk_mut(x, f),
        BoolExpr::And(a, b) => {
            walk_mut(a, f);
            walk_mut(b, f);
        }
        BoolExpr::Or(xs) => xs.iter_mut().for_each(|x| walk_mut(x, f)),
        BoolExpr::Timer(t) => walk_mut(&mut t.input, f),
        BoolExpr::Edge { input, .. } => walk_mut(input, f),
        BoolExpr::Compare(c) => {
            int_walk_mut(&mut c.a, f);
            int_walk_mut(&mut c.b, f);
        }
        BoolExpr::Const(_) | BoolExpr::Var(_) | BoolExpr::Temp(_) | BoolExpr::Fresh(_) => {}
    }
    f(e)
}

/// [`walk_mut`] on every Boolean expression inside an integer expression.
pub fn int_walk_mut(e: &mut IntExpr, f: &mut dyn FnMut(&mut BoolExpr)) {
    int_visit_mut(e, &mut |_| {}, &mut |c| walk_mut(c, f));
}

/// Calls `var` on the name of every integer variable `e` reads and `boolean` on every
/// Boolean expression directly inside it (a choice's condition), operands first, each
/// changed in place.
pub fn int_visit_mut(
    e: &mut IntExpr,
    var: &mut dyn FnMut(&mut String),
    boolean: &mut dyn FnMut(&mut BoolExpr),
) {
    match e {
        IntExpr::Const(_) => {}
        IntExpr::Var(n) => var(n),
        IntExpr::Add(a, b)
        | IntExpr::Sub(a, b)
        | IntExpr::Mul(a, b)
        | IntExpr::DivBy(a, b)
        | IntExpr::ModBy(a, b)
        | IntExpr::Real(_, a, b)
        | IntExpr::Bitwise(_, a, b) => {
            int_visit_mut(a, var, boolean);
            int_visit_mut(b, var, boolean);
        }
        IntExpr::Div(a, _)
        | IntExpr::Mod(a, _)
        | IntExpr::Cast(a, _)
        | IntExpr::ToReal(a, _)
        | IntExpr::FromReal(a, _)
        | IntExpr::Sqrt(a)
        | IntExpr::Shift(a, _) => int_visit_mut(a, var, boolean),
        IntExpr::Ite(c, a, b) => {
            boolean(c);
            int_visit_mut(a, var, boolean);
            int_visit_mut(b, var, boolean);
        }
        IntExpr::Checked(c) => {
            int_visit_mut(&mut c.a, var, boolean);
            int_visit_mut(&mut c.b, var, boolean);
            var(&mut c.undefined);
        }
    }
}

impl Stmt {
    /// `IF guard THEN stmts END_IF` (no statements, or the guard `1*`: `stmts` as they are).
    pub fn guarded(guard: &BoolExpr, stmts: Vec<Stmt>, span: Span) -> Vec<Stmt> {
        if stmts.is_empty() || matches!(guard, BoolExpr::Const(true)) {
            return stmts;
        }
        vec![Stmt::If { branches: vec![(guard.clone(), stmts)], otherwise: Vec::new(), span }]
    }

    /// The expression the statement computes itself, if any (an `If`'s are its
    /// conditions and its branches': [`Stmt::visit`]).
    pub fn expr(&self) -> Option<&BoolExpr> {
        match self {
            Stmt::Let { value, .. } | Stmt::Write { value, .. } => Some(value),
            Stmt::If { .. } | Stmt::SetInt { .. } | Stmt::Warn { .. } => None,
        }
    }

    /// Calls `stmt` on this statement and every statement nested in it, and `expr` on
    /// every expression they compute (an `If`'s conditions before its branches), in
    /// scan order.
    pub fn visit(&self, stmt: &mut dyn FnMut(&Stmt), expr: &mut dyn FnMut(&BoolExpr)) {
        stmt(self);
        match self {
            Stmt::Let { value, .. } | Stmt::Write { value, .. } => walk(value, expr),
            Stmt::If { branches, otherwise, .. } => {
                for (c, _) in branches {
                    walk(c, expr);
                }
                for s in branches.iter().flat_map(|(_, b)| b).chain(otherwise) {
                    s.visit(stmt, expr);
                }
            }
            Stmt::SetInt { value, .. } => value.visit(&mut |_| {}, &mut |x| expr(x)),
            Stmt::Warn { .. } => {}
        }
    }
}

/// Every bit the blocks read or write.
pub fn bits(blocks: &[Block]) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    let mut written = BTreeSet::new();
    for s in blocks.iter().flat_map(|b| &b.stmts) {
        s.visit(
            &mut |s| {
                if let Stmt::Write { target, .. } = s {
                    written.insert(target.clone());
                }
            },
            &mut |x| {
                if let BoolExpr::Var(n) = x {
                    out.insert(n.clone());
                }
            },
        );
    }
    out.extend(written);
    out
}

impl Default for Program {
    fn default() -> Program {
        Program {
            cycle_us: 0,
            blocks: Vec::new(),
            inputs: Inputs::default(),
            signals: BTreeSet::new(),
            names: BTreeSet::new(),
            skipped: Vec::new(),
            integer_writers: BTreeMap::new(),
            exact_names: false,
            block_noun: "rung",
            language: "an LDmicro",
            integers: BTreeMap::new(),
            started: None,
            hidden: BTreeSet::new(),
            undefined: BTreeSet::new(),
        }
    }
}

impl Program {
    /// The timer accumulators written by more than one element (several timers, or a
    /// timer and an integer element): such a timer does not time alone.
    pub fn shared_timers(&self) -> BTreeSet<String> {
        let mut count: BTreeMap<String, usize> = self.integer_writers.clone();
        for (name, calls) in self.timer_calls() {
            *count.entry(name).or_default() += calls.len();
        }
        count.into_iter().filter(|(_, n)| *n > 1).map(|(t, _)| t).collect()
    }

    /// The IEC timer instances (`TON`, `TOF`) called at several places in the scan, which
    /// run call by call as the runtime runs them: every element writing the accumulator
    /// is a call of the timer block itself ([`Timer::called`]), all of one kind and one
    /// preset. Per instance, how many calls, and whether it is a TON.
    pub fn repeated_timers(&self) -> BTreeMap<String, (usize, bool)> {
        self.timer_calls()
            .into_iter()
            .filter(|(name, ts)| {
                let (on_delay, _, preset) = &ts[0];
                ts.len() > 1
                    && !self.integer_writers.contains_key(name)
                    && ts.iter().all(|(o, called, p)| *called && o == on_delay && p == preset)
            })
            .map(|(name, ts)| (name, (ts.len(), ts[0].0)))
            .collect()
    }

    /// Per timer accumulator, each element that times it, in scan order: its kind (a
    /// TON), whether it is the timer block itself ([`Timer::called`]), its preset.
    fn timer_calls(&self) -> BTreeMap<String, Vec<(bool, bool, Preset)>> {
        let mut calls: BTreeMap<String, Vec<(bool, bool, Preset)>> = BTreeMap::new();
        for (_, s) in self.stmts() {
            s.visit(&mut |_| {}, &mut |e| {
                if let BoolExpr::Timer(t) = e {
                    let call = (t.on_delay, t.called, t.preset.clone());
                    calls.entry(t.accumulator.clone()).or_default().push(call);
                }
            });
        }
        calls
    }

    /// The name of bit `k` (0 the least significant) of integer `x`: `Ccount_b3`.
    pub fn int_bit(x: &str, k: u32) -> String {
        // The second program's integer `X'` in `equiv`'s product has the bits `X_bk'`.
        match x.strip_suffix('\'') {
            Some(base) => format!("{base}_b{k}'"),
            None => format!("{x}_b{k}"),
        }
    }

    /// Every statement, block by block.
    pub fn stmts(&self) -> impl Iterator<Item = (&Block, &Stmt)> {
        self.blocks.iter().flat_map(|b| b.stmts.iter().map(move |s| (b, s)))
    }
}

#[cfg(test)]
mod tests {
    use super::IntType;

    #[test]
    fn the_widest_types_wrap_without_overflow() {
        let wide = IntType::int(63, true);
        assert_eq!(wide.max(), (1i64 << 62) - 1);
        assert_eq!(wide.wrap(65535), 65535);
        assert_eq!(wide.wrap(-1), -1);
        assert_eq!(wide.wrap(1i64 << 62), -(1i64 << 62));
        let unsigned = IntType::int(63, false);
        assert_eq!(unsigned.max(), i64::MAX);
        assert_eq!(unsigned.wrap(-1), i64::MAX);
        assert_eq!(IntType::I16.wrap(65535), -1);
        assert_eq!(IntType::I16.wrap(32768), -32768);
        assert_eq!(IntType::int(1, false).wrap(3), 1);
    }
}
