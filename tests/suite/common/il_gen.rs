//! Random Instruction List programs for the differential tests, kept as instructions as well as text: loads, the Boolean operators with `N` and `( … )`, `NOT`, `EQ`/`NE`, `ST`/`STN`/`S`/`R`, forward `JMP`/`JMPC`/`JMPCN` with labels reached from several paths, `RETC`/`RETCN`, `INT` arithmetic ending in a comparison or `INT_TO_BOOL`, and calls of TON, TOF, R_TRIG, F_TRIG, SR, RS (`CAL` with formal or positional inputs, `CLK`/`S1`/`R1`/`IN` as operators), some skipped by jumps, some inputs left out (a timer's `PT` among them) and some instances called twice; `INT` locals, the first sometimes of a subrange type.
#![allow(dead_code)]

use super::rng::Rng;
use std::collections::BTreeMap;

/// An operand: a BOOL variable or FB output (`T0.Q`), possibly negated where it is an
/// argument, or a literal.
#[derive(Clone, Debug)]
pub enum Operand {
    /// A variable or output.
    Var(String),
    /// `TRUE`/`FALSE`.
    Lit(bool),
}

/// The logical operators.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Logic {
    /// `AND`.
    And,
    /// `OR`.
    Or,
    /// `XOR`.
    Xor,
    /// `EQ`.
    Eq,
    /// `NE`.
    Ne,
}

/// An integer operand: an `INT` variable or a literal.
#[derive(Clone, Debug)]
pub enum IntOperand {
    /// A variable.
    Var(String),
    /// A literal (not negative).
    Lit(i64),
}

/// The arithmetic operators (`DIV` and `MOD` only by a literal that is not 0).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Arith {
    /// `ADD`.
    Add,
    /// `SUB`.
    Sub,
    /// `MUL`.
    Mul,
    /// `DIV`.
    Div,
    /// `MOD`.
    Mod,
}

/// The comparison operators on integers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cmp {
    /// `GT`.
    Gt,
    /// `GE`.
    Ge,
    /// `EQ`.
    Eq,
    /// `NE`.
    Ne,
    /// `LT`.
    Lt,
    /// `LE`.
    Le,
}

/// When a jump or return acts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum When {
    /// Always.
    Always,
    /// `C`.
    True,
    /// `CN`.
    False,
}

/// How a call is written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Form {
    /// `CAL T0(IN := x, PT := T#5ms)`, one input per line.
    Formal,
    /// `CAL S0(x, y)`, a timer's preset a `CONSTANT` (`PT := P_T0` formally: matiec
    /// misplaces a duration literal given to an IL call, and reads `R :=` as the `R`
    /// operator).
    Positional,
    /// `CAL T0(IN := x, PT := P_T0)`, the preset a `CONSTANT`.
    NamedPreset,
}

/// One instruction (one line, or several for `( … )` and calls).
#[derive(Clone, Debug)]
pub enum Ins {
    /// `LD x`/`LDN x`.
    Ld(bool, Operand),
    /// `AND x`, `ORN x`, `EQ x`, …
    Op(Logic, bool, Operand),
    /// `AND( x` then the inner operations, then `)` (`ANDN(` when negated).
    Nested(Logic, bool, Operand, Vec<(Logic, bool, Operand)>),
    /// `NOT`.
    Not,
    /// `ST x`/`STN x`.
    St(bool, String),
    /// `S x`.
    Set(String),
    /// `R x`.
    Reset(String),
    /// `JMP l`, `JMPC l`, `JMPCN l`.
    Jump(When, String),
    /// `l:`.
    Label(String),
    /// `RETC`, `RETCN`.
    Ret(When),
    /// `CAL inst(pin := [NOT] x, …, PT := T#…)`: the instance, its type, its Boolean
    /// inputs, the preset in µs for timers, and the call's form.
    Cal(String, String, Vec<(String, bool, Operand)>, Option<u64>, Form),
    /// `LD x` then `PIN inst` (`CLK R0`, `S1 S0`, `R1 Z0`, `IN T0`): a call with the
    /// current result as that input, the instance's other inputs left out.
    FbIn(String, String),
    /// `LD n` of an `INT`.
    LdInt(String),
    /// `ADD x`, `MUL 3`, …: the integer current result.
    Arith(Arith, IntOperand),
    /// `GT x`, …: the integer current result compared, a BOOL from then on.
    Compare(Cmp, IntOperand),
    /// `ST n` of the integer current result.
    StInt(String),
    /// `INT_TO_BOOL` (the type named): the integer current result a BOOL from then on,
    /// TRUE when it is not 0.
    ToBool(String),
}

