//! The command line end to end: exit codes in both modes, `show`, `axioms`, JSON, and the
//! length of the water plant's proofs against the paper's.

use crate::common;

use std::path::Path;
use std::process::Command;

use common::{ii_prove, text};

use ii_prove::report::{self, Options, Status};

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
    // Its previous-scan reads (`pre`) make it a description of scans: read as free
    // signals it is refused, at the first `pre`, with a located error.
    let again = ii_prove(&[file.to_str().unwrap()]);
    assert_eq!(again.status.code(), Some(2), "{}", text(&again.stdout));
    assert!(text(&again.stderr).contains("needs a program"), "{}", text(&again.stderr));
    assert!(text(&again.stderr).contains("water_show.ii:"), "{}", text(&again.stderr));
    // A program without them reads back as free signals.
    let out = ii_prove(&["show", "examples/early_timer.ld"]);
    let shown = text(&out.stdout);
    assert!(shown.lines().filter(|l| l.starts_with("assume")).all(|l| !l.contains("pre ")));
    std::fs::write(&file, format!("{shown}\nproperty belt: YBelt => XStart\n")).unwrap();
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

/// A fresh temporary directory for one test.
fn temp_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("ii-prove-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn a_closed_output_pipe_ends_the_run_quietly() {
    use std::io::Read;
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_ii-prove"))
        .args(["examples/water.ld", "examples/water.ii", "--json", "--trace"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // Read 100 bytes, then close the pipe (as `| head -c 100` does).
    let mut stdout = child.stdout.take().unwrap();
    let mut head = [0u8; 100];
    stdout.read_exact(&mut head).unwrap();
    drop(stdout);
    let out = child.wait_with_output().unwrap();
    let stderr = text(&out.stderr);
    assert!(!stderr.contains("panicked") && !stderr.contains("Broken pipe"), "{stderr}");
    assert_eq!(out.status.code(), Some(141), "{stderr}");
}

#[test]
fn no_property_at_all_is_an_error() {
    let dir = temp_dir("empty");
    let empty = dir.join("empty.ii");
    std::fs::write(&empty, "input f // nothing to prove\n").unwrap();
    let out = ii_prove(&[empty.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("no property to check"), "{}", text(&out.stderr));
    let lone = ii_prove(&["examples/water.ld"]);
    assert_eq!(lone.status.code(), Some(2));
    assert!(text(&lone.stderr).contains("no property file (.ii) was given"));
}

#[test]
fn the_program_is_recognised_by_content_wherever_it_stands() {
    let dir = temp_dir("order");
    // A program without the `.ld` extension, after its property file.
    let program = dir.join("plant.txt");
    std::fs::copy(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/water.ld"), &program)
        .unwrap();
    let out = ii_prove(&["examples/water.ii", program.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(text(&out.stdout).contains("P1a "));
    let two = ii_prove(&["examples/water.ld", "examples/water.ii", "examples/water_faulty.ld"]);
    assert_eq!(two.status.code(), Some(2));
    let stderr = text(&two.stderr);
    assert!(
        stderr.contains("two ladder programs") && stderr.contains("water_faulty.ld"),
        "{stderr}"
    );
    assert!(two.stdout.is_empty());
}

#[test]
fn binary_input_is_refused_at_once() {
    let dir = temp_dir("binary");
    let binary = dir.join("blob.ii");
    // 5 MB of pseudo-random bytes.
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let bytes: Vec<u8> = (0..5_000_000)
        .map(|_| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 24) as u8
        })
        .collect();
    std::fs::write(&binary, bytes).unwrap();
    let started = std::time::Instant::now();
    let out = ii_prove(&[binary.to_str().unwrap()]);
    assert!(started.elapsed() < std::time::Duration::from_secs(5), "took {:?}", started.elapsed());
    assert_eq!(out.status.code(), Some(2));
    let stderr = text(&out.stderr);
    assert!(stderr.contains("binary file") && stderr.lines().count() < 5, "{stderr}");
    // As the program too.
    let out = ii_prove(&["tests/data/ldmicro/parse_err/nul_byte.ld", "examples/water.ii"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("binary file"));
    // A binary program with no extension, or named .xml: its error alone, no unknown
    // signals of the property file after it, and no talk of `.ld` only.
    let bare = dir.join("program");
    std::fs::write(&bare, b"\x7fELF\x02\x01\x01\0\0").unwrap();
    let xml = dir.join("program.xml");
    std::fs::write(&xml, b"\x7fELF\x02\x01\x01\0\0").unwrap();
    for program in [&bare, &xml] {
        let out = ii_prove(&[program.to_str().unwrap(), "examples/water.ii"]);
        assert_eq!(out.status.code(), Some(2));
        let stderr = text(&out.stderr);
        assert!(stderr.contains("binary file") && stderr.contains(".xml"), "{stderr}");
        assert!(!stderr.contains("unknown signal"), "{stderr}");
        assert_eq!(stderr.matches("error").count(), 1, "{stderr}");
    }
}

#[test]
fn errors_are_capped() {
    let dir = temp_dir("many-errors");
    let bad = dir.join("bad.ii");
    let text_: String = (0..500).map(|i| format!("property P{i}: f => nosuch{i}\n")).collect();
    std::fs::write(&bad, text_).unwrap();
    let out = ii_prove(&[bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let stderr = text(&out.stderr);
    let shown = stderr.matches("error:").count();
    assert_eq!(shown, report::MAX_ERRORS, "{stderr}");
    let more = stderr.lines().last().unwrap();
    assert!(more.starts_with("… and ") && more.ends_with(" more errors"), "{more}");
}

/// A free-signal file whose first property is proved at once and whose second runs to
/// its time limit.
fn quick_then_slow(dir: &Path) -> std::path::PathBuf {
    let file = dir.join("slow.ii");
    std::fs::write(
        &file,
        "input f\nproperty quick: f => f + f\nproperty slow: (3s/f)/1s => 2s/(f/1s)\n",
    )
    .unwrap();
    file
}

#[test]
fn results_are_printed_as_they_are_known_and_ctrl_c_prints_the_partial_summary() {
    use std::io::{BufRead, BufReader};
    use std::process::Stdio;
    let dir = temp_dir("interrupt");
    let file = quick_then_slow(&dir);
    let mut child = Command::new(env!("CARGO_BIN_EXE_ii-prove"))
        .args([file.to_str().unwrap(), "--timeout", "60s"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdout = BufReader::new(child.stdout.take().unwrap());
    let mut first = String::new();
    stdout.read_line(&mut first).unwrap();
    assert!(first.starts_with("quick ") && first.contains("proved"), "{first}");
    // The second property is still running: interrupt it.
    let kill = Command::new("kill").args(["-INT", &child.id().to_string()]).status().unwrap();
    assert!(kill.success());
    let mut rest = String::new();
    std::io::Read::read_to_string(&mut stdout, &mut rest).unwrap();
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(130), "{rest}");
    assert!(
        rest.contains("interrupted after 1 of 2 properties: 1 proved, 0 refuted, 0 unknown"),
        "{rest}"
    );
}

#[test]
fn flags_a_subcommand_does_not_use_are_refused() {
    for args in [
        &["axioms", "--timeout", "3"][..],
        &["axioms", "--trace"],
        &["show", "examples/water.ld", "--json"],
        &["check", "proofs/water.ii", "--vcd", "x.vcd"],
        &["repl", "--ascii"],
    ] {
        let out = ii_prove(args);
        assert_eq!(out.status.code(), Some(2), "{args:?} was accepted");
        assert!(text(&out.stderr).contains("unexpected argument"), "{args:?}");
    }
    assert_eq!(ii_prove(&["axioms", "--ascii"]).status.code(), Some(0));
}

#[test]
fn timeout_accepts_units() {
    for ok in ["10", "10s", "500ms", "1m", "0.5"] {
        let out = ii_prove(&["tests/data/proves/derived_timer_laws.ii", "--timeout", ok]);
        assert_eq!(out.status.code(), Some(0), "--timeout {ok}: {}", text(&out.stderr));
    }
    for bad in ["0", "-1", "0s", "soon", "inf"] {
        let out = ii_prove(&["tests/data/proves/derived_timer_laws.ii", "--timeout", bad]);
        assert_eq!(out.status.code(), Some(2), "--timeout {bad} was accepted");
    }
}

#[test]
fn a_dash_writes_the_waveforms_to_standard_output() {
    let out =
        ii_prove(&["examples/water_faulty.ld", "examples/water.ii", "--only", "P2", "--vcd", "-"]);
    assert_eq!(out.status.code(), Some(1));
    let stdout = text(&out.stdout);
    assert!(stdout.starts_with("$date") || stdout.contains("$timescale"), "{stdout}");
    assert!(text(&out.stderr).contains("P2 "), "the report moves to standard error");
    let wave = ii_prove(&[
        "examples/water_faulty.ld",
        "examples/water.ii",
        "--only",
        "P2",
        "--wavedrom",
        "-",
    ]);
    let json: serde_json::Value = serde_json::from_slice(&wave.stdout).expect("WaveDrom JSON");
    assert_eq!(json["signal"][0][0], "P2", "{json}");
    let both =
        ii_prove(&["examples/water.ld", "examples/water.ii", "--vcd", "-", "--wavedrom", "-"]);
    assert_eq!(both.status.code(), Some(2));
}

#[test]
fn an_unwritable_output_path_fails_before_any_proof_runs() {
    let out = ii_prove(&[
        "examples/water_faulty.ld",
        "examples/water.ii",
        "--vcd",
        "/no/such/folder/out.vcd",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("cannot write /no/such/folder/out.vcd"));
    assert!(out.stdout.is_empty(), "no proof ran: {}", text(&out.stdout));
    let dir = temp_dir("unwritable");
    let out =
        ii_prove(&["examples/water.ld", "examples/water.ii", "--wavedrom", dir.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2), "a directory is not a file");
    assert!(std::fs::read_dir(&dir).unwrap().next().is_none(), "the probe left nothing");
}

#[test]
fn completions_and_the_manual_page_are_generated() {
    for shell in ["bash", "zsh", "fish"] {
        let out = ii_prove(&["completions", shell]);
        assert_eq!(out.status.code(), Some(0), "{shell}");
        let script = text(&out.stdout);
        assert!(script.contains("ii-prove") && script.contains("--format"), "{shell}");
    }
    assert_eq!(ii_prove(&["completions", "tcsh"]).status.code(), Some(2));
    // `--install` on a fresh home: the folders are made, the script is the printed one.
    let home = temp_dir("completions-home");
    for (shell, place) in [
        ("bash", ".local/share/bash-completion/completions/ii-prove"),
        ("fish", ".config/fish/completions/ii-prove.fish"),
        ("zsh", ".zfunc/_ii-prove"),
    ] {
        let out = Command::new(env!("CARGO_BIN_EXE_ii-prove"))
            .args(["completions", shell, "--install"])
            .env("HOME", &home)
            .env_remove("XDG_DATA_HOME")
            .env_remove("XDG_CONFIG_HOME")
            .env_remove("ZDOTDIR")
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(0), "{shell}: {}", text(&out.stderr));
        let installed = std::fs::read_to_string(home.join(place)).expect("installed");
        assert_eq!(installed, text(&ii_prove(&["completions", shell]).stdout), "{shell}");
        assert!(text(&out.stdout).contains(place), "{}", text(&out.stdout));
    }
    let out = ii_prove(&["completions", "elvish", "--install"]);
    assert_eq!(out.status.code(), Some(2));
    let man = ii_prove(&["man"]);
    assert_eq!(man.status.code(), Some(0));
    let page = text(&man.stdout);
    assert!(page.contains(".TH ii-prove") && page.contains("\\-\\-deny"), "{}", &page[..200]);
}

/// On a terminal (a pseudo-terminal from util-linux `script`), a long run shows which
/// property it is checking; skipped where `script` is missing.
#[test]
fn the_progress_line_is_drawn_on_a_terminal_once_the_run_is_long() {
    let dir = temp_dir("progress-tty");
    let file = quick_then_slow(&dir);
    let command = format!("{} {} --timeout 3s", env!("CARGO_BIN_EXE_ii-prove"), file.display());
    let Ok(out) = Command::new("script").args(["-qec", &command, "/dev/null"]).output() else {
        eprintln!("no `script` command: the terminal case is not checked");
        return;
    };
    let screen = text(&out.stdout);
    if !screen.contains("quick") {
        eprintln!("`script` gave no terminal here: the terminal case is not checked");
        return;
    }
    assert!(screen.contains("[1/2] checking slow (1 s)"), "{screen}");
    // The line is cleared before the result is printed over it.
    assert!(screen.contains("\r\x1b[Kslow "), "{screen:?}");
    assert!(!screen.contains("checking quick"), "the first second shows no progress");
}

#[test]
fn the_progress_line_is_not_drawn_when_standard_error_is_not_a_terminal() {
    let dir = temp_dir("progress");
    let file = quick_then_slow(&dir);
    let out = ii_prove(&[file.to_str().unwrap(), "--timeout", "2s"]);
    assert!(!text(&out.stderr).contains('\r') && !text(&out.stderr).contains("checking"));
}

/// The quick-then-slow file checked in `format`, interrupted by Ctrl-C once the quick
/// property is done: what the run wrote to standard output.
fn interrupted(format: &str) -> String {
    use std::io::Read;
    use std::process::Stdio;
    let dir = temp_dir(&format!("interrupt-{format}"));
    let file = quick_then_slow(&dir);
    let mut child = Command::new(env!("CARGO_BIN_EXE_ii-prove"))
        .args([file.to_str().unwrap(), "--timeout", "60s", "--format", format])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // The quick property takes milliseconds; the slow one a minute.
    std::thread::sleep(std::time::Duration::from_millis(1500));
    let kill = Command::new("kill").args(["-INT", &child.id().to_string()]).status().unwrap();
    assert!(kill.success());
    let mut out = String::new();
    child.stdout.take().unwrap().read_to_string(&mut out).unwrap();
    assert_eq!(child.wait().unwrap().code(), Some(130));
    out
}

#[test]
fn ctrl_c_under_junit_writes_the_partial_document_and_marks_the_rest() {
    let xml = interrupted("junit");
    let doc = roxmltree::Document::parse(&xml).expect("well-formed XML");
    let cases: Vec<_> = doc.descendants().filter(|n| n.has_tag_name("testcase")).collect();
    assert_eq!(cases.len(), 2, "{xml}");
    assert_eq!(cases[0].attribute("name"), Some("quick"));
    assert!(cases[0].children().all(|c| !c.is_element()), "{xml}");
    // What the run did not finish is marked: a test case in error, counted.
    assert_eq!(cases[1].attribute("name"), Some("slow"));
    let error = cases[1].children().find(|c| c.has_tag_name("error")).expect("an error");
    assert_eq!(error.attribute("type"), Some("interrupted"));
    assert_eq!(doc.root_element().attribute("errors"), Some("1"), "{xml}");
}

#[test]
fn jobs_change_neither_the_verdicts_nor_their_order() {
    let run = |jobs: &str| {
        let out = ii_prove(&["examples/water_faulty.ld", "examples/water.ii", "--jobs", jobs]);
        assert_eq!(out.status.code(), Some(1), "{}", text(&out.stderr));
        // Name and verdict of each property line, in the order printed.
        text(&out.stdout)
            .lines()
            .filter_map(|l| {
                let mut words = l.split_whitespace();
                let (name, status) = (words.next()?, words.next()?);
                matches!(status, "proved" | "refuted" | "unknown")
                    .then(|| format!("{name} {status}"))
            })
            .collect::<Vec<_>>()
    };
    let one = run("1");
    assert_eq!(one.len(), 12, "{one:?}");
    assert!(one.contains(&"P2 refuted".to_string()), "{one:?}");
    assert_eq!(run("2"), one);
    assert_eq!(run("4"), one);
    let out = ii_prove(&["examples/water.ld", "examples/water.ii", "--jobs", "0"]);
    assert_eq!(out.status.code(), Some(2), "--jobs 0 is refused");
}

#[test]
fn ctrl_c_under_json_closes_the_document_written_so_far_and_lists_the_rest() {
    let out = interrupted("json");
    let json: serde_json::Value = serde_json::from_str(&out).expect("a whole JSON document");
    assert_eq!(json["interrupted"], true, "{out}");
    let props = json["properties"].as_array().unwrap();
    assert_eq!(props.len(), 1, "{out}");
    assert_eq!(props[0]["name"], "quick");
    assert_eq!(json["unchecked"][0]["name"], "slow", "{out}");
    assert_eq!(json["summary"]["proved"], 1, "{out}");
}
