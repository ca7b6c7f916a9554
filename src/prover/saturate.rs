//! Untrusted search by equality saturation: laws as egg rewrites, hypotheses as named unions.
//!
//! The e-graph holds both encodings of an implication goal `f ⇒ g`
//! (`f·g = f` and `f·¬g = 0*`) and stops as soon as either pair merges. Delay
//! arithmetic is constant folding in the e-class analysis, recorded as a
//! `delay-arith` step. Every rule carries a name that [`super::explain`] maps
//! back to a kernel rule; nothing here is trusted.

use std::str::FromStr;
use std::time::{Duration, Instant};

use egg::{
    Analysis, BackoffScheduler, Condition, ConditionalApplier, DidMerge, EGraph, ENodeOrVar,
    Pattern, PatternAst, Rewrite, Runner, StopReason, Subst, Var,
};

use crate::kernel::{Axiom, Cmp, Rel};
use crate::term::{
    Delay, Expr, Id, Symbol, Term, and, and_not, constant, mentions_pre, not, or, root,
};

/// Folds `max`, `min` and `+` of delay literals; the data is the delay's value.
#[derive(Default, Clone, Copy, Debug)]
pub struct DelayFold;

/// The rule name of a delay-arithmetic step.
pub const DELAY_ARITH: &str = "delay-arith";

impl Analysis<Term> for DelayFold {
    type Data = Option<Delay>;

    fn make(egraph: &mut EGraph<Term, Self>, node: &Term, _id: Id) -> Self::Data {
        let value = |i: &Id| egraph[*i].data.clone();
        match node {
            Term::Delay(d) => Some(d.clone()),
            Term::DMax([a, b]) => Some(value(a)?.dmax(&value(b)?)),
            Term::DMin([a, b]) => Some(value(a)?.dmin(&value(b)?)),
            Term::DAdd([a, b]) => Some(value(a)?.dadd(&value(b)?)),
            _ => None,
        }
    }

    fn merge(&mut self, to: &mut Self::Data, from: Self::Data) -> DidMerge {
        egg::merge_option(to, from, |a, b| {
            // Two different delays in one class would mean an unsound rule; keep the first
            // (the kernel would reject any proof that relied on it).
            debug_assert_eq!(*a, b, "two different delays merged");
            DidMerge(false, false)
        })
    }

    fn modify(egraph: &mut EGraph<Term, Self>, id: Id) {
        let Some(value) = egraph[id].data.clone() else { return };
        if egraph[id].nodes.iter().any(|n| matches!(n, Term::Delay(_))) {
            return;
        }
        let arith = egraph[id].nodes.iter().find_map(|n| {
            let (a, b) = match n {
                Term::DMax([a, b]) | Term::DMin([a, b]) | Term::DAdd([a, b]) => (*a, *b),
                _ => return None,
            };
            let (da, db) = (egraph[a].data.clone()?, egraph[b].data.clone()?);
            Some((n.clone(), da, db))
        });
        if let Some((node, da, db)) = arith {
            let mut from = PatternAst::default();
            let x = from.add(ENodeOrVar::ENode(Term::Delay(da)));
            let y = from.add(ENodeOrVar::ENode(Term::Delay(db)));
            from.add(ENodeOrVar::ENode(match node {
                Term::DMax(_) => Term::DMax([x, y]),
                Term::DMin(_) => Term::DMin([x, y]),
                _ => Term::DAdd([x, y]),
            }));
            let mut to = PatternAst::default();
            to.add(ENodeOrVar::ENode(Term::Delay(value)));
            egraph.union_instantiations(&from, &to, &Subst::default(), DELAY_ARITH);
        }
    }
}

/// The e-graph of the search.
pub type Graph = EGraph<Term, DelayFold>;
/// One rewrite rule of the search.
pub type Rule = Rewrite<Term, DelayFold>;

