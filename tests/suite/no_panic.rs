//! Nothing panics on any input: arbitrary strings, random soups of tokens, and
//! a list of inputs that once caused trouble. Whatever parses also prints and
//! parses back.

use ii_prove::diag::{Diagnostic, RenderStyle, Sources, render};
use ii_prove::syntax::{
    NoProgram, Notation, document_to_string, parse_document, parse_expression, parse_goal,
};
use proptest::prelude::*;

/// Runs every entry point on `text`; panics only if the library does.
fn exercise(text: &str) {
    let mut sources = Sources::new();
    let file = sources.add("fuzz.ii", text.to_string());
    match parse_document(&sources, file, &NoProgram) {
        Ok(doc) => {
            for notation in [Notation::Paper, Notation::Ascii] {
                let printed = document_to_string(&doc, notation);
                let again = sources.add("printed.ii", printed.clone());
                assert!(
                    parse_document(&sources, again, &NoProgram).is_ok(),
                    "{text:?} printed as {printed:?} does not parse back"
                );
            }
        }
        Err(errors) => {
            assert!(!errors.is_empty());
            for e in errors {
                let _ = render(&Diagnostic::from(e), &sources, RenderStyle::default());
            }
        }
    }
    let inputs = vec!["f".to_string(), "g".to_string(), "a".to_string()];
    let _ = parse_expression(&sources, file, &NoProgram, &inputs);
    let _ = parse_goal(&sources, file, &NoProgram, &inputs);
}

/// Inputs that broke something once, or look like they might.
const REGRESSIONS: &[&str] = &[
    "",
    " ",
    "\n",
    "`",
    "``",
    "\"",
    "T#",
    "T#-",
    "t#1",
    "TIME#_",
    "T#1m30",
    "T#1.",
    "1.",
    "1.s",
    ".5s",
    "0*",
    "2*",
    "*",
    "=>",
    "⇒⇒",
    "¬",
    "property",
    "property P",
    "property P:",
    "property P: after",
    "property P: after 5s",
    "property P: after 5s:",
    "law L: f = f if",
    "law L: f = f if ,",
    "delay",
    "input ,",
    "program",
    "let = f",
    "let x = x",
    "SR(",
    "max(",
    "max(1s, 2s)",
    "property P: max(1s, 2s) => f",
    "property P: (5s + 2s)/f => f",
    "property P: (5s + f)/f => f",
    "input f\nproperty P: 5s/f/2s/3s/4s => f",
    "input f\nproperty P: f/5s/g => f",
    "input f\nproperty P: /f => f",
    "input f\nproperty P: f/ => f",
    "input f\nproperty P: 0.0000000000000000000000000000000000000000001s/f => f",
    "input f\nproperty P: 99999999999999999999999999999999999h/f => f",
    "\u{0}\u{1}\u{7f}",
    "é",
    "💥/5s",
    "input f\nproperty P: f\r\n=> f",
];

#[test]
fn known_troublemakers_do_not_panic() {
    for text in REGRESSIONS {
        exercise(text);
    }
}

#[test]
fn deep_but_allowed_nesting_does_not_overflow() {
    for n in [150, 199, 200, 201, 5000] {
        let parens = format!("input f\nproperty P: {}f{} => f", "(".repeat(n), ")".repeat(n));
        exercise(&parens);
        let nots = format!("input f\nproperty P: {}f => f", "!".repeat(n));
        exercise(&nots);
        let delays = format!("input f\nproperty P: {}f => f", "1s/".repeat(n));
        exercise(&delays);
        let sum = format!("input f\nproperty P: f{} => f", " + f".repeat(n));
        exercise(&sum);
    }
    let long_sum = format!("input f\nproperty P: f{} => f", " . f".repeat(20_000));
    exercise(&long_sum);
}

const TOKENS: &[&str] = &[
    "let", "input", "delay", "assume", "property", "law", "program", "after", "if", "f", "g", "a",
    "d", "SR", "RS", "max", "min", "`X@1`", "5s", "0.5s", "250ms", "T#1m30s", "0", "1", "0*", "1*",
    "=>", "⇒", "=", "+", "∨", "|", ".", "·", "&", "!", "¬", "~", "/", "(", ")", ",", ":", ">=",
    ">", "<=", "<", "\"p.ld\"", "// c\n", "# c\n", "\n", "5", "0s", "T#", "`",
];

fn soup() -> impl Strategy<Value = String> {
    prop::collection::vec(prop::sample::select(TOKENS), 0..40).prop_map(|v| v.join(" "))
}

/// Mostly well-formed statements with a few random tokens mixed in.
fn near_miss() -> impl Strategy<Value = String> {
    (prop::collection::vec(prop::sample::select(TOKENS), 0..12), 0usize..5).prop_map(|(v, at)| {
        let mut parts = vec!["input f, g, a\ndelay d\nproperty P:", "f", "=>", "5s/g"];
        let at = at.min(parts.len());
        for t in v.iter().rev() {
            parts.insert(at, t);
        }
        parts.join(" ")
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn arbitrary_strings_do_not_panic(text in any::<String>()) {
        exercise(&text);
    }

    #[test]
    fn ascii_noise_does_not_panic(text in "[ -~\n]{0,60}") {
        exercise(&text);
    }

    #[test]
    fn token_soups_do_not_panic(text in soup()) {
        exercise(&text);
    }

    #[test]
    fn near_misses_do_not_panic(text in near_miss()) {
        exercise(&text);
    }
}
