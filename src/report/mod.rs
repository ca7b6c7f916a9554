//! Runs the properties of a session and reports verdicts: text for people, JSON for tools.
//!
//! This is the layer the command line and the test harness share: it loads
//! files (reporting located diagnostics), builds the prover's context, proves
//! each property, looks for a witness when a proof fails, and renders the
//! result. Exit codes: 0 all proved, 1 some refuted or unknown, 2 bad input
//! (including input with no property to check). An [`Observer`] hears of each
//! result as soon as it is known, in file order.
//!
//! The report's data is `model.rs`; this file runs the session.

pub mod aiger;
mod any_state;
pub mod console;
pub mod equiv;
pub mod export;
pub mod formats;
pub mod html;
mod load;
mod model;
mod property;
pub mod stream;
pub mod text;
pub mod trace;
pub mod tracks;
mod unknown;
mod vacuity;
use vacuity::{contradictory, flag_vacuity, forced_by_assumptions, forced_constants, forced_text};
pub mod waveform;

pub use load::{
    Inputs, LoadedProgram, classify, elapsed_named, is_ladder, load_program, load_program_with,
    wanting_elapsed,
};
pub use model::{
    CounterexampleReport, EquationLine, IntegerReport, Location, PropertyReport, RunReport,
    SignalReport, Status, StepReport, Summary, TraceReport, Unchecked, WarningReport,
};
pub use property::{Attempt, attempt, check_property, refute};
pub use text::render_text;

use std::time::Duration;

use crate::counterexample;
use crate::diag::{Diagnostic, IoError, RenderStyle, Sources, render};
use crate::kernel::Axiom;
use crate::prover::{Context, Obligation};
use crate::semantics::format_time;
use crate::syntax::{self, Document, Goal, NoProgram, Notation, Scope};
use crate::term::Expr;
use crate::theory;

/// How a run reports.
#[derive(Clone, Debug)]
pub struct Options {
    /// Print each checked proof.
    pub trace: bool,
    /// Print every lemma of a proof in full (`--trace-all`), not the folded view.
    pub trace_all: bool,
    /// ASCII notation and diagrams.
    pub ascii: bool,
    /// Time limit per property.
    pub timeout: Duration,
    /// Check only the properties whose name contains one of these, or matches one of
    /// these glob patterns (`P1*`); all when empty.
    pub only: Vec<String>,
    /// A vacuous proof fails the run (exit 1).
    pub deny_vacuous: bool,
    /// How a program's timers are compiled.
    pub timers: crate::ladder::TimerModel,
    /// Properties checked at once (threads); results are reported in file order.
    pub jobs: usize,
    /// For a PLCopen program: which POU (`--pou`) and which cycle (`--cycle`).
    pub plcopen: crate::ladder::plcopen::Selection,
    /// Render each proof's printed lines and atomic steps into the report (the JSON
    /// output and `--trace` show them; without, a trace keeps its method and length).
    pub proof_text: bool,
    /// Put every signal of a program counterexample's run, with its exact pieces, into
    /// the report (the JSON output shows them; the text, the diagram files and the
    /// HTML page need only the signals the diagram shows, which a deep cone makes far
    /// fewer).
    pub run_signals: bool,
    /// Put the program's compiled equations, printed, into the report (the HTML page's
    /// appendix shows them; a plant of 10,000 units has 110,000).
    pub equations: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            trace: false,
            trace_all: false,
            ascii: false,
            timeout: Duration::from_secs(10),
            only: Vec::new(),
            deny_vacuous: false,
            timers: crate::ladder::TimerModel::default(),
            jobs: 1,
            plcopen: Default::default(),
            proof_text: true,
            run_signals: true,
            equations: true,
        }
    }
}

impl Options {
    fn notation(&self) -> Notation {
        if self.ascii { Notation::Ascii } else { Notation::Paper }
    }

    /// The glyphs of the text timing diagrams.
    fn glyphs(&self) -> waveform::Glyphs {
        if self.ascii { waveform::Glyphs::ASCII } else { waveform::Glyphs::UNICODE }
    }
}

/// A run that could not start: located diagnostics, already rendered.
#[derive(Clone, Debug)]
pub struct InputError {
    /// The rendered diagnostics.
    pub rendered: String,
}

