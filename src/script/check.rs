//! The checker of proof scripts: justifies each step with the cited rules only, then asks the kernel.
//!
//! A step `A = B [r1, r2]` is justified by a small equality saturation that
//! knows only the cited laws (as rewrite rules) and the cited hypotheses and
//! lemmas (as named unions); its explanation becomes kernel steps. If that does
//! not close, a single rewrite with one cited rule at some position is tried
//! (an implication forward at a monotone position, an equation either way),
//! and the kernel's own objection is reported when the rewrite fits but is not
//! allowed (a false side condition, a wrong position). `auto` runs the full
//! prover. Each step is checked by the kernel on its own (for a located
//! error), and then the whole claim's certificate — earlier lemmas it cites,
//! and the steps joined by transitivity — is checked by [`Kernel::check_goal`].
//! Nothing is accepted without the kernel.

use std::collections::BTreeSet;
use std::time::{Duration, Instant};

use crate::diag::{Span, did_you_mean};
use crate::kernel::{
    Axiom, Certificate, Kernel, KernelError, Proof, Rel, Rule, Source, Step, Theorem, Use,
};
use crate::ladder::CompiledProgram;
use crate::prover::saturate::{self, Closed, Limits};
use crate::prover::{self, Budget, Context, Obligation, Outcome, explain, normalize};
use crate::syntax::{
    Claim, Goal, Notation, RuleRef, ScriptProof, Statement, goal_to_string, term_to_string,
};
use crate::term::instantiate;
use crate::term::{
    Expr, Id, Language, Term, and, and_not, constant, is_delay_node, root, same, subterm,
};
use crate::theory;
use crate::theory::match_side;

use super::error::{FailedStep, ScriptError};

/// Where a step is, for locating its failure.
#[derive(Clone, Copy)]
pub struct Site<'a> {
    /// The cited rules.
    pub rules: &'a [RuleRef],
    /// The step.
    pub span: Span,
    /// Its number (1-based).
    pub index: usize,
    /// The term before it.
    pub from: &'a Expr,
    /// Its relation.
    pub rel: Rel,
    /// The term after it.
    pub to: &'a Expr,
    /// The claim's goal, as printed.
    pub goal: &'a str,
}

/// A claim proved earlier, usable as a rule (a lemma of later certificates).
#[derive(Clone, Debug)]
pub struct ProvedClaim {
    /// Its name.
    pub name: String,
    /// Left side.
    pub lhs: Expr,
    /// `=` or `⇒`.
    pub rel: Rel,
    /// Right side.
    pub rhs: Expr,
    /// Its proof (may cite earlier claims as lemmas).
    pub proof: Proof,
    /// The earlier claims its proof cites, directly or not.
    pub deps: BTreeSet<String>,
    /// The lemmas of its own certificate (an induction's invariant and chains), named
    /// `CLAIM/LEMMA` so that no two claims' lemmas clash; replayed before its proof.
    pub own: Vec<(String, Proof)>,
}

impl ProvedClaim {
    /// A claim from a whole certificate the search returned: its lemmas are renamed
    /// `NAME/LEMMA`, in their proofs and in the main proof alike (`None` without a main
    /// proof).
    pub fn from_certificate(
        name: &str,
        (lhs, rel, rhs): (Expr, Rel, Expr),
        certificate: &Certificate,
    ) -> Option<ProvedClaim> {
        let own: BTreeSet<&str> = certificate.lemmas.iter().map(|(n, _)| n.as_str()).collect();
        let rename = |proof: &mut Proof| {
            proof.for_each_step_mut(&mut |s| {
                if let Rule::Cite(Source::Lemma, lemma, _) = &mut s.rule
                    && own.contains(lemma.as_str())
                {
                    *lemma = format!("{name}/{lemma}");
                }
            })
        };
        let mut proof = certificate.main.clone()?;
        rename(&mut proof);
        let own = certificate
            .lemmas
            .iter()
            .map(|(lemma, p)| {
                let mut p = p.clone();
                rename(&mut p);
                (format!("{name}/{lemma}"), p)
            })
            .collect();
        let deps = BTreeSet::new();
        Some(ProvedClaim { name: name.to_string(), lhs, rel, rhs, proof, deps, own })
    }
}

