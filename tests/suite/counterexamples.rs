//! Counterexamples of ladder programs: water_faulty's P2 refuted and replayed on the scan simulator, `--vcd`/`--wavedrom` files read back, the faulty programs of `tests/data/refutes_programs/`, candidates the simulator rejects (`tests/data/unknown_programs/`), and vacuity.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use ii_prove::counterexample::{self, Limits, Verdict};
use ii_prove::diag::Sources;
use ii_prove::report::{self, Options, Status, load_program};
use ii_prove::semantics::Time;
use ii_prove::syntax;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn path(rel: &str) -> String {
    root().join(rel).display().to_string()
}

fn opts() -> Options {
    Options { timeout: Duration::from_secs(5), ..Options::default() }
}

/// The `(program, properties)` pairs of a folder: each `NAME.ld` with its `NAME.ii`.
fn pairs(folder: &str) -> Vec<(String, String)> {
    let dir = root().join("tests/data").join(folder);
    let mut out: Vec<(String, String)> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "ld" || x == "xml" || x == "st"))
        .map(|p| (p.display().to_string(), p.with_extension("ii").display().to_string()))
        .collect();
    out.sort();
    out
}

#[test]
fn water_faulty_p2_is_refuted_with_a_confirmed_diagram() {
    let run = report::run_program(
        &path("examples/water_faulty.ld"),
        &[path("examples/water.ii")],
        &opts(),
    )
    .unwrap_or_else(|e| panic!("{}", e.rendered));
    let p2 = run.properties.iter().find(|p| p.name == "P2").expect("P2");
    assert_eq!(p2.status, Status::Refuted, "{:?}", p2.reason);
    let c = p2.counterexample.as_ref().expect("a counterexample");
    assert_eq!(c.confirmed_by, ["exact evaluation", "scan simulator"]);
    assert!(c.simulator_scan.is_some() && c.scan.is_some());
    let text = report::render_text(&run, &opts());
    assert!(text.contains("P2                         refuted"), "{text}");
    assert!(text.contains("confirmed by exact evaluation and by the scan simulator"), "{text}");
    // The diagram: line 1 runs, Line_swap rises, line 2 starts while line 1 still runs.
    let sig = |name: &str| {
        c.shown.iter().find(|(n, _)| n == name).map(|(_, s)| s.clone()).unwrap_or_else(|| {
            panic!("{name} not shown: {:?}", c.shown.iter().map(|(n, _)| n).collect::<Vec<_>>())
        })
    };
    let t = c.mark.clone().expect("marked");
    let (swap, l1, l2) = (sig("XLine_swap"), sig("L1_up"), sig("L2_up"));
    assert!(swap.value_at(&t) && !swap.left_limit(&t), "Line_swap rises at the violation");
    assert!(l1.value_at(&t) && l1.left_limit(&t), "line 1 was running and still runs");
    assert!(l2.value_at(&t) && !l2.left_limit(&t), "line 2 starts");
    assert!(c.diagram.iter().any(|l| l.starts_with("XLine_swap")));
    assert!(c.diagram.last().is_some_and(|l| l.contains('▲')));
}

#[test]
fn water_faulty_overlap_replays_on_the_scan_simulator() {
    let mut sources = Sources::new();
    let loaded = load_program(&mut sources, &path("examples/water_faulty.ld"), &Default::default())
        .expect("loads");
    let file = sources.add("p2.ii", "let Line1 = L1_up + L1_pump + L1_down\nlet Line2 = L2_up + L2_pump + L2_down\nproperty P2: Line1 . Line2 = 0*\n".to_string());
    let doc = syntax::parse_document(&sources, file, &loaded.compiled).expect("parses");
    let goal = report::obligation(&doc.properties[0].value);
    let session = counterexample::Program {
        reference: loaded.reference.as_ref(),
        compiled: &loaded.compiled,
        assumptions: &[],
        shared: None,
    };
    let limits = Limits {
        deadline: Instant::now() + Duration::from_secs(20),
        max_steps: 200,
        max_scans: 100_000,
        minimised: false,
        signals: true,
    };
    let Verdict::Refuted(c) = counterexample::refute(&session, &goal, limits) else {
        panic!("P2 is not refuted");
    };
    let scan = c.simulator_scan.expect("the simulator confirms");
    assert_eq!(c.trace.cycle, Time::new(1.into(), 100.into()));
    // Replay independently: one step per scan, inputs from the trace.
    let mut sim = loaded.reference.simulator();
    let mut overlap = None;
    for k in 0..c.trace.scans {
        let inputs: BTreeMap<String, bool> =
            c.trace.values.iter().map(|(n, v)| (n.clone(), v[k])).collect();
        sim.step(&inputs);
        if sim.bit("YL1_up") && sim.bit("YL2_up") && overlap.is_none() {
            overlap = Some(k + 1);
        }
    }
    assert_eq!(overlap, Some(scan), "the PLC runs both lines at the reported scan");
    // Line_swap is what changes: off before, on at the overlap.
    let swap = &c.trace.values["XLine_swap"];
    assert!(swap[scan - 1] && swap[..scan - 1].iter().any(|v| !v));
}

