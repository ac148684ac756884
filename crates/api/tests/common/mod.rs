//! What the API's test files share: both engines, and a PLC compiled from one STL text.

use stljit_api::{EngineKind, Options, Plc, Project};

/// The engines every API test runs on.
pub(crate) const ENGINES: [EngineKind; 2] = [EngineKind::Jit, EngineKind::Interp];

/// A PLC of `text` (one file, `t.stl`) on `engine`, with the default options otherwise.
pub(crate) fn plc(text: &str, engine: EngineKind) -> Plc {
    let project = Project::new().text("t.stl", text);
    let options = Options {
        engine,
        ..Options::default()
    };
    Plc::compile(&project, &options).expect("compiles")
}
