//! A compiled program unrolled over discrete steps, concretely (`bool`) or symbolically (SAT literals).
//!
//! One step is a stretch `[(k−1)·g, k·g)` of time (the first one `(0, g)`) on which every
//! input is constant. The equations are evaluated step by step in program order:
//! `·, +, ¬` pointwise, `SR(s, r)`: `Q := s + Q·¬r`, `RS(s, r)`: `Q := (s + Q)·¬r` (from
//! 0), `d/f` with `d = N·g`: `f` true at each of the steps `k−N … k` (and `k > N`),
//! `f/d`: `f` true at one of the steps `k−N … k`. For inputs constant on the steps this
//! is exactly the II algebra (`semantics.md`) sampled once per step. `pre f` is `f` at
//! the previous step (its initial value at the first): the scan cycle's meaning when a
//! step is a scan. What is read only under `pre` is computed at the end of its step.
#![warn(missing_docs)]

use std::collections::{BTreeMap, BTreeSet, HashMap};

use varisat::Lit;

use crate::program::fast_hash::FastSet;
use crate::sat_trace::Traced;

use crate::kernel::Rel;
use crate::semantics::{Assignment, Time, eval_delay};
use crate::term::{Delay, Expr, Id, Language as _, Symbol, Term, initial_values};

/// Boolean operations over some kind of value (a `bool`, a SAT literal).
pub trait Bits {
    /// A value.
    type V: Clone;
    /// A constant.
    fn konst(&mut self, b: bool) -> Self::V;
    /// Negation.
    fn not(&mut self, a: &Self::V) -> Self::V;
    /// Conjunction of all.
    fn and_all(&mut self, xs: &[Self::V]) -> Self::V;
    /// Disjunction of all.
    fn or_all(&mut self, xs: &[Self::V]) -> Self::V;
}

/// Plain Booleans.
pub struct Concrete;

impl Bits for Concrete {
    type V = bool;
    fn konst(&mut self, b: bool) -> bool {
        b
    }
    fn not(&mut self, a: &bool) -> bool {
        !a
    }
    fn and_all(&mut self, xs: &[bool]) -> bool {
        xs.iter().all(|x| *x)
    }
    fn or_all(&mut self, xs: &[bool]) -> bool {
        xs.iter().any(|x| *x)
    }
}

/// 64 runs at once: bit `i` of a value is its value in run `i`; free values come from
/// a fixed pseudo-random sequence (xorshift), so the runs are the same on every call.
pub struct Runs64 {
    state: u64,
}

impl Default for Runs64 {
    fn default() -> Self {
        Runs64 { state: 0x9e37_79b9_7f4a_7c15 }
    }
}

impl Runs64 {
    /// Runs of another fixed sequence, one per `seed`.
    pub fn seeded(seed: u64) -> Runs64 {
        let mut runs = Runs64::default();
        runs.state ^= seed.wrapping_mul(0xbf58_476d_1ce4_e5b9);
        if runs.state == 0 {
            runs.state = 1;
        }
        runs
    }

    /// The next 64 pseudo-random bits.
    pub fn random(&mut self) -> u64 {
        self.state ^= self.state << 13;
        self.state ^= self.state >> 7;
        self.state ^= self.state << 17;
        self.state
    }

