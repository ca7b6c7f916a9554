//! The product of two compiled programs for equivalence checking: the second program's signals renamed apart (`X` → `X'`) except the inputs it shares with the first, both sets of equations side by side, and a scan simulator that runs both programs' own simulators on the same inputs.
//!
//! Both programs scan at the same cycle, so one scan of the product is one scan of
//! each; the equations of the two never mention each other's signals except the shared
//! inputs, so their union describes exactly the pairs of runs that read the same
//! inputs. A property `X = X'` of the product says that the two programs' outputs are
//! equal at every scan.
#![warn(missing_docs)]

use std::collections::{BTreeMap, BTreeSet};
use std::sync::Arc;

use super::compile::{CompiledProgram, Hypothesis, SignalKind};
use super::simulate::{Reference, ScanSimulator};
use crate::term::{Expr, Symbol, Term};

/// What the second program's one-shot indexes are shifted by in the product, so that
/// the product's simulator can tell whose memory an index names.
pub const SECOND_EDGE_OFFSET: usize = 1 << 24;

/// The name the second program's signal `name` has in the product, unless it is a
/// shared input.
pub fn primed(name: &str) -> String {
    format!("{name}'")
}

/// How the second program's names read in the product.
#[derive(Clone, Debug, Default)]
pub struct Renaming {
    /// The second program's inputs that are the first's (its name → the first's).
    pub shared: BTreeMap<String, String>,
}

impl Renaming {
    /// The product's name of the second program's signal `name`.
    pub fn of(&self, name: &str) -> String {
        self.shared.get(name).cloned().unwrap_or_else(|| primed(name))
    }

    fn expr(&self, e: &Expr) -> Expr {
        let nodes: Vec<Term> = e
            .as_ref()
            .iter()
            .map(|node| match node {
                Term::Name(n) => Term::Name(Symbol::from(self.of(n.as_str()).as_str())),
                other => other.clone(),
            })
            .collect();
        Expr::from(nodes)
    }
}

/// The product of `a` and `b` with `b`'s names renamed by `renaming`; `None` when the
/// two do not scan at the same cycle, or when a renamed name of `b` is one of `a`'s
/// (a name of `a` ending in `'`): the product would then mix their signals.
pub fn product(
    a: &CompiledProgram,
    b: &CompiledProgram,
    renaming: &Renaming,
) -> Result<CompiledProgram, String> {
    if a.cycle_us != b.cycle_us {
        return Err(format!(
            "the two programs scan at different cycles ({} µs and {} µs): scans can only be compared at one cycle (give both the same, e.g. with --cycle)",
            a.cycle_us, b.cycle_us
        ));
    }
    let mut signals = a.signals.clone();
    for (name, kind) in &b.signals {
        let renamed = renaming.of(name);
        let kind = match kind {
            SignalKind::EdgeMemory { rung, element, index } => SignalKind::EdgeMemory {
                rung: *rung,
                element: element.clone(),
                index: index + SECOND_EDGE_OFFSET,
            },
            SignalKind::IntBit { of, bit, start, input } => {
                SignalKind::IntBit { of: renaming.of(of), bit: *bit, start: *start, input: *input }
            }
            other => other.clone(),
        };
        if renaming.shared.contains_key(name) {
            let input = matches!(kind, SignalKind::Input | SignalKind::IntBit { input: true, .. });
            if !input || a.signals.get(&renamed) != Some(&kind) {
                return Err(format!(
                    "`{name}` of the second program is matched with `{renamed}` of the first, but the two are not both input bits"
                ));
            }
            continue;
        }
        if signals.insert(renamed.clone(), kind).is_some() {
            return Err(format!(
                "the first program has a signal `{renamed}`, the name the second program's `{name}` takes in the comparison"
            ));
        }
    }
    let taken: BTreeSet<&str> = a.hypotheses.iter().map(|h| h.name.as_str()).collect();
    let mut hypotheses = a.hypotheses.clone();
    for h in &b.hypotheses {
        let name = primed(&h.name);
        if taken.contains(name.as_str()) {
            return Err(format!("both programs have an equation named `{name}`"));
        }
        hypotheses.push(Hypothesis {
            name,
            lhs: renaming.expr(&h.lhs),
            rhs: renaming.expr(&h.rhs),
            ..h.clone()
        });
    }
    let mut timer_info = a.timer_info.clone();
    timer_info.extend(
        b.timer_info.iter().map(|t| super::TimerInfo { name: renaming.of(&t.name), ..t.clone() }),
    );
    let mut integers = a.integers.clone();
    integers.extend(b.integers.iter().map(|(n, v)| (renaming.of(n), *v)));
    let mut warnings = a.warnings.clone();
    warnings.extend(b.warnings.iter().cloned());
    Ok(CompiledProgram {
        hypotheses,
        signals,
        warnings,
        timers: a.timers,
        timer_info,
        cycle_us: a.cycle_us,
        exact_names: true,
        language: a.language,
        block_noun: a.block_noun,
        integers,
        int_depth: a.int_depth.max(b.int_depth),
        ..CompiledProgram::default()
    })
}

