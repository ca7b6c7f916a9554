//! Induction over scans (untrusted search): an inductive strengthening of a program property, found Houdini-style over clauses of the program's state bits, and the certificate `Proof::Induction` the kernel checks.
//!
//! A property `f ⇒ g` of a program often holds only because of what earlier scans did.
//! The search looks for an invariant `Inv = C1 · C2 · … · Cn`, where `C1` is the goal
//! itself (`¬f + g`) and the other clauses are candidates over the program's *state
//! bits* (the names `X` whose previous value `pre X` the equations read): every `X`,
//! `¬X`, and every disjunction of two of them. Candidates are pruned on the Boolean
//! skeleton (the cone's equations and the laws' instances, SAT by varisat):
//!
//! 1. *base*: a model of the hypotheses at the first scan (each `pre f` replaced by
//!    the value `f` has before it) where some candidate is 0 removes every candidate
//!    0 in it, until no such model exists;
//! 2. *step*: a model where every candidate held at the previous scan (`pre Ci`, with
//!    `pre` pushed down to the state bits) and one fails now removes every candidate
//!    that fails in it, until the set is inductive.
//!
//! If the goal's clause survives, the set is minimised (a clause goes if the rest is
//! still inductive) and the certificate is built: a lemma `inv: Inv = 1*` by
//! [`Proof::Induction`] (base and step by case splits on the skeleton, the step after
//! the chain `pre Inv = …` of `pre` laws), and the goal from the lemma by cases.
//! Everything is re-checked by the kernel; a failure anywhere is "no proof".

use std::collections::{BTreeSet, HashMap};
use std::time::Instant;

use super::timing::{self, Chains};
use super::{Budget, Context, Method, Obligation, Proved, boolean, constraint, constraints_for};
use crate::kernel::{Axiom, Certificate, Proof, Rel, Rule, Source, Step, Use};
use crate::term::{
    Expr, Id, Language as _, Term, and, and_not, at_first_scan, constant, mentions_pre, not, or,
    root, subterm,
};

/// At most this many state bits take part in candidate clauses.
const MAX_STATE: usize = 16;

/// At most this many rounds of pruning (each one SAT call).
const MAX_ROUNDS: usize = 200;

/// The name the invariant lemma has in certificates and traces.
pub const LEMMA: &str = "inv";

/// Why the search found no inductive invariant: how many candidate clauses over how
/// many state bits it started from, where it stopped, and, when the step failed, the
/// state it failed from.
#[derive(Clone, Debug)]
pub struct Stalled {
    /// State bits the candidate clauses range over.
    pub state_bits: usize,
    /// Candidate clauses at the start (the goal's own included).
    pub candidates: usize,
    /// Candidate clauses still standing when the search stopped.
    pub kept: usize,
    /// Where it stopped.
    pub stop: Stop,
    /// When the step failed: the state bits (the goal's first) with their values at the
    /// previous scan and now, in a model where the kept clauses held before and the goal
    /// fails now.
    pub step_model: Vec<(String, Option<bool>, Option<bool>)>,
    /// When the search also read timer chains: how many chain atoms.
    pub timers: Option<usize>,
}

/// Where the invariant search stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stop {
    /// Not a program's context: no induction over scans.
    NoScans,
    /// The goal fails at the first scan on the Boolean skeleton.
    Base,
    /// The step breaks the goal from a state where every kept clause held.
    Step,
    /// A pruning round removed nothing while the set was not inductive.
    NoProgress,
    /// The rounds or the time ran out.
    Limit,
    /// An invariant was found but its certificate was not built or not accepted.
    Certificate,
}

impl std::fmt::Display for Stalled {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (n, bits, kept) = (self.candidates, self.state_bits, self.kept);
        let s = super::plural(bits, "", "s");
        let mut over = format!("{n} candidate clauses over {bits} state bit{s}");
        if let Some(t) = self.timers {
            over.push_str(&format!(" and {t} timer scans"));
        }
        match self.stop {
            Stop::NoScans => write!(f, "not available for free signals"),
            Stop::Base => write!(f, "{over}; the goal fails at the first scan of the skeleton"),
            Stop::Step => write!(
                f,
                "{over}; the step fails: from a state where {kept} of them (the goal's among them) held, one scan breaks the goal"
            ),
            Stop::NoProgress => write!(f, "{over}; pruning stalled with {kept} clauses left"),
            Stop::Limit => write!(f, "{over}; stopped at its round or time limit ({kept} left)"),
            Stop::Certificate => {
                write!(
                    f,
                    "{over}; an invariant of {kept} clauses was found, its certificate was not"
                )
            }
        }
    }
}

