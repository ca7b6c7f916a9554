//! The kernel accepts correct certificates and fails closed on every kind of bad one.

use ii_prove::kernel::{
    Axiom, Certificate, Cmp, Kernel, KernelError, Lemmas, Proof, Rel, Rule, Source, Step, Theorem,
    Use,
};
use ii_prove::term::{Expr, Symbol, sexp};

fn law(name: &str, lhs: &str, rel: Rel, rhs: &str, vars: &[&str], delays: &[&str]) -> Axiom {
    Axiom {
        signal_vars: vars.iter().map(|v| Symbol::from(*v)).collect(),
        delay_vars: delays.iter().map(|v| Symbol::from(*v)).collect(),
        ..Axiom::ground(name, sexp(lhs), rel, sexp(rhs))
    }
}

fn kernel() -> Kernel {
    let mut ton_longer =
        law("ton_longer", "(ton d1 f)", Rel::Implies, "(ton d2 f)", &["f"], &["d1", "d2"]);
    ton_longer.delay_conditions.push((sexp("d1"), Cmp::Ge, sexp("d2")));
    let mut sr_is_rs = law("sr_is_rs", "(sr s r)", Rel::Eq, "(rs s r)", &["s", "r"], &[]);
    sr_is_rs.signal_conditions.push((sexp("(& s r)"), Rel::Eq, sexp("0*")));
    let laws = vec![
        law("and_comm", "(& f g)", Rel::Eq, "(& g f)", &["f", "g"], &[]),
        law("and_not", "(& f (! f))", Rel::Eq, "0*", &["f"], &[]),
        law("and_one", "(& f 1*)", Rel::Eq, "f", &["f"], &[]),
        law("and_zero", "(& f 0*)", Rel::Eq, "0*", &["f"], &[]),
        law("not_one", "(! 1*)", Rel::Eq, "0*", &[], &[]),
        law("not_zero", "(! 0*)", Rel::Eq, "1*", &[], &[]),
        law("ton_weaken", "(ton d f)", Rel::Implies, "f", &["f"], &["d"]),
        law(
            "ton_ton",
            "(ton d1 (ton d2 f))",
            Rel::Eq,
            "(ton (dadd d1 d2) f)",
            &["f"],
            &["d1", "d2"],
        ),
        ton_longer,
        sr_is_rs,
    ];
    let hyps = vec![
        Axiom::ground("L05", sexp("L1_up"), Rel::Eq, sexp("L1_Prod")),
        Axiom::ground("L06", sexp("L1_pump"), Rel::Eq, sexp("(ton 5s L1_Prod)")),
        Axiom::ground("H0", sexp("(& a b)"), Rel::Eq, sexp("0*")),
    ];
    Kernel::new(laws, hyps).expect("well-formed axioms")
}

fn step(path: &[usize], rule: Rule, after: &str) -> Step {
    Step { path: path.to_vec(), rule, after: sexp(after), subst: vec![], premises: vec![] }
}

fn cite(source: Source, name: &str, how: Use) -> Rule {
    Rule::Cite(source, name.to_string(), how)
}

fn chain(start: &str, steps: Vec<Step>) -> Certificate {
    Certificate { lemmas: vec![], main: Some(Proof::Chain { start: sexp(start), steps }) }
}

/// P1 of the water plant, as in the paper: L1_pump = 5s/L1_Prod = 5s/L1_up.
fn p1_steps() -> Vec<Step> {
    vec![
        step(&[], cite(Source::Hypothesis, "L06", Use::Forward), "(ton 5s L1_Prod)"),
        step(&[1], cite(Source::Hypothesis, "L05", Use::Backward), "(ton 5s L1_up)"),
    ]
}

#[test]
fn accepts_the_paper_proof_of_p1() {
    let thm = kernel().check(&chain("L1_pump", p1_steps())).expect("checks");
    assert!(thm.proves(&sexp("L1_pump"), Rel::Implies, &sexp("(ton 5s L1_up)")));
    assert!(thm.proves(&sexp("L1_pump"), Rel::Eq, &sexp("(ton 5s L1_up)")));
    assert_eq!(thm.axioms_used().1.len(), 2);
}

#[test]
fn an_implication_step_makes_an_implication() {
    let cert = chain(
        "(ton 5s L1_Prod)",
        vec![step(&[], cite(Source::Law, "ton_weaken", Use::Forward), "L1_Prod")],
    );
    let thm = kernel().check(&cert).expect("checks");
    assert_eq!(thm.rel(), Rel::Implies);
    assert!(!thm.proves(&sexp("(ton 5s L1_Prod)"), Rel::Eq, &sexp("L1_Prod")));
}

