//! Random Structured Text programs over `REAL` values, for the tests against matiec and of the compiled equations: `REAL` inputs and variables (initial values given or not), real literals plain (C `double`s) and typed (`REAL#…`), `+ - * /` (values the C computes in `double`, `INT_TO_REAL(N) * 0.1` among them), unary `-`, comparisons, `INT_TO_REAL`, `REAL_TO_INT` of a `LIMIT`ed value, `MIN`/`MAX`/`LIMIT`/`ABS`/`SEL`/`MOVE` and `ADD`/`SUB`/`MUL`/`DIV`, an `IF` on a comparison.
#![allow(dead_code)]

use super::rng::Rng;

/// A random program (of the ST generator's shape: its `REAL` inputs are found from the
/// text by [`schedule`]).
pub use super::st_gen::Generated;

/// Literals a `float` holds and some it does not (`0.1`), large, small and subnormal.
const LITERALS: [&str; 16] = [
    "0.0",
    "1.0",
    "2.5",
    "0.5",
    "10.0",
    "50.0",
    "100.0",
    "0.1",
    "0.3",
    "1.0E3",
    "3.0E38",
    "1.0E-40",
    "65535.0",
    "16777217.0",
    "1.5E-5",
    "7.25",
];

/// Literals no `float` holds: compared with a `float` as C does, in `double`.
const BETWEEN: [&str; 6] = ["0.1", "0.3", "0.2", "1.1", "16777217.0", "1.0E-50"];

struct Gen<'r> {
    rng: &'r mut Rng,
    /// `REAL` variables and inputs to read.
    reals: Vec<String>,
    /// `INT` variables and inputs to read.
    ints: Vec<String>,
    /// BOOL variables to read.
    bools: Vec<String>,
    /// How many `ABS` or `SQRT` were written (they alternate).
    absolutes: usize,
}

impl Gen<'_> {
    fn literal(&mut self) -> String {
        let l = *self.rng.pick(&LITERALS);
        match self.rng.below(4) {
            0 => format!("REAL#{l}"),
            _ => l.to_string(),
        }
    }

    /// A `REAL` expression.
    fn real(&mut self, depth: u32) -> String {
        if depth == 0 || self.rng.chance(25) {
            return match self.rng.below(6) {
                0 | 1 => self.literal(),
                2 if !self.ints.is_empty() => {
                    format!("INT_TO_REAL({})", self.rng.pick(&self.ints).clone())
                }
                _ => self.rng.pick(&self.reals).clone(),
            };
        }
        let d = depth - 1;
        match self.rng.below(11) {
            0..=3 => {
                let op = *self.rng.pick(&["+", "-", "*", "/"]);
                format!("({} {op} {})", self.real(d), self.real(d))
            }
            4 if self.rng.chance(10) && !self.ints.is_empty() => {
                // A raw reading scaled by a literal no `float` holds: computed in
                // `double` by the C, rounded where stored, compared in `double`.
                let n = self.rng.pick(&self.ints).clone();
                let k = *self.rng.pick(&["0.1", "0.01", "0.3"]);
                format!("(INT_TO_REAL({n}) * {k})")
            }
            4 => format!("-({})", self.real(d)),
            5 => {
                let f = *self.rng.pick(&["MIN", "MAX"]);
                format!("{f}({}, {})", self.real(d), self.real(d))
            }
            6 => format!("LIMIT({}, {}, {})", self.real(d), self.real(d), self.real(d)),
            // Every other one a root (counted, not drawn: the draws stay those of
            // the programs before roots were generated).
            7 => {
                self.absolutes += 1;
                let f = if self.absolutes.is_multiple_of(2) { "SQRT" } else { "ABS" };
                format!("{f}({})", self.real(d))
            }
            8 => format!("SEL({}, {}, {})", self.boolean(d), self.real(d), self.real(d)),
            9 => {
                let f = *self.rng.pick(&["ADD", "SUB", "MUL", "DIV", "MOVE"]);
                if f == "MOVE" {
                    format!("MOVE({})", self.real(d))
                } else {
                    format!("{f}({}, {})", self.real(d), self.real(d))
                }
            }
            _ => format!("({})", self.real(d)),
        }
    }

    /// A BOOL expression: mostly a comparison of `REAL`s.
    fn boolean(&mut self, depth: u32) -> String {
        if self.rng.chance(15) && !self.bools.is_empty() {
            return self.rng.pick(&self.bools).clone();
        }
        // A variable against a literal: where a `float` meets a `double` literal.
        if self.rng.chance(40) {
            let op = *self.rng.pick(&["<", "<=", ">", ">=", "=", "<>"]);
            let x = self.rng.pick(&self.reals).clone();
            let k = if self.rng.chance(60) {
                self.rng.pick(&BETWEEN).to_string()
            } else {
                self.literal()
            };
            return format!("{x} {op} {k}");
        }
        let op = *self.rng.pick(&["<", "<=", ">", ">=", "=", "<>"]);
        let d = depth.min(2);
        let b = if self.rng.chance(50) { self.literal() } else { self.real(d) };
        format!("{} {op} {b}", self.real(d))
    }
}

