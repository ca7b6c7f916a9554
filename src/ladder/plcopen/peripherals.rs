//! Library blocks that talk to the world outside the scan: their outputs are what a Python interpreter, a file, the network or an operator at an HMI answers, so they are peripheral reads — free inputs, named as such — not elements ii-prove leaves out.
//!
//! From the libraries that define them: Beremiz's `py_ext/pous.xml` (`python_eval`,
//! `python_poll`, `python_gear`: a Python expression evaluated by the runtime's Python
//! thread, its `ACK` and `RESULT` set when that thread answers, between scans;
//! `csv_read_by_string`, `csv_read_by_int`, `csv_reload`: a CSV file read through it),
//! `NativeLib.xml` (`LOGGER`: a message to the runtime's log), the SVGUI and wxGlade HMI
//! widgets (`Button`, `Led`, `TextCtrl`, `Transform`: what the operator does on the
//! screen), and the OpenPLC editor's communication blocks (`MQTT_*`, `TCP_*`, `CLOUD_*`:
//! a broker, a socket, the Arduino cloud).

/// What the outputs of the library block `type_name` follow, if it is a peripheral.
pub fn peripheral(type_name: &str) -> Option<&'static str> {
    let upper = type_name.to_ascii_uppercase();
    Some(match upper.as_str() {
        "PYTHON_EVAL" | "PYTHON_POLL" | "PYTHON_GEAR" => {
            "its outputs are set when the runtime's Python thread answers, between scans"
        }
        "CSV_READ_BY_STRING" | "CSV_READ_BY_INT" | "CSV_RELOAD" => {
            "its outputs are what a CSV file read through the runtime's Python thread holds"
        }
        "LOGGER" => "it writes a message to the runtime's log",
        "BUTTON" | "LED" | "TEXTCTRL" | "TRANSFORM" => {
            "an HMI widget: its outputs are what the operator does on the screen"
        }
        _ if upper.starts_with("MQTT_") => "its outputs are what the MQTT broker answers",
        _ if upper.starts_with("TCP_") => "its outputs are what the TCP socket gives",
        _ if upper.starts_with("CLOUD_") => "its outputs are what the Arduino cloud answers",
        _ => return None,
    })
}

/// The output `pin` of a block of type `type_name`: `the output ACK of py1
/// (PYTHON_EVAL)`, or the type's name for a block without an instance.
pub fn output_of(type_name: &str, instance: Option<&str>, pin: &str) -> String {
    let upper = type_name.to_ascii_uppercase();
    instance.map_or(upper.clone(), |i| format!("the output {pin} of {i} ({upper})"))
}

/// Where the string a `STRING_TO_*` block converts comes from, when it is known.
pub enum StringSource {
    /// A string literal on its `IN` or on the input variable wired to it: its bytes as
    /// matiec's C holds them ([`string_literal`](crate::iec::literal::string_literal)).
    Literal(Vec<u8>),
    /// An output of a peripheral block: the block and the output's name (upper case).
    Peripheral(usize, String),
}

impl super::PlcProgram {
    /// The peripheral block output wired straight to `input`, if it is one: the block
    /// and the output's name (upper case).
    pub fn peripheral_output(&self, input: &super::PinIn) -> Option<(usize, String)> {
        let [c] = input.conns.as_slice() else { return None };
        let Some(super::Source::BlockOut(j, pin)) = self.source(c) else { return None };
        self.peripherals.contains(&j).then(|| (j, self.output_pin(j, pin).0))
    }

    /// The free input that stands for the integer output `pin` of the peripheral block
    /// `j`: its hidden variable, else `{instance}_{pin}`.
    pub fn peripheral_input(&self, j: usize, pin: &str) -> String {
        match (self.hidden_name(j, pin), self.obj(j).map(|o| &o.kind)) {
            (Some(n), _) => n.to_string(),
            (None, Some(super::ObjKind::Block { instance: Some(i), .. })) => format!("{i}_{pin}"),
            (None, Some(super::ObjKind::Block { type_name, .. })) => {
                format!("_TMP_{}{j}_{pin}", type_name.to_ascii_uppercase())
            }
            _ => format!("_TMP_{j}_{pin}"),
        }
    }

    /// The free input that stands for `STRING_TO_*` (whose `OUT` is `out`) of a
    /// peripheral's string.
    pub fn peripheral_conversion_input(out: &str) -> String {
        format!("{out}_READ")
    }

    /// The string at block `k`'s input `IN`: a literal, or a peripheral's output.
    pub fn string_input(&self, k: usize) -> Option<StringSource> {
        self.pin_string(self.pin(k, "IN")?)?.ok()
    }

