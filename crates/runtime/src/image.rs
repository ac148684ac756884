//! The memory image: one flat byte buffer of [`Layout::size`] bytes plus its [`Layout`].
//!
//! The interpreter works on an [`Image`] directly; the JIT hands [`Image::bytes_mut`] to native
//! code. Everything observable (areas, timer/counter/edge state, scan bookkeeping, physical I/O
//! copies) lives in the bytes, so two engines agree exactly when their byte buffers are equal.

use crate::mem;
use std::fmt;
use stljit_core::ir::{BitLoc, Loc, Program};
use stljit_core::layout::CounterState;
use stljit_core::layout::{DEFAULT_LOOP_LIMIT, L_FRAMES, Layout, Sched, TimerState};
use stljit_core::{Area, ProfileId, Width};

/// An access that does not fit its area.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageError {
    /// `offset + width` runs past the end of `area` (or the L frame does not exist).
    OutOfRange {
        /// The area.
        area: Area,
        /// The first byte.
        offset: u32,
        /// Bytes accessed.
        len: u32,
    },
}

impl fmt::Display for ImageError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ImageError::OutOfRange { area, offset, len } => {
                write!(
                    f,
                    "{len} byte(s) at {area:?} byte {offset} run past the end of the area"
                )
            }
        }
    }
}

impl std::error::Error for ImageError {}

/// Image offset of `len` bytes at `offset` of `area` (L: in frame `frame`), or `None` when they do
/// not fit the area. This is the one bounds rule every direct access goes through.
#[inline]
pub fn area_span(layout: &Layout, area: Area, offset: u32, len: u32, frame: u32) -> Option<u32> {
    let end = offset.checked_add(len)?;
    if end > layout.area_size(area) || (area == Area::L && frame >= L_FRAMES) {
        return None;
    }
    Some(layout.addr(area, offset, frame))
}

/// Image offset of a value at `loc` of `width` (L: in frame `frame`), bounds-checked.
#[inline]
pub fn loc_addr(layout: &Layout, loc: Loc, width: Width, frame: u32) -> Option<u32> {
    area_span(layout, loc.area, loc.offset, width.bytes(), frame)
}

/// Image offset of the byte holding `bit` (L: in frame `frame`), bounds-checked.
#[inline]
pub fn bit_addr(layout: &Layout, bit: BitLoc, frame: u32) -> Option<u32> {
    if bit.bit > 7 {
        return None;
    }
    area_span(layout, bit.area, bit.byte, 1, frame)
}

/// The flat memory image of one PLC.
///
/// Two images are equal when their bytes and layouts are; the [`Image::version`] is not part of
/// the value.
#[derive(Clone, Debug)]
pub struct Image {
    /// The image's `layout.size` bytes, then the engine scratch ([`Image::bytes_and_scratch`]).
    buf: Vec<u8>,
    layout: Layout,
    /// See [`Image::version`].
    version: u64,
}

impl PartialEq for Image {
    fn eq(&self, other: &Image) -> bool {
        self.bytes() == other.bytes() && self.layout == other.layout
    }
}

impl Eq for Image {}

impl Image {
    /// A zeroed image for `profile` with the scheduler defaults of a cold start (first scan,
    /// default loop budget, SCR gate open) but no timers, counters or edges declared.
    pub fn blank(profile: ProfileId) -> Image {
        let layout = Layout::of(profile);
        let mut img = Image {
            buf: vec![0; layout.size as usize],
            layout,
            version: 0,
        };
        img.set_sched_u8(Sched::FIRST_SCAN, 1);
        img.set_sched_u8(Sched::SCR_ENABLE, 1);
        img.set_loop_limit(DEFAULT_LOOP_LIMIT);
        img
    }

