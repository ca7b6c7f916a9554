//! The kernel on a program's scans: `pre` is rewritten only by laws that hold before the first scan, induction over scans is checked (base and step) and refused outside programs, and terms are validated.

use std::time::{Duration, Instant};

use ii_prove::diag::Sources;
use ii_prove::kernel::{
    Axiom, Certificate, Cmp, Kernel, KernelError, Proof, Rel, Rule, Source, Step, Use,
};
use ii_prove::ladder::{compile, read_ldmicro};
use ii_prove::prover::{Budget, Context, Obligation, induction};
use ii_prove::term::{Delay, Expr, Symbol, Term, sexp};
use ii_prove::theory;

fn law(name: &str, lhs: &str, rel: Rel, rhs: &str, vars: &[&str]) -> Axiom {
    Axiom {
        signal_vars: vars.iter().map(|v| Symbol::from(*v)).collect(),
        ..Axiom::ground(name, sexp(lhs), rel, sexp(rhs))
    }
}

fn laws() -> Vec<Axiom> {
    vec![
        law("and_comm", "(& f g)", Rel::Eq, "(& g f)", &["f", "g"]),
        law("pre_not", "(pre (! a))", Rel::Eq, "(! (pre a))", &["a"]),
        law("ton_weaken", "(ton 5s f)", Rel::Implies, "f", &["f"]),
    ]
}

fn ms(n: u64) -> Delay {
    Delay::from_micros(n * 1_000).unwrap()
}

fn scan_kernel() -> Kernel {
    let hyps = vec![Axiom::ground("L01", sexp("X"), Rel::Eq, sexp("(! Y)"))];
    Kernel::for_scans(laws(), hyps, ms(1)).expect("well-formed axioms")
}

fn one_step(start: &str, path: &[usize], rule: Rule, after: &str) -> Certificate {
    let step =
        Step { path: path.to_vec(), rule, after: sexp(after), subst: vec![], premises: vec![] };
    Certificate {
        lemmas: vec![],
        main: Some(Proof::Chain { start: sexp(start), steps: vec![step] }),
    }
}

#[test]
fn a_hypothesis_false_before_the_first_scan_does_not_rewrite_under_pre() {
    // `X = ¬Y` at every scan, but before the first scan X is 0 and ¬Y is 1: `pre X` and
    // `pre ¬Y` differ at the first scan.
    let cert = one_step(
        "(pre X)",
        &[0],
        Rule::Cite(Source::Hypothesis, "L01".into(), Use::Forward),
        "(pre (! Y))",
    );
    assert!(matches!(scan_kernel().check(&cert), Err(KernelError::BadPosition(_))));
    // At the top it does.
    let cert =
        one_step("X", &[], Rule::Cite(Source::Hypothesis, "L01".into(), Use::Forward), "(! Y)");
    assert!(scan_kernel().check(&cert).is_ok());
}

#[test]
fn a_fact_true_before_the_first_scan_rewrites_under_pre() {
    // `Q = A · ¬B` holds at every scan and before the first (0 = 0 · 1): at the previous
    // scan too, so `pre Q = pre (A · ¬B)`; an implication only at a monotone position.
    let hyps = vec![
        Axiom::ground("L02", sexp("Q"), Rel::Eq, sexp("(& A (! B))")),
        Axiom::ground("B01", sexp("Q"), Rel::Implies, sexp("A")),
        Axiom::ground("B02", sexp("(! Q)"), Rel::Implies, sexp("B")),
    ];
    let k = Kernel::for_scans(laws(), hyps, ms(10)).expect("kernel");
    let cite = |name: &str, how| Rule::Cite(Source::Hypothesis, name.into(), how);
    let eq = one_step("(pre Q)", &[0], cite("L02", Use::Forward), "(pre (& A (! B)))");
    assert!(k.check(&eq).is_ok());
    let meet = one_step("(pre Q)", &[0], cite("B01", Use::Meet), "(pre (& Q A))");
    assert!(k.check(&meet).is_ok());
    // `¬Q ⇒ B` fails before the first scan (¬0 = 1, B = 0).
    let early = one_step("(pre (! Q))", &[0], cite("B02", Use::Meet), "(pre (& (! Q) B))");
    assert!(matches!(k.check(&early), Err(KernelError::BadPosition(_))));
}