/// The exact checks a session remembers (`counterexample::confirm::ExactMemo`) change
/// no confirmation: each property of a faulty plant refuted in a session that has
/// already confirmed it gives the same counterexample as alone.
#[test]
fn remembered_exact_checks_give_the_same_counterexamples() {
    for (program, properties) in [
        ("examples/water_faulty.ld", "examples/water.ii"),
        ("examples/parts_faulty.ld", "examples/parts.ii"),
    ] {
        let mut sources = Sources::new();
        let loaded =
            load_program(&mut sources, &path(program), &Default::default()).expect("loads");
        let text = std::fs::read_to_string(path(properties)).expect("reads");
        let file = sources.add(properties, text);
        let doc = syntax::parse_document(&sources, file, &loaded.compiled).expect("parses");
        let shared = counterexample::shared::Shared::default();
        let run = |shared| {
            let session = counterexample::Program {
                reference: loaded.reference.as_ref(),
                compiled: &loaded.compiled,
                assumptions: &[],
                shared,
            };
            let limits = Limits {
                deadline: Instant::now() + Duration::from_secs(20),
                max_steps: 200,
                max_scans: 100_000,
                minimised: false,
                signals: true,
            };
            let refuted = |p: &syntax::Statement<_>| match counterexample::refute(
                &session,
                &report::obligation(&p.value),
                limits,
            ) {
                Verdict::Refuted(c) => Some((
                    c.trace.values.clone(),
                    (c.scan, c.simulator_scan),
                    (c.lhs, c.rhs),
                    c.assignment.signals.len(),
                )),
                _ => None,
            };
            doc.properties.iter().map(refuted).collect::<Vec<_>>()
        };
        let alone = run(None);
        assert!(alone.iter().any(Option::is_some), "{program} has a refutation");
        let first = run(Some(&shared));
        let again = run(Some(&shared));
        assert_eq!(alone, first, "{program}");
        assert_eq!(alone, again, "{program}");
    }
}

/// Two units whose properties have one form: the run that refutes unit 2's, kept by
/// the session, does not violate unit 1's (it leaves unit 1's input at 0, which unit 2
/// reads, so that no grown run sets it either), and is repaired
/// near unit 1's property into a confirmed counterexample that sets unit 1's input
/// only. A false property of another form, and a true one of the same form, get
/// nothing from the store.
#[test]
fn a_kept_run_is_repaired_for_a_property_of_the_same_form() {
    const UNITS: &str = "LDmicro0.1\nCYCLE=10000\n\nIO LIST\n    Xa1 at 0\n    Xa2 at 0\n    Yb1 at 0\n    Yb2 at 0\n    Yc at 0\nEND\n\nPROGRAM\nRUNG\n    CONTACTS Xa1 0\n    COIL Yb1 0 0 0\nEND\nRUNG\n    CONTACTS Xa2 0\n    CONTACTS Xa1 1\n    COIL Yb2 0 0 0\nEND\nRUNG\n    CONTACTS Xa1 0\n    CONTACTS Xa1 1\n    COIL Yc 0 0 0\nEND\n";
    const PROPERTIES: &str = "property unit2: Yb2 => 0*\nproperty unit1: Yb1 => 0*\nproperty other: Yb1 . Xa1 => 0*\nproperty never: Yc => 0*\n";
    let dir = tempfile::tempdir().expect("a temporary folder");
    let ld = dir.path().join("units.ld");
    std::fs::write(&ld, UNITS).expect("writes");
    let mut sources = Sources::new();
    let loaded =
        load_program(&mut sources, &ld.display().to_string(), &Default::default()).expect("loads");
    let file = sources.add("units.ii", PROPERTIES.to_string());
    let doc = syntax::parse_document(&sources, file, &loaded.compiled).expect("parses");
    let goals: Vec<_> = doc.properties.iter().map(|p| report::obligation(&p.value)).collect();
    let shared = counterexample::shared::Shared::default();
    let session = counterexample::Program {
        reference: loaded.reference.as_ref(),
        compiled: &loaded.compiled,
        assumptions: &[],
        shared: Some(&shared),
    };
    let limits = Limits {
        deadline: Instant::now() + Duration::from_secs(20),
        max_steps: 200,
        max_scans: 100_000,
        minimised: false,
        signals: true,
    };
    let Verdict::Refuted(first) = counterexample::refute(&session, &goals[0], limits) else {
        panic!("unit 2's property is refuted by a search of its own");
    };
    assert_eq!(first.trace.values.get("Xa2").map(|v| v.contains(&true)), Some(true));
    let shared_refutation = |goal| counterexample::shared::refute_shared(&session, goal, limits);
    let repaired = shared_refutation(&goals[1]).expect("unit 1's property: the repaired run");
    assert_eq!(repaired.simulator_scan, Some(repaired.scan), "confirmed by the simulator too");
    assert_eq!(repaired.trace.values.get("Xa1").map(|v| v.contains(&true)), Some(true));
    assert!(!repaired.trace.values.contains_key("Xa2"), "unit 2's input is outside the cone");
    assert!(shared_refutation(&goals[2]).is_none(), "another form is not repaired");
    assert!(shared_refutation(&goals[3]).is_none(), "a true property is never refuted");
}

