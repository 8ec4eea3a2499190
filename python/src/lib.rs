//! `softgrip._softgrip`: the Python bindings of the softgrip core.
//!
//! Thin by design: every number comes from the Rust core (`softgrip`), computed the way
//! `host-sim fls` and `host-sim required-force` compute it, so the Python answers equal the
//! command line's JSON. The Python package (`softgrip/__init__.py`) only turns lists into
//! numpy arrays and broadcasts array arguments.

#![forbid(unsafe_code)]

mod calibrate;
mod config;
mod controller;
mod rule;
mod surface;

use config::*;
use controller::*;
use rule::*;
use surface::*;

use pyo3::create_exception;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use softgrip::contact::ContactSize;
use softgrip::controller::{
    Controller as CoreController, ControllerConfig, FingerShape, Libm, Measurement, Mode,
    SkewParams, SlipSignal, Status, TickOutput,
};
use softgrip::fls::{EllipseFit, InscribedEllipse, RadialGap};
use softgrip::{
    BuildError, ConfigError as CoreConfigError, FlsConfig, FlsModel, FlsTable, QuadratureOrder,
    RangeOverflow,
};

create_exception!(
    softgrip,
    ConfigError,
    PyValueError,
    "A bad argument: a ValueError whose `param` attribute names the parameter."
);

/// Largest `samples` of `fls` (as `host-sim fls`).
const MAX_SAMPLES: usize = 4096;

/// A `ConfigError` (a `ValueError`) with `param` set and the given text.
fn bad(py: Python<'_>, param: &str, text: String) -> PyErr {
    let err = ConfigError::new_err(text);
    // Setting an attribute on a fresh exception instance cannot fail in practice; if it
    // did, the error would still carry the parameter's name in its text.
    let _ = err.value(py).setattr("param", param);
    err
}

/// The core's error, its parameter renamed to the Python keyword `rename` gives, then its
/// reason.
fn core_err(py: Python<'_>, e: CoreConfigError, rename: fn(&'static str) -> &'static str) -> PyErr {
    let name = rename(e.param());
    bad(py, name, format!("{name}: {}", e.reason()))
}

fn same(p: &'static str) -> &'static str {
    p
}

/// The `Controller` keyword of a core parameter: its `ControllerConfig` field
/// ([`softgrip::error::field_of`]; the skew law's `skew`, `alpha` and `locus` keep theirs).
fn field_name(p: &'static str) -> &'static str {
    softgrip::error::field_of(p)
}

fn finite(py: Python<'_>, name: &str, v: f64) -> PyResult<f64> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(bad(py, name, format!("{name}: must be a finite number")))
    }
}

fn shape_of(py: Python<'_>, s: &str) -> PyResult<FingerShape> {
    FingerShape::from_name(s).ok_or_else(|| {
        bad(
            py,
            "shape",
            format!("shape: {s:?} is not a shape, expected \"rect\" or \"disc\""),
        )
    })
}

fn mode_of(py: Python<'_>, s: &str) -> PyResult<Mode> {
    Mode::from_name(s).ok_or_else(|| {
        bad(
            py,
            "mode",
            format!("mode: {s:?} is not a mode, expected \"ellipse\" or \"table\""),
        )
    })
}

/// The defaults of `ControllerConfig`, as a dict.
#[pyfunction]
fn default_config(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
    config_dict(py, &ControllerConfig::default())
}

/// Contact half-width `a = c·N^γ` [m] at normal force `normal_force_n` [N].
#[pyfunction]
fn half_width(
    py: Python<'_>,
    c_m_per_n_gamma: f64,
    gamma: f64,
    normal_force_n: f64,
) -> PyResult<f64> {
    let contact =
        ContactSize::<f64>::new(c_m_per_n_gamma, gamma).map_err(|e| core_err(py, e, rf_name))?;
    Ok(contact.half_width_m(normal_force_n))
}

#[pymodule]
fn _softgrip(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(fls, m)?)?;
    m.add_function(wrap_pyfunction!(required_force, m)?)?;
    m.add_function(wrap_pyfunction!(default_config, m)?)?;
    m.add_function(wrap_pyfunction!(half_width, m)?)?;
    m.add_function(wrap_pyfunction!(calibrate::calibrate, m)?)?;
    m.add_class::<Controller>()?;
    m.add_class::<TickStatus>()?;
    m.add("ConfigError", m.py().get_type::<ConfigError>())?;
    m.add("CONFIG_FIELDS", PyTuple::new(m.py(), FIELDS)?)?;
    Ok(())
}
