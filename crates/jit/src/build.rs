//! Module setup: the ISA, the symbol table, one function per POU and the many-scans entry.
//!
//! This file is safe code: it produces a [`JITModule`] with everything defined and the ids of
//! the two entry points; [`crate::engine`] finalizes it and calls into it.

use crate::analysis::{self, ChunkPlan};
use crate::helpers::HelperIds;
use crate::lower::cache::StoreLog;
use crate::lower::state::{BlockState, FnState};
use crate::lower::value::Stack;
use crate::lower::{Baked, Env, Lower};
use crate::resident::Resident;
use crate::{JitError, JitOptions, OptLevel};
use cranelift_codegen::ir::{
    AbiParam, Function, InstBuilder, Signature, UserFuncName, Value,
    condcodes::IntCC,
    types::{I32, I64},
};
use cranelift_codegen::settings::{self, Configurable};
use cranelift_codegen::{
    Context,
    isa::{CallConv, OwnedTargetIsa},
};
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext};
use cranelift_jit::{JITBuilder, JITModule};
use cranelift_module::{FuncId, Linkage, Module, default_libcall_names};
use std::collections::HashMap;
use stljit_core::ir::{PouKind, Program};
use stljit_core::layout::{ISR_FRAME, Layout};
use stljit_runtime::rules::Rules;

fn cg(e: impl std::fmt::Display) -> JitError {
    JitError::Codegen(e.to_string())
}

/// A fresh module for the host with the runtime's symbols registered. Its ISA is at
/// `opt_level = none` whatever `opts` says: [`crate::midend::Midend`] runs the optimisations.
pub(crate) fn new_module(opts: &JitOptions) -> Result<JITModule, JitError> {
    let isa = host_isa(opts, "none")?;
    let mut jb = JITBuilder::with_isa(isa, default_libcall_names());
    crate::helpers::register_symbols(&mut jb);
    Ok(JITModule::new(jb))
}

/// The host ISA with the flags every compilation uses, at Cranelift's `opt_level` `opt`.
pub(crate) fn host_isa(opts: &JitOptions, opt: &str) -> Result<OwnedTargetIsa, JitError> {
    let mut flags = settings::builder();
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
    cranelift_native::builder()
        .map_err(|m| JitError::UnsupportedHost(m.to_string()))?
        .finish(settings::Flags::new(flags))
        .map_err(cg)
}

/// The signature of every POU function: `(image: i64, depth: i32) -> i32`.
pub(crate) fn pou_signature(cc: CallConv) -> Signature {
    let mut s = Signature::new(cc);
    s.params.push(AbiParam::new(I64));
    s.params.push(AbiParam::new(I32));
    s.returns.push(AbiParam::new(I32));
    s
}

/// The signature of a chunk function: `(image: i64, depth: i32, stack: i32, at: i32) -> i64`
/// (see [`crate::lower::Lower::lower_chunk`]).
pub(crate) fn chunk_signature(cc: CallConv) -> Signature {
    let mut s = pou_signature(cc);
    s.params.push(AbiParam::new(I32));
    s.params.push(AbiParam::new(I32));
    s.returns[0] = AbiParam::new(I64);
    s
}

/// The signature of the many-scans entry: `(image, t0, dt, n, done_out, watch) -> status`
/// (`watch` a `ChangeWatch` or null: `scan_loop`).
pub(crate) fn run_signature(cc: CallConv) -> Signature {
    let mut s = Signature::new(cc);
    for _ in 0..6 {
        s.params.push(AbiParam::new(I64));
    }
    s.returns.push(AbiParam::new(I32));
    s
}

/// Checks the properties lowering relies on: the IR verifier's rules.
pub(crate) fn validate(prog: &Program) -> Result<(), JitError> {
    stljit_core::ir::verify(prog).map_err(JitError::Malformed)
}

/// What [`build`] produced.
pub(crate) struct Built {
    pub(crate) module: JITModule,
    pub(crate) run_id: FuncId,
    /// The function of each POU (index = POU), for the interrupt routines' table.
    pub(crate) pou_ids: Vec<FuncId>,
    /// The payloads whose addresses the code holds; they must live as long as it.
    pub(crate) ext: crate::lower::ext::ExtKeep,
}

