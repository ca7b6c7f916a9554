//! `ii-prove equiv --any-state`: which free start values of the two programs are one (the state both keep under one name starts equal), and what is said of the rest.

use std::collections::{BTreeMap, BTreeSet};

use crate::ladder::CompiledProgram;
use crate::program::compile::start::StartOf;

/// The start values of the two programs matched for `--any-state`.
pub(super) struct Starts {
    /// The second program's start value → the first's it is (for the product's renaming).
    pub shared: Vec<(String, String)>,
    /// A line for each state that starts arbitrary on its own.
    pub unmatched: Vec<String>,
}

/// What each start value of `c` is the start of, by the state's description.
fn by_state(c: &CompiledProgram) -> BTreeMap<(String, u32), String> {
    let mut out = BTreeMap::new();
    for (s, of) in &c.starts {
        match of {
            StartOf::Bit(x) => {
                out.insert((x.clone(), 0), s.clone());
            }
            StartOf::IntBit { of, bit, .. } => {
                out.insert((of.clone(), *bit), s.clone());
            }
            StartOf::Edge(_) => {}
        }
    }
    out
}

/// Matches the start values of `a` and `b`: those of the bits `pairs` names (the state
/// both programs write under one name, and the compared outputs), and of the integers
/// both write under one name (matched bit by bit when their types are one).
pub(super) fn match_starts(
    a: &CompiledProgram,
    b: &CompiledProgram,
    pairs: &[(String, String)],
    int_pairs: &[(String, String)],
) -> Starts {
    let (sa, sb) = (by_state(a), by_state(b));
    let mut shared = Vec::new();
    let mut unmatched = Vec::new();
    for (x, y) in pairs {
        if let (Some(p), Some(q)) = (sa.get(&(x.clone(), 0)), sb.get(&(y.clone(), 0))) {
            shared.push((q.clone(), p.clone()));
        }
    }
    for (x, y) in int_pairs {
        let (Some(u), Some(v)) = (a.integers.get(x), b.integers.get(y)) else { continue };
        if u.ty != v.ty {
            unmatched.push(format!(
                "--any-state: the integer `{x}` is {} in the first program and {} in the second: their start values are not matched",
                u.ty.describe(),
                v.ty.describe()
            ));
            continue;
        }
        for k in 0..u.ty.bits {
            if let (Some(p), Some(q)) = (sa.get(&(x.clone(), k)), sb.get(&(y.clone(), k))) {
                shared.push((q.clone(), p.clone()));
            }
        }
    }
    let taken_b: BTreeSet<&String> = shared.iter().map(|p| &p.0).collect();
    let taken_a: BTreeSet<&String> = shared.iter().map(|p| &p.1).collect();
    for (side, c, taken) in [("first", a, &taken_a), ("second", b, &taken_b)] {
        let mut states: BTreeSet<String> = BTreeSet::new();
        let mut edges = 0;
        for (s, of) in &c.starts {
            if taken.contains(s) {
                continue;
            }
            match of {
                StartOf::Bit(x) | StartOf::IntBit { of: x, .. } => {
                    states.insert(x.clone());
                }
                StartOf::Edge(_) => edges += 1,
            }
        }
        for x in states {
            unmatched.push(format!(
                "--any-state: `{x}` of the {side} program has no counterpart in the other: it starts arbitrary on its own"
            ));
        }
        if edges > 0 {
            unmatched.push(format!(
                "--any-state: the {side} program's {edges} one-shot or toggle memor{} start{} arbitrary on {}",
                if edges == 1 { "y" } else { "ies" },
                if edges == 1 { "s" } else { "" },
                if edges == 1 { "its own" } else { "their own" }
            ));
        }
    }
    Starts { shared, unmatched }
}
