//! The PLCopen simulator's integers, evaluated concretely as matiec's C runs them (written from `iec_std_functions.h` and `lib/counter.txt`, not from the lowering): integer variables, literals on wires, the standard integer blocks and the counters.

use std::collections::BTreeMap;

use super::PlcSimulator;
use crate::iec::literal::int_literal;
use crate::ladder::plcopen::ints::{Arith, IntBlock};
use crate::ladder::plcopen::{ObjKind, PinIn, PlcProgram, Source};

/// An integer type as C declares it: width and signedness; or `float` (IEC `REAL`), whose
/// values are kept as their 32-bit patterns.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct CType {
    bits: u32,
    signed: bool,
    float: bool,
}

/// `REAL`, C's `float`.
const FLOAT: CType = CType { bits: 32, signed: false, float: true };

/// The number a kept `float` pattern stands for.
fn float(v: i128) -> f32 {
    f32::from_bits(v as u32)
}

/// The kept pattern of a `float`.
fn pattern(x: f32) -> i128 {
    i128::from(x.to_bits())
}

/// A `REAL` literal (`2.5`, `REAL#-1.0E3`) as C reads the digits matiec prints: a
/// `double`, then stored into a `float`.
fn float_literal(text: &str) -> Option<i64> {
    let t = text.trim();
    let t = t.strip_prefix("REAL#").or_else(|| t.strip_prefix("real#")).unwrap_or(t);
    if !t.contains('.') || t.contains('#') {
        return None;
    }
    let x: f64 = t.replace('_', "").parse().ok()?;
    Some(i64::from((x as f32).to_bits()))
}

/// A function of `REAL`s (`vals` their patterns), as C computes it on `float`s.
fn float_function(
    b: &IntBlock,
    vals: &[(String, i64, Option<CType>)],
    get: impl Fn(&str) -> bool,
) -> Option<Out> {
    let xs: Vec<f32> = vals.iter().map(|(_, x, _)| float((*x).into())).collect();
    let named = |pin: &str| vals.iter().position(|(n, _, _)| n == pin).map(|j| xs[j]);
    let x = match b {
        IntBlock::Compare(op) => {
            return Some(Out::Bool(xs.windows(2).all(|w| op.compares(w[0], w[1]))));
        }
        // `__extrem_`: `op1 = op1 > tmp ? tmp : op1` (MAX: `op1 < tmp`).
        IntBlock::Min => xs.iter().copied().reduce(|a, x| if a > x { x } else { a })?,
        IntBlock::Max => xs.iter().copied().reduce(|a, x| if a < x { x } else { a })?,
        IntBlock::Limit => {
            let (mn, x, mx) = (named("MN")?, named("IN")?, named("MX")?);
            if x > mn { if x < mx { x } else { mx } } else { mn }
        }
        IntBlock::Abs => {
            let x = named("IN")?;
            if x < 0.0 { -x } else { x }
        }
        IntBlock::Move => named("IN")?,
        // `__arith_expand`: `op1 = op1 + tmp` (in `double`, then rounded to `float`: the
        // same as one rounding); `SUB`: `op1 - op2`; `DIV_REAL`: `TEST_EN_COND(REAL, op2
        // == 0)` returns 0, else `op1 / op2`; NaNs as x86 gives them (`real`).
        IntBlock::Arith(op) => {
            use crate::program::real;
            let f = match op {
                Arith::Add => real::add,
                Arith::Mul => real::mul,
                Arith::Sub if xs.len() == 2 => real::sub,
                Arith::Div if xs.len() == 2 => real::div,
                _ => return None,
            };
            let bits = |x: f32| i64::from(x.to_bits());
            xs.iter().copied().reduce(|x, y| real::to_f32(f(bits(x), bits(y))))?
        }
        IntBlock::Sel => {
            if get("G") {
                named("IN1")?
            } else {
                named("IN0")?
            }
        }
        _ => return None,
    };
    Some(Out::Int(pattern(x), FLOAT))
}

