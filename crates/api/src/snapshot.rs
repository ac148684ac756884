//! [`Snapshot`]: the whole state of a [`crate::Plc`] at a scan boundary — the image (every
//! area, the timers', counters' and edges' private state, the scan number and virtual time,
//! which all live in it), the scan time and the forces — for checkpoints and branching what-if
//! runs. Restoring it into any `Plc` of the same program (fresh or not, either engine) continues
//! exactly as the original would have.
//!
//! [`Snapshot::to_bytes`] / [`Snapshot::from_bytes`] serialize it (FMI's serialized FMU state,
//! Python's pickling): a magic, a format version, the program's fingerprint, the scan time, the
//! image bytes and the forces by name. The fingerprint (FNV-1a over the program's IR text) is
//! what tells "the same program" when a snapshot comes back as bytes.

use crate::Error;

const MAGIC: &[u8; 8] = b"STLJSNAP";
const VERSION: u32 = 1;

/// The saved state of a PLC (see the module doc).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Snapshot {
    pub(crate) fingerprint: u64,
    pub(crate) scan_ms: u64,
    pub(crate) image: Vec<u8>,
    /// `(name, raw value)` of every force, in the order they were set.
    pub(crate) forces: Vec<(String, u32)>,
}

impl Snapshot {
    /// The snapshot as bytes (see the module doc for the format).
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(self.image.len() + 64);
        out.extend_from_slice(MAGIC);
        out.extend_from_slice(&VERSION.to_le_bytes());
        out.extend_from_slice(&self.fingerprint.to_le_bytes());
        out.extend_from_slice(&self.scan_ms.to_le_bytes());
        out.extend_from_slice(&(self.image.len() as u32).to_le_bytes());
        out.extend_from_slice(&self.image);
        out.extend_from_slice(&(self.forces.len() as u32).to_le_bytes());
        for (name, raw) in &self.forces {
            out.extend_from_slice(&(name.len() as u32).to_le_bytes());
            out.extend_from_slice(name.as_bytes());
            out.extend_from_slice(&raw.to_le_bytes());
        }
        out
    }

    /// Reads bytes written by [`Snapshot::to_bytes`]. Whether the snapshot fits a PLC is checked
    /// when it is restored.
    pub fn from_bytes(bytes: &[u8]) -> Result<Snapshot, Error> {
        let mut r = Reader { bytes, at: 0 };
        if r.take(8)? != MAGIC {
            return Err(Error::Snapshot {
                reason: "wrong magic",
            });
        }
        if r.u32()? != VERSION {
            return Err(Error::Snapshot {
                reason: "unknown format version",
            });
        }
        let fingerprint = r.u64()?;
        let scan_ms = r.u64()?;
        let len = r.u32()? as usize;
        let image = r.take(len)?.to_vec();
        let n = r.u32()?;
        let mut forces = Vec::new();
        for _ in 0..n {
            let len = r.u32()? as usize;
            let name = std::str::from_utf8(r.take(len)?)
                .map_err(|_| Error::Snapshot {
                    reason: "a forced name is not UTF-8",
                })?
                .to_string();
            forces.push((name, r.u32()?));
        }
        if r.at != bytes.len() {
            return Err(Error::Snapshot {
                reason: "trailing bytes",
            });
        }
        Ok(Snapshot {
            fingerprint,
            scan_ms,
            image,
            forces,
        })
    }
}

struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    fn take(&mut self, n: usize) -> Result<&'a [u8], Error> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.bytes.len());
        let end = end.ok_or(Error::Snapshot {
            reason: "truncated",
        })?;
        let s = &self.bytes[self.at..end];
        self.at = end;
        Ok(s)
    }

    fn u32(&mut self) -> Result<u32, Error> {
        let b = self.take(4)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    fn u64(&mut self) -> Result<u64, Error> {
        let lo = u64::from(self.u32()?);
        let hi = u64::from(self.u32()?);
        Ok(hi << 32 | lo)
    }
}

/// FNV-1a, 64 bits: a fingerprint that is the same on every machine and Rust version (of a
/// program's IR text, of an FMU's contents).
pub fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}
