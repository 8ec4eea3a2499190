//! `ControllerConfig` from Python keywords and back, and building the controller.
//!
//! The fields come from the struct itself: their names from `ControllerConfig::FIELDS`,
//! their values through its serde implementation (via a `toml::Value`, which, unlike
//! JSON, holds an infinite float). Only the three fields Python spells its own way are
//! written here: `shape` and `mode` (their names), `skew` (a number, tuple or dict).

use crate::*;
use toml::{Table, Value};

/// Every `ControllerConfig` field, in declaration order.
pub(crate) const FIELDS: &[&str] = ControllerConfig::FIELDS;

/// A plain field's value as serde reads it: a Python float or int, else a `TypeError`.
fn number(name: &str, v: &Bound<'_, PyAny>) -> PyResult<Value> {
    if v.is_instance_of::<pyo3::types::PyInt>() && !v.is_instance_of::<pyo3::types::PyBool>() {
        if let Ok(i) = v.extract::<i64>() {
            return Ok(Value::Integer(i));
        }
    }
    v.extract::<f64>()
        .map(Value::Float)
        .map_err(|_| PyTypeError::new_err(format!("{name}: expected a number")))
}

/// `cfg` as a table of its fields (serde; a `None` is left out).
fn table_of(cfg: &ControllerConfig) -> PyResult<Table> {
    Table::try_from(cfg).map_err(|e| PyValueError::new_err(format!("config: {e}")))
}

/// `cfg` with the plain field `key` set to `value`, through serde: a value the field's
/// type cannot hold (e.g. a count beyond `u16`) is a `ConfigError` naming `key`.
fn with_field(
    py: Python<'_>,
    cfg: &ControllerConfig,
    key: &str,
    value: Value,
) -> PyResult<ControllerConfig> {
    let mut table = table_of(cfg)?;
    table.insert(key.to_string(), value);
    let skew = cfg.skew;
    let out: ControllerConfig = Value::Table(table)
        .try_into()
        .map_err(|e: toml::de::Error| bad(py, key, format!("{key}: {}", e.message().trim())))?;
    // The table leaves `None` out, which serde reads as the default: put it back.
    Ok(ControllerConfig { skew, ..out })
}

fn real(name: &str, v: &Bound<'_, PyAny>) -> PyResult<f64> {
    v.extract()
        .map_err(|_| PyTypeError::new_err(format!("{name}: expected a number")))
}

/// `skew` as Python gives it: `None` (or 0), `Δ/a` (then `α = 1.1`, locus `Δ/2`), a tuple
/// `(Δ/a, α, h/a)` or a dict with those field names.
pub(crate) fn skew_of(v: &Bound<'_, PyAny>) -> PyResult<Option<SkewParams>> {
    if v.is_none() {
        return Ok(None);
    }
    if let Ok(d) = v.extract::<f64>() {
        if d == 0.0 {
            // No skew, as `--skew 0` on the command line.
            return Ok(None);
        }
        return Ok(Some(SkewParams {
            delta_over_a: d,
            alpha: 1.1,
            locus_over_a: d / 2.0,
        }));
    }
    if let Ok((d, a, h)) = v.extract::<(f64, f64, f64)>() {
        return Ok(Some(SkewParams {
            delta_over_a: d,
            alpha: a,
            locus_over_a: h,
        }));
    }
    if let Ok(dict) = v.cast::<PyDict>() {
        let get = |k: &str, default: Option<f64>| -> PyResult<f64> {
            match dict.get_item(k)? {
                Some(x) => real(k, &x),
                None => default.ok_or_else(|| PyTypeError::new_err(format!("skew: needs {k}"))),
            }
        };
        let d = get("delta_over_a", None)?;
        return Ok(Some(SkewParams {
            delta_over_a: d,
            alpha: get("alpha", Some(1.1))?,
            locus_over_a: get("locus_over_a", Some(d / 2.0))?,
        }));
    }
    Err(PyTypeError::new_err(
        "skew: expected None, a number (delta_over_a), a tuple (delta_over_a, alpha, \
         locus_over_a) or a dict with those keys",
    ))
}

/// `cfg` with the keywords applied; an unknown one is a `TypeError` naming it.
pub(crate) fn apply(
    py: Python<'_>,
    mut cfg: ControllerConfig,
    kwargs: Option<&Bound<'_, PyDict>>,
) -> PyResult<ControllerConfig> {
    let Some(kw) = kwargs else {
        return Ok(cfg);
    };
    for (key, v) in kw.iter() {
        let key: String = key.extract()?;
        match key.as_str() {
            "shape" => cfg.shape = shape_of(py, &v.extract::<String>()?)?,
            "mode" => cfg.mode = mode_of(py, &v.extract::<String>()?)?,
            "skew" => cfg.skew = skew_of(&v)?,
            plain if FIELDS.contains(&plain) => {
                cfg = with_field(py, &cfg, plain, number(plain, &v)?)?;
            }
            other => {
                return Err(PyTypeError::new_err(format!(
                    "unexpected keyword argument {other:?} (ControllerConfig fields: {})",
                    FIELDS.join(", ")
                )))
            }
        }
    }
    Ok(cfg)
}

/// `c` as a dict of its fields, in declaration order, as `apply` takes them.
pub(crate) fn config_dict<'py>(
    py: Python<'py>,
    c: &ControllerConfig,
) -> PyResult<Bound<'py, PyDict>> {
    let table = table_of(c)?;
    let d = PyDict::new(py);
    for &name in FIELDS {
        match name {
            "shape" => d.set_item(name, c.shape.name())?,
            "mode" => d.set_item(name, c.mode.name())?,
            "skew" => d.set_item(
                name,
                c.skew.map(|s| (s.delta_over_a, s.alpha, s.locus_over_a)),
            )?,
            _ => match table.get(name) {
                Some(Value::Float(x)) => d.set_item(name, x)?,
                Some(Value::Integer(i)) => d.set_item(name, i)?,
                Some(Value::Boolean(b)) => d.set_item(name, b)?,
                Some(Value::String(s)) => d.set_item(name, s)?,
                None => d.set_item(name, py.None())?,
                Some(other) => {
                    return Err(PyValueError::new_err(format!(
                        "config: {name}: cannot show {other} in Python"
                    )))
                }
            },
        }
    }
    Ok(d)
}

pub(crate) fn build(py: Python<'_>, cfg: ControllerConfig) -> PyResult<CoreController<f64, Libm>> {
    CoreController::<f64, Libm>::new_precomputed_in::<f64>(cfg)
        .map_err(|e| core_err(py, e, field_name))
}
