//! Counterexamples for ladder programs: bounded model checking over scans, confirmed by exact evaluation and by the scan simulator.
//!
//! # Method
//!
//! The property's cone of influence (the equations of every signal it reads, closed
//! under `pre X → X`, with every `assume` statement and its cone) is unrolled over
//! *steps* ([`unroll`](mod@unroll)) and handed to a SAT solver (varisat), for 1, 2, … steps up
//! to a bound (3× the longest timer plus 4 steps), asking for a violation at the last
//! step. Inputs (and the outputs of elements the algebra cannot express) are free at
//! each step, `pre X` is `X` at the previous step, timers count steps.
//!
//! A step is `m` scans, where `m` is the greatest common divisor of every timer's
//! delay in scans (one scan when there are no timers): inputs change only at step
//! boundaries. This coarse grid is an abstraction (within a step the scans may
//! differ); nothing found on it is trusted. If it finds nothing, one scan per step is
//! tried as well when the timers are short enough.
//!
//! # Confirmation
//!
//! A candidate is expanded to one value per scan (scan `k` is the time `[(k−1)·c, k·c)`
//! for the cycle `c`, the first scan `(0, c)`) and re-run scan by scan; the horizon is
//! cut at the first violating scan. It is then **confirmed twice**:
//!
//! 1. *exactly*: the inputs become exact [`Signal`]s with breakpoints at scan
//!    boundaries, every compiled signal is computed from its equation with
//!    [`semantics::eval`](fn@crate::semantics::eval), every hypothesis of the cone
//!    (equations, recurrences, assumptions) is checked at every scan instant, with
//!    every signal taken from the run and `pre X` as `X` one cycle earlier, and the
//!    property must fail at the violating scan's instant;
//! 2. *by the scan simulator* ([`Simulator`]): the same inputs, one `step` per scan,
//!    and the property (its timers read per scan) must fail at some scan.
//!
//! Only then is the result a [`Verdict::Refuted`]. A candidate that passes the first
//! check only is a [`Verdict::Unconfirmed`], with the rung whose abstraction is
//! responsible (the first signal on which the equations and the PLC part).
//!
//! Timer quantisation: the search times a `d` timer as the algebra does (`d/f` turns
//! on at the `(N+1)`-th scan, `N = d / c`); an LDmicro 0.1 timer (`P = N − 1`) fires one
//! scan earlier in the simulator. The simulator only has to show *some* violating
//! scan, so this one-scan difference is tolerated, never hidden.
#![warn(missing_docs)]

pub mod aiger;
mod complete;
mod cone;
mod confirm;
pub mod shared;
pub mod unroll;

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::sync::Mutex;
use std::time::Instant;

use num_integer::Integer;
use num_traits::ToPrimitive;

use crate::kernel::{Axiom, Rel};
use crate::ladder::{CompiledProgram, Reference};
use crate::prover::Obligation;
use crate::semantics::{Assignment, Signal, Time, format_time};
use crate::term::{Delay, Expr, Term};
use confirm::{Judged, discrete_violation, judge};
use unroll::{Bits, Cnf, Model, unroll, violated};

/// Limits of one search.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// Give up after this instant.
    pub deadline: Instant,
    /// At most this many steps on a grid.
    pub max_steps: usize,
    /// At most this many scans in a candidate.
    pub max_scans: usize,
    /// Candidates are confirmed as they are, not minimised first (a run already
    /// minimised for another property).
    pub minimised: bool,
    /// A counterexample's assignment holds every signal of the property's cone; else
    /// it may hold only the inputs it sets and what the property reads (what a timing
    /// diagram shows).
    pub signals: bool,
}

/// Input values scan by scan.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ScanTrace {
    /// The scan cycle, in seconds.
    pub cycle: Time,
    /// Number of scans.
    pub scans: usize,
    /// Per free name (inputs and unconstrained element outputs): one value a scan.
    pub values: BTreeMap<String, Vec<bool>>,
}

impl ScanTrace {
    /// The instant that stands for scan `k` (0-based): `k·c`, or `c/2` for the first.
    pub fn instant(&self, k: usize) -> Time {
        if k == 0 {
            &self.cycle / Time::from_integer(2.into())
        } else {
            &self.cycle * Time::from_integer(k.into())
        }
    }

