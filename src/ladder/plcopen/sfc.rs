//! A PLCopen `<SFC>` body read as the textual chart Beremiz's `PLCGenerator.py` writes for matiec: the same steps, transitions and actions in the same order (steps from each initial step depth first, a step's actions and then its transitions, each transition followed by its next steps), so that `crate::iec::sfc` runs it as matiec runs the generated text.
//!
//! Read: steps, jumps, selection and simultaneous divergences and convergences, action
//! blocks (actions referring to a BOOL variable or to an action of the POU with a
//! Structured Text body, or inline Structured Text, which the generator names
//! `STEP_INLINE1`, `STEP_INLINE2`, …), transitions with a priority and an inline
//! Structured Text condition or one referring to a transition of the POU with a
//! Structured Text body (`:= expression;`); a condition drawn as a network in the chart's
//! body, a named transition and a named action whose body is LD or FBD (`sfc/network.rs`;
//! the calls of the blocks of condition networks in the action `COMPUTE_FUNCTION_BLOCKS`,
//! qualifier `S`, of the first initial step, as the generator writes them). Refused with a
//! located error: Instruction List, LD or FBD inline in an action block, what
//! `sfc/network.rs` refuses, macro steps.

use std::collections::{BTreeMap, BTreeSet};
use std::ops::Range;

mod network;

use super::{Pou, Project, StatementOrder};
use crate::diag::{Sources, Span};
use crate::iec::StError;
use crate::iec::ast::{self, Association, Expr, ExprKind, Ident};

type Node<'a, 'i> = roxmltree::Node<'a, 'i>;

/// The chart of `pou`, whose body is SFC, as the IEC front end's chart; the statements
/// of its LD and FBD actions in the order `order` chooses (by position when none).
pub fn read<'g>(
    sources: &'g mut Sources,
    project: &'g Project,
    pou: &'g Pou,
    order: Option<StatementOrder>,
) -> Result<ast::Body, StError> {
    let text = sources.text(project.file).to_string();
    let body = pou.body.as_ref().map_or(pou.span, |b| b.span);
    let options = roxmltree::ParsingOptions { allow_dtd: true, ..Default::default() };
    let doc = roxmltree::Document::parse_with_options(&text, options)
        .map_err(|_| StError::new(body, "the project is not well-formed XML", "here"))?;
    let sfc = doc
        .descendants()
        .find(|n| n.is_element() && n.tag_name().name() == "SFC" && n.range().start == body.start)
        .ok_or_else(|| StError::new(body, "this chart is not found again in the file", "here"))?;
    let pou_node = sfc.ancestors().find(|n| n.tag_name().name() == "pou").unwrap_or(sfc);
    let mut g = Gen {
        sources,
        project,
        pou: pou_node,
        nodes: sfc
            .children()
            .filter(|c| c.is_element())
            .filter_map(|c| Some((c.attribute("localId")?.parse().ok()?, c)))
            .collect(),
        steps: BTreeMap::new(),
        initial: Vec::new(),
        transitions: BTreeMap::new(),
        actions: BTreeMap::new(),
        numbered: 0,
        out: ast::Sfc::default(),
        connectors: BTreeMap::new(),
        called: BTreeSet::new(),
        computed: Vec::new(),
        order,
        vars: &pou.vars,
        functions: BTreeMap::new(),
        temps: Vec::new(),
    };
    for c in sfc.children().filter(|c| c.is_element()) {
        match c.tag_name().name() {
            "step" => g.step(c)?,
            "actionBlock" => g.action_block(c)?,
            "transition" => g.transition(c)?,
            "jumpStep" => g.jump(c)?,
            "macroStep" => return Err(g.refuse(c, "a macro step is not read yet")),
            _ => {}
        }
    }
    // The calls of the networks drawn for conditions: an action of the first initial step
    // (`COMPUTE_FUNCTION_BLOCKS`, qualifier `S`), as the generator writes it.
    if let Some(first) = g.initial.first().cloned()
        && !g.computed.is_empty()
    {
        let name = "COMPUTE_FUNCTION_BLOCKS".to_string();
        let span = g.span(sfc);
        let body = std::mem::take(&mut g.computed);
        g.actions.insert(name.clone(), (name.clone(), body, span));
        let association = Association {
            action: Ident { name, span },
            qualifier: Some(Ident { name: "S".into(), span }),
            time: None,
            span,
        };
        if let Some((_, info)) = g.steps.get_mut(&first) {
            info.actions.push(association);
        }
    }
    for s in g.initial.clone() {
        g.compute_step(&s)?;
    }
    g.out.temps = std::mem::take(&mut g.temps);
    Ok(ast::Body::Sfc(g.out))
}