/// A VCD file read back: timescale, variable names by identifier, value changes (a
/// bit's `0`/`1`, or a vector's value read as an unsigned word).
type Vcd = (String, BTreeMap<String, String>, Vec<(u64, String, u64)>);

/// A tiny VCD reader: variable names by identifier and the value changes in time order.
fn read_vcd(text: &str) -> Vcd {
    let mut timescale = String::new();
    let mut vars = BTreeMap::new();
    let mut changes = Vec::new();
    let mut now = None;
    let mut definitions = true;
    let mut tokens = text.split_whitespace().peekable();
    while let Some(tok) = tokens.next() {
        if definitions {
            match tok {
                "$timescale" => timescale = tokens.next().expect("a timescale").to_string(),
                "$var" => {
                    assert_eq!(tokens.next(), Some("wire"));
                    let width: u32 = tokens.next().unwrap().parse().expect("a width");
                    assert!((1..=64).contains(&width));
                    let id = tokens.next().unwrap().to_string();
                    let name = tokens.next().unwrap().to_string();
                    assert_eq!(tokens.next(), Some("$end"));
                    vars.insert(id, name);
                }
                "$enddefinitions" => {
                    assert_eq!(tokens.next(), Some("$end"));
                    definitions = false;
                }
                _ => {}
            }
            continue;
        }
        if let Some(t) = tok.strip_prefix('#') {
            let t: u64 = t.parse().expect("an integer time");
            assert!(now.is_none_or(|n| n <= t), "times increase");
            now = Some(t);
        } else if let Some(word) = tok.strip_prefix('b') {
            let id = tokens.next().expect("a vector's identifier");
            let v = u64::from_str_radix(word, 2).expect("a binary word");
            assert!(vars.contains_key(id), "unknown identifier {id}");
            changes.push((now.expect("a time before the first change"), vars[id].clone(), v));
        } else {
            let (v, id) = tok.split_at(1);
            let v = match v {
                "0" => 0,
                "1" => 1,
                other => panic!("bad value {other}"),
            };
            assert!(vars.contains_key(id), "unknown identifier {id}");
            changes.push((now.expect("a time before the first change"), vars[id].clone(), v));
        }
    }
    assert!(!definitions, "no $enddefinitions");
    (timescale, vars, changes)
}

/// Runs `ii-prove ARGS --vcd DIR/NAME.vcd --wavedrom DIR/NAME.json` (a run that
/// refutes something) and returns the two files' paths.
fn refute_with_files(dir: &Path, name: &str, args: &[String]) -> (PathBuf, PathBuf) {
    std::fs::create_dir_all(dir).unwrap();
    let (vcd, wave) = (dir.join(format!("{name}.vcd")), dir.join(format!("{name}.json")));
    let out = Command::new(env!("CARGO_BIN_EXE_ii-prove"))
        .args(args)
        .arg("--vcd")
        .arg(&vcd)
        .arg("--wavedrom")
        .arg(&wave)
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(1), "{}", String::from_utf8_lossy(&out.stderr));
    (vcd, wave)
}

