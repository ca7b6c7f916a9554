//! LDmicro timers the algebra cannot express, as exact integer accumulators of the scan model: RTO, RTL, THI, TLO, TCY, a TON with a variable delay, and a TON/TOF whose accumulator another element writes or reads.
//!
//! The accumulator `T` counts scans exactly as LDmicro's generated code does
//! (`intcode.cpp`, the same in orig 2.x and new; ldmicro.md §6.3), with `lt` the
//! comparison `T < P` made as the element runs:
//!
//! * TON: `if i { if lt { T := T+1 } } else { T := 0 }`, output `i · ¬lt`;
//! * TOF: `if ¬i { if lt { T := T+1 } } else { T := 0 }`, output `i + lt`;
//! * RTO: `if lt ∧ i { T := T+1 }`, RTL: `if lt ∧ ¬i { T := T+1 }`, output `¬lt`.
//!
//! `P` is `floor(delay/cycle) + adjust`, or a TON's delay variable. A TOF's accumulator
//! starts at `P`: new LDmicro sets it before the first scan (the last TOF of that name
//! wins); orig loads it when its first TOF runs in the first scan (an "antiglitch" bit
//! per name), which is the same unless an element before that TOF touches the
//! accumulator or TOFs of that name count to different periods: such an accumulator is
//! not computed. THI, TLO and TCY keep state bits besides the count ([`Lowering::pulse`],
//! and the TCY arm of [`Lowering::int_timer`]).

use std::collections::{BTreeMap, BTreeSet};

use super::{Lowering, bytes_needed, int_names};
use crate::ladder::ldmicro::{Element, ElementKind, LdProgram, Operand, TimerDelay, TimerKind};
use crate::program::{BoolExpr, CmpOp, Compare, IntExpr, IntType, IntVar, canonical};

/// `b = 1` for a hidden 1-bit integer.
fn is_set(b: &str) -> BoolExpr {
    let (a, b) = (IntExpr::Var(b.to_string()), IntExpr::Const(1));
    BoolExpr::Compare(Box::new(Compare { op: CmpOp::Eq, ty: IntType::BIT, a, b }))
}

/// The timers whose accumulator is an integer of the scan model: every RTO and RTL,
/// every TON with a variable delay, and every TON/TOF whose accumulator another element
/// of the rungs that run also writes (`RES`, `MOVE`, a SHIFT_REGISTER stage, `PERSIST`,
/// another timer) or reads (a comparison, arithmetic, a counter of that name).
pub(super) fn integer_timers(live: &[&Element]) -> BTreeSet<String> {
    let mut writers: BTreeMap<String, usize> = BTreeMap::new();
    let mut mentioned: BTreeSet<String> = BTreeSet::new();
    for e in live {
        if matches!(e.kind, ElementKind::Coil { .. }) {
            continue;
        }
        for n in e.names_written() {
            *writers.entry(n).or_default() += 1;
        }
        if !matches!(e.kind, ElementKind::Timer { .. }) {
            mentioned.extend(int_names(e));
        }
    }
    live.iter()
        .filter_map(|e| match &e.kind {
            ElementKind::Timer { kind, name, delay, .. } => {
                let own = !matches!(kind, TimerKind::Ton | TimerKind::Tof)
                    || (*kind == TimerKind::Ton && matches!(delay, TimerDelay::Variable(_)));
                let shared =
                    writers.get(name).copied().unwrap_or(0) > 1 || mentioned.contains(name);
                (own || shared).then(|| name.clone())
            }
            _ => None,
        })
        .collect()
}

/// What the timers say about the integers (see [`super::integers`]).
#[derive(Default)]
pub(super) struct Accumulators {
    /// The accumulators of every timer.
    pub names: BTreeSet<String>,
    /// Why each timer accumulator that is not computed is not.
    pub causes: BTreeMap<String, String>,
    /// The power-up value of a TOF's accumulator (its `P`).
    pub init: BTreeMap<String, i64>,
    /// new: how many bytes LDmicro gives an accumulator (`byteNeeded` of its delay in
    /// scans, `TestTimerPeriod`), for the timers with a literal delay.
    pub bytes: BTreeMap<String, u32>,
}

