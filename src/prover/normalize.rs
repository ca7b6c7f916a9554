//! Structured proofs from a saturated e-graph: rewrite each side to its simplest form.
//!
//! egg's explanation of `a = b` follows the e-graph's proof forest and often
//! takes detours. Here the proof is built bottom-up instead: every subterm is
//! first rewritten to the simplest term of its e-class (children first, then
//! a short explanation between two small terms at the node), so the chain
//! reads like a hand calculation: unfold, simplify, close.

use std::collections::HashMap;

use egg::{AstSize, Extractor};

use crate::kernel::{Rule, Step, Use};
use crate::term::{Expr, Id, Language, copy_into, root, same, subterm};

use super::explain::ExplainError;
use super::saturate::Graph;

/// The simplest term of every e-class reachable from the given terms.
fn best_terms(egraph: &Graph, terms: &[&Expr]) -> HashMap<Id, Expr> {
    let extractor = Extractor::new(egraph, AstSize);
    let mut best = HashMap::new();
    for term in terms {
        for id in 0..term.as_ref().len() {
            let sub = subterm(term, Id::from(id));
            if let Some(class) = egraph.lookup_expr(&sub) {
                best.entry(class).or_insert_with(|| extractor.find_best(class).1);
            }
        }
    }
    best
}

/// `whole` with the subterm at `path` replaced by `new`.
pub fn replace_at(whole: &Expr, path: &[usize], new: &Expr) -> Expr {
    fn go(e: &Expr, id: Id, path: &[usize], new: &Expr, out: &mut Expr) -> Id {
        match path.split_first() {
            None => copy_into(new, root(new), out),
            Some((&i, rest)) => {
                let mut k = 0;
                let node = e[id].clone().map_children(|c| {
                    let child =
                        if k == i { go(e, c, rest, new, out) } else { copy_into(e, c, out) };
                    k += 1;
                    child
                });
                out.add(node)
            }
        }
    }
    let mut out = Expr::default();
    go(whole, root(whole), path, new, &mut out);
    out
}

/// Steps on a subterm, lifted into the whole term at `prefix`.
fn lift(whole: &mut Expr, prefix: &[usize], steps: Vec<Step>, out: &mut Vec<Step>) {
    for step in steps {
        let mut path = prefix.to_vec();
        path.extend(&step.path);
        *whole = replace_at(whole, prefix, &step.after);
        out.push(Step { path, after: whole.clone(), ..step });
    }
}

/// Proves two small terms equal (a fresh search, so the explanation has no detours).
pub type Bridge<'a> = dyn FnMut(&Expr, &Expr) -> Result<Vec<Step>, ExplainError> + 'a;

/// Rewrites `term` to the simplest term of its class; returns the steps and that term.
fn normalize(
    egraph: &Graph,
    best: &HashMap<Id, Expr>,
    term: &Expr,
    bridge: &mut Bridge<'_>,
    lines: &mut Vec<usize>,
) -> Result<(Vec<Step>, Expr), ExplainError> {
    let mut current = term.clone();
    let mut steps = Vec::new();
    let top = root(term);
    for (i, child) in term[top].children().iter().enumerate() {
        let sub = subterm(term, *child);
        let (sub_steps, _) = normalize(egraph, best, &sub, bridge, lines)?;
        lift(&mut current, &[i], sub_steps, &mut steps);
    }
    let class = egraph
        .lookup_expr(term)
        .ok_or_else(|| ExplainError("a subterm is missing from the e-graph".into()))?;
    let target = best
        .get(&egraph.find(class))
        .or_else(|| best.get(&class))
        .cloned()
        .unwrap_or_else(|| current.clone());
    if !same(&current, &target) {
        let tail = bridge(&current, &target)?;
        if !tail.is_empty() {
            lines.push(tail.len());
        }
        lift(&mut current, &[], tail, &mut steps);
    }
    Ok((steps, current))
}

/// The same step read backwards (case and delay steps are their own reverse).
pub fn reversed(rule: &Rule) -> Rule {
    match rule {
        Rule::Cite(source, name, how) => {
            let back = match how {
                Use::Forward => Use::Backward,
                Use::Backward => Use::Forward,
                Use::Meet => Use::MeetBack,
                Use::MeetBack => Use::Meet,
                Use::Join => Use::JoinBack,
                Use::JoinBack => Use::Join,
                Use::Contra => Use::ContraBack,
                Use::ContraBack => Use::Contra,
            };
            Rule::Cite(*source, name.clone(), back)
        }
        other => other.clone(),
    }
}

/// A chain from `a` to `b` (equal in the e-graph): `a` down to its simplest form, then
/// up to `b`. Also returns how many steps make each line of the printed calculation
/// (one line per subterm brought to its simplest form).
pub fn chain_via_normal_form(
    egraph: &Graph,
    a: &Expr,
    b: &Expr,
    bridge: &mut Bridge<'_>,
) -> Result<(Vec<Step>, Vec<usize>), ExplainError> {
    let best = best_terms(egraph, &[a, b]);
    let mut lines = Vec::new();
    let (mut steps, na) = normalize(egraph, &best, a, bridge, &mut lines)?;
    let mut b_lines = Vec::new();
    let (b_steps, nb) = normalize(egraph, &best, b, bridge, &mut b_lines)?;
    if !same(&na, &nb) {
        let middle = bridge(&na, &nb)?;
        if !middle.is_empty() {
            lines.push(middle.len());
        }
        steps.extend(middle);
    }
    lines.extend(b_lines.iter().rev());
    // Walk b's normalisation backwards: each step's `after` becomes the term before it.
    let mut befores: Vec<Expr> = vec![b.clone()];
    befores.extend(b_steps.iter().map(|s| s.after.clone()));
    for (i, step) in b_steps.iter().enumerate().rev() {
        steps.push(Step { rule: reversed(&step.rule), after: befores[i].clone(), ..step.clone() });
    }
    Ok((steps, lines))
}
