//! Random Structured Text programs for the differential tests: Boolean assignments, IF/ELSIF/ELSE, every modelled function block (TON, TOF, TP, R_TRIG, F_TRIG, SR, RS, CTU, CTD, CTUD) with formal inputs and outputs (`EN` and `ENO` in some calls; timers and edge detectors sometimes called under an IF, a timer's `PT` sometimes left out, and some instances called a second time with inputs left out), user functions and function blocks (inputs left out keep their values; some declaring `EN` and `ENO`, their bodies writing `ENO`, called with `EN` and `ENO =>`), standard and user function calls with `EN` and `ENO =>`, FOR loops with constant bounds and WHILE/REPEAT loops counted before the scan (EXIT and CONTINUE under IF in their bodies), RETURN under IF in a program and a function block, the Boolean operators and functions, integers of every 8- to 32-bit type and a subrange of one (arithmetic, division by literals, MOD by literals and variables, conversions, MIN/MAX/LIMIT/ABS/SEL, comparisons, CASE, integer inputs), initial values, some locals of the program and the function block in `VAR_TEMP` (FALSE again at every scan or call), and a configuration giving the cycle.
#![allow(dead_code)]

use super::rng::Rng;

/// A random program and the names of its inputs.
pub struct Generated {
    /// The `.st` text.
    pub text: String,
    /// The program's type name.
    pub pou: String,
    /// Its BOOL inputs.
    pub inputs: Vec<String>,
    /// The bits worth comparing: BOOL variables and FB outputs (hidden `T0_Q` names).
    pub bits: Vec<String>,
    /// The scan cycle, in µs.
    pub cycle_us: u64,
    /// The integer variables worth comparing (name, IEC type), counts (`C0.CV`) included.
    pub ints: Vec<(String, String)>,
    /// The integer inputs (name, width): the schedule gives their bits `X_b0 …`.
    pub int_inputs: Vec<(String, u32)>,
}

/// Integer types: (name, bits, signed).
const INT_TYPES: [(&str, u32, bool); 6] = [
    ("INT", 16, true),
    ("DINT", 32, true),
    ("SINT", 8, true),
    ("UINT", 16, false),
    ("USINT", 8, false),
    ("UDINT", 32, false),
];

fn int_info(t: &str) -> (u32, bool) {
    INT_TYPES.iter().find(|(n, _, _)| *n == t).map_or((16, true), |(_, b, s)| (*b, *s))
}

struct Gen<'r> {
    rng: &'r mut Rng,
    /// Boolean literals written so far (every third is written `1` or `0`).
    literals: u32,
    /// `MOD`s written so far (every third divides by a variable, perhaps 0).
    mods: u32,
    /// Readable Boolean terms.
    reads: Vec<String>,
    /// Writable BOOL variables.
    writes: Vec<String>,
    /// User functions of two BOOL inputs it may call.
    funcs: Vec<String>,
    /// Readable integers: (expression, IEC type).
    ints: Vec<(String, String)>,
    /// Writable integers: (name, IEC type).
    int_writes: Vec<(String, String)>,
}

