//! Timer chains for induction over scans (untrusted search): how long a timer's input has been on, as the shorter timers of that input, with lemmas of their scan recurrences.
//!
//! On a program's scans a timer of `P` cycles counts one cycle per scan
//! (`theories/scan.ii`): `kδ/f = f · pre ((k−1)δ/f)` (`ton_scan`), `δ/f = f · pre f ·
//! δ/1*` (`ton_scan_one`), and the same for off-delays with `+` (`tof_scan`,
//! `tof_scan_one`). For each timer of the cone whose delay is `P` whole cycles, the
//! *chain* is `T_1 = δ/f, …, T_P = Pδ/f`; its lemmas are these recurrences, each one
//! law step that the kernel checks. The invariant search then reads the chain at the
//! previous scan: the atoms `pre T_k` are 0 at the first scan (every timer is), so the
//! induction's base needs nothing about timers, and the step relates them through the
//! lemmas, now and (a lemma true before the first scan rewrites under `pre`) one scan
//! earlier. A clause `¬pre T_k + pre U_k` says "`f` has not been on for `k` scans
//! without `g`"; that is what an upper bound on an on-time or a timer racing another
//! needs. Nothing here is trusted: a wrong lemma or clause is refused by the kernel.

use std::collections::BTreeSet;

use super::boolean::Constraint;
use super::constraint;
use super::induction::{pre, push_pre};
use crate::kernel::{Axiom, Proof, Rel, Rule, Source, Step, Use};
use crate::term::{Delay, Expr, Id, Term, and, constant, copy_into, or, root, subterm};

/// At most this many chain atoms (`pre T_k`) over all timers of a goal.
pub const MAX_ATOMS: usize = 400;

/// The lemma names of this module, after the invariant's own name `P`: `P_t{i}_{k}`
/// (chain `i`'s recurrence of `T_k`), `…_mono` (`T_k ⇒ T_(k−1)`), `P_t{i}_started`,
/// `P_m{i}` (a memory's recurrence), `P_s{i}` (the step's clause `i`), and `…_pre`, a
/// lemma one scan earlier.
const CHAIN: &str = "_t";
const MONO: &str = "_mono";
const STARTED: &str = "_started";
const PREVIOUS: &str = "_pre";
const MEMORY: &str = "_m";
const STEP: &str = "_s";

/// What a lemma of the induction search states, read back from its name (for the
/// trace's folded view; the kernel never reads names).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LemmaKind {
    /// A lemma of a timer chain.
    Chain {
        /// Which chain (`i` of `P_t{i}`).
        chain: usize,
        /// The count `k` of `T_k` (1 for `started`).
        k: usize,
        /// `T_k`'s recurrence, `T_k ⇒ T_(k−1)`, or an off-delay's `pre U ⇒ δ/1*`.
        form: ChainForm,
        /// The same one scan earlier.
        previous: bool,
    },
    /// A memory's scan recurrence.
    Memory(usize),
    /// The induction step for one clause of the invariant.
    Step(usize),
}

/// The forms of a chain's lemmas.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum ChainForm {
    /// `T_k = f · pre T_(k−1)` (an equation).
    Recurrence,
    /// `T_k ⇒ T_(k−1)`.
    Monotone,
    /// `pre U ⇒ δ/1*`.
    Started,
}

impl ChainForm {
    /// The relation the lemma states.
    pub fn rel(self) -> Rel {
        if self == ChainForm::Recurrence { Rel::Eq } else { Rel::Implies }
    }
}

/// The name chain `chain`'s lemmas start with (`P_t{chain}`).
pub fn chain_family(prefix: &str, chain: usize) -> String {
    format!("{prefix}{CHAIN}{chain}")
}

/// The name of the step lemma of clause `i`.
pub fn step_lemma(prefix: &str, i: usize) -> String {
    format!("{prefix}{STEP}{i}")
}

