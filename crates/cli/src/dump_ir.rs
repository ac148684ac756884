//! `stljit dump-ir`: print the checked IR readably, one op per line with its index, its source
//! line and the op in STL spelling, followed by the timer, counter and edge tables.

use std::fmt::Write as _;
use std::process::ExitCode;
use stljit_syntax::{print_op, render_human};

/// Arguments of `stljit dump-ir`.
#[derive(clap::Args)]
pub(crate) struct Args {
    #[command(flatten)]
    input: crate::check::Input,
}

pub(crate) fn main(args: Args) -> anyhow::Result<ExitCode> {
    let c = args.input.compile()?;
    for d in &c.diagnostics {
        eprintln!("{}", render_human(d, &c.sources));
    }
    let Some(program) = &c.program else {
        return Ok(ExitCode::from(1));
    };
    let mut out = String::new();
    let _ = writeln!(
        out,
        "program: cpu {}, {} pou(s), {} op(s), logic stack depth {}",
        program.profile,
        program.pous.len(),
        program.op_count(),
        program.logic_stack_depth
    );
    for (i, pou) in program.pous.iter().enumerate() {
        let _ = writeln!(out, "\npou{i} {} ({:?})", pou.name, pou.kind);
        for (j, (op, loc)) in pou.ops.iter().zip(&pou.locs).enumerate() {
            let file = program
                .files
                .get(loc.file.index())
                .map_or("?", String::as_str);
            let _ = writeln!(
                out,
                "  {j:>5}  {file}:{}:{}  {:<32} {op:?}",
                loc.line,
                loc.col,
                print_op(program, pou, op)
            );
        }
        for (l, at) in pou.labels.iter().enumerate() {
            let _ = writeln!(out, "  label L{l} -> {at}");
        }
    }
    for t in &program.timers {
        let _ = writeln!(
            out,
            "timer {} {} {} ms",
            t.id,
            t.kind.mnemonic(),
            t.resolution.millis()
        );
    }
    for c in &program.counters {
        let _ = writeln!(out, "counter {} {}", c.id, c.kind.mnemonic());
    }
    let _ = writeln!(out, "edges: {}", program.edges.len());
    print!("{out}");
    Ok(ExitCode::SUCCESS)
}
