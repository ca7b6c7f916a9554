//! `ii-prove equiv A B`: are two programs' outputs equal at every scan? Each matched output pair is the property `X = X'` of the two programs' product, proved or refuted by the property pipeline (kernel-checked proofs, counterexamples confirmed on both programs' own simulators).
//!
//! Inputs and outputs are matched by name: exactly, else by the name without an
//! LDmicro kind prefix, case-insensitively (IEC names); a `--map` file renames. An
//! input only one program reads is free for both; an output without a partner is not
//! compared; both are reported as warnings. The second program's signals take a prime
//! (`YL1_pump'`) in proofs and diagrams; the shared inputs keep the first's names.

use std::collections::{BTreeMap, BTreeSet};

use super::*;
use crate::diag::{Report, Span};
use crate::ladder::{CompiledProgram, SignalKind, TimerModel};
use crate::program::Program;
use crate::program::product::{ProductReference, Renaming, product};

/// What `equiv` compares besides the common options.
#[derive(Clone, Debug, Default)]
pub struct EquivOptions {
    /// A file of renames, one `NAME_IN_A = NAME_IN_B` a line.
    pub map: Option<String>,
    /// Compare only these outputs (names of either program); all matched when empty.
    pub outputs: Vec<String>,
    /// How the second program's timers are compiled (default: as the first's).
    pub b_timers: Option<TimerModel>,
    /// The second program's POU and cycle (default: as the first's).
    pub b_plcopen: Option<crate::ladder::plcopen::Selection>,
    /// Compare from matched arbitrary states instead of from power-up: the state both
    /// programs keep under one name (or a `--map` pair) starts equal and arbitrary, the
    /// rest arbitrary.
    pub any_state: bool,
}

/// A located error in a `--map` file.
struct MapError {
    span: Span,
    message: String,
}

impl Report for MapError {
    fn span(&self) -> Option<Span> {
        Some(self.span)
    }
    fn message(&self) -> String {
        self.message.clone()
    }
}

/// The key two names match by: without an LDmicro kind prefix, in lower case.
fn key(program: &CompiledProgram, name: &str) -> String {
    let base = match program.exact_names {
        true => None,
        false => crate::program::short_name(name),
    };
    base.unwrap_or_else(|| name.to_string()).to_ascii_lowercase()
}

/// The signals of `program` compared as outputs: its output pins, or, for a language
/// without them (ST, IL, PLCopen), every declared bit its code writes except the bits
/// of its own `#ASSERT` properties (never the bits the front end made: a function
/// block's `T1_Q`, `_STARTED`).
fn outputs(loaded: &LoadedProgram) -> BTreeSet<String> {
    let c = &loaded.compiled;
    let pins = of_kind(c, |k| matches!(k, SignalKind::Output));
    if !pins.is_empty() {
        return pins;
    }
    let asserted: BTreeSet<String> = loaded
        .properties
        .iter()
        .flat_map(|p| p.value.lhs.as_ref().iter())
        .filter_map(|t| match t {
            crate::term::Term::Name(n) => Some(n.as_str().to_string()),
            _ => None,
        })
        .collect();
    let mut relays = of_kind(c, |k| matches!(k, SignalKind::Relay));
    relays.retain(|n| !asserted.contains(n) && !loaded.scan.hidden.contains(n));
    relays
}

/// The signals of `c` of the kinds `kind` accepts.
fn of_kind(c: &CompiledProgram, kind: impl Fn(&SignalKind) -> bool) -> BTreeSet<String> {
    c.signals.iter().filter(|(_, k)| kind(k)).map(|(n, _)| n.clone()).collect()
}

fn has_pins(c: &CompiledProgram) -> bool {
    c.signals.values().any(|k| matches!(k, SignalKind::Output))
}

/// The inputs of `c` the outside world writes (not the start values of `--any-state`).
fn inputs(c: &CompiledProgram) -> BTreeSet<String> {
    let mut out = of_kind(c, |k| matches!(k, SignalKind::Input));
    out.retain(|n| !c.starts.contains_key(n));
    out
}

