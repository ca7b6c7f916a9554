//! The ST/IL lexer: tokens with byte spans (keywords case-insensitive, identifiers as spelt, nesting `(* … *)` and `//` comments and `{ … }` pragmas skipped, `#ASSERT` comments kept as tokens, literals decoded exactly), reading raw text or XML text with its entities and CDATA markers.

use std::ops::Range;

use super::StError;
use crate::diag::{FileId, Span};

/// A token's kind.
#[derive(Clone, Debug, PartialEq)]
pub enum Tok {
    /// An identifier or keyword, as written (a typed enumerated value `Color#Red` too).
    Word(String),
    /// An integer literal; `ty` is the upper-cased type of a typed literal (`INT#5`).
    Int {
        /// The value.
        value: i128,
        /// The type prefix, upper-cased.
        ty: Option<String>,
    },
    /// `BOOL#TRUE` or `BOOL#FALSE` (plain `TRUE`/`FALSE` are words).
    Bool(bool),
    /// A real literal as written, without `_` separators (`1.5E3`, `REAL#2.5`).
    Real(String),
    /// A duration in microseconds.
    Time(i64),
    /// A string literal, escapes decoded.
    Str(String),
    /// A direct address (`%IX0.1`), as written.
    Direct(String),
    /// Punctuation and operators.
    Sym(&'static str),
    /// A property comment `//#ASSERT …` or `(*#ASSERT … *)`: its tokens (ending with
    /// [`Tok::Eof`]) and its text.
    Assert(Vec<Token>, String),
    /// The end of the text.
    Eof,
}

/// A token, where it is, and whether it is the first on its line.
#[derive(Clone, Debug, PartialEq)]
pub struct Token {
    /// What it is.
    pub tok: Tok,
    /// Where it is.
    pub span: Span,
    /// Whether a line break separates it from the previous token (IL is line-based).
    pub line_start: bool,
}

impl Token {
    /// Whether the token is the keyword `kw` (given in capitals).
    pub fn is(&self, kw: &str) -> bool {
        matches!(&self.tok, Tok::Word(w) if w.eq_ignore_ascii_case(kw))
    }
    /// Whether the token is the symbol `sym`.
    pub fn is_sym(&self, sym: &str) -> bool {
        matches!(self.tok, Tok::Sym(s) if s == sym)
    }
    /// The word upper-cased, if the token is a word.
    pub fn word(&self) -> Option<String> {
        match &self.tok {
            Tok::Word(w) => Some(w.to_ascii_uppercase()),
            _ => None,
        }
    }
    /// How the token reads in a message.
    pub fn describe(&self) -> String {
        match &self.tok {
            Tok::Word(w) => format!("`{w}`"),
            Tok::Int { .. } | Tok::Real(_) | Tok::Bool(_) => "a number".into(),
            Tok::Time(_) => "a duration".into(),
            Tok::Str(_) => "a string".into(),
            Tok::Direct(d) => format!("`{d}`"),
            Tok::Sym(s) => format!("`{s}`"),
            Tok::Assert(..) => "an `#ASSERT` comment".into(),
            Tok::Eof => "the end of the text".into(),
        }
    }
}

const SYMS: &[&str] = &[
    ":=", "=>", "<=", ">=", "<>", "**", "..", "(", ")", "[", "]", ",", ";", ":", ".", "+", "-",
    "*", "/", "=", "<", ">", "&", "^", "#",
];

/// Elementary type names that may prefix a typed literal (`INT#5`).
const LITERAL_TYPES: &[&str] = &[
    "BOOL", "SINT", "INT", "DINT", "LINT", "USINT", "UINT", "UDINT", "ULINT", "BYTE", "WORD",
    "DWORD", "LWORD", "REAL", "LREAL",
];

/// Splits `text[range]` of `file` into tokens, ending with [`Tok::Eof`]. With `xml`,
/// the range is XML character data: entities and CDATA markers are decoded first. Never
/// panics; the first problem is the error.
pub fn lex(file: FileId, text: &str, range: Range<usize>, xml: bool) -> Result<Vec<Token>, StError> {
    let end = range.end.min(text.len());
    let start = range.start.min(end);
    if !(text.is_char_boundary(start) && text.is_char_boundary(end)) {
        let span = Span::new(file, start..start);
        return Err(StError::new(span, "the text does not start or end on a character boundary", "here"));
    }
    let chars: Vec<(usize, char)> = if xml {
        decode_xml(text, start..end)
    } else {
        text[start..end].char_indices().map(|(i, c)| (start + i, c)).collect()
    };
    Lexer { file, chars: &chars, end, i: 0, out: Vec::new(), line_start: true }.run()
}

/// The characters of XML character data at `range` with the raw offset of each: entities
/// (`&lt;`, `&#65;`) become their character, `<![CDATA[` and `]]>` vanish and what is
/// between them is taken as it stands.
fn decode_xml(text: &str, range: Range<usize>) -> Vec<(usize, char)> {
    let mut out = Vec::new();
    let mut in_cdata = text[..range.start].ends_with("<![CDATA[");
    let mut i = range.start;
    while i < range.end {
        let rest = &text[i..range.end];
        if in_cdata {
            if rest.starts_with("]]>") {
                in_cdata = false;
                i += 3;
                continue;
            }
        } else if rest.starts_with("<![CDATA[") {
            in_cdata = true;
            i += 9;
            continue;
        } else if let Some(c) = rest.strip_prefix('&').and_then(entity) {
            out.push((i, c.0));
            i += c.1 + 1;
            continue;
        }
        let c = rest.chars().next().unwrap_or('\0');
        out.push((i, c));
        i += c.len_utf8().max(1);
    }
    out
}

/// The character an entity after its `&` stands for, and the entity's length after `&`.
fn entity(rest: &str) -> Option<(char, usize)> {
    let semi = rest.find(';').filter(|&n| n <= 10)?;
    let name = &rest[..semi];
    let c = match name {
        "lt" => '<',
        "gt" => '>',
        "amp" => '&',
        "quot" => '"',
        "apos" => '\'',
        _ => {
            let code = match name.strip_prefix("#x").or_else(|| name.strip_prefix("#X")) {
                Some(hex) => u32::from_str_radix(hex, 16).ok()?,
                None => name.strip_prefix('#')?.parse().ok()?,
            };
            char::from_u32(code)?
        }
    };
    Some((c, semi + 1))
}

struct Lexer<'a> {
    file: FileId,
    chars: &'a [(usize, char)],
    /// The raw offset just past the last character.
    end: usize,
    i: usize,
    out: Vec<Token>,
    line_start: bool,
}

