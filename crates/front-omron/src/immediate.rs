//! The `!` option, immediate refresh (omron-cp.md §2.5 and §4: "`!LD`, `!OUT` refresh the
//! whole 16-bit word"): before the instruction executes, every source operand in a built-in
//! input word has that whole word copied from the physical inputs into the image; after it,
//! every destination in a built-in output word has that whole image word copied to the physical
//! outputs. Operands elsewhere are not refreshed (no effect, as on expansion I/O).
//!
//! A word copy is the S7 immediate I/O boxes, one per byte: `Box(ImmediateRead)` (physical input
//! byte → image byte) and `Box(ImmediateWrite)` (image byte → image and physical output byte),
//! which run on the power flow. An instruction evaluated in every cycle (a contact, OUT, OUT NOT,
//! KEEP) refreshes whatever its condition: the boxes run on a pushed `P_On` (`Load(P_On); …;
//! Pop`), so only an active interlock or a jump skips them, as it skips the instruction. One
//! that executes only with its condition ON (SET, RSET, the data instructions, `@`/`%` forms)
//! refreshes when it executes: the boxes run on its own power flow.

use crate::lower::Lowerer;
use stljit_core::Area;
use stljit_core::ir::{BitLoc, BoxOp, Contact, Loc, OmronBox, Op, Operand};
use stljit_core::omron::{SystemBit, word_bit};

/// When the refresh of an instruction happens.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Refresh {
    /// Every time the instruction is evaluated (contacts, OUT, OUT NOT, KEEP).
    Always,
    /// When it executes (its power flow is ON).
    WhenExecuted,
}

impl Lowerer<'_> {
    /// Copies the physical input bytes `bytes` (of built-in input words; see [`reads_of_bit`],
    /// [`reads_of_words`], [`data_refresh`]) into the image.
    pub(crate) fn refresh_inputs(&mut self, bytes: Vec<u32>, when: Refresh) {
        self.refresh(
            when,
            bytes.into_iter().map(|b| {
                Op::Box(BoxOp::ImmediateRead {
                    input: b,
                    dst: Operand::Mem(Loc {
                        area: Area::I,
                        offset: b,
                    }),
                })
            }),
        );
    }

    /// Copies the image bytes `bytes` (of built-in output words; see [`writes_of_bit`],
    /// [`data_refresh`]) to the physical outputs.
    pub(crate) fn refresh_outputs(&mut self, bytes: Vec<u32>, when: Refresh) {
        self.refresh(
            when,
            bytes.into_iter().map(|b| {
                Op::Box(BoxOp::ImmediateWrite {
                    src: Operand::Mem(Loc {
                        area: Area::Q,
                        offset: b,
                    }),
                    output: b,
                })
            }),
        );
    }

    fn refresh(&mut self, when: Refresh, boxes: impl Iterator<Item = Op>) {
        let boxes: Vec<Op> = boxes.collect();
        if boxes.is_empty() {
            return;
        }
        let always = when == Refresh::Always;
        if always {
            self.emit(Op::Load(Contact::Bit {
                bit: SystemBit::On.bit_loc(),
                negated: false,
            }));
        }
        for b in boxes {
            self.emit(b);
        }
        if always {
            self.emit(Op::Pop);
        }
    }
}

/// The input bytes `!` refreshes for a contact on `bit`: its word's, if it is an input word.
pub(crate) fn reads_of_bit(bit: BitLoc) -> Vec<u32> {
    io_bytes(&[word_of_bit(bit)], Area::I)
}

/// The output bytes `!` refreshes for a coil on `bit`: its word's, if it is an output word.
pub(crate) fn writes_of_bit(bit: BitLoc) -> Vec<u32> {
    io_bytes(&[word_of_bit(bit)], Area::Q)
}

/// The input bytes `!` refreshes for the operands `ops` of `words` words each (a comparison
/// contact's two sides).
pub(crate) fn reads_of_words(ops: &[Operand], words: u32) -> Vec<u32> {
    let locs: Vec<Loc> = ops.iter().flat_map(|o| words_of(o, words)).collect();
    io_bytes(&locs, Area::I)
}

/// The input bytes a `!` data instruction refreshes before it executes (of its direct source
/// words in input words) and the output bytes it refreshes after (of its destination words in
/// output words). The lowering emits these and the printer reads them back.
pub(crate) fn data_refresh(op: &OmronBox) -> (Vec<u32>, Vec<u32>) {
    let o = op.operands();
    let sources: Vec<Operand> = o.sources.iter().flatten().copied().collect();
    let dst = o.dst.map_or_else(Vec::new, |d| words_of(&d, o.dst_words));
    (
        reads_of_words(&sources, o.src_words),
        io_bytes(&dst, Area::Q),
    )
}

/// The word a bit operand is in.
fn word_of_bit(bit: BitLoc) -> Loc {
    word_bit(bit).0
}

/// The words of a direct word operand of `words` words (a double word is two).
fn words_of(o: &Operand, words: u32) -> Vec<Loc> {
    match *o {
        Operand::Mem(loc) => (0..words)
            .map(|i| Loc {
                area: loc.area,
                offset: loc.offset + 2 * i,
            })
            .collect(),
        _ => Vec::new(),
    }
}

/// The bytes of the words in `area` among `words`, each once, in order.
fn io_bytes(words: &[Loc], area: Area) -> Vec<u32> {
    let mut bytes: Vec<u32> = words
        .iter()
        .filter(|w| w.area == area)
        .flat_map(|w| [w.offset, w.offset + 1])
        .collect();
    bytes.sort_unstable();
    bytes.dedup();
    bytes
}
