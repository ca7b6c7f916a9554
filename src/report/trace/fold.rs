//! The folded view of a proof's lemmas: an induction's timer chains, its step clauses and its invariant's clauses that differ only in a count of cycles each print as one line.
//!
//! The invariant search proves a lemma per step of each timer chain (`T_k = f · pre
//! T_(k−1)`, `T_k ⇒ T_(k−1)`, each also one scan earlier) and one per clause of the
//! induction step. Printed in full they make traces of thousands of lines; here
//!
//! - a chain's lemmas are one header (`lemma inv_t0_1…10 (14 lemmas), the timer chain
//!   of X = …, δ = 100ms:`) and one line of its forms, each a template in `k` with
//!   the values of `k` it was proved for (`kδ/X = X · pre ((k−1)δ/X) for k = 2…5, 10`);
//! - the induction lemma is its invariant (clauses of the same shape folded the same
//!   way), its first scan and its step, each one line naming what it cites, the step's
//!   per-clause lemmas included;
//! - a memory's recurrence is one line.
//!
//! Other lemmas print in full. Presentation only: the kernel checked every lemma, and
//! `--trace-all` prints each one.

use std::collections::BTreeSet;

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;

use super::{Style, is_bookkeeping, parts, proof_text, rule_label, start_of};
use crate::kernel::{Proof, Rel, Rule, Source};
use crate::prover::Proved;
use crate::prover::timing::{ChainForm, LemmaKind, chain_family, lemma_kind, step_lemma};
use crate::syntax::{Notation, delay_to_string, term_to_string};
use crate::term::{Delay, Expr, Id, Language, Term, copy_into, root, same_tree, subterm};

/// A printed line is wrapped (clauses of an invariant) at this width.
const WIDTH: usize = 100;
/// A summary names at most this many of the statements a proof cites.
const CITED: usize = 10;

/// The lemmas of `proved`, folded, as text lines.
pub(super) fn lemmas(proved: &Proved, style: &Style) -> Vec<String> {
    let lemmas = &proved.certificate.lemmas;
    let prefixes: Vec<&str> = lemmas
        .iter()
        .filter(|(_, p)| matches!(p, Proof::Induction { .. }))
        .map(|(n, _)| n.as_str())
        .collect();
    let kind = |name: &str| prefixes.iter().find_map(|p| Some((*p, lemma_kind(name, p)?)));
    let mut folder = Folder::new(proved, style, &prefixes);
    let mut out = Vec::new();
    let mut chains_done = BTreeSet::new();
    for (name, proof) in lemmas {
        match kind(name) {
            Some((prefix, LemmaKind::Chain { chain, .. })) => {
                if chains_done.insert((prefix, chain)) {
                    let members: Vec<Member> = lemmas
                        .iter()
                        .filter_map(|(n, p)| match kind(n) {
                            Some((q, LemmaKind::Chain { chain: c, k, form, previous }))
                                if q == prefix && c == chain =>
                            {
                                Some(Member { proof: p, k, form, previous })
                            }
                            _ => None,
                        })
                        .collect();
                    folder.chain(&chain_family(prefix, chain), &members, &mut out);
                }
            }
            Some((_, LemmaKind::Step(_))) => {}
            Some((_, LemmaKind::Memory(_))) => folder.one_line(name, proof, Rel::Eq, &mut out),
            None => match proof {
                Proof::Induction { inv, base, step } if prefixes.contains(&name.as_str()) => {
                    folder.induction(name, inv, base, step, &mut out)
                }
                _ => {
                    out.push(format!("lemma {name}:"));
                    proof_text(proof, &[], style, "    ", &mut out);
                }
            },
        }
    }
    out
}

/// One lemma of a timer chain.
struct Member<'p> {
    proof: &'p Proof,
    k: usize,
    form: ChainForm,
    previous: bool,
}

/// One statement to fold: its terms (renamed and abbreviated) and what must agree for
/// it to share a line with others (relation, cited laws).
struct Item {
    terms: Vec<Expr>,
    tag: String,
}

/// Statements printed as one: their text (a template in `k` when folded) and the `k`
/// of each member (empty when the group is one statement).
struct Group {
    members: Vec<usize>,
    texts: Vec<String>,
    ks: Vec<BigInt>,
}