impl Lexer<'_> {
    fn peek(&self, k: usize) -> Option<char> {
        self.chars.get(self.i + k).map(|c| c.1)
    }
    fn offset(&self, i: usize) -> usize {
        self.chars.get(i).map_or(self.end, |c| c.0)
    }
    fn span(&self, from: usize, to: usize) -> Span {
        Span::new(self.file, self.offset(from)..self.offset(to))
    }
    fn text(&self, from: usize, to: usize) -> String {
        self.chars[from..to].iter().map(|c| c.1).collect()
    }
    fn starts_with(&self, s: &str) -> bool {
        s.chars().enumerate().all(|(k, c)| self.peek(k) == Some(c))
    }
    fn error(&self, from: usize, to: usize, message: impl Into<String>, label: &str) -> StError {
        StError::new(self.span(from, to), message, label)
    }
    fn push(&mut self, tok: Tok, from: usize) {
        let span = self.span(from, self.i);
        self.out.push(Token { tok, span, line_start: self.line_start });
        self.line_start = false;
    }

    fn run(mut self) -> Result<Vec<Token>, StError> {
        while let Some(c) = self.peek(0) {
            let from = self.i;
            if c == '\n' {
                self.line_start = true;
                self.i += 1;
            } else if c.is_whitespace() {
                self.i += 1;
            } else if self.starts_with("(*") {
                self.block_comment()?;
            } else if self.starts_with("//") {
                self.line_comment()?;
            } else if c == '{' {
                self.pragma()?;
            } else if c.is_ascii_alphabetic() || c == '_' {
                self.word()?;
            } else if c.is_ascii_digit() {
                let tok = self.number(from, None)?;
                self.push(tok, from);
            } else if c == '\'' || c == '"' {
                self.string()?;
            } else if c == '%' {
                self.direct()?;
            } else if let Some(sym) = SYMS.iter().find(|s| self.starts_with(s)) {
                self.i += sym.len();
                self.push(Tok::Sym(sym), from);
            } else {
                return Err(self.error(from, from + 1, format!("unexpected character `{c}`"), "not part of IEC 61131-3 text"));
            }
        }
        let from = self.i;
        self.push(Tok::Eof, from);
        Ok(self.out)
    }

    /// `(* … *)`, nesting; `(*#ASSERT … *)` becomes a token.
    fn block_comment(&mut self) -> Result<(), StError> {
        let from = self.i;
        self.i += 2;
        if self.assert_ahead() {
            let content = self.i + 7;
            while self.peek(0).is_some() && !self.starts_with("*)") {
                self.i += 1;
            }
            if self.peek(0).is_none() {
                return Err(self.error(from, from + 2, "unterminated comment: expected `*)`", "this comment is never closed"));
            }
            let end = self.i;
            self.assertion(content, end)?;
            self.i += 2;
            return Ok(());
        }
        let mut depth = 1;
        while depth > 0 {
            match self.peek(0) {
                None => return Err(self.error(from, from + 2, "unterminated comment: expected `*)`", "this comment is never closed")),
                Some('\n') => self.line_start = true,
                _ => {}
            }
            if self.starts_with("(*") {
                depth += 1;
                self.i += 2;
            } else if self.starts_with("*)") {
                depth -= 1;
                self.i += 2;
            } else {
                self.i += 1;
            }
        }
        Ok(())
    }

    /// `// …` to the end of the line; `//#ASSERT …` becomes a token.
    fn line_comment(&mut self) -> Result<(), StError> {
        self.i += 2;
        let assert = self.assert_ahead();
        let content = self.i + 7;
        while self.peek(0).is_some_and(|c| c != '\n') {
            self.i += 1;
        }
        if assert {
            self.assertion(content.min(self.i), self.i)?;
        }
        Ok(())
    }

    /// Whether `#ASSERT` follows (at the start of a comment's text).
    fn assert_ahead(&self) -> bool {
        self.peek(0) == Some('#')
            && self.i + 7 <= self.chars.len()
            && self.text(self.i + 1, self.i + 7).eq_ignore_ascii_case("ASSERT")
            && !self.peek(7).is_some_and(|c| c.is_ascii_alphanumeric() || c == '_')
    }

    /// The token of a property comment whose text is `chars[from..to]`.
    fn assertion(&mut self, from: usize, to: usize) -> Result<(), StError> {
        let inner = Lexer {
            file: self.file,
            chars: &self.chars[from..to],
            end: self.offset(to),
            i: 0,
            out: Vec::new(),
            line_start: false,
        };
        let toks = inner.run()?;
        let text = self.text(from, to).trim().to_string();
        let span = self.span(from, to);
        self.out.push(Token { tok: Tok::Assert(toks, text), span, line_start: self.line_start });
        self.line_start = false;
        Ok(())
    }

    /// `{ … }`, skipped.
    fn pragma(&mut self) -> Result<(), StError> {
        let from = self.i;
        while let Some(c) = self.peek(0) {
            self.i += 1;
            match c {
                '}' => return Ok(()),
                '\n' => self.line_start = true,
                _ => {}
            }
        }
        Err(self.error(from, from + 1, "unterminated pragma: expected `}`", "this pragma is never closed"))
    }

    fn take_while(&mut self, f: impl Fn(char) -> bool) -> String {
        let from = self.i;
        while self.peek(0).is_some_and(&f) {
            self.i += 1;
        }
        self.text(from, self.i)
    }

    /// A word, or a typed literal `TYPE#…` (durations, `INT#5`, `Color#Red`).
    fn word(&mut self) -> Result<(), StError> {
        let from = self.i;
        let word = self.take_while(|c| c.is_ascii_alphanumeric() || c == '_');
        if self.peek(0) != Some('#') {
            self.push(Tok::Word(word), from);
            return Ok(());
        }
        self.i += 1;
        let upper = word.to_ascii_uppercase();
        let tok = match upper.as_str() {
            "T" | "TIME" | "LT" | "LTIME" => {
                let body_from = self.i;
                if self.peek(0).is_some_and(|c| c == '-' || c == '+') {
                    self.i += 1;
                }
                self.take_while(|c| c.is_ascii_alphanumeric() || c == '_' || c == '.');
                let body = self.text(body_from, self.i);
                match duration(&body) {
                    Ok(us) => Tok::Time(us),
                    Err(why) => {
                        let lit = self.text(from, self.i);
                        return Err(self.error(from, self.i, format!("`{lit}` is not a duration: {why}"), "expected a duration like `T#1h2m3s4ms`"));
                    }
                }
            }
            "D" | "DATE" | "TOD" | "TIME_OF_DAY" | "DT" | "DATE_AND_TIME" | "LDATE" | "LTOD" | "LDT" => {
                return Err(self.error(from, self.i, format!("date and time-of-day literals (`{word}#…`) are not supported"), "not supported"));
            }
            ty if LITERAL_TYPES.contains(&ty) => self.typed_value(from, ty)?,
            _ if self.peek(0).is_some_and(|c| c.is_ascii_alphabetic() || c == '_') => {
                let value = self.take_while(|c| c.is_ascii_alphanumeric() || c == '_');
                Tok::Word(format!("{word}#{value}"))
            }
            _ => return Err(self.error(from, self.i, format!("expected a value after `{word}#`"), "expected a literal")),
        };
        self.push(tok, from);
        Ok(())
    }

    /// The value of `TYPE#…` for an elementary type (signed, any base, `BOOL#TRUE`).
    fn typed_value(&mut self, from: usize, ty: &str) -> Result<Tok, StError> {
        if ty == "BOOL" && self.peek(0).is_some_and(|c| c.is_ascii_alphabetic()) {
            let v = self.take_while(|c| c.is_ascii_alphanumeric() || c == '_');
            return match v.to_ascii_uppercase().as_str() {
                "TRUE" => Ok(Tok::Bool(true)),
                "FALSE" => Ok(Tok::Bool(false)),
                _ => Err(self.error(from, self.i, format!("`BOOL#{v}` is not a Boolean"), "expected `TRUE`, `FALSE`, 0 or 1")),
            };
        }
        let negative = self.peek(0) == Some('-');
        if self.peek(0).is_some_and(|c| c == '-' || c == '+') {
            self.i += 1;
        }
        if !self.peek(0).is_some_and(|c| c.is_ascii_digit()) {
            return Err(self.error(from, self.i, format!("expected a number after `{ty}#`"), "expected a number"));
        }
        Ok(match self.number(from, Some(ty))? {
            Tok::Int { value, ty } => Tok::Int { value: if negative { -value } else { value }, ty },
            Tok::Real(_) => Tok::Real(self.text(from, self.i).replace('_', "")),
            tok => tok,
        })
    }

    /// An integer (`1_000`, `16#FF`) or a real (`1.5E-3`) starting at the current digit.
    fn number(&mut self, from: usize, ty: Option<&str>) -> Result<Tok, StError> {
        let digits_from = self.i;
        let digits = self.take_while(|c| c.is_ascii_digit() || c == '_');
        let ty = ty.map(str::to_string);
        if self.peek(0) == Some('#') {
            let base = match digits.as_str() {
                "2" => 2,
                "8" => 8,
                "16" => 16,
                _ => return Err(self.error(digits_from, self.i + 1, format!("`{digits}#` is not a base: expected `2#`, `8#` or `16#`"), "not a base")),
            };
            self.i += 1;
            let body = self.take_while(|c| c.is_ascii_alphanumeric() || c == '_');
            return match int_value(&body, base) {
                Some(value) => Ok(Tok::Int { value, ty }),
                None => Err(self.error(from, self.i, format!("`{}` is not a base-{base} number", self.text(from, self.i)), "bad digits")),
            };
        }
        let is_real = self.peek(0) == Some('.') && self.peek(1).is_some_and(|c| c.is_ascii_digit());
        if is_real {
            self.i += 1;
            self.take_while(|c| c.is_ascii_digit() || c == '_');
            let exp_digit = |k| self.peek(k).is_some_and(|c: char| c.is_ascii_digit());
            if self.peek(0).is_some_and(|c| c == 'e' || c == 'E')
                && (exp_digit(1) || (self.peek(1).is_some_and(|c| c == '+' || c == '-') && exp_digit(2)))
            {
                self.i += 2;
                self.take_while(|c| c.is_ascii_digit());
            }
            return Ok(Tok::Real(self.text(digits_from, self.i).replace('_', "")));
        }
        match int_value(&digits, 10) {
            Some(value) => Ok(Tok::Int { value, ty }),
            None => Err(self.error(from, self.i, "integer literal too large", "too large")),
        }
    }

    /// `'…'` (or `"…"`) with `$` escapes.
    fn string(&mut self) -> Result<(), StError> {
        let from = self.i;
        let quote = self.peek(0).unwrap_or('\'');
        self.i += 1;
        let mut value = String::new();
        loop {
            match self.peek(0) {
                None | Some('\n') => return Err(self.error(from, self.i, format!("unterminated string: expected `{quote}`"), "this string is never closed")),
                Some(c) if c == quote => break,
                Some('$') => {
                    let (c, len) = match self.peek(1).map(|c| c.to_ascii_uppercase()) {
                        Some('$') => ('$', 2),
                        Some('\'') => ('\'', 2),
                        Some('"') => ('"', 2),
                        Some('L' | 'N') => ('\n', 2),
                        Some('P') => ('\u{c}', 2),
                        Some('R') => ('\r', 2),
                        Some('T') => ('\t', 2),
                        _ => {
                            let hex = self.text(self.i + 1, (self.i + 3).min(self.chars.len()));
                            match u32::from_str_radix(&hex, 16).ok().filter(|_| hex.len() == 2).and_then(char::from_u32) {
                                Some(c) => (c, 3),
                                None => return Err(self.error(self.i, self.i + 2, "unknown escape in a string", "expected `$$`, `$'`, `$N`, `$R`, `$T`, `$P`, `$L` or two hex digits")),
                            }
                        }
                    };
                    value.push(c);
                    self.i += len;
                }
                Some(c) => {
                    value.push(c);
                    self.i += 1;
                }
            }
        }
        self.i += 1;
        self.push(Tok::Str(value), from);
        Ok(())
    }

    /// `%IX0.1`, `%QW3`, `%MD10`.
    fn direct(&mut self) -> Result<(), StError> {
        let from = self.i;
        self.i += 1;
        let ok_area = self.peek(0).is_some_and(|c| matches!(c.to_ascii_uppercase(), 'I' | 'Q' | 'M'));
        if ok_area {
            self.i += 1;
            if self.peek(0).is_some_and(|c| matches!(c.to_ascii_uppercase(), 'X' | 'B' | 'W' | 'D' | 'L')) {
                self.i += 1;
            }
        }
        let digits_ok = self.peek(0).is_some_and(|c| c.is_ascii_digit());
        if !(ok_area && digits_ok) {
            return Err(self.error(from, self.i.max(from + 1), "expected a direct address like `%IX0.1`, `%QW3` or `%MD10`", "not a direct address"));
        }
        while self.peek(0).is_some_and(|c| c.is_ascii_digit())
            || (self.peek(0) == Some('.') && self.peek(1).is_some_and(|c| c.is_ascii_digit()))
        {
            self.i += 1;
        }
        let text = self.text(from, self.i);
        self.push(Tok::Direct(text), from);
        Ok(())
    }
}

