//! Random falsification: look for exact signals under which a statement fails.
//!
//! Used to validate every law of `theories/` and to find witnesses for false
//! goals about free signals. A [`Witness`] is always re-checked by exact
//! evaluation before it is returned.

use std::collections::BTreeSet;

use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

use super::eval::{Assignment, eval, free_names};
use super::signal::{Signal, Time};
use crate::term::{Delay, Expr, Symbol, Term, root};

/// How two sides are compared.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Relation {
    /// Equal at every instant.
    Equal,
    /// Wherever the left side is 1, so is the right side.
    Implies,
}

/// A side condition on a sample.
#[derive(Clone, Debug)]
pub enum Condition {
    /// A comparison of two delay expressions: `lhs ≥ rhs` etc. (`ordering` lists the accepted results).
    Delay {
        /// Left.
        lhs: Expr,
        /// Accepted orderings of `lhs` against `rhs`.
        accept: Vec<std::cmp::Ordering>,
        /// Right.
        rhs: Expr,
    },
    /// A relation between signals that must hold on the sample.
    Signal {
        /// Left.
        lhs: Expr,
        /// `=` or `⇒`.
        rel: Relation,
        /// Right.
        rhs: Expr,
    },
}

/// Exact signals (and delays) under which a statement fails, and where.
#[derive(Clone, Debug)]
pub struct Witness {
    /// The signals and delays.
    pub assignment: Assignment,
    /// An instant where the two sides violate the relation.
    pub time: Time,
    /// The left side's value there.
    pub lhs: bool,
    /// The right side's value there.
    pub rhs: bool,
}

/// Why a statement could not be sampled.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SampleError {
    /// The statement does not evaluate (e.g. a delay where a signal is expected).
    Eval(String),
    /// Too few samples satisfied the side conditions.
    TooFewSamples {
        /// Samples that satisfied them.
        valid: usize,
        /// Samples wanted.
        wanted: usize,
    },
}

/// Where `lhs rel rhs` fails on the sample, if it does.
pub fn violation(lhs: &Signal, rel: Relation, rhs: &Signal) -> Option<Time> {
    match rel {
        Relation::Equal => lhs.first_difference(rhs),
        Relation::Implies => lhs.first_violation_of_implication(rhs),
    }
}

fn delay_literals(e: &Expr, into: &mut Vec<Delay>) {
    for node in e.as_ref() {
        if let Term::Delay(d) = node {
            into.push(d.clone());
        }
    }
}

fn holds(condition: &Condition, env: &Assignment) -> Result<bool, String> {
    match condition {
        Condition::Delay { lhs, accept, rhs } => {
            let value =
                |e: &Expr| super::eval::eval_delay(e, root(e), env).map_err(|x| x.to_string());
            Ok(accept.contains(&value(lhs)?.cmp(&value(rhs)?)))
        }
        Condition::Signal { lhs, rel, rhs } => {
            let (l, r) = (
                eval(lhs, env).map_err(|e| e.to_string())?,
                eval(rhs, env).map_err(|e| e.to_string())?,
            );
            Ok(violation(&l, *rel, &r).is_none())
        }
    }
}

/// Changes the sample so that a condition that fails may hold: `x · y = 0*` for two
/// signal variables by removing `x` from `y`; a definition `Q = e` (or a bound
/// `Q ⇒ e`, `e ⇒ Q`) whose `e` does not mention `Q` by setting `Q` from `e`. Every
/// condition is re-checked exactly afterwards; a repair only makes samples useful.
fn repair(condition: &Condition, env: &mut Assignment) {
    let Condition::Signal { lhs, rel, rhs } = condition else { return };
    if *rel == Relation::Equal
        && let (Term::And([a, b]), Term::Zero) = (&lhs[root(lhs)], &rhs[root(rhs)])
        && let (Term::Name(x), Term::Name(y)) = (&lhs[*a], &lhs[*b])
        && let (Some(sx), Some(sy)) = (env.signals.get(x).cloned(), env.signals.get(y).cloned())
    {
        env.signals.insert(*y, sy.and(&sx.not()));
        return;
    }
    let mentions = |e: &Expr, q: &Symbol| e.as_ref().contains(&Term::Name(*q));
    if let Term::Name(q) = &lhs[root(lhs)]
        && !mentions(rhs, q)
        && let Ok(value) = eval(rhs, env)
    {
        let new = match (rel, env.signals.get(q)) {
            (Relation::Implies, Some(current)) => current.and(&value),
            _ => value,
        };
        env.signals.insert(*q, new);
    } else if *rel == Relation::Implies
        && let Term::Name(q) = &rhs[root(rhs)]
        && !mentions(lhs, q)
        && let (Ok(value), Some(current)) = (eval(lhs, env), env.signals.get(q))
    {
        let new = current.or(&value);
        env.signals.insert(*q, new);
    }
}

