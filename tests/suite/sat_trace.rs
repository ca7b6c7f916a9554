//! The SAT trace (`II_PROVE_SAT_TRACE`): a run with it records every query, and each recorded instance replayed in a fresh solver gives the answers the run got.

use std::path::Path;
use std::process::Command;

use varisat::{ExtendFormula, Lit, Solver};

/// Replays one trace; the number of solves, and the first answer that differs.
fn replay(text: &str) -> (usize, Option<String>) {
    let mut solver = Solver::new();
    let mut assumptions: Vec<Lit> = Vec::new();
    let mut solves = 0;
    let lits = |line: &str| -> Vec<Lit> {
        line.split_whitespace()
            .filter_map(|w| w.parse::<isize>().ok())
            .filter(|&v| v != 0)
            .map(Lit::from_dimacs)
            .collect()
    };
    for line in text.lines() {
        if line.starts_with("c ") {
            continue;
        } else if let Some(rest) = line.strip_prefix("a ") {
            assumptions = lits(rest);
        } else if let Some(rest) = line.strip_prefix("r ") {
            solves += 1;
            solver.assume(&assumptions);
            let got = match solver.solve() {
                Ok(true) => "sat",
                Ok(false) => "unsat",
                Err(_) => "error",
            };
            let recorded = rest.split_whitespace().next().unwrap_or("");
            if got != recorded {
                return (solves, Some(format!("solve {solves}: {got}, recorded {recorded}")));
            }
            let secs: f64 = rest.split_whitespace().nth(1).and_then(|t| t.parse().ok()).unwrap();
            assert!(secs >= 0.0, "{rest}");
        } else {
            assert!(line.ends_with(" 0") || line == "0", "a clause ends with 0: {line}");
            solver.add_clause(&lits(line));
        }
    }
    (solves, None)
}

/// Runs ii-prove on `program` and `properties` with the trace in `dir`; its exit status.
fn traced(program: &Path, properties: &Path, dir: &Path) -> Option<i32> {
    let out = Command::new(env!("CARGO_BIN_EXE_ii-prove"))
        .arg(program)
        .arg(properties)
        .env("II_PROVE_SAT_TRACE", dir)
        .output()
        .unwrap();
    eprint!("{}", String::from_utf8_lossy(&out.stderr));
    out.status.code()
}

#[test]
fn a_traced_run_records_queries_that_replay_to_the_same_answers() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = std::env::temp_dir().join(format!("ii-prove-sat-trace-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    // A refuted property: bounded model checking.
    let refutes = root.join("tests/data/refutes_programs");
    let status = traced(&refutes.join("lamp_short.ld"), &refutes.join("lamp_short.ii"), &dir);
    assert_eq!(status, Some(1));
    // Proved properties whose proof is a propositional refutation with a DRAT proof (a
    // solver that must never be given assumptions) and case splits.
    let proves = root.join("tests/data/proves_programs");
    let (program, properties) =
        (proves.join("var_timer_delay_range.ld"), proves.join("var_timer_delay_range.ii"));
    assert_eq!(traced(&program, &properties, &dir), Some(0));
    let mut kinds = std::collections::BTreeSet::new();
    let mut solves = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        let kind = text.lines().next().and_then(|l| l.strip_prefix("c kind ")).unwrap();
        kinds.insert(kind.to_string());
        let (n, differs) = replay(&text);
        assert_eq!(differs, None, "{}", path.display());
        solves += n;
    }
    for kind in ["bmc", "refute", "split"] {
        assert!(kinds.contains(kind), "no {kind} query recorded: {kinds:?}");
    }
    assert!(solves > 0, "no solve recorded");
    // Without the variable nothing is written.
    let quiet = dir.join("quiet");
    std::fs::create_dir_all(&quiet).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_ii-prove"))
        .arg(refutes.join("lamp_short.ld"))
        .arg(refutes.join("lamp_short.ii"))
        .env_remove("II_PROVE_SAT_TRACE")
        .current_dir(&quiet)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(std::fs::read_dir(&quiet).unwrap().count(), 0);
    let _ = std::fs::remove_dir_all(&dir);
}
