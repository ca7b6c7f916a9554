//! Instruction List in the scan model: the current result as a lowered value, forward jumps and conditional returns as a guard on every later write, calls as in Structured Text.
//!
//! An IL body runs its lines in order with one register, the current result (CR). Its
//! value here is a scan-local value, taken anew before each instruction that writes or
//! jumps (so a later write cannot change what was read). A line runs when the guard holds:
//! `TRUE` at the start; after `JMPC L` it is `guard ∧ ¬CR` and the jump's condition
//! `guard ∧ CR` joins the guard at `L:` (with the CR it carried); after `RET` it is
//! `FALSE` until a label some jump reaches. A write under a guard that is not `TRUE` is
//! an `If` of the scan model. A jump to an earlier label would repeat instructions within
//! one scan (a loop): refused with a located error, as is a timer or edge detector called
//! on a line some jump may skip (its memory would update only on some scans).

use std::collections::BTreeMap;

use super::ints::{Int, Opaque};
use super::{Lowering, Sym, Ty};
use crate::diag::Span;
use crate::iec::StError;
use crate::iec::ast::{self, BinOp, ExprKind, IlCond, IlInstr, IlLine, IlOp};
use crate::program::{BoolExpr, IntExpr, Stmt, WriteKind};

/// The current result.
#[derive(Clone, Debug)]
enum Cr {
    /// Nothing loaded yet.
    Unset,
    /// A BOOL.
    Bool(BoolExpr),
    /// An integer, or why its value is not computed.
    Int(Result<Int, Opaque>),
    /// A value of another type (a duration, a REAL), named for messages.
    Other(String),
}

impl Cr {
    /// What it holds, for messages.
    fn what(&self) -> String {
        match self {
            Cr::Int(_) => "an integer".into(),
            Cr::Other(t) => t.clone(),
            Cr::Bool(_) => "a BOOL".into(),
            Cr::Unset => "nothing".into(),
        }
    }
}

/// How many jump conditions a guard's truth table follows.
const ATOMS: usize = 12;
const WORDS: usize = (1 << ATOMS) / 64;

/// A guard as a Boolean function of the jump conditions met so far, each taken as a free
/// variable: where every path from a jump meets again the guard is `TRUE` whatever the
/// conditions were (a truth table over the first [`ATOMS`] conditions; `None` beyond).
#[derive(Clone, Debug, PartialEq, Eq)]
struct Table(Option<Box<[u64; WORDS]>>);

impl Table {
    fn constant(v: bool) -> Table {
        Table(Some(Box::new([if v { u64::MAX } else { 0 }; WORDS])))
    }

    /// The `k`-th condition.
    fn atom(k: usize) -> Table {
        if k >= ATOMS {
            return Table(None);
        }
        let mut t = [0u64; WORDS];
        for (w, word) in t.iter_mut().enumerate() {
            for b in 0..64 {
                if ((w * 64 + b) >> k) & 1 == 1 {
                    *word |= 1 << b;
                }
            }
        }
        Table(Some(Box::new(t)))
    }

    fn zip(&self, other: &Table, f: impl Fn(u64, u64) -> u64) -> Table {
        match (&self.0, &other.0) {
            (Some(a), Some(b)) => {
                let mut t = [0u64; WORDS];
                for (k, w) in t.iter_mut().enumerate() {
                    *w = f(a[k], b[k]);
                }
                Table(Some(Box::new(t)))
            }
            _ => Table(None),
        }
    }

    fn and(&self, o: &Table) -> Table {
        self.zip(o, |a, b| a & b)
    }

    fn or(&self, o: &Table) -> Table {
        self.zip(o, |a, b| a | b)
    }

    fn not(&self) -> Table {
        self.zip(&Table::constant(true), |a, _| !a)
    }

    /// `Some(v)` when the function is the constant `v`.
    fn value(&self) -> Option<bool> {
        let t = self.0.as_ref()?;
        if t.iter().all(|w| *w == u64::MAX) {
            Some(true)
        } else if t.iter().all(|w| *w == 0) {
            Some(false)
        } else {
            None
        }
    }
}

/// Whether a line runs: the scan-model value, and its function of the jump conditions.
#[derive(Clone, Debug)]
struct Guard {
    value: BoolExpr,
    table: Table,
}

