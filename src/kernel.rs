//! The trusted kernel: re-checks every proof step and is the only maker of [`Theorem`]s.
//!
//! Everything else (search, case splitter, proof scripts) is untrusted: it produces a
//! [`Proof`] of plain data and [`Kernel::check`] replays it. The kernel imports only the
//! term module, the certificate format and `std`. It **fails closed**: an unknown rule, a
//! non-matching instance, a disagreeing substitution, a broken or truncated chain, a false
//! side condition, a rewrite at an unsound position — each is an error, never a theorem.
//!
//! # What a theorem means
//!
//! `Γ ⊢ a = b` (or `a ⇒ b`) holds at every instant `t > 0` at which the local
//! case assumptions `Γ` (pairs `x = 1*` / `x = 0*`) hold, for all signals that
//! satisfy the kernel's hypotheses and laws; with no local assumptions, at every instant.
//!
//! # The primitive rules (the whole trusted surface)
//!
//! | rule | from | gives |
//! |---|---|---|
//! | chain of rewrite steps | a term `t0` and steps | `t0 R tn` (`R` is `⇒` if any step is) |
//! | law / hypothesis / lemma step | an instance at a position | `=` anywhere; `⇒` at a monotone position |
//! | implication used as equation | `p ⇒ q` | `p = p·q` (meet), `q = q + p` (join) or `¬q = ¬q·¬p` (contrapositive), anywhere |
//! | case step | local assumption `x = v` | `x` replaced by `v` at a pointwise position |
//! | delay arithmetic | `max`/`min`/`+` of two literals | the exact result |
//! | case split | `Γ,x=1* ⊢ a R b` and `Γ,x=0* ⊢ a R b` | `Γ ⊢ a R b` |
//! | symmetry | `a = b` | `b = a` |
//! | transitivity | `a R b` and `b R' c` | `a R c` (`⇒` if either is) |
//! | antisymmetry | `a ⇒ b` and `b ⇒ a` | `a = b` |
//! | implication from meet | `f·g = f` | `f ⇒ g` |
//! | implication from zero | `f·¬g = 0*` | `f ⇒ g` |
//! | shared lemma | a theorem this kernel checked before ([`Kernel::check_using`]) | the same, cited as a step |
//! | propositional refutation | `Γi ⊢ li Ri ri` and clauses each implied by unit propagation ([`crate::refutation`]), the last empty | `∪Γi ⊢ g = 0*` |
//!
//! On a program's scans ([`Kernel::for_scans`]) every delay is a whole number of cycles.
//! Laws and hypotheses are the kernel's axioms, given to [`Kernel::new`] (the hypotheses
//! are listed by [`Kernel::hypotheses`]); every theorem records which it used.

#![forbid(unsafe_code)]

use std::collections::{BTreeMap, BTreeSet};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

pub use crate::certificate::{
    Axiom, CYCLE, Certificate, Cmp, KernelError, Proof, Rel, Rule, Source, Step, Use, Uses,
};
use crate::certificate::{KernelError::BadAxiom, bound};
use crate::refutation::Cnf;
use crate::term::{
    Delay, Expr, Id, Language, Symbol, Term, and, at_first_scan, fold_delay, is_delay_node,
    matches, mentions_pre, not, or, root, same, same_tree, subterm,
};

/// A checked statement. Only this module can create one.
#[derive(Clone, Debug)]
pub struct Theorem {
    lhs: Expr,
    rel: Rel,
    rhs: Expr,
    local: Vec<(Expr, bool)>,
    /// The laws, hypotheses and shared lemmas it rests on.
    uses: Arc<Uses>,
    /// The kernel that checked it.
    kernel: u64,
}

/// Theorems by lemma name.
pub type Lemmas = BTreeMap<String, Arc<Theorem>>;

impl Theorem {
    /// Left side.
    pub fn lhs(&self) -> &Expr {
        &self.lhs
    }
    /// `=` or `⇒`.
    pub fn rel(&self) -> Rel {
        self.rel
    }
    /// Right side.
    pub fn rhs(&self) -> &Expr {
        &self.rhs
    }
    /// Local case assumptions (empty for a theorem about whole signals).
    pub fn local(&self) -> &[(Expr, bool)] {
        &self.local
    }
    /// The laws and the hypotheses this theorem depends on, through its shared lemmas too.
    pub fn axioms_used(&self) -> (BTreeSet<String>, BTreeSet<String>) {
        self.uses.all()
    }

