//! The runtime functions compiled code calls, and their Cranelift signatures.
//!
//! Two kinds: the runtime's own `extern "C"` shims over the image (`stljit_rt_*`, see
//! `stljit_runtime::ffi`), and value shims defined here (`stljit_jit_*`) that wrap the runtime's
//! pure box computations (`arith`, `bitops`, `convert`), so that every intricate flag rule is the
//! runtime's code, not a re-derivation. A value shim takes and returns plain integers, so it
//! needs no `unsafe`; it packs the runtime's [`Outcome`] into a `u64` (see [`pack_outcome`]).

use cranelift_codegen::ir::{
    AbiParam, Signature,
    types::{I32, I64},
};
use cranelift_codegen::isa::CallConv;
use cranelift_module::{FuncId, Linkage, Module};
use std::panic::{AssertUnwindSafe, catch_unwind};
use stljit_core::Width;
use stljit_core::ir::{ArithOp, Conversion, CounterKind, RealFn, TimerKind};
use stljit_runtime::ffi::FfiCode as _;
use stljit_runtime::flags::Outcome;
use stljit_runtime::{arith, bitops, convert};

/// A function compiled code may call.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(crate) enum Helper {
    Timer,
    /// `stljit_rt_{ton,tonr,tof}_fast(value, bit, state, d100, ctl, preset)`: pointers, no
    /// layout; one shim per kind.
    TonFast,
    TonrFast,
    TofFast,
    TimerReset,
    Counter,
    /// `stljit_rt_{ctu,ctd,ctud}_fast(value, bit, state, first_scan, ctl, preset)`.
    CtuFast,
    CtdFast,
    CtudFast,
    CounterReset,
    Pointer,
    ScanBegin,
    ScanEnd,
    SetRange,
    BlockMove,
    Fill,
    ShiftRegister,
    PointerEnd,
    /// `stljit_jit_value(op, width_or_sub, out, in1) -> u64` packed outcome.
    Value,
}

impl Helper {
    pub(crate) const ALL: [Helper; 19] = [
        Helper::SetRange,
        Helper::BlockMove,
        Helper::Fill,
        Helper::ShiftRegister,
        Helper::PointerEnd,
        Helper::Timer,
        Helper::TonFast,
        Helper::TonrFast,
        Helper::TofFast,
        Helper::TimerReset,
        Helper::Counter,
        Helper::CtuFast,
        Helper::CtdFast,
        Helper::CtudFast,
        Helper::CounterReset,
        Helper::Pointer,
        Helper::ScanBegin,
        Helper::ScanEnd,
        Helper::Value,
    ];

    /// The symbol name.
    pub(crate) fn name(self) -> &'static str {
        match self {
            Helper::Timer => "stljit_rt_timer",
            Helper::TonFast => "stljit_rt_ton_fast",
            Helper::TonrFast => "stljit_rt_tonr_fast",
            Helper::TofFast => "stljit_rt_tof_fast",
            Helper::CtuFast => "stljit_rt_ctu_fast",
            Helper::CtdFast => "stljit_rt_ctd_fast",
            Helper::CtudFast => "stljit_rt_ctud_fast",
            Helper::TimerReset => "stljit_rt_timer_reset",
            Helper::Counter => "stljit_rt_counter",
            Helper::CounterReset => "stljit_rt_counter_reset",
            Helper::Pointer => "stljit_rt_pointer",
            Helper::ScanBegin => "stljit_rt_scan_begin",
            Helper::ScanEnd => "stljit_rt_scan_end",
            Helper::SetRange => "stljit_rt_set_range",
            Helper::BlockMove => "stljit_rt_block_move",
            Helper::Fill => "stljit_rt_fill",
            Helper::ShiftRegister => "stljit_rt_shift_register",
            Helper::PointerEnd => "stljit_rt_pointer_end",
            Helper::Value => "stljit_jit_value",
        }
    }

    /// Whether the first argument is the image pointer (runtime shims except the fast ones,
    /// which take pointers to their bytes; not value shims).
    pub(crate) fn takes_image(self) -> bool {
        !(self == Helper::Value || self.is_fast())
    }

    /// The per-kind fast timer and counter shims.
    fn is_fast(self) -> bool {
        use Helper::*;
        matches!(
            self,
            TonFast | TonrFast | TofFast | CtuFast | CtdFast | CtudFast
        )
    }

    /// The fast shim of a timer kind.
    pub(crate) fn timer_fast(kind: TimerKind) -> Helper {
        match kind {
            TimerKind::On => Helper::TonFast,
            TimerKind::Retentive => Helper::TonrFast,
            TimerKind::Off => Helper::TofFast,
        }
    }

    /// The fast shim of a counter kind.
    pub(crate) fn counter_fast(kind: CounterKind) -> Helper {
        match kind {
            CounterKind::Up => Helper::CtuFast,
            CounterKind::Down => Helper::CtdFast,
            CounterKind::UpDown => Helper::CtudFast,
        }
    }

    /// Whether the layout pointer is passed (the same shims as the image).
    pub(crate) fn takes_layout(self) -> bool {
        self.takes_image()
    }

    /// Argument types after `image, layout`, and the return type.
    fn sig_parts(
        self,
    ) -> (
        &'static [cranelift_codegen::ir::Type],
        cranelift_codegen::ir::Type,
    ) {
        match self {
            Helper::Timer | Helper::Counter => (&[I32, I32, I32, I32, I32], I32),
            Helper::TonFast
            | Helper::TonrFast
            | Helper::TofFast
            | Helper::CtuFast
            | Helper::CtdFast
            | Helper::CtudFast => (&[I64, I64, I64, I64, I32, I32], I32),
            Helper::TimerReset | Helper::CounterReset => (&[I32, I32], I32),
            Helper::Pointer => (&[I32, I32, I32], I64),
            Helper::ScanBegin => (&[I64], I32),
            Helper::ScanEnd => (&[I32], I32),
            Helper::Value => (&[I32, I32, I32, I32], I64),
            Helper::SetRange => (&[I32; 7], I32),
            Helper::BlockMove => (&[I32; 6], I32),
            Helper::Fill => (&[I32; 4], I32),
            Helper::ShiftRegister => (&[I32; 6], I32),
            Helper::PointerEnd => (&[I32], I32),
        }
    }

    /// The full signature.
    pub(crate) fn signature(self, cc: CallConv) -> Signature {
        let mut s = Signature::new(cc);
        if self.takes_image() {
            s.params.push(AbiParam::new(I64));
        }
        if self.takes_layout() {
            s.params.push(AbiParam::new(I64));
        }
        let (args, ret) = self.sig_parts();
        s.params.extend(args.iter().map(|t| AbiParam::new(*t)));
        s.returns.push(AbiParam::new(ret));
        s
    }

    /// The host address of the function.
    pub(crate) fn address(self) -> *const u8 {
        if self == Helper::Value {
            return stljit_jit_value as *const u8;
        }
        stljit_runtime::ffi::symbols()
            .into_iter()
            .find(|(n, _)| *n == self.name())
            .map_or(std::ptr::null(), |(_, p)| p)
    }
}