    /// The power-up image of `program` (spec §1.7 cold start): everything 0 except each used
    /// timer's KIND and RES bytes, each used counter's KIND byte, the edge memories' initial
    /// values, the initial V values of its data block (`Program::data`, in order),
    /// FIRST_SCAN = 1, LOOP_LIMIT = [`DEFAULT_LOOP_LIMIT`] and SCR_ENABLE = 1. The clock starts
    /// at 2000-01-01 00:00:00 ([`Image::set_clock_start`] sets another date).
    /// Declarations naming a timer, counter or slot the profile lacks are ignored (the front end
    /// rejects them; an engine must not crash on them either).
    pub fn cold_start(program: &Program) -> Image {
        let mut img = Image::blank(program.profile);
        let l = img.layout.clone();
        let profile = program.profile.profile();
        for t in &program.timers {
            if t.id.0 < profile.timers {
                let at = l.timer_state(t.id.0);
                mem::set_u8(img.img_mut(), at + TimerState::KIND, t.kind.code());
                let res = t.resolution.millis() as u8;
                mem::set_u8(img.img_mut(), at + TimerState::RES, res);
            }
        }
        for c in &program.counters {
            if c.id.0 < profile.counters {
                let at = l.counter_state(c.id.0) + CounterState::KIND;
                mem::set_u8(img.img_mut(), at, c.kind.code());
            }
        }
        for (slot, e) in program.edges.iter().enumerate() {
            if slot < usize::from(profile.max_edges) {
                mem::set_u8(img.img_mut(), l.edges + slot as u32, u8::from(e.init));
            }
        }
        let (v, v_size) = (l.base(Area::V) as usize, l.area_size(Area::V) as usize);
        for d in &program.data {
            // The verifier keeps runs inside V; one that is not is left out, never a panic.
            let start = d.offset as usize;
            if start.saturating_add(d.bytes.len()) <= v_size {
                img.img_mut()[v + start..v + start + d.bytes.len()].copy_from_slice(&d.bytes);
            }
        }
        img
    }

    /// Sets the date and time the real-time clock shows at t = 0 (before the first scan;
    /// s7-200-more §6.2 `rtc_start`). Nothing on a profile without the clock's state.
    pub fn set_clock_start(&mut self, start: crate::rtc::DateTime) {
        self.version = 0;
        let (b, l) = self.parts_mut();
        crate::rtc::set_start(b, l, start);
    }

    /// The image's bytes (`layout.size` of them; the scratch is not part of the image).
    fn img(&self) -> &[u8] {
        &self.buf[..self.layout.size as usize]
    }

    fn img_mut(&mut self) -> &mut [u8] {
        &mut self.buf[..self.layout.size as usize]
    }

    /// The raw bytes.
    pub fn bytes(&self) -> &[u8] {
        self.img()
    }

    /// The raw bytes, mutable (what engines execute on).
    pub fn bytes_mut(&mut self) -> &mut [u8] {
        self.version = 0;
        self.img_mut()
    }

    /// A tag an engine may set on the image ([`Image::set_version`]) to recognise it later
    /// unchanged: every method that may change bytes a program addresses sets it back to 0
    /// (`bytes_mut`, `split_mut`, `write`, `set_bit` and the harness's stimuli), all but the
    /// physical input copy ([`Image::set_inputs`], [`Image::phys_in_mut`]), which a program
    /// only sees through the next scan's input copy, and the scheduler fields. The compiled
    /// engine tags an image after each run so that the next run on it can keep the bit copies
    /// it holds (`stljit_jit`'s resident bits) instead of reading them from the bytes again.
    pub fn version(&self) -> u64 {
        self.version
    }

    /// Tags the image (see [`Image::version`]).
    pub fn set_version(&mut self, version: u64) {
        self.version = version;
    }

    /// The layout the bytes follow.
    pub fn layout(&self) -> &Layout {
        &self.layout
    }

    /// Both at once, for engines that read the layout while writing the bytes.
    pub fn split_mut(&mut self) -> (&mut [u8], &Layout) {
        self.version = 0;
        self.parts_mut()
    }

    /// Both, without touching the version (for the methods that set it themselves).
    fn parts_mut(&mut self) -> (&mut [u8], &Layout) {
        (&mut self.buf[..self.layout.size as usize], &self.layout)
    }

    /// The raw bytes followed by at least `scratch` bytes of engine scratch space (zeroed
    /// when first made): memory an engine keeps with the image between its runs, at a fixed
    /// distance from the bytes, which nothing else reads or writes and which is no part of
    /// the image's value (not in [`Image::bytes`], not compared; a clone copies it). The
    /// compiled engine keeps its resident bits there. Resets the [`Image::version`], like
    /// [`Image::bytes_mut`].
    pub fn bytes_and_scratch(&mut self, scratch: usize) -> &mut [u8] {
        self.version = 0;
        let want = self.layout.size as usize + scratch;
        if self.buf.len() < want {
            self.buf.resize(want, 0);
        }
        &mut self.buf
    }

    // ---- typed access ----------------------------------------------------------------------

    /// Reads a big-endian value at `loc` (L: in frame `frame`), zero-extended.
    pub fn read(&self, loc: Loc, width: Width, frame: u32) -> Result<u32, ImageError> {
        let at = self.checked(loc, width, frame)?;
        Ok(mem::get_be(self.img(), at, width))
    }

