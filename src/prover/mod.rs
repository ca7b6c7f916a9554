//! The prover: untrusted search that returns certificates for the kernel to check.
//!
//! [`prove`] restricts the hypotheses to the goal's cone of influence, tries
//! equality saturation in growing rule sets ([`saturate`]) and turns the
//! explanation into a readable chain ([`normalize`], [`explain`]). If that does
//! not close the goal, the Boolean skeleton is decided by a SAT solver and
//! proved by case splits ([`boolean`]). Every certificate is checked by the
//! kernel before the outcome says "proved"; otherwise the outcome is unknown,
//! with the reason and, when the skeleton has one, a candidate countermodel.

pub mod boolean;
pub mod explain;
pub mod induction;
pub mod lemmas;
pub mod normalize;
pub mod saturate;
pub mod timing;

use std::collections::BTreeSet;
use std::time::{Duration, Instant};

use crate::kernel::{self, Axiom, Certificate, Kernel, KernelError, Proof, Rel, Source, Theorem};
use crate::term::{Delay, Expr, Symbol, Term, and_not, mentions_pre, root};

use saturate::{Closed, Limits};

/// A goal `lhs rel rhs` about whole signals.
#[derive(Clone, Debug)]
pub struct Obligation {
    /// Left side.
    pub lhs: Expr,
    /// `=` or `⇒`.
    pub rel: Rel,
    /// Right side.
    pub rhs: Expr,
}

/// A checked proof.
#[derive(Clone, Debug)]
pub struct Proved {
    /// The kernel's theorem.
    pub theorem: Theorem,
    /// The certificate the kernel checked.
    pub certificate: Certificate,
    /// Which method found it.
    pub method: Method,
    /// The shared lemmas it cites ([`lemmas`]), by name.
    pub shared: kernel::Lemmas,
    /// How many atomic steps of the main chain form each printed line (saturation proofs).
    pub lines: Vec<usize>,
}

/// The method that found a proof.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Equality saturation with the laws and hypotheses.
    Saturation,
    /// Case splits on the Boolean skeleton.
    CaseSplit,
    /// Induction over scans with an invariant found by the search.
    Induction,
}

/// How a proof attempt ended.
#[derive(Clone, Debug)]
pub enum Outcome {
    /// The kernel checked a certificate of the goal.
    Proved(Box<Proved>),
    /// No proof. `candidate` is a model of the Boolean skeleton (atom values) when the
    /// search found one: a *possible* counterexample, not a confirmed one.
    Unknown {
        /// What was tried and how far it got: a few short lines (see [`clip`]), never
        /// a dump of terms.
        reason: String,
        /// Atom values under which every constraint holds and the goal fails.
        candidate: Option<Candidate>,
        /// Why induction over scans found no invariant, when it was tried.
        induction: Option<Box<induction::Stalled>>,
    },
}

/// Limits of one proof attempt. Every attempt ends within them.
#[derive(Clone, Copy, Debug)]
pub struct Budget {
    /// Wall-clock time for the whole attempt.
    pub time: Duration,
    /// E-nodes per saturation run.
    pub nodes: usize,
    /// Leaves of a case-split proof.
    pub cases: usize,
}

impl Default for Budget {
    fn default() -> Self {
        Budget { time: Duration::from_secs(10), nodes: 60_000, cases: 4_096 }
    }
}

/// Everything a proof attempt may use.
pub struct Context {
    /// The checker with the laws and hypotheses.
    pub kernel: Kernel,
    /// The laws (also in the kernel), for building search rules.
    pub laws: Vec<Axiom>,
    rules: saturate::RuleSet,
    /// The laws' temporal pieces, for their instances on atoms.
    law_index: boolean::LawIndex,
    /// Side conditions already attempted, with their proofs (shared by every goal).
    premises: std::sync::Mutex<std::collections::HashMap<String, Option<Proof>>>,
    /// Which hypotheses concern each signal (for cones of influence).
    index: ConeIndex,
    /// What literals force through the hypotheses, with the lemmas proved so far.
    lemmas: lemmas::Store,
    /// Whether proofs may cite those shared lemmas (a proof script's proofs stand
    /// alone, so its checker's context does not).
    pub shared_lemmas: bool,
    /// A program's context: signals are scan runs (induction over scans is available).
    pub scans: bool,
    /// A program's scan cycle, for the laws that need it (see [`kernel::CYCLE`]).
    pub cycle: Option<Delay>,
    /// Candidate invariants the program suggests (bounds of its integers), over its
    /// state bits: the invariant search tries them beside its own clauses.
    pub hints: Vec<Expr>,
}

