//! Turns egg's flat explanations into kernel certificates, and shortens chains.
//!
//! A flat explanation is a list of terms, each (after the first) carrying one
//! rewrite annotation at the rewritten position. Each becomes a kernel
//! [`Step`]: the path to the annotation, the rule named by the annotation,
//! and the whole term after it. The mapping from egg rule names to kernel
//! rules is the inverse of [`super::saturate::rule_name`].

use std::collections::HashMap;
use std::rc::Rc;

use egg::{FlatTerm, Symbol as EggSymbol, TreeTerm};

use crate::kernel::{Proof, Rule, Source, Step, Use};
use crate::term::{Expr, Term, same};

use super::saturate::{DELAY_ARITH, Graph};

/// Why an explanation could not be turned into a certificate.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ExplainError(pub String);

fn usage(tag: &str, backward: bool) -> Option<Use> {
    Some(match (tag, backward) {
        ("", false) | ("rev", true) => Use::Forward,
        ("", true) | ("rev", false) => Use::Backward,
        ("meet", false) | ("meetback", true) => Use::Meet,
        ("meet", true) | ("meetback", false) => Use::MeetBack,
        ("join", false) | ("joinback", true) => Use::Join,
        ("join", true) | ("joinback", false) => Use::JoinBack,
        ("contra", false) | ("contraback", true) => Use::Contra,
        ("contra", true) | ("contraback", false) => Use::ContraBack,
        _ => return None,
    })
}

/// The kernel rule for an egg rule name used forward (`backward == false`) or backward.
pub fn kernel_rule(name: &str, backward: bool) -> Result<Rule, ExplainError> {
    if name == DELAY_ARITH {
        return Ok(Rule::DelayArith);
    }
    let (source, rest) = match name.strip_prefix("hyp:") {
        Some(rest) => (Source::Hypothesis, rest),
        None => match name.strip_prefix("lemma:") {
            Some(rest) => (Source::Lemma, rest),
            None => (Source::Law, name),
        },
    };
    let (base, tag) = rest.split_once('~').unwrap_or((rest, ""));
    let how = usage(tag, backward)
        .ok_or_else(|| ExplainError(format!("unknown rule usage in `{name}`")))?;
    Ok(Rule::Cite(source, base.to_string(), how))
}

/// The path to the single rewrite annotation of a flat term, and its rule.
fn annotation(term: &FlatTerm<crate::term::Term>) -> Option<(Vec<usize>, EggSymbol, bool)> {
    if let Some(rule) = term.forward_rule {
        return Some((vec![], rule, false));
    }
    if let Some(rule) = term.backward_rule {
        return Some((vec![], rule, true));
    }
    term.children.iter().enumerate().find_map(|(i, child)| {
        let (mut path, rule, backward) = annotation(child)?;
        path.insert(0, i);
        Some((path, rule, backward))
    })
}

/// Explanations longer than this are not flattened (flattening can grow exponentially).
pub const MAX_STEPS: usize = 5_000;

/// An upper bound on the length of the flattened explanation, without flattening it
/// (shared sub-proofs counted once per use, memoised by pointer).
fn flat_length_bound(
    proof: &[Rc<TreeTerm<Term>>],
    memo: &mut HashMap<*const TreeTerm<Term>, usize>,
) -> usize {
    let mut total = 0usize;
    for tree in proof {
        let key = Rc::as_ptr(tree);
        let own = match memo.get(&key) {
            Some(n) => *n,
            None => {
                let mut n = 1usize;
                for child in &tree.child_proofs {
                    n = n.saturating_add(flat_length_bound(child, memo).saturating_sub(1));
                }
                memo.insert(key, n);
                n
            }
        };
        total = total.saturating_add(own);
        if total > MAX_STEPS * 4 {
            return total;
        }
    }
    total
}

/// A chain proof from an egg explanation of `a = b`.
pub fn chain_from_explanation(
    egraph: &mut Graph,
    a: &Expr,
    b: &Expr,
) -> Result<Proof, ExplainError> {
    Ok(Proof::Chain { start: a.clone(), steps: chain_steps(egraph, a, b)? })
}

/// The steps of egg's explanation of `a = b`, without loops.
pub fn chain_steps(egraph: &mut Graph, a: &Expr, b: &Expr) -> Result<Vec<Step>, ExplainError> {
    let mut explanation = egraph.explain_equivalence(a, b);
    let bound = flat_length_bound(&explanation.explanation_trees, &mut HashMap::new());
    if bound > MAX_STEPS {
        return Err(ExplainError(format!("the explanation would have over {MAX_STEPS} steps")));
    }
    let flat = explanation.make_flat_explanation();
    let first = flat.first().ok_or_else(|| ExplainError("an empty explanation".into()))?;
    let start = first.get_recexpr();
    let mut steps = Vec::with_capacity(flat.len());
    for term in &flat[1..] {
        let (path, rule, backward) = annotation(term)
            .ok_or_else(|| ExplainError("a step without a rewrite annotation".into()))?;
        steps.push(Step {
            path,
            rule: kernel_rule(rule.as_str(), backward)?,
            after: term.get_recexpr(),
            subst: Vec::new(),
            premises: Vec::new(),
        });
    }
    Ok(remove_loops(&start, steps))
}

/// Drops every detour that comes back to a term seen before (`t … t`).
pub fn remove_loops(start: &Expr, steps: Vec<Step>) -> Vec<Step> {
    let mut kept: Vec<Step> = Vec::with_capacity(steps.len());
    for step in steps {
        if same(&step.after, start) {
            kept.clear();
            continue;
        }
        if let Some(i) = kept.iter().position(|s| same(&s.after, &step.after)) {
            kept.truncate(i + 1);
            continue;
        }
        kept.push(step);
    }
    kept
}
