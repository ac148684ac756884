//! Line lexer: splits one source line into its mnemonic and comma-separated operands, dropping
//! `//` comments. Every token keeps its 1-based character column for diagnostics.

/// Most instructions take at most three operands; CALL with parameters may take more, and only
/// the count matters then.
pub(crate) const MAX_OPS: usize = 4;

/// A piece of a source line.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Tok<'a> {
    /// The text, without surrounding blanks.
    pub(crate) text: &'a str,
    /// Column of its first character, 1-based, in characters.
    pub(crate) col: u32,
    /// Length in characters.
    pub(crate) len: u32,
}

/// One lexed non-empty line.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Line<'a> {
    /// Line number, 1-based.
    pub(crate) line: u32,
    /// The first token.
    pub(crate) mnemonic: Tok<'a>,
    /// Everything after the mnemonic up to the comment, trimmed.
    pub(crate) rest: Tok<'a>,
    /// The operands (the first [`MAX_OPS`] of them).
    pub(crate) ops: [Tok<'a>; MAX_OPS],
    /// The real number of operands (may exceed [`MAX_OPS`]).
    pub(crate) n_ops: usize,
}

impl<'a> Line<'a> {
    /// The stored operands.
    pub(crate) fn operands(&self) -> &[Tok<'a>] {
        &self.ops[..self.n_ops.min(MAX_OPS)]
    }
}

fn is_blank(c: char) -> bool {
    c == ' ' || c == '\t' || c == '\u{3000}' || c == '\u{feff}' || c == '\r'
}

/// Column (1-based, characters) of byte offset `off` in `line`.
fn col_at(line: &str, ascii: bool, off: usize) -> u32 {
    let chars = if ascii {
        off
    } else {
        line.get(..off).map_or(off, |s| s.chars().count())
    };
    u32::try_from(chars + 1).unwrap_or(u32::MAX)
}

fn tok<'a>(line: &'a str, ascii: bool, start: usize, end: usize) -> Tok<'a> {
    let raw = &line[start..end];
    let lead = raw.len() - raw.trim_start_matches(is_blank).len();
    let text = raw.trim_matches(is_blank);
    let len = if ascii {
        text.len()
    } else {
        text.chars().count()
    };
    Tok {
        text,
        col: col_at(line, ascii, start + lead),
        len: u32::try_from(len).unwrap_or(u32::MAX),
    }
}

/// Byte offset where the `//` comment starts (outside quotes), or the line length.
fn code_end(line: &str) -> usize {
    let b = line.as_bytes();
    let mut quote = 0u8;
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if quote != 0 {
            if c == quote {
                quote = 0;
            }
        } else if c == b'"' || c == b'\'' {
            quote = c;
        } else if c == b'/' && b.get(i + 1) == Some(&b'/') {
            return i;
        }
        i += 1;
    }
    b.len()
}

/// Lexes one line; `None` for a line with nothing but blanks and comments.
pub(crate) fn lex_line(line: &str, number: u32) -> Option<Line<'_>> {
    let ascii = line.is_ascii();
    let end = code_end(line);
    let code = &line[..end];
    let start = code.len() - code.trim_start_matches(is_blank).len();
    if code[start..].trim_end_matches(is_blank).is_empty() {
        return None;
    }
    let mn_end = code[start..]
        .find(is_blank)
        .map_or(code.len(), |i| start + i);
    let mut out = Line {
        line: number,
        mnemonic: tok(line, ascii, start, mn_end),
        rest: tok(line, ascii, mn_end, end),
        ..Line::default()
    };
    if out.rest.text.is_empty() {
        return Some(out);
    }
    comma_pieces(code, mn_end, |start, end| {
        if out.n_ops < MAX_OPS {
            out.ops[out.n_ops] = tok(line, ascii, start, end);
        }
        out.n_ops += 1;
    });
    Some(out)
}

/// Calls `piece(start, end)` for each comma-separated piece of `text` from byte `from` on, commas
/// inside `"…"` or `'…'` not counting.
fn comma_pieces(text: &str, from: usize, mut piece: impl FnMut(usize, usize)) {
    let b = text.as_bytes();
    let (mut quote, mut start) = (0u8, from);
    for i in from..=b.len() {
        let c = b.get(i).copied().unwrap_or(b',');
        if quote != 0 {
            if c == quote {
                quote = 0;
            }
            if i < b.len() {
                continue;
            }
        } else if c == b'"' || c == b'\'' {
            quote = c;
            continue;
        }
        if c == b',' || i == b.len() {
            piece(start, i);
            start = i + 1;
        }
    }
}

