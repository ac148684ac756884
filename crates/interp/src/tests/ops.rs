//! Instruction groups: stack edge cases, boxes with flags and error paths, immediate I/O.