struct Folder<'a> {
    style: &'a Style<'a>,
    /// Names in use in the proof (an abbreviation is none of them).
    names: BTreeSet<String>,
    /// Compound chain inputs (renamed) and the short names they print as.
    short: Vec<(Expr, Expr)>,
    /// The delay `k` counts, once known, and whether a line has said it.
    delta: Option<Delay>,
    said: bool,
    /// The certificate's lemmas, for the step's per-clause lemmas.
    lemmas: &'a [(String, Proof)],
    prefixes: &'a [&'a str],
}

impl<'a> Folder<'a> {
    fn new(proved: &'a Proved, style: &'a Style<'a>, prefixes: &'a [&'a str]) -> Self {
        let mut names = BTreeSet::new();
        let mut add = |e: &Expr| {
            for t in (style.rename)(e).as_ref() {
                if let Term::Name(n) = t {
                    names.insert(n.as_str().to_string());
                }
            }
        };
        for (_, p) in &proved.certificate.lemmas {
            if let Some(s) = start_of(p) {
                add(s);
            }
        }
        add(proved.theorem.lhs());
        add(proved.theorem.rhs());
        Folder {
            style,
            names,
            short: Vec::new(),
            delta: None,
            said: false,
            lemmas: &proved.certificate.lemmas,
            prefixes,
        }
    }

    fn paper(&self) -> bool {
        self.style.notation == Notation::Paper
    }

    /// `…` (ASCII `..`).
    fn dots(&self) -> &'static str {
        if self.paper() { "…" } else { ".." }
    }

    /// `e` renamed for display, with the chains' inputs abbreviated.
    fn shown(&self, e: &Expr) -> Expr {
        let renamed = (self.style.rename)(e);
        map_tree(&renamed, &mut |x, id| {
            self.short
                .iter()
                .find(|(long, _)| same_tree(x, id, long, root(long)))
                .map(|(_, s)| s.clone())
        })
    }

    fn print(&self, e: &Expr) -> String {
        flat(&term_to_string(e, self.style.notation))
    }

    /// `δ = 100ms` the first time a line uses `δ`.
    fn say_delta(&mut self) -> String {
        match (&self.delta, self.said) {
            (Some(d), false) => {
                self.said = true;
                let symbol = if self.paper() { "δ" } else { "d" };
                format!(", {symbol} = {}", delay_to_string(d))
            }
            _ => String::new(),
        }
    }

    /// A chain's lemmas: a header naming the chain, then its forms on one line.
    fn chain(&mut self, family: &str, members: &[Member], out: &mut Vec<String>) {
        let statement = |m: &Member| Some((start_of(m.proof)?.clone(), end_of(m.proof)?.clone()));
        // The chain's input, from a timer `kδ/f` (or `f/kδ`) on a left side, and its
        // cycle where that timer is `T_k` of the lemma's name (not in an off-delay's
        // `T_(k−1) ⇒ T_k`).
        let timer = |exact: bool| {
            members.iter().find_map(|m| {
                let (lhs, _) = statement(m)?;
                let (d, f) = timer_parts(&lhs)?;
                let named = m.form != ChainForm::Monotone;
                (named || !exact).then_some((d, f, if named { m.k } else { 0 }))
            })
        };
        let timer = timer(true).or_else(|| timer(false));
        let (low, high) =
            members.iter().fold((usize::MAX, 0), |(l, h), m| (l.min(m.k), h.max(m.k)));
        let mut header = match low == high {
            true => format!("lemma {family}_{low}"),
            false => format!("lemma {family}_{low}{}{high}", self.dots()),
        };
        header.push_str(&match members.len() {
            1 => " (1 lemma)".to_string(),
            n => format!(" ({n} lemmas)"),
        });
        if let Some((d, f, k)) = &timer {
            if self.delta.is_none() && *k > 0 {
                let k = BigRational::from_integer(BigInt::from(*k));
                self.delta = Delay::new(d.seconds() / k).ok();
            }
            let input = (self.style.rename)(f);
            let text = self.print(&input);
            if matches!(input[root(&input)], Term::Name(_) | Term::One | Term::Zero) {
                header.push_str(&format!(", the timer chain of {text}"));
            } else {
                let short = self.fresh_name();
                header.push_str(&format!(", the timer chain of {short} = {text}"));
                self.short.push((input, crate::term::name(&short)));
            }
        }
        let base: Vec<&Member> = members.iter().filter(|m| !m.previous).collect();
        let earlier: BTreeSet<(usize, ChainForm)> =
            members.iter().filter(|m| m.previous).map(|m| (m.k, m.form)).collect();
        let items: Vec<Item> = base
            .iter()
            .filter_map(|m| {
                let (l, r) = statement(m)?;
                let tag = format!("{:?} {}", m.form, cited(m.proof, &|_| None).join(", "));
                Some(Item { terms: vec![self.shown(&l), self.shown(&r)], tag })
            })
            .collect();
        let groups = self.fold(&items);
        let mut segments = Vec::new();
        for g in &groups {
            let m = base[g.members[0]];
            let rel = self.rel(m.form.rel());
            let mut text = format!("{} {rel} {}", g.texts[0], g.texts[1]);
            if !g.ks.is_empty() {
                text.push_str(&format!(" for k = {}", self.range(&g.ks)));
            }
            // The members proved one scan earlier too, by their `k` in the template.
            let before: Vec<BigInt> = g
                .members
                .iter()
                .zip(g.ks.iter().map(Some).chain(std::iter::repeat(None)))
                .filter(|(i, _)| earlier.contains(&(base[**i].k, base[**i].form)))
                .filter_map(|(_, k)| k.cloned())
                .collect();
            let all = g.members.iter().all(|i| earlier.contains(&(base[*i].k, base[*i].form)));
            if all {
                text.push_str(", and one scan earlier");
            } else if !before.is_empty() {
                text.push_str(&format!(", and one scan earlier for k = {}", self.range(&before)));
            }
            let laws = cited(m.proof, &|_| None).join(", ");
            segments.push(format!("{text}   [{laws}]"));
        }
        header.push_str(&self.say_delta());
        header.push(':');
        out.push(header);
        out.push(format!("    {}", segments.join(";  ")));
    }

