//! Reference tests of the exact semantics: every operator against a brute-force evaluation of its definition.
//!
//! The brute-force side reads a signal only through its raw parts
//! (`breakpoints`, `open_values`, `point_values`) and evaluates the
//! quantifiers of `/work/shared/spec/semantics.md` over a finite set of
//! witness instants that represents every instant of the window: each
//! breakpoint inside it, its right end, and the midpoint of every gap between
//! them (the signals are constant on those gaps). The result of an operator is
//! compared with it at every instant where either could change (breakpoints of
//! the inputs and of the result, `d`, breakpoints plus `d`) and at the midpoint
//! of every gap between those, which decides equality on all of `(0, H]`.

use std::collections::BTreeMap;

use ii_prove::semantics::random::{assignment, exhaustive_boolean, signal_strategy};
use ii_prove::semantics::{Assignment, Signal, Time, eval};
use ii_prove::term::{Delay, Expr, Symbol, sexp};
use num_bigint::BigInt;
use num_traits::{Signed, Zero};
use proptest::prelude::*;
use proptest::strategy::ValueTree;
use proptest::test_runner::{Config, TestRunner};

const CASES: u32 = 1000;

fn config() -> Config {
    Config { cases: CASES, failure_persistence: None, ..Config::default() }
}

fn q(n: i64, d: i64) -> Time {
    Time::new(BigInt::from(n), BigInt::from(d))
}

fn int(n: i64) -> Time {
    q(n, 1)
}

fn mid(a: &Time, b: &Time) -> Time {
    (a + b) / int(2)
}

fn delay(text: &str) -> Delay {
    text.parse().unwrap()
}

fn sym(name: &str) -> Symbol {
    Symbol::from(name)
}

// ---------------------------------------------------------------------------
// The brute-force reference.

/// The value at `t ∈ (0, H]`, read from the raw parts by a linear scan.
fn bf_value(f: &Signal, t: &Time) -> bool {
    let mut lo = Time::zero();
    for (i, b) in f.breakpoints().iter().enumerate() {
        if t == b {
            return f.point_values()[i];
        }
        if lo < *t && t < b {
            return f.open_values()[i];
        }
        lo = b.clone();
    }
    panic!("instant outside the horizon");
}

/// Instants representing all of `(a, b]` (with `0 ≤ a < b`) for the signals `fs`.
fn witnesses(fs: &[&Signal], a: &Time, b: &Time) -> Vec<Time> {
    let mut cuts: Vec<Time> = fs
        .iter()
        .flat_map(|f| f.breakpoints().iter())
        .filter(|c| a < *c && *c < b)
        .cloned()
        .collect();
    cuts.push(b.clone());
    cuts.sort();
    cuts.dedup();
    let mut out = Vec::new();
    let mut previous = a.clone();
    for c in cuts {
        out.push(mid(&previous, &c));
        out.push(c.clone());
        previous = c;
    }
    out
}

fn clamp0(t: Time) -> Time {
    if t.is_negative() { Time::zero() } else { t }
}

/// `d/f` at `t`: `t ≥ d ∧ ∀τ ∈ (t−d, t]: f(τ)`.
fn bf_ton(f: &Signal, d: &Time, t: &Time) -> bool {
    t >= d && witnesses(&[f], &(t - d), t).iter().all(|tau| bf_value(f, tau))
}

/// `f/d` at `t`: `∃τ ∈ (max(0, t−d), t]: f(τ)`.
fn bf_tof(f: &Signal, d: &Time, t: &Time) -> bool {
    witnesses(&[f], &clamp0(t - d), t).iter().any(|tau| bf_value(f, tau))
}

/// `SR(s, r)` at `t`: `∃t1 ∈ (0, t]: s(t1) ∧ ∀τ ∈ (t1, t]: s(τ) ∨ ¬r(τ)`.
fn bf_sr(s: &Signal, r: &Signal, t: &Time) -> bool {
    witnesses(&[s, r], &Time::zero(), t).iter().any(|t1| {
        bf_value(s, t1)
            && (t1 == t
                || witnesses(&[s, r], t1, t)
                    .iter()
                    .all(|tau| bf_value(s, tau) || !bf_value(r, tau)))
    })
}

