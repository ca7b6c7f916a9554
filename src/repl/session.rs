//! The state of a REPL session and the commands that change it; every command returns
//! its output text. This file holds the session's state, the dispatch of commands, its
//! inputs and hypotheses and `prove`; a goal proved step by step is `calc.rs`, loading
//! and saving files `files.rs`, what the session shows `render.rs`, `simulate`
//! `simulate.rs`.

use std::sync::atomic::Ordering;
use std::sync::mpsc;
use std::time::{Duration, Instant};

use super::refute::{SearchKit, counterexample_lines};
use super::{CANCEL, COMMANDS};
use crate::diag::{RenderStyle, Sources, Span, did_you_mean, render};
use crate::kernel::{Axiom, Rel};
use crate::ladder::CompiledProgram;
use crate::prover::{self, Obligation};
use crate::report::{self, Attempt, trace};
use crate::script::{Checker, Justified, ProvedClaim};
use crate::syntax::Scope;
use crate::syntax::{
    self, CalcStep, Claim, ClaimKind, Goal, NoProgram, Notation, Relation, ScriptProof, Statement,
};
use crate::term::Expr;
use crate::theory::{self, Theory};
use render::ms;

mod calc;
mod files;
mod render;
mod simulate;

/// A goal being proved step by step.
#[derive(Clone)]
struct Open {
    name: String,
    goal: Goal,
    lhs: Expr,
    rel: Rel,
    rhs: Expr,
    span: Span,
    steps: Vec<(CalcStep, Justified)>,
}

impl Open {
    fn current(&self) -> &Expr {
        self.steps.last().map_or(&self.lhs, |(s, _)| &s.term)
    }
}

/// One REPL session: signals, hypotheses, proved claims, the open goal.
pub struct Session {
    sources: Sources,
    theory: Theory,
    inputs: Vec<String>,
    assumptions: Vec<Statement<Goal>>,
    properties: Vec<Statement<Goal>>,
    checker: Checker,
    open: Option<Open>,
    closed: Option<Open>,
    done: Vec<Statement<Claim>>,
    /// The last finished proof, folded and (`trace all`) with every lemma in full.
    last_trace: Vec<String>,
    last_trace_all: Vec<String>,
    notation: Notation,
    counter: usize,
    program: Option<(String, CompiledProgram)>,
    /// The loaded program as read (its scan simulator replays counterexamples).
    reference: Option<std::sync::Arc<dyn crate::ladder::Reference>>,
    program_hypotheses: Vec<Axiom>,
}

fn is_ident(s: &str) -> bool {
    let mut chars = s.chars();
    chars.next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// Splits `NAME: rest` off a goal (not `after 5s: ...`).
fn named_goal(text: &str) -> (Option<String>, &str) {
    if let Some((head, rest)) = text.split_once(':') {
        let head = head.trim();
        if is_ident(head) && head != "after" {
            return (Some(head.to_string()), rest);
        }
    }
    (None, text)
}

/// Runs `job` on a worker thread; `None` if Ctrl-C was pressed before it finished.
fn cancellable<T: Send + 'static>(job: impl FnOnce() -> T + Send + 'static) -> Option<T> {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(job());
    });
    loop {
        match rx.recv_timeout(Duration::from_millis(20)) {
            Ok(value) => return Some(value),
            Err(mpsc::RecvTimeoutError::Timeout) => {
                if CANCEL.swap(false, Ordering::SeqCst) {
                    return None;
                }
            }
            Err(mpsc::RecvTimeoutError::Disconnected) => return None,
        }
    }
}

const CANCELLED: &str = "cancelled (Ctrl-C): the command was abandoned\n";

