//! Values known before the scan: while a body is lowered, the bits and integers whose value at this point of the scan is fixed by what ran before it in the same scan (assignments of values computed from literals, constants and other such values), so that a `WHILE`/`REPEAT` loop can be counted and unrolled.
//!
//! Every statement of the scan model lowered is run here on those values, as the scan
//! runs it: a write of a computed value makes its target known, any other write (a
//! timer's output, a value read from an input, a write in a branch whose condition is
//! not known) makes it unknown. The start of a scan knows nothing: every variable keeps
//! its value from the scan before. A guard bit of `EXIT` or `RETURN` whose value is not
//! known is taken as not set while the loop or body it leaves is being lowered: the
//! values computed are those of the path that goes on, the only one on which they are
//! read (after the loop or body, the scan model's own guards decide).

use std::collections::{BTreeMap, BTreeSet};

use super::Lowering;
use crate::program::{BoolExpr, IntExpr, IntType, Preset, Stmt, Temp, WriteKind, walk};

/// The values known at a point of the scan.
#[derive(Clone, Debug, Default)]
pub(super) struct Known {
    /// Bits (0 or 1) and integers, by their names in the scan model.
    values: BTreeMap<String, i64>,
    /// Scan-local values.
    temps: BTreeMap<Temp, bool>,
    /// Guard bits taken as not set when their value is not known.
    pub(super) assumed: BTreeSet<String>,
    /// Per timer instance, the preset its last call gave it, where that call ran for sure
    /// earlier in this scan: what a call that leaves `PT` out keeps.
    pub(super) presets: BTreeMap<String, Preset>,
}

impl Known {
    /// Forgets every value (a new program body, whose start depends on earlier scans).
    pub(super) fn clear(&mut self) {
        self.values.clear();
        self.temps.clear();
        self.presets.clear();
    }

    /// The preset of the timers `e` calls, a literal kept for later calls.
    fn note_timers(&mut self, e: &BoolExpr) {
        walk(e, &mut |b| {
            if let BoolExpr::Timer(t) = b
                && t.called
            {
                match &t.preset {
                    p @ Preset::Micros { .. } => {
                        self.presets.insert(t.accumulator.clone(), p.clone())
                    }
                    Preset::Variable { .. } => self.presets.remove(&t.accumulator),
                };
            }
        });
    }

    /// Whether the bit `x` is known to be set.
    pub(super) fn is_set(&self, x: &str) -> bool {
        self.values.get(x) == Some(&1)
    }
}