/// `RS(s, r) = SR(s·¬r, r)` at `t`, unfolded:
/// `∃t1 ∈ (0, t]: s(t1) ∧ ¬r(t1) ∧ ∀τ ∈ (t1, t]: ¬r(τ)`.
fn bf_rs(s: &Signal, r: &Signal, t: &Time) -> bool {
    witnesses(&[s, r], &Time::zero(), t).iter().any(|t1| {
        bf_value(s, t1)
            && !bf_value(r, t1)
            && (t1 == t || witnesses(&[s, r], t1, t).iter().all(|tau| !bf_value(r, tau)))
    })
}

/// The closed form the spec rejects: `∃t1 ∈ (0, t]: s(t1) ∧ ∀τ ∈ (t1, t]: ¬r(τ)`.
fn bf_sr_not_r_only(s: &Signal, r: &Signal, t: &Time) -> bool {
    witnesses(&[s, r], &Time::zero(), t).iter().any(|t1| {
        bf_value(s, t1)
            && (t1 == t || witnesses(&[s, r], t1, t).iter().all(|tau| !bf_value(r, tau)))
    })
}

/// Every instant where the inputs, the result or a delay shift may change,
/// and the midpoint of every gap between them, within `(0, H]`.
fn check_points(h: &Time, signals: &[&Signal], delays: &[&Time]) -> Vec<Time> {
    let mut cuts: Vec<Time> = vec![h.clone()];
    for f in signals {
        for b in f.breakpoints() {
            cuts.push(b.clone());
            for d in delays {
                cuts.push(b + *d);
            }
        }
    }
    for d in delays {
        cuts.push((*d).clone());
    }
    cuts.retain(|c| c.is_positive() && c <= h);
    cuts.sort();
    cuts.dedup();
    let mut out = Vec::new();
    let mut previous = Time::zero();
    for c in cuts {
        out.push(mid(&previous, &c));
        out.push(c.clone());
        previous = c;
    }
    out
}

/// Compares `result` with `reference` everywhere on `(0, H]`.
fn agrees(
    what: &str,
    result: &Signal,
    inputs: &[&Signal],
    delays: &[&Time],
    reference: impl Fn(&Time) -> bool,
) -> Result<(), TestCaseError> {
    if let Err(why) = result.check_invariants() {
        return Err(TestCaseError::fail(format!("{what}: {why}: {result}")));
    }
    let h = inputs[0].horizon();
    prop_assert_eq!(result.horizon(), h);
    let mut all = inputs.to_vec();
    all.push(result);
    for t in check_points(h, &all, delays) {
        let want = reference(&t);
        if result.value_at(&t) != want || bf_value(result, &t) != want {
            let mut msg = format!(
                "{what}: at t = {} the result is {} but the definition gives {}\n  result: {result}",
                ii_prove::semantics::format_time(&t),
                result.value_at(&t),
                want
            );
            for (i, f) in inputs.iter().enumerate() {
                msg.push_str(&format!("\n  input {i}: {f}"));
            }
            for d in delays {
                msg.push_str(&format!("\n  delay: {}", ii_prove::semantics::format_time(d)));
            }
            return Err(TestCaseError::fail(msg));
        }
    }
    Ok(())
}

fn two_signals() -> impl Strategy<Value = Assignment> {
    assignment(vec![sym("s"), sym("r")], vec![sym("d")])
}

fn get<'a>(env: &'a Assignment, name: &str) -> &'a Signal {
    &env.signals[&sym(name)]
}

fn d_of(env: &Assignment) -> &Delay {
    &env.delays[&sym("d")]
}

// ---------------------------------------------------------------------------
// Each operator against its definition, on many random cases.