impl Context {
    /// A context over these laws and hypotheses about free signals; fails if the kernel
    /// refuses an axiom.
    pub fn new(laws: Vec<Axiom>, hypotheses: Vec<Axiom>) -> Result<Context, KernelError> {
        Context::with_scans(laws, hypotheses, None)
    }

    /// A context for the scans of a program with this cycle (signals are scan runs, with
    /// `pre` and induction over scans) or, with `None`, for free signals.
    pub fn with_scans(
        laws: Vec<Axiom>,
        hypotheses: Vec<Axiom>,
        cycle: Option<Delay>,
    ) -> Result<Context, KernelError> {
        let index = ConeIndex::new(&hypotheses);
        let scans = cycle.is_some();
        // The kernel keeps the one copy of the hypotheses.
        let kernel = match &cycle {
            Some(c) => Kernel::for_scans(laws.clone(), hypotheses, c.clone())?,
            None => Kernel::new(laws.clone(), hypotheses)?,
        };
        let rules = saturate::RuleSet::new(&laws);
        // The search uses the laws of `pre` only where signals are scan runs.
        let laws = if scans {
            laws
        } else {
            laws.into_iter().filter(|l| !mentions_pre(&l.lhs) && !mentions_pre(&l.rhs)).collect()
        };
        let law_index = boolean::LawIndex::new(&laws);
        let premises = Default::default();
        let lemmas = lemmas::Store::default();
        let shared_lemmas = true;
        Ok(Context {
            kernel,
            laws,
            rules,
            law_index,
            premises,
            index,
            lemmas,
            shared_lemmas,
            scans,
            cycle,
            hints: Vec::new(),
        })
    }

    /// The hypotheses, in the order given (the kernel's).
    pub fn hypotheses(&self) -> &[Axiom] {
        self.kernel.hypotheses()
    }

    /// The hypotheses in the cone of influence of `terms` (see [`cone_of_influence`]),
    /// at most `depth` steps of signal dependence away when a depth is given.
    pub fn cone(&self, terms: &[&Expr], depth: Option<usize>) -> Vec<&Axiom> {
        self.index.cone(self.hypotheses(), terms, depth, false, None)
    }

    /// Does the cone of influence of `terms` hold more than `n` hypotheses? (Stops
    /// looking once it has found `n + 1`.)
    fn cone_exceeds(&self, terms: &[&Expr], n: usize) -> bool {
        self.index.cone(self.hypotheses(), terms, None, false, Some(n)).len() > n
    }

    /// A tighter cone for goal-directed attempts: a bound `X ⇒ e` or `e ⇒ X` of a signal
    /// `X` that has a definition `X = …` joins only when `X` itself is reached (while
    /// `X` is outside, the bound constrains nothing the goal reads).
    fn near_cone(&self, terms: &[&Expr], depth: usize) -> Vec<&Axiom> {
        self.index.cone(self.hypotheses(), terms, Some(depth), true, None)
    }
}

/// Which hypotheses concern each signal: a definition `Q = …` concerns `Q`, any other
/// hypothesis every signal it mentions (`concerns`); for the tighter cone, a bound of a
/// defined signal concerns that signal only (`anchored`). Built once per context.
struct ConeIndex {
    concerns: std::collections::HashMap<Symbol, Vec<usize>>,
    anchored: std::collections::HashMap<Symbol, Vec<usize>>,
    mentions: Vec<Vec<Symbol>>,
    /// The hypotheses that mention each signal.
    mentioning: std::collections::HashMap<Symbol, Vec<usize>>,
}