/// Both programs' own simulators, run on the same inputs: the product's reference.
pub struct ProductReference {
    /// The first program's simulator.
    pub a: Arc<dyn Reference>,
    /// The second program's simulator.
    pub b: Arc<dyn Reference>,
    /// Per product name of a signal of the second program (shared inputs included), its
    /// name there.
    pub b_names: BTreeMap<String, String>,
}

impl ProductReference {
    /// The reference of the product of `a` and `b` renamed by `renaming`, given every
    /// signal name of `b`.
    pub fn new(
        a: Arc<dyn Reference>,
        b: Arc<dyn Reference>,
        b_signals: impl Iterator<Item = String>,
        renaming: &Renaming,
    ) -> ProductReference {
        let mut b_names: BTreeMap<String, String> = BTreeMap::new();
        for n in b_signals {
            let renamed = renaming.of(&n);
            // Integers are kept by name too (their bits are `X_bK`).
            b_names.insert(renamed, n);
        }
        ProductReference { a, b, b_names }
    }
}

impl Reference for ProductReference {
    fn simulator(&self) -> Box<dyn ScanSimulator> {
        Box::new(ProductSimulator {
            a: self.a.simulator(),
            b: self.b.simulator(),
            b_names: self.b_names.clone(),
        })
    }
}

struct ProductSimulator {
    a: Box<dyn ScanSimulator>,
    b: Box<dyn ScanSimulator>,
    b_names: BTreeMap<String, String>,
}

impl ProductSimulator {
    /// The second program's name of a product name that is its own (not a shared
    /// input, which the first program answers for).
    fn own(&self, name: &str) -> Option<&str> {
        name.ends_with('\'').then(|| self.b_names.get(name).map(String::as_str)).flatten()
    }
}

impl ScanSimulator for ProductSimulator {
    fn step(&mut self, inputs: &BTreeMap<String, bool>) {
        let for_b: BTreeMap<String, bool> = inputs
            .iter()
            .filter_map(|(n, v)| self.b_names.get(n).map(|orig| (orig.clone(), *v)))
            .collect();
        let for_a: BTreeMap<String, bool> = inputs
            .iter()
            .filter(|(n, _)| self.own(n).is_none())
            .map(|(n, v)| (n.clone(), *v))
            .collect();
        self.a.step(&for_a);
        self.b.step(&for_b);
    }
    fn bit(&self, name: &str) -> bool {
        match self.own(name) {
            Some(orig) => self.b.bit(orig),
            None => self.a.bit(name),
        }
    }
    fn is_known(&self, name: &str) -> bool {
        match self.own(name) {
            Some(orig) => self.b.is_known(orig),
            None => self.a.is_known(name),
        }
    }
    fn edge_memory(&self, index: usize) -> Option<bool> {
        match index.checked_sub(SECOND_EDGE_OFFSET) {
            Some(k) => self.b.edge_memory(k),
            None => self.a.edge_memory(index),
        }
    }
    fn int(&self, name: &str) -> Option<i64> {
        match name.strip_suffix('\'') {
            Some(orig) => self.b.int(orig),
            None => self.a.int(name),
        }
    }
}
