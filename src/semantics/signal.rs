//! Signals on a finite horizon `(0, H]`: exact piecewise-constant 0/1 functions, with the operators of the II algebra.
//!
//! A [`Signal`] is stored as breakpoints `0 = b0 < b1 < … < bn = H` (exact
//! rationals), a value on each open interval `(b(i−1), b(i))` and a value at
//! each breakpoint `b(i)`, `i ≥ 1`. It is kept normalised (a breakpoint below
//! `H` whose value equals the values on both sides is dropped), so `==` is
//! equality of the functions on `(0, H]`.
//!
//! Every operator is causal (its value at `t` depends only on `(0, t]`), so
//! computing it on `(0, H]` is exact, not an approximation of the signal on
//! `(0, ∞)`. Every operator matches `/work/shared/spec/semantics.md` exactly; the tests
//! in `tests/suite/semantics.rs` check each one against a brute-force evaluation of
//! its quantified definition.

use std::fmt;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

use crate::term::{Delay, format_decimal};

/// An instant, in seconds, exactly.
pub type Time = BigRational;

/// A 0/1 signal on the horizon `(0, H]`, normalised so that `==` is semantic equality.
#[derive(Clone, PartialEq, Eq, Hash)]
pub struct Signal {
    horizon: Time,
    /// `b1 … bn`, strictly increasing, `bn == horizon`; never empty.
    breaks: Vec<Time>,
    /// `open[i]` is the value on `(b(i), b(i+1))` with `b(0) = 0` (0-based: the
    /// open interval that ends at `breaks[i]`).
    open: Vec<bool>,
    /// `point[i]` is the value at `breaks[i]`.
    point: Vec<bool>,
}

fn zero() -> Time {
    Time::zero()
}

fn two() -> Time {
    Time::from_integer(BigInt::from(2))
}

fn midpoint(a: &Time, b: &Time) -> Time {
    (a + b) / two()
}

/// Writes an instant as a plain decimal (`1.25`) when it is one, else as `p/q`.
pub fn format_time(t: &Time) -> String {
    let mut den = t.denom().clone();
    for p in [2u32, 5] {
        let p = BigInt::from(p);
        while !den.is_zero() && (&den % &p).is_zero() {
            den /= &p;
        }
    }
    if den.is_one()
        && let Some(text) = format_decimal(t)
    {
        return text;
    }
    format!("{}/{}", t.numer(), t.denom())
}

impl Signal {
    /// The constant signal `value` on `(0, horizon]`.
    ///
    /// The horizon should be positive; a non-positive one gives a degenerate
    /// signal (harmless, but meaningless) rather than a panic. [`Signal::from_parts`]
    /// and [`Signal::from_steps`] reject it.
    pub fn constant(horizon: Time, value: bool) -> Signal {
        Signal { breaks: vec![horizon.clone()], horizon, open: vec![value], point: vec![value] }
    }

    /// A signal from its raw parts: `breakpoints` are `b1 … bn` (strictly
    /// increasing, positive, the last equal to `horizon`), `open_values[i]` is
    /// the value on the open interval that ends at `breakpoints[i]`, and
    /// `point_values[i]` the value at `breakpoints[i]`. The result is normalised.
    pub fn from_parts(
        horizon: Time,
        breakpoints: Vec<Time>,
        open_values: Vec<bool>,
        point_values: Vec<bool>,
    ) -> Result<Signal, String> {
        if !horizon.is_positive() {
            return Err(format!("the horizon must be positive, not {}", format_time(&horizon)));
        }
        if breakpoints.is_empty() {
            return Err("a signal needs at least one breakpoint (the horizon)".to_string());
        }
        if open_values.len() != breakpoints.len() || point_values.len() != breakpoints.len() {
            return Err(format!(
                "{} breakpoints need as many open values and point values (got {} and {})",
                breakpoints.len(),
                open_values.len(),
                point_values.len()
            ));
        }
        let mut previous = zero();
        for b in &breakpoints {
            if *b <= previous {
                return Err(format!(
                    "breakpoints must be positive and strictly increasing ({} after {})",
                    format_time(b),
                    format_time(&previous)
                ));
            }
            previous = b.clone();
        }
        if previous != horizon {
            return Err(format!(
                "the last breakpoint {} must be the horizon {}",
                format_time(&previous),
                format_time(&horizon)
            ));
        }
        Ok(Signal { horizon, breaks: breakpoints, open: open_values, point: point_values }
            .normalised())
    }

