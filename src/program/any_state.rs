//! Runs from an arbitrary state (`equiv --any-state`): the state a run starts from, read from the free start values of the first scan, and a reference whose simulators start there.
//!
//! A program compiled with [`CompileOptions::any_state`](super::CompileOptions::any_state)
//! reads, at its first scan, free start values (`start_X`, inputs to the bounded model
//! checker and to the counterexample's trace) instead of the power-up values
//! ([`StartOf`] says of what). [`AnyStateReference`] wraps a front end's reference: at the
//! first scan it gathers those values into a [`StartState`], hands it to the front end's
//! simulator ([`ScanSimulator::start_from`]) and then steps it on the other inputs, so
//! that a counterexample is replayed from the very state it starts from. A simulator
//! that cannot start there knows no value: the counterexample is then not confirmed.
#![warn(missing_docs)]

use std::collections::BTreeMap;
use std::sync::Arc;

use super::compile::start::StartOf;
use super::simulate::{Reference, ScanSimulator};
use super::{CompiledProgram, IntVar};

/// The state a run starts from instead of the power-up values.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct StartState {
    /// Bits the program writes, by name.
    pub bits: BTreeMap<String, bool>,
    /// Hidden memories of one-shots and toggles, by the front end's index.
    pub edges: BTreeMap<usize, bool>,
    /// Integers, by name (values of their types).
    pub ints: BTreeMap<String, i64>,
}

impl StartState {
    /// The state that the start values `value` gives (a start value not given is 0),
    /// for a program with these start values, integers and start-up flag.
    pub fn of(
        starts: &BTreeMap<String, StartOf>,
        integers: &BTreeMap<String, IntVar>,
        flag: Option<&str>,
        value: &dyn Fn(&str) -> bool,
    ) -> StartState {
        let mut state = StartState::default();
        let mut stored: BTreeMap<&str, Vec<bool>> = BTreeMap::new();
        for (s, of) in starts {
            let v = value(s);
            match of {
                StartOf::Bit(x) => {
                    state.bits.insert(x.clone(), v);
                }
                StartOf::Edge(k) => {
                    state.edges.insert(*k, v);
                }
                StartOf::IntBit { of, bit, start } => {
                    let Some(var) = integers.get(of) else { continue };
                    let bits = stored
                        .entry(of.as_str())
                        .or_insert_with(|| (0..var.ty.bits).map(|k| var.start_bit(k)).collect());
                    if let Some(b) = bits.get_mut(*bit as usize) {
                        *b = v != *start;
                    }
                }
            }
        }
        for (of, bits) in stored {
            if let Some(var) = integers.get(of) {
                state.ints.insert(of.to_string(), super::bitvec::value_of(&bits, var.ty));
            }
        }
        if let Some(flag) = flag {
            state.bits.insert(flag.to_string(), true);
        }
        state
    }
}

/// A front end's reference whose runs start from the state the first scan's start
/// values give.
pub struct AnyStateReference {
    inner: Arc<dyn Reference>,
    starts: BTreeMap<String, StartOf>,
    integers: BTreeMap<String, IntVar>,
    started: Option<String>,
    flag: Option<String>,
}

impl AnyStateReference {
    /// `inner`'s runs from the start values of `compiled` (compiled with `--any-state`).
    pub fn new(inner: Arc<dyn Reference>, compiled: &CompiledProgram) -> AnyStateReference {
        AnyStateReference {
            inner,
            starts: compiled.starts.clone(),
            integers: compiled.integers.clone(),
            started: compiled.started.clone(),
            flag: compiled.start_flag.clone(),
        }
    }
}

impl Reference for AnyStateReference {
    fn simulator(&self) -> Box<dyn ScanSimulator> {
        Box::new(AnyStateSimulator {
            inner: self.inner.simulator(),
            starts: self.starts.clone(),
            integers: self.integers.clone(),
            started: self.started.clone(),
            flag: self.flag.clone(),
            begun: false,
            started_there: false,
        })
    }
}

struct AnyStateSimulator {
    inner: Box<dyn ScanSimulator>,
    starts: BTreeMap<String, StartOf>,
    integers: BTreeMap<String, IntVar>,
    started: Option<String>,
    flag: Option<String>,
    begun: bool,
    /// Whether the inner simulator started from the state asked.
    started_there: bool,
}

impl ScanSimulator for AnyStateSimulator {
    fn step(&mut self, inputs: &BTreeMap<String, bool>) {
        if !self.begun {
            let value = |s: &str| inputs.get(s).copied().unwrap_or(false);
            let state = StartState::of(&self.starts, &self.integers, self.flag.as_deref(), &value);
            self.started_there = self.inner.start_from(&state);
            self.begun = true;
        }
        let rest: BTreeMap<String, bool> = inputs
            .iter()
            .filter(|(n, _)| !self.starts.contains_key(*n))
            .map(|(n, v)| (n.clone(), *v))
            .collect();
        self.inner.step(&rest);
    }
    fn bit(&self, name: &str) -> bool {
        match &self.started {
            Some(s) if s == name => self.begun,
            _ => self.inner.bit(name),
        }
    }
    fn is_known(&self, name: &str) -> bool {
        self.started_there
            && match &self.started {
                Some(s) if s == name => true,
                _ => self.inner.is_known(name),
            }
    }
    fn edge_memory(&self, index: usize) -> Option<bool> {
        self.started_there.then(|| self.inner.edge_memory(index)).flatten()
    }
    fn int(&self, name: &str) -> Option<i64> {
        self.started_there.then(|| self.inner.int(name)).flatten()
    }
}
