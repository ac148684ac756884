//! The parser's lexical layer: a [`Line`] split into words and quoted strings, and the value
//! readers on a [`Word`] (numbers, indices, flags, enum names, locations, operands). Every
//! reader returns an error with the word's line and column instead of panicking.

use super::debug_is;
use super::error::{ParseError, ParseErrorKind, Result, error};
use crate::area::Area;
use crate::index::FileId;
use crate::ir::{BitLoc, IndexOffset, IndexStep, Loc, OmronRef, Operand, SrcLoc};
use std::fmt;

/// A 1-based column from a 0-based character count.
pub(super) fn col_of(chars: usize) -> u32 {
    u32::try_from(chars)
        .unwrap_or(u32::MAX - 1)
        .saturating_add(1)
}

/// One piece of a line.
#[derive(Debug)]
enum Piece<'a> {
    Word(&'a str),
    Str(String),
}

/// A line split into pieces, read left to right.
pub(super) struct Line<'a> {
    no: u32,
    pieces: Vec<(Piece<'a>, u32)>,
    next: usize,
    end_col: u32,
}

impl<'a> Line<'a> {
    /// Splits a line into words (runs of anything but white space, `"` and `;`) and strings;
    /// `;` outside a string starts a comment.
    pub(super) fn split(raw: &'a str, no: u32) -> Result<Line<'a>> {
        let mut pieces = Vec::new();
        let mut chars = raw.char_indices().enumerate().peekable();
        let mut end_col = col_of(raw.chars().count());
        while let Some((n, (at, c))) = chars.next() {
            let col = col_of(n);
            if c == ';' {
                end_col = col;
                break;
            }
            if c.is_whitespace() {
                continue;
            }
            if c == '"' {
                let mut s = String::new();
                loop {
                    let Some((m, (_, c))) = chars.next() else {
                        return Err(error(no, col, ParseErrorKind::String("no closing `\"`")));
                    };
                    match c {
                        '"' => break,
                        '\\' => s.push(escape(&mut chars, no, col_of(m))?),
                        c => s.push(c),
                    }
                }
                pieces.push((Piece::Str(s), col));
                continue;
            }
            let mut end = at + c.len_utf8();
            while let Some(&(_, (b, c))) = chars.peek() {
                if c.is_whitespace() || c == '"' || c == ';' {
                    break;
                }
                end = b + c.len_utf8();
                chars.next();
            }
            pieces.push((Piece::Word(&raw[at..end]), col));
        }
        Ok(Line {
            no,
            pieces,
            next: 0,
            end_col,
        })
    }

    pub(super) fn is_empty(&self) -> bool {
        self.pieces.is_empty()
    }

    pub(super) fn err(&self, col: u32, kind: ParseErrorKind) -> ParseError {
        error(self.no, col, kind)
    }

    /// The column of the next piece (or of the line's end).
    fn col(&self) -> u32 {
        self.pieces.get(self.next).map_or(self.end_col, |p| p.1)
    }

    /// What the next piece is, for messages.
    fn found(&self) -> String {
        match self.pieces.get(self.next) {
            Some((Piece::Word(w), _)) => format!("`{w}`"),
            Some((Piece::Str(_), _)) => "a string".to_owned(),
            None => "end of line".to_owned(),
        }
    }

    fn expected(&self, expected: &'static str) -> ParseError {
        let found = self.found();
        self.err(self.col(), ParseErrorKind::Expected { expected, found })
    }

    /// The next piece, which must be a word.
    pub(super) fn word(&mut self, expected: &'static str) -> Result<Word<'a>> {
        match self.pieces.get(self.next) {
            Some(&(Piece::Word(text), col)) => {
                self.next += 1;
                Ok(Word {
                    text,
                    col,
                    line: self.no,
                })
            }
            _ => Err(self.expected(expected)),
        }
    }

    /// The next piece, which must be a string.
    pub(super) fn string(&mut self, expected: &'static str) -> Result<String> {
        match self.pieces.get_mut(self.next) {
            Some((Piece::Str(s), _)) => {
                self.next += 1;
                Ok(std::mem::take(s))
            }
            _ => Err(self.expected(expected)),
        }
    }

    /// The next piece, which must be the word `key=value`; returns the value.
    pub(super) fn field(&mut self, key: &'static str) -> Result<Word<'a>> {
        if let Some(&(Piece::Word(text), col)) = self.pieces.get(self.next)
            && let Some((k, v)) = text.split_once('=')
            && k == key
        {
            self.next += 1;
            return Ok(Word {
                text: v,
                col: col.saturating_add(col_of(k.chars().count())),
                line: self.no,
            });
        }
        let found = self.found();
        Err(self.err(self.col(), ParseErrorKind::Field { key, found }))
    }

    /// Takes the next piece when it is the word `key=value`; returns the value.
    pub(super) fn optional_field(&mut self, key: &'static str) -> Option<Word<'a>> {
        match self.pieces.get(self.next) {
            Some((Piece::Word(text), _)) if text.split_once('=').is_some_and(|(k, _)| k == key) => {
                self.field(key).ok()
            }
            _ => None,
        }
    }

    /// Takes the next piece when it is a word starting with `c`.
    pub(super) fn word_starting(&mut self, c: char) -> Option<Word<'a>> {
        match self.pieces.get(self.next) {
            Some(&(Piece::Word(text), col)) if text.starts_with(c) => {
                self.next += 1;
                Some(Word {
                    text,
                    col,
                    line: self.no,
                })
            }
            _ => None,
        }
    }

    /// Nothing may follow.
    pub(super) fn finish(&self) -> Result<()> {
        if self.next < self.pieces.len() {
            return Err(self.expected("end of line"));
        }
        Ok(())
    }
}

/// The character after a `\` in a string.
fn escape(
    chars: &mut impl Iterator<Item = (usize, (usize, char))>,
    no: u32,
    col: u32,
) -> Result<char> {
    let bad = || error(no, col, ParseErrorKind::String("unknown escape"));
    Ok(match chars.next().ok_or_else(bad)?.1.1 {
        '"' => '"',
        '\\' => '\\',
        'n' => '\n',
        't' => '\t',
        'r' => '\r',
        'u' => {
            if chars.next().map(|c| c.1.1) != Some('{') {
                return Err(bad());
            }
            let mut code = 0u32;
            let mut digits = 0;
            loop {
                let c = chars.next().ok_or_else(bad)?.1.1;
                if c == '}' {
                    break;
                }
                let d = c.to_digit(16).ok_or_else(bad)?;
                digits += 1;
                if digits > 6 {
                    return Err(bad());
                }
                code = code * 16 + d;
            }
            if digits == 0 {
                return Err(bad());
            }
            char::from_u32(code).ok_or_else(bad)?
        }
        _ => return Err(bad()),
    })
}

/// A word of a line with its position, for values and their errors.
#[derive(Clone, Copy)]
pub(super) struct Word<'a> {
    /// The word (or the part of it being read).
    pub(super) text: &'a str,
    /// Its column.
    pub(super) col: u32,
    /// Its line.
    pub(super) line: u32,
}

impl<'a> Word<'a> {
    pub(super) fn err(&self, kind: ParseErrorKind) -> ParseError {
        error(self.line, self.col, kind)
    }

    pub(super) fn unknown(&self, what: &'static str) -> ParseError {
        self.err(ParseErrorKind::Unknown {
            what,
            word: self.text.to_owned(),
        })
    }

    /// The part after `offset` bytes (which end on a character boundary), with its column.
    pub(super) fn tail(&self, offset: usize) -> Word<'a> {
        let text = self.text.get(offset..).unwrap_or("");
        let skipped = self.text.get(..offset).map_or(0, |s| s.chars().count());
        Word {
            text,
            col: self.col.saturating_add(col_of(skipped) - 1),
            ..*self
        }
    }

    /// A decimal or `0x` hexadecimal number that fits `T`.
    pub(super) fn number<T: TryFrom<u64>>(&self, what: &'static str) -> Result<T> {
        let bad = || {
            self.err(ParseErrorKind::Number {
                what,
                word: self.text.to_owned(),
            })
        };
        let (digits, radix) = match self.text.strip_prefix("0x") {
            Some(hex) => (hex, 16),
            None => (self.text, 10),
        };
        if digits.is_empty() || !digits.chars().all(|c| c.is_digit(radix)) {
            return Err(bad());
        }
        let n = u64::from_str_radix(digits, radix).map_err(|_| bad())?;
        T::try_from(n).map_err(|_| bad())
    }

    /// An index written as its `Display` form, e.g. `T37` for `TimerId(37)`: the prefix is
    /// taken from `zero`'s `Display`, so index.rs stays the one place that spells it.
    pub(super) fn index<T: TryFrom<u64>>(
        &self,
        zero: impl fmt::Display,
        what: &'static str,
    ) -> Result<T> {
        let z = zero.to_string();
        let prefix = z.strip_suffix('0').unwrap_or(&z);
        if !self.text.starts_with(prefix) {
            return Err(self.err(ParseErrorKind::Expected {
                expected: what,
                found: format!("`{}`", self.text),
            }));
        }
        self.tail(prefix.len()).number(what)
    }

    pub(super) fn flag(&self) -> Result<bool> {
        match self.text {
            "0" => Ok(false),
            "1" => Ok(true),
            _ => Err(self.err(ParseErrorKind::Expected {
                expected: "0 or 1",
                found: format!("`{}`", self.text),
            })),
        }
    }

    /// One of `all`, by its `Debug` name.
    pub(super) fn choice<T: Copy + fmt::Debug>(&self, all: &[T], what: &'static str) -> Result<T> {
        all.iter()
            .copied()
            .find(|v| debug_is(v, self.text))
            .ok_or_else(|| self.unknown(what))
    }

    /// Splits the word at the first `N - 1` separators `sep` into `N` parts (the last takes
    /// the rest, separators included), each with its column.
    pub(super) fn split_n<const N: usize>(&self, sep: char) -> Result<[Word<'a>; N]> {
        let mut parts = [*self; N];
        let mut start = 0;
        for (i, part) in parts.iter_mut().enumerate() {
            let rest = &self.text[start..];
            let len = if i + 1 == N {
                rest.len()
            } else {
                rest.find(sep).ok_or_else(|| {
                    self.err(ParseErrorKind::Expected {
                        expected: "more comma-separated parts",
                        found: format!("`{}`", self.text),
                    })
                })?
            };
            let tail = self.tail(start);
            *part = Word {
                text: &tail.text[..len],
                ..tail
            };
            start += len + sep.len_utf8();
        }
        Ok(parts)
    }

    /// `Area.offset`.
    pub(super) fn loc(&self) -> Result<Loc> {
        let (area, rest) = self.area()?;
        Ok(Loc {
            area,
            offset: rest.number("byte offset")?,
        })
    }

    /// `Area.byte.bit`.
    pub(super) fn bit(&self) -> Result<BitLoc> {
        let (area, rest) = self.area()?;
        let Some(dot) = rest.text.find('.') else {
            return Err(rest.err(ParseErrorKind::Expected {
                expected: "`byte.bit`",
                found: format!("`{}`", rest.text),
            }));
        };
        Ok(BitLoc {
            area,
            byte: Word {
                text: &rest.text[..dot],
                ..rest
            }
            .number("byte offset")?,
            bit: rest.tail(dot + 1).number("bit number")?,
        })
    }

    /// The area before the first `.`, and what follows the `.`.
    fn area(&self) -> Result<(Area, Word<'a>)> {
        let Some(dot) = self.text.find('.') else {
            return Err(self.err(ParseErrorKind::Expected {
                expected: "a location `Area.offset`",
                found: format!("`{}`", self.text),
            }));
        };
        let name = Word {
            text: &self.text[..dot],
            ..*self
        };
        Ok((name.choice(&Area::ALL, "area")?, self.tail(dot + 1)))
    }

    /// A value operand: `Area.offset`, `const(n)`, `deref(Area.offset)`, `addr(Area.offset)`,
    /// or an Omron indirect one: `ind_bin(n)`, `ind_bcd(n)`, `ind_ir(ir,offset,step)`.
    pub(super) fn operand(&self) -> Result<Operand> {
        if let Some(r) = self.omron_ref()? {
            return Ok(Operand::Omron(r));
        }
        for (head, make) in [
            ("const(", None),
            ("deref(", Some(Operand::Indirect as fn(Loc) -> Operand)),
            ("addr(", Some(Operand::AddressOf as fn(Loc) -> Operand)),
        ] {
            if self.text.starts_with(head) {
                let Some(inner) = self.text.strip_suffix(')') else {
                    return Err(self.err(ParseErrorKind::Expected {
                        expected: "`)` at the operand's end",
                        found: format!("`{}`", self.text),
                    }));
                };
                let inner = Word {
                    text: inner,
                    ..*self
                }
                .tail(head.len());
                return match make {
                    None => Ok(Operand::Const(inner.number("constant")?)),
                    Some(make) => Ok(make(inner.loc()?)),
                };
            }
        }
        Ok(Operand::Mem(self.loc()?))
    }

    /// `ind_bin(n)`, `ind_bcd(n)`, `ind_ir(ir,offset,step)` (offset `+c`/`-c` or `drN`, step
    /// an `IndexStep` name), or `None` for another operand.
    fn omron_ref(&self) -> Result<Option<OmronRef>> {
        let Some((head, inner)) = ["ind_bin(", "ind_bcd(", "ind_ir("]
            .into_iter()
            .find_map(|h| Some((h, self.text.strip_prefix(h)?.strip_suffix(')')?)))
        else {
            return Ok(None);
        };
        let part = |text: &'a str| Word { text, ..*self };
        let bad = || {
            self.err(ParseErrorKind::Expected {
                expected: "`ind_ir(ir,+offset|drN,none|post1|post2|pre1|pre2)`",
                found: format!("`{}`", self.text),
            })
        };
        Ok(Some(match head {
            "ind_bin(" => OmronRef::DmBinary(part(inner).number("DM word")?),
            "ind_bcd(" => OmronRef::DmBcd(part(inner).number("DM word")?),
            _ => {
                let mut it = inner.split(',');
                let (Some(ir), Some(off), Some(step), None) =
                    (it.next(), it.next(), it.next(), it.next())
                else {
                    return Err(bad());
                };
                let offset = match off.strip_prefix("dr") {
                    Some(m) => IndexOffset::Dr(part(m).number("data register")?),
                    None => {
                        let c: i16 = off.parse().map_err(|_| bad())?;
                        IndexOffset::Const(c)
                    }
                };
                let step = IndexStep::ALL
                    .into_iter()
                    .find(|s| s.name() == step)
                    .ok_or_else(bad)?;
                OmronRef::Index {
                    ir: part(ir).number("index register")?,
                    offset,
                    step,
                }
            }
        }))
    }

    /// `@file0:12:3`.
    pub(super) fn src_loc(&self) -> Result<SrcLoc> {
        let parts: Vec<&str> = self.text.trim_start_matches('@').split(':').collect();
        let [file, line, col] = parts[..] else {
            return Err(self.err(ParseErrorKind::Expected {
                expected: "a source location `@fileN:line:col`",
                found: format!("`{}`", self.text),
            }));
        };
        let part = |text| Word { text, ..*self };
        Ok(SrcLoc {
            file: FileId(part(file).index(FileId(0), "file index")?),
            line: part(line).number("line number")?,
            col: part(col).number("column number")?,
        })
    }
}
