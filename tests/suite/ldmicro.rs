//! Integration tests for the LDmicro reader and simulator: the real-world corpus, malformed files, fuzzing and the examples.

use crate::common;

use std::collections::BTreeMap;
use std::fs;
use std::path::{Path, PathBuf};

use ii_prove::diag::{Diagnostic, RenderStyle, Sources, render};
use ii_prove::ladder::{
    ElementKind, HeaderVersion, LadderError, LdProgram, Simulator, decode_latin1, read_ldmicro,
};
use proptest::prelude::*;

fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/ldmicro")
}

fn load_bytes(name: &str, bytes: &[u8]) -> (Sources, Result<LdProgram, Vec<LadderError>>) {
    let mut sources = Sources::new();
    let file = sources.add(name, decode_latin1(bytes));
    let result = read_ldmicro(&sources, file);
    (sources, result)
}

fn load(path: &Path) -> (Sources, Result<LdProgram, Vec<LadderError>>) {
    let bytes = fs::read(path).expect("test data is readable");
    let name = path.strip_prefix(data()).unwrap_or(path).display().to_string();
    load_bytes(&name, &bytes)
}

/// Renders an error and checks it is located: `name:line:col` and a caret.
fn render_located(sources: &Sources, e: &LadderError) -> String {
    let text = render(&Diagnostic::from(e.clone()), sources, RenderStyle { ascii: true });
    let name = sources.name(0);
    let located = text.lines().any(|l| {
        l.contains(&format!("{name}:"))
            && l.split(&format!("{name}:")).nth(1).is_some_and(|rest| {
                let mut parts = rest.split(':');
                parts.next().is_some_and(|p| p.trim().parse::<usize>().is_ok())
                    && parts.next().is_some_and(|p| {
                        p.trim().chars().take_while(|c| c.is_ascii_digit()).count() > 0
                    })
            })
    });
    assert!(located, "not located (name:line:col):\n{text}");
    assert!(text.contains('^'), "no caret:\n{text}");
    text
}

#[test]
fn corpus_loads_or_fails_located() {
    let files = common::files_with(&data().join("corpus"), "ld");
    assert_eq!(files.len(), 56, "the corpus has 56 .ld files");
    let mut loaded = 0;
    let mut failed = Vec::new();
    let mut rungs = 0;
    let mut boolean_rungs = 0;
    let mut elements = 0;
    let mut versions: BTreeMap<String, usize> = BTreeMap::new();
    let mut unmodelled: BTreeMap<String, usize> = BTreeMap::new();
    for path in &files {
        let (sources, result) = load(path);
        match result {
            Ok(p) => {
                loaded += 1;
                rungs += p.rungs.len();
                *versions.entry(format!("{:?}", p.version)).or_default() += 1;
                for r in &p.rungs {
                    let es = r.elements();
                    elements += es.len();
                    if !r.is_comment(&p.version) && es.iter().all(|e| e.kind.is_boolean_core()) {
                        boolean_rungs += 1;
                    }
                }
                let mut sim = Simulator::new(&p);
                sim.step(&BTreeMap::new());
                for k in sim.unmodelled() {
                    *unmodelled.entry(k.clone()).or_default() += 1;
                }
                for w in &p.warnings {
                    let text = render_located(&sources, w);
                    println!(
                        "warning in {}: {}",
                        path.display(),
                        text.lines().next().unwrap_or("")
                    );
                }
            }
            Err(errors) => {
                assert!(!errors.is_empty());
                let text = render_located(&sources, &errors[0]);
                failed.push((path.clone(), text));
            }
        }
    }
    println!(
        "LDmicro corpus: {loaded} of {} files load: {rungs} rungs ({boolean_rungs} Boolean+timer rungs), {elements} elements",
        files.len()
    );
    println!("headers: {versions:?}");
    println!("files per element the simulator does not model: {unmodelled:?}");
    for (path, text) in &failed {
        println!("FAILED {}:\n{text}", path.display());
    }
    assert!(failed.is_empty(), "{} corpus files failed", failed.len());
}

