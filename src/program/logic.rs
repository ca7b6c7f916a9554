//! Working terms of the rung compiler: Boolean structure over opaque temporal atoms, with truth tables, simplification and the sound elimination of unconstrained signals.
//!
//! A [`L`] is an II term with n-ary sums and products, easy to flatten and
//! substitute into. Anything that is not `0*`, `1*`, `·`, `+` or `¬` (a name, a
//! timer, a memory) is an *atom* for Boolean reasoning: two terms are equivalent
//! when their truth tables over their atoms agree. That is sound for the II
//! algebra (Boolean identities hold pointwise whatever the atoms' values) and
//! never confuses two different atoms. Truth tables are built 64 rows at a time
//! and only for at most [`MAX_ATOMS`] atoms; beyond that the Boolean checks
//! answer "unknown" and the compiler falls back to its always-sound choice.
#![warn(missing_docs)]

use crate::term::{Builder, Delay, Expr, Id, Term, root};

/// The most atoms a truth table is built for (2^16 rows, 1024 words).
pub const MAX_ATOMS: usize = 16;

/// The most word operations one simplification spends on truth tables (beyond it the
/// operands are kept as they are): bounds the cost of simplifying large terms of many
/// atoms, such as bit-blasted arithmetic, which is rebuilt at every operator.
const SIMPLIFY_BUDGET: usize = 1 << 16;

/// A signal's name in a working term, shared by every copy of the term.
pub type Name = std::sync::Arc<str>;

/// A working term.
#[derive(Clone, Debug, Eq)]
pub enum L {
    /// `0*`.
    Zero,
    /// `1*`.
    One,
    /// A named signal.
    Var(Name),
    /// `¬f`.
    Not(Box<L>),
    /// A product (empty = `1*`).
    And(Ops),
    /// A sum (empty = `0*`).
    Or(Ops),
    /// `d/f`.
    Ton(Delay, Box<L>),
    /// `f/d`.
    Tof(Box<L>, Delay),
    /// `SR(s, r)`.
    Sr(Box<L>, Box<L>),
    /// `RS(s, r)`.
    Rs(Box<L>, Box<L>),
    /// `pre f`: `f` one scan earlier.
    Pre(Box<L>),
}

/// The operands of a sum or product, and whether the term is [`simp`]'s result: then
/// simplifying it again gives it back (simplification is idempotent), and [`simp`] does
/// not look inside. Terms of bit-blasted arithmetic are built from simplified operands,
/// which every later operator would otherwise simplify again. Only [`simp`] marks a term;
/// a term built any other way is unmarked, and the mark plays no part in equality.
#[derive(Clone, Default, Eq)]
pub struct Ops {
    items: Vec<L>,
    simplified: bool,
}

impl Ops {
    /// The operands.
    pub fn into_vec(self) -> Vec<L> {
        self.items
    }
}

impl PartialEq for Ops {
    fn eq(&self, other: &Ops) -> bool {
        self.items == other.items
    }
}

impl std::fmt::Debug for Ops {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.items.fmt(f)
    }
}

impl std::ops::Deref for Ops {
    type Target = Vec<L>;
    fn deref(&self) -> &Vec<L> {
        &self.items
    }
}

impl From<Vec<L>> for Ops {
    fn from(items: Vec<L>) -> Ops {
        Ops { items, simplified: false }
    }
}

impl FromIterator<L> for Ops {
    fn from_iter<I: IntoIterator<Item = L>>(iter: I) -> Ops {
        Ops::from(iter.into_iter().collect::<Vec<L>>())
    }
}

impl IntoIterator for Ops {
    type Item = L;
    type IntoIter = std::vec::IntoIter<L>;
    fn into_iter(self) -> Self::IntoIter {
        self.items.into_iter()
    }
}

impl<'a> IntoIterator for &'a Ops {
    type Item = &'a L;
    type IntoIter = std::slice::Iter<'a, L>;
    fn into_iter(self) -> Self::IntoIter {
        self.items.iter()
    }
}