    /// The next value of a free signal that was `previous` one step before. The 64 runs
    /// differ in how often a signal is 1 (in eight groups of eight runs: 1/2, 3/4, 1/4,
    /// 7/8, 1/8, 15/16, 1/16 and 1/2 of the steps) and in how long it keeps a value
    /// (within a group, redrawn at every step, at half, a quarter or a sixteenth of
    /// them), so that some runs make a long conjunction true, or hold an input long
    /// enough for its timers to expire.
    pub fn sticky(&mut self, previous: Option<u64>) -> u64 {
        let r: [u64; 4] = std::array::from_fn(|_| self.random());
        let (any2, all2) = (r[0] | r[1], r[0] & r[1]);
        let (any3, all3) = (any2 | r[2], all2 & r[2]);
        let (any4, all4) = (any3 | r[3], all3 & r[3]);
        let groups = [r[0], any2, all2, any3, all3, any4, all4, r[1]];
        let drawn = groups.iter().enumerate().fold(0, |v, (g, x)| v | (x & 0xff << (8 * g)));
        let Some(previous) = previous else { return drawn };
        let r: [u64; 4] = std::array::from_fn(|_| self.random());
        let rates = [!0, r[0], r[0] & r[1], r[0] & r[1] & r[2] & r[3]];
        // Within each group of eight runs: two per rate.
        let redraw = rates
            .iter()
            .enumerate()
            .fold(0, |v, (i, x)| v | (x & 0x0303_0303_0303_0303 << (2 * i)));
        (drawn & redraw) | (previous & !redraw)
    }
}

impl Bits for Runs64 {
    type V = u64;
    fn konst(&mut self, b: bool) -> u64 {
        if b { !0 } else { 0 }
    }
    fn not(&mut self, a: &u64) -> u64 {
        !a
    }
    fn and_all(&mut self, xs: &[u64]) -> u64 {
        xs.iter().fold(!0, |a, x| a & x)
    }
    fn or_all(&mut self, xs: &[u64]) -> u64 {
        xs.iter().fold(0, |a, x| a | x)
    }
}

/// A SAT formula under construction (Tseitin encoding, constants folded).
pub struct Cnf {
    /// The solver holding the clauses (its queries recorded when `II_PROVE_SAT_TRACE`
    /// asks for it, see [`crate::sat_trace`]).
    solver: Traced<'static>,
    truth: Lit,
}

impl Cnf {
    /// An empty formula whose queries are recorded as `kind` ([`crate::sat_trace`]).
    pub fn named(kind: &str) -> Cnf {
        let mut solver = Traced::new(kind);
        let truth = solver.new_lit();
        solver.add_clause(&[truth]);
        Cnf { solver, truth }
    }

    /// A fresh unconstrained literal.
    pub fn fresh(&mut self) -> Lit {
        self.solver.new_lit()
    }

    /// Adds `a → b`.
    pub fn imply(&mut self, a: Lit, b: Lit) {
        self.solver.add_clause(&[!a, b]);
    }

    /// Adds the clause `a`.
    pub fn require(&mut self, a: Lit) {
        self.solver.add_clause(&[a]);
    }

    /// Solves under assumptions; `Some(true literals)` when satisfiable.
    pub fn solve(&mut self, assumptions: &[Lit]) -> Option<BTreeSet<Lit>> {
        match self.solver.solve(assumptions) {
            Ok(true) => self.solver.solver.model().map(|m| m.into_iter().collect()),
            _ => None,
        }
    }

    /// Solves under `required` and as many of `preferred` as a model allows: after each
    /// unsatisfiable attempt the preferred literals of the solver's failed core are
    /// given up (at most `rounds` attempts). `Some(true literals)` when satisfiable under
    /// `required` alone within the rounds.
    pub fn solve_preferring(
        &mut self,
        required: &[Lit],
        preferred: &[Lit],
        rounds: usize,
    ) -> Option<BTreeSet<Lit>> {
        let mut kept: Vec<Lit> = preferred.to_vec();
        for _ in 0..rounds {
            let assumptions: Vec<Lit> = required.iter().chain(&kept).copied().collect();
            match self.solver.solve(&assumptions) {
                Ok(true) => return self.solver.solver.model().map(|m| m.into_iter().collect()),
                Ok(false) => {}
                Err(_) => return None,
            }
            let core: BTreeSet<Lit> = self.solver.solver.failed_core()?.iter().copied().collect();
            let before = kept.len();
            kept.retain(|l| !core.contains(l));
            if kept.len() == before {
                // The core is of required literals alone: unsatisfiable.
                return None;
            }
        }
        self.solve(required)
    }
}

