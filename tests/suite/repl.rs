//! REPL sessions as transcripts: `tests/repl/*.session` interleave commands (`> `, with
//! continuation lines after `… `) and the exact expected output.
//!
//! The commands are fed to `repl_with` (non-interactive, so it echoes them) and its
//! output must equal the file, after one normalisation: every time `<number> ms`
//! (with the spaces before it) becomes ` <t> ms`. `$TMP` in a transcript stands for a
//! fresh temporary directory (files the session saves go there, never into the source
//! tree or `target/`). `UPDATE_TRANSCRIPTS=1` rewrites the files from the actual output
//! (review the diff before committing).

use std::path::{Path, PathBuf};

use ii_prove::repl::{self, COMMANDS};
use ii_prove::report::Options;
use ii_prove::script;

fn normalise(text: &str) -> String {
    let mut out = String::new();
    for line in text.lines() {
        let mut line = line.to_string();
        let mut from = 0;
        while let Some(i) = line[from..].find(" ms").map(|i| i + from) {
            let head = &line[..i];
            let number = head.trim_end_matches(|c: char| c.is_ascii_digit() || c == '.');
            if number.len() == head.len() {
                from = i + 3;
                continue;
            }
            let start = number.trim_end_matches(' ').len();
            let replaced = format!("{} <t> ms", &line[..start]);
            from = replaced.len();
            line = format!("{replaced}{}", &line[i + 3..]);
        }
        out.push_str(line.trim_end());
        out.push('\n');
    }
    out
}

fn sessions() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/repl");
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .expect("tests/repl exists")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "session"))
        .collect();
    files.sort();
    files
}

/// A fresh temporary directory for one test (`name`), empty.
fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("ii-prove-repl-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("a temporary directory");
    dir
}

/// Replays the commands of `transcript` with `$TMP` standing for `tmp`; the output
/// with `tmp` written back as `$TMP`.
fn run_in(transcript: &str, tmp: &Path) -> String {
    let tmp = tmp.display().to_string();
    let input: String = transcript
        .lines()
        .filter_map(|l| l.strip_prefix("> ").or_else(|| l.strip_prefix("… ")))
        .map(|l| format!("{}\n", l.replace("$TMP", &tmp)))
        .collect();
    let mut output = Vec::new();
    repl::repl_with(input.as_bytes(), &mut output, false, None).expect("the REPL runs");
    String::from_utf8(output).expect("UTF-8 output").replace(&tmp, "$TMP")
}