impl CType {
    /// The C type matiec declares for an IEC integer type (64-bit ones not kept).
    pub(super) fn of(name: &str) -> Option<CType> {
        let (bits, signed) = match name.to_ascii_uppercase().as_str() {
            "SINT" => (8, true),
            "USINT" | "BYTE" => (8, false),
            "INT" => (16, true),
            "UINT" | "WORD" => (16, false),
            "DINT" => (32, true),
            "UDINT" | "DWORD" => (32, false),
            "REAL" => return Some(FLOAT),
            _ => return None,
        };
        Some(CType { bits, signed, float: false })
    }

    /// The C type of a scan-model integer type.
    pub(super) fn of_int(t: crate::program::IntType) -> CType {
        CType { bits: t.bits, signed: t.signed, float: t.real }
    }

    /// `v` stored into a variable of this type (C's conversion: modulo 2^bits).
    pub(super) fn store(self, v: i128) -> i64 {
        let m = v.rem_euclid(1i128 << self.bits);
        let v =
            if self.signed && m >= 1i128 << (self.bits - 1) { m - (1i128 << self.bits) } else { m };
        v as i64
    }
}

/// A value on a wire: the number and its type (`None`: a literal).
type Val = Option<(i64, Option<CType>)>;

/// What an integer function computes.
enum Out {
    /// A number, before it is stored into the result's type.
    Int(i128, CType),
    /// A number of the type that C leaves undefined (`REAL_TO_*` of a NaN, …).
    Undefined(CType),
    /// A comparison's result.
    Bool(bool),
}

/// A BCD conversion's sides (`BCD_TO_UINT`, `UINT_TO_BCD`, `WORD_BCD_TO_UINT`,
/// `UINT_TO_BCD_WORD`): whether it converts to BCD, the unsigned integer type, the bit
/// string type (where the name gives none, Beremiz's pair of the integer type's width).
fn bcd_sides(from: &str, to: &str) -> Option<(bool, CType, CType)> {
    let (uint, to_bcd, bits) = crate::ladder::plcopen::ints::bcd_conversion(from, to)?;
    let u = CType::of(uint).filter(|_| matches!(uint, "USINT" | "UINT" | "UDINT"))?;
    let b = match bits {
        Some(b) => CType::of(b).filter(|_| matches!(b, "BYTE" | "WORD" | "DWORD"))?,
        None => u,
    };
    Some((to_bcd, u, b))
}

/// The input of `BCD_TO_*`: a value of an unsigned bit string type (a literal's that of
/// the block's own bit string type), as the `LWORD` `__bcd_to_uint` and `__test_bcd` take.
fn bcd_input(x: i64, t: Option<CType>, bits: CType) -> Option<u64> {
    let t = t.unwrap_or(bits);
    (!t.signed && !t.float).then(|| t.store(i128::from(x)) as u64)
}

/// `__test_bcd` (`lib/C/iec_std_lib.h`): whether a digit of `op` is above 9.
fn test_bcd(mut op: u64) -> bool {
    while op != 0 {
        if op & 0xf > 9 {
            return true;
        }
        op >>= 4;
    }
    false
}

/// `__bcd_to_uint`: the 4-bit digits of `op` times the powers of ten.
fn bcd_to_uint(mut op: u64) -> u64 {
    let mut res = op & 0xf;
    let mut factor = 10u64;
    loop {
        op >>= 4;
        if op == 0 {
            return res;
        }
        res = res.wrapping_add((op & 0xf).wrapping_mul(factor));
        factor = factor.wrapping_mul(10);
    }
}

/// `__uint_to_bcd`: the decimal digits of `op` as 4-bit digits.
fn uint_to_bcd(mut op: u64) -> u64 {
    let mut res = op % 10;
    let mut shift = 4u32;
    loop {
        op /= 10;
        if op == 0 {
            return res;
        }
        res |= (op % 10).checked_shl(shift).unwrap_or(0);
        shift += 4;
    }
}