/// Every operand of a line, however many (a `CALL` may pass 16 parameters; [`Line`] keeps only
/// the first [`MAX_OPS`]): `rest` split at commas outside quotes, with columns.
pub(crate) fn all_operands<'a>(line: &Line<'a>) -> Vec<Tok<'a>> {
    let rest = line.rest;
    if rest.text.is_empty() {
        return Vec::new();
    }
    let ascii = rest.text.is_ascii();
    let mut out = Vec::with_capacity(line.n_ops);
    comma_pieces(rest.text, 0, |start, end| {
        let t = tok(rest.text, ascii, start, end);
        out.push(Tok {
            col: rest.col + t.col - 1,
            ..t
        });
    });
    out
}

/// Uppercases an ASCII mnemonic into `buf`; `None` when it is too long or not ASCII (then it
/// cannot be a known mnemonic).
pub(crate) fn upper<'b>(s: &str, buf: &'b mut [u8; 16]) -> Option<&'b str> {
    let b = s.as_bytes();
    if b.len() > buf.len() || !s.is_ascii() {
        return None;
    }
    for (d, &c) in buf.iter_mut().zip(b) {
        *d = c.to_ascii_uppercase();
    }
    std::str::from_utf8(&buf[..b.len()]).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mnemonic_operands_and_comment() {
        let l = lex_line("\tMOVW  VW10, VW100 // copy, twice", 7).unwrap();
        assert_eq!(l.line, 7);
        assert_eq!(l.mnemonic.text, "MOVW");
        assert_eq!(l.mnemonic.col, 2);
        assert_eq!(l.n_ops, 2);
        assert_eq!(l.ops[0].text, "VW10");
        assert_eq!(l.ops[0].col, 8);
        assert_eq!(l.ops[1].text, "VW100");
        assert_eq!(l.ops[1].col, 14);
        assert_eq!(l.rest.text, "VW10, VW100");
    }

    #[test]
    fn blank_and_comment_lines() {
        assert!(lex_line("   // hello", 1).is_none());
        assert!(lex_line("\r", 1).is_none());
        assert!(lex_line("", 1).is_none());
    }

    #[test]
    fn quoted_symbol_with_comma_and_slashes() {
        let l = lex_line("LD \"Start, //Button\"  // c", 1).unwrap();
        assert_eq!(l.n_ops, 1);
        assert_eq!(l.ops[0].text, "\"Start, //Button\"");
    }

    #[test]
    fn columns_count_characters() {
        let l = lex_line("LD 启动按钮, Q0.0", 1).unwrap();
        assert_eq!(l.ops[0].text, "启动按钮");
        assert_eq!(l.ops[0].len, 4);
        assert_eq!(l.ops[1].col, 10);
    }

    #[test]
    fn empty_operand_is_kept() {
        let l = lex_line("S Q0.0,", 1).unwrap();
        assert_eq!(l.n_ops, 2);
        assert_eq!(l.ops[1].text, "");
    }

    #[test]
    fn many_operands_counted() {
        let l = lex_line("CALL SBR0, a, b, c, d, e", 1).unwrap();
        assert_eq!(l.n_ops, 6);
    }

    #[test]
    fn all_operands_of_a_long_call() {
        let l = lex_line("\tCALL   SCALE, L60.0, VW0, +3, \"a,b\", VW20 // c", 1).unwrap();
        let ops = all_operands(&l);
        let texts: Vec<_> = ops.iter().map(|t| t.text).collect();
        assert_eq!(texts, ["SCALE", "L60.0", "VW0", "+3", "\"a,b\"", "VW20"]);
        assert_eq!(ops[0].col, l.ops[0].col);
        assert_eq!(ops[3].col, l.ops[3].col);
        assert_eq!(ops[5].col, 39);
    }

    #[test]
    fn upper_case() {
        let mut buf = [0; 16];
        assert_eq!(upper("ldw>=", &mut buf), Some("LDW>="));
        assert_eq!(upper("启动", &mut buf), None);
    }
}
