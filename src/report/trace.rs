//! Checked proofs printed as calculations, one line per step, each naming its laws.
//!
//! A line of the calculation is a group of kernel steps: the prover's own
//! grouping for saturation proofs (one line per subterm brought to its
//! simplest form), and for case-split proofs the case assumptions and
//! constant evaluation folded into the next citation. Every atomic step was
//! checked by the kernel; the grouping is presentation only.

mod fold;

use crate::kernel::{Proof, Rel, Rule, Source, Step};
use crate::prover::Proved;
use crate::syntax::{Notation, term_to_string};
use crate::term::{Expr, Language};

/// How to print terms: notation and display names.
pub struct Style<'a> {
    /// Paper (`·`, `¬`, `⇒`) or ASCII.
    pub notation: Notation,
    /// Renames signals for display (e.g. `YL1_pump` → `L1_pump`).
    pub rename: &'a dyn Fn(&Expr) -> Expr,
}

impl Style<'_> {
    fn term(&self, e: &Expr) -> String {
        term_to_string(&(self.rename)(e), self.notation)
    }
    fn implies(&self) -> &'static str {
        match self.notation {
            Notation::Paper => "⇒",
            Notation::Ascii => "=>",
        }
    }
}

/// One printed line: relation, term, and the rules of its steps.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize)]
pub struct Line {
    /// `=` or `⇒` (in the chosen notation).
    pub relation: String,
    /// The term after the line's steps.
    pub term: String,
    /// The laws, hypotheses and lemmas cited, in order, without repeats.
    pub rules: Vec<String>,
}

/// The name a step cites, as printed.
pub fn rule_label(rule: &Rule) -> String {
    match rule {
        Rule::Cite(_, name, _) => name.clone(),
        Rule::Case(..) => "case".into(),
        Rule::DelayArith => "delay arithmetic".into(),
    }
}

/// The kind of a cited rule, for the JSON schema.
pub fn rule_kind(rule: &Rule) -> &'static str {
    match rule {
        Rule::Cite(Source::Law, ..) => "law",
        Rule::Cite(Source::Hypothesis, ..) => "hypothesis",
        Rule::Cite(Source::Lemma, ..) => "lemma",
        Rule::Case(..) => "case",
        Rule::DelayArith => "delay-arithmetic",
    }
}

/// Groups steps into lines of given sizes (`sizes` empty: fold bookkeeping steps —
/// case assumptions, delay arithmetic — into the next citation).
fn group<'s>(steps: &'s [Step], sizes: &[usize]) -> Vec<&'s [Step]> {
    let mut groups = Vec::new();
    if !sizes.is_empty() && sizes.iter().sum::<usize>() == steps.len() {
        let mut at = 0;
        for &n in sizes {
            groups.push(&steps[at..at + n]);
            at += n;
        }
        return groups;
    }
    let mut start = 0;
    for (i, step) in steps.iter().enumerate() {
        if !is_bookkeeping(&step.rule) || i + 1 == steps.len() {
            groups.push(&steps[start..=i]);
            start = i + 1;
        }
    }
    groups
}

/// Steps that only bookkeep — case assumptions, delay arithmetic, the constant laws
/// the case splitter evaluates with — are folded into the next line.
fn is_bookkeeping(rule: &Rule) -> bool {
    matches!(rule, Rule::Case(..) | Rule::DelayArith)
        || matches!(rule, Rule::Cite(Source::Law, name, _) if crate::prover::boolean::CONSTANT_LAWS.contains(&name.as_str()))
}

fn lines_of(steps: &[Step], sizes: &[usize], style: &Style) -> Vec<Line> {
    group(steps, sizes)
        .into_iter()
        .map(|g| {
            let mut rules: Vec<String> = Vec::new();
            for s in g {
                let label = rule_label(&s.rule);
                if !rules.contains(&label) {
                    rules.push(label);
                }
            }
            Line { relation: "=".into(), term: style.term(&g[g.len() - 1].after), rules }
        })
        .collect()
}