/// Tries to prove `goal` by induction over scans (a program's context only); the
/// invariant is the certificate's lemma [`LEMMA`].
pub fn prove(
    ctx: &Context,
    goal: &Obligation,
    budget: Budget,
    deadline: Instant,
) -> Result<Proved, Stalled> {
    prove_as(ctx, goal, budget, deadline, LEMMA)
}

/// [`prove`], with the invariant lemma called `lemma`.
pub fn prove_as(
    ctx: &Context,
    goal: &Obligation,
    budget: Budget,
    deadline: Instant,
    lemma: &str,
) -> Result<Proved, Stalled> {
    let chains = ctx.cycle.as_ref().filter(|_| ctx.scans).map(|cycle| {
        let cone = ctx.cone(&[&goal.lhs, &goal.rhs], None);
        let mut terms: Vec<&Expr> = vec![&goal.lhs, &goal.rhs];
        terms.extend(cone.iter().flat_map(|h| [&h.lhs, &h.rhs]));
        let mut chains = timing::chains(&terms, cycle, lemma);
        chains.add_memories(&memories(goal), lemma);
        chains
    });
    let chains = chains.filter(|c| !c.chains.is_empty());
    // With timers, a third of the time without them first (the shorter invariant).
    let plain = match &chains {
        Some(_) => Instant::now() + deadline.saturating_duration_since(Instant::now()) / 3,
        None => deadline,
    };
    let stalled = match search(ctx, goal, budget, plain, lemma, None) {
        Ok(proved) => return Ok(proved),
        Err(stalled) => stalled,
    };
    // Timers: the same search, with how long each timer's input has been on.
    match chains {
        Some(chains) if Instant::now() < deadline => {
            // The report keeps the plain search's failed step unless this one has its own.
            search(ctx, goal, budget, deadline, lemma, Some(&chains)).map_err(|timed| {
                if timed.stop != Stop::Step && stalled.stop == Stop::Step { stalled } else { timed }
            })
        }
        _ => Err(stalled),
    }
}

