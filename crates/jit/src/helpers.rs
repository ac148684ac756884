//! The runtime functions compiled code calls, and their Cranelift signatures.
//!
//! Every helper is a runtime `extern "C"` shim (`stljit_rt_*`, see `stljit_runtime::ffi`):
//! the shims over the image and the per-kind Omron timer and counter fast shims. Beside them,
//! the pure value shims, one per `ffi::ValueOp` (`ffi::VALUE_SHIMS`), run the runtime's box
//! computations (`arith`, `bitops`, `convert`), so that every intricate flag rule is the
//! runtime's code, not a re-derivation. [`helpers!`] builds the
//! registry from one table: the enum, [`Helper::ALL`], and per helper its symbol, its host
//! address and its signature.

use cranelift_codegen::ir::{
    AbiParam, Signature, Type,
    types::{I32, I64},
};
use cranelift_codegen::isa::CallConv;
use cranelift_module::{FuncId, Linkage, Module};
use stljit_core::ir::{OmronCounterKind, OmronTimerKind};
use stljit_runtime::ffi;

/// The arguments a helper takes before its own.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Lead {
    /// `image: i64, layout: i64` (the shims over the image).
    ImageLayout,
    /// Nothing (the fast Omron shims take pointers to their bytes; the value shim takes none).
    Nothing,
}

/// One row of the registry.
struct Row {
    symbol: &'static str,
    lead: Lead,
    /// Argument types after the lead.
    args: &'static [Type],
    ret: Type,
}

/// Defines [`Helper`] with one variant per row, and its table, from rows of
/// `Variant => symbol, runtime function, lead, [argument types] -> return type;`.
macro_rules! helpers {
    ($($(#[$doc:meta])* $variant:ident => $symbol:literal, $func:path, $lead:ident,
        [$($arg:expr),*] -> $ret:expr;)+) => {
        /// A function compiled code may call.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub(crate) enum Helper {
            $($(#[$doc])* $variant,)+
        }

        impl Helper {
            /// Every helper, in table order (the order they are declared in a module).
            pub(crate) const ALL: &'static [Helper] = &[$(Helper::$variant),+];

            /// The rows, in the order of the variants (so `ROWS[h as usize]` is `h`'s).
            const ROWS: &'static [Row] = &[$(Row {
                symbol: $symbol,
                lead: Lead::$lead,
                args: &[$($arg),*],
                ret: $ret,
            }),+];

            /// The host address of the function.
            pub(crate) fn address(self) -> *const u8 {
                match self {
                    $(Helper::$variant => $func as *const u8,)+
                }
            }
        }
    };
}