    /// A signal from right-continuous steps: `initial` on `(0, t1)`, then each
    /// `(t, v)` of `changes` makes the value `v` from `t` on (at `t` included).
    /// The change instants must be strictly increasing and in `(0, horizon]`.
    pub fn from_steps(
        horizon: Time,
        initial: bool,
        changes: &[(Time, bool)],
    ) -> Result<Signal, String> {
        if !horizon.is_positive() {
            return Err(format!("the horizon must be positive, not {}", format_time(&horizon)));
        }
        let mut breaks = Vec::new();
        let mut open = Vec::new();
        let mut point = Vec::new();
        let mut current = initial;
        let mut at_horizon = None;
        let mut previous = zero();
        for (t, v) in changes {
            if *t <= previous {
                return Err(format!(
                    "change instants must be positive and strictly increasing ({} after {})",
                    format_time(t),
                    format_time(&previous)
                ));
            }
            if *t > horizon {
                return Err(format!(
                    "the change at {} is after the horizon {}",
                    format_time(t),
                    format_time(&horizon)
                ));
            }
            previous = t.clone();
            if *t == horizon {
                at_horizon = Some(*v);
            } else {
                breaks.push(t.clone());
                open.push(current);
                point.push(*v);
            }
            current = *v;
        }
        breaks.push(horizon.clone());
        open.push(if at_horizon.is_some() {
            // The value before the last change.
            *point.last().unwrap_or(&initial)
        } else {
            current
        });
        point.push(at_horizon.unwrap_or(current));
        Ok(Signal { horizon, breaks, open, point }.normalised())
    }

    /// The signal equal to `value(t)` on `(0, horizon]`, where `value` must be
    /// constant on every open interval between consecutive `candidates`
    /// (candidates outside `(0, horizon)` are ignored; `horizon` is always one).
    /// `value` is called at every candidate and at the midpoint of every gap.
    pub fn from_fn(horizon: Time, candidates: Vec<Time>, value: impl Fn(&Time) -> bool) -> Signal {
        let mut cuts: Vec<Time> =
            candidates.into_iter().filter(|c| c.is_positive() && *c < horizon).collect();
        cuts.push(horizon.clone());
        cuts.sort();
        cuts.dedup();
        let mut open = Vec::with_capacity(cuts.len());
        let mut point = Vec::with_capacity(cuts.len());
        let mut previous = zero();
        for c in &cuts {
            open.push(value(&midpoint(&previous, c)));
            point.push(value(c));
            previous = c.clone();
        }
        Signal { horizon, breaks: cuts, open, point }.normalised()
    }

    fn normalised(self) -> Signal {
        let n = self.breaks.len();
        let mut breaks = Vec::with_capacity(n);
        let mut open = Vec::with_capacity(n);
        let mut point = Vec::with_capacity(n);
        for (i, b) in self.breaks.into_iter().enumerate() {
            let redundant =
                i + 1 < n && self.point[i] == self.open[i] && self.open[i] == self.open[i + 1];
            if !redundant {
                breaks.push(b);
                open.push(self.open[i]);
                point.push(self.point[i]);
            }
        }
        Signal { horizon: self.horizon, breaks, open, point }
    }

    /// Checks the representation invariants (for tests): breakpoints strictly
    /// increasing and positive, the last one the horizon, and normalised.
    pub fn check_invariants(&self) -> Result<(), String> {
        let n = self.breaks.len();
        if n == 0 || self.open.len() != n || self.point.len() != n {
            return Err("inconsistent lengths".to_string());
        }
        if self.breaks[n - 1] != self.horizon {
            return Err("the last breakpoint is not the horizon".to_string());
        }
        let mut previous = zero();
        for (i, b) in self.breaks.iter().enumerate() {
            if *b <= previous {
                return Err(format!("breakpoint {} out of order", format_time(b)));
            }
            previous = b.clone();
            if i + 1 < n && self.point[i] == self.open[i] && self.open[i] == self.open[i + 1] {
                return Err(format!("breakpoint {} is redundant", format_time(b)));
            }
        }
        Ok(())
    }

