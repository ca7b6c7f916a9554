//! The resolver: names, `/` chains and durations of the syntax tree become terms.
//!
//! In `assume`, `property` and `let`, a name is an abbreviation (expanded), an
//! `input`, or a signal of the program ([`Scope::lookup`]). In a `law`, every
//! signal name is a metavariable and delay metavariables must be declared by
//! an earlier `delay` statement. Duration arithmetic whose operands are all
//! literals is folded to one literal.
//!
//! This file holds the resolver's state and its entry points (a document, an
//! expression, a goal); terms are resolved in `terms.rs`, statements in
//! `statements.rs`, over the term builder of `nodes.rs`.

use std::collections::HashMap;

use super::ast::AstStatement;
use super::lexer::{Tok, lex};
use super::parser::Parser;
use super::{Document, Goal, Scope, SyntaxError};
use crate::diag::{FileId, Span};
use crate::term::Expr;
use nodes::Out;

mod nodes;
mod statements;
mod terms;

/// Where a term is being resolved: the rules for names differ.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mode {
    /// `assume`, `property`, `let`, REPL input: concrete names and durations.
    Concrete,
    /// `law`: names are metavariables.
    Law,
}

struct Resolver<'a> {
    file: FileId,
    scope: &'a dyn Scope,
    lets: HashMap<String, Expr>,
    inputs: Vec<(String, Span)>,
    delays: Vec<(String, Span)>,
    /// Every name declared by `let`, `input` or `delay`, with where.
    declared: HashMap<String, Span>,
    errors: Vec<SyntaxError>,
}