impl ConeIndex {
    fn new(hypotheses: &[Axiom]) -> ConeIndex {
        let definition = |h: &Axiom| match (&h.lhs[root(&h.lhs)], h.rel) {
            (Term::Name(q), Rel::Eq) => Some(*q),
            _ => None,
        };
        let defined: BTreeSet<Symbol> = hypotheses.iter().filter_map(definition).collect();
        let mut concerns: std::collections::HashMap<Symbol, Vec<usize>> = Default::default();
        let mut anchored: std::collections::HashMap<Symbol, Vec<usize>> = Default::default();
        let mut mentioning: std::collections::HashMap<Symbol, Vec<usize>> = Default::default();
        let mut mentions = Vec::with_capacity(hypotheses.len());
        for (i, h) in hypotheses.iter().enumerate() {
            let mut named = BTreeSet::new();
            names(&h.lhs, &mut named);
            names(&h.rhs, &mut named);
            let bound_of = match (&h.lhs[root(&h.lhs)], &h.rhs[root(&h.rhs)], h.rel) {
                (Term::Name(q), _, Rel::Implies) | (_, Term::Name(q), Rel::Implies)
                    if defined.contains(q) =>
                {
                    Some(*q)
                }
                _ => None,
            };
            match definition(h) {
                Some(q) => {
                    concerns.entry(q).or_default().push(i);
                    anchored.entry(q).or_default().push(i);
                }
                None => {
                    named.iter().for_each(|n| concerns.entry(*n).or_default().push(i));
                    match bound_of {
                        Some(q) => anchored.entry(q).or_default().push(i),
                        None => named.iter().for_each(|n| anchored.entry(*n).or_default().push(i)),
                    }
                }
            }
            named.iter().for_each(|n| mentioning.entry(*n).or_default().push(i));
            mentions.push(named.into_iter().collect());
        }
        ConeIndex { concerns, anchored, mentions, mentioning }
    }

    /// The hypotheses that mention a signal of `e`, in order, each once.
    fn mentioning(&self, e: &Expr) -> Vec<usize> {
        let mut named = BTreeSet::new();
        names(e, &mut named);
        let mut out: Vec<usize> =
            named.iter().filter_map(|n| self.mentioning.get(n)).flatten().copied().collect();
        out.sort_unstable();
        out.dedup();
        out
    }

    /// Breadth first from the names of `terms`, one layer per step of dependence;
    /// with a `cap`, it stops once more than `cap` hypotheses are taken.
    fn cone<'a>(
        &self,
        hypotheses: &'a [Axiom],
        terms: &[&Expr],
        depth: Option<usize>,
        tight: bool,
        cap: Option<usize>,
    ) -> Vec<&'a Axiom> {
        let index = if tight { &self.anchored } else { &self.concerns };
        let mut reached = BTreeSet::new();
        for t in terms {
            names(t, &mut reached);
        }
        let mut frontier: Vec<Symbol> = reached.iter().copied().collect();
        let mut taken = BTreeSet::new();
        let mut layer = 0;
        while !frontier.is_empty() && depth.is_none_or(|d| layer < d) {
            let mut next = Vec::new();
            for n in &frontier {
                for &i in index.get(n).map_or(&[][..], Vec::as_slice) {
                    if taken.insert(i) {
                        next.extend(self.mentions[i].iter().filter(|m| reached.insert(**m)));
                        if cap.is_some_and(|c| taken.len() > c) {
                            return taken.into_iter().map(|i| &hypotheses[i]).collect();
                        }
                    }
                }
            }
            frontier = next;
            layer += 1;
        }
        taken.into_iter().map(|i| &hypotheses[i]).collect()
    }
}

fn names(e: &Expr, into: &mut BTreeSet<Symbol>) {
    for node in e.as_ref() {
        if let Term::Name(s) = node {
            into.insert(*s);
        }
    }
}

/// The hypotheses in the cone of influence of `terms`: definitions `Q = …` of a
/// signal `Q` the cone reaches, and any other hypothesis that mentions one, in the
/// order of `hypotheses`. ([`Context::cone`] does the same with an index built once.)
pub fn cone_of_influence<'a>(hypotheses: &'a [Axiom], terms: &[&Expr]) -> Vec<&'a Axiom> {
    ConeIndex::new(hypotheses).cone(hypotheses, terms, None, false, None)
}

/// Tries to prove the goal within the budget.
pub fn prove(ctx: &Context, goal: &Obligation, budget: Budget) -> Outcome {
    prove_with(ctx, goal, budget, &mut |_, _| false)
}

/// A model of the Boolean skeleton: atom values under which every constraint holds
/// and the goal fails.
pub type Candidate = Vec<(Expr, bool)>;

/// When [`prove_with`] shows the skeleton's model to its caller.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Look {
    /// Before the invariant search over scans (which cannot prove a false goal, and
    /// costs more the larger the cone).
    BeforeInduction,
    /// After it, before the larger rule sets.
    BeforeLargerRules,
}

