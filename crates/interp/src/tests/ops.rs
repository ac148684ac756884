//! Instruction groups: stack edge cases, boxes with flags and error paths, immediate I/O.

use super::build::*;
use stljit_core::ir::{
    ArithOp, BoxOp, CmpOp, CmpType, Contact, Conversion, Loc, Op, Operand, TimerKind,
};
use stljit_core::{Area, ErrorCode, TimerId, Width};

fn smb1(sim: &Sim) -> u32 {
    sim.val(mem(Area::SM, 1), Width::Byte)
}

fn ptr_at_vd(n: u32) -> Operand {
    Operand::Indirect(Loc {
        area: Area::V,
        offset: n,
    })
}

#[test]
fn stack_ops_bit_vector_rules() {
    // §3.2: LDS with n > 8 reads 0 (beyond the register); LRD copies S1; AENO with ENO 0.
    let mut sim = Sim::main(vec![
        ld(sm(0, 0)),
        ldn(sm(0, 0)),
        Op::ReadSecond,
        out(q(0, 0)), // S1 = 1
        Op::Pick(12),
        out(q(0, 1)), // 0
        Op::Pop,
        Op::AndEno, // no box ran: ENO = 0 (S4)
        out(q(0, 2)),
    ]);
    sim.scan(&[]);
    assert_eq!(sim.bits(&[q(0, 0), q(0, 1), q(0, 2)]), [1, 0, 0]);
}

#[test]
fn box_without_power_flow_does_nothing_and_clears_eno() {
    let add = Op::Box(BoxOp::IntArith {
        op: ArithOp::Add,
        width: Width::Word,
        src: k(1),
        dst: v(0),
    });
    let mut sim = Sim::main(vec![
        ld(sm(0, 0)),
        movw(k(1), v(0)),
        Op::AndEno,
        out(q(0, 0)),
        ldn(sm(0, 0)),
        add,
        Op::AndEno,
        out(q(0, 1)),
    ]);
    sim.scan(&[]);
    assert_eq!(sim.word(v(0)), 1);
    assert_eq!(sim.bits(&[q(0, 0), q(0, 1)]), [1, 0]);
    assert_eq!(smb1(&sim), 0, "§4.0 rule 1: no flag changes");
}

#[test]
fn bad_pointer_is_0x0006_and_writes_nothing() {
    // §1.6, E2: VD0 = 0 is no pointer; a pointer into SMB0 is read-only (A8).
    let sm_ptr = stljit_runtime::pointer::make(Area::SM, 4).unwrap();
    let add = Op::Box(BoxOp::IntArith {
        op: ArithOp::Add,
        width: Width::Word,
        src: k(1),
        dst: ptr_at_vd(4),
    });
    let mut sim = Sim::main(vec![
        ld(sm(0, 0)),
        movw(k(7), ptr_at_vd(0)),
        Op::AndEno,
        out(q(0, 0)),
        ld(sm(0, 0)),
        movd(k(i64::from(sm_ptr)), v(4)),
        add,
        out(q(0, 1)),
    ]);
    sim.scan(&[]);
    assert_eq!(sim.img.last_error(), ErrorCode::IndirectAddress as u16);
    assert_eq!(sim.img.error_site(), (0, 6));
    assert!(!sim.bit(q(0, 0)));
    assert!(!sim.img.eno());
    // Nothing written through the pointer; the error sets SM4.3 (`RUN_Err`, s7-200-more §0.4).
    assert_eq!(sim.val(mem(Area::SM, 4), Width::Word), 0x0800);
    assert_eq!(smb1(&sim), 0, "operand error: no flags");
}

