//! `stljit dump-clif`: the annotated CLIF names each op's source line, covers every function
//! (chunks and dispatcher of a split POU included), and the optimised form is what Cranelift's
//! mid-end made of it.

use stljit_core::ir::Program;
use stljit_jit::{JitOptions, OptLevel, asm_text, clif_text, optimized_clif_text};

fn stl(text: &str) -> Program {
    let c = stljit_front_s7::compile_str("test.stl", text, stljit_core::ProfileId::A5);
    c.program.expect("test program compiles")
}

const PROGRAM: &str = "LD I0.0\nA M1.0\n+I VW0, VW2\nAENO\n= Q0.0\nLD I0.1\nMOVW VW4, VW6\n";

/// Instruction lines (`vN = ...` definitions and side-effecting ops such as stores).
/// Instructions of the program's own functions (the dump ends with the scan loop, whose
/// optimised form is not the point here).
fn instructions(text: &str) -> usize {
    let program = text.split("; the scan loop").next().unwrap_or(text);
    program
        .lines()
        .filter(|l| {
            let l = l.trim_start();
            l.starts_with('@') || l.starts_with('v')
        })
        .count()
}

#[test]
fn ops_are_annotated_with_their_source_lines_in_order() {
    let p = stl(PROGRAM);
    let text = clif_text(&p, &JitOptions::default()).expect("dump");
    assert!(text.starts_with("; POU 0: MAIN"), "{text}");
    // `; test.stl:LINE op I: ...` above the first instruction of every op that emits any (a
    // contact whose byte is already loaded emits none).
    let ops: Vec<(usize, usize)> = text
        .lines()
        .filter_map(|l| l.trim_start().strip_prefix("; test.stl:"))
        .map(|rest| {
            let (line, rest) = rest.split_once(" op ").expect("op index");
            let (op, _) = rest.split_once(':').expect("op text");
            (line.parse().expect("line"), op.parse().expect("op"))
        })
        .collect();
    assert!(ops.iter().all(|&(line, op)| line == op + 1), "{ops:?}");
    assert!(
        ops.windows(2).all(|w| w[0].1 < w[1].1),
        "not in op order: {ops:?}"
    );
    for op in [0, 1, 2, 4, 6] {
        assert!(
            ops.iter().any(|&(_, o)| o == op),
            "op {op} missing:\n{text}"
        );
    }
}

#[test]
fn optimized_clif_is_smaller_at_speed_and_still_annotated() {
    let p = stl(PROGRAM);
    let opts = JitOptions::at(OptLevel::Speed);
    let raw = clif_text(&p, &opts).expect("dump");
    let opt = optimized_clif_text(&p, &opts).expect("dump");
    assert!(
        instructions(&opt) < instructions(&raw),
        "{} optimised vs {} generated instructions",
        instructions(&opt),
        instructions(&raw)
    );
    assert!(opt.contains("sadd_overflow"), "{opt}");
    assert!(opt.contains("; test.stl:3 op 2: Box(IntArith"), "{opt}");
}

#[test]
fn a_split_pou_dumps_its_chunks_and_dispatcher() {
    let mut text = String::new();
    for i in 0..40 {
        text.push_str(&format!("LD I0.{}\n= Q0.{}\nLBL {i}\n", i % 8, i % 8));
    }
    let p = stl(&text);
    let opts = JitOptions {
        chunk_ops: 16,
        ..JitOptions::default()
    };
    let clif = clif_text(&p, &opts).expect("dump");
    assert!(clif.contains("; POU 0: MAIN (Main) chunk 0"), "{clif}");
    assert!(clif.contains("; POU 0: MAIN (Main) chunk 1"), "{clif}");
    assert!(clif.contains("; POU 0: MAIN (Main) dispatcher"), "{clif}");
    let asm = asm_text(&p, &opts).expect("asm");
    assert!(
        asm.contains("Chunk(1)") && asm.contains("Dispatch"),
        "{asm}"
    );
    assert!(asm.contains("ret"), "{asm}");
}

#[test]
fn integer_boxes_in_a_row_derive_smb1_once() {
    // Three +/- boxes under three power flows: each box's SM1.0–SM1.2 depend only on its
    // result and overflow, so the JIT selects those along the chain and tests the surviving
    // result for zero once; the first two boxes' SMB1 stores are overwritten unread and go,
    // and their flag computations with them. (What the bytes must be is conformance case
    // `t20_box_flag_chain.toml`.)
    let p = stl("LD I0.0\n+I VW0, VW2\nLD I0.1\n-I VW4, VW6\nLD I0.2\nINCW VW8\n");
    let opt = optimized_clif_text(&p, &JitOptions::at(OptLevel::Speed)).expect("dump");
    let main = opt.split("; the scan loop").next().unwrap_or(&opt);
    let zero_tests = main.lines().filter(|l| l.contains("icmp eq")).count();
    let smb1_stores = main
        .lines()
        // SMB1 is image byte 81 in the a5 layout.
        .filter(|l| l.contains("istore8") && l.ends_with("v0+81"))
        .count();
    assert_eq!((zero_tests, smb1_stores), (1, 1), "{main}");
}