/// Which function of a POU [`build`] hands to its `dump` callback.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Part {
    /// The POU's only function (the main program's is inlined into the scan loop instead of
    /// being compiled on its own).
    Whole,
    /// The dispatcher of a split POU (the function its callers call).
    Dispatch,
    /// Chunk `k` of a split POU.
    Chunk(usize),
    /// The native many-scans loop (`run_scans`, `crate::scan_loop`); its POU index is unused.
    ScanLoop,
}

/// Declares and defines every function. `dump` receives each function's CLIF before it is
/// compiled; with `define = false` nothing is compiled (for `dump-clif`).
#[allow(clippy::too_many_arguments)]
pub(crate) fn build(
    prog: &Program,
    opts: &JitOptions,
    rules: Rules,
    layout: &Layout,
    baked: Baked,
    resident: &Resident,
    define: bool,
    dump: &mut dyn FnMut(&Function, usize, Part),
) -> Result<Built, JitError> {
    validate(prog)?;
    let mut module = new_module(opts)?;
    let cc = module.isa().default_call_conv();
    let helpers = HelperIds::declare(&mut module).map_err(cg)?;
    let info = analysis::analyse(prog, resident);
    let plans: Vec<_> = prog
        .pous
        .iter()
        .zip(&info)
        .map(|(p, i)| analysis::plan_chunks(p, &i.leader, opts.chunk_ops))
        .collect();
    let mut pou_funcs = Vec::with_capacity(prog.pous.len());
    let mut chunk_funcs = Vec::with_capacity(prog.pous.len());
    for (i, plan) in plans.iter().enumerate() {
        let id = module
            .declare_function(&format!("pou{i}"), Linkage::Local, &pou_signature(cc))
            .map_err(cg)?;
        pou_funcs.push(id);
        let chunks = plan.as_ref().map_or(0, |p| p.starts.len());
        let ids = (0..chunks)
            .map(|k| {
                module
                    .declare_function(
                        &format!("pou{i}_chunk{k}"),
                        Linkage::Local,
                        &chunk_signature(cc),
                    )
                    .map_err(cg)
            })
            .collect::<Result<Vec<_>, _>>()?;
        chunk_funcs.push(ids);
    }
    let run_id = module
        .declare_function("run_scans", Linkage::Local, &run_signature(cc))
        .map_err(cg)?;
    let ext = crate::lower::ext::ExtKeep::of(prog);
    let env = Env {
        prog,
        layout,
        baked,
        pou_funcs: pou_funcs.clone(),
        helpers: &helpers,
        info,
        plans,
        hot_ops: opts.hot_ops,
        opt: opts.opt,
        timer_res: stljit_runtime::timer::declared_resolutions(prog),
        rules,
        ext: &ext,
        resident,
    };
    let mut ctx = module.make_context();
    let mut fbc = FunctionBuilderContext::new();
    let midend = crate::midend::Midend::new(opts)?;
    let define_fn = |module: &mut JITModule, ctx: &mut Context, id| -> Result<(), JitError> {
        if define {
            midend.run(ctx)?;
            module
                .define_function(id, ctx)
                .map_err(|e| cg(format!("{e:?}")))?;
        }
        module.clear_context(ctx);
        Ok(())
    };
    let mut main_body = None;
    for (i, &id) in pou_funcs.iter().enumerate() {
        let name = UserFuncName::user(0, i as u32);
        match &env.plans[i] {
            None => {
                ctx.func = Function::with_name_signature(name, pou_signature(cc));
                lower_fn(&env, &mut module, &mut ctx, &mut fbc, i, None)?;
                dump(&ctx.func, i, Part::Whole);
                if i == 0 {
                    // The scan loop is the main program's only caller: it gets the body to
                    // inline, and the function itself is never compiled.
                    main_body = Some(ctx.func.clone());
                    module.clear_context(&mut ctx);
                } else {
                    define_fn(&mut module, &mut ctx, id)?;
                }
            }
            Some(plan) => {
                for (k, &cid) in chunk_funcs[i].iter().enumerate() {
                    let name = UserFuncName::user(1 + k as u32, i as u32);
                    ctx.func = Function::with_name_signature(name, chunk_signature(cc));
                    lower_fn(&env, &mut module, &mut ctx, &mut fbc, i, Some(k))?;
                    dump(&ctx.func, i, Part::Chunk(k));
                    define_fn(&mut module, &mut ctx, cid)?;
                }
                ctx.func = Function::with_name_signature(name, pou_signature(cc));
                build_dispatch(
                    &env,
                    &mut module,
                    &mut ctx,
                    &mut fbc,
                    i,
                    plan,
                    &chunk_funcs[i],
                );
                dump(&ctx.func, i, Part::Dispatch);
                define_fn(&mut module, &mut ctx, id)?;
            }
        }
    }
    ctx.func = Function::with_name_signature(UserFuncName::user(0, u32::MAX), run_signature(cc));
    let scan_plan = stljit_runtime::scan::ScanPlan::of(prog);
    crate::scan_loop::build_run(
        &env,
        &scan_plan,
        &mut module,
        &mut ctx,
        &mut fbc,
        pou_funcs[0],
        main_body.as_ref(),
    )?;
    dump(&ctx.func, 0, Part::ScanLoop);
    define_fn(&mut module, &mut ctx, run_id)?;
    drop(env);
    Ok(Built {
        module,
        run_id,
        pou_ids: pou_funcs,
        ext,
    })
}