impl Accumulators {
    /// The accumulators of the live elements `live` of `program`.
    pub(super) fn new(program: &LdProgram, live: &[&Element]) -> Accumulators {
        let orig = program.version.is_orig();
        let modelled = integer_timers(live);
        let mut acc = Accumulators::default();
        let mut sizes: BTreeMap<String, BTreeSet<u32>> = BTreeMap::new();
        let cause = |causes: &mut BTreeMap<String, String>, name: &str, why: String| {
            causes.entry(name.to_string()).or_insert(why);
        };
        // orig: the names whose first TOF has been met, and every name touched so far.
        let mut tof_seen: BTreeSet<String> = BTreeSet::new();
        let mut touched: BTreeSet<String> = BTreeSet::new();
        // The names a timer with a variable delay counts in.
        let mut variable: BTreeSet<String> = BTreeSet::new();
        for e in live {
            let ElementKind::Timer { kind, name, delay, adjust, .. } = &e.kind else {
                touched.extend(int_names(e));
                touched.extend(e.names_written());
                continue;
            };
            let keyword = e.kind.keyword();
            acc.names.insert(name.clone());
            if !modelled.contains(name) {
                cause(&mut acc.causes, name, "it is a timer's count".to_string());
                touched.insert(name.clone());
                continue;
            }
            match delay {
                TimerDelay::Variable(v)
                    if matches!(kind, TimerKind::Tof | TimerKind::Rto | TimerKind::Rtl) =>
                {
                    let why = format!(
                        "it is the count of a {keyword} with the variable delay {v}, whose \
                         period LDmicro computes from a literal delay only"
                    );
                    cause(&mut acc.causes, name, why);
                }
                TimerDelay::Variable(_) => {
                    variable.insert(name.clone());
                }
                TimerDelay::Micros(_) if program.cycle_us == 0 => {
                    cause(&mut acc.causes, name, "the PLC cycle is 0".into());
                }
                TimerDelay::Micros(us) => {
                    let n = us / program.cycle_us;
                    let p = program.timer_scans(delay, *adjust).unwrap_or(i64::MAX);
                    if !(1..=i64::from(i16::MAX)).contains(&p) {
                        let why = format!(
                            "its {keyword} counts to {p} scans, outside the 1..32767 LDmicro \
                             accepts"
                        );
                        cause(&mut acc.causes, name, why);
                    }
                    if !orig {
                        let size = bytes_needed(i64::try_from(n).unwrap_or(i64::MAX));
                        let max = (1i64 << (8 * size.min(4) - 1)) - 1;
                        if p > max {
                            let why = format!(
                                "LDmicro stores it in {size} byte(s), too few for its period \
                                 of {p} scans"
                            );
                            cause(&mut acc.causes, name, why);
                        }
                        sizes.entry(name.clone()).or_default().insert(size);
                    }
                    if *kind == TimerKind::Tof {
                        if !orig {
                            acc.init.insert(name.clone(), p);
                        } else if tof_seen.insert(name.clone()) {
                            if touched.contains(name) {
                                let why = "orig LDmicro loads it when its first TOF runs in the \
                                           first scan, after an element before that TOF \
                                           touched it"
                                    .to_string();
                                cause(&mut acc.causes, name, why);
                            }
                            acc.init.insert(name.clone(), p);
                        } else if acc.init.get(name) != Some(&p) {
                            // A 0.1 file run by new LDmicro takes the last TOF's `P`.
                            let why = "its TOFs count to different periods, and orig LDmicro \
                                       loads the first one's where new loads the last one's"
                                .to_string();
                            cause(&mut acc.causes, name, why);
                        }
                    }
                }
            }
            touched.insert(name.clone());
        }
        for (name, set) in sizes {
            if variable.contains(&name) {
                // The size comes from the literal delays only, and the variable delay may
                // pass what it holds.
                let why = "a timer with a variable delay counts in it, in the size another \
                           timer's literal delay gives it"
                    .to_string();
                cause(&mut acc.causes, &name, why);
                continue;
            }
            match set.iter().next() {
                Some(size) if set.len() == 1 => {
                    acc.bytes.insert(name, *size);
                }
                _ => {
                    let why = "its timers give it different sizes in LDmicro".to_string();
                    cause(&mut acc.causes, &name, why);
                }
            }
        }
        acc
    }
}

