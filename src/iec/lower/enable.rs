//! `EN` and `ENO` of a function-block call in Structured Text and IL, as matiec runs them: every function block has them (declared or not); a call's `EN := …` is kept in the instance like any input (TRUE at power-up), the body runs only while it is TRUE (`if (!EN) { ENO := FALSE; return; }`, `lib/C/iec_std_FB.h`, and the same for user FBs, `generate_c.cc`), and `ENO => x` copies the instance's ENO after the call.

use super::Lowering;
use crate::diag::Span;
use crate::iec::ast::{self, Arg};
use crate::program::{BoolExpr, CmpOp, Stmt, WriteKind};

/// What a call's `EN` and `ENO` ask of it.
pub(super) struct Enable<'a> {
    /// Where the body runs: the instance's EN bit, when some call of it gives `EN`.
    guard: Option<BoolExpr>,
    /// The write of the instance's EN bit, when this call gives it.
    set: Vec<Stmt>,
    /// Each `ENO => x` (negated or not).
    eno: Vec<(bool, &'a ast::Expr)>,
    /// The instance's `ENO` bit, where its body may write it (declared, or named by the
    /// body): each call sets it to its EN before the body, and `ENO => x` reads it.
    pub(super) eno_bit: Option<String>,
}

/// Whether `a` is the call's `EN := …` or `ENO => …` (handled here, not by the callee).
pub(super) fn is_en_eno(a: &Arg) -> bool {
    match a {
        Arg::Input(n, _) => n.key() == "EN",
        Arg::Output(n, _, _) => n.key() == "ENO",
        Arg::Positional(_) => false,
    }
}

impl Enable<'_> {
    /// Whether the body runs under the instance's EN.
    pub(super) fn guarded(&self) -> bool {
        self.guard.is_some()
    }

    /// The call's `ENO => x` are copied among its outputs (a declared `ENO`, in its
    /// place), not by [`Lowering::enabled_call`].
    pub(super) fn eno_among_outputs(&mut self) {
        self.eno.clear();
    }
}

impl Lowering<'_> {
    /// The `EN` and `ENO` of a call of the FB instance `inst` (its name in the scan
    /// model) with `args`.
    pub(super) fn enable<'a>(&mut self, inst: &str, args: &'a [Arg]) -> Enable<'a> {
        let key = inst.to_ascii_uppercase();
        let mut set = Vec::new();
        let mut eno = Vec::new();
        for a in args {
            match a {
                Arg::Input(n, e) if n.key() == "EN" => {
                    self.enabled.insert(key.clone());
                    let bit = self.en_bit(inst);
                    let value = self.bool_expr(e);
                    let value = self.temp(&mut set, value);
                    set.push(Stmt::Write {
                        target: bit,
                        kind: WriteKind::Assign,
                        value,
                        span: n.span,
                    });
                }
                Arg::Output(n, negated, target) if n.key() == "ENO" => eno.push((*negated, target)),
                _ => {}
            }
        }
        // A declared `EN := FALSE` no call gives: the body never runs.
        let guard = match self.enabled.contains(&key) {
            true => Some(BoolExpr::var(&self.en_bit(inst))),
            false => self.en_off.contains(&key).then_some(BoolExpr::Const(false)),
        };
        Enable { guard, set, eno, eno_bit: None }
    }

    /// Whether the standard FB instance `key` is followed call by call (its edge
    /// memories hidden bits, its timers matiec's own state): called more than once in a
    /// scan, or in a body that runs under an `EN` ([`super::lower_under_en`]), whose
    /// state the caller's simulator then reads as the program's bits and integers.
    pub(super) fn call_by_call(&self, key: &str) -> bool {
        self.multi.contains(key) || self.enable.is_some()
    }

    /// Writes that keep what a call gives its instance (an input, a preset): into `out`,
    /// or, in a call under its EN, before the call's `IF`, as they run whatever its EN.
    pub(super) fn keep(&mut self, out: &mut Vec<Stmt>, writes: impl IntoIterator<Item = Stmt>) {
        self.kept_writes.as_mut().unwrap_or(out).extend(writes);
    }

    /// The hidden bit of the instance's `EN`, TRUE at power-up (unless declared
    /// `EN : BOOL := FALSE`).
    fn en_bit(&mut self, inst: &str) -> String {
        let bit = self.hidden(inst, "EN");
        if !self.starts.contains(&bit) && !self.en_off.contains(&inst.to_ascii_uppercase()) {
            self.starts.push(bit.clone());
        }
        bit
    }

    /// The call: `before` (what it writes whatever its EN: the inputs it gives), the
    /// write of its EN, its `body` where EN is TRUE, then its `ENO`s and `after` (its
    /// `=>` outputs, copied whatever its EN): matiec copies the outputs in their
    /// declaration order, the `ENO` it declares itself first.
    pub(super) fn enabled_call(
        &mut self,
        en: Enable<'_>,
        parts: [Vec<Stmt>; 3],
        span: Span,
    ) -> Vec<Stmt> {
        let [before, body, after] = parts;
        let mut out = before;
        out.extend(en.set);
        let on = en.guard.clone().unwrap_or(BoolExpr::Const(true));
        // `if (!EN) { ENO := FALSE; return; } else ENO := TRUE;`
        if let Some(bit) = &en.eno_bit {
            let (target, value) = (bit.clone(), on.clone());
            out.push(Stmt::Write { target, kind: WriteKind::Assign, value, span });
        }
        match &en.guard {
            Some(g) => out.extend(Stmt::guarded(g, body, span)),
            None => out.extend(body),
        }
        let eno = en.eno_bit.as_deref().map_or(on, BoolExpr::var);
        for (negated, target) in en.eno {
            out.extend(self.eno_copy(negated, target, &eno, span));
        }
        out.extend(after);
        out
    }

    /// `ENO => target` (`NOT ENO =>` where `negated`) of a call whose ENO is `eno`.
    fn eno_copy(
        &mut self,
        negated: bool,
        target: &ast::Expr,
        eno: &BoolExpr,
        span: Span,
    ) -> Vec<Stmt> {
        let value = if negated { BoolExpr::negate(eno.clone()) } else { eno.clone() };
        self.assign_value(target, value, span)
    }

    /// The copies of the `ENO => x` among a function call's `args`, its ENO being `eno`.
    pub(super) fn eno_copies(&mut self, args: &[Arg], eno: &BoolExpr, span: Span) -> Vec<Stmt> {
        let mut out = Vec::new();
        for a in args {
            if let Arg::Output(n, negated, target) = a
                && n.key() == "ENO"
            {
                out.extend(self.eno_copy(*negated, target, eno, span));
            }
        }
        out
    }
}

