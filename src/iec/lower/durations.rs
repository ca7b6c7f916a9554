//! TIME variables that are constant in fact, over the whole file before lowering: every write (initial value, assignments, IL stores, call outputs, and for a function block's input, a standard timer's `PT` included, every call of its instances) gives the same literal duration, so a timer whose `PT` is that variable has that preset; any other TIME variable keeps the reason it may change.

use std::collections::{BTreeMap, BTreeSet};

use super::super::ast::{self, Arg, Expr, ExprKind, IlInstr, IlOp, PouKind, StmtKind, VarClass};
use crate::diag::Sources;
use crate::program::durations::{TimeWrite, constant_value};

/// What the file says of its TIME variables.
#[derive(Clone, Debug, Default)]
pub(super) struct TimeFacts {
    /// Per TIME variable, by (owner, the variable's upper-case name): the duration it
    /// holds at every read, or why it may hold another. The owner is the declaring POU's
    /// upper-case name (`""` for a configuration's globals), and for a function block's
    /// input that of the instance's declaration, `POU.INSTANCE` (`.INSTANCE` for a global).
    pub values: BTreeMap<(String, String), Result<u64, String>>,
    /// The programs' TIME inputs no statement writes: a caller that gives one a literal
    /// gives the program that preset (a PLCopen text block's call).
    pub unwritten_inputs: BTreeSet<(String, String)>,
}

/// Whether a declared type is `TIME`.
fn is_time(v: &ast::VarDecl) -> bool {
    v.ty.name.eq_ignore_ascii_case("TIME")
}

/// A declared initial value in µs (`None`: T#0s), or the text that is not a duration.
fn init_of(v: &ast::VarDecl) -> Result<u64, String> {
    match v.init.as_ref().map(|e| &e.kind) {
        None => Ok(0),
        Some(ExprKind::Time(us)) => Ok(*us),
        Some(ExprKind::Literal(t)) => {
            crate::iec::literal::parse_duration(t).ok_or_else(|| t.clone())
        }
        Some(_) => Err("an expression".into()),
    }
}

/// The writes found so far: per variable, and per function block's input the values
/// its calls give (`None`: a call that leaves it out).
#[derive(Default)]
struct Found {
    writes: BTreeMap<(String, String), Vec<TimeWrite>>,
    calls: BTreeMap<(String, String), Vec<Option<TimeWrite>>>,
    /// A call of an instance whose type or declaration is not known here: where.
    unknown_call: Option<String>,
}

/// The facts of every TIME variable the file declares.
pub(super) fn time_facts(sources: &Sources, unit: &ast::Unit) -> TimeFacts {
    let fbs: BTreeMap<String, &ast::Pou> = unit
        .pous
        .iter()
        .filter(|p| p.kind == PouKind::FunctionBlock)
        .map(|p| (p.name.key(), p))
        .collect();
    let globals: Vec<&ast::VarDecl> = unit.configs.iter().flat_map(|c| &c.globals).collect();
    let mut found = Found::default();
    for pou in &unit.pous {
        let walk = Walk { sources, pou, globals: &globals, fbs: &fbs };
        match &pou.body {
            ast::Body::St(stmts) => walk.stmts(stmts, &mut found),
            ast::Body::Il(lines) => walk.il(lines, &mut found),
            // Charts are Structured Text by the time durations are read (`sfc::desugar`).
            ast::Body::Sfc(_) => {}
        }
    }
    let mut facts = TimeFacts::default();
    for v in &globals {
        instance_facts("", v, &fbs, &found, &mut facts);
    }
    for v in globals.iter().filter(|v| is_time(v)) {
        let writes = found.writes.get(&(String::new(), v.name.key())).map_or(&[][..], |w| w);
        let fact = fixed_class(v).and_then(|()| {
            if writes.is_empty() {
                return Err("it is a global no statement writes, so the outside world (an HMI, \
                            another resource) writes it"
                    .into());
            }
            constant_value(init_of(v).map_err(bad_init)?, writes)
        });
        facts.values.insert((String::new(), v.name.key()), fact);
    }
    for pou in &unit.pous {
        let instances = pou.vars.iter().filter(|v| v.class != VarClass::External);
        for v in instances.clone() {
            instance_facts(&pou.name.key(), v, &fbs, &found, &mut facts);
        }
        for v in pou.vars.iter().filter(|v| is_time(v) && v.class != VarClass::External) {
            let key = (pou.name.key(), v.name.key());
            let writes = found.writes.get(&key).map_or(&[][..], |w| w);
            let fact = match (pou.kind, v.class) {
                // Each instance's own, by its declaration (`instance_facts`).
                (PouKind::FunctionBlock, VarClass::Input) => continue,
                (PouKind::Program, VarClass::Input) if writes.is_empty() => {
                    facts.unwritten_inputs.insert(key.clone());
                    Err("it is an input of the program, written from outside".into())
                }
                (PouKind::Program, VarClass::Input) => {
                    Err("it is an input of the program, written from outside and by it".into())
                }
                (PouKind::Function, VarClass::Input) => {
                    Err("it is an input of a function, given by each call".into())
                }
                (_, VarClass::InOut) => Err("it is passed by reference".into()),
                (_, VarClass::Global) => {
                    Err("it is a global variable declared in a POU, which ii-prove does not follow"
                        .into())
                }
                _ => fixed_class(v).and_then(|()| {
                    let init = init_of(v).map_err(bad_init)?;
                    constant_value(init, writes)
                }),
            };
            facts.values.insert(key, fact);
        }
    }
    facts
}

