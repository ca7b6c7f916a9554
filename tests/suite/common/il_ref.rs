//! A reference interpreter of the generated Instruction List programs (`il_gen.rs`), written from IEC 61131-3's description of IL (one current result; `S`/`R` act when it is TRUE; `( … )` computes an operand; jumps and returns by the current result; `INT_TO_BOOL` TRUE when the integer is not 0, as matiec's `iec_std_functions.h` has it) and matiec's library (`lib/timer.txt`, `edge_detection.txt`, `bistable.txt`; an instance keeps each input, `PT` included, from the last call that gave it) with the clock at scan × cycle — not from the lowering it checks.
#![allow(dead_code)]

use std::collections::BTreeMap;

use super::il_gen::{Arith, Cmp, Generated, Ins, IntOperand, Logic, Operand, When};

/// A function block's state.
#[derive(Clone, Debug, Default)]
struct FbState {
    q: bool,
    /// TON/TOF: 0 reset, 1 counting, 2 set.
    state: u8,
    prev_in: bool,
    start: u64,
    /// R_TRIG/F_TRIG memory.
    m: bool,
    /// The inputs as the last call that gave each left them (FALSE before).
    inputs: BTreeMap<String, bool>,
    /// `PT` as the last call that gave it left it, in µs (T#0s before).
    pt: u64,
}

/// The interpreter.
pub struct IlRef<'g> {
    g: &'g Generated,
    vars: BTreeMap<String, bool>,
    /// The `INT` variables.
    ints: BTreeMap<String, i64>,
    fbs: BTreeMap<String, FbState>,
    scan: u64,
}

