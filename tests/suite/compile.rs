//! Integration tests of the rung compiler: water.ld's equations, seal-ins, set/reset, bounds, names, `.ii` round trips and data-driven cases (the differential test against the scan simulator is `tests/suite/differential.rs`).
#![warn(missing_docs)]

use crate::common;

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};

use ii_prove::diag::Sources;
use ii_prove::kernel::Rel;
use ii_prove::ladder::{
    CompiledProgram, EdgeKind, ElementKind, HypothesisKind, LdProgram, SignalKind, decode_latin1,
    program_to_ii, read_ldmicro,
};
use ii_prove::syntax::{Lookup, Notation, Relation, Scans, Scope, parse_document, term_to_string};
use ii_prove::term::{Expr, same};

/// Compiles a program the compiler must accept (no control flow).
fn compile(program: &LdProgram) -> CompiledProgram {
    ii_prove::ladder::compile(program).unwrap_or_else(|e| panic!("refused: {e:?}"))
}

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).to_path_buf()
}

fn examples() -> Vec<PathBuf> {
    common::files_with(&root().join("examples"), "ld")
}

fn corpus() -> Vec<PathBuf> {
    common::files_with(&root().join("tests/data/ldmicro/corpus"), "ld")
}

fn parse(name: &str, text: &str) -> Option<LdProgram> {
    let mut s = Sources::new();
    let f = s.add(name, text.to_string());
    read_ldmicro(&s, f).ok()
}

fn load_text(name: &str, text: &str) -> LdProgram {
    parse(name, text).unwrap_or_else(|| panic!("{name} does not parse"))
}

fn load(path: &Path) -> Option<LdProgram> {
    let bytes = fs::read(path).expect("readable");
    parse(&path.display().to_string(), &decode_latin1(&bytes))
}

/// A program from rungs only (0.1 header, 10 ms cycle).
fn rungs(text: &str) -> LdProgram {
    load_text("t.ld", &format!("LDmicro0.1\nCYCLE=10000\nPROGRAM\n{text}"))
}

fn water() -> CompiledProgram {
    compile(&load(&root().join("examples/water.ld")).expect("water.ld parses"))
}

fn p(e: &Expr) -> String {
    term_to_string(e, Notation::Paper)
}

/// `name: lhs rel rhs` in paper notation.
fn stmt(c: &CompiledProgram, name: &str) -> String {
    let h = c.hypothesis(name).unwrap_or_else(|| panic!("no hypothesis {name}"));
    let rel = if h.rel == Rel::Eq { "=" } else { "⇒" };
    format!("{} {rel} {}", p(&h.lhs), p(&h.rhs))
}

fn names(c: &CompiledProgram) -> Vec<String> {
    c.hypotheses.iter().map(|h| h.name.clone()).collect()
}

// ---------------------------------------------------------------- water.ld

#[test]
fn water_equations_follow_the_paper() {
    let c = water();
    let expected = [
        ("L01", "RDemand = (XL_flow + XH_flow) · ¬XSP_fail"),
        ("L02", "RPrio2 = XLine_swap · ¬XL2_fail + XL1_fail"),
        ("L03", "RL1_Prod = RS(¬RPrio2, ¬(RDemand · ¬XL1_fail · ¬pre RL2_Prod))"),
        ("L04", "RL2_Prod = RS(RPrio2, ¬(RDemand · ¬XL2_fail · ¬RL1_Prod))"),
        ("L05", "YL1_up = RL1_Prod"),
        ("L06a", "YL1_pump = 5s/RL1_Prod"),
        ("L06b", "YL1_down = 5s/RL1_Prod"),
        ("L07", "YL2_up = RL2_Prod"),
        ("L08a", "YL2_pump = 5s/RL2_Prod"),
        ("L08b", "YL2_down = 5s/RL2_Prod"),
        ("L09", "YOut_valve = YL1_pump + YL2_pump"),
        ("L10", "YBf_valve = (YL1_pump + YL2_pump) · XL_flow · ¬XH_flow"),
    ];
    for (name, text) in expected {
        assert_eq!(stmt(&c, name), text, "{name}");
        assert_eq!(c.hypothesis(name).map(|h| h.kind), Some(HypothesisKind::Equation));
    }
    assert_eq!(
        names(&c),
        [
            "L01", "L02", "L03", "L03_scan", "L04", "L04_scan", "L05", "L06a", "L06b", "L07",
            "L08a", "L08b", "L09", "L10"
        ]
    );
    assert!(c.warnings.is_empty(), "{:?}", c.warnings);
    // The read of RL2_Prod before its rung is its previous-scan value, exactly.
    assert!(stmt(&c, "L03").contains("pre RL2_Prod"), "{}", stmt(&c, "L03"));
    assert_eq!(
        stmt(&c, "L03_scan"),
        "RL1_Prod = (¬RPrio2 + pre RL1_Prod) · RDemand · ¬XL1_fail · ¬pre RL2_Prod"
    );
    assert_eq!(c.hypothesis("L03_scan").map(|h| h.kind), Some(HypothesisKind::Recurrence));
    assert!(!c.signals.contains_key("pre_RL2_Prod"));
    assert_eq!(c.signals.get("XL_flow"), Some(&SignalKind::Input));
    assert_eq!(c.signals.get("YL1_pump"), Some(&SignalKind::Output));
    assert_eq!(c.signals.get("RL1_Prod"), Some(&SignalKind::Relay));
    // The rung numbers are file rung numbers (comment rungs count).
    assert_eq!(c.hypothesis("L01").map(|h| h.rung), Some(3));
}

