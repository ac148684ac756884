//! The generator of Omron CP programs: **source text** written from a small structured model
//! (rungs of conditions and outputs, regions, subroutines) and compiled by the Omron front end,
//! so every case also exercises the lexer, the circuit checks and the lowering, and the IR is
//! exactly what a user's program would give.
//!
//! Validity by construction: a condition leaves exactly one execution condition and no pending
//! block (E005–E009), at most 13 blocks are ever pending (E041), TR bits are stored once per
//! circuit before they are read (E010), options come from the mnemonic's entry in
//! `front_omron::mnemonics::TABLE` (E012), every timer and counter number is used once (E021),
//! IL/ILC, JMP/JME, JMP0/JME0, FOR/NEXT, step areas and block programs are emitted as properly
//! nested regions of one POU (jumps never cross an IL or a block program or enter a FOR body,
//! backward only with the option: E022–E027), a step area or a block program holds only what
//! its region allows (E026, E029), destinations are writable and multi-word operands stay
//! inside their area (E016, E018, E019), the subroutines stand before END, and every unit's
//! pairs, calls and step bits stay in that unit (E025). A program the front end rejects is a
//! generator bug: [`generate`] returns it as a [`GenError`] with the diagnostics, and campaigns
//! report it.
//!
//! The parts: [`units`] (the program's options, its `$TASK`/`$FB` units and each unit's
//! program), [`circuit`] (conditions, contacts, bit outputs, TR branches, multi-condition
//! instructions), [`data`] (timers, counters and the data instructions with their operands),
//! [`control`] (IL, jumps, FOR, subroutine calls), [`regions`] (step areas, block programs,
//! backward jumps); the stimulus is [`super::stimulus::generate`], which knows the Omron I/O
//! words.

mod circuit;
mod control;
mod data;
mod regions;
mod units;

use super::{Case, GenConfig, stimulus};
use crate::rng::Choices;
use std::collections::BTreeSet;
use std::fmt::Write as _;
use stljit_core::{CpuProfile, ProfileId};
use stljit_front_omron::Options;
use stljit_front_omron::mnemonics::{Group, Mnemonic, TABLE};

/// A generated Omron case: the compiled case and the text it was compiled from.
#[derive(Clone, Debug, PartialEq)]
pub struct OmronCase {
    /// The program (compiled from `source`) and its stimulus.
    pub case: Case,
    /// The generated Omron source text.
    pub source: String,
    /// The front-end options it was compiled with (the binary timer mode, backward jumps).
    pub options: Options,
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
    let (source, options) = generate_source(c, cfg, profile);
    let compiled = std::panic::catch_unwind(|| {
        let file = stljit_front_omron::SourceFile::from_text("fuzz.omr", &source);
        stljit_front_omron::compile_with(&[file], None, profile, options)
    });
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
        options,
    })
}

/// Generates the text of one Omron program for `profile` and the front-end options it is
/// compiled with (named in its first line when they are not the default).
pub fn generate_source(
    c: &mut Choices<'_>,
    cfg: &GenConfig,
    profile: ProfileId,
) -> (String, Options) {
    let mut g = OmronGen::new(c, cfg, profile);
    g.program();
    (g.out, g.options)
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
    /// Inside a step area (no jumps, IL, FOR or another step area there).
    pub(crate) in_step: bool,
    /// Inside a block program (its restrictions are [`OmronGen::block`]'s).
    pub(crate) in_block: bool,
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
    /// The front-end options the program is compiled with.
    pub(crate) options: Options,
    /// Subroutine numbers of the whole project (each unit has its own subroutines).
    pub(crate) all_subs: BTreeSet<u32>,
    /// Writing a block program: no `@`/`%`, no UP/DOWN, no OUT/KEEP/DIFU/DIFD, no timers.
    pub(crate) block: bool,
    /// Writing a function block: no `!`.
    pub(crate) plain: bool,
    /// Block program numbers used in the current unit.
    pub(crate) blocks: BTreeSet<u32>,
    /// Step bits used so far (each in one unit: a SNXT and its STEP must be in one task).
    pub(crate) step_bits: u32,
    /// Words D200… used as counters of backward-jump loops.
    pub(crate) loop_words: u32,
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
            options: Options::default(),
            all_subs: BTreeSet::new(),
            block: false,
            plain: false,
            blocks: BTreeSet::new(),
            step_bits: 0,
            loop_words: 0,
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

    /// One rung, or one region of rungs, of any kind allowed in `ctx`.
    pub(crate) fn rung(&mut self, ctx: &Ctx) {
        self.trs = 0;
        let structured = ctx.depth < 3;
        let (step, block) = (ctx.in_step, ctx.in_block);
        // Regions a step area (NOT_IN_STEPS) or a block program (NOT_IN_BLOCKS) holds none of.
        let free = !step && !block;
        let on = |b: bool, w: u32| if b { w } else { 0 };
        // Step areas are only in a task's body (not in subroutines); IL around one is the
        // case the front end's gate saving is for.
        let main_body = self.current_sub.is_none();
        let step_area = if ctx.in_il { 4 } else { 2 };
        let backward = self.options.allow_backward_jumps;
        let weights = [
            30,                                                     // contacts and coils
            on(!block, 8),                                          // timer
            6,                                                      // counter
            on(!block, 4),                                          // KEEP
            on(!block, 3),                                          // DIFU/DIFD
            14,                                                     // data
            2,                                                      // PV rewrite
            on(free, if structured && !ctx.in_il { 4 } else { 1 }), // IL region
            on(structured && !step, 4),                             // jump region
            on(structured && free && !ctx.in_jmp0, 2),              // JMP0 region
            on(structured && free && ctx.for_depth < 3, 3),         // FOR
            on(self.has_callee(), 4),                               // SBS
            2,                                                      // CCS/CCL, IORF
            2,                                                      // deep blocks
            on(free && ctx.for_depth > 0, 3),                       // BREAK / leave the loop
            on(structured && free && main_body, step_area),         // step area
            on(structured && !block, 2),                            // block program
            on(structured && !step && backward, 4),                 // backward jump
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
            14 => self.leave_loop(ctx),
            15 => self.step_area(ctx),
            16 => self.block_program(ctx),
            _ => self.backward_jump(ctx),
        }
    }
}

#[cfg(test)]
mod tests;
