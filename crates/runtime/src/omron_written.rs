//! Which condition flags an Omron op can change, found by running its rule — the code both
//! engines run (`omron_image::run_box`, `timer`, `counter`) — on sample operands from two
//! opposite flag states: a flag the rule writes differs from one of the two start values
//! afterwards, so it shows up. The front end's flag-discipline check (OMR-W033) asks this
//! instead of keeping a second list of which instruction writes which flag.
//!
//! Only direct operands are sampled, so `P_AER` (set by an illegal indirect access) never shows
//! up: AER collects the task's access errors on purpose (omron-cp.md §1.8 rule 2).

use crate::image::Image;
use crate::omron::flags::Flag;
use crate::omron_image;
use crate::rules::Gate;
use std::collections::HashMap;
use std::sync::{Mutex, OnceLock};
use stljit_core::ir::{OmronCounterKind, OmronTimerKind, Op};
use stljit_core::{Area, ProfileId};

/// Operand pairs: a zero result, plain values, BCD values with a carry, and a value that is
/// not BCD with a zero divisor (the error paths).
const SAMPLES: [(u32, u32); 4] = [(0, 0), (1, 1), (0x9999, 0x0001), (0x000A, 0)];

/// The condition flags (bits of [`Flag::MASK`]) `op` can change: those of its rule for the Omron
/// boxes, timers and counters; 0 for every other op (bit instructions leave the flags alone,
/// omron-cp.md §1.8 rule 4).
pub fn flags_changed_by(op: &Op) -> u16 {
    let key = match op {
        Op::Omron(b) => Key::Box(omron_image::box_code(b)),
        Op::OmronTimer { kind, .. } => Key::Timer(*kind),
        Op::OmronCounter { kind, .. } => Key::Counter(*kind),
        _ => return 0,
    };
    static CACHE: OnceLock<Mutex<HashMap<Key, u16>>> = OnceLock::new();
    let cache = CACHE.get_or_init(Default::default);
    if let Some(m) = cache.lock().ok().and_then(|c| c.get(&key).copied()) {
        return m;
    }
    let m = observe(key);
    if let Ok(mut c) = cache.lock() {
        c.insert(key, m);
    }
    m
}

/// What is run: a box by its code, a timer or counter by its kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum Key {
    Box(u32),
    Timer(OmronTimerKind),
    Counter(OmronCounterKind),
}

/// The flags that differ from their start value after some sample run of `key`.
fn observe(key: Key) -> u16 {
    let mut changed = 0;
    for start in [0, Flag::MASK] {
        for (a, b) in SAMPLES {
            // Every input combination: up to three execution conditions on the stack.
            for stack in 0..8u16 {
                let mut image = Image::blank(ProfileId::Cp1h);
                let (img, layout) = image.split_mut();
                let at = layout.base(Area::Flags) as usize;
                let [lo, hi] = start.to_le_bytes();
                (img[at], img[at + 1]) = (lo, hi);
                match key {
                    Key::Box(code) => {
                        let dst = layout.base(Area::Dm);
                        omron_image::run_box(img, layout, code, a, b, dst);
                    }
                    Key::Timer(kind) => {
                        omron_image::timer(img, layout, kind, 0, stack, Gate::Open, a as u16);
                    }
                    Key::Counter(kind) => {
                        omron_image::counter(img, layout, kind, 0, stack, Gate::Open, a as u16);
                    }
                }
                let after = u16::from_le_bytes([img[at], img[at + 1]]);
                changed |= (after ^ start) & Flag::MASK;
                if matches!(key, Key::Box(_)) {
                    break; // a box does not read the stack
                }
            }
        }
    }
    changed
}

#[cfg(test)]
mod tests {
    use super::*;
    use stljit_core::ir::{OmronArith, OmronBox, Operand};

    fn bits(flags: &[Flag]) -> u16 {
        flags.iter().fold(0, |m, f| m | f.bit())
    }

    #[test]
    fn the_flags_of_the_rules() {
        use Flag::*;
        let d = Operand::Const(0);
        let mov = Op::Omron(OmronBox::Move {
            double: false,
            src: d,
            dst: d,
        });
        // Spec §3.5: MOV sets ER OFF, = and N.
        assert_eq!(flags_changed_by(&mov), bits(&[Er, Eq, N]));
        let cmp = Op::Omron(OmronBox::Compare {
            double: false,
            signed: false,
            lhs: d,
            rhs: d,
        });
        assert_eq!(flags_changed_by(&cmp), bits(&[Er, Gt, Ge, Eq, Le, Lt, Ne]));
        let add = Op::Omron(OmronBox::Arith {
            op: OmronArith::Add,
            lhs: d,
            rhs: d,
            dst: d,
        });
        assert_eq!(flags_changed_by(&add), bits(&[Er, Cy, Eq, N, Of, Uf]));
        // +B: ER on a non-BCD operand, else CY and =.
        let add_b = Op::Omron(OmronBox::Arith {
            op: OmronArith::AddB,
            lhs: d,
            rhs: d,
            dst: d,
        });
        assert_eq!(flags_changed_by(&add_b), bits(&[Er, Cy, Eq]));
        // CCL loads every flag, CCS none.
        let ccl = Op::Omron(OmronBox::Flags { save: false });
        assert_eq!(flags_changed_by(&ccl), Flag::MASK);
        assert_eq!(
            flags_changed_by(&Op::Omron(OmronBox::Flags { save: true })),
            0
        );
        // Timers and counters: ER only.
        let tim = Op::OmronTimer {
            kind: OmronTimerKind::Tim,
            timer: stljit_core::TimerId(0),
            set_value: d,
        };
        assert_eq!(flags_changed_by(&tim), bits(&[Er]));
        let cnt = Op::OmronCounter {
            kind: OmronCounterKind::Cntr,
            counter: stljit_core::CounterId(0),
            set_value: d,
        };
        assert_eq!(flags_changed_by(&cnt), bits(&[Er]));
        assert_eq!(flags_changed_by(&Op::Interlock), 0);
    }
}