impl Gen<'_> {
    /// `TRUE` or `FALSE`, every third time `1` or `0` (matiec reads an integer literal 0
    /// or 1 as a BOOL where a BOOL fits); no draw of the generator's.
    fn bool_literal(&mut self, value: bool) -> String {
        self.literals += 1;
        let bit = self.literals.is_multiple_of(3);
        match (value, bit) {
            (true, false) => "TRUE",
            (false, false) => "FALSE",
            (true, true) => "1",
            (false, true) => "0",
        }
        .into()
    }

    fn expr(&mut self, depth: u32) -> String {
        if depth == 0 || self.rng.chance(30) {
            return match self.rng.below(12) {
                0 => self.bool_literal(true),
                1 => self.bool_literal(false),
                3 | 4 if !self.ints.is_empty() => {
                    let t = self.rng.pick(&self.ints).1.clone();
                    let (a, b) = (self.iexpr(&t, 1), self.iexpr(&t, 1));
                    let op = *self.rng.pick(&["<", "<=", ">", ">=", "=", "<>"]);
                    format!("({a} {op} {b})")
                }
                5 if !self.ints.is_empty() => {
                    let t = self.rng.pick(&self.ints).1.clone();
                    format!("{t}_TO_BOOL({})", self.iexpr(&t, 1))
                }
                2 if !self.funcs.is_empty() => {
                    let f = self.rng.pick(&self.funcs).clone();
                    let (a, b) =
                        (self.rng.pick(&self.reads).clone(), self.rng.pick(&self.reads).clone());
                    format!("{f}({a}, {b})")
                }
                _ => self.rng.pick(&self.reads).clone(),
            };
        }
        let a = self.expr(depth - 1);
        let b = self.expr(depth - 1);
        match self.rng.below(10) {
            0 | 1 => format!("{a} AND {b}"),
            2 | 3 => format!("({a} OR {b})"),
            4 => format!("({a} XOR {b})"),
            5 => format!("NOT ({a})"),
            6 => format!("({a} = {b})"),
            7 => format!("({a} <> {b})"),
            8 => {
                let c = self.expr(depth - 1);
                format!("SEL({a}, {b}, {c})")
            }
            _ => {
                let c = self.expr(depth - 1);
                format!("AND({a}, {b}, {c}) & {}", self.expr(0))
            }
        }
    }

    fn assign(&mut self, indent: &str) -> String {
        if !self.int_writes.is_empty() && self.rng.chance(35) {
            let (x, t) = self.rng.pick(&self.int_writes).clone();
            let depth = 1 + u32::from(int_info(&t).0 < 32 && self.rng.chance(30));
            return format!("{indent}{x} := {};\n", self.iexpr(&t, depth));
        }
        let x = self.rng.pick(&self.writes).clone();
        format!("{indent}{x} := {};\n", self.expr(2))
    }

    /// A literal of type `t` (mostly small, sometimes an extreme).
    fn literal(&mut self, t: &str) -> String {
        let (bits, signed) = int_info(t);
        if self.rng.chance(8) {
            let max = if signed { (1i64 << (bits - 1)) - 1 } else { (1i64 << bits) - 1 };
            let v = if signed && self.rng.chance(50) { -max } else { max };
            return v.to_string();
        }
        let v = self.rng.below(25) as i64;
        if signed && self.rng.chance(30) { format!("-{v}") } else { v.to_string() }
    }

    /// An integer expression of type `t`.
    fn iexpr(&mut self, t: &str, depth: u32) -> String {
        let (bits, signed) = int_info(t);
        let same: Vec<String> =
            self.ints.iter().filter(|(_, u)| u == t).map(|(e, _)| e.clone()).collect();
        if depth == 0 || self.rng.chance(30) {
            return if !same.is_empty() && self.rng.chance(65) {
                self.rng.pick(&same).clone()
            } else {
                self.literal(t)
            };
        }
        let a = self.iexpr(t, depth - 1);
        match self.rng.below(13) {
            0 | 1 => format!("({a} + {})", self.iexpr(t, depth - 1)),
            2 | 3 => format!("({a} - {})", self.iexpr(t, depth - 1)),
            // A product of two 32-bit variables is a thousand adders: by literals there.
            4 if int_info(t).0 < 32 && self.rng.chance(50) => {
                format!("({a} * {})", self.iexpr(t, depth - 1))
            }
            4 => format!("({a} * {})", self.literal(t)),
            5 | 6 if bits < 32 => {
                let mut k = 1 + self.rng.below(9) as i64;
                if signed && self.rng.chance(30) {
                    k = -k;
                }
                let op = if self.rng.chance(50) { "/" } else { "MOD" };
                // matiec's `MOD` gives 0 for a divisor 0; its `/` leaves that undefined.
                if op == "MOD" {
                    self.mods += 1;
                    if self.mods.is_multiple_of(3) && !same.is_empty() {
                        return format!("({a} MOD {})", same[self.mods as usize % same.len()]);
                    }
                }
                format!("({a} {op} {k})")
            }
            7 if signed => format!("-({a})"),
            7 => format!("MAX({a}, {})", self.iexpr(t, depth - 1)),
            8 => format!("MIN({a}, {})", self.iexpr(t, depth - 1)),
            9 => {
                let b = self.iexpr(t, depth - 1);
                format!("LIMIT({b}, {a}, {})", self.iexpr(t, depth - 1))
            }
            10 if signed => format!("ABS({a})"),
            10 => format!("SEL({}, {a}, {})", self.expr(1), self.iexpr(t, depth - 1)),
            11 => {
                let (from, _, _) = *self.rng.pick(&INT_TYPES);
                if from == t {
                    return a;
                }
                format!("{from}_TO_{t}({})", self.iexpr(from, depth - 1))
            }
            _ => a,
        }
    }

    /// A `CASE` on an integer.
    fn case(&mut self, indent: &str, depth: u32) -> String {
        let (x, t) = self.rng.pick(&self.ints).clone();
        let inner = format!("{indent}  ");
        let (_, signed) = int_info(&t);
        let mut out = format!("{indent}CASE {x} OF\n");
        let mut next: i64 = if signed { -2 } else { 0 };
        for _ in 0..1 + self.rng.below(3) {
            let label = match self.rng.below(3) {
                0 => format!("{next}..{}", next + 2),
                1 => format!("{next}, {}", next + 2),
                _ => next.to_string(),
            };
            next += 3 + self.rng.below(3) as i64;
            out += &format!("{indent}  {label}:\n");
            out += &self.body(&format!("{inner}  "), depth);
        }
        if self.rng.chance(50) {
            out += &format!("{indent}ELSE\n");
            out += &self.body(&inner, depth);
        }
        out + &format!("{indent}END_CASE;\n")
    }

    fn choice(&mut self, indent: &str, depth: u32) -> String {
        let inner = format!("{indent}  ");
        let mut out = format!("{indent}IF {} THEN\n", self.expr(1));
        out += &self.body(&inner, depth);
        for _ in 0..self.rng.below(2) {
            out += &format!("{indent}ELSIF {} THEN\n", self.expr(1));
            out += &self.body(&inner, depth);
        }
        if self.rng.chance(50) {
            out += &format!("{indent}ELSE\n");
            out += &self.body(&inner, depth);
        }
        out + &format!("{indent}END_IF;\n")
    }

    /// A loop's body: assignments and choices, perhaps an `EXIT` or `CONTINUE` under an
    /// IF among them.
    fn loop_body(&mut self, indent: &str) -> String {
        let mut out = String::new();
        for _ in 0..1 + self.rng.below(3) {
            if self.rng.chance(35) {
                let word = if self.rng.chance(50) { "EXIT" } else { "CONTINUE" };
                let inner = format!("{indent}  ");
                let before = if self.rng.chance(40) { self.assign(&inner) } else { String::new() };
                out += &format!(
                    "{indent}IF {} THEN\n{before}{inner}{word};\n{indent}END_IF;\n",
                    self.expr(1)
                );
            } else if self.rng.chance(25) {
                out += &self.choice(indent, 0);
            } else {
                out += &self.assign(indent);
            }
        }
        out
    }

    /// A `WHILE` or `REPEAT` loop counted by `i`, set just before it: its count is known
    /// before the scan (the body's `CONTINUE` comes after the count's update).
    fn counted_loop(&mut self, indent: &str) -> String {
        let inner = format!("{indent}  ");
        let from = self.rng.below(3);
        let to = from + self.rng.below(4);
        let step = 1 + self.rng.below(2);
        let body = self.loop_body(&inner);
        let mut out = format!("{indent}i := {from};\n");
        if self.rng.chance(50) {
            let test = if step == 1 && self.rng.chance(30) { "<>" } else { "<" };
            out += &format!("{indent}WHILE i {test} {to} DO\n{inner}i := i + {step};\n{body}");
            out += &format!("{indent}END_WHILE;\n");
        } else {
            out += &format!("{indent}REPEAT\n{inner}i := i + {step};\n{body}");
            out += &format!("{indent}UNTIL i >= {} END_REPEAT;\n", to.max(from + 1));
        }
        out
    }

    fn body(&mut self, indent: &str, depth: u32) -> String {
        let mut out = String::new();
        for _ in 0..1 + self.rng.below(3) {
            if depth > 0 && self.rng.chance(25) {
                out += &self.choice(indent, depth - 1);
            } else if depth > 0 && !self.ints.is_empty() && self.rng.chance(10) {
                out += &self.case(indent, depth - 1);
            } else {
                out += &self.assign(indent);
            }
        }
        out
    }
}

