//! The timing examples of `tests/data/proves_programs/` and their false variants in
//! `tests/data/refutes_programs/`, judged by the ladder simulator alone: each sentence,
//! evaluated directly on random runs of LDmicro's scan semantics (`src/ladder/simulate.rs`),
//! holds on every run of the program whose property is proved, and fails on some run of
//! its false variant. This checks the examples' truth independently of the prover (and of
//! the patterns' compilation to II terms).

use crate::common::rng;

use std::collections::BTreeMap;
use std::path::Path;

use ii_prove::diag::Sources;
use ii_prove::ladder::{Simulator, read_ldmicro};
use rng::Rng;

/// Each signal's value at each scan.
type Run = BTreeMap<String, Vec<bool>>;

/// `runs` random runs of `scans` scans of the program at `path` (relative to the crate),
/// its `inputs` held for random stretches of 1 to `hold` scans; `watch` recorded.
fn runs(path: &str, inputs: &[&str], watch: &[&str], hold: u64, seed: u64) -> Vec<Run> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(path);
    let text = std::fs::read_to_string(&path).expect("the example exists");
    let mut sources = Sources::new();
    let file = sources.add(path.display().to_string(), text);
    let program = read_ldmicro(&sources, file).expect("the example reads");
    let mut rng = Rng::new(seed);
    let mut out = Vec::new();
    for _ in 0..300 {
        let mut sim = Simulator::new(&program);
        let mut run = Run::new();
        let mut values: BTreeMap<String, bool> =
            inputs.iter().map(|n| (n.to_string(), false)).collect();
        let mut left = vec![0u64; inputs.len()];
        for _ in 0..200 {
            for (i, n) in inputs.iter().enumerate() {
                if left[i] == 0 {
                    values.insert(n.to_string(), rng.chance(50));
                    left[i] = 1 + rng.below(hold);
                }
                left[i] -= 1;
            }
            sim.step(&values);
            for n in inputs.iter().chain(watch) {
                run.entry(n.to_string()).or_default().push(sim.bit(n));
            }
        }
        out.push(run);
    }
    out
}

/// Every `a` is answered by a `b` at its own scan or within `n` scans after it (an `a`
/// too close to the end of the run to tell is not judged).
fn within(run: &Run, a: &str, b: &str, n: usize) -> bool {
    let (a, b) = (&run[a], &run[b]);
    (0..a.len()).filter(|&k| a[k] && k + n < a.len()).all(|k| b[k..=k + n].iter().any(|x| *x))
}

/// `f` is never on for `n + 1` scans in a row.
fn at_most(run: &Run, f: &str, n: usize) -> bool {
    run[f].windows(n + 1).all(|w| w.iter().any(|x| !x))
}

/// Every stretch of `f` that has ended lasted `n` scans or more.
fn at_least(run: &Run, f: &str, n: usize) -> bool {
    let mut length = 0;
    for &on in &run[f] {
        if on {
            length += 1;
        } else if length > 0 {
            if length < n {
                return false;
            }
            length = 0;
        }
    }
    true
}

/// Whenever `f` has been on for the last `n + 1` scans, `g` is on.
fn after(run: &Run, f: &str, n: usize, g: &str) -> bool {
    let (f, g) = (&run[f], &run[g]);
    (n..f.len()).all(|k| !f[k - n..=k].iter().all(|x| *x) || g[k])
}

/// The sentence holds on every run of the proved program and fails on some run of the
/// false variant.
fn judged(name: &str, good: &[Run], bad: &[Run], sentence: &dyn Fn(&Run) -> bool) {
    assert!(good.iter().all(sentence), "{name}: the proved example fails on the simulator");
    assert!(!bad.iter().all(sentence), "{name}: the false variant holds on every run");
}

#[test]
fn a_failed_line_hands_over_within_1s() {
    let (inputs, watch) = (["XL1_fail", "XReset"], ["YL2_up"]);
    let good = runs("tests/data/proves_programs/handover_within.ld", &inputs, &watch, 12, 1);
    // The false variant is the same program with 0.4 s (4 scans) instead of 1 s.
    let bad = runs("tests/data/refutes_programs/handover_late.ld", &inputs, &watch, 12, 2);
    assert!(good.iter().all(|r| within(r, "XL1_fail", "YL2_up", 10)), "handover: 1 s fails");
    assert!(!bad.iter().all(|r| within(r, "XL1_fail", "YL2_up", 4)), "handover: 0.4 s holds");
}

#[test]
fn after_5s_of_demand_the_valve_is_open() {
    let (inputs, watch) = (["XL_flow", "XH_flow"], ["RDemand", "YOut_valve"]);
    let good = runs("tests/data/proves_programs/valve_after_demand.ld", &inputs, &watch, 90, 3);
    let bad = runs("tests/data/refutes_programs/valve_one_scan_late.ld", &inputs, &watch, 90, 4);
    judged("valve", &good, &bad, &|r| after(r, "RDemand", 50, "YOut_valve"));
}

#[test]
fn the_fast_blink_is_never_on_for_150ms() {
    let (inputs, watch) = (["XEnable"], ["Rfast"]);
    let good = runs("tests/data/proves_programs/fast_blink.ld", &inputs, &watch, 40, 5);
    let bad = runs("tests/data/refutes_programs/fast_blink_long.ld", &inputs, &watch, 40, 6);
    // 150 ms is 3 scans of 50 ms; the blink must also blink.
    assert!(good.iter().all(|r| r["Rfast"].iter().any(|x| *x)));
    judged("blink", &good, &bad, &|r| at_most(r, "Rfast", 3));
}

#[test]
fn the_lamp_stays_on_at_least_1s() {
    let (inputs, watch) = (["XButton"], ["YLamp"]);
    let good = runs("tests/data/proves_programs/lamp_min_on.ld", &inputs, &watch, 15, 7);
    let bad = runs("tests/data/refutes_programs/lamp_short.ld", &inputs, &watch, 15, 8);
    judged("lamp", &good, &bad, &|r| at_least(r, "YLamp", 10));
}

#[test]
fn a_running_line_is_not_preempted_for_1s() {
    let (inputs, watch) = (["XReq2", "XStart1", "XStop2"], ["RL1_up"]);
    let good = runs("tests/data/proves_programs/line_not_preempted.ld", &inputs, &watch, 15, 9);
    let bad =
        runs("tests/data/refutes_programs/line_preempted_at_once.ld", &inputs, &watch, 15, 10);
    judged("line", &good, &bad, &|r| at_least(r, "RL1_up", 10));
}
