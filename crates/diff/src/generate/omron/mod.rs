//! The generator of Omron CP programs: **source text** written from a small structured model
//! (rungs of conditions and outputs, regions, subroutines) and compiled by the Omron front end,
//! so every case also exercises the lexer, the circuit checks and the lowering, and the IR is
//! exactly what a user's program would give.
//!
//! Validity by construction: a condition leaves exactly one execution condition and no pending
//! block (E005–E009), at most 13 blocks are ever pending (E041), TR bits are stored once per
//! circuit before they are read (E010), options come from the mnemonic's entry in
//! `front_omron::mnemonics::TABLE` (E012), every timer and counter number is used once (E021),
//! IL/ILC, JMP/JME, JMP0/JME0 and FOR/NEXT are emitted as properly nested regions of one POU
//! (jumps go forward and never cross an IL or enter a FOR body: E022–E027), destinations are
//! writable and multi-word operands stay inside their area (E016, E018, E019), and the
//! subroutines stand before END. A program the front end rejects is a generator bug:
//! [`generate`] returns it as a [`GenError`] with the diagnostics, and campaigns report it.
//!
//! The parts: [`circuit`] (conditions, contacts, bit outputs, TR branches, multi-condition
//! instructions), [`data`] (timers, counters and the data instructions with their operands),
//! [`control`] (IL, jumps, FOR, subroutine calls); the stimulus is
//! [`super::stimulus::generate`], which knows the Omron I/O words.

mod circuit;
mod control;
mod data;

use super::{Case, GenConfig, stimulus};
use crate::rng::Choices;
use std::collections::BTreeSet;
use std::fmt::Write as _;
use stljit_core::{CpuProfile, ProfileId};
use stljit_front_omron::mnemonics::{Group, Mnemonic, TABLE};

/// A generated Omron case: the compiled case and the text it was compiled from.
#[derive(Clone, Debug, PartialEq)]
pub struct OmronCase {
    /// The program (compiled from `source`) and its stimulus.
    pub case: Case,
    /// The generated Omron source text.
    pub source: String,
}

/// The Omron front end rejected a generated program: a generator bug.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GenError {
    /// The generated text.
    pub source: String,
    /// The profile it was compiled for.
    pub profile: ProfileId,
    /// The error diagnostics, rendered.
    pub diagnostics: String,
}

impl std::fmt::Display for GenError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the Omron front end rejects a generated program ({}):\n{}",
            self.profile.name(),
            self.diagnostics
        )
    }
}

impl std::error::Error for GenError {}

/// Generates an Omron case from any choice stream: the text, its compilation, the stimulus.
pub fn generate(c: &mut Choices<'_>, cfg: &GenConfig) -> Result<OmronCase, GenError> {
    let profile = match cfg.profile {
        Some(p) if p.profile().family == stljit_core::Family::Omron => p,
        // The CP1H is the reference model; the CP1E has the smaller areas (and D bits).
        _ => [ProfileId::Cp1h, ProfileId::Cp1e][c.weighted(&[4, 1])],
    };
    let source = generate_source(c, cfg, profile);
    let compiled =
        std::panic::catch_unwind(|| stljit_front_omron::compile_str("fuzz.omr", &source, profile));
    let Ok(compiled) = compiled else {
        return Err(GenError {
            source,
            profile,
            diagnostics: "the front end panicked".into(),
        });
    };
    let Some(program) = compiled.program else {
        let diagnostics = compiled
            .diagnostics
            .iter()
            .filter(|d| d.severity == stljit_front_omron::Severity::Error)
            .map(|d| stljit_front_omron::render_human(d, &compiled.sources))
            .collect::<Vec<_>>()
            .join("");
        return Err(GenError {
            source,
            profile,
            diagnostics,
        });
    };
    let stimulus = stimulus::generate(c, profile, cfg.scans);
    Ok(OmronCase {
        case: Case { program, stimulus },
        source,
    })
}

/// Generates the text of one Omron program for `profile`.
pub fn generate_source(c: &mut Choices<'_>, cfg: &GenConfig, profile: ProfileId) -> String {
    let mut g = OmronGen::new(c, cfg, profile);
    g.program();
    g.out
}