/// matiec's `__real_to_sint` and (`unsigned`) `__real_to_uint` / `__real_to_bit` of `x`,
/// as `lib/C/iec_std_lib.h` writes them: `x` promoted to `double`; `__preal_to_sint`:
/// `IN >= 0 ? __real_round(IN + 0.5) : __real_round(IN - 0.5)` (`__preal_to_uint`: `: 0`);
/// `__real_round(IN)`: `fmod(IN, 1) == 0 ? ((LINT)IN / 2) * 2 : (LINT)IN`. `None` where
/// the cast `(LINT)IN` is undefined in C (C11 6.3.1.4: a NaN, or an integral part that
/// LINT cannot hold).
fn real_to_lint(x: f32, unsigned: bool) -> Option<i64> {
    let v = f64::from(x);
    let lint = |v: f64| {
        let t = v.trunc();
        (t >= -(2f64.powi(63)) && t < 2f64.powi(63)).then_some(v as i64)
    };
    let round = |v: f64| {
        if v % 1.0 == 0.0 { lint(v).map(|n| n / 2 * 2) } else { lint(v) }
    };
    match v >= 0.0 {
        true => round(v + 0.5),
        false if unsigned => Some(0),
        false => round(v - 0.5),
    }
}

/// The value of the integer function `b` over its arguments, as matiec's C computes it
/// (`None`: not computed, e.g. arguments of different types).
fn function(b: &IntBlock, args: Vec<(String, Val)>, get: impl Fn(&str) -> bool) -> Option<Out> {
    // Every argument a value of the block's one type (a literal takes it).
    let vals: Vec<(String, i64, Option<CType>)> =
        args.into_iter().map(|(n, v)| v.map(|(x, t)| (n, x, t))).collect::<Option<_>>()?;
    if let IntBlock::Convert(from, to) = b
        && let Some((to_bcd, u, bits)) = bcd_sides(from, to)
    {
        let [(_, x, t)] = vals.as_slice() else { return None };
        return if to_bcd {
            // `(to) __uint_to_bcd(op)`, `op` a value of the unsigned integer type.
            let op = u.store(i128::from(*x));
            t.is_none_or(|t| t == u).then(|| Out::Int(uint_to_bcd(op as u64).into(), bits))
        } else {
            // `TEST_EN_COND(to, __test_bcd(op))`: 0; else `(to) __bcd_to_uint(op)`.
            let op = bcd_input(*x, *t, bits)?;
            Some(Out::Int(if test_bcd(op) { 0 } else { bcd_to_uint(op).into() }, u))
        };
    }
    if let IntBlock::Convert(from, to) = b {
        // `__convert_type`: `(to) __move_to(op)`, the argument a value of `from` (a BOOL
        // is 0 or 1); `__convert_num_to_bool`: `op == 0 ? 0 : 1`.
        let x: i128 = match (from.as_str(), vals.as_slice()) {
            ("BOOL", []) => get("IN").into(),
            // A `float` argument is a `REAL` (C takes no integer literal for it).
            (from, [(_, x, t)]) => match CType::of(from)? {
                ct if ct.float && t.is_none_or(|t| t == ct) => {
                    let x = float((*x).into());
                    return match to.as_str() {
                        "BOOL" => Some(Out::Bool(x != 0.0)),
                        "REAL" => Some(Out::Int(pattern(x), FLOAT)),
                        to => {
                            let target = CType::of(to)?;
                            Some(match real_to_lint(x, !target.signed) {
                                Some(v) => Out::Int(v.into(), target),
                                None => Out::Undefined(target),
                            })
                        }
                    };
                }
                ct if ct.float => return None,
                ct => ct.store((*x).into()).into(),
            },
            _ => return None,
        };
        if to == "BOOL" {
            return Some(Out::Bool(x != 0));
        }
        let ct = CType::of(to)?;
        // `(REAL)` of an integer: `as f32` rounds to nearest, ties to even, as C does.
        return Some(if ct.float { Out::Int(pattern(x as f32), ct) } else { Out::Int(x, ct) });
    }
    if *b == IntBlock::Mux {
        // `MUX__in2__in1__in2`: `TEST_EN_COND(in2, K >= param_count)` (0, see
        // `int_exec` for ENO), then the argument whose place is K, else `tmp`'s initial 0.
        let k = mux_k(&vals)?;
        let data: Vec<&(String, i64, Option<CType>)> =
            vals.iter().filter(|(n, _, _)| n != "K").collect();
        let types: Vec<CType> = data.iter().filter_map(|(_, _, t)| *t).collect();
        let &ct = types.first()?;
        if types.iter().any(|t| *t != ct) {
            return None;
        }
        let picked = data.iter().find(|(n, _, _)| *n == format!("IN{k}"));
        return Some(Out::Int(picked.map_or(0, |(_, x, _)| ct.store((*x).into()).into()), ct));
    }
    let types: Vec<CType> = vals.iter().filter_map(|(_, _, t)| *t).collect();
    let &ct = types.first()?;
    if types.iter().any(|t| *t != ct) {
        return None;
    }
    if ct.float {
        // Every argument a `REAL` (C does not take an integer literal for one here).
        return if types.len() == vals.len() { float_function(b, &vals, get) } else { None };
    }
    let xs: Vec<i128> = vals.iter().map(|(_, x, _)| i128::from(ct.store((*x).into()))).collect();
    let named = |pin: &str| vals.iter().position(|(n, _, _)| n == pin).map(|j| xs[j]).unwrap_or(0);
    // C computes `op1 OP op2` in `int` for a type of at most 32 signed bits or fewer
    // bits (integer promotion), where a result beyond `int` is undefined; in `unsigned`
    // for a 32-bit unsigned type, where it wraps.
    let in_int = ct.bits < 32 || ct.signed;
    let step = |v: i128| (!in_int || i32::try_from(v).is_ok()).then(|| i128::from(ct.store(v)));
    let undefined = || Some(Out::Undefined(ct));
    let result: i128 = match b {
        IntBlock::Compare(op) => {
            return Some(Out::Bool(xs.windows(2).all(|w| op.compares(w[0], w[1]))));
        }
        IntBlock::Arith(op @ (Arith::Add | Arith::Mul)) => {
            let (first, rest) = xs.split_first()?;
            let mut acc = *first;
            for x in rest {
                match step(if *op == Arith::Add { acc + x } else { acc * x }) {
                    Some(v) => acc = v,
                    None => return undefined(),
                }
            }
            acc
        }
        IntBlock::Arith(op) => {
            let [a, d] = xs.as_slice() else { return None };
            let v = match op {
                Arith::Sub => a - d,
                // matiec's DIV and MOD give 0 for a divisor 0.
                _ if *d == 0 => 0,
                Arith::Div => a / d,
                // `a % d` is computed by the division, which may overflow.
                _ if step(a / d).is_none() => return undefined(),
                _ => a % d,
            };
            match step(v) {
                Some(_) => v,
                None => return undefined(),
            }
        }
        IntBlock::Min => xs.iter().copied().reduce(|a, x| if a > x { x } else { a }).unwrap_or(0),
        IntBlock::Max => xs.iter().copied().reduce(|a, x| if a < x { x } else { a }).unwrap_or(0),
        IntBlock::Limit => {
            let (mn, x, mx) = (named("MN"), named("IN"), named("MX"));
            if x > mn { if x < mx { x } else { mx } } else { mn }
        }
        IntBlock::Abs => {
            let x = named("IN");
            match step(if x < 0 { -x } else { x }) {
                Some(_) => x.abs(),
                None => return undefined(),
            }
        }
        IntBlock::Move => named("IN"),
        IntBlock::Sel => {
            if get("G") {
                named("IN1")
            } else {
                named("IN0")
            }
        }
        IntBlock::Convert(..) | IntBlock::Counter(_) | IntBlock::Mux => return None,
    };
    Some(Out::Int(result, ct))
}

