//! The textual sequential function chart (IEC 61131-3 B.1.6): `INITIAL_STEP`, `STEP` with action associations, `TRANSITION … FROM … TO …` with a Structured Text condition and an optional priority, `ACTION … END_ACTION` with a Structured Text body.

use super::Parser;
use crate::iec::StError;
use crate::iec::ast::{Action, Association, Expr, ExprKind, Ident, Sfc, Step, Transition};
use crate::iec::lexer::Tok;
use crate::iec::lexer::lex;

/// The qualifiers of an action association (`D`, `L`, `SD`, `DS`, `SL` take a time).
const QUALIFIERS: &[&str] = &["N", "R", "S", "P", "P0", "P1", "L", "D", "SD", "DS", "SL"];
const TIMED: &[&str] = &["L", "D", "SD", "DS", "SL"];

/// Parses a transition's condition at `range` of `text` (a PLCopen chart's): an
/// expression, written alone (inline) or as `:= expression;` (a named transition's body).
pub fn parse_condition(
    file: usize,
    text: &str,
    range: std::ops::Range<usize>,
) -> Result<Expr, StError> {
    let toks = lex(file, text, range)?;
    let mut p = Parser::new(toks, text);
    let assigned = p.eat_sym(":=");
    let e = p.expr()?;
    if assigned {
        p.expect_sym(";", "after the transition's condition")?;
    } else {
        p.eat_sym(";");
    }
    p.expect_eof()?;
    Ok(e)
}

impl Parser<'_> {
    /// Whether a POU's body starting here is a chart.
    pub(super) fn sfc_ahead(&self) -> bool {
        ["INITIAL_STEP", "STEP", "TRANSITION", "ACTION"].iter().any(|k| self.is_kw(k))
            && matches!(self.peek_at(1).tok, Tok::Ident(_))
    }

    /// The chart's elements up to the POU's end keyword.
    pub(super) fn sfc(&mut self) -> Result<Sfc, StError> {
        let mut sfc = Sfc::default();
        loop {
            let start = self.peek().span;
            if self.eat_kw("INITIAL_STEP") {
                sfc.steps.push(self.step(true, start)?);
            } else if self.eat_kw("STEP") {
                sfc.steps.push(self.step(false, start)?);
            } else if self.eat_kw("TRANSITION") {
                sfc.transitions.push(self.transition(start)?);
            } else if self.eat_kw("ACTION") {
                let name = self.ident("the action's name")?;
                self.expect_sym(":", "after the action's name")?;
                if self.il_ahead() {
                    return Err(StError::new(
                        self.peek().span,
                        "an action in Instruction List is not read yet",
                        "write the action in Structured Text",
                    ));
                }
                let body = self.stmts(Some(("ACTION", start)))?;
                let end = self.expect_kw("END_ACTION", Some(("ACTION", start)))?;
                sfc.actions.push(Action { name, body, span: start.to(end) });
            } else if matches!(&self.peek().tok, Tok::Ident(w) if w.to_ascii_uppercase().starts_with("END_"))
                || self.peek().tok == Tok::Eof
            {
                return Ok(sfc);
            } else {
                return Err(self.unexpected(
                    "`STEP`, `INITIAL_STEP`, `TRANSITION` or `ACTION` in a sequential function chart",
                ));
            }
        }
    }

    fn step(&mut self, initial: bool, start: crate::diag::Span) -> Result<Step, StError> {
        let what = if initial { "INITIAL_STEP" } else { "STEP" };
        let name = self.ident("the step's name")?;
        self.expect_sym(":", "after the step's name")?;
        let mut actions = Vec::new();
        while !self.is_kw("END_STEP") {
            if self.peek().tok == Tok::Eof {
                self.expect_kw("END_STEP", Some((what, start)))?;
            }
            actions.push(self.association()?);
            self.expect_sym(";", "after the action association")?;
        }
        self.expect_kw("END_STEP", Some((what, start)))?;
        Ok(Step { name, initial, actions })
    }

    /// `action(qualifier[, time][, indicator…])`.
    fn association(&mut self) -> Result<Association, StError> {
        let action = self.ident("an action's name")?;
        self.expect_sym("(", "after the action's name (its qualifier in parentheses)")?;
        let (mut qualifier, mut time) = (None, None);
        if let Tok::Ident(w) = &self.peek().tok {
            let upper = w.to_ascii_uppercase();
            if !QUALIFIERS.contains(&upper.as_str()) {
                return Err(
                    self.unexpected("an action qualifier (N, R, S, P, P0, P1, L, D, SD, DS, SL)")
                );
            }
            let t = self.bump();
            if TIMED.contains(&upper.as_str()) {
                self.expect_sym(",", "and the qualifier's time")?;
                time = Some(self.action_time()?);
            }
            qualifier = Some(Ident { name: upper, span: t.span });
        }
        // Indicator variables show what the action does; they do not change it.
        while self.eat_sym(",") {
            self.ident("an indicator variable")?;
        }
        let end = self.expect_sym(")", "to close the action association")?;
        Ok(Association { span: action.span.to(end), action, qualifier, time })
    }

    fn action_time(&mut self) -> Result<Expr, StError> {
        let t = self.peek().clone();
        match t.tok {
            Tok::Time(us) => {
                self.bump();
                Ok(Expr { kind: ExprKind::Time(us), span: t.span })
            }
            Tok::Ident(_) => {
                let id = self.ident("a duration")?;
                Ok(Expr { span: id.span, kind: ExprKind::Var(id) })
            }
            _ => Err(self.unexpected("a duration like `T#2s` or a TIME variable")),
        }
    }

    fn transition(&mut self, start: crate::diag::Span) -> Result<Transition, StError> {
        let name = if self.is_kw("FROM") || self.is_sym("(") {
            None
        } else {
            Some(self.ident("the transition's name or `FROM`")?)
        };
        let mut priority = None;
        if self.eat_sym("(") {
            if !self.eat_kw("PRIORITY") {
                return Err(self.unexpected("`PRIORITY`"));
            }
            self.expect_sym(":=", "after `PRIORITY`")?;
            let t = self.bump();
            let Tok::Int(n) = t.tok else {
                return Err(StError::new(
                    t.span,
                    "expected the priority, an integer",
                    "expected an integer",
                ));
            };
            priority = Some((n, t.span));
            self.expect_sym(")", "after the priority")?;
        }
        self.expect_kw("FROM", Some(("TRANSITION", start)))?;
        let from = self.step_names()?;
        self.expect_kw("TO", Some(("TRANSITION", start)))?;
        let to = self.step_names()?;
        if self.is_sym(":") {
            return Err(StError::new(
                self.peek().span,
                "a transition condition in Instruction List is not read yet",
                "write it as `:= condition;`",
            ));
        }
        self.expect_sym(":=", "and the transition's condition")?;
        let condition = self.expr()?;
        self.expect_sym(";", "after the transition's condition")?;
        let end = self.expect_kw("END_TRANSITION", Some(("TRANSITION", start)))?;
        Ok(Transition { name, priority, from, to, condition, span: start.to(end) })
    }

    /// `S` or `(S1, S2, …)`.
    fn step_names(&mut self) -> Result<Vec<Ident>, StError> {
        if !self.eat_sym("(") {
            return Ok(vec![self.ident("a step's name")?]);
        }
        let mut out = vec![self.ident("a step's name")?];
        while self.eat_sym(",") {
            out.push(self.ident("a step's name")?);
        }
        self.expect_sym(")", "to close the list of steps")?;
        Ok(out)
    }
}