#[test]
fn under_pre_only_laws_of_the_boolean_operators_and_pre_rewrite() {
    let k = scan_kernel();
    let comm = Rule::Cite(Source::Law, "and_comm".into(), Use::Forward);
    assert!(k.check(&one_step("(pre (& a b))", &[0], comm, "(pre (& b a))")).is_ok());
    let pre_not = Rule::Cite(Source::Law, "pre_not".into(), Use::Forward);
    assert!(k.check(&one_step("(pre (pre (! a)))", &[0], pre_not, "(pre (! (pre a)))")).is_ok());
    // `5s/f ⇒ f` holds at every scan, not before the first one (where `f` may be 1).
    let weaken = Rule::Cite(Source::Law, "ton_weaken".into(), Use::Forward);
    let cert = one_step("(pre (ton 5s f))", &[0], weaken, "(pre f)");
    assert!(matches!(k.check(&cert), Err(KernelError::BadPosition(_))));
    // A case assumption is about the present scan.
    let case = Rule::Case(sexp("a"), true);
    let cert = one_step("(pre a)", &[0], case, "(pre 1*)");
    assert!(matches!(k.check(&cert), Err(KernelError::BadPosition(_))));
}

#[test]
fn a_law_about_the_cycle_needs_the_programs_cycle() {
    // `d/f ⇒ pre f if d ≥ cycle`: `cycle`, named in the condition only, is the kernel's.
    let ton_pre = Axiom {
        signal_vars: vec![Symbol::from("f")],
        delay_vars: vec![Symbol::from("d"), Symbol::from("cycle")],
        delay_conditions: vec![(sexp("d"), Cmp::Ge, sexp("cycle"))],
        ..Axiom::ground("ton_pre", sexp("(ton d f)"), Rel::Implies, sexp("(pre f)"))
    };
    let kernel = |cycle| Kernel::for_scans(vec![ton_pre.clone()], vec![], cycle).expect("kernel");
    let cite = Rule::Cite(Source::Law, "ton_pre".into(), Use::Meet);
    let step = |delay: &str| {
        let start = format!("(ton {delay} X)");
        one_step(&start, &[], cite.clone(), &format!("(& {start} (pre X))"))
    };
    assert!(kernel(ms(10)).check(&step("20ms")).is_ok());
    assert!(kernel(ms(20)).check(&step("20ms")).is_ok());
    // A delay shorter than the cycle is refused (a term has no sub-cycle delay on scans,
    // and the side condition fails for a shorter whole multiple: none exists), and free
    // signals have no cycle.
    let short = kernel(ms(50)).check(&step("20ms"));
    assert!(matches!(short, Err(KernelError::SubCycleDelay(_))), "{short:?}");
    assert!(Kernel::new(vec![ton_pre.clone()], vec![]).unwrap().check(&step("20ms")).is_err());
    // Nor can a certificate choose the cycle itself.
    let mut claimed = step("20ms");
    if let Some(Proof::Chain { steps, .. }) = &mut claimed.main {
        steps[0].subst = vec![(Symbol::from("cycle"), sexp("1ms"))];
    }
    assert!(kernel(ms(10)).check(&claimed).is_err());
}

#[test]
fn free_signals_have_no_pre() {
    let hyps = vec![Axiom::ground("H", sexp("X"), Rel::Eq, sexp("(pre Y)"))];
    assert!(matches!(Kernel::new(laws(), hyps), Err(KernelError::BadAxiom(_))));
    let free = Kernel::new(laws(), vec![]).expect("kernel");
    let comm = Rule::Cite(Source::Law, "and_comm".into(), Use::Forward);
    let cert = one_step("(pre (& a b))", &[0], comm, "(pre (& b a))");
    assert!(free.check(&cert).is_err());
}

#[test]
fn terms_whose_nodes_are_out_of_order_are_refused() {
    // A node pointing at itself: not a term, whoever built it.
    let looped: Expr = Expr::from(vec![Term::Name(Symbol::from("a")), Term::Not(1.into())]);
    let cert =
        Certificate { lemmas: vec![], main: Some(Proof::Chain { start: looped, steps: vec![] }) };
    assert!(scan_kernel().check(&cert).is_err());
}

