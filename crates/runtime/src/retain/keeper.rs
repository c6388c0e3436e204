//! Keeping the RETAIN file of a running PLC: only states reached at the end
//! of a scan are ever saved.
//!
//! The [`Keeper`] is a [`ScanObserver`] wrapped around the run's own
//! observer: after each completed scan it copies the retain ranges of the
//! image (a snapshot, usually a few bytes), and every `save_every` of PLC
//! time saves that snapshot when it changed since the last save. A scan
//! that faults never reaches the observer, so after a fault the snapshot is
//! the image before the faulting scan began; [`Keeper::finish`] saves it
//! at the end of the run, whatever the fault or the safe state did to the
//! image since. A periodic save that fails does not stop the PLC (its
//! machine matters more than its memory): the failures are counted and the
//! last one kept for the caller to report.

use super::{encode_payload, layout_hash, payload, save_bytes};
use crate::scan::ScanObserver;
use crate::stats::Stats;
use automat_ir::Program;
use std::ops::Range;
use std::path::PathBuf;

pub struct Keeper<'a> {
    path: PathBuf,
    ranges: Vec<Range<usize>>,
    hash: u64,
    every_ns: Option<i64>,
    /// The retain ranges at the end of the last completed scan.
    snapshot: Vec<u8>,
    /// What the file holds (`None` until this run saved it).
    saved: Option<Vec<u8>>,
    last_save_ns: Option<i64>,
    inner: &'a mut dyn ScanObserver,
    /// Periodic saves that failed, and the message of the last one.
    pub failures: u64,
    pub last_error: Option<String>,
    /// Periodic saves done.
    pub saves: u64,
}

impl<'a> Keeper<'a> {
    /// A keeper of `path` for `program`, starting from `image` (cold- or
    /// warm-started, before the first scan); `every_ns` the period of
    /// saves in PLC time (`None`: only at the end). `None` when a retain
    /// range is not inside the image.
    pub fn new(
        program: &Program,
        image: &[u8],
        path: PathBuf,
        every_ns: Option<i64>,
        inner: &'a mut dyn ScanObserver,
    ) -> Option<Keeper<'a>> {
        let ranges = program
            .retain
            .iter()
            .map(|r| Some(usize::try_from(r.start).ok()?..usize::try_from(r.end).ok()?))
            .collect::<Option<Vec<_>>>()?;
        Some(Keeper {
            path,
            ranges,
            hash: layout_hash(program),
            every_ns: every_ns.filter(|&n| n > 0),
            snapshot: payload(program, image)?,
            saved: None,
            last_save_ns: None,
            inner,
            failures: 0,
            last_error: None,
            saves: 0,
        })
    }

    /// The retain bytes of the last consistent image.
    pub fn snapshot(&self) -> &[u8] {
        &self.snapshot
    }

    fn take_snapshot(&mut self, image: &[u8]) {
        let mut at = 0;
        for r in &self.ranges {
            let (Some(src), Some(dst)) = (
                image.get(r.clone()),
                self.snapshot.get_mut(at..at + r.len()),
            ) else {
                continue;
            };
            dst.copy_from_slice(src);
            at += r.len();
        }
    }

    /// Saves the snapshot unless the file already holds it.
    fn save(&mut self) -> Result<(), String> {
        if self.saved.as_deref() == Some(self.snapshot.as_slice()) {
            return Ok(());
        }
        let data = encode_payload(self.hash, &self.snapshot)
            .ok_or_else(|| format!("{}: the RETAIN data is too large", self.path.display()))?;
        save_bytes(&self.path, &data)?;
        self.saved = Some(self.snapshot.clone());
        Ok(())
    }

    /// The final save at the end of the run: the snapshot of the last
    /// completed scan (or the start image when none completed).
    pub fn finish(&mut self) -> Result<(), String> {
        self.saved = None;
        self.save()
    }
}

impl ScanObserver for Keeper<'_> {
    fn after_scan(&mut self, plc_time_ns: i64, image: &[u8]) -> Result<(), String> {
        self.take_snapshot(image);
        if let Some(every) = self.every_ns {
            let last = *self.last_save_ns.get_or_insert(plc_time_ns);
            if plc_time_ns.saturating_sub(last) >= every {
                self.last_save_ns = Some(plc_time_ns);
                match self.save() {
                    Ok(()) => self.saves += 1,
                    Err(e) => {
                        self.failures += 1;
                        self.last_error = Some(e);
                    }
                }
            }
        }
        self.inner.after_scan(plc_time_ns, image)
    }

    fn stats(&mut self, stats: &Stats) {
        self.inner.stats(stats);
    }
}
