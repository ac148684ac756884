//! Lowering, op by op, against the patterns the crate doc states (the lead's decisions) and the
//! Omron memory mapping of `core::omron` (big-endian words at `2w`, bit 00 = LSB in byte
//! `2w + 1`; CIO 0–1 are area I, CIO 100–101 area Q).

use stljit_core::ir::{
    BitLoc, BoxOp, Contact, EdgeDecl, Loc, OmronArith, OmronBox, OmronCounterKind, OmronTimerKind,
    Op, Operand, PouKind, Program, verify,
};
use stljit_core::omron::{SystemBit, tr_bit};
use stljit_core::{Area, CounterId, EdgeSlot, LabelId, OpIdx, PouId, ProfileId, TimerId};
use stljit_front_omron::compile_str;

fn program(text: &str) -> Program {
    let c = compile_str("t.omr", text, ProfileId::Cp1h);
    let p = c.program.unwrap_or_else(|| panic!("{:#?}", c.diagnostics));
    verify(&p).expect("verifies");
    assert_eq!(p.logic_stack_depth, 16);
    p
}

/// The main POU's ops without the final `End`.
fn main_ops(text: &str) -> Vec<Op> {
    let p = program(&format!("{text}\nEND(001)\n"));
    let mut ops = p.pous[0].ops.clone();
    assert_eq!(ops.pop(), Some(Op::End { conditional: false }));
    ops
}

fn bit(area: Area, byte: u32, bit: u8) -> BitLoc {
    BitLoc { area, byte, bit }
}
/// CIO 0.bb: input word 0, so area I; bits 00–07 in byte 1.
fn i0(b: u8) -> BitLoc {
    bit(Area::I, 1 - u32::from(b / 8), b % 8)
}
/// CIO 100.bb: output word 0, area Q.
fn q0(b: u8) -> BitLoc {
    bit(Area::Q, 1 - u32::from(b / 8), b % 8)
}
fn c(b: BitLoc) -> Contact {
    Contact::Bit {
        bit: b,
        negated: false,
    }
}
fn n(b: BitLoc) -> Contact {
    Contact::Bit {
        bit: b,
        negated: true,
    }
}
fn edge(slot: usize, falling: bool) -> Op {
    Op::Edge {
        slot: EdgeSlot::new(slot),
        falling,
    }
}
fn set(b: BitLoc, value: bool) -> Op {
    Op::SetRange {
        start: b,
        count: Operand::Const(1),
        value,
        immediate: false,
    }
}
fn assign(b: BitLoc) -> Op {
    Op::Assign {
        bit: b,
        immediate: false,
    }
}
/// `ImmediateWrite` of Q byte `b` (the image byte to the physical output).
fn write(b: u32) -> Op {
    Op::Box(BoxOp::ImmediateWrite {
        src: Operand::Mem(Loc {
            area: Area::Q,
            offset: b,
        }),
        output: b,
    })
}
fn dm(w: u32) -> Operand {
    Operand::Mem(Loc {
        area: Area::Dm,
        offset: 2 * w,
    })
}