/// Reads a file into `sources` (Latin-1 fallback for non-UTF-8 bytes). A binary file
/// (a NUL byte, or control characters no text file has) is refused at once.
pub fn read_source(sources: &mut Sources, path: &str) -> Result<usize, Diagnostic> {
    let io_error = |reason: String| Diagnostic::from(IoError { path: path.to_string(), reason });
    let bytes = std::fs::read(path).map_err(|e| io_error(e.to_string()))?;
    if let Some(why) = binary(&bytes) {
        return Err(io_error(format!(
            "it is a binary file ({why}), not a text file (a program: LDmicro .ld, PLCopen .xml, Structured Text .st, Instruction List .il; properties: .ii)"
        )));
    }
    let text = match String::from_utf8(bytes) {
        Ok(text) => text,
        Err(e) => crate::ladder::decode_latin1(e.as_bytes()),
    };
    Ok(sources.add(path, text))
}

/// Why `bytes` are not text: a NUL byte, or a control character other than tab, line
/// feed, form feed, carriage return and the DOS end-of-file mark.
pub fn binary(bytes: &[u8]) -> Option<String> {
    let at = bytes
        .iter()
        .position(|&b| b < 0x20 && !matches!(b, b'\t' | b'\n' | 0x0c | b'\r' | 0x1a))?;
    Some(match bytes[at] {
        0 => format!("a NUL byte at offset {at}"),
        b => format!("control character 0x{b:02x} at offset {at}"),
    })
}

/// At most this many diagnostics are printed for one run; the rest are counted.
pub const MAX_ERRORS: usize = 20;

fn fail(sources: &Sources, diagnostics: Vec<Diagnostic>, opts: &Options) -> InputError {
    let style = RenderStyle { ascii: opts.ascii };
    let mut rendered: String =
        diagnostics.iter().take(MAX_ERRORS).map(|d| render(d, sources, style)).collect();
    if diagnostics.len() > MAX_ERRORS {
        let more = diagnostics.len() - MAX_ERRORS;
        let dots = if opts.ascii { "..." } else { "…" };
        rendered.push_str(&format!(
            "{dots} and {more} more error{}\n",
            if more == 1 { "" } else { "s" }
        ));
    }
    InputError { rendered }
}

/// What a run tells as it goes: the command line prints each result as soon as it is
/// known (in file order), draws a progress line, and can print a partial summary when
/// interrupted. Every method does nothing by default.
pub trait Observer {
    /// Every file is read: these properties (name, location) of these files (the
    /// report's `files`) will be checked, in order.
    fn begin(&mut self, _plan: &[(String, Location)], _files: &[String]) {}
    /// Must the run's report hold every result in full? When not (the observer has
    /// shown or written each one already), it keeps only what the summary and the exit
    /// status need, so that a run of many properties does not hold every proof.
    fn wants_results(&self) -> bool {
        true
    }
    /// A warning about the input.
    fn warning(&mut self, _warning: &WarningReport) {}
    /// The property at `index` of the plan is being checked.
    fn started(&mut self, _index: usize) {}
    /// A property's result.
    fn finished(&mut self, _report: &PropertyReport) {}
    /// `equiv`: a state correspondence proved before the outputs.
    fn correspondence(&mut self, _report: &PropertyReport) {}
}

/// Hears nothing.
impl Observer for () {}

/// Checks the properties of `doc` that `selection` selects, on `jobs` threads, telling
/// `observer` and appending to `properties` in file order.
fn check_selected(
    doc: &Document,
    selection: &Selection,
    jobs: usize,
    program: Option<&counterexample::Program>,
    check: impl Fn(&crate::syntax::Statement<Goal>) -> PropertyReport + Sync,
    observer: &mut dyn Observer,
    properties: &mut Vec<PropertyReport>,
) {
    let selected: Vec<&crate::syntax::Statement<Goal>> =
        doc.properties.iter().filter(|s| selection.selects(&s.name)).collect();
    // About a program, the deepest properties first: their counterexamples, shared,
    // refute shallower properties without a search of their own.
    let order = match program.and_then(|p| p.shared.map(|shared| (p.compiled, shared))) {
        Some((compiled, shared)) => {
            let sides: Vec<[&Expr; 2]> =
                selected.iter().map(|s| [&s.value.lhs, &s.value.rhs]).collect();
            shared.deepest_first(compiled, &sides)
        }
        None => (0..selected.len()).collect(),
    };
    in_order_by(
        &selected,
        &order,
        jobs,
        |s| check(s),
        |event| match event {
            InOrder::Next => observer.started(properties.len()),
            InOrder::Done(report) => {
                observer.finished(&report);
                properties.push(kept(observer, report));
            }
        },
    );
}

