//! A recursive-descent parser from tokens to the syntax tree, recovering at statement keywords.
//!
//! Loosest to tightest: `=>`/`=` (top of a statement only), `+`, `.`, `/`, `!`.
//! `/` chains are kept whole ([`AstKind::Chain`]); the resolver decides which
//! operands are durations.

use super::SyntaxError;
use super::ast::{
    Ast, AstGoal, AstKind, AstPattern, AstProof, AstStatement, AstStep, ClaimKind, Func, NamedKind,
    RelOp, RuleRef,
};
use super::ast::{CmpOp, IntOperand};
use super::lexer::{Keyword, Tok, Token};
use crate::diag::Span;

/// How deeply expressions may nest before the parser gives up (keeps the stack safe).
const MAX_DEPTH: usize = 200;

/// The parser state over a token list that ends with [`Tok::Eof`].
pub struct Parser {
    tokens: Vec<Token>,
    pos: usize,
    depth: usize,
}

type PResult<T> = Result<T, SyntaxError>;

const ATOM: &[&str] =
    &["a signal name", "a duration", "`0*`", "`1*`", "`!`", "`(`", "`SR(`", "`RS(`"];

fn names(list: &[&str]) -> Vec<String> {
    list.iter().map(|s| s.to_string()).collect()
}

impl Parser {
    /// A parser over `tokens` (which must end with [`Tok::Eof`]; one is added if not).
    pub fn new(mut tokens: Vec<Token>) -> Parser {
        if tokens.last().map(|t| &t.tok) != Some(&Tok::Eof) {
            let span = tokens
                .last()
                .map(|t| Span::new(t.span.file, t.span.end..t.span.end))
                .unwrap_or(Span::new(0, 0..0));
            tokens.push(Token { tok: Tok::Eof, span });
        }
        Parser { tokens, pos: 0, depth: 0 }
    }

    fn peek(&self) -> &Token {
        let last = self.tokens.len() - 1;
        &self.tokens[self.pos.min(last)]
    }

    fn peek_at(&self, n: usize) -> &Tok {
        let last = self.tokens.len() - 1;
        &self.tokens[(self.pos + n).min(last)].tok
    }

    fn bump(&mut self) -> Token {
        let token = self.peek().clone();
        if self.pos < self.tokens.len() - 1 {
            self.pos += 1;
        }
        token
    }

    fn at(&self, tok: &Tok) -> bool {
        &self.peek().tok == tok
    }

    fn eat(&mut self, tok: &Tok) -> Option<Span> {
        if self.at(tok) { Some(self.bump().span) } else { None }
    }

    fn prev_end(&self) -> Span {
        let token = &self.tokens[self.pos.saturating_sub(1)];
        Span::new(token.span.file, token.span.end..token.span.end)
    }

    /// An "unexpected token" error at the current token.
    fn unexpected(&self, expected: Vec<String>) -> SyntaxError {
        let token = self.peek();
        if matches!(token.tok, Tok::Implies | Tok::Eq) && expected.iter().any(|e| e == "`)`") {
            return SyntaxError::RelationNotAtTop { span: token.span };
        }
        // At the end of the input, point just after the last token rather than at a blank line.
        let span = if token.tok == Tok::Eof && self.pos > 0 { self.prev_end() } else { token.span };
        SyntaxError::UnexpectedToken { span, found: token.tok.describe(), expected }
    }

    fn expect(&mut self, tok: Tok, what: &str) -> PResult<Span> {
        self.eat(&tok).ok_or_else(|| self.unexpected(vec![what.into()]))
    }

    fn at_statement_start(&self) -> bool {
        matches!(self.peek().tok, Tok::Keyword(k) if k.starts_statement())
    }

    /// Skips to the next statement keyword (or the end), past the statement begun at `start`.
    fn recover(&mut self, start: usize) {
        if self.pos == start {
            self.bump();
        }
        while !self.at(&Tok::Eof) && !self.at_statement_start() {
            self.bump();
        }
    }

    /// Parses a whole file; statements with errors are skipped and reported.
    pub fn document(&mut self) -> (Vec<AstStatement>, Vec<SyntaxError>) {
        let mut statements = Vec::new();
        let mut errors = Vec::new();
        while !self.at(&Tok::Eof) {
            let start = self.pos;
            match self.statement() {
                Ok(s) => statements.push(s),
                Err(e) => {
                    errors.push(e);
                    self.recover(start);
                }
            }
        }
        (statements, errors)
    }

