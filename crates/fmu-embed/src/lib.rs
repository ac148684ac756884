//! The FMU runtime library (`stljit-fmu-runtime`) as bytes inside the `stljit` binary, so that
//! `stljit fmu` works from an installation made with `cargo install --path crates/cli`. The
//! build script (`build.rs`) says how the bytes get here and how to opt out.

/// The runtime library for this platform, or `None` when the binary was built without one
/// (`STLJIT_FMU_RUNTIME=skip`, or under clippy).
pub fn runtime() -> Option<&'static [u8]> {
    static BYTES: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/fmu-runtime.bin"));
    (!BYTES.is_empty()).then_some(BYTES)
}

/// Why [`runtime`] is `None` (empty when it is not).
pub fn missing_reason() -> &'static str {
    include_str!(concat!(env!("OUT_DIR"), "/fmu-runtime.note"))
}

/// The FMI 2.0 platform folder of this build (`linux64`, `darwin64`, `win64`).
pub const PLATFORM: &str = env!("STLJIT_FMU_PLATFORM");

/// The runtime library's file extension (`so`, `dylib`, `dll`).
pub const LIBRARY_EXTENSION: &str = env!("STLJIT_FMU_LIBRARY_EXTENSION");