/// Pairs of `a` and `b` names: exactly equal first, then by [`key`] where that is
/// unambiguous on both sides; the rest unmatched.
fn match_names(
    a: &CompiledProgram,
    a_names: &BTreeSet<String>,
    b: &CompiledProgram,
    b_names: &BTreeSet<String>,
    pairs: &mut Vec<(String, String)>,
) {
    let taken_a: BTreeSet<String> = pairs.iter().map(|p| p.0.clone()).collect();
    let taken_b: BTreeSet<String> = pairs.iter().map(|p| p.1.clone()).collect();
    let mut left_a: BTreeSet<&String> = a_names.iter().filter(|n| !taken_a.contains(*n)).collect();
    let mut left_b: BTreeSet<&String> = b_names.iter().filter(|n| !taken_b.contains(*n)).collect();
    let exact: Vec<&String> = left_a.iter().filter(|n| left_b.contains(*n)).copied().collect();
    for n in exact {
        pairs.push((n.clone(), n.clone()));
        left_a.remove(n);
        left_b.remove(n);
    }
    let group = |c: &CompiledProgram, names: &BTreeSet<&String>| {
        let mut by: BTreeMap<String, Vec<String>> = BTreeMap::new();
        for n in names {
            by.entry(key(c, n)).or_default().push((*n).clone());
        }
        by
    };
    let (ga, gb) = (group(a, &left_a), group(b, &left_b));
    for (k, xs) in &ga {
        if let (1, Some(ys)) = (xs.len(), gb.get(k))
            && ys.len() == 1
        {
            pairs.push((xs[0].clone(), ys[0].clone()));
        }
    }
}

/// The renames of a `--map` file, resolved in both programs.
fn read_map(
    sources: &mut Sources,
    path: &str,
    a: &CompiledProgram,
    b: &CompiledProgram,
) -> Result<Vec<(String, String)>, Vec<Diagnostic>> {
    use crate::syntax::{Lookup, Scope};
    let file = read_source(sources, path).map_err(|d| vec![d])?;
    let text = sources.text(file).to_string();
    let mut pairs = Vec::new();
    let mut errors: Vec<Diagnostic> = Vec::new();
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let start = offset;
        offset += line.len();
        let body = line.split(['#']).next().unwrap_or("").trim_end();
        let body = body.split("//").next().unwrap_or("");
        if body.trim().is_empty() {
            continue;
        }
        let at = |from: usize, len: usize| Span::new(file, start + from..start + from + len.max(1));
        let lead = body.len() - body.trim_start().len();
        let Some((l, r)) = body.split_once('=') else {
            errors.push(
                MapError {
                    span: at(lead, body.trim().len()),
                    message: "expected `NAME_IN_A = NAME_IN_B`".into(),
                }
                .into(),
            );
            continue;
        };
        let mut resolve = |side: &str, from: usize, program: &CompiledProgram, which: &str| {
            let name = side.trim();
            let col = from + side.len() - side.trim_start().len();
            let found = match program.lookup(name) {
                Lookup::Signal(n) => Some(n),
                _ => program
                    .signals
                    .keys()
                    .chain(program.integers.keys())
                    .find(|n| key(program, n) == key(program, name))
                    .cloned(),
            };
            if found.is_none() {
                errors.push(
                    MapError {
                        span: at(col, name.len()),
                        message: format!("no signal `{name}` in {which}"),
                    }
                    .into(),
                );
            }
            found
        };
        let x = resolve(l, 0, a, "the first program");
        let y = resolve(r, l.len() + 1, b, "the second program");
        if let (Some(x), Some(y)) = (x, y) {
            pairs.push((x, y));
        }
    }
    if errors.is_empty() { Ok(pairs) } else { Err(errors) }
}

