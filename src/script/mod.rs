//! Proof scripts (`ii-prove check FILE...`): theorems and lemmas with proofs the kernel re-checks.
//!
//! A script is a `.ii` file with `theorem`/`lemma` statements (see the grammar
//! in [`crate::syntax`]). Each claim is checked in file order by a
//! [`Checker`]: every step of a calculation is justified with the rules it
//! cites and nothing else, and the whole claim's certificate goes to the
//! kernel. A checked claim may be cited by later steps. A step that does not
//! follow is a located [`ScriptError`]; the run then exits with status 2.

pub mod check;
pub mod error;

use std::path::{Path, PathBuf};
use std::time::Instant;

pub use check::{Checked, Checker, Justified, ProvedClaim, Site, StepError};
pub use error::{FailedStep, ScriptError};

use crate::diag::{Diagnostic, FileId, RenderStyle, Sources, Span, render};
use crate::ladder::CompiledProgram;
use crate::report::{self, Options};
use crate::syntax::lexer::{self, Keyword, Tok};
use crate::syntax::{self, ClaimKind, Document, NoProgram, Notation};
use crate::theory::{self, Theory};

/// The result of checking one claim.
#[derive(Clone, Debug, serde::Serialize)]
pub struct ClaimReport {
    /// The file it is in.
    pub file: String,
    /// Its name.
    pub name: String,
    /// `theorem` or `lemma`.
    pub kind: String,
    /// Did the kernel accept it?
    pub ok: bool,
    /// Time spent, in milliseconds.
    pub time_ms: f64,
}

/// The result of `ii-prove check`.
#[derive(Clone, Debug, Default)]
pub struct ScriptRun {
    /// Per claim, in file order.
    pub claims: Vec<ClaimReport>,
    /// Rendered located errors (malformed files, failed steps).
    pub errors: Vec<String>,
}

impl ScriptRun {
    /// 0 when every claim of every file checked; 2 on any malformed file or failed step.
    pub fn exit_code(&self) -> i32 {
        if self.errors.is_empty() && self.claims.iter().all(|c| c.ok) { 0 } else { 2 }
    }
}

/// The checker for a script document: the standard laws, the program's equations and
/// bounds (for a script about a `program`'s scans, with its cycle, and its integer bounds as
/// candidates for the invariant search) and the document's `assume`s.
pub fn checker_for(
    theory: &Theory,
    doc: &Document,
    program: Option<&CompiledProgram>,
) -> Result<Checker, ScriptError> {
    let mut hypotheses = program.map(CompiledProgram::axioms).unwrap_or_default();
    hypotheses.extend(report::assumptions(doc));
    let cycle = program.map(CompiledProgram::scan_cycle);
    let mut checker = Checker::with_scans(theory.axioms(), hypotheses, cycle).map_err(|e| {
        ScriptError::BadContext {
            span: doc.assumptions.first().map_or(Span::new(doc.file, 0..0), |s| s.span),
            reason: format!("the hypotheses cannot be loaded: {e}"),
        }
    })?;
    checker.ctx.hints = program.map(CompiledProgram::bound_hints).unwrap_or_default();
    Ok(checker)
}

/// Checks every claim of one parsed script; returns the reports and the errors.
/// `program` is the compiled program of a `program` header: its equations and recurrences are
/// hypotheses and its short names are shown in messages.
pub fn check_document(
    theory: &Theory,
    doc: &Document,
    program: Option<&CompiledProgram>,
    file_name: &str,
    notation: Notation,
) -> (Vec<ClaimReport>, Vec<ScriptError>) {
    let mut reports = Vec::new();
    let mut errors = Vec::new();
    let mut checker = match checker_for(theory, doc, program) {
        Ok(c) => c,
        Err(e) => return (reports, vec![e]),
    };
    checker.notation = notation;
    checker.display = program.cloned();
    for statement in &doc.claims {
        let started = Instant::now();
        let result = checker.check_claim(statement);
        reports.push(ClaimReport {
            file: file_name.to_string(),
            name: statement.name.clone(),
            kind: match statement.value.kind {
                ClaimKind::Theorem => "theorem".into(),
                ClaimKind::Lemma => "lemma".into(),
            },
            ok: result.is_ok(),
            time_ms: started.elapsed().as_secs_f64() * 1e3,
        });
        if let Err(e) = result {
            errors.push(e);
        }
    }
    (reports, errors)
}

