//! A goal proved step by step: `goal`, the steps `= TERM [RULES]` and `=> TERM [RULES]`,
//! `auto`, `apply` and `undo`, and the whole calculation handed to the kernel when it
//! reaches the goal's right side.

use std::collections::BTreeSet;
use std::time::{Duration, Instant};

use super::render::ms;
use super::{CANCELLED, Open, Session, cancellable};
use crate::diag::{Span, did_you_mean};
use crate::kernel::{Proof, Rel, Rule, Source};
use crate::prover::Obligation;
use crate::repl::refute::counterexample_lines;
use crate::report;
use crate::script::{Justified, ProvedClaim, StepError};
use crate::syntax::{self, CalcStep, Claim, ClaimKind, Relation, RuleRef, ScriptProof, Statement};
use crate::term::{Expr, same};
use crate::theory;

fn relation_of(r: Rel) -> Relation {
    match r {
        Rel::Eq => Relation::Equals,
        Rel::Implies => Relation::Implies,
    }
}

impl Session {
    pub(super) fn goal(&mut self, rest: &str) -> String {
        if rest.is_empty() {
            return match &self.open {
                Some(open) => {
                    format!("goal {}: {}\n", open.name, self.goal_text(&open.goal))
                }
                None => "no goal; start one with `goal F => G`\n".into(),
            };
        }
        let (name, goal, span) = match self.parse_named_goal(rest, "goal") {
            Ok(x) => x,
            Err(e) if e.starts_with("error") => return e,
            Err(e) => return format!("error: {e}\n"),
        };
        let mut out = String::new();
        if let Some(old) = &self.open {
            out.push_str(&format!("(goal {} abandoned)\n", old.name));
        }
        let (lhs, rel, rhs) = theory::goal_parts(&goal);
        out.push_str(&format!("goal {name}: {}\n    {}\n", self.goal_text(&goal), self.term(&lhs)));
        self.open = Some(Open { name, goal, lhs, rel, rhs, span, steps: Vec::new() });
        self.closed = None;
        if let Some(open) = &self.open
            && same(&open.lhs, &open.rhs)
        {
            out.push_str(&self.finish());
        }
        out
    }

    /// Records a justified step; finishes the goal when it reaches the right side.
    fn record(&mut self, step: CalcStep, justified: Justified) -> String {
        let line = self.step_line(&step);
        let Some(open) = &mut self.open else { return String::new() };
        open.steps.push((step, justified));
        let mut out = format!("{line}\n");
        if same(open.current(), &open.rhs) {
            out.push_str(&self.finish());
        }
        out
    }

    /// The open goal reached its right side: the whole calculation goes to the kernel.
    pub(super) fn finish(&mut self) -> String {
        let Some(open) = self.open.take() else { return String::new() };
        let mut main: Option<Proof> = None;
        let mut lemmas = BTreeSet::new();
        for (_, j) in &open.steps {
            lemmas.extend(j.lemmas.iter().cloned());
            main = Some(match main {
                None => j.proof.clone(),
                Some(p) => Proof::Trans(Box::new(p), Box::new(j.proof.clone())),
            });
        }
        let main = main.unwrap_or(Proof::Chain { start: open.lhs.clone(), steps: Vec::new() });
        let started = Instant::now();
        match self.checker.check(&lemmas, main.clone(), &open.lhs, open.rel, &open.rhs) {
            Ok(_) => {
                let mut deps = lemmas.clone();
                for p in self.checker.proved.iter().rev() {
                    if deps.contains(&p.name) {
                        deps.extend(p.deps.iter().cloned());
                    }
                }
                self.checker.add_proved(ProvedClaim {
                    name: open.name.clone(),
                    lhs: open.lhs.clone(),
                    rel: open.rel,
                    rhs: open.rhs.clone(),
                    proof: main,
                    deps,
                    own: Vec::new(),
                });
                let steps = open.steps.iter().map(|(s, _)| s.clone()).collect();
                self.done.push(Statement {
                    name: open.name.clone(),
                    name_span: open.span,
                    span: open.span,
                    value: Claim {
                        kind: ClaimKind::Theorem,
                        goal: open.goal.clone(),
                        proof: ScriptProof::Calc {
                            start: open.lhs.clone(),
                            start_span: open.span,
                            steps,
                            qed: open.span,
                        },
                    },
                });
                self.last_trace = self.calculation(&open).lines().map(str::to_string).collect();
                self.last_trace_all = self.last_trace.clone();
                let text = format!(
                    "proved {}: {}  (kernel-checked, {})\n",
                    open.name,
                    self.goal_text(&open.goal),
                    ms(started.elapsed())
                );
                self.closed = Some(open);
                text
            }
            Err(e) => {
                let text = format!("error: the kernel rejects the calculation: {e}\n");
                self.open = Some(open);
                text
            }
        }
    }

