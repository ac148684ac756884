//! [`JitProgram`]: finalizes the compiled module, enters the native code, frees it on drop.
//!
//! This is the only module with `unsafe`: turning finalized code addresses into `extern "C"`
//! function pointers, calling them, and releasing the code memory.
#![allow(unsafe_code)]

use crate::build::{self, Built};
use crate::lower::Baked;
use crate::resident::Resident;
use crate::{JitError, JitOptions};
use cranelift_jit::JITModule;
use std::sync::atomic::{AtomicU64, Ordering};
use stljit_core::ScanStatus;
use stljit_core::ir::Program;
use stljit_core::layout::Layout;
use stljit_runtime::ffi::{NativeRoutines, PouFn};
use stljit_runtime::rules::Rules;
use stljit_runtime::scan::ScanPlan;
use stljit_runtime::{ChangeWatch, Engine, Image};

type RunFn = unsafe extern "C" fn(*mut u8, u64, u64, u64, *mut u64, *mut ChangeWatch) -> i32;

/// A program compiled to native code. Implements [`Engine`]; all state lives in the [`Image`].
pub struct JitProgram {
    module: Option<JITModule>,
    run: RunFn,
    /// Boxed so its address, baked into the code for the runtime shims, never moves.
    layout: Box<Layout>,
    /// What the scan prologue touches; boxed for the same reason, and only ever read by the
    /// runtime's `scan::begin` through the address baked into the code.
    _plan: Box<ScanPlan>,
    /// The compiled interrupt routines the scan prologue runs (`None` without interrupt
    /// routines); boxed for the same reason, and only read through the baked address.
    _routines: Option<Box<NativeRoutines>>,
    op_count: usize,
    /// The s7-200-more ops' payloads, whose addresses are baked into the code.
    _ext: crate::lower::ext::ExtKeep,
    /// The executed-op counter of an instrumented build ([`JitProgram::compile_counting`]).
    counter: Option<Box<AtomicU64>>,
    /// The shadow of the resident bytes (`crate::resident`), if any byte is resident.
    shadow: Option<Shadow>,
}

/// Where the shadow of the resident bytes is and what says whether it still holds an image's.
struct Shadow {
    /// How many bytes are resident (at least one, or there is no shadow).
    bytes: usize,
    /// The image scratch it takes (`Image::bytes_and_scratch`).
    scratch: usize,
    /// The offset of its flag (a `u32`, non-zero: the shadow holds the image's resident bytes).
    flag: usize,
    /// This program's key (upper 32 bits of every version it gives an image), unique in the
    /// process ([`next_key`]).
    key: u64,
    /// Runs since the key was taken (lower 32 bits of the versions).
    runs: u64,
    /// The version given to the image the last run packed its resident bytes into (0: none).
    last: u64,
}

impl Shadow {
    /// Before a run on `image`: the image's bytes and scratch, with the flag telling the code
    /// whether the shadow holds its resident bytes, i.e. `image` is the one the last run of
    /// this program left, unchanged since (`Image::version`).
    fn enter<'i>(&self, image: &'i mut Image) -> &'i mut [u8] {
        let held = self.last != 0 && image.version() == self.last;
        let buf = image.bytes_and_scratch(self.scratch);
        buf[self.flag..self.flag + 4].copy_from_slice(&u32::from(held).to_ne_bytes());
        buf
    }

    /// After a run on `image`, which packed the resident bytes into it: tags it with a version
    /// no other image has.
    fn leave(&mut self, image: &mut Image) {
        if self.runs == u64::from(u32::MAX) {
            self.key = next_key();
            self.runs = 0;
        }
        self.runs += 1;
        self.last = self.key | self.runs;
        image.set_version(self.last);
    }
}

/// A key no other shadow of this process has had (keys repeat only after 2^32 of them, and
/// with them versions).
fn next_key() -> u64 {
    static NEXT: AtomicU64 = AtomicU64::new(1);
    NEXT.fetch_add(1, Ordering::Relaxed) << 32
}

