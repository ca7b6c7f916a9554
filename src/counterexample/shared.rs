//! Counterexamples shared between the properties of one run: a confirmed run that also
//! violates another property refutes it without a proof attempt or a new search.
//!
//! A confirmed counterexample's inputs are run, scan by scan, through the equations
//! that read (through any chain of equations) an input it sets; every other signal
//! keeps its value in the program's run with every input at 0. A later
//! property is evaluated on them; if it fails at some scan, the run's inputs, kept to
//! those the property's own cone reads and cut after that scan, go through the same
//! confirmation as any candidate ([`judge`]: every hypothesis of the cone checked
//! exactly, the violation shown by the scan simulator), without a new minimisation
//! (the run was minimised for the property it refuted). The store only proposes
//! candidates: nothing in it is trusted.
//!
//! Each confirmed run is also kept grown: the Boolean inputs its property's cone does
//! not read, held at values drawn for them (they cannot change its violation). A
//! property refuted from a grown run keeps, of the drawn inputs, only those its
//! violation needs (a grown run that drew more than a few of its inputs is not tried:
//! a search of its own costs less). Grown runs cost a run of most of the program, so
//! they are kept only while they refute several properties each, at most [`MAX_GROWN`].
//!
//! A property that no kept run violates may still belong to a family of the same form
//! (one per unit of a plant) whose member the most recent run refuted: that run is
//! repaired near the property ([`Near`]). A solver chooses the inputs of the property's
//! cone cut after [`REPAIR_CAP`] equations, every other name the cut reads held at its
//! value in the run, so that the property fails, keeping each input at its value in the
//! run where a violation allows it (the fewer changes, the less the judge runs); the
//! result is judged on the whole cone like any candidate (an equation outside the cut
//! may read a changed input).
//!
//! A candidate from a kept run is judged on part of its cone where the front end can
//! replay a run ([`Shared::near`]): the equations that read, through any chain, an input
//! whose values differ from the kept run's, everything else they read at its value in
//! the kept run. That run of the cone of the property it refuted is computed and checked
//! exactly once per kept run ([`Kept::base`]: every compiled hypothesis of the cone), and
//! the front end's simulator runs the same part, replaying the rest from its own record
//! of the run. A refutation near a kept run then costs what it changes, not its cone.
//!
//! Which properties a run can refute depends on the order they are checked in: a
//! property whose cone is deep (its signals computed from long chains of rungs) has
//! counterexamples that set more of the program in motion, so [`deepest_first`] orders
//! the properties.

use std::collections::{BTreeMap, BTreeSet, VecDeque};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

use super::confirm::{Background, base_holds, changed_inputs, discrete_violation_near, judge_near};
use super::unroll::{Bits as _, Cnf, Concrete, Model, unroll, violated};
use super::{
    Counterexample, Judged, Limits, Program, ScanTrace, discrete_violation, equations_model, judge,
    program_model, scans_of,
};
use crate::ladder::{CompiledProgram, SignalKind};
use crate::program::fast_hash::{FastMap as HashMap, FastSet as HashSet};
use crate::program::simulate::Recording;
use crate::prover::Obligation;
use crate::term::{Expr, Symbol, Term};

/// The confirmed counterexamples of a run, shared by the threads that check its
/// properties.
#[derive(Default)]
pub struct Shared {
    /// The most recent runs kept, oldest first.
    runs: Mutex<VecDeque<Arc<Kept>>>,
    /// The program's run with every input at 0, the longest needed so far.
    quiet: Mutex<Option<Arc<Bits>>>,
    /// Per name, the equations (positions in scan order) that read it (built at the
    /// first run kept).
    readers: OnceLock<HashMap<Symbol, Vec<usize>>>,
    /// Per signal, how deep it is computed ([`depths`], built once: for the order of
    /// the properties and for each run kept).
    depth: OnceLock<HashMap<Symbol, usize>>,
    /// How many properties looked for a kept run that refutes them, how many runs were
    /// kept, and how many properties a kept run refuted.
    checks: AtomicUsize,
    kept: AtomicUsize,
    hits: AtomicUsize,
    /// How many grown runs were kept, and how many properties they refuted.
    grown_kept: AtomicUsize,
    grown_hits: AtomicUsize,
    /// The exact checks passed on the runs judged so far.
    pub(super) exact: super::confirm::ExactMemo,
}

/// Per signal, its value at each scan (bit `k` for scan `k + 1`).
struct Bits {
    scans: usize,
    /// By name (read by `&str`, not interned: the runs read names by their text).
    values: HashMap<String, u64>,
}

