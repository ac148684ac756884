//! The differential oracle: two engines, two images from the same cold start, the same stimulus,
//! and after **every** scan the statuses and the whole images compared byte for byte (PLC areas,
//! timer/counter/edge state, SM bits, accumulators, the scan bookkeeping, the physical I/O copies).
//!
//! The oracle knows nothing about which engine is which: it drives two [`Engine`]s, so a fault
//! injector ([`crate::inject`]) or any future engine slots in unchanged. A panic inside an engine
//! is caught and reported as a finding too: no input may crash anything.

use crate::generate::{ScanInput, Stimulus};
use crate::locate::Place;
use std::fmt;
use std::panic::{AssertUnwindSafe, catch_unwind};
use stljit_core::ir::{Address, Loc, Program};
use stljit_core::{Area, ScanStatus, Width};
use stljit_runtime::{Engine, Image, mem};

/// Loop budget the oracle gives each scan: small, so that programs left to the watchdog end
/// quickly, and the same on both sides.
pub const FUZZ_LOOP_LIMIT: u32 = 1000;

/// Options of one differential run.
#[derive(Clone, Copy, Debug)]
pub struct RunOptions {
    /// The loop budget written into both images at cold start.
    pub loop_limit: u32,
    /// How many differing bytes a divergence lists.
    pub max_diffs: usize,
}

impl Default for RunOptions {
    fn default() -> RunOptions {
        RunOptions {
            loop_limit: FUZZ_LOOP_LIMIT,
            max_diffs: 8,
        }
    }
}

/// One differing image byte.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ByteDiff {
    /// Offset in the image.
    pub offset: u32,
    /// What the byte belongs to.
    pub place: Place,
    /// The byte in each engine's image (first engine, second engine).
    pub bytes: [u8; 2],
    /// For scan bookkeeping fields, the whole field in each image (native-endian).
    pub field: Option<[u64; 2]>,
}

impl fmt::Display for ByteDiff {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "offset {:#06x} {}: {:#04x} vs {:#04x}",
            self.offset, self.place, self.bytes[0], self.bytes[1]
        )?;
        if let Some([a, b]) = self.field {
            write!(f, " (field {a} vs {b})")?;
        }
        Ok(())
    }
}

/// The engines disagreed after a scan.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Divergence {
    /// The scan (0-based) after which they differed.
    pub scan: u32,
    /// Engine names (first, second).
    pub engines: [&'static str; 2],
    /// Each engine's status for that scan.
    pub status: [ScanStatus; 2],
    /// The first differing bytes, in image order.
    pub diffs: Vec<ByteDiff>,
    /// How many bytes differ in total.
    pub total: usize,
}

impl fmt::Display for Divergence {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [a, b] = self.engines;
        writeln!(f, "divergence after scan {} ({a} vs {b})", self.scan)?;
        if self.status[0] != self.status[1] {
            writeln!(f, "  status: {:?} vs {:?}", self.status[0], self.status[1])?;
        }
        writeln!(f, "  {} byte(s) differ; first:", self.total)?;
        for d in &self.diffs {
            writeln!(f, "  {d}")?;
        }
        Ok(())
    }
}

/// Something the oracle found.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Finding {
    /// Status or image differ after a scan.
    Divergence(Divergence),
    /// An engine panicked during a scan.
    Panic {
        /// The engine.
        engine: &'static str,
        /// The scan.
        scan: u32,
        /// The panic message.
        message: String,
    },
    /// An engine could not be built for a valid program.
    Build {
        /// The engine.
        engine: &'static str,
        /// Its error.
        message: String,
    },
}

impl Finding {
    /// The scan the finding occurred in (`None` for build failures).
    pub fn scan(&self) -> Option<u32> {
        match self {
            Finding::Divergence(d) => Some(d.scan),
            Finding::Panic { scan, .. } => Some(*scan),
            Finding::Build { .. } => None,
        }
    }

    /// Whether `other` is the same kind of failure (used by the shrinker, so that shrinking does
    /// not wander from one bug to another).
    pub fn same_kind(&self, other: &Finding) -> bool {
        match (self, other) {
            (Finding::Divergence(_), Finding::Divergence(_)) => true,
            (Finding::Panic { engine: a, .. }, Finding::Panic { engine: b, .. })
            | (Finding::Build { engine: a, .. }, Finding::Build { engine: b, .. }) => a == b,
            _ => false,
        }
    }
}

impl fmt::Display for Finding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Finding::Divergence(d) => d.fmt(f),
            Finding::Panic {
                engine,
                scan,
                message,
            } => writeln!(f, "{engine} panicked in scan {scan}: {message}"),
            Finding::Build { engine, message } => {
                writeln!(f, "{engine} could not be built: {message}")
            }
        }
    }
}

