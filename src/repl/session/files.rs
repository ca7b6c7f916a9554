//! The session's files: `load` (a property or proof file, or a program whose compiled
//! rungs become hypotheses), `save` (the finished proofs as a script that `ii-prove
//! check` accepts) and `check`.

use super::Session;
use super::render::{counted, ms};
use crate::diag::{Diagnostic, RenderStyle, Span, render};
use crate::report::{self, Options};
use crate::script;
use crate::syntax::{self, Document, Notation, document_to_string};

/// `target` as a path relative to the folder of `file` (both made absolute; `target`
/// unchanged when they share no root, as on two Windows drives).
fn relative_to_file(target: &str, file: &str) -> String {
    use std::path::{Component, Path, PathBuf};
    let absolute = |p: &Path| {
        p.canonicalize().or_else(|_| std::path::absolute(p)).unwrap_or_else(|_| p.to_path_buf())
    };
    let target_abs = absolute(Path::new(target));
    let folder = Path::new(file).parent().filter(|p| !p.as_os_str().is_empty());
    let base = absolute(folder.unwrap_or(Path::new(".")));
    let (t, b): (Vec<Component>, Vec<Component>) =
        (target_abs.components().collect(), base.components().collect());
    let common = t.iter().zip(&b).take_while(|(x, y)| x == y).count();
    if common == 0 {
        return target.to_string();
    }
    let mut relative = PathBuf::new();
    for _ in common..b.len() {
        relative.push("..");
    }
    for c in &t[common..] {
        relative.push(c);
    }
    relative.display().to_string().replace('\\', "/")
}

impl Session {
    pub(super) fn load(&mut self, rest: &str) -> String {
        let path = rest.trim().trim_matches('"');
        if path.is_empty() {
            return "error: expected `load FILE.ii`\n".into();
        }
        if report::is_ladder(path) {
            return self.load_program(path);
        }
        let file = match report::read_source(&mut self.sources, path) {
            Ok(f) => f,
            Err(d) => return render(&d, &self.sources, RenderStyle::default()),
        };
        let mut out = String::new();
        if let Some((program, _)) = script::program_header(&self.sources, file) {
            let program = script::program_path(path, &program).display().to_string();
            // The session keeps the program's absolute path.
            let absolute = std::fs::canonicalize(&program)
                .map_or_else(|_| program.clone(), |p| p.display().to_string());
            let already = self.program.as_ref().is_some_and(|(p, _)| *p == absolute);
            if !already {
                // The elapsed times the file names are computed (`[T1.ET < T#2s]`).
                let wanted = report::elapsed_named(self.sources.text(file));
                out.push_str(&self.load_program_wanting(&program, wanted));
                if self.program.as_ref().is_none_or(|(p, _)| *p != absolute) {
                    return out;
                }
            }
        }
        let doc = match syntax::parse_properties(&self.sources, file, self.scope()) {
            Ok(d) => d,
            Err(errors) => return format!("{out}{}", self.syntax_errors(errors)),
        };
        if let Err(e) = self.define_atoms() {
            return format!("{out}error: {e}\n");
        }
        for (name, _) in &doc.inputs {
            if !self.inputs.contains(name) {
                self.inputs.push(name.clone());
            }
        }
        let mut hyps = 0;
        for a in &doc.assumptions {
            if let Err(e) = self.fresh_name(&a.name) {
                out.push_str(&format!("error: {e}\n"));
                continue;
            }
            self.assumptions.push(a.clone());
            hyps += 1;
        }
        if let Err(e) = self.rebuild() {
            return format!("{out}error: the hypotheses are not accepted: {e}\n");
        }
        for p in &doc.properties {
            self.properties.retain(|q| q.name != p.name);
            self.properties.push(p.clone());
        }
        let mut checked = 0;
        for claim in &doc.claims {
            match self.checker.check_claim(claim) {
                Ok(c) => {
                    checked += 1;
                    out.push_str(&format!("ok {}  ({})\n", c.name, ms(c.time)));
                    self.done.push(claim.clone());
                }
                Err(e) => {
                    out.push_str(&render(
                        &Diagnostic::from(e),
                        &self.sources,
                        RenderStyle::default(),
                    ));
                }
            }
        }
        let props: Vec<&str> = doc.properties.iter().map(|p| p.name.as_str()).collect();
        out.push_str(&format!(
            "loaded {path}: {}, {}, {}{}, {} checked\n",
            counted(doc.inputs.len(), "input", "inputs"),
            counted(hyps, "hypothesis", "hypotheses"),
            counted(props.len(), "property", "properties"),
            if props.is_empty() { String::new() } else { format!(" ({})", props.join(", ")) },
            counted(checked, "claim", "claims"),
        ));
        out
    }

