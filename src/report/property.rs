//! Proves one property and, when no proof is found, searches for a counterexample that
//! exact evaluation (and, for a program, the scan simulator) confirms.

use std::time::{Duration, Instant};

use super::tracks::IntegerTrack;
use super::{
    CounterexampleReport, IntegerReport, Options, PropertyReport, SignalReport, Status, StepReport,
    TraceReport, obligation, trace, unknown, waveform,
};
use crate::counterexample::{self, Counterexample, Limits, Verdict};
use crate::kernel::{Axiom, Rel};
use crate::prover::{self, Budget, Context, Obligation, Outcome};
use crate::semantics::falsify::{self, Condition, Witness};
use crate::semantics::{eval, format_time};
use crate::syntax::{self, Goal, Statement};
use crate::term::Expr;
use crate::theory;

/// How an attempt at a goal ended.
pub enum Attempt {
    /// The kernel checked a proof.
    Proved(Box<prover::Proved>),
    /// A confirmed counterexample.
    Refuted(CounterexampleReport),
    /// Neither: why, and a counterexample only the exact evaluation confirms, if any.
    Unknown {
        /// What was tried.
        reason: String,
        /// An unconfirmed counterexample (a program's, that the simulator does not show).
        candidate: Option<CounterexampleReport>,
    },
}

/// The command line's attempt at a goal within `opts.timeout`: the proof search (70 %
/// of the time), with a first, short look for a counterexample as soon as the quick
/// methods find a model of the Boolean skeleton, then — when no proof is found — the
/// counterexample search (bounded model checking over scans for a program, random
/// exact signals otherwise). The REPL's `prove` runs the same.
pub fn attempt(
    ctx: &Context,
    goal: &Obligation,
    hypotheses: &[Axiom],
    opts: &Options,
    rename: &dyn Fn(&Expr) -> Expr,
    program: Option<&counterexample::Program>,
) -> Attempt {
    let started = Instant::now();
    // A run that refuted another property of the program may refute this one too.
    if let Some(session) = program {
        let deadline = started + FIRST_LOOK.min(opts.timeout);
        let limits = Limits {
            deadline,
            max_steps: 200,
            max_scans: 100_000,
            minimised: false,
            signals: opts.run_signals,
        };
        if let Some(c) = counterexample::shared::refute_shared(session, goal, limits) {
            return Attempt::Refuted(program_counterexample(session, goal, &c, opts, rename));
        }
    }
    let style = trace::Style { notation: opts.notation(), rename };
    // `--timeout` bounds the whole property: the proof search gets most of it, the
    // counterexample search the rest.
    let budget = Budget { time: opts.timeout.mul_f64(PROOF_SHARE), ..Budget::default() };
    let end = started + opts.timeout;
    let search = |deadline: Instant| {
        search_counterexample(goal, hypotheses, opts, rename, program, deadline)
    };
    // When the Boolean skeleton has a model the property is likely false, and the
    // invariant search and the larger rule sets are slow to give up: look for a
    // counterexample before them, once.
    let mut refuted = None;
    // A first look that tried every run it planned need not be repeated.
    let mut first_look = None;
    let outcome = prover::prove_with(ctx, goal, budget, &mut |_, look| {
        if look != prover::Look::BeforeInduction {
            return refuted.is_some();
        }
        match search((Instant::now() + FIRST_LOOK).min(end)) {
            Search::Refuted(c) => refuted = Some(c),
            found @ Search::NotFound { complete: true, .. } => first_look = Some(found),
            Search::Unconfirmed { .. } | Search::NotFound { .. } => {}
        }
        refuted.is_some()
    });
    if let Some(c) = refuted {
        return Attempt::Refuted(c);
    }
    match outcome {
        // The search is untrusted: a goal is proved only by a theorem of this context's
        // kernel that states exactly it.
        Outcome::Proved(proved) => {
            match ctx.kernel.vouch(&proved.theorem, &goal.lhs, goal.rel, &goal.rhs) {
                Ok(()) => Attempt::Proved(proved),
                Err(e) => Attempt::Unknown {
                    reason: prover::clip(
                        &format!("the search's theorem is refused: {e}"),
                        prover::REASON_LINE,
                    ),
                    candidate: None,
                },
            }
        }
        Outcome::Unknown { reason, candidate, induction } => {
            let limit = if program.is_some() { PROGRAM_SEARCH } else { FREE_SEARCH };
            // A short look even when the proof search ran to the end of the limit,
            // so that the property ends within `--timeout` and `LAST_LOOK` of it.
            let floor = Instant::now() + opts.timeout.mul_f64(LAST_LOOK);
            let found =
                first_look.unwrap_or_else(|| search((Instant::now() + limit).min(end.max(floor))));
            let induction = induction.as_deref();
            let expert = opts.trace.then_some(&style);
            let glyphs = opts.glyphs();
            match found {
                Search::Refuted(c) => Attempt::Refuted(c),
                Search::Unconfirmed { candidate: c, why } => Attempt::Unknown {
                    reason: unknown::reason(
                        &reason,
                        unknown::Search::Unconfirmed(&why),
                        induction,
                        candidate.as_ref(),
                        expert,
                    ),
                    candidate: Some(unknown::bounded(c, glyphs)),
                },
                Search::NotFound { why, .. } => Attempt::Unknown {
                    reason: unknown::reason(
                        &reason,
                        unknown::Search::NotFound(&why),
                        induction,
                        candidate.as_ref(),
                        expert,
                    ),
                    candidate: induction.and_then(|s| {
                        let compiled = program.map(|p| p.compiled);
                        unknown::step_candidate(s, compiled, rename, opts.notation(), glyphs)
                    }),
                },
            }
        }
    }
}

