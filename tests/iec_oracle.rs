//! The IEC text front end against matiec, the editors' own compiler: random Structured Text (`common/st_gen.rs`) and Instruction List (`common/il_gen.rs`) programs are compiled by `iec2c` and gcc and run scan by scan (`tools/oracle/run.py`); every BOOL variable and function-block output must have, at every scan, the value the scan-model simulator gives the lowered program — whose compiled equations `tests/st.rs` and `tests/il.rs` check against that simulator.
//!
//! Outside the test command (it needs the toolchain built by `tools/oracle/setup.sh DIR`):
//! `II_ORACLE=DIR cargo test --release --test iec_oracle -- --ignored`, with
//! `II_ST_PROGRAMS=N` / `II_IL_PROGRAMS=N` programs (500 by default) from seed
//! `II_ST_FIRST` / `II_IL_FIRST` (0).

mod common;
#[path = "common/il_gen.rs"]
mod il_gen;
#[path = "common/rng.rs"]
mod rng;
#[path = "common/st_gen.rs"]
mod st_gen;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use ii_prove::diag::Sources;
use ii_prove::ladder::TimerModel;
use serde_json::{Value, json};

const SCANS: usize = 120;

fn env_u64(name: &str, default: u64) -> u64 {
    std::env::var(name).ok().and_then(|v| v.parse().ok()).unwrap_or(default)
}

/// A random program to run.
struct Job {
    seed: u64,
    text: String,
    pou: String,
    inputs: Vec<String>,
    bits: Vec<String>,
    cycle_us: u64,
}

/// The scan-model simulator's values of the job's bits, per bit a string of `0`/`1` per
/// scan.
fn ours(g: &Job, inputs: &[BTreeMap<String, bool>]) -> Result<Vec<String>, String> {
    let mut sources = Sources::new();
    let file = sources.add("random.st", g.text.clone());
    let unit = ii_prove::iec::read(&sources, file).map_err(|e| format!("{e:?}"))?;
    let lowered =
        ii_prove::iec::lower(&sources, &unit, None, None).map_err(|e| format!("{e:?}"))?;
    let mut sim = ii_prove::program::simulate::Simulator::new(&lowered.program, TimerModel::Plc);
    let mut out = vec![String::new(); g.bits.len()];
    for step in inputs {
        sim.step(step);
        for (k, b) in g.bits.iter().enumerate() {
            if !sim.is_known(b) {
                return Err(format!("{b} is unknown"));
            }
            out[k].push(if sim.bit(b) { '1' } else { '0' });
        }
    }
    Ok(out)
}

#[test]
#[ignore = "needs the toolchain of tools/oracle/setup.sh (II_ORACLE=DIR)"]
fn random_st_programs_run_as_matiec_runs_them() {
    let (first, n) = (env_u64("II_ST_FIRST", 0), env_u64("II_ST_PROGRAMS", 500));
    let jobs = (first..first + n).map(|seed| {
        let g = st_gen::program_with(seed, false);
        Job { seed, text: g.text, pou: g.pou, inputs: g.inputs, bits: g.bits, cycle_us: g.cycle_us }
    });
    against_matiec("ST", jobs.collect());
}

#[test]
#[ignore = "needs the toolchain of tools/oracle/setup.sh (II_ORACLE=DIR)"]
fn random_il_programs_run_as_matiec_runs_them() {
    let (first, n) = (env_u64("II_IL_FIRST", 0), env_u64("II_IL_PROGRAMS", 500));
    let jobs = (first..first + n).map(|seed| {
        let g = il_gen::program_with(seed, true);
        let pou = "Random".to_string();
        Job { seed, text: g.text, pou, inputs: g.inputs, bits: g.bits, cycle_us: g.cycle_us }
    });
    against_matiec("IL", jobs.collect());
}

/// Runs every job through matiec and compares its bits with the scan-model simulator's.
fn against_matiec(language: &str, programs: Vec<Job>) {
    let n = programs.len();
    let dir = PathBuf::from(std::env::var_os("II_ORACLE").expect("II_ORACLE=DIR"));
    assert!(dir.join("matiec/iec2c").is_file(), "{} has no matiec/iec2c", dir.display());
    let temp = tempfile::tempdir().expect("temporary directory");
    let work = common::oracle_work_dir(temp.path());
    let mut jobs = Vec::new();
    let mut failures = Vec::new();
    for g in programs {
        let seed = g.seed;
        let inputs = st_gen::schedule_of(&g.inputs, seed, SCANS);
        let expected = match ours(&g, &inputs) {
            Ok(x) => x,
            Err(e) => {
                failures.push(format!("seed {seed}: {e}\n{}", g.text));
                continue;
            }
        };
        let key = format!("{seed:06}");
        let trace =
            |n: &str| inputs.iter().map(|s| if s[n] { '1' } else { '0' }).collect::<String>();
        let req = json!({
            "pou": g.pou,
            "cycle_ns": g.cycle_us * 1000,
            "scans": SCANS,
            "inputs": g.inputs.iter().map(|n| (n.clone(), Value::from(trace(n)))).collect::<serde_json::Map<_, _>>(),
            "want": g.bits.iter().map(|b| json!({"bit": b})).collect::<Vec<_>>(),
        });
        std::fs::write(work.join(format!("{key}.st")), &g.text).expect("write");
        std::fs::write(work.join(format!("{key}.req.json")), req.to_string()).expect("write");
        jobs.push((key, seed, g, expected));
    }
    let status = std::process::Command::new("python3")
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tools/oracle/run.py"))
        .arg(&work)
        .env("ORACLE_MATIEC", dir.join("matiec"))
        .status()
        .expect("run.py");
    assert!(status.success(), "run.py failed");
    let (mut compared, mut refused, mut bit_scans) = (0u64, BTreeMap::<String, u64>::new(), 0u64);
    for (key, seed, g, expected) in jobs {
        let out = std::fs::read_to_string(work.join(format!("{key}.out.json"))).expect("an answer");
        let out: Value = serde_json::from_str(&out).expect("JSON");
        let stage = out["status"].as_str().unwrap_or("?");
        if stage != "ok" {
            *refused.entry(stage.to_string()).or_default() += 1;
            if refused[stage] == 1 {
                eprintln!("seed {seed}: {stage}: {}", out["message"].as_str().unwrap_or(""));
            }
            continue;
        }
        compared += 1;
        let traces: Vec<&str> = out["trace"]
            .as_array()
            .map(|a| a.iter().filter_map(Value::as_str).collect())
            .unwrap_or_default();
        for (k, bit) in g.bits.iter().enumerate() {
            let theirs = traces.get(k).copied().unwrap_or("");
            bit_scans += theirs.len() as u64;
            if theirs != expected[k] {
                let at =
                    theirs.chars().zip(expected[k].chars()).position(|(a, b)| a != b).unwrap_or(0);
                failures.push(format!(
                    "seed {seed}: {bit} differs from scan {at}:\n  matiec {theirs}\n  ours   {}\n{}",
                    expected[k], g.text
                ));
                break;
            }
        }
    }
    eprintln!(
        "random {language} programs against matiec: {n} generated, {compared} run by the toolchain ({refused:?} refused), {bit_scans} bit-scans compared; {} disagreements",
        failures.len()
    );
    assert!(
        failures.is_empty(),
        "{}",
        failures.iter().take(3).cloned().collect::<Vec<_>>().join("\n\n")
    );
    assert!(compared > 0, "the toolchain ran no program");
}

