//! What an unknown tells people: what each method tried and how far it got, what is
//! missing, and a possible counterexample drawn small — a few lines, the same in every
//! format, never a dump of terms.

use super::tracks::IntegerTrack;
use super::{CounterexampleReport, IntegerReport, SignalReport, trace, waveform};
use crate::program::CompiledProgram;
use crate::prover::induction::{Stalled, Stop};
use crate::prover::{Candidate, REASON_LINE, clip};
use crate::semantics::{Assignment, Signal, Time};
use crate::term::{Expr, Symbol};

/// At most this many signals in a possible counterexample's diagram.
pub const DIAGRAM_ROWS: usize = 8;
/// At most this many characters per line of that diagram (where the signals allow).
pub const DIAGRAM_WIDTH: usize = 96;
/// At most this many atoms of the Boolean skeleton's model under `--trace`.
const MODEL_ATOMS: usize = 12;
/// At most this many characters per atom shown under `--trace`.
const ATOM_WIDTH: usize = 48;

/// What the counterexample search found for a goal the prover left open.
pub enum Search<'a> {
    /// A run violates the compiled terms, but the scan simulator does not show it: `why`.
    Unconfirmed(&'a str),
    /// Nothing found: `why` (how far the search went).
    NotFound(&'a str),
}

/// The reason of an unknown: the prover's lines (what it tried), the counterexample
/// search's, what is missing, and — with `--trace` — a bounded sample of the Boolean
/// skeleton's model. Every line is clipped to [`REASON_LINE`] characters.
pub fn reason(
    proof: &str,
    search: Search,
    induction: Option<&Stalled>,
    model: Option<&Candidate>,
    expert: Option<&trace::Style>,
) -> String {
    let mut lines: Vec<String> = proof.lines().map(str::to_string).collect();
    match search {
        Search::Unconfirmed(why) => {
            lines.push(format!("bounded model checking: a run violates the equations, but {why}"));
        }
        Search::NotFound(why) => {
            lines.push(format!("counterexample search: {why}"));
            lines.extend(missing(induction, model.is_some()));
        }
    }
    if let (Some(style), Some(model)) = (expert, model) {
        lines.push(model_line(style, model));
    }
    lines.iter().map(|l| clip(l, REASON_LINE)).collect::<Vec<_>>().join("\n")
}

/// What would settle the goal, when neither a proof nor a counterexample was found.
fn missing(induction: Option<&Stalled>, has_model: bool) -> Option<String> {
    let text = match induction.map(|s| (s.stop, s.candidates)) {
        Some((Stop::Step, n)) => format!(
            "missing: an invariant that rules out the state the induction step fails from (no run the search tried reaches a violation, so that state is likely unreachable); none was found among {n} candidates (literals and pairs of state bits)"
        ),
        Some((Stop::Base, _)) => "missing: the skeleton breaks the goal at the first scan through a timer or memory value the laws do not pin down".into(),
        Some((Stop::Limit, _)) => "missing: time for the invariant search (a larger --timeout)".into(),
        _ if has_model => "missing: a law or hypothesis that rules out the skeleton's model (timers, memories and `pre` terms are free atoms there), or a counterexample the search did not reach".into(),
        _ => "missing: a proof within the limits (a larger --timeout gives every method more)".into(),
    };
    Some(text)
}

/// `--trace`: the first atoms of the Boolean skeleton's model, each cut short.
fn model_line(style: &trace::Style, model: &Candidate) -> String {
    let shown: Vec<String> = model
        .iter()
        .take(MODEL_ATOMS)
        .map(|(atom, v)| {
            let text = clip(&super::property::style_term(style, atom), ATOM_WIDTH);
            format!("{text} = {}", *v as u8)
        })
        .collect();
    let more = model.len().saturating_sub(MODEL_ATOMS);
    let more = if more > 0 { format!(", … {more} more") } else { String::new() };
    format!("skeleton model ({} atoms): {}{more}", model.len(), shown.join(", "))
}

/// A possible counterexample drawn small: the last [`DIAGRAM_ROWS`] signals shown (the
/// property's own signals and sides come last), [`DIAGRAM_WIDTH`] characters wide, and
/// only those signals in the JSON.
pub fn bounded(mut c: CounterexampleReport, glyphs: waveform::Glyphs) -> CounterexampleReport {
    let cut = c.shown.len().saturating_sub(DIAGRAM_ROWS);
    c.shown.drain(..cut);
    c.signals.retain(|s| c.shown.iter().any(|(n, _)| *n == s.name));
    c.diagram = waveform::draw_within(&c.shown, c.mark.as_ref(), glyphs, DIAGRAM_WIDTH);
    c
}

/// The state the induction step failed from, as two scans (the previous one and the one
/// that breaks the goal), when the invariant search stopped there.
pub fn step_candidate(
    stalled: &Stalled,
    compiled: Option<&CompiledProgram>,
    rename: &dyn Fn(&Expr) -> Expr,
    notation: crate::syntax::Notation,
    glyphs: waveform::Glyphs,
) -> Option<CounterexampleReport> {
    if stalled.stop != Stop::Step || stalled.step_model.is_empty() {
        return None;
    }
    let one = Time::from_integer(1.into());
    let two = Time::from_integer(2.into());
    let named = |n: &str| crate::syntax::term_to_string(&rename(&crate::term::name(n)), notation);
    let all: Vec<(String, Signal)> = stalled
        .step_model
        .iter()
        .map(|(name, before, now)| {
            let (b, n) = (before.unwrap_or(false), now.unwrap_or(false));
            let s =
                Signal::from_fn(two.clone(), vec![one.clone()], |t| if *t <= one { b } else { n });
            (name.clone(), s)
        })
        .collect();
    // An integer whose every bit is a state bit is drawn as its value, not its bits.
    let mut env = Assignment::new(two.clone());
    env.signals.extend(all.iter().map(|(n, s)| (Symbol::from(n.as_str()), s.clone())));
    let mut tracked = compiled.map(|c| IntegerTrack::all(c, &env, &named)).unwrap_or_default();
    // At most DIAGRAM_ROWS rows in all, one of them a signal; the integers in the order
    // of their bits in the model (the goal's first).
    tracked.sort_by_cached_key(|t| all.iter().position(|(n, _)| t.shows_bit(&named(n))));
    tracked.truncate(DIAGRAM_ROWS - 1);
    let shown: Vec<(String, Signal)> = all
        .into_iter()
        .map(|(n, s)| (named(&n), s))
        .filter(|(label, _)| !tracked.iter().any(|t| t.shows_bit(label)))
        .take(DIAGRAM_ROWS - tracked.len())
        .collect();
    let mut diagram = super::tracks::draw(&shown, &tracked, None, glyphs);
    // The columns are a scan and the next, not instants of a run: the axis says so.
    let width = shown
        .iter()
        .map(|(n, _)| n.chars().count())
        .chain(tracked.iter().map(|t| t.name.chars().count()))
        .max()
        .unwrap_or(0)
        .max(4);
    if let Some(axis) = diagram.last_mut() {
        *axis = format!("{:<width$} {:^5} {:^5}", "scan", "k-1", "k").trim_end().to_string();
    }
    Some(CounterexampleReport {
        time: "k".into(),
        lhs: true,
        rhs: false,
        signals: shown
            .iter()
            .map(|(name, s)| SignalReport::of(name.clone(), s))
            .collect(),
        diagram,
        integers: tracked
            .iter()
            .map(|t| IntegerReport {
                name: t.name.clone(),
                values: vec![t.value_at(&one), t.value_at(&two)],
                ty: t.ty.time.then_some("TIME"),
            })
            .collect(),
        tracks: tracked,
        scan: None,
        simulator_scan: None,
        confirmed_by: Vec::new(),
        title: Some(
            "possible counterexample of the induction step (a state no invariant excluded; unknown values drawn 0):"
                .into(),
        ),
        shown,
        mark: None,
    })
}
