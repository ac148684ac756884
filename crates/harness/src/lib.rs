//! Shared helpers for the integration tests under `tests/` and the benches under `benches/`.
//! The package exists so that the workspace root can stay a virtual manifest while test data,
//! tests and benches live at the top level where a reader looks for them.

/// Absolute path of the repository root (where `tests/`, `benches/` and `examples/` live).
pub fn repo_root() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}