/// The kind of the lemma `name` made by the induction of invariant `prefix`.
pub fn lemma_kind(name: &str, prefix: &str) -> Option<LemmaKind> {
    let rest = name.strip_prefix(prefix)?;
    let number =
        |s: &str| s.parse::<usize>().ok().filter(|_| s.bytes().all(|b| b.is_ascii_digit()));
    if let Some(i) = rest.strip_prefix(STEP) {
        return number(i).map(LemmaKind::Step);
    }
    if let Some(i) = rest.strip_prefix(MEMORY) {
        return number(i).map(LemmaKind::Memory);
    }
    let rest = rest.strip_prefix(CHAIN)?;
    let (rest, previous) = match rest.strip_suffix(PREVIOUS) {
        Some(r) => (r, true),
        None => (rest, false),
    };
    let (chain, tail) = rest.split_once('_')?;
    let chain = number(chain)?;
    let (k, form) = if tail == &STARTED[1..] {
        (1, ChainForm::Started)
    } else if let Some(k) = tail.strip_suffix(MONO) {
        (number(k)?, ChainForm::Monotone)
    } else {
        (number(tail)?, ChainForm::Recurrence)
    };
    Some(LemmaKind::Chain { chain, k, form, previous })
}

/// One timer's chain: its input, kind and the terms `T_1 … T_P`.
#[derive(Clone, Debug)]
pub struct Chain {
    /// An on-delay (`d/f`), else an off-delay (`f/d`).
    pub on: bool,
    /// The input `f`.
    pub input: Expr,
    /// `T_k = kδ/f` (or `f/kδ`), `k = 1 … P`.
    pub timers: Vec<Expr>,
    /// The recurrence of each `T_k`: the right side of its lemma.
    pub recurrences: Vec<Expr>,
}

/// The chains of a goal's cone, with their lemmas and constraints.
#[derive(Clone, Debug, Default)]
pub struct Chains {
    /// The chains, the goal's timers first.
    pub chains: Vec<Chain>,
    /// `T_k = recurrence`, each proved by one law step, for the certificate.
    pub lemmas: Vec<(String, Proof)>,
    /// The lemmas as constraints at the current scan.
    pub now: Vec<Constraint>,
    /// The lemmas one scan earlier (those true before the first scan).
    pub before: Vec<Constraint>,
}

impl Chains {
    /// The candidate atoms: `pre T_k` of every chain, chain by chain.
    pub fn atoms(&self) -> Vec<Vec<Expr>> {
        self.chains.iter().map(|c| c.timers.iter().map(pre).collect()).collect()
    }

    /// The lemmas as they read at the first scan (each `pre` replaced by its value
    /// before it, as the kernel reads a lemma in an induction's base).
    pub fn at_first(&self) -> Vec<Constraint> {
        let first = crate::term::at_first_scan;
        let read = |c: &Constraint| {
            let stated = Axiom::ground(&c.name, first(&c.raw.0), c.rel, first(&c.raw.1));
            Constraint { source: Source::Lemma, ..constraint(&stated) }
        };
        self.now.iter().chain(&self.before).map(read).collect()
    }

    /// The names the chains' inputs read.
    pub fn input_names(&self) -> BTreeSet<String> {
        let mut out = BTreeSet::new();
        for c in &self.chains {
            for t in c.input.as_ref() {
                if let Term::Name(n) = t {
                    out.insert(n.as_str().to_string());
                }
            }
        }
        out
    }

    /// `e` with every timer that ends a chain, outside timers, memories and `pre`,
    /// replaced by its recurrence (so that it reads the chain at the previous scan,
    /// which is 0 at the first).
    pub fn unfold(&self, e: &Expr) -> Expr {
        fn go(chains: &Chains, e: &Expr, id: Id, out: &mut Expr) -> Id {
            let whole = subterm(e, id);
            for c in &chains.chains {
                if let Some(k) = c.timers.iter().position(|t| *t == whole) {
                    return copy_into(&c.recurrences[k], root(&c.recurrences[k]), out);
                }
            }
            match &e[id] {
                Term::Not(a) => {
                    let a = go(chains, e, *a, out);
                    out.add(Term::Not(a))
                }
                Term::And([a, b]) => {
                    let (a, b) = (go(chains, e, *a, out), go(chains, e, *b, out));
                    out.add(Term::And([a, b]))
                }
                Term::Or([a, b]) => {
                    let (a, b) = (go(chains, e, *a, out), go(chains, e, *b, out));
                    out.add(Term::Or([a, b]))
                }
                _ => copy_into(e, id, out),
            }
        }
        let mut out = Expr::default();
        go(self, e, root(e), &mut out);
        subterm(&out, root(&out))
    }
}