/// The value of a counterexample signal (`--json`) at `t`, in seconds.
fn sample(signal: &Value, t: f64) -> Option<bool> {
    let bps: Vec<f64> = signal["breakpoints"]
        .as_array()?
        .iter()
        .filter_map(|b| b.as_str().and_then(|s| s.parse().ok()))
        .collect();
    let at = |key: &str, k: usize| {
        signal[key].as_array().and_then(|a| a.get(k)).and_then(Value::as_bool)
    };
    for (k, bp) in bps.iter().enumerate() {
        if (bp - t).abs() < 1e-9 {
            return at("points", k);
        }
        if t < *bp {
            return at("intervals", k);
        }
    }
    None
}

/// The faulty water plants' counterexamples, replayed on the program as matiec builds
/// it: at every scan up to the violation, every program bit the counterexample shows has
/// the value matiec's run gives it.
#[test]
#[ignore = "needs the toolchain of tools/oracle/setup.sh (II_ORACLE=DIR)"]
fn counterexamples_of_the_faulty_text_plants_replay_on_matiec() {
    let dir = PathBuf::from(std::env::var_os("II_ORACLE").expect("II_ORACLE=DIR"));
    let inputs = ["L_flow", "H_flow", "Line_swap", "L1_fail", "L2_fail", "SP_fail"];
    for program in ["examples/water_faulty.st", "examples/water_faulty.il"] {
        let out = common::ii_prove(&[program, "examples/water.ii", "--only", "P2", "--json"]);
        let report: Value = serde_json::from_str(&common::text(&out.stdout)).expect("JSON");
        let cex = &report["properties"][0]["counterexample"];
        let signals = cex["signals"].as_array().expect("a counterexample");
        let violated: f64 = cex["time"].as_str().and_then(|t| t.parse().ok()).expect("its time");
        let cycle = 0.01;
        let scans = (violated / cycle).round() as usize + 1;
        let named = |n: &str| signals.iter().find(|s| s["name"] == n);
        let trace = |s: &Value| -> String {
            (0..scans)
                .map(|k| if sample(s, k as f64 * cycle).unwrap_or(false) { '1' } else { '0' })
                .collect()
        };
        let mut drive = serde_json::Map::new();
        for i in inputs {
            let t = named(i).map_or("0".repeat(scans), trace);
            drive.insert(i.to_string(), Value::from(t));
        }
        let shown: Vec<&Value> = signals
            .iter()
            .filter(|s| {
                let n = s["name"].as_str().unwrap_or("");
                !inputs.contains(&n) && !n.starts_with("lhs") && !n.starts_with("rhs")
            })
            .collect();
        let work = tempfile::tempdir().expect("temporary directory");
        let req = json!({
            "pou": "Water",
            "cycle_ns": 10_000_000u64,
            "scans": scans,
            "inputs": drive,
            "want": shown.iter().map(|s| json!({"bit": s["name"]})).collect::<Vec<_>>(),
        });
        let text = std::fs::read_to_string(program).expect("read");
        std::fs::write(work.path().join("water.st"), text).expect("write");
        std::fs::write(work.path().join("water.req.json"), req.to_string()).expect("write");
        let status = std::process::Command::new("python3")
            .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("tools/oracle/run.py"))
            .arg(work.path())
            .env("ORACLE_MATIEC", dir.join("matiec"))
            .status()
            .expect("run.py");
        assert!(status.success(), "run.py failed");
        let answer = std::fs::read_to_string(work.path().join("water.out.json")).expect("answer");
        let answer: Value = serde_json::from_str(&answer).expect("JSON");
        assert_eq!(answer["status"], "ok", "{program}: {answer}");
        let traces = answer["trace"].as_array().expect("traces");
        for (s, theirs) in shown.iter().zip(traces) {
            assert_eq!(theirs.as_str(), Some(trace(s).as_str()), "{program}: {}", s["name"]);
        }
        eprintln!(
            "{program}: the counterexample's {} program bits over {scans} scans are matiec's",
            shown.len()
        );
    }
}
