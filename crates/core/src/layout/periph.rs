//! The private state records of the high-speed counters (s7-200-more §8.7) and the pulse
//! output channels (§9.5), declared with the layout's `record_fields!`.

use super::Field;

record_fields! {
    /// Field offsets inside one high-speed counter's private state (s7-200-more §8.7, §11.1):
    /// one record per counter of the profile's table, read and written only by
    /// `stljit_runtime::hsc`. The current value is the program-visible HC area.
    HscState {
        /// 1 once HDEF defined the counter.
        DEFINED: u8 = 0;
        /// The mode HDEF gave it (0–12).
        MODE: u8 = 1;
        /// 1 while enabled (HSC with control bit 7).
        ENABLED: u8 = 2;
        /// The counting direction: 1 up, 0 down.
        DIR: u8 = 3;
        /// Control bit 0 at HDEF: the reset input is active low.
        RESET_LOW: u8 = 4;
        /// Control bit 1 at HDEF: the start input is active low.
        START_LOW: u8 = 5;
        /// Control bit 2 at HDEF: quadrature at 1x (else 4x).
        RATE1X: u8 = 6;
        /// The direction of the current interval's steps in modes 3–11 (1 up).
        STEP_UP: u8 = 7;
        /// Native-endian: the preset PV.
        PV: i32 = 8;
        /// Native-endian: the stimulus, the signed counting activity `n` per scan interval
        /// (§8.4, §11.2 `hsc_steps`), written by the harness and held until it writes again.
        RATE: i32 = 12;
        /// Native-endian: the unit steps of the current interval (`s`).
        STEPS: u32 = 16;
        /// Native-endian: the steps of the current interval already applied (`j`).
        DONE: u32 = 20;
        /// Native-endian: the start of the current interval in µs (`T_{k−1}`).
        T_START: u64 = 24;
        /// Native-endian: its length in µs (`D`).
        SPAN: u64 = 32;
    }
}

record_fields! {
    /// Field offsets inside one pulse output channel's private state (s7-200-more §9.5,
    /// §11.1): one record per channel of the profile's table, read and written only by
    /// `stljit_runtime::pulse`. Times and durations are in µs.
    PulseState {
        /// 0 idle, 1 PTO, 2 PWM.
        STATE: u8 = 0;
        /// 1 while a multi-segment profile runs.
        MULTI: u8 = 1;
        /// The profile segment in progress (1-based; 0 single segment).
        SEG_NO: u8 = 2;
        /// 1 while a single segment waits in the pipeline.
        PIPE_VALID: u8 = 3;
        /// Native-endian: µs per time unit of the running generator (1 or 1000).
        BASE_US: u32 = 4;
        /// Native-endian: PTO the start of the current pulse's cycle; PWM the waveform start.
        START: u64 = 8;
        /// Native-endian: PTO the current pulse's cycle, PWM the cycle.
        CYCLE: u32 = 16;
        /// Native-endian: PWM the pulse width.
        WIDTH: u32 = 20;
        /// Native-endian: PTO the cycle change per pulse of the segment.
        DELTA: i32 = 24;
        /// Native-endian: PTO the pulses of the current segment.
        COUNT: u32 = 28;
        /// Native-endian: PTO the pulses of the current segment completed.
        DONE_IN_SEG: u32 = 32;
        /// Native-endian: the pulses completed since RUN entry.
        TOTAL: u32 = 36;
        /// Native-endian: the pipelined segment's cycle.
        PIPE_CYCLE: u32 = 40;
        /// Native-endian: the pipelined segment's pulse count.
        PIPE_COUNT: u32 = 44;
        /// Native-endian: the profile table's offset in V (SMW168 at PLS).
        PROFILE_OFF: u16 = 48;
        /// The profile's number of segments.
        NSEG: u8 = 50;
        /// Native-endian: the last single-segment cycle in time units (0: none yet, 2 units).
        LAST_CYCLE: u32 = 52;
        /// Native-endian: the last single-segment pulse count (0: none yet, 1 pulse).
        LAST_COUNT: u32 = 56;
    }
}
