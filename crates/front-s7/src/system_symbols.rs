//! The predefined system symbols (s7-200-more §2): the names MicroWIN knows without a project
//! symbol table (`Always_On`, `First_Scan_On`, and on the S7-200 SMART the register names of its
//! exports such as `Time_0_Intrvl`). They are data: `system_symbols/*.txt` in the MicroWIN
//! symbol-table format, read with the user table's own reader, so a name is added without a code
//! change. [`table`] says which files a profile uses; a project symbol table overrides them
//! (name resolution in `names.rs`).

use crate::symbols::SymbolTable;
use std::sync::OnceLock;
use stljit_core::{FileId, ProfileId};

/// The names every S7 profile knows (§2's normative table but SM0.7).
const COMMON: &str = include_str!("system_symbols/common.txt");
/// The classic CPUs' (A5, S7-200) additions.
const CLASSIC: &str = include_str!("system_symbols/classic.txt");
/// The S7-200 SMART's additions: SM0.7, the register names and the built-in I/O names.
const SMART: &str = include_str!("system_symbols/smart.txt");

/// The data files of `profile`, in order.
fn files(profile: ProfileId) -> &'static [&'static str] {
    match profile {
        ProfileId::A5 | ProfileId::S7_200 => &[COMMON, CLASSIC],
        ProfileId::Smart => &[COMMON, SMART],
        // Not S7 CPUs: the S7 front end knows no system names for them.
        ProfileId::Cp1h | ProfileId::Cp1e => &[],
    }
}

/// The system symbol table of `profile`, parsed once.
pub(crate) fn table(profile: ProfileId) -> &'static SymbolTable {
    static TABLES: [OnceLock<SymbolTable>; ProfileId::ALL.len()] =
        [const { OnceLock::new() }; ProfileId::ALL.len()];
    let i = ProfileId::ALL
        .iter()
        .position(|&p| p == profile)
        .unwrap_or(0);
    TABLES[i].get_or_init(|| parse(profile).0)
}

/// Parses a profile's files as one table; the diagnostics are for the data's own test (the
/// shipped files parse without any).
fn parse(profile: ProfileId) -> (SymbolTable, Vec<stljit_source::Diagnostic>) {
    let text = files(profile).join("\n");
    SymbolTable::parse(&text, FileId(0))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::operand::Syn;
    use crate::symbols::SymTarget;
    use stljit_core::{Area, Width};

    fn get(p: ProfileId, name: &str) -> Option<SymTarget> {
        table(p).get(name).copied()
    }

    fn bit(area: Area, byte: u32, bit: u8) -> Option<SymTarget> {
        Some(SymTarget::Operand(Syn::Bit { area, byte, bit }))
    }

    #[test]
    fn the_data_files_parse_cleanly() {
        for p in [ProfileId::A5, ProfileId::S7_200, ProfileId::Smart] {
            let (t, diags) = parse(p);
            assert!(diags.is_empty(), "{p}: {diags:?}");
            assert!(t.len() >= 27, "{p}");
        }
    }

    /// s7-200-more §2: the normative names, and SM0.7's two meanings.
    #[test]
    fn normative_names() {
        for p in [ProfileId::A5, ProfileId::S7_200, ProfileId::Smart] {
            assert_eq!(get(p, "Always_On"), bit(Area::SM, 0, 0));
            assert_eq!(get(p, "Clock_1s"), bit(Area::SM, 0, 5));
            assert_eq!(get(p, "IO_Err"), bit(Area::SM, 5, 0));
        }
        assert_eq!(get(ProfileId::Smart, "RTC_Lost"), bit(Area::SM, 0, 7));
        assert_eq!(get(ProfileId::Smart, "Mode_Switch"), None);
        assert_eq!(get(ProfileId::S7_200, "Mode_Switch"), bit(Area::SM, 0, 7));
        assert_eq!(get(ProfileId::A5, "RTC_Lost"), None);
    }

    /// The names the corpus's MicroWIN SMART export writes for the addresses of its source.
    #[test]
    fn smart_register_and_io_names() {
        let mem = |width, offset| {
            Some(SymTarget::Operand(Syn::Mem {
                area: Area::SM,
                width,
                offset,
            }))
        };
        let s = ProfileId::Smart;
        assert_eq!(get(s, "Time_0_Intrvl"), mem(Width::Byte, 34));
        assert_eq!(get(s, "HSC0_CV"), mem(Width::DWord, 38));
        assert_eq!(get(s, "P0_Idle_Time"), mem(Width::Word, 90));
        assert_eq!(get(s, "CPU_输入8"), bit(Area::I, 1, 0));
        assert_eq!(get(s, "CPU_输出11"), bit(Area::Q, 1, 3));
        assert_eq!(get(ProfileId::S7_200, "Time_0_Intrvl"), None);
    }
}
