//! Fuzz target: arbitrary bytes as a program file (and as a symbol table) must never panic the
//! front end, and every accepted program must print to text that compiles to the same IR. Bit 0
//! of the first byte picks the dialect (S7 STL or Omron mnemonics); the rest is the file. S7
//! text is compiled for every profile, Omron text for the Omron ones.
#![no_main]

use libfuzzer_sys::fuzz_target;
use stljit_core::ProfileId;
use stljit_core::ir::Program;
use stljit_front::{Dialect, SourceFile, render_human, render_json};

/// The program without source locations and file names, for comparison.
fn normalized(mut p: Program) -> Program {
    for pou in &mut p.pous {
        pou.locs.clear();
    }
    p.files.clear();
    p
}

fuzz_target!(|data: &[u8]| {
    let dialect = match data.first() {
        Some(b) if b & 1 == 1 => Dialect::Omron,
        _ => Dialect::S7,
    };
    let file = SourceFile {
        name: "fuzz.txt".into(),
        bytes: data.get(1..).unwrap_or_default().to_vec(),
    };
    let profiles: &[ProfileId] = match dialect {
        Dialect::S7 => &ProfileId::ALL,
        Dialect::Omron => dialect.profiles(),
    };
    for &profile in profiles {
        let c = dialect.compile(std::slice::from_ref(&file), Some(&file), profile);
        for d in &c.diagnostics {
            let _ = render_human(d, &c.sources);
            let _ = render_json(d, &c.sources);
        }
        let c = dialect.compile(std::slice::from_ref(&file), None, profile);
        if let Some(program) = c.program {
            let text = dialect
                .print_program(&program)
                .expect("an accepted program prints");
            let printed = SourceFile::from_text("printed.txt", &text);
            let again = dialect.compile(&[printed], None, profile);
            let again = again.program.expect("printed program compiles");
            assert_eq!(
                normalized(program),
                normalized(again),
                "round trip changed the IR:\n{text}"
            );
        }
    }
});