/// What the run keeps of a result the observer has had: all of it, or its outline.
fn kept(observer: &dyn Observer, report: PropertyReport) -> PropertyReport {
    if observer.wants_results() { report } else { report.outline() }
}

/// What [`in_order`] tells its caller.
enum InOrder<R> {
    /// The next item in order is the one being waited for.
    Next,
    /// The next item's result.
    Done(R),
}

/// Runs `work` on every item on up to `jobs` threads and hands each result to `emit`
/// in the order of `items`, as soon as it and every earlier one are known (each
/// preceded by `Next` when it becomes the one waited for). Each item's work is
/// independent of the others.
fn in_order<T: Sync, R: Send>(
    items: &[T],
    jobs: usize,
    work: impl Fn(&T) -> R + Sync,
    emit: impl FnMut(InOrder<R>),
) {
    let order: Vec<usize> = (0..items.len()).collect();
    in_order_by(items, &order, jobs, work, emit);
}

/// [`in_order`], with the work started in the order of `order` (a permutation of the
/// items' positions); the results are still handed to `emit` in the order of `items`.
fn in_order_by<T: Sync, R: Send>(
    items: &[T],
    order: &[usize],
    jobs: usize,
    work: impl Fn(&T) -> R + Sync,
    mut emit: impl FnMut(InOrder<R>),
) {
    let jobs = jobs.clamp(1, items.len().max(1));
    let mut waiting = std::collections::BTreeMap::new();
    let mut due = 0;
    let mut deliver = |i: usize, result: R, emit: &mut dyn FnMut(InOrder<R>)| {
        waiting.insert(i, result);
        while let Some(result) = waiting.remove(&due) {
            emit(InOrder::Done(result));
            due += 1;
            if due < items.len() {
                emit(InOrder::Next);
            }
        }
    };
    if !items.is_empty() {
        emit(InOrder::Next);
    }
    if jobs == 1 {
        for &i in order {
            deliver(i, work(&items[i]), &mut emit);
        }
        return;
    }
    let next = std::sync::atomic::AtomicUsize::new(0);
    let (send, receive) = std::sync::mpsc::channel::<(usize, R)>();
    std::thread::scope(|scope| {
        for _ in 0..jobs {
            let send = send.clone();
            let (next, work) = (&next, &work);
            scope.spawn(move || {
                loop {
                    let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    let Some(&i) = order.get(k) else { break };
                    if send.send((i, work(&items[i]))).is_err() {
                        break;
                    }
                }
            });
        }
        drop(send);
        for (i, result) in receive {
            deliver(i, result, &mut emit);
        }
    });
}

/// The properties `--only` selects (all when it names none).
struct Selection(Vec<Pattern>);

enum Pattern {
    Substring(String),
    Glob(globset::GlobMatcher),
}

impl Selection {
    fn new(only: &[String]) -> Result<Selection, InputError> {
        let mut patterns = Vec::new();
        for p in only {
            if p.contains(['*', '?', '[', '{']) {
                let glob = globset::Glob::new(p).map_err(|e| InputError {
                    rendered: format!("error: `--only {p}` is not a valid pattern: {e}\n"),
                })?;
                patterns.push(Pattern::Glob(glob.compile_matcher()));
            } else {
                patterns.push(Pattern::Substring(p.clone()));
            }
        }
        Ok(Selection(patterns))
    }

    fn selects(&self, name: &str) -> bool {
        self.0.is_empty()
            || self.0.iter().any(|p| match p {
                Pattern::Substring(s) => name.contains(s.as_str()),
                Pattern::Glob(g) => g.is_match(name),
            })
    }
}

