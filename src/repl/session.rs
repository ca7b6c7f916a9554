//! The state of a REPL session and the commands that change it; every command returns its output text.

use std::collections::BTreeSet;
use std::sync::atomic::Ordering;
use std::sync::mpsc;
use std::time::{Duration, Instant};

use super::refute::{SearchKit, counterexample_lines};
use super::{CANCEL, COMMANDS};
use crate::diag::{Diagnostic, RenderStyle, Sources, Span, did_you_mean, render};
use crate::kernel::{Axiom, Proof, Rel, Rule, Source};
use crate::ladder::CompiledProgram;
use crate::prover::{self, Obligation};
use crate::report::{self, Attempt, Options, trace, waveform};
use crate::script::{self, Checker, Justified, ProvedClaim, StepError};
use crate::semantics::{Assignment, Signal, Time, eval, format_time};
use crate::syntax::Scope;
use crate::syntax::{
    self, CalcStep, Claim, ClaimKind, Document, Goal, NoProgram, Notation, Relation, RuleRef,
    ScriptProof, Statement, SyntaxError, document_to_string, step_to_string,
};
use crate::term::{Builder, Delay, Expr, Id, Language, Symbol, Term, root, same};
use crate::theory::{self, Theory};

/// A signal given to `simulate`: name, initial value, changes.
type GivenSignal = (String, bool, Vec<(Time, bool)>);

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

