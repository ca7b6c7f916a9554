//! The PLCopen XML front end end to end: the corpus loads or is refused with located errors, the reader never panics, the water plant drawn in LD and FBD proves what `water.ld` proves, the command line (`show`, `--pou`, `--cycle`, errors).

use crate::common;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use common::{ii_prove, laws, text, verdicts};
use ii_prove::diag::{Diagnostic, RenderStyle, Sources, render};
use ii_prove::ladder::plcopen::{Selection, lower, read_plcopen, select};
use ii_prove::ladder::program_to_ii;
use ii_prove::report;
use ii_prove::syntax::Notation;
use proptest::prelude::*;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn temp(name: &str, content: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ii-prove-plcopen-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, content).unwrap();
    path
}

// ---------------------------------------------------------------- corpus

/// Loaded / refused counts over `tests/data/plcopen/corpus` (recorded in the README).
const CORPUS_LOADED: usize = 54;
const CORPUS_REFUSED: usize = 30;

#[test]
fn every_corpus_file_loads_or_is_refused_with_located_errors() {
    let files = common::files_with(&root().join("tests/data/plcopen/corpus"), "xml");
    assert_eq!(files.len(), 84, "the corpus has 84 files");
    let (mut loaded, mut refused) = (0, 0);
    let mut reasons: BTreeSet<String> = BTreeSet::new();
    for f in &files {
        let path = f.to_str().unwrap();
        let mut sources = Sources::new();
        match report::load_program(&mut sources, path, &Default::default()) {
            Ok(l) => {
                loaded += 1;
                let shown = program_to_ii(&l.compiled, Notation::Paper);
                assert!(shown.contains("Compiled from a PLCopen program"), "{path}");
            }
            Err(diagnostics) => {
                refused += 1;
                for d in &diagnostics {
                    assert!(d.span().is_some(), "{path}: unlocated: {}", d.message());
                    let shown = render(d, &sources, RenderStyle::default());
                    assert!(shown.contains(".xml:") && shown.contains('^'), "{path}: {shown}");
                }
                reasons.insert(diagnostics[0].message());
            }
        }
    }
    eprintln!("corpus: {loaded} loaded, {refused} refused; reasons: {reasons:#?}");
    assert_eq!((loaded, refused), (CORPUS_LOADED, CORPUS_REFUSED));
}

// ---------------------------------------------------------------- no panic

fn exercise(text: &str) {
    let mut sources = Sources::new();
    let file = sources.add("fuzz.xml", text.to_string());
    let result = read_plcopen(&sources, file)
        .and_then(|p| select(&p, &Selection::default()))
        .and_then(|p| lower(&p));
    match result {
        Ok(l) => {
            let _ = ii_prove::program::compile(&l.program, &Default::default());
        }
        Err(errors) => {
            assert!(!errors.is_empty());
            for e in errors {
                let _ = render(&Diagnostic::from(e), &sources, RenderStyle::default());
            }
        }
    }
}

fn water_ld() -> String {
    std::fs::read_to_string(root().join("examples/water_ld.xml")).unwrap()
}

fn water_fbd() -> String {
    std::fs::read_to_string(root().join("examples/water_fbd.xml")).unwrap()
}

