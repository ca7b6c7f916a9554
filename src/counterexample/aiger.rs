//! AIGER export of a compiled program and its properties: the scan model as an and-inverter graph with latches, each property a bad-state output, for hardware model checkers (ABC `pdr`, `int`).
//!
//! # Encoding
//!
//! One AIGER step is one scan, read exactly as [`unroll`](super::unroll) reads the
//! model's equations (`shared/spec/semantics.md`, "Programs, scan by scan"):
//!
//! * a name no equation defines (an input, the output of an element the algebra
//!   cannot express) is an AIGER input, free at every scan;
//! * the equations are evaluated in scan order; `·`, `+`, `¬` are gates;
//! * `pre f` is a latch holding `f` from the previous scan; before the first scan it
//!   holds `f`'s initial value ([`initial_values`]: names, timers, memories 0, the
//!   Boolean operators applied). AIGER latches start at 0, so a latch whose initial
//!   value is 1 stores the complement;
//! * `SR(s, r)` and `RS(s, r)` are a latch each with their scan recurrences;
//! * `d/f` with `d = n` scans (`n > 0`) is a binary counter of the consecutive scans of
//!   `f` saturating at `n` (on when `f` is on and the count was `n`); `f/d` a counter
//!   loaded with `n` while `f` is on and counting down otherwise (on when `f` is on or
//!   the count was not 0); `n = 0` is `f` itself. A delay that is not a whole number of
//!   scans has no single scan reading and is refused.
//!
//! A property `lhs rel rhs` of a file with `assume` statements fails at a scan when it
//! is violated there and every assumption of its file has held at every scan up to and
//! including it (one latch per file remembers that an assumption was once broken): its
//! output is 1 exactly at the scans where ii-prove's verdict "refuted" needs a run to
//! reach. The outputs are old-style AIGER outputs, which ABC and the HWMCC tools read
//! as bad-state properties; the symbol table names each (`o3 P2`).
#![warn(missing_docs)]

use std::collections::{BTreeMap, HashMap};

use super::unroll::{Model, needed_now, violated};
use crate::kernel::Rel;
use crate::semantics::{Assignment, Time, eval_delay};
use crate::syntax::{Notation, term_to_string};
use crate::term::{Expr, Id, Term, initial_values, subterm};

/// A literal of the graph under construction: `2 · node + complemented`, node 0 the
/// constant false.
type Lit = u32;

const FALSE: Lit = 0;
const TRUE: Lit = 1;

/// A node of the graph under construction.
#[derive(Clone, Copy, Debug)]
enum Node {
    False,
    Input(usize),
    Latch(usize),
    And(Lit, Lit),
}

/// An and-inverter graph with latches, inputs and outputs: what [`encode`] builds.
#[derive(Clone, Debug, Default)]
pub struct Aig {
    nodes: Vec<Node>,
    strash: HashMap<(Lit, Lit), Lit>,
    /// Input names, in AIGER order.
    inputs: Vec<String>,
    /// Per latch: its name and next-state literal (set once the scan is built).
    latches: Vec<(String, Lit)>,
    /// Per output: its name and literal.
    outputs: Vec<(String, Lit)>,
    /// Comment lines.
    comments: Vec<String>,
}

/// One property to export: a relation that must hold at every scan, with the group of
/// assumptions (one per property file) that its runs must satisfy.
#[derive(Clone, Debug)]
pub struct Property {
    /// Its name (the `o` symbol).
    pub name: String,
    /// Left side.
    pub lhs: Expr,
    /// `=` or `⇒`.
    pub rel: Rel,
    /// Right side.
    pub rhs: Expr,
    /// Index into the assumption groups given to [`encode`].
    pub group: usize,
}

/// Why a model cannot be encoded exactly: the message, and the property whose terms
/// caused it (`None`: the program or an assumption).
#[derive(Clone, Debug)]
pub struct EncodeError {
    /// Index of the property, when one of its sides is the cause.
    pub property: Option<usize>,
    /// What cannot be encoded.
    pub message: String,
}

impl Aig {
    /// An empty graph: only the constant.
    fn new() -> Aig {
        Aig { nodes: vec![Node::False], ..Aig::default() }
    }

    fn node(&mut self, n: Node) -> Lit {
        self.nodes.push(n);
        2 * (self.nodes.len() as Lit - 1)
    }