impl Lowering<'_> {
    /// The hidden 1-bit integer `k` of element `e` (see [`super::timer_bits`]), 0 at
    /// power-up.
    fn hidden_bit(&mut self, e: &Element, k: u8) -> String {
        let index = self.element_index(e);
        let bit = canonical(self.timer_bits.get(&(index, k)).map_or("", String::as_str));
        self.hidden_bits.insert(bit.clone());
        self.ints.insert(bit.clone(), IntVar { ty: IntType::BIT, input: false, init: 0 });
        bit
    }

    /// A timer whose accumulator is an integer of the scan model (see
    /// [`integer_timers`]): its output.
    pub(super) fn int_timer(&mut self, e: &Element, input: BoolExpr) -> BoolExpr {
        let ElementKind::Timer { kind, name, delay, adjust, .. } = &e.kind else { return input };
        let acc = canonical(name);
        if !self.ints.contains_key(&acc) {
            let why = match self.opaque.get(name) {
                Some(why) => format!("the accumulator {name} is not computed: {why}"),
                None => format!("the accumulator {name} is not computed"),
            };
            return self.fresh(format!("{}_{name}", e.kind.keyword()), e, &why);
        }
        let p = match delay {
            TimerDelay::Variable(v) => Operand::Var(v.clone()),
            TimerDelay::Micros(_) => {
                Operand::Literal(self.program.timer_scans(delay, *adjust).unwrap_or(0))
            }
        };
        let t = || IntExpr::Var(acc.clone());
        let lt = self.compare(CmpOp::Lt, &Operand::Var(name.clone()), &p);
        let lt = self.temp(lt);
        let step = IntExpr::plus(t(), IntExpr::Const(1));
        let not_input = || BoolExpr::negate(input.clone());
        match kind {
            TimerKind::Ton | TimerKind::Tof => {
                let on = *kind == TimerKind::Ton;
                let counting = if on { input.clone() } else { not_input() };
                let power = self.temp(BoolExpr::and(counting, lt.clone()));
                self.set_int(e, name, &power, step);
                let clear = if on { not_input() } else { input.clone() };
                self.set_int(e, name, &clear, IntExpr::Const(0));
                if on {
                    self.temp(BoolExpr::and(input, BoolExpr::negate(lt)))
                } else {
                    self.temp(BoolExpr::Or(vec![input, lt]))
                }
            }
            TimerKind::Rto | TimerKind::Rtl => {
                let counting = if *kind == TimerKind::Rto { input.clone() } else { not_input() };
                let power = self.temp(BoolExpr::and(counting, lt.clone()));
                self.set_int(e, name, &power, step);
                self.temp(BoolExpr::negate(lt))
            }
            TimerKind::Thi | TimerKind::Tlo => self.pulse(e, *kind == TimerKind::Thi, input, lt),
            TimerKind::Tcy => {
                // `intcode.cpp`, `ELEM_TCY` (`NEW_TON` undefined): while `i`, count to
                // `P`, then clear the count and flip the phase bit; the output is `i`
                // and the phase; `¬i` clears the count and keeps the phase.
                let phase = self.hidden_bit(e, 0);
                let on = || is_set(&phase);
                let counting = self.temp(BoolExpr::and(input.clone(), lt.clone()));
                self.set_int(e, name, &counting, step);
                let flip = self.temp(BoolExpr::and(input.clone(), BoolExpr::negate(lt)));
                self.set_int(e, name, &flip, IntExpr::Const(0));
                let flipped = IntExpr::minus(IntExpr::Const(1), IntExpr::Var(phase.clone()));
                self.set_int(e, &phase, &flip, flipped);
                self.set_int(e, name, &not_input(), IntExpr::Const(0));
                self.temp(BoolExpr::and(input, on()))
            }
        }
    }

    /// THI (`high`) or TLO, `intcode.cpp` `ELEM_THI` / `ELEM_TLO`, with `lt` the
    /// comparison `T < P` made as the element runs. THI: `i` sets the bit `s`; while
    /// `s`, the output is 1 and the count grows until `P`; at `P` the output is 0, and
    /// once `i` is low the count and `s` clear. TLO mirrors it on a falling edge: `s`
    /// is set when `i` is low after it has been high once (the bit `h`), the output is
    /// 0 while counting, then 1, the count and `s` clearing once `i` is high; with `s`
    /// clear the output is `h`.
    fn pulse(&mut self, e: &Element, high: bool, input: BoolExpr, lt: BoolExpr) -> BoolExpr {
        let ElementKind::Timer { name, .. } = &e.kind else { return input };
        let s = self.hidden_bit(e, 0);
        let t = IntExpr::Var(canonical(name));
        let not_input = || BoolExpr::negate(input.clone());
        let (arm, h_now) = if high {
            (input.clone(), None)
        } else {
            let h = self.hidden_bit(e, 1);
            let arm = self.temp(BoolExpr::and(not_input(), is_set(&h)));
            let h_now = self.temp(BoolExpr::Or(vec![is_set(&h), input.clone()]));
            self.set_int(e, &h, &input, IntExpr::Const(1));
            (arm, Some(h_now))
        };
        let s_now = self.temp(BoolExpr::Or(vec![is_set(&s), arm.clone()]));
        self.set_int(e, &s, &arm, IntExpr::Const(1));
        let lt = self.temp(BoolExpr::and(s_now.clone(), lt));
        let done = self.temp(BoolExpr::and(s_now.clone(), BoolExpr::negate(lt.clone())));
        self.set_int(e, name, &lt, IntExpr::plus(t, IntExpr::Const(1)));
        let release = if high { not_input() } else { input.clone() };
        let clear = self.temp(BoolExpr::and(done.clone(), release));
        self.set_int(e, name, &clear, IntExpr::Const(0));
        self.set_int(e, &s, &clear, IntExpr::Const(0));
        match h_now {
            None => lt,
            Some(h) => {
                self.temp(BoolExpr::Or(vec![done, BoolExpr::and(BoolExpr::negate(s_now), h)]))
            }
        }
    }
}
