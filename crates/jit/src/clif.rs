//! `stljit dump-clif`: the Cranelift IR of every POU, annotated with the STL source of each op.
//!
//! Lowering sets each instruction's source location to `op index + 1`; this writer prints a
//! comment naming the file, line and op wherever that location changes.

use crate::build::{self, Part};
use crate::midend::Midend;
use crate::{JitError, JitOptions};
use cranelift_codegen::entity::SecondaryMap;
use cranelift_codegen::ir::{Block, Function, Inst, Value};
use cranelift_codegen::isa::TargetIsa;
use cranelift_codegen::write::{FuncWriter, PlainWriter, decorate_function};
use std::fmt::{self, Write};
use stljit_core::ir::{Pou, Program};
use stljit_core::layout::Layout;

struct Annotated<'a> {
    prog: &'a Program,
    pou: &'a Pou,
    last: u32,
    plain: PlainWriter,
}

impl FuncWriter for Annotated<'_> {
    fn write_block_header(
        &mut self,
        w: &mut dyn Write,
        func: &Function,
        block: Block,
        indent: usize,
    ) -> fmt::Result {
        self.plain.write_block_header(w, func, block, indent)
    }

    fn write_instruction(
        &mut self,
        w: &mut dyn Write,
        func: &Function,
        aliases: &SecondaryMap<Value, Vec<Value>>,
        inst: Inst,
        indent: usize,
    ) -> fmt::Result {
        let loc = func.srcloc(inst);
        if !loc.is_default() && loc.bits() != self.last {
            self.last = loc.bits();
            let i = loc.bits() as usize - 1;
            if let (Some(op), Some(src)) = (self.pou.ops.get(i), self.pou.locs.get(i)) {
                let file = self
                    .prog
                    .files
                    .get(src.file.index())
                    .map_or("?", String::as_str);
                writeln!(w, "{:indent$}; {file}:{} op {i}: {op:?}", "", src.line)?;
            } else if let Some(op) = self.pou.ops.get(i) {
                writeln!(w, "{:indent$}; op {i}: {op:?}", "")?;
            }
        }
        self.plain.write_instruction(w, func, aliases, inst, indent)
    }
}

/// The annotated CLIF of every function of `program` as the JIT generates it, before
/// Cranelift's own optimisations.
pub fn clif_text(program: &Program, opts: &JitOptions) -> Result<String, JitError> {
    annotated_clif(program, opts, false)
}

/// The annotated CLIF after the mid-end ([`crate::midend`]: Cranelift's unreachable-code
/// removal, at `--opt speed` its e-graph pass, then the encoding passes: byte loads, bit
/// tests, byte masks, constants near their uses), i.e. what is lowered to machine code.
pub fn optimized_clif_text(program: &Program, opts: &JitOptions) -> Result<String, JitError> {
    annotated_clif(program, opts, true)
}

fn annotated_clif(
    program: &Program,
    opts: &JitOptions,
    optimized: bool,
) -> Result<String, JitError> {
    render(program, opts, |midend, _isa, func, pou, part, out| {
        let Some(p) = program.pous.get(pou) else {
            return Ok(());
        };
        let mut ctx = cranelift_codegen::Context::for_function(func.clone());
        if optimized {
            midend.run(&mut ctx).map_err(|e| e.to_string())?;
        }
        let part = match part {
            Part::Whole => String::new(),
            Part::Dispatch => " dispatcher".to_string(),
            Part::Chunk(k) => format!(" chunk {k}"),
            Part::ScanLoop => {
                let _ = writeln!(out, "; the scan loop (run_scans)");
                decorate_function(&mut PlainWriter, out, &ctx.func).map_err(|e| e.to_string())?;
                out.push('\n');
                return Ok(());
            }
        };
        let _ = writeln!(out, "; POU {pou}: {} ({:?}){part}", p.name, p.kind);
        let mut wr = Annotated {
            prog: program,
            pou: p,
            last: 0,
            plain: PlainWriter,
        };
        decorate_function(&mut wr, out, &ctx.func).map_err(|e| e.to_string())?;
        out.push('\n');
        Ok(())
    })
}

/// The machine code Cranelift generates for every function of `program` at `opts`, as its
/// VCode disassembly (for `stljit dump-clif --asm`: counting host instructions per op).
pub fn asm_text(program: &Program, opts: &JitOptions) -> Result<String, JitError> {
    render(program, opts, |midend, isa, func, pou, part, out| {
        let mut ctx = cranelift_codegen::Context::for_function(func.clone());
        midend.run(&mut ctx).map_err(|e| e.to_string())?;
        ctx.set_disasm(true);
        let mut cp = cranelift_codegen::control::ControlPlane::default();
        let code = ctx
            .compile(isa, &mut cp)
            .map_err(|e| format!("{:?}", e.inner))?;
        let _ = writeln!(out, "; function {pou} {part:?}");
        out.push_str(code.vcode.as_deref().unwrap_or(""));
        Ok(())
    })
}

/// Lowers every function of `program` without compiling it and lets `write` append its text;
/// the first error `write` returns fails the whole dump.
fn render(
    program: &Program,
    opts: &JitOptions,
    mut write: impl FnMut(
        &Midend,
        &dyn TargetIsa,
        &Function,
        usize,
        Part,
        &mut String,
    ) -> Result<(), String>,
) -> Result<String, JitError> {
    let layout = Layout::of(program.profile);
    let module = build::new_module(opts)?;
    let midend = Midend::new(opts)?;
    let isa = cranelift_module::Module::isa(&module);
    let mut out = String::new();
    let mut failure = None;
    let mut sink = |func: &Function, pou: usize, part: Part| {
        if failure.is_none()
            && let Err(e) = write(&midend, isa, func, pou, part, &mut out)
        {
            failure = Some(e);
        }
    };
    // The baked addresses only reach shim calls and the shadow; a dump never runs, so 0 is
    // fine.
    let built = build::build(
        program,
        opts,
        stljit_runtime::rules::Rules::IN_FORCE,
        &layout,
        crate::lower::Baked::default(),
        &crate::resident::Resident::plan(program, &layout),
        false,
        &mut sink,
    )?;
    drop(built);
    match failure {
        Some(e) => Err(JitError::Codegen(e)),
        None => Ok(out),
    }
}