impl Lowering<'_> {
    /// The value of `e` here, else the operand that is not known (described).
    pub(super) fn known_bool(&self, e: &BoolExpr) -> Result<bool, String> {
        let k = &self.known;
        match e {
            BoolExpr::Const(b) => Ok(*b),
            BoolExpr::Var(x) => match k.values.get(x) {
                Some(v) => Ok(*v != 0),
                None if k.assumed.contains(x) => Ok(false),
                None => Err(format!("`{x}`")),
            },
            BoolExpr::Temp(t) => {
                k.temps.get(t).copied().ok_or_else(|| "a value computed by a call".into())
            }
            BoolExpr::Not(x) => self.known_bool(x).map(|v| !v),
            BoolExpr::And(a, b) => match (self.known_bool(a), self.known_bool(b)) {
                (Ok(false), _) | (_, Ok(false)) => Ok(false),
                (Ok(_), Ok(_)) => Ok(true),
                (Err(e), _) | (_, Err(e)) => Err(e),
            },
            BoolExpr::Or(xs) => {
                let vs: Vec<Result<bool, String>> = xs.iter().map(|x| self.known_bool(x)).collect();
                if vs.iter().any(|v| matches!(v, Ok(true))) {
                    return Ok(true);
                }
                vs.into_iter().try_fold(false, |acc, v| v.map(|v| acc || v))
            }
            BoolExpr::Timer(t) => Err(format!("the output of the timer `{}`", t.accumulator)),
            BoolExpr::Edge { memory, .. } => Err(format!("the edge detector `{}`", memory.base)),
            BoolExpr::Fresh(f) => Err(format!("a value that is not computed ({})", f.why)),
            BoolExpr::Compare(c) => {
                let (a, b) = (self.known_int(&c.a, c.ty)?, self.known_int(&c.b, c.ty)?);
                Ok(c.ty.holds(c.op, a, b))
            }
        }
    }

    /// The value of `e` computed in `ty` here (every operation wraps to it, as the scan
    /// model's integers do), else the operand that is not known.
    pub(super) fn known_int(&self, e: &IntExpr, ty: IntType) -> Result<i64, String> {
        let two = |a: &IntExpr, b: &IntExpr, f: fn(i64, i64) -> i64| -> Result<i64, String> {
            Ok(ty.wrap(f(self.known_int(a, ty)?, self.known_int(b, ty)?)))
        };
        match e {
            IntExpr::Const(v) => Ok(ty.wrap(*v)),
            IntExpr::Var(x) => {
                self.known.values.get(x).map(|v| ty.wrap(*v)).ok_or_else(|| format!("`{x}`"))
            }
            IntExpr::Add(a, b) => two(a, b, i64::wrapping_add),
            IntExpr::Sub(a, b) => two(a, b, i64::wrapping_sub),
            IntExpr::Mul(a, b) => two(a, b, i64::wrapping_mul),
            IntExpr::Div(a, k) => Ok(ty.wrap(self.known_int(a, ty)?.wrapping_div(*k))),
            IntExpr::Mod(a, k) => Ok(ty.wrap(self.known_int(a, ty)?.wrapping_rem(*k))),
            IntExpr::DivBy(a, b) => two(a, b, |x, y| if y == 0 { 0 } else { x.wrapping_div(y) }),
            IntExpr::ModBy(a, b) => two(a, b, |x, y| if y == 0 { 0 } else { x.wrapping_rem(y) }),
            IntExpr::Cast(a, inner) => Ok(ty.wrap(self.known_int(a, *inner)?)),
            IntExpr::Real(op, a, b) => {
                Ok(op.apply_in(ty, self.known_int(a, ty)?, self.known_int(b, ty)?))
            }
            IntExpr::Sqrt(a) => Ok(crate::program::real::sqrt_in(ty, self.known_int(a, ty)?)),
            IntExpr::FromReal(a, unsigned) => {
                let a = self.known_int(a, crate::program::IntType::REAL)?;
                Ok(ty.wrap(crate::program::real::to_int(a, *unsigned).unwrap_or(0)))
            }
            IntExpr::ToReal(a, inner) => {
                Ok(crate::program::real::convert(self.known_int(a, *inner)?, *inner, ty))
            }
            IntExpr::Bitwise(op, a, b) => {
                Ok(ty.wrap(op.apply(self.known_int(a, ty)?, self.known_int(b, ty)?)))
            }
            IntExpr::Shift(a, k) => Ok(ty.wrap(crate::program::shift(self.known_int(a, ty)?, *k))),
            IntExpr::Checked(c) => {
                let (a, b) = (self.known_int(&c.a, c.ty)?, self.known_int(&c.b, c.ty)?);
                let v = c.op.apply(a, b, c.ty).ok_or_else(|| format!("`{}`", c.undefined))?;
                Ok(ty.wrap(v))
            }
            IntExpr::Ite(c, a, b) => match self.known_bool(c) {
                Ok(true) => self.known_int(a, ty),
                Ok(false) => self.known_int(b, ty),
                Err(e) => match (self.known_int(a, ty), self.known_int(b, ty)) {
                    (Ok(x), Ok(y)) if x == y => Ok(x),
                    _ => Err(e),
                },
            },
        }
    }

    /// Runs `stmts` on the known values, as the scan runs them.
    pub(super) fn run_known(&mut self, stmts: &[Stmt]) {
        for s in stmts {
            self.run_known_one(s);
        }
    }

    fn run_known_one(&mut self, s: &Stmt) {
        if let Stmt::Let { value, .. } | Stmt::Write { value, .. } = s {
            self.known.note_timers(value);
        }
        match s {
            Stmt::Let { temp, value } => match self.known_bool(value) {
                Ok(v) => {
                    self.known.temps.insert(*temp, v);
                }
                Err(_) => {
                    self.known.temps.remove(temp);
                }
            },
            Stmt::Write { target, kind, value, .. } => {
                let v = self.known_bool(value);
                let now = self.known.values.get(target).copied();
                let new = match (kind, v) {
                    (WriteKind::Assign, Ok(v)) => Some(i64::from(v)),
                    (WriteKind::AssignNot, Ok(v)) => Some(i64::from(!v)),
                    (WriteKind::Set, Ok(true)) => Some(1),
                    (WriteKind::Reset, Ok(true)) => Some(0),
                    (WriteKind::Set | WriteKind::Reset, Ok(false)) => now,
                    (WriteKind::Set, Err(_)) => now.filter(|v| *v == 1),
                    (WriteKind::Reset, Err(_)) => now.filter(|v| *v == 0),
                    _ => None,
                };
                match new {
                    Some(v) => self.known.values.insert(target.clone(), v),
                    None => self.known.values.remove(target),
                };
            }
            Stmt::If { branches, otherwise, .. } => {
                for (k, (c, body)) in branches.iter().enumerate() {
                    match self.known_bool(c) {
                        Ok(true) => return self.run_known(body),
                        Ok(false) => {}
                        Err(_) => {
                            for (_, b) in &branches[k..] {
                                self.forget(b);
                            }
                            return self.forget(otherwise);
                        }
                    }
                }
                self.run_known(otherwise);
            }
            Stmt::SetInt { target, value, .. } => {
                match self.ints.get(target).map(|v| v.ty).map(|t| self.known_int(value, t)) {
                    Some(Ok(v)) => self.known.values.insert(target.clone(), v),
                    _ => self.known.values.remove(target),
                };
            }
            Stmt::Warn { .. } => {}
        }
    }

    /// Forgets what `stmts` write (they may or may not run).
    pub(super) fn forget(&mut self, stmts: &[Stmt]) {
        let known = &mut self.known;
        for s in stmts {
            s.visit(
                &mut |s| match s {
                    Stmt::Write { target, .. } | Stmt::SetInt { target, .. } => {
                        known.values.remove(target);
                    }
                    Stmt::Let { temp, .. } => {
                        known.temps.remove(temp);
                    }
                    _ => {}
                },
                &mut |e| {
                    if let BoolExpr::Timer(t) = e {
                        known.presets.remove(&t.accumulator);
                    }
                },
            );
        }
    }
}