#[test]
fn vcd_and_wavedrom_files_read_back() {
    let dir = std::env::temp_dir().join(format!("ii-prove-cex-{}", std::process::id()));
    let args = [
        path("examples/water_faulty.ld"),
        path("examples/water.ii"),
        "--timeout".into(),
        "5".into(),
    ];
    let (vcd, wave) = refute_with_files(&dir, "p2", &args);
    let (timescale, vars, changes) = read_vcd(&std::fs::read_to_string(&vcd).unwrap());
    assert_eq!(timescale, "1ms");
    assert!(vars.values().any(|n| n == "XLine_swap") && vars.values().any(|n| n == "L2_up"));
    // Replay the dump: at the instant Line_swap rises, L1_up and L2_up are both 1.
    let mut state: BTreeMap<String, bool> = BTreeMap::new();
    let mut overlap = false;
    let mut i = 0;
    while i < changes.len() {
        let t = changes[i].0;
        while i < changes.len() && changes[i].0 == t {
            state.insert(changes[i].1.clone(), changes[i].2 == 1);
            i += 1;
        }
        overlap |= state.get("L1_up") == Some(&true) && state.get("L2_up") == Some(&true);
    }
    assert!(overlap, "the dump shows both lines on: {changes:?}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&wave).unwrap()).expect("WaveDrom JSON");
    // WaveDrom's format: `signal` holds one group per property, a group is an array
    // whose first element is its name, then lanes `{name, wave}`; the last lane is the
    // time axis, one `=` per column labelled by `data`.
    let groups = json["signal"].as_array().expect("a signal array");
    assert!(!groups.is_empty());
    for group in groups {
        let group = group.as_array().expect("a group per property");
        let property = group[0].as_str().expect("the group's name");
        let lanes = &group[1..];
        let mut width = None;
        for s in lanes {
            let name = s["name"].as_str().expect("a name");
            let wave = s["wave"].as_str().expect("a wave");
            assert!(!wave.starts_with('.'));
            assert_eq!(*width.get_or_insert(wave.len()), wave.len(), "{property}.{name}: ragged");
        }
        let (time, signals) = lanes.split_last().unwrap();
        assert_eq!(time["name"], "t (s)");
        let labels = time["data"].as_array().expect("time labels");
        assert!(time["wave"].as_str().unwrap().chars().all(|c| c == '='));
        assert_eq!(labels.len(), width.unwrap(), "a label per column");
        assert_eq!(labels[0], "0");
        for s in signals {
            let wave = s["wave"].as_str().unwrap();
            assert!(wave.chars().all(|c| matches!(c, '0' | '1' | '.')), "{wave}");
        }
    }
    let p2 = groups.iter().find(|g| g[0] == "P2").expect("a group for P2");
    let lanes = p2.as_array().unwrap();
    let swap = lanes.iter().find(|s| s["name"] == "XLine_swap").expect("XLine_swap");
    assert!(swap["wave"].as_str().unwrap().contains("01"));
    // Labels fit their columns: 40 px per column per unit of hscale, ~7 px a character.
    let longest = lanes.last().unwrap()["data"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l.as_str().unwrap().len())
        .max()
        .unwrap();
    assert!(json["config"]["hscale"].as_u64().unwrap() as usize * 40 >= longest * 7);
    std::fs::remove_dir_all(&dir).ok();
}

/// The faulty box counter (its capacity one too high): the count is a 16-bit vector in
/// VCD and a data lane in WaveDrom. Replayed scan by scan (100 ms, the program's task),
/// it counts the rising edges of `Part AND Conveyor` (`Conveyor` as the previous scan
/// wrote it, since the program writes it after the call; `Empty` never resets the
/// count in the run) up to 10, where `Stop` fails.
#[test]
fn integers_are_value_tracks_in_vcd_and_wavedrom() {
    let dir = std::env::temp_dir().join(format!("ii-prove-int-{}", std::process::id()));
    let args =
        [path("examples/box_faulty.st"), path("examples/box.ii"), "--only".into(), "Stop".into()];
    let (vcd, wave) = refute_with_files(&dir, "stop", &args);
    let text = std::fs::read_to_string(&vcd).unwrap();
    assert!(text.contains("$var wire 16 "), "{text}");
    let (_, vars, changes) = read_vcd(&text);
    assert!(!vars.values().any(|n| n == "Empty"), "Empty stays 0 in the run");
    let mut state: BTreeMap<String, u64> = BTreeMap::new();
    let (mut rises, mut cu, mut i) = (0, false, 0);
    let end = changes.last().unwrap().0;
    for t in (0..=end).step_by(100) {
        let conveyor = state.get("Conveyor") == Some(&1);
        while i < changes.len() && changes[i].0 <= t {
            assert_eq!(changes[i].0 % 100, 0, "a change between scans");
            state.insert(changes[i].1.clone(), changes[i].2);
            i += 1;
        }
        let now = state.get("Part") == Some(&1) && conveyor;
        rises += u64::from(now && !cu);
        cu = now;
        assert_eq!(state["Count_CV"], rises, "at {t} ms: {changes:?}");
    }
    assert_eq!(rises, 10);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&wave).unwrap()).expect("WaveDrom JSON");
    let lanes = json["signal"][0].as_array().expect("a group");
    let lane = lanes.iter().find(|l| l["name"] == "Count_CV").expect("a lane for the count");
    let wave_text = lane["wave"].as_str().unwrap();
    let data: Vec<String> =
        lane["data"].as_array().unwrap().iter().map(|d| d.as_str().unwrap().into()).collect();
    // A data lane: one `=` per new value, each labelled, and the values 0, 1, … 10.
    assert_eq!(wave_text.matches('=').count(), data.len());
    assert_eq!(data, (0..=10).map(|k: i32| k.to_string()).collect::<Vec<_>>());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn no_file_is_written_on_bad_input() {
    let dir = std::env::temp_dir().join(format!("ii-prove-cex-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.ii");
    std::fs::write(&bad, "property P: Nonsense => 0*\n").unwrap();
    let vcd = dir.join("out.vcd");
    let out = Command::new(env!("CARGO_BIN_EXE_ii-prove"))
        .arg(path("examples/water_faulty.ld"))
        .arg(&bad)
        .arg("--vcd")
        .arg(&vcd)
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(2));
    assert!(!vcd.exists());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn faulty_programs_are_refuted_and_confirmed_twice() {
    let cases = pairs("refutes_programs");
    assert!(cases.len() >= 3, "only {} cases", cases.len());
    for (ld, ii) in cases {
        let run = report::run_program(&ld, std::slice::from_ref(&ii), &opts())
            .unwrap_or_else(|e| panic!("{ld}: {}", e.rendered));
        assert!(!run.properties.is_empty(), "{ii}: no property");
        for p in &run.properties {
            assert_eq!(p.status, Status::Refuted, "{ld}: {} ({:?})", p.name, p.reason);
            let c = p.counterexample.as_ref().expect("a counterexample");
            assert_eq!(c.confirmed_by, ["exact evaluation", "scan simulator"], "{ld}");
            assert!(c.simulator_scan.is_some(), "{ld}");
            assert!(!c.diagram.is_empty());
        }
        let json: serde_json::Value = serde_json::from_str(&report::render_json(&run)).unwrap();
        assert!(json["properties"][0]["counterexample"]["simulator_scan"].is_u64(), "{ld}");
    }
}

#[test]
fn exact_only_candidates_stay_unknown_and_name_the_rung() {
    let cases = pairs("unknown_programs");
    assert!(!cases.is_empty());
    for (ld, ii) in cases {
        let run = report::run_program(&ld, std::slice::from_ref(&ii), &opts())
            .unwrap_or_else(|e| panic!("{ld}: {}", e.rendered));
        for p in &run.properties {
            assert_eq!(p.status, Status::Unknown, "{ld}: {}", p.name);
            assert!(
                p.counterexample.is_none(),
                "{ld}: an unconfirmed counterexample is shown as confirmed"
            );
            let reason = p.reason.as_deref().unwrap_or("");
            assert!(reason.contains("scan simulator does not reproduce"), "{ld}: {reason}");
            assert!(reason.contains("rung 2 (L01) is responsible"), "{ld}: {reason}");
            assert!(p.candidate.is_some(), "{ld}: the candidate is shown");
        }
        let text = report::render_text(&run, &opts());
        assert!(!text.contains("refuted "), "{text}");
        assert!(text.contains("possible counterexample"), "{text}");
    }
}

#[test]
fn an_assumption_that_contradicts_the_program_is_reported() {
    let run = report::run_program(
        &path("tests/data/refutes_programs/traffic_greens_overlap.ld"),
        &[path("tests/data/vacuity/contradicts_program.ii")],
        &opts(),
    )
    .unwrap_or_else(|e| panic!("{}", e.rendered));
    assert!(
        run.warnings
            .iter()
            .any(|w| w.message.contains("always_done") && w.message.contains("contradict")),
        "{:?}",
        run.warnings
    );
    for p in &run.properties {
        assert_ne!(p.status, Status::Refuted);
        assert!(
            p.status != Status::Proved || p.vacuous,
            "{}: proved without the vacuity flag",
            p.name
        );
    }
}

/// A counterexample is a run of the program that satisfies every `assume`, also one about
/// signals the property does not read: it is shown, and an assumption that no run
/// satisfies leaves nothing to refute.
#[test]
fn a_counterexample_satisfies_every_assumption() {
    let ld = path("tests/data/refutes_programs/assumption_outside_cone.ld");
    let ii = path("tests/data/refutes_programs/assumption_outside_cone.ii");
    let run = report::run_program(&ld, std::slice::from_ref(&ii), &opts()).expect("runs");
    assert_eq!(run.properties[0].status, Status::Refuted);
    let json: serde_json::Value = serde_json::from_str(&report::render_json(&run)).unwrap();
    let signals = json["properties"][0]["counterexample"]["signals"].as_array().unwrap();
    let b = signals.iter().find(|s| s["name"] == "B").expect("the assumed signal is shown");
    assert!(b["intervals"].as_array().unwrap().iter().all(|v| v == true), "{b}");
    assert!(b["points"].as_array().unwrap().iter().all(|v| v == true), "{b}");
    let dir = std::env::temp_dir().join(format!("ii-prove-cex-assume-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let vcd = dir.join("out.vcd");
    let out = Command::new(env!("CARGO_BIN_EXE_ii-prove"))
        .args([&ld, &ii, "--vcd"])
        .arg(&vcd)
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(1));
    let text = std::fs::read_to_string(&vcd).expect("written");
    assert!(text.contains(" B $end"), "{text}");
    std::fs::remove_dir_all(&dir).ok();

    let ld = path("tests/data/vacuity/contradicts_outside_the_cone.ld");
    let ii = path("tests/data/vacuity/contradicts_outside_the_cone.ii");
    let run = report::run_program(&ld, std::slice::from_ref(&ii), &opts()).expect("runs");
    assert!(run.warnings.iter().any(|w| w.message.contains("contradict")), "{:?}", run.warnings);
    for p in &run.properties {
        assert_ne!(p.status, Status::Refuted, "{}: a run that violates `H`", p.name);
        assert!(p.counterexample.is_none());
    }
}

#[test]
fn a_property_over_forced_constants_is_flagged_vacuous() {
    let run = report::run_program(
        &path("tests/data/refutes_programs/traffic_greens_overlap.ld"),
        &[path("tests/data/vacuity/forces_constant.ii")],
        &opts(),
    )
    .unwrap_or_else(|e| panic!("{}", e.rendered));
    let p = &run.properties[0];
    assert_eq!(p.status, Status::Proved);
    assert!(p.vacuous);
    assert!(p.vacuity.as_deref().unwrap_or("").contains("Ns_green = 0*"), "{:?}", p.vacuity);
    let json: serde_json::Value = serde_json::from_str(&report::render_json(&run)).unwrap();
    assert_eq!(json["properties"][0]["vacuous"], true);
    assert!(report::render_text(&run, &opts()).contains("warning: vacuous"));
    // The real water plant: nothing is vacuous.
    let water =
        report::run_program(&path("examples/water.ld"), &[path("examples/water.ii")], &opts())
            .unwrap_or_else(|e| panic!("{}", e.rendered));
    for p in &water.properties {
        assert!(!p.vacuous, "{}: {:?}", p.name, p.vacuity);
    }
}

#[test]
fn a_property_that_states_the_forced_constant_is_not_vacuous() {
    let (ld, ii) = (
        path("tests/data/refutes_programs/traffic_greens_overlap.ld"),
        path("tests/data/vacuity/states_the_constant.ii"),
    );
    let run = report::run_program(&ld, std::slice::from_ref(&ii), &opts())
        .unwrap_or_else(|e| panic!("{}", e.rendered));
    assert_eq!(run.properties.len(), 3);
    for p in &run.properties {
        assert_eq!(p.status, Status::Proved, "{}: {:?}", p.name, p.reason);
        assert!(!p.vacuous, "{}: {:?}", p.name, p.vacuity);
    }
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_ii-prove"))
        .args([ld.as_str(), ii.as_str(), "--deny", "vacuous"])
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stdout));
}

