//! The judge of a candidate counterexample: its run scan by scan on the property's cone, then its two confirmations — every compiled hypothesis evaluated exactly on the run's signals, and the front end's scan simulator replaying its inputs — and the responsible rung when only the first holds.

use std::collections::{BTreeMap, BTreeSet, HashMap, HashSet};
use std::sync::Mutex;

use super::unroll::{Concrete, Model, unroll, violated};
use super::{Counterexample, Limits, Program, ScanTrace, minimise, names_of, scans_of};
use crate::kernel::Rel;
use crate::ladder::{Hypothesis, HypothesisKind, SignalKind};
use crate::program::simulate::Recording;
use crate::prover::Obligation;
use crate::semantics::falsify::violation;
use crate::semantics::{Assignment, eval, format_time};
use crate::term::{Expr, Symbol, Term, root};
use crate::theory::sample_relation;

/// Per signal name, one value a scan.
type Values = BTreeMap<String, Vec<bool>>;

/// The scan-by-scan run of the equations: every signal, the goal's sides, constraints.
struct Run {
    signals: BTreeMap<String, Vec<bool>>,
    lhs: Vec<bool>,
    rhs: Vec<bool>,
    constraints_hold: bool,
}

/// What a candidate judged on part of its property's cone reads from outside that part:
/// a *base* run (of the part of the program it covers), on which every compiled
/// hypothesis about its signals was checked exactly once ([`base_holds`]). The part
/// holds every equation of the cone that reads, through any chain, an input of
/// `changed`; every other name the part reads that the program defines has its value in
/// the base run. A candidate whose inputs differ from the base run's in any other input
/// is not judged on it.
pub(super) struct Background<'a> {
    /// A defined name's value at a scan of the base run.
    pub base: &'a (dyn Fn(&str, usize) -> Option<bool> + Sync),
    /// The base run's inputs.
    pub inputs: &'a ScanTrace,
    /// The inputs the part was taken for.
    pub changed: &'a BTreeSet<String>,
    /// The front end's record of the base run, for its simulator.
    pub record: Option<&'a Recording>,
}

impl Background<'_> {
    /// The inputs whose values in `trace` differ from the base run's at a scan of
    /// `trace`; `None` for a trace longer than the base run or on another cycle.
    fn changed_in(&self, trace: &ScanTrace) -> Option<BTreeSet<String>> {
        if trace.scans > self.inputs.scans || trace.cycle != self.inputs.cycle {
            return None;
        }
        Some(changed_inputs(trace, self.inputs))
    }
}

/// The inputs whose values in `trace` differ from those in `base` at a scan of `trace`
/// (an input a trace does not give is 0): the two maps walked together, in order.
pub(super) fn changed_inputs(trace: &ScanTrace, base: &ScanTrace) -> BTreeSet<String> {
    let scans = trace.scans;
    let differ = |a: Option<&Vec<bool>>, b: Option<&Vec<bool>>| match (a, b) {
        (Some(a), Some(b)) if a.len() >= scans && b.len() >= scans => a[..scans] != b[..scans],
        _ => (0..scans).any(|k| {
            a.and_then(|v| v.get(k)).copied().unwrap_or(false)
                != b.and_then(|v| v.get(k)).copied().unwrap_or(false)
        }),
    };
    let (mut a, mut b) = (trace.values.iter().peekable(), base.values.iter().peekable());
    let mut changed = BTreeSet::new();
    loop {
        let (name, x, y) = match (a.peek(), b.peek()) {
            (None, None) => return changed,
            (Some((n, _)), None) => (*n, a.next().map(|p| p.1), None),
            (None, Some((n, _))) => (*n, None, b.next().map(|p| p.1)),
            (Some((n, _)), Some((m, _))) => match n.cmp(m) {
                std::cmp::Ordering::Less => (*n, a.next().map(|p| p.1), None),
                std::cmp::Ordering::Greater => (*m, None, b.next().map(|p| p.1)),
                std::cmp::Ordering::Equal => (*n, a.next().map(|p| p.1), b.next().map(|p| p.1)),
            },
        };
        if differ(x, y) {
            changed.insert(name.clone());
        }
    }
}

