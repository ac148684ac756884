//! Resident bits: image bytes that compiled code keeps one byte per bit while it runs.
//!
//! The image packs eight bits into a byte, so a contact on a bit costs a load, an alignment and
//! the `and`/`or`, and a coil a read-modify-write of its byte (five or six instructions). C
//! that keeps one byte per boolean (matiec's, `../shared/bench/vs-gcc`) pays one instruction
//! for either. Packing cannot be given up: the image is what every engine, the driver, the
//! API and the FMU read. But inside one call of the native loop nothing else reads most of the
//! bytes that bit logic works on, so the compiled code keeps those in a *shadow*: one byte per
//! bit (bit 0 holds the value, bits 1–7 are garbage, as in a [`B`](crate::lower::value::B)),
//! in the image's engine scratch (`Image::bytes_and_scratch`), at a fixed offset from the
//! image's first byte, so that the code reaches it through the image pointer it already holds.
//!
//! **Rule** ([`Resident::plan`]). A byte is resident when
//! - the program is of the S7 family, every op of every POU has a memory footprint that its
//!   operands state exactly (no pointers, block moves, tables, strings, communication, pulse
//!   profiles, shift registers or call parameters: any of these makes no byte resident), and
//! - the byte is in Q, M or V, some op names one of its bits directly (a contact, a coil,
//!   `S`/`R` with a constant count that is written inline), and no op names it as part of a
//!   value operand (a byte, word or double word, at any width) or may touch it through an
//!   `S`/`R` that the runtime runs (a count from memory, a long range).
//!
//! A byte of I or Q named by one op only stays in the image ([`MIN_USES`]), and at most
//! [`MAX_BYTES`] bytes are resident (the lowest), so the shadow stays in the L1 cache.
//!
//! **Invariant.** While the native loop runs, the shadow holds the resident bytes and their
//! image bytes are stale; at every point outside it the image holds them. The loop packs the
//! bytes of M and V that some op writes on every exit and before a change watch compares bytes
//! (`scan_loop`), those of Q at the end of every scan (the epilogue copies Q to the physical
//! outputs, and a scan's end is the only place the runtime reads Q), and unpacks all of them on
//! entry unless the shadow still holds them (its flag, which the engine sets from
//! `Image::version`). Nothing else inside the loop reads or writes Q, M or V but compiled code
//! and the runtime helpers it calls with its operands' addresses, and the rule keeps those
//! bytes out; compiled interrupt routines that the runtime calls back run on the same shadow.
//! The runtime writes the physical output copy, never Q itself.
//!
//! Packing costs about two instructions per written byte on every call, which a program of a
//! thousand bit instructions earns back many times over in a scan (`docs/performance.md`).

use cranelift_codegen::ir::{
    ConstantData, Endianness, InstBuilder, MemFlagsData, Value,
    condcodes::IntCC,
    types::{I8X16, I16X8, I32, I32X4, I64},
};
use cranelift_frontend::FunctionBuilder;
use std::collections::{BTreeMap, BTreeSet, HashMap};
use stljit_core::ir::{Access, BitLoc, BoxOp, Op, Operand, Program};
use stljit_core::layout::Layout;
use stljit_core::{Area, Family};

use crate::lower::bits::MAX_INLINE_RANGE;

/// The areas whose bytes may be resident: the runtime touches them only through operands, but
/// for Q, which the scan's epilogue reads (`scan::end`, the inline output copy), so the loop
/// packs Q's written bytes at the end of every scan.
const AREAS: [Area; 4] = [Area::I, Area::Q, Area::M, Area::V];

/// A byte of I or Q is resident only if at least this many ops name its bits: it costs an
/// unpack or pack of a few instructions every scan, and a single access saves about as much
/// (the empty program's one coil on Q0 was a nanosecond slower resident). M and V are packed
/// once per run, which one access already repays.
const MIN_USES: usize = 2;

/// At most this many resident bytes (a shadow of 32 KiB).
pub(crate) const MAX_BYTES: usize = 4096;

