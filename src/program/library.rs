//! The IEC standard library's elements as matiec's C runs them, built over the scan model for every front end that has them (Structured Text, PLCopen LD/FBD): the integer types, comparisons (extensible), MIN/MAX/LIMIT/ABS, the counters CTU/CTD/CTUD and the pulse timer TP.

use super::{
    BitOp, BoolExpr, Checked, CheckedOp, CmpOp, Compare, IntExpr, IntType, Preset, Stmt, Timer,
    WriteKind,
};
use crate::diag::Span;

/// The IEC integer type `name` (upper-case) as matiec declares it in C; `None` for the
/// 64-bit types (not modelled) and every other type.
pub fn int_type(name: &str) -> Option<IntType> {
    let (bits, signed) = match name {
        "SINT" => (8, true),
        "INT" => (16, true),
        "DINT" => (32, true),
        "USINT" | "BYTE" => (8, false),
        "UINT" | "WORD" => (16, false),
        "UDINT" | "DWORD" => (32, false),
        _ => return None,
    };
    Some(IntType::int(bits, signed))
}

/// The IEC type `name` (upper-case) the scan model computes: an integer type of
/// [`int_type`], or `REAL` ([`IntType::REAL`]).
pub fn number_type(name: &str) -> Option<IntType> {
    if name == "REAL" { Some(IntType::REAL) } else { int_type(name) }
}

/// The IEC name of an integer type (or `REAL`).
pub fn type_name(t: IntType) -> &'static str {
    if t.real {
        return "REAL";
    }
    if t.time {
        return "TIME";
    }
    match (t.bits, t.signed) {
        (8, true) => "SINT",
        (16, true) => "INT",
        (32, true) => "DINT",
        (8, false) => "USINT",
        (16, false) => "UINT",
        _ => "UDINT",
    }
}

/// Where [`real_to_int`] gives its free value, as a warning says it (`unsigned`: to an
/// unsigned or bit-string type).
pub fn real_to_int_undefined(unsigned: bool) -> &'static str {
    if unsigned {
        "where its input is +inf or at least 2^63, which C leaves undefined"
    } else {
        "where its input is a NaN, ±inf or outside [-2^63, 2^63), which C leaves undefined"
    }
}

/// matiec's `REAL_TO_*` of the `REAL` `x` to an integer type (`unsigned`: an unsigned or
/// bit-string one, `__real_to_uint`/`__real_to_bit`; else `__real_to_sint`): the rounded
/// value ([`IntExpr::FromReal`]) where C defines it, else the free integer input `free`
/// (any value of the type): C leaves the conversion of a NaN or `±∞` to a signed type, of
/// `+∞` to an unsigned one, and of a number outside `[-2^63, 2^63)` to `LINT` undefined.
pub fn real_to_int(x: IntExpr, unsigned: bool, free: &str) -> IntExpr {
    let (low, end) = super::real::LINT_RANGE;
    let below_end =
        BoolExpr::negate(compare(CmpOp::Ge, IntType::REAL, x.clone(), IntExpr::Const(end)));
    let defined = if unsigned {
        below_end
    } else {
        let above_low = compare(CmpOp::Ge, IntType::REAL, x.clone(), IntExpr::Const(low));
        BoolExpr::and(above_low, below_end)
    };
    IntExpr::ite(defined, IntExpr::FromReal(Box::new(x), unsigned), IntExpr::var(free))
}

/// The `k`-th 4-bit digit of `x` (a value of an unsigned type).
fn nibble(x: &IntExpr, k: u32) -> IntExpr {
    let shifted = IntExpr::Shift(Box::new(x.clone()), -4 * k as i32);
    IntExpr::Bitwise(BitOp::And, Box::new(shifted), Box::new(IntExpr::Const(15)))
}

/// matiec's `__test_bcd` of `x`, a bit string of the unsigned type `t`
/// (`lib/C/iec_std_lib.h`: a digit above 9 makes it not BCD), negated: whether every 4-bit
/// digit of `x` is at most 9. `BCD_TO_*` is `TEST_EN_COND(…, __test_bcd(op))`: where it
/// fails, `OUT` is 0 and `ENO` FALSE.
pub fn is_bcd(x: &IntExpr, t: IntType) -> BoolExpr {
    (0..t.bits.div_ceil(4))
        .map(|k| compare(CmpOp::Le, t, nibble(x, k), IntExpr::Const(9)))
        .reduce(BoolExpr::and)
        .unwrap_or(BoolExpr::Const(true))
}

