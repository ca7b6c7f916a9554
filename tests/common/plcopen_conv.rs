//! The random PLCopen generator's draws between BOOL and integers and between integer types: `BOOL_TO_INT` of negated pins and Boolean blocks, `INT_TO_BOOL`, round trips through other integer types, SINT division by a SINT.

use std::fmt::Write as _;

use super::{Gen, SINT_VAR};

/// The types an integer goes through and back in a `CONV` draw (`INT_TO_X`, then
/// `X_TO_INT` or `X_TO_BOOL`): narrower ones wrap, unsigned ones wrap negatives.
const CONV_TYPES: &[&str] = &["SINT", "USINT", "BYTE", "UINT", "WORD", "DINT", "UDINT", "DWORD"];

impl Gen {
    /// A one-input block `ty` (`IN` from `src`, with the modifier `m`): its id.
    pub(super) fn unary(&mut self, ty: &str, src: (u64, Option<&'static str>), m: &str) -> u64 {
        let id = self.nid();
        let (p, o) = (self.pos(400), self.order(true));
        writeln!(
            self.body,
            r#"<block localId="{id}" typeName="{ty}"{o}>{p}<inputVariables><variable formalParameter="IN"{m}>{}</variable></inputVariables><inOutVariables/><outputVariables><variable formalParameter="OUT"><connectionPointOut/></variable></outputVariables></block>"#,
            Gen::conn(&[src])
        )
        .unwrap();
        id
    }

    /// The draws of [`INT_BLOCKS`] between BOOL and integers and between integer types
    /// (`false` for the others): `BOOL_TO_INT` of a Boolean (negated pins, comparisons,
    /// ANDs), `INT_TO_BOOL`, an AND of Booleans, a round trip through another integer
    /// type (`CONV`), a SINT division or remainder by a SINT (`DIVS`).
    pub(super) fn conversion(
        &mut self,
        ty: &str,
        ints: &mut Vec<(u64, Option<&'static str>)>,
        bools: &mut Vec<(u64, Option<&'static str>)>,
    ) -> bool {
        let negated = |g: &mut Gen| if g.rng.chance(40) { r#" negated="true""# } else { "" };
        match ty {
            "BOOL_TO_INT" => {
                let (src, m) = (*self.rng.pick(bools), negated(self));
                ints.push((self.unary(ty, src, m), Some("OUT")));
            }
            "INT_TO_BOOL" => {
                let src = *self.rng.pick(ints);
                bools.push((self.unary(ty, src, ""), Some("OUT")));
            }
            "AND" => {
                let id = self.nid();
                let (p, o) = (self.pos(200), self.order(true));
                let mut ins = String::new();
                for pin in ["IN1", "IN2"] {
                    let (src, m) = (*self.rng.pick(bools), negated(self));
                    let c = Gen::conn(&[src]);
                    write!(ins, r#"<variable formalParameter="{pin}"{m}>{c}</variable>"#).unwrap();
                }
                writeln!(
                    self.body,
                    r#"<block localId="{id}" typeName="AND"{o}>{p}<inputVariables>{ins}</inputVariables><inOutVariables/><outputVariables><variable formalParameter="OUT"><connectionPointOut/></variable></outputVariables></block>"#
                )
                .unwrap();
                bools.push((id, Some("OUT")));
            }
            "CONV" => {
                let x = *self.rng.pick(CONV_TYPES);
                let src = *self.rng.pick(ints);
                let there = (self.unary(&format!("INT_TO_{x}"), src, ""), Some("OUT"));
                if self.rng.chance(30) {
                    bools.push((self.unary(&format!("{x}_TO_BOOL"), there, ""), Some("OUT")));
                } else {
                    ints.push((self.unary(&format!("{x}_TO_INT"), there, ""), Some("OUT")));
                }
            }
            "DIVS" => {
                let op = if self.rng.chance(50) { "DIV" } else { "MOD" };
                let a = (self.in_var(SINT_VAR, true), None);
                let src = *self.rng.pick(ints);
                let d = (self.unary("INT_TO_SINT", src, ""), Some("OUT"));
                let id = self.nid();
                let (p, o) = (self.pos(200), self.order(true));
                writeln!(
                    self.body,
                    r#"<block localId="{id}" typeName="{op}"{o}>{p}<inputVariables><variable formalParameter="IN1">{}</variable><variable formalParameter="IN2">{}</variable></inputVariables><inOutVariables/><outputVariables><variable formalParameter="OUT"><connectionPointOut/></variable></outputVariables></block>"#,
                    Gen::conn(&[a]),
                    Gen::conn(&[d])
                )
                .unwrap();
                ints.push((self.unary("SINT_TO_INT", (id, Some("OUT")), ""), Some("OUT")));
            }
            _ => return false,
        }
        true
    }
}
