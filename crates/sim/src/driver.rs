//! [`Simulation`]: runs an [`Engine`] scan by scan at virtual time, feeding a [`Stimulus`] and
//! reporting every scan to an [`Observer`].
//!
//! Scan `k` starts at virtual time `k · scan_ms`. Before it, the stimulus rows due at `k` are
//! written into the image (addresses, high-speed counter steps, received bytes:
//! [`crate::stimulus`]); after it, the observer sees the image. The run ends after the
//! requested scans, or early when a scan reports STOP or a fatal error, or when the caller's
//! cancel flag is set (checked between scans only, so the image is always a whole-scan state).

use crate::stimulus::{Cell, Row, Stimulus, Target};
use crate::value::write_address;
use std::borrow::BorrowMut;
use std::fmt;
use std::io;
use std::ops::Range;
use std::sync::atomic::{AtomicBool, Ordering};
use stljit_core::layout::Layout;
use stljit_core::{FatalCode, ScanStatus, comm};
use stljit_runtime::engine::{ChangeWatch, Engine};
use stljit_runtime::image::Image;

/// The most scans one engine call runs when no observer needs every scan: a few milliseconds of
/// wall time, so that a cancel flag and a progress bar stay responsive.
const MAX_STRETCH: u64 = 1 << 16;

/// How long to run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Until {
    /// This many scans.
    Scans(u64),
    /// Every scan that starts within this many ms of the run's first scan (so
    /// `ceil(ms / scan_ms)` scans).
    Duration(u64),
}

/// What an observer sees after each scan.
#[derive(Clone, Copy, Debug)]
pub struct ScanEvent<'a> {
    /// Scan number (0 is the first after cold start).
    pub scan: u64,
    /// Virtual time at the scan's start.
    pub t_ms: u64,
    /// The image after the scan.
    pub image: &'a Image,
    /// What the engine reported.
    pub status: ScanStatus,
}

/// Receives the scans of a run (trace writers, test recorders).
pub trait Observer {
    /// Called after each scan (or, when [`Observer::needs_every_scan`] is false, after each
    /// stretch of scans the engine ran at once, with the stretch's last scan); an error ends the
    /// run with [`SimError::Observer`].
    fn observe(&mut self, event: &ScanEvent<'_>) -> io::Result<()>;

    /// Whether the observer must see the image after every scan. When no observer of a run
    /// does, the simulation runs the scans between two stimulus rows in one engine call (the
    /// JIT's native loop) and reports only each stretch's end.
    fn needs_every_scan(&self) -> bool {
        true
    }

    /// For an observer that needs every scan only to see the image bytes some of them change
    /// (a VCD trace writes nothing for a scan that changed no watched value): those bytes. The
    /// driver then runs the scans between two stimulus rows in stretches that end at the first
    /// scan changing one of them ([`Engine::run_scans_watching`]; the JIT's native loop
    /// compares after each scan), and shows this observer each stretch's last scan and the
    /// first scan of a run. `None` (the default): every scan, as [`Observer::needs_every_scan`]
    /// says.
    fn changes_of(&self, _layout: &Layout) -> Option<Vec<Range<usize>>> {
        None
    }
}

/// The bytes `observers` need to see changes of ([`Observer::changes_of`]): each one that needs
/// every scan must name its bytes (`None` otherwise); the rest need none.
pub fn changes_of_all<'o>(
    observers: impl IntoIterator<Item = &'o (dyn Observer + 'o)>,
    layout: &Layout,
) -> Option<Vec<Range<usize>>> {
    let mut all = Vec::new();
    for o in observers {
        if o.needs_every_scan() {
            all.extend(o.changes_of(layout)?);
        }
    }
    Some(all)
}

/// Observes nothing.
impl Observer for () {
    fn observe(&mut self, _: &ScanEvent<'_>) -> io::Result<()> {
        Ok(())
    }

    fn needs_every_scan(&self) -> bool {
        false
    }
}