/// A random program of seed `seed`.
pub fn program(seed: u64) -> Generated {
    program_with(seed, true)
}

/// A random program of seed `seed`; `negated_outputs`: whether FB calls may give
/// `NOT Q => x` (matiec stops with an internal error on them).
pub fn program_with(seed: u64, negated_outputs: bool) -> Generated {
    let mut rng = Rng::new(seed);
    // The draws of inputs left out and second calls, apart (the other draws, and so the
    // rest of each program, stay what they were before these were generated).
    let mut own = Rng::new(seed ^ 0x0DD5);
    // Which locals are `VAR_TEMP` (set to their initial values at the start of every
    // scan or call), drawn apart as well.
    let mut temp = Rng::new(seed ^ 0x7E3F);
    // The draws of declared `EN` and `ENO`, of `EN` and `ENO =>` on user calls and of
    // standard and user function calls with `ENO =>`, apart as well.
    let mut en = Rng::new(seed ^ 0xE0E0);
    let n_in = 1 + rng.below(4) as usize;
    let n_local = 2 + rng.below(5) as usize;
    let inputs: Vec<String> = (0..n_in).map(|k| format!("In{k}")).collect();
    let locals: Vec<String> = (0..n_local).map(|k| format!("B{k}")).collect();
    let cycle_ms = *rng.pick(&[1u64, 5, 10, 20, 100]);
    // Function blocks: each called once per scan (some a second time, later), at top level.
    let fbs: Vec<(String, &str)> =
        [("T", "TON"), ("F", "TOF"), ("R", "R_TRIG"), ("D", "F_TRIG"), ("S", "SR"), ("Z", "RS")]
            .iter()
            .filter(|_| rng.chance(60))
            .map(|(p, t)| (format!("{p}0"), *t))
            .collect();
    let out_pin = |t: &str| if t == "SR" || t == "RS" { "Q1" } else { "Q" };
    let mut reads: Vec<String> = inputs.iter().chain(&locals).cloned().collect();
    reads.extend(fbs.iter().map(|(n, t)| format!("{n}.{}", out_pin(t))));
    // Integers: variables of random types, perhaps an input, a counter, a pulse timer.
    let with_ints = rng.chance(40);
    let mut int_vars: Vec<(String, String)> = Vec::new();
    let mut int_inputs: Vec<(String, u32)> = Vec::new();
    let mut int_input_decl = String::new();
    let mut counter: Option<(String, &str)> = None;
    let mut pulse = false;
    if with_ints {
        for k in 0..1 + rng.below(4) {
            let (t, _, _) = *rng.pick(&INT_TYPES);
            int_vars.push((format!("N{k}"), t.to_string()));
        }
        if rng.chance(35) {
            let (t, bits, _) = *rng.pick(&INT_TYPES[..5]);
            int_inputs.push(("Nin".into(), bits));
            int_input_decl = format!("    Nin : {t};\n");
        }
        if rng.chance(50) {
            counter = Some(("C0".into(), *rng.pick(&["CTU", "CTD", "CTUD"])));
        }
        pulse = rng.chance(40);
    }
    if let Some((c, t)) = &counter {
        match *t {
            "CTUD" => reads.extend([format!("{c}.QU"), format!("{c}.QD")]),
            _ => reads.push(format!("{c}.Q")),
        }
    }
    if pulse {
        reads.push("P0.Q".into());
    }
    let mut int_reads = int_vars.clone();
    if with_ints {
        int_reads.push(("i".into(), "INT".into()));
    }
    if let Some((c, _)) = &counter {
        int_reads.push((format!("{c}.CV"), "INT".into()));
    }
    if !int_input_decl.is_empty() {
        let t =
            int_input_decl.trim().trim_start_matches("Nin : ").trim_end_matches(';').to_string();
        int_reads.push(("Nin".into(), t));
    }
    let mut g = Gen {
        rng: &mut rng,
        literals: 0,
        mods: 0,
        reads,
        writes: locals.clone(),
        funcs: Vec::new(),
        ints: int_reads,
        int_writes: int_vars.clone(),
    };
    // User POUs: a function of two BOOLs, a function block with a state bit and perhaps a
    // timer or edge detector, called by one or two instances (an input may be left out:
    // it keeps its value from the call before).
    let mut text = String::new();
    let mut user_bits = Vec::new();
    let mut user_calls = Vec::new();
    let mut user_vars = String::new();
    // A subrange type over one integer's type (drawn apart, as above): some variables of
    // that type declared of it, and a block whose input is of it, called with its output
    // given into one of them, where matiec holds the value within the limits.
    let mut sub = Rng::new(seed ^ 0x5B12);
    let subrange = (with_ints && sub.chance(70)).then(|| {
        let base = sub.pick(&int_vars).1.clone();
        let (bits, signed) = int_info(&base);
        let (min, max) = match signed {
            true => (-(1i64 << (bits - 1)), (1i64 << (bits - 1)) - 1),
            false => (0, (1i64 << bits) - 1),
        };
        let lo = (sub.below(60) as i64 - if signed { 30 } else { 0 }).clamp(min, max);
        let hi = (lo + sub.below(80) as i64).min(max);
        (base, lo, hi)
    });
    let mut ranged: Vec<String> = Vec::new();
    if let Some((base, lo, hi)) = &subrange {
        let init = match sub.chance(25) {
            true => format!(" := {}", lo + sub.below((hi - lo + 1) as u64) as i64),
            false => String::new(),
        };
        text += &format!("TYPE\n  Rg0 : {base} ({lo}..{hi}){init};\nEND_TYPE\n\n");
        ranged = int_vars
            .iter()
            .filter(|(_, t)| t == base)
            .filter(|_| sub.chance(60))
            .map(|(n, _)| n.clone())
            .collect();
        let k = sub.below(20);
        let op = if sub.chance(50) { "+" } else { "-" };
        text += &format!(
            "FUNCTION_BLOCK Sb0\n  VAR_INPUT\n    X : Rg0;\n  END_VAR\n  VAR_OUTPUT\n    Y : {base};\n  END_VAR\n  Y := X {op} {k};\nEND_FUNCTION_BLOCK\n\n"
        );
        user_vars += "    Q0 : Sb0;\n";
        let mut f = Gen {
            rng: &mut sub,
            literals: 0,
            mods: 0,
            reads: g.reads.clone(),
            writes: Vec::new(),
            funcs: Vec::new(),
            ints: g.ints.clone(),
            int_writes: Vec::new(),
        };
        let x = f.iexpr(base, 1);
        let out = match ranged.is_empty() || f.rng.chance(20) {
            true => String::new(),
            false => format!(", Y => {}", f.rng.pick(&ranged)),
        };
        user_calls.push(format!("  Q0(X := {x}{out});\n"));
    }
    if g.rng.chance(35) {
        let mut f = Gen {
            rng: &mut *g.rng,
            literals: 0,
            mods: 0,
            reads: vec!["A".into(), "B".into(), "L".into()],
            writes: vec!["L".into(), "Fn0".into()],
            funcs: Vec::new(),
            ints: Vec::new(),
            int_writes: Vec::new(),
        };
        // Perhaps a declared EN (after A and B: the calls give them by position; FALSE
        // at first: the function runs only where a call gives EN) and ENO.
        let en_decl = match (en.chance(30), en.chance(25)) {
            (true, true) => "    EN : BOOL := FALSE;\n",
            (true, false) => "    EN : BOOL := TRUE;\n",
            _ => "",
        };
        let eno_decl =
            if en.chance(30) { "  VAR_OUTPUT\n    ENO : BOOL;\n  END_VAR\n" } else { "" };
        text += &format!(
            "FUNCTION Fn0 : BOOL\n  VAR_INPUT\n    A, B : BOOL;\n{en_decl}  END_VAR\n{eno_decl}  VAR\n    L : BOOL;\n  END_VAR\n"
        );
        text += &f.body("  ", 1);
        if !eno_decl.is_empty() || en.chance(20) {
            let (c, v) = (en.pick(&["A", "B", "L"]), en.pick(&["FALSE", "A", "NOT B"]));
            text += &format!("  IF {c} THEN\n    ENO := {v};\n  END_IF;\n");
        }
        text += &format!("  Fn0 := {};\nEND_FUNCTION\n\n", f.expr(2));
        g.funcs.push("Fn0".into());
    }
    if g.rng.chance(35) {
        let inner = *g.rng.pick(&["", "TON", "R_TRIG"]);
        let mut reads: Vec<String> =
            ["I0", "I1", "O0", "O1", "M"].iter().map(|s| s.to_string()).collect();
        if !inner.is_empty() {
            reads.push("K.Q".into());
        }
        let mut f = Gen {
            rng: &mut *g.rng,
            literals: 0,
            mods: 0,
            reads,
            writes: vec!["O0".into(), "O1".into(), "M".into()],
            funcs: g.funcs.clone(),
            ints: Vec::new(),
            int_writes: Vec::new(),
        };
        let init = if f.rng.chance(50) { " := TRUE" } else { "" };
        // Perhaps a declared EN (FALSE at first: an instance runs only once a call gives
        // it TRUE) and ENO, and a body that clears or sets ENO.
        let en_decl = match (en.chance(40), en.chance(25)) {
            (true, true) => "    EN : BOOL := FALSE;\n",
            (true, false) => "    EN : BOOL := TRUE;\n",
            _ => "",
        };
        let eno_decl = if en.chance(40) { "    ENO : BOOL;\n" } else { "" };
        let eno_write = !eno_decl.is_empty() || en.chance(20);
        text += &format!(
            "FUNCTION_BLOCK Fb0\n  VAR_INPUT\n{en_decl}    I0, I1 : BOOL;\n  END_VAR\n  VAR_OUTPUT\n{eno_decl}    O0, O1 : BOOL;\n  END_VAR\n"
        );
        // matiec reads no initial value in `VAR_TEMP` (as IEC 61131-3 writes it).
        let section = match temp.chance(35) {
            true if init.is_empty() => "VAR_TEMP",
            _ => "VAR",
        };
        text += &format!("  {section}\n    M : BOOL{init};\n  END_VAR\n");
        if !inner.is_empty() {
            text += &format!("  VAR\n    K : {inner};\n  END_VAR\n");
        }
        text += &f.body("  ", 1);
        match inner {
            "TON" => {
                text +=
                    &format!("  K(IN := {}, PT := T#{}ms);\n", f.expr(1), cycle_ms * f.rng.below(4))
            }
            "R_TRIG" => text += &format!("  K(CLK := {});\n", f.expr(1)),
            _ => {}
        }
        if f.rng.chance(30) {
            text += &format!("  IF {} THEN\n    RETURN;\n  END_IF;\n", f.expr(1));
        }
        text += &f.body("  ", 1);
        if eno_write {
            let (c, v) = (en.pick(&["I0", "I1", "M", "O0"]), en.pick(&["FALSE", "TRUE", "NOT I1"]));
            text += &format!("  IF {c} THEN\n    ENO := {v};\n  END_IF;\n");
        }
        text += "END_FUNCTION_BLOCK\n\n";
        for k in 0..1 + g.rng.below(2) {
            let u = format!("U{k}");
            user_vars += &format!("    {u} : Fb0;\n");
            g.reads.push(format!("{u}.O0"));
            g.reads.push(format!("{u}.O1"));
            user_bits.extend(["O0", "O1", "M"].iter().map(|v| format!("{u}_{v}")));
            if eno_write {
                user_bits.push(format!("{u}_ENO"));
            }
            let mut args = vec![format!("I0 := {}", g.expr(1))];
            if g.rng.chance(70) {
                args.push(format!("I1 := {}", g.expr(1)));
            }
            if g.rng.chance(40) {
                args.push(format!("O1 => {}", g.rng.pick(&locals)));
            }
            if en.chance(35) || en_decl.contains("FALSE") && en.chance(60) {
                args.insert(0, format!("EN := {}", en.pick(&g.reads)));
            }
            if en.chance(40) {
                args.push(format!("ENO => {}", en.pick(&locals)));
            }
            user_calls.push(format!("  {u}({});\n", args.join(", ")));
        }
    }
    text += "PROGRAM Random\n  VAR_INPUT\n";
    for i in &inputs {
        text += &format!("    {i} : BOOL;\n");
    }
    text += &int_input_decl;
    text += "  END_VAR\n  VAR\n";
    for (n, t) in &int_vars {
        let init = if g.rng.chance(30) { format!(" := {}", g.literal(t)) } else { String::new() };
        let t = if ranged.contains(n) { "Rg0" } else { t };
        text += &format!("    {n} : {t}{init};\n");
    }
    if let Some((c, t)) = &counter {
        text += &format!("    {c} : {t};\n");
    }
    if pulse {
        text += "    P0 : TP;\n";
    }
    let mut temps = String::new();
    for b in &locals {
        let init = if g.rng.chance(30) { " := TRUE" } else { "" };
        match temp.chance(15) {
            true => temps += &format!("    {b} : BOOL;\n"),
            false => text += &format!("    {b} : BOOL{init};\n"),
        }
    }
    for (n, t) in &fbs {
        text += &format!("    {n} : {t};\n");
    }
    text += "    i : INT;\n";
    text += &user_vars;
    text += "  END_VAR\n";
    if !temps.is_empty() {
        text += &format!("  VAR_TEMP\n{temps}  END_VAR\n");
    }
    // The calls, placed among the other statements.
    let mut pts: Vec<(String, String)> = Vec::new();
    let mut conditional: Vec<String> = Vec::new();
    let mut counted = 0;
    let mut calls: Vec<String> = fbs
        .iter()
        .map(|(n, t)| {
            let call = match *t {
                "TON" | "TOF" => {
                    let pt = g.rng.below(6) * cycle_ms * 1000 + g.rng.below(3) * 700;
                    let pt = format!("T#{}ms", ms(pt));
                    // A call that leaves PT out: T#0s, as no call gives it.
                    match own.chance(20) {
                        true => format!("{n}(IN := {})", g.expr(2)),
                        false => {
                            pts.push((n.clone(), pt.clone()));
                            format!("{n}(IN := {}, PT := {pt})", g.expr(2))
                        }
                    }
                }
                "R_TRIG" | "F_TRIG" => format!("{n}(CLK := {})", g.expr(2)),
                "SR" => format!("{n}(S1 := {}, R := {})", g.expr(2), g.expr(2)),
                _ => format!("{n}(S := {}, R1 := {})", g.expr(2), g.expr(2)),
            };
            // Every fifth call gives EN (which the instance keeps: its later calls run
            // under it too), every tenth copies ENO; chosen by a count, so that the
            // draws are those of the programs checked before.
            counted += 1;
            let call = match counted % 5 {
                0 => {
                    let en = &g.reads[counted % g.reads.len()];
                    let eno = if counted % 10 == 0 {
                        format!(", ENO => {}", locals[counted % locals.len()])
                    } else {
                        String::new()
                    };
                    let args = &call[n.len() + 1..call.len() - 1];
                    format!("{n}(EN := {en}, {args}{eno})")
                }
                _ => call,
            };
            let line = if g.rng.chance(30) {
                let x = g.rng.pick(&locals).clone();
                let not = if negated_outputs && g.rng.chance(30) { "NOT " } else { "" };
                let pin = out_pin(t);
                format!("  {}, {not}{pin} => {x});\n", call.strip_suffix(")").unwrap_or(&call))
            } else {
                format!("  {call};\n")
            };
            // A timer or edge detector called under a condition: it runs only then.
            if matches!(*t, "TON" | "TOF" | "R_TRIG" | "F_TRIG") && own.chance(25) {
                conditional.push(n.clone());
                let not = if own.chance(50) { "NOT " } else { "" };
                format!("  IF {not}{} THEN\n  {line}  END_IF;\n", own.pick(&g.reads))
            } else {
                line
            }
        })
        .collect();
    // Second calls of some instances, later in the scan, each input left out keeping the
    // value the first call gave; a timer's perhaps under a condition, as a timer that
    // resets itself (`IF T0.Q THEN T0(IN := FALSE)`).
    for (n, t) in &fbs {
        if matches!(*t, "TON" | "TOF") && own.chance(35) {
            let given = pts.iter().find(|(m, _)| m == n).map(|(_, pt)| pt);
            // A call that leaves PT out after a first call under a condition keeps T#0s
            // or the first call's: the timer is not computed.
            let must = conditional.contains(n);
            let pt = match given {
                Some(pt) if must || own.chance(30) => format!(", PT := {pt}"),
                _ => String::new(),
            };
            let value = if own.chance(30) {
                format!("NOT {}", own.pick(&g.reads))
            } else {
                own.pick(&g.reads).clone()
            };
            let (stop, q) = if *t == "TON" { ("FALSE", "") } else { ("TRUE", "NOT ") };
            conditional.push(n.clone());
            calls.push(match own.below(4) {
                0 => format!("  IF {q}{n}.Q THEN\n    {n}(IN := {stop}{pt});\n  END_IF;\n"),
                1 => format!("  {n}(IN := {value}{pt});\n"),
                2 => {
                    let c = own.pick(&g.reads).clone();
                    format!("  IF {c} THEN\n    {n}(IN := {value}{pt});\n  END_IF;\n")
                }
                _ => format!("  {n}({});\n", pt.trim_start_matches(", ")),
            });
            continue;
        }
        if matches!(*t, "TON" | "TOF") || !own.chance(25) {
            continue;
        }
        let pins: &[&str] = match *t {
            "SR" => &["S1", "R"],
            "RS" => &["S", "R1"],
            _ => &["CLK"],
        };
        let mut given = Vec::new();
        for p in pins {
            if own.chance(40) {
                given.push(format!("{p} := {}", own.pick(&g.reads)));
            }
        }
        calls.push(format!("  {n}({});\n", given.join(", ")));
    }
    calls.extend(user_calls);
    if let Some((c, t)) = &counter {
        let literal = g.rng.chance(70);
        let pv = if literal { g.rng.below(5).to_string() } else { g.iexpr("INT", 1) };
        let mut args = Vec::new();
        if *t != "CTD" {
            args.push(format!("CU := {}", g.expr(1)));
        }
        if *t != "CTU" {
            args.push(format!("CD := {}", g.expr(1)));
        }
        if *t != "CTD" && g.rng.chance(70) {
            args.push(format!("R := {}", g.expr(1)));
        }
        if *t != "CTU" && g.rng.chance(70) {
            args.push(format!("LD := {}", g.expr(1)));
        }
        args.push(format!("PV := {pv}"));
        let ints: Vec<String> =
            int_vars.iter().filter(|(_, u)| u == "INT").map(|(n, _)| n.clone()).collect();
        if !ints.is_empty() && g.rng.chance(40) {
            args.push(format!("CV => {}", g.rng.pick(&ints)));
        }
        calls.push(format!("  {c}({});\n", args.join(", ")));
        // A second call giving one counting input: the others and PV kept (a literal: a
        // kept expression of the count doubles the count's circuit, and the test's time).
        if literal && own.chance(25) {
            let pin = if *t == "CTD" { "CD" } else { "CU" };
            calls.push(format!("  {c}({pin} := {});\n", own.pick(&g.reads)));
        }
    }
    let mut pulse_pt = false;
    if pulse {
        let pt = g.rng.below(6) * cycle_ms * 1000 + g.rng.below(3) * 700;
        match own.chance(20) {
            true => calls.push(format!("  P0(IN := {});\n", g.expr(1))),
            false => {
                pulse_pt = true;
                calls.push(format!("  P0(IN := {}, PT := T#{}ms);\n", g.expr(1), ms(pt)))
            }
        }
        // In half the programs a second call, PT left out (the one given kept): the pulse
        // is then followed call by call.
        if pulse_pt && seed.is_multiple_of(2) {
            calls.push(format!("  P0(IN := {});\n", own.pick(&g.reads)));
        }
    }
    // Reads of the elapsed time of the timers whose first call gives a preset (called
    // once at every scan, or also under a condition or a second time), among the calls
    // (before a call: the last scan's value): compared with a duration, or whole seconds
    // into an integer. (A timer called once at every scan without a preset has its
    // elapsed time not computed.)
    let mut timers: Vec<String> = fbs
        .iter()
        .filter(|(_, t)| matches!(*t, "TON" | "TOF"))
        .filter(|(n, _)| pts.iter().any(|(m, _)| m == n))
        .map(|(n, _)| n.clone())
        .collect();
    if pulse_pt {
        timers.push("P0".into());
    }
    for n in &timers {
        if !own.chance(40) {
            continue;
        }
        let ms = own.below(7) * cycle_ms / 2 + own.below(2) * 350;
        let op = *own.pick(&[">=", ">", "<", "<=", "=", "<>"]);
        let x = own.pick(&locals).clone();
        let read = match own.below(4) {
            0 => format!("{x} := {n}.ET {op} T#{ms}ms;"),
            1 => format!("{x} := {} AND T#{ms}ms {op} {n}.ET;", own.pick(&g.reads)),
            2 => format!("IF {n}.ET {op} T#{ms}ms THEN {x} := NOT {x}; END_IF;"),
            _ => {
                let ints: Vec<&String> = int_vars
                    .iter()
                    .filter(|(_, t)| matches!(t.as_str(), "INT" | "DINT" | "SINT"))
                    .map(|(v, _)| v)
                    .collect();
                match ints.is_empty() {
                    true => format!("{x} := MAX({n}.ET, T#{ms}ms) = {n}.ET;"),
                    false => {
                        let v = own.pick(&ints);
                        let t = &int_vars.iter().find(|(w, _)| w == *v).map_or("INT", |(_, t)| t);
                        format!("{v} := TIME_TO_{t}({n}.ET);")
                    }
                }
            }
        };
        let at = own.below(calls.len() as u64 + 1) as usize;
        calls.insert(at, format!("  {read}\n"));
    }
    let n_stmts = 3 + g.rng.below(7);
    for _ in 0..n_stmts {
        if !calls.is_empty() && g.rng.chance(30) {
            text += &calls.remove(0);
        } else if g.rng.chance(25) {
            text += &g.choice("  ", 1);
        } else if g.rng.chance(8) {
            // A loop with constant bounds (unrolled).
            // Not of one iteration: matiec runs those zero times, IEC once (refused).
            let mut from = g.rng.below(3);
            let to = from + 1 + g.rng.below(2);
            if g.rng.chance(15) {
                from = to + 1; // no iteration
            }
            let body = if g.rng.chance(50) { g.loop_body("    ") } else { g.body("    ", 1) };
            text += &format!("  FOR i := {from} TO {to} DO\n{body}  END_FOR;\n");
        } else if g.rng.chance(8) {
            text += &g.counted_loop("  ");
        } else {
            text += &g.assign("  ");
        }
        if g.rng.chance(10) {
            text += "  (* a comment *)\n";
        }
    }
    for c in calls {
        text += &c;
    }
    text +=
        &super::st_gen_en::function_calls(&mut en, &inputs, &locals, &int_vars, &ranged, &g.funcs);
    // A RETURN after the calls (a call it may skip would be a timer run on some scans).
    if g.rng.chance(20) {
        text += &format!("  IF {} THEN\n    RETURN;\n  END_IF;\n", g.expr(1));
        text += &g.body("  ", 1);
    }
    text += "END_PROGRAM\n\n";
    text += &format!(
        "CONFIGURATION Config\n  RESOURCE Res ON PLC\n    TASK Cyclic (INTERVAL := T#{cycle_ms}ms, PRIORITY := 1);\n    PROGRAM Main WITH Cyclic : Random;\n  END_RESOURCE\nEND_CONFIGURATION\n"
    );
    let mut bits = locals;
    bits.extend(fbs.iter().map(|(n, t)| format!("{n}_{}", out_pin(t))));
    bits.extend(user_bits);
    if let Some((c, t)) = &counter {
        match *t {
            "CTUD" => bits.extend([format!("{c}_QU"), format!("{c}_QD")]),
            _ => bits.push(format!("{c}_Q")),
        }
    }
    if pulse {
        bits.push("P0_Q".into());
    }
    let mut ints = int_vars;
    if let Some((c, _)) = &counter {
        ints.push((format!("{c}.CV"), "INT".into()));
    }
    Generated {
        text,
        pou: "Random".into(),
        inputs,
        bits,
        cycle_us: cycle_ms * 1000,
        ints,
        int_inputs,
    }
}

