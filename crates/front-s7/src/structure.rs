//! Program structure: groups the lexed lines of every file into POUs. Two layouts are accepted
//! (spec §4.13): the linear one (main … MEND, `SBR n` … RET, `INT n` …) and MicroWIN's export
//! blocks (`ORGANIZATION_BLOCK`, `SUBROUTINE_BLOCK`, `INTERRUPT_BLOCK` with `TITLE=`, `VAR_…`
//! sections, `BEGIN` and `END_…_BLOCK`). The declarations of the `VAR_…` sections are read here
//! (`locals::parse_decl`) and kept with their POU; a linear `SBR n`/`INT n` may be followed by
//! such sections too [design].

use crate::lexer::{Line, Tok, lex_line};
use crate::locals::{Decl, Section, parse_decl};
use stljit_core::ir::PouKind;
use stljit_core::{CpuProfile, FileId};
use stljit_source::Code;
use stljit_source::{Diagnostic, Span, clip};

/// The source lines of one POU.
#[derive(Debug)]
pub(crate) struct PouSrc<'a> {
    /// Symbolic name (`MAIN`, `Motor_Logic`, `SBR0`).
    pub(crate) name: String,
    /// Main, subroutine or interrupt.
    pub(crate) kind: PouKind,
    /// The file holding it.
    pub(crate) file: FileId,
    /// Where it is declared (for duplicate messages).
    pub(crate) decl: Span,
    /// Its instruction lines.
    pub(crate) lines: Vec<Line<'a>>,
    /// Its local variable declarations (`VAR_…` sections), in textual order.
    pub(crate) decls: Vec<Decl>,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum BlockKind {
    Org,
    Sub,
    Int,
}

impl BlockKind {
    fn end_keyword(self) -> &'static str {
        match self {
            BlockKind::Org => "END_ORGANIZATION_BLOCK",
            BlockKind::Sub => "END_SUBROUTINE_BLOCK",
            BlockKind::Int => "END_INTERRUPT_BLOCK",
        }
    }
}

struct Builder<'a, 'd> {
    pous: Vec<PouSrc<'a>>,
    diags: &'d mut Vec<Diagnostic>,
    profile: &'static CpuProfile,
    names: Vec<&'a str>,
}

fn span(file: FileId, line: u32, t: Tok<'_>) -> Span {
    Span {
        file,
        line,
        col: t.col,
        len: t.len,
    }
}

fn is(t: &Tok<'_>, kw: &str) -> bool {
    t.text.eq_ignore_ascii_case(kw)
}