fn run_scans(
    model: &Model,
    goal: &Obligation,
    trace: &ScanTrace,
    background: Option<&Background>,
) -> Result<Run, String> {
    let cycle = trace.cycle.clone();
    let u = unroll(
        &mut Concrete,
        model,
        &[&goal.lhs, &goal.rhs],
        trace.scans,
        &|d| scans_of(d, &cycle),
        &mut |_, name, k| match trace.values.get(name) {
            Some(v) => v.get(k).copied().unwrap_or(false),
            None => background.and_then(|b| (b.base)(name, k)).unwrap_or(false),
        },
    )?;
    let constraints_hold = model
        .constraints
        .iter()
        .zip(&u.constraints)
        .all(|(c, (l, r))| l.iter().zip(r).all(|(a, b)| !violated(&mut Concrete, c.1, a, b)));
    let mut it = u.extra.into_iter();
    let lhs = it.next().unwrap_or_default();
    let rhs = it.next().unwrap_or_default();
    Ok(Run { signals: u.signals, lhs, rhs, constraints_hold })
}

fn first_violation(goal: &Obligation, run: &Run) -> Option<usize> {
    (0..run.lhs.len()).find(|&k| violated(&mut Concrete, goal.rel, &run.lhs[k], &run.rhs[k]))
}

