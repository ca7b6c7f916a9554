//! The Structured Text front end against matiec, the editors' own compiler: random ST programs (`common/st_gen.rs`) are compiled by `iec2c` and gcc and run scan by scan (`tools/oracle/run.py`); every BOOL variable and function-block output must have, at every scan, the value the scan-model simulator gives the lowered program — whose compiled equations `tests/st.rs` checks against that simulator.
//!
//! Outside the test command (it needs the toolchain built by `tools/oracle/setup.sh DIR`):
//! `II_ORACLE=DIR cargo test --release --test st_oracle -- --ignored`, with
//! `II_ST_PROGRAMS=N` programs (500 by default) from seed `II_ST_FIRST` (0).

mod common;
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

/// The scan-model simulator's values of `bits`, per bit a string of `0`/`1` per scan.
fn ours(g: &st_gen::Generated, inputs: &[BTreeMap<String, bool>]) -> Result<Vec<String>, String> {
    let mut sources = Sources::new();
    let file = sources.add("random.st", g.text.clone());
    let unit = ii_prove::st::read(&sources, file).map_err(|e| format!("{e:?}"))?;
    let lowered = ii_prove::st::lower(&sources, &unit, None, None).map_err(|e| format!("{e:?}"))?;
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
    let dir = PathBuf::from(std::env::var_os("II_ORACLE").expect("II_ORACLE=DIR"));
    assert!(dir.join("matiec/iec2c").is_file(), "{} has no matiec/iec2c", dir.display());
    let first = env_u64("II_ST_FIRST", 0);
    let n = env_u64("II_ST_PROGRAMS", 500);
    let temp = tempfile::tempdir().expect("temporary directory");
    let work = match std::env::var_os("II_ORACLE_KEEP") {
        Some(d) => PathBuf::from(d),
        None => temp.path().to_path_buf(),
    };
    std::fs::create_dir_all(&work).expect("work directory");
    let mut jobs = Vec::new();
    let mut failures = Vec::new();
    for seed in first..first + n {
        let g = st_gen::program_with(seed, false);
        let inputs = st_gen::schedule(&g, seed, SCANS);
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
        "random ST programs against matiec: {n} generated, {compared} run by the toolchain ({refused:?} refused), {bit_scans} bit-scans compared; {} disagreements",
        failures.len()
    );
    assert!(
        failures.is_empty(),
        "{}",
        failures.iter().take(3).cloned().collect::<Vec<_>>().join("\n\n")
    );
    assert!(compared > 0, "the toolchain ran no program");
}