/// Whether some call of `g` leaves an input out (an input operator, a `CAL` without
/// one of its instance's Boolean inputs or a timer's `PT`), and whether some instance
/// is called twice.
pub fn calls_leaving_inputs_out(g: &Generated) -> (bool, bool) {
    let mut called: Vec<&str> = Vec::new();
    let mut omits = false;
    for i in &g.ins {
        let inst = match i {
            Ins::FbIn(_, inst) => {
                omits = true;
                inst
            }
            Ins::Cal(inst, ty, args, pt, _) => {
                let pins = if ty == "TON" || ty == "TOF" || ty.ends_with("TRIG") { 1 } else { 2 };
                let timer = ty == "TON" || ty == "TOF";
                omits |= args.len() < pins || (timer && pt.is_none());
                inst
            }
            _ => continue,
        };
        called.push(inst);
    }
    let n = called.len();
    called.sort();
    called.dedup();
    (omits, called.len() < n)
}

/// A random program.
pub struct Generated {
    /// The `.il` text.
    pub text: String,
    /// Its instructions.
    pub ins: Vec<Ins>,
    /// Its BOOL inputs.
    pub inputs: Vec<String>,
    /// Its BOOL locals with their initial values.
    pub locals: Vec<(String, bool)>,
    /// Its `INT` locals with their initial values.
    pub ints: Vec<(String, i64)>,
    /// Its function-block instances and their types.
    pub fbs: Vec<(String, String)>,
    /// The bits worth comparing: locals and FB outputs, as the lowering names them (`T0_Q`).
    pub bits: Vec<String>,
    /// The scan cycle, in µs.
    pub cycle_us: u64,
}

fn operand_text(o: &Operand) -> String {
    match o {
        Operand::Var(v) => v.clone(),
        Operand::Lit(b) => if *b { "TRUE" } else { "FALSE" }.into(),
    }
}

fn int_text(o: &IntOperand) -> String {
    match o {
        IntOperand::Var(v) => v.clone(),
        IntOperand::Lit(k) => k.to_string(),
    }
}

fn logic_word(l: Logic, neg: bool) -> String {
    let base = match l {
        Logic::And => "AND",
        Logic::Or => "OR",
        Logic::Xor => "XOR",
        Logic::Eq => "EQ",
        Logic::Ne => "NE",
    };
    if neg { format!("{base}N") } else { base.into() }
}

fn when_suffix(w: When) -> &'static str {
    match w {
        When::Always => "",
        When::True => "C",
        When::False => "CN",
    }
}

fn duration(us: u64) -> String {
    match us % 1000 {
        0 => format!("T#{}ms", us / 1000),
        f => format!("T#{}.{}ms", us / 1000, format!("{f:03}").trim_end_matches('0')),
    }
}

