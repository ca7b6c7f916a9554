//! A scan-model program's names renamed, and its scan-local values and one-shot indexes shifted: how a front end places a standalone program (a function block's body) inside another, one instance at a time.
#![warn(missing_docs)]

use std::collections::BTreeMap;

use super::{Block, BoolExpr, IntExpr, Preset, Program, Stmt, WriteKind};

/// What a renaming changes: every name (bits, integers, timer accumulators, variable
/// presets, the bases of one-shot memories and unconstrained values) through `name`,
/// every scan-local value by `temps`, every one-shot index through `edge`, and each
/// variable preset whose (new) variable `presets` names into that preset.
pub struct Renaming<'a> {
    /// The new name of a name.
    pub name: &'a dyn Fn(&str) -> String,
    /// What scan-local values are shifted by.
    pub temps: usize,
    /// The new index of a one-shot's memory.
    pub edge: &'a mut dyn FnMut(usize) -> usize,
    /// The presets of variables known to hold one duration, by their new names.
    pub presets: &'a BTreeMap<String, Preset>,
}

impl Renaming<'_> {
    /// The blocks with everything renamed and shifted.
    pub fn blocks(&mut self, blocks: &[Block]) -> Vec<Block> {
        blocks
            .iter()
            .map(|b| Block { stmts: b.stmts.iter().map(|s| self.stmt(s)).collect(), ..b.clone() })
            .collect()
    }

    fn stmt(&mut self, s: &Stmt) -> Stmt {
        let name = self.name;
        match s {
            Stmt::Let { temp, value } => {
                Stmt::Let { temp: temp + self.temps, value: self.expr(value) }
            }
            Stmt::Write { target, kind, value, span } => {
                let kind = match kind {
                    WriteKind::Toggle(m) => WriteKind::Toggle(Box::new(super::Memory {
                        base: name(&m.base),
                        index: (self.edge)(m.index),
                        element: m.element.clone(),
                    })),
                    k => k.clone(),
                };
                Stmt::Write { target: name(target), kind, value: self.expr(value), span: *span }
            }
            Stmt::If { branches, otherwise, span } => Stmt::If {
                branches: branches
                    .iter()
                    .map(|(c, b)| (self.expr(c), b.iter().map(|s| self.stmt(s)).collect()))
                    .collect(),
                otherwise: otherwise.iter().map(|s| self.stmt(s)).collect(),
                span: *span,
            },
            Stmt::SetInt { target, value, span } => {
                Stmt::SetInt { target: name(target), value: self.int(value), span: *span }
            }
            Stmt::Warn { .. } => s.clone(),
        }
    }

    fn expr(&mut self, e: &BoolExpr) -> BoolExpr {
        let name = self.name;
        match e {
            BoolExpr::Const(_) => e.clone(),
            BoolExpr::Var(n) => BoolExpr::Var(name(n)),
            BoolExpr::Temp(t) => BoolExpr::Temp(t + self.temps),
            BoolExpr::Not(x) => BoolExpr::negate(self.expr(x)),
            BoolExpr::And(a, b) => BoolExpr::and(self.expr(a), self.expr(b)),
            BoolExpr::Or(xs) => BoolExpr::Or(xs.iter().map(|x| self.expr(x)).collect()),
            BoolExpr::Timer(t) => {
                let preset = match &t.preset {
                    Preset::Variable { name: v, why } => match self.presets.get(&name(v)) {
                        Some(p) => p.clone(),
                        None => Preset::Variable { name: name(v), why: why.clone() },
                    },
                    p => p.clone(),
                };
                BoolExpr::Timer(Box::new(super::Timer {
                    accumulator: name(&t.accumulator),
                    preset,
                    input: self.expr(&t.input),
                    ..(**t).clone()
                }))
            }
            BoolExpr::Edge { kind, input, memory } => BoolExpr::Edge {
                kind: *kind,
                input: Box::new(self.expr(input)),
                memory: Box::new(super::Memory {
                    base: name(&memory.base),
                    index: (self.edge)(memory.index),
                    element: memory.element.clone(),
                }),
            },
            BoolExpr::Fresh(f) => {
                BoolExpr::Fresh(Box::new(super::Fresh { base: name(&f.base), ..(**f).clone() }))
            }
            BoolExpr::Compare(c) => BoolExpr::Compare(Box::new(super::Compare {
                a: self.int(&c.a),
                b: self.int(&c.b),
                ..(**c).clone()
            })),
        }
    }

    fn int(&mut self, e: &IntExpr) -> IntExpr {
        let mut e = e.clone();
        let name = self.name;
        super::int_visit_mut(&mut e, &mut |n| *n = name(n), &mut |c| *c = self.expr(c));
        e
    }
}