proptest! {
    #![proptest_config(config())]

    #[test]
    fn representation_reads_back(env in two_signals()) {
        let f = get(&env, "s");
        f.check_invariants().map_err(TestCaseError::fail)?;
        for t in check_points(&env.horizon, &[f], &[]) {
            prop_assert_eq!(f.value_at(&t), bf_value(f, &t));
            // The left limit is the value just before t.
            let before = f
                .breakpoints()
                .iter()
                .filter(|b| **b < t)
                .max()
                .cloned()
                .unwrap_or_else(Time::zero);
            prop_assert_eq!(f.left_limit(&t), bf_value(f, &mid(&before, &t)));
        }
        // Rebuilding from the parts, or through redundant cut points, gives `==`.
        let again = Signal::from_parts(
            env.horizon.clone(),
            f.breakpoints().to_vec(),
            f.open_values().to_vec(),
            f.point_values().to_vec(),
        )
        .map_err(TestCaseError::fail)?;
        prop_assert_eq!(&again, f);
        let mut cuts = f.breakpoints().to_vec();
        cuts.extend(get(&env, "r").breakpoints().iter().cloned());
        cuts.push(q(1, 3));
        let resampled = Signal::from_fn(env.horizon.clone(), cuts, |t| bf_value(f, t));
        prop_assert_eq!(&resampled, f);
    }

    #[test]
    fn not_and_or_are_pointwise(env in two_signals()) {
        let (s, r) = (get(&env, "s"), get(&env, "r"));
        agrees("¬s", &s.not(), &[s], &[], |t| !bf_value(s, t))?;
        agrees("s·r", &s.and(r), &[s, r], &[], |t| bf_value(s, t) && bf_value(r, t))?;
        agrees("s+r", &s.or(r), &[s, r], &[], |t| bf_value(s, t) || bf_value(r, t))?;
    }

    #[test]
    fn ton_matches_its_definition(env in two_signals()) {
        let (f, d) = (get(&env, "s"), d_of(&env));
        agrees("d/f", &f.ton(d), &[f], &[d.seconds()], |t| bf_ton(f, d.seconds(), t))?;
    }

    #[test]
    fn tof_matches_its_definition(env in two_signals()) {
        let (f, d) = (get(&env, "s"), d_of(&env));
        agrees("f/d", &f.tof(d), &[f], &[d.seconds()], |t| bf_tof(f, d.seconds(), t))?;
    }

    #[test]
    fn sr_matches_its_definition(env in two_signals()) {
        let (s, r) = (get(&env, "s"), get(&env, "r"));
        agrees("SR(s,r)", &Signal::sr(s, r), &[s, r], &[], |t| bf_sr(s, r, t))?;
    }

    #[test]
    fn rs_matches_its_definition(env in two_signals()) {
        let (s, r) = (get(&env, "s"), get(&env, "r"));
        let rs = Signal::rs(s, r);
        agrees("RS(s,r)", &rs, &[s, r], &[], |t| bf_rs(s, r, t))?;
        prop_assert_eq!(&rs, &Signal::sr(&s.and(&r.not()), r));
    }

    #[test]
    fn differences_and_violations_have_true_witnesses(env in two_signals()) {
        let (s, r) = (get(&env, "s"), get(&env, "r"));
        // `==` is semantic equality.
        let pointwise_equal = check_points(&env.horizon, &[s, r], &[])
            .iter()
            .all(|t| bf_value(s, t) == bf_value(r, t));
        prop_assert_eq!(pointwise_equal, s == r);
        match s.first_difference(r) {
            Some(t) => {
                prop_assert!(t.is_positive() && t <= env.horizon);
                prop_assert_ne!(bf_value(s, &t), bf_value(r, &t));
            }
            None => prop_assert_eq!(s, r),
        }
        prop_assert_eq!(s.first_difference(s), None);
        let implies = check_points(&env.horizon, &[s, r], &[])
            .iter()
            .all(|t| !bf_value(s, t) || bf_value(r, t));
        match s.first_violation_of_implication(r) {
            Some(t) => {
                prop_assert!(!implies);
                prop_assert!(bf_value(s, &t) && !bf_value(r, &t));
            }
            None => prop_assert!(implies),
        }
    }
}

// ---------------------------------------------------------------------------
// Hand-written cases from the spec.

fn steps(h: i64, initial: bool, changes: &[(Time, bool)]) -> Signal {
    Signal::from_steps(int(h), initial, changes).unwrap()
}