/// Every `parse_err/NAME.ld` must fail, and the rendered first error must
/// contain every line of `parse_err/NAME.expected`. A new case is a new pair of files.
#[test]
fn malformed_files_fail_with_the_expected_message() {
    let dir = data().join("parse_err");
    let files = common::files_with(&dir, "ld");
    assert!(files.len() >= 20, "only {} parse_err cases", files.len());
    for path in &files {
        let expected_path = path.with_extension("expected");
        let expected = fs::read_to_string(&expected_path)
            .unwrap_or_else(|_| panic!("{} has no .expected file", path.display()));
        let (sources, result) = load(path);
        let errors = match result {
            Ok(_) => panic!("{} loaded but should fail", path.display()),
            Err(e) => e,
        };
        let text = render_located(&sources, &errors[0]);
        for fragment in expected.lines().filter(|l| !l.trim().is_empty()) {
            assert!(
                text.contains(fragment),
                "{}: expected `{fragment}` in\n{text}",
                path.display()
            );
        }
    }
}

fn corpus_texts() -> Vec<Vec<u8>> {
    common::files_with(&data().join("corpus"), "ld")
        .iter()
        .map(|p| fs::read(p).expect("readable"))
        .collect()
}

/// Loading must never panic, and every error must render located.
fn check_no_panic(bytes: &[u8]) {
    let (sources, result) = load_bytes("fuzz.ld", bytes);
    match result {
        Ok(p) => {
            // The simulator must not panic on anything the reader accepts.
            let mut sim = Simulator::new(&p);
            let inputs: BTreeMap<String, bool> =
                p.signals().into_iter().filter(|s| s.starts_with('X')).map(|s| (s, true)).collect();
            for k in 0..6 {
                let flip: BTreeMap<String, bool> =
                    inputs.keys().map(|n| (n.clone(), k % 2 == 0)).collect();
                sim.step(&flip);
            }
        }
        Err(errors) => {
            assert!(!errors.is_empty());
            for e in &errors {
                render_located(&sources, e);
            }
        }
    }
}

