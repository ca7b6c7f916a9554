//! End-to-end benchmark: synthetic plants of N rungs (copies of the water plant with
//! its interlock), read, compiled and checked with `ii-prove PLANT.ld PROPS.ii`.
//!
//! Each unit is the 10 logic rungs of `examples/water.ld` with its signals renamed
//! (`RL1_Prod` → `RL1_Prod_u7`); the distribution stoppage `XSP_fail` is shared. The
//! properties are P2 (the interlock) and P3 (the stoppage) of the first and the last
//! unit. `II_BENCH_MAX_N` caps the size for quick runs. A second group times
//! `examples/water_faulty.ld` end to end, where P2 is refuted.

use std::path::Path;
use std::time::Duration;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use ii_prove::report::{self, Options, Status};

/// The PROGRAM part of the water plant, without comment rungs.
fn unit_rungs() -> Vec<String> {
    let text = include_str!("../examples/water.ld");
    let program = text.split("PROGRAM").nth(1).expect("a PROGRAM section");
    let mut rungs = Vec::new();
    let mut current = String::new();
    for line in program.lines() {
        let t = line.trim();
        if t.is_empty() {
            continue;
        }
        current.push_str(line);
        current.push('\n');
        if line.starts_with("END") {
            if !current.contains("COMMENT") {
                rungs.push(current.clone());
            }
            current.clear();
        }
    }
    rungs
}

/// Renames every bit and timer of a rung for unit `k` (the shared stoppage excepted).
fn rename(rung: &str, k: usize) -> String {
    rung.lines()
        .map(|line| {
            let mut words: Vec<String> = line.split(' ').map(str::to_string).collect();
            for w in words.iter_mut() {
                let is_name = w.len() > 1
                    && w.starts_with(['X', 'Y', 'R', 'T'])
                    && !matches!(w.as_str(), "RUNG" | "TON" | "TOF")
                    && w != "XSP_fail";
                if is_name {
                    w.push_str(&format!("_u{k}"));
                }
            }
            words.join(" ")
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn plant(rungs: usize) -> String {
    let unit = unit_rungs();
    let mut out = String::from("LDmicro0.1\nCYCLE=10000\nCRYSTAL=4000000\nBAUD=2400\n\nPROGRAM\n");
    for k in 0..rungs.div_ceil(unit.len()) {
        for r in &unit {
            out.push_str(&rename(r, k));
            out.push('\n');
        }
    }
    out
}

fn properties(units: usize) -> String {
    let mut out = String::new();
    let mut ends = vec![0, units - 1];
    ends.dedup();
    for k in ends {
        out.push_str(&format!(
            "property P2_u{k}: (L1_up_u{k} + L1_pump_u{k} + L1_down_u{k}) . (L2_up_u{k} + L2_pump_u{k} + L2_down_u{k}) = 0*\n\
             property P3_u{k}: SP_fail => !L1_pump_u{k} . !L2_pump_u{k} . !Out_valve_u{k} . !Bf_valve_u{k}\n"
        ));
    }
    out
}

fn write(dir: &Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).expect("the temporary file is written");
    path.display().to_string()
}

fn plants(c: &mut Criterion) {
    let max: usize =
        std::env::var("II_BENCH_MAX_N").ok().and_then(|v| v.parse().ok()).unwrap_or(10_000);
    let dir = std::env::temp_dir().join(format!("ii-prove-plants-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("a temporary directory");
    let opts = Options::default();
    let mut group = c.benchmark_group("plant_end_to_end");
    group.sample_size(10).measurement_time(Duration::from_secs(5));
    for rungs in [10, 100, 1_000, 10_000].into_iter().filter(|n| *n <= max) {
        let units = rungs.div_ceil(10);
        let program = write(&dir, &format!("plant_{rungs}.ld"), &plant(rungs));
        let props = write(&dir, &format!("plant_{rungs}.ii"), &properties(units));
        let run = report::run_program(&program, std::slice::from_ref(&props), &opts)
            .unwrap_or_else(|e| panic!("{}", e.rendered));
        assert!(run.properties.iter().all(|p| p.status == Status::Proved), "{rungs} rungs");
        group.bench_with_input(BenchmarkId::from_parameter(rungs), &rungs, |b, _| {
            b.iter(|| report::run_program(&program, std::slice::from_ref(&props), &opts))
        });
    }
    group.finish();
}

/// The faulty water plant end to end: P2 is refuted (counterexample found and
/// confirmed twice), the other properties proved.
fn faulty_water(c: &mut Criterion) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let program = root.join("water_faulty.ld").display().to_string();
    let props = root.join("water.ii").display().to_string();
    let opts = Options::default();
    let run = report::run_program(&program, std::slice::from_ref(&props), &opts)
        .unwrap_or_else(|e| panic!("{}", e.rendered));
    let refuted: Vec<&str> = run
        .properties
        .iter()
        .filter(|p| p.status == Status::Refuted)
        .map(|p| p.name.as_str())
        .collect();
    assert_eq!(refuted, ["P2"], "the faulty plant breaks the interlock only");
    let mut group = c.benchmark_group("faulty_water_end_to_end");
    group.sample_size(10).measurement_time(Duration::from_secs(5));
    group.bench_function("water_faulty.ld", |b| {
        b.iter(|| report::run_program(&program, std::slice::from_ref(&props), &opts))
    });
    group.finish();
}

criterion_group!(benches, plants, faulty_water);
criterion_main!(benches);