/// Both observers see every scan, the first one first (e.g. a CSV and a VCD trace at once).
impl<A: Observer, B: Observer> Observer for (A, B) {
    fn observe(&mut self, event: &ScanEvent<'_>) -> io::Result<()> {
        self.0.observe(event)?;
        self.1.observe(event)
    }

    fn needs_every_scan(&self) -> bool {
        self.0.needs_every_scan() || self.1.needs_every_scan()
    }

    fn changes_of(&self, layout: &Layout) -> Option<Vec<Range<usize>>> {
        changes_of_all([&self.0 as &dyn Observer, &self.1], layout)
    }
}

impl<O: Observer + ?Sized> Observer for &mut O {
    fn observe(&mut self, event: &ScanEvent<'_>) -> io::Result<()> {
        (**self).observe(event)
    }

    fn needs_every_scan(&self) -> bool {
        (**self).needs_every_scan()
    }

    fn changes_of(&self, layout: &Layout) -> Option<Vec<Range<usize>>> {
        (**self).changes_of(layout)
    }
}

/// A closure as an observer.
pub struct FnObserver<F>(pub F);

impl<F: FnMut(&ScanEvent<'_>) -> io::Result<()>> Observer for FnObserver<F> {
    fn observe(&mut self, event: &ScanEvent<'_>) -> io::Result<()> {
        (self.0)(event)
    }
}

/// Where a run stands, for a progress bar.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Progress {
    /// Scans run so far in this run.
    pub done: u64,
    /// Scans this run will take if nothing stops it.
    pub total: u64,
    /// Virtual time of the last scan.
    pub t_ms: u64,
}

/// How a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    /// All requested scans ran.
    Completed,
    /// A STOP instruction executed in the last scan (or the image was already in STOP).
    Stopped,
    /// A fatal error aborted the last scan.
    Fatal {
        /// The raw code from the image (`Sched::FATAL`).
        code: u16,
    },
    /// The cancel flag was set.
    Cancelled,
}

impl Outcome {
    /// The fatal code, when it is a known one.
    pub fn fatal_code(self) -> Option<FatalCode> {
        match self {
            Outcome::Fatal { code } => FatalCode::try_from(code).ok(),
            _ => None,
        }
    }
}

impl fmt::Display for Outcome {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Outcome::Completed => f.write_str("completed"),
            Outcome::Stopped => f.write_str("stopped (STOP instruction)"),
            Outcome::Fatal { code } => match FatalCode::try_from(*code) {
                Ok(c) => write!(f, "{c}"),
                Err(raw) => write!(f, "fatal 16#{raw:04X}"),
            },
            Outcome::Cancelled => f.write_str("cancelled"),
        }
    }
}

/// Summary of one [`Simulation::run`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RunReport {
    /// Scans executed by this run.
    pub scans: u64,
    /// Number of the next scan the simulation would run.
    pub next_scan: u64,
    /// Virtual time of the last executed scan (of the run's start when none ran).
    pub t_ms: u64,
    /// Why the run ended.
    pub outcome: Outcome,
}

/// Why a simulation could not be set up or run.
#[derive(Debug)]
pub enum SimError {
    /// `scan_ms` was 0: time must advance between scans.
    ZeroScanTime,
    /// The stimulus was built for another profile's image (an address does not fit it).
    StimulusAddress {
        /// The column's name.
        column: String,
        /// The row's source line.
        line: u32,
    },
    /// The stimulus was built for another profile (an `HSCn` or `PORTn` column the image's
    /// CPU lacks).
    StimulusColumn {
        /// The column's name.
        column: String,
        /// The row's source line.
        line: u32,
        /// What does not fit.
        reason: &'static str,
    },
    /// An observer failed (a trace writer's I/O error).
    Observer(io::Error),
}

impl fmt::Display for SimError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SimError::ZeroScanTime => f.write_str("scan time must be at least 1 ms"),
            SimError::StimulusAddress { column, line } => {
                write!(
                    f,
                    "stimulus line {line}: `{column}` is outside the memory image"
                )
            }
            SimError::StimulusColumn {
                column,
                line,
                reason,
            } => write!(f, "stimulus line {line}: `{column}`: {reason}"),
            SimError::Observer(e) => write!(f, "trace output failed: {e}"),
        }
    }
}

