//! Complete reasoning on the Boolean skeleton: a SAT solver decides, case splits prove.
//!
//! Names and temporal subterms (`d/f`, `f/d`, `SR`, `RS`) are opaque *atoms*;
//! the hypotheses and instances of the laws for the atoms present (e.g.
//! `5s/a ⇒ a`) are constraints that hold at every instant. If the goal is
//! valid over the skeleton, a Shannon case-split proof is built: each branch
//! fixes atoms with named case assumptions and either evaluates the goal to
//! `0*` with the constant laws or shows that a constraint is violated. If it
//! is not valid, the satisfying assignment is a *candidate* countermodel of
//! the abstraction, not yet a counterexample.

use std::collections::{BTreeMap, HashMap};
use std::time::Instant;

use varisat::{Lit, ProofFormat};

use crate::sat_trace::Traced;

use crate::kernel::{Axiom, Proof, Rel, Rule, Source, Step, Use};
use crate::refutation::Cnf;
use crate::term::{
    Expr, Id, Language, Symbol, Term, and, constant, mentions_pre, root, same, same_tree, subterm,
    tree_hash,
};

use super::induction::{pre, push_pre};
use super::normalize::replace_at;

/// A statement that holds at every instant: a hypothesis, a law instance or a lemma.
#[derive(Clone, Debug)]
pub struct Constraint {
    /// What the proof cites.
    pub source: Source,
    /// Its name.
    pub name: String,
    /// The instance exactly as the citation produces it.
    pub raw: (Expr, Expr),
    /// The same with delay arithmetic evaluated.
    pub lhs: Expr,
    /// `=` or `⇒`.
    pub rel: Rel,
    /// Right side, delay arithmetic evaluated.
    pub rhs: Expr,
    /// The law's side conditions on signals, instantiated (to be proved as premises).
    pub conditions: Vec<(Expr, Rel, Expr)>,
    /// Proofs of `conditions`, in order.
    pub premises: Vec<Proof>,
    /// The hypothesis `raw` one scan earlier: `lhs` and `rhs` are `pre` of its sides
    /// with `pre` pushed down to the atoms, and the citation rewrites under `pre`.
    pub shifted: bool,
}

/// A Boolean view of a term: atoms are opaque; paths match the term's.
#[derive(Clone, Debug)]
pub(super) enum B {
    Const(bool),
    Atom(usize),
    Not(Box<B>),
    And(Box<B>, Box<B>),
    Or(Box<B>, Box<B>),
}

/// The atoms met so far, by their tree (equal trees, one atom).
#[derive(Default, Debug)]
pub struct Atoms {
    /// Each atom's term.
    pub terms: Vec<Expr>,
    /// The atoms by the hash of their tree ([`tree_hash`]), those whose hashes collide
    /// side by side: a subterm is looked up without being copied.
    index: HashMap<u64, Vec<usize>>,
    /// Towards the representative of the atom's class: the next atom and the
    /// hypothesis (`a = b`, used forward or backward) that rewrites this one into it.
    link: Vec<Option<(usize, String, Use)>>,
}

impl Atoms {
    /// Merges atoms that a hypothesis `a = b` between two atoms makes equal (a rung
    /// `L1_pump = 5s/L1_Prod`, say) into one class, represented preferably by a name.
    /// Such hypotheses leave the constraints: evaluating an atom first rewrites it to
    /// its representative with them.
    pub fn merge_equal(&mut self, constraints: &mut Vec<Constraint>) {
        let mut edges: Vec<(usize, usize, String)> = Vec::new();
        constraints.retain(|c| {
            let atomic = |e: &Expr| {
                !matches!(
                    e[root(e)],
                    Term::Zero | Term::One | Term::Not(_) | Term::And(_) | Term::Or(_)
                )
            };
            let definitional = c.source == Source::Hypothesis
                && !c.shifted
                && c.rel == Rel::Eq
                && atomic(&c.lhs)
                && atomic(&c.rhs);
            if definitional {
                edges.push((self.intern(&c.lhs), self.intern(&c.rhs), c.name.clone()));
            }
            !definitional
        });
        self.link = vec![None; self.terms.len()];
        let mut seen = vec![false; self.terms.len()];
        let mut order: Vec<usize> = (0..self.terms.len()).collect();
        order.sort_by_key(|&i| {
            (
                !matches!(self.terms[i][root(&self.terms[i])], Term::Name(_)),
                self.terms[i].as_ref().len(),
                i,
            )
        });
        for start in order {
            if seen[start] {
                continue;
            }
            seen[start] = true;
            let mut queue = std::collections::VecDeque::from([start]);
            while let Some(at) = queue.pop_front() {
                for (a, b, name) in &edges {
                    let (next, how) = if *a == at {
                        (*b, Use::Backward)
                    } else if *b == at {
                        (*a, Use::Forward)
                    } else {
                        continue;
                    };
                    if !seen[next] {
                        seen[next] = true;
                        self.link[next] = Some((at, name.clone(), how));
                        queue.push_back(next);
                    }
                }
            }
        }
    }

    /// The representative of an atom's class.
    fn rep(&self, mut i: usize) -> usize {
        while let Some((next, _, _)) = self.link.get(i).and_then(|l| l.as_ref()) {
            i = *next;
        }
        i
    }

    pub(super) fn intern(&mut self, e: &Expr) -> usize {
        let hash = tree_hash(e, root(e));
        match self.find(e, root(e), hash) {
            Some(i) => i,
            None => self.add(hash, e.clone()),
        }
    }

    /// The atom whose tree is the one at `id` in `e` (of hash `hash`), if met.
    fn find(&self, e: &Expr, id: Id, hash: u64) -> Option<usize> {
        let same = |&i: &usize| same_tree(&self.terms[i], root(&self.terms[i]), e, id);
        self.index.get(&hash)?.iter().copied().find(same)
    }