helpers! {
    SetRange => "stljit_rt_set_range", ffi::stljit_rt_set_range, ImageLayout, [I32, I32, I32, I32, I32, I32, I32] -> I32;
    BlockMove => "stljit_rt_block_move", ffi::stljit_rt_block_move, ImageLayout, [I32, I32, I32, I32, I32, I32] -> I32;
    Fill => "stljit_rt_fill", ffi::stljit_rt_fill, ImageLayout, [I32, I32, I32, I32] -> I32;
    ShiftRegister => "stljit_rt_shift_register", ffi::stljit_rt_shift_register, ImageLayout, [I32, I32, I32, I32, I32, I32] -> I32;
    PointerEnd => "stljit_rt_pointer_end", ffi::stljit_rt_pointer_end, ImageLayout, [I32] -> I32;
    Timer => "stljit_rt_timer", ffi::stljit_rt_timer, ImageLayout, [I32, I32, I32, I32, I32] -> I32;
    TimerReset => "stljit_rt_timer_reset", ffi::stljit_rt_timer_reset, ImageLayout, [I32, I32] -> I32;
    Counter => "stljit_rt_counter", ffi::stljit_rt_counter, ImageLayout, [I32, I32, I32, I32, I32] -> I32;
    CounterReset => "stljit_rt_counter_reset", ffi::stljit_rt_counter_reset, ImageLayout, [I32, I32] -> I32;
    Pointer => "stljit_rt_pointer", ffi::stljit_rt_pointer, ImageLayout, [I32, I32, I32] -> I64;
    /// `stljit_rt_scan_begin(plan, routines, t_ms) -> scan::Begin`.
    ScanBegin => "stljit_rt_scan_begin", ffi::stljit_rt_scan_begin, ImageLayout, [I64, I64, I64] -> I32;
    /// `stljit_rt_scan_steps(plan, routines, instant) -> scan::Begin`: E1, or the events of
    /// the instant.
    ScanSteps => "stljit_rt_scan_steps", ffi::stljit_rt_scan_steps, ImageLayout, [I64, I64, I32] -> I32;
    /// `stljit_rt_watch_changed(watch) -> u32`: whether a watched byte changed (the native
    /// loop's early end, `Engine::run_scans_watching`).
    WatchChanged => "stljit_rt_watch_changed", ffi::stljit_rt_watch_changed, ImageLayout, [I64] -> I32;
    ScanEnd => "stljit_rt_scan_end", ffi::stljit_rt_scan_end, ImageLayout, [I32] -> I32;
    TaskStart => "stljit_rt_task_start", ffi::stljit_rt_task_start, ImageLayout, [] -> I32;
    /// `stljit_rt_interrupt(kind, event, routine)`: ATCH, DTCH, ENI, DISI, CEVNT.
    Interrupt => "stljit_rt_interrupt", ffi::stljit_rt_interrupt, ImageLayout, [I32, I32, I32] -> I32;
    /// `stljit_rt_omron_<kind>_fast(value, flag, state, now, ctl, sv)`: pointers; one shim
    /// per Omron timer kind.
    OmronTimFast => "stljit_rt_omron_tim_fast", ffi::stljit_rt_omron_tim_fast, Nothing, [I64, I64, I64, I64, I32, I32] -> I32;
    OmronTimXFast => "stljit_rt_omron_timx_fast", ffi::stljit_rt_omron_timx_fast, Nothing, [I64, I64, I64, I64, I32, I32] -> I32;
    OmronTimHFast => "stljit_rt_omron_timh_fast", ffi::stljit_rt_omron_timh_fast, Nothing, [I64, I64, I64, I64, I32, I32] -> I32;
    OmronTimHXFast => "stljit_rt_omron_timhx_fast", ffi::stljit_rt_omron_timhx_fast, Nothing, [I64, I64, I64, I64, I32, I32] -> I32;
    OmronTmhhFast => "stljit_rt_omron_tmhh_fast", ffi::stljit_rt_omron_tmhh_fast, Nothing, [I64, I64, I64, I64, I32, I32] -> I32;
    OmronTmhhXFast => "stljit_rt_omron_tmhhx_fast", ffi::stljit_rt_omron_tmhhx_fast, Nothing, [I64, I64, I64, I64, I32, I32] -> I32;
    OmronTtimFast => "stljit_rt_omron_ttim_fast", ffi::stljit_rt_omron_ttim_fast, Nothing, [I64, I64, I64, I64, I32, I32] -> I32;
    OmronTtimXFast => "stljit_rt_omron_ttimx_fast", ffi::stljit_rt_omron_ttimx_fast, Nothing, [I64, I64, I64, I64, I32, I32] -> I32;
    /// `stljit_rt_omron_<kind>_fast(value, flag, state, ctl, sv)`: one per counter kind.
    OmronCntFast => "stljit_rt_omron_cnt_fast", ffi::stljit_rt_omron_cnt_fast, Nothing, [I64, I64, I64, I32, I32] -> I32;
    OmronCntXFast => "stljit_rt_omron_cntx_fast", ffi::stljit_rt_omron_cntx_fast, Nothing, [I64, I64, I64, I32, I32] -> I32;
    OmronCntrFast => "stljit_rt_omron_cntr_fast", ffi::stljit_rt_omron_cntr_fast, Nothing, [I64, I64, I64, I32, I32] -> I32;
    OmronCntrXFast => "stljit_rt_omron_cntrx_fast", ffi::stljit_rt_omron_cntrx_fast, Nothing, [I64, I64, I64, I32, I32] -> I32;
    /// `stljit_rt_omron_arith(op, a, b, cy) -> u64`: pure, no image.
    OmronArith => "stljit_rt_omron_arith", ffi::stljit_rt_omron_arith, Nothing, [I32, I32, I32, I32] -> I64;
    /// `stljit_rt_omron_box_refs(code, lhs_ref, lhs_val, rhs_ref, rhs_val, dst_ref, dst_off, words)`.
    OmronBoxRefs => "stljit_rt_omron_box_refs", ffi::stljit_rt_omron_box_refs, ImageLayout, [I32, I32, I32, I32, I32, I32, I32, I32] -> I32;
    /// `stljit_rt_ext(op, frame, pf) -> u64`: an s7-200-more box, ENO or the error code.
    Ext => "stljit_rt_ext", ffi::stljit_rt_ext, ImageLayout, [I64, I32, I32] -> I64;
    /// `stljit_rt_str_compare(c, frame) -> u64`: the contact's value or the fatal code.
    StrCompare => "stljit_rt_str_compare", ffi::stljit_rt_str_compare, ImageLayout, [I64, I32] -> I64;
    /// `stljit_rt_omron_box(code, a, b, dst)`.
    OmronBox => "stljit_rt_omron_box", ffi::stljit_rt_omron_box, ImageLayout, [I32, I32, I32, I32] -> I32;
}

