//! The native many-scans loop (`run_scans`): `for i in 0..n { begin; main; end }` at times
//! `t0 + i · dt`, stopping at the first scan whose status is not Ok.
//!
//! A scan that stays on the common path runs its prologue and epilogue inline: a program of
//! either dialect whose plan has no clock-refreshed timer and no event source, outside the
//! first scan, not in STOP, whose main program returns Ok without a STOP request. Every other
//! scan calls the runtime's `scan::begin`/`scan::end` shims, which remain the definition; in
//! particular every scan of a program with interrupt routines, whose event phases run inside
//! `scan::begin` (it calls back into the compiled routines through `NativeRoutines`). The
//! inline path reads every fact it applies from `runtime::scan` (`DELTAS`, `RESETS`, the
//! `SMB0_*` bits), from `core::omron` (the system bits, their pulse periods, the condition
//! flags, `P_First_Cycle`) and the image layout, so it restates no fact; the differential tests
//! and every fuzz campaign compare its bytes with the interpreter's, which always calls
//! `scan::begin`/`end`.
//!
//! Why inline: an empty program's scan is otherwise two shim calls, each with its pointer
//! checks and `catch_unwind`, around a few dozen stores; inline, the whole scan of a small
//! program costs a few nanoseconds (`docs/performance.md`).

use crate::JitError;
use crate::helpers::Helper;
use crate::lower::Env;
use cranelift_codegen::Context;
use cranelift_codegen::inline::{Inline, InlineCommand};
use cranelift_codegen::ir::{
    Block, BlockArg, Endianness, FuncRef, Function, Inst, InstBuilder, MemFlagsData, Opcode, Value,
    condcodes::IntCC,
    types::{I8, I16, I32, I64},
};
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext};
use cranelift_jit::JITModule;
use cranelift_module::{FuncId, Module};
use std::borrow::Cow;
use stljit_core::layout::{Layout, Sched};
use stljit_core::omron::{self, SystemBit};
use stljit_core::{Area, Family, ScanStatus};
use stljit_runtime::scan::{self, Begin, ScanPlan};

/// Whether scans of `plan`'s program may take the inline path at all (the interrupt
/// machinery could act in a program with interrupt routines, high-speed counters, pulse
/// outputs or communication; Omron timers are never clock-refreshed).
fn inline_path(plan: &ScanPlan) -> bool {
    plan.clock_timers().is_empty() && !plan.has_events()
}

