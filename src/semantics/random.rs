//! Proptest strategies for signals and assignments that produce the hard cases on purpose.
//!
//! All instants are exact rationals built from integer ratios. For one
//! assignment, every signal draws its change instants from a SHARED pool, so
//! several signals change at the same instant; the pool holds the chosen
//! delays, their sums and multiples, other instants shifted by the delays
//! (so `b + d` meets other breakpoints), and instants that are not multiples
//! of anything (`k/3`, `k/7`, instants close to 0). Signals are built from
//! pulses whose lengths are the delays, a little less, a little more, half,
//! double, sums of delays or zero (an isolated point), with independently
//! chosen values at both ends, so isolated points and both kinds of edges
//! occur. The horizon is larger than twice the sum of the delays.

use std::collections::BTreeMap;

use num_bigint::BigInt;
use num_traits::{Signed, ToPrimitive, Zero};
use proptest::prelude::*;
use proptest::sample::Index;

use super::eval::Assignment;
use super::signal::{Signal, Time};
use crate::term::{Delay, Symbol};

/// The delays the strategies choose from, as `(numerator, denominator)`
/// seconds: some multiples of one another (1, 2, 0.5, 0.25, 3), some not
/// (0.3, 0.7, 1.5, 0.2). Duplicates make the multiples more likely.
pub const DELAY_POOL: &[(i64, i64)] = &[
    (1, 1),
    (2, 1),
    (1, 2),
    (3, 10),
    (7, 10),
    (3, 2),
    (1, 4),
    (1, 5),
    (3, 1),
    (1, 1),
    (1, 2),
    (2, 1),
];

fn ratio(n: i64, d: i64) -> Time {
    Time::new(BigInt::from(n), BigInt::from(d))
}

/// The delay of a pool entry (every entry is a positive finite decimal).
fn pool_delay(n: i64, d: i64) -> Delay {
    Delay::new(ratio(n, d)).unwrap_or_else(|_| {
        // Unreachable for the constants above; one second is a safe fallback.
        Delay::from_micros(1_000_000).expect("one second is a delay")
    })
}

/// A delay from [`DELAY_POOL`].
pub fn delay_strategy() -> impl Strategy<Value = Delay> {
    prop::sample::select(DELAY_POOL.to_vec()).prop_map(|(n, d)| pool_delay(n, d))
}

/// The horizon used for these delays: an integer above twice their sum (at least 4).
pub fn horizon_for(delays: &[Delay]) -> Time {
    let sum = delays.iter().fold(Time::zero(), |acc, d| acc + d.seconds());
    let h = (sum * ratio(2, 1)).ceil() + ratio(1, 1);
    if h < ratio(4, 1) { ratio(4, 1) } else { h }
}

/// The shared pool of change instants in `(0, horizon]` for these delays,
/// around the given base instants.
pub fn time_pool(horizon: &Time, delays: &[Delay], base: &[Time]) -> Vec<Time> {
    let mut pool: Vec<Time> = Vec::new();
    let ds: Vec<&Time> = delays.iter().map(Delay::seconds).collect();
    for (i, d) in ds.iter().enumerate() {
        pool.push((*d).clone());
        pool.push(*d * ratio(2, 1));
        pool.push(*d * ratio(3, 1));
        for e in &ds[i + 1..] {
            pool.push(*d + *e);
            pool.push(*d + *e + *d);
        }
    }
    let all: Time = ds.iter().fold(Time::zero(), |acc, d| acc + *d);
    pool.push(all);
    for b in base {
        pool.push(b.clone());
        for d in &ds {
            pool.push(b + *d);
            pool.push(b - *d);
        }
    }
    pool.retain(|t| t.is_positive() && t <= horizon);
    pool.sort();
    pool.dedup();
    if pool.is_empty() {
        pool.push(horizon / ratio(2, 1));
    }
    pool
}

/// The pulse lengths for these delays: 0 (an isolated point), each delay,
/// a little less and a little more, half and double, sums of two delays,
/// `1/7`, and the horizon (a step that stays). Repeated entries weigh more.
pub fn length_pool(horizon: &Time, delays: &[Delay]) -> Vec<Time> {
    let eps = ratio(1, 20);
    let mut lengths = vec![Time::zero(), ratio(1, 7), horizon.clone()];
    let ds: Vec<&Time> = delays.iter().map(Delay::seconds).collect();
    for (i, d) in ds.iter().enumerate() {
        // The delay itself three times: pulses of exactly `d` are the hardest case.
        for _ in 0..3 {
            lengths.push((*d).clone());
        }
        lengths.push(*d + &eps);
        lengths.push(*d - &eps);
        lengths.push(*d / ratio(2, 1));
        lengths.push(*d * ratio(2, 1));
        for e in &ds[i + 1..] {
            lengths.push(*d + *e);
        }
    }
    if ds.is_empty() {
        lengths.push(ratio(1, 2));
        lengths.push(ratio(1, 1));
    }
    lengths.retain(|l| !l.is_negative());
    lengths.sort();
    lengths
}

