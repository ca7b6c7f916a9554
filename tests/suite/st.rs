//! The Structured Text front end end to end: the water plant in ST proves what `water.ld` proves and its faulty variant is refuted, malformed and unsupported files fail with located errors (data in `tests/data/st/rejects/`), and random ST programs (over BOOLs and integers, and over REALs) compile to equations that hold at every scan of the scan model's simulator.

use crate::common;
use crate::common::real_gen;
use crate::common::scan_eval;
use crate::common::st_gen;

use common::{ii_prove, laws, text, verdicts};
use scan_eval::{Checked, Tally, check_scans};

#[test]
fn the_water_plant_in_st_proves_what_water_ld_proves() {
    let reference = verdicts(&["examples/water.ld", "examples/water.ii"]);
    assert!(reference.iter().all(|(_, v)| v == "proved"), "{reference:?}");
    // Its own #ASSERT properties come first, then those of water.ii.
    let st = verdicts(&["examples/water.st", "examples/water.ii"]);
    let asserted = ["one_line_at_a_time", "backflow_needs_out_valve"];
    assert_eq!(st[..2].iter().map(|(n, _)| n.as_str()).collect::<Vec<_>>(), asserted);
    assert_eq!(st[2..], reference[..]);
    let out = ii_prove(&["examples/water.st", "examples/water.ii"]);
    assert_eq!(out.status.code(), Some(0));
    assert!(text(&out.stderr).trim().is_empty(), "no warnings: {}", text(&out.stderr));
    for p in ["P1a", "P2", "P3", "P4a"] {
        let a = laws(&["examples/water.ld", "examples/water.ii"], p);
        let b = laws(&["examples/water.st", "examples/water.ii"], p);
        assert_eq!(a, b, "{p}");
    }
}

#[test]
fn the_faulty_st_plant_is_refuted_with_a_counterexample_the_simulator_confirms() {
    let out = ii_prove(&["examples/water_faulty.st", "examples/water.ii", "--only", "P2"]);
    assert_eq!(out.status.code(), Some(1));
    let stdout = text(&out.stdout);
    assert!(stdout.contains("refuted") && stdout.contains("by the scan simulator"), "{stdout}");
}