    fn input(&mut self, name: &str) -> Lit {
        self.inputs.push(name.to_string());
        self.node(Node::Input(self.inputs.len() - 1))
    }

    /// A new latch (its next state [`FALSE`] until [`set_next`](Self::set_next)).
    fn latch(&mut self, name: String) -> Lit {
        self.latches.push((name, FALSE));
        self.node(Node::Latch(self.latches.len() - 1))
    }

    fn set_next(&mut self, latch: Lit, next: Lit) {
        if let Node::Latch(i) = self.nodes[(latch / 2) as usize] {
            self.latches[i].1 = next ^ (latch & 1);
        }
    }

    fn and(&mut self, a: Lit, b: Lit) -> Lit {
        let (a, b) = if a >= b { (a, b) } else { (b, a) };
        if b == FALSE || a == b ^ 1 {
            return FALSE;
        }
        if b == TRUE || a == b {
            return a;
        }
        if let Some(&l) = self.strash.get(&(a, b)) {
            return l;
        }
        let l = self.node(Node::And(a, b));
        self.strash.insert((a, b), l);
        l
    }

    fn or(&mut self, a: Lit, b: Lit) -> Lit {
        self.and(a ^ 1, b ^ 1) ^ 1
    }

    fn mux(&mut self, c: Lit, t: Lit, e: Lit) -> Lit {
        let x = self.and(c, t);
        let y = self.and(c ^ 1, e);
        self.or(x, y)
    }

    /// `bits` (least significant first) equal to the constant `n`.
    fn equals(&mut self, bits: &[Lit], n: usize) -> Lit {
        bits.iter().enumerate().fold(TRUE, |acc, (i, &b)| {
            let b = if n >> i & 1 == 1 { b } else { b ^ 1 };
            self.and(acc, b)
        })
    }

    /// `bits + 1` (`delta` false) or `bits − 1` (`delta` true), modulo the width.
    fn step(&mut self, bits: &[Lit], down: bool) -> Vec<Lit> {
        let mut carry = TRUE;
        let mut out = Vec::with_capacity(bits.len());
        for &b in bits {
            let x = self.and(b, carry ^ 1);
            let y = self.and(b ^ 1, carry);
            out.push(self.or(x, y));
            carry = if down { self.and(b ^ 1, carry) } else { self.and(b, carry) };
        }
        out
    }

    fn counter(&mut self, name: &str, n: usize) -> Vec<Lit> {
        let width = (usize::BITS - n.leading_zeros()) as usize;
        (0..width).map(|i| self.latch(format!("{name}[{i}]"))).collect()
    }

    /// An output named `name`, or `name_2`, `name_3`, … when an output already has that
    /// name (model checkers such as ABC refuse two outputs of one name).
    fn output(&mut self, name: String, lit: Lit) {
        let taken = |n: &str| self.outputs.iter().any(|(o, _)| o == n);
        let mut unique = name.clone();
        let mut k = 1;
        while taken(&unique) {
            k += 1;
            unique = format!("{name}_{k}");
        }
        self.outputs.push((unique, lit));
    }

    /// The number of inputs, latches, outputs and and-gates.
    pub fn sizes(&self) -> (usize, usize, usize, usize) {
        let ands = self.nodes.iter().filter(|n| matches!(n, Node::And(..))).count();
        (self.inputs.len(), self.latches.len(), self.outputs.len(), ands)
    }

    /// Adds a comment line (after the symbol table).
    pub fn comment(&mut self, line: impl Into<String>) {
        self.comments.push(line.into());
    }

    /// Final AIGER variable of each node: inputs `1..=I`, latches next, and-gates in the
    /// order they were made (children first).
    fn numbering(&self) -> Vec<u32> {
        let (i, l, _, _) = self.sizes();
        let mut var = vec![0u32; self.nodes.len()];
        let mut next_and = (i + l) as u32;
        for (k, n) in self.nodes.iter().enumerate() {
            var[k] = match n {
                Node::False => 0,
                Node::Input(x) => *x as u32 + 1,
                Node::Latch(x) => (i + x) as u32 + 1,
                Node::And(..) => {
                    next_and += 1;
                    next_and
                }
            };
        }
        var
    }