/// `ii-prove equiv A B`: one verdict per matched output, `X = X'` proved, refuted or
/// unknown, in a run report as for properties (A is its program, B its one file).
pub fn run_equiv_with(
    a_path: &str,
    b_path: &str,
    opts: &Options,
    equiv: &EquivOptions,
    observer: &mut dyn Observer,
) -> Result<RunReport, InputError> {
    let mut sources = Sources::new();
    let theory = theory::standard(&mut sources).map_err(|d| fail(&sources, d, opts))?;
    let a_compile =
        crate::ladder::CompileOptions { any_state: equiv.any_state, ..compile_options(opts) };
    let a = load_program_with(&mut sources, a_path, &a_compile, &opts.plcopen)
        .map_err(|d| fail(&sources, d, opts))?;
    let b_compile = crate::ladder::CompileOptions {
        timers: equiv.b_timers.unwrap_or(opts.timers),
        any_state: equiv.any_state,
    };
    let b_selection = equiv.b_plcopen.as_ref().unwrap_or(&opts.plcopen);
    let b = load_program_with(&mut sources, b_path, &b_compile, b_selection)
        .map_err(|d| fail(&sources, d, opts))?;
    let error = |text: String| InputError { rendered: format!("error: {text}\n") };
    // Renames first, then names matched by spelling.
    let mut input_pairs = Vec::new();
    let mut output_pairs = Vec::new();
    let (a_in, b_in) = (inputs(&a.compiled), inputs(&b.compiled));
    let (a_out, b_out) = (outputs(&a), outputs(&b));
    let (a_int_in, b_int_in) = (int_inputs(&a), int_inputs(&b));
    let (a_int_out, b_int_out) = (written_ints(&a), written_ints(&b));
    let mut int_in_pairs = Vec::new();
    let mut int_out_pairs = Vec::new();
    if let Some(map) = &equiv.map {
        let renames = read_map(&mut sources, map, &a.compiled, &b.compiled)
            .map_err(|d| fail(&sources, d, opts))?;
        for (x, y) in renames {
            let ints = (a.compiled.integers.get(&x), b.compiled.integers.get(&y));
            if let (Some(u), Some(v)) = ints {
                match (u.input, v.input) {
                    (true, true) => int_in_pairs.push((x, y)),
                    (false, false) => int_out_pairs.push((x, y)),
                    _ => {
                        return Err(error(format!(
                            "{map}: `{x}` and `{y}` cannot be matched: one is an input, the other is not"
                        )));
                    }
                }
                continue;
            }
            if ints.0.is_some() || ints.1.is_some() {
                return Err(error(format!(
                    "{map}: `{x}` and `{y}` cannot be matched: one is an integer, the other a bit"
                )));
            }
            match (a_in.contains(&x), b_in.contains(&y)) {
                (true, true) => input_pairs.push((x, y)),
                (false, false) => output_pairs.push((x, y)),
                _ => {
                    return Err(error(format!(
                        "{map}: `{x}` and `{y}` cannot be matched: one is an input, the other is not"
                    )));
                }
            }
        }
    }
    match_names(&a.compiled, &a_in, &b.compiled, &b_in, &mut input_pairs);
    match_names(&a.compiled, &a_int_in, &b.compiled, &b_int_in, &mut int_in_pairs);
    match_names(&a.compiled, &a_int_out, &b.compiled, &b_int_out, &mut int_out_pairs);
    // Integers matched are one type, or the comparison would not be of equal values.
    let mismatched: Vec<Diagnostic> = int_in_pairs
        .iter()
        .chain(&int_out_pairs)
        .filter_map(|(x, y)| type_mismatch(&sources, &a.compiled, x, &b.compiled, y))
        .collect();
    if !mismatched.is_empty() {
        return Err(fail(&sources, mismatched, opts));
    }
    // An output renamed by the map may be any written bit; the others are outputs.
    let mut a_cmp = a_out.clone();
    let mut b_cmp = b_out.clone();
    a_cmp.extend(output_pairs.iter().map(|p| p.0.clone()));
    b_cmp.extend(output_pairs.iter().map(|p| p.1.clone()));
    match_names(&a.compiled, &a_out, &b.compiled, &b_out, &mut output_pairs);
    let mut warnings: Vec<WarningReport> = a.located.clone();
    warnings.extend(b.located.iter().cloned());
    let note = |message: String| WarningReport { message, location: None };
    // The names of each side that no pair takes, each said with `say(name, side)`.
    let mut unpaired = |a_all: &BTreeSet<String>,
                        b_all: &BTreeSet<String>,
                        pairs: &[(String, String)],
                        say: &dyn Fn(&str, &str) -> String| {
        let (a_paired, b_paired): (BTreeSet<&String>, BTreeSet<&String>) =
            (pairs.iter().map(|p| &p.0).collect(), pairs.iter().map(|p| &p.1).collect());
        for (side, all, paired) in [("first", a_all, a_paired), ("second", b_all, b_paired)] {
            for n in all.iter().filter(|n| !paired.contains(n)) {
                warnings.push(note(say(n, side)));
            }
        }
    };
    unpaired(&a_in, &b_in, &input_pairs, &|n, side| {
        format!(
            "input `{n}` is read only by the {side} program: it is free (any value at every scan) in the comparison"
        )
    });
    unpaired(&a_int_in, &b_int_in, &int_in_pairs, &|n, side| {
        format!(
            "integer input `{n}` is read only by the {side} program: it is free (any value at every scan) in the comparison"
        )
    });
    unpaired(&a_int_out, &b_int_out, &int_out_pairs, &|n, side| {
        format!(
            "integer `{n}` of the {side} program has no counterpart in the other (name it in a --map file): not compared"
        )
    });
    // A program without output pins (ST, IL, PLCopen) compared with one that has them:
    // its other written bits are internal, not outputs without a partner.
    let (a_pins, b_pins) = (has_pins(&a.compiled), has_pins(&b.compiled));
    for (side, all, pairs_of, internal) in [
        (
            "first",
            &a_cmp,
            output_pairs.iter().map(|p| &p.0).collect::<BTreeSet<_>>(),
            !a_pins && b_pins,
        ),
        ("second", &b_cmp, output_pairs.iter().map(|p| &p.1).collect(), !b_pins && a_pins),
    ] {
        if internal {
            continue;
        }
        for n in all.iter().filter(|n| !pairs_of.contains(n)) {
            warnings.push(note(format!(
                "output `{n}` of the {side} program has no counterpart in the other (name it in a --map file): not compared"
            )));
        }
    }
    // `--outputs`: by either program's name.
    if !equiv.outputs.is_empty() {
        let wanted: Vec<String> = equiv.outputs.iter().map(|n| n.to_ascii_lowercase()).collect();
        let names = |w: &String, p: &(String, String)| {
            *w == key(&a.compiled, &p.0)
                || *w == key(&b.compiled, &p.1)
                || *w == p.0.to_ascii_lowercase()
                || *w == p.1.to_ascii_lowercase()
        };
        let picks = |p: &(String, String)| wanted.iter().any(|w| names(w, p));
        let missing: Vec<&String> = equiv
            .outputs
            .iter()
            .zip(&wanted)
            .filter(|(_, w)| !output_pairs.iter().chain(&int_out_pairs).any(|p| names(w, p)))
            .map(|(n, _)| n)
            .collect();
        if !missing.is_empty() {
            let all: Vec<&str> =
                output_pairs.iter().chain(&int_out_pairs).map(|p| p.0.as_str()).collect();
            return Err(error(format!(
                "no matched output `{}`; the matched outputs are: {}",
                missing.iter().map(|s| s.as_str()).collect::<Vec<_>>().join("`, `"),
                all.join(", ")
            )));
        }
        output_pairs.retain(picks);
        int_out_pairs.retain(picks);
    }
    if output_pairs.is_empty() && int_out_pairs.is_empty() {
        return Err(error(format!(
            "no output of `{a_path}` matches one of `{b_path}` by name: name the pairs in a --map file (`NAME_IN_A = NAME_IN_B`)"
        )));
    }
    output_pairs.sort();
    int_out_pairs.sort();
    let mut renaming =
        Renaming { shared: input_pairs.iter().map(|(x, y)| (y.clone(), x.clone())).collect() };
    // An integer input is shared bit by bit (and by name, for the simulators' values).
    for (x, y) in &int_in_pairs {
        let bits = a.compiled.integers.get(x).map_or(0, |v| v.ty.bits);
        for k in 0..bits {
            renaming.shared.insert(Program::int_bit(y, k), Program::int_bit(x, k));
        }
        renaming.shared.insert(y.clone(), x.clone());
    }
    let (a_bits, b_bits) = (written(&a.compiled), written(&b.compiled));
    let mut state_pairs = Vec::new();
    match_names(&a.compiled, &a_bits, &b.compiled, &b_bits, &mut state_pairs);
    if equiv.any_state {
        let mut matched = state_pairs.clone();
        matched.extend(output_pairs.iter().cloned());
        let starts =
            super::any_state::match_starts(&a.compiled, &b.compiled, &matched, &int_out_pairs);
        for w in &starts.unmatched {
            warnings.push(note(w.clone()));
        }
        renaming.shared.extend(starts.shared);
    }
    let compiled = product(&a.compiled, &b.compiled, &renaming).map_err(error)?;
    // Each integer output pair is compared bit for bit: `X_bk = X_bk'`.
    let mut int_bits = Vec::new();
    for (x, y) in &int_out_pairs {
        let bits = a.compiled.integers.get(x).map_or(0, |v| v.ty.bits);
        for k in 0..bits {
            let (p, q) = (Program::int_bit(x, k), Program::int_bit(&renaming.of(y), k));
            int_bits.push((p, q));
        }
    }
    let reference = ProductReference::new(
        reference_of(&a),
        reference_of(&b),
        b.compiled.signals.keys().chain(b.compiled.integers.keys()).cloned(),
        &renaming,
    );
    let cycle = Some(compiled.scan_cycle());
    // The state correspondence: bits both programs write under one name, each proved
    // equal in the two (by the algebra or induction over scans) in the product's own
    // context; the outputs' context adds those theorems as hypotheses. An output the
    // programs read back (an ST output that starts a timer) is state too. In rounds: a
    // pair proved is a hypothesis of the next round's attempts at the others.
    let read = read_names(&compiled);
    state_pairs.retain(|(x, y)| {
        let is_output = output_pairs.contains(&(x.clone(), y.clone()));
        !is_output || read.contains(x) || read.contains(&renaming.of(y))
    });
    let mut lemmas: Vec<(PropertyReport, Axiom)> = Vec::new();
    let identity = |e: &Expr| e.clone();
    let context = |lemmas: &[(PropertyReport, Axiom)]| {
        let mut hypotheses = compiled.axioms();
        hypotheses.extend(lemmas.iter().map(|(_, axiom)| axiom.clone()));
        Context::with_scans(theory.axioms(), hypotheses, cycle.clone())
            .map_err(|e| error(format!("{a_path}, {b_path}: {e}")))
    };
    let mut ctx = context(&lemmas)?;
    for _ in 0..MAX_ROUNDS {
        if state_pairs.is_empty() {
            break;
        }
        let mut found = Vec::new();
        in_order(
            &state_pairs,
            opts.jobs,
            |(x, y)| {
                correspondence(&ctx, x, &renaming.of(y), opts, &identity).map(|l| (x.clone(), l))
            },
            |event| {
                if let InOrder::Done(Some(lemma)) = event {
                    found.push(lemma);
                }
            },
        );
        if found.is_empty() {
            break;
        }
        let proved: BTreeSet<String> = found.iter().map(|(x, _)| x.clone()).collect();
        lemmas.extend(found.into_iter().map(|(_, lemma)| lemma));
        state_pairs.retain(|(x, _)| !proved.contains(x));
        ctx = context(&lemmas)?;
    }
    let session = counterexample::Program {
        reference: &reference,
        compiled: &compiled,
        assumptions: &[],
        shared: None,
    };
    // Each output's statement stands where the first program writes it.
    let a_file = a.compiled.hypotheses.first().map_or(0, |h| h.span.file);
    let statements: Vec<crate::syntax::Statement<Goal>> = output_pairs
        .iter()
        .map(|(x, y)| {
            let span = writer(&a.compiled, x).unwrap_or(Span::new(a_file, 0..0));
            crate::syntax::Statement {
                name: x.clone(),
                name_span: span,
                span,
                value: Goal {
                    lhs: crate::term::name(x),
                    relation: crate::syntax::Relation::Equals,
                    rhs: crate::term::name(&renaming.of(y)),
                    after: None,
                    pattern: None,
                },
            }
        })
        .chain(int_bits.iter().map(|(p, q)| {
            let span = writer(&a.compiled, p).unwrap_or(Span::new(a_file, 0..0));
            crate::syntax::Statement {
                name: p.clone(),
                name_span: span,
                span,
                value: Goal {
                    lhs: crate::term::name(p),
                    relation: crate::syntax::Relation::Equals,
                    rhs: crate::term::name(q),
                    after: None,
                    pattern: None,
                },
            }
        }))
        .collect();
    let selection = Selection::new(&opts.only)?;
    let statements: Vec<_> =
        statements.into_iter().filter(|s| selection.selects(&s.name)).collect();
    if statements.is_empty() {
        return Err(error(format!(
            "no compared output matches `--only {}`",
            opts.only.join(" --only ")
        )));
    }
    let plan: Vec<(String, Location)> =
        statements.iter().map(|s| (s.name.clone(), Location::of(&sources, s.span))).collect();
    observer.begin(&plan, &[b_path.to_string()]);
    for w in &warnings {
        observer.warning(w);
    }
    let mut properties = Vec::new();
    for (report, _) in &lemmas {
        observer.correspondence(report);
    }
    in_order(
        &statements,
        opts.jobs,
        |s| {
            let mut report =
                check_property(&ctx, s, ctx.hypotheses(), opts, &identity, Some(&session));
            report.location = Some(Location::of(&sources, s.span));
            // Runs longer than bounded model checking reaches (timers of 499 and 500
            // scans): held inputs on the simulators, confirmed as any counterexample.
            if report.status == Status::Unknown
                && let Some(c) = search_on_simulators(&session, &obligation(&s.value), opts)
            {
                let goal = obligation(&s.value);
                let shown = property::program_counterexample(&session, &goal, &c, opts, &identity);
                report.status = Status::Refuted;
                report.reason = None;
                report.candidate = None;
                report.counterexample = Some(Box::new(shown));
            }
            report
        },
        |event| match event {
            InOrder::Next => observer.started(properties.len()),
            InOrder::Done(report) => {
                observer.finished(&report);
                properties.push(super::kept(observer, report));
            }
        },
    );
    let mut report =
        finish(Some(a_path.to_string()), vec![b_path.to_string()], warnings, properties);
    report.correspondences = lemmas.into_iter().map(|(r, _)| r).collect();
    report.timers = Some(opts.timers.as_str());
    Ok(report)
}