    /// Does this theorem establish `lhs rel rhs` about whole signals?
    /// An equation also establishes the implication.
    pub fn proves(&self, lhs: &Expr, rel: Rel, rhs: &Expr) -> bool {
        self.local.is_empty()
            && same(&self.lhs, lhs)
            && same(&self.rhs, rhs)
            && (self.rel == rel || self.rel == Rel::Eq)
    }
}

type Result<T> = std::result::Result<T, KernelError>;

/// The checker, holding the axioms (laws and hypotheses) it trusts.
#[derive(Clone, Debug, Default)]
pub struct Kernel {
    laws: BTreeMap<String, Axiom>,
    /// The hypotheses in the order given, and their positions by name (shared by copies).
    hyps: Arc<Vec<Axiom>>,
    hyp_names: Arc<BTreeMap<String, usize>>,
    /// Checking the base of an induction: the hypotheses hold at the first scan only.
    first_scan: bool,
    /// A program's scan cycle (`None`: free signals). Signals are then scan runs, so `pre`
    /// and induction are available; the value of `cycle` in laws' side conditions.
    cycle: Option<Delay>,
    /// This kernel's identity: only its own theorems are lemmas to it.
    id: u64,
}

/// The next kernel's identity.
static KERNELS: AtomicU64 = AtomicU64::new(1);

/// A law that holds before the first scan too (only `·`, `+`, `¬`, `pre` and constants,
/// no side conditions): the only kind of rewrite allowed under `pre`.
fn pointwise_law(law: &Axiom) -> bool {
    let plain = |e: &Expr| {
        e.as_ref().iter().all(|t| {
            matches!(
                t,
                Term::Zero | Term::One | Term::And(_) | Term::Or(_) | Term::Not(_) | Term::Pre(_)
            ) || matches!(t, Term::Name(v) if law.signal_vars.contains(v))
        })
    };
    law.signal_conditions.is_empty() && plain(&law.lhs) && plain(&law.rhs)
}

/// A rewrite rule `from → to` after choosing how a law is used.
struct Oriented {
    from: Expr,
    to: Expr,
    /// `Some(true)`: the step is `before ⇒ after` only at a monotone position;
    /// `Some(false)`: only at an antitone position; `None`: an equation.
    implication: Option<bool>,
}

/// Checks that every node below `id` is a well-formed signal (or delay, in delay slots).
fn well_formed(e: &Expr, id: Id, want_delay: bool, delay_vars: &[Symbol]) -> bool {
    let node = &e[id];
    let is_delay_var = matches!(node, Term::Name(s) if delay_vars.contains(s));
    if want_delay != (is_delay_node(node) || is_delay_var) {
        return false;
    }
    match node {
        Term::Ton([d, f]) | Term::Tof([f, d]) => {
            well_formed(e, *d, true, delay_vars) && well_formed(e, *f, false, delay_vars)
        }
        Term::DMax([a, b]) | Term::DMin([a, b]) | Term::DAdd([a, b]) => {
            well_formed(e, *a, true, delay_vars) && well_formed(e, *b, true, delay_vars)
        }
        other => other.children().iter().all(|c| well_formed(e, *c, false, delay_vars)),
    }
}

/// Every child precedes its node (so the term is a finite tree, whoever built it).
fn ordered(e: &Expr) -> bool {
    e.as_ref().iter().enumerate().all(|(i, n)| n.children().iter().all(|c| usize::from(*c) < i))
}

fn check_signal_term(what: &str, e: &Expr, delay_vars: &[Symbol]) -> Result<()> {
    if e.as_ref().is_empty() || !ordered(e) || !well_formed(e, root(e), false, delay_vars) {
        return Err(KernelError::BadAxiom(format!("{what} is not a signal term")));
    }
    Ok(())
}

impl Kernel {
    /// A kernel trusting these laws and (ground) hypotheses. Rejects malformed
    /// axioms and duplicate names.
    pub fn new(laws: Vec<Axiom>, hypotheses: Vec<Axiom>) -> Result<Kernel> {
        Kernel::build(laws, hypotheses, None)
    }

