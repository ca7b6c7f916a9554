//! Diagnostics: located errors and warnings from every front end, rendered in one place.
//!
//! Each front end owns a typed error enum whose variants carry [`Span`]s and
//! implements [`Report`]; [`Diagnostic`] wraps them all, and [`render`] is the
//! only function that turns one into text (file:line:col, the source line, a
//! caret, what was expected, a "did you mean"). Rendering uses
//! `codespan-reporting`.

use std::fmt::Write as _;
use std::ops::Range;
use std::sync::OnceLock;

use codespan_reporting::diagnostic as cs;
use codespan_reporting::files::{self, Files, SimpleFiles};
use codespan_reporting::term;

/// Identifies one source text in [`Sources`].
pub type FileId = usize;

/// A byte range in one source file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Span {
    /// The file the range is in.
    pub file: FileId,
    /// First byte.
    pub start: usize,
    /// One past the last byte.
    pub end: usize,
}

impl Span {
    /// A span of `range` in `file`.
    pub fn new(file: FileId, range: Range<usize>) -> Span {
        Span { file, start: range.start, end: range.end }
    }
    /// The smallest span covering both (same file assumed).
    pub fn to(self, other: Span) -> Span {
        Span { file: self.file, start: self.start.min(other.start), end: self.end.max(other.end) }
    }
    /// The byte range.
    pub fn range(self) -> Range<usize> {
        self.start..self.end
    }
}

/// Every source text the run has read, by [`FileId`].
#[derive(Default)]
pub struct Sources {
    files: SimpleFiles<String, String>,
    /// Per file, the text as the renderer shows it (see [`visible`]), made when a
    /// diagnostic first shows that file.
    shown: Vec<OnceLock<String>>,
}

/// [`Sources`] as the renderer reads them: the texts as [`visible`] shows them, with
/// the line index of the originals (the two have the same byte offsets).
struct Shown<'a>(&'a Sources);

impl<'a> Files<'a> for Shown<'a> {
    type FileId = FileId;
    type Name = &'a str;
    type Source = &'a str;

    fn name(&'a self, id: FileId) -> Result<&'a str, files::Error> {
        Ok(self.0.files.get(id)?.name().as_str())
    }
    fn source(&'a self, id: FileId) -> Result<&'a str, files::Error> {
        let text = self.0.files.get(id)?.source();
        let shown = self.0.shown.get(id).ok_or(files::Error::FileMissing)?;
        Ok(shown.get_or_init(|| visible(text)).as_str())
    }
    fn line_index(&'a self, id: FileId, byte_index: usize) -> Result<usize, files::Error> {
        self.0.files.line_index(id, byte_index)
    }
    fn line_range(&'a self, id: FileId, line_index: usize) -> Result<Range<usize>, files::Error> {
        self.0.files.line_range(id, line_index)
    }
}

impl Sources {
    /// An empty set of sources.
    pub fn new() -> Sources {
        Sources::default()
    }
    /// Registers a text under the name shown in messages (usually its path).
    pub fn add(&mut self, name: impl Into<String>, text: impl Into<String>) -> FileId {
        let (name, text) = (name.into(), text.into());
        self.shown.push(OnceLock::new());
        self.files.add(name, text)
    }
    /// The text of a file.
    pub fn text(&self, file: FileId) -> &str {
        self.files.get(file).map(|f| f.source().as_str()).unwrap_or("")
    }
    /// The name of a file.
    pub fn name(&self, file: FileId) -> &str {
        self.files.get(file).map(|f| f.name().as_str()).unwrap_or("?")
    }
    /// The 1-based line and column of a byte offset.
    pub fn line_col(&self, file: FileId, offset: usize) -> (usize, usize) {
        let line = self.files.line_index(file, offset).unwrap_or(0);
        let col = self.files.column_number(file, line, offset).unwrap_or(1);
        (line + 1, col)
    }
    /// `name:line:col` of the start of a span.
    pub fn location(&self, span: Span) -> String {
        let (line, col) = self.line_col(span.file, span.start);
        format!("{}:{line}:{col}", self.name(span.file))
    }
}

/// Control and zero-width format characters: they print as nothing.
fn is_invisible(c: char) -> bool {
    c.is_control()
        || matches!(c, '\u{ad}' | '\u{61c}' | '\u{180e}' | '\u{feff}')
        || ('\u{200b}'..='\u{200f}').contains(&c)
        || ('\u{2028}'..='\u{202e}').contains(&c)
        || ('\u{2060}'..='\u{206f}').contains(&c)
        || ('\u{fff9}'..='\u{fffb}').contains(&c)
        || ('\u{e0000}'..='\u{e007f}').contains(&c)
}

/// `text` with every character that prints as nothing (control and zero-width
/// format characters, which binary garbage is full of) replaced by a visible one
/// of the same UTF-8 length, so that byte offsets, columns and line breaks stay
/// those of the original and a caret under such a character is never zero
/// columns wide.
fn visible(text: &str) -> String {
    let mut chars = text.chars().peekable();
    let mut out = String::with_capacity(text.len());
    while let Some(c) = chars.next() {
        let line_break = c == '\n' || (c == '\r' && chars.peek() == Some(&'\n'));
        let invisible = !line_break && c != '\t' && is_invisible(c);
        out.push(match (invisible, c.len_utf8()) {
            (false, _) => c,
            (true, 1) => '?',
            (true, 2) => '\u{bf}',
            (true, 3) => '\u{fffd}',
            (true, _) => '\u{1d7d8}',
        });
    }
    out
}

/// A message with the characters [`visible`] replaces in sources written as
/// escapes (`\u{0}`), so that quoted input such as a token of binary garbage
/// reads unambiguously.
fn escape_invisible(message: &str) -> String {
    message
        .chars()
        .map(|c| match c {
            '\n' | '\t' => c.to_string(),
            c if is_invisible(c) => c.escape_unicode().to_string(),
            c => c.to_string(),
        })
        .collect()
}

/// Error or warning.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    /// The input is rejected.
    Error,
    /// The input is accepted, but the user should know.
    Warning,
}

