//! The Omron instructions on the image: decode an object's bytes, run the rule of
//! [`crate::omron`] on plain values, encode the result and apply the condition-flag writes.
//! Both engines call these functions (the interpreter directly, the JIT through the
//! `stljit_rt_omron_*` shims), so the bytes an Omron timer, counter or data box leaves are the
//! same in both by construction.
//!
//! Byte layout (ARCHITECTURE.md "Omron memory"): a timer's PV is the big-endian word at
//! `TimerValue + 2n`, its completion flag the byte `TimerBit + n`, its hidden state
//! (omron-cp.md §2.12) `TimerState::RUN` (running), `TimerState::TOF` (ms not yet converted)
//! and `TimerState::LAST` (time of the last execution); a counter's PV and flag likewise, its
//! count-input memories `CounterState::PREV_UP` (count / increment) and `PREV_DOWN`
//! (decrement). The condition flags are bytes 0–1 of [`Area::Flags`], little-endian, in the
//! order of [`SystemBit`].

use crate::mem;
use crate::omron::bcd;
use crate::omron::flags::{Flag, FlagWrites};
use crate::omron::{OmronCounter, OmronTimer, arith, data};
use crate::rules::Gate;
use stljit_core::Area;
use stljit_core::ir::{
    IndexOffset, IndexStep, OmronArith, OmronBox, OmronCounterKind, OmronRef, OmronTimerKind,
};
use stljit_core::layout::{
    COUNTER_STATE_SIZE, CounterState, Layout, Sched, TIMER_STATE_SIZE, TimerState,
};
use stljit_core::omron;
use stljit_core::omron::SystemBit;

/// Applies `writes` to the condition flags.
pub fn apply_flags(img: &mut [u8], layout: &Layout, writes: FlagWrites) {
    let at = layout.base(Area::Flags);
    if layout.area_size(Area::Flags) < 2 {
        return;
    }
    let old = u16::from_le_bytes([mem::get_u8(img, at), mem::get_u8(img, at + 1)]);
    let [lo, hi] = writes.apply_bits(old).to_le_bytes();
    mem::set_u8(img, at, lo);
    mem::set_u8(img, at + 1, hi);
}

/// One Omron timer's bytes: PV (big-endian), completion flag, private state.
pub type TimerBytes = ([u8; 2], u8, [u8; TIMER_STATE_SIZE as usize]);

/// One Omron counter's bytes: PV, completion flag, private state.
pub type CounterBytes = ([u8; 2], u8, [u8; COUNTER_STATE_SIZE as usize]);

/// Executes Omron timer instruction `kind` on one timer's bytes at virtual time `t_ms` with
/// the logic stack `stack` (bit i = `S_i`: the TIM family's execution condition is `S0`; TTIM's
/// timer input `S1`, reset `S0`) under `gate`, with set value `sv` (the raw word); returns the
/// condition-flag writes. Both engines' timer paths end here.
pub fn timer_step(
    (value, flag, state): (&mut [u8; 2], &mut u8, &mut [u8; TIMER_STATE_SIZE as usize]),
    t_ms: u64,
    kind: OmronTimerKind,
    stack: u16,
    gate: Gate,
    sv: u16,
) -> FlagWrites {
    let last = |s: &[u8; TIMER_STATE_SIZE as usize]| {
        let at = TimerState::LAST as usize;
        let mut b = [0; 8];
        b.copy_from_slice(&s[at..at + 8]);
        u64::from_ne_bytes(b)
    };
    let mut timer = OmronTimer {
        pv: u16::from_be_bytes(*value),
        flag: *flag != 0,
        running: state[TimerState::RUN as usize] != 0,
        last_ms: last(state),
        rem_ms: u32::from(state[TimerState::TOF as usize]),
    };
    let (ec, reset) = if kind.totalizing() {
        (stack & 0b10 != 0, stack & 1 != 0)
    } else {
        (stack & 1 != 0, false)
    };
    let writes = timer.step(kind, ec, reset, sv, t_ms, gate);
    *value = timer.pv.to_be_bytes();
    *flag = u8::from(timer.flag);
    state[TimerState::RUN as usize] = u8::from(timer.running);
    // The remainder is below the unit (at most 99 ms), so it fits its byte.
    state[TimerState::TOF as usize] = timer.rem_ms.min(255) as u8;
    let at = TimerState::LAST as usize;
    state[at..at + 8].copy_from_slice(&timer.last_ms.to_ne_bytes());
    writes
}

