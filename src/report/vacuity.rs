//! Which constants a property states itself: a signal the hypotheses force is a sign of a vacuous proof only when the property does not claim that value.
//!
//! `Out = 0*` ("this output is never energised") and `Out1 + Out2 = 0*` claim their
//! signals' values: that the program forces them is what was to be proved. In
//! `Ns_green · Ew_green = 0*` a forced `Ns_green = 0*` makes `Ew_green` irrelevant: the
//! property holds vacuously. The test is pointwise: the goal, with its signals and its
//! timer, memory and `pre` subterms read as free Boolean atoms, must imply the value.

use crate::kernel::Rel;
use crate::prover::Obligation;
use crate::term::{Expr, Term};

/// The most atoms a goal may have for the test (2^12 assignments).
const MAX_ATOMS: usize = 12;

/// Whether the goal, read pointwise, implies `name = value`. False when `name` is not
/// one of its atoms or it has too many atoms to tell.
pub(super) fn claimed(goal: &Obligation, name: &str, value: bool) -> bool {
    let mut atoms: Vec<Atom> = Vec::new();
    let lhs = Side::of(&goal.lhs, 0, &mut atoms);
    let rhs = Side::of(&goal.rhs, 1, &mut atoms);
    let Some(target) = atoms.iter().position(|a| *a == Atom::Name(name.to_string())) else {
        return false;
    };
    if atoms.len() > MAX_ATOMS {
        return false;
    }
    (0u32..1 << atoms.len()).all(|bits| {
        let (l, r) = (lhs.eval(bits), rhs.eval(bits));
        let holds = match goal.rel {
            Rel::Eq => l == r,
            Rel::Implies => !l || r,
        };
        !holds || (bits >> target & 1 == 1) == value
    })
}

/// A free Boolean atom of a goal: a signal, or a non-Boolean subterm (side, node).
#[derive(PartialEq)]
enum Atom {
    Name(String),
    Opaque(usize, usize),
}

/// One side of a goal: its nodes, each Boolean node or the index of its atom.
struct Side {
    nodes: Vec<Node>,
}

enum Node {
    Const(bool),
    Atom(usize),
    And(usize, usize),
    Or(usize, usize),
    Not(usize),
}

impl Side {
    /// The Boolean structure above the root's atoms; nodes only an atom reads (its
    /// delay, the signal under a timer) are not atoms of the goal.
    fn of(expr: &Expr, side: usize, atoms: &mut Vec<Atom>) -> Side {
        let terms = expr.as_ref();
        let mut boolean = vec![false; terms.len()];
        if let Some(last) = boolean.last_mut() {
            *last = true;
        }
        for i in (0..terms.len()).rev() {
            if boolean[i] {
                match &terms[i] {
                    Term::And([a, b]) | Term::Or([a, b]) => {
                        boolean[usize::from(*a)] = true;
                        boolean[usize::from(*b)] = true;
                    }
                    Term::Not(a) => boolean[usize::from(*a)] = true,
                    _ => {}
                }
            }
        }
        let mut atom = |a: Atom| match atoms.iter().position(|b| *b == a) {
            Some(i) => i,
            None => {
                atoms.push(a);
                atoms.len() - 1
            }
        };
        let nodes = terms
            .iter()
            .enumerate()
            .map(|(i, node)| match node {
                _ if !boolean[i] => Node::Const(false),
                Term::Zero => Node::Const(false),
                Term::One => Node::Const(true),
                Term::And([a, b]) => Node::And(usize::from(*a), usize::from(*b)),
                Term::Or([a, b]) => Node::Or(usize::from(*a), usize::from(*b)),
                Term::Not(a) => Node::Not(usize::from(*a)),
                Term::Name(n) => Node::Atom(atom(Atom::Name(n.to_string()))),
                _ => Node::Atom(atom(Atom::Opaque(side, i))),
            })
            .collect();
        Side { nodes }
    }

    /// The root's value when atom `i` is bit `i` of `bits`.
    fn eval(&self, bits: u32) -> bool {
        let mut values: Vec<bool> = Vec::with_capacity(self.nodes.len());
        for node in &self.nodes {
            let v = match *node {
                Node::Const(c) => c,
                Node::Atom(i) => bits >> i & 1 == 1,
                Node::And(a, b) => values[a] && values[b],
                Node::Or(a, b) => values[a] || values[b],
                Node::Not(a) => !values[a],
            };
            values.push(v);
        }
        values.last().copied().unwrap_or(false)
    }
}