/// The Houdini search, with timer chains when given.
fn search(
    ctx: &Context,
    goal: &Obligation,
    budget: Budget,
    deadline: Instant,
    lemma: &str,
    chains: Option<&Chains>,
) -> Result<Proved, Stalled> {
    let mut stalled = Stalled {
        state_bits: 0,
        candidates: 0,
        kept: 0,
        stop: Stop::NoScans,
        step_model: Vec::new(),
        timers: chains.map(|c| c.atoms().iter().map(Vec::len).sum()),
    };
    if !ctx.scans {
        return Err(stalled);
    }
    let cone: Vec<Axiom> = ctx.cone(&[&goal.lhs, &goal.rhs], None).into_iter().cloned().collect();
    let expanded = expand_atoms(&cone, goal);
    // A goal over comparison atoms reads integers' bits (see below).
    let integers = expanded.lhs != goal.lhs || expanded.rhs != goal.rhs;
    let mut goals = goal_clauses(&expanded);
    let inputs = chains.map(Chains::input_names).unwrap_or_default();
    let read = read_before(&cone);
    // A name the goal reads the previous value of is state too (`Sample · pre Sample`),
    // though no equation reads it so.
    let mut with_goal = read.clone();
    with_goal.extend(pre_names(&[&goal.lhs, &goal.rhs]));
    let state = state_bits(with_goal, goal, &inputs);
    let mut more = clauses(&state);
    // Which of `more` are disjunctions of two literals (after the literals themselves).
    let pairs = 2 * state.len()..more.len();
    // The program's bounds of its integers, where the cone reads every bit they read.
    more.extend(ctx.hints.iter().filter(|h| names_in(h).iter().all(|n| read.contains(n))).cloned());
    if let Some(chains) = chains {
        goals = goals.iter().map(|g| chains.unfold(g)).collect();
        more.extend(timing::clauses(chains, &state, &inputs, &memories(goal)));
    }
    let mut candidates: Vec<Clause> = goals.iter().map(|g| Clause::new(g, true)).collect();
    candidates.extend(
        more.iter()
            .enumerate()
            .map(|(i, c)| Clause { pair: pairs.contains(&i), ..Clause::new(c, false) }),
    );
    stalled.state_bits = state.len();
    stalled.candidates = candidates.len();
    let stop = |mut stalled: Stalled, stop: Stop, kept: usize| {
        stalled.stop = stop;
        stalled.kept = kept;
        stalled
    };
    let first: Vec<Axiom> = cone
        .iter()
        .map(|h| Axiom::ground(h.name.clone(), at_first_scan(&h.lhs), h.rel, at_first_scan(&h.rhs)))
        .collect();
    let mut rounds = 0;
    // Base: drop what fails at the first scan.
    let mut atoms0 = boolean::Atoms::default();
    let refs: Vec<&Expr> = candidates.iter().map(|c| &c.first).collect();
    let mut base_constraints = constraints_for(ctx, &first, &refs, &mut atoms0, budget, 1);
    base_constraints.extend(chains.map(Chains::at_first).unwrap_or_default());
    let fails_first = |set: &[Clause], atoms: &mut boolean::Atoms| {
        let at_first: Vec<Expr> = set.iter().map(|c| c.first.clone()).collect();
        boolean::model_of(&not(&product(&at_first)), &base_constraints, atoms)
    };
    if let Err((why, _)) = prune(
        &mut candidates,
        &mut rounds,
        deadline,
        |c| &c.first,
        |set| fails_first(set, &mut atoms0),
    ) {
        let why = if why == Stop::Step { Stop::Base } else { why };
        return Err(stop(stalled, why, candidates.len()));
    }
    // Step: drop what is not preserved, until the rest is inductive.
    let mut atoms = boolean::Atoms::default();
    let refs: Vec<&Expr> = candidates.iter().flat_map(|c| [&c.now, &c.before]).collect();
    let mut step_constraints = constraints_for(ctx, &cone, &refs, &mut atoms, budget, 1);
    if let Some(chains) = chains {
        step_constraints.extend(chains.now.iter().chain(&chains.before).cloned());
    }
    let inductive = |set: &[Clause], atoms: &mut boolean::Atoms| {
        let now: Vec<Expr> = set.iter().map(|c| c.now.clone()).collect();
        let before: Vec<Expr> = set.iter().map(|c| c.before.clone()).collect();
        boolean::model_of(&and_not(&product(&before), &product(&now)), &step_constraints, atoms)
    };
    // The goal alone, when it is inductive: the shortest invariant, found at once.
    let alone: Vec<Clause> = candidates.iter().filter(|c| c.goal).cloned().collect();
    let all = candidates.clone();
    if inductive(&alone, &mut atoms).is_none() {
        candidates = alone;
    }
    let pruned =
        prune(&mut candidates, &mut rounds, deadline, |c| &c.now, |set| inductive(set, &mut atoms));
    if let Err((why, model)) = pruned {
        // The goal's names first (state bits or not), then the other state bits.
        let mut shown: Vec<String> = Vec::new();
        for side in [&goal.lhs, &goal.rhs] {
            for t in side.as_ref() {
                if let Term::Name(n) = t
                    && !shown.iter().any(|s| s == n.as_str())
                {
                    shown.push(n.as_str().to_string());
                }
            }
        }
        shown.extend(state.iter().filter(|n| !shown.contains(n)).cloned().collect::<Vec<_>>());
        stalled.step_model = if why != Stop::Step {
            Vec::new()
        } else {
            shown
                .iter()
                .map(|n| {
                    let x = crate::term::name(n);
                    let at = |e: &Expr| model.get(&e.to_string()).copied();
                    (n.clone(), at(&push_pre(&pre(&x)).0), at(&x))
                })
                .filter(|(_, before, now)| before.is_some() || now.is_some())
                .collect()
        };
        return Err(stop(stalled, why, candidates.len()));
    }
    // Grow from the goal's clauses: while they are not inductive, the step's model starts
    // from a state the inductive set excludes, so one of its clauses is 0 there before the
    // scan; add it (those that are not pairs first). A small invariant is then found in a
    // few calls, where dropping clauses one at a time from the large set costs one each.
    let mut core: Vec<Clause> = candidates.iter().filter(|c| c.goal).cloned().collect();
    while !core.is_empty() && Instant::now() < deadline {
        let Some(model) = inductive(&core, &mut atoms) else {
            candidates = core;
            break;
        };
        let fails = |c: &Clause| {
            !core.iter().any(|k| k.now == c.now) && value(&c.before, &model) == Some(false)
        };
        let add: Vec<Clause> =
            match candidates.iter().filter(|c| !c.pair && fails(c)).cloned().collect::<Vec<_>>() {
                singles if !singles.is_empty() => singles,
                _ => candidates.iter().filter(|c| fails(c)).take(1).cloned().collect(),
            };
        if add.is_empty() {
            break;
        }
        core.extend(add);
    }
    // Half the time left (one SAT call per clause): with timer chains every clause kept
    // is proved on its own, so each one dropped saves a case proof.
    let minimise_until = Instant::now() + deadline.saturating_duration_since(Instant::now()) / 2;
    // Minimise: a clause goes when the others are still inductive; then one of the
    // goal's own clauses when the others also imply it (a shorter invariant).
    // (With timer chains the goal's clauses stay: the goal is read from the invariant
    // through the chains' lemmas at the current scan only.)
    let passes: &[bool] = if chains.is_some() { &[false] } else { &[false, true] };
    for &goals_now in passes {
        let mut k = 0;
        while k < candidates.len() && candidates.len() > 1 {
            // Minimising is optional: the set is already inductive.
            if Instant::now() > minimise_until {
                break;
            }
            if candidates[k].goal != goals_now {
                k += 1;
                continue;
            }
            let mut fewer = candidates.clone();
            let dropped = fewer.remove(k);
            let rest: Vec<Expr> = fewer.iter().map(|c| c.now.clone()).collect();
            let implied = !dropped.goal
                || boolean::model_of(
                    &and_not(&product(&rest), &dropped.now),
                    &step_constraints,
                    &mut atoms,
                )
                .is_none();
            if implied && inductive(&fewer, &mut atoms).is_none() {
                candidates = fewer;
            } else {
                k += 1;
            }
        }
    }
    let kept = candidates.len();
    let candidates: Vec<Expr> = candidates.into_iter().map(|c| c.now).collect();
    // A minimal invariant can be inductive and still too hard to certify by cases: a
    // bound on a counter (`[C <= 10]`) is, but its step reasons through the adder's
    // carries. The largest inductive set without its two-literal clauses (its single-bit
    // facts, the counter's high bits staying 0, and the program's integer bounds) cuts
    // those case splits short.
    // (Timer chains have their own clauses and a certificate per clause.)
    let mut strengthen = || {
        if chains.is_some() {
            return None;
        }
        let mut all = all.clone();
        let pruned =
            prune(&mut all, &mut rounds, deadline, |c| &c.now, |set| inductive(set, &mut atoms));
        all.retain(|c| !c.pair);
        let stronger = pruned.is_ok() && all.len() > kept && inductive(&all, &mut atoms).is_none();
        stronger.then(|| all.into_iter().map(|c| c.now).collect::<Vec<Expr>>())
    };
    let certify = |clauses: &[Expr], deadline| {
        certificate(ctx, goal, (&cone, &first), clauses, (budget, deadline), (lemma, chains))
    };
    // Over integers the minimal set gets a third of the time left, so that the stronger
    // one still has its chance.
    let share = if integers { 3 } else { 1 };
    let first_try = Instant::now() + deadline.saturating_duration_since(Instant::now()) / share;
    let proved = certify(&candidates, first_try)
        .or_else(|| strengthen().and_then(|s| certify(&s, deadline)));
    proved.ok_or_else(|| stop(stalled, Stop::Certificate, kept))
}