/// The chains of the timers in `terms` (the goal's sides first, then the cone's
/// hypotheses) whose delay is a whole number of `cycle`s, at most [`MAX_ATOMS`] atoms
/// in all; lemma names start with `prefix`.
pub fn chains(terms: &[&Expr], cycle: &Delay, prefix: &str) -> Chains {
    let mut found: Vec<(bool, Expr, usize)> = Vec::new();
    for e in terms {
        for t in e.as_ref() {
            let (on, d, f) = match t {
                Term::Ton([d, f]) => (true, *d, *f),
                Term::Tof([f, d]) => (false, *d, *f),
                _ => continue,
            };
            let Term::Delay(d) = &e[d] else { continue };
            let ratio = d.seconds() / cycle.seconds();
            if !ratio.is_integer() {
                continue;
            }
            let Ok(p) = usize::try_from(ratio.to_integer()) else { continue };
            let f = subterm(e, f);
            match found.iter_mut().find(|(o, g, _)| *o == on && *g == f) {
                Some(entry) => entry.2 = entry.2.max(p),
                None => found.push((on, f, p)),
            }
        }
    }
    let mut out = Chains::default();
    let mut atoms = 0;
    for (i, (on, input, p)) in found.into_iter().enumerate() {
        if p == 0 || atoms + p > MAX_ATOMS {
            continue;
        }
        atoms += p;
        let timers: Vec<Expr> = (1..=p).map(|k| timer(on, &times(cycle, k), &input)).collect();
        let mut recurrences = Vec::new();
        for k in 0..p {
            let rec = recurrence(on, &input, &timers, k, cycle);
            let name = format!("{}_{}", chain_family(prefix, i), k + 1);
            let (law, statement) =
                (law(on, k), Axiom::ground(&name, timers[k].clone(), Rel::Eq, rec.clone()));
            let proof = Proof::Chain {
                start: timers[k].clone(),
                steps: vec![Step {
                    path: Vec::new(),
                    rule: Rule::Cite(Source::Law, law.into(), Use::Forward),
                    after: rec.clone(),
                    subst: Vec::new(),
                    premises: Vec::new(),
                }],
            };
            out.lemmas.push((name.clone(), proof));
            let now = Constraint { source: Source::Lemma, ..constraint(&statement) };
            // One scan earlier, a lemma of its own: `pre T_k`, the lemma under `pre`
            // (it holds before the first scan), then `pre` pushed down.
            if statement.holds_initially() {
                let (rhs, push) = push_pre(&pre(&rec));
                let mut steps = vec![Step {
                    path: vec![0],
                    rule: Rule::Cite(Source::Lemma, name.clone(), Use::Forward),
                    after: pre(&rec),
                    subst: Vec::new(),
                    premises: Vec::new(),
                }];
                steps.extend(push);
                let earlier = format!("{name}{PREVIOUS}");
                let lhs = pre(&timers[k]);
                let proof = Proof::Chain { start: lhs.clone(), steps };
                out.lemmas.push((earlier.clone(), proof));
                let stated = Axiom::ground(&earlier, lhs, Rel::Eq, rhs);
                out.before.push(Constraint { source: Source::Lemma, ..constraint(&stated) });
            }
            out.now.push(now);
            recurrences.push(rec);
            if k > 0 {
                out.monotone(on, &name, &timers[k], &timers[k - 1]);
            }
        }
        if !on {
            out.started(&chain_family(prefix, i), &timers[0], cycle);
        }
        out.chains.push(Chain { on, input, timers, recurrences });
    }
    out
}