    /// Checks that the input is used up.
    pub fn end(&mut self) -> PResult<()> {
        if self.at(&Tok::Eof) {
            Ok(())
        } else {
            Err(self.unexpected(names(&["an operator", "the end of the input"])))
        }
    }

    fn name(&mut self, what: &str) -> PResult<(String, Span)> {
        let token = self.peek().clone();
        match token.tok {
            Tok::Ident(s) | Tok::Quoted(s) => {
                self.bump();
                Ok((s, token.span))
            }
            Tok::Keyword(k) => {
                // Consume it, so recovery does not restart at a misused keyword.
                self.bump();
                Err(SyntaxError::ReservedWord { span: token.span, word: k.text().into() })
            }
            _ => Err(self.unexpected(vec![what.into()])),
        }
    }

    fn name_list(&mut self) -> PResult<Vec<(String, Span)>> {
        let mut list = vec![self.name("a name")?];
        while self.eat(&Tok::Comma).is_some() {
            list.push(self.name("a name")?);
        }
        Ok(list)
    }

    /// One statement, starting at its keyword.
    pub fn statement(&mut self) -> PResult<AstStatement> {
        let start = self.peek().span;
        let Tok::Keyword(keyword) = self.peek().tok else {
            return Err(self.unexpected(names(&[
                "a statement (`let`, `input`, `delay`, `assume`, `property`, `law`, `program`, `theorem`, `lemma`)",
            ])));
        };
        let statement = match keyword {
            Keyword::Let => {
                self.bump();
                let name = self.name("the name of the abbreviation")?;
                self.expect(Tok::Eq, "`=`")?;
                let value = self.expr()?;
                AstStatement::Let { name, value, span: start.to(self.prev_end()) }
            }
            Keyword::Input => {
                self.bump();
                AstStatement::Input(self.name_list()?)
            }
            Keyword::Delay => {
                self.bump();
                AstStatement::Delay(self.name_list()?)
            }
            Keyword::Program => {
                self.bump();
                let token = self.peek().clone();
                match token.tok {
                    Tok::Str(path) => {
                        self.bump();
                        AstStatement::Program(path, token.span)
                    }
                    _ => return Err(self.unexpected(names(&["a quoted path"]))),
                }
            }
            Keyword::Assume | Keyword::Property | Keyword::Law => {
                self.bump();
                let kind = match keyword {
                    Keyword::Assume => NamedKind::Assume,
                    Keyword::Property => NamedKind::Property,
                    _ => NamedKind::Law,
                };
                let name = self.name("a name for the statement")?;
                self.expect(Tok::Colon, "`:`")?;
                let goal = self.goal()?;
                let mut conditions = Vec::new();
                if kind == NamedKind::Law && self.eat(&Tok::Keyword(Keyword::If)).is_some() {
                    conditions.push(self.relation(None)?);
                    while self.eat(&Tok::Comma).is_some() {
                        conditions.push(self.relation(None)?);
                    }
                }
                AstStatement::Named {
                    kind,
                    name,
                    goal: Box::new(goal),
                    conditions,
                    span: start.to(self.prev_end()),
                }
            }
            Keyword::Theorem | Keyword::Lemma => {
                self.bump();
                let kind = match keyword {
                    Keyword::Theorem => ClaimKind::Theorem,
                    _ => ClaimKind::Lemma,
                };
                let name = self.name("a name for the statement")?;
                self.expect(Tok::Colon, "`:`")?;
                let goal = self.goal()?;
                let proof = self.proof()?;
                AstStatement::Claim {
                    kind,
                    name,
                    goal: Box::new(goal),
                    proof,
                    span: start.to(self.prev_end()),
                }
            }
            Keyword::After | Keyword::If | Keyword::Proof | Keyword::Qed | Keyword::By => {
                return Err(self.unexpected(names(&["a statement"])));
            }
        };
        if !self.at(&Tok::Eof) && !self.at_statement_start() {
            let mut expected = match &statement {
                AstStatement::Input(_) | AstStatement::Delay(_) => names(&["`,`"]),
                AstStatement::Program(..) | AstStatement::Claim { .. } => Vec::new(),
                _ => names(&["an operator"]),
            };
            expected.push("a new statement".into());
            if let AstStatement::Named { kind: NamedKind::Law, conditions, .. } = &statement {
                expected.push(if conditions.is_empty() { "`if`" } else { "`,`" }.into());
            }
            return Err(self.unexpected(expected));
        }
        Ok(statement)
    }