/// The text of the instructions.
pub fn render(ins: &[Ins]) -> String {
    let mut out = String::new();
    for i in ins {
        match i {
            Ins::Ld(n, o) => {
                out += &format!("  LD{} {}\n", if *n { "N" } else { "" }, operand_text(o))
            }
            Ins::Op(l, n, o) => out += &format!("  {} {}\n", logic_word(*l, *n), operand_text(o)),
            Ins::Nested(l, n, first, inner) => {
                out += &format!("  {}( {}\n", logic_word(*l, *n), operand_text(first));
                for (l, n, o) in inner {
                    out += &format!("    {} {}\n", logic_word(*l, *n), operand_text(o));
                }
                out += "  )\n";
            }
            Ins::Not => out += "  NOT\n",
            Ins::St(n, x) => out += &format!("  ST{} {x}\n", if *n { "N" } else { "" }),
            Ins::Set(x) => out += &format!("  S {x}\n"),
            Ins::Reset(x) => out += &format!("  R {x}\n"),
            Ins::Jump(w, l) => out += &format!("  JMP{} {l}\n", when_suffix(*w)),
            Ins::Label(l) => out += &format!("{l}:\n"),
            Ins::Ret(w) => out += &format!("  RET{}\n", when_suffix(*w)),
            Ins::Cal(inst, _, args, pt, form) => {
                let value = |n: bool, o: &Operand| {
                    format!("{}{}", if n { "NOT " } else { "" }, operand_text(o))
                };
                let preset = |us: u64| match form {
                    Form::Formal => duration(us),
                    _ => format!("P_{inst}"),
                };
                if args.is_empty() && pt.is_none() {
                    out += &format!("  CAL {inst}\n");
                    continue;
                }
                if *form == Form::Positional && pt.is_none() {
                    let a: Vec<String> = args.iter().map(|(_, n, o)| value(*n, o)).collect();
                    out += &format!("  CAL {inst}({})\n", a.join(", "));
                    continue;
                }
                let mut a: Vec<String> =
                    args.iter().map(|(p, n, o)| format!("{p} := {}", value(*n, o))).collect();
                if let Some(us) = pt {
                    a.push(format!("PT := {}", preset(*us)));
                }
                // matiec reads a formal call's inputs on lines of their own.
                out += &format!("  CAL {inst}(\n    {}\n  )\n", a.join(",\n    "));
            }
            Ins::FbIn(pin, inst) => out += &format!("  {pin} {inst}\n"),
            Ins::LdInt(n) => out += &format!("  LD {n}\n"),
            Ins::Arith(a, o) => {
                let word = match a {
                    Arith::Add => "ADD",
                    Arith::Sub => "SUB",
                    Arith::Mul => "MUL",
                    Arith::Div => "DIV",
                    Arith::Mod => "MOD",
                };
                out += &format!("  {word} {}\n", int_text(o));
            }
            Ins::Compare(c, o) => {
                let word = match c {
                    Cmp::Gt => "GT",
                    Cmp::Ge => "GE",
                    Cmp::Eq => "EQ",
                    Cmp::Ne => "NE",
                    Cmp::Lt => "LT",
                    Cmp::Le => "LE",
                };
                out += &format!("  {word} {}\n", int_text(o));
            }
            Ins::StInt(n) => out += &format!("  ST {n}\n"),
            Ins::ToBool(t) => out += &format!("  {t}_TO_BOOL\n"),
        }
    }
    out
}

struct Gen<'r> {
    rng: &'r mut Rng,
    /// Whether matiec must build it: no `EQ`/`NE` between BOOLs (its C library has no
    /// `EQ_BOOL`) and plain operands as call inputs (its IL grammar).
    for_matiec: bool,
    reads: Vec<String>,
    locals: Vec<String>,
    /// The `INT` locals (none in a program without integers).
    ints: Vec<String>,
    labels: usize,
}

