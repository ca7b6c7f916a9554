//! The compiler under `--any-state`: the program's state starts arbitrary instead of at its power-up values, each state bit's previous-scan value at the first scan a free start value.
//!
//! Without it, `pre X` is `X` at the end of the previous scan and 0 at the first scan
//! (power-up). With [`CompileOptions::any_state`](super::CompileOptions::any_state), every
//! read of a previous-scan value becomes
//!
//! `pre X · pre started + ¬pre started · start_X`
//!
//! where `started = 1*` is stated as an equation (so `pre started` is 0 at the first scan
//! only) and `start_X` is a free signal: at the first scan the read sees `start_X`, later
//! the previous scan's `X`, exactly. The state covered is every bit the program writes,
//! the hidden memory of every one-shot and toggle (its own memory, never its power's
//! previous value), and the stored bits of every integer the program writes; a bit the
//! front end uses to tell the first scan (ST's and PLCopen's start-up flag) starts at 1,
//! as after power-up, so that start-up writes do not run again. Memories are stated as
//! their scan recurrences (`SR`/`RS` start at 0). A timer's count is state too and is
//! not modelled: a timer is refused with a located error. Bits the program never writes
//! keep their power-up values.

use std::collections::{BTreeMap, BTreeSet};

use super::super::logic::L;
use super::super::{Program, Timer};
use super::{CompileError, Compiler, SignalKind};

/// `program` with every integer's power-up value 0 (under `--any-state` its stored
/// bits are its value's, each a start value).
pub(super) fn without_start_values(program: &Program) -> Program {
    let mut out = program.clone();
    for v in out.integers.values_mut() {
        v.init = 0;
    }
    out
}

/// What a free start value of `--any-state` is the start of.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum StartOf {
    /// A bit the program writes: its value before the first scan.
    Bit(String),
    /// The hidden memory of the one-shot or toggle with this index (the front end's
    /// order, [`Memory::index`](super::super::Memory::index)).
    Edge(usize),
    /// Bit `bit` of an integer's stored value (the value xor `start`, the bit of its
    /// power-up value).
    IntBit {
        /// The integer.
        of: String,
        /// Which bit (0 the least significant).
        bit: u32,
        /// The bit of the power-up value the stored bit is flipped by.
        start: bool,
    },
}

impl Compiler<'_> {
    /// The read of `x`'s previous-scan value `pre` (the term `pre X`): under
    /// `--any-state`, `pre X` from the second scan on and `x`'s start value at the first.
    pub(super) fn start_or(&self, x: &str, pre: L) -> L {
        let Some(started) = &self.started else { return pre };
        let later = L::Pre(Box::new(L::var(started)));
        let first_value = match self.starts.get(x) {
            Some(s) => L::var(s),
            None if self.program.started.as_deref() == Some(x) => L::One,
            None => return pre,
        };
        pre.and(later.clone()).or(later.negate().and(first_value))
    }

    /// A timer under `--any-state`: refused, since its count at the start is not modelled.
    pub(super) fn timer_from_any_state(&mut self, t: &Timer) -> L {
        self.errors.push(CompileError {
            span: t.span,
            keyword: t.keyword.clone(),
            reason: format!(
                "--any-state: the count of the timer {} at the start is state that ii-prove \
                 does not model (only bits, one-shot memories and integers start arbitrary); \
                 compare this program from power-up (without --any-state)",
                t.accumulator
            ),
        });
        L::Zero
    }

    /// States `started = 1*` under `--any-state`.
    pub(super) fn state_start(&mut self) {
        let Some(started) = self.started.clone() else { return };
        let block = self.program.blocks.first();
        let name = self.unique("any_state_started");
        self.hypotheses.push(super::Hypothesis {
            name,
            rung: block.map_or(0, |b| b.number),
            span: block.map_or(crate::diag::Span::new(0, 0..0), |b| b.span),
            kind: super::HypothesisKind::Equation,
            lhs: L::var(&started).to_expr(),
            rel: crate::kernel::Rel::Eq,
            rhs: L::One.to_expr(),
        });
        self.fresh.insert(started, SignalKind::Started);
    }

    /// The start values the equations read, by name, with what each is the start of.
    pub(super) fn start_targets(
        &self,
        signals: &BTreeMap<String, SignalKind>,
    ) -> BTreeMap<String, StartOf> {
        let read: BTreeSet<&String> = signals.keys().collect();
        let mut out = BTreeMap::new();
        for (x, s) in &self.starts {
            if !read.contains(s) {
                continue;
            }
            let target = match (self.fresh.get(x), self.int_bit_kind(x)) {
                (Some(SignalKind::EdgeMemory { index, .. }), _) => StartOf::Edge(*index),
                (_, Some(SignalKind::IntBit { of, bit, start, .. })) => {
                    StartOf::IntBit { of, bit, start }
                }
                _ => StartOf::Bit(x.clone()),
            };
            out.insert(s.clone(), target);
        }
        out
    }
}
