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