#[test]
fn no_bounds_beside_the_exact_equations() {
    // What a bound free of `pre` would say follows from the exact equation; the prover
    // derives it (tests/data/proves_programs/shannon_bounds.ii). [10] L1_Prod ⇒ ¬L2_Prod
    // follows from L04 itself by rs_reset.
    let c = water();
    let kinds = [HypothesisKind::Equation, HypothesisKind::Recurrence];
    assert!(c.hypotheses.iter().all(|h| kinds.contains(&h.kind)));
    assert!(stmt(&c, "L04").contains("¬RL1_Prod"));
}

#[test]
fn water_faulty_drops_the_interlock() {
    let c = compile(&load(&root().join("examples/water_faulty.ld")).expect("parses"));
    assert_eq!(stmt(&c, "L04"), "RL2_Prod = RS(RPrio2, ¬(RDemand · ¬XL2_fail))");
}

#[test]
fn water_axioms_are_ground() {
    let c = water();
    let axioms = c.axioms();
    assert_eq!(axioms.len(), c.hypotheses.len());
    assert!(axioms.iter().all(|a| a.signal_vars.is_empty() && a.delay_vars.is_empty()));
    assert_eq!(axioms[0].name, "L01");
}

#[test]
fn other_examples_compile_to_readable_memories() {
    let ex = |f: &str| compile(&load(&root().join("examples").join(f)).expect("parses"));
    let c = ex("motor.ld");
    assert_eq!(stmt(&c, "L01"), "YMotor = RS(XStart, XStop + XOverload + pre RTripped)");
    assert_eq!(stmt(&c, "L03"), "RTripped = RS(XOverload, XReset · ¬XOverload)", "reset rung last");
    let c = ex("conveyor.ld");
    assert_eq!(stmt(&c, "L01"), "RRun = RS(XStart, XStop + XJam)");
    assert_eq!(stmt(&c, "L02"), "YConv2 = RRun/10s");
    assert_eq!(stmt(&c, "L03"), "YConv1 = 2s/(RRun · YConv2)");
    let c = ex("traffic.ld");
    assert_eq!(stmt(&c, "L01"), "RRed_done = 5s/(XRun · ¬pre RNext)");
}

// ---------------------------------------------------------------- names