impl Bits {
    fn of(signals: BTreeMap<String, Vec<bool>>, scans: usize) -> Bits {
        let values = signals
            .into_iter()
            .map(|(n, v)| {
                let bits = v.iter().enumerate().fold(0u64, |m, (k, b)| m | (u64::from(*b) << k));
                (n, bits)
            })
            .collect();
        Bits { scans, values }
    }

    fn at(&self, name: &str, k: usize) -> Option<bool> {
        self.values.get(name).map(|bits| bits >> k & 1 == 1)
    }
}

/// A confirmed run: its inputs, and the signals that differ from the quiet run's
/// (those that read, through any chain of equations, an input the run sets).
struct Kept {
    trace: ScanTrace,
    moved: Bits,
    quiet: Arc<Bits>,
    /// The depth of the property it refuted.
    depth: usize,
    /// The form of the property it refuted ([`form`]).
    form: u64,
    /// The inputs outside that property's cone it sets (held at 1 by [`drawn`]).
    drawn: Vec<String>,
    /// The check (by number) at which it was kept or last refuted a property.
    used: AtomicUsize,
    /// The equations (positions in scan order) of the cone of the property it refuted.
    cone: Arc<Vec<usize>>,
    /// The names that cone defines (made at the first call of [`Kept::cone_names`]).
    names: OnceLock<HashSet<String>>,
    /// The run of that cone on its inputs, checked ([`Kept::base`]).
    base: OnceLock<Option<Base>>,
}

/// A kept run as the base of candidates judged on part of their cones: every signal of
/// the cone of the property it refuted on its inputs, every compiled hypothesis about them
/// checked exactly, and the front end's record of the same run for its simulator.
struct Base {
    values: Bits,
    record: Recording,
}

impl Kept {
    /// The run as a base ([`Base`]), made at the first call: a run of the cone of the
    /// property it refuted (a judge's cost); `None` when a compiled hypothesis fails on
    /// it (then no candidate is judged on part of its cone).
    fn base(&self, program: &Program) -> Option<&Base> {
        self.base
            .get_or_init(|| {
                let trace = &self.trace;
                let cone = equations_model(program.compiled, self.cone.iter().copied());
                let cycle = trace.cycle.clone();
                let run = unroll(
                    &mut Concrete,
                    &cone,
                    &[],
                    trace.scans,
                    &|d| scans_of(d, &cycle),
                    &mut |_, name, k| {
                        trace.values.get(name).and_then(|v| v.get(k)).copied().unwrap_or(false)
                    },
                )
                .ok()?;
                if !base_holds(program, &run.signals, trace) {
                    return None;
                }
                let inputs: Vec<BTreeMap<String, bool>> = (0..trace.scans)
                    .map(|k| {
                        trace
                            .values
                            .iter()
                            .map(|(n, v)| (n.clone(), v.get(k) == Some(&true)))
                            .collect()
                    })
                    .collect();
                let names: BTreeSet<String> = cone.defs.iter().map(|(n, _)| n.clone()).collect();
                let record = program.reference.record(&names, &inputs)?;
                Some(Base { values: Bits::of(run.signals, trace.scans), record })
            })
            .as_ref()
    }

    /// The names the cone of the property it refuted defines.
    fn cone_names(&self, program: &Program) -> &HashSet<String> {
        self.names.get_or_init(|| {
            let index = program.compiled.equation_index();
            self.cone.iter().map(|&p| index.equations[p].0.clone()).collect()
        })
    }

    fn value(&self, name: &str, k: usize) -> bool {
        self.moved
            .at(name, k)
            .or_else(|| self.trace.values.get(name).and_then(|v| v.get(k)).copied())
            .or_else(|| self.quiet.at(name, k))
            .unwrap_or(false)
    }
}

/// At most this many runs are kept, the most recent.
const MAX_RUNS: usize = 32;
/// A kept run that refuted none of the last this many properties checked is dropped.
const STALE: usize = 64;
/// Runs kept before any has refuted a property; after them, one more per property
/// refuted from a kept run.
const FREE_KEEPS: usize = 8;
/// Grown runs kept before any has refuted a property; after them, one more per
/// [`GROWN_HITS`] properties refuted from grown runs.
const FREE_GROWN: usize = 2;
/// One more grown run is kept per this many properties refuted from grown runs (a grown
/// run costs a run of most of the program: it must refute several to pay for itself).
const GROWN_HITS: usize = 4;
/// At most this many grown runs are kept in a session.
const MAX_GROWN: usize = 64;
/// A grown run that drew more than this many of a property's inputs is not tried for it.
const MAX_DRAWN: usize = 6;
/// Runs longer than this many scans are not kept (a bit mask per signal).
const MAX_SCANS: usize = 64;

