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
use softgrip_calibrate::finger_toml::{finger_toml, report_text, source_name};
use softgrip_calibrate::lab_csv::{read_indentation, read_slip, Indentation, SlipOnset};
use softgrip_calibrate::margins::{margins_text, margins_toml};
use softgrip_calibrate::{calibrate, CalibError, ResolvedSetup, Setup};
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
    /// Finger shape [default: the one the files record (`# shape = ...`), else rect]; one
    /// that contradicts the files' is refused.
    #[arg(long, value_parser = shape_parser())]
    shape: Option<FingerShape>,
    // host-sim/tests/calibrate_contradiction.rs::the_files_record_the_rig_and_a_contradicting_flag_is_refused
    /// Half-length l of the rectangular patch [m] (measured, not fitted) [default: the one
    /// the files record (`# half_length_m = ...`), else 0.01]; one that contradicts the
    /// files' is refused.
    #[arg(long)]
    half_length: Option<f64>,
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

/// A calibration error as the CLI says it: a setting that contradicts a file by its flag.
fn calib_error(e: CalibError) -> CliError {
    match e {
        CalibError::Contradiction {
            setting,
            given,
            given_in: None,
            file,
            recorded,
        } => {
            let flag = if setting == "shape" {
                "--shape"
            } else {
                "--half-length"
            };
            CliError::Usage(format!(
                "{flag} {given} contradicts {file}, which records the rig's {setting} = \
                 {recorded}: leave {flag} out to use the file's, or correct the file"
            ))
        }
        e => CliError::Usage(e.to_string()),
    }
}

/// The lab files' names and rows, and the setup: the flags', else the files' record of
/// the rig, else the default.
type Lab = (
    (String, Vec<Indentation>),
    (String, Vec<SlipOnset>),
    ResolvedSetup,
);

fn lab(args: &CalibrateArgs) -> Result<Lab, CliError> {
    if let Some(l) = args.half_length.filter(|l| !(*l > 0.0 && l.is_finite())) {
        return Err(CliError::Usage(format!(
            "--half-length: {} must be a finite length > 0 [m]",
            short_num(l)
        )));
    }
    let (ind_name, ind_text) = read(&args.indentation, "--indentation")?;
    let (slip_name, slip_text) = read(&args.slip, "--slip")?;
    let (ind, ind_rig) = read_indentation(&ind_name, &ind_text).map_err(calib_error)?;
    let (slip, slip_rig) = read_slip(&slip_name, &slip_text).map_err(calib_error)?;
    let resolved = Setup::resolve(
        args.shape,
        args.half_length,
        &[(&ind_name, ind_rig), (&slip_name, slip_rig)],
    )
    .map_err(calib_error)?;
    Ok(((ind_name, ind), (slip_name, slip), resolved))
}

/// Runs the calibration.
pub fn run(args: &CalibrateArgs) -> Result<(), CliError> {
    let ((ind_name, ind), (slip_name, slip), resolved) = lab(args)?;
    let shape = resolved.setup.shape;
    let fitted_margins = margins::fit(args.cyclic.as_ref(), args.hold.as_ref(), shape)?;
    let joint = calibrate(&resolved.setup, &ind_name, &ind, &slip_name, &slip)
        .map_err(calib_error)?
        .noting_defaults(&resolved);
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
    for w in &cal.warnings {
        eprintln!("warning: {w}");
    }
    match args.format {
        Format::Text => print!("{}{}", report_text(&cal), margins_text(&m, shape)),
        Format::Json => println!("{}", margins::json(&cal, &m)?),
    }
    if let Some(out) = &args.out {
        let heading = format!(
            "{} and {}",
            source_name(&args.indentation),
            source_name(&args.slip)
        );
        let toml = finger_toml(&cal, &heading) + &margins_toml(&m, shape);
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