#[test]
fn contacts_blocks_and_their_options() {
    // LD/AND/OR (NOT forms) are Load/And/Or; AND LD/OR LD the block ops; OR NOT negated.
    assert_eq!(
        main_ops("LD 0.00\nOR NOT 0.01\nLD 0.02\nAND 0.03\nOR LD\nAND NOT 0.04\nOUT 100.00"),
        [
            Op::Load(c(i0(0))),
            Op::Or(n(i0(1))),
            Op::Load(c(i0(2))),
            Op::And(c(i0(3))),
            Op::OrBlock,
            Op::And(n(i0(4))),
            assign(q0(0)),
        ]
    );
    // @LD: Load; Edge(rising). %AND: Load; Edge(falling); AndBlock. @OR: …; OrBlock.
    let p = program("@LD 0.00\n%AND 0.01\n@OR W0.00\nOUT 100.00\nEND(001)");
    let w0 = bit(Area::Work, 1, 0);
    assert_eq!(
        p.pous[0].ops[..8],
        [
            Op::Load(c(i0(0))),
            edge(0, false),
            Op::Load(c(i0(1))),
            edge(1, true),
            Op::AndBlock,
            Op::Load(c(w0)),
            edge(2, false),
            Op::OrBlock,
        ]
    );
    // §2.6: rising memories start ON, falling ones OFF.
    assert_eq!(
        p.edges,
        [
            EdgeDecl { init: true },
            EdgeDecl { init: false },
            EdgeDecl { init: true }
        ]
    );
    // `!` on an input-word bit first copies the whole physical input word into the image
    // (whatever the condition: on a pushed P_On), then reads the bit; on a W bit it is a plain
    // contact.
    let on = c(SystemBit::On.bit_loc());
    let read = |b: u32| {
        Op::Box(BoxOp::ImmediateRead {
            input: b,
            dst: Operand::Mem(Loc {
                area: Area::I,
                offset: b,
            }),
        })
    };
    assert_eq!(
        main_ops("!LD 1.15\n!AND W3.08\nOUT 100.00")[..6],
        [
            Op::Load(on),
            read(2),
            read(3),
            Op::Pop,
            Op::Load(c(bit(Area::I, 2, 7))),
            Op::And(c(bit(Area::Work, 6, 0))),
        ]
    );
}

#[test]
fn intermediate_and_outputs() {
    // NOT: Not; UP: Edge rising; DOWN: Edge falling; OUT NOT: Not; Assign; Not.
    assert_eq!(
        main_ops("LD 0.00\nNOT(520)\nUP(521)\nDOWN(522)\nOUT NOT 100.01\n!OUT 100.02"),
        [
            Op::Load(c(i0(0))),
            Op::Not,
            edge(0, false),
            edge(1, true),
            Op::Not,
            assign(q0(1)),
            Op::Not,
            // `!OUT`: the bit, then the whole image word 100 to the physical outputs.
            assign(q0(2)),
            Op::Load(c(SystemBit::On.bit_loc())),
            write(0),
            write(1),
            Op::Pop,
        ]
    );
    // `!SET` refreshes when it executes: on its own power flow.
    assert_eq!(
        main_ops("LD 0.00\n!SET 101.03")[1..],
        [set(bit(Area::Q, 3, 3), true), write(2), write(3)]
    );
    // `!MOV` from an input word to an output word: the input word before, the output after.
    assert_eq!(
        main_ops("LD 0.00\n!MOV(021) 1 100")[1..],
        [
            Op::Box(BoxOp::ImmediateRead {
                input: 2,
                dst: Operand::Mem(Loc {
                    area: Area::I,
                    offset: 2
                })
            }),
            Op::Box(BoxOp::ImmediateRead {
                input: 3,
                dst: Operand::Mem(Loc {
                    area: Area::I,
                    offset: 3
                })
            }),
            Op::Omron(OmronBox::Move {
                double: false,
                src: Operand::Mem(Loc {
                    area: Area::I,
                    offset: 2
                }),
                dst: Operand::Mem(Loc {
                    area: Area::Q,
                    offset: 0
                })
            }),
            write(0),
            write(1),
        ]
    );
    // SET/RSET: SetRange count 1; @SET: Dup; Edge; SetRange; Pop; %RSET the falling edge.
    assert_eq!(
        main_ops("LD 0.00\nSET W0.00\n@SET W0.01\n%RSET H1.15")[1..],
        [
            set(bit(Area::Work, 1, 0), true),
            Op::Dup,
            edge(0, false),
            set(bit(Area::Work, 1, 1), true),
            Op::Pop,
            Op::Dup,
            edge(1, true),
            set(bit(Area::Holding, 2, 7), false),
            Op::Pop,
        ]
    );
    // KEEP (S1 set, S0 reset): SetRange(0); Not; AndBlock; SetRange(1): reset wins.
    assert_eq!(
        main_ops("LD 0.00\nLD 0.01\nKEEP(011) 100.00")[2..],
        [set(q0(0), false), Op::Not, Op::AndBlock, set(q0(0), true)]
    );
    // DIFU: Dup; Edge rising; SetRange(1); Not; SetRange(0); Pop. DIFD: falling edge.
    assert_eq!(
        main_ops("LD 0.00\nDIFU(013) W0.00\nDIFD(014) W0.01")[1..],
        [
            Op::Dup,
            edge(0, false),
            set(bit(Area::Work, 1, 0), true),
            Op::Not,
            set(bit(Area::Work, 1, 0), false),
            Op::Pop,
            Op::Dup,
            edge(1, true),
            set(bit(Area::Work, 1, 1), true),
            Op::Not,
            set(bit(Area::Work, 1, 1), false),
            Op::Pop,
        ]
    );
}

