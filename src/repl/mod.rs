//! The interactive prover (`ii-prove repl [FILE]`): state goals, prove them step by step or at once.
//!
//! A [`Session`] holds the free signals, the hypotheses, the claims proved so
//! far (citable as lemmas) and the goal being proved. Each command is one
//! entry of [`COMMANDS`] (name, usage, help); `help` is generated from it.
//! Proof steps are checked exactly as in proof scripts ([`crate::script`]),
//! and a finished goal is re-checked as a whole claim by the kernel, so what
//! `save` writes is accepted by `ii-prove check`.
//!
//! [`repl_with`] runs the loop over any input and output (the transcript
//! tests use it); [`run_interactive`] adds line editing, history, tab
//! completion and Ctrl-C handling with rustyline. A command ends at the end
//! of a line unless the line ends with an operator (`+ . = => , / : !`) or
//! leaves a parenthesis or bracket open; then the next line continues it.
//!
//! **Ctrl-C** while typing discards the current (possibly multi-line) input;
//! while a proof search runs (`prove`, `auto`, `[auto]`, a step) it abandons
//! that command and returns to the prompt at once (the search itself runs on
//! in the background until its time budget ends, and its result is dropped).
//! Ctrl-D (end of input) or `quit` leaves.

mod interactive;
mod refute;
pub mod session;

use std::io::{self, BufRead, Write};
use std::sync::atomic::{AtomicBool, Ordering};

pub use interactive::run_interactive;
pub use session::Session;

/// Set by Ctrl-C; a running command checks it and gives up.
pub static CANCEL: AtomicBool = AtomicBool::new(false);

/// Clears the cancellation flag (at the start of each command).
pub fn reset_cancel() {
    CANCEL.store(false, Ordering::SeqCst);
}

/// One REPL command: its name, how it is written, what it does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CommandInfo {
    /// The word that starts it.
    pub name: &'static str,
    /// How it is written.
    pub usage: &'static str,
    /// What it does (one line).
    pub help: &'static str,
}

/// Every command, in the order `help` lists them.
pub const COMMANDS: &[CommandInfo] = &[
    CommandInfo {
        name: "help",
        usage: "help [COMMAND]",
        help: "list the commands, or explain one",
    },
    CommandInfo { name: "input", usage: "input NAME, ...", help: "declare free signals" },
    CommandInfo {
        name: "assume",
        usage: "assume NAME: F = G  (or F => G)",
        help: "add a named hypothesis",
    },
    CommandInfo {
        name: "load",
        usage: "load FILE.ii",
        help: "read inputs, hypotheses and properties of a file and check its theorems and lemmas",
    },
    CommandInfo {
        name: "goal",
        usage: "goal [NAME:] F => G  (or F = G)",
        help: "start proving a goal step by step, from its left side",
    },
    CommandInfo {
        name: "prove",
        usage: "prove [[NAME:] F => G | PROPERTY]",
        help: "prove a goal, a loaded property or the current goal with the full prover",
    },
    CommandInfo {
        name: "apply",
        usage: "apply RULE [at PATH]",
        help: "rewrite the current term once with a law, hypothesis or lemma (PATH: child indices like 1.0)",
    },
    CommandInfo {
        name: "=",
        usage: "= TERM [RULE, ...]",
        help: "a calculational step to TERM justified by the cited rules (`auto` for the prover)",
    },
    CommandInfo {
        name: "=>",
        usage: "=> TERM [RULE, ...]",
        help: "an implication step to TERM justified by the cited rules",
    },
    CommandInfo {
        name: "auto",
        usage: "auto",
        help: "finish the current goal with the full prover",
    },
    CommandInfo {
        name: "undo",
        usage: "undo",
        help: "take back the last step (reopens a just-finished goal)",
    },
    CommandInfo {
        name: "trace",
        usage: "trace [all]",
        help: "show the current calculation, or the last finished proof (`all`: every lemma in full)",
    },
    CommandInfo {
        name: "show",
        usage: "show NAME",
        help: "show a signal's equations, or a law, hypothesis or lemma",
    },
    CommandInfo {
        name: "simulate",
        usage: "simulate TERM, ... [for DURATION] [with NAME=STEPS ...]",
        help: "draw terms over time; STEPS like 1@1s,0@6s (start value 0, or `1,0@3s`); defined signals follow their equations",
    },
    CommandInfo {
        name: "axioms",
        usage: "axioms [PREFIX]",
        help: "list the laws, hypotheses and lemmas (whose names start with PREFIX)",
    },
    CommandInfo {
        name: "save",
        usage: "save FILE.ii",
        help: "write the inputs, hypotheses and finished proofs as a proof script",
    },
    CommandInfo {
        name: "check",
        usage: "check FILE.ii ...",
        help: "check proof scripts as `ii-prove check` does",
    },
    CommandInfo { name: "quit", usage: "quit", help: "leave (also `exit` or Ctrl-D)" },
];

