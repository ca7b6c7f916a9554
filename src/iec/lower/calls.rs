//! Function-block calls in Structured Text, as matiec runs them: TON/TOF, TP, R_TRIG/F_TRIG, SR/RS and the counters CTU/CTD/CTUD; their inputs, their `=>` outputs and the hidden bits and integers they write.

use std::collections::BTreeMap;

use super::{Lowering, Sym, Ty};
use crate::diag::Span;
use crate::iec::StError;
use crate::iec::ast::{self, Arg, ExprKind};
use crate::program::{
    BoolExpr, EdgeKind, Fresh, IntExpr, IntType, IntVar, Memory, Preset, Stmt, Timer, WriteKind,
    library,
};
use library::Elapsed;

/// Function-block types the lowering knows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Fb {
    Ton,
    Tof,
    Tp,
    RTrig,
    FTrig,
    Sr,
    Rs,
    Counter,
}

impl Fb {
    pub(super) fn of(ty: &str) -> Option<Fb> {
        Some(match ty {
            "TON" => Fb::Ton,
            "TOF" => Fb::Tof,
            "TP" => Fb::Tp,
            "R_TRIG" => Fb::RTrig,
            "F_TRIG" => Fb::FTrig,
            "SR" => Fb::Sr,
            "RS" => Fb::Rs,
            "CTU" | "CTD" | "CTUD" | "CTU_DINT" | "CTD_DINT" | "CTUD_DINT" | "CTU_UDINT"
            | "CTD_UDINT" | "CTUD_UDINT" | "CTU_LINT" | "CTD_LINT" | "CTUD_LINT" | "CTU_ULINT"
            | "CTD_ULINT" | "CTUD_ULINT" => Fb::Counter,
            _ => return None,
        })
    }

    /// Its inputs in declaration order (what a positional argument gives), for the type
    /// `ty` (the counters differ).
    pub(super) fn inputs(self, ty: &str) -> &'static [&'static str] {
        match (self, ty) {
            (Fb::Ton | Fb::Tof | Fb::Tp, _) => &["IN", "PT"],
            (Fb::RTrig | Fb::FTrig, _) => &["CLK"],
            (Fb::Sr, _) => &["S1", "R"],
            (Fb::Rs, _) => &["S", "R1"],
            (Fb::Counter, t) if t.starts_with("CTUD") => &["CU", "CD", "R", "LD", "PV"],
            (Fb::Counter, t) if t.starts_with("CTU") => &["CU", "R", "PV"],
            (Fb::Counter, t) if t.starts_with("CTD") => &["CD", "LD", "PV"],
            (Fb::Counter, _) => &["CU", "CD", "R", "LD", "PV"],
        }
    }

    /// Its Boolean outputs.
    pub(super) fn outputs(self) -> &'static [&'static str] {
        match self {
            Fb::Sr | Fb::Rs => &["Q1"],
            Fb::Counter => &["Q", "QU", "QD"],
            _ => &["Q"],
        }
    }
}

