//! `stljit fmu`: export a program as an FMI 2.0 co-simulation FMU.
//!
//! The FMU's platform binary is the FMU runtime embedded in this executable at build time
//! (`stljit-fmu-embed`), or the library given with `--runtime`. Inputs, outputs and locals:
//! `stljit_fmu::variables`; the mapping is documented in `docs/fmu.md`.

use crate::check::Input;
use crate::duration::parse_duration;
use anyhow::Context as _;
use std::path::PathBuf;
use std::process::ExitCode;
use stljit_fmu::{ExportOptions, export};

/// Arguments of `stljit fmu`.
#[derive(clap::Args)]
pub(crate) struct Args {
    #[command(flatten)]
    input: Input,
    /// Virtual time per scan (fmi2DoStep runs every scan that starts within the step).
    #[arg(long, value_name = "DURATION", default_value = "10ms", value_parser = parse_duration)]
    scan_time: u64,
    /// Internal variables to expose as FMU locals, e.g. `VD100:real,T37:i,Walk_Total`.
    #[arg(long, value_delimiter = ',', value_name = "NAME,...")]
    local: Vec<String>,
    /// The FMU file to write (its stem is the modelIdentifier).
    #[arg(short, long, value_name = "OUT.fmu")]
    output: PathBuf,
    /// The FMU runtime library to pack instead of the one built into stljit
    /// (target/release/libstljit_fmu_runtime.so from `cargo build --release -p stljit-fmu-runtime`).
    #[arg(long, value_name = "LIBRARY")]
    runtime: Option<PathBuf>,
}

/// The modelIdentifier for an output path: its stem with every character that is not a letter,
/// digit or `_` replaced by `_` (and a leading digit prefixed).
fn model_identifier(path: &std::path::Path) -> String {
    let stem = path
        .file_stem()
        .map_or_else(|| "plc".to_string(), |s| s.to_string_lossy().into_owned());
    let mut id: String = stem
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    if !id.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_') {
        id.insert(0, '_');
    }
    id
}

pub(crate) fn main(args: Args) -> anyhow::Result<ExitCode> {
    if args.scan_time == 0 {
        anyhow::bail!("scan time must be at least 1 ms");
    }
    let project = args.input.project()?;
    let compiled = project.compile()?;
    if crate::project::checked_program(compiled.compilation()).is_none() {
        return Ok(ExitCode::from(1));
    }
    let loaded;
    let runtime: &[u8] = match &args.runtime {
        Some(path) => {
            loaded =
                std::fs::read(path).with_context(|| format!("cannot read {}", path.display()))?;
            &loaded
        }
        None => stljit_fmu_embed::runtime().with_context(|| {
            format!(
                "this stljit was built without the FMU runtime ({}); pass --runtime \
                 path/to/libstljit_fmu_runtime.so or rebuild without STLJIT_FMU_RUNTIME=skip",
                stljit_fmu_embed::missing_reason()
            )
        })?,
    };
    let opts = ExportOptions {
        model_identifier: model_identifier(&args.output),
        scan_ms: args.scan_time,
        locals: args.local.clone(),
        runtime,
        platform: stljit_fmu_embed::PLATFORM,
        library_extension: stljit_fmu_embed::LIBRARY_EXTENSION,
    };
    let bytes = export(&project, &opts).map_err(|e| anyhow::anyhow!("{e}"))?;
    std::fs::write(&args.output, &bytes)
        .with_context(|| format!("cannot write {}", args.output.display()))?;
    eprintln!(
        "wrote {} ({} KiB): FMI 2.0 co-simulation, modelIdentifier {}, {} ms per scan",
        args.output.display(),
        bytes.len() / 1024,
        opts.model_identifier,
        args.scan_time
    );
    Ok(ExitCode::SUCCESS)
}

#[cfg(test)]
mod tests {
    use super::model_identifier;
    use std::path::Path;

    #[test]
    fn model_identifiers_are_c_identifiers() {
        assert_eq!(model_identifier(Path::new("out/plc.fmu")), "plc");
        assert_eq!(
            model_identifier(Path::new("traffic-light.v2.fmu")),
            "traffic_light_v2"
        );
        assert_eq!(model_identifier(Path::new("2tank.fmu")), "_2tank");
    }
}