impl Chains {
    /// The scan recurrence of each memory `M` of `memories` (`sr_scan`, `rs_scan`) as a
    /// lemma `M = s + ¬r · pre M` (`M = ¬r · (s + pre M)`), named `{prefix}_m{i}`: read
    /// at the first scan (as the kernel reads a lemma in an induction's base) it gives
    /// the memory's first value, which the law alone leaves open.
    pub fn add_memories(&mut self, memories: &[Expr], prefix: &str) {
        for (i, m) in memories.iter().enumerate() {
            let (law, rec) = match &m[root(m)] {
                Term::Sr([a, b]) => {
                    let (s, r) = (subterm(m, *a), subterm(m, *b));
                    ("sr_scan", or(&s, &and(&crate::term::not(&r), &pre(m))))
                }
                Term::Rs([a, b]) => {
                    let (s, r) = (subterm(m, *a), subterm(m, *b));
                    ("rs_scan", and(&crate::term::not(&r), &or(&s, &pre(m))))
                }
                _ => continue,
            };
            let name = format!("{prefix}{MEMORY}{i}");
            let proof = Proof::Chain {
                start: m.clone(),
                steps: vec![Step {
                    path: Vec::new(),
                    rule: Rule::Cite(Source::Law, law.into(), Use::Forward),
                    after: rec.clone(),
                    subst: Vec::new(),
                    premises: Vec::new(),
                }],
            };
            self.lemmas.push((name.clone(), proof));
            let stated = Axiom::ground(&name, m.clone(), Rel::Eq, rec);
            self.now.push(Constraint { source: Source::Lemma, ..constraint(&stated) });
        }
    }

    /// `pre U ⇒ δ/1*` (`tof_started`) for an off-delay `U`, now and, as a lemma under
    /// `pre`, at the previous scan: an off-delay seen on at the previous scan says that
    /// this is not the first scan (what a count from a release needs).
    fn started(&mut self, name: &str, off: &Expr, cycle: &Delay) {
        let (from, to) = (pre(off), timer(true, cycle, &constant(true)));
        let step = |path: Vec<usize>, source, law: &str, after: &Expr| Step {
            path,
            rule: Rule::Cite(source, law.into(), Use::Forward),
            after: after.clone(),
            subst: Vec::new(),
            premises: Vec::new(),
        };
        let (now, before) = (format!("{name}{STARTED}"), format!("{name}{STARTED}{PREVIOUS}"));
        let proof = Proof::Chain {
            start: from.clone(),
            steps: vec![step(vec![], Source::Law, "tof_started", &to)],
        };
        self.lemmas.push((now.clone(), proof));
        let (pf, pt) = (pre(&from), pre(&to));
        let proof = Proof::Chain {
            start: pf.clone(),
            steps: vec![step(vec![0], Source::Lemma, &now, &pt)],
        };
        self.lemmas.push((before.clone(), proof));
        for (name, l, r) in [(now, from, to), (before, pf, pt)] {
            let stated = Axiom::ground(&name, l, Rel::Implies, r);
            self.now.push(Constraint { source: Source::Lemma, ..constraint(&stated) });
        }
    }

    /// `T_k ⇒ T_(k−1)` (`ton_longer`; `U_(k−1) ⇒ U_k` by `tof_shorter`), now and, as
    /// a lemma under `pre` (0 ⇒ 0 before the first scan), at the previous scan.
    fn monotone(&mut self, on: bool, name: &str, longer: &Expr, shorter: &Expr) {
        let (from, to, law) =
            if on { (longer, shorter, "ton_longer") } else { (shorter, longer, "tof_shorter") };
        let step = |path: Vec<usize>, source, law: &str, after: &Expr| Step {
            path,
            rule: Rule::Cite(source, law.into(), Use::Forward),
            after: after.clone(),
            subst: Vec::new(),
            premises: Vec::new(),
        };
        let (now, before) = (format!("{name}{MONO}"), format!("{name}{MONO}{PREVIOUS}"));
        let proof =
            Proof::Chain { start: from.clone(), steps: vec![step(vec![], Source::Law, law, to)] };
        self.lemmas.push((now.clone(), proof));
        let (pf, pt) = (pre(from), pre(to));
        let proof = Proof::Chain {
            start: pf.clone(),
            steps: vec![step(vec![0], Source::Lemma, &now, &pt)],
        };
        self.lemmas.push((before.clone(), proof));
        for (name, l, r) in [(now, from.clone(), to.clone()), (before, pf, pt)] {
            let stated = Axiom::ground(&name, l, Rel::Implies, r);
            self.now.push(Constraint { source: Source::Lemma, ..constraint(&stated) });
        }
    }
}