/// The scan simulator's run on the trace: the first violating scan (0-based), and per
/// scan the value of every defined signal of the model.
fn simulate(
    program: &Program,
    model: &Model,
    goal: &Obligation,
    trace: &ScanTrace,
    background: Option<&Background>,
) -> Result<(Option<usize>, Values), String> {
    let mut read = BTreeSet::new();
    names_of(&goal.lhs, &mut read);
    names_of(&goal.rhs, &mut read);
    for (l, _, r) in &model.constraints {
        names_of(l, &mut read);
        names_of(r, &mut read);
    }
    let mut watched: BTreeSet<String> = model.defs.iter().map(|(n, _)| n.clone()).collect();
    for n in &read {
        match program.compiled.signals.get(n) {
            Some(k) if k.is_unconstrained() => {
                return Err(format!(
                    "the property reads `{n}`, which the simulator does not compute"
                ));
            }
            _ => {
                watched.insert(n.clone());
            }
        }
    }
    // The simulator may run only the rungs that can write what is watched, and of
    // those, for a candidate judged on part of its cone, only those the inputs it
    // changes can change (the front end replays the others from its record of the
    // base run).
    let near = background.and_then(|b| {
        let record = b.record?;
        program.reference.simulator_near(&watched, record, b.changed, trace.scans)
    });
    let part = near.is_some();
    let mut sim = near.unwrap_or_else(|| program.reference.simulator_for(&watched));
    // Every input at every scan (0 where the trace has none), the map built once; an
    // input held at 0 that the run never reads (outside its part of the program) is
    // left out, so that a scan costs what the part costs.
    // The program's inputs (an integer input by its bits) that the trace sets, that are
    // watched or that the simulator reads, and free names of the `.ii` files the program
    // does not know; a simulator of a slice says what it reads, so that finding them
    // costs the slice, not the program.
    let signals = &program.compiled.signals;
    let read = sim.read_names();
    let mut candidates: BTreeSet<&str> = trace.values.keys().map(String::as_str).collect();
    candidates.extend(watched.iter().map(String::as_str));
    match &read {
        Some(names) => candidates.extend(names.iter().copied()),
        None => {
            candidates.extend(signals.iter().filter(|(_, k)| k.is_input()).map(|(n, _)| n.as_str()))
        }
    }
    // (A simulator of a part near a base run, whose programs have no integer inputs, is
    // not given the trace's inputs it never reads.)
    let given = |n: &str| trace.values.contains_key(n) && (!part || sim.reads(n));
    let mut step: BTreeMap<String, bool> = candidates
        .into_iter()
        .filter(|n| match signals.get(*n) {
            Some(k) => k.is_input() && (given(n) || watched.contains(*n) || sim.reads(n)),
            None => trace.values.contains_key(*n),
        })
        .map(|n| (n.to_string(), false))
        .collect();
    drop(read);
    // Each watched name's kind, looked up once rather than at every scan.
    let kinds: Vec<(&String, Option<&SignalKind>)> =
        watched.iter().map(|n| (n, program.compiled.signals.get(n))).collect();
    let mut values: Vec<Vec<bool>> = vec![Vec::with_capacity(trace.scans); kinds.len()];
    for k in 0..trace.scans {
        for (n, x) in step.iter_mut() {
            *x = trace.values.get(n).and_then(|v| v.get(k)).copied().unwrap_or(false);
        }
        sim.step(&step);
        for ((n, kind), seen) in kinds.iter().zip(values.iter_mut()) {
            // Compiler-made names (atoms, intermediate values) stand for what they read.
            let depends = match kind {
                Some(SignalKind::IntBit { of, .. }) => Some(of),
                // (A one-shot's memory is the simulator's memory of its element, below.)
                Some(
                    SignalKind::Atom
                    | SignalKind::Intermediate { .. }
                    | SignalKind::HeldInput { .. }
                    | SignalKind::EdgeMemory { .. },
                ) => None,
                _ => Some(*n),
            };
            if depends.is_some_and(|d| !sim.is_known(d)) {
                return Err(format!("the simulator does not model what `{n}` depends on"));
            }
            // A one-shot's hidden memory is the simulator's memory of that element, never
            // a bit of the same name (the PLC has none).
            let value = match kind {
                Some(SignalKind::EdgeMemory { index, .. }) => {
                    sim.edge_memory(*index).ok_or_else(|| {
                        format!("the simulator does not show the memory `{n}` of its one-shot")
                    })?
                }
                // A bit of an integer: of its value xor its start value.
                Some(SignalKind::IntBit { of, bit, start, .. }) => {
                    let v = sim
                        .int(of)
                        .ok_or_else(|| format!("the simulator does not show the integer `{of}`"))?;
                    (v >> bit & 1 == 1) != *start
                }
                // Named parts of a computation: what they stand for is checked where read.
                Some(SignalKind::Atom) => {
                    let int = |x: &str| sim.int(x);
                    program.compiled.atom_value(n, &int).ok_or_else(|| {
                        format!("the simulator does not show the integers of `{n}`")
                    })?
                }
                // A held timer input is checked through the timer's output it decides.
                Some(SignalKind::Intermediate { .. } | SignalKind::HeldInput { .. }) => continue,
                _ => sim.bit(n),
            };
            seen.push(value);
        }
    }
    let seen: BTreeMap<String, Vec<bool>> = kinds
        .into_iter()
        .zip(values)
        .filter(|((_, kind), _)| {
            !matches!(kind, Some(SignalKind::Intermediate { .. } | SignalKind::HeldInput { .. }))
        })
        .map(|((n, _), v)| (n.clone(), v))
        .collect();
    // The property (and the assumptions) on the simulator's values.
    let cycle = trace.cycle.clone();
    let u = unroll(
        &mut Concrete,
        &Model { defs: Vec::new(), constraints: model.constraints.clone() },
        &[&goal.lhs, &goal.rhs],
        trace.scans,
        &|d| scans_of(d, &cycle),
        &mut |_, name, k| {
            if let Some(v) = seen.get(name) {
                return v.get(k).copied().unwrap_or(false);
            }
            trace.values.get(name).and_then(|v| v.get(k)).copied().unwrap_or(false)
        },
    )?;
    Ok((u.first_violation(model, goal.rel), seen))
}

