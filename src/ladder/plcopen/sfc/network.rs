//! Ladder and FBD networks inside a chart (a condition wired to contacts or variables, a transition or an action whose body is LD or FBD) as the Structured Text Beremiz's `PLCGenerator.py` writes for them (`ComputeExpression`, `ComputeProgram`).
//!
//! A network's value is the OR of the paths wired to a pin; a contact is its variable
//! (`NOT(v)` when negated) AND the paths wired to it; a left rail is `TRUE`; a variable
//! is its expression; a continuation is its connector's value, computed once for the
//! whole POU as the generator does; a function block's output is `instance.pin`, the
//! block being called (`instance(IN := …);`) the first time a path reaches it; a
//! function's output is the variable the generator declares for it (`_TMP_AND8_OUT`,
//! assigned the first time a path reaches it); a path back to a block reads what it gave
//! at its last call. A body is its coils and output variables, then its blocks not yet
//! called, each list in the statement order `--order` chooses (by position when none:
//! the loader compares the two orders where they differ): `v := e;`, `v := NOT(e);`,
//! `IF e THEN v := TRUE; END_IF;`. Refused with a located error: `EN`/`ENO`, in-out
//! pins, edges (`R_TRIG` instances the generator declares), execution order numbers, a
//! function whose result's type is not known here, a text with operators pasted next to
//! another operand (the generator pastes it without parentheses), a loop through no
//! block, and objects that are no network element.

use std::collections::{BTreeMap, BTreeSet};

use crate::diag::{Sources, Span};
use crate::iec::StError;
use crate::iec::ast::{Arg, BinOp, Expr, ExprKind, Ident, Stmt, StmtKind, UnOp, VarClass, VarDecl};

use super::super::select::geometric;
use super::super::{Project, StatementOrder, Var};

type Node<'a, 'i> = roxmltree::Node<'a, 'i>;

/// One LD or FBD body (or the chart's own body, for conditions drawn in it).
pub(super) struct Net<'g, 'a, 'i> {
    pub sources: &'g mut Sources,
    pub project: &'g Project,
    /// The body's objects by `localId`.
    pub nodes: BTreeMap<u64, Node<'a, 'i>>,
    /// Connectors' values, by name, for the whole POU (the generator's `ComputedConnectors`).
    pub connectors: &'g mut BTreeMap<String, Expr>,
    /// The blocks already called (by where they start in the file).
    pub called: &'g mut BTreeSet<usize>,
    /// The calls written so far.
    pub out: Vec<Stmt>,
    pub visiting: BTreeSet<usize>,
    /// The statement order `--order` chooses (by position when none).
    pub order: Option<StatementOrder>,
    /// The POU's variables.
    pub vars: &'g [Var],
    /// The functions already computed (by where they start in the file), with their
    /// result variable; those variables' declarations.
    pub functions: &'g mut BTreeMap<usize, Expr>,
    pub temps: &'g mut Vec<VarDecl>,
}

fn child<'a, 'i>(n: Node<'a, 'i>, name: &str) -> Option<Node<'a, 'i>> {
    n.children().find(|c| c.is_element() && c.tag_name().name() == name)
}

fn elements<'a, 'i>(n: Node<'a, 'i>, name: &'static str) -> impl Iterator<Item = Node<'a, 'i>> {
    n.children().filter(move |c| c.is_element() && c.tag_name().name() == name)
}

fn flag(n: Node, name: &str) -> bool {
    n.attribute(name).is_some_and(|v| v.trim() == "true" || v.trim() == "1")
}

fn edge(n: Node) -> bool {
    n.attribute("edge").is_some_and(|v| v.trim() != "none" && !v.trim().is_empty())
}

/// An edge, or a `set`/`reset` storage, on what is no coil: the generator's
/// `ExtractModifier` writes an instance or an `IF` of its own for it.
fn modified(n: Node) -> bool {
    edge(n) || n.attribute("storage").is_some_and(|v| matches!(v.trim(), "set" | "reset"))
}

pub(super) fn local_ids<'a, 'i>(body: Node<'a, 'i>) -> BTreeMap<u64, Node<'a, 'i>> {
    body.children()
        .filter(|c| c.is_element())
        .filter_map(|c| Some((c.attribute("localId")?.trim().parse().ok()?, c)))
        .collect()
}