/// The resident bytes of a program and where each one's bits sit in the shadow.
///
/// The shadow's first eight bytes are a `u32` flag the engine sets before each run, non-zero
/// when the shadow still holds the image's resident bytes (the image is the one the last run
/// packed them into, unchanged since: `Image::version`), so the run need not unpack them; and
/// the first-scan mask ([`Resident::first_scan_mask`]).
#[derive(Clone, Debug, Default)]
pub(crate) struct Resident {
    /// The resident bytes, those some op writes first, each part in image order; byte `k`'s
    /// bit `i` is shadow byte `8 (k + 1) + i` (after the flag).
    bytes: Vec<(Area, u32)>,
    /// How many of `bytes` some op writes (only those are packed); the first `outputs` of them
    /// are Q's.
    written: usize,
    /// How many written bytes are Q's (packed at the end of every scan).
    outputs: usize,
    /// How many bytes after the written ones are I's (unpacked at the start of every scan).
    inputs: usize,
    /// The shadow's offset from the image's first byte (in the image's scratch, 8-aligned).
    start: u32,
    slot: HashMap<(Area, u32), u32>,
    /// Whether the shadow keeps the first-scan mask ([`Resident::first_scan_mask`]).
    mask: bool,
}

impl Resident {
    /// Applies the rule (module docs) to `prog`.
    pub(crate) fn plan(prog: &Program, layout: &Layout) -> Resident {
        Resident::plan_with(prog, layout, MIN_USES)
    }

    /// [`Resident::plan`] with bytes named by `min_uses` ops or more.
    fn plan_with(prog: &Program, layout: &Layout, min_uses: usize) -> Resident {
        if prog.profile.profile().family != Family::S7 {
            return Resident::default();
        }
        // How many ops name each byte's bits.
        let mut named: BTreeMap<(Area, u32), usize> = BTreeMap::new();
        let mut written = BTreeSet::new();
        let mut excluded = BTreeSet::new();
        let area_end = |area: Area| layout.area_size(area);
        for op in prog.pous.iter().flat_map(|p| &p.ops) {
            if !op.footprint_stated() {
                return Resident::default();
            }
            for u in op.operand_uses().iter() {
                match u.operand {
                    Operand::Const(_) => {}
                    Operand::Mem(loc) => {
                        for off in loc.offset..loc.offset + u.width.bytes() {
                            excluded.insert((loc.area, off));
                        }
                    }
                    Operand::Indirect(_) | Operand::AddressOf(_) | Operand::Omron(_) => {
                        return Resident::default();
                    }
                }
            }
            match op {
                Op::SetRange { start, count, .. } => match *count {
                    Operand::Const(k) if k & 0xFF <= MAX_INLINE_RANGE => {
                        let bits = (k & 0xFF) + u32::from(start.bit);
                        let last =
                            (start.byte + bits.saturating_sub(1) / 8).min(area_end(start.area));
                        for b in start.byte..=last {
                            *named.entry((start.area, b)).or_default() += 1;
                        }
                        written.extend((start.byte..=last).map(|b| (start.area, b)));
                    }
                    _ => {
                        excluded.extend((start.byte..area_end(start.area)).map(|b| (start.area, b)))
                    }
                },
                // `BIW` writes its Q byte as well as the physical output.
                Op::Box(BoxOp::ImmediateWrite { output, .. }) => {
                    excluded.insert((Area::Q, *output));
                }
                _ => {
                    for (bit, access) in op.bit_uses() {
                        *named.entry((bit.area, bit.byte)).or_default() += 1;
                        if access != Access::Read {
                            written.insert((bit.area, bit.byte));
                        }
                    }
                }
            }
        }
        // I: the prologue copies the inputs into it every scan, so the loop unpacks I's resident
        // bytes after it, and the program must never write them. In the runtime's prologue
        // the routines of the instant run after that copy and before the unpack, so a program
        // with interrupt routines keeps I in the image.
        let inputs_ok = |byte: u32| !written.contains(&(Area::I, byte)) && !prog.has_interrupts();
        let chosen: Vec<(Area, u32)> = named
            .into_iter()
            .filter(|&((area, _), uses)| !matches!(area, Area::I | Area::Q) || uses >= min_uses)
            .map(|(ab, _)| ab)
            .filter(|(area, byte)| {
                AREAS.contains(area)
                    && *byte < area_end(*area)
                    && !excluded.contains(&(*area, *byte))
                    && (*area != Area::I || inputs_ok(*byte))
            })
            .take(MAX_BYTES)
            .collect();
        let (mut bytes, read_only): (Vec<_>, Vec<_>) =
            chosen.into_iter().partition(|ab| written.contains(ab));
        let written = bytes.len();
        // Areas in image order, so Q's written bytes come first.
        let outputs = bytes
            .iter()
            .take_while(|(area, _)| *area == Area::Q)
            .count();
        let inputs = read_only
            .iter()
            .take_while(|(area, _)| *area == Area::I)
            .count();
        bytes.extend(read_only);
        let start = layout.size.next_multiple_of(8);
        let slot = bytes
            .iter()
            .enumerate()
            .map(|(k, &ab)| (ab, start + 8 * (k as u32 + 1)))
            .collect();
        // Interrupt routines may run inside the runtime's prologue, before the loop sets the
        // mask, and call subroutines that main calls too.
        let mask = !bytes.is_empty() && !prog.has_interrupts();
        Resident {
            bytes,
            written,
            outputs,
            inputs,
            start,
            slot,
            mask,
        }
    }