#[test]
fn delay_arithmetic_is_recomputed() {
    let cert = chain(
        "(ton 2s (ton 3s f))",
        vec![
            step(&[], cite(Source::Law, "ton_ton", Use::Forward), "(ton (dadd 2s 3s) f)"),
            step(&[0], Rule::DelayArith, "(ton 5s f)"),
        ],
    );
    assert!(kernel().check(&cert).is_ok());
    let wrong = chain(
        "(ton 2s (ton 3s f))",
        vec![
            step(&[], cite(Source::Law, "ton_ton", Use::Forward), "(ton (dadd 2s 3s) f)"),
            step(&[0], Rule::DelayArith, "(ton 6s f)"),
        ],
    );
    assert!(matches!(kernel().check(&wrong), Err(KernelError::NoMatch { .. })));
}

#[test]
fn rejects_an_unknown_rule() {
    let cert = chain("(& a b)", vec![step(&[], cite(Source::Law, "and_magic", Use::Forward), "a")]);
    assert!(matches!(kernel().check(&cert), Err(KernelError::UnknownRule(_))));
    let hyp_as_law =
        chain("L1_up", vec![step(&[], cite(Source::Law, "L05", Use::Forward), "L1_Prod")]);
    assert!(matches!(kernel().check(&hyp_as_law), Err(KernelError::UnknownRule(_))));
}

#[test]
fn rejects_a_step_whose_instance_does_not_match() {
    let cert = chain("(& a b)", vec![step(&[], cite(Source::Law, "and_not", Use::Forward), "0*")]);
    assert!(matches!(kernel().check(&cert), Err(KernelError::NoMatch { .. })));
    let wrong_result =
        chain("(& a b)", vec![step(&[], cite(Source::Law, "and_comm", Use::Forward), "(& a a)")]);
    assert!(kernel().check(&wrong_result).is_err());
}

#[test]
fn rejects_a_wrong_substitution() {
    let mut s = step(&[], cite(Source::Law, "and_comm", Use::Forward), "(& b a)");
    s.subst = vec![(Symbol::from("f"), sexp("b"))];
    let cert = chain("(& a b)", vec![s]);
    assert!(matches!(kernel().check(&cert), Err(KernelError::WrongSubstitution(_))));
    let mut s = step(&[], cite(Source::Law, "and_comm", Use::Forward), "(& b a)");
    s.subst = vec![(Symbol::from("zz"), sexp("b"))];
    assert!(matches!(
        kernel().check(&chain("(& a b)", vec![s])),
        Err(KernelError::WrongSubstitution(_))
    ));
}

#[test]
fn rejects_a_change_outside_the_position() {
    let cert = chain(
        "(& L1_up c)",
        vec![step(&[0], cite(Source::Hypothesis, "L05", Use::Forward), "(& L1_Prod d)")],
    );
    assert!(matches!(kernel().check(&cert), Err(KernelError::WrongResult(_))));
}

#[test]
fn a_truncated_chain_does_not_prove_the_goal() {
    let mut steps = p1_steps();
    steps.pop();
    let cert = chain("L1_pump", steps);
    let k = kernel();
    let thm = k.check(&cert).expect("the prefix itself is fine");
    assert!(!thm.proves(&sexp("L1_pump"), Rel::Implies, &sexp("(ton 5s L1_up)")));
    assert!(matches!(
        k.check_goal(&cert, &sexp("L1_pump"), Rel::Implies, &sexp("(ton 5s L1_up)")),
        Err(KernelError::NotTheGoal(_))
    ));
    assert!(matches!(k.check(&Certificate::default()), Err(KernelError::NotTheGoal(_))));
}

#[test]
fn rejects_a_bad_path() {
    let cert = chain(
        "(& a b)",
        vec![step(&[0, 3], cite(Source::Law, "and_comm", Use::Forward), "(& b a)")],
    );
    assert!(matches!(kernel().check(&cert), Err(KernelError::BadPath(_))));
}