#[test]
fn names_resolve_exactly_unprefixed_ambiguously() {
    let c = water();
    assert_eq!(c.lookup("YL1_pump"), Lookup::Signal("YL1_pump".into()));
    assert_eq!(c.lookup("L1_pump"), Lookup::Signal("YL1_pump".into()));
    assert_eq!(c.lookup("L1_Prod"), Lookup::Signal("RL1_Prod".into()));
    assert_eq!(c.lookup("L_flow"), Lookup::Signal("XL_flow".into()));
    // Previous values are `pre` terms, not names.
    assert_eq!(c.lookup("pre_L2_Prod"), Lookup::Unknown);
    assert_eq!(c.lookup("nothing"), Lookup::Unknown);
    // Output spells a name as the user does: short once looked up short, else exact.
    assert_eq!(c.display_name("YL1_pump"), "L1_pump");
    let names = c.names();
    assert!(names.contains(&"L1_pump".to_string()) && names.contains(&"YL1_pump".to_string()));
    let h = c.hypothesis("L03").expect("L03");
    assert_eq!(
        p(&c.rename_for_display(&h.rhs)),
        "RS(¬RPrio2, ¬(RDemand · ¬XL1_fail · ¬pre RL2_Prod))",
        "none of these was written short"
    );
    assert_eq!(c.lookup("L2_Prod"), Lookup::Signal("RL2_Prod".into()));
    assert_eq!(
        p(&c.rename_for_display(&h.rhs)),
        "RS(¬RPrio2, ¬(RDemand · ¬XL1_fail · ¬pre L2_Prod))",
        "L2_Prod now is"
    );
    let fresh = water();
    assert_eq!(fresh.display_name("YL1_pump"), "YL1_pump", "nothing written yet");

    let amb = compile(&rungs(
        "RUNG\nCONTACTS Xa 0\nCOIL Ya 0 0 0\nEND\nRUNG\nCONTACTS Ya 0\nCOIL Ra 0 0 0\nEND\n",
    ));
    match amb.lookup("a") {
        Lookup::Ambiguous(mut c) => {
            c.sort();
            assert_eq!(c, ["Ra", "Xa", "Ya"]);
        }
        other => panic!("{other:?}"),
    }
    assert_eq!(amb.display_name("Ya"), "Ya");
    assert_eq!(amb.lookup("Ya"), Lookup::Signal("Ya".into()));
    assert!(!amb.names().contains(&"a".to_string()));
}

#[test]
fn odd_names_are_quoted_and_round_trip() {
    let c = compile(&rungs("RUNG\nCONTACTS Xpi@90 0\nCOIL Yinput 0 0 0\nEND\n"));
    let text = program_to_ii(&c, Notation::Ascii);
    assert!(text.contains("`Xpi@90`"), "{text}");
    round_trip("odd", &c);
}

// ---------------------------------------------------------------- rung forms

#[test]
fn seal_in_up_to_boolean_equivalence() {
    // Q := S·¬R + Q·¬R is RS(S, R).
    let c = compile(&rungs(
        "RUNG\nPARALLEL\nSERIES\nCONTACTS XS 0\nCONTACTS XR 1\nEND\nSERIES\nCONTACTS YQ 0\nCONTACTS XR 1\nEND\nEND\nCOIL YQ 0 0 0\nEND\n",
    ));
    assert_eq!(stmt(&c, "L01"), "YQ = RS(XS, XR)");
    // Q := S + Q·¬R is SR(S, R).
    let c = compile(&rungs(
        "RUNG\nPARALLEL\nCONTACTS XS 0\nSERIES\nCONTACTS YQ 0\nCONTACTS XR 1\nEND\nEND\nCOIL YQ 0 0 0\nEND\n",
    ));
    assert_eq!(stmt(&c, "L01"), "YQ = SR(XS, XR)");
    // Q := (S + Q)·¬R is RS(S, R), with no `pre` left; its scan
    // recurrence comes with it.
    let c = compile(&rungs(
        "RUNG\nPARALLEL\nCONTACTS XS 0\nCONTACTS YQ 0\nEND\nCONTACTS XR 1\nCOIL YQ 0 0 0\nEND\n",
    ));
    assert_eq!(stmt(&c, "L01"), "YQ = RS(XS, XR)");
    assert_eq!(stmt(&c, "L01_scan"), "YQ = (XS + pre YQ) · ¬XR");
    assert_eq!(names(&c), ["L01", "L01_scan"]);
    // A pure latch Q := S + Q is SR(S, 0*).
    let c =
        compile(&rungs("RUNG\nPARALLEL\nCONTACTS XS 0\nCONTACTS YQ 0\nEND\nCOIL YQ 0 0 0\nEND\n"));
    assert_eq!(stmt(&c, "L01"), "YQ = SR(XS, 0*)");
}

#[test]
fn non_monotone_self_read_is_pre() {
    // Q := ¬Q · a (a toggle-ish form): not a memory; exact over pre YQ.
    let c = compile(&rungs("RUNG\nCONTACTS YQ 1\nCONTACTS Xa 0\nCOIL YQ 0 0 0\nEND\n"));
    assert_eq!(stmt(&c, "L01"), "YQ = ¬pre YQ · Xa");
    assert_eq!(names(&c), ["L01"]);
}

