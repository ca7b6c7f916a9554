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
    assert!(row.contains("T#900ms"), "{report}");
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
