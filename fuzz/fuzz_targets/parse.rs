//! Fuzz target: arbitrary bytes as a program file (and as a symbol table) must never panic the
//! front end, and every accepted program must print to text that compiles to the same IR. Bit 0
//! of the first byte picks the dialect (S7 STL or Omron mnemonics), for Omron bit 1 the binary
//! timer mode and bit 2 `allow_backward_jumps`; the rest is the file. S7 text is compiled for
//! every profile, Omron text for the Omron ones.
#![no_main]

use libfuzzer_sys::fuzz_target;
use stljit_core::ProfileId;
use stljit_core::ir::Program;
use stljit_front::{Dialect, Options, SourceFile, TcMode, render_human, render_json};

/// The program without source locations and file names, for comparison.
fn normalized(mut p: Program) -> Program {
    for pou in &mut p.pous {
        pou.locs.clear();
    }
    p.files.clear();
    p
}

fuzz_target!(|data: &[u8]| {
    let first = data.first().copied().unwrap_or(0);
    let dialect = if first & 1 == 1 {
        Dialect::Omron
    } else {
        Dialect::S7
    };
    let mut options = Options::default();
    if dialect == Dialect::Omron {
        if first & 2 != 0 {
            options.omron.tc_mode = TcMode::Binary;
        }
        options.omron.allow_backward_jumps = first & 4 != 0;
    }
    let file = SourceFile {
        name: "fuzz.txt".into(),
        bytes: data.get(1..).unwrap_or_default().to_vec(),
    };
    let profiles: &[ProfileId] = match dialect {
        Dialect::S7 => &ProfileId::ALL,
        Dialect::Omron => dialect.profiles(),
    };
    for &profile in profiles {
        let c = dialect.compile_with(std::slice::from_ref(&file), Some(&file), profile, options);
        for d in &c.diagnostics {
            let _ = render_human(d, &c.sources);
            let _ = render_json(d, &c.sources);
        }
        let c = dialect.compile_with(std::slice::from_ref(&file), None, profile, options);
        if let Some(program) = c.program {
            let text = dialect
                .print_program(&program)
                .expect("an accepted program prints");
            let printed = SourceFile::from_text("printed.txt", &text);
            let again =
                dialect.compile_with(&[printed], None, profile, dialect.printed_options(&program));
            let again = again.program.expect("printed program compiles");
            assert_eq!(
                normalized(program),
                normalized(again),
                "round trip changed the IR:\n{text}"
            );
        }
    }
});