/// [`prove`], with a look at the skeleton's model before the slow part: when the
/// smallest rule set and the Boolean skeleton leave the goal open and the skeleton
/// has a model, `look` gets it, first before the invariant search, then (if that did
/// not prove the goal) before the larger rule sets. When it answers `true` (it settled
/// the goal otherwise, e.g. found a counterexample), the attempt stops there,
/// "unknown" with that candidate; otherwise the search goes on as usual.
pub fn prove_with(
    ctx: &Context,
    goal: &Obligation,
    budget: Budget,
    look: &mut dyn FnMut(&Candidate, Look) -> bool,
) -> Outcome {
    prove_at(ctx, goal, budget, 0, look)
}

/// [`prove_with`], at a nesting depth (side conditions of laws are proved one level
/// down, with the quick methods only).
fn prove_at(
    ctx: &Context,
    goal: &Obligation,
    budget: Budget,
    depth: usize,
    look: &mut dyn FnMut(&Candidate, Look) -> bool,
) -> Outcome {
    let started = Instant::now();
    let deadline = started + budget.time;
    let goal_terms = [&goal.lhs, &goal.rhs];
    // Goal-directed first: the hypotheses about the goal's own signals, then those one
    // and two steps further, … (deeper signals stay opaque atoms), widened while the
    // abstraction has a model, with the quick methods only. A proof from fewer
    // hypotheses is a proof; the kernel checks it in the whole context.
    // A side condition of a law (depth > 0) is a local fact: only the nearest
    // hypotheses are tried for it. The whole cone is collected only when these fail.
    let mut reach = 1;
    let mut previous = 0;
    while Instant::now() < deadline {
        if depth > 0 && reach > SIDE_CONDITION_REACH {
            return unknown(vec!["no quick proof from the nearest hypotheses".into()], None, None);
        }
        let small: Vec<Axiom> = ctx.near_cone(&goal_terms, reach).into_iter().cloned().collect();
        if !ctx.cone_exceeds(&goal_terms, small.len()) || (small.len() == previous && reach > 1) {
            break;
        }
        previous = small.len();
        if let Some(proved) = quick_proof(ctx, goal, &small, budget, deadline, depth) {
            return Outcome::Proved(Box::new(proved));
        }
        reach *= 2;
    }
    let cone: Vec<Axiom> = ctx.cone(&goal_terms, None).into_iter().cloned().collect();
    let limits = Limits { time: budget.time / 6, nodes: budget.nodes, ..Limits::default() };
    let mut terms: Vec<&Expr> = vec![&goal.lhs, &goal.rhs];
    terms.extend(cone.iter().flat_map(|h| [&h.lhs, &h.rhs]));
    let tiers = saturate::tiers(&ctx.rules, &terms);
    let mut saturation = String::new();
    let sets = std::cell::Cell::new(0usize);
    // Small rule sets get small limits: when they close, they close quickly.
    let tier_limits = |tier: usize| match tier {
        0 => Limits { time: budget.time / 20, nodes: budget.nodes / 6, ..limits },
        1 => Limits { time: budget.time / 10, nodes: budget.nodes / 3, ..limits },
        _ => limits,
    };
    // Whether a run stopped on its time or node limit rather than closing, saturating
    // or running out of iterations.
    let exhausted = std::cell::Cell::new(false);
    let attempt = |tier: usize, rules: &[saturate::Rule], saturation: &mut String, time| {
        let limits = Limits { time, ..tier_limits(tier) };
        let mut run = saturate::saturate(&goal.lhs, goal.rel, &goal.rhs, &cone, rules, limits);
        sets.set(sets.get() + 1);
        *saturation = format!(
            "algebra: e-graph saturation with {} rule set{} did not join the two sides (last run: {}, {} e-nodes, {} hypothes{})",
            sets.get(),
            plural(sets.get(), "", "s"),
            run.stop,
            run.nodes,
            cone.len(),
            plural(cone.len(), "is", "es"),
        );
        exhausted.set(run.hit_limit);
        let closed = run.closed?;
        certify_saturation(ctx, goal, &cone, &mut run.egraph, closed, limits)
    };
    // Cheap rule sets first: they give the shortest proofs when they close.
    if let Some(proved) = attempt(0, &tiers[0], &mut saturation, tier_limits(0).time) {
        return Outcome::Proved(Box::new(proved));
    }
    // The Boolean skeleton decides; a short case proof is accepted at once.
    let cases = prove_by_cases(ctx, goal, &cone, deadline, budget, depth);
    let boolean_only = terms.iter().all(|t| !has_temporal(t));
    match &cases {
        Ok(proved) if case_leaves(proved) <= SHORT_CASE_PROOF => {
            return Outcome::Proved(Box::new(proved.clone()));
        }
        Err(boolean::Failure::Countermodel(candidate)) if boolean_only => {
            let why = "case splits: the goal is false on constant signals".to_string();
            return unknown(vec![saturation, why], Some(candidate.clone()), None);
        }
        _ => {}
    }
    // The skeleton's model is a likely counterexample: the caller may look for one
    // before the invariant search, which on a false property can only fail, at a cost
    // that grows with the cone (one atom per scan of every timer).
    if let Err(boolean::Failure::Countermodel(candidate)) = &cases
        && depth == 0
        && look(candidate, Look::BeforeInduction)
    {
        let why = "case splits: the Boolean skeleton has a model in which the goal fails";
        return unknown(vec![saturation, why.into()], Some(candidate.clone()), None);
    }
    // What the program did in earlier scans: an inductive invariant.
    let mut stalled = None;
    if let Err(boolean::Failure::Countermodel(_)) = &cases
        && depth == 0
        && ctx.scans
    {
        // A half: with timers the search reads one atom per scan of every timer.
        let share = Instant::now() + budget.time / 2;
        match induction::prove(ctx, goal, budget, share.min(deadline)) {
            Ok(proved) => return Outcome::Proved(Box::new(proved)),
            Err(why) => stalled = Some(Box::new(why)),
        }
    }
    // The lines of an unknown: what each method tried and how far it got.
    let tried = |saturation: &str, cases: &Result<Proved, boolean::Failure>| {
        let mut lines = vec![saturation.to_string()];
        match cases {
            Err(boolean::Failure::Countermodel(model)) => lines.push(format!(
                "case splits: the Boolean skeleton ({} atoms; timers, memories and `pre` terms opaque) has a model in which the goal fails",
                model.len()
            )),
            Err(boolean::Failure::Limit(why)) => {
                lines.push(format!("case splits: stopped: {why}"));
            }
            Ok(_) => {}
        }
        if let Some(why) = &stalled {
            lines.push(format!("induction over scans: {why}"));
        }
        lines
    };
    // Larger rule sets may still find a proof (or a shorter one).
    // When a (long) case proof exists, a shorter one is looked for only in small cones:
    // in large ones the bigger rule sets rarely close and would cost the whole budget.
    if let Ok(proved) = &cases
        && cone.len() > SHORTENING_CONE
    {
        return Outcome::Proved(Box::new(proved.clone()));
    }
    if let Err(boolean::Failure::Countermodel(candidate)) = &cases
        && depth == 0
        && look(candidate, Look::BeforeLargerRules)
    {
        let lines = tried(&saturation, &cases);
        return unknown(lines, Some(candidate.clone()), stalled.clone());
    }
    // For a program, the larger rule sets share one slice of the budget, and a run
    // that stops on its time or node limit ends the escalation: the case split, the
    // invariant search and bounded model checking have had their turn, and a larger
    // set on the same hypotheses only grows the e-graph faster. A free-signal goal,
    // whose proofs are algebra, gives each larger set its own share.
    let larger_until = Instant::now() + budget.time / LARGER_TIERS_SHARE;
    for (tier, rules) in tiers.iter().enumerate().skip(1) {
        let now = Instant::now();
        // Only a shortening of a case proof: for a program, the larger sets rarely
        // give one and would cost their whole slice.
        let shortening = cases.is_ok();
        let spent = ctx.scans && (shortening || exhausted.get() || now >= larger_until);
        if now > deadline || depth > 0 || (tier > 1 && spent) {
            break;
        }
        let time = match tier {
            1 => tier_limits(1).time,
            _ if ctx.scans => larger_until - now,
            _ => budget.time / 4,
        };
        if let Some(proved) = attempt(tier, rules, &mut saturation, time) {
            let better = match &cases {
                Ok(c) => case_leaves(c) > proved.lines.len(),
                Err(_) => true,
            };
            if better {
                return Outcome::Proved(Box::new(proved));
            }
            break;
        }
    }
    let lines = tried(&saturation, &cases);
    match cases {
        Ok(proved) => Outcome::Proved(Box::new(proved)),
        Err(boolean::Failure::Countermodel(candidate)) => unknown(lines, Some(candidate), stalled),
        Err(boolean::Failure::Limit(_)) => unknown(lines, None, stalled),
    }
}