/// The law that gives `T_(k+1)`'s recurrence.
fn law(on: bool, k: usize) -> &'static str {
    match (on, k) {
        (true, 0) => "ton_scan_one",
        (true, _) => "ton_scan",
        (false, 0) => "tof_scan_one",
        (false, _) => "tof_scan",
    }
}

/// `T_(k+1)` by its scan law: `f · pre T_k` (`f + pre T_k`), and for one cycle
/// `f · pre f · δ/1*` (`f + pre f · δ/1*`).
fn recurrence(on: bool, f: &Expr, timers: &[Expr], k: usize, cycle: &Delay) -> Expr {
    let combine = if on { and } else { or };
    if k == 0 {
        let later = timer(true, cycle, &constant(true));
        if on { and(&and(f, &pre(f)), &later) } else { or(f, &and(&pre(f), &later)) }
    } else {
        combine(f, &pre(&timers[k - 1]))
    }
}

/// `k` cycles.
fn times(cycle: &Delay, k: usize) -> Delay {
    let k = crate::semantics::Time::from_integer(k.into());
    Delay::new(cycle.seconds() * k).expect("a positive multiple of a positive delay")
}

/// `d/f` (`on`) or `f/d`.
fn timer(on: bool, d: &Delay, f: &Expr) -> Expr {
    let mut out = Expr::default();
    let node = if on {
        let d = out.add(Term::Delay(d.clone()));
        let f = copy_into(f, root(f), &mut out);
        Term::Ton([d, f])
    } else {
        let f = copy_into(f, root(f), &mut out);
        let d = out.add(Term::Delay(d.clone()));
        Term::Tof([f, d])
    };
    out.add(node);
    subterm(&out, root(&out))
}

/// Chain atoms pair with the literals of this many state bits (the goal's first).
const NEAR_STATE: usize = 0;

/// At most this many candidate clauses about chains.
const MAX_CLAUSES: usize = 20_000;

