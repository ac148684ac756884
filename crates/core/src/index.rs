//! Newtype indices. Each is a `u32`/`u16` wrapper so that a timer number can never be used where an
//! edge slot is meant; `Display` prints them the way the IR text does.

use std::fmt;

macro_rules! newtype_index {
    ($(#[$doc:meta])* $name:ident($repr:ty), $prefix:literal) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
        pub struct $name(pub $repr);

        impl $name {
            /// The index as a `usize`, for indexing vectors.
            #[inline]
            pub fn index(self) -> usize {
                self.0 as usize
            }

            /// Builds the index from a `usize` position.
            ///
            /// # Panics
            /// If `i` does not fit the underlying integer (a compiler bug, never user input).
            #[inline]
            pub fn new(i: usize) -> Self {
                Self(<$repr>::try_from(i).expect(concat!(stringify!($name), " overflow")))
            }
        }

        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, concat!($prefix, "{}"), self.0)
            }
        }
    };
}

newtype_index!(
    /// A program organisation unit (main program, subroutine) within [`crate::ir::Program::pous`].
    PouId(u32), "pou"
);
newtype_index!(
    /// An instruction within one POU's [`crate::ir::Pou::ops`].
    OpIdx(u32), "op"
);
newtype_index!(
    /// A jump label within one POU, index into [`crate::ir::Pou::labels`].
    LabelId(u32), "L"
);
newtype_index!(
    /// A static edge-memory slot (one per EU/ED instruction), byte `slot` of the edge area.
    EdgeSlot(u16), "edge"
);
newtype_index!(
    /// A timer number (`T37` is `TimerId(37)`).
    TimerId(u16), "T"
);
newtype_index!(
    /// A counter number (`C5` is `CounterId(5)`).
    CounterId(u16), "C"
);
newtype_index!(
    /// A source file of a project, index into [`crate::ir::Program::files`].
    FileId(u32), "file"
);