/// Exact confirmation: every hypothesis of the cone holds on the whole horizon (with
/// `pre f` as `f` one cycle earlier), the goal fails at scan `v`.
fn exact(
    program: &Program,
    model: &Model,
    goal: &Obligation,
    trace: &ScanTrace,
    run: &Run,
    v: usize,
) -> Result<(Assignment, bool, bool), String> {
    // Every signal as the run computed it, scan by scan; then each equation must hold
    // exactly at every scan (a read one scan back, `pre`, makes the order of the
    // equations no guide).
    let env = environment(&run.signals, trace)?;
    let instants = trace.instants();
    let memo = Memo::of(program, &run.signals, trace.scans);
    for (name, rhs) in &model.defs {
        let key = memo.as_ref().and_then(|m| m.equation(name, rhs));
        if key.as_ref().is_some_and(|k| k.passed()) {
            continue;
        }
        let s = eval(rhs, &env).map_err(|e| e.to_string())?;
        let x = env.signals.get(&Symbol::from(name.as_str())).ok_or("a signal is missing")?;
        if let Some(k) = instants.iter().position(|t| x.value_at(t) != s.value_at(t)) {
            return Err(format!("the equation of `{name}` fails at scan {}", k + 1));
        }
        if let Some(k) = key {
            k.pass();
        }
    }
    for (l, rel, r) in &model.constraints {
        let (a, b) =
            (eval(l, &env).map_err(|e| e.to_string())?, eval(r, &env).map_err(|e| e.to_string())?);
        if let Some(t) = violation(&a, sample_relation(*rel), &b) {
            return Err(format!("an assumption fails at t = {}", format_time(&t)));
        }
    }
    let l = eval(&goal.lhs, &env).map_err(|e| e.to_string())?;
    let r = eval(&goal.rhs, &env).map_err(|e| e.to_string())?;
    let t = trace.instant(v);
    let (a, b) = (l.value_at(&t), r.value_at(&t));
    if !violated(&mut Concrete, goal.rel, &a, &b) {
        return Err("the exact evaluation does not show the violation".into());
    }
    Ok((env, a, b))
}

/// Checks a compiled hypothesis set on the exact signals (every equation and bound).
/// Every compiled hypothesis whose signals the run has holds at every scan of the trace
/// (read at each scan's instant: the end of the horizon is the start of a scan the trace
/// does not have).
/// The equations of `checked` (the model's, which [`exact`] has checked on the same
/// instants) are not evaluated again.
fn hypotheses_hold(
    program: &Program,
    checked: &Model,
    env: &Assignment,
    trace: &ScanTrace,
    signals: &Values,
) -> bool {
    let mut done: HashMap<&str, Vec<&Expr>> = HashMap::new();
    for (n, rhs) in &checked.defs {
        done.entry(n.as_str()).or_default().push(rhs);
    }
    let is_done = |h: &Hypothesis| {
        h.kind == HypothesisKind::Equation
            && h.rel == Rel::Eq
            && matches!(&h.lhs[root(&h.lhs)], Term::Name(n)
                if done.get(n.as_str()).is_some_and(|es| es.iter().any(|e| **e == h.rhs)))
    };
    // Only a hypothesis that mentions no name or a name of the run can have all its
    // names in the run: those are looked up, not the whole program's.
    let index = program.compiled.equation_index();
    let mut candidates: Vec<usize> = index.nameless.clone();
    for n in env.signals.keys() {
        candidates.extend(index.mentioning.get(n).map_or(&[][..], Vec::as_slice));
    }
    candidates.sort_unstable();
    candidates.dedup();
    let instants = trace.instants();
    let memo = Memo::of(program, signals, trace.scans);
    candidates.into_iter().filter(|&i| !is_done(&program.compiled.hypotheses[i])).all(|i| {
        let h = &program.compiled.hypotheses[i];
        let known = |e: &Expr| {
            e.as_ref().iter().all(|node| match node {
                Term::Name(n) => env.signals.contains_key(n),
                _ => true,
            })
        };
        if !known(&h.lhs) || !known(&h.rhs) {
            return true; // outside the cone
        }
        let key = memo.as_ref().and_then(|m| m.hypothesis(i));
        if key.as_ref().is_some_and(|k| k.passed()) {
            return true;
        }
        let (Ok(a), Ok(b)) = (eval(&h.lhs, env), eval(&h.rhs, env)) else { return false };
        let holds = instants
            .iter()
            .all(|t| !violated(&mut Concrete, h.rel, &a.value_at(t), &b.value_at(t)));
        if let (true, Some(k)) = (holds, key) {
            k.pass();
        }
        holds
    })
}

pub(super) enum Judged {
    Both(Box<Counterexample>),
    ExactOnly(Box<Counterexample>, String),
}

/// Checks (discretely) that a trace still violates the goal; the first violating scan.
pub(super) fn discrete_violation(
    model: &Model,
    goal: &Obligation,
    trace: &ScanTrace,
) -> Option<usize> {
    violating_run(model, goal, trace, None).map(|(v, _)| v)
}

