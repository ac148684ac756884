//! The native many-scans loop (`run_scans`): `for i in 0..n { begin; main; end }` at times
//! `t0 + i · dt`, stopping at the first scan whose status is not Ok.
//!
//! A scan that stays on the common path runs its prologue and epilogue inline: any program of
//! either dialect, outside the first scan, not in STOP, whose main program returns Ok without
//! a STOP request. The parts of `scan::begin` that are more than a few stores stay in the
//! runtime and are called where `begin` runs them ([`FastPath`]): the event phase E1 of a
//! program with event sources (`scan::interval_events`), and the events of the instant
//! (`scan::instant_events`), which call back into the compiled interrupt routines through
//! `NativeRoutines`; a program with pulse outputs ends its scans in `scan::end`. The
//! clock-driven refresh of 1-ms and 10-ms timers between them is emitted inline from the
//! runtime's rule text ([`clock`]). Every other scan calls the runtime's
//! `scan::begin`/`scan::end` shims, which remain the definition. The inline path reads every
//! fact it applies from `runtime::scan` (`DELTAS`, `RESETS`, the `SMB0_*` bits), from
//! `runtime::timer` (the refresh rule), from `core::omron` (the system bits, their pulse
//! periods, the condition flags, `P_First_Cycle`) and the image layout, so it restates no
//! fact; the differential tests and every fuzz campaign compare its bytes with the
//! interpreter's, which always calls `scan::begin`/`end`.
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
    BlockArg, Endianness, FuncRef, Function, Inst, InstBuilder, MemFlagsData, Opcode, Value,
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

#[path = "scan_clock.rs"]
mod clock;

/// What the inline path of a scan (in RUN, after the first) leaves to the runtime: the parts
/// of `scan::begin` it does not restate, each called where `begin` runs it, and `scan::end`
/// where the inline epilogue would miss a step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct FastPath {
    /// `scan::interval_events` (E1), after the time step and the resets: the program has
    /// interrupt routines, high-speed counters, pulse outputs or communication.
    interval: bool,
    /// `scan::instant_events` (the events of the instant), after the system bits and the
    /// clock-driven timer refresh, which is inline ([`clock::inline_refresh`]): the program
    /// has events.
    instant: bool,
    /// The epilogue is inline: the program has no pulse outputs, whose generators `scan::end`
    /// lets drive their outputs.
    inline_end: bool,
}

impl FastPath {
    fn of(plan: &ScanPlan) -> FastPath {
        FastPath {
            interval: plan.has_events(),
            instant: plan.has_events(),
            inline_end: !plan.has_pulse_outputs(),
        }
    }
}