/// `one` when `n` is 1, else `many`: the ending of a counted word.
pub(crate) fn plural(n: usize, one: &'static str, many: &'static str) -> &'static str {
    if n == 1 { one } else { many }
}

/// The longest line of an unknown's reason, in characters.
pub const REASON_LINE: usize = 280;

/// `text` cut to at most `max` characters, with `…` where it was cut: a line of an
/// unknown's reason never carries a whole term dump (a kernel error, a long name list).
pub fn clip(text: &str, max: usize) -> String {
    match text.char_indices().nth(max.saturating_sub(1)) {
        Some((at, _)) if text.chars().count() > max => format!("{}…", &text[..at]),
        _ => text.to_string(),
    }
}

/// An unknown outcome from the lines of what was tried, each clipped to [`REASON_LINE`].
fn unknown(
    lines: Vec<String>,
    candidate: Option<Candidate>,
    induction: Option<Box<induction::Stalled>>,
) -> Outcome {
    let lines: Vec<String> =
        lines.iter().filter(|l| !l.is_empty()).map(|l| clip(l, REASON_LINE)).collect();
    Outcome::Unknown { reason: lines.join("\n"), candidate, induction }
}

/// The smallest rule set, then the Boolean skeleton, on the hypotheses `cone`, with a
/// small share of the budget: a proof when the goal follows quickly from them.
fn quick_proof(
    ctx: &Context,
    goal: &Obligation,
    cone: &[Axiom],
    budget: Budget,
    deadline: Instant,
    depth: usize,
) -> Option<Proved> {
    let limits = Limits { time: budget.time / 50, nodes: QUICK_NODES, ..Limits::default() };
    let mut terms: Vec<&Expr> = vec![&goal.lhs, &goal.rhs];
    terms.extend(cone.iter().flat_map(|h| [&h.lhs, &h.rhs]));
    // Side conditions (depth > 0) are decided on the Boolean skeleton alone, and so are
    // goals whose nearest hypotheses are many (a chain of implications): there the case
    // split's unit propagation walks the chain, and saturation seldom closes.
    let saturating = depth == 0 && cone.len() <= QUICK_SATURATION_CONE;
    let tiers = if saturating { saturate::tiers(&ctx.rules, &terms) } else { Vec::new() };
    if let Some(rules) = tiers.first() {
        let mut run = saturate::saturate(&goal.lhs, goal.rel, &goal.rhs, cone, rules, limits);
        if let Some(closed) = run.closed
            && let Some(proved) =
                certify_saturation(ctx, goal, cone, &mut run.egraph, closed, limits)
        {
            return Some(proved);
        }
    }
    let deadline = deadline.min(Instant::now() + budget.time / 10);
    prove_by_cases(ctx, goal, cone, deadline, budget, depth).ok()
}

