//! The reference interpreter (work in progress).
