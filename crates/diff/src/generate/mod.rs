//! The generator of valid random programs and stimulus.
//!
//! Programs are built directly as IR, valid by construction for the chosen profile: direct operands
//! fit their areas, read-only areas are never written, each timer and counter number keeps one
//! kind, labels, FOR/NEXT and SCR segments are properly structured, and calls form a DAG. The shape
//! follows real ladder networks (a boolean expression on the logic stack, then coils and boxes),
//! with deliberate corner cases mixed in: stacks deeper than nine levels, call chains deeper than
//! eight, pointers stepped past their area, loops left to the watchdog.
//!
//! The parts: [`operands`] picks operands per operand class, [`programs`] builds networks and
//! POUs, [`params`] gives subroutines parameters and calls them with actuals, [`interrupts`] the
//! interrupt routines and instructions, [`hsc`] the high-speed counters, [`ext`] the table,
//! text, string, clock and PID instructions of s7-200-more §4–§7 (their memory in
//! [`ext_data`]), [`stimulus`] builds the per-scan inputs and scan times. Omron programs are
//! generated as mnemonic text instead, by [`omron`] (its module says why).

pub mod boxes;
pub mod comm;
pub mod control;
pub mod ext;
pub mod ext_data;
pub mod hsc;
pub mod interrupts;
pub mod omron;
pub mod operands;
pub mod params;
pub mod programs;
pub mod pulse;
pub mod stimulus;

use crate::rng::Choices;
use std::collections::BTreeMap;
use stljit_core::ir::{
    BitLoc, CounterDecl, CounterKind, EdgeDecl, Op, Pou, PouKind, Program, SrcLoc, TimerDecl,
    TimerKind,
};
use stljit_core::{CounterId, CpuProfile, Family, LabelId, OpIdx, PouId, ProfileId, TimerId};

pub use stimulus::{HmiWrite, Received, ScanInput, Stimulus};

/// Knobs of the generator. The defaults aim at many small, realistic programs per second.
#[derive(Clone, Debug)]
pub struct GenConfig {
    /// The profile, or `None` to pick one per program (a profile of the other dialect than
    /// the one generated is ignored).
    pub profile: Option<ProfileId>,
    /// Upper bound on networks in the main program (the actual count is random below it).
    pub max_networks: u32,
    /// Upper bound on ordinary subroutines (a deep call chain may add more).
    pub max_subroutines: u32,
    /// Upper bound on ops per POU (Omron: instruction lines); generation stops adding
    /// networks past it.
    pub max_ops_per_pou: usize,
    /// Number of scans of the stimulus.
    pub scans: u32,
    /// S7: a program without pointers, block moves, fills, shift registers, call parameters,
    /// string compares and the ops of tables, text, clock, PID, high-speed counters, pulse
    /// outputs and communication, so that the compiled engine keeps its M and V bits resident
    /// (`stljit_jit`'s resident bits): campaigns make every fourth S7 program plain.
    pub plain: bool,
}

impl Default for GenConfig {
    fn default() -> GenConfig {
        GenConfig {
            profile: None,
            max_networks: 10,
            max_subroutines: 3,
            max_ops_per_pou: 160,
            scans: 50,
            plain: false,
        }
    }
}

/// A generated test case: a program and the stimulus to drive it with.
#[derive(Clone, Debug, PartialEq)]
pub struct Case {
    /// The program, valid for its profile.
    pub program: Program,
    /// Inputs and time of every scan.
    pub stimulus: Stimulus,
}

/// Generates a case from a seed.
pub fn case_from_seed(seed: u64, cfg: &GenConfig) -> Case {
    let mut c = Choices::from_seed(seed);
    generate_case(&mut c, cfg)
}

/// Generates a case from fuzzer bytes.
pub fn case_from_bytes(data: &[u8], cfg: &GenConfig) -> Case {
    let mut c = Choices::from_bytes(data);
    generate_case(&mut c, cfg)
}