/// A claim the kernel accepted.
#[derive(Clone, Debug)]
pub struct Checked {
    /// The claim's name.
    pub name: String,
    /// The kernel's theorem.
    pub theorem: Theorem,
    /// The certificate it checked.
    pub certificate: Certificate,
    /// Time spent on the claim.
    pub time: Duration,
}

/// What a step may cite, sorted by kind.
#[derive(Default)]
struct Cited {
    auto: bool,
    laws: Vec<Axiom>,
    unions: Vec<Axiom>,
    lemmas: BTreeSet<String>,
}

/// One justified step: its proof and the earlier claims it cites.
#[derive(Clone, Debug)]
pub struct Justified {
    /// A proof of `from rel to`.
    pub proof: Proof,
    /// Earlier claims the proof cites.
    pub lemmas: BTreeSet<String>,
}

/// Why a step could not be justified (before it is given a location).
#[derive(Clone, Debug)]
pub enum StepError {
    /// A cited name is unknown (index into the cited list).
    Unknown(usize, Option<String>, bool),
    /// Nothing fits; the reason.
    NoProof(String),
    /// `auto` failed.
    Auto(String),
    /// The step is only an implication but was written as an equation.
    OnlyImplication,
}

/// The checker of one script: the kernel's axioms and the claims proved so far.
pub struct Checker {
    /// Laws and hypotheses (the kernel and the search rules).
    pub ctx: Context,
    /// Claims proved so far, in order.
    pub proved: Vec<ProvedClaim>,
    /// Claims of the script that failed (cited later: a clear error, not "unknown").
    pub failed: BTreeSet<String>,
    /// Budget of `auto`.
    pub budget: Budget,
    /// Limits of the saturation that justifies one step.
    pub step_limits: Limits,
    /// Notation of terms in messages.
    pub notation: Notation,
    /// The ladder program whose short names are shown in messages (`L1_pump` for `YL1_pump`).
    pub display: Option<CompiledProgram>,
}

/// Every position of a term (paths of child indices), root first.
pub fn positions(e: &Expr) -> Vec<Vec<usize>> {
    fn go(e: &Expr, id: Id, path: &mut Vec<usize>, out: &mut Vec<Vec<usize>>) {
        if is_delay_node(&e[id]) {
            return;
        }
        out.push(path.clone());
        for (i, c) in e[id].children().iter().enumerate() {
            path.push(i);
            go(e, *c, path, out);
            path.pop();
        }
    }
    let mut out = Vec::new();
    if !e.as_ref().is_empty() {
        go(e, root(e), &mut Vec::new(), &mut out);
    }
    out
}

/// The subterm at a path, if there is one.
pub fn at_path(e: &Expr, path: &[usize]) -> Option<Expr> {
    if e.as_ref().is_empty() {
        return None;
    }
    let mut id = root(e);
    for &i in path {
        id = *e[id].children().get(i)?;
    }
    Some(subterm(e, id))
}

fn rel_symbol(rel: Rel, notation: Notation) -> &'static str {
    match (rel, notation) {
        (Rel::Eq, _) => "=",
        (Rel::Implies, Notation::Paper) => "⇒",
        (Rel::Implies, Notation::Ascii) => "=>",
    }
}

impl Checker {
    /// A checker trusting these laws and hypotheses about free signals.
    pub fn new(laws: Vec<Axiom>, hypotheses: Vec<Axiom>) -> Result<Checker, KernelError> {
        Checker::with_scans(laws, hypotheses, None)
    }