    /// A lemma proved by one chain, as its statement on one line.
    fn one_line(&mut self, name: &str, proof: &Proof, rel: Rel, out: &mut Vec<String>) {
        let (Some(l), Some(r)) = (start_of(proof), end_of(proof)) else {
            out.push(format!("lemma {name}:"));
            proof_text(proof, &[], self.style, "    ", out);
            return;
        };
        let (l, r) = (self.print(&self.shown(l)), self.print(&self.shown(r)));
        let laws = cited(proof, &|_| None).join(", ");
        out.push(format!("lemma {name}: {l} {} {r}   [{laws}]", self.rel(rel)));
    }

    /// The induction lemma: its invariant's clauses (folded), first scan and step.
    fn induction(
        &mut self,
        name: &str,
        inv: &Expr,
        base: &Proof,
        step: &Proof,
        out: &mut Vec<String>,
    ) {
        let shown = self.shown(inv);
        let mut clauses = Vec::new();
        spine(&shown, root(&shown), &mut clauses);
        let items: Vec<Item> = clauses
            .iter()
            .map(|&id| Item { terms: vec![subterm(&shown, id)], tag: String::new() })
            .collect();
        let groups = self.fold(&items);
        let and = if self.paper() { " · " } else { " . " };
        let parts: Vec<String> = groups
            .iter()
            .map(|g| {
                let c = &items[g.members[0]].terms[0];
                let text = match (&c[root(c)], clauses.len()) {
                    (Term::Or(_) | Term::And(_), 2..) => format!("({})", g.texts[0]),
                    _ => g.texts[0].clone(),
                };
                match g.ks.is_empty() {
                    true => text,
                    false => format!("{text} for k = {}", self.range(&g.ks)),
                }
            })
            .collect();
        let delta =
            if groups.iter().any(|g| !g.ks.is_empty()) { self.say_delta() } else { String::new() };
        out.push(match clauses.len() {
            1 => format!("lemma {name}: I = 1*, by induction over scans, where I is{delta}:"),
            n => format!(
                "lemma {name}: I = 1*, by induction over scans, where I is the product of {n} clauses{delta}:"
            ),
        });
        let mut line = String::new();
        for part in parts {
            if !line.is_empty() && line.chars().count() + part.chars().count() + 3 > WIDTH {
                out.push(line);
                line = format!("  {}", and.trim_start());
            } else if line.is_empty() {
                line.push_str("    ");
            } else {
                line.push_str(and);
            }
            line.push_str(&part);
        }
        out.push(line);
        let implies = self.rel(Rel::Implies);
        let how = |p: &Proof| method(std::slice::from_ref(&p));
        let from = |n: &str| self.step_of(n);
        out.push(format!(
            "    first scan (every previous value 0): 1* {implies} I, {}{}",
            how(base),
            self.capped(cited(base, &from))
        ));
        let steps: Vec<&Proof> = (0..).map_while(|i| self.lemma(&step_lemma(name, i))).collect();
        let (cases, d) = (method(&steps), self.dots());
        let per_clause = match steps.len() {
            0 => how(step).to_string(),
            1 => format!("one clause at a time ({}, {cases})", step_lemma(name, 0)),
            n => format!(
                "one clause at a time ({}{d}{}, {cases})",
                step_lemma(name, 0),
                step_lemma(name, n - 1)
            ),
        };
        out.push(format!(
            "    step, from the previous scan: pre I {implies} I, {per_clause}{}",
            self.capped(cited(step, &from))
        ));
    }