/// A generated case with the source text it was compiled from (Omron), for coverage.
#[derive(Clone, Debug, PartialEq)]
pub struct Generated {
    /// The program and its stimulus.
    pub case: Case,
    /// The generated source text (`None` for S7 programs, which are built as IR).
    pub source: Option<String>,
    /// The Omron front-end options `source` compiles with (the default for S7 programs).
    pub options: stljit_front_omron::Options,
}

/// Generates a case of the dialect `family` (S7 programs as IR, Omron programs as text
/// compiled by the Omron front end, whose rejection is the error).
pub fn generate_in(
    family: Family,
    c: &mut Choices<'_>,
    cfg: &GenConfig,
) -> Result<Generated, omron::GenError> {
    match family {
        Family::S7 => Ok(Generated {
            case: generate_case(c, cfg),
            source: None,
            options: Default::default(),
        }),
        Family::Omron => omron::generate(c, cfg).map(|g| Generated {
            case: g.case,
            source: Some(g.source),
            options: g.options,
        }),
    }
}

/// Generates a case from any choice stream.
pub fn generate_case(c: &mut Choices<'_>, cfg: &GenConfig) -> Case {
    let program = generate_program(c, cfg);
    let stimulus = stimulus::for_program(c, &program, cfg.scans);
    Case { program, stimulus }
}

/// Generates a program from any choice stream.
pub fn generate_program(c: &mut Choices<'_>, cfg: &GenConfig) -> Program {
    let profile = match cfg.profile {
        Some(p) if p.profile().family == Family::S7 => p,
        // The A5 is the product; the S7-200 table exercises the kind-by-number timer rules, the
        // SMART its larger areas.
        _ => [ProfileId::A5, ProfileId::S7_200, ProfileId::Smart][c.weighted(&[4, 1, 1])],
    };
    let mut g = Gen::new(c, cfg, profile);
    g.program()
}

/// Where the op being emitted sits, for the structural rules (no WDR inside a loop, no jump or
/// FOR inside an SCR segment, FOR nesting limit).
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Ctx {
    /// Inside a backward-jump loop or a FOR body.
    pub(crate) in_loop: bool,
    /// FOR nesting depth.
    pub(crate) for_depth: u8,
    /// The S bit of the enclosing SCR segment.
    pub(crate) scr: Option<BitLoc>,
    /// Nesting depth of structured blocks (bounds recursion of the generator itself).
    pub(crate) depth: u8,
}

/// Generator state for one program.
pub(crate) struct Gen<'c, 'a> {
    pub(crate) c: &'c mut Choices<'a>,
    pub(crate) cfg: GenConfig,
    pub(crate) p: &'static CpuProfile,
    pub(crate) timers: BTreeMap<u16, TimerKind>,
    pub(crate) counters: BTreeMap<u16, CounterKind>,
    pub(crate) edges: u16,
    /// The POU being built.
    pub(crate) pou: PouId,
    pub(crate) ops: Vec<Op>,
    pub(crate) labels: Vec<Option<OpIdx>>,
    /// Total number of POUs (main + subroutines) in the program.
    pub(crate) n_pous: u32,
    /// Whether the program may contain a loop without an exit (then it ends in the watchdog).
    pub(crate) allow_endless: bool,
    /// Whether calls may go to any subroutine, including the caller (recursion ends in 0x0008).
    pub(crate) recursion: bool,
    /// Whether unstructured jumps (into and out of FOR bodies, crossing other jumps) appear; such
    /// programs have no WDR, so every loop they make still ends in the watchdog.
    pub(crate) wild_jumps: bool,
    /// Op limit of the POU being built (raised for the occasional very long main program).
    pub(crate) room_limit: usize,
    /// The POU being built is an interrupt routine (no END or WDR there).
    pub(crate) in_interrupt: bool,
    /// The program's interrupt routines, `(POU, number)`.
    pub(crate) int_routines: Vec<(PouId, u16)>,
    /// The high-speed counters the program defines.
    pub(crate) hsc_counters: Vec<u8>,
    /// The pulse output channels the program drives.
    pub(crate) pulse_channels: Vec<u8>,
    /// The program communicates (s7-200-more §10).
    pub(crate) comm: bool,
    /// Wild-jump labels of the current POU not yet placed.
    pub(crate) pending_wild: Vec<LabelId>,
    /// Wild-jump labels of the current POU already placed (targets of backward jumps).
    pub(crate) placed_wild: Vec<LabelId>,
    /// Each POU's parameters (empty for the main program and most subroutines), by POU index.
    pub(crate) params: Vec<Vec<params::Param>>,
    /// PID loop numbers already used (bit n: loop n); a loop number belongs to one PID.
    pub(crate) pid_loops: u8,
    /// Initial V bytes, the program's data block.
    pub(crate) data: BTreeMap<u32, u8>,
}