    /// A checker for the scans of a program with this cycle, or (`None`) for free signals.
    pub fn with_scans(
        laws: Vec<Axiom>,
        hypotheses: Vec<Axiom>,
        cycle: Option<crate::term::Delay>,
    ) -> Result<Checker, KernelError> {
        // A script's proofs stand alone: they cite no lemma shared between goals.
        let mut ctx = Context::with_scans(laws, hypotheses, cycle)?;
        ctx.shared_lemmas = false;
        Ok(Checker {
            ctx,
            proved: Vec::new(),
            failed: BTreeSet::new(),
            budget: Budget::default(),
            step_limits: Limits { time: Duration::from_secs(3), nodes: 30_000, iterations: 30 },
            notation: Notation::Paper,
            display: None,
        })
    }

    /// An independent copy (same axioms, claims and settings), e.g. for a worker thread.
    pub fn snapshot(&self) -> Result<Checker, KernelError> {
        let (laws, hypotheses) = (self.ctx.laws.clone(), self.ctx.hypotheses().to_vec());
        let mut copy = Checker::with_scans(laws, hypotheses, self.ctx.cycle.clone())?;
        copy.ctx.hints = self.ctx.hints.clone();
        copy.proved = self.proved.clone();
        copy.failed = self.failed.clone();
        copy.budget = self.budget;
        copy.step_limits = self.step_limits;
        copy.notation = self.notation;
        copy.display = self.display.clone();
        Ok(copy)
    }

    /// Forgets a proved claim (the REPL's `undo` of a finished goal).
    pub fn forget(&mut self, name: &str) {
        self.proved.retain(|p| p.name != name);
    }

    /// The kernel.
    pub fn kernel(&self) -> &Kernel {
        &self.ctx.kernel
    }

    /// Prints a term in the checker's notation.
    pub fn term(&self, e: &Expr) -> String {
        match &self.display {
            Some(program) => term_to_string(&program.rename_for_display(e), self.notation),
            None => term_to_string(e, self.notation),
        }
    }

    /// Prints a goal in the checker's notation, with the program's short names.
    pub fn goal_text(&self, goal: &Goal) -> String {
        match &self.display {
            Some(program) => {
                let shown = Goal {
                    lhs: program.rename_for_display(&goal.lhs),
                    rhs: program.rename_for_display(&goal.rhs),
                    ..goal.clone()
                };
                goal_to_string(&shown, self.notation)
            }
            None => goal_to_string(goal, self.notation),
        }
    }

    /// Every name a step may cite: laws, hypotheses, proved claims.
    pub fn rule_names(&self) -> Vec<String> {
        let mut names: Vec<String> = self.ctx.laws.iter().map(|a| a.name.clone()).collect();
        names.extend(self.ctx.hypotheses().iter().map(|a| a.name.clone()));
        names.extend(self.proved.iter().map(|p| p.name.clone()));
        names
    }

    /// The statement a name stands for, as an axiom, and where it comes from.
    pub fn lookup(&self, name: &str) -> Option<(Source, Axiom)> {
        if let Some(law) = self.ctx.laws.iter().find(|a| a.name == name) {
            return Some((Source::Law, law.clone()));
        }
        if let Some(hyp) = self.ctx.hypotheses().iter().find(|a| a.name == name) {
            return Some((Source::Hypothesis, hyp.clone()));
        }
        self.proved.iter().find(|p| p.name == name).map(|p| {
            (Source::Lemma, Axiom::ground(p.name.clone(), p.lhs.clone(), p.rel, p.rhs.clone()))
        })
    }

    /// `name: lhs R rhs`, for notes and the REPL's `show`.
    pub fn describe(&self, name: &str) -> Option<String> {
        let (source, axiom) = self.lookup(name)?;
        let kind = match source {
            Source::Law => "law",
            Source::Hypothesis => "hypothesis",
            Source::Lemma => "lemma",
        };
        let mut text = format!(
            "{kind} {name}: {} {} {}",
            self.term(&axiom.lhs),
            rel_symbol(axiom.rel, self.notation),
            self.term(&axiom.rhs)
        );
        for (l, cmp, r) in &axiom.delay_conditions {
            let cmp = match cmp {
                crate::kernel::Cmp::Ge => ">=",
                crate::kernel::Cmp::Gt => ">",
                crate::kernel::Cmp::Le => "<=",
                crate::kernel::Cmp::Lt => "<",
                crate::kernel::Cmp::Eq => "=",
            };
            text.push_str(&format!(" if {} {cmp} {}", self.term(l), self.term(r)));
        }
        for (l, rel, r) in &axiom.signal_conditions {
            let rel = rel_symbol(*rel, self.notation);
            text.push_str(&format!(" if {} {rel} {}", self.term(l), self.term(r)));
        }
        Some(text)
    }

