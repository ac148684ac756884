//! [`Plc`]: one compiled program on one engine with its memory image, virtual clock and forces
//! — the component other simulation tools drive.
//!
//! Time is virtual: scan `k` starts at `k × scan_ms` and [`Plc::time_ms`] is the start of the
//! next scan (so after `run_for(120_000)` at 10 ms it is 120 000). Every run goes through
//! `stljit_sim`'s [`Simulation`] with the forces applied around each scan ([`crate::force`]),
//! so the CLI's `run`, the Python package and the FMU all step the PLC the same way.

use crate::Error;
use crate::force::{Forced, Forces};
use crate::handle::{Handle, Value};
use crate::project::{Compiled, Project};
use crate::snapshot::{Snapshot, fnv1a};
use std::sync::Arc;
use std::sync::atomic::AtomicBool;
use stljit_core::ir::Program;
use stljit_interp::Interpreter;
use stljit_jit::{JitOptions, JitProgram, OptLevel};
use stljit_runtime::rtc::DateTime;
use stljit_runtime::{Engine, Image};
use stljit_sim::{Observer, Progress, RunReport, ScanEvent, Simulation, Stimulus, TimeBase, Until};

/// Which engine runs the program.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum EngineKind {
    /// Native code from Cranelift (the default).
    #[default]
    Jit,
    /// The reference interpreter.
    Interp,
}

impl EngineKind {
    /// `jit` or `interp`.
    pub fn name(self) -> &'static str {
        match self {
            EngineKind::Jit => "jit",
            EngineKind::Interp => "interp",
        }
    }

    /// The engine called `name` (`jit`, `interp`).
    pub fn from_name(name: &str) -> Option<EngineKind> {
        [EngineKind::Jit, EngineKind::Interp]
            .into_iter()
            .find(|e| e.name() == name)
    }
}

/// How to build a [`Plc`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Options {
    /// The engine.
    pub engine: EngineKind,
    /// The JIT's optimisation level (ignored by the interpreter).
    pub opt: OptLevel,
    /// Virtual time per scan, at least 1 ms.
    pub scan_ms: u64,
    /// The date and time the real-time clock shows at cold start (s7-200-more §6.2); `None`
    /// is 2000-01-01 00:00:00. Ignored by profiles without a clock.
    pub clock_start: Option<DateTime>,
}

impl Default for Options {
    /// The JIT at `speed`, 10 ms per scan (the CLI's defaults).
    fn default() -> Options {
        Options {
            engine: EngineKind::Jit,
            opt: OptLevel::Speed,
            scan_ms: 10,
            clock_start: None,
        }
    }
}

/// Builds the engine `kind` for `program`.
pub fn build_engine(
    kind: EngineKind,
    opt: OptLevel,
    program: &Program,
) -> Result<Box<dyn Engine + Send>, Error> {
    let engine_error = |message: String| Error::Engine { message };
    Ok(match kind {
        EngineKind::Interp => {
            Box::new(Interpreter::new(program).map_err(|e| engine_error(e.to_string()))?)
        }
        EngineKind::Jit => Box::new(
            JitProgram::compile(program, &JitOptions::at(opt))
                .map_err(|e| engine_error(e.to_string()))?,
        ),
    })
}

/// A cold-started image of `program` whose clock shows `clock_start` (if given).
fn cold_image(program: &Program, clock_start: Option<DateTime>) -> Image {
    let mut image = Image::cold_start(program);
    if let Some(start) = clock_start {
        image.set_clock_start(start);
    }
    image
}

/// One run of [`Plc::simulate`]: how long, and optionally a stimulus, an observer, a cancel
/// flag and a progress callback.
pub struct Run<'a> {
    until: Until,
    stimulus: Option<&'a Stimulus>,
    observer: Option<&'a mut dyn Observer>,
    cancel: Option<&'a AtomicBool>,
    progress: Option<&'a mut dyn FnMut(Progress)>,
}