fn binary(op: BinOp, a: Expr, b: Expr) -> Expr {
    let span = a.span;
    Expr { kind: ExprKind::Binary(op, Box::new(a), Box::new(b)), span }
}

fn not(e: Expr, span: Span) -> Expr {
    Expr { kind: ExprKind::Unary(UnOp::Not, Box::new(e)), span }
}

fn is_true(e: &Expr) -> bool {
    matches!(e.kind, ExprKind::Bool(true))
}

/// The statements of an LD or FBD body in document order: its coils and output
/// variables, its blocks, its connectors.
struct Statements<'a, 'i> {
    outs: Vec<Node<'a, 'i>>,
    blocks: Vec<Node<'a, 'i>>,
    connectors: Vec<Node<'a, 'i>>,
}

impl<'a, 'i> Statements<'a, 'i> {
    /// The statements of `body`, or the object with an execution order number.
    fn of(body: Node<'a, 'i>) -> Result<Self, Node<'a, 'i>> {
        let mut lists = Statements { outs: Vec::new(), blocks: Vec::new(), connectors: Vec::new() };
        for n in body.children().filter(|c| c.is_element()) {
            if numbered(n) {
                return Err(n);
            }
            match n.tag_name().name() {
                "outVariable" | "inOutVariable" | "coil" => lists.outs.push(n),
                "block" => lists.blocks.push(n),
                "connector" => lists.connectors.push(n),
                _ => {}
            }
        }
        Ok(lists)
    }

    /// The outputs and the blocks each sorted by position as the generator's
    /// `SortInstances` sorts them (document order when they have no distinct
    /// positions), or an object where that sort is not reproduced.
    #[allow(clippy::type_complexity)]
    fn by_position(&self) -> Result<(Vec<Node<'a, 'i>>, Vec<Node<'a, 'i>>), Node<'a, 'i>> {
        let all = || self.outs.iter().chain(&self.blocks);
        let positions: Vec<Option<(i64, i64)>> = all().map(|n| position(*n)).collect();
        let distinct: BTreeSet<(i64, i64)> = positions.iter().flatten().copied().collect();
        if positions.iter().any(Option::is_none) || distinct.len() < 2 {
            return Ok((self.outs.clone(), self.blocks.clone()));
        }
        let sort = |list: &Vec<Node<'a, 'i>>| {
            let pos = |k: usize| position(list[k]).unwrap_or((0, 0));
            let mut order: Vec<usize> = (0..list.len()).collect();
            match geometric(&mut order, &pos) {
                Ok(_) => Ok(order.into_iter().map(|k| list[k]).collect::<Vec<_>>()),
                Err((_, b)) => Err(list[b]),
            }
        };
        Ok((sort(&self.outs)?, sort(&self.blocks)?))
    }
}

/// Whether `n` has an execution order number (`executionOrderId` other than 0).
fn numbered(n: Node) -> bool {
    n.attribute("executionOrderId").is_some_and(|v| v.trim().parse() != Ok(0))
}

/// The refusal of an object with an execution order number.
const NUMBERED: &str = "an execution order number in a chart's network is not read yet";

/// Whether the block `b` is a function (no instance name).
fn is_function(b: Node) -> bool {
    b.attribute("instanceName").is_none_or(|i| i.trim().is_empty())
}

/// The position `(x, y)` of an object, as the generator reads it.
fn position(n: Node) -> Option<(i64, i64)> {
    let p = child(n, "position")?;
    let v = |k| p.attribute(k)?.trim().parse::<f64>().ok();
    Some((v("x")? as i64, v("y")? as i64))
}

/// Where the statements of the LD or FBD `body` run in another order by position than
/// in document order: the first statement whose place differs.
pub(super) fn order_dispute<'a, 'i>(body: Node<'a, 'i>) -> Option<Node<'a, 'i>> {
    let lists = Statements::of(body).ok()?;
    let Ok((outs, blocks)) = lists.by_position() else { return lists.outs.first().copied() };
    let by_position = outs.iter().chain(&blocks);
    let document = lists.outs.iter().chain(&lists.blocks);
    by_position.zip(document).find(|(a, b)| a != b).map(|(a, _)| *a)
}