    /// The horizon `H`: the signal is defined on `(0, H]`.
    pub fn horizon(&self) -> &Time {
        &self.horizon
    }

    /// The breakpoints `b1 … bn` (the last is the horizon).
    pub fn breakpoints(&self) -> &[Time] {
        &self.breaks
    }

    /// The values on the open intervals: the `i`-th is the value on the
    /// interval that ends at `breakpoints()[i]`.
    pub fn open_values(&self) -> &[bool] {
        &self.open
    }

    /// The values at the breakpoints: the `i`-th is the value at `breakpoints()[i]`.
    pub fn point_values(&self) -> &[bool] {
        &self.point
    }

    /// The value on the open interval that ends at `breakpoints()[i]`
    /// (0-based), or `None` if there is no such breakpoint.
    pub fn value_on_interval(&self, i: usize) -> Option<bool> {
        self.open.get(i).copied()
    }

    /// The value at `breakpoints()[i]` (0-based), or `None` if there is no such breakpoint.
    pub fn value_at_breakpoint(&self, i: usize) -> Option<bool> {
        self.point.get(i).copied()
    }

    /// Is the signal constant (with this value) on the whole horizon?
    pub fn as_constant(&self) -> Option<bool> {
        let v = self.point[0];
        (self.open.iter().chain(&self.point).all(|&x| x == v)).then_some(v)
    }

    /// The value at `t`, for `t` in `(0, H]`. Outside, the nearest meaningful
    /// answer: the value just after 0 for `t ≤ 0`, the value at `H` for `t > H`.
    pub fn value_at(&self, t: &Time) -> bool {
        if !t.is_positive() {
            return self.open[0];
        }
        let i = self.breaks.partition_point(|b| b < t);
        match self.breaks.get(i) {
            None => self.point[self.point.len() - 1],
            Some(b) if b == t => self.point[i],
            Some(_) => self.open[i],
        }
    }

    /// The left limit at `t` (the value just before `t`), for `t` in `(0, H]`.
    /// Outside: the value just after 0 for `t ≤ 0`, the value at `H` for `t > H`.
    pub fn left_limit(&self, t: &Time) -> bool {
        if !t.is_positive() {
            return self.open[0];
        }
        let i = self.breaks.partition_point(|b| b < t);
        match self.open.get(i) {
            None => self.point[self.point.len() - 1],
            Some(&v) => v,
        }
    }

    /// Which values the signal takes on `(a, b] ∩ (0, H]`: `(some 1, some 0)`.
    fn window(&self, a: &Time, b: &Time) -> (bool, bool) {
        let a = if a.is_negative() { zero() } else { a.clone() };
        let b = if *b > self.horizon { self.horizon.clone() } else { b.clone() };
        let (mut one, mut nought) = (false, false);
        if a >= b {
            return (one, nought);
        }
        let start = self.breaks.partition_point(|x| *x <= a);
        for i in start..self.breaks.len() {
            let lo = if i == 0 { zero() } else { self.breaks[i - 1].clone() };
            if lo >= b {
                break;
            }
            // The open interval ends after `a` and starts before `b`: it meets (a, b].
            if self.open[i] {
                one = true
            } else {
                nought = true
            }
            if self.breaks[i] <= b {
                if self.point[i] { one = true } else { nought = true }
            }
        }
        (one, nought)
    }

    /// Is the signal 1 at every instant of `(a, b] ∩ (0, H]`? (True if that is empty.)
    pub fn all_on(&self, a: &Time, b: &Time) -> bool {
        !self.window(a, b).1
    }