/// The arguments of a standard function call as matiec matches them: positional ones in
/// order, formal ones by the parameter they name (`SEL(IN1 := a, G := g, IN0 := b)` is
/// `SEL(g, b, a)`), and its `EN`. `TEST_EN` (`lib/C/iec_std_functions.h`) returns the
/// type's initial value (0, FALSE, 0.0, T#0s) where `EN` is FALSE.
pub(super) struct FnArgs<'a> {
    /// The inputs, in the order of the function's parameters.
    pub(super) values: Vec<&'a ast::Expr>,
    /// The `EN := …` given.
    pub(super) en: Option<&'a ast::Expr>,
}

/// The place of the formal parameter `name` among the inputs of the standard function
/// `f` (both upper case).
fn param_index(f: &str, name: &str) -> Option<usize> {
    let numbered = |n: &str| n.strip_prefix("IN")?.parse::<usize>().ok();
    match (f, name) {
        ("SEL", "G") | ("MUX", "K") | ("LIMIT", "MN") => Some(0),
        ("LIMIT", "IN") | ("SHL" | "SHR" | "ROL" | "ROR", "N") => Some(1),
        ("LIMIT", "MX") => Some(2),
        ("SEL" | "MUX", n) => numbered(n).map(|k| k + 1),
        ("LIMIT", _) => None,
        (_, "IN") => Some(0),
        (_, n) => numbered(n).filter(|k| *k >= 1).map(|k| k - 1),
    }
}

/// The input `k` (in parameter order) of the standard function call `f(args)`.
pub(super) fn std_arg<'a>(f: &str, args: &'a [Arg], k: usize) -> Option<&'a ast::Expr> {
    let mut positional = args.iter().filter_map(|a| match a {
        Arg::Positional(x) => Some(x),
        _ => None,
    });
    positional.nth(k).or_else(|| {
        args.iter().find_map(|a| match a {
            Arg::Input(n, x) if param_index(f, &n.key()) == Some(k) && n.key() != "EN" => Some(x),
            _ => None,
        })
    })
}