/// [`discrete_violation`] on part of the cone, what it reads from outside taken from
/// `background`.
pub(super) fn discrete_violation_near(
    model: &Model,
    goal: &Obligation,
    trace: &ScanTrace,
    background: &Background,
) -> Option<usize> {
    violating_run(model, goal, trace, Some(background)).map(|(v, _)| v)
}

/// [`discrete_violation`] with the run: its first violating scan, and the run cut after
/// it (a scan's values depend only on the scans before, so the cut run is the run of
/// the cut trace).
fn violating_run(
    model: &Model,
    goal: &Obligation,
    trace: &ScanTrace,
    background: Option<&Background>,
) -> Option<(usize, Run)> {
    let mut run = run_scans(model, goal, trace, background).ok()?;
    if !run.constraints_hold {
        return None;
    }
    let v = first_violation(goal, &run)?;
    for values in run.signals.values_mut().chain([&mut run.lhs, &mut run.rhs]) {
        values.truncate(v + 1);
    }
    Some((v, run))
}

pub(super) fn judge(
    program: &Program,
    model: &Model,
    goal: &Obligation,
    mut trace: ScanTrace,
    limits: Limits,
) -> Result<Judged, String> {
    let (v, run) = violating_run(model, goal, &trace, None).ok_or("no violation scan by scan")?;
    trace.truncate(v + 1);
    if limits.minimised {
        let simulated = simulate(program, model, goal, &trace, None);
        return confirmed(program, model, goal, (trace, run, v), simulated);
    }
    // The simulator runs the whole program: the trace is minimised on the cone's
    // equations, and the simulator asked about the result. Only when it shows the
    // violation on the candidate but not on the minimised trace is the minimisation
    // redone with the simulator asked at each step (as it keeps both).
    let sim_ok =
        |t: &ScanTrace| matches!(simulate(program, model, goal, t, None), Ok((Some(_), _)));
    let original = trace.clone();
    let discrete = |t: &ScanTrace| discrete_violation(model, goal, t).is_some();
    minimise(&mut trace, &discrete, limits);
    let (mut v, mut run) = violating_run(model, goal, &trace, None).ok_or("lost the violation")?;
    trace.truncate(v + 1);
    let mut simulated = simulate(program, model, goal, &trace, None);
    if !matches!(simulated, Ok((Some(_), _))) && sim_ok(&original) {
        trace = original;
        let keep = |t: &ScanTrace| discrete(t) && sim_ok(t);
        minimise(&mut trace, &keep, limits);
        (v, run) = violating_run(model, goal, &trace, None).ok_or("lost the violation")?;
        trace.truncate(v + 1);
        simulated = simulate(program, model, goal, &trace, None);
    }
    confirmed(program, model, goal, (trace, run, v), simulated)
}

/// [`judge`] of a candidate already minimised, on part of its property's cone `full`:
/// the equations `part` keeps, what they read from outside taken from `background`, and
/// the simulator asked for the same part. Fails when the trace changes an input outside
/// `background.changed`. Once both confirmations hold, the counterexample's signals are
/// completed with the inputs it sets and, with `all`, every signal of the whole cone,
/// the values of those outside the part taken from the base run.
pub(super) fn judge_near(
    program: &Program,
    (full, part): (&Model, &Model),
    goal: &Obligation,
    (mut trace, all): (ScanTrace, bool),
    background: &Background,
) -> Result<Judged, String> {
    let changed = background.changed_in(&trace).ok_or("the trace is not one of the base run")?;
    if let Some(n) = changed.iter().find(|n| !background.changed.contains(*n)) {
        return Err(format!("the input `{n}` changes outside the part judged"));
    }
    let (v, run) =
        violating_run(part, goal, &trace, Some(background)).ok_or("no violation scan by scan")?;
    trace.truncate(v + 1);
    let simulated = simulate(program, part, goal, &trace, Some(background));
    let mut judged = confirmed(program, part, goal, (trace, run, v), simulated)?;
    let (Judged::Both(c) | Judged::ExactOnly(c, _)) = &mut judged;
    let mut names: BTreeSet<String> =
        c.trace.values.iter().filter(|(_, v)| v.contains(&true)).map(|(n, _)| n.clone()).collect();
    if all {
        names.extend(full.defs.iter().map(|(n, _)| n.clone()));
        names.extend(full.free_names([&goal.lhs, &goal.rhs].into_iter()));
    }
    names.retain(|n| !c.assignment.signals.contains_key(&Symbol::from(n.as_str())));
    // A defined name the base run does not give (outside the cone it covers, and not
    // read by the part) takes its value from a run of the whole cone.
    let defined = &program.compiled.equation_index().defining;
    let outside =
        names.iter().any(|n| defined.contains_key(n) && (background.base)(n, 0).is_none());
    let whole = match outside {
        true => Some(run_scans(full, goal, &c.trace, None)?.signals),
        false => None,
    };
    for n in names {
        let values: Vec<bool> = (0..c.trace.scans)
            .map(|k| match (c.trace.values.get(&n), whole.as_ref().and_then(|w| w.get(&n))) {
                (Some(v), _) | (None, Some(v)) => v.get(k).copied().unwrap_or(false),
                (None, None) => (background.base)(&n, k).unwrap_or(false),
            })
            .collect();
        c.assignment.signals.insert(Symbol::from(n.as_str()), c.trace.signal(&values)?);
    }
    Ok(judged)
}