    /// A kernel for the scan runs of a program with this cycle (`pre`, induction over
    /// scans, `cycle` in laws' side conditions, every delay a whole number of cycles).
    pub fn for_scans(laws: Vec<Axiom>, hypotheses: Vec<Axiom>, cycle: Delay) -> Result<Kernel> {
        Kernel::build(laws, hypotheses, Some(cycle))
    }

    fn build(laws: Vec<Axiom>, hypotheses: Vec<Axiom>, cycle: Option<Delay>) -> Result<Kernel> {
        let id = KERNELS.fetch_add(1, Ordering::Relaxed);
        let scans = cycle.is_some();
        let mut kernel = Kernel { cycle, id, ..Kernel::default() };
        let (mut hyps, mut names) = (Vec::new(), BTreeMap::new());
        for (axiom, is_law) in
            laws.into_iter().map(|a| (a, true)).chain(hypotheses.into_iter().map(|a| (a, false)))
        {
            let name = axiom.name.clone();
            check_signal_term(&name, &axiom.lhs, &axiom.delay_vars)?;
            check_signal_term(&name, &axiom.rhs, &axiom.delay_vars)?;
            let vars = axiom.signal_vars.len() + axiom.delay_vars.len();
            if !is_law && vars + axiom.signal_conditions.len() > 0 {
                return Err(KernelError::BadAxiom(format!("hypothesis `{name}` is not ground")));
            }
            if !is_law && !scans && (mentions_pre(&axiom.lhs) || mentions_pre(&axiom.rhs)) {
                return Err(KernelError::BadAxiom(format!("`pre` in `{name}` about free signals")));
            }
            if !is_law {
                let whole = kernel.whole_cycles(&name, &axiom.lhs);
                whole
                    .and(kernel.whole_cycles(&name, &axiom.rhs))
                    .map_err(|e| BadAxiom(e.to_string()))?;
            }
            if kernel.laws.contains_key(&name) || names.contains_key(&name) {
                return Err(KernelError::BadAxiom(format!("`{name}` is defined twice")));
            }
            if is_law {
                kernel.laws.insert(name, axiom);
            } else {
                names.insert(name, hyps.len());
                hyps.push(axiom);
            }
        }
        (kernel.hyps, kernel.hyp_names) = (Arc::new(hyps), Arc::new(names));
        Ok(kernel)
    }

    /// A term this kernel may reason about: well formed, without `pre` unless the
    /// signals are scan runs, and on scans with whole-cycle delays only.
    fn admit(&self, what: &str, e: &Expr) -> Result<()> {
        check_signal_term(what, e, &[])?;
        if self.cycle.is_none() && mentions_pre(e) {
            return Err(KernelError::BadPosition(format!("{what} uses `pre`: free signals")));
        }
        self.whole_cycles(what, e)
    }

    /// On scans every delay is a whole number of cycles (others have no one reading there).
    fn whole_cycles(&self, what: &str, e: &Expr) -> Result<()> {
        let sub = self.cycle.as_ref().and_then(|c| crate::term::sub_cycle_delay(e, c));
        sub.map_or(Ok(()), |d| Err(KernelError::SubCycleDelay(format!("{what} has the delay {d}"))))
    }

    /// Every hypothesis the kernel trusts, in the order given.
    pub fn hypotheses(&self) -> &[Axiom] {
        &self.hyps
    }

    /// Replays a certificate: its lemmas in order, then its main proof.
    pub fn check(&self, cert: &Certificate) -> Result<Theorem> {
        self.check_using(cert, Lemmas::new())
    }