/// `MUX`'s `K`, as a value of its own type (a literal's as written).
fn mux_k(vals: &[(String, i64, Option<CType>)]) -> Option<i64> {
    let (_, k, kt) = vals.iter().find(|(n, _, _)| n == "K")?;
    Some(kt.map_or(*k, |t| t.store((*k).into())))
}

impl PlcSimulator {
    /// The integer variables at power-up: each at its declared value.
    pub(super) fn init_ints(p: &PlcProgram, ints: &mut BTreeMap<String, (i64, CType)>) {
        for v in p.vars.values() {
            let super::super::Ty::Other(t) = &v.ty else { continue };
            let t = t.to_ascii_uppercase();
            let Some(ct) = CType::of(t.strip_prefix("HMI_").unwrap_or(&t)) else { continue };
            let init = match v.init.as_deref() {
                Some(text) if ct.float => float_literal(text).unwrap_or(0),
                init => init.and_then(int_literal).map_or(0, |(k, _)| ct.store(k)),
            };
            ints.insert(v.name.clone(), (init, ct));
        }
        // The free inputs of `REAL_TO_*` blocks (C's undefined results).
        for (n, t) in p.undefined_inputs().into_iter().chain(p.peripheral_inputs()) {
            ints.extend(CType::of(&t).map(|ct| (n, (0, ct))));
        }
        // A counter's CV starts at 0, whether its body has run or not.
        for ((k, pin), name) in &p.hidden {
            if let (true, Some(IntBlock::Counter(ty))) = (pin == "CV", p.int_block(*k)) {
                ints.extend(counter_ctype(&ty).map(|ct| (name.clone(), (0, ct))));
            }
        }
        for sub in p.subs.values() {
            PlcSimulator::init_ints(sub, ints);
        }
        for call in p.text_calls.values() {
            for (n, v) in &call.program.integers {
                ints.insert(n.clone(), (v.init, CType::of_int(v.ty)));
            }
        }
    }