/// The selected properties of `docs` with their locations; an error when there are none
/// (a run that checks nothing must not pass).
fn plan(
    sources: &Sources,
    docs: &[Document],
    paths: &[String],
    opts: &Options,
) -> Result<(Selection, Vec<(String, Location)>), InputError> {
    let selection = Selection::new(&opts.only)?;
    let plan: Vec<(String, Location)> = docs
        .iter()
        .flat_map(|d| &d.properties)
        .filter(|s| selection.selects(&s.name))
        .map(|s| (s.name.clone(), Location::of(sources, s.span)))
        .collect();
    if !plan.is_empty() {
        return Ok((selection, plan));
    }
    let files = if paths.is_empty() {
        "no property file (.ii) was given: `ii-prove PROGRAM.ld PROPS.ii`".to_string()
    } else {
        let names: Vec<String> = paths.iter().map(|p| format!("`{p}`")).collect();
        format!(
            "{} {} no `property` statement",
            names.join(", "),
            if paths.len() == 1 { "has" } else { "have" }
        )
    };
    let rendered = if opts.only.is_empty() || docs.iter().all(|d| d.properties.is_empty()) {
        format!("error: no property to check: {files}\n")
    } else {
        let all: Vec<&str> =
            docs.iter().flat_map(|d| &d.properties).map(|s| s.name.as_str()).collect();
        format!(
            "error: no property matches `--only {}`; the properties are: {}\n",
            opts.only.join(" --only "),
            all.join(", ")
        )
    };
    Err(InputError { rendered })
}

/// A statement's goal as a kernel obligation.
pub fn obligation(goal: &Goal) -> Obligation {
    let (lhs, rel, rhs) = theory::goal_parts(goal);
    Obligation { lhs, rel, rhs }
}

/// The hypotheses of `assume` statements.
pub fn assumptions(doc: &Document) -> Vec<Axiom> {
    doc.assumptions
        .iter()
        .map(|s| {
            let (lhs, rel, rhs) = theory::goal_parts(&s.value);
            Axiom::ground(s.name.clone(), lhs, rel, rhs)
        })
        .collect()
}

/// Reads and resolves property files against `scope`; all their diagnostics, or the documents.
fn read_documents(
    sources: &mut Sources,
    paths: &[String],
    scope: &dyn Scope,
    opts: &Options,
) -> Result<Vec<Document>, InputError> {
    let mut docs = Vec::new();
    let mut diagnostics = Vec::new();
    for path in paths {
        match read_source(sources, path) {
            Ok(file) => match syntax::parse_properties(sources, file, scope) {
                Ok(doc) => docs.push(doc),
                Err(errors) => diagnostics.extend(errors.into_iter().map(Diagnostic::from)),
            },
            Err(d) => diagnostics.push(d),
        }
    }
    if diagnostics.is_empty() { Ok(docs) } else { Err(fail(sources, diagnostics, opts)) }
}

/// The session for properties about free signals (`ii-prove FILE.ii …`).
pub fn run_free(paths: &[String], opts: &Options) -> Result<RunReport, InputError> {
    run_free_with(paths, opts, &mut ())
}

/// [`run_free`], telling `observer` of each result as it is known.
pub fn run_free_with(
    paths: &[String],
    opts: &Options,
    observer: &mut dyn Observer,
) -> Result<RunReport, InputError> {
    let mut sources = Sources::new();
    let theory = theory::standard(&mut sources).map_err(|d| fail(&sources, d, opts))?;
    let docs = read_documents(&mut sources, paths, &NoProgram, opts)?;
    let (selection, plan) = plan(&sources, &docs, paths, opts)?;
    observer.begin(&plan, paths);
    let identity = |e: &Expr| e.clone();
    let mut warnings = Vec::new();
    let mut properties = Vec::new();
    // Each file is its own theory: its assumptions are the hypotheses of its properties.
    for (doc, path) in docs.iter().zip(paths) {
        if !doc.properties.iter().any(|s| selection.selects(&s.name)) {
            continue;
        }
        let hypotheses = assumptions(doc);
        let ctx = Context::new(theory.axioms(), hypotheses.clone())
            .map_err(|e| InputError { rendered: format!("error: {path}: {e}\n") })?;
        // Consistency: assumptions that prove `0* = 1*` make every property vacuous.
        let assumed: Vec<&str> = hypotheses.iter().map(|h| h.name.as_str()).collect();
        let inconsistent = contradictory(&ctx, &hypotheses, opts).then(|| {
            format!(
                "{path}: the assumptions ({}) contradict each other: they prove 0* = 1*; every property holds vacuously",
                assumed.join(", ")
            )
        });
        if let Some(text) = &inconsistent {
            let message = text.strip_prefix(&format!("{path}: ")).unwrap_or(text).to_string();
            let location = doc.assumptions.first().map(|a| Location::of(&sources, a.span));
            let warning = WarningReport { message, location };
            observer.warning(&warning);
            warnings.push(warning);
        }
        let check = |statement: &crate::syntax::Statement<Goal>| {
            let mut report = check_property(&ctx, statement, &hypotheses, opts, &identity, None);
            report.location = Some(Location::of(&sources, statement.span));
            flag_vacuity(&mut report, inconsistent.as_deref(), || {
                if hypotheses.is_empty() {
                    return None;
                }
                let goal = obligation(&statement.value);
                let style = trace::Style { notation: opts.notation(), rename: &identity };
                let forced = forced_by_assumptions(&ctx, &goal, opts);
                (!forced.is_empty()).then(|| forced_text(&style, &forced, None))
            });
            report
        };
        check_selected(doc, &selection, opts.jobs, None, check, observer, &mut properties);
    }
    Ok(finish(None, paths.to_vec(), warnings, properties))
}

