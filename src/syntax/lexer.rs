//! The lexer of the `.ii` language: text to tokens with byte spans; never panics.
//!
//! Names are `[A-Za-z_][A-Za-z0-9_]*`, or any text between back quotes
//! (`` `Xpi@90` ``, for LDmicro names) except a back quote or a newline.
//! Durations are `<decimal><unit>` (`us ms s min h`) or IEC literals
//! (`T#1m30s`, `t#250ms`, `TIME#5s`, components `d h m s ms us`, `_` allowed
//! between them). Comments run from `//` or `#` to the end of the line.

use num_bigint::BigInt;
use num_rational::BigRational;

use super::SyntaxError;
use crate::diag::{FileId, Span};
use crate::term::{Delay, parse_decimal};

/// The reserved words.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Keyword {
    /// `let`
    Let,
    /// `input`
    Input,
    /// `delay`
    Delay,
    /// `assume`
    Assume,
    /// `property`
    Property,
    /// `law`
    Law,
    /// `program`
    Program,
    /// `after`
    After,
    /// `if`
    If,
    /// `theorem` (proof scripts)
    Theorem,
    /// `lemma` (proof scripts)
    Lemma,
    /// `proof` (proof scripts)
    Proof,
    /// `qed` (proof scripts)
    Qed,
    /// `by` (proof scripts: `by auto`, `by H1, H2`)
    By,
}

impl Keyword {
    /// Every keyword with its spelling.
    pub const ALL: &'static [(&'static str, Keyword)] = &[
        ("let", Keyword::Let),
        ("input", Keyword::Input),
        ("delay", Keyword::Delay),
        ("assume", Keyword::Assume),
        ("property", Keyword::Property),
        ("law", Keyword::Law),
        ("program", Keyword::Program),
        ("after", Keyword::After),
        ("if", Keyword::If),
        ("theorem", Keyword::Theorem),
        ("lemma", Keyword::Lemma),
        ("proof", Keyword::Proof),
        ("qed", Keyword::Qed),
        ("by", Keyword::By),
    ];

    /// The keyword spelled `text`, if it is one.
    pub fn from_text(text: &str) -> Option<Keyword> {
        Keyword::ALL.iter().find(|(s, _)| *s == text).map(|&(_, k)| k)
    }

    /// How the keyword is spelled.
    pub fn text(self) -> &'static str {
        Keyword::ALL.iter().find(|(_, k)| *k == self).map(|(s, _)| *s).unwrap_or("?")
    }

    /// Does this keyword start a statement?
    pub fn starts_statement(self) -> bool {
        !matches!(self, Keyword::After | Keyword::If | Keyword::Proof | Keyword::Qed | Keyword::By)
    }
}

/// What a token is.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Tok {
    /// A plain identifier that is not a keyword.
    Ident(String),
    /// A back-quoted name (without the quotes).
    Quoted(String),
    /// A reserved word.
    Keyword(Keyword),
    /// A duration literal, already checked positive.
    Duration(Delay),
    /// `0*` or `0`.
    Zero,
    /// `1*` or `1`.
    One,
    /// A string literal (without the quotes, escapes resolved).
    Str(String),
    /// `=>` or `⇒`.
    Implies,
    /// `=`.
    Eq,
    /// `+`, `∨` or `|`.
    Or,
    /// `.`, `·`, `&` or `∧`.
    And,
    /// `.` inside a comparison's brackets: an instance's pin (`[T1.ET < T#2s]`).
    Dot,
    /// `!`, `¬` or `~`.
    Not,
    /// `/`.
    Slash,
    /// `(`.
    LParen,
    /// `)`.
    RParen,
    /// `,`.
    Comma,
    /// `:`.
    Colon,
    /// `[` (rule lists of proof steps).
    LBracket,
    /// `]`.
    RBracket,
    /// `>=` or `≥`.
    Ge,
    /// `>`.
    Gt,
    /// `<=` or `≤`.
    Le,
    /// `<`.
    Lt,
    /// `<>` (inside `[ ]`).
    Ne,
    /// An integer literal (inside `[ ]`, a comparison of integers).
    Int(i64),
    /// Text the lexer rejected (the error is already reported).
    Error,
    /// The end of the input.
    Eof,
}

