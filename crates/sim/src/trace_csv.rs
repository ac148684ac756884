//! The CSV trace: a `scan,t_ms,WATCH,...` header, then one row per scan with the watched values
//! after the scan, formatted per [`WatchSpec`].

use crate::driver::{Observer, ScanEvent};
use crate::watch::WatchSpec;
use std::io::{self, Write};

/// Streams one CSV row per scan to `W`.
pub struct CsvTrace<W: Write> {
    out: W,
    watches: Vec<WatchSpec>,
}

impl<W: Write> CsvTrace<W> {
    /// Writes the header at once, so even a run that stops in scan 0 leaves a valid file.
    pub fn new(mut out: W, watches: Vec<WatchSpec>) -> io::Result<CsvTrace<W>> {
        write!(out, "scan,t_ms")?;
        for w in &watches {
            write!(out, ",{}", w.text)?;
        }
        writeln!(out)?;
        Ok(CsvTrace { out, watches })
    }

    /// Flushes and returns the writer.
    pub fn finish(mut self) -> io::Result<W> {
        self.out.flush()?;
        Ok(self.out)
    }
}

impl<W: Write> Observer for CsvTrace<W> {
    fn observe(&mut self, e: &ScanEvent<'_>) -> io::Result<()> {
        write!(self.out, "{},{}", e.scan, e.t_ms)?;
        for w in &self.watches {
            let raw = w.read(e.image).ok_or_else(|| {
                io::Error::new(
                    io::ErrorKind::InvalidInput,
                    format!("watch `{}` is outside the memory image", w.text),
                )
            })?;
            write!(self.out, ",{}", w.format(raw))?;
        }
        writeln!(self.out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_resolver::{observe_scan, resolve, watches, write_watches};
    use stljit_core::{ProfileId, ScanStatus};
    use stljit_runtime::image::Image;

    #[test]
    fn golden() {
        let watches = watches(&["Q0.0", "VW0", "VD4:real", "VB8:hex"]);
        let mut trace = CsvTrace::new(Vec::new(), watches.clone()).unwrap();
        let mut img = Image::blank(ProfileId::A5);
        for (k, (q, vw, vd)) in [(0u32, 0u32, 0.0f32), (1, 0xFFFF, 2.5)]
            .into_iter()
            .enumerate()
        {
            let bits = [q, vw, vd.to_bits(), 0xA0 + k as u32];
            write_watches(&mut img, &watches, &bits);
            observe_scan(&mut trace, &img, k);
        }
        let text = String::from_utf8(trace.finish().unwrap()).unwrap();
        assert_eq!(
            text,
            "scan,t_ms,Q0.0,VW0,VD4:real,VB8:hex\n0,0,0,0,0.0,16#A0\n1,10,1,-1,2.5,16#A1\n"
        );
    }

    #[test]
    fn watch_outside_the_image_is_an_error() {
        let w = WatchSpec::parse("VW2499", &resolve).unwrap();
        let mut trace = CsvTrace::new(Vec::new(), vec![w]).unwrap();
        let img = Image::blank(ProfileId::A5);
        let e = ScanEvent {
            scan: 0,
            t_ms: 0,
            image: &img,
            status: ScanStatus::Ok,
        };
        assert_eq!(
            trace.observe(&e).unwrap_err().kind(),
            io::ErrorKind::InvalidInput
        );
    }
}
