//! An optional record of the SAT queries a run makes (clauses, assumptions, varisat's time), so that other solvers can be timed on exactly the same queries (`benches/sat_solvers.py`).
//!
//! Off unless the environment variable `II_PROVE_SAT_TRACE` names a directory. Then
//! each solver instance writes one file there, `KIND-PID-N.trace`, in DIMACS literals:
//!
//! ```text
//! c kind bmc
//! 1 -2 0            a clause
//! a 3 -4 0          solve under the assumptions 3 and -4 (possibly none)
//! r sat 0.000123    the answer and varisat's wall time in seconds for that solve
//! ```
//!
//! Clauses and solves come in the order the run made them, so an incremental solver
//! can replay the file query by query. Nothing here changes what a run decides; a file
//! that cannot be written is skipped (the run goes on without its record).

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::sync::OnceLock;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Duration;

use varisat::Lit;

/// The directory named by `II_PROVE_SAT_TRACE`, read once.
fn directory() -> Option<&'static PathBuf> {
    static DIR: OnceLock<Option<PathBuf>> = OnceLock::new();
    DIR.get_or_init(|| std::env::var_os("II_PROVE_SAT_TRACE").map(PathBuf::from)).as_ref()
}

/// The record of one solver instance; does nothing when tracing is off.
#[derive(Default)]
struct Trace {
    out: Option<BufWriter<File>>,
}

impl Trace {
    /// A record for a new solver instance used for `kind` (`bmc`, `split`, `refute`).
    fn start(kind: &str) -> Trace {
        static NEXT: AtomicUsize = AtomicUsize::new(0);
        let Some(dir) = directory() else { return Trace::default() };
        let n = NEXT.fetch_add(1, Ordering::Relaxed);
        let path = dir.join(format!("{kind}-{}-{n}.trace", std::process::id()));
        let mut out = File::create(path).ok().map(BufWriter::new);
        if let Some(w) = &mut out
            && writeln!(w, "c kind {kind}").is_err()
        {
            out = None;
        }
        Trace { out }
    }

    /// Whether this instance is recorded.
    fn on(&self) -> bool {
        self.out.is_some()
    }

    /// Records a clause.
    fn clause(&mut self, lits: &[Lit]) {
        if let Some(w) = &mut self.out {
            let ok = lits.iter().try_for_each(|l| write!(w, "{} ", l.to_dimacs()));
            if ok.and_then(|()| writeln!(w, "0")).is_err() {
                self.out = None;
            }
        }
    }

    /// Records a solve under `assumptions`, its answer and the time varisat took.
    fn solve(&mut self, assumptions: &[Lit], sat: Option<bool>, took: Duration) {
        if let Some(w) = &mut self.out {
            let answer = match sat {
                Some(true) => "sat",
                Some(false) => "unsat",
                None => "error",
            };
            let ok = write!(w, "a ")
                .and_then(|()| assumptions.iter().try_for_each(|l| write!(w, "{} ", l.to_dimacs())))
                .and_then(|()| writeln!(w, "0\nr {answer} {:.9}", took.as_secs_f64()));
            if ok.is_err() {
                self.out = None;
            }
        }
    }
}

/// A varisat solver whose clauses and solves are recorded in a [`Trace`].
pub struct Traced<'a> {
    /// The solver.
    pub solver: varisat::Solver<'a>,
    trace: Trace,
    /// Whether assumptions are set (a solver writing a DRAT proof must never be given
    /// any, not even an empty set).
    assumed: bool,
}

impl<'a> Traced<'a> {
    /// A new solver, recorded as `kind`.
    pub fn new(kind: &str) -> Traced<'a> {
        Traced { solver: varisat::Solver::new(), trace: Trace::start(kind), assumed: false }
    }

    /// A fresh variable.
    pub fn new_lit(&mut self) -> Lit {
        use varisat::ExtendFormula as _;
        self.solver.new_lit()
    }

    /// Adds a clause.
    pub fn add_clause(&mut self, lits: &[Lit]) {
        use varisat::ExtendFormula as _;
        self.solver.add_clause(lits);
        self.trace.clause(lits);
    }

    /// Solves under `assumptions` (none: `&[]`), recording the query and its time.
    pub fn solve(&mut self, assumptions: &[Lit]) -> Result<bool, varisat::solver::SolverError> {
        if self.assumed || !assumptions.is_empty() {
            self.solver.assume(assumptions);
            self.assumed = !assumptions.is_empty();
        }
        let start = self.trace.on().then(std::time::Instant::now);
        let answer = self.solver.solve();
        if let Some(start) = start {
            self.trace.solve(assumptions, answer.as_ref().ok().copied(), start.elapsed());
        }
        answer
    }
}
