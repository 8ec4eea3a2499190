//! What can go wrong in a calibration, each error naming where: the file, line and column
//! of a bad value, the expected header, the minimum number of rows, the file whose record
//! of the rig a setting contradicts.

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
    /// A file whose first line (after blank and comment lines) is not the expected header.
    Header {
        /// The file's name.
        file: String,
        /// Its 1-based line.
        line: usize,
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
    /// A setting that contradicts what a lab file records of the rig (`# shape = ...`,
    /// `# half_length_m = ...`), or two files that record different values.
    Contradiction {
        /// The setting: `shape` or `half_length_m`.
        setting: &'static str,
        /// The value given.
        given: String,
        /// Where it was given: `None` for the caller's setting, else the file that
        /// records it.
        given_in: Option<String>,
        /// The file that records another value.
        file: String,
        /// The value it records.
        recorded: String,
    },
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
                line,
                expected,
                found,
            } => write!(
                f,
                "{file}:{line}: the header must be `{expected}` (found `{found}`)"
            ),
            Self::TooFew { file, needed } => write!(f, "{file}: {needed}"),
            Self::Setting(m) => f.write_str(m),
            Self::Contradiction {
                setting,
                given,
                given_in: None,
                file,
                recorded,
            } => write!(
                f,
                "{setting}: {given} was given, but {file} records the rig's {setting} = \
                 {recorded}: leave the setting out to use the file's, or correct the file"
            ),
            Self::Contradiction {
                setting,
                given,
                given_in: Some(first),
                file,
                recorded,
            } => write!(
                f,
                "{setting}: {first} records {given}, but {file} records {recorded}: the files \
                 are of different rigs"
            ),
        }
    }
}

impl std::error::Error for CalibError {}