/// The loop, with the signature `build::run_signature`:
/// `(image, t0, dt, n, done_out) -> status`; writes the number of scans run to `done_out`.
///
/// With `main_body` (the main program's function, `main`'s CLIF, not yet compiled), the loop
/// runs the main program inline instead of calling `main`: no call, no second prologue, and
/// its loads and bases are the loop's (see [`InlineMain`]).
#[allow(clippy::too_many_arguments)]
pub(crate) fn build_run(
    env: &Env<'_>,
    plan: &ScanPlan,
    module: &mut JITModule,
    ctx: &mut Context,
    fbc: &mut FunctionBuilderContext,
    main: FuncId,
    main_body: Option<&Function>,
) -> Result<(), JitError> {
    let mut b = FunctionBuilder::new(&mut ctx.func, fbc);
    let entry = b.create_block();
    b.append_block_params_for_function_params(entry);
    b.switch_to_block(entry);
    let p = b.block_params(entry).to_vec();
    let (image, t0, dt, n, done) = (p[0], p[1], p[2], p[3], p[4]);
    let begin = module.declare_func_in_func(env.helpers.id(Helper::ScanBegin), b.func);
    let end = module.declare_func_in_func(env.helpers.id(Helper::ScanEnd), b.func);
    let mainf = module.declare_func_in_func(main, b.func);
    let layout = b.ins().iconst(I64, env.baked.layout);
    let scan_plan = b.ins().iconst(I64, env.baked.scan_plan);
    let routines = b.ins().iconst(I64, env.baked.routines);
    let img = Img {
        base: image,
        layout: env.layout,
    };

    // The loop carries this scan's time and `t / div` of this scan and of the previous one for
    // every delta field (the scan before the first one of this call left its time in `T_NOW`),
    // so each scan divides its time once, in the step to the next scan, and the scan's blocks
    // only read block parameters. (Divisions of the scan's time inside the scan were placed by
    // the optimizer at each of their uses, and computed twice per scan.)
    let body = b.create_block();
    let i = b.append_block_param(body, I64);
    let t = b.append_block_param(body, I64);
    let prev_q = quotient_params(&mut b, body);
    let q = quotient_params(&mut b, body);
    let slow_begin = b.create_block();
    let fast_begin = b.create_block();
    let run = b.create_block();
    let slow_end = b.create_block();
    let end_status = b.append_block_param(slow_end, I32);
    let fast_end = b.create_block();
    let next = b.create_block();
    let advance = b.create_block();
    let fin = b.create_block();
    let (fin_i, fin_st) = (
        b.append_block_param(fin, I64),
        b.append_block_param(fin, I32),
    );
    let zero64 = b.ins().iconst(I64, 0);
    let ok = b.ins().iconst(I32, ScanStatus::Ok as i64);
    let before = img.load(&mut b, I64, Sched::T_NOW);
    let mut args = vec![zero64, t0];
    args.extend(quotients(&mut b, before));
    args.extend(quotients(&mut b, t0));
    let any = b.ins().icmp_imm_u(IntCC::NotEqual, n, 0);
    b.ins().brif(
        any,
        body,
        &block_args(&args),
        fin,
        &[zero64.into(), ok.into()],
    );

    b.switch_to_block(body);
    let i1 = b.ins().iadd_imm_s(i, 1);
    if inline_path(plan) {
        // The common path needs RUN mode and a scan after the first.
        let mode = img.load(&mut b, I8, Sched::MODE);
        let first = img.load(&mut b, I8, Sched::FIRST_SCAN);
        let slow = b.ins().bor(mode, first);
        b.ins().brif(slow, slow_begin, &[], fast_begin, &[]);
    } else {
        b.ins().jump(slow_begin, &[]);
    }

    b.switch_to_block(slow_begin);
    let c = b
        .ins()
        .call(begin, &[image, layout, scan_plan, routines, t]);
    let begun = b.inst_results(c)[0];
    let stopped = b.ins().iconst(I32, ScanStatus::Stopped as i64);
    let started = b.create_block();
    b.ins()
        .brif(begun, started, &[], fin, &[i1.into(), stopped.into()]);
    // Not in STOP: run the main program, or (a fatal error in an interrupt routine) end the
    // scan as aborted.
    b.switch_to_block(started);
    let runs = b.ins().icmp_imm_s(IntCC::Equal, begun, Begin::Run as i64);
    let fatal = b.ins().iconst(I32, ScanStatus::Fatal as i64);
    b.ins().brif(runs, run, &[], slow_end, &[fatal.into()]);

    b.switch_to_block(fast_begin);
    inline_begin(&mut b, &img, plan.family(), t, &q, &prev_q);
    b.ins().jump(run, &[]);

    b.switch_to_block(run);
    let zero32 = b.ins().iconst(I32, 0);
    let c = b.ins().call(mainf, &[image, zero32]);
    let s = b.inst_results(c)[0];
    if inline_path(plan) {
        // Ok and no STOP request: the epilogue is the output copy and the scan counters.
        let stop = img.load(&mut b, I8, Sched::STOP_REQ);
        let stop = b.ins().uextend(I32, stop);
        let slow = b.ins().bor(s, stop);
        b.ins().brif(slow, slow_end, &[s.into()], fast_end, &[]);
    } else {
        b.ins().jump(slow_end, &[s.into()]);
    }

    b.switch_to_block(slow_end);
    let c = b.ins().call(end, &[image, layout, end_status]);
    let st = b.inst_results(c)[0];
    b.ins().brif(st, fin, &[i1.into(), st.into()], next, &[]);

    b.switch_to_block(fast_end);
    inline_end(&mut b, &img);
    b.ins().jump(next, &[]);

    b.switch_to_block(next);
    let more = b.ins().icmp(IntCC::UnsignedLessThan, i1, n);
    b.ins()
        .brif(more, advance, &[], fin, &[i1.into(), ok.into()]);

    b.switch_to_block(advance);
    let t1 = b.ins().iadd(t, dt);
    let mut args = vec![i1, t1];
    args.extend_from_slice(&q);
    args.extend(quotients(&mut b, t1));
    b.ins().jump(body, &block_args(&args));

    b.switch_to_block(fin);
    b.ins()
        .store(MemFlagsData::new().with_notrap(), fin_i, done, 0);
    b.ins().return_(&[fin_st]);
    b.seal_all_blocks();
    let fc = module.isa().frontend_config();
    b.finalize(fc);
    if let Some(body) = main_body {
        ctx.inline(InlineMain { call: mainf, body })
            .map_err(|e| JitError::Codegen(format!("inlining the main program: {e:?}")))?;
    }
    Ok(())
}

