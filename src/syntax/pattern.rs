//! Requirement patterns: properties in a control engineer's words, compiled to II goals.
//!
//! Each pattern is a safety property over scans, stated as one goal of the algebra (the
//! README's catalogue gives the sentence each one means; `tests/suite/patterns.rs` checks the
//! goal against an evaluation of that sentence on random scan runs). With `n = d/δ`
//! scans of the program's cycle `δ`:
//!
//! | pattern | goal |
//! |---|---|
//! | `always f` | `f = 1*` |
//! | `never f` | `f = 0*` |
//! | `a then b => c` | `pre a · b ⇒ c` |
//! | `whenever a then b within d` | `d/SR(a·¬b, b) = 0*` (an `a` still waiting for its `b` after `d`) |
//! | `b not before d after a` | `b ⇒ ¬(a/d)` |
//! | `f at most d` | `d/f = 0*` |
//! | `f at least d once on` | `pre f · ¬f ⇒ pre ((d−δ)/f)` (`n ≥ 2`), `pre f · ¬f ⇒ pre f` (`n = 1`) |
//!
//! `reachable f` is an existence claim, not a safety property: it is refused with a
//! located error that says how to get a run reaching `f` (the counterexample of
//! `never f`).

use super::Relation;
use crate::term::{Delay, Expr, Term, and, constant, copy_into, not, root};

/// Which requirement pattern a goal was written as (the goal is its II term).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Pattern {
    /// `always f`.
    Always,
    /// `never f`.
    Never,
    /// `a then b => c`.
    Then,
    /// `whenever a then b within d`.
    Within,
    /// `b not before d after a`.
    NotBefore,
    /// `f at most d`.
    AtMost,
    /// `f at least d once on`.
    AtLeast,
}

impl Pattern {
    /// The pattern's words, as the catalogue names it.
    pub fn words(self) -> &'static str {
        match self {
            Pattern::Always => "always f",
            Pattern::Never => "never f",
            Pattern::Then => "a then b => c",
            Pattern::Within => "whenever a then b within d",
            Pattern::NotBefore => "b not before d after a",
            Pattern::AtMost => "f at most d",
            Pattern::AtLeast => "f at least d once on",
        }
    }

    /// Does the pattern read the previous scan (so it needs a program)?
    pub fn needs_scans(self) -> bool {
        matches!(self, Pattern::Then | Pattern::AtLeast)
    }
}

fn unary(a: &Expr, op: fn(egg::Id) -> Term) -> Expr {
    let mut nodes = a.as_ref().to_vec();
    nodes.push(op(root(a)));
    Expr::from(nodes)
}

fn pre(a: &Expr) -> Expr {
    unary(a, Term::Pre)
}

fn ton(d: &Delay, f: &Expr) -> Expr {
    let mut out = Expr::default();
    let delay = out.add(Term::Delay(d.clone()));
    let signal = copy_into(f, root(f), &mut out);
    out.add(Term::Ton([delay, signal]));
    out
}

fn tof(f: &Expr, d: &Delay) -> Expr {
    let mut out = Expr::default();
    let signal = copy_into(f, root(f), &mut out);
    let delay = out.add(Term::Delay(d.clone()));
    out.add(Term::Tof([signal, delay]));
    out
}

fn sr(s: &Expr, r: &Expr) -> Expr {
    let mut out = Expr::default();
    let (x, y) = (copy_into(s, root(s), &mut out), copy_into(r, root(r), &mut out));
    out.add(Term::Sr([x, y]));
    out
}

/// The goal `lhs rel rhs` of a pattern over its signals (in the order written) and its
/// delay; `scans`: the signals are a program's scan runs, with this `cycle` when it is
/// known. `Err`: why the pattern has no meaning here.
pub fn compile(
    pattern: Pattern,
    signals: &[Expr],
    delay: Option<&Delay>,
    scans: bool,
    cycle: Option<&Delay>,
) -> Result<(Expr, Relation, Expr), String> {
    if pattern.needs_scans() && !scans {
        return Err(format!(
            "`{}` reads the previous scan, so it needs a program: free signals have no scans",
            pattern.words()
        ));
    }
    let signal = |i: usize| signals.get(i).cloned().ok_or("a pattern lacks an operand");
    let delay = || delay.cloned().ok_or("a pattern lacks its duration");
    let zero = constant(false);
    Ok(match pattern {
        Pattern::Always => (signal(0)?, Relation::Equals, constant(true)),
        Pattern::Never => (signal(0)?, Relation::Equals, zero),
        Pattern::Then => {
            let (a, b, c) = (signal(0)?, signal(1)?, signal(2)?);
            (and(&pre(&a), &b), Relation::Implies, c)
        }
        Pattern::Within => {
            let (a, b) = (signal(0)?, signal(1)?);
            let waiting = sr(&and(&a, &not(&b)), &b);
            (ton(&delay()?, &waiting), Relation::Equals, zero)
        }
        Pattern::NotBefore => {
            let (b, a) = (signal(0)?, signal(1)?);
            (b, Relation::Implies, not(&tof(&a, &delay()?)))
        }
        Pattern::AtMost => (ton(&delay()?, &signal(0)?), Relation::Equals, zero),
        Pattern::AtLeast => {
            let f = signal(0)?;
            let falls = and(&pre(&f), &not(&f));
            let d = delay()?;
            let cycle = cycle.ok_or("`f at least d once on` needs the program's scan cycle")?;
            let shorter = Delay::new(d.seconds() - cycle.seconds()).ok();
            match shorter {
                Some(rest) => (falls, Relation::Implies, pre(&ton(&rest, &f))),
                None => (falls, Relation::Implies, pre(&f)),
            }
        }
    })
}