impl<'a> Builder<'a, '_> {
    fn error(&mut self, s: Span, text: &str, msg: String, help: Option<&str>) {
        let mut d = Diagnostic::new(Code::Structure, s, text, msg);
        d.help = help.map(str::to_owned);
        self.diags.push(d);
    }

    /// Adds a POU, reporting a second main program or a reused block number.
    fn add(&mut self, name: String, kind: PouKind, file: FileId, decl: Span, text: &str) -> usize {
        if let Some(prev) = self.pous.iter().find(|p| p.kind == kind) {
            let what = match kind {
                PouKind::Main => "the main program is defined twice".to_owned(),
                PouKind::Subroutine(n) => format!("subroutine SBR{n} is defined twice"),
                PouKind::Interrupt(n) => format!("interrupt routine INT{n} is defined twice"),
            };
            let help = if prev.decl.file == file {
                format!("first defined on line {}", prev.decl.line)
            } else {
                let name = self
                    .names
                    .get(prev.decl.file.index())
                    .copied()
                    .unwrap_or("?");
                format!("first defined on line {} of {name}", prev.decl.line)
            };
            self.error(decl, text, what, Some(&help));
        } else if let Some(prev) = self
            .pous
            .iter()
            .find(|p| p.name == name && kind != PouKind::Main)
        {
            let help = format!("first used at line {}", prev.decl.line);
            self.error(
                decl,
                text,
                format!("block name `{}` is used twice", clip(&name)),
                Some(&help),
            );
        }
        self.pous.push(PouSrc {
            name,
            kind,
            file,
            decl,
            lines: Vec::new(),
            decls: Vec::new(),
        });
        self.pous.len() - 1
    }

    /// The main program of linear text in `file` (added at `s` unless the file has one).
    fn main_for(&mut self, file: FileId, s: Span, text: &str) -> usize {
        match self.pous.iter().position(|p| p.kind == PouKind::Main) {
            Some(i) if self.pous[i].file == file => i,
            _ => self.add("MAIN".into(), PouKind::Main, file, s, text),
        }
    }

    /// Parses `Motor_Logic:SBR0` / `MAIN:OB1` / `SBR0` after a block keyword.
    fn block_header(&mut self, kind: BlockKind, line: &Line<'a>, file: FileId) -> usize {
        let rest = line.rest;
        let s = span(
            file,
            line.line,
            if rest.text.is_empty() {
                line.mnemonic
            } else {
                rest
            },
        );
        let (name, id) = match rest.text.rsplit_once(':') {
            Some((n, id)) => (n.trim(), id.trim()),
            None => (rest.text, rest.text),
        };
        let upper = id.to_ascii_uppercase();
        let (prefix, default) = match kind {
            BlockKind::Org => ("OB", "MAIN"),
            BlockKind::Sub => ("SBR", ""),
            BlockKind::Int => ("INT", ""),
        };
        let number = upper
            .strip_prefix(prefix)
            .and_then(|n| n.parse::<u16>().ok());
        let name = if name.is_empty() { default } else { name };
        let pou_kind = match (kind, number) {
            (BlockKind::Org, Some(1)) => Some(PouKind::Main),
            (BlockKind::Sub, Some(n)) if n <= self.profile.max_subroutine => {
                Some(PouKind::Subroutine(n))
            }
            (BlockKind::Int, Some(n)) if n <= 127 => Some(PouKind::Interrupt(n)),
            _ => None,
        };
        let pou_kind = pou_kind.unwrap_or_else(|| {
            let expected = match kind {
                BlockKind::Org => "NAME:OB1".to_owned(),
                BlockKind::Sub => format!("NAME:SBRn with n 0 .. {}", self.profile.max_subroutine),
                BlockKind::Int => "NAME:INTn with n 0 .. 127".to_owned(),
            };
            self.error(
                s,
                rest.text,
                format!("bad block header `{}`", clip(rest.text)),
                Some(&format!("expected {expected}")),
            );
            // Keep checking the body under a number nobody can call.
            match kind {
                BlockKind::Org => PouKind::Main,
                BlockKind::Sub => PouKind::Subroutine(u16::MAX),
                BlockKind::Int => PouKind::Interrupt(u16::MAX),
            }
        });
        let name = if name.is_empty() {
            match pou_kind {
                PouKind::Subroutine(n) => format!("SBR{n}"),
                PouKind::Interrupt(n) => format!("INT{n}"),
                PouKind::Main => "MAIN".to_owned(),
            }
        } else {
            name.to_owned()
        };
        self.add(name, pou_kind, file, s, rest.text)
    }

    /// `SBR n` / `INT n` in the linear layout.
    fn linear_marker(&mut self, sub: bool, line: &Line<'a>, file: FileId) -> usize {
        let t = line.ops[0];
        let s = span(
            file,
            line.line,
            if line.n_ops == 0 { line.mnemonic } else { t },
        );
        let max = if sub {
            self.profile.max_subroutine
        } else {
            127
        };
        let n = t
            .text
            .parse::<u16>()
            .ok()
            .filter(|&n| n <= max && line.n_ops == 1);
        let n = n.unwrap_or_else(|| {
            let what = if sub { "SBR" } else { "INT" };
            self.error(
                s,
                t.text,
                format!("`{what}` needs one number 0 .. {max}"),
                None,
            );
            u16::MAX
        });
        let (name, kind) = if sub {
            (format!("SBR{n}"), PouKind::Subroutine(n))
        } else {
            (format!("INT{n}"), PouKind::Interrupt(n))
        };
        self.add(name, kind, file, s, line.mnemonic.text)
    }
}

/// Groups every file's lines into POUs; the main program comes first (an empty one if no file
/// has main code).
pub(crate) fn structure<'a>(
    files: &[(FileId, &'a str, &'a str)],
    profile: &'static CpuProfile,
    diags: &mut Vec<Diagnostic>,
) -> Vec<PouSrc<'a>> {
    let mut b = Builder {
        pous: Vec::new(),
        diags,
        profile,
        names: files.iter().map(|f| f.2).collect(),
    };
    for &(file, text, _) in files {
        structure_file(&mut b, file, text);
    }
    let mut pous = b.pous;
    match pous.iter().position(|p| p.kind == PouKind::Main) {
        Some(0) => {}
        Some(i) => {
            let main = pous.remove(i);
            pous.insert(0, main);
        }
        None => pous.insert(
            0,
            PouSrc {
                name: "MAIN".into(),
                kind: PouKind::Main,
                file: files.first().map_or(FileId(0), |f| f.0),
                decl: Span::default(),
                lines: Vec::new(),
                decls: Vec::new(),
            },
        ),
    }
    pous
}