/// Where the lowering of a body stands.
struct Flow {
    /// Whether the current line runs.
    guard: Guard,
    cr: Cr,
    /// Jumps not yet reached: label key → (when taken, the CR they carry).
    pending: BTreeMap<String, Vec<(Guard, Cr)>>,
    /// How many jump conditions there have been.
    atoms: usize,
}

fn is_const(e: &BoolExpr, v: bool) -> bool {
    matches!(e, BoolExpr::Const(b) if *b == v)
}

impl Lowering<'_> {
    /// Lowers the lines of a program's IL body, one block per line that writes.
    pub(super) fn il_body(&mut self, lines: &[IlLine]) {
        for (span, line, stmts) in self.il_run(lines) {
            self.line = line;
            self.push_block(span, stmts);
        }
    }

    /// The statements of each line of an IL body: its span, its line number, what it does.
    pub(super) fn il_run(&mut self, lines: &[IlLine]) -> Vec<(Span, usize, Vec<Stmt>)> {
        let mut labels: BTreeMap<String, (usize, Span)> = BTreeMap::new();
        for (k, line) in lines.iter().enumerate() {
            let Some(l) = &line.label else { continue };
            if let Some((_, first)) = labels.get(&l.key()) {
                let mut e = StError::new(
                    l.span,
                    format!("the label `{}` is declared twice", l.name),
                    "declared again here",
                );
                e.related = Some(Box::new((*first, "first declared here".into())));
                self.errors.push(e);
            } else {
                labels.insert(l.key(), (k, l.span));
            }
        }
        let mut flow = Flow {
            guard: Guard { value: BoolExpr::Const(true), table: Table::constant(true) },
            cr: Cr::Unset,
            pending: BTreeMap::new(),
            atoms: 0,
        };
        let mut run = Vec::new();
        for (k, line) in lines.iter().enumerate() {
            self.line = self.line_of(line.span);
            let mut out = Vec::new();
            if let Some(l) = &line.label {
                self.join(&mut flow, &l.key(), &mut out);
            }
            if let Some(instr) = &line.instr {
                self.il_instr(instr, k, &labels, &mut flow, &mut out);
            }
            // The user functions a call's inputs call run before the line.
            let mut first = std::mem::take(&mut self.prelude);
            first.append(&mut out);
            run.push((line.span, self.line, first));
        }
        run
    }

    /// At a label: the guard is the fall-through's or that of a jump here; the CR is
    /// the one of whichever path came.
    fn join(&mut self, flow: &mut Flow, label: &str, out: &mut Vec<Stmt>) {
        let Some(jumps) = flow.pending.remove(label) else { return };
        let mut paths: Vec<(Guard, Cr)> = Vec::new();
        // A path whose value is FALSE still counts in the table (its condition is free there).
        let live = |g: &Guard| match g.table.value() {
            Some(v) => v,
            None => g.table.0.is_some() || !is_const(&g.value, false),
        };
        if live(&flow.guard) {
            paths.push((flow.guard.clone(), flow.cr.clone()));
        }
        paths.extend(jumps.into_iter().filter(|(g, _)| live(g)));
        match paths.as_slice() {
            [] => {
                flow.guard = Guard { value: BoolExpr::Const(false), table: Table::constant(false) }
            }
            [(g, cr)] => {
                flow.guard = g.clone();
                flow.cr = cr.clone();
            }
            _ => {
                let value = BoolExpr::Or(paths.iter().map(|(g, _)| g.value.clone()).collect());
                let table =
                    paths.iter().skip(1).fold(paths[0].0.table.clone(), |t, (g, _)| t.or(&g.table));
                flow.guard = self.guard(out, value, table);
                flow.cr = if paths.iter().all(|(_, c)| matches!(c, Cr::Bool(_))) {
                    // The paths exclude one another: the CR of the one taken.
                    let terms = paths.iter().map(|(g, c)| match c {
                        Cr::Bool(v) => BoolExpr::and(g.value.clone(), v.clone()),
                        _ => unreachable!("all BOOL"),
                    });
                    Cr::Bool(self.temp(out, BoolExpr::Or(terms.collect())))
                } else if paths.iter().all(|(_, c)| matches!(c, Cr::Unset)) {
                    Cr::Unset
                } else if let [(_, Cr::Int(Ok(first))), rest @ ..] = paths.as_slice()
                    && rest.iter().all(|(_, c)| matches!(c, Cr::Int(Ok(v)) if same(v, first)))
                {
                    // Every path carries the same integer (settled before its jump).
                    Cr::Int(Ok(first.clone()))
                } else if paths.iter().all(|(_, c)| matches!(c, Cr::Int(_))) {
                    Cr::Int(Err("the current result where jumps meet is not computed".into()))
                } else {
                    Cr::Other("a value of several types".into())
                };
            }
        }
    }

    /// Takes the CR as a scan-local value (so later writes leave what it read); an
    /// integer CR only where `ints` (before a call, which may write integers): a store
    /// into an integer leaves the CR that integer's value.
    fn settle(&mut self, flow: &mut Flow, out: &mut Vec<Stmt>, span: Span, ints: bool) {
        match &flow.cr {
            Cr::Bool(v) if !matches!(v, BoolExpr::Const(_) | BoolExpr::Temp(_)) => {
                let v = v.clone();
                flow.cr = Cr::Bool(self.temp(out, v));
            }
            Cr::Int(Ok(v)) if ints => {
                let v = v.clone();
                flow.cr = Cr::Int(Ok(self.int_temp(out, v, span)));
            }
            _ => {}
        }
    }

    /// The CR as a BOOL, for the instruction `word`.
    fn cr_bool(&mut self, cr: &Cr, word: &ast::Ident) -> BoolExpr {
        match cr {
            Cr::Bool(v) => v.clone(),
            Cr::Unset => {
                self.errors.push(StError::new(
                    word.span,
                    format!("`{}` reads the current result before any `LD` sets it", word.name),
                    "no current result here",
                ));
                BoolExpr::Const(false)
            }
            Cr::Other(_) | Cr::Int(_) => {
                self.errors.push(StError::new(
                    word.span,
                    format!(
                        "`{}` needs a BOOL current result, but it holds {}",
                        word.name,
                        cr.what()
                    ),
                    "expected a BOOL current result",
                ));
                BoolExpr::Const(false)
            }
        }
    }

    /// When a `C`/`CN` instruction acts (its condition is a new free variable of the
    /// guards' tables).
    fn when(
        &mut self,
        flow: &mut Flow,
        cond: IlCond,
        word: &ast::Ident,
        out: &mut Vec<Stmt>,
    ) -> Guard {
        let g = flow.guard.clone();
        if cond == IlCond::Always {
            return g;
        }
        let cr = self.cr_bool(&flow.cr, word);
        let atom = Table::atom(flow.atoms);
        flow.atoms += 1;
        let (c, t) = match cond {
            IlCond::IfTrue => (cr, atom),
            _ => (BoolExpr::negate(cr), atom.not()),
        };
        self.guard(out, BoolExpr::and(g.value, c), g.table.and(&t))
    }

    /// A guard from its value and table: a constant where the table is one.
    fn guard(&mut self, out: &mut Vec<Stmt>, value: BoolExpr, table: Table) -> Guard {
        let value = match table.value() {
            Some(v) => BoolExpr::Const(v),
            None => self.temp_unless_simple(out, value),
        };
        Guard { value, table }
    }

    /// What stays on this path after `leave` is taken.
    fn stay(&mut self, flow: &Flow, leave: &Guard, out: &mut Vec<Stmt>) -> Guard {
        let g = &flow.guard;
        let value = BoolExpr::and(g.value.clone(), BoolExpr::negate(leave.value.clone()));
        self.guard(out, value, g.table.and(&leave.table.not()))
    }

    fn il_instr(
        &mut self,
        instr: &IlInstr,
        at: usize,
        labels: &BTreeMap<String, (usize, Span)>,
        flow: &mut Flow,
        out: &mut Vec<Stmt>,
    ) {
        match instr {
            IlInstr::Op { op: IlOp::St | IlOp::S | IlOp::R, negate, operand, word, .. } => {
                self.settle(flow, out, word.span, false);
                let Some(target) = operand else { return };
                let stmts = match &instr {
                    IlInstr::Op { op: IlOp::St, .. } => {
                        let stmts = self.il_store(flow, target, *negate, word);
                        // The integer stored holds the CR's value now (same type).
                        if let (Cr::Int(Ok(v)), [Stmt::SetInt { target, .. }]) =
                            (&flow.cr, stmts.as_slice())
                            && let Some(t) = v.ty
                        {
                            flow.cr = Cr::Int(Ok(Int::var(target, t)));
                        }
                        stmts
                    }
                    IlInstr::Op { op, .. } => {
                        let set = *op == IlOp::S;
                        self.il_set(flow, target, set, word)
                    }
                    _ => unreachable!("matched above"),
                };
                out.extend(Stmt::guarded(&flow.guard.value, stmts, word.span));
            }
            IlInstr::Op { op, negate, operand, nested, word } => {
                let cr = std::mem::replace(&mut flow.cr, Cr::Unset);
                flow.cr = self.il_op(cr, op, *negate, operand.as_ref(), nested.as_deref(), word);
                // What the user functions it calls run (their variables are their own).
                out.append(&mut self.prelude);
            }
            IlInstr::Call { cond, instance, args, word } => {
                self.settle(flow, out, word.span, true);
                let when = self.when(flow, *cond, word, out);
                self.il_call(instance, args, None, &when.value, word, out);
            }
            IlInstr::FbInput { pin, instance, word } => {
                self.settle(flow, out, word.span, true);
                let v = self.cr_bool(&flow.cr, word);
                let guard = flow.guard.value.clone();
                self.il_call(instance, &[], Some((pin, v)), &guard, word, out);
            }
            IlInstr::Jump { cond, label, word } => {
                // An integer CR goes to the label as it is: if the jump is taken, nothing
                // between here and the label runs, so what it reads is unchanged there.
                self.settle(flow, out, word.span, false);
                let Some(&(target, _)) = labels.get(&label.key()) else {
                    let mut e = StError::new(
                        label.span,
                        format!("no label `{}` in this body", label.name),
                        "not declared",
                    );
                    let names: Vec<String> = labels.keys().cloned().collect();
                    if let Some(m) =
                        crate::diag::did_you_mean(&label.key(), names.iter().map(String::as_str))
                    {
                        e.notes.push(format!("did you mean `{m}`?"));
                    }
                    self.errors.push(e);
                    return;
                };
                if target <= at {
                    self.refuse(
                        word.span.to(label.span),
                        "a backward jump (a loop within the scan)",
                        "ii-prove models straight-line scans; jump only to later labels",
                    );
                    return;
                }
                let taken = self.when(flow, *cond, word, out);
                flow.guard = self.stay(flow, &taken, out);
                flow.pending.entry(label.key()).or_default().push((taken, flow.cr.clone()));
            }
            IlInstr::Return { cond, word } => {
                let leave = self.when(flow, *cond, word, out);
                flow.guard = self.stay(flow, &leave, out);
            }
            IlInstr::Assert(e, name) => {
                let reached =
                    (!is_const(&flow.guard.value, true)).then(|| flow.guard.value.clone());
                out.extend(self.assertion(e, name.as_ref(), reached));
            }
        }
    }

    /// A scan-local value of `e`, unless it is a constant, a variable or a value already.
    fn temp_unless_simple(&mut self, out: &mut Vec<Stmt>, e: BoolExpr) -> BoolExpr {
        let e = simplify(e);
        match e {
            BoolExpr::Const(_) | BoolExpr::Temp(_) => e,
            _ => self.temp(out, e),
        }
    }

    /// An operator on the CR: its new value (no write).
    fn il_op(
        &mut self,
        cr: Cr,
        op: &IlOp,
        negate: bool,
        operand: Option<&ast::Expr>,
        nested: Option<&[IlLine]>,
        word: &ast::Ident,
    ) -> Cr {
        let not = |v: Cr| match v {
            Cr::Bool(b) if negate => Cr::Bool(BoolExpr::negate(b)),
            Cr::Int(_) if negate => {
                Cr::Int(Err(format!("the bitwise `{}N` is not computed", word.name)))
            }
            v => v,
        };
        let bitwise = || Cr::Int(Err(format!("the bitwise `{}` is not computed", word.name)));
        let rhs = |l: &mut Self| -> Cr {
            match nested {
                Some(lines) => {
                    let first = operand.map_or(Cr::Unset, |e| l.il_value(e));
                    not(l.il_nested(first, lines))
                }
                None => not(operand.map_or(Cr::Unset, |e| l.il_value(e))),
            }
        };
        match op {
            IlOp::Ld => rhs(self),
            IlOp::Not => match cr {
                Cr::Bool(b) => Cr::Bool(BoolExpr::negate(b)),
                Cr::Unset => Cr::Bool(self.cr_bool(&cr, word)),
                Cr::Int(_) => bitwise(),
                other => other,
            },
            IlOp::Bin(b @ (BinOp::And | BinOp::Or | BinOp::Xor)) => {
                let r = rhs(self);
                match (cr, r) {
                    (Cr::Bool(a), Cr::Bool(c)) => Cr::Bool(match b {
                        BinOp::And => BoolExpr::and(a, c),
                        BinOp::Or => BoolExpr::Or(vec![a, c]),
                        _ => super::expr::xor(a, c),
                    }),
                    (Cr::Unset, _) | (_, Cr::Unset) => Cr::Bool(self.cr_bool(&Cr::Unset, word)),
                    (Cr::Other(t), _) | (_, Cr::Other(t)) => Cr::Other(t),
                    (Cr::Int(_), _) | (_, Cr::Int(_)) => bitwise(),
                }
            }
            IlOp::Bin(
                b @ (BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Le | BinOp::Gt | BinOp::Ge),
            ) => {
                let r = rhs(self);
                match (cr, r) {
                    (Cr::Bool(a), Cr::Bool(c)) if matches!(b, BinOp::Eq | BinOp::Ne) => {
                        let x = super::expr::xor(a, c);
                        Cr::Bool(if *b == BinOp::Ne { x } else { BoolExpr::negate(x) })
                    }
                    (Cr::Unset, _) => Cr::Bool(self.cr_bool(&Cr::Unset, word)),
                    (Cr::Int(a), Cr::Int(c)) => {
                        let span = operand.map_or(word.span, |e| word.span.to(e.span));
                        let op = super::expr::comparison_op(*b);
                        Cr::Bool(match (a, c) {
                            (Ok(a), Ok(c)) => self.int_compare_values(op, a, c, span),
                            (Err(why), _) | (_, Err(why)) => {
                                self.unknown_comparison(op, span, &why)
                            }
                        })
                    }
                    _ => {
                        let name = word.name.to_ascii_uppercase();
                        let span = operand.map_or(word.span, |e| word.span.to(e.span));
                        Cr::Bool(self.comparison(&name, span))
                    }
                }
            }
            IlOp::Bin(b) => {
                let r = rhs(self);
                let span = operand.map_or(word.span, |e| word.span.to(e.span));
                match (cr, r) {
                    (Cr::Int(Ok(a)), Cr::Int(Ok(c))) => Cr::Int(self.il_arithmetic(*b, a, c, span)),
                    (Cr::Int(Err(why)), _) | (_, Cr::Int(Err(why))) => Cr::Int(Err(why)),
                    (Cr::Unset, _) => {
                        let _ = self.cr_bool(&Cr::Unset, word);
                        Cr::Unset
                    }
                    (a, c) => Cr::Int(Err(format!(
                        "`{}` of {} and {} is not computed",
                        word.name,
                        a.what(),
                        c.what()
                    ))),
                }
            }
            IlOp::Function(f) => self.il_function(cr, f, operand),
            IlOp::St | IlOp::S | IlOp::R => unreachable!("writes are lowered by il_instr"),
        }
    }

    /// The lines of `OP( … )`, from the CR `first`: only operators on the CR.
    fn il_nested(&mut self, first: Cr, lines: &[IlLine]) -> Cr {
        let mut cr = first;
        for line in lines {
            match &line.instr {
                Some(IlInstr::Op { op, negate, operand, nested, word })
                    if !matches!(op, IlOp::St | IlOp::S | IlOp::R) =>
                {
                    cr = self.il_op(cr, op, *negate, operand.as_ref(), nested.as_deref(), word);
                }
                _ => {
                    self.refuse(
                        line.span,
                        "a write, jump, call or return inside `( … )`",
                        "parentheses compute an operand; write, jump or call after the `)`",
                    );
                    return Cr::Unset;
                }
            }
        }
        cr
    }

    /// An operand's value.
    fn il_value(&mut self, e: &ast::Expr) -> Cr {
        if self.is_bool(e) {
            return Cr::Bool(self.bool_expr(e));
        }
        match &e.kind {
            ExprKind::Var(id) => match self.lookup(id) {
                // Instruction List keeps a REAL in its current result: not computed yet.
                Some(Sym { ty: Ty::Int(t), .. }) if !t.real => Cr::Int(self.int_expr(e)),
                Some(Sym { ty, .. }) if ty.value_type().is_some() => {
                    Cr::Other(format!("a {}", ty.value_type().unwrap_or_default()))
                }
                Some(Sym { ty: Ty::Fb(_, t) | Ty::User(t), name, .. }) => {
                    self.errors.push(StError::new(
                        e.span,
                        format!("the {t} instance `{name}` where a value is expected"),
                        "expected a variable or a literal",
                    ));
                    Cr::Unset
                }
                _ => Cr::Unset,
            },
            ExprKind::Member(of, field) => {
                if let ExprKind::Var(id) = &of.kind {
                    let _ = self.lookup(id);
                }
                Cr::Other(format!("the output {}", field.name))
            }
            ExprKind::Int(_) | ExprKind::Unary(ast::UnOp::Neg, _) => Cr::Int(self.int_expr(e)),
            ExprKind::Time(_) => Cr::Other("a duration".into()),
            ExprKind::Literal(s)
                if s.split_once('#').is_some_and(|(t, _)| {
                    super::ints::int_type(&t.to_ascii_uppercase()).is_some()
                }) =>
            {
                Cr::Int(self.int_expr(e))
            }
            ExprKind::Literal(s) => Cr::Other(format!("the literal {s}")),
            _ => {
                let _ = self.bool_expr(e);
                Cr::Unset
            }
        }
    }

    /// A function as an operator: the CR is its first argument.
    fn il_function(&mut self, cr: Cr, f: &ast::Ident, operand: Option<&ast::Expr>) -> Cr {
        let args: Vec<&ast::Expr> = match operand.map(|e| &e.kind) {
            Some(ExprKind::Call(_, args)) => args
                .iter()
                .map(|a| match a {
                    ast::Arg::Positional(x) | ast::Arg::Input(_, x) | ast::Arg::Output(_, _, x) => {
                        x
                    }
                })
                .collect(),
            _ => Vec::new(),
        };
        let key = f.key();
        if self.user.get(&key).is_some_and(|p| p.kind == ast::PouKind::Function) {
            let first = match cr {
                Cr::Bool(v) => Some(v),
                _ => None,
            };
            let rest: Vec<ast::Arg> =
                args.iter().map(|e| ast::Arg::Positional((*e).clone())).collect();
            return match self.user_function(f, first, &rest) {
                Some(v) => Cr::Bool(v),
                None => Cr::Other(format!("the result of {}", f.name)),
            };
        }
        let values: Vec<Cr> = args.iter().map(|e| self.il_value(e)).collect();
        match (key.as_str(), &cr, values.as_slice()) {
            ("MOVE", _, []) => cr,
            (k, Cr::Int(v), []) if k.ends_with("_TO_BOOL") => {
                let from = &k[..k.len() - "_TO_BOOL".len()];
                Cr::Bool(self.value_to_bool(f, from, v.clone(), f.span))
            }
            ("SEL", Cr::Bool(g), [Cr::Bool(a), Cr::Bool(b)]) => Cr::Bool(BoolExpr::Or(vec![
                BoolExpr::and(BoolExpr::negate(g.clone()), a.clone()),
                BoolExpr::and(g.clone(), b.clone()),
            ])),
            _ => Cr::Other(format!("the result of {}", f.name)),
        }
    }

    /// `ST x`/`STN x`.
    fn il_store(
        &mut self,
        flow: &Flow,
        target: &ast::Expr,
        negate: bool,
        word: &ast::Ident,
    ) -> Vec<Stmt> {
        let span = word.span.to(target.span);
        match (&target.kind, &flow.cr) {
            (ExprKind::Var(id), Cr::Other(_) | Cr::Int(_)) => match self.lookup(id) {
                Some(Sym { ty: Ty::Int(t), name, .. }) => {
                    let v = match &flow.cr {
                        Cr::Int(v) => v.clone(),
                        cr => Err(format!("`{}` stores {} into it", word.name, cr.what())),
                    };
                    self.int_store(&name, t, v, span, span)
                }
                Some(Sym { ty, name, .. }) if ty.value_type().is_some() => {
                    let t = ty.value_type().unwrap_or_default();
                    vec![super::ints::integer_write(
                        span,
                        &word.name.to_ascii_uppercase(),
                        &t,
                        &name,
                    )]
                }
                Some(_) => {
                    self.errors.push(StError::new(
                        span,
                        format!(
                            "`{}` stores {} into the BOOL `{}`",
                            word.name,
                            flow.cr.what(),
                            id.name
                        ),
                        "expected a BOOL current result",
                    ));
                    Vec::new()
                }
                None => Vec::new(),
            },
            (ExprKind::Member(..), _) => {
                self.refuse(
                    target.span,
                    "writing a function block's input outside its call",
                    "give it in the call: `CAL T1(IN := …, PT := …)`",
                );
                Vec::new()
            }
            _ => {
                let v = self.cr_bool(&flow.cr, word);
                let v = if negate { BoolExpr::negate(v) } else { v };
                if let ExprKind::Var(id) = &target.kind
                    && let Some(t) = self.syms.get(&id.key()).and_then(|s| s.ty.value_type())
                {
                    self.errors.push(StError::new(
                        span,
                        format!("`{}` stores a BOOL into the {t} `{}`", word.name, id.name),
                        "expected a BOOL variable",
                    ));
                    return Vec::new();
                }
                self.assign_value(target, v, span)
            }
        }
    }

    /// `S x`/`R x`: set or reset a BOOL when the CR is TRUE; with an instance, its input.
    fn il_set(
        &mut self,
        flow: &mut Flow,
        target: &ast::Expr,
        set: bool,
        word: &ast::Ident,
    ) -> Vec<Stmt> {
        if let ExprKind::Var(id) = &target.kind
            && let Some(Sym { ty: Ty::Fb(..), .. }) = self.syms.get(&id.key())
        {
            let v = self.cr_bool(&flow.cr, word);
            let pin = if set { "S" } else { "R" };
            let mut out = Vec::new();
            let guard = BoolExpr::Const(true);
            self.il_call(target, &[], Some((pin, v)), &guard, word, &mut out);
            return out;
        }
        let v = self.cr_bool(&flow.cr, word);
        let kind = if set { WriteKind::Set } else { WriteKind::Reset };
        self.write_value(target, kind, v, word.span.to(target.span))
    }

    /// A call, run when `when` holds (a call a jump, a return or `CALC` may skip is the
    /// block run only at the scans it is called, as matiec runs it).
    fn il_call(
        &mut self,
        instance: &ast::Expr,
        args: &[ast::Arg],
        given: Option<(&str, BoolExpr)>,
        when: &BoolExpr,
        word: &ast::Ident,
        out: &mut Vec<Stmt>,
    ) {
        let span = word.span.to(instance.span);
        let stmts = self.call_with(instance, args, given, span);
        out.extend(Stmt::guarded(when, stmts, span));
    }
}

/// Constant folding of `∧`/`∨`/`¬` over `TRUE`/`FALSE`.
fn simplify(e: BoolExpr) -> BoolExpr {
    match e {
        BoolExpr::And(a, b) => match (simplify(*a), simplify(*b)) {
            (BoolExpr::Const(false), _) | (_, BoolExpr::Const(false)) => BoolExpr::Const(false),
            (BoolExpr::Const(true), x) | (x, BoolExpr::Const(true)) => x,
            (x, y) => BoolExpr::and(x, y),
        },
        BoolExpr::Not(a) => match simplify(*a) {
            BoolExpr::Const(b) => BoolExpr::Const(!b),
            x => BoolExpr::negate(x),
        },
        other => other,
    }
}

/// Whether two settled integers (a hidden variable or a literal) are the same value.
fn same(a: &Int, b: &Int) -> bool {
    a.ty == b.ty
        && match (&a.e, &b.e) {
            (IntExpr::Var(x), IntExpr::Var(y)) => x == y,
            (IntExpr::Const(x), IntExpr::Const(y)) => x == y,
            _ => false,
        }
}