    /// [`Kernel::check`], where the proofs may also cite `known`: theorems this kernel
    /// checked before (another kernel's are refused).
    pub fn check_using(&self, cert: &Certificate, known: Lemmas) -> Result<Theorem> {
        for (name, thm) in &known {
            if thm.kernel != self.id {
                return Err(KernelError::Mismatch(format!("lemma `{name}` is another context's")));
            }
            // Under case assumptions it holds only where they do: no fact about whole signals.
            if !thm.local.is_empty() {
                return Err(KernelError::Mismatch(format!("lemma `{name}` is only local")));
            }
        }
        let mut lemmas = known;
        for (name, proof) in &cert.lemmas {
            let thm = self.replay(proof, &lemmas)?;
            if !thm.local.is_empty() {
                return Err(KernelError::Mismatch(format!("lemma `{name}` is only local")));
            }
            if lemmas.insert(name.clone(), Arc::new(thm)).is_some() {
                return Err(KernelError::Mismatch(format!("lemma `{name}` twice")));
            }
        }
        let main = cert
            .main
            .as_ref()
            .ok_or_else(|| KernelError::NotTheGoal("the certificate has no main proof".into()))?;
        let mut thm = self.replay(main, &lemmas)?;
        Arc::make_mut(&mut thm.uses).lemmas.extend(lemmas.values().map(|t| Arc::clone(&t.uses)));
        Ok(thm)
    }

    /// Checks a certificate and that it proves exactly `lhs rel rhs` about whole signals.
    pub fn check_goal(
        &self,
        cert: &Certificate,
        lhs: &Expr,
        rel: Rel,
        rhs: &Expr,
    ) -> Result<Theorem> {
        let thm = self.check(cert)?;
        self.vouch(&thm, lhs, rel, rhs).map(|()| thm)
    }

    /// Is `thm` this kernel's theorem of exactly `lhs rel rhs`? (Asked before "proved".)
    pub fn vouch(&self, thm: &Theorem, lhs: &Expr, rel: Rel, rhs: &Expr) -> Result<()> {
        if thm.kernel == self.id && thm.proves(lhs, rel, rhs) {
            return Ok(());
        }
        let (l, r, n) = (&thm.lhs, &thm.rhs, thm.local.len());
        let got = format!("`{l} {:?} {r}` under {n} case assumption(s)", thm.rel);
        Err(KernelError::NotTheGoal(format!(
            "{got} (kernel {}), not `{lhs} {rel:?} {rhs}`",
            thm.kernel
        )))
    }

    fn replay(&self, proof: &Proof, lemmas: &Lemmas) -> Result<Theorem> {
        match proof {
            Proof::Chain { start, steps } => self.chain(start, steps, lemmas),
            Proof::CaseSplit { atom, one, zero } => {
                let one = self.replay(one, lemmas)?;
                let zero = self.replay(zero, lemmas)?;
                case_split(atom, one, zero)
            }
            Proof::Induction { inv, base, step } => self.induction(inv, base, step, lemmas),
            Proof::Symm(p) => {
                let mut thm = self.replay(p, lemmas)?;
                if thm.rel != Rel::Eq {
                    return Err(KernelError::Mismatch("symmetry of an implication".into()));
                }
                std::mem::swap(&mut thm.lhs, &mut thm.rhs);
                Ok(thm)
            }
            Proof::Trans(p, q) => {
                let a = self.replay(p, lemmas)?;
                let b = self.replay(q, lemmas)?;
                if !same(&a.rhs, &b.lhs) {
                    return Err(KernelError::Mismatch("transitivity through other terms".into()));
                }
                let rel = if a.rel == Rel::Eq && b.rel == Rel::Eq { Rel::Eq } else { Rel::Implies };
                let rhs = b.rhs.clone();
                Ok(merge(Theorem { rel, rhs, ..a }, b))
            }
            Proof::Antisym(p, q) => {
                let a = self.replay(p, lemmas)?;
                let b = self.replay(q, lemmas)?;
                if !(same(&a.lhs, &b.rhs) && same(&a.rhs, &b.lhs)) {
                    return Err(KernelError::Mismatch("antisymmetry of unrelated facts".into()));
                }
                Ok(merge(Theorem { rel: Rel::Eq, ..a }, b))
            }
            Proof::ImpliesByMeet(p) => {
                let thm = self.replay(p, lemmas)?;
                match &thm.lhs[root(&thm.lhs)] {
                    Term::And([f, g])
                        if thm.rel == Rel::Eq
                            && same_tree(&thm.lhs, *f, &thm.rhs, root(&thm.rhs)) =>
                    {
                        let (f, g) = (subterm(&thm.lhs, *f), subterm(&thm.lhs, *g));
                        Ok(Theorem { lhs: f, rel: Rel::Implies, rhs: g, ..thm })
                    }
                    _ => Err(KernelError::Mismatch("expected a proof of `f·g = f`".into())),
                }
            }
            Proof::ImpliesByZero(p) => {
                let thm = self.replay(p, lemmas)?;
                let lhs = &thm.lhs;
                if thm.rel == Rel::Eq
                    && matches!(thm.rhs[root(&thm.rhs)], Term::Zero)
                    && let Term::And([f, not_g]) = &lhs[root(lhs)]
                    && let Term::Not(g) = &lhs[*not_g]
                {
                    let (f, g) = (subterm(lhs, *f), subterm(lhs, *g));
                    return Ok(Theorem { lhs: f, rel: Rel::Implies, rhs: g, ..thm });
                }
                Err(KernelError::Mismatch("expected a proof of `f·¬g = 0*`".into()))
            }
            Proof::Refutation { goal, facts, lemmas: derived } => {
                self.admit("a refuted term", goal)?;
                let (mut cnf, zero) = (Cnf::with_goal(goal), crate::term::constant(false));
                let mut thm = self.start(goal.clone(), zero);
                for fact in facts {
                    let t = self.replay(fact, lemmas)?;
                    cnf.fact(&t.lhs, t.rel == Rel::Eq, &t.rhs);
                    thm = merge(thm, t);
                }
                cnf.refuted_by(derived).map_err(KernelError::Mismatch)?;
                Ok(thm)
            }
        }
    }

