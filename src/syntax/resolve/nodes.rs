//! Terms under construction: nodes added in O(1), the metavariables a law uses, and
//! the limits on a resolved term's size and depth.

use crate::term::{Delay, Expr, Id, Language, Symbol, Term};

/// The most nodes one resolved term may have (abbreviations can double a term per line).
pub(super) const MAX_NODES: usize = 100_000;

/// The deepest a resolved term may be (keeps every recursive consumer's stack safe).
pub(super) const MAX_TERM_DEPTH: usize = 1_000;

/// The depth of the deepest node of a term (linear: children come before parents).
pub(super) fn depth(nodes: &[Term]) -> usize {
    let mut depths: Vec<usize> = Vec::with_capacity(nodes.len());
    for node in nodes {
        let below = node
            .children()
            .iter()
            .map(|&c| depths.get(usize::from(c)).copied().unwrap_or(0))
            .max()
            .unwrap_or(0);
        depths.push(below + 1);
    }
    depths.into_iter().max().unwrap_or(0)
}

/// Nodes of a term under construction.
///
/// Like [`crate::term::Builder`], but adding a node is O(1): egg's
/// `RecExpr::add` finds its root by walking every id, which makes long
/// sums quadratic.
#[derive(Default)]
pub(super) struct Nodes {
    pub(super) nodes: Vec<Term>,
}

impl Nodes {
    pub(super) fn add(&mut self, node: Term) -> Id {
        self.nodes.push(node);
        Id::from(self.nodes.len() - 1)
    }

    pub(super) fn name(&mut self, name: &str) -> Id {
        self.add(Term::Name(Symbol::from(name)))
    }

    pub(super) fn delay(&mut self, d: Delay) -> Id {
        self.add(Term::Delay(d))
    }

    pub(super) fn zero(&mut self) -> Id {
        self.add(Term::Zero)
    }

    pub(super) fn one(&mut self) -> Id {
        self.add(Term::One)
    }

    pub(super) fn not(&mut self, a: Id) -> Id {
        self.add(Term::Not(a))
    }

    pub(super) fn pre(&mut self, a: Id) -> Id {
        self.add(Term::Pre(a))
    }

    pub(super) fn ton(&mut self, d: Id, f: Id) -> Id {
        self.add(Term::Ton([d, f]))
    }

    pub(super) fn tof(&mut self, f: Id, d: Id) -> Id {
        self.add(Term::Tof([f, d]))
    }

    pub(super) fn sr(&mut self, s: Id, r: Id) -> Id {
        self.add(Term::Sr([s, r]))
    }

    pub(super) fn rs(&mut self, s: Id, r: Id) -> Id {
        self.add(Term::Rs([s, r]))
    }

    /// Copies a whole (compact, root-last) term in; returns the id of its root.
    pub(super) fn term(&mut self, expr: &Expr) -> Id {
        let base = self.nodes.len();
        for node in expr.as_ref() {
            let node = node.clone().map_children(|c| Id::from(usize::from(c) + base));
            self.nodes.push(node);
        }
        Id::from(self.nodes.len().saturating_sub(1))
    }

    /// The term rooted at `root`, without unreachable nodes, root last.
    pub(super) fn finish(&self, root: Id) -> Expr {
        let root = usize::from(root);
        let mut keep = vec![false; root + 1];
        keep[root] = true;
        for i in (0..=root).rev() {
            if keep[i] {
                for &c in self.nodes[i].children() {
                    keep[usize::from(c)] = true;
                }
            }
        }
        let mut new_id = vec![0usize; root + 1];
        let mut out = Vec::with_capacity(keep.iter().filter(|k| **k).count());
        for i in 0..=root {
            if keep[i] {
                new_id[i] = out.len();
                let node = self.nodes[i].clone().map_children(|c| Id::from(new_id[usize::from(c)]));
                out.push(node);
            }
        }
        Expr::from(out)
    }
}

/// One term under construction and the metavariables it uses.
#[derive(Default)]
pub(super) struct Out {
    pub(super) b: Nodes,
    pub(super) signal_vars: Vec<Symbol>,
    pub(super) delay_vars: Vec<Symbol>,
}

impl Out {
    pub(super) fn finish(self, root: Id) -> Expr {
        self.b.finish(root)
    }
}

pub(super) fn push_unique(list: &mut Vec<Symbol>, s: Symbol) {
    if !list.contains(&s) {
        list.push(s);
    }
}