/// What a clean run did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RunStats {
    /// Scans executed (per engine).
    pub scans: u64,
    /// Whether the run ended in STOP (a STOP instruction or a fatal error).
    pub stopped: bool,
    /// Whether a fatal error occurred (the watchdog, a NaN or bad pointer in a compare).
    pub fatal: bool,
    /// The fatal error code at the end of the run (0 = none).
    pub fatal_code: u16,
}

/// The cold-start image the oracle gives both engines.
pub fn start_image(program: &Program, opts: &RunOptions) -> Image {
    let mut img = Image::cold_start(program);
    img.set_loop_limit(opts.loop_limit);
    img
}

/// Writes one scan's stimulus into an image: physical inputs, AI words, HMI writes, high-speed
/// counter activity, received bytes. Writes that do not fit the image are skipped (a reproducer
/// edited by hand must not crash the oracle; `Image::queue_rx` ignores a port the image has
/// not).
pub fn apply_stimulus(img: &mut Image, s: &ScanInput) {
    img.set_inputs(&s.inputs);
    for (n, &steps) in s.hsc.iter().enumerate() {
        if let Ok(n) = u8::try_from(n) {
            img.set_hsc_rate(n, steps);
        }
    }
    for (port, bytes) in &s.rx {
        img.queue_rx(*port, bytes);
    }
    for (i, &w) in s.ai.iter().enumerate() {
        let loc = Loc {
            area: Area::AI,
            offset: 2 * i as u32,
        };
        let _ = img.write(loc, Width::Word, 0, u32::from(w));
    }
    for w in &s.writes {
        let _ = match w.addr {
            Address::Bit(bit) => img.set_bit(bit, 0, w.value & 1 != 0),
            Address::Value { loc, width } => img.write(loc, width, 0, w.value),
        };
    }
}

fn panic_message(p: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = p.downcast_ref::<&str>() {
        (*s).to_owned()
    } else if let Some(s) = p.downcast_ref::<String>() {
        s.clone()
    } else {
        "(non-string panic)".to_owned()
    }
}

fn scan_caught(e: &mut dyn Engine, img: &mut Image, t: u64, k: u32) -> Result<ScanStatus, Finding> {
    catch_unwind(AssertUnwindSafe(|| e.scan(img, t))).map_err(|p| Finding::Panic {
        engine: e.name(),
        scan: k,
        message: panic_message(p.as_ref()),
    })
}

/// Compares two images; `None` when equal.
pub fn compare_images(a: &Image, b: &Image, max: usize) -> Option<(Vec<ByteDiff>, usize)> {
    let (x, y) = (a.bytes(), b.bytes());
    if x == y {
        return None;
    }
    let layout = a.layout();
    let mut diffs = Vec::new();
    let mut total = 0;
    for (i, (&p, &q)) in x.iter().zip(y).enumerate() {
        if p == q {
            continue;
        }
        total += 1;
        if diffs.len() < max {
            let offset = i as u32;
            let place = Place::of(layout, offset);
            let field = place.sched_field().map(|(at, size)| {
                let at = layout.sched(at);
                let read = |img: &[u8]| match size {
                    1 => u64::from(mem::get_u8(img, at)),
                    2 => u64::from(mem::get_u16_ne(img, at)),
                    4 => u64::from(mem::get_u32_ne(img, at)),
                    _ => mem::get_u64_ne(img, at),
                };
                [read(x), read(y)]
            });
            diffs.push(ByteDiff {
                offset,
                place,
                bytes: [p, q],
                field,
            });
        }
    }
    if x.len() != y.len() {
        total += x.len().abs_diff(y.len());
    }
    Some((diffs, total))
}

/// Runs `program` on both engines with `stimulus` and compares after every scan. The engines must
/// be fresh (built for this program, never run).
pub fn run_pair(
    program: &Program,
    stimulus: &Stimulus,
    a: &mut dyn Engine,
    b: &mut dyn Engine,
    opts: &RunOptions,
) -> Result<RunStats, Finding> {
    let mut ia = start_image(program, opts);
    let mut ib = ia.clone();
    let mut stats = RunStats::default();
    for (k, s) in stimulus.scans.iter().enumerate() {
        let k = k as u32;
        apply_stimulus(&mut ia, s);
        apply_stimulus(&mut ib, s);
        let sa = scan_caught(a, &mut ia, s.t_ms, k)?;
        let sb = scan_caught(b, &mut ib, s.t_ms, k)?;
        stats.scans += 1;
        let diff = compare_images(&ia, &ib, opts.max_diffs);
        if sa != sb || diff.is_some() {
            let (diffs, total) = diff.unwrap_or_default();
            return Err(Finding::Divergence(Divergence {
                scan: k,
                engines: [a.name(), b.name()],
                status: [sa, sb],
                diffs,
                total,
            }));
        }
        stats.fatal |= sa == ScanStatus::Fatal;
        stats.stopped |= sa != ScanStatus::Ok;
    }
    stats.fatal_code = ia.fatal();
    Ok(stats)
}
