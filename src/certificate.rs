//! The certificate format: plain data that the search produces and the kernel replays.
//!
//! Nothing here checks anything: these are the statements the kernel is given as
//! axioms ([`Axiom`]) and the proofs it is asked to replay ([`Certificate`],
//! [`Proof`], [`Step`]), and the reasons it gives for a rejection ([`KernelError`]).
//! Keeping the format apart keeps `kernel.rs` to its logic.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt;
use std::sync::Arc;

use crate::term::{Delay, Expr, Symbol, Term, fold_delay, initially, instantiate, root};

/// The relation a theorem, law or hypothesis states between two signals.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Rel {
    /// `a = b`: equal at every instant.
    Eq,
    /// `a ⇒ b`: wherever `a` is 1, `b` is 1.
    Implies,
}

/// A comparison between two delays in a law's side condition.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cmp {
    /// `≥`
    Ge,
    /// `>`
    Gt,
    /// `≤`
    Le,
    /// `<`
    Lt,
    /// `=`
    Eq,
}

impl Cmp {
    /// Does `a cmp b` hold?
    pub fn holds(self, a: &Delay, b: &Delay) -> bool {
        match self {
            Cmp::Ge => a >= b,
            Cmp::Gt => a > b,
            Cmp::Le => a <= b,
            Cmp::Lt => a < b,
            Cmp::Eq => a == b,
        }
    }
}

/// An axiom: a law of `theories/` (a schema over metavariables) or a ground
/// hypothesis (a rung's equation, a bound, an `assume`; no variables).
#[derive(Clone, Debug)]
pub struct Axiom {
    /// The name printed in traces (`ton_weaken`, `L06`).
    pub name: String,
    /// Left side (metavariables are `Term::Name`s listed below).
    pub lhs: Expr,
    /// `=` or `⇒`.
    pub rel: Rel,
    /// Right side.
    pub rhs: Expr,
    /// Names standing for any signal.
    pub signal_vars: Vec<Symbol>,
    /// Names standing for any delay.
    pub delay_vars: Vec<Symbol>,
    /// Side conditions on delays, checked on the instance.
    pub delay_conditions: Vec<(Expr, Cmp, Expr)>,
    /// Side conditions on signals: each instance must be supplied as a premise theorem.
    pub signal_conditions: Vec<(Expr, Rel, Expr)>,
}

impl Axiom {
    /// A ground axiom `lhs rel rhs` without variables or side conditions.
    pub fn ground(name: impl Into<String>, lhs: Expr, rel: Rel, rhs: Expr) -> Axiom {
        let name = name.into();
        let (signal_vars, delay_vars) = (Vec::new(), Vec::new());
        let (delay_conditions, signal_conditions) = (Vec::new(), Vec::new());
        Axiom { name, lhs, rel, rhs, signal_vars, delay_vars, delay_conditions, signal_conditions }
    }

    /// Does this ground fact hold before the first scan (every variable, timer and
    /// memory 0), so that at the previous scan too, even at the first one?
    pub fn holds_initially(&self) -> bool {
        let (l, r) = (initially(&self.lhs), initially(&self.rhs));
        let ground = self.signal_vars.is_empty() && self.delay_vars.is_empty();
        ground && if self.rel == Rel::Eq { l == r } else { !l || r }
    }

    /// Binds [`CYCLE`] to a program's scan cycle in an instance's substitution when the
    /// law names it and matching left it unbound (it is in no side of the law).
    pub fn bind_cycle(&self, cycle: Option<&Delay>, sigma: &mut BTreeMap<Symbol, Expr>) {
        let var = Symbol::from(CYCLE);
        if let Some(c) = cycle
            && self.delay_vars.contains(&var)
            && !sigma.contains_key(&var)
        {
            sigma.insert(var, Expr::from(vec![Term::Delay(c.clone())]));
        }
    }

    /// Checks the law's delay side conditions under a substitution: each side, with its
    /// variables replaced, must fold to a concrete delay, and the comparison must hold.
    pub fn check_delay_conditions(
        &self,
        sigma: &BTreeMap<Symbol, Expr>,
    ) -> Result<(), KernelError> {
        for (lhs, cmp, rhs) in &self.delay_conditions {
            let value = |side: &Expr| -> Result<Delay, KernelError> {
                let ground = bound(side, sigma)?;
                fold_delay(&ground, root(&ground)).ok_or_else(|| {
                    KernelError::SideCondition(format!("`{ground}` is not a concrete delay"))
                })
            };
            let (a, b) = (value(lhs)?, value(rhs)?);
            if !cmp.holds(&a, &b) {
                return Err(KernelError::SideCondition(format!(
                    "`{}` needs {a} {cmp:?} {b}",
                    self.name
                )));
            }
        }
        Ok(())
    }
}

/// A law side with its variables replaced; an error if one is unbound.
pub fn bound(pat: &Expr, sigma: &BTreeMap<Symbol, Expr>) -> Result<Expr, KernelError> {
    instantiate(pat, sigma).ok_or_else(|| {
        KernelError::WrongSubstitution("a variable of a side condition is unbound".into())
    })
}