/// Leaf lines for generated programs: every element family, with extreme literals.
const LEAVES: &[&str] = &[
    "CONTACTS X0 0",
    "CONTACTS X1 1",
    "CONTACTS R0 0",
    "COIL R0 0 0 0",
    "COIL Y0 1 0 0",
    "COIL Y1 0 1 0",
    "COIL Y1 0 0 1",
    "COIL R1 0 0 0 1",
    "SHORT",
    "OPEN",
    "PLACEHOLDER",
    "COMMENT hi",
    "MASTER_RELAY",
    "TON T0 30000",
    "TOF T1 20000 0",
    "RTO T2 20000",
    "RTL T2 20000",
    "THI T3 20000",
    "TCY T4 20000",
    "TON T5 Tvar",
    "TON T6 9223372036854775807 9223372036854775807",
    "OSR",
    "OSF",
    "ODR",
    "ODF",
    "OSC",
    "CTU C0 3",
    "CTD C0 -2 0 -",
    "CTC C1 2 9223372036854775807",
    "CTR C2 0 5 o",
    "CTU C3 Cmax Cinit \\",
    "RES C0",
    "RES T2",
    "EQU C1 1",
    "GEQ T0 x",
    "MOVE x 9223372036854775807",
    "MOVE T0 -32768",
    "ADD x x 1",
    "SUB x x 32767",
    "MUL x x x",
    "DIV x x 0",
    "DIV x -9223372036854775808 -1",
    "SHL x x 1",
    "IF_BIT_SET x 1",
    "UART_SEND x",
    "FORMATTED_STRING (none) 2 65 66",
    "GOTO lbl",
];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn random_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..2000)) {
        check_no_panic(&bytes);
    }

    #[test]
    fn random_keyword_soup_never_panics(
        lines in proptest::collection::vec(
            prop_oneof![
                Just("RUNG".to_string()), Just("END".to_string()), Just("SERIES".to_string()),
                Just("PARALLEL".to_string()), Just("PROGRAM".to_string()), Just("LDmicro0.1".to_string()),
                Just("IO LIST".to_string()), Just("CONTACTS X0 0".to_string()), Just("COIL Y0 0 0 0".to_string()),
                Just("TON T0 100000".to_string()), Just("CTC C0 5 0 /".to_string()), Just("OSR".to_string()),
                Just("MASTER_RELAY".to_string()), Just("DIV x y 0".to_string()), Just("RES C0".to_string()),
                Just("CTC C0 5 9223372036854775807".to_string()), Just("CTD C0 -9223372036854775808 0 -".to_string()),
                Just("TON T0 9223372036854775807 9223372036854775807".to_string()), Just("TOF T0 0 -9223372036854775807".to_string()),
                Just("MOVE T0 9223372036854775807".to_string()), Just("ADD C0 C0 9223372036854775807".to_string()),
                Just("DIV x -9223372036854775808 -1".to_string()), Just("TON T0 Tvar".to_string()), Just("LDmicro0.2".to_string()),
                "[A-Z_]{1,8}( [A-Za-z0-9-]{1,5}){0,4}",
            ],
            0..60,
        )
    ) {
        check_no_panic(lines.join("\n").as_bytes());
    }

    #[test]
    fn random_valid_programs_simulate_without_panic(
        header in prop_oneof![Just("LDmicro0.1"), Just("LDmicro0.2"), Just("LDmicro")],
        cycle in prop_oneof![Just(1u64), Just(1000u64), Just(10000u64)],
        rungs in proptest::collection::vec(
            proptest::collection::vec(
                (prop::sample::select(LEAVES.to_vec()), prop::sample::select(LEAVES.to_vec()), 0u8..3),
                1..6,
            ),
            1..8,
        ),
    ) {
        let mut text = format!("{header}\nCYCLE={cycle}\nPROGRAM\n");
        for rung in rungs {
            text.push_str("RUNG\n");
            for (a, b, shape) in rung {
                match shape {
                    0 => text.push_str(&format!("{a}\n")),
                    1 => text.push_str(&format!("PARALLEL\n{a}\n{b}\nEND\n")),
                    _ => text.push_str(&format!("PARALLEL\nSERIES\n{a}\n{b}\nEND\n{b}\nEND\n")),
                }
            }
            text.push_str("END\n");
        }
        let (_, result) = load_bytes("gen.ld", text.as_bytes());
        prop_assert!(result.is_ok(), "{text}");
        check_no_panic(text.as_bytes());
    }

    #[test]
    fn mutated_corpus_files_never_panic(
        which in any::<prop::sample::Index>(),
        edits in proptest::collection::vec((0u8..3, any::<prop::sample::Index>()), 1..6),
        cut in any::<prop::sample::Index>(),
        truncate in any::<bool>(),
    ) {
        let texts = corpus_texts();
        let text = &texts[which.index(texts.len())];
        let mut lines: Vec<&[u8]> = text.split(|&b| b == b'\n').collect();
        for (op, at) in edits {
            if lines.is_empty() {
                break;
            }
            let i = at.index(lines.len());
            match op {
                0 => { lines.remove(i); }
                1 => { let l = lines[i]; lines.insert(i, l); }
                _ => { let l = lines[i]; lines.push(l); }
            }
        }
        let mut bytes = lines.join(&b'\n');
        if truncate && !bytes.is_empty() {
            bytes.truncate(cut.index(bytes.len()));
        }
        check_no_panic(&bytes);
    }
}

#[test]
#[ignore = "prints the rendered parse_err diagnostics for eyeballing"]
fn show_parse_errors() {
    for path in common::files_with(&data().join("parse_err"), "ld") {
        let (sources, result) = load(&path);
        if let Err(errors) = result {
            println!("{}", render_located(&sources, &errors[0]));
        }
    }
}

fn example(name: &str) -> LdProgram {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(name);
    let (sources, result) = load(&path);
    match result {
        Ok(p) => {
            assert!(p.warnings.is_empty(), "{name}: {:?}", p.warnings);
            p
        }
        Err(errors) => panic!("{name}: {}", render_located(&sources, &errors[0])),
    }
}

fn inputs(pairs: &[(&str, bool)]) -> BTreeMap<String, bool> {
    pairs.iter().map(|(n, v)| (n.to_string(), *v)).collect()
}

const WATER_INPUTS: [&str; 6] =
    ["XL_flow", "XH_flow", "XLine_swap", "XL1_fail", "XL2_fail", "XSP_fail"];

