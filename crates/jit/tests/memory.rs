//! Compiled code is released on drop: compiling and dropping thousands of programs in one
//! process keeps the resident set bounded (Linux only: reads `/proc/self/statm`).

use stljit_jit::{JitOptions, JitProgram};

fn rss_pages() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/statm").ok()?;
    s.split_whitespace().nth(1)?.parse().ok()
}

#[test]
fn compile_and_drop_does_not_grow() {
    let text =
        "LD I0.0\nA I0.1\n= Q0.0\nLD I0.2\nTON T37, 10\nLD SM0.0\nMOVW IW0, VW0\n+I 1, VW0\n";
    let c = stljit_front_s7::compile_str("mem.stl", text, stljit_core::ProfileId::A5);
    let p = c.program.expect("compiles");
    let opts = JitOptions::default();
    let n = if cfg!(debug_assertions) { 600 } else { 2000 };
    // Warm up allocator pools before taking the baseline.
    for _ in 0..100 {
        drop(JitProgram::compile(&p, &opts).expect("compiles"));
    }
    let Some(before) = rss_pages() else { return };
    for _ in 0..n {
        drop(JitProgram::compile(&p, &opts).expect("compiles"));
    }
    let after = rss_pages().unwrap_or(before);
    // Without free_memory every program keeps at least one 4 KiB code page: n pages of growth.
    let grown = after.saturating_sub(before);
    assert!(
        grown < 256,
        "RSS grew by {grown} pages over {n} compile/drop cycles"
    );
}
