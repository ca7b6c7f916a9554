//! The Structured Text parser: recursive descent over the lexer's tokens into the AST, with IEC 61131-3 precedence and errors that say what was expected and where the open construct began.

mod il;
mod sfc;
mod types;

pub use sfc::parse_condition;

use std::collections::BTreeSet;

use super::StError;
use super::ast::*;
use super::lexer::{Tok, Token, lex};
use crate::diag::Span;

/// Keywords that end a statement list, with the construct each closes.
const ENDERS: &[&str] = &[
    "END_IF",
    "ELSIF",
    "ELSE",
    "END_CASE",
    "END_FOR",
    "END_WHILE",
    "UNTIL",
    "END_REPEAT",
    "END_PROGRAM",
    "END_FUNCTION_BLOCK",
    "END_FUNCTION",
    "END_ACTION",
];

/// Keywords a misspelt word is compared with.
const KEYWORDS: &[&str] = &[
    "IF",
    "THEN",
    "ELSIF",
    "ELSE",
    "END_IF",
    "CASE",
    "OF",
    "END_CASE",
    "FOR",
    "TO",
    "BY",
    "DO",
    "END_FOR",
    "WHILE",
    "END_WHILE",
    "REPEAT",
    "UNTIL",
    "END_REPEAT",
    "EXIT",
    "RETURN",
    "VAR",
    "VAR_INPUT",
    "VAR_OUTPUT",
    "VAR_IN_OUT",
    "VAR_GLOBAL",
    "VAR_EXTERNAL",
    "VAR_TEMP",
    "END_VAR",
    "PROGRAM",
    "END_PROGRAM",
    "FUNCTION_BLOCK",
    "END_FUNCTION_BLOCK",
    "FUNCTION",
    "END_FUNCTION",
    "CONFIGURATION",
    "END_CONFIGURATION",
    "RESOURCE",
    "END_RESOURCE",
    "TASK",
    "CONSTANT",
    "RETAIN",
];

/// Parses a whole `.st` file.
pub fn parse_unit(file: usize, text: &str) -> Result<Unit, StError> {
    let toks = lex(file, text, 0..text.len())?;
    let mut p = Parser::new(toks, text);
    p.unit()
}

/// Parses the statements of a body at `range` of `text` (a PLCopen `<ST>` body).
pub fn parse_body(
    file: usize,
    text: &str,
    range: std::ops::Range<usize>,
) -> Result<Vec<Stmt>, StError> {
    let toks = lex(file, text, range)?;
    let mut p = Parser::new(toks, text);
    let body = p.stmts(None)?;
    p.expect_eof()?;
    Ok(body)
}

/// Parses the lines of an Instruction List body at `range` of `text` (a PLCopen `<IL>`
/// body).
pub fn parse_il_body(
    file: usize,
    text: &str,
    range: std::ops::Range<usize>,
) -> Result<Vec<IlLine>, StError> {
    let toks = lex(file, text, range)?;
    let mut p = Parser::new(toks, text);
    let body = p.il_lines()?;
    p.expect_eof()?;
    Ok(body)
}

struct Parser<'t> {
    toks: Vec<Token>,
    at: usize,
    text: &'t str,
    /// The functions the text declares (upper-case): IL may use them as operators.
    functions: BTreeSet<String>,
}

fn describe(t: &Token) -> String {
    match &t.tok {
        Tok::Ident(s) => format!("`{s}`"),
        Tok::Int(v) => format!("the number {v}"),
        Tok::Time(_) | Tok::Typed(_) | Tok::Real(_) | Tok::Str(_) | Tok::Direct(_) => {
            "a literal".into()
        }
        Tok::Sym(s) => format!("`{s}`"),
        Tok::Assert(..) => "an #ASSERT comment".into(),
        Tok::Eof => "the end of the text".into(),
    }
}

