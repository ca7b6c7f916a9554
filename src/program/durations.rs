//! TIME variables that are constant in fact: when every write of the whole program, the initial value included, gives the same literal duration, a timer whose preset is that variable reads that duration at every call; the front ends list the writes, this decides.

/// One write of a TIME variable, as a front end found it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TimeWrite {
    /// A literal duration (µs) and where it is written (`at line 12`, `by an outVariable`).
    Literal(u64, String),
    /// A value that is not a literal duration: what and where (`an expression at line 12`).
    Other(String),
}

/// The duration (µs) a TIME variable holds at every read when it starts at `init` and
/// `writes` are all its writes, or why it may hold another: a write of another duration,
/// or of a value that is not a literal.
pub fn constant_value(init: u64, writes: &[TimeWrite]) -> Result<u64, String> {
    for w in writes {
        match w {
            TimeWrite::Literal(us, _) if *us == init => {}
            TimeWrite::Literal(us, at) => {
                return Err(format!(
                    "it holds {} and is also written with {} {at}",
                    show(init),
                    show(*us)
                ));
            }
            TimeWrite::Other(what) => {
                return Err(format!("it is written with {what}, not a literal duration"));
            }
        }
    }
    Ok(init)
}

/// A duration in µs as an IEC literal (`T#2s`, `T#1500ms`, `T#250us`).
pub fn show(us: u64) -> String {
    crate::syntax::print::duration(us)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_value_or_the_first_other() {
        let lit = |us, at: &str| TimeWrite::Literal(us, at.into());
        assert_eq!(constant_value(2_000_000, &[]), Ok(2_000_000));
        assert_eq!(constant_value(2_000_000, &[lit(2_000_000, "at line 3")]), Ok(2_000_000));
        assert_eq!(
            constant_value(2_000_000, &[lit(2_000_000, "at line 3"), lit(3_000, "at line 4")]),
            Err("it holds T#2s and is also written with T#3ms at line 4".into())
        );
        assert_eq!(
            constant_value(0, &[TimeWrite::Other("`a + b` at line 5".into())]),
            Err("it is written with `a + b` at line 5, not a literal duration".into())
        );
        assert_eq!(show(1_500), "T#1500us");
    }
}