impl JitProgram {
    /// Compiles `program` for the host CPU.
    pub fn compile(program: &Program, opts: &JitOptions) -> Result<JitProgram, JitError> {
        Self::compile_with(
            program,
            opts,
            false,
            Rules::in_force(program.profile.profile().family),
        )
    }

    /// Compiles `program` following `rules` instead of [`Rules::IN_FORCE`] (for tests that flip
    /// a rule switch on both engines).
    pub fn compile_with_rules(
        program: &Program,
        opts: &JitOptions,
        rules: Rules,
    ) -> Result<JitProgram, JitError> {
        Self::compile_with(program, opts, false, rules)
    }

    /// Compiles an instrumented build that counts every executed op (slower; for `bench`'s
    /// per-instruction figures). Read the count with [`JitProgram::executed_ops`].
    pub fn compile_counting(program: &Program, opts: &JitOptions) -> Result<JitProgram, JitError> {
        Self::compile_with(
            program,
            opts,
            true,
            Rules::in_force(program.profile.profile().family),
        )
    }

    /// Ops executed so far by an instrumented build (`None` for a normal build).
    pub fn executed_ops(&self) -> Option<u64> {
        self.counter.as_deref().map(|c| c.load(Ordering::Relaxed))
    }

    fn compile_with(
        program: &Program,
        opts: &JitOptions,
        count: bool,
        rules: Rules,
    ) -> Result<JitProgram, JitError> {
        let layout = Box::new(Layout::of(program.profile));
        let plan = Box::new(ScanPlan::of(program));
        // An atomic so that the code's plain stores through its address are legal interior
        // mutation; it is only read between scans.
        let counter = count.then(|| Box::new(AtomicU64::new(0)));
        // Filled after finalizing, through a shared reference (`NativeRoutines::install`).
        let routines = program
            .has_interrupts()
            .then(|| Box::new(NativeRoutines::new()));
        let resident = Resident::plan(program, &layout);
        let baked = Baked {
            layout: &*layout as *const Layout as i64,
            scan_plan: &*plan as *const ScanPlan as i64,
            routines: routines
                .as_deref()
                .map_or(0, |r| r as *const NativeRoutines as i64),
            op_counter: counter.as_deref().map(|c| c.as_ptr() as i64),
        };
        let Built {
            mut module,
            run_id,
            pou_ids,
            ext,
        } = build::build(
            program,
            opts,
            rules,
            &layout,
            baked,
            &resident,
            true,
            &mut |_, _, _| {},
        )?;
        module
            .finalize_definitions()
            .map_err(|e| JitError::Codegen(format!("{e:?}")))?;
        let run_ptr = module.get_finalized_function(run_id);
        // SAFETY: the address is a finalized function of `module` compiled with the signature
        // `build::run_signature` in the host's default calling convention, which is the C ABI
        // this type names. `module` (and with it the code) lives as long as `self`.
        let run = unsafe { std::mem::transmute::<*const u8, RunFn>(run_ptr) };
        if let Some(table) = routines.as_deref() {
            let fns = program
                .pous
                .iter()
                .zip(&pou_ids)
                .map(|(pou, &id)| {
                    pou.kind.interrupt().map(|_| {
                        let ptr = module.get_finalized_function(id);
                        // SAFETY: a finalized function of `module` compiled with
                        // `build::pou_signature` in the host's default calling convention,
                        // the C ABI `PouFn` names; it lives as long as `self`, which owns
                        // the table too.
                        unsafe { std::mem::transmute::<*const u8, PouFn>(ptr) }
                    })
                })
                .collect();
            // SAFETY: as above, each function is the program's compiled POU for this layout
            // and lives as long as the table.
            unsafe { table.install(fns) };
        }
        let shadow = (resident.len() > 0).then(|| Shadow {
            bytes: resident.len(),
            scratch: resident.scratch(&layout),
            flag: resident.flag_offset(),
            key: next_key(),
            runs: 0,
            last: 0,
        });
        Ok(JitProgram {
            module: Some(module),
            run,
            layout,
            _plan: plan,
            _routines: routines,
            op_count: program.op_count(),
            _ext: ext,
            counter,
            shadow,
        })
    }