    /// A new atom.
    fn add(&mut self, hash: u64, term: Expr) -> usize {
        self.terms.push(term);
        self.index.entry(hash).or_default().push(self.terms.len() - 1);
        self.terms.len() - 1
    }

    pub(super) fn view(&mut self, e: &Expr, id: Id) -> B {
        match &e[id] {
            Term::Zero => B::Const(false),
            Term::One => B::Const(true),
            Term::Not(a) => B::Not(Box::new(self.view(e, *a))),
            Term::And([a, b]) => B::And(Box::new(self.view(e, *a)), Box::new(self.view(e, *b))),
            Term::Or([a, b]) => B::Or(Box::new(self.view(e, *a)), Box::new(self.view(e, *b))),
            _ => {
                let hash = tree_hash(e, id);
                B::Atom(match self.find(e, id, hash) {
                    Some(i) => i,
                    None => self.add(hash, subterm(e, id)),
                })
            }
        }
    }
}

/// Is `l rel r` false under the (partial) assignment?
pub(super) fn violated(rel: Rel, l: &B, r: &B, sigma: &[Option<bool>]) -> bool {
    let (vl, vr) = (eval3(l, sigma), eval3(r, sigma));
    match rel {
        Rel::Eq => vl.is_some() && vr.is_some() && vl != vr,
        Rel::Implies => vl == Some(true) && vr == Some(false),
    }
}

pub(super) fn eval3(b: &B, sigma: &[Option<bool>]) -> Option<bool> {
    match b {
        B::Const(v) => Some(*v),
        B::Atom(i) => sigma[*i],
        B::Not(a) => eval3(a, sigma).map(|v| !v),
        B::And(a, b) => match (eval3(a, sigma), eval3(b, sigma)) {
            (Some(false), _) | (_, Some(false)) => Some(false),
            (Some(true), Some(true)) => Some(true),
            _ => None,
        },
        B::Or(a, b) => match (eval3(a, sigma), eval3(b, sigma)) {
            (Some(true), _) | (_, Some(true)) => Some(true),
            (Some(false), Some(false)) => Some(false),
            _ => None,
        },
    }
}

fn first_unassigned(b: &B, sigma: &[Option<bool>]) -> Option<usize> {
    match b {
        B::Const(_) => None,
        B::Atom(i) => sigma[*i].is_none().then_some(*i),
        B::Not(a) => first_unassigned(a, sigma),
        B::And(a, b) | B::Or(a, b) => {
            first_unassigned(a, sigma).or_else(|| first_unassigned(b, sigma))
        }
    }
}

/// Registers the atoms of the constraints' sides.
pub fn register(atoms: &mut Atoms, constraints: &[Constraint]) {
    for c in constraints {
        atoms.view(&c.lhs, root(&c.lhs));
        atoms.view(&c.rhs, root(&c.rhs));
    }
}

/// The laws' temporal pieces ([`temporal_pieces`]), by law: computed once per context.
pub struct LawIndex(Vec<Vec<Expr>>);

impl LawIndex {
    /// The index of `laws`.
    pub fn new(laws: &[Axiom]) -> LawIndex {
        LawIndex(laws.iter().map(temporal_pieces).collect())
    }
}

/// Instances of the laws for the atoms present: every law side with a temporal
/// root (or a `·`/`+` of two of them) is matched against the atoms, in two rounds
/// so that atoms introduced by instances get their own lemmas. The second round
/// matches only what involves an atom the first introduced: an instance of the first
/// round's atoms alone is the first round's again (matching and instantiating are
/// functions of the law and the atoms), already taken or already refused.
pub fn law_instances(
    laws: &[Axiom],
    index: &LawIndex,
    cycle: Option<&crate::term::Delay>,
    atoms: &mut Atoms,
    limit: usize,
) -> Vec<Constraint> {
    let mut out: Vec<Constraint> = Vec::new();
    // The instances in `out`, by the hash of their two sides.
    let mut seen: HashMap<u64, Vec<usize>> = HashMap::new();
    // The atoms every earlier round matched: `atoms.terms` only grows.
    let mut matched = 0;
    for _round in 0..2 {
        let pool: Vec<Expr> = atoms.terms.clone();
        // Each temporal atom, and whether this round is the first to match it.
        let temporal: Vec<(&Expr, bool)> = pool
            .iter()
            .enumerate()
            .filter(|(_, a)| !matches!(a[root(a)], Term::Name(_)))
            .map(|(i, a)| (a, i >= matched))
            .collect();
        matched = pool.len();
        for (law, pieces) in laws.iter().zip(&index.0) {
            let Some(first) = pieces.first() else { continue };
            // Each match, and whether it involves an atom new in this round.
            let mut sigmas: Vec<(BTreeMap<Symbol, Expr>, bool)> = Vec::new();
            for &(atom, new) in &temporal {
                // An old atom's match is wanted only to pair with a new atom.
                if !new && pieces.len() == 1 {
                    continue;
                }
                let mut sigma = BTreeMap::new();
                if crate::theory::match_side(law, first, atom, &mut sigma) {
                    sigmas.push((sigma, new));
                }
            }
            if let Some(second) = pieces.get(1) {
                let mut extended = Vec::new();
                for (sigma, new_first) in &sigmas {
                    for &(atom, new) in &temporal {
                        if !new_first && !new {
                            continue;
                        }
                        let mut s = sigma.clone();
                        if crate::theory::match_side(law, second, atom, &mut s) {
                            extended.push((s, true));
                        }
                    }
                }
                sigmas.extend(extended);
            }
            for (sigma, new) in sigmas {
                if out.len() >= limit {
                    return out;
                }
                if !new {
                    continue;
                }
                let Some(c) = instance(law, cycle, sigma) else { continue };
                // Once per law and instance (its two sides as trees).
                let (l, r) = (&c.raw.0, &c.raw.1);
                let hash = tree_hash(l, root(l)) ^ tree_hash(r, root(r)).rotate_left(1);
                let taken = seen.entry(hash).or_default();
                if taken.iter().any(|&k: &usize| {
                    let d: &Constraint = &out[k];
                    d.name == law.name && same(&d.raw.0, l) && same(&d.raw.1, r)
                }) {
                    continue;
                }
                taken.push(out.len());
                atoms.view(&c.lhs, root(&c.lhs));
                atoms.view(&c.rhs, root(&c.rhs));
                out.push(c);
            }
        }
    }
    out
}

