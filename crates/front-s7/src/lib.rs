//! The S7-200/A5 statement-list front end of stljit.
//!
//! [`compile`] takes the files of a project (plain STL or MicroWIN `.awl` exports, UTF-8 or GBK),
//! an optional MicroWIN symbol table and a CPU profile, and returns the checked
//! [`stljit_core::ir::Program`] together with every diagnostic. It never panics and never stops
//! at the first error. [`print_program`] turns a program back into STL text that parses to the
//! same IR; [`parse_address`] reads the addresses the CLI's stimulus and watch options name.
//!
//! Pipeline: `decode` → `structure` (lines into POUs, using `lexer`; `VAR_…` declarations with
//! `locals`; `DATA_BLOCK` lines read by `data_block`) → `program` (lowering with
//! `lower`/`control`/`interrupts`/`ext`, operands through
//! `operand`/`names`/`classes` against the project symbols, the CPU's `system_symbols` and the
//! block's `locals`, the `stack` analysis) → IR.

mod address;
mod classes;
mod comm;
mod control;
mod data_block;
mod ext;
mod hsc;
mod interrupts;
mod lexer;
pub mod locals;
mod lower;
mod mnemonics;
mod names;
mod operand;
mod params;
mod print;
mod program;
mod pulse;
pub mod spelling;
mod stack;
mod structure;
mod symbols;
mod system_symbols;

pub use address::{Address, AddressError, parse_address};
pub use print::{print_address, print_op, print_program};
pub use stljit_source::{
    Code, Diagnostic, Encoding, Severity, SourceFile, SourceText, Sources, render_human,
    render_json,
};
pub use symbols::{PouRef, SymbolTable};

use classes::Cx;
use stljit_core::{FileId, ProfileId};
use stljit_source::decode_project;

/// What compiling an S7 project produced (with its MicroWIN symbol table).
pub type Compilation = stljit_source::Compilation<SymbolTable>;

/// Compiles a project: every file in `files` (together one program), the optional symbol table,
/// against the CPU `profile`. All diagnostics of all files are reported.
pub fn compile(
    files: &[SourceFile],
    symbols: Option<&SourceFile>,
    profile: ProfileId,
) -> Compilation {
    let (sources, table, mut diags) = decode_project(files, symbols, SymbolTable::parse);
    let profile_data = profile.profile();
    let program = {
        let texts: Vec<(FileId, &str, &str)> = sources.files[..files.len()]
            .iter()
            .enumerate()
            .map(|(i, s)| (FileId::new(i), s.text.as_str(), s.name.as_str()))
            .collect();
        let (pous, data_lines) = structure::structure(&texts, profile_data, &mut diags);
        let encodings: Vec<_> = sources.files.iter().map(|s| s.encoding).collect();
        let data = data_block::lower(&data_lines, profile_data, &encodings, &mut diags);
        let cx = Cx {
            profile: profile_data,
            symbols: table.as_ref(),
            system: system_symbols::table(profile),
            locals: None,
            diags: std::mem::take(&mut diags),
            file: FileId(0),
            line: 0,
            file_names: files.iter().map(|f| f.name.clone()).collect(),
            encodings,
        };
        let names = files.iter().map(|f| f.name.clone()).collect();
        let (mut program, d) = program::lower(&pous, cx, names);
        program.data = data;
        diags = d;
        program
    };
    diags.sort_by_key(|d| (d.file, d.line, d.col));
    let ok = diags.iter().all(|d| d.severity != Severity::Error);
    Compilation {
        program: ok.then_some(program),
        diagnostics: diags,
        sources,
        symbols: table,
    }
}

/// Compiles one UTF-8 text as a single file named `name` (for tests and tools).
pub fn compile_str(name: &str, text: &str, profile: ProfileId) -> Compilation {
    compile(&[SourceFile::from_text(name, text)], None, profile)
}

#[cfg(test)]
mod roundtrip_tests;