#[test]
fn path_helper_points_into_the_repository() {
    assert!(Path::new(&path("examples/water_faulty.ld")).exists());
}

/// An LDmicro program: a chain `Chain1 … ChainN` (`Chain_i = Chain_{i−1} · Go_i`, one
/// rung each, in scan order), then `Armed = ChainN · Arm`, a local interlock
/// `Clash = Armed · ¬Arm` (0 in every run), and `Timed`, the chain's end through a timer.
fn long_chain(n: usize) -> String {
    let mut ld = String::from("LDmicro0.2\nCYCLE=10000\n\nPROGRAM\n");
    for i in 1..=n {
        let from = if i == 1 { "XIn".to_string() } else { format!("RChain{}", i - 1) };
        ld.push_str(&format!(
            "RUNG\n    CONTACTS {from} 0\n    CONTACTS XGo{i} 0\n    COIL RChain{i} 0 0 0\nEND\n"
        ));
    }
    ld.push_str(&format!(
        "RUNG\n    CONTACTS RChain{n} 0\n    CONTACTS XArm 0\n    COIL RArmed 0 0 0\nEND\n"
    ));
    ld.push_str("RUNG\n    CONTACTS RArmed 0\n    CONTACTS XArm 1\n    COIL RClash 0 0 0\nEND\n");
    ld.push_str(&format!(
        "RUNG\n    CONTACTS RChain{n} 0\n    TON TChain 50000\n    COIL RTimed 0 0 0\nEND\n"
    ));
    ld
}