impl<'g> IlRef<'g> {
    /// Every variable at its initial value.
    pub fn new(g: &'g Generated) -> IlRef<'g> {
        let mut vars = BTreeMap::new();
        for i in &g.inputs {
            vars.insert(i.clone(), false);
        }
        for (b, init) in &g.locals {
            vars.insert(b.clone(), *init);
        }
        let fbs = g.fbs.iter().map(|(n, _)| (n.clone(), FbState::default())).collect();
        let ints = g.ints.iter().cloned().collect();
        IlRef { g, vars, ints, fbs, scan: 0 }
    }

    /// An `INT` variable's value.
    pub fn int(&self, name: &str) -> i64 {
        self.ints[name]
    }

    fn int_read(&self, o: &IntOperand) -> i64 {
        match o {
            IntOperand::Var(v) => self.ints[v],
            IntOperand::Lit(k) => *k,
        }
    }

    fn read(&self, o: &Operand) -> bool {
        match o {
            Operand::Lit(b) => *b,
            Operand::Var(v) => match v.split_once('.') {
                Some((inst, _)) => self.fbs[inst].q,
                None => self.vars[v],
            },
        }
    }

    fn apply(cr: bool, l: Logic, neg: bool, v: bool) -> bool {
        let v = v != neg;
        match l {
            Logic::And => cr && v,
            Logic::Or => cr || v,
            Logic::Xor => cr != v,
            Logic::Eq => cr == v,
            Logic::Ne => cr != v,
        }
    }

    /// One scan with these inputs.
    pub fn step(&mut self, inputs: &BTreeMap<String, bool>) {
        for (k, v) in inputs {
            self.vars.insert(k.clone(), *v);
        }
        let now = self.scan * self.g.cycle_us;
        let ins = &self.g.ins;
        let mut cr = false;
        // The current result while it is an INT (matiec's C keeps it in an `INT` field:
        // `CR += x` wraps to 16 bits at each instruction).
        let mut int_cr: i64 = 0;
        let mut pc = 0;
        while pc < ins.len() {
            match &ins[pc] {
                Ins::Ld(n, o) => cr = self.read(o) != *n,
                Ins::Op(l, n, o) => cr = Self::apply(cr, *l, *n, self.read(o)),
                Ins::Nested(l, n, first, inner) => {
                    let mut v = self.read(first);
                    for (il, ineg, o) in inner {
                        v = Self::apply(v, *il, *ineg, self.read(o));
                    }
                    cr = Self::apply(cr, *l, *n, v);
                }
                Ins::Not => cr = !cr,
                Ins::St(n, x) => {
                    self.vars.insert(x.clone(), cr != *n);
                }
                Ins::Set(x) => {
                    if cr {
                        self.vars.insert(x.clone(), true);
                    }
                }
                Ins::Reset(x) => {
                    if cr {
                        self.vars.insert(x.clone(), false);
                    }
                }
                Ins::Jump(w, l) => {
                    let go = match w {
                        When::Always => true,
                        When::True => cr,
                        When::False => !cr,
                    };
                    if go {
                        pc = ins
                            .iter()
                            .position(|i| matches!(i, Ins::Label(m) if m == l))
                            .expect("generated labels exist");
                        continue;
                    }
                }
                Ins::Label(_) => {}
                Ins::Ret(w) => {
                    let go = match w {
                        When::Always => true,
                        When::True => cr,
                        When::False => !cr,
                    };
                    if go {
                        break;
                    }
                }
                Ins::Cal(inst, ty, args, pt, _) => {
                    let vals: BTreeMap<&str, bool> =
                        args.iter().map(|(p, n, o)| (p.as_str(), self.read(o) != *n)).collect();
                    self.call(inst, ty, &vals, *pt, now);
                }
                Ins::LdInt(n) => int_cr = self.ints[n],
                Ins::Arith(a, o) => {
                    let x = self.int_read(o);
                    let v = match a {
                        Arith::Add => int_cr + x,
                        Arith::Sub => int_cr - x,
                        Arith::Mul => int_cr * x,
                        Arith::Div => int_cr / x,
                        Arith::Mod => int_cr % x,
                    };
                    int_cr = i64::from(v as i16);
                }
                Ins::Compare(c, o) => {
                    let x = self.int_read(o);
                    cr = match c {
                        Cmp::Gt => int_cr > x,
                        Cmp::Ge => int_cr >= x,
                        Cmp::Eq => int_cr == x,
                        Cmp::Ne => int_cr != x,
                        Cmp::Lt => int_cr < x,
                        Cmp::Le => int_cr <= x,
                    };
                }
                Ins::StInt(n) => {
                    self.ints.insert(n.clone(), int_cr);
                }
                // matiec's `<T>_TO_BOOL` (`iec_std_functions.h`): `op == 0 ? 0 : 1`.
                Ins::ToBool(_) => cr = int_cr != 0,
                Ins::FbIn(pin, inst) => {
                    let ty = self.g.fbs.iter().find(|(n, _)| n == inst).map(|(_, t)| t.clone());
                    let vals = BTreeMap::from([(pin.as_str(), cr)]);
                    self.call(inst, ty.as_deref().unwrap_or(""), &vals, None, now);
                }
            }
            pc += 1;
        }
        self.scan += 1;
    }

    /// A call giving the inputs `vals` and the preset `pt` (`None`: left out); an FB
    /// instance keeps each input from the last call that gave it.
    fn call(
        &mut self,
        inst: &str,
        ty: &str,
        vals: &BTreeMap<&str, bool>,
        pt: Option<u64>,
        now: u64,
    ) {
        let f = self.fbs.get_mut(inst).expect("declared instance");
        for (pin, v) in vals {
            f.inputs.insert(pin.to_string(), *v);
        }
        if let Some(pt) = pt {
            f.pt = pt;
        }
        let vals: BTreeMap<&str, bool> = ["IN", "CLK", "S1", "R", "S", "R1"]
            .into_iter()
            .map(|p| (p, f.inputs.get(p).copied().unwrap_or(false)))
            .collect();
        let pt = f.pt;
        match ty {
            "TON" => {
                let input = vals["IN"];
                if f.state == 0 && !f.prev_in && input {
                    f.state = 1;
                    f.q = false;
                    f.start = now;
                } else if !input {
                    f.q = false;
                    f.state = 0;
                } else if f.state == 1 && f.start + pt <= now {
                    f.state = 2;
                    f.q = true;
                }
                f.prev_in = input;
            }
            "TOF" => {
                let input = vals["IN"];
                if f.state == 0 && f.prev_in && !input {
                    f.state = 1;
                    f.start = now;
                } else if input {
                    f.state = 0;
                } else if f.state == 1 && f.start + pt <= now {
                    f.state = 2;
                }
                f.q = input || f.state == 1;
                f.prev_in = input;
            }
            "R_TRIG" => {
                let clk = vals["CLK"];
                f.q = clk && !f.m;
                f.m = clk;
            }
            "F_TRIG" => {
                let clk = vals["CLK"];
                f.q = !clk && !f.m;
                f.m = !clk;
            }
            "SR" => f.q = vals["S1"] || (!vals["R"] && f.q),
            "RS" => f.q = !vals["R1"] && (vals["S"] || f.q),
            _ => panic!("no function block type {ty}"),
        }
    }

    /// A bit as the lowering names it: a variable, or `T0_Q` for an FB output.
    pub fn bit(&self, name: &str) -> bool {
        match self.vars.get(name) {
            Some(v) => *v,
            None => {
                let inst = name.rsplit_once('_').map_or(name, |(i, _)| i);
                self.fbs[inst].q
            }
        }
    }
}
