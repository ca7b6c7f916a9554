//! Propositional refutation for the kernel (trusted): statements over signals as clauses, and a check that a list of clauses, each implied by unit propagation, ends in the empty clause.
//!
//! Every operator of the algebra other than `0*`, `1*`, `¬`, `·` and `+` is opaque: a
//! subterm headed by a name, `pre`, a timer or a memory is an *atom*, one variable per
//! distinct tree. `¬`, `·` and `+` act on the values of signals at each instant, so if a
//! term `g` were 1 at some instant where every fact `l = r` (or `l ⇒ r`) holds, the values
//! of the atoms there, and of every subterm, would satisfy the clauses [`Cnf`] writes
//! (the goal's variable true, each subterm's variable equal to its operator applied to its
//! children's, each fact's sides equal or ordered). A clause that unit propagation derives
//! from clauses satisfied by an assignment is satisfied by it (reverse unit propagation),
//! so deriving the empty clause shows that no such instant exists: `g = 0*` wherever the
//! facts hold.
//!
//! Literals are non-zero `i32` as in DIMACS: `v` is variable `v` true, `-v` false.

use std::collections::HashMap;

use crate::term::{Expr, Id, Term, root, subterm};

/// A clause: a disjunction of literals.
pub type Clause = Vec<i32>;

/// Clauses over the variables of the terms added so far.
#[derive(Default, Debug)]
pub struct Cnf {
    /// The clauses, in the order they were written.
    pub clauses: Vec<Clause>,
    /// Variables of atoms, by their tree.
    atoms: HashMap<Expr, i32>,
    /// Variables of `·` and `+` nodes, by operator and the literals of their children.
    gates: HashMap<(bool, i32, i32), i32>,
    vars: i32,
}

impl Cnf {
    /// The clauses saying that `goal` is 1.
    pub fn with_goal(goal: &Expr) -> Cnf {
        let mut cnf = Cnf::default();
        let g = cnf.literal(goal, root(goal));
        cnf.clauses.push(vec![g]);
        cnf
    }

    /// The number of variables used so far.
    pub fn vars(&self) -> i32 {
        self.vars
    }

    /// Adds the clauses of a fact `lhs = rhs` (`equal`) or `lhs ⇒ rhs`.
    pub fn fact(&mut self, lhs: &Expr, equal: bool, rhs: &Expr) {
        let l = self.literal(lhs, root(lhs));
        let r = self.literal(rhs, root(rhs));
        self.clauses.push(vec![-l, r]);
        if equal {
            self.clauses.push(vec![l, -r]);
        }
    }

    /// The literal whose value is that of the subterm at `id`, with the clauses defining it.
    fn literal(&mut self, e: &Expr, id: Id) -> i32 {
        match &e[id] {
            Term::One => self.truth(),
            Term::Zero => -self.truth(),
            Term::Not(a) => -self.literal(e, *a),
            Term::And([a, b]) => {
                let (x, y) = (self.literal(e, *a), self.literal(e, *b));
                self.gate(true, x, y)
            }
            Term::Or([a, b]) => {
                let (x, y) = (self.literal(e, *a), self.literal(e, *b));
                self.gate(false, x, y)
            }
            _ => {
                let tree = subterm(e, id);
                if let Some(&v) = self.atoms.get(&tree) {
                    return v;
                }
                let v = self.fresh();
                self.atoms.insert(tree, v);
                v
            }
        }
    }

    /// A variable that is always true (the value of `1*`).
    fn truth(&mut self) -> i32 {
        let key = (true, 0, 0);
        if let Some(&v) = self.gates.get(&key) {
            return v;
        }
        let v = self.fresh();
        self.gates.insert(key, v);
        self.clauses.push(vec![v]);
        v
    }

    /// `v ↔ x·y` (`and`) or `v ↔ x+y`.
    fn gate(&mut self, and: bool, x: i32, y: i32) -> i32 {
        if let Some(&v) = self.gates.get(&(and, x, y)) {
            return v;
        }
        let v = self.fresh();
        self.gates.insert((and, x, y), v);
        // An `or` is the `and` of the negations, negated: v ↔ x+y is ¬v ↔ ¬x·¬y.
        let (o, a, b) = if and { (v, x, y) } else { (-v, -x, -y) };
        self.clauses.push(vec![-o, a]);
        self.clauses.push(vec![-o, b]);
        self.clauses.push(vec![o, -a, -b]);
        v
    }

    fn fresh(&mut self) -> i32 {
        self.vars += 1;
        self.vars
    }

