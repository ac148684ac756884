//! The conformance programs of omron-cp.md §6 (copied verbatim into `tests/spec/`) compile with
//! no error, and every compiled program passes the IR verifier.

use stljit_core::ProfileId;
use stljit_core::ir::{OmronBox, Op, Operand, verify};
use stljit_front_omron::{Code, Severity, compile_str};

fn spec(name: &str) -> String {
    let path = format!("{}/tests/spec/{name}.omr", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn errors(text: &str) -> Vec<(Code, u32, String)> {
    let c = compile_str("t.omr", text, ProfileId::Cp1h);
    c.diagnostics
        .iter()
        .filter(|d| d.severity == Severity::Error)
        .map(|d| (d.code, d.line, d.message.clone()))
        .collect()
}

#[test]
fn every_section_6_program_compiles_and_verifies() {
    for name in [
        "s6_1", "s6_2", "s6_3", "s6_4", "s6_5", "s6_6", "s6_7", "s6_8", "s6_9", "s6_10",
    ] {
        let text = spec(name);
        assert!(errors(&text).is_empty(), "{name}: {:#?}", errors(&text));
        for profile in [ProfileId::Cp1h, ProfileId::Cp1e] {
            let c = compile_str(name, &text, profile);
            assert_eq!(
                c.error_count(),
                0,
                "{name} on {profile:?}: {:#?}",
                c.diagnostics
            );
            let p = c.program.expect("no errors, so a program");
            verify(&p).unwrap_or_else(|e| panic!("{name}: {e}"));
        }
    }
}

#[test]
fn section_6_8_warns_exactly_about_its_pitfalls() {
    // §6.8 writes the seed's pitfalls on purpose (§2.10): part A reads "=" after the MOV that
    // overwrote the CMP's (W033 at its `AND NOT P_EQ`), part C connects a flag to the bus
    // (W032 at `LD P_EQ`), part D reads the flag of a differentiated MOV (W033 at the `AND
    // P_EQ` after `@MOV`). The fixes (parts B, C's second circuit, D's DIFU) draw nothing.
    let text = spec("s6_8");
    let c = compile_str("s6_8", &text, ProfileId::Cp1h);
    let w: Vec<_> = c.diagnostics.iter().map(|d| (d.code, d.line)).collect();
    let line = |prefix: &str, nth: usize| {
        text.lines()
            .enumerate()
            .filter(|(_, l)| l.starts_with(prefix))
            .nth(nth)
            .map(|(i, _)| i as u32 + 1)
            .unwrap()
    };
    assert_eq!(
        w,
        [
            (Code::OmrFlagOverwritten, line("AND NOT P_EQ", 0)),
            (Code::OmrFlagAtStart, line("LD      P_EQ", 0)),
            (Code::OmrFlagOverwritten, line("AND     P_EQ", 3)),
        ]
    );
}

#[test]
fn section_6_10_compiles_with_its_indirect_and_index_register_lines() {
    // MOVR, `@D20`, `*D21`, `,IR0+` and `+2,IR0` (§1.7) lower to Omron indirect operands and
    // `SetIndex`: the whole of §6.10 compiles and verifies.
    let c = compile_str("s6_10", &spec("s6_10"), ProfileId::Cp1h);
    assert_eq!(c.error_count(), 0, "{:#?}", c.diagnostics);
    let p = c.program.unwrap();
    verify(&p).unwrap();
    let ops = &p.pous[0].ops;
    assert!(
        ops.iter()
            .any(|o| matches!(o, Op::Omron(OmronBox::SetIndex { ir: 0, .. })))
    );
    let refs = ops
        .iter()
        .filter(|o| {
            matches!(
                o,
                Op::Omron(OmronBox::Move {
                    dst: Operand::Omron(_),
                    ..
                })
            )
        })
        .count();
    assert_eq!(refs, 5, "@D20, *D21, ,IR0+ twice, +2,IR0");
}
