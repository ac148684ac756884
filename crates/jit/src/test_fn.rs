//! Hand-built Cranelift functions for the tests of the passes that run on lowered functions
//! ([`crate::dse`], [`crate::rebase`]).

use cranelift_codegen::ir::{
    AbiParam, Function, InstBuilder, Signature, UserFuncName, Value, types::I64,
};
use cranelift_codegen::isa::{CallConv, TargetFrontendConfig};
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext};

/// Builds `fn(i64 × params)`: `body` fills it from the entry block on (it may add blocks),
/// then a `return` ends the current block and the function is finalised.
pub(crate) fn build(params: usize, body: impl FnOnce(&mut FunctionBuilder, &[Value])) -> Function {
    let mut sig = Signature::new(CallConv::SystemV);
    sig.params = vec![AbiParam::new(I64); params];
    let mut func = Function::with_name_signature(UserFuncName::user(0, 0), sig);
    let mut ctx = FunctionBuilderContext::new();
    let mut b = FunctionBuilder::new(&mut func, &mut ctx);
    let entry = b.create_block();
    b.append_block_params_for_function_params(entry);
    b.switch_to_block(entry);
    let p = b.block_params(entry).to_vec();
    body(&mut b, &p);
    b.ins().return_(&[]);
    b.seal_all_blocks();
    b.finalize(TargetFrontendConfig {
        default_call_conv: CallConv::SystemV,
        pointer_width: target_lexicon::PointerWidth::U64,
        page_size_align_log2: 12,
    });
    func
}

/// Emits an indirect call of `callee` with no arguments (a call the passes must respect).
pub(crate) fn call(b: &mut FunctionBuilder, callee: Value) {
    let sig = b.import_signature(Signature::new(CallConv::SystemV));
    b.ins().call_indirect(sig, callee, &[]);
}

/// Ends the current block with a jump to a new one, which it continues in.
pub(crate) fn next_block(b: &mut FunctionBuilder) {
    let next = b.create_block();
    b.ins().jump(next, &[]);
    b.switch_to_block(next);
}