impl Bits for Cnf {
    type V = Lit;
    fn konst(&mut self, b: bool) -> Lit {
        if b { self.truth } else { !self.truth }
    }
    fn not(&mut self, a: &Lit) -> Lit {
        !*a
    }
    fn and_all(&mut self, xs: &[Lit]) -> Lit {
        let mut kept: Vec<Lit> = Vec::new();
        for x in xs {
            if *x == !self.truth {
                return !self.truth;
            }
            if *x != self.truth && !kept.contains(x) {
                kept.push(*x);
            }
        }
        match kept.len() {
            0 => self.truth,
            1 => kept[0],
            _ => {
                let z = self.solver.new_lit();
                let mut long = vec![z];
                for x in &kept {
                    self.solver.add_clause(&[!z, *x]);
                    long.push(!*x);
                }
                self.solver.add_clause(&long);
                z
            }
        }
    }
    fn or_all(&mut self, xs: &[Lit]) -> Lit {
        let negated: Vec<Lit> = xs.iter().map(|x| !*x).collect();
        !self.and_all(&negated)
    }
}

/// What is unrolled: equations in evaluation order and side terms.
#[derive(Clone, Debug, Default)]
pub struct Model {
    /// `X = term`, in the order the scan computes them.
    pub defs: Vec<(String, Expr)>,
    /// Relations that must hold at every step (`assume` statements).
    pub constraints: Vec<(Expr, Rel, Expr)>,
}

impl Model {
    /// Every term of the model: the definitions' right sides and both sides of each constraint.
    fn terms(&self) -> impl Iterator<Item = &Expr> {
        let defs = self.defs.iter().map(|(_, e)| e);
        defs.chain(self.constraints.iter().flat_map(|(l, _, r)| [l, r]))
    }

    /// The names the model leaves free (not defined) among `exprs`.
    pub fn free_names<'a>(&'a self, exprs: impl Iterator<Item = &'a Expr>) -> BTreeSet<String> {
        let defined: FastSet<&str> = self.defs.iter().map(|(n, _)| n.as_str()).collect();
        let mut free: FastSet<Symbol> = FastSet::default();
        for e in self.terms().chain(exprs) {
            for node in e.as_ref() {
                if let Term::Name(n) = node
                    && !free.contains(n)
                    && !defined.contains(n.as_str())
                {
                    free.insert(*n);
                }
            }
        }
        free.into_iter().map(|n| n.as_str().to_string()).collect()
    }

    /// Every delay literal of a timer in the model and in `exprs`.
    pub fn delays<'a>(&'a self, exprs: impl Iterator<Item = &'a Expr>) -> Vec<Delay> {
        let env = Assignment::new(Time::from_integer(1.into()));
        let mut out = Vec::new();
        for e in self.terms().chain(exprs) {
            for node in e.as_ref() {
                let d = match node {
                    Term::Ton([d, _]) | Term::Tof([_, d]) => *d,
                    _ => continue,
                };
                if let Ok(d) = eval_delay(e, d, &env) {
                    out.push(d);
                }
            }
        }
        out
    }
}

/// The values of an unrolled model: per signal name and per extra term, one value a step.
#[derive(Clone, Debug)]
pub struct Unrolled<V> {
    /// Defined, free and previous-value signals.
    pub signals: BTreeMap<String, Vec<V>>,
    /// The constraints' sides, `(lhs, rhs)` per step, in order.
    pub constraints: Vec<(Vec<V>, Vec<V>)>,
    /// The extra terms' values, in order.
    pub extra: Vec<Vec<V>>,
}

impl Unrolled<bool> {
    /// The first step (0-based) at which the first two extra terms stand in violation
    /// of `rel`, every constraint of `model` having held at each step up to it.
    pub fn first_violation(&self, model: &Model, rel: Rel) -> Option<usize> {
        let (l, r) = (self.extra.first()?, self.extra.get(1)?);
        let holds = |k: usize| {
            model
                .constraints
                .iter()
                .zip(&self.constraints)
                .all(|(c, (a, b))| !violated(&mut Concrete, c.1, &a[k], &b[k]))
        };
        (0..l.len().min(r.len()))
            .take_while(|&k| holds(k))
            .find(|&k| violated(&mut Concrete, rel, &l[k], &r[k]))
    }
}

