//! The random PLCopen generator's draws between BOOL and integers and between integer types: `BOOL_TO_INT` of negated pins and Boolean blocks, `INT_TO_BOOL`, round trips through other integer types, SINT division by a SINT, conversions from and to BCD.

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
            "BCD" => self.bcd(ints, bools),
            _ => return false,
        }
        true
    }

    /// A conversion from or to BCD of an integer of the network, converted to a type
    /// Beremiz pairs with BCD and back to INT: `BCD_TO_UINT` of a `WORD` (digits above 9
    /// among its values: `OUT` 0 and `ENO` FALSE), `UINT_TO_BCD` (digits past the width
    /// dropped), of each width, `EN` wired sometimes.
    fn bcd(
        &mut self,
        ints: &mut Vec<(u64, Option<&'static str>)>,
        bools: &mut Vec<(u64, Option<&'static str>)>,
    ) {
        let (uint, bits) =
            *self.rng.pick(&[("USINT", "BYTE"), ("UINT", "WORD"), ("UDINT", "DWORD")]);
        let to_bcd = self.rng.chance(50);
        let (from, to, back) = if to_bcd {
            (uint, format!("{uint}_TO_BCD"), bits)
        } else {
            (bits, format!("BCD_TO_{uint}"), uint)
        };
        let src = *self.rng.pick(ints);
        let x = (self.unary(&format!("INT_TO_{from}"), src, ""), Some("OUT"));
        let en = self.rng.chance(30).then(|| *self.rng.pick(bools));
        let id = self.nid();
        let (p, o) = (self.pos(300), self.order(true));
        let (mut ins, mut outs) = (String::new(), String::new());
        if let Some(src) = en {
            write!(ins, r#"<variable formalParameter="EN">{}</variable>"#, Gen::conn(&[src]))
                .unwrap();
            outs.push_str(r#"<variable formalParameter="ENO"><connectionPointOut/></variable>"#);
            bools.push((id, Some("ENO")));
        }
        write!(ins, r#"<variable formalParameter="IN">{}</variable>"#, Gen::conn(&[x])).unwrap();
        writeln!(
            self.body,
            r#"<block localId="{id}" typeName="{to}"{o}>{p}<inputVariables>{ins}</inputVariables><inOutVariables/><outputVariables>{outs}<variable formalParameter="OUT"><connectionPointOut/></variable></outputVariables></block>"#
        )
        .unwrap();
        ints.push((self.unary(&format!("{back}_TO_INT"), (id, Some("OUT")), ""), Some("OUT")));
    }
}