/// `signal` with the value `inside` on `(start, end)`, `at_start` at `start`
/// and `at_end` at `end` (only `at_start` at `start` if the pulse is empty).
fn overlay(
    signal: &Signal,
    start: &Time,
    end: &Time,
    inside: bool,
    at_start: bool,
    at_end: bool,
) -> Signal {
    let mut cuts = signal.breakpoints().to_vec();
    cuts.push(start.clone());
    cuts.push(end.clone());
    Signal::from_fn(signal.horizon().clone(), cuts, |t| {
        if t == start {
            at_start
        } else if t == end {
            at_end
        } else if start < t && t < end {
            inside
        } else {
            signal.value_at(t)
        }
    })
}

/// Signals on `(0, horizon]` built from an initial value and up to six
/// pulses: each starts at an instant of `pool` and lasts a length of `lengths`
/// (zero: an isolated point), with independently chosen values inside and at
/// both ends. Empty pools are replaced by `horizon / 2` and `0`.
pub fn signal_strategy(
    horizon: Time,
    pool: Vec<Time>,
    lengths: Vec<Time>,
) -> impl Strategy<Value = Signal> {
    let pool = if pool.is_empty() { vec![&horizon / ratio(2, 1)] } else { pool };
    let lengths = if lengths.is_empty() { vec![Time::zero()] } else { lengths };
    let pulse = (any::<Index>(), any::<Index>(), any::<bool>(), any::<bool>(), any::<bool>());
    (any::<bool>(), prop::collection::vec(pulse, 0..7)).prop_map(move |(initial, pulses)| {
        let mut signal = Signal::constant(horizon.clone(), initial);
        for (at, len, inside, at_start, at_end) in pulses {
            let start = at.get(&pool);
            let end = start + len.get(&lengths);
            signal = overlay(&signal, start, &end, inside, at_start, at_end);
        }
        signal
    })
}

/// Base instants in `(0, horizon)`: multiples of 1/20 s, thirds, sevenths,
/// and instants close to 0 (hundredths below 0.1 s).
fn base_instants(horizon: &Time) -> impl Strategy<Value = Vec<Time>> + use<> {
    let h = horizon.to_integer().to_i64().unwrap_or(4).clamp(1, 1_000_000);
    let instant = prop_oneof![
        (1..h * 20).prop_map(|k| ratio(k, 20)),
        (1..h * 3).prop_map(|k| ratio(k, 3)),
        (1..h * 7).prop_map(|k| ratio(k, 7)),
        (1i64..10).prop_map(|k| ratio(k, 100)),
    ];
    prop::collection::vec(instant, 2..7)
}

/// Assignments for these signal names and delay metavariables: delays from
/// [`DELAY_POOL`], a horizon from [`horizon_for`], and signals from
/// [`signal_strategy`] over one shared [`time_pool`] and [`length_pool`].
pub fn assignment(signals: Vec<Symbol>, delays: Vec<Symbol>) -> impl Strategy<Value = Assignment> {
    assignment_with_delays(signals, delays, Vec::new())
}

/// Like [`assignment`], with extra fixed delays (for example the delay
/// literals of the terms under test) that shape the pool and the horizon.
pub fn assignment_with_delays(
    signals: Vec<Symbol>,
    delays: Vec<Symbol>,
    fixed: Vec<Delay>,
) -> impl Strategy<Value = Assignment> {
    let count = delays.len();
    prop::collection::vec(delay_strategy(), count).prop_flat_map(move |chosen| {
        let mut all = chosen.clone();
        all.extend(fixed.iter().cloned());
        let horizon = horizon_for(&all);
        let names = signals.clone();
        let delay_names = delays.clone();
        base_instants(&horizon).prop_flat_map(move |base| {
            let pool = time_pool(&horizon, &all, &base);
            let lengths = length_pool(&horizon, &all);
            let one = signal_strategy(horizon.clone(), pool, lengths);
            let names = names.clone();
            let delay_map: BTreeMap<Symbol, Delay> =
                delay_names.iter().cloned().zip(chosen.iter().cloned()).collect();
            let horizon = horizon.clone();
            let twin = (0u8..3, any::<Index>(), prop::collection::vec(any::<bool>(), 64));
            prop::collection::vec((one, twin), names.len()).prop_map(move |drawn| {
                let mut sigs: Vec<Signal> = Vec::with_capacity(drawn.len());
                for (own, (mode, source, bits)) in drawn {
                    let signal = if mode == 0 && !sigs.is_empty() {
                        twin_of(source.get(&sigs), &own, &bits)
                    } else {
                        own
                    };
                    sigs.push(signal);
                }
                Assignment {
                    horizon: horizon.clone(),
                    signals: names.iter().cloned().zip(sigs).collect(),
                    delays: delay_map.clone(),
                    cycle: None,
                }
            })
        })
    })
}

