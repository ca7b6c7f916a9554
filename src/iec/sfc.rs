//! Sequential function charts as matiec runs them: a chart becomes the Structured Text of the scan matiec's C performs (`stage4/generate_c/generate_c_sfc.cc`) over hidden BOOLs, which the IEC front end then lowers like any body.
//!
//! Each scan, in matiec's order: every step's state is kept (`S_PREV`) and the time of
//! an active step grows by the scan's cycle; every action's `state`, `set` and `reset`
//! are cleared; each transition whose steps are all active evaluates its condition (in
//! priority order; one with a priority leaves its steps at once); the transitions that
//! fired leave their steps, then enter their next ones; each step's associations run
//! (`active`, `activated`, `desactivated` from `S_X` and `S_PREV`): `N` writes while
//! active and clears on leaving, `S`/`R` mark the action set or reset, `P`/`P1` (`P0`)
//! are true the scan the step was entered (left) and false on every other scan, `D`
//! (`L`) after (before) the step has been active for the given time; an action's
//! stored set state joins its state; a BOOL variable that is an action is reset or set
//! by its `R`/`S` marks; each action with a body runs it while its state is true.
//!
//! A step's flag is `S_X` (what `S.X` reads). The time a step has been active counts
//! in scans, saturated at the longest time its associations compare with, so `D` and
//! `L` are exact at any cycle; they are refused where the time between two runs of the
//! chart is not one cycle (a function block's chart, whose instance may not run every
//! scan) or not known (the initial step's first scan: the runtime's clock at start-up).
//! `SD`, `DS` and `SL`, a step's time `S.T` in an expression, and Instruction List in a
//! chart are refused with located errors.

use std::collections::{BTreeMap, BTreeSet};

use super::StError;
use super::ast::{
    Association, Body, Expr, ExprKind, Ident, Pou, PouKind, Sfc, Stmt, StmtKind, Unit, VarClass,
    VarDecl,
};
use crate::diag::Span;

/// `unit` with every chart turned into Structured Text (`None`: it has none).
pub fn desugar(unit: &Unit, cycle_us: u64) -> Result<Option<Unit>, Vec<StError>> {
    if !unit.pous.iter().any(|p| matches!(p.body, Body::Sfc(_))) {
        return Ok(None);
    }
    let mut out = unit.clone();
    let mut errors = Vec::new();
    for pou in &mut out.pous {
        if let Body::Sfc(sfc) = &pou.body {
            let sfc = sfc.clone();
            match Chart::new(pou, &sfc, cycle_us).and_then(|c| c.lower()) {
                Ok((vars, stmts)) => {
                    pou.vars.extend(vars);
                    pou.body = Body::St(stmts);
                }
                Err(e) => errors.extend(e),
            }
        }
    }
    if errors.is_empty() { Ok(Some(out)) } else { Err(errors) }
}

/// What a qualifier writes: a BOOL variable itself, or an action's state.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Kind {
    Variable,
    Body,
}

/// A step's flag (`S_X`), its state at the scan's start (`S_PREV`), and its time in
/// scans with the count it saturates at (only for a step with `D` or `L`).
type StepBits = (String, String, Option<(String, u64)>);

struct Chart<'a> {
    pou: &'a Pou,
    sfc: &'a Sfc,
    cycle_us: u64,
    /// Names taken (upper-case): the POU's variables and the names made so far.
    taken: BTreeSet<String>,
    /// Step (upper-case) → its hidden bits.
    steps: BTreeMap<String, StepBits>,
    /// Action (upper-case) → what it is and its hidden bits (state, stored, set, reset).
    actions: BTreeMap<String, (Kind, String, [String; 4])>,
    /// The actions in matiec's list order: bodies, then variables by first association.
    order: Vec<String>,
    vars: Vec<VarDecl>,
    errors: Vec<StError>,
}

fn var(name: &str, span: Span) -> Expr {
    Expr { kind: ExprKind::Var(Ident { name: name.to_string(), span }), span }
}

fn not(e: Expr) -> Expr {
    let span = e.span;
    Expr { kind: ExprKind::Unary(super::ast::UnOp::Not, Box::new(e)), span }
}