impl<'a, 'i> Net<'_, 'a, 'i> {
    fn span(&self, n: Node) -> Span {
        Span::new(self.project.file, n.range())
    }

    fn refuse(&self, n: Node, message: &str) -> StError {
        StError::new(self.span(n), message, "not read yet")
    }

    /// The text of `n` (a `variable` or an `expression` element) parsed as an expression.
    fn text(&mut self, n: Node<'a, 'i>, what: &str) -> Result<Expr, StError> {
        let text = super::super::read::text_of_body(self.sources.text(self.project.file), n);
        if text.1.trim().is_empty() {
            return Err(self.refuse(n, &format!("{what} without a text")));
        }
        if text.1.contains('{') {
            return Err(self.refuse(n, &format!("{what} with a pragma `{{…}}`")));
        }
        super::super::text::parse_text(
            self.sources,
            self.project,
            text,
            what,
            crate::iec::parser::parse_condition,
        )
    }

    /// `e`, which the generator pastes as written next to other operands: refused when it
    /// has operators of its own.
    fn operand(&self, e: Expr, n: Node) -> Result<Expr, StError> {
        if matches!(e.kind, ExprKind::Binary(..)) {
            return Err(self.refuse(
                n,
                "an expression with operators next to other operands in a network (the generator pastes it without parentheses) is not read yet",
            ));
        }
        Ok(e)
    }

    /// The value wired to the `connectionPointIn` of `n` (`None`: nothing wired).
    pub fn input(&mut self, n: Node<'a, 'i>) -> Result<Option<Expr>, StError> {
        // A condition holds its connections itself (PLCopen 2.01, Beremiz).
        let own = n.tag_name().name() == "condition";
        let Some(point) = child(n, "connectionPointIn").or(own.then_some(n)) else {
            return Ok(None);
        };
        let conns: Vec<Node> = elements(point, "connection").collect();
        let alone = conns.len() == 1;
        let mut value: Option<Expr> = None;
        for c in conns {
            let e = self.path(c, alone)?;
            value = Some(match value {
                Some(v) => binary(BinOp::Or, v, e),
                None => e,
            });
        }
        Ok(value)
    }

    /// The value of the object a `connection` comes from.
    fn path(&mut self, c: Node<'a, 'i>, alone: bool) -> Result<Expr, StError> {
        let id = c.attribute("refLocalId").and_then(|v| v.trim().parse::<u64>().ok());
        let Some(n) = id.and_then(|id| self.nodes.get(&id).copied()) else {
            return Err(self.refuse(c, "a wire from an object that is not in this body"));
        };
        let span = self.span(n);
        // A loop through a block reads what the block gave at its last call, as the
        // generator's code does (it marks a block computed before its inputs); any other
        // loop has no value.
        let block = n.tag_name().name() == "block";
        if !block && !self.visiting.insert(n.range().start) {
            return Err(self.refuse(n, "a network wired in a loop through no block"));
        }
        let e = match n.tag_name().name() {
            "leftPowerRail" => Ok(Expr { kind: ExprKind::Bool(true), span }),
            "inVariable" | "inOutVariable" => self.variable(n, alone),
            "contact" => self.contact(n),
            "coil" => self
                .input(n)?
                .ok_or_else(|| self.refuse(n, "a coil wired to nothing, read by another object")),
            "continuation" => self.continuation(n),
            "block" => self.block_output(n, c.attribute("formalParameter")),
            other => {
                Err(self.refuse(n, &format!("a `{other}` in a network of a chart is not read yet")))
            }
        };
        if !block {
            self.visiting.remove(&n.range().start);
        }
        e
    }

    fn variable(&mut self, n: Node<'a, 'i>, alone: bool) -> Result<Expr, StError> {
        if flag(n, "negated") || flag(n, "negatedOut") || edge(n) {
            return Err(self.refuse(
                n,
                "a negated or edge variable in a network of a chart (which Beremiz's generator ignores) is not read yet",
            ));
        }
        let Some(x) = child(n, "expression") else {
            return Err(self.refuse(n, "a variable without an expression"));
        };
        let e = self.text(x, "a variable's expression")?;
        if alone { Ok(e) } else { self.operand(e, x) }
    }

    fn contact(&mut self, n: Node<'a, 'i>) -> Result<Expr, StError> {
        let span = self.span(n);
        if modified(n) {
            return Err(self.refuse(
                n,
                "a contact with an edge or a storage (an `R_TRIG`/`F_TRIG` instance the generator declares) in a chart is not read yet",
            ));
        }
        let Some(v) = child(n, "variable") else {
            return Err(self.refuse(n, "a contact without a variable"));
        };
        let var = self.text(v, "a contact's variable")?;
        let var = if flag(n, "negated") { not(var, span) } else { self.operand(var, v)? };
        match self.input(n)? {
            None => Err(self.refuse(n, "a contact wired to nothing")),
            Some(e) if is_true(&e) => Ok(var),
            Some(e) => Ok(binary(BinOp::And, var, e)),
        }
    }

    fn continuation(&mut self, n: Node<'a, 'i>) -> Result<Expr, StError> {
        let name = n.attribute("name").unwrap_or("").to_string();
        if let Some(e) = self.connectors.get(&name) {
            return Ok(e.clone());
        }
        let found: Vec<Node> = self
            .nodes
            .values()
            .filter(|c| c.tag_name().name() == "connector" && c.attribute("name") == Some(&name))
            .copied()
            .collect();
        let [connector] = found.as_slice() else {
            return Err(self.refuse(
                n,
                &format!("the continuation `{name}` has not exactly one connector in this body"),
            ));
        };
        let e = self
            .input(*connector)?
            .ok_or_else(|| self.refuse(*connector, "a connector wired to nothing"))?;
        self.connectors.insert(name, e.clone());
        Ok(e)
    }

    /// Refuses what the generator would write with declarations of its own or in an order
    /// of its own.
    fn plain_block(&self, b: Node<'a, 'i>) -> Result<String, StError> {
        let instance = b.attribute("instanceName").unwrap_or("").trim();
        if numbered(b) {
            return Err(self.refuse(b, NUMBERED));
        }
        Ok(instance.to_string())
    }

    fn block_output(&mut self, b: Node<'a, 'i>, pin: Option<&str>) -> Result<Expr, StError> {
        if is_function(b) {
            if pin.is_some_and(|p| p.trim().eq_ignore_ascii_case("ENO")) {
                return Err(self.refuse(b, "`ENO` in a chart's network is not read yet"));
            }
            if pin.is_none_or(|p| p.trim().is_empty()) {
                return Err(self.refuse(b, "a wire from a block that names no output pin"));
            }
            return self.function(b);
        }
        let instance = self.plain_block(b)?;
        let Some(pin) = pin.map(str::trim).filter(|p| !p.is_empty()) else {
            return Err(self.refuse(b, "a wire from a block that names no output pin"));
        };
        if pin.eq_ignore_ascii_case("ENO") {
            return Err(self.refuse(b, "`ENO` in a chart's network is not read yet"));
        }
        self.call(b)?;
        let outs = child(b, "outputVariables").map(|o| elements(o, "variable").collect::<Vec<_>>());
        let out = outs
            .unwrap_or_default()
            .into_iter()
            .find(|v| v.attribute("formalParameter") == Some(pin))
            .ok_or_else(|| self.refuse(b, &format!("the block has no output `{pin}`")))?;
        if modified(out) {
            return Err(self.refuse(out, "an output pin with an edge in a chart is not read yet"));
        }
        let span = self.span(out);
        let base = Expr { kind: ExprKind::Var(Ident { name: instance, span }), span };
        let e = Expr {
            kind: ExprKind::Member(Box::new(base), Ident { name: pin.to_string(), span }),
            span,
        };
        Ok(if flag(out, "negated") { not(e, span) } else { e })
    }

    /// Writes the call of the function block `b` (once).
    fn call(&mut self, b: Node<'a, 'i>) -> Result<(), StError> {
        let instance = self.plain_block(b)?;
        if !self.called.insert(b.range().start) {
            return Ok(());
        }
        let args = self.arguments(b)?;
        let span = self.span(b);
        let f = Expr { kind: ExprKind::Var(Ident { name: instance, span }), span };
        self.out.push(Stmt { kind: StmtKind::Call(f, args), span });
        Ok(())
    }

    /// The arguments of the call of the block `b`: `PIN := value` for each input wired.
    fn arguments(&mut self, b: Node<'a, 'i>) -> Result<Vec<Arg>, StError> {
        let outs: Vec<String> = child(b, "outputVariables")
            .map(|o| elements(o, "variable").filter_map(|v| v.attribute("formalParameter")))
            .into_iter()
            .flatten()
            .map(str::to_string)
            .collect();
        let mut args = Vec::new();
        for v in child(b, "inputVariables").into_iter().flat_map(|i| elements(i, "variable")) {
            let pin = v.attribute("formalParameter").unwrap_or("").to_string();
            if pin.eq_ignore_ascii_case("EN") {
                return Err(self.refuse(v, "`EN` in a chart's network is not read yet"));
            }
            if outs.contains(&pin) || modified(v) {
                return Err(self.refuse(
                    v,
                    "an in-out pin or an edge pin in a chart's network is not read yet",
                ));
            }
            let Some(e) = self.input(v)? else { continue };
            let span = self.span(v);
            let e = if flag(v, "negated") { not(e, span) } else { e };
            args.push(Arg::Input(Ident { name: pin, span }, e));
        }
        Ok(args)
    }

    /// The result of the function `b` (a block without an instance), as the generator
    /// computes it: the first time a path reaches it (or, unread, in its place among the
    /// blocks), `_TMP_<TYPE><localId>_OUT := TYPE(IN1 := …, …);`, a variable of the
    /// result's type it declares; then that variable.
    fn function(&mut self, b: Node<'a, 'i>) -> Result<Expr, StError> {
        if let Some(e) = self.functions.get(&b.range().start) {
            return Ok(e.clone());
        }
        let ty = b.attribute("typeName").unwrap_or("").trim().to_ascii_uppercase();
        if numbered(b) {
            return Err(self.refuse(b, NUMBERED));
        }
        let outs: Vec<Node> =
            child(b, "outputVariables").into_iter().flat_map(|o| elements(o, "variable")).collect();
        let [out] = outs.as_slice() else {
            return Err(self.refuse(b, &format!("the function `{ty}` without one output")));
        };
        if modified(*out) || flag(*out, "negated") {
            return Err(self.refuse(
                *out,
                "a negated or edge output of a function in a chart's network is not read yet",
            ));
        }
        let pin = out.attribute("formalParameter").unwrap_or("OUT").trim().to_string();
        let span = self.span(b);
        let id = b.attribute("localId").unwrap_or("").trim();
        let name = format!("_TMP_{ty}{id}_{pin}");
        let ident = |name: &str| Ident { name: name.to_string(), span };
        let target = Expr { kind: ExprKind::Var(ident(&name)), span };
        // Marked computed before its inputs: a loop back to it reads its last result.
        self.functions.insert(b.range().start, target.clone());
        let args = self.arguments(b)?;
        let Some(result) = self.result_type(&ty, &args) else {
            return Err(self.refuse(
                b,
                &format!(
                    "the function `{ty}` in a network of a chart, whose result's type is not known here (the generator takes it from the variables wired to it), is not read yet"
                ),
            ));
        };
        self.temps.push(VarDecl {
            name: ident(&name),
            class: VarClass::Local,
            ty: ident(&result),
            init: None,
            retain: false,
            constant: false,
            location: None,
            made: true,
            range: None,
        });
        let value = Expr { kind: ExprKind::Call(ident(&ty), args), span };
        self.out.push(Stmt { kind: StmtKind::Assign(target.clone(), value), span });
        Ok(target)
    }

    /// The type of the result of the function `ty` called with `args`, where it is
    /// known: BOOL for a comparison, `T` for a conversion `…_TO_T`, else (the Boolean,
    /// bit, arithmetic and selection functions) the one type of its operands whose type
    /// is known.
    fn result_type(&self, ty: &str, args: &[Arg]) -> Option<String> {
        if matches!(ty, "GT" | "GE" | "EQ" | "LE" | "LT" | "NE") {
            return Some("BOOL".into());
        }
        if let Some((_, to)) = ty.rsplit_once("_TO_") {
            return Some(to.to_string());
        }
        let same = [
            "AND", "OR", "XOR", "NOT", "MOVE", "ADD", "SUB", "MUL", "DIV", "MOD", "MIN", "MAX",
            "ABS", "SEL", "LIMIT",
        ];
        if !same.contains(&ty) {
            return None;
        }
        let operands = args.iter().filter_map(|a| match a {
            Arg::Input(pin, e) if !(ty == "SEL" && pin.name.eq_ignore_ascii_case("G")) => Some(e),
            _ => None,
        });
        let types: BTreeSet<Option<String>> = operands.map(|e| self.type_of(e)).collect();
        let known: Vec<&String> = types.iter().flatten().collect();
        match known.as_slice() {
            [one] => Some(one.to_string()),
            _ => None,
        }
    }

    /// The type of `e`, a value in a network, where it is plain: a Boolean literal, a
    /// contact's AND/OR/NOT, a variable of the POU, a function's result.
    fn type_of(&self, e: &Expr) -> Option<String> {
        match &e.kind {
            ExprKind::Bool(_) => Some("BOOL".into()),
            ExprKind::Unary(UnOp::Not, x) => self.type_of(x),
            ExprKind::Binary(BinOp::And | BinOp::Or, a, b) => {
                let t = self.type_of(a)?;
                (self.type_of(b)? == t).then_some(t)
            }
            ExprKind::Literal(text) => {
                let (prefix, _) = text.split_once('#')?;
                match prefix.trim().to_ascii_uppercase().as_str() {
                    "T" | "TIME" => Some("TIME".into()),
                    p if p.chars().all(|c| c.is_ascii_alphabetic()) => Some(p.to_string()),
                    _ => None,
                }
            }
            ExprKind::Var(id) => {
                if let Some(t) = self.temps.iter().find(|t| t.name.name == id.name) {
                    return Some(t.ty.name.clone());
                }
                let v = self.vars.iter().find(|v| v.name.eq_ignore_ascii_case(&id.name))?;
                Some(v.ty.iec_name())
            }
            _ => None,
        }
    }

    /// The statements of an LD or FBD body (`ComputeProgram`), in the statement order
    /// `--order` chooses where position and document order differ (by position when it
    /// chooses none: [`order_dispute`] then finds the difference, which the loader
    /// settles).
    pub fn program(&mut self, body: Node<'a, 'i>) -> Result<(), StError> {
        let lists = Statements::of(body).map_err(|n| self.refuse(n, NUMBERED))?;
        let (outs, blocks) = match self.order {
            Some(StatementOrder::Document) => (lists.outs, lists.blocks),
            _ => match lists.by_position() {
                Ok(by_position) => by_position,
                Err(n) => return Err(self.refuse(
                    n,
                    "a statement order by position among 64 or more objects less than 10 units apart in height (Beremiz's position comparison is no order there, and what its sort makes of it is not reproduced for so many objects; align them, move them 10 units apart, or choose `--order document`)",
                )),
            },
        };
        for n in outs {
            self.statement(n)?;
        }
        for b in blocks {
            if is_function(b) {
                self.function(b)?;
            } else {
                self.plain_block(b)?;
                self.call(b)?;
            }
        }
        for c in lists.connectors {
            let name = c.attribute("name").unwrap_or("").to_string();
            if !self.connectors.contains_key(&name)
                && let Some(e) = self.input(c)?
            {
                self.connectors.insert(name, e);
            }
        }
        Ok(())
    }

    fn statement(&mut self, n: Node<'a, 'i>) -> Result<(), StError> {
        let span = self.span(n);
        let coil = n.tag_name().name() == "coil";
        if !coil && (flag(n, "negated") || flag(n, "negatedIn") || edge(n)) {
            return Err(self.refuse(
                n,
                "a negated or edge variable in a network of a chart (which Beremiz's generator ignores) is not read yet",
            ));
        }
        let Some(e) = self.input(n)? else { return Ok(()) };
        let target = child(n, if coil { "variable" } else { "expression" })
            .ok_or_else(|| self.refuse(n, "an output without a variable"))?;
        let target = self.text(target, "an output's variable")?;
        let assign = |value: Expr| Stmt { kind: StmtKind::Assign(target.clone(), value), span };
        let storage = n.attribute("storage").unwrap_or("none").trim().to_string();
        let stmt = if coil && flag(n, "negated") {
            assign(not(e, span))
        } else if coil && (storage == "set" || storage == "reset") {
            let value = Expr { kind: ExprKind::Bool(storage == "set"), span };
            Stmt { kind: StmtKind::If(vec![(e, vec![assign(value)])], Vec::new()), span }
        } else if coil && edge(n) {
            return Err(self.refuse(
                n,
                "a coil with an edge (an `R_TRIG`/`F_TRIG` instance the generator declares) in a chart is not read yet",
            ));
        } else {
            assign(e)
        };
        self.out.push(stmt);
        Ok(())
    }
}
