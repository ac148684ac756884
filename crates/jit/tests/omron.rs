//! The Omron CP ops (interlock, Omron timers and counters, the data boxes with condition
//! flags) on the JIT against the reference interpreter, as IR text for the CP1H profile:
//! random stimulus, whole image compared after every scan. The front end's conformance cases
//! check the values against the spec; these check that both engines agree on every byte,
//! hidden timer state and condition flags included.

#[allow(dead_code)] // the S7 helpers of `common` are for the other test binary
mod common;

use common::check;
use stljit_core::ProfileId;
use stljit_core::ir::OmronArith;
use stljit_diff::generate::Stimulus;
use stljit_diff::rng::Choices;

/// A random CP1H stimulus (input words CIO 0–1) of `scans` scans.
fn stimulus(seed: u64, scans: u32) -> Stimulus {
    let bytes: Vec<u8> = (0..4096u64)
        .map(|i| {
            (seed
                .wrapping_mul(0x9E37_79B9_7F4A_7C15)
                .wrapping_add(i * 0x5851_F42D)
                >> 23) as u8
        })
        .collect();
    let mut c = Choices::from_bytes(&bytes);
    stljit_diff::generate::stimulus::generate(&mut c, ProfileId::Cp1h, scans)
}

fn program(body: &str, edges: usize) -> stljit_core::ir::Program {
    let mut text =
        String::from("stljit-ir 1\nprofile cp1h\nlogic_stack_depth 16\nfile file0 \"t.omr\"\n");
    for i in 0..edges {
        text.push_str(&format!("edge edge{i} init={}\n", i % 2));
    }
    text.push_str("pou pou0 main \"MAIN\" {\n");
    for (i, line) in body.lines().filter(|l| !l.trim().is_empty()).enumerate() {
        text.push_str(&format!("  op{i} @file0:{}:1 {}\n", i + 1, line.trim()));
    }
    text.push_str("}\n");
    match stljit_core::text::parse(&text) {
        Ok(p) => p,
        Err(e) => panic!("{e}\n{text}"),
    }
}

#[test]
fn timers_counters_and_interlock() {
    let p = program(
        "load bit I.1.0
         omron_timer kind=Tim timer=T0 set_value=const(3)
         load bit I.1.1
         omron_timer kind=TimH timer=T1 set_value=const(0x25)
         load bit I.1.2
         omron_timer kind=TmhhX timer=T2 set_value=const(40)
         load bit I.1.3
         load bit I.1.4
         omron_timer kind=Ttim timer=T3 set_value=const(0x12)
         load bit I.1.3
         load bit I.1.4
         omron_timer kind=TtimX timer=T4 set_value=Dm.0
         load bit I.1.5
         load bit I.1.6
         omron_counter kind=Cnt counter=C0 set_value=const(0x3)
         load bit I.1.5
         load bit I.1.6
         load bit I.1.7
         omron_counter kind=CntrX counter=C1 set_value=const(4)
         load bit I.0.0
         interlock
         load bit I.1.0
         assign bit=Q.1.0 immediate=0
         load bit I.1.1
         omron_timer kind=TimX timer=T5 set_value=const(5)
         load bit I.1.2
         load bit I.1.3
         omron_counter kind=Cntr counter=C2 set_value=const(0x2)
         load bit I.1.4
         edge slot=edge0 falling=0
         assign bit=Work.1.0 immediate=0
         interlock_end
         load bit TimerBit.0.0
         assign bit=Q.1.1 immediate=0
         load bit CounterBit.1.0
         assign bit=Q.1.2 immediate=0
         load bit Flags.0.0
         assign bit=Q.1.3 immediate=0",
        1,
    );
    for seed in 0..6 {
        check(&p, &stimulus(seed, 60));
    }
}

/// Every timer kind with constant set values (valid, non-BCD, zero, the largest), execution
/// conditions shared between timers so that starts, running executions and resets meet in
/// every order, and PVs rewritten by MOV: the resets and starts compiled code stores inline
/// must leave the interpreter's bytes, hidden time state included.
#[test]
fn timers_with_constant_set_values() {
    let mut body = String::new();
    let kinds = [
        "Tim", "TimX", "TimH", "TimHX", "Tmhh", "TmhhX", "Ttim", "TtimX",
    ];
    let svs = ["const(0x3)", "const(0x1A)", "const(0)", "const(0x9999)"];
    let mut n = 0;
    for kind in kinds {
        for sv in svs {
            body.push_str(&format!("load bit I.1.{}\n", n % 8));
            if kind.starts_with("Ttim") {
                body.push_str(&format!("load bit I.1.{}\n", (n + 3) % 8));
            }
            body.push_str(&format!(
                "omron_timer kind={kind} timer=T{n} set_value={sv}\n"
            ));
            n += 1;
        }
    }
    for (bit, t) in [(1, 1), (6, 6), (3, 13), (5, 20)] {
        body.push_str(&format!(
            "load bit I.0.{bit}\nomron move double=0 src=I.0 dst=TimerValue.{}\n",
            2 * t
        ));
    }
    body.push_str("load bit Flags.0.0\nassign bit=Q.1.0 immediate=0\n");
    let p = program(&body, 0);
    for seed in 0..8 {
        check(&p, &stimulus(seed, 80));
    }
}