fn is_delay_arithmetic(node: &Term) -> bool {
    matches!(node, Term::DMax(_) | Term::DMin(_) | Term::DAdd(_))
}

/// The law's instance under `sigma`, unless a variable is unbound, a delay condition
/// fails or the two sides are the same.
fn instance(
    law: &Axiom,
    cycle: Option<&crate::term::Delay>,
    mut sigma: BTreeMap<Symbol, Expr>,
) -> Option<Constraint> {
    law.bind_cycle(cycle, &mut sigma);
    if law.check_delay_conditions(&sigma).is_err() {
        return None;
    }
    let l = crate::term::instantiate(&law.lhs, &sigma)?;
    let r = crate::term::instantiate(&law.rhs, &sigma)?;
    // An instance is a tree (`instantiate` copies every value in), so without delay
    // arithmetic it is its own folding.
    let fold = |e: &Expr| match e.as_ref().iter().any(is_delay_arithmetic) {
        true => fold_delays(e),
        false => e.clone(),
    };
    let (fl, fr) = (fold(&l), fold(&r));
    if crate::term::same(&fl, &fr) {
        return None;
    }
    let mut conditions = Vec::new();
    for (cl, rel, cr) in &law.signal_conditions {
        let a = crate::term::instantiate(cl, &sigma)?;
        let b = crate::term::instantiate(cr, &sigma)?;
        conditions.push((a, *rel, b));
    }
    Some(Constraint {
        source: Source::Law,
        name: law.name.clone(),
        raw: (l, r),
        lhs: fl,
        rel: law.rel,
        rhs: fr,
        conditions,
        premises: Vec::new(),
        shifted: false,
    })
}

/// The hypotheses one scan earlier, for the signals the atoms read through `pre`:
/// `pre l rel pre r` with `pre` pushed down to the atoms, for each hypothesis `l rel r`
/// that mentions such a signal, has no `pre` itself and holds before the first scan
/// (so that it holds at the previous scan even at the first). A definition `X = e`
/// taken this way brings in the signals of `e`, for `rounds` rounds.
pub fn shifted(cone: &[Axiom], atoms: &mut Atoms, rounds: usize) -> Vec<Constraint> {
    let mut wanted: std::collections::BTreeSet<Symbol> = atoms
        .terms
        .iter()
        .filter_map(|a| match &a[root(a)] {
            Term::Pre(x) => match a[*x] {
                Term::Name(n) => Some(n),
                _ => None,
            },
            _ => None,
        })
        .collect();
    let names = |e: &Expr| {
        let mut set = std::collections::BTreeSet::new();
        super::names(e, &mut set);
        set
    };
    let mut taken = vec![false; cone.len()];
    let mut out = Vec::new();
    for _ in 0..rounds {
        let mut more = Vec::new();
        for (h, done) in cone.iter().zip(taken.iter_mut()) {
            let mentioned = names(&h.lhs).into_iter().chain(names(&h.rhs));
            if *done
                || !h.holds_initially()
                || mentions_pre(&h.lhs)
                || mentions_pre(&h.rhs)
                || !mentioned.into_iter().any(|n| wanted.contains(&n))
            {
                continue;
            }
            *done = true;
            if h.rel == Rel::Eq && matches!(h.lhs[root(&h.lhs)], Term::Name(_)) {
                more.extend(names(&h.rhs));
            }
            let (lhs, rhs) = (push_pre(&pre(&h.lhs)).0, push_pre(&pre(&h.rhs)).0);
            atoms.view(&lhs, root(&lhs));
            atoms.view(&rhs, root(&rhs));
            out.push(Constraint {
                source: Source::Hypothesis,
                name: h.name.clone(),
                raw: (h.lhs.clone(), h.rhs.clone()),
                lhs,
                rel: h.rel,
                rhs,
                conditions: Vec::new(),
                premises: Vec::new(),
                shifted: true,
            });
        }
        if more.is_empty() {
            break;
        }
        wanted.extend(more);
    }
    out
}

/// The temporal subpatterns of a law (roots of either side, or children of a top `·`/`+`).
fn temporal_pieces(law: &Axiom) -> Vec<Expr> {
    let temporal = |e: &Expr, id: Id| crate::term::is_temporal_node(&e[id]);
    let mut pieces = Vec::new();
    for side in [&law.lhs, &law.rhs] {
        let top = root(side);
        if temporal(side, top) {
            pieces.push(subterm(side, top));
        } else if let Term::And([a, b]) | Term::Or([a, b]) = &side[top] {
            for c in [*a, *b] {
                if temporal(side, c) {
                    pieces.push(subterm(side, c));
                }
            }
        }
    }
    pieces.sort_by_key(|p| std::cmp::Reverse(p.as_ref().len()));
    pieces.truncate(2);
    pieces
}