/// The value of `digits` (with `_` separators) in `base`.
fn int_value(digits: &str, base: u32) -> Option<i128> {
    let digits = digits.replace('_', "");
    if digits.is_empty() {
        return None;
    }
    i128::from_str_radix(&digits, base).ok().filter(|v| *v <= i128::from(u64::MAX))
}

/// The body of a duration literal after `T#` (`1h2m3s4ms`, `1.5s`, `-2s`), in exact
/// microseconds, or why not.
pub fn duration(body: &str) -> Result<i64, String> {
    let body: String = body.chars().filter(|c| *c != '_').collect::<String>().to_ascii_lowercase();
    let (negative, mut rest) = match body.strip_prefix('-') {
        Some(r) => (true, r),
        None => (false, body.strip_prefix('+').unwrap_or(&body)),
    };
    if rest.is_empty() {
        return Err("expected a number and a unit".into());
    }
    let mut ns: i128 = 0;
    while !rest.is_empty() {
        let n = rest.find(|c: char| !(c.is_ascii_digit() || c == '.')).unwrap_or(rest.len());
        let (num, after) = rest.split_at(n);
        let u = after.find(|c: char| !c.is_ascii_alphabetic()).unwrap_or(after.len());
        let (unit, after) = after.split_at(u);
        let scale: i128 = match unit {
            "d" => 86_400_000_000_000,
            "h" => 3_600_000_000_000,
            "m" => 60_000_000_000,
            "s" => 1_000_000_000,
            "ms" => 1_000_000,
            "us" => 1_000,
            "ns" => 1,
            "" => return Err(format!("a unit (d, h, m, s, ms, us, ns) must follow `{num}`")),
            _ => return Err(format!("unknown unit `{unit}` (expected d, h, m, s, ms, us or ns)")),
        };
        let (int, frac) = num.split_once('.').unwrap_or((num, ""));
        if int.is_empty() || int.contains('.') || frac.contains('.') || (num.contains('.') && frac.is_empty()) {
            return Err(format!("`{num}` is not a number"));
        }
        let too_large = || "too large".to_string();
        let mut v = int.parse::<i128>().map_err(|_| too_large())?.checked_mul(scale).ok_or_else(too_large)?;
        if !frac.is_empty() {
            let f: i128 = frac.get(..30).unwrap_or(frac).parse().map_err(|_| too_large())?;
            let den = 10i128.checked_pow(frac.len() as u32).filter(|_| frac.len() <= 30);
            let exact = den.and_then(|d| f.checked_mul(scale).filter(|x| x % d == 0).map(|x| x / d));
            v = v.checked_add(exact.ok_or("a fraction finer than 1 µs")?).ok_or_else(too_large)?;
        }
        ns = ns.checked_add(v).ok_or_else(too_large)?;
        rest = after;
    }
    if ns % 1000 != 0 {
        return Err("a fraction finer than 1 µs".into());
    }
    let us = i64::try_from(ns / 1000).map_err(|_| "too large".to_string())?;
    Ok(if negative { -us } else { us })
}