/// The facts of the TIME inputs of `v` when it is an instance of a user function block,
/// declared in the POU `owner`: what the calls of this instance give.
fn instance_facts(
    owner: &str,
    v: &ast::VarDecl,
    fbs: &BTreeMap<String, &ast::Pou>,
    found: &Found,
    facts: &mut TimeFacts,
) {
    let decl = format!("{owner}.{}", v.name.key());
    // A retained instance's inputs start, after a warm restart, with any value.
    let retained = |init: Result<u64, String>| match init {
        _ if v.retain => Err(format!(
            "the instance {} is retained, and a call leaves it out or none writes \
             it: after a warm restart it keeps the value it had",
            v.name.name
        )),
        init => init,
    };
    if timer_type(&v.ty.key()) {
        // A standard timer's PT: T#0s until a call gives it; no body writes it.
        let calls = found.calls.get(&(decl.clone(), "PT".to_string()));
        let fact = fb_input(retained(Ok(0)), &[], calls, found.unknown_call.as_deref());
        facts.values.insert((decl, "PT".to_string()), fact);
        return;
    }
    let Some(fb) = fbs.get(&v.ty.key()) else { return };
    for x in fb.vars.iter().filter(|x| is_time(x) && x.class == VarClass::Input) {
        let writes = found.writes.get(&(fb.name.key(), x.name.key())).map_or(&[][..], |w| w);
        let calls = found.calls.get(&(decl.clone(), x.name.key()));
        let fact = fixed_class(x).and_then(|()| {
            let init = retained(init_of(x).map_err(bad_init));
            fb_input(init, writes, calls, found.unknown_call.as_deref())
        });
        facts.values.insert((decl.clone(), x.name.key()), fact);
    }
}

/// Whether a type is one of the standard timers, whose inputs are `IN` and `PT`.
fn timer_type(ty: &str) -> bool {
    matches!(ty, "TON" | "TOF" | "TP")
}

fn bad_init(text: String) -> String {
    format!("its initial value `{text}` is not a literal duration")
}

/// Why a variable's declaration lets the outside world give it another value.
fn fixed_class(v: &ast::VarDecl) -> Result<(), String> {
    if let Some(l) = &v.location {
        return Err(format!("it is located at {l}, which the outside world may write"));
    }
    if v.retain {
        return Err("it is retained: after a warm restart it keeps the value it had".into());
    }
    Ok(())
}