/// The term with every delay arithmetic node replaced by its value (as a tree: a copy
/// of `e` where it has none).
pub fn fold_delays(e: &Expr) -> Expr {
    fn go(e: &Expr, id: Id, out: &mut Expr) -> Id {
        if let Term::DMax(_) | Term::DMin(_) | Term::DAdd(_) = &e[id]
            && let Some(v) = crate::term::fold_delay(e, id)
        {
            return out.add(Term::Delay(v));
        }
        let node = e[id].clone().map_children(|c| go(e, c, out));
        out.add(node)
    }
    let mut out = Expr::default();
    go(e, root(e), &mut out);
    out
}

/// Delay-arithmetic steps turning `from` into `to` where they differ only in delays.
fn align_delays(whole: &mut Expr, prefix: &[usize], from: &Expr, to: &Expr, out: &mut Vec<Step>) {
    fn diffs(a: &Expr, x: Id, b: &Expr, y: Id, path: &mut Vec<usize>, found: &mut Vec<Vec<usize>>) {
        if crate::term::same_tree(a, x, b, y) {
            return;
        }
        let arith = |e: &Expr, i: Id| crate::term::is_delay_node(&e[i]);
        if arith(a, x) && arith(b, y) {
            found.push(path.clone());
            return;
        }
        use crate::term::Language;
        for (i, (&c, &d)) in a[x].children().iter().zip(b[y].children()).enumerate() {
            path.push(i);
            diffs(a, c, b, d, path, found);
            path.pop();
        }
    }
    let mut found = Vec::new();
    diffs(from, root(from), to, root(to), &mut Vec::new(), &mut found);
    for path in found {
        let mut full = prefix.to_vec();
        full.extend(&path);
        let (target, _) = locate_sub(to, &path);
        *whole = replace_at(whole, &full, &subterm(to, target));
        out.push(step(full, Rule::DelayArith, whole.clone()));
    }
}

fn locate_sub(e: &Expr, path: &[usize]) -> (Id, ()) {
    use crate::term::Language;
    let mut id = root(e);
    for &i in path {
        id = e[id].children()[i];
    }
    (id, ())
}

fn step(path: Vec<usize>, rule: Rule, after: Expr) -> Step {
    Step { path, rule, after, subst: Vec::new(), premises: Vec::new() }
}

/// The laws that evaluate `·`, `+` and `¬` on constants; case proofs use only these
/// (and the cited constraints) once every atom of a term has a value.
pub const CONSTANT_LAWS: &[&str] = &[
    "and_one", "one_and", "and_zero", "zero_and", "or_zero", "zero_or", "or_one", "one_or",
    "not_zero", "not_one",
];

fn law(name: &str, how: Use) -> Rule {
    Rule::Cite(Source::Law, name.to_string(), how)
}

/// Steps rewriting the subterm at `path` (viewed as `b`) to the constant it evaluates to.
fn evaluate(
    whole: &mut Expr,
    path: &[usize],
    b: &B,
    sigma: &[Option<bool>],
    atoms: &Atoms,
    out: &mut Vec<Step>,
) -> Option<bool> {
    let value = eval3(b, sigma)?;
    let child = |i: usize| {
        let mut p = path.to_vec();
        p.push(i);
        p
    };
    let finish = |whole: &mut Expr, out: &mut Vec<Step>, rule: Rule| {
        *whole = replace_at(whole, path, &constant(value));
        out.push(step(path.to_vec(), rule, whole.clone()));
    };
    match b {
        B::Const(_) => {}
        B::Atom(i) => {
            let mut at = *i;
            while let Some((next, name, how)) = atoms.link.get(at).and_then(|l| l.as_ref()) {
                *whole = replace_at(whole, path, &atoms.terms[*next]);
                let cite = Rule::Cite(Source::Hypothesis, name.clone(), *how);
                out.push(step(path.to_vec(), cite, whole.clone()));
                at = *next;
            }
            finish(whole, out, Rule::Case(atoms.terms[at].clone(), value));
        }
        B::Not(a) => {
            let inner = evaluate(whole, &child(0), a, sigma, atoms, out)?;
            finish(whole, out, law(if inner { "not_one" } else { "not_zero" }, Use::Forward));
        }
        B::And(a, c) | B::Or(a, c) => {
            let is_and = matches!(b, B::And(..));
            let dominant = !is_and; // 0 for `·`, 1 for `+`
            let (va, vc) = (eval3(a, sigma), eval3(c, sigma));
            let rule = if va == Some(dominant) {
                evaluate(whole, &child(0), a, sigma, atoms, out);
                if is_and { "zero_and" } else { "one_or" }
            } else if vc == Some(dominant) {
                evaluate(whole, &child(1), c, sigma, atoms, out);
                if is_and { "and_zero" } else { "or_one" }
            } else {
                evaluate(whole, &child(0), a, sigma, atoms, out);
                evaluate(whole, &child(1), c, sigma, atoms, out);
                if is_and { "and_one" } else { "or_zero" }
            };
            finish(whole, out, law(rule, Use::Forward));
        }
    }
    Some(value)
}

/// The reverse of a chain that started at `start`.
fn reverse(start: &Expr, steps: Vec<Step>) -> Vec<Step> {
    let mut befores = vec![start.clone()];
    befores.extend(steps.iter().map(|s| s.after.clone()));
    steps
        .into_iter()
        .enumerate()
        .rev()
        .map(|(i, s)| Step {
            rule: super::normalize::reversed(&s.rule),
            after: befores[i].clone(),
            ..s
        })
        .collect()
}

pub(super) fn atoms_in(b: &B, out: &mut Vec<usize>) {
    match b {
        B::Const(_) => {}
        B::Atom(i) => out.push(*i),
        B::Not(a) => atoms_in(a, out),
        B::And(a, c) | B::Or(a, c) => {
            atoms_in(a, out);
            atoms_in(c, out);
        }
    }
}

