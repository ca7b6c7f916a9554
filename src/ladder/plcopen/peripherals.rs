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