impl Lowering<'_> {
    /// The hidden bit of an FB instance's output.
    pub(super) fn hidden(&mut self, inst: &str, pin: &str) -> String {
        let key = (inst.to_ascii_uppercase(), pin.to_string());
        if let Some(n) = self.hidden.get(&key) {
            return n.clone();
        }
        let n = self.unique(&format!("{inst}_{pin}"));
        self.hidden.insert(key, n.clone());
        n
    }

    pub(super) fn call(&mut self, callee: &ast::Expr, args: &[Arg], span: Span) -> Vec<Stmt> {
        self.call_with(callee, args, None, span)
    }

    /// The call `callee(args)`, with the input `given.0` set to the lowered value
    /// `given.1` (an Instruction List operator such as `CLK R1` gives the current result).
    pub(super) fn call_with(
        &mut self,
        callee: &ast::Expr,
        args: &[Arg],
        given: Option<(&str, BoolExpr)>,
        span: Span,
    ) -> Vec<Stmt> {
        let ExprKind::Var(id) = &callee.kind else {
            self.refuse(
                callee.span,
                "calling a member or an array element",
                "call a declared instance",
            );
            return Vec::new();
        };
        if id.name.contains('.') {
            let what = format!("the method call `{}(…)`", id.name);
            self.refuse(id.span, &what, "methods (object-oriented extensions) are not read");
            return Vec::new();
        }
        let Some(sym) = self.lookup(id) else { return Vec::new() };
        if let Ty::User(fb) = &sym.ty {
            if given.is_some() {
                self.refuse(
                    span,
                    &format!("an IL input operator on the {fb} instance `{}`", sym.name),
                    "call it with `CAL inst(…)`",
                );
                return Vec::new();
            }
            return self.user_call(&sym.name, fb, args, span);
        }
        const ELEMENTARY: &[&str] = &[
            "BOOL",
            "SINT",
            "INT",
            "DINT",
            "LINT",
            "USINT",
            "UINT",
            "UDINT",
            "ULINT",
            "BYTE",
            "WORD",
            "DWORD",
            "LWORD",
            "REAL",
            "LREAL",
            "TIME",
            "DATE",
            "TOD",
            "DT",
            "STRING",
            "WSTRING",
            "TIME_OF_DAY",
            "DATE_AND_TIME",
            "LTIME",
            "CHAR",
            "WCHAR",
        ];
        if let Ty::Other(t) = &sym.ty
            && !ELEMENTARY.contains(&t.to_ascii_uppercase().as_str())
        {
            self.errors.push(StError::new(
                id.span,
                format!(
                    "`{}` is an instance of `{t}`, a function block this file does not declare",
                    sym.name
                ),
                format!("declare it (`FUNCTION_BLOCK {t} … END_FUNCTION_BLOCK`)"),
            ));
            return Vec::new();
        }
        let Ty::Fb(fb, ty) = sym.ty else {
            let what = format!(
                "calling `{}` (a {})",
                sym.name,
                match &sym.ty {
                    Ty::Other(t) => t.as_str(),
                    _ => "BOOL",
                }
            );
            self.refuse(id.span, &what, "only instances of TON, TOF, TP, R_TRIG, F_TRIG, SR, RS and the counters are modelled");
            return Vec::new();
        };
        let inst = sym.name.clone();
        let en = self.enable(&inst, args);
        let mut inputs: BTreeMap<String, &ast::Expr> = BTreeMap::new();
        let mut outputs = Vec::new();
        let order = fb.inputs(&ty);
        for (k, a) in args.iter().enumerate() {
            match a {
                _ if super::enable::is_en_eno(a) => {}
                Arg::Input(n, e) => {
                    inputs.insert(n.key(), e);
                }
                Arg::Output(n, neg, target) => outputs.push((n, *neg, target)),
                // A non-formal call gives the inputs in their declaration order.
                Arg::Positional(e) => match order.get(k) {
                    Some(pin) => {
                        inputs.insert(pin.to_string(), e);
                    }
                    None => self.errors.push(StError::new(
                        e.span,
                        format!("{ty} has {} inputs; this is argument {}", order.len(), k + 1),
                        format!("{ty}'s inputs are {}", order.join(", ")),
                    )),
                },
            }
        }
        let mut out = Vec::new();
        // The inputs it keeps are written whatever its EN.
        let kept = std::mem::replace(&mut self.kept_writes, en.guarded().then(Vec::new));
        // The value a call gives an input (`None`: the call leaves it out).
        let input = |l: &mut Self, pin: &str| -> Option<BoolExpr> {
            match (inputs.get(pin), &given) {
                (_, Some((p, v))) if *p == pin => Some(v.clone()),
                (Some(e), _) => Some(l.bool_expr(e)),
                (None, _) => None,
            }
        };
        *self.called.entry(inst.clone()).or_default() += 1;
        match fb {
            Fb::Ton | Fb::Tof => {
                let v = self.kept_input(&inst, "IN", &input, &mut out, span);
                let preset = match inputs.get("PT").map(|e| &e.kind) {
                    Some(ExprKind::Time(us)) => Preset::iec(*us, self.cycle_us),
                    Some(ExprKind::Var(id)) if self.duration(id).is_some() => {
                        Preset::iec(self.duration(id).unwrap_or(0), self.cycle_us)
                    }
                    Some(ExprKind::Var(id)) => self.variable_preset(id, &inst),
                    Some(_) => Preset::Variable { name: format!("{inst}.PT"), why: None },
                    // Left out: the value the instance keeps from its last call, given
                    // by a call that ran for sure earlier in the scan, or at every call.
                    None if self.known.presets.contains_key(&inst) => {
                        self.known.presets[&inst].clone()
                    }
                    None => match self.kept_pt(&inst) {
                        Ok(us) => Preset::iec(us, self.cycle_us),
                        Err(why) => Preset::Variable { name: format!("{inst}.PT"), why },
                    },
                };
                let kind = if fb == Fb::Ton { Elapsed::On } else { Elapsed::Off };
                let pt = inputs.get("PT").copied();
                let value = match self.elapsed_timer(&inst, kind, pt, &v, &mut out, span) {
                    Some(q) => q,
                    None => BoolExpr::Timer(Box::new(Timer {
                        on_delay: fb == Fb::Ton,
                        keyword: ty.clone(),
                        accumulator: inst.clone(),
                        preset,
                        input: v,
                        span,
                        called: true,
                    })),
                };
                let q = self.hidden(&inst, "Q");
                out.push(Stmt::Write { target: q, kind: WriteKind::Assign, value, span });
            }
            Fb::RTrig | Fb::FTrig => {
                // matiec: Q := CLK AND NOT M; M := CLK (F_TRIG: CLK negated).
                let v = self.kept_input(&inst, "CLK", &input, &mut out, span);
                let clk = if fb == Fb::FTrig { BoolExpr::negate(v) } else { v };
                let value = self.edge(&inst, "M", &ty, clk, &mut out, span);
                let q = self.hidden(&inst, "Q");
                out.push(Stmt::Write { target: q, kind: WriteKind::Assign, value, span });
            }
            Fb::Sr | Fb::Rs => {
                // SR: Q1 := S1 OR (NOT R AND Q1) (reset, then set); RS: Q1 := NOT R1 AND (S OR Q1).
                // Both inputs are read when the call starts, before Q1 changes.
                let (set, reset) = if fb == Fb::Sr { ("S1", "R") } else { ("S", "R1") };
                let s = self.kept_input(&inst, set, &input, &mut out, span);
                let r = self.kept_input(&inst, reset, &input, &mut out, span);
                let (s, r) = (self.temp(&mut out, s), self.temp(&mut out, r));
                let q = self.hidden(&inst, "Q1");
                let set = Stmt::Write { target: q.clone(), kind: WriteKind::Set, value: s, span };
                let reset = Stmt::Write { target: q, kind: WriteKind::Reset, value: r, span };
                if fb == Fb::Sr { out.extend([reset, set]) } else { out.extend([set, reset]) }
            }
            Fb::Tp => out.extend(self.pulse(&inst, &ty, &inputs, &input, span)),
            Fb::Counter => out.extend(self.counter(&inst, &ty, &inputs, &input, span)),
        }
        let before = std::mem::replace(&mut self.kept_writes, kept).unwrap_or_default();
        let body = out;
        let mut out = Vec::new();
        for (pin, negated, target) in outputs {
            if fb == Fb::Counter && pin.key() == "CV" && !negated {
                out.extend(self.counter_output(&inst, &ty, target, span));
                continue;
            }
            if matches!(fb, Fb::Ton | Fb::Tof | Fb::Tp) && pin.key() == "ET" && !negated {
                out.extend(self.elapsed_output(&inst, target, span));
                continue;
            }
            if !fb.outputs().contains(&pin.key().as_str()) {
                self.refuse(
                    pin.span,
                    &format!("the output {} of {ty}", pin.name),
                    "only its Boolean outputs are modelled",
                );
                continue;
            }
            let q = BoolExpr::var(&self.hidden(&inst, &pin.key()));
            let value = if negated { BoolExpr::negate(q) } else { q };
            out.extend(self.assign_value(target, value, span));
        }
        self.enabled_call(en, [before, body, out], span)
    }

    /// A call of the TON or TOF `inst` with the preset `pt` and `IN` `v` whose `ET` is
    /// read: the statements that update its count, then `Some(Q)` from it; `None` where
    /// its `ET` is not read or not computed (the timer of the algebra gives `Q`).
    fn elapsed_timer(
        &mut self,
        inst: &str,
        kind: Elapsed,
        pt: Option<&ast::Expr>,
        v: &BoolExpr,
        out: &mut Vec<Stmt>,
        span: Span,
    ) -> Option<BoolExpr> {
        let key = inst.to_ascii_uppercase();
        // In a body under EN its state is the program's (the caller's simulator reads it).
        if self.enable.is_some() {
            self.elapsed.entry(key.clone()).or_default();
        }
        if !self.elapsed.contains_key(&key) {
            return None;
        }
        let mut stmts = Vec::new();
        let v = self.temp(&mut stmts, v.clone());
        let q = self.elapsed_call(inst, kind, pt, &v, &mut stmts, span)?;
        out.extend(stmts);
        Some(q)
    }

    /// The preset of a timer whose `PT` is the variable `id`, not one known duration:
    /// the variable with why it may change.
    fn variable_preset(&self, id: &ast::Ident, inst: &str) -> Preset {
        match self.syms.get(&id.key()) {
            Some(sym) => Preset::Variable {
                name: sym.name.clone(),
                why: self.time_why.get(&sym.name).cloned(),
            },
            None => Preset::Variable { name: format!("{inst}.PT"), why: None },
        }
    }

    /// The value of a `CONSTANT` TIME variable, or of one constant in fact.
    fn duration(&self, id: &ast::Ident) -> Option<u64> {
        let sym = self.syms.get(&id.key())?;
        self.durations.get(&sym.name).copied()
    }

    /// A scan-local value computed here (so later writes do not change what it read).
    pub(super) fn temp(&mut self, out: &mut Vec<Stmt>, value: BoolExpr) -> BoolExpr {
        let temp = self.next_temp;
        self.next_temp += 1;
        out.push(Stmt::Let { temp, value });
        BoolExpr::Temp(temp)
    }

    /// `target := value` for a value already lowered (an FB output given with `=>`).
    pub(super) fn assign_value(
        &mut self,
        target: &ast::Expr,
        value: BoolExpr,
        span: Span,
    ) -> Vec<Stmt> {
        self.write_value(target, WriteKind::Assign, value, span)
    }

    /// The variable `target` names, where a write goes (`expected`: what it should be,
    /// "a BOOL variable"); `None` (refused with a located error) for a member or array
    /// element.
    pub(super) fn written_variable<'e>(
        &mut self,
        target: &'e ast::Expr,
        expected: &str,
    ) -> Option<&'e ast::Ident> {
        if let ExprKind::Var(id) = &target.kind {
            return Some(id);
        }
        self.refuse(
            target.span,
            "a write into a member or array element",
            &format!("write it to {expected}"),
        );
        None
    }

    /// A write of a lowered value into the BOOL variable `target`.
    pub(super) fn write_value(
        &mut self,
        target: &ast::Expr,
        kind: WriteKind,
        value: BoolExpr,
        span: Span,
    ) -> Vec<Stmt> {
        let Some(id) = self.written_variable(target, "a BOOL variable") else { return Vec::new() };
        match self.lookup(id) {
            Some(Sym { ty: Ty::Bool, name, .. }) if !self.inputs.contains(&name) => {
                vec![Stmt::Write { target: name, kind, value, span }]
            }
            Some(_) => {
                self.errors.push(StError::new(
                    id.span,
                    format!("`{}` is not a BOOL the program writes", id.name),
                    "expected a BOOL variable",
                ));
                Vec::new()
            }
            None => Vec::new(),
        }
    }
}