/// The delay variable that, when a law names it in its side conditions only, stands
/// for the program's scan cycle (`d/f ⇒ pre f if d >= cycle`). Without a cycle such a
/// law is never used.
pub const CYCLE: &str = "cycle";

/// How a cited statement `l R r` is used in one rewrite step.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Use {
    /// Replace an instance of `l` by `r` (an `⇒` law: only at a monotone position).
    Forward,
    /// Replace an instance of `r` by `l` (an `⇒` law: only at an antitone position).
    Backward,
    /// `⇒` law `p ⇒ q` as the equation `p = p·q`, left to right.
    Meet,
    /// `p·q` back to `p`.
    MeetBack,
    /// `⇒` law `p ⇒ q` as the equation `q = q + p`, left to right.
    Join,
    /// `q + p` back to `q`.
    JoinBack,
    /// `⇒` law `p ⇒ q` as the equation `¬q = ¬q·¬p` (its contrapositive), left to right.
    Contra,
    /// `¬q·¬p` back to `¬q`.
    ContraBack,
}

/// Where a cited statement comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Source {
    /// A law of the theory.
    Law,
    /// A hypothesis of the context.
    Hypothesis,
    /// A lemma proved earlier in the same certificate.
    Lemma,
}

/// What justifies one step.
#[derive(Clone, Debug)]
pub enum Rule {
    /// A law, hypothesis or lemma, by name, and how it is used.
    Cite(Source, String, Use),
    /// A local case assumption `atom = value` (only at pointwise positions).
    Case(Expr, bool),
    /// Exact `max`/`min`/`+` of two delay literals.
    DelayArith,
}

/// One rewrite step of a chain.
#[derive(Clone, Debug)]
pub struct Step {
    /// Child indices from the root to the rewritten subterm.
    pub path: Vec<usize>,
    /// Why the step is valid.
    pub rule: Rule,
    /// The whole term after the step.
    pub after: Expr,
    /// The substitution the search claims (may be empty: the kernel infers it by matching).
    pub subst: Vec<(Symbol, Expr)>,
    /// Proofs of the law's signal side conditions, in order.
    pub premises: Vec<Proof>,
}

/// A certificate: untrusted data that `Kernel::check` replays.
#[derive(Clone, Debug)]
pub enum Proof {
    /// `start`, rewritten step by step.
    Chain {
        /// The first term.
        start: Expr,
        /// The steps.
        steps: Vec<Step>,
    },
    /// Both cases of `atom` prove the same statement.
    CaseSplit {
        /// The split term (used only at pointwise positions).
        atom: Expr,
        /// The proof under `atom = 1*`.
        one: Box<Proof>,
        /// The proof under `atom = 0*`.
        zero: Box<Proof>,
    },
    /// `inv = 1*` at every scan of a program, by induction over scans: `base` proves
    /// `1* ⇒ inv` at the first scan (`inv` with each `pre f` replaced by the value `f`
    /// has before it, from the hypotheses read the same way), and `step` proves
    /// `pre inv ⇒ inv`.
    Induction {
        /// The invariant.
        inv: Expr,
        /// The proof at the first scan.
        base: Box<Proof>,
        /// The proof of `pre inv ⇒ inv`.
        step: Box<Proof>,
    },
    /// `b = a` from a proof of `a = b`.
    Symm(Box<Proof>),
    /// `a R c` from proofs of `a R b` and `b R' c` (`⇒` if either is).
    Trans(Box<Proof>, Box<Proof>),
    /// `a = b` from proofs of `a ⇒ b` and `b ⇒ a`.
    Antisym(Box<Proof>, Box<Proof>),
    /// `f ⇒ g` from a proof of `f·g = f`.
    ImpliesByMeet(Box<Proof>),
    /// `f ⇒ g` from a proof of `f·¬g = 0*`.
    ImpliesByZero(Box<Proof>),
    /// `goal = 0*` from the proved `facts` and `lemmas`, clauses over the variables
    /// [`crate::refutation::Cnf`] gives the goal and the facts' statements, each implied
    /// by unit propagation, the last the empty clause.
    Refutation {
        /// The term shown to be `0*`.
        goal: Expr,
        /// Proofs of the statements the refutation rests on.
        facts: Vec<Proof>,
        /// The derived clauses, in order.
        lemmas: Vec<Vec<i32>>,
    },
}

impl Proof {
    /// Calls `f` on every step of the proof, premises of steps included.
    pub fn for_each_step_mut(&mut self, f: &mut dyn FnMut(&mut Step)) {
        match self {
            Proof::Chain { steps, .. } => {
                for s in steps {
                    f(s);
                    s.premises.iter_mut().for_each(|p| p.for_each_step_mut(f));
                }
            }
            Proof::CaseSplit { one: p, zero: q, .. }
            | Proof::Induction { base: p, step: q, .. }
            | Proof::Antisym(p, q)
            | Proof::Trans(p, q) => {
                p.for_each_step_mut(f);
                q.for_each_step_mut(f);
            }
            Proof::Symm(p) | Proof::ImpliesByMeet(p) | Proof::ImpliesByZero(p) => {
                p.for_each_step_mut(f)
            }
            Proof::Refutation { facts, .. } => {
                facts.iter_mut().for_each(|p| p.for_each_step_mut(f))
            }
        }
    }

