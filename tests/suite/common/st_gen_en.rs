//! Function calls with `EN` and `ENO =>` for the random Structured Text programs (`st_gen.rs`), drawn from a generator of their own so that the rest of each program stays what it was.

use super::rng::Rng;

/// Zero to two statements calling a function with `EN` and `ENO =>`: a standard Boolean
/// function, a comparison or `DIV` (its `ENO` FALSE where the divisor is 0 too), or the
/// user function `Fn0` (in `funcs`). Their inputs read the program's `inputs` only (a
/// statement that also reads the variable its `ENO` writes is refused); results and
/// `ENO`s go to `locals`, integer results to `int_vars` outside the subrange `ranged`.
pub fn function_calls(
    en: &mut Rng,
    inputs: &[String],
    locals: &[String],
    int_vars: &[(String, String)],
    ranged: &[String],
    funcs: &[String],
) -> String {
    let mut text = String::new();
    let r = |en: &mut Rng| en.pick(inputs).clone();
    for _ in 0..en.below(3) {
        let (x, e) = (en.pick(locals).clone(), en.pick(locals).clone());
        let plain: Vec<&(String, String)> =
            int_vars.iter().filter(|(n, _)| !ranged.contains(n)).collect();
        let call = match en.below(4) {
            0 if !plain.is_empty() => {
                let (n, t) = (*en.pick(&plain)).clone();
                let same: Vec<&(String, String)> =
                    int_vars.iter().filter(|(_, u)| *u == t).collect();
                let m = en.pick(&same).0.clone();
                format!("{n} := DIV(EN := {}, IN1 := {n}, IN2 := {m}, ENO => {e});", r(en))
            }
            1 if !plain.is_empty() => {
                let n = en.pick(&plain).0.clone();
                format!("{x} := GT(EN := {}, IN1 := {n}, IN2 := 3, ENO => {e});", r(en))
            }
            2 if !funcs.is_empty() => {
                let (a, b, c) = (r(en), r(en), r(en));
                format!("{x} := Fn0(EN := {a}, A := {b}, B := {c}, ENO => {e});")
            }
            _ => {
                let f = en.pick(&["AND", "OR", "XOR"]);
                let (a, b, c) = (r(en), r(en), r(en));
                format!("{x} := {f}(EN := {a}, IN1 := {b}, IN2 := {c}, ENO => {e});")
            }
        };
        text += &format!("  {call}\n");
    }
    text
}