/// How a call reads a Boolean input of the instance being called: its value, or `None`
/// where the call leaves it out.
type PinReader<'a, 's> = &'a dyn Fn(&mut Lowering<'s>, &str) -> Option<BoolExpr>;

impl<'s> Lowering<'s> {
    /// The count of the counter instance `inst` of type `t` (an integer of the scan
    /// model, `{inst}_CV`, from 0).
    pub(super) fn counter_value(&mut self, inst: &str, t: IntType) -> String {
        self.hidden_int(inst, "CV", t)
    }

    /// The hidden integer `pin` of the instance `inst` (`{inst}_{pin}`, 0 at first), of
    /// type `t`.
    pub(super) fn hidden_int(&mut self, inst: &str, pin: &str, t: IntType) -> String {
        let key = (inst.to_ascii_uppercase(), pin.to_string());
        if let Some(n) = self.hidden.get(&key) {
            return n.clone();
        }
        let n = self.unique(&format!("{inst}_{pin}"));
        self.hidden.insert(key, n.clone());
        self.ints.insert(n.clone(), IntVar { ty: t, input: false, init: 0 });
        n
    }

    /// A Boolean input of a standard function block: as given, else the value its last
    /// call gave (matiec keeps an FB's inputs between calls; FALSE before any call gives
    /// it), kept in a hidden bit that every call giving it writes once some call of the
    /// instance leaves it out.
    fn kept_input(
        &mut self,
        inst: &str,
        pin: &str,
        read: PinReader<'_, 's>,
        out: &mut Vec<Stmt>,
        span: Span,
    ) -> BoolExpr {
        let key = (inst.to_ascii_uppercase(), pin.to_string());
        match read(self, pin) {
            Some(v) if self.omitted.contains(&key) => {
                let mut writes = Vec::new();
                let v = self.temp(&mut writes, v);
                let kept = self.hidden(inst, &format!("{pin}_in"));
                writes.push(Stmt::Write {
                    target: kept,
                    kind: WriteKind::Assign,
                    value: v.clone(),
                    span,
                });
                self.keep(out, writes);
                v
            }
            Some(v) => v,
            None => {
                self.omitted.insert(key);
                BoolExpr::var(&self.hidden(inst, &format!("{pin}_in")))
            }
        }
    }