    /// The number of resident bytes.
    pub(crate) fn len(&self) -> usize {
        self.bytes.len()
    }

    /// The image scratch the shadow needs (`Image::bytes_and_scratch`): the padding to an
    /// 8-byte boundary, the flag, eight bytes per resident byte, and eight more so that a
    /// 32-bit load of any shadow byte stays inside ([`crate::lower::bits`]).
    pub(crate) fn scratch(&self, layout: &Layout) -> usize {
        (self.end() - layout.size) as usize
    }

    /// The offset just past the scratch the shadow needs.
    pub(crate) fn end(&self) -> u32 {
        self.start + 8 * (self.bytes.len() as u32 + 2)
    }

    /// The flag's offset from the image's first byte.
    pub(crate) fn flag_offset(&self) -> usize {
        self.start as usize
    }

    /// The offset of the first-scan mask, if the shadow keeps one: an `i32` beside the flag,
    /// all ones in every scan but the first after entering RUN, 0 in that one (spec §2.2). The
    /// loop sets it before each scan's program runs; an edge ANDs it in with one instruction
    /// where reading `Sched::FIRST_SCAN` and clearing with it take two. Only in programs
    /// without interrupt routines, which the runtime's prologue runs before the loop sets it.
    pub(crate) fn first_scan_mask(&self) -> Option<i32> {
        self.mask.then_some(self.start as i32 + 4)
    }

    /// The shadow offset of `bit`, if its byte is resident.
    pub(crate) fn slot(&self, bit: BitLoc) -> Option<i32> {
        self.slot
            .get(&(bit.area, bit.byte))
            .map(|s| (s + u32::from(bit.bit)) as i32)
    }

    /// Whether `bit`'s byte is resident.
    pub(crate) fn holds(&self, bit: BitLoc) -> bool {
        self.slot.contains_key(&(bit.area, bit.byte))
    }

    /// Copies every resident byte from the image into the shadow, unless the shadow's flag
    /// says it holds them already: byte `b` becomes eight bytes whose bit 0 is bit `i` of `b`
    /// (`((b · 0x0101…01) AND 0x8040…01) + 0x7F7F…7F` puts bit `i` at bit 7 of byte `i`
    /// without carries between bytes, then a shift by 7). The builder continues in a new
    /// block.
    pub(crate) fn emit_unpack(&self, b: &mut FunctionBuilder<'_>, layout: &Layout, image: Value) {
        if self.bytes.is_empty() {
            return;
        }
        let (unpack, done) = (b.create_block(), b.create_block());
        let held = b.ins().load(I32, flags(), image, self.start as i32);
        b.ins().brif(held, done, &[], unpack, &[]);
        b.switch_to_block(unpack);
        self.unpack_range(b, layout, image, 0..self.bytes.len());
        b.ins().jump(done, &[]);
        b.switch_to_block(done);
    }