/// Limits on one saturation run. Every run ends within them.
#[derive(Clone, Copy, Debug)]
pub struct Limits {
    /// Wall-clock time.
    pub time: Duration,
    /// E-nodes (checked between rule applications, so a run may overshoot a little).
    pub nodes: usize,
    /// Iterations.
    pub iterations: usize,
}

impl Default for Limits {
    fn default() -> Self {
        Limits { time: Duration::from_secs(2), nodes: 60_000, iterations: 40 }
    }
}

/// How a law's egg rule is used, encoded in the rule's name after `~`.
pub fn rule_name(law: &str, usage: &str) -> String {
    if usage.is_empty() { law.to_string() } else { format!("{law}~{usage}") }
}

/// The rule name of a hypothesis union.
pub fn hypothesis_name(hyp: &str, usage: &str) -> String {
    format!("hyp:{}", rule_name(hyp, usage))
}

fn vars_of(e: &Expr, vars: &[Symbol]) -> Vec<Symbol> {
    let mut found: Vec<Symbol> = e
        .as_ref()
        .iter()
        .filter_map(|n| match n {
            Term::Name(s) if vars.contains(s) => Some(*s),
            _ => None,
        })
        .collect();
    found.sort();
    found.dedup();
    found
}

fn to_pattern(e: &Expr, vars: &[Symbol]) -> PatternAst<Term> {
    let mut out = PatternAst::default();
    for node in e.as_ref() {
        out.add(match node {
            Term::Name(s) if vars.contains(s) => {
                ENodeOrVar::Var(Var::from_str(&format!("?{s}")).expect("a valid variable"))
            }
            other => ENodeOrVar::ENode(other.clone()),
        });
    }
    out
}

/// A ground term as a pattern without variables (for hypothesis unions).
pub fn ground_pattern(e: &Expr) -> PatternAst<Term> {
    to_pattern(e, &[])
}

fn is_bare_var(e: &Expr, vars: &[Symbol]) -> bool {
    matches!(&e[root(e)], Term::Name(s) if vars.contains(s))
}

/// Checks the delay side conditions of a law on a match, from the e-class analysis.
struct DelayCondition {
    conditions: Vec<(Expr, Cmp, Expr)>,
}

fn delay_value(egraph: &Graph, e: &Expr, id: Id, subst: &Subst) -> Option<Delay> {
    match &e[id] {
        Term::Name(s) => {
            let var = Var::from_str(&format!("?{s}")).ok()?;
            egraph[*subst.get(var)?].data.clone()
        }
        Term::Delay(d) => Some(d.clone()),
        Term::DMax([a, b]) => {
            Some(delay_value(egraph, e, *a, subst)?.dmax(&delay_value(egraph, e, *b, subst)?))
        }
        Term::DMin([a, b]) => {
            Some(delay_value(egraph, e, *a, subst)?.dmin(&delay_value(egraph, e, *b, subst)?))
        }
        Term::DAdd([a, b]) => {
            Some(delay_value(egraph, e, *a, subst)?.dadd(&delay_value(egraph, e, *b, subst)?))
        }
        _ => None,
    }
}

impl Condition<Term, DelayFold> for DelayCondition {
    fn check(&self, egraph: &mut Graph, _eclass: Id, subst: &Subst) -> bool {
        self.conditions.iter().all(|(l, cmp, r)| {
            match (delay_value(egraph, l, root(l), subst), delay_value(egraph, r, root(r), subst)) {
                (Some(a), Some(b)) => cmp.holds(&a, &b),
                _ => false,
            }
        })
    }
}