    /// An integer input of a standard function block (a counter's `PV`, of type `t`): as
    /// given, else the value its last call gave (0 before any call gives it), kept in a
    /// hidden integer like [`Self::kept_input`]'s bits; `Err`: why it is not computed.
    fn kept_int_input(
        &mut self,
        inst: &str,
        pin: &str,
        given: Option<&ast::Expr>,
        t: IntType,
        out: &mut Vec<Stmt>,
        span: Span,
    ) -> Result<IntExpr, String> {
        let key = (inst.to_ascii_uppercase(), pin.to_string());
        let kept = |l: &mut Self| l.hidden_int(inst, &format!("{pin}_in"), t);
        match given {
            Some(e) if self.omitted.contains(&key) => {
                let target = kept(self);
                match self.int_input(e, t) {
                    Ok(value) => {
                        let write = Stmt::SetInt { target: target.clone(), value, span };
                        self.keep(out, [write]);
                        Ok(IntExpr::Var(target))
                    }
                    Err(why) => {
                        self.make_opaque(&target, why.clone(), e.span);
                        Err(why)
                    }
                }
            }
            Some(e) => self.int_input(e, t),
            None => {
                self.omitted.insert(key);
                let kept = kept(self);
                match self.opaque.get(&kept) {
                    Some((why, _)) => Err(why.clone()),
                    None => Ok(IntExpr::Var(kept)),
                }
            }
        }
    }