/// The rung compiler's options a run asks for.
pub fn compile_options(opts: &Options) -> crate::ladder::CompileOptions {
    crate::ladder::CompileOptions { timers: opts.timers, any_state: false }
}

/// The session for `ii-prove PROGRAM.ld PROPS.ii…`: the properties are goals about the
/// compiled program, whose equations and recurrences are the hypotheses.
pub fn run_program(
    program: &str,
    paths: &[String],
    opts: &Options,
) -> Result<RunReport, InputError> {
    run_program_with(program, paths, opts, &mut ())
}

/// [`run_program`], telling `observer` of each result as it is known.
pub fn run_program_with(
    program: &str,
    paths: &[String],
    opts: &Options,
    observer: &mut dyn Observer,
) -> Result<RunReport, InputError> {
    let mut sources = Sources::new();
    let theory = theory::standard(&mut sources).map_err(|d| fail(&sources, d, opts))?;
    // A timer's elapsed time the properties name is computed as if the program read it.
    let selection = wanting_elapsed(&opts.plcopen, paths);
    let loaded = load_program_with(&mut sources, program, &compile_options(opts), &selection)
        .map_err(|d| fail(&sources, d, opts))?;
    let (docs, paths) = program_documents(&mut sources, program, &loaded, paths, opts)?;
    // The comparison atoms the properties use, each defined by its equation.
    let with_atoms = loaded.compiled.with_atoms();
    let compiled = &with_atoms;
    let (selection, plan) = plan(&sources, &docs, &paths, opts)?;
    observer.begin(&plan, &paths);
    let rename = |e: &Expr| compiled.rename_for_display(e);
    let mut warnings = loaded.located.clone();
    for w in &warnings {
        observer.warning(w);
    }
    let mut properties = Vec::new();
    // Each file's assumptions join the program's equations for that file's properties.
    for (doc, path) in docs.iter().zip(&paths) {
        if !doc.properties.iter().any(|s| selection.selects(&s.name)) {
            continue;
        }
        let assumed = assumptions(doc);
        let mut hypotheses = compiled.axioms();
        hypotheses.extend(assumed.iter().cloned());
        let mut ctx = Context::with_scans(theory.axioms(), hypotheses, Some(compiled.scan_cycle()))
            .map_err(|e| InputError { rendered: format!("error: {path}: {e}\n") })?;
        ctx.hints = compiled.bound_hints();
        // The file's properties share their confirmed counterexamples.
        let shared = counterexample::shared::Shared::default();
        let session = counterexample::Program {
            reference: loaded.reference.as_ref(),
            compiled,
            assumptions: &assumed,
            shared: Some(&shared),
        };
        // Consistency: an `assume` that no run of the program satisfies makes every
        // property hold vacuously.
        let mut inconsistent = None;
        if !assumed.is_empty() {
            let sides: Vec<&Expr> = assumed.iter().flat_map(|a| [&a.lhs, &a.rhs]).collect();
            let v = counterexample::vacuity(&session, &sides);
            if v.inconsistent {
                let names: Vec<&str> = assumed.iter().map(|a| a.name.as_str()).collect();
                let text = format!(
                    "{path}: the assumptions ({}) contradict the program: no scan-by-scan run satisfies them{}; every property holds vacuously",
                    names.join(", "),
                    v.horizon
                        .map(|h| format!(" (checked up to t = {} s)", format_time(&h)))
                        .unwrap_or_default()
                );
                let message = text.strip_prefix(&format!("{path}: ")).unwrap_or(&text).to_string();
                let location = doc.assumptions.first().map(|a| Location::of(&sources, a.span));
                let warning = WarningReport { message, location };
                observer.warning(&warning);
                warnings.push(warning);
                inconsistent = Some(text);
            }
        }
        // The file's properties share the per-signal answers of the vacuity check.
        let forced = counterexample::VacuityCache::default();
        let check = |statement: &crate::syntax::Statement<Goal>| {
            let mut report =
                check_property(&ctx, statement, ctx.hypotheses(), opts, &rename, Some(&session));
            report.location = Some(Location::of(&sources, statement.span));
            flag_vacuity(&mut report, inconsistent.as_deref(), || {
                let goal = obligation(&statement.value);
                forced_constants(&session, &forced, &goal, &rename, opts)
            });
            report
        };
        check_selected(
            doc,
            &selection,
            opts.jobs,
            Some(&session),
            check,
            observer,
            &mut properties,
        );
    }
    let mut report = finish(Some(program.to_string()), paths, warnings, properties);
    report.timers = Some(opts.timers.as_str());
    // After the properties are read: names print as they spell them.
    let shown = if opts.equations { &loaded.compiled.hypotheses[..] } else { &[] };
    report.equations = shown
        .iter()
        .map(|h| {
            let goal = h.goal();
            let shown = Goal { lhs: rename(&goal.lhs), rhs: rename(&goal.rhs), ..goal };
            EquationLine {
                name: h.name.clone(),
                text: syntax::goal_to_string(&shown, opts.notation()),
                location: Location::of(&sources, h.span),
            }
        })
        .collect();
    Ok(report)
}