    fn cite(&self, rules: &[RuleRef]) -> Result<Cited, StepError> {
        let mut cited = Cited::default();
        for (i, rule) in rules.iter().enumerate() {
            if rule.name == "auto" {
                cited.auto = true;
                continue;
            }
            match self.lookup(&rule.name) {
                Some((Source::Law, axiom)) => cited.laws.push(axiom),
                Some((Source::Hypothesis, axiom)) => cited.unions.push(axiom),
                Some((Source::Lemma, axiom)) => {
                    cited.lemmas.insert(rule.name.clone());
                    cited.unions.push(axiom);
                }
                None => {
                    let names = self.rule_names();
                    let suggestion = did_you_mean(&rule.name, names.iter().map(String::as_str))
                        .map(str::to_string);
                    let claim = self.failed.contains(&rule.name);
                    return Err(StepError::Unknown(i, suggestion, claim));
                }
            }
        }
        Ok(cited)
    }

    /// The certificate of `main` with the earlier claims it needs, in order.
    pub fn certificate(&self, lemmas: &BTreeSet<String>, main: Proof) -> Certificate {
        let mut needed: BTreeSet<String> = lemmas.clone();
        for p in self.proved.iter().rev() {
            if needed.contains(&p.name) {
                needed.extend(p.deps.iter().cloned());
            }
        }
        let lemmas = self
            .proved
            .iter()
            .filter(|p| needed.contains(&p.name))
            .flat_map(|p| p.own.iter().cloned().chain([(p.name.clone(), p.proof.clone())]))
            .collect();
        Certificate { lemmas, main: Some(main) }
    }

    /// Checks a claim made by [`ProvedClaim::from_certificate`] (its own lemmas, then its
    /// proof, citing no earlier claim) and adds it.
    pub fn add_checked(&mut self, claim: ProvedClaim) -> Result<Theorem, KernelError> {
        let certificate =
            Certificate { lemmas: claim.own.clone(), main: Some(claim.proof.clone()) };
        let theorem =
            self.ctx.kernel.check_goal(&certificate, &claim.lhs, claim.rel, &claim.rhs)?;
        self.add_proved(claim);
        Ok(theorem)
    }

    /// Checks `proof` as a proof of `from rel to` (earlier claims as lemmas).
    pub fn check(
        &self,
        lemmas: &BTreeSet<String>,
        proof: Proof,
        from: &Expr,
        rel: Rel,
        to: &Expr,
    ) -> Result<(Theorem, Certificate), KernelError> {
        let certificate = self.certificate(lemmas, proof);
        let theorem = self.ctx.kernel.check_goal(&certificate, from, rel, to)?;
        Ok((theorem, certificate))
    }

