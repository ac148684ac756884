//! The mnemonic lists: every supported instruction (for "did you mean" suggestions) and the
//! out-of-scope ones of spec §4.12 that get a "not supported" error instead of "unknown".

/// Every supported mnemonic (compare contacts are listed with each relation).
pub(crate) const KNOWN: &[&str] = &[
    "LD", "LDN", "A", "AN", "O", "ON", "=", "NOT", "S", "R", "EU", "ED", "LDI", "LDNI", "AI",
    "ANI", "OI", "ONI", "=I", "SI", "RI", "BIR", "BIW", "NOP", "ALD", "OLD", "LPS", "LRD", "LPP",
    "LDS", "AENO", "TON", "TONR", "TOF", "TOFF", "CTU", "CTD", "CTUD", "LDB=", "LDB<>", "LDB>=",
    "LDB<=", "LDB>", "LDB<", "AB=", "AB<>", "AB>=", "AB<=", "AB>", "AB<", "OB=", "OB<>", "OB>=",
    "OB<=", "OB>", "OB<", "LDW=", "LDW<>", "LDW>=", "LDW<=", "LDW>", "LDW<", "AW=", "AW<>", "AW>=",
    "AW<=", "AW>", "AW<", "OW=", "OW<>", "OW>=", "OW<=", "OW>", "OW<", "LDD=", "LDD<>", "LDD>=",
    "LDD<=", "LDD>", "LDD<", "AD=", "AD<>", "AD>=", "AD<=", "AD>", "AD<", "OD=", "OD<>", "OD>=",
    "OD<=", "OD>", "OD<", "LDR=", "LDR<>", "LDR>=", "LDR<=", "LDR>", "LDR<", "AR=", "AR<>", "AR>=",
    "AR<=", "AR>", "AR<", "OR=", "OR<>", "OR>=", "OR<=", "OR>", "OR<", "MOVB", "MOVW", "MOVD",
    "MOVR", "SWAP", "BMB", "BMW", "BMD", "FILL", "+I", "-I", "*I", "/I", "+D", "-D", "*D", "/D",
    "MUL", "DIV", "+R", "-R", "*R", "/R", "SQRT", "LN", "EXP", "SIN", "COS", "TAN", "INCB", "DECB",
    "INCW", "DECW", "INCD", "DECD", "ANDB", "ANDW", "ANDD", "ORB", "ORW", "ORD", "XORB", "XORW",
    "XORD", "INVB", "INVW", "INVD", "SLB", "SLW", "SLD", "SRB", "SRW", "SRD", "RLB", "RLW", "RLD",
    "RRB", "RRW", "RRD", "SHRB", "BTI", "ITB", "ITD", "DTI", "DTR", "ROUND", "TRUNC", "BCDI",
    "IBCD", "DECO", "ENCO", "SEG", "END", "MEND", "STOP", "WDR", "JMP", "LBL", "CALL", "CRET",
    "RET", "RETI", "FOR", "NEXT", "LSCR", "SCRT", "CSCRE", "SCRE",
];

/// Out of scope for version 1 (spec §4.12): parsed and rejected with a clear message.
pub(crate) const OUT_OF_SCOPE: &[&str] = &[
    "ATH", "HTA", "ITA", "DTA", "RTA", "ITS", "DTS", "RTS", "STI", "STD", "STR", "SCPY", "SSCPY",
    "SLEN", "SCAT", "SFND", "CFND", "ATT", "FIFO", "LIFO", "FND=", "FND<>", "FND<", "FND>", "TBL",
    "TODR", "TODW", "TODRX", "TODWX", "PID", "HDEF", "HSC", "PLS", "XMT", "RCV", "NETR", "NETW",
    "GPA", "SPA", "GIP", "SIP", "ATCH", "DTCH", "ENI", "DISI", "CRETI", "DIAG_LED", "CEVNT",
    "TODR", "BITIM", "CITIM", "LDS=", "LDS<>", "AS=", "AS<>", "OS=", "OS<>",
];

/// `LDS=`, `AS<>`, ...: string compares (not the LDS stack instruction).
pub(crate) fn is_string_compare(m: &str) -> bool {
    let rest = m
        .strip_prefix("LDS")
        .or_else(|| m.strip_prefix("AS"))
        .or_else(|| m.strip_prefix("OS"));
    rest.is_some_and(|r| !r.is_empty() && r.bytes().all(|c| matches!(c, b'=' | b'<' | b'>')))
}

fn distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, &cb) in b.iter().enumerate() {
            let sub = prev[j] + usize::from(ca != cb);
            cur[j + 1] = sub.min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

/// The supported mnemonic closest to `m` (upper case), if one is close enough to be a likely typo.
pub(crate) fn closest(m: &str) -> Option<&'static str> {
    if m.is_empty() || m.len() > 12 {
        return None;
    }
    let (best, d) = KNOWN
        .iter()
        .map(|k| (*k, distance(m, k)))
        .min_by_key(|&(_, d)| d)?;
    let limit = if m.len() <= 3 { 1 } else { 2 };
    (d <= limit).then_some(best)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suggestions() {
        assert!(closest("MOVV").is_some_and(|s| s.starts_with("MOV")));
        assert_eq!(closest("MOVWW"), Some("MOVW"));
        assert_eq!(closest("TONN"), Some("TON"));
        assert_eq!(closest("XYZZYQ"), None);
    }

    #[test]
    fn string_compares() {
        assert!(is_string_compare("LDS="));
        assert!(is_string_compare("AS<>"));
        assert!(!is_string_compare("LDS"));
        assert!(!is_string_compare("AN"));
    }
}
