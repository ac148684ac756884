//! Counter tables of spec §7 (T11, T12, T13) and the §5.3 / TC rules.

use super::*;
use crate::rules::{Gate, Rules};
use crate::testutil::Rig;
use CounterKind::{Down, Up, UpDown};

/// One counter instruction of a test program: counter `n` of `kind` with preset `preset`.
#[derive(Clone, Copy)]
struct Ctr {
    n: u16,
    kind: CounterKind,
    preset: i16,
}

/// Stack after `LD a / LD b` (b on top) or `LD a / LD b / LD c`.
fn stack(levels: &[u8]) -> u16 {
    levels.iter().fold(0, |st, &v| (st << 1) | u16::from(v))
}

impl Ctr {
    /// A rig whose program uses this counter (its kind written as cold start does).
    fn rig(self) -> Rig {
        Rig::new(10).counter(self.n, self.kind.code())
    }

    /// The counter's (bit, value).
    fn state(self, img: &[u8], l: &Layout) -> (bool, i16) {
        (
            mem::get_u8(img, bit_at(l, self.n)) != 0,
            mem::get_i16_be(img, value_at(l, self.n)),
        )
    }

    /// Executes the counter with the stack `levels` under an SCR gate open or not and returns
    /// its (bit, value) after.
    fn exec(self, b: &mut [u8], l: &Layout, levels: &[u8], open: bool) -> (bool, i16) {
        let gate = Gate::scr(open);
        execute(
            b,
            l,
            self.n,
            self.kind,
            stack(levels),
            gate,
            self.preset,
            Rules::IN_FORCE,
        )
        .unwrap();
        self.state(b, l)
    }

    /// One scan of `rig` executing the counter once; returns its (bit, value) after.
    fn scan(self, rig: &mut Rig, levels: &[u8], open: bool) -> (bool, i16) {
        let mut got = (false, 0);
        rig.scan(|b, l| got = self.exec(b, l, levels, open));
        got
    }

    /// One scan per row, with the gate open: the stack levels the counter executes with and the
    /// (bit, value) expected after. `before_first` runs at the start of the first scan.
    fn check_table(
        self,
        rows: &[(&[u8], bool, i16)],
        before_first: impl FnOnce(&mut [u8], &Layout),
    ) {
        let mut rig = self.rig();
        let mut before_first = Some(before_first);
        for (k, &(levels, q, v)) in rows.iter().enumerate() {
            let mut got = (false, 0);
            rig.scan(|b, l| {
                if let Some(f) = before_first.take() {
                    f(b, l);
                }
                got = self.exec(b, l, levels, true);
            });
            assert_eq!(got, (q, v), "scan {k}");
        }
    }
}

#[test]
fn t11_ctu_with_reset() {
    // ([I0.0 = CU, I0.1 = R]) → (Q0.0, VW0).
    let rows: &[(&[u8], bool, i16)] = &[
        (&[0, 0], false, 0),
        (&[1, 0], false, 1),
        (&[0, 0], false, 1),
        (&[1, 0], false, 2),
        (&[1, 0], false, 2),
        (&[0, 0], false, 2),
        (&[1, 0], true, 3),
        (&[0, 0], true, 3),
        (&[1, 0], true, 4),
        (&[0, 1], false, 0),
        (&[1, 1], false, 0),
        (&[1, 0], false, 0),
    ];
    let c = Ctr {
        n: 0,
        kind: Up,
        preset: 3,
    };
    c.check_table(rows, |_, _| {});
}

#[test]
fn t12_ctd_with_load() {
    // ([CD, LD]) → (bit, CV).
    let rows: &[(&[u8], bool, i16)] = &[
        (&[0, 0], true, 0),
        (&[0, 1], false, 2),
        (&[1, 0], false, 1),
        (&[0, 0], false, 1),
        (&[1, 0], true, 0),
        (&[0, 0], true, 0),
        (&[1, 0], true, 0),
        (&[0, 1], false, 2),
    ];
    let c = Ctr {
        n: 1,
        kind: Down,
        preset: 2,
    };
    c.check_table(rows, |_, _| {});
}

#[test]
fn t13_ctud_wraps() {
    // ([CU, CD, R]) → (bit, CV), from CV = 32766.
    let rows: &[(&[u8], bool, i16)] = &[
        (&[0, 0, 0], true, 32766),
        (&[1, 0, 0], true, 32767),
        (&[0, 0, 0], true, 32767),
        (&[1, 0, 0], false, -32768),
        (&[0, 1, 0], true, 32767),
        (&[0, 0, 0], true, 32767),
        (&[0, 0, 1], false, 0),
    ];
    let c = Ctr {
        n: 2,
        kind: UpDown,
        preset: 10,
    };
    // MOVW +32766, C2 on SM0.1.
    c.check_table(rows, |b, l| mem::set_i16_be(b, value_at(l, 2), 32766));
}

#[test]
fn first_scan_input_on_does_not_count() {
    // TC7: a counter whose input is already on at power-up does not count.
    let c = Ctr {
        n: 4,
        kind: Up,
        preset: 1,
    };
    assert_eq!(c.scan(&mut c.rig(), &[1, 0], true), (false, 0));
}

#[test]
fn ctud_up_and_down_in_one_execution_cancel() {
    // TC9.
    let c = Ctr {
        n: 5,
        kind: UpDown,
        preset: 1,
    };
    let mut rig = c.rig();
    c.scan(&mut rig, &[], true);
    assert_eq!(c.scan(&mut rig, &[1, 1, 0], true), (false, 0));
}

#[test]
fn ctd_negative_cv_does_not_decrement() {
    // TC8.
    let c = Ctr {
        n: 6,
        kind: Down,
        preset: 1,
    };
    let mut rig = c.rig();
    rig.scan(|b, l| mem::set_i16_be(b, value_at(l, 6), -3));
    assert_eq!(c.scan(&mut rig, &[1, 0], true), (false, -3));
}

#[test]
fn closed_gate_sees_all_inputs_off_and_updates_memory() {
    // §3.6: counters in an inactive segment see 0 on every input; memories record 0, so the
    // input still being on when the gate opens counts as an edge.
    let c = Ctr {
        n: 7,
        kind: Up,
        preset: 5,
    };
    let mut rig = c.rig();
    c.scan(&mut rig, &[1, 0], true);
    c.scan(&mut rig, &[1, 1], false);
    assert_eq!(c.scan(&mut rig, &[1, 0], true), (false, 1));
}

#[test]
fn reset_keeps_edge_memory_and_checks_range() {
    let c = Ctr {
        n: 0,
        kind: Up,
        preset: 5,
    };
    let mut rig = c.rig();
    c.scan(&mut rig, &[], true);
    rig.scan(|b, l| {
        c.exec(b, l, &[1, 0], true);
        reset_range(b, l, 0, 1).unwrap();
    });
    assert_eq!(
        c.scan(&mut rig, &[1, 0], true),
        (false, 0),
        "CU still high after R: no new edge"
    );
    let (b, l) = rig.img.split_mut();
    assert_eq!(reset_range(b, l, 30, 3), Err(ErrorCode::OperandRange));
    assert_eq!(
        execute(b, l, 32, Up, 0, Gate::scr(true), 1, Rules::IN_FORCE),
        Err(ErrorCode::OperandRange)
    );
}
