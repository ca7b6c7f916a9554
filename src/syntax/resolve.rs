//! The resolver: names, `/` chains and durations of the syntax tree become terms.
//!
//! In `assume`, `property` and `let`, a name is an abbreviation (expanded), an
//! `input`, or a signal of the program ([`Scope::lookup`]). In a `law`, every
//! signal name is a metavariable and delay metavariables must be declared by
//! an earlier `delay` statement. Duration arithmetic whose operands are all
//! literals is folded to one literal.

use std::collections::HashMap;

use super::ast::{
    Ast, AstGoal, AstKind, AstPattern, AstProof, AstStatement, Func, NamedKind, RelOp,
};
use super::lexer::{Tok, lex};
use super::parser::Parser;
use super::pattern::{self, Pattern};
use super::{
    CalcStep, Claim, Declaration, DelayComparison, Document, Goal, Law, Lookup, Relation, Scope,
    ScriptProof, SideCondition, Statement, SyntaxError,
};
use crate::diag::{FileId, Span, did_you_mean};
use crate::term::{Delay, Expr, Id, Language, Symbol, Term};

/// The most nodes one resolved term may have (abbreviations can double a term per line).
const MAX_NODES: usize = 100_000;

/// The deepest a resolved term may be (keeps every recursive consumer's stack safe).
const MAX_TERM_DEPTH: usize = 1_000;

/// The depth of the deepest node of a term (linear: children come before parents).
fn depth(nodes: &[Term]) -> usize {
    let mut depths: Vec<usize> = Vec::with_capacity(nodes.len());
    for node in nodes {
        let below = node
            .children()
            .iter()
            .map(|&c| depths.get(usize::from(c)).copied().unwrap_or(0))
            .max()
            .unwrap_or(0);
        depths.push(below + 1);
    }
    depths.into_iter().max().unwrap_or(0)
}

/// Where a term is being resolved: the rules for names differ.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mode {
    /// `assume`, `property`, `let`, REPL input: concrete names and durations.
    Concrete,
    /// `law`: names are metavariables.
    Law,
}

/// A resolved duration: a literal (foldable) or a node already in the builder.
enum DVal {
    Lit(Delay),
    Node(Id),
}

/// Nodes of a term under construction.
///
/// Like [`crate::term::Builder`], but adding a node is O(1): egg's
/// `RecExpr::add` finds its root by walking every id, which makes long
/// sums quadratic.
#[derive(Default)]
struct Nodes {
    nodes: Vec<Term>,
}

impl Nodes {
    fn add(&mut self, node: Term) -> Id {
        self.nodes.push(node);
        Id::from(self.nodes.len() - 1)
    }
    fn name(&mut self, name: &str) -> Id {
        self.add(Term::Name(Symbol::from(name)))
    }
    fn delay(&mut self, d: Delay) -> Id {
        self.add(Term::Delay(d))
    }
    fn zero(&mut self) -> Id {
        self.add(Term::Zero)
    }
    fn one(&mut self) -> Id {
        self.add(Term::One)
    }
    fn not(&mut self, a: Id) -> Id {
        self.add(Term::Not(a))
    }
    fn pre(&mut self, a: Id) -> Id {
        self.add(Term::Pre(a))
    }
    fn ton(&mut self, d: Id, f: Id) -> Id {
        self.add(Term::Ton([d, f]))
    }
    fn tof(&mut self, f: Id, d: Id) -> Id {
        self.add(Term::Tof([f, d]))
    }
    fn sr(&mut self, s: Id, r: Id) -> Id {
        self.add(Term::Sr([s, r]))
    }
    fn rs(&mut self, s: Id, r: Id) -> Id {
        self.add(Term::Rs([s, r]))
    }
    /// Copies a whole (compact, root-last) term in; returns the id of its root.
    fn term(&mut self, expr: &Expr) -> Id {
        let base = self.nodes.len();
        for node in expr.as_ref() {
            let node = node.clone().map_children(|c| Id::from(usize::from(c) + base));
            self.nodes.push(node);
        }
        Id::from(self.nodes.len().saturating_sub(1))
    }
    /// The term rooted at `root`, without unreachable nodes, root last.
    fn finish(&self, root: Id) -> Expr {
        let root = usize::from(root);
        let mut keep = vec![false; root + 1];
        keep[root] = true;
        for i in (0..=root).rev() {
            if keep[i] {
                for &c in self.nodes[i].children() {
                    keep[usize::from(c)] = true;
                }
            }
        }
        let mut new_id = vec![0usize; root + 1];
        let mut out = Vec::with_capacity(keep.iter().filter(|k| **k).count());
        for i in 0..=root {
            if keep[i] {
                new_id[i] = out.len();
                let node = self.nodes[i].clone().map_children(|c| Id::from(new_id[usize::from(c)]));
                out.push(node);
            }
        }
        Expr::from(out)
    }
}

/// One term under construction and the metavariables it uses.
#[derive(Default)]
struct Out {
    b: Nodes,
    signal_vars: Vec<Symbol>,
    delay_vars: Vec<Symbol>,
}