impl<'a> Run<'a> {
    /// A run of `until` (scans or a span of virtual time).
    pub fn new(until: Until) -> Run<'a> {
        Run {
            until,
            stimulus: None,
            observer: None,
            cancel: None,
            progress: None,
        }
    }

    /// Applies `stimulus` (rows due before the first scan of the run are applied before it).
    pub fn stimulus(mut self, stimulus: &'a Stimulus) -> Run<'a> {
        self.stimulus = Some(stimulus);
        self
    }

    /// Shows every scan to `observer` (after the PLC's own hook, [`Plc::set_observer`]).
    pub fn observer(mut self, observer: &'a mut dyn Observer) -> Run<'a> {
        self.observer = Some(observer);
        self
    }

    /// Stops before the next scan once `flag` is set.
    pub fn cancel(mut self, flag: &'a AtomicBool) -> Run<'a> {
        self.cancel = Some(flag);
        self
    }

    /// Calls `f` after every scan.
    pub fn progress(mut self, f: &'a mut dyn FnMut(Progress)) -> Run<'a> {
        self.progress = Some(f);
        self
    }
}

/// The hook and the run's observer, in that order.
struct Both<'h, 'r> {
    hook: Option<&'h mut (dyn Observer + Send)>,
    run: Option<&'r mut (dyn Observer + 'r)>,
}

impl Observer for Both<'_, '_> {
    fn observe(&mut self, event: &ScanEvent<'_>) -> std::io::Result<()> {
        if let Some(h) = self.hook.as_mut() {
            h.observe(event)?;
        }
        if let Some(o) = self.run.as_mut() {
            o.observe(event)?;
        }
        Ok(())
    }

    fn needs_every_scan(&self) -> bool {
        self.hook.as_ref().is_some_and(|h| h.needs_every_scan())
            || self.run.as_ref().is_some_and(|o| o.needs_every_scan())
    }

    fn changes_of(
        &self,
        layout: &stljit_core::layout::Layout,
    ) -> Option<Vec<std::ops::Range<usize>>> {
        let hook = self.hook.as_deref().map(|h| h as &dyn Observer);
        let run = self.run.as_deref().map(|o| o as &dyn Observer);
        stljit_sim::driver::changes_of_all(hook.into_iter().chain(run), layout)
    }
}

/// A compiled PLC program on an engine, with its image, virtual clock and forces.
pub struct Plc {
    compiled: Arc<Compiled>,
    program: Program,
    engine: Box<dyn Engine + Send>,
    kind: EngineKind,
    image: Image,
    scan_ms: u64,
    clock_start: Option<DateTime>,
    forces: Forces,
    fingerprint: u64,
    hook: Option<Box<dyn Observer + Send>>,
    stimulus: Stimulus,
}

impl std::fmt::Debug for Plc {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Plc")
            .field("engine", &self.kind)
            .field("scan_ms", &self.scan_ms)
            .field("scan_no", &self.scan_no())
            .finish_non_exhaustive()
    }
}

impl Plc {
    /// Compiles `project` and builds a PLC on `options.engine`, cold-started (spec §1.7).
    pub fn compile(project: &Project, options: &Options) -> Result<Plc, Error> {
        Plc::new(Arc::new(project.compile()?), options)
    }

    /// A PLC for an already compiled project (shared, e.g. by the workers of a batch).
    pub fn new(compiled: Arc<Compiled>, options: &Options) -> Result<Plc, Error> {
        if options.scan_ms == 0 {
            return Err(Error::ZeroScanTime);
        }
        let program = compiled.program()?;
        let engine = build_engine(options.engine, options.opt, program)?;
        let fingerprint = fnv1a(stljit_core::text::print(program).as_bytes());
        let image = cold_image(program, options.clock_start);
        let stimulus = Stimulus::empty(TimeBase::Scan, program.profile.profile());
        let program = program.clone();
        Ok(Plc {
            compiled,
            program,
            engine,
            kind: options.engine,
            image,
            scan_ms: options.scan_ms,
            clock_start: options.clock_start,
            forces: Forces::default(),
            fingerprint,
            hook: None,
            stimulus,
        })
    }

    // ---- what it is ----------------------------------------------------------------------

    /// The compiled project (program, dialect, symbols, diagnostics).
    pub fn compiled(&self) -> &Compiled {
        &self.compiled
    }

    /// The program.
    pub fn program(&self) -> &Program {
        &self.program
    }

    /// The engine.
    pub fn engine(&self) -> EngineKind {
        self.kind
    }

    /// Virtual time per scan.
    pub fn scan_ms(&self) -> u64 {
        self.scan_ms
    }

    /// The memory image as it stands (between scans).
    pub fn image(&self) -> &Image {
        &self.image
    }

    /// Identifies the program (FNV-1a of its IR text): equal for equal programs.
    pub fn fingerprint(&self) -> u64 {
        self.fingerprint
    }

    // ---- time ----------------------------------------------------------------------------

    /// Number of the next scan (scans run since the cold start).
    pub fn scan_no(&self) -> u64 {
        self.image.scan_no()
    }

    /// Virtual time now: the start of the next scan.
    pub fn time_ms(&self) -> u64 {
        self.scan_no().saturating_mul(self.scan_ms)
    }

    /// Whether the PLC is in STOP (after a STOP instruction or a fatal error).
    pub fn is_stopped(&self) -> bool {
        self.image.is_stopped()
    }

    // ---- addresses -----------------------------------------------------------------------

    /// Resolves a name once for fast reads and writes ([`crate::handle`] for the syntax).
    pub fn handle(&self, name: &str) -> Result<Handle, Error> {
        self.compiled.handle(name)
    }

    /// The value at `handle`.
    pub fn get(&self, handle: &Handle) -> Result<Value, Error> {
        Ok(handle.decode(self.get_raw(handle)?))
    }

    /// The value written at `handle` from outside: for an input the physical input copy (what
    /// the next scan's input refresh will read), for anything else the image, as [`Plc::get`].
    pub fn get_written(&self, handle: &Handle) -> Result<Value, Error> {
        handle.check_image(&self.image)?;
        Ok(handle.decode(handle.load(self.image.bytes(), handle.write_offset())))
    }

    /// The raw bits at `handle` (zero-extended).
    pub fn get_raw(&self, handle: &Handle) -> Result<u32, Error> {
        handle.check_image(&self.image)?;
        Ok(handle.load(self.image.bytes(), handle.read_offset()))
    }

    /// Writes `value` at `handle`: an input for the next scan's input refresh, anything else
    /// into the image now. A forced address keeps its forced value.
    pub fn set(&mut self, handle: &Handle, value: impl Into<Value>) -> Result<(), Error> {
        let raw = handle.encode(value.into())?;
        self.set_raw(handle, raw)
    }

    /// Writes raw bits at `handle` (as [`Plc::set`], without the range check).
    pub fn set_raw(&mut self, handle: &Handle, raw: u32) -> Result<(), Error> {
        handle.check_image(&self.image)?;
        handle.check_writable()?;
        handle.store(self.image.bytes_mut(), handle.write_offset(), raw);
        if !handle.is_input()
            && let Some(f) = self
                .forces
                .iter()
                .find(|f| f.handle.address() == handle.address())
        {
            let forced = f.raw;
            handle.store(self.image.bytes_mut(), handle.read_offset(), forced);
        }
        Ok(())
    }

    /// The value of a name (resolved on every call; keep a [`Handle`] in a loop).
    pub fn read(&self, name: &str) -> Result<Value, Error> {
        self.get(&self.handle(name)?)
    }

    /// Writes a name (resolved on every call; keep a [`Handle`] in a loop).
    pub fn write(&mut self, name: &str, value: impl Into<Value>) -> Result<(), Error> {
        let h = self.handle(name)?;
        self.set(&h, value)
    }

    // ---- simulated hardware --------------------------------------------------------------

    /// Sets high-speed counter `counter`'s counting activity: `steps` signed unit steps in
    /// every scan interval from the next scan on, held until set again (s7-200-more §8.4: the
    /// steps of an interval are spread evenly over it; modes 0–2 count in the counter's
    /// direction and ignore the sign, modes 3–11 count up for `steps > 0` and down for
    /// `steps < 0`). A stimulus's `HSCn` column does the same. The counter counts them only
    /// once the program has defined and enabled it (HDEF, HSC).
    pub fn set_hsc_steps(&mut self, counter: u8, steps: i32) -> Result<(), Error> {
        let profile = self.program.profile.profile();
        if profile.hsc.get(counter).is_none() {
            return Err(Error::NoCounter {
                counter,
                cpu: profile.model,
                have: stljit_sim::stimulus::hsc_columns(profile),
            });
        }
        self.image.set_hsc_rate(counter, steps);
        Ok(())
    }

    /// Queues `bytes` to be received on serial port `port` in the interval before the next
    /// scan, back to back from its start, one character time each (s7-200-more §10.4; what
    /// does not complete by the next scan stays pending into the following interval). The port
    /// holds at most 256 pending bytes; more are dropped. The program sees them in Freeport
    /// mode (SMB30/SMB130), through RCV or the receive-character event. A stimulus's `PORTn`
    /// column does the same.
    pub fn queue_rx(&mut self, port: u8, bytes: &[u8]) -> Result<(), Error> {
        let profile = self.program.profile.profile();
        if stljit_core::comm::port(profile, port).is_none() {
            return Err(Error::NoPort {
                port,
                cpu: profile.model,
                have: stljit_sim::stimulus::port_columns(profile),
            });
        }
        self.image.queue_rx(port, bytes);
        Ok(())
    }

    // ---- forcing -------------------------------------------------------------------------

    /// Holds `handle`'s address at `value` whatever the program or a write does, from now on
    /// (the exact points in the scan: [`crate::force`]). Forcing again replaces the value.
    pub fn force(&mut self, handle: &Handle, value: impl Into<Value>) -> Result<(), Error> {
        handle.check_image(&self.image)?;
        handle.check_writable()?;
        let raw = handle.encode(value.into())?;
        self.forces.set(&mut self.image, handle.clone(), raw);
        Ok(())
    }

    /// Releases a force; `false` when the address was not forced. The address keeps its value
    /// until the program, an input refresh or a write changes it.
    pub fn unforce(&mut self, handle: &Handle) -> bool {
        self.forces.remove(handle)
    }

    /// Releases every force.
    pub fn unforce_all(&mut self) {
        self.forces.clear();
    }

    /// Every forced address (as it was named) with its forced value.
    pub fn forced(&self) -> Vec<(String, Value)> {
        self.forces
            .iter()
            .map(|f| (f.handle.name().to_string(), f.handle.decode(f.raw)))
            .collect()
    }

    // ---- running -------------------------------------------------------------------------

    /// Calls `hook` after every scan of every run from now on (`None` removes it).
    pub fn set_observer(&mut self, hook: Option<Box<dyn Observer + Send>>) {
        self.hook = hook;
    }

    /// Runs one scan.
    pub fn scan(&mut self) -> Result<RunReport, Error> {
        self.run(Until::Scans(1))
    }

    /// Runs `n` scans, or a span of virtual time ([`Until`]), stopping early on STOP or a
    /// fatal error (the report says which).
    pub fn run(&mut self, until: Until) -> Result<RunReport, Error> {
        self.simulate(Run::new(until))
    }

    /// Runs `ms` of virtual time: every scan that starts within it.
    pub fn run_for(&mut self, ms: u64) -> Result<RunReport, Error> {
        self.run(Until::Duration(ms))
    }

    /// Runs every scan that starts before virtual time `t_ms` (none when the PLC is there
    /// already): how a co-simulation step `[t, t + h)` maps onto scans.
    pub fn run_until(&mut self, t_ms: u64) -> Result<RunReport, Error> {
        let end = t_ms.div_ceil(self.scan_ms);
        self.run(Until::Scans(end.saturating_sub(self.scan_no())))
    }

    /// Runs with `observer` seeing every scan (after the hook).
    pub fn run_observed(
        &mut self,
        until: Until,
        observer: &mut dyn Observer,
    ) -> Result<RunReport, Error> {
        self.simulate(Run::new(until).observer(observer))
    }

    /// The general run: stimulus, observer, cancel flag and progress as given.
    pub fn simulate(&mut self, run: Run<'_>) -> Result<RunReport, Error> {
        let stimulus = run.stimulus.unwrap_or(&self.stimulus);
        let progress_wanted = run.progress.is_some();
        let mut engine = Forced {
            engine: &mut *self.engine,
            forces: &mut self.forces,
        };
        let mut progress = run.progress;
        let mut report = |p: Progress| {
            if let Some(f) = progress.as_mut() {
                f(p);
            }
        };
        let mut sim = Simulation::new(&mut engine, &mut self.image, self.scan_ms)?;
        if let Some(flag) = run.cancel {
            sim = sim.with_cancel(flag);
        }
        if progress_wanted {
            sim = sim.with_progress(&mut report);
        }
        let mut observer = Both {
            hook: match self.hook.as_mut() {
                Some(h) => Some(&mut **h as &mut (dyn Observer + Send)),
                None => None,
            },
            run: run.observer,
        };
        Ok(sim.run(run.until, stimulus, &mut observer)?)
    }

    /// Back to the power-up state (spec §1.7): a cold-started image at scan 0, no forces. The
    /// engine, scan time and hook stay.
    pub fn reset(&mut self) {
        self.image = cold_image(&self.program, self.clock_start);
        self.forces.clear();
    }

    // ---- state ---------------------------------------------------------------------------

    /// The whole state: image (timers, counters, edges, time), scan time and forces.
    pub fn snapshot(&self) -> Snapshot {
        Snapshot {
            fingerprint: self.fingerprint,
            scan_ms: self.scan_ms,
            image: self.image.bytes().to_vec(),
            forces: self
                .forces
                .iter()
                .map(|f| (f.handle.name().to_string(), f.raw))
                .collect(),
        }
    }

    /// Continues from `snapshot`, which must come from a PLC of the same program (either
    /// engine). Nothing changes when it is refused.
    pub fn restore(&mut self, snapshot: &Snapshot) -> Result<(), Error> {
        let foreign = || Error::Foreign {
            what: "snapshot".to_string(),
        };
        if snapshot.fingerprint != self.fingerprint
            || snapshot.image.len() != self.image.bytes().len()
            || snapshot.scan_ms == 0
        {
            return Err(foreign());
        }
        let mut image = Image::blank(self.image.layout().profile);
        image.bytes_mut().copy_from_slice(&snapshot.image);
        let mut forces = Forces::default();
        for (name, raw) in &snapshot.forces {
            let h = self.handle(name).map_err(|_| foreign())?;
            forces.set(&mut image, h, *raw);
        }
        self.image = image;
        self.forces = forces;
        self.scan_ms = snapshot.scan_ms;
        Ok(())
    }
}
