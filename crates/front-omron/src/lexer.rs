//! Line lexer of the Omron mnemonic dialect (omron-cp.md §1.2): one instruction per line, the
//! options `!`, `@`, `%`, the mnemonic (also the two-word ones `AND LD`, `OUT NOT` …), an
//! optional function code `(nnn)` and whitespace-separated operands, with `;` and `//`
//! comments. An operand token that is exactly `CIO` is joined with the token after it. Every
//! token keeps its 1-based character column for diagnostics.

/// A piece of a source line.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct Tok {
    /// The text (a joined `CIO` operand is `CIO` + the next token).
    pub(crate) text: String,
    /// Column of its first character, 1-based, in characters.
    pub(crate) col: u32,
    /// Length in characters, up to the end of the last joined piece.
    pub(crate) len: u32,
}

/// The execution options written before a mnemonic.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Options {
    /// `!`: immediate refresh.
    pub(crate) immediate: bool,
    /// `@` (`Some(false)`) or `%` (`Some(true)`): up- or down-differentiated.
    pub(crate) edge: Option<bool>,
}

impl Options {
    /// The options as written (`!@`, `%`, or empty).
    pub(crate) fn text(self) -> String {
        let mut s = String::new();
        if self.immediate {
            s.push('!');
        }
        match self.edge {
            Some(false) => s.push('@'),
            Some(true) => s.push('%'),
            None => {}
        }
        s
    }
}

/// One lexed non-empty line.
#[derive(Clone, Debug, Default)]
pub(crate) struct Line {
    /// Line number, 1-based.
    pub(crate) line: u32,
    /// The options.
    pub(crate) options: Options,
    /// The mnemonic, upper-cased, two-word forms joined by one space (`AND LD`).
    pub(crate) mnemonic: String,
    /// Where the whole instruction word (options, mnemonic, code) is.
    pub(crate) head: Tok,
    /// The function code written in parentheses, if any (`Err` with the text when it is not a
    /// number).
    pub(crate) code: Option<Result<u16, String>>,
    /// The operands.
    pub(crate) operands: Vec<Tok>,
    /// A `CIO` token with nothing usable after it (E013).
    pub(crate) dangling_cio: Option<Tok>,
}

/// The words that, after `LD`/`AND`/`OR`/`OUT` (and the block-program `IF`/`WAIT`/`EXIT`/
/// `LEND`), form one two-word mnemonic.
const SECOND_WORDS: [(&str, &str); 10] = [
    ("AND", "LD"),
    ("OR", "LD"),
    ("AND", "NOT"),
    ("OR", "NOT"),
    ("LD", "NOT"),
    ("OUT", "NOT"),
    ("IF", "NOT"),
    ("WAIT", "NOT"),
    ("EXIT", "NOT"),
    ("LEND", "NOT"),
];

fn is_blank(c: char) -> bool {
    c.is_whitespace() || c == '\u{feff}'
}

/// Byte offset where the comment (`;` or `//` outside quotes) starts, or the line length.
fn code_end(line: &str) -> usize {
    let b = line.as_bytes();
    let mut quoted = false;
    for (i, &c) in b.iter().enumerate() {
        if c == b'\'' {
            quoted = !quoted;
        } else if !quoted && (c == b';' || (c == b'/' && b.get(i + 1) == Some(&b'/'))) {
            return i;
        }
    }
    b.len()
}

fn count(s: &str) -> u32 {
    u32::try_from(s.chars().count()).unwrap_or(u32::MAX)
}

/// The blank-separated words of `code` with their 1-based character columns.
fn words(code: &str) -> Vec<(u32, &str)> {
    let mut out = Vec::new();
    let mut start: Option<usize> = None;
    for (i, c) in code
        .char_indices()
        .chain(std::iter::once((code.len(), ' ')))
    {
        match (start, is_blank(c)) {
            (None, false) => start = Some(i),
            (Some(s), true) => {
                let col = count(&code[..s]).saturating_add(1);
                out.push((col, &code[s..i]));
                start = None;
            }
            _ => {}
        }
    }
    out
}

/// Splits `!@MOV(021)` into options, mnemonic and code text.
fn split_head(word: &str) -> (Options, &str, Option<&str>) {
    let mut options = Options::default();
    let mut rest = word;
    if let Some(r) = rest.strip_prefix('!') {
        options.immediate = true;
        rest = r;
    }
    // `@`/`%` is an option only when a mnemonic follows it (a lone `%` is not an instruction).
    if rest.len() > 1 {
        if let Some(r) = rest.strip_prefix('@') {
            options.edge = Some(false);
            rest = r;
        } else if let Some(r) = rest.strip_prefix('%') {
            options.edge = Some(true);
            rest = r;
        }
    }
    match rest.find('(') {
        Some(i) if i > 0 => (options, &rest[..i], Some(&rest[i..])),
        _ => (options, rest, None),
    }
}