/// The property files read against the compiled program, with the program's own
/// properties first as a document of the program's file; and the paths, in that order.
fn program_documents(
    sources: &mut Sources,
    program: &str,
    loaded: &LoadedProgram,
    paths: &[String],
    opts: &Options,
) -> Result<(Vec<Document>, Vec<String>), InputError> {
    let mut docs = read_documents(sources, paths, &loaded.compiled, opts)?;
    let mut paths = paths.to_vec();
    if let Some(first) = loaded.properties.first() {
        docs.insert(
            0,
            Document {
                file: first.span.file,
                program: None,
                inputs: Vec::new(),
                delays: Vec::new(),
                assumptions: Vec::new(),
                properties: loaded.properties.clone(),
                laws: Vec::new(),
                claims: Vec::new(),
            },
        );
        paths.insert(0, program.to_string());
    }
    Ok((docs, paths))
}

/// `ii-prove show PROGRAM`: the compiled equations and recurrences as `.ii` text.
pub fn show_program(program: &str, opts: &Options) -> Result<String, InputError> {
    let mut sources = Sources::new();
    let loaded = load_program_with(&mut sources, program, &compile_options(opts), &opts.plcopen)
        .map_err(|d| fail(&sources, d, opts))?;
    let notes: String = loaded.notes.iter().map(|n| format!("// warning: {n}\n")).collect();
    Ok(notes + &crate::ladder::program_to_ii(&loaded.compiled, opts.notation()))
}

fn finish(
    program: Option<String>,
    files: Vec<String>,
    warnings: Vec<WarningReport>,
    properties: Vec<PropertyReport>,
) -> RunReport {
    let summary = Summary::of(&properties);
    RunReport {
        program,
        files,
        timers: None,
        warnings,
        properties,
        correspondences: Vec::new(),
        summary,
        interrupted: false,
        unchecked: Vec::new(),
        equations: Vec::new(),
    }
}

/// The JSON report (schema: [`RunReport`]).
pub fn render_json(report: &RunReport) -> String {
    serde_json::to_string_pretty(report).unwrap_or_else(|e| format!("{{\"error\": \"{e}\"}}"))
}

/// The laws of the standard theory, one per line with name and file, for `ii-prove axioms`.
pub fn list_axioms(opts: &Options) -> Result<String, InputError> {
    let mut sources = Sources::new();
    let theory = theory::standard(&mut sources).map_err(|d| fail(&sources, d, opts))?;
    let width = theory.laws.iter().map(|l| l.axiom.name.len()).max().unwrap_or(0);
    let mut out = String::new();
    for law in &theory.laws {
        let text = syntax::law_to_string(&law.statement, opts.notation());
        let text = text.trim_start_matches("law ").to_string();
        let text = text.split_once(": ").map(|(_, t)| t.to_string()).unwrap_or(text);
        out.push_str(&format!("{:<width$}  {}:{}  {}\n", law.axiom.name, law.file, law.line, text));
    }
    out.push_str(&format!("{} laws\n", theory.laws.len()));
    Ok(out)
}