/// Candidate clauses about the chains: `pre X` and `¬pre X` for the chains' input
/// names and their disjunctions of two; each chain atom `pre T_k` alone, negated, with
/// `¬pre T_k + pre T_(k−1)`, with `¬pre T_k + pre U_k` for every other chain's atom of
/// the same count, and `¬pre T_k + ℓ` for the literals `ℓ` of the first state bits.
pub fn clauses(
    chains: &Chains,
    state: &[String],
    inputs: &BTreeSet<String>,
    memories: &[Expr],
) -> Vec<Expr> {
    let name = |n: &String| crate::term::name(n);
    let previous: Vec<Expr> = inputs.iter().map(|n| pre(&name(n))).collect();
    let mut lits: Vec<Expr> = Vec::new();
    for a in state.iter().map(name).chain(previous.iter().cloned()) {
        lits.push(crate::term::not(&a));
        lits.push(a);
    }
    let mut out: Vec<Expr> = Vec::new();
    for p in &previous {
        out.extend([p.clone(), crate::term::not(p)]);
    }
    let first_previous = 2 * state.len();
    for i in first_previous..lits.len() {
        for j in 0..lits.len() {
            if j / 2 != i / 2 && (j < first_previous || j > i) {
                out.push(or(&lits[i], &lits[j]));
            }
        }
    }
    // A memory of the goal (a request still waiting) against the literals of the state
    // bits and of the chains' inputs.
    let mut others: Vec<Expr> = state.iter().map(name).collect();
    others.extend(chains.chains.iter().map(|c| c.input.clone()).filter(|i| !memories.contains(i)));
    for m in memories {
        for l in [m.clone(), crate::term::not(m)] {
            out.push(l.clone());
            for s in &others {
                out.push(or(&l, s));
                out.push(or(&l, &crate::term::not(s)));
            }
        }
    }
    // With a memory in the goal (a request waiting for its answer), the chains at the
    // current scan: `¬T_k` and `¬T_k + U_k` (the request against the timer that answers
    // it), whose reading one scan earlier is about the atoms `pre T_k`.
    let current = if memories.is_empty() { &[][..] } else { &chains.chains[..] };
    for (c, chain) in current.iter().enumerate() {
        for (k, t) in chain.timers.iter().enumerate() {
            let off = crate::term::not(t);
            out.push(off.clone());
            for (d, other) in current.iter().enumerate() {
                if d != c
                    && let Some(u) = other.timers.get(k)
                {
                    out.push(or(&off, u));
                }
            }
        }
    }
    // An off-delay's input last on exactly `k` scans ago (`pre U_k · ¬pre U_(k−1)`,
    // `U_0` its input) against how long an on-delay's input has been on (`pre T_j`,
    // `j ≤ k`, `T_0` its input): what a minimum on-time after a release needs.
    for off in chains.chains.iter().filter(|c| !c.on) {
        for on in chains.chains.iter().filter(|c| c.on && c.input != off.input) {
            for k in 0..off.timers.len() {
                let shorter = if k == 0 { pre(&off.input) } else { pre(&off.timers[k - 1]) };
                let exact = or(&crate::term::not(&pre(&off.timers[k])), &shorter);
                for j in 0..=k.min(on.timers.len()) {
                    let long = if j == 0 { pre(&on.input) } else { pre(&on.timers[j - 1]) };
                    out.push(or(&exact, &long));
                }
            }
        }
    }
    let atoms = chains.atoms();
    for (c, chain) in atoms.iter().enumerate() {
        for (k, a) in chain.iter().enumerate() {
            let off = crate::term::not(a);
            out.extend([a.clone(), off.clone()]);
            if k > 0 {
                out.push(or(&off, &chain[k - 1]));
            }
            for (d, other) in atoms.iter().enumerate() {
                if d != c
                    && let Some(b) = other.get(k)
                {
                    out.push(or(&off, b));
                }
            }
            out.extend(lits.iter().take(2 * NEAR_STATE).map(|l| or(&off, l)));
            if out.len() > MAX_CLAUSES {
                return out;
            }
        }
    }
    out
}

/// `p ⇒ c1 · c2 · … · cn` (the product as [`super::induction`] builds it, left-nested)
/// one clause at a time, where a single case split over all of them would multiply
/// their cases: a lemma `p ⇒ ci` for each clause (by `prove`, a proof of `p·¬ci = 0*`),
/// then `p · (c1 · … · cn) = p` by `and_assoc` and each lemma as `p · ci → p`, and the
/// implication from that meet. Lemma names are `{prefix}_s{i}`; `None` when a clause's
/// proof fails.
pub fn implies_clauses(
    p: &Expr,
    clauses: &[Expr],
    prefix: &str,
    mut prove: impl FnMut(&Expr) -> Option<Proof>,
) -> Option<(Vec<(String, Proof)>, Proof)> {
    let n = clauses.len();
    let mut lemmas = Vec::new();
    for (i, c) in clauses.iter().enumerate() {
        let zero = crate::term::and_not(p, c);
        let proof = Proof::ImpliesByZero(Box::new(prove(&zero)?));
        lemmas.push((step_lemma(prefix, i), proof));
    }
    // The products c1 · … · cj, left-nested.
    let mut prefixes = vec![clauses.first()?.clone()];
    for c in &clauses[1..] {
        let last = prefixes.last().expect("one prefix at least").clone();
        prefixes.push(and(&last, c));
    }
    // p · (c1…cn) → ((p · c1…c(n−1)) · cn) → … → ((p · c1) · c2) · … · cn.
    let mut whole = and(p, &prefixes[n - 1]);
    let start = whole.clone();
    let mut steps = Vec::new();
    let step = |path: Vec<usize>, law: Rule, after: &Expr| Step {
        path,
        rule: law,
        after: after.clone(),
        subst: Vec::new(),
        premises: Vec::new(),
    };
    for j in 0..n.saturating_sub(1) {
        // At depth j: p · (c1…c(n−1−j) · c(n−j)) → (p · c1…c(n−1−j)) · c(n−j).
        let path = vec![0; j];
        let assoc = and(&and(p, &prefixes[n - 2 - j]), &clauses[n - 1 - j]);
        whole = super::normalize::replace_at(&whole, &path, &assoc);
        steps.push(step(path, Rule::Cite(Source::Law, "and_assoc".into(), Use::Forward), &whole));
    }
    // Then p · ci → p, innermost first.
    for (i, (lemma, _)) in lemmas.iter().enumerate() {
        let path = vec![0; n - 1 - i];
        whole = super::normalize::replace_at(&whole, &path, p);
        let cite = Rule::Cite(Source::Lemma, lemma.clone(), Use::MeetBack);
        steps.push(step(path, cite, &whole));
    }
    Some((lemmas, Proof::ImpliesByMeet(Box::new(Proof::Chain { start, steps }))))
}