/// Which logic-stack level feeds each input of an Omron counter (spec §3.3): CNT counts on
/// `S1` and resets on `S0`; CNTR increments on `S2`, decrements on `S1`, resets on `S0`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CounterLevels {
    /// The count (CNT) or increment (CNTR) input.
    pub count: usize,
    /// CNTR's decrement input.
    pub dec: Option<usize>,
    /// The reset input.
    pub reset: usize,
}

impl CounterLevels {
    /// The levels of `kind`.
    pub fn of(kind: OmronCounterKind) -> CounterLevels {
        if kind.ring() {
            CounterLevels {
                count: 2,
                dec: Some(1),
                reset: 0,
            }
        } else {
            CounterLevels {
                count: 1,
                dec: None,
                reset: 0,
            }
        }
    }

    /// The inputs in [`OmronCounter::step`]'s order ([`crate::omron::counter::COUNT`], `DEC`,
    /// `RESET`) read off the logic stack `stack` (bit i = `S_i`).
    pub fn inputs(self, stack: u16) -> [bool; 3] {
        let s = |i: usize| stack >> i & 1 != 0;
        [s(self.count), self.dec.is_some_and(s), s(self.reset)]
    }
}

/// Executes Omron counter instruction `kind` on one counter's bytes with the logic stack
/// `stack` (levels as [`CounterLevels`] says) under `gate`, set value `sv`; returns the
/// condition-flag writes.
pub fn counter_step(
    (value, flag, state): (
        &mut [u8; 2],
        &mut u8,
        &mut [u8; COUNTER_STATE_SIZE as usize],
    ),
    kind: OmronCounterKind,
    stack: u16,
    gate: Gate,
    sv: u16,
) -> FlagWrites {
    let mut counter = OmronCounter {
        pv: u16::from_be_bytes(*value),
        flag: *flag != 0,
        prev_count: state[CounterState::PREV_UP as usize] != 0,
        prev_dec: state[CounterState::PREV_DOWN as usize] != 0,
    };
    let inputs = CounterLevels::of(kind).inputs(stack);
    let writes = counter.step(kind, inputs, sv, gate);
    *value = counter.pv.to_be_bytes();
    *flag = u8::from(counter.flag);
    state[CounterState::PREV_UP as usize] = u8::from(counter.prev_count);
    state[CounterState::PREV_DOWN as usize] = u8::from(counter.prev_dec);
    writes
}

/// What a TIM-family timer with the constant set value `sv` does when its execution condition
/// is OFF under an open gate, if that does not depend on the timer's previous state: the PV
/// word, the completion flag, `running` and the flag writes. Compiled code uses it to skip the
/// call on the most frequent path; it is `timer_step` itself, run on two different states.
pub fn timer_reset_outcome(kind: OmronTimerKind, sv: u16) -> Option<([u8; 2], u8, u8, FlagWrites)> {
    if kind.totalizing() {
        return None;
    }
    let outcome = |start: TimerBytes| {
        let mut t = start;
        let w = timer_step((&mut t.0, &mut t.1, &mut t.2), 0, kind, 0, Gate::Open, sv);
        let run = t.2[TimerState::RUN as usize];
        // Everything but the fields reported must be as it was.
        let rest_kept =
            t.2.iter()
                .zip(start.2.iter())
                .enumerate()
                .all(|(i, (a, b))| i == TimerState::RUN as usize || a == b);
        rest_kept.then_some((t.0, t.1, run, w))
    };
    let busy = {
        let mut state = [0xA5u8; TIMER_STATE_SIZE as usize];
        state[TimerState::RUN as usize] = 1;
        ([0x12, 0x34], 1, state)
    };
    let idle = ([0, 0], 0, [0u8; TIMER_STATE_SIZE as usize]);
    let a = outcome(busy)?;
    (outcome(idle)? == a).then_some(a)
}

