//! The ladder model against what the PLC does: programs whose properties hold are proved (`tests/data/proves_programs/`), programs the compiler cannot model are refused with a located error (`tests/data/ldmicro/refused/`), and `--timers` changes what is compiled.

mod common;

use std::path::{Path, PathBuf};
use std::time::Duration;

use ii_prove::diag::{RenderStyle, Sources, render};
use ii_prove::ladder::{CompileOptions, TimerModel};
use ii_prove::report::{self, Options, Status, load_program};

fn data(folder: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(folder)
}

fn opts() -> Options {
    // As tests/verdicts.rs: a timer invariant is found and checked within seconds.
    Options { timeout: Duration::from_secs(20), ..Options::default() }
}

/// Every `NAME.ld` (or PLCopen `NAME.xml`, Structured Text `NAME.st`) of `proves_programs/` with its `NAME.ii`: every
/// property proved.
#[test]
fn programs_whose_properties_hold_are_proved() {
    let mut files = common::files_with(&data("proves_programs"), "ld");
    files.extend(common::files_with(&data("proves_programs"), "xml"));
    files.extend(common::files_with(&data("proves_programs"), "st"));
    assert!(files.len() >= 3, "only {} cases", files.len());
    for ld in files {
        let ii = ld.with_extension("ii").display().to_string();
        let ld = ld.display().to_string();
        let run = report::run_program(&ld, std::slice::from_ref(&ii), &opts())
            .unwrap_or_else(|e| panic!("{ld}: {}", e.rendered));
        assert!(!run.properties.is_empty(), "{ii}: no property");
        let bounds = trace_bounds(&std::fs::read_to_string(&ii).expect("readable"));
        for p in &run.properties {
            assert_eq!(p.status, Status::Proved, "{ld}: {} ({:?})", p.name, p.reason);
            if let (Some(&bound), Some(trace)) = (bounds.get(&p.name), &p.trace) {
                assert!(
                    trace.length <= bound,
                    "{ii}: the proof of {} has {} lines, at most {bound} expected",
                    p.name,
                    trace.length
                );
            }
        }
        assert_eq!(run.timers, Some("plc"));
    }
}

/// The bounds `// trace: at most N lines` written right above `property NAME` (as in
/// `tests/verdicts.rs`).
fn trace_bounds(text: &str) -> std::collections::BTreeMap<String, usize> {
    let mut bounds = std::collections::BTreeMap::new();
    let mut pending = None;
    for line in text.lines().map(str::trim) {
        if let Some(n) = line.strip_prefix("// trace: at most ") {
            let n = n.trim_end_matches(" lines").trim_end_matches(" line");
            pending = Some(n.parse::<usize>().expect("`// trace: at most N lines`"));
        } else if let Some(rest) = line.strip_prefix("property ") {
            let name = rest.split(':').next().unwrap_or("").trim().to_string();
            if let Some(n) = pending.take() {
                bounds.insert(name, n);
            }
        }
    }
    bounds
}

/// Every `refused/NAME.ld` fails to load, and the rendered error contains every
/// non-blank line of `NAME.expected` (message and `file:line:col`).
#[test]
fn programs_with_control_flow_are_refused_with_a_located_error() {
    let files = common::files_with(&data("ldmicro/refused"), "ld");
    assert!(files.len() >= 3, "only {} cases", files.len());
    for path in files {
        let expected = std::fs::read_to_string(path.with_extension("expected"))
            .unwrap_or_else(|_| panic!("{} has no .expected file", path.display()));
        let mut sources = Sources::new();
        let shown = path.display().to_string();
        let Err(errors) = load_program(&mut sources, &shown, &CompileOptions::default()) else {
            panic!("{shown} loaded but must be refused");
        };
        let text = render(&errors[0], &sources, RenderStyle { ascii: false });
        assert!(text.contains('^'), "{shown}: no caret in\n{text}");
        for fragment in expected.lines().filter(|l| !l.trim().is_empty()) {
            assert!(text.contains(fragment), "{shown}: expected `{fragment}` in\n{text}");
        }
        // The command line exits with 2 and proves nothing.
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_ii-prove"))
            .arg("show")
            .arg(&path)
            .output()
            .expect("runs");
        assert_eq!(out.status.code(), Some(2), "{shown}");
        assert!(out.stdout.is_empty(), "{shown}: {}", String::from_utf8_lossy(&out.stdout));
    }
}

