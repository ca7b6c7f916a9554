//! Function-block calls in Structured Text, as matiec runs them: TON/TOF, R_TRIG/F_TRIG, SR/RS, and TP and the counters as unconstrained outputs; their inputs, their `=>` outputs and the hidden bits they write.

use std::collections::BTreeMap;

use super::{Lowering, Sym, Ty};
use crate::diag::Span;
use crate::iec::StError;
use crate::iec::ast::{self, Arg, ExprKind};
use crate::program::{BoolExpr, EdgeKind, Fresh, Memory, Preset, Stmt, Timer, WriteKind};

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
            "CTU" | "CTD" | "CTUD" => Fb::Counter,
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
            (Fb::Counter, "CTU") => &["CU", "R", "PV"],
            (Fb::Counter, "CTD") => &["CD", "LD", "PV"],
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
        let mut inputs: BTreeMap<String, &ast::Expr> = BTreeMap::new();
        let mut outputs = Vec::new();
        let order = fb.inputs(&ty);
        for (k, a) in args.iter().enumerate() {
            match a {
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
        let input = |l: &mut Self, pin: &str| -> BoolExpr {
            match (inputs.get(pin), &given) {
                (_, Some((p, v))) if *p == pin => v.clone(),
                (Some(e), _) => l.bool_expr(e),
                (None, _) => {
                    l.refuse(span, &format!("a call of {inst} without {pin}"), "an input kept from an earlier call is not modelled; give every input in each call");
                    BoolExpr::Const(false)
                }
            }
        };
        match fb {
            Fb::Ton | Fb::Tof => {
                let v = input(self, "IN");
                let preset = match inputs.get("PT").map(|e| &e.kind) {
                    Some(ExprKind::Time(us)) => Preset::iec(*us, self.cycle_us),
                    Some(ExprKind::Var(id)) if self.duration(id).is_some() => {
                        Preset::iec(self.duration(id).unwrap_or(0), self.cycle_us)
                    }
                    Some(_) => Preset::Variable(format!("{inst}.PT")),
                    None => {
                        self.refuse(
                            span,
                            &format!("a call of {inst} without PT"),
                            "give the preset in each call",
                        );
                        Preset::Variable(format!("{inst}.PT"))
                    }
                };
                let timer = Timer {
                    on_delay: fb == Fb::Ton,
                    keyword: ty.clone(),
                    accumulator: inst.clone(),
                    preset,
                    input: v,
                    span,
                };
                let q = self.hidden(&inst, "Q");
                out.push(Stmt::Write {
                    target: q,
                    kind: WriteKind::Assign,
                    value: BoolExpr::Timer(Box::new(timer)),
                    span,
                });
            }
            Fb::RTrig | Fb::FTrig => {
                // matiec: Q := CLK AND NOT M; M := CLK (F_TRIG: CLK negated).
                let v = input(self, "CLK");
                let clk = if fb == Fb::FTrig { BoolExpr::negate(v) } else { v };
                let memory =
                    Memory { base: format!("{inst}_M"), element: ty.clone(), index: self.edges };
                self.edges += 1;
                let q = self.hidden(&inst, "Q");
                let value = BoolExpr::Edge { kind: EdgeKind::Rising, input: Box::new(clk), memory };
                out.push(Stmt::Write { target: q, kind: WriteKind::Assign, value, span });
            }
            Fb::Sr | Fb::Rs => {
                // SR: Q1 := S1 OR (NOT R AND Q1) (reset, then set); RS: Q1 := NOT R1 AND (S OR Q1).
                // Both inputs are read when the call starts, before Q1 changes.
                let (set, reset) = if fb == Fb::Sr { ("S1", "R") } else { ("S", "R1") };
                let s = input(self, set);
                let r = input(self, reset);
                let (s, r) = (self.temp(&mut out, s), self.temp(&mut out, r));
                let q = self.hidden(&inst, "Q1");
                let set = Stmt::Write { target: q.clone(), kind: WriteKind::Set, value: s, span };
                let reset = Stmt::Write { target: q, kind: WriteKind::Reset, value: r, span };
                if fb == Fb::Sr { out.extend([reset, set]) } else { out.extend([set, reset]) }
            }
            Fb::Tp | Fb::Counter => {
                for (pin, e) in &inputs {
                    if !matches!(e.kind, ExprKind::Time(_) | ExprKind::Int(_))
                        && pin != "PT"
                        && pin != "PV"
                    {
                        let _ = self.bool_expr(e);
                    }
                }
                let what = if fb == Fb::Tp { "the pulse timer" } else { "the counter" };
                for pin in fb.outputs() {
                    let q = self.hidden(&inst, pin);
                    let fresh = Fresh {
                        base: format!("{ty}_{inst}_{pin}"),
                        keyword: ty.clone(),
                        why: format!("{what} {inst} ({ty}) is not expressible in the algebra"),
                        span,
                    };
                    out.push(Stmt::Write {
                        target: q,
                        kind: WriteKind::Assign,
                        value: BoolExpr::Fresh(Box::new(fresh)),
                        span,
                    });
                }
            }
        }
        for (pin, negated, target) in outputs {
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
        out
    }

    /// The value of a `CONSTANT` TIME variable.
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

    /// A write of a lowered value into the BOOL variable `target`.
    pub(super) fn write_value(
        &mut self,
        target: &ast::Expr,
        kind: WriteKind,
        value: BoolExpr,
        span: Span,
    ) -> Vec<Stmt> {
        let ExprKind::Var(id) = &target.kind else {
            self.refuse(
                target.span,
                "a write into a member or array element",
                "write it to a BOOL variable",
            );
            return Vec::new();
        };
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