/// What a TIM-family timer with the constant set value `sv` does when its execution condition
/// is ON under an open gate and it is not running (a start, §2.12), if that does not depend on
/// its previous PV and flag: the PV word, the completion flag and the flag writes it stores;
/// `running` becomes 1, the unconverted milliseconds 0 and the time of the last execution the
/// scan's time (`TimerState::LAST`, the native-endian `T_NOW`). Like [`timer_reset_outcome`]
/// it is `timer_step` itself, run on several states at two times.
pub fn timer_start_outcome(kind: OmronTimerKind, sv: u16) -> Option<([u8; 2], u8, FlagWrites)> {
    if kind.totalizing() {
        return None;
    }
    let (run, rem, last) = (
        TimerState::RUN as usize,
        TimerState::TOF as usize,
        TimerState::LAST as usize,
    );
    let mut seen = Seen::Nothing;
    for (pv, flag, fill) in [
        ([0x12, 0x34], 1, 0xA5),
        ([0, 0], 0, 0),
        ([0xAB, 0xCD], 1, 0x3C),
    ] {
        for t in [1_000u64, 0x0123_4567_89AB] {
            let mut state = [fill; TIMER_STATE_SIZE as usize];
            state[run] = 0;
            let mut b: TimerBytes = (pv, flag, state);
            let w = timer_step((&mut b.0, &mut b.1, &mut b.2), t, kind, 1, Gate::Open, sv);
            let mut want = state;
            want[run] = 1;
            want[rem] = 0;
            want[last..last + 8].copy_from_slice(&t.to_ne_bytes());
            seen = seen.and((b.2 == want).then_some((b.0, b.1, w)));
        }
    }
    seen.always()
}

/// What an Omron counter with a constant set value does under an open gate on the two paths
/// whose outcome does not depend on its PV and flag. On both, the count-input memories take the
/// inputs (`PREV_UP` := the count input; CNTR: `PREV_DOWN` := the decrement input; the rest of
/// the private state is kept).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CounterFixed {
    /// Reset input ON: the PV and completion flag bytes stored and the flag writes (`None`:
    /// they depend on the state, e.g. a non-BCD SV makes the reset do nothing).
    pub reset: Option<([u8; 2], u8, FlagWrites)>,
    /// Reset OFF and no count edge (no count input ON whose memory is OFF): PV and flag kept;
    /// the flag writes.
    pub quiet: Option<FlagWrites>,
}

/// The [`CounterFixed`] outcomes of counter `kind` with the constant set value `sv`. Compiled
/// code stores them inline and calls the runtime only for a count; they are `counter_step`
/// itself, run on every input and memory combination from several PV/flag states, and a path
/// whose outcome differs between states (or whose memories are not the inputs) is `None`.
pub fn counter_fixed(kind: OmronCounterKind, sv: u16) -> CounterFixed {
    let levels = CounterLevels::of(kind);
    let (up, down) = (
        CounterState::PREV_UP as usize,
        CounterState::PREV_DOWN as usize,
    );
    let states: [([u8; 2], u8); 3] = [([0x12, 0x34], 1), ([0, 0], 0), ([0xAB, 0xCD], 0)];
    let mut reset = Seen::Nothing;
    let mut quiet = Seen::Nothing;
    for stack in 0..8u16 {
        let [count, dec, rst] = levels.inputs(stack);
        for prev in 0..4u8 {
            for &(pv, flag) in &states {
                let mut state = [0x5A; COUNTER_STATE_SIZE as usize];
                state[up] = prev & 1;
                state[down] = prev >> 1;
                let mut c: CounterBytes = (pv, flag, state);
                let w = counter_step((&mut c.0, &mut c.1, &mut c.2), kind, stack, Gate::Open, sv);
                let mut memories = state;
                memories[up] = u8::from(count);
                if levels.dec.is_some() {
                    memories[down] = u8::from(dec);
                }
                let recorded = c.2 == memories;
                let counts = (count && state[up] == 0) || (dec && state[down] == 0);
                if rst {
                    reset = reset.and(recorded.then_some((c.0, c.1, w)));
                } else if !counts {
                    quiet = quiet.and((recorded && (c.0, c.1) == (pv, flag)).then_some(w));
                }
            }
        }
    }
    CounterFixed {
        reset: reset.always(),
        quiet: quiet.always(),
    }
}

/// The outcomes one path of [`counter_fixed`] had so far.
enum Seen<T> {
    Nothing,
    Always(T),
    Varies,
}

impl<T: PartialEq> Seen<T> {
    /// With one more outcome (`None`: one that does not qualify).
    fn and(self, v: Option<T>) -> Seen<T> {
        match (self, v) {
            (Seen::Nothing, Some(v)) => Seen::Always(v),
            (Seen::Always(a), Some(b)) if a == b => Seen::Always(a),
            _ => Seen::Varies,
        }
    }