fn structure_file<'a>(b: &mut Builder<'a, '_>, file: FileId, text: &'a str) {
    // The open block and whether its BEGIN was seen; the linear POU lines go to.
    let mut block: Option<(BlockKind, usize, Span)> = None;
    // Inside a `DATA_BLOCK` (skipped, reported once at its header).
    let mut in_data = false;
    // The open `VAR_…` section: where it opened, its section and the POU it declares for.
    let mut in_var: Option<(Span, Section, usize)> = None;
    let mut linear: Option<usize> = None;
    let mut used_blocks = false;
    let mut warned_outside = false;
    for (i, raw) in text.split('\n').enumerate() {
        let number = u32::try_from(i + 1).unwrap_or(u32::MAX);
        let Some(line) = lex_line(raw, number) else {
            continue;
        };
        let m = line.mnemonic;
        let s = span(file, number, m);
        let upper_prefix = |p: &str| {
            m.text.len() >= p.len()
                && m.text.as_bytes()[..p.len()].eq_ignore_ascii_case(p.as_bytes())
        };
        if upper_prefix("NETWORK") && m.text[7..].bytes().all(|c| c.is_ascii_digit()) {
            continue;
        }
        if let Some((_, section, target)) = in_var {
            if is(&m, "END_VAR") {
                in_var = None;
            } else {
                match parse_decl(raw, number, file, section) {
                    Ok(Some(d)) => b.pous[target].decls.push(d),
                    Ok(None) => {}
                    Err(d) => b.diags.push(d),
                }
            }
            continue;
        }
        if upper_prefix("TITLE")
            && (m.text[5..].starts_with('=') || line.rest.text.starts_with('='))
        {
            continue;
        }
        if in_data {
            in_data = !is(&m, "END_DATA_BLOCK");
            continue;
        }
        if is(&m, "DATA_BLOCK") {
            // MicroWIN exports the data block (V-memory initial values) in the same file; they
            // are not loaded yet, which must not pass silently.
            b.diags.push(
                Diagnostic::new(
                    Code::Unsupported,
                    s,
                    m.text,
                    "`DATA_BLOCK` is not supported yet: its V-memory initial values would be lost",
                )
                .help("set the initial values in the first scan (LD SM0.1 / MOV…) meanwhile"),
            );
            used_blocks = true;
            in_data = true;
            continue;
        }
        let kind = [
            ("ORGANIZATION_BLOCK", BlockKind::Org),
            ("SUBROUTINE_BLOCK", BlockKind::Sub),
            ("INTERRUPT_BLOCK", BlockKind::Int),
        ]
        .into_iter()
        .find(|(kw, _)| is(&m, kw));
        if let Some((_, kind)) = kind {
            if let Some((open, _, at)) = block.take() {
                b.error(
                    s,
                    m.text,
                    format!("block opened at line {} is not closed", at.line),
                    Some(open.end_keyword()),
                );
            }
            used_blocks = true;
            let idx = b.block_header(kind, &line, file);
            block = Some((kind, idx, s));
            continue;
        }
        if let Some(end) = [BlockKind::Org, BlockKind::Sub, BlockKind::Int]
            .into_iter()
            .find(|k| is(&m, k.end_keyword()))
        {
            match block {
                Some((open, _, _)) if open == end => block = None,
                Some((open, _, _)) => {
                    b.error(
                        s,
                        m.text,
                        format!("`{}` closes a different kind of block", m.text),
                        Some(open.end_keyword()),
                    );
                    block = None;
                }
                None => b.error(
                    s,
                    m.text,
                    format!("`{}` without an open block", m.text),
                    None,
                ),
            }
            continue;
        }
        if is(&m, "BEGIN") {
            if block.is_none() {
                b.error(s, m.text, "BEGIN outside a block".into(), None);
            }
            continue;
        }
        if let Some(section) = Section::from_keyword(m.text) {
            // Declarations belong to the open block, or to the linear POU they follow; they
            // precede its first instruction (s7-200-more §1.1).
            let target = match (block, linear) {
                (Some((_, idx, _)), _) | (None, Some(idx)) => idx,
                (None, None) => b.main_for(file, s, m.text),
            };
            if !b.pous[target].lines.is_empty() {
                b.diags.push(
                    Diagnostic::new(
                        Code::LocalDecl,
                        s,
                        m.text,
                        format!("`{}` after the block's first instruction", m.text),
                    )
                    .help("local variable sections come between the block header and BEGIN"),
                );
            }
            if linear.is_none() && block.is_none() {
                linear = Some(target);
            }
            in_var = Some((s, section, target));
            continue;
        }
        if is(&m, "END_VAR") {
            b.error(s, m.text, "END_VAR without VAR_…".into(), None);
            continue;
        }
        let marker = if is(&m, "SBR") {
            Some(true)
        } else if is(&m, "INT") {
            Some(false)
        } else {
            None
        };
        if let Some(sub) = marker {
            if block.is_some() {
                b.error(
                    s,
                    m.text,
                    format!("`{}` marker inside a block", m.text),
                    Some("blocks end with END_…_BLOCK"),
                );
                continue;
            }
            linear = Some(b.linear_marker(sub, &line, file));
            continue;
        }
        let target = if let Some((_, idx, _)) = block {
            idx
        } else if let Some(idx) = linear {
            idx
        } else {
            if used_blocks && !warned_outside {
                warned_outside = true;
                b.error(
                    s,
                    m.text,
                    "instruction outside any block".into(),
                    Some("put it between BEGIN and END_…_BLOCK"),
                );
            }
            let idx = b.main_for(file, s, m.text);
            linear = Some(idx);
            idx
        };
        b.pous[target].lines.push(line);
    }
    if let Some((open, _, at)) = block {
        b.error(
            at,
            "",
            "block opened here is not closed before the end of the file".to_owned(),
            Some(open.end_keyword()),
        );
    }
    if let Some((at, _, _)) = in_var {
        b.error(at, "", "VAR section is not closed".into(), Some("END_VAR"));
    }
}