    /// `inv = 1*` at every scan, from `1* ⇒ inv` at the first scan (checked against the
    /// hypotheses as they read there) and `pre inv ⇒ inv`.
    fn induction(
        &self,
        inv: &Expr,
        base: &Proof,
        step: &Proof,
        lemmas: &Lemmas,
    ) -> Result<Theorem> {
        if self.cycle.is_none() || self.first_scan {
            return Err(KernelError::BadPosition(
                "induction over scans needs a program's scans (and not inside a base case)".into(),
            ));
        }
        self.admit("an invariant", inv)?;
        let first = Kernel { first_scan: true, ..self.clone() };
        let (one, inv0) = (crate::term::constant(true), at_first_scan(inv));
        let b = first.replay(base, lemmas)?;
        if !b.proves(&one, Rel::Implies, &inv0) {
            let (l, rel, r) = (&b.lhs, b.rel, &b.rhs);
            let got = format!("`{l} {rel:?} {r}`");
            return Err(KernelError::Mismatch(format!("the base proves {got}, not `1* ⇒ {inv0}`")));
        }
        let s = self.replay(step, lemmas)?;
        let mut pre_inv = inv.clone();
        pre_inv.add(Term::Pre(root(inv)));
        if !s.proves(&pre_inv, Rel::Implies, inv) {
            return Err(KernelError::Mismatch(format!(
                "the step does not prove `pre {inv} ⇒ {inv}`"
            )));
        }
        Ok(merge(Theorem { lhs: inv.clone(), rel: Rel::Eq, rhs: one, ..b }, s))
    }

    /// `lhs = rhs` resting on nothing yet: only where the rule itself shows it (`t = t`,
    /// the start of a chain) or checks it before returning it (a refutation).
    fn start(&self, lhs: Expr, rhs: Expr) -> Theorem {
        let (local, uses) = (Vec::new(), Arc::default());
        Theorem { lhs, rel: Rel::Eq, rhs, local, uses, kernel: self.id }
    }

    fn chain(&self, start: &Expr, steps: &[Step], lemmas: &Lemmas) -> Result<Theorem> {
        self.admit("the start of a chain", start)?;
        let mut thm = self.start(start.clone(), start.clone());
        for step in steps {
            let rel = self.step(&mut thm, step, lemmas)?;
            if rel == Rel::Implies {
                thm.rel = Rel::Implies;
            }
            thm.rhs = step.after.clone();
        }
        Ok(thm)
    }

