//! The ladder model against what the PLC does: programs whose properties hold are proved (`tests/data/proves_programs/`), programs the compiler cannot model are refused with a located error (`tests/data/ldmicro/refused/`), and `--timers` changes what is compiled.

use crate::common;

use std::path::{Path, PathBuf};
use std::time::Duration;

use ii_prove::diag::{RenderStyle, Sources, render};
use ii_prove::ladder::{CompileOptions, TimerModel};
use ii_prove::report::{self, Options, Status, load_program};

fn data(folder: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(folder)
}

fn opts() -> Options {
    // As tests/suite/verdicts.rs: a timer invariant is found and checked within seconds.
    Options { timeout: Duration::from_secs(20), ..Options::default() }
}

/// Every `NAME.ld` (or PLCopen `NAME.xml`, Structured Text `NAME.st`, `NAME.il`) of
/// `proves_programs/` with its `NAME.ii`: every property proved, its printed trace
/// (`--trace`, lemmas folded) within the bound written above it. Every property of an
/// `.ld` or `.xml` there proved by induction over scans (the timing cases): its folded
/// trace is at most 25 lines, the trace of `--trace-all` prints every lemma the kernel
/// checked with the proof, each under its name, and each timer chain's template,
/// written out for every count it lists, is a lemma of the full trace. The files are
/// shared between two threads.
#[test]
fn programs_whose_properties_hold_are_proved_and_their_traces_fold() {
    let mut files = common::files_with(&data("proves_programs"), "ld");
    files.extend(common::files_with(&data("proves_programs"), "xml"));
    files.extend(common::files_with(&data("proves_programs"), "st"));
    files.extend(common::files_with(&data("proves_programs"), "il"));
    assert!(files.len() >= 3, "only {} cases", files.len());
    let next = std::sync::atomic::AtomicUsize::new(0);
    let (inductions, templates) = std::thread::scope(|scope| {
        let worker = || {
            let (mut inductions, mut templates) = (0, 0);
            while let Some(ld) = files.get(next.fetch_add(1, std::sync::atomic::Ordering::SeqCst)) {
                let (i, t) = proved_with_folding_traces(ld);
                (inductions, templates) = (inductions + i, templates + t);
            }
            (inductions, templates)
        };
        let other = scope.spawn(worker);
        let (i, t) = worker();
        let (j, u) = other.join().expect("the other thread");
        (i + j, t + u)
    });
    assert!(inductions >= 8, "only {inductions} properties proved by induction");
    assert!(templates >= 100, "only {templates} chain lemmas read back from templates");
}

/// The checks of [`programs_whose_properties_hold_are_proved_and_their_traces_fold`] on
/// one program: how many properties were proved by induction, and how many chain
/// lemmas were read back from templates.
fn proved_with_folding_traces(ld: &Path) -> (usize, usize) {
    let ii = ld.with_extension("ii").display().to_string();
    let ladder = matches!(ld.extension().and_then(|e| e.to_str()), Some("ld" | "xml"));
    let ld = ld.display().to_string();
    let folded = report::run_program(&ld, std::slice::from_ref(&ii), &opts())
        .unwrap_or_else(|e| panic!("{ld}: {}", e.rendered));
    assert!(!folded.properties.is_empty(), "{ii}: no property");
    assert_eq!(folded.timers, Some("plc"));
    let bounds = common::trace_bounds(&std::fs::read_to_string(&ii).expect("readable"));
    for p in &folded.properties {
        assert_eq!(p.status, Status::Proved, "{ld}: {} ({:?})", p.name, p.reason);
        if let (Some(&bound), Some(trace)) = (bounds.get(&p.name), &p.trace) {
            let printed = printed_lines(&trace.lines);
            assert!(
                printed <= bound,
                "{ii}: the proof of {} prints {printed} lines, at most {bound} expected:\n{}",
                p.name,
                trace.lines.join("\n")
            );
        }
    }
    let by_induction =
        |p: &&report::PropertyReport| p.trace.as_ref().is_some_and(|t| t.method == "induction");
    if !ladder || !folded.properties.iter().any(|p| by_induction(&p)) {
        return (0, 0);
    }
    let full = Options { trace_all: true, ..opts() };
    let whole = report::run_program(&ld, std::slice::from_ref(&ii), &full).expect("runs");
    let (mut inductions, mut templates) = (0, 0);
    for (p, q) in folded.properties.iter().zip(&whole.properties) {
        let (Some(t), Some(u)) = (&p.trace, &q.trace) else { continue };
        if t.method != "induction" {
            continue;
        }
        inductions += 1;
        let (short, long) = (printed_lines(&t.lines), printed_lines(&u.lines));
        println!("{ii} {}: {short} lines folded, {long} in full", p.name);
        assert!(short <= 25, "{ii}: {} prints {short} lines:\n{}", p.name, t.lines.join("\n"));
        assert!(!u.lemmas.is_empty(), "{ii}: {}: an induction with no lemma", p.name);
        for lemma in &u.lemmas {
            let header = format!("lemma {lemma}:");
            assert!(
                u.lines.contains(&header),
                "{ii}: {}: `{header}` missing from the full trace",
                p.name
            );
        }
        assert_eq!(t.lemmas, u.lemmas, "{ii}: {}: the same proof both ways", p.name);
        templates += chain_templates_match(&t.lines, &u.lines, &format!("{ii}: {}", p.name));
    }
    (inductions, templates)
}

