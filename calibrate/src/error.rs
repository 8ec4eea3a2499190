//! What can go wrong in a calibration, each error naming where: the file, line and column
//! of a bad value, the expected header, the minimum number of rows.

use std::fmt;

/// A calibration that could not be made.
#[derive(Debug, Clone, PartialEq)]
pub enum CalibError {
    /// A value that is not a number, or not a valid one (`file:line:column: why`). Lines
    /// and columns count from 1; the column is the field's position in the row.
    Cell {
        /// The file's name as the user gave it.
        file: String,
        /// 1-based line.
        line: usize,
        /// 1-based field number.
        column: usize,
        /// What is wrong with it.
        message: String,
    },
    /// A file whose first line is not the expected header.
    Header {
        /// The file's name.
        file: String,
        /// The header the file must start with.
        expected: &'static str,
        /// The first line it has (shortened).
        found: String,
    },
    /// Too few rows to fit, with the minimum.
    TooFew {
        /// The file's name.
        file: String,
        /// What is needed, e.g. "indentation needs at least 3 rows".
        needed: String,
    },
    /// A setting out of its range (the half-length, a parameter of the core).
    Setting(String),
}

impl fmt::Display for CalibError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Cell {
                file,
                line,
                column,
                message,
            } => write!(f, "{file}:{line}:{column}: {message}"),
            Self::Header {
                file,
                expected,
                found,
            } => write!(
                f,
                "{file}:1: the header must be `{expected}` (found `{found}`)"
            ),
            Self::TooFew { file, needed } => write!(f, "{file}: {needed}"),
            Self::Setting(m) => f.write_str(m),
        }
    }
}

impl std::error::Error for CalibError {}
