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
//!
//! A durable save waits for the disk (two fsyncs, tens of milliseconds on
//! an ordinary disk), longer than many scan cycles. In real time the
//! periodic saves therefore go to a writer thread ([`Keeper::in_background`]):
//! the scan only copies the snapshot and hands it over; a newer snapshot
//! replaces one the writer has not started yet. The final save is always
//! done by [`Keeper::finish`] itself, after the writer has finished.

use super::{encode_payload, layout_hash, payload, save_bytes};
use crate::scan::ScanObserver;
use crate::stats::Stats;
use automat_ir::Program;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Condvar, Mutex, PoisonError};
use std::thread::JoinHandle;

/// What the scan and the writer thread share.
#[derive(Default)]
struct Slot {
    /// File bytes waiting to be written.
    pending: Option<Vec<u8>>,
    stop: bool,
    written: u64,
    failures: u64,
    last_error: Option<String>,
}

type Shared = Arc<(Mutex<Slot>, Condvar)>;

struct Writer {
    shared: Shared,
    handle: Option<JoinHandle<()>>,
}

fn lock(shared: &Shared) -> std::sync::MutexGuard<'_, Slot> {
    shared.0.lock().unwrap_or_else(PoisonError::into_inner)
}

/// The writer thread: writes whatever is pending until told to stop (and
/// nothing is pending any more).
fn write_loop(path: &Path, shared: &Shared) {
    loop {
        let data = {
            let mut slot = lock(shared);
            loop {
                if let Some(d) = slot.pending.take() {
                    break d;
                }
                if slot.stop {
                    return;
                }
                slot = shared.1.wait(slot).unwrap_or_else(PoisonError::into_inner);
            }
        };
        let result = save_bytes(path, &data);
        let mut slot = lock(shared);
        match result {
            Ok(()) => slot.written += 1,
            Err(e) => {
                slot.failures += 1;
                slot.last_error = Some(e);
            }
        }
    }
}

impl Writer {
    /// Stops the thread once everything pending is written; the counts.
    fn stop(&mut self) -> (u64, u64, Option<String>) {
        lock(&self.shared).stop = true;
        self.shared.1.notify_all();
        if let Some(h) = self.handle.take() {
            let _ = h.join();
        }
        let mut slot = lock(&self.shared);
        (slot.written, slot.failures, slot.last_error.take())
    }
}

pub struct Keeper<'a> {
    /// `None`: no RETAIN file, the keeper only passes scans on.
    path: Option<PathBuf>,
    ranges: Vec<Range<usize>>,
    hash: u64,
    every_ns: Option<i64>,
    /// The retain ranges at the end of the last completed scan (`None`
    /// when a range is not inside the image).
    snapshot: Option<Vec<u8>>,
    /// What the file holds (`None` until this run saved it).
    saved: Option<Vec<u8>>,
    last_save_ns: Option<i64>,
    inner: &'a mut dyn ScanObserver,
    /// Periodic saves that failed, and the message of the last one.
    pub failures: u64,
    pub last_error: Option<String>,
    /// Periodic saves that wrote the file (an unchanged snapshot is not
    /// written again); with a writer thread, counted at [`Keeper::finish`].
    pub saves: u64,
    writer: Option<Writer>,
}