impl Shared {
    /// Keeps a confirmed counterexample of `goal` for the properties checked after it:
    /// the equations that read what the run sets, run on its inputs (the others keep the
    /// quiet run's values). Keeping costs a run of that part of the program, so a run is
    /// kept only when its property is at least as deep as those of the runs kept (the
    /// deepest set the most in motion), after the runs that refuted none of the last
    /// [`STALE`] properties checked are dropped, and only while the kept runs pay for
    /// themselves ([`FREE_KEEPS`] plus one per property they refuted).
    pub fn keep(&self, program: &Program, goal: &Obligation, model: &Model, c: &Counterexample) {
        let trace = &c.trace;
        let paid = FREE_KEEPS + self.hits.load(Ordering::Relaxed);
        if trace.scans > MAX_SCANS || self.kept.load(Ordering::Relaxed) >= paid {
            return;
        }
        let depth = self.depth_of(program.compiled, [&goal.lhs, &goal.rhs]);
        let now = self.checks.load(Ordering::Relaxed);
        {
            let Ok(mut runs) = self.runs.lock() else { return };
            runs.retain(|r| now.saturating_sub(r.used.load(Ordering::Relaxed)) < STALE);
            if runs.iter().any(|r| r.depth > depth) {
                return;
            }
        }
        let salt = self.kept.fetch_add(1, Ordering::Relaxed) as u64;
        let form = form(goal);
        let defining = &program.compiled.equation_index().defining;
        let mut cone: Vec<usize> = model
            .defs
            .iter()
            .flat_map(|(n, _)| defining.get(n.as_str()).map_or(&[][..], Vec::as_slice))
            .copied()
            .collect();
        cone.sort_unstable();
        cone.dedup();
        let cone = Arc::new(cone);
        self.keep_run(program, trace.clone(), Vec::new(), (depth, form, cone.clone()), now);
        // The run grown: every Boolean input the property's cone does not read held at a
        // value drawn for it (it cannot change the violation, and sets in motion parts
        // of the program the run left at rest; each run kept draws other values). A
        // grown run costs a run of most of the program: grown runs are kept only while
        // they pay for themselves, as the others.
        let grown_paid =
            (FREE_GROWN + self.grown_hits.load(Ordering::Relaxed) / GROWN_HITS).min(MAX_GROWN);
        if self.grown_kept.load(Ordering::Relaxed) >= grown_paid {
            return;
        }
        let free = model.free_names([&goal.lhs, &goal.rhs].into_iter());
        let mut grown = trace.clone();
        let mut set = Vec::new();
        for (n, kind) in &program.compiled.signals {
            if matches!(kind, SignalKind::Input) && !free.contains(n) && drawn(n, salt) {
                grown.values.insert(n.clone(), vec![true; trace.scans]);
                set.push(n.clone());
            }
        }
        if !set.is_empty() && self.grown_kept.fetch_add(1, Ordering::Relaxed) < grown_paid {
            self.keep_run(program, grown, set, (depth, form, cone), now);
        }
    }

    /// Keeps one run: the equations that read what it sets run on its inputs.
    fn keep_run(
        &self,
        program: &Program,
        trace: ScanTrace,
        drawn: Vec<String>,
        (depth, form, cone): (usize, u64, Arc<Vec<usize>>),
        now: usize,
    ) {
        // An input the run holds at 0 throughout is left out (a trace's missing input is
        // 0): the candidates made from the run then carry, and compare, only what it sets.
        let mut trace = trace;
        trace.values.retain(|_, v| v.contains(&true));
        let Some(quiet) = self.quiet(program, &trace) else { return };
        let index = program.compiled.equation_index();
        let readers = self.readers(program);
        // The equations that read, through any chain, an input the run sets.
        let mut moved = BTreeSet::new();
        let mut pending: Vec<Symbol> = trace
            .values
            .iter()
            .filter(|(_, v)| v.contains(&true))
            .map(|(n, _)| Symbol::from(n.as_str()))
            .collect();
        while let Some(n) = pending.pop() {
            for &p in readers.get(&n).map_or(&[][..], Vec::as_slice) {
                if moved.insert(p) {
                    pending.push(Symbol::from(index.equations[p].0.as_str()));
                }
            }
        }
        let model = equations_model(program.compiled, moved);
        let cycle = trace.cycle.clone();
        let Ok(run) = unroll(
            &mut Concrete,
            &model,
            &[],
            trace.scans,
            &|d| scans_of(d, &cycle),
            &mut |_, name, k| match trace.values.get(name) {
                Some(v) => v.get(k).copied().unwrap_or(false),
                None => quiet.at(name, k).unwrap_or(false),
            },
        ) else {
            return;
        };
        let scans = trace.scans;
        let kept = Kept {
            trace,
            moved: Bits::of(run.signals, scans),
            quiet,
            depth,
            form,
            drawn,
            used: AtomicUsize::new(now),
            cone,
            names: OnceLock::new(),
            base: OnceLock::new(),
        };
        if let Ok(mut runs) = self.runs.lock() {
            if runs.len() == MAX_RUNS {
                runs.pop_front();
            }
            runs.push_back(Arc::new(kept));
        }
    }