    /// Checks `lemmas` in order, each implied by unit propagation from the clauses and the
    /// lemmas before it, then that the empty clause is: `Ok` when it is, else which
    /// lemma failed.
    pub fn refuted_by(&self, lemmas: &[Clause]) -> Result<(), String> {
        let mut db = Propagator::new(self.vars);
        for c in &self.clauses {
            db.add(c)?;
        }
        for (i, lemma) in lemmas.iter().enumerate() {
            if !db.implies(lemma)? {
                return Err(format!(
                    "lemma {} of the refutation is not implied by unit propagation",
                    i + 1
                ));
            }
            db.add(lemma)?;
        }
        if db.implies(&[])? {
            Ok(())
        } else {
            Err("the refutation does not reach the empty clause".into())
        }
    }
}

/// Clauses with two watched literals each, and unit propagation over them.
struct Propagator {
    clauses: Vec<Clause>,
    /// The clauses watching each literal, by [`Propagator::index`].
    watches: Vec<Vec<usize>>,
    /// Clauses of one literal.
    units: Vec<i32>,
    /// The empty clause was added.
    empty: bool,
    /// Per variable: 1 true, -1 false, 0 unassigned.
    value: Vec<i8>,
}

impl Propagator {
    fn new(vars: i32) -> Propagator {
        let n = vars as usize + 1;
        Propagator {
            clauses: Vec::new(),
            watches: vec![Vec::new(); 2 * n],
            units: Vec::new(),
            empty: false,
            value: vec![0; n],
        }
    }

    fn var(&self, lit: i32) -> Result<usize, String> {
        let v = lit.unsigned_abs() as usize;
        if lit == 0 || v >= self.value.len() {
            return Err(format!("literal {lit} names no variable of the clauses"));
        }
        Ok(v)
    }

    fn index(lit: i32) -> usize {
        2 * lit.unsigned_abs() as usize + usize::from(lit < 0)
    }

    /// 1 when `lit` is true, -1 when false, 0 when unassigned.
    fn eval(&self, lit: i32) -> i8 {
        let v = self.value[lit.unsigned_abs() as usize];
        if lit < 0 { -v } else { v }
    }

    fn add(&mut self, clause: &[i32]) -> Result<(), String> {
        for &l in clause {
            self.var(l)?;
        }
        match clause {
            [] => self.empty = true,
            [l] => self.units.push(*l),
            [a, b, ..] => {
                let i = self.clauses.len();
                self.watches[Self::index(*a)].push(i);
                self.watches[Self::index(*b)].push(i);
                self.clauses.push(clause.to_vec());
            }
        }
        Ok(())
    }

    /// Does unit propagation from the negation of `clause` reach a conflict? The
    /// assignment is undone afterwards.
    fn implies(&mut self, clause: &[i32]) -> Result<bool, String> {
        if self.empty {
            return Ok(true);
        }
        let mut trail: Vec<i32> = Vec::new();
        let assumed: Vec<i32> = clause.iter().map(|&l| -l).collect();
        let conflict = 'run: {
            for &l in self.units.clone().iter().chain(&assumed) {
                self.var(l)?;
                match self.eval(l) {
                    1 => {}
                    -1 => break 'run true,
                    _ => {
                        self.value[l.unsigned_abs() as usize] = if l > 0 { 1 } else { -1 };
                        trail.push(l);
                    }
                }
            }
            let mut next = 0;
            while next < trail.len() {
                let falsified = -trail[next];
                next += 1;
                if self.propagate(falsified, &mut trail) {
                    break 'run true;
                }
            }
            false
        };
        for l in trail {
            self.value[l.unsigned_abs() as usize] = 0;
        }
        Ok(conflict)
    }

    /// Visits the clauses watching `falsified` (a literal just made false): each finds
    /// another watch, or its other watch is implied (pushed on `trail`), or it is a
    /// conflict (`true`).
    fn propagate(&mut self, falsified: i32, trail: &mut Vec<i32>) -> bool {
        let watching = std::mem::take(&mut self.watches[Self::index(falsified)]);
        let mut kept = Vec::with_capacity(watching.len());
        let mut conflict = false;
        for (k, &ci) in watching.iter().enumerate() {
            if conflict {
                kept.extend_from_slice(&watching[k..]);
                break;
            }
            let clause = &mut self.clauses[ci];
            if clause[0] == falsified {
                clause.swap(0, 1);
            }
            // Now clause[1] is the falsified watch; clause[0] the other.
            let other = clause[0];
            let replacement = (2..clause.len()).find(|&j| {
                let l = clause[j];
                let v = self.value[l.unsigned_abs() as usize];
                (if l < 0 { -v } else { v }) != -1
            });
            if let Some(j) = replacement {
                clause.swap(1, j);
                let new = clause[1];
                self.watches[Self::index(new)].push(ci);
                continue;
            }
            kept.push(ci);
            match self.eval(other) {
                1 => {}
                -1 => conflict = true,
                _ => {
                    self.value[other.unsigned_abs() as usize] = if other > 0 { 1 } else { -1 };
                    trail.push(other);
                }
            }
        }
        let slot = &mut self.watches[Self::index(falsified)];
        kept.append(slot);
        *slot = kept;
        conflict
    }
}