/// Writes `long_chain(n)` and `props` into a fresh directory; the two paths.
fn long_chain_files(name: &str, n: usize, props: &str) -> (String, String) {
    let dir = std::env::temp_dir().join(format!("ii-prove-vacuity-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (ld, ii) = (dir.join("chain.ld"), dir.join("chain.ii"));
    std::fs::write(&ld, long_chain(n)).unwrap();
    std::fs::write(&ii, props).unwrap();
    (ld.display().to_string(), ii.display().to_string())
}

#[test]
fn a_constant_forced_locally_is_found_beyond_the_vacuity_cone() {
    const N: usize = 600;
    let props =
        "property clash_needs_chain: Clash => Chain600\nproperty armed_needs_arm: Armed => Arm\n";
    let (ld, ii) = long_chain_files("forced", N, props);
    // The cone of `Clash` is far larger than the vacuity check's cut.
    let mut sources = Sources::new();
    let loaded = load_program(&mut sources, &ld, &Default::default()).expect("loads");
    let session = counterexample::Program {
        reference: loaded.reference.as_ref(),
        compiled: &loaded.compiled,
        assumptions: &[],
        shared: None,
    };
    let clash = ii_prove::term::name("RClash");
    assert!(session.model(&[&clash]).defs.len() > 2 * counterexample::VACUITY_CONE);
    let run = report::run_program(&ld, &[ii], &opts()).unwrap_or_else(|e| panic!("{}", e.rendered));
    let clash = &run.properties[0];
    assert_eq!(clash.status, Status::Proved, "{:?}", clash.reason);
    assert!(clash.vacuous, "{:?}", clash.vacuity);
    assert!(clash.vacuity.as_deref().unwrap_or("").contains("Clash = 0*"), "{:?}", clash.vacuity);
    // `Armed` reads the end of the chain and is not constant: no warning.
    let armed = &run.properties[1];
    assert_eq!(armed.status, Status::Proved, "{:?}", armed.reason);
    assert!(!armed.vacuous, "{:?}", armed.vacuity);
}

#[test]
fn the_cut_cone_never_invents_a_constant() {
    // The cut cone stops long before the chain's start; neither the chain's end nor
    // the timer after it is constant.
    const N: usize = 600;
    let props = "property timed_needs_chain: Timed => Chain600\nproperty chain_end: Chain600 . Go600 => Chain600\n";
    let (ld, ii) = long_chain_files("free", N, props);
    let run = report::run_program(&ld, &[ii], &opts()).unwrap_or_else(|e| panic!("{}", e.rendered));
    for p in &run.properties {
        assert_eq!(p.status, Status::Proved, "{}: {:?}", p.name, p.reason);
        assert!(!p.vacuous, "{}: {:?}", p.name, p.vacuity);
    }
}

#[test]
fn the_cached_vacuity_check_agrees_with_the_whole_cone_on_small_programs() {
    let cases = [
        (
            "tests/data/refutes_programs/traffic_greens_overlap.ld",
            "Ns_green . Ew_green",
            "Run = 0*",
        ),
        ("examples/water.ld", "L1_pump . L2_pump", "SP_fail = 0*"),
        ("examples/water_faulty.ld", "L1_up + L2_down", "L1_fail = 1*"),
    ];
    let (chain, _) = long_chain_files("small", 5, "");
    let cases = cases.map(|(ld, term, a)| (path(ld), term, a));
    let mut constants = 0;
    for (ld, term, assumption) in cases.into_iter().chain([(chain, "Clash + Timed", "In = 1*")]) {
        let mut sources = Sources::new();
        let loaded = load_program(&mut sources, &ld, &Default::default()).expect("loads");
        let text = format!("assume a: {assumption}\nproperty p: {term} = 0*\n");
        let file = sources.add("p.ii", text);
        let doc = syntax::parse_document(&sources, file, &loaded.compiled).expect("parses");
        let goal = report::obligation(&doc.properties[0].value);
        let assumed = report::assumptions(&doc);
        for assumptions in [&[][..], &assumed[..]] {
            let session = counterexample::Program {
                reference: loaded.reference.as_ref(),
                compiled: &loaded.compiled,
                assumptions,
                shared: None,
            };
            let cache = counterexample::VacuityCache::default();
            let exact = counterexample::vacuity(&session, &[&goal.lhs, &goal.rhs]);
            for _ in 0..2 {
                let cached =
                    counterexample::vacuity_cached(&session, &[&goal.lhs, &goal.rhs], &cache);
                assert_eq!(cached.constants, exact.constants, "{ld}");
                assert_eq!(cached.horizon, exact.horizon, "{ld}");
            }
            constants += exact.constants.len();
        }
    }
    // Some constants are found, with and without assumptions.
    assert!(constants >= 3, "{constants}");
}

/// A run that refutes one property of a program is kept, and refutes another property
/// it violates too (confirmed again: the trace replays on the simulator), but not one
/// it does not violate nor one that holds.
/// An LDmicro program and its properties, for the tests of shared counterexamples: the
/// loaded program and the properties' goals.
fn program_and_goals(
    sources: &mut Sources,
    stem: &str,
    ld: &str,
    props: &str,
) -> (report::LoadedProgram, Vec<ii_prove::prover::Obligation>) {
    let program = std::env::temp_dir().join(format!("ii_prove_{stem}_{}.ld", std::process::id()));
    std::fs::write(&program, ld).expect("writes");
    let loaded =
        load_program(sources, &program.display().to_string(), &Default::default()).expect("loads");
    let file = sources.add(format!("{stem}.ii"), props.to_string());
    let doc = syntax::parse_document(sources, file, &loaded.compiled).expect("parses");
    let goals = doc.properties.iter().map(|p| report::obligation(&p.value)).collect();
    (loaded, goals)
}

/// A session of `loaded` whose counterexamples are kept in `shared`.
fn shared_session<'a>(
    loaded: &'a report::LoadedProgram,
    shared: &'a counterexample::shared::Shared,
) -> counterexample::Program<'a> {
    counterexample::Program {
        reference: loaded.reference.as_ref(),
        compiled: &loaded.compiled,
        assumptions: &[],
        shared: Some(shared),
    }
}