fn parse_code(text: &str) -> Result<u16, String> {
    text.strip_prefix('(')
        .and_then(|t| t.strip_suffix(')'))
        .filter(|d| !d.is_empty() && d.len() <= 4 && d.bytes().all(|b| b.is_ascii_digit()))
        .and_then(|d| d.parse().ok())
        .ok_or_else(|| text.to_owned())
}

/// Lexes one line; `None` for a line with nothing but blanks and comments.
pub(crate) fn lex_line(line: &str, number: u32) -> Option<Line> {
    let code = &line[..code_end(line)];
    let mut ws = words(code).into_iter().peekable();
    let (col, first) = ws.next()?;
    let (options, name, mut code_text) = split_head(first);
    let mut mnemonic = name.to_ascii_uppercase();
    let mut head_len = count(first);
    if let Some(&(c2, second)) = ws.peek() {
        let up = second.to_ascii_uppercase();
        if SECOND_WORDS.contains(&(mnemonic.as_str(), up.as_str())) {
            mnemonic = format!("{mnemonic} {up}");
            head_len = c2 + count(second) - col;
            ws.next();
        }
    }
    if code_text.is_none()
        && let Some(&(c2, w)) = ws.peek()
        && w.starts_with('(')
        && w.ends_with(')')
    {
        code_text = Some(w);
        head_len = c2 + count(w) - col;
        ws.next();
    }
    let mut out = Line {
        line: number,
        options,
        mnemonic,
        head: Tok {
            text: first.to_owned(),
            col,
            len: head_len,
        },
        code: code_text.map(parse_code),
        ..Line::default()
    };
    while let Some((c, w)) = ws.next() {
        if w.eq_ignore_ascii_case("CIO") {
            match ws.next() {
                Some((c2, next)) => out.operands.push(Tok {
                    text: format!("CIO{next}"),
                    col: c,
                    len: c2 + count(next) - c,
                }),
                None => {
                    out.dangling_cio = Some(Tok {
                        text: w.to_owned(),
                        col: c,
                        len: 3,
                    })
                }
            }
        } else {
            out.operands.push(Tok {
                text: w.to_owned(),
                col: c,
                len: count(w),
            });
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn options_mnemonic_code_and_operands() {
        let l = lex_line("  !@MOV(021) #0001\tD100 ; copy", 3).unwrap();
        assert_eq!(l.line, 3);
        assert!(l.options.immediate);
        assert_eq!(l.options.edge, Some(false));
        assert_eq!(l.mnemonic, "MOV");
        assert_eq!(l.code, Some(Ok(21)));
        assert_eq!(l.head.col, 3);
        let ops: Vec<_> = l
            .operands
            .iter()
            .map(|t| (t.text.as_str(), t.col))
            .collect();
        assert_eq!(ops, [("#0001", 14), ("D100", 20)]);
    }

    #[test]
    fn two_word_mnemonics_and_separate_code() {
        assert_eq!(lex_line("and ld", 1).unwrap().mnemonic, "AND LD");
        let l = lex_line("OUT NOT 100.00", 1).unwrap();
        assert_eq!(l.mnemonic, "OUT NOT");
        assert_eq!(l.operands[0].text, "100.00");
        let l = lex_line("END (001)", 1).unwrap();
        assert_eq!((l.mnemonic.as_str(), l.code.clone()), ("END", Some(Ok(1))));
        assert_eq!(lex_line("%LD 0.00", 1).unwrap().options.edge, Some(true));
        assert_eq!(lex_line("-B(414) #1 #2 D0", 1).unwrap().mnemonic, "-B");
    }

    #[test]
    fn cio_is_joined_with_the_next_token() {
        let l = lex_line("LD CIO 0100.01", 1).unwrap();
        assert_eq!(l.operands.len(), 1);
        assert_eq!(l.operands[0].text, "CIO0100.01");
        assert_eq!((l.operands[0].col, l.operands[0].len), (4, 11));
        let l = lex_line("OUT CIO", 1).unwrap();
        assert!(l.operands.is_empty());
        assert!(l.dangling_cio.is_some());
    }

    #[test]
    fn comments_and_blank_lines() {
        assert!(lex_line("   ; only a comment", 1).is_none());
        assert!(lex_line("// c", 1).is_none());
        assert!(lex_line("\r", 1).is_none());
        assert_eq!(lex_line("LD 0.00 // x", 1).unwrap().operands.len(), 1);
        assert_eq!(
            lex_line("MOV(21x) 1 2", 1).unwrap().code,
            Some(Err("(21x)".into()))
        );
    }
}
