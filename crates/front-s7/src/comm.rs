//! The communication instructions (s7-200-more §10): `XMT TBL, PORT`, `RCV TBL, PORT`,
//! `NETR TBL, PORT`, `NETW TBL, PORT`, `GET TBL`, `PUT TBL`, `GPA ADDR, PORT` and
//! `SPA ADDR, PORT`, lowered to [`ExtBox::Comm`] (the runtime's `comm` module runs them).
//! PORT is a constant port of the CPU whose registers its SM area holds (E080: the `a5`'s SM
//! area ends before port 1's receive registers, so RCV on port 1 is rejected there). Which
//! CPU has which instruction is the profile's (E033). The STL spelling for the printer is in
//! `ext`.

use crate::classes::{R, Val};
use crate::ext::run;
use crate::lexer::{Line, Tok};
use crate::program::{Lowerer, PouState};
use stljit_core::comm::{self, rcv};
use stljit_core::ir::{CommOp, ExtBox, Op};
use stljit_core::{Area, Width};
use stljit_source::Code;

/// The op of mnemonic `m` (upper case).
pub(crate) fn comm_op(m: &str) -> Option<CommOp> {
    CommOp::ALL.into_iter().find(|o| o.mnemonic() == m)
}

impl Lowerer<'_> {
    /// Lowers a communication instruction (`m`, upper case).
    pub(crate) fn comm(&mut self, ps: &mut PouState, m: &str, line: &Line<'_>) -> R<()> {
        let Some(op) = comm_op(m) else {
            return Ok(());
        };
        let o = line.ops;
        let n = if op.has_port() { 2 } else { 1 };
        self.arity(line, n, n)?;
        let val = match op {
            CommOp::Transmit => run(false),
            CommOp::SetAddress => Val::input(Width::Byte),
            CommOp::GetAddress => Val::output(Width::Byte),
            _ => run(true),
        };
        let table = self.cx.value(o[0], val);
        let port = if op.has_port() {
            self.port_operand(o[1], op)
        } else {
            Ok(0)
        };
        let b = ExtBox::Comm {
            op,
            table: table?,
            port: port?,
        };
        self.emit(ps, Op::Ext(Box::new(b)));
        Ok(())
    }

    /// A PORT operand: 0 or 1, and for RCV a port whose receive registers the SM area holds.
    fn port_operand(&mut self, t: Tok<'_>, op: CommOp) -> R<u8> {
        let n = self.cx.number(t, 0, 255, "port number", Code::PortNumber)?;
        let profile = self.cx.profile;
        let sm = profile.area_size(Area::SM);
        let regs = comm::PORTS.get(n as usize);
        let ok = regs.is_some_and(|p| {
            p.mode_smb < sm && (op != CommOp::Receive || p.rcv_smb + rcv::MAX_COUNT < sm)
        });
        if ok {
            return Ok(n as u8);
        }
        Err(self.cx.report(
            Code::PortNumber,
            t,
            format!(
                "`{}` cannot use port {n} on the {}",
                op.mnemonic(),
                profile.model
            ),
            Some(if regs.is_some() {
                format!(
                    "the {}'s SM area has no receive registers for port {n}",
                    profile.model
                )
            } else {
                "ports: 0, 1".into()
            }),
        ))
    }
}
