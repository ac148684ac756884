//! Pulse output channels per CPU (s7-200-more §9.1, §0.2): which outputs have a PTO/PWM
//! generator, their SM registers and their PTO-complete events. The one place for these facts;
//! the front end checks `PLS Q` against it and `stljit_runtime::pulse` reads it.

/// One pulse output channel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PulseChannel {
    /// The channel number `Q` of `PLS Q`.
    pub number: u8,
    /// The output it drives: Q byte and bit.
    pub output: (u32, u8),
    /// The SM byte of its status register (SMB66, SMB76, SMB566); control, cycle time, pulse
    /// width and pulse count follow at +1, +2, +4 and +6 (§9.1).
    pub status_smb: u32,
    /// The SM byte of its profile registers: segment number here, table offset word at +2
    /// (SMB166/SMW168, SMB176/SMW178, SMB576/SMW578).
    pub profile_smb: u32,
    /// Whether PTO is supported (`smart` PTO is frequency-based and unsupported, §9.1).
    pub pto: bool,
    /// The high-speed counter whose mode 12 counts this channel's pulses (§8.2: HSC0 ↔ Q0.0,
    /// HSC3 ↔ Q0.1), if the CPU has one.
    pub counter: Option<u8>,
}

impl PulseChannel {
    /// The control byte (status + 1).
    pub fn control_smb(&self) -> u32 {
        self.status_smb + 1
    }
    /// The cycle time word (status + 2).
    pub fn cycle_smw(&self) -> u32 {
        self.status_smb + 2
    }
    /// The PWM pulse width word (status + 4).
    pub fn width_smw(&self) -> u32 {
        self.status_smb + 4
    }
    /// The PTO pulse count double word (status + 6).
    pub fn count_smd(&self) -> u32 {
        self.status_smb + 6
    }
    /// The profile table offset word (profile byte + 2).
    pub fn table_smw(&self) -> u32 {
        self.profile_smb + 2
    }
}

/// A CPU's pulse output channels, indexed by number.
#[derive(Debug)]
pub struct PulseProfile {
    /// The channels, entry `n` for channel `n`.
    pub channels: &'static [PulseChannel],
}

impl PulseProfile {
    /// No pulse outputs (A5, Omron).
    pub const NONE: PulseProfile = PulseProfile { channels: &[] };

    /// Channel `n`, if the CPU has it.
    pub fn get(&self, n: u8) -> Option<&PulseChannel> {
        self.channels.get(usize::from(n))
    }
}

const fn ch(number: u8, bit: u8, status_smb: u32, profile_smb: u32, pto: bool) -> PulseChannel {
    PulseChannel {
        number,
        output: (0, bit),
        status_smb,
        profile_smb,
        pto,
        counter: None,
    }
}

/// `c` with its pulses counted by HSC `n` in mode 12.
const fn counted(c: PulseChannel, n: u8) -> PulseChannel {
    PulseChannel {
        counter: Some(n),
        ..c
    }
}

/// The S7-200 (DC-output CPUs): Q0.0 and Q0.1 [S7-200 manual].
pub static S7_200_PULSE: PulseProfile = PulseProfile {
    channels: &[
        counted(ch(0, 0, 66, 166, true), 0),
        counted(ch(1, 1, 76, 176, true), 3),
    ],
};

/// The S7-200 SMART (ST CPUs): Q0.0, Q0.1, Q0.3 [SMART manual, recalled, §13 Q2]; PTO is
/// frequency-based there and not supported in version 1, PWM follows §9 (§9.1 [design]); its
/// counters have no mode 12 (§8.2).
pub static SMART_PULSE: PulseProfile = PulseProfile {
    channels: &[
        ch(0, 0, 66, 166, false),
        ch(1, 1, 76, 176, false),
        ch(2, 3, 566, 576, false),
    ],
};

#[cfg(test)]
mod tests {
    use super::*;

    /// The registers follow §9.1's table.
    #[test]
    fn registers() {
        let c = S7_200_PULSE.get(1).unwrap();
        assert_eq!(
            (c.control_smb(), c.cycle_smw(), c.width_smw(), c.count_smd()),
            (77, 78, 80, 82)
        );
        assert_eq!(c.table_smw(), 178);
        let c = SMART_PULSE.get(2).unwrap();
        assert_eq!((c.output, c.status_smb, c.table_smw()), ((0, 3), 566, 578));
        assert!(S7_200_PULSE.get(2).is_none());
    }
}
