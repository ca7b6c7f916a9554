//! The command line end to end: exit codes in both modes, `show`, `axioms`, JSON, and the
//! length of the water plant's proofs against the paper's.

use std::path::Path;
use std::process::{Command, Output};

use ii_prove::report::{self, Options, Status};

fn ii_prove(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_ii-prove"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the binary runs")
}

fn text(out: &[u8]) -> String {
    String::from_utf8_lossy(out).into_owned()
}

#[test]
fn free_mode_exit_0_when_everything_is_proved() {
    let out = ii_prove(&["tests/data/proves/derived_timer_laws.ii"]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(text(&out.stdout).contains("11 proved, 0 refuted, 0 unknown"));
}

#[test]
fn free_mode_exit_1_when_something_is_refuted() {
    let out = ii_prove(&["tests/data/refutes/paper_false_forms.ii", "--ascii"]);
    assert_eq!(out.status.code(), Some(1));
    let stdout = text(&out.stdout);
    assert!(stdout.contains("refuted") && stdout.contains("counterexample: at t ="), "{stdout}");
}

#[test]
fn free_mode_exit_2_on_bad_input_with_a_located_error() {
    let dir = std::env::temp_dir().join(format!("ii-prove-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.ii");
    std::fs::write(&bad, "input f\nproperty P: f => L1_pmup\n").unwrap();
    let out = ii_prove(&[bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = text(&out.stderr);
    assert!(stderr.contains("bad.ii:2:") && stderr.contains('^'), "{stderr}");
    assert!(out.stdout.is_empty(), "nothing is reported from bad input");
    let missing = ii_prove(&["no/such/file.ii"]);
    assert_eq!(missing.status.code(), Some(2));
    assert_eq!(ii_prove(&[]).status.code(), Some(2));
    assert_eq!(ii_prove(&["--timeout", "-1", "x.ii"]).status.code(), Some(2));
}

#[test]
fn program_mode_exit_0_on_the_water_plant() {
    let out = ii_prove(&["examples/water.ld", "examples/water.ii"]);
    assert_eq!(out.status.code(), Some(0), "{}{}", text(&out.stdout), text(&out.stderr));
}

#[test]
fn program_mode_exit_1_on_the_faulty_plant_which_still_proves_the_rest() {
    let out = ii_prove(&["examples/water_faulty.ld", "examples/water.ii", "--timeout", "3"]);
    assert_eq!(out.status.code(), Some(1));
    let stdout = text(&out.stdout);
    let p2 = stdout.lines().find(|l| l.starts_with("P2 ")).expect("a line for P2");
    assert!(!p2.contains("proved"), "{p2}");
    for name in ["P1a", "P1b", "P3", "P4a", "P4b"] {
        let line = stdout.lines().find(|l| l.starts_with(&format!("{name} "))).unwrap();
        assert!(line.contains("proved"), "{line}");
    }
}

#[test]
fn program_mode_exit_2_on_a_malformed_ladder_file() {
    let out = ii_prove(&["tests/data/ldmicro/parse_err/unknown_keyword.ld", "examples/water.ii"]);
    let code = out.status.code();
    assert_eq!(code, Some(2), "{}", text(&out.stderr));
    assert!(text(&out.stderr).contains("unknown_keyword.ld:"));
}

#[test]
fn show_prints_text_that_parses_back() {
    let out = ii_prove(&["show", "examples/water.ld"]);
    assert_eq!(out.status.code(), Some(0));
    let shown = text(&out.stdout);
    assert!(shown.contains("assume L06a: YL1_pump = 5s/RL1_Prod"), "{shown}");
    let dir = std::env::temp_dir().join(format!("ii-prove-show-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("water_show.ii");
    std::fs::write(&file, format!("{shown}\nproperty P1a: YL1_pump => 5s/YL1_up\n")).unwrap();
    let again = ii_prove(&[file.to_str().unwrap()]);
    assert_eq!(again.status.code(), Some(0), "{}", text(&again.stderr));
}

#[test]
fn axioms_lists_every_law_of_the_registry() {
    let out = ii_prove(&["axioms"]);
    assert_eq!(out.status.code(), Some(0));
    let mut sources = ii_prove::diag::Sources::new();
    let theory = ii_prove::theory::standard(&mut sources).unwrap();
    let listed = text(&out.stdout);
    for law in &theory.laws {
        assert!(listed.contains(&law.axiom.name), "{} is not listed", law.axiom.name);
    }
    assert!(listed.contains(&format!("{} laws", theory.laws.len())));
}

#[test]
fn json_output_follows_the_schema() {
    let out = ii_prove(&["examples/water.ld", "examples/water.ii", "--json", "--trace"]);
    assert_eq!(out.status.code(), Some(0));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).expect("valid JSON");
    assert_eq!(v["program"], "examples/water.ld");
    let props = v["properties"].as_array().unwrap();
    assert!(props.iter().all(|p| p["status"] == "proved"));
    let p1 = &props[0];
    assert_eq!(p1["name"], "P1a");
    assert!(p1["trace"]["steps"].as_array().unwrap().iter().all(|s| s["rule"].is_string()));
    assert_eq!(v["summary"]["proved"], props.len());
}

/// The paper's proofs (water.md) are 3, 8 and 6 lines; ours may be at most 2 longer.
#[test]
fn water_proofs_are_no_longer_than_the_papers_plus_two() {
    let bars = [("P1a", 3), ("P1b", 3), ("P2", 8), ("Fig9", 6)];
    let opts = Options::default();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let relations = root.join("tests/data/proves/water_paper.ii").display().to_string();
    let free = report::run_free(&[relations], &opts).unwrap_or_else(|e| panic!("{}", e.rendered));
    let program = report::run_program(
        &root.join("examples/water.ld").display().to_string(),
        &[root.join("examples/water.ii").display().to_string()],
        &opts,
    )
    .unwrap_or_else(|e| panic!("{}", e.rendered));
    for run in [free, program] {
        for (name, bar) in bars {
            let p = run.properties.iter().find(|p| p.name == name).expect("the property");
            assert_eq!(p.status, Status::Proved, "{name}");
            let trace = p.trace.as_ref().unwrap();
            assert!(
                trace.length <= bar + 2,
                "{name}: {} lines\n{}",
                trace.length,
                trace.lines.join("\n")
            );
        }
    }
}