/// Structural equality, names compared from their last character: the names of a
/// bit-blasted circuit share long prefixes and differ at their ends (`X_b3`, `X_b4`).
impl PartialEq for L {
    fn eq(&self, other: &L) -> bool {
        if std::ptr::eq(self, other) {
            return true;
        }
        match (self, other) {
            (L::Zero, L::Zero) | (L::One, L::One) => true,
            (L::Var(a), L::Var(b)) => {
                std::sync::Arc::ptr_eq(a, b)
                    || (a.len() == b.len() && a.bytes().rev().eq(b.bytes().rev()))
            }
            (L::Not(a), L::Not(b)) | (L::Pre(a), L::Pre(b)) => a == b,
            (L::And(a), L::And(b)) | (L::Or(a), L::Or(b)) => a == b,
            (L::Ton(d, a), L::Ton(e, b)) | (L::Tof(a, d), L::Tof(b, e)) => d == e && a == b,
            (L::Sr(a, b), L::Sr(c, d)) | (L::Rs(a, b), L::Rs(c, d)) => a == c && b == d,
            _ => false,
        }
    }
}

impl L {
    /// A named signal.
    pub fn var(name: &str) -> L {
        L::Var(name.into())
    }

    /// `¬self`, folding constants and double negation.
    pub fn negate(self) -> L {
        match self {
            L::Zero => L::One,
            L::One => L::Zero,
            L::Not(x) => *x,
            x => L::Not(Box::new(x)),
        }
    }

    /// `self · other`, folding constants and flattening.
    pub fn and(self, other: L) -> L {
        match (self, other) {
            (L::Zero, _) | (_, L::Zero) => L::Zero,
            (L::One, x) | (x, L::One) => x,
            (L::And(a), L::And(b)) => {
                let mut a = a.into_vec();
                a.extend(b);
                L::And(a.into())
            }
            (L::And(a), x) => {
                let mut a = a.into_vec();
                a.push(x);
                L::And(a.into())
            }
            (x, L::And(b)) => {
                let mut a = vec![x];
                a.extend(b);
                L::And(a.into())
            }
            (x, y) => L::And(vec![x, y].into()),
        }
    }

    /// `self + other`, folding constants and flattening.
    pub fn or(self, other: L) -> L {
        match (self, other) {
            (L::One, _) | (_, L::One) => L::One,
            (L::Zero, x) | (x, L::Zero) => x,
            (L::Or(a), L::Or(b)) => {
                let mut a = a.into_vec();
                a.extend(b);
                L::Or(a.into())
            }
            (L::Or(a), x) => {
                let mut a = a.into_vec();
                a.push(x);
                L::Or(a.into())
            }
            (x, L::Or(b)) => {
                let mut a = vec![x];
                a.extend(b);
                L::Or(a.into())
            }
            (x, y) => L::Or(vec![x, y].into()),
        }
    }

    /// The number of nodes.
    pub fn size(&self) -> usize {
        1 + match self {
            L::Zero | L::One | L::Var(_) => 0,
            L::Not(x) | L::Ton(_, x) | L::Tof(x, _) | L::Pre(x) => x.size(),
            L::And(xs) | L::Or(xs) => xs.iter().map(L::size).sum(),
            L::Sr(a, b) | L::Rs(a, b) => a.size() + b.size(),
        }
    }

    /// Whether `name` occurs.
    pub fn mentions(&self, name: &str) -> bool {
        match self {
            L::Zero | L::One => false,
            L::Var(v) => **v == *name,
            L::Not(x) | L::Ton(_, x) | L::Tof(x, _) | L::Pre(x) => x.mentions(name),
            L::And(xs) | L::Or(xs) => xs.iter().any(|x| x.mentions(name)),
            L::Sr(a, b) | L::Rs(a, b) => a.mentions(name) || b.mentions(name),
        }
    }

    /// Whether `name` occurs under a timer or a memory (then it is not a pointwise Boolean argument).
    pub fn mentions_temporally(&self, name: &str) -> bool {
        match self {
            L::Zero | L::One | L::Var(_) => false,
            L::Not(x) => x.mentions_temporally(name),
            L::And(xs) | L::Or(xs) => xs.iter().any(|x| x.mentions_temporally(name)),
            L::Ton(_, x) | L::Tof(x, _) | L::Pre(x) => x.mentions(name),
            L::Sr(a, b) | L::Rs(a, b) => a.mentions(name) || b.mentions(name),
        }
    }