/// The counterexample search alone, within the command line's limits: a confirmed
/// counterexample of `goal`, if one is found.
pub fn refute(
    goal: &Obligation,
    hypotheses: &[Axiom],
    opts: &Options,
    rename: &dyn Fn(&Expr) -> Expr,
    program: Option<&counterexample::Program>,
) -> Option<CounterexampleReport> {
    let limit = if program.is_some() { PROGRAM_SEARCH } else { FREE_SEARCH };
    let deadline = Instant::now() + limit.min(opts.timeout);
    match search_counterexample(goal, hypotheses, opts, rename, program, deadline) {
        Search::Refuted(c) => Some(c),
        Search::Unconfirmed { .. } | Search::NotFound { .. } => None,
    }
}

/// Proves one property; if that fails, looks for a witness that the exact evaluator
/// confirms (and, for a program, the scan simulator too).
pub fn check_property(
    ctx: &Context,
    statement: &Statement<Goal>,
    hypotheses: &[Axiom],
    opts: &Options,
    rename: &dyn Fn(&Expr) -> Expr,
    program: Option<&counterexample::Program>,
) -> PropertyReport {
    let started = Instant::now();
    let goal = obligation(&statement.value);
    let style = trace::Style { notation: opts.notation(), rename };
    let shown = Goal {
        lhs: rename(&statement.value.lhs),
        rhs: rename(&statement.value.rhs),
        ..statement.value.clone()
    };
    let mut report = PropertyReport {
        name: statement.name.clone(),
        location: None,
        statement: syntax::goal_to_string(&shown, opts.notation()),
        status: Status::Unknown,
        reason: None,
        time_ms: 0.0,
        trace: None,
        counterexample: None,
        candidate: None,
        vacuous: false,
        vacuity: None,
    };
    match attempt(ctx, &goal, hypotheses, opts, rename, program) {
        Attempt::Proved(proved) => {
            report.status = Status::Proved;
            report.trace = Some(Box::new(trace_report(&proved, goal.rel, opts, &style)));
        }
        Attempt::Refuted(c) => {
            report.status = Status::Refuted;
            report.counterexample = Some(Box::new(c));
        }
        Attempt::Unknown { reason, candidate } => {
            report.reason = Some(reason);
            report.candidate = candidate.map(Box::new);
        }
    }
    report.time_ms = started.elapsed().as_secs_f64() * 1e3;
    report
}

