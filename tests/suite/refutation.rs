//! The kernel's propositional refutation rule: a goal shown `0*` from proved facts and clauses derived by unit propagation, accepted only when it follows, refused when a clause, a fact or the empty clause is missing or forged.

use crate::common::rng;

use ii_prove::kernel::{Axiom, Certificate, Kernel, Proof, Rel, Rule, Source, Step, Use};
use ii_prove::prover::boolean::{Constraint, refute};
use ii_prove::prover::constraint;
use ii_prove::term::{Expr, sexp};
use rng::Rng;

fn kernel(hyps: &[Axiom]) -> Kernel {
    Kernel::new(Vec::new(), hyps.to_vec()).expect("well-formed axioms")
}

/// The proof of hypothesis `name` (`lhs = rhs`, or `lhs ⇒ rhs` as `lhs = lhs·rhs`).
fn cite(h: &Axiom) -> Proof {
    let (how, after) = match h.rel {
        Rel::Eq => (Use::Forward, h.rhs.clone()),
        Rel::Implies => (Use::Meet, sexp(&format!("(& {} {})", h.lhs, h.rhs))),
    };
    let step = Step {
        path: vec![],
        rule: Rule::Cite(Source::Hypothesis, h.name.clone(), how),
        after,
        subst: vec![],
        premises: vec![],
    };
    Proof::Chain { start: h.lhs.clone(), steps: vec![step] }
}

fn refutation(goal: &str, facts: Vec<Proof>, lemmas: Vec<Vec<i32>>) -> Certificate {
    Certificate {
        lemmas: vec![],
        main: Some(Proof::Refutation { goal: sexp(goal), facts, lemmas }),
    }
}

fn hyps() -> Vec<Axiom> {
    vec![
        Axiom::ground("H1", sexp("x"), Rel::Eq, sexp("(& a b)")),
        Axiom::ground("H2", sexp("y"), Rel::Implies, sexp("(! a)")),
    ]
}

#[test]
fn a_goal_refuted_by_propagation_from_its_facts_is_zero() {
    let h = hyps();
    let k = kernel(&h);
    // x·¬a: x = a·b forces a.
    let cert = refutation("(& x (! a))", vec![cite(&h[0])], vec![]);
    let thm = k.check_goal(&cert, &sexp("(& x (! a))"), Rel::Eq, &sexp("0*")).expect("accepted");
    assert!(thm.local().is_empty());
    // x·y: x forces a, y forces ¬a; with an explicit derived clause `¬x` first.
    let cert = refutation("(& x y)", vec![cite(&h[0]), cite(&h[1])], vec![vec![-1], vec![]]);
    k.check_goal(&cert, &sexp("(& x y)"), Rel::Eq, &sexp("0*")).expect("accepted");
}

#[test]
fn a_refutation_needs_every_fact_it_rests_on() {
    let h = hyps();
    let k = kernel(&h);
    let err = k.check(&refutation("(& x y)", vec![cite(&h[0])], vec![])).unwrap_err();
    assert!(err.to_string().contains("empty clause"), "{err}");
    let err = k.check(&refutation("(& x (! a))", vec![], vec![vec![]])).unwrap_err();
    assert!(err.to_string().contains("not implied"), "{err}");
}

#[test]
fn forged_clauses_and_facts_are_refused() {
    let h = hyps();
    let k = kernel(&h);
    // A satisfiable goal, with the empty clause claimed outright.
    let err = k.check(&refutation("(& x a)", vec![cite(&h[0])], vec![vec![]])).unwrap_err();
    assert!(err.to_string().contains("lemma 1"), "{err}");
    // A derived clause that does not follow, even with a true one after it.
    let err = k.check(&refutation("(& x a)", vec![cite(&h[0])], vec![vec![-2], vec![]]));
    assert!(err.is_err());
    // A literal of no variable.
    let err = k.check(&refutation("(& x (! a))", vec![cite(&h[0])], vec![vec![99]])).unwrap_err();
    assert!(err.to_string().contains("no variable"), "{err}");
    // A fact that is not the hypothesis: `x = a` instead of `x = a·b`.
    let mut wrong = cite(&h[0]);
    if let Proof::Chain { steps, .. } = &mut wrong {
        steps[0].after = sexp("a");
    }
    assert!(k.check(&refutation("(& x (! a))", vec![wrong], vec![])).is_err());
}

#[test]
fn a_fact_under_a_case_assumption_keeps_it() {
    let k = kernel(&hyps());
    // `a = 1*` under the case `a = 1*`; `¬a = 0*` then holds only under it.
    let case = Step {
        path: vec![],
        rule: Rule::Case(sexp("a"), true),
        after: sexp("1*"),
        subst: vec![],
        premises: vec![],
    };
    let fact = Proof::Chain { start: sexp("a"), steps: vec![case] };
    let cert = refutation("(! a)", vec![fact], vec![]);
    let thm = k.check(&cert).expect("checked under the case");
    assert_eq!(thm.local().len(), 1);
    assert!(k.vouch(&thm, &sexp("(! a)"), Rel::Eq, &sexp("0*")).is_err());
}