#[test]
fn later_rung_read_is_previous_value() {
    let c = compile(&rungs(
        "RUNG\nCONTACTS Xa 0\nCONTACTS Rlater 0\nCOIL Rearly 0 0 0\nEND\nRUNG\nCONTACTS Xb 0\nCOIL Rlater 0 0 0\nEND\nRUNG\nCONTACTS Rlater 1\nCOIL Rsame 0 0 0\nEND\n",
    ));
    assert_eq!(stmt(&c, "L01"), "Rearly = Xa · pre Rlater");
    assert_eq!(stmt(&c, "L02"), "Rlater = Xb");
    assert_eq!(stmt(&c, "L03"), "Rsame = ¬Rlater");
}

#[test]
fn set_and_reset_coils_in_both_orders() {
    let c = compile(&rungs(
        "RUNG\nCONTACTS XS 0\nCOIL YQ 0 1 0\nEND\nRUNG\nCONTACTS XR 0\nCOIL YQ 0 0 1\nEND\n",
    ));
    assert_eq!(names(&c), ["L02", "L02_scan"], "the memory is stated at its last rung");
    assert_eq!(stmt(&c, "L02"), "YQ = RS(XS, XR)");
    let c = compile(&rungs(
        "RUNG\nCONTACTS XR 0\nCOIL YQ 0 0 1\nEND\nRUNG\nCONTACTS XS 0\nCOIL YQ 0 1 0\nEND\n",
    ));
    assert_eq!(stmt(&c, "L02"), "YQ = SR(XS, XR)");
    // Two set coils sum; a read between the set and the reset rung is exact over pre YQ.
    let c = compile(&rungs(
        "RUNG\nCONTACTS XS1 0\nCOIL YQ 0 1 0\nEND\nRUNG\nCONTACTS YQ 0\nCOIL Ymid 0 0 0\nEND\nRUNG\nCONTACTS XS2 0\nCOIL YQ 0 1 0\nEND\nRUNG\nCONTACTS XR 0\nCOIL YQ 0 0 1\nEND\n",
    ));
    assert_eq!(stmt(&c, "L02"), "Ymid = XS1 + pre YQ");
    assert_eq!(stmt(&c, "L04"), "YQ = RS(XS1 + XS2, XR)");
}

#[test]
fn several_plain_coils_last_one_wins() {
    let c = compile(&rungs(
        "RUNG\nCONTACTS Xa 0\nCOIL Rx 0 0 0\nEND\nRUNG\nCONTACTS Rx 0\nCOIL Ry 0 0 0\nEND\nRUNG\nCONTACTS Xb 0\nCOIL Rx 0 0 0\nEND\n",
    ));
    assert_eq!(stmt(&c, "L02"), "Ry = Xa", "an intermediate read is the earlier assignment");
    assert_eq!(stmt(&c, "L03"), "Rx = Xb");
    assert!(c.hypothesis("L01").is_none());
}

#[test]
fn negated_coils_short_open_and_mid_series_coils() {
    let c = compile(&rungs(
        "RUNG\nCONTACTS Xa 0\nCOIL Yn 1 0 0\nEND\nRUNG\nSHORT\nCOIL Yone 0 0 0\nEND\nRUNG\nCONTACTS Xa 0\nOPEN\nCOIL Yzero 0 0 0\nEND\nRUNG\nCONTACTS Xa 0\nPARALLEL\nCOIL Ymid 0 0 0\nSERIES\nCONTACTS Xb 0\nCOIL Yend 0 0 0\nEND\nEND\nEND\n",
    ));
    assert_eq!(stmt(&c, "L01"), "Yn = ¬Xa");
    assert_eq!(stmt(&c, "L02"), "Yone = 1*");
    assert_eq!(stmt(&c, "L03"), "Yzero = 0*");
    assert_eq!(stmt(&c, "L04a"), "Ymid = Xa");
    assert_eq!(stmt(&c, "L04b"), "Yend = Xa · Xb");
}

