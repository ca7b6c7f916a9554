//! Loading the command line's program: telling the program from the property files by content, and reading, lowering and compiling it (LDmicro, PLCopen, Structured Text) with its warnings and the properties it states itself.

use super::*;

/// A ladder program and property files, told apart by content.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Inputs {
    /// The LDmicro program, if one is given.
    pub program: Option<String>,
    /// The property files, in command-line order.
    pub properties: Vec<String>,
}

/// Sorts the command line's files into a ladder program and property files, wherever
/// the program stands: a file is a program when its text starts with an LDmicro
/// header (`LDmicro0.1`, `LDmicro0.2`), or it is a PLCopen XML project (root
/// `project` in a TC6 namespace), or, failing that, its name ends in `.ld`. Two
/// programs are refused.
pub fn classify(files: &[String]) -> Result<Inputs, InputError> {
    let mut inputs = Inputs::default();
    for path in files {
        // A file that cannot be read as text stops the run before anything is parsed:
        // a program mistaken for properties would bury the error under unknown names.
        let mut sources = Sources::new();
        if let Err(e) = read_source(&mut sources, path) {
            return Err(fail(&sources, vec![e], &Options::default()));
        }
        if !is_ladder(path) {
            inputs.properties.push(path.clone());
            continue;
        }
        if let Some(first) = &inputs.program {
            return Err(InputError {
                rendered: format!(
                    "error: two ladder programs, `{first}` and `{path}`: give one program and its property files (.ii)\n"
                ),
            });
        }
        inputs.program = Some(path.clone());
    }
    Ok(inputs)
}

/// Does the file look like a ladder program: LDmicro by its first bytes, PLCopen by its
/// root element, else LDmicro by its name?
pub fn is_ladder(path: &str) -> bool {
    use std::io::Read;
    let mut head = [0u8; 4096];
    let n = std::fs::File::open(path).and_then(|mut f| f.read(&mut head)).unwrap_or(0);
    let text = head[..n].strip_prefix(b"\xef\xbb\xbf").unwrap_or(&head[..n]);
    let start = text.iter().position(|b| !b.is_ascii_whitespace()).unwrap_or(text.len());
    let lower = path.to_ascii_lowercase();
    text[start..].starts_with(b"LDmicro")
        || crate::ladder::plcopen::is_plcopen(&String::from_utf8_lossy(text))
        || crate::iec::is_st(&String::from_utf8_lossy(text))
        || lower.ends_with(".ld")
        || lower.ends_with(".st")
        || lower.ends_with(".il")
}

/// A ladder program read and compiled, with its sources for diagnostics.
pub struct LoadedProgram {
    /// The program as its front end read it (for its scan simulator).
    pub reference: std::sync::Arc<dyn crate::ladder::Reference>,
    /// The program in the scan model: what the compiler read.
    pub scan: crate::program::Program,
    /// Properties the program states itself (ST `//#ASSERT expr : name` comments), each
    /// `assert_NAME = 1*` about the bit written with the asserted value where it stands.
    pub properties: Vec<crate::syntax::Statement<Goal>>,
    /// The reader's own warnings (PLCopen: order, cycle, unmodelled blocks), rendered
    /// with file and line; the compiler's are in `compiled.warnings`.
    pub notes: Vec<String>,
    /// The compiled equations, bounds, signals and warnings.
    pub compiled: crate::ladder::CompiledProgram,
    /// The warnings, rendered with file and line.
    pub warnings: Vec<String>,
    /// The same warnings with their locations.
    pub located: Vec<WarningReport>,
}

/// Reads and compiles a ladder program (LDmicro or PLCopen) registered under `path`.
pub fn load_program(
    sources: &mut Sources,
    path: &str,
    options: &crate::ladder::CompileOptions,
) -> Result<LoadedProgram, Vec<Diagnostic>> {
    load_program_with(sources, path, options, &Default::default())
}