#[test]
fn known_troublemakers_do_not_panic() {
    for t in [
        "",
        "<",
        "\u{feff}",
        "<project/>",
        r#"<project xmlns="http://www.plcopen.org/xml/tc6_0201"/>"#,
        r#"<project xmlns="http://www.plcopen.org/xml/tc6_0201"><types><pous><pou name="p" pouType="program"><body><LD><coil localId="1"><connectionPointIn><connection refLocalId="1"/></connectionPointIn><variable>x</variable></coil></LD></body></pou></pous></types></project>"#,
        r#"<project xmlns="http://www.plcopen.org/xml/tc6_0201"><types><pous><pou name="p" pouType="program"><interface><localVars><variable name="x"><type><BOOL/></type></variable></localVars></interface><body><LD><contact localId="1"><connectionPointIn><connection refLocalId="2"/></connectionPointIn><variable>x</variable></contact><contact localId="2"><connectionPointIn><connection refLocalId="1"/></connectionPointIn><variable>x</variable></contact><coil localId="3"><connectionPointIn><connection refLocalId="2"/></connectionPointIn><variable>x</variable></coil></LD></body></pou></pous></types></project>"#,
    ] {
        exercise(t);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn arbitrary_strings_do_not_panic(text in any::<String>()) {
        exercise(&text);
    }

    #[test]
    fn damaged_examples_do_not_panic(cut in 0usize..40_000, at in 0usize..40_000, with in "[ -~]{0,8}", fbd in any::<bool>()) {
        let base = if fbd { water_fbd() } else { water_ld() };
        let mut s = base.clone();
        let at = at % s.len().max(1);
        if s.is_char_boundary(at) {
            s.insert_str(at, &with);
        }
        let cut = cut % s.len().max(1);
        if s.is_char_boundary(cut) {
            exercise(&s[..cut]);
        }
        exercise(&s);
        // Ids, names and modifiers changed in place.
        for (from, to) in [("refLocalId=\"3\"", "refLocalId=\"999\""), ("negated=\"true\"", "edge=\"rising\""), ("L1_Prod<", "L1_Prdo<"), ("typeName=\"TON\"", "typeName=\"TOF\""), ("T#5s", "T#x")] {
            exercise(&base.replacen(from, to, 1 + at % 3));
        }
    }
}

// ---------------------------------------------------------------- the water plant

#[test]
fn the_water_plant_in_ld_and_fbd_proves_what_water_ld_proves() {
    let reference = verdicts(&["examples/water.ld", "examples/water.ii"]);
    assert!(reference.iter().all(|(_, v)| v == "proved"), "{reference:?}");
    for xml in ["examples/water_ld.xml", "examples/water_fbd.xml"] {
        assert_eq!(verdicts(&[xml, "examples/water.ii"]), reference, "{xml}");
        let out = ii_prove(&[xml, "examples/water.ii"]);
        assert_eq!(out.status.code(), Some(0));
        assert!(text(&out.stderr).trim().is_empty(), "{xml}: no warnings: {}", text(&out.stderr));
    }
    // The LD drawing is proved with the same laws as the LDmicro program.
    for p in ["P1a", "P2", "P3", "P4a"] {
        let a = laws(&["examples/water.ld", "examples/water.ii"], p);
        let b = laws(&["examples/water_ld.xml", "examples/water.ii"], p);
        assert_eq!(a, b, "{p}");
    }
}

#[test]
fn the_faulty_drawing_is_refuted_with_a_counterexample_the_plcopen_simulator_confirms() {
    let out = ii_prove(&["examples/water_ld_faulty.xml", "examples/water.ii", "--only", "P2"]);
    assert_eq!(out.status.code(), Some(1));
    let stdout = text(&out.stdout);
    assert!(stdout.contains("refuted"), "{stdout}");
    assert!(stdout.contains("by the scan simulator"), "{stdout}");
}

/// Integers in FBD, exact: a CTU's count and a GT comparison prove the bottle counter's
/// properties; its early warning is refuted with the count drawn, confirmed by the
/// PLCopen simulator.
#[test]
fn the_bottle_counter_in_fbd_is_proved_and_its_early_warning_refuted() {
    let proves = "tests/data/proves_programs/bottle_counter_fbd";
    let (xml, ii) = (format!("{proves}.xml"), format!("{proves}.ii"));
    let got = verdicts(&[&xml, &ii]);
    assert!(got.len() == 4 && got.iter().all(|(_, v)| v == "proved"), "{got:?}");
    let out = ii_prove(&["show", &xml]);
    let all = format!("{}{}", text(&out.stdout), text(&out.stderr));
    assert!(!all.contains("unconstrained"), "{all}");
    assert!(all.contains("Counter_CV_b15"), "the count is compiled into bits: {all}");
    let refutes = "tests/data/refutes_programs/bottle_counter_warn_early";
    let out = ii_prove(&[&format!("{refutes}.xml"), &format!("{refutes}.ii")]);
    let stdout = text(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    assert!(stdout.contains("by the scan simulator"), "{stdout}");
    let row = stdout.lines().find(|l| l.trim_start().starts_with("Counter_CV"));
    assert!(
        row.is_some_and(|r| r.contains(" 3") && r.contains(" 4")),
        "the count is drawn: {stdout}"
    );
}

// ---------------------------------------------------------------- command line

#[test]
fn show_prints_the_equations_of_a_plcopen_program() {
    let out = ii_prove(&["show", "examples/water_ld.xml"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    assert!(stdout.contains("assume L06: T1_Q = 5s/L1_Prod"), "{stdout}");
    assert!(
        stdout.contains("input H_flow, L1_fail, L2_fail, L_flow, Line_swap, SP_fail"),
        "{stdout}"
    );
}

#[test]
fn a_plcopen_file_is_recognised_by_content_whatever_its_name() {
    let renamed = temp("plant.txt", &water_ld());
    let out = ii_prove(&["examples/water.ii", renamed.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0), "{}{}", text(&out.stdout), text(&out.stderr));
}

#[test]
fn cycle_changes_the_timer_count_and_pou_chooses_the_program() {
    let out = ii_prove(&["show", "--cycle", "3ms", "examples/water_ld.xml"]);
    let stdout = text(&out.stdout);
    assert!(stdout.contains("P = 1667 scans"), "{stdout}");
    assert!(stdout.contains("T1_Q = 5.001s/L1_Prod"), "{stdout}");
    let two = water_ld().replace(
        "</pous>",
        r#"<pou name="other" pouType="program"><body><LD/></body></pou></pous>"#,
    );
    let two = temp(
        "two.xml",
        &two.replace(
            r#"<pouInstance name="instance0" typeName="water"/>"#,
            r#"<pouInstance name="a" typeName="water"/><pouInstance name="b" typeName="other"/>"#,
        ),
    );
    let out = ii_prove(&["show", two.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = text(&out.stderr);
    assert!(stderr.contains("--pou") && stderr.contains("water, other"), "{stderr}");
    let out = ii_prove(&["show", "--pou", "water", two.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let out = ii_prove(&["show", "--pou", "wtaer", two.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("did you mean `water`?"), "{}", text(&out.stderr));
}

#[test]
fn errors_name_line_and_column_and_exit_2() {
    let bad = temp(
        "bad.xml",
        &water_ld().replacen("<variable>L1_Prod</variable>", "<variable>L1_Prdo</variable>", 1),
    );
    let out = ii_prove(&[bad.to_str().unwrap(), "examples/water.ii"]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = text(&out.stderr);
    assert!(stderr.contains("unknown variable `L1_Prdo`"), "{stderr}");
    assert!(stderr.contains("bad.xml:") && stderr.contains('^'), "{stderr}");
    assert!(stderr.contains("did you mean `L1_Prod`?"), "{stderr}");
    let broken = temp("broken.xml", &water_ld()[..2000]);
    let out = ii_prove(&["show", broken.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("malformed XML"), "{}", text(&out.stderr));
    let stray = temp(
        "stray.xml",
        &water_ld().replacen(
            "<rightPowerRail",
            "<jump localId=\"900\" label=\"x\"/><rightPowerRail",
            1,
        ),
    );
    let out = ii_prove(&["show", stray.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("`jump` is not supported"), "{}", text(&out.stderr));
}

#[test]
fn the_cycle_default_is_documented_in_a_warning() {
    let untasked = water_ld().replace(r#" interval="T#10ms""#, "");
    let path = temp("untasked.xml", &untasked);
    let out = ii_prove(&[path.to_str().unwrap(), "examples/water.ii"]);
    assert_eq!(out.status.code(), Some(0));
    assert!(text(&out.stderr).contains("20 ms"), "{}", text(&out.stderr));
    let _ = Path::new("unused");
}

#[test]
fn user_function_blocks_are_inlined_per_instance() {
    // A seal-in drawn once as a function block, used for two motors.
    let fb = r#"<pou name="SealIn" pouType="functionBlock"><interface>
<inputVars><variable name="Start"><type><BOOL/></type></variable><variable name="Stop"><type><BOOL/></type></variable></inputVars>
<outputVars><variable name="Run"><type><BOOL/></type></variable></outputVars></interface>
<body><LD>
<leftPowerRail localId="1"><position x="0" y="0"/><connectionPointOut/></leftPowerRail>
<contact localId="2"><position x="10" y="0"/><connectionPointIn><connection refLocalId="1"/></connectionPointIn><connectionPointOut/><variable>Start</variable></contact>
<contact localId="3"><position x="10" y="20"/><connectionPointIn><connection refLocalId="1"/></connectionPointIn><connectionPointOut/><variable>Run</variable></contact>
<contact localId="4" negated="true"><position x="20" y="0"/><connectionPointIn><connection refLocalId="2"/><connection refLocalId="3"/></connectionPointIn><connectionPointOut/><variable>Stop</variable></contact>
<coil localId="5"><position x="30" y="0"/><connectionPointIn><connection refLocalId="4"/></connectionPointIn><connectionPointOut/><variable>Run</variable></coil>
</LD></body></pou>"#;
    let block = |id: u64, inst: &str, start: u64, stop: u64, y: i64| {
        format!(
            r#"<block localId="{id}" typeName="SealIn" instanceName="{inst}"><position x="100" y="{y}"/><inputVariables><variable formalParameter="Start"><connectionPointIn><connection refLocalId="{start}"/></connectionPointIn></variable><variable formalParameter="Stop"><connectionPointIn><connection refLocalId="{stop}"/></connectionPointIn></variable></inputVariables><inOutVariables/><outputVariables><variable formalParameter="Run"><connectionPointOut/></variable></outputVariables></block>"#
        )
    };
    let program = format!(
        r#"<?xml version="1.0"?>
<project xmlns="http://www.plcopen.org/xml/tc6_0201"><types><pous>
<pou name="main" pouType="program"><interface>
<inputVars><variable name="Go"><type><BOOL/></type></variable><variable name="Halt"><type><BOOL/></type></variable></inputVars>
<localVars><variable name="M1"><type><derived name="SealIn"/></type></variable><variable name="M2"><type><derived name="SealIn"/></type></variable>
<variable name="Both"><type><BOOL/></type></variable></localVars></interface>
<body><FBD>
<inVariable localId="1"><position x="0" y="0"/><connectionPointOut/><expression>Go</expression></inVariable>
<inVariable localId="2"><position x="0" y="10"/><connectionPointOut/><expression>Halt</expression></inVariable>
{}
{}
<block localId="20" typeName="AND"><position x="200" y="0"/><inputVariables><variable formalParameter="IN1"><connectionPointIn><connection refLocalId="10" formalParameter="Run"/></connectionPointIn></variable><variable formalParameter="IN2"><connectionPointIn><connection refLocalId="11" formalParameter="Run"/></connectionPointIn></variable></inputVariables><inOutVariables/><outputVariables><variable formalParameter="OUT"><connectionPointOut/></variable></outputVariables></block>
<outVariable localId="21"><position x="300" y="0"/><connectionPointIn><connection refLocalId="20" formalParameter="OUT"/></connectionPointIn><expression>Both</expression></outVariable>
</FBD></body></pou>
{fb}
</pous></types>
<instances><configurations><configuration name="C"><resource name="R"><task name="t" priority="0" interval="T#10ms"><pouInstance name="i" typeName="main"/></task></resource></configuration></configurations></instances></project>"#,
        block(10, "M1", 1, 2, 0),
        block(11, "M2", 1, 2, 50)
    );
    let path = temp("inline.xml", &program);
    let out = ii_prove(&["show", path.to_str().unwrap()]);
    let shown = text(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(shown.contains("M1_Run = RS(M1_Start, M1_Stop)"), "{shown}");
    assert!(shown.contains("M2_Run = RS(M2_Start, M2_Stop)"), "{shown}");
    let props =
        temp("inline.ii", "property halted: Halt => !Both\nproperty same: M1_Run = M2_Run\n");
    let out = ii_prove(&[path.to_str().unwrap(), props.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0), "{}{}", text(&out.stdout), text(&out.stderr));
}

/// `In → TYPE(PT) → Out` at a 10 ms cycle.
fn timer_program(ty: &str, pt: &str) -> String {
    format!(
        r#"<?xml version="1.0"?>
<project xmlns="http://www.plcopen.org/xml/tc6_0201"><types><pous>
<pou name="main" pouType="program"><interface>
<inputVars><variable name="In"><type><BOOL/></type></variable></inputVars>
<localVars><variable name="T"><type><derived name="{ty}"/></type></variable><variable name="Out"><type><BOOL/></type></variable></localVars></interface>
<body><LD>
<leftPowerRail localId="1"><position x="0" y="0"/><connectionPointOut/></leftPowerRail>
<contact localId="2"><position x="10" y="0"/><connectionPointIn><connection refLocalId="1"/></connectionPointIn><connectionPointOut/><variable>In</variable></contact>
<inVariable localId="3"><position x="10" y="20"/><connectionPointOut/><expression>{pt}</expression></inVariable>
<block localId="4" typeName="{ty}" instanceName="T"><position x="20" y="0"/><inputVariables><variable formalParameter="IN"><connectionPointIn><connection refLocalId="2"/></connectionPointIn></variable><variable formalParameter="PT"><connectionPointIn><connection refLocalId="3"/></connectionPointIn></variable></inputVariables><inOutVariables/><outputVariables><variable formalParameter="Q"><connectionPointOut/></variable><variable formalParameter="ET"><connectionPointOut/></variable></outputVariables></block>
<coil localId="5"><position x="30" y="0"/><connectionPointIn><connection refLocalId="4" formalParameter="Q"/></connectionPointIn><connectionPointOut/><variable>Out</variable></coil>
</LD></body></pou></pous></types>
<instances><configurations><configuration name="C"><resource name="R"><task name="t" priority="0" interval="T#10ms"><pouInstance name="i" typeName="main"/></task></resource></configuration></configurations></instances></project>"#
    )
}

/// `Out` at each scan of the PLCopen simulator for these values of `In`.
fn run_timer(ty: &str, pt: &str, ins: &[u8]) -> String {
    let mut sources = Sources::new();
    let file = sources.add("t.xml", timer_program(ty, pt));
    let p = read_plcopen(&sources, file).and_then(|p| select(&p, &Selection::default())).unwrap();
    let mut sim = ii_prove::ladder::plcopen::PlcSimulator::new(&p);
    ins.iter()
        .map(|i| {
            sim.step(&[("In".to_string(), *i == 1)].into_iter().collect());
            if sim.bit("Out") { '1' } else { '0' }
        })
        .collect()
}

#[test]
fn the_simulator_times_ton_and_tof_as_matiec_on_a_10ms_tick() {
    // TON: on at the first scan whose time is ≥ start + PT, never at the starting scan.
    assert_eq!(run_timer("TON", "T#0ms", &[1, 1, 1, 0, 1, 1]), "011001");
    assert_eq!(run_timer("TON", "T#15ms", &[1, 1, 1, 1, 0]), "00110");
    assert_eq!(run_timer("TON", "T#20ms", &[1, 1, 1, 1, 0]), "00110");
    assert_eq!(run_timer("TON", "T#21ms", &[1, 1, 1, 1, 0]), "00010");
    // TOF: on with its input, and for P = max(1, ceil(PT / cycle)) scans after it falls.
    assert_eq!(run_timer("TOF", "T#15ms", &[0, 1, 0, 0, 0, 0]), "011100");
    assert_eq!(run_timer("TOF", "T#0ms", &[1, 0, 0]), "110");
    // The compiled equation says the same: P scans, d = P · cycle.
    let out =
        ii_prove(&["show", temp("ton15.xml", &timer_program("TON", "T#15ms")).to_str().unwrap()]);
    assert!(text(&out.stdout).contains("T_Q = 20ms/In"), "{}", text(&out.stdout));
}

/// Start-up state: a written BOOL declared TRUE starts TRUE; a retained one starts with
/// any value (warm restart), or its declared value with `--cold-start`. The same seal-in
/// (`Lamp := (Start + Lamp) · ¬Stop`) gets the verdicts the PLC gives in each case, every
/// refutation confirmed by the PLCopen simulator from the same start.
#[test]
fn start_values_decide_the_verdicts() {
    let dir = "tests/data/plcopen/start_state";
    let file = |f: &str| format!("{dir}/{f}");
    let (needs_start, until_stop) = (file("lamp_needs_start.ii"), file("lamp_until_stop.ii"));
    for (xml, cold, needs, until) in [
        ("plain.xml", false, "proved", "refuted"),
        ("starts_on.xml", false, "refuted", "proved"),
        ("retained.xml", false, "refuted", "refuted"),
        ("retained.xml", true, "proved", "refuted"),
    ] {
        let program = file(xml);
        let mut args = vec![program.as_str(), needs_start.as_str(), until_stop.as_str()];
        if cold {
            args.push("--cold-start");
        }
        let got = verdicts(&args);
        let want = [("lamp_needs_start", needs), ("lamp_until_stop", until)];
        let want: Vec<(String, String)> =
            want.iter().map(|(n, v)| (n.to_string(), v.to_string())).collect();
        assert_eq!(got, want, "{xml} (cold start: {cold})");
    }
    // The warm start is said, at the variable, and the counterexample chooses it.
    let out = ii_prove(&[&file("retained.xml"), &needs_start]);
    let (stdout, stderr) = (text(&out.stdout), text(&out.stderr));
    assert!(
        stderr.contains("`Lamp` is retained") && stderr.contains("retained.xml:13:"),
        "{stderr}"
    );
    assert!(stdout.contains("Lamp_START"), "{stdout}");
    assert!(stdout.contains("confirmed by exact evaluation and by the scan simulator"), "{stdout}");
}

/// Every `refused/NAME.xml` fails to load with exit status 2 and nothing on standard
/// output, and the error contains every line of `NAME.expected` (message, location).
#[test]
fn programs_whose_meaning_depends_on_the_tool_are_refused_with_a_located_error() {
    let files = common::files_with(&root().join("tests/data/plcopen/refused"), "xml");
    assert!(files.len() >= 7, "only {} cases", files.len());
    for path in files {
        let expected = std::fs::read_to_string(path.with_extension("expected"))
            .unwrap_or_else(|_| panic!("{} has no .expected file", path.display()));
        let out = ii_prove(&["show", path.to_str().unwrap()]);
        let stderr = text(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{}: {stderr}", path.display());
        assert!(out.stdout.is_empty(), "{}", path.display());
        assert!(stderr.contains('^'), "{stderr}");
        for fragment in expected.lines().filter(|l| !l.trim().is_empty()) {
            assert!(stderr.contains(fragment), "expected `{fragment}` in\n{stderr}");
        }
    }
}

/// Where positions and document order give different programs, `--order` chooses the
/// editor: by position `Z` is written before `Y` reads it, in document order after.
#[test]
fn order_chooses_the_editor() {
    let xml = "tests/data/plcopen/refused/order_depends_on_editor.xml";
    let props = temp("order.ii", "property Same_scan: Y = In\n");
    let props = props.to_str().unwrap();
    let layout = ii_prove(&["--order", "layout", xml, props]);
    assert_eq!(layout.status.code(), Some(0), "{}", text(&layout.stdout));
    let document = ii_prove(&["--order", "document", xml, props]);
    assert_eq!(document.status.code(), Some(1), "{}", text(&document.stdout));
    assert!(text(&document.stdout).contains("refuted"), "{}", text(&document.stdout));
}

/// Coils 8 units apart in height, and 16 between the first and the last: Beremiz's
/// position comparison says Y's coil before X's (one row, by x), Z's before Y's, and X's
/// before Z's (by height), which is no order. What the editor runs is what CPython's sort
/// makes of it from document order (X, Y, Z): Z, Y, X. Rows formed from the top would give
/// Y, X, Z, and `Z = Y`; the toolchain oracle found that difference.
#[test]
fn a_position_comparison_that_is_no_order_sorts_as_the_editor_does() {
    let xml = "tests/data/plcopen/order/position_is_no_order.xml";
    let props = temp("layout.ii", "property z_lags: Z = pre Y\nproperty z_same: Z = Y\n");
    let out = ii_prove(&["--order", "layout", xml, props.to_str().unwrap()]);
    let stdout = text(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    let verdict = |name: &str| {
        stdout.lines().find(|l| l.starts_with(&format!("{name} "))).map(|l| l.to_string())
    };
    assert!(verdict("z_lags").is_some_and(|l| l.contains("proved")), "{stdout}");
    assert!(verdict("z_same").is_some_and(|l| l.contains("refuted")), "{stdout}");
}

/// An edge contact read on two paths: Beremiz's `PLCGenerator.py` makes one `R_TRIG` per
/// path (`AddTrigger`, called where each statement is generated), so with `A` written
/// between the two coils `B` and `C` differ; the program is refused at the contact, not
/// compiled with one shared detector (which proved `B = C`).
#[test]
fn an_edge_contact_on_two_paths_is_refused_at_the_contact() {
    let out = ii_prove(&["show", "tests/data/plcopen/refused/edge_contact_two_paths.xml"]);
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("an edge contact on more than one path"), "{stderr}");
    assert!(stderr.contains("edge_contact_two_paths.xml:17:9"), "{stderr}");
}

#[test]
fn warnings_name_the_type_of_what_is_not_computed() {
    // Rounded declared REAL but written by REAL_TO_INT; REAL_TO_LINT's output is 64 bits.
    let dial =
        std::fs::read_to_string(root().join("tests/data/proves_programs/dial_bcd_round.xml"))
            .unwrap()
            .replace(
                r#"<variable name="Rounded"><type><INT/></type>"#,
                r#"<variable name="Rounded"><type><REAL/></type>"#,
            )
            .replace(r#"typeName="REAL_TO_USINT""#, r#"typeName="REAL_TO_LINT""#);
    let path = temp("dial_types.xml", &dial);
    let out = ii_prove(&["show", path.to_str().unwrap()]);
    let err = text(&out.stdout) + &text(&out.stderr);
    assert!(
        err.contains("the REAL Rounded is not computed (it is a REAL written with a INT)"),
        "{err}"
    );
    assert!(err.contains("the USINT Level is not computed"), "{err}");
    assert!(err.contains("the block output _TMP_REAL_TO_LINT19_OUT is not computed"), "{err}");
    assert!(!err.contains("the integer"), "{err}");
}

#[test]
fn a_value_from_a_block_not_computed_names_the_block() {
    let dir = root().join("tests/data/plcopen/corpus/beremiz__beremiz");
    let out =
        ii_prove(&["show", dir.join("tests__projects__svghmi_xy__plc.xml").to_str().unwrap()]);
    let all = text(&out.stdout) + &text(&out.stderr);
    assert!(
        all.contains("the REAL trendval0 is not computed (COS is computed by C's math library"),
        "{all}"
    );
}

#[test]
fn a_text_block_read_by_ld_gives_its_real_output_from_a_restarting_timer() {
    // BACnet's `Simulator`, in ST, calls TON0 once, then again under an `IF` with
    // `IN := FALSE` and `PT` left out (a timer that restarts itself), and computes its
    // REAL `OUT` from `TIME_TO_INT(TON0.ET) MOD PeriodSeconds`: the elapsed time follows
    // the block call by call, counted by a clock at the start of the caller's scan, and
    // the LD program's comparisons read `OUT`.
    let dir = root().join("tests/data/plcopen/corpus/beremiz__beremiz");
    let out = ii_prove(&["show", dir.join("tests__projects__BACnet__plc.xml").to_str().unwrap()]);
    let all = text(&out.stdout) + &text(&out.stderr);
    assert!(!all.contains("not computed"), "{all}");
    assert!(!all.contains("unconstrained signal"), "{all}");
    assert!(all.contains("TempSimulation_TON0_AGE"), "{all}");
    // The clock counts before the block's calls read it.
    let at = |what: &str| all.lines().position(|l| l.starts_with("assume") && l.contains(what));
    assert!(at("TempSimulation_TON0_AGE") < at("TempSimulation_TON0_STATE"), "{all}");
}

/// The door alarm of `tests/data/proves_programs/door_alarm_delay_var.xml` with the
/// literal that writes `Delay` replaced by `written`.
fn door_alarm(written: &str) -> String {
    std::fs::read_to_string(root().join("tests/data/proves_programs/door_alarm_delay_var.xml"))
        .unwrap()
        .replace("<expression>T#2s</expression>", &format!("<expression>{written}</expression>"))
}

#[test]
fn a_time_variable_written_with_a_second_literal_keeps_its_timer_unconstrained() {
    let path = temp("door_3s.xml", &door_alarm("T#3s"));
    let out = ii_prove(&["show", path.to_str().unwrap()]);
    let all = text(&out.stdout) + &text(&out.stderr);
    assert!(
        all.contains(
            "a delay given by the variable Delay is not a constant: it holds T#2s and is also \
             written with T#3s by the outVariable with localId 6"
        ),
        "{all}"
    );
    assert!(all.contains("AlarmTimer_Q = TON_AlarmTimer"), "{all}");
    // The PLC's alarm waits 3 s: not proved to wait 2 s (true, but the timer is
    // unconstrained), and refuted to come 2 s after the door opened, the simulator
    // reading Delay's current value.
    let props = root().join("tests/data/proves_programs/door_alarm_delay_var.ii");
    let out = ii_prove(&[path.to_str().unwrap(), props.to_str().unwrap()]);
    let all = text(&out.stdout);
    assert!(all.contains("AlarmAfterDelay  unknown"), "{all}");
    assert!(all.contains("HeldDoorAlarms   refuted"), "{all}");
    assert!(all.contains("by the scan simulator (violated at scan 101)"), "{all}");
    // A non-literal write (another variable's value) is not one value either.
    let path = temp("door_var.xml", &door_alarm("Door"));
    let out = ii_prove(&["show", path.to_str().unwrap()]);
    let all = text(&out.stdout) + &text(&out.stderr);
    assert!(all.contains("it is written with a value that is not a literal by the"), "{all}");
}

#[test]
fn the_simulator_reads_a_time_variable_preset_at_each_call() {
    // The TON reads Delay (T#2s) at the first scan, T#3s from the second on (localId 6
    // runs after it): matiec compares the elapsed time with PT at each call, so the
    // alarm sounds at the first scan 3 s after the door opened, at 20 ms a scan.
    let mut sources = Sources::new();
    let file = sources.add("door.xml", door_alarm("T#3s"));
    let p = read_plcopen(&sources, file).and_then(|p| select(&p, &Selection::default())).unwrap();
    let mut sim = ii_prove::ladder::plcopen::PlcSimulator::new(&p);
    let door = [("Door".to_string(), true)].into_iter().collect();
    let first = (1..=200).find(|_| {
        sim.step(&door);
        sim.bit("Alarm")
    });
    assert_eq!(first, Some(151));
}

/// A block of a library that talks to the outside world (a CSV file read through the
/// runtime's Python thread) is named a peripheral, its Boolean outputs free inputs; a
/// standard block the lowering does not compute is not.
#[test]
fn library_blocks_that_read_the_outside_world_are_peripherals() {
    let out = ii_prove(&[
        "show",
        "tests/data/plcopen/corpus/beremiz__beremiz/exemples__csv_read__plc.xml",
    ]);
    let all = format!("{}{}", text(&out.stdout), text(&out.stderr));
    for block in ["csv_read_by_string", "csv_read_by_int", "csv_reload"] {
        let line = format!("the library block `{block}` is a peripheral");
        assert!(all.contains(&line), "wanted `{line}` in\n{all}");
    }
    assert!(all.contains("CSV_READ_BY_INT: a peripheral: the output ACK of csv_read_by_int0"));
    assert!(!all.contains("the library block `csv_reload` is not modelled"));
}

/// What a peripheral gives is a peripheral read, computed on from there: a socket's
/// integer stored in a variable is a free input of the variable's type, so the
/// comparisons on it are exact (a property about the connection flag is proved, another
/// refuted with the socket's number drawn, the PLCopen simulator confirming it); a
/// Python thread's string converted by `STRING_TO_INT` is a free INT; `STRING_TO_BOOL`
/// of a literal is matiec's value. `show` lists these under peripheral reads and leaves
/// no comparison unconstrained.
#[test]
fn integers_and_strings_from_peripherals_are_peripheral_reads() {
    let corpus = "tests/data/plcopen/corpus";
    let tcp = format!("{corpus}/thiagoralves__editor/examples__TCP_socket__plc.xml");
    let props = temp(
        "tcp.ii",
        "property holds: connected => [socket_id >= 0]\nproperty fails: connected => [socket_id > 0]\n",
    );
    let props = props.display().to_string();
    let pairs = |v: &[(&str, &str)]| -> Vec<(String, String)> {
        v.iter().map(|(a, b)| (a.to_string(), b.to_string())).collect()
    };
    assert_eq!(verdicts(&[&tcp, &props]), pairs(&[("holds", "proved"), ("fails", "refuted")]));
    let out = ii_prove(&[&tcp, &props, "--only", "fails"]);
    let stdout = text(&out.stdout);
    assert!(stdout.contains("confirmed by exact evaluation and by the scan simulator"), "{stdout}");
    assert!(stdout.contains("TCP_Connect0_SOCKET_ID"), "{stdout}");
    let shown = |file: &str| {
        let out = ii_prove(&["show", file]);
        format!("{}{}", text(&out.stdout), text(&out.stderr))
    };
    let all = shown(&tcp);
    assert!(all.contains("a peripheral read: the free input TCP_Connect0_SOCKET_ID, any INT"));
    for cmp in ["LT: the comparison", "GT: the comparison", "EQ: the comparison"] {
        assert!(!all.contains(cmp), "{cmp} in\n{all}");
    }
    // `Received_msg = 'hi'`, where only the socket's MSG writes `Received_msg`.
    assert!(
        all.contains(
            "a peripheral read: EQ compares strings from outside (Received_msg, written only \
             by the output MSG of TCP_Receive0 (TCP_RECEIVE)): its result is any value"
        ),
        "{all}"
    );
    assert!(!all.contains("// fresh outputs of unsupported elements"), "{all}");
    let wx = shown(&format!("{corpus}/beremiz__beremiz/tests__projects__wxGlade__plc.xml"));
    assert!(wx.contains("its OUT is the free input _TMP_STRING_TO_INT30_OUT_READ, any INT"));
    assert!(!wx.contains("INT_TO_BOOL: the conversion"), "{wx}");
    assert!(!wx.contains("// fresh outputs of unsupported elements"), "{wx}");
    assert!(wx.contains(
        "// peripheral reads (free: what the world outside the scan answers)\ninput PYTHON_POLL_r1"
    ));
    let py = format!("{corpus}/beremiz__beremiz/tests__python__plc.xml");
    let props = temp("py.ii", "property from_string: Test_Bool = 1*\n");
    assert_eq!(verdicts(&[&py, &props.display().to_string()]), pairs(&[("from_string", "proved")]));
}

/// `press_count_st_function.xml` with `from` replaced by `to`.
fn press_count(from: &str, to: &str) -> String {
    std::fs::read_to_string(root().join("tests/data/proves_programs/press_count_st_function.xml"))
        .unwrap()
        .replace(from, to)
}

/// A user FUNCTION with an ST body called from FBD is its body run from power-up at
/// each call: Beremiz's `function0` (its return type and input a derived type of BOOL)
/// gives the caller its input, no unconstrained signal. Under a wired EN, where the
/// block is not run, its integer output is not computed rather than a stale value; a
/// function declaring a timer stays opaque with matiec's reason.
#[test]
fn a_text_function_called_from_fbd_starts_afresh_at_each_call() {
    let dir = root().join("tests/data/plcopen/corpus/beremiz__beremiz");
    let out = ii_prove(&["show", dir.join("tests__python__plc.xml").to_str().unwrap()]);
    let all = text(&out.stdout) + &text(&out.stderr);
    assert!(!all.to_ascii_lowercase().contains("function0`"), "{all}");
    assert!(!all.contains("function0_r"), "{all}");
    for line in [
        "_TMP_FUNCTION061_LocalVar0 = pre fefvsd",
        "_TMP_FUNCTION061_function0 = _TMP_FUNCTION061_LocalVar0",
        "fefvsd = _TMP_FUNCTION061_function0",
    ] {
        assert!(all.contains(line), "wanted `{line}` in\n{all}");
    }
    let en = press_count(
        r#"<variable formalParameter="IN">"#,
        r#"<variable formalParameter="EN"><connectionPointIn><connection refLocalId="1"/></connectionPointIn></variable><variable formalParameter="IN">"#,
    );
    let out = ii_prove(&["show", temp("press_en.xml", &en).to_str().unwrap()]);
    let all = text(&out.stdout) + &text(&out.stderr);
    assert!(
        all.contains("the INT N is not computed (_TMP_PRESSED2_Count is not computed: the block of its pin COUNT runs under a wired EN, not followed)"),
        "{all}"
    );
    assert!(!all.contains("assume L02a: N_b0"), "{all}");
    let timer = press_count(
        r#"<variable name="first">"#,
        r#"<variable name="T1"><type><derived name="TON"/></type></variable><variable name="first">"#,
    );
    let out = ii_prove(&["show", temp("press_ton.xml", &timer).to_str().unwrap()]);
    let all = text(&out.stdout) + &text(&out.stderr);
    assert!(
        all.contains("the user block `Pressed` is not modelled (it declares the function block instance `T1`: matiec refuses one in a function"),
        "{all}"
    );
}