    /// Every name, in first-occurrence order, without repeats.
    pub fn names(&self, out: &mut Vec<String>) {
        match self {
            L::Zero | L::One => {}
            L::Var(v) => {
                if !out.iter().any(|o| **o == **v) {
                    out.push(v.to_string());
                }
            }
            L::Not(x) | L::Ton(_, x) | L::Tof(x, _) | L::Pre(x) => x.names(out),
            L::And(xs) | L::Or(xs) => xs.iter().for_each(|x| x.names(out)),
            L::Sr(a, b) | L::Rs(a, b) => {
                a.names(out);
                b.names(out);
            }
        }
    }

    /// `self[name := value]` everywhere (also under timers and memories).
    pub fn subst(&self, name: &str, value: &L) -> L {
        self.substitute(&|v| (v == name).then(|| value.clone()))
    }

    /// `self` with every name `f` gives a term for replaced by that term, in one pass
    /// (also under timers and memories).
    pub fn substitute(&self, f: &dyn Fn(&str) -> Option<L>) -> L {
        match self {
            L::Zero => L::Zero,
            L::One => L::One,
            L::Var(v) => f(v).unwrap_or_else(|| self.clone()),
            L::Not(x) => L::Not(Box::new(x.substitute(f))),
            L::And(xs) => L::And(xs.iter().map(|x| x.substitute(f)).collect()),
            L::Or(xs) => L::Or(xs.iter().map(|x| x.substitute(f)).collect()),
            L::Ton(d, x) => L::Ton(d.clone(), Box::new(x.substitute(f))),
            L::Tof(x, d) => L::Tof(Box::new(x.substitute(f)), d.clone()),
            L::Sr(a, b) => L::Sr(Box::new(a.substitute(f)), Box::new(b.substitute(f))),
            L::Rs(a, b) => L::Rs(Box::new(a.substitute(f)), Box::new(b.substitute(f))),
            L::Pre(x) => L::Pre(Box::new(x.substitute(f))),
        }
    }

    /// Renames every name through `f`.
    pub fn rename(&self, f: &dyn Fn(&str) -> String) -> L {
        match self {
            L::Zero => L::Zero,
            L::One => L::One,
            L::Var(v) => L::Var(f(v).into()),
            L::Not(x) => L::Not(Box::new(x.rename(f))),
            L::And(xs) => L::And(xs.iter().map(|x| x.rename(f)).collect()),
            L::Or(xs) => L::Or(xs.iter().map(|x| x.rename(f)).collect()),
            L::Ton(d, x) => L::Ton(d.clone(), Box::new(x.rename(f))),
            L::Tof(x, d) => L::Tof(Box::new(x.rename(f)), d.clone()),
            L::Sr(a, b) => L::Sr(Box::new(a.rename(f)), Box::new(b.rename(f))),
            L::Rs(a, b) => L::Rs(Box::new(a.rename(f)), Box::new(b.rename(f))),
            L::Pre(x) => L::Pre(Box::new(x.rename(f))),
        }
    }