    fn always(self) -> Option<T> {
        match self {
            Seen::Always(v) => Some(v),
            Seen::Nothing | Seen::Varies => None,
        }
    }
}

/// Copies `N` image bytes from `at` (zeros past the end, which the callers' range checks rule
/// out).
fn take<const N: usize>(img: &[u8], at: u32) -> [u8; N] {
    let mut b = [0; N];
    for (i, v) in b.iter_mut().enumerate() {
        *v = mem::get_u8(img, at + i as u32);
    }
    b
}

fn put(img: &mut [u8], at: u32, bytes: &[u8]) {
    for (i, &v) in bytes.iter().enumerate() {
        mem::set_u8(img, at + i as u32, v);
    }
}

/// [`timer_step`] on timer `n` of the image (a number outside the profile does nothing; the
/// verifier rejects such a program), the flags applied.
pub fn timer(
    img: &mut [u8],
    layout: &Layout,
    kind: OmronTimerKind,
    n: u16,
    stack: u16,
    gate: Gate,
    sv: u16,
) {
    if u32::from(n) >= layout.area_size(Area::TimerBit) {
        return;
    }
    let [(value, _), (bit, _), (state, _)] = layout.timer_bytes(n);
    let t_ms = mem::get_u64_ne(img, layout.sched(Sched::T_NOW));
    let mut t: TimerBytes = (take(img, value), mem::get_u8(img, bit), take(img, state));
    let writes = timer_step((&mut t.0, &mut t.1, &mut t.2), t_ms, kind, stack, gate, sv);
    put(img, value, &t.0);
    mem::set_u8(img, bit, t.1);
    put(img, state, &t.2);
    apply_flags(img, layout, writes);
}

/// [`counter_step`] on counter `n` of the image, the flags applied.
pub fn counter(
    img: &mut [u8],
    layout: &Layout,
    kind: OmronCounterKind,
    n: u16,
    stack: u16,
    gate: Gate,
    sv: u16,
) {
    if u32::from(n) >= layout.area_size(Area::CounterBit) {
        return;
    }
    let [(value, _), (bit, _), (state, _)] = layout.counter_bytes(n);
    let mut c: CounterBytes = (take(img, value), mem::get_u8(img, bit), take(img, state));
    let writes = counter_step((&mut c.0, &mut c.1, &mut c.2), kind, stack, gate, sv);
    put(img, value, &c.0);
    mem::set_u8(img, bit, c.1);
    put(img, state, &c.2);
    apply_flags(img, layout, writes);
}

/// The Omron value of a double-word operand read as the IR's big-endian dword: Omron keeps the
/// low 16 bits in the lower-numbered word (omron-cp.md §1.6), which big-endian storage puts
/// first, so the halves swap.
#[inline]
pub fn double_of_be(be: u32) -> u32 {
    be.rotate_left(16)
}

/// Writes `words` (word 0 first) as Omron words from image offset `at`.
fn write_words(img: &mut [u8], at: u32, words: &[u16]) {
    for (i, w) in words.iter().enumerate() {
        let [hi, lo] = w.to_be_bytes();
        let a = at + 2 * i as u32;
        mem::set_u8(img, a, hi);
        mem::set_u8(img, a + 1, lo);
    }
}

/// Sets the access-error flag (AER, spec §2.11): an illegal indirect access.
fn access_error(img: &mut [u8], layout: &Layout) {
    apply_flags(img, layout, FlagWrites::NONE.write(Flag::Aer, true));
}

fn get_be(img: &[u8], at: u32, n: u32) -> u32 {
    (0..n).fold(0, |v, i| v << 8 | u32::from(mem::get_u8(img, at + i)))
}

fn set_be(img: &mut [u8], at: u32, n: u32, v: u32) {
    for i in 0..n {
        mem::set_u8(img, at + i, (v >> (8 * (n - 1 - i))) as u8);
    }
}

