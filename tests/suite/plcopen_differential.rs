//! Differential test of the PLCopen front end: every hypothesis the one rung compiler derives from a lowered PLCopen program must hold at every scan of random runs of the PLCopen scan simulator, for random LD and FBD programs (every supported element kind), the examples and the corpus files that load.
//!
//! The reference is [`PlcSimulator`], written over the PLCopen objects from the
//! format note and matiec's function blocks, independently of the lowering and of
//! the LDmicro simulator. Hypotheses are evaluated on its scans by
//! `common/scan_eval.rs` (fresh signals existential, timers by `ceil(d / δ)`).
//! Only the declared inputs are driven, with values held for random numbers of
//! scans. `II_PLC_DIFF_PROGRAMS=N` sets the number of random programs (2000 by
//! default), `II_PLC_DIFF_SEED=S` reruns one; failures print the XML and the seed.

use crate::common;
use crate::common::plcopen_diff;
use plcopen_diff::{Figures, check, random_program};

use std::path::Path;

fn programs() -> u64 {
    std::env::var("II_PLC_DIFF_PROGRAMS").ok().and_then(|v| v.parse().ok()).unwrap_or(600)
}

#[test]
fn random_programs_agree_with_the_simulator() {
    let seeds: Vec<u64> = match std::env::var("II_PLC_DIFF_SEED").ok().and_then(|v| v.parse().ok())
    {
        Some(s) => vec![s],
        None => (0..programs()).collect(),
    };
    // The seeds shared out between the machine's cores, each thread stopping at its
    // third failure.
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get()).clamp(1, 8);
    let total = std::sync::Mutex::new(Figures::default());
    std::thread::scope(|s| {
        for t in 0..threads {
            let (total, seeds) = (&total, &seeds);
            s.spawn(move || {
                let mut fig = Figures::default();
                for &seed in seeds.iter().skip(t).step_by(threads) {
                    let xml = random_program(seed);
                    check(&xml, seed, &mut fig, true);
                    if fig.failures.len() >= 3 {
                        break;
                    }
                }
                total.lock().expect("figures").add(fig);
            });
        }
    });
    let fig = total.into_inner().expect("figures");
    eprintln!(
        "plcopen differential: {} programs ({} refused), {} scans, {} hypotheses checked ({} of integer bits) ({} skipped), {} timer hypotheses fired",
        fig.programs,
        fig.refused,
        fig.scans,
        fig.checked,
        fig.int_checked,
        fig.skipped,
        fig.timer_fired
    );
    assert!(fig.failures.is_empty(), "{}", fig.failures.join("\n\n"));
    assert!(fig.timer_fired > 0 || fig.programs < 50, "no timer ever fired");
    assert!(fig.refused * 10 <= fig.programs, "more than a tenth refused: {}", fig.refused);
    assert!(fig.int_checked > 0 || fig.programs < 50, "no integer equation was checked");
}

#[test]
fn examples_and_corpus_agree_with_the_simulator() {
    let mut fig = Figures::default();
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = common::files_with(&root.join("examples"), "xml");
    files.extend(common::files_with(&root.join("tests/data/plcopen/corpus"), "xml"));
    // The verdict folders' PLCopen programs (graphical bodies calling blocks in ST).
    for dir in ["tests/data/proves_programs", "tests/data/refutes_programs"] {
        files.extend(common::files_with(&root.join(dir), "xml"));
    }
    for (k, f) in files.iter().enumerate() {
        let Ok(text) = std::fs::read_to_string(f) else { continue };
        // Text bodies are the IEC text front end's (tests/suite/st.rs, tests/suite/il.rs).
        if text.contains("<ST>") && !text.contains("<LD>") && !text.contains("<FBD>")
            || text.contains("<IL>") && !text.contains("<LD>") && !text.contains("<FBD>")
        {
            continue;
        }
        let is_example = f.starts_with(root.join("examples"));
        check(&text, k as u64, &mut fig, is_example);
    }
    eprintln!("plcopen differential on files: {fig:?}");
    assert!(fig.failures.is_empty(), "{}", fig.failures.join("\n\n"));
}
