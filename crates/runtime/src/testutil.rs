//! Test rig for the runtime's own unit tests: an A5 image driven scan by scan with a fixed
//! period, where the "program" is a closure calling runtime functions directly.

use crate::image::Image;
use crate::{mem, scan};
use stljit_core::layout::{CounterState, Layout, TimerState};
use stljit_core::{ProfileId, ScanStatus};

pub(crate) struct Rig {
    pub(crate) img: Image,
    period: u64,
    k: u64,
}

impl Rig {
    pub(crate) fn new(period: u64) -> Rig {
        Rig {
            img: Image::blank(ProfileId::A5),
            period,
            k: 0,
        }
    }

    /// Declares timer `n` the way cold start does for a program using it.
    pub(crate) fn timer(mut self, n: u16, kind: u8, res: u8) -> Rig {
        let at = self.img.layout().timer_state(n);
        mem::set_u8(self.img.bytes_mut(), at + TimerState::KIND, kind);
        mem::set_u8(self.img.bytes_mut(), at + TimerState::RES, res);
        self
    }

    pub(crate) fn counter(mut self, n: u16, kind: u8) -> Rig {
        let at = self.img.layout().counter_state(n) + CounterState::KIND;
        mem::set_u8(self.img.bytes_mut(), at, kind);
        self
    }

    /// Runs scan k at `t = k * period`.
    pub(crate) fn scan(&mut self, body: impl FnOnce(&mut [u8], &Layout)) {
        let t = self.k * self.period;
        self.k += 1;
        let plan = scan::ScanPlan::every_timer(self.img.layout());
        let (b, l) = self.img.split_mut();
        scan::run(b, l, &plan, t, |b, l| {
            body(b, l);
            ScanStatus::Ok
        });
    }
}