impl std::error::Error for SimError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            SimError::Observer(e) => Some(e),
            _ => None,
        }
    }
}

/// A PLC under simulation: an engine, its image and the virtual clock.
///
/// The image is owned (`Simulation<'a>`, the default) or borrowed (`Simulation<'a, &mut Image>`,
/// for a caller such as `stljit-api`'s `Plc` that keeps the image between runs).
pub struct Simulation<'a, I: BorrowMut<Image> = Image> {
    engine: &'a mut dyn Engine,
    image: I,
    scan_ms: u64,
    next_scan: u64,
    cancel: Option<&'a AtomicBool>,
    progress: Option<&'a mut dyn FnMut(Progress)>,
}

impl<'a, I: BorrowMut<Image>> Simulation<'a, I> {
    /// A simulation continuing from `image` (normally `Image::cold_start`, or `&mut` an image the
    /// caller keeps): the next scan is the image's scan number.
    pub fn new(
        engine: &'a mut dyn Engine,
        image: I,
        scan_ms: u64,
    ) -> Result<Simulation<'a, I>, SimError> {
        if scan_ms == 0 {
            return Err(SimError::ZeroScanTime);
        }
        let next_scan = image.borrow().scan_no();
        Ok(Simulation {
            engine,
            image,
            scan_ms,
            next_scan,
            cancel: None,
            progress: None,
        })
    }

    /// Stops the run before the next scan once `flag` is set (e.g. by a Ctrl-C handler).
    pub fn with_cancel(mut self, flag: &'a AtomicBool) -> Self {
        self.cancel = Some(flag);
        self
    }

    /// Calls `f` after every scan, or every stretch of scans run at once.
    pub fn with_progress(mut self, f: &'a mut dyn FnMut(Progress)) -> Self {
        self.progress = Some(f);
        self
    }

    /// The image as it stands.
    pub fn image(&self) -> &Image {
        self.image.borrow()
    }

    /// Gives the image back (the borrow, for a borrowed one).
    pub fn into_image(self) -> I {
        self.image
    }

    /// The engine's name.
    pub fn engine_name(&self) -> &'static str {
        self.engine.name()
    }

    /// Virtual time at the start of scan `k`.
    pub fn time_of(&self, k: u64) -> u64 {
        k.saturating_mul(self.scan_ms)
    }

    /// Runs scans until `until`, a STOP, a fatal error or cancellation. Stimulus rows due before
    /// this run's first scan are applied before it (so a continued simulation sees the
    /// stimulus's state at the current time; their received bytes are not delivered, their
    /// interval is past), rows due later before their scan.
    pub fn run(
        &mut self,
        until: Until,
        stimulus: &Stimulus,
        observer: &mut dyn Observer,
    ) -> Result<RunReport, SimError> {
        let first = self.next_scan;
        let total = match until {
            Until::Scans(n) => n,
            Until::Duration(ms) => ms.div_ceil(self.scan_ms),
        };
        let mut report = RunReport {
            scans: 0,
            next_scan: first,
            t_ms: self.time_of(first),
            outcome: Outcome::Completed,
        };
        if self.image.borrow().is_stopped() {
            report.outcome = Outcome::Stopped;
            return Ok(report);
        }
        let rows = stimulus.rows();
        let mut next_row = 0;
        let every_scan = observer.needs_every_scan();
        // An observer that needs only the scans changing some bytes sees stretches ending at
        // such a scan; the first scan of the run it sees on its own.
        let mut watch = if every_scan {
            let image = self.image.borrow();
            observer
                .changes_of(image.layout())
                .map(|ranges| ChangeWatch::new(image, ranges))
        } else {
            None
        };
        let mut done = 0;
        while done < total {
            if self.cancel.is_some_and(|c| c.load(Ordering::Relaxed)) {
                report.outcome = Outcome::Cancelled;
                break;
            }
            let k = first + done;
            while let Some(row) = rows.get(next_row)
                && stimulus.due_scan(row, self.scan_ms) <= k
            {
                let past = stimulus.due_scan(row, self.scan_ms) < first;
                apply_row(self.image.borrow_mut(), stimulus, row, past)?;
                next_row += 1;
            }
            // One scan, or every scan up to the next stimulus row in one engine call (bounded,
            // so that cancellation and progress stay responsive).
            let stretch = if every_scan && (watch.is_none() || done == 0) {
                1
            } else {
                let next_due = rows
                    .get(next_row)
                    .map_or(u64::MAX, |row| stimulus.due_scan(row, self.scan_ms));
                (total - done)
                    .min(next_due.saturating_sub(k).max(1))
                    .min(MAX_STRETCH)
            };
            let t0 = self.time_of(k);
            let image = self.image.borrow_mut();
            let (ran, status) = match watch.as_mut() {
                _ if stretch == 1 => (1, self.engine.scan(image, t0)),
                Some(w) => self
                    .engine
                    .run_scans_watching(image, t0, self.scan_ms, stretch, w),
                None => self.engine.run_scans(image, t0, self.scan_ms, stretch),
            };
            if ran == 0 {
                report.outcome = Outcome::Fatal {
                    code: self.image.borrow().fatal(),
                };
                break;
            }
            let last = k + ran - 1;
            let t_ms = self.time_of(last);
            done += ran;
            self.next_scan = last + 1;
            report.scans = done;
            report.next_scan = last + 1;
            report.t_ms = t_ms;
            let event = ScanEvent {
                scan: last,
                t_ms,
                image: self.image.borrow(),
                status,
            };
            observer.observe(&event).map_err(SimError::Observer)?;
            if let Some(w) = watch.as_mut() {
                // The bytes as the observer saw them: a change after this (a stimulus row's
                // write included) ends the next stretch at its first scan.
                w.changed(self.image.borrow().bytes());
            }
            if let Some(p) = self.progress.as_mut() {
                p(Progress { done, total, t_ms });
            }
            match status {
                ScanStatus::Ok => {}
                ScanStatus::Stopped => {
                    report.outcome = Outcome::Stopped;
                    break;
                }
                ScanStatus::Fatal => {
                    report.outcome = Outcome::Fatal {
                        code: self.image.borrow().fatal(),
                    };
                    break;
                }
            }
        }
        Ok(report)
    }
}