    /// The names of the lemmas the proof cites.
    pub fn lemmas_cited(&self) -> BTreeSet<String> {
        let mut names = BTreeSet::new();
        // A copy walked mutably: the visitor is shared with the relabelling of traces.
        self.clone().for_each_step_mut(&mut |s| {
            if let Rule::Cite(Source::Lemma, name, _) = &s.rule {
                names.insert(name.clone());
            }
        });
        names
    }
}

/// What a theorem rests on: the laws and hypotheses it cites by name, and what the
/// shared lemmas it cites rest on. The kernel keeps it for reports; it decides nothing.
#[derive(Clone, Debug, Default)]
pub struct Uses {
    /// Laws cited.
    pub laws: BTreeSet<String>,
    /// Hypotheses cited.
    pub hyps: BTreeSet<String>,
    /// What each shared lemma cited rests on (shared, not copied).
    pub lemmas: Vec<Arc<Uses>>,
}

impl Uses {
    /// Adds what `other` rests on: its sets join (the smaller into the larger), or, when
    /// it is shared, it is kept as shared.
    pub fn absorb(&mut self, other: Arc<Uses>) {
        let mut other = match Arc::try_unwrap(other) {
            Ok(other) => other,
            Err(shared) => return self.lemmas.push(shared),
        };
        for (mine, theirs) in [(&mut self.laws, &mut other.laws), (&mut self.hyps, &mut other.hyps)]
        {
            if mine.len() < theirs.len() {
                std::mem::swap(mine, theirs);
            }
            mine.extend(std::mem::take(theirs));
        }
        self.lemmas.append(&mut other.lemmas);
    }

    /// Every law and every hypothesis, through the lemmas too.
    pub fn all(&self) -> (BTreeSet<String>, BTreeSet<String>) {
        let (mut laws, mut hyps) = (self.laws.clone(), self.hyps.clone());
        let mut seen = BTreeSet::new();
        let mut stack: Vec<&Uses> = self.lemmas.iter().map(|u| &**u).collect();
        while let Some(u) = stack.pop() {
            if seen.insert(u as *const Uses) {
                laws.extend(u.laws.iter().cloned());
                hyps.extend(u.hyps.iter().cloned());
                stack.extend(u.lemmas.iter().map(|u| &**u));
            }
        }
        (laws, hyps)
    }
}

impl Drop for Uses {
    /// Drops a long chain of lemmas one link at a time, not by recursion.
    fn drop(&mut self) {
        let mut stack = std::mem::take(&mut self.lemmas);
        while let Some(u) = stack.pop() {
            if let Ok(mut u) = Arc::try_unwrap(u) {
                stack.append(&mut u.lemmas);
            }
        }
    }
}

/// A certificate with named lemmas, checked in order before the main proof.
#[derive(Clone, Debug, Default)]
pub struct Certificate {
    /// Lemmas, each usable by later lemmas and by the main proof.
    pub lemmas: Vec<(String, Proof)>,
    /// The proof of the goal.
    pub main: Option<Proof>,
}

/// Why the kernel rejected a certificate. Every failure is one of these; each
/// carries a sentence saying what was wrong.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum KernelError {
    /// A rule name the kernel does not know.
    UnknownRule(String),
    /// A law or hypothesis given to `Kernel::new` is malformed.
    BadAxiom(String),
    /// The path does not lead to a subterm.
    BadPath(String),
    /// The rewritten subterm is not an instance of the rule.
    NoMatch(String),
    /// The claimed substitution disagrees with the instance.
    WrongSubstitution(String),
    /// The step changes the term outside the rewritten position.
    WrongResult(String),
    /// An implication or a case assumption used where it is unsound.
    BadPosition(String),
    /// A delay side condition is false or not decidable on the instance.
    SideCondition(String),
    /// A signal side condition lacks a matching premise.
    MissingPremise(String),
    /// The pieces of a proof do not fit together.
    Mismatch(String),
    /// The certificate has no main proof, or proves something else.
    NotTheGoal(String),
    /// On a program's scans, a delay that is not a whole number of cycles.
    SubCycleDelay(String),
}

impl fmt::Display for KernelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use KernelError::*;
        let (what, detail) = match self {
            UnknownRule(d) => ("unknown rule", d),
            BadAxiom(d) => ("malformed axiom", d),
            BadPath(d) => ("no subterm at the position", d),
            NoMatch(d) => ("the instance does not match", d),
            WrongSubstitution(d) => ("wrong substitution", d),
            WrongResult(d) => ("wrong result", d),
            BadPosition(d) => ("unsound position", d),
            SideCondition(d) => ("side condition fails", d),
            MissingPremise(d) => ("missing premise", d),
            Mismatch(d) => ("proof pieces do not fit", d),
            NotTheGoal(d) => ("not a proof of the goal", d),
            SubCycleDelay(d) => ("a delay that is not a whole number of scan cycles", d),
        };
        write!(f, "{what}: {detail}")
    }
}

impl std::error::Error for KernelError {}