/// Whether every compiled hypothesis whose names `signals` all give holds exactly on
/// them, a run (every signal of part of the program, scan by scan) on the inputs of
/// `trace`: the check that lets a [`Background`] take values from that run.
pub(super) fn base_holds(program: &Program, signals: &Values, trace: &ScanTrace) -> bool {
    let Ok(env) = environment(signals, trace) else { return false };
    let none = Model { defs: Vec::new(), constraints: Vec::new() };
    hypotheses_hold(program, &none, &env, trace, signals)
}

/// The exact signals of a run's values, scan by scan, on the trace's cycle and horizon.
fn environment(signals: &Values, trace: &ScanTrace) -> Result<Assignment, String> {
    let mut env = Assignment::new(trace.horizon());
    env.cycle = Some(trace.cycle.clone());
    for (name, values) in signals {
        env.signals.insert(Symbol::from(name.as_str()), trace.signal(values)?);
    }
    Ok(env)
}

/// The two confirmations of a trace that violates the goal at scan `v` (0-based),
/// given the scan simulator's run on it.
fn confirmed(
    program: &Program,
    model: &Model,
    goal: &Obligation,
    (trace, run, v): (ScanTrace, Run, usize),
    simulated: Result<(Option<usize>, Values), String>,
) -> Result<Judged, String> {
    let (assignment, lhs, rhs) = exact(program, model, goal, &trace, &run, v)?;
    if !hypotheses_hold(program, model, &assignment, &trace, &run.signals) {
        return Err("a compiled hypothesis fails on the exact signals".into());
    }
    let mut cex = Counterexample {
        time: trace.instant(v),
        scan: v + 1,
        lhs,
        rhs,
        simulator_scan: None,
        assignment,
        trace,
    };
    match simulated {
        Ok((Some(s), _)) => {
            cex.simulator_scan = Some(s + 1);
            Ok(Judged::Both(Box::new(cex)))
        }
        Ok((None, seen)) => {
            let why = responsible(program, &run, &seen, &cex.trace);
            Ok(Judged::ExactOnly(Box::new(cex), why))
        }
        Err(e) => {
            Ok(Judged::ExactOnly(Box::new(cex), format!("the scan simulator cannot check it: {e}")))
        }
    }
}

