//! The parser's error: what is wrong with an IR text, and the line and column where.

use super::VERSION;
use std::fmt;

/// Why a text is not an IR program, and where: 1-based line and column (in characters).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ParseError {
    /// The line, 1-based.
    pub line: u32,
    /// The column (in characters), 1-based; one past the line's end for "missing" errors.
    pub col: u32,
    /// What is wrong.
    pub kind: ParseErrorKind,
}

/// What is wrong with an IR text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ParseErrorKind {
    /// Something else was expected here (`found` is the word, or "end of line").
    Expected {
        /// What the grammar allows here.
        expected: &'static str,
        /// What the text has.
        found: String,
    },
    /// The field `key=...` was expected here (fields come in a fixed order).
    Field {
        /// The field's name.
        key: &'static str,
        /// What the text has.
        found: String,
    },
    /// A word that names nothing of its kind (an unknown op, area, enum variant or profile).
    Unknown {
        /// The kind of name.
        what: &'static str,
        /// The word.
        word: String,
    },
    /// Not a decimal (or `0x` hexadecimal) number, or out of the field's range.
    Number {
        /// The field.
        what: &'static str,
        /// The word.
        word: String,
    },
    /// A positional index out of sequence (`op4` where the fifth op is `op5`, `edge2` after
    /// `edge0`).
    Index {
        /// The index the position has.
        expected: String,
        /// The index the text gives.
        found: String,
    },
    /// A declaration that may appear once appears again.
    Duplicate(&'static str),
    /// Something required is missing (the header, the profile, a closing `}`).
    Missing(&'static str),
    /// A malformed string literal.
    String(&'static str),
    /// An op without a source location followed by one with a location: locations are a
    /// prefix of the ops.
    LocationGap,
    /// The text's format version is not [`VERSION`].
    Version(String),
}

impl fmt::Display for ParseErrorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ParseErrorKind::Expected { expected, found } => {
                write!(f, "expected {expected}, found {found}")
            }
            ParseErrorKind::Field { key, found } => {
                write!(f, "expected the field `{key}=...`, found {found}")
            }
            ParseErrorKind::Unknown { what, word } => write!(f, "unknown {what} `{word}`"),
            ParseErrorKind::Number { what, word } => {
                write!(f, "`{word}` is not a valid {what}")
            }
            ParseErrorKind::Index { expected, found } => {
                write!(
                    f,
                    "index `{found}` out of sequence: this position is `{expected}`"
                )
            }
            ParseErrorKind::Duplicate(what) => write!(f, "{what} given twice"),
            ParseErrorKind::Missing(what) => write!(f, "missing {what}"),
            ParseErrorKind::String(why) => write!(f, "bad string: {why}"),
            ParseErrorKind::LocationGap => f.write_str(
                "an op with a source location follows one without (locations are a prefix)",
            ),
            ParseErrorKind::Version(v) => {
                write!(
                    f,
                    "format version `{v}` is not supported (this reader reads {VERSION})"
                )
            }
        }
    }
}

impl fmt::Display for ParseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "line {}, column {}: {}", self.line, self.col, self.kind)
    }
}

impl std::error::Error for ParseError {}

/// The parser's result.
pub(super) type Result<T> = std::result::Result<T, ParseError>;

/// An error at a place.
pub(super) fn error(line: u32, col: u32, kind: ParseErrorKind) -> ParseError {
    ParseError { line, col, kind }
}