    /// The rising edge of `input` at a call of the instance `inst` (of type `ty`), over
    /// the instance's memory `pin` (matiec: `input AND NOT M; M := input`). An instance
    /// called once per scan: a one-shot of the scan model; called more often: the memory
    /// a hidden bit each call reads and then writes, so that a later call in the same
    /// scan sees what the earlier one left.
    fn edge(
        &mut self,
        inst: &str,
        pin: &str,
        ty: &str,
        input: BoolExpr,
        out: &mut Vec<Stmt>,
        span: Span,
    ) -> BoolExpr {
        if self.call_by_call(&inst.to_ascii_uppercase()) {
            let input = self.temp(out, input);
            let m = self.hidden(inst, pin);
            let before = self.temp(out, BoolExpr::var(&m));
            out.push(Stmt::Write {
                target: m,
                kind: WriteKind::Assign,
                value: input.clone(),
                span,
            });
            return BoolExpr::and(input, BoolExpr::negate(before));
        }
        let memory =
            Memory { base: format!("{inst}_{pin}"), element: ty.to_string(), index: self.edges };
        self.edges += 1;
        BoolExpr::Edge { kind: EdgeKind::Rising, input: Box::new(input), memory: Box::new(memory) }
    }

    /// The facts of the `PT` of the timer instance `inst` (its name in the scan model),
    /// declared at `decl` (`POU.INSTANCE`), for the calls that leave it out.
    pub(super) fn declare_timer(&mut self, inst: &str, decl: &str) {
        let pin = format!("{inst}.PT");
        match self.time_facts.values.get(&(decl.to_string(), "PT".to_string())) {
            Some(Ok(us)) => {
                self.durations.insert(pin, *us);
            }
            Some(Err(why)) => {
                self.time_why.insert(pin, why.clone());
            }
            None => {}
        }
    }

