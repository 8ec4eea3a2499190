//! `host-sim calibrate`: fits the finger's parameters to a lab's indentation and slip
//! files (softgrip-calibrate, docs/calibration.md) and reports them, writes the finger
//! TOML and plots the onsets against the fitted surface.

mod margins;
mod plot;

use crate::args::shape_parser;
use crate::input::{read_capped_text, short_num};
use crate::CliError;
use clap::{Args, ValueEnum};
use softgrip::controller::FingerShape;
use softgrip_calibrate::finger_toml::{finger_toml, report_text};
use softgrip_calibrate::lab_csv::{parse_indentation, parse_slip};
use softgrip_calibrate::margins::{margins_text, margins_toml};
use softgrip_calibrate::{calibrate, CalibError, Setup};
use std::path::{Path, PathBuf};

/// Largest lab file \[bytes\] (a million rows of three numbers is about 40 MiB).
pub const CSV_CAP_BYTES: u64 = 64 << 20;

/// Output format of `calibrate`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Format {
    /// One line per parameter for people.
    Text,
    /// One JSON object: each parameter under its finger-TOML name as
    /// {"value", "ci95", "identified", "reason"}.
    Json,
}

/// Arguments of `host-sim calibrate`.
#[derive(Debug, Args)]
pub struct CalibrateArgs {
    /// Indentation CSV (normal_force_n,half_width_m).
    #[arg(long)]
    indentation: PathBuf,
    /// Slip-onset CSV (normal_force_n,tangential_force_n,torsional_moment_nm).
    #[arg(long)]
    slip: PathBuf,
    /// Finger shape.
    #[arg(long, value_parser = shape_parser(), default_value = "rect")]
    shape: FingerShape,
    /// Half-length l of the rectangular patch [m] (measured, not fitted).
    #[arg(long, default_value_t = 0.01)]
    half_length: f64,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    format: Format,
    // host-sim/tests/calibrate_cli.rs::conservative_moves_each_parameter_toward_less_capacity.
    /// Report and write every parameter at the end of its 95 % interval that lowers the
    /// required-force rule's capacity (docs/calibration.md).
    #[arg(long, conflicts_with = "friction_contact")]
    conservative: bool,
    /// After the joint fit, take mu from the pure-force onsets alone and refit the
    /// contact scale c (on a long hemicylinder, the half-length) to the torsion onsets:
    /// the contact friction sees, for a finger whose pressure the model does not
    /// describe (docs/calibration.md, "The contact friction sees").
    #[arg(long)]
    friction_contact: bool,
    /// Write the finger TOML ([finger], and [effect.skewed_pressure] if skewed) here.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Plot the onsets against the fitted surface at several forces, and the residuals.
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Cyclic-load CSV (host-sim experiment cyclic): the cyclic share, and cyclic_factor
    /// in [margins].
    #[arg(long)]
    cyclic: Option<PathBuf>,
    /// Sustained-load CSV (host-sim experiment hold): the hold shares, a disc's
    /// disc_torsion_factor in [margins] and the least safety·steady_factor.
    #[arg(long)]
    hold: Option<PathBuf>,
}

fn read(path: &Path, flag: &str) -> Result<(String, String), CliError> {
    let text =
        read_capped_text(path, flag, CSV_CAP_BYTES).map_err(|e| CliError::Usage(e.to_string()))?;
    Ok((path.display().to_string(), text))
}

fn calib_error(e: CalibError) -> CliError {
    CliError::Usage(e.to_string())
}

/// Runs the calibration.
pub fn run(args: &CalibrateArgs) -> Result<(), CliError> {
    let l = args.half_length;
    if !(l > 0.0 && l.is_finite()) {
        return Err(CliError::Usage(format!(
            "--half-length: {} must be a finite length > 0 [m]",
            short_num(l)
        )));
    }
    let (ind_name, ind_text) = read(&args.indentation, "--indentation")?;
    let (slip_name, slip_text) = read(&args.slip, "--slip")?;
    let ind = parse_indentation(&ind_name, &ind_text).map_err(calib_error)?;
    let slip = parse_slip(&slip_name, &slip_text).map_err(calib_error)?;
    let fitted_margins = margins::fit(args.cyclic.as_ref(), args.hold.as_ref(), args.shape)?;
    let setup = Setup {
        shape: args.shape,
        half_length_m: l,
    };
    let joint = calibrate(&setup, &ind_name, &ind, &slip_name, &slip).map_err(calib_error)?;
    let fitted = if args.friction_contact {
        joint
            .with_friction_contact(&slip_name, &slip)
            .map_err(calib_error)?
    } else {
        joint
    };
    let cal = if args.conservative {
        fitted.conservative()
    } else {
        fitted.clone()
    };
    let m = if args.conservative {
        fitted_margins.conservative()
    } else {
        fitted_margins
    };
    match args.format {
        Format::Text => print!("{}{}", report_text(&cal), margins_text(&m, args.shape)),
        Format::Json => println!("{}", margins::json(&cal, &m)?),
    }
    if let Some(out) = &args.out {
        let toml = finger_toml(&cal, &format!("{ind_name} and {slip_name}"))
            + &margins_toml(&m, args.shape);
        std::fs::write(out, toml)
            .map_err(|e| CliError::Failed(format!("--out: {}: {e}", out.display())))?;
        eprintln!("wrote {}", out.display());
    }
    if let Some(path) = &args.plot {
        plot::fit(path, &fitted, &slip).map_err(|e| CliError::Failed(format!("--plot: {e}")))?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}