    /// The string on `pin`: a literal or a peripheral's output, on the pin or on its wire;
    /// `Err`: the text of the input variable wired to it that is not a literal (a
    /// variable's name). `None` for anything else.
    fn pin_string<'a>(&'a self, pin: &super::PinIn) -> Option<Result<StringSource, &'a str>> {
        if pin.negated || pin.edge != super::Edge::None {
            return None;
        }
        let literal =
            |text: &str| crate::iec::literal::string_literal(text).map(StringSource::Literal);
        if let Some((text, _)) = &pin.expr {
            return literal(text).map(Ok);
        }
        if let Some((j, out)) = self.peripheral_output(pin) {
            return Some(Ok(StringSource::Peripheral(j, out)));
        }
        let [c] = pin.conns.as_slice() else { return None };
        let Some(super::Source::Object(j)) = self.source(c) else { return None };
        match &self.obj(j)?.kind {
            super::ObjKind::InVar { expr, .. } => Some(literal(&expr.0).ok_or(expr.0.as_str())),
            _ => None,
        }
    }

    /// Where block `k` (a comparison) compares only strings that are literals or what
    /// peripherals give (each read on a wire or through a local STRING variable that only
    /// such outputs write), why its result is a peripheral read, naming them. `None`
    /// where an operand is anything else, or no peripheral is read.
    pub fn peripheral_strings(&self, k: usize) -> Option<String> {
        let super::ObjKind::Block { inputs, type_name, .. } = &self.obj(k)?.kind else {
            return None;
        };
        let mut read = Vec::new();
        for pin in inputs.iter().filter(|p| !p.name.eq_ignore_ascii_case("EN")) {
            match self.pin_string(pin)? {
                Ok(StringSource::Literal(_)) => {}
                Ok(StringSource::Peripheral(j, out)) => read.push(self.output_named(j, &out)),
                Err(variable) => read.push(self.peripheral_string_variable(variable)?),
            }
        }
        (!read.is_empty()).then(|| {
            format!(
                "a peripheral read: {} compares strings from outside ({}): its result is any \
                 value at every scan, also where they did not change",
                type_name.to_ascii_uppercase(),
                read.join("; ")
            )
        })
    }

    /// The local STRING variable `name`, where every statement that writes it writes a
    /// peripheral's output (one at least): `Rx_msg, written only by the output MSG of Rx
    /// (TCP_RECEIVE)`.
    fn peripheral_string_variable(&self, name: &str) -> Option<String> {
        let v = self.vars.get(&name.trim().to_ascii_uppercase())?;
        let string = matches!(&v.ty, super::Ty::Other(t) if t.eq_ignore_ascii_case("STRING"));
        if !string || !matches!(v.class, super::VarClass::Local | super::VarClass::Output) {
            return None;
        }
        let mut from = Vec::new();
        for (k, o) in self.objects().iter().enumerate() {
            let (super::ObjKind::OutVar { input, .. } | super::ObjKind::InOutVar { input, .. }) =
                &o.kind
            else {
                continue;
            };
            match self.operands.get(&k) {
                Some(super::Operand::Other(w)) if w.eq_ignore_ascii_case(&v.name) => {
                    let (j, out) = self.peripheral_output(input)?;
                    from.push(self.output_named(j, &out));
                }
                _ => {}
            }
        }
        (!from.is_empty()).then(|| format!("{}, written only by {}", v.name, from.join(" and ")))
    }

    /// The output `pin` of the block at `j`, as [`output_of`] names it.
    fn output_named(&self, j: usize, pin: &str) -> String {
        match self.obj(j).map(|o| &o.kind) {
            Some(super::ObjKind::Block { type_name, instance, .. }) => {
                output_of(type_name, instance.as_deref(), pin)
            }
            _ => format!("the output {pin}"),
        }
    }

    /// The free integer inputs that stand for what peripherals give, with their types
    /// (upper case): each integer output of a peripheral block written into an integer
    /// variable, and each `STRING_TO_<integer>` of a peripheral's string.
    pub fn peripheral_inputs(&self) -> Vec<(String, String)> {
        let mut out = Vec::new();
        for (k, o) in self.objects().iter().enumerate() {
            match &o.kind {
                super::ObjKind::OutVar { input, .. } | super::ObjKind::InOutVar { input, .. } => {
                    let Some(super::Operand::Other(var)) = self.operands.get(&k) else { continue };
                    let (Some(t), Some((j, pin))) =
                        (self.int_var_type(var), self.peripheral_output(input))
                    else {
                        continue;
                    };
                    out.push((self.peripheral_input(j, &pin), t));
                }
                super::ObjKind::Block { type_name, .. } => {
                    let upper = type_name.to_ascii_uppercase();
                    let Some(to) = upper.strip_prefix("STRING_TO_") else { continue };
                    if !matches!(self.string_input(k), Some(StringSource::Peripheral(..))) {
                        continue;
                    }
                    let computed = matches!(
                        super::ints::ConvType::of(to),
                        Ok(super::ints::ConvType::Int(t)) if !t.real
                    );
                    if let (Some(o), true) = (self.hidden_name(k, "OUT"), computed) {
                        out.push((Self::peripheral_conversion_input(o), to.to_string()));
                    }
                }
                _ => {}
            }
        }
        out
    }
}