/// A signal that changes where `source` and `own` change (so it shares all
/// the change instants of `source`), with the values of its pieces taken
/// from `bits` (cycled): makes simultaneous edges, such as two signals
/// falling together, common.
fn twin_of(source: &Signal, own: &Signal, bits: &[bool]) -> Signal {
    let mut breaks: Vec<Time> =
        source.breakpoints().iter().chain(own.breakpoints()).cloned().collect();
    breaks.sort();
    breaks.dedup();
    let bit = |i: usize| bits.get(i % bits.len().max(1)).copied().unwrap_or(false);
    let open = (0..breaks.len()).map(|i| bit(2 * i)).collect();
    let point = (0..breaks.len()).map(|i| bit(2 * i + 1)).collect();
    Signal::from_parts(own.horizon().clone(), breaks, open, point).unwrap_or_else(|_| own.clone())
}

/// All `2^k` assignments of constant signals (horizon 1 s, no delays) to `names`.
pub fn exhaustive_boolean(names: &[Symbol]) -> Vec<Assignment> {
    let horizon = ratio(1, 1);
    let mut maps: Vec<BTreeMap<Symbol, Signal>> = vec![BTreeMap::new()];
    for name in names {
        let mut next = Vec::with_capacity(maps.len() * 2);
        for map in maps {
            for value in [false, true] {
                let mut m = map.clone();
                m.insert(*name, Signal::constant(horizon.clone(), value));
                next.push(m);
            }
        }
        maps = next;
    }
    maps.into_iter()
        .map(|signals| Assignment {
            horizon: horizon.clone(),
            signals,
            delays: BTreeMap::new(),
            cycle: None,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;

    #[test]
    fn exhaustive_covers_every_combination() {
        let names: Vec<Symbol> = ["a", "b", "c"].iter().map(|n| Symbol::from(*n)).collect();
        let all = exhaustive_boolean(&names);
        assert_eq!(all.len(), 8);
        let mut seen: Vec<Vec<bool>> = all
            .iter()
            .map(|a| a.signals.values().map(|s| s.as_constant().unwrap()).collect())
            .collect();
        seen.sort();
        seen.dedup();
        assert_eq!(seen.len(), 8);
        assert_eq!(exhaustive_boolean(&[]).len(), 1);
    }

    #[test]
    fn pools_are_valid_and_hard() {
        let ds = vec![pool_delay(1, 2), pool_delay(3, 10)];
        let h = horizon_for(&ds);
        assert!(h > ratio(8, 5));
        let pool = time_pool(&h, &ds, &[ratio(1, 3)]);
        assert!(pool.contains(&ratio(1, 2)));
        assert!(pool.contains(&ratio(4, 5)));
        assert!(pool.contains(&(ratio(1, 3) + ratio(1, 2))));
        assert!(pool.iter().all(|t| t.is_positive() && *t <= h));
    }

    #[test]
    fn generated_signals_are_well_formed_and_varied() {
        let mut runner = TestRunner::deterministic();
        let names = vec![Symbol::from("a"), Symbol::from("b")];
        let strat = assignment(names, vec![Symbol::from("d")]);
        let mut isolated = 0;
        let mut shared = 0;
        for _ in 0..200 {
            let env = strat.new_tree(&mut runner).unwrap().current();
            assert_eq!(env.delays.len(), 1);
            let sigs: Vec<&Signal> = env.signals.values().collect();
            for s in &sigs {
                s.check_invariants().unwrap();
                assert_eq!(s.horizon(), &env.horizon);
                let n = s.breakpoints().len();
                for i in 0..n.saturating_sub(1) {
                    let p = s.point_values()[i];
                    if p != s.open_values()[i] && p != s.open_values()[i + 1] {
                        isolated += 1;
                    }
                }
            }
            let h = &env.horizon;
            if sigs[0].breakpoints().iter().any(|b| b < h && sigs[1].breakpoints().contains(b)) {
                shared += 1;
            }
        }
        assert!(isolated > 20, "isolated points: {isolated}");
        assert!(shared > 20, "shared instants: {shared}");
    }
}
