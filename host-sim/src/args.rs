//! Argument types more than one command takes.

use clap::ValueEnum;

/// Patch shape on the command line.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ShapeArg {
    /// Hemicylindrical fingertip: rectangular patch `[-l, l] × [-a, a]`.
    Rect,
    /// Hemispherical fingertip: disc of radius `a`.
    Disc,
}

/// Arithmetic of a command's computation: the sweep (`fls`), the grid and solver
/// (`required-force`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Precision {
    /// Double precision (default).
    F64,
    /// Single precision, as on the Cortex-M4F (the firmware's tick).
    F32,
}