    /// The instants of every scan, [`ScanTrace::instant`] for `k` in `0..scans`.
    pub fn instants(&self) -> Vec<Time> {
        (0..self.scans).map(|k| self.instant(k)).collect()
    }

    /// The horizon `scans · c`.
    pub fn horizon(&self) -> Time {
        &self.cycle * Time::from_integer(self.scans.into())
    }

    /// Per-scan values as an exact signal, constant on each `[k·c, (k+1)·c)`.
    pub fn signal(&self, values: &[bool]) -> Result<Signal, String> {
        let first = values.first().copied().unwrap_or(false);
        let mut changes = Vec::new();
        for k in 1..self.scans.min(values.len()) {
            if values[k] != values[k - 1] {
                changes.push((&self.cycle * Time::from_integer(k.into()), values[k]));
            }
        }
        Signal::from_steps(self.horizon(), first, &changes)
    }

    /// The trace of the inputs of `names` only: walked from the smaller side (a run kept
    /// for a whole plant may set thousands of inputs, a property's cone read a few).
    fn restricted(&self, names: &BTreeSet<String>) -> ScanTrace {
        let values = if names.len() < self.values.len() {
            names.iter().filter_map(|n| Some((n.clone(), self.values.get(n)?.clone()))).collect()
        } else {
            self.values
                .iter()
                .filter(|(n, _)| names.contains(*n))
                .map(|(n, v)| (n.clone(), v.clone()))
                .collect()
        };
        ScanTrace { cycle: self.cycle.clone(), scans: self.scans, values }
    }

    fn truncate(&mut self, scans: usize) {
        self.scans = scans.min(self.scans);
        for v in self.values.values_mut() {
            v.truncate(self.scans);
        }
    }

    fn changes(&self) -> usize {
        self.values.values().map(|v| v.windows(2).filter(|w| w[0] != w[1]).count()).sum()
    }
}

/// A counterexample with the evidence that confirms it.
#[derive(Clone, Debug)]
pub struct Counterexample {
    /// The inputs, scan by scan.
    pub trace: ScanTrace,
    /// Every signal of the cone, exactly (inputs, previous values, computed signals).
    pub assignment: Assignment,
    /// The instant where the property fails (the violating scan's instant).
    pub time: Time,
    /// The violating scan (1-based) in the exact evaluation.
    pub scan: usize,
    /// The left side's value there.
    pub lhs: bool,
    /// The right side's value there.
    pub rhs: bool,
    /// The first scan (1-based) where the scan simulator violates the property.
    pub simulator_scan: Option<usize>,
}

/// The end of a search.
#[derive(Clone, Debug)]
pub enum Verdict {
    /// Confirmed by exact evaluation and by the scan simulator.
    Refuted(Box<Counterexample>),
    /// Confirmed exactly, but the simulator does not reproduce it; `why` names the rung.
    Unconfirmed {
        /// The candidate.
        candidate: Box<Counterexample>,
        /// Which rung's abstraction is responsible, and how.
        why: String,
    },
    /// Nothing found: why, and whether every run the search meant to try was tried
    /// (`false` when the deadline cut it short).
    NotFound {
        /// What was searched.
        why: String,
        /// Every planned run was checked.
        complete: bool,
    },
}

/// The program a property is about.
pub struct Program<'a> {
    /// The program as its front end read it: candidates are confirmed on its simulator.
    pub reference: &'a dyn Reference,
    /// Its compiled equations.
    pub compiled: &'a CompiledProgram,
    /// The `assume` statements.
    pub assumptions: &'a [Axiom],
    /// Where the confirmed counterexamples of the run's properties are kept for the
    /// others ([`shared::refute_shared`]); `None` keeps none.
    pub shared: Option<&'a shared::Shared>,
}

fn names_of(e: &Expr, into: &mut BTreeSet<String>) {
    for node in e.as_ref() {
        if let Term::Name(n) = node {
            into.insert(n.as_str().to_string());
        }
    }
}

/// The program's equations at `positions` (in scan order, `EquationIndex::equations`)
/// as a model without constraints.
pub fn equations_model(
    compiled: &CompiledProgram,
    positions: impl IntoIterator<Item = usize>,
) -> Model {
    let index = compiled.equation_index();
    let defs = positions
        .into_iter()
        .map(|p| {
            let (n, h) = &index.equations[p];
            (n.clone(), compiled.hypotheses[*h].rhs.clone())
        })
        .collect();
    Model { defs, constraints: Vec::new() }
}