    /// Writes the low bits of `value` big-endian at `loc`.
    pub fn write(
        &mut self,
        loc: Loc,
        width: Width,
        frame: u32,
        value: u32,
    ) -> Result<(), ImageError> {
        let at = self.checked(loc, width, frame)?;
        self.version = 0;
        mem::set_be(self.img_mut(), at, width, value);
        Ok(())
    }

    /// Reads a bit.
    pub fn bit(&self, bit: BitLoc, frame: u32) -> Result<bool, ImageError> {
        let at = self.checked_bit(bit, frame)?;
        Ok(mem::get_bit(self.img(), at, bit.bit))
    }

    /// Writes a bit.
    pub fn set_bit(&mut self, bit: BitLoc, frame: u32, value: bool) -> Result<(), ImageError> {
        let at = self.checked_bit(bit, frame)?;
        self.version = 0;
        mem::set_bit(self.img_mut(), at, bit.bit, value);
        Ok(())
    }

    fn checked(&self, loc: Loc, width: Width, frame: u32) -> Result<u32, ImageError> {
        loc_addr(&self.layout, loc, width, frame).ok_or(ImageError::OutOfRange {
            area: loc.area,
            offset: loc.offset,
            len: width.bytes(),
        })
    }

    fn checked_bit(&self, bit: BitLoc, frame: u32) -> Result<u32, ImageError> {
        bit_addr(&self.layout, bit, frame).ok_or(ImageError::OutOfRange {
            area: bit.area,
            offset: bit.byte,
            len: 1,
        })
    }

    /// Current value of timer `n` (0 when it does not exist).
    pub fn timer_value(&self, n: u16) -> i16 {
        self.value_of(Area::TimerValue, n)
    }

    /// Bit of timer `n`.
    pub fn timer_bit(&self, n: u16) -> bool {
        self.bit_of(Area::TimerBit, n)
    }

    /// Current value of counter `n`.
    pub fn counter_value(&self, n: u16) -> i16 {
        self.value_of(Area::CounterValue, n)
    }

    /// Bit of counter `n`.
    pub fn counter_bit(&self, n: u16) -> bool {
        self.bit_of(Area::CounterBit, n)
    }

    fn value_of(&self, area: Area, n: u16) -> i16 {
        let loc = Loc {
            area,
            offset: 2 * u32::from(n),
        };
        self.read(loc, Width::Word, 0)
            .map_or(0, |v| v as u16 as i16)
    }

    fn bit_of(&self, area: Area, n: u16) -> bool {
        let bit = BitLoc {
            area,
            byte: u32::from(n),
            bit: 0,
        };
        self.bit(bit, 0).unwrap_or(false)
    }

    // ---- physical I/O ----------------------------------------------------------------------

    /// The physical input copy: the harness writes the next scan's inputs here.
    pub fn phys_in_mut(&mut self) -> &mut [u8] {
        let (at, n) = (
            self.layout.phys_in as usize,
            self.layout.area_size(Area::I) as usize,
        );
        self.img_mut().get_mut(at..at + n).unwrap_or_default()
    }

    /// Copies `inputs` into the physical input copy (extra bytes ignored, missing ones 0).
    pub fn set_inputs(&mut self, inputs: &[u8]) {
        let dst = self.phys_in_mut();
        // The usual call passes exactly the 16 input bytes of the S7 profiles, once per scan:
        // as a fixed-size copy that is two moves instead of calls to `memmove` and `memset`
        // (about 1 ns of an empty program's 17-ns scan in `stljit bench`).
        if let (Ok(dst), Ok(src)) = (
            <&mut [u8; 16]>::try_from(&mut *dst),
            <&[u8; 16]>::try_from(inputs),
        ) {
            *dst = *src;
            return;
        }
        let n = inputs.len().min(dst.len());
        let (given, rest) = dst.split_at_mut(n);
        given.copy_from_slice(&inputs[..n]);
        rest.fill(0);
    }

    /// Sets high-speed counter `n`'s counting activity per scan interval (s7-200-more §8.4,
    /// §11.2 `hsc_steps`): the harness's stimulus, held until set again
    /// ([`crate::hsc::set_rate`]).
    pub fn set_hsc_rate(&mut self, n: u8, steps: i32) {
        self.version = 0;
        let (b, l) = self.parts_mut();
        crate::hsc::set_rate(b, l, n, steps);
    }

