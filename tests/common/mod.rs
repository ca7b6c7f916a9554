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
