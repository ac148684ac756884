//! Interrupts (s7-200-more §3): interrupt routines, the first-scan network that gives the timed
//! interrupts their intervals and attaches the routines to events, and interrupt instructions
//! (ATCH, DTCH, ENI, DISI, CEVNT) anywhere, ENI/DISI in a routine included (error 0x0004).
//!
//! Events are mostly ones the simulation raises: input edges (the stimulus flips input bits,
//! I0.0–I0.3 among them), timed interrupts with intervals from 1 ms to 255 ms (several per
//! scan, or one every few scans) and, on the S7-200, T32/T96 reaching their preset (a
//! network running the timer is added); now and then one of the profile's other events, which
//! never occur. Routines may call subroutines (past the one allowed level they fail with
//! 0x0008), return early (CRETI) and, rarely, STOP.

use super::Gen;
use super::programs::{on, sm};
use stljit_core::interrupt::EventSource;
use stljit_core::ir::{BoxOp, IntOp, Loc, Op, Operand, TimerKind};
use stljit_core::{Area, PouId, TimerId, Width};

impl Gen<'_, '_> {
    /// The interrupt routines of the program about to be generated, as `(POU, number)`, the
    /// POUs numbered from `first`: none in most programs, one to three in a third of them.
    pub(crate) fn plan_interrupts(&mut self, first: usize) -> Vec<(PouId, u16)> {
        if !self.p.interrupts.any() || !self.c.chance(1, 3) {
            return Vec::new();
        }
        // Distinct numbers by construction (no rejection loop: a fuzzer's choices may run
        // out and answer 0 forever).
        let mut k = self.c.below(8) as u16;
        (0..self.c.range(1, 3) as usize)
            .map(|i| {
                if i > 0 {
                    k += self.c.range(1, 4) as u16;
                }
                (PouId::new(first + i), k)
            })
            .collect()
    }

    /// The first network of the main program when it has interrupt routines: on the first
    /// scan, the timed intervals, an ATCH for each routine (sometimes two) and usually ENI;
    /// then a network running T32/T96 when their event is attached.
    pub(crate) fn interrupt_setup(&mut self) {
        self.emit(Op::Load(on(sm(0, 1))));
        // Intervals: mostly a few ms (several per scan at the usual periods), sometimes longer
        // than a scan; 1–2 ms rarely, as a long stimulus pause then exhausts the loop budget
        // (each happening and routine run counts); 0 never fires.
        const INTERVALS: [u32; 9] = [1, 2, 5, 10, 20, 50, 100, 255, 0];
        for smb in [34, 35] {
            let ms = INTERVALS[self.c.weighted(&[1, 1, 3, 3, 2, 2, 1, 1, 1])];
            self.emit(Op::Box(BoxOp::Move {
                width: Width::Byte,
                src: Operand::Const(ms),
                dst: Operand::Mem(Loc {
                    area: Area::SM,
                    offset: smb,
                }),
            }));
        }
        let mut timers = Vec::new();
        for (routine, _) in self.int_routines.clone() {
            for _ in 0..self.c.range(1, 2) {
                let event = self.event();
                if let Some(EventSource::TimerReached { timer }) =
                    stljit_core::interrupt::event(event).map(|e| e.source)
                {
                    timers.push(timer);
                }
                self.emit(Op::Interrupt(IntOp::Attach { routine, event }));
            }
        }
        if self.c.chance(5, 6) {
            self.emit(Op::Interrupt(IntOp::Enable));
        }
        for timer in timers {
            let kind = *self.timers.entry(timer).or_insert(TimerKind::On);
            let preset = Operand::Const(self.c.range(1, 60));
            let c = self.contact();
            self.emit(Op::Load(c));
            self.emit(Op::Timer {
                kind,
                timer: TimerId(timer),
                preset,
            });
        }
    }

    /// A network with one interrupt instruction under a random condition.
    pub(crate) fn interrupt_network(&mut self) {
        self.expr(1);
        let op = match self.c.weighted(&[3, 2, 2, 2, 2]) {
            0 => {
                let (routine, _) =
                    self.int_routines[self.c.below(self.int_routines.len() as u32) as usize];
                IntOp::Attach {
                    routine,
                    event: self.event(),
                }
            }
            1 => IntOp::Detach {
                event: self.event(),
            },
            2 => IntOp::ClearEvent {
                event: self.event(),
            },
            3 => IntOp::Enable,
            _ => IntOp::Disable,
        };
        self.emit(Op::Interrupt(op));
    }

    /// An event of the profile: mostly an input edge, a timed interrupt, (S7-200) a timer
    /// event or an event of a counter, pulse output or serial port the program uses; now and
    /// then any other (every event source is simulated, so any may occur).
    fn event(&mut self) -> u8 {
        let ints = self.p.interrupts;
        let pick = |c: &mut crate::rng::Choices<'_>, f: &dyn Fn(EventSource) -> bool| {
            let all: Vec<u8> = ints
                .infos()
                .filter(|e| f(e.source))
                .map(|e| e.number)
                .collect();
            (!all.is_empty()).then(|| all[c.below(all.len() as u32) as usize])
        };
        let hsc = self.hsc_counters.clone();
        let hsc_weight = if hsc.is_empty() { 0 } else { 4 };
        let pulse = self.pulse_channels.clone();
        let pulse_weight = if pulse.is_empty() { 0 } else { 3 };
        let comm_weight = if self.comm { 3 } else { 0 };
        let weights = [4, 4, 1, 1, hsc_weight, pulse_weight, comm_weight];
        let choice = match self.c.weighted(&weights) {
            0 => pick(self.c, &|s| matches!(s, EventSource::InputEdge { .. })),
            1 => pick(self.c, &|s| matches!(s, EventSource::Timed { .. })),
            2 => pick(self.c, &|s| matches!(s, EventSource::TimerReached { .. })),
            3 => pick(self.c, &|_| true),
            5 => pick(
                self.c,
                &|s| matches!(s, EventSource::PulseOutput { channel } if pulse.contains(&channel)),
            ),
            6 => pick(self.c, &|s| matches!(s, EventSource::Communication)),
            _ => pick(
                self.c,
                &|s| matches!(s, EventSource::HighSpeedCounter { counter, .. } if hsc.contains(&counter)),
            ),
        };
        choice.unwrap_or_else(|| ints.events.first().copied().unwrap_or(0))
    }
}