/// A checked proof as the report shows it.
pub(super) fn trace_report(
    proved: &prover::Proved,
    rel: Rel,
    opts: &Options,
    style: &trace::Style,
) -> TraceReport {
    // Through shared lemmas a theorem may rest on much of the program: the sets
    // are gathered only for a report that shows them.
    let (laws, hypotheses) = match opts.proof_text {
        true => proved.theorem.axioms_used(),
        false => Default::default(),
    };
    TraceReport {
        method: match proved.method {
            prover::Method::Saturation => "saturation".into(),
            prover::Method::CaseSplit => "case-split".into(),
            prover::Method::Induction => "induction".into(),
        },
        lines: if opts.proof_text {
            let detail = if opts.trace_all { trace::Detail::Full } else { trace::Detail::Folded };
            trace::render(proved, rel, style, detail)
        } else {
            Vec::new()
        },
        lemmas: proved.certificate.lemmas.iter().map(|(n, _)| n.clone()).collect(),
        length: trace::length(proved),
        steps: if opts.proof_text {
            trace::atomic_steps(proved, style)
                .into_iter()
                .map(|(rule, kind, term)| StepReport { rule, kind: kind.into(), term })
                .collect()
        } else {
            Vec::new()
        },
        hypotheses: hypotheses.into_iter().collect(),
        laws: laws.into_iter().collect(),
    }
}

/// The share of `--timeout` the proof search may use.
const PROOF_SHARE: f64 = 0.7;
/// The share of `--timeout` the counterexample search still gets when the proof search
/// used all the time there was.
const LAST_LOOK: f64 = 0.03;
/// How long the first look for a counterexample may take, when the prover's quick
/// methods found a model of the Boolean skeleton.
const FIRST_LOOK: Duration = Duration::from_secs(2);
/// How long the counterexample search after a failed proof may take, with a program.
const PROGRAM_SEARCH: Duration = Duration::from_secs(5);
/// The same for free signals (random search, confirmed exactly).
const FREE_SEARCH: Duration = Duration::from_secs(2);
/// Random assignments tried per free-signal search.
const FREE_SAMPLES: usize = 2_000;

/// What a counterexample search found for a goal.
enum Search {
    /// A confirmed counterexample: exact evaluation (and, for a program, the scan
    /// simulator) shows the violation.
    Refuted(CounterexampleReport),
    /// Violates the compiled terms, but the scan simulator does not reproduce it.
    Unconfirmed { candidate: CounterexampleReport, why: String },
    /// Nothing found within the limits, and why; `complete` when the deadline did not
    /// cut the search short.
    NotFound { why: String, complete: bool },
}

/// Looks for a counterexample until `deadline`: bounded model checking over scans
/// for a program, random exact signals for free signals.
fn search_counterexample(
    goal: &Obligation,
    hypotheses: &[Axiom],
    opts: &Options,
    rename: &dyn Fn(&Expr) -> Expr,
    program: Option<&counterexample::Program>,
    deadline: Instant,
) -> Search {
    if let Some(session) = program {
        let limits = Limits {
            deadline,
            max_steps: 200,
            max_scans: 100_000,
            minimised: false,
            signals: true,
        };
        return match counterexample::refute(session, goal, limits) {
            Verdict::Refuted(c) => {
                Search::Refuted(program_counterexample(session, goal, &c, opts, rename))
            }
            Verdict::Unconfirmed { candidate, why } => Search::Unconfirmed {
                candidate: program_counterexample(session, goal, &candidate, opts, rename),
                why,
            },
            Verdict::NotFound { why, complete } => Search::NotFound { why, complete },
        };
    }
    let conditions: Vec<Condition> = hypotheses
        .iter()
        .map(|h| Condition::Signal {
            lhs: h.lhs.clone(),
            rel: theory::sample_relation(h.rel),
            rhs: h.rhs.clone(),
        })
        .collect();
    let rel = theory::sample_relation(goal.rel);
    match falsify::falsify(&goal.lhs, rel, &goal.rhs, &conditions, FREE_SAMPLES, 1, Some(deadline))
    {
        Ok(Err(witness)) if confirmed(goal, &witness, hypotheses) => {
            let witness = simplified(goal, *witness, hypotheses);
            Search::Refuted(counterexample(goal, &witness, opts, rename))
        }
        Ok(Err(_)) => not_found("a sampled witness was not confirmed exactly".into()),
        Ok(Ok(n)) => not_found(format!("no counterexample among {n} random exact signals")),
        Err(falsify::SampleError::TooFewSamples { valid, .. }) => not_found(format!(
            "no counterexample among {valid} random exact signals that satisfy the assumptions"
        )),
        Err(falsify::SampleError::Eval(why)) => not_found(why),
    }
}