/// Lowers POU `pou` (or its chunk `chunk`) into `ctx.func`.
fn lower_fn(
    env: &Env<'_>,
    module: &mut JITModule,
    ctx: &mut Context,
    fbc: &mut FunctionBuilderContext,
    pou: usize,
    chunk: Option<usize>,
) -> Result<(), JitError> {
    let mut b = FunctionBuilder::new(&mut ctx.func, fbc);
    let entry = b.create_block();
    b.append_block_params_for_function_params(entry);
    b.switch_to_block(entry);
    b.seal_block(entry);
    let params = b.block_params(entry).to_vec();
    let (image, depth) = (params[0], params[1]);
    let st = b.declare_var(I32);
    let lbase = frame_base(env, &mut b, pou, image, depth);
    let func = FnState {
        pou: stljit_core::PouId(pou as u32),
        chunk,
        image,
        lbase,
        call_depth: depth,
        st,
        leaders: HashMap::new(),
        fnrefs: HashMap::new(),
        pou_refs: HashMap::new(),
        stores: StoreLog::new(
            env.layout.size.max(env.resident.end()),
            env.layout.area_size(stljit_core::Area::L),
            env.hot_ops,
        ),
        unsupported: None,
    };
    let mut l = Lower {
        env,
        module,
        b,
        func,
        block: BlockState::function_entry(initial_stack(env, pou)),
        in_box: Default::default(),
        op: 0,
    };
    match chunk {
        None => l.lower_pou(),
        Some(k) => l.lower_chunk(k, params[2], params[3]),
    }
    let unsupported = l.func.unsupported.take();
    l.b.seal_all_blocks();
    let fc = l.module.isa().frontend_config();
    l.b.finalize(fc);
    crate::lower::value::settle_alignments(&mut ctx.func);
    crate::dse::remove_dead_stores(&mut ctx.func);
    match unsupported {
        Some(what) => Err(JitError::Unsupported(what)),
        None => Ok(()),
    }
}

/// The first byte of the POU's L frame: main's (frame 0) and an interrupt routine's
/// ([`ISR_FRAME`]) are fixed, a subroutine's follows from `depth`.
fn frame_base(
    env: &Env<'_>,
    b: &mut FunctionBuilder<'_>,
    pou: usize,
    image: Value,
    depth: Value,
) -> Value {
    let lsize = i64::from(env.layout.area_size(stljit_core::Area::L));
    let lbase = i64::from(env.layout.base(stljit_core::Area::L));
    match env.prog.pous[pou].kind {
        PouKind::Main => b.ins().iadd_imm_s(image, lbase),
        PouKind::Interrupt(_) => b
            .ins()
            .iadd_imm_s(image, lbase + i64::from(ISR_FRAME) * lsize),
        PouKind::Subroutine(_) => {
            let d64 = b.ins().uextend(I64, depth);
            let off = b.ins().imul_imm_s(d64, lsize);
            let off = b.ins().iadd_imm_s(off, lbase);
            b.ins().iadd(image, off)
        }
    }
}