impl Lowering<'_> {
    /// The arguments of the standard function call `f(args)`, or why they are not read
    /// (an output `=>` given to a function is refused with a located error: it would
    /// write a variable).
    pub(super) fn std_args<'a>(
        &mut self,
        f: &ast::Ident,
        args: &'a [Arg],
    ) -> Result<FnArgs<'a>, String> {
        let name = f.key();
        let (mut values, mut formal, mut en) = (Vec::new(), Vec::new(), None);
        for a in args {
            match a {
                Arg::Positional(x) => values.push(x),
                Arg::Input(n, x) if n.key() == "EN" => en = Some(x),
                Arg::Input(n, x) => match param_index(&name, &n.key()) {
                    Some(k) => formal.push((k, x)),
                    None => {
                        return Err(format!(
                            "`{}` has no input `{}` ii-prove reads",
                            f.name, n.name
                        ));
                    }
                },
                // Written by [`Lowering::std_eno`].
                Arg::Output(n, _, _) if n.key() == "ENO" => {}
                // Refused (the lowering fails), so the call is read without it.
                Arg::Output(n, _, _) => {
                    let what = format!("the output `{}` of the function `{}`", n.name, f.name);
                    self.refuse(
                        n.span,
                        &what,
                        "a standard function has no output but its result and ENO",
                    );
                }
            }
        }
        if !formal.is_empty() {
            formal.sort_by_key(|(k, _)| *k);
            let gap = formal.iter().enumerate().any(|(i, (k, _))| i != *k);
            if !values.is_empty() || gap {
                return Err(format!(
                    "the inputs of `{}` are not given as its parameters in full",
                    f.name
                ));
            }
            values = formal.into_iter().map(|(_, x)| x).collect();
        }
        Ok(FnArgs { values, en })
    }
}

impl Lowering<'_> {
    /// The `ENO => x` of the standard function call `f(args)` (`values`: its inputs in
    /// parameter order; `en`: its `EN`), run before the statement as matiec's C runs it
    /// while evaluating it: `TEST_EN` (`lib/C/iec_std_functions.h`) sets ENO to EN;
    /// `DIV`'s `TEST_EN_COND` clears it where the divisor is 0 too. Refused for the
    /// functions whose condition ii-prove does not compute (`MUX`'s selector out of
    /// range, an invalid BCD, the string functions' lengths and positions).
    pub(super) fn std_eno(
        &mut self,
        f: &ast::Ident,
        args: &[Arg],
        values: &[&ast::Expr],
        en: Option<BoolExpr>,
    ) {
        let Some(pin) = args.iter().find_map(|a| match a {
            Arg::Output(n, _, _) if n.key() == "ENO" => Some(n),
            _ => None,
        }) else {
            return;
        };
        let name = f.key();
        let on = en.unwrap_or(BoolExpr::Const(true));
        let eno = match name.as_str() {
            "DIV" => match values.get(1) {
                Some(d) if plain(d) => match self.int_expr(d) {
                    Ok(d) => {
                        let zero = super::ints::Int::literal(0);
                        let nonzero = self.int_compare_values(CmpOp::Ne, d, zero, f.span);
                        Some(BoolExpr::and(on, nonzero))
                    }
                    Err(_) => None,
                },
                _ => None,
            },
            "MUX" | "LEFT" | "RIGHT" | "MID" | "DELETE" | "INSERT" | "REPLACE" => None,
            n if n.starts_with("BCD_TO_") || n.contains("_BCD_TO_") => None,
            _ => Some(on),
        };
        match eno {
            Some(eno) => {
                let copies = self.eno_copies(args, &eno, f.span);
                self.prelude.extend(copies);
            }
            None => self.refuse(
                pin.span,
                &format!("the ENO of `{}`", f.name),
                "matiec clears it where an input is out of range, which ii-prove does not compute here",
            ),
        }
    }
}

/// Whether `e` calls no function (lowering it again adds nothing to run before it).
fn plain(e: &ast::Expr) -> bool {
    use ast::ExprKind as K;
    match &e.kind {
        K::Call(..) => false,
        K::Member(x, _) | K::Unary(_, x) => plain(x),
        K::Binary(_, a, b) => plain(a) && plain(b),
        K::Index(x, ix) => plain(x) && ix.iter().all(plain),
        K::Bool(_) | K::Int(_) | K::Time(_) | K::Literal(_) | K::Var(_) => true,
    }
}