/// Writes a stimulus row into the image before its scan: address values (inputs into the
/// physical input copy, the rest like an HMI write), high-speed counter steps (the counter's
/// activity per interval, which the image holds until set again, so every scan of a stretch
/// the engine runs at once counts them) and received bytes (queued once, for the interval
/// before the scan; not for a row already `past` when the run started, whose bytes belonged to
/// an interval gone by).
fn apply_row(
    image: &mut Image,
    stimulus: &Stimulus,
    row: &Row,
    past: bool,
) -> Result<(), SimError> {
    for (cell, column) in row.cells.iter().zip(stimulus.columns()) {
        let Some(cell) = cell else { continue };
        let misfit = |reason| SimError::StimulusColumn {
            column: column.name.clone(),
            line: row.line,
            reason,
        };
        let profile = image.layout().profile.profile();
        match (cell, column.target) {
            (&Cell::Value(v), Target::Address(address)) => {
                if !write_address(image, &address, v) {
                    return Err(SimError::StimulusAddress {
                        column: column.name.clone(),
                        line: row.line,
                    });
                }
            }
            (&Cell::Steps(steps), Target::HscSteps(n)) => {
                if profile.hsc.get(n).is_none() {
                    return Err(misfit("the CPU has no such high-speed counter"));
                }
                image.set_hsc_rate(n, steps);
            }
            (Cell::Bytes(bytes), Target::Receive(port)) => {
                if comm::port(profile, port).is_none() {
                    return Err(misfit("the CPU has no such serial port"));
                }
                if !past {
                    image.queue_rx(port, bytes);
                }
            }
            _ => return Err(misfit("the cell does not fit its column")),
        }
    }
    Ok(())
}

#[cfg(test)]
#[path = "driver_tests.rs"]
mod tests;
