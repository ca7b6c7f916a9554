//! The test suite, one binary: each module is what a test file of its name checks
//! (`cargo test --release --test suite st::` runs the Structured Text tests), sharing
//! the helpers of `common/` compiled once, and its tests run side by side on every core.

mod common;

mod aiger;
mod cli;
mod compile;
mod counterexamples;
mod differential;
mod elapsed_time;
mod equiv;
mod formats;
mod html;
mod iec_oracle;
mod il;
mod integer_properties;
mod integers;
mod kernel;
mod kernel_scans;
mod laws;
mod ldmicro;
mod no_panic;
mod patterns;
mod plcopen;
mod plcopen_differential;
mod plcopen_oracle;
mod refutation;
mod repl;
mod sat_trace;
mod scripts;
mod semantics;
mod sfc;
mod shared_lemmas;
mod slice;
mod soundness;
mod st;
mod syntax_errors;
mod syntax_roundtrip;
mod tidy;
mod timer_examples;
mod timer_properties;
mod unknowns;
mod verdicts;
