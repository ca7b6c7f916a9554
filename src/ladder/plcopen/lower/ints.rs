//! Integers of PLCopen LD/FBD bodies in the scan model: integer variables and literals on wires, output variables that write integers, and the standard integer blocks (comparisons, arithmetic, MIN/MAX/LIMIT/ABS, MOVE/SEL, conversions, counters) as matiec's C computes them after Beremiz's generator: every argument a value of the block's type, the result wrapped to it. An integer that cannot be computed exactly is *opaque*: what reads it is unconstrained, with the reason.

use std::collections::BTreeMap;

use super::{Lower, fresh_because};
use crate::diag::Span;
use crate::iec::literal::int_literal;
use crate::ladder::plcopen::ints::{Arith, ConvType, IntBlock, bcd_conversion};
use crate::ladder::plcopen::{Edge, ObjKind, PinIn, PlcProgram, Source};
use crate::program::library::{self, Counter};
use crate::program::{
    Block, BoolExpr, C_INT, CheckedOp, CmpOp, EdgeKind, IntExpr, IntType, IntVar, Memory, RealOp,
    Stmt, WriteKind, c_operation,
};

/// An integer value on a wire and its type (`None`: a literal, typed by its reader), or
/// why it is not computed.
pub(super) type IntVal = Result<(IntExpr, Option<IntType>), String>;

/// `e` as a value of `t` (a literal wrapped into it, as the C cast `(INT)70000` does; a
/// `REAL` literal is already one).
pub(super) fn coerce(e: IntExpr, t: IntType) -> IntExpr {
    match e {
        IntExpr::Const(v) if !t.real => IntExpr::Const(t.wrap(v)),
        e => e,
    }
}

/// Why an integer literal where a `REAL` is expected is not computed.
const INT_LITERAL_AS_REAL: &str =
    "an integer literal where a REAL is expected, which matiec's type check does not accept";

/// The one type of a block's integer arguments (integer literals take it; none where it
/// is `REAL`).
fn unify<'a>(args: impl IntoIterator<Item = &'a Option<IntType>>) -> Result<IntType, String> {
    let mut t: Option<IntType> = None;
    let mut untyped = false;
    for ty in args {
        let Some(ty) = ty else {
            untyped = true;
            continue;
        };
        match t {
            Some(a) if a != *ty => {
                return Err(format!(
                    "it mixes {} and {}",
                    library::type_name(a),
                    library::type_name(*ty)
                ));
            }
            _ => t = Some(*ty),
        }
    }
    if untyped && t.is_some_and(|t| t.real) {
        return Err(INT_LITERAL_AS_REAL.into());
    }
    t.ok_or_else(|| {
        "its inputs are literals only, whose type the generated code leaves open".into()
    })
}

/// Whether the divisor (the second input) of a DIV is not 0, as matiec's
/// `TEST_EN_COND(TYPENAME, op2 == 0)` tests it: the divisor as a value of the block's type.
fn divisor_not_zero(keyword: &str, ints: &[(String, IntVal)], span: Span) -> BoolExpr {
    let divisor = ints.get(1).map_or(Ok((IntExpr::Const(0), None)), |(_, v)| v.clone());
    let typed = unify(ints.iter().filter_map(|(_, v)| v.as_ref().ok()).map(|(_, t)| t));
    match divisor.and_then(|(d, _)| Ok((d, typed?))) {
        Ok((d, t)) => library::compare_chain(CmpOp::Ne, t, &[coerce(d, t), IntExpr::Const(0)]),
        Err(why) => {
            let why = format!("the ENO of {keyword}, whose divisor is not computed: {why}");
            fresh_because(keyword, why, span)
        }
    }
}

/// Whether the input of `BCD_TO_*` is BCD, as matiec's `TEST_EN_COND(…, __test_bcd(op))`
/// tests it (`ENO` FALSE otherwise); TRUE for another conversion.
fn bcd_valid(
    keyword: &str,
    from: &str,
    to: &str,
    ints: &[(String, IntVal)],
    span: Span,
) -> BoolExpr {
    let Some((uint, false, bits)) = bcd_conversion(from, to) else {
        return BoolExpr::Const(true);
    };
    let vals: Result<Vec<Arg>, String> =
        ints.iter().map(|(n, v)| v.clone().map(|(e, t)| (n.as_str(), e, t))).collect();
    match vals.and_then(|vals| bcd_types(uint, false, bits, &vals)) {
        Ok((x, f, _)) => library::is_bcd(&x, f),
        Err(why) => {
            let why = format!("the ENO of {keyword}, whose input is not computed: {why}");
            fresh_because(keyword, why, span)
        }
    }
}

/// A computed argument of a function: its pin, value and type (`None`: a literal).
type Arg<'a> = (&'a str, IntExpr, Option<IntType>);