/// Every counter kind with constant set values (valid, non-BCD, zero), the inputs shared
/// between counters so that count edges, held inputs and resets meet in every order, and PVs
/// rewritten by MOV (some non-BCD): the paths compiled code stores inline (a reset, a quiet
/// execution) and the counts it calls for must leave the interpreter's bytes.
#[test]
fn counters_with_constant_set_values() {
    let mut body = String::new();
    let kinds = ["Cnt", "CntX", "Cntr", "CntrX"];
    let svs = ["const(0x3)", "const(0x1A)", "const(0)", "const(0x9999)"];
    let mut n = 0;
    for kind in kinds {
        for sv in svs {
            let ring = kind.starts_with("Cntr");
            let inputs: &[u32] = if ring {
                &[n % 8, (n + 3) % 8, (n + 5) % 8]
            } else {
                &[n % 8, (n + 6) % 8]
            };
            for i in inputs {
                body.push_str(&format!("load bit I.1.{i}\n"));
            }
            body.push_str(&format!(
                "omron_counter kind={kind} counter=C{n} set_value={sv}\n"
            ));
            n += 1;
        }
    }
    // Rewrite a few PVs from the inputs (a count then meets whatever pattern they have).
    for (bit, c) in [(1, 1), (6, 6), (3, 11)] {
        body.push_str(&format!(
            "load bit I.0.{bit}\nomron move double=0 src=I.0 dst=CounterValue.{}\n",
            2 * c
        ));
    }
    body.push_str("load bit Flags.0.0\nassign bit=Q.1.0 immediate=0\n");
    let p = program(&body, 0);
    for seed in 0..8 {
        check(&p, &stimulus(seed, 80));
    }
}

#[test]
fn data_boxes_and_every_arithmetic_op() {
    let mut body = String::from(
        "load bit I.1.0
         omron move double=0 src=I.0 dst=Dm.0
         omron move double=1 src=I.0 dst=Dm.4
         omron compare double=0 signed=1 lhs=Dm.0 rhs=const(0x8000)
         load bit Flags.0.2
         assign bit=Q.1.0 immediate=0
         omron compare double=1 signed=0 lhs=Dm.4 rhs=const(0x12345)
         load bit Flags.1.1
         assign bit=Q.1.1 immediate=0
         load bit I.1.1
         omron compare double=0 signed=0 lhs=I.2 rhs=Dm.0
         load bit Flags.0.4
         assign bit=Q.1.2 immediate=0
         omron compare double=1 signed=1 lhs=I.0 rhs=Dm.4
         load bit Flags.1.2
         assign bit=Q.1.3 immediate=0
         load bit I.1.2
         omron flags save=1
         load bit I.1.3
         omron flags save=0
         load bit Flags.0.3
         omron move double=0 src=const(0) dst=Dm.40
         load bit Flags.0.5
         assign bit=Q.1.4 immediate=0
",
    );
    for (i, op) in OmronArith::ALL.iter().enumerate() {
        let dst = 100 + 8 * i;
        body.push_str(&format!(
            "load bit I.1.{}\n omron arith op={op:?} lhs=Dm.0 rhs=I.0 dst=Dm.{dst}\n load bit Flags.0.{}\n assign bit=Work.{}.{} immediate=0\n",
            i % 8,
            i % 8,
            2 * (i / 8),
            i % 8
        ));
    }
    let p = program(&body, 0);
    for seed in 0..6 {
        check(&p, &stimulus(seed, 40));
    }
}

#[test]
fn indirect_and_index_register_operands() {
    // Pointers come from the inputs (most miss: AER), the index register walks through D.
    let p = program(
        "load bit Flags.1.4
         omron move double=0 src=I.0 dst=Dm.40
         omron move double=0 src=I.2 dst=Dm.42
         omron move double=0 src=const(0x0123) dst=Dm.44
         omron set_index ea=65936 ir=0
         omron set_index ea=49152 ir=1
         omron move double=0 src=const(0x1111) dst=ind_bin(20)
         omron move double=0 src=const(0x2222) dst=ind_bcd(21)
         omron move double=0 src=const(0x3333) dst=ind_bcd(22)
         omron move double=0 src=I.2 dst=ind_ir(0,+0,post1)
         omron move double=1 src=I.0 dst=ind_ir(0,+2,post2)
         omron move double=0 src=ind_ir(1,+0,none) dst=Dm.60
         omron move double=0 src=ind_ir(0,-3,pre1) dst=Dm.62
         omron compare double=0 signed=1 lhs=ind_bin(21) rhs=const(5)
         load bit I.1.0
         omron arith op=Add lhs=ind_ir(0,dr2,none) rhs=ind_bcd(20) dst=ind_ir(0,+4,pre2)
         omron arith op=MulL lhs=ind_bin(20) rhs=Dm.0 dst=ind_ir(0,+8,none)
         omron move double=0 src=I.0 dst=DataReg.4
         load bit Flags.1.3
         assign bit=Q.0.0 immediate=0",
        0,
    );
    for seed in 0..8 {
        check(&p, &stimulus(seed, 30));
    }
}