    /// Justifies one step `from rel to` with the cited rules only (or `auto`).
    pub fn justify(
        &self,
        from: &Expr,
        rel: Rel,
        to: &Expr,
        rules: &[RuleRef],
    ) -> Result<Justified, StepError> {
        let cited = self.cite(rules)?;
        if same(from, to) {
            let proof = Proof::Chain { start: from.clone(), steps: Vec::new() };
            return Ok(Justified { proof, lemmas: BTreeSet::new() });
        }
        if cited.auto {
            let goal = Obligation { lhs: from.clone(), rel, rhs: to.clone() };
            return match prover::prove(&self.ctx, &goal, self.budget) {
                Outcome::Proved(p) => match p.certificate.main {
                    Some(proof) => Ok(Justified { proof, lemmas: BTreeSet::new() }),
                    None => Err(StepError::Auto("the prover returned no proof".into())),
                },
                Outcome::Unknown { reason, .. } => Err(StepError::Auto(reason)),
            };
        }
        let mut objection: Option<String> = None;
        // 1. A small saturation with the cited rules only.
        let saturation = self.by_saturation(from, rel, to, &cited);
        let stop = match saturation {
            Ok(proof) => match self.check(&cited.lemmas, proof.clone(), from, rel, to) {
                Ok(_) => return Ok(Justified { proof, lemmas: cited.lemmas }),
                Err(e) => {
                    objection = Some(format!("the kernel rejects the rewrites found: {e}"));
                    String::new()
                }
            },
            Err(stop) => stop,
        };
        // 2. One rewrite with one cited rule; the kernel says why it is not allowed.
        match self.single_rewrite(from, rel, to, &cited) {
            Ok(proof) => return Ok(Justified { proof, lemmas: cited.lemmas }),
            Err(Some(e)) => objection = Some(e),
            Err(None) => {}
        }
        if rel == Rel::Eq {
            // Would it hold as an implication?
            if let Ok(p) = self.by_saturation(from, Rel::Implies, to, &cited)
                && self.check(&cited.lemmas, p, from, Rel::Implies, to).is_ok()
            {
                return Err(StepError::OnlyImplication);
            }
            if self.single_rewrite(from, Rel::Implies, to, &cited).is_ok() {
                return Err(StepError::OnlyImplication);
            }
        }
        Err(StepError::NoProof(objection.unwrap_or_else(|| {
            format!("no way to get from the left to the right with the cited rules ({stop})")
        })))
    }

    fn by_saturation(
        &self,
        from: &Expr,
        rel: Rel,
        to: &Expr,
        cited: &Cited,
    ) -> Result<Proof, String> {
        let rules = saturate::rules_for(&cited.laws);
        let mut run = saturate::saturate(from, rel, to, &cited.unions, &rules, self.step_limits);
        let Some(closed) = run.closed else {
            return Err(format!("saturation: {}, {} e-nodes", run.stop, run.nodes));
        };
        let (_, a, b) = saturate::goal_pairs(from, rel, to)
            .into_iter()
            .find(|(c, _, _)| *c == closed)
            .ok_or_else(|| "no goal pair".to_string())?;
        let steps = explain::chain_steps(&mut run.egraph, &a, &b).map_err(|e| e.0)?;
        let steps = steps
            .into_iter()
            .map(|mut s| {
                if let Rule::Cite(Source::Hypothesis, name, how) = &s.rule
                    && cited.lemmas.contains(name)
                {
                    s.rule = Rule::Cite(Source::Lemma, name.clone(), *how);
                }
                s
            })
            .collect();
        let chain = Proof::Chain { start: a, steps };
        Ok(match closed {
            Closed::Equal => chain,
            Closed::Meet => Proof::ImpliesByMeet(Box::new(chain)),
            Closed::Zero => Proof::ImpliesByZero(Box::new(chain)),
        })
    }