/// The loop, with the signature `build::run_signature`:
/// `(image, t0, dt, n, done_out, watch) -> status`; writes the number of scans run to
/// `done_out`. A non-null `watch` (a `ChangeWatch`) also ends the loop after a scan that changed
/// a byte it watches.
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
    let (image, t0, dt, n, done, watch) = (p[0], p[1], p[2], p[3], p[4], p[5]);
    let begin = module.declare_func_in_func(env.helpers.id(Helper::ScanBegin), b.func);
    let end = module.declare_func_in_func(env.helpers.id(Helper::ScanEnd), b.func);
    let fast = FastPath::of(plan);
    let mainf = module.declare_func_in_func(main, b.func);
    let layout = b.ins().iconst(I64, env.baked.layout);
    let scan_plan = b.ins().iconst(I64, env.baked.scan_plan);
    let routines = b.ins().iconst(I64, env.baked.routines);
    let img = Img {
        base: image,
        layout: env.layout,
    };

    // The loop carries this scan's time, its quotients `t / div` (the fields of
    // [`scan::DELTAS`] other than `div` 1) and its deltas, all computed in the step from the
    // previous scan (for the first scan of this call, from the time the scan before it left in
    // `T_NOW`): each scan divides its time once, and the scan's blocks only read block
    // parameters. (Divisions of the scan's time inside the scan were placed by the optimizer at
    // each of their uses, and computed twice per scan.)
    let body = b.create_block();
    let i = b.append_block_param(body, I64);
    let t = b.append_block_param(body, I64);
    let q_rest: Vec<Value> = (1..scan::DELTAS.len())
        .map(|_| b.append_block_param(body, I64))
        .collect();
    let d: Vec<Value> = scan::DELTAS
        .iter()
        .map(|_| b.append_block_param(body, I32))
        .collect();
    let q: Vec<Value> = std::iter::once(t).chain(q_rest).collect();
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
    // The resident bytes live in the shadow for the whole call: unpacked here unless the
    // shadow still holds them, packed at the one exit and before a change watch compares
    // bytes (`crate::resident`).
    env.resident.emit_unpack(&mut b, env.layout, image);
    let zero64 = b.ins().iconst(I64, 0);
    let ok = b.ins().iconst(I32, ScanStatus::Ok as i64);
    let before = img.load(&mut b, I64, Sched::T_NOW);
    let before_q = quotients(&mut b, before);
    let first_q = quotients(&mut b, t0);
    let first_d = deltas(&mut b, &first_q, &before_q);
    let any = b.ins().icmp_imm_u(IntCC::NotEqual, n, 0);
    b.ins().brif(
        any,
        body,
        &scan_args(zero64, &first_q, &first_d),
        fin,
        &[zero64.into(), ok.into()],
    );

    b.switch_to_block(body);
    let i1 = b.ins().iadd_imm_s(i, 1);
    // The common path needs RUN mode and a scan after the first.
    // Two byte loads, not one word: the word would span bytes of several recent stores,
    // which the CPU cannot forward to a load (a stall costing more than the scan).
    let mode = img.load(&mut b, I8, Sched::MODE);
    let first = img.load(&mut b, I8, Sched::FIRST_SCAN);
    let slow = b.ins().bor(mode, first);
    b.ins().brif(slow, slow_begin, &[], fast_begin, &[]);

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
    env.resident.emit_unpack_inputs(&mut b, env.layout, image);
    let runs = b.ins().icmp_imm_s(IntCC::Equal, begun, Begin::Run as i64);
    let fatal = b.ins().iconst(I32, ScanStatus::Fatal as i64);
    b.ins().brif(runs, run, &[], slow_end, &[fatal.into()]);

    b.switch_to_block(fast_begin);
    inline_time_step(&mut b, &img, &q, &d);
    // The runtime's parts of the prologue (a fatal error in a routine ends the scan as aborted,
    // as `scan::begin`'s `Begin::Fatal` does).
    let steps = (fast.interval || fast.instant)
        .then(|| module.declare_func_in_func(env.helpers.id(Helper::ScanSteps), b.func));
    let call_steps = |b: &mut FunctionBuilder<'_>, steps: FuncRef, phase: i64, then| {
        let phase = b.ins().iconst(I32, phase);
        let c = b
            .ins()
            .call(steps, &[image, layout, scan_plan, routines, phase]);
        let r = b.inst_results(c)[0];
        let go = b.ins().icmp_imm_s(IntCC::Equal, r, Begin::Run as i64);
        let fatal = b.ins().iconst(I32, ScanStatus::Fatal as i64);
        b.ins().brif(go, then, &[], slow_end, &[fatal.into()]);
    };
    if let Some(steps) = steps.filter(|_| fast.interval) {
        let inputs = b.create_block();
        call_steps(&mut b, steps, 0, inputs);
        b.switch_to_block(inputs);
    }
    inline_inputs(&mut b, &img, plan.family(), &q);
    env.resident.emit_unpack_inputs(&mut b, env.layout, image);
    clock::inline_refresh(&mut b, &img, plan.clock_timers(), env.prog, &env.timer_res);
    match steps.filter(|_| fast.instant) {
        Some(steps) => call_steps(&mut b, steps, 1, run),
        None => {
            b.ins().jump(run, &[]);
        }
    }

    b.switch_to_block(run);
    if let Some(at) = env.resident.first_scan_mask() {
        // All ones unless this is the first scan (`FIRST_SCAN` is 0 or 1).
        let first = img.byte_at(&mut b, env.layout.sched(Sched::FIRST_SCAN));
        let mask = b.ins().iadd_imm_s(first, -1);
        img.store_at(&mut b, mask, at as u32);
    }
    let zero32 = b.ins().iconst(I32, 0);
    let c = b.ins().call(mainf, &[image, zero32]);
    let s = b.inst_results(c)[0];
    if fast.inline_end {
        // Ok and no STOP request: the epilogue is the output copy and the scan counters. Both
        // prologues reset the request, and only a `STOP` op (of any POU, interrupt routines
        // included) sets it again (the scheduler fields are not addressable), so without one
        // the status decides alone.
        let slow = if env.prog.has_stop() {
            let stop = img.load(&mut b, I8, Sched::STOP_REQ);
            let stop = b.ins().uextend(I32, stop);
            b.ins().bor(s, stop)
        } else {
            s
        };
        b.ins().brif(slow, slow_end, &[s.into()], fast_end, &[]);
    } else {
        b.ins().jump(slow_end, &[s.into()]);
    }

    b.switch_to_block(slow_end);
    env.resident.emit_pack_outputs(&mut b, env.layout, image);
    let c = b.ins().call(end, &[image, layout, end_status]);
    let st = b.inst_results(c)[0];
    b.ins().brif(st, fin, &[i1.into(), st.into()], next, &[]);

    b.switch_to_block(fast_end);
    env.resident.emit_pack_outputs(&mut b, env.layout, image);
    inline_end(&mut b, &img);
    b.ins().jump(next, &[]);

    // With a `ChangeWatch` (`Engine::run_scans_watching`), a scan that changed a watched byte
    // ends the stretch; without one (null), the test is one predictable branch per scan.
    b.switch_to_block(next);
    let (check, count) = (b.create_block(), b.create_block());
    b.ins().brif(watch, check, &[], count, &[]);
    b.switch_to_block(check);
    env.resident.emit_pack(&mut b, env.layout, image);
    let changed = module.declare_func_in_func(env.helpers.id(Helper::WatchChanged), b.func);
    let c = b.ins().call(changed, &[image, layout, watch]);
    let changed = b.inst_results(c)[0];
    b.ins()
        .brif(changed, fin, &[i1.into(), ok.into()], count, &[]);
    b.switch_to_block(count);
    let more = b.ins().icmp(IntCC::UnsignedLessThan, i1, n);
    b.ins()
        .brif(more, advance, &[], fin, &[i1.into(), ok.into()]);

    b.switch_to_block(advance);
    let t1 = b.ins().iadd(t, dt);
    let next_q = quotients(&mut b, t1);
    let next_d = deltas(&mut b, &next_q, &q);
    b.ins().jump(body, &scan_args(i1, &next_q, &next_d));

    b.switch_to_block(fin);
    env.resident.emit_pack(&mut b, env.layout, image);
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