#[test]
fn set_reset_ranges_and_errors() {
    let mut sim = Sim::main(vec![
        ld(sm(0, 0)),
        set(q(15, 6), 3), // M11: past the end → 0x0091, nothing set
        set(q(15, 6), 0), // M12: no-op
        set(tbit(5), 2),
        Op::SetRange {
            start: q(1, 0),
            count: k(2),
            value: true,
            immediate: true,
        },
    ]);
    sim.scan(&[]);
    assert_eq!(sim.img.last_error(), ErrorCode::OperandRange as u16);
    assert_eq!(sim.val(mem(Area::Q, 15), Width::Byte), 0);
    assert!(sim.img.timer_bit(5) && sim.img.timer_bit(6));
    assert_eq!(sim.img.timer_value(5), 0, "S on T sets only the bit (A10)");
    assert_eq!(sim.val(mem(Area::Q, 1), Width::Byte), 3);
}

#[test]
fn immediate_io_reads_physical_copy() {
    // §4.2 / A9: after `= I0.0` the image differs from the physical input.
    let ldi = Op::Load(Contact::ImmediateInput {
        bit: i(0, 0),
        negated: false,
    });
    let mut sim = Sim::main(vec![
        ld(sm(0, 0)),
        out(i(0, 0)),
        ld(i(0, 0)),
        out(q(0, 0)),
        ldi,
        out(q(0, 1)),
        ld(sm(0, 0)),
        Op::Box(BoxOp::ImmediateRead {
            input: 1,
            dst: v(0),
        }),
        Op::Box(BoxOp::ImmediateWrite {
            src: k(0x81),
            output: 3,
        }),
        Op::Assign {
            bit: q(2, 2),
            immediate: true,
        },
    ]);
    sim.img.set_inputs(&[0, 0x5A]);
    sim.scan(&[i(1, 1), i(1, 3), i(1, 4), i(1, 6)]);
    assert_eq!(sim.bits(&[q(0, 0), q(0, 1)]), [1, 0]);
    assert_eq!(sim.val(v(0), Width::Byte), 0x5A);
    assert_eq!(sim.val(mem(Area::Q, 3), Width::Byte), 0x81);
    assert_eq!(sim.img.phys_out()[3], 0x81);
    assert_eq!(sim.img.phys_out()[2], 0x04);
}

#[test]
fn accumulator_byte_write_keeps_upper_bits() {
    // A5: a byte write replaces only the low 8 bits (AC0 as a byte is offset 3).
    let mut sim = Sim::main(vec![
        ld(sm(0, 0)),
        movd(k(0x1122_3344), ac(0)),
        movb(k(0xFF), mem(Area::AC, 3)),
    ]);
    sim.scan(&[]);
    assert_eq!(sim.val(ac(0), Width::DWord), 0x1122_33FF);
}

#[test]
fn block_moves_fill_and_counts() {
    let bm = |width, n| {
        Op::Box(BoxOp::BlockMove {
            width,
            src: v(0),
            dst: v(100),
            count: k(n),
        })
    };
    let mut sim = Sim::main(vec![
        ld(sm(0, 0)),
        Op::Box(BoxOp::Fill {
            src: k(0x0102),
            dst: v(0),
            count: k(3),
        }),
        bm(Width::Word, 3),
        Op::AndEno,
        out(q(0, 0)),
        ld(sm(0, 0)),
        bm(Width::Byte, 0), // §4.7: N = 0 → 0x0091
        Op::AndEno,
        out(q(0, 1)),
    ]);
    sim.scan(&[]);
    assert_eq!(sim.val(v(100), Width::DWord), 0x0102_0102);
    assert_eq!(sim.val(v(104), Width::Word), 0x0102);
    assert_eq!(sim.bits(&[q(0, 0), q(0, 1)]), [1, 0]);
    assert_eq!(sim.img.last_error(), ErrorCode::OperandRange as u16);
}