#[test]
fn examples_load() {
    for name in ["water.ld", "water_faulty.ld", "motor.ld", "traffic.ld", "conveyor.ld"] {
        let p = example(name);
        assert_eq!(p.version, HeaderVersion::V0_2("0.2".into()), "{name}");
        assert_eq!(p.cycle_us, 10000, "{name}");
        // Every rung is either a comment rung or pure Boolean + timers (class A).
        for r in &p.rungs {
            assert!(
                r.elements().iter().all(|e| e.kind.is_boolean_core()),
                "{name} rung {}",
                r.number
            );
        }
    }
    let water = example("water.ld");
    let timers: Vec<_> = water
        .elements()
        .filter_map(|e| match &e.kind {
            ElementKind::Timer { delay, adjust, .. } => water.timer_scans(delay, *adjust),
            _ => None,
        })
        .collect();
    assert_eq!(timers, [500, 500], "5 s at 10 ms, LDmicro0.2: P = 500 + 0");
    let logic: Vec<_> = water.rungs.iter().filter(|r| !r.is_comment(&water.version)).collect();
    assert_eq!(logic.len(), 10, "L01..L10");
    assert_eq!(water.io_list.len(), 14);
    let signals = water.signals();
    for s in ["RDemand", "RPrio2", "RL1_Prod", "RL2_Prod", "YOut_valve"] {
        assert!(signals.contains(s), "{s}");
    }
}

#[test]
fn water_line_1_starts_5_s_after_l_flow() {
    let p = example("water.ld");
    let mut sim = Simulator::new(&p);
    let on = inputs(&[("XL_flow", true)]);
    sim.step(&on);
    assert!(sim.bit("RDemand") && sim.bit("RL1_Prod") && sim.bit("YL1_up"));
    assert!(!sim.bit("YL1_pump"));
    // P = floor(5000000 / 10000) + 0 = 500 for an LDmicro0.2 file: on at scan 501.
    for scan in 2..501 {
        sim.step(&on);
        assert!(!sim.bit("YL1_pump"), "scan {scan}");
    }
    sim.step(&on);
    assert_eq!(sim.scans(), 501);
    assert!(sim.bit("YL1_pump") && sim.bit("YL1_down") && sim.bit("YOut_valve"));
    assert!(sim.bit("YBf_valve"), "low flow only: backflow valve open");
    assert!(!sim.bit("YL2_up") && !sim.bit("YL2_pump"));
    // SP_fail stops everything in the same scan.
    sim.step(&inputs(&[("XL_flow", true), ("XSP_fail", true)]));
    for y in ["YL1_up", "YL1_pump", "YL1_down", "YOut_valve", "YBf_valve"] {
        assert!(!sim.bit(y), "{y}");
    }
}

/// Drives L_flow, then Line_swap: the faulty program starts line 2 while line 1 runs.
fn swap_scenario(p: &LdProgram) -> bool {
    let mut sim = Simulator::new(p);
    let mut both = false;
    for scan in 0..1500 {
        let swap = scan >= 700;
        sim.step(&inputs(&[("XL_flow", true), ("XLine_swap", swap)]));
        let l1 = sim.bit("YL1_up") || sim.bit("YL1_pump") || sim.bit("YL1_down");
        let l2 = sim.bit("YL2_up") || sim.bit("YL2_pump") || sim.bit("YL2_down");
        both |= l1 && l2;
    }
    both
}

#[test]
fn water_faulty_runs_both_lines_after_line_swap() {
    assert!(swap_scenario(&example("water_faulty.ld")));
    assert!(!swap_scenario(&example("water.ld")));
}

/// A small deterministic generator (no extra dependency) for long random input traces.
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        self.0 >> 33
    }
}

/// Random traces where each input holds for a random number of scans (so timers expire).
fn random_trace(seed: u64, names: &[&str], scans: usize) -> Vec<BTreeMap<String, bool>> {
    let mut rng = Lcg(seed);
    let mut state: BTreeMap<String, bool> = names.iter().map(|n| (n.to_string(), false)).collect();
    let mut hold: BTreeMap<String, u64> = names.iter().map(|n| (n.to_string(), 0)).collect();
    (0..scans)
        .map(|_| {
            for n in names {
                let h = hold.get_mut(*n).expect("present");
                if *h == 0 {
                    let v = rng.next().is_multiple_of(3);
                    state.insert(n.to_string(), v);
                    *h = 1 + rng.next() % 900;
                } else {
                    *h -= 1;
                }
            }
            state.clone()
        })
        .collect()
}