    /// `load PROGRAM.ld`: its compiled rungs become hypotheses, its signals names.
    fn load_program(&mut self, path: &str) -> String {
        self.load_program_wanting(path, Default::default())
    }

    /// [`Session::load_program`], computing the elapsed time of the timer instances
    /// `wanted` names as if the program read it.
    fn load_program_wanting(
        &mut self,
        path: &str,
        wanted: std::collections::BTreeSet<String>,
    ) -> String {
        if self.program.is_some() {
            // Another program: the session starts over on it (the goals, proofs and
            // properties were about the first), unless it does not load.
            let mut fresh = match Session::new() {
                Ok(s) => s,
                Err(e) => return format!("error: {e}\n"),
            };
            fresh.notation = self.notation;
            let out = fresh.load_program_wanting(path, wanted);
            if fresh.program.is_none() {
                return out;
            }
            *self = fresh;
            return format!(
                "the session starts over on {path}: the previous program's goals, proofs and properties are put away\n{out}"
            );
        }
        let selection = crate::ladder::plcopen::Selection { elapsed: wanted, ..Default::default() };
        let options = crate::ladder::CompileOptions::default();
        let loaded = match report::load_program_with(&mut self.sources, path, &options, &selection)
        {
            Ok(l) => l,
            Err(diagnostics) => {
                return diagnostics
                    .iter()
                    .map(|d| render(d, &self.sources, RenderStyle::default()))
                    .collect();
            }
        };
        let compiled = loaded.compiled;
        for h in compiled.axioms() {
            if let Err(e) = self.fresh_name(&h.name) {
                return format!("error: {e}\n");
            }
        }
        let absolute = std::fs::canonicalize(path)
            .map_or_else(|_| path.to_string(), |p| p.display().to_string());
        let (count, signals) = (compiled.hypotheses.len(), compiled.signals.len());
        self.program_hypotheses = compiled.axioms();
        self.program = Some((absolute, compiled));
        self.reference = Some(loaded.reference);
        if let Err(e) = self.rebuild() {
            self.program = None;
            self.reference = None;
            self.program_hypotheses.clear();
            let _ = self.rebuild();
            return format!("error: the program's hypotheses are not accepted: {e}\n");
        }
        let mut out = String::new();
        for w in &loaded.warnings {
            out.push_str(&format!("warning: {w}\n"));
        }
        out.push_str(&format!(
            "loaded program {path}: {} (`axioms L` lists them), {}\n",
            counted(count, "hypothesis", "hypotheses"),
            counted(signals, "signal", "signals")
        ));
        out
    }

    pub(super) fn save(&mut self, rest: &str) -> String {
        let path = rest.trim().trim_matches('"');
        if path.is_empty() {
            return "error: expected `save FILE.ii`\n".into();
        }
        if self.done.is_empty() {
            return "error: no finished proofs to save\n".into();
        }
        let span = Span::new(0, 0..0);
        // The script names its program relative to itself, so the two can move together.
        let program = self.program.as_ref().map(|(p, _)| (relative_to_file(p, path), span));
        let doc = Document {
            file: 0,
            program,
            inputs: self.inputs.iter().map(|n| (n.clone(), span)).collect(),
            delays: Vec::new(),
            assumptions: self.assumptions.clone(),
            properties: Vec::new(),
            laws: Vec::new(),
            claims: self.done.clone(),
        };
        let text = format!(
            "// Saved by the ii-prove REPL; re-check with `ii-prove check {path}`.\n{}",
            document_to_string(&doc, Notation::Ascii)
        );
        match std::fs::write(path, text) {
            Ok(()) => format!("saved {} to {path}\n", counted(self.done.len(), "proof", "proofs")),
            Err(e) => format!("error: cannot write `{path}`: {e}\n"),
        }
    }

    pub(super) fn check(&self, rest: &str) -> String {
        let paths: Vec<String> = rest.split_whitespace().map(str::to_string).collect();
        if paths.is_empty() {
            return "error: expected `check FILE.ii ...`\n".into();
        }
        let run = script::check_files(&paths, &Options::default());
        let mut out: String = run.errors.concat();
        out.push_str(&script::render_text(&run));
        out
    }
}
