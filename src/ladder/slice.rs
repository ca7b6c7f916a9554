//! The part of an LDmicro program a run needs: the rungs that can write the names it watches ([`LdProgram::slice`]), and, for a run whose inputs differ from those of a recorded run of the whole program in a few, only the rungs those inputs set in motion, every other rung they read replayed from the record ([`LdProgram::slice_near`]).
//!
//! Both are read from the rungs themselves (what each element reads and writes), not from
//! the compiled equations, so that a run of a part is still the simulator's own reading of
//! the program.

use std::collections::{BTreeMap, BTreeSet};
use std::sync::{Arc, OnceLock};

use super::ldmicro::{ElementKind, LdProgram};
use super::simulate::{RunRecord, Simulator};
use crate::program::fast_hash::{FastMap as HashMap, FastSet as HashSet};

impl LdProgram {
    /// The rungs that can change `names`, in scan order: those that write a name of
    /// `names` (a coil, a timer's count), then those that write a name a rung taken
    /// reads (its contacts, coils and timers), and so on. Only for programs whose rungs
    /// hold nothing but contacts, coils, timers, `SHORT`, `OPEN`, comments and
    /// placeholders, whose effects are the writes of their coils and timers; `None`
    /// for any other program (a master relay, a one-shot's memory by position,
    /// counters and integers: then the whole program runs).
    pub fn slice(&self, names: &BTreeSet<String>) -> Option<LdProgram> {
        let tables = self.tables()?;
        let keep = tables.writing(names.iter().map(String::as_str), |_| true).0;
        Some(self.part(keep))
    }

    /// A run on `inputs` (one map a scan, at most 64) of the rungs that can write
    /// `names` ([`slice`](Self::slice)), what each wrote recorded for
    /// [`slice_near`](Self::slice_near); `None` where [`slice`](Self::slice) is.
    pub fn record(
        &self,
        names: &BTreeSet<String>,
        inputs: &[BTreeMap<String, bool>],
    ) -> Option<RunRecord> {
        let tables = self.tables()?;
        if inputs.len() > 64 {
            return None;
        }
        let mut kept: Vec<usize> =
            tables.writing(names.iter().map(String::as_str), |_| true).0.into_iter().collect();
        kept.sort_unstable();
        let part = self.part(kept.iter().copied().collect());
        let writes: Vec<&[String]> = kept.iter().map(|&i| tables.writes[i].as_slice()).collect();
        Some(RunRecord::of((&part, &kept, self.rungs.len()), &writes, inputs))
    }

    /// A simulator of the part of [`slice`](Self::slice)`(names)` that the inputs
    /// `changed` can change, for a run of at most `scans` scans whose other inputs are
    /// those of the run `record` recorded (made by [`record`](Self::record) of this
    /// program). A rung is *moved* when it reads, through any chain of rungs, an input
    /// of `changed`; a rung that is not reads only names no writer of which is moved,
    /// so it writes at each scan what it wrote in the recorded run. The part runs the
    /// moved rungs that can write `names` and replays, from the record, the rungs that
    /// are not moved and write what those read. `None` where [`slice`](Self::slice) is,
    /// for a run longer than the record, or when a rung to replay is not recorded.
    pub fn slice_near(
        &self,
        names: &BTreeSet<String>,
        record: &Arc<RunRecord>,
        changed: &BTreeSet<String>,
        scans: usize,
    ) -> Option<Simulator> {
        let tables = self.tables()?;
        if scans > record.scans() || record.rungs() != self.rungs.len() {
            return None;
        }
        let all = tables.writing(names.iter().map(String::as_str), |_| true).0;
        // Moved: every rung of the slice that reads an input of `changed` or a name a
        // moved rung writes. (A writer of a name a rung of the slice reads is in it.)
        let mut moved = HashSet::default();
        let mut seen: HashSet<&str> = changed.iter().map(String::as_str).collect();
        // The changed inputs some rung of the slice reads (from the smaller side).
        let mut pending: Vec<&str> = if changed.len() <= all.len() {
            seen.iter().copied().collect()
        } else {
            all.iter()
                .flat_map(|&i| &tables.reads[i])
                .map(String::as_str)
                .filter(|n| seen.contains(n))
                .collect()
        };
        while let Some(n) = pending.pop() {
            for &i in tables.readers.get(n).map_or(&[][..], Vec::as_slice) {
                if all.contains(&i) && moved.insert(i) {
                    for w in &tables.writes[i] {
                        if seen.insert(w.as_str()) {
                            pending.push(w.as_str());
                        }
                    }
                }
            }
        }
        let (live, replayed) =
            tables.writing(names.iter().map(String::as_str), |i| moved.contains(&i));
        if !replayed.iter().all(|&i| record.has(i)) {
            return None;
        }
        let mut kept: Vec<usize> = live.iter().chain(&replayed).copied().collect();
        kept.sort_unstable();
        kept.dedup();
        let replay = kept.iter().map(|i| (!live.contains(i)).then_some(*i)).collect();
        let part = self.part(kept.into_iter().collect());
        Some(Simulator::replaying(&part, replay, record.clone()))
    }