/// A candidate clause: as it reads now, at the first scan, and at the previous scan
/// (`pre` pushed down to its atoms); `goal` for the goal's own clauses, `pair` for a
/// disjunction of two state-bit literals.
#[derive(Clone)]
struct Clause {
    now: Expr,
    first: Expr,
    before: Expr,
    goal: bool,
    pair: bool,
}

impl Clause {
    fn new(c: &Expr, goal: bool) -> Clause {
        Clause {
            now: c.clone(),
            first: at_first_scan(c),
            before: push_pre(&pre(c)).0,
            goal,
            pair: false,
        }
    }
}

/// Removes every candidate that is 0 in a model `model_of` finds, until it finds none;
/// an error when a goal clause goes ([`Stop::Step`], with that model), nothing goes, or
/// the limits are reached.
fn prune(
    candidates: &mut Vec<Clause>,
    rounds: &mut usize,
    deadline: Instant,
    reading: fn(&Clause) -> &Expr,
    mut model_of: impl FnMut(&[Clause]) -> Option<HashMap<String, bool>>,
) -> Result<(), (Stop, HashMap<String, bool>)> {
    loop {
        *rounds += 1;
        if *rounds > MAX_ROUNDS || Instant::now() > deadline {
            return Err((Stop::Limit, HashMap::new()));
        }
        let Some(model) = model_of(candidates) else { return Ok(()) };
        let before = candidates.len();
        let fails = |c: &Clause| value(reading(c), &model) == Some(false);
        if candidates.iter().any(|c| c.goal && fails(c)) {
            return Err((Stop::Step, model));
        }
        candidates.retain(|c| !fails(c));
        if candidates.len() == before {
            return Err((Stop::NoProgress, model));
        }
    }
}