/// Every equation `X = term` of the program in scan order (what a scan computes), as a
/// model without constraints.
pub fn program_model(compiled: &CompiledProgram) -> Model {
    equations_model(compiled, 0..compiled.equation_index().equations.len())
}

impl Program<'_> {
    fn cycle(&self) -> Option<Time> {
        (self.compiled.cycle_us > 0)
            .then(|| Time::new(self.compiled.cycle_us.into(), 1_000_000u64.into()))
    }
}

/// The delay of `d` in units of `unit`, if it is a whole number of them.
fn whole(d: &Delay, unit: &Time) -> Option<usize> {
    let q = d.seconds() / unit;
    q.is_integer().then(|| q.to_integer().to_usize()).flatten()
}

/// A timer's delay in scans: `d / c` rounded up. Each scan is read at its start, so
/// `d/f` is on from the (⌈d/c⌉+1)-th consecutive scan of `f` and `f/d` stays on ⌈d/c⌉
/// scans after `f` falls (the same count for delays that are whole scans).
pub fn scans_of(d: &Delay, cycle: &Time) -> Option<usize> {
    (d.seconds() / cycle).ceil().to_integer().to_usize()
}

/// Looks for a counterexample of `goal` on `program`, confirmed twice.
pub fn refute(program: &Program, goal: &Obligation, limits: Limits) -> Verdict {
    let Some(cycle) = program.cycle() else {
        return Verdict::NotFound {
            why: "the program has a zero cycle time".into(),
            complete: true,
        };
    };
    let model = program.model(&[&goal.lhs, &goal.rhs]);
    let delays = model.delays([&goal.lhs, &goal.rhs].into_iter());
    let scans: Vec<usize> = delays.iter().filter_map(|d| scans_of(d, &cycle)).collect();
    let exact_grid = delays.iter().all(|d| whole(d, &cycle).is_some());
    let m = if exact_grid { scans.iter().fold(0usize, |g, n| g.gcd(n)).max(1) } else { 1 };
    let longest = scans.iter().copied().max().unwrap_or(0);
    // Steps of `m` scans reach long timers in few steps; single scans find the
    // counterexamples whose inputs change between two timer steps.
    let mut grids = vec![m];
    if m > 1 {
        grids.push(1);
    }
    let mut unconfirmed: Option<(Box<Counterexample>, String)> = None;
    let mut tried = 0usize;
    let mut checked = 0usize;
    let mut complete = true;
    for grid in grids {
        // Counting to a program constant takes up to `int_depth` scans.
        let k_max = (3 * longest / grid + 4)
            .max(program.compiled.int_depth / grid + 4)
            .min(limits.max_steps);
        if k_max * grid > limits.max_scans {
            continue;
        }
        let steps_of = |d: &Delay| scans_of(d, &cycle).map(|n| n / grid);
        // One solver per grid: each depth adds a frame, and asks for a violation at its
        // last step under an assumption (the clauses of the shorter runs are kept).
        let Ok(mut search) = Bmc::new(&model, goal, &steps_of) else { continue };
        for k in 1..=k_max {
            if Instant::now() > limits.deadline {
                complete = false;
                break;
            }
            checked = checked.max(k * grid);
            let Some(step_trace) = search.deepen() else { continue };
            tried += 1;
            let mut trace =
                ScanTrace { cycle: cycle.clone(), scans: k * grid, values: BTreeMap::new() };
            for (name, v) in step_trace {
                trace
                    .values
                    .insert(name, v.iter().flat_map(|b| std::iter::repeat_n(*b, grid)).collect());
            }
            match judge(program, &model, goal, trace, limits) {
                Ok(Judged::Both(c)) => {
                    if let Some(shared) = program.shared {
                        shared.keep(program, goal, &model, &c);
                    }
                    return Verdict::Refuted(c);
                }
                Ok(Judged::ExactOnly(c, why)) => {
                    if unconfirmed.is_none() {
                        unconfirmed = Some((c, why));
                    }
                }
                Err(_) => {}
            }
        }
    }
    match unconfirmed {
        Some((candidate, why)) => Verdict::Unconfirmed { candidate, why },
        None => Verdict::NotFound {
            why: format!(
                "bounded model checking found no counterexample in runs of up to {checked} scans ({} s; {tried} candidates rejected{})",
                format_time(&(&cycle * Time::from_integer(checked.into()))),
                if complete { "" } else { "; stopped at the time limit" }
            ),
            complete,
        },
    }
}

