//! A confirmed counterexample completed with signals the property does not read (the bits of a timer's elapsed time a diagram draws): their cone run scan by scan on the counterexample's inputs, checked against the signals it already has and against every equation exactly.

use super::unroll::{Concrete, unroll};
use super::{Counterexample, Program, scans_of};
use crate::semantics::{Assignment, eval};
use crate::term::{Symbol, name};

impl Program<'_> {
    /// `c`'s assignment with the signals `wanted` added, as the program's equations
    /// compute them on `c`'s inputs; `None` when the run of their cone disagrees with a
    /// signal `c` already has, or an equation fails on the exact signals (nothing is
    /// drawn then rather than a value the run does not have).
    pub fn completed(&self, c: &Counterexample, wanted: &[String]) -> Option<Assignment> {
        let terms: Vec<_> = wanted.iter().map(|w| name(w)).collect();
        let refs: Vec<_> = terms.iter().collect();
        let model = self.model(&refs);
        let cycle = c.trace.cycle.clone();
        let run = unroll(
            &mut Concrete,
            &model,
            &[],
            c.trace.scans,
            &|d| scans_of(d, &cycle),
            &mut |_, n, k| c.trace.values.get(n).and_then(|v| v.get(k).copied()).unwrap_or(false),
        )
        .ok()?;
        let instants = c.trace.instants();
        let mut env = c.assignment.clone();
        for (n, values) in &run.signals {
            let symbol = Symbol::from(n.as_str());
            match env.signals.get(&symbol) {
                Some(s) => {
                    if instants.iter().zip(values).any(|(t, v)| s.value_at(t) != *v) {
                        return None;
                    }
                }
                None => {
                    env.signals.insert(symbol, c.trace.signal(values).ok()?);
                }
            }
        }
        for (n, rhs) in &model.defs {
            let s = eval(rhs, &env).ok()?;
            let x = env.signals.get(&Symbol::from(n.as_str()))?;
            if instants.iter().any(|t| x.value_at(t) != s.value_at(t)) {
                return None;
            }
        }
        let mut out = c.assignment.clone();
        for w in wanted {
            let symbol = Symbol::from(w.as_str());
            out.signals.insert(symbol, env.signals.get(&symbol)?.clone());
        }
        Some(out)
    }
}