#[test]
fn tr_bits_and_continuation_after_an_output() {
    // §6.2: OUT TR0 stores the EC; LD TR0 pushes it back; outputs never pop.
    assert_eq!(
        main_ops("LD 0.00\nOUT TR0\nAND 0.01\nOUT 100.00\nLD TR0\nAND 0.02\nOUT 100.01"),
        [
            Op::Load(c(i0(0))),
            assign(tr_bit(0)),
            Op::And(c(i0(1))),
            assign(q0(0)),
            Op::Load(c(tr_bit(0))),
            Op::And(c(i0(2))),
            assign(q0(1)),
        ]
    );
}

#[test]
fn timers_counters_and_numbers() {
    // TIM n #sv (BCD), TTIM (2 conditions), CNT (2), CNTR (3); numbers 0000 / T0000 / &n.
    let ops = main_ops(
        "LD 0.00\nTIM 0001 #0003\nLD 0.01\nLD 0.02\nTTIMX(555) T0002 &100\nLD 0.01\nLD 0.02\nCNT &2 #0002\nLD 0.03\nLD 0.04\nLD 0.05\nCNTR(012) C0003 D5",
    );
    assert_eq!(
        ops[1],
        Op::OmronTimer {
            kind: OmronTimerKind::Tim,
            timer: TimerId(1),
            set_value: Operand::Const(0x0003)
        }
    );
    assert_eq!(
        ops[4],
        Op::OmronTimer {
            kind: OmronTimerKind::TtimX,
            timer: TimerId(2),
            set_value: Operand::Const(100)
        }
    );
    assert_eq!(
        ops[7],
        Op::OmronCounter {
            kind: OmronCounterKind::Cnt,
            counter: CounterId(2),
            set_value: Operand::Const(2)
        }
    );
    assert_eq!(
        ops[11],
        Op::OmronCounter {
            kind: OmronCounterKind::Cntr,
            counter: CounterId(3),
            set_value: dm(5)
        }
    );
    // T as a bit is the completion flag (TimerBit byte n); as a word the PV (offset 2n).
    assert_eq!(
        main_ops("LD T0001\nMOV(021) T0001 C0002"),
        [
            Op::Load(c(bit(Area::TimerBit, 1, 0))),
            Op::Omron(OmronBox::Move {
                double: false,
                src: Operand::Mem(Loc {
                    area: Area::TimerValue,
                    offset: 2
                }),
                dst: Operand::Mem(Loc {
                    area: Area::CounterValue,
                    offset: 4
                }),
            }),
        ]
    );
}