/// The first signal (scan, then program order) on which the equations and the PLC part,
/// and the rung that computes it.
fn responsible(
    program: &Program,
    run: &Run,
    seen: &BTreeMap<String, Vec<bool>>,
    trace: &ScanTrace,
) -> String {
    for k in 0..trace.scans {
        for h in &program.compiled.hypotheses {
            let Term::Name(n) = &h.lhs[root(&h.lhs)] else { continue };
            if h.kind != HypothesisKind::Equation {
                continue;
            }
            let (Some(a), Some(b)) = (run.signals.get(n.as_str()), seen.get(n.as_str())) else {
                continue;
            };
            if a.get(k) != b.get(k) {
                let mut names = BTreeSet::new();
                names_of(&h.rhs, &mut names);
                let loose: Vec<String> = names
                    .iter()
                    .filter(|m| {
                        program.compiled.signals.get(*m).is_some_and(|s| s.is_unconstrained())
                    })
                    .cloned()
                    .collect();
                let reads = if loose.is_empty() {
                    String::new()
                } else {
                    format!("; its equation reads the unconstrained {}", loose.join(", "))
                };
                return format!(
                    "the scan simulator does not reproduce it: at scan {} `{n}` is {} by the equations but {} in the PLC — rung {} ({}) is responsible{reads}",
                    k + 1,
                    a.get(k).copied().unwrap_or(false) as u8,
                    b.get(k).copied().unwrap_or(false) as u8,
                    h.rung,
                    h.name
                );
            }
        }
    }
    let fresh: Vec<String> = program
        .compiled
        .signals
        .iter()
        .filter_map(|(n, k)| match k {
            SignalKind::Fresh { rung, element, .. } if trace.values.contains_key(n) => {
                Some(format!("`{n}` ({element}, rung {rung})"))
            }
            _ => None,
        })
        .collect();
    if fresh.is_empty() {
        "the scan simulator does not reproduce it (timer quantisation: the PLC's timers count scans)".into()
    } else {
        format!(
            "the scan simulator does not reproduce it: it depends on the unconstrained {}",
            fresh.join(", ")
        )
    }
}

/// The exact checks this session has passed: a compiled hypothesis (by index) with the
/// scan values of every name it mentions, which alone decide it (the signals are built
/// from those values on the program's cycle). Kept in [`Shared`](super::shared::Shared):
/// the properties of a program whose cones overlap check the same equations on the same
/// values, each once.
#[derive(Default)]
pub(super) struct ExactMemo(Mutex<HashSet<(usize, Box<[u64]>)>>);

/// The memo's view of one run.
struct Memo<'a> {
    program: &'a Program<'a>,
    memo: &'a ExactMemo,
    values: &'a BTreeMap<String, Vec<bool>>,
    scans: usize,
}

/// A hypothesis on a run's values: what the memo is asked and told.
struct Key<'a> {
    memo: &'a ExactMemo,
    key: (usize, Box<[u64]>),
}

impl<'a> Memo<'a> {
    fn of(
        program: &'a Program<'a>,
        values: &'a BTreeMap<String, Vec<bool>>,
        scans: usize,
    ) -> Option<Memo<'a>> {
        Some(Memo { program, memo: &program.shared?.exact, values, scans })
    }

    /// The key of the program's equation `name = rhs`.
    fn equation(&self, name: &str, rhs: &Expr) -> Option<Key<'a>> {
        let index = self.program.compiled.equation_index();
        let hypotheses = &self.program.compiled.hypotheses;
        let h = index.defining.get(name)?.iter().map(|&p| index.equations[p].1).find(|&h| {
            let hyp = &hypotheses[h];
            hyp.rhs == *rhs
                && matches!(&hyp.lhs[root(&hyp.lhs)], Term::Name(n) if n.as_str() == name)
        })?;
        self.hypothesis(h)
    }

    /// The key of hypothesis `h`: the scans, then per name it mentions (in the order
    /// its terms mention them) how many values the run has and those values, 64 a word.
    fn hypothesis(&self, h: usize) -> Option<Key<'a>> {
        let hyp = &self.program.compiled.hypotheses[h];
        let mut words = vec![self.scans as u64];
        let mut seen: Vec<Symbol> = Vec::new();
        for node in hyp.lhs.as_ref().iter().chain(hyp.rhs.as_ref()) {
            if let Term::Name(n) = node
                && !seen.contains(n)
            {
                seen.push(*n);
                let v = self.values.get(n.as_str())?;
                let v = &v[..v.len().min(self.scans)];
                words.push(v.len() as u64);
                words.extend(v.chunks(64).map(|c| {
                    c.iter().enumerate().fold(0u64, |m, (k, b)| m | (u64::from(*b) << k))
                }));
            }
        }
        Some(Key { memo: self.memo, key: (h, words.into()) })
    }
}

impl Key<'_> {
    fn passed(&self) -> bool {
        self.memo.0.lock().is_ok_and(|m| m.contains(&self.key))
    }

    fn pass(self) {
        if let Ok(mut m) = self.memo.0.lock() {
            m.insert(self.key);
        }
    }
}
