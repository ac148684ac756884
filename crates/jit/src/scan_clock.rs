//! Step 4 of `scan::begin` on the inline scan path: the clock refresh of the 1-ms and 10-ms
//! timers a program declares, emitted from the runtime's rule text
//! ([`stljit_runtime::timer::refresh_rule`], written over [`RuleOps`]) as the timer
//! instructions are (`lower::rules`).
//!
//! The runtime's `timer::refresh` decides on a timer's kind and resolution bytes, which cold
//! start writes from the program's declaration and nothing a program runs changes. So each
//! timer's code compares the two bytes with the declaration (one 16-bit compare and a branch
//! the same bytes take every scan) and runs the rule with both as constants, which folds it to
//! a few instructions; bytes that differ (an image restored from another program) take the
//! rule as written, on the bytes.
//!
//! [`RuleOps`]: stljit_runtime::rule_ops::RuleOps

use super::Img;
use crate::lower::rules::{Emit, Rv};
use cranelift_codegen::ir::{
    Endianness, InstBuilder, Value,
    condcodes::IntCC,
    types::{I8, I16, I64},
};
use cranelift_frontend::FunctionBuilder;
use stljit_core::Area;
use stljit_core::ir::Program;
use stljit_core::layout::{Sched, TimerState};
use stljit_runtime::block;
use stljit_runtime::timer::{TimerFields, refresh_applies, refresh_rule};

// The fast path loads the kind and resolution bytes as one little-endian word.
const _: () = assert!(TimerState::RES == TimerState::KIND + 1);

/// Emits the clock refresh of `timers` (the plan's, in the runtime's order) at the current
/// point of `b`, which it leaves at the point after them; `resolutions` are the program's
/// declared ones (`Env::timer_res`).
pub(super) fn inline_refresh(
    b: &mut FunctionBuilder<'_>,
    img: &Img<'_>,
    timers: &[u16],
    prog: &Program,
    resolutions: &[Option<u8>],
) {
    if timers.is_empty() {
        return;
    }
    let l = img.layout;
    let deltas = [Sched::D1, Sched::D10].map(|f| {
        let d = b.ins().uload32(Img::flags(), img.base, l.sched(f) as i32);
        Rv::R(d)
    });
    for &n in timers {
        // Outside the profile: `refresh` skips the timer on the same check.
        if block::object_run(l, Area::TimerBit, n, 1).is_err() {
            continue;
        }
        let at = Fields::of(img, n);
        let declared = prog
            .timers
            .iter()
            .find(|t| t.id.0 == n)
            .map(|t| t.kind.code())
            .zip(resolutions.get(usize::from(n)).copied().flatten());
        let done = b.create_block();
        let on_bytes = b.create_block();
        if let Some((kind, res)) = declared {
            let as_declared = b.create_block();
            let little = Img::flags().with_endianness(Endianness::Little);
            let word = b.ins().uload16(I64, little, img.base, at.kind as i32);
            let expected = i64::from(kind) | i64::from(res) << 8;
            let same = b.ins().icmp_imm_s(IntCC::Equal, word, expected);
            b.ins().brif(same, as_declared, &[], on_bytes, &[]);
            b.switch_to_block(as_declared);
            at.refresh(b, img, Rv::K(kind.into()), Rv::K(res.into()), deltas);
            b.ins().jump(done, &[]);
        } else {
            b.ins().jump(on_bytes, &[]);
        }
        b.switch_to_block(on_bytes);
        let kind = at.byte(b, img, at.kind);
        let res = at.byte(b, img, at.res);
        let applies = refresh_applies(&mut Emit { b }, kind, res);
        let applies = Emit { b }.value(applies);
        let apply = b.create_block();
        b.ins().brif(applies, apply, &[], done, &[]);
        b.switch_to_block(apply);
        at.refresh(b, img, kind, res, deltas);
        b.ins().jump(done, &[]);
        b.switch_to_block(done);
    }
}

/// The image offsets of one timer's fields.
struct Fields {
    value: u32,
    bit: u32,
    run: u32,
    tof: u32,
    pt_cache: u32,
    kind: u32,
    res: u32,
}

impl Fields {
    fn of(img: &Img<'_>, n: u16) -> Fields {
        let [(value, _), (bit, _), (state, _)] = img.layout.timer_bytes(n);
        let field = |f: u32| state + f;
        Fields {
            value,
            bit,
            run: field(TimerState::RUN),
            tof: field(TimerState::TOF),
            pt_cache: field(TimerState::PT_CACHE),
            kind: field(TimerState::KIND),
            res: field(TimerState::RES),
        }
    }

    /// The byte at `off`, zero-extended.
    fn byte(&self, b: &mut FunctionBuilder<'_>, img: &Img<'_>, off: u32) -> Rv {
        Rv::R(b.ins().uload8(I64, Img::flags(), img.base, off as i32))
    }

    /// The `i16` at `off`, sign-extended: big-endian (a `bswap`: x86 has no big-endian load)
    /// or native.
    fn word(&self, b: &mut FunctionBuilder<'_>, img: &Img<'_>, off: u32, big: bool) -> Rv {
        let w = b.ins().load(I16, Img::flags(), img.base, off as i32);
        let w = if big { b.ins().bswap(w) } else { w };
        Rv::R(b.ins().sextend(I64, w))
    }

    /// Stores the low byte (`I8`) or the low word, big-endian (`I16`), of `v` at `off`.
    fn put(
        &self,
        b: &mut FunctionBuilder<'_>,
        img: &Img<'_>,
        v: Rv,
        ty: cranelift_codegen::ir::Type,
        off: u32,
    ) {
        let v: Value = Emit { b }.value(v);
        let v = b.ins().ireduce(ty, v);
        let v = if ty == I16 { b.ins().bswap(v) } else { v };
        b.ins().store(Img::flags(), v, img.base, off as i32);
    }

    /// [`refresh_rule`] on the timer's fields, decoded and written back as the runtime's
    /// `Timer::decode`/`encode` do: the CV, the bit, `run` and the TOF byte are written (a
    /// field the rule returns as it read it is not), the PT cache, kind and resolution only
    /// read.
    fn refresh(
        &self,
        b: &mut FunctionBuilder<'_>,
        img: &Img<'_>,
        kind: Rv,
        res: Rv,
        [d1, d10]: [Rv; 2],
    ) {
        let raw = TimerFields {
            cv: self.word(b, img, self.value, true),
            bit: self.byte(b, img, self.bit),
            run: self.byte(b, img, self.run),
            tof: self.byte(b, img, self.tof),
            pt_cache: self.word(b, img, self.pt_cache, false),
            res,
        };
        let next = {
            let o = &mut Emit { b };
            let t = TimerFields::from_raw(o, raw);
            refresh_rule(o, kind, t, d1, d10)
        };
        for (old, new, ty, off) in [
            (raw.cv, next.cv, I16, self.value),
            (raw.bit, next.bit, I8, self.bit),
            (raw.run, next.run, I8, self.run),
            (raw.tof, next.tof, I8, self.tof),
        ] {
            if new != old {
                self.put(b, img, new, ty, off);
            }
        }
    }
}
