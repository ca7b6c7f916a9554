//! Readable unknowns: every unknown's text — in the text report, JSON, JUnit, SARIF and
//! GitHub annotations, with and without `--trace` — stays short (at most 2,000
//! characters, the reason at most 10 lines) on the cases of
//! `tests/data/unknown_programs/readable/` (corpus programs, each `.ii` naming its program
//! on a first line `// program: PATH`), the other unknown cases and the examples.

use crate::common;

use std::path::{Path, PathBuf};
use std::time::Duration;

use ii_prove::report::formats::{self, Format};
use ii_prove::report::text::{Paint, render_property};
use ii_prove::report::{self, Options, PropertyReport, RunReport, Status};

/// The longest an unknown's text may be in any format, in characters.
const MAX_TEXT: usize = 2_000;
/// The most lines an unknown's reason may have.
const MAX_REASON_LINES: usize = 10;
/// The longest an unknown's JSON object may be (its structured candidate included).
const MAX_JSON_OBJECT: usize = 8_000;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn opts(trace: bool) -> Options {
    Options { timeout: Duration::from_millis(500), trace, ..Options::default() }
}

/// The program a `readable/` case names on its first line.
fn program_of(ii: &Path) -> String {
    let text = std::fs::read_to_string(ii).expect("readable");
    let first = text.lines().next().unwrap_or("");
    let rel = first
        .strip_prefix("// program: ")
        .unwrap_or_else(|| panic!("{}: first line `// program: PATH`", ii.display()));
    root().join(rel.trim()).display().to_string()
}