/// For a program, the larger rule sets together may use `1 / LARGER_TIERS_SHARE` of
/// the budget.
const LARGER_TIERS_SHARE: u32 = 10;

/// E-nodes of a goal-directed saturation attempt: when a small cone closes the goal,
/// it does so in a small e-graph.
const QUICK_NODES: usize = 1_500;

/// Above this many nearest hypotheses, the quick methods skip saturation.
const QUICK_SATURATION_CONE: usize = 8;

/// How many steps of dependence from its own signals a side condition's proof may use.
const SIDE_CONDITION_REACH: usize = 4;

/// Above this many hypotheses in the cone, a case proof is not shortened by saturation.
const SHORTENING_CONE: usize = 40;

/// Case proofs with at most this many cases are accepted without trying larger rule sets.
const SHORT_CASE_PROOF: usize = 24;

fn has_temporal(e: &Expr) -> bool {
    e.as_ref().iter().any(crate::term::is_temporal_node)
}

/// The number of cases (leaves) of a proof's case splits (1 for a plain chain).
pub fn case_leaves(proved: &Proved) -> usize {
    fn count(p: &Proof) -> usize {
        match p {
            Proof::Chain { .. } | Proof::Refutation { .. } => 1,
            Proof::CaseSplit { one, zero, .. } => count(one) + count(zero),
            Proof::Symm(p) | Proof::ImpliesByMeet(p) | Proof::ImpliesByZero(p) => count(p),
            Proof::Antisym(p, q) | Proof::Trans(p, q) => count(p) + count(q),
            Proof::Induction { base, step, .. } => count(base) + count(step),
        }
    }
    proved.certificate.main.as_ref().map_or(0, count)
}