#[test]
fn ton_of_one_is_zero_before_d_and_one_from_d_on() {
    let one = Signal::constant(int(5), true);
    let want = steps(5, false, &[(int(2), true)]);
    assert_eq!(one.ton(&delay("2s")), want);
    assert!(!want.value_at(&q(199, 100)));
    assert!(want.value_at(&int(2)));
    // A delay longer than the horizon: never.
    assert_eq!(one.ton(&delay("6s")), Signal::constant(int(5), false));
    // A delay equal to the horizon: only at H.
    let at_h = one.ton(&delay("5s"));
    assert!(!at_h.value_at(&q(49, 10)) && at_h.value_at(&int(5)));
}

#[test]
fn ton_of_a_pulse_of_length_exactly_d_is_a_single_instant() {
    // f = 1 on [1, 3] (closed): d/f with d = 2 is 1 at 3 only.
    let f = Signal::from_parts(
        int(6),
        vec![int(1), int(3), int(6)],
        vec![false, true, false],
        vec![true, true, false],
    )
    .unwrap();
    let g = f.ton(&delay("2s"));
    let want =
        Signal::from_parts(int(6), vec![int(3), int(6)], vec![false, false], vec![true, false])
            .unwrap();
    assert_eq!(g, want, "got {g}");
    // A right-continuous pulse [1, 3) of length d never holds for a whole window.
    let f = steps(6, false, &[(int(1), true), (int(3), false)]);
    assert_eq!(f.ton(&delay("2s")), Signal::constant(int(6), false));
    // Left-continuous (1, 3]: the same single instant.
    let f = Signal::from_parts(
        int(6),
        vec![int(1), int(3), int(6)],
        vec![false, true, false],
        vec![false, true, false],
    )
    .unwrap();
    assert_eq!(f.ton(&delay("2s")), want);
    // Longer than d: on from start + d to the end.
    let f = steps(6, false, &[(int(1), true), (int(4), false)]);
    assert_eq!(f.ton(&delay("2s")), steps(6, false, &[(int(3), true), (int(4), false)]));
}

#[test]
fn sr_stays_set_when_s_and_r_fall_together() {
    // s = r = 1 on [1, 2), then both 0.
    let s = steps(5, false, &[(int(1), true), (int(2), false)]);
    let r = s.clone();
    let sr = Signal::sr(&s, &r);
    assert_eq!(sr, steps(5, false, &[(int(1), true)]), "got {sr}");
    // The rejected closed form with ¬r alone gives 0 after the fall.
    assert!(!bf_sr_not_r_only(&s, &r, &int(3)));
    assert!(bf_sr(&s, &r, &int(3)));
    // RS = SR(s·¬r, r) never sets here; so `SR = s + RS` fails without s·r = 0.
    let rs = Signal::rs(&s, &r);
    assert_eq!(rs, Signal::constant(int(5), false));
    assert_eq!(rs, Signal::sr(&s.and(&r.not()), &r));
    assert_ne!(sr, s.or(&rs));
    // Reset after set, and set again.
    let s = steps(8, false, &[(int(1), true), (int(2), false), (int(5), true)]);
    let r = steps(8, false, &[(int(3), true), (int(4), false), (int(6), true)]);
    assert_eq!(
        Signal::sr(&s, &r),
        steps(8, false, &[(int(1), true), (int(3), false), (int(5), true)])
    );
    assert_eq!(
        Signal::rs(&s, &r),
        steps(8, false, &[(int(1), true), (int(3), false), (int(5), true), (int(6), false)])
    );
}

#[test]
fn sr_of_f_and_zero_is_f_has_been_true() {
    // An isolated point at 1.5.
    let f =
        Signal::from_parts(int(4), vec![q(3, 2), int(4)], vec![false, false], vec![true, false])
            .unwrap();
    let zero = Signal::constant(int(4), false);
    assert_eq!(Signal::sr(&f, &zero), steps(4, false, &[(q(3, 2), true)]));
    // An isolated reset point only resets at that instant if s is 0... and stays reset.
    let s = steps(4, false, &[(int(1), true), (q(11, 10), false)]);
    let sr = Signal::sr(&s, &f);
    assert_eq!(sr, steps(4, false, &[(int(1), true), (q(3, 2), false)]));
}