/// The arguments of the loop's `body` block for scan number `i`: its time and quotients `q`
/// (from [`quotients`]) and its deltas `d`.
fn scan_args(i: Value, q: &[Value], d: &[Value]) -> Vec<BlockArg> {
    std::iter::once(i)
        .chain(q.iter().copied())
        .chain(d.iter().copied())
        .map(BlockArg::from)
        .collect()
}

/// `t / div` for every field of [`scan::DELTAS`] (so the first is `t` itself).
fn quotients(b: &mut FunctionBuilder<'_>, t: Value) -> Vec<Value> {
    const _: () = assert!(
        scan::DELTAS[0].1 == 1,
        "the loop carries the time as the first quotient"
    );
    let mut q = Vec::with_capacity(scan::DELTAS.len());
    for &(_, div) in &scan::DELTAS {
        let v = divide(b, t, &q, div);
        q.push(v);
    }
    q
}

/// `t / d`, from the quotient in `q` (a prefix of [`quotients`]) of the largest field divisor
/// that divides `d`: `(t / a) / b = t / (a·b)` for whole numbers, and a quotient already at
/// hand needs a smaller division, which for these divisors is a multiply and a shift where the
/// full one needs five instructions (`t / 100` as `(t / 10) / 10`).
fn divide(b: &mut FunctionBuilder<'_>, t: Value, q: &[Value], d: u64) -> Value {
    let (base, div) = scan::DELTAS
        .iter()
        .zip(q)
        .filter(|((_, div), _)| d.is_multiple_of(*div))
        .map(|(&(_, div), &v)| (v, div))
        .max_by_key(|&(_, div)| div)
        .unwrap_or((t, 1));
    if d == div {
        base
    } else {
        b.ins().udiv_imm_u(base, (d / div) as i64)
    }
}

/// The fields of [`scan::DELTAS`] for a scan whose quotients are `now` after a scan whose
/// quotients are `before`: `now − before` saturated at 0 below and at `u32::MAX` above. The
/// divisions are monotonic, so every field is below exactly when the time (the first field)
/// is, and one comparison serves all of them.
fn deltas(b: &mut FunctionBuilder<'_>, now: &[Value], before: &[Value]) -> Vec<Value> {
    let below = b.ins().icmp(IntCC::UnsignedLessThan, now[0], before[0]);
    let zero = b.ins().iconst(I64, 0);
    let max = b.ins().iconst(I64, i64::from(u32::MAX));
    now.iter()
        .zip(before)
        .map(|(&now, &before)| {
            let d = b.ins().isub(now, before);
            let d = b.ins().umin(d, max);
            let d = b.ins().select(below, zero, d);
            b.ins().ireduce(I32, d)
        })
        .collect()
}