#[test]
fn mul_div_conversions_and_shift_register() {
    let mut sim = Sim::main(vec![
        ld(sm(0, 0)),
        movd(k(0xFFFF_0007), v(0)),
        Op::Box(BoxOp::DivWide {
            src: k(2),
            dst: v(0),
        }),
        movd(k(-3), v(4)),
        Op::Box(BoxOp::MulWide {
            src: k(1000),
            dst: v(4),
        }),
        movd(k(i64::from((-2.5f32).to_bits())), v(8)),
        Op::Box(BoxOp::Convert {
            conv: Conversion::Round,
            src: v(8),
            dst: v(12),
        }),
        movw(k(0x1234), v(16)),
        Op::Box(BoxOp::Convert {
            conv: Conversion::BcdToInt,
            src: v(16),
            dst: v(16),
        }),
        Op::Box(BoxOp::Swap { dst: v(18) }),
        Op::Box(BoxOp::ShiftRegister {
            data: sm(0, 0),
            start: m(0, 0),
            len: k(4),
        }),
    ]);
    sim.scan(&[]);
    assert_eq!(
        sim.val(v(0), Width::DWord),
        0x0001_0003,
        "§4.8 DIV: remainder high, quotient low"
    );
    assert_eq!(sim.val(v(4), Width::DWord) as i32, -3000);
    assert_eq!(sim.val(v(12), Width::DWord) as i32, -3, "M6");
    assert_eq!(sim.word(v(16)), 1234);
    sim.scan(&[]);
    assert_eq!(
        sim.val(mem(Area::M, 0), Width::Byte),
        0b11,
        "two SHRB steps with DATA = 1"
    );
}

#[test]
fn real_and_compare_boxes() {
    let r = |x: f32| k(i64::from(x.to_bits()));
    let mut sim = Sim::main(vec![
        ld(sm(0, 0)),
        movd(r(2.0), v(0)),
        Op::Box(BoxOp::RealArith {
            op: ArithOp::Div,
            src: r(0.0),
            dst: v(0),
        }),
        Op::AndEno,
        out(q(0, 0)),
        Op::Load(Contact::Compare {
            ty: CmpType::Real,
            op: CmpOp::Gt,
            lhs: r(f32::INFINITY),
            rhs: v(0),
        }),
        out(q(0, 1)),
        Op::Load(Contact::Compare {
            ty: CmpType::Byte,
            op: CmpOp::Gt,
            lhs: k(200),
            rhs: k(100),
        }),
        out(q(0, 2)),
    ]);
    sim.scan(&[]);
    assert_eq!(sim.bits(&[q(0, 0), q(0, 1), q(0, 2)]), [0, 1, 1]);
    assert_eq!(smb1(&sim), 1 << 3, "DIV0 sets SM1.3 only");
    assert_eq!(f32::from_bits(sim.val(v(0), Width::DWord)), 2.0);
}

#[test]
fn timers_in_an_inactive_segment() {
    // §3.6 / TC13: TOF in an inactive segment is held reset; coils in it are driven to 0.
    let mut sim = Sim::main(vec![
        Op::ScrBegin { bit: s(0, 0) },
        ld(sm(0, 0)),
        Op::Timer {
            kind: TimerKind::Off,
            timer: TimerId(30),
            preset: k(5),
        },
        out(q(0, 0)),
        Op::ScrEnd,
        ld(sm(0, 0)),
        out(q(0, 1)),
    ]);
    sim.scan(&[]);
    assert_eq!(sim.bits(&[q(0, 0), q(0, 1)]), [0, 1]);
    assert!(!sim.img.timer_bit(30));
}

#[test]
fn reset_counters_and_timers_ranges() {
    let mut sim = Sim::main(vec![
        ld(sm(0, 0)),
        movw(k(9), cv(3)),
        movw(k(9), tv(63)),
        Op::ResetCounters {
            first: stljit_core::CounterId(3),
            count: k(1),
        },
        Op::ResetTimers {
            first: TimerId(63),
            count: k(2),
        },
    ]);
    sim.scan(&[]);
    assert_eq!(sim.word(cv(3)), 0);
    assert_eq!(sim.word(tv(63)), 9, "R T63, 2 runs past T63: nothing reset");
    assert_eq!(sim.img.last_error(), ErrorCode::OperandRange as u16);
}