    /// Is the signal 1 at some instant of `(a, b] ∩ (0, H]`? (False if that is empty.)
    pub fn any_on(&self, a: &Time, b: &Time) -> bool {
        self.window(a, b).0
    }

    /// The same signal on the shorter horizon `(0, horizon]` (unchanged if
    /// `horizon` is not shorter, or not positive).
    pub fn restrict(&self, horizon: &Time) -> Signal {
        if *horizon >= self.horizon || !horizon.is_positive() {
            return self.clone();
        }
        Signal::from_fn(horizon.clone(), self.breaks.clone(), |t| self.value_at(t))
    }

    fn common_horizon(&self, other: &Signal) -> Time {
        if self.horizon <= other.horizon { self.horizon.clone() } else { other.horizon.clone() }
    }

    fn merged_cuts(&self, other: &Signal) -> Vec<Time> {
        let mut cuts: Vec<Time> = self.breaks.iter().chain(&other.breaks).cloned().collect();
        cuts.sort();
        cuts.dedup();
        cuts
    }

    /// Pointwise combination of two signals, on the common horizon.
    pub fn zip_with(&self, other: &Signal, op: impl Fn(bool, bool) -> bool) -> Signal {
        Signal::from_fn(self.common_horizon(other), self.merged_cuts(other), |t| {
            op(self.value_at(t), other.value_at(t))
        })
    }

    /// `¬f`.
    pub fn not(&self) -> Signal {
        Signal {
            horizon: self.horizon.clone(),
            breaks: self.breaks.clone(),
            open: self.open.iter().map(|v| !v).collect(),
            point: self.point.iter().map(|v| !v).collect(),
        }
    }

    /// `f · g` (on the common horizon if the horizons differ).
    pub fn and(&self, other: &Signal) -> Signal {
        self.zip_with(other, |a, b| a && b)
    }

    /// `f + g` (on the common horizon if the horizons differ).
    pub fn or(&self, other: &Signal) -> Signal {
        self.zip_with(other, |a, b| a || b)
    }

    /// The instants where a delay operator's result may change: `d`, every
    /// breakpoint, and every breakpoint plus `d`.
    fn delay_cuts(&self, d: &Time) -> Vec<Time> {
        let mut cuts = Vec::with_capacity(2 * self.breaks.len() + 1);
        cuts.push(d.clone());
        for b in &self.breaks {
            cuts.push(b.clone());
            cuts.push(b + d);
        }
        cuts
    }

    /// `d/f` (on-delay, TON): at `t`, `t ≥ d ∧ ∀τ ∈ (t−d, t]: f(τ)`.
    pub fn ton(&self, d: &Delay) -> Signal {
        let d = d.seconds();
        Signal::from_fn(self.horizon.clone(), self.delay_cuts(d), |t| {
            t >= d && self.all_on(&(t - d), t)
        })
    }

    /// `f/d` (off-delay, TOF): at `t`, `∃τ ∈ (max(0, t−d), t]: f(τ)`.
    pub fn tof(&self, d: &Delay) -> Signal {
        let d = d.seconds();
        Signal::from_fn(self.horizon.clone(), self.delay_cuts(d), |t| self.any_on(&(t - d), t))
    }

    /// `pre f` for scans of length `cycle` (scan `k` is `[k·c, (k+1)·c)`, the first
    /// `(0, c)`, the last one closed at the horizon): `f` one cycle earlier, and `init`
    /// (its value before the first scan) on the first scan.
    pub fn delayed(&self, cycle: &Time, init: bool) -> Signal {
        let mut cuts: Vec<Time> = self.breaks.iter().map(|b| b + cycle).collect();
        cuts.push(cycle.clone());
        Signal::from_fn(self.horizon.clone(), cuts, |t| {
            if t < cycle || (t == cycle && *t == self.horizon) {
                init
            } else if *t == self.horizon {
                // The horizon belongs to the last scan: one cycle back is the scan before.
                self.left_limit(&(t - cycle))
            } else if t == cycle {
                self.open[0]
            } else {
                self.value_at(&(t - cycle))
            }
        })
    }

