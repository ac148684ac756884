//! The string rules of s7-200-more §5.5 as pure functions on the characters of S7 strings (the
//! bytes after the length byte): concatenation, substrings and the two searches. Positions are
//! 1-based as in the manual; characters are bytes (GBK text is searched byte-wise).

use stljit_core::ErrorCode;
use stljit_core::ir::MAX_STRING;

/// `SCAT`: `out` followed by `src`; a result longer than 254 characters is 0x0091 (§13 A4).
pub fn concat(out: &[u8], src: &[u8]) -> Result<Vec<u8>, ErrorCode> {
    if out.len() + src.len() > MAX_STRING {
        return Err(ErrorCode::OperandRange);
    }
    Ok([out, src].concat())
}

/// `SSCPY`: the `count` characters of `src` from position `index`. Index 0 is 0x009B; a
/// substring reaching past the end of `src` is 0x0091 (§13 A4); `count` 0 is the empty string.
pub fn substring(src: &[u8], index: u8, count: u8) -> Result<Vec<u8>, ErrorCode> {
    if index == 0 {
        return Err(ErrorCode::StringIndex);
    }
    let first = usize::from(index) - 1;
    let end = first + usize::from(count);
    if end > src.len() {
        return Err(ErrorCode::OperandRange);
    }
    Ok(src[first..end].to_vec())
}

/// `SFND` (`chars` false: the first occurrence of the whole of `pattern`) and `CFND` (`chars`
/// true: the first character that is any character of `pattern`) in `s` from position `start`:
/// the position found, or 0. Start 0 is 0x009B; a start past the end of `s`, or an empty
/// `pattern`, finds nothing.
pub fn find(s: &[u8], pattern: &[u8], start: u8, chars: bool) -> Result<u8, ErrorCode> {
    if start == 0 {
        return Err(ErrorCode::StringIndex);
    }
    let from = usize::from(start) - 1;
    if from >= s.len() || pattern.is_empty() {
        return Ok(0);
    }
    let hit = if chars {
        s[from..].iter().position(|c| pattern.contains(c))
    } else {
        s[from..].windows(pattern.len()).position(|w| w == pattern)
    };
    // A position is at most 254 + 1 characters in: it fits a byte.
    Ok(hit.map_or(0, |i| (from + i + 1) as u8))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// s7-200-more §12 M9.
    #[test]
    fn m9_strings() {
        let s = concat(b"HELLO", b" WORLD").unwrap();
        assert_eq!(s, b"HELLO WORLD");
        assert_eq!(substring(&s, 7, 5).unwrap(), b"WORLD");
        assert_eq!(find(&s, b"LO", 1, false), Ok(4));
        assert_eq!(find(&s, b" W", 1, true), Ok(6));
    }

    #[test]
    fn edges_and_errors() {
        let s = b"ABCABC";
        assert_eq!(find(s, b"BC", 3, false), Ok(5), "from position 3");
        assert_eq!(find(s, b"BC", 6, false), Ok(0), "too short to hold it");
        assert_eq!(find(s, b"BC", 7, false), Ok(0), "past the end");
        assert_eq!(find(s, b"", 1, false), Ok(0), "empty pattern");
        assert_eq!(find(s, b"C", 0, true), Err(ErrorCode::StringIndex));
        assert_eq!(find(s, b"XC", 4, true), Ok(6));
        assert_eq!(substring(s, 0, 1), Err(ErrorCode::StringIndex));
        assert_eq!(substring(s, 6, 1).unwrap(), b"C");
        assert_eq!(substring(s, 6, 2), Err(ErrorCode::OperandRange));
        assert_eq!(
            substring(s, 7, 0).unwrap(),
            b"",
            "empty right after the end"
        );
        assert_eq!(substring(s, 8, 0), Err(ErrorCode::OperandRange));
        assert_eq!(
            concat(&[b'x'; 200], &[b'y'; 55]),
            Err(ErrorCode::OperandRange)
        );
        assert_eq!(concat(&[b'x'; 200], &[b'y'; 54]).unwrap().len(), 254);
    }
}