/// Samples `cases` assignments satisfying `conditions` and checks `lhs rel rhs` on each.
/// Returns the number of samples checked, or the first witness found (re-checked exactly).
/// Stops with [`SampleError::TooFewSamples`] at the deadline.
pub fn falsify(
    lhs: &Expr,
    rel: Relation,
    rhs: &Expr,
    conditions: &[Condition],
    cases: usize,
    seed: u64,
    deadline: Option<std::time::Instant>,
) -> Result<Result<usize, Box<Witness>>, SampleError> {
    let mut signals = BTreeSet::new();
    let mut delays = BTreeSet::new();
    let mut literals = Vec::new();
    let mut signal_terms: Vec<&Expr> = vec![lhs, rhs];
    for c in conditions {
        match c {
            Condition::Signal { lhs, rhs, .. } => signal_terms.extend([lhs, rhs]),
            Condition::Delay { lhs, rhs, .. } => {
                for node in lhs.as_ref().iter().chain(rhs.as_ref()) {
                    if let Term::Name(s) = node {
                        delays.insert(*s);
                    }
                }
            }
        }
    }
    for t in signal_terms {
        let (s, d) = free_names(t).map_err(|e| SampleError::Eval(e.to_string()))?;
        signals.extend(s);
        delays.extend(d);
        delay_literals(t, &mut literals);
    }
    let strategy = super::random::assignment_with_delays(
        signals.into_iter().collect::<Vec<Symbol>>(),
        delays.into_iter().collect::<Vec<Symbol>>(),
        literals,
    );
    let mut runner = TestRunner::new_with_rng(
        Config { failure_persistence: None, ..Config::default() },
        TestRng::from_seed(RngAlgorithm::ChaCha, &seed_bytes(seed)),
    );
    let (mut valid, mut tried) = (0usize, 0usize);
    while valid < cases {
        tried += 1;
        if tried > cases * 20 || deadline.is_some_and(|d| std::time::Instant::now() > d) {
            return Err(SampleError::TooFewSamples { valid, wanted: cases });
        }
        let Ok(tree) = strategy.new_tree(&mut runner) else { continue };
        let mut env = tree.current();
        // Definitions may depend on one another in any order: repair in passes. The
        // sample is kept once a pass finds every condition holding; the last pass
        // only checks.
        let passes = conditions.len().min(REPAIR_PASSES);
        let mut ok = false;
        for pass in 0..=passes {
            let mut failed = false;
            for c in conditions {
                if !holds(c, &env).map_err(SampleError::Eval)? {
                    failed = true;
                    if pass == passes {
                        break;
                    }
                    repair(c, &mut env);
                }
            }
            if !failed {
                ok = true;
                break;
            }
        }
        if !ok {
            continue;
        }
        valid += 1;
        let l = eval(lhs, &env).map_err(|e| SampleError::Eval(e.to_string()))?;
        let r = eval(rhs, &env).map_err(|e| SampleError::Eval(e.to_string()))?;
        if let Some(time) = violation(&l, rel, &r) {
            let (lv, rv) = (l.value_at(&time), r.value_at(&time));
            return Ok(Err(Box::new(Witness { assignment: env, time, lhs: lv, rhs: rv })));
        }
    }
    Ok(Ok(valid))
}

/// At most this many repair passes per sample.
const REPAIR_PASSES: usize = 8;

fn seed_bytes(seed: u64) -> [u8; 32] {
    let mut bytes = [0u8; 32];
    for (i, chunk) in bytes.chunks_mut(8).enumerate() {
        chunk.copy_from_slice(
            &(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15).wrapping_add(i as u64)).to_le_bytes(),
        );
    }
    bytes
}