impl Tok {
    /// A short description for "found ..." messages.
    pub fn describe(&self) -> String {
        match self {
            Tok::Ident(s) => format!("name `{s}`"),
            Tok::Quoted(s) => format!("name `{s}`"),
            Tok::Keyword(k) => format!("keyword `{}`", k.text()),
            Tok::Duration(d) => format!("duration `{d}`"),
            Tok::Zero => "`0*`".into(),
            Tok::One => "`1*`".into(),
            Tok::Str(s) => format!("string {s:?}"),
            Tok::Implies => "`=>`".into(),
            Tok::Eq => "`=`".into(),
            Tok::Or => "`+`".into(),
            Tok::And | Tok::Dot => "`.`".into(),
            Tok::Not => "`!`".into(),
            Tok::Slash => "`/`".into(),
            Tok::LParen => "`(`".into(),
            Tok::RParen => "`)`".into(),
            Tok::Comma => "`,`".into(),
            Tok::Colon => "`:`".into(),
            Tok::LBracket => "`[`".into(),
            Tok::RBracket => "`]`".into(),
            Tok::Ge => "`>=`".into(),
            Tok::Gt => "`>`".into(),
            Tok::Le => "`<=`".into(),
            Tok::Lt => "`<`".into(),
            Tok::Ne => "`<>`".into(),
            Tok::Int(v) => format!("integer `{v}`"),
            Tok::Error => "malformed text".into(),
            Tok::Eof => "end of input".into(),
        }
    }
}

/// A token and where it is.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Token {
    /// What it is.
    pub tok: Tok,
    /// Where it is.
    pub span: Span,
}

/// The units of the `<decimal><unit>` form, with their length in seconds (num/den).
const SUFFIX_UNITS: &[(&str, i64, i64)] =
    &[("us", 1, 1_000_000), ("ms", 1, 1_000), ("s", 1, 1), ("min", 60, 1), ("h", 3_600, 1)];

/// The components of an IEC literal (`T#1d2h3m4s5ms6us`).
const IEC_UNITS: &[(&str, i64, i64)] = &[
    ("d", 86_400, 1),
    ("h", 3_600, 1),
    ("m", 60, 1),
    ("s", 1, 1),
    ("ms", 1, 1_000),
    ("us", 1, 1_000_000),
];

/// Longest accepted decimal number, in characters (keeps delays printable).
const MAX_NUMBER_LEN: usize = 200;

struct Lexer<'a> {
    src: &'a str,
    pos: usize,
    file: FileId,
    tokens: Vec<Token>,
    errors: Vec<SyntaxError>,
    /// How many `[` are open: inside, numbers are integers (comparison atoms).
    brackets: usize,
}

/// Splits `text` into tokens (ending with [`Tok::Eof`]) and the errors found on the way.
///
/// Rejected text becomes a [`Tok::Error`] token so the parser does not report it twice.
pub fn lex(text: &str, file: FileId) -> (Vec<Token>, Vec<SyntaxError>) {
    let mut lexer =
        Lexer { src: text, pos: 0, file, tokens: Vec::new(), errors: Vec::new(), brackets: 0 };
    lexer.run();
    (lexer.tokens, lexer.errors)
}

fn is_ident_start(c: char) -> bool {
    c.is_ascii_alphabetic() || c == '_'
}

fn is_ident_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