    /// Number of IR ops compiled.
    pub fn op_count(&self) -> usize {
        self.op_count
    }

    /// Number of image bytes the code keeps one byte per bit while it runs (its resident
    /// bits, ARCHITECTURE.md).
    pub fn resident_bytes(&self) -> usize {
        self.shadow.as_ref().map_or(0, |s| s.bytes)
    }

    /// Whether `image` has the layout this program was compiled for (anything else is refused:
    /// the code addresses the image at constant offsets).
    fn fits(&self, image: &Image) -> bool {
        // An image's layout is `Layout::of` its profile (the only constructor), so the profile
        // names it: comparing it instead of the whole table keeps this check off the per-scan
        // cost.
        debug_assert!(
            image.layout().profile != self.layout.profile || *image.layout() == *self.layout
        );
        image.layout().profile == self.layout.profile
            && image.bytes().len() == self.layout.size as usize
    }

    /// [`Engine::run_scans`] in one native call (the compiled N-scan loop). Never inlined, so
    /// that a profiler can count everything a scan costs from here (`valgrind --tool=callgrind
    /// --toggle-collect='*native_scans*'`, `docs/performance.md`) without the driver.
    #[inline(never)]
    fn native_scans(
        &mut self,
        image: &mut Image,
        t0_ms: u64,
        scan_ms: u64,
        n: u64,
        watch: Option<&mut ChangeWatch>,
    ) -> (u64, ScanStatus) {
        if !self.fits(image) {
            return (0, ScanStatus::Fatal);
        }
        let mut done = 0u64;
        let bytes = match &self.shadow {
            Some(s) => s.enter(image).as_mut_ptr(),
            None => image.bytes_mut().as_mut_ptr(),
        };
        let watch = watch.map_or(std::ptr::null_mut(), |w| w as *mut ChangeWatch);
        // SAFETY: `bytes` points to `layout.size` bytes exclusively borrowed for the call (checked
        // by `fits`), the code only addresses the image within its layout (direct offsets are
        // range-checked at compile time, pointers through `pointer::resolve`), `done` is a
        // live u64, and `watch` is null or a live `ChangeWatch` borrowed for the call, which the
        // code only passes to `stljit_rt_watch_changed`.
        let st = unsafe { (self.run)(bytes, t0_ms, scan_ms, n, &mut done, watch) };
        if let Some(s) = &mut self.shadow {
            s.leave(image);
        }
        (
            done,
            ScanStatus::try_from(st as u8).unwrap_or(ScanStatus::Fatal),
        )
    }
}

impl Engine for JitProgram {
    fn name(&self) -> &'static str {
        "jit"
    }

    fn scan(&mut self, image: &mut Image, t_ms: u64) -> ScanStatus {
        // One turn of the native loop: its inline prologue and epilogue are the cheapest way
        // through a scan (`scan_loop`), and the same bytes as `scan::run` around the body.
        self.native_scans(image, t_ms, 0, 1, None).1
    }

    fn run_scans(
        &mut self,
        image: &mut Image,
        t0_ms: u64,
        scan_ms: u64,
        n: u64,
    ) -> (u64, ScanStatus) {
        self.native_scans(image, t0_ms, scan_ms, n, None)
    }

    fn run_scans_watching(
        &mut self,
        image: &mut Image,
        t0_ms: u64,
        scan_ms: u64,
        n: u64,
        watch: &mut ChangeWatch,
    ) -> (u64, ScanStatus) {
        self.native_scans(image, t0_ms, scan_ms, n, Some(watch))
    }
}

impl Drop for JitProgram {
    fn drop(&mut self) {
        if let Some(m) = self.module.take() {
            // SAFETY: no code of this module is running (we hold `&mut self`) and the function
            // pointers die with `self`.
            unsafe { m.free_memory() };
        }
    }
}

impl std::fmt::Debug for JitProgram {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("JitProgram")
            .field("ops", &self.op_count)
            .finish()
    }
}