/// The egg rules for the laws: each law in the directions that make sense for search.
///
/// An equation `l = r` gives `l → r` and, when it loses no variable and `r` is
/// not a bare variable, `r → l`. An implication `p ⇒ q` gives `p·q → p` and
/// `q + p → q`, and the growing forms `p → p·q`, `q → q + p` when they
/// introduce no variable and do not apply to every class. Laws with side
/// conditions on signals are left to other methods.
pub fn rules_for(laws: &[Axiom]) -> Vec<Rule> {
    let mut rules = Vec::new();
    for law in laws {
        // `pre` terms are atoms of the search (rewriting under `pre` needs care the
        // e-graph's congruence does not take), so the laws of `pre` stay out of it.
        if !law.signal_conditions.is_empty() || mentions_pre(&law.lhs) || mentions_pre(&law.rhs) {
            continue;
        }
        let vars: Vec<Symbol> = law.signal_vars.iter().chain(&law.delay_vars).cloned().collect();
        let mut add = |from: &Expr, to: &Expr, usage: &str| {
            let (vf, vt) = (vars_of(from, &vars), vars_of(to, &vars));
            if !vt.iter().all(|v| vf.contains(v)) || is_bare_var(from, &vars) {
                return;
            }
            let searcher = Pattern::new(to_pattern(from, &vars));
            let applier = Pattern::new(to_pattern(to, &vars));
            let name = rule_name(&law.name, usage);
            let rule = if law.delay_conditions.is_empty() {
                Rewrite::new(name, searcher, applier)
            } else {
                let condition = DelayCondition { conditions: law.delay_conditions.clone() };
                Rewrite::new(name, searcher, ConditionalApplier { condition, applier })
            };
            if let Ok(rule) = rule {
                rules.push(rule);
            }
        };
        match law.rel {
            Rel::Eq => {
                add(&law.lhs, &law.rhs, "");
                if !is_bare_var(&law.rhs, &vars) {
                    add(&law.rhs, &law.lhs, "rev");
                }
            }
            Rel::Implies => {
                let (p, q) = (&law.lhs, &law.rhs);
                add(&and(p, q), p, "meetback");
                add(&or(q, p), q, "joinback");
                add(p, &and(p, q), "meet");
                add(q, &or(q, p), "join");
            }
        }
    }
    rules
}

/// Adds the hypotheses to the e-graph as named unions: an equation as itself, an
/// implication `p ⇒ q` as `p = p·q`, `q = q + p` and `¬q = ¬q·¬p`.
pub fn add_hypotheses(egraph: &mut Graph, hypotheses: &[Axiom]) {
    let subst = Subst::default();
    for hyp in hypotheses {
        let mut union = |from: &Expr, to: &Expr, usage: &str| {
            let name = hypothesis_name(&hyp.name, usage);
            egraph.union_instantiations(&ground_pattern(from), &ground_pattern(to), &subst, name);
        };
        match hyp.rel {
            Rel::Eq => union(&hyp.lhs, &hyp.rhs, ""),
            Rel::Implies => {
                let (p, q) = (&hyp.lhs, &hyp.rhs);
                union(p, &and(p, q), "meet");
                union(q, &or(q, p), "join");
                union(&not(q), &and(&not(q), &not(p)), "contra");
            }
        }
    }
}

/// Which encoding of the goal closed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Closed {
    /// `lhs = rhs` directly.
    Equal,
    /// `lhs·rhs = lhs` (implication goals only).
    Meet,
    /// `lhs·¬rhs = 0*` (implication goals only).
    Zero,
}

/// The result of one saturation run.
pub struct Saturation {
    /// The e-graph, kept for explanations.
    pub egraph: Graph,
    /// The encoding that closed, if any.
    pub closed: Option<Closed>,
    /// Why the run stopped.
    pub stop: String,
    /// Size reached.
    pub nodes: usize,
    /// Time spent.
    pub elapsed: Duration,
    /// Whether the run stopped on its time or node limit.
    pub hit_limit: bool,
}

/// The pairs of terms whose merging proves `lhs rel rhs`.
pub fn goal_pairs(lhs: &Expr, rel: Rel, rhs: &Expr) -> Vec<(Closed, Expr, Expr)> {
    let mut pairs = vec![(Closed::Equal, lhs.clone(), rhs.clone())];
    if rel == Rel::Implies {
        pairs.push((Closed::Meet, and(lhs, rhs), lhs.clone()));
        pairs.push((Closed::Zero, and_not(lhs, rhs), constant(false)));
    }
    pairs
}