    /// Queues `bytes` to arrive on serial port `port` during the next scan interval
    /// (s7-200-more §10.4, §11.2 `rx`): [`crate::comm::queue_rx`].
    pub fn queue_rx(&mut self, port: u8, bytes: &[u8]) {
        self.version = 0;
        let (b, l) = self.parts_mut();
        crate::comm::queue_rx(b, l, port, bytes);
    }

    /// The physical output copy, as written at the end of the last scan.
    pub fn phys_out(&self) -> &[u8] {
        let (at, n) = (
            self.layout.phys_out as usize,
            self.layout.area_size(Area::Q) as usize,
        );
        self.img().get(at..at + n).unwrap_or_default()
    }

    // ---- scheduler fields ------------------------------------------------------------------

    fn sched_u8(&self, field: u32) -> u8 {
        mem::sched_u8(self.img(), &self.layout, field)
    }

    fn set_sched_u8(&mut self, field: u32, v: u8) {
        let (b, l) = self.parts_mut();
        mem::set_sched_u8(b, l, field, v);
    }

    fn sched_u16(&self, field: u32) -> u16 {
        mem::get_u16_ne(self.img(), self.layout.sched(field))
    }

    /// Number of the next scan to run (scans completed so far).
    pub fn scan_no(&self) -> u64 {
        mem::get_u64_ne(self.img(), self.layout.sched(Sched::SCAN_NO))
    }

    /// Virtual time at the start of the last scan.
    pub fn t_now(&self) -> u64 {
        mem::get_u64_ne(self.img(), self.layout.sched(Sched::T_NOW))
    }

    /// Whether the next (or current) scan is the first one.
    pub fn first_scan(&self) -> bool {
        self.sched_u8(Sched::FIRST_SCAN) != 0
    }

    /// ENO of the last box instruction.
    pub fn eno(&self) -> bool {
        self.sched_u8(Sched::ENO) != 0
    }

    /// Whether the PLC is in STOP (after a STOP instruction or a fatal error).
    pub fn is_stopped(&self) -> bool {
        self.sched_u8(Sched::MODE) != 0
    }

    /// Code of the last non-fatal error (0 = none).
    pub fn last_error(&self) -> u16 {
        self.sched_u16(Sched::LAST_ERR)
    }

    /// Fatal error code (0 = none).
    pub fn fatal(&self) -> u16 {
        self.sched_u16(Sched::FATAL)
    }

    /// POU and op index of the instruction that raised the last error.
    pub fn error_site(&self) -> (u16, u32) {
        let op = mem::get_u32_ne(self.img(), self.layout.sched(Sched::ERR_OP));
        (self.sched_u16(Sched::ERR_POU), op)
    }

    /// Loop-budget events counted in the last scan.
    pub fn loop_count(&self) -> u32 {
        mem::sched_u32(self.img(), &self.layout, Sched::LOOP_COUNT)
    }

    /// The loop budget per scan (spec §2.5).
    pub fn loop_limit(&self) -> u32 {
        mem::sched_u32(self.img(), &self.layout, Sched::LOOP_LIMIT)
    }

    /// Changes the loop budget per scan.
    pub fn set_loop_limit(&mut self, limit: u32) {
        let (b, l) = self.parts_mut();
        mem::set_sched_u32(b, l, Sched::LOOP_LIMIT, limit);
    }

