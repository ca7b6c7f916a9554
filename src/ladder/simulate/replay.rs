//! Rungs replayed from a recorded run of the whole program: what each rung wrote at each scan of that run, written again in the rung's turn by a simulator of part of the program that runs on nearly the same inputs ([`LdProgram::slice_near`](crate::ladder::LdProgram::slice_near)).

use std::collections::BTreeMap;
use std::sync::Arc;

use super::Simulator;
use crate::ladder::LdProgram;

/// What each rung of a program wrote at each scan of a run.
#[derive(Debug)]
pub struct RunRecord {
    scans: usize,
    /// How many rungs the recorded program has.
    rungs: usize,
    /// Per rung recorded (by its index in the program), per name it writes, its values
    /// just after the rung.
    writes: std::collections::HashMap<usize, Vec<Written>>,
}

/// A name's values just after a rung, one bit a scan (at most 64 scans).
#[derive(Debug)]
struct Written {
    name: String,
    /// Whether the name is a bit of the simulator (a coil), not only an integer.
    bit: bool,
    bits: u64,
    /// The scans where the value is not exact.
    unknown: u64,
    /// The integer (a timer's count), at the scans where there is one.
    ints: Option<Box<[Option<i64>]>>,
}

/// Which rungs of a simulator's program are replayed, by their index in the program
/// that was recorded.
#[derive(Clone, Debug)]
pub(super) struct Replay {
    rungs: Vec<Option<usize>>,
    record: Arc<RunRecord>,
}

impl Replay {
    /// The recorded rung the simulator's rung `i` replays, if it is replayed.
    pub(super) fn rung(&self, i: usize) -> Option<usize> {
        self.rungs.get(i).copied().flatten()
    }
}

impl RunRecord {
    /// How many scans are recorded.
    pub fn scans(&self) -> usize {
        self.scans
    }

    /// How many rungs the recorded program has.
    pub fn rungs(&self) -> usize {
        self.rungs
    }

    /// Whether the rung of index `k` (in the program) is recorded.
    pub fn has(&self, k: usize) -> bool {
        self.writes.contains_key(&k)
    }

    /// Runs `part`, the rungs `origin` (their indices in a program of `rungs` rungs), from
    /// power-up on `inputs` (one map a scan, at most 64 scans), recording after each
    /// rung the names `writes` gives for it (in the part's order).
    pub fn of(
        (part, origin, rungs): (&LdProgram, &[usize], usize),
        writes: &[&[String]],
        inputs: &[BTreeMap<String, bool>],
    ) -> RunRecord {
        let scans = inputs.len().min(64);
        let mut record: Vec<Vec<Written>> = writes
            .iter()
            .map(|names| {
                names
                    .iter()
                    .map(|n| Written {
                        name: n.clone(),
                        bit: false,
                        bits: 0,
                        unknown: 0,
                        ints: None,
                    })
                    .collect()
            })
            .collect();
        let mut sim = Simulator::new(part);
        for (k, step) in inputs.iter().take(scans).enumerate() {
            sim.scan(step, &mut |sim, i| {
                for w in record.get_mut(i).map_or(&mut [][..], Vec::as_mut_slice) {
                    w.bit |= sim.bits.contains_key(&w.name);
                    w.bits |= u64::from(sim.bit(&w.name)) << k;
                    w.unknown |= u64::from(!sim.is_known(&w.name)) << k;
                    if let Some(v) = sim.ints.get(&w.name) {
                        w.ints.get_or_insert_with(|| vec![None; scans].into())[k] = Some(*v);
                    }
                }
            });
        }
        let writes = origin.iter().copied().zip(record).collect();
        RunRecord { scans, rungs, writes }
    }
}

impl Simulator {
    /// A simulator of `part` whose rung `i` is replayed from `record`'s rung
    /// `replay[i]` where that is given.
    pub(in crate::ladder) fn replaying(
        part: &LdProgram,
        replay: Vec<Option<usize>>,
        record: Arc<RunRecord>,
    ) -> Simulator {
        let mut sim = Simulator::new(part);
        sim.replay = Some(Replay { rungs: replay, record });
        sim
    }

    /// Writes what the recorded rung `k` wrote at this scan of the recorded run; past
    /// the record, its names are not exact.
    pub(super) fn replay_rung(&mut self, k: usize) {
        let Some(record) = self.replay.as_ref().map(|r| r.record.clone()) else { return };
        let scan = usize::try_from(self.scans).unwrap_or(usize::MAX);
        for w in record.writes.get(&k).map_or(&[][..], Vec::as_slice) {
            if scan >= record.scans {
                self.mark(&w.name, false);
                continue;
            }
            let sure = w.unknown >> scan & 1 == 0;
            if w.bit {
                self.set_bit(&w.name, w.bits >> scan & 1 == 1, sure);
            }
            self.mark(&w.name, sure);
            if let Some(v) = w.ints.as_ref().and_then(|vs| vs[scan]) {
                self.set_int(&w.name, v, sure);
            }
        }
    }
}
