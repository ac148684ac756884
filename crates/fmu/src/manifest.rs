//! `resources/stljit.txt`: what the FMU runtime needs to rebuild the PLC at `fmi2Instantiate` —
//! the GUID it must be instantiated with, the dialect, CPU and scan time, the program files and
//! symbol table (paths inside `resources/`) and every variable with its value reference.
//!
//! One record per line, fields separated by TABs (names and specs contain none; shown here as
//! spaces):
//!
//! ```text
//! stljit-fmu  1
//! guid  {8c4e81e8-...}
//! dialect  s7
//! cpu  a5
//! scan_ms  10
//! file  program/traffic_light.awl
//! symbols  program/symbols.txt
//! var  1  input  Boolean  Ped_Button  I0.0  0  1  Ped_Button (I0.0)
//! ```
//!
//! A `var` line is `vr, causality, type, name, spec, min, max, description`. [`Manifest::parse`] rejects anything else
//! with the line number, so a damaged FMU fails at instantiation with a message, not later.

use crate::variables::{Causality, FmiType, Variable};
use std::fmt;

const HEADER: &str = "stljit-fmu\t1";

/// The contents of `resources/stljit.txt`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Manifest {
    /// The FMU's GUID, as in modelDescription.xml.
    pub guid: String,
    /// `s7` or `omron`.
    pub dialect: String,
    /// The CPU profile's name.
    pub cpu: String,
    /// Virtual time per scan.
    pub scan_ms: u64,
    /// Program files, relative to `resources/`.
    pub files: Vec<String>,
    /// The symbol table, relative to `resources/`.
    pub symbols: Option<String>,
    /// The variables, value references ascending.
    pub variables: Vec<Variable>,
}

/// A line of the manifest that does not parse.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ManifestError {
    /// 1-based line number (0: the file as a whole).
    pub line: usize,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for ManifestError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "resources/stljit.txt:{}: {}", self.line, self.message)
    }
}

impl std::error::Error for ManifestError {}

impl Manifest {
    /// The manifest's text.
    pub fn to_text(&self) -> String {
        let mut s = format!(
            "{HEADER}\nguid\t{}\ndialect\t{}\ncpu\t{}\nscan_ms\t{}\n",
            self.guid, self.dialect, self.cpu, self.scan_ms
        );
        for f in &self.files {
            s += &format!("file\t{f}\n");
        }
        if let Some(sym) = &self.symbols {
            s += &format!("symbols\t{sym}\n");
        }
        for v in &self.variables {
            s += &format!(
                "var\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\n",
                v.vr,
                v.causality.name(),
                v.ty.name(),
                v.name,
                v.spec,
                v.range.0,
                v.range.1,
                v.description
            );
        }
        s
    }

    /// Reads a manifest's text.
    pub fn parse(text: &str) -> Result<Manifest, ManifestError> {
        let err = |line: usize, message: String| ManifestError { line, message };
        let mut lines = text.lines().enumerate();
        match lines.next() {
            Some((_, l)) if l == HEADER => {}
            _ => return Err(err(1, format!("expected `{HEADER}`"))),
        }
        let mut m = Manifest {
            guid: String::new(),
            dialect: String::new(),
            cpu: String::new(),
            scan_ms: 0,
            files: Vec::new(),
            symbols: None,
            variables: Vec::new(),
        };
        for (i, line) in lines {
            let n = i + 1;
            let fields: Vec<&str> = line.split('\t').collect();
            let one = || -> Result<String, ManifestError> {
                match fields.as_slice() {
                    [_, v] => Ok((*v).to_string()),
                    _ => Err(err(n, format!("`{}` takes one value", fields[0]))),
                }
            };
            match fields[0] {
                "" => {}
                "guid" => m.guid = one()?,
                "dialect" => m.dialect = one()?,
                "cpu" => m.cpu = one()?,
                "scan_ms" => {
                    m.scan_ms = one()?
                        .parse()
                        .map_err(|_| err(n, "scan_ms is not a number".into()))?;
                }
                "file" => m.files.push(one()?),
                "symbols" => m.symbols = Some(one()?),
                "var" => m.variables.push(parse_var(&fields).map_err(|e| err(n, e))?),
                other => return Err(err(n, format!("unknown record `{other}`"))),
            }
        }
        if m.guid.is_empty() || m.dialect.is_empty() || m.cpu.is_empty() || m.files.is_empty() {
            return Err(err(
                0,
                "guid, dialect, cpu and at least one file are required".into(),
            ));
        }
        if m.scan_ms == 0 {
            return Err(err(0, "scan_ms must be at least 1".into()));
        }
        for (i, v) in m.variables.iter().enumerate() {
            if v.vr != i as u32 + 1 {
                return Err(err(
                    0,
                    format!("value references must be 1, 2, 3, ... ({})", v.name),
                ));
            }
        }
        Ok(m)
    }
}

fn parse_var(f: &[&str]) -> Result<Variable, String> {
    let [_, vr, causality, ty, name, spec, lo, hi, description] = f else {
        return Err("a var line has 8 fields after `var`".into());
    };
    let int = |s: &str| {
        s.parse::<i64>()
            .map_err(|_| format!("`{s}` is not a number"))
    };
    Ok(Variable {
        vr: vr
            .parse()
            .map_err(|_| format!("bad value reference `{vr}`"))?,
        causality: Causality::from_name(causality)
            .ok_or_else(|| format!("unknown causality `{causality}`"))?,
        ty: FmiType::from_name(ty).ok_or_else(|| format!("unknown type `{ty}`"))?,
        name: (*name).to_string(),
        spec: (*spec).to_string(),
        range: (int(lo)?, int(hi)?),
        description: (*description).to_string(),
    })
}
