//! The Omron CP-series mnemonic (instruction-list) front end of stljit (omron-cp.md).
//!
//! [`compile`] (or [`compile_with`] and the [`Options`] `tc_mode` and `allow_backward_jumps`)
//! takes the files of one project (UTF-8 or GBK, concatenated; `$TASK` directives
//! split it into task programs, docs/omron.md "Tasks"), an optional CX-Programmer symbol table
//! and an Omron profile (`cp1h`, `cp1e`), and returns the checked
//! [`stljit_core::ir::Program`] with every diagnostic (codes `OMR-E…`/`OMR-W…`, §5). It never
//! panics and never stops at the first error. [`parse_address`]/[`print_address`] read and
//! write single addresses in Omron spelling; [`looks_like_omron`]/[`looks_like_s7`] guess a
//! text's dialect. [`print_program`] prints a compiled program back as Omron text that
//! compiles to the same IR (it reads the patterns below in reverse), and [`mnemonics::TABLE`]
//! is the one list of the supported instructions, which the fuzzer's generator and coverage
//! read too.
//!
//! Pipeline: `lexer` (one instruction per line) → `lower` (dispatch over `mnemonics::TABLE`,
//! the circuit machine of `circuit`, operands through `operand`/`resolve`, timers and data in
//! `boxes`, regions and jumps in `control`, program units in `tasks`) → IR.
//!
//! # Lowering (the lead's decisions)
//!
//! The program has the chosen Omron profile and `logic_stack_depth = 16`. Every LD-type
//! instruction is an IR push (`Op::Load`), whether it starts a circuit or a block; AND LD / OR
//! LD are `AndBlock` / `OrBlock`; outputs never pop, so the execution condition continues after
//! them. More than 8 pending blocks is OMR-W040, more than 13 OMR-E041: every push below adds
//! at most two temporaries, so 16 levels always hold the live values.
//!
//! * `LD/AND/OR b` (and `NOT` forms): `Load/And/Or(Contact::Bit)`.
//!   `@LD b`: `Load(b); Edge{rising}`; `%LD b`: `Load(b); Edge{falling}`; `@AND b`:
//!   `Load(b); Edge; AndBlock`; `@OR b`: `Load(b); Edge; OrBlock`. Every edge has its own slot,
//!   `init` true for rising, false for falling (§2.6).
//! * `NOT(520)`: `Not`; `UP(521)`/`DOWN(522)`: `Edge` (init true / false).
//! * `OUT b`: `Assign`; `OUT NOT b`: `Not; Assign; Not`; `OUT TRn` / `LD TRn`: the TR bit
//!   (`core::omron::tr_bit`), checked per circuit (E010).
//! * `SET`/`RSET b`: `SetRange{count: 1}`. Every `@`/`%` output (SET, RSET, MOV, CMP,
//!   arithmetic, SBS): `Dup; Edge; <op>; Pop`.
//! * `KEEP(011) b` (S1 set, S0 reset): `SetRange(b, 0); Not; AndBlock; SetRange(b, 1)`
//!   (reset wins). `DIFU(013)`/`DIFD(014)`: `Dup; Edge; SetRange(b, 1); Not; SetRange(b, 0);
//!   Pop`.
//! * `IL(002)`/`ILC(003)`: `Interlock`/`InterlockEnd`. `JMP(004)`/`CJPN(511)`: `Not; Jump;
//!   Not`; `CJP(510)`: `Jump`; `JME(005)`: `Label`; `JMP0(515)`: like JMP to a fresh label
//!   placed at the next `JME0(516)`. Jumps go forward only (backward with
//!   `allow_backward_jumps`), within one POU, one IL region and one block program.
//! * `END(001)`: `End`; lines after it are W002 and not lowered. `SBN(092) n … RET(093)`: a
//!   `PouKind::Subroutine(n)` ending in `Return`; `SBS(091) n`: `Call`. The main POU ends at
//!   the first SBN or END (its `End` op is emitted at the END line).
//! * `FOR(503) N`: `Load(P_On); For{index: L word 2·depth, init: 1, limit: N}`; `NEXT(504)`:
//!   `Next` and a label after it, which `BREAK(514)` (`Jump`) reaches: the rest of the pass
//!   is skipped and the loop ends. The counter is a private word of the call level's L frame
//!   (no Omron operand names it); `N` is compared as the IR's FOR does (signed: a count above
//!   32767 runs the loop zero times) and every pass counts against the scan's loop budget.
//!   E026: nesting beyond the profile's depth, an unclosed FOR, a JME inside a loop whose jump
//!   is outside; E027: NEXT/BREAK outside a loop.
//! * `MOVR(560) S IRn`: `Omron(SetIndex{ea})` with `S`'s effective address
//!   (`core::omron::effective_address`; a bit's is `16 · word + bit`). Indirect operands
//!   `@Dn`, `*Dn`, `c,IRn`, `DRm,IRn`, `,IRn+`, `,IRn++`, `,-IRn`, `,--IRn` are
//!   `Operand::Omron` in MOV/CMP/arithmetic, resolved at run time (`DRn` is a word anywhere).
//! * Timers: `OmronTimer`, counters: `OmronCounter` (with `tc_mode = binary` the plain BCD
//!   kinds become their `X` kinds); numbers `0000`, `T0000` or `&0`, each
//!   used once per area (E021); BCD set-value constants are checked (E015).
//! * `MOV`/`MOVL`: `Omron(Move)`; `CMP`/`CMPL`/`CPS`/`CPSL`: `Omron(Compare)`; §3.6:
//!   `Omron(Arith)`. Comparison contacts (`LD>=S D0 -5`): `Load(P_On); Omron(Compare); Pop;`
//!   then `Load/And/Or` of the relation's flag (U2's default).
//! * Operands: words and bits through `core::omron::word_loc`/`bit_of_word`; `T`/`C` bits are
//!   `TimerBit`/`CounterBit` byte `n`, their words `TimerValue`/`CounterValue` offset `2n`;
//!   `P_…` flags are `SystemBit`s, `P_First_Cycle` is A200.11; constants are `Operand::Const`
//!   in Omron value order (a double constant's low 16 bits are the low word).
//!
//! * Tasks: each `$TASK CYCLIC n` program is lowered like a program of its own; the main POU
//!   is the started cyclic tasks in ascending number, every task's body with its op indices
//!   and labels moved behind the previous one, `TaskStart` before every task but the first,
//!   and only the last task's `End` kept (the others fall through into the next task). Only
//!   the running tasks' subroutines are POUs. Standby tasks, `$TASK UNASSIGNED` programs and
//!   `$FB` bodies are checked and dropped.
//! * `STEP(008) B`: `InterlockEnd; Load(B); Interlock; Pop` (the gate is B: the step runs
//!   while B is ON and is interlocked while it is OFF); inside IL–ILC the first STEP saves the
//!   interlock's gate in a front-end bit (`Load(P_On); Assign(L bit); Pop`, the L byte after
//!   the FOR counters) and every STEP ANDs it in. `STEP(008)`: `InterlockEnd`, and inside
//!   IL–ILC `Load(L bit); Interlock; Pop`. `SNXT(009) B`: `SetRange(current step, 0);
//!   SetRange(B, 1)`. `BPRG(096) N`: `Not; Jump; Not` to a label at `BEND(801)`.
//! * `CCS(282)`/`CCL(283)`: `Omron(Flags{save})`; `IORF(097) St E`: its operands checked, no
//!   op (the model has only the built-in I/O, on which IORF has no effect).
//!
//! **Not supported yet** (OMR-E011 "not supported yet"): the block-program-only instructions
//! (IF/ELSE/IEND, WAIT, TIMW, CNTW, BPPS/BPRS …), interrupt tasks, indirect operands outside
//! MOV/CMP/arithmetic (contacts, coils, timer set values), TK operands, strings.
//!
//! * `!` (immediate refresh of the whole 16-bit word, §2.5/§4): a source operand in a built-in
//!   input word first has the whole word copied from the physical inputs (two
//!   `Box(ImmediateRead)`, one per byte), a destination in a built-in output word afterwards
//!   has the whole image word copied to the physical outputs (two `Box(ImmediateWrite)`).
//!   Contacts, OUT, OUT NOT and KEEP refresh in every cycle (the boxes on a pushed `P_On`),
//!   SET, RSET and the data instructions when they execute (on their power flow, inside the
//!   `@`/`%` pattern). Other operands are not refreshed (no effect, as on expansion I/O).