/// A function block's TIME input: each call writes it before the body reads it, so when
/// every call gives the same literal and the body writes only that, the body reads it;
/// a call that leaves it out keeps the value before, from the start value `init` on (or
/// why that is not known).
fn fb_input(
    init: Result<u64, String>,
    writes: &[TimeWrite],
    calls: Option<&Vec<Option<TimeWrite>>>,
    unknown_call: Option<&str>,
) -> Result<u64, String> {
    if let Some(at) = unknown_call {
        return Err(format!("a call {at} is of an instance whose type ii-prove does not name"));
    }
    let calls = calls.map_or(&[][..], |c| c);
    let mut all: Vec<TimeWrite> = calls.iter().flatten().cloned().collect();
    all.extend(writes.iter().cloned());
    let omitted = calls.iter().any(Option::is_none);
    match all.first() {
        Some(TimeWrite::Literal(us, _)) if !omitted => constant_value(*us, &all),
        _ => constant_value(init?, &all),
    }
}

/// The writes of one POU's body.
struct Walk<'a> {
    sources: &'a Sources,
    pou: &'a ast::Pou,
    globals: &'a [&'a ast::VarDecl],
    fbs: &'a BTreeMap<String, &'a ast::Pou>,
}

impl Walk<'_> {
    /// Where `e` is, for a reason: `at line 12`.
    fn at(&self, e: &Expr) -> String {
        format!("at line {}", self.sources.line_col(e.span.file, e.span.start).0)
    }

    /// The declaration a name refers to in this POU and its key in the facts.
    fn resolve(&self, name: &ast::Ident) -> Option<(&ast::VarDecl, (String, String))> {
        let key = name.key();
        match self.pou.vars.iter().find(|v| v.name.key() == key) {
            Some(v) if v.class != VarClass::External => Some((v, (self.pou.name.key(), key))),
            _ => {
                let g = self.globals.iter().copied().find(|v| v.name.key() == key)?;
                Some((g, (String::new(), key)))
            }
        }
    }

    /// `target` written with `value` (`None`: a value that is not an expression here).
    fn write(&self, target: &Expr, value: Option<&Expr>, what: &str, found: &mut Found) {
        let ExprKind::Var(id) = &target.kind else { return };
        let Some((v, key)) = self.resolve(id) else { return };
        if !is_time(v) {
            return;
        }
        let at = self.at(target);
        let w = match value.map(|e| &e.kind) {
            Some(ExprKind::Time(us)) => TimeWrite::Literal(*us, at),
            _ => TimeWrite::Other(format!("{what} {at}")),
        };
        found.writes.entry(key).or_default().push(w);
    }

    fn stmts(&self, stmts: &[ast::Stmt], found: &mut Found) {
        for s in stmts {
            match &s.kind {
                StmtKind::Assign(target, value) => {
                    self.write(target, Some(value), "an expression", found);
                    self.expr(value, found);
                }
                StmtKind::Call(inst, args) => self.call(inst, args, found),
                StmtKind::If(arms, otherwise) => {
                    for (c, body) in arms {
                        self.expr(c, found);
                        self.stmts(body, found);
                    }
                    self.stmts(otherwise, found);
                }
                StmtKind::Case(e, arms, otherwise) => {
                    self.expr(e, found);
                    for (_, body) in arms {
                        self.stmts(body, found);
                    }
                    self.stmts(otherwise, found);
                }
                StmtKind::For(_, a, b, c, body) => {
                    for e in [Some(a), Some(b), c.as_ref()].into_iter().flatten() {
                        self.expr(e, found);
                    }
                    self.stmts(body, found);
                }
                StmtKind::While(e, body) | StmtKind::Repeat(body, e) => {
                    self.expr(e, found);
                    self.stmts(body, found);
                }
                StmtKind::Assert(e, _) => self.expr(e, found),
                StmtKind::Exit | StmtKind::Continue | StmtKind::Return | StmtKind::Empty => {}
            }
        }
    }

    /// The outputs of the function calls in `e`.
    fn expr(&self, e: &Expr, found: &mut Found) {
        match &e.kind {
            ExprKind::Call(_, args) => {
                for a in args {
                    match a {
                        Arg::Output(_, _, target) => {
                            self.write(target, None, "a call's output", found)
                        }
                        Arg::Positional(x) | Arg::Input(_, x) => self.expr(x, found),
                    }
                }
            }
            ExprKind::Member(x, _) | ExprKind::Unary(_, x) => self.expr(x, found),
            ExprKind::Index(x, xs) => {
                self.expr(x, found);
                xs.iter().for_each(|x| self.expr(x, found));
            }
            ExprKind::Binary(_, a, b) => {
                self.expr(a, found);
                self.expr(b, found);
            }
            _ => {}
        }
    }

    /// The call of the instance `inst` with `args`.
    fn call(&self, inst: &Expr, args: &[Arg], found: &mut Found) {
        for a in args {
            match a {
                Arg::Output(_, _, target) => self.write(target, None, "a call's output", found),
                Arg::Positional(x) | Arg::Input(_, x) => self.expr(x, found),
            }
        }
        let Some((inputs, decl)) = self.instance_inputs(inst, found) else { return };
        let at = self.at(inst);
        let mut given: BTreeMap<String, &Expr> = BTreeMap::new();
        let mut next = 0;
        for a in args {
            match a {
                Arg::Input(n, e) => {
                    given.insert(n.key(), e);
                }
                Arg::Positional(e) => {
                    if let Some((v, _)) = inputs.get(next) {
                        given.insert(v.clone(), e);
                    }
                    next += 1;
                }
                Arg::Output(..) => {}
            }
        }
        for (v, _) in inputs.iter().filter(|(_, time)| *time) {
            let w = given.get(v).map(|e| match &e.kind {
                ExprKind::Time(us) => TimeWrite::Literal(*us, format!("by the call {at}")),
                _ => TimeWrite::Other(format!("a value that is not a literal by the call {at}")),
            });
            found.calls.entry((decl.clone(), v.clone())).or_default().push(w);
        }
    }

    /// The inputs of the instance `inst` when it is of a user function block or a
    /// standard timer (upper-case names in declaration order, each with whether it is a
    /// TIME), and its declaration (`POU.INSTANCE`); a call of an instance this cannot
    /// name is noted (every block input then stays unknown).
    fn instance_inputs(
        &self,
        inst: &Expr,
        found: &mut Found,
    ) -> Option<(Vec<(String, bool)>, String)> {
        let ExprKind::Var(id) = &inst.kind else {
            found.unknown_call.get_or_insert_with(|| self.at(inst));
            return None;
        };
        let (v, (owner, key)) = self.resolve(id)?;
        let inputs = if timer_type(&v.ty.key()) {
            vec![("IN".to_string(), false), ("PT".to_string(), true)]
        } else {
            let fb = self.fbs.get(&v.ty.key())?;
            let inputs = fb.vars.iter().filter(|v| v.class == VarClass::Input);
            inputs.map(|v| (v.name.key(), is_time(v))).collect()
        };
        Some((inputs, format!("{owner}.{key}")))
    }

    fn il(&self, lines: &[ast::IlLine], found: &mut Found) {
        for line in lines {
            match &line.instr {
                Some(IlInstr::Op { op, operand, nested, .. }) => {
                    if let (IlOp::St | IlOp::S | IlOp::R, Some(target)) = (op, operand) {
                        self.write(target, None, "an IL store", found);
                    }
                    if let Some(lines) = nested {
                        self.il(lines, found);
                    }
                }
                Some(IlInstr::Call { instance, args, .. }) => self.call(instance, args, found),
                Some(IlInstr::FbInput { pin, instance, .. }) => {
                    // A call with the current result as `pin`, every other input left out.
                    if let Some((inputs, decl)) = self.instance_inputs(instance, found) {
                        let at = self.at(instance);
                        for (v, _) in inputs.iter().filter(|(_, time)| *time) {
                            let w = (v == pin)
                                .then(|| TimeWrite::Other(format!("the IL operator {pin} {at}")));
                            found.calls.entry((decl.clone(), v.clone())).or_default().push(w);
                        }
                    }
                }
                _ => {}
            }
        }
    }
}
