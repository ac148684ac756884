//! The Omron CP instructions' own enums: timer and counter kinds, and the data, compare and
//! arithmetic boxes whose flags go to the condition-flag area (omron-cp.md §3.3–§3.6). Their
//! rules are in `stljit_runtime::omron`; this module only names them.

use crate::profile::Resolution;

/// An Omron timer instruction (spec §3.3): the TIM family counts down from the set value, TTIM
/// accumulates up to it. `X` kinds take binary set values, the others BCD.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum OmronTimerKind {
    /// `TIM`: 100 ms, BCD.
    Tim,
    /// `TIMX(550)`: 100 ms, binary.
    TimX,
    /// `TIMH(015)`: 10 ms, BCD.
    TimH,
    /// `TIMHX(551)`: 10 ms, binary.
    TimHX,
    /// `TMHH(540)`: 1 ms, BCD.
    Tmhh,
    /// `TMHHX(552)`: 1 ms, binary.
    TmhhX,
    /// `TTIM(087)`: accumulating, 100 ms, BCD; timer input `S1`, reset `S0`.
    Ttim,
    /// `TTIMX(555)`: accumulating, 100 ms, binary.
    TtimX,
}

impl OmronTimerKind {
    /// The time unit.
    pub fn unit(self) -> Resolution {
        use OmronTimerKind::*;
        match self {
            Tim | TimX | Ttim | TtimX => Resolution::Ms100,
            TimH | TimHX => Resolution::Ms10,
            Tmhh | TmhhX => Resolution::Ms1,
        }
    }

    /// Whether set value and PV are BCD (else unsigned binary).
    pub fn bcd(self) -> bool {
        use OmronTimerKind::*;
        matches!(self, Tim | TimH | Tmhh | Ttim)
    }

    /// Whether this is an accumulating timer with a reset input (`TTIM`, `TTIMX`).
    pub fn totalizing(self) -> bool {
        matches!(self, OmronTimerKind::Ttim | OmronTimerKind::TtimX)
    }

    /// How many execution conditions the instruction takes (1, or 2 for TTIM).
    pub fn conditions(self) -> u8 {
        if self.totalizing() { 2 } else { 1 }
    }
}

/// An Omron counter instruction (spec §3.3). `X` kinds take binary set values.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum OmronCounterKind {
    /// `CNT`: count `S1`, reset `S0`; counts down from the set value, BCD.
    Cnt,
    /// `CNTX(546)`: binary.
    CntX,
    /// `CNTR(012)`: ring counter, increment `S2`, decrement `S1`, reset `S0`; BCD.
    Cntr,
    /// `CNTRX(548)`: binary.
    CntrX,
}

impl OmronCounterKind {
    /// Whether set value and PV are BCD.
    pub fn bcd(self) -> bool {
        matches!(self, OmronCounterKind::Cnt | OmronCounterKind::Cntr)
    }

    /// Whether this is the reversible ring counter.
    pub fn ring(self) -> bool {
        matches!(self, OmronCounterKind::Cntr | OmronCounterKind::CntrX)
    }

    /// How many execution conditions the instruction takes (2, or 3 for CNTR).
    pub fn conditions(self) -> u8 {
        if self.ring() { 3 } else { 2 }
    }
}

/// The arithmetic instructions of spec §3.6.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[allow(missing_docs)] // each variant is the instruction of its name: `AddL` is `+L(401)`
pub enum OmronArith {
    Add,
    AddL,
    AddC,
    AddCL,
    AddB,
    AddBL,
    AddBC,
    AddBCL,
    Sub,
    SubL,
    SubC,
    SubCL,
    SubB,
    SubBL,
    SubBC,
    SubBCL,
    Mul,
    MulL,
    MulU,
    MulUL,
    MulB,
    MulBL,
    Div,
    DivL,
    DivU,
    DivUL,
    DivB,
    DivBL,
}

