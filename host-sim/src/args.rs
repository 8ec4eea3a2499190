//! Argument types more than one command takes.

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use clap::{Args, ValueEnum};
use softgrip::controller::FingerShape;

/// `--shape`: the core's [`FingerShape`] by its name, with the valid names, their meaning
/// and clap's suggestions in errors and `--help`.
pub fn shape_parser() -> impl TypedValueParser<Value = FingerShape> {
    PossibleValuesParser::new(FingerShape::ALL.map(|s| {
        PossibleValue::new(s.name()).help(match s {
            FingerShape::Rect => "Hemicylindrical fingertip: rectangular patch `[-l, l] × [-a, a]`",
            FingerShape::Disc => "Hemispherical fingertip: disc of radius `a`",
        })
    }))
    // Only the names above get here.
    .map(|name| FingerShape::from_name(&name).unwrap_or(FingerShape::Rect))
}

/// Arithmetic of a command's computation: the sweep (`fls`), the grid and solver
/// (`required-force`), the tables' precomputation (`tables`; the tables themselves are
/// f32).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Precision {
    /// Double precision (default).
    F64,
    /// Single precision, as on the Cortex-M4F (the firmware's tick).
    F32,
}

/// The fingertip's contact patch and pressure, as `fls` and `required-force` take them:
/// the shape, the pressure exponent and the skew law of the pressure peak (Eq. 16, 17).
#[derive(Debug, Clone, Copy, Args)]
pub struct PatchArgs {
    /// Patch shape.
    #[arg(long, value_parser = shape_parser(), default_value = "rect")]
    pub shape: FingerShape,
    /// Pressure exponent k >= 1 (`inf` for uniform pressure).
    #[arg(long, default_value_t = 2.0)]
    pub k: f64,
    /// Largest skew of the pressure peak, Δ/a in [0, 1); 0 is the symmetric profile.
    #[arg(long, default_value_t = 0.0)]
    pub skew: f64,
    /// Rate α of the skew law Δy = Δ·tanh(α d_c/a).
    #[arg(long, default_value_t = 1.1)]
    pub alpha: f64,
    /// Half-axis h/a of the peak's locus (Eq. 16); default Δ/2, the paper's circular path.
    #[arg(long)]
    pub locus: Option<f64>,
}

/// `--link`: where softgrip's device loop runs, as `simulate` and `bench` take it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum LinkName {
    /// The firmware loop on a thread of its own, over a pseudo-terminal (also
    /// `inprocess`).
    #[value(alias = "inprocess")]
    Pty,
    /// The same loop and bytes through memory, on the calling thread.
    Direct,
    /// The Cortex-M4F firmware in QEMU, over its USART (`simulate` only).
    Qemu,
    /// The firmware on a board, over the serial port `--port` (`simulate` only).
    Serial,
}

impl LinkName {
    /// The name, as `--link` takes it and bench.json records it.
    pub fn name(self) -> &'static str {
        match self {
            Self::Pty => "pty",
            Self::Direct => "direct",
            Self::Qemu => "qemu",
            Self::Serial => "serial",
        }
    }
}
