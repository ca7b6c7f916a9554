//! Control flow of Structured Text in the scan model: statement lists with `EXIT`, `CONTINUE` and `RETURN` as hidden guard bits, and `FOR`, `WHILE` and `REPEAT` loops unrolled to the number of iterations the values known before the scan give.
//!
//! A body with a `RETURN` has a hidden bit (`_RETURN`) set `FALSE` where the body starts
//! and `TRUE` at the `RETURN`; a loop with an `EXIT` or `CONTINUE` has one for each
//! (`_EXIT_L07`, `_CONTINUE_L07`), the first set `FALSE` before the loop, the second at
//! the start of each iteration. Every statement after one that may set such a bit runs
//! under `IF NOT (bits)`, and every iteration after the first under `IF NOT (exit OR
//! return)`, counter update included: as matiec's C runs `break`, `continue` and `goto
//! END` (a `FOR` counter keeps the value of the iteration that left). A `WHILE` or
//! `REPEAT` loop is unrolled while its condition, computed from the values known at
//! that point ([`super::known`]), says to go on; a condition that reads a value not known
//! there, or more than [`MAX_ITERATIONS`] iterations, is refused with a located error.

use super::{Lowering, Sym, Ty};
use crate::diag::Span;
use crate::iec::StError;
use crate::iec::ast::{self, StmtKind};
use crate::program::{Block, BoolExpr, IntExpr, Stmt, WriteKind};

/// The most iterations a loop is unrolled to.
pub(super) const MAX_ITERATIONS: u64 = 10_000;

/// The guard bits of a body being lowered (a program's, a function block's or a
/// function's).
#[derive(Default)]
pub(super) struct Frame {
    /// Set by `RETURN` (none when the body has no `RETURN`).
    ret: Option<String>,
    /// The loops being lowered in it, innermost last.
    loops: Vec<LoopBits>,
}

/// A loop's guard bits (none for a loop without `EXIT`, `CONTINUE`).
#[derive(Clone)]
struct LoopBits {
    exit: Option<String>,
    cont: Option<String>,
}

/// Whether `stmts` hold a statement `want` accepts, in branches and (`into_loops`) in
/// nested loops.
fn has(stmts: &[ast::Stmt], want: fn(&StmtKind) -> bool, into_loops: bool) -> bool {
    stmts.iter().any(|s| {
        want(&s.kind)
            || match &s.kind {
                StmtKind::If(branches, otherwise) => {
                    branches.iter().any(|(_, b)| has(b, want, into_loops))
                        || has(otherwise, want, into_loops)
                }
                StmtKind::Case(_, arms, otherwise) => {
                    arms.iter().any(|(_, b)| has(b, want, into_loops))
                        || has(otherwise, want, into_loops)
                }
                StmtKind::For(.., body) | StmtKind::While(_, body) | StmtKind::Repeat(body, _) => {
                    into_loops && has(body, want, into_loops)
                }
                _ => false,
            }
    })
}

fn is_return(k: &StmtKind) -> bool {
    matches!(k, StmtKind::Return)
}

/// Whether `s` may set a guard bit of the body or loop it stands in (an `EXIT` or
/// `CONTINUE` of a nested loop is that loop's).
fn jumps(s: &ast::Stmt) -> bool {
    let one = std::slice::from_ref(s);
    has(one, |k| matches!(k, StmtKind::Exit | StmtKind::Continue), false)
        || has(one, is_return, true)
}

/// `x := FALSE`.
fn reset(x: &str, span: Span) -> Stmt {
    Stmt::Write {
        target: x.to_string(),
        kind: WriteKind::Assign,
        value: BoolExpr::Const(false),
        span,
    }
}

/// `IF NOT (bits) THEN stmts END_IF` (no bits: `stmts`).
fn unless(bits: Vec<&String>, stmts: Vec<Stmt>, span: Span) -> Vec<Stmt> {
    if bits.is_empty() {
        return stmts;
    }
    let stop = BoolExpr::Or(bits.into_iter().map(|x| BoolExpr::var(x)).collect());
    Stmt::guarded(&BoolExpr::negate(stop), stmts, span)
}

