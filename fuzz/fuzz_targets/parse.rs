//! Fuzz target: arbitrary bytes as a program file (and as a symbol table) must never panic the
//! front end, and every accepted program must print to text that compiles to the same IR.
#![no_main]

use libfuzzer_sys::fuzz_target;
use stljit_core::ProfileId;
use stljit_front_s7::{SourceFile, compile, print_program, render_human, render_json};

fuzz_target!(|data: &[u8]| {
    let file = SourceFile {
        name: "fuzz.stl".into(),
        bytes: data.to_vec(),
    };
    for profile in ProfileId::ALL {
        let c = compile(std::slice::from_ref(&file), Some(&file), profile);
        for d in &c.diagnostics {
            let _ = render_human(d, &c.sources);
            let _ = render_json(d, &c.sources);
        }
        let c = compile(std::slice::from_ref(&file), None, profile);
        if let Some(program) = c.program {
            let text = print_program(&program);
            let again = compile(
                &[SourceFile {
                    name: "printed.awl".into(),
                    bytes: text.clone().into_bytes(),
                }],
                None,
                profile,
            );
            let mut again = again.program.expect("printed program compiles");
            let mut program = program;
            for p in program.pous.iter_mut().chain(again.pous.iter_mut()) {
                p.locs.clear();
            }
            program.files.clear();
            again.files.clear();
            assert_eq!(program, again, "round trip changed the IR:\n{text}");
        }
    }
});