    /// `by auto`, `by r1, r2` or `proof START (= TERM [RULES])* qed`, after a claim's goal.
    fn proof(&mut self) -> PResult<AstProof> {
        if let Some(by) = self.eat(&Tok::Keyword(Keyword::By)) {
            let rules = self.rule_list("`auto` or the rules that justify the claim")?;
            let span = by.to(self.prev_end());
            if let [only] = rules.as_slice()
                && only.name == "auto"
            {
                return Ok(AstProof::Auto(span));
            }
            if let [only] = rules.as_slice()
                && only.name == "induction"
            {
                return Ok(AstProof::Induction(span));
            }
            return Ok(AstProof::By(rules, span));
        }
        if self.eat(&Tok::Keyword(Keyword::Proof)).is_none() {
            return Err(self.unexpected(names(&["`proof`", "`by`", "an operator"])));
        }
        let start = self.expr()?;
        let mut steps = Vec::new();
        loop {
            let op = match self.peek().tok {
                Tok::Eq => RelOp::Equals,
                Tok::Implies => RelOp::Implies,
                _ => break,
            };
            let op_span = self.bump().span;
            let term = self.expr()?;
            self.expect(Tok::LBracket, "`[` and the rules that justify this step")?;
            let rules = self.rule_list("a law, hypothesis or lemma name, or `auto`")?;
            let end = self.expect(Tok::RBracket, "`]` or `,`")?;
            steps.push(AstStep { op, op_span, term, rules, span: op_span.to(end) });
        }
        let what = if steps.is_empty() {
            names(&["`=`", "`=>`", "an operator"])
        } else {
            names(&["`=`", "`=>`", "`qed`"])
        };
        let qed = self.eat(&Tok::Keyword(Keyword::Qed)).ok_or_else(|| self.unexpected(what))?;
        Ok(AstProof::Calc { start, steps, qed })
    }

    fn rule_list(&mut self, what: &str) -> PResult<Vec<RuleRef>> {
        let (name, span) = self.name(what)?;
        let mut rules = vec![RuleRef { name, span }];
        while self.eat(&Tok::Comma).is_some() {
            let (name, span) = self.name(what)?;
            rules.push(RuleRef { name, span });
        }
        Ok(rules)
    }

    /// `after D: f => g`, `f => g`, `f = g`, or a requirement pattern ([`AstPattern`]).
    pub fn goal(&mut self) -> PResult<AstGoal> {
        let start = self.peek().span;
        if self.eat(&Tok::Keyword(Keyword::After)).is_some() {
            let after = self.expr()?;
            self.expect(Tok::Colon, "`:` after the duration")?;
            let mut goal = self.relation(Some(after))?;
            goal.span = start.to(goal.span);
            Ok(goal)
        } else {
            self.relation(None)
        }
    }

    /// Is the token at `n` the word `w` (a pattern's word: a name elsewhere)?
    fn word_at(&self, n: usize, w: &str) -> bool {
        matches!(self.peek_at(n), Tok::Ident(x) if x == w)
    }

    /// Does an operand start at `n` (so a word before it is a pattern's, not a name)?
    fn operand_at(&self, n: usize) -> bool {
        matches!(
            self.peek_at(n),
            Tok::Ident(_)
                | Tok::Quoted(_)
                | Tok::LParen
                | Tok::Not
                | Tok::Zero
                | Tok::One
                | Tok::Duration(_)
                | Tok::LBracket
        )
    }

    fn expect_word(&mut self, w: &str) -> PResult<Span> {
        if self.word_at(0, w) {
            return Ok(self.bump().span);
        }
        Err(self.unexpected(vec![format!("`{w}`")]))
    }

