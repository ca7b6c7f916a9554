//! A timer's elapsed time `ET` (TON, TOF, TP) in Structured Text: the scan model's values of `ET` and `Q` against matiec's `lib/timer.txt` state machines transcribed here (STATE, PREV_IN, START_TIME against the runtime's clock), on random inputs; the star-delta example's stages proved and its overlap refuted with the elapsed time drawn; TIME comparisons of the wrong type refused.

use crate::common;
use crate::common::rng;

use std::collections::BTreeMap;

use common::{ii_prove, text, verdicts};
use ii_prove::diag::Sources;
use ii_prove::iec::literal::matiec_duration_ns;
use ii_prove::program::compile::TimerModel;
use ii_prove::program::simulate::Simulator;
use rng::Rng;

/// Which of matiec's timers.
#[derive(Clone, Copy)]
enum Kind {
    On,
    Off,
    Pulse,
}

/// matiec's `TON`, `TOF` and `TP` as `lib/timer.txt` writes them, the clock in ns.
struct Matiec {
    kind: Kind,
    pt: i64,
    state: u8,
    prev_in: bool,
    start: i64,
    q: bool,
    et: i64,
}

impl Matiec {
    fn new(kind: Kind, pt: i64) -> Matiec {
        Matiec { kind, pt, state: 0, prev_in: false, start: 0, q: false, et: 0 }
    }

    fn call(&mut self, input: bool, now: i64) {
        match self.kind {
            Kind::On => {
                if self.state == 0 && !self.prev_in && input {
                    (self.state, self.q, self.start) = (1, false, now);
                } else if !input {
                    (self.et, self.q, self.state) = (0, false, 0);
                } else if self.state == 1 {
                    if self.start + self.pt <= now {
                        (self.state, self.q, self.et) = (2, true, self.pt);
                    } else {
                        self.et = now - self.start;
                    }
                }
            }
            Kind::Off => {
                if self.state == 0 && self.prev_in && !input {
                    (self.state, self.start) = (1, now);
                } else if input {
                    (self.et, self.state) = (0, 0);
                } else if self.state == 1 {
                    if self.start + self.pt <= now {
                        (self.state, self.et) = (2, self.pt);
                    } else {
                        self.et = now - self.start;
                    }
                }
                self.q = input || self.state == 1;
            }
            Kind::Pulse => {
                if self.state == 0 && !self.prev_in && input {
                    (self.state, self.q, self.start) = (1, true, now);
                } else if self.state == 1 {
                    if self.start + self.pt <= now {
                        (self.state, self.q, self.et) = (2, false, self.pt);
                    } else {
                        self.et = now - self.start;
                    }
                }
                if self.state == 2 && !input {
                    (self.et, self.state) = (0, 0);
                }
            }
        }
        self.prev_in = input;
    }
}