    fn open_or_error(&self) -> Result<&Open, String> {
        self.open.as_ref().ok_or_else(|| "error: no goal; start one with `goal F => G`\n".into())
    }

    fn justify(
        &self,
        from: &Expr,
        rel: Rel,
        to: &Expr,
        rules: &[RuleRef],
    ) -> Option<Result<Justified, StepError>> {
        let snapshot = match self.checker.snapshot() {
            Ok(s) => s,
            Err(e) => return Some(Err(StepError::NoProof(e.to_string()))),
        };
        let (from, to, rules) = (from.clone(), to.clone(), rules.to_vec());
        cancellable(move || snapshot.justify(&from, rel, &to, &rules))
    }

    pub(super) fn step(&mut self, relation: Relation, rest: &str) -> String {
        let open = match self.open_or_error() {
            Ok(o) => o,
            Err(e) => return e,
        };
        if relation == Relation::Implies && open.rel == Rel::Eq {
            return "error: the goal is an equation; an implication step cannot prove it\n".into();
        }
        let from = open.current().clone();
        let rest = rest.trim();
        let (term_text, rules_text) = match rest.rfind('[') {
            Some(i) if rest.ends_with(']') => (&rest[..i], &rest[i + 1..rest.len() - 1]),
            _ => {
                return "error: expected `= TERM [RULE, ...]`: the rules go between brackets\n"
                    .into();
            }
        };
        let rules: Vec<RuleRef> = rules_text
            .split(',')
            .map(|r| r.trim().trim_matches('`'))
            .filter(|r| !r.is_empty())
            .map(|r| RuleRef { name: r.to_string(), span: Span::new(0, 0..0) })
            .collect();
        if rules.is_empty() {
            return "error: cite at least one rule (or `auto`) between the brackets\n".into();
        }
        let file = self.source(term_text.trim());
        let term = match syntax::parse_expression(&self.sources, file, self.scope(), &self.inputs) {
            Ok(t) => t,
            Err(errors) => return self.syntax_errors(errors),
        };
        if let Err(e) = self.define_atoms() {
            return format!("error: {e}\n");
        }
        let span = Span::new(file, 0..term_text.trim().len());
        let Some(result) = self.justify(&from, theory::relation(relation), &term, &rules) else {
            return CANCELLED.into();
        };
        match result {
            Ok(justified) => {
                let step = CalcStep { relation, term, term_span: span, rules, span };
                self.record(step, justified)
            }
            Err(e) => self.step_error(e, &rules),
        }
    }