/// What every typed error of a front end can say about itself.
pub trait Report {
    /// Where the problem is. `None` only for problems with no place in a file
    /// (for example a file that cannot be read).
    fn span(&self) -> Option<Span>;
    /// One line saying what is wrong.
    fn message(&self) -> String;
    /// The text under the caret, usually what was expected.
    fn label(&self) -> String {
        String::new()
    }
    /// Other places worth showing (for example the first definition of a duplicate).
    fn related(&self) -> Vec<(Span, String)> {
        Vec::new()
    }
    /// Notes and hints ("did you mean `L1_pump`?").
    fn notes(&self) -> Vec<String> {
        Vec::new()
    }
    /// Error or warning.
    fn severity(&self) -> Severity {
        Severity::Error
    }
}

/// A problem with a file that could not be read at all.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct IoError {
    /// The path as the user gave it.
    pub path: String,
    /// What the operating system said.
    pub reason: String,
}

impl Report for IoError {
    fn span(&self) -> Option<Span> {
        None
    }
    fn message(&self) -> String {
        format!("cannot read `{}`: {}", self.path, self.reason)
    }
}

/// Any diagnostic the tool can emit: whatever a front end, the `.ii` reader or the
/// proof checker reports, seen only through the [`Report`] trait (this module knows no
/// front end).
#[derive(Clone)]
pub struct Diagnostic(std::sync::Arc<dyn Report + Send + Sync>);

impl std::fmt::Debug for Diagnostic {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Diagnostic({:?}: {})", self.span(), self.message())
    }
}

impl Diagnostic {
    fn report(&self) -> &dyn Report {
        self.0.as_ref()
    }
    /// Where the problem is.
    pub fn span(&self) -> Option<Span> {
        self.report().span()
    }
    /// One line saying what is wrong.
    pub fn message(&self) -> String {
        self.report().message()
    }
    /// Error or warning.
    pub fn severity(&self) -> Severity {
        self.report().severity()
    }
}

impl<R: Report + Send + Sync + 'static> From<R> for Diagnostic {
    fn from(e: R) -> Self {
        Diagnostic(std::sync::Arc::new(e))
    }
}

/// How to draw a rendered diagnostic.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RenderStyle {
    /// Use only ASCII characters in the frame.
    pub ascii: bool,
}

/// Renders a diagnostic as text: `error: …`, then `┌─ file:line:col`, the line and a caret.
pub fn render(diag: &Diagnostic, sources: &Sources, style: RenderStyle) -> String {
    render_report(diag.report(), sources, style)
}

/// Renders anything that implements [`Report`]; [`render`] is the usual entry point.
pub fn render_report(report: &dyn Report, sources: &Sources, style: RenderStyle) -> String {
    let mut out = match report.severity() {
        Severity::Error => cs::Diagnostic::error(),
        Severity::Warning => cs::Diagnostic::warning(),
    }
    .with_message(escape_invisible(&report.message()));
    let mut labels = Vec::new();
    if let Some(span) = report.span() {
        labels.push(
            cs::Label::primary(span.file, span.range())
                .with_message(escape_invisible(&report.label())),
        );
    }
    for (span, text) in report.related() {
        labels.push(
            cs::Label::secondary(span.file, span.range()).with_message(escape_invisible(&text)),
        );
    }
    out = out
        .with_labels(labels)
        .with_notes(report.notes().iter().map(|n| escape_invisible(n)).collect());
    let mut config = term::Config::default();
    if style.ascii {
        config.chars = term::Chars::ascii();
    }
    match term::emit_into_string(&config, &Shown(sources), &out) {
        Ok(text) => text,
        Err(_) => {
            // A span outside its file is a bug in a front end; still say something useful.
            let mut text = format!("error: {}\n", report.message());
            for note in report.notes() {
                let _ = writeln!(text, "  = {note}");
            }
            text
        }
    }
}

/// The closest name to `wanted` among `candidates`, if one is close enough to suggest.
pub fn did_you_mean<'a>(
    wanted: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<&'a str> {
    candidates
        .into_iter()
        .map(|c| (strsim::jaro_winkler(wanted, c), c))
        .filter(|(score, _)| *score > 0.8)
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, c)| c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn io_errors_render_without_a_location() {
        let sources = Sources::new();
        let diag = Diagnostic::from(IoError {
            path: "missing.ii".into(),
            reason: "No such file or directory".into(),
        });
        let text = render(&diag, &sources, RenderStyle::default());
        assert!(text.contains("cannot read `missing.ii`"), "{text}");
    }

    #[test]
    fn suggestions_pick_the_nearest_name() {
        let names = ["L1_pump", "L2_pump", "Out_valve"];
        assert_eq!(did_you_mean("L1_pmup", names), Some("L1_pump"));
        assert_eq!(did_you_mean("zzz", names), None);
    }
}
