//! The part of `quanta` that egg uses (`quanta::Instant`: `now`, `elapsed`, arithmetic),
//! on `std::time::Instant`.
//!
//! The real crate reads the TSC and, at its first reading in a process, calibrates it
//! against the monotonic clock in a busy loop of at least 500 rounds until the error is
//! under 10 ns: 2 to 5 ms on a virtual machine, paid by every `ii-prove` run at its first
//! e-graph rebuild, with the other threads waiting for it. egg reads the clock a few
//! times per rebuild and per runner iteration, where the vDSO's `clock_gettime` behind
//! `std::time::Instant` costs a few tens of nanoseconds. The semantics are quanta's:
//! differences saturate at zero.

use std::ops::{Add, AddAssign, Sub, SubAssign};
use std::time::Duration;

/// A point in time (monotonic).
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Debug)]
pub struct Instant(std::time::Instant);

impl Instant {
    /// The current time.
    pub fn now() -> Instant {
        Instant(std::time::Instant::now())
    }

    /// The current time (quanta's cached reading; here the same as [`Instant::now`]).
    pub fn recent() -> Instant {
        Instant::now()
    }

    /// The time from `earlier` to this instant, zero if `earlier` is later.
    pub fn duration_since(&self, earlier: Instant) -> Duration {
        self.0.saturating_duration_since(earlier.0)
    }

    /// The time from `earlier` to this instant, `None` if `earlier` is later.
    pub fn checked_duration_since(&self, earlier: Instant) -> Option<Duration> {
        self.0.checked_duration_since(earlier.0)
    }

    /// The time from `earlier` to this instant, zero if `earlier` is later.
    pub fn saturating_duration_since(&self, earlier: Instant) -> Duration {
        self.0.saturating_duration_since(earlier.0)
    }

    /// The time since this instant.
    pub fn elapsed(&self) -> Duration {
        self.0.elapsed()
    }

    /// `self + duration`, if representable.
    pub fn checked_add(&self, duration: Duration) -> Option<Instant> {
        self.0.checked_add(duration).map(Instant)
    }

    /// `self - duration`, if representable.
    pub fn checked_sub(&self, duration: Duration) -> Option<Instant> {
        self.0.checked_sub(duration).map(Instant)
    }
}

impl Add<Duration> for Instant {
    type Output = Instant;

    fn add(self, other: Duration) -> Instant {
        self.checked_add(other).expect("overflow when adding duration to instant")
    }
}

impl AddAssign<Duration> for Instant {
    fn add_assign(&mut self, other: Duration) {
        *self = *self + other;
    }
}

impl Sub<Duration> for Instant {
    type Output = Instant;

    fn sub(self, other: Duration) -> Instant {
        self.checked_sub(other).expect("overflow when subtracting duration from instant")
    }
}

impl SubAssign<Duration> for Instant {
    fn sub_assign(&mut self, other: Duration) {
        *self = *self - other;
    }
}

impl Sub<Instant> for Instant {
    type Output = Duration;

    fn sub(self, other: Instant) -> Duration {
        self.duration_since(other)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn differences_saturate_at_zero_as_quantas_do() {
        let a = Instant::now();
        let b = a + Duration::from_millis(5);
        assert_eq!(b - a, Duration::from_millis(5));
        assert_eq!(a - b, Duration::ZERO);
        assert_eq!(a.checked_duration_since(b), None);
        assert!(a.elapsed() >= Duration::ZERO && b > a);
    }
}