/// `--timers ideal` compiles the delay as written, `--timers plc` what the runtime counts;
/// the report and `show` say which, and an LDmicro0.1 timer's one scan early is refuted
/// only under `plc`.
#[test]
fn timers_plc_and_ideal() {
    let ld = data("refutes_programs/timer_v01_one_scan_early.ld").display().to_string();
    let ii = data("refutes_programs/timer_v01_one_scan_early.ii").display().to_string();
    let plc = report::run_program(&ld, std::slice::from_ref(&ii), &opts()).expect("runs");
    assert_eq!(plc.properties[0].status, Status::Refuted);
    let ideal = Options { timers: TimerModel::Ideal, ..opts() };
    let run = report::run_program(&ld, std::slice::from_ref(&ii), &ideal).expect("runs");
    assert_eq!(run.properties[0].status, Status::Proved);
    assert_eq!(run.timers, Some("ideal"));
    let json: serde_json::Value = serde_json::from_str(&report::render_json(&plc)).expect("json");
    assert_eq!(json["timers"], "plc");
    assert!(report::render_text(&run, &ideal).contains("(--timers ideal)"));
    let shown = report::show_program(&ld, &opts()).expect("shows");
    assert!(
        shown.contains("TON TDelay 1000000 µs, adjust -1: P = 9 scans; effective delay 900ms"),
        "{shown}"
    );
    assert!(shown.contains("assume L01: YMotor = 900ms/XStart"), "{shown}");
    let shown = report::show_program(&ld, &ideal).expect("shows");
    assert!(shown.contains("assume L01: YMotor = 1s/XStart"), "{shown}");
}

/// A timer whose count differs from its written delay is named in a warning, with the
/// count; one that matches is not.
#[test]
fn a_timer_that_does_not_time_what_is_written_is_reported() {
    let ld = data("refutes_programs/timer_adjust_short_delay.ld").display().to_string();
    let mut sources = Sources::new();
    let loaded = load_program(&mut sources, &ld, &CompileOptions::default()).expect("loads");
    let text = loaded.warnings.join("\n");
    assert!(text.contains("= 8 scans") && text.contains("80ms, not the 30ms written"), "{text}");
    let water = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/water.ld");
    let loaded = load_program(&mut sources, &water.display().to_string(), &Default::default())
        .expect("loads");
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    assert!(loaded.compiled.timer_info.iter().all(|t| t.scans == 500));
}

/// Every `refused_properties/NAME.ii` (about `NAME.ld`) writes a delay that is not a
/// whole number of the program's scan cycles: the run exits with 2, proves nothing, and
/// the error names the place and the whole multiples around the delay.
#[test]
fn delays_between_scan_cycles_are_refused_with_a_located_error() {
    let files = common::files_with(&data("refused_properties"), "ii");
    assert!(files.len() >= 3, "only {} cases", files.len());
    for ii in files {
        let expected = std::fs::read_to_string(ii.with_extension("expected"))
            .unwrap_or_else(|_| panic!("{} has no .expected file", ii.display()));
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_ii-prove"))
            .args(["--color", "never"])
            .arg(ii.with_extension("ld"))
            .arg(&ii)
            .output()
            .expect("runs");
        let shown = ii.display();
        let text = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{shown}: {text}");
        assert!(out.stdout.is_empty(), "{shown}: {}", String::from_utf8_lossy(&out.stdout));
        assert!(text.contains('^'), "{shown}: no caret in\n{text}");
        assert!(!text.contains("unknown signal"), "{shown}: a follow-on error in\n{text}");
        for fragment in expected.lines().filter(|l| !l.trim().is_empty()) {
            assert!(text.contains(fragment), "{shown}: expected `{fragment}` in\n{text}");
        }
    }
}

/// `--timers ideal` uses a timer's delay as written, so a delay between whole cycles is
/// refused with the timer's place; `--timers plc` compiles the scans the runtime counts.
#[test]
fn ideal_timers_between_scan_cycles_are_refused() {
    let path = data("ldmicro/refused_ideal/between.ld");
    let shown = path.display().to_string();
    let mut sources = Sources::new();
    let ideal = CompileOptions { timers: TimerModel::Ideal, ..CompileOptions::default() };
    let Err(errors) = load_program(&mut sources, &shown, &ideal) else {
        panic!("{shown} loaded with --timers ideal");
    };
    let rendered = render(&errors[0], &sources, RenderStyle { ascii: false });
    assert!(rendered.contains("between.ld:6:5"), "{rendered}");
    assert!(rendered.contains("20000 µs and 30000 µs"), "{rendered}");
    assert!(load_program(&mut sources, &shown, &CompileOptions::default()).is_ok());
}