/// Refutes `deep`, the property whose run the others are refuted from.
fn refute_deep(
    session: &counterexample::Program,
    goal: &ii_prove::prover::Obligation,
    limits: Limits,
) {
    let Verdict::Refuted(_) = counterexample::refute(session, goal, limits) else {
        panic!("`deep` is not refuted");
    };
}

/// The limits of the searches in the tests of shared counterexamples.
fn shared_limits() -> Limits {
    Limits {
        deadline: Instant::now() + Duration::from_secs(20),
        max_steps: 200,
        max_scans: 100_000,
        minimised: false,
        signals: true,
    }
}

/// Whether the program's own simulator, run on the counterexample's inputs, sets `bit`.
fn replay_sets(
    loaded: &report::LoadedProgram,
    c: &counterexample::Counterexample,
    bit: &str,
) -> bool {
    let mut sim = loaded.reference.simulator();
    let mut seen = false;
    for k in 0..c.trace.scans {
        let inputs: BTreeMap<String, bool> =
            c.trace.values.iter().map(|(n, v)| (n.clone(), v[k])).collect();
        sim.step(&inputs);
        seen |= sim.bit(bit);
    }
    seen
}

/// A kept run also holds the inputs outside its property's cone at drawn values: the
/// properties those inputs violate are refuted from it, each counterexample cut to the
/// inputs its own violation needs and confirmed on the simulator.
#[test]
fn a_grown_run_refutes_properties_outside_the_cone_it_came_from() {
    let mut sources = Sources::new();
    // Yb follows Xa; eight units apart: Yd_i follows Xe_i, Yf_i follows Xg_i or Xe_i.
    let mut text =
        String::from("LDmicro0.1\nCYCLE=10000\nPROGRAM\nRUNG\nCONTACTS Xa 0\nCOIL Yb 0 0 0\nEND\n");
    let mut props = String::from("property deep: Yb = 0*\n");
    for i in 0..8 {
        text += &format!("RUNG\nCONTACTS Xe{i} 0\nCOIL Yd{i} 0 0 0\nEND\n");
        text += &format!(
            "RUNG\nPARALLEL\nCONTACTS Xg{i} 0\nCONTACTS Xe{i} 0\nEND\nCOIL Yf{i} 0 0 0\nEND\n"
        );
        props += &format!("property apart{i}: Yd{i} = 0*\nproperty holds{i}: Yd{i} => Yf{i}\n");
    }
    let (loaded, goals) = program_and_goals(&mut sources, "grown", &text, &props);
    let shared = counterexample::shared::Shared::default();
    let session = shared_session(&loaded, &shared);
    let limits = shared_limits();
    refute_deep(&session, &goals[0], limits);
    let mut refuted = 0;
    for i in 0..8 {
        let Some(c) = counterexample::shared::refute_shared(&session, &goals[1 + 2 * i], limits)
        else {
            continue;
        };
        refuted += 1;
        assert!(c.simulator_scan.is_some(), "confirmed on the simulator");
        let set: Vec<&String> =
            c.trace.values.iter().filter(|(_, v)| v.contains(&true)).map(|(n, _)| n).collect();
        assert_eq!(set, vec![&format!("Xe{i}")], "only the input the violation needs");
        assert!(replay_sets(&loaded, &c, &format!("Yd{i}")), "the replay sets Yd{i}");
        assert!(
            counterexample::shared::refute_shared(&session, &goals[2 + 2 * i], limits).is_none(),
            "holds{i} holds"
        );
    }
    assert!(refuted > 0, "no property outside the cone of `deep` is refuted from its grown run");
}