    /// `SR(s, r)` (set dominant): at `t`,
    /// `∃t1 ∈ (0, t]: s(t1) ∧ ∀τ ∈ (t1, t]: s(τ) ∨ ¬r(τ)` — the PLC recurrence
    /// `Q := S + Q·¬R`. On the common horizon if the horizons differ.
    pub fn sr(s: &Signal, r: &Signal) -> Signal {
        let horizon = s.common_horizon(r);
        let cuts: Vec<Time> = s
            .merged_cuts(r)
            .into_iter()
            .filter(|c| *c < horizon)
            .chain(std::iter::once(horizon.clone()))
            .collect();
        // A forward scan over the pieces (open interval, point, open interval, …):
        // s = 1 sets, s = 0 ∧ r = 1 resets, otherwise the value is kept.
        let step = |q: bool, t: &Time| {
            let (sv, rv) = (s.value_at(t), r.value_at(t));
            sv || (q && !rv)
        };
        let mut q = false;
        let mut open = Vec::with_capacity(cuts.len());
        let mut point = Vec::with_capacity(cuts.len());
        let mut previous = zero();
        for c in &cuts {
            q = step(q, &midpoint(&previous, c));
            open.push(q);
            q = step(q, c);
            point.push(q);
            previous = c.clone();
        }
        Signal { horizon, breaks: cuts, open, point }.normalised()
    }

    /// `RS(s, r)` (reset dominant) = `SR(s·¬r, r)`.
    pub fn rs(s: &Signal, r: &Signal) -> Signal {
        Signal::sr(&s.and(&r.not()), r)
    }

    /// The first instant of the common horizon where `pred(self, other)` holds
    /// (a breakpoint or the midpoint of an open piece), if any.
    fn first_where(&self, other: &Signal, pred: impl Fn(bool, bool) -> bool) -> Option<Time> {
        let horizon = self.common_horizon(other);
        let mut previous = zero();
        for c in self.merged_cuts(other) {
            if c > horizon {
                break;
            }
            let mid = midpoint(&previous, &c);
            if pred(self.value_at(&mid), other.value_at(&mid)) {
                return Some(mid);
            }
            if pred(self.value_at(&c), other.value_at(&c)) {
                return Some(c);
            }
            previous = c;
        }
        None
    }

    /// An instant in `(0, H]` where the two signals differ (the earliest
    /// breakpoint, or an interior point of the earliest open piece), or `None`
    /// if they are equal. If the horizons differ, only the common part is compared.
    pub fn first_difference(&self, other: &Signal) -> Option<Time> {
        self.first_where(other, |a, b| a != b)
    }

    /// An instant where `self` is 1 and `other` is 0 (the earliest, as in
    /// [`Signal::first_difference`]), or `None` if `self ⇒ other`.
    pub fn first_violation_of_implication(&self, other: &Signal) -> Option<Time> {
        self.first_where(other, |a, b| a && !b)
    }

    /// Does `self ⇒ other` hold (on the common horizon)?
    pub fn implies(&self, other: &Signal) -> bool {
        self.first_violation_of_implication(other).is_none()
    }
}

impl fmt::Display for Signal {
    /// Writes the pieces in order: `(0,1):0 @1:1 (1,2]:0` reads "0 on (0,1),
    /// 1 at 1, 0 on (1,2]" (a half-closed piece when the breakpoint agrees
    /// with the interval before it).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let bit = |v: bool| if v { '1' } else { '0' };
        let mut previous = zero();
        for (i, b) in self.breaks.iter().enumerate() {
            if i > 0 {
                write!(f, " ")?;
            }
            let (lo, hi) = (format_time(&previous), format_time(b));
            if self.open[i] == self.point[i] {
                write!(f, "({lo},{hi}]:{}", bit(self.open[i]))?;
            } else {
                write!(f, "({lo},{hi}):{} @{hi}:{}", bit(self.open[i]), bit(self.point[i]))?;
            }
            previous = b.clone();
        }
        Ok(())
    }
}