/// The goal with every comparison atom (`[Cparts <= 10]`, a name defined by an equation
/// of the cone over the integers' bits) replaced by its definition: the invariant then
/// reads the bits, whose values at the previous scan the equations relate to the new.
fn expand_atoms(cone: &[Axiom], goal: &Obligation) -> Obligation {
    let mut sigma = std::collections::BTreeMap::new();
    for h in cone {
        if let Term::Name(n) = &h.lhs[root(&h.lhs)]
            && n.as_str().starts_with('[')
            && h.rel == Rel::Eq
            && !mentions_pre(&h.rhs)
        {
            sigma.insert(*n, h.rhs.clone());
        }
    }
    if sigma.is_empty() {
        return goal.clone();
    }
    let expand = |e: &Expr| crate::term::instantiate(e, &sigma).unwrap_or_else(|| e.clone());
    Obligation { lhs: expand(&goal.lhs), rhs: expand(&goal.rhs), ..goal.clone() }
}

/// The goal's clauses: `¬f + g` (and `¬g + f` for an equation).
fn goal_clauses(goal: &Obligation) -> Vec<Expr> {
    let mut out = vec![or(&not(&goal.lhs), &goal.rhs)];
    if goal.rel == Rel::Eq {
        out.push(or(&not(&goal.rhs), &goal.lhs));
    }
    out
}

/// The state bits: names whose previous value the cone reads (`read`), the goal's names first,
/// then `also` (the inputs of timer chains).
fn state_bits(read: BTreeSet<String>, goal: &Obligation, also: &BTreeSet<String>) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for side in [&goal.lhs, &goal.rhs] {
        for t in side.as_ref() {
            if let Term::Name(n) = t
                && read.contains(n.as_str())
                && !out.iter().any(|o| o == n.as_str())
            {
                out.push(n.as_str().to_string());
            }
        }
    }
    out.extend(also.iter().filter(|n| !out.contains(n)).cloned().collect::<Vec<_>>());
    out.extend(read.into_iter().filter(|n| !out.contains(n)).collect::<Vec<_>>());
    out.truncate(MAX_STATE);
    out
}

/// The names whose previous value (`pre X`) the cone reads.
fn read_before(cone: &[Axiom]) -> BTreeSet<String> {
    pre_names(&cone.iter().flat_map(|h| [&h.lhs, &h.rhs]).collect::<Vec<_>>())
}

/// The names `X` of the terms' `pre X`.
fn pre_names(terms: &[&Expr]) -> BTreeSet<String> {
    let mut read: BTreeSet<String> = BTreeSet::new();
    for side in terms {
        for t in side.as_ref() {
            if let Term::Pre(a) = t
                && let Term::Name(n) = &side[*a]
            {
                read.insert(n.as_str().to_string());
            }
        }
    }
    read
}

