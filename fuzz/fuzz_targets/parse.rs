//! Fuzz target: arbitrary bytes as a program file (and as a symbol table) must never panic the
//! front end, and every accepted program must print to text that compiles to the same IR. Bit 0
//! of the first byte picks the dialect (S7 STL or Omron mnemonics); the rest is the file.
#![no_main]

use libfuzzer_sys::fuzz_target;
use stljit_core::ir::Program;
use stljit_core::{Family, ProfileId};

/// The program without source locations and file names, for comparison.
fn normalized(mut p: Program) -> Program {
    for pou in &mut p.pous {
        pou.locs.clear();
    }
    p.files.clear();
    p
}

fn s7(file: &stljit_front_s7::SourceFile, profile: ProfileId) {
    use stljit_front_s7::{SourceFile, compile, print_program, render_human, render_json};
    let c = compile(std::slice::from_ref(file), Some(file), profile);
    for d in &c.diagnostics {
        let _ = render_human(d, &c.sources);
        let _ = render_json(d, &c.sources);
    }
    let c = compile(std::slice::from_ref(file), None, profile);
    if let Some(program) = c.program {
        let text = print_program(&program);
        let printed = SourceFile::from_text("printed.awl", &text);
        let again = compile(&[printed], None, profile);
        let again = again.program.expect("printed program compiles");
        assert_eq!(
            normalized(program),
            normalized(again),
            "round trip changed the IR:\n{text}"
        );
    }
}

fn omron(file: &stljit_front_omron::SourceFile, profile: ProfileId) {
    use stljit_front_omron::{compile, compile_str, print_program, render_human, render_json};
    let c = compile(std::slice::from_ref(file), Some(file), profile);
    for d in &c.diagnostics {
        let _ = render_human(d, &c.sources);
        let _ = render_json(d, &c.sources);
    }
    let c = compile(std::slice::from_ref(file), None, profile);
    if let Some(program) = c.program {
        let text = print_program(&program).unwrap_or_else(|e| panic!("not printable: {e}"));
        let again = compile_str("printed.omr", &text, profile);
        let again = again.program.expect("printed program compiles");
        assert_eq!(
            normalized(program),
            normalized(again),
            "round trip changed the IR:\n{text}"
        );
    }
}

fuzz_target!(|data: &[u8]| {
    let omron_dialect = data.first().is_some_and(|b| b & 1 == 1);
    let bytes = data.get(1..).unwrap_or_default().to_vec();
    for profile in ProfileId::ALL {
        match (omron_dialect, profile.profile().family) {
            (false, _) => s7(
                &stljit_front_s7::SourceFile {
                    name: "fuzz.stl".into(),
                    bytes: bytes.clone(),
                },
                profile,
            ),
            (true, Family::Omron) => omron(
                &stljit_front_omron::SourceFile {
                    name: "fuzz.omr".into(),
                    bytes: bytes.clone(),
                },
                profile,
            ),
            _ => {}
        }
    }
});