/// Random values of the program's inputs for `scans` scans, each held for 1 to 12 scans.
pub fn schedule(
    g: &Generated,
    seed: u64,
    scans: usize,
) -> Vec<std::collections::BTreeMap<String, bool>> {
    let mut names = g.inputs.clone();
    for (x, bits) in &g.int_inputs {
        names.extend((0..*bits).map(|k| format!("{x}_b{k}")));
    }
    schedule_of(&names, seed, scans)
}

/// Random values of `inputs` for `scans` scans, each held for 1 to 12 scans.
pub fn schedule_of(
    inputs: &[String],
    seed: u64,
    scans: usize,
) -> Vec<std::collections::BTreeMap<String, bool>> {
    let mut rng = Rng::new(seed ^ 0x0AC1E);
    let mut held: std::collections::BTreeMap<String, (bool, u64)> =
        std::collections::BTreeMap::new();
    (0..scans)
        .map(|_| {
            inputs
                .iter()
                .map(|n| {
                    let e = held.entry(n.clone()).or_insert((false, 0));
                    if e.1 == 0 {
                        *e = (rng.chance(50), 1 + rng.below(12));
                    }
                    e.1 -= 1;
                    (n.clone(), e.0)
                })
                .collect()
        })
        .collect()
}

/// `us` µs in milliseconds as a literal's number (`2.7`, `15`).
fn ms(us: u64) -> String {
    match us % 1000 {
        0 => format!("{}", us / 1000),
        f => format!("{}.{}", us / 1000, format!("{f:03}").trim_end_matches('0')),
    }
}