/// The press of examples/press.ld, its compiled hypotheses, and the prover's
/// certificate of `RFire ⇒ RArmed` by induction.
fn press() -> (Context, Obligation, Certificate) {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut sources = Sources::new();
    let text = std::fs::read_to_string(root.join("examples/press.ld")).expect("readable");
    let file = sources.add("press.ld", text);
    let compiled = compile(&read_ldmicro(&sources, file).expect("parses")).expect("compiles");
    let theory = theory::standard(&mut Sources::new()).expect("theory");
    let cycle = Some(compiled.scan_cycle());
    let ctx = Context::with_scans(theory.axioms(), compiled.axioms(), cycle).expect("context");
    let goal = Obligation { lhs: sexp("RFire"), rel: Rel::Implies, rhs: sexp("RArmed") };
    let budget = Budget::default();
    let deadline = Instant::now() + Duration::from_secs(20);
    let proved = induction::prove(&ctx, &goal, budget, deadline).expect("proved by induction");
    (ctx, goal, proved.certificate)
}

fn check(ctx: &Context, goal: &Obligation, cert: &Certificate) -> Result<(), KernelError> {
    ctx.kernel.check_goal(cert, &goal.lhs, goal.rel, &goal.rhs).map(|_| ())
}

/// The invariant lemma's parts.
fn parts(cert: &Certificate) -> (Expr, Proof, Proof) {
    match &cert.lemmas[0].1 {
        Proof::Induction { inv, base, step } => (inv.clone(), (**base).clone(), (**step).clone()),
        other => panic!("not an induction: {other:?}"),
    }
}

fn with_lemma(cert: &Certificate, lemma: Proof) -> Certificate {
    Certificate { lemmas: vec![(cert.lemmas[0].0.clone(), lemma)], main: cert.main.clone() }
}

#[test]
fn an_induction_certificate_is_checked_base_and_step() {
    let (ctx, goal, cert) = press();
    check(&ctx, &goal, &cert).expect("the kernel accepts it");
    let (inv, base, step) = parts(&cert);
    // The step in place of the base, the base in place of the step: both refused.
    let swapped = Proof::Induction {
        inv: inv.clone(),
        base: Box::new(step.clone()),
        step: Box::new(base.clone()),
    };
    assert!(check(&ctx, &goal, &with_lemma(&cert, swapped)).is_err());
    // Another invariant than the one the base and step prove.
    let other = Proof::Induction {
        inv: sexp("(+ RArmed RFire)"),
        base: Box::new(base.clone()),
        step: Box::new(step.clone()),
    };
    assert!(check(&ctx, &goal, &with_lemma(&cert, other)).is_err());
    // An induction inside a base case would use the first scan's hypotheses as if they
    // held at every scan.
    let nested = Proof::Induction {
        inv: inv.clone(),
        base: Box::new(Proof::Induction {
            inv: inv.clone(),
            base: Box::new(base.clone()),
            step: Box::new(step.clone()),
        }),
        step: Box::new(step),
    };
    assert!(check(&ctx, &goal, &with_lemma(&cert, nested)).is_err());
}

#[test]
fn induction_is_refused_for_free_signals() {
    let (ctx, goal, cert) = press();
    // The same laws and a hypothesis-free kernel about free signals.
    let free = Kernel::new(ctx.laws.clone(), vec![]).expect("kernel");
    assert!(free.check_goal(&cert, &goal.lhs, goal.rel, &goal.rhs).is_err());
    let (inv, base, step) = parts(&cert);
    let lemma = Proof::Induction { inv, base: Box::new(base), step: Box::new(step) };
    let only = Certificate { lemmas: vec![], main: Some(lemma) };
    assert!(matches!(free.check(&only), Err(KernelError::BadPosition(_))));
}

