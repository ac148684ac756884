//! The three interrupt queues (s7-200-more §3.3) in the image: per group a length
//! (`IntState::QUEUE_LEN`) and that many `QueueEntry` records in the order they were queued.
//! Selection is by the smallest key `(group, τ, pri, seq)` over all three, so an entry may
//! leave from the middle of its queue; the entries after it move up and the freed record is
//! zeroed.

use super::{SMB4, attached};
use crate::mem;
use stljit_core::interrupt::{self, EventGroup};
use stljit_core::layout::{IntState, Layout, QUEUE_ENTRY_SIZE, QueueEntry};
use stljit_core::{Area, ProfileId};

/// One queued event.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Entry {
    /// When it occurred (µs).
    pub(crate) tau: u64,
    /// Its sequence number.
    pub(crate) seq: u32,
    /// The event number.
    pub(crate) event: u8,
}

fn profile_queue(profile: ProfileId, g: EventGroup) -> (u32, u32) {
    profile.profile().interrupts.queue(g)
}

fn len(img: &[u8], l: &Layout, g: EventGroup) -> u32 {
    u32::from(mem::get_u8(
        img,
        l.int_state(IntState::QUEUE_LEN) + g.index() as u32,
    ))
}

fn set_len(img: &mut [u8], l: &Layout, g: EventGroup, n: u32) {
    let at = l.int_state(IntState::QUEUE_LEN) + g.index() as u32;
    mem::set_u8(img, at, n as u8);
}

fn read(img: &[u8], l: &Layout, slot: u32) -> Entry {
    let at = l.queue_entry(slot);
    Entry {
        tau: mem::get_u64_ne(img, at + QueueEntry::TAU),
        seq: mem::get_u32_ne(img, at + QueueEntry::SEQ),
        event: mem::get_u8(img, at + QueueEntry::EVENT),
    }
}

fn write(img: &mut [u8], l: &Layout, slot: u32, e: Entry) {
    let at = l.queue_entry(slot);
    mem::set_u64_ne(img, at + QueueEntry::TAU, e.tau);
    mem::set_u32_ne(img, at + QueueEntry::SEQ, e.seq);
    mem::set_u8(img, at + QueueEntry::EVENT, e.event);
}

/// Event `event` occurred at `tau`: queued when it is attached (an unattached event is dropped
/// silently); a full queue loses it and sets the group's overflow bit in SMB4.
pub(crate) fn raise(img: &mut [u8], l: &Layout, event: u8, tau: u64) {
    if attached(img, l, event) == 0 {
        return;
    }
    let Some(info) = interrupt::event(event) else {
        return;
    };
    let (first, depth) = profile_queue(l.profile, info.group);
    let n = len(img, l, info.group);
    if n >= depth {
        let smb4 = l.base(Area::SM) + SMB4;
        mem::set_bit(img, smb4, info.group.index() as u8, true);
        return;
    }
    let seq_at = l.int_state(IntState::SEQ);
    let seq = mem::get_u32_ne(img, seq_at);
    mem::set_u32_ne(img, seq_at, seq.wrapping_add(1));
    write(img, l, first + n, Entry { tau, seq, event });
    set_len(img, l, info.group, n + 1);
}

/// Removes entry `i` of group `g`'s queue.
fn remove(img: &mut [u8], l: &Layout, g: EventGroup, i: u32) {
    let (first, _) = profile_queue(l.profile, g);
    let n = len(img, l, g);
    for k in i + 1..n {
        let e = read(img, l, first + k);
        write(img, l, first + k - 1, e);
    }
    let last = l.queue_entry(first + n - 1) as usize;
    if let Some(b) = img.get_mut(last..last + QUEUE_ENTRY_SIZE as usize) {
        b.fill(0);
    }
    set_len(img, l, g, n - 1);
}

/// The queued entry with the smallest selection key `(group, τ, pri, seq)` (§3.3), removed
/// from its queue. The group comes first in the key, so the entry is in the first group (by
/// index) with entries, and only that queue is searched.
pub(crate) fn pop_next(img: &mut [u8], l: &Layout) -> Option<Entry> {
    let (g, n) = EventGroup::ALL
        .into_iter()
        .map(|g| (g, len(img, l, g)))
        .find(|&(_, n)| n > 0)?;
    let (first, _) = profile_queue(l.profile, g);
    let key = |e: &Entry| {
        let pri = interrupt::event(e.event).map_or(u8::MAX, |info| info.pri);
        (e.tau, pri, e.seq)
    };
    let mut best = (0, read(img, l, first));
    for i in 1..n {
        let e = read(img, l, first + i);
        if key(&e) < key(&best.1) {
            best = (i, e);
        }
    }
    remove(img, l, g, best.0);
    Some(best.1)
}

/// Whether every queue is empty: the three lengths are one field of three bytes.
pub(crate) fn is_empty(img: &[u8], l: &Layout) -> bool {
    mem::get_array::<3>(img, l.int_state(IntState::QUEUE_LEN)) == [0; 3]
}

/// Drops every queued entry of `event` (DTCH, CEVNT).
pub(crate) fn remove_event(img: &mut [u8], l: &Layout, event: u8) {
    let Some(info) = interrupt::event(event) else {
        return;
    };
    let (first, _) = profile_queue(l.profile, info.group);
    let mut i = 0;
    while i < len(img, l, info.group) {
        if read(img, l, first + i).event == event {
            remove(img, l, info.group, i);
        } else {
            i += 1;
        }
    }
}

/// Drops every queued entry (STOP in a routine, §3.4).
pub(crate) fn clear(img: &mut [u8], l: &Layout) {
    for g in EventGroup::ALL {
        while len(img, l, g) > 0 {
            remove(img, l, g, 0);
        }
    }
}

/// Clears the overflow bits SM4.0–SM4.2 (after a service run that emptied every queue).
pub(crate) fn clear_overflow(img: &mut [u8], l: &Layout) {
    // Bit = the group's index, and the groups are indexed from 0.
    const OVERFLOW_BITS: u8 = (1 << EventGroup::ALL.len()) - 1;
    let smb4 = l.base(Area::SM) + SMB4;
    mem::set_u8(img, smb4, mem::get_u8(img, smb4) & !OVERFLOW_BITS);
}
