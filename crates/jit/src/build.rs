//! Module setup: the ISA, the symbol table, one function per POU and the many-scans entry.
//!
//! This file is safe code: it produces a [`JITModule`] with everything defined and the ids of
//! the two entry points; [`crate::engine`] finalizes it and calls into it.

use crate::analysis;
use crate::helpers::{Helper, HelperIds};
use crate::lower::value::Stack;
use crate::lower::{Env, Lower};
use crate::{JitError, JitOptions, OptLevel};
use cranelift_codegen::ir::{
    AbiParam, Function, InstBuilder, MemFlagsData, Signature, UserFuncName,
    condcodes::IntCC,
    types::{I32, I64},
};
use cranelift_codegen::settings::{self, Configurable};
use cranelift_codegen::{Context, isa::CallConv};
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext};
use cranelift_jit::{JITBuilder, JITModule};
use cranelift_module::{FuncId, Linkage, Module, default_libcall_names};
use std::collections::HashMap;
use stljit_core::ir::Program;
use stljit_core::layout::Layout;

fn cg(e: impl std::fmt::Display) -> JitError {
    JitError::Codegen(e.to_string())
}

/// A fresh module for the host with the runtime's symbols registered.
pub(crate) fn new_module(opts: &JitOptions) -> Result<JITModule, JitError> {
    let mut flags = settings::builder();
    let opt = match opts.opt {
        OptLevel::None => "none",
        OptLevel::Speed => "speed",
    };
    flags.set("opt_level", opt).map_err(cg)?;
    // `none` means fastest compile: the single-pass allocator is several times cheaper than
    // the backtracking one, which dominates compile time on long straight-line PLC code.
    let regalloc = match opts.opt {
        OptLevel::None => "single_pass",
        OptLevel::Speed => "backtracking",
    };
    flags.set("regalloc_algorithm", regalloc).map_err(cg)?;
    // The verifier costs compile time; our own differential tests check the code instead.
    let verify = if cfg!(debug_assertions) {
        "true"
    } else {
        "false"
    };
    flags.set("enable_verifier", verify).map_err(cg)?;
    flags.set("use_colocated_libcalls", "false").map_err(cg)?;
    flags.set("is_pic", "false").map_err(cg)?;
    let isa = cranelift_native::builder()
        .map_err(|m| JitError::UnsupportedHost(m.to_string()))?
        .finish(settings::Flags::new(flags))
        .map_err(cg)?;
    let mut jb = JITBuilder::with_isa(isa, default_libcall_names());
    for h in Helper::ALL {
        jb.symbol(h.name(), h.address());
    }
    Ok(JITModule::new(jb))
}

/// The signature of every POU function: `(image: i64, depth: i32) -> i32`.
pub(crate) fn pou_signature(cc: CallConv) -> Signature {
    let mut s = Signature::new(cc);
    s.params.push(AbiParam::new(I64));
    s.params.push(AbiParam::new(I32));
    s.returns.push(AbiParam::new(I32));
    s
}

/// The signature of the many-scans entry: `(image, t0, dt, n, done_out) -> status`.
pub(crate) fn run_signature(cc: CallConv) -> Signature {
    let mut s = Signature::new(cc);
    for _ in 0..5 {
        s.params.push(AbiParam::new(I64));
    }
    s.returns.push(AbiParam::new(I32));
    s
}

/// Checks the properties lowering relies on.
pub(crate) fn validate(prog: &Program) -> Result<(), JitError> {
    if prog.pous.is_empty() {
        return Err(JitError::Malformed("no main POU".into()));
    }
    if !(1..=16).contains(&prog.logic_stack_depth) {
        return Err(JitError::Malformed(format!(
            "logic stack depth {} not in 1..=16",
            prog.logic_stack_depth
        )));
    }
    for p in &prog.pous {
        if p.ops.len() >= u32::MAX as usize / 2 {
            return Err(JitError::Malformed("POU too long".into()));
        }
    }
    analysis::check_targets(prog).map_err(JitError::Malformed)
}

/// What [`build`] produced.
pub(crate) struct Built {
    pub(crate) module: JITModule,
    pub(crate) run_id: FuncId,
}

/// Declares and defines every function. `dump` receives each function's CLIF before it is
/// compiled; with `define = false` nothing is compiled (for `dump-clif`).
pub(crate) fn build(
    prog: &Program,
    opts: &JitOptions,
    layout: &Layout,
    layout_ptr: i64,
    op_counter: Option<i64>,
    define: bool,
    dump: &mut dyn FnMut(&Function, usize),
) -> Result<Built, JitError> {
    validate(prog)?;
    let mut module = new_module(opts)?;
    let cc = module.isa().default_call_conv();
    let helpers = HelperIds::declare(&mut module).map_err(cg)?;
    let mut pou_funcs = Vec::with_capacity(prog.pous.len());
    for i in 0..prog.pous.len() {
        let id = module
            .declare_function(&format!("pou{i}"), Linkage::Local, &pou_signature(cc))
            .map_err(cg)?;
        pou_funcs.push(id);
    }
    let run_id = module
        .declare_function("run_scans", Linkage::Local, &run_signature(cc))
        .map_err(cg)?;
    let env = Env {
        prog,
        layout,
        layout_ptr,
        pou_funcs: pou_funcs.clone(),
        helpers: &helpers,
        info: analysis::analyse(prog),
        op_counter,
    };
    let mut ctx = module.make_context();
    let mut fbc = FunctionBuilderContext::new();
    for (i, &id) in pou_funcs.iter().enumerate() {
        ctx.func =
            Function::with_name_signature(UserFuncName::user(0, i as u32), pou_signature(cc));
        lower_one(&env, &mut module, &mut ctx, &mut fbc, i)?;
        dump(&ctx.func, i);
        if define {
            module
                .define_function(id, &mut ctx)
                .map_err(|e| cg(format!("{e:?}")))?;
        }
        module.clear_context(&mut ctx);
    }
    ctx.func = Function::with_name_signature(UserFuncName::user(0, u32::MAX), run_signature(cc));
    build_run(&env, &mut module, &mut ctx, &mut fbc, pou_funcs[0]);
    if define {
        module
            .define_function(run_id, &mut ctx)
            .map_err(|e| cg(format!("{e:?}")))?;
    }
    module.clear_context(&mut ctx);
    Ok(Built { module, run_id })
}