/// Where the rung being generated sits: what may appear there.
#[derive(Clone, Debug, Default)]
pub(crate) struct Ctx {
    /// Inside an IL–ILC region.
    pub(crate) in_il: bool,
    /// Inside a JMP0–JME0 region (no nested JMP0 region: its JME0 would close both).
    pub(crate) in_jmp0: bool,
    /// FOR nesting depth.
    pub(crate) for_depth: u8,
    /// Nesting depth of regions (bounds the generator's recursion).
    pub(crate) depth: u8,
    /// Jump numbers whose JME follows the innermost FOR's NEXT at this IL level: a jump to
    /// one leaves the loop.
    pub(crate) loop_exits: Vec<u32>,
}

/// Generator state for one program.
pub(crate) struct OmronGen<'c, 'a> {
    pub(crate) c: &'c mut Choices<'a>,
    pub(crate) cfg: GenConfig,
    pub(crate) p: &'static CpuProfile,
    /// The text so far.
    pub(crate) out: String,
    /// Instruction lines so far (the size bound).
    pub(crate) lines: usize,
    /// Line bound of the POU being written.
    pub(crate) limit: usize,
    pub(crate) timers: BTreeSet<u32>,
    pub(crate) counters: BTreeSet<u32>,
    /// Jump numbers used in the current POU.
    pub(crate) jumps: BTreeSet<u32>,
    /// The subroutine numbers, in the order their SBN regions are written.
    pub(crate) subs: Vec<u32>,
    /// Index in `subs` of the subroutine being written (`None`: the main program).
    pub(crate) current_sub: Option<usize>,
    /// Whether calls may go anywhere (recursion ends at the nesting limit).
    pub(crate) recursion: bool,
    /// TR bits stored in the current circuit.
    pub(crate) trs: u16,
    /// Coils written so far (mostly avoided again: W020 is a warning, realistic programs have
    /// few).
    pub(crate) coils: BTreeSet<String>,
}

impl<'c, 'a> OmronGen<'c, 'a> {
    fn new(c: &'c mut Choices<'a>, cfg: &GenConfig, profile: ProfileId) -> OmronGen<'c, 'a> {
        OmronGen {
            c,
            cfg: cfg.clone(),
            p: profile.profile(),
            out: String::new(),
            lines: 0,
            limit: cfg.max_ops_per_pou,
            timers: BTreeSet::new(),
            counters: BTreeSet::new(),
            jumps: BTreeSet::new(),
            subs: Vec::new(),
            current_sub: None,
            recursion: false,
            trs: 0,
            coils: BTreeSet::new(),
        }
    }

    /// Whether the POU being written has room for more.
    pub(crate) fn room(&self) -> bool {
        self.lines < self.limit
    }