impl Helper {
    fn row(self) -> &'static Row {
        &Self::ROWS[self as usize]
    }

    /// The symbol name.
    pub(crate) fn name(self) -> &'static str {
        self.row().symbol
    }

    /// Whether the first two arguments are the image and layout pointers.
    pub(crate) fn takes_image(self) -> bool {
        self.row().lead == Lead::ImageLayout
    }

    /// The fast shim of an Omron timer kind.
    pub(crate) fn omron_timer_fast(kind: OmronTimerKind) -> Helper {
        use OmronTimerKind::*;
        match kind {
            Tim => Helper::OmronTimFast,
            TimX => Helper::OmronTimXFast,
            TimH => Helper::OmronTimHFast,
            TimHX => Helper::OmronTimHXFast,
            Tmhh => Helper::OmronTmhhFast,
            TmhhX => Helper::OmronTmhhXFast,
            Ttim => Helper::OmronTtimFast,
            TtimX => Helper::OmronTtimXFast,
        }
    }

    /// The fast shim of an Omron counter kind.
    pub(crate) fn omron_counter_fast(kind: OmronCounterKind) -> Helper {
        use OmronCounterKind::*;
        match kind {
            Cnt => Helper::OmronCntFast,
            CntX => Helper::OmronCntXFast,
            Cntr => Helper::OmronCntrFast,
            CntrX => Helper::OmronCntrXFast,
        }
    }

    /// The full signature.
    pub(crate) fn signature(self, cc: CallConv) -> Signature {
        self.row().signature(cc)
    }
}

impl Row {
    /// The full signature: the lead's arguments, then the row's own.
    fn signature(&self, cc: CallConv) -> Signature {
        signature(cc, self.lead, self.args, self.ret)
    }
}

/// A signature: `lead`'s arguments, then `args`, returning `ret`.
fn signature(cc: CallConv, lead: Lead, args: &[Type], ret: Type) -> Signature {
    let mut s = Signature::new(cc);
    if lead == Lead::ImageLayout {
        s.params.extend([AbiParam::new(I64), AbiParam::new(I64)]);
    }
    s.params.extend(args.iter().map(|t| AbiParam::new(*t)));
    s.returns.push(AbiParam::new(ret));
    s
}

/// Registers every runtime function compiled code may call with the JIT's symbol table: the
/// helpers, and the value shim of each `ffi::ValueOp`.
pub(crate) fn register_symbols(jb: &mut cranelift_jit::JITBuilder) {
    for h in Helper::ALL {
        jb.symbol(h.name(), h.address());
    }
    for (code, shim) in ffi::VALUE_SHIMS.iter().enumerate() {
        jb.symbol(ffi::value_shim_symbol(code as u32), *shim as *const u8);
    }
}

/// Every helper declared in one module.
pub(crate) struct HelperIds {
    /// Indexed by `Helper as usize`.
    ids: Vec<FuncId>,
    /// The value shims, indexed by the operation's code.
    values: Vec<FuncId>,
}

impl HelperIds {
    /// Declares every helper as an imported function.
    pub(crate) fn declare(
        m: &mut impl Module,
    ) -> Result<HelperIds, Box<cranelift_module::ModuleError>> {
        let cc = m.isa().default_call_conv();
        let ids = Helper::ALL
            .iter()
            .map(|h| {
                m.declare_function(h.name(), Linkage::Import, &h.signature(cc))
                    .map_err(Box::new)
            })
            .collect::<Result<_, _>>()?;
        // Every value shim is `ffi::ValueShim`: `(out, in1) -> packed outcome`.
        let sig = signature(cc, Lead::Nothing, &[I32, I32], I64);
        let values = (0..ffi::VALUE_OP_COUNT as u32)
            .map(|code| {
                m.declare_function(&ffi::value_shim_symbol(code), Linkage::Import, &sig)
                    .map_err(Box::new)
            })
            .collect::<Result<_, _>>()?;
        Ok(HelperIds { ids, values })
    }

    /// The id of a helper.
    pub(crate) fn id(&self, h: Helper) -> FuncId {
        self.ids[h as usize]
    }

    /// The id of the value shim of `op`.
    pub(crate) fn value(&self, op: ffi::ValueOp) -> FuncId {
        use ffi::FfiCode;
        self.values[op.ffi_code() as usize]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_is_consistent_with_the_runtime() {
        let doc = include_str!("../../runtime/src/ffi.rs");
        let mut names: Vec<_> = Helper::ALL.iter().map(|h| h.name()).collect();
        for (i, h) in Helper::ALL.iter().enumerate() {
            assert_eq!(*h as usize, i, "ALL is in variant order");
            assert!(h.name().starts_with("stljit_rt_"), "{h:?}");
            assert!(!h.address().is_null(), "{h:?}");
            assert!(
                doc.contains(&format!("`{}(", h.name())),
                "{} missing from the runtime's shim table",
                h.name()
            );
        }
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), Helper::ALL.len(), "symbols are unique");
    }
}