/// Unrolls `model` over `steps` steps. `steps_of(d)` is a timer's delay in steps;
/// `free(bits, name, k)` gives a free name's value at step `k` (0-based).
pub fn unroll<B: Bits>(
    bits: &mut B,
    model: &Model,
    extra: &[&Expr],
    steps: usize,
    steps_of: &dyn Fn(&Delay) -> Option<usize>,
    free: &mut dyn FnMut(&mut B, &str, usize) -> B::V,
) -> Result<Unrolled<B::V>, String> {
    let mut u = Unroller::new(model, extra, steps_of)?;
    for _ in 0..steps {
        u.step(bits, free)?;
    }
    Ok(u.finish())
}

/// [`unroll`] one step at a time: the values of step `k` depend only on steps `0..=k`,
/// so a formula of `k + 1` steps is the formula of `k` steps with one frame added (what
/// incremental bounded model checking asks one solver about, depth after depth).
pub struct Unroller<'m, V> {
    exprs: Vec<&'m Expr>,
    /// Every name the terms read or the model defines, each once: the defined ones
    /// first, in the model's order. Values are kept per slot, names resolved once here
    /// rather than looked up at every node of every step.
    names: Vec<&'m str>,
    /// Per slot, whether the model defines it.
    defined: Vec<bool>,
    /// Per equation, the slot of the name it defines.
    def_slot: Vec<usize>,
    /// Per term: per node, the slot of the name it reads (`NO_SLOT` for other nodes).
    slots: Vec<Vec<usize>>,
    constraints: usize,
    extra: usize,
    /// Per term: per node, the timer width in steps (resolved once).
    widths: Vec<Vec<Option<usize>>>,
    /// Per term: per node, its value before the first step (names, timers, memories 0).
    inits: Vec<Vec<bool>>,
    /// Per term: which nodes are needed at their own step.
    now: Vec<Vec<bool>>,
    hist: Vec<Vec<Vec<V>>>,
    /// Per slot, its value at each step computed so far.
    values: Vec<Vec<V>>,
    steps: usize,
}

/// The slot of a node that reads no name.
const NO_SLOT: usize = usize::MAX;

impl<'m, V: Clone> Unroller<'m, V> {
    /// Ready to unroll `model` and the `extra` terms; no step yet.
    pub fn new(
        model: &'m Model,
        extra: &[&'m Expr],
        steps_of: &dyn Fn(&Delay) -> Option<usize>,
    ) -> Result<Self, String> {
        let env = Assignment::new(Time::from_integer(1.into()));
        let mut exprs: Vec<&Expr> = model.defs.iter().map(|(_, e)| e).collect();
        for (l, _, r) in &model.constraints {
            exprs.push(l);
            exprs.push(r);
        }
        exprs.extend(extra.iter().copied());
        let mut widths: Vec<Vec<Option<usize>>> = Vec::new();
        for e in &exprs {
            let mut w = vec![None; e.as_ref().len()];
            for (i, node) in e.as_ref().iter().enumerate() {
                if let Term::Ton([d, _]) | Term::Tof([_, d]) = node {
                    let delay = eval_delay(e, *d, &env).map_err(|x| x.to_string())?;
                    w[i] = Some(
                        steps_of(&delay)
                            .ok_or_else(|| format!("the delay {delay} is not on the grid"))?,
                    );
                }
            }
            widths.push(w);
        }
        // Nodes read only under `pre` are evaluated at the end of the step, once every
        // equation of the scan is known.
        let inits = exprs.iter().map(|e| initial_values(e)).collect();
        let now = exprs.iter().map(|e| needed_now(e)).collect();
        let hist = exprs.iter().map(|e| vec![Vec::new(); e.as_ref().len()]).collect();
        let mut names: Vec<&str> = Vec::new();
        let mut slot_of: HashMap<&str, usize> = HashMap::new();
        let mut slot = |n: &'m str| {
            *slot_of.entry(n).or_insert_with(|| {
                names.push(n);
                names.len() - 1
            })
        };
        let def_slot: Vec<usize> = model.defs.iter().map(|(n, _)| slot(n.as_str())).collect();
        let slots = exprs
            .iter()
            .map(|e| {
                e.as_ref()
                    .iter()
                    .map(|node| match node {
                        Term::Name(n) => slot(n.as_str()),
                        _ => NO_SLOT,
                    })
                    .collect()
            })
            .collect();
        let mut defined = vec![false; names.len()];
        for &d in &def_slot {
            defined[d] = true;
        }
        Ok(Unroller {
            values: vec![Vec::new(); names.len()],
            names,
            defined,
            def_slot,
            slots,
            constraints: model.constraints.len(),
            extra: extra.len(),
            exprs,
            widths,
            inits,
            now,
            hist,
            steps: 0,
        })
    }

