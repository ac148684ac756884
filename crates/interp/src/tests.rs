//! Interpreter unit tests (see the `tests/` submodules).