#[test]
fn timer_chains() {
    let c = compile(&rungs(
        "RUNG\nCONTACTS Xa 0\nTON T1 1500000\nTOF T2 250000\nCOIL Yq 0 0 0\nEND\nRUNG\nCONTACTS Xb 0\nTOF T3 2000000\nCONTACTS Xc 1\nCOIL Yr 0 0 0\nEND\n",
    ));
    // An LDmicro0.1 timer counts floor(delay / cycle) - 1 scans of 10 ms (§6.3).
    assert_eq!(stmt(&c, "L01"), "Yq = (1.49s/Xa)/240ms");
    assert_eq!(stmt(&c, "L02"), "Yr = Xb/1.99s · ¬Xc");
    assert_eq!(c.warnings.len(), 3, "{:?}", c.warnings);
    assert!(c.warnings.iter().all(|w| w.message.contains("the default adjust")));
    let c = compile(&load_text(
        "t.ld",
        "LDmicro0.2\nCYCLE=10000\nPROGRAM\nRUNG\nCONTACTS Xa 0\nTON T1 1500000\nTOF T2 250000\nCOIL Yq 0 0 0\nEND\n",
    ));
    assert_eq!(stmt(&c, "L01"), "Yq = (1.5s/Xa)/250ms");
    assert!(c.warnings.is_empty());
}

#[test]
fn master_relay_zones_are_exact() {
    let c = compile(&rungs(
        "RUNG\nCONTACTS Xen 0\nMASTER_RELAY\nEND\nRUNG\nCONTACTS Xa 0\nCOIL Yin 0 0 0\nEND\nRUNG\nMASTER_RELAY\nEND\nRUNG\nCONTACTS Xa 0\nCOIL Yout 0 0 0\nEND\n",
    ));
    assert_eq!(stmt(&c, "L02"), "Yin = Xen · Xa");
    assert_eq!(stmt(&c, "L04"), "Yout = Xa");
}

#[test]
fn unsupported_elements_are_fresh_and_reported() {
    let c = compile(&rungs(
        "RUNG\nCONTACTS Xa 0\nOSR\nCOIL Yp 0 0 0\nEND\nRUNG\nCONTACTS Xa 0\nCTU Cpieces 5\nCOIL Yfull 0 0 0\nEND\nRUNG\nGRT Cpieces 3\nCOIL Ymany 0 0 0\nEND\nRUNG\nCONTACTS Xa 0\nOSC\nCOIL Yr 0 0 0\nEND\nRUNG\nCONTACTS Xa 0\nCOIL Yt 0 0 0 1\nEND\nRUNG\nCONTACTS Yt 0\nCOIL Yu 0 0 0\nEND\n",
    ));
    // A one-shot is an edge: its input now and not at the previous scan.
    assert_eq!(stmt(&c, "L01"), "Yp = Xa · ¬pre Xa");
    // A counter and a comparison are exact: Boolean functions of the count's bits.
    assert!(c.integers.contains_key("Cpieces"));
    let of = |x: &str| {
        let h = c.hypotheses.iter().find(|h| p(&h.lhs) == x).unwrap_or_else(|| panic!("{x}"));
        p(&h.rhs)
    };
    assert!(of("Yfull").contains("Cpieces_"), "{}", of("Yfull"));
    assert!(of("Ymany").contains("Cpieces_b"), "{}", of("Ymany"));
    assert_eq!(stmt(&c, "L04"), "Yr = OSC_r4");
    // A toggle flips its bit on a rising edge of its power.
    let toggle = stmt(&c, "L05");
    assert!(toggle.contains("pre Yt") && toggle.contains("pre Xa"), "{toggle}");
    assert_eq!(stmt(&c, "L06"), "Yu = Yt");
    assert_eq!(c.signals.get("Yt"), Some(&SignalKind::Output));
    assert!(!c.signals.contains_key("OSR_r1"));
    let rungs_warned: Vec<usize> = c.warnings.iter().map(|w| w.rung).collect();
    assert_eq!(rungs_warned, [4]);
    let text = program_to_ii(&c, Notation::Paper);
    assert!(text.contains("// warning: rung 4 (L04): OSC:"), "{text}");
    // With the sources, a warning names its file, line and column.
    let mut s = Sources::new();
    let f = s.add(
        "u.ld",
        "LDmicro0.1\nCYCLE=10000\nPROGRAM\nRUNG\nCONTACTS Xa 0\nODF\nCOIL Yp 0 0 0\nEND\n",
    );
    let program = read_ldmicro(&s, f).expect("parses");
    let c = compile(&program);
    assert_eq!(c.warnings[0].line(&s), 6);
    assert!(
        c.warnings[0].describe(&s).starts_with("u.ld:6:1: rung 1 (L01): ODF:"),
        "{}",
        c.warnings[0].describe(&s)
    );
}