    /// Checks one step from `thm.rhs` to `step.after`; records what it used.
    fn step(&self, thm: &mut Theorem, step: &Step, lemmas: &Lemmas) -> Result<Rel> {
        let before = &thm.rhs;
        let (target, position) = locate(before, &step.path)?;
        self.admit("the result of a step", &step.after)?;
        let (after_target, _) = locate(&step.after, &step.path).map_err(|_| {
            KernelError::WrongResult("the result has no subterm at the path".into())
        })?;
        if !same_outside(before, root(before), &step.after, root(&step.after), &step.path) {
            return Err(KernelError::WrongResult(
                "the step changes the term outside the rewritten position".into(),
            ));
        }
        let old = subterm(before, target);
        let new = subterm(&step.after, after_target);
        match &step.rule {
            Rule::DelayArith => {
                // `max`/`min`/`+` of literals equals the literal it computes, either way round.
                let computes = |a: &Expr, b: &Expr| {
                    !matches!(a[root(a)], Term::Delay(_))
                        && matches!(&b[root(b)], Term::Delay(d) if fold_delay(a, root(a)).as_ref() == Some(d))
                };
                if computes(&old, &new) || computes(&new, &old) {
                    return Ok(Rel::Eq);
                }
                Err(KernelError::NoMatch(format!(
                    "`{old}` and `{new}` are not a computation and its value"
                )))
            }
            Rule::Case(atom, value) => {
                if !position.pointwise {
                    return Err(KernelError::BadPosition(
                        "a case assumption rewrites only outside timers and memories".into(),
                    ));
                }
                let constant = if *value { Term::One } else { Term::Zero };
                let forward = same(&old, atom) && new.as_ref() == [constant.clone()];
                let backward = same(&new, atom) && old.as_ref() == [constant];
                if !(forward || backward) {
                    return Err(KernelError::NoMatch(format!(
                        "`{old}` → `{new}` is not `{atom}` ↔ constant"
                    )));
                }
                if !thm.local.iter().any(|(a, v)| same(a, atom) && v == value) {
                    thm.local.push((atom.clone(), *value));
                }
                Ok(Rel::Eq)
            }
            Rule::Cite(source, name, how) => {
                let lemma = lemmas.get(name).filter(|_| *source == Source::Lemma);
                // In a base case a lemma or a hypothesis reads as at the first scan.
                let read = |e: &Expr| if self.first_scan { at_first_scan(e) } else { e.clone() };
                let lemma_axiom =
                    lemma.map(|t| Axiom::ground(name, read(&t.lhs), t.rel, read(&t.rhs)));
                let hyp = self.hyp_names.get(name).map(|&i| &self.hyps[i]);
                let first = hyp.filter(|_| self.first_scan).map(|h| {
                    Axiom::ground(name, at_first_scan(&h.lhs), h.rel, at_first_scan(&h.rhs))
                });
                let axiom = match source {
                    Source::Law => self.laws.get(name),
                    Source::Hypothesis => first.as_ref().or(hyp),
                    Source::Lemma => lemma_axiom.as_ref(),
                }
                .ok_or_else(|| KernelError::UnknownRule(format!("{source:?} {name}")))?;
                // Under `pre` (the previous scan, or before the first): laws that hold
                // there too, and outside a base case facts true before the first scan.
                let before_first = match source {
                    Source::Law => pointwise_law(axiom),
                    _ => !self.first_scan && axiom.holds_initially(),
                };
                if position.under_pre && !before_first {
                    return Err(KernelError::BadPosition(format!(
                        "under `pre` only laws of `·`, `+`, `¬` and `pre` and facts true \
                         before the first scan rewrite; `{name}` is neither"
                    )));
                }
                let vars: Vec<Symbol> =
                    axiom.signal_vars.iter().chain(&axiom.delay_vars).cloned().collect();
                let rule = orient(&axiom.lhs, axiom.rel, &axiom.rhs, *how, name)?;
                let mut sigma =
                    instance(&rule, &vars, &axiom.delay_vars, &old, &new, &step.subst, name)?;
                axiom.bind_cycle(self.cycle.as_ref(), &mut sigma);
                let rel = position_rel(&rule, position)?;
                axiom.check_delay_conditions(&sigma)?;
                let wanted = axiom.signal_conditions.len();
                if step.premises.len() != wanted {
                    let n = step.premises.len();
                    return Err(KernelError::MissingPremise(format!(
                        "`{name}` has {wanted} side condition(s) on signals, {n} premise(s) given"
                    )));
                }
                for ((l, rel, r), premise) in axiom.signal_conditions.iter().zip(&step.premises) {
                    let (want_l, want_r) = (bound(l, &sigma)?, bound(r, &sigma)?);
                    let got = self.replay(premise, lemmas)?;
                    if !got.proves(&want_l, *rel, &want_r) {
                        return Err(KernelError::MissingPremise(format!(
                            "`{name}` needs `{want_l} {rel:?} {want_r}`"
                        )));
                    }
                    Arc::make_mut(&mut thm.uses).absorb(got.uses);
                }
                let uses = Arc::make_mut(&mut thm.uses);
                match (source, lemma) {
                    (Source::Law, _) => uses.laws.insert(name.clone()),
                    (Source::Hypothesis, _) => uses.hyps.insert(name.clone()),
                    (Source::Lemma, Some(used)) => {
                        uses.lemmas.push(Arc::clone(&used.uses));
                        true
                    }
                    (Source::Lemma, None) => false,
                };
                Ok(rel)
            }
        }
    }
}