/// Every helper declared in one module.
pub(crate) struct HelperIds {
    ids: Vec<(Helper, FuncId)>,
}

impl HelperIds {
    /// Declares every helper as an imported function.
    pub(crate) fn declare(
        m: &mut impl Module,
    ) -> Result<HelperIds, Box<cranelift_module::ModuleError>> {
        let cc = m.isa().default_call_conv();
        let mut ids = Vec::new();
        for h in Helper::ALL {
            let id = m
                .declare_function(h.name(), Linkage::Import, &h.signature(cc))
                .map_err(Box::new)?;
            ids.push((h, id));
        }
        Ok(HelperIds { ids })
    }

    /// The id of a helper.
    pub(crate) fn id(&self, h: Helper) -> FuncId {
        self.ids
            .iter()
            .find(|(x, _)| *x == h)
            .map(|(_, id)| *id)
            .unwrap_or(self.ids[0].1)
    }
}

/// Operation selectors of [`stljit_jit_value`].
#[derive(Clone, Copy, Debug)]
#[repr(u32)]
pub(crate) enum ValueOp {
    IntArith = 1,
    MulWide = 2,
    DivWide = 3,
    Step = 4,
    RealArith = 5,
    RealFunc = 6,
    ShiftL = 9,
    ShiftR = 10,
    RotL = 11,
    RotR = 12,
    Convert = 13,
}

/// Packs an outcome: bits 0–31 the value, bit 32 set when there is one, bits 40–47 the SMB1
/// bits to set, bits 48–55 the bits to clear.
pub(crate) fn pack_outcome(o: Outcome) -> u64 {
    let (v, has) = match o.value {
        Some(v) => (u64::from(v), 1u64 << 32),
        None => (0, 0),
    };
    v | has | u64::from(o.flags.set) << 40 | u64::from(o.flags.clear) << 48
}

fn width_of(n: u32) -> Width {
    match n {
        1 => Width::Byte,
        2 => Width::Word,
        _ => Width::DWord,
    }
}

/// Encodes the sub-operation of [`stljit_jit_value`].
pub(crate) fn sub_code(width: Width, sub: u32) -> u32 {
    width.bytes() | sub << 8
}

fn arith_op(n: u32) -> ArithOp {
    ArithOp::ALL[(n & 3) as usize]
}

/// The codes are positions in core's `ALL` lists, as for the runtime's own shims.
pub(crate) fn arith_code(op: ArithOp) -> u32 {
    op.ffi_code()
}

pub(crate) fn real_fn_code(f: RealFn) -> u32 {
    f.ffi_code()
}

pub(crate) fn conv_code(c: Conversion) -> u32 {
    c.ffi_code()
}

fn value_outcome(op: u32, sub: u32, out: u32, in1: u32) -> Outcome {
    let width = width_of(sub & 0xFF);
    let s = (sub >> 8) as usize;
    match op {
        1 => arith::int_arith(arith_op(s as u32), width, out, in1),
        2 => arith::mul_wide(out, in1),
        3 => arith::div_wide(out, in1),
        4 => arith::step(width, s != 0, out),
        5 => arith::real_arith(arith_op(s as u32), out, in1),
        6 => arith::real_func(RealFn::ALL[s % RealFn::ALL.len()], in1),
        9 | 10 => bitops::shift(op == 9, width, out, in1 as u8),
        11 | 12 => bitops::rotate(op == 11, width, out, in1 as u8),
        _ => convert::convert(Conversion::ALL[s % Conversion::ALL.len()], in1),
    }
}

/// The value shim: runs one of the runtime's box computations (selected by `op`, see
/// [`ValueOp`]) and packs its outcome. Never unwinds: a panic (a runtime bug) reads as "no
/// value, no flags", i.e. ENO = 0.
pub(crate) extern "C" fn stljit_jit_value(op: u32, sub: u32, out: u32, in1: u32) -> u64 {
    catch_unwind(AssertUnwindSafe(|| {
        pack_outcome(value_outcome(op, sub, out, in1))
    }))
    .unwrap_or(0)
}
