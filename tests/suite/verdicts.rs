//! The verdict harness: every `.ii` file under `tests/data/<verdict>/` is run through
//! `ii-prove FILE.ii` mode, and each property must end with the folder's verdict.
//! A new case is a new file. In `proves/`, a comment `// trace: at most N lines`
//! right above a property bounds the length of its printed proof.

use crate::common;

use std::path::{Path, PathBuf};
use std::time::Duration;

use ii_prove::report::{self, Options, Status};

fn files(verdict: &str) -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data").join(verdict);
    let out = common::files_with(&dir, "ii");
    assert!(!out.is_empty(), "{} has no case", dir.display());
    out
}

fn check_folder(verdict: &str, expected: Status, timeout: Duration) {
    let opts = Options { timeout, ..Options::default() };
    let mut checked = 0;
    for path in files(verdict) {
        let name = path.display().to_string();
        let run = report::run_free(std::slice::from_ref(&name), &opts)
            .unwrap_or_else(|e| panic!("{name} does not load:\n{}", e.rendered));
        assert!(!run.properties.is_empty(), "{name} has no property");
        let bounds = common::trace_bounds(&std::fs::read_to_string(&path).expect("readable"));
        for p in &run.properties {
            assert_eq!(p.status, expected, "{name}: {} is {:?} ({:?})", p.name, p.status, p.reason);
            match expected {
                Status::Proved => {
                    let trace = p.trace.as_ref().expect("a proved property has a trace");
                    assert!(!p.vacuous, "{name}: {} flagged vacuous: {:?}", p.name, p.vacuity);
                    assert!(
                        !trace.steps.is_empty() || trace.lines.len() <= 2,
                        "{}: empty proof",
                        p.name
                    );
                    if let Some(&bound) = bounds.get(&p.name) {
                        assert!(
                            trace.length <= bound,
                            "{name}: the proof of {} has {} lines, at most {bound} expected:\n{}",
                            p.name,
                            trace.length,
                            trace.lines.join("\n")
                        );
                    }
                }
                Status::Refuted => {
                    assert!(p.counterexample.is_some(), "{}: refuted without a witness", p.name)
                }
                Status::Unknown => {
                    assert!(p.reason.is_some(), "{}: unknown without a reason", p.name)
                }
            }
            checked += 1;
        }
    }
    assert!(checked > 0, "no property in tests/data/{verdict}");
}

#[test]
fn proves() {
    check_folder("proves", Status::Proved, Duration::from_secs(20));
}

/// Every property of `tests/data/vacuous_free/` is proved and flagged vacuous: the
/// assumptions contradict each other or force a signal it reads to a constant.
#[test]
fn vacuous_free() {
    let opts = Options { timeout: Duration::from_secs(20), ..Options::default() };
    for path in files("vacuous_free") {
        let name = path.display().to_string();
        let run = report::run_free(std::slice::from_ref(&name), &opts)
            .unwrap_or_else(|e| panic!("{name} does not load:\n{}", e.rendered));
        assert!(!run.properties.is_empty(), "{name} has no property");
        for p in &run.properties {
            assert_eq!(p.status, Status::Proved, "{name}: {} ({:?})", p.name, p.reason);
            assert!(p.vacuous, "{name}: {} not flagged vacuous", p.name);
            assert!(p.vacuity.as_deref().is_some_and(|w| w.contains("vacuous")), "{:?}", p.vacuity);
        }
    }
}

/// Each file is its own theory: an `assume` of one file is no hypothesis of another
/// file's properties in the same run, whatever the order.
#[test]
fn assumptions_stay_in_their_file() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let with = data.join("proves/assumed_equal.ii").display().to_string();
    let without = data.join("refutes/not_assumed.ii").display().to_string();
    let opts = Options { timeout: Duration::from_secs(20), ..Options::default() };
    for files in [[with.clone(), without.clone()], [without.clone(), with.clone()]] {
        let run = report::run_free(&files, &opts).unwrap_or_else(|e| panic!("{}", e.rendered));
        for p in &run.properties {
            let expected = if p.name.ends_with("without_assumption") {
                Status::Refuted
            } else {
                Status::Proved
            };
            assert_eq!(p.status, expected, "{files:?}: {}", p.name);
        }
        assert_eq!(run.properties.len(), 4);
    }
}

#[test]
fn refutes() {
    check_folder("refutes", Status::Refuted, Duration::from_secs(20));
}

#[test]
fn unknown() {
    // A short limit: these end when the limits are reached.
    check_folder("unknown", Status::Unknown, Duration::from_secs(2));
}
