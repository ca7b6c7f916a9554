//! Every file under `tests/data/parse_err/` must be rejected with a located, rendered error.
//!
//! The first line of each file is `// error: <fragment>`; the rendered text must
//! contain the fragment, `file:line:col` and a caret line. A new case is a new file.

use std::path::{Path, PathBuf};

use ii_prove::diag::{Diagnostic, RenderStyle, Sources, render};
use ii_prove::syntax::{Lookup, Scope, parse_document};

/// A small program: `Out_valve`, `T1.Q`, `T1.ET`; `T1` is ambiguous; its hypotheses
/// are `R1` and `R2`.
struct TestProgram;

impl Scope for TestProgram {
    fn lookup(&self, name: &str) -> Lookup {
        match name {
            "T1" => Lookup::Ambiguous(vec!["T1.Q".into(), "T1.ET".into()]),
            n if self.names().iter().any(|m| m == n) => Lookup::Signal(n.into()),
            _ => Lookup::Unknown,
        }
    }
    fn names(&self) -> Vec<String> {
        vec!["Out_valve".into(), "T1.Q".into(), "T1.ET".into()]
    }
    fn hypothesis_names(&self) -> Vec<String> {
        vec!["R1".into(), "R2".into()]
    }
}

fn cases() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/parse_err");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .expect("tests/data/parse_err exists")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "ii"))
        .collect();
    files.sort();
    files
}

#[test]
fn every_error_case_is_rejected_with_a_located_message() {
    let files = cases();
    assert!(files.len() >= 20, "only {} error cases", files.len());
    let mut failures = Vec::new();
    for path in files {
        let text = std::fs::read_to_string(&path).expect("readable");
        let expected = text
            .lines()
            .next()
            .and_then(|l| l.strip_prefix("// error:"))
            .map(str::trim)
            .unwrap_or_else(|| panic!("{}: first line must be `// error: ...`", path.display()))
            .to_string();
        let name = format!(
            "tests/data/parse_err/{}",
            path.file_name().and_then(|f| f.to_str()).unwrap_or("?")
        );
        let mut sources = Sources::new();
        let file = sources.add(name.clone(), text);
        let errors = match parse_document(&sources, file, &TestProgram) {
            Ok(_) => {
                failures.push(format!("{name}: was accepted"));
                continue;
            }
            Err(errors) => errors,
        };
        let rendered: String = errors
            .into_iter()
            .map(|e| render(&Diagnostic::from(e), &sources, RenderStyle { ascii: true }))
            .collect();
        let located = rendered.contains(&format!("{name}:")) && rendered.contains('^');
        if !located || !rendered.contains(&expected) {
            failures.push(format!("{name}: expected `{expected}` in\n{rendered}"));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}

#[test]
fn several_errors_are_reported_at_once() {
    let text = "input f, g\nproperty A: f/g => f\nproperty B: 5s/f/2s => f\nproperty C: zz => f\n";
    let mut sources = Sources::new();
    let file = sources.add("several.ii", text);
    let errors = parse_document(&sources, file, &TestProgram).unwrap_err();
    assert_eq!(errors.len(), 3, "{errors:?}");
    let rendered = render(&Diagnostic::from(errors[2].clone()), &sources, RenderStyle::default());
    assert!(rendered.contains("several.ii:4:13"), "{rendered}");
    assert!(rendered.contains("Out_valve"), "{rendered}");
}