fn chain_text(
    start: &Expr,
    steps: &[Step],
    sizes: &[usize],
    style: &Style,
    indent: &str,
    out: &mut Vec<String>,
) {
    out.push(format!("{indent}  {}", style.term(start)));
    let lines = lines_of(steps, sizes, style);
    let width = lines.iter().map(|l| l.term.chars().count()).max().unwrap_or(0);
    for line in lines {
        let pad = width.saturating_sub(line.term.chars().count());
        out.push(format!(
            "{indent}{} {}{}   [{}]",
            line.relation,
            line.term,
            " ".repeat(pad),
            line.rules.join(", ")
        ));
    }
}

fn proof_text(proof: &Proof, sizes: &[usize], style: &Style, indent: &str, out: &mut Vec<String>) {
    match proof {
        Proof::Chain { start, steps } => chain_text(start, steps, sizes, style, indent, out),
        Proof::CaseSplit { .. } => {
            if let Some(start) = start_of(proof) {
                out.push(format!("{indent}  {} = 0*, by cases:", style.term(start)));
            }
            cases_text(proof, style, indent, out);
        }
        Proof::Symm(p) => {
            proof_text(p, sizes, style, indent, out);
            out.push(format!("{indent}hence the converse   [symmetry]"));
        }
        Proof::Antisym(p, q) => {
            proof_text(p, sizes, style, indent, out);
            proof_text(q, sizes, style, indent, out);
            out.push(format!("{indent}both ways, hence equal   [antisymmetry]"));
        }
        Proof::Trans(p, q) => {
            proof_text(p, sizes, style, indent, out);
            out.push(format!("{indent}and then"));
            proof_text(q, &[], style, indent, out);
        }
        Proof::ImpliesByMeet(p) | Proof::ImpliesByZero(p) => {
            proof_text(p, sizes, style, indent, out);
        }
        Proof::Refutation { goal, facts, lemmas } => {
            let mut cited: Vec<String> = Vec::new();
            for s in facts.iter().flat_map(|f| match f {
                Proof::Chain { steps, .. } => steps.as_slice(),
                _ => &[],
            }) {
                let label = rule_label(&s.rule);
                if matches!(s.rule, Rule::Cite(..)) && !cited.contains(&label) {
                    cited.push(label);
                }
            }
            const SHOWN: usize = 6;
            let more = cited.len().saturating_sub(SHOWN);
            cited.truncate(SHOWN);
            if more > 0 {
                cited.push(format!("{more} more"));
            }
            out.push(format!("{indent}  {}", style.term(goal)));
            out.push(format!(
                "{indent}= 0*   [refuted with {}: {} clauses derived by unit propagation]",
                cited.join(", "),
                lemmas.len()
            ));
        }
        Proof::Induction { inv, base, step } => {
            let inv = style.term(inv);
            out.push(format!("{indent}{inv} = 1*, by induction over scans:"));
            out.push(format!("{indent}first scan (every previous value 0):"));
            proof_text(base, &[], style, &format!("{indent}  "), out);
            out.push(format!("{indent}step, from the previous scan:"));
            let inner = format!("{indent}  ");
            match &**step {
                // `pre` pushed down to the state bits: one line.
                Proof::Trans(chain, rest) if matches!(&**chain, Proof::Chain { .. }) => {
                    if let Proof::Chain { start, steps } = &**chain {
                        let mut rules: Vec<String> = Vec::new();
                        for s in steps {
                            let label = rule_label(&s.rule);
                            if !rules.contains(&label) {
                                rules.push(label);
                            }
                        }
                        out.push(format!("{inner}  {}", style.term(start)));
                        if let Some(last) = steps.last() {
                            let after = style.term(&last.after);
                            out.push(format!("{inner}= {after}   [{}]", rules.join(", ")));
                        }
                    }
                    out.push(format!("{inner}and then"));
                    proof_text(rest, &[], style, &inner, out);
                }
                _ => proof_text(step, &[], style, &inner, out),
            }
        }
    }
}

/// The first term of a proof.
fn start_of(proof: &Proof) -> Option<&Expr> {
    match proof {
        Proof::Chain { start, .. } => Some(start),
        Proof::CaseSplit { one, .. } => start_of(one),
        Proof::Symm(p) | Proof::ImpliesByMeet(p) | Proof::ImpliesByZero(p) | Proof::Trans(p, _) => {
            start_of(p)
        }
        Proof::Antisym(p, _) => start_of(p),
        Proof::Induction { inv, .. } => Some(inv),
        Proof::Refutation { goal, .. } => Some(goal),
    }
}