    /// Adds the atoms of `self` not yet in `out`, in first-occurrence order, and the index
    /// in `out` of each atom occurrence to `leaves`, in the order [`L::word`] and
    /// [`L::fill`] meet them; false when there would be more than [`MAX_ATOMS`].
    fn atoms<'a>(&'a self, out: &mut Vec<&'a L>, leaves: &mut Vec<u8>) -> bool {
        match self {
            L::Zero | L::One => true,
            L::Not(x) => x.atoms(out, leaves),
            L::And(xs) | L::Or(xs) => xs.iter().all(|x| x.atoms(out, leaves)),
            atom => {
                let i = match out.iter().position(|a| *a == atom) {
                    Some(i) => i,
                    None if out.len() == MAX_ATOMS => return false,
                    None => {
                        out.push(atom);
                        out.len() - 1
                    }
                };
                leaves.push(i as u8);
                true
            }
        }
    }

    /// The truth table when it fits one word (at most 6 atoms), each atom occurrence's
    /// index taken from `leaves` in order.
    fn word(&self, leaves: &mut std::slice::Iter<u8>) -> u64 {
        match self {
            L::Zero => 0,
            L::One => !0,
            L::Not(x) => !x.word(leaves),
            L::And(xs) => xs.iter().fold(!0, |acc, x| acc & x.word(leaves)),
            L::Or(xs) => xs.iter().fold(0, |acc, x| acc | x.word(leaves)),
            _ => atom_word(leaves.next().map_or(0, |i| usize::from(*i)), 0),
        }
    }

    /// Writes the truth table into `out` (one word per 64 rows), each atom occurrence's
    /// index taken from `leaves` in order; `spare` keeps the operands' buffers for reuse.
    fn fill(&self, leaves: &mut std::slice::Iter<u8>, out: &mut [u64], spare: &mut Vec<Vec<u64>>) {
        match self {
            L::Zero => out.fill(0),
            L::One => out.fill(!0),
            L::Not(x) => {
                x.fill(leaves, out, spare);
                out.iter_mut().for_each(|w| *w = !*w);
            }
            L::And(xs) | L::Or(xs) => {
                let is_and = matches!(self, L::And(_));
                out.fill(if is_and { !0 } else { 0 });
                let mut operand = spare.pop().unwrap_or_else(|| vec![0; out.len()]);
                for x in xs {
                    x.fill(leaves, &mut operand, spare);
                    for (o, w) in out.iter_mut().zip(&operand) {
                        *o = if is_and { *o & w } else { *o | w };
                    }
                }
                spare.push(operand);
            }
            _ => {
                let i = leaves.next().map_or(0, |i| usize::from(*i));
                out.iter_mut().enumerate().for_each(|(w, o)| *o = atom_word(i, w));
            }
        }
    }

    /// Converts to an egg term (sums and products left-associated).
    pub fn to_expr(&self) -> Expr {
        let mut b = Builder::default();
        self.build(&mut b);
        b.finish()
    }

    fn build(&self, b: &mut Builder) -> Id {
        match self {
            L::Zero => b.zero(),
            L::One => b.one(),
            L::Var(v) => b.name(v),
            L::Not(x) => {
                let x = x.build(b);
                b.not(x)
            }
            L::And(xs) => match xs.split_first() {
                None => b.one(),
                Some((first, rest)) => {
                    let mut acc = first.build(b);
                    for x in rest {
                        let y = x.build(b);
                        acc = b.and(acc, y);
                    }
                    acc
                }
            },
            L::Or(xs) => match xs.split_first() {
                None => b.zero(),
                Some((first, rest)) => {
                    let mut acc = first.build(b);
                    for x in rest {
                        let y = x.build(b);
                        acc = b.or(acc, y);
                    }
                    acc
                }
            },
            L::Ton(d, x) => {
                let d = b.delay(d.clone());
                let x = x.build(b);
                b.ton(d, x)
            }
            L::Tof(x, d) => {
                let x = x.build(b);
                let d = b.delay(d.clone());
                b.tof(x, d)
            }
            L::Sr(s, r) => {
                let s = s.build(b);
                let r = r.build(b);
                b.sr(s, r)
            }
            L::Rs(s, r) => {
                let s = s.build(b);
                let r = r.build(b);
                b.rs(s, r)
            }
            L::Pre(x) => {
                let x = x.build(b);
                b.pre(x)
            }
        }
    }

    /// Reads an egg term back (delay arithmetic other than literals is kept as `None`).
    pub fn from_expr(expr: &Expr) -> Option<L> {
        if expr.as_ref().is_empty() {
            return None;
        }
        from_node(expr, root(expr))
    }
}

fn from_node(expr: &Expr, id: Id) -> Option<L> {
    let delay = |id: Id| match &expr[id] {
        Term::Delay(d) => Some(d.clone()),
        _ => None,
    };
    Some(match &expr[id] {
        Term::Zero => L::Zero,
        Term::One => L::One,
        Term::Name(s) => L::Var(s.as_str().into()),
        Term::Not(x) => L::Not(Box::new(from_node(expr, *x)?)),
        Term::And([a, b]) => from_node(expr, *a)?.and(from_node(expr, *b)?),
        Term::Or([a, b]) => from_node(expr, *a)?.or(from_node(expr, *b)?),
        Term::Ton([d, f]) => L::Ton(delay(*d)?, Box::new(from_node(expr, *f)?)),
        Term::Tof([f, d]) => L::Tof(Box::new(from_node(expr, *f)?), delay(*d)?),
        Term::Sr([s, r]) => L::Sr(Box::new(from_node(expr, *s)?), Box::new(from_node(expr, *r)?)),
        Term::Rs([s, r]) => L::Rs(Box::new(from_node(expr, *s)?), Box::new(from_node(expr, *r)?)),
        Term::Pre(x) => L::Pre(Box::new(from_node(expr, *x)?)),
        Term::Delay(_) | Term::DMax(_) | Term::DMin(_) | Term::DAdd(_) => return None,
    })
}