    /// The program of the rungs `keep`, in scan order.
    fn part(&self, keep: HashSet<usize>) -> LdProgram {
        let mut kept: Vec<usize> = keep.into_iter().collect();
        kept.sort_unstable();
        LdProgram {
            version: self.version.clone(),
            cycle_us: self.cycle_us,
            micro: self.micro.clone(),
            io_list: Vec::new(),
            rungs: kept.into_iter().map(|i| self.rungs[i].clone()).collect(),
            warnings: Vec::new(),
            inputs: self.inputs.clone(),
            var_bytes: self.var_bytes.clone(),
            slicing: SliceIndex::default(),
        }
    }

    fn tables(&self) -> Option<&SliceTables> {
        self.slicing.0.get_or_init(|| self.slice_tables()).as_ref()
    }

    /// The names each rung reads and writes, and the rungs that read and write each
    /// name; `None` for a program [`slice`](Self::slice) does not apply to.
    fn slice_tables(&self) -> Option<SliceTables> {
        let mut reads = Vec::with_capacity(self.rungs.len());
        let mut writes = Vec::with_capacity(self.rungs.len());
        let mut writers: HashMap<String, Vec<usize>> = HashMap::default();
        let mut readers: HashMap<String, Vec<usize>> = HashMap::default();
        for (i, rung) in self.rungs.iter().enumerate() {
            let (mut r, mut w) = (Vec::new(), Vec::new());
            for e in rung.elements() {
                match &e.kind {
                    ElementKind::Contacts { name, .. } => r.push(name.clone()),
                    ElementKind::Coil { name, .. } | ElementKind::Timer { name, .. } => {
                        r.push(name.clone());
                        w.push(name.clone());
                    }
                    ElementKind::Short
                    | ElementKind::Open
                    | ElementKind::Comment(_)
                    | ElementKind::Placeholder => {}
                    _ => return None,
                }
            }
            r.sort_unstable();
            r.dedup();
            w.sort_unstable();
            w.dedup();
            for n in &r {
                readers.entry(n.clone()).or_default().push(i);
            }
            for n in &w {
                writers.entry(n.clone()).or_default().push(i);
            }
            reads.push(r);
            writes.push(w);
        }
        Some(SliceTables { reads, writes, writers, readers })
    }
}

/// The tables [`LdProgram::slice`] walks, built once per program on first use. They
/// are derived from the rungs, so two programs are equal whatever their tables hold,
/// and a clone (which may be changed) starts without them.
#[derive(Default)]
pub struct SliceIndex(OnceLock<Option<SliceTables>>);

/// What each rung reads and writes, and which rungs read and write each name.
struct SliceTables {
    reads: Vec<Vec<String>>,
    writes: Vec<Vec<String>>,
    writers: HashMap<String, Vec<usize>>,
    readers: HashMap<String, Vec<usize>>,
}

impl SliceTables {
    /// The rungs that write `names`, then those that write a name a rung taken reads,
    /// and so on, a rung taken only where `follow` holds of it: the rungs taken, and
    /// the writers met that were not.
    fn writing<'a>(
        &'a self,
        names: impl Iterator<Item = &'a str>,
        follow: impl Fn(usize) -> bool,
    ) -> (HashSet<usize>, HashSet<usize>) {
        let (mut taken, mut left) = (HashSet::default(), HashSet::default());
        let mut seen: HashSet<&str> = names.collect();
        let mut pending: Vec<&str> = seen.iter().copied().collect();
        while let Some(n) = pending.pop() {
            for &i in self.writers.get(n).map_or(&[][..], Vec::as_slice) {
                if !follow(i) {
                    left.insert(i);
                } else if taken.insert(i) {
                    for m in &self.reads[i] {
                        if seen.insert(m.as_str()) {
                            pending.push(m.as_str());
                        }
                    }
                }
            }
        }
        (taken, left)
    }
}

impl Clone for SliceIndex {
    fn clone(&self) -> Self {
        SliceIndex::default()
    }
}

impl PartialEq for SliceIndex {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl Eq for SliceIndex {}

impl std::fmt::Debug for SliceIndex {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("SliceIndex")
    }
}
