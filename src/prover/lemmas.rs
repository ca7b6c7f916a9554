//! Shared lemmas: what a literal forces through the hypotheses, proved once per context.
//!
//! A goal `f ⇒ g` whose `f` has a literal `a` among its conjuncts (a signal or its
//! negation) often needs what `a` forces far away: a stoppage switches off the demand
//! of every unit along a chain. [`Store::closure`] propagates `a` through the
//! hypotheses (unit propagation on their Boolean skeleton, temporal subterms opaque)
//! and records, for each literal `ℓ` it forces, the hypothesis that forced it and the
//! forced literals that hypothesis read. The lemma `a ⇒ ℓ` is then a case proof of a
//! few steps from that hypothesis and the lemmas of those literals, checked by the
//! kernel once and cited by every later goal of the context.
//!
//! A closure depends on its seed and the hypotheses only, in a fixed order, and so does
//! each lemma: a goal's proof is the same whichever goals were proved before it, in
//! whatever order and on however many threads. Lemmas save work; they decide nothing
//! the propagation would not.

use std::collections::{HashMap, VecDeque};
use std::sync::{Arc, Mutex, OnceLock};
use std::time::{Duration, Instant};

use crate::kernel::{Axiom, Certificate, Lemmas, Proof, Rel, Source, Theorem};
use crate::term::{Expr, Term, and_not, not, root, subterm};

use super::boolean::{self, Atoms, Constraint, atoms_in, violated};
use super::{Context, constraint};

/// The closures met so far, by seed, and their lemmas.
#[derive(Default)]
pub struct Store {
    /// Per seed: its closure, computed by the first property that needs it while the
    /// others that need it wait (a seed may reach the whole program).
    closures: Mutex<HashMap<(Expr, bool), Arc<Pending>>>,
}

/// A closure, computed once by whoever asks first.
type Pending = OnceLock<Arc<Closure>>;

/// What one literal forces, in the order propagation found it.
struct Closure {
    /// The seed as a term: `a` or `¬a`.
    seed: Expr,
    forced: Vec<Forced>,
    /// Position in `forced` of each literal forced farther than [`NEAR`] (the ones
    /// offered as lemmas), by the atom's tree.
    index: HashMap<Expr, usize>,
    /// The lemma of each forced literal once proved (`None` until then, or when the
    /// kernel refused it).
    lemmas: Mutex<Vec<Option<Arc<Theorem>>>>,
}

/// A literal the seed forces.
struct Forced {
    literal: Expr,
    /// The hypothesis (by index in the context) that forced it.
    reason: usize,
    /// The earlier forced literals the hypothesis read (positions in `forced`).
    after: Vec<usize>,
    /// Hypotheses on the longest path from the seed.
    depth: usize,
}

/// A literal forced within this many hypotheses of the seed is left to the goal's own
/// case split, where the reader sees each step; only farther ones are lemmas.
const NEAR: usize = 4;
/// At most this many literals are followed from one seed.
const MAX_FORCED: usize = 200_000;
/// A forced literal whose signal more hypotheses than this mention is not followed.
const MAX_FANOUT: usize = 256;
/// A lemma's proof is a handful of cases.
const LEMMA_CASES: usize = 64;
/// Time for one lemma's case proof.
const LEMMA_TIME: Duration = Duration::from_millis(200);

impl Store {
    /// The constraints `seed ⇒ ℓ` for the literals `ℓ` on atoms of `atoms` that the
    /// literal conjuncts of `f` force, with their theorems added to `known` for the
    /// kernel.
    pub fn for_goal(
        &self,
        ctx: &Context,
        f: &Expr,
        atoms: &Atoms,
        known: &mut Lemmas,
    ) -> Vec<Constraint> {
        let mut out = Vec::new();
        for (atom, value) in literals(f) {
            let closure = self.closure(ctx, &atom, value);
            let mut wanted: Vec<usize> =
                atoms.terms.iter().filter_map(|t| closure.index.get(t).copied()).collect();
            wanted.sort_unstable();
            wanted.dedup();
            for i in wanted {
                let Some(theorem) = closure.lemma(ctx, i) else { continue };
                let (name, c) = closure.citation(i);
                out.push(c);
                known.insert(name, theorem);
            }
        }
        out
    }

    fn closure(&self, ctx: &Context, atom: &Expr, value: bool) -> Arc<Closure> {
        let cell = {
            let mut map = self.closures.lock().unwrap_or_else(|e| e.into_inner());
            map.entry((atom.clone(), value)).or_default().clone()
        };
        // Computed outside the map's lock, once.
        cell.get_or_init(|| Arc::new(propagate(ctx, atom, value))).clone()
    }
}

/// The conjuncts of `f` that are a signal or a negated signal, with the value each
/// asserts.
fn literals(f: &Expr) -> Vec<(Expr, bool)> {
    let mut out = Vec::new();
    let mut stack = vec![root(f)];
    while let Some(id) = stack.pop() {
        match &f[id] {
            Term::And([a, b]) => stack.extend([*b, *a]),
            Term::Name(_) => out.push((subterm(f, id), true)),
            Term::Not(a) if matches!(f[*a], Term::Name(_)) => out.push((subterm(f, *a), false)),
            _ => {}
        }
    }
    out
}

fn literal(atom: &Expr, value: bool) -> Expr {
    if value { atom.clone() } else { not(atom) }
}

