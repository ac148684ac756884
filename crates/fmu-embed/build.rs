//! Builds the FMU runtime (`stljit-fmu-runtime`, a cdylib) and puts its bytes in `OUT_DIR`, for
//! `src/lib.rs` to embed with `include_bytes!`.
//!
//! `cargo install --path crates/cli` installs executables only, so the `stljit` binary carries
//! the FMU's platform library inside it. Cargo has no stable way to depend on another crate's
//! cdylib artifact, so this script runs a nested `cargo build --release -p stljit-fmu-runtime` of
//! this workspace with its own target directory (the way wasm builders embed a second build),
//! sharing the outer build's jobserver. The nested target directory sits next to the outer
//! profile directories, so debug and release builds of the CLI share it and a rebuild is
//! incremental.
//!
//! `STLJIT_FMU_RUNTIME` changes this: `skip` embeds nothing (`stljit fmu` then needs
//! `--runtime`), a path embeds that prebuilt library. Under clippy nothing is built (the bytes
//! do not matter to a lint).

use std::env;
use std::path::{Path, PathBuf};
use std::process::Command;

fn main() {
    println!("cargo:rerun-if-env-changed=STLJIT_FMU_RUNTIME");
    println!("cargo:rerun-if-changed=build.rs");
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    let dest = out.join("fmu-runtime.bin");
    let (ext, platform) = platform();
    let note =
        |s: &str| std::fs::write(out.join("fmu-runtime.note"), s).expect("OUT_DIR is writable");
    let under_clippy = env::var("RUSTC_WORKSPACE_WRAPPER").is_ok_and(|w| w.contains("clippy"));
    match env::var("STLJIT_FMU_RUNTIME") {
        Ok(v) if v == "skip" => {
            std::fs::write(&dest, b"").expect("OUT_DIR is writable");
            note("STLJIT_FMU_RUNTIME=skip");
        }
        Ok(path) => {
            println!("cargo:rerun-if-changed={path}");
            std::fs::copy(&path, &dest)
                .unwrap_or_else(|e| panic!("STLJIT_FMU_RUNTIME={path}: {e}"));
            note(&format!("STLJIT_FMU_RUNTIME={path}"));
        }
        Err(_) if under_clippy => {
            std::fs::write(&dest, b"").expect("OUT_DIR is writable");
            note("built under clippy");
        }
        Err(_) => {
            let lib = nested_build(&out, ext);
            std::fs::copy(&lib, &dest)
                .unwrap_or_else(|e| panic!("cannot copy {}: {e}", lib.display()));
            note("");
        }
    }
    println!("cargo:rustc-env=STLJIT_FMU_PLATFORM={platform}");
    println!("cargo:rustc-env=STLJIT_FMU_LIBRARY_EXTENSION={ext}");
}

/// The library extension and the FMI 2.0 platform folder of the target.
fn platform() -> (&'static str, &'static str) {
    let os = env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    let bits = env::var("CARGO_CFG_TARGET_POINTER_WIDTH").unwrap_or_default();
    match (os.as_str(), bits.as_str()) {
        ("windows", "32") => ("dll", "win32"),
        ("windows", _) => ("dll", "win64"),
        ("macos", _) => ("dylib", "darwin64"),
        (_, "32") => ("so", "linux32"),
        _ => ("so", "linux64"),
    }
}

fn nested_build(out: &Path, ext: &str) -> PathBuf {
    let manifest_dir = PathBuf::from(env::var_os("CARGO_MANIFEST_DIR").expect("set by cargo"));
    let root = manifest_dir
        .parent()
        .and_then(Path::parent)
        .expect("crates/fmu-embed sits two levels below the workspace root");
    // OUT_DIR is <target>[/<triple>]/<profile>/build/<pkg>-<hash>/out.
    let target_dir = out
        .ancestors()
        .nth(4)
        .map_or_else(|| out.join("fmu-runtime"), |t| t.join("fmu-runtime"));
    for dir in ["crates", "Cargo.toml", "Cargo.lock"] {
        println!("cargo:rerun-if-changed={}", root.join(dir).display());
    }
    let cargo = env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let mut cmd = Command::new(cargo);
    cmd.current_dir(root)
        .args(["build", "--release", "-p", "stljit-fmu-runtime", "--lib"])
        .arg("--target-dir")
        .arg(&target_dir)
        // The FMU's binary is shipped: no debug info, no static symbol table (the fmi2
        // functions stay in the dynamic symbol table).
        .env("CARGO_PROFILE_RELEASE_DEBUG", "0")
        .env("CARGO_PROFILE_RELEASE_STRIP", "symbols")
        .env_remove("CARGO_TARGET_DIR")
        .env_remove("CARGO_BUILD_TARGET_DIR")
        .env_remove("RUSTC_WORKSPACE_WRAPPER");
    if let Ok(target) = env::var("TARGET")
        && env::var("HOST").is_ok_and(|h| h != target)
    {
        cmd.args(["--target", &target]);
    }
    let status = cmd
        .status()
        .unwrap_or_else(|e| panic!("cannot run cargo for the FMU runtime: {e}"));
    assert!(
        status.success(),
        "building stljit-fmu-runtime failed (set STLJIT_FMU_RUNTIME=skip to build stljit \
         without an embedded FMU runtime)"
    );
    let triple_dir = match env::var("TARGET") {
        Ok(t) if env::var("HOST").is_ok_and(|h| h != t) => target_dir.join(t),
        _ => target_dir,
    };
    let prefix = if ext == "dll" { "" } else { "lib" };
    triple_dir
        .join("release")
        .join(format!("{prefix}stljit_fmu_runtime.{ext}"))
}
