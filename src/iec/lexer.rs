//! The Structured Text lexer: IEC 61131-3 tokens with their byte spans (keywords case-insensitive, comments `(* … *)` (not nesting, as matiec reads them) and `//`, pragmas `{ … }` refused (matiec runs their text as C), `//#ASSERT` and `(*#ASSERT … *)` kept as property tokens).

use super::StError;
use crate::diag::Span;

/// A token's kind.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Tok {
    /// An identifier or keyword, as written.
    Ident(String),
    /// An integer literal (`2#`, `8#`, `16#` bases, `_` separators).
    Int(i128),
    /// A duration literal, in µs.
    Time(u64),
    /// A typed literal `TYPE#value` that is not a duration (`BOOL#1`, `INT#5`), as written.
    Typed(String),
    /// A real literal, as written.
    Real(String),
    /// A string literal, as written.
    Str(String),
    /// A direct address (`%IX0.1`), as written.
    Direct(String),
    /// Punctuation and operators: `:=`, `=>`, `<=`, `>=`, `<>`, `**`, `..`, and single characters.
    Sym(&'static str),
    /// A property comment: the text after `#ASSERT`, and where it starts.
    Assert(String, usize),
    /// The end of the text.
    Eof,
}

/// A token and where it is.
#[derive(Clone, Debug)]
pub struct Token {
    /// What it is.
    pub tok: Tok,
    /// Where it is.
    pub span: Span,
    /// Whether a line break (outside comments) comes before it: Instruction List is
    /// line-based.
    pub line_start: bool,
}

impl Token {
    /// Whether the token is the keyword `kw` (case-insensitive).
    pub fn is_kw(&self, kw: &str) -> bool {
        matches!(&self.tok, Tok::Ident(s) if s.eq_ignore_ascii_case(kw))
    }

    /// Whether the token is the symbol `sym`.
    pub fn is_sym_tok(&self, sym: &str) -> bool {
        matches!(self.tok, Tok::Sym(s) if s == sym)
    }
}

const SYMS: &[&str] = &[
    ":=", "=>", "<=", ">=", "<>", "**", "..", "(", ")", "[", "]", ",", ";", ":", ".", "+", "-",
    "*", "/", "=", "<", ">", "&", "#",
];