mod address;
mod boxes;
mod capacity;
mod circuit;
mod contacts;
mod control;
mod detect;
mod discipline;
pub mod forms;
mod immediate;
mod lexer;
mod lower;
pub mod mnemonics;
mod operand;
mod options;
mod print;
mod regions;
mod resolve;
mod symbols;
mod tasks;

pub use address::{AddressError, parse_address, print_address};
pub use detect::{looks_like_omron, looks_like_s7};
pub use options::{Options, TcMode};
pub use print::{PrintError, print_program, printed_options};
pub use stljit_source::{
    Code, Diagnostic, Encoding, Severity, SourceFile, SourceText, Sources, render_human,
    render_json,
};
pub use symbols::SymbolTable;

use stljit_core::ir::Program;
use stljit_core::{FileId, ProfileId};
use stljit_source::{Span, decode_project};

/// What compiling an Omron project produced (with its CX-Programmer symbol table).
pub type Compilation = stljit_source::Compilation<SymbolTable>;

/// Depth of the IR logic stack of an Omron program (see the crate doc).
pub const LOGIC_STACK_DEPTH: u8 = 16;

/// Compiles a project: every file in `files` (in order, concatenated; its `$TASK` directives
/// split it into tasks), the optional symbol table, against the Omron `profile`, with the
/// default [`Options`]. All diagnostics of all files are reported.
pub fn compile(
    files: &[SourceFile],
    symbols: Option<&SourceFile>,
    profile: ProfileId,
) -> Compilation {
    compile_with(files, symbols, profile, Options::default())
}