/// Confirms a run found another way (a search on the scan simulators, whose inputs
/// change anywhere): the same two checks as [`refute`]'s candidates, after the trace is
/// cut at its first violation and minimised.
pub fn confirm(program: &Program, goal: &Obligation, trace: ScanTrace, limits: Limits) -> Verdict {
    if program.cycle().is_none() {
        return Verdict::NotFound {
            why: "the program has a zero cycle time".into(),
            complete: true,
        };
    }
    let model = program.model(&[&goal.lhs, &goal.rhs]);
    match judge(program, &model, goal, trace, limits) {
        Ok(Judged::Both(c)) => Verdict::Refuted(c),
        Ok(Judged::ExactOnly(c, why)) => Verdict::Unconfirmed { candidate: c, why },
        Err(why) => Verdict::NotFound { why, complete: false },
    }
}

/// Incremental bounded model checking of one goal on one grid: one solver, the model
/// unrolled one frame per depth, the violation at the last step asked as an assumption.
struct Bmc<'m> {
    cnf: Cnf,
    unroller: unroll::Unroller<'m, varisat::Lit>,
    model: &'m Model,
    rel: Rel,
    /// Per free name, its literal at each step.
    free: BTreeMap<String, Vec<varisat::Lit>>,
}

impl<'m> Bmc<'m> {
    fn new(
        model: &'m Model,
        goal: &'m Obligation,
        steps_of: &dyn Fn(&Delay) -> Option<usize>,
    ) -> Result<Self, String> {
        let unroller = unroll::Unroller::new(model, &[&goal.lhs, &goal.rhs], steps_of)?;
        Ok(Bmc { cnf: Cnf::named("bmc"), unroller, model, rel: goal.rel, free: BTreeMap::new() })
    }

    /// Adds one frame (the assumptions required at it) and asks for a run whose last
    /// step violates the goal: its free values, step by step.
    fn deepen(&mut self) -> Option<BTreeMap<String, Vec<bool>>> {
        let free = &mut self.free;
        self.unroller
            .step(&mut self.cnf, &mut |b, name, _| {
                let l = b.fresh();
                free.entry(name.to_string()).or_default().push(l);
                l
            })
            .ok()?;
        let k = self.unroller.steps() - 1;
        for (i, c) in self.model.constraints.iter().enumerate() {
            let (l, r) = self.unroller.constraint_at(i, k)?;
            let v = violated(&mut self.cnf, c.1, &l, &r);
            self.cnf.require(!v);
        }
        let (l, r) = (self.unroller.extra_at(0, k)?, self.unroller.extra_at(1, k)?);
        let v = violated(&mut self.cnf, self.rel, &l, &r);
        let model_lits = self.cnf.solve(&[v])?;
        Some(
            self.free
                .iter()
                .map(|(n, ls)| (n.clone(), ls.iter().map(|l| model_lits.contains(l)).collect()))
                .collect(),
        )
    }
}

