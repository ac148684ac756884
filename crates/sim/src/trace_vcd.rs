//! The VCD trace (IEEE 1364 value change dump), viewable in GTKWave or Surfer.
//!
//! Header: `$timescale 1ms`, one `$scope module` holding a `$var` per watch — `wire 1` for bits,
//! `wire 8/16/32` for values, `real` for `:real` watches. The first scan dumps every value under
//! `$dumpvars`; each scan writes its `#t_ms` and then only the values that changed. There is no
//! `$date`: the same run must give the same bytes.
//!
//! Variable names are the watch texts with every character outside `[A-Za-z0-9_]` replaced by
//! `_` (`I0.0` → `I0_0`, `VD50:real` → `VD50_real`), because viewers split names at `.` into a
//! hierarchy and `:`/`[` have meanings of their own.

use crate::driver::{Observer, ScanEvent};
use crate::watch::{Format, WatchSpec};
use std::io::{self, Write};
use std::ops::Range;
use stljit_core::layout::Layout;

/// Streams a VCD to `W`.
pub struct VcdTrace<W: Write> {
    out: W,
    watches: Vec<WatchSpec>,
    ids: Vec<String>,
    last: Vec<Option<u32>>,
    started: bool,
}

/// The short identifier of variable `i`: base-94 over the printable ASCII range.
fn ident(mut i: usize) -> String {
    let mut s = String::new();
    loop {
        s.push(char::from(b'!' + (i % 94) as u8));
        i /= 94;
        if i == 0 {
            return s;
        }
        i -= 1;
    }
}

fn var_name(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

impl<W: Write> VcdTrace<W> {
    /// Writes the header; `scope` names the module the variables sit in (e.g. the program name).
    pub fn new(mut out: W, watches: Vec<WatchSpec>, scope: &str) -> io::Result<VcdTrace<W>> {
        writeln!(out, "$version stljit $end")?;
        writeln!(out, "$timescale 1ms $end")?;
        let scope = var_name(scope);
        let scope = if scope.is_empty() {
            "plc".to_string()
        } else {
            scope
        };
        writeln!(out, "$scope module {scope} $end")?;
        let ids: Vec<String> = (0..watches.len()).map(ident).collect();
        for (w, id) in watches.iter().zip(&ids) {
            let name = var_name(&w.text);
            if w.format == Format::Real {
                writeln!(out, "$var real 64 {id} {name} $end")?;
            } else {
                writeln!(out, "$var wire {} {id} {name} $end", w.bits())?;
            }
        }
        writeln!(out, "$upscope $end")?;
        writeln!(out, "$enddefinitions $end")?;
        let last = vec![None; watches.len()];
        Ok(VcdTrace {
            out,
            watches,
            ids,
            last,
            started: false,
        })
    }

    /// Flushes and returns the writer.
    pub fn finish(mut self) -> io::Result<W> {
        self.out.flush()?;
        Ok(self.out)
    }

    fn value(&mut self, i: usize, raw: u32) -> io::Result<()> {
        let (w, id) = (&self.watches[i], &self.ids[i]);
        match (w.bits(), w.format) {
            (_, Format::Real) => writeln!(self.out, "r{:?} {id}", f32::from_bits(raw)),
            (1, _) => writeln!(self.out, "{}{id}", raw & 1),
            _ => writeln!(self.out, "b{raw:b} {id}"),
        }
    }
}

impl<W: Write> Observer for VcdTrace<W> {
    /// A timestamp is written only for scans in which a watched value changed: a day of 10 ms
    /// scans with a few changes stays a small file.
    fn observe(&mut self, e: &ScanEvent<'_>) -> io::Result<()> {
        let first = !self.started;
        self.started = true;
        let mut stamped = false;
        for i in 0..self.watches.len() {
            let raw = self.watches[i].read(e.image).ok_or_else(|| {
                io::Error::new(
                    io::ErrorKind::InvalidInput,
                    format!(
                        "watch `{}` is outside the memory image",
                        self.watches[i].text
                    ),
                )
            })?;
            if self.last[i] != Some(raw) {
                if !stamped {
                    writeln!(self.out, "#{}", e.t_ms)?;
                    if first {
                        writeln!(self.out, "$dumpvars")?;
                    }
                    stamped = true;
                }
                self.value(i, raw)?;
                self.last[i] = Some(raw);
            }
        }
        if first && stamped {
            writeln!(self.out, "$end")?;
        }
        Ok(())
    }

    /// A scan writes only the values that changed, so the trace needs to see only the scans
    /// that changed a watched byte (and the first).
    fn changes_of(&self, layout: &Layout) -> Option<Vec<Range<usize>>> {
        self.watches.iter().map(|w| w.bytes(layout)).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_resolver::{observe_scan, watches, write_watches};
    use stljit_core::ProfileId;
    use stljit_runtime::image::Image;

    #[test]
    fn identifiers_are_unique_and_printable() {
        assert_eq!(ident(0), "!");
        assert_eq!(ident(93), "~");
        assert_eq!(ident(94), "!!");
        let all: std::collections::HashSet<_> = (0..20_000).map(ident).collect();
        assert_eq!(all.len(), 20_000);
        assert!(
            all.iter()
                .all(|s| s.bytes().all(|b| (33..=126).contains(&b)))
        );
    }

    #[test]
    fn golden() {
        let watches = watches(&["I0.0", "VW0", "VD4:real", "VB8"]);
        let mut trace = VcdTrace::new(Vec::new(), watches.clone(), "t01").unwrap();
        let mut img = Image::blank(ProfileId::A5);
        let scans = [
            (0u32, 5u32, 1.5f32, 3u32),
            (1, 5, 1.5, 3),
            (1, 0xFFFF, -0.25, 3),
        ];
        for (k, (i, vw, vd, vb)) in scans.into_iter().enumerate() {
            write_watches(&mut img, &watches, &[i, vw, vd.to_bits(), vb]);
            // I is driven through the physical copy; mirror it into the image the way a scan would.
            let l = img.layout().clone();
            let phys = img.bytes()[l.phys_in as usize];
            img.bytes_mut()[l.base(stljit_core::Area::I) as usize] = phys;
            observe_scan(&mut trace, &img, k);
        }
        let text = String::from_utf8(trace.finish().unwrap()).unwrap();
        let want = "\
$version stljit $end
$timescale 1ms $end
$scope module t01 $end
$var wire 1 ! I0_0 $end
$var wire 16 \" VW0 $end
$var real 64 # VD4_real $end
$var wire 8 $ VB8 $end
$upscope $end
$enddefinitions $end
#0
$dumpvars
0!
b101 \"
r1.5 #
b11 $
$end
#10
1!
#20
b1111111111111111 \"
r-0.25 #
";
        assert_eq!(text, want);
    }
}