#[test]
fn on_scans_every_delay_is_a_whole_number_of_cycles() {
    // `d1/(d2/f) = (d1+d2)/f` holds in continuous time; with a 1 s cycle and
    // d1 = d2 = 0.5s it fails on scans, so such a term is refused wherever it appears.
    let ton_ton = Axiom {
        signal_vars: vec![Symbol::from("f")],
        delay_vars: vec![Symbol::from("d1"), Symbol::from("d2")],
        ..Axiom::ground(
            "ton_ton",
            sexp("(ton d1 (ton d2 f))"),
            Rel::Eq,
            sexp("(ton (dadd d1 d2) f)"),
        )
    };
    let cite = Rule::Cite(Source::Law, "ton_ton".into(), Use::Forward);
    let halves = one_step("(ton 0.5s (ton 0.5s X))", &[], cite.clone(), "(ton (dadd 0.5s 0.5s) X)");
    let second = Kernel::for_scans(vec![ton_ton.clone()], vec![], ms(1_000)).expect("kernel");
    let refused = second.check(&halves);
    assert!(matches!(refused, Err(KernelError::SubCycleDelay(_))), "{refused:?}");
    // With a 0.5 s cycle the same step is a whole number of cycles, and checks.
    let half = Kernel::for_scans(vec![ton_ton.clone()], vec![], ms(500)).expect("kernel");
    assert!(half.check(&halves).is_ok());
    // Free signals are continuous: the law holds there.
    assert!(Kernel::new(vec![ton_ton], vec![]).unwrap().check(&halves).is_ok());
    // A hypothesis with a sub-cycle delay is refused when the kernel is built.
    let hyp = Axiom::ground("L01", sexp("Y"), Rel::Eq, sexp("(ton 25ms X)"));
    let built = Kernel::for_scans(laws(), vec![hyp.clone()], ms(10));
    assert!(matches!(built, Err(KernelError::BadAxiom(_))), "{built:?}");
    assert!(Kernel::for_scans(laws(), vec![hyp], ms(5)).is_ok());
}

/// A lemma holds at every scan, so in an induction's base it reads as at the first scan
/// (each `pre f` replaced by the value `f` has before it), as a hypothesis does; its
/// reading at other scans is not the base's.
#[test]
fn in_a_base_case_a_lemma_reads_as_at_the_first_scan() {
    let mut all = laws();
    all.push(law("not_zero", "(! 0*)", Rel::Eq, "1*", &[]));
    let hyps = vec![Axiom::ground("H", sexp("Z"), Rel::Eq, sexp("(pre Z)"))];
    let kernel = Kernel::for_scans(all, hyps, ms(1)).expect("well-formed axioms");
    let step = |path: &[usize], source, name: &str, how, after: &str| Step {
        path: path.to_vec(),
        rule: Rule::Cite(source, name.into(), how),
        after: sexp(after),
        subst: vec![],
        premises: vec![],
    };
    let lemma = Proof::Chain {
        start: sexp("Z"),
        steps: vec![step(&[], Source::Hypothesis, "H", Use::Forward, "(pre Z)")],
    };
    let certificate = |base_steps: Vec<Step>| Certificate {
        lemmas: vec![
            ("m".into(), lemma.clone()),
            (
                "inv".into(),
                Proof::Induction {
                    inv: sexp("(! Z)"),
                    base: Box::new(Proof::Symm(Box::new(Proof::Chain {
                        start: sexp("(! Z)"),
                        steps: base_steps,
                    }))),
                    step: Box::new(Proof::Chain {
                        start: sexp("(pre (! Z))"),
                        steps: vec![
                            step(&[], Source::Law, "pre_not", Use::Forward, "(! (pre Z))"),
                            step(&[0], Source::Lemma, "m", Use::Backward, "(! Z)"),
                        ],
                    }),
                },
            ),
        ],
        main: Some(Proof::Chain { start: sexp("(! Z)"), steps: vec![] }),
    };
    // At the first scan `m` reads `Z = 0*`.
    let first = certificate(vec![
        step(&[0], Source::Lemma, "m", Use::Forward, "(! 0*)"),
        step(&[], Source::Law, "not_zero", Use::Forward, "1*"),
    ]);
    kernel.check(&first).expect("the lemma's first-scan reading");
    // Its reading at other scans, `Z = pre Z`, is not the base's.
    let later = certificate(vec![step(&[0], Source::Lemma, "m", Use::Forward, "(! (pre Z))")]);
    assert!(kernel.check(&later).is_err());
}