/// Fewer signals, fewer changes, a shorter horizon, while `keep` holds.
fn minimise(trace: &mut ScanTrace, keep: &dyn Fn(&ScanTrace) -> bool, limits: Limits) {
    let names: Vec<String> = trace.values.keys().cloned().collect();
    // Signals: constant 0, else constant 1; a block of signals at once, halved when
    // neither holds (a run that needs few of many signals costs few checks).
    // Signals already constant 0 stay so.
    let varying: Vec<&String> = names.iter().filter(|n| trace.values[*n].contains(&true)).collect();
    let mut blocks = vec![&varying[..]];
    while let Some(block) = blocks.pop() {
        if Instant::now() > limits.deadline {
            return;
        }
        let mut done = false;
        for c in [false, true] {
            let mut t = trace.clone();
            for n in block {
                t.values.insert((*n).clone(), vec![c; t.scans]);
            }
            if t != *trace && keep(&t) {
                *trace = t;
                done = true;
                break;
            }
        }
        if !done && block.len() > 1 {
            let (a, b) = block.split_at(block.len() / 2);
            blocks.push(b);
            blocks.push(a);
        }
    }
    // Changes: extend the previous value over the next run, or the next value back.
    let mut improved = true;
    while improved && Instant::now() <= limits.deadline {
        improved = false;
        'outer: for n in &names {
            let Some(v) = trace.values.get(n).cloned() else { continue };
            for p in 1..v.len() {
                if v[p] == v[p - 1] {
                    continue;
                }
                let mut forward = v.clone();
                let mut j = p;
                while j < v.len() && v[j] == v[p] {
                    forward[j] = v[p - 1];
                    j += 1;
                }
                let mut backward = v.clone();
                let mut j = p;
                while j > 0 && v[j - 1] == v[p - 1] {
                    backward[j - 1] = v[p];
                    j -= 1;
                }
                for cand in [forward, backward] {
                    let mut t = trace.clone();
                    t.values.insert(n.clone(), cand);
                    if t.changes() < trace.changes() && keep(&t) {
                        *trace = t;
                        improved = true;
                        break 'outer;
                    }
                }
            }
        }
    }
    // Horizon: shorten each stretch on which nothing changes.
    let mut improved = true;
    while improved && Instant::now() <= limits.deadline {
        improved = false;
        let cuts: Vec<usize> =
            (1..trace.scans).filter(|&k| trace.values.values().any(|v| v[k] != v[k - 1])).collect();
        let mut bounds = vec![0];
        bounds.extend(cuts);
        bounds.push(trace.scans);
        for w in bounds.windows(2) {
            let (a, b) = (w[0], w[1]);
            let len = b - a;
            for keep_len in [1, len / 2] {
                if keep_len == 0 || keep_len >= len {
                    continue;
                }
                let mut t = trace.clone();
                for v in t.values.values_mut() {
                    v.drain(a + keep_len..b);
                }
                t.scans -= len - keep_len;
                if keep(&t) {
                    *trace = t;
                    improved = true;
                    break;
                }
            }
            if improved {
                break;
            }
        }
    }
}

/// The longest run a vacuity check unrolls, in steps.
const MAX_STEPS: usize = 64;

/// The runs a vacuity check unrolls, from the delays of its model: `k` steps of `grid`
/// scans (3× the longest timer plus 4 steps; the grid divides every delay, one scan
/// when some delay is not a whole number of scans) and `k_scans` single scans (3× the
/// longest timer plus 4, at most [`MAX_STEPS`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
struct Steps {
    grid: usize,
    k_scans: usize,
    k: usize,
}

impl Steps {
    /// `int_depth`: the scans an integer of the model may take to reach a constant of
    /// the program ([`CompiledProgram::int_depth`](crate::program::CompiledProgram)).
    fn of(delays: &[Delay], cycle: &Time, int_depth: usize) -> Steps {
        let scans: Vec<usize> = delays.iter().filter_map(|d| scans_of(d, cycle)).collect();
        let exact_grid = delays.iter().all(|d| whole(d, cycle).is_some());
        let grid = if exact_grid { scans.iter().fold(0usize, |g, n| g.gcd(n)).max(1) } else { 1 };
        let longest = scans.iter().copied().max().unwrap_or(0);
        let k_scans = (3 * longest + 4).max(int_depth + 4).min(MAX_STEPS);
        Steps { grid, k_scans, k: (3 * longest / grid + 4).max(int_depth / grid + 4) }
    }

    /// How far the `k` coarse steps reach.
    fn horizon(&self, cycle: &Time) -> Time {
        cycle * Time::from_integer((self.k * self.grid).into())
    }
}

/// The names `terms` read, sorted.
fn read_names(terms: &[&Expr]) -> Vec<String> {
    let mut read = BTreeSet::new();
    for t in terms {
        names_of(t, &mut read);
    }
    read.into_iter().collect()
}

/// What the hypotheses force, found by bounded search over scans.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Vacuity {
    /// No run satisfies the assumptions (bounded: the first `steps` steps).
    pub inconsistent: bool,
    /// Signals the property reads that every bounded run holds constant.
    pub constants: Vec<(String, bool)>,
    /// The horizon checked, in seconds.
    pub horizon: Option<Time>,
}

