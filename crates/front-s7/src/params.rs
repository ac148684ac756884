//! `CALL` with actual parameters (s7-200-more §1.4): the actuals are checked against the
//! callee's declared parameters (count, then each one's type, width and direction) and become an
//! `Op::CallArgs` whose formals are the parameters' L addresses. A mismatch names the parameter
//! and where it is declared.

use crate::classes::{BitClass, R, Reported, Val};
use crate::lexer::{Line, Tok};
use crate::locals::{Local, LocalType, Section};
use crate::operand::{Const, parse_const};
use crate::program::Lowerer;
use stljit_core::ir::{Address, Arg, ArgDir, ArgValue, CallArgs, Op};
use stljit_core::{PouId, Width};
use stljit_source::{Code, clip};

/// The codes of an operand check that, for a parameter, mean "does not fit the parameter".
const KIND_CODES: &[Code] = &[
    Code::OperandClass,
    Code::OperandWidth,
    Code::ReadOnly,
    Code::NumberRange,
];

impl Lowerer<'_> {
    /// The op of `CALL callee, actuals…` (the target already resolved).
    pub(crate) fn call_op(&mut self, callee: PouId, line: &Line<'_>, actuals: &[Tok<'_>]) -> R<Op> {
        let locals = self.locals.get(callee.index()).cloned().unwrap_or_default();
        let params = locals.params();
        if params.is_empty() && actuals.is_empty() {
            return Ok(Op::Call(callee));
        }
        if params.len() != actuals.len() {
            return Err(self.count_mismatch(callee, line, &params, actuals.len()));
        }
        let mut args = Vec::with_capacity(params.len());
        let mut failed = false;
        for (p, &t) in params.iter().zip(actuals) {
            match self.actual(callee, p, t) {
                Ok(a) => args.push(a),
                Err(Reported) => failed = true,
            }
        }
        if failed {
            return Err(Reported);
        }
        Ok(Op::CallArgs(Box::new(CallArgs { callee, args })))
    }

    /// The name the messages give the callee.
    fn callee_name(&self, callee: PouId) -> String {
        self.pou_names
            .get(callee.index())
            .cloned()
            .unwrap_or_default()
    }

    fn count_mismatch(
        &mut self,
        callee: PouId,
        line: &Line<'_>,
        params: &[&Local],
        given: usize,
    ) -> Reported {
        let name = self.callee_name(callee);
        let signature: Vec<String> = params
            .iter()
            .map(|p| {
                format!(
                    "{} {}: {}",
                    p.decl.section.name(),
                    p.decl.name,
                    p.decl.ty.name()
                )
            })
            .collect();
        let at = self
            .pou_spans
            .get(callee.index())
            .map(|s| self.cx.place(*s))
            .unwrap_or_default();
        let help = if params.is_empty() {
            format!("`{}` declares no parameters ({at})", clip(&name))
        } else {
            format!(
                "`{}` ({at}) takes, in this order: {}",
                clip(&name),
                signature.join(", ")
            )
        };
        let t = if given == 0 { self.mnemonic } else { line.rest };
        self.cx.report(
            Code::CallParamCount,
            t,
            format!(
                "`{}` takes {} parameter(s), {given} given",
                clip(&name),
                params.len()
            ),
            Some(help),
        )
    }

    /// One actual `t` for parameter `p`.
    fn actual(&mut self, callee: PouId, p: &Local, t: Tok<'_>) -> R<Arg> {
        let dir = match p.decl.section {
            Section::In => ArgDir::In,
            Section::InOut => ArgDir::InOut,
            // TEMP variables are not parameters (`Locals::params`).
            Section::Out | Section::Temp => ArgDir::Out,
        };
        let before = self.cx.diags.len();
        let value = match (p.addr, p.decl.ty.width()) {
            (Address::Bit(formal), _) => {
                let class = if dir == ArgDir::In {
                    BitClass::Read
                } else {
                    BitClass::Write
                };
                self.cx
                    .bit(t, class)
                    .map(|actual| ArgValue::Bit { formal, actual })
            }
            (Address::Value { loc: formal, width }, _) => {
                if p.decl.ty == LocalType::Real
                    && dir == ArgDir::In
                    && matches!(parse_const(t.text), Ok(Const::Int(_)))
                {
                    return Err(self.kind_mismatch(
                        callee,
                        p,
                        t,
                        format!("integer constant `{}` for a REAL parameter", clip(t.text)),
                        "the CPU copies parameters bit for bit and converts nothing; write a real \
                         constant (5.0)"
                            .into(),
                    ));
                }
                let val = actual_class(p.decl.ty, width, dir);
                self.cx.value(t, val).map(|actual| ArgValue::Value {
                    width,
                    formal,
                    actual,
                })
            }
        };
        match value {
            Ok(value) => Ok(Arg { dir, value }),
            Err(Reported) => {
                // Recast an operand-kind error as a parameter mismatch that names the parameter.
                if self.cx.diags.len() == before + 1
                    && let Some(d) = self.cx.diags.pop()
                {
                    if KIND_CODES.contains(&d.code) {
                        let help = d.help.unwrap_or_default();
                        return Err(self.kind_mismatch(callee, p, t, d.message, help));
                    }
                    self.cx.diags.push(d);
                }
                Err(Reported)
            }
        }
    }

    fn kind_mismatch(
        &mut self,
        callee: PouId,
        p: &Local,
        t: Tok<'_>,
        why: String,
        help: String,
    ) -> Reported {
        let name = self.callee_name(callee);
        let declared = format!(
            "`{}` is declared {} on {}",
            clip(&p.decl.name),
            p.describe(),
            self.cx.place(p.decl.span)
        );
        let help = if help.is_empty() {
            declared
        } else {
            format!("{declared}; {help}")
        };
        self.cx.report(
            Code::CallParamKind,
            t,
            format!(
                "parameter `{}` of `{}`: {why}",
                clip(&p.decl.name),
                clip(&name)
            ),
            Some(help),
        )
    }
}

/// The operand class of an actual for a value parameter of type `ty` (s7-200-more §1.4): IN takes
/// the `*_IN` class of the width (constants included; a DWORD/DINT may be `&addr`, a pointer);
/// IN_OUT and OUT take writable operands of the width (an OUT word may be an `AQW`).
fn actual_class(ty: LocalType, width: Width, dir: ArgDir) -> Val {
    let real = ty == LocalType::Real;
    match dir {
        ArgDir::In => Val {
            real,
            addr_of: matches!(ty, LocalType::DWord | LocalType::DInt),
            ..Val::input(width)
        },
        ArgDir::InOut => Val {
            real,
            ..Val::output(width)
        },
        ArgDir::Out => Val {
            real,
            aq_out: width == Width::Word,
            ..Val::output(width)
        },
    }
}
