//! The command line's counterexample search for the REPL's `prove` and `auto`: what it
//! needs, owned by the worker thread it runs on, and how a counterexample is shown.

use std::time::Duration;

use crate::counterexample;
use crate::kernel::Axiom;
use crate::ladder::{CompiledProgram, Reference};
use crate::report::{self, Options};
use crate::syntax::{Goal, Notation, Statement};
use crate::term::Expr;
use crate::theory;

/// A counterexample search's inputs, owned (it runs on a worker thread): the `assume`
/// statements, the program, the limits.
pub(super) struct SearchKit {
    assumed: Vec<Axiom>,
    program: Option<CompiledProgram>,
    reference: Option<std::sync::Arc<dyn Reference>>,
    opts: Options,
}

impl SearchKit {
    /// Calls `job` with the hypotheses, options, display renaming and program a search
    /// takes.
    pub(super) fn run<T>(
        &self,
        job: impl FnOnce(
            &[Axiom],
            &Options,
            &dyn Fn(&Expr) -> Expr,
            Option<&counterexample::Program>,
        ) -> T,
    ) -> T {
        let rename = |e: &Expr| match &self.program {
            Some(c) => c.rename_for_display(e),
            None => e.clone(),
        };
        let program = match (&self.program, &self.reference) {
            (Some(compiled), Some(reference)) => {
                let reference = reference.as_ref();
                Some(counterexample::Program {
                    reference,
                    compiled,
                    assumptions: &self.assumed,
                    shared: None,
                })
            }
            _ => None,
        };
        job(&self.assumed, &self.opts, &rename, program.as_ref())
    }
}

/// A confirmed counterexample as REPL lines: when, where, the diagram.
pub(super) fn counterexample_lines(c: &report::CounterexampleReport) -> String {
    let mut out = format!(
        "    counterexample: at t = {}{} the left side is {} and the right side is {}\n",
        c.time,
        c.scan.map(|k| format!(" s (scan {k})")).unwrap_or_default(),
        c.lhs as u8,
        c.rhs as u8
    );
    for line in &c.diagram {
        out.push_str(&format!("    {line}\n"));
    }
    out
}

/// An `assume` statement as a hypothesis.
fn assumption(s: &Statement<Goal>) -> Axiom {
    let (lhs, rel, rhs) = theory::goal_parts(&s.value);
    Axiom::ground(s.name.clone(), lhs, rel, rhs)
}

impl SearchKit {
    /// The inputs of a search over the session's `assume` statements and program.
    pub(super) fn new(
        assumptions: &[Statement<Goal>],
        program: Option<&CompiledProgram>,
        reference: Option<&std::sync::Arc<dyn Reference>>,
        notation: Notation,
        timeout: Duration,
    ) -> SearchKit {
        SearchKit {
            assumed: assumptions.iter().map(assumption).collect(),
            program: program.cloned(),
            reference: reference.cloned(),
            opts: Options { timeout, ascii: notation == Notation::Ascii, ..Options::default() },
        }
    }
}