impl<'a> Keeper<'a> {
    /// A keeper of `path` (`None`: no RETAIN file) for `program`, starting
    /// from `image` (cold- or warm-started, before the first scan);
    /// `every_ns` the period of saves in PLC time (`None`: only at the
    /// end); `inner` the run's own observer, which sees every scan after
    /// the keeper.
    pub fn new(
        program: &Program,
        image: &[u8],
        path: Option<PathBuf>,
        every_ns: Option<i64>,
        inner: &'a mut dyn ScanObserver,
    ) -> Keeper<'a> {
        let ranges = program
            .retain
            .iter()
            .filter_map(|r| Some(usize::try_from(r.start).ok()?..usize::try_from(r.end).ok()?))
            .collect();
        let snapshot = path.as_ref().and_then(|_| payload(program, image));
        Keeper {
            path,
            ranges,
            hash: layout_hash(program),
            every_ns: every_ns.filter(|&n| n > 0),
            snapshot,
            saved: None,
            last_save_ns: None,
            inner,
            failures: 0,
            last_error: None,
            saves: 0,
            writer: None,
        }
    }

    /// Periodic saves are written by a thread of their own, so a scan
    /// never waits for the disk (for real-time runs). Without a RETAIN
    /// file, or when no thread can be started, saves stay in the scan.
    pub fn in_background(mut self) -> Self {
        let Some(path) = self.path.clone() else {
            return self;
        };
        let shared: Shared = Arc::default();
        let theirs = Arc::clone(&shared);
        let spawned = std::thread::Builder::new()
            .name("retain-writer".into())
            .spawn(move || write_loop(&path, &theirs));
        if let Ok(h) = spawned {
            self.writer = Some(Writer {
                shared,
                handle: Some(h),
            });
        }
        self
    }

    /// Stops the writer thread (after what it still had to write) and
    /// takes over its counts.
    fn stop_writer(&mut self) {
        if let Some(mut w) = self.writer.take() {
            let (written, failures, last_error) = w.stop();
            self.saves += written;
            self.failures += failures;
            if last_error.is_some() {
                self.last_error = last_error;
            }
        }
    }

    /// The retain bytes of the last consistent image.
    pub fn snapshot(&self) -> &[u8] {
        self.snapshot.as_deref().unwrap_or_default()
    }

    fn take_snapshot(&mut self, image: &[u8]) {
        let Some(snapshot) = self.snapshot.as_mut() else {
            return;
        };
        let mut at = 0;
        for r in &self.ranges {
            let (Some(src), Some(dst)) = (image.get(r.clone()), snapshot.get_mut(at..at + r.len()))
            else {
                continue;
            };
            dst.copy_from_slice(src);
            at += r.len();
        }
    }

    /// Saves the snapshot unless the file already holds it; `Ok(false)`
    /// when nothing had to be written.
    fn save(&mut self) -> Result<bool, String> {
        let Some(path) = &self.path else {
            return Ok(false);
        };
        let Some(snapshot) = &self.snapshot else {
            return Err(format!(
                "{}: a RETAIN range lies outside the memory image",
                path.display()
            ));
        };
        if self.saved.as_ref() == Some(snapshot) {
            return Ok(false);
        }
        let data = encode_payload(self.hash, snapshot)
            .ok_or_else(|| format!("{}: the RETAIN data is too large", path.display()))?;
        match &self.writer {
            Some(w) => {
                lock(&w.shared).pending = Some(data);
                w.shared.1.notify_one();
                self.saved = Some(snapshot.clone());
                // Counted by the writer.
                Ok(false)
            }
            None => {
                save_bytes(path, &data)?;
                self.saved = Some(snapshot.clone());
                Ok(true)
            }
        }
    }

    /// The final save at the end of the run: the snapshot of the last
    /// completed scan (or the start image when none completed), after the
    /// writer thread is done. Nothing without a RETAIN file. The counts of
    /// periodic saves are complete afterwards.
    pub fn finish(&mut self) -> Result<(), String> {
        self.stop_writer();
        self.saved = None;
        self.save().map(|_| ())
    }
}

impl Drop for Keeper<'_> {
    fn drop(&mut self) {
        self.stop_writer();
    }
}

impl ScanObserver for Keeper<'_> {
    fn after_scan(&mut self, plc_time_ns: i64, image: &[u8]) -> Result<(), String> {
        if self.path.is_some() {
            self.take_snapshot(image);
            if let Some(every) = self.every_ns {
                let last = *self.last_save_ns.get_or_insert(plc_time_ns);
                if plc_time_ns.saturating_sub(last) >= every {
                    self.last_save_ns = Some(plc_time_ns);
                    match self.save() {
                        Ok(written) => self.saves += u64::from(written),
                        Err(e) => {
                            self.failures += 1;
                            self.last_error = Some(e);
                        }
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