/// Resolves an Omron indirect operand of `words` words (1 or 2) to its image offset, carrying
/// out an index register's step (spec §1.7: pre-decrement before the access, post-increment
/// after); `None` is an illegal access (AER set): a pointer that is not a D address (or, for
/// `*D`, not BCD), an effective address outside the profile's memory, a bit address, a double
/// word running out of its area, or a write into the read-only auxiliary words. Operands are
/// resolved in operand order (sources, then the destination), the same in both engines.
pub fn resolve(
    img: &mut [u8],
    layout: &Layout,
    r: OmronRef,
    words: u32,
    write: bool,
) -> Option<u32> {
    let profile = layout.profile.profile();
    let dm = |v: u32| omron::word_loc(profile, omron::WordArea::Dm, v);
    let loc = match r {
        OmronRef::DmBinary(n) | OmronRef::DmBcd(n) => {
            let at = layout.base(Area::Dm) + 2 * u32::from(n);
            let raw = get_be(img, at, 2) as u16;
            let v = match r {
                OmronRef::DmBcd(_) => bcd::bcd16_to_bin(raw),
                _ => Some(raw),
            };
            v.and_then(|v| dm(u32::from(v)))
        }
        OmronRef::Index { ir, offset, step } => {
            let at = layout.base(Area::IndexReg) + 4 * u32::from(ir);
            let mut reg = get_be(img, at, 4);
            let (pre, post) = match step {
                IndexStep::None => (0, 0),
                IndexStep::PostInc1 => (0, 1),
                IndexStep::PostInc2 => (0, 2),
                IndexStep::PreDec1 => (1, 0),
                IndexStep::PreDec2 => (2, 0),
            };
            reg = reg.wrapping_sub(pre);
            let off = match offset {
                IndexOffset::Const(c) => i32::from(c),
                IndexOffset::Dr(m) => {
                    let at = layout.base(Area::DataReg) + 2 * u32::from(m);
                    i32::from(get_be(img, at, 2) as u16 as i16)
                }
            };
            let ea = reg.wrapping_add_signed(off);
            set_be(img, at, 4, reg.wrapping_add(post));
            omron::ea_loc(profile, ea)
        }
    };
    let fits = loc.filter(|l| {
        let ends_inside = l.offset + 2 * words <= layout.area_size(l.area);
        let read_only = write && l.area == Area::Aux && l.offset / 2 < profile.omron.aux_read_only;
        ends_inside && !read_only
    });
    match fits {
        Some(l) => Some(layout.base(l.area) + l.offset),
        None => {
            access_error(img, layout);
            None
        }
    }
}

/// An operand of [`run_box_refs`]: a value already read, an image offset to write, or an
/// indirect operand to resolve.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BoxOperand {
    /// A source's value (Omron order), or a destination's image offset.
    Direct(u32),
    /// An indirect operand.
    Ref(OmronRef),
    /// No operand (MOV's second source, a compare's destination).
    Absent,
}

/// [`run_box`] for a box with indirect operands: each `Ref` is resolved in operand order
/// (`lhs`, `rhs`, then `dst`), an illegal source reads 0 and an illegal destination drops the
/// write; the instruction is otherwise processed to the end (spec §2.11). `words` are the
/// sources' and the result's sizes.
pub fn run_box_refs(
    img: &mut [u8],
    layout: &Layout,
    code: u32,
    (lhs, rhs, dst): (BoxOperand, BoxOperand, BoxOperand),
    (src_words, dst_words): (u32, u32),
) -> bool {
    let value = |img: &mut [u8], o: BoxOperand| match o {
        BoxOperand::Direct(v) => v,
        BoxOperand::Absent => 0,
        BoxOperand::Ref(r) => match resolve(img, layout, r, src_words, false) {
            Some(at) if src_words == 2 => double_of_be(get_be(img, at, 4)),
            Some(at) => get_be(img, at, 2),
            None => 0,
        },
    };
    let a = value(img, lhs);
    let b = value(img, rhs);
    let dst = match dst {
        BoxOperand::Direct(at) => Some(at),
        BoxOperand::Absent => Some(0),
        BoxOperand::Ref(r) => resolve(img, layout, r, dst_words, true),
    };
    // An illegal destination drops the write; the flags are still the instruction's.
    run_box_at(img, layout, code, a, b, dst)
}