/// The random program of `seed`.
pub fn program(seed: u64) -> Generated {
    let mut rng = Rng::new(seed ^ 0x2EA1);
    let n_in = 1 + rng.below(3) as usize;
    let n_vars = 1 + rng.below(3) as usize;
    let n_bits = 1 + rng.below(3) as usize;
    let inputs = vec!["Go".to_string()];
    let mut text = String::from("PROGRAM Random\nVAR_INPUT\n  Go : BOOL;\n  N : INT;\n");
    let real_inputs: Vec<String> = (0..n_in).map(|k| format!("A{k}")).collect();
    for a in &real_inputs {
        text += &format!("  {a} : REAL;\n");
    }
    text += "END_VAR\nVAR\n";
    let vars: Vec<String> = (0..n_vars).map(|k| format!("X{k}")).collect();
    let bits: Vec<String> = (0..n_bits).map(|k| format!("B{k}")).collect();
    for x in &vars {
        match rng.below(3) {
            0 => text += &format!("  {x} : REAL;\n"),
            _ => text += &format!("  {x} : REAL := {};\n", rng.pick(&LITERALS)),
        }
    }
    for b in &bits {
        text += &format!("  {b} : BOOL;\n");
    }
    text += "  R : INT;\nEND_VAR\n";
    let mut reals = real_inputs.clone();
    reals.extend(vars.iter().cloned());
    let ints = vec!["N".into(), "R".into()];
    let mut g = Gen { rng: &mut rng, reals, ints, bools: vec![], absolutes: 0 };
    for _ in 0..(2 + g.rng.below(5)) {
        match g.rng.below(6) {
            0 | 1 => {
                let x = g.rng.pick(&vars).clone();
                text += &format!("  {x} := {};\n", g.real(3));
            }
            2 | 3 => {
                let b = g.rng.pick(&bits).clone();
                text += &format!("  {b} := {};\n", g.boolean(2));
                g.bools.push(b);
            }
            4 => {
                let x = g.rng.pick(&vars).clone();
                text += &format!("  R := REAL_TO_INT(LIMIT(-1000.0, {}, 1000.0));\n", g.real(2));
                text += &format!("  {x} := INT_TO_REAL(R) * 0.5;\n");
            }
            _ => {
                let (c, x) = (g.boolean(1), g.rng.pick(&vars).clone());
                text += &format!("  IF Go AND {c} THEN\n    {x} := {};\n  END_IF;\n", g.real(2));
            }
        }
    }
    text += "END_PROGRAM\n\n";
    text += "CONFIGURATION Config\n  RESOURCE Res ON PLC\n    TASK Cyclic (INTERVAL := T#10ms, PRIORITY := 1);\n    PROGRAM Main WITH Cyclic : Random;\n  END_RESOURCE\nEND_CONFIGURATION\n";
    let pou = "Random".into();
    Generated { text, pou, inputs, bits, cycle_us: 10_000, ints: vec![], int_inputs: vec![] }
}

/// Values a `REAL` input takes, as stored (bit patterns): numbers around the literals,
/// zeros, infinities, NaN, subnormals and random patterns.
pub fn real_value(rng: &mut Rng) -> i64 {
    let x: f32 = match rng.below(12) {
        // A literal's own `float` (or its neighbour): where comparisons with `double`
        // literals decide.
        4..=7 => {
            let l: f64 = match rng.chance(50) {
                true => rng.pick(&BETWEEN).parse().unwrap_or(0.0),
                false => rng.pick(&LITERALS).parse().unwrap_or(0.0),
            };
            let f = l as f32;
            *rng.pick(&[f, f, f.next_up(), f.next_down(), -f])
        }
        0 => f32::from_bits(rng.next() as u32),
        1 => *rng.pick(&[0.0, -0.0, f32::INFINITY, f32::NEG_INFINITY, f32::NAN, f32::MAX]),
        2 => *rng.pick(&[f32::from_bits(1), f32::MIN_POSITIVE, 0.1, 0.3, 1e-40, 3e38]),
        3 => (rng.below(2001) as f32 - 1000.0) / 10.0,
        _ => rng.below(201) as f32 - 100.0,
    };
    i64::from(x.to_bits())
}

/// Random values of the program's inputs for `scans` scans, each held for 1 to 12 scans:
/// `Go`, and the bits (`A0_b0` …) of the `REAL` inputs ([`real_value`]) and of `N`.
pub fn schedule(
    g: &Generated,
    seed: u64,
    scans: usize,
) -> Vec<std::collections::BTreeMap<String, bool>> {
    let mut rng = Rng::new(seed ^ 0x5CED);
    let numbers: Vec<(String, u32)> = g
        .text
        .lines()
        .filter_map(|l| l.trim().strip_suffix(" : REAL;").map(|a| (a.to_string(), 32)))
        .filter(|(a, _)| a.starts_with('A'))
        .chain([("N".to_string(), 16)])
        .collect();
    let mut held: Vec<(i64, u64)> = vec![(0, 0); numbers.len() + 1];
    (0..scans)
        .map(|_| {
            let mut step = std::collections::BTreeMap::new();
            for (k, h) in held.iter_mut().enumerate() {
                if h.1 == 0 {
                    let v = match numbers.get(k) {
                        Some((_, 32)) => real_value(&mut rng),
                        Some(_) => rng.below(2001) as i64 - 1000,
                        None => i64::from(rng.chance(50)),
                    };
                    *h = (v, 1 + rng.below(12));
                }
                h.1 -= 1;
                match numbers.get(k) {
                    Some((n, bits)) => {
                        for b in 0..*bits {
                            step.insert(format!("{n}_b{b}"), h.0 >> b & 1 == 1);
                        }
                    }
                    None => {
                        step.insert("Go".to_string(), h.0 == 1);
                    }
                }
            }
            step
        })
        .collect()
}