/// The model unrolled symbolically over `k` steps of `grid` scans, the constraints
/// required at every step; the values of the names in `read`, per step.
fn bounded(
    model: &Model,
    read: &[String],
    cycle: &Time,
    grid: usize,
    k: usize,
) -> Option<(Cnf, Vec<Vec<varisat::Lit>>)> {
    let exprs: Vec<Expr> = read.iter().map(|n| crate::term::name(n)).collect();
    let refs: Vec<&Expr> = exprs.iter().collect();
    let steps_of = |d: &Delay| scans_of(d, cycle).map(|n| n / grid);
    let mut cnf = Cnf::named("bounded");
    let u = unroll(&mut cnf, model, &refs, k, &steps_of, &mut |b, _, _| b.fresh()).ok()?;
    for (c, (l, r)) in model.constraints.iter().zip(&u.constraints) {
        for s in 0..k {
            let v = violated(&mut cnf, c.1, &l[s], &r[s]);
            cnf.require(!v);
        }
    }
    Some((cnf, u.extra))
}

/// Batches of 64 pseudo-random runs [`varying`] tries, each only while some signal has
/// not yet been seen both 1 and 0.
const RANDOM_BATCHES: u64 = 4;

/// Per name of `read`: whether up to [`RANDOM_BATCHES`] × 64 pseudo-random runs of the
/// model (free values drawn by [`unroll::Runs64::sticky`] at each of `k` steps of `grid`
/// scans) show it both 1 and 0. Each such run satisfies [`bounded`]'s formula for the
/// same steps, so a signal they show varying is forced by no check on those steps (all
/// `false` when the model does not unroll).
fn varying(model: &Model, read: &[String], cycle: &Time, grid: usize, k: usize) -> Vec<bool> {
    let exprs: Vec<Expr> = read.iter().map(|n| crate::term::name(n)).collect();
    let refs: Vec<&Expr> = exprs.iter().collect();
    let steps_of = |d: &Delay| scans_of(d, cycle).map(|n| n / grid);
    let (mut ones, mut zeros) = (vec![false; read.len()], vec![false; read.len()]);
    for batch in 0..RANDOM_BATCHES {
        let mut runs = unroll::Runs64::seeded(batch);
        // Each free name's latest value (the unrolling asks for a name's values once
        // each, step after step).
        let mut latest: HashMap<String, u64> = HashMap::new();
        let mut free = |b: &mut unroll::Runs64, n: &str, _step: usize| match latest.get_mut(n) {
            Some(v) => {
                *v = b.sticky(Some(*v));
                *v
            }
            None => {
                let v = b.sticky(None);
                latest.insert(n.to_string(), v);
                v
            }
        };
        let Ok(u) = unroll(&mut runs, model, &refs, k, &steps_of, &mut free) else { break };
        for (i, v) in u.extra.iter().enumerate() {
            ones[i] |= v.iter().any(|x| *x != 0);
            zeros[i] |= v.iter().any(|x| *x != !0);
        }
        if ones.iter().zip(&zeros).all(|(o, z)| *o && *z) {
            break;
        }
    }
    ones.iter().zip(&zeros).map(|(o, z)| *o && *z).collect()
}

/// [`vacuity`] for a model without assumptions: its equations define every signal from
/// the free ones, so any run of the free signals is a run (the scan-by-scan check is
/// satisfiable). The solver is asked only about the signals random runs on the coarse
/// grid do not show varying ([`varying`]), and the long scan-by-scan unrolling is built
/// only for the signals the coarse grid finds constant and random runs scan by scan do
/// not show varying. (It unrolls whenever the coarse grid does: both read the same
/// equations in the same order, and a delay in whole coarse steps is one in scans.)
fn unconstrained(model: &Model, read: &[String], cycle: &Time, steps: Steps) -> Vacuity {
    let Steps { grid, k_scans, k } = steps;
    if k > MAX_STEPS {
        return Vacuity::default();
    }
    let horizon = Some(steps.horizon(cycle));
    // Random runs settle most signals; only the others need the solver.
    let on_grid = varying(model, read, cycle, grid, k);
    let open: Vec<usize> = (0..read.len()).filter(|&i| !on_grid[i]).collect();
    if open.is_empty() {
        return Vacuity { inconsistent: false, constants: Vec::new(), horizon };
    }
    let Some((mut coarse, coarse_values)) = bounded(model, read, cycle, grid, k) else {
        return Vacuity::default();
    };
    let on_coarse = forced_each(&mut coarse, &coarse_values, &open);
    let mut constants = Vec::new();
    let mut candidates: Vec<usize> =
        open.iter().copied().filter(|&i| on_coarse[i].is_some()).collect();
    if !candidates.is_empty() {
        let on_scans = varying(model, read, cycle, 1, k_scans);
        candidates.retain(|&i| !on_scans[i]);
    }
    if !candidates.is_empty() {
        let Some((mut fine, fine_values)) = bounded(model, read, cycle, 1, k_scans) else {
            return Vacuity::default();
        };
        let on_fine = forced_each(&mut fine, &fine_values, &candidates);
        for i in candidates {
            if let Some(v) = on_coarse[i]
                && on_fine[i] == Some(v)
            {
                constants.push((read[i].clone(), v));
            }
        }
    }
    Vacuity { inconsistent: false, constants, horizon }
}