impl<'c, 'a> Gen<'c, 'a> {
    fn new(c: &'c mut Choices<'a>, cfg: &GenConfig, profile: ProfileId) -> Gen<'c, 'a> {
        Gen {
            c,
            cfg: cfg.clone(),
            p: profile.profile(),
            timers: BTreeMap::new(),
            counters: BTreeMap::new(),
            edges: 0,
            pou: PouId(0),
            ops: Vec::new(),
            labels: Vec::new(),
            n_pous: 1,
            allow_endless: false,
            recursion: false,
            wild_jumps: false,
            room_limit: cfg.max_ops_per_pou,
            in_interrupt: false,
            int_routines: Vec::new(),
            hsc_counters: Vec::new(),
            pulse_channels: Vec::new(),
            comm: false,
            pending_wild: Vec::new(),
            placed_wild: Vec::new(),
            params: Vec::new(),
            pid_loops: 0,
            data: BTreeMap::new(),
        }
    }

    /// Appends an op and returns its index.
    pub(crate) fn emit(&mut self, op: Op) -> OpIdx {
        self.ops.push(op);
        OpIdx::new(self.ops.len() - 1)
    }

    /// A fresh label of the current POU, not yet placed; `None` when the POU has used every
    /// label number the profile allows.
    pub(crate) fn new_label(&mut self) -> Option<LabelId> {
        if self.labels.len() > usize::from(self.p.max_label) {
            return None;
        }
        self.labels.push(None);
        Some(LabelId::new(self.labels.len() - 1))
    }

    /// Emits the label op.
    pub(crate) fn place_label(&mut self, l: LabelId) {
        let at = self.emit(Op::Label(l));
        self.labels[l.index()] = Some(at);
    }

    /// Whether the current POU has room for more ops.
    pub(crate) fn room(&self) -> bool {
        self.ops.len() < self.room_limit
    }

    /// A new edge slot, or `None` when the profile's limit is reached.
    pub(crate) fn edge_slot(&mut self) -> Option<stljit_core::EdgeSlot> {
        if self.edges >= self.p.max_edges {
            return None;
        }
        self.edges += 1;
        Some(stljit_core::EdgeSlot(self.edges - 1))
    }

    /// Finishes the POU being built.
    fn take_pou(&mut self, name: String, kind: PouKind) -> Pou {
        for l in std::mem::take(&mut self.pending_wild) {
            self.place_label(l);
        }
        self.placed_wild.clear();
        self.room_limit = self.cfg.max_ops_per_pou;
        let ops = std::mem::take(&mut self.ops);
        // Every label was placed when its construct closed; a missing one would be a generator
        // bug, so fall back to op 0 rather than panic (the front-end check would then flag it).
        let labels = std::mem::take(&mut self.labels)
            .into_iter()
            .map(|l| l.unwrap_or(OpIdx(0)))
            .collect();
        Pou {
            name,
            kind,
            locs: vec![SrcLoc::default(); ops.len()],
            ops,
            labels,
        }
    }

