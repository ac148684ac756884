//! Status and error codes shared by every engine. They cross the JIT's `extern "C"` boundary as
//! plain integers, so each enum is `#[repr]` with `TryFrom` for the way back.

use std::fmt;

/// Declares a `#[repr]` code enum, its `TryFrom` for the way back and its `ALL` list from the
/// same lines, so that each value is written once.
macro_rules! code_enum {
    (
        $(#[$doc:meta])*
        $name:ident: $repr:ty {
            $( $(#[$variant_doc:meta])* $variant:ident = $code:literal, )+
        }
    ) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        #[repr($repr)]
        pub enum $name {
            $( $(#[$variant_doc])* $variant = $code, )+
        }

        impl $name {
            /// Every value, in declaration order.
            pub const ALL: &'static [$name] = &[$($name::$variant),+];
        }

        impl TryFrom<$repr> for $name {
            type Error = $repr;
            fn try_from(v: $repr) -> Result<Self, $repr> {
                match v {
                    $( $code => Ok($name::$variant), )+
                    other => Err(other),
                }
            }
        }
    };
}

code_enum! {
    /// Result of executing one scan.
    ScanStatus: u8 {
        /// The scan completed; the PLC stays in RUN.
        Ok = 0,
        /// The scan completed and a `STOP` instruction executed: the PLC is now in STOP.
        Stopped = 1,
        /// A fatal error aborted the scan (no output write); the PLC is in STOP. The code is in
        /// the image's `Sched::FATAL` field.
        Fatal = 2,
    }
}

code_enum! {
    /// Non-fatal run-time errors (spec §2.5): the instruction is skipped, ENO = 0, and the code
    /// is stored in `Sched::LAST_ERR`. The values are the S7-200's.
    ErrorCode: u16 {
        /// HSC executed before its HDEF (s7-200-more §0.4, §8.1).
        HscNotDefined = 0x0001,
        /// ATCH of an input-edge event on an input a defined high-speed counter uses (§8.3).
        HscEdgeConflict = 0x0002,
        /// HDEF of a counter whose inputs an attached input-edge event or another defined
        /// counter uses (§8.3).
        HscInputConflict = 0x0003,
        /// ENI, DISI or HDEF executed in an interrupt routine (s7-200-more §0.4, §3.4).
        InInterrupt = 0x0004,
        /// Illegal indirect address (bad pointer, out of range, or a read-only target).
        IndirectAddress = 0x0006,
        /// TODW/TODWX data error: a field is no BCD value, out of its range, or no such day
        /// (s7-200-more §0.4, §6.2).
        ClockData = 0x0007,
        /// Subroutine nesting exceeded.
        CallNesting = 0x0008,
        /// XMT or RCV on port 0 while the port transmits or receives (s7-200-more §10.2).
        PortBusy0 = 0x0009,
        /// HDEF of a high-speed counter that is already defined (§8.1).
        HscRedefined = 0x000A,
        /// XMT or RCV on port 1 while the port transmits or receives (§10.2).
        PortBusy1 = 0x000B,
        /// The CPU has no real-time clock (TODR/TODW on a profile without one, §6.2).
        NoClock = 0x000C,
        /// PLS changing a running pulse output's mode or time base, or a profile while one
        /// runs (s7-200-more §9.2).
        PulseRedefined = 0x000D,
        /// PLS of a multi-segment PTO profile with 0 segments (§9.2).
        PulseNoSegments = 0x000E,
        /// Operand out of range (an S/R/BM* count runs past the area end).
        OperandRange = 0x0091,
        /// Bad count field (SHRB length 0 or above 64). Block-move and FILL counts use
        /// [`ErrorCode::OperandRange`] (spec §4.7).
        CountField = 0x0092,
        /// Illegal index 0 in a string instruction (SSCPY, SFND, CFND, STI/STD/STR, §0.4).
        StringIndex = 0x009B,
    }
}

impl fmt::Display for ErrorCode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let what = match self {
            ErrorCode::HscNotDefined => "HSC before HDEF",
            ErrorCode::HscEdgeConflict => "input interrupt on a high-speed counter input",
            ErrorCode::HscInputConflict => "high-speed counter input already in use",
            ErrorCode::InInterrupt => "ENI, DISI or HDEF in an interrupt routine",
            ErrorCode::HscRedefined => "high-speed counter already defined",
            ErrorCode::PulseRedefined => "pulse output redefined while active",
            ErrorCode::PulseNoSegments => "PTO profile with 0 segments",
            ErrorCode::PortBusy0 => "simultaneous XMT/RCV on port 0",
            ErrorCode::PortBusy1 => "simultaneous XMT/RCV on port 1",
            ErrorCode::IndirectAddress => "illegal indirect address",
            ErrorCode::ClockData => "clock data error",
            ErrorCode::CallNesting => "subroutine nesting exceeded",
            ErrorCode::NoClock => "no real-time clock",
            ErrorCode::OperandRange => "operand out of range",
            ErrorCode::CountField => "bad count field",
            ErrorCode::StringIndex => "string index 0",
        };
        write!(f, "error 16#{:04X} ({what})", *self as u16)
    }
}

code_enum! {
    /// Fatal run-time errors: the scan aborts without writing outputs and the PLC enters STOP.
    /// The S7-200 does not document numbers for these; the values are stljit's own.
    FatalCode: u16 {
        /// The loop budget of the scan ran out (spec §2.5).
        Watchdog = 0x0101,
        /// A compare instruction read through an illegal pointer.
        CompareIndirect = 0x0102,
        /// A real compare saw a NaN operand.
        CompareNaN = 0x0103,
        /// A string compare read a string with length byte 255 or one running past its area
        /// (s7-200-more §5.6).
        CompareString = 0x0104,
    }
}

impl fmt::Display for FatalCode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let what = match self {
            FatalCode::Watchdog => "watchdog: loop budget of the scan exhausted",
            FatalCode::CompareIndirect => "illegal indirect address in a compare",
            FatalCode::CompareNaN => "NaN operand in a real compare",
            FatalCode::CompareString => "invalid string in a string compare",
        };
        write!(f, "fatal 16#{:04X} ({what})", *self as u16)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_round_trip() {
        for &s in ScanStatus::ALL {
            assert_eq!(ScanStatus::try_from(s as u8), Ok(s));
        }
        for &e in ErrorCode::ALL {
            assert_eq!(ErrorCode::try_from(e as u16), Ok(e));
        }
        for &e in FatalCode::ALL {
            assert_eq!(FatalCode::try_from(e as u16), Ok(e));
        }
        assert_eq!(ScanStatus::try_from(9), Err(9));
        assert_eq!(ErrorCode::try_from(0x0005), Err(0x0005));
    }
}
