//! The program as a whole: its front-end options (the binary timer mode 1 program in 8,
//! backward jumps allowed 1 in 6) and its units. Most programs are one task without
//! directives; 1 in 4 on a model with several cyclic tasks runs two to four `$TASK CYCLIC n`
//! tasks, written in an order unlike their run order (ascending number), whose first rung now
//! and then reads a condition flag the task start has cleared; now and then a standby task, an
//! unassigned program or a `$FB` body (checked, never run, their edge memories still numbered)
//! stands among them. Each unit has its own subroutines (numbers unique in the project), jump
//! and block numbers, and END.

use super::{Ctx, OmronGen};
use stljit_front_omron::mnemonics::{Flow, Group, Join};
use stljit_front_omron::{Options, TcMode};

/// One unit of the generated project.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Unit {
    /// Cyclic task `number`, started at RUN or in standby.
    Cyclic { number: u32, started: bool },
    /// `$TASK UNASSIGNED`.
    Unassigned,
    /// `$FB name`.
    FunctionBlock,
}

impl OmronGen<'_, '_> {
    /// The whole program: options, then every unit.
    pub(super) fn program(&mut self) {
        self.options = Options {
            tc_mode: if self.c.chance(1, 8) {
                TcMode::Binary
            } else {
                TcMode::Bcd
            },
            allow_backward_jumps: self.c.chance(1, 6),
        };
        if self.options != Options::default() {
            self.out.push_str(&format!(
                "; compiled with tc_mode = {}, allow_backward_jumps = {}\n",
                self.options.tc_mode.name(),
                self.options.allow_backward_jumps
            ));
        }
        let units = self.units();
        let tasks = units
            .iter()
            .filter(|u| matches!(u, Unit::Cyclic { started: true, .. }))
            .count() as u32;
        let implicit = units.len() == 1 && self.c.chance(5, 6);
        for (k, unit) in units.iter().enumerate() {
            let first_of_run = match unit {
                Unit::Cyclic { number, .. } => !units
                    .iter()
                    .any(|u| matches!(u, Unit::Cyclic { number: m, started: true } if m < number)),
                _ => true,
            };
            let directive = match *unit {
                // The text before any directive is task 0.
                Unit::Cyclic {
                    number: 0,
                    started: true,
                } if k == 0 && (implicit || self.c.chance(1, 3)) => None,
                Unit::Cyclic { number, started } => Some(format!(
                    "$TASK CYCLIC {number}{}",
                    if started { "" } else { " STANDBY" }
                )),
                Unit::Unassigned => Some("$TASK UNASSIGNED".to_owned()),
                Unit::FunctionBlock => Some(format!("$FB fb{k}")),
            };
            if let Some(d) = directive {
                let d = if self.c.chance(1, 10) {
                    d.to_ascii_lowercase()
                } else {
                    d
                };
                self.out.push_str(&d);
                self.out.push('\n');
            }
            if *unit == Unit::FunctionBlock {
                self.function_block();
            } else {
                self.task_program(tasks.max(1), !first_of_run);
            }
        }
    }

    /// The units in source order: at least one cyclic task started at RUN.
    fn units(&mut self) -> Vec<Unit> {
        let cyclic = u32::from(self.p.omron.cyclic_tasks).max(1);
        let running = if cyclic > 1 && self.c.chance(1, 4) {
            self.c.range(2, 4)
        } else {
            1
        };
        // Distinct task numbers, small ones mostly; a lone task is mostly task 0.
        let mut numbers: Vec<u32> = Vec::new();
        let wanted = (running as usize + 1).min(cyclic as usize);
        for _ in 0..4 * wanted {
            if numbers.len() == wanted {
                break;
            }
            let n = if running == 1 && numbers.is_empty() && self.c.chance(5, 6) {
                0
            } else if self.c.chance(1, 3) {
                self.c.below(cyclic)
            } else {
                self.c.below(cyclic.min(6))
            };
            if !numbers.contains(&n) {
                numbers.push(n);
            }
        }
        // An exhausted byte stream repeats itself: the lowest free numbers then.
        while numbers.len() < wanted {
            if let Some(free) = (0..cyclic).find(|m| !numbers.contains(m)) {
                numbers.push(free);
            }
        }
        let mut units: Vec<Unit> = numbers
            .iter()
            .take(running as usize)
            .map(|&number| Unit::Cyclic {
                number,
                started: true,
            })
            .collect();
        if units.is_empty() {
            units.push(Unit::Cyclic {
                number: 0,
                started: true,
            });
        }
        if let (Some(&number), true) = (numbers.get(running as usize), self.c.chance(1, 8)) {
            units.push(Unit::Cyclic {
                number,
                started: false,
            });
        }
        if self.c.chance(1, 10) {
            units.push(Unit::Unassigned);
        }
        if self.c.chance(1, 12) {
            units.push(Unit::FunctionBlock);
        }
        // Source order is not run order.
        for i in (1..units.len()).rev() {
            let j = self.c.below(i as u32 + 1) as usize;
            units.swap(i, j);
        }
        units
    }