#[test]
fn every_transcript_replays_exactly() {
    let files = sessions();
    assert!(files.len() >= 3, "found only {files:?}");
    let update = std::env::var_os("UPDATE_TRANSCRIPTS").is_some();
    let mut failures = Vec::new();
    for path in files {
        let expected = std::fs::read_to_string(&path).expect("readable");
        let stem = path.file_stem().unwrap().to_string_lossy().into_owned();
        let actual = run_in(&expected, &temp_dir(&stem));
        if update {
            std::fs::write(&path, &actual).expect("writable");
            continue;
        }
        if normalise(&actual) != normalise(&expected) {
            failures.push(format!("{}:\n--- actual ---\n{actual}", path.display()));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn the_transcripts_cover_every_command() {
    let all: String = sessions().iter().map(|p| std::fs::read_to_string(p).unwrap()).collect();
    for c in COMMANDS {
        let used = all.lines().any(|l| {
            l.strip_prefix("> ")
                .is_some_and(|cmd| cmd == c.name || cmd.starts_with(&format!("{} ", c.name)))
        });
        assert!(used, "no transcript uses `{}`", c.name);
    }
}

#[test]
fn a_proof_saved_from_the_repl_checks_as_a_script() {
    let dir = temp_dir("saved");
    let saved = dir.join("saved.ii");
    let session = format!(
        "> input f, g\n> assume E: f = g\n> goal T: 2s/f => g\n> apply ton_weaken\n> apply E\n> prove g . f = g\n> save {}\n",
        saved.display()
    );
    let out = run_in(&session, &dir);
    assert!(out.contains("saved 2 proofs to"), "{out}");
    let result = script::check_files(&[saved.display().to_string()], &Options::default());
    assert_eq!(result.exit_code(), 0, "{}", result.errors.join("\n"));
    assert_eq!(result.claims.len(), 2);
}

#[test]
fn multi_line_input_continues_after_operators_and_open_brackets() {
    assert!(repl::incomplete("goal f =>"));
    assert!(repl::incomplete("= (f +"));
    assert!(repl::incomplete("prove f . g ."));
    assert!(!repl::incomplete("goal f => g"));
    assert!(!repl::incomplete("save out.ii"));
    assert!(!repl::incomplete("= f [H1]"));
}

#[test]
fn times_are_normalised() {
    assert_eq!(normalise("  ok T     12.5 ms\n"), "  ok T <t> ms\n");
    assert_eq!(normalise("proved T: f  (0.3 ms)\n"), "proved T: f  ( <t> ms)\n");
}

mod fuzz {
    use ii_prove::repl::Session;
    use proptest::prelude::*;

    const WORDS: &[&str] = &[
        "goal",
        "apply",
        "=",
        "=>",
        "undo",
        "trace",
        "show",
        "simulate",
        "axioms",
        "input",
        "assume",
        "help",
        "save",
        "f",
        "g",
        "(",
        ")",
        "[",
        "]",
        ".",
        "+",
        "!",
        ",",
        ":",
        "at",
        "0",
        "1.0",
        "5s",
        "2s/f",
        "f/3s",
        "SR(f, g)",
        "ton_weaken",
        "E",
        "for",
        "with",
        "f=1@1s",
        "0@2s",
        "`x`",
        "é",
        "",
        "=",
        "[E]",
        "[and_comm]",
        "T:",
    ];

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]

        /// Random command lines never panic (proof search commands are left out: they run
        /// to their time limit).
        #[test]
        fn random_commands_never_panic(lines in prop::collection::vec(
            prop::collection::vec(prop::sample::select(WORDS), 0..8), 1..12)) {
            let mut session = Session::new().expect("a session");
            let _ = session.execute("input f, g");
            let _ = session.execute("assume E: f = g");
            for words in lines {
                let line = words.join(" ");
                if line.contains("save") {
                    continue;
                }
                let _ = session.execute(&line);
            }
        }
    }
}

#[test]
fn prove_names_a_property_that_is_not_loaded() {
    let mut session = ii_prove::repl::Session::new().unwrap();
    session.execute("load tests/data/proves/water_paper.ii");
    let out = session.execute("prove P1");
    assert!(out.starts_with("error: no property `P1` is loaded"), "{out}");
    assert!(out.contains("P1a, P1b"), "{out}");
}

#[test]
fn tab_completes_the_program_signals() {
    let mut session = ii_prove::repl::Session::new().unwrap();
    session.execute(&format!("load {}/examples/water.ld", env!("CARGO_MANIFEST_DIR")));
    let names = session.completion_names();
    for signal in ["L1_pump", "YL1_pump", "L_flow", "L06a"] {
        assert!(names.iter().any(|n| n == signal), "{signal} does not complete");
    }
}

#[test]
fn save_names_the_program_relative_to_the_saved_script() {
    let dir = temp_dir("relative");
    let session = format!(
        "> load {}/examples/water.ld\n> prove SP_fail => !Bf_valve\n> save $TMP/nested/proofs.ii\n",
        env!("CARGO_MANIFEST_DIR")
    );
    std::fs::create_dir_all(dir.join("nested")).unwrap();
    let out = run_in(&session, &dir);
    assert!(out.contains("saved 1 proof to"), "{out}");
    let saved = std::fs::read_to_string(dir.join("nested/proofs.ii")).unwrap();
    let header = saved.lines().find(|l| l.starts_with("program ")).expect("a program line");
    assert!(header.starts_with("program \"../"), "{header}");
    assert!(header.ends_with("examples/water.ld\""), "{header}");
    let checked = script::check_files(
        &[dir.join("nested/proofs.ii").display().to_string()],
        &Options::default(),
    );
    assert_eq!(checked.exit_code(), 0, "{}", checked.errors.join("\n"));
}

#[test]
fn piped_commands_that_hit_an_error_exit_non_zero() {
    use std::io::Write;
    use std::process::{Command, Stdio};
    let status = |input: &str| {
        let mut child = Command::new(env!("CARGO_BIN_EXE_ii-prove"))
            .arg("repl")
            .stdin(Stdio::piped())
            .stdout(Stdio::null())
            .spawn()
            .unwrap();
        child.stdin.take().unwrap().write_all(input.as_bytes()).unwrap();
        child.wait().unwrap().code()
    };
    assert_eq!(status("input f\nprove f => f + f\n"), Some(0));
    assert_eq!(status("input f\nfrobnicate\nprove f => f\n"), Some(2));
}

#[test]
fn prove_and_auto_search_for_counterexamples_as_the_command_line_does() {
    let mut session = ii_prove::repl::Session::new().unwrap();
    session.execute(&format!("load {}/examples/water_faulty.ld", env!("CARGO_MANIFEST_DIR")));
    let started = std::time::Instant::now();
    let out =
        session.execute("prove P2: (L1_up + L1_pump + L1_down) . (L2_up + L2_pump + L2_down) = 0*");
    assert!(started.elapsed() < std::time::Duration::from_secs(5), "{:?}", started.elapsed());
    assert!(out.starts_with("refuted P2:"), "{out}");
    assert!(out.contains("scan simulator") && out.contains("Line_swap"), "{out}");
    let mut free = ii_prove::repl::Session::new().unwrap();
    free.execute("input f, g");
    free.execute("goal f => f . g");
    let out = free.execute("auto");
    assert!(
        out.contains("what is left is false") && out.contains("counterexample: at t ="),
        "{out}"
    );
}

#[test]
fn trace_all_prints_the_last_proof_with_every_lemma() {
    let mut session = ii_prove::repl::Session::new().unwrap();
    session.execute(&format!("load {}/examples/water.ld", env!("CARGO_MANIFEST_DIR")));
    let out = session.execute("prove Fig9: SP_fail => !Bf_valve");
    assert!(out.starts_with("proved Fig9:"), "{out}");
    // Without an induction nothing folds: both views are the whole proof.
    let (folded, full) = (session.execute("trace"), session.execute("trace all"));
    assert!(!folded.is_empty() && folded != "no proof yet\n", "{folded}");
    assert_eq!(folded, full);
    assert!(session.execute("trace some").starts_with("error: expected `trace` or `trace all`"));
}

/// A timer's elapsed time the program does not read: a property file loaded after the
/// program cannot add it and says where it is computed; one whose `program` header
/// (relative to the file) loads the program gets it computed, and its counterexample
/// draws it.
#[test]
fn an_elapsed_time_named_by_a_file_with_a_program_header_is_computed() {
    let dir = temp_dir("elapsed");
    let program =
        format!("{}/tests/data/refutes_programs/timer_et_unread.st", env!("CARGO_MANIFEST_DIR"));
    std::fs::copy(&program, dir.join("lamp.st")).expect("copy");
    let property = "property Early: lamp => [T1.ET < T#50ms]\n";
    std::fs::write(dir.join("plain.ii"), property).expect("write");
    std::fs::write(dir.join("headed.ii"), format!("program \"lamp.st\"\n{property}"))
        .expect("write");
    let mut after = ii_prove::repl::Session::new().unwrap();
    after.execute(&format!("load {}", dir.join("lamp.st").display()));
    let out = after.execute(&format!("load {}", dir.join("plain.ii").display()));
    assert!(out.contains("unknown pin `T1.ET`"), "{out}");
    assert!(out.contains("a file whose `program \"prog.st\"` header loads the program"), "{out}");
    let mut headed = ii_prove::repl::Session::new().unwrap();
    let out = headed.execute(&format!("load {}", dir.join("headed.ii").display()));
    assert!(out.contains("1 property (Early)"), "{out}");
    let out = headed.execute("prove Early");
    assert!(out.starts_with("refuted Early"), "{out}");
    let row = out.lines().find(|l| l.trim_start().starts_with("T1_ET ")).expect("an ET row");
    assert!(row.contains("100ms"), "{out}");
    std::fs::remove_dir_all(&dir).ok();
}