#[test]
fn data_boxes_constants_and_comparison_contacts() {
    // MOVL with a double constant: Omron value order, the low 16 bits are the low word.
    let ops = main_ops(
        "LD P_On\n@MOVL(498) #12345678 D10\nCPS(114) D0 -5\n+L(401) D0 &70000 D4\n-(410) W1 +1 100",
    );
    let on = SystemBit::On.bit_loc();
    assert_eq!(ops[0], Op::Load(c(on)));
    assert_eq!(
        ops[1..5],
        [
            Op::Dup,
            edge(0, false),
            Op::Omron(OmronBox::Move {
                double: true,
                src: Operand::Const(0x1234_5678),
                dst: dm(10)
            }),
            Op::Pop,
        ]
    );
    // -5 as a signed 16-bit constant is #FFFB (two's complement, §1.6).
    assert_eq!(
        ops[5],
        Op::Omron(OmronBox::Compare {
            double: false,
            signed: true,
            lhs: dm(0),
            rhs: Operand::Const(0xFFFB)
        })
    );
    assert_eq!(
        ops[6],
        Op::Omron(OmronBox::Arith {
            op: OmronArith::AddL,
            lhs: dm(0),
            rhs: Operand::Const(70000),
            dst: dm(4)
        })
    );
    // CIO 100 is output word 0 (area Q offset 0).
    assert_eq!(
        ops[7],
        Op::Omron(OmronBox::Arith {
            op: OmronArith::Sub,
            lhs: Operand::Mem(Loc {
                area: Area::Work,
                offset: 2
            }),
            rhs: Operand::Const(1),
            dst: Operand::Mem(Loc {
                area: Area::Q,
                offset: 0
            }),
        })
    );
    // LD>=S D0 -5: Load(P_On); Compare(signed); Pop; Load(P_GE). AND<L: …; And(P_LT).
    assert_eq!(
        main_ops("LD>=S D0 -5\nAND<L D0 D2\nOUT 100.00")[..8],
        [
            Op::Load(c(on)),
            Op::Omron(OmronBox::Compare {
                double: false,
                signed: true,
                lhs: dm(0),
                rhs: Operand::Const(0xFFFB)
            }),
            Op::Pop,
            Op::Load(c(SystemBit::Ge.bit_loc())),
            Op::Load(c(on)),
            Op::Omron(OmronBox::Compare {
                double: true,
                signed: false,
                lhs: dm(0),
                rhs: dm(2)
            }),
            Op::Pop,
            Op::And(c(SystemBit::Lt.bit_loc())),
        ]
    );
}

#[test]
fn control_interlocks_jumps_and_subroutines() {
    let p = program(
        "LD 0.00\nIL(002)\nLD 0.01\nJMP(004) &1\nLD 0.02\nCJP(510) 2\nJME(005) 1\nJME(005) 2\nILC(003)\nLD 0.03\nJMP0(515)\nJME0(516)\nLD 0.04\nSBS(091) 3\nSBN(092) 3\nLD 0.05\nOUT 100.00\nRET(093)\nEND(001)\n",
    );
    let main = &p.pous[0];
    assert_eq!(
        main.ops,
        [
            Op::Load(c(i0(0))),
            Op::Interlock,
            Op::Load(c(i0(1))),
            // JMP jumps when the EC is OFF: Not; Jump; Not.
            Op::Not,
            Op::Jump(LabelId(0)),
            Op::Not,
            Op::Load(c(i0(2))),
            // CJP jumps when it is ON.
            Op::Jump(LabelId(1)),
            Op::Label(LabelId(0)),
            Op::Label(LabelId(1)),
            Op::InterlockEnd,
            Op::Load(c(i0(3))),
            Op::Not,
            Op::Jump(LabelId(2)),
            Op::Not,
            Op::Label(LabelId(2)),
            Op::Load(c(i0(4))),
            Op::Call(PouId(1)),
            Op::End { conditional: false },
        ]
    );
    assert_eq!(main.labels, [OpIdx(8), OpIdx(9), OpIdx(15)]);
    let sub = &p.pous[1];
    assert_eq!(sub.kind, PouKind::Subroutine(3));
    assert_eq!(
        sub.ops,
        [
            Op::Load(c(i0(5))),
            assign(q0(0)),
            Op::Return { conditional: false }
        ]
    );
    // Every op has the location of its source line (the IL is on line 2, column 1).
    assert_eq!((main.locs[1].line, main.locs[1].col), (2, 1));
}

#[test]
fn symbols_stand_for_their_addresses() {
    use stljit_front_omron::{SourceFile, compile};
    let prog = SourceFile {
        name: "p.omr".into(),
        bytes: b"LD Start_PB\nOUT Motor\nEND(001)\n".to_vec(),
    };
    let syms = SourceFile { name: "s.txt".into(), bytes: "Name\tData Type\tAddress\tComment\nStart_PB\tBOOL\t0.00\tstart button\nMotor\tBOOL\t100.00\n".as_bytes().to_vec() };
    let out = compile(&[prog], Some(&syms), ProfileId::Cp1h);
    let p = out
        .program
        .unwrap_or_else(|| panic!("{:#?}", out.diagnostics));
    assert_eq!(p.pous[0].ops[..2], [Op::Load(c(i0(0))), assign(q0(0))]);
    assert_eq!(out.symbols.map(|s| s.len()), Some(2));
}