#[test]
fn res_on_a_ton_makes_its_count_an_integer() {
    let c = compile(&rungs(
        "RUNG\nCONTACTS Xa 0\nTON Tt 50000\nCOIL Yq 0 0 0\nEND\nRUNG\nCONTACTS Xr 0\nRES Tt\nEND\n",
    ));
    // The accumulator RES also writes is counted as LDmicro counts it, bit by bit.
    assert!(c.integers.contains_key("Tt"), "{:?}", c.integers.keys());
    let yq = c.hypotheses.iter().find(|h| p(&h.lhs) == "Yq").map(|h| p(&h.rhs)).expect("Yq");
    assert!(yq.contains("Tt_"), "{yq}");
    assert!(!c.signals.contains_key("TON_Tt"));
    assert!(c.warnings.is_empty(), "{:?}", c.warnings);
}

#[test]
fn a_pre_name_that_clashes_gets_a_suffix() {
    let c = compile(&rungs(
        "RUNG\nCONTACTS Xb 0\nCOIL pre_Rx 0 0 0\nEND\nRUNG\nCONTACTS Rx 0\nCONTACTS pre_Rx 0\nCOIL Ry 0 0 0\nEND\nRUNG\nCONTACTS Xa 0\nCOIL Rx 0 0 0\nEND\n",
    ));
    assert_eq!(stmt(&c, "L02"), "Ry = pre Rx · pre_Rx");
    assert_eq!(c.signals.get("pre_Rx"), Some(&SignalKind::Relay));
}

// ---------------------------------------------------------------- .ii round trips

fn round_trip(name: &str, c: &CompiledProgram) {
    for notation in [Notation::Paper, Notation::Ascii] {
        let text = program_to_ii(c, notation);
        let mut s = Sources::new();
        let f = s.add(format!("{name}.ii"), text.clone());
        let doc = parse_document(&s, f, &Scans).unwrap_or_else(|e| panic!("{name}: {e:?}\n{text}"));
        assert_eq!(doc.assumptions.len(), c.hypotheses.len(), "{name}");
        for (a, h) in doc.assumptions.iter().zip(&c.hypotheses) {
            assert_eq!(a.name, h.name, "{name}");
            let rel = if h.rel == Rel::Eq { Relation::Equals } else { Relation::Implies };
            assert_eq!(a.value.relation, rel, "{name} {}", h.name);
            assert!(same(&a.value.lhs, &h.lhs), "{name} {}", h.name);
            assert!(same(&a.value.rhs, &h.rhs), "{name} {}", h.name);
            assert!(a.value.after.is_none());
        }
        let declared: BTreeSet<&str> = doc.inputs.iter().map(|(n, _)| n.as_str()).collect();
        for s in c.signals.keys() {
            assert!(declared.contains(s.as_str()), "{name}: {s} not declared");
        }
    }
}

#[test]
fn examples_and_corpus_round_trip_through_ii() {
    let mut compiled = 0;
    for path in examples().into_iter().chain(corpus()) {
        let Some(program) = load(&path) else { continue };
        let c = compile(&program);
        round_trip(&path.display().to_string(), &c);
        compiled += 1;
    }
    assert!(compiled >= 40, "only {compiled} files compiled");
}

