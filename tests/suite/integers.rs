//! Integers of LDmicro programs: counters, comparisons and arithmetic compiled exactly (their bits), comparison atoms `[Cparts >= 10]` in properties, the parts example proved and its faulty variant refuted with the count shown, and comparisons that do not fit the program refused with located errors.

use crate::common;

use common::{ii_prove, text, verdicts};

#[test]
fn the_parts_example_is_proved() {
    let got = verdicts(&["examples/parts.ld", "examples/parts.ii"]);
    assert_eq!(got.len(), 4, "{got:?}");
    assert!(got.iter().all(|(_, v)| v == "proved"), "{got:?}");
    // `show` names the counter's bits (one byte, as LDmicro sizes a counter with limit
    // 10), and no element is left unconstrained.
    let out = ii_prove(&["show", "examples/parts.ld"]);
    let shown = text(&out.stdout);
    assert!(shown.contains("Cparts_b0") && shown.contains("Cparts_b7"), "{shown}");
    assert!(!shown.contains("Cparts_b8"), "{shown}");
    assert!(!shown.contains("unconstrained"), "{shown}");
    assert!(!shown.contains("// warning"), "{shown}");
}

#[test]
fn the_faulty_parts_counter_is_refuted_with_the_count_in_the_diagram() {
    let out = ii_prove(&["examples/parts_faulty.ld", "examples/parts.ii"]);
    assert_eq!(out.status.code(), Some(1));
    let report = text(&out.stdout);
    let room = report.split("\nNonnegative").next().unwrap_or("");
    assert!(room.contains("Room") && room.contains("refuted"), "{report}");
    assert!(room.contains("confirmed by exact evaluation and by the scan simulator"), "{report}");
    // The count as a value row: every value from 1 to 10, in order.
    let row = room.lines().find(|l| l.trim_start().starts_with("Cparts ")).expect("a value row");
    let values: Vec<i64> =
        row.split_whitespace().skip(1).map(|v| v.parse().expect("a number")).collect();
    assert_eq!(values, (1..=10).collect::<Vec<_>>(), "{row}");
    // The counter's bits are not drawn one by one.
    assert!(!room.contains("Cparts_b"), "{report}");
    // JSON: the count at every scan, reaching 10 at the violating scan.
    let out = ii_prove(&["examples/parts_faulty.ld", "examples/parts.ii", "--json"]);
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let room = json["properties"].as_array().unwrap().iter().find(|p| p["name"] == "Room").unwrap();
    let c = &room["counterexample"];
    let ints = c["integers"].as_array().expect("integers");
    let count = ints.iter().find(|i| i["name"] == "Cparts").expect("Cparts");
    let values: Vec<i64> =
        count["values"].as_array().unwrap().iter().map(|v| v.as_i64().unwrap()).collect();
    let scan = c["scan"].as_u64().unwrap() as usize;
    assert_eq!(values.len(), scan, "{values:?}");
    assert_eq!(values.last(), Some(&10), "{values:?}");
    assert!(values.windows(2).all(|w| w[1] == w[0] || w[1] == w[0] + 1), "{values:?}");
}

/// Every `refused_comparisons/NAME.ii` (about `counter.ld` there) writes a comparison
/// that does not fit the program's integers: exit 2, nothing proved, and the error names
/// the place, the reason and a hint (every line of `NAME.expected`).
#[test]
fn comparisons_that_do_not_fit_are_refused_with_a_located_error() {
    let dir =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/refused_comparisons");
    let program = dir.join("counter.ld");
    let files = common::files_with(&dir, "ii");
    assert!(files.len() >= 4, "only {} cases", files.len());
    for ii in files {
        let expected = std::fs::read_to_string(ii.with_extension("expected"))
            .unwrap_or_else(|_| panic!("{} has no .expected file", ii.display()));
        let out = ii_prove(&[
            "--color",
            "never",
            program.to_str().expect("utf-8"),
            ii.to_str().expect("utf-8"),
        ]);
        let shown = ii.display();
        let err = text(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{shown}: {err}");
        assert!(out.stdout.is_empty(), "{shown}: {}", text(&out.stdout));
        assert!(err.contains('^'), "{shown}: no caret in\n{err}");
        for fragment in expected.lines().filter(|l| !l.trim().is_empty()) {
            assert!(err.contains(fragment), "{shown}: expected `{fragment}` in\n{err}");
        }
    }
}

/// Without a program there are no integers to compare.
#[test]
fn a_comparison_needs_a_program() {
    let dir = tempfile::tempdir().expect("a temporary folder");
    let ii = dir.path().join("free.ii");
    std::fs::write(&ii, "input a\nproperty A: a => [x > 1]\n").expect("written");
    let out = ii_prove(&[ii.to_str().expect("utf-8")]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("there is no program here"), "{}", text(&out.stderr));
}
