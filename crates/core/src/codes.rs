//! Status and error codes shared by every engine. They cross the JIT's `extern "C"` boundary as
//! plain integers, so each enum is `#[repr]` with `TryFrom` for the way back.

use std::fmt;

/// Result of executing one scan.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum ScanStatus {
    /// The scan completed; the PLC stays in RUN.
    Ok = 0,
    /// The scan completed and a `STOP` instruction executed: the PLC is now in STOP.
    Stopped = 1,
    /// A fatal error aborted the scan (no output write); the PLC is in STOP. The code is in the
    /// image's `Sched::FATAL` field.
    Fatal = 2,
}

impl TryFrom<u8> for ScanStatus {
    type Error = u8;
    fn try_from(v: u8) -> Result<Self, u8> {
        match v {
            0 => Ok(ScanStatus::Ok),
            1 => Ok(ScanStatus::Stopped),
            2 => Ok(ScanStatus::Fatal),
            other => Err(other),
        }
    }
}

/// Non-fatal run-time errors (spec §2.5): the instruction is skipped, ENO = 0, and the code is
/// stored in `Sched::LAST_ERR`. The values are the S7-200's.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u16)]
pub enum ErrorCode {
    /// Illegal indirect address (bad pointer, out of range, or a read-only target).
    IndirectAddress = 0x0006,
    /// Subroutine nesting exceeded.
    CallNesting = 0x0008,
    /// Operand out of range (an S/R/BM* count runs past the area end).
    OperandRange = 0x0091,
    /// Bad count field (SHRB length 0 or above 64). Block-move and FILL counts use
    /// [`ErrorCode::OperandRange`] (spec §4.7).
    CountField = 0x0092,
}

impl TryFrom<u16> for ErrorCode {
    type Error = u16;
    fn try_from(v: u16) -> Result<Self, u16> {
        match v {
            0x0006 => Ok(ErrorCode::IndirectAddress),
            0x0008 => Ok(ErrorCode::CallNesting),
            0x0091 => Ok(ErrorCode::OperandRange),
            0x0092 => Ok(ErrorCode::CountField),
            other => Err(other),
        }
    }
}

impl fmt::Display for ErrorCode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let what = match self {
            ErrorCode::IndirectAddress => "illegal indirect address",
            ErrorCode::CallNesting => "subroutine nesting exceeded",
            ErrorCode::OperandRange => "operand out of range",
            ErrorCode::CountField => "bad count field",
        };
        write!(f, "error 16#{:04X} ({what})", *self as u16)
    }
}

/// Fatal run-time errors: the scan aborts without writing outputs and the PLC enters STOP.
/// The S7-200 does not document numbers for these; the values are stljit's own.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u16)]
pub enum FatalCode {
    /// The loop budget of the scan ran out (spec §2.5).
    Watchdog = 0x0101,
    /// A compare instruction read through an illegal pointer.
    CompareIndirect = 0x0102,
    /// A real compare saw a NaN operand.
    CompareNaN = 0x0103,
}

impl TryFrom<u16> for FatalCode {
    type Error = u16;
    fn try_from(v: u16) -> Result<Self, u16> {
        match v {
            0x0101 => Ok(FatalCode::Watchdog),
            0x0102 => Ok(FatalCode::CompareIndirect),
            0x0103 => Ok(FatalCode::CompareNaN),
            other => Err(other),
        }
    }
}

impl fmt::Display for FatalCode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let what = match self {
            FatalCode::Watchdog => "watchdog: loop budget of the scan exhausted",
            FatalCode::CompareIndirect => "illegal indirect address in a compare",
            FatalCode::CompareNaN => "NaN operand in a real compare",
        };
        write!(f, "fatal 16#{:04X} ({what})", *self as u16)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_round_trip() {
        for s in [ScanStatus::Ok, ScanStatus::Stopped, ScanStatus::Fatal] {
            assert_eq!(ScanStatus::try_from(s as u8), Ok(s));
        }
        for e in [
            ErrorCode::IndirectAddress,
            ErrorCode::CallNesting,
            ErrorCode::OperandRange,
            ErrorCode::CountField,
        ] {
            assert_eq!(ErrorCode::try_from(e as u16), Ok(e));
        }
        for e in [
            FatalCode::Watchdog,
            FatalCode::CompareIndirect,
            FatalCode::CompareNaN,
        ] {
            assert_eq!(FatalCode::try_from(e as u16), Ok(e));
        }
        assert_eq!(ScanStatus::try_from(9), Err(9));
    }
}
