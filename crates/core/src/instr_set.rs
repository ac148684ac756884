//! Optional instruction families of the S7 CPUs (s7-200-more.md Appendix A): which of them a CPU
//! lacks is data of its profile ([`crate::CpuProfile::lacks`]), so a front end rejects an
//! instruction the selected CPU does not have with one lookup, and adding a CPU or an
//! instruction changes data, not code. The front end maps each mnemonic to its family; what a
//! family contains is documented here only as a guide.

/// A family of instructions that not every CPU has. Instructions in no family (bit logic,
/// timers, counters, moves, arithmetic, program control, …) exist on every S7 CPU.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum InstrSet {
    /// `ATCH`, `DTCH`, `ENI`, `DISI`, `CRETI`, `CEVNT` (s7-200-more §3).
    Interrupts,
    /// `ATT`, `FIFO`, `LIFO`, `FND=` … (§4).
    Tables,
    /// `ATH`, `HTA`, `ITA`, `DTA`, `RTA` (§5.2, §5.3).
    Ascii,
    /// `ITS`, `DTS`, `RTS`, `STI`, `STD`, `STR`, `SLEN`, `SCPY`, `SSCPY`, `SCAT`, `SFND`, `CFND`
    /// and the string compare contacts (§5).
    Strings,
    /// `TODR`, `TODW`, `TODRX`, `TODWX` (§6).
    Clock,
    /// `PID` (§7).
    Pid,
    /// `HDEF`, `HSC` (§8).
    HighSpeedCounters,
    /// `PLS` (§9).
    PulseOutputs,
    /// `XMT`, `RCV` (§10.1–10.4).
    Freeport,
    /// `GPA`, `SPA` (§10.6).
    PortAddress,
    /// `NETR`, `NETW`: PPI network read/write of the classic CPUs (§10.5).
    NetReadWrite,
    /// `GET`, `PUT`: Ethernet S7 communication of the S7-200 SMART (§10.5).
    GetPut,
    /// `GIP`, `SIP`: the S7-200 SMART's own IP address.
    IpAddress,
    /// `BITIM`, `CITIM`: interval timers.
    IntervalTimers,
    /// `DIAG_LED` (on every S7 profile [uncertain]: no source lists it per CPU).
    DiagnosticLed,
}

impl InstrSet {
    /// Every family, in declaration order.
    pub const ALL: &'static [InstrSet] = &[
        InstrSet::Interrupts,
        InstrSet::Tables,
        InstrSet::Ascii,
        InstrSet::Strings,
        InstrSet::Clock,
        InstrSet::Pid,
        InstrSet::HighSpeedCounters,
        InstrSet::PulseOutputs,
        InstrSet::Freeport,
        InstrSet::PortAddress,
        InstrSet::NetReadWrite,
        InstrSet::GetPut,
        InstrSet::IpAddress,
        InstrSet::IntervalTimers,
        InstrSet::DiagnosticLed,
    ];

    /// A short name for messages ("interrupts", "PLS pulse outputs").
    pub fn describe(self) -> &'static str {
        match self {
            InstrSet::Interrupts => "interrupts",
            InstrSet::Tables => "table instructions",
            InstrSet::Ascii => "ASCII conversions",
            InstrSet::Strings => "string instructions",
            InstrSet::Clock => "the real-time clock",
            InstrSet::Pid => "PID loops",
            InstrSet::HighSpeedCounters => "high-speed counters",
            InstrSet::PulseOutputs => "pulse outputs (PTO/PWM)",
            InstrSet::Freeport => "Freeport communication",
            InstrSet::PortAddress => "port address instructions",
            InstrSet::NetReadWrite => "PPI network read/write",
            InstrSet::GetPut => "Ethernet GET/PUT",
            InstrSet::IpAddress => "IP address instructions",
            InstrSet::IntervalTimers => "interval timers",
            InstrSet::DiagnosticLed => "the diagnostic LED",
        }
    }
}
