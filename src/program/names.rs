//! Names of a compiled program in the plant's vocabulary: exact LDmicro names (`YL1_pump`) and the same without their one-letter kind prefix (`L1_pump`).
//!
//! The kind prefixes are those of ldmicro.md §5: `X Y R T C A P I M H`. A short
//! name resolves when exactly one signal has it; `pre_YL1_pump` is shortened to
//! `pre_L1_pump` the same way; fresh signals (`CTU_Cpieces`) have no short
//! form. An exact name always wins. Output prints a signal the way the user's text
//! spells it: short once a property, script or REPL line has named it short, else
//! exactly as the program declares it (what the user can search for).
#![warn(missing_docs)]

use std::collections::{BTreeMap, BTreeSet};

use super::compile::{CompiledProgram, SignalKind};
use crate::syntax::{Lookup, Scope};
use crate::term::{Expr, Symbol, Term};

/// The one-letter kind prefixes of LDmicro names.
pub const KIND_PREFIXES: &[char] = &['X', 'Y', 'R', 'T', 'C', 'A', 'P', 'I', 'M', 'H'];

/// `name` without its kind prefix (`XL_flow` → `L_flow`), if it has one and
/// the rest starts like an identifier.
pub fn short_name(name: &str) -> Option<String> {
    let mut chars = name.chars();
    let first = chars.next()?;
    let rest = chars.as_str();
    let ok = KIND_PREFIXES.contains(&first)
        && rest.chars().next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_');
    ok.then(|| rest.to_string())
}

/// The short names a user has written, recorded as they resolve (a lookup is `&self`);
/// the copies of one compiled program (a checker's, a session's) share them.
#[derive(Clone, Debug, Default)]
pub struct Spellings(std::sync::Arc<std::sync::Mutex<BTreeSet<String>>>);

impl Spellings {
    fn insert(&self, name: &str) {
        if let Ok(mut set) = self.0.lock() {
            set.insert(name.to_string());
        }
    }

    fn contains(&self, name: &str) -> bool {
        self.0.lock().is_ok_and(|set| set.contains(name))
    }
}

impl CompiledProgram {
    /// The short form of a signal of this program: program bits lose their
    /// kind prefix; fresh signals and edge memories have none.
    fn short_of(&self, name: &str) -> Option<String> {
        if self.exact_names {
            return None;
        }
        match self.signals.get(name)? {
            SignalKind::Fresh { .. } | SignalKind::EdgeMemory { .. } => None,
            _ => short_name(name),
        }
    }

    /// Short name → the signals that have it; built once per program, on first use.
    fn short_index(&self) -> &BTreeMap<String, Vec<String>> {
        self.short_names.get_or_init(|| {
            let mut index: BTreeMap<String, Vec<String>> = BTreeMap::new();
            for name in self.signals.keys() {
                if let Some(s) = self.short_of(name) {
                    index.entry(s).or_default().push(name.clone());
                }
            }
            index
        })
    }

    /// The name to print for a canonical signal name: the short name when the user has
    /// written it and it denotes only this signal (and is no other signal's exact name),
    /// else the name itself.
    pub fn display_name(&self, canonical: &str) -> String {
        match self.short_of(canonical) {
            Some(s) if !self.signals.contains_key(&s) && self.spelled_short.contains(&s) => {
                let unique = self.short_index().get(&s).is_some_and(|c| c.len() == 1);
                if unique { s } else { canonical.to_string() }
            }
            _ => canonical.to_string(),
        }
    }

    /// `expr` with every signal name replaced by its [`display_name`](Self::display_name).
    pub fn rename_for_display(&self, expr: &Expr) -> Expr {
        let nodes: Vec<Term> = expr
            .as_ref()
            .iter()
            .map(|node| match node {
                Term::Name(n) if self.signals.contains_key(n.as_str()) => {
                    Term::Name(Symbol::from(self.display_name(n.as_str())))
                }
                other => other.clone(),
            })
            .collect();
        Expr::from(nodes)
    }
}

impl Scope for CompiledProgram {
    fn lookup(&self, name: &str) -> Lookup {
        if self.signals.contains_key(name) {
            return Lookup::Signal(name.to_string());
        }
        match self.short_index().get(name) {
            Some(c) if c.len() == 1 => {
                self.spelled_short.insert(name);
                Lookup::Signal(c[0].clone())
            }
            Some(c) if c.len() > 1 => Lookup::Ambiguous(c.clone()),
            _ => Lookup::Unknown,
        }
    }

    fn names(&self) -> Vec<String> {
        let mut out: BTreeSet<String> = self.signals.keys().cloned().collect();
        for (short, c) in self.short_index() {
            if c.len() == 1 {
                out.insert(short.clone());
            }
        }
        out.into_iter().collect()
    }

    fn hypothesis_names(&self) -> Vec<String> {
        self.hypotheses.iter().map(|h| h.name.clone()).collect()
    }

    fn scans(&self) -> bool {
        true
    }

    fn cycle(&self) -> Option<crate::term::Delay> {
        Some(self.scan_cycle())
    }

    fn comparison(
        &self,
        op: crate::program::CmpOp,
        a: &crate::syntax::IntOperand,
        b: &crate::syntax::IntOperand,
    ) -> Result<String, (String, Option<String>)> {
        self.comparison_atom(op, a, b)
    }
}