/// A random term over the atoms `a`, `b`, `c`, `pre a`.
fn term(rng: &mut Rng, depth: u32) -> String {
    if depth == 0 || rng.chance(25) {
        return rng.pick(&["a", "b", "c", "(pre a)", "1*", "0*"]).to_string();
    }
    match rng.below(3) {
        0 => format!("(! {})", term(rng, depth - 1)),
        1 => format!("(& {} {})", term(rng, depth - 1), term(rng, depth - 1)),
        _ => format!("(+ {} {})", term(rng, depth - 1), term(rng, depth - 1)),
    }
}

fn eval(e: &Expr, id: ii_prove::term::Id, v: &[bool; 4]) -> bool {
    use ii_prove::term::Term;
    match &e[id] {
        Term::Zero => false,
        Term::One => true,
        Term::Not(a) => !eval(e, *a, v),
        Term::And([a, b]) => eval(e, *a, v) && eval(e, *b, v),
        Term::Or([a, b]) => eval(e, *a, v) || eval(e, *b, v),
        Term::Pre(_) => v[3],
        Term::Name(n) => v[["a", "b", "c"].iter().position(|x| *x == n.as_str()).unwrap()],
        other => panic!("unexpected {other:?}"),
    }
}

/// Is `goal` 0 at every assignment of the atoms where every hypothesis holds?
fn refuted(goal: &Expr, hyps: &[Axiom]) -> bool {
    let root = |e: &Expr| ii_prove::term::root(e);
    (0..16u8).all(|bits| {
        let v = [bits & 1 != 0, bits & 2 != 0, bits & 4 != 0, bits & 8 != 0];
        let holds = hyps.iter().all(|h| {
            let (l, r) = (eval(&h.lhs, root(&h.lhs), &v), eval(&h.rhs, root(&h.rhs), &v));
            if h.rel == Rel::Eq { l == r } else { !l || r }
        });
        !holds || !eval(goal, root(goal), &v)
    })
}

#[test]
fn random_refutations_are_accepted_exactly_when_the_goal_is_refuted() {
    let (mut found, mut forged) = (0, 0);
    let mut borrowed: Vec<Vec<i32>> = vec![vec![]];
    for seed in 0..400 {
        let mut rng = Rng::new(seed);
        let hyps: Vec<Axiom> = (0..1 + rng.below(3))
            .map(|i| {
                let rel = if rng.chance(50) { Rel::Eq } else { Rel::Implies };
                Axiom::ground(
                    format!("H{i}"),
                    sexp(&term(&mut rng, 2)),
                    rel,
                    sexp(&term(&mut rng, 2)),
                )
            })
            .collect();
        let Ok(k) = Kernel::for_scans(
            Vec::new(),
            hyps.clone(),
            ii_prove::term::Delay::from_micros(10_000).unwrap(),
        ) else {
            continue;
        };
        let goal = sexp(&term(&mut rng, 3));
        let constraints: Vec<Constraint> = hyps.iter().map(constraint).collect();
        let truth = refuted(&goal, &hyps);
        let zero = sexp("0*");
        match refute(&goal, &constraints) {
            Some(proof) => {
                assert!(truth, "seed {seed}: a refutation of a satisfiable goal {goal}");
                let cert = Certificate { lemmas: vec![], main: Some(proof.clone()) };
                k.check_goal(&cert, &goal, Rel::Eq, &zero).expect("the kernel accepts it");
                found += 1;
                if let Proof::Refutation { lemmas, .. } = proof {
                    borrowed = lemmas;
                }
            }
            None => assert!(!truth, "seed {seed}: no refutation of a refuted goal {goal}"),
        }
        if !truth {
            // Claims of the empty clause, with any facts, never pass on a satisfiable goal.
            let facts: Vec<Proof> = hyps.iter().map(cite).collect();
            let n = 1 + rng.below(6) as i32;
            // The empty clause claimed after a clause and its negation, or the clauses of
            // another goal's refutation.
            for lemmas in [vec![vec![n], vec![-n], vec![]], borrowed.clone()] {
                let cert = Certificate {
                    lemmas: vec![],
                    main: Some(Proof::Refutation {
                        goal: goal.clone(),
                        facts: facts.clone(),
                        lemmas,
                    }),
                };
                assert!(
                    k.check(&cert).is_err(),
                    "seed {seed}: forged refutation of {goal} accepted"
                );
                forged += 1;
            }
        }
    }
    assert!(found >= 50 && forged >= 50, "{found} refutations, {forged} forged");
}
