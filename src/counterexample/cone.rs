//! A property's cone: the program's equations that compute what it reads, through any chain, and the `assume` statements about them; whole, or cut after a number of equations taken breadth first.

use std::collections::VecDeque;

use super::Program;
use super::unroll::Model;
use crate::program::fast_hash::{FastMap as HashMap, FastSet as HashSet};
use crate::term::{Expr, Symbol, Term};

impl Program<'_> {
    /// The cone of `terms` and of every assumption: equations in scan order and all the
    /// assumptions. A run that violates a property counts only if it satisfies every
    /// `assume` up to that scan, also one about signals the property does not read (it
    /// may contradict the program, or fix an input the run would otherwise leave free).
    pub fn model(&self, terms: &[&Expr]) -> Model {
        let mut all = terms.to_vec();
        all.extend(self.assumptions.iter().flat_map(|a| [&a.lhs, &a.rhs]));
        self.cone(&all, usize::MAX)
    }

    /// [`model`](Self::model) cut after `cap` equations: the names are expanded breadth
    /// first from those `terms` read (all the equations of a name at once), and once
    /// `cap` equations are taken the names not yet expanded stay undefined, so the
    /// model leaves them free (any value at every step). Every run of the program is
    /// then a run of the cut model, whose runs may be more.
    pub fn cone(&self, terms: &[&Expr], cap: usize) -> Model {
        // The cone is a closure over names, walked once (a breadth-first worklist) with
        // the program's equation index (built once per program) and the assumptions
        // indexed here.
        let index = self.compiled.equation_index();
        let hypotheses = &self.compiled.hypotheses;
        // Names as symbols (no text copied); each name's newly found names are queued in
        // the order of their text, as a sorted set would give them.
        let names = |e: &Expr, into: &mut Vec<Symbol>| {
            into.extend(e.as_ref().iter().filter_map(|node| match node {
                Term::Name(n) => Some(*n),
                _ => None,
            }))
        };
        let mentioned: Vec<Vec<Symbol>> = self
            .assumptions
            .iter()
            .map(|a| {
                let mut m = Vec::new();
                names(&a.lhs, &mut m);
                names(&a.rhs, &mut m);
                m
            })
            .collect();
        let mut mentioning: HashMap<Symbol, Vec<usize>> = HashMap::default();
        for (i, m) in mentioned.iter().enumerate() {
            for n in m {
                mentioning.entry(*n).or_default().push(i);
            }
        }
        let mut first = Vec::new();
        for t in terms {
            names(t, &mut first);
        }
        first.sort_unstable_by(|a, b| a.as_str().cmp(b.as_str()));
        first.dedup();
        let mut reached: HashSet<Symbol> = first.iter().copied().collect();
        let mut pending: VecDeque<Symbol> = first.into_iter().collect();
        let mut taken_a = vec![false; self.assumptions.len()];
        let mut taken_defs = Vec::new();
        let mut found = Vec::new();
        while let Some(name) = pending.pop_front() {
            if taken_defs.len() >= cap {
                break;
            }
            found.clear();
            for &i in index.defining.get(name.as_str()).map_or(&[][..], Vec::as_slice) {
                taken_defs.push(i);
                names(&hypotheses[index.equations[i].1].rhs, &mut found);
            }
            for &i in mentioning.get(&name).map_or(&[][..], Vec::as_slice) {
                if !taken_a[i] {
                    taken_a[i] = true;
                    found.extend(mentioned[i].iter().copied());
                }
            }
            found.sort_unstable_by(|a, b| a.as_str().cmp(b.as_str()));
            found.dedup();
            for n in &found {
                if reached.insert(*n) {
                    pending.push_back(*n);
                }
            }
        }
        taken_defs.sort_unstable();
        Model {
            defs: taken_defs
                .into_iter()
                .map(|i| {
                    let (n, h) = &index.equations[i];
                    (n.clone(), hypotheses[*h].rhs.clone())
                })
                .collect(),
            constraints: self
                .assumptions
                .iter()
                .zip(&taken_a)
                .filter(|(_, t)| **t)
                .map(|(a, _)| (a.lhs.clone(), a.rel, a.rhs.clone()))
                .collect(),
        }
    }
}