    /// An integer input takes the value its bits give (`{name}_b{k}`), when given.
    pub(super) fn read_int_inputs(&mut self, inputs: &BTreeMap<String, bool>) {
        let free: Vec<&String> = self.undefined.iter().map(|(n, _)| n).collect();
        let names: Vec<String> =
            self.ints.keys().filter(|n| self.p.is_input(n) || free.contains(n)).cloned().collect();
        for n in names {
            let (_, ct) = self.ints[&n];
            let bits: Vec<Option<&bool>> =
                (0..ct.bits).map(|k| inputs.get(&format!("{n}_b{k}"))).collect();
            if bits.iter().all(Option::is_none) {
                continue;
            }
            let raw = bits
                .iter()
                .enumerate()
                .fold(0i128, |acc, (k, b)| acc | (i128::from(b.copied().unwrap_or(false)) << k));
            self.ints.insert(n, (ct.store(raw), ct));
        }
    }

    /// An integer's value after the last scan.
    pub fn int(&self, name: &str) -> Option<i64> {
        self.ints.get(name).map(|(v, _)| *v)
    }

    fn int_text(&self, text: &str) -> Val {
        if let Some(x) = float_literal(text) {
            return Some((x, Some(FLOAT)));
        }
        if let Some((v, ty)) = int_literal(text) {
            return match ty {
                None => Some((v.clamp(i64::MIN.into(), i64::MAX.into()) as i64, None)),
                Some(t) => CType::of(&t).map(|ct| (ct.store(v), Some(ct))),
            };
        }
        let v = self.p.vars.get(&text.trim().to_ascii_uppercase())?;
        self.ints.get(&v.name).map(|(x, t)| (*x, Some(*t)))
    }