/// The truth-table word `w` of atom `i`.
fn atom_word(i: usize, w: usize) -> u64 {
    const MASKS: [u64; 6] = [
        0xAAAA_AAAA_AAAA_AAAA,
        0xCCCC_CCCC_CCCC_CCCC,
        0xF0F0_F0F0_F0F0_F0F0,
        0xFF00_FF00_FF00_FF00,
        0xFFFF_0000_FFFF_0000,
        0xFFFF_FFFF_0000_0000,
    ];
    if i < 6 {
        MASKS[i]
    } else if (w >> (i - 6)) & 1 == 1 {
        !0
    } else {
        0
    }
}

/// Truth tables of several terms over their common atoms, with the mask of valid bits.
pub struct Tables {
    /// The tables one after the other, `words` words each.
    words: Vec<u64>,
    /// The words of one table.
    width: usize,
    mask: u64,
}

impl Tables {
    /// Tables for `terms`, or `None` if they have more than [`MAX_ATOMS`] atoms together.
    pub fn new(terms: &[&L]) -> Option<Tables> {
        Tables::within(terms, usize::MAX)
    }

    /// Tables for `terms`, or `None` if they have more than [`MAX_ATOMS`] atoms together
    /// or building them would cost more than `budget` word operations (their size times
    /// the words of a table).
    pub fn within(terms: &[&L], budget: usize) -> Option<Tables> {
        let mut atoms = Vec::new();
        let mut leaves = Vec::new();
        for t in terms {
            if !t.atoms(&mut atoms, &mut leaves) {
                return None;
            }
        }
        let n = atoms.len();
        let width = if n <= 6 { 1 } else { 1 << (n - 6) };
        if width > 1 && terms.iter().map(|t| t.size()).sum::<usize>() * width > budget {
            return None;
        }
        let mask = if n >= 6 { !0 } else { (1u64 << (1u32 << n)) - 1 };
        let mut leaves = leaves.iter();
        let mut words = vec![0; terms.len() * width];
        if width == 1 {
            for (w, t) in words.iter_mut().zip(terms) {
                *w = t.word(&mut leaves);
            }
        } else {
            let mut spare = Vec::new();
            for (table, t) in words.chunks_exact_mut(width).zip(terms) {
                t.fill(&mut leaves, table, &mut spare);
            }
        }
        Some(Tables { words, width, mask })
    }

    /// The table of term `i`.
    pub fn table(&self, i: usize) -> &[u64] {
        &self.words[i * self.width..(i + 1) * self.width]
    }

    /// Does term `i` imply term `j` (for every valuation of the atoms)?
    pub fn implies(&self, i: usize, j: usize) -> bool {
        self.table(i).iter().zip(self.table(j)).all(|(a, b)| a & !b & self.mask == 0)
    }

    /// Is term `i` always 0?
    pub fn is_zero(&self, i: usize) -> bool {
        self.table(i).iter().all(|a| a & self.mask == 0)
    }

    /// Is term `i` always 1?
    pub fn is_one(&self, i: usize) -> bool {
        self.table(i).iter().all(|a| !a & self.mask == 0)
    }
}

/// `a ⇒ b` as Boolean functions of their atoms; `None` when there are too many atoms.
pub fn implies(a: &L, b: &L) -> Option<bool> {
    Tables::new(&[a, b]).map(|t| t.implies(0, 1))
}

/// `a = b` as Boolean functions of their atoms; `None` when there are too many atoms.
pub fn equivalent(a: &L, b: &L) -> Option<bool> {
    Tables::new(&[a, b]).map(|t| t.implies(0, 1) && t.implies(1, 0))
}

/// Simplifies, keeping the order of operands: constants, double negation,
/// flattening, duplicates, and absorption (a factor implied by another factor,
/// or a summand implying another summand, is dropped); a sum or product that is
/// constant as a Boolean function becomes that constant. Also `d/0* = 0*`,
/// `0*/d = 0*`, `SR(0*, r) = RS(0*, r) = RS(s, 1*) = 0*`, `SR(1*, r) = 1*`.
pub fn simp(e: &L) -> L {
    simplify(e.clone())
}