/// [`compile`] with the front end's `options`.
pub fn compile_with(
    files: &[SourceFile],
    symbols: Option<&SourceFile>,
    profile: ProfileId,
    options: Options,
) -> Compilation {
    let (sources, table, diags) = decode_project(files, symbols, SymbolTable::parse);
    let cx = resolve::Cx {
        profile: profile.profile(),
        symbols: table.as_ref(),
        diags,
        file: FileId(0),
        line: 0,
        mn: String::new(),
        options,
    };
    let names = files.iter().map(|f| f.name.clone()).collect();
    let mut lw = lower::Lowerer::new(cx, names);
    let mut last = Span {
        file: FileId(0),
        line: 1,
        col: 1,
        len: 1,
    };
    for (i, src) in sources.files[..files.len()].iter().enumerate() {
        let file = FileId::new(i);
        lw.cx.file = file;
        for (n, raw) in src.text.split('\n').enumerate() {
            let number = u32::try_from(n + 1).unwrap_or(u32::MAX);
            last = Span {
                file,
                line: number,
                col: 1,
                len: 1,
            };
            if let Some(line) = lexer::lex_line(raw, number) {
                lw.cx.line = number;
                lw.loc = stljit_core::ir::SrcLoc {
                    file,
                    line: number,
                    col: line.head.col,
                };
                lw.line(&line);
            }
        }
    }
    lw.finish(last);
    let mut diags = std::mem::take(&mut lw.cx.diags);
    diags.sort_by_key(|d| (d.file, d.line, d.col));
    let ok = diags.iter().all(|d| d.severity != Severity::Error);
    let edges = std::mem::take(&mut lw.edges);
    let program = ok.then(|| Program {
        profile,
        pous: lw.assemble(),
        timers: Vec::new(),
        counters: Vec::new(),
        edges,
        logic_stack_depth: LOGIC_STACK_DEPTH,
        files: files.iter().map(|f| f.name.clone()).collect(),
        data: Vec::new(),
    });
    Compilation {
        program,
        diagnostics: diags,
        sources,
        symbols: table,
    }
}

/// Compiles one UTF-8 text as a single file named `name` (for tests and tools).
pub fn compile_str(name: &str, text: &str, profile: ProfileId) -> Compilation {
    compile(&[SourceFile::from_text(name, text)], None, profile)
}