    /// Per name, the equations (positions in scan order) that read it.
    fn readers(&self, program: &Program) -> &HashMap<Symbol, Vec<usize>> {
        let index = program.compiled.equation_index();
        self.readers.get_or_init(|| {
            let position: HashMap<usize, usize> =
                index.equations.iter().enumerate().map(|(p, (_, h))| (*h, p)).collect();
            index
                .mentioning
                .iter()
                .map(|(n, hs)| (*n, hs.iter().filter_map(|h| position.get(h).copied()).collect()))
                .collect()
        })
    }

    /// The part of `model` (a property's cone) that the inputs whose values in `trace`
    /// differ from those of the run `kept`, and the inputs of `also`, can change: its
    /// equations that read, through any chain, one of them, and those of the equations
    /// outside the cone of the property the kept run refuted (with the inputs they read,
    /// counted as changed), which the kept run's base does not give. Every other name the part
    /// reads that the program defines has its value in the kept run, on which every
    /// compiled hypothesis is checked exactly once ([`Kept::base`]); `None` when that
    /// check failed, `trace` is longer than the kept run, the cone is small
    /// ([`NEAR_MIN`]), or the part reads a name outside the cone of the property the
    /// kept run refuted.
    fn near(
        &self,
        program: &Program,
        (model, goal): (&Model, &Obligation),
        trace: &ScanTrace,
        kept: &Arc<Kept>,
        also: &[&String],
    ) -> Option<Part> {
        // A small cone is judged whole for less than finding its part costs.
        if trace.scans > kept.trace.scans || model.defs.len() < NEAR_MIN {
            return None;
        }
        let mut changed = changed_inputs(trace, &kept.trace);
        changed.extend(also.iter().map(|n| (*n).clone()));
        let index = program.compiled.equation_index();
        let readers = self.readers(program);
        let defined: HashSet<&str> = model.defs.iter().map(|(n, _)| n.as_str()).collect();
        // The equations of the cone whose signals the base run does not give (outside the
        // cone of the property the kept run refuted) are run too, as if an input they read
        // had changed: the part then reads from the base only what it gives. The inputs
        // they read count as changed (the simulator runs the rungs that read them).
        let in_cone = kept.cone_names(program);
        let mut moved: HashSet<&str> = HashSet::default();
        let mut pending: Vec<Symbol> = Vec::new();
        for (n, rhs) in &model.defs {
            if in_cone.contains(n) {
                continue;
            }
            if moved.insert(n.as_str()) {
                pending.push(Symbol::from(n.as_str()));
            }
            for node in rhs.as_ref() {
                if let Term::Name(m) = node
                    && !index.defining.contains_key(m.as_str())
                {
                    changed.insert(m.as_str().to_string());
                }
            }
        }
        pending.extend(changed.iter().map(|n| Symbol::from(n.as_str())));
        while let Some(n) = pending.pop() {
            for &p in readers.get(&n).map_or(&[][..], Vec::as_slice) {
                let name = index.equations[p].0.as_str();
                if defined.contains(name) && moved.insert(name) {
                    pending.push(Symbol::from(name));
                }
            }
        }
        let part = Model {
            defs: model.defs.iter().filter(|(n, _)| moved.contains(n.as_str())).cloned().collect(),
            constraints: model.constraints.clone(),
        };
        // Every defined name the part reads from outside must be in the kept run's cone
        // (looked up before the base is made: it costs a run of that cone).
        let outside = part.free_names([&goal.lhs, &goal.rhs].into_iter());
        if outside.iter().any(|n| index.defining.contains_key(n) && !in_cone.contains(n)) {
            return None;
        }
        kept.base(program)?;
        Some(Part { part, kept: kept.clone(), changed })
    }

    /// The program's run with every input at 0, at least as long as `trace`.
    fn quiet(&self, program: &Program, trace: &ScanTrace) -> Option<Arc<Bits>> {
        let mut quiet = self.quiet.lock().ok()?;
        if let Some(q) = quiet.as_ref().filter(|q| q.scans >= trace.scans) {
            return Some(q.clone());
        }
        let scans = trace.scans.max(quiet.as_ref().map_or(0, |q| 2 * q.scans)).min(MAX_SCANS);
        let whole = program_model(program.compiled);
        let cycle = trace.cycle.clone();
        let run =
            unroll(&mut Concrete, &whole, &[], scans, &|d| scans_of(d, &cycle), &mut |_, _, _| {
                false
            })
            .ok()?;
        let q = Arc::new(Bits::of(run.signals, scans));
        *quiet = Some(q.clone());
        Some(q)
    }