    /// Copies I's resident bytes from the image into the shadow, after the scan's prologue
    /// copied the inputs into I.
    pub(crate) fn emit_unpack_inputs(
        &self,
        b: &mut FunctionBuilder<'_>,
        layout: &Layout,
        image: Value,
    ) {
        self.unpack_range(b, layout, image, self.written..self.written + self.inputs);
    }

    /// The shadow offset of `bytes[k]`'s bit 0 (after the flag).
    fn shadow_at(&self, k: usize) -> i32 {
        (self.start as usize + 8 * (k + 1)) as i32
    }

    /// The image offset of `bytes[k]`.
    fn image_at(&self, layout: &Layout, k: usize) -> i32 {
        let (area, byte) = self.bytes[k];
        (layout.base(area) + byte) as i32
    }

    /// Unpacks `bytes[range]` (see [`Resident::emit_unpack`]). Two neighbours in the image at
    /// a time where they are also neighbours here: their 16-bit word spread over sixteen bytes
    /// (`pshufb`), each byte's own bit picked and compared with it (0xFF where set).
    fn unpack_range(
        &self,
        b: &mut FunctionBuilder<'_>,
        layout: &Layout,
        image: Value,
        range: std::ops::Range<usize>,
    ) {
        let mut pair_consts = None;
        let mut k = range.start;
        while k < range.end {
            if k + 1 < range.end && self.image_at(layout, k + 1) == self.image_at(layout, k) + 1 {
                let (spread_mask, bit_of) = *pair_consts.get_or_insert_with(|| {
                    let spread: Vec<u8> = (0..16).map(|i| i / 8).collect();
                    let bits: Vec<u8> = (0..16).map(|i| 1 << (i % 8)).collect();
                    let spread = b.func.dfg.immediates.push(ConstantData::from(spread));
                    let bits = b.func.dfg.constants.insert(ConstantData::from(bits));
                    (spread, b.ins().vconst(I8X16, bits))
                });
                let word = b
                    .ins()
                    .uload16(I32, flags(), image, self.image_at(layout, k));
                let v = b.ins().scalar_to_vector(I32X4, word);
                let v = b.ins().bitcast(I8X16, lanes(), v);
                let spread = b.ins().shuffle(v, v, spread_mask);
                let picked = b.ins().band(spread, bit_of);
                let set = b.ins().icmp(IntCC::Equal, picked, bit_of);
                b.ins().store(flags(), set, image, self.shadow_at(k));
                k += 2;
            } else {
                let v = b
                    .ins()
                    .uload8(I64, flags(), image, self.image_at(layout, k));
                let spread = b.ins().imul_imm_s(v, 0x0101_0101_0101_0101);
                let picked = b.ins().band_imm_s(spread, 0x8040_2010_0804_0201_u64 as i64);
                let high = b.ins().iadd_imm_s(picked, 0x7F7F_7F7F_7F7F_7F7F);
                let bits = b.ins().ushr_imm_s(high, 7);
                b.ins().store(flags(), bits, image, self.shadow_at(k));
                k += 1;
            }
        }
    }

    /// Copies the resident bytes of M and V that some op writes from the shadow back into the
    /// image (the others never change there), where the loop ends or a watch compares.
    pub(crate) fn emit_pack(&self, b: &mut FunctionBuilder<'_>, layout: &Layout, image: Value) {
        self.pack_range(b, layout, image, self.outputs..self.written);
    }

    /// The same for Q's written resident bytes, before the scan's epilogue copies Q.
    pub(crate) fn emit_pack_outputs(
        &self,
        b: &mut FunctionBuilder<'_>,
        layout: &Layout,
        image: Value,
    ) {
        self.pack_range(b, layout, image, 0..self.outputs);
    }