impl Program {
    /// The program with every name it uses prefixed by `prefix` (its blocks, inputs,
    /// integers, start-up flag and hidden names), its scan-local values and one-shot
    /// indexes kept: a function block's body for one instance.
    pub fn prefixed(&self, prefix: &str) -> Program {
        let name = |n: &str| format!("{prefix}{n}");
        let mut edge = |i: usize| i;
        let presets = BTreeMap::new();
        let blocks = Renaming { name: &name, temps: 0, edge: &mut edge, presets: &presets }
            .blocks(&self.blocks);
        let set = |s: &std::collections::BTreeSet<String>| s.iter().map(|n| name(n)).collect();
        Program {
            blocks,
            inputs: match &self.inputs {
                super::Inputs::Declared(s) => super::Inputs::Declared(set(s)),
                super::Inputs::ByPrefix => super::Inputs::ByPrefix,
            },
            signals: set(&self.signals),
            names: set(&self.names),
            skipped: self.skipped.iter().map(|(n, b)| (name(n), *b)).collect(),
            integer_writers: self.integer_writers.iter().map(|(n, k)| (name(n), *k)).collect(),
            integers: self.integers.iter().map(|(n, v)| (name(n), *v)).collect(),
            started: self.started.as_deref().map(name),
            hidden: set(&self.hidden),
            undefined: set(&self.undefined),
            ..self.clone()
        }
    }

    /// The program with each timer whose preset is a variable `presets` names given
    /// that preset (a variable known to hold one duration).
    pub fn with_presets(&self, presets: &BTreeMap<String, Preset>) -> Program {
        let same = |n: &str| n.to_string();
        let mut edge = |i: usize| i;
        let blocks =
            Renaming { name: &same, temps: 0, edge: &mut edge, presets }.blocks(&self.blocks);
        Program { blocks, ..self.clone() }
    }

    /// One more than the largest scan-local value the blocks use (0 without any).
    pub fn temps_used(&self) -> usize {
        self.one_past(
            |s| match s {
                Stmt::Let { temp, .. } => Some(*temp),
                _ => None,
            },
            |e| match e {
                BoolExpr::Temp(t) => Some(*t),
                _ => None,
            },
        )
    }

    /// One more than the largest one-shot index the blocks use (0 without any).
    pub fn edges_used(&self) -> usize {
        self.one_past(
            |s| match s {
                Stmt::Write { kind: WriteKind::Toggle(m), .. } => Some(m.index),
                _ => None,
            },
            |e| match e {
                BoolExpr::Edge { memory, .. } => Some(memory.index),
                _ => None,
            },
        )
    }

    /// One more than the largest number `stmt` and `expr` find in the blocks.
    fn one_past(
        &self,
        stmt: fn(&Stmt) -> Option<usize>,
        expr: fn(&BoolExpr) -> Option<usize>,
    ) -> usize {
        let (mut a, mut b) = (0, 0);
        for (_, s) in self.stmts() {
            s.visit(&mut |s| a = a.max(stmt(s).map_or(0, |k| k + 1)), &mut |e| {
                b = b.max(expr(e).map_or(0, |k| k + 1))
            });
        }
        a.max(b)
    }
}