#[test]
fn water_properties_hold_on_random_traces_and_p2_fails_for_the_faulty_one() {
    let good = example("water.ld");
    let faulty = example("water_faulty.ld");
    let mut faulty_violations = 0;
    for seed in 0..12 {
        let trace = random_trace(seed, &WATER_INPUTS, 4000);
        let mut sim = Simulator::new(&good);
        let (mut up1, mut up2) = (0u64, 0u64);
        for inp in &trace {
            sim.step(inp);
            let b = |n: &str| sim.bit(n);
            up1 = if b("YL1_up") { up1 + 1 } else { 0 };
            up2 = if b("YL2_up") { up2 + 1 } else { 0 };
            // P1: pump ⇒ 5s/up (on for the last 500 scans, this one included).
            assert!(!b("YL1_pump") || up1 >= 500, "P1 line 1, seed {seed}");
            assert!(!b("YL2_pump") || up2 >= 500, "P1 line 2, seed {seed}");
            // P2: never both lines.
            let l1 = b("YL1_up") || b("YL1_pump") || b("YL1_down");
            let l2 = b("YL2_up") || b("YL2_pump") || b("YL2_down");
            assert!(!(l1 && l2), "P2, seed {seed}, scan {}", sim.scans());
            // P3: SP_fail stops everything.
            if inp["XSP_fail"] {
                assert!(!l1 && !l2 && !b("YOut_valve") && !b("YBf_valve"), "P3");
            }
            // P4: a failed line is off.
            assert!(!inp["XL1_fail"] || !l1, "P4 line 1");
            assert!(!inp["XL2_fail"] || !l2, "P4 line 2");
        }
        let out = ii_prove::ladder::run(&faulty, &trace);
        faulty_violations += out.iter().filter(|b| b["YL1_up"] && b["YL2_up"]).count();
    }
    assert!(faulty_violations > 0, "random traces should expose the faulty interlock");
}

#[test]
fn motor_seal_in_and_overload_latch() {
    let p = example("motor.ld");
    let mut sim = Simulator::new(&p);
    sim.step(&inputs(&[("XStart", true)]));
    assert!(sim.bit("YMotor"));
    sim.step(&inputs(&[("XStart", false)]));
    assert!(sim.bit("YMotor"), "sealed in");
    sim.step(&inputs(&[("XStop", true)]));
    assert!(!sim.bit("YMotor"));
    sim.step(&inputs(&[("XStop", false), ("XStart", true)]));
    assert!(sim.bit("YMotor"));
    sim.step(&inputs(&[("XStart", false), ("XOverload", true)]));
    assert!(!sim.bit("YMotor") && sim.bit("YFault_lamp"));
    sim.step(&inputs(&[("XOverload", false), ("XStart", true)]));
    assert!(!sim.bit("YMotor"), "tripped until reset");
    sim.step(&inputs(&[("XStart", false), ("XReset", true)]));
    assert!(!sim.bit("YFault_lamp"));
    sim.step(&inputs(&[("XReset", false), ("XStart", true)]));
    assert!(sim.bit("YMotor"));
}

#[test]
fn traffic_light_cycles_with_one_lamp_at_a_time() {
    let p = example("traffic.ld");
    let mut sim = Simulator::new(&p);
    let run = inputs(&[("XRun", true)]);
    let mut colours = Vec::new();
    for _ in 0..2500 {
        sim.step(&run);
        let lit: Vec<&str> =
            ["Yred", "Ygreen", "Yyellow"].into_iter().filter(|y| sim.bit(y)).collect();
        assert_eq!(lit.len(), 1, "scan {}: {lit:?}", sim.scans());
        if colours.last() != Some(&lit[0]) {
            colours.push(lit[0]);
        }
    }
    assert_eq!(&colours[..7], ["Yred", "Ygreen", "Yyellow", "Yred", "Ygreen", "Yyellow", "Yred"]);
    sim.step(&inputs(&[("XRun", false)]));
    assert!(sim.bit("Yred") && !sim.bit("Ygreen") && !sim.bit("Yyellow"));
}

