//! The reference interpreter: walks the IR one op at a time, keeping the logic stack as the
//! bit vector of spec §3.1, and calls the shared runtime ([`stljit_runtime`]) for everything
//! stateful or intricate (timers, counters, edges, pointers, flag rules, block instructions,
//! the interrupt machinery, which calls back into the interpreter to run a routine's body).
//!
//! It is written to be obviously correct rather than fast: every operand access is bounds-checked,
//! every scheduler field lives in the image (so the image after a scan is complete and comparable
//! with the JIT's), and a malformed program yields an error from [`Interpreter::new`] or a
//! recorded run-time error, never a panic.

mod boxes;
mod call;
mod exec;
mod omron;
mod operand;

#[cfg(test)]
mod tests;

use stljit_core::ScanStatus;
use stljit_core::ir::{Program, VerifyError, verify};
use stljit_runtime::rules::Rules;
use stljit_runtime::{Engine, Image, scan};

/// The interpreter for one program.
#[derive(Clone, Debug)]
pub struct Interpreter {
    program: Program,
    /// `(1 << logic_stack_depth) - 1`.
    stack_mask: u16,
    /// The semantic switches (`Rules::IN_FORCE` unless a test chose others).
    rules: Rules,
    /// What the scan prologue touches for this program.
    plan: scan::ScanPlan,
    /// Each timer number's resolution (`timer::declared_resolutions`).
    timer_res: Vec<Option<u8>>,
}

impl Interpreter {
    /// Verifies `program` ([`verify`]: every reference the interpreter follows exists) and keeps
    /// a copy of it.
    pub fn new(program: &Program) -> Result<Interpreter, VerifyError> {
        verify(program)?;
        Ok(Interpreter {
            program: program.clone(),
            stack_mask: ((1u32 << program.logic_stack_depth) - 1) as u16,
            rules: Rules::in_force(program.profile.profile().family),
            plan: scan::ScanPlan::of(program),
            timer_res: stljit_runtime::timer::declared_resolutions(program),
        })
    }

    /// The interpreter following `rules` instead of [`Rules::IN_FORCE`] (for tests that flip a
    /// rule switch on both engines).
    pub fn with_rules(mut self, rules: Rules) -> Interpreter {
        self.rules = rules;
        self
    }

    /// The program being interpreted.
    pub fn program(&self) -> &Program {
        &self.program
    }
}

impl Engine for Interpreter {
    fn name(&self) -> &'static str {
        "interp"
    }

    fn scan(&mut self, image: &mut Image, t_ms: u64) -> ScanStatus {
        let (img, layout) = image.split_mut();
        let this = &*self;
        let mut routines = exec::Routines(this);
        scan::run(
            img,
            layout,
            &this.plan,
            t_ms,
            &mut routines,
            |img, layout| {
                let mut m = exec::Machine::new(this, img, layout);
                m.run_main()
            },
        )
    }
}