    /// `MUX(K, IN0, IN1, …)` of the BOOL inputs `values`: matiec's `MUX__BOOL__…`
    /// (`lib/C/iec_std_functions.h`) returns `IN{K}` for `0 ≤ K < param_count`, FALSE
    /// (`__INIT_BOOL`) when `K >= param_count` (`TEST_EN_COND`) or no `i` equals `K`.
    pub(super) fn bool_mux(&mut self, k: usize, values: &BTreeMap<String, bool>) -> bool {
        let Some(pin) = self.p.pin(k, "K").cloned() else { return false };
        let Some((key, _)) = self.int_pin(&pin) else { return false };
        let n = (0..).take_while(|i| values.contains_key(&format!("IN{i}"))).count() as i64;
        (0..n).contains(&key) && values.get(&format!("IN{key}")).copied().unwrap_or(false)
    }

    /// The integer at a consumer pin (its blocks called).
    pub(super) fn int_pin(&mut self, pin: &PinIn) -> Val {
        if let Some((text, _)) = &pin.expr {
            return self.int_text(text);
        }
        let [c] = pin.conns.as_slice() else { return None };
        match self.p.source(c)? {
            Source::Object(j) => match self.p.obj(j).map(|o| o.kind.clone()) {
                Some(ObjKind::InVar { expr, .. } | ObjKind::InOutVar { expr, .. }) => {
                    self.int_text(&expr.0)
                }
                Some(ObjKind::Connector { input, .. }) => {
                    if !self.visiting.insert(j) {
                        return None;
                    }
                    let v = self.int_pin(&input);
                    self.visiting.remove(&j);
                    v
                }
                _ => None,
            },
            Source::BlockOut(j, p) => {
                // Its block was called (or not, by the order) when the inputs were computed.
                // A peripheral's integer is the run's value of its free input.
                let (name, _) = self.p.output_pin(j, p);
                let h = match self.p.int_output_name(j, &name) {
                    Some(h) => h.to_string(),
                    None if self.p.peripherals.contains(&j) => self.p.peripheral_input(j, &name),
                    None => return None,
                };
                self.ints.get(&h).map(|(x, t)| (*x, Some(*t)))
            }
            _ => None,
        }
    }

    /// `target := ` the integer at `input` (an output or in-out variable).
    /// A value passed into an input of a subrange type `lo..hi`: matiec's C function
    /// `__CHECK_…` (`generate_c_typedecl.cc`) returns `lo` below it, `hi` above it.
    pub(super) fn subrange_check(&mut self, target: &str, (lo, hi): (i64, i64)) {
        if let Some((x, t)) = self.ints.get(target).copied() {
            let held = if x < lo {
                lo
            } else if x > hi {
                hi
            } else {
                x
            };
            self.ints.insert(target.to_string(), (held, t));
        }
    }

    pub(super) fn int_assign(&mut self, target: &str, input: &PinIn) {
        let v = self.int_pin(input);
        if let (Some((x, t)), Some((_, ct))) = (v, self.ints.get(target).copied()) {
            // C converts between integers and `float` by value, which no `REAL` write
            // here does (the lowering keeps such a variable opaque).
            if t.map_or(ct.float, |t| t.float != ct.float) {
                return;
            }
            self.ints.insert(target.to_string(), (ct.store(x.into()), ct));
        }
    }