/// A program's reference: its own simulator, started from the state of the first scan's
/// start values when it is compiled with `--any-state`.
fn reference_of(p: &LoadedProgram) -> std::sync::Arc<dyn crate::ladder::Reference> {
    match p.compiled.started {
        Some(_) => std::sync::Arc::new(crate::program::any_state::AnyStateReference::new(
            p.reference.clone(),
            &p.compiled,
        )),
        None => p.reference.clone(),
    }
}

/// The integers the outside world writes; not the free values a front end gives where
/// the runtime's result is undefined (a `REAL_TO_INT` of a NaN, a signed overflow), which
/// each program chooses for itself.
fn int_inputs(p: &LoadedProgram) -> BTreeSet<String> {
    let inputs =
        p.compiled.integers.iter().filter(|(n, v)| v.input && !p.scan.undefined.contains(*n));
    inputs.map(|(n, _)| n.clone()).collect()
}

/// A located error when the integers `x` of `a` and `y` of `b` are not of one type: at
/// the second program's first mention of its integer, naming the first's.
fn type_mismatch(
    sources: &Sources,
    a: &CompiledProgram,
    x: &str,
    b: &CompiledProgram,
    y: &str,
) -> Option<Diagnostic> {
    let (u, v) = (a.integers.get(x)?, b.integers.get(y)?);
    if u.ty == v.ty {
        return None;
    }
    let file = b.hypotheses.first().map_or(0, |h| h.span.file);
    let span = first_mention(sources, file, y).unwrap_or(Span::new(file, 0..0));
    let a_file = a.hypotheses.first().map_or(0, |h| h.span.file);
    let at_a = first_mention(sources, a_file, x).map_or(String::new(), |s| {
        let (line, col) = sources.line_col(a_file, s.start);
        format!(" ({}:{line}:{col})", sources.name(a_file))
    });
    Some(
        MapError {
            span,
            message: format!(
                "`{y}` is {} here, but `{x}` of the first program{at_a} is {}: integers are compared bit for bit and must be of one type",
                v.ty.describe(),
                u.ty.describe()
            ),
        }
        .into(),
    )
}

