//! Instruction List end to end: the water plant in IL (a `.il` file and a PLCopen `<IL>` body, beside the `<ST>` one) proves what `water.ld` proves and its faulty variants are refuted; malformed and unsupported IL fails with located errors (`tests/data/il/rejects/`); random IL programs run as an interpreter written from the standard and matiec's library runs them, and compile to equations that hold at every scan.

use crate::common;
use crate::common::il_gen;
use crate::common::il_ref;
use crate::common::scan_eval;
use crate::common::st_gen;

use std::path::Path;

use common::{files_with, ii_prove, laws, text, verdicts};
use ii_prove::diag::Sources;

/// The water plant in IL and in PLCopen text bodies: the same verdicts as `water.ld`,
/// after its own `#ASSERT` properties, and the same laws in the proofs.
#[test]
fn the_water_plant_in_il_and_in_plcopen_text_proves_what_water_ld_proves() {
    let reference = verdicts(&["examples/water.ld", "examples/water.ii"]);
    assert!(reference.iter().all(|(_, v)| v == "proved"), "{reference:?}");
    for program in ["examples/water.il", "examples/water_il.xml", "examples/water_st.xml"] {
        let got = verdicts(&[program, "examples/water.ii"]);
        let asserted = ["one_line_at_a_time", "backflow_needs_out_valve"];
        let names: Vec<&str> = got.iter().take(2).map(|(n, _)| n.as_str()).collect();
        assert_eq!(names, asserted, "{program}");
        assert!(got[..2].iter().all(|(_, v)| v == "proved"), "{program}: {got:?}");
        assert_eq!(got[2..], reference[..], "{program}");
        let out = ii_prove(&[program, "examples/water.ii"]);
        assert_eq!(out.status.code(), Some(0), "{program}");
        assert!(text(&out.stderr).trim().is_empty(), "{program}: {}", text(&out.stderr));
        for p in ["P1a", "P2", "P3", "P4a"] {
            let a = laws(&["examples/water.ld", "examples/water.ii"], p);
            let b = laws(&[program, "examples/water.ii"], p);
            assert_eq!(a, b, "{program}: {p}");
        }
    }
}

/// Without line 2's interlock the plant may run both lines: refuted in every text form,
/// with a counterexample the scan simulator confirms, and the assertion where it stands.
#[test]
fn the_faulty_plants_are_refuted_with_confirmed_counterexamples() {
    for (program, assert_at) in [
        ("examples/water_faulty.il", "examples/water_faulty.il:49:13"),
        ("tests/data/plcopen/refuted/water_il_faulty.xml", "water_il_faulty.xml:64:13"),
        ("tests/data/plcopen/refuted/water_st_faulty.xml", "water_st_faulty.xml:49:13"),
    ] {
        let out = ii_prove(&[program, "examples/water.ii", "--only", "P2"]);
        assert_eq!(out.status.code(), Some(1), "{program}");
        let stdout = text(&out.stdout);
        assert!(stdout.contains("refuted") && stdout.contains("by the scan simulator"), "{stdout}");
        let out = ii_prove(&[program]);
        let stdout = text(&out.stdout);
        assert_eq!(out.status.code(), Some(1), "{program}: {stdout}");
        assert!(stdout.contains(assert_at), "{program}: wanted {assert_at} in {stdout}");
        assert!(stdout.contains("one_line_at_a_time") && stdout.contains("refuted"), "{stdout}");
    }
}

/// IL arithmetic is computed: the batch counter made full at six parts is refuted, the
/// count drawn as a value track up to five and confirmed by the scan simulator.
#[test]
fn integer_il_programs_are_refuted_with_the_count_drawn() {
    let files = files_with(Path::new("tests/data/il/refutes"), "il");
    assert!(!files.is_empty());
    for program in files {
        let props = program.with_extension("ii");
        let (program, props) = (program.display().to_string(), props.display().to_string());
        let out = ii_prove(&[&program, &props]);
        let stdout = text(&out.stdout);
        assert_eq!(out.status.code(), Some(1), "{program}: {stdout}");
        assert!(stdout.contains("refuted") && stdout.contains("by the scan simulator"), "{stdout}");
        let row =
            stdout.lines().find(|l| l.trim_start().starts_with("Count ")).expect("a count row");
        let values: Vec<i64> = row.split_whitespace().skip(1).map(|v| v.parse().unwrap()).collect();
        assert!(values.windows(2).all(|w| w[1] == w[0] + 1) && values.last() == Some(&5), "{row}");
    }
}