    /// The order to check properties in: within each window of [`WINDOW`] properties (in
    /// file order), the deepest first. A property's depth is the longest chain of
    /// equations, in scan order, from an input to a signal it reads (a read of a
    /// signal computed later in the scan, the previous scan's value, adds nothing). The
    /// counterexamples of the deepest, kept, can refute the shallower ones. The window
    /// bounds how many results wait for an earlier one to be reported (they are reported
    /// in file order); properties of the same depth keep their order.
    pub fn deepest_first(&self, compiled: &CompiledProgram, goals: &[[&Expr; 2]]) -> Vec<usize> {
        let of: Vec<usize> = goals.iter().map(|sides| self.depth_of(compiled, *sides)).collect();
        let mut order: Vec<usize> = (0..goals.len()).collect();
        for window in order.chunks_mut(WINDOW) {
            window.sort_by_key(|&i| std::cmp::Reverse(of[i]));
        }
        order
    }

    /// The depth of the deepest signal the two sides of a goal read.
    fn depth_of(&self, compiled: &CompiledProgram, sides: [&Expr; 2]) -> usize {
        let depth = self.depth.get_or_init(|| depths(compiled));
        sides.iter().map(|e| deepest(e, depth)).max().unwrap_or(0)
    }
}

/// The part of a property's cone a candidate is judged on ([`Shared::near`]).
struct Part {
    part: Model,
    kept: Arc<Kept>,
    changed: BTreeSet<String>,
}

impl Part {
    /// `f` given the background the part reads: the kept run's values of the names the
    /// program defines.
    fn with<T>(&self, program: &Program, f: impl FnOnce(&Background) -> T) -> Option<T> {
        let base = self.kept.base(program)?;
        let defining = &program.compiled.equation_index().defining;
        let at = |n: &str, k: usize| match defining.contains_key(n) {
            true => base.values.at(n, k),
            false => None,
        };
        let background = Background {
            base: &at,
            inputs: &self.kept.trace,
            changed: &self.changed,
            record: Some(&base.record),
        };
        Some(f(&background))
    }

    /// Whether `trace` violates the goal on the part.
    fn violates(&self, program: &Program, goal: &Obligation, trace: &ScanTrace) -> bool {
        self.with(program, |b| discrete_violation_near(&self.part, goal, trace, b).is_some())
            .unwrap_or(false)
    }

    /// The judge's verdict on `trace`, on the part of the cone `full` (every signal of
    /// which the counterexample holds with `all`).
    fn judge(
        &self,
        program: &Program,
        full: &Model,
        goal: &Obligation,
        (trace, all): (ScanTrace, bool),
    ) -> Option<Box<Counterexample>> {
        let judged =
            |b: &Background| judge_near(program, (full, &self.part), goal, (trace, all), b);
        match self.with(program, judged)? {
            Ok(Judged::Both(found)) => Some(found),
            _ => None,
        }
    }
}

/// A value drawn for input `name` in the grown run number `salt`: a bit of a hash of
/// both (FNV-1a, then a multiplicative mix), so that runs are the same from one
/// session to the next.
fn drawn(name: &str, salt: u64) -> bool {
    let h = name.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    });
    (h ^ salt.wrapping_mul(0x9e37_79b9_7f4a_7c15)).wrapping_mul(0xff51_afd7_ed55_8ccd) >> 63 == 1
}