/// [`forced`] for the signals `which` of `values` (one list of literals per signal;
/// `None` for the others). Each model the solver finds shows which signals it sets 1 or
/// 0 somewhere, and those need no query of their own: the answers are [`forced`]'s.
fn forced_each(cnf: &mut Cnf, values: &[Vec<varisat::Lit>], which: &[usize]) -> Vec<Option<bool>> {
    let (mut ones, mut zeros) = (vec![false; values.len()], vec![false; values.len()]);
    let mut out = vec![None; values.len()];
    let seen = |model: &BTreeSet<varisat::Lit>, ones: &mut [bool], zeros: &mut [bool]| {
        for (i, lits) in values.iter().enumerate() {
            ones[i] |= lits.iter().any(|l| model.contains(l));
            zeros[i] |= lits.iter().any(|l| !model.contains(l));
        }
    };
    for &i in which {
        if !ones[i] {
            let some_one = cnf.or_all(&values[i]);
            match cnf.solve(&[some_one]) {
                None => {
                    out[i] = Some(false);
                    continue;
                }
                Some(model) => seen(&model, &mut ones, &mut zeros),
            }
        }
        if !zeros[i] {
            let negs: Vec<varisat::Lit> = values[i].iter().map(|v| !*v).collect();
            let some_zero = cnf.or_all(&negs);
            match cnf.solve(&[some_zero]) {
                None => out[i] = Some(true),
                Some(model) => seen(&model, &mut ones, &mut zeros),
            }
        }
    }
    out
}

/// The constant value `values` has in every model of `cnf`, if any.
fn forced(cnf: &mut Cnf, values: &[varisat::Lit]) -> Option<bool> {
    let some_one = cnf.or_all(values);
    let negs: Vec<varisat::Lit> = values.iter().map(|v| !*v).collect();
    let some_zero = cnf.or_all(&negs);
    if cnf.solve(&[some_one]).is_none() {
        Some(false)
    } else if cnf.solve(&[some_zero]).is_none() {
        Some(true)
    } else {
        None
    }
}

/// Whether some scan-by-scan run satisfies the assumptions (over the first scans:
/// up to 3× the longest timer plus 4, at most 64), and which signals `terms` read are
/// forced to a constant. A constant is reported only when it holds on runs covering 3×
/// the longest timer (on the step grid of [`refute`], at most 64 steps) *and* on the
/// scan grid; both checks are bounded.
pub fn vacuity(program: &Program, terms: &[&Expr]) -> Vacuity {
    let Some(cycle) = program.cycle() else { return Vacuity::default() };
    let model = program.model(terms);
    let steps = Steps::of(&model.delays(terms.iter().copied()), &cycle, program.compiled.int_depth);
    let Steps { grid, k_scans, k } = steps;
    let read = read_names(terms);
    if model.constraints.is_empty() {
        return unconstrained(&model, &read, &cycle, steps);
    }
    let Some((mut fine, fine_values)) = bounded(&model, &read, &cycle, 1, k_scans) else {
        return Vacuity::default();
    };
    if fine.solve(&[]).is_none() {
        let horizon = Some(&cycle * Time::from_integer(k_scans.into()));
        return Vacuity { inconsistent: true, constants: Vec::new(), horizon };
    }
    // Constants: runs long enough for every timer, confirmed scan by scan.
    if k > MAX_STEPS {
        return Vacuity::default();
    }
    let Some((mut coarse, coarse_values)) = bounded(&model, &read, &cycle, grid, k) else {
        return Vacuity::default();
    };
    let mut constants = Vec::new();
    for ((n, c), f) in read.iter().zip(&coarse_values).zip(&fine_values) {
        if let Some(v) = forced(&mut coarse, c)
            && forced(&mut fine, f) == Some(v)
        {
            constants.push((n.clone(), v));
        }
    }
    Vacuity { inconsistent: false, constants, horizon: Some(steps.horizon(&cycle)) }
}