    /// Declares retentive data lost: SM0.2 reads 1 during the first scan (spec §2.3).
    pub fn set_retentive_lost(&mut self, lost: bool) {
        self.set_sched_u8(Sched::RETENTIVE_LOST, u8::from(lost));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use stljit_core::ir::{CounterDecl, CounterKind, EdgeDecl, TimerDecl, TimerKind};
    use stljit_core::profile::Resolution;
    use stljit_core::{CounterId, TimerId};

    fn program() -> Program {
        Program {
            profile: ProfileId::A5,
            pous: vec![],
            timers: vec![TimerDecl {
                id: TimerId(37),
                kind: TimerKind::Off,
                resolution: Resolution::Ms100,
            }],
            counters: vec![CounterDecl {
                id: CounterId(5),
                kind: CounterKind::UpDown,
            }],
            edges: vec![EdgeDecl { init: false }, EdgeDecl { init: true }],
            logic_stack_depth: 9,
            files: vec![],
            data: Vec::new(),
        }
    }

    #[test]
    fn cold_start_writes_declared_state_only() {
        let img = Image::cold_start(&program());
        let l = img.layout().clone();
        let b = img.bytes();
        assert_eq!(b.len(), l.size as usize);
        assert_eq!(b[(l.timer_state(37) + TimerState::KIND) as usize], 3);
        assert_eq!(b[(l.timer_state(37) + TimerState::RES) as usize], 100);
        assert_eq!(b[(l.timer_state(36) + TimerState::KIND) as usize], 0);
        assert_eq!(b[(l.counter_state(5) + CounterState::KIND) as usize], 3);
        assert_eq!(b[l.edges as usize], 0);
        assert_eq!(b[l.edges as usize + 1], 1);
        assert!(img.first_scan());
        assert_eq!(img.loop_limit(), DEFAULT_LOOP_LIMIT);
        assert_eq!(b[l.sched(Sched::SCR_ENABLE) as usize], 1);
        assert!(!img.is_stopped());
    }

    #[test]
    fn typed_access_is_big_endian_and_bounds_checked() {
        let mut img = Image::blank(ProfileId::A5);
        let vw = |o| Loc {
            area: Area::V,
            offset: o,
        };
        img.write(vw(100), Width::Word, 0, 0x1234).unwrap();
        assert_eq!(img.read(vw(100), Width::Byte, 0), Ok(0x12));
        assert_eq!(img.read(vw(101), Width::Byte, 0), Ok(0x34));
        assert!(img.read(vw(2499), Width::Word, 0).is_err());
        assert!(img.read(vw(2498), Width::Word, 0).is_ok());
        // Accumulators: AC1 as a byte is offset 7 (its low byte).
        let ac1 = Loc {
            area: Area::AC,
            offset: 4,
        };
        img.write(ac1, Width::DWord, 0, 0xAABB_CCDD).unwrap();
        assert_eq!(
            img.read(
                Loc {
                    area: Area::AC,
                    offset: 7
                },
                Width::Byte,
                0
            ),
            Ok(0xDD)
        );
        // L frames are separate.
        let lb = Loc {
            area: Area::L,
            offset: 0,
        };
        img.write(lb, Width::Byte, 2, 9).unwrap();
        assert_eq!(img.read(lb, Width::Byte, 1), Ok(0));
        assert_eq!(img.read(lb, Width::Byte, 2), Ok(9));
        assert!(img.read(lb, Width::Byte, L_FRAMES).is_err());
        let q = BitLoc {
            area: Area::Q,
            byte: 1,
            bit: 3,
        };
        img.set_bit(q, 0, true).unwrap();
        assert_eq!(
            img.read(
                Loc {
                    area: Area::Q,
                    offset: 1
                },
                Width::Byte,
                0
            ),
            Ok(8)
        );
        assert!(img.set_bit(BitLoc { bit: 8, ..q }, 0, true).is_err());
    }

    #[test]
    fn the_version_falls_to_zero_on_every_write_but_the_input_copy() {
        let mut img = Image::blank(ProfileId::A5);
        let m0 = BitLoc {
            area: Area::M,
            byte: 0,
            bit: 0,
        };
        let mb1 = Loc {
            area: Area::M,
            offset: 1,
        };
        let writes: [&dyn Fn(&mut Image); 6] = [
            &|i| i.bytes_mut()[0] = 1,
            &|i| i.split_mut().0[0] = 1,
            &|i| i.set_bit(m0, 0, true).unwrap(),
            &|i| i.write(mb1, Width::Byte, 0, 7).unwrap(),
            &|i| i.set_hsc_rate(0, 5),
            &|i| i.queue_rx(0, b"x"),
        ];
        for (k, w) in writes.iter().enumerate() {
            img.set_version(42);
            w(&mut img);
            assert_eq!(img.version(), 0, "write {k}");
        }
        img.set_version(42);
        img.set_inputs(&[1; 16]);
        img.phys_in_mut()[0] = 3;
        let _ = (img.bytes(), img.phys_out(), img.bit(m0, 0));
        assert_eq!(img.version(), 42);
    }

    #[test]
    fn the_scratch_is_no_part_of_the_image() {
        let mut img = Image::blank(ProfileId::A5);
        let plain = img.clone();
        let size = img.layout().size as usize;
        let buf = img.bytes_and_scratch(24);
        assert!(buf.len() >= size + 24);
        assert!(buf[size..].iter().all(|&b| b == 0), "zeroed when made");
        buf[size + 3] = 9;
        img.set_version(5);
        assert_eq!(img.bytes().len(), size);
        assert!(
            img == plain,
            "neither the scratch nor the version is compared"
        );
        assert_eq!(img.bytes_and_scratch(8)[size + 3], 9, "kept between uses");
    }
}