#[test]
fn tof_of_an_isolated_point_and_near_zero() {
    let f = Signal::from_parts(int(5), vec![int(1), int(5)], vec![false, false], vec![true, false])
        .unwrap();
    // f/2 is 1 on [1, 3).
    assert_eq!(f.tof(&delay("2s")), steps(5, false, &[(int(1), true), (int(3), false)]));
    // d/f of an isolated point is never 1.
    assert_eq!(f.ton(&delay("2s")), Signal::constant(int(5), false));
    // 1 on (0, 0.1) then 0: f/1 is 1 on (0, 1.1).
    let f = steps(5, true, &[(q(1, 10), false)]);
    assert_eq!(f.tof(&delay("1s")), steps(5, true, &[(q(11, 10), false)]));
    // For t < d, d/f is 0 whatever f is.
    assert!(!f.ton(&delay("1s")).value_at(&q(1, 20)));
    // A point at the horizon.
    let f = Signal::from_parts(int(2), vec![int(2)], vec![false], vec![true]).unwrap();
    let g = f.tof(&delay("0.5s"));
    assert_eq!(g, f);
    assert!(g.value_at(&int(2)) && !g.left_limit(&int(2)));
}

#[test]
fn display_and_witness_rendering() {
    let f = steps(4, false, &[(int(1), true), (q(5, 2), false)]);
    assert_eq!(f.to_string(), "(0,1):0 @1:1 (1,2.5):1 @2.5:0 (2.5,4]:0");
    let g = steps(4, false, &[(int(1), true)]);
    assert_eq!(f.first_difference(&g), Some(q(5, 2)));
    assert_eq!(g.first_violation_of_implication(&f), Some(q(5, 2)));
    assert_eq!(f.first_violation_of_implication(&g), None);
    assert!(f.implies(&g));
}

#[test]
fn different_horizons_are_compared_on_the_common_part() {
    let f = steps(4, false, &[(int(1), true)]);
    let g = steps(2, false, &[(int(1), true)]);
    assert_eq!(f.and(&g), g);
    assert_eq!(f.restrict(&int(2)), g);
    assert_eq!(f.first_difference(&g), None);
}

// ---------------------------------------------------------------------------
// Known laws hold and the paper's false ones fail (a sanity check of `eval`).

fn law_env(signals: &[&str], delays: &[&str]) -> impl Strategy<Value = Assignment> {
    assignment(signals.iter().map(|n| sym(n)).collect(), delays.iter().map(|n| sym(n)).collect())
}

fn check_law(lhs: &str, rhs: &str, env: &Assignment) -> Result<(), TestCaseError> {
    let (l, r): (Expr, Expr) = (sexp(lhs), sexp(rhs));
    let a = eval(&l, env).map_err(|e| TestCaseError::fail(e.to_string()))?;
    let b = eval(&r, env).map_err(|e| TestCaseError::fail(e.to_string()))?;
    if let Some(t) = a.first_difference(&b) {
        return Err(TestCaseError::fail(format!(
            "{lhs} = {rhs} fails at {}\n  lhs: {a}\n  rhs: {b}\n{env}",
            ii_prove::semantics::format_time(&t)
        )));
    }
    Ok(())
}