    /// `   [cited]`: the names with a chain's lemmas as the chain (`inv_t0_…`), at most
    /// [`CITED`], then how many more; nothing when nothing is cited.
    fn capped(&self, names: Vec<String>) -> String {
        let d = self.dots();
        let mut shown: Vec<String> = Vec::new();
        for n in names {
            let family = self.prefixes.iter().find_map(|p| match lemma_kind(&n, p) {
                Some(LemmaKind::Chain { chain, .. }) => {
                    Some(format!("{}_{d}", chain_family(p, chain)))
                }
                _ => None,
            });
            let n = family.unwrap_or(n);
            if !shown.contains(&n) {
                shown.push(n);
            }
        }
        match shown.len() {
            0 => String::new(),
            n if n <= CITED => format!("   [{}]", shown.join(", ")),
            n => format!("   [{}, {d} ({} more)]", shown[..CITED].join(", "), n - CITED),
        }
    }

    fn lemma(&self, name: &str) -> Option<&'a Proof> {
        self.lemmas.iter().find(|(n, _)| n == name).map(|(_, p)| p)
    }

    /// The proof of `name` when it is an induction step's per-clause lemma.
    fn step_of(&self, name: &str) -> Option<&'a Proof> {
        let is_step =
            self.prefixes.iter().any(|p| matches!(lemma_kind(name, p), Some(LemmaKind::Step(_))));
        if is_step { self.lemma(name) } else { None }
    }

    fn rel(&self, rel: Rel) -> &'static str {
        match rel {
            Rel::Eq => "=",
            Rel::Implies => self.style.implies(),
        }
    }

    fn fresh_name(&self) -> String {
        let taken = |n: &String| {
            self.names.contains(n) || self.short.iter().any(|(_, s)| self.print(s) == *n)
        };
        let mut i = 0;
        loop {
            for base in ["X", "Y", "Z"] {
                let n = if i == 0 { base.to_string() } else { format!("{base}{i}") };
                if !taken(&n) {
                    return n;
                }
            }
            i += 1;
        }
    }

    /// `2…5, 10` (ASCII `2..5, 10`).
    fn range(&self, ks: &[BigInt]) -> String {
        let mut ks = ks.to_vec();
        ks.sort();
        ks.dedup();
        let d = self.dots();
        let mut runs: Vec<(BigInt, BigInt)> = Vec::new();
        for k in ks {
            match runs.last_mut() {
                Some((_, last)) if &*last + 1 == k => *last = k,
                _ => runs.push((k.clone(), k)),
            }
        }
        let runs: Vec<String> = runs
            .into_iter()
            .map(|(a, b)| {
                if a == b {
                    a.to_string()
                } else if &a + 1 == b {
                    format!("{a}, {b}")
                } else {
                    format!("{a}{d}{b}")
                }
            })
            .collect();
        runs.join(", ")
    }

    /// Groups the items of the same shape whose delays are whole multiples of `δ` at a
    /// fixed distance from the first varying one (`k`), in the order of their first
    /// member; the rest print one by one.
    fn fold(&mut self, items: &[Item]) -> Vec<Group> {
        let mut shapes: Vec<(String, Vec<usize>)> = Vec::new();
        for (i, item) in items.iter().enumerate() {
            let mut key = item.tag.clone();
            for t in &item.terms {
                key.push('\u{0}');
                key.push_str(&self.print(&map_delays(t, &mut |_| Some(marker_expr(None)))));
            }
            match shapes.iter_mut().find(|(k, _)| *k == key) {
                Some((_, members)) => members.push(i),
                None => shapes.push((key, vec![i])),
            }
        }
        let mut groups = Vec::new();
        for (_, members) in shapes {
            match self.template(items, &members) {
                Some(g) => groups.push(g),
                None => groups.extend(members.into_iter().map(|i| Group {
                    members: vec![i],
                    texts: items[i].terms.iter().map(|t| self.print(t)).collect(),
                    ks: Vec::new(),
                })),
            }
        }
        groups
    }

    /// The template of items of one shape, when their varying delays are `kδ + c`.
    fn template(&mut self, items: &[Item], members: &[usize]) -> Option<Group> {
        if members.len() < 2 {
            return None;
        }
        let delays: Vec<Vec<BigRational>> =
            members.iter().map(|&i| items[i].terms.iter().flat_map(delays_of).collect()).collect();
        let first = &delays[0];
        let varying: Vec<usize> =
            (0..first.len()).filter(|&j| delays.iter().any(|d| d[j] != first[j])).collect();
        let v0 = *varying.first()?;
        let delta = match &self.delta {
            Some(d) => d.seconds().clone(),
            None => {
                let g = varying
                    .iter()
                    .flat_map(|&j| delays.iter().map(move |d| d[j].clone()))
                    .reduce(|a, b| gcd(&a, &b))?;
                self.delta = Some(Delay::new(g.clone()).ok()?);
                g
            }
        };
        let whole = |x: &BigRational| {
            let m = x / &delta;
            m.is_integer().then(|| m.to_integer())
        };
        let mut ks = Vec::new();
        let mut offsets: Option<Vec<BigInt>> = None;
        for d in &delays {
            let k = whole(&d[v0])?;
            let o: Vec<BigInt> =
                varying.iter().map(|&j| Some(whole(&d[j])? - &k)).collect::<Option<_>>()?;
            match &offsets {
                Some(first) if *first != o => return None,
                Some(_) => {}
                None => offsets = Some(o),
            }
            ks.push(k);
        }
        let offsets = offsets?;
        let mut at = 0;
        let texts = items[members[0]]
            .terms
            .iter()
            .map(|t| {
                let marked = map_delays(t, &mut |_| {
                    let j = at;
                    at += 1;
                    let v = varying.iter().position(|&x| x == j)?;
                    Some(marker_expr(Some(&offsets[v])))
                });
                self.unmark(&self.print(&marked))
            })
            .collect();
        Some(Group { members: members.to_vec(), texts, ks })
    }

    /// A printed template with its markers as `kδ`, `(k−1)δ`, `(k+2)δ`.
    fn unmark(&self, text: &str) -> String {
        let paper = self.paper();
        let mut out = String::new();
        let mut rest = text;
        while let Some(at) = rest.find(MARK) {
            out.push_str(&rest[..at]);
            let tail = &rest[at + MARK.len()..];
            let end = tail.find("__").unwrap_or(tail.len());
            let offset: i64 = tail[..end].replace('m', "-").parse().unwrap_or(0);
            let (d, minus) = if paper { ("δ", "−") } else { ("*d", "-") };
            out.push_str(&match offset {
                0 => format!("k{d}"),
                o if o < 0 => format!("(k{minus}{}){d}", -o),
                o => format!("(k+{o}){d}"),
            });
            rest = &tail[(end + 2).min(tail.len())..];
        }
        out.push_str(rest);
        out
    }
}

