//! Random textual sequential function charts for the differential tests: steps (one or two initial), transitions from one step or a pair to one or a pair (some with priorities, conditions over inputs and steps' `X`), every untimed qualifier (`N`, `S`, `R`, `P`, `P1`, `P0`, none) on BOOL variables and on actions whose bodies assign outputs, count and call a timer, and `D`/`L` with short times on the steps that are not initial.
#![allow(dead_code)]

use super::rng::Rng;

/// A random chart and what to compare.
pub struct Generated {
    /// The `.st` text.
    pub text: String,
    /// The program's type name.
    pub pou: String,
    /// Its BOOL inputs.
    pub inputs: Vec<String>,
    /// Its BOOL variables worth comparing.
    pub bits: Vec<String>,
    /// The scan cycle, in µs.
    pub cycle_us: u64,
}

const QUALIFIERS: [&str; 7] = ["N", "S", "R", "P", "P1", "P0", ""];

/// The random chart of `seed`.
pub fn program(seed: u64) -> Generated {
    let mut r = Rng::new(seed ^ 0x5FC0);
    let inputs: Vec<String> = (0..3).map(|k| format!("In{k}")).collect();
    let outs: Vec<String> = (0..4).map(|k| format!("Out{k}")).collect();
    let n_steps = 3 + r.below(4) as usize;
    let steps: Vec<String> = (0..n_steps).map(|k| format!("S{k}")).collect();
    let n_actions = 1 + r.below(3) as usize;
    let actions: Vec<String> = (0..n_actions).map(|k| format!("A{k}")).collect();
    // Durations in whole milliseconds: matiec reads no `us`.
    // Durations in whole milliseconds: matiec reads no `us`.
    let cycle_us = *r.pick(&[10_000u64, 20_000, 100_000]);
    let second_initial = r.chance(15);
    let mut text = String::from("PROGRAM Chart\nVAR_INPUT\n");
    for i in &inputs {
        text += &format!("  {i} : BOOL;\n");
    }
    text += "END_VAR\nVAR\n";
    for o in &outs {
        text += &format!("  {o} : BOOL;\n");
    }
    text += "  Cnt : INT;\n  Tm : TON;\nEND_VAR\n";
    let literal = |r: &mut Rng| -> String {
        let x =
            if r.chance(25) { format!("{}.X", r.pick(&steps)) } else { r.pick(&inputs).clone() };
        if r.chance(30) { format!("NOT {x}") } else { x }
    };
    let condition = |r: &mut Rng| -> String {
        match r.below(4) {
            0 => literal(r),
            1 => format!("{} AND {}", literal(r), literal(r)),
            2 => format!("{} OR {}", literal(r), literal(r)),
            _ => "TRUE".to_string(),
        }
    };
    for (k, s) in steps.iter().enumerate() {
        let initial = k == 0 || (k == 1 && second_initial);
        text += &format!("{} {s}:\n", if initial { "INITIAL_STEP" } else { "STEP" });
        for _ in 0..r.below(3) {
            let target =
                if r.chance(50) { r.pick(&outs).clone() } else { r.pick(&actions).clone() };
            if !initial && r.chance(15) {
                let q = *r.pick(&["D", "L"]);
                let t = (1 + r.below(4)) * cycle_us - if r.chance(50) { cycle_us / 2 } else { 0 };
                text += &format!("  {target}({q}, T#{}ms);\n", t / 1000);
            } else {
                text += &format!("  {target}({});\n", r.pick(&QUALIFIERS));
            }
        }
        text += "END_STEP\n";
    }
    let n_transitions = n_steps + r.below(3) as usize;
    for k in 0..n_transitions {
        // Every step is left by some transition: the k-th from step k, then random ones.
        let from = if k < n_steps { steps[k].clone() } else { r.pick(&steps).clone() };
        let from = if r.chance(10) {
            let other = r.pick(&steps).clone();
            if other == from { from } else { format!("({from}, {other})") }
        } else {
            from
        };
        let to = r.pick(&steps).clone();
        let to = if r.chance(10) {
            let other = r.pick(&steps).clone();
            if other == to { to } else { format!("({to}, {other})") }
        } else {
            to
        };
        let priority =
            if r.chance(20) { format!(" (PRIORITY := {})", r.below(3)) } else { String::new() };
        text += &format!(
            "TRANSITION{priority} FROM {from} TO {to}\n  := {};\nEND_TRANSITION\n",
            condition(&mut r)
        );
    }
    for a in &actions {
        text += &format!("ACTION {a}:\n");
        for _ in 0..1 + r.below(2) {
            match r.below(4) {
                0 => text += "  Cnt := Cnt + 1;\n",
                1 => {
                    text += &format!(
                        "  Tm(IN := {}, PT := T#{}ms);\n",
                        literal(&mut r),
                        2 * cycle_us / 1000
                    )
                }
                2 => text += &format!("  {} := Tm.Q OR {};\n", r.pick(&outs), literal(&mut r)),
                _ => text += &format!("  {} := {};\n", r.pick(&outs), condition(&mut r)),
            }
        }
        text += "END_ACTION\n";
    }
    text += "END_PROGRAM\n";
    text += &format!(
        "CONFIGURATION Config\n  RESOURCE Res ON PLC\n    TASK Main(INTERVAL := T#{}ms, PRIORITY := 0);\n    PROGRAM Inst WITH Main : Chart;\n  END_RESOURCE\nEND_CONFIGURATION\n",
        cycle_us / 1000
    );
    Generated { text, pou: "Chart".into(), inputs, bits: outs, cycle_us }
}