/// Limits and bookkeeping of one proof search.
struct Search<'a> {
    goal: B,
    goal_term: Expr,
    constraints: &'a [Constraint],
    views: Vec<(B, B)>,
    atoms: &'a Atoms,
    reps: Vec<usize>,
    /// The atoms of each class, by representative.
    members: Vec<Vec<usize>>,
    /// The constraints that mention each class, by representative (in constraint order).
    occurs: Vec<Vec<usize>>,
    /// The atoms of the goal, in order.
    goal_atoms: Vec<usize>,
    /// The atoms of each constraint, in order (left side, then right side).
    atoms_of: Vec<Vec<usize>>,
    /// Per constraint: the unassigned classes (representatives) one of whose values
    /// violates it under the current assignment. Kept up to date for the constraints
    /// of each class the search assigns, so unit propagation never rescans them all.
    violators: Vec<Vec<usize>>,
    /// The constraints whose `violators` are not empty.
    units: std::collections::BTreeSet<usize>,
    leaves: usize,
    max_leaves: usize,
    deadline: Instant,
}

impl Search<'_> {
    /// A proof of the goal under `sigma`; `changed`: the class the caller just assigned
    /// (`None` at the root). Only the constraints on that class can change.
    fn prove(
        &mut self,
        sigma: &mut Vec<Option<bool>>,
        changed: Option<usize>,
    ) -> Result<Proof, String> {
        if Instant::now() > self.deadline {
            return Err("time limit".into());
        }
        self.leaves += 1;
        if self.leaves > self.max_leaves {
            return Err(format!("more than {} cases", self.max_leaves));
        }
        let mut whole = self.goal_term.clone();
        let mut steps = Vec::new();
        if evaluate(&mut whole, &[], &self.goal, sigma, self.atoms, &mut steps) == Some(false) {
            return Ok(Proof::Chain { start: self.goal_term.clone(), steps });
        }
        // The caller's assignment violated no constraint, so a violated one (the first
        // in order) mentions the class just assigned.
        let violated = match changed {
            None => (0..self.constraints.len()).find(|&i| self.violated(i, sigma)),
            Some(k) => self.occurs[k].iter().copied().find(|&i| self.violated(i, sigma)),
        };
        if let Some(i) = violated {
            let (l, r) = &self.views[i];
            return Ok(self.contradiction(&self.constraints[i], l, r, sigma));
        }
        let touched: Vec<usize> = match changed {
            None => (0..self.constraints.len()).collect(),
            Some(k) => self.occurs[k].clone(),
        };
        let mut saved = Vec::with_capacity(touched.len());
        for i in touched {
            let now = self.violators_of(i, sigma);
            saved.push((i, self.replace_violators(i, now)));
        }
        let result = self.split(sigma);
        for (i, old) in saved.into_iter().rev() {
            self.replace_violators(i, old);
        }
        result
    }

    /// The case split at a node that neither the goal nor a constraint closes.
    fn split(&mut self, sigma: &mut Vec<Option<bool>>) -> Result<Proof, String> {
        let next =
            self.unit_atom(sigma).or_else(|| first_unassigned(&self.goal, sigma)).or_else(|| {
                self.views.iter().find_map(|(l, r)| {
                    let undetermined = eval3(l, sigma).is_none() || eval3(r, sigma).is_none();
                    if undetermined {
                        first_unassigned(l, sigma).or_else(|| first_unassigned(r, sigma))
                    } else {
                        None
                    }
                })
            });
        let Some(atom) = next else {
            return Err("the skeleton has a countermodel".into());
        };
        let class = self.reps[atom];
        self.set(sigma, atom, Some(true));
        let one = self.prove(sigma, Some(class));
        self.set(sigma, atom, Some(false));
        let zero = self.prove(sigma, Some(class));
        self.set(sigma, atom, None);
        Ok(Proof::CaseSplit {
            atom: self.atoms.terms[class].clone(),
            one: Box::new(one?),
            zero: Box::new(zero?),
        })
    }

    /// Sets constraint `i`'s violators, keeping `units` in step; returns the old ones.
    fn replace_violators(&mut self, i: usize, now: Vec<usize>) -> Vec<usize> {
        if now.is_empty() {
            self.units.remove(&i);
        } else {
            self.units.insert(i);
        }
        std::mem::replace(&mut self.violators[i], now)
    }

    /// The unassigned classes of constraint `i` one of whose values violates it.
    fn violators_of(&self, i: usize, sigma: &mut [Option<bool>]) -> Vec<usize> {
        let mut out = Vec::new();
        let (l, r) = &self.views[i];
        if eval3(l, sigma).is_some() && eval3(r, sigma).is_some() {
            return out;
        }
        for &a in &self.atoms_of[i] {
            let class = self.reps[a];
            if sigma[a].is_some() || out.contains(&class) {
                continue;
            }
            for value in [true, false] {
                self.set(sigma, a, Some(value));
                let hit = self.violated(i, sigma);
                self.set(sigma, a, None);
                if hit {
                    out.push(class);
                    break;
                }
            }
        }
        out
    }

    /// Assigns a value to every atom of `atom`'s class.
    fn set(&self, sigma: &mut [Option<bool>], atom: usize, value: Option<bool>) {
        for &i in &self.members[self.reps[atom]] {
            sigma[i] = value;
        }
    }

    /// Is constraint `i` violated under the assignment?
    fn violated(&self, i: usize, sigma: &[Option<bool>]) -> bool {
        let (l, r) = &self.views[i];
        violated(self.constraints[i].rel, l, r, sigma)
    }

    /// Does the assignment close the branch at once (the goal is `0*`, or a constraint
    /// on `atom`'s class is violated)?
    fn closes_by(&self, atom: usize, sigma: &[Option<bool>]) -> bool {
        eval3(&self.goal, sigma) == Some(false)
            || self.occurs[self.reps[atom]].iter().any(|&i| self.violated(i, sigma))
    }

    /// Where a class first stands among the candidates of [`Search::unit_atom`]: the
    /// goal's atoms in order, then the atoms of each undecided constraint in order.
    fn position(&self, class: usize, sigma: &[Option<bool>]) -> (usize, usize, usize) {
        if let Some(p) = self.goal_atoms.iter().position(|a| self.reps[*a] == class) {
            return (0, p, 0);
        }
        for &i in &self.occurs[class] {
            let (l, r) = &self.views[i];
            if eval3(l, sigma).is_none() || eval3(r, sigma).is_none() {
                let at = self.atoms_of[i].iter().position(|a| self.reps[*a] == class);
                return (1, i, at.unwrap_or(0));
            }
        }
        (2, 0, 0)
    }

    /// An unassigned atom of the goal or a constraint one of whose values closes the
    /// branch at once, so that splitting on it costs one short case (unit propagation).
    /// Atoms that close the branch for both values come first, then the order of the
    /// goal and the constraints. Only the goal's classes and the constraints' known
    /// violators can close it, so only they are tried.
    fn unit_atom(&self, sigma: &mut [Option<bool>]) -> Option<usize> {
        let mut classes: Vec<usize> = Vec::new();
        for &a in &self.goal_atoms {
            if sigma[a].is_none() {
                classes.push(self.reps[a]);
            }
        }
        for &i in &self.units {
            classes.extend(self.violators[i].iter().copied());
        }
        let mut seen = std::collections::HashSet::new();
        let mut both: Option<((usize, usize, usize), usize)> = None;
        let mut unit: Option<((usize, usize, usize), usize)> = None;
        for class in classes {
            if !seen.insert(class) {
                continue;
            }
            self.set(sigma, class, Some(true));
            let one = self.closes_by(class, sigma);
            self.set(sigma, class, Some(false));
            let zero = self.closes_by(class, sigma);
            self.set(sigma, class, None);
            if !(one || zero) {
                continue;
            }
            let at = (self.position(class, sigma), class);
            let best = if one && zero { &mut both } else { &mut unit };
            if best.is_none_or(|b| at.0 < b.0) {
                *best = Some(at);
            }
        }
        both.or(unit).map(|(_, class)| class)
    }

    /// `G = G·1* = G·0* = 0*`, where `1* = … = 0*` runs through the violated constraint.
    fn contradiction(&self, c: &Constraint, l: &B, r: &B, sigma: &[Option<bool>]) -> Proof {
        let g = &self.goal_term;
        let mut whole = and(g, &constant(true));
        let mut steps = vec![step(vec![], law("and_one", Use::Backward), whole.clone())];
        let vl = eval3(l, sigma) == Some(true);
        // Start from the side that is 1 (for `⇒`, the left side).
        let (from_view, from_term, forward) =
            if vl { (l, &c.lhs, true) } else { (r, &c.rhs, false) };
        // 1* back up to that side.
        let mut scratch = from_term.clone();
        let mut eval_steps = Vec::new();
        evaluate(&mut scratch, &[], from_view, sigma, self.atoms, &mut eval_steps);
        let up = reverse(from_term, eval_steps);
        for s in up {
            let mut path = vec![1];
            path.extend(&s.path);
            whole = replace_at(&whole, &[1], &s.after);
            steps.push(Step { path, after: whole.clone(), ..s });
        }
        // Cite the constraint (through its raw, unevaluated-delay form).
        let (raw_from, raw_to) = if forward { (&c.raw.0, &c.raw.1) } else { (&c.raw.1, &c.raw.0) };
        let (how, result_raw) = match (c.rel, forward) {
            (Rel::Eq, true) => (Use::Forward, raw_to.clone()),
            (Rel::Eq, false) => (Use::Backward, raw_to.clone()),
            (Rel::Implies, _) => (Use::Meet, and(&c.raw.0, &c.raw.1)),
        };
        let cite = Rule::Cite(c.source, c.name.clone(), how);
        if c.shifted {
            // Back from the atoms to `pre` of the side, the hypothesis under `pre`, and
            // `pre` pushed down again.
            for s in cite_shifted(raw_from, cite, &result_raw).1 {
                whole = replace_at(&whole, &[1], &s.after);
                steps.push(Step {
                    path: [vec![1], s.path.clone()].concat(),
                    after: whole.clone(),
                    ..s
                });
            }
        } else {
            align_delays(&mut whole, &[1], from_term, raw_from, &mut steps);
            whole = replace_at(&whole, &[1], &result_raw);
            steps.push(Step { premises: c.premises.clone(), ..step(vec![1], cite, whole.clone()) });
            let result = fold_delays(&result_raw);
            align_delays(&mut whole, &[1], &result_raw, &result, &mut steps);
        }
        // The result evaluates to 0*.
        let result_view = match (c.rel, forward) {
            (Rel::Eq, true) => r.clone(),
            (Rel::Eq, false) => l.clone(),
            (Rel::Implies, _) => B::And(Box::new(l.clone()), Box::new(r.clone())),
        };
        evaluate(&mut whole, &[1], &result_view, sigma, self.atoms, &mut steps);
        whole = constant(false);
        steps.push(step(vec![], law("and_zero", Use::Forward), whole));
        Proof::Chain { start: g.clone(), steps }
    }
}