    /// Fresh per-unit state and this unit's subroutine numbers (unique in the project).
    fn start_unit(&mut self, subs: u32) {
        self.jumps.clear();
        self.blocks.clear();
        self.current_sub = None;
        self.lines = 0;
        self.subs.clear();
        let max_sub = u32::from(self.p.max_subroutine);
        for _ in 0..subs {
            // An exhausted byte stream picks 0 every time: fall back to the next free number.
            let n = if self.c.chance(1, 10) {
                max_sub - self.c.below(3)
            } else {
                self.c.below(16)
            };
            let n = if self.all_subs.contains(&n) {
                (16..=max_sub).find(|m| !self.all_subs.contains(m))
            } else {
                Some(n)
            };
            if let Some(n) = n {
                self.all_subs.insert(n);
                self.subs.push(n);
            }
        }
    }

    /// One task's (or unassigned program's) text: rungs, subroutines, END. `tasks` running
    /// tasks share the size; `after_task_start` when another task ran before this one in the
    /// cycle (the flags this one reads first were cleared at its start).
    fn task_program(&mut self, tasks: u32, after_task_start: bool) {
        self.recursion = self.c.chance(1, 12);
        let n_subs = self.c.below(self.cfg.max_subroutines / tasks + 1);
        self.start_unit(n_subs);
        self.limit = self.cfg.max_ops_per_pou / tasks as usize;
        if self.c.chance(1, 2) {
            self.setup();
        }
        if after_task_start && self.c.chance(1, 2) {
            // W034: a condition flag read before anything in this task set it.
            self.op("", Group::Contact(Join::Load, false), &["P_On".into()]);
            let negated = self.c.chance(1, 3);
            let f = self.condition_flag();
            self.op("", Group::Contact(Join::And, negated), &[f]);
            self.bit_output();
        }
        let long = tasks == 1 && self.c.chance(1, 25);
        let rungs = if long {
            self.limit = 4 * self.cfg.max_ops_per_pou;
            4 * self.cfg.max_networks
        } else {
            self.c.range(1, (self.cfg.max_networks / tasks).max(1))
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
            self.op("", Group::Control(Flow::Sbn), &[n]);
            for _ in 0..self.c.range(0, 4) {
                self.rung(&Ctx::default());
            }
            self.op("", Group::Control(Flow::Ret), &[]);
            if self.c.chance(1, 30) {
                // Never runs (W028): code between the subroutine region and END.
                self.out.push_str("LD 0.00\nOUT W511.15\n");
            }
        }
        self.op("", Group::Control(Flow::End), &[]);
        if self.c.chance(1, 20) {
            // Never runs (W002): lines after the first END, a second END among them.
            self.out.push_str("LD 0.01\nOUT 100.00\nEND(001)\n");
        }
    }

    /// A function-block body: checked, never run; no `!`, no subroutines, jumps, steps,
    /// blocks, IORF or TMHH (E039); its END is optional.
    fn function_block(&mut self) {
        self.start_unit(0);
        self.plain = true;
        for _ in 0..self.c.range(1, 4) {
            match self.c.below(5) {
                0 => self.logic_rung(),
                1 => self.counter_rung(),
                2 => self.keep_rung(),
                3 => self.differentiate_rung(),
                _ => self.data_rung(),
            }
        }
        self.plain = false;
        if self.c.chance(1, 2) {
            self.op("", Group::Control(Flow::End), &[]);
        }
    }
}