/// A counterexample of `goal` confirmed from a run kept in `program.shared`, if one of
/// them violates it.
pub fn refute_shared(
    program: &Program,
    goal: &Obligation,
    limits: Limits,
) -> Option<Box<Counterexample>> {
    let shared = program.shared?;
    let now = shared.checks.fetch_add(1, Ordering::Relaxed) + 1;
    let runs: Vec<Arc<Kept>> = shared.runs.lock().ok()?.iter().rev().cloned().collect();
    // A zero cycle has no scans to share.
    program.cycle()?;
    // The property's cone, and the names it leaves free: the inputs its run may set.
    let mut cone = None;
    let cone_of = || {
        let model = program.model(&[&goal.lhs, &goal.rhs]);
        let free = model.free_names([&goal.lhs, &goal.rhs].into_iter());
        (model, free)
    };
    for kept in &runs {
        let Some(v) = violated_at(goal, kept) else { continue };
        let (model, free) = cone.get_or_insert_with(cone_of);
        let mut trace = kept.trace.restricted(free);
        trace.truncate(v + 1);
        // Of the inputs drawn, only those the violation needs stay set; a run that drew
        // many of the property's inputs costs more than a search of its own.
        let drawn: Vec<&String> =
            kept.drawn.iter().filter(|n| trace.values.contains_key(*n)).collect();
        if drawn.len() > MAX_DRAWN {
            continue;
        }
        // Judged on the part of the cone that differs from the kept run where it can be
        // (not from a grown run: every input it drew and this trace drops is a change).
        let part = shared.near(program, (model, goal), &trace, kept, &drawn);
        keep_needed(&mut trace, &drawn, &|t| match &part {
            Some(part) => part.violates(program, goal, t),
            None => discrete_violation(model, goal, t).is_some(),
        });
        if let Some(found) = judged(program, model, part.as_ref(), goal, trace, limits) {
            kept.used.store(now, Ordering::Relaxed);
            shared.hits.fetch_add(1, Ordering::Relaxed);
            if !kept.drawn.is_empty() {
                shared.grown_hits.fetch_add(1, Ordering::Relaxed);
            }
            return Some(found);
        }
    }
    // No kept run violates it: the most recent that refuted a property of the same form
    // (a family of properties, one per unit of a plant), with the inputs near this one
    // chosen anew. Only a candidate, judged as any other.
    let form = form(goal);
    for kept in runs.iter().filter(|k| k.form == form).take(REPAIRS) {
        let (model, free) = cone.get_or_insert_with(cone_of);
        let near = Near::new(program.cone(&[&goal.lhs, &goal.rhs], REPAIR_CAP), kept, free, goal);
        let Some((mut trace, changed)) = near.repaired(goal) else { continue };
        let still = |t: &ScanTrace| near.violation(goal, t).is_some();
        let Some(v) = near.violation(goal, &trace) else { continue };
        trace.truncate(v + 1);
        let changed: Vec<&String> =
            changed.iter().filter(|n| trace.values.contains_key(*n)).collect();
        keep_needed(&mut trace, &changed, &still);
        steady(&mut trace, &changed, &still);
        let part = shared.near(program, (model, goal), &trace, kept, &[]);
        if let Some(found) = judged(program, model, part.as_ref(), goal, trace, limits) {
            kept.used.store(now, Ordering::Relaxed);
            shared.hits.fetch_add(1, Ordering::Relaxed);
            return Some(found);
        }
    }
    None
}

/// A candidate from a kept run judged (already minimised): on `part` of the cone
/// `model` where there is one, else on the whole cone; confirmed both ways or nothing.
fn judged(
    program: &Program,
    model: &Model,
    part: Option<&Part>,
    goal: &Obligation,
    trace: ScanTrace,
    limits: Limits,
) -> Option<Box<Counterexample>> {
    if let Some(part) = part {
        return part.judge(program, model, goal, (trace, limits.signals));
    }
    let limits = Limits { minimised: true, ..limits };
    match judge(program, model, goal, trace, limits) {
        Ok(Judged::Both(found)) => Some(found),
        _ => None,
    }
}

/// A candidate is judged on part of its cone only when the cone has at least this many
/// equations (a smaller cone is judged whole for less than finding the part costs).
const NEAR_MIN: usize = 256;

/// How many times a repair's solver gives up the inputs held at their values in the run
/// that block a violation (a failed core's), before it lets every input of the cut change.
const PREFER_ROUNDS: usize = 16;

/// How many kept runs (the most recent first) are repaired for a property none of them
/// violates.
const REPAIRS: usize = 1;
/// How many equations of a property's cone a repair solves over (taken breadth first
/// from the property's signals).
const REPAIR_CAP: usize = 64;

/// The form of a property: its relation and the shape of its two sides, names left out
/// (`L1_pump_u7 ⇒ 5s/L1_up_u7` and `L1_pump_u8 ⇒ 5s/L1_up_u8` have one form).
fn form(goal: &Obligation) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    goal.rel.hash(&mut h);
    for side in [&goal.lhs, &goal.rhs] {
        side.as_ref().len().hash(&mut h);
        for node in side.as_ref() {
            match node {
                Term::Name(_) => 0u8.hash(&mut h),
                other => other.hash(&mut h),
            }
        }
    }
    h.finish()
}

/// A kept run seen from a property's cone cut after [`REPAIR_CAP`] equations: every name
/// the cut leaves free is at its value in the run, except the free names of the
/// property's whole cone (`free`: its inputs), which a trace sets.
struct Near<'a> {
    model: Model,
    kept: &'a Kept,
    free: &'a BTreeSet<String>,
    /// The names the cut reads from outside it, each with whether it is in `free`
    /// (looked up once, not at each read of a run).
    outside: HashMap<String, bool>,
    /// The same names, each with its values in the kept run at each of its scans (bit `k`
    /// for scan `k + 1`, read once rather than at each run of the cut), or `None` for
    /// those in `free`.
    held: HashMap<String, Option<u64>>,
}