/// Why the skeleton method did not prove the goal.
#[derive(Clone, Debug)]
pub enum Failure {
    /// The skeleton has a model: atom values under which every constraint holds and the goal fails.
    Countermodel(Vec<(Expr, bool)>),
    /// A limit was reached.
    Limit(String),
}

/// The constraints left (those equating two atoms merged into classes), the Boolean
/// views of the goal and of each constraint, and each atom's representative.
type Skeleton = (Vec<Constraint>, B, Vec<(B, B)>, Vec<usize>);

/// The Boolean views of `goal` and of the constraints (hypotheses equating two atoms
/// merged into classes), and each atom's representative.
fn skeleton(goal: &Expr, constraints: &[Constraint], atoms: &mut Atoms) -> Skeleton {
    let mut constraints = constraints.to_vec();
    atoms.view(goal, root(goal));
    register(atoms, &constraints);
    atoms.merge_equal(&mut constraints);
    let goal_view = atoms.view(goal, root(goal));
    let reps: Vec<usize> = (0..atoms.terms.len()).map(|i| atoms.rep(i)).collect();
    let views: Vec<(B, B)> = constraints
        .iter()
        .map(|c| (atoms.view(&c.lhs, root(&c.lhs)), atoms.view(&c.rhs, root(&c.rhs))))
        .collect();
    (constraints, goal_view, views, reps)
}