/// matiec's `BCD_TO_*` of `x`, a bit string of the unsigned type `from`, into the type of
/// the context: `(to) __bcd_to_uint(op)`, the sum of its 4-bit digits times the powers of
/// ten (computed in `from`, where it fits: 99 in 8 bits, 9999 in 16, 99999999 in 32), 0
/// where [`is_bcd`] fails.
pub fn bcd_to_uint(x: &IntExpr, from: IntType) -> IntExpr {
    let sum = (0..from.bits.div_ceil(4))
        .map(|k| {
            let digit = nibble(x, k);
            IntExpr::Mul(Box::new(digit), Box::new(IntExpr::Const(10i64.pow(k))))
        })
        .reduce(IntExpr::plus)
        .unwrap_or(IntExpr::Const(0));
    let value = IntExpr::Cast(Box::new(sum), from);
    IntExpr::ite(is_bcd(x, from), value, IntExpr::Const(0))
}

/// matiec's `*_TO_BCD` of `x`, a value of the unsigned type `t`, into a bit string of
/// the unsigned type `out` (the context's): `(to) __uint_to_bcd(op)`, the decimal digits
/// of `x` as 4-bit digits, those past `out`'s width dropped by the cast
/// (`UINT_TO_BCD(12345)` is `16#2345`). Computed in the wider of the two types.
pub fn uint_to_bcd(x: &IntExpr, t: IntType, out: IntType) -> IntExpr {
    let wide = if t.bits > out.bits { t } else { out };
    let x = IntExpr::Cast(Box::new(x.clone()), t);
    let digits = (0..out.bits / 4)
        .map(|k| {
            let quotient = IntExpr::Div(Box::new(x.clone()), 10i64.pow(k));
            let digit = IntExpr::Mod(Box::new(quotient), 10);
            IntExpr::Shift(Box::new(digit), 4 * k as i32)
        })
        .reduce(|a, b| IntExpr::Bitwise(BitOp::Or, Box::new(a), Box::new(b)))
        .unwrap_or(IntExpr::Const(0));
    IntExpr::Cast(Box::new(digits), wide)
}

/// The type of the count of a counter type (`CTU`, `CTD_DINT`, …); `None` for the
/// 64-bit ones.
pub fn counter_type(ty: &str) -> Option<IntType> {
    match ty.split_once('_') {
        None => int_type("INT"),
        Some((_, t)) => int_type(t),
    }
}

/// `a op b` in the type `t`.
pub fn compare(op: CmpOp, t: IntType, a: IntExpr, b: IntExpr) -> BoolExpr {
    BoolExpr::Compare(Box::new(Compare { op, ty: t, a, b }))
}

/// matiec's extensible comparison `GT(a, b, c, …)`: `a op b AND b op c AND …`.
pub fn compare_chain(op: CmpOp, t: IntType, args: &[IntExpr]) -> BoolExpr {
    let mut pairs = args.windows(2).map(|w| compare(op, t, w[0].clone(), w[1].clone()));
    let first = pairs.next().unwrap_or(BoolExpr::Const(true));
    pairs.fold(first, BoolExpr::and)
}

/// `MIN(…)` (`min`) or `MAX(…)` of values of `t`, as matiec's `__extrem_` folds them:
/// `op1 = op1 > tmp ? tmp : op1` (`MAX`: `op1 < tmp`), which keeps the first of equal
/// values (`MAX(-0.0, 0.0)` is `-0.0`) and a NaN met first.
pub fn extreme(min: bool, t: IntType, args: &[IntExpr]) -> IntExpr {
    let op = if min { CmpOp::Gt } else { CmpOp::Lt };
    let mut it = args.iter().cloned();
    let first = it.next().unwrap_or(IntExpr::Const(0));
    it.fold(first, |acc, x| IntExpr::ite(compare(op, t, acc.clone(), x.clone()), x, acc))
}

/// `LIMIT(mn, x, mx)` as matiec computes it: `x > mn ? x < mx ? x : mx : mn` (so `mn`
/// wins when `mn > mx`).
pub fn limit(t: IntType, mn: IntExpr, x: IntExpr, mx: IntExpr) -> IntExpr {
    let below_max = IntExpr::ite(compare(CmpOp::Lt, t, x.clone(), mx.clone()), x.clone(), mx);
    IntExpr::ite(compare(CmpOp::Gt, t, x, mn.clone()), below_max, mn)
}