#[test]
fn rejects_a_false_delay_side_condition() {
    let ok = chain(
        "(ton 5s f)",
        vec![step(&[], cite(Source::Law, "ton_longer", Use::Forward), "(ton 2s f)")],
    );
    assert!(kernel().check(&ok).is_ok());
    let bad = chain(
        "(ton 2s f)",
        vec![step(&[], cite(Source::Law, "ton_longer", Use::Forward), "(ton 5s f)")],
    );
    assert!(matches!(kernel().check(&bad), Err(KernelError::SideCondition(_))));
}

#[test]
fn a_signal_side_condition_needs_its_premise() {
    let no_premise =
        chain("(sr a b)", vec![step(&[], cite(Source::Law, "sr_is_rs", Use::Forward), "(rs a b)")]);
    assert!(matches!(kernel().check(&no_premise), Err(KernelError::MissingPremise(_))));
    let premise = Proof::Chain {
        start: sexp("(& a b)"),
        steps: vec![step(&[], cite(Source::Hypothesis, "H0", Use::Forward), "0*")],
    };
    let mut s = step(&[], cite(Source::Law, "sr_is_rs", Use::Forward), "(rs a b)");
    s.premises = vec![premise.clone()];
    assert!(kernel().check(&chain("(sr a b)", vec![s])).is_ok());
    // The premise of another instance does not do.
    let mut s = step(&[], cite(Source::Law, "sr_is_rs", Use::Forward), "(rs b a)");
    s.premises = vec![premise];
    assert!(kernel().check(&chain("(sr b a)", vec![s])).is_err());
}

#[test]
fn an_implication_is_not_used_under_a_negation() {
    // ¬(5s/f) ⇒ ¬f is false; the kernel must not let `d/f ⇒ f` rewrite under ¬.
    let cert = chain(
        "(! (ton 5s f))",
        vec![step(&[0], cite(Source::Law, "ton_weaken", Use::Forward), "(! f)")],
    );
    assert!(matches!(kernel().check(&cert), Err(KernelError::BadPosition(_))));
    // Used backwards under ¬ it is sound: ¬f ⇒ ¬(5s/f).
    let cert = chain(
        "(! f)",
        vec![step(&[0], cite(Source::Law, "ton_weaken", Use::Backward), "(! (ton 5s f))")],
    );
    let thm = kernel().check(&cert).expect("antitone position, backward use");
    assert_eq!(thm.rel(), Rel::Implies);
    // As an equation (meet form) it may go anywhere.
    let cert = chain(
        "(! (ton 5s f))",
        vec![step(&[0], cite(Source::Law, "ton_weaken", Use::Meet), "(! (& (ton 5s f) f))")],
    );
    assert_eq!(kernel().check(&cert).expect("meet is an equation").rel(), Rel::Eq);
}

#[test]
fn an_implication_is_not_used_in_a_reset_argument() {
    let cert = chain(
        "(sr a (ton 5s b))",
        vec![step(&[1], cite(Source::Law, "ton_weaken", Use::Forward), "(sr a b)")],
    );
    assert!(matches!(kernel().check(&cert), Err(KernelError::BadPosition(_))));
}

fn case_chain(start: &str, atom: &str, value: bool, rewrites: Vec<Step>) -> Proof {
    let mut steps = Vec::new();
    let _ = (atom, value);
    steps.extend(rewrites);
    Proof::Chain { start: sexp(start), steps }
}

#[test]
fn a_case_split_proves_excluded_middle_like_goals() {
    // a · ¬a = 0* by cases on a.
    let case = |v: bool, konst: &str, not_konst: &str, simp: &str| {
        case_chain(
            "(& a (! a))",
            "a",
            v,
            vec![
                step(&[0], Rule::Case(sexp("a"), v), &format!("(& {konst} (! a))")),
                step(&[1, 0], Rule::Case(sexp("a"), v), &format!("(& {konst} (! {konst}))")),
                step(
                    &[1],
                    cite(Source::Law, simp, Use::Forward),
                    &format!("(& {konst} {not_konst})"),
                ),
                step(
                    &[],
                    cite(Source::Law, if v { "and_zero" } else { "and_not" }, Use::Forward),
                    "0*",
                ),
            ],
        )
    };
    let one = case(true, "1*", "0*", "not_one");
    // In the zero case: 0*·¬0* → 0*·1*; use and_one... then 0*. Build it explicitly.
    let zero = Proof::Chain {
        start: sexp("(& a (! a))"),
        steps: vec![
            step(&[0], Rule::Case(sexp("a"), false), "(& 0* (! a))"),
            step(&[1, 0], Rule::Case(sexp("a"), false), "(& 0* (! 0*))"),
            step(&[1], cite(Source::Law, "not_zero", Use::Forward), "(& 0* 1*)"),
            step(&[], cite(Source::Law, "and_one", Use::Forward), "0*"),
        ],
    };
    let split =
        Proof::CaseSplit { atom: sexp("a"), one: Box::new(one), zero: Box::new(zero.clone()) };
    let thm = kernel().check(&Certificate { lemmas: vec![], main: Some(split) }).expect("checks");
    assert!(thm.proves(&sexp("(& a (! a))"), Rel::Eq, &sexp("0*")));
    // One case alone is only local.
    let thm = kernel().check(&Certificate { lemmas: vec![], main: Some(zero.clone()) }).unwrap();
    assert!(!thm.proves(&sexp("(& a (! a))"), Rel::Eq, &sexp("0*")));
    // Two copies of the same case are not a split.
    let bogus =
        Proof::CaseSplit { atom: sexp("a"), one: Box::new(zero.clone()), zero: Box::new(zero) };
    let thm = kernel().check(&Certificate { lemmas: vec![], main: Some(bogus) }).unwrap();
    assert!(!thm.local().is_empty());
}

