//! Line editing for the REPL: rustyline with history, tab completion and Ctrl-C handling.

use std::borrow::Cow;
use std::io::{self, Write};
use std::path::PathBuf;
use std::sync::atomic::Ordering;

use rustyline::completion::{Completer, FilenameCompleter};
use rustyline::error::ReadlineError;
use rustyline::highlight::Highlighter;
use rustyline::hint::Hinter;
use rustyline::history::DefaultHistory;
use rustyline::validate::Validator;
use rustyline::{Config, Editor, Helper};

use super::{CANCEL, Session, gather, reset_cancel};

/// Completes command names at the start of a line, file names after `load` and
/// `save`, and signal, law, hypothesis and lemma names elsewhere.
struct Names {
    commands: Vec<String>,
    names: Vec<String>,
    files: FilenameCompleter,
}

/// The commands whose argument is a file.
const FILE_COMMANDS: &[&str] = &["load", "save"];

impl Completer for Names {
    type Candidate = String;

    fn complete(
        &self,
        line: &str,
        pos: usize,
        ctx: &rustyline::Context<'_>,
    ) -> rustyline::Result<(usize, Vec<String>)> {
        let before = line.get(..pos).unwrap_or(line);
        let command = before.split_whitespace().next().unwrap_or("");
        if FILE_COMMANDS.contains(&command) && before.trim_start().len() > command.len() {
            let (start, pairs) = self.files.complete(line, pos, ctx)?;
            return Ok((start, pairs.into_iter().map(|p| p.replacement).collect()));
        }
        let start = before
            .char_indices()
            .rev()
            .find(|(_, c)| !(c.is_ascii_alphanumeric() || *c == '_'))
            .map_or(0, |(i, c)| i + c.len_utf8());
        let word = &before[start..];
        let first = before[..start].trim().is_empty();
        let pool = if first { &self.commands } else { &self.names };
        let mut found: Vec<String> = pool.iter().filter(|n| n.starts_with(word)).cloned().collect();
        found.sort();
        found.dedup();
        Ok((start, found))
    }
}

impl Hinter for Names {
    type Hint = String;
}

impl Highlighter for Names {
    fn highlight_prompt<'b, 's: 'b, 'p: 'b>(
        &'s self,
        prompt: &'p str,
        _default: bool,
    ) -> Cow<'b, str> {
        Cow::Borrowed(prompt)
    }
}

impl Validator for Names {}

impl Helper for Names {}

/// Where the history is kept: `$HOME/.ii-prove-history`, else `.ii-prove-history` here.
pub fn history_path() -> PathBuf {
    match std::env::var_os("HOME") {
        Some(home) => PathBuf::from(home).join(".ii-prove-history"),
        None => PathBuf::from(".ii-prove-history"),
    }
}

/// The REPL on a terminal: `ii> ` prompt, `... ` for continued lines, history,
/// tab completion. Ctrl-C discards the current input, or abandons a running
/// command; Ctrl-D leaves.
pub fn run_interactive(file: Option<&str>) -> io::Result<()> {
    let mut session = Session::new().map_err(io::Error::other)?;
    // Ctrl-C during a command sets the flag; the command gives up and returns.
    let _ = ctrlc::set_handler(|| CANCEL.store(true, Ordering::SeqCst));
    // Tab lists the candidates when there are several.
    let config = Config::builder()
        .auto_add_history(false)
        .completion_type(rustyline::CompletionType::List)
        .build();
    let mut editor: Editor<Names, DefaultHistory> =
        Editor::with_config(config).map_err(io::Error::other)?;
    let commands: Vec<String> = super::COMMANDS.iter().map(|c| c.name.to_string()).collect();
    let names = session.completion_names();
    editor.set_helper(Some(Names { commands, names, files: FilenameCompleter::new() }));
    let history = history_path();
    let _ = editor.load_history(&history);
    let mut stdout = io::stdout();
    println!("ii-prove REPL: `help` lists the commands; Ctrl-D leaves.");
    if let Some(path) = file {
        print!("{}", session.execute(&format!("load {path}")));
    }
    let mut pending = String::new();
    loop {
        let prompt = if pending.is_empty() { "ii> " } else { "... " };
        match editor.readline(prompt) {
            Ok(line) => {
                let Some(command) = gather(&mut pending, &line) else { continue };
                let _ = editor.add_history_entry(command.replace('\n', " ").as_str());
                if matches!(command.trim(), "quit" | "exit") {
                    break;
                }
                reset_cancel();
                let text = session.execute(&command);
                print!("{text}");
                stdout.flush()?;
                if let Some(helper) = editor.helper_mut() {
                    helper.names = session.completion_names();
                }
            }
            Err(ReadlineError::Interrupted) => {
                if !pending.is_empty() {
                    println!("(input discarded)");
                }
                pending.clear();
            }
            Err(ReadlineError::Eof) => break,
            Err(e) => return Err(io::Error::other(e)),
        }
    }
    let _ = editor.save_history(&history);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn complete(line: &str) -> Vec<String> {
        let names = Names {
            commands: vec!["load".into(), "lemma".into()],
            names: vec!["L1_pump".into()],
            files: FilenameCompleter::new(),
        };
        let history = DefaultHistory::new();
        let ctx = rustyline::Context::new(&history);
        names.complete(line, line.len(), &ctx).expect("completes").1
    }

    #[test]
    fn tab_completes_file_names_after_load_and_save() {
        let dir = std::env::temp_dir().join(format!("ii-prove-complete-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("water_plant.ld"), "").unwrap();
        let base = dir.display().to_string();
        for command in ["load", "save"] {
            let found = complete(&format!("{command} {base}/water_p"));
            assert!(found.iter().any(|f| f.ends_with("water_plant.ld")), "{command}: {found:?}");
        }
        // Elsewhere: commands first, names after.
        assert_eq!(complete("lo"), vec!["load".to_string()]);
        assert_eq!(complete("goal L1_p"), vec!["L1_pump".to_string()]);
        let _ = std::fs::remove_dir_all(&dir);
    }
}
