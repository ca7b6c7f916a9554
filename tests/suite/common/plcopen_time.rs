//! The random PLCopen generator's TIME variables as timer presets: `D0` declared with a literal and written only with it (its timers exact), `D1` declared with one literal and, in FBD bodies, also written with another (its timers unconstrained, though the simulator reads its current value at each call), drawn apart from the other draws.

use std::fmt::Write as _;

use super::{Gen, PRESETS, Rng};

/// The TIME variables: written with one literal, written with two.
pub(super) const TIME_VARS: [&str; 2] = ["D0", "D1"];

/// The TIME variables of one program: their declared literals, D1's second one, and the
/// draws that place them.
pub(super) struct Times {
    pub rng: Rng,
    pub init: [&'static str; 2],
    pub second: &'static str,
}

impl Times {
    /// The draws for `seed`.
    pub fn new(seed: u64) -> Times {
        let mut rng = Rng::new(seed ^ 0x7E0D);
        let init = [*rng.pick(PRESETS), *rng.pick(PRESETS)];
        let others: Vec<&'static str> = PRESETS.iter().copied().filter(|p| *p != init[1]).collect();
        let second = *rng.pick(&others);
        Times { rng, init, second }
    }

    /// The declarations of the TIME variables.
    pub fn decls(&self) -> String {
        TIME_VARS
            .iter()
            .zip(self.init)
            .map(|(n, d)| {
                format!(
                    r#"<variable name="{n}"><type><TIME/></type><initialValue><simpleValue value="{d}"/></initialValue></variable>"#
                )
            })
            .collect::<Vec<_>>()
            .join("\n")
    }
}

impl Gen {
    /// A timer's `PT`: now and then a TIME variable instead of the literal `literal`.
    pub(super) fn preset(&mut self, literal: &'static str) -> &'static str {
        let Some(t) = self.times.as_mut() else { return literal };
        if !t.rng.chance(35) {
            return literal;
        }
        TIME_VARS[usize::from(t.rng.chance(50))]
    }

    /// In an FBD body: the TIME variables' writes, `D0 := its literal` sometimes, and
    /// `D1 := another literal` (before or after its timers, by the statement order).
    pub(super) fn time_writes(&mut self) {
        let Some(t) = self.times.as_mut() else { return };
        let mut writes = Vec::new();
        if t.rng.chance(50) {
            writes.push((t.init[0], TIME_VARS[0]));
        }
        if t.rng.chance(70) {
            writes.push((t.second, TIME_VARS[1]));
        }
        for (literal, target) in writes {
            let src = self.in_var(literal, true);
            let id = self.nid();
            let (p, o) = (self.pos(500), self.order(true));
            writeln!(
                self.body,
                r#"<outVariable localId="{id}"{o}>{p}{}<expression>{target}</expression></outVariable>"#,
                Gen::conn(&[(src, None)])
            )
            .unwrap();
        }
    }
}