fn certify_saturation(
    ctx: &Context,
    goal: &Obligation,
    cone: &[Axiom],
    egraph: &mut saturate::Graph,
    closed: Closed,
    limits: Limits,
) -> Option<Proved> {
    let (_, from, to) = saturate::goal_pairs(&goal.lhs, goal.rel, &goal.rhs)
        .into_iter()
        .find(|(c, _, _)| *c == closed)?;
    let mut bridge = |x: &Expr, y: &Expr| bridge(ctx, cone, x, y, limits);
    let mut candidates = Vec::new();
    if let Ok((steps, lines)) = normalize::chain_via_normal_form(egraph, &from, &to, &mut bridge) {
        candidates.push((steps, lines));
    }
    if let Ok(steps) = explain::chain_steps(egraph, &from, &to) {
        let lines = vec![1; steps.len()];
        candidates.push((steps, lines));
    }
    candidates.sort_by_key(|(steps, lines)| (lines.len(), steps.len()));
    for (steps, lines) in candidates {
        let chain = Proof::Chain { start: from.clone(), steps };
        let main = match closed {
            Closed::Equal => chain,
            Closed::Meet => Proof::ImpliesByMeet(Box::new(chain)),
            Closed::Zero => Proof::ImpliesByZero(Box::new(chain)),
        };
        let certificate = Certificate { lemmas: vec![], main: Some(main) };
        if let Ok(theorem) = ctx.kernel.check_goal(&certificate, &goal.lhs, goal.rel, &goal.rhs) {
            return Some(Proved {
                theorem,
                certificate,
                method: Method::Saturation,
                lines,
                shared: Default::default(),
            });
        }
    }
    None
}

/// Proves `x = y` in a fresh, small e-graph (growing rule sets), for a detour-free chain.
fn bridge(
    ctx: &Context,
    cone: &[Axiom],
    x: &Expr,
    y: &Expr,
    limits: Limits,
) -> Result<Vec<kernel::Step>, explain::ExplainError> {
    let mut terms: Vec<&Expr> = vec![x, y];
    terms.extend(cone.iter().flat_map(|h| [&h.lhs, &h.rhs]));
    for rules in saturate::tiers(&ctx.rules, &terms) {
        let mut run = saturate::saturate(x, Rel::Eq, y, cone, &rules, limits);
        if run.closed.is_some() {
            return explain::chain_steps(&mut run.egraph, x, y);
        }
    }
    Err(explain::ExplainError(format!("no local proof of `{x} = {y}`")))
}

/// A hypothesis as a constraint of the Boolean skeleton.
pub fn constraint(h: &Axiom) -> boolean::Constraint {
    boolean::Constraint {
        source: Source::Hypothesis,
        name: h.name.clone(),
        raw: (h.lhs.clone(), h.rhs.clone()),
        lhs: h.lhs.clone(),
        rel: h.rel,
        rhs: h.rhs.clone(),
        conditions: Vec::new(),
        premises: Vec::new(),
        shifted: false,
    }
}

/// The cone's hypotheses as constraints, and the laws' instances for the atoms of the
/// hypotheses and of `terms` (one whose side conditions on signals are not proved is
/// left out).
fn constraints_for(
    ctx: &Context,
    cone: &[Axiom],
    terms: &[&Expr],
    atoms: &mut boolean::Atoms,
    budget: Budget,
    depth: usize,
) -> Vec<boolean::Constraint> {
    let mut constraints: Vec<boolean::Constraint> = cone.iter().map(constraint).collect();
    // Register the atoms of the hypotheses and of the terms, then instantiate the laws
    // for them.
    boolean::register(atoms, &constraints);
    for t in terms {
        atoms.view(t, root(t));
    }
    for mut c in boolean::law_instances(&ctx.laws, &ctx.law_index, ctx.cycle.as_ref(), atoms, 2_000)
    {
        // A law with side conditions on signals is used only where they are proved.
        if !c.conditions.is_empty() {
            if depth > 0 {
                continue;
            }
            let small = Budget { time: budget.time / 20, ..budget };
            for (l, rel, r) in &c.conditions {
                let key = format!("{l} {rel:?} {r}");
                let known = ctx.premises.lock().ok().and_then(|m| m.get(&key).cloned());
                let proof = known.unwrap_or_else(|| {
                    let sub = Obligation { lhs: l.clone(), rel: *rel, rhs: r.clone() };
                    let proof = match prove_at(ctx, &sub, small, depth + 1, &mut |_, _| false) {
                        Outcome::Proved(p) => p.certificate.main,
                        Outcome::Unknown { .. } => None,
                    };
                    if let Ok(mut m) = ctx.premises.lock() {
                        m.insert(key, proof.clone());
                    }
                    proof
                });
                c.premises.extend(proof);
            }
            if c.premises.len() != c.conditions.len() {
                continue;
            }
        }
        constraints.push(c);
    }
    if let Some(cycle) = ctx.cycle.as_ref().filter(|_| ctx.scans) {
        constraints.extend(timing::ton_of_pre_instances(atoms, cycle));
    }
    // What the hypotheses said at the previous scan, for the signals read through `pre`.
    if ctx.scans {
        constraints.extend(boolean::shifted(cone, atoms, SHIFT_ROUNDS));
    }
    constraints
}