/// A free-signal search's result without a counterexample. Sampling with a deadline
/// is never repeated, so it counts as incomplete.
fn not_found(why: String) -> Search {
    Search::NotFound { why, complete: false }
}

/// A program counterexample for people: the inputs that are not always 0, the signals
/// the property reads, its two sides; the violation marked.
pub(super) fn program_counterexample(
    session: &counterexample::Program,
    goal: &Obligation,
    c: &Counterexample,
    opts: &Options,
    rename: &dyn Fn(&Expr) -> Expr,
) -> CounterexampleReport {
    let style = trace::Style { notation: opts.notation(), rename };
    let env = &c.assignment;
    let named = |n: &str| style_term(&style, &crate::term::name(n));
    let mut shown: Vec<(String, crate::semantics::Signal)> = Vec::new();
    for (name, values) in &c.trace.values {
        if values.iter().any(|v| *v)
            && let Some(s) = env.signals.get(&crate::term::Symbol::from(name.as_str()))
        {
            shown.push((named(name), s.clone()));
        }
    }
    let mut read = Vec::new();
    for side in [&goal.lhs, &goal.rhs] {
        for node in side.as_ref() {
            if let crate::term::Term::Name(n) = node
                && !read.contains(n)
            {
                read.push(*n);
            }
        }
    }
    for n in read {
        let label = named(n.as_str());
        if !shown.iter().any(|(l, _)| *l == label)
            && let Some(s) = env.signals.get(&n)
        {
            shown.push((label, s.clone()));
        }
    }
    for (label, side) in [("lhs", &goal.lhs), ("rhs", &goal.rhs)] {
        let is_name = matches!(side[crate::term::root(side)], crate::term::Term::Name(_));
        if !is_name && let Ok(s) = eval(side, env) {
            shown.push((format!("{label}: {}", style_term(&style, side)), s));
        }
    }
    let glyphs = opts.glyphs();
    let mut confirmed_by = vec!["exact evaluation".to_string()];
    if c.simulator_scan.is_some() {
        confirmed_by.push("scan simulator".into());
    }
    // Integers whose bits the run computed: a value row each, and their bits unshown.
    // A timer's elapsed time is drawn as the TIME the run computes (its bits the
    // property does not read added from the run of their cone), not as its count.
    let wanted = IntegerTrack::elapsed_bits(session.compiled, env);
    let completed = match wanted.is_empty() {
        true => None,
        false => session.completed(c, &wanted),
    };
    let tracked = IntegerTrack::all(session.compiled, completed.as_ref().unwrap_or(env), &named);
    shown.retain(|(label, _)| !tracked.iter().any(|t| t.shows_bit(label)));
    CounterexampleReport {
        time: format_time(&c.time),
        lhs: c.lhs,
        rhs: c.rhs,
        signals: match opts.run_signals {
            true => env
                .signals
                .iter()
                .map(|(name, s)| SignalReport::of(named(name.as_str()), s))
                .collect(),
            false => Vec::new(),
        },
        diagram: super::tracks::draw(&shown, &tracked, Some(&c.time), glyphs),
        integers: tracked
            .iter()
            .map(|t| IntegerReport {
                name: t.name.clone(),
                values: (0..c.trace.scans).map(|k| t.value_at(&c.trace.instant(k))).collect(),
                ty: t.ty.time.then_some("TIME"),
            })
            .collect(),
        tracks: tracked,
        scan: Some(c.scan),
        simulator_scan: c.simulator_scan,
        confirmed_by,
        title: None,
        shown,
        mark: Some(c.time.clone()),
    }
}