    /// The table entry of `group`.
    pub(crate) fn entry(group: Group) -> Option<&'static Mnemonic> {
        TABLE.iter().find(|m| m.group == group)
    }

    /// Writes one instruction: `options` + the mnemonic (with its function code, mostly) and
    /// the operands, with varied spacing, case and comments as people write them.
    pub(crate) fn ins(
        &mut self,
        options: &str,
        name: &str,
        code: Option<u16>,
        operands: &[String],
    ) {
        self.lines += 1;
        let mut head = format!("{options}{name}");
        if let Some(code) = code {
            match self.c.weighted(&[6, 2, 1]) {
                0 => {
                    let _ = write!(head, "({code:03})");
                }
                1 => {}
                _ => {
                    let _ = write!(head, " ({code:03})");
                }
            }
        }
        let sep = ["\t", " ", "    ", "\t\t"][self.c.weighted(&[4, 3, 2, 1])];
        let mut text = if operands.is_empty() {
            head
        } else {
            format!(
                "{head}{sep}{}",
                operands.join(if self.c.chance(1, 8) { "\t" } else { " " })
            )
        };
        if self.c.chance(1, 40) {
            text = text.to_ascii_lowercase();
        }
        self.out.push_str(&text);
        match self.c.weighted(&[30, 1, 1]) {
            0 => {}
            1 => self.out.push_str("\t; comment"),
            _ => self.out.push_str(" // 注释"),
        }
        self.out.push('\n');
        if self.c.chance(1, 60) {
            self.out
                .push_str(["\n", "; ----\n", "   \n"][self.c.below(3) as usize]);
        }
    }

    /// Writes the instruction of `group` (its table name and code).
    pub(crate) fn op(&mut self, options: &str, group: Group, operands: &[String]) {
        if let Some(m) = Self::entry(group) {
            self.ins(options, m.name, m.code, operands);
        }
    }

    /// Options for the instruction of `group` ([`OmronGen::options_of`]).
    pub(crate) fn options(&mut self, group: Group) -> String {
        match Self::entry(group) {
            Some(m) => self.options_of(m),
            None => String::new(),
        }
    }

    fn program(&mut self) {
        self.recursion = self.c.chance(1, 12);
        let n_subs = self.c.below(self.cfg.max_subroutines + 1);
        let max_sub = u32::from(self.p.max_subroutine);
        for k in 0..n_subs {
            // An exhausted byte stream picks 0 every time: fall back to the next free number.
            let n = if self.c.chance(1, 10) {
                max_sub - self.c.below(3)
            } else {
                self.c.below(16)
            };
            let n = if self.subs.contains(&n) { 16 + k } else { n };
            self.subs.push(n);
        }
        if self.c.chance(1, 2) {
            self.setup();
        }
        let long = self.c.chance(1, 25);
        let rungs = if long {
            self.limit = 4 * self.cfg.max_ops_per_pou;
            4 * self.cfg.max_networks
        } else {
            self.c.range(1, self.cfg.max_networks)
        };
        for _ in 0..rungs {
            if !self.room() {
                break;
            }
            self.rung(&Ctx::default());
        }
        for i in 0..self.subs.len() {
            self.current_sub = Some(i);
            self.jumps.clear();
            self.lines = 0;
            self.limit = self.cfg.max_ops_per_pou / 2;
            let n = self.subs[i].to_string();
            self.op(
                "",
                Group::Control(stljit_front_omron::mnemonics::Flow::Sbn),
                &[n],
            );
            for _ in 0..self.c.range(0, 4) {
                self.rung(&Ctx::default());
            }
            self.op(
                "",
                Group::Control(stljit_front_omron::mnemonics::Flow::Ret),
                &[],
            );
            if self.c.chance(1, 30) {
                // Never runs (W028): code between the subroutine region and END.
                self.out.push_str("LD 0.00\nOUT W511.15\n");
            }
        }
        self.op(
            "",
            Group::Control(stljit_front_omron::mnemonics::Flow::End),
            &[],
        );
        if self.c.chance(1, 20) {
            // Never runs (W002): lines after the first END, a second END among them.
            self.out.push_str("LD 0.01\nOUT 100.00\nEND(001)\n");
        }
    }

    /// One rung, or one region of rungs, of any kind allowed in `ctx`.
    pub(crate) fn rung(&mut self, ctx: &Ctx) {
        self.trs = 0;
        let structured = ctx.depth < 3;
        let in_loop = ctx.for_depth > 0;
        let weights = [
            30,                                             // contacts and coils
            8,                                              // timer
            6,                                              // counter
            4,                                              // KEEP
            3,                                              // DIFU/DIFD
            14,                                             // data
            2,                                              // PV rewrite
            if structured && !ctx.in_il { 4 } else { 1 },   // IL region
            if structured { 4 } else { 0 },                 // jump region
            if structured && !ctx.in_jmp0 { 2 } else { 0 }, // JMP0 region
            if structured && ctx.for_depth < 3 {
                3
            } else {
                0
            }, // FOR
            if self.has_callee() { 4 } else { 0 },          // SBS
            2,                                              // CCS/CCL, IORF
            2,                                              // deep blocks
            if in_loop { 3 } else { 0 },                    // BREAK / leave the loop
        ];
        match self.c.weighted(&weights) {
            0 => self.logic_rung(),
            1 => self.timer_rung(),
            2 => self.counter_rung(),
            3 => self.keep_rung(),
            4 => self.differentiate_rung(),
            5 => self.data_rung(),
            6 => self.pv_rewrite(),
            7 => self.interlock(ctx),
            8 => self.jump_region(ctx),
            9 => self.jmp0_region(ctx),
            10 => self.for_loop(ctx),
            11 => self.call_rung(),
            12 => self.misc_rung(),
            13 => self.deep_rung(),
            _ => self.leave_loop(ctx),
        }
    }
}

#[cfg(test)]
mod tests;
