//! Helpers shared by the test modules: file listing, running the binary, and the random program generators with their reference interpreters.

pub mod il_gen;
pub mod il_ref;
pub mod ld_to_st;
pub mod plcopen_diff;
pub mod real_gen;
pub mod rng;
pub mod scan_eval;
pub mod sfc_gen;
pub mod st_gen;
pub mod st_gen_en;

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

/// Checks every `.EXT` file of `dir` (relative to the crate) fails to load (exit 2) with
/// the error its first two lines record, `// error: FRAGMENT` and `// at: LINE:COL`;
/// returns how many files there were.
#[allow(dead_code)]
pub fn check_rejects(dir: &str, ext: &str) -> usize {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join(dir);
    let files = files_with(&dir, ext);
    for f in &files {
        let body = std::fs::read_to_string(f).expect("readable");
        let mut lines = body.lines();
        let fragment =
            lines.next().and_then(|l| l.strip_prefix("// error: ")).expect("// error: line");
        let at = lines.next().and_then(|l| l.strip_prefix("// at: ")).expect("// at: line");
        let out = ii_prove(&["show", f.to_str().expect("utf-8 path")]);
        let stderr = text(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{}: {stderr}", f.display());
        assert!(stderr.contains(fragment), "{}: wanted `{fragment}` in\n{stderr}", f.display());
        let place = format!("{}:{at}", f.file_name().and_then(|n| n.to_str()).unwrap_or(""));
        assert!(stderr.contains(&place), "{}: wanted the place {place} in\n{stderr}", f.display());
    }
    files.len()
}

/// Where an oracle run writes its generated files: `II_ORACLE_KEEP=DIR` keeps them there,
/// else the temporary directory `temp` (created if missing).
#[allow(dead_code)]
pub fn oracle_work_dir(temp: &Path) -> PathBuf {
    let work = match std::env::var_os("II_ORACLE_KEEP") {
        Some(d) => PathBuf::from(d),
        None => temp.to_path_buf(),
    };
    std::fs::create_dir_all(&work).expect("work directory");
    work
}

/// The bounds `// trace: at most N lines` written right above `property NAME` in a
/// property file; a bound anywhere else fails the test.
pub fn trace_bounds(text: &str) -> std::collections::BTreeMap<String, usize> {
    let mut bounds = std::collections::BTreeMap::new();
    let mut pending = None;
    for line in text.lines().map(str::trim) {
        if let Some(n) = line.strip_prefix("// trace: at most ") {
            let n = n.trim_end_matches(" lines").trim_end_matches(" line");
            pending = Some(n.parse::<usize>().expect("`// trace: at most N lines`"));
        } else if let Some(rest) = line.strip_prefix("property ") {
            let name = rest.split(':').next().unwrap_or("").trim().to_string();
            if let Some(n) = pending.take() {
                bounds.insert(name, n);
            }
        } else if !line.is_empty() {
            assert!(pending.is_none(), "a trace bound must stand right above its property");
        }
    }
    bounds
}

/// The Structured Text or Instruction List `text` (shown as `file`) read, lowered and
/// compiled: the scan model and its equations, or the first error.
pub fn compile_text(
    file: &str,
    text: &str,
) -> Result<(ii_prove::program::Program, ii_prove::ladder::CompiledProgram), String> {
    let mut sources = ii_prove::diag::Sources::new();
    let file = sources.add(file, text.to_string());
    let unit = ii_prove::iec::read(&sources, file).map_err(|e| format!("{e:?}"))?;
    let lowered =
        ii_prove::iec::lower(&sources, &unit, None, None).map_err(|e| format!("{e:?}"))?;
    let compiled = ii_prove::program::compile(&lowered.program, &Default::default())
        .map_err(|e| format!("{e:?}"))?;
    Ok((lowered.program, compiled))
}
