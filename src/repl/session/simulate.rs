//! `simulate`: given signals and terms drawn as timing diagrams, evaluated exactly from
//! the semantics (defined signals expanded through their equations) or, with a program
//! loaded, its equations run scan by scan.

use std::collections::BTreeSet;

use super::Session;
use crate::kernel::Rel;
use crate::report::waveform;
use crate::semantics::{Assignment, Signal, Time, eval, format_time};
use crate::syntax;
use crate::term::{Builder, Delay, Expr, Id, Language, Symbol, Term, root};

/// A signal given to `simulate`: name, initial value, changes.
type GivenSignal = (String, bool, Vec<(Time, bool)>);

impl Session {
    pub(super) fn simulate(&mut self, rest: &str) -> String {
        match self.simulate_inner(rest) {
            Ok(lines) => lines,
            Err(e) if e.starts_with("error") => e,
            Err(e) => format!("error: {e}\n"),
        }
    }

    fn duration(&mut self, text: &str) -> Result<Delay, String> {
        let (tokens, errors) = syntax::lexer::lex(text.trim(), 0);
        match (tokens.as_slice(), errors.is_empty()) {
            ([t, _eof], true) => match &t.tok {
                syntax::lexer::Tok::Duration(d) => Ok(d.clone()),
                _ => Err(format!("`{}` is not a duration such as `5s`", text.trim())),
            },
            _ => Err(format!("`{}` is not a duration such as `5s`", text.trim())),
        }
    }

    fn simulate_inner(&mut self, rest: &str) -> Result<String, String> {
        let (head, assigns) = match rest.split_once(" with ") {
            Some((h, a)) => (h, a),
            None => (rest, ""),
        };
        let (terms_text, horizon_text) = match head.split_once(" for ") {
            Some((t, h)) => (t, Some(h)),
            None => (head, None),
        };
        if terms_text.trim().is_empty() {
            return Err("expected `simulate TERM, ... [for DURATION] [with NAME=STEPS ...]`".into());
        }
        // The given signals: NAME=STEPS, separated by spaces or `;`.
        let mut given: Vec<GivenSignal> = Vec::new();
        for item in assigns.split([';', ' ']).map(str::trim).filter(|s| !s.is_empty()) {
            let Some((name, spec)) = item.split_once('=') else {
                return Err(format!("`{item}` should be NAME=STEPS, e.g. L_flow=1@1s,0@6s"));
            };
            let mut initial = false;
            let mut changes = Vec::new();
            for (i, part) in spec.split(',').map(str::trim).enumerate() {
                match part.split_once('@') {
                    Some((v, t)) => {
                        let value = match v.trim() {
                            "1" => true,
                            "0" => false,
                            other => return Err(format!("`{other}` is not 0 or 1")),
                        };
                        changes.push((self.duration(t)?.seconds().clone(), value));
                    }
                    None if i == 0 => {
                        initial = match part {
                            "1" => true,
                            "0" => false,
                            other => return Err(format!("`{other}` is not 0 or 1 (or v@time)")),
                        }
                    }
                    None => return Err(format!("`{part}` should be VALUE@TIME, e.g. 1@2s")),
                }
            }
            let name = name.trim();
            let canonical = match self.scope().lookup(name) {
                syntax::Lookup::Signal(c) => c,
                _ => name.to_string(),
            };
            given.push((canonical, initial, changes));
        }
        let last = given.iter().flat_map(|g| g.2.iter().map(|c| c.0.clone())).max();
        let horizon: Time = match horizon_text {
            Some(h) => self.duration(h)?.seconds().clone(),
            None => {
                let ten = Time::from_integer(10.into());
                match last {
                    Some(t) if t.clone() + Time::from_integer(5.into()) > ten => {
                        t + Time::from_integer(5.into())
                    }
                    _ => ten,
                }
            }
        };
        let mut env = Assignment::new(horizon.clone());
        for (name, initial, changes) in &given {
            let signal = Signal::from_steps(horizon.clone(), *initial, changes)
                .map_err(|e| format!("{name}: {e}"))?;
            env.signals.insert(Symbol::from(name.as_str()), signal);
        }
        if self.program.is_some() {
            return self.simulate_scans(terms_text, &given, &env);
        }
        // Parse the terms; expand defined signals through their equations.
        let mut rows: Vec<(String, Signal)> = given
            .iter()
            .filter_map(|(n, _, _)| {
                env.signals.get(&Symbol::from(n.as_str())).map(|s| (self.display(n), s.clone()))
            })
            .collect();
        let mut zeros: BTreeSet<String> = BTreeSet::new();
        let mut inputs = self.inputs.clone();
        inputs.extend(given.iter().map(|g| g.0.clone()));
        for text in terms_text.split(',').map(str::trim).filter(|t| !t.is_empty()) {
            let file = self.source(text);
            let term = syntax::parse_expression(&self.sources, file, self.scope(), &inputs)
                .map_err(|errors| self.syntax_errors(errors))?;
            let expanded = self.expand(&term, &env)?;
            for node in expanded.as_ref() {
                if let Term::Name(s) = node
                    && !env.signals.contains_key(s)
                {
                    zeros.insert(s.to_string());
                }
            }
            let mut local = env.clone();
            for z in &zeros {
                local
                    .signals
                    .insert(Symbol::from(z.as_str()), Signal::constant(horizon.clone(), false));
            }
            let signal =
                eval(&expanded, &local).map_err(|e| format!("cannot evaluate `{text}`: {e:?}"))?;
            let label = self.term(&term);
            if !rows.iter().any(|(l, _)| *l == label) {
                rows.push((label, signal));
            }
        }
        let mut out: String = waveform::draw(&rows, None, waveform::Glyphs::UNICODE)
            .into_iter()
            .map(|l| format!("{l}\n"))
            .collect();
        if !zeros.is_empty() {
            let list: Vec<String> = zeros.iter().map(|z| self.display(z)).collect();
            out.push_str(&format!("(0 throughout: {})\n", list.join(", ")));
        }
        out.push_str(&format!("horizon {}\n", format_time(&horizon)));
        Ok(out)
    }