/// Whether a `pre` lies on the way from the root of `e` down `path`.
fn under_pre(e: &Expr, path: &[usize]) -> bool {
    let mut id = crate::term::root(e);
    for &i in path {
        if matches!(e[id], crate::term::Term::Pre(_)) {
            return true;
        }
        match e[id].children().get(i) {
            Some(c) => id = *c,
            None => return false,
        }
    }
    false
}

/// What closes a one-line case: the statements it cites, or the goal itself.
fn closing(leaf: &Proof) -> String {
    let Proof::Chain { steps, .. } = leaf else { return String::new() };
    let mut rules: Vec<String> = Vec::new();
    for s in steps {
        let mut label = rule_label(&s.rule);
        // A hypothesis cited under `pre` is what it said at the previous scan.
        let earlier = matches!(s.rule, Rule::Cite(Source::Hypothesis | Source::Lemma, ..))
            && under_pre(&s.after, &s.path);
        if earlier {
            label.push_str(" at the previous scan");
        }
        if !is_bookkeeping(&s.rule) && !rules.contains(&label) {
            rules.push(label);
        }
    }
    if rules.is_empty() { "the goal".into() } else { rules.join(", ") }
}

/// A case split as the paper reads it: a case that closes at once becomes a fact
/// (`L1_Prod = 0*  [H9]`: the other value contradicts H9), consecutive facts with
/// the same reason share a line, and only real splits nest.
fn cases_text(proof: &Proof, style: &Style, indent: &str, out: &mut Vec<String>) {
    let mut facts: Vec<(String, String)> = Vec::new();
    let mut node = proof;
    let flush = |facts: &mut Vec<(String, String)>, out: &mut Vec<String>| {
        let mut merged: Vec<(Vec<String>, String)> = Vec::new();
        for (fact, reason) in facts.drain(..) {
            match merged.last_mut() {
                Some((list, r)) if *r == reason => list.push(fact),
                _ => merged.push((vec![fact], reason)),
            }
        }
        for (list, reason) in merged {
            out.push(format!("{indent}{}   [{reason}]", list.join(", ")));
        }
    };
    loop {
        let Proof::CaseSplit { atom, one, zero } = node else {
            flush(&mut facts, out);
            out.push(format!("{indent}hence 0*   [{}]", closing(node)));
            return;
        };
        let a = style.term(atom);
        let leaf = |p: &Proof| matches!(p, Proof::Chain { .. });
        match (leaf(one), leaf(zero)) {
            (true, true) => {
                flush(&mut facts, out);
                out.push(format!(
                    "{indent}{a} = 1* contradicts {}; {a} = 0* contradicts {}",
                    closing(one),
                    closing(zero)
                ));
                return;
            }
            (true, false) => {
                facts.push((format!("{a} = 0*"), closing(one)));
                node = zero;
            }
            (false, true) => {
                facts.push((format!("{a} = 1*"), closing(zero)));
                node = one;
            }
            (false, false) => {
                flush(&mut facts, out);
                out.push(format!("{indent}case {a} = 1*:"));
                cases_text(one, style, &format!("{indent}  "), out);
                out.push(format!("{indent}case {a} = 0*:"));
                cases_text(zero, style, &format!("{indent}  "), out);
                return;
            }
        }
    }
}

/// How much of a proof's lemmas a trace prints.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Detail {
    /// An induction's timer chains, step lemmas and invariant folded (`fold`).
    #[default]
    Folded,
    /// Every lemma in full.
    Full,
}