    /// One call of the integer block `k` with its `EN`: its outputs written. A function
    /// runs every scan: under `EN` FALSE it returns its type's initial value 0 (FALSE for
    /// a comparison) and clears its `ENO` (matiec's `TEST_EN`); DIV also clears `ENO` for
    /// a divisor 0 (`TEST_EN_COND(TYPENAME, op2 == 0)`). A counter is a function block:
    /// under `EN` FALSE its body does not run, its outputs and memories kept.
    pub(super) fn int_exec(
        &mut self,
        k: usize,
        b: &IntBlock,
        en: bool,
        bools: &BTreeMap<String, bool>,
    ) {
        let pins: Vec<PinIn> = match self.p.obj(k).map(|o| &o.kind) {
            Some(ObjKind::Block { inputs, .. }) => inputs.clone(),
            _ => return,
        };
        let mut args: Vec<(String, Val)> = Vec::new();
        for pin in &pins {
            let n = pin.name.to_ascii_uppercase();
            if n == "EN" || b.bool_input(&n) {
                continue;
            }
            let v = if pin.conns.is_empty() && pin.expr.is_none() {
                Some((0, None))
            } else {
                self.int_pin(pin)
            };
            args.push((n, v));
        }
        let get = |n: &str| bools.get(n).copied().unwrap_or(false);
        if let IntBlock::Counter(ty) = b {
            // Its ENO (where drawn) is its EN.
            self.set_hidden(k, "ENO", en);
            if en {
                self.count(k, ty, get("CU"), get("CD"), get("R"), get("LD"), &args);
            }
            return;
        }
        let typed = args.iter().find_map(|(_, v)| v.and_then(|(_, t)| t));
        // `op2 == 0`: for a `REAL`, `-0.0` too.
        let divisor_zero =
            args.get(1).and_then(|(_, v)| *v).is_some_and(|(x, t)| match t.or(typed) {
                Some(ct) if ct.float => float(x.into()) == 0.0,
                Some(ct) => ct.store(x.into()) == 0,
                None => x == 0,
            });
        let divides_by_zero = matches!(b, IntBlock::Arith(Arith::Div)) && divisor_zero;
        // `BCD_TO_*`: `TEST_EN_COND(…, __test_bcd(op))`.
        let not_bcd = match (b, args.as_slice()) {
            (IntBlock::Convert(from, to), [(_, Some((x, t)))]) => {
                bcd_sides(from, to).is_some_and(|(to_bcd, _, bits)| {
                    !to_bcd && bcd_input(*x, *t, bits).is_some_and(test_bcd)
                })
            }
            _ => false,
        };
        // MUX: `TEST_EN_COND(…, K >= param_count)`, the count of its data inputs.
        let past = *b == IntBlock::Mux && {
            let known: Option<Vec<(String, i64, Option<CType>)>> =
                args.iter().map(|(n, v)| v.map(|(x, t)| (n.clone(), x, t))).collect();
            known.and_then(|v| mux_k(&v)).is_some_and(|k| k >= args.len() as i64 - 1)
        };
        self.set_hidden(k, "ENO", en && !divides_by_zero && !past && !not_bcd);
        let Some(out) = self.p.hidden_name(k, "OUT").map(str::to_string) else { return };
        let string = match b {
            IntBlock::Convert(from, to) if from == "STRING" => self.string_conversion(k, to, &out),
            _ => None,
        };
        match string.or_else(|| function(b, args, get)) {
            Some(Out::Int(_, ct)) if !en => {
                self.ints.insert(out, (0, ct));
            }
            Some(Out::Int(v, ct)) => {
                self.ints.insert(out, (ct.store(v), ct));
            }
            // C's undefined result: the run's value of the block's free input.
            Some(Out::Undefined(ct)) => {
                let free = crate::ladder::plcopen::ints::undefined_input(&out);
                let v = if en { self.ints.get(&free).map_or(0, |(v, _)| *v) } else { 0 };
                let v = ct.store(v.into());
                self.ints.insert(out, (v, ct));
            }
            Some(Out::Bool(holds)) => {
                self.bits.insert(out, en && holds);
            }
            None => {}
        }
    }