/// [`load_program`], choosing the POU and cycle of a PLCopen program.
pub fn load_program_with(
    sources: &mut Sources,
    path: &str,
    options: &crate::ladder::CompileOptions,
    selection: &crate::ladder::plcopen::Selection,
) -> Result<LoadedProgram, Vec<Diagnostic>> {
    use crate::ladder::plcopen;
    let file = read_source(sources, path).map_err(|d| vec![d])?;
    let diagnostics = |errors: Vec<crate::ladder::LadderError>| {
        errors.into_iter().map(Diagnostic::from).collect::<Vec<_>>()
    };
    let plc_diagnostics = |errors: Vec<plcopen::PlcError>| {
        errors.into_iter().map(Diagnostic::from).collect::<Vec<_>>()
    };
    let lower_path = path.to_ascii_lowercase();
    let is_st = crate::iec::is_st(sources.text(file))
        || lower_path.ends_with(".st")
        || lower_path.ends_with(".il");
    let is_plcopen = !is_st && plcopen::is_plcopen(sources.text(file));
    let mut properties = Vec::new();
    // A PLCopen program whose statement order is disputed (in its body or in a chart's
    // action): refused unless both orders compile to the same equations.
    let mut dispute: Option<Diagnostic> = None;
    let project = match is_plcopen {
        true => Some(plcopen::read_plcopen(sources, file).map_err(plc_diagnostics)?),
        false => None,
    };
    let chart_dispute = match (&project, selection.order) {
        (Some(p), None) => plcopen::chart_order_dispute(sources, p).map(Diagnostic::from),
        _ => None,
    };
    // A PLCopen program with a Structured Text or Instruction List body is read by the
    // IEC text front end.
    let st_body = project.as_ref().and_then(|p| plcopen::st_program(sources, p, selection));
    let (reference, scan, mut located) = if is_st || st_body.is_some() {
        let st_diagnostics = |errors: Vec<crate::iec::StError>| {
            errors.into_iter().map(Diagnostic::from).collect::<Vec<_>>()
        };
        let lowered = match st_body {
            Some(lowered) => {
                dispute = chart_dispute;
                lowered?
            }
            None => {
                let unit = crate::iec::read(sources, file).map_err(st_diagnostics)?;
                let (pou, cycle) = (selection.pou.as_deref(), selection.cycle_us);
                crate::iec::lower_wanting(sources, &unit, pou, cycle, &selection.elapsed)
                    .map_err(st_diagnostics)?
            }
        };
        let notes = with_places(sources, &lowered.warnings);
        let reference: std::sync::Arc<dyn crate::ladder::Reference> =
            std::sync::Arc::new(lowered.program.clone());
        use crate::program::logic::L;
        properties = lowered
            .asserts
            .iter()
            .map(|a| crate::syntax::Statement {
                name: a.name.clone(),
                name_span: a.span,
                span: a.span,
                value: Goal {
                    lhs: L::var(&a.signal).to_expr(),
                    relation: crate::syntax::Relation::Equals,
                    rhs: L::One.to_expr(),
                    after: None,
                    pattern: None,
                },
            })
            .collect();
        (reference, lowered.program, notes)
    } else if let Some(mut project) = project {
        plcopen::prepare_text_blocks(sources, &mut project, selection);
        let plc = plcopen::select(&project, selection).map_err(plc_diagnostics)?;
        let lowered = plcopen::lower(&plc).map_err(plc_diagnostics)?;
        if selection.order.is_none() {
            dispute = plc.order_dispute().map(Diagnostic::from).or(chart_dispute);
        }
        let notes = with_places(sources, &lowered.warnings);
        let reference = plcopen::PlcReference { program: plc, edges: lowered.edges };
        (
            std::sync::Arc::new(reference) as std::sync::Arc<dyn crate::ladder::Reference>,
            lowered.program,
            notes,
        )
    } else {
        let ld = crate::ladder::read_ldmicro(sources, file).map_err(diagnostics)?;
        let scan = crate::ladder::lower::lower(&ld).map_err(diagnostics)?;
        (std::sync::Arc::new(ld) as std::sync::Arc<dyn crate::ladder::Reference>, scan, Vec::new())
    };
    let compiled = crate::program::compile(&scan, options).map_err(|errors| {
        diagnostics(errors.into_iter().map(crate::ladder::LadderError::from).collect())
    })?;
    if let Some(dispute) = dispute {
        let other = in_document_order(sources, file, selection);
        // The two orders may give the very same program (the statements whose places
        // differ land in the same blocks in the same order): then the one compile holds
        // for both. Else both are compiled and their equations compared.
        let identical = other.as_ref().is_some_and(|o| format!("{o:?}") == format!("{scan:?}"));
        let same = || other.and_then(|scan| crate::program::compile(&scan, options).ok());
        if !identical && !same().is_some_and(|other| same_equations(&compiled, &other)) {
            return Err(vec![dispute]);
        }
    }
    let notes: Vec<String> = located
        .iter()
        .map(|w| match &w.location {
            Some(l) => format!("{l}: {}", w.message),
            None => w.message.clone(),
        })
        .collect();
    let mut warnings = notes.clone();
    warnings.extend(compiled.warnings.iter().map(|w| w.describe(sources)));
    located.extend(with_places(sources, &compiled.warnings));
    Ok(LoadedProgram { reference, scan, properties, notes, compiled, warnings, located })
}

/// The PLCopen program of `file` with every statement in document order (its graphical
/// body's and its charts' LD and FBD actions'), in the scan model.
fn in_document_order(
    sources: &mut Sources,
    file: usize,
    selection: &crate::ladder::plcopen::Selection,
) -> Option<crate::program::Program> {
    use crate::ladder::plcopen;
    let document =
        plcopen::Selection { order: Some(plcopen::StatementOrder::Document), ..selection.clone() };
    let mut project = plcopen::read_plcopen(sources, file).ok()?;
    if let Some(lowered) = plcopen::st_program(sources, &project, &document) {
        return lowered.ok().map(|l| l.program);
    }
    plcopen::prepare_text_blocks(sources, &mut project, &document);
    let plc = plcopen::select(&project, &document).ok()?;
    plcopen::lower(&plc).ok().map(|l| l.program)
}