/// The largest cone, in equations, that [`vacuity_cached`] unrolls for one signal.
pub const VACUITY_CONE: usize = 40;

/// The answers of [`vacuity_cached`] for one program and one set of assumptions (one
/// property file's session), per signal, shared by its properties and their threads.
#[derive(Debug, Default)]
pub struct VacuityCache {
    /// Per signal: the delays of its cut cone (`None`: the cone touches an assumption).
    cones: Mutex<HashMap<String, Option<Vec<Delay>>>>,
    /// Per signal and runs checked: its forced value (`None`: the check could not be built).
    forced: Mutex<HashMap<(String, Steps), Checked>>,
}

/// One signal's answer: `Some(forced value, if any)`, `None` when the check could not
/// be built.
type Checked = Option<Option<bool>>;

/// The value cached under `key`, or `make`'s, stored (computed outside the lock).
fn cached<K: Eq + std::hash::Hash, V: Clone>(
    map: &Mutex<HashMap<K, V>>,
    key: K,
    make: impl FnOnce() -> V,
) -> V {
    let known = map.lock().unwrap_or_else(|e| e.into_inner()).get(&key).cloned();
    if let Some(v) = known {
        return v;
    }
    let v = make();
    map.lock().unwrap_or_else(|e| e.into_inner()).insert(key, v.clone());
    v
}

/// [`vacuity`]'s constants for a property, at a cost that does not grow with the
/// program: each signal `terms` read is checked on its own cone cut after
/// [`VACUITY_CONE`] equations ([`Program::cone`]: what lies beyond is free), once per
/// session (`cache`). Every run of the program is a run of the cut cone, so a constant
/// found there is one of the program; a signal held constant only by equations beyond
/// the cut is missed. Each signal is checked on the same runs, those [`vacuity`] would
/// unroll for the union of the cut cones; without a cut (a cone within the cap) the
/// answer is [`vacuity`]'s. When a cut cone touches an `assume`, the check is
/// [`vacuity`]'s, on the whole cone.
pub fn vacuity_cached(program: &Program, terms: &[&Expr], cache: &VacuityCache) -> Vacuity {
    let Some(cycle) = program.cycle() else { return Vacuity::default() };
    let read = read_names(terms);
    let cone = |n: &String| program.cone(&[&crate::term::name(n)], VACUITY_CONE);
    let mut delays = Model::default().delays(terms.iter().copied());
    // The cones built here, for the checks below.
    let mut built: HashMap<&String, Model> = HashMap::new();
    for n in &read {
        let of_cone = cached(&cache.cones, n.clone(), || {
            let model = cone(n);
            let delays = model.constraints.is_empty().then(|| model.delays(std::iter::empty()));
            built.insert(n, model);
            delays
        });
        match of_cone {
            Some(d) => delays.extend(d),
            None => return vacuity(program, terms),
        }
    }
    let steps = Steps::of(&delays, &cycle, program.compiled.int_depth);
    if steps.k > MAX_STEPS {
        return Vacuity::default();
    }
    let mut constants = Vec::new();
    for n in &read {
        let forced = cached(&cache.forced, (n.clone(), steps), || {
            let model = built.remove(n).unwrap_or_else(|| cone(n));
            let v = unconstrained(&model, std::slice::from_ref(n), &cycle, steps);
            v.horizon.is_some().then(|| v.constants.first().map(|c| c.1))
        });
        match forced {
            Some(Some(v)) => constants.push((n.clone(), v)),
            Some(None) => {}
            None => return Vacuity::default(),
        }
    }
    Vacuity { inconsistent: false, constants, horizon: Some(steps.horizon(&cycle)) }
}