fn lower_one(
    env: &Env<'_>,
    module: &mut JITModule,
    ctx: &mut Context,
    fbc: &mut FunctionBuilderContext,
    pou: usize,
) -> Result<(), JitError> {
    let mut b = FunctionBuilder::new(&mut ctx.func, fbc);
    let entry = b.create_block();
    b.append_block_params_for_function_params(entry);
    b.switch_to_block(entry);
    b.seal_block(entry);
    let image = b.block_params(entry)[0];
    let depth = b.block_params(entry)[1];
    let st = b.declare_var(I32);
    let lsize = i64::from(env.layout.area_size(stljit_core::Area::L));
    let lbase = if pou == 0 {
        b.ins()
            .iadd_imm_s(image, i64::from(env.layout.base(stljit_core::Area::L)))
    } else {
        let d64 = b.ins().uextend(I64, depth);
        let off = b.ins().imul_imm_s(d64, lsize);
        let off = b
            .ins()
            .iadd_imm_s(off, i64::from(env.layout.base(stljit_core::Area::L)));
        b.ins().iadd(image, off)
    };
    // Main starts each scan with an all-zero stack; a subroutine with S0 = 1 (spec §3.2 CALL).
    let depth_n = env.prog.logic_stack_depth;
    let stack = if pou == 0 {
        Stack {
            lv: vec![crate::lower::value::B::K(false); usize::from(depth_n)],
        }
    } else {
        Stack::fresh(depth_n)
    };
    let mut l = Lower {
        env,
        module,
        b,
        pou: stljit_core::PouId(pou as u32),
        image,
        lbase,
        depth,
        st,
        stack,
        entry_st: None,
        gate: crate::lower::value::B::K(true),
        cache: Default::default(),
        leaders: HashMap::new(),
        fnrefs: HashMap::new(),
        pou_refs: HashMap::new(),
        op: 0,
        live: true,
        unsupported: None,
        pred: None,
        pred_reads: Vec::new(),
        free_box: false,
    };
    l.lower_pou();
    let unsupported = l.unsupported.take();
    l.b.seal_all_blocks();
    let fc = l.module.isa().frontend_config();
    l.b.finalize(fc);
    match unsupported {
        Some(what) => Err(JitError::Unsupported(what)),
        None => Ok(()),
    }
}

/// The many-scans loop: `for i in 0..n { begin; main; end }`, stopping at the first scan whose
/// status is not Ok; writes the number of scans run to `done_out`.
fn build_run(
    env: &Env<'_>,
    module: &mut JITModule,
    ctx: &mut Context,
    fbc: &mut FunctionBuilderContext,
    main: FuncId,
) {
    let mut b = FunctionBuilder::new(&mut ctx.func, fbc);
    let entry = b.create_block();
    b.append_block_params_for_function_params(entry);
    b.switch_to_block(entry);
    let p = b.block_params(entry).to_vec();
    let (image, t0, dt, n, done) = (p[0], p[1], p[2], p[3], p[4]);
    let begin = module.declare_func_in_func(env.helpers.id(Helper::ScanBegin), b.func);
    let end = module.declare_func_in_func(env.helpers.id(Helper::ScanEnd), b.func);
    let mainf = module.declare_func_in_func(main, b.func);
    let layout = b.ins().iconst(I64, env.layout_ptr);
    let head = b.create_block();
    let i = b.append_block_param(head, I64);
    let body = b.create_block();
    let fin = b.create_block();
    let (fin_i, fin_st) = (
        b.append_block_param(fin, I64),
        b.append_block_param(fin, I32),
    );
    let zero64 = b.ins().iconst(I64, 0);
    b.ins().jump(head, &[zero64.into()]);

    b.switch_to_block(head);
    let more = b.ins().icmp(IntCC::UnsignedLessThan, i, n);
    let ok = b.ins().iconst(I32, 0);
    b.ins().brif(more, body, &[], fin, &[i.into(), ok.into()]);

    b.switch_to_block(body);
    let it = b.ins().imul(i, dt);
    let t = b.ins().iadd(t0, it);
    let i1 = b.ins().iadd_imm_s(i, 1);
    let c = b.ins().call(begin, &[image, layout, t]);
    let runs = b.inst_results(c)[0];
    let run = b.create_block();
    let stopped = b.ins().iconst(I32, 1);
    b.ins()
        .brif(runs, run, &[], fin, &[i1.into(), stopped.into()]);

    b.switch_to_block(run);
    let zero32 = b.ins().iconst(I32, 0);
    let c = b.ins().call(mainf, &[image, zero32]);
    let s = b.inst_results(c)[0];
    let c = b.ins().call(end, &[image, layout, s]);
    let st = b.inst_results(c)[0];
    b.ins()
        .brif(st, fin, &[i1.into(), st.into()], head, &[i1.into()]);

    b.switch_to_block(fin);
    b.ins()
        .store(MemFlagsData::new().with_notrap(), fin_i, done, 0);
    b.ins().return_(&[fin_st]);
    b.seal_all_blocks();
    let fc = module.isa().frontend_config();
    b.finalize(fc);
}