/// `scan::begin` for a scan in RUN after the first, up to its event phase E1: the time step
/// (`q`: the scan's time and quotients, `d`: its deltas, see [`build_run`]) and the step-5
/// resets.
fn inline_time_step(b: &mut FunctionBuilder<'_>, img: &Img<'_>, q: &[Value], d: &[Value]) {
    let l = img.layout;
    let t = q[0];
    for (&(field, _), &d) in scan::DELTAS.iter().zip(d) {
        img.store(b, d, field);
    }
    let prev = img.load(b, I64, Sched::T_NOW);
    img.store(b, prev, Sched::T_PREV);
    img.store(b, t, Sched::T_NOW);
    // The resets, and `FIRST_SCAN`, which this path has just read as 0: rewriting it lets the
    // bytes form one run with their neighbours in the layout.
    let mut resets = ConstBytes::default();
    resets.put(l.sched(Sched::LOOP_COUNT), &0u32.to_le_bytes());
    for (field, v) in scan::RESETS {
        resets.put(l.sched(field), &[v]);
    }
    resets.put(l.sched(Sched::FIRST_SCAN), &[0]);
    resets.store(b, img);
}

/// `scan::begin` after E1 and before the clock refresh: the input copy and the family's
/// system bits (`q`: the scan's time and quotients).
fn inline_inputs(b: &mut FunctionBuilder<'_>, img: &Img<'_>, family: Family, q: &[Value]) {
    let l = img.layout;
    img.copy(b, l.phys_in, l.base(Area::I), l.area_size(Area::I));
    match family {
        Family::S7 => inline_smb0(b, img, q),
        Family::Omron => inline_omron_bits(b, img, q),
    }
}

/// Constant bytes to store at image offsets, written as few wide stores as their runs allow.
#[derive(Default)]
struct ConstBytes(std::collections::BTreeMap<u32, u8>);

impl ConstBytes {
    /// `bytes` from image offset `at` (a later `put` of the same byte wins).
    fn put(&mut self, at: u32, bytes: &[u8]) {
        for (k, &v) in (at..).zip(bytes) {
            self.0.insert(k, v);
        }
    }

    /// Stores every run of consecutive bytes in pieces of 8, 4, 2 and 1 bytes (little-endian
    /// words, so that byte `k` of a piece goes to `at + k` on any host).
    fn store(&self, b: &mut FunctionBuilder<'_>, img: &Img<'_>) {
        let bytes: Vec<(u32, u8)> = self.0.iter().map(|(&k, &v)| (k, v)).collect();
        let mut k = 0;
        while k < bytes.len() {
            let at = bytes[k].0;
            let run = bytes[k..]
                .iter()
                .zip(at..)
                .take_while(|((off, _), want)| off == want)
                .count();
            let ty = match run {
                8.. => I64,
                4..=7 => I32,
                2..=3 => I16,
                _ => I8,
            };
            let n = ty.bytes() as usize;
            let word = bytes[k..k + n]
                .iter()
                .rev()
                .fold(0u64, |w, &(_, v)| (w << 8) | u64::from(v));
            let v = b.ins().iconst(ty, word as i64);
            let flags = Img::flags().with_endianness(Endianness::Little);
            b.ins().store(flags, v, img.base, at as i32);
            k += n;
        }
    }
}

/// SMB0 outside the first scan (S7, spec §2.3): the constant bits, the clock bits, the parity
/// bit.
fn inline_smb0(b: &mut FunctionBuilder<'_>, img: &Img<'_>, q: &[Value]) {
    let l = img.layout;
    if l.area_size(Area::SM) > 0 {
        let mut v = b.ins().iconst(I32, i64::from(scan::SMB0_ALWAYS));
        for (bit, period) in scan::SMB0_CLOCKS {
            // ON while `t / (period / 2)` is even.
            let half = divide(b, q[0], q, period / 2);
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
/// division, a multiplication and a compare; [`divide`] starts it from the scan's quotients
/// `q` (of [`scan::DELTAS`]), which for the 20 ms and 200 ms pulses are that division already.
fn inline_omron_bits(b: &mut FunctionBuilder<'_>, img: &Img<'_>, q: &[Value]) {
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
        let halves = divide(b, q[0], q, period / 2);
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
