//! The IEC 61131-3 text languages, as matiec accepts them: Structured Text and Instruction List files (`.st`, `.il`) read into one AST ([`parser`]; a POU's body is ST or IL) and lowered into the scan model ([`lower`]).
//!
//! The reader never panics; every problem is an [`StError`] with a span into the
//! source and, for a misspelt keyword, a "did you mean". What the scan model cannot
//! express yet (loops, `CASE`, user function blocks, a timer called inside a branch or on
//! an IL line a jump may skip, a backward jump) is refused with a located error naming the
//! construct; what the algebra cannot express (integer comparisons, counters, the pulse
//! timer) becomes an unconstrained signal with a warning, as for the ladder languages.
#![warn(missing_docs)]

pub mod ast;
pub mod lexer;
pub mod literal;
pub mod lower;
pub mod parser;
pub mod sfc;

use crate::diag::{Report, Severity, Sources, Span};

pub use lower::{Lowered, lower, lower_under_en, lower_wanting};

/// A Structured Text error (or, with [`Severity::Warning`], a note), located.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StError {
    /// Where.
    pub span: Span,
    /// What is wrong.
    pub message: String,
    /// The label under the caret.
    pub label: String,
    /// Another place that matters (the `IF` a missing `END_IF` would close).
    pub related: Option<Box<(Span, String)>>,
    /// Hints (did you mean).
    pub notes: Vec<String>,
    /// Error or warning.
    pub severity: Severity,
}

impl StError {
    /// An error at `span`.
    pub fn new(span: Span, message: impl Into<String>, label: impl Into<String>) -> StError {
        StError {
            span,
            message: message.into(),
            label: label.into(),
            related: None,
            notes: Vec::new(),
            severity: Severity::Error,
        }
    }

    /// A warning at `span`.
    pub fn warning(span: Span, message: impl Into<String>) -> StError {
        StError {
            severity: Severity::Warning,
            ..StError::new(span, message, "not modelled exactly")
        }
    }
}

impl Report for StError {
    fn span(&self) -> Option<Span> {
        Some(self.span)
    }
    fn message(&self) -> String {
        self.message.clone()
    }
    fn label(&self) -> String {
        self.label.clone()
    }
    fn related(&self) -> Vec<(Span, String)> {
        self.related.iter().map(|r| (**r).clone()).collect()
    }
    fn notes(&self) -> Vec<String> {
        self.notes.clone()
    }
    fn severity(&self) -> Severity {
        self.severity
    }
}

/// Whether `text` looks like Structured Text or Instruction List: its first word after comments is
/// `PROGRAM`, `FUNCTION_BLOCK`, `FUNCTION`, `CONFIGURATION` or `TYPE`, in capitals (a
/// property file's lower-case `program` header is not one).
pub fn is_st(text: &str) -> bool {
    // Only the first token counts: lex a prefix, longer until that token lies wholly
    // inside it (a comment or a token cut by the prefix's end makes it longer), so that
    // a large file of another language costs a few kilobytes, not a lexing of it all.
    let mut len = 4096;
    loop {
        let end = (len..=text.len()).find(|&e| text.is_char_boundary(e)).unwrap_or(text.len());
        let whole = end == text.len();
        let first = match lexer::lex(0, text, 0..end) {
            Ok(toks) => toks.into_iter().find(|t| !matches!(t.tok, lexer::Tok::Assert(..))),
            Err(_) if whole => return false,
            Err(_) => None,
        };
        match first {
            Some(t) if whole || t.span.end < end => {
                return matches!(&t.tok, lexer::Tok::Ident(w) if ["PROGRAM", "FUNCTION_BLOCK", "FUNCTION", "CONFIGURATION", "TYPE"].contains(&w.as_str()));
            }
            None if whole => return false,
            _ => len = end * 4,
        }
    }
}

/// Reads a `.st` or `.il` file of `sources`.
pub fn read(sources: &Sources, file: usize) -> Result<ast::Unit, Vec<StError>> {
    parser::parse_unit(file, sources.text(file)).map_err(|e| vec![e])
}

#[cfg(test)]
mod tests {
    use super::is_st;

    #[test]
    fn the_first_word_decides_wherever_the_prefix_ends() {
        let comment = format!("(* {} *)\n", "x".repeat(10_000));
        assert!(is_st(&format!("{comment}PROGRAM p\nEND_PROGRAM\n")));
        // A keyword cut by the first prefix's end is read whole.
        for pad in 4090..4100 {
            let text = format!("{}PROGRAM p END_PROGRAM", " ".repeat(pad));
            assert!(is_st(&text), "padding {pad}");
            let text = format!("{}PROGRAMME p", " ".repeat(pad));
            assert!(!is_st(&text), "padding {pad}");
        }
        assert!(!is_st("LDmicro0.1\nCYCLE=10000\n"));
        assert!(!is_st("program water\n"));
        assert!(!is_st(""));
        // An unterminated comment is not a program.
        assert!(!is_st(&format!("(* {}", "x".repeat(10_000))));
    }
}