impl Session {
    /// A session with the standard laws and nothing else.
    pub fn new() -> Result<Session, String> {
        let mut sources = Sources::new();
        let theory = theory::standard(&mut sources).map_err(|d| {
            d.iter().map(|d| render(d, &sources, RenderStyle::default())).collect::<String>()
        })?;
        let checker = Checker::new(theory.axioms(), Vec::new()).map_err(|e| e.to_string())?;
        Ok(Session {
            sources,
            theory,
            inputs: Vec::new(),
            assumptions: Vec::new(),
            properties: Vec::new(),
            checker,
            open: None,
            closed: None,
            done: Vec::new(),
            last_trace: Vec::new(),
            last_trace_all: Vec::new(),
            notation: Notation::Paper,
            counter: 0,
            program: None,
            reference: None,
            program_hypotheses: Vec::new(),
        })
    }

    /// Names for tab completion: commands, signals, laws, hypotheses, lemmas, properties.
    pub fn completion_names(&self) -> Vec<String> {
        let mut names: Vec<String> = COMMANDS.iter().map(|c| c.name.to_string()).collect();
        names.extend(self.inputs.iter().cloned());
        names.extend(self.checker.rule_names());
        names.extend(self.properties.iter().map(|p| p.name.clone()));
        if let Some((_, program)) = &self.program {
            // The program's signals: exact names, and short ones where unambiguous.
            names.extend(program.names());
        }
        names.push("auto".into());
        names
    }

    fn source(&mut self, text: &str) -> usize {
        self.counter += 1;
        self.sources.add(format!("<repl {}>", self.counter), text.to_string())
    }

    /// Runs one command (possibly several lines) and returns what it prints.
    pub fn execute(&mut self, command: &str) -> String {
        let text = command.trim();
        if text.is_empty() || text.starts_with("//") || text.starts_with('#') {
            return String::new();
        }
        if let Some(rest) = text.strip_prefix("=>").or_else(|| text.strip_prefix('⇒')) {
            return self.step(Relation::Implies, rest);
        }
        if let Some(rest) = text.strip_prefix('=') {
            return self.step(Relation::Equals, rest);
        }
        let (word, rest) = match text.split_once(char::is_whitespace) {
            Some((w, r)) => (w, r.trim()),
            None => (text, ""),
        };
        match word {
            "help" => self.help(rest),
            "input" => self.input(rest),
            "assume" => self.assume(text),
            "load" => self.load(rest),
            "goal" => self.goal(rest),
            "prove" => self.prove(rest),
            "apply" => self.apply(rest),
            "auto" => self.auto(),
            "undo" => self.undo(),
            "trace" => self.trace(rest),
            "show" => self.show(rest),
            "simulate" => self.simulate(rest),
            "axioms" => self.axioms(rest),
            "save" => self.save(rest),
            "check" => self.check(rest),
            "quit" | "exit" => String::new(),
            other => {
                let names = COMMANDS.iter().map(|c| c.name);
                let hint = did_you_mean(other, names)
                    .map(|s| format!(" (did you mean `{s}`?)"))
                    .unwrap_or_default();
                format!("error: unknown command `{other}`{hint}; `help` lists the commands\n")
            }
        }
    }

    fn input(&mut self, rest: &str) -> String {
        let mut added = Vec::new();
        for written in rest.split(',').map(str::trim).filter(|n| !n.is_empty()) {
            let quoted = written.len() > 2 && written.starts_with('`') && written.ends_with('`');
            let name = written.trim_matches('`');
            if !(is_ident(name) || quoted && !name.contains('\n')) {
                return format!(
                    "error: `{written}` is not a signal name (write other names between back quotes)\n"
                );
            }
            if syntax::lexer::Keyword::from_text(name).is_some() {
                return format!("error: `{name}` is a reserved word\n");
            }
            if !self.inputs.iter().any(|n| n == name) {
                self.inputs.push(name.to_string());
                added.push(name.to_string());
            }
        }
        if added.is_empty() {
            return "no new inputs\n".into();
        }
        format!("inputs: {}\n", added.join(", "))
    }

