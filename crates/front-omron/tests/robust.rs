//! No input makes the Omron front end panic: truncated and garbled lines of a real program,
//! random bytes, a 1 MB line; and every diagnostic of a file is reported, not just the first.

use stljit_core::ProfileId;
use stljit_front_omron::{Code, SourceFile, compile, render_human};

fn run(bytes: Vec<u8>) -> stljit_front_omron::Compilation {
    let f = SourceFile {
        name: "x.omr".into(),
        bytes,
    };
    let c = compile(std::slice::from_ref(&f), Some(&f), ProfileId::Cp1e);
    for d in &c.diagnostics {
        let _ = render_human(d, &c.sources);
    }
    assert_eq!(c.program.is_some(), c.error_count() == 0);
    c
}

#[test]
fn truncated_and_garbled_lines_never_panic() {
    let base = std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/tests/spec/s6_8.omr")).unwrap();
    let text = String::from_utf8(base.clone()).unwrap();
    // Every line cut at every position.
    for line in text.lines() {
        for cut in 0..=line.len() {
            if line.is_char_boundary(cut) {
                run(format!("{}\nEND(001)\n", &line[..cut]).into_bytes());
            }
        }
    }
    // Byte flips, cuts and splices from a fixed-seed xorshift.
    let mut s = 0x9E37_79B9_7F4A_7C15_u64;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        s
    };
    for _ in 0..400 {
        let mut b = base.clone();
        for _ in 0..(next() % 12) {
            let at = (next() as usize) % b.len().max(1);
            match next() % 3 {
                0 if !b.is_empty() => b[at] = next() as u8,
                1 => b.truncate(at),
                _ => b.insert(
                    at.min(b.len()),
                    b"()@%!#&+-.,;'*TRCIO"[(next() % 19) as usize],
                ),
            }
        }
        run(b);
    }
    let mut long = b"LD ".to_vec();
    long.extend(std::iter::repeat_n(b'9', 1 << 20));
    let c = run(long);
    assert!(
        c.diagnostics
            .iter()
            .all(|d| d.text.len() < 200 && d.message.len() < 400)
    );
    run((0..4096u32)
        .map(|i| (i.wrapping_mul(2_654_435_761) >> 13) as u8)
        .collect());
    run(Vec::new());
}

#[test]
fn every_diagnostic_of_a_file_is_reported() {
    let c = run(b"LD 0.00\nOUT W600.00\nLD 0.01\nMOVV D0 D1\nAND LD\nLD 0.02\nOUT P_EQ\n".to_vec());
    let codes: Vec<_> = c.diagnostics.iter().map(|d| (d.code, d.line)).collect();
    // W600 is outside CP1E's W0–W99; MOVV is unknown; AND LD has nothing to combine after the
    // unknown line (its recovery leaves no pending block); P_EQ is read-only; no END.
    assert!(codes.contains(&(Code::OmrRange, 2)), "{codes:?}");
    assert!(codes.contains(&(Code::OmrInstruction, 4)), "{codes:?}");
    assert!(codes.contains(&(Code::OmrNothingToCombine, 5)), "{codes:?}");
    assert!(codes.contains(&(Code::OmrReadOnly, 7)), "{codes:?}");
    assert!(codes.contains(&(Code::OmrNoEnd, 8)), "{codes:?}");
}
