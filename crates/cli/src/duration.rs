//! Durations on the command line (`10ms`, `1.5s`, `2m`, `24h`, `250`): the embedding API's
//! parser and printer, so every front door reads them alike.

pub(crate) use stljit_api::duration::{format_ms, parse_duration};