    /// `STRING_TO_<to>` of block `k` (its `OUT` is `out`): matiec's `__string_to_bool`
    /// and `__string_to_sint` (`lib/C/iec_std_lib.h`) of a string literal, the run's
    /// value of its free input for a peripheral's string into an integer; `None` (not
    /// known) otherwise.
    fn string_conversion(&self, k: usize, to: &str, out: &str) -> Option<Out> {
        use crate::iec::literal::{matiec_string_to_bool, matiec_string_to_lint};
        use crate::ladder::plcopen::StringSource;
        let ct = if to == "BOOL" { None } else { Some(CType::of(to).filter(|c| !c.float)?) };
        match (self.p.string_input(k)?, ct) {
            (StringSource::Literal(body), None) => Some(Out::Bool(matiec_string_to_bool(&body))),
            (StringSource::Literal(body), Some(ct)) => {
                Some(Out::Int(matiec_string_to_lint(&body)?.into(), ct))
            }
            (StringSource::Peripheral(..), Some(ct)) => {
                let free = PlcProgram::peripheral_conversion_input(out);
                Some(Out::Int(self.ints.get(&free)?.0.into(), ct))
            }
            (StringSource::Peripheral(..), None) => None,
        }
    }

    /// A counter call as `lib/counter.txt` writes it.
    #[allow(clippy::too_many_arguments)]
    fn count(
        &mut self,
        k: usize,
        ty: &str,
        cu: bool,
        cd: bool,
        r: bool,
        ld: bool,
        args: &[(String, Val)],
    ) {
        let kind = ty.split('_').next().unwrap_or(ty).to_string();
        let ct = counter_ctype(ty);
        let (Some(ct), Some(cv_name)) = (ct, self.p.hidden_name(k, "CV").map(str::to_string))
        else {
            return;
        };
        let pv = match args.iter().find(|(n, _)| n == "PV") {
            None => 0,
            Some((_, Some((x, t)))) if t.is_none_or(|t| t == ct) => ct.store((*x).into()),
            Some(_) => return,
        };
        // R_TRIG: Q := CLK AND NOT M; M := CLK.
        let trig = |s: &mut Self, pin: &str, clk: bool| {
            let key = (k, format!("{pin}_T"));
            let m = s.memory.get(&key).copied().unwrap_or(false);
            s.memory.insert(key, clk);
            clk && !m
        };
        let (cu_q, cd_q) = match kind.as_str() {
            "CTU" => (trig(self, "CU", cu), false),
            "CTD" => (false, trig(self, "CD", cd)),
            _ => {
                let cd_q = trig(self, "CD", cd);
                (trig(self, "CU", cu), cd_q)
            }
        };
        let mut cv = self.ints.get(&cv_name).map_or(0, |(v, _)| *v);
        match kind.as_str() {
            "CTU" => {
                if r {
                    cv = 0;
                } else if cu_q && cv < pv {
                    cv += 1;
                }
            }
            "CTD" => {
                if ld {
                    cv = pv;
                } else if cd_q && cv > 0 {
                    cv -= 1;
                }
            }
            _ => {
                if r {
                    cv = 0;
                } else if ld {
                    cv = pv;
                } else if !(cu_q && cd_q) {
                    if cu_q && cv < pv {
                        cv += 1;
                    } else if cd_q && cv > 0 {
                        cv -= 1;
                    }
                }
            }
        }
        self.ints.insert(cv_name, (cv, ct));
        let outs: &[(&str, bool)] = if kind == "CTUD" {
            &[("QU", cv >= pv), ("QD", cv <= 0)]
        } else if kind == "CTU" {
            &[("Q", cv >= pv)]
        } else {
            &[("Q", cv <= 0)]
        };
        for (pin, v) in outs {
            self.set_hidden(k, pin, *v);
        }
    }
}

/// The C type of the count of the counter `ty` (`CTU` an INT, `CTU_DINT` a DINT, …).
fn counter_ctype(ty: &str) -> Option<CType> {
    match ty.split_once('_') {
        None => CType::of("INT"),
        Some((_, t)) => CType::of(t),
    }
}