/// matiec's check of a subrange type `t (lo..hi)` on `x`, a value of `t`
/// (`generate_c_typedecl.cc`, `__CHECK_name`): `x < lo ? lo : x > hi ? hi : x`.
pub fn subrange_check(t: IntType, x: IntExpr, lo: i64, hi: i64) -> IntExpr {
    let above = IntExpr::ite(
        compare(CmpOp::Gt, t, x.clone(), IntExpr::Const(hi)),
        IntExpr::Const(hi),
        x.clone(),
    );
    IntExpr::ite(compare(CmpOp::Lt, t, x, IntExpr::Const(lo)), IntExpr::Const(lo), above)
}

/// `ABS(x)` in the type `t`: `x < 0 ? 0 - x : x` (wrapped: `ABS` of the smallest value is
/// itself; with `undefined`, the value of that free integer there, as C leaves `-op` of
/// the least `int` undefined: [`Checked`]). For a `REAL`, C's `-op` flips the sign bit
/// (`-0.0` and a NaN are kept: `x < 0` is false for them).
pub fn abs(t: IntType, x: IntExpr, undefined: Option<String>) -> IntExpr {
    if t.real {
        let negated = IntExpr::Bitwise(
            super::BitOp::Xor,
            Box::new(x.clone()),
            Box::new(IntExpr::Const(1 << 31)),
        );
        let negative = compare(CmpOp::Lt, t, x.clone(), IntExpr::Const(0));
        return IntExpr::ite(negative, negated, x);
    }
    let negated = match undefined {
        Some(undefined) => IntExpr::Checked(Box::new(Checked {
            op: CheckedOp::Sub,
            a: IntExpr::Const(0),
            b: x.clone(),
            ty: t,
            undefined,
        })),
        None => IntExpr::minus(IntExpr::Const(0), x.clone()),
    };
    IntExpr::ite(compare(CmpOp::Lt, t, x.clone(), IntExpr::Const(0)), negated, x)
}

/// Which of matiec's timers (`lib/standard_FB.txt`) measures its elapsed time `ET`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Elapsed {
    /// `TON`: from a rising edge of `IN` while `IN` stays on; 0 when it is off.
    On,
    /// `TOF`: from a falling edge of `IN` while it stays off; 0 when it is on.
    Off,
    /// `TP`: from a rising edge while idle, to `PT`, held until `IN` is off.
    Pulse,
}

/// The elapsed time `ET` of a timer called once at every scan, as matiec computes it
/// with the runtime's clock at `k · cycle` on scan `k`: `CURRENT_TIME - START_TIME`
/// while running, `PT` once it has run out, 0 when idle. It is counted in scans: the
/// hidden count `scans` (of type `count`, 0 at first) is 0 while idle, `j + 1` on the
/// `j`-th scan after the start, and `n + 1` once the timer has run out, where `n` is
/// the first `j` with `j · cycle >= PT` (at least 1: the start's scan compares nothing).
#[derive(Clone, Debug)]
pub struct ElapsedTime<'a> {
    /// Which timer.
    pub kind: Elapsed,
    /// The hidden count's name.
    pub scans: &'a str,
    /// Its type (unsigned, wide enough for `n + 2`).
    pub count: IntType,
    /// The scans until it runs out.
    pub n: i64,
    /// The preset, in ns (as matiec's C computes its literal).
    pub pt_ns: i64,
    /// The cycle, in ns.
    pub cycle_ns: i64,
}