/// Directs Cranelift's inliner to put the main program's body where the loop calls it (and
/// nowhere else: the calls inside the body stay calls).
struct InlineMain<'a> {
    /// The loop's reference to the main program's function.
    call: FuncRef,
    body: &'a Function,
}

impl Inline for InlineMain<'_> {
    fn inline(
        &mut self,
        _caller: &Function,
        _inst: Inst,
        _opcode: Opcode,
        callee: FuncRef,
        _args: &[Value],
    ) -> InlineCommand<'_> {
        if callee == self.call {
            InlineCommand::Inline {
                callee: Cow::Borrowed(self.body),
                visit_callee: false,
            }
        } else {
            InlineCommand::KeepCall
        }
    }
}

/// The image at its base address, with the layout its offsets come from.
struct Img<'a> {
    base: Value,
    layout: &'a Layout,
}

impl Img<'_> {
    fn flags() -> MemFlagsData {
        MemFlagsData::new().with_notrap()
    }

    /// Loads a native-endian value of type `ty` from scheduler field `field`.
    fn load(
        &self,
        b: &mut FunctionBuilder<'_>,
        ty: cranelift_codegen::ir::Type,
        field: u32,
    ) -> Value {
        b.ins().load(
            ty,
            Self::flags(),
            self.base,
            self.layout.sched(field) as i32,
        )
    }

    /// The byte at image offset `off`, zero-extended to `i32`.
    fn byte_at(&self, b: &mut FunctionBuilder<'_>, off: u32) -> Value {
        b.ins().uload8(I32, Self::flags(), self.base, off as i32)
    }

    /// Stores `v` (its own type) to scheduler field `field`.
    fn store(&self, b: &mut FunctionBuilder<'_>, v: Value, field: u32) {
        self.store_at(b, v, self.layout.sched(field));
    }

    /// Stores `v` at image offset `off`.
    fn store_at(&self, b: &mut FunctionBuilder<'_>, v: Value, off: u32) {
        b.ins().store(Self::flags(), v, self.base, off as i32);
    }

    /// Copies `len` bytes from image offset `src` to `dst`, each piece as wide as fits of 8, 4,
    /// 2 and 1 bytes (the I/O images are small; their offsets and size are constants of the
    /// layout).
    fn copy(&self, b: &mut FunctionBuilder<'_>, src: u32, dst: u32, len: u32) {
        let mut at = 0;
        while at < len {
            let ty = match len - at {
                8.. => I64,
                4..=7 => I32,
                2..=3 => I16,
                _ => I8,
            };
            let v = b
                .ins()
                .load(ty, Self::flags(), self.base, (src + at) as i32);
            self.store_at(b, v, dst + at);
            at += ty.bytes();
        }
    }
}