    /// A goal that is a pattern, `pattern` its operands; `lhs` and `rhs` repeat its first
    /// and last operand (only the pattern is read).
    fn pattern_goal(after: Option<Ast>, start: Span, pattern: AstPattern) -> AstGoal {
        let (first, last) = match &pattern {
            AstPattern::Always(f) | AstPattern::Never(f) | AstPattern::Reachable(f) => (f, f),
            AstPattern::Then { first, then, .. } => (first, then),
            AstPattern::Within { trigger, delay, .. } => (trigger, delay),
            AstPattern::NotBefore { response, trigger, .. } => (response, trigger),
            AstPattern::AtMost { signal, delay } | AstPattern::AtLeast { signal, delay } => {
                (signal, delay)
            }
        };
        let (lhs, rhs) = (first.clone(), last.clone());
        let span = start.to(rhs.span);
        let pattern = Some(Box::new(pattern));
        AstGoal { after, lhs, op: RelOp::Implies, op_span: start, rhs, span, pattern }
    }

    fn relation(&mut self, after: Option<Ast>) -> PResult<AstGoal> {
        let start = self.peek().span;
        // Prefix patterns: `always f`, `never f`, `reachable f`, `whenever a then b within d`.
        if self.operand_at(1) {
            for (w, make) in [
                ("always", AstPattern::Always as fn(Ast) -> AstPattern),
                ("never", AstPattern::Never),
                ("reachable", AstPattern::Reachable),
            ] {
                if self.word_at(0, w) {
                    self.bump();
                    let f = self.expr()?;
                    return Ok(Parser::pattern_goal(after, start, make(f)));
                }
            }
            if self.word_at(0, "whenever") {
                self.bump();
                let trigger = self.expr()?;
                self.expect_word("then")?;
                let response = self.expr()?;
                self.expect_word("within")?;
                let delay = self.expr()?;
                let pattern = AstPattern::Within { trigger, response, delay };
                return Ok(Parser::pattern_goal(after, start, pattern));
            }
            for w in ["eventually", "infinitely"] {
                if self.word_at(0, w) {
                    return Err(SyntaxError::NotSafety { span: start, word: w.into() });
                }
            }
        }
        let lhs = self.expr()?;
        // Infix patterns: `a then b => c`, `f at most d`, `f at least d once on`,
        // `b not before d after a`.
        if self.word_at(0, "then") {
            self.bump();
            let next = self.expr()?;
            self.expect(Tok::Implies, "`=>`")?;
            let then = self.expr()?;
            let pattern = AstPattern::Then { first: lhs, next, then };
            return Ok(Parser::pattern_goal(after, start, pattern));
        }
        if self.word_at(0, "at") && (self.word_at(1, "most") || self.word_at(1, "least")) {
            self.bump();
            let most = self.bump().tok == Tok::Ident("most".into());
            let delay = self.expr()?;
            let pattern = if most {
                AstPattern::AtMost { signal: lhs, delay }
            } else {
                self.expect_word("once")?;
                self.expect_word("on")?;
                AstPattern::AtLeast { signal: lhs, delay }
            };
            return Ok(Parser::pattern_goal(after, start, pattern));
        }
        if self.word_at(0, "not") && self.word_at(1, "before") {
            self.bump();
            self.bump();
            let delay = self.expr()?;
            self.expect(Tok::Keyword(Keyword::After), "`after`")?;
            let trigger = self.expr()?;
            let pattern = AstPattern::NotBefore { response: lhs, delay, trigger };
            return Ok(Parser::pattern_goal(after, start, pattern));
        }
        if self.word_at(0, "until") {
            return Err(SyntaxError::NotSafety { span: self.peek().span, word: "until".into() });
        }
        let op = match self.peek().tok {
            Tok::Implies => RelOp::Implies,
            Tok::Eq => RelOp::Equals,
            Tok::Ge => RelOp::Ge,
            Tok::Gt => RelOp::Gt,
            Tok::Le => RelOp::Le,
            Tok::Lt => RelOp::Lt,
            _ => return Err(self.unexpected(names(&["`=>`", "`=`", "an operator"]))),
        };
        let op_span = self.bump().span;
        let rhs = self.expr()?;
        let span = lhs.span.to(rhs.span);
        Ok(AstGoal { after, lhs, op, op_span, rhs, span, pattern: None })
    }

    fn nested<T>(&mut self, f: impl FnOnce(&mut Parser) -> PResult<T>) -> PResult<T> {
        if self.depth >= MAX_DEPTH {
            return Err(SyntaxError::TooDeep { span: self.peek().span });
        }
        self.depth += 1;
        let result = f(self);
        self.depth -= 1;
        result
    }