/// The lemmas `main` cites, directly or through the lemmas it cites, in their order.
pub fn cited(lemmas: Vec<(String, Proof)>, main: &Proof) -> Vec<(String, Proof)> {
    fn walk(p: &Proof, out: &mut BTreeSet<String>) {
        match p {
            Proof::Chain { steps, .. } => {
                for s in steps {
                    if let Rule::Cite(Source::Lemma, name, _) = &s.rule {
                        out.insert(name.clone());
                    }
                    s.premises.iter().for_each(|q| walk(q, out));
                }
            }
            Proof::CaseSplit { one, zero, .. } => [one, zero].iter().for_each(|q| walk(q, out)),
            Proof::Induction { base, step, .. } => [base, step].iter().for_each(|q| walk(q, out)),
            Proof::Symm(q) | Proof::ImpliesByMeet(q) | Proof::ImpliesByZero(q) => walk(q, out),
            Proof::Antisym(q, r) | Proof::Trans(q, r) => [q, r].iter().for_each(|q| walk(q, out)),
            Proof::Refutation { facts, .. } => facts.iter().for_each(|q| walk(q, out)),
        }
    }
    let mut wanted = BTreeSet::new();
    walk(main, &mut wanted);
    // Later lemmas cite earlier ones only: one pass from the last.
    let mut keep = vec![false; lemmas.len()];
    for (i, (name, proof)) in lemmas.iter().enumerate().rev() {
        if wanted.contains(name) {
            keep[i] = true;
            walk(proof, &mut wanted);
        }
    }
    lemmas.into_iter().zip(keep).filter_map(|(l, k)| k.then_some(l)).collect()
}

/// Instances of `ton_of_pre` (`d/pre f ⇒ pre ((d−δ)/f)`, `theories/scan.ii`) for the
/// atoms `d/pre f` whose delay is two cycles or more, whole: a timer that reads a bit
/// written later in the scan compiles to such an atom, and this relates it to the
/// bit's own timers at the previous scan. The search's instance finder leaves this law
/// out (its `d2` is named on the right side only); the kernel binds it by matching.
pub fn ton_of_pre_instances(atoms: &mut super::boolean::Atoms, cycle: &Delay) -> Vec<Constraint> {
    let mut out = Vec::new();
    let pool: Vec<Expr> = atoms.terms.clone();
    for a in &pool {
        let Term::Ton([d, x]) = &a[root(a)] else { continue };
        let (Term::Delay(d), Term::Pre(f)) = (&a[*d], &a[*x]) else { continue };
        let ratio = d.seconds() / cycle.seconds();
        if !ratio.is_integer() || ratio.to_integer() < 2u8.into() {
            continue;
        }
        let Ok(shorter) = Delay::new(d.seconds() - cycle.seconds()) else { continue };
        let rhs = pre(&timer(true, &shorter, &subterm(a, *f)));
        let stated = Axiom::ground("ton_of_pre", a.clone(), Rel::Implies, rhs);
        let c = Constraint { source: Source::Law, ..constraint(&stated) };
        atoms.view(&c.lhs, root(&c.lhs));
        atoms.view(&c.rhs, root(&c.rhs));
        out.push(c);
    }
    out
}
