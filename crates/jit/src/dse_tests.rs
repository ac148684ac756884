//! Tests of [`super::remove_dead_stores`] on small hand-built blocks: which stores go and, as
//! important, which must stay. Each case is a list of memory events in program order.

use super::remove_dead_stores;
use crate::lower::mf;
use cranelift_codegen::ir::{InstBuilder, types::*};

/// One event of a test function `fn(image, other, callee)`.
#[derive(Clone, Copy)]
enum Ev {
    /// A store of `n` (1, 2, 4) bytes at `image + off`.
    St(i32, u8),
    /// The same through `image + 100 + off`, the 100 added by its own `iadd` of a constant.
    StVia100(i32),
    /// A load of `n` bytes at `image + off`.
    Ld(i32, u8),
    /// A store of 2 bytes at `image + i64::MAX + 1` (the sum written as an `iadd` of a
    /// constant and the offset 1), which wraps.
    StMax,
    /// A byte load through the other pointer parameter (it may point into the image).
    LdOther,
    /// An indirect call.
    Call,
    /// The block ends; the rest goes into the next one.
    NewBlock,
}
use Ev::*;

/// Builds the function, runs the pass, returns (stores removed, stores left).
fn run(events: &[Ev]) -> (usize, usize) {
    let mut func = crate::test_fn::build(3, |b, p| {
        let (img, other, callee) = (p[0], p[1], p[2]);
        for &e in events {
            match e {
                St(off, n) => {
                    let ty = [I8, I16, I32][n.trailing_zeros() as usize];
                    let v = b.ins().iconst(ty, 1);
                    b.ins().store(mf(), v, img, off);
                }
                StVia100(off) => {
                    let c = b.ins().iconst(I64, 100);
                    let base = b.ins().iadd(img, c);
                    let v = b.ins().iconst(I32, 1);
                    b.ins().istore8(mf(), v, base, off);
                }
                StMax => {
                    let c = b.ins().iconst(I64, i64::MAX);
                    let base = b.ins().iadd(img, c);
                    let v = b.ins().iconst(I16, 1);
                    b.ins().store(mf(), v, base, 1);
                }
                Ld(off, n) => {
                    let ty = [I8, I16, I32][n.trailing_zeros() as usize];
                    b.ins().load(ty, mf(), img, off);
                }
                LdOther => {
                    b.ins().uload8(I32, mf(), other, 0);
                }
                Call => crate::test_fn::call(b, callee),
                NewBlock => crate::test_fn::next_block(b),
            }
        }
    });
    let removed = remove_dead_stores(&mut func);
    let left = func
        .layout
        .blocks()
        .flat_map(|bl| func.layout.block_insts(bl))
        .filter(|&i| func.dfg.insts[i].opcode().can_store())
        .count();
    (removed, left)
}

#[test]
fn a_byte_stored_twice_keeps_only_the_second_store() {
    assert_eq!(run(&[St(5, 1), St(5, 1)]), (1, 1));
}

#[test]
fn a_load_of_the_byte_between_keeps_both_stores() {
    assert_eq!(run(&[St(5, 1), Ld(5, 1), St(5, 1)]), (0, 2));
    // A wider load that includes it (bytes 2..6) reads it too.
    assert_eq!(run(&[St(5, 1), Ld(2, 4), St(5, 1)]), (0, 2));
}

#[test]
fn loads_of_other_bytes_do_not_matter() {
    // Byte 6, and bytes 3..5.
    assert_eq!(run(&[St(5, 1), Ld(6, 1), Ld(3, 2), St(5, 1)]), (1, 1));
}

#[test]
fn a_store_is_dead_only_when_every_byte_is_overwritten() {
    // Byte 5 inside a later word store of bytes 4..6 goes; that word, of which only byte 5 is
    // stored again, stays.
    assert_eq!(run(&[St(5, 1), St(4, 2), St(5, 1)]), (1, 2));
}

#[test]
fn constant_offsets_in_the_address_are_seen_through() {
    // image + 100 + 4 and image + 104 are the same byte.
    assert_eq!(run(&[StVia100(4), St(104, 1)]), (1, 1));
}

#[test]
fn a_load_through_another_root_may_read_anything() {
    assert_eq!(run(&[St(5, 1), LdOther, St(5, 1)]), (0, 2));
}

#[test]
fn a_call_may_read_anything() {
    assert_eq!(run(&[St(5, 1), Call, St(5, 1)]), (0, 2));
}

#[test]
fn a_store_before_the_block_ends_stays() {
    // The successor (or the caller) sees memory at the block's end.
    assert_eq!(run(&[St(5, 1), NewBlock, St(5, 1)]), (0, 2));
}

#[test]
fn offsets_at_the_end_of_the_address_space_neither_panic_nor_cover_nothing() {
    // image + i64::MAX (an iadd of a constant) + 1 wraps; the byte store there and a store
    // elsewhere are kept, and the pass does not overflow.
    assert_eq!(run(&[StMax, St(5, 1)]), (0, 2));
    assert_eq!(run(&[StMax, StMax]), (1, 1));
}