    /// The `PT` a call of the timer `inst` leaves out: the duration the instance holds at
    /// every call (T#0s, or the one literal every call that gives it gives), else why it
    /// may hold another.
    pub(super) fn kept_pt(&self, inst: &str) -> Result<u64, Option<String>> {
        let pin = format!("{inst}.PT");
        match self.durations.get(&pin) {
            Some(us) => Ok(*us),
            None => Err(self.time_why.get(&pin).cloned()),
        }
    }

    /// A call of the counter `inst` (CTU, CTD, CTUD and their typed variants), as
    /// matiec's library computes it: a rising edge of `CU`/`CD` counts, within
    /// `0 … PV`; `R` resets to 0, `LD` loads `PV`.
    pub(super) fn counter(
        &mut self,
        inst: &str,
        ty: &str,
        inputs: &BTreeMap<String, &ast::Expr>,
        read: PinReader<'_, 's>,
        span: Span,
    ) -> Vec<Stmt> {
        let kind = ty.split('_').next().unwrap_or(ty).to_string();
        let pv = inputs.get("PV").copied();
        let t = super::ints::counter_type(ty);
        let mut out = Vec::new();
        let value = match t {
            Some(t) => self.kept_int_input(inst, "PV", pv, t, &mut out, span).map(|v| (t, v)),
            None => Err(format!("{ty} counts in 64 bits, which ii-prove does not compute")),
        };
        let (t, pv) = match value {
            Ok(v) => v,
            Err(why) => {
                // Not computed: the outputs are unconstrained, the count opaque.
                for (pin, e) in inputs {
                    if pin != "PV" {
                        let _ = self.bool_expr(e);
                    }
                }
                if let Some(t) = t {
                    let cv = self.counter_value(inst, t);
                    self.make_opaque(&cv, why.clone(), span);
                }
                let why = format!("the counter {inst} ({ty}) is not computed: {why}");
                for pin in Fb::Counter.outputs() {
                    out.push(self.unconstrained_output(inst, ty, pin, &why, span));
                }
                return out;
            }
        };
        let cv_name = self.counter_value(inst, t);
        let no = || BoolExpr::Const(false);
        let pin = |l: &mut Self, out: &mut Vec<Stmt>, pin: &str| {
            let v = l.kept_input(inst, pin, read, out, span);
            l.temp(out, v)
        };
        let edge = |l: &mut Self, out: &mut Vec<Stmt>, p: &str, v: BoolExpr| {
            let e = l.edge(inst, &format!("{p}_T"), ty, v, out, span);
            l.temp(out, e)
        };
        let kind = library::Counter::of(&kind).unwrap_or(library::Counter::UpDown);
        let (edges, r, ld) = match kind {
            library::Counter::Up => {
                let cu = pin(self, &mut out, "CU");
                let r = pin(self, &mut out, "R");
                ((edge(self, &mut out, "CU", cu), no()), r, no())
            }
            library::Counter::Down => {
                let cd = pin(self, &mut out, "CD");
                let ld = pin(self, &mut out, "LD");
                ((no(), edge(self, &mut out, "CD", cd)), no(), ld)
            }
            library::Counter::UpDown => {
                let cu = pin(self, &mut out, "CU");
                let cd = pin(self, &mut out, "CD");
                let r = pin(self, &mut out, "R");
                let ld = pin(self, &mut out, "LD");
                // matiec's CTUD: CD_T(CD); CU_T(CU).
                let cd = edge(self, &mut out, "CD", cd);
                let cu = edge(self, &mut out, "CU", cu);
                ((cu, cd), r, ld)
            }
        };
        let (next, outputs) = library::counter(kind, t, &cv_name, pv, edges, r, ld);
        out.push(Stmt::SetInt { target: cv_name, value: next, span });
        for (pin, value) in outputs {
            let q = self.hidden(inst, pin);
            out.push(Stmt::Write { target: q, kind: WriteKind::Assign, value, span });
        }
        // CTU and CTD have one output, `Q`; the others of the shared list stay unwritten.
        out
    }

    /// The write of an unconstrained value into the output `pin` of `inst` (of type `ty`),
    /// for the reason `why`.
    fn unconstrained_output(
        &mut self,
        inst: &str,
        ty: &str,
        pin: &str,
        why: &str,
        span: Span,
    ) -> Stmt {
        let fresh = Fresh {
            base: format!("{ty}_{inst}_{pin}"),
            keyword: ty.to_string(),
            why: why.to_string(),
            span,
            peripheral: false,
        };
        let target = self.hidden(inst, pin);
        Stmt::Write {
            target,
            kind: WriteKind::Assign,
            value: BoolExpr::Fresh(Box::new(fresh)),
            span,
        }
    }