/// The first whole-word mention of `name` (ignoring case) in `file`.
fn first_mention(sources: &Sources, file: crate::diag::FileId, name: &str) -> Option<Span> {
    let text = sources.text(file);
    let lower = text.to_ascii_lowercase();
    let want = name.to_ascii_lowercase();
    let word = |c: Option<char>| c.is_some_and(|c| c.is_ascii_alphanumeric() || c == '_');
    let mut from = 0;
    while let Some(k) = lower[from..].find(&want) {
        let at = from + k;
        let end = at + want.len();
        if !word(lower[..at].chars().next_back()) && !word(lower[end..].chars().next()) {
            return Some(Span::new(file, at..end));
        }
        from = end;
    }
    None
}

/// The integers `program` writes (not its input integers), without those its front end
/// made (a counter's `C1_CV`, a kept `_IL_CR`).
fn written_ints(loaded: &LoadedProgram) -> BTreeSet<String> {
    let visible = |n: &&String| !loaded.scan.hidden.contains(*n);
    let written = loaded.compiled.integers.iter().filter(|(_, v)| !v.input);
    written.map(|(n, _)| n).filter(visible).cloned().collect()
}

/// At most this many rounds of state correspondences (each retries the pairs not yet
/// proved with those proved so far as hypotheses).
const MAX_ROUNDS: usize = 4;

