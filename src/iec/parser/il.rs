//! Instruction List bodies: one instruction per line (an optional `label:`, an operator with its `N`/`C` modifiers and its operand), `OP( … )` nesting, jumps, calls, returns and function-block inputs as operators; operands are read with the Structured Text expression parser.

use super::{KEYWORDS, Parser, describe, line_col};
use crate::diag::Span;
use crate::iec::StError;
use crate::iec::ast::*;
use crate::iec::lexer::Tok;

/// What an operator word does.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    Ld,
    St,
    S,
    R,
    Not,
    Bin(BinOp),
    Jmp,
    Cal,
    Ret,
    FbInput,
}

/// The IL operators: their spelling, kind, `N` modifier and `C` modifier.
const OPERATORS: &[(&str, Kind, bool, bool)] = &[
    ("LD", Kind::Ld, false, false),
    ("LDN", Kind::Ld, true, false),
    ("ST", Kind::St, false, false),
    ("STN", Kind::St, true, false),
    ("S", Kind::S, false, false),
    ("R", Kind::R, false, false),
    ("NOT", Kind::Not, false, false),
    ("AND", Kind::Bin(BinOp::And), false, false),
    ("ANDN", Kind::Bin(BinOp::And), true, false),
    ("OR", Kind::Bin(BinOp::Or), false, false),
    ("ORN", Kind::Bin(BinOp::Or), true, false),
    ("XOR", Kind::Bin(BinOp::Xor), false, false),
    ("XORN", Kind::Bin(BinOp::Xor), true, false),
    ("ADD", Kind::Bin(BinOp::Add), false, false),
    ("SUB", Kind::Bin(BinOp::Sub), false, false),
    ("MUL", Kind::Bin(BinOp::Mul), false, false),
    ("DIV", Kind::Bin(BinOp::Div), false, false),
    ("MOD", Kind::Bin(BinOp::Mod), false, false),
    ("GT", Kind::Bin(BinOp::Gt), false, false),
    ("GE", Kind::Bin(BinOp::Ge), false, false),
    ("EQ", Kind::Bin(BinOp::Eq), false, false),
    ("NE", Kind::Bin(BinOp::Ne), false, false),
    ("LE", Kind::Bin(BinOp::Le), false, false),
    ("LT", Kind::Bin(BinOp::Lt), false, false),
    ("JMP", Kind::Jmp, false, false),
    ("JMPC", Kind::Jmp, false, true),
    ("JMPCN", Kind::Jmp, true, true),
    ("CAL", Kind::Cal, false, false),
    ("CALC", Kind::Cal, false, true),
    ("CALCN", Kind::Cal, true, true),
    ("RET", Kind::Ret, false, false),
    ("RETC", Kind::Ret, false, true),
    ("RETCN", Kind::Ret, true, true),
    ("S1", Kind::FbInput, false, false),
    ("R1", Kind::FbInput, false, false),
    ("CLK", Kind::FbInput, false, false),
    ("CU", Kind::FbInput, false, false),
    ("CD", Kind::FbInput, false, false),
    ("PV", Kind::FbInput, false, false),
    ("IN", Kind::FbInput, false, false),
    ("PT", Kind::FbInput, false, false),
];

/// Standard functions that may stand as IL operators (`MAX b`), besides `X_TO_Y`
/// conversions and functions the file declares.
const FUNCTIONS: &[&str] = &[
    "ABS", "SQRT", "LN", "LOG", "EXP", "SIN", "COS", "TAN", "ASIN", "ACOS", "ATAN", "EXPT", "MOVE",
    "SEL", "MAX", "MIN", "LIMIT", "MUX", "SHL", "SHR", "ROL", "ROR", "TRUNC", "LEN", "LEFT",
    "RIGHT", "MID", "CONCAT", "INSERT", "DELETE", "REPLACE", "FIND",
];

fn operator(word: &str) -> Option<(Kind, bool, bool)> {
    let upper = word.to_ascii_uppercase();
    OPERATORS.iter().find(|o| o.0 == upper).map(|o| (o.1, o.2, o.3))
}

fn cond(c: bool, n: bool) -> IlCond {
    match (c, n) {
        (false, _) => IlCond::Always,
        (true, false) => IlCond::IfTrue,
        (true, true) => IlCond::IfFalse,
    }
}

