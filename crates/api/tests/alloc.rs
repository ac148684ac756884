//! Running with pre-resolved handles allocates nothing per scan: a counting global allocator
//! (this test binary's own) sees no allocation across thousands of closed-loop scans on either
//! engine, whether the loop is one `scan()` per step or one `run` with a recording observer.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use stljit_api::{EngineKind, Options, Plc, Project, Recorder, Until, Value};

struct Counting;

thread_local! {
    /// Allocations made by this thread (the test harness's own threads are not counted).
    static ALLOCATIONS: Cell<u64> = const { Cell::new(0) };
}

fn count() {
    ALLOCATIONS.with(|c| c.set(c.get() + 1));
}

// SAFETY: forwards every call to the system allocator unchanged; only counts.
#[allow(unsafe_code)]
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        // SAFETY: same contract as the caller's.
        unsafe { System.alloc(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as the caller's.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        // SAFETY: same contract as the caller's.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// A level controller with hysteresis, a timer and a counter, so the scans do real work.
const PROGRAM: &str = "\
NETWORK 1
LDW< AIW0, 8000
S Q0.0, 1
NETWORK 2
LDW> AIW0, 24000
R Q0.0, 1
NETWORK 3
LD Q0.0
TON T37, 100
NETWORK 4
LD Q0.0
EU
LD M0.0
CTU C0, 100
";

fn allocations_during(f: impl FnOnce()) -> u64 {
    let before = ALLOCATIONS.with(Cell::get);
    f();
    ALLOCATIONS.with(Cell::get) - before
}

#[test]
fn closed_loop_scans_with_handles_do_not_allocate() {
    for engine in [EngineKind::Jit, EngineKind::Interp] {
        let options = Options {
            engine,
            ..Options::default()
        };
        let mut plc = Plc::compile(&Project::new().text("level.stl", PROGRAM), &options).unwrap();
        let (level_in, valve) = (plc.handle("AIW0").unwrap(), plc.handle("Q0.0").unwrap());
        let mut level = 16_000i64;
        let mut step = |plc: &mut Plc| {
            plc.set(&level_in, level).unwrap();
            plc.scan().unwrap();
            let open = plc.get(&valve).unwrap() == Value::Bool(true);
            level += if open { 40 } else { -25 };
        };
        step(&mut plc); // the first scan may set up lazily
        let n = allocations_during(|| {
            for _ in 0..5_000 {
                step(&mut plc);
            }
        });
        assert_eq!(n, 0, "{engine:?}: {n} allocations in 5000 scans");
        assert!(plc.read("C0").is_ok());

        let mut rec = Recorder::new(vec![valve.clone(), level_in.clone()], 10_000);
        let n = allocations_during(|| {
            plc.run_observed(Until::Scans(10_000), &mut rec).unwrap();
        });
        assert_eq!(n, 0, "{engine:?}: run with a recorder allocated {n} times");
        assert_eq!(rec.len(), 10_000);
    }
}