/// One `i64` parameter of `block` per field of [`scan::DELTAS`] (a quotient carried along).
fn quotient_params(b: &mut FunctionBuilder<'_>, block: Block) -> Vec<Value> {
    scan::DELTAS
        .iter()
        .map(|_| b.append_block_param(block, I64))
        .collect()
}

/// `values` as block arguments.
fn block_args(values: &[Value]) -> Vec<BlockArg> {
    values.iter().map(|&v| BlockArg::from(v)).collect()
}

/// `t / div` for every field of [`scan::DELTAS`].
fn quotients(b: &mut FunctionBuilder<'_>, t: Value) -> Vec<Value> {
    scan::DELTAS
        .iter()
        .map(|&(_, div)| match div {
            1 => t,
            _ => b.ins().udiv_imm_u(t, div as i64),
        })
        .collect()
}

/// `scan::begin` for a scan in RUN after the first, no clock-refreshed timer: the time step
/// with its deltas (`q`: this scan's `t / div`, `prev_q`: the previous scan's), the step-5
/// resets, the input copy and the family's system bits.
fn inline_begin(
    b: &mut FunctionBuilder<'_>,
    img: &Img<'_>,
    family: Family,
    t: Value,
    q: &[Value],
    prev_q: &[Value],
) {
    let l = img.layout;
    let prev = img.load(b, I64, Sched::T_NOW);
    for (&(field, _), (&now, &before)) in scan::DELTAS.iter().zip(q.iter().zip(prev_q)) {
        // `t / div − prev / div`, saturated at 0 below and at u32::MAX above.
        let d = b.ins().isub(now, before);
        let below = b.ins().icmp(IntCC::UnsignedLessThan, now, before);
        let zero = b.ins().iconst(I64, 0);
        let d = b.ins().select(below, zero, d);
        let max = b.ins().iconst(I64, i64::from(u32::MAX));
        let d = b.ins().umin(d, max);
        let d = b.ins().ireduce(I32, d);
        img.store(b, d, field);
    }
    img.store(b, prev, Sched::T_PREV);
    img.store(b, t, Sched::T_NOW);
    for (field, v) in scan::RESETS {
        let v = b.ins().iconst(I8, i64::from(v));
        img.store(b, v, field);
    }
    let zero = b.ins().iconst(I32, 0);
    img.store(b, zero, Sched::LOOP_COUNT);
    img.copy(b, l.phys_in, l.base(Area::I), l.area_size(Area::I));
    match family {
        Family::S7 => inline_smb0(b, img, t),
        Family::Omron => inline_omron_bits(b, img, t, q),
    }
}

/// SMB0 outside the first scan (S7, spec §2.3): the constant bits, the clock bits, the parity
/// bit.
fn inline_smb0(b: &mut FunctionBuilder<'_>, img: &Img<'_>, t: Value) {
    let l = img.layout;
    if l.area_size(Area::SM) > 0 {
        let mut v = b.ins().iconst(I32, i64::from(scan::SMB0_ALWAYS));
        for (bit, period) in scan::SMB0_CLOCKS {
            // ON while `t / (period / 2)` is even.
            let half = b.ins().udiv_imm_u(t, (period / 2) as i64);
            let odd = b.ins().band_imm_u(half, 1);
            let on = b.ins().bxor_imm_u(odd, 1);
            let on = b.ins().ireduce(I32, on);
            let on = b.ins().ishl_imm_u(on, i64::from(bit));
            v = b.ins().bor(v, on);
        }
        let k = img.load(b, I64, Sched::SCAN_NO);
        let odd = b.ins().band_imm_u(k, 1);
        let even = b.ins().bxor_imm_u(odd, 1);
        let even = b.ins().ireduce(I32, even);
        let even = b.ins().ishl_imm_u(even, i64::from(scan::SMB0_EVEN_SCAN));
        let v = b.ins().bor(v, even);
        let v = b.ins().ireduce(I8, v);
        img.store_at(b, v, l.base(Area::SM));
    }
}