    /// Packs `bytes[range]`. Two at a time: their sixteen shadow bytes shifted left by 7 (bit 0
    /// to the sign bit) and gathered by `pmovmskb`, stored as one 16-bit word where the two
    /// bytes are neighbours in the image. A last odd one: bit 0 of each of its eight bytes
    /// gathered into the top byte by one multiplication (`(x AND 0x0101…01) ·
    /// 0x0102040810204080`, no two partial products meet there).
    fn pack_range(
        &self,
        b: &mut FunctionBuilder<'_>,
        layout: &Layout,
        image: Value,
        range: std::ops::Range<usize>,
    ) {
        let mut k = range.start;
        while k + 1 < range.end {
            let v = b.ins().load(I8X16, flags(), image, self.shadow_at(k));
            let words = b.ins().bitcast(I16X8, lanes(), v);
            let signs = b.ins().ishl_imm_s(words, 7);
            let bytes = b.ins().bitcast(I8X16, lanes(), signs);
            let mask = b.ins().vhigh_bits(I32, bytes);
            let (lo, hi) = (self.image_at(layout, k), self.image_at(layout, k + 1));
            if hi == lo + 1 {
                b.ins().istore16(flags(), mask, image, lo);
            } else {
                b.ins().istore8(flags(), mask, image, lo);
                let upper = b.ins().ushr_imm_s(mask, 8);
                b.ins().istore8(flags(), upper, image, hi);
            }
            k += 2;
        }
        if k < range.end {
            let x = b.ins().load(I64, flags(), image, self.shadow_at(k));
            let bits = b.ins().band_imm_s(x, 0x0101_0101_0101_0101);
            let gathered = b.ins().imul_imm_s(bits, 0x0102_0408_1020_4080);
            let v = b.ins().ushr_imm_s(gathered, 56);
            b.ins().istore8(flags(), v, image, self.image_at(layout, k));
        }
    }
}

fn flags() -> MemFlagsData {
    MemFlagsData::new().with_notrap()
}