    /// Every single rewrite of `term` by one rule (at `path`, or anywhere; into exactly
    /// `target` if given, which also binds variables the rewritten side lacks), with the
    /// relation the kernel grants it. Returns the accepted ones and the kernel's last objection.
    pub fn rewrites(
        &self,
        term: &Expr,
        name: &str,
        path: Option<&[usize]>,
        target: Option<&Expr>,
    ) -> (Vec<(Step, Rel)>, Option<String>) {
        let Some((source, axiom)) = self.lookup(name) else {
            return (Vec::new(), None);
        };
        let mut accepted = Vec::new();
        let mut objection = None;
        let paths = match path {
            Some(p) => vec![p.to_vec()],
            None => positions(term),
        };
        let lemmas: BTreeSet<String> =
            if source == Source::Lemma { [name.to_string()].into() } else { BTreeSet::new() };
        for p in paths {
            let Some(sub) = at_path(term, &p) else { continue };
            // With a target, the new subterm is the target's subterm at the same place.
            let wanted = match target {
                Some(t) => match at_path(t, &p) {
                    Some(new) if same(&normalize::replace_at(term, &p, &new), t) => Some(new),
                    _ => continue,
                },
                None => None,
            };
            for how in [Use::Forward, Use::Backward] {
                let (pattern, other) = match how {
                    Use::Forward => (&axiom.lhs, &axiom.rhs),
                    _ => (&axiom.rhs, &axiom.lhs),
                };
                let mut sigma = std::collections::BTreeMap::new();
                if !match_side(&axiom, pattern, &sub, &mut sigma) {
                    continue;
                }
                let new = match &wanted {
                    Some(new) => {
                        if !match_side(&axiom, other, new, &mut sigma) {
                            continue;
                        }
                        new.clone()
                    }
                    None => {
                        // Every variable of the result must be bound by the match.
                        let unbound = other.as_ref().iter().any(|n| {
                            matches!(n, Term::Name(v)
                                if (axiom.signal_vars.contains(v) || axiom.delay_vars.contains(v))
                                    && !sigma.contains_key(v))
                        });
                        if unbound {
                            continue;
                        }
                        match instantiate(other, &sigma) {
                            Some(new) => new,
                            None => continue,
                        }
                    }
                };
                let after = normalize::replace_at(term, &p, &new);
                if same(&after, term) {
                    continue;
                }
                let premises = self.premises(&axiom, &sigma);
                let step = Step {
                    path: p.clone(),
                    rule: Rule::Cite(source, name.to_string(), how),
                    after: after.clone(),
                    subst: Vec::new(),
                    premises,
                };
                let proof = Proof::Chain { start: term.clone(), steps: vec![step.clone()] };
                let certificate = self.certificate(&lemmas, proof);
                match self.ctx.kernel.check(&certificate) {
                    Ok(thm) => accepted.push((step, thm.rel())),
                    Err(e) => {
                        // The first objection (a forward use) unless a later one is about
                        // a side condition, which says more.
                        let telling = matches!(
                            e,
                            KernelError::SideCondition(_) | KernelError::MissingPremise(_)
                        );
                        if objection.is_none() || telling {
                            objection = Some(format!("`{name}` does not apply here: {e}"));
                        }
                    }
                }
            }
        }
        (accepted, objection)
    }

    /// Proofs of a law's signal side conditions on an instance, by the full prover.
    fn premises(
        &self,
        axiom: &Axiom,
        sigma: &std::collections::BTreeMap<crate::term::Symbol, Expr>,
    ) -> Vec<Proof> {
        let mut out = Vec::new();
        for (l, rel, r) in &axiom.signal_conditions {
            let (Some(lhs), Some(rhs)) = (instantiate(l, sigma), instantiate(r, sigma)) else {
                return Vec::new();
            };
            let small = Budget { time: self.budget.time / 4, ..self.budget };
            match prover::prove(&self.ctx, &Obligation { lhs, rel: *rel, rhs }, small) {
                Outcome::Proved(p) if p.certificate.main.is_some() => {
                    out.extend(p.certificate.main);
                }
                _ => return Vec::new(),
            }
        }
        out
    }

    /// One rewrite with one cited rule from `from` to exactly `to`.
    /// `Err(Some(why))`: a rewrite fits but the kernel objects.
    fn single_rewrite(
        &self,
        from: &Expr,
        rel: Rel,
        to: &Expr,
        cited: &Cited,
    ) -> Result<Proof, Option<String>> {
        let mut objection = None;
        for axiom in cited.laws.iter().chain(&cited.unions) {
            let (found, why) = self.rewrites(from, &axiom.name, None, Some(to));
            for (step, got) in found {
                if rel == Rel::Implies || got == Rel::Eq {
                    return Ok(Proof::Chain { start: from.clone(), steps: vec![step] });
                }
            }
            if why.is_some() && objection.is_none() {
                objection = why;
            }
        }
        Err(objection)
    }

