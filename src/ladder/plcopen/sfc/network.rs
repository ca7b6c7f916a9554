//! Ladder and FBD networks inside a chart (a condition wired to contacts or variables, a transition or an action whose body is LD or FBD) as the Structured Text Beremiz's `PLCGenerator.py` writes for them (`ComputeExpression`, `ComputeProgram`).
//!
//! A network's value is the OR of the paths wired to a pin; a contact is its variable
//! (`NOT(v)` when negated) AND the paths wired to it; a left rail is `TRUE`; a variable
//! is its expression; a continuation is its connector's value, computed once for the
//! whole POU as the generator does; a function block's output is `instance.pin`, the
//! block being called (`instance(IN := …);`) the first time a path reaches it. A body is
//! its coils and output variables (by position and in document order, which must
//! agree), then its blocks not yet called: `v := e;`, `v := NOT(e);`,
//! `IF e THEN v := TRUE; END_IF;`. Refused with a located error: functions (their
//! results are variables the generator declares), `EN`/`ENO`, in-out pins, edges
//! (`R_TRIG` instances the generator declares), execution order numbers, a text with
//! operators pasted next to another operand (the generator pastes it without
//! parentheses), and objects that are no network element.

use std::collections::{BTreeMap, BTreeSet};

use crate::diag::{Sources, Span};
use crate::iec::StError;
use crate::iec::ast::{Arg, BinOp, Expr, ExprKind, Ident, Stmt, StmtKind, UnOp};

use super::super::Project;

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

/// The generator's position comparator (`SortInstances`): rows 10 units high, left to right.
fn by_position(a: Node, b: Node) -> std::cmp::Ordering {
    let pos = |n: Node| {
        child(n, "position").map_or((0, 0), |p| {
            let v = |k| p.attribute(k).and_then(|x| x.trim().parse::<f64>().ok()).unwrap_or(0.0);
            (v("x") as i64, v("y") as i64)
        })
    };
    let ((ax, ay), (bx, by)) = (pos(a), pos(b));
    if (ay - by).abs() < 10 { ax.cmp(&bx) } else { ay.cmp(&by) }
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
        if !self.visiting.insert(n.range().start) {
            return Err(self.refuse(n, "a network wired in a loop"));
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
        self.visiting.remove(&n.range().start);
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
        let ty = b.attribute("typeName").unwrap_or("");
        let instance = b.attribute("instanceName").unwrap_or("").trim();
        if instance.is_empty() {
            return Err(self.refuse(
                b,
                &format!(
                    "the function `{ty}` in a network of a chart (its result a variable the generator declares) is not read yet"
                ),
            ));
        }
        if b.attribute("executionOrderId").is_some_and(|v| v.trim().parse() != Ok(0)) {
            return Err(
                self.refuse(b, "an execution order number in a chart's network is not read yet")
            );
        }
        Ok(instance.to_string())
    }

    fn block_output(&mut self, b: Node<'a, 'i>, pin: Option<&str>) -> Result<Expr, StError> {
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
        let span = self.span(b);
        let f = Expr { kind: ExprKind::Var(Ident { name: instance, span }), span };
        self.out.push(Stmt { kind: StmtKind::Call(f, args), span });
        Ok(())
    }

    /// The statements of an LD or FBD body (`ComputeProgram`).
    pub fn program(&mut self, body: Node<'a, 'i>) -> Result<(), StError> {
        let mut outs = Vec::new();
        let mut blocks = Vec::new();
        let mut connectors = Vec::new();
        for n in body.children().filter(|c| c.is_element()) {
            if n.attribute("executionOrderId").is_some_and(|v| v.trim().parse() != Ok(0)) {
                return Err(self
                    .refuse(n, "an execution order number in a chart's network is not read yet"));
            }
            match n.tag_name().name() {
                "outVariable" | "inOutVariable" | "coil" => outs.push(n),
                "block" => blocks.push(n),
                "connector" => connectors.push(n),
                _ => {}
            }
        }
        for list in [&outs, &blocks] {
            let mut sorted = list.clone();
            // Insertion sort (stable, never panics), then checked to be an order.
            for k in 1..sorted.len() {
                let mut j = k;
                while j > 0 && by_position(sorted[j - 1], sorted[j]).is_gt() {
                    sorted.swap(j - 1, j);
                    j -= 1;
                }
            }
            for (k, a) in sorted.iter().enumerate() {
                for b in &sorted[k + 1..] {
                    if by_position(*a, *b).is_gt() || sorted != *list {
                        return Err(self.refuse(
                            *b,
                            "a statement order that depends on the editor (by position, it differs from document order) in a chart's network is not read yet",
                        ));
                    }
                }
            }
        }
        for n in outs {
            self.statement(n)?;
        }
        for b in blocks {
            self.plain_block(b)?;
            self.call(b)?;
        }
        for c in connectors {
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