/// The names the product's hypotheses read (on their right-hand sides).
fn read_names(c: &CompiledProgram) -> BTreeSet<String> {
    let mut read = BTreeSet::new();
    for h in &c.hypotheses {
        for node in h.rhs.as_ref() {
            if let crate::term::Term::Name(n) = node {
                read.insert(n.as_str().to_string());
            }
        }
    }
    read
}

/// The bits `program` writes (outputs and internal relays).
fn written(c: &CompiledProgram) -> BTreeSet<String> {
    of_kind(c, |k| matches!(k, SignalKind::Relay | SignalKind::Output))
}

/// The state correspondence lemma `x = y` of the product, if the prover finds a proof
/// the kernel vouches for: its report (named `state_x`) and the hypothesis it becomes.
fn correspondence(
    ctx: &Context,
    x: &str,
    y: &str,
    opts: &Options,
    rename: &dyn Fn(&Expr) -> Expr,
) -> Option<(PropertyReport, Axiom)> {
    let started = std::time::Instant::now();
    let goal = Obligation {
        lhs: crate::term::name(x),
        rel: crate::kernel::Rel::Eq,
        rhs: crate::term::name(y),
    };
    let budget = crate::prover::Budget {
        time: opts.timeout.mul_f64(0.3),
        ..crate::prover::Budget::default()
    };
    let crate::prover::Outcome::Proved(proved) = crate::prover::prove(ctx, &goal, budget) else {
        return None;
    };
    ctx.kernel.vouch(&proved.theorem, &goal.lhs, goal.rel, &goal.rhs).ok()?;
    let style = trace::Style { notation: opts.notation(), rename };
    let name = format!("state_{x}");
    let shown = Goal {
        lhs: goal.lhs.clone(),
        relation: crate::syntax::Relation::Equals,
        rhs: goal.rhs.clone(),
        after: None,
        pattern: None,
    };
    let report = PropertyReport {
        name: name.clone(),
        location: None,
        statement: syntax::goal_to_string(&shown, opts.notation()),
        status: Status::Proved,
        reason: None,
        time_ms: started.elapsed().as_secs_f64() * 1e3,
        trace: Some(Box::new(property::trace_report(&proved, goal.rel, opts, &style))),
        counterexample: None,
        candidate: None,
        vacuous: false,
        vacuity: None,
    };
    Some((report, Axiom::ground(name, goal.lhs, goal.rel, goal.rhs)))
}