/// Saturates an e-graph holding the goal and the hypotheses under the rules, until
/// the goal closes or a limit is reached.
pub fn saturate(
    lhs: &Expr,
    rel: Rel,
    rhs: &Expr,
    hypotheses: &[Axiom],
    rules: &[Rule],
    limits: Limits,
) -> Saturation {
    let started = Instant::now();
    let mut egraph = Graph::default().with_explanations_enabled();
    let pairs = goal_pairs(lhs, rel, rhs);
    let ids: Vec<(Closed, Id, Id)> =
        pairs.iter().map(|(c, a, b)| (*c, egraph.add_expr(a), egraph.add_expr(b))).collect();
    add_hypotheses(&mut egraph, hypotheses);
    egraph.rebuild();
    let closed_in = |g: &Graph| ids.iter().find(|(_, a, b)| g.find(*a) == g.find(*b)).map(|p| p.0);
    if let Some(c) = closed_in(&egraph) {
        let nodes = egraph.total_number_of_nodes();
        return Saturation {
            egraph,
            closed: Some(c),
            stop: "closed".into(),
            nodes,
            elapsed: started.elapsed(),
            hit_limit: false,
        };
    }
    let watch = ids.clone();
    let runner = Runner::default()
        .with_egraph(egraph)
        .with_time_limit(limits.time)
        .with_node_limit(limits.nodes)
        .with_iter_limit(limits.iterations)
        .with_scheduler(BackoffScheduler::default())
        .with_hook(move |r| {
            if watch.iter().any(|(_, a, b)| r.egraph.find(*a) == r.egraph.find(*b)) {
                Err("closed".into())
            } else {
                Ok(())
            }
        })
        .run(rules);
    let stop = match &runner.stop_reason {
        Some(StopReason::Saturated) => "saturated".to_string(),
        Some(StopReason::IterationLimit(n)) => format!("iteration limit ({n})"),
        Some(StopReason::NodeLimit(n)) => format!("node limit ({n})"),
        Some(StopReason::TimeLimit(t)) => format!("time limit ({t:.1}s)"),
        Some(StopReason::Other(s)) => s.clone(),
        None => "stopped".to_string(),
    };
    let hit_limit =
        matches!(runner.stop_reason, Some(StopReason::NodeLimit(_) | StopReason::TimeLimit(_)));
    let egraph = runner.egraph;
    let closed = closed_in(&egraph);
    let nodes = egraph.total_number_of_nodes();
    Saturation { egraph, closed, stop, nodes, elapsed: started.elapsed(), hit_limit }
}

/// A pattern's size, each delay-arithmetic subterm counted as one node: it folds to
/// a constant, so `d1/(d2/f) → (d1+d2)/f` shrinks terms.
fn pattern_size(p: &egg::PatternAst<Term>) -> usize {
    let folded: usize = p
        .as_ref()
        .iter()
        .map(|n| match n {
            egg::ENodeOrVar::ENode(Term::DMax(_) | Term::DMin(_) | Term::DAdd(_)) => 2,
            _ => 0,
        })
        .sum();
    p.as_ref().len() - folded
}

/// The temporal operators (`ton`, `tof`, `sr`, `rs`) a term or pattern mentions.
fn temporal_ops<'a>(nodes: impl Iterator<Item = &'a Term>) -> u8 {
    nodes.fold(0, |acc, n| {
        acc | match n {
            Term::Ton(_) => 1,
            Term::Tof(_) => 2,
            Term::Sr(_) => 4,
            Term::Rs(_) => 8,
            _ => 0,
        }
    })
}

fn pattern_ops(p: &PatternAst<Term>) -> u8 {
    temporal_ops(p.as_ref().iter().filter_map(|n| match n {
        ENodeOrVar::ENode(t) => Some(t),
        ENodeOrVar::Var(_) => None,
    }))
}