impl Gen<'_> {
    fn operand(&mut self) -> Operand {
        if self.rng.chance(10) {
            Operand::Lit(self.rng.chance(50))
        } else {
            Operand::Var(self.rng.pick(&self.reads).clone())
        }
    }

    /// An operator and its `N` modifier (`EQ` and `NE` have none).
    /// A call's input (matiec misplaces a literal given to an IL call: a variable then).
    fn argument(&mut self) -> Operand {
        match self.operand() {
            Operand::Lit(_) if self.for_matiec => Operand::Var(self.rng.pick(&self.reads).clone()),
            o => o,
        }
    }

    fn logic(&mut self) -> (Logic, bool) {
        let all = [Logic::And, Logic::And, Logic::Or, Logic::Or, Logic::Xor, Logic::Eq, Logic::Ne];
        let l = *self.rng.pick(if self.for_matiec { &all[..5] } else { &all[..] });
        (l, !matches!(l, Logic::Eq | Logic::Ne) && self.rng.chance(30))
    }

    /// Operations on the current result.
    fn ops(&mut self, out: &mut Vec<Ins>) {
        for _ in 0..self.rng.below(4) {
            match self.rng.below(10) {
                0 => out.push(Ins::Not),
                1 | 2 => {
                    let ((l, n), first) = (self.logic(), self.operand());
                    let inner = (0..1 + self.rng.below(2))
                        .map(|_| {
                            let (l, n) = self.logic();
                            (l, n, self.operand())
                        })
                        .collect();
                    out.push(Ins::Nested(l, n, first, inner));
                }
                _ => {
                    let ((l, n), o) = (self.logic(), self.operand());
                    out.push(Ins::Op(l, n, o));
                }
            }
        }
    }

    /// Writes of the current result.
    fn writes(&mut self, out: &mut Vec<Ins>) {
        for _ in 0..1 + self.rng.below(2) {
            let x = self.rng.pick(&self.locals).clone();
            out.push(match self.rng.below(6) {
                0 => Ins::Set(x),
                1 => Ins::Reset(x),
                2 => Ins::St(true, x),
                _ => Ins::St(false, x),
            });
        }
    }

    /// How to write a call: matiec needs the positional form with named presets.
    fn form(&mut self) -> Form {
        if self.for_matiec {
            return Form::Positional;
        }
        *self.rng.pick(&[Form::Formal, Form::Formal, Form::Positional, Form::NamedPreset])
    }

    fn int_operand(&mut self) -> IntOperand {
        if self.rng.chance(50) {
            IntOperand::Var(self.rng.pick(&self.ints).clone())
        } else {
            IntOperand::Lit(*self.rng.pick(&[0, 1, 2, 3, 7, 10, 100, 1000, 20_000, 32_767]))
        }
    }

    /// An integer group: `LD n`, arithmetic and stores, then a comparison or (one group
    /// in four) `INT_TO_BOOL` followed by Boolean operations (the current result a BOOL
    /// again), and writes of it.
    fn integers(&mut self, out: &mut Vec<Ins>) {
        out.push(Ins::LdInt(self.rng.pick(&self.ints).clone()));
        for _ in 0..1 + self.rng.below(4) {
            let op = *self.rng.pick(&[
                Arith::Add,
                Arith::Add,
                Arith::Sub,
                Arith::Mul,
                Arith::Div,
                Arith::Mod,
            ]);
            let o = match op {
                Arith::Div | Arith::Mod => IntOperand::Lit(1 + self.rng.below(7) as i64),
                _ => self.int_operand(),
            };
            out.push(Ins::Arith(op, o));
            if self.rng.chance(40) {
                out.push(Ins::StInt(self.rng.pick(&self.ints).clone()));
            }
        }
        if self.rng.chance(25) {
            out.push(Ins::ToBool("INT".into()));
            self.ops(out);
        } else {
            let c = *self.rng.pick(&[Cmp::Gt, Cmp::Ge, Cmp::Eq, Cmp::Ne, Cmp::Lt, Cmp::Le]);
            let o = self.int_operand();
            out.push(Ins::Compare(c, o));
        }
        self.writes(out);
    }

    fn label(&mut self) -> String {
        self.labels += 1;
        format!("L_{}", self.labels)
    }
}

/// A random program of seed `seed`.
pub fn program(seed: u64) -> Generated {
    program_with(seed, false)
}