/// `a`'s statement with both theorems' assumptions (the smaller sets join the larger).
fn merge(mut a: Theorem, mut b: Theorem) -> Theorem {
    if !b.local.is_empty() {
        let key = |(x, v): &(Expr, bool)| (subterm(x, root(x)), *v);
        let mut known: std::collections::HashSet<(Expr, bool)> = a.local.iter().map(key).collect();
        b.local.into_iter().filter(|l| known.insert(key(l))).for_each(|l| a.local.push(l));
    }
    Arc::make_mut(&mut a.uses).absorb(std::mem::take(&mut b.uses));
    a
}

fn case_split(atom: &Expr, one: Theorem, zero: Theorem) -> Result<Theorem> {
    if !(same(&one.lhs, &zero.lhs) && same(&one.rhs, &zero.rhs) && one.rel == zero.rel) {
        return Err(KernelError::Mismatch("the two cases prove different statements".into()));
    }
    let without = |thm: &Theorem, value: bool| -> Vec<(Expr, bool)> {
        thm.local.iter().filter(|(a, v)| !(same(a, atom) && *v == value)).cloned().collect()
    };
    let (rest_one, rest_zero) = (without(&one, true), without(&zero, false));
    Ok(merge(Theorem { local: rest_one, ..one }, Theorem { local: rest_zero, ..zero }))
}

/// Where a subterm sits: may an implication be used there, and is it pointwise?
#[derive(Clone, Copy, Debug)]
struct Position {
    /// The whole term grows with the subterm (an even number of negations and
    /// reset arguments on the way down).
    monotone: bool,
    /// Only `·`, `+` and `¬` lie on the way down.
    pointwise: bool,
    /// The subterm is (inside) a delay, not a signal.
    delay: bool,
    /// `pre` lies on the way down.
    under_pre: bool,
}

/// Follows `path` from the root; the id of the subterm and its position.
fn locate(e: &Expr, path: &[usize]) -> Result<(Id, Position)> {
    let bad = || KernelError::BadPath(format!("{path:?}"));
    if e.as_ref().is_empty() {
        return Err(bad());
    }
    let mut id = root(e);
    let mut pos = Position { monotone: true, pointwise: true, delay: false, under_pre: false };
    for &index in path {
        let node = &e[id];
        let child = *node.children().get(index).ok_or_else(bad)?;
        match (node, index) {
            (Term::And(_) | Term::Or(_), _) => {}
            (Term::Not(_), _) => pos.monotone = !pos.monotone,
            (Term::Ton(_), 0) | (Term::Tof(_), 1) => {
                pos.delay = true;
                pos.pointwise = false;
            }
            (Term::Ton(_) | Term::Tof(_) | Term::Sr(_) | Term::Rs(_), 0 | 1) => {
                pos.pointwise = false;
                if index == 1 && matches!(node, Term::Sr(_) | Term::Rs(_)) {
                    pos.monotone = !pos.monotone;
                }
            }
            (Term::DMax(_) | Term::DMin(_) | Term::DAdd(_), _) => {}
            (Term::Pre(_), _) => {
                pos.pointwise = false;
                pos.under_pre = true;
            }
            _ => return Err(bad()),
        }
        id = child;
    }
    Ok((id, pos))
}