/// The Omron system bits outside the first cycle (omron-cp.md §2.2 step 3, `scan::begin`'s
/// `omron_system_bits` then `clear_condition_flags`): the first four bytes of the Flags area
/// become `P_On` and the clock pulses ON in the first half of their period, keeping only what
/// neither writes, and `P_First_Cycle` goes OFF.
///
/// A pulse is ON while `t % period < period / 2` (the runtime's definition); this computes it
/// as "`t / (period / 2)` is even", which is the same for an even period (`t = k·period + r`
/// gives `t / (period / 2) = 2k + [r >= period / 2]`) and costs one division instead of a
/// division, a multiplication and a compare. Where `period / 2` is the divisor of a delta
/// field, the scan's quotient `q` (of [`scan::DELTAS`]) is that division already.
fn inline_omron_bits(b: &mut FunctionBuilder<'_>, img: &Img<'_>, t: Value, q: &[Value]) {
    const _: () = {
        let mut k = 0;
        while k < SystemBit::PULSES.len() {
            assert!(
                SystemBit::PULSES[k].1.is_multiple_of(2),
                "the parity form needs even periods"
            );
            k += 1;
        }
    };
    let l = img.layout;
    let mut bits = b.ins().iconst(I32, 1i64 << SystemBit::On.index());
    for (pulse, period) in SystemBit::PULSES {
        let half = period / 2;
        let halves = match scan::DELTAS.iter().position(|&(_, div)| div == half) {
            Some(k) => q[k],
            None => b.ins().udiv_imm_u(t, half as i64),
        };
        let odd = b.ins().band_imm_u(halves, 1);
        let on = b.ins().bxor_imm_u(odd, 1);
        let on = b.ins().ireduce(I32, on);
        let on = b.ins().ishl_imm_u(on, i64::from(pulse.index()));
        bits = b.ins().bor(bits, on);
    }
    // The condition flags are kept by the system bits and then cleared (where the area holds
    // them), so of an old byte only what is neither a system bit nor a condition flag stays.
    let keep = u32::from(SystemBit::CONDITION_FLAGS);
    let cleared = if l.area_size(Area::Flags) >= 2 {
        u32::from(SystemBit::CONDITION_FLAGS)
    } else {
        0
    };
    // The four bytes as one little-endian word: byte `i` of the area is bits `8i..8i+8`.
    let base = l.base(Area::Flags);
    let word_flags = Img::flags().with_endianness(Endianness::Little);
    let k = i64::from(keep & !cleared);
    let word = if k == 0 {
        bits
    } else {
        let old = b.ins().load(I32, word_flags, img.base, base as i32);
        let old = b.ins().band_imm_u(old, k);
        b.ins().bor(bits, old)
    };
    b.ins().store(word_flags, word, img.base, base as i32);
    if let Some((a, bit)) = omron::first_cycle_bit(l) {
        let old = img.byte_at(b, a);
        let off = b.ins().band_imm_u(old, !(1i64 << bit) & 0xFF);
        let off = b.ins().ireduce(I8, off);
        img.store_at(b, off, a);
    }
}

/// `scan::end` for a scan that returned Ok without a STOP request: the output copy, the first-
/// scan flag cleared, the scan number counted.
fn inline_end(b: &mut FunctionBuilder<'_>, img: &Img<'_>) {
    let l = img.layout;
    img.copy(b, l.base(Area::Q), l.phys_out, l.area_size(Area::Q));
    let zero = b.ins().iconst(I8, 0);
    img.store(b, zero, Sched::FIRST_SCAN);
    let k = img.load(b, I64, Sched::SCAN_NO);
    let k = b.ins().iadd_imm_u(k, 1);
    img.store(b, k, Sched::SCAN_NO);
}
