//! The margins of `calibrate` (`--cyclic`, `--hold`): the margin protocols' files read and
//! fitted (`softgrip_calibrate::margins`), and the JSON report with them
//! (`softgrip_calibrate::margins::Report`, as Python's).

use super::{calib_error, read};
use crate::CliError;
use softgrip::controller::FingerShape;
use softgrip_calibrate::margin_csv::{parse_cyclic, parse_hold};
use softgrip_calibrate::margins::{fit_cyclic, fit_hold, Margins, Report};
use softgrip_calibrate::Calibration;
use std::path::PathBuf;

/// The margins the given files measure (each absent one "not measured").
pub fn fit(
    cyclic: Option<&PathBuf>,
    hold: Option<&PathBuf>,
    shape: FingerShape,
) -> Result<Margins, CliError> {
    let mut m = Margins::none();
    if let Some(path) = cyclic {
        let (name, text) = read(path, "--cyclic")?;
        let rows = parse_cyclic(&name, &text).map_err(calib_error)?;
        m.cyclic = fit_cyclic(&name, &rows).map_err(calib_error)?;
    }
    if let Some(path) = hold {
        let (name, text) = read(path, "--hold")?;
        let rows = parse_hold(&name, &text).map_err(calib_error)?;
        m.hold = fit_hold(&name, &rows, shape).map_err(calib_error)?;
    }
    Ok(m)
}

/// The calibration and its margins as one JSON object.
pub fn json(cal: &Calibration, margins: &Margins) -> Result<String, CliError> {
    serde_json::to_string_pretty(&Report {
        calibration: cal,
        margins,
        safety_for_mu: cal.safety_for_mu(),
    })
    .map_err(|e| CliError::Failed(e.to_string()))
}
