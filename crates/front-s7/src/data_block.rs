//! MicroWIN's data block (`DATA_BLOCK … END_DATA_BLOCK`): the initial values of V memory,
//! which the engines write at cold start (`Program::data`).
//!
//! Each line is `address value, value, …  // comment` or, continuing the line before it, just
//! `value, …`. The address is `VBn`, `VWn` or `VDn` and fixes the width of the values that
//! follow; a line without an address continues right after the previous value with the same
//! width (MicroWIN's "implicit address assignment"); the first line needs an address. Values are
//! integers (`255`, `-35`, `+1000`), `16#…` and `2#…` constants and reals (`700.5`, `VD` only),
//! each range-checked against the width, `'text'` (its characters, one byte each, as they
//! are) and `"text"` (an S7 string: a length byte, then the characters; `VB` only). Characters
//! are stored in the bytes of the file's encoding. Anything else, or a value past the end of V,
//! is E061; a value that sets bytes an earlier one already set is W060 (the later wins).

use crate::lexer::{code_end, comma_pieces};
use crate::operand::{Const, parse_const};
use stljit_core::ir::{DataInit, MAX_STRING};
use stljit_core::{Area, CpuProfile, FileId, Width};
use stljit_source::{Code, Diagnostic, Encoding, Span, clip};

/// A line inside a data block, as the structure pass found it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct DataLine<'a> {
    /// The file.
    pub(crate) file: FileId,
    /// Its line number.
    pub(crate) line: u32,
    /// The raw text.
    pub(crate) text: &'a str,
}

/// Reading state across the lines of every data block.
struct Reader<'d> {
    diags: &'d mut Vec<Diagnostic>,
    v_size: u32,
    /// Bytes of V already set (for W060).
    set: Vec<bool>,
    /// Where an implicit value goes next, and its width.
    next: Option<(u32, Width)>,
    out: Vec<DataInit>,
}

/// The column (1-based, in characters) of byte `at` of `text`.
fn col(text: &str, at: usize) -> u32 {
    let chars = text.get(..at).map_or(at, |s| s.chars().count());
    u32::try_from(chars + 1).unwrap_or(u32::MAX)
}