/// The logic stack a POU starts with: all zero for the main program and an interrupt routine
/// (spec §3.1, s7-200-more §3.6.4), `S0 = 1` for a subroutine (spec §3.2 CALL).
fn initial_stack(env: &Env<'_>, pou: usize) -> Stack {
    let depth_n = env.prog.logic_stack_depth;
    match env.prog.pous[pou].kind {
        PouKind::Main | PouKind::Interrupt(_) => Stack {
            lv: vec![crate::lower::value::B::K(false); usize::from(depth_n)],
        },
        PouKind::Subroutine(_) => Stack::fresh(depth_n),
    }
}

/// The function callers of a split POU call: runs its chunks, starting with the first, until
/// one returns "POU done" (upper half 0), and passes the stack register between them.
/// Falling into the next chunk is a direct call; any other transfer goes through a chain of
/// range compares over the chunk starts.
fn build_dispatch(
    env: &Env<'_>,
    module: &mut JITModule,
    ctx: &mut Context,
    fbc: &mut FunctionBuilderContext,
    pou: usize,
    plan: &ChunkPlan,
    chunks: &[FuncId],
) {
    let mut b = FunctionBuilder::new(&mut ctx.func, fbc);
    let entry = b.create_block();
    b.append_block_params_for_function_params(entry);
    b.switch_to_block(entry);
    let (image, depth) = (b.block_params(entry)[0], b.block_params(entry)[1]);
    let with_params = |b: &mut FunctionBuilder<'_>| {
        let blk = b.create_block();
        let st = b.append_block_param(blk, I32);
        let at = b.append_block_param(blk, I32);
        (blk, st, at)
    };
    let calls: Vec<_> = chunks.iter().map(|_| with_params(&mut b)).collect();
    let routes: Vec<_> = chunks.iter().map(|_| with_params(&mut b)).collect();
    let st0 = initial_stack(env, pou).to_reg(&mut b);
    let at0 = b.ins().iconst(I32, 0);
    b.ins().jump(calls[0].0, &[st0.into(), at0.into()]);

    // routes[k]: the op is in chunk k or later.
    for k in 0..chunks.len() {
        let (blk, st, at) = routes[k];
        b.switch_to_block(blk);
        match (plan.starts.get(k + 1), routes.get(k + 1)) {
            (Some(&next_start), Some(&(next, ..))) => {
                let here = b
                    .ins()
                    .icmp_imm_s(IntCC::UnsignedLessThan, at, next_start as i64);
                let args = [st.into(), at.into()];
                b.ins().brif(here, calls[k].0, &args, next, &args);
            }
            _ => {
                b.ins().jump(calls[k].0, &[st.into(), at.into()]);
            }
        }
    }
    for (k, &id) in chunks.iter().enumerate() {
        let (blk, st, at) = calls[k];
        b.switch_to_block(blk);
        let f = module.declare_func_in_func(id, b.func);
        let c = b.ins().call(f, &[image, depth, st, at]);
        let r = b.inst_results(c)[0];
        let hi = b.ins().ushr_imm_u(r, 32);
        let hi = b.ins().ireduce(I32, hi);
        let lo = b.ins().ireduce(I32, r);
        let done = b.create_block();
        let transfer = b.create_block();
        b.ins().brif(hi, transfer, &[], done, &[]);
        b.switch_to_block(done);
        b.ins().return_(&[lo]);
        b.switch_to_block(transfer);
        let target = b.ins().iadd_imm_s(hi, -1);
        let args = [lo.into(), target.into()];
        match (plan.starts.get(k + 1), calls.get(k + 1)) {
            (Some(&next_start), Some(&(next, ..))) => {
                let fall = b.ins().icmp_imm_s(IntCC::Equal, target, next_start as i64);
                b.ins().brif(fall, next, &args, routes[0].0, &args);
            }
            _ => {
                b.ins().jump(routes[0].0, &args);
            }
        }
    }
    b.seal_all_blocks();
    let fc = module.isa().frontend_config();
    b.finalize(fc);
}