#[test]
fn a_case_assumption_does_not_rewrite_inside_a_timer() {
    let cert = chain("(ton 5s a)", vec![step(&[1], Rule::Case(sexp("a"), true), "(ton 5s 1*)")]);
    assert!(matches!(kernel().check(&cert), Err(KernelError::BadPosition(_))));
}

#[test]
fn implication_from_meet_and_from_zero() {
    // a·b = 0* gives a ⇒ ¬b via a·¬¬b? Keep it simple: (a·¬b = 0*) needs a hypothesis.
    let meet = Proof::Chain {
        start: sexp("(& L1_pump (ton 5s L1_up))"),
        steps: vec![
            step(
                &[0],
                cite(Source::Hypothesis, "L06", Use::Forward),
                "(& (ton 5s L1_Prod) (ton 5s L1_up))",
            ),
            step(
                &[1, 1],
                cite(Source::Hypothesis, "L05", Use::Forward),
                "(& (ton 5s L1_Prod) (ton 5s L1_Prod))",
            ),
        ],
    };
    // This chain ends in x·x, not in L1_pump: ImpliesByMeet must refuse it.
    let cert = Certificate { lemmas: vec![], main: Some(Proof::ImpliesByMeet(Box::new(meet))) };
    assert!(matches!(kernel().check(&cert), Err(KernelError::Mismatch(_))));
}

#[test]
fn lemmas_are_checked_and_cited() {
    let lemma = Proof::Chain { start: sexp("L1_pump"), steps: p1_steps() };
    let main = Proof::Chain {
        start: sexp("(& L1_pump c)"),
        steps: vec![step(&[0], cite(Source::Lemma, "P1", Use::Forward), "(& (ton 5s L1_up) c)")],
    };
    let cert = Certificate { lemmas: vec![("P1".into(), lemma)], main: Some(main.clone()) };
    let thm = kernel().check(&cert).expect("checks");
    assert!(thm.axioms_used().1.contains("L06"));
    let missing = Certificate { lemmas: vec![], main: Some(main) };
    assert!(matches!(kernel().check(&missing), Err(KernelError::UnknownRule(_))));
}

#[test]
fn malformed_axioms_are_refused() {
    let delay_as_signal = Axiom::ground("bad", sexp("(& 5s a)"), Rel::Eq, sexp("a"));
    assert!(Kernel::new(vec![], vec![delay_as_signal]).is_err());
    let not_ground = law("h", "f", Rel::Eq, "f", &["f"], &[]);
    assert!(Kernel::new(vec![], vec![not_ground]).is_err());
    let twice = vec![
        Axiom::ground("H", sexp("a"), Rel::Eq, sexp("b")),
        Axiom::ground("H", sexp("a"), Rel::Eq, sexp("c")),
    ];
    assert!(Kernel::new(vec![], twice).is_err());
}

#[test]
fn a_signal_variable_never_binds_a_delay() {
    // not_not-like rule used backwards at a delay would build ¬¬5s.
    let k =
        Kernel::new(vec![law("and_one", "(& f 1*)", Rel::Eq, "f", &["f"], &[])], vec![]).unwrap();
    let cert = chain(
        "(ton 5s a)",
        vec![step(&[0], cite(Source::Law, "and_one", Use::Backward), "(ton (& 5s 1*) a)")],
    );
    assert!(k.check(&cert).is_err());
    let _unused: Option<Expr> = None;
}