/// Splits `text[range]` (of file `file`) into tokens. Never panics.
pub fn lex(file: usize, text: &str, range: std::ops::Range<usize>) -> Result<Vec<Token>, StError> {
    let bytes = text.as_bytes();
    let end = range.end.min(text.len());
    let mut i = range.start.min(end);
    let mut out = Vec::new();
    // Offsets of the line breaks outside comments.
    let mut breaks: Vec<usize> = Vec::new();
    let span = |a: usize, b: usize| Span::new(file, a..b);
    while i < end {
        let c = bytes[i];
        if c.is_ascii_whitespace() {
            if c == b'\n' {
                breaks.push(i);
            }
            i += 1;
            continue;
        }
        let rest = &text[i..end];
        if rest.starts_with("//") {
            let line_end = rest.find('\n').map_or(end, |n| i + n);
            let body = &text[i + 2..line_end];
            if let Some(p) = body.trim_start().strip_prefix("#ASSERT") {
                let at = line_end - p.len();
                out.push(Token {
                    tok: Tok::Assert(p.to_string(), at),
                    span: span(i, line_end),
                    line_start: false,
                });
            }
            i = line_end;
            continue;
        }
        if rest.starts_with("(*") {
            let (close, depth_end) = comment_end(text, i, end);
            let Some(close) = close else {
                return Err(StError::new(
                    span(i, i + 2),
                    "unterminated comment",
                    "this `(*` is never closed by `*)`",
                ));
            };
            let body = &text[i + 2..close];
            if let Some(p) = body.trim_start().strip_prefix("#ASSERT") {
                let at = close - p.len();
                out.push(Token {
                    tok: Tok::Assert(p.to_string(), at),
                    span: span(i, depth_end),
                    line_start: false,
                });
            }
            i = depth_end;
            continue;
        }
        if c == b'{' {
            // matiec copies a pragma's text into the C it generates (`generate_c_base.cc`,
            // `pragma_c`), or leaves code out (`{disable code generation}`): what the
            // program does then is not in its text.
            let end = rest.find('}').map_or(i + 1, |n| i + n + 1);
            return Err(StError::new(
                span(i, end),
                "a pragma, which ii-prove does not model",
                "matiec copies a pragma's text into the C code it generates (or, for `{disable code generation}`, leaves code out), so the program does what ii-prove cannot read; remove the pragma or check this program with another tool",
            ));
        }
        if c.is_ascii_alphabetic() || c == b'_' {
            let n = rest
                .find(|ch: char| !(ch.is_ascii_alphanumeric() || ch == '_'))
                .unwrap_or(rest.len());
            let word = &rest[..n];
            // Typed and duration literals: `T#5s`, `TIME#1h`, `INT#5`, `BOOL#TRUE`, `16#FF` below.
            if rest[n..].starts_with('#') {
                let lit_end = rest[n + 1..]
                    .find(|ch: char| {
                        !(ch.is_ascii_alphanumeric() || ch == '_' || ch == '.' || ch == '-')
                    })
                    .map_or(rest.len(), |m| n + 1 + m);
                let lit = &rest[..lit_end];
                let upper = word.to_ascii_uppercase();
                let tok = if ["T", "TIME", "LT", "LTIME"].contains(&upper.as_str()) {
                    match super::literal::parse_duration(lit) {
                        Some(us) => Tok::Time(us),
                        None => {
                            return Err(StError::new(
                                span(i, i + lit_end),
                                format!("`{lit}` is not a duration ii-prove reads"),
                                "expected a duration like `T#5s`, `T#1h2m`, `T#250ms` (non-negative, whole microseconds)",
                            ));
                        }
                    }
                } else {
                    Tok::Typed(lit.to_string())
                };
                out.push(Token { tok, span: span(i, i + lit_end), line_start: false });
                i += lit_end;
                continue;
            }
            out.push(Token {
                tok: Tok::Ident(word.to_string()),
                span: span(i, i + n),
                line_start: false,
            });
            i += n;
            continue;
        }
        if c.is_ascii_digit() {
            let n = rest
                .find(|ch: char| {
                    !(ch.is_ascii_alphanumeric() || ch == '_' || ch == '#' || ch == '.')
                })
                .unwrap_or(rest.len());
            let mut lit = &rest[..n];
            // `1..5` is a range, not a real.
            if let Some(k) = lit.find("..") {
                lit = &lit[..k];
            }
            let clean: String = lit.chars().filter(|ch| *ch != '_').collect();
            let tok = if let Some((base, digits)) = clean.split_once('#') {
                let radix = match base {
                    "2" => 2,
                    "8" => 8,
                    "16" => 16,
                    _ => 0,
                };
                match (radix > 0).then(|| i128::from_str_radix(digits, radix).ok()).flatten() {
                    Some(v) => Tok::Int(v),
                    None => {
                        return Err(StError::new(
                            span(i, i + lit.len()),
                            format!("`{lit}` is not an integer literal"),
                            "expected `2#…`, `8#…` or `16#…` digits",
                        ));
                    }
                }
            } else if clean.contains('.') || clean.contains(['e', 'E']) {
                Tok::Real(lit.to_string())
            } else {
                match clean.parse::<i128>() {
                    Ok(v) => Tok::Int(v),
                    Err(_) => {
                        return Err(StError::new(
                            span(i, i + lit.len()),
                            format!("`{lit}` is not a number"),
                            "expected digits",
                        ));
                    }
                }
            };
            out.push(Token { tok, span: span(i, i + lit.len()), line_start: false });
            i += lit.len();
            continue;
        }
        if c == b'\'' || c == b'"' {
            let q = c as char;
            // `$` escapes the character after it (`$'`, `$$`, `$N`, …).
            let bytes = rest.as_bytes();
            let mut k = 1;
            while k < bytes.len() && bytes[k] != c {
                k += if bytes[k] == b'$' { 2 } else { 1 };
            }
            let Some(n) = (k < bytes.len()).then(|| k - 1) else {
                return Err(StError::new(
                    span(i, i + 1),
                    "unterminated string",
                    format!("this {q} is never closed"),
                ));
            };
            out.push(Token {
                tok: Tok::Str(rest[..n + 2].to_string()),
                span: span(i, i + n + 2),
                line_start: false,
            });
            i += n + 2;
            continue;
        }
        if c == b'%' {
            let n = 1 + rest[1..]
                .find(|ch: char| !(ch.is_ascii_alphanumeric() || ch == '.'))
                .unwrap_or(rest.len() - 1);
            out.push(Token {
                tok: Tok::Direct(rest[..n].to_string()),
                span: span(i, i + n),
                line_start: false,
            });
            i += n;
            continue;
        }
        match SYMS.iter().find(|s| rest.starts_with(**s)) {
            Some(s) => {
                out.push(Token { tok: Tok::Sym(s), span: span(i, i + s.len()), line_start: false });
                i += s.len();
            }
            None => {
                let ch = rest.chars().next().unwrap_or(' ');
                return Err(StError::new(
                    span(i, i + ch.len_utf8()),
                    format!("unexpected character `{ch}`"),
                    "not part of Structured Text",
                ));
            }
        }
    }
    out.push(Token { tok: Tok::Eof, span: span(end, end), line_start: true });
    // A token starts a line when a line break lies between it and the token before.
    let mut k = 0;
    let mut prev_end = range.start;
    for t in &mut out {
        while k < breaks.len() && breaks[k] < prev_end {
            k += 1;
        }
        t.line_start |= k < breaks.len() && breaks[k] < t.span.start;
        prev_end = t.span.end;
    }
    Ok(out)
}

/// The end of the comment opened at `start`: the offset of its closing `*)` and the
/// offset after it. Comments do not nest (as matiec reads them: the first `*)` closes).
fn comment_end(text: &str, start: usize, end: usize) -> (Option<usize>, usize) {
    match text.get(start + 2..end).and_then(|rest| rest.find("*)")) {
        Some(n) => (Some(start + 2 + n), start + 2 + n + 2),
        None => (None, end),
    }
}