impl ElapsedTime<'_> {
    /// The count after a call that reads `input` (`IN`), where `before` is `IN` at the
    /// previous scan's call (FALSE before the first).
    pub fn next(&self, input: BoolExpr, before: BoolExpr) -> IntExpr {
        let t = self.count;
        let d = || IntExpr::var(self.scans);
        let k = IntExpr::Const;
        let is = |op, v| compare(op, t, d(), k(v));
        let step = IntExpr::ite(is(CmpOp::Ge, self.n + 1), k(self.n + 1), IntExpr::plus(d(), k(1)));
        match self.kind {
            // STATE 0 and IN: started (1); IN on: the next scan; IN off: 0.
            Elapsed::On => IntExpr::ite(input, step, k(0)),
            // IN on: 0; a falling edge (IN was on) or running: the next scan.
            Elapsed::Off => {
                let running = BoolExpr::Or(vec![is(CmpOp::Gt, 0), before]);
                IntExpr::ite(input, k(0), IntExpr::ite(running, step, k(0)))
            }
            // Idle: started by IN. Running: the next scan, to idle at once if it runs
            // out while IN is off. Run out: held while IN is on.
            Elapsed::Pulse => {
                let ends_off =
                    BoolExpr::and(is(CmpOp::Eq, self.n), BoolExpr::negate(input.clone()));
                let running = IntExpr::ite(ends_off, k(0), IntExpr::plus(d(), k(1)));
                let held = IntExpr::ite(input.clone(), k(self.n + 1), k(0));
                IntExpr::ite(
                    is(CmpOp::Eq, 0),
                    IntExpr::ite(input, k(1), k(0)),
                    IntExpr::ite(is(CmpOp::Le, self.n), running, held),
                )
            }
        }
    }

    /// `Q` from the count (updated by a call reading `input`): TON's is on once it has
    /// run out, TP's while it runs, TOF's while `IN` is on or it runs.
    pub fn q(&self, input: BoolExpr) -> BoolExpr {
        let (t, d, k) = (self.count, || IntExpr::var(self.scans), IntExpr::Const);
        let running =
            BoolExpr::and(compare(CmpOp::Ge, t, d(), k(1)), compare(CmpOp::Le, t, d(), k(self.n)));
        match self.kind {
            Elapsed::On => compare(CmpOp::Gt, t, d(), k(self.n)),
            Elapsed::Off => BoolExpr::Or(vec![input, running]),
            Elapsed::Pulse => running,
        }
    }

    /// `ET` (a [`IntType::TIME`]) from the count: 0, `(count - 1) · cycle`, or `PT`.
    pub fn value(&self) -> IntExpr {
        let t = self.count;
        let d = || IntExpr::Cast(Box::new(IntExpr::var(self.scans)), t);
        let k = IntExpr::Const;
        let elapsed = IntExpr::Mul(Box::new(IntExpr::minus(d(), k(1))), Box::new(k(self.cycle_ns)));
        IntExpr::ite(
            compare(CmpOp::Eq, t, IntExpr::var(self.scans), k(0)),
            k(0),
            IntExpr::ite(
                compare(CmpOp::Gt, t, IntExpr::var(self.scans), k(self.n)),
                k(self.pt_ns),
                elapsed,
            ),
        )
    }
}

/// Which counter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Counter {
    /// `CTU`: counts up, `Q := CV >= PV`.
    Up,
    /// `CTD`: counts down, `Q := CV <= 0`.
    Down,
    /// `CTUD`: both, `QU := CV >= PV`, `QD := CV <= 0`.
    UpDown,
}

impl Counter {
    /// The counter kind of a type name (`CTU`, `CTD_DINT`, …).
    pub fn of(ty: &str) -> Option<Counter> {
        match ty.split('_').next().unwrap_or(ty) {
            "CTU" => Some(Counter::Up),
            "CTD" => Some(Counter::Down),
            "CTUD" => Some(Counter::UpDown),
            _ => None,
        }
    }

    /// Its Boolean outputs.
    pub fn outputs(self) -> &'static [&'static str] {
        match self {
            Counter::UpDown => &["QU", "QD"],
            _ => &["Q"],
        }
    }
}