/// [`OmronRef`] as one integer for the JIT's shim (`stljit_rt_omron_box_refs`): bits 28–31
/// the kind (1 `@D`, 2 `*D`, 3 indexed); `@D`/`*D`: the pointer word in bits 0–15; indexed:
/// the register in bits 0–3, the step's position in `IndexStep::ALL` in bits 4–6, bit 7 set
/// for a `DR` offset, the offset (`i16`) or the `DR` number in bits 8–23. 0 is no reference.
pub fn pack_ref(r: OmronRef) -> u32 {
    match r {
        OmronRef::DmBinary(n) => 1 << 28 | u32::from(n),
        OmronRef::DmBcd(n) => 2 << 28 | u32::from(n),
        OmronRef::Index { ir, offset, step } => {
            let step = IndexStep::ALL.iter().position(|&s| s == step).unwrap_or(0) as u32;
            let (dr, off) = match offset {
                IndexOffset::Const(c) => (0, u32::from(c as u16)),
                IndexOffset::Dr(m) => (1, u32::from(m)),
            };
            3 << 28 | u32::from(ir & 15) | step << 4 | dr << 7 | off << 8
        }
    }
}

/// The inverse of [`pack_ref`] (`None` for 0 or an impossible packing).
pub fn unpack_ref(p: u32) -> Option<OmronRef> {
    Some(match p >> 28 {
        1 => OmronRef::DmBinary(p as u16),
        2 => OmronRef::DmBcd(p as u16),
        3 => OmronRef::Index {
            ir: (p & 15) as u8,
            step: *IndexStep::ALL.get(((p >> 4) & 7) as usize)?,
            offset: if p & (1 << 7) != 0 {
                IndexOffset::Dr(((p >> 8) & 15) as u8)
            } else {
                IndexOffset::Const((p >> 8) as u16 as i16)
            },
        },
        _ => return None,
    })
}

/// An Omron box as one integer for the JIT's shim (`stljit_rt_omron_box`): `MOV` 0, `MOVL` 1,
/// the compares 2–5 (`2 + 2·double + signed`), `MOVR` 6, the arithmetic
/// `7 + position in OmronArith::ALL`, `CCS` 64, `CCL` 65.
pub fn box_code(b: &OmronBox) -> u32 {
    match *b {
        OmronBox::Move { double, .. } => u32::from(double),
        OmronBox::Compare { double, signed, .. } => 2 + 2 * u32::from(double) + u32::from(signed),
        OmronBox::SetIndex { .. } => 6,
        OmronBox::Flags { save } => {
            if save {
                CODE_CCS
            } else {
                CODE_CCS + 1
            }
        }
        OmronBox::Arith { op, .. } => {
            7 + OmronArith::ALL.iter().position(|&a| a == op).unwrap_or(0) as u32
        }
    }
}

/// [`box_code`] of CCS(282); CCL(283) is the next.
const CODE_CCS: u32 = 64;

/// Runs the box of code `code` (see [`box_code`]) on the operand values `a` and `b` (Omron
/// order: a double's low word in the low 16 bits), writing a result to image offset `dst`
/// (unused by the compares) and the condition flags. `false` for an unknown code.
pub fn run_box(img: &mut [u8], layout: &Layout, code: u32, a: u32, b: u32, dst: u32) -> bool {
    run_box_at(img, layout, code, a, b, Some(dst))
}