    /// `simulate` for a loaded program: its equations run scan by scan (the given
    /// signals read at the start of each scan, every other input 0), the terms drawn.
    fn simulate_scans(
        &mut self,
        terms_text: &str,
        given: &[GivenSignal],
        env: &Assignment,
    ) -> Result<String, String> {
        use crate::counterexample::{ScanTrace, program_model, scans_of, unroll};
        let mut inputs = self.inputs.clone();
        inputs.extend(given.iter().map(|g| g.0.clone()));
        let mut terms = Vec::new();
        for text in terms_text.split(',').map(str::trim).filter(|t| !t.is_empty()) {
            let file = self.source(text);
            let term = syntax::parse_expression(&self.sources, file, self.scope(), &inputs)
                .map_err(|errors| self.syntax_errors(errors))?;
            terms.push(term);
        }
        self.define_atoms()?;
        let Some((_, compiled)) = &self.program else {
            return Err("no program is loaded".into());
        };
        let cycle = Time::new(compiled.cycle_us.into(), 1_000_000u64.into());
        if compiled.cycle_us == 0 {
            return Err("the program has a zero cycle time: it has no scans to simulate".into());
        }
        let count = (&env.horizon / &cycle).ceil().to_integer();
        let scans: usize =
            count.clone().try_into().ok().filter(|n| *n <= 200_000).ok_or_else(|| {
                format!("{count} scans of the cycle is too long to simulate; give a shorter `for`")
            })?;
        let model = program_model(compiled);
        let trace = ScanTrace { cycle: cycle.clone(), scans, values: Default::default() };
        let mut zeros: BTreeSet<String> = BTreeSet::new();
        let mut free = |_: &mut unroll::Concrete, name: &str, k: usize| match env
            .signals
            .get(&Symbol::from(name))
        {
            Some(s) => s.value_at(&trace.instant(k)),
            None => {
                zeros.insert(name.to_string());
                false
            }
        };
        let steps_of = |d: &Delay| scans_of(d, &cycle);
        let extra: Vec<&Expr> = terms.iter().collect();
        let run =
            unroll::unroll(&mut unroll::Concrete, &model, &extra, scans, &steps_of, &mut free)?;
        let mut rows: Vec<(String, Signal)> = given
            .iter()
            .filter_map(|(n, _, _)| {
                env.signals.get(&Symbol::from(n.as_str())).map(|s| (self.display(n), s.clone()))
            })
            .collect();
        for (term, values) in terms.iter().zip(&run.extra) {
            let label = self.term(term);
            if !rows.iter().any(|(l, _)| *l == label) {
                rows.push((label, trace.signal(values)?));
            }
        }
        let mut out: String = waveform::draw(&rows, None, waveform::Glyphs::UNICODE)
            .into_iter()
            .map(|l| format!("{l}\n"))
            .collect();
        let zeros: Vec<String> = zeros.iter().map(|z| self.display(z)).collect();
        if !zeros.is_empty() {
            out.push_str(&format!("(0 throughout: {})\n", zeros.join(", ")));
        }
        out.push_str(&format!(
            "horizon {}, {scans} scans of {}\n",
            format_time(&env.horizon),
            format_time(&cycle)
        ));
        Ok(out)
    }

    /// Replaces signals that have an equation `NAME = ...` (and are not given) by its right side.
    fn expand(&self, term: &Expr, env: &Assignment) -> Result<Expr, String> {
        let definitions: Vec<(Symbol, Expr)> = self
            .checker
            .ctx
            .hypotheses()
            .iter()
            .filter(|h| h.rel == Rel::Eq)
            .filter_map(|h| match &h.lhs[root(&h.lhs)] {
                Term::Name(s) if !env.signals.contains_key(s) => Some((*s, h.rhs.clone())),
                _ => None,
            })
            .collect();
        let mut current = term.clone();
        for _ in 0..50 {
            let mut changed = false;
            let mut b = Builder::default();
            fn go(
                e: &Expr,
                id: Id,
                defs: &[(Symbol, Expr)],
                b: &mut Builder,
                changed: &mut bool,
            ) -> Id {
                if let Term::Name(s) = &e[id]
                    && let Some((_, rhs)) = defs.iter().find(|(n, _)| n == s)
                {
                    *changed = true;
                    return b.term(rhs);
                }
                let node = e[id].clone().map_children(|c| go(e, c, defs, b, changed));
                b.add(node)
            }
            go(&current, root(&current), &definitions, &mut b, &mut changed);
            current = b.finish();
            if !changed {
                return Ok(current);
            }
            if current.as_ref().len() > 10_000 {
                break;
            }
        }
        Err("the signals' equations are cyclic or too large to simulate; give the signals with `with`".into())
    }
}