impl<'a> Near<'a> {
    fn new(model: Model, kept: &'a Kept, free: &'a BTreeSet<String>, goal: &Obligation) -> Self {
        let outside = model
            .free_names([&goal.lhs, &goal.rhs].into_iter())
            .into_iter()
            .map(|n| {
                let input = free.contains(&n);
                (n, input)
            })
            .collect::<HashMap<String, bool>>();
        let scans = kept.trace.scans.min(64);
        let held = outside
            .iter()
            .map(|(n, input)| {
                let bits = (0..scans).fold(0u64, |m, k| m | (u64::from(kept.value(n, k)) << k));
                (n.clone(), (!*input).then_some(bits))
            })
            .collect();
        Near { model, kept, free, outside, held }
    }

    /// Whether the run reads `name` from the trace (an input of the whole cone), not
    /// from the kept run.
    fn is_input(&self, name: &str) -> bool {
        self.outside.get(name).copied().unwrap_or_else(|| self.free.contains(name))
    }

    /// The kept run with the inputs of the cut chosen anew by a solver, so that `goal`
    /// fails at some scan of the run while every assumption holds: the trace of the
    /// run's inputs of the whole cone with those chosen, and the names whose values
    /// changed. Equations outside the cut may read a changed input: only the judge's
    /// run of the whole cone shows whether the goal still fails.
    fn repaired(&self, goal: &Obligation) -> Option<(ScanTrace, Vec<String>)> {
        let trace = &self.kept.trace;
        let cycle = trace.cycle.clone();
        let mut cnf = Cnf::named("repair");
        let mut chosen: BTreeMap<String, Vec<varisat::Lit>> = BTreeMap::new();
        let u = unroll(
            &mut cnf,
            &self.model,
            &[&goal.lhs, &goal.rhs],
            trace.scans,
            &|d| scans_of(d, &cycle),
            &mut |b, name, k| {
                if self.is_input(name) {
                    let l = b.fresh();
                    chosen.entry(name.to_string()).or_default().push(l);
                    l
                } else {
                    b.konst(self.kept.value(name, k))
                }
            },
        )
        .ok()?;
        for (c, (l, r)) in self.model.constraints.iter().zip(&u.constraints) {
            for (a, b) in l.iter().zip(r) {
                let v = violated(&mut cnf, c.1, a, b);
                cnf.require(!v);
            }
        }
        let (l, r) = (u.extra.first()?, u.extra.get(1)?);
        let fails: Vec<varisat::Lit> =
            l.iter().zip(r).map(|(a, b)| violated(&mut cnf, goal.rel, a, b)).collect();
        let some = cnf.or_all(&fails);
        // Each input kept at its value in the run where the violation allows it: the
        // fewer inputs change, the fewer the judge runs and the smaller its part.
        let preferred: Vec<varisat::Lit> = chosen
            .iter()
            .flat_map(|(n, lits)| {
                let before = |k: usize| trace.values.get(n).and_then(|v| v.get(k)).copied();
                lits.iter().enumerate().map(move |(k, l)| match before(k) {
                    Some(true) => *l,
                    _ => !*l,
                })
            })
            .collect();
        let model = cnf.solve_preferring(&[some], &preferred, PREFER_ROUNDS)?;
        let mut out = trace.restricted(self.free);
        let mut changed = Vec::new();
        for (n, lits) in chosen {
            let values: Vec<bool> = lits.iter().map(|l| model.contains(l)).collect();
            let before = |k: usize| trace.values.get(&n).and_then(|v| v.get(k)).copied();
            if values.iter().enumerate().any(|(k, b)| before(k).unwrap_or(false) != *b) {
                out.values.insert(n.clone(), values);
                changed.push(n);
            }
        }
        Some((out, changed))
    }

    /// The first scan at which `goal` fails on the cut with the inputs of `trace`.
    fn violation(&self, goal: &Obligation, trace: &ScanTrace) -> Option<usize> {
        let cycle = trace.cycle.clone();
        let run = unroll(
            &mut Concrete,
            &self.model,
            &[&goal.lhs, &goal.rhs],
            trace.scans,
            &|d| scans_of(d, &cycle),
            &mut |_, name, k| match self.held.get(name) {
                Some(Some(bits)) if k < self.kept.trace.scans.min(64) => bits >> k & 1 == 1,
                Some(None) => {
                    trace.values.get(name).and_then(|v| v.get(k)).copied().unwrap_or(false)
                }
                _ => match self.is_input(name) {
                    true => trace.values.get(name).and_then(|v| v.get(k)).copied().unwrap_or(false),
                    false => self.kept.value(name, k),
                },
            },
        )
        .ok()?;
        run.first_violation(&self.model, goal.rel)
    }
}