impl Lowering<'_> {
    /// The first scan sets every BOOL whose initial value is TRUE, before any statement
    /// (an input's initial value is the outside's business).
    pub(super) fn starts(&mut self) {
        let inputs = &self.inputs;
        self.starts.retain(|x| !inputs.contains(x));
        if self.starts.is_empty() {
            return;
        }
        let started = self.unique("_STARTED");
        self.started = Some(started.clone());
        let first = BoolExpr::negate(BoolExpr::var(&started));
        let span = self.syms.values().next().map_or(Span::new(0, 0..0), |s| s.span);
        let mut stmts: Vec<Stmt> = self
            .starts
            .iter()
            .map(|x| Stmt::Write {
                target: x.clone(),
                kind: WriteKind::Set,
                value: first.clone(),
                span,
            })
            .collect();
        stmts.push(Stmt::Write {
            target: started,
            kind: WriteKind::Assign,
            value: BoolExpr::Const(true),
            span,
        });
        self.blocks.insert(0, Block { number: 0, label: Some("L00_init".into()), span, stmts });
    }

    fn frame(&mut self) -> &mut Frame {
        if self.frames.is_empty() {
            self.frames.push(Frame::default());
        }
        self.frames.last_mut().expect("a frame")
    }

    /// The bits a jump in the current statement list sets: the body's `RETURN`, the
    /// innermost loop's `EXIT` and (`cont`) `CONTINUE`.
    fn stop_bits(&mut self, cont: bool) -> Vec<String> {
        let f = self.frame();
        let mut bits: Vec<String> = f.ret.iter().cloned().collect();
        if let Some(l) = f.loops.last() {
            bits.extend(l.exit.iter().cloned());
            if cont {
                bits.extend(l.cont.iter().cloned());
            }
        }
        bits
    }

    /// Whether the body's `RETURN` or the innermost loop's `EXIT` is known to have run.
    fn stopped(&mut self) -> bool {
        let bits = self.stop_bits(false);
        bits.iter().any(|x| self.known.is_set(x))
    }

    /// A hidden bit of the statement at `span` (the same each time it is lowered: it is
    /// set where its loop or body starts).
    fn flow_bit(&mut self, span: Span, kind: &'static str) -> String {
        if let Some(x) = self.flow_bits.get(&(span, kind)) {
            return x.clone();
        }
        let x = match kind {
            "RETURN" => self.unique("_RETURN"),
            _ => self.unique(&format!("_{kind}_L{:02}", self.line_of(span))),
        };
        self.flow_bits.insert((span, kind), x.clone());
        x
    }

    /// Starts a body (`span` its first statement): its `RETURN` bit, if it has one, and
    /// the statements that clear it.
    pub(super) fn enter_body(&mut self, body: &[ast::Stmt], span: Span) -> Vec<Stmt> {
        let ret = has(body, is_return, true).then(|| self.flow_bit(span, "RETURN"));
        let out: Vec<Stmt> = ret.iter().map(|x| reset(x, span)).collect();
        if let Some(x) = &ret {
            self.known.assumed.insert(x.clone());
        }
        self.frames.push(Frame { ret, loops: Vec::new() });
        out
    }

    pub(super) fn leave_body(&mut self) {
        if let Some(Frame { ret: Some(x), .. }) = self.frames.pop() {
            self.known.assumed.remove(&x);
        }
    }

    /// A property comment: the bit `assert_NAME` takes the asserted value here (where
    /// `reached` is given, only the scans that reach this point count).
    pub(super) fn assertion(
        &mut self,
        e: &ast::Expr,
        name: Option<&crate::iec::ast::Ident>,
        reached: Option<BoolExpr>,
    ) -> Vec<Stmt> {
        let mut value = self.bool_expr(e);
        if let Some(g) = reached {
            value = BoolExpr::Or(vec![BoolExpr::negate(g), value]);
        }
        let name = match name {
            Some(n) => n.name.clone(),
            None => format!("ASSERT_L{:02}", self.line),
        };
        let signal = self.unique(&format!("assert_{name}"));
        self.asserts.push(super::Assertion { name, signal: signal.clone(), span: e.span });
        vec![Stmt::Write { target: signal, kind: WriteKind::Assign, value, span: e.span }]
    }

    /// One run of the program `pou`, at every scan: its `VAR_TEMP` variables set to their
    /// initial values (a block of its own, at their declaration's line), then its body.
    pub(super) fn program_run(&mut self, pou: &ast::Pou) {
        let names = self.syms.clone();
        let resets = self.temp_resets(pou, &names);
        if let Some(v) = pou.vars.iter().find(|v| v.class == ast::VarClass::Temp) {
            self.line = self.line_of(v.name.span);
            self.run_known(&resets);
            self.push_block(v.name.span, resets);
        }
        match &pou.body {
            ast::Body::St(stmts) => self.program_body(stmts),
            ast::Body::Il(lines) => {
                self.il = true;
                self.il_body(lines)
            }
            // Turned into Structured Text before lowering (`sfc::desugar`).
            ast::Body::Sfc(_) => {}
        }
    }

    /// A program's body: a block per top-level statement; after a statement that may
    /// `RETURN`, each block under `IF NOT _RETURN` (an `#ASSERT` counts only on the scans
    /// that reach it).
    pub(super) fn program_body(&mut self, stmts: &[ast::Stmt]) {
        let Some(first) = stmts.first() else { return };
        let mut clear = self.enter_body(stmts, first.span);
        let mut returned = false;
        for s in stmts {
            self.line = self.line_of(s.span);
            let saved = self.known.clone();
            self.reached = returned.then(|| self.stop_bits(false)).map(|bits| {
                BoolExpr::negate(BoolExpr::Or(bits.iter().map(|x| BoolExpr::var(x)).collect()))
            });
            let mut lowered = self.stmt(s, 0);
            self.reached = None;
            self.known = saved;
            if returned && !matches!(s.kind, StmtKind::Assert(..)) {
                let bits = self.stop_bits(false);
                lowered = unless(bits.iter().collect(), lowered, s.span);
            }
            lowered.splice(0..0, std::mem::take(&mut clear));
            self.run_known(&lowered);
            self.push_block(s.span, lowered);
            returned |= jumps(s);
        }
        self.leave_body();
        // The next program starts from values that depend on where this one returned.
        self.known.clear();
    }

    /// A statement list run in order (`lines`: each statement names the current line);
    /// after a statement that may jump, the rest under `IF NOT (bits)`.
    pub(super) fn seq(&mut self, stmts: &[ast::Stmt], depth: usize, lines: bool) -> Vec<Stmt> {
        let mut out = Vec::new();
        for (k, s) in stmts.iter().enumerate() {
            if lines {
                self.line = self.line_of(s.span);
            }
            let saved = self.known.clone();
            let lowered = self.stmt(s, depth);
            self.known = saved;
            self.run_known(&lowered);
            out.extend(lowered);
            let rest = &stmts[k + 1..];
            if let (Some(a), Some(b)) = (rest.first(), rest.last())
                && jumps(s)
            {
                let saved = self.known.clone();
                let body = self.seq(rest, depth, lines);
                self.known = saved;
                let bits = self.stop_bits(true);
                let guarded = unless(bits.iter().collect(), body, a.span.to(b.span));
                self.run_known(&guarded);
                out.extend(guarded);
                break;
            }
        }
        out
    }

    /// The statements of a branch (run from the values known before the choice).
    pub(super) fn branch(&mut self, stmts: &[ast::Stmt], depth: usize) -> Vec<Stmt> {
        let saved = self.known.clone();
        let out = self.seq(stmts, depth, false);
        self.known = saved;
        out
    }

    /// `EXIT`, `CONTINUE`, `RETURN`: its bit set.
    pub(super) fn jump(&mut self, s: &ast::Stmt) -> Vec<Stmt> {
        let f = self.frame();
        let (bit, word) = match s.kind {
            StmtKind::Exit => (f.loops.last().and_then(|l| l.exit.clone()), "EXIT"),
            StmtKind::Continue => (f.loops.last().and_then(|l| l.cont.clone()), "CONTINUE"),
            _ => (f.ret.clone(), "RETURN"),
        };
        match bit {
            Some(x) => vec![Stmt::Write {
                target: x,
                kind: WriteKind::Assign,
                value: BoolExpr::Const(true),
                span: s.span,
            }],
            None => {
                self.errors.push(StError::new(
                    self.keyword(s.span),
                    format!("`{word}` outside a loop"),
                    "it leaves the innermost FOR, WHILE or REPEAT loop of this body",
                ));
                Vec::new()
            }
        }
    }

    /// Starts a loop (`span`: the loop statement): its bits, and the statements that
    /// clear its `EXIT` bit.
    fn enter_loop(&mut self, span: Span, body: &[ast::Stmt]) -> (LoopBits, Vec<Stmt>) {
        let exit =
            has(body, |k| matches!(k, StmtKind::Exit), false).then(|| self.flow_bit(span, "EXIT"));
        let cont = has(body, |k| matches!(k, StmtKind::Continue), false)
            .then(|| self.flow_bit(span, "CONTINUE"));
        let bits = LoopBits { exit, cont };
        let clear: Vec<Stmt> = bits.exit.iter().map(|x| reset(x, span)).collect();
        self.run_known(&clear);
        if let Some(x) = &bits.exit {
            self.known.assumed.insert(x.clone());
        }
        self.frame().loops.push(bits.clone());
        (bits, clear)
    }

    fn leave_loop(&mut self, bits: &LoopBits) {
        self.frame().loops.pop();
        if let Some(x) = &bits.exit {
            self.known.assumed.remove(x);
        }
    }

    /// One iteration: `head` (a counter's update), the `CONTINUE` bit cleared, the body;
    /// after the first (`later`), under `IF NOT (exit OR return)`.
    fn iteration(
        &mut self,
        bits: &LoopBits,
        head: Vec<Stmt>,
        body: &[ast::Stmt],
        depth: usize,
        later: bool,
        span: Span,
    ) -> Vec<Stmt> {
        let stop = if later { self.stop_bits(false) } else { Vec::new() };
        let mut iter = head;
        iter.extend(bits.cont.iter().map(|x| reset(x, span)));
        self.run_known(&iter);
        iter.extend(self.seq(body, depth + 1, false));
        unless(stop.iter().collect(), iter, span)
    }

    /// `FOR var := from TO to BY by DO body END_FOR`, unrolled as matiec runs it: the
    /// counter starts at the first value and takes the next before each later iteration
    /// (it ends at the last value, or at the value of the iteration an `EXIT` left).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn for_loop(
        &mut self,
        s: &ast::Stmt,
        var: &ast::Ident,
        (from, to, by): (&ast::Expr, &ast::Expr, Option<&ast::Expr>),
        body: &[ast::Stmt],
        depth: usize,
    ) -> Vec<Stmt> {
        let Some((first, step, count)) = self.iterations(var, from, to, by, s.span) else {
            return Vec::new();
        };
        let counter = match self.lookup(var) {
            Some(Sym { ty: Ty::Int(t), name, .. }) if !self.opaque.contains_key(&name) => {
                Some((name, t))
            }
            _ => None,
        };
        let (bits, mut out) = self.enter_loop(s.span, body);
        let errors = self.errors.len();
        for k in 0..count.max(1) {
            if self.stopped() {
                break;
            }
            let head: Vec<Stmt> = counter
                .iter()
                .map(|(name, t)| Stmt::SetInt {
                    target: name.clone(),
                    value: IntExpr::Const(t.wrap(first + step * k as i64)),
                    span: var.span,
                })
                .collect();
            if count == 0 {
                self.run_known(&head);
                out.extend(head);
                break;
            }
            let iter = self.iteration(&bits, head, body, depth, k > 0, s.span);
            // The update in `head` writes it once; the body must not.
            let mut writes = 0;
            for s in &iter {
                s.visit(
                    &mut |s| {
                        writes += usize::from(matches!((s, &counter), (Stmt::SetInt { target, .. }, Some((c, _))) if target == c))
                    },
                    &mut |_| {},
                );
            }
            if writes > usize::from(counter.is_some()) {
                self.refuse(
                    var.span,
                    "a FOR loop whose body writes its counter",
                    "the number of iterations then depends on the scan",
                );
                break;
            }
            out.extend(iter);
            if self.errors.len() > errors {
                break;
            }
        }
        self.leave_loop(&bits);
        out
    }

    /// `WHILE cond DO body END_WHILE` (`repeat`: `REPEAT body UNTIL cond END_REPEAT`),
    /// unrolled while the condition, known at each test, goes on.
    pub(super) fn while_loop(
        &mut self,
        s: &ast::Stmt,
        cond: &ast::Expr,
        body: &[ast::Stmt],
        depth: usize,
        repeat: bool,
    ) -> Vec<Stmt> {
        let word = if repeat { "REPEAT" } else { "WHILE" };
        let (bits, mut out) = self.enter_loop(s.span, body);
        let errors = self.errors.len();
        let mut n = 0u64;
        let ok = loop {
            if self.stopped() {
                break true;
            }
            if !repeat {
                match self.loop_condition(cond, word) {
                    Some(true) => {}
                    Some(false) => break true,
                    None => break false,
                }
            }
            n += 1;
            if n > MAX_ITERATIONS {
                self.errors.push(StError::new(
                    self.keyword(s.span),
                    format!("this {word} loop runs more than {MAX_ITERATIONS} iterations"),
                    format!("ii-prove unrolls loops of at most {MAX_ITERATIONS} iterations"),
                ));
                break false;
            }
            let iter = self.iteration(&bits, Vec::new(), body, depth, n > 1, s.span);
            out.extend(iter);
            if self.errors.len() > errors {
                break false;
            }
            if repeat && !self.stopped() {
                match self.loop_condition(cond, word) {
                    Some(true) => break true,
                    Some(false) => {}
                    None => break false,
                }
            }
        };
        self.leave_loop(&bits);
        if ok { out } else { Vec::new() }
    }

    /// The value of a loop's condition at this test, else `None` with a located error
    /// naming what is not known.
    fn loop_condition(&mut self, cond: &ast::Expr, word: &str) -> Option<bool> {
        let (errors, prelude) = (self.errors.len(), self.prelude.len());
        let c = self.bool_expr(cond);
        if self.errors.len() > errors {
            return None;
        }
        let detail = if self.prelude.len() > prelude {
            self.prelude.truncate(prelude);
            "it calls a function".to_string()
        } else {
            match self.known_bool(&c) {
                Ok(v) => return Some(v),
                Err(what) => format!("it reads {what}"),
            }
        };
        self.errors.push(StError::new(
            cond.span,
            format!("the condition of this {word} loop is not known before the scan: {detail}"),
            "ii-prove unrolls a loop only when the values that count its iterations are fixed by assignments earlier in the same scan",
        ));
        None
    }
}