/// Looks for a run on which the product's simulators (both programs' own) part on
/// `goal`'s two sides: a few random input vectors, each held for a number of scans
/// around the longest timer's; a run found is confirmed by exact evaluation and the
/// simulators ([`counterexample::confirm`]) before it is returned.
fn search_on_simulators(
    session: &counterexample::Program,
    goal: &Obligation,
    opts: &Options,
) -> Option<Box<counterexample::Counterexample>> {
    use crate::term::{Term, root};
    let side = |e: &Expr| match &e[root(e)] {
        Term::Name(n) => Some(n.as_str().to_string()),
        _ => None,
    };
    let (x, y) = (side(&goal.lhs)?, side(&goal.rhs)?);
    let compiled = session.compiled;
    // The start values of `--any-state` too: the runs start from random states.
    let inputs = of_kind(compiled, |k| {
        matches!(k, SignalKind::Input | SignalKind::IntBit { input: true, .. })
    });
    let longest =
        compiled.timer_info.iter().filter_map(|t| usize::try_from(t.scans).ok()).max().unwrap_or(0);
    let mut lengths: Vec<usize> = vec![
        1,
        2,
        3,
        longest.saturating_sub(1),
        longest,
        longest + 1,
        longest + 2,
        2 * longest + 2,
    ];
    lengths.retain(|&n| n > 0);
    lengths.dedup();
    let started = std::time::Instant::now();
    let deadline = started + opts.timeout.mul_f64(0.3).min(std::time::Duration::from_secs(3));
    let cycle = crate::semantics::Time::new(compiled.cycle_us.into(), 1_000_000u64.into());
    // The counterexample module's fixed pseudo-random sequence: the same run every time.
    let mut runs = counterexample::unroll::Runs64::default();
    let mut next = move || runs.random();
    while std::time::Instant::now() < deadline {
        let segments = 1 + (next() % 3) as usize;
        let mut values: BTreeMap<String, Vec<bool>> = BTreeMap::new();
        let mut scans = 0;
        for _ in 0..segments {
            let n = lengths[(next() % lengths.len() as u64) as usize];
            for i in &inputs {
                let v = next() % 2 == 1;
                values.entry(i.clone()).or_default().extend(std::iter::repeat_n(v, n));
            }
            scans += n;
        }
        let mut sim = session.reference.simulator();
        let mut parted = None;
        for k in 0..scans {
            let step: BTreeMap<String, bool> =
                values.iter().map(|(n, v)| (n.clone(), v[k])).collect();
            sim.step(&step);
            if !sim.is_known(&x) || !sim.is_known(&y) {
                return None;
            }
            if sim.bit(&x) != sim.bit(&y) {
                parted = Some(k);
                break;
            }
        }
        let Some(k) = parted else { continue };
        for v in values.values_mut() {
            v.truncate(k + 1);
        }
        let trace = counterexample::ScanTrace { cycle: cycle.clone(), scans: k + 1, values };
        let limits = counterexample::Limits {
            deadline,
            max_steps: 200,
            max_scans: 100_000,
            minimised: false,
            signals: true,
        };
        if let counterexample::Verdict::Refuted(c) =
            counterexample::confirm(session, goal, trace, limits)
        {
            return Some(c);
        }
    }
    None
}

/// Where `program` writes `name`: its last defining equation's block.
fn writer(program: &CompiledProgram, name: &str) -> Option<Span> {
    let index = program.equation_index();
    let at = *index.defining.get(name)?.last()?;
    let (_, h) = index.equations.get(at)?;
    Some(program.hypotheses.get(*h)?.span)
}