    /// `CV => target`: the count into an integer variable of its type.
    fn counter_output(
        &mut self,
        inst: &str,
        ty: &str,
        target: &ast::Expr,
        span: Span,
    ) -> Vec<Stmt> {
        let Some(t) = super::ints::counter_type(ty) else {
            if let ExprKind::Var(id) = &target.kind
                && let Some(Sym { ty: Ty::Int(_), name, .. }) = self.lookup(id)
            {
                self.make_opaque(&name, format!("it takes the 64-bit count of {inst}"), span);
            }
            return Vec::new();
        };
        let cv = self.counter_value(inst, t);
        self.int_copy(target, &cv, t, span)
    }

    /// A call of the pulse timer `inst` as matiec's library runs it: a rising edge of
    /// `IN` while idle starts a pulse of `Q` for `PT` (at least one scan), which no edge
    /// restarts; after it, `Q` stays off until `IN` falls. In the scan model: `Q`
    /// (running) and a hidden `DONE` bit, the edge's memory, and an on-delay timer of
    /// `Q` as it stood at the previous scan.
    pub(super) fn pulse(
        &mut self,
        inst: &str,
        ty: &str,
        inputs: &BTreeMap<String, &ast::Expr>,
        read: PinReader<'_, 's>,
        span: Span,
    ) -> Vec<Stmt> {
        let mut out = Vec::new();
        let v = self.kept_input(inst, "IN", read, &mut out, span);
        let input = self.temp(&mut out, v);
        let q = self.hidden(inst, "Q");
        // Called more than once in a scan, the second call sees the time of the first,
        // which the scan model's count of scans does not: the pulse is followed call by
        // call, as where its `ET` is read (lowering runs again with it).
        let key = inst.to_ascii_uppercase();
        if self.call_by_call(&key) {
            self.elapsed.entry(key.clone()).or_default();
        }
        let given = inputs.get("PT").copied();
        if let Some(value) = self.elapsed_call(inst, Elapsed::Pulse, given, &input, &mut out, span)
        {
            out.push(Stmt::Write { target: q, kind: WriteKind::Assign, value, span });
            return out;
        }
        let pt = match inputs.get("PT").map(|e| &e.kind) {
            Some(ExprKind::Time(us)) => Ok(*us),
            Some(ExprKind::Var(id)) => {
                self.duration(id).ok_or_else(|| match self.variable_preset(id, inst) {
                    Preset::Variable { name, why: Some(why) } => format!(
                        "the pulse timer {inst} has its preset from the variable {name}, which \
                         is not a constant: {why}"
                    ),
                    _ => format!(
                        "the pulse timer {inst} has a preset that is not a constant duration"
                    ),
                })
            }
            Some(_) => {
                Err(format!("the pulse timer {inst} has a preset that is not a constant duration"))
            }
            None => self.kept_pt(inst).map_err(|why| match why {
                Some(why) => format!(
                    "the pulse timer {inst} is called without PT, and the PT it keeps is not \
                     a constant: {why}"
                ),
                None => format!("the pulse timer {inst} keeps a PT that is not a constant"),
            }),
        };
        let pt = match pt {
            Ok(pt) => pt,
            Err(why) => {
                out.push(self.unconstrained_output(inst, ty, "Q", &why, span));
                return out;
            }
        };
        let done = self.hidden(inst, "DONE");
        // Not followed call by call (its preset is not a duration literal).
        if self.multi.contains(&key) && pt > 0 {
            let why = format!(
                "the pulse timer {inst} is called more than once in a scan, and its pulse \
                 ends at the first call one PT after it started, which is not modelled"
            );
            out.push(self.unconstrained_output(inst, ty, "Q", &why, span));
            return out;
        }
        let rise = self.edge(inst, "PREV_IN", ty, input.clone(), &mut out, span);
        let rise = self.temp(&mut out, rise);
        let pulse = library::Pulse {
            keyword: ty,
            instance: inst,
            q: &q,
            done: &done,
            pt_us: pt,
            cycle_us: self.cycle_us,
            span,
        };
        out.extend(pulse.call(input, rise, &mut |out, e| self.temp(out, e)));
        out
    }
}
