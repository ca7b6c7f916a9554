//! Helpers shared by the test binaries.

use std::path::{Path, PathBuf};

/// Every file under `dir` (recursively) whose name ends in `.ext`, sorted; none if
/// `dir` does not exist.
#[allow(dead_code)]
pub fn files_with(dir: &Path, ext: &str) -> Vec<PathBuf> {
    fn walk(dir: &Path, ext: &str, out: &mut Vec<PathBuf>) {
        let Ok(entries) = std::fs::read_dir(dir) else { return };
        for path in entries.flatten().map(|e| e.path()) {
            if path.is_dir() {
                walk(&path, ext, out);
            } else if path.extension().is_some_and(|e| e == ext) {
                out.push(path);
            }
        }
    }
    let mut out = Vec::new();
    walk(dir, ext, &mut out);
    out.sort();
    out
}

/// Runs the `ii-prove` binary in the crate's root folder.
#[allow(dead_code)]
pub fn ii_prove(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_ii-prove"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the binary runs")
}

/// Captured output as text.
#[allow(dead_code)]
pub fn text(out: &[u8]) -> String {
    String::from_utf8_lossy(out).into_owned()
}

/// The verdict of each property a run prints: `(name, proved|refuted|unknown)`, in order.
#[allow(dead_code)]
pub fn verdicts(args: &[&str]) -> Vec<(String, String)> {
    let out = ii_prove(args);
    text(&out.stdout)
        .lines()
        .filter_map(|l| {
            let mut w = l.split_whitespace();
            let (name, verdict) = (w.next()?, w.next()?);
            matches!(verdict, "proved" | "refuted" | "unknown")
                .then(|| (name.to_string(), verdict.to_string()))
        })
        .collect()
}

/// The laws (not program hypotheses) a property's printed proof cites.
#[allow(dead_code)]
pub fn laws(args: &[&str], property: &str) -> std::collections::BTreeSet<String> {
    let mut a = args.to_vec();
    a.extend(["--trace", "--only", property]);
    let out = text(&ii_prove(&a).stdout);
    out.split(['[', ']', ',', ' ', ';'])
        .map(str::trim)
        .filter(|w| w.chars().next().is_some_and(|c| c.is_ascii_lowercase()) && w.contains('_'))
        .map(str::to_string)
        .collect()
}