/// The search rules of a set of laws, with what [`tiers`] needs to know of each: built
/// once per context.
pub struct RuleSet {
    rules: Vec<Rule>,
    shapes: Vec<Shape>,
}

/// A rule's temporal operators on each side, and its class: 0 shrinks terms, 1 is a
/// permutation (commutativity, associativity), 2 grows a term by at most two nodes,
/// 3 grows it more (or is not a pattern rule).
#[derive(Clone, Copy)]
struct Shape {
    from_ops: u8,
    to_ops: u8,
    class: usize,
}

impl RuleSet {
    /// The rules of `laws` ([`rules_for`]) and their shapes.
    pub fn new(laws: &[Axiom]) -> RuleSet {
        let rules = rules_for(laws);
        let shapes = rules
            .iter()
            .map(|r| {
                let (Some(l), Some(rt)) =
                    (r.searcher.get_pattern_ast(), r.applier.get_pattern_ast())
                else {
                    return Shape { from_ops: 0, to_ops: 0, class: 3 };
                };
                let (a, b) = (pattern_size(l), pattern_size(rt));
                let mut lv: Vec<String> = l.as_ref().iter().map(|n| format!("{n:?}")).collect();
                let mut rv: Vec<String> = rt.as_ref().iter().map(|n| format!("{n:?}")).collect();
                lv.sort();
                rv.sort();
                let class = if lv == rv {
                    1
                } else if b < a {
                    0
                } else if b <= a + 2 {
                    2
                } else {
                    3
                };
                Shape { from_ops: pattern_ops(l), to_ops: pattern_ops(rt), class }
            })
            .collect();
        RuleSet { rules, shapes }
    }
}

/// The rules in growing sets, restricted to the temporal operators present in
/// `terms`: first the rules that shrink terms, then with the permutations
/// (commutativity, associativity), then with rules that grow a term by at most
/// two nodes, then everything; each of the last two followed, if that adds any, by
/// the same with the operators the laws reach from those present. Small sets give
/// short proofs quickly when they suffice; the last set is the whole relevant rule set.
pub fn tiers(set: &RuleSet, terms: &[&Expr]) -> Vec<Vec<Rule>> {
    let rules = &set.rules;
    let present = terms.iter().fold(0u8, |acc, t| acc | temporal_ops(t.as_ref().iter()));
    // The operators reachable from those present by rules that rewrite one of them
    // into another: `RS(s, r) = SR(s·¬r, r)` brings the SR laws to a goal about RS
    // (rules that make an operator out of none, such as `f ⇒ SR(f, 0*)`, do not count).
    let mut reachable = present;
    loop {
        let before = reachable;
        for s in &set.shapes {
            if s.from_ops != 0 && s.from_ops & !reachable == 0 {
                reachable |= s.to_ops;
            }
        }
        if reachable == before {
            break;
        }
    }
    let class = |s: &Shape, ops: u8| {
        if (s.from_ops | s.to_ops) & !ops != 0 { usize::MAX } else { s.class }
    };
    let classes: Vec<usize> = set.shapes.iter().map(|s| class(s, present)).collect();
    let reachable_classes: Option<Vec<usize>> =
        (reachable != present).then(|| set.shapes.iter().map(|s| class(s, reachable)).collect());
    let tier = |max: usize, classes: &[usize]| {
        rules
            .iter()
            .zip(classes)
            .filter(|(_, c)| **c <= max)
            .map(|(r, _)| r.clone())
            .collect::<Vec<_>>()
    };
    let mut out = vec![tier(0, &classes), tier(1, &classes)];
    // The growing rules, each set followed by the same with the reachable operators
    // when that adds any.
    for max in [2, 3] {
        out.push(tier(max, &classes));
        if let Some(reachable_classes) = &reachable_classes {
            out.push(tier(max, reachable_classes));
        }
    }
    out
}