    fn rebuild(&mut self) -> Result<(), String> {
        let mut hypotheses: Vec<Axiom> = self.program_hypotheses.clone();
        hypotheses.extend(self.assumptions.iter().map(|s| {
            let (lhs, rel, rhs) = theory::goal_parts(&s.value);
            Axiom::ground(s.name.clone(), lhs, rel, rhs)
        }));
        let cycle = self.program.as_ref().map(|(_, c)| c.scan_cycle());
        let mut checker = Checker::with_scans(self.theory.axioms(), hypotheses, cycle)
            .map_err(|e| e.to_string())?;
        checker.proved = std::mem::take(&mut self.checker.proved);
        checker.failed = std::mem::take(&mut self.checker.failed);
        checker.notation = self.notation;
        checker.display = self.program.as_ref().map(|(_, c)| c.clone());
        checker.ctx.hints = self.program.as_ref().map(|(_, c)| c.bound_hints()).unwrap_or_default();
        self.checker = checker;
        Ok(())
    }

    fn fresh_name(&self, name: &str) -> Result<(), String> {
        if self.checker.lookup(name).is_some() {
            return Err(format!("`{name}` is already a law, hypothesis or proved claim"));
        }
        if self.properties.iter().any(|p| p.name == name) {
            return Err(format!("`{name}` is already a property"));
        }
        Ok(())
    }

    fn assume(&mut self, text: &str) -> String {
        let body = text.trim_start_matches("assume").trim();
        let Some((name, _)) = body.split_once(':') else {
            return "error: expected `assume NAME: F = G`\n".into();
        };
        let name = name.trim().to_string();
        if !is_ident(&name) {
            return format!("error: `{name}` is not a name for a hypothesis\n");
        }
        if let Err(e) = self.fresh_name(&name) {
            return format!("error: {e}\n");
        }
        let file = self.source(text);
        let goal = match syntax::parse_goal(&self.sources, file, self.scope(), &self.inputs) {
            Ok(g) => g,
            Err(errors) => return self.syntax_errors(errors),
        };
        if let Err(e) = self.define_atoms() {
            return format!("error: {e}\n");
        }
        let span = Span::new(file, 0..text.len());
        let shown = self.goal_text(&goal);
        self.assumptions.push(Statement { name: name.clone(), name_span: span, span, value: goal });
        if let Err(e) = self.rebuild() {
            self.assumptions.pop();
            let _ = self.rebuild();
            return format!("error: the hypothesis is not accepted: {e}\n");
        }
        format!("assumed {name}: {shown}\n")
    }

    /// Gives the comparison atoms (`[Cparts >= 10]`) a line has just used their
    /// equations, as hypotheses of the session (see `program::atoms`).
    fn define_atoms(&mut self) -> Result<(), String> {
        let Some((path, compiled)) = &self.program else { return Ok(()) };
        if !compiled.atoms_pending() {
            return Ok(());
        }
        let compiled = compiled.with_atoms();
        self.program_hypotheses = compiled.axioms();
        self.program = Some((path.clone(), compiled));
        self.rebuild()
    }

    /// The names in scope: the loaded program's signals (and the inputs).
    fn scope(&self) -> &dyn Scope {
        match &self.program {
            Some((_, compiled)) => compiled,
            None => &NoProgram,
        }
    }

    fn parse_named_goal(
        &mut self,
        rest: &str,
        default: &str,
    ) -> Result<(String, Goal, Span), String> {
        let (name, body) = named_goal(rest);
        let name = match name {
            Some(n) => n,
            None => {
                let mut k = self.done.len() + 1;
                loop {
                    let candidate = format!("{default}{k}");
                    if self.fresh_name(&candidate).is_ok() {
                        break candidate;
                    }
                    k += 1;
                }
            }
        };
        if self.checker.lookup(&name).is_some() {
            return Err(format!("`{name}` is already a law, hypothesis or proved claim"));
        }
        let file = self.source(body.trim());
        let goal = syntax::parse_goal(&self.sources, file, self.scope(), &self.inputs)
            .map_err(|errors| self.syntax_errors(errors))?;
        self.define_atoms().map_err(|e| format!("error: {e}\n"))?;
        Ok((name, goal, Span::new(file, 0..body.trim().len())))
    }

