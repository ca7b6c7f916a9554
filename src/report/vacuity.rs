//! Vacuity: hypotheses that contradict each other or the program, signals they force to a constant, and which constants a property states itself.
//!
//! A signal the hypotheses force is a sign of a vacuous proof only when the property does
//! not claim that value: `Out = 0*` ("this output is never energised") and `Out1 + Out2 = 0*` claim their
//! signals' values: that the program forces them is what was to be proved. In
//! `Ns_green · Ew_green = 0*` a forced `Ns_green = 0*` makes `Ew_green` irrelevant: the
//! property holds vacuously. The test is pointwise: the goal, with its signals and its
//! timer, memory and `pre` subterms read as free Boolean atoms, must imply the value.

use std::time::Duration;

use super::property::style_term;
use super::{Options, PropertyReport, Status, trace};
use crate::counterexample;
use crate::kernel::{Axiom, Rel};
use crate::prover::{self, Budget, Context, Obligation, Outcome};
use crate::semantics::format_time;
use crate::term::{Expr, Term};

/// Marks what inconsistent hypotheses mean for a property: an unknown one's reason
/// says so, a proved one is vacuous. Otherwise `forced` (run only for a proved
/// property) may name signals the hypotheses force to a constant.
pub(super) fn flag_vacuity(
    report: &mut PropertyReport,
    inconsistent: Option<&str>,
    forced: impl FnOnce() -> Option<String>,
) {
    match report.status {
        Status::Unknown => {
            if let (Some(text), Some(reason)) = (inconsistent, &mut report.reason) {
                let line = crate::prover::clip(text, crate::prover::REASON_LINE);
                reason.push_str(&format!("\n{line}"));
            }
        }
        Status::Proved => {
            let why = inconsistent.map(str::to_string).or_else(forced);
            report.vacuous = why.is_some();
            report.vacuity = why;
        }
        Status::Refuted => {}
    }
}

/// Do the assumptions prove `0* = 1*`? Asked as `n·¬n = n + ¬n` for a name `n` of
/// each assumption, so that the goal's cone of influence reaches the assumptions.
pub(super) fn contradictory(ctx: &Context, hypotheses: &[Axiom], opts: &Options) -> bool {
    let mut asked = std::collections::BTreeSet::new();
    hypotheses.iter().any(|h| {
        let Some(n) = h.lhs.as_ref().iter().chain(h.rhs.as_ref()).find_map(|node| match node {
            crate::term::Term::Name(n) => Some(*n),
            _ => None,
        }) else {
            return false;
        };
        let signal = crate::term::name(n.as_str());
        let zero = crate::term::and_not(&signal, &signal);
        let one = crate::term::or(&signal, &crate::term::not(&signal));
        asked.insert(n) && proves_quickly(ctx, &zero, &one, opts)
    })
}

/// Does the prover prove `lhs = rhs` quickly (a short budget, and no larger rule sets
/// once the Boolean skeleton has a model: this is a check on the assumptions, not a
/// property)?
pub(super) fn proves_quickly(ctx: &Context, lhs: &Expr, rhs: &Expr, opts: &Options) -> bool {
    let goal = Obligation { lhs: lhs.clone(), rel: Rel::Eq, rhs: rhs.clone() };
    let budget = Budget { time: opts.timeout.min(VACUITY_CHECK), ..Budget::default() };
    // A model of the Boolean skeleton is answer enough: no larger rule sets.
    let stop = &mut |_: &prover::Candidate, look| look == prover::Look::BeforeLargerRules;
    matches!(prover::prove_with(ctx, &goal, budget, stop), Outcome::Proved(_))
}

/// The signals a goal reads that the assumptions force to a constant (free signals).
pub(super) fn forced_by_assumptions(
    ctx: &Context,
    goal: &Obligation,
    opts: &Options,
) -> Vec<(String, bool)> {
    let mut read = std::collections::BTreeSet::new();
    for side in [&goal.lhs, &goal.rhs] {
        for node in side.as_ref() {
            if let crate::term::Term::Name(n) = node {
                read.insert(n.to_string());
            }
        }
    }
    let mut forced = Vec::new();
    for n in read {
        for value in [false, true] {
            let signal = crate::term::name(&n);
            if proves_quickly(ctx, &signal, &crate::term::constant(value), opts) {
                if !claimed(goal, &n, value) {
                    forced.push((n.clone(), value));
                }
                break;
            }
        }
    }
    forced
}

/// Time for each consistency or constancy check of the assumptions.
const VACUITY_CHECK: Duration = Duration::from_millis(500);

/// Signals the property reads that the hypotheses force to a constant (bounded search
/// on each signal's cut cone, answers shared through the session's `cache`).
pub(super) fn forced_constants(
    session: &counterexample::Program,
    cache: &counterexample::VacuityCache,
    goal: &Obligation,
    rename: &dyn Fn(&Expr) -> Expr,
    opts: &Options,
) -> Option<String> {
    let mut v = counterexample::vacuity_cached(session, &[&goal.lhs, &goal.rhs], cache);
    v.constants.retain(|(n, c)| !claimed(goal, n, *c));
    if v.constants.is_empty() {
        return None;
    }
    let style = trace::Style { notation: opts.notation(), rename };
    Some(forced_text(&style, &v.constants, v.horizon.as_ref()))
}

/// "the hypotheses force X = 0*, … in every run": a property reading them may hold
/// only vacuously. `horizon`: how far a bounded check looked.
pub(super) fn forced_text(
    style: &trace::Style,
    forced: &[(String, bool)],
    horizon: Option<&crate::semantics::Time>,
) -> String {
    let parts: Vec<String> = forced
        .iter()
        .map(|(n, c)| {
            let value = if *c { "1*" } else { "0*" };
            format!("{} = {value}", style_term(style, &crate::term::name(n)))
        })
        .collect();
    format!(
        "the hypotheses force {}{}: the property may hold only vacuously",
        parts.join(", "),
        horizon
            .map(|h| format!(" in every run up to t = {} s", format_time(h)))
            .unwrap_or_default()
    )
}

/// The most atoms a goal may have for the test.
const MAX_ATOMS: usize = 12;

/// Whether the goal, read pointwise, implies `name = value`: the prover's Boolean
/// skeleton (signals, timers, memories and `pre` terms as atoms) has no model where the
/// goal holds and `name` differs. False when `name` is not one of its atoms or it has
/// too many atoms to tell.
pub(super) fn claimed(goal: &Obligation, name: &str, value: bool) -> bool {
    use crate::term::{and, and_not, not, or};
    let signal = crate::term::name(name);
    let reads =
        |e: &Expr| e.as_ref().iter().any(|n| matches!(n, Term::Name(s) if s.as_str() == name));
    if !reads(&goal.lhs) && !reads(&goal.rhs) {
        return false;
    }
    let (l, r) = (&goal.lhs, &goal.rhs);
    let violated = match goal.rel {
        Rel::Eq => or(&and_not(l, r), &and_not(r, l)),
        Rel::Implies => and_not(l, r),
    };
    let differs = if value { not(&signal) } else { signal };
    let mut atoms = prover::boolean::Atoms::default();
    let model = prover::boolean::model_of(&and(&not(&violated), &differs), &[], &mut atoms);
    model.is_none() && atoms.terms.len() <= MAX_ATOMS
}