/// Are the two trees equal everywhere except (possibly) at `path`?
fn same_outside(x: &Expr, a: Id, y: &Expr, b: Id, path: &[usize]) -> bool {
    let Some((&first, rest)) = path.split_first() else {
        return true;
    };
    let (m, n) = (&x[a], &y[b]);
    m.matches(n)
        && m.children().iter().zip(n.children()).enumerate().all(|(i, (&c, &d))| {
            if i == first { same_outside(x, c, y, d, rest) } else { same_tree(x, c, y, d) }
        })
}

/// Chooses the two sides of `lhs rel rhs` for a use.
fn orient(lhs: &Expr, rel: Rel, rhs: &Expr, how: Use, name: &str) -> Result<Oriented> {
    let (l, r) = (lhs.clone(), rhs.clone());
    let (from, to, implication) = match (rel, how) {
        (Rel::Eq, Use::Forward) => (l, r, None),
        (Rel::Eq, Use::Backward) => (r, l, None),
        (Rel::Implies, Use::Forward) => (l, r, Some(true)),
        (Rel::Implies, Use::Backward) => (r, l, Some(false)),
        (Rel::Implies, Use::Meet) => (l, and(lhs, rhs), None),
        (Rel::Implies, Use::MeetBack) => (and(lhs, rhs), l, None),
        (Rel::Implies, Use::Join) => (r, or(rhs, lhs), None),
        (Rel::Implies, Use::JoinBack) => (or(rhs, lhs), r, None),
        (Rel::Implies, Use::Contra) => (not(rhs), and(&not(rhs), &not(lhs)), None),
        (Rel::Implies, Use::ContraBack) => (and(&not(rhs), &not(lhs)), not(rhs), None),
        (Rel::Eq, _) => {
            return Err(KernelError::UnknownRule(format!(
                "`{name}` is an equation; it has no {how:?} use"
            )));
        }
    };
    Ok(Oriented { from, to, implication })
}

/// The relation a step establishes at `pos`, or an error where it is unsound.
fn position_rel(rule: &Oriented, pos: Position) -> Result<Rel> {
    if pos.delay {
        return Err(KernelError::BadPosition("only delay arithmetic rewrites a delay".into()));
    }
    match rule.implication {
        None => Ok(Rel::Eq),
        Some(wanted) if wanted == pos.monotone => Ok(Rel::Implies),
        Some(_) => Err(KernelError::BadPosition(
            "an implication used in the wrong direction for this position (under ¬ or a reset)"
                .into(),
        )),
    }
}

/// Matches `rule.from` against `old` and `rule.to` against `new`, one substitution for both;
/// checks the claimed substitution against it.
fn instance(
    rule: &Oriented,
    vars: &[Symbol],
    delay_vars: &[Symbol],
    old: &Expr,
    new: &Expr,
    claimed: &[(Symbol, Expr)],
    name: &str,
) -> Result<BTreeMap<Symbol, Expr>> {
    let mut sigma = BTreeMap::new();
    let no_match = |side: &str, term: &Expr, pattern: &Expr| {
        KernelError::NoMatch(format!("`{name}`: `{term}` is not an instance of {side} `{pattern}`"))
    };
    if !matches(&rule.from, root(&rule.from), vars, delay_vars, old, root(old), &mut sigma) {
        return Err(no_match("the rewritten side", old, &rule.from));
    }
    if !matches(&rule.to, root(&rule.to), vars, delay_vars, new, root(new), &mut sigma) {
        return Err(no_match("the result side", new, &rule.to));
    }
    for (var, value) in claimed {
        match sigma.get(var) {
            Some(bound) if same(bound, value) => {}
            Some(bound) => {
                return Err(KernelError::WrongSubstitution(format!(
                    "`{var}` is `{bound}` in the instance, not `{value}`"
                )));
            }
            None => {
                return Err(KernelError::WrongSubstitution(format!(
                    "`{var}` is not a variable of `{name}`"
                )));
            }
        }
    }
    Ok(sigma)
}
