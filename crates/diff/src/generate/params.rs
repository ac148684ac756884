//! Subroutine parameters for the S7 generator (s7-200-more §1): each subroutine gets a random
//! parameter list (or none), its formals allocated by the front end's own §1.2 rule
//! (`stljit_front_s7::locals::allocate`, so the S7 printer's rebuilt declarations compile back to
//! the same IR), and every call of it passes actuals of the right class, so the differential
//! oracle compares `Op::CallArgs` with copy-in, copy-back, pointer actuals and nesting errors.

use super::Gen;
use super::operands::Class;
use stljit_core::ir::{Address, Arg, ArgDir, ArgValue, CallArgs, Op};
use stljit_core::{PouId, Width};
use stljit_front_s7::locals::{LocalType, Section, allocate};

/// One generated parameter: how it is passed and its formal in the callee's frame.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Param {
    dir: ArgDir,
    formal: Address,
}

impl Gen<'_, '_> {
    /// A parameter list for a subroutine: none half of the time, else one to six in table order.
    pub(crate) fn signature(&mut self) -> Vec<Param> {
        if self.c.chance(1, 2) {
            return Vec::new();
        }
        let n = self.c.range(1, 6) as usize;
        let mut items: Vec<(Section, LocalType)> = (0..n)
            .map(|_| {
                let section =
                    [Section::In, Section::InOut, Section::Out][self.c.weighted(&[5, 2, 3])];
                let ty = [
                    LocalType::Bool,
                    LocalType::Byte,
                    LocalType::Word,
                    LocalType::DWord,
                ][self.c.weighted(&[4, 2, 3, 2])];
                (section, ty)
            })
            .collect();
        // Table order is the order of a CALL's actuals.
        items.sort_by_key(|&(s, _)| Section::ALL.iter().position(|&x| x == s));
        let (formals, _) = allocate(&items);
        items
            .iter()
            .zip(formals)
            .map(|(&(section, _), formal)| Param {
                dir: match section {
                    Section::In => ArgDir::In,
                    Section::InOut => ArgDir::InOut,
                    Section::Out | Section::Temp => ArgDir::Out,
                },
                formal,
            })
            .collect()
    }

    /// The op that calls `id`: a plain CALL, or one passing fresh actuals for its parameters.
    pub(crate) fn call_op(&mut self, id: PouId) -> Op {
        let params = self.params.get(id.index()).cloned().unwrap_or_default();
        if params.is_empty() {
            return Op::Call(id);
        }
        let args = params.iter().map(|p| self.arg(*p)).collect();
        Op::CallArgs(Box::new(CallArgs { callee: id, args }))
    }

    fn arg(&mut self, p: Param) -> Arg {
        let value = match p.formal {
            Address::Bit(formal) => ArgValue::Bit {
                formal,
                actual: if p.dir == ArgDir::In {
                    self.bit_in()
                } else {
                    self.bit_out(false)
                },
            },
            Address::Value { loc, width } => {
                let class = match p.dir {
                    ArgDir::In => Class {
                        addr: width == Width::DWord,
                        ..Class::IN
                    },
                    ArgDir::InOut => Class::OUT,
                    ArgDir::Out => Class {
                        aq: width == Width::Word,
                        ..Class::OUT
                    },
                };
                ArgValue::Value {
                    width,
                    formal: loc,
                    actual: self.value(width, class),
                }
            }
        };
        Arg { dir: p.dir, value }
    }
}