impl OmronArith {
    /// The mnemonic as the programmer writes it (`+BL`, `*U`, `/`).
    pub fn mnemonic(self) -> &'static str {
        use OmronArith::*;
        match self {
            Add => "+",
            AddL => "+L",
            AddC => "+C",
            AddCL => "+CL",
            AddB => "+B",
            AddBL => "+BL",
            AddBC => "+BC",
            AddBCL => "+BCL",
            Sub => "-",
            SubL => "-L",
            SubC => "-C",
            SubCL => "-CL",
            SubB => "-B",
            SubBL => "-BL",
            SubBC => "-BC",
            SubBCL => "-BCL",
            Mul => "*",
            MulL => "*L",
            MulU => "*U",
            MulUL => "*UL",
            MulB => "*B",
            MulBL => "*BL",
            Div => "/",
            DivL => "/L",
            DivU => "/U",
            DivUL => "/UL",
            DivB => "/B",
            DivBL => "/BL",
        }
    }

    /// The function code (spec §3.6): each family counts up from its base in the order of
    /// [`OmronArith::ALL`]: `+` 400–407, `-` 410–417, `*` 420–425, `/` 430–435.
    pub fn function_code(self) -> u16 {
        use OmronArith::*;
        match self {
            Add => 400,
            AddL => 401,
            AddC => 402,
            AddCL => 403,
            AddB => 404,
            AddBL => 405,
            AddBC => 406,
            AddBCL => 407,
            Sub => 410,
            SubL => 411,
            SubC => 412,
            SubCL => 413,
            SubB => 414,
            SubBL => 415,
            SubBC => 416,
            SubBCL => 417,
            Mul => 420,
            MulL => 421,
            MulU => 422,
            MulUL => 423,
            MulB => 424,
            MulBL => 425,
            Div => 430,
            DivL => 431,
            DivU => 432,
            DivUL => 433,
            DivB => 434,
            DivBL => 435,
        }
    }

    /// Words of each source operand (1, or 2 for the `L` forms).
    pub fn operand_words(self) -> u32 {
        use OmronArith::*;
        match self {
            AddL | AddCL | AddBL | AddBCL | SubL | SubCL | SubBL | SubBCL | MulL | MulUL
            | MulBL | DivL | DivUL | DivBL => 2,
            _ => 1,
        }
    }

    /// Words of the result: products and quotient + remainder are twice the operand width.
    pub fn result_words(self) -> u32 {
        use OmronArith::*;
        let double = matches!(
            self,
            Mul | MulL | MulU | MulUL | MulB | MulBL | Div | DivL | DivU | DivUL | DivB | DivBL
        );
        self.operand_words() * if double { 2 } else { 1 }
    }
}

/// The data-memory boxes of the Omron dialect (run when `PF`; their flags go to the
/// condition-flag area, never to `Sched::ENO`'s SM bits).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum OmronBox {
    /// `MOV(021)` / `MOVL(498)`: `dst := src`; ER OFF, `=` and `N` from the value.
    Move {
        /// Two words (low word first) instead of one.
        double: bool,
        /// Source.
        src: super::Operand,
        /// Destination.
        dst: super::Operand,
    },
    /// `CMP(020)` / `CMPL(060)` / `CPS(114)` / `CPSL(115)`, and the comparison contacts' flag
    /// side (U2): the six comparison flags from `lhs` against `rhs`, ER OFF.
    Compare {
        /// Two words.
        double: bool,
        /// Signed instead of unsigned.
        signed: bool,
        /// First operand.
        lhs: super::Operand,
        /// Second operand.
        rhs: super::Operand,
    },
    /// `MOVR(560) S IRn`: `IRn := ea`, the effective address of `S` (core::omron's map,
    /// computed by the front end); ER OFF.
    SetIndex {
        /// The effective address.
        ea: u32,
        /// The index register 0..=15.
        ir: u8,
    },
    /// `CCS(282)` (`save`) / `CCL(283)`: copy the condition flags to their save area, or back
    /// (spec §3.4; the save area survives the task-start clearing, so flags can pass between
    /// tasks).
    Flags {
        /// CCS instead of CCL.
        save: bool,
    },
    /// An arithmetic instruction: `dst := lhs op rhs` ([`OmronArith::result_words`] words from
    /// `dst`); on ER nothing is written.
    Arith {
        /// Which instruction.
        op: OmronArith,
        /// First operand (augend, minuend, multiplicand, dividend).
        lhs: super::Operand,
        /// Second operand.
        rhs: super::Operand,
        /// First result word.
        dst: super::Operand,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arith_names_and_codes_are_distinct_and_follow_the_families() {
        // Spec §3.6: `+(400)` … `+BCL(407)`, `-(410)` … `-BCL(417)`, `*(420)` … `*BL(425)`,
        // `/(430)` … `/BL(435)`; within a family the code counts up in ALL's order, and the
        // mnemonic's first character names the family.
        let mut seen = std::collections::HashSet::new();
        for (i, op) in OmronArith::ALL.iter().enumerate() {
            assert!(seen.insert(op.mnemonic()), "{op:?}");
            let (base, first) = match op.mnemonic().as_bytes()[0] {
                b'+' => (400, 0),
                b'-' => (410, 8),
                b'*' => (420, 16),
                _ => (430, 22),
            };
            assert_eq!(op.function_code(), base + (i - first) as u16, "{op:?}");
        }
        assert_eq!(OmronArith::AddBL.mnemonic(), "+BL");
        assert_eq!(OmronArith::AddBL.function_code(), 405);
        assert_eq!(OmronArith::DivBL.function_code(), 435);
        assert_eq!(OmronArith::MulU.result_words(), 2);
        assert_eq!(OmronArith::MulUL.result_words(), 4);
        assert_eq!(OmronArith::DivL.result_words(), 4);
        assert_eq!(OmronArith::AddCL.result_words(), 2);
    }
}