impl<'t> Parser<'t> {
    fn new(toks: Vec<Token>, text: &'t str) -> Parser<'t> {
        let functions = toks
            .windows(2)
            .filter(|w| w[0].is_kw("FUNCTION"))
            .filter_map(|w| match &w[1].tok {
                Tok::Ident(n) => Some(n.to_ascii_uppercase()),
                _ => None,
            })
            .collect();
        Parser { toks, at: 0, text, functions }
    }

    fn peek(&self) -> &Token {
        &self.toks[self.at.min(self.toks.len() - 1)]
    }

    fn peek_at(&self, k: usize) -> &Token {
        &self.toks[(self.at + k).min(self.toks.len() - 1)]
    }

    fn bump(&mut self) -> Token {
        let t = self.peek().clone();
        if self.at < self.toks.len() - 1 {
            self.at += 1;
        }
        t
    }

    fn is_kw(&self, kw: &str) -> bool {
        self.peek().is_kw(kw)
    }

    fn is_sym(&self, s: &str) -> bool {
        matches!(self.peek().tok, Tok::Sym(x) if x == s)
    }

    fn eat_kw(&mut self, kw: &str) -> bool {
        let yes = self.is_kw(kw);
        if yes {
            self.bump();
        }
        yes
    }

    fn eat_sym(&mut self, s: &str) -> bool {
        let yes = matches!(self.peek().tok, Tok::Sym(x) if x == s);
        if yes {
            self.bump();
        }
        yes
    }

    /// An error at the current token: `expected …, found …`, with a "did you mean" when
    /// the token is a near miss of a keyword.
    fn unexpected(&self, expected: &str) -> StError {
        let t = self.peek();
        let mut e = StError::new(
            t.span,
            format!("expected {expected}, found {}", describe(t)),
            format!("expected {expected}"),
        );
        if let Tok::Ident(word) = &t.tok {
            let upper = word.to_ascii_uppercase();
            if !KEYWORDS.contains(&upper.as_str())
                && let Some(k) = crate::diag::did_you_mean(&upper, KEYWORDS.iter().copied())
            {
                e.notes.push(format!("did you mean `{k}`?"));
            }
        }
        e
    }

    fn expect_kw(&mut self, kw: &str, opened: Option<(&str, Span)>) -> Result<Span, StError> {
        if self.is_kw(kw) {
            return Ok(self.bump().span);
        }
        let mut e = self.unexpected(&format!("`{kw}`"));
        if let Some((what, span)) = opened {
            let (line, _) = line_col(self.text, span.start);
            e.message = format!(
                "expected `{kw}` to close the `{what}` at line {line}, found {}",
                describe(self.peek())
            );
            e.related = Some(Box::new((span, format!("this `{what}` is not closed"))));
        }
        Err(e)
    }

    fn expect_sym(&mut self, s: &str, after: &str) -> Result<Span, StError> {
        if matches!(self.peek().tok, Tok::Sym(x) if x == s) {
            return Ok(self.bump().span);
        }
        Err(self.unexpected(&format!("`{s}` {after}")))
    }

    fn expect_eof(&mut self) -> Result<(), StError> {
        if self.peek().tok == Tok::Eof { Ok(()) } else { Err(self.unexpected("a statement")) }
    }

    fn ident(&mut self, what: &str) -> Result<Ident, StError> {
        match &self.peek().tok {
            Tok::Ident(s) if !KEYWORDS.contains(&s.to_ascii_uppercase().as_str()) => {
                let t = self.bump();
                let Tok::Ident(name) = t.tok else { unreachable!("checked above") };
                Ok(Ident { name, span: t.span })
            }
            _ => Err(self.unexpected(what)),
        }
    }

    fn unit(&mut self) -> Result<Unit, StError> {
        let mut unit = Unit::default();
        let mut types = Vec::new();
        loop {
            let t = self.peek().clone();
            if t.tok == Tok::Eof {
                types::resolve(&mut unit, &types);
                return Ok(unit);
            }
            if self.eat_kw("PROGRAM") {
                unit.pous.push(self.pou(PouKind::Program, "END_PROGRAM", t.span)?);
            } else if self.eat_kw("FUNCTION_BLOCK") {
                unit.pous.push(self.pou(PouKind::FunctionBlock, "END_FUNCTION_BLOCK", t.span)?);
            } else if self.eat_kw("FUNCTION") {
                unit.pous.push(self.pou(PouKind::Function, "END_FUNCTION", t.span)?);
            } else if self.eat_kw("CONFIGURATION") {
                unit.configs.push(self.config(t.span)?);
            } else if self.eat_kw("TYPE") {
                self.types(&mut types)?;
            } else {
                return Err(
                    self.unexpected("`PROGRAM`, `FUNCTION_BLOCK`, `FUNCTION` or `CONFIGURATION`")
                );
            }
        }
    }

    fn pou(&mut self, kind: PouKind, end: &str, start: Span) -> Result<Pou, StError> {
        let name = self.ident("the POU's name")?;
        let mut result = None;
        if kind == PouKind::Function {
            self.expect_sym(":", "and the function's result type")?;
            result = Some(self.ident("the result type")?);
        }
        let mut vars = Vec::new();
        while self.peek().is_kw("VAR")
            || matches!(&self.peek().tok, Tok::Ident(s) if s.to_ascii_uppercase().starts_with("VAR_") && !s.eq_ignore_ascii_case("VAR_CONFIG"))
        {
            vars.extend(self.var_block()?);
        }
        let word = match kind {
            PouKind::Program => "PROGRAM",
            PouKind::FunctionBlock => "FUNCTION_BLOCK",
            PouKind::Function => "FUNCTION",
        };
        let body = if self.sfc_ahead() {
            Body::Sfc(self.sfc()?)
        } else if self.il_ahead() {
            Body::Il(self.il_lines()?)
        } else {
            Body::St(self.stmts(Some((word, start)))?)
        };
        let end_span = self.expect_kw(end, Some((word, start)))?;
        Ok(Pou { kind, name, vars, result, body, span: start.to(end_span) })
    }

    fn var_block(&mut self) -> Result<Vec<VarDecl>, StError> {
        let t = self.bump();
        let Tok::Ident(word) = &t.tok else { return Err(self.unexpected("`VAR`")) };
        let class = match word.to_ascii_uppercase().as_str() {
            "VAR" => VarClass::Local,
            "VAR_INPUT" => VarClass::Input,
            "VAR_OUTPUT" => VarClass::Output,
            "VAR_IN_OUT" => VarClass::InOut,
            "VAR_GLOBAL" => VarClass::Global,
            "VAR_EXTERNAL" => VarClass::External,
            "VAR_TEMP" => VarClass::Temp,
            other => {
                return Err(StError::new(
                    t.span,
                    format!("`{other}` is not a variable section"),
                    "expected `VAR`, `VAR_INPUT`, `VAR_OUTPUT`, …",
                ));
            }
        };
        let (mut constant, mut retain) = (false, false);
        loop {
            if self.eat_kw("CONSTANT") {
                constant = true;
            } else if self.eat_kw("RETAIN") || self.eat_kw("PERSISTENT") {
                retain = true;
            } else if self.eat_kw("NON_RETAIN") {
                retain = false;
            } else {
                break;
            }
        }
        let mut out = Vec::new();
        while !self.is_kw("END_VAR") {
            if self.peek().tok == Tok::Eof {
                return Err(self
                    .expect_kw("END_VAR", Some((word, t.span)))
                    .err()
                    .unwrap_or_else(|| self.unexpected("`END_VAR`")));
            }
            let mut names = vec![self.ident("a variable name or `END_VAR`")?];
            while self.eat_sym(",") {
                names.push(self.ident("a variable name")?);
            }
            let location = if self.eat_kw("AT") {
                match self.bump().tok {
                    Tok::Direct(d) => Some(d),
                    _ => return Err(self.unexpected("a direct address like `%IX0.0`")),
                }
            } else {
                None
            };
            self.expect_sym(":", "and the variable's type")?;
            let ty = self.type_ref()?;
            let init = if self.eat_sym(":=") { Some(self.init()?) } else { None };
            self.expect_sym(";", "after the declaration")?;
            for name in names {
                out.push(VarDecl {
                    name,
                    class,
                    ty: ty.clone(),
                    init: init.clone(),
                    retain,
                    constant,
                    location: location.clone(),
                    made: false,
                    range: None,
                });
            }
        }
        self.bump();
        Ok(out)
    }

    fn type_ref(&mut self) -> Result<Ident, StError> {
        let t = self.peek().clone();
        if self.eat_kw("ARRAY") {
            // `ARRAY [a..b, …] OF T`: read and kept as `ARRAY`.
            self.expect_sym("[", "after `ARRAY`")?;
            while !self.eat_sym("]") {
                if self.peek().tok == Tok::Eof {
                    return Err(self.unexpected("`]`"));
                }
                self.bump();
            }
            self.expect_kw("OF", None)?;
            let of = self.type_ref()?;
            return Ok(Ident { name: "ARRAY".into(), span: t.span.to(of.span) });
        }
        let mut ty = self.ident("a type name")?;
        if ty.key() == "STRING" && self.eat_sym("[") {
            self.bump();
            self.expect_sym("]", "after the string length")?;
        }
        ty.name = ty.key();
        Ok(ty)
    }

    /// An initial value: an expression, or a structure/FB initialiser `(IN := …)`, kept
    /// only when it is an expression.
    fn init(&mut self) -> Result<Expr, StError> {
        if self.is_sym("(")
            && matches!(self.peek_at(1).tok, Tok::Ident(_))
            && matches!(self.peek_at(2).tok, Tok::Sym(":="))
        {
            let start = self.bump().span;
            let mut depth = 1;
            while depth > 0 {
                let t = self.bump();
                match t.tok {
                    Tok::Sym("(") => depth += 1,
                    Tok::Sym(")") => depth -= 1,
                    Tok::Eof => {
                        return Err(StError::new(
                            start,
                            "unclosed initialiser",
                            "this `(` is never closed",
                        ));
                    }
                    _ => {}
                }
            }
            return Ok(Expr { kind: ExprKind::Literal("(…)".into()), span: start });
        }
        self.expr()
    }

    fn config(&mut self, start: Span) -> Result<Config, StError> {
        let name = self.ident("the configuration's name")?;
        let mut config =
            Config { name, tasks: Vec::new(), instances: Vec::new(), globals: Vec::new() };
        loop {
            if self.eat_kw("END_CONFIGURATION") {
                return Ok(config);
            }
            let t = self.peek().clone();
            if self.eat_kw("RESOURCE") {
                self.ident("the resource's name")?;
                self.expect_kw("ON", None)?;
                self.ident("the resource's processor type")?;
                while !self.eat_kw("END_RESOURCE") {
                    if self.peek().tok == Tok::Eof {
                        return Err(self
                            .expect_kw("END_RESOURCE", Some(("RESOURCE", t.span)))
                            .err()
                            .unwrap_or_else(|| self.unexpected("`END_RESOURCE`")));
                    }
                    self.config_item(&mut config)?;
                }
            } else if self.peek().tok == Tok::Eof {
                return Err(self
                    .expect_kw("END_CONFIGURATION", Some(("CONFIGURATION", start)))
                    .err()
                    .unwrap_or_else(|| self.unexpected("`END_CONFIGURATION`")));
            } else {
                self.config_item(&mut config)?;
            }
        }
    }

    fn config_item(&mut self, config: &mut Config) -> Result<(), StError> {
        if self.is_kw("VAR_GLOBAL") {
            config.globals.extend(self.var_block()?);
        } else if self.eat_kw("TASK") {
            let name = self.ident("the task's name")?;
            self.expect_sym("(", "and the task's properties")?;
            let mut task = Task { name, interval: None, single: false, priority: 0 };
            loop {
                let key = self.ident("`INTERVAL`, `SINGLE` or `PRIORITY`")?;
                self.expect_sym(":=", "after the task property")?;
                let value = self.expr()?;
                match (key.key().as_str(), &value.kind) {
                    ("INTERVAL", ExprKind::Time(us)) => task.interval = Some(*us),
                    ("INTERVAL", _) => {
                        return Err(StError::new(
                            value.span,
                            "the interval must be a duration literal",
                            "expected a duration like `T#20ms`",
                        ));
                    }
                    ("PRIORITY", ExprKind::Int(p)) => task.priority = *p,
                    ("SINGLE", _) => task.single = true,
                    _ => {}
                }
                if !self.eat_sym(",") {
                    break;
                }
            }
            self.expect_sym(")", "after the task's properties")?;
            self.expect_sym(";", "after the task")?;
            config.tasks.push(task);
        } else if self.eat_kw("PROGRAM") {
            let name = self.ident("the program instance's name")?;
            let task = if self.eat_kw("WITH") { Some(self.ident("a task name")?) } else { None };
            self.expect_sym(":", "and the program's type")?;
            let ty = self.ident("the program's type")?;
            if self.is_sym("(") {
                let start = self.bump().span;
                let mut depth = 1;
                while depth > 0 {
                    match self.bump().tok {
                        Tok::Sym("(") => depth += 1,
                        Tok::Sym(")") => depth -= 1,
                        Tok::Eof => {
                            return Err(StError::new(
                                start,
                                "unclosed argument list",
                                "this `(` is never closed",
                            ));
                        }
                        _ => {}
                    }
                }
            }
            self.expect_sym(";", "after the program instance")?;
            config.instances.push(Instance { name, task, ty });
        } else {
            return Err(self.unexpected("`TASK`, `PROGRAM`, `VAR_GLOBAL` or `END_RESOURCE`"));
        }
        Ok(())
    }

    /// Statements up to a closing keyword (or the end of a body).
    fn stmts(&mut self, opened: Option<(&str, Span)>) -> Result<Vec<Stmt>, StError> {
        let mut out = Vec::new();
        loop {
            let t = self.peek().clone();
            if t.tok == Tok::Eof || ENDERS.iter().any(|k| t.is_kw(k)) {
                if t.tok == Tok::Eof
                    && let Some((what, span)) = opened
                {
                    let end = match what {
                        "PROGRAM" => "END_PROGRAM",
                        "FUNCTION_BLOCK" => "END_FUNCTION_BLOCK",
                        "FUNCTION" => "END_FUNCTION",
                        "IF" => "END_IF",
                        "CASE" => "END_CASE",
                        "FOR" => "END_FOR",
                        "WHILE" => "END_WHILE",
                        "ACTION" => "END_ACTION",
                        _ => "END_REPEAT",
                    };
                    return Err(self
                        .expect_kw(end, Some((what, span)))
                        .err()
                        .unwrap_or_else(|| self.unexpected(end)));
                }
                return Ok(out);
            }
            out.push(self.stmt(opened)?);
        }
    }

    fn stmt(&mut self, opened: Option<(&str, Span)>) -> Result<Stmt, StError> {
        let t = self.peek().clone();
        let start = t.span;
        let kind = if let Tok::Assert(body, at) = &t.tok {
            self.bump();
            return self.assert(body, *at, start);
        } else if self.eat_sym(";") {
            return Ok(Stmt { kind: StmtKind::Empty, span: start });
        } else if self.eat_kw("IF") {
            let mut branches = Vec::new();
            let c = self.expr()?;
            self.expect_kw("THEN", None)?;
            branches.push((c, self.stmts(Some(("IF", start)))?));
            let mut otherwise = Vec::new();
            loop {
                if self.eat_kw("ELSIF") {
                    let c = self.expr()?;
                    self.expect_kw("THEN", None)?;
                    branches.push((c, self.stmts(Some(("IF", start)))?));
                } else if self.eat_kw("ELSE") {
                    otherwise = self.stmts(Some(("IF", start)))?;
                } else {
                    break;
                }
            }
            self.expect_kw("END_IF", Some(("IF", start)))?;
            StmtKind::If(branches, otherwise)
        } else if self.eat_kw("CASE") {
            let selector = self.expr()?;
            self.expect_kw("OF", None)?;
            let mut arms = Vec::new();
            let mut otherwise = Vec::new();
            loop {
                if self.eat_kw("ELSE") {
                    otherwise = self.stmts(Some(("CASE", start)))?;
                    break;
                }
                if self.is_kw("END_CASE") || self.peek().tok == Tok::Eof {
                    break;
                }
                let mut labels = Vec::new();
                loop {
                    let a = self.expr()?;
                    let b = if self.eat_sym("..") { Some(self.expr()?) } else { None };
                    labels.push((a, b));
                    if !self.eat_sym(",") {
                        break;
                    }
                }
                self.expect_sym(":", "after the case labels")?;
                let body = self.case_arm(start)?;
                arms.push((labels, body));
            }
            self.expect_kw("END_CASE", Some(("CASE", start)))?;
            StmtKind::Case(selector, arms, otherwise)
        } else if self.eat_kw("FOR") {
            let var = self.ident("the loop variable")?;
            self.expect_sym(":=", "after the loop variable")?;
            let from = self.expr()?;
            self.expect_kw("TO", None)?;
            let to = self.expr()?;
            let by = if self.eat_kw("BY") { Some(self.expr()?) } else { None };
            self.expect_kw("DO", None)?;
            let body = self.stmts(Some(("FOR", start)))?;
            self.expect_kw("END_FOR", Some(("FOR", start)))?;
            StmtKind::For(var, from, to, by, body)
        } else if self.eat_kw("WHILE") {
            let c = self.expr()?;
            self.expect_kw("DO", None)?;
            let body = self.stmts(Some(("WHILE", start)))?;
            self.expect_kw("END_WHILE", Some(("WHILE", start)))?;
            StmtKind::While(c, body)
        } else if self.eat_kw("REPEAT") {
            let body = self.stmts(Some(("REPEAT", start)))?;
            self.expect_kw("UNTIL", Some(("REPEAT", start)))?;
            let c = self.expr()?;
            self.expect_kw("END_REPEAT", Some(("REPEAT", start)))?;
            StmtKind::Repeat(body, c)
        } else if self.eat_kw("EXIT") {
            StmtKind::Exit
        } else if self.eat_kw("CONTINUE") {
            StmtKind::Continue
        } else if self.eat_kw("RETURN") {
            StmtKind::Return
        } else {
            let _ = opened;
            let target = self.postfix()?;
            if self.eat_sym(":=") {
                let value = self.expr()?;
                StmtKind::Assign(target, value)
            } else if let ExprKind::Call(name, args) = target.kind {
                let callee = Expr { kind: ExprKind::Var(name), span: target.span };
                StmtKind::Call(callee, args)
            } else if self.eat_sym("(") {
                let args = self.args()?;
                StmtKind::Call(target, args)
            } else if let ExprKind::Var(name) = &target.kind {
                // A lone word: most often a misspelt keyword.
                let mut e = StError::new(
                    name.span,
                    format!("expected a statement, found `{}`", name.name),
                    "a statement assigns (`x := …;`) or calls (`T1(…);`)",
                );
                if let Some(k) = crate::diag::did_you_mean(&name.key(), KEYWORDS.iter().copied()) {
                    e.notes.push(format!("did you mean `{k}`?"));
                }
                return Err(e);
            } else {
                return Err(
                    self.unexpected("`:=` or `(` after the name (a statement assigns or calls)")
                );
            }
        };
        // CODESYS lets `;` after `END_IF`, `END_CASE` and the loops' ends be left out.
        let block = matches!(
            kind,
            StmtKind::If(..)
                | StmtKind::Case(..)
                | StmtKind::For(..)
                | StmtKind::While(..)
                | StmtKind::Repeat(..)
        );
        let end = match block {
            true if !self.is_sym(";") => self.toks[self.at.saturating_sub(1)].span,
            _ => self.expect_sym(";", "after the statement")?,
        };
        Ok(Stmt { kind, span: start.to(end) })
    }

    /// The statements of a CASE arm: up to the next label (`expr :` or `expr ..`), `ELSE`
    /// or `END_CASE`.
    fn case_arm(&mut self, start: Span) -> Result<Vec<Stmt>, StError> {
        let mut out = Vec::new();
        loop {
            if self.is_kw("ELSE") || self.is_kw("END_CASE") || self.peek().tok == Tok::Eof {
                return Ok(out);
            }
            // A label starts with a literal, or a (dotted) name followed by `:`, `,` or `..`.
            let mut k = 0;
            while matches!(self.peek_at(k).tok, Tok::Ident(_))
                && matches!(self.peek_at(k + 1).tok, Tok::Sym("."))
            {
                k += 2;
            }
            let next = &self.peek_at(k + 1).tok;
            let label_like = matches!(self.peek().tok, Tok::Int(_) | Tok::Typed(_))
                || (matches!(self.peek_at(k).tok, Tok::Ident(_))
                    && matches!(next, Tok::Sym(":") | Tok::Sym(",") | Tok::Sym("..")));
            if label_like || self.is_sym("-") {
                return Ok(out);
            }
            out.push(self.stmt(Some(("CASE", start)))?);
        }
    }

    fn assert(&mut self, body: &str, at: usize, span: Span) -> Result<Stmt, StError> {
        let file = span.file;
        let end = at + body.len();
        let (expr_end, name) = match body.rfind(':').filter(|k| !body[*k..].starts_with(":=")) {
            Some(k) => {
                let raw = &body[k + 1..];
                let trimmed = raw.trim().trim_end_matches("*)").trim();
                let start = at + k + 1 + (raw.len() - raw.trim_start().len());
                (
                    at + k,
                    (!trimmed.is_empty()).then(|| Ident {
                        name: trimmed.to_string(),
                        span: Span::new(file, start..start + trimmed.len()),
                    }),
                )
            }
            None => (end, None),
        };
        let toks = lex(file, self.text, at..expr_end)?;
        let mut sub = Parser::new(toks, self.text);
        let expr = sub.expr()?;
        if sub.peek().tok != Tok::Eof {
            return Err(sub.unexpected("the end of the asserted expression (`: name` may follow)"));
        }
        Ok(Stmt { kind: StmtKind::Assert(expr, name), span })
    }

    fn args(&mut self) -> Result<Vec<Arg>, StError> {
        let mut args = Vec::new();
        if self.eat_sym(")") {
            return Ok(args);
        }
        loop {
            let negated_out = self.is_kw("NOT") && matches!(self.peek_at(2).tok, Tok::Sym("=>"));
            if negated_out {
                self.bump();
            }
            if matches!(self.peek().tok, Tok::Ident(_))
                && matches!(self.peek_at(1).tok, Tok::Sym(":=") | Tok::Sym("=>"))
            {
                let name = self.ident("a parameter name")?;
                if self.eat_sym(":=") {
                    args.push(Arg::Input(name, self.expr()?));
                } else {
                    self.bump();
                    // CODESYS writes `Q =>` with no variable for an output it does not read.
                    if !self.is_sym(",") && !self.is_sym(")") {
                        args.push(Arg::Output(name, negated_out, self.postfix()?));
                    }
                }
            } else {
                args.push(Arg::Positional(self.expr()?));
            }
            if self.eat_sym(")") {
                return Ok(args);
            }
            self.expect_sym(",", "or `)` between arguments")?;
        }
    }

    fn expr(&mut self) -> Result<Expr, StError> {
        self.binary(0)
    }

    fn binary(&mut self, level: usize) -> Result<Expr, StError> {
        const LEVELS: &[&[(&str, BinOp)]] = &[
            &[("OR", BinOp::Or)],
            &[("XOR", BinOp::Xor)],
            &[("AND", BinOp::And), ("&", BinOp::And)],
            &[("=", BinOp::Eq), ("<>", BinOp::Ne)],
            &[("<", BinOp::Lt), ("<=", BinOp::Le), (">", BinOp::Gt), (">=", BinOp::Ge)],
            &[("+", BinOp::Add), ("-", BinOp::Sub)],
            &[("*", BinOp::Mul), ("/", BinOp::Div), ("MOD", BinOp::Mod)],
            &[("**", BinOp::Pow)],
        ];
        if level == LEVELS.len() {
            return self.unary();
        }
        let mut left = self.binary(level + 1)?;
        loop {
            let t = self.peek();
            let op = LEVELS[level].iter().find(|(s, _)| match &t.tok {
                Tok::Sym(x) => x == s,
                Tok::Ident(w) => w.eq_ignore_ascii_case(s),
                _ => false,
            });
            let Some((_, op)) = op else { return Ok(left) };
            self.bump();
            let right = self.binary(level + 1)?;
            let span = left.span.to(right.span);
            left = Expr { kind: ExprKind::Binary(*op, Box::new(left), Box::new(right)), span };
        }
    }

    fn unary(&mut self) -> Result<Expr, StError> {
        let t = self.peek().clone();
        let op = if t.is_kw("NOT") {
            Some(UnOp::Not)
        } else if t.tok == Tok::Sym("-") {
            Some(UnOp::Neg)
        } else {
            None
        };
        if let Some(op) = op {
            self.bump();
            let e = self.unary()?;
            let span = t.span.to(e.span);
            return Ok(Expr { kind: ExprKind::Unary(op, Box::new(e)), span });
        }
        self.postfix()
    }

    fn postfix(&mut self) -> Result<Expr, StError> {
        let mut e = self.primary()?;
        loop {
            if self.eat_sym(".") {
                let field = match self.bump() {
                    Token { tok: Tok::Ident(name), span, .. } => Ident { name, span },
                    Token { tok: Tok::Int(v), span, .. } => Ident { name: v.to_string(), span },
                    _ => return Err(self.unexpected("a member name after `.`")),
                };
                let span = e.span.to(field.span);
                e = Expr { kind: ExprKind::Member(Box::new(e), field), span };
                if self.is_sym("(") {
                    // `obj.Method(…)`: kept as a call of the dotted name (refused when lowered).
                    self.bump();
                    let args = self.args()?;
                    let span = span.to(self.toks[self.at.saturating_sub(1)].span);
                    let text = self.text.get(span.range()).unwrap_or("");
                    let name = text.split('(').next().unwrap_or("").trim().to_string();
                    e = Expr { kind: ExprKind::Call(Ident { name, span }, args), span };
                }
            } else if self.is_sym("[") {
                self.bump();
                let mut index = vec![self.expr()?];
                while self.eat_sym(",") {
                    index.push(self.expr()?);
                }
                let end = self.expect_sym("]", "after the index")?;
                let span = e.span.to(end);
                e = Expr { kind: ExprKind::Index(Box::new(e), index), span };
            } else {
                return Ok(e);
            }
        }
    }

    fn primary(&mut self) -> Result<Expr, StError> {
        let t = self.peek().clone();
        let kind = match &t.tok {
            Tok::Sym("(") => {
                self.bump();
                let e = self.expr()?;
                let end = self.expect_sym(")", "to close the parenthesis")?;
                return Ok(Expr { kind: e.kind, span: t.span.to(end) });
            }
            Tok::Int(v) => ExprKind::Int(*v),
            Tok::Time(us) => ExprKind::Time(*us),
            Tok::Typed(s) => match s.to_ascii_uppercase().as_str() {
                "BOOL#TRUE" | "BOOL#1" => ExprKind::Bool(true),
                "BOOL#FALSE" | "BOOL#0" => ExprKind::Bool(false),
                _ => ExprKind::Literal(s.clone()),
            },
            Tok::Real(s) | Tok::Str(s) | Tok::Direct(s) => ExprKind::Literal(s.clone()),
            Tok::Ident(w) if w.eq_ignore_ascii_case("TRUE") => ExprKind::Bool(true),
            Tok::Ident(w) if w.eq_ignore_ascii_case("FALSE") => ExprKind::Bool(false),
            Tok::Ident(w) if !KEYWORDS.contains(&w.to_ascii_uppercase().as_str()) => {
                let name = Ident { name: w.clone(), span: t.span };
                self.bump();
                if self.is_sym("(") {
                    self.bump();
                    let args = self.args()?;
                    let span = t.span.to(self.toks[self.at.saturating_sub(1)].span);
                    return Ok(Expr { kind: ExprKind::Call(name, args), span });
                }
                return Ok(Expr { kind: ExprKind::Var(name), span: t.span });
            }
            _ => return Err(self.unexpected("an expression")),
        };
        self.bump();
        Ok(Expr { kind, span: t.span })
    }
}

/// The 1-based line and column of `offset` in `text`.
fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rfind('\n').map_or(before.len(), |n| before.len() - n - 1) + 1;
    (line, col)
}