/// A random program of seed `seed`, within what matiec builds when `for_matiec`.
pub fn program_with(seed: u64, for_matiec: bool) -> Generated {
    let mut rng = Rng::new(seed);
    let n_in = 1 + rng.below(4) as usize;
    let n_local = 2 + rng.below(5) as usize;
    let inputs: Vec<String> = (0..n_in).map(|k| format!("In{k}")).collect();
    let locals: Vec<(String, bool)> =
        (0..n_local).map(|k| (format!("B{k}"), rng.chance(30))).collect();
    let cycle_ms = *rng.pick(&[1u64, 5, 10, 20, 100]);
    let fbs: Vec<(String, String)> =
        [("T", "TON"), ("F", "TOF"), ("R", "R_TRIG"), ("D", "F_TRIG"), ("S", "SR"), ("Z", "RS")]
            .iter()
            .filter(|_| rng.chance(50))
            .map(|(p, t)| (format!("{p}0"), t.to_string()))
            .collect();
    let out_pin = |t: &str| if t == "SR" || t == "RS" { "Q1" } else { "Q" };
    let mut reads: Vec<String> = inputs.clone();
    reads.extend(locals.iter().map(|(n, _)| n.clone()));
    reads.extend(fbs.iter().map(|(n, t)| format!("{n}.{}", out_pin(t))));
    let local_names: Vec<String> = locals.iter().map(|(n, _)| n.clone()).collect();
    // Half the programs compute with INT locals too.
    let ints: Vec<(String, i64)> = if rng.chance(50) {
        (0..1 + rng.below(3)).map(|k| (format!("N{k}"), rng.below(41) as i64 - 20)).collect()
    } else {
        Vec::new()
    };
    let int_names = ints.iter().map(|(n, _)| n.clone()).collect();
    let mut g =
        Gen { rng: &mut rng, for_matiec, reads, locals: local_names, ints: int_names, labels: 0 };
    let mut ins = Vec::new();
    // Labels that forward jumps wait for (calls mostly come where none is pending);
    // returns only after the last call.
    let mut pending: Vec<String> = Vec::new();
    let mut calls: Vec<(String, String)> = fbs.clone();
    // The instances called a second time, and each timer's `PT` at its first call.
    let mut seconds: Vec<String> = Vec::new();
    let mut presets: BTreeMap<String, Option<u64>> = BTreeMap::new();
    let groups = 3 + g.rng.below(8);
    let mut returned = false;
    for k in 0..groups {
        if !pending.is_empty() && g.rng.chance(40) {
            let at = g.rng.below(pending.len() as u64) as usize;
            ins.push(Ins::Label(pending.remove(at)));
            // A label may be followed by operations on the CR its paths bring.
            if g.rng.chance(50) {
                g.ops(&mut ins);
                g.writes(&mut ins);
            }
        }
        let last_calls = k + 1 == groups;
        if !calls.is_empty() && (last_calls || g.rng.chance(30)) {
            // Most calls come where no jump is pending; the others are skipped by the
            // jumps that pass them (the block runs only at the scans it is called).
            if last_calls || g.rng.chance(70) {
                for l in pending.drain(..) {
                    ins.push(Ins::Label(l));
                }
            }
            while !calls.is_empty() && (last_calls || g.rng.chance(50)) {
                let (inst, ty) = calls.remove(0);
                let timer = ty == "TON" || ty == "TOF";
                // An instance may be called again later in the scan, its inputs left out
                // (a timer's with the same `PT`: one instance, one preset).
                let second = seconds.contains(&inst);
                let again = !second && g.rng.chance(30);
                if again {
                    seconds.push(inst.clone());
                    calls.push((inst.clone(), ty.clone()));
                }
                // An input operator: the instance's other inputs keep their values.
                let pin = match ty.as_str() {
                    "R_TRIG" | "F_TRIG" => "CLK",
                    "SR" => "S1",
                    "RS" => "R1",
                    _ => "IN",
                };
                if !(timer && second) && g.rng.chance(if timer { 15 } else { 40 }) {
                    if timer {
                        presets.insert(inst.clone(), None);
                    }
                    let o = g.operand();
                    ins.push(Ins::Ld(g.rng.chance(30), o));
                    g.ops(&mut ins);
                    ins.push(Ins::FbIn(pin.to_string(), inst));
                    continue;
                }
                let pins: &[&str] = match ty.as_str() {
                    "TON" | "TOF" => &["IN"],
                    "R_TRIG" | "F_TRIG" => &["CLK"],
                    "SR" => &["S1", "R"],
                    _ => &["S", "R1"],
                };
                let form = g.form();
                let mut args: Vec<(String, bool, Operand)> = pins
                    .iter()
                    .map(|p| (p.to_string(), !g.for_matiec && g.rng.chance(25), g.argument()))
                    .collect();
                // Inputs left out: a positional call's last ones, a formal call's any.
                if args.len() > 1 && g.rng.chance(25) {
                    let at = match form {
                        Form::Positional => args.len() - 1,
                        _ => g.rng.below(args.len() as u64) as usize,
                    };
                    args.remove(at);
                } else if !timer && g.rng.chance(10) {
                    args.clear();
                }
                let pt = timer
                    .then(|| g.rng.below(6) * cycle_ms * 1000 + g.rng.below(3) * 700)
                    .filter(|_| !g.rng.chance(20));
                let pt = match presets.get(&inst) {
                    Some(first) if timer && second => *first,
                    _ => pt,
                };
                if timer {
                    presets.insert(inst.clone(), pt);
                }
                ins.push(Ins::Cal(inst, ty, args, pt, form));
            }
        }
        if !g.ints.is_empty() && g.rng.chance(40) {
            g.integers(&mut ins);
            continue;
        }
        let o = g.operand();
        ins.push(Ins::Ld(g.rng.chance(25), o));
        g.ops(&mut ins);
        match g.rng.below(10) {
            0..=1 => {
                let w = *g.rng.pick(&[When::True, When::False, When::Always]);
                let l = if !pending.is_empty() && g.rng.chance(40) {
                    g.rng.pick(&pending).clone()
                } else {
                    let l = g.label();
                    pending.push(l.clone());
                    l
                };
                if g.rng.chance(50) {
                    g.writes(&mut ins);
                }
                ins.push(Ins::Jump(w, l));
            }
            2 if calls.is_empty() && !returned && k + 2 < groups => {
                returned = true;
                g.writes(&mut ins);
                ins.push(Ins::Ret(*g.rng.pick(&[When::True, When::False])));
            }
            _ => g.writes(&mut ins),
        }
    }
    for l in pending {
        ins.push(Ins::Label(l));
    }
    // Every function block is called once per scan.
    for (inst, ty) in calls {
        let pins: &[&str] = match ty.as_str() {
            "TON" | "TOF" => &["IN"],
            "R_TRIG" | "F_TRIG" => &["CLK"],
            "SR" => &["S1", "R"],
            _ => &["S", "R1"],
        };
        let args = pins.iter().map(|p| (p.to_string(), false, g.argument())).collect();
        let pt = (ty == "TON" || ty == "TOF").then(|| g.rng.below(6) * cycle_ms * 1000);
        let form = g.form();
        ins.push(Ins::Cal(inst, ty, args, pt, form));
    }
    // Sometimes the first INT local is of a subrange type (drawn apart, so the rest of
    // the program stays as it was): matiec's `ST` stores into it unchecked.
    let mut sub = Rng::new(seed ^ 0x5B12);
    let ranged = !ints.is_empty() && sub.chance(50);
    let mut text = String::new();
    if ranged {
        let lo = sub.below(40) as i64 - 20;
        let hi = lo + sub.below(60) as i64;
        text += &format!("TYPE\n  Rg0 : INT ({lo}..{hi});\nEND_TYPE\n\n");
    }
    text += "PROGRAM Random\n  VAR_INPUT\n";
    for i in &inputs {
        text += &format!("    {i} : BOOL;\n");
    }
    text += "  END_VAR\n  VAR\n";
    for (b, init) in &locals {
        text += &format!("    {b} : BOOL{};\n", if *init { " := TRUE" } else { "" });
    }
    for (k, (n, init)) in ints.iter().enumerate() {
        let t = if ranged && k == 0 { "Rg0" } else { "INT" };
        text += &format!("    {n} : {t} := {init};\n");
    }
    for (n, t) in &fbs {
        text += &format!("    {n} : {t};\n");
    }
    text += "  END_VAR\n";
    // One constant per instance (a timer called twice gives the same preset both times).
    let mut named: Vec<String> = ins
        .iter()
        .filter_map(|i| match i {
            Ins::Cal(inst, _, _, Some(us), Form::Positional | Form::NamedPreset) => {
                Some(format!("    P_{inst} : TIME := {};\n", duration(*us)))
            }
            _ => None,
        })
        .collect();
    named.sort();
    named.dedup();
    if !named.is_empty() {
        text += &format!("  VAR CONSTANT\n{}  END_VAR\n", named.concat());
    }
    text += &render(&ins);
    text += "END_PROGRAM\n\n";
    text += &format!(
        "CONFIGURATION Config\n  RESOURCE Res ON PLC\n    TASK Cyclic (INTERVAL := T#{cycle_ms}ms, PRIORITY := 1);\n    PROGRAM Main WITH Cyclic : Random;\n  END_RESOURCE\nEND_CONFIGURATION\n"
    );
    let mut bits: Vec<String> = locals.iter().map(|(n, _)| n.clone()).collect();
    bits.extend(fbs.iter().map(|(n, t)| format!("{n}_{}", out_pin(t))));
    Generated { text, ins, inputs, locals, ints, fbs, bits, cycle_us: cycle_ms * 1000 }
}