    /// How many steps are unrolled.
    pub fn steps(&self) -> usize {
        self.steps
    }

    /// Adds the next step.
    pub fn step<B: Bits<V = V>>(
        &mut self,
        bits: &mut B,
        free: &mut dyn FnMut(&mut B, &str, usize) -> V,
    ) -> Result<(), String> {
        let k = self.steps;
        let hist = &mut self.hist;
        let values = &mut self.values;
        let mut cx = Step {
            bits,
            names: &self.names,
            defined: &self.defined,
            free,
            widths: &self.widths,
            inits: &self.inits,
        };
        for (j, e) in self.exprs.iter().enumerate() {
            for (i, node) in e.as_ref().iter().enumerate() {
                let value = if self.now[j][i] {
                    cx.node(node, &hist[j], (i, self.slots[j][i]), j, k, values)?
                } else {
                    cx.bits.konst(false)
                };
                hist[j][i].push(value);
            }
            if let Some(&slot) = self.def_slot.get(j) {
                let top = hist[j].last().and_then(|v| v.get(k)).cloned();
                let name = self.names[slot];
                let top = top.ok_or_else(|| format!("the equation of `{name}` is empty"))?;
                values[slot].push(top);
            }
        }
        for (j, e) in self.exprs.iter().enumerate() {
            for (i, node) in e.as_ref().iter().enumerate() {
                if !self.now[j][i] {
                    let value = cx.node(node, &hist[j], (i, self.slots[j][i]), j, k, values)?;
                    hist[j][i][k] = value;
                }
            }
        }
        self.steps += 1;
        Ok(())
    }

    fn root(&self, j: usize, k: usize) -> Option<&V> {
        self.hist[j].last().and_then(|v| v.get(k))
    }

    /// Constraint `c`'s two sides at step `k`.
    pub fn constraint_at(&self, c: usize, k: usize) -> Option<(V, V)> {
        let d = self.def_slot.len();
        Some((self.root(d + 2 * c, k)?.clone(), self.root(d + 2 * c + 1, k)?.clone()))
    }

    /// Extra term `x`'s value at step `k`.
    pub fn extra_at(&self, x: usize, k: usize) -> Option<V> {
        self.root(self.def_slot.len() + 2 * self.constraints + x, k).cloned()
    }

    /// The values of every step unrolled.
    pub fn finish(self) -> Unrolled<V> {
        let root = |j: usize| self.hist[j].last().cloned().unwrap_or_default();
        let d = self.def_slot.len();
        let constraints =
            (0..self.constraints).map(|c| (root(d + 2 * c), root(d + 2 * c + 1))).collect();
        let extra = (0..self.extra).map(|x| root(d + 2 * self.constraints + x)).collect();
        let signals = self
            .names
            .iter()
            .zip(self.values)
            .filter(|(_, v)| !v.is_empty())
            .map(|(n, v)| (n.to_string(), v))
            .collect();
        Unrolled { signals, constraints, extra }
    }
}