proptest! {
    #![proptest_config(Config { cases: 300, failure_persistence: None, ..Config::default() })]

    #[test]
    fn delay_laws_hold(env in law_env(&["f", "g"], &["d1", "d2"])) {
        check_law("(ton d1 (ton d2 f))", "(ton (dadd d1 d2) f)", &env)?;
        check_law("(tof (tof f d1) d2)", "(tof f (dadd d1 d2))", &env)?;
        check_law("(! (ton d1 f))", "(+ (tof (! f) d1) (! (ton d1 1*)))", &env)?;
        check_law(
            "(! (tof f d1))",
            "(+ (ton d1 (! f)) (& (! (ton d1 1*)) (! (sr f 0*))))",
            &env,
        )?;
        check_law("(ton d1 (& f g))", "(& (ton d1 f) (ton d1 g))", &env)?;
        check_law("(tof (+ f g) d1)", "(+ (tof f d1) (tof g d1))", &env)?;
        check_law("(ton (dmax d1 d2) f)", "(& (ton d1 f) (ton d2 f))", &env)?;
        check_law("(tof f (dmin d1 d2))", "(& (tof f d1) (tof f d2))", &env)?;
    }

    #[test]
    fn boolean_and_memory_laws_hold(env in law_env(&["s", "r", "f"], &[])) {
        check_law("(! (+ s r))", "(& (! s) (! r))", &env)?;
        check_law("(& s (+ r f))", "(+ (& s r) (& s f))", &env)?;
        check_law("(rs s r)", "(sr (& s (! r)) r)", &env)?;
        // With the side condition s·r = 0 built in (r := r·¬s).
        check_law("(sr s (& r (! s)))", "(+ s (rs s (& r (! s))))", &env)?;
        check_law("(rs s (& r (! s)))", "(& (! (& r (! s))) (sr s (& r (! s))))", &env)?;
        // Monotone in s, antitone in r.
        let sr = eval(&sexp("(sr s r)"), &env).unwrap();
        let bigger = eval(&sexp("(sr (+ s f) (& r (! f)))"), &env).unwrap();
        prop_assert!(sr.implies(&bigger));
    }
}

/// A law that must fail on some of `runs` random assignments; every witness is re-checked.
fn refuted(lhs: &str, rhs: &str, signals: &[&str], delays: &[&str], runs: usize) -> usize {
    let mut runner = TestRunner::deterministic();
    let strategy = law_env(signals, delays);
    let (l, r) = (sexp(lhs), sexp(rhs));
    let mut failures = 0;
    for _ in 0..runs {
        let env = strategy.new_tree(&mut runner).unwrap().current();
        let (a, b) = (eval(&l, &env).unwrap(), eval(&r, &env).unwrap());
        if let Some(t) = a.first_difference(&b) {
            assert_ne!(bf_value(&a, &t), bf_value(&b, &t));
            failures += 1;
        }
    }
    failures
}

#[test]
fn the_papers_false_laws_fail_with_witnesses() {
    let n = refuted("(! (ton d f))", "(tof (! f) d)", &["f"], &["d"], 200);
    assert!(n > 50, "¬(d/f) = (¬f)/d refuted only {n} times");
    let n = refuted("(! (tof f d))", "(ton d (! f))", &["f"], &["d"], 200);
    assert!(n > 50, "¬(f/d) = d/¬f refuted only {n} times");
    let n = refuted("(! (& s (! r)))", "(& (! s) (! r))", &["s", "r"], &[], 200);
    assert!(n > 50, "the misprinted De Morgan refuted only {n} times");
    let n = refuted("(sr s r)", "(+ s (rs s r))", &["s", "r"], &[], 200);
    assert!(n > 5, "SR = s + RS (no side condition) refuted only {n} times");
    // A specific witness: f = 1*, before d.
    let mut env = Assignment::new(int(4));
    env.signals.insert(sym("f"), Signal::constant(int(4), true));
    env.delays.insert(sym("d"), delay("1s"));
    let a = eval(&sexp("(! (ton d f))"), &env).unwrap();
    let b = eval(&sexp("(tof (! f) d)"), &env).unwrap();
    let t = a.first_difference(&b).unwrap();
    assert!(t < int(1));
}

#[test]
fn exhaustive_boolean_assignments_check_boolean_laws() {
    let names = [sym("a"), sym("b"), sym("c")];
    let all = exhaustive_boolean(&names);
    assert_eq!(all.len(), 8);
    for env in &all {
        let l = eval(&sexp("(& a (+ b c))"), env).unwrap();
        let r = eval(&sexp("(+ (& a b) (& a c))"), env).unwrap();
        assert_eq!(l, r);
        let l = eval(&sexp("(! (+ a b))"), env).unwrap();
        let r = eval(&sexp("(& (! a) (! b))"), env).unwrap();
        assert_eq!(l, r);
    }
    let misprint = all.iter().any(|env| {
        eval(&sexp("(! (& a (! b)))"), env).unwrap() != eval(&sexp("(& (! a) (! b))"), env).unwrap()
    });
    assert!(misprint);
}

