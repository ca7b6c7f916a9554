//! Exact semantics: signals on a finite horizon and the evaluation of terms on them.
//!
//! [`signal`] holds the [`Signal`] type and the operators of the II algebra,
//! exactly as `/work/shared/spec/semantics.md` defines them; [`mod@eval`]
//! evaluates a term on an [`Assignment`]; [`random`] has the proptest
//! strategies that produce the hard cases (shared change instants, isolated
//! points, pulses as long as the delays).

pub mod eval;
pub mod falsify;
pub mod random;
pub mod signal;

pub use eval::{Assignment, EvalError, eval, eval_delay, eval_signal, free_names};
pub use signal::{Signal, Time, format_time};