impl Lexer<'_> {
    fn peek(&self) -> Option<char> {
        self.src.get(self.pos..).and_then(|s| s.chars().next())
    }

    fn peek_at(&self, n: usize) -> Option<char> {
        self.src.get(self.pos..).and_then(|s| s.chars().nth(n))
    }

    fn bump(&mut self) -> Option<char> {
        let c = self.peek()?;
        self.pos += c.len_utf8();
        Some(c)
    }

    fn eat_while(&mut self, pred: impl Fn(char) -> bool) -> &str {
        let start = self.pos;
        while let Some(c) = self.peek() {
            if !pred(c) {
                break;
            }
            self.pos += c.len_utf8();
        }
        self.src.get(start..self.pos).unwrap_or("")
    }

    fn span(&self, start: usize) -> Span {
        Span::new(self.file, start..self.pos)
    }

    fn push(&mut self, tok: Tok, start: usize) {
        let span = self.span(start);
        self.tokens.push(Token { tok, span });
    }

    fn fail(&mut self, error: SyntaxError, start: usize) {
        self.errors.push(error);
        self.push(Tok::Error, start);
    }

    fn run(&mut self) {
        while let Some(c) = self.peek() {
            let start = self.pos;
            match c {
                c if c.is_whitespace() => {
                    self.bump();
                }
                '#' => self.skip_line(),
                '/' if self.peek_at(1) == Some('/') => self.skip_line(),
                c if is_ident_start(c) => self.word(start),
                c if self.brackets > 0
                    && (c.is_ascii_digit()
                        || c == '-' && self.peek_at(1).is_some_and(|d| d.is_ascii_digit())) =>
                {
                    self.integer(start)
                }
                c if c.is_ascii_digit() => self.number(start),
                '`' => self.quoted(start),
                '"' => self.string(start),
                _ => self.operator(start, c),
            }
        }
        let end = self.src.len();
        self.tokens.push(Token { tok: Tok::Eof, span: Span::new(self.file, end..end) });
    }

    fn skip_line(&mut self) {
        self.eat_while(|c| c != '\n');
    }

    fn operator(&mut self, start: usize, c: char) {
        self.bump();
        let next = self.peek();
        let tok = match c {
            '=' if next == Some('>') => {
                self.bump();
                Tok::Implies
            }
            '=' => Tok::Eq,
            '⇒' => Tok::Implies,
            '+' | '∨' | '|' => Tok::Or,
            '.' if self.brackets > 0 => Tok::Dot,
            '.' | '·' | '&' | '∧' => Tok::And,
            '!' | '¬' | '~' => Tok::Not,
            '/' => Tok::Slash,
            '(' => Tok::LParen,
            ')' => Tok::RParen,
            ',' => Tok::Comma,
            ':' => Tok::Colon,
            '[' => {
                self.brackets += 1;
                Tok::LBracket
            }
            ']' => {
                self.brackets = self.brackets.saturating_sub(1);
                Tok::RBracket
            }
            '<' if next == Some('>') && self.brackets > 0 => {
                self.bump();
                Tok::Ne
            }
            '>' if next == Some('=') => {
                self.bump();
                Tok::Ge
            }
            '>' => Tok::Gt,
            '<' if next == Some('=') => {
                self.bump();
                Tok::Le
            }
            '<' => Tok::Lt,
            '≥' => Tok::Ge,
            '≤' => Tok::Le,
            _ => {
                let span = self.span(start);
                self.fail(SyntaxError::UnexpectedChar { span, found: c }, start);
                return;
            }
        };
        self.push(tok, start);
    }

    fn word(&mut self, start: usize) {
        let word = self.eat_while(is_ident_char).to_string();
        if self.peek() == Some('#') && matches!(word.to_ascii_lowercase().as_str(), "t" | "time") {
            self.bump();
            self.iec(start);
            return;
        }
        let tok = match Keyword::from_text(&word) {
            Some(k) => Tok::Keyword(k),
            None => Tok::Ident(word),
        };
        self.push(tok, start);
    }

    fn quoted(&mut self, start: usize) {
        self.bump();
        let name = self.eat_while(|c| c != '`' && c != '\n').to_string();
        if self.peek() != Some('`') {
            let span = self.span(start);
            self.fail(SyntaxError::UnterminatedName { span }, start);
            return;
        }
        self.bump();
        if name.is_empty() {
            let span = self.span(start);
            self.fail(SyntaxError::EmptyName { span }, start);
            return;
        }
        self.push(Tok::Quoted(name), start);
    }

    fn string(&mut self, start: usize) {
        self.bump();
        let mut value = String::new();
        loop {
            match self.peek() {
                None | Some('\n') => {
                    let span = self.span(start);
                    self.fail(SyntaxError::UnterminatedString { span }, start);
                    return;
                }
                Some('"') => {
                    self.bump();
                    break;
                }
                Some('\\') => {
                    self.bump();
                    match self.peek() {
                        Some(c @ ('"' | '\\')) => {
                            self.bump();
                            value.push(c);
                        }
                        _ => value.push('\\'),
                    }
                }
                Some(c) => {
                    self.bump();
                    value.push(c);
                }
            }
        }
        self.push(Tok::Str(value), start);
    }

    /// Reads the digits of a decimal number (`5`, `0.25`); a `.` is part of the
    /// number only when a digit follows it (so `1.f` is `1 . f`).
    fn decimal(&mut self) -> String {
        let mut text = self.eat_while(|c| c.is_ascii_digit()).to_string();
        if self.peek() == Some('.') && self.peek_at(1).is_some_and(|c| c.is_ascii_digit()) {
            self.bump();
            text.push('.');
            text.push_str(self.eat_while(|c| c.is_ascii_digit()));
        }
        text
    }

    fn number(&mut self, start: usize) {
        let number = self.decimal();
        match self.peek() {
            Some('*') if number == "0" || number == "1" => {
                self.bump();
                let tok = if number == "0" { Tok::Zero } else { Tok::One };
                self.push(tok, start);
            }
            Some(c) if is_ident_start(c) => {
                let unit_start = self.pos;
                let unit = self.eat_while(is_ident_char).to_string();
                let unit_span = self.span(unit_start);
                let Some(&(_, num, den)) = SUFFIX_UNITS.iter().find(|(u, _, _)| *u == unit) else {
                    let error = SyntaxError::BadUnit {
                        span: unit_span,
                        unit,
                        allowed: "us, ms, s, min, h".into(),
                    };
                    self.fail(error, start);
                    return;
                };
                let mut total = BigRational::from_integer(BigInt::from(0));
                if let Err(e) = self.add_component(&number, num, den, &mut total) {
                    let span = self.span(start);
                    self.fail(SyntaxError::BadDuration { span, reason: e }, start);
                    return;
                }
                self.finish_duration(total, start);
            }
            _ if number == "0" => self.push(Tok::Zero, start),
            _ if number == "1" => self.push(Tok::One, start),
            _ => {
                let span = self.span(start);
                self.fail(SyntaxError::MissingUnit { span, number }, start);
            }
        }
    }

    /// An integer literal of a comparison atom: `10`, `-3`.
    fn integer(&mut self, start: usize) {
        if self.peek() == Some('-') {
            self.bump();
        }
        self.eat_while(|c| c.is_ascii_digit());
        let text = self.src.get(start..self.pos).unwrap_or("");
        match text.parse::<i64>() {
            Ok(v) => self.push(Tok::Int(v), start),
            Err(_) => {
                let span = self.span(start);
                let reason = format!("`{text}` is not a 64-bit integer");
                self.fail(SyntaxError::BadComparison { span, reason, help: None }, start);
            }
        }
    }

    fn add_component(
        &self,
        number: &str,
        num: i64,
        den: i64,
        total: &mut BigRational,
    ) -> Result<(), String> {
        if number.len() > MAX_NUMBER_LEN {
            return Err(format!("a number may have at most {MAX_NUMBER_LEN} characters"));
        }
        let value = parse_decimal(number).ok_or_else(|| format!("`{number}` is not a number"))?;
        *total += value * BigRational::new(BigInt::from(num), BigInt::from(den));
        Ok(())
    }

    fn finish_duration(&mut self, total: BigRational, start: usize) {
        match Delay::new(total) {
            Ok(d) => self.push(Tok::Duration(d), start),
            Err(e) => {
                let span = self.span(start);
                let reason = e.to_string();
                self.fail(SyntaxError::BadDuration { span, reason }, start);
            }
        }
    }

    /// The rest of an IEC literal, after `T#`.
    fn iec(&mut self, start: usize) {
        if self.peek() == Some('-') {
            self.bump();
            self.eat_while(|c| is_ident_char(c) || c == '.');
            let span = self.span(start);
            let reason = "a delay must be positive (negative durations are not delays)".into();
            self.fail(SyntaxError::BadDuration { span, reason }, start);
            return;
        }
        let mut total = BigRational::from_integer(BigInt::from(0));
        let mut components = 0;
        loop {
            if self.peek() == Some('_') && self.peek_at(1).is_some_and(|c| c.is_ascii_digit()) {
                self.bump();
            }
            if !self.peek().is_some_and(|c| c.is_ascii_digit()) {
                break;
            }
            let number = self.decimal();
            let unit_start = self.pos;
            let unit = self.eat_while(|c| c.is_ascii_alphabetic()).to_ascii_lowercase();
            let found = IEC_UNITS.iter().find(|(u, _, _)| *u == unit);
            let Some(&(_, num, den)) = found else {
                self.eat_while(is_ident_char);
                let error = if unit.is_empty() {
                    SyntaxError::MissingUnit { span: self.span(start), number }
                } else {
                    SyntaxError::BadUnit {
                        span: self.span(unit_start),
                        unit,
                        allowed: "d, h, m, s, ms, us".into(),
                    }
                };
                self.fail(error, start);
                return;
            };
            if let Err(reason) = self.add_component(&number, num, den, &mut total) {
                let span = self.span(start);
                self.fail(SyntaxError::BadDuration { span, reason }, start);
                return;
            }
            components += 1;
        }
        if components == 0 || self.peek().is_some_and(is_ident_char) {
            self.eat_while(|c| is_ident_char(c) || c == '.');
            let span = self.span(start);
            let reason = "expected an IEC duration such as `T#5s` or `T#1m30s`".into();
            self.fail(SyntaxError::BadDuration { span, reason }, start);
            return;
        }
        self.finish_duration(total, start);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn toks(text: &str) -> Vec<Tok> {
        let (tokens, errors) = lex(text, 0);
        assert!(errors.is_empty(), "{text}: {errors:?}");
        tokens.into_iter().map(|t| t.tok).collect()
    }

    fn delay(text: &str) -> Delay {
        match toks(text).as_slice() {
            [Tok::Duration(d), Tok::Eof] => d.clone(),
            other => panic!("{text}: {other:?}"),
        }
    }

    fn secs(n: i64, d: i64) -> BigRational {
        BigRational::new(BigInt::from(n), BigInt::from(d))
    }

    #[test]
    fn durations_with_units_are_exact() {
        assert_eq!(delay("0.1s").seconds(), &secs(1, 10));
        assert_eq!(delay("250ms").seconds(), &secs(1, 4));
        assert_eq!(delay("1.25min").seconds(), &secs(75, 1));
        assert_eq!(delay("2h").seconds(), &secs(7200, 1));
        assert_eq!(delay("3us").seconds(), &secs(3, 1_000_000));
    }

    #[test]
    fn iec_durations() {
        assert_eq!(delay("T#5s").seconds(), &secs(5, 1));
        assert_eq!(delay("T#1m30s").seconds(), &secs(90, 1));
        assert_eq!(delay("t#250ms").seconds(), &secs(1, 4));
        assert_eq!(delay("TIME#1h_2m").seconds(), &secs(3720, 1));
        assert_eq!(delay("T#1d").seconds(), &secs(86_400, 1));
        assert_eq!(delay("T#1.5s").seconds(), &secs(3, 2));
    }

    #[test]
    fn bad_durations_are_errors() {
        for text in ["0s", "0.5", "12", "5parsec", "T#", "T#-5s", "T#5x", "T#0s", "5m"] {
            let (_, errors) = lex(text, 0);
            assert!(!errors.is_empty(), "{text}");
        }
        let (_, errors) = lex("0.5", 0);
        assert!(matches!(errors[0], SyntaxError::MissingUnit { .. }));
    }

    #[test]
    fn constants_operators_and_comments() {
        assert_eq!(
            toks("0* 1 0 1* # c\n a.b // x\n ⇒ ¬ ∨ · ≥ <= `X@1`"),
            vec![
                Tok::Zero,
                Tok::One,
                Tok::Zero,
                Tok::One,
                Tok::Ident("a".into()),
                Tok::And,
                Tok::Ident("b".into()),
                Tok::Implies,
                Tok::Not,
                Tok::Or,
                Tok::And,
                Tok::Ge,
                Tok::Le,
                Tok::Quoted("X@1".into()),
                Tok::Eof,
            ]
        );
        assert_eq!(toks("1.f")[1], Tok::And);
        assert_eq!(toks("law")[0], Tok::Keyword(Keyword::Law));
    }

    #[test]
    fn spans_are_byte_ranges() {
        let (tokens, _) = lex("¬ab", 0);
        assert_eq!(tokens[1].span.range(), 2..4);
    }
}