#[test]
fn show_names_il_lines() {
    let out = ii_prove(&["show", "examples/water.il"]);
    let stdout = text(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(stdout.contains("Compiled from an Instruction List program"), "{stdout}");
    assert!(stdout.contains("assume L53: T1_Q = 5s/L1_Prod"), "{stdout}");
    // `AND( … )` computes its operand first.
    assert!(stdout.contains("assume L75: Bf_valve = (L1_pump + L2_pump) · L_flow · ¬H_flow"));
}

/// A forward jump guards what it skips, the CR at a label is that of the path taken
/// (`jumps.il`); a function block and a function written in IL are inlined, a `RET` in
/// the block ending only the block (`user_block.il`); a call a jump or `CALC` skips runs
/// the block only at the scans it is called (`skipped_calls.il`).
#[test]
fn il_programs_with_jumps_and_user_blocks_prove_their_properties() {
    for name in ["jumps", "user_block", "batch", "skipped_calls"] {
        let program = format!("tests/data/il/programs/{name}.il");
        let props = format!("tests/data/il/programs/{name}.ii");
        let out = ii_prove(&["show", &program]);
        let stdout = text(&out.stdout);
        assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
        assert!(text(&out.stderr).trim().is_empty(), "{}", text(&out.stderr));
        let got = verdicts(&[&program, &props]);
        assert!(got.len() > 3 && got.iter().all(|(_, v)| v == "proved"), "{got:?}\n{stdout}");
    }
}

#[test]
fn malformed_and_unsupported_il_is_refused_with_located_errors() {
    let n = common::check_rejects("tests/data/il/rejects", "il");
    assert!(n >= 12, "{n} reject files");
}

/// The IL forms matiec reads parse (what they use that is not modelled is refused when
/// lowered, with a located error).
#[test]
fn il_forms_parse() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/il/parses");
    let files = files_with(&dir, "il");
    assert!(files.len() >= 8, "{} files", files.len());
    for f in files {
        let mut sources = Sources::new();
        let file = sources.add(f.display().to_string(), std::fs::read_to_string(&f).expect("read"));
        let unit = ii_prove::iec::read(&sources, file);
        assert!(unit.is_ok(), "{}: {:?}", f.display(), unit.err());
        let il = unit
            .expect("parsed")
            .pous
            .iter()
            .any(|p| matches!(p.body, ii_prove::iec::ast::Body::Il(_)));
        assert!(il, "{}: no IL body", f.display());
    }
}

fn programs_to_run() -> u64 {
    std::env::var("II_IL_PROGRAMS").ok().and_then(|v| v.parse().ok()).unwrap_or(250)
}

/// Random IL programs: at every scan every local and function-block output has the value
/// the reference interpreter gives it, and every compiled equation holds.
#[test]
fn random_il_programs_run_as_the_reference_interpreter_runs_them() {
    let first: u64 = std::env::var("II_IL_FIRST").ok().and_then(|v| v.parse().ok()).unwrap_or(0);
    let (mut programs, mut bit_scans, mut int_scans) = (0u64, 0u64, 0u64);
    let (mut jumps, mut nested, mut to_bool) = (0u64, 0u64, 0u64);
    let (mut left_out, mut twice) = (0u64, 0u64);
    let mut tally = scan_eval::Tally::default();
    for seed in first..first + programs_to_run() {
        let g = il_gen::program(seed);
        jumps += u64::from(g.ins.iter().any(|i| matches!(i, il_gen::Ins::Jump(..))));
        nested += u64::from(g.ins.iter().any(|i| matches!(i, il_gen::Ins::Nested(..))));
        to_bool += u64::from(g.ins.iter().any(|i| matches!(i, il_gen::Ins::ToBool(..))));
        let (omits, again) = il_gen::calls_leaving_inputs_out(&g);
        (left_out, twice) = (left_out + u64::from(omits), twice + u64::from(again));
        let mut sources = Sources::new();
        let file = sources.add("random.il", g.text.clone());
        let lowered =
            ii_prove::iec::read(&sources, file).map_err(|e| format!("{e:?}")).and_then(|u| {
                ii_prove::iec::lower(&sources, &u, None, None).map_err(|e| format!("{e:?}"))
            });
        let lowered = match lowered {
            Ok(l) => l,
            Err(e) => {
                tally.fail(seed, &g.text, &format!("refused: {e}"));
                continue;
            }
        };
        let compiled = match ii_prove::program::compile(&lowered.program, &Default::default()) {
            Ok(c) => c,
            Err(e) => {
                tally.fail(seed, &g.text, &format!("not compiled: {e:?}"));
                continue;
            }
        };
        programs += 1;
        let schedule = st_gen::schedule_of(&g.inputs, seed, 120);
        let mut reference = il_ref::IlRef::new(&g);
        let mut compare = |scan: usize, sim: &ii_prove::program::simulate::Simulator| {
            reference.step(&schedule[scan]);
            for b in &g.bits {
                if !sim.is_known(b) {
                    return Err(format!("{b} is unknown at scan {scan}"));
                }
                if sim.bit(b) != reference.bit(b) {
                    return Err(format!(
                        "{b} is {} at scan {scan}; the interpreter says {}",
                        sim.bit(b),
                        reference.bit(b)
                    ));
                }
            }
            bit_scans += g.bits.len() as u64;
            for (n, _) in &g.ints {
                if !sim.is_known(n) || sim.int(n) != Some(reference.int(n)) {
                    return Err(format!(
                        "{n} is {:?} at scan {scan}; the interpreter says {}",
                        sim.int(n).filter(|_| sim.is_known(n)),
                        reference.int(n)
                    ));
                }
            }
            int_scans += g.ints.len() as u64;
            Ok(())
        };
        let run = scan_eval::check_scans(
            &lowered.program,
            &compiled,
            g.cycle_us,
            &schedule,
            &mut compare,
        );
        tally.add(seed, &g.text, run);
    }
    let scan_eval::Checked { scans, hypotheses, fired } = tally.totals;
    tally.finish(&format!(
        "random IL programs: {programs} lowered ({jumps} with jumps, {nested} with parentheses, {to_bool} with `INT_TO_BOOL`, {left_out} with a call that leaves an input out, {twice} with an instance called twice), {scans} scans, {bit_scans} bit-scans and {int_scans} integer-scans compared with the interpreter, {hypotheses} hypotheses checked at every scan, {fired} timer hypotheses fired"
    ));
}