/// Unit propagation of `atom = value` through the hypotheses that mention a signal
/// of an assigned atom: a hypothesis forces an atom when one of its two values would
/// violate it. Stops at a contradiction (the seed never holds: nothing more is needed).
fn propagate(ctx: &Context, atom: &Expr, value: bool) -> Closure {
    let mut atoms = Atoms::default();
    let seed = atoms.intern(atom);
    let mut sigma = vec![Some(value)];
    let mut position: HashMap<usize, usize> = HashMap::new();
    let mut forced: Vec<Forced> = Vec::new();
    let mut queue = VecDeque::from([seed]);
    'propagation: while let Some(a) = queue.pop_front() {
        let readers = ctx.index.mentioning(&atoms.terms[a]);
        // A literal forced on a signal most of the program reads (a hub) is kept, but
        // what it forces through every reader is not followed: each seed that reaches it
        // would pay for the whole program, and its own closure has it.
        if a != seed && readers.len() > MAX_FANOUT {
            continue;
        }
        for h in readers {
            // Viewed afresh at each visit: a seed may reach the whole program, and
            // keeping every view would hold a copy of it.
            let hyp = &ctx.hypotheses()[h];
            let (l, r) =
                (atoms.view(&hyp.lhs, root(&hyp.lhs)), atoms.view(&hyp.rhs, root(&hyp.rhs)));
            let mut inside = Vec::new();
            atoms_in(&l, &mut inside);
            atoms_in(&r, &mut inside);
            inside.sort_unstable();
            inside.dedup();
            let (l, r) = (&l, &r);
            sigma.resize(atoms.terms.len(), None);
            let rel = ctx.hypotheses()[h].rel;
            for &b in inside.iter() {
                if sigma[b].is_some() {
                    continue;
                }
                let mut violates = [false; 2];
                for (k, v) in [true, false].into_iter().enumerate() {
                    sigma[b] = Some(v);
                    violates[k] = violated(rel, l, r, &sigma);
                }
                sigma[b] = None;
                let w = match violates {
                    [true, true] => break 'propagation,
                    [true, false] => false,
                    [false, true] => true,
                    [false, false] => continue,
                };
                sigma[b] = Some(w);
                let after =
                    inside.iter().filter(|&&x| x != b).filter_map(|x| position.get(x).copied());
                let after: Vec<usize> = after.collect();
                let depth = 1 + after.iter().map(|&j| forced[j].depth).max().unwrap_or(0);
                position.insert(b, forced.len());
                let literal = literal(&atoms.terms[b], w);
                forced.push(Forced { literal, reason: h, after, depth });
                queue.push_back(b);
                if forced.len() >= MAX_FORCED {
                    break 'propagation;
                }
            }
        }
    }
    // Only far literals become lemmas; a seed that forces none keeps nothing.
    let far = |i: &usize| forced[*i].depth > NEAR;
    let index: HashMap<Expr, usize> = position
        .iter()
        .filter(|(_, i)| far(i))
        .map(|(&a, &i)| (atoms.terms[a].clone(), i))
        .collect();
    if index.is_empty() {
        forced.clear();
    }
    forced.shrink_to_fit();
    let lemmas = Mutex::new(vec![None; forced.len()]);
    Closure { seed: literal(atom, value), forced, index, lemmas }
}

impl Closure {
    /// The lemma of forced literal `i` as the case split cites it: its name and constraint.
    fn citation(&self, i: usize) -> (String, Constraint) {
        let literal = &self.forced[i].literal;
        let name = format!("{} ⇒ {literal}", self.seed);
        let axiom = Axiom::ground(&name, self.seed.clone(), Rel::Implies, literal.clone());
        (name, Constraint { source: Source::Lemma, ..constraint(&axiom) })
    }

    /// The kernel's theorem `seed ⇒ ℓ` for forced literal `i`, proving first the lemmas
    /// it rests on (in the order they were forced, so each proof finds its own).
    fn lemma(&self, ctx: &Context, i: usize) -> Option<Arc<Theorem>> {
        let mut lemmas = self.lemmas.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(t) = &lemmas[i] {
            return Some(t.clone());
        }
        let mut needed = vec![i];
        let mut stack = vec![i];
        let mut seen = std::collections::HashSet::from([i]);
        while let Some(j) = stack.pop() {
            for &k in &self.forced[j].after {
                if lemmas[k].is_none() && seen.insert(k) {
                    needed.push(k);
                    stack.push(k);
                }
            }
        }
        needed.sort_unstable();
        for j in needed {
            lemmas[j] = self.prove(ctx, j, &lemmas).map(Arc::new);
        }
        lemmas[i].clone()
    }

    /// `seed ⇒ ℓ` by cases, from the hypothesis that forced `ℓ` and the lemmas of the
    /// literals it read.
    fn prove(&self, ctx: &Context, i: usize, lemmas: &[Option<Arc<Theorem>>]) -> Option<Theorem> {
        let f = &self.forced[i];
        let mut constraints = vec![constraint(&ctx.hypotheses()[f.reason])];
        let mut known = Lemmas::new();
        for &j in &f.after {
            let (name, c) = self.citation(j);
            constraints.push(c);
            known.insert(name, lemmas[j].clone()?);
        }
        let goal = and_not(&self.seed, &f.literal);
        let deadline = Instant::now() + LEMMA_TIME;
        let mut atoms = Atoms::default();
        let proof =
            boolean::prove_zero(&goal, &constraints, &mut atoms, LEMMA_CASES, deadline).ok()?;
        let certificate =
            Certificate { lemmas: vec![], main: Some(Proof::ImpliesByZero(Box::new(proof))) };
        ctx.kernel
            .check_using(&certificate, known)
            .and_then(|t| ctx.kernel.vouch(&t, &self.seed, Rel::Implies, &f.literal).map(|()| t))
            .ok()
    }
}