impl Parser<'_> {
    /// Whether the body that starts here is Instruction List: a label, or an IL operator
    /// not followed by what follows a Structured Text statement's first name.
    pub(super) fn il_ahead(&self) -> bool {
        let (t, next) = (self.peek(), self.peek_at(1));
        let Tok::Ident(word) = &t.tok else { return t.is_sym_tok("&") };
        let label = matches!(next.tok, Tok::Sym(":")) && !KEYWORDS.contains(&word.as_str());
        let st_follows = matches!(next.tok, Tok::Sym(":=" | "." | "[" | "=>"))
            || (matches!(next.tok, Tok::Sym("(")) && !next.line_start && {
                !matches!(operator(word), Some((Kind::Bin(_) | Kind::Ld, ..)))
            });
        label || (operator(word).is_some() && !st_follows)
    }

    /// IL lines up to a POU's end keyword or the end of the text.
    pub(super) fn il_lines(&mut self) -> Result<Vec<IlLine>, StError> {
        let mut out = Vec::new();
        loop {
            let t = self.peek();
            let end_word =
                matches!(&t.tok, Tok::Ident(w) if w.to_ascii_uppercase().starts_with("END_"));
            if t.tok == Tok::Eof || end_word {
                return Ok(out);
            }
            out.push(self.il_line()?);
        }
    }

    fn at_line_end(&self) -> bool {
        let t = self.peek();
        t.line_start || t.tok == Tok::Eof || t.is_sym_tok(")")
    }

    fn il_line(&mut self) -> Result<IlLine, StError> {
        let start = self.peek().span;
        let is_label = matches!(&self.peek().tok, Tok::Ident(w) if !KEYWORDS.contains(&w.to_ascii_uppercase().as_str()))
            && matches!(self.peek_at(1).tok, Tok::Sym(":"));
        let label = if is_label {
            let id = self.ident("a label")?;
            self.bump();
            Some(id)
        } else {
            None
        };
        let instr = if label.is_some() && (self.peek().line_start || self.peek().tok == Tok::Eof) {
            None
        } else {
            Some(self.il_instr()?)
        };
        if !self.at_line_end() || self.is_sym(")") {
            return Err(self.unexpected("the end of the line after the IL instruction"));
        }
        let span = self.since(start);
        Ok(IlLine { label, instr, span })
    }

    /// The span from `start` to the last token read.
    fn since(&self, start: Span) -> Span {
        start.to(self.toks[self.at.saturating_sub(1)].span)
    }

    fn il_instr(&mut self) -> Result<IlInstr, StError> {
        let t = self.peek().clone();
        if let Tok::Assert(body, at) = &t.tok {
            self.bump();
            let s = self.assert(body, *at, t.span)?;
            let StmtKind::Assert(e, name) = s.kind else {
                unreachable!("assert() returns an assertion")
            };
            return Ok(IlInstr::Assert(e, name));
        }
        let (word, kind, negate, c) = if t.is_sym_tok("&") {
            // `&` is `AND`; `&N` is `ANDN`.
            self.bump();
            let n = self.peek().is_kw("N") && self.peek().span.start == t.span.end;
            let end = if n { self.bump().span } else { t.span };
            let word = Ident { name: if n { "&N" } else { "&" }.into(), span: t.span.to(end) };
            (word, Kind::Bin(BinOp::And), n, false)
        } else {
            let Tok::Ident(w) = &t.tok else {
                return Err(self.unexpected("an IL operator"));
            };
            match operator(w) {
                Some((kind, n, c)) => {
                    self.bump();
                    (Ident { name: w.clone(), span: t.span }, kind, n, c)
                }
                None => return self.function_op(),
            }
        };
        Ok(match kind {
            Kind::Jmp => {
                if self.at_line_end() {
                    return Err(StError::new(
                        word.span,
                        format!("expected a label after `{}`", word.name),
                        "a jump names the label it goes to",
                    ));
                }
                IlInstr::Jump { cond: cond(c, negate), label: self.ident("a label")?, word }
            }
            Kind::Ret => IlInstr::Return { cond: cond(c, negate), word },
            Kind::Cal => {
                let instance =
                    self.target(&format!("a function block instance after `{}`", word.name))?;
                let args = if self.is_sym("(") && !self.peek().line_start {
                    self.bump();
                    self.args()?
                } else {
                    Vec::new()
                };
                IlInstr::Call { cond: cond(c, negate), instance, args, word }
            }
            Kind::FbInput => {
                let pin = word.name.to_ascii_uppercase();
                let instance =
                    self.target(&format!("a function block instance after `{}`", word.name))?;
                IlInstr::FbInput { pin, instance, word }
            }
            Kind::Not => IlInstr::Op { op: IlOp::Not, negate, operand: None, nested: None, word },
            Kind::Ld | Kind::St | Kind::S | Kind::R | Kind::Bin(_) => {
                let op = match kind {
                    Kind::Ld => IlOp::Ld,
                    Kind::St => IlOp::St,
                    Kind::S => IlOp::S,
                    Kind::R => IlOp::R,
                    Kind::Bin(b) => IlOp::Bin(b),
                    _ => unreachable!("matched above"),
                };
                if matches!(kind, Kind::Bin(_)) && self.is_sym("(") && !self.peek().line_start {
                    let (operand, nested) = self.nested(&word)?;
                    IlInstr::Op { op, negate, operand, nested: Some(nested), word }
                } else {
                    if self.at_line_end() {
                        return Err(self.unexpected(&format!("an operand after `{}`", word.name)));
                    }
                    let operand = Some(self.operand()?);
                    IlInstr::Op { op, negate, operand, nested: None, word }
                }
            }
        })
    }

    /// A function used as an operator (`MAX b`, `LIMIT 0, 10`), or an unknown operator.
    fn function_op(&mut self) -> Result<IlInstr, StError> {
        let t = self.peek().clone();
        let Tok::Ident(w) = &t.tok else { return Err(self.unexpected("an IL operator")) };
        let upper = w.to_ascii_uppercase();
        let known = FUNCTIONS.contains(&upper.as_str())
            || upper.contains("_TO_")
            || upper.starts_with("TO_")
            || self.functions.contains(&upper);
        if !known {
            let mut e = StError::new(
                t.span,
                format!("unknown IL operator `{w}`"),
                "expected an IL operator",
            );
            let candidates = OPERATORS.iter().map(|o| o.0).chain(FUNCTIONS.iter().copied());
            if let Some(m) = crate::diag::did_you_mean(&upper, candidates) {
                e.notes.push(format!("did you mean `{m}`?"));
            }
            return Err(e);
        }
        self.bump();
        let name = Ident { name: w.clone(), span: t.span };
        let mut args = Vec::new();
        if !self.at_line_end() {
            args.push(Arg::Positional(self.operand()?));
            while self.eat_sym(",") {
                args.push(Arg::Positional(self.operand()?));
            }
        }
        let operand = (!args.is_empty()).then(|| {
            let span = self.since(name.span);
            Expr { kind: ExprKind::Call(name.clone(), args), span }
        });
        Ok(IlInstr::Op {
            op: IlOp::Function(name.clone()),
            negate: false,
            operand,
            nested: None,
            word: name,
        })
    }

    /// An operand: a literal (possibly negative), a variable, a member, a direct address.
    fn operand(&mut self) -> Result<Expr, StError> {
        if self.is_sym("-") {
            let minus = self.bump().span;
            let e = self.postfix()?;
            let span = minus.to(e.span);
            return Ok(Expr { kind: ExprKind::Unary(UnOp::Neg, Box::new(e)), span });
        }
        self.postfix()
    }

    /// A function-block instance named after a call operator.
    fn target(&mut self, what: &str) -> Result<Expr, StError> {
        if self.at_line_end() {
            return Err(self.unexpected(what));
        }
        let id = self.ident(what)?;
        let mut e = Expr { span: id.span, kind: ExprKind::Var(id) };
        while self.is_sym(".") && !self.peek().line_start {
            self.bump();
            let f = self.ident("a member name after `.`")?;
            let span = e.span.to(f.span);
            e = Expr { kind: ExprKind::Member(Box::new(e), f), span };
        }
        Ok(e)
    }

    /// `OP( operand` then lines, then `)`; or `OP( LD a OR b )` on one line.
    fn nested(&mut self, op: &Ident) -> Result<(Option<Expr>, Vec<IlLine>), StError> {
        let open = self.bump().span;
        let first_is_op = matches!(&self.peek().tok, Tok::Ident(w) if operator(w).is_some());
        let operand =
            if !self.at_line_end() && !first_is_op { Some(self.operand()?) } else { None };
        let mut lines = Vec::new();
        loop {
            if self.eat_sym(")") {
                return Ok((operand, lines));
            }
            let t = self.peek();
            let end_word =
                matches!(&t.tok, Tok::Ident(w) if w.to_ascii_uppercase().starts_with("END_"));
            if t.tok == Tok::Eof || end_word {
                let (line, _) = line_col(self.text, op.span.start);
                let opener = format!("{}(", op.name.to_ascii_uppercase());
                let mut e = StError::new(
                    t.span,
                    format!(
                        "expected `)` to close the `{opener}` at line {line}, found {}",
                        describe(t)
                    ),
                    "expected `)`",
                );
                e.related =
                    Some(Box::new((op.span.to(open), format!("this `{opener}` is not closed"))));
                return Err(e);
            }
            let start = self.peek().span;
            let instr = self.il_instr()?;
            if !self.at_line_end() {
                return Err(self.unexpected("the end of the line after the IL instruction"));
            }
            lines.push(IlLine { label: None, instr: Some(instr), span: self.since(start) });
        }
    }
}