/// [`simp`] of a term the caller gives away: its simplified parts are moved into the
/// result, not copied.
pub fn simplify(e: L) -> L {
    match e {
        L::Zero | L::One | L::Var(_) => e,
        L::Not(x) => simplify(*x).negate(),
        L::And(ref xs) | L::Or(ref xs) if xs.simplified => e,
        L::And(xs) => junction(xs, true),
        L::Or(xs) => junction(xs, false),
        L::Ton(d, x) => match simplify(*x) {
            L::Zero => L::Zero,
            x => L::Ton(d, Box::new(x)),
        },
        L::Tof(x, d) => match simplify(*x) {
            L::Zero => L::Zero,
            x => L::Tof(Box::new(x), d),
        },
        L::Sr(s, r) => match (simplify(*s), simplify(*r)) {
            (L::Zero, _) => L::Zero,
            (L::One, _) => L::One,
            (s, r) => L::Sr(Box::new(s), Box::new(r)),
        },
        L::Rs(s, r) => match (simplify(*s), simplify(*r)) {
            (L::Zero, _) | (_, L::One) => L::Zero,
            (s, r) => L::Rs(Box::new(s), Box::new(r)),
        },
        L::Pre(x) => match simplify(*x) {
            c @ (L::Zero | L::One) => c,
            x => L::Pre(Box::new(x)),
        },
    }
}

/// [`simp`] of a product (`is_and`) or a sum: marked as simplified.
fn junction(xs: Ops, is_and: bool) -> L {
    match combine(xs.into_iter().map(simplify), is_and) {
        L::And(ys) => L::And(Ops { simplified: true, ..ys }),
        L::Or(ys) => L::Or(Ops { simplified: true, ..ys }),
        other => other,
    }
}

/// `a · b` for operands that are already [`simp`]'s results: the same term as
/// `simp(&a.and(b))`, without simplifying the operands again.
pub fn simp_and(a: L, b: L) -> L {
    combine([a, b].into_iter(), true)
}

/// The sum of operands that are already [`simp`]'s results: the same term as
/// `simp(&sum(xs))`, without simplifying the operands again.
pub fn simp_sum(xs: Vec<L>) -> L {
    combine(xs.into_iter(), false)
}

/// A product (`is_and`) or a sum of simplified operands: flattened, without constants
/// and duplicates, redundant operands absorbed, constant functions folded.
fn combine(xs: impl Iterator<Item = L>, is_and: bool) -> L {
    let (unit, absorbing) = if is_and { (L::One, L::Zero) } else { (L::Zero, L::One) };
    let mut items: Vec<L> = Vec::with_capacity(xs.size_hint().0);
    // Adds an operand not met yet; false for the absorbing constant.
    let add = |items: &mut Vec<L>, y: L| {
        if y == absorbing {
            return false;
        }
        if y != unit && !items.contains(&y) {
            items.push(y);
        }
        true
    };
    for x in xs {
        let added = match x {
            L::And(ys) if is_and => ys.into_iter().all(|y| add(&mut items, y)),
            L::Or(ys) if !is_and => ys.into_iter().all(|y| add(&mut items, y)),
            y => add(&mut items, y),
        };
        if !added {
            return absorbing;
        }
    }
    if items.len() > 1 {
        let refs: Vec<&L> = items.iter().collect();
        if let Some(t) = Tables::within(&refs, SIMPLIFY_BUDGET) {
            let n = items.len();
            let mut keep = vec![true; n];
            // Drop, from the last to the first, an operand made redundant by another kept one.
            for j in (0..n).rev() {
                let redundant = (0..n).any(|i| {
                    i != j && keep[i] && if is_and { t.implies(i, j) } else { t.implies(j, i) }
                });
                if redundant {
                    keep[j] = false;
                }
            }
            // The kept operands' function, from their tables.
            let mut folded = vec![if is_and { !0 } else { 0 }; t.width];
            for (k, _) in keep.iter().enumerate().filter(|(_, kept)| **kept) {
                for (f, w) in folded.iter_mut().zip(t.table(k)) {
                    *f = if is_and { *f & w } else { *f | w };
                }
            }
            if folded.iter().all(|w| w & t.mask == 0) {
                return L::Zero;
            }
            if folded.iter().all(|w| !w & t.mask == 0) {
                return L::One;
            }
            let mut k = 0;
            items.retain(|_| {
                k += 1;
                keep[k - 1]
            });
        }
    }
    match items.len() {
        0 => unit,
        1 => items.pop().unwrap_or(unit),
        _ => {
            if is_and {
                L::And(items.into())
            } else {
                L::Or(items.into())
            }
        }
    }
}

