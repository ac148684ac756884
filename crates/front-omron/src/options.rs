//! The front end's options (omron-cp.md §1.9 `omron.tc_mode`, §2.8 `allow_backward_jumps`), set
//! on the command line with `--tc-mode` and `--allow-backward-jumps` (docs/omron.md "Options").

use stljit_core::ir::{OmronCounterKind, OmronTimerKind};

/// How the plain timer and counter instructions (TIM, TIMH, TMHH, TTIM, CNT, CNTR) read their
/// set values and keep their PVs (§1.9).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum TcMode {
    /// BCD (`#0000`–`#9999`), the default.
    #[default]
    Bcd,
    /// Unsigned binary (`&0`–`&65535`): CX-Programmer's binary-mode project option; the plain
    /// instructions then behave as their `X` forms (TIMX, CNTX …).
    Binary,
}

impl TcMode {
    /// Every mode.
    pub const ALL: &'static [TcMode] = &[TcMode::Bcd, TcMode::Binary];

    /// The name on the command line (`bcd`, `binary`).
    pub fn name(self) -> &'static str {
        match self {
            TcMode::Bcd => "bcd",
            TcMode::Binary => "binary",
        }
    }

    /// The mode called `name`.
    pub fn from_name(name: &str) -> Option<TcMode> {
        TcMode::ALL.iter().copied().find(|m| m.name() == name)
    }

    /// The timer instruction a written one runs as in this mode.
    pub fn timer(self, kind: OmronTimerKind) -> OmronTimerKind {
        use OmronTimerKind::*;
        match (self, kind) {
            (TcMode::Binary, Tim) => TimX,
            (TcMode::Binary, TimH) => TimHX,
            (TcMode::Binary, Tmhh) => TmhhX,
            (TcMode::Binary, Ttim) => TtimX,
            (_, k) => k,
        }
    }

    /// The counter instruction a written one runs as in this mode.
    pub fn counter(self, kind: OmronCounterKind) -> OmronCounterKind {
        use OmronCounterKind::*;
        match (self, kind) {
            (TcMode::Binary, Cnt) => CntX,
            (TcMode::Binary, Cntr) => CntrX,
            (_, k) => k,
        }
    }
}

/// The options of one compilation; the default is the spec's default behaviour.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Options {
    /// `omron.tc_mode` (§1.9).
    pub tc_mode: TcMode,
    /// `allow_backward_jumps` (§2.8): a JME may stand before its jump (within the same interlock
    /// region and block program, into no FOR loop); each backward jump taken counts against the
    /// scan's loop budget, so a jump that loops for ever ends in the watchdog's fatal error.
    pub allow_backward_jumps: bool,
}