#[test]
fn conveyor_upstream_never_runs_without_downstream() {
    let p = example("conveyor.ld");
    let mut sim = Simulator::new(&p);
    sim.step(&inputs(&[("XStart", true)]));
    assert!(sim.bit("YConv2") && !sim.bit("YConv1"));
    // LDmicro0.2: P = 200 scans, so on at the 201st scan.
    for _ in 0..199 {
        sim.step(&inputs(&[("XStart", false)]));
    }
    assert!(!sim.bit("YConv1"));
    sim.step(&inputs(&[("XStart", false)]));
    assert!(sim.bit("YConv1"), "2 s (200 scans) after downstream started");
    sim.step(&inputs(&[("XStop", true)]));
    assert!(!sim.bit("YConv1") && sim.bit("YConv2"), "run-on");
    for _ in 0..999 {
        sim.step(&inputs(&[("XStop", false)]));
    }
    assert!(sim.bit("YConv2"));
    sim.step(&inputs(&[("XStop", false)]));
    assert!(!sim.bit("YConv2"), "stops after the 10 s run-on");
    for seed in 0..6 {
        for b in ii_prove::ladder::run(&p, &random_trace(seed, &["XStart", "XStop", "XJam"], 3000))
        {
            assert!(!b["YConv1"] || b["YConv2"]);
        }
    }
}

/// A slice's simulator, given only the inputs it reads (`ScanSimulator::reads`), shows
/// each watched coil as the whole program's simulator given every input does, scan by
/// scan on random inputs; slicing twice (its tables built once) gives the same rungs.
#[test]
fn a_slice_given_only_what_it_reads_agrees_with_the_whole_program() {
    use ii_prove::ladder::Reference;
    use std::collections::BTreeSet;
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut compared = 0usize;
    for name in ["water.ld", "conveyor.ld", "motor.ld", "traffic.ld"] {
        let (_, program) = load(&root.join(name));
        let program = program.expect("the example reads");
        let coils: Vec<String> = program
            .signals()
            .into_iter()
            .filter(|n| n.starts_with('Y') || n.starts_with('R'))
            .collect();
        let inputs: Vec<String> =
            program.signals().into_iter().filter(|n| n.starts_with('X')).collect();
        for watched in &coils {
            let names: BTreeSet<String> = [watched.clone()].into();
            let first = program.slice(&names).map(|p| p.rungs);
            assert_eq!(first, program.slice(&names).map(|p| p.rungs), "{name}: {watched}");
            let mut part = program.simulator_for(&names);
            let mut whole = Simulator::new(&program);
            for _ in 0..40 {
                let all: BTreeMap<String, bool> = inputs
                    .iter()
                    .map(|n| {
                        seed ^= seed << 13;
                        seed ^= seed >> 7;
                        seed ^= seed << 17;
                        (n.clone(), seed.is_multiple_of(3))
                    })
                    .collect();
                let given: BTreeMap<String, bool> = all
                    .iter()
                    .filter(|(n, v)| **v || part.reads(n))
                    .map(|(n, v)| (n.clone(), *v))
                    .collect();
                part.step(&given);
                whole.step(&all);
                assert_eq!(part.bit(watched), whole.bit(watched), "{name}: {watched}");
                compared += 1;
            }
        }
    }
    assert!(compared > 400, "only {compared} comparisons");
}

/// The names a peripheral read adds: its value and flags are free inputs, PERSIST's
/// one-shot is the lowering's own integer (hidden: `equiv` never compares it as an
/// output), and none of them is among the names the compiler must avoid by accident.
#[test]
fn a_persist_load_names_its_inputs_and_hides_its_one_shot() {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/proves_programs/persist_count.ld");
    let (_, program) = load(&path);
    let program = program.expect("loads");
    let scan = ii_prove::ladder::lower::lower(&program).expect("lowers");
    let once = "PERSIST_saved_r1_loaded";
    assert!(scan.hidden.contains(once), "{:?}", scan.hidden);
    assert!(!scan.integers[once].input);
    for input in ["PERSIST_saved_r1", "PERSIST_saved_r1_ready"] {
        assert!(scan.integers[input].input, "{input}");
        assert!(!scan.hidden.contains(input), "{input}");
    }
    for name in [once, "PERSIST_saved_r1", "PERSIST_saved_r1_ready"] {
        assert!(scan.names.contains(name), "{name}");
    }
}
