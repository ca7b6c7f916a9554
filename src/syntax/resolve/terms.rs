//! Terms: names (abbreviations, inputs, the program's signals, a law's metavariables),
//! `/` chains as timers, durations with their literal arithmetic folded, comparisons
//! through the scope.

use super::nodes::{MAX_NODES, MAX_TERM_DEPTH, Out, depth, push_unique};
use super::{Mode, Resolver};
use crate::diag::{Span, did_you_mean};
use crate::syntax::ast::{Ast, AstKind, Func};
use crate::syntax::{Lookup, SyntaxError};
use crate::term::{Delay, Expr, Id, Symbol, Term};

/// A resolved duration: a literal (foldable) or a node already in the builder.
pub(super) enum DVal {
    Lit(Delay),
    Node(Id),
}

impl<'a> Resolver<'a> {
    fn is_delay_var(&self, name: &str) -> bool {
        !self.lets.contains_key(name) && self.delays.iter().any(|(d, _)| d == name)
    }

    fn is_input(&self, name: &str) -> bool {
        self.inputs.iter().any(|(d, _)| d == name)
    }

    /// Is this operand of a `/` chain (or side of a comparison) a duration?
    pub(super) fn is_duration(&self, a: &Ast) -> bool {
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
    pub(super) fn delay(&mut self, a: &Ast, mode: Mode, out: &mut Out) -> Option<DVal> {
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

    pub(super) fn signal_expr(&mut self, a: &Ast, mode: Mode, out: &mut Out) -> Option<Expr> {
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

    pub(super) fn delay_expr(&mut self, a: &Ast, mode: Mode, out: &mut Out) -> Option<Expr> {
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
}