    /// A step's failure, located at the step (or at the unknown name).
    pub fn located(&self, error: StepError, site: &Site<'_>) -> ScriptError {
        let Site { rules, span, index, from, rel, to, goal } = *site;
        match error {
            StepError::Unknown(i, suggestion, unproved_claim) => {
                let (name, rule_span) =
                    rules.get(i).map_or((String::new(), span), |r| (r.name.clone(), r.span));
                ScriptError::UnknownRule { span: rule_span, name, suggestion, unproved_claim }
            }
            StepError::OnlyImplication => {
                ScriptError::OnlyImplication { span, goal: goal.to_string() }
            }
            StepError::Auto(reason) => ScriptError::AutoFailed {
                method: "auto",
                span,
                goal: format!(
                    "{} {} {}",
                    self.term(from),
                    rel_symbol(rel, self.notation),
                    self.term(to)
                ),
                reason,
            },
            StepError::NoProof(reason) => ScriptError::StepFailed(Box::new(FailedStep {
                span,
                index,
                from: self.term(from),
                relation: rel_symbol(rel, self.notation).to_string(),
                to: self.term(to),
                reason,
                cited: rules.iter().filter_map(|r| self.describe(&r.name)).collect(),
            })),
        }
    }

    /// Checks one claim; on success it becomes citable by later steps.
    pub fn check_claim(&mut self, statement: &Statement<Claim>) -> Result<Checked, ScriptError> {
        let result = self.check_claim_inner(statement);
        match &result {
            Ok(_) => {}
            Err(_) => {
                self.failed.insert(statement.name.clone());
            }
        }
        result
    }

