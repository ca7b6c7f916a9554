//! Statements: goals (with `after`), requirement patterns, a law's side conditions,
//! `let`, `input`, `delay`, `program`, named statements and claims with their proofs,
//! into a `Document`.

use std::collections::HashMap;

use super::nodes::Out;
use super::terms::DVal;
use super::{Mode, Resolver};
use crate::diag::Span;
use crate::syntax::ast::{Ast, AstGoal, AstPattern, AstProof, AstStatement, NamedKind, RelOp};
use crate::syntax::pattern::{self, Pattern};
use crate::syntax::{
    CalcStep, Claim, Declaration, DelayComparison, Document, Goal, Law, Lookup, Relation,
    ScriptProof, SideCondition, Statement, SyntaxError,
};
use crate::term::{Delay, Expr};

impl<'a> Resolver<'a> {
    pub(super) fn goal(&mut self, g: &AstGoal, mode: Mode, out: &mut Out) -> Option<Goal> {
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

    pub(super) fn statements(&mut self, statements: &[AstStatement]) -> Document {
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
                    self.name_once(&mut statement_names, name);
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
                    } else {
                        self.name_once(&mut statement_names, name);
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

    /// Records a statement's name, or reports it taken by an earlier statement.
    fn name_once(&mut self, names: &mut HashMap<String, Span>, name: &(String, Span)) {
        if let Some(first) = names.get(&name.0) {
            self.errors.push(SyntaxError::DuplicateName {
                span: name.1,
                name: name.0.clone(),
                first: *first,
            });
        } else {
            names.insert(name.0.clone(), name.1);
        }
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
}