/// The names a term mentions.
fn names_in(e: &Expr) -> BTreeSet<String> {
    e.as_ref()
        .iter()
        .filter_map(|t| match t {
            Term::Name(n) => Some(n.as_str().to_string()),
            _ => None,
        })
        .collect()
}

/// The memories (`SR`, `RS`) of the goal's sides, outermost first: a pattern's request
/// still waiting for its answer is one.
fn memories(goal: &Obligation) -> Vec<Expr> {
    let mut out: Vec<Expr> = Vec::new();
    for side in [&goal.lhs, &goal.rhs] {
        for (i, t) in side.as_ref().iter().enumerate().rev() {
            if matches!(t, Term::Sr(_) | Term::Rs(_)) {
                let m = subterm(side, Id::from(i));
                if !out.contains(&m) {
                    out.push(m);
                }
            }
        }
    }
    out
}

/// Every literal and every disjunction of two literals over the state bits.
fn clauses(state: &[String]) -> Vec<Expr> {
    let lits: Vec<Expr> =
        state.iter().flat_map(|n| [crate::term::name(n), not(&crate::term::name(n))]).collect();
    let mut out = lits.clone();
    for i in 0..lits.len() {
        for j in (i + 1)..lits.len() {
            if i / 2 != j / 2 {
                out.push(or(&lits[i], &lits[j]));
            }
        }
    }
    out
}

/// `c1 · c2 · …` (`1*` for none).
fn product(cs: &[Expr]) -> Expr {
    cs.iter().skip(1).fold(cs.first().cloned().unwrap_or_else(|| constant(true)), |a, c| and(&a, c))
}

/// `pre e`.
pub fn pre(e: &Expr) -> Expr {
    let mut out = e.clone();
    out.add(Term::Pre(root(e)));
    out
}

/// The value of a Boolean combination of atoms under a model (by the atoms' printed form).
fn value(e: &Expr, model: &HashMap<String, bool>) -> Option<bool> {
    fn go(e: &Expr, id: Id, model: &HashMap<String, bool>) -> Option<bool> {
        Some(match &e[id] {
            Term::Zero => false,
            Term::One => true,
            Term::Not(a) => !go(e, *a, model)?,
            Term::And([a, b]) => go(e, *a, model)? && go(e, *b, model)?,
            Term::Or([a, b]) => go(e, *a, model)? || go(e, *b, model)?,
            _ => *model.get(&subterm(e, id).to_string())?,
        })
    }
    go(e, root(e), model)
}

/// `pre` pushed down through `·`, `+`, `¬` and the constants to the atoms, with the
/// chain of `pre` law steps from `e` to the result.
pub fn push_pre(e: &Expr) -> (Expr, Vec<Step>) {
    let mut whole = e.clone();
    let mut steps = Vec::new();
    while let Some(path) = pushable(&whole, root(&whole), &mut Vec::new()) {
        let at = locate(&whole, &path);
        let Term::Pre(inner) = whole[at] else { break };
        let (law, replacement) = match &whole[inner] {
            Term::Zero => ("pre_zero", constant(false)),
            Term::One => ("pre_one", constant(true)),
            Term::Not(a) => ("pre_not", not(&pre(&subterm(&whole, *a)))),
            Term::And([a, b]) => {
                ("pre_and", and(&pre(&subterm(&whole, *a)), &pre(&subterm(&whole, *b))))
            }
            Term::Or([a, b]) => {
                ("pre_or", or(&pre(&subterm(&whole, *a)), &pre(&subterm(&whole, *b))))
            }
            _ => break,
        };
        whole = super::normalize::replace_at(&whole, &path, &replacement);
        steps.push(Step {
            path,
            rule: Rule::Cite(Source::Law, law.into(), Use::Forward),
            after: whole.clone(),
            subst: Vec::new(),
            premises: Vec::new(),
        });
    }
    (whole, steps)
}