    /// An expression without a relation: `+` of `.` of `/` chains.
    pub fn expr(&mut self) -> PResult<Ast> {
        self.nested(|p| p.operands(&Tok::Or, AstKind::Or, Parser::product))
    }

    fn product(&mut self) -> PResult<Ast> {
        self.operands(&Tok::And, AstKind::And, Parser::chain)
    }

    fn chain(&mut self) -> PResult<Ast> {
        self.operands(&Tok::Slash, AstKind::Chain, Parser::unary)
    }

    fn operands(
        &mut self,
        sep: &Tok,
        make: fn(Vec<Ast>) -> AstKind,
        next: fn(&mut Parser) -> PResult<Ast>,
    ) -> PResult<Ast> {
        let first = next(self)?;
        if !self.at(sep) {
            return Ok(first);
        }
        let mut list = vec![first];
        while self.eat(sep).is_some() {
            list.push(next(self)?);
        }
        let span = list[0].span.to(list[list.len() - 1].span);
        Ok(Ast { kind: make(list), span })
    }

    fn unary(&mut self) -> PResult<Ast> {
        if let Some(start) = self.eat(&Tok::Not) {
            let inner = self.nested(Parser::unary)?;
            let span = start.to(inner.span);
            return Ok(Ast { kind: AstKind::Not(Box::new(inner)), span });
        }
        // `pre` is the previous-scan operator when an operand follows; otherwise a name.
        if matches!(&self.peek().tok, Tok::Ident(n) if n == "pre")
            && matches!(
                self.peek_at(1),
                Tok::Ident(_) | Tok::Quoted(_) | Tok::LParen | Tok::Not | Tok::Zero | Tok::One
            )
        {
            let start = self.bump().span;
            let inner = self.nested(Parser::unary)?;
            let span = start.to(inner.span);
            return Ok(Ast { kind: AstKind::Pre(Box::new(inner)), span });
        }
        self.atom()
    }

    fn atom(&mut self) -> PResult<Ast> {
        let token = self.peek().clone();
        let kind = match token.tok {
            Tok::Ident(name) => {
                if let Some(func) = Func::from_name(&name)
                    && self.peek_at(1) == &Tok::LParen
                {
                    return self.call(func);
                }
                AstKind::Name(name)
            }
            Tok::Quoted(name) => AstKind::Name(name),
            Tok::Duration(d) => AstKind::Duration(d),
            Tok::Zero => AstKind::Zero,
            Tok::One => AstKind::One,
            Tok::Error => AstKind::Error,
            Tok::LParen => {
                self.bump();
                let inner = self.expr()?;
                let end = self.expect(Tok::RParen, "`)`")?;
                return Ok(Ast { kind: AstKind::Paren(Box::new(inner)), span: token.span.to(end) });
            }
            Tok::LBracket => return self.comparison(),
            _ => return Err(self.unexpected(names(ATOM))),
        };
        self.bump();
        Ok(Ast { kind, span: token.span })
    }

    /// `[a op b]`: a comparison of integers (each side a name or a literal).
    fn comparison(&mut self) -> PResult<Ast> {
        let start = self.bump().span;
        let a = self.int_operand()?;
        let op = match self.peek().tok {
            Tok::Eq => CmpOp::Eq,
            Tok::Ne => CmpOp::Ne,
            Tok::Lt => CmpOp::Lt,
            Tok::Le => CmpOp::Le,
            Tok::Gt => CmpOp::Gt,
            Tok::Ge => CmpOp::Ge,
            _ => {
                let ops = ["`=`", "`<>`", "`<`", "`<=`", "`>`", "`>=`"];
                return Err(self.unexpected(names(&ops)));
            }
        };
        self.bump();
        let b = self.int_operand()?;
        let end = self.expect(Tok::RBracket, "`]` (a comparison is `[a op b]`)")?;
        Ok(Ast { kind: AstKind::Compare(op, a, b), span: start.to(end) })
    }

