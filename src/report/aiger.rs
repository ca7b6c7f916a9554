//! `ii-prove export --aiger`: a compiled program and its properties as an AIGER model (one bad-state output per property) for hardware model checkers; the encoding is `counterexample::aiger`.

use crate::counterexample::aiger::{Property, encode};
use crate::counterexample::{self, unroll::Model};
use crate::diag::{Report, Sources, Span};
use crate::kernel::Axiom;
use crate::ladder::SignalKind;
use crate::semantics::Time;
use crate::syntax::{self, Notation};
use crate::term::Expr;

use super::{
    InputError, Options, assumptions, compile_options, fail, load_program_with, obligation, plan,
    program_documents,
};

/// An exported model.
pub struct Exported {
    /// The AIGER file.
    pub bytes: Vec<u8>,
    /// Its sizes, as a line of text.
    pub summary: String,
}

/// What cannot be exported exactly, where it is.
#[derive(Clone, Debug)]
struct ExportError {
    span: Option<Span>,
    message: String,
    label: String,
}

impl Report for ExportError {
    fn span(&self) -> Option<Span> {
        self.span
    }
    fn message(&self) -> String {
        format!("cannot export to AIGER: {}", self.message)
    }
    fn label(&self) -> String {
        self.label.clone()
    }
}

/// The AIGER model of `program` with the selected properties of `paths` (and of the
/// program itself) as bad-state outputs, in order: ASCII (`aag`) or binary (`aig`).
/// The model is the cone of the properties and assumptions. With `signals`, one more
/// output per equation of that cone (`signal X`), for comparing a
/// run of the model with a simulator. Anything the model would only approximate (an
/// element the algebra leaves unconstrained, a delay that is not a whole number of
/// scans) is a located error; nothing is returned then.
pub fn export_aiger(
    program: &str,
    paths: &[String],
    opts: &Options,
    binary: bool,
    signals: bool,
) -> Result<Exported, InputError> {
    let mut sources = Sources::new();
    let selection = super::wanting_elapsed(&opts.plcopen, paths);
    let loaded = load_program_with(&mut sources, program, &compile_options(opts), &selection)
        .map_err(|d| fail(&sources, d, opts))?;
    let (docs, paths) = program_documents(&mut sources, program, &loaded, paths, opts)?;
    // The comparison atoms the properties use, each defined by its equation.
    let with_atoms = loaded.compiled.with_atoms();
    let compiled = &with_atoms;
    let (selection, _) = plan(&sources, &docs, &paths, opts)?;
    let refuse = |sources: &Sources, span: Option<Span>, message: String, label: &str| {
        let e = ExportError { span, message, label: label.into() };
        fail(sources, vec![e.into()], opts)
    };
    if compiled.cycle_us == 0 {
        return Err(refuse(&sources, None, "the program's scan cycle is 0".into(), ""));
    }
    let cycle = Time::new(compiled.cycle_us.into(), 1_000_000u64.into());
    let mut groups = Vec::new();
    let mut properties = Vec::new();
    let mut statements = Vec::new();
    for (doc, path) in docs.iter().zip(&paths) {
        let group = groups.len();
        groups
            .push(assumptions(doc).into_iter().map(|a| (a.lhs, a.rel, a.rhs)).collect::<Vec<_>>());
        for s in doc.properties.iter().filter(|s| selection.selects(&s.name)) {
            let goal = obligation(&s.value);
            properties.push(Property {
                name: s.name.clone(),
                lhs: goal.lhs,
                rel: goal.rel,
                rhs: goal.rhs,
                group,
            });
            statements.push((s, path));
        }
    }
    // The cone of the properties and of every assumption: the equations they read,
    // in scan order.
    let all: Vec<Axiom> = docs.iter().flat_map(assumptions).collect();
    let session = counterexample::Program {
        reference: loaded.reference.as_ref(),
        compiled,
        assumptions: &all,
        shared: None,
    };
    let sides: Vec<&Expr> = properties.iter().flat_map(|p| [&p.lhs, &p.rhs]).collect();
    let model = Model { constraints: Vec::new(), ..session.model(&sides) };
    // Elements the algebra leaves unconstrained would be free inputs: an approximation.
    // A peripheral read is one by nature: what the world outside the scan answers.
    let assumed = groups.iter().flatten().flat_map(|(l, _, r)| [l, r]);
    for name in model.free_names(sides.iter().copied().chain(assumed)) {
        if let Some(SignalKind::Fresh { rung, element, peripheral: false }) =
            compiled.signals.get(&name)
        {
            let warning =
                compiled.warnings.iter().find(|w| w.rung == *rung && &w.element == element);
            let message = format!(
                "`{name}` is the output of {element} ({} {rung}), which the algebra leaves unconstrained: the model would allow runs the PLC cannot make",
                compiled.block_noun
            );
            return Err(refuse(
                &sources,
                warning.map(|w| w.span),
                message,
                "not expressed exactly",
            ));
        }
    }
    let mut aig = encode(&model, &groups, &properties, &cycle, signals).map_err(|e| {
        let span = e.property.map(|k| statements[k].0.span);
        refuse(&sources, span, e.message, "")
    })?;
    aig.comment(format!(
        "ii-prove {} export of {program}: one step a scan of {} us, timers {}",
        env!("CARGO_PKG_VERSION"),
        compiled.cycle_us,
        opts.timers.as_str()
    ));
    aig.comment("each output is 1 at a scan where its property fails and its file's assumptions have held at every scan so far");
    for (k, (s, path)) in statements.iter().enumerate() {
        let (line, _) = sources.line_col(s.span.file, s.span.start);
        let text = syntax::goal_to_string(&s.value, Notation::Ascii);
        let text = text.split_whitespace().collect::<Vec<_>>().join(" ");
        aig.comment(format!("output {k}: {} ({path}:{line}): {text}", s.name));
    }
    let (i, l, o, a) = aig.sizes();
    Ok(Exported {
        bytes: aig.to_bytes(binary),
        summary: format!(
            "{o} {} (outputs), {i} inputs, {l} latches, {a} and-gates",
            if o == 1 { "property" } else { "properties" }
        ),
    })
}