#[test]
fn every_unsupported_element_is_reported_with_its_rung() {
    let mut files = 0;
    for path in corpus().into_iter().chain(examples()) {
        let Some(program) = load(&path) else { continue };
        files += 1;
        let c = compile(&program);
        // The integer elements are exact when every integer they touch is computed.
        let ints = |e: &ii_prove::ladder::ldmicro::Element| -> Vec<String> {
            use ii_prove::ladder::ldmicro::Operand;
            let var = |o: &Operand| o.var().map(str::to_string);
            match &e.kind {
                ElementKind::Counter { name, limit, init, .. } => {
                    [Some(name.clone()), var(limit), var(init)].into_iter().flatten().collect()
                }
                // A timer whose count is an integer of the program (RTO, RTL, a count
                // another element writes or reads) is exact.
                ElementKind::Res { name } | ElementKind::Timer { name, .. } => vec![name.clone()],
                ElementKind::Compare { a, b, .. } => {
                    [var(a), var(b)].into_iter().flatten().collect()
                }
                ElementKind::Move { dest, src } => {
                    [Some(dest.clone()), var(src)].into_iter().flatten().collect()
                }
                // A division by 0 is undefined: DIV is computed only by a nonzero literal.
                ElementKind::Math { op, dest, a, b }
                    if *op != ii_prove::ladder::ldmicro::MathOp::Div
                        || matches!(b, Operand::Literal(v) if *v != 0 && (-32768..=32767).contains(v)) =>
                {
                    [Some(dest.clone()), var(a), var(b)].into_iter().flatten().collect()
                }
                // A bit operation is exact when its operands are (`lower/bits.rs`).
                ElementKind::Other { keyword, args }
                    if [
                        "AND", "OR", "XOR", "NOT", "NEG", "SHL", "SHR", "SR0", "ROL", "ROR", "MOD",
                        "BIN2BCD", "BCD2BIN", "OPPOSITE", "SWAP",
                    ]
                    .contains(&keyword.as_str()) =>
                {
                    args.iter()
                        .filter(|a| a.starts_with(|c: char| c.is_alphabetic() || c == '_'))
                        .cloned()
                        .collect()
                }
                ElementKind::Other { keyword, args }
                    if keyword == "SHIFT_REGISTER" && args.len() == 2 =>
                {
                    let stages: u32 = args[1].parse().unwrap_or(0);
                    (0..stages).map(|k| format!("{}{k}", args[0])).collect()
                }
                _ => Vec::new(),
            }
        };
        for rung in &program.rungs {
            if rung.is_comment(&program.version) {
                continue;
            }
            for e in rung.elements() {
                let computed = ints(e);
                let exact = e.kind.is_boolean_core()
                    || matches!(
                        e.kind,
                        ElementKind::MasterRelay
                            | ElementKind::Comment(_)
                            | ElementKind::Edge {
                                kind: EdgeKind::Osr | EdgeKind::Osf | EdgeKind::Odr
                            }
                    )
                    || (!computed.is_empty()
                        && computed.iter().all(|n| c.integers.contains_key(n.as_str())));
                if !exact {
                    assert!(
                        c.warnings.iter().any(|w| w.rung == rung.number && w.span == e.span),
                        "{}: rung {} element {} not reported",
                        path.display(),
                        rung.number,
                        e.kind.keyword()
                    );
                }
            }
        }
        let names: BTreeSet<&String> = c.hypotheses.iter().map(|h| &h.name).collect();
        assert_eq!(names.len(), c.hypotheses.len(), "{}: duplicate names", path.display());
    }
    assert!(files > 0);
}

// ---------------------------------------------------------------- data-driven cases

#[test]
fn data_driven_cases() {
    let dir = root().join("tests/data/compile");
    let bless = std::env::var_os("BLESS").is_some();
    let mut n = 0;
    for path in common::files_with(&dir, "ld") {
        let program = load(&path).unwrap_or_else(|| panic!("{} parses", path.display()));
        let c = compile(&program);
        let got = program_to_ii(&c, Notation::Paper);
        let expected_path = path.with_extension("expected");
        if bless {
            fs::write(&expected_path, &got).expect("writable");
        }
        let expected = fs::read_to_string(&expected_path)
            .unwrap_or_else(|_| panic!("{} missing (run with BLESS=1)", expected_path.display()));
        assert_eq!(got, expected, "{}", path.display());
        round_trip(&path.display().to_string(), &c);
        n += 1;
    }
    assert!(n >= 5, "only {n} cases");
}

// ---------------------------------------------------------------- property files and random programs