#[test]
fn assert_comments_are_properties_checked_where_they_stand() {
    let out = ii_prove(&["examples/water.st"]);
    let stdout = text(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{stdout}{}", text(&out.stderr));
    assert!(
        stdout.contains("one_line_at_a_time") && stdout.contains("(examples/water.st:31:13)"),
        "{stdout}"
    );
    assert!(stdout.contains("2 proved, 0 refuted"), "{stdout}");
    // Without its interlock, line 2 may start while line 1 runs: refuted, confirmed.
    let out = ii_prove(&["examples/water_faulty.st"]);
    let stdout = text(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    assert!(stdout.contains("one_line_at_a_time") && stdout.contains("refuted"), "{stdout}");
    assert!(stdout.contains("by the scan simulator"), "{stdout}");
}

/// A configuration's program instances all run, every scan, by task priority, sharing
/// their globals; a local name two instances declare takes the instance's name.
#[test]
fn every_program_of_the_configuration_runs_in_task_order() {
    let st = "tests/data/st/programs/two_tasks.st";
    let stdout = shown(st);
    // Pumps (task Fast, priority 1) runs before Alarm (task Slow), though declared after.
    let run = stdout.find("assume L06: Run = P_Latch").expect("Pumps writes Run");
    let timer = stdout.find("assume L13: T_Q = 2s/(Run · Fault)").expect("Alarm reads it");
    assert!(run < timer, "{stdout}");
    assert!(stdout.contains("A_Latch") && stdout.contains("P_Latch"), "{stdout}");
    let out = ii_prove(&[st, "tests/data/st/programs/two_tasks.ii"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stdout));
}

#[test]
fn show_names_st_lines() {
    let out = ii_prove(&["show", "examples/water.st"]);
    let stdout = text(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(stdout.contains("Compiled from a Structured Text program"), "{stdout}");
    assert!(stdout.contains("assume L33: T1_Q = 5s/L1_Prod"), "{stdout}");
    assert!(stdout.contains("// line 33: TON T1 5000000 µs"), "{stdout}");
}

/// Every file of `tests/data/st/rejects/` fails (exit 2) with the error its first two
/// lines record: `// error: FRAGMENT` and `// at: LINE:COL`.
#[test]
fn malformed_and_unsupported_st_is_refused_with_located_errors() {
    let n = common::check_rejects("tests/data/st/rejects", "st");
    assert!(n >= 15, "{n} reject files");
}

fn programs_to_run() -> u64 {
    std::env::var("II_ST_PROGRAMS").ok().and_then(|v| v.parse().ok()).unwrap_or(120)
}

/// Random ST programs: every compiled equation and recurrence holds at every scan of the
/// scan model's simulator (timers counted as matiec counts them), and every bit is known
/// (`II_ST_SHOW=1` prints each program).
#[test]
fn random_st_programs_agree_with_the_scan_simulator() {
    let first: u64 = std::env::var("II_ST_FIRST").ok().and_then(|v| v.parse().ok()).unwrap_or(0);
    let (mut programs, mut too_large, mut repeated) = (0u64, 0u64, 0u64);
    let mut tally = Tally::default();
    for seed in first..first + programs_to_run() {
        let g = st_gen::program(seed);
        if std::env::var_os("II_ST_SHOW").is_some() {
            eprintln!("seed {seed}:\n{}", g.text);
        }
        let (program, compiled) = match common::compile_text("random.st", &g.text) {
            Ok(x) => x,
            Err(e) => {
                tally.fail(seed, &g.text, &format!("refused: {e}"));
                continue;
            }
        };
        programs += 1;
        repeated += u64::from(!program.repeated_timers().is_empty());
        // An intermediate value too large to inline is an unconstrained signal (sound; the
        // evaluator treats it existentially).
        too_large += u64::from(compiled.signals.values().any(|k| k.is_unconstrained()));
        let schedule = st_gen::schedule(&g, seed, 120);
        let run = check_scans(&program, &compiled, g.cycle_us, &schedule, &mut |_, _| Ok(()));
        tally.add(seed, &g.text, run);
    }
    let Checked { scans, hypotheses, fired } = tally.totals;
    tally.finish(&format!(
        "random ST programs: {programs} compiled ({too_large} with an intermediate value too large to inline, {repeated} with a timer called at several places), {scans} scans, {hypotheses} hypotheses checked at every scan, {fired} timer hypotheses fired"
    ));
}

/// Random programs over `REAL`s (`common/real_gen.rs`; `II_REAL_PROGRAMS`, 8 by default,
/// `II_REAL_SCANS` scans, 10): every compiled equation holds at every scan of the scan
/// model's simulator, the `REAL` inputs driven with numbers, zeros, infinities, NaNs and
/// subnormals (values the C computes in `double` among them); a program that compares a
/// value ii-prove leaves unconstrained is counted, not run. Few and short, as a `REAL` operation compiles to
/// hundreds of equations; what the lowering reads programs as is checked against matiec
/// by `tests/suite/iec_oracle.rs`, and each `REAL` circuit against `f32` in `bitvec::float`.
#[test]
fn random_real_programs_agree_with_the_scan_simulator() {
    let var = |name: &str, default: u64| {
        std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
    };
    let (n, length) = (var("II_REAL_PROGRAMS", 8), var("II_REAL_SCANS", 10));
    let (mut exact, mut partial) = (0u64, 0u64);
    let mut tally = Tally::default();
    for seed in 0..n {
        let g = real_gen::program(seed);
        let (program, compiled) = match common::compile_text("random.st", &g.text) {
            Ok(x) => x,
            Err(e) => {
                tally.fail(seed, &g.text, &format!("refused: {e}"));
                continue;
            }
        };
        if compiled.signals.values().any(|k| k.is_unconstrained()) {
            partial += 1;
            continue;
        }
        exact += program.integers.values().filter(|v| v.ty.real && !v.input).count() as u64;
        let schedule = real_gen::schedule(&g, seed, length as usize);
        let run = check_scans(&program, &compiled, g.cycle_us, &schedule, &mut |_, _| Ok(()));
        tally.add(seed, &g.text, run);
    }
    let Checked { scans, hypotheses, .. } = tally.totals;
    tally.finish(&format!(
        "random REAL programs: {n}, {partial} with an unconstrained value, {exact} REAL variables computed in the others, {scans} scans, {hypotheses} hypotheses checked at every scan"
    ));
    assert!(exact >= n / 2, "too few REAL variables computed: {exact}");
}

/// What `show` prints for the program at `path`, which loads.
fn shown(path: &str) -> String {
    let out = ii_prove(&["show", path]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    text(&out.stdout)
}

/// User function blocks and functions are inlined: each instance's variables are bits
/// of its own, a function's are its call's.
#[test]
fn user_function_blocks_and_functions_are_inlined() {
    let st = "tests/data/st/programs/user_blocks.st";
    let stdout = shown(st);
    assert!(stdout.contains("M1_Overload_Q = 2s/(M1_Run · ¬M1_Ok)"), "{stdout}");
    assert!(stdout.contains("M2_Overload_Q = 2s/(M2_Run · ¬M2_Ok)"), "{stdout}");
    assert!(stdout.contains("Permit_1 = Permit_1_Guard · ¬Permit_1_EStop"), "{stdout}");
    let got = verdicts(&[st, "tests/data/st/programs/user_blocks.ii"]);
    assert!(got.len() == 6 && got.iter().all(|(_, v)| v == "proved"), "{got:?}");
}

/// `CASE` is a chain of choices on exact comparisons of the selector's bits (an integer
/// input here); a `FOR` loop with constant bounds is unrolled.
#[test]
fn case_and_constant_for_loops_are_lowered() {
    let st = "tests/data/st/programs/case_and_for.st";
    let stdout = shown(st);
    assert!(stdout.contains("Blink = ¬pre Blink"), "three toggles in one scan: {stdout}");
    assert!(stdout.contains("input Mode_b0, Mode_b1"), "the selector is an input: {stdout}");
    assert!(!stdout.contains("unconstrained"), "{stdout}");
    let got = verdicts(&[st, "tests/data/st/programs/case_and_for.ii"]);
    assert!(got.len() == 5 && got.iter().all(|(_, v)| v == "proved"), "{got:?}");
}

/// Integers in ST, exact: a CTU's count, a CONSTANT preset, comparisons in `#ASSERT`s and
/// in `.ii` atoms; the faulty preset is refuted with the count drawn, confirmed by the
/// scan simulator.
#[test]
fn the_box_counter_in_st_is_proved_and_its_faulty_preset_refuted() {
    let got = verdicts(&["examples/box.st", "examples/box.ii"]);
    assert!(got.len() == 5 && got.iter().all(|(_, v)| v == "proved"), "{got:?}");
    let out = ii_prove(&["examples/box_faulty.st", "examples/box.ii", "--only", "Stop"]);
    let stdout = text(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    assert!(stdout.contains("by the scan simulator"), "{stdout}");
    assert!(stdout.contains("Count_CV") && stdout.contains(" 10"), "the count is drawn: {stdout}");
}

#[test]
fn a_variable_not_computed_is_named_with_its_type() {
    let st = "PROGRAM p\nVAR\n  n : DINT;\n  l : LINT;\n  b : BOOL;\nEND_VAR\nn := LINT_TO_DINT(l);\n\
              b := n > 1;\nEND_PROGRAM\nCONFIGURATION c RESOURCE res ON PLC TASK t(INTERVAL := \
              T#10ms, PRIORITY := 0); PROGRAM inst WITH t : p; END_RESOURCE END_CONFIGURATION\n";
    let dir = std::env::temp_dir().join(format!("ii-prove-st-types-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("types.st");
    std::fs::write(&path, st).unwrap();
    let out = ii_prove(&["show", path.to_str().unwrap()]);
    let all = text(&out.stdout) + &text(&out.stderr);
    assert!(all.contains("the DINT n is not computed (the conversion LINT_TO_DINT"), "{all}");
}

/// A TIME variable written only with its declared literal, and a function block's TIME
/// input given one literal by each instance's call, are exact presets; a TIME variable
/// also written with another literal leaves its timer unconstrained, with the reason.
#[test]
fn time_variables_constant_in_fact_are_exact_presets() {
    let st = "tests/data/st/programs/time_presets.st";
    let stdout = shown(st);
    let equations = [
        "AlarmTimer_Q = 2s/Start",
        "B1_T_Q = 500ms/B1_Run",
        "B2_T_Q = 1s/B2_Run",
        "SlowTimer_Q = TON_SlowTimer",
        "a delay given by the variable Slow is not a constant: it holds T#1s and is also \
         written with T#3s at line 42",
    ];
    for e in equations {
        assert!(stdout.contains(e), "{e}: {stdout}");
    }
    let got = verdicts(&[st, "tests/data/st/programs/time_presets.ii"]);
    assert!(got.len() == 4 && got.iter().all(|(_, v)| v == "proved"), "{got:?}");
    // Variants, each with the timer it leaves unconstrained and the reason.
    let variants = [
        // The block's body also writes its input: no instance's timer has a preset.
        (
            ("  Q := T.Q;", "  Q := T.Q;\n  On := T#3s;"),
            "B1_T_Q = TON_B1_T",
            "the variable B1_On is not a constant: it holds T#500ms and is also written with \
             T#3s at line 17",
        ),
        (
            ("  Delay := T#2s;", "  Delay := Slow;"),
            "AlarmTimer_Q = TON_AlarmTimer",
            "the variable Delay is not a constant: it is written with an expression at line \
             38, not a literal duration",
        ),
        (
            ("  Delay : TIME", "  Delay AT %MD0 : TIME"),
            "AlarmTimer_Q = TON_AlarmTimer",
            "the variable Delay is not a constant: it is located at %MD0, which the outside \
             world may write",
        ),
    ];
    let dir = std::env::temp_dir().join(format!("ii-prove-st-time-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (k, ((from, to), equation, reason)) in variants.into_iter().enumerate() {
        let variant = std::fs::read_to_string(st).unwrap().replace(from, to);
        let path = dir.join(format!("time_presets_{k}.st"));
        std::fs::write(&path, variant).unwrap();
        let all = shown(path.to_str().unwrap());
        assert!(all.contains(equation) && all.contains(reason), "{equation}, {reason}: {all}");
    }
}

/// A call that leaves an input out runs the block with the value the instance last
/// received (FALSE, 0 or T#0s before any call gives it): the latch's reset, the edge
/// detector's memory and clock, the counter's preset and a TON's `PT` never given.
#[test]
fn inputs_left_out_keep_the_values_the_instance_last_received() {
    let stdout = shown("tests/data/proves_programs/kept_inputs.st");
    let equations = [
        "Latch_R_in = Stop",
        "Latch_Q1 = SR(Start, Latch_R_in + Stop)",
        "Edge_Q = Edge_CLK_in · ¬Jog",
        "Settle_Q = 10ms/Run",
        "Jogs_R_in = Stop",
    ];
    for e in equations {
        assert!(stdout.contains(e), "{e}: {stdout}");
    }
    assert!(!stdout.contains("unconstrained"), "{stdout}");
}

/// A pulse timer called twice in a scan, the second call keeping the first's `PT`, runs
/// call by call as matiec's block does (the matiec oracle's random programs check its
/// values): its `Q` is computed, not unconstrained.
#[test]
fn a_pulse_timer_called_twice_runs_call_by_call() {
    let source = "PROGRAM P\n  VAR_INPUT\n    A, B : BOOL;\n  END_VAR\n  VAR\n    P0 : TP;\n    \
                X : BOOL;\n  END_VAR\n  P0(IN := A, PT := T#50ms);\n  X := P0.Q;\n  \
                P0(IN := B);\nEND_PROGRAM\n";
    let dir = std::env::temp_dir().join(format!("ii-prove-st-tp2-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("tp2.st");
    std::fs::write(&path, source).unwrap();
    let out = ii_prove(&["show", "--cycle", "10ms", path.to_str().unwrap()]);
    let all = text(&out.stdout) + &text(&out.stderr);
    assert!(!all.contains("unconstrained"), "{all}");
    assert!(!all.contains("not modelled"), "{all}");
    for hidden in ["P0_AGE", "P0_STATE", "P0_PT_GIVEN"] {
        assert!(all.contains(hidden), "{hidden}: {all}");
    }
}

/// What stays unconstrained (or refused) where inputs are left out, each with its reason:
/// a pulse timer called twice in a scan with two presets; a TON
/// called twice whose second call keeps a `PT` that is not one literal; an input written
/// outside the call.
#[test]
fn inputs_left_out_that_are_not_one_value_are_named_with_the_reason() {
    let program = |body: &str| {
        format!(
            "PROGRAM P\n  VAR_INPUT\n    A, B : BOOL;\n  END_VAR\n  VAR\n    T0 : TON;\n    \
             P0 : TP;\n    X : BOOL;\n  END_VAR\n{body}END_PROGRAM\n"
        )
    };
    let cases = [
        (
            "  P0(IN := A, PT := T#50ms);\n  X := P0.Q;\n  P0(IN := B, PT := T#1s);\n",
            "the integer P0_ET is not computed (its timer is called with different presets",
        ),
        // Called twice, the second call keeping a PT the first gives only under a
        // condition (T#0s or T#1s): two presets for one count.
        (
            "  IF A THEN\n    T0(IN := A, PT := T#1s);\n  END_IF;\n  T0(IN := B);\n  X := T0.Q;\n",
            "the accumulator T0 is also written by another element",
        ),
        (
            "  T0(IN := A, PT := T#1s);\n  X := T0.Q;\n  T0.IN := B;\n",
            "assigning to a member or an array element is not modelled yet",
        ),
    ];
    let dir = std::env::temp_dir().join(format!("ii-prove-st-kept-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (k, (body, reason)) in cases.into_iter().enumerate() {
        let path = dir.join(format!("kept_{k}.st"));
        std::fs::write(&path, program(body)).unwrap();
        let out = ii_prove(&["show", "--cycle", "10ms", path.to_str().unwrap()]);
        let all = text(&out.stdout) + &text(&out.stderr);
        assert!(all.contains(reason), "{reason}: {all}");
    }
}
