//! ii-prove: a theorem prover for the II algebra of binary signals.
//!
//! Layers, from the trusted bottom up (see `ARCHITECTURE.md`):
//! [`term`] (the term type) → [`kernel`] (re-checks proofs; the only maker of
//! theorems) → [`semantics`] (exact evaluation of terms on signals) →
//! [`syntax`] (the `.ii` language) → [`theory`] (laws as data) → prover, ladder
//! front ends, REPL and CLI.
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod certificate;
pub mod counterexample;
pub mod diag;
pub mod iec;
pub mod kernel;
pub mod ladder;
pub mod program;
pub mod prover;
pub mod refutation;
pub mod repl;
pub mod report;
pub mod sat_trace;
pub mod script;
pub mod semantics;
pub mod syntax;
pub mod term;
pub mod theory;