impl<'a> Resolver<'a> {
    fn new(file: FileId, scope: &'a dyn Scope) -> Resolver<'a> {
        Resolver {
            file,
            scope,
            lets: HashMap::new(),
            inputs: Vec::new(),
            delays: Vec::new(),
            declared: HashMap::new(),
            errors: Vec::new(),
        }
    }

    fn declare(&mut self, name: &str, span: Span) -> bool {
        if let Some(first) = self.declared.get(name) {
            self.errors.push(SyntaxError::DuplicateName { span, name: name.into(), first: *first });
            false
        } else {
            self.declared.insert(name.into(), span);
            true
        }
    }

    fn with_inputs(mut self, inputs: &[String]) -> Self {
        let span = Span::new(self.file, 0..0);
        self.inputs = inputs.iter().map(|n| (n.clone(), span)).collect();
        self
    }
}

fn finish<T>(value: Option<T>, mut errors: Vec<SyntaxError>) -> Result<T, Vec<SyntaxError>> {
    errors.sort_by_key(|e| {
        let s = e.primary_span();
        (s.start, s.end)
    });
    errors.dedup();
    match value {
        Some(v) if errors.is_empty() => Ok(v),
        _ => Err(errors),
    }
}

/// Lexes, parses and resolves a whole file.
pub(super) fn document(
    text: &str,
    file: FileId,
    scope: &dyn Scope,
) -> Result<Document, Vec<SyntaxError>> {
    let (tokens, mut errors) = lex(text, file);
    let (statements, parse_errors) = Parser::new(tokens).document();
    errors.extend(parse_errors);
    let mut resolver = Resolver::new(file, scope);
    let doc = resolver.statements(&statements);
    errors.extend(resolver.errors);
    finish(Some(doc), errors)
}

/// Resolves one parsed item (an expression or a goal) with `resolve`, collecting the
/// parse error or the resolver's errors.
fn resolve_one<A, T>(
    ast: Result<A, SyntaxError>,
    mut errors: Vec<SyntaxError>,
    mut resolver: Resolver<'_>,
    resolve: impl FnOnce(&mut Resolver<'_>, &A) -> Option<T>,
) -> Result<T, Vec<SyntaxError>> {
    let ast = match ast {
        Ok(a) => a,
        Err(e) => {
            errors.push(e);
            return finish(None, errors);
        }
    };
    let value = resolve(&mut resolver, &ast);
    errors.extend(resolver.errors);
    finish(value, errors)
}

/// Lexes, parses and resolves one expression.
pub(super) fn expression(
    text: &str,
    file: FileId,
    scope: &dyn Scope,
    inputs: &[String],
) -> Result<Expr, Vec<SyntaxError>> {
    let (tokens, errors) = lex(text, file);
    let mut parser = Parser::new(tokens);
    let ast = parser.expr().and_then(|a| parser.end().map(|()| a));
    resolve_one(ast, errors, Resolver::new(file, scope).with_inputs(inputs), |r, a| {
        r.signal_expr(a, Mode::Concrete, &mut Out::default())
    })
}

/// Lexes, parses and resolves one goal, or one `property`/`assume` statement.
pub(super) fn goal(
    text: &str,
    file: FileId,
    scope: &dyn Scope,
    inputs: &[String],
) -> Result<Goal, Vec<SyntaxError>> {
    use super::lexer::Keyword;
    let (tokens, errors) = lex(text, file);
    let statement = matches!(
        tokens.first().map(|t| &t.tok),
        Some(Tok::Keyword(Keyword::Property | Keyword::Assume))
    );
    let mut parser = Parser::new(tokens);
    let ast = if statement {
        parser.statement().and_then(|s| match s {
            AstStatement::Named { goal, .. } => Ok(*goal),
            // `statement` returns a named statement for these keywords.
            _ => Err(SyntaxError::UnexpectedToken {
                span: Span::new(file, 0..0),
                found: "a statement".into(),
                expected: vec!["a goal".into()],
            }),
        })
    } else {
        parser.goal()
    };
    let ast = ast.and_then(|a| parser.end().map(|()| a));
    resolve_one(ast, errors, Resolver::new(file, scope).with_inputs(inputs), |r, a| {
        r.goal(a, Mode::Concrete, &mut Out::default())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::syntax::NoProgram;
    use crate::syntax::{DelayComparison, Lookup, Relation, SideCondition};
    use crate::term::Symbol;
    use crate::term::{same, sexp};

    fn expr(text: &str) -> Expr {
        let inputs: Vec<String> = ["f", "g", "h", "s", "r"].map(String::from).to_vec();
        expression(text, 0, &NoProgram, &inputs).unwrap_or_else(|e| panic!("{text}: {e:?}"))
    }

    fn err(text: &str) -> SyntaxError {
        let inputs: Vec<String> = ["f", "g"].map(String::from).to_vec();
        expression(text, 0, &NoProgram, &inputs).unwrap_err().remove(0)
    }

    #[test]
    fn precedence_and_associativity() {
        assert!(same(&expr("f + g . h"), &sexp("(+ f (& g h))")));
        assert!(same(&expr("f . g . h"), &sexp("(& (& f g) h)")));
        assert!(same(&expr("f . (g . h)"), &sexp("(& f (& g h))")));
        assert!(same(&expr("!f/5s"), &sexp("(tof (! f) 5s)")));
        assert!(same(&expr("!(5s/f)"), &sexp("(! (ton 5s f))")));
        assert!(same(&expr("¬¬f ∨ 0"), &sexp("(+ (! (! f)) 0*)")));
        assert!(same(&expr("SR(s, r) · RS(s, 1*)"), &sexp("(& (sr s r) (rs s 1*))")));
    }

    #[test]
    fn slash_chains() {
        assert!(same(&expr("2s/5s/f"), &sexp("(ton 2s (ton 5s f))")));
        assert!(same(&expr("f/1s/2s"), &sexp("(tof (tof f 1s) 2s)")));
        assert!(same(&expr("(5s/f)/2s"), &sexp("(tof (ton 5s f) 2s)")));
        assert!(same(&expr("max(1s, 2s)/f"), &sexp("(ton 2s f)")));
        assert!(same(&expr("(1s + 250ms)/f"), &sexp("(ton 1.25s f)")));
        assert!(matches!(err("5s/f/2s"), SyntaxError::BothDelayKinds { .. }));
        assert!(matches!(err("f/g"), SyntaxError::NoDuration { .. }));
        assert!(matches!(err("5s/2s"), SyntaxError::NoSignal { .. }));
        assert!(matches!(err("f . 5s"), SyntaxError::DurationAsSignal { .. }));
    }

    #[test]
    fn after_goals() {
        let g = goal("after 5s: f => g", 0, &NoProgram, &["f".into(), "g".into()]).unwrap();
        assert_eq!(g.after, Some("5s".parse().unwrap()));
        assert!(same(&g.lhs_with_after(), &sexp("(& (ton 5s 1*) f)")));
        let g = goal("property P: f = g", 0, &NoProgram, &["f".into(), "g".into()]).unwrap();
        assert_eq!(g.relation, Relation::Equals);
    }

    #[test]
    fn names_resolve_and_unknown_names_are_reported() {
        match err("f . gg") {
            SyntaxError::UnknownName { suggestion, .. } => {
                assert_eq!(suggestion.as_deref(), Some("g"));
            }
            e => panic!("{e:?}"),
        }
        let text = "input pump, up\nlet L = pump + up\nproperty P: L => pmup";
        let errors = document(text, 0, &NoProgram).unwrap_err();
        match &errors[0] {
            SyntaxError::UnknownName { suggestion, .. } => {
                assert_eq!(suggestion.as_deref(), Some("pump"))
            }
            e => panic!("{e:?}"),
        }
    }

    #[test]
    fn laws_have_metavariables() {
        let text = "delay d, e\nlaw L: d/(e/f) = (d + e)/f if d >= e, f . g = 0*";
        let doc = document(text, 0, &NoProgram).unwrap();
        let law = &doc.laws[0].value;
        assert_eq!(law.signal_vars, vec![Symbol::from("f"), Symbol::from("g")]);
        assert_eq!(law.delay_vars, vec![Symbol::from("d"), Symbol::from("e")]);
        assert!(same(&law.goal.rhs, &sexp("(ton (dadd d e) f)")));
        assert_eq!(law.conditions.len(), 2);
        let errors = document("law L: x/f = f", 0, &NoProgram).unwrap_err();
        assert!(matches!(errors[0], SyntaxError::UndeclaredDelay { .. }));
        let errors = document("delay d\nproperty P: d/f => f", 0, &NoProgram).unwrap_err();
        assert!(matches!(errors[0], SyntaxError::DelayVariableOutsideLaw { .. }));
    }

    /// A program whose lookup ignores case, with `T1` ambiguous.
    struct Program;

    impl Scope for Program {
        fn lookup(&self, name: &str) -> Lookup {
            if name == "T1" {
                return Lookup::Ambiguous(vec!["T1.Q".into(), "T1.ET".into()]);
            }
            self.names()
                .into_iter()
                .find(|n| n.eq_ignore_ascii_case(name))
                .map_or(Lookup::Unknown, Lookup::Signal)
        }
        fn names(&self) -> Vec<String> {
            vec!["L1_pump".into(), "T1.Q".into(), "T1.ET".into()]
        }
    }

    #[test]
    fn program_names_resolve_to_canonical_names() {
        let text = "input free\nproperty P: l1_PUMP . `T1.Q` => free";
        let doc = document(text, 0, &Program).unwrap();
        assert!(same(&doc.properties[0].value.lhs, &sexp("(& L1_pump T1.Q)")));
        let errors = document("property P: T1 => L1_pmp", 0, &Program).unwrap_err();
        assert!(matches!(errors[0], SyntaxError::AmbiguousName { .. }));
        match &errors[1] {
            SyntaxError::UnknownName { suggestion, known, .. } => {
                assert_eq!(suggestion.as_deref(), Some("L1_pump"));
                assert_eq!(known.len(), 3);
            }
            e => panic!("{e:?}"),
        }
    }

    #[test]
    fn delay_arithmetic_folds_only_literals() {
        let doc =
            document("delay d\nlaw L: max(1s, 2s)/f = (d + 1s + 2s)/f", 0, &NoProgram).unwrap();
        let goal = &doc.laws[0].value.goal;
        assert!(same(&goal.lhs, &sexp("(ton 2s f)")));
        assert!(same(&goal.rhs, &sexp("(ton (dadd (dadd d 1s) 2s) f)")));
        let doc =
            document("delay d\nlaw L: d/f = d/f if d + 1s >= max(d, 2s)", 0, &NoProgram).unwrap();
        assert!(matches!(
            &doc.laws[0].value.conditions[0],
            SideCondition::Delay { op: DelayComparison::Ge, .. }
        ));
    }

    #[test]
    fn several_errors_at_once() {
        let text = "property A: f/g => 0\nproperty B: ( => 1\nproperty A: 1 => 1";
        let errors = document(text, 0, &NoProgram).unwrap_err();
        assert!(errors.len() >= 3, "{errors:?}");
    }
}