#[test]
fn signal_strategy_is_usable_alone() {
    let mut runner = TestRunner::deterministic();
    let strategy =
        signal_strategy(int(5), vec![int(1), q(3, 2), int(2)], vec![Time::zero(), int(1)]);
    let mut seen = BTreeMap::new();
    for _ in 0..100 {
        let s = strategy.new_tree(&mut runner).unwrap().current();
        s.check_invariants().unwrap();
        *seen.entry(s.breakpoints().len()).or_insert(0) += 1;
    }
    assert!(seen.len() > 2);
}

#[test]
fn random_assignments_contain_the_hard_cases() {
    let mut runner = TestRunner::deterministic();
    let strategy = two_signals();
    let (mut exact_d, mut ton_point, mut shared, mut fall_together, mut before_d, mut isolated) =
        (0, 0, 0, 0, 0, 0);
    let runs = 500;
    for _ in 0..runs {
        let env = strategy.new_tree(&mut runner).unwrap().current();
        let (s, r, d) = (get(&env, "s"), get(&env, "r"), d_of(&env).seconds());
        let bs = s.breakpoints();
        if bs.iter().any(|a| bs.iter().any(|b| b - a == *d)) {
            exact_d += 1;
        }
        let g = s.ton(d_of(&env));
        let n = g.breakpoints().len();
        if (0..n.saturating_sub(1))
            .any(|i| g.point_values()[i] && !g.open_values()[i] && !g.open_values()[i + 1])
        {
            ton_point += 1;
        }
        if (0..bs.len().saturating_sub(1)).any(|i| {
            let p = s.point_values()[i];
            p != s.open_values()[i] && p != s.open_values()[i + 1]
        }) {
            isolated += 1;
        }
        let common: Vec<&Time> =
            bs.iter().filter(|b| **b < env.horizon && r.breakpoints().contains(b)).collect();
        if !common.is_empty() {
            shared += 1;
        }
        if common
            .iter()
            .any(|b| s.left_limit(b) && r.left_limit(b) && !s.value_at(b) && !r.value_at(b))
        {
            fall_together += 1;
        }
        if bs.iter().any(|b| b < d) {
            before_d += 1;
        }
    }
    let report = format!(
        "of {runs}: pulse/gap of exactly d {exact_d}, isolated instant of d/f {ton_point}, \
         isolated points {isolated}, shared instants {shared}, s and r fall together \
         {fall_together}, change before d {before_d}"
    );
    assert!(exact_d > runs / 4, "{report}");
    assert!(ton_point > 20, "{report}");
    assert!(isolated > runs / 3, "{report}");
    assert!(shared > runs / 3, "{report}");
    assert!(fall_together > 25, "{report}");
    assert!(before_d > runs / 4, "{report}");
    println!("{report}");
}

/// Any decimal delay (hundredths of a second up to 4 s) and signals over a pool built for it.
fn signal_and_any_delay() -> impl Strategy<Value = (Signal, Delay)> {
    (1i64..400).prop_flat_map(|k| {
        let d = Delay::new(q(k, 100)).unwrap();
        let h = ii_prove::semantics::random::horizon_for(std::slice::from_ref(&d));
        let pool = ii_prove::semantics::random::time_pool(
            &h,
            std::slice::from_ref(&d),
            &[q(1, 3), int(1)],
        );
        let lengths = ii_prove::semantics::random::length_pool(&h, std::slice::from_ref(&d));
        (signal_strategy(h, pool, lengths), Just(d))
    })
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn timers_match_their_definitions_for_any_decimal_delay((f, d) in signal_and_any_delay()) {
        agrees("d/f", &f.ton(&d), &[&f], &[d.seconds()], |t| bf_ton(&f, d.seconds(), t))?;
        agrees("f/d", &f.tof(&d), &[&f], &[d.seconds()], |t| bf_tof(&f, d.seconds(), t))?;
    }
}