/// Adds a line to the input gathered so far; returns the whole command once it is
/// complete (no operator at its end, no open bracket).
pub fn gather(pending: &mut String, line: &str) -> Option<String> {
    if !pending.is_empty() {
        pending.push('\n');
    }
    pending.push_str(line);
    if incomplete(pending) { None } else { Some(std::mem::take(pending)) }
}

/// Does this input need another line (an operator at its end, an open bracket)?
pub fn incomplete(text: &str) -> bool {
    let mut depth: i64 = 0;
    for c in text.chars() {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            _ => {}
        }
    }
    if depth > 0 {
        return true;
    }
    let code = text.split("//").next().unwrap_or("").trim_end();
    let first_word = code.split_whitespace().next().unwrap_or("");
    if matches!(first_word, "save" | "load" | "check" | "help" | "show" | "axioms") {
        return false;
    }
    code.ends_with(['+', '.', '=', '>', ',', '/', ':', '!', '¬', '~', '·', '∨', '∧', '&', '|', '⇒'])
        && !code.is_empty()
}

/// Did a command's output report an error?
fn failed(text: &str) -> bool {
    text.lines().any(|l| l.starts_with("error"))
}

/// Runs the REPL over `input` and `output` until the input ends or `quit`; whether
/// some command failed (its output has an `error` line), so that a script of commands
/// can end with a failing status.
///
/// With `interactive == false` (scripts and transcripts) each command is echoed
/// after `> ` (continuation lines after `… `), so the output reads as a session.
/// With `interactive == true` a prompt is printed before each line instead.
pub fn repl_with(
    input: impl BufRead,
    mut output: impl Write,
    interactive: bool,
    file: Option<&str>,
) -> io::Result<bool> {
    let mut session = match Session::new() {
        Ok(s) => s,
        Err(e) => {
            write!(output, "{e}")?;
            return Ok(true);
        }
    };
    let mut any_failed = false;
    if let Some(path) = file {
        let text = session.execute(&format!("load {path}"));
        any_failed |= failed(&text);
        output.write_all(text.as_bytes())?;
    }
    let mut pending = String::new();
    let mut lines = input.lines();
    loop {
        if interactive {
            write!(output, "{}", if pending.is_empty() { "ii> " } else { "... " })?;
            output.flush()?;
        }
        let Some(line) = lines.next() else { break };
        let line = line?;
        if !interactive {
            writeln!(output, "{}{line}", if pending.is_empty() { "> " } else { "… " })?;
        }
        let Some(command) = gather(&mut pending, &line) else { continue };
        if matches!(command.trim(), "quit" | "exit") {
            break;
        }
        reset_cancel();
        let text = session.execute(&command);
        any_failed |= failed(&text);
        output.write_all(text.as_bytes())?;
        output.flush()?;
    }
    Ok(any_failed)
}