/// [`run_box`] with the result dropped when `dst` is `None` (an illegal indirect destination).
fn run_box_at(
    img: &mut [u8],
    layout: &Layout,
    code: u32,
    a: u32,
    b: u32,
    dst: Option<u32>,
) -> bool {
    let emit = |img: &mut [u8], words: &[u16]| {
        if let Some(at) = dst {
            write_words(img, at, words);
        }
    };
    match code {
        0 | 1 => {
            let double = code == 1;
            let (v, writes) = data::mov(double, a);
            if double {
                emit(img, &[v as u16, (v >> 16) as u16]);
            } else {
                emit(img, &[v as u16]);
            }
            apply_flags(img, layout, writes);
        }
        2..=5 => {
            let double = code >= 4;
            let signed = code % 2 == 1;
            apply_flags(img, layout, data::compare(double, signed, a, b));
        }
        CODE_CCS | 65 => {
            // CCS/CCL: the twelve condition flags to or from their save area (bytes 4–5).
            let (flags, saved) = (
                layout.base(Area::Flags),
                layout.base(Area::Flags) + omron::SAVED_FLAGS,
            );
            let (from, to) = if code == CODE_CCS {
                (flags, saved)
            } else {
                (saved, flags)
            };
            if layout.area_size(Area::Flags) >= omron::SAVED_FLAGS + 2 {
                let v = u16::from_le_bytes([mem::get_u8(img, from), mem::get_u8(img, from + 1)]);
                let w = FlagWrites {
                    mask: SystemBit::CONDITION_FLAGS,
                    value: v,
                };
                let old = u16::from_le_bytes([mem::get_u8(img, to), mem::get_u8(img, to + 1)]);
                let [lo, hi] = w.apply_bits(old).to_le_bytes();
                mem::set_u8(img, to, lo);
                mem::set_u8(img, to + 1, hi);
            }
        }
        6 => {
            // MOVR: the index register takes the effective address (big-endian dword).
            emit(img, &[(a >> 16) as u16, a as u16]);
            apply_flags(img, layout, FlagWrites::OK);
        }
        _ => {
            let Some(&op) = OmronArith::ALL.get((code - 7) as usize) else {
                return false;
            };
            let cy = {
                let at = layout.base(Area::Flags);
                let bit = SystemBit::Cy.bit_loc();
                layout.area_size(Area::Flags) > 0
                    && mem::get_u8(img, at + bit.byte) & (1 << bit.bit) != 0
            };
            let out = arith::execute(op, a, b, cy);
            if let Some(words) = out.words() {
                let n = op.result_words() as usize;
                emit(img, &words[..n]);
            }
            apply_flags(img, layout, out.flags);
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_timer_reset_is_state_free_only_with_a_valid_set_value() {
        // §2.12: EC OFF → PV := SV, flag OFF, running := false, ER OFF.
        let (pv, flag, run, w) = timer_reset_outcome(OmronTimerKind::Tim, 0x0003).unwrap();
        assert_eq!((pv, flag, run), ([0x00, 0x03], 0, 0));
        assert_eq!(w, FlagWrites::OK);
        // A non-BCD SV keeps PV and flag (ER ON): the outcome depends on the state.
        assert_eq!(timer_reset_outcome(OmronTimerKind::Tim, 0x12A4), None);
        // Binary set values are always valid; TTIM has no reset-by-EC path.
        assert!(timer_reset_outcome(OmronTimerKind::TimX, 0x12A4).is_some());
        assert_eq!(timer_reset_outcome(OmronTimerKind::Ttim, 3), None);
    }

    #[test]
    fn a_timer_start_is_state_free_only_with_a_valid_set_value() {
        // §2.12: EC ON, not running → PV := SV, flag := (SV = 0), running, rem 0, last := t.
        let start = |kind, sv| timer_start_outcome(kind, sv);
        assert_eq!(
            start(OmronTimerKind::Tim, 0x0030),
            Some(([0x00, 0x30], 0, FlagWrites::OK))
        );
        assert_eq!(
            start(OmronTimerKind::TimHX, 0),
            Some(([0, 0], 1, FlagWrites::OK))
        );
        // A non-BCD SV: ER and nothing changes, so the outcome is the state's.
        assert_eq!(start(OmronTimerKind::Tmhh, 0x00A0), None);
        assert_eq!(start(OmronTimerKind::TtimX, 5), None);
    }

    #[test]
    fn a_counter_reset_and_a_quiet_execution_are_state_free() {
        // §3.3: reset ON → PV := SV (CNT) or 0 (CNTR), flag OFF, ER OFF; no reset and no count
        // edge → PV and flag kept, ER OFF; on both the input memories take the inputs.
        let f = counter_fixed(OmronCounterKind::Cnt, 0x0005);
        assert_eq!(f.reset, Some(([0x00, 0x05], 0, FlagWrites::OK)));
        assert_eq!(f.quiet, Some(FlagWrites::OK));
        let f = counter_fixed(OmronCounterKind::CntrX, 4);
        assert_eq!(f.reset, Some(([0, 0], 0, FlagWrites::OK)));
        assert_eq!(f.quiet, Some(FlagWrites::OK));
        // A non-BCD SV: ER ON and the execution does nothing (§1.9), so a reset keeps PV and
        // flag (state-dependent); a quiet execution is ER with the memories still updated.
        let f = counter_fixed(OmronCounterKind::Cnt, 0x00A0);
        assert_eq!(f.reset, None);
        assert_eq!(f.quiet, Some(FlagWrites::ERROR));
    }

    #[test]
    fn counter_levels_follow_the_spec() {
        // CNT: count S1, reset S0; CNTR: increment S2, decrement S1, reset S0.
        assert_eq!(
            CounterLevels::of(OmronCounterKind::Cnt).inputs(0b010),
            [true, false, false]
        );
        assert_eq!(
            CounterLevels::of(OmronCounterKind::CntrX).inputs(0b011),
            [false, true, true]
        );
    }
}