/// The first LD or FBD action of a chart of `project` whose statements run in another
/// order by position than in document order: the error to report if the difference
/// changes what the program does.
pub fn order_dispute(sources: &Sources, project: &Project) -> Option<StError> {
    // Only a chart has such actions: a project without one is not parsed again.
    let chart = |p: &Pou| p.body.as_ref().is_some_and(|b| b.lang == super::Lang::Sfc);
    if !project.pous.iter().any(chart) {
        return None;
    }
    let options = roxmltree::ParsingOptions { allow_dtd: true, ..Default::default() };
    let doc = roxmltree::Document::parse_with_options(sources.text(project.file), options).ok()?;
    let charts = doc.descendants().filter(|n| n.is_element() && n.tag_name().name() == "SFC");
    let pous = charts.filter_map(|c| c.ancestors().find(|n| n.tag_name().name() == "pou"));
    let actions = pous.filter_map(|p| child(p, "actions")).flat_map(|a| a.children());
    let bodies = actions.filter_map(|a| child(a, "body"));
    let networks = bodies.filter_map(|b| child(b, "LD").or_else(|| child(b, "FBD")));
    let first = networks.into_iter().find_map(network::order_dispute)?;
    Some(StError::new(
        Span::new(project.file, first.range()),
        format!(
            "a statement order that depends on the editor (this `{}` of a chart's action runs \
             at another place by position than in document order, and the program computes \
             differently): {}",
            first.tag_name().name(),
            super::ORDER_CHOICE
        ),
        "its place differs",
    ))
}

struct StepInfo {
    node: Range<usize>,
    initial: bool,
    /// The transitions leaving it (by `localId`), in the order they were read.
    transitions: Vec<u64>,
    actions: Vec<Association>,
}

struct TransitionInfo {
    node: Range<usize>,
    priority: Option<(i128, Span)>,
    from: Vec<Ident>,
    to: Vec<Ident>,
    condition: Expr,
}

struct Gen<'g, 'a, 'i> {
    sources: &'g mut Sources,
    project: &'g Project,
    pou: Node<'a, 'i>,
    nodes: BTreeMap<u64, Node<'a, 'i>>,
    /// Steps read, by upper-case name, with their name as written.
    steps: BTreeMap<String, (String, StepInfo)>,
    initial: Vec<String>,
    transitions: BTreeMap<u64, TransitionInfo>,
    /// Actions read (upper-case name → name and body), not yet written out.
    actions: BTreeMap<String, (String, Vec<ast::Stmt>, Span)>,
    numbered: usize,
    out: ast::Sfc,
    /// Connectors' values, by name, for the whole POU (the generator's `ComputedConnectors`).
    connectors: BTreeMap<String, Expr>,
    /// The blocks of networks already called (by where they start in the file).
    called: BTreeSet<usize>,
    /// The calls of the networks drawn for conditions (the generator's `SFCComputedBlocks`).
    computed: Vec<ast::Stmt>,
    /// The statement order `--order` chooses for LD and FBD actions.
    order: Option<StatementOrder>,
    /// The POU's variables.
    vars: &'g [super::Var],
    /// The functions of its networks computed so far, with their result variables, and
    /// those variables' declarations.
    functions: BTreeMap<usize, Expr>,
    temps: Vec<ast::VarDecl>,
}

fn child<'a, 'i>(n: Node<'a, 'i>, name: &str) -> Option<Node<'a, 'i>> {
    n.children().find(|c| c.is_element() && c.tag_name().name() == name)
}