/// The prefix of the names that mark a delay `kδ + c` in a template.
const MARK: &str = "__k";

/// `__k0__`, `__km1__`, `__k2__`; `None`: any delay (a shape's key).
fn marker_expr(offset: Option<&BigInt>) -> Expr {
    let text = match offset {
        Some(o) => o.to_string().replace('-', "m"),
        None => "any".into(),
    };
    crate::term::name(&format!("{MARK}{text}__"))
}

/// The delays of `e`, in the order [`map_delays`] visits them.
fn delays_of(e: &Expr) -> Vec<BigRational> {
    let mut out = Vec::new();
    map_delays(e, &mut |d| {
        out.push(d.seconds().clone());
        None
    });
    out
}

/// `e` with its delay nodes replaced where `f` says, visited left to right.
fn map_delays(e: &Expr, f: &mut dyn FnMut(&Delay) -> Option<Expr>) -> Expr {
    map_tree(e, &mut |x, id| match &x[id] {
        Term::Delay(d) => f(d),
        _ => None,
    })
}

/// `e` rebuilt as a tree, each subterm `f` replaces (tried from the root down) replaced.
fn map_tree(e: &Expr, f: &mut dyn FnMut(&Expr, Id) -> Option<Expr>) -> Expr {
    fn go(e: &Expr, id: Id, f: &mut dyn FnMut(&Expr, Id) -> Option<Expr>, out: &mut Expr) -> Id {
        if let Some(r) = f(e, id) {
            return copy_into(&r, root(&r), out);
        }
        let mut node = e[id].clone();
        for c in node.children_mut() {
            *c = go(e, *c, f, out);
        }
        out.add(node)
    }
    if e.as_ref().is_empty() {
        return e.clone();
    }
    let mut out = Expr::default();
    go(e, root(e), f, &mut out);
    out
}