    fn int_operand(&mut self) -> PResult<IntOperand> {
        let operand = match &self.peek().tok {
            // An instance's pin, `T1.ET`: the scope resolves it to the pin's name.
            Tok::Ident(n) | Tok::Quoted(n) if self.peek_at(1) == &Tok::Dot => {
                let inst = n.clone();
                self.bump();
                self.bump();
                let pin = match &self.peek().tok {
                    Tok::Ident(p) | Tok::Quoted(p) => p.clone(),
                    _ => return Err(self.unexpected(names(&["a pin name (`T1.ET`)"]))),
                };
                IntOperand::Var(format!("{inst}.{pin}"))
            }
            Tok::Ident(n) | Tok::Quoted(n) => IntOperand::Var(n.clone()),
            Tok::Int(v) => IntOperand::Int(*v),
            Tok::Duration(d) => {
                let us = d.seconds() * num_bigint::BigInt::from(1_000_000_000);
                match us.is_integer().then(|| i64::try_from(us.to_integer()).ok()).flatten() {
                    Some(us) => IntOperand::Time(us),
                    None => {
                        let reason = "a duration compared with a TIME is a whole number of \
                                      nanoseconds, at most 2^62"
                            .into();
                        return Err(SyntaxError::BadDuration { span: self.peek().span, reason });
                    }
                }
            }
            _ => {
                let expected = ["an integer variable", "an integer", "a duration"];
                return Err(self.unexpected(names(&expected)));
            }
        };
        self.bump();
        Ok(operand)
    }

    fn call(&mut self, func: Func) -> PResult<Ast> {
        let start = self.bump().span;
        self.expect(Tok::LParen, "`(`")?;
        let a = self.expr()?;
        self.expect(Tok::Comma, "`,` (this takes two arguments)")?;
        let b = self.expr()?;
        let end = self.expect(Tok::RParen, "`)` (this takes two arguments)")?;
        Ok(Ast { kind: AstKind::Call(func, Box::new(a), Box::new(b)), span: start.to(end) })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::lexer::lex;

    fn parse(text: &str) -> Ast {
        let (tokens, errors) = lex(text, 0);
        assert!(errors.is_empty());
        let mut p = Parser::new(tokens);
        let e = p.expr().unwrap();
        p.end().unwrap();
        e
    }

    fn shape(a: &Ast) -> String {
        let list = |op: &str, v: &[Ast]| {
            let parts: Vec<_> = v.iter().map(shape).collect();
            format!("({op} {})", parts.join(" "))
        };
        match &a.kind {
            AstKind::Name(n) => n.clone(),
            AstKind::Duration(d) => d.to_string(),
            AstKind::Zero => "0*".into(),
            AstKind::One => "1*".into(),
            AstKind::Not(x) => format!("(! {})", shape(x)),
            AstKind::Pre(x) => format!("(pre {})", shape(x)),
            AstKind::Or(v) => list("+", v),
            AstKind::And(v) => list(".", v),
            AstKind::Chain(v) => list("/", v),
            AstKind::Paren(x) => shape(x),
            AstKind::Call(f, x, y) => format!("({f:?} {} {})", shape(x), shape(y)),
            AstKind::Compare(op, a, b) => format!("[{a} {} {b}]", op.symbol()),
            AstKind::Error => "?".into(),
        }
    }

    #[test]
    fn precedence() {
        assert_eq!(shape(&parse("a + b . c")), "(+ a (. b c))");
        assert_eq!(shape(&parse("!f/5s")), "(/ (! f) 5s)");
        assert_eq!(shape(&parse("!!f")), "(! (! f))");
        assert_eq!(shape(&parse("a . 2s/b + c")), "(+ (. a (/ 2s b)) c)");
        assert_eq!(shape(&parse("SR(a, b + c)")), "(Sr a (+ b c))");
        assert_eq!(shape(&parse("max(1s, 2s)/f")), "(/ (Max 1s 2s) f)");
        assert_eq!(shape(&parse("max . min")), "(. max min)");
    }

    #[test]
    fn relations_only_at_the_top() {
        let (tokens, _) = lex("(a => b)", 0);
        let err = Parser::new(tokens).expr().unwrap_err();
        assert!(matches!(err, SyntaxError::RelationNotAtTop { .. }));
    }

    #[test]
    fn deep_nesting_is_an_error_not_a_crash() {
        let text = "(".repeat(100_000);
        let (tokens, _) = lex(&text, 0);
        assert!(matches!(Parser::new(tokens).expr(), Err(SyntaxError::TooDeep { .. })));
        let text = "!".repeat(100_000);
        let (tokens, _) = lex(&text, 0);
        assert!(Parser::new(tokens).expr().is_err());
    }
}