/// Which nodes of `e` are read at their own step: the root and everything below it
/// except what is read only through `pre`.
pub(super) fn needed_now(e: &Expr) -> Vec<bool> {
    let nodes = e.as_ref();
    let mut now = vec![false; nodes.len()];
    if let Some(last) = now.last_mut() {
        *last = true;
    }
    for i in (0..nodes.len()).rev() {
        if now[i] && !matches!(nodes[i], Term::Pre(_)) {
            for c in nodes[i].children() {
                now[usize::from(*c)] = true;
            }
        }
    }
    now
}

/// What [`unroll`] needs to compute one node at one step.
struct Step<'a, 'm, B: Bits> {
    bits: &'a mut B,
    names: &'a [&'m str],
    defined: &'a [bool],
    free: &'a mut dyn FnMut(&mut B, &str, usize) -> B::V,
    widths: &'a [Vec<Option<usize>>],
    inits: &'a [Vec<bool>],
}

impl<B: Bits> Step<'_, '_, B> {
    /// The value at step `k` of node `i` of term `j`, whose history is `h`; `slot` is
    /// the slot of the name the node reads.
    fn node(
        &mut self,
        node: &Term,
        h: &[Vec<B::V>],
        (i, slot): (usize, usize),
        j: usize,
        k: usize,
        values: &mut [Vec<B::V>],
    ) -> Result<B::V, String> {
        let bits = &mut *self.bits;
        let at = |id: &Id| h[usize::from(*id)][k].clone();
        Ok(match node {
            Term::Zero | Term::Delay(_) | Term::DMax(_) | Term::DMin(_) | Term::DAdd(_) => {
                bits.konst(false)
            }
            Term::One => bits.konst(true),
            Term::Not(a) => {
                let a = at(a);
                bits.not(&a)
            }
            Term::Pre(a) => {
                let a = usize::from(*a);
                if k == 0 { bits.konst(self.inits[j][a]) } else { h[a][k - 1].clone() }
            }
            Term::And([a, b]) => {
                let xs = [at(a), at(b)];
                bits.and_all(&xs)
            }
            Term::Or([a, b]) => {
                let xs = [at(a), at(b)];
                bits.or_all(&xs)
            }
            Term::Sr([s, r]) | Term::Rs([s, r]) => {
                let prev = if k == 0 { bits.konst(false) } else { h[i][k - 1].clone() };
                let (s, r) = (at(s), at(r));
                let nr = bits.not(&r);
                if matches!(node, Term::Sr(_)) {
                    let hold = bits.and_all(&[prev, nr]);
                    bits.or_all(&[s, hold])
                } else {
                    let set = bits.or_all(&[s, prev]);
                    bits.and_all(&[set, nr])
                }
            }
            Term::Ton([_, f]) => {
                let n = self.widths[j][i].unwrap_or(0);
                if k < n {
                    bits.konst(false)
                } else {
                    let xs: Vec<B::V> = h[usize::from(*f)][k - n..=k].to_vec();
                    bits.and_all(&xs)
                }
            }
            Term::Tof([f, _]) => {
                let n = self.widths[j][i].unwrap_or(0);
                let xs: Vec<B::V> = h[usize::from(*f)][k.saturating_sub(n)..=k].to_vec();
                bits.or_all(&xs)
            }
            Term::Name(_) => {
                if let Some(v) = values[slot].get(k) {
                    v.clone()
                } else if self.defined[slot] {
                    return Err(format!(
                        "`{}` is read before the scan computes it",
                        self.names[slot]
                    ));
                } else {
                    let v = (self.free)(bits, self.names[slot], k);
                    values[slot].push(v.clone());
                    v
                }
            }
        })
    }
}

