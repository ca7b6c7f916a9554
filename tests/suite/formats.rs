//! The reports for CI end to end, each read back by a real parser: JUnit XML (roxmltree),
//! SARIF 2.1.0 (validated against the official schema), GitHub Actions workflow
//! commands, JSON; locations of properties and warnings; `--only`, `--deny vacuous`,
//! `-q`, `--color`.

use std::process::{Command, Output};

fn ii_prove(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_ii-prove"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .env_remove("NO_COLOR")
        .output()
        .expect("the binary runs")
}

fn text(out: &[u8]) -> String {
    String::from_utf8_lossy(out).into_owned()
}

/// The faulty water plant: P2 refuted (line 14 of water.ii), the rest proved.
const FAULTY: &[&str] = &["examples/water_faulty.ld", "examples/water.ii", "--timeout", "3s"];
/// A program with a counter (a warning at its rung) and a property that stays unknown.
const QUOTIENT: &[&str] = &[
    "tests/data/unknown_programs/quotient_never_done.ld",
    "tests/data/unknown_programs/quotient_never_done.ii",
    "--timeout",
    "2s",
];
/// A property that holds only vacuously.
const VACUOUS: &[&str] = &[
    "tests/data/refutes_programs/traffic_greens_overlap.ld",
    "tests/data/vacuity/forces_constant.ii",
];

fn with(base: &[&str], more: &[&str]) -> Vec<String> {
    base.iter().chain(more).map(|s| s.to_string()).collect()
}

fn run(base: &[&str], more: &[&str]) -> Output {
    let args = with(base, more);
    ii_prove(&args.iter().map(String::as_str).collect::<Vec<_>>())
}

#[test]
fn junit_has_a_test_case_per_property_and_a_failure_with_the_counterexample() {
    let out = run(FAULTY, &["--format", "junit"]);
    assert_eq!(out.status.code(), Some(1));
    let xml = text(&out.stdout);
    let doc = roxmltree::Document::parse(&xml).expect("well-formed XML");
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "testsuites");
    let cases: Vec<_> = root.descendants().filter(|n| n.has_tag_name("testcase")).collect();
    let json: serde_json::Value =
        serde_json::from_slice(&run(FAULTY, &["--format", "json"]).stdout).unwrap();
    let props = json["properties"].as_array().unwrap();
    assert_eq!(cases.len(), props.len());
    assert_eq!(root.attribute("tests"), Some(props.len().to_string().as_str()));
    assert_eq!(root.attribute("failures"), Some("1"));
    for (case, p) in cases.iter().zip(props) {
        assert_eq!(case.attribute("name"), p["name"].as_str());
        assert_eq!(case.attribute("file"), Some("examples/water.ii"));
        assert_eq!(case.attribute("line"), Some(p["location"]["line"].to_string().as_str()));
    }
    let p2 = cases.iter().find(|c| c.attribute("name") == Some("P2")).unwrap();
    assert_eq!(p2.attribute("line"), Some("14"));
    let failure = p2.children().find(|n| n.has_tag_name("failure")).expect("a failure");
    assert_eq!(failure.attribute("type"), Some("refuted"));
    let body = failure.text().unwrap_or("");
    assert!(body.contains("counterexample: at t =") && body.contains("L2_up"), "{body}");
    let p1 = cases.iter().find(|c| c.attribute("name") == Some("P1a")).unwrap();
    assert!(p1.children().all(|n| !n.is_element()), "a proved property has no child");
}

#[test]
fn junit_skips_unknown_properties_and_carries_the_warnings() {
    let out = run(QUOTIENT, &["--format", "junit"]);
    assert_eq!(out.status.code(), Some(1));
    let xml = text(&out.stdout);
    let doc = roxmltree::Document::parse(&xml).expect("well-formed XML");
    let skipped: Vec<_> = doc.descendants().filter(|n| n.has_tag_name("skipped")).collect();
    assert!(!skipped.is_empty(), "{xml}");
    assert!(skipped[0].attribute("message").unwrap().contains("unknown"));
    assert_eq!(doc.root_element().attribute("skipped"), Some(skipped.len().to_string().as_str()));
    let err = doc.descendants().find(|n| n.has_tag_name("system-err")).expect("warnings");
    assert!(err.text().unwrap().contains("quotient_never_done.ld:"), "{xml}");
}

fn sarif_validator() -> jsonschema::Validator {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/sarif-schema-2.1.0.json");
    let schema: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    jsonschema::validator_for(&schema).expect("the SARIF schema compiles")
}