/// A model of the skeleton in which `goal` is 1: each atom's value, by its printed form.
pub fn model_of(
    goal: &Expr,
    constraints: &[Constraint],
    atoms: &mut Atoms,
) -> Option<HashMap<String, bool>> {
    let (constraints, goal_view, views, reps) = skeleton(goal, constraints, atoms);
    let model = satisfiable(&goal_view, &constraints, &views, &reps)?;
    Some(model.into_iter().enumerate().map(|(i, v)| (atoms.terms[i].to_string(), v)).collect())
}

/// Decides `goal = 0*` over the skeleton with a SAT solver; if valid, builds a case-split proof.
pub fn prove_zero(
    goal: &Expr,
    constraints: &[Constraint],
    atoms: &mut Atoms,
    max_leaves: usize,
    deadline: Instant,
) -> Result<Proof, Failure> {
    let given = constraints;
    let (constraints, goal_view, views, reps) = skeleton(goal, constraints, atoms);
    let constraints = &constraints[..];
    let mut members = vec![Vec::new(); reps.len()];
    for (i, r) in reps.iter().enumerate() {
        members[*r].push(i);
    }
    let mut occurs = vec![Vec::new(); reps.len()];
    for (i, (l, r)) in views.iter().enumerate() {
        let mut found = Vec::new();
        atoms_in(l, &mut found);
        atoms_in(r, &mut found);
        for a in found {
            let list: &mut Vec<usize> = &mut occurs[reps[a]];
            if list.last() != Some(&i) {
                list.push(i);
            }
        }
    }
    if let Some(model) = satisfiable(&goal_view, constraints, &views, &reps) {
        let assignment =
            model.into_iter().enumerate().map(|(i, v)| (atoms.terms[i].clone(), v)).collect();
        return Err(Failure::Countermodel(assignment));
    }
    let mut goal_atoms = Vec::new();
    atoms_in(&goal_view, &mut goal_atoms);
    let atoms_of: Vec<Vec<usize>> = views
        .iter()
        .map(|(l, r)| {
            let mut found = Vec::new();
            atoms_in(l, &mut found);
            atoms_in(r, &mut found);
            found
        })
        .collect();
    let mut search = Search {
        goal: goal_view,
        goal_term: goal.clone(),
        constraints,
        violators: vec![Vec::new(); views.len()],
        units: Default::default(),
        views,
        atoms,
        members,
        occurs,
        reps,
        goal_atoms,
        atoms_of,
        leaves: 0,
        max_leaves,
        // A quarter of the time left: the refutation below gets the rest.
        deadline: Instant::now() + deadline.saturating_duration_since(Instant::now()) / 4,
    };
    let mut sigma = vec![None; search.atoms.terms.len()];
    // Cases read best; where they run past their limits (an adder's carries under an
    // invariant), a refutation the kernel checks clause by clause.
    match search.prove(&mut sigma, None) {
        Ok(proof) => Ok(prune(proof)),
        Err(why) if Instant::now() < deadline => refute(goal, given).ok_or(Failure::Limit(why)),
        Err(why) => Err(Failure::Limit(why)),
    }
}

/// At most this many clauses derived by the SAT solver are put in a refutation.
const MAX_DERIVED: usize = 50_000;

/// `goal = 0*` by a propositional refutation: the constraints as facts, the goal and the
/// facts as clauses ([`Cnf`], the kernel's own encoding), and the clauses the SAT solver
/// derives on its way to the empty one (its DRAT proof without deletions), which the
/// kernel checks by unit propagation.
pub fn refute(goal: &Expr, constraints: &[Constraint]) -> Option<Proof> {
    let facts: Vec<(Proof, Expr, Expr)> = constraints.iter().map(fact).collect();
    let mut cnf = Cnf::with_goal(goal);
    for (_, lhs, rhs) in &facts {
        cnf.fact(lhs, true, rhs);
    }
    let mut drat: Vec<u8> = Vec::new();
    {
        let mut solver = Traced::new("refute");
        solver.solver.write_proof(&mut drat, ProofFormat::Drat);
        for clause in &cnf.clauses {
            let lits: Vec<Lit> = clause.iter().map(|&l| Lit::from_dimacs(l as isize)).collect();
            solver.add_clause(&lits);
        }
        if solver.solve(&[]).ok()? {
            return None;
        }
        solver.solver.close_proof().ok()?;
    }
    let text = String::from_utf8(drat).ok()?;
    let mut lemmas: Vec<Vec<i32>> = Vec::new();
    for line in text.lines().filter(|l| !l.starts_with('d')) {
        let lits: Vec<i32> = line.split_whitespace().filter_map(|w| w.parse().ok()).collect();
        match lits.split_last() {
            Some((0, clause)) => lemmas.push(clause.to_vec()),
            _ => return None,
        }
        if lemmas.len() > MAX_DERIVED {
            return None;
        }
    }
    let facts = facts.into_iter().map(|(proof, ..)| proof).collect();
    Some(Proof::Refutation { goal: goal.clone(), facts, lemmas })
}

