//! What the session shows: terms, goals and steps in its notation and the program's
//! names, `help`, `trace`, `show`, `axioms`, and the text of a step's or a name's error.

use std::time::Duration;

use super::{Open, Session};
use crate::diag::{Diagnostic, RenderStyle, did_you_mean, render};
use crate::repl::COMMANDS;
use crate::script::StepError;
use crate::syntax::{self, CalcStep, Goal, RuleRef, SyntaxError, step_to_string};
use crate::term::{Expr, Symbol, Term, root};

/// `1 hypothesis`, `2 hypotheses`.
pub(super) fn counted(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

pub(super) fn ms(d: Duration) -> String {
    format!("{:.1} ms", d.as_secs_f64() * 1e3)
}

impl Session {
    pub(super) fn term(&self, e: &Expr) -> String {
        self.checker.term(e)
    }

    /// A canonical signal name as shown (the program's short name when unambiguous).
    pub(super) fn display(&self, name: &str) -> String {
        match &self.program {
            Some((_, program)) => program.display_name(name),
            None => name.to_string(),
        }
    }

    pub(super) fn step_line(&self, step: &CalcStep) -> String {
        let term = match &self.program {
            Some((_, program)) => program.rename_for_display(&step.term),
            None => step.term.clone(),
        };
        step_to_string(step.relation, &term, &step.rules, self.notation)
    }

    pub(super) fn goal_text(&self, goal: &Goal) -> String {
        self.checker.goal_text(goal)
    }

    pub(super) fn syntax_errors(&self, errors: Vec<SyntaxError>) -> String {
        errors
            .into_iter()
            .map(|e| render(&Diagnostic::from(e), &self.sources, RenderStyle::default()))
            .collect()
    }

    pub(super) fn help(&self, rest: &str) -> String {
        if !rest.is_empty() {
            return match COMMANDS.iter().find(|c| c.name == rest) {
                Some(c) => format!("{}\n    {}\n", c.usage, c.help),
                None => format!("error: no command `{rest}`\n"),
            };
        }
        let width = COMMANDS.iter().map(|c| c.usage.chars().count()).max().unwrap_or(0);
        let mut out = String::new();
        for c in COMMANDS {
            out.push_str(&format!("  {:<width$}  {}\n", c.usage, c.help));
        }
        out.push_str(
            "Ctrl-C discards the current input or abandons a running proof; Ctrl-D leaves.\n",
        );
        out
    }

    /// `prove NAME` where no property is called NAME: say so, with the loaded ones.
    pub(super) fn no_such_property(&self, name: &str) -> String {
        let names: Vec<&str> = self.properties.iter().map(|p| p.name.as_str()).collect();
        let mut out = format!("error: no property `{name}` is loaded");
        if let Some(near) = did_you_mean(name, names.iter().copied()) {
            out.push_str(&format!(" (did you mean `{near}`?)"));
        }
        if names.is_empty() {
            out.push_str("; `load FILE.ii` reads properties, `prove F => G` proves a goal\n");
        } else {
            out.push_str(&format!("; the loaded properties: {}\n", names.join(", ")));
        }
        out
    }

    pub(super) fn calculation(&self, open: &Open) -> String {
        let mut out = format!("    {}\n", self.term(&open.lhs));
        for (step, _) in &open.steps {
            out.push_str(&self.step_line(step));
            out.push('\n');
        }
        out
    }

    pub(super) fn step_error(&self, e: StepError, rules: &[RuleRef]) -> String {
        match e {
            StepError::Unknown(i, suggestion, claim) => {
                let name = rules.get(i).map_or("?", |r| r.name.as_str());
                let why = if claim {
                    "is a claim that did not check"
                } else {
                    "is no law, hypothesis or lemma"
                };
                let hint =
                    suggestion.map(|s| format!(" (did you mean `{s}`?)")).unwrap_or_default();
                format!("error: `{name}` {why}{hint}\n")
            }
            StepError::NoProof(reason) => {
                let mut out = format!("error: the step does not follow: {reason}\n");
                for r in rules {
                    if let Some(d) = self.checker.describe(&r.name) {
                        out.push_str(&format!("  = {d}\n"));
                    }
                }
                out
            }
            StepError::Auto(reason) => format!("error: `auto` found no proof: {reason}\n"),
            StepError::OnlyImplication => {
                "error: this step holds only as an implication: write it with `=>`\n".into()
            }
        }
    }

    pub(super) fn trace(&self, rest: &str) -> String {
        let all = match rest {
            "" => false,
            "all" => true,
            _ => return format!("error: expected `trace` or `trace all`, found `{rest}`\n"),
        };
        if let Some(open) = &self.open {
            return format!(
                "goal {}: {}\n{}",
                open.name,
                self.goal_text(&open.goal),
                self.calculation(open)
            );
        }
        let lines = if all { &self.last_trace_all } else { &self.last_trace };
        if lines.is_empty() {
            return "no proof yet\n".into();
        }
        lines.iter().map(|l| format!("{l}\n")).collect()
    }

    pub(super) fn show(&self, rest: &str) -> String {
        let name = rest.trim();
        if name.is_empty() {
            return "error: expected `show NAME`\n".into();
        }
        if let Some(text) = self.checker.describe(name) {
            return format!("{text}\n");
        }
        if let Some(p) = self.properties.iter().find(|p| p.name == name) {
            return format!("property {name}: {}\n", self.goal_text(&p.value));
        }
        let canonical = match self.scope().lookup(name) {
            syntax::Lookup::Signal(c) => c,
            _ => name.to_string(),
        };
        let symbol = Symbol::from(canonical.as_str());
        let mentions =
            |e: &Expr| e.as_ref().iter().any(|n| matches!(n, Term::Name(s) if *s == symbol));
        let mut defining = Vec::new();
        let mut others = Vec::new();
        for h in self.checker.ctx.hypotheses() {
            if matches!(&h.lhs[root(&h.lhs)], Term::Name(s) if *s == symbol) {
                defining.push(h.name.clone());
            } else if mentions(&h.lhs) || mentions(&h.rhs) {
                others.push(h.name.clone());
            }
        }
        if defining.is_empty() && others.is_empty() {
            if self.inputs.iter().any(|i| i == name) {
                return format!("{name} is a free signal (no hypothesis mentions it)\n");
            }
            let mut names = self.checker.rule_names();
            names.extend(self.inputs.iter().cloned());
            let hint = did_you_mean(name, names.iter().map(String::as_str))
                .map(|s| format!(" (did you mean `{s}`?)"))
                .unwrap_or_default();
            return format!("error: `{name}` is no signal, law, hypothesis or lemma{hint}\n");
        }
        let mut out = String::new();
        for h in defining {
            if let Some(d) = self.checker.describe(&h) {
                out.push_str(&format!("{d}\n"));
            }
        }
        if !others.is_empty() {
            out.push_str(&format!("{name} also appears in {}\n", others.join(", ")));
        }
        out
    }

    pub(super) fn axioms(&self, prefix: &str) -> String {
        let prefix = prefix.trim();
        let mut out = String::new();
        let mut count = 0;
        for name in self.checker.rule_names() {
            if name.starts_with(prefix)
                && let Some(d) = self.checker.describe(&name)
            {
                out.push_str(&format!("{d}\n"));
                count += 1;
            }
        }
        out.push_str(&format!("{}\n", counted(count, "rule", "rules")));
        out
    }
}