impl fmt::Debug for Signal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Signal[{self}]")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> Time {
        Time::new(BigInt::from(n), BigInt::from(d))
    }

    fn int(n: i64) -> Time {
        q(n, 1)
    }

    #[test]
    fn normalisation_makes_equality_semantic() {
        let a = Signal::from_parts(
            int(3),
            vec![int(1), int(2), int(3)],
            vec![true, true, false],
            vec![true, true, false],
        )
        .unwrap();
        let b = Signal::from_steps(int(3), true, &[(q(2, 1), true), (q(5, 2), false)]).unwrap();
        // b has a redundant change at 2 and a right-continuous fall at 2.5.
        assert_ne!(a, b);
        let c = Signal::from_steps(int(3), true, &[(int(1), true), (int(2), false)]);
        let c = c.unwrap();
        assert_ne!(a, c); // a is 1 at 2, c is 0 at 2
        let d =
            Signal::from_parts(int(3), vec![int(2), int(3)], vec![true, false], vec![true, false])
                .unwrap();
        assert_eq!(a, d);
        assert_eq!(a.breakpoints().len(), 2);
        a.check_invariants().unwrap();
    }

    #[test]
    fn parts_are_validated() {
        assert!(Signal::from_parts(int(0), vec![int(0)], vec![true], vec![true]).is_err());
        assert!(Signal::from_parts(int(2), vec![int(1)], vec![true], vec![true]).is_err());
        assert!(
            Signal::from_parts(int(2), vec![int(1), int(1), int(2)], vec![true; 3], vec![true; 3])
                .is_err()
        );
        assert!(Signal::from_parts(int(2), vec![int(2)], vec![], vec![true]).is_err());
        assert!(Signal::from_steps(int(2), true, &[(int(3), false)]).is_err());
        assert!(Signal::from_steps(int(2), true, &[(int(0), false)]).is_err());
        assert!(Signal::from_steps(int(2), true, &[(int(1), false), (int(1), true)]).is_err());
    }

    #[test]
    fn steps_are_right_continuous() {
        let s = Signal::from_steps(int(4), false, &[(int(1), true), (int(4), false)]).unwrap();
        assert!(!s.value_at(&q(1, 2)));
        assert!(s.value_at(&int(1)));
        assert!(!s.left_limit(&int(1)));
        assert!(s.value_at(&q(7, 2)));
        assert!(!s.value_at(&int(4)));
        assert!(s.left_limit(&int(4)));
        assert_eq!(s.to_string(), "(0,1):0 @1:1 (1,4):1 @4:0");
    }

    #[test]
    fn display_is_readable() {
        let s = Signal::from_parts(
            int(3),
            vec![int(1), q(3, 2), int(3)],
            vec![false, false, true],
            vec![true, false, true],
        )
        .unwrap();
        assert_eq!(s.to_string(), "(0,1):0 @1:1 (1,1.5]:0 (1.5,3]:1");
        let third = Signal::from_steps(int(1), false, &[(q(1, 3), true)]).unwrap();
        assert_eq!(format!("{third:?}"), "Signal[(0,1/3):0 @1/3:1 (1/3,1]:1]");
    }

    #[test]
    fn degenerate_inputs_do_not_panic() {
        let d: Delay = "1s".parse().unwrap();
        for h in [int(0), int(-3)] {
            let c = Signal::constant(h.clone(), true);
            let _ = c.ton(&d).tof(&d).not().and(&c).or(&c);
            let _ = Signal::sr(&c, &c.not());
            let _ = Signal::rs(&c, &c);
            let _ = c.first_difference(&c.not());
            let _ = (c.value_at(&int(1)), c.left_limit(&int(-1)), c.to_string());
            assert!(Signal::from_steps(h, true, &[]).is_err());
        }
        let c = Signal::constant(int(2), true);
        assert!(c.value_at(&int(7)) && c.value_at(&int(-7)) && c.left_limit(&int(9)));
        assert_eq!(c.value_on_interval(5), None);
        assert_eq!(c.value_at_breakpoint(0), Some(true));
        assert_eq!(c.restrict(&int(-1)), c);
    }
}