impl Out {
    fn finish(self, root: Id) -> Expr {
        self.b.finish(root)
    }
}

fn push_unique(list: &mut Vec<Symbol>, s: Symbol) {
    if !list.contains(&s) {
        list.push(s);
    }
}

struct Resolver<'a> {
    file: FileId,
    scope: &'a dyn Scope,
    lets: HashMap<String, Expr>,
    inputs: Vec<(String, Span)>,
    delays: Vec<(String, Span)>,
    /// Every name declared by `let`, `input` or `delay`, with where.
    declared: HashMap<String, Span>,
    errors: Vec<SyntaxError>,
}

impl<'a> Resolver<'a> {
    fn new(file: FileId, scope: &'a dyn Scope) -> Resolver<'a> {
        Resolver {
            file,
            scope,
            lets: HashMap::new(),
            inputs: Vec::new(),
            delays: Vec::new(),
            declared: HashMap::new(),
            errors: Vec::new(),
        }
    }

    fn is_delay_var(&self, name: &str) -> bool {
        !self.lets.contains_key(name) && self.delays.iter().any(|(d, _)| d == name)
    }

    fn is_input(&self, name: &str) -> bool {
        self.inputs.iter().any(|(d, _)| d == name)
    }

    fn declare(&mut self, name: &str, span: Span) -> bool {
        if let Some(first) = self.declared.get(name) {
            self.errors.push(SyntaxError::DuplicateName { span, name: name.into(), first: *first });
            false
        } else {
            self.declared.insert(name.into(), span);
            true
        }
    }

    /// Is this operand of a `/` chain (or side of a comparison) a duration?
    fn is_duration(&self, a: &Ast) -> bool {
        match &a.kind {
            AstKind::Duration(_) => true,
            AstKind::Name(n) => self.is_delay_var(n),
            AstKind::Call(Func::Max | Func::Min, _, _) => true,
            AstKind::Paren(x) => self.is_duration(x),
            AstKind::Or(v) => v.iter().all(|x| self.is_duration(x)),
            _ => false,
        }
    }

    fn has_error(a: &Ast) -> bool {
        matches!(a.kind, AstKind::Error)
    }

    fn unknown(&self, name: &str, span: Span) -> SyntaxError {
        let program = self.scope.names();
        let inputs: Vec<String> = self.inputs.iter().map(|(n, _)| n.clone()).collect();
        let mut candidates: Vec<&str> = program.iter().map(String::as_str).collect();
        candidates.extend(inputs.iter().map(String::as_str));
        candidates.extend(self.lets.keys().map(String::as_str));
        let suggestion = did_you_mean(name, candidates).map(str::to_string);
        let known = if program.is_empty() { inputs } else { program };
        SyntaxError::UnknownName { span, name: name.into(), suggestion, known }
    }

    fn name(&mut self, name: &str, span: Span, mode: Mode, out: &mut Out) -> Option<Id> {
        if let Some(expr) = self.lets.get(name) {
            if out.b.nodes.len() + expr.as_ref().len() > MAX_NODES {
                self.errors.push(SyntaxError::TooLarge { span });
                return None;
            }
            if mode == Mode::Law {
                for node in expr.as_ref() {
                    if let Term::Name(s) = node {
                        push_unique(&mut out.signal_vars, *s);
                    }
                }
            }
            return Some(out.b.term(expr));
        }
        if self.is_delay_var(name) {
            self.errors.push(match mode {
                Mode::Law => SyntaxError::DurationAsSignal { span },
                Mode::Concrete => SyntaxError::DelayVariableOutsideLaw { span, name: name.into() },
            });
            return None;
        }
        if mode == Mode::Law {
            let symbol = Symbol::from(name);
            push_unique(&mut out.signal_vars, symbol);
            return Some(out.b.add(Term::Name(symbol)));
        }
        if self.is_input(name) {
            return Some(out.b.name(name));
        }
        match self.scope.lookup(name) {
            Lookup::Signal(canonical) => Some(out.b.name(&canonical)),
            Lookup::Ambiguous(candidates) => {
                self.errors.push(SyntaxError::AmbiguousName {
                    span,
                    name: name.into(),
                    candidates,
                });
                None
            }
            Lookup::Unknown => {
                let error = self.unknown(name, span);
                self.errors.push(error);
                None
            }
        }
    }

    /// Resolves a list of operands and folds them with `op` from the left.
    fn fold(
        &mut self,
        v: &[Ast],
        mode: Mode,
        out: &mut Out,
        op: fn([Id; 2]) -> Term,
    ) -> Option<Id> {
        let ids: Vec<Option<Id>> = v.iter().map(|x| self.signal(x, mode, out)).collect();
        let ids: Option<Vec<Id>> = ids.into_iter().collect();
        let ids = ids?;
        let (&first, rest) = ids.split_first()?;
        Some(rest.iter().fold(first, |acc, &next| out.b.add(op([acc, next]))))
    }

    /// Resolves a signal expression.
    fn signal(&mut self, a: &Ast, mode: Mode, out: &mut Out) -> Option<Id> {
        match &a.kind {
            AstKind::Name(n) => self.name(n, a.span, mode, out),
            AstKind::Duration(_) | AstKind::Call(Func::Max | Func::Min, _, _) => {
                self.errors.push(SyntaxError::DurationAsSignal { span: a.span });
                None
            }
            AstKind::Zero => Some(out.b.zero()),
            AstKind::One => Some(out.b.one()),
            AstKind::Not(x) => {
                let x = self.signal(x, mode, out)?;
                Some(out.b.not(x))
            }
            AstKind::Pre(x) => {
                if mode == Mode::Concrete && !self.scope.scans() {
                    self.errors.push(SyntaxError::PreOutsideProgram { span: a.span });
                    return None;
                }
                let x = self.signal(x, mode, out)?;
                Some(out.b.pre(x))
            }
            AstKind::Or(v) => self.fold(v, mode, out, Term::Or),
            AstKind::And(v) => self.fold(v, mode, out, Term::And),
            AstKind::Paren(x) => self.signal(x, mode, out),
            AstKind::Call(func, x, y) => {
                let x = self.signal(x, mode, out);
                let y = self.signal(y, mode, out);
                let (x, y) = (x?, y?);
                Some(match func {
                    Func::Sr => out.b.sr(x, y),
                    _ => out.b.rs(x, y),
                })
            }
            AstKind::Chain(v) => self.chain(v, a.span, mode, out),
            AstKind::Compare(op, x, y) => match self.scope.comparison(*op, x, y) {
                Ok(name) => Some(out.b.name(&name)),
                Err((reason, help)) => {
                    self.errors.push(SyntaxError::BadComparison { span: a.span, reason, help });
                    None
                }
            },
            AstKind::Error => None,
        }
    }

    fn chain(&mut self, v: &[Ast], span: Span, mode: Mode, out: &mut Out) -> Option<Id> {
        if v.iter().any(Self::has_error) {
            return None;
        }
        let signals: Vec<usize> = (0..v.len()).filter(|&i| !self.is_duration(&v[i])).collect();
        let k = match signals.as_slice() {
            [] => {
                self.errors.push(SyntaxError::NoSignal { span });
                return None;
            }
            [k] => *k,
            _ => {
                // `!2s/f`: `!` binds tightest, so it took the duration alone.
                if let Some(negated) = v.iter().find(|a| match &a.kind {
                    AstKind::Not(inner) => self.is_duration(inner),
                    _ => false,
                }) {
                    self.errors.push(SyntaxError::NegatedDuration { span: negated.span });
                    return None;
                }
                let guess = [0, v.len() - 1].into_iter().find_map(|i| match &v[i].kind {
                    AstKind::Name(n) if mode == Mode::Law && !self.lets.contains_key(n) => {
                        Some((n.clone(), v[i].span))
                    }
                    _ => None,
                });
                self.errors.push(match guess {
                    Some((name, span)) => SyntaxError::UndeclaredDelay { span, name },
                    None => SyntaxError::NoDuration { span },
                });
                return None;
            }
        };
        if k > 0 && k + 1 < v.len() {
            self.errors.push(SyntaxError::BothDelayKinds { span });
            return None;
        }
        // Resolve in written order, so metavariables are listed by first use.
        let left: Vec<Option<Id>> = v[..k].iter().map(|d| self.delay_node(d, mode, out)).collect();
        let mut x = self.signal(&v[k], mode, out);
        for d in left.into_iter().rev() {
            x = match (x, d) {
                (Some(x), Some(d)) => Some(out.b.ton(d, x)),
                _ => None,
            };
        }
        for d in &v[k + 1..] {
            let d = self.delay_node(d, mode, out);
            x = match (x, d) {
                (Some(x), Some(d)) => Some(out.b.tof(x, d)),
                _ => None,
            };
        }
        x
    }

    fn delay_node(&mut self, a: &Ast, mode: Mode, out: &mut Out) -> Option<Id> {
        match self.delay(a, mode, out)? {
            DVal::Lit(d) => Some(out.b.delay(d)),
            DVal::Node(id) => Some(id),
        }
    }

    fn delay_op(
        &mut self,
        x: &Ast,
        y: &Ast,
        mode: Mode,
        out: &mut Out,
        lit: fn(&Delay, &Delay) -> Delay,
        node: fn([Id; 2]) -> Term,
    ) -> Option<DVal> {
        let x = self.delay(x, mode, out);
        let y = self.delay(y, mode, out);
        Some(Self::combine(x?, y?, out, lit, node))
    }

    fn combine(
        x: DVal,
        y: DVal,
        out: &mut Out,
        lit: fn(&Delay, &Delay) -> Delay,
        node: fn([Id; 2]) -> Term,
    ) -> DVal {
        match (x, y) {
            (DVal::Lit(a), DVal::Lit(b)) => DVal::Lit(lit(&a, &b)),
            (x, y) => {
                let x = Self::materialize(x, out);
                let y = Self::materialize(y, out);
                DVal::Node(out.b.add(node([x, y])))
            }
        }
    }

    fn materialize(x: DVal, out: &mut Out) -> Id {
        match x {
            DVal::Lit(d) => out.b.delay(d),
            DVal::Node(id) => id,
        }
    }

    /// Resolves a duration expression, folding literal arithmetic.
    fn delay(&mut self, a: &Ast, mode: Mode, out: &mut Out) -> Option<DVal> {
        match &a.kind {
            AstKind::Duration(d) => {
                if let Some(cycle) = self.scope.cycle().filter(|c| !d.is_whole_cycles(c)) {
                    let (delay, span, cycle) = (Box::new(d.clone()), a.span, Box::new(cycle));
                    // Reported; resolving goes on, so no error follows from this one.
                    self.errors.push(SyntaxError::SubCycleDelay { span, delay, cycle });
                }
                Some(DVal::Lit(d.clone()))
            }
            AstKind::Name(n) if self.is_delay_var(n) => match mode {
                Mode::Law => {
                    let symbol = Symbol::from(n.as_str());
                    push_unique(&mut out.delay_vars, symbol);
                    Some(DVal::Node(out.b.add(Term::Name(symbol))))
                }
                Mode::Concrete => {
                    self.errors.push(SyntaxError::DelayVariableOutsideLaw {
                        span: a.span,
                        name: n.clone(),
                    });
                    None
                }
            },
            AstKind::Name(n) if mode == Mode::Law && !self.lets.contains_key(n) => {
                self.errors.push(SyntaxError::UndeclaredDelay { span: a.span, name: n.clone() });
                None
            }
            AstKind::Call(Func::Max, x, y) => {
                self.delay_op(x, y, mode, out, Delay::dmax, Term::DMax)
            }
            AstKind::Call(Func::Min, x, y) => {
                self.delay_op(x, y, mode, out, Delay::dmin, Term::DMin)
            }
            AstKind::Paren(x) => self.delay(x, mode, out),
            AstKind::Or(v) => {
                let vals: Vec<Option<DVal>> = v.iter().map(|x| self.delay(x, mode, out)).collect();
                let vals: Option<Vec<DVal>> = vals.into_iter().collect();
                let mut vals = vals?.into_iter();
                let first = vals.next()?;
                Some(vals.fold(first, |acc, next| {
                    Self::combine(acc, next, out, Delay::dadd, Term::DAdd)
                }))
            }
            AstKind::Error => None,
            _ => {
                self.errors.push(SyntaxError::SignalAsDuration { span: a.span });
                None
            }
        }
    }

    fn signal_expr(&mut self, a: &Ast, mode: Mode, out: &mut Out) -> Option<Expr> {
        let mut local = Out::default();
        let id = self.signal(a, mode, &mut local)?;
        if local.b.nodes.len() > MAX_NODES || depth(&local.b.nodes) > MAX_TERM_DEPTH {
            self.errors.push(SyntaxError::TooLarge { span: a.span });
            return None;
        }
        for s in &local.signal_vars {
            push_unique(&mut out.signal_vars, *s);
        }
        for s in &local.delay_vars {
            push_unique(&mut out.delay_vars, *s);
        }
        Some(local.finish(id))
    }

    fn delay_expr(&mut self, a: &Ast, mode: Mode, out: &mut Out) -> Option<Expr> {
        let mut local = Out::default();
        let d = self.delay(a, mode, &mut local)?;
        let id = Self::materialize(d, &mut local);
        if local.b.nodes.len() > MAX_NODES || depth(&local.b.nodes) > MAX_TERM_DEPTH {
            self.errors.push(SyntaxError::TooLarge { span: a.span });
            return None;
        }
        for s in &local.delay_vars {
            push_unique(&mut out.delay_vars, *s);
        }
        Some(local.finish(id))
    }

    fn goal(&mut self, g: &AstGoal, mode: Mode, out: &mut Out) -> Option<Goal> {
        if let Some(p) = &g.pattern {
            return self.pattern(g, p, mode, out);
        }
        let relation = match g.op {
            RelOp::Implies => Some(Relation::Implies),
            RelOp::Equals => Some(Relation::Equals),
            _ => {
                self.errors.push(SyntaxError::BadRelation {
                    span: g.op_span,
                    reason: "expected `=>` or `=` between signals (comparisons are for durations in a law's `if`)".into(),
                });
                None
            }
        };
        let after = self.after(g, mode);
        let lhs = self.signal_expr(&g.lhs, mode, out);
        let rhs = self.signal_expr(&g.rhs, mode, out);
        Some(Goal { lhs: lhs?, relation: relation?, rhs: rhs?, after: after?, pattern: None })
    }

    /// `after D:`'s duration, if any: `Some(None)` without one, `None` after an error.
    fn after(&mut self, g: &AstGoal, mode: Mode) -> Option<Option<Delay>> {
        g.after.as_ref().map_or(Some(None), |a| self.concrete_delay(a, mode).map(Some))
    }

    /// A duration that folds to a literal (an error otherwise).
    fn concrete_delay(&mut self, a: &Ast, mode: Mode) -> Option<Delay> {
        match self.delay(a, mode, &mut Out::default()) {
            Some(DVal::Lit(d)) => Some(d),
            Some(DVal::Node(_)) => {
                self.errors.push(SyntaxError::AfterNotConcrete { span: a.span });
                None
            }
            None => None,
        }
    }

    /// A requirement pattern, compiled to its goal ([`pattern::compile`]).
    fn pattern(&mut self, g: &AstGoal, p: &AstPattern, mode: Mode, out: &mut Out) -> Option<Goal> {
        if mode == Mode::Law {
            let reason = "a law states `=` or `=>` between terms, not a requirement pattern";
            self.errors.push(SyntaxError::BadPattern { span: g.span, reason: reason.into() });
            return None;
        }
        let (kind, signals, delay): (Pattern, Vec<&Ast>, Option<&Ast>) = match p {
            AstPattern::Always(f) => (Pattern::Always, vec![f], None),
            AstPattern::Never(f) => (Pattern::Never, vec![f], None),
            AstPattern::Reachable(_) => {
                let reason = "`reachable f` claims that some run reaches `f`: an existence \
                              claim, not a safety property over scans, which is all ii-prove \
                              checks; check `never f` instead: its counterexample is a run \
                              that reaches `f`, and its proof shows that none does";
                self.errors.push(SyntaxError::BadPattern { span: g.span, reason: reason.into() });
                return None;
            }
            AstPattern::Then { first, next, then } => {
                (Pattern::Then, vec![first, next, then], None)
            }
            AstPattern::Within { trigger, response, delay } => {
                (Pattern::Within, vec![trigger, response], Some(delay))
            }
            AstPattern::NotBefore { response, delay, trigger } => {
                (Pattern::NotBefore, vec![response, trigger], Some(delay))
            }
            AstPattern::AtMost { signal, delay } => (Pattern::AtMost, vec![signal], Some(delay)),
            AstPattern::AtLeast { signal, delay } => (Pattern::AtLeast, vec![signal], Some(delay)),
        };
        let after = self.after(g, mode);
        let signals: Vec<Option<Expr>> =
            signals.into_iter().map(|a| self.signal_expr(a, mode, out)).collect();
        let delay = delay.map_or(Some(None), |a| self.concrete_delay(a, mode).map(Some));
        let (after, delay) = (after?, delay?);
        let signals: Vec<Expr> = signals.into_iter().collect::<Option<_>>()?;
        let (scans, cycle) = (self.scope.scans(), self.scope.cycle());
        match pattern::compile(kind, &signals, delay.as_ref(), scans, cycle.as_ref()) {
            Ok((lhs, relation, rhs)) => {
                Some(Goal { lhs, relation, rhs, after, pattern: Some(kind) })
            }
            Err(reason) => {
                self.errors.push(SyntaxError::BadPattern { span: g.span, reason });
                None
            }
        }
    }

    fn condition(&mut self, g: &AstGoal, out: &mut Out) -> Option<SideCondition> {
        let op = match g.op {
            RelOp::Ge => DelayComparison::Ge,
            RelOp::Gt => DelayComparison::Gt,
            RelOp::Le => DelayComparison::Le,
            RelOp::Lt => DelayComparison::Lt,
            RelOp::Equals if self.is_duration(&g.lhs) || self.is_duration(&g.rhs) => {
                DelayComparison::Eq
            }
            _ => return self.goal(g, Mode::Law, out).map(SideCondition::Signal),
        };
        let lhs = self.delay_expr(&g.lhs, Mode::Law, out);
        let rhs = self.delay_expr(&g.rhs, Mode::Law, out);
        Some(SideCondition::Delay { lhs: lhs?, op, rhs: rhs? })
    }

    fn statements(&mut self, statements: &[AstStatement]) -> Document {
        let mut doc = Document {
            file: self.file,
            program: None,
            inputs: Vec::new(),
            delays: Vec::new(),
            assumptions: Vec::new(),
            properties: Vec::new(),
            laws: Vec::new(),
            claims: Vec::new(),
        };
        let mut statement_names: HashMap<String, Span> = HashMap::new();
        for statement in statements {
            match statement {
                AstStatement::Let { name, value, .. } => {
                    let mut out = Out::default();
                    let value = self.signal_expr(value, Mode::Concrete, &mut out);
                    if self.scope.names().contains(&name.0) {
                        self.errors.push(SyntaxError::ShadowsSignal {
                            span: name.1,
                            name: name.0.clone(),
                            by: Declaration::Let,
                        });
                        continue;
                    }
                    if self.declare(&name.0, name.1)
                        && let Some(value) = value
                    {
                        self.lets.insert(name.0.clone(), value);
                    }
                }
                AstStatement::Input(names) => {
                    for (name, span) in names {
                        if self.scope.lookup(name) != Lookup::Unknown {
                            self.errors.push(SyntaxError::ShadowsSignal {
                                span: *span,
                                name: name.clone(),
                                by: Declaration::Input,
                            });
                            continue;
                        }
                        if self.declare(name, *span) {
                            self.inputs.push((name.clone(), *span));
                        }
                    }
                }
                AstStatement::Delay(names) => {
                    for (name, span) in names {
                        if self.declare(name, *span) {
                            self.delays.push((name.clone(), *span));
                        }
                    }
                }
                AstStatement::Program(path, span) => match &doc.program {
                    Some((_, first)) => self.errors.push(SyntaxError::DuplicateName {
                        span: *span,
                        name: "program".into(),
                        first: *first,
                    }),
                    None => doc.program = Some((path.clone(), *span)),
                },
                AstStatement::Claim { kind, name, goal, proof, span } => {
                    if let Some(first) = statement_names.get(&name.0) {
                        self.errors.push(SyntaxError::DuplicateName {
                            span: name.1,
                            name: name.0.clone(),
                            first: *first,
                        });
                    } else {
                        statement_names.insert(name.0.clone(), name.1);
                    }
                    let mut out = Out::default();
                    let goal = self.goal(goal, Mode::Concrete, &mut out);
                    let proof = self.proof(proof);
                    let (Some(goal), Some(proof)) = (goal, proof) else {
                        continue;
                    };
                    doc.claims.push(Statement {
                        name: name.0.clone(),
                        name_span: name.1,
                        span: *span,
                        value: Claim { kind: *kind, goal, proof },
                    });
                }
                AstStatement::Named { kind, name, goal, conditions, span } => {
                    if *kind == NamedKind::Assume && self.scope.hypothesis_names().contains(&name.0)
                    {
                        self.errors.push(SyntaxError::ShadowsSignal {
                            span: name.1,
                            name: name.0.clone(),
                            by: Declaration::Assume,
                        });
                    } else if let Some(first) = statement_names.get(&name.0) {
                        self.errors.push(SyntaxError::DuplicateName {
                            span: name.1,
                            name: name.0.clone(),
                            first: *first,
                        });
                    } else {
                        statement_names.insert(name.0.clone(), name.1);
                    }
                    let mode = match kind {
                        NamedKind::Law => Mode::Law,
                        _ => Mode::Concrete,
                    };
                    let mut out = Out::default();
                    let goal = self.goal(goal, mode, &mut out);
                    let conditions: Vec<Option<SideCondition>> =
                        conditions.iter().map(|c| self.condition(c, &mut out)).collect();
                    let conditions: Option<Vec<SideCondition>> = conditions.into_iter().collect();
                    let (Some(goal), Some(conditions)) = (goal, conditions) else {
                        continue;
                    };
                    let make = |value| Statement {
                        name: name.0.clone(),
                        name_span: name.1,
                        span: *span,
                        value,
                    };
                    match kind {
                        NamedKind::Assume => doc.assumptions.push(make(goal)),
                        NamedKind::Property => doc.properties.push(make(goal)),
                        NamedKind::Law => {
                            let law = Law {
                                goal,
                                conditions,
                                signal_vars: out.signal_vars,
                                delay_vars: out.delay_vars,
                            };
                            doc.laws.push(Statement {
                                name: name.0.clone(),
                                name_span: name.1,
                                span: *span,
                                value: law,
                            });
                        }
                    }
                }
            }
        }
        doc.inputs = self.inputs.clone();
        doc.delays = self.delays.clone();
        doc
    }

    fn proof(&mut self, proof: &AstProof) -> Option<ScriptProof> {
        match proof {
            AstProof::Auto(span) => Some(ScriptProof::Auto(*span)),
            AstProof::Induction(span) => Some(ScriptProof::Induction(*span)),
            AstProof::By(rules, span) => Some(ScriptProof::By(rules.clone(), *span)),
            AstProof::Calc { start, steps, qed } => {
                let mut out = Out::default();
                let first = self.signal_expr(start, Mode::Concrete, &mut out);
                let mut resolved = Vec::new();
                for step in steps {
                    let relation = match step.op {
                        RelOp::Implies => Relation::Implies,
                        _ => Relation::Equals,
                    };
                    let term = self.signal_expr(&step.term, Mode::Concrete, &mut out);
                    resolved.push(term.map(|term| CalcStep {
                        relation,
                        term,
                        term_span: step.term.span,
                        rules: step.rules.clone(),
                        span: step.span,
                    }));
                }
                let steps: Option<Vec<CalcStep>> = resolved.into_iter().collect();
                Some(ScriptProof::Calc {
                    start: first?,
                    start_span: start.span,
                    steps: steps?,
                    qed: *qed,
                })
            }
        }
    }

    fn with_inputs(mut self, inputs: &[String]) -> Self {
        let span = Span::new(self.file, 0..0);
        self.inputs = inputs.iter().map(|n| (n.clone(), span)).collect();
        self
    }
}

fn finish<T>(value: Option<T>, mut errors: Vec<SyntaxError>) -> Result<T, Vec<SyntaxError>> {
    errors.sort_by_key(|e| {
        let s = e.primary_span();
        (s.start, s.end)
    });
    errors.dedup();
    match value {
        Some(v) if errors.is_empty() => Ok(v),
        _ => Err(errors),
    }
}

/// Lexes, parses and resolves a whole file.
pub(super) fn document(
    text: &str,
    file: FileId,
    scope: &dyn Scope,
) -> Result<Document, Vec<SyntaxError>> {
    let (tokens, mut errors) = lex(text, file);
    let (statements, parse_errors) = Parser::new(tokens).document();
    errors.extend(parse_errors);
    let mut resolver = Resolver::new(file, scope);
    let doc = resolver.statements(&statements);
    errors.extend(resolver.errors);
    finish(Some(doc), errors)
}

/// Resolves one parsed item (an expression or a goal) with `resolve`, collecting the
/// parse error or the resolver's errors.
fn resolve_one<A, T>(
    ast: Result<A, SyntaxError>,
    mut errors: Vec<SyntaxError>,
    mut resolver: Resolver<'_>,
    resolve: impl FnOnce(&mut Resolver<'_>, &A) -> Option<T>,
) -> Result<T, Vec<SyntaxError>> {
    let ast = match ast {
        Ok(a) => a,
        Err(e) => {
            errors.push(e);
            return finish(None, errors);
        }
    };
    let value = resolve(&mut resolver, &ast);
    errors.extend(resolver.errors);
    finish(value, errors)
}

/// Lexes, parses and resolves one expression.
pub(super) fn expression(
    text: &str,
    file: FileId,
    scope: &dyn Scope,
    inputs: &[String],
) -> Result<Expr, Vec<SyntaxError>> {
    let (tokens, errors) = lex(text, file);
    let mut parser = Parser::new(tokens);
    let ast = parser.expr().and_then(|a| parser.end().map(|()| a));
    resolve_one(ast, errors, Resolver::new(file, scope).with_inputs(inputs), |r, a| {
        r.signal_expr(a, Mode::Concrete, &mut Out::default())
    })
}

/// Lexes, parses and resolves one goal, or one `property`/`assume` statement.
pub(super) fn goal(
    text: &str,
    file: FileId,
    scope: &dyn Scope,
    inputs: &[String],
) -> Result<Goal, Vec<SyntaxError>> {
    use super::lexer::Keyword;
    let (tokens, errors) = lex(text, file);
    let statement = matches!(
        tokens.first().map(|t| &t.tok),
        Some(Tok::Keyword(Keyword::Property | Keyword::Assume))
    );
    let mut parser = Parser::new(tokens);
    let ast = if statement {
        parser.statement().and_then(|s| match s {
            AstStatement::Named { goal, .. } => Ok(*goal),
            // `statement` returns a named statement for these keywords.
            _ => Err(SyntaxError::UnexpectedToken {
                span: Span::new(file, 0..0),
                found: "a statement".into(),
                expected: vec!["a goal".into()],
            }),
        })
    } else {
        parser.goal()
    };
    let ast = ast.and_then(|a| parser.end().map(|()| a));
    resolve_one(ast, errors, Resolver::new(file, scope).with_inputs(inputs), |r, a| {
        r.goal(a, Mode::Concrete, &mut Out::default())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::NoProgram;
    use crate::term::{same, sexp};

    fn expr(text: &str) -> Expr {
        let inputs: Vec<String> = ["f", "g", "h", "s", "r"].map(String::from).to_vec();
        expression(text, 0, &NoProgram, &inputs).unwrap_or_else(|e| panic!("{text}: {e:?}"))
    }

    fn err(text: &str) -> SyntaxError {
        let inputs: Vec<String> = ["f", "g"].map(String::from).to_vec();
        expression(text, 0, &NoProgram, &inputs).unwrap_err().remove(0)
    }

    #[test]
    fn precedence_and_associativity() {
        assert!(same(&expr("f + g . h"), &sexp("(+ f (& g h))")));
        assert!(same(&expr("f . g . h"), &sexp("(& (& f g) h)")));
        assert!(same(&expr("f . (g . h)"), &sexp("(& f (& g h))")));
        assert!(same(&expr("!f/5s"), &sexp("(tof (! f) 5s)")));
        assert!(same(&expr("!(5s/f)"), &sexp("(! (ton 5s f))")));
        assert!(same(&expr("¬¬f ∨ 0"), &sexp("(+ (! (! f)) 0*)")));
        assert!(same(&expr("SR(s, r) · RS(s, 1*)"), &sexp("(& (sr s r) (rs s 1*))")));
    }

    #[test]
    fn slash_chains() {
        assert!(same(&expr("2s/5s/f"), &sexp("(ton 2s (ton 5s f))")));
        assert!(same(&expr("f/1s/2s"), &sexp("(tof (tof f 1s) 2s)")));
        assert!(same(&expr("(5s/f)/2s"), &sexp("(tof (ton 5s f) 2s)")));
        assert!(same(&expr("max(1s, 2s)/f"), &sexp("(ton 2s f)")));
        assert!(same(&expr("(1s + 250ms)/f"), &sexp("(ton 1.25s f)")));
        assert!(matches!(err("5s/f/2s"), SyntaxError::BothDelayKinds { .. }));
        assert!(matches!(err("f/g"), SyntaxError::NoDuration { .. }));
        assert!(matches!(err("5s/2s"), SyntaxError::NoSignal { .. }));
        assert!(matches!(err("f . 5s"), SyntaxError::DurationAsSignal { .. }));
    }

    #[test]
    fn after_goals() {
        let g = goal("after 5s: f => g", 0, &NoProgram, &["f".into(), "g".into()]).unwrap();
        assert_eq!(g.after, Some("5s".parse().unwrap()));
        assert!(same(&g.lhs_with_after(), &sexp("(& (ton 5s 1*) f)")));
        let g = goal("property P: f = g", 0, &NoProgram, &["f".into(), "g".into()]).unwrap();
        assert_eq!(g.relation, Relation::Equals);
    }

    #[test]
    fn names_resolve_and_unknown_names_are_reported() {
        match err("f . gg") {
            SyntaxError::UnknownName { suggestion, .. } => {
                assert_eq!(suggestion.as_deref(), Some("g"));
            }
            e => panic!("{e:?}"),
        }
        let text = "input pump, up\nlet L = pump + up\nproperty P: L => pmup";
        let errors = document(text, 0, &NoProgram).unwrap_err();
        match &errors[0] {
            SyntaxError::UnknownName { suggestion, .. } => {
                assert_eq!(suggestion.as_deref(), Some("pump"))
            }
            e => panic!("{e:?}"),
        }
    }

    #[test]
    fn laws_have_metavariables() {
        let text = "delay d, e\nlaw L: d/(e/f) = (d + e)/f if d >= e, f . g = 0*";
        let doc = document(text, 0, &NoProgram).unwrap();
        let law = &doc.laws[0].value;
        assert_eq!(law.signal_vars, vec![Symbol::from("f"), Symbol::from("g")]);
        assert_eq!(law.delay_vars, vec![Symbol::from("d"), Symbol::from("e")]);
        assert!(same(&law.goal.rhs, &sexp("(ton (dadd d e) f)")));
        assert_eq!(law.conditions.len(), 2);
        let errors = document("law L: x/f = f", 0, &NoProgram).unwrap_err();
        assert!(matches!(errors[0], SyntaxError::UndeclaredDelay { .. }));
        let errors = document("delay d\nproperty P: d/f => f", 0, &NoProgram).unwrap_err();
        assert!(matches!(errors[0], SyntaxError::DelayVariableOutsideLaw { .. }));
    }

    /// A program whose lookup ignores case, with `T1` ambiguous.
    struct Program;

    impl Scope for Program {
        fn lookup(&self, name: &str) -> Lookup {
            if name == "T1" {
                return Lookup::Ambiguous(vec!["T1.Q".into(), "T1.ET".into()]);
            }
            self.names()
                .into_iter()
                .find(|n| n.eq_ignore_ascii_case(name))
                .map_or(Lookup::Unknown, Lookup::Signal)
        }
        fn names(&self) -> Vec<String> {
            vec!["L1_pump".into(), "T1.Q".into(), "T1.ET".into()]
        }
    }

    #[test]
    fn program_names_resolve_to_canonical_names() {
        let text = "input free\nproperty P: l1_PUMP . `T1.Q` => free";
        let doc = document(text, 0, &Program).unwrap();
        assert!(same(&doc.properties[0].value.lhs, &sexp("(& L1_pump T1.Q)")));
        let errors = document("property P: T1 => L1_pmp", 0, &Program).unwrap_err();
        assert!(matches!(errors[0], SyntaxError::AmbiguousName { .. }));
        match &errors[1] {
            SyntaxError::UnknownName { suggestion, known, .. } => {
                assert_eq!(suggestion.as_deref(), Some("L1_pump"));
                assert_eq!(known.len(), 3);
            }
            e => panic!("{e:?}"),
        }
    }

    #[test]
    fn delay_arithmetic_folds_only_literals() {
        let doc =
            document("delay d\nlaw L: max(1s, 2s)/f = (d + 1s + 2s)/f", 0, &NoProgram).unwrap();
        let goal = &doc.laws[0].value.goal;
        assert!(same(&goal.lhs, &sexp("(ton 2s f)")));
        assert!(same(&goal.rhs, &sexp("(ton (dadd (dadd d 1s) 2s) f)")));
        let doc =
            document("delay d\nlaw L: d/f = d/f if d + 1s >= max(d, 2s)", 0, &NoProgram).unwrap();
        assert!(matches!(
            &doc.laws[0].value.conditions[0],
            SideCondition::Delay { op: DelayComparison::Ge, .. }
        ));
    }

    #[test]
    fn several_errors_at_once() {
        let text = "property A: f/g => 0\nproperty B: ( => 1\nproperty A: 1 => 1";
        let errors = document(text, 0, &NoProgram).unwrap_err();
        assert!(errors.len() >= 3, "{errors:?}");
    }
}