/// An Omron indirect word operand (omron-cp.md §1.7), resolved at run time by the runtime
/// (`stljit_runtime::omron_image::resolve`); an illegal one is an access error (AER: the read
/// gives 0, the write is dropped).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum OmronRef {
    /// `@Dn`: D[n] read as unsigned binary is the D address.
    DmBinary(u16),
    /// `*Dn`: D[n] read as BCD is the D address.
    DmBcd(u16),
    /// `c,IRn`, `DRm,IRn`, `,IRn+`, `,--IRn` …: the effective address in `IRn` plus an offset,
    /// with the register stepped after (`+`/`++`) or before (`-`/`--`) the access.
    Index {
        /// The index register 0..=15.
        ir: u8,
        /// What is added to the register's address.
        offset: IndexOffset,
        /// The register's auto-increment or pre-decrement.
        step: IndexStep,
    },
}

/// The offset of an indexed operand.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum IndexOffset {
    /// A constant −2048..=2047 (0 for `,IRn`).
    Const(i16),
    /// Data register `DRm`, sign-extended.
    Dr(u8),
}

/// The auto step of an indexed operand.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum IndexStep {
    /// `,IRn`.
    None,
    /// `,IRn+`: the register += 1 after the access.
    PostInc1,
    /// `,IRn++`: += 2 after.
    PostInc2,
    /// `,-IRn`: −= 1 before.
    PreDec1,
    /// `,--IRn`: −= 2 before.
    PreDec2,
}

impl IndexStep {
    /// Every step, in declaration order.
    pub const ALL: [IndexStep; 5] = [
        IndexStep::None,
        IndexStep::PostInc1,
        IndexStep::PostInc2,
        IndexStep::PreDec1,
        IndexStep::PreDec2,
    ];

    /// The text form's name (`none`, `post1`, `post2`, `pre1`, `pre2`).
    pub fn name(self) -> &'static str {
        match self {
            IndexStep::None => "none",
            IndexStep::PostInc1 => "post1",
            IndexStep::PostInc2 => "post2",
            IndexStep::PreDec1 => "pre1",
            IndexStep::PreDec2 => "pre2",
        }
    }
}

/// The operands of an Omron box in evaluation order, with their sizes in words: what both
/// engines read, resolve and write, stated once.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoxOperands {
    /// The sources, first operand first (`None` where the box has fewer).
    pub sources: [Option<super::Operand>; 2],
    /// The destination (`None` for the compares).
    pub dst: Option<super::Operand>,
    /// Words of each source (1 or 2).
    pub src_words: u32,
    /// Words of the result (1, 2 or 4; 0 without a destination).
    pub dst_words: u32,
}

impl OmronBox {
    /// The box's operands ([`BoxOperands`]); MOVR's source is its effective address as a
    /// constant and its destination the index register's dword.
    pub fn operands(&self) -> BoxOperands {
        let words = |double: bool| if double { 2 } else { 1 };
        match *self {
            OmronBox::Move { double, src, dst } => BoxOperands {
                sources: [Some(src), None],
                dst: Some(dst),
                src_words: words(double),
                dst_words: words(double),
            },
            OmronBox::Compare {
                double, lhs, rhs, ..
            } => BoxOperands {
                sources: [Some(lhs), Some(rhs)],
                dst: None,
                src_words: words(double),
                dst_words: 0,
            },
            OmronBox::SetIndex { ea, ir } => BoxOperands {
                sources: [Some(super::Operand::Const(ea)), None],
                dst: Some(super::Operand::Mem(super::Loc {
                    area: crate::area::Area::IndexReg,
                    offset: 4 * u32::from(ir),
                })),
                src_words: 2,
                dst_words: 2,
            },
            OmronBox::Arith { op, lhs, rhs, dst } => BoxOperands {
                sources: [Some(lhs), Some(rhs)],
                dst: Some(dst),
                src_words: op.operand_words(),
                dst_words: op.result_words(),
            },
            OmronBox::Flags { .. } => BoxOperands {
                sources: [None, None],
                dst: None,
                src_words: 0,
                dst_words: 0,
            },
        }
    }
}