fn bin(op: super::ast::BinOp, a: Expr, b: Expr) -> Expr {
    let span = a.span;
    Expr { kind: ExprKind::Binary(op, Box::new(a), Box::new(b)), span }
}

fn and(a: Expr, b: Expr) -> Expr {
    bin(super::ast::BinOp::And, a, b)
}

fn lit(b: bool, span: Span) -> Expr {
    Expr { kind: ExprKind::Bool(b), span }
}

fn int(k: u64, span: Span) -> Expr {
    Expr { kind: ExprKind::Int(i128::from(k)), span }
}

fn assign(name: &str, value: Expr, span: Span) -> Stmt {
    Stmt { kind: StmtKind::Assign(var(name, span), value), span }
}

fn when(cond: Expr, then: Vec<Stmt>, otherwise: Vec<Stmt>) -> Stmt {
    let span = cond.span;
    Stmt { kind: StmtKind::If(vec![(cond, then)], otherwise), span }
}

impl<'a> Chart<'a> {
    fn new(pou: &'a Pou, sfc: &'a Sfc, cycle_us: u64) -> Result<Chart<'a>, Vec<StError>> {
        let mut c = Chart {
            pou,
            sfc,
            cycle_us,
            taken: pou.vars.iter().map(|v| v.name.key()).collect(),
            steps: BTreeMap::new(),
            actions: BTreeMap::new(),
            order: Vec::new(),
            vars: Vec::new(),
            errors: Vec::new(),
        };
        c.declare_steps();
        c.declare_actions();
        if c.errors.is_empty() { Ok(c) } else { Err(c.errors) }
    }

    fn error(&mut self, span: Span, message: impl Into<String>, label: impl Into<String>) {
        self.errors.push(StError::new(span, message, label));
    }

    /// A fresh name from `base`, declared as a hidden BOOL (or INT) of the chart.
    fn make(&mut self, base: &str, span: Span, ty: &str, init: Option<Expr>) -> String {
        let mut name = base.to_string();
        let mut k = 2;
        while self.taken.contains(&name.to_ascii_uppercase()) {
            name = format!("{base}_{k}");
            k += 1;
        }
        self.taken.insert(name.to_ascii_uppercase());
        self.vars.push(VarDecl {
            name: Ident { name: name.clone(), span },
            class: VarClass::Local,
            ty: Ident { name: ty.to_string(), span },
            init,
            retain: false,
            constant: false,
            location: None,
            made: true,
            range: None,
        });
        name
    }

    fn declare_steps(&mut self) {
        let sfc = self.sfc;
        if !sfc.steps.iter().any(|s| s.initial) {
            let span = sfc.steps.first().map_or(self.pou.name.span, |s| s.name.span);
            self.error(
                span,
                "a sequential function chart needs an INITIAL_STEP",
                "no initial step",
            );
        }
        for s in &sfc.steps {
            let key = s.name.key();
            if self.steps.contains_key(&key) || self.pou.vars.iter().any(|v| v.name.key() == key) {
                self.error(
                    s.name.span,
                    format!("`{}` is declared twice", s.name.name),
                    "a second step or variable of this name",
                );
                continue;
            }
            let x = self.make(
                &format!("{}_X", s.name.name),
                s.name.span,
                "BOOL",
                s.initial.then(|| lit(true, s.name.span)),
            );
            let prev = self.make(&format!("{}_PREV", s.name.name), s.name.span, "BOOL", None);
            let ticks = self.ticks(s);
            let time = ticks.map(|k| {
                {
                    // The smallest unsigned type that holds the count (fewer state bits).
                    let ty = if k <= 255 { "USINT" } else { "UINT" };
                    (self.make(&format!("{}_TICKS", s.name.name), s.name.span, ty, None), k)
                }
            });
            self.steps.insert(key, (x, prev, time));
        }
    }

    /// The longest time (in scans) step `s`'s timed associations compare with, if any.
    fn ticks(&mut self, s: &super::ast::Step) -> Option<u64> {
        let mut most = None;
        for a in &s.actions {
            let (Some(q), Some(t)) = (&a.qualifier, &a.time) else { continue };
            if !matches!(q.name.as_str(), "D" | "L") {
                self.error(
                    q.span,
                    format!("the qualifier `{}` is not modelled yet", q.name),
                    "an action's stored timing",
                );
                continue;
            }
            if self.pou.kind != PouKind::Program {
                self.error(q.span, "a timed qualifier in a function block's chart is not modelled yet: the step's time grows by the time between two calls of the instance, which need not be one cycle", "a timed qualifier");
                continue;
            }
            if s.initial {
                self.error(q.span, "a timed qualifier on the initial step is not modelled yet: its time at the first scan is the runtime's clock at start-up", "a timed qualifier on the initial step");
                continue;
            }
            let ExprKind::Time(us) = t.kind else {
                self.error(t.span, "a qualifier's time must be a duration literal here (a TIME variable is not modelled yet)", "not a literal");
                continue;
            };
            // T >= t with T = n·cycle: n >= ⌈t / cycle⌉.
            let n = us.div_ceil(self.cycle_us.max(1));
            if n > 30_000 {
                self.error(
                    t.span,
                    format!(
                        "{us} µs is more than 30,000 cycles of {} µs: not modelled",
                        self.cycle_us
                    ),
                    "too long",
                );
                continue;
            }
            most = Some(most.map_or(n, |m: u64| m.max(n)));
        }
        most
    }

    fn declare_actions(&mut self) {
        let sfc = self.sfc;
        for a in &sfc.actions {
            let key = a.name.key();
            if self.actions.contains_key(&key)
                || self.steps.contains_key(&key)
                || self.pou.vars.iter().any(|v| v.name.key() == key)
            {
                self.error(
                    a.name.span,
                    format!("`{}` is declared twice", a.name.name),
                    "a second action, step or variable of this name",
                );
                continue;
            }
            let bits = ["STATE", "STORED", "SET", "RESET"]
                .map(|b| self.make(&format!("{}_{b}", a.name.name), a.name.span, "BOOL", None));
            self.actions.insert(key.clone(), (Kind::Body, a.name.name.clone(), bits));
            self.order.push(key);
        }
        for s in &sfc.steps {
            for a in &s.actions {
                let key = a.action.key();
                if self.actions.contains_key(&key) {
                    continue;
                }
                match self.pou.vars.iter().find(|v| v.name.key() == key) {
                    Some(v) if v.ty.key() == "BOOL" => {
                        // A variable's state is read by nothing: only its marks are
                        // kept, where an `S` or `R` association sets them.
                        let marked = sfc.steps.iter().flat_map(|s| &s.actions).any(|x| {
                            x.action.key() == key
                                && x.qualifier
                                    .as_ref()
                                    .is_some_and(|q| ["S", "R"].contains(&q.name.as_str()))
                        });
                        let mut bits: [String; 4] = Default::default();
                        if marked {
                            for (k, b) in [(2, "SET"), (3, "RESET")] {
                                bits[k] = self.make(
                                    &format!("{}_{b}", a.action.name),
                                    a.action.span,
                                    "BOOL",
                                    None,
                                );
                            }
                        }
                        self.actions
                            .insert(key.clone(), (Kind::Variable, v.name.name.clone(), bits));
                        self.order.push(key);
                    }
                    Some(v) => {
                        let ty = v.ty.name.clone();
                        self.error(a.action.span, format!("the action `{}` is of type {ty}: only a BOOL variable can be an action", a.action.name), "not a BOOL");
                    }
                    None => {
                        let mut e = StError::new(
                            a.action.span,
                            format!("unknown action `{}`", a.action.name),
                            "no ACTION or BOOL variable of this name",
                        );
                        let names = sfc
                            .actions
                            .iter()
                            .map(|x| x.name.name.as_str())
                            .chain(self.pou.vars.iter().map(|v| v.name.name.as_str()));
                        if let Some(m) = crate::diag::did_you_mean(&a.action.name, names) {
                            e.notes.push(format!("did you mean `{m}`?"));
                        }
                        self.errors.push(e);
                    }
                }
            }
        }
    }

    /// The flag of step `id`, or an error.
    fn step(&mut self, id: &Ident) -> Option<StepBits> {
        if let Some(s) = self.steps.get(&id.key()) {
            return Some(s.clone());
        }
        let mut e =
            StError::new(id.span, format!("unknown step `{}`", id.name), "no step of this name");
        if let Some(m) =
            crate::diag::did_you_mean(&id.name, self.sfc.steps.iter().map(|s| s.name.name.as_str()))
        {
            e.notes.push(format!("did you mean `{m}`?"));
        }
        self.errors.push(e);
        None
    }

    fn lower(mut self) -> Result<(Vec<VarDecl>, Vec<Stmt>), Vec<StError>> {
        let sfc = self.sfc;
        let at = self.pou.name.span;
        let mut out = Vec::new();
        // Steps initialisation: the state kept, an active step's time grown by a cycle.
        for s in &sfc.steps {
            let Some((x, prev, time)) = self.steps.get(&s.name.key()).cloned() else { continue };
            out.push(assign(&prev, var(&x, s.name.span), s.name.span));
            if let Some((t, n)) = time {
                let grow = assign(
                    &t,
                    bin(super::ast::BinOp::Add, var(&t, s.name.span), int(1, s.name.span)),
                    s.name.span,
                );
                let below = bin(super::ast::BinOp::Lt, var(&t, s.name.span), int(n, s.name.span));
                out.push(when(and(var(&x, s.name.span), below), vec![grow], vec![]));
            }
        }
        // Actions initialisation.
        for key in self.order.clone() {
            let (_, _, [state, _, set, reset]) = self.actions[&key].clone();
            for b in [state, set, reset].iter().filter(|b| !b.is_empty()) {
                out.push(assign(b, lit(false, at), at));
            }
        }
        // Transitions fire test, in matiec's list order (by priority where given).
        let mut list: Vec<(usize, i128)> = Vec::new();
        for (k, t) in sfc.transitions.iter().enumerate() {
            match t.priority {
                Some((p, _)) => {
                    let at = list.iter().position(|(_, q)| *q > p).unwrap_or(list.len());
                    list.insert(at, (k, p));
                }
                None => list.push((k, 0)),
            }
        }
        let mut fire = Vec::new();
        for (k, t) in sfc.transitions.iter().enumerate() {
            let base = match &t.name {
                Some(n) => format!("{}_FIRES", n.name),
                None => format!("{}_T{}", self.pou.name.name, k + 1),
            };
            fire.push(self.make(&base, t.span, "BOOL", None));
        }
        let mut condition = Vec::new();
        for t in &sfc.transitions {
            let c = self.expr(&t.condition);
            condition.push(c);
        }
        // Each transition's steps, resolved once (an unknown one is reported once).
        let ends: Vec<(Vec<StepBits>, Vec<StepBits>)> = sfc
            .transitions
            .iter()
            .map(|t| {
                let from = t.from.iter().filter_map(|s| self.step(s)).collect();
                (from, t.to.iter().filter_map(|s| self.step(s)).collect())
            })
            .collect();
        for &(k, _) in &list {
            let t = &sfc.transitions[k];
            let from = &ends[k].0;
            let Some(all) = from.iter().map(|(x, ..)| var(x, t.span)).reduce(and) else { continue };
            let mut then = vec![assign(&fire[k], condition[k].clone(), t.span)];
            if t.priority.is_some() {
                let leave =
                    from.iter().map(|(x, ..)| assign(x, lit(false, t.span), t.span)).collect();
                then.push(when(var(&fire[k], t.span), leave, vec![]));
            }
            out.push(when(all, then, vec![assign(&fire[k], lit(false, t.span), t.span)]));
        }
        // Transitions reset steps, then set steps.
        for (k, t) in sfc.transitions.iter().enumerate() {
            if t.priority.is_none() {
                let leave =
                    ends[k].0.iter().map(|(x, ..)| assign(x, lit(false, t.span), t.span)).collect();
                out.push(when(var(&fire[k], t.span), leave, vec![]));
            }
        }
        for (k, t) in sfc.transitions.iter().enumerate() {
            let mut enter = Vec::new();
            for (x, _, time) in &ends[k].1 {
                enter.push(assign(x, lit(true, t.span), t.span));
                if let Some((ticks, _)) = time {
                    enter.push(assign(ticks, int(0, t.span), t.span));
                }
            }
            out.push(when(var(&fire[k], t.span), enter, vec![]));
        }
        // Steps association.
        for s in &sfc.steps {
            let Some((x, prev, time)) = self.steps.get(&s.name.key()).cloned() else { continue };
            for a in &s.actions {
                out.extend(self.association(a, &x, &prev, time.as_ref()));
            }
        }
        // Actions state evaluation.
        for key in self.order.clone() {
            let (kind, _, [state, stored, set, reset]) = self.actions[&key].clone();
            if kind == Kind::Body {
                out.push(when(var(&set, at), vec![assign(&stored, lit(true, at), at)], vec![]));
                out.push(when(var(&reset, at), vec![assign(&stored, lit(false, at), at)], vec![]));
                out.push(assign(
                    &state,
                    bin(super::ast::BinOp::Or, var(&state, at), var(&stored, at)),
                    at,
                ));
            }
        }
        // Actions execution: variables by their marks, then the bodies.
        for key in self.order.clone() {
            let (kind, name, [_, _, set, reset]) = self.actions[&key].clone();
            if kind == Kind::Variable && !set.is_empty() {
                let stmt = Stmt {
                    kind: StmtKind::If(
                        vec![
                            (var(&reset, at), vec![assign(&name, lit(false, at), at)]),
                            (var(&set, at), vec![assign(&name, lit(true, at), at)]),
                        ],
                        vec![],
                    ),
                    span: at,
                };
                out.push(stmt);
            }
        }
        for a in &sfc.actions {
            let Some((_, _, [state, ..])) = self.actions.get(&a.name.key()).cloned() else {
                continue;
            };
            let body = a.body.iter().map(|s| self.stmt(s)).collect();
            out.push(when(var(&state, a.name.span), body, vec![]));
        }
        if self.errors.is_empty() { Ok((self.vars, out)) } else { Err(self.errors) }
    }

    /// The statements of association `a` of the step with flag `x` and previous state
    /// `prev`.
    fn association(
        &mut self,
        a: &Association,
        x: &str,
        prev: &str,
        time: Option<&(String, u64)>,
    ) -> Vec<Stmt> {
        let sp = a.span;
        let Some((kind, name, [state, _, set, reset])) = self.actions.get(&a.action.key()).cloned()
        else {
            return vec![];
        };
        let target = if kind == Kind::Variable { name } else { state.clone() };
        let active = || var(x, sp);
        let activated = || and(var(x, sp), not(var(prev, sp)));
        let desactivated = || and(not(var(x, sp)), var(prev, sp));
        let set_to = |b: bool| vec![assign(&target, lit(b, sp), sp)];
        let Some(q) = &a.qualifier else {
            // `A()`: the action's state while active (a variable's state is read by nothing).
            if kind == Kind::Variable {
                return vec![];
            }
            return vec![when(active(), vec![assign(&state, lit(true, sp), sp)], vec![])];
        };
        match q.name.as_str() {
            "N" => vec![
                when(active(), set_to(true), vec![]),
                when(desactivated(), set_to(false), vec![]),
            ],
            "S" => vec![when(active(), vec![assign(&set, lit(true, sp), sp)], vec![])],
            "R" => vec![when(active(), vec![assign(&reset, lit(true, sp), sp)], vec![])],
            "P" | "P1" => vec![when(activated(), set_to(true), set_to(false))],
            "P0" => vec![when(desactivated(), set_to(true), set_to(false))],
            "D" | "L" => {
                let (Some((ticks, _)), Some(ExprKind::Time(us))) =
                    (time, a.time.as_ref().map(|t| &t.kind))
                else {
                    return vec![];
                };
                let n = us.div_ceil(self.cycle_us.max(1));
                let reached = bin(super::ast::BinOp::Ge, var(ticks, sp), int(n, sp));
                if q.name == "D" {
                    vec![Stmt {
                        kind: StmtKind::If(
                            vec![
                                (and(active(), reached), set_to(true)),
                                (desactivated(), set_to(false)),
                            ],
                            vec![],
                        ),
                        span: sp,
                    }]
                } else {
                    let leave = bin(super::ast::BinOp::Or, desactivated(), active());
                    vec![Stmt {
                        kind: StmtKind::If(
                            vec![
                                (and(active(), not(reached)), set_to(true)),
                                (leave, set_to(false)),
                            ],
                            vec![],
                        ),
                        span: sp,
                    }]
                }
            }
            _ => vec![],
        }
    }

    /// `e` with every step's `S.X` read as its flag.
    fn expr(&mut self, e: &Expr) -> Expr {
        let kind = match &e.kind {
            ExprKind::Member(of, field) => {
                if let ExprKind::Var(id) = &of.kind
                    && let Some((x, _, _)) = self.steps.get(&id.key()).cloned()
                {
                    if field.key() == "X" {
                        return var(&x, e.span);
                    }
                    self.error(
                        field.span,
                        format!(
                            "a step's `{}` is not modelled yet (only `{}.X`, whether it is active)",
                            field.name, id.name
                        ),
                        "not modelled",
                    );
                    return lit(false, e.span);
                }
                ExprKind::Member(Box::new(self.expr(of)), field.clone())
            }
            ExprKind::Index(a, i) => {
                ExprKind::Index(Box::new(self.expr(a)), i.iter().map(|x| self.expr(x)).collect())
            }
            ExprKind::Unary(op, a) => ExprKind::Unary(*op, Box::new(self.expr(a))),
            ExprKind::Binary(op, a, b) => {
                ExprKind::Binary(*op, Box::new(self.expr(a)), Box::new(self.expr(b)))
            }
            ExprKind::Call(f, args) => {
                ExprKind::Call(f.clone(), args.iter().map(|a| self.arg(a)).collect())
            }
            other => other.clone(),
        };
        Expr { kind, span: e.span }
    }

    fn arg(&mut self, a: &super::ast::Arg) -> super::ast::Arg {
        use super::ast::Arg;
        match a {
            Arg::Positional(e) => Arg::Positional(self.expr(e)),
            Arg::Input(n, e) => Arg::Input(n.clone(), self.expr(e)),
            Arg::Output(n, neg, e) => Arg::Output(n.clone(), *neg, self.expr(e)),
        }
    }

    fn stmts(&mut self, s: &[Stmt]) -> Vec<Stmt> {
        s.iter().map(|s| self.stmt(s)).collect()
    }

    fn stmt(&mut self, s: &Stmt) -> Stmt {
        let kind = match &s.kind {
            StmtKind::Assign(a, b) => StmtKind::Assign(self.expr(a), self.expr(b)),
            StmtKind::Call(f, args) => {
                StmtKind::Call(self.expr(f), args.iter().map(|a| self.arg(a)).collect())
            }
            StmtKind::If(arms, other) => StmtKind::If(
                arms.iter().map(|(c, b)| (self.expr(c), self.stmts(b))).collect(),
                self.stmts(other),
            ),
            StmtKind::Case(sel, arms, other) => StmtKind::Case(
                self.expr(sel),
                arms.iter()
                    .map(|(labels, body)| {
                        (
                            labels
                                .iter()
                                .map(|(a, b)| (self.expr(a), b.as_ref().map(|b| self.expr(b))))
                                .collect(),
                            self.stmts(body),
                        )
                    })
                    .collect(),
                self.stmts(other),
            ),
            StmtKind::For(v, a, b, c, body) => StmtKind::For(
                v.clone(),
                self.expr(a),
                self.expr(b),
                c.as_ref().map(|c| self.expr(c)),
                self.stmts(body),
            ),
            StmtKind::While(c, body) => StmtKind::While(self.expr(c), self.stmts(body)),
            StmtKind::Repeat(body, c) => StmtKind::Repeat(self.stmts(body), self.expr(c)),
            StmtKind::Assert(e, n) => StmtKind::Assert(self.expr(e), n.clone()),
            other => other.clone(),
        };
        Stmt { kind, span: s.span }
    }
}