    /// The AIGER text (`aag`) or binary (`aig`) form.
    pub fn to_bytes(&self, binary: bool) -> Vec<u8> {
        let var = self.numbering();
        let lit = |l: Lit| 2 * var[(l / 2) as usize] + (l & 1);
        let (i, l, o, a) = self.sizes();
        let m = i + l + a;
        let mut out: Vec<u8> = Vec::new();
        let line = |out: &mut Vec<u8>, text: String| {
            out.extend_from_slice(text.as_bytes());
            out.push(b'\n');
        };
        line(&mut out, format!("{} {m} {i} {l} {o} {a}", if binary { "aig" } else { "aag" }));
        if !binary {
            for k in 0..i {
                line(&mut out, format!("{}", 2 * (k + 1)));
            }
        }
        for (k, (_, next)) in self.latches.iter().enumerate() {
            if binary {
                line(&mut out, format!("{}", lit(*next)));
            } else {
                line(&mut out, format!("{} {}", 2 * (i + k + 1), lit(*next)));
            }
        }
        for (_, l) in &self.outputs {
            line(&mut out, format!("{}", lit(*l)));
        }
        for (k, n) in self.nodes.iter().enumerate() {
            if let Node::And(x, y) = n {
                let (lhs, r0, r1) = (2 * var[k], lit(*x), lit(*y));
                let (r0, r1) = if r0 >= r1 { (r0, r1) } else { (r1, r0) };
                if binary {
                    encode_delta(&mut out, lhs - r0);
                    encode_delta(&mut out, r0 - r1);
                } else {
                    line(&mut out, format!("{lhs} {r0} {r1}"));
                }
            }
        }
        let symbol = |s: &str| s.replace(['\n', '\r'], " ");
        for (k, name) in self.inputs.iter().enumerate() {
            line(&mut out, format!("i{k} {}", symbol(name)));
        }
        for (k, (name, _)) in self.latches.iter().enumerate() {
            line(&mut out, format!("l{k} {}", symbol(name)));
        }
        for (k, (name, _)) in self.outputs.iter().enumerate() {
            line(&mut out, format!("o{k} {}", symbol(name)));
        }
        if !self.comments.is_empty() {
            line(&mut out, "c".into());
            for c in &self.comments {
                line(&mut out, symbol(c));
            }
        }
        out
    }
}

/// The binary AIGER's variable-length unsigned integer (7 bits a byte, low first).
fn encode_delta(out: &mut Vec<u8>, mut x: u32) {
    while x >= 0x80 {
        out.push((x & 0x7f) as u8 | 0x80);
        x >>= 7;
    }
    out.push(x as u8);
}