fn valid_sarif(out: &Output) -> serde_json::Value {
    let sarif: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let validator = sarif_validator();
    let errors: Vec<String> = validator.iter_errors(&sarif).map(|e| e.to_string()).collect();
    assert!(errors.is_empty(), "not SARIF 2.1.0: {errors:?}");
    assert_eq!(sarif["version"], "2.1.0");
    sarif
}

#[test]
fn the_schema_refuses_what_is_not_sarif() {
    let validator = sarif_validator();
    let bad = serde_json::json!({"version": "2.1.0", "runs": [{"results": []}]});
    assert!(!validator.is_valid(&bad), "a run without `tool` is not SARIF");
}

#[test]
fn sarif_has_a_located_result_per_refuted_property() {
    let out = run(FAULTY, &["--format", "sarif"]);
    assert_eq!(out.status.code(), Some(1));
    let sarif = valid_sarif(&out);
    let results = sarif["runs"][0]["results"].as_array().unwrap();
    assert_eq!(results.len(), 1, "{results:?}");
    let r = &results[0];
    assert_eq!(r["ruleId"], "refuted");
    assert_eq!(r["level"], "error");
    let at = &r["locations"][0]["physicalLocation"];
    assert_eq!(at["artifactLocation"]["uri"], "examples/water.ii");
    assert_eq!(at["region"]["startLine"], 14);
    assert_eq!(at["region"]["startColumn"], 1);
    assert!(r["message"]["text"].as_str().unwrap().contains("counterexample"));
}

#[test]
fn sarif_reports_unknown_properties_and_warnings_in_the_program() {
    let out = run(QUOTIENT, &["--format", "sarif"]);
    let sarif = valid_sarif(&out);
    let results = sarif["runs"][0]["results"].as_array().unwrap();
    assert!(results.iter().any(|r| r["ruleId"] == "unknown" && r["level"] == "warning"));
    let warning = results.iter().find(|r| r["ruleId"] == "input-warning").expect("a warning");
    let at = &warning["locations"][0]["physicalLocation"];
    assert_eq!(at["artifactLocation"]["uri"], "tests/data/unknown_programs/quotient_never_done.ld");
    assert!(at["region"]["startLine"].as_u64().unwrap() > 1);
}

#[test]
fn github_annotations_point_at_the_property() {
    let out = run(FAULTY, &["--format", "github"]);
    assert_eq!(out.status.code(), Some(1));
    let stdout = text(&out.stdout);
    let error = stdout.lines().find(|l| l.starts_with("::error ")).expect("an annotation");
    assert!(
        error.starts_with("::error file=examples/water.ii,line=14,col=1,title=P2 refuted::"),
        "{error}"
    );
    // A workflow command is one line: the diagram's lines are escaped.
    assert!(error.contains("%0A"), "{error}");
    // Where it fails, as the text report says it, before the diagram.
    let json: serde_json::Value =
        serde_json::from_slice(&run(FAULTY, &["--format", "json"]).stdout).unwrap();
    let p2 = json["properties"].as_array().unwrap().iter().find(|p| p["name"] == "P2").unwrap();
    let at = format!("at t = {} s", p2["counterexample"]["time"].as_str().unwrap());
    assert!(error.contains(&format!("counterexample: {at}")), "{error}");
    assert!(error.contains("confirmed by exact evaluation and by the scan simulator"), "{error}");
    assert_eq!(stdout.lines().filter(|l| l.starts_with("::")).count(), 1, "{stdout}");
    let warned = run(QUOTIENT, &["--format", "github"]);
    let stdout = text(&warned.stdout);
    assert!(
        stdout.lines().any(|l| l.starts_with(
            "::warning file=tests/data/unknown_programs/quotient_never_done.ld,line="
        )),
        "{stdout}"
    );
    assert!(stdout.lines().any(|l| l.starts_with("::warning ") && l.contains("unknown")));
}