/// A proof of constraint `c` as an equation between the terms it relates (`a ⇒ b` as
/// `a = a·b`), with `pre` pushed down to the atoms for one a scan earlier; and that
/// equation's sides.
fn fact(c: &Constraint) -> (Proof, Expr, Expr) {
    let (how, result) = match c.rel {
        Rel::Eq => (Use::Forward, c.raw.1.clone()),
        Rel::Implies => (Use::Meet, and(&c.raw.0, &c.raw.1)),
    };
    let cite = Rule::Cite(c.source, c.name.clone(), how);
    let (start, steps) = if c.shifted {
        cite_shifted(&c.raw.0, cite, &result)
    } else {
        let cited = Step { premises: c.premises.clone(), ..step(vec![], cite, result) };
        (c.raw.0.clone(), vec![cited])
    };
    let end = steps.last().map_or_else(|| start.clone(), |s| s.after.clone());
    (Proof::Chain { start: start.clone(), steps }, start, end)
}

/// A constraint cited one scan earlier, from its side `from` with `pre` pushed down to the
/// atoms: back up to `pre from`, the citation under `pre` (giving `pre result`), and `pre`
/// pushed down again. The chain's start and steps.
fn cite_shifted(from: &Expr, cite: Rule, result: &Expr) -> (Expr, Vec<Step>) {
    let (start, push) = push_pre(&pre(from));
    let mut steps = reverse(&pre(from), push);
    steps.push(step(vec![0], cite, pre(result)));
    steps.extend(push_pre(&pre(result)).1);
    (start, steps)
}

/// Does any step of the proof rewrite with the case assumption on `atom`?
fn uses_case(proof: &Proof, atom: &Expr) -> bool {
    match proof {
        Proof::Chain { steps, .. } => {
            steps.iter().any(|s| matches!(&s.rule, Rule::Case(a, _) if crate::term::same(a, atom)))
        }
        Proof::CaseSplit { one, zero, .. } => uses_case(one, atom) || uses_case(zero, atom),
        Proof::Symm(p) | Proof::ImpliesByMeet(p) | Proof::ImpliesByZero(p) => uses_case(p, atom),
        Proof::Antisym(p, q) | Proof::Trans(p, q) => uses_case(p, atom) || uses_case(q, atom),
        // Its base and step are closed proofs: no case assumption of the context reaches them.
        Proof::Induction { .. } => false,
        Proof::Refutation { facts, .. } => facts.iter().any(|p| uses_case(p, atom)),
    }
}

/// Drops case splits whose assumption one branch never uses: that branch alone proves
/// the statement.
fn prune(proof: Proof) -> Proof {
    match proof {
        Proof::CaseSplit { atom, one, zero } => {
            let (one, zero) = (prune(*one), prune(*zero));
            if !uses_case(&one, &atom) {
                one
            } else if !uses_case(&zero, &atom) {
                zero
            } else {
                Proof::CaseSplit { atom, one: Box::new(one), zero: Box::new(zero) }
            }
        }
        other => other,
    }
}

/// A model of `goal ∧ constraints` over the atoms, if there is one.
fn satisfiable(
    goal: &B,
    constraints: &[Constraint],
    views: &[(B, B)],
    reps: &[usize],
) -> Option<Vec<bool>> {
    let mut solver = Traced::new("split");
    // Atoms of one class share the representative's variable.
    let own: Vec<Lit> = (0..reps.len()).map(|_| solver.new_lit()).collect();
    let atom_vars: Vec<Lit> = reps.iter().map(|r| own[*r]).collect();
    let truth = solver.new_lit();
    solver.add_clause(&[truth]);
    fn encode(b: &B, s: &mut Traced, atoms: &[Lit], truth: Lit) -> Lit {
        match b {
            B::Const(v) => {
                if *v {
                    truth
                } else {
                    !truth
                }
            }
            B::Atom(i) => atoms[*i],
            B::Not(a) => !encode(a, s, atoms, truth),
            B::And(a, c) | B::Or(a, c) => {
                let (x, y) = (encode(a, s, atoms, truth), encode(c, s, atoms, truth));
                let z = s.new_lit();
                if matches!(b, B::And(..)) {
                    s.add_clause(&[!z, x]);
                    s.add_clause(&[!z, y]);
                    s.add_clause(&[z, !x, !y]);
                } else {
                    s.add_clause(&[z, !x]);
                    s.add_clause(&[z, !y]);
                    s.add_clause(&[!z, x, y]);
                }
                z
            }
        }
    }
    let g = encode(goal, &mut solver, &atom_vars, truth);
    solver.add_clause(&[g]);
    for (c, (l, r)) in constraints.iter().zip(views) {
        let (x, y) =
            (encode(l, &mut solver, &atom_vars, truth), encode(r, &mut solver, &atom_vars, truth));
        solver.add_clause(&[!x, y]);
        if c.rel == Rel::Eq {
            solver.add_clause(&[x, !y]);
        }
    }
    match solver.solve(&[]) {
        Ok(true) => {
            let model = solver.solver.model()?;
            let set: std::collections::HashSet<Lit> = model.into_iter().collect();
            Some(atom_vars.iter().map(|l| set.contains(l)).collect())
        }
        _ => None,
    }
}