/// Whether `program` and `other` have the same equations (up to their names and order):
/// the two statement orders then do the same on every scan.
fn same_equations(
    program: &crate::program::CompiledProgram,
    other: &crate::program::CompiledProgram,
) -> bool {
    use crate::ladder::SignalKind;
    let equations = |compiled: &crate::program::CompiledProgram| {
        // Compiler-made names carry their rung number: compare them by what they stand
        // for. An intermediate signal (a part of an integer value) stands for its
        // definition, named by a hash of the definition's canonical text, which names the
        // intermediates it reads the same way (defined before they are read). Names are
        // looked up by hash, each word of a side's text read in place (a REAL-heavy
        // program's sides run to megabytes).
        use crate::program::fast_hash::FastMap;
        use std::fmt::Write as _;
        let kinds: FastMap<&str, &SignalKind> =
            compiled.signals.iter().map(|(n, k)| (n.as_str(), k)).collect();
        let mut defined: FastMap<String, String> = FastMap::default();
        let canonical =
            |name: &str, defined: &FastMap<String, String>, out: &mut String| match kinds.get(name)
            {
                Some(SignalKind::Fresh { element, .. }) => {
                    let _ = write!(out, "fresh[{element}]");
                }
                Some(SignalKind::EdgeMemory { element, .. }) => {
                    let _ = write!(out, "edge[{element}]");
                }
                Some(SignalKind::Intermediate { .. }) => {
                    out.push_str(defined.get(name).map_or(name, String::as_str))
                }
                _ => out.push_str(name),
            };
        let side = |e| crate::syntax::term_to_string(e, crate::syntax::Notation::Ascii);
        let words = |text: &str, defined: &FastMap<String, String>| {
            let mut out = String::with_capacity(text.len());
            let mut start = 0;
            for (i, c) in text.char_indices() {
                if !(c.is_alphanumeric() || c == '_') {
                    canonical(&text[start..i], defined, &mut out);
                    out.push(c);
                    start = i + c.len_utf8();
                }
            }
            canonical(&text[start..], defined, &mut out);
            out.push(' ');
            out
        };
        let mut all: Vec<String> = Vec::new();
        for h in &compiled.hypotheses {
            let lhs = side(&h.lhs);
            let rhs = words(&side(&h.rhs), &defined);
            if matches!(kinds.get(lhs.as_str()), Some(SignalKind::Intermediate { .. })) {
                use std::hash::{Hash, Hasher};
                let mut hasher = std::collections::hash_map::DefaultHasher::new();
                rhs.hash(&mut hasher);
                defined.insert(lhs.clone(), format!("int{:016x}", hasher.finish()));
            }
            all.push(format!("{} {:?} {rhs}", words(&lhs, &defined), h.rel));
        }
        all.sort();
        all
    };
    equations(program) == equations(other)
}

/// A front end's warnings as the report shows them, each with its place.
fn with_places<R: crate::diag::Report>(sources: &Sources, warnings: &[R]) -> Vec<WarningReport> {
    warnings
        .iter()
        .map(|w| WarningReport {
            message: w.message(),
            location: w.span().map(|s| Location::of(sources, s)),
        })
        .collect()
}

/// `selection` with the timer instances whose elapsed time the property files `paths`
/// name: a cheap scan of their text for `X.ET` and `X_ET` (any case; a file that cannot
/// be read names none). Naming too many costs nothing but the computation: a name that
/// is no timer instance changes nothing.
pub fn wanting_elapsed(
    selection: &crate::ladder::plcopen::Selection,
    paths: &[String],
) -> crate::ladder::plcopen::Selection {
    let mut out = selection.clone();
    for path in paths {
        if let Ok(text) = std::fs::read_to_string(path) {
            out.elapsed.extend(elapsed_named(&text));
        }
    }
    out
}

/// The instances `text` names the elapsed time of, upper case: `T1` for `T1.ET` and
/// for `T1_ET` (any case).
pub fn elapsed_named(text: &str) -> std::collections::BTreeSet<String> {
    let upper = text.to_ascii_uppercase();
    // The words, each with where it starts and ends.
    let mut words: Vec<(usize, usize)> = Vec::new();
    let mut start = None;
    for (at, c) in upper.char_indices().chain(std::iter::once((upper.len(), ' '))) {
        match (c.is_alphanumeric() || c == '_', start) {
            (true, None) => start = Some(at),
            (false, Some(s)) => {
                words.push((s, at));
                start = None;
            }
            _ => {}
        }
    }
    let mut out = std::collections::BTreeSet::new();
    for (k, &(s, e)) in words.iter().enumerate() {
        let w = &upper[s..e];
        if let Some(inst) = w.strip_suffix("_ET").filter(|i| !i.is_empty()) {
            out.insert(inst.to_string());
        }
        let pin = words.get(k + 1).filter(|(s2, _)| *s2 == e + 1 && upper[e..].starts_with('.'));
        if pin.is_some_and(|&(s2, e2)| &upper[s2..e2] == "ET") {
            out.insert(w.to_string());
        }
    }
    out
}
