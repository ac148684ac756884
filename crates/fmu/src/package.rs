//! [`export`]: the `.fmu` archive of a program — modelDescription.xml, the platform binary and
//! the resources (program files, symbol table, manifest) — as bytes.
//!
//! The archive is deterministic: entries in a fixed order, every timestamp 1980-01-01 (the zip
//! epoch), so the same program and options give the same bytes.

use crate::manifest::Manifest;
use crate::model_description::{self, Description};
use crate::variables::variables;
use std::fmt;
use std::io::{Cursor, Write as _};
use std::path::Path;
use std::sync::Arc;
use stljit_api::Project;
use zip::write::SimpleFileOptions;
use zip::{CompressionMethod, DateTime, ZipWriter};

/// How to export.
#[derive(Clone, Debug)]
pub struct ExportOptions<'a> {
    /// `modelIdentifier` and the binary's file stem; a C identifier.
    pub model_identifier: String,
    /// Virtual time per scan.
    pub scan_ms: u64,
    /// Internal variables to expose as locals (`VD100:real`, `T37:i`, a symbol).
    pub locals: Vec<String>,
    /// The FMI runtime library's bytes.
    pub runtime: &'a [u8],
    /// The FMI platform folder (`linux64`, `darwin64`, `win64`).
    pub platform: &'a str,
    /// The library's file extension (`so`, `dylib`, `dll`).
    pub library_extension: &'a str,
}

/// Why an FMU could not be made.
#[derive(Debug)]
pub enum ExportError {
    /// The program does not compile or a local does not resolve.
    Api(stljit_api::Error),
    /// The model identifier is not a C identifier.
    ModelIdentifier(String),
    /// Writing the archive failed.
    Archive(String),
}

impl fmt::Display for ExportError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ExportError::Api(e) => write!(f, "{e}"),
            ExportError::ModelIdentifier(id) => write!(
                f,
                "model identifier `{id}` is not a C identifier (letters, digits, _; not a digit first)"
            ),
            ExportError::Archive(m) => write!(f, "cannot write the FMU archive: {m}"),
        }
    }
}

impl std::error::Error for ExportError {}

impl From<stljit_api::Error> for ExportError {
    fn from(e: stljit_api::Error) -> ExportError {
        ExportError::Api(e)
    }
}

fn archive(e: impl fmt::Display) -> ExportError {
    ExportError::Archive(e.to_string())
}

/// Whether `id` is a C identifier.
pub fn is_c_identifier(id: &str) -> bool {
    let mut chars = id.chars();
    chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// The FMU of `project` as zip bytes.
pub fn export(project: &Project, opts: &ExportOptions<'_>) -> Result<Vec<u8>, ExportError> {
    if !is_c_identifier(&opts.model_identifier) {
        return Err(ExportError::ModelIdentifier(opts.model_identifier.clone()));
    }
    let compiled = Arc::new(project.compile()?);
    let program = compiled.program()?;
    let vars = variables(&compiled, &opts.locals)?;

    // Resources: the files under program/, named by their base names (numbered when two share
    // one), the symbol table beside them.
    let mut resources: Vec<(String, &[u8])> = Vec::new();
    let mut unique = |name: &str, bytes| {
        let base = Path::new(name).file_name().map_or_else(
            || "program".to_string(),
            |b| b.to_string_lossy().into_owned(),
        );
        let mut path = format!("program/{base}");
        let mut i = 1;
        while resources.iter().any(|(p, _)| *p == path) {
            i += 1;
            path = format!("program/{i}_{base}");
        }
        resources.push((path.clone(), bytes));
        path
    };
    let files: Vec<String> = project
        .files()
        .iter()
        .map(|f| unique(&f.name, &f.bytes))
        .collect();
    let symbols = project.symbols_source().map(|s| unique(&s.name, &s.bytes));

    let mut manifest = Manifest {
        guid: String::new(),
        dialect: compiled.dialect().name().to_string(),
        cpu: compiled.profile().name().to_string(),
        scan_ms: opts.scan_ms,
        files,
        symbols,
        variables: vars,
    };
    manifest.guid = guid(&manifest.to_text(), &resources);
    let model_name = project
        .files()
        .first()
        .and_then(|f| Path::new(&f.name).file_stem())
        .map_or_else(|| "plc".to_string(), |s| s.to_string_lossy().into_owned());
    let description = format!(
        "{} PLC program ({} ops, {} dialect, {}) compiled by stljit at instantiation, {} ms per scan",
        model_name,
        program.op_count(),
        compiled.dialect().name(),
        compiled.profile().name(),
        opts.scan_ms
    );
    let tool = format!("stljit {}", env!("CARGO_PKG_VERSION"));
    let xml = model_description::write(
        &Description {
            model_name: &model_name,
            model_identifier: &opts.model_identifier,
            guid: &manifest.guid,
            description: &description,
            scan_ms: opts.scan_ms,
            tool: &tool,
        },
        &manifest.variables,
    )
    .map_err(archive)?;

    let mut zip = ZipWriter::new(Cursor::new(Vec::new()));
    let options = SimpleFileOptions::default()
        .compression_method(CompressionMethod::Deflated)
        .last_modified_time(DateTime::default());
    let mut add = |path: &str, bytes: &[u8]| -> Result<(), ExportError> {
        zip.start_file(path, options).map_err(archive)?;
        zip.write_all(bytes).map_err(archive)
    };
    add("modelDescription.xml", xml.as_bytes())?;
    add(
        &format!(
            "binaries/{}/{}.{}",
            opts.platform, opts.model_identifier, opts.library_extension
        ),
        opts.runtime,
    )?;
    add("resources/stljit.txt", manifest.to_text().as_bytes())?;
    for (path, bytes) in &resources {
        add(&format!("resources/{path}"), bytes)?;
    }
    let cursor = zip.finish().map_err(archive)?;
    Ok(cursor.into_inner())
}

/// A GUID from the manifest (without its guid line) and the resources' bytes.
fn guid(manifest: &str, resources: &[(String, &[u8])]) -> String {
    let mut bytes = manifest.as_bytes().to_vec();
    for (path, b) in resources {
        bytes.extend_from_slice(path.as_bytes());
        bytes.extend_from_slice(b);
    }
    let a = stljit_api::fingerprint(&bytes);
    bytes.push(0x5a);
    let b = stljit_api::fingerprint(&bytes);
    format!(
        "{{{:08x}-{:04x}-{:04x}-{:04x}-{:012x}}}",
        a >> 32,
        (a >> 16) & 0xffff,
        a & 0xffff,
        b >> 48,
        b & 0xffff_ffff_ffff
    )
}