    fn check_claim_inner(&mut self, statement: &Statement<Claim>) -> Result<Checked, ScriptError> {
        let started = Instant::now();
        if matches!(self.lookup(&statement.name), Some((Source::Law | Source::Hypothesis, _))) {
            return Err(ScriptError::BadContext {
                span: statement.name_span,
                reason: format!(
                    "`{}` is already the name of a law or hypothesis; a claim needs another name",
                    statement.name
                ),
            });
        }
        let claim = &statement.value;
        let (lhs, rel, rhs) = theory::goal_parts(&claim.goal);
        let goal_text = self.goal_text(&claim.goal);
        let (main, lemmas) = match &claim.proof {
            ScriptProof::Auto(span) | ScriptProof::By(_, span) => {
                let auto = [RuleRef { name: "auto".into(), span: *span }];
                let rules: &[RuleRef] = match &claim.proof {
                    ScriptProof::By(rules, _) => rules,
                    _ => &auto,
                };
                let justified = self.justify(&lhs, rel, &rhs, rules).map_err(|e| {
                    let site = Site {
                        rules,
                        span: *span,
                        index: 1,
                        from: &lhs,
                        rel,
                        to: &rhs,
                        goal: &goal_text,
                    };
                    self.located(e, &site)
                })?;
                (justified.proof, justified.lemmas)
            }
            ScriptProof::Induction(span) => {
                if !self.ctx.scans {
                    return Err(ScriptError::BadContext {
                        span: *span,
                        reason: "induction over scans needs a program: start the script with \
                                 a `program \"FILE.ld\"` header"
                            .into(),
                    });
                }
                let goal = Obligation { lhs: lhs.clone(), rel, rhs: rhs.clone() };
                let deadline = Instant::now() + self.budget.time;
                let name = format!("{}_inv", statement.name);
                let found =
                    prover::induction::prove_as(&self.ctx, &goal, self.budget, deadline, &name)
                        .ok();
                let Some(Certificate { mut lemmas, main: Some(main) }) =
                    found.map(|p| p.certificate)
                else {
                    return Err(ScriptError::AutoFailed {
                        method: "induction",
                        span: *span,
                        goal: goal_text,
                        reason: "no inductive invariant over the program's state bits was found"
                            .into(),
                    });
                };
                let (name, invariant) = lemmas.remove(0);
                if let Proof::Induction { inv, .. } = &invariant {
                    let (lhs, rhs) = (inv.clone(), constant(true));
                    let deps = BTreeSet::new();
                    let proof = invariant.clone();
                    self.add_proved(ProvedClaim {
                        name: name.clone(),
                        lhs,
                        rel: Rel::Eq,
                        rhs,
                        proof,
                        deps,
                        own: Vec::new(),
                    });
                }
                (main, BTreeSet::from([name]))
            }
            ScriptProof::Calc { start, start_span, steps, qed } => {
                // Where must the chain start and end, and how does it close?
                let meet = and(&lhs, &rhs);
                let zero_start = and_not(&lhs, &rhs);
                enum Closing {
                    Direct,
                    Symm,
                    Meet,
                    Zero,
                }
                let (closing, end) = if same(start, &lhs) {
                    (Closing::Direct, rhs.clone())
                } else if rel == Rel::Eq && same(start, &rhs) {
                    (Closing::Symm, lhs.clone())
                } else if rel == Rel::Implies && same(start, &meet) {
                    (Closing::Meet, lhs.clone())
                } else if rel == Rel::Implies && same(start, &zero_start) {
                    (Closing::Zero, constant(false))
                } else {
                    return Err(ScriptError::WrongStart {
                        span: *start_span,
                        found: self.term(start),
                        expected: self.term(&lhs),
                    });
                };
                let mut current = start.clone();
                let mut proof: Option<Proof> = None;
                let mut lemmas = BTreeSet::new();
                for (i, step) in steps.iter().enumerate() {
                    let step_rel = theory::relation(step.relation);
                    let only_eq = matches!(closing, Closing::Meet | Closing::Zero | Closing::Symm)
                        || rel == Rel::Eq;
                    if step_rel == Rel::Implies && only_eq {
                        return Err(ScriptError::OnlyImplication {
                            span: step.span,
                            goal: goal_text.clone(),
                        });
                    }
                    let justified =
                        self.justify(&current, step_rel, &step.term, &step.rules).map_err(|e| {
                            let site = Site {
                                rules: &step.rules,
                                span: step.span,
                                index: i + 1,
                                from: &current,
                                rel: step_rel,
                                to: &step.term,
                                goal: &goal_text,
                            };
                            self.located(e, &site)
                        })?;
                    lemmas.extend(justified.lemmas);
                    proof = Some(match proof {
                        None => justified.proof,
                        Some(p) => Proof::Trans(Box::new(p), Box::new(justified.proof)),
                    });
                    current = step.term.clone();
                }
                if !same(&current, &end) {
                    let span = steps.last().map_or(*start_span, |s| s.span);
                    let _ = qed;
                    return Err(ScriptError::StopsShort {
                        span,
                        reached: self.term(&current),
                        expected: self.term(&end),
                    });
                }
                let chain = proof.unwrap_or(Proof::Chain { start: start.clone(), steps: vec![] });
                let main = match closing {
                    Closing::Direct => chain,
                    Closing::Symm => Proof::Symm(Box::new(chain)),
                    Closing::Meet => Proof::ImpliesByMeet(Box::new(chain)),
                    Closing::Zero => Proof::ImpliesByZero(Box::new(chain)),
                };
                (main, lemmas)
            }
        };
        let (theorem, certificate) =
            self.check(&lemmas, main.clone(), &lhs, rel, &rhs).map_err(|e| {
                ScriptError::Kernel {
                    span: statement.name_span,
                    name: statement.name.clone(),
                    error: e.to_string(),
                }
            })?;
        self.add_proved(ProvedClaim {
            name: statement.name.clone(),
            lhs,
            rel,
            rhs,
            proof: main,
            deps: self.closure(&lemmas),
            own: Vec::new(),
        });
        Ok(Checked { name: statement.name.clone(), theorem, certificate, time: started.elapsed() })
    }

    fn closure(&self, lemmas: &BTreeSet<String>) -> BTreeSet<String> {
        let mut all = lemmas.clone();
        for p in self.proved.iter().rev() {
            if all.contains(&p.name) {
                all.extend(p.deps.iter().cloned());
            }
        }
        all
    }

    /// Records a claim the kernel accepted, so later steps may cite it.
    pub fn add_proved(&mut self, claim: ProvedClaim) {
        self.failed.remove(&claim.name);
        self.proved.retain(|p| p.name != claim.name);
        self.proved.push(claim);
    }
}