/// The `program "PATH"` header of a script, found before names are resolved.
pub fn program_header(sources: &Sources, file: FileId) -> Option<(String, Span)> {
    let (tokens, _) = lexer::lex(sources.text(file), file);
    tokens.windows(2).find_map(|pair| match (&pair[0].tok, &pair[1].tok) {
        (Tok::Keyword(Keyword::Program), Tok::Str(path)) => Some((path.clone(), pair[1].span)),
        _ => None,
    })
}

/// Where a script's `program` path points: relative paths are relative to the script.
pub fn program_path(script: &str, program: &str) -> PathBuf {
    let program = Path::new(program);
    if program.is_absolute() {
        return program.to_path_buf();
    }
    match Path::new(script).parent() {
        Some(dir) => dir.join(program),
        None => program.to_path_buf(),
    }
}

/// Parses a script; with a `program` header the program is loaded and compiled first and
/// its signals are the names in scope. Returns the document and the program's hypotheses.
pub fn load_script(
    sources: &mut Sources,
    file: FileId,
    options: &crate::ladder::CompileOptions,
) -> Result<(Document, Option<CompiledProgram>), Vec<Diagnostic>> {
    let Some((program, span)) = program_header(sources, file) else {
        let doc = syntax::parse_properties(sources, file, &NoProgram)
            .map_err(|errors| errors.into_iter().map(Diagnostic::from).collect::<Vec<_>>())?;
        return Ok((doc, None));
    };
    let path = program_path(sources.name(file), &program);
    let shown = path.display().to_string();
    // The elapsed times the script names are computed (`[T1.ET < T#2s]`).
    let selection = crate::ladder::plcopen::Selection {
        elapsed: report::elapsed_named(sources.text(file)),
        ..Default::default()
    };
    let loaded = report::load_program_with(sources, &shown, options, &selection);
    let loaded = loaded.map_err(|mut diagnostics| {
        diagnostics.push(Diagnostic::from(ScriptError::BadContext {
            span,
            reason: format!("the program `{shown}` named here cannot be loaded"),
        }));
        diagnostics
    })?;
    let compiled = loaded.compiled;
    let doc = syntax::parse_properties(sources, file, &compiled)
        .map_err(|errors| errors.into_iter().map(Diagnostic::from).collect::<Vec<_>>())?;
    // The comparison atoms the script uses, each defined by its equation.
    Ok((doc, Some(compiled.with_atoms())))
}

/// `ii-prove check FILE...`: checks every claim of every file.
pub fn check_files(paths: &[String], opts: &Options) -> ScriptRun {
    let mut run = ScriptRun::default();
    let mut sources = Sources::new();
    let style = RenderStyle { ascii: opts.ascii };
    let notation = if opts.ascii { Notation::Ascii } else { Notation::Paper };
    let theory = match theory::standard(&mut sources) {
        Ok(t) => t,
        Err(diagnostics) => {
            run.errors.extend(diagnostics.iter().map(|d| render(d, &sources, style)));
            return run;
        }
    };
    for path in paths {
        let file = match report::read_source(&mut sources, path) {
            Ok(file) => file,
            Err(d) => {
                run.errors.push(render(&d, &sources, style));
                continue;
            }
        };
        let (doc, program) = match load_script(&mut sources, file, &report::compile_options(opts)) {
            Ok(loaded) => loaded,
            Err(diagnostics) => {
                run.errors.extend(diagnostics.iter().map(|d| render(d, &sources, style)));
                continue;
            }
        };
        let (reports, errors) = check_document(&theory, &doc, program.as_ref(), path, notation);
        run.claims.extend(reports);
        for e in errors {
            run.errors.push(render(&Diagnostic::from(e), &sources, style));
        }
    }
    run
}

/// The text report: `ok NAME  TIME` (or `FAILED NAME`) per claim, then a summary line.
pub fn render_text(run: &ScriptRun) -> String {
    let width = run.claims.iter().map(|c| c.name.chars().count()).max().unwrap_or(0);
    let mut out = String::new();
    let mut file = None;
    for c in &run.claims {
        if file != Some(&c.file) {
            out.push_str(&format!("{}\n", c.file));
            file = Some(&c.file);
        }
        let status = if c.ok { "ok    " } else { "FAILED" };
        out.push_str(&format!("  {status} {:<width$}  {:>9.1} ms\n", c.name, c.time_ms));
    }
    let ok = run.claims.iter().filter(|c| c.ok).count();
    let failed = run.claims.len() - ok;
    let other = run.errors.len().saturating_sub(failed);
    if other > 0 {
        out.push_str(&format!("{ok} checked, {failed} failed, {other} other error(s)\n"));
    } else {
        out.push_str(&format!("{ok} checked, {failed} failed\n"));
    }
    out
}