    fn program(&mut self) -> Program {
        self.allow_endless = self.c.chance(1, 40);
        self.recursion = self.c.chance(1, 10);
        self.wild_jumps = self.c.chance(1, 12);
        let plan = self.plan_subroutines();
        self.n_pous = 1 + plan.len() as u32;
        self.params = std::iter::once(Vec::new())
            .chain(plan.iter().map(|_| Vec::new()))
            .collect();
        for i in 1..self.params.len() {
            self.params[i] = self.signature();
        }
        self.int_routines = self.plan_interrupts(1 + plan.len());
        self.hsc_counters = self.plan_hsc();
        self.pulse_channels = self.plan_pulse();
        self.comm = self.plan_comm();
        if self.cfg.plain {
            self.params.iter_mut().for_each(Vec::clear);
            self.hsc_counters.clear();
            self.pulse_channels.clear();
            self.comm = false;
        }
        let mut pous = Vec::with_capacity(self.n_pous as usize);
        self.pou = Program::MAIN;
        self.main_body(&plan);
        pous.push(self.take_pou("MAIN".into(), PouKind::Main));
        for (i, sub) in plan.iter().enumerate() {
            self.pou = PouId::new(i + 1);
            self.sub_body(sub);
            pous.push(self.take_pou(format!("SBR{i}"), PouKind::Subroutine(i as u16)));
        }
        // The interrupt routines: after the subroutines, not counted in `n_pous`, so no CALL
        // names one; they may call the subroutines.
        for (id, n) in self.int_routines.clone() {
            self.pou = id;
            self.in_interrupt = true;
            let networks = self.c.range(1, 3);
            self.sub_body(&SubPlan {
                chain_next: None,
                networks,
            });
            pous.push(self.take_pou(format!("INT{n}"), PouKind::Interrupt(n)));
            self.in_interrupt = false;
        }
        let mut program = Program {
            profile: self.p.id,
            pous,
            timers: self
                .timers
                .iter()
                .map(|(&n, &kind)| TimerDecl {
                    id: TimerId(n),
                    kind,
                    resolution: self
                        .p
                        .timer_resolution(n, kind)
                        .unwrap_or(stljit_core::profile::Resolution::Ms100),
                })
                .collect(),
            counters: self
                .counters
                .iter()
                .map(|(&n, &kind)| CounterDecl {
                    id: CounterId(n),
                    kind,
                })
                .collect(),
            edges: vec![EdgeDecl { init: false }; usize::from(self.edges)],
            logic_stack_depth: 9,
            files: vec!["fuzz.stl".into()],
            data: ext_data::data_runs(&self.data),
        };
        crate::canon::canonicalize(&mut program);
        program
    }
}

/// What a subroutine is for, decided before any code is generated so that callers know their
/// callees.
#[derive(Clone, Debug)]
pub(crate) struct SubPlan {
    /// Part of a chain deeper than the call-nesting limit: calls the next subroutine first thing.
    pub(crate) chain_next: Option<PouId>,
    /// Number of networks.
    pub(crate) networks: u32,
}

impl Gen<'_, '_> {
    fn plan_subroutines(&mut self) -> Vec<SubPlan> {
        let mut plan = Vec::new();
        let n = self.c.below(self.cfg.max_subroutines + 1);
        for _ in 0..n {
            let networks = self.c.range(1, 6);
            plan.push(SubPlan {
                chain_next: None,
                networks,
            });
        }
        // A chain one to four levels past the nesting limit, so that the deepest calls fail with
        // 0x0008 in both engines.
        if self.c.chance(1, 12) {
            let len = u32::from(self.p.max_call_depth) + self.c.range(1, 4);
            let first = plan.len();
            for k in 0..len {
                let next = (k + 1 < len).then(|| PouId::new(first + k as usize + 2));
                plan.push(SubPlan {
                    chain_next: next,
                    networks: self.c.range(0, 2),
                });
            }
        }
        let max = usize::from(self.p.max_subroutine) + 1;
        plan.truncate(max);
        let len = plan.len();
        if let Some(last) = plan.last_mut()
            && last.chain_next.is_some_and(|p| p.index() > len)
        {
            last.chain_next = None;
        }
        plan
    }
}

#[cfg(test)]
mod tests;