/// `MUX`'s `K` (a value of its type: a literal's is `DINT`) and its data inputs `IN0`,
/// `IN1`, … in the order of their numbers, as matiec's `MUX__…` takes them.
#[allow(clippy::type_complexity)]
fn mux_args(vals: &[Arg]) -> Result<(IntExpr, IntType, Vec<(IntExpr, Option<IntType>)>), String> {
    let (_, k, kt) = vals.iter().find(|(n, _, _)| *n == "K").ok_or("it has no input K")?;
    let kt = kt.unwrap_or(IntType::int(32, true));
    if kt.real {
        return Err("its K is a REAL".into());
    }
    let mut data = Vec::new();
    for i in 0.. {
        match vals.iter().find(|(n, _, _)| *n == format!("IN{i}")) {
            Some((_, x, t)) => data.push((x.clone(), *t)),
            None => break,
        }
    }
    if data.len() + 1 != vals.len() {
        return Err("its inputs are not K, IN0, IN1, …".into());
    }
    Ok((coerce(k.clone(), kt), kt, data))
}

/// Whether `MUX`'s `K` is below the number of its inputs, as matiec's `TEST_EN_COND(…, K
/// >= param_count)` tests it (`K` in its own type against the `UINT` count: a negative
/// `K` passes, and gives 0).
fn k_in_range(keyword: &str, ints: &[(String, IntVal)], span: Span) -> BoolExpr {
    let vals: Result<Vec<Arg>, String> =
        ints.iter().map(|(n, v)| v.clone().map(|(e, t)| (n.as_str(), e, t))).collect();
    match vals.and_then(|vals| mux_args(&vals).map(|(k, kt, data)| (k, kt, data.len()))) {
        Ok((_, kt, n)) if n as i64 > kt.max() => BoolExpr::Const(true),
        Ok((k, kt, n)) => {
            BoolExpr::negate(library::compare(CmpOp::Ge, kt, k, IntExpr::Const(n as i64)))
        }
        Err(why) => {
            let why = format!("the ENO of {keyword}, whose K is not computed: {why}");
            fresh_because(keyword, why, span)
        }
    }
}

/// What a function gives: an integer of a type, or a BOOL.
pub(super) enum Value {
    Int(IntExpr, IntType),
    Bool(BoolExpr),
}

/// A BCD conversion's input, its type and the type of its result (see
/// [`bcd_conversion`]): the unsigned integer `uint`, and a bit string of any width (`bits`,
/// or where the name gives none, of `uint`'s width, as Beremiz's library pairs them: `UINT`
/// with `WORD`); a literal input takes the type of its side.
fn bcd_types(
    uint: &str,
    to_bcd: bool,
    bits: Option<&str>,
    vals: &[Arg],
) -> Result<(IntExpr, IntType, IntType), String> {
    let unsigned = |name: &str, kinds: [&str; 3]| match library::int_type(name) {
        Some(t) if kinds.contains(&name) => Ok(t),
        _ if matches!(name, "ULINT" | "LWORD") => {
            Err(format!("{name} is 64 bits wide, which ii-prove does not compute"))
        }
        _ => Err(format!("{name} is not a type matiec converts to or from BCD")),
    };
    let u = unsigned(uint, ["USINT", "UINT", "UDINT"])?;
    let b = match bits {
        Some(bits) => unsigned(bits, ["BYTE", "WORD", "DWORD"])?,
        None => u,
    };
    let [(_, x, ty)] = vals else { return Err("it takes one input".into()) };
    let (input, output) = if to_bcd { (u, b) } else { (ty.unwrap_or(b), u) };
    if ty.is_some_and(|ty| ty != input) || input.signed || input.real {
        return Err(format!("its input is not {}", library::type_name(input)));
    }
    Ok((coerce(x.clone(), input), input, output))
}

/// The conversion `FROM_TO_TO` of its input, as matiec's `lib/C/iec_std_functions.h`
/// computes it: `BOOL_TO_*` and `*_TO_*` between integers by `__convert_type` (`(to)
/// __move_to(op)`: the value converted as C converts it, sign- or zero-extended or
/// wrapped; a BOOL is 0 or 1), `*_TO_BOOL` by `__convert_num_to_bool` (`op == 0 ? 0 :
/// 1`). `input` is `IN` when it is a BOOL, `vals` the integer inputs.
fn convert(from: &str, to: &str, input: Option<BoolExpr>, vals: &[Arg]) -> Result<Value, String> {
    if let Some((uint, to_bcd, bits)) = bcd_conversion(from, to) {
        let (x, f, o) = bcd_types(uint, to_bcd, bits, vals)?;
        return Ok(Value::Int(
            if to_bcd { library::uint_to_bcd(&x, f, o) } else { library::bcd_to_uint(&x, f) },
            o,
        ));
    }
    let t = ConvType::of(to)?;
    match ConvType::of(from)? {
        ConvType::Bool => {
            let b = input.unwrap_or(BoolExpr::Const(false));
            Ok(match t {
                ConvType::Bool => Value::Bool(b),
                ConvType::Int(t) => {
                    let one = if t.real { crate::program::real::of_f32(1.0) } else { 1 };
                    Value::Int(IntExpr::ite(b, IntExpr::Const(one), IntExpr::Const(0)), t)
                }
            })
        }
        ConvType::Int(f) => {
            let [(_, x, ty)] = vals else { return Err("it takes one input".into()) };
            if ty.is_some_and(|ty| ty != f) {
                return Err(format!("its input is not a {from}"));
            }
            if ty.is_none() && f.real {
                return Err(INT_LITERAL_AS_REAL.into());
            }
            let x = coerce(x.clone(), f);
            Ok(match t {
                ConvType::Bool => Value::Bool(library::compare(CmpOp::Ne, f, x, IntExpr::Const(0))),
                ConvType::Int(t) if f.real && t.real => Value::Int(x, t),
                // `(REAL)` of an integer: the nearest float, ties to even.
                ConvType::Int(t) if t.real => Value::Int(IntExpr::ToReal(Box::new(x), f), t),
                // `__real_to_sint`, `__real_to_uint`, `__real_to_bit`: rounded through
                // `LINT`, a free value where C leaves it undefined (`int_call`).
                ConvType::Int(t) if f.real => {
                    Value::Int(IntExpr::FromReal(Box::new(x), !t.signed), t)
                }
                // A value of `from`, then converted to `to` (sign- or zero-extended, or
                // wrapped).
                ConvType::Int(t) => Value::Int(IntExpr::Cast(Box::new(x), f), t),
            })
        }
    }
}