/// Random presets (0, below, at and above a whole number of cycles) and random inputs
/// held for random numbers of scans: every scan, each timer's `ET` and `Q` in the scan
/// model's simulator are matiec's.
#[test]
fn elapsed_times_are_matiec_s() {
    let mut rng = Rng::new(0xE7);
    let (mut scans, mut running) = (0u64, 0u64);
    for round in 0..60 {
        let cycle_ms = 10 * (1 + rng.below(10) as i64);
        let pts: Vec<i64> = (0..3)
            .map(|_| match rng.below(4) {
                0 => 0,
                1 => cycle_ms * rng.below(5) as i64,
                _ => rng.below(6) as i64 * cycle_ms + rng.below(cycle_ms as u64) as i64,
            })
            .collect();
        let text = format!(
            "PROGRAM p\n  VAR\n    a AT %IX0.0 : BOOL;\n    b AT %IX0.1 : BOOL;\n    c AT %IX0.2 : BOOL;\n    \
             T1 : TON;\n    F1 : TOF;\n    P1 : TP;\n    x, y, z : BOOL;\n  END_VAR\n  \
             T1(IN := a, PT := T#{}ms);\n  F1(IN := b, PT := T#{}ms);\n  P1(IN := c, PT := T#{}ms);\n  \
             x := T1.ET > T#0ms;\n  y := F1.ET > T#0ms;\n  z := P1.ET > T#0ms;\nEND_PROGRAM\n\
             CONFIGURATION c\n  RESOURCE r ON PLC\n    TASK t (INTERVAL := T#{cycle_ms}ms, PRIORITY := 1);\n    \
             PROGRAM i WITH t : p;\n  END_RESOURCE\nEND_CONFIGURATION\n",
            pts[0], pts[1], pts[2]
        );
        let mut sources = Sources::default();
        let file = sources.add("timers.st", text.clone());
        let unit = ii_prove::iec::read(&sources, file).expect("read");
        let lowered = ii_prove::iec::lower(&sources, &unit, None, None).expect("lowered");
        let mut sim = Simulator::new(&lowered.program, TimerModel::Plc);
        // A preset is the value matiec's C gives its literal (`T#1400ms` is 1 ns short),
        // checked against gcc's in the `iec::literal` unit tests.
        let pt = |ms: i64| matiec_duration_ns(&format!("T#{ms}ms")).expect("a literal");
        let mut timers = [
            ("T1", "a", Matiec::new(Kind::On, pt(pts[0]))),
            ("F1", "b", Matiec::new(Kind::Off, pt(pts[1]))),
            ("P1", "c", Matiec::new(Kind::Pulse, pt(pts[2]))),
        ];
        let mut inputs: BTreeMap<String, bool> = BTreeMap::new();
        let mut hold = [0u64; 3];
        for k in 0..200i64 {
            for (j, (_, pin, _)) in timers.iter().enumerate() {
                if hold[j] == 0 {
                    inputs.insert(pin.to_string(), rng.chance(50));
                    hold[j] = 1 + rng.below(12);
                }
                hold[j] -= 1;
            }
            sim.step(&inputs);
            scans += 1;
            for (name, pin, m) in &mut timers {
                m.call(inputs[*pin], k * cycle_ms * 1_000_000);
                running += u64::from(m.state == 1);
                let et = sim.int(&format!("{name}_ET"));
                let q = sim.bit(&format!("{name}_Q"));
                assert_eq!(
                    (et, q),
                    (Some(m.et), m.q),
                    "round {round}, scan {k}, {name} (PT {} ns):\n{text}",
                    m.pt
                );
            }
        }
    }
    eprintln!("elapsed time: {scans} scans of three timers, {running} timer-scans running");
}

#[test]
fn the_star_delta_stages_are_proved_and_their_overlap_refuted_with_the_elapsed_time() {
    let got = verdicts(&[
        "tests/data/proves_programs/stage_timer.st",
        "tests/data/proves_programs/stage_timer.ii",
    ]);
    assert_eq!(got.len(), 5, "{got:?}");
    assert!(got.iter().all(|(_, v)| v == "proved"), "{got:?}");
    let out = ii_prove(&[
        "tests/data/refutes_programs/stage_timer_overlap.st",
        "tests/data/refutes_programs/stage_timer_overlap.ii",
    ]);
    assert_eq!(out.status.code(), Some(1));
    let report = text(&out.stdout);
    // Delta on at 0.9 s while Star is on until 1 s: the scan the timer has run 0.9 s.
    assert!(report.contains("at t = 0.9 s (scan 10)"), "{report}");
    let row = report
        .lines()
        .find(|l| l.trim_start().starts_with("Ramp_ET "))
        .expect("the elapsed time as a value row");
    assert!(row.contains(" 900ms"), "{report}");
}