/// Encodes `model` (its constraints ignored: `assumptions` gives them per group) with
/// one bad-state output per property, and, when `signals` is set, one more output per
/// equation (named `signal X`, after the properties) so that a run of the graph can be
/// compared with a scan simulator. `cycle` is the scan cycle: every delay must be a
/// whole number of it.
pub fn encode(
    model: &Model,
    assumptions: &[Vec<(Expr, Rel, Expr)>],
    properties: &[Property],
    cycle: &Time,
    signals: bool,
) -> Result<Aig, EncodeError> {
    // The terms: equations, then each group's assumptions, then each property's sides.
    let mut exprs: Vec<(&Expr, Option<usize>)> =
        model.defs.iter().map(|(_, e)| (e, None)).collect();
    let mut group_at = Vec::new();
    for group in assumptions {
        group_at.push(exprs.len());
        exprs.extend(group.iter().flat_map(|(l, _, r)| [(l, None), (r, None)]));
    }
    let property_at = exprs.len();
    for (k, p) in properties.iter().enumerate() {
        exprs.push((&p.lhs, Some(k)));
        exprs.push((&p.rhs, Some(k)));
    }
    let mut defined: BTreeMap<&str, Option<Lit>> = BTreeMap::new();
    for (name, _) in &model.defs {
        if defined.insert(name.as_str(), None).is_some() {
            return Err(EncodeError {
                property: None,
                message: format!("`{name}` has two equations"),
            });
        }
    }
    let mut g = Aig::new();
    let mut free: BTreeMap<String, Lit> = BTreeMap::new();
    let env = Assignment::new(Time::from_integer(1.into()));
    // Per term, per node: its literal (None until computed); per `pre` node its latch, and
    // per timer node its delay in scans. Equal subterms denote the same signal, so a
    // `pre`, timer or memory of the same argument is one latch (or counter).
    let mut lits: Vec<Vec<Option<Lit>>> = exprs.iter().map(|(e, _)| vec![None; e.len()]).collect();
    let mut pre: Vec<HashMap<usize, (Lit, bool)>> = vec![HashMap::new(); exprs.len()];
    let mut widths: Vec<HashMap<usize, usize>> = vec![HashMap::new(); exprs.len()];
    let mut pres: HashMap<String, Lit> = HashMap::new();
    let mut shared: HashMap<(u8, Lit, Lit, usize), Lit> = HashMap::new();
    for (j, (e, owner)) in exprs.iter().enumerate() {
        let inits = initial_values(e);
        let fail = |message: String| EncodeError { property: *owner, message };
        for (i, node) in e.as_ref().iter().enumerate() {
            match node {
                Term::Pre(a) => {
                    let shown = term_to_string(&subterm(e, *a), Notation::Ascii);
                    let first = !pres.contains_key(&shown);
                    let l = *pres.entry(shown.clone()).or_insert_with(|| {
                        let l = g.latch(format!("pre {shown}"));
                        if inits[usize::from(*a)] { l ^ 1 } else { l }
                    });
                    pre[j].insert(i, (l, first));
                }
                Term::Ton([d, _]) | Term::Tof([_, d]) => {
                    let delay = eval_delay(e, *d, &env).map_err(|x| fail(x.to_string()))?;
                    let n = super::whole(&delay, cycle).ok_or_else(|| {
                        fail(format!(
                            "the delay {delay} is not a whole number of scan cycles: a timer's scans are not exact"
                        ))
                    })?;
                    widths[j].insert(i, n);
                }
                _ => {}
            }
        }
    }
    let now: Vec<Vec<bool>> = exprs.iter().map(|(e, _)| needed_now(e)).collect();
    for pass in [true, false] {
        for (j, (e, owner)) in exprs.iter().enumerate() {
            for (i, node) in e.as_ref().iter().enumerate() {
                if now[j][i] != pass {
                    continue;
                }
                let at = |id: &crate::term::Id| lits[j][usize::from(*id)].unwrap_or(FALSE);
                let lit = match node {
                    Term::Zero | Term::Delay(_) | Term::DMax(_) | Term::DMin(_) | Term::DAdd(_) => {
                        FALSE
                    }
                    Term::One => TRUE,
                    Term::Not(a) => at(a) ^ 1,
                    Term::And([a, b]) => g.and(at(a), at(b)),
                    Term::Or([a, b]) => g.or(at(a), at(b)),
                    Term::Pre(_) => pre[j][&i].0,
                    Term::Sr([s, r]) | Term::Rs([s, r]) => {
                        let (s, r) = (at(s), at(r));
                        let sr = matches!(node, Term::Sr(_));
                        let key = (u8::from(sr), s, r, 0);
                        if let Some(&l) = shared.get(&key) {
                            l
                        } else {
                            let shown = term_to_string(&subterm(e, Id::from(i)), Notation::Ascii);
                            let prev = g.latch(format!("memory {}", short(&shown)));
                            let q = if sr {
                                let hold = g.and(prev, r ^ 1);
                                g.or(s, hold)
                            } else {
                                let set = g.or(s, prev);
                                g.and(set, r ^ 1)
                            };
                            g.set_next(prev, q);
                            shared.insert(key, q);
                            q
                        }
                    }
                    Term::Ton([_, f]) | Term::Tof([f, _]) => {
                        let f = at(f);
                        let n = widths[j][&i];
                        let ton = matches!(node, Term::Ton(_));
                        let key = (2 + u8::from(ton), f, FALSE, n);
                        if n == 0 {
                            f
                        } else if let Some(&l) = shared.get(&key) {
                            l
                        } else {
                            let shown = term_to_string(&subterm(e, Id::from(i)), Notation::Ascii);
                            let c = g.counter(&format!("timer {}", short(&shown)), n);
                            let l = if ton {
                                let full = g.equals(&c, n);
                                let up = g.step(&c, false);
                                for (&bit, &inc) in c.iter().zip(&up) {
                                    let kept = g.mux(full, bit, inc);
                                    let next = g.and(f, kept);
                                    g.set_next(bit, next);
                                }
                                g.and(f, full)
                            } else {
                                let empty = g.equals(&c, 0);
                                let down = g.step(&c, true);
                                for (k, (&bit, &dec)) in c.iter().zip(&down).enumerate() {
                                    let counted = g.and(empty ^ 1, dec);
                                    let load = if n >> k & 1 == 1 { TRUE } else { FALSE };
                                    let next = g.mux(f, load, counted);
                                    g.set_next(bit, next);
                                }
                                g.or(f, empty ^ 1)
                            };
                            shared.insert(key, l);
                            l
                        }
                    }
                    Term::Name(n) => match defined.get(n.as_str()) {
                        Some(Some(l)) => *l,
                        Some(None) => {
                            return Err(EncodeError {
                                property: *owner,
                                message: format!("`{n}` is read before the scan computes it"),
                            });
                        }
                        None => match free.get(n.as_str()) {
                            Some(l) => *l,
                            None => {
                                let l = g.input(n.as_str());
                                free.insert(n.as_str().to_string(), l);
                                l
                            }
                        },
                    },
                };
                lits[j][i] = Some(lit);
            }
            if pass && let Some((name, _)) = model.defs.get(j) {
                let top = lits[j].last().copied().flatten().unwrap_or(FALSE);
                defined.insert(name.as_str(), Some(top));
            }
        }
    }
    // `pre f`: the latch takes f's value of this scan.
    for (j, (e, _)) in exprs.iter().enumerate() {
        for (i, node) in e.as_ref().iter().enumerate() {
            if let (Term::Pre(a), Some((latch, true))) = (node, pre[j].get(&i)) {
                let next = lits[j][usize::from(*a)].unwrap_or(FALSE);
                g.set_next(*latch, next);
            }
        }
    }
    let root = |j: usize| lits[j].last().copied().flatten().unwrap_or(FALSE);
    // Per group: its assumptions hold now and have held at every scan before.
    let mut holding = Vec::new();
    for (k, group) in assumptions.iter().enumerate() {
        let mut now = TRUE;
        for (c, (_, rel, _)) in group.iter().enumerate() {
            let (l, r) = (root(group_at[k] + 2 * c), root(group_at[k] + 2 * c + 1));
            let v = violated(&mut g, *rel, &l, &r);
            now = g.and(now, v ^ 1);
        }
        if now == TRUE {
            holding.push(TRUE);
            continue;
        }
        let broken = g.latch(format!("an assumption of file {k} was broken"));
        let next = g.or(broken, now ^ 1);
        g.set_next(broken, next);
        holding.push(g.and(broken ^ 1, now));
    }
    for (k, p) in properties.iter().enumerate() {
        let (l, r) = (root(property_at + 2 * k), root(property_at + 2 * k + 1));
        let v = violated(&mut g, p.rel, &l, &r);
        let bad = g.and(holding.get(p.group).copied().unwrap_or(TRUE), v);
        g.output(p.name.clone(), bad);
    }
    if signals {
        for (name, _) in &model.defs {
            let l = defined.get(name.as_str()).copied().flatten().unwrap_or(FALSE);
            g.output(format!("signal {name}"), l);
        }
    }
    Ok(g)
}

/// A term's text cut to a readable length for a symbol.
fn short(text: &str) -> String {
    let text: String = text.split_whitespace().collect::<Vec<_>>().join(" ");
    match text.char_indices().nth(60) {
        Some((at, _)) => format!("{}...", &text[..at]),
        None => text,
    }
}

impl super::unroll::Bits for Aig {
    type V = Lit;
    fn konst(&mut self, b: bool) -> Lit {
        if b { TRUE } else { FALSE }
    }
    fn not(&mut self, a: &Lit) -> Lit {
        a ^ 1
    }
    fn and_all(&mut self, xs: &[Lit]) -> Lit {
        xs.iter().fold(TRUE, |acc, x| self.and(acc, *x))
    }
    fn or_all(&mut self, xs: &[Lit]) -> Lit {
        xs.iter().fold(FALSE, |acc, x| self.or(acc, *x))
    }
}
