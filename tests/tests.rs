//! The workspace's single integration-test binary. Each module covers one test area and
//! discovers its cases from data files under `tests/`, so a new case is a new file.

mod conformance;
mod corpus;
mod demo_station;
mod diagnostics;
mod examples;
mod fuzz_smoke;
mod inputs;
mod ir_text;
mod mutate;
mod omron_text;
mod regressions;
mod stimulus_hardware;
mod tidy;