/// Each unknown property's text in every format, as `(format, text)`.
fn texts(run: &RunReport, opts: &Options) -> Vec<(String, Vec<(&'static str, String)>)> {
    let unknown: Vec<&PropertyReport> =
        run.properties.iter().filter(|p| p.status == Status::Unknown).collect();
    let json: serde_json::Value =
        serde_json::from_str(&formats::render(Format::Json, run, opts)).expect("JSON");
    let junit = formats::render(Format::Junit, run, opts);
    let junit = roxmltree::Document::parse(&junit).expect("JUnit XML");
    let sarif: serde_json::Value =
        serde_json::from_str(&formats::render(Format::Sarif, run, opts)).expect("SARIF");
    let mut out = Vec::new();
    for p in unknown {
        let mut each: Vec<(&'static str, String)> = Vec::new();
        each.push(("text", render_property(p, 0, opts, Paint::default())));
        // GitHub: the annotation (the text lines before it are the text report's).
        let github = formats::github_property(p, 0, opts);
        let annotation = github.lines().find(|l| l.starts_with("::")).unwrap_or("");
        let message = annotation.split_once("::").and_then(|(_, r)| r.split_once("::"));
        let message = message.map_or("", |(_, m)| m).replace("%0A", "\n").replace("%25", "%");
        each.push(("github", message));
        let object = json["properties"]
            .as_array()
            .and_then(|ps| ps.iter().find(|q| q["name"] == p.name.as_str()))
            .expect("the property is in the JSON");
        let object_text = object.to_string();
        assert!(
            object_text.chars().count() <= MAX_JSON_OBJECT,
            "{}: JSON object of {} characters",
            p.name,
            object_text.chars().count()
        );
        let mut json_text = object["reason"].as_str().unwrap_or("").to_string();
        for line in object["candidate"]["diagram"].as_array().into_iter().flatten() {
            json_text.push('\n');
            json_text.push_str(line.as_str().unwrap_or(""));
        }
        each.push(("json", json_text));
        let case = junit
            .descendants()
            .find(|n| n.has_tag_name("testcase") && n.attribute("name") == Some(&p.name))
            .expect("a JUnit test case");
        let skipped = case
            .children()
            .find(|n| n.has_tag_name("skipped"))
            .and_then(|n| n.attribute("message"))
            .unwrap_or("");
        let output = case.children().find(|n| n.has_tag_name("system-out")).and_then(|n| n.text());
        each.push(("junit", format!("{skipped}\n{}", output.unwrap_or(""))));
        let result = sarif["runs"][0]["results"]
            .as_array()
            .and_then(|rs| {
                rs.iter().find(|r| {
                    r["ruleId"] == "unknown" && r["properties"]["property"] == p.name.as_str()
                })
            })
            .expect("a SARIF result");
        each.push(("sarif", result["message"]["text"].as_str().unwrap_or("").to_string()));
        let reason = p.reason.as_deref().expect("an unknown has a reason");
        assert!(
            reason.lines().count() <= MAX_REASON_LINES,
            "{}: a reason of {} lines:\n{reason}",
            p.name,
            reason.lines().count()
        );
        out.push((p.name.clone(), each));
    }
    out
}

/// Checks every unknown of `run`; returns how many there were.
fn check(what: &str, run: &RunReport, opts: &Options) -> usize {
    let texts = texts(run, opts);
    for (name, each) in &texts {
        for (format, text) in each {
            let n = text.chars().count();
            assert!(n <= MAX_TEXT, "{what}: {name}: {n} characters in {format}:\n{text}");
        }
    }
    texts.len()
}

#[test]
fn readable_cases_are_unknown_and_short_in_every_format() {
    let dir = root().join("tests/data/unknown_programs/readable");
    let cases = common::files_with(&dir, "ii");
    assert!(!cases.is_empty(), "{} has no case", dir.display());
    let mut unknowns = 0;
    let mut step_diagrams = 0;
    for ii in cases {
        let program = program_of(&ii);
        let name = ii.display().to_string();
        let opts = opts(false);
        let run = report::run_program(&program, std::slice::from_ref(&name), &opts)
            .unwrap_or_else(|e| panic!("{name}: {}", e.rendered));
        for p in &run.properties {
            assert_eq!(p.status, Status::Unknown, "{name}: {} is {:?}", p.name, p.status);
            let reason = p.reason.as_deref().unwrap_or("");
            assert!(reason.contains("algebra: e-graph saturation"), "{name}: {reason}");
            let title = p.candidate.as_ref().and_then(|c| c.title.as_deref());
            if title.is_some_and(|t| t.contains("induction step")) {
                step_diagrams += 1;
                assert!(reason.contains("induction over scans"), "{name}: {reason}");
            }
        }
        unknowns += check(&name, &run, &opts);
    }
    assert!(unknowns >= 10, "only {unknowns} unknowns");
    assert!(step_diagrams >= 1, "no induction step drawn");
}

/// One case of `readable/`, run with a one-second limit: its name, report and options.
fn readable_case(file: &str, trace: bool) -> (String, RunReport, Options) {
    let ii = root().join("tests/data/unknown_programs/readable").join(file);
    let name = ii.display().to_string();
    let opts = opts(trace);
    let run = report::run_program(&program_of(&ii), std::slice::from_ref(&name), &opts)
        .unwrap_or_else(|e| panic!("{name}: {}", e.rendered));
    (name, run, opts)
}

#[test]
fn trace_adds_a_bounded_model() {
    let (name, run, opts) = readable_case("traffic_light_fbd.ii", true);
    assert!(check(&name, &run, &opts) > 0);
    let reason = run.properties[0].reason.as_deref().unwrap_or("");
    assert!(reason.contains("skeleton model ("), "{reason}");
}

/// The state an induction step fails from draws a counter as its value at the two scans
/// (consistent with its bits), not as a row per bit.
#[test]
fn the_induction_step_draws_a_counter_as_its_value() {
    let (_, run, _) = readable_case("count_down.ii", false);
    let p = &run.properties[0];
    assert_eq!(p.status, Status::Unknown, "{:?}", p.status);
    let c = p.candidate.as_ref().expect("a possible counterexample of the step");
    assert!(c.title.as_deref().is_some_and(|t| t.contains("induction step")), "{:?}", c.title);
    let cn = c.integers.iter().find(|i| i.name == "Cn").expect("Cn drawn as a value");
    assert_eq!(cn.values.len(), 2, "{:?}", cn.values);
    let row = c.diagram.iter().find(|l| l.starts_with("Cn ")).expect("a value row for Cn");
    for v in &cn.values {
        assert!(row.contains(&v.to_string()), "{row} lacks {v}");
    }
    assert!(!c.diagram.iter().any(|l| l.starts_with("Cn_b")), "{:?}", c.diagram);
    assert!(!c.signals.iter().any(|s| s.name.starts_with("Cn_b")));
}

#[test]
fn other_unknowns_and_the_examples_stay_short() {
    let opts = opts(false);
    let mut checked = 0;
    for ii in common::files_with(&root().join("tests/data/unknown"), "ii") {
        let name = ii.display().to_string();
        let run = report::run_free(std::slice::from_ref(&name), &opts)
            .unwrap_or_else(|e| panic!("{name}: {}", e.rendered));
        checked += check(&name, &run, &opts);
    }
    let folders = ["tests/data/unknown_programs", "examples"];
    for folder in folders {
        let dir = root().join(folder);
        for ii in common::files_with(&dir, "ii").into_iter().filter(|p| p.parent() == Some(&dir)) {
            let Some(program) =
                ["ld", "xml"].iter().map(|ext| ii.with_extension(ext)).find(|p| p.exists())
            else {
                continue;
            };
            let name = ii.display().to_string();
            let run = report::run_program(
                &program.display().to_string(),
                std::slice::from_ref(&name),
                &opts,
            )
            .unwrap_or_else(|e| panic!("{name}: {}", e.rendered));
            checked += check(&name, &run, &opts);
        }
    }
    assert!(checked >= 3, "only {checked} unknowns among the other cases");
}

#[test]
fn a_diagram_cut_to_a_width_keeps_the_mark_and_the_last_pieces() {
    use ii_prove::report::waveform::{Glyphs, draw, draw_within};
    use ii_prove::semantics::{Signal, Time};
    let t = |n: i64| Time::from_integer(n.into());
    // 1 on [2k, 2k+1), 0 on [2k+1, 2k+2): sixty pieces.
    let toggling = Signal::from_fn(t(60), (1..60).map(t).collect(), |x| {
        (x / t(2)).floor() * t(2) == x.floor()
    });
    let shown = vec![("toggling".to_string(), toggling)];
    let whole = draw(&shown, Some(&t(60)), Glyphs::ASCII);
    assert!(whole[0].chars().count() > 300);
    let cut = draw_within(&shown, Some(&t(60)), Glyphs::ASCII, 96);
    assert!(cut.iter().all(|row| row.chars().count() <= 96), "{cut:#?}");
    assert!(cut[1].ends_with("60"), "{cut:#?}");
    assert!(cut[2].ends_with('^'), "{cut:#?}");
}

/// Every program of `examples/` and of the corpus (`tests/data/ldmicro/corpus`,
/// `tests/data/plcopen/corpus`) that loads, with generated properties over its written
/// bits (outputs and relays, else the other bits it computes: `o1 ⇒ o2`, `o1 · o2 = 0*`
/// for neighbours in name order, at most four; `o ⇒ pre o` for a single one), under `--trace` (whose reason is a line longer): each unknown's
/// text is short in every format. `--nocapture` prints the figures.
#[test]
fn unknowns_of_every_example_and_corpus_program_stay_short() {
    use ii_prove::diag::Sources;
    use ii_prove::ladder::SignalKind;
    use ii_prove::syntax::print::name_to_string;
    let opts = Options { jobs: 2, ..opts(true) };
    let mut files = Vec::new();
    for ext in ["ld", "xml", "st", "il"] {
        files.extend(common::files_with(&root().join("examples"), ext));
    }
    files.extend(common::files_with(&root().join("tests/data/ldmicro/corpus"), "ld"));
    files.extend(common::files_with(&root().join("tests/data/plcopen/corpus"), "xml"));
    let dir = std::env::temp_dir().join(format!("ii-prove-unknowns-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    let (mut programs, mut refused, mut silent, mut properties, mut unknowns) = (0, 0, 0, 0, 0);
    let mut longest: (usize, String) = (0, String::new());
    for path in &files {
        let shown = path.display().to_string();
        let mut sources = Sources::new();
        let Ok(loaded) = report::load_program(&mut sources, &shown, &Default::default()) else {
            refused += 1;
            continue;
        };
        // Outputs and relays; without two of them, the other bits the program computes.
        let of = |pick: fn(&SignalKind) -> bool| -> Vec<&String> {
            loaded.compiled.signals.iter().filter(|(_, k)| pick(k)).map(|(n, _)| n).collect()
        };
        let mut written = of(|k| matches!(k, SignalKind::Output | SignalKind::Relay));
        if written.len() < 2 {
            written.extend(of(|k| {
                matches!(
                    k,
                    SignalKind::Intermediate { .. }
                        | SignalKind::EdgeMemory { .. }
                        | SignalKind::IntBit { input: false, .. }
                )
            }));
        }
        let mut text = String::new();
        for (i, pair) in written.windows(2).take(2).enumerate() {
            let (a, b) = (name_to_string(pair[0]), name_to_string(pair[1]));
            text.push_str(&format!("property implies_{i}: {a} => {b}\n"));
            text.push_str(&format!("property exclusive_{i}: {a} . {b} = 0*\n"));
        }
        if let [only] = written[..] {
            let o = name_to_string(only);
            text.push_str(&format!("property kept: {o} => pre {o}\n"));
        }
        if text.is_empty() {
            silent += 1;
            continue;
        }
        programs += 1;
        let ii = dir.join(format!("p{programs}.ii"));
        std::fs::write(&ii, &text).expect("writable");
        let ii = ii.display().to_string();
        let run = match report::run_program(&shown, std::slice::from_ref(&ii), &opts) {
            Ok(run) => run,
            Err(e) => panic!("{shown} with\n{text}: {}", e.rendered),
        };
        properties += run.properties.len();
        for (name, each) in texts(&run, &opts) {
            unknowns += 1;
            for (format, t) in each {
                let n = t.chars().count();
                if n > longest.0 {
                    longest = (n, format!("{shown}: {name} in {format}"));
                }
                assert!(n <= MAX_TEXT, "{shown}: {name}: {n} characters in {format}:\n{t}");
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    println!(
        "{} files: {programs} programs with written bits, {silent} without, {refused} refused; {properties} properties, {unknowns} unknown; longest unknown text {} characters ({})",
        files.len(),
        longest.0,
        longest.1
    );
    assert!(unknowns >= 20, "only {unknowns} unknowns");
}