/// Holds each input of `names` that changes in the trace at 1 from the first scan, where
/// `still` holds so (a solver's choice changes more than it needs; 0 throughout is
/// [`keep_needed`]'s try).
fn steady(trace: &mut ScanTrace, names: &[&String], still: &dyn Fn(&ScanTrace) -> bool) {
    for n in names {
        let Some(values) = trace.values.get(*n) else { continue };
        if values.iter().all(|b| *b) {
            continue;
        }
        let saved = trace.values.insert((*n).clone(), vec![true; values.len()]);
        if !still(trace)
            && let Some(v) = saved
        {
            trace.values.insert((*n).clone(), v);
        }
    }
}

/// Unsets the inputs of `names` that `still` holds without, a block at a time (all of
/// them, else each half in turn).
fn keep_needed(trace: &mut ScanTrace, names: &[&String], still: &dyn Fn(&ScanTrace) -> bool) {
    if names.is_empty() {
        return;
    }
    let saved: Vec<(String, Vec<bool>)> =
        names.iter().filter_map(|n| trace.values.remove(*n).map(|v| ((*n).clone(), v))).collect();
    if still(trace) {
        return;
    }
    trace.values.extend(saved);
    if names.len() > 1 {
        let (a, b) = names.split_at(names.len() / 2);
        keep_needed(trace, a, still);
        keep_needed(trace, b, still);
    }
}

/// The first scan (0-based) at which the goal fails on a kept run.
fn violated_at(goal: &Obligation, kept: &Kept) -> Option<usize> {
    let trace = &kept.trace;
    let cycle = trace.cycle.clone();
    let bare = Model { defs: Vec::new(), constraints: Vec::new() };
    let run = unroll(
        &mut Concrete,
        &bare,
        &[&goal.lhs, &goal.rhs],
        trace.scans,
        &|d| scans_of(d, &cycle),
        &mut |_, name, k| kept.value(name, k),
    )
    .ok()?;
    run.first_violation(&bare, goal.rel)
}

/// Per defined signal, the longest chain of equations, in scan order, from an input to
/// it (inputs and signals read before they are computed count 0).
fn depths(compiled: &CompiledProgram) -> HashMap<Symbol, usize> {
    let index = compiled.equation_index();
    let mut depth: HashMap<Symbol, usize> = HashMap::default();
    for (name, h) in &index.equations {
        let d = deepest(&compiled.hypotheses[*h].rhs, &depth) + 1;
        let slot = depth.entry(Symbol::from(name.as_str())).or_insert(0);
        *slot = (*slot).max(d);
    }
    depth
}

/// The depth of the deepest signal `e` reads.
fn deepest(e: &Expr, depth: &HashMap<Symbol, usize>) -> usize {
    e.as_ref()
        .iter()
        .filter_map(|node| match node {
            Term::Name(n) => depth.get(n).copied(),
            _ => None,
        })
        .max()
        .unwrap_or(0)
}

/// How many properties [`deepest_first`] reorders at once. The larger the window, the
/// more properties the run kept for its deepest can refute directly rather than by a
/// repair (twice the cost); the smaller, the sooner results print in file order. On a
/// chain of 1,000 water units (7,000 properties), 1,024 rather than 256 turns about 660
/// of the 2,000 refutations from repairs into direct ones.
const WINDOW: usize = 1024;

#[cfg(test)]
mod tests {
    use super::*;

    /// A chain of three rungs: `b` reads `a`, `c` reads `b`.
    const CHAIN: &str = "LDmicro0.1\nCYCLE=10000\n\nIO LIST\n    Xa at 0\n    Yb at 0\n    Yc at 0\n    Yd at 0\nEND\n\nPROGRAM\nRUNG\n    CONTACTS Xa 0\n    COIL Yb 0 0 0\nEND\nRUNG\n    CONTACTS Yb 0\n    COIL Yc 0 0 0\nEND\nRUNG\n    CONTACTS Yc 0\n    CONTACTS Yd 0\n    COIL Yd 0 0 0\nEND\n";

    #[test]
    fn the_deepest_property_comes_first_and_ties_keep_their_order() {
        let mut sources = crate::diag::Sources::new();
        let file = sources.add("chain.ld", CHAIN.to_string());
        let program = crate::ladder::read_ldmicro(&sources, file).expect("parses");
        let compiled = crate::ladder::compile(&program).expect("compiles");
        let name = |n: &str| crate::term::name(n);
        let (a, b, c) = (name("Xa"), name("Yb"), name("Yc"));
        let goals = [[&a, &a], [&c, &a], [&b, &a], [&b, &b]];
        assert_eq!(Shared::default().deepest_first(&compiled, &goals), vec![1, 2, 3, 0]);
    }
}