/// Reads the folded trace's timer chains back — each header's abbreviation (`X = …`) and
/// `δ`, each form's template in `k` for every count listed — and finds each statement so
/// written as a lemma (its first term, then its last step) in the full trace. Returns how
/// many were found.
fn chain_templates_match(folded: &[String], full: &[String], what: &str) -> usize {
    let mut delta_us: Option<u64> = None;
    let mut found = 0;
    for pair in folded.windows(2) {
        let Some((_, chain)) = pair[0].split_once(", the timer chain of ") else { continue };
        let chain = chain.trim_end_matches(':');
        let (chain, delta) = match chain.rsplit_once(", δ = ") {
            Some((c, d)) => (c, Some(d)),
            None => (chain, None),
        };
        if let Some(d) = delta {
            delta_us = Some(micros(d));
        }
        let short = chain.split_once(" = ");
        for segment in pair[1].trim().split(";  ") {
            let statement = segment.rsplit_once("   [").map_or(segment, |(s, _)| s);
            let statement = statement.split(", and one scan earlier").next().unwrap_or("");
            let (statement, ks) = match statement.split_once(" for k = ") {
                Some((s, ks)) => (s, counts(ks)),
                None => (statement, vec![0]),
            };
            let (lhs, rhs) = statement
                .split_once(" = ")
                .or_else(|| statement.split_once(" ⇒ "))
                .unwrap_or_else(|| panic!("{what}: no relation in `{statement}`"));
            for k in ks {
                let side = |s: &str| {
                    let mut s = s.to_string();
                    if let Some(d) = delta_us {
                        for o in -3i64..=3 {
                            let mark = match o {
                                0 => "kδ".to_string(),
                                o if o < 0 => format!("(k−{})δ", -o),
                                o => format!("(k+{o})δ"),
                            };
                            let count = u64::try_from(k as i64 + o).unwrap_or(0);
                            s = s.replace(&mark, &delay(count * d));
                        }
                    }
                    if let Some((name, term)) = short {
                        let atomic = !term.contains(' ') || term.starts_with("SR(");
                        let term = if atomic { term.to_string() } else { format!("({term})") };
                        s = replace_word(&s, name, &term);
                    }
                    s
                };
                let (l, r) = (format!("      {}", side(lhs)), format!("    = {}   [", side(rhs)));
                let ok = full.iter().enumerate().filter(|(_, line)| **line == l).any(|(i, _)| {
                    full[i + 1..]
                        .iter()
                        .take_while(|line| !line.starts_with("lemma "))
                        .any(|line| line.starts_with(&r))
                });
                assert!(
                    ok,
                    "{what}: `{segment}` at k = {k}: no lemma\n{l}\n{r}… in the full trace"
                );
                found += 1;
            }
        }
    }
    found
}

/// `2…5, 10` as the counts.
fn counts(text: &str) -> Vec<usize> {
    let mut out = Vec::new();
    for part in text.split(", ") {
        match part.split_once('…') {
            Some((a, b)) => out.extend(a.parse::<usize>().unwrap()..=b.parse::<usize>().unwrap()),
            None => out.push(part.parse().unwrap()),
        }
    }
    out
}

/// `100ms`, `1.5s` in µs.
fn micros(text: &str) -> u64 {
    if let Some(ms) = text.strip_suffix("ms") {
        return ms.parse::<u64>().expect("whole ms") * 1000;
    }
    let s = text.strip_suffix('s').expect("a delay");
    let (whole, frac) = s.split_once('.').unwrap_or((s, ""));
    let frac = format!("{frac:0<6}");
    whole.parse::<u64>().unwrap() * 1_000_000 + frac[..6].parse::<u64>().unwrap()
}

/// A delay as the trace prints it: `900ms`, `1s`, `1.1s`.
fn delay(us: u64) -> String {
    if us < 1_000_000 && us.is_multiple_of(1000) {
        return format!("{}ms", us / 1000);
    }
    let frac = format!("{:06}", us % 1_000_000);
    let frac = frac.trim_end_matches('0');
    if frac.is_empty() {
        format!("{}s", us / 1_000_000)
    } else {
        format!("{}.{frac}s", us / 1_000_000)
    }
}

/// `text` with the word `name` (not part of a longer name) replaced by `by`.
fn replace_word(text: &str, name: &str, by: &str) -> String {
    let word = |c: char| c.is_alphanumeric() || c == '_';
    let mut out = String::new();
    let mut rest = text;
    while let Some(at) = rest.find(name) {
        let before = rest[..at].chars().next_back();
        let after = rest[at + name.len()..].chars().next();
        out.push_str(&rest[..at]);
        if before.is_some_and(word) || after.is_some_and(word) {
            out.push_str(name);
        } else {
            out.push_str(by);
        }
        rest = &rest[at + name.len()..];
    }
    out.push_str(rest);
    out
}

/// The lines a trace prints (a term broken over several lines counts each).
fn printed_lines(lines: &[String]) -> usize {
    lines.iter().map(|l| l.lines().count().max(1)).sum()
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