impl<'a, 'i> Gen<'_, 'a, 'i> {
    fn span(&self, n: Node) -> Span {
        Span::new(self.project.file, n.range())
    }

    fn refuse(&self, n: Node, message: &str) -> StError {
        StError::new(self.span(n), message, "not read yet")
    }

    /// The element `n`'s one input connection leads to.
    fn input(&self, n: Node<'a, 'i>) -> Vec<Node<'a, 'i>> {
        n.children()
            .filter(|c| c.is_element() && c.tag_name().name() == "connectionPointIn")
            .filter_map(|p| {
                let conns: Vec<_> = p
                    .children()
                    .filter(|c| c.is_element() && c.tag_name().name() == "connection")
                    .collect();
                match conns.as_slice() {
                    [one] => self.nodes.get(&one.attribute("refLocalId")?.parse().ok()?).copied(),
                    _ => None,
                }
            })
            .collect()
    }

    /// The transitions a step or a jump is entered by (`ExtractConvergenceInputs`…).
    fn entering(&self, n: Node<'a, 'i>) -> Vec<Node<'a, 'i>> {
        let Some(first) = self.input(n).first().copied() else { return Vec::new() };
        match first.tag_name().name() {
            "transition" => vec![first],
            "selectionConvergence" => self.input(first),
            "simultaneousDivergence" => match self.input(first).first().copied() {
                Some(t) if t.tag_name().name() == "transition" => vec![t],
                Some(c) if c.tag_name().name() == "selectionConvergence" => self.input(c),
                _ => Vec::new(),
            },
            _ => Vec::new(),
        }
        .into_iter()
        .filter(|t| t.tag_name().name() == "transition")
        .collect()
    }

    fn step(&mut self, n: Node<'a, 'i>) -> Result<(), StError> {
        let name = n.attribute("name").unwrap_or("").to_string();
        let key = name.to_ascii_uppercase();
        if self.steps.contains_key(&key) {
            return Ok(());
        }
        let initial = n.attribute("initialStep") == Some("true");
        if initial {
            self.initial.push(key.clone());
        }
        let info =
            StepInfo { node: n.range(), initial, transitions: Vec::new(), actions: Vec::new() };
        self.steps.insert(key, (name.clone(), info));
        self.entered_by(n, &name)
    }

    /// The transitions `n` (a step or a jump) is entered by lead to step `name`.
    fn entered_by(&mut self, n: Node<'a, 'i>, name: &str) -> Result<(), StError> {
        for t in self.entering(n) {
            self.transition(t)?;
            let (id, span) = (self.id(t), self.span(n));
            if let Some(info) = self.transitions.get_mut(&id) {
                info.to.push(Ident { name: name.to_string(), span });
            }
        }
        Ok(())
    }

    fn id(&self, n: Node) -> u64 {
        n.attribute("localId").and_then(|v| v.parse().ok()).unwrap_or(u64::MAX)
    }

    fn jump(&mut self, n: Node<'a, 'i>) -> Result<(), StError> {
        let target = n.attribute("targetName").unwrap_or("").to_string();
        let known = self.nodes.values().any(|s| {
            s.tag_name().name() == "step"
                && s.attribute("name").is_some_and(|x| x.eq_ignore_ascii_case(&target))
        });
        if !known {
            return Err(StError::new(
                self.span(n),
                format!("this jump goes to `{target}`, which is no step of the chart"),
                "no such step",
            ));
        }
        self.entered_by(n, &target)
    }

    fn action_block(&mut self, n: Node<'a, 'i>) -> Result<(), StError> {
        let Some(step) = self.input(n).first().copied() else { return Ok(()) };
        if step.tag_name().name() != "step" {
            return Ok(());
        }
        self.step(step)?;
        let step_name = step.attribute("name").unwrap_or("").to_string();
        for a in n.children().filter(|c| c.is_element() && c.tag_name().name() == "action") {
            let span = self.span(a);
            let qualifier = a.attribute("qualifier").unwrap_or("N").to_ascii_uppercase();
            let time =
                a.attribute("duration").map(|d| match crate::iec::literal::parse_duration(d) {
                    Some(us) => Expr { kind: ExprKind::Time(us), span },
                    None => Expr {
                        kind: ExprKind::Var(Ident { name: d.trim().to_string(), span }),
                        span,
                    },
                });
            let name = if let Some(r) = child(a, "reference") {
                let name = r.attribute("name").unwrap_or("").to_string();
                self.named_action(&name, span)?;
                name
            } else if let Some(inline) = child(a, "inline") {
                self.numbered += 1;
                let name = format!("{}_INLINE{}", step_name.to_ascii_uppercase(), self.numbered);
                let body = self.statements(inline, &format!("action {name}"))?;
                self.actions.insert(name.to_ascii_uppercase(), (name.clone(), body, span));
                name
            } else {
                return Err(self.refuse(a, "an action without a reference or an inline body"));
            };
            let qualifier = Some(Ident { name: qualifier, span });
            let action = Ident { name, span };
            let association = Association { action, qualifier, time, span };
            if let Some((_, info)) = self.steps.get_mut(&step_name.to_ascii_uppercase()) {
                info.actions.push(association);
            }
        }
        Ok(())
    }

    /// The POU's action `name`, if it has one (else `name` is a variable).
    fn named_action(&mut self, name: &str, span: Span) -> Result<(), StError> {
        let key = name.to_ascii_uppercase();
        if self.actions.contains_key(&key) {
            return Ok(());
        }
        let found = child(self.pou, "actions").and_then(|acts| {
            acts.children().find(|c| {
                c.tag_name().name() == "action"
                    && c.attribute("name").is_some_and(|x| x.eq_ignore_ascii_case(name))
            })
        });
        if let Some(act) = found {
            let body = child(act, "body").unwrap_or(act);
            let body = self.statements(body, &format!("action {name}"))?;
            self.actions.insert(key, (name.to_string(), body, span));
        }
        Ok(())
    }

    /// The Structured Text statements in `n` (an `inline` or a `body`).
    fn statements(&mut self, n: Node<'a, 'i>, what: &str) -> Result<Vec<ast::Stmt>, StError> {
        let network = child(n, "LD").or_else(|| child(n, "FBD"));
        if let Some(body) = network.filter(|_| n.tag_name().name() == "body") {
            let mut net = self.net(network::local_ids(body));
            net.program(body)?;
            return Ok(net.out);
        }
        let Some(st) = child(n, "ST") else {
            let lang = n.children().find(|c| c.is_element()).map_or("?", |c| c.tag_name().name());
            return Err(self.refuse(
                n,
                &format!("an {what} in {lang} is not read yet (only Structured Text)"),
            ));
        };
        let text = super::read::text_of_body(self.sources.text(self.project.file), st);
        if text.1.contains('{') {
            return Err(self.refuse(
                st,
                &format!("an {what} with a pragma `{{…}}`, C code that ii-prove cannot see"),
            ));
        }
        super::text::parse_text(
            self.sources,
            self.project,
            text,
            what,
            crate::iec::parser::parse_body,
        )
    }

    /// The network whose objects are `nodes`.
    fn net<'s>(&'s mut self, nodes: BTreeMap<u64, Node<'a, 'i>>) -> network::Net<'s, 'a, 'i> {
        network::Net {
            sources: self.sources,
            project: self.project,
            nodes,
            connectors: &mut self.connectors,
            called: &mut self.called,
            out: Vec::new(),
            visiting: BTreeSet::new(),
            order: self.order,
            vars: self.vars,
            functions: &mut self.functions,
            temps: &mut self.temps,
        }
    }

    fn transition(&mut self, n: Node<'a, 'i>) -> Result<(), StError> {
        let id = self.id(n);
        if self.transitions.contains_key(&id) {
            return Ok(());
        }
        let mut from = Vec::new();
        if let Some(first) = self.input(n).first().copied() {
            from = match first.tag_name().name() {
                "step" => vec![first],
                "selectionDivergence" => match self.input(first).first().copied() {
                    Some(s) if s.tag_name().name() == "step" => vec![s],
                    Some(c) if c.tag_name().name() == "simultaneousConvergence" => self.input(c),
                    _ => Vec::new(),
                },
                "simultaneousConvergence" => self.input(first),
                _ => Vec::new(),
            };
        }
        let span = self.span(n);
        let priority =
            n.attribute("priority").and_then(|p| p.trim().parse::<i128>().ok()).map(|p| (p, span));
        let condition = self.condition(n)?;
        let info = TransitionInfo {
            node: n.range(),
            priority,
            from: Vec::new(),
            to: Vec::new(),
            condition,
        };
        self.transitions.insert(id, info);
        for s in from.into_iter().filter(|s| s.tag_name().name() == "step") {
            self.step(s)?;
            let name = s.attribute("name").unwrap_or("").to_string();
            let step_span = self.span(s);
            if let Some(info) = self.transitions.get_mut(&id) {
                info.from.push(Ident { name: name.clone(), span: step_span });
            }
            if let Some((_, step)) = self.steps.get_mut(&name.to_ascii_uppercase()) {
                step.transitions.push(id);
            }
        }
        Ok(())
    }

    fn condition(&mut self, n: Node<'a, 'i>) -> Result<Expr, StError> {
        let Some(c) = child(n, "condition") else {
            return Err(self.refuse(n, "a transition without a condition"));
        };
        if c.attribute("negated").is_some_and(|v| v.trim() == "true" || v.trim() == "1") {
            return Err(self.refuse(
                c,
                "a negated condition (which Beremiz's generator ignores) is not read yet",
            ));
        }
        if let Some(inline) = child(c, "inline") {
            let Some(st) = child(inline, "ST") else {
                return Err(self.refuse(
                    inline,
                    "a transition condition that is not Structured Text is not read yet",
                ));
            };
            let text = super::read::text_of_body(self.sources.text(self.project.file), st);
            return super::text::parse_text(
                self.sources,
                self.project,
                text,
                "a condition",
                crate::iec::parser::parse_condition,
            );
        }
        if let Some(r) = child(c, "reference") {
            let name = r.attribute("name").unwrap_or("");
            let body = child(self.pou, "transitions")
                .and_then(|ts| {
                    ts.children().find(|t| {
                        t.tag_name().name() == "transition"
                            && t.attribute("name").is_some_and(|x| x.eq_ignore_ascii_case(name))
                    })
                })
                .and_then(|t| child(t, "body"));
            let Some(body) = body else {
                return Err(
                    self.refuse(r, &format!("the transition `{name}` is not found in the POU"))
                );
            };
            if let Some(network) = child(body, "LD").or_else(|| child(body, "FBD")) {
                return self.named_network(network, name);
            }
            let Some(st) = child(body, "ST") else {
                return Err(self.refuse(
                    body,
                    &format!("the transition `{name}` is not Structured Text: not read yet"),
                ));
            };
            let text = super::read::text_of_body(self.sources.text(self.project.file), st);
            return super::text::parse_text(
                self.sources,
                self.project,
                text,
                &format!("transition {name}"),
                crate::iec::parser::parse_condition,
            );
        }
        // Drawn as a network in the chart's body.
        let nodes = self.nodes.clone();
        let mut net = self.net(nodes);
        let value = net.input(c)?;
        let calls = std::mem::take(&mut net.out);
        self.computed.extend(calls);
        value.ok_or_else(|| self.refuse(c, "a transition condition wired to nothing"))
    }

    /// The condition of the transition `name` whose body is the LD or FBD `network`: what
    /// is wired to its output variable or coil named `name` (the last one, as the
    /// generator writes them all and keeps the last).
    fn named_network(&mut self, network: Node<'a, 'i>, name: &str) -> Result<Expr, StError> {
        let mut net = self.net(network::local_ids(network));
        let mut value = None;
        for n in network.children().filter(|c| c.is_element()) {
            let text = match n.tag_name().name() {
                "outVariable" => child(n, "expression"),
                "coil" => child(n, "variable"),
                _ => None,
            };
            if text.and_then(|t| t.text()) == Some(name)
                && let Some(e) = net.input(n)?
            {
                value = Some(e);
            }
        }
        let calls = std::mem::take(&mut net.out);
        self.computed.extend(calls);
        value.ok_or_else(|| {
            self.refuse(
                network,
                &format!("the transition `{name}` has no output variable or coil `{name}` wired to a value"),
            )
        })
    }

    /// Writes step `key` out, then its actions and its transitions (with their next
    /// steps), as the generator does.
    fn compute_step(&mut self, key: &str) -> Result<(), StError> {
        let Some((name, info)) = self.steps.remove(key) else { return Ok(()) };
        let span = Span::new(self.project.file, info.node.clone());
        let names: Vec<String> = info.actions.iter().map(|a| a.action.key()).collect();
        self.out.steps.push(ast::Step {
            name: Ident { name, span },
            initial: info.initial,
            actions: info.actions,
        });
        for a in names {
            if let Some((name, body, span)) = self.actions.remove(&a) {
                self.out.actions.push(ast::Action { name: Ident { name, span }, body, span });
            }
        }
        for t in info.transitions {
            self.compute_transition(t)?;
        }
        Ok(())
    }

    fn compute_transition(&mut self, id: u64) -> Result<(), StError> {
        let Some(t) = self.transitions.remove(&id) else { return Ok(()) };
        let span = Span::new(self.project.file, t.node.clone());
        if t.from.is_empty() || t.to.is_empty() {
            let side = if t.from.is_empty() { "previous" } else { "next" };
            return Err(StError::new(
                span,
                format!("this transition is not connected to a {side} step"),
                "not connected",
            ));
        }
        let next: Vec<String> = t.to.iter().map(Ident::key).collect();
        self.out.transitions.push(ast::Transition {
            name: None,
            priority: t.priority,
            from: t.from,
            to: t.to,
            condition: t.condition,
            span,
        });
        for s in next {
            self.compute_step(&s)?;
        }
        Ok(())
    }
}