/// The path to the outermost `pre` whose argument is `·`, `+`, `¬` or a constant.
fn pushable(e: &Expr, id: Id, path: &mut Vec<usize>) -> Option<Vec<usize>> {
    if let Term::Pre(a) = &e[id]
        && matches!(e[*a], Term::Zero | Term::One | Term::Not(_) | Term::And(_) | Term::Or(_))
    {
        return Some(path.clone());
    }
    for (i, c) in e[id].children().iter().enumerate() {
        path.push(i);
        let found = pushable(e, *c, path);
        path.pop();
        if found.is_some() {
            return found;
        }
    }
    None
}

fn locate(e: &Expr, path: &[usize]) -> Id {
    path.iter().fold(root(e), |id, &i| e[id].children()[i])
}

/// The certificate: the invariant lemma by induction, then the goal from it by cases.
/// The hypotheses are `cone` (at every scan) and `first` (as they read at the first scan).
fn certificate(
    ctx: &Context,
    goal: &Obligation,
    (cone, first): (&[Axiom], &[Axiom]),
    clauses: &[Expr],
    (budget, deadline): (Budget, Instant),
    (name, chains): (&str, Option<&Chains>),
) -> Option<Proved> {
    let inv = product(clauses);
    let leaves = budget.cases;
    // Base: `1* ⇒ Inv` at the first scan, from `1*·¬Inv = 0*`.
    let inv0 = at_first_scan(&inv);
    let one = constant(true);
    let base_goal = and_not(&one, &inv0);
    let mut atoms = boolean::Atoms::default();
    let mut base_c = constraints_for(ctx, first, &[&base_goal], &mut atoms, budget, 1);
    base_c.extend(chains.map(Chains::at_first).unwrap_or_default());
    let base = boolean::prove_zero(&base_goal, &base_c, &mut atoms, leaves, deadline).ok()?;
    // Step: `pre Inv = P` by the laws of `pre`, then `P ⇒ Inv` by cases.
    let (p, chain) = push_pre(&pre(&inv));
    let step_goal = and_not(&p, &inv);
    let mut atoms = boolean::Atoms::default();
    let mut step_c = constraints_for(ctx, cone, &[&step_goal], &mut atoms, budget, 1);
    if let Some(chains) = chains {
        step_c.extend(chains.now.iter().chain(&chains.before).cloned());
    }
    // With timer chains the clauses are many: one case split each.
    let mut lemmas = chains.map(|c| c.lemmas.clone()).unwrap_or_default();
    let implied = if chains.is_some() {
        let prove = |zero: &Expr| {
            let mut atoms = boolean::Atoms::default();
            boolean::prove_zero(zero, &step_c, &mut atoms, leaves, deadline).ok()
        };
        let (steps, proof) = timing::implies_clauses(&p, clauses, name, prove)?;
        lemmas.extend(steps);
        proof
    } else {
        let step = boolean::prove_zero(&step_goal, &step_c, &mut atoms, leaves, deadline).ok()?;
        Proof::ImpliesByZero(Box::new(step))
    };
    let step =
        Proof::Trans(Box::new(Proof::Chain { start: pre(&inv), steps: chain }), Box::new(implied));
    let lemma = Proof::Induction {
        inv: inv.clone(),
        base: Box::new(Proof::ImpliesByZero(Box::new(base))),
        step: Box::new(step),
    };
    // The goal from `inv = 1*`.
    let mut uses = vec![boolean::Constraint {
        source: Source::Lemma,
        name: name.into(),
        ..constraint(&Axiom::ground(name, inv.clone(), Rel::Eq, one.clone()))
    }];
    uses.extend(
        cone.iter().filter(|h| !mentions_pre(&h.lhs) && !mentions_pre(&h.rhs)).map(constraint),
    );
    if let Some(chains) = chains {
        uses.extend(chains.now.iter().cloned());
    }
    let main = super::both_ways(goal, &mut |zero| {
        let mut atoms = boolean::Atoms::default();
        boolean::prove_zero(zero, &uses, &mut atoms, leaves, deadline)
    })
    .ok()?;
    lemmas.push((name.into(), lemma));
    let lemmas = timing::cited(lemmas, &main);
    let certificate = Certificate { lemmas, main: Some(main) };
    let theorem = ctx.kernel.check_goal(&certificate, &goal.lhs, goal.rel, &goal.rhs).ok()?;
    Some(Proved {
        theorem,
        certificate,
        method: Method::Induction,
        lines: vec![],
        shared: Default::default(),
    })
}