    pub(super) fn auto(&mut self) -> String {
        let open = match self.open_or_error() {
            Ok(o) => o,
            Err(e) => return e,
        };
        let (from, rel, to, span) = (open.current().clone(), open.rel, open.rhs.clone(), open.span);
        let rules = vec![RuleRef { name: "auto".into(), span }];
        let Some(result) = self.justify(&from, rel, &to, &rules) else {
            return CANCELLED.into();
        };
        match result {
            Ok(justified) => {
                let step =
                    CalcStep { relation: relation_of(rel), term: to, term_span: span, rules, span };
                self.record(step, justified)
            }
            Err(StepError::Auto(reason)) => {
                // As on the command line: is what is left to prove false?
                let mut out = format!("error: `auto` found no proof: {reason}\n");
                let goal = Obligation { lhs: from, rel, rhs: to };
                let kit = self.search_kit(Duration::from_secs(10));
                let Some(found) = cancellable(move || {
                    kit.run(|assumed, opts, rename, program| {
                        report::refute(&goal, assumed, opts, rename, program)
                    })
                }) else {
                    return CANCELLED.into();
                };
                if let Some(c) = found {
                    out.push_str(&format!(
                        "  what is left is false (confirmed by {}):\n{}",
                        c.confirmed_by.join(" and "),
                        counterexample_lines(&c)
                    ));
                }
                out
            }
            Err(e) => self.step_error(e, &rules),
        }
    }

    pub(super) fn apply(&mut self, rest: &str) -> String {
        let open = match self.open_or_error() {
            Ok(o) => o,
            Err(e) => return e,
        };
        let (name, path) = match rest.split_once(" at ") {
            Some((n, p)) => (n.trim(), Some(p.trim())),
            None => (rest.trim(), None),
        };
        if name.is_empty() {
            return "error: expected `apply RULE [at PATH]`\n".into();
        }
        let path: Option<Vec<usize>> = match path {
            None => None,
            Some("root") | Some("") => Some(Vec::new()),
            Some(p) => {
                let parts: Result<Vec<usize>, _> =
                    p.split(['.', ',', ' ']).filter(|s| !s.is_empty()).map(str::parse).collect();
                match parts {
                    Ok(v) => Some(v),
                    Err(_) => {
                        return format!(
                            "error: `{p}` is not a path (child indices such as `1.0`)\n"
                        );
                    }
                }
            }
        };
        let rules = vec![RuleRef { name: name.to_string(), span: open.span }];
        if self.checker.lookup(name).is_none() {
            let names = self.checker.rule_names();
            let hint = did_you_mean(name, names.iter().map(String::as_str))
                .map(|s| format!(" (did you mean `{s}`?)"))
                .unwrap_or_default();
            return format!("error: `{name}` is no law, hypothesis or lemma{hint}\n");
        }
        let current = open.current().clone();
        let goal_rel = open.rel;
        let span = open.span;
        let (found, objection) = self.checker.rewrites(&current, name, path.as_deref(), None);
        let fitting = found.iter().find(|(_, rel)| goal_rel == Rel::Implies || *rel == Rel::Eq);
        let Some((step, rel)) = fitting.cloned() else {
            if !found.is_empty() {
                return format!(
                    "error: `{name}` gives only an implication here, and the goal is an equation\n"
                );
            }
            if let Some(why) = objection {
                return format!("error: {why}\n");
            }
            let place = match &path {
                Some(p) => format!(" at {p:?}"),
                None => String::new(),
            };
            return format!(
                "error: `{name}` does not rewrite {}{place} (a rule whose result has new variables needs a step `= TERM [{name}]`)\n",
                self.term(&current)
            );
        };
        let lemmas: BTreeSet<String> = match &step.rule {
            Rule::Cite(Source::Lemma, n, _) => [n.clone()].into(),
            _ => BTreeSet::new(),
        };
        let term = step.after.clone();
        let proof = Proof::Chain { start: current, steps: vec![step] };
        let calc = CalcStep { relation: relation_of(rel), term, term_span: span, rules, span };
        self.record(calc, Justified { proof, lemmas })
    }

    pub(super) fn undo(&mut self) -> String {
        if let Some(open) = &mut self.open {
            if open.steps.pop().is_none() {
                return "nothing to undo\n".into();
            }
            let now = self.checker.term(open.current());
            return format!("undone; now at\n    {now}\n");
        }
        if let Some(mut open) = self.closed.take() {
            self.checker.forget(&open.name);
            self.done.retain(|d| d.name != open.name);
            open.steps.pop();
            let text =
                format!("goal {} reopened; now at\n    {}\n", open.name, self.term(open.current()));
            self.open = Some(open);
            return text;
        }
        "nothing to undo\n".into()
    }
}