#[test]
fn property_files_resolve_against_the_compiled_program() {
    let c = water();
    let mut s = Sources::new();
    let f = s.add(
        "p.ii",
        "property P1: L1_pump => 5s/L1_up\nproperty P3: SP_fail => !Out_valve . !YBf_valve\n",
    );
    let doc = parse_document(&s, f, &c).unwrap_or_else(|e| panic!("{e:?}"));
    assert_eq!(p(&doc.properties[0].value.lhs), "YL1_pump");
    assert_eq!(p(&doc.properties[0].value.rhs), "5s/YL1_up");
    assert_eq!(p(&doc.properties[1].value.rhs), "¬YOut_valve · ¬YBf_valve");
    let fresh = compile(&rungs("RUNG\nCONTACTS Xa 0\nCTU Cpieces 5\nCOIL Yfull 0 0 0\nEND\n"));
    assert_eq!(fresh.display_name("CTU_Cpieces"), "CTU_Cpieces");
    assert_eq!(fresh.lookup("TU_Cpieces"), Lookup::Unknown);
    assert_eq!(fresh.display_name("Yfull"), "Yfull");
    assert_eq!(fresh.lookup("full"), Lookup::Signal("Yfull".into()));
    assert_eq!(fresh.display_name("Yfull"), "full");
}

mod random_programs {
    use super::*;
    use proptest::prelude::*;

    fn leaf() -> impl Strategy<Value = String> {
        let name =
            prop_oneof![Just("Xa"), Just("Xb"), Just("Xc"), Just("Ra"), Just("Rb"), Just("Ya")];
        let coil = prop_oneof![Just("Ra"), Just("Rb"), Just("Ya"), Just("Yb")];
        prop_oneof![
            4 => (name, any::<bool>()).prop_map(|(n, neg)| format!("CONTACTS {n} {}\n", u8::from(neg))),
            3 => (coil, 0..5u8).prop_map(|(n, k)| {
                let f = |i| u8::from(k == i);
                format!("COIL {n} {} {} {}\n", f(1), f(2), f(3))
            }),
            1 => (0..3u8, 2..6u64, any::<bool>()).prop_map(|(t, d, on)| {
                format!("{} T{t} {}\n", if on { "TON" } else { "TOF" }, d * 10_000)
            }),
            1 => Just("SHORT\n".to_string()),
            1 => Just("OPEN\n".to_string()),
            1 => Just("OSR\n".to_string()),
            1 => Just("MASTER_RELAY\n".to_string()),
            1 => prop_oneof![
                Just("CTU C0 3\n".to_string()),
                Just("GRT C0 1\n".to_string()),
                Just("RES T0\n".to_string()),
                Just("COIL Yb 0 0 0 1\n".to_string()),
                Just("MOVE var 3\n".to_string()),
                Just("PLACEHOLDER\n".to_string()),
                Just("RTO T2 30000\n".to_string()),
                Just("OSF\n".to_string()),
            ],
        ]
    }

    fn series(depth: u32) -> BoxedStrategy<String> {
        let item = if depth == 0 {
            leaf().boxed()
        } else {
            prop_oneof![3 => leaf(), 1 => parallel(depth - 1)].boxed()
        };
        prop::collection::vec(item, 1..4).prop_map(|v| v.concat()).boxed()
    }

    fn parallel(depth: u32) -> BoxedStrategy<String> {
        let branch = prop_oneof![leaf(), series(depth).prop_map(|s| format!("SERIES\n{s}END\n")),];
        prop::collection::vec(branch, 2..4)
            .prop_map(|v| format!("PARALLEL\n{}END\n", v.concat()))
            .boxed()
    }

    fn program() -> impl Strategy<Value = String> {
        (any::<bool>(), prop::collection::vec(series(2), 1..7)).prop_map(|(orig, rs)| {
            let header = if orig { "LDmicro0.1" } else { "LDmicro0.2" };
            let body: String = rs.iter().map(|r| format!("RUNG\n{r}END\n")).collect();
            format!("{header}\nCYCLE=10000\nPROGRAM\n{body}")
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

        /// Random programs: the compiler never panics and its `.ii` text parses back
        /// (`tests/suite/differential.rs` checks the hypotheses against the simulator).
        #[test]
        fn random_programs_compile_and_round_trip(text in program()) {
            let Some(program) = parse("random.ld", &text) else { return Ok(()) };
            let c = compile(&program);
            round_trip("random", &c);
        }
    }
}

#[test]
#[ignore = "prints every compiled example and corpus file; run with --ignored --nocapture"]
fn print_all() {
    for path in examples().into_iter().chain(corpus()) {
        let Some(program) = load(&path) else { continue };
        println!("==== {}\n{}", path.display(), program_to_ii(&compile(&program), Notation::Paper));
    }
}