#[test]
fn a_time_compared_with_an_integer_is_refused() {
    let program = "tests/data/proves_programs/stage_timer.st";
    for (property, expected) in [
        ("property P: 1* => [Ramp_ET <= 2000]", "this compares a TIME with an integer"),
        ("property P: 1* => [Seconds <= T#2s]", "this compares a TIME with an integer"),
        ("property P: 1* => [Ramp_ET <= T#0.0005us]", "whole number of nanoseconds"),
    ] {
        let dir = std::env::temp_dir().join(format!("ii-elapsed-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        let ii = dir.join("p.ii");
        std::fs::write(&ii, property).expect("write");
        let out = ii_prove(&[program, ii.to_str().expect("path")]);
        assert_eq!(out.status.code(), Some(2), "{property}");
        let err = text(&out.stderr);
        assert!(err.contains(expected), "{property}: {err}");
    }
}

/// Where the elapsed-time properties' program is.
const UNREAD: &str = "tests/data/refutes_programs/timer_et_unread";

/// A signal of the JSON report at the instant `t` (s): the value at a breakpoint, else
/// on the interval that ends at the next one.
fn json_value(signal: &serde_json::Value, t: f64) -> bool {
    let breaks: Vec<f64> = signal["breakpoints"]
        .as_array()
        .expect("breakpoints")
        .iter()
        .map(|b| b.as_str().expect("a time").parse::<f64>().expect("a decimal"))
        .collect();
    if let Some(i) = breaks.iter().position(|b| (b - t).abs() < 1e-9) {
        return signal["points"][i].as_bool().expect("a bit");
    }
    let i = breaks.iter().filter(|b| **b < t).count();
    signal["intervals"][i].as_bool().expect("a bit")
}

/// A duration below 1 s as the diagrams write it (`0s`, `20ms`), written here from its
/// value in ns.
fn in_ms(ns: i64) -> String {
    assert!((0..1_000_000_000).contains(&ns) && ns % 1_000_000 == 0, "{ns}");
    if ns == 0 { "0s".into() } else { format!("{}ms", ns / 1_000_000) }
}

/// Consecutive repeats dropped: the values a track writes where they change.
fn changes(values: &[String]) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for v in values {
        if out.last() != Some(v) {
            out.push(v.clone());
        }
    }
    out
}

/// The program does not read `T1.ET`; the properties do. Each counterexample draws
/// the elapsed time, not the hidden count of scans, in the text diagram, JSON, VCD
/// (a 64-bit vector in ns) and WaveDrom (a data lane in ms), and its values are those
/// of matiec's `TON` (transcribed above) run on the counterexample's input: `min(k ·
/// 20 ms, 100 ms)` on the `k`-th scan after the start.
#[test]
fn an_unread_elapsed_time_is_drawn_as_matiec_computes_it() {
    let dir = std::env::temp_dir().join(format!("ii-et-drawn-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let (vcd, wavedrom) = (dir.join("run.vcd"), dir.join("run.json"));
    let (st, ii) = (format!("{UNREAD}.st"), format!("{UNREAD}.ii"));
    let out = ii_prove(&[
        &st,
        &ii,
        "--format",
        "json",
        "--vcd",
        vcd.to_str().expect("path"),
        "--wavedrom",
        wavedrom.to_str().expect("path"),
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
    let json: serde_json::Value = serde_json::from_str(&text(&out.stdout)).expect("JSON");
    let (cycle_s, cycle_ns, pt) = (0.02, 20_000_000i64, matiec_duration_ns("T#100ms").unwrap());
    let vcd = std::fs::read_to_string(&vcd).expect("the VCD file");
    let wavedrom: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&wavedrom).expect("WaveDrom")).unwrap();
    let properties = json["properties"].as_array().expect("properties");
    assert_eq!(properties.len(), 3);
    let mut running = 0;
    for (index, p) in properties.iter().enumerate() {
        let name = p["name"].as_str().unwrap();
        assert_eq!(p["status"], "refuted", "{name}");
        let c = &p["counterexample"];
        assert_eq!(c["simulator_scan"], c["scan"], "{name}");
        let integers = c["integers"].as_array().expect("integers");
        assert_eq!(integers.len(), 1, "{name}: only the elapsed time, not its count");
        let et = &integers[0];
        assert_eq!((&et["name"], &et["type"]), (&"T1_ET".into(), &"TIME".into()), "{name}");
        let got: Vec<i64> =
            et["values"].as_array().unwrap().iter().map(|v| v.as_i64().unwrap()).collect();
        // matiec's TON on the counterexample's input, the clock at k · cycle.
        let start = c["signals"]
            .as_array()
            .unwrap()
            .iter()
            .find(|s| s["name"] == "start")
            .expect("the input start");
        let mut ton = Matiec::new(Kind::On, pt);
        let expected: Vec<i64> = (0..got.len())
            .map(|k| {
                let at = if k == 0 { cycle_s / 2.0 } else { k as f64 * cycle_s };
                ton.call(json_value(start, at), k as i64 * cycle_ns);
                running += usize::from(ton.state == 1);
                ton.et
            })
            .collect();
        assert_eq!(got, expected, "{name}");
        assert!(expected.iter().any(|v| *v > 0), "{name}: the timer runs");
        // The text diagram: the values in ms where they change, no count of scans.
        let diagram: Vec<&str> =
            c["diagram"].as_array().unwrap().iter().map(|l| l.as_str().unwrap()).collect();
        assert!(!diagram.iter().any(|l| l.contains("_SCANS")), "{diagram:#?}");
        let row = diagram.iter().find(|l| l.starts_with("T1_ET ")).expect("an ET row");
        let written: Vec<String> = row.split_whitespace().skip(1).map(String::from).collect();
        let in_units: Vec<String> = expected.iter().map(|v| in_ms(*v)).collect();
        assert_eq!(written, changes(&in_units), "{name}: {diagram:#?}");
        // WaveDrom: a data lane with the same texts.
        let group = &wavedrom["signal"][index];
        assert_eq!(group[0], name);
        let lane = group.as_array().unwrap().iter().find(|l| l["name"] == "T1_ET").expect("lane");
        let data: Vec<String> =
            lane["data"].as_array().unwrap().iter().map(|d| d.as_str().unwrap().into()).collect();
        assert_eq!(data, changes(&in_units), "{name}");
        // VCD: this scope's 64-bit vector, in ns, read at each scan's start (ms ticks).
        let scope = vcd.split("$scope module ").nth(index + 1).expect("a scope");
        let var = scope.lines().find(|l| l.ends_with(" T1_ET $end")).expect("the ET vector");
        let fields: Vec<&str> = var.split_whitespace().collect();
        assert_eq!(fields[2], "64", "{var}");
        let id = fields[3];
        assert!(vcd.contains("$timescale 1ms $end"), "{vcd}");
        let mut tick = 0u64;
        let mut values: Vec<(u64, i64)> = Vec::new();
        for line in vcd.lines() {
            if let Some(t) = line.strip_prefix('#') {
                tick = t.parse().expect("a tick");
            } else if let Some((word, rest)) =
                line.strip_prefix('b').and_then(|l| l.split_once(' '))
                && rest == id
            {
                values.push((tick, i64::from_str_radix(word, 2).expect("a word")));
            }
        }
        for (k, e) in expected.iter().enumerate() {
            let at = k as u64 * 20;
            let v = values.iter().rev().find(|(t, _)| *t <= at).map(|(_, v)| *v);
            assert_eq!(v, Some(*e), "{name}: scan {k} in the VCD");
        }
    }
    assert!(running >= 5, "only {running} scans with the timer running");
    std::fs::remove_dir_all(&dir).ok();
}

/// `[T1.ET …]`, `[t1.et …]` and `[T1_ET …]` are one atom: the same verdicts, whether
/// the program reads the elapsed time (stage_timer.st) or not (timer_et_unread.st); the
/// bound `ET <= PT` is proved with a kernel-checked proof.
#[test]
fn a_pin_and_its_name_give_the_same_verdicts() {
    let dir = std::env::temp_dir().join(format!("ii-et-pin-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    for (program, inst, atoms) in [
        (
            format!("{UNREAD}.st"),
            "T1",
            ["<= T#100ms", "< T#100ms", ">= T#40ms", "= 0", "<> T#60ms", "< T#50ms"],
        ),
        (
            "tests/data/proves_programs/stage_timer.st".to_string(),
            "Ramp",
            ["<= T#2s", ">= T#100ms", ">= T#1100ms", "= 0", "<> T#1s", "< T#900ms"],
        ),
    ] {
        let mut props = String::new();
        for (k, atom) in atoms.iter().enumerate() {
            let lower = inst.to_ascii_lowercase();
            props.push_str(&format!("property N{k}: 1* => [{inst}_ET {atom}]\n"));
            props.push_str(&format!("property D{k}: 1* => [{inst}.ET {atom}]\n"));
            props.push_str(&format!("property L{k}: 1* => [{lower}.et {atom}]\n"));
        }
        let ii = dir.join(format!("{inst}.ii"));
        std::fs::write(&ii, props).expect("write");
        let got = verdicts(&[&program, ii.to_str().unwrap()]);
        assert_eq!(got.len(), 3 * atoms.len(), "{program}: {got:?}");
        for (k, atom) in atoms.iter().enumerate() {
            let of = |p: &str| got.iter().find(|(n, _)| *n == format!("{p}{k}")).map(|(_, v)| v);
            assert_eq!(of("N"), of("D"), "{program}: [{inst}.ET {atom}]");
            assert_eq!(of("N"), of("L"), "{program}: [{inst}.ET {atom}]");
        }
        let of = |p: &str| got.iter().find(|(n, _)| n == p).map(|(_, v)| v.as_str());
        assert_eq!(of("D0"), Some("proved"), "{program}: ET <= PT");
        assert_eq!(of("D5"), Some("refuted"), "{program}");
    }
    // The bound of the unread elapsed time, proved: its proof printed as the kernel
    // checked it.
    let out = ii_prove(&[
        &format!("{UNREAD}.st"),
        "tests/data/proves_programs/timer_et_unread.ii",
        "--trace",
        "--only",
        "BoundedPin",
    ]);
    let report = text(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{report}");
    let first: Vec<&str> = report.lines().next().unwrap_or("").split_whitespace().collect();
    assert_eq!(first[..2], ["BoundedPin", "proved"], "{report}");
    assert!(report.lines().count() > 5, "a proof is printed: {report}");
    std::fs::remove_dir_all(&dir).ok();
}

/// A pin the program computes no integer for is an error at the comparison, with the
/// pins it has; a misspelt instance gets a suggestion. `show` of a program whose ET
/// nothing reads has none.
#[test]
fn an_unknown_pin_is_a_located_error() {
    let dir = std::env::temp_dir().join(format!("ii-et-unknown-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let program = format!("{UNREAD}.st");
    for (property, expected) in [
        (
            "property E: lamp => [T1.ET < T#1s]\nproperty P: lamp => [T1.XX < 3]",
            vec!["unknown pin `T1.XX`", "p.ii:2:21", "`T1.ET`"],
        ),
        (
            "property P: lamp => [T1.XX < 3]",
            vec!["unknown pin `T1.XX`", "p.ii:1:21", "no integer pin"],
        ),
        (
            "property E: lamp => [T1.ET < T#1s]\nproperty P: lamp => [T2.ET < T#1s]",
            vec!["unknown pin `T2.ET`", "p.ii:2:21", "did you mean `T1.ET`?"],
        ),
        (
            "property P: lamp => [T2.ET < T#1s]",
            vec!["unknown pin `T2.ET`", "where a property file given with the program names it"],
        ),
        ("property P: lamp => [T1. < 3]", vec!["p.ii:1:26", "a pin name"]),
    ] {
        let ii = dir.join("p.ii");
        std::fs::write(&ii, property).expect("write");
        let out = ii_prove(&[&program, ii.to_str().expect("path")]);
        assert_eq!(out.status.code(), Some(2), "{property}");
        let err = text(&out.stderr);
        for e in expected {
            assert!(err.contains(e), "{property}: {e} in\n{err}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
    let show = ii_prove(&["show", &program]);
    assert_eq!(show.status.code(), Some(0));
    assert!(!text(&show.stdout).contains("T1_ET"), "{}", text(&show.stdout));
}

/// The loader's scan of property files for the elapsed times they name.
#[test]
fn property_files_name_elapsed_times() {
    let named = ii_prove::report::elapsed_named(
        "property A: x => [T1.ET < T#2s] // Ramp_ET, main.t2.et\nproperty B: [P1_et >= 0] . Q1_ETA . ET\n",
    );
    let got: Vec<&str> = named.iter().map(String::as_str).collect();
    assert_eq!(got, ["P1", "RAMP", "T1", "T2"]);
}