#[test]
fn a_kept_run_refutes_the_other_properties_it_violates() {
    let mut sources = Sources::new();
    // Yb follows Xa, Yc follows Yb, Yd follows Xe.
    let (loaded, goals) = program_and_goals(
        &mut sources,
        "shared",
        "LDmicro0.1\nCYCLE=10000\nPROGRAM\nRUNG\nCONTACTS Xa 0\nCOIL Yb 0 0 0\nEND\nRUNG\nCONTACTS Yb 0\nCOIL Yc 0 0 0\nEND\nRUNG\nCONTACTS Xe 0\nCOIL Yd 0 0 0\nEND\n",
        "property deep: Yc = 0*\nproperty shallow: Yb = 0*\nproperty apart: Yd = 0*\nproperty holds: Yc => Yb\n",
    );
    let shared = counterexample::shared::Shared::default();
    let session = shared_session(&loaded, &shared);
    let limits = shared_limits();
    // Nothing kept yet.
    assert!(counterexample::shared::refute_shared(&session, &goals[1], limits).is_none());
    refute_deep(&session, &goals[0], limits);
    let c = counterexample::shared::refute_shared(&session, &goals[1], limits)
        .expect("the run that refutes `deep` refutes `shallow`");
    assert!(c.simulator_scan.is_some(), "confirmed on the simulator");
    assert!(c.trace.values.get("Xa").is_some_and(|v| v.contains(&true)), "{:?}", c.trace);
    assert!(replay_sets(&loaded, &c, "Yb"), "the replay sets Yb");
    // `holds` holds: no run kept refutes it.
    assert!(counterexample::shared::refute_shared(&session, &goals[3], limits).is_none());
}

/// A property whose cone reaches past that of the kept run's property (`RArmed` reads
/// the end of a 300-rung chain and its own input) is refuted near the kept run, the
/// equations outside that cone judged with the part: confirmed on the simulator, the
/// program's own simulator sets `RArmed` on its inputs, and `RClash` (0 in every run)
/// is not refuted.
#[test]
fn a_property_past_the_kept_cone_is_refuted_near_the_kept_run() {
    let mut sources = Sources::new();
    let props =
        "property deep: RChain300 = 0*\nproperty armed: RArmed = 0*\nproperty clash: RClash = 0*\n";
    let (loaded, goals) = program_and_goals(&mut sources, "past", &long_chain(300), props);
    let shared = counterexample::shared::Shared::default();
    let session = shared_session(&loaded, &shared);
    let limits = shared_limits();
    refute_deep(&session, &goals[0], limits);
    let c = counterexample::shared::refute_shared(&session, &goals[1], limits)
        .expect("the run that refutes `deep` is repaired for `armed`");
    assert!(c.simulator_scan.is_some(), "confirmed on the simulator");
    assert!(c.trace.values.get("XArm").is_some_and(|v| v.contains(&true)), "{:?}", c.trace);
    assert!(replay_sets(&loaded, &c, "RArmed"), "the replay sets RArmed");
    assert!(counterexample::shared::refute_shared(&session, &goals[2], limits).is_none());
}