/// The calculation of a checked proof of a goal with relation `goal`, as text lines
/// (without the goal line; a line may hold a term broken over several). An
/// implication proved by an equation ends with the implication it gives.
pub fn render(proved: &Proved, goal: Rel, style: &Style, detail: Detail) -> Vec<String> {
    let mut out = match detail {
        Detail::Folded => fold::lemmas(proved, style),
        Detail::Full => Vec::new(),
    };
    if detail == Detail::Full {
        for (name, lemma) in &proved.certificate.lemmas {
            out.push(format!("lemma {name}:"));
            proof_text(lemma, &[], style, "    ", &mut out);
        }
    }
    // A shared lemma is cited by its statement, as the reader's names print it.
    let statement = |t: &crate::kernel::Theorem| {
        format!("{} {} {}", style.term(t.lhs()), style.implies(), style.term(t.rhs()))
    };
    let mut main = proved.certificate.main.clone();
    if let Some(main) = main.as_mut().filter(|_| !proved.shared.is_empty()) {
        main.for_each_step_mut(&mut |s| {
            if let Rule::Cite(Source::Lemma, name, _) = &mut s.rule
                && let Some(t) = proved.shared.get(name.as_str())
            {
                *name = statement(t);
            }
        });
    }
    if let Some(main) = &main {
        proof_text(main, &proved.lines, style, "    ", &mut out);
        let theorem = &proved.theorem;
        let closing = match main {
            Proof::ImpliesByMeet(_) => Some("f·g = f"),
            Proof::ImpliesByZero(_) => Some("f·¬g = 0*"),
            _ if goal == Rel::Implies && theorem.rel() == Rel::Eq => Some("f = g"),
            _ => None,
        };
        if let Some(form) = closing {
            out.push(format!(
                "    hence {} {} {}   [{form}]",
                style.term(theorem.lhs()),
                style.implies(),
                style.term(theorem.rhs())
            ));
        }
    }
    // Each shared lemma in one line: what it rests on, folded.
    for t in proved.shared.values() {
        let hyps: Vec<String> = t.axioms_used().1.into_iter().collect();
        let shown = match hyps.len() {
            0..=4 => hyps.join(", "),
            n => format!("{}, {}, …, {} ({n} hypotheses)", hyps[0], hyps[1], hyps[n - 1]),
        };
        out.push(format!(
            "    where {}   [forced through {shown}; a lemma checked once for the program]",
            statement(t)
        ));
    }
    out
}

/// The number of printed calculation lines (the measure compared with the paper's proofs).
pub fn length(proved: &Proved) -> usize {
    fn count(p: &Proof, sizes: &[usize]) -> usize {
        match p {
            Proof::Chain { steps, .. } => group(steps, sizes).len(),
            Proof::CaseSplit { .. } => {
                let mut lines = Vec::new();
                let style = Style { notation: Notation::Ascii, rename: &|e: &Expr| e.clone() };
                cases_text(p, &style, "", &mut lines);
                lines.len() + 1
            }
            Proof::Symm(p) | Proof::ImpliesByMeet(p) | Proof::ImpliesByZero(p) => count(p, sizes),
            Proof::Antisym(p, q) | Proof::Trans(p, q) => count(p, sizes) + count(q, sizes),
            Proof::Induction { base, step, .. } => 3 + count(base, &[]) + count(step, &[]),
            Proof::Refutation { .. } => 2,
        }
    }
    proved.certificate.main.as_ref().map_or(0, |m| count(m, &proved.lines))
}

/// The proofs a proof is made of, in order (a chain's: its steps' premises).
fn parts(p: &Proof) -> Vec<&Proof> {
    match p {
        Proof::Chain { steps, .. } => steps.iter().flat_map(|s| &s.premises).collect(),
        Proof::CaseSplit { one: p, zero: q, .. }
        | Proof::Induction { base: p, step: q, .. }
        | Proof::Antisym(p, q)
        | Proof::Trans(p, q) => vec![p, q],
        Proof::Symm(p) | Proof::ImpliesByMeet(p) | Proof::ImpliesByZero(p) => vec![p],
        Proof::Refutation { facts, .. } => facts.iter().collect(),
    }
}

/// The atomic steps of the main chain, for the JSON output.
pub fn atomic_steps(proved: &Proved, style: &Style) -> Vec<(String, &'static str, String)> {
    fn walk(p: &Proof, style: &Style, out: &mut Vec<(String, &'static str, String)>) {
        match p {
            Proof::Chain { steps, .. } => out.extend(
                steps
                    .iter()
                    .map(|s| (rule_label(&s.rule), rule_kind(&s.rule), style.term(&s.after))),
            ),
            _ => parts(p).into_iter().for_each(|q| walk(q, style, out)),
        }
    }
    let mut out = Vec::new();
    for (_, lemma) in &proved.certificate.lemmas {
        walk(lemma, style, &mut out);
    }
    if let Some(main) = &proved.certificate.main {
        walk(main, style, &mut out);
    }
    out
}