/// How many steps of definitions [`boolean::shifted`] follows back from a `pre`.
const SHIFT_ROUNDS: usize = 3;

/// The lemmas of `offered` that the certificate cites.
fn cited_lemmas(certificate: &Certificate, mut offered: kernel::Lemmas) -> kernel::Lemmas {
    if offered.is_empty() {
        return offered;
    }
    let names = certificate.main.as_ref().map(Proof::lemmas_cited).unwrap_or_default();
    offered.retain(|name, _| names.contains(name));
    offered
}

/// `f ⇒ g` from a proof of `f·¬g = 0*` by `prove`, and `f = g` from both directions.
fn both_ways<E>(
    goal: &Obligation,
    prove: &mut dyn FnMut(&Expr) -> Result<Proof, E>,
) -> Result<Proof, E> {
    let one = |f: &Expr, g: &Expr, prove: &mut dyn FnMut(&Expr) -> Result<Proof, E>| {
        prove(&and_not(f, g)).map(|p| Proof::ImpliesByZero(Box::new(p)))
    };
    let forward = one(&goal.lhs, &goal.rhs, prove)?;
    if goal.rel == Rel::Implies {
        return Ok(forward);
    }
    let backward = one(&goal.rhs, &goal.lhs, prove)?;
    Ok(Proof::Antisym(Box::new(forward), Box::new(backward)))
}

/// The goal as `f·¬g = 0*` (both ways for an equation), proved by cases on the skeleton.
fn prove_by_cases(
    ctx: &Context,
    goal: &Obligation,
    cone: &[Axiom],
    deadline: Instant,
    budget: Budget,
    depth: usize,
) -> Result<Proved, boolean::Failure> {
    let mut shared = kernel::Lemmas::new();
    let main = both_ways(goal, &mut |zero_goal| {
        // `pre` pushed down to the atoms first, as in the hypotheses one scan earlier.
        let (pushed, push) = induction::push_pre(zero_goal);
        let mut atoms = boolean::Atoms::default();
        let mut constraints = constraints_for(ctx, cone, &[&pushed], &mut atoms, budget, depth);
        // What the goal's literals force far away, as shared lemmas.
        if ctx.shared_lemmas
            && let Term::And([f, _]) = &pushed[root(&pushed)]
        {
            let f = crate::term::subterm(&pushed, *f);
            constraints.extend(ctx.lemmas.for_goal(ctx, &f, &atoms, &mut shared));
        }
        let proof = boolean::prove_zero(&pushed, &constraints, &mut atoms, budget.cases, deadline)?;
        Ok(match push.is_empty() {
            true => proof,
            false => {
                let push = Proof::Chain { start: zero_goal.clone(), steps: push };
                Proof::Trans(Box::new(push), Box::new(proof))
            }
        })
    })?;
    let certificate = Certificate { lemmas: vec![], main: Some(main) };
    let cited = cited_lemmas(&certificate, shared);
    match ctx
        .kernel
        .check_using(&certificate, cited.clone())
        .and_then(|t| ctx.kernel.vouch(&t, &goal.lhs, goal.rel, &goal.rhs).map(|()| t))
    {
        Ok(theorem) => Ok(Proved {
            theorem,
            certificate,
            method: Method::CaseSplit,
            lines: vec![],
            shared: cited,
        }),
        Err(e) => Err(boolean::Failure::Limit(format!("the kernel rejected the case split: {e}"))),
    }
}