    fn prove(&mut self, rest: &str) -> String {
        let (name, goal, span) = if rest.is_empty() {
            match self.open.take() {
                Some(open) => (open.name, open.goal, open.span),
                None => return "error: no goal to prove; `prove F => G` or `goal F => G`\n".into(),
            }
        } else if let Some(p) = self.properties.iter().find(|p| p.name == rest) {
            if self.checker.lookup(&p.name).is_some() {
                return format!(
                    "error: `{}` is already a law, hypothesis or proved claim\n",
                    p.name
                );
            }
            (p.name.clone(), p.value.clone(), p.span)
        } else if is_ident(rest) {
            return self.no_such_property(rest);
        } else {
            match self.parse_named_goal(rest, "goal") {
                Ok(x) => x,
                Err(e) if e.starts_with("error") => return e,
                Err(e) => return format!("error: {e}\n"),
            }
        };
        let (lhs, rel, rhs) = theory::goal_parts(&goal);
        let snapshot = match self.checker.snapshot() {
            Ok(s) => s,
            Err(e) => return format!("error: {e}\n"),
        };
        let obligation = Obligation { lhs: lhs.clone(), rel, rhs: rhs.clone() };
        let started = Instant::now();
        // The command line's attempt: the proof search and the counterexample search.
        let kit = self.search_kit(snapshot.budget.time.div_f64(0.7));
        let Some(outcome) = cancellable(move || {
            kit.run(|assumed, opts, rename, program| {
                report::attempt(&snapshot.ctx, &obligation, assumed, opts, rename, program)
            })
        }) else {
            return CANCELLED.into();
        };
        let statement = self.goal_text(&goal);
        match outcome {
            Attempt::Proved(proved) => {
                let parts = (lhs, rel, rhs);
                let Some(claim) = ProvedClaim::from_certificate(&name, parts, &proved.certificate)
                else {
                    return "error: the prover returned no proof\n".into();
                };
                if let Err(e) = self.checker.add_checked(claim) {
                    return format!("error: the kernel rejects the proof: {e}\n");
                }
                let program = self.program.as_ref().map(|(_, c)| c);
                let rename = |e: &Expr| match program {
                    Some(c) => c.rename_for_display(e),
                    None => e.clone(),
                };
                let style = trace::Style { notation: self.notation, rename: &rename };
                self.last_trace = trace::render(&proved, rel, &style, trace::Detail::Folded);
                self.last_trace_all = trace::render(&proved, rel, &style, trace::Detail::Full);
                self.done.push(Statement {
                    name: name.clone(),
                    name_span: span,
                    span,
                    value: Claim { kind: ClaimKind::Theorem, goal, proof: ScriptProof::Auto(span) },
                });
                self.closed = None;
                let method = match proved.method {
                    prover::Method::Saturation => "by rewriting",
                    prover::Method::CaseSplit => "by cases",
                    prover::Method::Induction => "by induction over scans",
                };
                format!(
                    "proved {name}: {statement}  ({method}, kernel-checked, {}; `trace` shows the proof)\n",
                    ms(started.elapsed())
                )
            }
            Attempt::Refuted(c) => format!(
                "refuted {name}: {statement}  (confirmed by {}, {})\n{}",
                c.confirmed_by.join(" and "),
                ms(started.elapsed()),
                counterexample_lines(&c)
            ),
            Attempt::Unknown { reason, candidate } => {
                let mut out = format!("not proved {name}: {statement}\n");
                out.push_str(&crate::report::text::reason_text(&reason, "  "));
                if let Some(c) = candidate {
                    out.push_str(&crate::report::text::candidate_text(&c, "  "));
                }
                out
            }
        }
    }

    /// What the command line's counterexample search needs, owned by a worker thread.
    fn search_kit(&self, timeout: Duration) -> SearchKit {
        let program = self.program.as_ref().map(|(_, c)| c);
        let ladder = self.reference.as_ref();
        SearchKit::new(&self.assumptions, program, ladder, self.notation, timeout)
    }
}
