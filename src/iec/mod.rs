//! IEC 61131-3 textual languages (3rd edition, as matiec accepts them): Structured Text and Instruction List files and PLCopen `<ST>`/`<IL>` bodies read into a typed AST with spans.
//!
//! [`parse_file`] reads a whole `.st`/`.il` file (POUs, `TYPE` blocks, configurations;
//! each POU body is ST or IL, decided by its first line); [`parse_st_body`] and
//! [`parse_il_body`] read the text of a PLCopen XML body in place, decoding XML entities
//! and CDATA markers while every span stays on the raw bytes of the file. Parsing never
//! panics: every problem is an [`StError`] saying what was expected where, naming the
//! construct left open, and offering a "did you mean" for a near miss. [`print`] prints
//! an AST back as text that parses to the same AST.
#![warn(missing_docs)]

pub mod ast;
pub mod il;
pub mod lexer;
pub mod parser;
pub mod print;

use std::ops::Range;

use crate::diag::{FileId, Report, Sources, Span};

pub use ast::*;
pub use print::print;

/// A located syntax error in Structured Text or Instruction List.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StError {
    /// Where.
    pub span: Span,
    /// What is wrong, saying what was expected.
    pub message: String,
    /// The text under the caret.
    pub label: String,
    /// Other places that matter (the `IF` a missing `END_IF` would close).
    pub related: Vec<(Span, String)>,
    /// Hints ("did you mean `END_IF`?").
    pub notes: Vec<String>,
}

impl StError {
    /// An error at `span`.
    pub fn new(span: Span, message: impl Into<String>, label: impl Into<String>) -> StError {
        StError {
            span,
            message: message.into(),
            label: label.into(),
            related: Vec::new(),
            notes: Vec::new(),
        }
    }

    /// The same error, also showing `span` with `text`.
    pub fn with_related(mut self, span: Span, text: impl Into<String>) -> StError {
        self.related.push((span, text.into()));
        self
    }

    /// The same error with a note.
    pub fn with_note(mut self, note: impl Into<String>) -> StError {
        self.notes.push(note.into());
        self
    }

    /// The same error with "did you mean `x`?" when `word` is close to one of `candidates`.
    pub fn suggest<'a>(self, word: &str, candidates: impl IntoIterator<Item = &'a str>) -> StError {
        let upper = word.to_ascii_uppercase();
        match crate::diag::did_you_mean(&upper, candidates) {
            Some(best) if !best.eq_ignore_ascii_case(word) => {
                self.with_note(format!("did you mean `{best}`?"))
            }
            _ => self,
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
        self.related.clone()
    }
    fn notes(&self) -> Vec<String> {
        self.notes.clone()
    }
}

/// Reads a whole `.st` or `.il` file: POUs, `TYPE` blocks and configurations.
pub fn parse_file(sources: &Sources, file: FileId) -> Result<StFile, Vec<StError>> {
    let text = sources.text(file);
    let toks = lexer::lex(file, text, 0..text.len(), false).map_err(|e| vec![e])?;
    parser::Parser::new(toks, file).file()
}

/// Reads the statements of a PLCopen `<ST>` body whose text is at byte `range` of `file`
/// (XML entities and CDATA markers decoded; spans point into the file).
pub fn parse_st_body(
    sources: &Sources,
    file: FileId,
    range: Range<usize>,
) -> Result<Vec<Stmt>, Vec<StError>> {
    let toks = lexer::lex(file, sources.text(file), range, true).map_err(|e| vec![e])?;
    parser::Parser::new(toks, file).st_body()
}

/// Reads the lines of a PLCopen `<IL>` body whose text is at byte `range` of `file`
/// (XML entities and CDATA markers decoded; spans point into the file).
pub fn parse_il_body(
    sources: &Sources,
    file: FileId,
    range: Range<usize>,
) -> Result<Vec<IlLine>, Vec<StError>> {
    let toks = lexer::lex(file, sources.text(file), range, true).map_err(|e| vec![e])?;
    parser::Parser::new(toks, file).il_body()
}