/// The operands of a product (a non-product is a product of one).
pub fn factors(e: &L) -> Vec<L> {
    match e {
        L::And(xs) => xs.to_vec(),
        L::One => Vec::new(),
        x => vec![x.clone()],
    }
}

/// The operands of a sum (a non-sum is a sum of one).
pub fn summands(e: &L) -> Vec<L> {
    match e {
        L::Or(xs) => xs.to_vec(),
        L::Zero => Vec::new(),
        x => vec![x.clone()],
    }
}

/// A product of `xs` (`1*` if empty).
pub fn product(xs: Vec<L>) -> L {
    xs.into_iter().fold(L::One, L::and)
}

/// A sum of `xs` (`0*` if empty).
pub fn sum(xs: Vec<L>) -> L {
    xs.into_iter().fold(L::Zero, L::or)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(n: &str) -> L {
        L::var(n)
    }

    #[test]
    fn absorption_and_constants() {
        let e = v("a").and(v("b")).or(v("a"));
        assert_eq!(simp(&e), v("a"));
        let e = v("a").and(v("a").negate());
        assert_eq!(simp(&e), L::Zero);
        let e = v("s").and(v("r").negate()).or(v("r").negate());
        assert_eq!(simp(&e), v("r").negate());
        assert_eq!(simp(&e.negate()), v("r"));
    }

    #[test]
    fn tables_beyond_six_atoms() {
        let names: Vec<L> = (0..9).map(|i| v(&format!("x{i}"))).collect();
        let all = product(names.clone());
        let any = sum(names);
        assert_eq!(implies(&all, &any), Some(true));
        assert_eq!(implies(&any, &all), Some(false));
    }

    fn term() -> impl proptest::strategy::Strategy<Value = L> {
        use proptest::prelude::*;
        let leaf = prop_oneof![
            Just(L::Zero),
            Just(L::One),
            (0..8usize).prop_map(|i| v(&format!("x{i}"))),
            (0..3usize).prop_map(|i| L::Pre(Box::new(v(&format!("x{i}"))))),
        ];
        leaf.prop_recursive(4, 40, 4, |inner| {
            prop_oneof![
                inner.clone().prop_map(L::negate),
                proptest::collection::vec(inner.clone(), 0..4).prop_map(|xs| L::And(xs.into())),
                proptest::collection::vec(inner, 0..4).prop_map(|xs| L::Or(xs.into())),
            ]
        })
    }

    proptest::proptest! {
        /// Combining simplified operands gives `simp`'s own term, and `simp` keeps the function.
        #[test]
        fn combining_simplified_operands_is_simp(a in term(), b in term(), c in term()) {
            let (a, b, c) = (simp(&a), simp(&b), simp(&c));
            let and = simp_and(a.clone(), b.clone());
            proptest::prop_assert_eq!(&and, &simp(&a.clone().and(b.clone())));
            let or = simp_sum(vec![a.clone(), b.clone(), c.clone()]);
            proptest::prop_assert_eq!(&or, &simp(&sum(vec![a.clone(), b.clone(), c.clone()])));
            proptest::prop_assert_eq!(equivalent(&and, &L::And(vec![a.clone(), b.clone()].into())), Some(true));
            proptest::prop_assert_eq!(equivalent(&or, &L::Or(vec![a, b, c].into())), Some(true));
            proptest::prop_assert_eq!(simp(&and), and);
        }

        /// Simplifying a simplified term again from scratch (every sum and product rebuilt
        /// unmarked) gives it back: what lets `simp` return a marked term as it is.
        #[test]
        fn simplification_is_idempotent(a in term(), b in term()) {
            let s = simp(&a.and(b.negate()));
            let unmarked = s.substitute(&|_| None);
            proptest::prop_assert!(!matches!(&unmarked, L::And(xs) | L::Or(xs) if xs.simplified));
            proptest::prop_assert_eq!(simp(&unmarked), s);
        }
    }
}