#[test]
fn a_shared_lemma_is_cited_only_by_the_kernel_that_checked_it() {
    // `L1_pump = 5s/L1_up`, checked once and kept.
    let k = kernel();
    let p1 = std::sync::Arc::new(k.check(&chain("L1_pump", p1_steps())).expect("checks"));
    let uses_p1 = chain(
        "(& L1_pump a)",
        vec![step(&[0], cite(Source::Lemma, "P1", Use::Forward), "(& (ton 5s L1_up) a)")],
    );
    let known = |t: &std::sync::Arc<Theorem>| -> Lemmas { [("P1".to_string(), t.clone())].into() };
    let thm = k.check_using(&uses_p1, known(&p1)).expect("its own theorem");
    assert!(thm.proves(&sexp("(& L1_pump a)"), Rel::Eq, &sexp("(& (ton 5s L1_up) a)")));
    // What the lemma rests on, the theorem rests on.
    assert!(thm.axioms_used().1.contains("L06") && thm.axioms_used().1.contains("L05"));
    // Without it, or from another kernel with the same axioms, the citation is unknown.
    assert!(matches!(k.check(&uses_p1), Err(KernelError::UnknownRule(_))));
    let other = kernel();
    assert!(matches!(other.check_using(&uses_p1, known(&p1)), Err(KernelError::Mismatch(_))));
    // A long chain of lemmas drops without exhausting the stack.
    let again = chain(
        "L1_pump",
        vec![step(&[], cite(Source::Lemma, "P1", Use::Forward), "(ton 5s L1_up)")],
    );
    let mut last = p1;
    for _ in 0..100_000 {
        let next = k.check_using(&again, known(&last)).expect("checks");
        last = std::sync::Arc::new(next);
    }
    drop(last);
}

#[test]
fn a_theorem_under_case_assumptions_is_no_lemma() {
    // `a = 1*` under `a = 1*`, and `a = 0*` under `a = 0*`: each holds only in its case.
    let k = kernel();
    let case = |v: bool| {
        let konst = if v { "1*" } else { "0*" };
        let thm = k.check(&chain("a", vec![step(&[], Rule::Case(sexp("a"), v), konst)])).unwrap();
        assert_eq!(thm.local().len(), 1, "the case assumption is kept");
        std::sync::Arc::new(thm)
    };
    let known: Lemmas = [("A1".to_string(), case(true)), ("A0".to_string(), case(false))].into();
    // 1* = a = 0*, citing both as if they were facts about whole signals.
    let false_goal = chain(
        "1*",
        vec![
            step(&[], cite(Source::Lemma, "A1", Use::Backward), "a"),
            step(&[], cite(Source::Lemma, "A0", Use::Forward), "0*"),
        ],
    );
    let refused = k.check_using(&false_goal, known);
    assert!(matches!(refused, Err(KernelError::Mismatch(ref m)) if m.contains("only local")));
    // Each alone is refused the same way, whatever the certificate.
    let only_one: Lemmas = [("A1".to_string(), case(true))].into();
    assert!(k.check_using(&chain("b", vec![]), only_one).is_err());
}

#[test]
fn a_kernel_vouches_only_for_its_own_theorem_of_the_goal() {
    let k = kernel();
    let thm = k.check(&chain("L1_pump", p1_steps())).expect("checks");
    let (l, r) = (sexp("L1_pump"), sexp("(ton 5s L1_up)"));
    assert!(k.vouch(&thm, &l, Rel::Eq, &r).is_ok());
    assert!(k.vouch(&thm, &l, Rel::Implies, &r).is_ok(), "an equation gives the implication");
    // Another statement, or another kernel with the same axioms (another file's context).
    assert!(matches!(k.vouch(&thm, &r, Rel::Implies, &l), Err(KernelError::NotTheGoal(_))));
    assert!(matches!(kernel().vouch(&thm, &l, Rel::Eq, &r), Err(KernelError::NotTheGoal(_))));
    // A theorem under a case assumption is not one about whole signals.
    let local = k.check(&chain("a", vec![step(&[], Rule::Case(sexp("a"), true), "1*")])).unwrap();
    assert!(k.vouch(&local, &sexp("a"), Rel::Eq, &sexp("1*")).is_err());
}