/// Lane order for bitcasts between vector types.
fn lanes() -> MemFlagsData {
    MemFlagsData::new().with_endianness(Endianness::Little)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The resident bytes of `text` (area, byte, written), for bytes named once or more.
    fn plan(text: &str) -> Vec<(Area, u32, bool)> {
        plan_min(text, 1)
    }

    fn plan_min(text: &str, min_uses: usize) -> Vec<(Area, u32, bool)> {
        let c = stljit_front_s7::compile_str("t.stl", text, stljit_core::ProfileId::A5);
        let prog = c.program.expect("compiles");
        let r = Resident::plan_with(&prog, &Layout::of(prog.profile), min_uses);
        let written = r.written;
        r.bytes
            .iter()
            .enumerate()
            .map(|(k, &(area, byte))| (area, byte, k < written))
            .collect()
    }

    #[test]
    fn bits_of_i_q_m_and_v_are_resident_written_ones_first() {
        assert_eq!(
            plan("LD I0.0\nA M3.1\nA V7.0\n= M0.1\n= Q0.0\nLD V9.7\nS V4.6, 3\nA Q1.0\n"),
            [
                (Area::Q, 0, true),
                (Area::M, 0, true),
                (Area::V, 4, true),
                (Area::V, 5, true),
                (Area::I, 0, false),
                (Area::Q, 1, false),
                (Area::M, 3, false),
                (Area::V, 7, false),
                (Area::V, 9, false),
            ]
        );
    }

    #[test]
    fn a_byte_of_i_or_q_named_once_stays_in_the_image() {
        // Q0 and I0 once each, Q1 twice, M0 and V0 once each.
        let text = "LD I0.0\n= Q0.0\n= Q1.0\n= Q1.1\nLD V0.0\n= M0.1\n";
        assert_eq!(
            plan_min(text, MIN_USES),
            [(Area::Q, 1, true), (Area::M, 0, true), (Area::V, 0, false)]
        );
    }

    #[test]
    fn bytes_named_as_values_stay_in_the_image() {
        // VW2 covers V2 and V3, MB0 covers M0, a byte compare VB5.
        assert_eq!(
            plan(
                "LD V2.0\n= V3.1\n= V4.0\nMOVW 1, VW2\nLD M0.0\n= M1.0\nINCB MB0\nLDB= VB5, 1\n= V5.5\n"
            ),
            [(Area::M, 1, true), (Area::V, 4, true)]
        );
    }

    #[test]
    fn a_count_from_memory_keeps_the_rest_of_the_area_out() {
        // M2 up to M31 may be set; M0 and M1 lie before the range.
        assert_eq!(
            plan("LD M0.0\n= M1.0\n= M5.0\nS M2.0, MB9\n"),
            [(Area::M, 1, true), (Area::M, 0, false)]
        );
    }

    #[test]
    fn pointers_and_runs_make_nothing_resident() {
        for text in [
            "LD M0.0\n= M1.0\nMOVD &VB0, VD100\n",
            "LD M0.0\n= M1.0\nMOVB *VD100, MB10\n",
            "LD M0.0\n= M1.0\nBMB VB0, VB10, 4\n",
            "LD M0.0\n= M1.0\nFILL 0, VW0, 4\n",
            "LD M0.0\n= M1.0\nSHRB M0.1, V0.0, 4\n",
        ] {
            assert_eq!(plan(text), [], "{text}");
        }
    }

    #[test]
    fn inputs_are_resident_unless_written_or_read_by_interrupt_routines() {
        // `= I1.0` writes I1 (the next input copy overwrites it).
        assert_eq!(
            plan("LD I0.0\n= I1.0\n= M0.0\nLD I1.1\n= M0.1\n"),
            [(Area::M, 0, true), (Area::I, 0, false)]
        );
        let with_routine = "LD I0.0\n= M0.0\nLD SM0.1\nATCH INT_0, 10\nENI\nMEND\n\
                            INT 0\nLD I0.1\n= M0.1\n";
        assert_eq!(plan(with_routine), [(Area::M, 0, true)]);
    }

    #[test]
    fn the_first_scan_mask_is_kept_with_a_shadow_and_no_interrupt_routine() {
        let mask = |text: &str| {
            let c = stljit_front_s7::compile_str("t.stl", text, stljit_core::ProfileId::A5);
            let prog = c.program.expect("compiles");
            Resident::plan(&prog, &Layout::of(prog.profile)).first_scan_mask()
        };
        let r = {
            let c = stljit_front_s7::compile_str(
                "t.stl",
                "LD M0.0\nEU\n= M1.0\n",
                stljit_core::ProfileId::A5,
            );
            let prog = c.program.expect("compiles");
            Resident::plan(&prog, &Layout::of(prog.profile))
        };
        // Beside the flag, inside the scratch the shadow asks for.
        assert_eq!(r.first_scan_mask(), Some(r.flag_offset() as i32 + 4));
        assert!(r.first_scan_mask().unwrap() as u32 + 4 <= r.end());
        // No resident byte (I0 is named once): no shadow, no mask.
        assert_eq!(mask("LD I0.0\nEU\nMOVB 1, MB1\n"), None);
        // The runtime's prologue may run a routine with an edge before the loop sets it.
        let with_routine = "LD M0.0\nEU\n= M1.0\nLD SM0.1\nATCH INT_0, 10\nENI\nMEND\n\
                            INT 0\nLD M0.1\nEU\n= M1.1\n";
        assert_eq!(mask(with_routine), None);
    }

    #[test]
    fn what_the_runtime_writes_stays_in_the_image() {
        // A range past the inline limit is the runtime's; BIW writes QB7 itself.
        assert_eq!(
            plan("LD M0.0\n= M1.0\nS M2.0, 65\n= Q7.0\n= Q6.0\nBIW 18, QB7\n"),
            [(Area::Q, 6, true), (Area::M, 1, true), (Area::M, 0, false)]
        );
    }
}