#[test]
fn tasks_run_in_ascending_number_with_a_task_start_between() {
    // Task 1 is written first; its jump label and its subroutine are moved behind task 0's.
    // Task 2 is in standby and the unassigned program never runs: neither is in the IR.
    let p = program(
        "$TASK CYCLIC 1\nLD 0.01\nJMP(004) &1\nJME(005) &1\nLD 0.02\nSBS(091) 7\nSBN(092) 7\nLD 0.03\nOUT 100.01\nRET(093)\nEND(001)\n\
         $TASK CYCLIC 0\nLD 0.00\nJMP(004) &1\nJME(005) &1\nEND(001)\n\
         $TASK CYCLIC 2 STANDBY\nLD 0.05\nOUT 100.05\nSBN(092) 8\nRET(093)\nEND(001)\n\
         $TASK UNASSIGNED\nLD 0.06\nOUT 100.06\nEND(001)\n",
    );
    let main = &p.pous[0];
    assert_eq!(
        main.ops,
        [
            // Task 0; its END falls through into task 1.
            Op::Load(c(i0(0))),
            Op::Not,
            Op::Jump(LabelId(0)),
            Op::Not,
            Op::Label(LabelId(0)),
            Op::TaskStart,
            // Task 1.
            Op::Load(c(i0(1))),
            Op::Not,
            Op::Jump(LabelId(1)),
            Op::Not,
            Op::Label(LabelId(1)),
            Op::Load(c(i0(2))),
            Op::Call(PouId(1)),
            Op::End { conditional: false },
        ]
    );
    assert_eq!(main.labels, [OpIdx(4), OpIdx(10)]);
    assert_eq!(p.pous.len(), 2, "only the running tasks' subroutines");
    assert_eq!(p.pous[1].kind, PouKind::Subroutine(7));
    // The task start has the location of the first instruction of the task it starts.
    assert_eq!(main.locs[5].line, 2);
}

#[test]
fn a_project_without_directives_is_task_0() {
    let plain = program("LD 0.00\nOUT 100.00\nEND(001)\n");
    let task0 = program("$TASK CYCLIC 0\nLD 0.00\nOUT 100.00\nEND(001)\n");
    assert_eq!(plain.pous[0].ops, task0.pous[0].ops);
    assert!(!plain.pous[0].ops.contains(&Op::TaskStart));
}

#[test]
fn step_areas_and_block_programs() {
    let w = |b: u8| bit(Area::Work, 1, b);
    let saved = bit(Area::L, 30, 0);
    let on = c(SystemBit::On.bit_loc());
    let ops = main_ops(
        "LD 0.00\nIL(002)\nLD P_On\nSNXT(009) W0.00\nSTEP(008) W0.00\nLD 0.01\nSNXT(009) W0.01\nSTEP(008) W0.01\nSTEP(008)\nILC(003)\nLD 0.02\nBPRG(096) &5\nLD 0.03\nSET 100.00\nBEND(801)",
    );
    assert_eq!(
        ops,
        [
            Op::Load(c(i0(0))),
            Op::Interlock,
            Op::Load(on),
            set(w(0), true),
            // The first STEP inside IL–ILC saves the interlock's gate.
            Op::Load(on),
            assign(saved),
            Op::Pop,
            Op::InterlockEnd,
            Op::Load(c(w(0))),
            Op::And(c(saved)),
            Op::Interlock,
            Op::Pop,
            Op::Load(c(i0(1))),
            // SNXT: the current step OFF, the next ON.
            set(w(0), false),
            set(w(1), true),
            Op::InterlockEnd,
            Op::Load(c(w(1))),
            Op::And(c(saved)),
            Op::Interlock,
            Op::Pop,
            // The end of the area restores the interlock's gate.
            Op::InterlockEnd,
            Op::Load(c(saved)),
            Op::Interlock,
            Op::Pop,
            Op::InterlockEnd,
            Op::Load(c(i0(2))),
            Op::Not,
            Op::Jump(LabelId(0)),
            Op::Not,
            Op::Load(c(i0(3))),
            set(q0(0), true),
            Op::Label(LabelId(0)),
        ]
    );
}
