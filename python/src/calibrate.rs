//! `calibrate`: the finger's parameters fitted to lab files, by the same code as
//! `host-sim calibrate` (the crate `softgrip-calibrate`).

use crate::*;
use softgrip_calibrate::finger_toml::{finger_toml, source_name};
use softgrip_calibrate::lab_csv::{read_indentation, read_slip};
use softgrip_calibrate::margin_csv::{parse_cyclic, parse_hold};
use softgrip_calibrate::margins::{fit_cyclic, fit_hold, margins_toml, Margins, Report};
use softgrip_calibrate::{CalibError, Setup};

/// Largest lab file read [bytes], as `host-sim calibrate`.
const CSV_CAP_BYTES: u64 = 64 << 20;

fn read(py: Python<'_>, param: &str, path: &std::path::Path) -> PyResult<(String, String)> {
    let name = path.display().to_string();
    let size = std::fs::metadata(path)
        .map_err(|e| bad(py, param, format!("{param}: {name}: {e}")))?
        .len();
    if size > CSV_CAP_BYTES {
        return Err(bad(
            py,
            param,
            format!("{param}: {name}: {size} bytes, more than the {CSV_CAP_BYTES} read"),
        ));
    }
    let text = std::fs::read_to_string(path)
        .map_err(|e| bad(py, param, format!("{param}: {name}: {e}")))?;
    Ok((name, text))
}

/// A calibration error as a `ConfigError` whose `param` is the file's keyword.
fn calib_err(py: Python<'_>, e: CalibError, ind_name: &str) -> PyErr {
    let param = match &e {
        CalibError::Cell { file, .. }
        | CalibError::Header { file, .. }
        | CalibError::TooFew { file, .. } => {
            if file == ind_name {
                "indentation"
            } else {
                "slip"
            }
        }
        CalibError::Setting(_) => "half_length_m",
        CalibError::Contradiction { setting, .. } => setting,
    };
    bad(py, param, e.to_string())
}

/// The margins of the margin protocols' files, when given (`cyclic`, `hold`: their
/// keywords name them in errors).
fn margins(
    py: Python<'_>,
    cyclic: Option<std::path::PathBuf>,
    hold: Option<std::path::PathBuf>,
    shape: softgrip::controller::FingerShape,
) -> PyResult<Margins> {
    let mut m = Margins::none();
    if let Some(path) = cyclic {
        let (name, text) = read(py, "cyclic", &path)?;
        let rows = parse_cyclic(&name, &text).map_err(|e| bad(py, "cyclic", e.to_string()))?;
        m.cyclic = fit_cyclic(&name, &rows).map_err(|e| bad(py, "cyclic", e.to_string()))?;
    }
    if let Some(path) = hold {
        let (name, text) = read(py, "hold", &path)?;
        let rows = parse_hold(&name, &text).map_err(|e| bad(py, "hold", e.to_string()))?;
        m.hold = fit_hold(&name, &rows, shape).map_err(|e| bad(py, "hold", e.to_string()))?;
    }
    Ok(m)
}

/// Fits the finger to the two lab files, and its margins to the margin protocols' files
/// when given; returns `(report JSON, finger TOML)`.
#[pyfunction]
#[pyo3(signature = (indentation, slip, *, shape = None, half_length_m = None, conservative = false, friction_contact = false, cyclic = None, hold = None))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn calibrate(
    py: Python<'_>,
    indentation: std::path::PathBuf,
    slip: std::path::PathBuf,
    shape: Option<&str>,
    half_length_m: Option<f64>,
    conservative: bool,
    friction_contact: bool,
    cyclic: Option<std::path::PathBuf>,
    hold: Option<std::path::PathBuf>,
) -> PyResult<(String, String)> {
    if conservative && friction_contact {
        return Err(bad(
            py,
            "friction_contact",
            "conservative values are the joint fit's: conservative and friction_contact \
             cannot both be set"
                .to_string(),
        ));
    }
    let shape = shape.map(|s| shape_of(py, s)).transpose()?;
    let half_length_m = half_length_m
        .map(|l| finite(py, "half_length_m", l))
        .transpose()?;
    let (ind_name, ind_text) = read(py, "indentation", &indentation)?;
    let (slip_name, slip_text) = read(py, "slip", &slip)?;
    let err = |e| calib_err(py, e, &ind_name);
    let (ind, ind_rig) = read_indentation(&ind_name, &ind_text).map_err(err)?;
    let (onsets, slip_rig) = read_slip(&slip_name, &slip_text).map_err(err)?;
    let resolved = Setup::resolve(
        shape,
        half_length_m,
        &[(&ind_name, ind_rig), (&slip_name, slip_rig)],
    )
    .map_err(err)?;
    let setup = resolved.setup;
    let fitted_margins = margins(py, cyclic, hold, setup.shape)?;
    let fitted = softgrip_calibrate::calibrate(&setup, &ind_name, &ind, &slip_name, &onsets)
        .map_err(err)?
        .noting_defaults(&resolved);
    let fitted = if friction_contact {
        fitted
            .with_friction_contact(&slip_name, &onsets)
            .map_err(|e| bad(py, "slip", e.to_string()))?
    } else {
        fitted
    };
    let (cal, m) = if conservative {
        (fitted.conservative(), fitted_margins.conservative())
    } else {
        (fitted, fitted_margins)
    };
    let report = Report {
        calibration: &cal,
        margins: &m,
        safety_for_mu: cal.safety_for_mu(),
    };
    let heading = format!("{} and {}", source_name(&indentation), source_name(&slip));
    let json = serde_json::to_string(&report).map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok((
        json,
        finger_toml(&cal, &heading) + &margins_toml(&m, setup.shape),
    ))
}