/// `lhs rel rhs` violated (as a value).
pub fn violated<B: Bits>(bits: &mut B, rel: Rel, l: &B::V, r: &B::V) -> B::V {
    let nr = bits.not(r);
    match rel {
        Rel::Implies => bits.and_all(&[l.clone(), nr]),
        Rel::Eq => {
            let nl = bits.not(l);
            let a = bits.and_all(&[l.clone(), nr]);
            let b = bits.and_all(&[nl, r.clone()]);
            bits.or_all(&[a, b])
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::semantics::{Signal, eval};
    use crate::term::{Symbol, sexp};
    use num_traits::ToPrimitive;

    /// The step reading agrees with the exact semantics at every step's instant, for
    /// inputs constant on `[k, k+1)` seconds (the first step `(0, 1)`).
    #[test]
    fn steps_agree_with_the_exact_semantics() {
        let terms = [
            "(ton 3s f)",
            "(tof f 2s)",
            "(sr f g)",
            "(rs f g)",
            "(ton 2s (tof (& f (! g)) 1s))",
            "(+ (sr (ton 1s f) g) (rs g (tof f 3s)))",
        ];
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        for text in terms {
            let e = sexp(text);
            for _ in 0..200 {
                let steps = 12;
                let mut values: BTreeMap<String, Vec<bool>> = BTreeMap::new();
                for n in ["f", "g"] {
                    let v: Vec<bool> = (0..steps)
                        .map(|_| {
                            seed ^= seed << 13;
                            seed ^= seed >> 7;
                            seed ^= seed << 17;
                            !seed.is_multiple_of(3)
                        })
                        .collect();
                    values.insert(n.into(), v);
                }
                let u = unroll(
                    &mut Concrete,
                    &Model::default(),
                    &[&e],
                    steps,
                    &|d| d.seconds().to_integer().to_usize(),
                    &mut |_, n, k| values[n][k],
                )
                .expect("unrolls");
                let horizon = Time::from_integer(steps.into());
                let mut env = Assignment::new(horizon.clone());
                for (n, v) in &values {
                    let changes: Vec<(Time, bool)> = (1..steps)
                        .filter(|&k| v[k] != v[k - 1])
                        .map(|k| (Time::from_integer(k.into()), v[k]))
                        .collect();
                    let s = Signal::from_steps(horizon.clone(), v[0], &changes).unwrap();
                    env.signals.insert(Symbol::from(n.as_str()), s);
                }
                let exact = eval(&e, &env).expect("evaluates");
                for k in 0..steps {
                    let t = if k == 0 {
                        Time::new(1.into(), 2.into())
                    } else {
                        Time::from_integer(k.into())
                    };
                    assert_eq!(u.extra[0][k], exact.value_at(&t), "{text} at step {k}: {values:?}");
                }
            }
        }
    }

    /// The runs `sticky` draws differ as documented: each group of eight runs is 1 about
    /// as often as its bias says, and runs redrawn rarely change value rarely.
    #[test]
    fn sticky_runs_differ_in_bias_and_in_how_long_they_hold() {
        let bias = [0.5, 0.75, 0.25, 0.875, 0.125, 0.9375, 0.0625, 0.5];
        let steps = 4096;
        let mut ones = [0usize; 64];
        let mut changes = [0usize; 64];
        for seed in 0..4 {
            let mut runs = Runs64::seeded(seed);
            let mut previous = None;
            for _ in 0..steps {
                let v = runs.sticky(previous);
                for (lane, count) in ones.iter_mut().enumerate() {
                    *count += (v >> lane & 1) as usize;
                    if let Some(p) = previous {
                        changes[lane] += ((v ^ p) >> lane & 1) as usize;
                    }
                }
                previous = Some(v);
            }
        }
        let total = (4 * steps) as f64;
        for (lane, &n) in ones.iter().enumerate() {
            let share = n as f64 / total;
            let want = bias[lane / 8];
            assert!(
                (share - want).abs() < 0.1,
                "run {lane}: 1 in {share:.3} of the steps, want {want}"
            );
        }
        for group in 0..8 {
            // Two runs per rate: every step, 1/2, 1/4 and 1/16 of the steps.
            let at = |i: usize| changes[8 * group + 2 * i] + changes[8 * group + 2 * i + 1];
            assert!(at(0) > at(1) && at(1) > at(2) && at(2) > at(3), "group {group}: {changes:?}");
            assert!(at(3) > 0, "group {group}: the slowest runs never change");
        }
    }
}