/// One call of a counter as matiec's `lib/counter.txt` computes it, given its count
/// `cv` (of type `t`), the preset `pv`, the rising edges `cu`/`cd` of its count inputs
/// (as their `R_TRIG`s give them) and its `r`/`ld` inputs (unused ones ignored): the
/// new count, and each Boolean output as a function of the new count.
pub fn counter(
    kind: Counter,
    t: IntType,
    cv: &str,
    pv: IntExpr,
    edges: (BoolExpr, BoolExpr),
    r: BoolExpr,
    ld: BoolExpr,
) -> (IntExpr, Vec<(&'static str, BoolExpr)>) {
    let (cu, cd) = edges;
    let cv = IntExpr::var(cv);
    let one = || IntExpr::Const(1);
    let up = IntExpr::plus(cv.clone(), one());
    let down = IntExpr::minus(cv.clone(), one());
    let below = compare(CmpOp::Lt, t, cv.clone(), pv.clone());
    let above_zero = compare(CmpOp::Gt, t, cv.clone(), IntExpr::Const(0));
    let next = match kind {
        Counter::Up => {
            let count = IntExpr::ite(BoolExpr::and(cu, below), up, cv.clone());
            IntExpr::ite(r, IntExpr::Const(0), count)
        }
        Counter::Down => {
            let count = IntExpr::ite(BoolExpr::and(cd, above_zero), down, cv.clone());
            IntExpr::ite(ld, pv.clone(), count)
        }
        Counter::UpDown => {
            // Neither counts when both rise.
            let inc = BoolExpr::and(BoolExpr::and(cu.clone(), BoolExpr::negate(cd.clone())), below);
            let dec = BoolExpr::and(BoolExpr::and(cd, BoolExpr::negate(cu)), above_zero);
            let count = IntExpr::ite(inc, up, IntExpr::ite(dec, down, cv.clone()));
            IntExpr::ite(r, IntExpr::Const(0), IntExpr::ite(ld, pv.clone(), count))
        }
    };
    let ge = compare(CmpOp::Ge, t, cv.clone(), pv);
    let le = compare(CmpOp::Le, t, cv, IntExpr::Const(0));
    let outputs = match kind {
        Counter::Up => vec![("Q", ge)],
        Counter::Down => vec![("Q", le)],
        Counter::UpDown => vec![("QU", ge), ("QD", le)],
    };
    (next, outputs)
}

/// A pulse timer `TP` as matiec's library runs it: a rising edge of `IN` while idle
/// starts a pulse of `Q` for `PT` (at least one scan), which no edge restarts; after it,
/// `Q` stays off until `IN` falls. Over `Q` (running), a hidden `DONE` bit and an
/// on-delay timer of `Q` as it stood at the previous scan; `input` and `rise` are
/// the scan-local values of `IN` and of its rising edge, `local` makes a scan-local
/// value of an expression.
pub struct Pulse<'a> {
    /// The element keyword (`TP`).
    pub keyword: &'a str,
    /// The instance (the timer's accumulator).
    pub instance: &'a str,
    /// `Q`'s bit.
    pub q: &'a str,
    /// The hidden bit that says the pulse is over and `IN` has not fallen yet.
    pub done: &'a str,
    /// `PT` in µs.
    pub pt_us: u64,
    /// The cycle in µs.
    pub cycle_us: u64,
    /// The call.
    pub span: Span,
}

impl Pulse<'_> {
    /// The statements of one call.
    pub fn call(
        &self,
        input: BoolExpr,
        rise: BoolExpr,
        local: &mut dyn FnMut(&mut Vec<Stmt>, BoolExpr) -> BoolExpr,
    ) -> Vec<Stmt> {
        let mut out = Vec::new();
        let span = self.span;
        let running = local(&mut out, BoolExpr::var(self.q));
        let finished = local(&mut out, BoolExpr::var(self.done));
        // The pulse has lasted PT when Q has been on K = ⌈PT / cycle⌉ (at least 1) scans
        // before this one: Q at the previous scan, on for K − 1 scans before.
        let scans = self.pt_us.div_ceil(self.cycle_us).max(1);
        let elapsed = if scans == 1 {
            running.clone()
        } else {
            BoolExpr::Timer(Box::new(Timer {
                on_delay: true,
                keyword: self.keyword.to_string(),
                accumulator: self.instance.to_string(),
                preset: Preset::iec(self.pt_us - self.cycle_us, self.cycle_us),
                input: running.clone(),
                span,
                called: false,
            }))
        };
        let elapsed = local(&mut out, elapsed);
        let idle =
            BoolExpr::and(BoolExpr::negate(running.clone()), BoolExpr::negate(finished.clone()));
        let start = BoolExpr::and(idle, rise);
        let keep = BoolExpr::and(running.clone(), BoolExpr::negate(elapsed.clone()));
        out.push(Stmt::Write {
            target: self.q.to_string(),
            kind: WriteKind::Assign,
            value: BoolExpr::Or(vec![start, keep]),
            span,
        });
        let ended = BoolExpr::Or(vec![finished, BoolExpr::and(running, elapsed)]);
        out.push(Stmt::Write {
            target: self.done.to_string(),
            kind: WriteKind::Assign,
            value: BoolExpr::and(ended, input),
            span,
        });
        out
    }
}
