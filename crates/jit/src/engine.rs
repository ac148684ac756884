//! [`JitProgram`]: finalizes the compiled module, enters the native code, frees it on drop.
//!
//! This is the only module with `unsafe`: turning finalized code addresses into `extern "C"`
//! function pointers, calling them, and releasing the code memory.
#![allow(unsafe_code)]

use crate::build::{self, Built};
use crate::lower::Baked;
use crate::{JitError, JitOptions};
use cranelift_jit::JITModule;
use cranelift_module::Module;
use std::sync::atomic::{AtomicU64, Ordering};
use stljit_core::ir::Program;
use stljit_core::layout::Layout;
use stljit_core::{PouId, ScanStatus};
use stljit_runtime::rules::Rules;
use stljit_runtime::scan::{self, ScanPlan};
use stljit_runtime::{Engine, Image};

type PouFn = unsafe extern "C" fn(*mut u8, i32) -> i32;
type RunFn = unsafe extern "C" fn(*mut u8, u64, u64, u64, *mut u64) -> i32;

/// A program compiled to native code. Implements [`Engine`]; all state lives in the [`Image`].
pub struct JitProgram {
    module: Option<JITModule>,
    main: PouFn,
    run: RunFn,
    /// Boxed so its address, baked into the code for the runtime shims, never moves.
    layout: Box<Layout>,
    /// What the scan prologue touches; boxed for the same reason.
    plan: Box<ScanPlan>,
    op_count: usize,
    /// The executed-op counter of an instrumented build ([`JitProgram::compile_counting`]).
    counter: Option<Box<AtomicU64>>,
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
        let baked = Baked {
            layout: &*layout as *const Layout as i64,
            scan_plan: &*plan as *const ScanPlan as i64,
            op_counter: counter.as_deref().map(|c| c.as_ptr() as i64),
        };
        let Built { mut module, run_id } = build::build(
            program,
            opts,
            rules,
            &layout,
            baked,
            true,
            &mut |_, _, _| {},
        )?;
        module
            .finalize_definitions()
            .map_err(|e| JitError::Codegen(format!("{e:?}")))?;
        let main_id = module
            .get_name("pou0")
            .and_then(|n| match n {
                cranelift_module::FuncOrDataId::Func(f) => Some(f),
                cranelift_module::FuncOrDataId::Data(_) => None,
            })
            .ok_or_else(|| JitError::Codegen("main function missing".into()))?;
        let main_ptr = module.get_finalized_function(main_id);
        let run_ptr = module.get_finalized_function(run_id);
        // SAFETY: both addresses are finalized functions of `module` compiled with the
        // signatures `build::pou_signature` / `build::run_signature` in the host's default
        // calling convention, which is the C ABI these types name. `module` (and with it the
        // code) lives as long as `self`.
        let (main, run) = unsafe {
            (
                std::mem::transmute::<*const u8, PouFn>(main_ptr),
                std::mem::transmute::<*const u8, RunFn>(run_ptr),
            )
        };
        Ok(JitProgram {
            module: Some(module),
            main,
            run,
            layout,
            plan,
            op_count: program.op_count(),
            counter,
        })
    }

    /// Number of IR ops compiled.
    pub fn op_count(&self) -> usize {
        self.op_count
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

    /// [`Engine::run_scans`] in one native call (the compiled N-scan loop).
    fn native_scans(
        &mut self,
        image: &mut Image,
        t0_ms: u64,
        scan_ms: u64,
        n: u64,
    ) -> (u64, ScanStatus) {
        if !self.fits(image) {
            return (0, ScanStatus::Fatal);
        }
        let mut done = 0u64;
        let bytes = image.bytes_mut().as_mut_ptr();
        // SAFETY: `bytes` points to `layout.size` bytes exclusively borrowed for the call (checked
        // by `fits`), the code only addresses the image within its layout (direct offsets are
        // range-checked at compile time, pointers through `pointer::resolve`), and `done` is a
        // live u64.
        let st = unsafe { (self.run)(bytes, t0_ms, scan_ms, n, &mut done) };
        (
            done,
            ScanStatus::try_from(st as u8).unwrap_or(ScanStatus::Fatal),
        )
    }

    fn body(&self, bytes: &mut [u8]) -> ScanStatus {
        let st = enter_main(self.main, bytes);
        if st == 0 {
            ScanStatus::Ok
        } else {
            ScanStatus::Fatal
        }
    }

    /// The POU a native function belongs to, for diagnostics.
    pub fn main_pou(&self) -> PouId {
        PouId(0)
    }
}

/// Runs the compiled main program once. Never inlined, so that a profiler can count exactly
/// the program's own work (`valgrind --tool=callgrind --toggle-collect=*enter_main*`, see
/// `docs/performance.md`), without the scan's begin/end or the driver.
#[inline(never)]
fn enter_main(main: PouFn, bytes: &mut [u8]) -> i32 {
    // SAFETY: as in `run_scans`; the caller passes the whole image of the program's layout
    // (checked by `fits`).
    unsafe { main(bytes.as_mut_ptr(), 0) }
}

impl Engine for JitProgram {
    fn name(&self) -> &'static str {
        "jit"
    }

    fn scan(&mut self, image: &mut Image, t_ms: u64) -> ScanStatus {
        if !self.fits(image) {
            return ScanStatus::Fatal;
        }
        let (bytes, layout) = image.split_mut();
        scan::run(bytes, layout, &self.plan, t_ms, |b, _| self.body(b))
    }

    fn run_scans(
        &mut self,
        image: &mut Image,
        t0_ms: u64,
        scan_ms: u64,
        n: u64,
    ) -> (u64, ScanStatus) {
        self.native_scans(image, t0_ms, scan_ms, n)
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