#[test]
fn json_locates_every_property_and_warning() {
    let out = run(QUOTIENT, &["--json"]);
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    for p in json["properties"].as_array().unwrap() {
        assert_eq!(p["location"]["file"], "tests/data/unknown_programs/quotient_never_done.ii");
        assert!(p["location"]["line"].as_u64().unwrap() >= 1);
        assert!(p["location"]["column"].as_u64().unwrap() >= 1);
    }
    let w = &json["warnings"][0];
    assert!(w["message"].as_str().unwrap().contains("rung"), "{w}");
    assert!(w["location"]["file"].as_str().unwrap().ends_with("quotient_never_done.ld"));
    // `--json` is `--format json`, and the two cannot be mixed.
    let same = run(QUOTIENT, &["--format", "json"]);
    let again: serde_json::Value = serde_json::from_slice(&same.stdout).unwrap();
    assert_eq!(again["properties"][0]["location"], json["properties"][0]["location"]);
    assert_eq!(run(QUOTIENT, &["--json", "--format", "sarif"]).status.code(), Some(2));
}

#[test]
fn text_locates_every_property() {
    let out = ii_prove(&["examples/water.ld", "examples/water.ii"]);
    let stdout = text(&out.stdout);
    let p2 = stdout.lines().find(|l| l.starts_with("P2 ")).unwrap();
    assert!(p2.ends_with("(examples/water.ii:14:1)"), "{p2}");
}

#[test]
fn only_selects_properties_by_substring_or_pattern() {
    let out = ii_prove(&["examples/water.ld", "examples/water.ii", "--only", "P1"]);
    assert_eq!(out.status.code(), Some(0));
    let names: Vec<String> = text(&out.stdout)
        .lines()
        .filter(|l| l.contains(" proved "))
        .map(|l| l.split_whitespace().next().unwrap().to_string())
        .collect();
    assert_eq!(names, ["P1a", "P1b"]);
    let out = ii_prove(&[
        "examples/water_faulty.ld",
        "examples/water.ii",
        "--only",
        "P4?",
        "--only",
        "P3",
    ]);
    assert_eq!(out.status.code(), Some(0), "P2, the refuted one, is not run");
    assert!(text(&out.stdout).contains("3 proved, 0 refuted, 0 unknown"));
    let none = ii_prove(&["examples/water.ld", "examples/water.ii", "--only", "Nothing*"]);
    assert_eq!(none.status.code(), Some(2));
    let stderr = text(&none.stderr);
    assert!(stderr.contains("no property matches") && stderr.contains("P1a"), "{stderr}");
}

#[test]
fn deny_vacuous_fails_the_run_and_the_summary_counts_vacuous_proofs() {
    let out = run(VACUOUS, &[]);
    assert_eq!(out.status.code(), Some(0));
    assert!(text(&out.stdout).contains("1 proved (1 vacuous), 0 refuted, 0 unknown"));
    let denied = run(VACUOUS, &["--deny", "vacuous"]);
    assert_eq!(denied.status.code(), Some(1));
    let json: serde_json::Value =
        serde_json::from_slice(&run(VACUOUS, &["--json"]).stdout).unwrap();
    assert_eq!(json["summary"]["vacuous"], 1);
    let junit = text(&run(VACUOUS, &["--format", "junit", "--deny", "vacuous"]).stdout);
    let doc = roxmltree::Document::parse(&junit).unwrap();
    let failure = doc.descendants().find(|n| n.has_tag_name("failure")).expect("a failure");
    assert_eq!(failure.attribute("type"), Some("vacuous"));
}

#[test]
fn warnings_go_to_standard_error_and_q_silences_them() {
    let out = run(QUOTIENT, &[]);
    let (stdout, stderr) = (text(&out.stdout), text(&out.stderr));
    assert!(stderr.contains("warning: tests/data/unknown_programs/quotient_never_done.ld:"));
    assert!(!stdout.contains("warning: tests/"), "{stdout}");
    let quiet = run(QUOTIENT, &["-q"]);
    assert!(!text(&quiet.stderr).contains("warning:"), "{}", text(&quiet.stderr));
    assert_eq!(text(&quiet.stdout).lines().last(), stdout.lines().last());
}

#[test]
fn color_is_used_only_when_asked_or_on_a_terminal() {
    let always = ii_prove(&["examples/water.ld", "examples/water.ii", "--color", "always"]);
    assert!(text(&always.stdout).contains("\x1b["));
    for when in ["never", "auto"] {
        let out = ii_prove(&["examples/water.ld", "examples/water.ii", "--color", when]);
        assert!(!text(&out.stdout).contains('\x1b'), "--color {when} on a pipe");
    }
    let json = ii_prove(&["examples/water.ld", "examples/water.ii", "--color", "always", "--json"]);
    assert!(!text(&json.stdout).contains('\x1b'), "no colour in JSON");
}