/// `1 hypothesis`, `2 hypotheses`.
fn counted(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

fn is_ident(s: &str) -> bool {
    let mut chars = s.chars();
    chars.next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// `target` as a path relative to the folder of `file` (both made absolute; `target`
/// unchanged when they share no root, as on two Windows drives).
fn relative_to_file(target: &str, file: &str) -> String {
    use std::path::{Component, Path, PathBuf};
    let absolute = |p: &Path| {
        p.canonicalize().or_else(|_| std::path::absolute(p)).unwrap_or_else(|_| p.to_path_buf())
    };
    let target_abs = absolute(Path::new(target));
    let folder = Path::new(file).parent().filter(|p| !p.as_os_str().is_empty());
    let base = absolute(folder.unwrap_or(Path::new(".")));
    let (t, b): (Vec<Component>, Vec<Component>) =
        (target_abs.components().collect(), base.components().collect());
    let common = t.iter().zip(&b).take_while(|(x, y)| x == y).count();
    if common == 0 {
        return target.to_string();
    }
    let mut relative = PathBuf::new();
    for _ in common..b.len() {
        relative.push("..");
    }
    for c in &t[common..] {
        relative.push(c);
    }
    relative.display().to_string().replace('\\', "/")
}

fn rel_of(r: Relation) -> Rel {
    match r {
        Relation::Equals => Rel::Eq,
        Relation::Implies => Rel::Implies,
    }
}

fn relation_of(r: Rel) -> Relation {
    match r {
        Rel::Eq => Relation::Equals,
        Rel::Implies => Relation::Implies,
    }
}

fn ms(d: Duration) -> String {
    format!("{:.1} ms", d.as_secs_f64() * 1e3)
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

    fn term(&self, e: &Expr) -> String {
        self.checker.term(e)
    }

    /// A canonical signal name as shown (the program's short name when unambiguous).
    fn display(&self, name: &str) -> String {
        match &self.program {
            Some((_, program)) => program.display_name(name),
            None => name.to_string(),
        }
    }

    fn step_line(&self, step: &CalcStep) -> String {
        let term = match &self.program {
            Some((_, program)) => program.rename_for_display(&step.term),
            None => step.term.clone(),
        };
        step_to_string(step.relation, &term, &step.rules, self.notation)
    }

    fn goal_text(&self, goal: &Goal) -> String {
        self.checker.goal_text(goal)
    }

    fn source(&mut self, text: &str) -> usize {
        self.counter += 1;
        self.sources.add(format!("<repl {}>", self.counter), text.to_string())
    }

    fn syntax_errors(&self, errors: Vec<SyntaxError>) -> String {
        errors
            .into_iter()
            .map(|e| render(&Diagnostic::from(e), &self.sources, RenderStyle::default()))
            .collect()
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

    fn help(&self, rest: &str) -> String {
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

    fn load(&mut self, rest: &str) -> String {
        let path = rest.trim().trim_matches('"');
        if path.is_empty() {
            return "error: expected `load FILE.ii`\n".into();
        }
        if report::is_ladder(path) {
            return self.load_program(path);
        }
        let file = match report::read_source(&mut self.sources, path) {
            Ok(f) => f,
            Err(d) => return render(&d, &self.sources, RenderStyle::default()),
        };
        let mut out = String::new();
        if let Some((program, _)) = script::program_header(&self.sources, file) {
            let program = script::program_path(path, &program).display().to_string();
            let already = self.program.as_ref().is_some_and(|(p, _)| *p == program);
            if !already {
                out.push_str(&self.load_program(&program));
                if self.program.as_ref().is_none_or(|(p, _)| *p != program) {
                    return out;
                }
            }
        }
        let doc = match syntax::parse_properties(&self.sources, file, self.scope()) {
            Ok(d) => d,
            Err(errors) => return format!("{out}{}", self.syntax_errors(errors)),
        };
        if let Err(e) = self.define_atoms() {
            return format!("{out}error: {e}\n");
        }
        for (name, _) in &doc.inputs {
            if !self.inputs.contains(name) {
                self.inputs.push(name.clone());
            }
        }
        let mut hyps = 0;
        for a in &doc.assumptions {
            if let Err(e) = self.fresh_name(&a.name) {
                out.push_str(&format!("error: {e}\n"));
                continue;
            }
            self.assumptions.push(a.clone());
            hyps += 1;
        }
        if let Err(e) = self.rebuild() {
            return format!("{out}error: the hypotheses are not accepted: {e}\n");
        }
        for p in &doc.properties {
            self.properties.retain(|q| q.name != p.name);
            self.properties.push(p.clone());
        }
        let mut checked = 0;
        for claim in &doc.claims {
            match self.checker.check_claim(claim) {
                Ok(c) => {
                    checked += 1;
                    out.push_str(&format!("ok {}  ({})\n", c.name, ms(c.time)));
                    self.done.push(claim.clone());
                }
                Err(e) => {
                    out.push_str(&render(
                        &Diagnostic::from(e),
                        &self.sources,
                        RenderStyle::default(),
                    ));
                }
            }
        }
        let props: Vec<&str> = doc.properties.iter().map(|p| p.name.as_str()).collect();
        out.push_str(&format!(
            "loaded {path}: {}, {}, {}{}, {} checked\n",
            counted(doc.inputs.len(), "input", "inputs"),
            counted(hyps, "hypothesis", "hypotheses"),
            counted(props.len(), "property", "properties"),
            if props.is_empty() { String::new() } else { format!(" ({})", props.join(", ")) },
            counted(checked, "claim", "claims"),
        ));
        out
    }

    /// The names in scope: the loaded program's signals (and the inputs).
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

    fn scope(&self) -> &dyn Scope {
        match &self.program {
            Some((_, compiled)) => compiled,
            None => &NoProgram,
        }
    }

    /// `load PROGRAM.ld`: its compiled rungs become hypotheses, its signals names.
    fn load_program(&mut self, path: &str) -> String {
        if self.program.is_some() {
            // Another program: the session starts over on it (the goals, proofs and
            // properties were about the first), unless it does not load.
            let mut fresh = match Session::new() {
                Ok(s) => s,
                Err(e) => return format!("error: {e}\n"),
            };
            fresh.notation = self.notation;
            let out = fresh.load_program(path);
            if fresh.program.is_none() {
                return out;
            }
            *self = fresh;
            return format!(
                "the session starts over on {path}: the previous program's goals, proofs and properties are put away\n{out}"
            );
        }
        let loaded = match report::load_program(&mut self.sources, path, &Default::default()) {
            Ok(l) => l,
            Err(diagnostics) => {
                return diagnostics
                    .iter()
                    .map(|d| render(d, &self.sources, RenderStyle::default()))
                    .collect();
            }
        };
        let compiled = loaded.compiled;
        for h in compiled.axioms() {
            if let Err(e) = self.fresh_name(&h.name) {
                return format!("error: {e}\n");
            }
        }
        let absolute = std::fs::canonicalize(path)
            .map_or_else(|_| path.to_string(), |p| p.display().to_string());
        let (count, signals) = (compiled.hypotheses.len(), compiled.signals.len());
        self.program_hypotheses = compiled.axioms();
        self.program = Some((absolute, compiled));
        self.reference = Some(loaded.reference);
        if let Err(e) = self.rebuild() {
            self.program = None;
            self.reference = None;
            self.program_hypotheses.clear();
            let _ = self.rebuild();
            return format!("error: the program's hypotheses are not accepted: {e}\n");
        }
        let mut out = String::new();
        for w in &loaded.warnings {
            out.push_str(&format!("warning: {w}\n"));
        }
        out.push_str(&format!(
            "loaded program {path}: {} (`axioms L` lists them), {}\n",
            counted(count, "hypothesis", "hypotheses"),
            counted(signals, "signal", "signals")
        ));
        out
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

    fn goal(&mut self, rest: &str) -> String {
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

    /// `prove NAME` where no property is called NAME: say so, with the loaded ones.
    fn no_such_property(&self, name: &str) -> String {
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

    /// What the command line's counterexample search needs, owned by a worker thread.
    fn search_kit(&self, timeout: Duration) -> SearchKit {
        let program = self.program.as_ref().map(|(_, c)| c);
        let ladder = self.reference.as_ref();
        SearchKit::new(&self.assumptions, program, ladder, self.notation, timeout)
    }

    fn calculation(&self, open: &Open) -> String {
        let mut out = format!("    {}\n", self.term(&open.lhs));
        for (step, _) in &open.steps {
            out.push_str(&self.step_line(step));
            out.push('\n');
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
    fn finish(&mut self) -> String {
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

    fn step_error(&self, e: StepError, rules: &[RuleRef]) -> String {
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

    fn step(&mut self, relation: Relation, rest: &str) -> String {
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
        let Some(result) = self.justify(&from, rel_of(relation), &term, &rules) else {
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

    fn auto(&mut self) -> String {
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

    fn apply(&mut self, rest: &str) -> String {
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

    fn undo(&mut self) -> String {
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

    fn trace(&self, rest: &str) -> String {
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

    fn show(&self, rest: &str) -> String {
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

    fn axioms(&self, prefix: &str) -> String {
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

    fn save(&mut self, rest: &str) -> String {
        let path = rest.trim().trim_matches('"');
        if path.is_empty() {
            return "error: expected `save FILE.ii`\n".into();
        }
        if self.done.is_empty() {
            return "error: no finished proofs to save\n".into();
        }
        let span = Span::new(0, 0..0);
        // The script names its program relative to itself, so the two can move together.
        let program = self.program.as_ref().map(|(p, _)| (relative_to_file(p, path), span));
        let doc = Document {
            file: 0,
            program,
            inputs: self.inputs.iter().map(|n| (n.clone(), span)).collect(),
            delays: Vec::new(),
            assumptions: self.assumptions.clone(),
            properties: Vec::new(),
            laws: Vec::new(),
            claims: self.done.clone(),
        };
        let text = format!(
            "// Saved by the ii-prove REPL; re-check with `ii-prove check {path}`.\n{}",
            document_to_string(&doc, Notation::Ascii)
        );
        match std::fs::write(path, text) {
            Ok(()) => format!("saved {} to {path}\n", counted(self.done.len(), "proof", "proofs")),
            Err(e) => format!("error: cannot write `{path}`: {e}\n"),
        }
    }

    fn check(&self, rest: &str) -> String {
        let paths: Vec<String> = rest.split_whitespace().map(str::to_string).collect();
        if paths.is_empty() {
            return "error: expected `check FILE.ii ...`\n".into();
        }
        let run = script::check_files(&paths, &Options::default());
        let mut out: String = run.errors.concat();
        out.push_str(&script::render_text(&run));
        out
    }

    fn simulate(&mut self, rest: &str) -> String {
        match self.simulate_inner(rest) {
            Ok(lines) => lines,
            Err(e) if e.starts_with("error") => e,
            Err(e) => format!("error: {e}\n"),
        }
    }

    fn duration(&mut self, text: &str) -> Result<Delay, String> {
        let (tokens, errors) = syntax::lexer::lex(text.trim(), 0);
        match (tokens.as_slice(), errors.is_empty()) {
            ([t, _eof], true) => match &t.tok {
                syntax::lexer::Tok::Duration(d) => Ok(d.clone()),
                _ => Err(format!("`{}` is not a duration such as `5s`", text.trim())),
            },
            _ => Err(format!("`{}` is not a duration such as `5s`", text.trim())),
        }
    }

    fn simulate_inner(&mut self, rest: &str) -> Result<String, String> {
        let (head, assigns) = match rest.split_once(" with ") {
            Some((h, a)) => (h, a),
            None => (rest, ""),
        };
        let (terms_text, horizon_text) = match head.split_once(" for ") {
            Some((t, h)) => (t, Some(h)),
            None => (head, None),
        };
        if terms_text.trim().is_empty() {
            return Err("expected `simulate TERM, ... [for DURATION] [with NAME=STEPS ...]`".into());
        }
        // The given signals: NAME=STEPS, separated by spaces or `;`.
        let mut given: Vec<GivenSignal> = Vec::new();
        for item in assigns.split([';', ' ']).map(str::trim).filter(|s| !s.is_empty()) {
            let Some((name, spec)) = item.split_once('=') else {
                return Err(format!("`{item}` should be NAME=STEPS, e.g. L_flow=1@1s,0@6s"));
            };
            let mut initial = false;
            let mut changes = Vec::new();
            for (i, part) in spec.split(',').map(str::trim).enumerate() {
                match part.split_once('@') {
                    Some((v, t)) => {
                        let value = match v.trim() {
                            "1" => true,
                            "0" => false,
                            other => return Err(format!("`{other}` is not 0 or 1")),
                        };
                        changes.push((self.duration(t)?.seconds().clone(), value));
                    }
                    None if i == 0 => {
                        initial = match part {
                            "1" => true,
                            "0" => false,
                            other => return Err(format!("`{other}` is not 0 or 1 (or v@time)")),
                        }
                    }
                    None => return Err(format!("`{part}` should be VALUE@TIME, e.g. 1@2s")),
                }
            }
            let name = name.trim();
            let canonical = match self.scope().lookup(name) {
                syntax::Lookup::Signal(c) => c,
                _ => name.to_string(),
            };
            given.push((canonical, initial, changes));
        }
        let last = given.iter().flat_map(|g| g.2.iter().map(|c| c.0.clone())).max();
        let horizon: Time = match horizon_text {
            Some(h) => self.duration(h)?.seconds().clone(),
            None => {
                let ten = Time::from_integer(10.into());
                match last {
                    Some(t) if t.clone() + Time::from_integer(5.into()) > ten => {
                        t + Time::from_integer(5.into())
                    }
                    _ => ten,
                }
            }
        };
        let mut env = Assignment::new(horizon.clone());
        for (name, initial, changes) in &given {
            let signal = Signal::from_steps(horizon.clone(), *initial, changes)
                .map_err(|e| format!("{name}: {e}"))?;
            env.signals.insert(Symbol::from(name.as_str()), signal);
        }
        if self.program.is_some() {
            return self.simulate_scans(terms_text, &given, &env);
        }
        // Parse the terms; expand defined signals through their equations.
        let mut rows: Vec<(String, Signal)> = given
            .iter()
            .filter_map(|(n, _, _)| {
                env.signals.get(&Symbol::from(n.as_str())).map(|s| (self.display(n), s.clone()))
            })
            .collect();
        let mut zeros: BTreeSet<String> = BTreeSet::new();
        let mut inputs = self.inputs.clone();
        inputs.extend(given.iter().map(|g| g.0.clone()));
        for text in terms_text.split(',').map(str::trim).filter(|t| !t.is_empty()) {
            let file = self.source(text);
            let term = syntax::parse_expression(&self.sources, file, self.scope(), &inputs)
                .map_err(|errors| self.syntax_errors(errors))?;
            let expanded = self.expand(&term, &env)?;
            for node in expanded.as_ref() {
                if let Term::Name(s) = node
                    && !env.signals.contains_key(s)
                {
                    zeros.insert(s.to_string());
                }
            }
            let mut local = env.clone();
            for z in &zeros {
                local
                    .signals
                    .insert(Symbol::from(z.as_str()), Signal::constant(horizon.clone(), false));
            }
            let signal =
                eval(&expanded, &local).map_err(|e| format!("cannot evaluate `{text}`: {e:?}"))?;
            let label = self.term(&term);
            if !rows.iter().any(|(l, _)| *l == label) {
                rows.push((label, signal));
            }
        }
        let mut out: String = waveform::draw(&rows, None, waveform::Glyphs::UNICODE)
            .into_iter()
            .map(|l| format!("{l}\n"))
            .collect();
        if !zeros.is_empty() {
            let list: Vec<String> = zeros.iter().map(|z| self.display(z)).collect();
            out.push_str(&format!("(0 throughout: {})\n", list.join(", ")));
        }
        out.push_str(&format!("horizon {}\n", format_time(&horizon)));
        Ok(out)
    }

    /// `simulate` for a loaded program: its equations run scan by scan (the given
    /// signals read at the start of each scan, every other input 0), the terms drawn.
    fn simulate_scans(
        &mut self,
        terms_text: &str,
        given: &[GivenSignal],
        env: &Assignment,
    ) -> Result<String, String> {
        use crate::counterexample::{ScanTrace, equations, scans_of, unroll};
        let mut inputs = self.inputs.clone();
        inputs.extend(given.iter().map(|g| g.0.clone()));
        let mut terms = Vec::new();
        for text in terms_text.split(',').map(str::trim).filter(|t| !t.is_empty()) {
            let file = self.source(text);
            let term = syntax::parse_expression(&self.sources, file, self.scope(), &inputs)
                .map_err(|errors| self.syntax_errors(errors))?;
            terms.push(term);
        }
        self.define_atoms()?;
        let Some((_, compiled)) = &self.program else {
            return Err("no program is loaded".into());
        };
        let cycle = Time::new(compiled.cycle_us.into(), 1_000_000u64.into());
        if compiled.cycle_us == 0 {
            return Err("the program has a zero cycle time: it has no scans to simulate".into());
        }
        let count = (&env.horizon / &cycle).ceil().to_integer();
        let scans: usize =
            count.clone().try_into().ok().filter(|n| *n <= 200_000).ok_or_else(|| {
                format!("{count} scans of the cycle is too long to simulate; give a shorter `for`")
            })?;
        let defs = equations(compiled).into_iter().map(|(n, e)| (n, e.clone())).collect();
        let model = unroll::Model { defs, constraints: Vec::new() };
        let trace = ScanTrace { cycle: cycle.clone(), scans, values: Default::default() };
        let mut zeros: BTreeSet<String> = BTreeSet::new();
        let mut free = |_: &mut unroll::Concrete, name: &str, k: usize| match env
            .signals
            .get(&Symbol::from(name))
        {
            Some(s) => s.value_at(&trace.instant(k)),
            None => {
                zeros.insert(name.to_string());
                false
            }
        };
        let steps_of = |d: &Delay| scans_of(d, &cycle);
        let extra: Vec<&Expr> = terms.iter().collect();
        let run =
            unroll::unroll(&mut unroll::Concrete, &model, &extra, scans, &steps_of, &mut free)?;
        let mut rows: Vec<(String, Signal)> = given
            .iter()
            .filter_map(|(n, _, _)| {
                env.signals.get(&Symbol::from(n.as_str())).map(|s| (self.display(n), s.clone()))
            })
            .collect();
        for (term, values) in terms.iter().zip(&run.extra) {
            let label = self.term(term);
            if !rows.iter().any(|(l, _)| *l == label) {
                rows.push((label, trace.signal(values)?));
            }
        }
        let mut out: String = waveform::draw(&rows, None, waveform::Glyphs::UNICODE)
            .into_iter()
            .map(|l| format!("{l}\n"))
            .collect();
        let zeros: Vec<String> = zeros.iter().map(|z| self.display(z)).collect();
        if !zeros.is_empty() {
            out.push_str(&format!("(0 throughout: {})\n", zeros.join(", ")));
        }
        out.push_str(&format!(
            "horizon {}, {scans} scans of {}\n",
            format_time(&env.horizon),
            format_time(&cycle)
        ));
        Ok(out)
    }

    /// Replaces signals that have an equation `NAME = ...` (and are not given) by its right side.
    fn expand(&self, term: &Expr, env: &Assignment) -> Result<Expr, String> {
        let definitions: Vec<(Symbol, Expr)> = self
            .checker
            .ctx
            .hypotheses()
            .iter()
            .filter(|h| h.rel == Rel::Eq)
            .filter_map(|h| match &h.lhs[root(&h.lhs)] {
                Term::Name(s) if !env.signals.contains_key(s) => Some((*s, h.rhs.clone())),
                _ => None,
            })
            .collect();
        let mut current = term.clone();
        for _ in 0..50 {
            let mut changed = false;
            let mut b = Builder::default();
            fn go(
                e: &Expr,
                id: Id,
                defs: &[(Symbol, Expr)],
                b: &mut Builder,
                changed: &mut bool,
            ) -> Id {
                if let Term::Name(s) = &e[id]
                    && let Some((_, rhs)) = defs.iter().find(|(n, _)| n == s)
                {
                    *changed = true;
                    return b.term(rhs);
                }
                let node = e[id].clone().map_children(|c| go(e, c, defs, b, changed));
                b.add(node)
            }
            go(&current, root(&current), &definitions, &mut b, &mut changed);
            current = b.finish();
            if !changed {
                return Ok(current);
            }
            if current.as_ref().len() > 10_000 {
                break;
            }
        }
        Err("the signals' equations are cyclic or too large to simulate; give the signals with `with`".into())
    }
}
