//! Dialect detection heuristics: does a text look like Omron mnemonics or like S7 STL? Each
//! function scores the instruction lines by the marks only its dialect writes (Omron:
//! function codes `(021)`, `AND LD`, `OUT`, CIO bits `0.00`; S7: `NETWORK`, `= Q0.0`, `I0.0`
//! operands, block keywords); the caller decides when neither or both say yes.

/// How many lines are inspected (enough for any realistic header, cheap on huge files).
const LINES: usize = 400;

fn code_lines(text: &str) -> impl Iterator<Item = String> + '_ {
    text.lines().take(LINES).filter_map(|l| {
        let l = l.split("//").next().unwrap_or("");
        let l = l.split(';').next().unwrap_or("").trim();
        (!l.is_empty()).then(|| l.to_ascii_uppercase())
    })
}

fn is_cio_bit(op: &str) -> bool {
    let op = op.strip_prefix("CIO").unwrap_or(op);
    let (w, b) = op.split_once('.').unwrap_or(("", ""));
    let w = w.trim_start_matches(['W', 'H', 'A']);
    !w.is_empty()
        && w.bytes().all(|c| c.is_ascii_digit())
        && b.len() == 2
        && b.bytes().all(|c| c.is_ascii_digit())
}

fn is_s7_bit(op: &str) -> bool {
    let letters = op.trim_end_matches(|c: char| c.is_ascii_digit() || c == '.');
    matches!(letters, "I" | "Q" | "M" | "SM" | "V" | "S" | "L") && op[letters.len()..].contains('.')
}

fn has_function_code(first: &str) -> bool {
    first.find('(').is_some_and(|i| {
        let c = &first[i + 1..];
        c.len() == 4 && c.ends_with(')') && c[..3].bytes().all(|b| b.is_ascii_digit())
    })
}

/// Whether `text` looks like Omron CP mnemonics (`LD 0.00`, `OUT 100.00`, `MOV(021)`,
/// `AND LD`, `END(001)`).
pub fn looks_like_omron(text: &str) -> bool {
    let mut score = 0i32;
    for l in code_lines(text) {
        let mut w = l.split_whitespace();
        let first = w.next().unwrap_or("");
        let second = w.next().unwrap_or("");
        if has_function_code(first) || matches!((first, second), ("AND" | "OR", "LD") | ("OUT", _))
        {
            score += 2;
        }
        if is_cio_bit(second) || second.starts_with("TR") || second.starts_with("P_") {
            score += 1;
        }
        if is_s7_bit(second) || first == "=" || first == "NETWORK" {
            score -= 2;
        }
    }
    score > 0
}

/// Whether `text` looks like S7-200 STL (`LD I0.0`, `= Q0.0`, `NETWORK`,
/// `ORGANIZATION_BLOCK`).
pub fn looks_like_s7(text: &str) -> bool {
    let mut score = 0i32;
    for l in code_lines(text) {
        let mut w = l.split_whitespace();
        let first = w.next().unwrap_or("");
        let second = w.next().unwrap_or("").trim_end_matches(',');
        if matches!(
            first,
            "NETWORK"
                | "ORGANIZATION_BLOCK"
                | "SUBROUTINE_BLOCK"
                | "INTERRUPT_BLOCK"
                | "="
                | "ALD"
                | "OLD"
                | "LPS"
                | "LPP"
                | "MEND"
        ) {
            score += 2;
        }
        if is_s7_bit(second) {
            score += 1;
        }
        if has_function_code(first)
            || is_cio_bit(second)
            || matches!((first, second), ("AND" | "OR", "LD"))
        {
            score -= 2;
        }
    }
    score > 0
}

#[cfg(test)]
mod tests {
    use super::*;

    const OMRON: &str = "LD 0.00\nOR 0.01\nAND LD\nOUT 100.00\nMOV(021) #0001 D0\nEND(001)\n";
    const S7: &str = "NETWORK 1\nLD I0.0\nA I0.1\n= Q0.0\n";

    #[test]
    fn each_dialect_is_recognised_and_not_the_other() {
        assert!(looks_like_omron(OMRON));
        assert!(!looks_like_s7(OMRON));
        assert!(looks_like_s7(S7));
        assert!(!looks_like_omron(S7));
        assert!(looks_like_s7(
            "ORGANIZATION_BLOCK OB1\nBEGIN\nLD I0.0\n= Q0.0\nEND_ORGANIZATION_BLOCK\n"
        ));
        assert!(looks_like_omron(
            "LD P_First_Cycle ; c\n@MOV(021) #00AA D1\n"
        ));
    }

    #[test]
    fn undecidable_texts_are_neither() {
        for t in ["", "; only a comment\n", "LD X\n", "NOP\n"] {
            assert!(!looks_like_omron(t), "{t:?}");
            assert!(!looks_like_s7(t), "{t:?}");
        }
    }
}