impl Reader<'_> {
    fn error(&mut self, line: &DataLine<'_>, at: usize, piece: &str, msg: String, help: &str) {
        let span = Span {
            file: line.file,
            line: line.line,
            col: col(line.text, at),
            len: u32::try_from(piece.chars().count().max(1)).unwrap_or(u32::MAX),
        };
        self.diags
            .push(Diagnostic::new(Code::DataBlock, span, piece, msg).help(help));
    }

    /// The bytes of one value written at `width`.
    fn value(&self, piece: &str, width: Width, encoding: Encoding) -> Result<Vec<u8>, String> {
        if let Some(inner) = piece.strip_prefix('\'').and_then(|s| s.strip_suffix('\'')) {
            return Ok(stljit_source::decode::encode(inner, encoding));
        }
        if let Some(inner) = piece.strip_prefix('"').and_then(|s| s.strip_suffix('"')) {
            if width != Width::Byte {
                return Err("a string \"…\" needs a VB address".into());
            }
            let chars = stljit_source::decode::encode(inner, encoding);
            if chars.len() > MAX_STRING || inner.contains('"') {
                return Err(format!(
                    "a string holds at most {MAX_STRING} bytes, without `\"`"
                ));
            }
            let mut b = vec![chars.len() as u8];
            b.extend(chars);
            return Ok(b);
        }
        let (lo, hi): (i64, i64) = match width {
            Width::Byte => (-128, 255),
            Width::Word => (-32768, 65535),
            Width::DWord => (i64::from(i32::MIN), i64::from(u32::MAX)),
        };
        let bits = match parse_const(piece) {
            Ok(Const::Int(i)) if (lo..=hi).contains(&i) => (i as u32) & width.mask(),
            Ok(Const::Bits(b)) if b <= u64::from(width.mask()) => b as u32,
            Ok(Const::Real(f)) if width == Width::DWord => f.to_bits(),
            Ok(Const::Real(_)) => return Err("a real value needs a VD address".into()),
            Ok(_) => return Err(format!("the value does not fit: allowed {lo} .. {hi}")),
            Err(_) => {
                return Err("expected a number, 16#…, 2#…, a real, 'text' or \"text\"".to_owned());
            }
        };
        Ok(bits.to_be_bytes()[4 - width.bytes() as usize..].to_vec())
    }

    fn line(&mut self, line: &DataLine<'_>, encoding: Encoding) {
        let code = &line.text[..code_end(line.text)];
        let trimmed = code.trim_start();
        if trimmed.trim_end().is_empty() || trimmed.trim_end().eq_ignore_ascii_case("BEGIN") {
            return;
        }
        let lead = code.len() - trimmed.len();
        let word_end = trimmed
            .find(|c: char| c.is_whitespace())
            .unwrap_or(trimmed.len());
        let word = &trimmed[..word_end];
        let (mut values_at, explicit) = match address(word) {
            Some(Ok(a)) => (lead + word_end, Some(a)),
            Some(Err(why)) => {
                let msg = format!("`{}`: {why}", clip(word));
                self.error(
                    line,
                    lead,
                    word,
                    msg,
                    "data block addresses are VBn, VWn or VDn",
                );
                self.next = None;
                return;
            }
            None => (lead, None),
        };
        match explicit {
            Some(a) => self.next = Some(a),
            None if self.next.is_none() => {
                self.error(
                    line,
                    lead,
                    word,
                    "a data block line without an address follows no line with one".into(),
                    "start the data block with an address: `VB0  1, 2, 3`",
                );
                return;
            }
            None => {}
        }
        let mut pieces = Vec::new();
        comma_pieces(code, values_at, |s, e| pieces.push((s, e)));
        if explicit.is_some() && code[values_at..].trim().is_empty() {
            let at = values_at;
            self.error(
                line,
                at,
                "",
                "the address has no value".into(),
                "write `VB0  1` or `VW2  16#1234`",
            );
            return;
        }
        for (s, e) in pieces {
            let raw = &code[s..e];
            let piece = raw.trim();
            values_at = s + (raw.len() - raw.trim_start().len());
            let Some((at, width)) = self.next else {
                return;
            };
            let bytes = match self.value(piece, width, encoding) {
                Ok(b) => b,
                Err(why) => {
                    self.error(
                        line,
                        values_at,
                        piece,
                        format!("`{}`: {why}", clip(piece)),
                        "see docs/microwin.md, \"Data blocks\"",
                    );
                    self.next = None;
                    return;
                }
            };
            let end = at as usize + bytes.len();
            if end > self.v_size as usize {
                let last = self.v_size.saturating_sub(1);
                self.error(
                    line,
                    values_at,
                    piece,
                    format!("`{}` at VB{at} runs past the end of V", clip(piece)),
                    &format!("V runs from VB0 to VB{last} on this CPU"),
                );
                self.next = None;
                return;
            }
            if self.set[at as usize..end].iter().any(|&b| b) {
                let span = Span {
                    file: line.file,
                    line: line.line,
                    col: col(line.text, values_at),
                    len: u32::try_from(piece.chars().count().max(1)).unwrap_or(u32::MAX),
                };
                self.diags.push(
                    Diagnostic::new(
                        Code::DataOverlap,
                        span,
                        piece,
                        if end - 1 == at as usize {
                            format!("`{}` sets VB{at} again", clip(piece))
                        } else {
                            format!("`{}` sets VB{at} … VB{} again", clip(piece), end - 1)
                        },
                    )
                    .help("the later value wins"),
                );
            }
            self.set[at as usize..end].fill(true);
            // A value right after the previous one extends its run (one run per line).
            match self.out.last_mut() {
                Some(last) if last.offset as usize + last.bytes.len() == at as usize => {
                    last.bytes.extend(bytes);
                }
                _ => self.out.push(DataInit { offset: at, bytes }),
            }
            self.next = Some((end as u32, width));
        }
    }
}