impl Lower<'_> {
    /// Declares the integer variables of `p` (and of its inlined bodies): their types,
    /// start values and whether the outside world writes them; those not computed are
    /// opaque with the reason.
    pub(super) fn declare_ints(&mut self, p: &PlcProgram) {
        for v in p.vars.values() {
            let Some(ty) = p.int_var_type(&v.name) else { continue };
            if self.opaque.contains_key(&v.name) {
                continue;
            }
            let why = match library::number_type(&ty) {
                None => Some(format!("{ty} is 64 bits wide, which ii-prove does not compute")),
                // Written from outside at the start of every scan (an input, or latched).
                Some(_)
                    if v.retain
                        && !p.inputs.contains(&v.name)
                        && !p.latches.contains_key(&v.name) =>
                {
                    Some("it is retained, so it starts with any value after a warm restart".into())
                }
                Some(_) => None,
            };
            let Some(t) = library::number_type(&ty).filter(|_| why.is_none()) else {
                self.make_opaque(&v.name, why.unwrap_or_default());
                continue;
            };
            let init = match v.init.as_deref() {
                None => Some(0),
                Some(text) if t.real => crate::program::real::literal(text),
                Some(text) => int_literal(text)
                    .filter(|(_, lt)| lt.as_deref().is_none_or(|lt| lt == ty))
                    .map(|(k, _)| t.wrap(k.clamp(i64::MIN.into(), i64::MAX.into()) as i64)),
            };
            let Some(init) = init else {
                let why = format!(
                    "its initial value `{}` is not an integer literal of its type",
                    v.init.as_deref().unwrap_or("")
                );
                self.make_opaque(&v.name, why);
                continue;
            };
            let input = p.inputs.contains(&v.name);
            self.ints.insert(
                v.name.clone(),
                IntVar { ty: t, input, init: if input { 0 } else { init } },
            );
        }
        for sub in p.subs.values() {
            self.declare_ints(sub);
        }
        // The value an integer input the program also writes is latched from: an input
        // of its type.
        for (x, latch) in &p.latches {
            if let Some(t) = self.ints.get(x).map(|v| v.ty) {
                self.ints.insert(latch.clone(), IntVar { ty: t, input: true, init: 0 });
            }
        }
    }

    /// At the start of the scan, each latched input takes the value from outside: a BOOL
    /// by a coil, an integer by a write (none when the integer is opaque).
    pub(super) fn latch_inputs(&mut self, p: &PlcProgram, span: Span) {
        for (x, latch) in &p.latches {
            if self.ints.contains_key(x) {
                let set = Stmt::SetInt { target: x.clone(), value: IntExpr::var(latch), span };
                self.push_block(vec![set], span);
            } else if !self.opaque.contains_key(x) && !self.new_opaque.contains_key(x) {
                let value = BoolExpr::var(latch);
                self.coil(value, x, crate::program::WriteKind::Assign, span);
            }
        }
    }

    /// Marks the integer `x` as not computed, for `why` (the program is then lowered again
    /// with it opaque).
    pub(super) fn make_opaque(&mut self, x: &str, why: String) {
        self.ints.remove(x);
        if !self.opaque.contains_key(x) {
            self.new_opaque.entry(x.to_string()).or_insert(why);
        }
    }

    /// A read of the integer `name` (declared or hidden).
    fn int_read(&self, name: &str) -> IntVal {
        if let Some(why) = self.opaque.get(name).or_else(|| self.new_opaque.get(name)) {
            return Err(format!("{name} is not computed: {why}"));
        }
        match self.ints.get(name) {
            Some(v) => Ok((IntExpr::var(name), Some(v.ty))),
            None => Err(self.not_an_integer(name)),
        }
    }

    /// Why the variable `name`, read where an integer is expected, is not computed: its
    /// declared type when that is not an integer one (`REAL`, `STRING`, …).
    fn not_an_integer(&self, name: &str) -> String {
        let declared = self.p.vars.values().find(|v| v.name == name).map(|v| &v.ty);
        match declared {
            Some(crate::ladder::plcopen::Ty::Other(t) | crate::ladder::plcopen::Ty::Derived(t)) => {
                // Beremiz's SVGHMI types are their base type (`HMI_REAL`).
                let t = t.to_ascii_uppercase();
                match ConvType::of(t.strip_prefix("HMI_").unwrap_or(&t)) {
                    Err(why) => format!("{name} is not computed: {why}"),
                    Ok(_) => format!("{name} is not computed"),
                }
            }
            _ => format!("{name} is not computed"),
        }
    }

    /// The integer an operand text gives: a literal or an integer variable.
    fn int_operand(&self, text: &str) -> IntVal {
        if let Some(bits) = crate::program::real::literal(text) {
            return Ok((IntExpr::Const(bits), Some(IntType::REAL)));
        }
        if let Some((v, ty)) = int_literal(text) {
            let v = v.clamp(i64::MIN.into(), i64::MAX.into()) as i64;
            return match ty.map(|t| library::int_type(&t)) {
                None => Ok((IntExpr::Const(v), None)),
                Some(Some(t)) => Ok((IntExpr::Const(t.wrap(v)), Some(t))),
                Some(None) => Err(format!("the literal `{text}` is not computed")),
            };
        }
        match self.p.vars.get(&text.trim().to_ascii_uppercase()) {
            Some(v) => self.int_read(&v.name),
            None => Err(format!("`{text}` is not an integer ii-prove computes")),
        }
    }

    /// `MUX(K, IN0, IN1, …)` of BOOL inputs `vals` (by pin), as matiec's `MUX__BOOL__…`
    /// (`lib/C/iec_std_functions.h`) returns it: `IN{K}` for `0 ≤ K < n`; FALSE for `K ≥
    /// n` (`TEST_EN_COND(BOOL, K >= param_count)`) and for a negative `K` (no `K == i`,
    /// `__INIT_BOOL`). Unconstrained when `K` is not computed.
    pub(super) fn bool_mux(
        &mut self,
        k: usize,
        vals: &std::collections::BTreeMap<String, BoolExpr>,
        span: Span,
    ) -> BoolExpr {
        let key = self.p.pin(k, "K").cloned();
        let kv =
            key.ok_or_else(|| "it has no input K".to_string()).and_then(|pin| self.int_pin(&pin));
        let (kv, kt) = match kv {
            Ok(v) => v,
            Err(why) => {
                return fresh_because("MUX", format!("the MUX's K is not computed: {why}"), span);
            }
        };
        let kt = kt.unwrap_or(IntType::int(32, true));
        if kt.real {
            return fresh_because("MUX", "the MUX's K is a REAL".into(), span);
        }
        let key = coerce(kv, kt);
        let mut terms = Vec::new();
        for i in 0..vals.len() as i64 {
            let Some(v) = vals.get(&format!("IN{i}")) else { break };
            if i <= kt.max() {
                let eq = library::compare(CmpOp::Eq, kt, key.clone(), IntExpr::Const(i));
                terms.push(super::and(vec![eq, v.clone()]));
            }
        }
        if terms.is_empty() { BoolExpr::Const(false) } else { super::or(terms) }
    }

    /// The integer at a consumer pin.
    pub(super) fn int_pin(&mut self, pin: &PinIn) -> IntVal {
        if pin.negated || pin.edge != Edge::None {
            return Err("a negated or edge pin carries an integer".into());
        }
        if let Some((text, _)) = &pin.expr {
            return self.int_operand(text);
        }
        match pin.conns.as_slice() {
            [c] => match self.p.source(c) {
                Some(src) => self.int_source(src),
                None => Err("a wire from nowhere".into()),
            },
            [] => Err("an unconnected integer input".into()),
            _ => Err("several wires into an integer input".into()),
        }
    }

    fn int_source(&mut self, src: Source) -> IntVal {
        match src {
            Source::Object(j) => match self.p.obj(j).map(|o| &o.kind) {
                Some(ObjKind::InVar { expr, .. } | ObjKind::InOutVar { expr, .. }) => {
                    let text = expr.0.clone();
                    self.int_operand(&text)
                }
                Some(ObjKind::Connector { input, .. }) => {
                    if !self.visiting.insert(j) {
                        return Err("a loop of connectors".into());
                    }
                    let v = self.int_pin(input);
                    self.visiting.remove(&j);
                    v
                }
                _ => Err("a BOOL where an integer is expected".into()),
            },
            Source::BlockOut(j, pin) => {
                let (name, negated) = self.p.output_pin(j, pin);
                if negated {
                    return Err("a negated integer output".into());
                }
                self.int_block_output(j, &name)
            }
            Source::BlockPin(..) | Source::Rail => {
                Err("a BOOL where an integer is expected".into())
            }
        }
    }

    /// The integer output `pin` of block `j` (calling it at its first use this scan).
    fn int_block_output(&mut self, j: usize, pin: &str) -> IntVal {
        let before = self.no_pull && !self.called.contains(&j);
        if self.in_progress.contains(&j) || before {
            self.fed_back.insert(j);
        }
        if !before {
            self.call(j);
        }
        match self.p.int_output_name(j, pin).map(str::to_string) {
            Some(name) => self.int_read(&name),
            None => Err(self.output_not_computed(j, pin)),
        }
    }

    /// Why the output `pin` of block `j` carries no integer: the block named, and for
    /// the numerical functions of one `REAL` (`SIN`, `SQRT`, …) that C's math library
    /// computes them.
    fn output_not_computed(&self, j: usize, pin: &str) -> String {
        let Some(ObjKind::Block { type_name, instance, .. }) = self.p.obj(j).map(|o| &o.kind)
        else {
            return format!("the output {pin} of this block is not computed");
        };
        let upper = type_name.to_ascii_uppercase();
        const MATH: [&str; 12] = [
            "SQRT", "LN", "LOG", "EXP", "EXPT", "SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN",
            "ATAN2",
        ];
        match instance {
            _ if MATH.contains(&upper.as_str()) => {
                format!("{upper} is computed by C's math library, which ii-prove does not model")
            }
            Some(i) => format!("the output {pin} of {i} ({type_name}) is not computed"),
            None => format!("the output {pin} of the function {type_name} is not computed"),
        }
    }

    /// A block of its own with these statements (what the compiler names after it is
    /// named after its number, as [`Lower::coil`] does).
    pub(super) fn push_block(&mut self, mut stmts: Vec<Stmt>, span: Span) {
        let number = self.blocks.len() + 1;
        let mut rename = |e: &mut BoolExpr| match e {
            BoolExpr::Fresh(f) => f.base = format!("{}_r{number}", f.base),
            BoolExpr::Edge { memory, .. } => memory.base = format!("{}_r{number}", memory.base),
            _ => {}
        };
        for s in &mut stmts {
            match s {
                Stmt::Let { value, .. } | Stmt::Write { value, .. } => {
                    crate::program::walk_mut(value, &mut rename)
                }
                Stmt::SetInt { value, target, .. } => {
                    self.emitted.insert(target.clone());
                    crate::program::int_walk_mut(value, &mut rename)
                }
                _ => {}
            }
            if let Stmt::Write { target, .. } = s {
                self.emitted.insert(target.clone());
            }
        }
        self.blocks.push(Block { number, label: None, span, stmts });
    }

    pub(super) fn temp(&mut self, stmts: &mut Vec<Stmt>, value: BoolExpr) -> BoolExpr {
        let temp = self.next_temp;
        self.next_temp += 1;
        stmts.push(Stmt::Let { temp, value });
        BoolExpr::Temp(temp)
    }

    /// `target := ` the integer at `input` (an output or in-out variable on an integer).
    /// matiec's `__CHECK_…` of a subrange type `lo..hi` on the integer `var` just
    /// written (`library::subrange_check`); nothing when `var` is not computed.
    pub(super) fn subrange_check(&mut self, var: &str, (lo, hi): (i64, i64), span: Span) {
        let Some(t) = self.ints.get(var).map(|v| v.ty) else { return };
        let value = library::subrange_check(t, IntExpr::var(var), lo, hi);
        self.push_block(vec![Stmt::SetInt { target: var.to_string(), value, span }], span);
    }

    pub(super) fn int_assign(&mut self, target: &str, input: &PinIn, span: Span) {
        let value = self.int_pin(input);
        let Some(var) = self.ints.get(target).copied() else { return };
        let value =
            value.or_else(|why| self.peripheral_int(input, var.ty, span).unwrap_or(Err(why)));
        let exact = value.and_then(|(e, ty)| {
            if var.input {
                return Err("both the outside world and the program write it".into());
            }
            match ty {
                Some(t) if t != var.ty => Err(format!(
                    "it is a {} written with a {}",
                    library::type_name(var.ty),
                    library::type_name(t)
                )),
                None if var.ty.real => Err(INT_LITERAL_AS_REAL.into()),
                _ => Ok(coerce(e, var.ty)),
            }
        });
        match exact {
            Ok(value) => {
                let value = match self.eno_guard(input) {
                    Some(g) => IntExpr::ite(g, value, IntExpr::var(target)),
                    None => value,
                };
                let set = Stmt::SetInt { target: target.to_string(), value, span };
                self.push_block(vec![set], span);
            }
            Err(why) => self.make_opaque(target, why),
        }
    }

    /// The call of the integer block `k` with `EN` (`1` when it runs every scan): its
    /// inputs computed in document order, then its outputs written (opaque where not
    /// computed).
    ///
    /// Under a wired `EN`, Beremiz's `PLCGenerator.py` writes `_TMP_ADD7_OUT := ADD(EN
    /// := …, IN1 := …, ENO => _TMP_ADD7_ENO);` (`GenerateBlock`), and matiec calls the
    /// function every scan: its `TEST_EN` (`lib/C/iec_std_functions.h`) returns the
    /// type's initial value (`__INIT_INT 0`, `__INIT_BOOL 0`, `lib/C/iec_types.h`) and
    /// clears `ENO` when `EN` is FALSE, sets `ENO` otherwise (DIV: `TEST_EN_COND(…, op2
    /// == 0)` also clears it for a divisor 0); the wrapper `generate_c_inlinefcall.cc`
    /// writes `ENO` back after the call. So `OUT := EN ? f(…) : 0` and `ENO := EN ∧ ok`,
    /// no state. A counter is a function block: under a wired `EN` its body (and its
    /// edge detectors' memories) runs only where EN is TRUE.
    pub(super) fn int_call(&mut self, k: usize, b: &IntBlock, en: BoolExpr, span: Span) {
        let p = self.p;
        let Some(ObjKind::Block { inputs, type_name, instance, .. }) = p.obj(k).map(|o| &o.kind)
        else {
            return;
        };
        let mut bools: BTreeMap<String, BoolExpr> = BTreeMap::new();
        let mut ints: Vec<(String, IntVal)> = Vec::new();
        for pin in inputs {
            let n = pin.name.to_ascii_uppercase();
            if n == "EN" {
                continue;
            }
            if b.bool_input(&n) {
                let v = self.pin_value(k, pin);
                bools.insert(n, v);
            } else if pin.conns.is_empty() && pin.expr.is_none() {
                ints.push((n, Ok((IntExpr::Const(0), None))));
            } else {
                let v = self.int_pin(pin);
                ints.push((n, v));
            }
        }
        let upper = type_name.to_ascii_uppercase();
        let name = instance.as_deref().unwrap_or(&upper).to_string();
        let runs = matches!(en, BoolExpr::Const(true));
        if let IntBlock::Counter(ty) = b {
            // Under a wired EN its body runs under the instance's ENO (`lower/fbs.rs`).
            let start = self.fb_enable(k, Some(en), span);
            self.counter_call(k, ty, &name, bools, ints, span);
            return self.under_eno(k, start, runs);
        }
        let mut stmts = Vec::new();
        let en = if runs { en } else { self.temp(&mut stmts, en) };
        let enabled = |v: BoolExpr| if runs { v } else { BoolExpr::and(en.clone(), v) };
        if let Some(out) = p.hidden_name(k, "OUT").map(str::to_string) {
            let string = match b {
                IntBlock::Convert(from, to) if from == "STRING" => {
                    self.string_conversion(k, to, &out, &mut stmts, span)
                }
                _ => None,
            };
            match string.unwrap_or_else(|| self.int_function(b, &bools, &ints, &out)) {
                Ok(Value::Int(e, t)) => {
                    let e = match e {
                        IntExpr::FromReal(x, unsigned) => {
                            self.undefined_result(&out, &upper, *x, unsigned, t, &mut stmts, span)
                        }
                        e => e,
                    };
                    let free = crate::ladder::plcopen::ints::undefined_input(&out);
                    let mut overflows = false;
                    e.visit(&mut |n| overflows |= n == free, &mut |_| {});
                    if overflows && !self.undefined.contains(&free) {
                        self.undefined.insert(free.clone());
                        self.ints.insert(free.clone(), IntVar { ty: C_INT, input: true, init: 0 });
                        let message = format!(
                            "may overflow the 32-bit `int` the generated C computes it in, which \
                             C leaves undefined: there its OUT is the free input {free}"
                        );
                        stmts.push(Stmt::Warn { span, element: upper.clone(), message });
                    }
                    self.ints.insert(out.clone(), IntVar { ty: t, input: false, init: 0 });
                    let value =
                        if runs { e } else { IntExpr::ite(en.clone(), e, IntExpr::Const(0)) };
                    stmts.push(Stmt::SetInt { target: out, value, span });
                }
                Ok(Value::Bool(v)) => {
                    let value = enabled(v);
                    stmts.push(Stmt::Write { target: out, kind: WriteKind::Assign, value, span });
                }
                Err(_) if let (IntBlock::Compare(_), Some(why)) = (b, p.peripheral_strings(k)) => {
                    let value = enabled(super::free(&upper, why, span, true));
                    stmts.push(Stmt::Write { target: out, kind: WriteKind::Assign, value, span });
                }
                Err(why) if b.bool_out() => {
                    let what =
                        if matches!(b, IntBlock::Compare(_)) { "comparison" } else { "conversion" };
                    let why = format!("the {what} {upper} is not computed: {why}");
                    let value = enabled(fresh_because(&upper, why, span));
                    stmts.push(Stmt::Write { target: out, kind: WriteKind::Assign, value, span });
                }
                Err(why) => {
                    self.make_opaque(&out, format!("the {upper} block is not computed: {why}"))
                }
            }
        }
        if let Some(eno) = p.hidden_name(k, "ENO").map(str::to_string) {
            let ok = match b {
                IntBlock::Arith(Arith::Div) => divisor_not_zero(&upper, &ints, span),
                IntBlock::Mux => k_in_range(&upper, &ints, span),
                IntBlock::Convert(from, to) => bcd_valid(&upper, from, to, &ints, span),
                _ => BoolExpr::Const(true),
            };
            let value = enabled(ok);
            stmts.push(Stmt::Write { target: eno, kind: WriteKind::Assign, value, span });
        }
        if stmts.iter().any(|s| !matches!(s, Stmt::Let { .. })) {
            self.push_block(stmts, span);
        }
    }

    /// `REAL_TO_*` of `x` into `t` for the block whose `OUT` is `out`: the rounded value
    /// where C defines it, else a free input of `t` ([`library::real_to_int`]), said at
    /// the block.
    #[allow(clippy::too_many_arguments)]
    fn undefined_result(
        &mut self,
        out: &str,
        keyword: &str,
        x: IntExpr,
        unsigned: bool,
        t: IntType,
        stmts: &mut Vec<Stmt>,
        span: Span,
    ) -> IntExpr {
        let free = crate::ladder::plcopen::ints::undefined_input(out);
        self.ints.insert(free.clone(), IntVar { ty: t, input: true, init: 0 });
        self.undefined.insert(free.clone());
        let message = format!(
            "{}, its OUT is the free input {free}: any {}",
            library::real_to_int_undefined(unsigned),
            library::type_name(t)
        );
        stmts.push(Stmt::Warn { span, element: keyword.to_string(), message });
        library::real_to_int(x, unsigned, &free)
    }

    /// The value of a function over integers (a comparison's and a conversion to BOOL's
    /// a Boolean one), with its type.
    fn int_function(
        &self,
        b: &IntBlock,
        bools: &BTreeMap<String, BoolExpr>,
        ints: &[(String, IntVal)],
        out: &str,
    ) -> Result<Value, String> {
        let mut vals: Vec<Arg> = Vec::new();
        for (n, v) in ints {
            let (e, t) = v.clone().map_err(|why| format!("its input {n}: {why}"))?;
            vals.push((n, e, t));
        }
        if let IntBlock::Convert(from, to) = b {
            return convert(from, to, bools.get("IN").cloned(), &vals);
        }
        if *b == IntBlock::Mux {
            let (k, kt, data) = mux_args(&vals)?;
            let t = unify(data.iter().map(|(_, t)| t))?;
            // `IN_i` for `K == i`, else the type's initial value 0.
            let e = data.iter().enumerate().rev().fold(IntExpr::Const(0), |acc, (i, (x, _))| {
                let at = library::compare(CmpOp::Eq, kt, k.clone(), IntExpr::Const(i as i64));
                IntExpr::ite(at, coerce(x.clone(), t), acc)
            });
            return Ok(Value::Int(e, t));
        }
        let t = unify(vals.iter().map(|(_, _, t)| t))?;
        if t.real && matches!(b, IntBlock::Arith(Arith::Mod)) {
            return Err("MOD takes integers, not REALs".into());
        }
        let args: Vec<IntExpr> = vals.iter().map(|(_, e, _)| coerce(e.clone(), t)).collect();
        let named = |pin: &str| -> Result<IntExpr, String> {
            vals.iter()
                .find(|(n, _, _)| *n == pin)
                .map(|(_, e, _)| coerce(e.clone(), t))
                .ok_or_else(|| format!("it has no input {pin}"))
        };
        let e = match (b, args.as_slice()) {
            (IntBlock::Compare(op), [_, _, ..]) => {
                return Ok(Value::Bool(library::compare_chain(*op, t, &args)));
            }
            // IEEE division, `+0.0` for a divisor `±0.0`; sums and products folded as
            // `__arith_expand` does (each `op1 + tmp` in `double`, then rounded to
            // `float`: the same as one rounding, `double` having more than twice
            // `float`'s precision): `IntExpr::Real`.
            (IntBlock::Arith(Arith::Div), [a, b]) if t.real => {
                IntExpr::Real(RealOp::Div, Box::new(a.clone()), Box::new(b.clone()))
            }
            (IntBlock::Arith(Arith::Sub), [a, b]) if t.real => {
                IntExpr::Real(RealOp::Sub, Box::new(a.clone()), Box::new(b.clone()))
            }
            (IntBlock::Arith(op @ (Arith::Add | Arith::Mul)), [first, rest @ ..])
                if t.real && !rest.is_empty() =>
            {
                let op = if *op == Arith::Add { RealOp::Add } else { RealOp::Mul };
                rest.iter()
                    .fold(first.clone(), |a, b| IntExpr::Real(op, Box::new(a), Box::new(b.clone())))
            }
            // matiec's functions (`lib/C/iec_std_functions.h`): `op1 = op1 OP op2` in the
            // type, computed in C `int` for a narrower one, where an overflow is undefined
            // (`c_operation`: the block's OUT is then a free input); DIV and MOD (`__div`,
            // `__mod`) truncate toward zero, the remainder with the dividend's sign, 0 for
            // a divisor 0.
            (IntBlock::Arith(op), [first, rest @ ..]) if !rest.is_empty() => {
                let op = match op {
                    Arith::Add => CheckedOp::Add,
                    Arith::Sub => CheckedOp::Sub,
                    Arith::Mul => CheckedOp::Mul,
                    Arith::Div => CheckedOp::Div,
                    Arith::Mod => CheckedOp::Mod,
                };
                if rest.len() > 1 && !matches!(op, CheckedOp::Add | CheckedOp::Mul) {
                    return Err("its inputs are not the ones ii-prove computes".into());
                }
                let free = crate::ladder::plcopen::ints::undefined_input(out);
                let mut acc = first.clone();
                for (i, x) in rest.iter().enumerate() {
                    // A step's result, stored into `op1`, is a value of the type.
                    let a = if i == 0 { acc } else { IntExpr::Cast(Box::new(acc), t) };
                    acc = match c_operation(op, a, x.clone(), t, &free) {
                        Some(IntExpr::Checked(_)) if rest.len() > 1 => {
                            return Err(format!(
                                "a step of its sum or product of more than two {} values may \
                                 overflow C's `int`, which C leaves undefined",
                                library::type_name(t)
                            ));
                        }
                        Some(v) => v,
                        None => IntExpr::Const(0),
                    };
                }
                acc
            }
            (IntBlock::Min, [_, _, ..]) => library::extreme(true, t, &args),
            (IntBlock::Max, [_, _, ..]) => library::extreme(false, t, &args),
            (IntBlock::Limit, [_, _, _]) => {
                library::limit(t, named("MN")?, named("IN")?, named("MX")?)
            }
            // `-op` of the least `DINT` overflows.
            (IntBlock::Abs, [x]) => {
                let undefined =
                    (t == C_INT).then(|| crate::ladder::plcopen::ints::undefined_input(out));
                library::abs(t, x.clone(), undefined)
            }
            (IntBlock::Move, [x]) => x.clone(),
            (IntBlock::Sel, [_, _]) => {
                let g = bools.get("G").cloned().unwrap_or(BoolExpr::Const(false));
                IntExpr::ite(g, named("IN1")?, named("IN0")?)
            }
            _ => return Err("its inputs are not the ones ii-prove computes".into()),
        };
        Ok(Value::Int(e, t))
    }

    /// A counter call as matiec's `lib/counter.txt` runs it (see [`library::counter`]):
    /// the edges of `CU`/`CD` over hidden memories, the count, its Boolean outputs.
    fn counter_call(
        &mut self,
        k: usize,
        ty: &str,
        name: &str,
        bools: BTreeMap<String, BoolExpr>,
        ints: Vec<(String, IntVal)>,
        span: Span,
    ) {
        let p = self.p;
        let Some(cv) = p.hidden_name(k, "CV").map(str::to_string) else { return };
        let kind = Counter::of(ty).unwrap_or(Counter::UpDown);
        let pv = ints
            .into_iter()
            .find(|(n, _)| n == "PV")
            .map_or(Ok((IntExpr::Const(0), None)), |(_, v)| v);
        let exact = match library::counter_type(ty) {
            None => Err(format!("{ty} counts in 64 bits, which ii-prove does not compute")),
            Some(t) => pv.and_then(|(e, pt)| match pt {
                Some(pt) if pt != t => Err(format!(
                    "its PV is a {}, its count a {}",
                    library::type_name(pt),
                    library::type_name(t)
                )),
                _ => Ok((t, coerce(e, t))),
            }),
        };
        let (t, pv) = match exact {
            Ok(x) => x,
            Err(why) => {
                let why = format!("the counter {name} ({ty}) is not computed: {why}");
                for pin in kind.outputs() {
                    if let Some(q) = p.hidden_name(k, pin).map(str::to_string) {
                        let value = fresh_because(ty, why.clone(), span);
                        self.coil(value, &q, crate::program::WriteKind::Assign, span);
                    }
                }
                self.make_opaque(&cv, why);
                return;
            }
        };
        self.ints.insert(cv.clone(), IntVar { ty: t, input: false, init: 0 });
        let mut stmts = Vec::new();
        let input = |n: &str| bools.get(n).cloned().unwrap_or(BoolExpr::Const(false));
        let edge = |l: &mut Self, stmts: &mut Vec<Stmt>, pin: &str| {
            l.edges.push((l.path.clone(), k, format!("{pin}_T")));
            let memory =
                Memory { base: "OSR".into(), element: "OSR".into(), index: l.edges.len() - 1 };
            let e = BoolExpr::Edge {
                kind: EdgeKind::Rising,
                input: Box::new(input(pin)),
                memory: Box::new(memory),
            };
            l.temp(stmts, e)
        };
        let no = || BoolExpr::Const(false);
        let edges = match kind {
            Counter::Up => (edge(self, &mut stmts, "CU"), no()),
            Counter::Down => (no(), edge(self, &mut stmts, "CD")),
            Counter::UpDown => {
                // matiec's CTUD: CD_T(CD); CU_T(CU).
                let cd = edge(self, &mut stmts, "CD");
                (edge(self, &mut stmts, "CU"), cd)
            }
        };
        let r = self.temp(&mut stmts, input("R"));
        let ld = self.temp(&mut stmts, input("LD"));
        let (next, outputs) = library::counter(kind, t, &cv, pv, edges, r, ld);
        stmts.push(Stmt::SetInt { target: cv, value: next, span });
        for (pin, value) in outputs {
            if let Some(q) = p.hidden_name(k, pin).map(str::to_string) {
                stmts.push(Stmt::Write {
                    target: q,
                    kind: crate::program::WriteKind::Assign,
                    value,
                    span,
                });
            }
        }
        self.push_block(stmts, span);
    }
}