pub(super) fn style_term(style: &trace::Style, e: &Expr) -> String {
    syntax::term_to_string(&(style.rename)(e), style.notation)
}

/// Re-checks a witness with the exact evaluator: every hypothesis holds, the goal fails.
fn confirmed(goal: &Obligation, witness: &Witness, hypotheses: &[Axiom]) -> bool {
    let env = &witness.assignment;
    let holds = |l: &Expr, rel: Rel, r: &Expr| match (eval(l, env), eval(r, env)) {
        (Ok(a), Ok(b)) => falsify::violation(&a, theory::sample_relation(rel), &b).is_none(),
        _ => false,
    };
    hypotheses.iter().all(|h| holds(&h.lhs, h.rel, &h.rhs))
        && !holds(&goal.lhs, goal.rel, &goal.rhs)
}

/// A simpler confirmed witness: each signal made constant where that keeps the
/// violation and every assumption (re-checked exactly), then the horizon cut a little
/// after the violation.
fn simplified(goal: &Obligation, witness: Witness, hypotheses: &[Axiom]) -> Witness {
    let rewitness = |assignment: crate::semantics::Assignment| -> Option<Witness> {
        let l = eval(&goal.lhs, &assignment).ok()?;
        let r = eval(&goal.rhs, &assignment).ok()?;
        let time = falsify::violation(&l, theory::sample_relation(goal.rel), &r)?;
        let (lhs, rhs) = (l.value_at(&time), r.value_at(&time));
        let w = Witness { assignment, time, lhs, rhs };
        confirmed(goal, &w, hypotheses).then_some(w)
    };
    let mut best = witness;
    let names: Vec<_> = best.assignment.signals.keys().copied().collect();
    for name in names {
        if best.assignment.signals[&name].as_constant().is_some() {
            continue;
        }
        for value in [false, true] {
            let mut assignment = best.assignment.clone();
            let constant = crate::semantics::Signal::constant(assignment.horizon.clone(), value);
            assignment.signals.insert(name, constant);
            if let Some(w) = rewitness(assignment) {
                best = w;
                break;
            }
        }
    }
    // Signals are causal: cutting the horizon after the violation keeps it.
    let cut = &best.time * crate::semantics::Time::new(5.into(), 4.into());
    if cut < best.assignment.horizon {
        let mut assignment = best.assignment.clone();
        for s in assignment.signals.values_mut() {
            *s = s.restrict(&cut);
        }
        assignment.horizon = cut;
        if let Some(w) = rewitness(assignment) {
            best = w;
        }
    }
    best
}

fn counterexample(
    goal: &Obligation,
    witness: &Witness,
    opts: &Options,
    rename: &dyn Fn(&Expr) -> Expr,
) -> CounterexampleReport {
    let env = &witness.assignment;
    let mut shown: Vec<(String, crate::semantics::Signal)> =
        env.signals.iter().map(|(name, s)| (name.to_string(), s.clone())).collect();
    let style = trace::Style { notation: opts.notation(), rename };
    for (label, side) in [("lhs", &goal.lhs), ("rhs", &goal.rhs)] {
        if let Ok(s) = eval(side, env) {
            let text = style_term(&style, side);
            if !shown.iter().any(|(n, _)| *n == text) {
                shown.push((format!("{label}: {text}"), s));
            }
        }
    }
    let glyphs = opts.glyphs();
    CounterexampleReport {
        time: format_time(&witness.time),
        lhs: witness.lhs,
        rhs: witness.rhs,
        signals: env
            .signals
            .iter()
            .map(|(name, s)| SignalReport::of(name.to_string(), s))
            .collect(),
        diagram: waveform::draw(&shown, Some(&witness.time), glyphs),
        integers: Vec::new(),
        tracks: Vec::new(),
        scan: None,
        simulator_scan: None,
        confirmed_by: vec!["exact evaluation".into()],
        title: None,
        mark: Some(witness.time.clone()),
        shown,
    }
}