/// A data block address: `VBn`/`VWn`/`VDn`, or why a word that looks like an address is
/// none (`None`: not an address at all, so the line starts with a value).
fn address(word: &str) -> Option<Result<(u32, Width), &'static str>> {
    let b = word.as_bytes();
    if !b.first()?.is_ascii_alphabetic() {
        return None;
    }
    if !b[0].eq_ignore_ascii_case(&b'V') {
        return Some(Err("only V memory has initial values"));
    }
    let width = match b.get(1).map(u8::to_ascii_uppercase) {
        Some(b'B') => Width::Byte,
        Some(b'W') => Width::Word,
        Some(b'D') => Width::DWord,
        Some(c) if c.is_ascii_digit() => return Some(Err("give the width: VB, VW or VD")),
        _ => return Some(Err("expected VBn, VWn or VDn")),
    };
    let digits = &word[2..];
    if digits.is_empty() || !digits.bytes().all(|c| c.is_ascii_digit()) {
        return Some(Err("expected VBn, VWn or VDn"));
    }
    Some(
        digits
            .parse::<u32>()
            .map(|n| (n, width))
            .map_err(|_| "the address is too large"),
    )
}

/// The initial values of every data block line, in order, with their diagnostics.
pub(crate) fn lower(
    lines: &[DataLine<'_>],
    profile: &CpuProfile,
    encodings: &[Encoding],
    diags: &mut Vec<Diagnostic>,
) -> Vec<DataInit> {
    let v_size = profile.area_size(Area::V);
    let mut r = Reader {
        diags,
        v_size,
        set: vec![false; v_size as usize],
        next: None,
        out: Vec::new(),
    };
    let mut file = None;
    for line in lines {
        // Implicit addresses do not continue across files.
        if file != Some(line.file) {
            r.next = None;
            file = Some(line.file);
        }
        let enc = encodings
            .get(line.file.index())
            .copied()
            .unwrap_or_default();
        r.line(line, enc);
    }
    r.out
}

#[cfg(test)]
mod tests {
    use super::*;
    use stljit_core::ProfileId;

    fn run(text: &str) -> (Vec<DataInit>, Vec<Diagnostic>) {
        let lines: Vec<DataLine<'_>> = text
            .lines()
            .enumerate()
            .map(|(i, t)| DataLine {
                file: FileId(0),
                line: i as u32 + 1,
                text: t,
            })
            .collect();
        let mut diags = Vec::new();
        let out = lower(
            &lines,
            ProfileId::A5.profile(),
            &[Encoding::Utf8],
            &mut diags,
        );
        (out, diags)
    }

    fn bytes(out: &[DataInit]) -> Vec<(u32, Vec<u8>)> {
        out.iter().map(|d| (d.offset, d.bytes.clone())).collect()
    }

    #[test]
    fn values_widths_and_implicit_addresses() {
        let (out, d) = run("VB0    255, -1   // bytes\n\
             VW2    16#1234\n\
             \t+1000, 2#11\n\
             VD10   700.5\n\
             VB20   'AB', \"HI\"\n");
        assert!(d.is_empty(), "{d:?}");
        let real = 700.5f32.to_be_bytes().to_vec();
        assert_eq!(
            bytes(&out),
            [
                (0, vec![255, 255, 0x12, 0x34, 0x03, 0xE8, 0, 3]),
                (10, real),
                (20, vec![b'A', b'B', 2, b'H', b'I']),
            ]
        );
    }

    #[test]
    fn errors_and_overlap() {
        let (_, d) = run("1, 2\n");
        assert_eq!(d[0].code, Code::DataBlock);
        let (_, d) = run("MB0 1\n");
        assert_eq!(d[0].code, Code::DataBlock);
        let (_, d) = run("VB0 256\nVW2 1.5\nVW4 \"x\"\nVB2499 1, 2\nV0 1\n");
        let codes: Vec<_> = d.iter().map(|x| (x.code, x.line)).collect();
        assert_eq!(
            codes,
            [
                (Code::DataBlock, 1),
                (Code::DataBlock, 2),
                (Code::DataBlock, 3),
                (Code::DataBlock, 4),
                (Code::DataBlock, 5),
            ]
        );
        let (out, d) = run("VW0 1\nVB1 7\n");
        assert_eq!(d.len(), 1);
        assert_eq!(d[0].code, Code::DataOverlap);
        assert_eq!(
            bytes(&out),
            [(0, vec![0, 1]), (1, vec![7])],
            "no merge into earlier bytes"
        );
    }
}