/// The operands of a left-nested product.
fn spine(e: &Expr, id: Id, out: &mut Vec<Id>) {
    match &e[id] {
        Term::And([a, b]) => {
            spine(e, *a, out);
            out.push(*b);
        }
        _ => out.push(id),
    }
}

/// `d/f` or `f/d` at the root (under `pre`s): its delay and input.
fn timer_parts(e: &Expr) -> Option<(Delay, Expr)> {
    let mut id = root(e);
    while let Term::Pre(x) = &e[id] {
        id = *x;
    }
    let (d, f) = match &e[id] {
        Term::Ton([d, f]) | Term::Tof([f, d]) => (*d, *f),
        _ => return None,
    };
    let Term::Delay(d) = &e[d] else { return None };
    Some((d.clone(), subterm(e, f)))
}

/// The last term of a proof by one chain.
fn end_of(proof: &Proof) -> Option<&Expr> {
    match proof {
        Proof::Chain { start, steps } => Some(steps.last().map_or(start, |s| &s.after)),
        _ => None,
    }
}

/// Whether a proof splits cases (an induction counts as one).
fn has_cases(p: &Proof) -> bool {
    matches!(p, Proof::CaseSplit { .. } | Proof::Induction { .. })
        || parts(p).into_iter().any(has_cases)
}

fn has_refutation(p: &Proof) -> bool {
    matches!(p, Proof::Refutation { .. }) || parts(p).into_iter().any(has_refutation)
}

/// How proofs go, in a word: a refutation (clauses checked by unit propagation) if one
/// of them has one, else by cases if one splits, else by rewriting.
fn method(proofs: &[&Proof]) -> &'static str {
    if proofs.iter().any(|p| has_refutation(p)) {
        "by refutation"
    } else if proofs.iter().any(|p| has_cases(p)) {
        "by cases"
    } else {
        "by rewriting"
    }
}

/// What a proof cites, in order, without repeats or bookkeeping; a cited lemma that
/// `inner` opens is read through (its own citations instead of its name).
fn cited<'p>(proof: &'p Proof, inner: &dyn Fn(&str) -> Option<&'p Proof>) -> Vec<String> {
    fn walk<'p>(p: &'p Proof, inner: &dyn Fn(&str) -> Option<&'p Proof>, out: &mut Vec<String>) {
        let Proof::Chain { steps, .. } = p else {
            parts(p).into_iter().for_each(|q| walk(q, inner, out));
            return;
        };
        for s in steps {
            if let Rule::Cite(Source::Lemma, name, _) = &s.rule
                && let Some(q) = inner(name)
            {
                walk(q, inner, out);
                continue;
            }
            let label = rule_label(&s.rule);
            if !is_bookkeeping(&s.rule) && !out.contains(&label) {
                out.push(label);
            }
            s.premises.iter().for_each(|q| walk(q, inner, out));
        }
    }
    let mut out = Vec::new();
    walk(proof, inner, &mut out);
    out
}

/// One line: the printer's breaks as single spaces.
fn flat(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// The greatest common divisor of two positive rationals.
fn gcd(a: &BigRational, b: &BigRational) -> BigRational {
    let (p, q) = (a.numer() * b.denom(), b.numer() * a.denom());
    BigRational::new(p.gcd(&q), a.denom() * b.denom())
}
